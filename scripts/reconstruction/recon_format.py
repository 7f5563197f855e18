"""Formatting shared by the reconstruction's data files and its page: per cent, Markdown
tables, the rows of Table 1 and the residual groups."""
from __future__ import annotations

import math

import recon_core as rc

ROWS = ("elastic", "plastic")
ROW_LABEL = {"elastic": "Elastic", "plastic": "Elasto-plastic"}


def pct(x: float | None, d: int = 1) -> str:
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "-"
    return f"{100 * x:+.{d}f} %"



def md_table(head: list[str], rows: list[list[str]]) -> str:
    out = ["| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)



def group_of(q: str, row: str) -> str:
    if q in rc.ROBUST:
        return "robust"
    if q == "contact_duration" and row == "plastic":
        return "intermediate"
    return "fragile"

