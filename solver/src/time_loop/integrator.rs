//! The explicit central-difference time loop, eqs. (8)-(12), coupled with the rigid impactor
//! and the contact law, eqs. (19)-(21), following the solution procedure of section 3.5.
//! See `ALGORITHM.md` section 6 for the exact order of operations.

use crate::input::error::{Error, Result};
use crate::input::scene::{DtChoice, DtUpdate, End, Scene};
use crate::mesh::PlateMesh;
use crate::physics::contacts::contact::LineContactLaw;
use crate::physics::elements::element::Formulation;
use crate::physics::materials::material::ConstitutiveModel;
use crate::time_loop::history::{locate_probes, HistorySink, Recorder, RunTotals, StopReason};
use crate::time_loop::observer::field_frame;
use crate::time_loop::schedule::{steps_to, Schedule};
use crate::time_loop::stable_step::{self, Estimate, Spring};
use crate::time_loop::step_size::{at_end, EveryStep};
use crate::time_loop::stepper::Stepper;
use crate::time_loop::surface_coupling::SurfaceImpact;

// Kept at their paths before the plate model, the observer and the stepper had their files.
pub use crate::time_loop::observer::{FieldFrame, Observer, Quiet};
pub use crate::time_loop::plate_model::PlateModel;
pub use crate::time_loop::stepper::{
    BLOW_UP_BALANCE_ERROR, BLOW_UP_BALANCE_ERROR_CONSISTENT, CONSISTENT_GUARD_AFTER_STEPS,
};

/// Steps between checks for inverted elements (a run that inverts one stops within this).
pub const INVERSION_CHECK_EVERY: u64 = 32;

/// Whether step `n` checks the deformed geometry (inverted elements; under finite deformation
/// also the deformed mesh's stable step): every [`INVERSION_CHECK_EVERY`] steps and at the
/// `last` (`ALGORITHM.md` sections 3c and 7).
fn geometry_check_due(n: u64, last: bool) -> bool {
    n % INVERSION_CHECK_EVERY == 0 || last
}

/// Runs the time loop of a validated scene on a built model, sending the history rows to
/// `sink`: the steps of `ALGORITHM.md` section 6 ([`Stepper`]) written down by the
/// [`Recorder`] (section 8).
pub fn run<F: Formulation, M: ConstitutiveModel>(
    scene: &Scene,
    mesh: &PlateMesh,
    model: &mut PlateModel<F, M>,
    observer: &mut dyn Observer,
    sink: &mut dyn HistorySink,
) -> Result<RunTotals> {
    let surface = scene
        .surface_impactor()
        .map(|spec| SurfaceImpact::new(spec, mesh, model, scene.material.density));
    let dt_plate = critical_step(scene, mesh, model);
    let dt_critical = surface
        .as_ref()
        .map_or(dt_plate, |c| c.stable_step(dt_plate, &model.mass));
    let dt = chosen_step(scene, dt_critical)?;
    crate::input::estimate::time_step::check_steps(scene, dt)?;
    model.material.set_time_step(dt);
    let probes = locate_probes(scene, mesh, &model.formulation)?;
    let clock = Clock::new(scene, dt);
    let mut watch = Watch::new(scene, observer, &clock);
    let mut recorder = Recorder::new(scene, probes, sink, dt, dt_critical, dt_plate)?;
    let mut stepper = Stepper::new(scene, mesh, model, dt, dt_critical, surface);
    if scene.time.dt_update == DtUpdate::EveryStep {
        stepper.every_step = Some(EveryStep::new(dt / dt_critical, dt_plate, dt));
    }
    let mut march = || -> Result<RunTotals> {
        let mut n: u64 = 0;
        loop {
            let t = stepper.time(n);
            // 1: internal forces at u_n; the step from t_n; 2: the force on the plate at t_n.
            let element_energy = stepper
                .model
                .internal_forces(&stepper.u, &mut stepper.f_int);
            stepper.choose_step(n, t, clock.end_time)?;
            let applied = stepper.applied(t);
            recorder.contact(t, applied, stepper.previous_dt);
            let stop = clock.stop(n, t, stepper.dt, recorder.separated_at());
            // 2-3: accelerations, velocities at n + 1/2; 4: energies at t_n.
            let energies = stepper.half_step(n, applied, element_energy);
            let (imbalance, balance_error) = stepper.check_balance(n, t, &energies)?;
            stepper.check_nose(n, t)?;
            if geometry_check_due(n, stop.is_some()) {
                stepper.check_inversion(n, t)?;
                stepper.check_deformed_step(n, t, dt_plate)?;
            }
            let at = stepper.sample(t, applied, &energies, imbalance);
            recorder.sample(n, stepper.dt, stop.is_some(), &at, |p| stepper.probe(p))?;
            watch.step(n, t, stop.is_some(), &stepper)?;
            if let Some(reason) = stop {
                let balance = stepper.balance;
                let released = recorder.separated_at().filter(|_| applied == 0.0);
                let wall = stepper.wall_totals(released, &energies);
                let mut totals =
                    recorder.finish(n, reason, &at, stepper.initial_energy, &balance)?;
                totals.wall = wall;
                totals.dt_range = stepper.every_step.as_ref().map(|e| e.range);
                totals.max_temperature = stepper.model.max_temperature();
                totals.max_penetration = stepper.surface.as_ref().map(|c| c.max_penetration);
                return Ok(totals);
            }
            // u_{n+1}, then 5: the contact force at n + 1 and the impactor.
            stepper.advance(n, t, applied, balance_error)?;
            n += 1;
        }
    };
    let result = march();
    if result.is_err() {
        // The rows so far, for a caller that keeps partial output (`--keep-partial`); the
        // run's own error is the one to report, so a failure to keep them is not.
        let _ = recorder.abandon(&stepper.balance);
    }
    result
}

