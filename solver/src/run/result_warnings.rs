//! What a run finds doubtful in its own results, said beside them (`summary.json`'s
//! `result_warnings`, printed after the summary): the results stand, the warning says how far
//! to trust them and what would make them better.

use crate::input::scene::{Enforcement, Scene};
use crate::time_loop::history::RunTotals;

/// The share of the energy put in (initial energy plus external work) above which the
/// kinematic surface contact's dissipation is called out. It is the inelastic landing of the
/// top nodes on the nose, a discretisation loss that falls as the mesh under the nose is
/// refined: 44 %, 16 %, 4.7 %, 1.2 % of a 0.1 kg striker's energy at 10 x 2, 20 x 4, 40 x 8 and
/// 80 x 16 on a 0.2 m steel plate (measured); 3.7e-4 on the paper's 18 kg impact at 80 x 16.
pub const KINEMATIC_LOSS_SHARE: f64 = 0.05;

/// The warnings of a finished run of `scene` with totals `t`.
pub fn result_warnings(scene: &Scene, t: &RunTotals) -> Vec<String> {
    let mut warnings = Vec::new();
    if let Some(i) = scene.surface_impactor() {
        let put_in = t.initial_energy.total() + t.final_energy.external_work.max(0.0);
        let lost = t.final_energy.contact;
        if i.contact.enforcement == Enforcement::Kinematic
            && put_in > 0.0
            && lost > KINEMATIC_LOSS_SHARE * put_in
        {
            warnings.push(format!(
                "the kinematic surface contact took {:.1} % of the energy put in ({lost:.4e} of {put_in:.4e} J, the contact_energy_J column): each top node that lands on the nose is stopped inelastically, a loss that falls as the mesh under the nose is refined (its nodes are heavy against the {} kg impactor here); refine the mesh under the nose (mesh.nx, mesh.ny), or use enforcement: penalty",
                100.0 * lost / put_in,
                crate::input::error::shown(i.mass)
            ));
        }
    }
    warnings
}
