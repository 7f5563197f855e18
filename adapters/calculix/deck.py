"""Write the ccx input deck (job.inp) for a scene. Lengths m, forces N, times s, Pa, kg/m^3.

Plane strain: CPE4/CPE4R with the section thickness plate.width, so ccx's forces and energies
are those of the whole width of the modelled part (times 2 for the half model's report).
Axisymmetric: CAX4/CAX4R: a *CLOAD is the whole ring's, while ccx's reactions and energies are
its 2-degree segment's (times 180 for the whole ring).
"""

import math

ELEMENT = {  # (geometry, scene element) -> (ccx type, substitution or None)
    ("plane-strain", "q4-full"): ("CPE4", None),
    ("plane-strain", "q4-sri"): ("CPE4", "q4-sri -> CPE4 (2x2 full integration, no B-bar: ccx has no "
                                 "selective reduced integration element; same deviatoric/shear "
                                 "part, stiffer volumetric part, locks under plastic flow)"),
    ("plane-strain", "q4-1pt"): ("CPE4R", "q4-1pt -> CPE4R (one point, ccx's own hourglass "
                                 "control, not Flanagan-Belytschko with mesh.hourglass)"),
    ("axisymmetric", "q4-full"): ("CAX4", None),
    ("axisymmetric", "q4-sri"): ("CAX4", "q4-sri -> CAX4 (2x2 full integration, no B-bar/F-bar: "
                                 "ccx has no selective reduced integration element; locks "
                                 "under plastic flow)"),
    ("axisymmetric", "q4-1pt"): ("CAX4R", "q4-1pt -> CAX4R (one point, ccx's own hourglass "
                                 "control, not Flanagan-Belytschko with mesh.hourglass)"),
}


def report_factor(s):
    """ccx's forces and energies times this are the scene's (whole plate, width or ring)."""
    if s["geometry"] == "axisymmetric":
        return 180.0
    return 2.0 if s["mesh"]["model"] == "half" else 1.0


def load_divisor(s):
    """The scene's force over the one ccx is given: 2 on the half model's symmetry line; 1 in
    the axisymmetric geometry, where ccx takes a *CLOAD as the whole ring's (measured: a
    *CLOAD of 1000 N on a CAX4 disk gives a reaction of 1000/180 N, its 2-degree share)."""
    if s["geometry"] == "axisymmetric":
        return 1.0
    return 2.0 if s["mesh"]["model"] == "half" else 1.0


def wave_speed(material):
    """Plane-strain P-wave speed sqrt(E (1 - nu) / (rho (1 + nu)(1 - 2 nu))), m/s."""
    e, nu, rho = (float(material[k]) for k in ("youngs_modulus", "poisson_ratio", "density"))
    return math.sqrt(e * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)))


def time_step(s, mesh):
    """The largest step given to ccx, s: time.dt.fixed, or cfl times the lumped bilinear
    bound 1 / (c_P sqrt(1/dx^2 + 1/dy^2)) on the smallest element (ccx takes the smaller of
    this and its own Courant estimate)."""
    dt = s["time"]["dt"]
    if dt.get("fixed") is not None:
        return float(dt["fixed"])
    dx, dy = mesh.smallest_sizes()
    return float(dt["cfl"]) / (wave_speed(s["material"]) * math.sqrt(dx ** -2 + dy ** -2))


def flow_curve(material):
    """ccx *PLASTIC rows [(true stress Pa, equivalent plastic strain)], flat after the last."""
    p = material["plasticity"]
    kind, value = next(iter(p["hardening"].items()))
    if kind == "table":
        return [(float(sig), float(eps)) for eps, sig in value]
    e, et, sy = float(material["youngs_modulus"]), float(value), float(p["yield_stress"])
    h = e * et / (e - et)  # the plastic modulus of the uniaxial tangent modulus Et
    return [(sy, 0.0), (sy + h * 10.0, 10.0)]


def num(v):
    """A number as ccx reads it: at most 20 characters a field (exact when it fits)."""
    text = repr(float(v))
    return text if len(text) <= 20 else f"{float(v):.14g}"


def lines_of(values, per_line=8):
    """Comma-separated data lines of at most per_line numbers (ccx reads up to 16); ints
    (node and element numbers) as they are."""
    text = lambda v: str(v) if isinstance(v, int) else num(v)
    return [", ".join(text(v) for v in values[k:k + per_line])
            for k in range(0, len(values), per_line)]


