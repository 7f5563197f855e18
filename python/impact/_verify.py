"""`verify`: the verification matrix, run by the harness library, as data."""
from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any

from . import _impact

if TYPE_CHECKING:
    import pandas


class Verification:
    """The outcome of :func:`verify`.

    Attributes:
        results: the content of ``results.json`` (``counts`` and ``cases``, each case with
            its checks: status, computed, reference, error, tolerance, reason, ...).
    """

    __slots__ = ("results",)

    def __init__(self, results: dict[str, Any]):
        self.results = results

    @property
    def counts(self) -> dict[str, int]:
        """Checks by status, as results.json: ``ok``, ``fail`` (known failures included),
        ``skip``, ``known_fail``, ``xpass`` (known failures that pass), ``unexpected``."""
        return dict(self.results["counts"])

    @property
    def passed(self) -> bool:
        """No unexpected failure and no unexpected pass (``impact verify`` exits 0)."""
        return self.results["counts"]["unexpected"] == 0

    def checks(self) -> list[dict[str, Any]]:
        """One flat dict per check: ``suite``, ``case`` and the check's own fields."""
        return [
            {"suite": c["suite"], "case": c["case"], **k}
            for c in self.results["cases"]
            for k in c["checks"]
        ]

    def to_pandas(self) -> "pandas.DataFrame":
        """The checks as a pandas DataFrame, one row per check (needs pandas)."""
        import pandas

        return pandas.DataFrame.from_records(self.checks())

    def __repr__(self) -> str:
        c = self.results["counts"]
        return (f"Verification(ok={c['ok']}, fail={c['fail']} ({c['known_fail']} known), "
                f"skip={c['skip']}, unexpected={c['unexpected']})")


def verify(
    *selectors: str,
    filter: str | None = None,
    light: bool = False,
    jobs: int | None = None,
    out: str | os.PathLike[str] | None = None,
    report: bool = False,
    root: str | os.PathLike[str] | None = None,
) -> Verification:
    """Runs the verification matrix, as ``impact verify`` does, and returns its results.

    Args:
        selectors: suites (folder names under ``verification/cases``), case ids or
            ``suite/case`` names; none: every case.
        filter: only checks whose ``suite/case/check`` name contains this text.
        light: leave out the cases marked heavy (what ``cargo test`` runs).
        jobs: runs at a time (default: one per core); results do not depend on it.
        out: also write ``results.json``, ``junit.xml``, ``matrix.txt``, ``runs/`` and
            ``environment.json`` there, as ``impact verify --out``.
        report: with ``out``: also write the V&V report (``index.html``, ``report.md``).
        root: the repository (default: found from the current folder upwards).

    The GIL is released while the matrix runs.

    Raises:
        VerifyError: a case does not load or lint, or no case matches the selectors.
    """
    if report and out is None:
        raise ValueError("report=True needs out= (the folder the report is written to)")
    text = _impact.verify(
        list(selectors),
        filter=filter,
        light=light,
        jobs=jobs,
        out=None if out is None else os.fspath(out),
        report=report,
        root=None if root is None else os.fspath(root),
    )
    return Verification(json.loads(text))
