"""Explicit central-difference time loop (ALGORITHM.md sections 4, 6, 7, 8)."""
from __future__ import annotations

import csv
import dataclasses
import json
import math
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .contact import make_law
from .axisymmetric import Ring, ring_eigenvalues, ring_formulation, ring_node_masses
from .elements import (elastic_matrix, element_eigenvalues, formulation, global_operators,
                       kinematics, lumped_mass)
from .finite import CHECK_EVERY, FiniteKinematics, inverted_element
from .finite_ring import FiniteRing
from .material import MaterialModel, lame, von_mises
from .mesh import build_mesh, find_element
from .scene import Scene
from .step import StepPlan, cut, reached, summary_keys, velocity_step
from .surface import SurfaceNose
from .wall import RigidWall

ENERGY_COLUMNS = ["plate_kinetic_J", "impactor_kinetic_J", "strain_energy_J", "plastic_work_J",
                  "hourglass_energy_J", "contact_energy_J", "external_work_J",
                  "energy_balance_error"]
PROBE_SUFFIXES = ["sxx_Pa", "syy_Pa", "sxy_Pa", "szz_Pa", "von_mises_Pa"]
RATE_SUFFIX = "plastic_strain_rate_1_s"     # with a rate law (section 3b)
TEMPERATURE_SUFFIX = "temperature_K"         # with its thermal part


IMPACT_COLUMNS = ["indentation_m", "impactor_displacement_m", "impactor_velocity_mps"]
SURFACE_COLUMNS = ["contact_half_width_m", "nodes_in_contact"]
WALL_COLUMNS = ["foot_radius_m", "bar_length_m", "contact_radius_m", "bearing_force_N",
                "undeformed_length_m"]
# Blow-up guard (ALGORITHM.md section 7): imbalance above this multiple of the largest energy
# scale reached so far stops the run as unstable; for energy-consistent scenes (force node =
# datum node, a pulse, the surface coupling) 0.1 of it does, from step 100 on.
BLOW_UP_RATIO = 10.0
CONSISTENT_RATIO = 0.1
CONSISTENT_FROM_STEP = 100


class UnstableRun(RuntimeError):
    pass


def history_columns(probe_names: list[str], impact: bool = True, surface: bool = False,
                    rate: bool = False, thermal: bool = False, wall: bool = False,
                    every_step: bool = False) -> list[str]:
    """ALGORITHM.md section 8. Pulse scenes omit the three impactor columns; the surface
    coupling adds its two after them; a rate law adds each probe's plastic strain rate after
    its von Mises stress, and `thermal` its temperature after that (section 3b); the wall its
    two after the surface coupling's place (section 5c); a step re-estimated at every step its
    `dt_s` (the step from t_n, s) right after `time_s` (section 6b)."""
    cols = ["time_s"] + (["dt_s"] if every_step else []) + ["contact_force_N"] + (IMPACT_COLUMNS if impact else [])
    cols += SURFACE_COLUMNS if surface else []
    cols += WALL_COLUMNS if wall else []
    cols += ["top_uy_m", "mid_uy_m", "bottom_uy_m"]
    for p in probe_names:
        cols += [f"{p}_{s}" for s in PROBE_SUFFIXES]
        cols += [f"{p}_{RATE_SUFFIX}"] if rate else []
        cols += [f"{p}_{TEMPERATURE_SUFFIX}"] if thermal else []
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


@dataclass
class _Plate:
    """The discretised plate: mesh, element operators, masses (fixed during the run)."""
    pm: object
    form: object
    Bg: object
    BgT: object
    G: object
    GT: object
    m_dof: np.ndarray
    inv_m: np.ndarray
    s: float
    w_flat: np.ndarray
    ngp: int
    dt_plate: float                       # the plate's critical step (section 4)
    nose: SurfaceNose | None = None       # the surface coupling (section 5b)
    finite: FiniteKinematics | FiniteRing | None = None  # kinematics: finite (3c, 3e)


