//! `impact verify --results-from DIR`: a scene's run read from `DIR/<suite>/<case>/<scene>/`
//! (the adapter contract's files), for a code with no adapter. A scene with no folder is
//! *not produced* (N/E), not FAIL; a folder with missing or malformed files is an error that
//! names the file.

use std::path::Path;

use impact_solver::Scene;

use super::NOT_PRODUCED;
use crate::definition::run_data::RunData;

/// The run of the first of `names` (suite, case, scene: every case and scene that uses this
/// job) that has a folder under `dir`.
pub fn read(
    dir: &Path,
    names: &[(String, String, String)],
    scene: &Scene,
) -> Result<RunData, String> {
    for (suite, case, name) in names {
        let folder = dir.join(suite).join(case).join(name);
        if folder.is_dir() {
            return super::contract::read_run(&folder, Some(scene));
        }
    }
    let wanted: Vec<String> = names
        .iter()
        .map(|(s, c, n)| format!("{s}/{c}/{n}"))
        .collect();
    Err(format!(
        "{NOT_PRODUCED}no folder {} under {}",
        wanted.join(" or "),
        dir.display()
    ))
}
