//! `impact lint`: the rules every case must follow before its results mean anything.
//!
//! - every check has a reference with a kind and a one-line source, and a tolerance with a
//!   reason (or is a pending reference, which runs as a SKIP), or, against a measurement
//!   (kind `experiment`), a `validation` budget whose scenes exist and whose parts say why;
//! - requirement ids are unique across cases, case ids are unique, check ids are unique
//!   within a case, and every requirement is a "shall" sentence;
//! - a skip (case or check) and a known failure carry a reason;
//! - every reference file sits under reference-data/ and has a provenance note
//!   (`PROVENANCE.md` in its folder or a parent folder inside reference-data/), and so does
//!   every data file found in reference-data/;
//! - measures name scenes and series the case defines;
//! - every row of a measurement table the validation cases read is compared by a check or
//!   declared not compared, with why (`crate::definition::not_compared`).

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::{Path, PathBuf};

use crate::definition::case::{Case, Compare, Loc, MeasureFile, RefKind};
use crate::definition::repo::Repo;
use crate::definition::validation::ValidationFile;

#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct Finding {
    pub loc: Loc,
    pub message: String,
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.loc, self.message)
    }
}

/// File extensions under reference-data/ that are data (and so need provenance).
const DATA_EXTENSIONS: [&str; 4] = ["csv", "json", "txt", "dat"];

/// The folder of `file` or a parent inside `reference-data/` holds a PROVENANCE.md.
pub fn has_provenance(root: &Path, file: &Path) -> bool {
    let top = root.join("reference-data");
    let mut dir = file.parent();
    while let Some(d) = dir {
        if d.join("PROVENANCE.md").is_file() {
            return true;
        }
        if d == top || !d.starts_with(&top) {
            return false;
        }
        dir = d.parent();
    }
    false
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.filter_map(|e| e.ok().map(|e| e.path())).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            walk(&p, out);
        } else {
            out.push(p);
        }
    }
}

pub fn lint(repo: &Repo, cases: &[Case]) -> Vec<Finding> {
    let mut findings = Vec::new();
    let mut requirement_ids: BTreeMap<String, Loc> = BTreeMap::new();
    let mut case_ids: BTreeMap<String, Loc> = BTreeMap::new();
    for case in cases {
        lint_case(
            repo,
            case,
            &mut findings,
            &mut requirement_ids,
            &mut case_ids,
        );
    }
    findings.extend(
        crate::definition::not_compared::findings(&repo.root, cases)
            .into_iter()
            .map(|(loc, message)| Finding { loc, message }),
    );
    // Every data file in reference-data/ has provenance.
    let mut files = Vec::new();
    walk(&repo.root.join("reference-data"), &mut files);
    for f in files {
        let is_data = f
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| DATA_EXTENSIONS.contains(&e));
        if is_data && !has_provenance(&repo.root, &f) {
            findings.push(Finding {
                loc: Loc::file(&f),
                message: "reference file without provenance: add a PROVENANCE.md to its folder (source, script or transcription, units)".into(),
            });
        }
    }
    findings.sort();
    findings
}

fn lint_case(
    repo: &Repo,
    case: &Case,
    out: &mut Vec<Finding>,
    requirement_ids: &mut BTreeMap<String, Loc>,
    case_ids: &mut BTreeMap<String, Loc>,
) {
    lint_identity(case, out, requirement_ids, case_ids);
    let scenes = lint_scenes(case, out);
    let mut check_ids = BTreeSet::new();
    for c in &case.file.checks {
        lint_check(repo, case, c, &scenes, &mut check_ids, out);
    }
}

