//! An uncertainty study's declaration (issue 27, section 1): a scene, its uncertain inputs as
//! distributions with their source, the sampling, the outputs and their references. Read and
//! validated here like every other input (messages `file:line:col: field = value: what is
//! allowed`); the Python package samples, runs and analyses it (`impact.uq`).
//!
//! ```yaml
//! title: Table 1, elasto-plastic row
//! scene: ../scenes/paper-plastic.yaml            # relative to this file
//! set: {mesh.nx: 20, mesh.ny: 4}                # optional: fixed overrides of every run
//! inputs:                                         # dotted scene keys, as overrides
//!   material.youngs_modulus: {normal: {mean: 207.0e9, std: 6.21e9}, source: "..."}
//!   material.plasticity.yield_stress: {lognormal: {mean: 176.0e6, cov: 0.07}, source: "..."}
//!   plate.width: {uniform: {lower: 0.178, upper: 0.180}, source: "..."}
//!   plate.thickness: {truncated: {normal: {mean: 0.0188, std: 2.0e-4}, lower: 0.0182, upper: 0.0194}, source: "..."}
//! sampling: {method: sobol, seed: 27, sizes: [16, 32, 64]}   # or lhs; sizes: base samples N, doubling
//! #   optional mesh: 0.5: the sampled runs on that mesh level, S and u_num on the declared mesh
//! convergence: {mean: 0.002, std: 0.05, total_index: 0.05}   # allowed change from N/2 to N
//! mesh_levels: [0.25, 0.5, 1.0]                  # u_num: the GCI on the declared mesh (last level 1)
//! outputs:
//!   impulse_Ns: {table: {file: reference-data/paper/table1.csv, row: impulse, column: elasto_plastic}, kind: calibration}
//!   max_plate_displacement_m: {table: {...}, scale: -1.0e-3, kind: calibration}   # reference x scale = SI
//! ```
//!
//! Several scenes that share the inputs (Table 2's velocities) take `scenes:` instead of
//! `scene:`, each with its label and its row of the outputs' tables (the tables then give no
//! `row`); every output is then compared once per scene, all from one design of the inputs:
//!
//! ```yaml
//! scenes:
//!   - {scene: ../scenes/paper-table2/v01.25-plastic.yaml, label: "1.25 m/s", row: "1.25"}
//!   - {scene: ../scenes/paper-table2/v02.50-plastic.yaml, label: "2.5 m/s", row: "2.5"}
//! outputs:
//!   impulse_Ns: {table: {file: reference-data/paper/table2.csv, column: ep_impulse_Ns}, kind: calibration}
//! ```
//!
//! A study based on another, `based_on: {study: other.yaml, except: [keys]}`, takes that
//! study's inputs (validated where they are declared, that study's own base's included) less
//! the keys named, plus any `inputs:` of its own that it does not repeat; and its outputs when
//! it declares none. A chain of bases that comes back to a study is refused.
//!
//! The study is read in steps, each in its file beside this one: the file's keys as declared
//! ([`declaration`](crate::uq::declaration)), the [`scenes`](crate::uq::scenes), what a base
//! study shares ([`based_on`](crate::uq::based_on)), the [`outputs`](crate::uq::outputs) and
//! the [`sampling`](crate::uq::sampling) plan; their public items are re-exported here.

use std::path::Path;

use serde::Serialize;

use crate::definition::case::parse_located;
use crate::uq::based_on::{canonical, shared};
use crate::uq::declaration::STUDY_FILE;
use crate::uq::distribution::Input;
use crate::uq::outputs::outputs;
use crate::uq::sampling::{check_convergence, check_levels, check_sampling, check_sampling_mesh};
use crate::uq::scenes::{check_scene, scene_decls, InputPlaces};

pub use crate::uq::declaration::{
    BasedOn, Convergence, OutputFile, Sampling, SceneEntryFile, StudyFile, TableRefFile,
};
pub use crate::uq::outputs::{Output, TableRef};
pub use crate::uq::scenes::{MeshSize, StudyScene};

