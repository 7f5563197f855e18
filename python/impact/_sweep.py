"""`sweep`: one scene under many overrides, on a local thread pool or a Dask cluster.

Every run goes through the same native call whatever the pool, so a row depends only on the
scene and its overrides: local, Dask and serial sweeps give bit-identical values (wall-clock
keys aside, see ``TIMING_KEYS``).

Ctrl-C (KeyboardInterrupt) stops a sweep within a second: the runs not started are cancelled,
the local runs under way stop at their next signal check (every 256 steps: the pool's threads
poll a stop event, since Python runs signal handlers on the main thread only), and a Dask
sweep cancels its futures (and closes the client it connected itself): each run under way on
a worker polls whether its task was cancelled, and stops.
"""
from __future__ import annotations

import concurrent.futures as cf
import json
import os
import threading
from typing import TYPE_CHECKING, Any, Mapping, Sequence

from . import _impact
from ._scene import SceneLike, overrides_json, scene_text

if TYPE_CHECKING:
    import pandas
    from distributed import Client

ERROR = "error"


def run_row(text: str, source: str, overrides: str | None,
            stop: threading.Event | None = None) -> dict[str, Any]:
    """One run of a sweep: the summary (parsed ``summary.json``) with ``error`` None, or only
    ``error`` (the message) when the scene is refused or the run fails. Runs on one thread;
    raises KeyboardInterrupt when ``stop`` is set while it runs."""
    try:
        summary, _, _ = _impact.simulate(text, source, overrides=overrides, threads=1, stop=stop)
    except (_impact.SceneError, _impact.RunError) as e:
        return {ERROR: str(e)}
    row = json.loads(summary)
    row[ERROR] = None
    return row


def sweep(
    scene: SceneLike,
    overrides: Sequence[Mapping[str, Any]],
    *,
    client: "Client | str | None" = None,
    jobs: int | None = None,
) -> "pandas.DataFrame":
    """Runs ``scene`` once per entry of ``overrides`` and returns one row per run.

    Args:
        scene: as for :func:`impact.simulate` (a path, YAML text or a dict); a path is read
            here, so Dask workers need the package but not the file.
        overrides: one dict per run of dotted scene keys to values, e.g.
            ``{"material.plasticity.yield_stress": 2.0e8}`` (Pa) or ``{"mesh.nx": 40}``; set
            before validation with the rules of a scene file (an empty dict: the scene as is),
            as for :func:`impact.simulate`.
        client: None for a local pool; a ``dask.distributed.Client`` (of a ``LocalCluster`` or
            of a scheduler on other machines) to run there; or a scheduler address
            (``"tcp://host:8786"``), connected to for this sweep. Workers need ``impact``
            installed.
        jobs: local runs at a time (default: one per core). Each run uses one thread; the
            GIL is released while it runs. Not allowed with ``client`` (the cluster's workers
            set its parallelism).

    Returns:
        A pandas DataFrame, row ``i`` for ``overrides[i]``: one column per override key (NaN
        where a run did not set it), then every ``summary.json`` key with its value (units in
        the key names; nested values such as ``max_von_mises_Pa`` stay dicts), then ``error``:
        missing (None/NaN: test with ``isna()``), or the message of a run that failed (its summary columns are then NaN). A
        failed run never stops the sweep.
    """
    import pandas

    text, source = scene_text(scene)
    overrides = list(overrides)
    # An override the JSON cannot carry (NaN, inf) is that row's error; the others run.
    refused: dict[int, str] = {}
    payloads: list[str | None] = []
    for i, o in enumerate(overrides):
        try:
            payloads.append(overrides_json(o, source))
        except _impact.SceneError as e:
            refused[i] = str(e)
    if client is None:
        ran = _local(text, source, payloads, jobs)
    elif jobs is not None:
        raise ValueError("jobs sets the local pool; with a Dask client its workers decide")
    elif isinstance(client, str):
        from distributed import Client

        with Client(client) as connected:
            ran = _dask(connected, text, source, payloads)
    else:
        ran = _dask(client, text, source, payloads)
    it = iter(ran)
    rows = [{ERROR: refused[i]} if i in refused else next(it) for i in range(len(overrides))]
    keys = _ordered_keys(overrides)
    summary_keys = _ordered_keys([r for r in rows if r[ERROR] is None] or [{}])
    columns = keys + [k for k in summary_keys if k not in keys and k != ERROR] + [ERROR]
    records = [{**dict(o), **r} for o, r in zip(overrides, rows)]
    return pandas.DataFrame.from_records(records, columns=columns)


def _local(text: str, source: str, payloads: list[str | None], jobs: int | None) -> list[dict]:
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise ValueError(f"jobs must be an int >= 1 or None, not {jobs!r}")
    workers = jobs or os.cpu_count() or 1
    if workers == 1 or len(payloads) <= 1:
        return [run_row(text, source, p) for p in payloads]
    stop = threading.Event()
    pool = cf.ThreadPoolExecutor(max_workers=workers)
    try:
        futures = [pool.submit(run_row, text, source, p, stop) for p in payloads]
        return [f.result() for f in futures]
    except BaseException:
        # Ctrl-C (or any error here): the runs under way stop at their next check.
        stop.set()
        raise
    finally:
        pool.shutdown(wait=True, cancel_futures=True)


def _dask(client: "Client", text: str, source: str, payloads: list[str | None]) -> list[dict]:
    n = len(payloads)
    futures = client.map(_dask_row, [text] * n, [source] * n, payloads, pure=False)
    try:
        # One future at a time: an interrupted wait leaves no other waits behind.
        return [f.result() for f in futures]
    except BaseException:
        client.cancel(futures)
        raise


def _dask_row(text: str, source: str, overrides: str | None) -> dict[str, Any]:
    """:func:`run_row` as a Dask task: it stops when the task is cancelled (its row, which no
    one reads, then says so: a KeyboardInterrupt would take the worker down)."""
    try:
        return run_row(text, source, overrides, _TaskCancelled())
    except KeyboardInterrupt as e:
        return {ERROR: str(e)}


class _TaskCancelled:
    """``is_set()``: whether the Dask task that runs this was cancelled (the worker can only
    mark a running task so; the run polls it) or its worker stopped running."""

    def __init__(self) -> None:
        from distributed import get_worker
        from distributed.core import Status

        self._worker = get_worker()
        self._key = self._worker.get_current_task()
        self._running = Status.running

    def is_set(self) -> bool:
        task = self._worker.state.tasks.get(self._key)
        return task is None or task.state == "cancelled" or self._worker.status != self._running


def _ordered_keys(dicts: Sequence[Mapping[str, Any]]) -> list[str]:
    """Keys of all dicts, each once, in first-seen order."""
    seen: dict[str, None] = {}
    for d in dicts:
        for k in d:
            seen.setdefault(k, None)
    return list(seen)
