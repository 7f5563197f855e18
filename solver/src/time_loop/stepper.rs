//! The state of the plate and the impactor between steps, and the steps of `ALGORITHM.md`
//! section 6 that advance it ([`Stepper`]): the forces on the plate, the half step of the
//! velocities and the energies, the guards (energy balance, inverted elements, the deformed
//! mesh's stable step), what the recorder samples, and the contact force at the next step.

use std::result::Result as StdResult;

use crate::input::error::{Error, Result};
use crate::input::scene::{ElementKind, Impactor, Kinematics, Scene};
use crate::lanes::simd::dispatch;
use crate::mesh::PlateMesh;
use crate::physics::contacts::contact::{solve_contact_force, BeyondMaximum, LineContactLaw};
use crate::physics::contacts::rigid_wall::{RigidWall, WallReading, WallTotals};
use crate::physics::elements::element::{ElementEnergy, Formulation};
use crate::physics::impactor::RigidImpactor;
use crate::physics::load::PrescribedLoad;
use crate::physics::materials::material::ConstitutiveModel;
use crate::time_loop::energy::{BalanceMonitor, Energies};
use crate::time_loop::history::{Probe, ProbeReading, Sample};
use crate::time_loop::nodal_update::{Displace, VelocityUpdate};
use crate::time_loop::plate_model::PlateModel;
use crate::time_loop::stable_step;
use crate::time_loop::step_size::{self, EveryStep};
use crate::time_loop::surface_coupling::SurfaceImpact;

/// Energy error beyond which any run is stopped as unstable: total energy more than this
/// multiple of the largest energy the run was given.
pub const BLOW_UP_BALANCE_ERROR: f64 = 10.0;

/// Tighter bound for energy-consistent scenes (force on the node the indentation is read
/// from, or a pulse): their balance is an identity up to O(dt^2) and stays below 1e-2 in
/// every stable run seen (`impact-bench stability`), so 10 % means the run has gone wrong
/// (e.g. an instability that plastic flow absorbs). The paper's literal force-node reading
/// does not balance by design (27 % seen elastically) and keeps only the bound above.
pub const BLOW_UP_BALANCE_ERROR_CONSISTENT: f64 = 0.1;

/// Steps before the tighter bound applies: the first steps of a suddenly applied pulse carry
/// an O(dt) imbalance against a still tiny energy scale.
pub const CONSISTENT_GUARD_AFTER_STEPS: u64 = 100;

/// Why the energies left double precision (inf or NaN): the inputs beyond any physical
/// magnitude when the scene has some (no time step can make those arithmetic finite), else
/// the numbers grew without bound (an instability past the guard's bound within one step).
fn overflow_cause(scene: &Scene, total: f64, initial: f64) -> String {
    let extreme = crate::input::estimate::measures::extreme_inputs(scene);
    if extreme.is_empty() {
        format!(
            "the arithmetic overflowed: total energy {total:.6e} J (from {initial:.6e} J); the solution grew without bound within a step: lower time.dt, or check the inputs' units"
        )
    } else {
        format!(
            "the arithmetic overflowed: total energy {total:.6e} J (from {initial:.6e} J), because of {}: beyond any physical value of this problem, no time step makes it computable; give it a physical value (SI units)",
            extreme.join(", ")
        )
    }
}

/// The rigid impactor and its contact law (impact scenes).
struct Impact<'a> {
    spec: &'a Impactor,
    law: LineContactLaw,
    body: RigidImpactor,
    /// Indentation `alpha_n = delta_S - delta_C`, m.
    alpha: f64,
}

impl Impact<'_> {
    /// Step 5: the contact force `F_{n+1}` (N) of eq. (21) for the datum's deflection
    /// `delta_c` (m) at n + 1, and the impactor moved to n + 1 (eqs. 19-20); `force` is `F_n`.
    fn advance(&mut self, dt: f64, force: f64, delta_c: f64) -> StdResult<f64, BeyondMaximum> {
        let alpha_free = self.body.displacement_after(dt, force, 0.0) - delta_c;
        let extra = dt * dt / (6.0 * self.body.mass);
        let f1 = solve_contact_force(&self.law, extra, alpha_free)?;
        self.body.advance(dt, force, f1);
        self.alpha = self.body.displacement - delta_c;
        Ok(f1)
    }
}