def _discretise(scene: Scene) -> tuple[_Plate, MaterialModel, float, float]:
    """The plate's operators (sections 1-2), its material, the time step and the critical one."""
    plate, mat, ms = scene.plate, scene.material, scene.mesh
    W = plate.width
    pm = build_mesh(plate, ms)
    kin = kinematics(pm)
    lam, mu = lame(mat.youngs_modulus, mat.poisson_ratio)
    D = elastic_matrix(lam, mu)
    if scene.geometry == "axisymmetric":
        # section 3d: the whole ring, symmetry factor 1, plate.width unused
        pm = dataclasses.replace(pm, symmetry=1.0)
        ring = Ring(pm, kin)
        form = ring_formulation(ms.element, pm, kin, ring, lam, mu, ms.hourglass)
        m_e = ring.node_masses(mat.density)
        lam_e = ring_eigenvalues(form, D, m_e)
        m_node = ring_node_masses(pm, m_e)
    else:
        ring = None
        form = formulation(ms.element, pm, kin, W, lam, mu, ms.hourglass)
        lam_e = element_eigenvalues(form, D, kin, mat.density, W)
        m_node = lumped_mass(pm, kin, mat.density, W)
    dt_plate = 2.0 / np.sqrt(lam_e.max())
    ndof = 2 * pm.n_nodes
    m_dof = np.repeat(m_node, 2)
    free = np.ones(ndof, bool)
    free[pm.fixed_dofs] = False
    inv_m = np.where(free, 1.0 / m_dof, 0.0)
    nose = None
    dt_crit = dt_plate
    imp = scene.impactor
    if imp is not None and imp.coupling == "surface":
        # section 5b: the penalty springs shorten the stable step (kinematic: the plate's)
        nose = SurfaceNose.build(pm, plate.length, plate.thickness, imp.nose_radius,
                                 imp.enforcement, imp.penalty_scale, imp.mass, imp.velocity,
                                 m_node, inv_m, lam_e)
        dt_crit = nose.stable_step(dt_plate)
    dt = _plan_dt(scene, dt_crit)

    Bg, G = global_operators(form, pm)
    nel, ngp = form.B.shape[:2]
    finite = None
    if scene.kinematics == "finite":
        # section 3c in the plane, section 3e in the ring
        finite = (FiniteRing(ms.element, pm, kin, ring) if scene.geometry == "axisymmetric"
                  else FiniteKinematics(ms.element, pm, kin, W))
    pl = _Plate(pm=pm, form=form, Bg=Bg, BgT=Bg.T.tocsr(), G=G,
                GT=G.T.tocsr() if G is not None else None, m_dof=m_dof,
                inv_m=inv_m, s=pm.symmetry, w_flat=form.w.ravel(),
                ngp=ngp, dt_plate=dt_plate, nose=nose, finite=finite)
    return pl, MaterialModel(mat, nel * ngp, dt), dt, dt_crit


def _probes(scene: Scene, pl: _Plate) -> tuple[list[str], list[int]]:
    """Probes, sorted by name (column order): x > L/2 mirrored in the half model; the nearest
    integration point (flat index) of the element containing the point."""
    plate = scene.plate
    probes = sorted(scene.output.probes, key=lambda p: p.name)
    probe_pts = []
    for pr in probes:
        x = plate.length - pr.x if (scene.mesh.model == "half" and pr.x > plate.length / 2) else pr.x
        e = find_element(pl.pm, x, pr.y, plate.length)
        d2 = ((pl.form.gp_xy[e] - np.array([x, pr.y])) ** 2).sum(axis=1)
        probe_pts.append(e * pl.ngp + int(np.argmin(d2)))
    return [pr.name for pr in probes], probe_pts


