"""The rigid nose in surface contact (`load.impactor` with `contact: surface`), as ccx can run
it: implicit dynamics with a penalty contact pair. Lengths m, forces N, times s, Pa, kg.

ccx 2.20's explicit dynamics stops once a contact pair is defined, and it drops initial
velocities on the 2-D elements it expands (both measured), so the plate is written as what
ccx makes of a CPE4 anyway, a one-layer C3D8 slab of thickness `plate.width` with u_z = 0
on every node (plane strain), and the nose as a rigid body (impact's section 5b: a cylinder of
radius R, its lowest point on the top surface at mid-span at t = 0, moving along y only):
- an arc of C3D8 elements (from the lowest point toward x = 0 in the half model, both ways in
  the full one: the quarter circle, or less where R > L / 2; density ~0) made a
  `*RIGID BODY` with its reference node at the circle's centre; a `MASS` element there carries
  the impactor's mass (half of it in the half model, whose width is the half plate's);
  `*INITIAL CONDITIONS, TYPE=VELOCITY` -v0 on the nose;
- `*CONTACT PAIR, TYPE=SURFACE TO SURFACE` (penalty, frictionless), the plate's top faces the
  slave, the nose's outer faces the master, `PRESSURE-OVERCLOSURE=LINEAR` with the slope
  `PENALTY_PER_MODULUS E / dy` (dy the top row's element height);
- `*DYNAMIC` (implicit, ccx's alpha method with its default alpha = -0.05) with the step
  `implicit_step`, ccx free to cut it back where the contact changes.
The contact force is ccx's `*CONTACT PRINT` `CF` (the total force on the slave surface).
"""

import math

import deck

ARC_SEGMENTS = 32  # elements along the nose's arc (the quarter circle: 2.8 degrees each)
RING_FRACTION = 0.1  # the ring's thickness over min(R, h) (rigid: no effect but its faces)
REACH = 1.1  # the arc's reach over L / 2 (where R is larger)
# The penalty slope over E / dy (1/1): on the Table 1 plate (80 x 16, dy = 1.175 mm) 5.7e14
# Pa/m; see the README for the measured effect of the slope and the step.
PENALTY_PER_MODULUS = 5.0
STEPS_PER_RUN = 1500  # the implicit step: time.end / this, a multiple of output.every
# ccx's increment bound (the step's INC): with INC=100000000 (the explicit decks' bound) ccx
# 2.20 dies of signal 11 reading a 20 x 4 elasto-plastic contact deck that it reads with this.
MAX_INCREMENTS = 100000


def implicit_step(s):
    """The step, s: the larger of output.every and time.end / STEPS_PER_RUN, rounded up to a
    multiple of output.every. ccx prints every increment, so the rows fall on k every as the
    solver's where ccx has not cut the step back."""
    target = float(s["time"]["end"]) / STEPS_PER_RUN
    every = s["output"].get("every")
    if not every:
        return target
    every = float(every)
    return every * max(1, math.ceil(target / every - 1e-9))


def penalty_slope(s, mesh):
    """The contact pair's pressure-overclosure slope, Pa/m."""
    _, dy = mesh.smallest_sizes()
    return PENALTY_PER_MODULUS * float(s["material"]["youngs_modulus"]) / dy


class Nose:
    """The nose's ring of C3D8 elements (numbers after the plate's) and its two nodes. Arc
    stations are angles phi from the lowest point, toward x = 0 (phi > 0); the arc reaches
    |x - x_c| = min(R, REACH (L / 2)) (impact's candidates reach 1.1 R, and no node lies past
    L / 2), so a flat nose (R = 1e6 m) is a strip over the plate."""

    def __init__(self, s, mesh, first_node, first_element):
        impactor = s["load"][1]
        self.radius = float(impactor["nose_radius"])
        self.width = float(s["plate"]["width"])
        self.centre = (0.5 * mesh.length, mesh.h + self.radius)
        self.top = mesh.h
        self.thickness = RING_FRACTION * min(self.radius, mesh.h)
        self.half_model = mesh.model == "half"
        reach = min(1.0, REACH * 0.5 * mesh.length / self.radius)
        self.span = math.asin(reach)
        self.first_node, self.first_element = first_node, first_element

    def angles(self):
        """The arc's stations phi, rad: from 0 to the span (half model), or from the span
        on the x > x_c side through 0 to the span toward x = 0 (full model)."""
        if self.half_model:
            return [self.span * k / ARC_SEGMENTS for k in range(ARC_SEGMENTS + 1)]
        return [self.span * (k - ARC_SEGMENTS) / ARC_SEGMENTS for k in range(2 * ARC_SEGMENTS + 1)]

    def node(self, k, inner, back):
        """Node number of arc station k, the outer (0) or inner (1) circle, z = 0 or W."""
        return self.first_node + (4 * k + 2 * inner + back)

    def point(self, phi, r):
        """(x, y) of the circle of radius r about the centre at phi from the lowest point, m
        (arc_point)."""
        return arc_point((self.centre[0], self.top), self.radius, r, phi)

    def coordinates(self):
        """[(node number, x, y, z)] of the ring."""
        out = []
        for k, phi in enumerate(self.angles()):
            for inner, r in ((0, self.radius), (1, self.radius - self.thickness)):
                x, y = self.point(phi, r)
                out += [(self.node(k, inner, z), x, y, z * self.width) for z in (0, 1)]
        return out

    def elements(self):
        """[(element number, 8 nodes)]; corners 1-4 on z = 0 counter-clockwise (phi grows
        clockwise about the centre, toward x = 0), the outer face (ccx face S6: nodes
        4-8-5-1) toward the plate."""
        out = []
        for k in range(len(self.angles()) - 1):
            a, b = k, k + 1
            ring = [self.node(a, 0, 0), self.node(a, 1, 0), self.node(b, 1, 0), self.node(b, 0, 0)]
            ring += [self.node(a, 0, 1), self.node(a, 1, 1), self.node(b, 1, 1), self.node(b, 0, 1)]
            out.append((self.first_element + k, ring))
        return out

    def reference_nodes(self):
        """(reference node, rotation node): after the ring's nodes."""
        last = self.node(len(self.angles()) - 1, 1, 1)
        return last + 1, last + 2