/// The state of the plate and the impactor between steps, and the steps of `ALGORITHM.md`
/// section 6 that advance it.
pub(super) struct Stepper<'a, F: Formulation, M: ConstitutiveModel> {
    scene: &'a Scene,
    mesh: &'a PlateMesh,
    pub(super) model: &'a mut PlateModel<F, M>,
    /// `dt_{n+1/2}`, the step from `t_n`, s.
    pub(super) dt: f64,
    /// `dt_{n-1/2}`, the step to `t_n`, s.
    pub(super) previous_dt: f64,
    /// `h_n`, the velocity step at `t_n` ([`step_size::velocity_step`]), s.
    h: f64,
    /// The step re-estimated at every step (`time.dt.update: every-step`); `None`: fixed.
    pub(super) every_step: Option<EveryStep>,
    /// s
    dt_critical: f64,
    /// Symmetry factor `s`.
    s: f64,
    impact: Option<Impact<'a>>,
    /// The surface coupling's nose and impactor.
    pub(super) surface: Option<SurfaceImpact>,
    /// The rigid wall the body flies onto, with its reading at `t_n` (the history's wall
    /// columns).
    wall: Option<(RigidWall, WallReading)>,
    /// The kinetic energy at `t_0`, J (0 unless the body starts moving: the wall).
    initial_kinetic: f64,
    prescribed: Option<PrescribedLoad>,
    /// Node whose `u_y` the force acts on.
    force_node: usize,
    /// Node the indentation is read from.
    datum: usize,
    energy_consistent: bool,
    /// `u_n`, m.
    pub(super) u: Vec<f64>,
    /// `v_{n-1/2}` before step 3, `v_{n+1/2}` after, m/s.
    pub(super) v: Vec<f64>,
    /// `f_int - f_ext`, N.
    pub(super) f_int: Vec<f64>,
    /// Contact force `F_n` on the whole plate, N (0 under a prescribed load).
    force: f64,
    pub(super) balance: BalanceMonitor,
    /// Finite deformation: each element's [`stable_step::centroid_spread`] as made, for
    /// [`Stepper::check_deformed_step`]; empty under small kinematics.
    reference_spreads: Vec<f64>,
    /// J
    external_work: f64,
    /// J
    plastic_work: f64,
    pub(super) initial_energy: Energies,
}

impl<'a, F: Formulation, M: ConstitutiveModel> Stepper<'a, F, M> {
    pub(super) fn new(
        scene: &'a Scene,
        mesh: &'a PlateMesh,
        model: &'a mut PlateModel<F, M>,
        dt: f64,
        dt_critical: f64,
        surface: Option<SurfaceImpact>,
    ) -> Self {
        let spec = scene.impactor();
        let datum = spec.map_or(mesh.top, |i| mesh.mid_span_node(i.indentation_datum));
        let force_node = spec.map_or(mesh.top, |i| mesh.mid_span_node(i.force_node));
        let ndof = model.inverse_mass.len();
        let mut v = vec![0.0; ndof];
        let wall = scene.wall().map(|spec| {
            let wall = RigidWall::new(mesh, scene.plate.thickness, (spec.hold_face, spec.friction));
            wall.launch(spec.velocity, &model.inverse_mass, &mut v);
            (wall, WallReading::default())
        });
        let initial_kinetic = wall
            .as_ref()
            .map_or(0.0, |(w, _)| w.kinetic_energy(&model.mass, &v));
        Stepper {
            scene,
            mesh,
            dt,
            previous_dt: dt,
            h: 0.5 * dt,
            every_step: None,
            dt_critical,
            s: mesh.symmetry_factor,
            impact: spec.map(|i| Impact {
                spec: i,
                law: LineContactLaw::new(i, &scene.material, scene.plate.width),
                body: RigidImpactor::new(i.mass, i.velocity),
                alpha: 0.0,
            }),
            prescribed: PrescribedLoad::from_scene(&scene.load, &scene.plate, mesh),
            force_node,
            datum,
            energy_consistent: force_node == datum || surface.is_some(),
            surface,
            wall,
            initial_kinetic,
            u: vec![0.0; ndof],
            v,
            f_int: vec![0.0; ndof],
            model,
            force: 0.0,
            balance: BalanceMonitor::default(),
            reference_spreads: match scene.kinematics {
                Kinematics::Small => Vec::new(),
                Kinematics::Finite => stable_step::reference_spreads(&mesh.mesh),
            },
            external_work: 0.0,
            plastic_work: 0.0,
            initial_energy: Energies::default(),
        }
    }

