//! The explicit central-difference time loop, eqs. (8)-(12), coupled with the rigid impactor
//! and the contact law, eqs. (19)-(21), following the solution procedure of section 3.5.
//! See `ALGORITHM.md` section 6 for the exact order of operations.

use std::result::Result as StdResult;

use crate::input::error::{Error, Result};
use crate::input::scene::{DtChoice, DtUpdate, End, Impactor, Kinematics, Scene};
use crate::kernels::assembly::Assembly;
use crate::kernels::elastic_screen::ElasticScreen;
use crate::kernels::stiffness::LinearKernel;
use crate::lanes::heap;
use crate::lanes::simd::{dispatch, each_lane, Kernel, KernelPath, Lanes, LANES};
use crate::mesh::PlateMesh;
use crate::physics::contact::{solve_contact_force, BeyondMaximum, LineContactLaw};
use crate::physics::element::{gather, lumped_masses, ElementEnergy, Formulation};
use crate::physics::impactor::RigidImpactor;
use crate::physics::load::PrescribedLoad;
use crate::physics::material::Elastic;
use crate::physics::material::{von_mises, ConstitutiveModel, Stress};
use crate::physics::rigid_wall::{RigidWall, WallTotals};
use crate::time_loop::energy::{BalanceMonitor, Energies};
use crate::time_loop::history::{
    locate_probes, HistorySink, Probe, ProbeReading, Recorder, RunTotals, Sample, StopReason,
};
use crate::time_loop::schedule::{steps_to, Schedule};
use crate::time_loop::stable_step::{self, Estimate, Spring};
use crate::time_loop::step_size::{self, at_end, EveryStep};
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

/// Steps between checks for inverted elements (a run that inverts one stops within this).
pub const INVERSION_CHECK_EVERY: u64 = 32;

/// Whether step `n` checks the deformed geometry (inverted elements; under finite deformation
/// also the deformed mesh's stable step): every [`INVERSION_CHECK_EVERY`] steps and at the
/// `last` (`ALGORITHM.md` sections 3c and 7).
fn geometry_check_due(n: u64, last: bool) -> bool {
    n % INVERSION_CHECK_EVERY == 0 || last
}

/// The plate model: formulation, material, per-point states, masses.
pub struct PlateModel<F: Formulation, M: ConstitutiveModel> {
    pub formulation: F,
    pub material: M,
    /// The material states, batch-major: `POINTS` batches (one per point) per batch of
    /// [`LANES`] elements (zero-sized for elastic models); [`PlateModel::state`] reads one.
    pub states: Vec<M::Batch>,
    /// Lumped nodal mass, kg.
    pub mass: Vec<f64>,
    /// 1/mass per dof, 0 on constrained dofs.
    pub inverse_mass: Vec<f64>,
    /// Precomputed element stiffness, used instead of the stress path when the material is
    /// linear elastic (see [`PlateModel::with_linear_kernel`]).
    pub linear: Option<LinearKernel>,
    /// For a plastic material: elements that never yielded and stay elastic by `K_e u_e`
    /// (see [`PlateModel::with_elastic_screen`]).
    pub screen: Option<ElasticScreen>,
    /// Chunked (optionally multithreaded) assembly buffers.
    pub assembly: Assembly,
    /// Batched kernels (the default) or the scalar reference.
    pub kernel_path: KernelPath,
}

impl<F: Formulation, M: ConstitutiveModel> PlateModel<F, M> {
    pub fn new(formulation: F, material: M, mesh: &PlateMesh, density: f64) -> Self {
        let n = formulation.n_elements();
        let mass = lumped_masses(&formulation, mesh.mesh.n_nodes(), density);
        let inverse_mass = (0..2 * mass.len())
            .map(|d| {
                if mesh.fixed_dofs[d] {
                    0.0
                } else {
                    1.0 / mass[d / 2]
                }
            })
            .collect();
        // Elastic materials have no states and a cheap kernel.
        let assembly = Assembly::for_mesh(
            formulation.connectivity(),
            mesh.mesh.n_nodes(),
            M::HAS_STATES,
        );
        PlateModel {
            states: vec![M::Batch::default(); n.div_ceil(LANES) * F::POINTS],
            formulation,
            material,
            mass,
            inverse_mass,
            linear: None,
            screen: None,
            assembly,
            kernel_path: KernelPath::fastest(),
        }
    }

