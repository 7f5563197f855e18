"""An output folder written whole or not at all, as ``impact simulate`` writes its run
(``solver/src/output/out_dir.rs``): the files go into a staging folder beside the output
folder, ``.NAME.partial-PID``, and are moved in once all are written, replacing the files of
an earlier output that the writer owns (and those alone: the folder's other files stay). Ctrl-C,
an error or a kill before that leaves the output folder as it was; the staging folder is removed
(a killed writer's by the next one). Ctrl-C during the moves waits until they are done.
"""
from __future__ import annotations

import contextlib
import fnmatch
import os
import shutil
import signal
import threading
from pathlib import Path
from typing import Iterator, Sequence


def staging_dir(out: Path) -> Path:
    """``.NAME.partial-PID`` beside ``out``: where this process writes before moving in."""
    return out.parent / f".{out.name}.partial-{os.getpid()}"


@contextlib.contextmanager
def staged(out: str | os.PathLike[str], owned: Sequence[str]) -> Iterator[Path]:
    """Yields the staging folder of ``out``; when the block ends without an exception, moves
    what it holds into ``out``, first removing the entries of ``out`` whose names match one of
    the patterns ``owned`` (``fnmatch``: the writer's own files, e.g. ``"study*-*.svg"``).
    Whatever the block raises, ``out`` is left as it was and the staging folder removed."""
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    _remove_stale(out)
    staging = staging_dir(out)
    shutil.rmtree(staging, ignore_errors=True)
    staging.mkdir()
    try:
        yield staging
        with _sigint_held():
            _publish(staging, out, owned)
    finally:
        shutil.rmtree(staging, ignore_errors=True)


def _publish(staging: Path, out: Path, owned: Sequence[str]) -> None:
    out.mkdir(parents=True, exist_ok=True)
    for old in out.iterdir():
        if any(fnmatch.fnmatch(old.name, p) for p in owned):
            _remove(old)
    for new in staging.iterdir():
        os.replace(new, out / new.name)


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path)
    else:
        path.unlink()


@contextlib.contextmanager
def _sigint_held() -> Iterator[None]:
    """Ctrl-C held until the block ends, then delivered (on the main thread; elsewhere Python
    delivers none)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    pending: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda signum, _frame: pending.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if pending:
            signal.raise_signal(signal.SIGINT)


def _remove_stale(out: Path) -> None:
    """Removes the staging folders of ``out`` left by processes that no longer run."""
    prefix = f".{out.name}.partial-"
    if not out.parent.is_dir():
        return
    for entry in out.parent.iterdir():
        pid = entry.name[len(prefix):] if entry.name.startswith(prefix) else ""
        if pid.isdigit() and int(pid) != os.getpid() and not _alive(int(pid)):
            shutil.rmtree(entry, ignore_errors=True)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True
