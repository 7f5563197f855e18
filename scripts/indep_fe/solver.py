"""Explicit central-difference time loop (ALGORITHM.md sections 4, 6, 7, 8)."""
from __future__ import annotations

import csv
import json
import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .contact import make_law
from .elements import (critical_dt, elastic_matrix, formulation, global_operators, kinematics,
                       lumped_mass)
from .material import MaterialModel, lame, von_mises
from .mesh import build_mesh, find_element
from .scene import Scene

ENERGY_COLUMNS = ["plate_kinetic_J", "impactor_kinetic_J", "strain_energy_J", "plastic_work_J",
                  "hourglass_energy_J", "contact_energy_J", "external_work_J",
                  "energy_balance_error"]
PROBE_SUFFIXES = ["sxx_Pa", "syy_Pa", "sxy_Pa", "szz_Pa", "von_mises_Pa"]


IMPACT_COLUMNS = ["indentation_m", "impactor_displacement_m", "impactor_velocity_mps"]
# Blow-up guard (ALGORITHM.md section 7): imbalance above this multiple of the largest energy
# scale reached so far stops the run as unstable.
BLOW_UP_RATIO = 10.0


class UnstableRun(RuntimeError):
    pass


def history_columns(probe_names: list[str], impact: bool = True) -> list[str]:
    """ALGORITHM.md section 8. Pulse scenes omit the three impactor columns."""
    cols = ["time_s", "contact_force_N"] + (IMPACT_COLUMNS if impact else [])
    cols += ["top_uy_m", "mid_uy_m", "bottom_uy_m"]
    for p in probe_names:
        cols += [f"{p}_{s}" for s in PROBE_SUFFIXES]
    return cols + ENERGY_COLUMNS


def steps_for(t: float, dt: float) -> int:
    """First step n with n dt >= t (with the contract's 1e-9 slack)."""
    return max(0, math.ceil(t / dt - 1e-9))


@dataclass
class Result:
    columns: list[str]
    rows: list[list[float | None]]
    summary: dict
    extra: dict = field(default_factory=dict)

    def column(self, name: str) -> np.ndarray:
        j = self.columns.index(name)
        return np.array([np.nan if r[j] is None else r[j] for r in self.rows], float)


def _plan_dt(scene: Scene, dt_crit: float) -> float:
    ts = scene.time
    if ts.cfl is not None:
        return ts.cfl * dt_crit
    if ts.fixed_dt > dt_crit and not ts.allow_unstable_dt:
        raise ValueError(f"time.dt.fixed = {ts.fixed_dt:.6g} s exceeds the critical step "
                         f"{dt_crit:.6g} s (set time.allow_unstable_dt: true to force it)")
    return ts.fixed_dt


