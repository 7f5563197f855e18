//! A run: a validated scene simulated in memory ([`simulate`] and its variants), what it
//! produces ([`Outcome`]) and its scalars, `summary.json` ([`summary`]). The files of a run
//! ([`crate::output`]) are written around these.

use std::time::Instant;

use crate::input::error::{Error, Result};
use crate::input::scene::Scene;
use crate::lanes::simd::KernelPath;
use crate::mesh::PlateMesh;
use crate::physics::elements::element::Formulation;
use crate::physics::materials::material::ConstitutiveModel;
use crate::time_loop::history::{History, HistorySink};
use crate::time_loop::integrator;
use crate::time_loop::model::{self, Kernel, UseModel};
use crate::time_loop::observer::Observer;
use crate::time_loop::plate_model::PlateModel;

pub mod result_warnings;
pub mod summary;

use summary::{Summary, Timing};

/// Everything a run produces in memory.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub summary: Summary,
    /// Every row, or only the column names when the rows were streamed to a file
    /// ([`crate::output::RunOptions::keep_history`]).
    pub history: History,
    pub mesh: PlateMesh,
}

/// Runs a validated scene.
pub fn simulate(scene: &Scene, observer: &mut dyn Observer) -> Result<Outcome> {
    simulate_within(scene, observer, None)
}

/// [`simulate`] refusing, before anything is allocated, a scene whose memory estimate
/// ([`crate::input::budget::Estimate`]) exceeds `max_memory` bytes or, when None, the memory the machine has
/// available: every run is protected, the CLI's, the harness's and the Python package's.
pub fn simulate_within(
    scene: &Scene,
    observer: &mut dyn Observer,
    max_memory: Option<f64>,
) -> Result<Outcome> {
    let mut history = History::default();
    let (summary, mesh) = simulate_into(scene, observer, max_memory, &mut history)?;
    Ok(Outcome {
        summary,
        history,
        mesh,
    })
}

/// [`simulate_within`] sending the history rows to `sink` as they are produced (e.g. a file,
/// so that memory does not grow with the run's length) instead of holding them.
pub fn simulate_into(
    scene: &Scene,
    observer: &mut dyn Observer,
    max_memory: Option<f64>,
    sink: &mut dyn HistorySink,
) -> Result<(Summary, PlateMesh)> {
    simulate_on(scene, observer, max_memory, sink, KernelPath::fastest())
}

/// [`simulate_into`] with the element kernels on `path` (the scalar reference or a batched
/// instruction set: the results are the same bits).
pub fn simulate_on(
    scene: &Scene,
    observer: &mut dyn Observer,
    max_memory: Option<f64>,
    sink: &mut dyn HistorySink,
    path: KernelPath,
) -> Result<(Summary, PlateMesh)> {
    let estimate = crate::input::estimate::budget::Estimate::of(scene);
    let estimate = if sink.holds_rows() {
        estimate
    } else {
        estimate.streamed()
    };
    crate::input::estimate::budget::check(scene, &estimate, max_memory)?;
    let started = Instant::now();
    let mesh = PlateMesh::of_scene(scene);
    let run = Run {
        scene,
        mesh: &mesh,
        started,
        observer,
        sink,
    };
    let summary = model::build_on(scene, &mesh, Kernel::Solver, path, run)
        .and_then(|r| r)
        .map_err(|e| with_extreme_inputs(scene, e))?;
    Ok((summary, mesh))
}

/// A run that failed on a scene holding inputs beyond any physical magnitude
/// ([`crate::input::plausibility::extreme_fields`]) says so: whatever the failure's own words (an
/// element found degenerate, a contact law beyond its maximum), those inputs are its cause.
fn with_extreme_inputs(scene: &Scene, e: Error) -> Error {
    match e {
        Error::Run { step, time_s, what } => {
            let extreme = crate::input::estimate::measures::extreme_inputs(scene);
            let what = if extreme.is_empty() || what.contains("because of") {
                what
            } else {
                format!(
                    "{what} (the scene holds {}: beyond any physical value of this problem in SI units; give a physical value)",
                    extreme.join(", ")
                )
            };
            Error::Run { step, time_s, what }
        }
        other => other,
    }
}

/// The time loop of a run, on whatever model the factory built.
struct Run<'a> {
    scene: &'a Scene,
    mesh: &'a PlateMesh,
    started: Instant,
    observer: &'a mut dyn Observer,
    sink: &'a mut dyn HistorySink,
}

impl UseModel for Run<'_> {
    type Output = Result<Summary>;

    fn use_model<F: Formulation, M: ConstitutiveModel>(
        self,
        mut model: PlateModel<F, M>,
    ) -> Self::Output {
        let setup_done = Instant::now();
        let totals = integrator::run(self.scene, self.mesh, &mut model, self.observer, self.sink)?;
        let timing = Timing {
            setup_s: (setup_done - self.started).as_secs_f64(),
            loop_s: setup_done.elapsed().as_secs_f64(),
            threads_fallback: model.assembly.threads_fallback(),
        };
        Ok(Summary::new(self.scene, self.mesh, &totals, timing))
    }
}