def nodes_and_elements(s, mesh, ccx_type, lift=0.0):
    """*NODE and *ELEMENT blocks (ccx numbers = index + 1), the body raised by lift (m)."""
    out = ["*NODE, NSET=NALL"]
    for n in range((mesh.nx + 1) * (mesh.ny + 1)):
        x, y = mesh.ccx_xy(n)
        out.append(f"{n + 1}, {num(x)}, {num(y + lift)}")
    out.append(f"*ELEMENT, TYPE={ccx_type}, ELSET=EALL")
    for e, c in mesh.elements():
        out.append(f"{e + 1}, " + ", ".join(str(n + 1) for n in c))
    return out


def node_set(name, nodes):
    """An *NSET of node indices."""
    return [f"*NSET, NSET={name}"] + lines_of([n + 1 for n in nodes], 16)


def material_block(s):
    """*MATERIAL, *ELASTIC, *DENSITY, *PLASTIC and the *SOLID SECTION."""
    m = s["material"]
    out = ["*MATERIAL, NAME=PLATE", "*ELASTIC",
           f"{num(float(m['youngs_modulus']))}, {num(float(m['poisson_ratio']))}",
           "*DENSITY", f"{num(float(m['density']))}"]
    if m.get("plasticity"):
        out.append("*PLASTIC")
        out += [f"{num(sig)}, {num(eps)}" for sig, eps in flow_curve(m)]
    out.append("*SOLID SECTION, ELSET=EALL, MATERIAL=PLATE")
    out.append("" if s["geometry"] == "axisymmetric" else f"{num(float(s['plate']['width']))}")
    return out


def boundary_block(mesh):
    """*BOUNDARY of the supports and the symmetry line or axis (u_x = 0)."""
    held = mesh.supports()
    if not held:
        return []
    out = ["*BOUNDARY"]
    for n in sorted(held):
        out += [f"{n + 1}, {d}, {d}, 0." for d in sorted(held[n])]
    return out


def rectangular_amplitude(duration, end, dt):
    """*AMPLITUDE PULSE: 1 for 0 <= t < duration, 0 after (a ramp of dt/1000 at the end)."""
    off = duration + 1e-3 * dt
    pts = [0.0, 1.0, duration, 1.0, off, 0.0, max(end, off) * 2.0, 0.0]
    return ["*AMPLITUDE, NAME=PULSE"] + lines_of(pts)


def load_blocks(s, mesh, dt):
    """(model-data lines, step lines) of the pulse, the traction or the wall."""
    kind, load = s["load"]
    end = float(s["time"]["end"])
    if kind == "pulse":
        top = mesh.mid_span()["top"]
        force = float(load["force"]) / load_divisor(s)
        return (rectangular_amplitude(float(load["duration"]), end, dt),
                ["*CLOAD, AMPLITUDE=PULSE", f"{top + 1}, 2, {num(-force)}"])
    if kind == "traction":
        width = float(s["plate"]["width"])
        normal, shear = float(load.get("normal", 0.0)), float(load.get("shear", 0.0))
        step = ["*CLOAD, AMPLITUDE=PULSE"]
        for n, length in mesh.top_nodes_tributary():
            if shear:
                step.append(f"{n + 1}, 1, {num(shear * length * width)}")
            if normal:
                step.append(f"{n + 1}, 2, {num(-normal * length * width)}")
        return rectangular_amplitude(float(load["duration"]), end, dt), step
    if kind == "wall":
        # The body is launched by the step before (wall_launch); here the foot lands.
        lift = wall_lift(s, dt)
        return (["*AMPLITUDE, NAME=CONST", "0., 1., 1., 1."],
                ["*DLOAD, OP=NEW", "*BOUNDARY, AMPLITUDE=CONST"]
                + [f"{n + 1}, 2, 2, {num(-lift)}" for n in mesh.bottom_nodes()])
    raise ValueError(f"load {kind} reaches the deck writer")


LAUNCH_STEPS = 10


def wall_lift(s, dt):
    """How far above the wall the body starts, m: V T / 2 with T = LAUNCH_STEPS dt (s), the
    launch under the uniform acceleration V / T that ends with the foot on the wall at -V."""
    return float(s["load"][1]["velocity"]) * LAUNCH_STEPS * dt / 2.0