@dataclass
class _Impactor:
    """The rigid impactor and its contact law (eqs. 19-21); state at t_n."""
    law: object
    datum: int
    m_s: float
    v0: float
    F: float = 0.0     # contact force F_n, N
    dS: float = 0.0    # displacement delta_S, m
    vS: float = 0.0    # velocity, m/s

    def step(self, u_new: np.ndarray, dt: float) -> float:
        """Section 6 step 5: F_{n+1} from eq. (21), then eqs. (19)-(20); returns the impulse
        increment (F_n + F_{n+1}) dt / 2."""
        F, m_s = self.F, self.m_s
        d_c = -u_new[2 * self.datum + 1]
        alpha_free = self.dS + self.vS * dt - F * dt * dt / (3 * m_s) - d_c
        if alpha_free <= 0.0:
            F_new = 0.0
        else:
            F_new = self.law.solve(alpha_free, dt * dt / (6 * m_s), guess=F if F > 0 else None)
        di = 0.5 * (F + F_new) * dt
        self.vS, self.dS = (self.vS - (F + F_new) * dt / (2 * m_s),
                            self.dS + self.vS * dt - (2 * F + F_new) * dt * dt / (6 * m_s))
        self.F = F_new
        return di


def _impactor(scene: Scene, pl: _Plate) -> tuple[_Impactor | SurfaceNose | None, int]:
    """The impactor (None for a pulse; the SurfaceNose under the surface coupling) and the node
    whose u_y the force acts on (nodal coupling, pulse)."""
    imp = scene.impactor
    node_of = {"mid-plane": pl.pm.mid, "top-surface": pl.pm.top}
    if imp is None:
        return None, pl.pm.top
    if imp.coupling == "surface":
        return pl.nose, pl.pm.top
    body = _Impactor(law=make_law(imp, scene.material, scene.plate.width),
                     datum=node_of[imp.indentation_datum], m_s=imp.mass, v0=imp.velocity,
                     vS=imp.velocity)
    return body, node_of[imp.force_node]


@dataclass
class _Contact:
    """Contact intervals and the stop rule (section 8), both from F_n only."""
    n_end: int | None
    n_limit: int
    after: float | None
    intervals: list = field(default_factory=list)
    prev_load: float = 0.0
    t_sep: float | None = None   # first t_n with F_n = 0 after the last contact interval
    timed: tuple | None = None   # section 6b: (end or None, limit) in s, reached by t_n

    def step(self, n: int, t: float, dt: float, load: float) -> tuple[bool, str]:
        """Records F_n at t_n; returns whether the run stops after this step, and why."""
        if load > 0.0 and self.prev_load == 0.0:
            self.intervals.append([t, None])
        elif load == 0.0 and self.prev_load > 0.0:
            self.intervals[-1][1] = t
        if load > 0.0:
            self.t_sep = None
        elif self.prev_load > 0.0:
            self.t_sep = t
        self.prev_load = load
        if self.timed is not None:
            end, limit = self.timed
            if end is not None:
                return reached(t, end, dt), "end_time"
            if reached(t, limit, dt):
                return True, "time_limit"
        elif self.n_end is not None:
            return n >= self.n_end, "end_time"
        # end: {after_contact: T}: first t_n with t_n - t_sep >= T; time.limit hard stop
        elif n >= self.n_limit:
            return True, "time_limit"
        if self.t_sep is not None and t - self.t_sep >= self.after - 1e-9 * dt:
            return True, "after_contact"
        return False, "time_limit"


@dataclass
class _Balance:
    """The energy balance (section 7): imbalance |E - E(0) - W_ext| and its scale."""
    E0: float | None = None   # total energy at t_0
    scale: float = 0.0        # running max of max(|E(t_k)|, |W_ext(t_k)|, |E(0)|)
    max_imbalance: float = 0.0
    consistent: bool = False  # energy-consistent scene (section 7): the 0.1 bound applies

    def record(self, n: int, t: float, total: float, W_ext: float, dt: float,
               dt_crit: float) -> float:
        """The imbalance at t_n (J); UnstableRun beyond the blow-up guard (or, energy-consistent
        scenes from step 100 on, beyond 0.1 of the scale)."""
        if self.E0 is None:
            self.E0 = total
        self.scale = max(self.scale, abs(total), abs(W_ext), abs(self.E0))
        imbalance = abs(total - self.E0 - W_ext)
        self.max_imbalance = max(self.max_imbalance, imbalance)
        running = imbalance / self.scale if self.scale > 0 else 0.0
        bound = (CONSISTENT_RATIO if self.consistent and n >= CONSISTENT_FROM_STEP
                 else BLOW_UP_RATIO)
        if not (math.isfinite(running) and running <= bound):
            raise UnstableRun(f"unstable at step {n} (t = {t:.6e} s): energy imbalance "
                              f"{imbalance:.6e} J above {bound:g} x the energy scale "
                              f"{self.scale:.6e} J "
                              f"(dt = {dt:.6e} s = {dt / dt_crit:.3f} dt_crit)")
        return imbalance

    def ratio(self, x: float) -> float:
        """An imbalance over the largest energy scale of the WHOLE run."""
        return x / self.scale if self.scale > 0 else 0.0