/// The requirement (id unique, a "shall" sentence), the case id (unique), the case's skip
/// reason and that it has checks.
fn lint_identity(
    case: &Case,
    out: &mut Vec<Finding>,
    requirement_ids: &mut BTreeMap<String, Loc>,
    case_ids: &mut BTreeMap<String, Loc>,
) {
    let f = &case.file;
    let mut push = |loc: Loc, message: String| out.push(Finding { loc, message });
    let rid = &f.requirement.id;
    if rid.value.trim().is_empty() {
        push(case.loc(rid), "empty requirement id".into());
    } else if let Some(first) = requirement_ids.get(&rid.value) {
        push(
            case.loc(rid),
            format!(
                "duplicate requirement id {:?} (first at {first})",
                rid.value
            ),
        );
    } else {
        requirement_ids.insert(rid.value.clone(), case.loc(rid));
    }
    if !f.requirement.text.value.contains(" shall ") {
        push(
            case.loc(&f.requirement.text),
            "the requirement must be a sentence \"The solver shall ...\"".into(),
        );
    }
    if let Some(first) = case_ids.get(&f.id.value) {
        push(
            case.loc(&f.id),
            format!("duplicate case id {:?} (first at {first})", f.id.value),
        );
    } else {
        case_ids.insert(f.id.value.clone(), case.loc(&f.id));
    }
    if let Some(s) = &f.skip {
        if s.value.is_skip() && s.value.reason().is_none() {
            push(case.loc(s), "a skip needs a reason: skip: \"why\"".into());
        }
    }
    if f.checks.is_empty() {
        push(
            Loc::file(&case.path),
            "a case needs at least one check".into(),
        );
    }
}

/// The series, scene files and wrong models name what the case has; returns every scene name
/// a measure may use (the case's scenes and the series' levels).
fn lint_scenes(case: &Case, out: &mut Vec<Finding>) -> BTreeSet<String> {
    let f = &case.file;
    let mut push = |loc: Loc, message: String| out.push(Finding { loc, message });
    let mut scenes: BTreeSet<String> = f.scenes.keys().cloned().collect();
    for (name, s) in &f.series {
        for l in &s.value.levels {
            scenes.insert(crate::definition::case::series_scene_name(name, *l));
        }
        if !f.scenes.contains_key(&s.value.scene) {
            push(
                case.loc(s),
                format!("series {name}: no scene {:?}", s.value.scene),
            );
        }
    }
    for (name, s) in &f.scenes {
        if let Some(file) = &s.value.file {
            if !case.dir.join(file).is_file() {
                push(
                    case.loc(s),
                    format!("scene {name}: no file {file:?} in the case folder"),
                );
            }
        }
    }
    for (name, m) in &f.wrong_models {
        let w = &m.value;
        let forms = [w.rigid_wall, !w.replace.is_empty(), !w.set.is_empty()];
        if forms.iter().filter(|&&b| b).count() != 1 || w.set.is_empty() != w.scenes.is_empty() {
            push(
                case.loc(m),
                format!(
                    "wrong model {name}: exactly one of rigid_wall, replace, or set with scenes"
                ),
            );
        }
        let named = w.replace.iter().flat_map(|(a, b)| [a, b]).chain(&w.scenes);
        for s in named.filter(|s| !f.scenes.contains_key(*s)) {
            push(case.loc(m), format!("wrong model {name}: no scene {s:?}"));
        }
    }
    scenes
}

