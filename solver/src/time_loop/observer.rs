//! What a run tells while it goes on: field frames ([`FieldFrame`]) and progress to an
//! [`Observer`], which may also stop it.

use crate::input::error::Result;
use crate::physics::elements::element::Formulation;
use crate::physics::materials::material::{von_mises, ConstitutiveModel, Stress};
use crate::time_loop::plate_model::PlateModel;

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
    /// [`crate::Error::Interrupted`].
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

/// The field frame of `model` at `t` (s): displacements `u` (m), velocities `v_next` (m/s)
/// and the elements' average stresses and states.
pub(crate) fn field_frame<F: Formulation, M: ConstitutiveModel>(
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
