"""Turn ccx's printed blocks into impact's history columns (SI units, whole plate)."""

import math

from results import DatError, nodal, point_stress, series


def von_mises(sxx, syy, szz, sxy):
    """Von Mises stress of an in-plane state with the out-of-plane szz, Pa."""
    return math.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                     + 3.0 * sxy ** 2)


def load_force(s, t):
    """The pulse's or traction's reported force at t (s), N: on for 0 <= t < duration."""
    kind, load = s["load"]
    if t >= float(load["duration"]):
        return 0.0
    if kind == "pulse":
        return float(load["force"])
    normal, shear = float(load.get("normal", 0.0)), float(load.get("shear", 0.0))
    area = float(s["plate"]["length"]) * float(s["plate"]["width"])
    return (normal if normal else shear) * area


def columns(s, probes):
    """The history header, in impact's column order."""
    cols = ["time_s", "contact_force_N"]
    if s["load"][0] == "impactor":
        cols += ["indentation_m", "impactor_displacement_m", "impactor_velocity_mps"]
    if s["load"][0] == "wall":
        cols += ["foot_radius_m", "bar_length_m"]
    cols += ["top_uy_m", "mid_uy_m", "bottom_uy_m"]
    for name in probes:
        cols += [f"{name}_{c}" for c in ("sxx_Pa", "syy_Pa", "sxy_Pa", "szz_Pa", "von_mises_Pa")]
    if s["load"][0] != "wall" or "wedge" in s:
        cols.append("plate_kinetic_J")  # not after the launch step: garbage (1e20 J, measured)
    if not s["material"].get("plasticity"):
        cols.append("strain_energy_J")
    return cols


def initial_row(s, mesh, probes):
    """The row at t = 0 (the state at rest, before ccx's first increment), or None under the
    wall (the body starts moving: its t = 0 wall force is not a ccx output)."""
    if s["load"][0] == "wall":
        return None
    row = {c: 0.0 for c in columns(s, probes)}
    if s["load"][0] == "impactor":
        row["impactor_velocity_mps"] = float(s["load"][1]["velocity"])
    else:
        row["contact_force_N"] = load_force(s, 0.0)
    return row


def block_at(blocks, kind, name, k):
    """The k-th block of a kind and set (time, rows)."""
    data = series(blocks, kind, name)
    if k >= len(data):
        raise DatError(f"'{kind}' for set {name} stops after {len(data)} outputs")
    return data[k]


def wedge_row(mesh, w, blocks, k, factor):
    """The k-th output of the axisymmetric wedge under the wall (deck.write_wedge): the axis
    nodes in global dofs (y = axial), the off-axis foot in its cylindrical (r, theta, axial)
    dofs."""
    t, rows = block_at(blocks, "U", "NMID", k)
    u = nodal(rows)
    row = {"time_s": t}
    for which, n in w.mid_span().items():
        row[f"{which}_uy_m"] = u[n][1]
    rf_off = block_at(blocks, "RF", "NFOOTOFF", k)[1][0]
    rf_axis = block_at(blocks, "RF", "NFOOTAX", k)[1][0]
    row["contact_force_N"] = (rf_off[1] + rf_axis[1]) * factor  # totals print global dofs
    foot = nodal(block_at(blocks, "U", "NFOOTOFF", k)[1])
    row["foot_radius_m"] = max(w.radius[n] + v[0] for n, v in foot.items())
    row["bar_length_m"] = mesh.h + row["top_uy_m"] - row["bottom_uy_m"]
    return row


def impactor_columns(blocks, k, factor, top_uy):
    """The nose's columns of the k-th output (nose.py): the contact force on the plate's top
    surface (ccx's CF, whole width), the nose's displacement and velocity positive toward the
    plate, and the indentation delta_S + u_y of the top mid-span node (ALGORITHM.md 8)."""
    force = block_at(blocks, "CF", "SPLATE", k)[1][0]
    (u,) = nodal(block_at(blocks, "U", "NREF", k)[1]).values()
    (v,) = nodal(block_at(blocks, "V", "NREF", k)[1]).values()
    return {"contact_force_N": -force[1] * factor, "impactor_displacement_m": -u[1],
            "impactor_velocity_mps": -v[1], "indentation_m": -u[1] + top_uy}


def row_at(s, mesh, probes, blocks, k, factor, launch):
    """The k-th ccx output as a history row {column: value}; launch = (time offset s,
    lift m) of the wall's launch step (ccx's time and u_y start before the landing)."""
    if "wedge" in s:
        row = wedge_row(mesh, s["wedge"], blocks, k, factor)
        row["plate_kinetic_J"] = block_at(blocks, "ELKE", "EALL", k)[1][0][0] * factor
        if not s["material"].get("plasticity"):
            row["strain_energy_J"] = block_at(blocks, "ELSE", "EALL", k)[1][0][0] * factor
        return row
    t, rows = block_at(blocks, "U", "NMID", k)
    u = nodal(rows)
    mid = mesh.mid_span()
    row = {"time_s": t - launch[0]}
    for which in ("top", "mid", "bottom"):
        row[f"{which}_uy_m"] = u[mid[which] + 1][1] + launch[1]
    if s["load"][0] == "wall":
        row["contact_force_N"] = block_at(blocks, "RF", "NFOOT", k)[1][0][1] * factor
        foot = nodal(block_at(blocks, "U", "NFOOT", k)[1])
        row["foot_radius_m"] = max(mesh.ccx_xy(n - 1)[0] + v[0] for n, v in foot.items())
        row["bar_length_m"] = mesh.h + row["top_uy_m"] - row["bottom_uy_m"]
    elif s["load"][0] == "impactor":
        row.update(impactor_columns(blocks, k, factor, row["top_uy_m"]))
    else:
        row["contact_force_N"] = load_force(s, row["time_s"])
    if probes:
        stress_rows = block_at(blocks, "S", "EPROBE", k)[1]
        for name, (e, p) in probes.items():
            sxx, syy, szz, sxy = point_stress(stress_rows, e + 1, p)
            if mesh.axisymmetric:
                sxy = -sxy  # the solver's x runs against the radius
            row.update({f"{name}_sxx_Pa": sxx, f"{name}_syy_Pa": syy, f"{name}_sxy_Pa": sxy,
                        f"{name}_szz_Pa": szz,
                        f"{name}_von_mises_Pa": von_mises(sxx, syy, szz, sxy)})
    if s["load"][0] != "wall":
        row["plate_kinetic_J"] = block_at(blocks, "ELKE", "EALL", k)[1][0][0] * factor
    if not s["material"].get("plasticity"):
        row["strain_energy_J"] = block_at(blocks, "ELSE", "EALL", k)[1][0][0] * factor
    return row


def build(s, mesh, probes, blocks, factor, end, launch=(0.0, 0.0)):
    """All history rows; DatError when ccx's output stops before time.end."""
    if launch[0] > 0.0:  # the launch step's outputs are not the scene's
        blocks = {key: [(t, r) for t, r in data if t > launch[0] * (1 + 1e-9)]
                  for key, data in blocks.items()}
    n = len(series(blocks, "U", "NMID"))
    rows = [row_at(s, mesh, probes, blocks, k, factor, launch) for k in range(n)]
    if not rows or rows[-1]["time_s"] < end * (1 - 1e-6):
        last = rows[-1]["time_s"] if rows else 0.0
        raise DatError(f"job.dat ends at t = {last:.6g} s, before time.end = {end:.6g} s")
    first = initial_row(s, mesh, probes)
    return ([first] if first else []) + rows