/// A validated study, as the Python package reads it (JSON).
#[derive(Debug, Clone, Serialize)]
pub struct Study {
    pub title: String,
    /// One or more scenes, sampled with the same design of the inputs.
    pub scenes: Vec<StudyScene>,
    pub set: impact_solver::overrides::Overrides,
    pub inputs: Vec<Input>,
    pub sampling: Sampling,
    pub convergence: Convergence,
    pub mesh_levels: Vec<f64>,
    /// Per scene (in order) the declared outputs (by key).
    pub outputs: Vec<Output>,
}

/// Reads and validates a study file.
pub fn read(path: &Path) -> Result<Study, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("{}: cannot read the study: {e}", path.display()))?;
    parse(&text, path)
}

/// Parses and validates a study's YAML text; `path` names it and resolves its scenes.
pub fn parse(text: &str, path: &Path) -> Result<Study, String> {
    let file: StudyFile = parse_located(text, path, STUDY_FILE).map_err(|e| e.to_string())?;
    let decls = scene_decls(&file, path)?;
    let set = file
        .set
        .as_ref()
        .map(|s| s.value.clone())
        .unwrap_or_default();
    let shared = shared(&file, path, &mut vec![canonical(path)])?;
    if shared.inputs.is_empty() {
        return Err(format!(
            "{}: inputs: the study declares no uncertain input",
            path.display()
        ));
    }
    if shared.outputs.is_empty() {
        return Err(format!(
            "{}: outputs: the study compares no output",
            path.display()
        ));
    }
    let places: InputPlaces = (shared.inputs.iter())
        .map(|(k, (_, l))| (k.clone(), l.clone()))
        .collect();
    let inputs: Vec<Input> = shared.inputs.into_values().map(|(i, _)| i).collect();
    let mut scenes = Vec::new();
    for d in &decls {
        scenes.push(check_scene(d, &file, &set, &inputs, &places, path)?);
    }
    check_sampling(&file.sampling, path)?;
    check_convergence(&file.convergence, path)?;
    check_levels(&file.mesh_levels, path)?;
    check_sampling_mesh(&file.sampling, &file.mesh_levels.value, path)?;
    let declared = (&shared.outputs, shared.outputs_file.as_path());
    let several = file.scenes.is_some();
    let outputs = outputs(declared, several, &decls, &scenes, path)?;
    Ok(Study {
        title: file.title,
        scenes,
        set,
        inputs,
        sampling: file.sampling.value,
        convergence: file.convergence.value,
        mesh_levels: file.mesh_levels.value,
        outputs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

    fn repo() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
    }

    /// A folder for test studies with `reference-data` beside them (a link to the repo's).
    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("uq-study-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::os::unix::fs::symlink(repo().join("reference-data"), dir.join("reference-data"))
            .unwrap();
        dir
    }

    fn scene(name: &str) -> String {
        repo()
            .join("verification/scenes")
            .join(name)
            .display()
            .to_string()
    }

    const TAIL: &str = "sampling: {method: sobol, seed: 1, sizes: [4, 8]}\n\
        convergence: {mean: 0.01, std: 0.1, total_index: 0.1}\n\
        mesh_levels: [0.25, 0.5, 1.0]\n";

    const WIDTH: &str =
        "inputs:\n  plate.width: {uniform: {lower: 0.178, upper: 0.180}, source: s}\n";

    fn two_scenes(row_a: &str, table_row: &str) -> String {
        format!(
            "title: t\nscenes:\n  - {{scene: {}, label: slow, row: {row_a}}}\n  - {{scene: {}, row: \"15\"}}\n{WIDTH}{TAIL}\
             outputs:\n  impulse_Ns: {{table: {{file: reference-data/paper/table2.csv, {table_row}column: ep_impulse_Ns}}, kind: calibration}}\n",
            scene("paper-table2/v01.25-plastic.yaml"),
            scene("paper-table2/v15.00-plastic.yaml"),
        )
    }

    fn parse_in(dir: &Path, name: &str, text: &str) -> Result<Study, String> {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        read(&path)
    }

    #[test]
    fn the_shipped_studies_read_and_share_their_inputs() {
        let uq = repo().join("verification/uq");
        let plastic = read(&uq.join("paper-plastic.yaml")).unwrap();
        let keys = |s: &Study| s.inputs.iter().map(|i| i.key.clone()).collect::<Vec<_>>();
        let elastic = read(&uq.join("paper-elastic.yaml")).unwrap();
        let ci = read(&uq.join("ci-coarse.yaml")).unwrap();
        assert_eq!(keys(&ci), keys(&plastic));
        assert_eq!(ci.outputs.len(), plastic.outputs.len());
        let no_plasticity: Vec<_> = keys(&plastic)
            .into_iter()
            .filter(|k| !k.starts_with("material.plasticity"))
            .collect();
        assert_eq!(keys(&elastic), no_plasticity);
        // each shared input keeps its distribution and where it is declared
        let e = &elastic.inputs[0];
        let p = plastic.inputs.iter().find(|i| i.key == e.key).unwrap();
        assert_eq!((&e.distribution, &e.at), (&p.distribution, &p.at));
        assert!(e.at.contains("paper-plastic.yaml:"), "{}", e.at);
        let surface = read(&uq.join("paper-elastic-surface.yaml")).unwrap();
        assert!(!keys(&surface).iter().any(|k| k.contains("contact_law")));
        assert_eq!(surface.outputs.len(), elastic.outputs.len());
        assert_eq!(surface.outputs[0].table.as_ref().unwrap().column, "elastic");
        for (name, column) in [
            ("table2-plastic", "ep_impulse_Ns"),
            ("table2-elastic", "elastic_impulse_Ns"),
        ] {
            let t2 = read(&uq.join(format!("{name}.yaml"))).unwrap();
            assert_eq!(t2.scenes.len(), 7);
            assert!(!keys(&t2)
                .iter()
                .any(|k| k.ends_with("mass") || k.ends_with("velocity")));
            let rows: Vec<_> = t2
                .outputs
                .iter()
                .map(|o| o.table.as_ref().unwrap().row.clone())
                .collect();
            assert_eq!(rows, ["1.25", "2.5", "5", "7.5", "10", "12.5", "15"]);
            assert!(t2
                .outputs
                .iter()
                .all(|o| o.table.as_ref().unwrap().column == column));
            assert_eq!(t2.outputs[6].id, "impulse_Ns [15 m/s]");
            assert_eq!(t2.outputs[6].scene, 6);
        }
    }

    #[test]
    fn several_scenes_give_one_output_per_scene_with_its_row() {
        let dir = folder("several");
        let s = parse_in(&dir, "s.yaml", &two_scenes("\"1.25\"", "")).unwrap();
        assert_eq!(s.scenes[0].label, "slow");
        assert_eq!(s.scenes[1].label, "v15.00-plastic");
        assert_eq!((s.scenes[1].mesh.nx, s.scenes[1].mesh.ny), (80, 16));
        let ids: Vec<_> = s.outputs.iter().map(|o| (o.id.as_str(), o.scene)).collect();
        assert_eq!(
            ids,
            [("impulse_Ns [slow]", 0), ("impulse_Ns [v15.00-plastic]", 1)]
        );
        assert_eq!(s.outputs[1].table.as_ref().unwrap().row, "15");
    }

    #[test]
    fn a_bad_declaration_of_scenes_names_its_place() {
        let dir = folder("bad-scenes");
        let cases = [
            // a row the table does not have: the output's place and the file
            (
                two_scenes("\"3\"", ""),
                "s.yaml:3:13: scenes[0].row = 3 (outputs.impulse_Ns): ",
                "table2.csv: no row",
            ),
            // a row on the output of a study of several scenes
            (
                two_scenes("\"1.25\"", "row: \"1.25\", "),
                "s.yaml:11:15: outputs.impulse_Ns.table.row = 1.25",
                "each scene gives its row",
            ),
            // a scene without its row
            (
                two_scenes("\"1.25\"", "").replace(", row: \"15\"", ""),
                "s.yaml:4:13: scenes[1].row: missing",
                "table2.csv",
            ),
            // both forms
            (
                format!("title: t\nscene: {}\n", scene("paper-plastic.yaml"))
                    + &two_scenes("\"1.25\"", "")[9..],
                "s.yaml:4:3: scenes: give either",
                "",
            ),
            // an empty list
            (
                format!("title: t\nscenes: []\n{WIDTH}{TAIL}outputs: {{impulse_Ns: {{}}}}\n"),
                "s.yaml:2:9: scenes = []",
                "",
            ),
        ];
        for (text, want, also) in cases {
            let e = parse_in(&dir, "s.yaml", &text).unwrap_err();
            let e = e.replace(&format!("{}/", dir.display()), "");
            assert!(
                e.starts_with(want) && e.contains(also),
                "{e}\nwanted {want} ... {also}"
            );
        }
    }

    #[test]
    fn based_on_shares_inputs_and_refuses_what_it_cannot_share() {
        let dir = folder("based-on");
        let base = format!(
            "title: base\nscene: {}\ninputs:\n  plate.width: {{uniform: {{lower: 0.178, upper: 0.180}}, source: s}}\n  \
             plate.thickness: {{uniform: {{lower: 0.018, upper: 0.019}}, source: s}}\n{TAIL}outputs: {{impulse_Ns: {{}}}}\n",
            scene("paper-plastic.yaml")
        );
        std::fs::write(dir.join("base.yaml"), base).unwrap();
        let head = format!("title: t\nscene: {}\n", scene("paper-plastic.yaml"));
        let ok = parse_in(
            &dir,
            "a.yaml",
            &format!("{head}based_on: {{study: base.yaml, except: [plate.thickness]}}\n{TAIL}"),
        )
        .unwrap();
        assert_eq!(ok.inputs.len(), 1);
        assert_eq!(ok.outputs[0].id, "impulse_Ns");
        assert!(
            ok.inputs[0].at.ends_with("base.yaml:4:16"),
            "{}",
            ok.inputs[0].at
        );
        let cases = [
            (
                format!("{head}based_on: {{study: base.yaml, except: [plate.length]}}\n{TAIL}"),
                "a.yaml:3:39: based_on.except = plate.length: is not an input of",
            ),
            (
                format!("{head}based_on: {{study: base.yaml}}\n{WIDTH}{TAIL}"),
                "a.yaml:5:16: inputs.plate.width: also an input of based_on.study",
            ),
            (
                format!("{head}based_on: {{study: a.yaml}}\n{TAIL}"),
                "a.yaml:3:19: based_on.study = ",
            ),
            (
                format!("{head}based_on: {{study: missing.yaml}}\n{TAIL}"),
                "a.yaml:3:19: based_on.study = ",
            ),
        ];
        for (text, want) in cases {
            let e = parse_in(&dir, "a.yaml", &text).unwrap_err();
            let e = e.replace(&format!("{}/", dir.display()), "");
            assert!(e.starts_with(want), "{e}\nwanted {want}");
        }
        let e = parse_in(
            &dir,
            "a.yaml",
            &format!("{head}based_on: {{study: a.yaml}}\n{TAIL}"),
        )
        .unwrap_err();
        assert!(e.contains("already on this chain"), "{e}");
    }

    #[test]
    fn the_sampling_mesh_is_a_coarser_declared_level() {
        let dir = folder("sampling-mesh");
        let study = |mesh: &str| {
            format!(
                "title: t\nscene: {}\n{WIDTH}sampling: {{method: sobol, seed: 1, sizes: [4, 8]{mesh}}}\n\
                 convergence: {{mean: 0.01, std: 0.1, total_index: 0.1}}\nmesh_levels: [0.25, 0.5, 1.0]\n\
                 outputs: {{impulse_Ns: {{}}}}\n",
                scene("paper-plastic.yaml")
            )
        };
        let ok = parse_in(&dir, "m.yaml", &study(", mesh: 0.5")).unwrap();
        assert_eq!(ok.sampling.mesh, Some(0.5));
        assert_eq!(
            parse_in(&dir, "m.yaml", &study("")).unwrap().sampling.mesh,
            None
        );
        for bad in [", mesh: 0.3", ", mesh: 1.0"] {
            let e = parse_in(&dir, "m.yaml", &study(bad)).unwrap_err();
            let e = e.replace(&format!("{}/", dir.display()), "");
            assert!(
                e.starts_with("m.yaml:5:11: sampling.mesh = ") && e.contains("below 1"),
                "{e}"
            );
        }
    }
}
