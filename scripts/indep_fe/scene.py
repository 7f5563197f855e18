"""Scene YAML (SI units) -> plain dataclasses, with validation."""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field
from pathlib import Path

import yaml


class SceneError(ValueError):
    pass


ENDS = ("clamped", "roller", "slider", "free")


@dataclass
class Plate:
    length: float
    width: float
    thickness: float
    ends: str = "clamped"     # clamped: u_x = u_y = 0 | roller: u_x = 0 | slider: u_y = 0 | free


@dataclass
class Thermal:
    """Adiabatic heating of the Johnson-Cook law (ALGORITHM.md section 3b)."""
    initial_temperature: float    # T0, K
    melting_temperature: float    # Tm, K (> T0)
    specific_heat: float          # c, J/(kg K)
    taylor_quinney: float         # beta in [0, 1]
    reference_temperature: float = None   # Tr of T*, K (<= T0); None: T0


@dataclass
class RateLaw:
    """material.plasticity.rate (ALGORITHM.md section 3b): cowper_symonds {D, q} or
    johnson_cook {A, B, n, C, reference_rate, m, thermal}."""
    kind: str                          # cowper_symonds | johnson_cook
    D: float | None = None             # Cowper-Symonds, 1/s
    q: float | None = None             # Cowper-Symonds exponent
    A: float | None = None             # Johnson-Cook static curve A + B k^n (Pa, Pa, 1)
    B: float | None = None
    n: float | None = None
    C: float | None = None             # Johnson-Cook rate coefficient
    reference_rate: float | None = None  # 1/s
    m: float | None = None             # thermal softening exponent (needed with thermal)
    thermal: Thermal | None = None


@dataclass
class Plasticity:
    yield_stress: float
    linear_tangent: float | None = None      # E_t (Pa), linear hardening
    table: list[tuple[float, float]] | None = None  # [(k_i, sigma_i)], piecewise linear in k
    rate: RateLaw | None = None              # section 3b; johnson_cook: yield_stress = A


@dataclass
class Material:
    density: float
    youngs_modulus: float
    poisson_ratio: float
    plasticity: Plasticity | None = None


@dataclass
class MeshSpec:
    nx: int
    ny: int
    element: str          # q4-full | q4-sri | q4-1pt
    model: str            # half | full
    grading: float = 1.0
    hourglass: float = 0.05


@dataclass
class ContactLaw:
    kind: str             # paper | johnson
    length_unit: float | None = None
    datum_depth: float | None = None


@dataclass
class Impactor:
    mass: float
    velocity: float
    nose_radius: float
    # nodal coupling (ALGORITHM.md sections 5, 6 step 5): None under the surface coupling
    youngs_modulus: float | None
    poisson_ratio: float | None
    contact_law: ContactLaw | None
    indentation_datum: str | None = "mid-plane"
    force_node: str | None = None     # defaults to the datum
    # load.impactor.contact: nodal (default) | surface |
    #   {surface: {enforcement: kinematic (default) | penalty, penalty_scale: s_p}}
    coupling: str = "nodal"
    enforcement: str | None = None       # surface coupling: kinematic | penalty (section 5b)
    penalty_scale: float | None = None   # s_p of the penalty enforcement (section 5b)


@dataclass
class Pulse:
    force: float
    duration: float


@dataclass
class Wall:
    velocity: float      # m/s toward the rigid wall y = 0 (ALGORITHM.md section 5c)


@dataclass
class TimeSpec:
    end: float | None = None              # fixed end time
    after_contact: float | None = None    # or: stop this long after contact ended
    limit: float = 0.05                   # hard stop
    cfl: float | None = None
    fixed_dt: float | None = None
    allow_unstable_dt: bool = False
    update: str | None = None             # time.dt.update: once | every-step (section 6b);
                                          # None: not given (default_update)


DT_UPDATES = ("once", "every-step")


@dataclass
class Probe:
    name: str
    x: float
    y: float


@dataclass
class Output:
    every: float | None           # None: every step
    probes: list[Probe] = field(default_factory=list)


@dataclass
class Scene:
    plate: Plate
    material: Material
    mesh: MeshSpec
    impactor: Impactor | None
    pulse: Pulse | None
    time: TimeSpec
    output: Output
    kinematics: str = "small"    # small (sections 2-3) | finite (section 3c)
    geometry: str = "plane-strain"  # plane-strain (sections 1-2) | axisymmetric (section 3d)
    wall: Wall | None = None        # the body onto the rigid wall (section 5c)