def wall_launch(s, dt, nlgeom, every):
    """The launch step: a uniform body acceleration V / T downward for T = LAUNCH_STEPS dt
    gives every node -V with no strain (ccx 2.20 drops *INITIAL CONDITIONS, TYPE=VELOCITY
    on the 2-D elements it expands, measured)."""
    t_launch = LAUNCH_STEPS * dt
    accel = float(s["load"][1]["velocity"]) / t_launch
    return [f"*STEP, INC=100000000{nlgeom}", "*DYNAMIC, EXPLICIT",
            f"{num(dt)}, {num(t_launch)}, {num(dt * 1e-6)}, {num(dt)}",
            "*DLOAD", f"EALL, GRAV, {num(accel)}, 0., -1., 0."] + (
                # ccx wants energy output requested in the first step with NLGEOM
                [f"*EL PRINT, ELSET=EALL, TOTALS=ONLY, FREQUENCY={LAUNCH_STEPS}", "ELSE, ELKE"]
                if every else []) + ["*END STEP"]


def output_step(s, dt_limit):
    """(step s, rows every N steps): the largest step <= dt_limit (s) that divides
    output.every, so the rows fall on k * every as the solver's; every step without every."""
    every = s["output"].get("every")
    if not every:
        return dt_limit, 1
    n = max(1, math.ceil(float(every) / dt_limit - 1e-9))
    return float(every) / n, n


def output_blocks(probe_elements, foot, every):
    """*NODE PRINT / *EL PRINT requests, every `every` increments (none when 0: the probe
    run that reads ccx's step)."""
    if not every:
        return []
    f = f"FREQUENCY={every}"
    out = [f"*NODE PRINT, NSET=NMID, {f}", "U",
           f"*EL PRINT, ELSET=EALL, TOTALS=ONLY, {f}", "ELSE, ELKE"]
    if probe_elements:
        out += [f"*EL PRINT, ELSET=EPROBE, {f}", "S"]
    if foot:
        out += [f"*NODE PRINT, NSET=NFOOT, TOTALS=ONLY, {f}", "RF",
                f"*NODE PRINT, NSET=NFOOT, {f}", "U"]
    return out


def write(s, mesh, probes, path, dt, every=0, end=None):
    """Write the deck to path with the largest step dt (s) and a history row every `every`
    steps (0: no output, for the probe run), the step ending at `end` (default time.end).
    Returns {'ccx_type', 'substitutions'}."""
    ccx_type, substitution = ELEMENT[(s["geometry"], s["mesh"]["element"])]
    end = float(s["time"]["end"]) if end is None else end
    kind = s["load"][0]
    foot = sorted(mesh.bottom_nodes()) if kind == "wall" else []
    model_data, step_loads = load_blocks(s, mesh, dt)
    probe_elements = sorted({e for e, _ in probes.values()})
    lines = ["*HEADING", f"impact scene {s.get('title') or ''} (written by adapters/calculix)"]
    lift = wall_lift(s, dt) if kind == "wall" else 0.0
    lines += nodes_and_elements(s, mesh, ccx_type, lift)
    lines += node_set("NMID", sorted(set(mesh.mid_span().values())))
    if foot:
        lines += node_set("NFOOT", foot)
    if probe_elements:
        lines += ["*ELSET, ELSET=EPROBE"] + lines_of([e + 1 for e in probe_elements], 16)
    lines += material_block(s) + boundary_block(mesh) + model_data
    nlgeom = ", NLGEOM" if s["kinematics"] == "finite" else ""
    if kind == "wall":
        lines += wall_launch(s, dt, nlgeom, every)
    lines += [f"*STEP, INC=100000000{nlgeom}", "*DYNAMIC, EXPLICIT",
              f"{num(dt)}, {num(end)}, {num(dt * 1e-6)}, {num(dt)}"]
    lines += step_loads + output_blocks(probe_elements, foot, every) + ["*END STEP"]
    with open(path, "w", encoding="ascii") as f:
        f.write("\n".join(lines) + "\n")
    subs = [substitution] if substitution else []
    if kind == "wall":
        subs.append("load.wall -> the body launched to -V by a uniform acceleration over "
                    f"{LAUNCH_STEPS} steps before t = 0 (a first step), then u_y held on the "
                    "bottom face (*BOUNDARY): the foot lands at t = 0 and never leaves the "
                    "wall (no release), and side nodes that roll down are not stopped at "
                    "y = 0; the wall force is the foot's reaction RF")
    return {"ccx_type": ccx_type, "substitutions": subs,
            "time_offset_s": LAUNCH_STEPS * dt if kind == "wall" else 0.0, "lift_m": lift}