    /// `t_n`, s: `n dt` for a fixed step (exactly: `t + dt` can round differently and
    /// misplace the end of a pulse), the steps' sum when it changes.
    pub(super) fn time(&self, n: u64) -> f64 {
        self.every_step
            .as_ref()
            .map_or(n as f64 * self.dt, |e| e.time)
    }

    /// `t_{n+1}` after step `n` at `t`, s ([`Stepper::time`]).
    fn time_after(&self, n: u64, t: f64) -> f64 {
        match self.every_step {
            Some(_) => t + self.dt,
            None => (n + 1) as f64 * self.dt,
        }
    }

    /// The step from `t_n` (`t` s, the run's `end` s) and the velocity step at it
    /// ([`step_size`]): under `time.dt.update: every-step` the stable estimate of the
    /// deformed mesh at `u_n` ([`stable_step::deformed_ratio`] times the plate's first, with
    /// the contact springs), given to the material too (its rates divide by it); an error
    /// naming the element when it collapsed.
    pub(super) fn choose_step(&mut self, n: u64, t: f64, end: f64) -> Result<()> {
        self.previous_dt = self.dt;
        if let Some(every) = &mut self.every_step {
            let (ratio, e) =
                stable_step::deformed_ratio(&self.mesh.mesh, &self.reference_spreads, &self.u);
            let plate = ratio * every.dt_plate;
            let stable = self
                .surface
                .as_ref()
                .map_or(plate, |c| c.stable_step(plate, &self.model.mass));
            self.dt = every.next(stable, end).map_err(|step| {
                let [x, y] = self.mesh.mesh.element_centre(e);
                Error::Run {
                    step: n,
                    time_s: t,
                    what: format!(
                        "the stable step collapsed: element {e} (around x = {x:.4e} m, y = {y:.4e} m) is crushed to {ratio:.3e} of its stable length, giving a step of {step:.6e} s, below {} of the first ({:.6e} s): the mesh cannot follow this deformation (refine it where it crushes, or stop the run earlier)",
                        step_size::SMALLEST_STEP_FRACTION,
                        every.first
                    ),
                }
            })?;
            self.dt_critical = stable;
            self.model.material.set_time_step(self.dt);
        }
        self.h = step_size::velocity_step(n, self.previous_dt, self.dt);
        Ok(())
    }

    /// The force on the plate at `t_n`: the contact force, or the prescribed load, N (after
    /// the internal forces at `u_n`: the surface coupling's kinematic solve reads them).
    pub(super) fn applied(&mut self, t: f64) -> f64 {
        let h = self.h;
        if let Some(surface) = &mut self.surface {
            self.force = surface.solve(self.dt, h, &self.u, &self.v, &self.f_int);
        }
        if let Some((wall, _)) = &mut self.wall {
            let (mass, inverse_mass) = (&self.model.mass, &self.model.inverse_mass);
            let state = (&self.u[..], &self.v[..], &self.f_int[..]);
            self.force = wall.solve((self.dt, h), state, mass, inverse_mass);
        }
        self.prescribed
            .as_ref()
            .map_or(self.force, |l| l.magnitude_at(t))
    }