KINEMATICS = ("small", "finite")
GEOMETRIES = ("plane-strain", "axisymmetric")


def _refuse_unknown(d: dict, known: set[str], where: str) -> None:
    """Unknown keys are refused, as the Rust scene parser does (never silently ignored)."""
    unknown = sorted(str(k) for k in d if k not in known)
    if unknown:
        raise SceneError(f"unknown key '{where}.{unknown[0]}' (known: {', '.join(sorted(known))})")


def _refuse_unsupported(d: dict, keys: set[str], where: str) -> None:
    """Keys of the scene contract this independent solver does not implement: refused, so a
    comparison never runs a different problem than the one written."""
    for key in sorted(keys & set(d)):
        raise SceneError(f"'{where}.{key}' is not supported by indep_fe")


def _req(d: dict, key: str, where: str):
    if not isinstance(d, dict) or key not in d:
        raise SceneError(f"missing '{where}.{key}'")
    return d[key]


def _pos(value, where: str, allow_zero: bool = False) -> float:
    v = float(value)
    if not math.isfinite(v) or v < 0 or (v == 0 and not allow_zero):
        raise SceneError(f"'{where}' must be {'>= 0' if allow_zero else '> 0'}, got {value!r}")
    return v


def _one_of(d, where: str) -> tuple[str, object]:
    if not isinstance(d, dict) or len(d) != 1:
        raise SceneError(f"'{where}' must be a mapping with exactly one key, got {d!r}")
    (k, v), = d.items()
    return k, v


def _parse_plate(data: dict) -> Plate:
    """plate: dimensions and end supports."""
    p = _req(data, "plate", "scene")
    _refuse_unknown(p, {"length", "width", "thickness", "ends"}, "plate")
    ends = str(p.get("ends", "clamped"))
    if ends not in ENDS:
        raise SceneError(f"plate.ends must be {' | '.join(ENDS)}, got {ends}")
    return Plate(_pos(_req(p, "length", "plate"), "plate.length"),
                  _pos(_req(p, "width", "plate"), "plate.width"),
                  _pos(_req(p, "thickness", "plate"), "plate.thickness"), ends)


def _parse_hardening(pl: dict, plast: Plasticity, E: float, sy0: float) -> None:
    """material.plasticity.hardening into `plast`: linear (tangent modulus) or a table."""
    hard = _req(pl, "hardening", "material.plasticity")
    kind, val = _one_of(hard, "material.plasticity.hardening")
    if kind == "linear":
        et = _pos(val, "material.plasticity.hardening.linear", allow_zero=True)
        if et >= E:
            raise SceneError("hardening.linear (tangent modulus E_t) must be < youngs_modulus")
        plast.linear_tangent = et
    elif kind == "table":
        rows = [(float(a), float(b)) for a, b in val]
        if not rows:
            raise SceneError("hardening.table is empty")
        # the table must start at (0, yield_stress) (to 1e-9 relative): an error, never patched
        if rows[0][0] != 0.0 or abs(rows[0][1] - sy0) > 1e-9 * sy0:
            raise SceneError(f"hardening.table[0] = {list(rows[0])} must be "
                             f"[0, yield_stress] = [0, {sy0:g}]")
        if not all(math.isfinite(a) and math.isfinite(b) for a, b in rows):
            raise SceneError("hardening.table: entries must be finite numbers")
        ks = [r[0] for r in rows]
        if any(b <= a for a, b in zip(ks, ks[1:])):
            raise SceneError("hardening.table: plastic strains must increase strictly")
        ss = [r[1] for r in rows]
        if any(b < a for a, b in zip(ss, ss[1:])):
            raise SceneError("hardening.table: flow stresses must not decrease")
        plast.table = rows
    else:
        raise SceneError(f"unknown hardening '{kind}' (linear | table)")


CS_KEYS = {"D", "q"}
JC_KEYS = {"A", "B", "n", "C", "reference_rate", "m", "thermal"}
THERMAL_KEYS = {"initial_temperature", "melting_temperature", "specific_heat", "taylor_quinney",
                "reference_temperature"}


