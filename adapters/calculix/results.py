"""Read ccx's job.dat: the blocks of *NODE PRINT / *EL PRINT, by kind, set and time.

A block starts with a header such as ' displacements (vx,vy,vz) for set NMID and time  0.1E-05'
or ' total internal energy for set EALL and time ...' (after some kinds ccx leaves out the space
before "for set": ' equivalent plastic strain (elem, integ.pnt.,pe)for set EALL ...'), then rows
of numbers. A *CONTACT PRINT
CF block (' statistics for slave set S, master set M and time ...') is kept under ('CF', S):
its rows are the numeric lines between its captions, the first the total surface force on the
slave surface and its moment about the origin (fx, fy, fz, mx, my, mz).
"""

import re

HEADER = re.compile(r"^\s*(?P<what>.+?)\s*for set\s+(?P<set>\S+)\s+and time\s+(?P<t>\S+)\s*$")
CONTACT = re.compile(r"^\s*statistics for slave set\s+(?P<set>[^,\s]+),\s*master set\s+\S+"
                     r"\s+and time\s+(?P<t>\S+)\s*$")

KINDS = {  # header text -> short name
    "displacements (vx,vy,vz)": "U",
    "stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz)": "S",
    "total internal energy": "ELSE",
    "total kinetic energy": "ELKE",
    "total force (fx,fy,fz)": "RF",
    "forces (fx,fy,fz)": "F",  # *NODE PRINT RF without TOTALS: each node's
    "velocities (vx,vy,vz)": "V",
    "equivalent plastic strain (elem, integ.pnt.,pe)": "PEEQ",  # no space before "for set"
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
    blocks, current, captions = {}, None, False
    for line in text:
        m, c = HEADER.match(line), CONTACT.match(line)
        if c:
            current, captions = [], True
            blocks.setdefault(("CF", c.group("set")), []).append((number(c.group("t")), current))
        elif m:
            captions = False
            kind = KINDS.get(m.group("what").strip(), m.group("what").strip())
            current = []
            blocks.setdefault((kind, m.group("set")), []).append((number(m.group("t")), current))
        elif captions and line.strip() and line.strip()[0].isalpha():
            continue  # a caption of the contact statistics
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