def _internal_forces(pl: _Plate, material: MaterialModel, u: np.ndarray):
    """Step 1: stresses and internal forces at u_n (material update, once per step); returns
    (stress, strain energy, plastic work increment, f_int, hourglass energy). Under finite
    kinematics (section 3c) the stress is the Cauchy stress and the hourglass term is added
    unchanged on the total displacements."""
    if pl.finite is not None:
        stress, strain_energy, dwork, f_int = pl.finite.update(u, material)
    else:
        eps = (pl.Bg @ u).reshape(-1, 4)
        stress, strain_energy, dwork = material.update(eps, pl.w_flat)
        f_int = pl.BgT @ (pl.w_flat[:, None] * stress).ravel()
    hg_energy = 0.0
    if pl.G is not None:
        q = (pl.G @ u).reshape(-1, 2)
        f_int += pl.GT @ (pl.form.k_hg[:, None] * q).ravel()
        hg_energy = 0.5 * float(np.sum(pl.form.k_hg * (q[:, 0] ** 2 + q[:, 1] ** 2)))
    return stress, strain_energy, dwork, f_int, hg_energy


def _check_mesh(pl: _Plate, u: np.ndarray, n: int, t: float, dt: float,
                allow_unstable_dt: bool) -> None:
    """Every 32 steps and at the last (sections 7, 3c): an inverted element stops the run; under
    finite kinematics so does a step above the deformed mesh's estimate
    dt_plate min_e sqrt(S_ref / S_cur) (unless time.allow_unstable_dt)."""
    e = inverted_element(pl.pm, u)
    if e is not None:
        raise UnstableRun(f"element {e} inverted at step {n} (t = {t:.6e} s)")
    if pl.finite is not None and not allow_unstable_dt:
        factor, e = pl.finite.step_factor(u)
        if dt > pl.dt_plate * factor:
            raise UnstableRun(f"at step {n} (t = {t:.6e} s) the deformed mesh's stable step "
                              f"{pl.dt_plate * factor:.6e} s (element {e}) is below dt = "
                              f"{dt:.6e} s")