    /// Steps 2-3 (the external forces, accelerations, `v_{n+1/2}`) after step 1's internal
    /// forces, whose element energies are `element_energy`; returns the energies at `t_n`
    /// (section 7).
    pub(super) fn half_step(
        &mut self,
        n: u64,
        applied: f64,
        element_energy: ElementEnergy,
    ) -> Energies {
        let s = self.s;
        self.plastic_work += s * element_energy.plastic_work;
        match (&self.prescribed, &self.surface, &self.wall) {
            (Some(load), _, _) => load.subtract_from(applied, &mut self.f_int),
            (None, Some(surface), _) => surface.subtract_from(&mut self.f_int),
            (None, None, Some((wall, _))) => wall.subtract_from(&mut self.f_int),
            (None, None, None) => self.f_int[2 * self.force_node + 1] += applied / s, // f_int - f_ext, f_ext = -F/s on u_y
        }
        let update = VelocityUpdate {
            v: &mut self.v,
            f_int: &self.f_int,
            inverse_mass: &self.model.inverse_mass,
            mass: &self.model.mass,
            h: self.h,
        };
        let twice_kinetic = dispatch(self.model.kernel_path.isa(), update);
        if let Some((wall, reading)) = &mut self.wall {
            *reading = wall.observe(&self.u);
        }
        Energies {
            plate_kinetic: if n > 0 {
                0.5 * s * twice_kinetic
            } else {
                self.initial_kinetic
            },
            impactor_kinetic: self.impactor_kinetic(),
            strain: s * element_energy.strain,
            plastic_work: self.plastic_work,
            hourglass: s * element_energy.hourglass,
            contact: match (&self.impact, &self.surface, &self.wall) {
                (Some(i), _, _) => i.law.energy(self.force),
                (None, Some(surface), _) => surface.energy(),
                (None, None, Some((wall, _))) => wall.energy(),
                (None, None, None) => 0.0,
            },
            external_work: self.external_work,
        }
    }

    /// The impactor's kinetic energy at `t_n`, J (0 without one).
    fn impactor_kinetic(&self) -> f64 {
        match (&self.impact, &self.surface) {
            (Some(i), _) => i.body.kinetic_energy(),
            (None, Some(surface)) => {
                let v = surface.body.velocity(self.h, surface.force());
                0.5 * surface.body.mass * v * v
            }
            (None, None) => 0.0,
        }
    }

    /// Step 4's guard: records the energies at `t_n` in the balance and returns the imbalance
    /// (J) and the running balance error; an error when the run has gone unstable.
    pub(super) fn check_balance(
        &mut self,
        n: u64,
        t: f64,
        energies: &Energies,
    ) -> Result<(f64, f64)> {
        let (imbalance, balance_error) = self.balance.record(energies);
        if n == 0 {
            self.initial_energy = *energies;
        }
        let bound = if self.energy_consistent && n >= CONSISTENT_GUARD_AFTER_STEPS {
            BLOW_UP_BALANCE_ERROR_CONSISTENT
        } else {
            BLOW_UP_BALANCE_ERROR
        };
        if !(energies.total().is_finite() && self.initial_energy.total().is_finite()) {
            // An element turned inside out makes the finite kinematics' arithmetic fail at
            // once, before the periodic geometry check: name it first, unless an input beyond
            // any physical value is the cause (the overflow's message names it).
            if crate::input::estimate::measures::extreme_inputs(self.scene).is_empty() {
                self.check_inversion(n, t)?;
            }
            return Err(Error::Run {
                step: n,
                time_s: t,
                what: overflow_cause(self.scene, energies.total(), self.initial_energy.total()),
            });
        }
        if !balance_error.is_finite() || balance_error > bound {
            return Err(Error::Run {
                step: n,
                time_s: t,
                what: format!(
                    "unstable: the energy balance error reached {balance_error:.3e}, above {bound} (energy grows without a source: total energy {:.6e} J from {:.6e} J with {:.6e} J of external work); dt = {:.6e} s is {:.3} of the stable estimate{}",
                    energies.total(), self.initial_energy.total(), self.external_work, self.dt, self.dt / self.dt_critical,
                    crate::physics::contacts::contact_failure::light_impactor_cause(self.scene)
                ),
            });
        }
        Ok((imbalance, balance_error))
    }

    /// Surface coupling: records the penetration at `t_n` and stops the run (naming the node,
    /// its depth and the likeliest cause) once the plate's top surface has crossed the nose.
    pub(super) fn check_nose(&mut self, n: u64, t: f64) -> Result<()> {
        let Some(surface) = &mut self.surface else {
            return Ok(());
        };
        let Some((node, e)) = surface.observe(&self.u) else {
            return Ok(());
        };
        let r = surface.nose.radius;
        let speed = surface.body.half_step_velocity;
        let per_step = speed.abs() * self.dt;
        let cause = if per_step > 0.5 * r {
            format!("the nose moves {per_step:.3e} m in one step at {speed:.4e} m/s, {:.2} of its radius: a contact is found only where a node is inside the nose, so the step (time.dt) must move the nose well under its radius (lower time.dt.cfl or use a larger nose_radius)", per_step / r)
        } else {
            match self.scene.surface_impactor().map(|i| &i.contact) {
                Some(c) if c.enforcement == crate::input::scene::Enforcement::Penalty => format!("the penalty (penalty_scale {}) is too soft to stop the nose within its radius: raise penalty_scale or use enforcement: kinematic", crate::input::error::shown(c.penalty_scale)),
                _ => "the nose has sunk more than its radius into the plate, where the model (a rigid cylinder without the impactor's body above it) no longer holds: use a larger nose_radius".to_string(),
            }
        };
        Err(Error::Run {
            step: n,
            time_s: t,
            what: format!(
                "the plate's top surface has crossed the nose: the top node at reference x = {:.4e} m is {e:.4e} m above the nose's lowest point, at or above its centre (nose_radius {r:.4e} m); {cause}",
                node.x
            ),
        })
    }