def arc_point(touch, radius, r, phi):
    """(x, y) of the circle of radius r about the centre of a cylinder of `radius` whose lowest
    point is `touch` (x, y), at the angle phi from the lowest point toward -x, m:
    y = y_touch + (R - r) + 2 r sin^2(phi / 2), written without R - R cos(phi) (a flat nose's R
    is 1e6 m)."""
    return (touch[0] - r * math.sin(phi),
            touch[1] + (radius - r) + 2.0 * r * math.sin(0.5 * phi) ** 2)


def slab_blocks(s, mesh, element_type):
    """*NODE and *ELEMENT of the plate as a one-layer slab: node n + 1 at z = 0 and
    n + 1 + N at z = W (N nodes a layer); element numbers as the 2-D mesh's."""
    count = (mesh.nx + 1) * (mesh.ny + 1)
    width = float(s["plate"]["width"])
    out = ["*NODE, NSET=NPLATE"]
    for n in range(count):
        x, y = mesh.ccx_xy(n)
        out += [f"{n + 1}, {deck.num(x)}, {deck.num(y)}, 0.",
                f"{n + 1 + count}, {deck.num(x)}, {deck.num(y)}, {deck.num(width)}"]
    out.append(f"*ELEMENT, TYPE={element_type}, ELSET=EALL")
    for e, corners in mesh.elements():
        nodes = [c + 1 for c in corners] + [c + 1 + count for c in corners]
        out.append(f"{e + 1}, " + ", ".join(map(str, nodes)))
    return out, count


def top_faces(mesh):
    """The plate's top faces as ccx element faces: face S5 (nodes 3-7-8-4) of the top row."""
    first = (mesh.ny - 1) * mesh.nx
    return [f"{first + i + 1}, S5" for i in range(mesh.nx)]


def nose_blocks(s, nose):
    """The ring, its rigid body, the mass and the initial velocity."""
    ref, rot = nose.reference_nodes()
    mass = float(s["load"][1]["mass"]) / deck.load_divisor(s)
    v0 = float(s["load"][1]["velocity"])
    cx, cy = nose.centre
    out = ["*NODE, NSET=NNOSE"]
    out += [f"{n}, {deck.num(x)}, {deck.num(y)}, {deck.num(z)}" for n, x, y, z in nose.coordinates()]
    out += ["*NODE, NSET=NREF", f"{ref}, {deck.num(cx)}, {deck.num(cy)}, {deck.num(nose.width / 2)}",
            "*NODE, NSET=NROT", f"{rot}, {deck.num(cx)}, {deck.num(cy)}, {deck.num(nose.width / 2)}",
            "*ELEMENT, TYPE=C3D8, ELSET=ENOSE"]
    out += [f"{e}, " + ", ".join(map(str, nodes)) for e, nodes in nose.elements()]
    mass_element = nose.elements()[-1][0] + 1
    out += ["*SURFACE, NAME=SNOSE, TYPE=ELEMENT"] + [f"{e}, S6" for e, _ in nose.elements()]
    out += ["*ELEMENT, TYPE=MASS, ELSET=EMASS", f"{mass_element}, {ref}",
            "*MASS, ELSET=EMASS", deck.num(mass),
            "*MATERIAL, NAME=NOSE", "*ELASTIC",
            f"{deck.num(float(s['material']['youngs_modulus']))}, 0.3",
            "*DENSITY", "1e-6", "*SOLID SECTION, ELSET=ENOSE, MATERIAL=NOSE",
            f"*RIGID BODY, ELSET=ENOSE, REF NODE={ref}, ROT NODE={rot}"]
    out += ["*INITIAL CONDITIONS, TYPE=VELOCITY", f"{ref}, 2, {deck.num(-v0)}"]
    out += [f"{n}, 2, {deck.num(-v0)}" for n, _, _, _ in nose.coordinates()]
    return out


