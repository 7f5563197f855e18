//! The rigid-plastic numbers of an elasto-plastic impact run (issue 27, section 3; closed forms
//! in `impact_analytical::rigid_plastic`, after Jones, *Structural Impact*): the energy ratio,
//! the band on the maximum mid-span displacement, and the plastic work that cannot come from a
//! mechanism. They are properties of the scene (its plate, material and impactor), except the
//! local dissipation, which reads the run's plastic work.

use impact_analytical::beam::ClampedBeam;
use impact_analytical::rigid_plastic::BeamImpact;
use impact_solver::scene::{Ends, Hardening, Scene};

/// The metric names, all prefixed `rigid_plastic_`: the closed forms of the scene (carried
/// over to a rigid wall in the discriminating-power table, since they do not depend on the run).
pub const SCENE_KEYS: [&str; 6] = [
    "rigid_plastic_collapse_load_N",
    "rigid_plastic_elastic_energy_J",
    "rigid_plastic_energy_ratio",
    "rigid_plastic_estimate_m",
    "rigid_plastic_lower_m",
    "rigid_plastic_upper_m",
];

/// The slope of the flow stress against the plastic strain, Pa: `E E_t / (E - E_t)` for
/// linear hardening (E_t the tangent of the uniaxial curve), the first segment's for a table,
/// the secant over the first 1 % of plastic strain for a power law (`B k^n`, whose tangent is
/// infinite at 0). The rate law, if any, is left out: the bands are the static ones.
fn hardening_modulus(h: &Hardening, youngs_modulus: f64) -> f64 {
    match h {
        Hardening::Linear { tangent_modulus } => {
            youngs_modulus * tangent_modulus / (youngs_modulus - tangent_modulus)
        }
        Hardening::Table(rows) => match rows.as_slice() {
            [(e0, s0), (e1, s1), ..] if e1 > e0 => (s1 - s0) / (e1 - e0),
            _ => 0.0,
        },
        Hardening::Power {
            coefficient,
            exponent,
        } => coefficient * 0.01f64.powf(*exponent) / 0.01,
    }
}

/// The impact of `scene` as a clamped beam struck by a mass, when it is one: an impactor on an
/// elasto-plastic plate with clamped ends.
pub fn beam_impact(scene: &Scene) -> Option<BeamImpact> {
    let p = scene.material.plasticity.as_ref()?;
    let (mass, velocity) = scene.impactor_motion()?;
    if scene.plate.ends != Ends::Clamped {
        return None;
    }
    let m = &scene.material;
    let beam = ClampedBeam::new(
        scene.plate.length,
        scene.plate.width,
        scene.plate.thickness,
        m.youngs_modulus,
        m.poisson_ratio,
    )
    .ok()?;
    let hardening = hardening_modulus(&p.hardening, m.youngs_modulus);
    BeamImpact::new(beam, m.density, p.yield_stress, hardening, mass, velocity).ok()
}

/// The metrics of a run of `scene` whose plastic work at the end is `plastic_work` (J): the
/// [`SCENE_KEYS`], and `rigid_plastic_local_dissipation_J`, the plastic work no mechanism can
/// take: all of it below an energy ratio of 1 (no mechanism forms), else what exceeds the
/// energy left once the elastic energy at collapse is stored, `max(0, W_p - (K - U_c))`.
pub fn metrics(scene: &Scene, plastic_work: f64) -> Vec<(&'static str, f64)> {
    let Some(impact) = beam_impact(scene) else {
        return Vec::new();
    };
    let b = impact.bounds();
    let available = impact.kinetic_energy() - b.elastic_energy_at_collapse;
    let local = if b.energy_ratio < 1.0 {
        plastic_work
    } else {
        (plastic_work - available).max(0.0)
    };
    let values = [
        b.collapse_load,
        b.elastic_energy_at_collapse,
        b.energy_ratio,
        b.estimate,
        b.lower,
        b.upper,
    ];
    let mut out: Vec<(&'static str, f64)> = SCENE_KEYS.into_iter().zip(values).collect();
    out.push(("rigid_plastic_local_dissipation_J", local));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_plastic_scene_is_a_beam_impact_and_the_elastic_one_is_not() {
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
        let plastic = Scene::from_file(&root.join("paper-plastic.yaml")).unwrap();
        let m: std::collections::BTreeMap<_, _> = metrics(&plastic, 838.7).into_iter().collect();
        assert!(m["rigid_plastic_energy_ratio"] > 10.0, "{m:?}");
        assert!(m["rigid_plastic_lower_m"] < 4.877e-3 && 4.877e-3 < m["rigid_plastic_upper_m"]);
        assert_eq!(m["rigid_plastic_local_dissipation_J"], 0.0);
        let elastic = Scene::from_file(&root.join("paper-elastic.yaml")).unwrap();
        assert!(metrics(&elastic, 0.0).is_empty());
    }
}
