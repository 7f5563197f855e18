"""Read the resolved scene (scene.json) and decide what CalculiX can express.

Every value is in SI units, as in docs/scene-reference.md. A missing optional key takes the
documented default, so an unresolved scene (written by hand) is read the same way.
"""

import json
import os


class NotExpressible(Exception):
    """A scene feature ccx cannot express: `feature` names it, `reason` says why."""

    def __init__(self, feature, reason):
        super().__init__(f"{feature}: {reason}")
        self.feature = feature
        self.reason = reason


def load(scene_yaml):
    """The scene as a dict, from `scene.json` next to `scene_yaml` (no YAML reader here)."""
    path = os.path.join(os.path.dirname(os.path.abspath(scene_yaml)), "scene.json")
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def one_key(mapping, where):
    """The single (key, value) of a 'one key of' mapping; a bare word is (word, {})."""
    if isinstance(mapping, str):
        return mapping, {}
    if not isinstance(mapping, dict) or len(mapping) != 1:
        raise ValueError(f"{where}: expected exactly one key, got {mapping!r}")
    key = next(iter(mapping))
    return key, mapping[key] if mapping[key] is not None else {}


def settings(scene):
    """The scene with the defaults of docs/scene-reference.md filled in (a new dict)."""
    plate = dict(scene["plate"])
    plate.setdefault("ends", "clamped")
    mesh = dict(scene["mesh"])
    for key, default in (("element", "q4-sri"), ("model", "half"), ("grading", 1.0),
                         ("distortion", 0.0), ("hourglass", 0.05)):
        if mesh.get(key) is None:
            mesh[key] = default
    time = dict(scene["time"])
    time.setdefault("limit", 0.05)
    time.setdefault("allow_unstable_dt", False)
    output = dict(scene.get("output") or {})
    output["probes"] = dict(output.get("probes") or {})
    load_kind, load_value = one_key(scene["load"], "load")
    return {
        "title": scene.get("title"),
        "geometry": scene.get("geometry") or "plane-strain",
        "kinematics": scene.get("kinematics") or "small",
        "plate": plate,
        "material": dict(scene["material"]),
        "mesh": mesh,
        "load": (load_kind, dict(load_value)),
        "time": time,
        "output": output,
    }


def check_expressible(s):
    """Raise NotExpressible for the first scene feature this adapter cannot put in ccx."""
    mesh, material, (kind, load_value), time = s["mesh"], s["material"], s["load"], s["time"]
    if float(mesh["distortion"]) != 0.0:
        raise NotExpressible("mesh.distortion", "the solver's splitmix64 node shifts are not "
                             "replicated by this adapter (only undistorted meshes)")
    plasticity = material.get("plasticity")
    if plasticity and plasticity.get("rate"):
        law, _ = one_key(plasticity["rate"], "material.plasticity.rate")
        raise NotExpressible(f"material.plasticity.rate.{law}",
                             "ccx 2.20 has no rate-dependent flow stress for *PLASTIC "
                             "(only *CREEP or a user material)")
    if kind == "impactor":
        check_impactor(load_value, s["geometry"])
    if kind == "wall" and float(load_value.get("friction") or 0.0) != 0.0:
        raise NotExpressible("load.wall.friction",
                             "this adapter holds the foot on the wall by a boundary condition "
                             "(no contact pair), which slides freely: a frictionless wall only")
    end = time["end"]
    if isinstance(end, dict):
        raise NotExpressible("time.end.after_contact",
                             "a ccx step has a fixed length; it cannot end on a contact "
                             "condition")
    if s["geometry"] == "axisymmetric" and kind == "traction":
        raise NotExpressible("load.traction", "refused by impact in the axisymmetric geometry")


def check_impactor(impactor, geometry):
    """Refuse the impactor couplings this adapter cannot write: the nodal law, and the
    surface coupling's spherical nose (nose.py writes the plane-strain cylinder)."""
    contact = impactor.get("contact", "nodal")
    name, _ = one_key(contact, "load.impactor.contact")
    if name == "nodal":
        raise NotExpressible("load.impactor.contact: nodal",
                             "the paper's nodal contact law (eq. 4 at one node) is not a "
                             "ccx contact law")
    if geometry == "axisymmetric":
        raise NotExpressible("load.impactor.contact: surface",
                             "in the axisymmetric geometry (a spherical nose): this adapter "
                             "writes the plane-strain cylinder only")


def end_time(s):
    """The run's end time, s (a number: after_contact is refused)."""
    return float(s["time"]["end"])