def _parse_rate(rate) -> RateLaw:
    """material.plasticity.rate: {cowper_symonds: {D, q}} | {johnson_cook: {A, B, n, C,
    reference_rate, m, thermal: {initial_temperature, melting_temperature, specific_heat,
    taylor_quinney, reference_temperature}}} (ALGORITHM.md section 3b)."""
    where = "material.plasticity.rate"
    kind, val = _one_of(rate, where)
    if not isinstance(val, dict):
        raise SceneError(f"'{where}.{kind}' must be a mapping, got {val!r}")
    w = f"{where}.{kind}"
    if kind == "cowper_symonds":
        _refuse_unknown(val, CS_KEYS, w)
        return RateLaw("cowper_symonds", D=_pos(_req(val, "D", w), f"{w}.D"),
                       q=_pos(_req(val, "q", w), f"{w}.q"))
    if kind != "johnson_cook":
        raise SceneError(f"unknown rate law '{kind}' (cowper_symonds | johnson_cook)")
    _refuse_unknown(val, JC_KEYS, w)
    law = RateLaw("johnson_cook",
                  A=_pos(_req(val, "A", w), f"{w}.A"),
                  B=_pos(_req(val, "B", w), f"{w}.B", allow_zero=True),
                  n=_pos(_req(val, "n", w), f"{w}.n"),
                  C=_pos(_req(val, "C", w), f"{w}.C", allow_zero=True),
                  reference_rate=_pos(_req(val, "reference_rate", w), f"{w}.reference_rate"),
                  m=_pos(val["m"], f"{w}.m") if val.get("m") is not None else None)
    if val.get("thermal") is not None:
        th = val["thermal"]
        wt = f"{w}.thermal"
        if not isinstance(th, dict):
            raise SceneError(f"'{wt}' must be a mapping, got {th!r}")
        _refuse_unknown(th, THERMAL_KEYS, wt)
        t0 = _pos(_req(th, "initial_temperature", wt), f"{wt}.initial_temperature")
        tm = _pos(_req(th, "melting_temperature", wt), f"{wt}.melting_temperature")
        if not tm > t0:
            raise SceneError(f"{wt}.melting_temperature ({tm}) must be above "
                             f"initial_temperature ({t0})")
        beta = float(_req(th, "taylor_quinney", wt))
        if not 0.0 <= beta <= 1.0:
            raise SceneError(f"{wt}.taylor_quinney must be in [0, 1], got {beta}")
        if law.m is None:
            raise SceneError(f"{w}.m (thermal softening exponent) is needed with thermal")
        tr = None   # absent: T0 (rate.py)
        if th.get("reference_temperature") is not None:
            tr = _pos(th["reference_temperature"], f"{wt}.reference_temperature")
            if tr > t0:
                raise SceneError(f"{wt}.reference_temperature ({tr}) must not be above "
                                 f"initial_temperature ({t0})")
        law.thermal = Thermal(t0, tm, _pos(_req(th, "specific_heat", wt), f"{wt}.specific_heat"),
                              beta, tr)
    return law


def _parse_plasticity(pl: dict, E: float) -> Plasticity:
    """material.plasticity: yield stress and hardening (section 3), and the optional rate law
    (section 3b); under johnson_cook the static curve is A + B k^n and yield_stress and
    hardening are left out."""
    _refuse_unknown(pl, {"yield_stress", "hardening", "rate"}, "material.plasticity")
    rate = _parse_rate(pl["rate"]) if pl.get("rate") is not None else None
    if rate is not None and rate.kind == "johnson_cook":
        for key in ("yield_stress", "hardening"):
            if key in pl:
                raise SceneError(f"material.plasticity.{key} must be left out under "
                                 f"johnson_cook (its static curve is A + B k^n)")
        return Plasticity(yield_stress=rate.A, rate=rate)
    sy0 = _pos(_req(pl, "yield_stress", "material.plasticity"), "material.plasticity.yield_stress")
    plast = Plasticity(yield_stress=sy0, rate=rate)
    _parse_hardening(pl, plast, E, sy0)
    return plast


def _parse_material(data: dict) -> Material:
    """material: elastic constants and the optional plasticity."""
    m = _req(data, "material", "scene")
    _refuse_unknown(m, {"density", "youngs_modulus", "poisson_ratio", "plasticity"}, "material")
    nu = float(_req(m, "poisson_ratio", "material"))
    if not (-1.0 < nu < 0.5):
        raise SceneError(f"material.poisson_ratio must be in (-1, 0.5), got {nu}")
    E = _pos(_req(m, "youngs_modulus", "material"), "material.youngs_modulus")
    plast = None
    if m.get("plasticity") is not None:
        plast = _parse_plasticity(m["plasticity"], E)
    return Material(_pos(_req(m, "density", "material"), "material.density"), E, nu, plast)


