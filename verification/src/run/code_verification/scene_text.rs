//! A builtin's scene written as YAML text, run on the solver's own time loop.

/// Runs a builtin's scene, written as YAML `text` (`name` stands for the file in messages),
/// on the solver's own time loop with `observer`: the outcome, or the error's message.
pub(crate) fn run_scene_text(
    text: &str,
    name: &str,
    observer: &mut dyn impact_solver::Observer,
) -> Result<impact_solver::Outcome, String> {
    let scene = impact_solver::Scene::from_yaml(text, std::path::Path::new(name))
        .map_err(|e| e.to_string())?;
    impact_solver::simulate(&scene, observer).map_err(|e| e.to_string())
}
