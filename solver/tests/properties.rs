//! Property-based tests (proptest) on random inputs.
//!
//! - Random valid scenes (small meshes, short runs): no panic, no NaN, the impulse-momentum
//!   identity to round-off (an invariant of eqs. 19-20), the energy balance bounded (1 %:
//!   central differences on coarse meshes at cfl <= 0.9), or one of the two clear run errors
//!   a valid scene may meet - the contact law's maximum ("no root"), or an element inverted
//!   by a deformation far beyond small strain (e.g. 199 kg at 16 m/s on a 50 x 5 mm plate) -
//!   never garbage and never "unstable" (every step here is below the stable estimate).
//! - The random seed is fixed, so every run draws the same scenes (determinism); the
//!   regressions file replays the cases CI has found. 600 cases at two other seeds passed
//!   when the seed was fixed.
//! - Random and mutated YAML: a scene or an error message, never a panic.

use std::path::Path;

use impact_solver::scene::{ContactLawChoice, DtChoice, ElementKind, End, Load};
use impact_solver::{simulate, Error, Quiet, Scene};
use proptest::prelude::*;

const PLASTIC: &str = include_str!("../../verification/scenes/example-plastic.yaml");

fn base() -> Scene {
    let mut s = Scene::from_yaml(PLASTIC, Path::new("base.yaml")).unwrap();
    s.output.fields_every = None;
    s.output.every = Some(1e-4);
    s
}

prop_compose! {
    fn scenes()(
        nx in 4usize..16, half_ny in 1usize..4,
        element in prop::sample::select(vec![ElementKind::Q4Full, ElementKind::Q4Sri, ElementKind::Q4OnePoint]),
        plastic in any::<bool>(),
        thickness in 0.005f64..0.04, length in 0.05f64..0.4,
        mass in 0.05f64..200.0, velocity in 0.05f64..30.0,
        radius in 1e-3f64..0.1, law in 0usize..3,
        cfl in 0.1f64..0.9, tangent in 0.0f64..5e9,
        grading in 1.0f64..4.0, distortion in 0.0f64..0.3,
    ) -> Scene {
        let mut s = base();
        s.plate.thickness = thickness;
        s.plate.length = length;
        s.mesh.nx = nx;
        s.mesh.ny = 2 * half_ny;
        s.mesh.element = element;
        s.mesh.grading = grading;
        s.mesh.distortion = distortion;
        if !plastic {
            s.material.plasticity = None;
        } else if let Some(p) = &mut s.material.plasticity {
            p.hardening = impact_solver::scene::Hardening::Linear { tangent_modulus: tangent };
        }
        if let Load::Impactor(i) = &mut s.load {
            i.mass = mass;
            i.velocity = velocity;
            i.nose_radius = radius;
            i.contact_law = match law {
                0 => ContactLawChoice::Paper { length_unit: 1.0 },
                1 => ContactLawChoice::Paper { length_unit: 1e-3 },
                _ => ContactLawChoice::Johnson { datum_depth: 0.5 * thickness },
            };
        }
        s.output.probes = vec![("A".into(), [0.5 * length, 0.0])];
        s.time.dt = DtChoice::Cfl(cfl);
        s.time.end = End::AfterContact { after: 5e-5, limit: 2e-3 };
        s
    }
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20261123),
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_valid_scenes_keep_the_invariants(scene in scenes()) {
        match simulate(&scene, &mut Quiet) {
            Ok(o) => {
                let s = &o.summary;
                prop_assert!(o.history.values.iter().all(|x| x.is_finite()));
                prop_assert!(s.impulse_momentum_error.unwrap() < 1e-9, "{:e}", s.impulse_momentum_error.unwrap());
                prop_assert!(s.max_energy_balance_error < 1e-2, "{:e}", s.max_energy_balance_error);
            }
            Err(Error::Run { what, .. }) => {
                let clear = what.contains("no root") || what.contains("has inverted");
                prop_assert!(clear && !what.starts_with("unstable"), "unexpected run error: {}", what);
            }
            Err(e) => prop_assert!(false, "unexpected error: {e}"),
        }
    }

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,200}") {
        let _ = Scene::from_yaml(&text, Path::new("random.yaml"));
    }

    #[test]
    fn mutated_scenes_give_a_scene_or_a_message(cut in 0usize..PLASTIC.len(), insert in "[ -~\\n]{0,12}") {
        let mut text = PLASTIC.to_string();
        let at = (0..=cut).rev().find(|&i| text.is_char_boundary(i)).unwrap_or(0);
        text.insert_str(at, &insert);
        if let Err(e) = Scene::from_yaml(&text, Path::new("mutated.yaml")) {
            prop_assert!(e.to_string().starts_with("mutated.yaml"), "{e}");
        }
    }
}