def _summary(scene: Scene, pl: _Plate, material: MaterialModel,
             body: _Impactor | SurfaceNose | None,
             contact: _Contact, balance: _Balance, totals: dict, n: int, dt: float,
             dt_crit: float, stop_reason: str, t_end: float, h_last: float) -> dict:
    """summary.json (section 8); dt the first step, t_end the final time, h_last the last
    velocity step (s)."""
    intervals = contact.intervals
    impulse = totals["impulse"]
    surface = isinstance(body, SurfaceNose)
    law = body if surface else (body.law if body is not None else None)
    v_final = (body.velocity(h_last) if surface else body.vS) if body is not None else None
    out = {
        "solver": "indep_fe (Python reference, scripts/indep_fe)",
        "impulse_Ns": impulse,
        "peak_contact_force_N": totals["peak_F"],
        "max_plate_displacement_m": totals["max_down"],
        "contact_intervals_s": intervals,
        "contact_duration_s": intervals[-1][1] if intervals else 0.0,
        "final_impactor_velocity_mps": v_final,
        "impactor_momentum_change_Ns": body.m_s * (body.v0 - v_final) if body is not None else None,
        "impulse_momentum_error": (abs(impulse - body.m_s * (body.v0 - v_final)) / (body.m_s * body.v0)
                                   if body is not None else None),
        "max_von_mises_Pa": totals["max_vm"],
        "max_energy_balance_error": balance.ratio(balance.max_imbalance),
        "dt_s": dt,
        "dt_critical_s": dt_crit,
        "n_steps": n,
        "end_time_s": t_end,
        "final_time_s": t_end,
        "stop_reason": stop_reason,
        "cfl": dt / dt_crit,
        "n_elements": pl.pm.n_elements,
        "n_nodes": pl.pm.n_nodes,
        "element": scene.mesh.element,
        **({"kinematics": "finite"} if pl.finite is not None else {}),
        **({"geometry": "axisymmetric"} if scene.geometry == "axisymmetric" else {}),
        "model": scene.mesh.model,
        "contact_law": law.description if law is not None else None,
        "final_plastic_work_J": pl.s * totals["plastic_work"],
        "wall_time_s": time.perf_counter() - totals["wall0"],
    }
    rate = material.rate
    if rate is not None:
        # section 8: per probe, over all steps; with thermal the hottest point at the end and
        # the heat beta W_p (beta times the final plastic work)
        out["max_plastic_strain_rate_1_s"] = totals["max_rate"]
        if rate.thermal is not None:
            out["max_temperature_K"] = float(rate.temperature().max())
            out["heat_J"] = rate.thermal.taylor_quinney * pl.s * totals["plastic_work"]
    if surface:
        out["contact_step_factor"] = dt_crit / pl.dt_plate
        out["max_contact_half_width_m"] = totals["max_half_width"]
        out["max_nodes_in_contact"] = totals["max_nodes"]
    return out


