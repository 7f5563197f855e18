//! Explicit-dynamics solver for a clamped plate hit by a rigid line-nose impactor, after
//! Dokko & Kim (2004): 2-D plane strain, 4-node quads with lumped mass, central differences,
//! Hertz line contact solved each step, von Mises plasticity, energy bookkeeping.
//!
//! Read `ALGORITHM.md` (next to this crate's `Cargo.toml`) for the exact contract. Modules:
//! [`scene`] (input), [`mesh`], [`element`], [`material`], [`contact`], [`impactor`],
//! [`model`] (element x material x kernel), [`integrator`] (the time loop), [`energy`],
//! [`summary`], [`output`] (files).

pub mod assembly;
pub mod budget;
pub mod contact;
pub mod contact_failure;
pub mod elastic_screen;
pub mod element;
pub mod energy;
pub mod error;
pub mod impactor;
pub mod integrator;
pub mod interrupt;
pub mod load;
pub mod material;
pub mod mesh;
pub mod model;
pub mod out_dir;
pub mod output;
pub mod overrides;
pub mod progress;
pub mod scene;
pub mod stable_step;
pub mod stiffness;
pub mod summary;
pub mod yaml_field;

use std::time::Instant;

pub use error::{Error, Result};
pub use integrator::{History, Observer, Quiet};
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
    budget::check(scene, &budget::Estimate::of(scene), max_memory)?;
    let started = Instant::now();
    let mesh = PlateMesh::new(&scene.plate, &scene.mesh);
    let run = Run {
        scene,
        mesh: &mesh,
        started,
        observer,
    };
    let (summary, history) = model::build(scene, &mesh, model::Kernel::Solver, run)??;
    Ok(Outcome {
        summary,
        history,
        mesh,
    })
}

/// The time loop of a run, on whatever model the factory built.
struct Run<'a> {
    scene: &'a Scene,
    mesh: &'a PlateMesh,
    started: Instant,
    observer: &'a mut dyn Observer,
}

impl model::UseModel for Run<'_> {
    type Output = Result<(Summary, History)>;

    fn use_model<F: Formulation, M: ConstitutiveModel>(
        self,
        mut model: PlateModel<F, M>,
    ) -> Self::Output {
        let setup_done = Instant::now();
        let (history, totals) = integrator::run(self.scene, self.mesh, &mut model, self.observer)?;
        let timing = summary::Timing {
            setup_s: (setup_done - self.started).as_secs_f64(),
            loop_s: setup_done.elapsed().as_secs_f64(),
        };
        let summary = Summary::new(self.scene, self.mesh, &totals, timing);
        Ok((summary, history))
    }
}