def write_wedge(s, mesh, path, dt, every=0, end=None):
    """The axisymmetric wall as a C3D8/C3D6 wedge (wedge.py) with initial velocities -V on
    every node but the foot, whose axial displacement is held from t = 0."""
    import wedge as wedge_mod
    w = wedge_mod.Wedge(mesh)
    end = float(s["time"]["end"]) if end is None else end
    hex_type = "C3D8R" if s["mesh"]["element"] == "q4-1pt" else "C3D8"
    hexes, wedges = w.elements()
    foot_off, foot_axis = w.foot()
    lines = ["*HEADING", f"impact scene {s.get('title') or ''} (axisymmetric wedge, adapters/calculix)",
             "*NODE, NSET=NALL"]
    lines += [f"{i + 1}, {num(x)}, {num(y)}, {num(z)}" for i, (x, y, z) in enumerate(w.coords)]
    for kind, rows in ((hex_type, hexes), ("C3D6", wedges)):
        if rows:
            lines.append(f"*ELEMENT, TYPE={kind}, ELSET=EALL")
            lines += [f"{e}, " + ", ".join(map(str, nodes)) for e, nodes in rows]
    for name, nodes in (("NOFF", w.off_axis()), ("NAXIS", w.axis()),
                        ("NMID", sorted(set(w.mid_span().values()))),
                        ("NFOOTOFF", sorted(foot_off)), ("NFOOTAX", sorted(foot_axis))):
        lines += [f"*NSET, NSET={name}"] + lines_of(nodes, 16)
    lines += ["*TRANSFORM, NSET=NOFF, TYPE=C", "0., 0., 0., 0., 1., 0."]
    lines += [l for l in material_block(s) if l != ""]
    lines += ["*BOUNDARY", "NOFF, 2, 2, 0.", "NAXIS, 1, 1, 0.", "NAXIS, 3, 3, 0.",
              "NFOOTOFF, 3, 3, 0.", "NFOOTAX, 2, 2, 0."]
    foot = set(foot_off) | set(foot_axis)
    v = float(s["load"][1]["velocity"])
    lines.append("*INITIAL CONDITIONS, TYPE=VELOCITY")  # global dofs: 2 is the axis
    lines += [f"{i}, 2, {num(-v)}" for i in range(1, len(w.coords) + 1) if i not in foot]
    nlgeom = ", NLGEOM" if s["kinematics"] == "finite" else ""
    lines += [f"*STEP, INC=100000000{nlgeom}", "*DYNAMIC, EXPLICIT",
              f"{num(dt)}, {num(end)}, {num(dt * 1e-6)}, {num(dt)}"]
    if every:
        f = f"FREQUENCY={every}"
        lines += [f"*NODE PRINT, NSET=NMID, {f}", "U",
                  f"*EL PRINT, ELSET=EALL, TOTALS=ONLY, {f}", "ELSE, ELKE",
                  f"*NODE PRINT, NSET=NFOOTOFF, TOTALS=ONLY, {f}", "RF",
                  f"*NODE PRINT, NSET=NFOOTAX, TOTALS=ONLY, {f}", "RF",
                  f"*NODE PRINT, NSET=NFOOTOFF, {f}", "U"]
    lines.append("*END STEP")
    with open(path, "w", encoding="ascii") as fh:
        fh.write("\n".join(lines) + "\n")
    subs = [f"geometry: axisymmetric under the wall -> a {math.degrees(2 * wedge_mod.HALF_ANGLE):g}"
            f"-degree wedge of {hex_type} (C3D6 on the axis) with a cylindrical *TRANSFORM "
            "holding every node in its meridian plane (ccx 2.20 ignores initial velocities on "
            "CAX4, measured); results times pi / (sin a cos a)",
            "load.wall -> u_y held on the bottom face from t = 0 (*BOUNDARY), the rest of the "
            "body at -V (*INITIAL CONDITIONS): the foot starts at rest (its momentum is not in "
            "the impulse), never leaves the wall (no release), and side nodes that roll down "
            "are not stopped at y = 0; the wall force is the foot's reaction RF"]
    if s["mesh"]["element"] == "q4-sri":
        subs.insert(0, "q4-sri -> C3D8 (full integration, no B-bar: ccx has no selective "
                       "reduced integration element; locks under plastic flow)")
    elif s["mesh"]["element"] == "q4-1pt":
        subs.insert(0, "q4-1pt -> C3D8R (ccx's hourglass control), C3D6 (full) on the axis")
    return {"ccx_type": hex_type, "substitutions": subs, "time_offset_s": 0.0, "lift_m": 0.0,
            "wedge": w}