def simulate(scene: Scene, progress: bool = False) -> Result:
    wall0 = time.perf_counter()
    plate, mat, ms = scene.plate, scene.material, scene.mesh
    W = plate.width
    pm = build_mesh(plate, ms)
    kin = kinematics(pm)
    lam, mu = lame(mat.youngs_modulus, mat.poisson_ratio)
    form = formulation(ms.element, pm, kin, W, lam, mu, ms.hourglass)
    D = elastic_matrix(lam, mu)
    dt_crit = critical_dt(form, D, kin, mat.density, W)
    dt = _plan_dt(scene, dt_crit)

    Bg, G = global_operators(form, pm)
    BgT = Bg.T.tocsr()
    GT = G.T.tocsr() if G is not None else None
    ndof = 2 * pm.n_nodes
    m_dof = np.repeat(lumped_mass(pm, kin, mat.density, W), 2)
    free = np.ones(ndof, bool)
    free[pm.fixed_dofs] = False
    inv_m = np.where(free, 1.0 / m_dof, 0.0)
    s = pm.symmetry
    nel, ngp = form.B.shape[:2]
    w_flat = form.w.ravel()
    material = MaterialModel(mat, nel * ngp)

    # probes, sorted by name (column order): x > L/2 mirrored in the half model; nearest
    # integration point of the element containing the point
    probes = sorted(scene.output.probes, key=lambda p: p.name)
    probe_pts = []
    for pr in probes:
        x = plate.length - pr.x if (ms.model == "half" and pr.x > plate.length / 2) else pr.x
        e = find_element(pm, x, pr.y, plate.length)
        d2 = ((form.gp_xy[e] - np.array([x, pr.y])) ** 2).sum(axis=1)
        probe_pts.append(e * ngp + int(np.argmin(d2)))
    probe_names = [pr.name for pr in probes]

    imp, pulse = scene.impactor, scene.pulse
    node_of = {"mid-plane": pm.mid, "top-surface": pm.top}
    if imp is not None:
        law = make_law(imp, mat, W)
        datum = node_of[imp.indentation_datum]
        force_node = node_of[imp.force_node]
        m_s, v0 = imp.mass, imp.velocity
    else:
        law = None
        force_node = pm.top
    F_pulse = (lambda t: pulse.force if 0.0 <= t < pulse.duration else 0.0) if pulse else None

    ts = scene.time
    n_limit = steps_for(ts.limit, dt)
    n_end = steps_for(ts.end, dt) if ts.end is not None else None
    after = ts.after_contact
    every = scene.output.every      # None: a row every step

    columns = history_columns(probe_names, impact=imp is not None)
    rows: list[list] = []

    # state at t_n
    u = np.zeros(ndof)
    v_half = np.zeros(ndof)
    F = 0.0
    dS = 0.0
    vS = v0 if imp is not None else 0.0
    W_ext = 0.0
    plastic_work = 0.0
    E0 = None            # total energy at t_0
    scale = 0.0          # running max of max(|E(t_k)|, |W_ext(t_k)|, |E(0)|)
    max_imbalance = 0.0

    impulse = 0.0
    peak_F = 0.0
    max_down = 0.0
    max_vm = {p: 0.0 for p in probe_names}
    intervals: list[list] = []
    prev_load = 0.0
    t_sep = None         # first t_n with F_n = 0 after the last contact interval
    k_row = 1
    next_row = steps_for(k_row * every, dt) if every is not None else 1
    top_uy, mid_uy, bot_uy = 2 * pm.top + 1, 2 * pm.mid + 1, 2 * pm.bottom + 1
    fy = 2 * force_node + 1

    n = 0
    while True:
        t = n * dt
        load = F if imp is not None else F_pulse(t)

        # contact intervals and the stop rule (both depend on F_n only)
        if load > 0.0 and prev_load == 0.0:
            intervals.append([t, None])
        elif load == 0.0 and prev_load > 0.0:
            intervals[-1][1] = t
        if load > 0.0:
            t_sep = None
        elif prev_load > 0.0:
            t_sep = t
        prev_load = load
        if n_end is not None:
            last = n >= n_end
            stop_reason = "end_time"
        else:   # end: {after_contact: T}: first t_n with t_n - t_sep >= T; time.limit hard stop
            last = n >= n_limit
            stop_reason = "time_limit"
            if not last and t_sep is not None and t - t_sep >= after - 1e-9 * dt:
                last, stop_reason = True, "after_contact"

        # 1. internal forces at u_n (material update, once per step)
        eps = (Bg @ u).reshape(-1, 4)
        stress, strain_energy, dwork = material.update(eps, w_flat)
        plastic_work += dwork
        f_int = BgT @ (w_flat[:, None] * stress).ravel()
        hg_energy = 0.0
        if G is not None:
            q = (G @ u).reshape(-1, 2)
            f_int += GT @ (form.k_hg[:, None] * q).ravel()
            hg_energy = 0.5 * float(np.sum(form.k_hg * (q[:, 0] ** 2 + q[:, 1] ** 2)))

        # 2. external force
        f_ext = np.zeros(ndof)
        f_ext[fy] = -load / s

        # 3. central difference
        a = (f_ext - f_int) * inv_m
        v_new = v_half + dt * a if n > 0 else 0.5 * dt * a
        u_new = u + dt * v_new

        # 4. energies at t_n
        v_n = 0.5 * (v_half + v_new) if n > 0 else np.zeros(ndof)
        e_kin = s * 0.5 * float(np.dot(m_dof, v_n * v_n))
        e_imp = 0.5 * m_s * vS * vS if imp is not None else 0.0
        e_con = law.energy(F) if imp is not None else 0.0
        total = e_kin + e_imp + s * strain_energy + s * plastic_work + s * hg_energy + e_con
        if E0 is None:
            E0 = total
        scale = max(scale, abs(total), abs(W_ext), abs(E0))
        imbalance = abs(total - E0 - W_ext)
        max_imbalance = max(max_imbalance, imbalance)
        running = imbalance / scale if scale > 0 else 0.0
        if not (math.isfinite(running) and running <= BLOW_UP_RATIO):
            raise UnstableRun(f"unstable at step {n} (t = {t:.6e} s): energy imbalance "
                              f"{imbalance:.6e} J against an energy scale {scale:.6e} J "
                              f"(dt = {dt:.6e} s = {dt / dt_crit:.3f} dt_crit)")

        peak_F = max(peak_F, load)
        max_down = min(max_down, u[mid_uy])
        vm = von_mises(stress[probe_pts]) if probe_pts else np.zeros(0)
        for name, val in zip(probe_names, vm):
            max_vm[name] = max(max_vm[name], float(val))

        if n == 0 or n >= next_row or last:
            row = [t, load]
            if imp is not None:
                d_c = -u[2 * datum + 1]
                row += [dS - d_c, dS, vS]
            row += [u[top_uy], u[mid_uy], u[bot_uy]]
            for pi, p in enumerate(probe_pts):
                sx = stress[p]
                row += [sx[0], sx[1], sx[3], sx[2], float(vm[pi])]
            # the last entry holds the imbalance (J) until the run's energy scale is known
            row += [e_kin, e_imp, s * strain_energy, s * plastic_work, s * hg_energy, e_con,
                    W_ext, imbalance]
            rows.append(row)
            while next_row <= n:
                k_row += 1
                next_row = steps_for(k_row * every, dt) if every is not None else n + 1
        if progress and n % 2000 == 0:
            print(f"  step {n} t = {t:.4e} s F = {load:.4e} N", file=sys.stderr)
        if last:
            break

        # external work of the pulse over [t_n, t_n+1]
        if pulse is not None:
            W_ext += 0.5 * (F_pulse(t) + F_pulse((n + 1) * dt)) * (-u_new[top_uy] + u[top_uy])
            impulse += 0.5 * (F_pulse(t) + F_pulse((n + 1) * dt)) * dt

        # 5. contact (eq. 21, then eqs. 19-20)
        if imp is not None:
            d_c = -u_new[2 * datum + 1]
            alpha_free = dS + vS * dt - F * dt * dt / (3 * m_s) - d_c
            if alpha_free <= 0.0:
                F_new = 0.0
            else:
                F_new = law.solve(alpha_free, dt * dt / (6 * m_s), guess=F if F > 0 else None)
            impulse += 0.5 * (F + F_new) * dt
            vS, dS = (vS - (F + F_new) * dt / (2 * m_s),
                      dS + vS * dt - (2 * F + F_new) * dt * dt / (6 * m_s))
            F = F_new

        u, v_half = u_new, v_new
        n += 1

    # contact still open at the end of the run: closed at the final time
    if intervals and intervals[-1][1] is None:
        intervals[-1][1] = n * dt
    # balance error: imbalance over the largest energy scale of the WHOLE run (section 7)
    ratio = (lambda x: x / scale) if scale > 0 else (lambda x: 0.0)
    for row in rows:
        row[-1] = ratio(row[-1])

    summary = {
        "solver": "indep_fe (Python reference, scripts/indep_fe)",
        "impulse_Ns": impulse,
        "peak_contact_force_N": peak_F,
        "max_plate_displacement_m": max_down,
        "contact_intervals_s": intervals,
        "contact_duration_s": intervals[-1][1] if intervals else 0.0,
        "final_impactor_velocity_mps": vS if imp is not None else None,
        "impactor_momentum_change_Ns": m_s * (v0 - vS) if imp is not None else None,
        "impulse_momentum_error": (abs(impulse - m_s * (v0 - vS)) / (m_s * v0)
                                   if imp is not None else None),
        "max_von_mises_Pa": max_vm,
        "max_energy_balance_error": ratio(max_imbalance),
        "dt_s": dt,
        "dt_critical_s": dt_crit,
        "n_steps": n,
        "end_time_s": n * dt,
        "final_time_s": n * dt,
        "stop_reason": stop_reason,
        "cfl": dt / dt_crit,
        "n_elements": pm.n_elements,
        "n_nodes": pm.n_nodes,
        "element": ms.element,
        "model": ms.model,
        "contact_law": law.description if law is not None else None,
        "final_plastic_work_J": s * plastic_work,
        "wall_time_s": time.perf_counter() - wall0,
    }
    return Result(columns, rows, summary)


def write_outputs(res: Result, out_dir: str | Path) -> None:
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    with open(out / "history.csv", "w", newline="") as fh:
        wr = csv.writer(fh)
        wr.writerow(res.columns)
        for r in res.rows:
            wr.writerow(["" if x is None else f"{x:.17g}" for x in r])
    with open(out / "summary.json", "w") as fh:
        json.dump(res.summary, fh, indent=2)
        fh.write("\n")