def write_contact(s, mesh, probes, path):
    """Write the implicit contact deck to path. Returns the adapter's info: the ccx element,
    the substitutions, the step and the nose (for the history)."""
    element_type = "C3D8R" if s["mesh"]["element"] == "q4-1pt" else "C3D8"
    end = float(s["time"]["end"])
    dt = implicit_step(s)
    lines = ["*HEADING", f"impact scene {s.get('title') or ''} (surface contact, adapters/calculix)"]
    slab, count = slab_blocks(s, mesh, element_type)
    lines += slab
    nose = Nose(s, mesh, 2 * count + 1, mesh.nx * mesh.ny + 1)
    lines += ["*SURFACE, NAME=SPLATE, TYPE=ELEMENT"] + top_faces(mesh)
    lines += nose_blocks(s, nose)
    lines += deck.node_set("NMID", sorted(set(mesh.mid_span().values())))
    probe_elements = sorted({e for e, _ in probes.values()})
    if probe_elements:
        lines += ["*ELSET, ELSET=EPROBE"] + deck.lines_of([e + 1 for e in probe_elements], 16)
    lines += plate_material(s)
    lines += supports(mesh, count, nose)
    lines += ["*SURFACE INTERACTION, NAME=NOSECONTACT",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              deck.num(penalty_slope(s, mesh)),
              "*CONTACT PAIR, INTERACTION=NOSECONTACT, TYPE=SURFACE TO SURFACE",
              "SPLATE, SNOSE"]
    nlgeom = ", NLGEOM" if s["kinematics"] == "finite" else ""
    lines += [f"*STEP, INC={MAX_INCREMENTS}{nlgeom}", "*DYNAMIC",
              f"{deck.num(dt)}, {deck.num(end)}, {deck.num(dt * 1e-4)}, {deck.num(dt)}"]
    lines += output_requests(probe_elements)
    lines.append("*END STEP")
    with open(path, "w", encoding="ascii") as f:
        f.write("\n".join(lines) + "\n")
    subs = [f"mesh.element {s['mesh']['element']} -> {element_type} in a one-layer slab with "
            "u_z = 0 (plane strain)" + ("" if element_type == "C3D8R" else
                                        " (2x2x2 full integration, no B-bar)"),
            "load.impactor.contact: surface (kinematic or penalty) -> ccx's penalty "
            "SURFACE TO SURFACE pair with a rigid nose (*RIGID BODY) and the slope "
            f"{penalty_slope(s, mesh):.3g} Pa/m, in implicit dynamics (*DYNAMIC, alpha "
            f"-0.05) with the step {dt:.3g} s (ccx cuts it back where it needs)"]
    return {"ccx_type": element_type, "substitutions": subs, "dt": dt, "nose": nose}


def plate_material(s):
    """The plate's material and its solid section (no thickness line: a 3-D section)."""
    return deck.material_block(s)[:-1]


def supports(mesh, count, nose):
    """The plate's supports on both layers, u_z = 0 everywhere, the nose along y only."""
    out = ["*BOUNDARY"]
    for n, dofs in sorted(mesh.supports().items()):
        for d in sorted(dofs):
            out += [f"{n + 1}, {d}, {d}, 0.", f"{n + 1 + count}, {d}, {d}, 0."]
    ref, rot = nose.reference_nodes()
    out += ["NPLATE, 3, 3, 0.", f"{ref}, 1, 1, 0.", f"{ref}, 3, 3, 0.", f"{rot}, 1, 3, 0."]
    return out


def output_requests(probe_elements):
    """The nose's motion, the mid-span nodes, the probes, the energies and the contact force
    at every increment."""
    f = "FREQUENCY=1"
    out = [f"*NODE PRINT, NSET=NREF, {f}", "U, V",
           f"*NODE PRINT, NSET=NMID, {f}", "U",
           f"*EL PRINT, ELSET=EALL, TOTALS=ONLY, {f}", "ELSE, ELKE"]
    if probe_elements:
        out += [f"*EL PRINT, ELSET=EPROBE, {f}", "S"]
    out += [f"*CONTACT PRINT, SLAVE=SPLATE, MASTER=SNOSE, {f}", "CF"]
    return out