def _parse_mesh(data: dict) -> MeshSpec:
    """mesh: size, element, model, grading, hourglass."""
    me = _req(data, "mesh", "scene")
    _refuse_unknown(me, {"nx", "ny", "element", "model", "grading", "hourglass", "distortion"},
                    "mesh")
    if float(me.get("distortion", 0.0)) != 0.0:
        _refuse_unsupported(me, {"distortion"}, "mesh")
    mesh = MeshSpec(int(_req(me, "nx", "mesh")), int(_req(me, "ny", "mesh")),
                    str(me.get("element", "q4-sri")), str(me.get("model", "half")),
                    float(me.get("grading", 1.0)), float(me.get("hourglass", 0.05)))
    if mesh.element not in ("q4-full", "q4-sri", "q4-1pt"):
        raise SceneError(f"mesh.element must be q4-full | q4-sri | q4-1pt, got {mesh.element}")
    if mesh.model not in ("half", "full"):
        raise SceneError(f"mesh.model must be half | full, got {mesh.model}")
    if mesh.nx < 1 or mesh.ny < 2 or mesh.ny % 2:
        raise SceneError("mesh.nx must be >= 1 and mesh.ny even and >= 2")
    if mesh.model == "full" and mesh.nx % 2:
        raise SceneError("mesh.nx must be even for the full model (mid-span node row)")
    if mesh.grading < 1.0:
        raise SceneError("mesh.grading (largest/smallest element length) must be >= 1")
    if mesh.hourglass < 0:
        raise SceneError("mesh.hourglass must be >= 0")
    return mesh


NODAL_KEYS = ("youngs_modulus", "poisson_ratio", "contact_law", "indentation_datum", "force_node")
PENALTY_SCALE_DEFAULT = 0.1
ENFORCEMENTS = ("kinematic", "penalty")


def _parse_coupling(c) -> tuple[str, str | None, float | None]:
    """load.impactor.contact: nodal (default) | surface |
    {surface: {enforcement: kinematic | penalty, penalty_scale: s_p}} (ALGORITHM.md section 5b):
    the enforcement defaults to kinematic; penalty_scale, in (0, 1], default 0.1, belongs to the
    penalty enforcement only (an error otherwise). Returns (coupling, enforcement, s_p)."""
    if c is None or c == "nodal":
        return "nodal", None, None
    if c == "surface":
        return "surface", "kinematic", None
    if isinstance(c, dict) and len(c) == 1 and "surface" in c:
        opts = c["surface"] or {}
        if not isinstance(opts, dict):
            raise SceneError(f"load.impactor.contact.surface must be a mapping, got {opts!r}")
        _refuse_unknown(opts, {"enforcement", "penalty_scale"}, "load.impactor.contact.surface")
        enf = str(opts.get("enforcement", "kinematic"))
        if enf not in ENFORCEMENTS:
            raise SceneError(f"load.impactor.contact.surface.enforcement must be kinematic | "
                             f"penalty, got {enf!r}")
        if enf != "penalty":
            if "penalty_scale" in opts:
                raise SceneError("load.impactor.contact.surface.penalty_scale belongs to the "
                                 "penalty enforcement: give `enforcement: penalty` with it, or "
                                 "remove it (the kinematic enforcement has no stiffness)")
            return "surface", enf, None
        sp = float(opts.get("penalty_scale", PENALTY_SCALE_DEFAULT))
        if not (0.0 < sp <= 1.0):
            raise SceneError(f"load.impactor.contact.surface.penalty_scale must be in (0, 1], "
                             f"got {sp}")
        return "surface", enf, sp
    raise SceneError(f"load.impactor.contact must be nodal | surface | {{surface: "
                     f"{{enforcement: kinematic | penalty, penalty_scale: s}}}}, got {c!r}")