def simulate(scene: Scene, progress: bool = False) -> Result:
    """Runs a scene: the time loop of section 6, recording rows and totals (section 8)."""
    wall0 = time.perf_counter()
    pl, material, dt, dt_crit = _discretise(scene)
    probe_names, probe_pts = _probes(scene, pl)
    body, force_node = _impactor(scene, pl)
    pulse = scene.pulse
    F_pulse = (lambda t: pulse.force if 0.0 <= t < pulse.duration else 0.0) if pulse else None
    ts = scene.time
    plan = (StepPlan(ts.cfl, pl.dt_plate, pl.finite, pl.nose if pl.nose is not None
                     and not pl.nose.kinematic else None)
            if ts.update == "every-step" else None)   # section 6b
    contact = _Contact(n_end=steps_for(ts.end, dt) if ts.end is not None else None,
                       n_limit=steps_for(ts.limit, dt), after=ts.after_contact,
                       timed=(ts.end, ts.limit) if plan is not None else None)
    target = ts.end if ts.end is not None else ts.limit   # the end a re-estimated step lands on
    imp = scene.impactor
    # section 7: energy-consistent scenes (force node = datum node, a pulse; section 5b: the
    # surface coupling)
    balance = _Balance(consistent=imp is None or imp.coupling == "surface"
                       or imp.force_node == imp.indentation_datum)
    every = scene.output.every      # None: a row every step
    surface = isinstance(body, SurfaceNose)
    rate = material.rate
    thermal = rate is not None and rate.thermal is not None
    columns = history_columns(probe_names, impact=body is not None, surface=surface,
                              rate=rate is not None, thermal=thermal, wall=scene.wall is not None,
                              every_step=plan is not None)
    rows: list[list] = []
    s, ndof, pm = pl.s, 2 * pl.pm.n_nodes, pl.pm
    u, v_half = np.zeros(ndof), np.zeros(ndof)   # u_n, v_{n-1/2} (v_0 at n = 0)
    wall = None
    if scene.wall is not None:      # section 5c
        wall = RigidWall(pm.coords, pl.inv_m, pl.m_dof[0::2], s, scene.plate.thickness,
                         pm.top, pm.bottom)
        v_half = wall.launch(scene.wall.velocity)
    F_last = 0.0
    W_ext = 0.0
    totals = {"impulse": 0.0, "peak_F": 0.0, "max_down": 0.0, "plastic_work": 0.0,
              "max_vm": {p: 0.0 for p in probe_names}, "wall0": wall0,
              "max_rate": {p: 0.0 for p in probe_names},
              "max_half_width": 0.0, "max_nodes": 0.0}
    k_row = 1
    next_row = steps_for(k_row * every, dt) if every is not None else 1
    top_uy, mid_uy, bot_uy = 2 * pm.top + 1, 2 * pm.mid + 1, 2 * pm.bottom + 1
    fy = 2 * force_node + 1

    kinematic = surface and body.kinematic
    n, t, dt_prev = 0, 0.0, None     # dt_prev: dt_{n-1/2} (section 6b), None at n = 0
    while True:
        if plan is None:
            t = n * dt
            dt_est = dt
        else:
            # section 6b: dt_{n+1/2} on u_n; the rates over the step the increment was made on
            dt_est = plan.estimate(u, n)
            if rate is not None:
                rate.dt = dt_est if dt_prev is None else dt_prev
        # 1. internal forces at u_n
        stress, strain_energy, dwork, f_int, hg_energy = _internal_forces(pl, material, u)
        totals["plastic_work"] += dwork
        plastic_work = totals["plastic_work"]
        # the step from t_n (section 6b: cut to land on the end, uncut at the last step) and the
        # velocity step h_n
        if plan is None:
            dt_step, h = dt, (0.5 * dt if n == 0 else dt)
            dt_back = dt
        else:
            at_end = reached(t, target, dt_est)
            dt_step = dt_est if at_end else cut(t, target, dt_est)
            h, dt_back = velocity_step(dt_prev, dt_step), dt_prev
        if kinematic:
            # section 5b: the kinematic enforcement solves f_n, F_n here, from f_int(u_n); the
            # impulse's trapezoid (F_n-1 + F_n) dt / 2 is counted once F_n is known
            totals["impulse"] += body.solve(u, v_half, f_int, dt_step, first=n == 0, h=h,
                                            dt_prev=dt_back)
        if wall is not None:
            load = wall.solve(u, v_half, f_int, dt_step, first=n == 0, h=h)
            totals["impulse"] += 0.5 * (F_last + load) * dt_back if n > 0 else 0.0
            F_last = load
        else:
            load = body.F if body is not None else F_pulse(t)
        last, stop_reason = contact.step(n, t, dt_est, load)
        if plan is not None and dt_step == dt_est:
            # section 6b: every estimate used uncut, the last step's (its velocity step) too;
            # the step cut to land on the end not counted (reading checked against the Rust:
            # leaving the last step's estimate out gives dt_min_s 2.6e-3 off on
            # axisym-wall-taylor-every-step, where the step falls to the end)
            plan.taken.append(dt_est)

        # 2. external force; 3. central difference
        f_ext = np.zeros(ndof)
        if surface:
            body.apply(f_ext)           # the nose's f_i at t_n (section 5b)
        elif wall is not None:
            wall.apply(f_ext)           # the wall's R_i at t_n (section 5c)
        else:
            f_ext[fy] = -load / s
        a = (f_ext - f_int) * pl.inv_m
        v_new = v_half + h * a
        u_new = u + dt_step * v_new

        # 4. energies at t_n
        v_n = 0.5 * (v_half + v_new) if n > 0 else v_half
        e_kin = s * 0.5 * float(np.dot(pl.m_dof, v_n * v_n))
        if surface:
            v_S = body.velocity(h)
            e_imp = 0.5 * body.m_s * v_S * v_S
            e_con = body.energy
            totals["max_half_width"] = max(totals["max_half_width"], body.half_width)
            totals["max_nodes"] = max(totals["max_nodes"], body.n_contact)
        else:
            e_imp = 0.5 * body.m_s * body.vS * body.vS if body is not None else 0.0
            e_con = body.law.energy(body.F) if body is not None else 0.0
        if wall is not None:
            e_con = wall.energy
            wall_row = wall.reading(u)
        total = e_kin + e_imp + s * strain_energy + s * plastic_work + s * hg_energy + e_con
        imbalance = balance.record(n, t, total, W_ext, dt_step, dt_crit)
        if n % CHECK_EVERY == 0 or last:
            # section 6b: the re-estimated step needs no deformed-step check (it is that estimate)
            _check_mesh(pl, u, n, t, dt, scene.time.allow_unstable_dt or plan is not None)

        totals["peak_F"] = max(totals["peak_F"], load)
        totals["max_down"] = min(totals["max_down"], u[mid_uy])
        vm = von_mises(stress[probe_pts]) if probe_pts else np.zeros(0)
        for name, val in zip(probe_names, vm):
            totals["max_vm"][name] = max(totals["max_vm"][name], float(val))
        if rate is not None:
            for name, p in zip(probe_names, probe_pts):
                totals["max_rate"][name] = max(totals["max_rate"][name], float(rate.kdot[p]))

        due = (n >= next_row if plan is None
               else every is None or reached(t, k_row * every, dt_est))
        if n == 0 or due or last:
            row = [t] + ([dt_step] if plan is not None else []) + [load]
            if surface:
                row += [body.dS + u[top_uy], body.dS, v_S, body.half_width, body.n_contact]
            elif body is not None:
                d_c = -u[2 * body.datum + 1]
                row += [body.dS - d_c, body.dS, body.vS]
            if wall is not None:
                row += list(wall_row)
            row += [u[top_uy], u[mid_uy], u[bot_uy]]
            for pi, p in enumerate(probe_pts):
                sx = stress[p]
                row += [sx[0], sx[1], sx[3], sx[2], float(vm[pi])]
                if rate is not None:
                    row += [float(rate.kdot[p])]
                if thermal:
                    row += [float(rate.temperature()[p])]
            # the last entry holds the imbalance (J) until the run's energy scale is known
            row += [e_kin, e_imp, s * strain_energy, s * plastic_work, s * hg_energy, e_con,
                    W_ext, imbalance]
            rows.append(row)
            while plan is None and next_row <= n:
                k_row += 1
                next_row = steps_for(k_row * every, dt) if every is not None else n + 1
            while plan is not None and every is not None and reached(t, k_row * every, dt_est):
                k_row += 1
        if progress and n % 2000 == 0:
            print(f"  step {n} t = {t:.4e} s F = {load:.4e} N", file=sys.stderr)
        if last:
            break

        # external work of the pulse over [t_n, t_n+1]
        t_next = (n + 1) * dt if plan is None else t + dt_step
        if pulse is not None:
            W_ext += 0.5 * (F_pulse(t) + F_pulse(t_next)) * (-u_new[top_uy] + u[top_uy])
            totals["impulse"] += 0.5 * (F_pulse(t) + F_pulse(t_next)) * dt_step
        # 5. contact (surface: section 5b; nodal: eq. 21, then eqs. 19-20)
        if surface:
            totals["impulse"] += body.step(u_new, dt_step, h if plan is not None else None)
        elif body is not None:
            totals["impulse"] += body.step(u_new, dt_step)
        u, v_half = u_new, v_new
        n, t, dt_prev = n + 1, t_next, dt_step

    # contact still open at the end of the run: closed at the final time
    if contact.intervals and contact.intervals[-1][1] is None:
        contact.intervals[-1][1] = t
    for row in rows:
        row[-1] = balance.ratio(row[-1])
    summary = _summary(scene, pl, material, body, contact, balance, totals, n, dt, dt_crit,
                       stop_reason, t, h)
    if plan is not None:
        summary.update(summary_keys(plan))
    if wall is not None:
        ivs = contact.intervals
        release = ivs[-1][1] if ivs and load == 0.0 else None
        eqps = float(np.max(material.k)) if scene.material.plasticity is not None else None
        summary["wall"] = wall.summary(v_new, totals["peak_F"], release, wall_row,
                                       scene.plate, eqps)
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