/// One check: a unique id, a measure of what the case defines, skip and known-failure
/// reasons, its reference and its tolerance.
fn lint_check(
    repo: &Repo,
    case: &Case,
    c: &serde_saphyr::Spanned<crate::definition::case::CheckFile>,
    scenes: &BTreeSet<String>,
    check_ids: &mut BTreeSet<String>,
    out: &mut Vec<Finding>,
) {
    let f = &case.file;
    let loc = case.loc(c);
    let k = &c.value;
    let mut push = |loc: Loc, message: String| out.push(Finding { loc, message });
    if !check_ids.insert(k.id.clone()) {
        push(loc.clone(), format!("duplicate check id {:?}", k.id));
    }
    let mut measure_findings = Vec::new();
    let case_skipped = f.skip.as_ref().is_some_and(|s| s.value.is_skip());
    if !case_skipped {
        lint_measure(
            &k.measure.value,
            f.scenes.len() == 1,
            scenes,
            &f.series,
            &mut measure_findings,
        );
    }
    for m in measure_findings {
        push(case.loc(&k.measure), format!("check {}: {m}", k.id));
    }
    if let Some(s) = &k.skip {
        if s.value.is_skip() && s.value.reason().is_none() {
            push(
                case.loc(s),
                format!("check {}: a skip needs a reason: skip: \"why\"", k.id),
            );
        }
    }
    if let Some(kf) = &k.known_failure {
        if kf.trim().is_empty() {
            push(
                loc.clone(),
                format!("check {}: known_failure needs a reason", k.id),
            );
        }
    }
    match &k.reference {
        None => push(
            loc.clone(),
            format!(
                "check {}: no reference (needs kind, a value source and `source`)",
                k.id
            ),
        ),
        Some(r) => lint_reference(repo, case, &k.id, r, scenes, out),
    }
    match (&k.tolerance, &k.validation) {
        (None, None) => out.push(Finding {
            loc,
            message: format!(
                "check {}: no tolerance (relative and/or absolute, with a reason)",
                k.id
            ),
        }),
        (Some(t), None) => lint_tolerance(case, &k.id, t, out),
        (Some(t), Some(_)) => out.push(Finding {
            loc: case.loc(t),
            message: format!(
                "check {}: a check with `validation` takes no tolerance (its bound is k u_val)",
                k.id
            ),
        }),
        (None, Some(v)) => lint_validation(case, k, v, scenes, out),
    }
    let experiment = k.reference.as_ref().and_then(|r| r.value.kind) == Some(RefKind::Experiment);
    if experiment && k.validation.is_none() {
        out.push(Finding {
            loc: case.loc(c),
            message: format!(
                "check {}: a reference of kind experiment needs `validation` (u_D, u_num, u_input)",
                k.id
            ),
        });
    }
}

/// A comparison with a measurement: the kind `experiment`, `compare: within`, a measure on a
/// scene, every scene of its budget in the case and every part with a reason.
fn lint_validation(
    case: &Case,
    k: &crate::definition::case::CheckFile,
    v: &serde_saphyr::Spanned<ValidationFile>,
    scenes: &BTreeSet<String>,
    out: &mut Vec<Finding>,
) {
    let loc = case.loc(v);
    let mut push = |message: String| {
        out.push(Finding {
            loc: loc.clone(),
            message: format!("check {}: validation: {message}", k.id),
        })
    };
    if k.reference.as_ref().and_then(|r| r.value.kind) != Some(RefKind::Experiment) {
        push("needs a reference of kind experiment".into());
    }
    if k.compare != Compare::Within {
        push("compares within k u_val: no compare".into());
    }
    if k.measure.value.scene.is_none() {
        push("the measure must name its scene (the budget measures the same on others)".into());
    }
    let spec = &v.value;
    for problem in spec.declaration_problems() {
        push(problem.into());
    }
    let parts = std::iter::once(("numerical", &spec.numerical))
        .chain(spec.input.iter().map(|(n, d)| (n.as_str(), d)));
    for (name, d) in parts {
        if !scenes.contains(&d.scene) {
            push(format!("{name}: no scene {:?} in this case", d.scene));
        }
        if d.reason.trim().is_empty() {
            push(format!("{name}: needs a reason"));
        }
    }
    if spec.experiment.reason.trim().is_empty() {
        push("experiment: needs a reason".into());
    }
}

