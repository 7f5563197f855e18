//! Builtin computations, a registry by name: unit checks of the solver's public contact,
//! impactor and element API, and the solver against closed-form reference solutions (beam
//! theory, modal superposition, plane waves: `impact_analytical`). Each returns named metrics
//! (and histories) for the checks to read. The code-verification builtins
//! (`crate::run::code_verification`) are found through the same names. A builtin with a
//! problem form ([`ProblemForm`]) runs on another code too: its problem solved by the code's
//! adapter, its metrics from the code's fields.

use crate::codes::problem::{Fields, Problem};
use crate::codes::{Adapter, Code};
use crate::definition::run_data::RunData;
use crate::run::builtin_params::Params;
use crate::run::code_verification::{
    axisymmetric_problems, column_impact, hertz_line_problem, macneal_harder, plastic_path_problem,
};
use impact_solver::Scene;

mod beam_bending;
mod contact_law;
mod impactor;
mod modal_beam;
mod patch;
mod plane_wave;

type Builtin = fn(&Params) -> Result<RunData, String>;

/// Every builtin of this module by the name a case's `builtin:` gives.
const REGISTRY: [(&str, Builtin); 6] = [
    ("hertz-law", contact_law::hertz_law),
    ("impactor-kinematics", impactor::impactor_kinematics),
    ("patch", patch::patch),
    ("beam-bending", beam_bending::beam_bending),
    ("modal-beam", modal_beam::modal_beam),
    ("plane-wave", plane_wave::plane_wave),
];

/// A builtin another code can compute, and how: its problems (`crate::codes::problem`) or its
/// scene (the adapter's scene contract), with its metrics from what the code gives back.
pub enum ProblemForm {
    /// Static problems, each with a label that names it (`a`, `b`; a single problem's label is
    /// empty), and the metrics from the code's fields, one per problem in the same order (a
    /// path problem's, one per load factor, in its place).
    Problems {
        problems: fn(&Params) -> Result<Vec<(&'static str, Problem)>, String>,
        evaluate: fn(&Params, &[Fields]) -> Result<RunData, String>,
    },
    /// A scene the builtin runs on the solver's own time loop, and the metrics from a run of
    /// it (its history and summary).
    Scene {
        scene: fn(&Params) -> Result<Scene, String>,
        evaluate: fn(&Params, &RunData) -> Result<RunData, String>,
    },
}

/// The builtins with a problem form, by name.
const PROBLEMS: [(&str, ProblemForm); 6] = [
    (
        "patch",
        ProblemForm::Problems {
            problems: patch::patch_problems,
            evaluate: patch::patch_from_fields,
        },
    ),
    (
        "axisymmetric",
        ProblemForm::Problems {
            problems: axisymmetric_problems::problems,
            evaluate: axisymmetric_problems::from_fields,
        },
    ),
    (
        "macneal-harder-patch",
        ProblemForm::Problems {
            problems: macneal_harder::problems,
            evaluate: macneal_harder::from_fields,
        },
    ),
    (
        "plastic-strain-path",
        ProblemForm::Problems {
            problems: plastic_path_problem::problems,
            evaluate: plastic_path_problem::from_fields,
        },
    ),
    (
        "hertz-line",
        ProblemForm::Problems {
            problems: hertz_line_problem::problems,
            evaluate: hertz_line_problem::from_fields,
        },
    ),
    (
        "column-impact",
        ProblemForm::Scene {
            scene: column_impact::column_scene,
            evaluate: column_impact::column_from_run,
        },
    ),
];

/// The problem form of builtin `name`, if it has one.
pub fn problem_form(name: &str) -> Option<&'static ProblemForm> {
    PROBLEMS.iter().find(|(n, _)| *n == name).map(|(_, f)| f)
}

/// Whether `code` computes builtin `name` (through its adapter, [`run_on`]): an adapter does
/// for a builtin with a problem form; otherwise the builtin is `impact`'s own computation.
pub fn runs_on(code: &Code, name: &str) -> bool {
    matches!(code, Code::Adapter(_)) && problem_form(name).is_some()
}

/// Builtin `name` computed by another code's `adapter`, evaluated as the builtin evaluates
/// its own run (`None` when it has no problem form: it runs in-process). The run keeps the
/// adapter's record (of the first problem) and the files of every problem (named by the
/// label when there are several); no cost, as `impact`'s builtins have none.
pub fn run_on(adapter: &Adapter, name: &str, p: &Params) -> Option<Result<RunData, String>> {
    let run = match problem_form(name)? {
        ProblemForm::Problems { problems, evaluate } => {
            (|| solve_problems(adapter, name, p, problems(p)?, *evaluate))()
        }
        ProblemForm::Scene { scene, evaluate } => (|| {
            let code_run = adapter.run(&scene(p)?)?;
            let mut run = evaluate(p, &code_run)?;
            (run.info, run.files) = (code_run.info, code_run.files);
            Ok(run)
        })(),
    };
    Some(run.map(|mut run| {
        labelled(&mut run, name, p);
        run
    }))
}

/// The `problems` of builtin `name` solved by `adapter`, the metrics by `evaluate`.
fn solve_problems(
    adapter: &Adapter,
    name: &str,
    p: &Params,
    problems: Vec<(&'static str, Problem)>,
    evaluate: fn(&Params, &[Fields]) -> Result<RunData, String>,
) -> Result<RunData, String> {
    let mut fields = Vec::new();
    let mut run = RunData::default();
    for (k, (label, problem)) in problems.iter().enumerate() {
        let (f, r) = adapter.run_problem(&format!("{name} {label}"), problem)?;
        fields.extend(f);
        if k == 0 {
            run.info = r.info;
        }
        let prefix = if problems.len() > 1 {
            format!("{label}-")
        } else {
            String::new()
        };
        run.files.extend(
            r.files
                .into_iter()
                .map(|(n, b)| (format!("{prefix}{n}"), b)),
        );
    }
    let evaluated = evaluate(p, &fields)?;
    run.metrics = evaluated.metrics;
    run.histories = evaluated.histories;
    Ok(run)
}

/// Names the builtin and its parameters in the run's info.
fn labelled(d: &mut RunData, name: &str, p: &Params) {
    d.info.insert("builtin".into(), name.to_string());
    for (k, v) in p {
        d.info.insert(format!("param {k}"), v.to_string());
    }
}

/// The names a case may give, the code-verification builtins included.
pub fn names() -> impl Iterator<Item = &'static str> + Clone {
    REGISTRY
        .iter()
        .map(|(n, _)| *n)
        .chain(crate::run::code_verification::NAMES)
}

/// Runs the builtin `name` with its parameters; its metrics and histories name it and them.
pub fn run(name: &str, p: &Params) -> Result<RunData, String> {
    let mut d = match REGISTRY.iter().find(|(n, _)| *n == name) {
        Some((_, builtin)) => builtin(p),
        None => crate::run::code_verification::run(name, p)
            .unwrap_or_else(|| Err(format!("unknown builtin {name:?}"))),
    }?;
    labelled(&mut d, name, p);
    Ok(d)
}