    /// Heap bytes the model holds: geometry, states, masses, stiffness matrices, screen and
    /// assembly buffers (not the time loop's nodal vectors).
    pub fn heap_bytes(&self) -> usize {
        self.formulation.heap_bytes()
            + heap::vec_bytes(&self.states)
            + heap::vec_bytes(&self.mass)
            + heap::vec_bytes(&self.inverse_mass)
            + self.linear.as_ref().map_or(0, LinearKernel::heap_bytes)
            + self.screen.as_ref().map_or(0, ElasticScreen::heap_bytes)
            + self.assembly.heap_bytes()
    }

    /// Runs the element kernels on `path` (the scalar reference or a batched instruction set).
    pub fn with_kernel_path(mut self, path: KernelPath) -> Self {
        self.kernel_path = path;
        self
    }

    /// Switches the internal forces to precomputed element stiffness matrices. Only valid
    /// for a linear elastic material (the caller's guarantee: `M = Elastic`).
    pub fn with_linear_kernel(mut self, elastic: &Elastic) -> Self {
        self.linear = Some(LinearKernel::new(&self.formulation, elastic));
        self
    }

    /// Lets elements that never yielded respond by `K_e u_e` while they certainly stay
    /// elastic (no effect for a material that never yields).
    pub fn with_elastic_screen(mut self) -> Self {
        self.screen = ElasticScreen::new(&self.formulation, &self.material);
        self
    }

    /// The critical time step 2 / omega_max from the element eigenvalue bound (eq. 15), s.
    pub fn critical_time_step(&self, density: f64) -> f64 {
        stable_step::element_bound(&self.formulation, self.material.elastic(), density)
    }

    /// The critical time step from the global estimate of omega_max (power iteration, the
    /// contact `spring` included, times the safety factor), s.
    pub fn global_time_step(&self, spring: Option<Spring>) -> f64 {
        stable_step::global_estimate(
            &self.formulation,
            self.material.elastic(),
            &self.inverse_mass,
            spring,
        )
    }

    /// The material state of integration point `p` of element `e`.
    pub fn state(&self, e: usize, p: usize) -> M::State {
        M::state_of(&self.states[e / LANES * F::POINTS + p], e % LANES)
    }

    /// Stress at integration point `p` of element `e` for displacements `u`.
    pub fn point_stress(&self, e: usize, p: usize, u: &[f64]) -> Stress {
        let ue = gather(self.formulation.nodes(e), u);
        let strain = self.formulation.strains(e, &ue)[p];
        self.material.stress(&strain, &self.state(e, p))
    }

    /// The highest temperature over the points (K); `None` for a material without one.
    pub fn max_temperature(&self) -> Option<f64> {
        let n = self.formulation.n_elements();
        (0..n)
            .flat_map(|e| (0..F::POINTS).map(move |p| (e, p)))
            .filter_map(|(e, p)| self.material.temperature(&self.state(e, p)))
            .reduce(f64::max)
    }

    /// The weighted mean over element `e`'s points of `value` (for field output); `None`
    /// where the material has no such value.
    pub fn element_mean(&self, e: usize, value: impl Fn(&M::State) -> Option<f64>) -> Option<f64> {
        let w = self.formulation.weights(e);
        let total: f64 = w[..F::POINTS].iter().sum();
        let mut mean = 0.0;
        for (p, &wp) in w.iter().enumerate().take(F::POINTS) {
            mean += wp / total * value(&self.state(e, p))?;
        }
        Some(mean)
    }

    /// Element-average stress and equivalent plastic strain (for field output).
    pub fn element_average(&self, e: usize, u: &[f64]) -> (Stress, f64) {
        let w = self.formulation.weights(e);
        let total: f64 = w[..F::POINTS].iter().sum();
        let mut s = [0.0; 4];
        let mut k = 0.0;
        for (p, &wp) in w.iter().enumerate().take(F::POINTS) {
            let sp = self.point_stress(e, p, u);
            for c in 0..4 {
                s[c] += wp / total * sp[c];
            }
            k += wp / total * self.material.equivalent_plastic_strain(&self.state(e, p));
        }
        (s, k)
    }
}

