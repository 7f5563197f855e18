//! Broken cases: a case.yaml that cannot be read or parsed, or that lint refuses, is reported
//! as a FAIL row of that case (issue 13: "one broken case stops `impact verify` for every
//! other suite" no more); the other cases still run. Lint findings outside any case folder
//! (e.g. a reference file without provenance) still stop the run: they are not one case's.

use std::path::Path;

use crate::definition::case::{Case, CaseError};
use crate::definition::lint::Finding;

/// A case that will not run, and why (each message names the file, line and column).
#[derive(Debug)]
pub struct Broken {
    pub suite: String,
    pub case: String,
    pub messages: Vec<String>,
    /// Whether its case.yaml parsed (then its own id, title, requirement, category are known).
    pub parsed: Option<Case>,
}

/// The loaded cases without the broken ones, the broken ones (in folder order), and the
/// problems that are no single case's.
pub fn split(
    cases: Vec<Case>,
    errors: Vec<CaseError>,
    findings: Vec<Finding>,
) -> (Vec<Case>, Vec<Broken>, Vec<String>) {
    let mut broken: Vec<Broken> = Vec::new();
    for e in errors {
        let path = match &e {
            CaseError::Read { path, .. } => path.clone(),
            CaseError::Parse { loc, .. } => loc.file.clone(),
        };
        let (suite, case) = suite_and_case(&path);
        broken.push(Broken {
            suite,
            case,
            messages: vec![e.to_string()],
            parsed: None,
        });
    }
    let mut fatal = Vec::new();
    let mut findings_of: Vec<Vec<String>> = vec![Vec::new(); cases.len()];
    for f in findings {
        match cases.iter().position(|c| f.loc.file.starts_with(&c.dir)) {
            Some(i) => findings_of[i].push(f.to_string()),
            None => fatal.push(f.to_string()),
        }
    }
    let mut good = Vec::new();
    for (case, messages) in cases.into_iter().zip(findings_of) {
        if messages.is_empty() {
            good.push(case);
        } else {
            broken.push(Broken {
                suite: case.suite.clone(),
                case: case.name.clone(),
                messages,
                parsed: Some(case),
            });
        }
    }
    broken.sort_by(|a, b| (&a.suite, &a.case).cmp(&(&b.suite, &b.case)));
    (good, broken, fatal)
}

/// `.../cases/SUITE/CASE/case.yaml` -> (SUITE, CASE).
fn suite_and_case(path: &Path) -> (String, String) {
    let name = |p: Option<&Path>| {
        p.and_then(|p| p.file_name())
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    };
    let case_dir = path.parent();
    (name(case_dir.and_then(|d| d.parent())), name(case_dir))
}
