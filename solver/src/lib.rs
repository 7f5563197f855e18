//! Explicit-dynamics solver for a clamped plate hit by a rigid line-nose impactor, after
//! Dokko & Kim (2004): 2-D plane strain, 4-node quads with lumped mass, central differences,
//! Hertz line contact solved each step, von Mises plasticity, energy bookkeeping.
//!
//! Read `ALGORITHM.md` (next to this crate's `Cargo.toml`) for the exact contract. Modules:
//! [`scene`] (input), [`mesh`], [`element`], [`material`], [`contact`], [`impactor`],
//! [`integrator`] (the time loop), [`energy`], [`summary`], [`output`] (files).

pub mod assembly;
pub mod budget;
pub mod contact;
pub mod contact_failure;
pub mod element;
pub mod energy;
pub mod error;
pub mod impactor;
pub mod integrator;
pub mod interrupt;
pub mod load;
pub mod material;
pub mod mesh;
pub mod out_dir;
pub mod output;
pub mod overrides;
pub mod progress;
pub mod scene;
pub mod stiffness;
pub mod summary;
pub mod yaml_field;

use std::time::Instant;

pub use error::{Error, Result};
pub use integrator::{History, Observer, Quiet};
pub use scene::Scene;
pub use summary::Summary;

use element::{Formulation, FullQ4, OnePointQ4, SelectiveQ4};
use integrator::PlateModel;
use material::{ConstitutiveModel, Elastic, VonMises};
use mesh::PlateMesh;
use scene::ElementKind;

/// Everything a run produces in memory.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub summary: Summary,
    pub history: History,
    pub mesh: PlateMesh,
}

/// Runs a validated scene.
pub fn simulate(scene: &Scene, observer: &mut dyn Observer) -> Result<Outcome> {
    let started = Instant::now();
    let mesh = PlateMesh::new(&scene.plate, &scene.mesh);
    let width = scene.plate.width;
    let elastic = Elastic::new(scene.material.youngs_modulus, scene.material.poisson_ratio);
    let run = Run {
        scene,
        mesh: &mesh,
        started,
    };
    let (summary, history) = match scene.mesh.element {
        ElementKind::Q4Full => run.with_formulation(FullQ4::new(&mesh.mesh, width)?, observer),
        ElementKind::Q4Sri => run.with_formulation(SelectiveQ4::new(&mesh.mesh, width)?, observer),
        ElementKind::Q4OnePoint => run.with_formulation(
            OnePointQ4::new(&mesh.mesh, width, scene.mesh.hourglass, elastic.p_modulus())?,
            observer,
        ),
    }?;
    Ok(Outcome {
        summary,
        history,
        mesh,
    })
}

struct Run<'a> {
    scene: &'a Scene,
    mesh: &'a PlateMesh,
    started: Instant,
}

impl Run<'_> {
    fn with_formulation<F: Formulation>(
        &self,
        formulation: F,
        observer: &mut dyn Observer,
    ) -> Result<(Summary, History)> {
        let m = &self.scene.material;
        let density = m.density;
        match VonMises::new(m) {
            Some(plastic) => {
                let model = PlateModel::new(formulation, plastic, self.mesh, density);
                self.with_model(model, observer)
            }
            None => {
                let elastic = Elastic::new(m.youngs_modulus, m.poisson_ratio);
                let model = PlateModel::new(formulation, elastic, self.mesh, density);
                let model = if F::STIFFNESS_MATRIX_PAYS {
                    model.with_linear_kernel(&self.mesh.mesh, &elastic)
                } else {
                    model
                };
                self.with_model(model, observer)
            }
        }
    }

    fn with_model<F: Formulation, M: ConstitutiveModel>(
        &self,
        mut model: PlateModel<F, M>,
        observer: &mut dyn Observer,
    ) -> Result<(Summary, History)> {
        let setup_done = Instant::now();
        let (history, totals) = integrator::run(self.scene, self.mesh, &mut model, observer)?;
        let timing = summary::Timing {
            setup_s: (setup_done - self.started).as_secs_f64(),
            loop_s: setup_done.elapsed().as_secs_f64(),
        };
        let summary = Summary::new(self.scene, self.mesh, &totals, timing);
        Ok((summary, history))
    }
}