/// One frame of field output.
#[derive(Debug, Clone)]
pub struct FieldFrame {
    pub time: f64,
    /// Per node, m.
    pub displacement: Vec<[f64; 2]>,
    /// Per node, m/s.
    pub velocity: Vec<[f64; 2]>,
    /// Per element average `[xx, yy, zz, xy]`, Pa.
    pub stress: Vec<Stress>,
    pub von_mises: Vec<f64>,
    pub eqps: Vec<f64>,
    /// Per element average, 1/s (rate-dependent materials).
    pub plastic_strain_rate: Option<Vec<f64>>,
    /// Per element average, K (heating materials).
    pub temperature: Option<Vec<f64>>,
    /// Surface coupling: the nose's force on each node at `t_n`, N (whole width; 0 off the
    /// contact).
    pub contact_force: Option<Vec<[f64; 2]>>,
}

/// Receives field frames and progress while a run goes on.
pub trait Observer {
    fn progress(&mut self, _time: f64, _end: f64) {}
    /// Polled every [`crate::time_loop::interrupt::POLL_EVERY`] steps: `true` stops the run with
    /// [`Error::Interrupted`].
    fn stop_requested(&self) -> bool {
        false
    }
    fn wants_fields(&self) -> bool {
        false
    }
    fn fields(&mut self, _frame: FieldFrame) -> Result<()> {
        Ok(())
    }
}

/// An observer that takes nothing.
pub struct Quiet;
impl Observer for Quiet {}

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
    crate::input::time_step::check_steps(scene, dt)?;
    model.material.set_time_step(dt);
    let probes = locate_probes(scene, mesh, &model.formulation)?;
    let clock = Clock::new(scene, dt);
    let mut watch = Watch::new(scene, observer, &clock);
    let mut recorder = Recorder::new(scene, probes, sink, dt, dt_critical, dt_plate)?;
    let mut stepper = Stepper::new(scene, mesh, model, dt, dt_critical, surface);
    if scene.time.dt_update == DtUpdate::EveryStep {
        stepper.every_step = Some(EveryStep::new(dt / dt_critical, dt_plate, dt));
    }
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
            let mut totals = recorder.finish(n, reason, &at, stepper.initial_energy, &balance)?;
            totals.wall = wall;
            totals.dt_range = stepper.every_step.as_ref().map(|e| e.range);
            totals.max_temperature = stepper.model.max_temperature();
            return Ok(totals);
        }
        // u_{n+1}, then 5: the contact force at n + 1 and the impactor.
        stepper.advance(n, t, applied, balance_error)?;
        n += 1;
    }
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

/// Why the energies left double precision (inf or NaN): the inputs beyond any physical
/// magnitude when the scene has some (no time step can make those arithmetic finite), else
/// the numbers grew without bound (an instability past the guard's bound within one step).
fn overflow_cause(scene: &Scene, total: f64, initial: f64) -> String {
    let extreme = crate::input::plausibility::extreme_inputs(scene);
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
struct Stepper<'a, F: Formulation, M: ConstitutiveModel> {
    scene: &'a Scene,
    mesh: &'a PlateMesh,
    model: &'a mut PlateModel<F, M>,
    /// `dt_{n+1/2}`, the step from `t_n`, s.
    dt: f64,
    /// `dt_{n-1/2}`, the step to `t_n`, s.
    previous_dt: f64,
    /// `h_n`, the velocity step at `t_n` ([`step_size::velocity_step`]), s.
    h: f64,
    /// The step re-estimated at every step (`time.dt.update: every-step`); `None`: fixed.
    every_step: Option<EveryStep>,
    /// s
    dt_critical: f64,
    /// Symmetry factor `s`.
    s: f64,
    impact: Option<Impact<'a>>,
    /// The surface coupling's nose and impactor.
    surface: Option<SurfaceImpact>,
    /// The rigid wall the body flies onto, with its reading at `t_n`: the radius of the nodes
    /// touching it and the top axis node's height (the bar's length), m.
    wall: Option<(RigidWall, [f64; 2])>,
    /// The kinetic energy at `t_0`, J (0 unless the body starts moving: the wall).
    initial_kinetic: f64,
    prescribed: Option<PrescribedLoad>,
    /// Node whose `u_y` the force acts on.
    force_node: usize,
    /// Node the indentation is read from.
    datum: usize,
    energy_consistent: bool,
    /// `u_n`, m.
    u: Vec<f64>,
    /// `v_{n-1/2}` before step 3, `v_{n+1/2}` after, m/s.
    v: Vec<f64>,
    /// `f_int - f_ext`, N.
    f_int: Vec<f64>,
    /// Contact force `F_n` on the whole plate, N (0 under a prescribed load).
    force: f64,
    balance: BalanceMonitor,
    /// Finite deformation: each element's [`stable_step::centroid_spread`] as made, for
    /// [`Stepper::check_deformed_step`]; empty under small kinematics.
    reference_spreads: Vec<f64>,
    /// J
    external_work: f64,
    /// J
    plastic_work: f64,
    initial_energy: Energies,
}