/// A check's reference: a kind, a source line, a pending reason, its files under
/// reference-data/ with provenance, and its metric.
fn lint_reference(
    repo: &Repo,
    case: &Case,
    id: &str,
    r: &serde_saphyr::Spanned<crate::definition::case::ReferenceFile>,
    scenes: &BTreeSet<String>,
    out: &mut Vec<Finding>,
) {
    let rloc = case.loc(r);
    let rv = &r.value;
    let mut push = |message: String| {
        out.push(Finding {
            loc: rloc.clone(),
            message: format!("check {id}: {message}"),
        })
    };
    if rv.kind.is_none() {
        push("the reference has no kind (analytical | independent code | paper | calibration | invariant | regression | acceptance | other codes | other code | experiment)".into());
    }
    for m in crate::definition::other_code_reference::findings(&repo.root, rv) {
        push(m);
    }
    if rv.source.as_deref().is_none_or(|s| s.trim().is_empty()) {
        push("the reference has no source line".into());
    }
    if let Some(p) = &rv.pending {
        if p.trim().is_empty() {
            push("a pending reference needs a reason".into());
        }
    }
    // A NaN or inf reference compares as no difference, or as every difference.
    for (key, x) in [("value", rv.value), ("scale", rv.scale)] {
        if let Some(x) = x.filter(|x| !x.is_finite()) {
            push(format!(
                "reference.{key} = {}: must be a finite number",
                impact_solver::error::shown(x)
            ));
        }
    }
    let mut files = Vec::new();
    if let Some(t) = &rv.table {
        files.push(&t.file);
    }
    if let Some(j) = &rv.json {
        files.push(&j.file);
    }
    if let Some(h) = &rv.history {
        if let Some(file) = &h.file {
            files.push(file);
        }
    }
    for file in files {
        let path = repo.root.join(file);
        if !Path::new(file).starts_with("reference-data") {
            push(format!(
                "reference file {file:?} must live under reference-data/"
            ));
        } else if rv.pending.is_some() {
            // Not there yet: it must come with its provenance note.
        } else if !has_provenance(&repo.root, &path) {
            push(format!(
                "reference file {file:?} has no provenance note (PROVENANCE.md in its folder)"
            ));
        } else if !path.is_file() {
            push(format!("reference file {file:?} does not exist (declare it `pending: reason` until it does)"));
        }
    }
    if let Some(m) = &rv.metric {
        let mut fs = Vec::new();
        lint_measure(m, true, scenes, &case.file.series, &mut fs);
        for m in fs {
            push(format!("reference metric: {m}"));
        }
    }
}

/// A check's tolerance: a reason, finite non-negative values, relative and/or absolute.
fn lint_tolerance(
    case: &Case,
    id: &str,
    t: &serde_saphyr::Spanned<crate::definition::case::ToleranceFile>,
    out: &mut Vec<Finding>,
) {
    let tv = &t.value;
    let mut push = |message: &str| {
        out.push(Finding {
            loc: case.loc(t),
            message: format!("check {id}: {message}"),
        })
    };
    if tv.reason.as_deref().is_none_or(|s| s.trim().is_empty()) {
        push("the tolerance has no reason");
    }
    for (key, x) in [
        ("relative", tv.relative),
        ("absolute", tv.absolute),
        ("floor", tv.floor),
    ] {
        if let Some(x) = x.filter(|v| !(v.is_finite() && *v >= 0.0)) {
            push(&format!(
                "tolerance.{key} = {}: tolerances must be finite and >= 0",
                impact_solver::error::shown(x)
            ));
        }
    }
    if tv.relative.is_none() && tv.absolute.is_none() {
        push("the tolerance needs relative and/or absolute (0 for exact)");
    }
}

fn lint_measure(
    m: &MeasureFile,
    has_default: bool,
    scenes: &BTreeSet<String>,
    series: &BTreeMap<String, serde_saphyr::Spanned<crate::definition::case::SeriesSpec>>,
    out: &mut Vec<String>,
) {
    if m.selector_count() != 1 {
        out.push(crate::definition::case::ONE_SELECTOR.into());
    }
    if let Some(s) = &m.scene {
        if !scenes.contains(s) {
            out.push(format!("no scene {s:?} in this case"));
        }
    }
    let parts = [
        (&m.ratio, 2, "ratio needs [numerator, denominator]"),
        (&m.band, 3, "band needs [value, lower, upper]"),
    ];
    if let Some((r, n, message)) = parts
        .iter()
        .find_map(|(r, n, t)| r.as_ref().map(|r| (r, *n, *t)))
    {
        if r.len() != n {
            out.push(message.into());
        }
        for x in r {
            lint_measure(x, has_default || m.scene.is_some(), scenes, series, out);
        }
    } else if let Some(q) = m.series_quantity() {
        let needed = if m.change.is_some() { 2 } else { 3 };
        match series.get(&q.series) {
            None => out.push(format!("no series {:?} in this case", q.series)),
            Some(s) if s.value.levels.len() < needed => {
                out.push(format!("series {:?} needs {needed} levels", q.series))
            }
            _ => {}
        }
    } else if m.scene.is_none() && !has_default {
        out.push("the measure names no scene and the case has not exactly one".into());
    }
}