def _parse_impactor(im: dict) -> Impactor:
    """load.impactor: mass, velocity, nose radius and the coupling: the nodal one (contact law,
    datum and force node) or the surface one (section 5b: rigid nose, no law)."""
    _refuse_unknown(im, {"mass", "velocity", "nose_radius", "contact", *NODAL_KEYS}, "load.impactor")
    coupling, enforcement, sp = _parse_coupling(im.get("contact"))
    mass = _pos(_req(im, "mass", "load.impactor"), "load.impactor.mass")
    velocity = float(_req(im, "velocity", "load.impactor"))
    radius = _pos(_req(im, "nose_radius", "load.impactor"), "load.impactor.nose_radius")
    if coupling == "surface":
        for key in NODAL_KEYS:
            if key in im:
                raise SceneError(f"load.impactor.{key} belongs to the nodal coupling; "
                                 f"with contact: surface the nose is rigid: remove it")
        return Impactor(mass, velocity, radius, None, None, None, None, None,
                        coupling="surface", enforcement=enforcement, penalty_scale=sp)
    kind, val = _one_of(_req(im, "contact_law", "load.impactor"), "load.impactor.contact_law")
    if kind == "paper":
        law = ContactLaw("paper", length_unit=_pos(_req(val, "length_unit", "contact_law.paper"),
                                                   "contact_law.paper.length_unit"))
    elif kind == "johnson":
        law = ContactLaw("johnson", datum_depth=_pos(_req(val, "datum_depth", "contact_law.johnson"),
                                                     "contact_law.johnson.datum_depth"))
    else:
        raise SceneError(f"unknown contact_law '{kind}' (paper | johnson)")
    datum = str(im.get("indentation_datum", "mid-plane"))
    fnode = im.get("force_node")
    for name, v in (("indentation_datum", datum), ("force_node", fnode)):
        if v is not None and v not in ("mid-plane", "top-surface"):
            raise SceneError(f"load.impactor.{name} must be mid-plane | top-surface, got {v}")
    isnu = float(_req(im, "poisson_ratio", "load.impactor"))
    return Impactor(mass, velocity, radius,
                    _pos(_req(im, "youngs_modulus", "load.impactor"), "load.impactor.youngs_modulus"),
                    isnu, law, datum, fnode if fnode is not None else datum)


def _parse_load(data: dict) -> tuple[Impactor | None, Pulse | None, Wall | None]:
    """load: exactly one of an impactor, a pulse or the wall."""
    load = _req(data, "load", "scene")
    _refuse_unknown(load, {"impactor", "pulse", "traction", "wall"}, "load")
    _refuse_unsupported(load, {"traction"}, "load")
    impactor = pulse = wall = None
    if sum(k in load for k in ("impactor", "pulse", "wall")) != 1:
        raise SceneError("load must have exactly one of 'impactor', 'pulse' or 'wall'")
    if "impactor" in load:
        impactor = _parse_impactor(load["impactor"])
    elif "wall" in load:
        _refuse_unknown(load["wall"], {"velocity"}, "load.wall")
        wall = Wall(_pos(_req(load["wall"], "velocity", "load.wall"), "load.wall.velocity"))
    else:
        pu = load["pulse"]
        _refuse_unknown(pu, {"force", "duration"}, "load.pulse")
        pulse = Pulse(float(_req(pu, "force", "load.pulse")),
                      _pos(_req(pu, "duration", "load.pulse"), "load.pulse.duration"))
    return impactor, pulse, wall


def _parse_time(data: dict) -> TimeSpec:
    """time: the end (a time or after_contact), the step, the limit."""
    t = _req(data, "time", "scene")
    _refuse_unknown(t, {"end", "dt", "limit", "allow_unstable_dt"}, "time")
    ts = TimeSpec(limit=_pos(t.get("limit", 0.05), "time.limit"),
                  allow_unstable_dt=bool(t.get("allow_unstable_dt", False)))
    end = _req(t, "end", "time")
    if isinstance(end, dict):
        kind, val = _one_of(end, "time.end")
        if kind != "after_contact":
            raise SceneError("time.end must be a number or {after_contact: T}")
        ts.after_contact = _pos(val, "time.end.after_contact", allow_zero=True)
    else:
        ts.end = _pos(end, "time.end")
    dt = _req(t, "dt", "time")
    if isinstance(dt, dict) and "update" in dt:
        # section 6b: the step re-estimated at every step (finite kinematics and cfl only,
        # checked in parse_scene once the kinematics is known)
        dt = dict(dt)
        ts.update = str(dt.pop("update"))
        if ts.update not in DT_UPDATES:
            raise SceneError(f"time.dt.update must be once | every-step, got {ts.update!r}")
    kind, val = _one_of(dt, "time.dt")
    if kind == "cfl":
        ts.cfl = _pos(val, "time.dt.cfl")
    elif kind == "fixed":
        ts.fixed_dt = _pos(val, "time.dt.fixed")
    else:
        raise SceneError("time.dt must be {cfl: c} or {fixed: dt}")
    return ts