impl<'a, F: Formulation, M: ConstitutiveModel> Stepper<'a, F, M> {
    fn new(
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
            let wall = RigidWall::new(mesh, scene.plate.thickness);
            wall.launch(spec.velocity, &model.inverse_mass, &mut v);
            (wall, [0.0; 2])
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
    fn time(&self, n: u64) -> f64 {
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
    fn choose_step(&mut self, n: u64, t: f64, end: f64) -> Result<()> {
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
    fn applied(&mut self, t: f64) -> f64 {
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
    fn half_step(&mut self, n: u64, applied: f64, element_energy: ElementEnergy) -> Energies {
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
            *reading = [
                wall.touching_radius(&self.u),
                wall.height(self.mesh.top, &self.u),
            ];
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
    fn check_balance(&mut self, n: u64, t: f64, energies: &Energies) -> Result<(f64, f64)> {
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
                    crate::physics::contact_failure::light_impactor_cause(self.scene)
                ),
            });
        }
        Ok((imbalance, balance_error))
    }

    /// An error naming the first inverted element (at the steps of [`geometry_check_due`]).
    fn check_inversion(&self, n: u64, t: f64) -> Result<()> {
        let Some(e) = self.mesh.mesh.first_inverted(&self.u) else {
            return Ok(());
        };
        let [x, y] = self.mesh.mesh.element_centre(e);
        Err(Error::Run {
            step: n,
            time_s: t,
            what: format!(
                "element {e} (around x = {x:.4e} m, y = {y:.4e} m) has inverted: {} (dt = {:.6e} s, {:.3} of the stable estimate)",
                match self.scene.kinematics {
                    Kinematics::Small => "the displacements are no longer small against the mesh (kinematics: finite follows large deformation)",
                    Kinematics::Finite => "it was crushed or turned inside out (a finer mesh, or q4-sri instead of q4-1pt, may carry the deformation)",
                },
                self.dt,
                self.dt / self.dt_critical
            ),
        })
    }

    /// Finite deformation: the run's step is fixed, so the run stops (naming the element)
    /// when deformation has brought the plate's stable estimate `dt_plate` (s) times
    /// [`stable_step::deformed_ratio`] below it, checked with the inversions (unless
    /// `time.allow_unstable_dt`).
    fn check_deformed_step(&self, n: u64, t: f64, dt_plate: f64) -> Result<()> {
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
    fn wall_totals(&self, released: Option<f64>, energies: &Energies) -> Option<WallTotals> {
        let (wall, [_, length]) = self.wall.as_ref()?;
        let model = &*self.model;
        let n_points = model.formulation.n_elements() * F::POINTS;
        let eqps = (0..n_points).map(|k| {
            let state = model.state(k / F::POINTS, k % F::POINTS);
            model.material.equivalent_plastic_strain(&state)
        });
        Some(WallTotals {
            release_time: released,
            length: *length,
            foot_radius: wall.foot_radius(&self.u),
            max_touching_radius: wall.max_touching_radius(),
            rebound_velocity: RigidWall::mean_velocity(&model.mass, &self.v),
            dissipated: energies.contact,
            max_plastic_strain: self.scene.is_plastic().then(|| eqps.fold(0.0, f64::max)),
        })
    }

    /// What the recorder writes down at `t_n`.
    fn sample<'e>(
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
            wall: self.wall.as_ref().map(|(_, reading)| *reading),
            uy: [uy(self.mesh.top), uy(self.mesh.mid), uy(self.mesh.bottom)],
            energies,
            imbalance,
        }
    }