    /// An error naming the first inverted element (checked every
    /// [`crate::time_loop::integrator::INVERSION_CHECK_EVERY`] steps and at the last).
    pub(super) fn check_inversion(&self, n: u64, t: f64) -> Result<()> {
        let Some(e) = self.mesh.mesh.first_inverted(&self.u) else {
            return Ok(());
        };
        let [x, y] = self.mesh.mesh.element_centre(e);
        Err(Error::Run {
            step: n,
            time_s: t,
            what: format!(
                "element {e} (around x = {x:.4e} m, y = {y:.4e} m) has inverted: {} (dt = {:.6e} s, {:.3} of the stable estimate)",
                self.inversion_cause(),
                self.dt,
                self.dt / self.dt_critical
            ),
        })
    }

    /// The likeliest cause of an inversion: a step above the stable one first (the
    /// integration's blow-up inverts elements whatever the kinematics), then the kinematics,
    /// then the element.
    fn inversion_cause(&self) -> String {
        let over = self.dt / self.dt_critical;
        if over > 1.0 {
            return format!("the step is {over:.2}x the stable estimate (time.allow_unstable_dt: true), so the central-difference integration is unstable and the inversion is its blow-up: lower time.dt below the stable step");
        }
        let remedy = match (self.scene.kinematics, self.scene.mesh.element) {
            (Kinematics::Small, _) => "the displacements are no longer small against the mesh (kinematics: finite follows large deformation)",
            (Kinematics::Finite, ElementKind::Q4OnePoint) => "it was crushed or turned inside out (a finer mesh, or q4-sri instead of q4-1pt, may carry the deformation)",
            (Kinematics::Finite, _) => "it was crushed or turned inside out: the load is beyond what this mesh can carry (a finer mesh where it is crushed, or a load spread over a face instead of a node)",
        };
        remedy.to_string()
    }

    /// Finite deformation: the run's step is fixed, so the run stops (naming the element)
    /// when deformation has brought the plate's stable estimate `dt_plate` (s) times
    /// [`stable_step::deformed_ratio`] below it, checked with the inversions (unless
    /// `time.allow_unstable_dt`).
    pub(super) fn check_deformed_step(&self, n: u64, t: f64, dt_plate: f64) -> Result<()> {
        let small = self.scene.kinematics == Kinematics::Small;
        if small || self.scene.time.allow_unstable_dt || self.every_step.is_some() {
            return Ok(());
        }
        let (ratio, e) =
            stable_step::deformed_ratio(&self.mesh.mesh, &self.reference_spreads, &self.u);
        if self.dt <= ratio * dt_plate {
            return Ok(());
        }
        Err(Error::Run {
            step: n,
            time_s: t,
            what: format!(
                "the deformed mesh's stable step fell below the run's: element {e} is compressed to {ratio:.3} of its stable length, giving {:.6e} s against dt = {:.6e} s (the step is fixed for the run: start with a smaller time.dt.cfl, about {:.2} of this one or less, or let the step follow the deformed mesh with time.dt.update: every-step)",
                ratio * dt_plate,
                self.dt,
                ratio * dt_plate / self.dt
            ),
        })
    }

