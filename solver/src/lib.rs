//! Explicit-dynamics solver for a clamped plate hit by a rigid line-nose impactor, after
//! Dokko & Kim (2004): 2-D plane strain, 4-node quads with lumped mass, central differences,
//! Hertz line contact solved each step, von Mises plasticity, energy bookkeeping.
//!
//! Read `ALGORITHM.md` (next to this crate's `Cargo.toml`) for the exact contract. The folders
//! follow the pipeline: [`input`] (the scene, validated; its cost estimated), [`mesh`],
//! [`lanes`] (the number types of the kernels, scalar and batched), [`physics`] (elements,
//! materials, impactor, contact, loads), [`kernels`] (the batched element kernels and their
//! assembly on threads), [`time_loop`] (the model factory, the
//! central-difference loop, its stable step, energies and recorder), [`output`] (files and
//! `summary.json`).

pub mod input;
pub mod kernels;
pub mod lanes;
pub mod mesh;
pub mod output;
pub mod physics;
pub mod time_loop;

// The modules' paths before the solver was grouped into folders, kept for the other crates.
pub use input::{budget, error, overrides, scene, yaml_field};
pub use kernels::{assembly, batch, elastic_screen, row_batches, stiffness, workers};
pub use lanes::{heap, real, simd};
pub use output::{out_dir, summary};
pub use physics::{
    axisymmetric, centroid, contact, contact_failure, element, finite_element, finite_material,
    geometry, impactor, kinematics, load, material, rate_plasticity,
};
pub use time_loop::{
    energy, history, integrator, internal_forces, interrupt, model, progress, stable_step,
};

use std::time::Instant;

pub use input::error::{Error, Result};
pub use input::scene::Scene;
pub use output::summary::Summary;
pub use time_loop::history::{History, HistorySink};
pub use time_loop::integrator::{Observer, Quiet};

use mesh::PlateMesh;
use physics::element::Formulation;
use physics::material::ConstitutiveModel;
use time_loop::integrator::PlateModel;

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
/// ([`input::budget::Estimate`]) exceeds `max_memory` bytes or, when None, the memory the machine has
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
        lanes::simd::KernelPath::fastest(),
    )
}

/// [`simulate_into`] with the element kernels on `path` (the scalar reference or a batched
/// instruction set: the results are the same bits).
pub fn simulate_on(
    scene: &Scene,
    observer: &mut dyn Observer,
    max_memory: Option<f64>,
    sink: &mut dyn HistorySink,
    path: lanes::simd::KernelPath,
) -> Result<(Summary, PlateMesh)> {
    let estimate = input::budget::Estimate::of(scene);
    let estimate = if sink.holds_rows() {
        estimate
    } else {
        estimate.streamed()
    };
    input::budget::check(scene, &estimate, max_memory)?;
    let started = Instant::now();
    let mesh = PlateMesh::of_scene(scene);
    let run = Run {
        scene,
        mesh: &mesh,
        started,
        observer,
        sink,
    };
    let summary =
        time_loop::model::build_on(scene, &mesh, time_loop::model::Kernel::Solver, path, run)
            .and_then(|r| r)
            .map_err(|e| with_extreme_inputs(scene, e))?;
    Ok((summary, mesh))
}

/// A run that failed on a scene holding inputs beyond any physical magnitude
/// ([`input::plausibility::extreme_fields`]) says so: whatever the failure's own words (an
/// element found degenerate, a contact law beyond its maximum), those inputs are its cause.
fn with_extreme_inputs(scene: &Scene, e: Error) -> Error {
    match e {
        Error::Run { step, time_s, what } => {
            let extreme = input::plausibility::extreme_inputs(scene);
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

impl time_loop::model::UseModel for Run<'_> {
    type Output = Result<Summary>;

    fn use_model<F: Formulation, M: ConstitutiveModel>(
        self,
        mut model: PlateModel<F, M>,
    ) -> Self::Output {
        let setup_done = Instant::now();
        let totals = time_loop::integrator::run(
            self.scene,
            self.mesh,
            &mut model,
            self.observer,
            self.sink,
        )?;
        let timing = output::summary::Timing {
            setup_s: (setup_done - self.started).as_secs_f64(),
            loop_s: setup_done.elapsed().as_secs_f64(),
            threads_fallback: model.assembly.threads_fallback(),
        };
        Ok(Summary::new(self.scene, self.mesh, &totals, timing))
    }
}