    /// A probe's stress (Pa) at `u_n`, and a rate-dependent material's rate and temperature.
    fn probe(&self, p: &Probe) -> ProbeReading {
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
    fn advance(&mut self, n: u64, t: f64, applied: f64, balance_error: f64) -> Result<f64> {
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
                        what: crate::physics::contact_failure::Failure {
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

/// Steps 2-3: `v += h a` with `a = -f_int / m` per dof (`h`: the velocity step, s); `run`
/// returns `sum m v_n^2` (kg m^2/s^2) with `v_n` the mean of the old and new velocity, summed
/// as [`LANES`] partial sums (dof `d` into sum `d % LANES`) then added in order: a fixed
/// order (the same bits on every run and thread count) that lets the loop run in vectors
/// instead of waiting on one chain of additions. A [`Kernel`], compiled for the element kernels'
/// instruction set (the same bits on any: no operation here is fused or reordered).
struct VelocityUpdate<'a> {
    v: &'a mut [f64],
    f_int: &'a [f64],
    /// Per dof, 1/kg.
    inverse_mass: &'a [f64],
    /// Per node, kg.
    mass: &'a [f64],
    h: f64,
}

impl Kernel for VelocityUpdate<'_> {
    type Output = f64;
    #[inline(always)]
    fn run(self) -> f64 {
        let (v, h) = (self.v, self.h);
        let (f_int, inverse_mass) = (&self.f_int[..v.len()], &self.inverse_mass[..v.len()]);
        let mass = &self.mass[..v.len() / 2];
        let group =
            |v: &mut [f64], f: &[f64], im: &[f64], m: &[f64]| velocity_group(v, f, im, m, h);
        let mut sums = Lanes::splat(0.0);
        let groups = v
            .chunks_exact_mut(LANES)
            .zip(f_int.chunks_exact(LANES))
            .zip(inverse_mass.chunks_exact(LANES))
            .zip(mass.chunks_exact(LANES / 2));
        for (((v, f), im), m) in groups {
            sums += group(v, f, im, m);
        }
        // The last dofs (fewer than LANES), padded with zeros that add 0 to their sums.
        let whole = v.len() - v.len() % LANES;
        let mut tail = [[0.0; LANES]; 3];
        let mut tail_mass = [0.0; LANES / 2];
        for d in whole..v.len() {
            let i = d - whole;
            (tail[0][i], tail[1][i], tail[2][i]) = (v[d], f_int[d], inverse_mass[d]);
            tail_mass[i / 2] = mass[d / 2];
        }
        let [mut tv, tf, tim] = tail;
        sums += group(&mut tv, &tf, &tim, &tail_mass);
        let n = v.len() - whole;
        v[whole..].copy_from_slice(&tv[..n]);
        sums.0.iter().sum()
    }
}

/// [`VelocityUpdate`] of a group of [`LANES`] dofs `v` (m/s) with their forces `f` (N) and
/// inverse masses `inverse_mass` (1/kg) and their nodes' masses `m` (kg), in lanes; returns
/// `v_n^2 m` per dof. (A function, not a closure: a closure may be left out of line,
/// compiled for the baseline.)
#[inline(always)]
fn velocity_group(v: &mut [f64], f: &[f64], inverse_mass: &[f64], m: &[f64], h: f64) -> Lanes {
    let lanes = |x: &[f64]| Lanes(each_lane(|i| x[i]));
    let (old, f, im) = (lanes(v), lanes(f), lanes(inverse_mass));
    let m = Lanes(each_lane(|i| m[i / 2]));
    let new = old + h * (f.map(|x| -x) * im);
    let mean = 0.5 * (old + new);
    v.copy_from_slice(&new.0);
    m * mean * mean
}

/// `u += dt v` per dof (m; `dt` s, `v` m/s), compiled as [`VelocityUpdate`].
struct Displace<'a> {
    u: &'a mut [f64],
    v: &'a [f64],
    dt: f64,
}

impl Kernel for Displace<'_> {
    type Output = ();
    #[inline(always)]
    fn run(self) {
        for (u, v) in self.u.iter_mut().zip(self.v) {
            *u += self.dt * v;
        }
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

fn field_frame<F: Formulation, M: ConstitutiveModel>(
    model: &PlateModel<F, M>,
    u: &[f64],
    v_next: &[f64],
    t: f64,
) -> FieldFrame {
    let n_el = model.formulation.n_elements();
    let averages: Vec<(Stress, f64)> = (0..n_el).map(|e| model.element_average(e, u)).collect();
    FieldFrame {
        time: t,
        displacement: u.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
        velocity: v_next.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
        von_mises: averages.iter().map(|a| von_mises(&a.0)).collect(),
        eqps: averages.iter().map(|a| a.1).collect(),
        stress: averages.into_iter().map(|a| a.0).collect(),
        plastic_strain_rate: (0..n_el)
            .map(|e| model.element_mean(e, |s| model.material.plastic_strain_rate(s)))
            .collect(),
        temperature: (0..n_el)
            .map(|e| model.element_mean(e, |s| model.material.temperature(s)))
            .collect(),
        contact_force: None,
    }
}
