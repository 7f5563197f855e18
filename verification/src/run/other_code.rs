//! A check's row on another code (issue 38): the same check, reference and tolerance, and
//! rules of its own. A check that measures `impact`'s own computation (a builtin: a
//! kernel, a manufactured solution) is *not expressible* (N/E) on another code, unless the
//! builtin's problem was the code's to solve (`crate::codes::problem`); so is one
//! that reads a scene the code refused (its adapter's exit status 3, or no folder under
//! `--results-from`), and one that reads a column or key the code did not write (*not
//! produced*), and one whose reference is the same code's own stored run (kind `other
//! code`). The known failures are the code's own (its adapter's `expected`), never the
//! case's, which are `impact`'s.

use std::collections::{BTreeMap, BTreeSet};

use crate::codes::{is_not_expressible, Code};
use crate::definition::case::{Case, CheckFile, MeasureFile, RefKind};
use crate::definition::check::{CheckResult, Status};
use crate::definition::run_data::JobResult;

/// Rewrites `r` (check `k` of `case`, evaluated on the code `on`'s `results`) by the rules above;
/// `expected`: the code's known failures, `suite/case/check` -> reason.
pub fn judge(
    r: &mut CheckResult,
    k: &CheckFile,
    case: &Case,
    results: &BTreeMap<String, JobResult>,
    on: &Code,
    expected: &BTreeMap<String, String>,
) {
    let name = on.name();
    let code = name.as_str();
    r.known_failure = expected
        .get(&format!("{}/{}/{}", case.suite, case.name, k.id))
        .cloned();
    // A code compared with its own stored run proves nothing about either.
    let own = k.reference.as_ref().and_then(|r| {
        let r = &r.value;
        (r.kind == Some(RefKind::OtherCode) && r.code.as_deref() == Some(code)).then(|| {
            format!("not expressible: the reference is {code}'s own stored run, not another code's")
        })
    });
    let mut read = Vec::new();
    scenes_read(&k.measure.value, case.default_scene(), results, &mut read);
    let builtin = read.iter().find_map(|name| {
        let b = case.file.scenes.get(name)?.value.builtin.as_deref()?;
        (!crate::run::builtins::runs_on(on, b)).then(|| {
            format!("not expressible: measures impact's own computation (builtin {name}), not a run of {code}")
        })
    });
    // A reference the same code computes from a scene it refused is not expressible either
    // (a surface coupling compared with the nodal one on the same plate); a builtin's
    // reference (a closed form, a modal solution) stays what it is.
    reference_scenes_read(k, case, results, &mut read);
    let why = own.or(builtin).or_else(|| {
        read.iter().find_map(|name| match results.get(name) {
            Some(Err(e)) if is_not_expressible(e) => Some(e.clone()),
            _ => None,
        })
    });
    if let Some(why) = why {
        not_expressible(r, why);
    } else if r.not_produced {
        let why = format!("not produced by {code}: {}", r.message);
        not_expressible(r, why);
    }
}

/// The builtins of `case` that another code's rows need: those a check's reference reads (a
/// modal solution, a closed form). A builtin only measured is impact's own computation, N/E on
/// another code, and is not run for it.
pub fn referenced_builtins(case: &Case) -> BTreeSet<String> {
    let mut read = Vec::new();
    for k in &case.file.checks {
        reference_scenes_read(&k.value, case, &BTreeMap::new(), &mut read);
    }
    read.into_iter()
        .filter(|n| {
            case.file
                .scenes
                .get(n)
                .is_some_and(|s| s.value.builtin.is_some())
        })
        .collect()
}

fn not_expressible(r: &mut CheckResult, why: String) {
    r.status = Status::NotExpressible;
    r.message = why;
    r.computed = None;
    r.error = None;
}

/// The scenes a check's reference reads: its metric's, its history's.
fn reference_scenes_read(
    k: &CheckFile,
    case: &Case,
    results: &BTreeMap<String, JobResult>,
    out: &mut Vec<String>,
) {
    let Some(reference) = &k.reference else {
        return;
    };
    if let Some(m) = &reference.value.metric {
        scenes_read(m, case.default_scene(), results, out);
    }
    out.extend(
        reference
            .value
            .history
            .as_ref()
            .and_then(|h| h.scene.clone()),
    );
}

/// The scenes (and series levels) a measure reads.
fn scenes_read(
    m: &MeasureFile,
    default_scene: Option<&str>,
    results: &BTreeMap<String, JobResult>,
    out: &mut Vec<String>,
) {
    if let Some(q) = m.series_quantity() {
        let prefix = format!("{}@", q.series);
        out.extend(results.keys().filter(|k| k.starts_with(&prefix)).cloned());
    } else if let Some(children) = m.ratio.as_ref().or(m.band.as_ref()) {
        for c in children {
            scenes_read(c, default_scene, results, out);
        }
    } else if let Some(s) = m.scene.as_deref().or(default_scene) {
        out.push(s.to_string());
    }
}
