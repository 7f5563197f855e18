"""`simulate`: one run, its summary and history."""
from __future__ import annotations

import json
import os
import warnings
from typing import TYPE_CHECKING, Any, Mapping

import numpy as np

from . import _impact
from ._scene import SceneLike, overrides_json, scene_text

if TYPE_CHECKING:
    import pandas


class SceneWarning(UserWarning):
    """An input the scene accepts that looks wrong: units (a plate of 200 m, E of 2e5 Pa, a
    density under 1 kg/m^3), an option that does nothing in the scene (``hourglass`` without
    ``q4-1pt``, ``time.limit`` with a fixed end), output that swamps the run (a VTK frame every
    step). The message is the CLI's ``warning:`` line: ``file:line:col: field = value: why``."""


def _warn(message: str) -> None:
    # stacklevel 3: the caller of impact.simulate (this function, then simulate).
    warnings.warn(message, SceneWarning, stacklevel=3)


class Run:
    """A finished run.

    Attributes:
        summary: the keys and values of ``summary.json`` exactly (``impulse_Ns`` in N s,
            ``peak_contact_force_N`` in N, ``max_plate_displacement_m`` in m (signed, negative
            = downward), ``max_von_mises_Pa`` per probe in Pa, ``wall_time_s`` in s, ...),
            parsed from the solver's own serialisation.
        history: one 1-D ``float64`` numpy array per column of ``history.csv``, named like it
            (``time_s``, ``contact_force_N``, ``top_uy_m``, ``<probe>_von_mises_Pa``,
            energies in J, ``energy_balance_error`` (-)), in the file's column order; one
            entry per output time (``output.every``).
    """

    __slots__ = ("summary", "history")

    def __init__(self, summary: dict[str, Any], history: dict[str, np.ndarray]):
        self.summary = summary
        self.history = history

    @property
    def warnings(self) -> list[str]:
        """The scene's plausibility warnings (``summary.json``'s ``warnings``; empty when none):
        inputs whose units look wrong, options that do nothing in the scene, output that
        swamps the run. Also raised as :class:`SceneWarning` by :func:`simulate`."""
        return list(self.summary.get("warnings", []))

    def to_pandas(self) -> "pandas.DataFrame":
        """The history as a pandas DataFrame, one column per history column (needs pandas)."""
        import pandas

        return pandas.DataFrame(self.history, copy=False)

    def __repr__(self) -> str:
        n = len(next(iter(self.history.values()))) if self.history else 0
        return (
            f"Run(impulse_Ns={self.summary.get('impulse_Ns')!r}, n_steps="
            f"{self.summary.get('n_steps')!r}, history: {len(self.history)} columns x {n} rows)"
        )


def simulate(
    scene: SceneLike,
    *,
    out: str | os.PathLike[str] | None = None,
    threads: int | None = None,
    overrides: Mapping[str, Any] | None = None,
) -> Run:
    """Runs one scene and returns its :class:`Run`.

    Args:
        scene: a scene file path, YAML text (with a line break, or one ``{...}`` flow line),
            or a dict with the scene's keys (docs/scene-reference.md; SI units).
        out: a folder to write the files ``impact simulate --out`` writes (``history.csv``,
            ``summary.json``, VTK fields when the scene asks), by the same code and with the
            same protections: staged and moved in only on success; ``/``, the home folder and
            a non-empty folder holding no earlier run are refused; a run whose memory estimate
            exceeds the memory available is refused. None: nothing is written.
        threads: threads for the element loop, 1 to 4 x the cores (at most 256; else
            ValueError). The solver assembles element forces on
            several threads only for costly kernels on large meshes (elasto-plastic, >= 256
            elements); every other run uses one thread whatever this says. Results are
            bit-identical for every thread count. None: one per core (as the CLI).
        overrides: values set at dotted scene keys before validation, with the rules of a
            scene file, e.g. ``{"material.plasticity.yield_stress": 2.0e8}`` (Pa). A key
            through a word that is short for a map sets that map
            (``load.impactor.contact.surface.enforcement`` on ``contact: surface``).

    The GIL is released while the solver runs, so threads of a pool run in parallel.

    Warns:
        SceneWarning: once per plausibility warning of the scene (before the run, also when
            the run is then refused); they are kept in ``Run.warnings``.

    Raises:
        SceneError: the scene cannot be read, parsed or validated (message: the CLI's,
            ``file:line:col: field = value: what is allowed``).
        RunError: the run could not go on (instability, contact law beyond its maximum).
        OSError: ``out`` is refused or cannot be written.
        MemoryError: with ``out``, the run's memory estimate exceeds the memory available.
    """
    text, source = scene_text(scene)
    if threads is not None and (isinstance(threads, bool) or not isinstance(threads, int)):
        raise TypeError(f"threads must be an int from 1 to 4 x the cores, or None, not {threads!r}")
    summary, columns, arrays = _impact.simulate(
        text,
        source,
        out=None if out is None else os.fspath(out),
        threads=threads,
        overrides=overrides_json(overrides, source),
        warn=_warn,
    )
    return Run(json.loads(summary), dict(zip(columns, arrays)))
