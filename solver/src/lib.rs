//! Explicit-dynamics solver for a clamped plate hit by a rigid line-nose impactor, after
//! Dokko & Kim (2004): 2-D plane strain, 4-node quads with lumped mass, central differences,
//! Hertz line contact solved each step, von Mises plasticity, energy bookkeeping.
//!
//! Read `ALGORITHM.md` (next to this crate's `Cargo.toml`) for the exact contract. Modules:
//! [`scene`] (input), [`mesh`], [`element`], [`material`], [`contact`], [`impactor`],
//! [`model`] (element x material x kernel), [`integrator`] (the time loop), [`history`] (what
//! the loop records), [`energy`],
//! [`summary`], [`output`] (files).

pub mod assembly;
pub mod batch;
pub mod budget;
pub mod centroid;
pub mod contact;
pub mod contact_failure;
pub mod elastic_screen;
pub mod element;
pub mod energy;
pub mod error;
pub mod geometry;
pub mod heap;
pub mod history;
pub mod impactor;
pub mod integrator;
pub mod internal_forces;
pub mod interrupt;
pub mod load;
pub mod material;
pub mod mesh;
pub mod model;
pub mod out_dir;
pub mod output;
pub mod overrides;
pub mod progress;
pub mod real;
pub mod row_batches;
pub mod scene;
pub mod simd;
pub mod stable_step;
pub mod stiffness;
pub mod summary;
pub mod workers;
pub mod yaml_field;

use std::time::Instant;

pub use error::{Error, Result};
pub use history::{History, HistorySink};
pub use integrator::{Observer, Quiet};
pub use scene::Scene;
pub use summary::Summary;

use element::Formulation;
use integrator::PlateModel;
use material::ConstitutiveModel;
use mesh::PlateMesh;

/// Everything a run produces in memory.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub summary: Summary,
    /// Every row, or only the column names when the rows were streamed to a file
    /// ([`output::RunOptions::keep_history`]).
    pub history: History,
    pub mesh: PlateMesh,
}

/// Runs a validated scene.
pub fn simulate(scene: &Scene, observer: &mut dyn Observer) -> Result<Outcome> {
    simulate_within(scene, observer, None)
}

/// [`simulate`] refusing, before anything is allocated, a scene whose memory estimate
/// ([`budget::Estimate`]) exceeds `max_memory` bytes or, when None, the memory the machine has
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
    simulate_on(
        scene,
        observer,
        max_memory,
        sink,
        simd::KernelPath::fastest(),
    )
}

/// [`simulate_into`] with the element kernels on `path` (the scalar reference or a batched
/// instruction set: the results are the same bits).
pub fn simulate_on(
    scene: &Scene,
    observer: &mut dyn Observer,
    max_memory: Option<f64>,
    sink: &mut dyn HistorySink,
    path: simd::KernelPath,
) -> Result<(Summary, PlateMesh)> {
    let estimate = budget::Estimate::of(scene);
    let estimate = if sink.holds_rows() {
        estimate
    } else {
        estimate.streamed()
    };
    budget::check(scene, &estimate, max_memory)?;
    let started = Instant::now();
    let mesh = PlateMesh::new(&scene.plate, &scene.mesh);
    let run = Run {
        scene,
        mesh: &mesh,
        started,
        observer,
        sink,
    };
    let summary = model::build_on(scene, &mesh, model::Kernel::Solver, path, run)??;
    Ok((summary, mesh))
}

/// The time loop of a run, on whatever model the factory built.
struct Run<'a> {
    scene: &'a Scene,
    mesh: &'a PlateMesh,
    started: Instant,
    observer: &'a mut dyn Observer,
    sink: &'a mut dyn HistorySink,
}

impl model::UseModel for Run<'_> {
    type Output = Result<Summary>;

    fn use_model<F: Formulation, M: ConstitutiveModel>(
        self,
        mut model: PlateModel<F, M>,
    ) -> Self::Output {
        let setup_done = Instant::now();
        let totals = integrator::run(self.scene, self.mesh, &mut model, self.observer, self.sink)?;
        let timing = summary::Timing {
            setup_s: (setup_done - self.started).as_secs_f64(),
            loop_s: setup_done.elapsed().as_secs_f64(),
        };
        Ok(Summary::new(self.scene, self.mesh, &totals, timing))
    }
}