    /// The wall's results at the end (`t_n`, its `energies`; `released`: when the body left the
    /// wall, if it is off it now): `None` without a wall.
    pub(super) fn wall_totals(
        &self,
        released: Option<f64>,
        energies: &Energies,
    ) -> Option<WallTotals> {
        let (wall, reading) = self.wall.as_ref()?;
        let (max_foot_radius, peak_bearing_force) = wall.maxima();
        let model = &*self.model;
        let n_points = model.formulation.n_elements() * F::POINTS;
        let eqps = (0..n_points).map(|k| {
            let state = model.state(k / F::POINTS, k % F::POINTS);
            model.material.equivalent_plastic_strain(&state)
        });
        Some(WallTotals {
            release_time: released,
            length: reading.bar_length,
            foot_radius: reading.foot_radius,
            undeformed_length: reading.undeformed_length,
            outline: wall.outline(&self.u),
            max_foot_radius,
            peak_bearing_force,
            rebound_velocity: released.map(|_| RigidWall::mean_velocity(&model.mass, &self.v)),
            dissipated: energies.contact,
            max_plastic_strain: self.scene.is_plastic().then(|| eqps.fold(0.0, f64::max)),
        })
    }

    /// What the recorder writes down at `t_n`.
    pub(super) fn sample<'e>(
        &self,
        t: f64,
        applied: f64,
        energies: &'e Energies,
        imbalance: f64,
    ) -> Sample<'e> {
        let uy = |node: usize| self.u[2 * node + 1];
        let surface = self.surface.as_ref();
        Sample {
            t,
            force: applied,
            impactor: match (&self.impact, surface) {
                (Some(i), _) => Some([i.alpha, i.body.displacement, i.body.velocity]),
                (None, Some(c)) => Some(c.motion(self.h, uy(self.mesh.top))),
                (None, None) => None,
            },
            patch: surface.map(SurfaceImpact::patch),
            wall: self.wall.as_ref().map(|(_, reading)| reading.values()),
            uy: [uy(self.mesh.top), uy(self.mesh.mid), uy(self.mesh.bottom)],
            energies,
            imbalance,
        }
    }

    /// A probe's stress (Pa) at `u_n`, and a rate-dependent material's rate and temperature.
    pub(super) fn probe(&self, p: &Probe) -> ProbeReading {
        let state = self.model.state(p.element, p.point);
        let material = &self.model.material;
        ProbeReading {
            stress: self.model.point_stress(p.element, p.point, &self.u),
            plastic_strain_rate: material.plastic_strain_rate(&state),
            temperature: material.temperature(&state),
        }
    }

    /// `u_{n+1} = u_n + dt v_{n+1/2}`, then step 5 (impact: the contact force at n + 1 and the
    /// impactor) and the external work of a prescribed load. Returns the force at `t_{n+1}`,
    /// N (contact, or the prescribed load's magnitude).
    pub(super) fn advance(
        &mut self,
        n: u64,
        t: f64,
        applied: f64,
        balance_error: f64,
    ) -> Result<f64> {
        let dt = self.dt;
        let projection_before = self
            .prescribed
            .as_ref()
            .map_or(0.0, |l| l.projection(&self.u));
        let displace = Displace {
            u: &mut self.u,
            v: &self.v,
            dt,
        };
        dispatch(self.model.kernel_path.isa(), displace);
        let t_next = self.time_after(n, t);
        if let Some(every) = &mut self.every_step {
            every.time = t_next;
        }
        if let Some(surface) = &mut self.surface {
            self.force = surface.advance((dt, self.h), &self.u);
            return Ok(self.force);
        }
        let next_force = match &mut self.impact {
            Some(impact) => {
                let delta_c = -self.u[2 * self.datum + 1];
                impact
                    .advance(dt, self.force, delta_c)
                    .map_err(|beyond| Error::Run {
                        step: n + 1,
                        time_s: t_next,
                        what: crate::physics::contacts::contact_failure::Failure {
                            scene: self.scene,
                            impactor: impact.spec,
                            law: &impact.law,
                            beyond,
                            balance_error,
                            dt,
                            dt_critical: self.dt_critical,
                        }
                        .explain(),
                    })?
            }
            None => self
                .prescribed
                .as_ref()
                .map_or(0.0, |l| l.magnitude_at(t_next)),
        };
        if let Some(load) = &self.prescribed {
            let projection_after = load.projection(&self.u);
            self.external_work +=
                load.work(applied, next_force, projection_before, projection_after);
        }
        self.force = if self.prescribed.is_some() {
            0.0
        } else {
            next_force
        };
        Ok(next_force)
    }
}