/// The time step of the scene's `time.dt` choice, s: a fraction of `dt_critical`, or a fixed
/// step refused above it (unless `time.allow_unstable_dt`).
fn chosen_step(scene: &Scene, dt_critical: f64) -> Result<f64> {
    match scene.time.dt {
        DtChoice::Cfl(c) => Ok(c * dt_critical),
        DtChoice::Fixed(d) => {
            if d > dt_critical && !scene.time.allow_unstable_dt {
                return Err(Error::invalid(
                    scene.time.dt_location.clone(),
                    "time.dt.fixed",
                    d,
                    format!("must not exceed the stable estimate {dt_critical:.6e} s of this mesh (or set time.allow_unstable_dt: true)"),
                ));
            }
            Ok(d)
        }
    }
}

/// When the run ends: at `time.end`, or `after` s after contact ends (at most at `limit`).
struct Clock {
    /// s
    end_time: f64,
    last_step: u64,
    /// Whether the step changes (`time.dt.update: every-step`): the end is read on the time.
    in_time: bool,
    /// s after separation (`time.end: {after_contact}`).
    after_contact: Option<f64>,
}

impl Clock {
    fn new(scene: &Scene, dt: f64) -> Clock {
        let (end_time, after_contact) = match scene.time.end {
            End::At(t) => (t, None),
            End::AfterContact { after, limit } => (limit, Some(after)),
        };
        Clock {
            end_time,
            last_step: steps_to(end_time, dt),
            in_time: scene.time.dt_update == DtUpdate::EveryStep,
            after_contact,
        }
    }

    /// Whether the run stops after step `n` (at `t`; `dt` the step from it, s), and why.
    fn stop(&self, n: u64, t: f64, dt: f64, separated_at: Option<f64>) -> Option<StopReason> {
        let reached = if self.in_time {
            at_end(self.end_time, t, dt)
        } else {
            n >= self.last_step
        };
        if reached {
            return Some(if self.after_contact.is_some() {
                StopReason::TimeLimit
            } else {
                StopReason::EndTime
            });
        }
        match (self.after_contact, separated_at) {
            (Some(after), Some(since)) if t - since >= after - 1e-9 * dt => {
                Some(StopReason::AfterContact)
            }
            _ => None,
        }
    }
}

/// What the observer is given: field frames, progress, and the chance to stop the run.
struct Watch<'o> {
    observer: &'o mut dyn Observer,
    frames: Schedule,
    wants_fields: bool,
    progress_every: u64,
    /// s
    end_time: f64,
}

impl<'o> Watch<'o> {
    fn new(scene: &Scene, observer: &'o mut dyn Observer, clock: &Clock) -> Watch<'o> {
        let wants = observer.wants_fields();
        Watch {
            frames: Schedule::of(
                wants.then_some(scene.output.fields_every).flatten(),
                scene.time.dt_update,
            ),
            wants_fields: wants && scene.output.fields_every.is_some(),
            progress_every: (clock.last_step / 200).max(1),
            end_time: clock.end_time,
            observer,
        }
    }

    /// Step `n` at `t` (`last`: the run stops after it): a field frame when one is due,
    /// progress, and [`Error::Interrupted`] when a stop was requested.
    fn step<F: Formulation, M: ConstitutiveModel>(
        &mut self,
        n: u64,
        t: f64,
        last: bool,
        stepper: &Stepper<F, M>,
    ) -> Result<()> {
        if self.wants_fields && (self.frames.due_at(n, t, stepper.dt) || last) {
            let mut frame = field_frame(stepper.model, &stepper.u, &stepper.v, t);
            frame.contact_force = stepper
                .surface
                .as_ref()
                .map(|c| c.nodal_forces(frame.displacement.len()));
            self.observer.fields(frame)?;
        }
        if n % self.progress_every == 0 {
            self.observer.progress(t, self.end_time);
        }
        if n % crate::time_loop::interrupt::POLL_EVERY == 0 && self.observer.stop_requested() {
            return Err(Error::Interrupted {
                step: n,
                time_s: t,
                cleanup: String::new(),
            });
        }
        Ok(())
    }
}

/// The stable step of `scene.time.dt.estimate`, s. The global estimate includes the contact
/// spring on the force node's u_y (for the modelled part: divided by the symmetry factor) at
/// the stiffest force the impactor's kinetic energy can reach.
fn critical_step<F: Formulation, M: ConstitutiveModel>(
    scene: &Scene,
    mesh: &PlateMesh,
    model: &PlateModel<F, M>,
) -> f64 {
    match scene.time.dt_estimate {
        Estimate::Element => model.critical_time_step(scene.material.density),
        Estimate::Global => {
            let spring = scene.impactor().map(|i| {
                let law = LineContactLaw::new(i, &scene.material, scene.plate.width);
                let energy = 0.5 * i.mass * i.velocity * i.velocity;
                Spring {
                    dof: 2 * mesh.mid_span_node(i.force_node) + 1,
                    stiffness: stable_step::contact_stiffness_bound(&law, energy)
                        / mesh.symmetry_factor,
                }
            });
            model.global_time_step(spring)
        }
    }
}