def _parse_output(data: dict, plate: Plate) -> Output:
    """output: history spacing and probes (inside the plate)."""
    o = data.get("output") or {}
    _refuse_unknown(o, {"every", "probes", "fields"}, "output")
    for name, pr in (o.get("probes") or {}).items():
        _refuse_unknown(pr, {"x", "y"}, f"output.probes.{name}")
    probes = [Probe(str(name), float(_req(pr, "x", f"output.probes.{name}")),
                    float(_req(pr, "y", f"output.probes.{name}")))
              for name, pr in (o.get("probes") or {}).items()]
    for pr in probes:
        if not (0.0 <= pr.x <= plate.length and 0.0 <= pr.y <= plate.thickness):
            raise SceneError(f"output.probes.{pr.name} = ({pr.x}, {pr.y}) must lie in the plate")
    every = o.get("every")      # omitted: a history row every step
    return Output(None if every is None else _pos(every, "output.every"), probes)


def parse_scene(data: dict) -> Scene:
    if not isinstance(data, dict):
        raise SceneError("scene must be a YAML mapping")
    _refuse_unknown(data, {"plate", "material", "mesh", "load", "time", "output", "title",
                           "kinematics", "geometry"}, "scene")
    kinematics = str(data.get("kinematics", "small"))
    if kinematics not in KINEMATICS:
        raise SceneError(f"kinematics must be small | finite, got {kinematics!r}")
    plate = _parse_plate(data)
    material = _parse_material(data)
    mesh = _parse_mesh(data)
    impactor, pulse, wall = _parse_load(data)
    ts = _parse_time(data)
    if wall is not None and (plate.ends != "free" or mesh.model != "half" or ts.end is None):
        raise SceneError("load: {wall} needs plate.ends: free, mesh.model: half and time.end a time")
    output = _parse_output(data, plate)
    geometry = str(data.get("geometry", "plane-strain"))
    if geometry not in GEOMETRIES:
        raise SceneError(f"geometry must be plane-strain | axisymmetric, got {geometry!r}")
    if geometry == "axisymmetric":
        _check_axisymmetric(mesh, impactor)
    if ts.update is None:
        ts.update = default_update(ts, kinematics, wall)
    if ts.update == "every-step" and (kinematics != "finite" or ts.cfl is None):
        raise SceneError("time.dt.update: every-step needs kinematics: finite and time.dt.cfl "
                         f"(got kinematics {kinematics!r}, time.dt {'cfl' if ts.cfl else 'fixed'})")
    return Scene(plate, material, mesh, impactor, pulse, ts, output, kinematics, geometry, wall)


def default_update(ts: TimeSpec, kinematics: str, wall: Wall | None) -> str:
    """time.dt.update when the scene does not say (section 6b): every-step for a finite body on
    the rigid wall with the step given as cfl (its elements are crushed), else once."""
    return "every-step" if (wall is not None and kinematics == "finite"
                            and ts.cfl is not None) else "once"


def _check_axisymmetric(mesh: MeshSpec, impactor: Impactor | None) -> None:
    """Section 3d's domain: the half model, a pulse, the surface nose or the wall, either kinematics
    (finite: section 3e) (time.dt.estimate: global, also refused there, is refused for every
    scene here)."""
    if mesh.model != "half":
        raise SceneError(f"geometry: axisymmetric needs mesh.model: half, got {mesh.model!r}")
    if impactor is not None and impactor.coupling != "surface":
        raise SceneError("geometry: axisymmetric needs load.impactor.contact: surface")


def load_scene(path: str | Path) -> Scene:
    with open(path) as fh:
        return parse_scene(yaml.safe_load(fh))


def with_dotted(base: dict, over: dict) -> dict:
    """A deep copy of the scene dict `base` with dotted-path overrides (the scene's YAML paths,
    e.g. {"mesh.element": "q4-1pt"}); a value None removes the key."""
    d = copy.deepcopy(base)
    for path, value in over.items():
        keys = path.split(".")
        node = d
        for k in keys[:-1]:
            node = node.setdefault(k, {})
        if value is None:
            node.pop(keys[-1], None)
        else:
            node[keys[-1]] = copy.deepcopy(value)
    return d
