"""Read ccx's job.dat: the blocks of *NODE PRINT / *EL PRINT, by kind, set and time.

A block starts with a header such as ' displacements (vx,vy,vz) for set NMID and time  0.1E-05'
or ' total internal energy for set EALL and time ...', then rows of numbers.
"""

import re

HEADER = re.compile(r"^\s*(?P<what>.+?)\s+for set\s+(?P<set>\S+)\s+and time\s+(?P<t>\S+)\s*$")

KINDS = {  # header text -> short name
    "displacements (vx,vy,vz)": "U",
    "stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz)": "S",
    "total internal energy": "ELSE",
    "total kinetic energy": "ELKE",
    "total force (fx,fy,fz)": "RF",
}


class DatError(Exception):
    """The .dat file is missing, unreadable or short."""


def number(text):
    """A float from ccx's text (which may drop the E of three-digit exponents: 1.0-100)."""
    try:
        return float(text)
    except ValueError:
        return float(re.sub(r"(\d)([+-]\d{3})$", r"\1E\2", text))


def parse(path):
    """{(kind, set): [(time s, [[row numbers], ...]), ...]} in file order."""
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read().splitlines()
    except OSError as e:
        raise DatError(f"cannot read {path}: {e.strerror}") from e
    blocks, current = {}, None
    for line in text:
        m = HEADER.match(line)
        if m:
            kind = KINDS.get(m.group("what").strip(), m.group("what").strip())
            current = []
            blocks.setdefault((kind, m.group("set")), []).append((number(m.group("t")), current))
        elif line.strip() and current is not None:
            current.append([number(v) for v in line.split() if v != "L"])  # L: local dofs
    return blocks


def series(blocks, kind, name):
    """The (time, rows) list of one kind and set; DatError when ccx wrote none."""
    try:
        return blocks[(kind, name)]
    except KeyError:
        raise DatError(f"no '{kind}' output for set {name} in job.dat") from None


def nodal(rows):
    """{node number: [values]} of a node block."""
    return {int(r[0]): r[1:] for r in rows}


def point_stress(rows, element, point):
    """(sxx, syy, szz, sxy) of element number, point number from a stress block, Pa."""
    for r in rows:
        if int(r[0]) == element and int(r[1]) == point:
            return r[2], r[3], r[4], r[5]
    raise DatError(f"no stress for element {element} point {point}")
