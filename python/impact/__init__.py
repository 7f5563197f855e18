"""The impact solver from Python.

A 2-D plane-strain explicit-dynamics solver for a clamped plate hit by a rigid line-nose
impactor (after Dokko & Kim 2004). SI units throughout; every history column and summary key
names its unit (``time_s``, ``contact_force_N``, ``impulse_Ns``, ...).

- :func:`simulate` runs one scene (a path, YAML text or a dict) and returns a :class:`Run`
  (``summary`` as in ``summary.json``, ``history`` as numpy arrays named like the columns of
  ``history.csv``), optionally writing the files of ``impact simulate``.
- :func:`sweep` runs one scene under many overrides (dotted scene keys) on a local pool or a
  Dask cluster and returns one row per run.
- :func:`verify` runs the verification matrix and returns its results as data.
- :func:`uq` runs an uncertainty study from its declaration (distributions of the inputs,
  Sobol' sampling through :func:`sweep`, Sobol' indices, the V&V 20 inputs).

Scene errors raise :class:`SceneError` with the message of the ``impact`` command
(``file:line:col: field = value: what is allowed``); a run that cannot go on raises
:class:`RunError`; an input that is accepted but looks wrong (units, an option that does
nothing) warns with :class:`SceneWarning`.
"""
from __future__ import annotations

from ._impact import TIMING_KEYS, RunError, SceneError, VerifyError
from ._run import Run, SceneWarning, simulate
from ._sweep import sweep
from ._uq import StudyRunError, UQResult, uq
from ._verify import Verification, verify

__all__ = [
    "Run",
    "RunError",
    "SceneError",
    "SceneWarning",
    "StudyRunError",
    "TIMING_KEYS",
    "UQResult",
    "Verification",
    "VerifyError",
    "simulate",
    "sweep",
    "uq",
    "verify",
]
