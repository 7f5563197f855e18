"""Write the contract's three files (adapters/README.md): history.csv, summary.json,
adapter.json, each to a temporary name first and renamed, so a failure leaves none of them."""

import json
import os

OUTPUTS = ("history.csv", "summary.json", "adapter.json")
# A problem's outputs (problem.py): the fields in place of the history and summary.
PROBLEM_OUTPUTS = ("fields.json", "adapter.json")


def summary(s, cols, rows, n_elements, dt):
    """summary.json's keys that the rows determine (impact's names, units and signs)."""
    force = [r["contact_force_N"] for r in rows]
    times = [r["time_s"] for r in rows]
    out = {"peak_contact_force_N": max(force),
           "max_plate_displacement_m": min(r["mid_uy_m"] for r in rows),
           "n_elements": n_elements}
    kind, load = s["load"]
    if kind in ("pulse", "traction"):
        # The rectangular load ccx applied: force times its duration (within the run).
        out["impulse_Ns"] = force[0] * min(float(load["duration"]), times[-1])
    else:
        out["impulse_Ns"] = sum((f0 + f1) * (t1 - t0) / 2 for f0, f1, t0, t1
                                in zip(force, force[1:], times, times[1:]))
    probes = sorted({c[:-len("_von_mises_Pa")] for c in cols if c.endswith("_von_mises_Pa")})
    if probes:
        out["max_von_mises_Pa"] = {p: max(r[f"{p}_von_mises_Pa"] for r in rows) for p in probes}
    if dt:
        out["dt_s"] = dt
    if kind == "impactor":
        out["contact_intervals_s"] = contact_intervals(times, force)
        out["contact_duration_s"] = out["contact_intervals_s"][-1][1] if out[
            "contact_intervals_s"] else 0.0
        out["final_impactor_velocity_mps"] = rows[-1]["impactor_velocity_mps"]
    if kind == "wall":
        last = rows[-1]
        # ccx's reaction holds the landing's stop: it is the one-step force; the bearing
        # force (impact's peak_force_N, ALGORITHM.md 5c) is not split out of it here.
        out["wall"] = {"peak_step_force_N": max(force), "final_length_m": last["bar_length_m"],
                       "length_ratio": last["bar_length_m"] / float(s["plate"]["thickness"]),
                       "foot_radius_m": last["foot_radius_m"],
                       "max_foot_radius_m": max(r["foot_radius_m"] for r in rows)}
    return out


def contact_intervals(times, force):
    """[start, end] pairs, s, as impact defines them (ALGORITHM.md 8): contact starts at the
    first row with a force > 0 after a zero, ends at the first later row with none; an
    interval still open at the last row ends there."""
    out, start = [], None
    for t, f in zip(times, force):
        if f > 0.0 and start is None:
            start = t
        elif f <= 0.0 and start is not None:
            out.append([start, t])
            start = None
    if start is not None:
        out.append([start, times[-1]])
    return out


def write_atomic(path, text):
    """Write text to path through path + '.part'."""
    with open(path + ".part", "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(path + ".part", path)


def history_text(cols, rows):
    """history.csv: the header, then one line per row (shortest exact float text)."""
    lines = [",".join(cols)]
    lines += [",".join(repr(float(r[c])) for c in cols) for r in rows]
    return "\n".join(lines) + "\n"


def write(out_dir, cols, rows, summary_dict, adapter_dict):
    """Write the three files into out_dir (none of them on an exception)."""
    write_all(out_dir, {"history.csv": history_text(cols, rows),
                        "summary.json": json.dumps(summary_dict, indent=2) + "\n",
                        "adapter.json": json.dumps(adapter_dict, indent=2) + "\n"})


def write_all(out_dir, texts):
    """Write each {name: text} into out_dir (none of them on an exception)."""
    try:
        for name, text in texts.items():
            write_atomic(os.path.join(out_dir, name), text)
    except BaseException:
        remove(out_dir)
        raise


def remove(out_dir):
    """Remove any output file (and its .part) from out_dir."""
    for name in OUTPUTS + PROBLEM_OUTPUTS:
        for p in (name, name + ".part"):
            try:
                os.remove(os.path.join(out_dir, p))
            except FileNotFoundError:
                pass
