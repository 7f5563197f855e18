//! `case.yaml`: one verification case (a folder under `verification/cases/<suite>/<case>/`)
//! with its requirement, its scenes and its checks.
//!
//! [`CaseFile`] mirrors the YAML as written: unknown keys, wrong types and duplicate keys are
//! refused by the parser with file, line and column. Fields that the lint must be able to
//! report as missing (a reference kind, a tolerance reason, a skip reason) are optional here
//! and enforced by [`crate::definition::lint`], which also names the line and column.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use serde_saphyr::Spanned;

/// Where something is written: `file:line:column` (line 0 = file only); the solver's
/// [`SourceLocation`](impact_solver::error::SourceLocation), one type for scenes and cases.
pub use impact_solver::error::SourceLocation as Loc;

/// A case file that cannot be read or parsed.
#[derive(Debug, thiserror::Error)]
pub enum CaseError {
    #[error("{path}: cannot read: {source}")]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error("{loc}: {message}")]
    Parse { loc: Loc, message: String },
}

/// The categories of the V&V matrix (ASME V&V 10 / Oberkampf & Roy wording).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Deserialize, serde::Serialize)]
pub enum Category {
    #[serde(rename = "code verification")]
    CodeVerification,
    #[serde(rename = "solution verification")]
    SolutionVerification,
    #[serde(rename = "code-to-code")]
    CodeToCode,
    #[serde(rename = "literature")]
    Literature,
    #[serde(rename = "regression")]
    Regression,
    /// A case whose case.yaml does not load (`crate::definition::broken`); no case file may declare it.
    #[serde(rename = "unknown (case.yaml does not load)", skip_deserializing)]
    Unknown,
}

impl Category {
    pub fn name(self) -> &'static str {
        match self {
            Category::CodeVerification => "code verification",
            Category::SolutionVerification => "solution verification",
            Category::CodeToCode => "code-to-code",
            Category::Literature => "literature",
            Category::Regression => "regression",
            Category::Unknown => "unknown (case.yaml does not load)",
        }
    }
}

/// What a reference value is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
pub enum RefKind {
    /// A closed form or an exact property of the discrete method (computed independently).
    #[serde(rename = "analytical")]
    Analytical,
    /// Another code's output (the independent Python FE).
    #[serde(rename = "independent code")]
    IndependentCode,
    /// A number printed in Dokko & Kim (2004) that no parameter was fitted to.
    #[serde(rename = "paper")]
    Paper,
    /// A number printed in Dokko & Kim (2004) that the reconstructed plate was fitted to
    /// (scripts/reconstruct.py): agreement shows the fit, it is not evidence (issue 10).
    #[serde(rename = "calibration")]
    Calibration,
    /// A conservation law or identity that must hold in every run.
    #[serde(rename = "invariant")]
    Invariant,
    /// A pinned earlier result of this code.
    #[serde(rename = "regression")]
    Regression,
    /// A bound set by the requirement itself (e.g. a GCI below 5 %).
    #[serde(rename = "acceptance")]
    Acceptance,
    /// Published results of other codes for a benchmark of the field (the band they span).
    #[serde(rename = "other codes")]
    OtherCodes,
    /// A run of another production code through its adapter (adapters/), stored with the
    /// adapter's record under reference-data/codes/<code>/ (issue 38): a reference that shares
    /// none of this project's readings, as the independent Python FE does.
    #[serde(rename = "other code")]
    OtherCode,
    /// A measurement of a physical test (validation, ASME V&V 20): the check carries its
    /// `validation` budget and passes when `|E| <= k u_val`.
    #[serde(rename = "experiment")]
    Experiment,
}

impl RefKind {
    pub fn name(self) -> &'static str {
        match self {
            RefKind::Analytical => "analytical",
            RefKind::IndependentCode => "independent code",
            RefKind::Paper => "paper",
            RefKind::Calibration => "calibration",
            RefKind::Invariant => "invariant",
            RefKind::Regression => "regression",
            RefKind::Acceptance => "acceptance",
            RefKind::OtherCodes => "other codes",
            RefKind::OtherCode => "other code",
            RefKind::Experiment => "experiment",
        }
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CaseFile {
    pub id: Spanned<String>,
    pub title: String,
    pub requirement: RequirementFile,
    pub category: Category,
    #[serde(default)]
    pub heavy: bool,
    /// The reference problem in words (for the report).
    #[serde(default)]
    pub problem: Option<String>,
    /// Whole-case skip with its reason.
    #[serde(default)]
    pub skip: Option<Spanned<SkipFile>>,
    #[serde(default)]
    pub scenes: BTreeMap<String, Spanned<SceneSpec>>,
    #[serde(default)]
    pub series: BTreeMap<String, Spanned<SeriesSpec>>,
    pub checks: Vec<Spanned<CheckFile>>,
    /// What `cargo test` pins with insta (histories at fixed times, summaries).
    #[serde(default)]
    pub snapshot: Option<SnapshotSpec>,
    /// Plots for the report.
    #[serde(default)]
    pub plots: Vec<PlotSpec>,
    /// What the report shows of this case outside its own section (the paper's tables, the
    /// Energy section, the reading paragraph); the report names no suite, it reads these.
    #[serde(default)]
    pub report: Option<ReportSpec>,
    /// Trivial or wrong models the evidence checks are re-evaluated on (issue 10).
    #[serde(default)]
    pub wrong_models: BTreeMap<String, Spanned<WrongModelSpec>>,
    /// Rows of a measurement table the case does not compare, with why
    /// (`crate::definition::not_compared`).
    #[serde(default)]
    pub not_compared: Vec<Spanned<NotComparedFile>>,
}

/// A `not_compared:` entry of a case.yaml: rows of one table and why they are left out.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NotComparedFile {
    /// The measurement table, a CSV under reference-data/ (path from the repository root).
    pub file: String,
    /// The column whose value names a row (`shot_id`).
    pub key: String,
    /// The rows left out, by their key.
    pub rows: Vec<String>,
    /// Why: what stops the run (with its evidence), or why a comparison could not fail.
    pub why: String,
}

/// A trivial or wrong model: what the case's checks would say about it (the
/// discriminating-power table of the report). Exactly one of `rigid_wall`, `replace`, `set`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WrongModelSpec {
    pub title: String,
    /// No plate at all: every impact scene reads I = 2 m v0, v_f = -v0, no displacement, no
    /// stress, no dissipation (closed form, no run).
    #[serde(default)]
    pub rigid_wall: bool,
    /// Scenes read in place of others, e.g. `{plastic: elastic}`: the elastic plate in the
    /// elasto-plastic row (no run).
    #[serde(default)]
    pub replace: BTreeMap<String, String>,
    /// Overrides (as a scene's `set`) applied to each of `scenes`, run as `SCENE~MODEL`.
    #[serde(default)]
    pub set: BTreeMap<String, serde_json::Value>,
    #[serde(default)]
    pub scenes: Vec<String>,
    /// The runs of `set` happen only in the full matrix (`impact verify` without --light).
    #[serde(default)]
    pub heavy: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RequirementFile {
    pub id: Spanned<String>,
    /// "The solver shall ..."
    pub text: Spanned<String>,
}

/// `skip: "reason"` (or `skip: true`, which the lint refuses: a skip needs a reason).
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum SkipFile {
    Reason(String),
    Flag(bool),
}

impl SkipFile {
    pub fn reason(&self) -> Option<&str> {
        match self {
            SkipFile::Reason(r) if !r.trim().is_empty() => Some(r.trim()),
            _ => None,
        }
    }
    pub fn is_skip(&self) -> bool {
        !matches!(self, SkipFile::Flag(false))
    }
}

/// A scene: a file in the case folder (with optional overrides) or a builtin computation.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    #[serde(default)]
    pub file: Option<String>,
    /// Dotted overrides applied to the scene file, e.g. `impactor.velocity: 5.0`.
    #[serde(default)]
    pub set: BTreeMap<String, serde_json::Value>,
    /// Record field frames and the stress / flow-stress ratio (slower).
    #[serde(default)]
    pub stress_bound: bool,
    /// The run is expected to stop with an error: the job then yields the metrics
    /// `run_failed` (1/0) and `error_mentions_<word>` for each word of `expect_error`.
    #[serde(default)]
    pub expect_error: Vec<String>,
    /// A computation of the harness itself (contact-law and element unit checks, closed forms).
    #[serde(default)]
    pub builtin: Option<String>,
    #[serde(default)]
    pub params: BTreeMap<String, serde_json::Value>,
}

/// A refinement series of a scene: `mesh` multiplies nx and ny, `dt` divides the step.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeriesSpec {
    pub scene: String,
    pub refine: Refine,
    /// Refinement factors relative to the base scene, coarse to fine, constant ratio.
    pub levels: Vec<f64>,
}

/// The name of a series' scene at one level: `SERIES@LEVEL`.
pub fn series_scene_name(series: &str, level: f64) -> String {
    format!("{series}@{level}")
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Refine {
    Mesh,
    Dt,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckFile {
    pub id: String,
    pub title: String,
    pub measure: Spanned<MeasureFile>,
    #[serde(default)]
    pub reference: Option<Spanned<ReferenceFile>>,
    #[serde(default)]
    pub compare: Compare,
    #[serde(default)]
    pub tolerance: Option<Spanned<ToleranceFile>>,
    #[serde(default)]
    pub skip: Option<Spanned<SkipFile>>,
    /// A failure that is known and tracked: still FAIL in the matrix (and `impact verify`
    /// exits non-zero), but `cargo test` accepts it; it fails the test when it starts passing.
    #[serde(default)]
    pub known_failure: Option<String>,
    /// A comparison with a measurement (reference kind `experiment`): its V&V 20 budget in place
    /// of a tolerance (`crate::definition::validation`).
    #[serde(default)]
    pub validation: Option<Spanned<crate::definition::validation::ValidationFile>>,
}

/// How the computed value must relate to the reference.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Compare {
    /// |computed - reference| within the tolerance.
    #[default]
    Within,
    /// computed <= reference + tolerance.
    AtMost,
    /// computed >= reference - tolerance.
    AtLeast,
}

/// One measured value (exactly one of the selectors).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasureFile {
    /// The scene (or builtin) the value comes from.
    #[serde(default)]
    pub scene: Option<String>,
    /// A summary key (`impulse_Ns`, `max_von_mises_Pa.A`, ...), a derived metric, or a builtin's metric.
    #[serde(default)]
    pub metric: Option<String>,
    /// A history value at a time (linear interpolation between rows).
    #[serde(default)]
    pub at: Option<AtFile>,
    /// A reduction of a history column over a window.
    #[serde(default)]
    pub extreme: Option<ExtremeFile>,
    /// A norm of the difference to the reference history.
    #[serde(default)]
    pub error: Option<ErrorFile>,
    /// numerator / denominator.
    #[serde(default)]
    pub ratio: Option<Vec<MeasureFile>>,
    /// `[value, lower, upper]`: where the value lies in the band, `(v - lo) / (hi - lo)`
    /// (0 at the lower edge, 1 at the upper; inside: within 0.5 +- 0.5).
    #[serde(default)]
    pub band: Option<Vec<MeasureFile>>,
    /// Observed order of convergence over a series.
    #[serde(default)]
    pub order: Option<SeriesQuantity>,
    /// Grid convergence index of the finest level, relative, by the rule of `crate::definition::gci`
    /// (Roache; Celik et al. 2008): needs `formal`; a non-asymptotic series fails.
    #[serde(default)]
    pub gci: Option<SeriesQuantity>,
    /// The largest radial gap (m) between a Taylor bar's final outline and a digitised
    /// profile (`crate::definition::profile_gap`).
    #[serde(default)]
    pub profile_gap: Option<crate::definition::profile_gap::ProfileGapFile>,
    /// Relative change from the first to the last level of a series,
    /// `|f_first - f_last| / |f_last|`: how much the whole refinement moves a quantity.
    #[serde(default)]
    pub change: Option<SeriesQuantity>,
    /// Scale applied to the measured value (unit conversion).
    #[serde(default)]
    pub scale: Option<f64>,
    /// Take the absolute value.
    #[serde(default)]
    pub abs: bool,
}

/// The message for a measure that does not name exactly one selector.
pub const ONE_SELECTOR: &str = "a measure needs exactly one of metric, at, extreme, error, ratio, band, order, gci, change, profile_gap";

impl MeasureFile {
    /// How many of the value selectors (metric, at, extreme, ...) are given; exactly one is valid.
    pub fn selector_count(&self) -> usize {
        [
            self.metric.is_some(),
            self.at.is_some(),
            self.extreme.is_some(),
            self.error.is_some(),
            self.ratio.is_some(),
            self.band.is_some(),
            self.order.is_some(),
            self.gci.is_some(),
            self.change.is_some(),
            self.profile_gap.is_some(),
        ]
        .iter()
        .filter(|&&b| b)
        .count()
    }

    /// The series quantity of an `order`, `gci` or `change` measure.
    pub fn series_quantity(&self) -> Option<&SeriesQuantity> {
        self.order
            .as_ref()
            .or(self.gci.as_ref())
            .or(self.change.as_ref())
    }
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AtFile {
    pub column: String,
    pub time: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Reduce {
    Max,
    Min,
    AbsMax,
    Mean,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExtremeFile {
    pub column: String,
    pub reduce: Reduce,
    #[serde(default)]
    pub window: Option<[f64; 2]>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Norm {
    L2,
    Linf,
}

/// `error: {column, norm, window}`: `norm(computed - reference) / max |reference|` over the
/// window, the computed history interpolated at the reference times.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ErrorFile {
    pub column: String,
    pub norm: Norm,
    #[serde(default)]
    pub window: Option<[f64; 2]>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeriesQuantity {
    pub series: String,
    pub metric: String,
    /// The method's formal order: required by `gci` (it sets the safety factor and caps the
    /// order, see `crate::definition::gci`).
    #[serde(default)]
    pub formal: Option<f64>,
}

/// The reference of a check: its kind, where the value comes from, and a one-line source.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceFile {
    #[serde(default)]
    pub kind: Option<RefKind>,
    /// A literal (for closed forms: 0 residual, 1 ratio, a bound) with `source` saying why.
    #[serde(default)]
    pub value: Option<f64>,
    /// A cell of a CSV table under reference-data/.
    #[serde(default)]
    pub table: Option<TableRef>,
    /// A value computed in this run by independent means (a builtin's closed form, or an
    /// identity from other outputs of the same scene).
    #[serde(default)]
    pub metric: Option<MeasureFile>,
    /// A reference history (CSV under reference-data/ or a builtin's history).
    #[serde(default)]
    pub history: Option<HistoryRef>,
    /// A JSON value under reference-data/ (e.g. the independent code's summary.json).
    #[serde(default)]
    pub json: Option<JsonRef>,
    /// The code whose stored run the reference reads (kind `other code` only): its `json` or
    /// `history` file lies in a folder of reference-data/codes/<code>/ beside the adapter's
    /// `adapter.json`.
    #[serde(default)]
    pub code: Option<String>,
    /// Multiplies the reference value (unit conversion, e.g. 1e-3 for mm -> m).
    #[serde(default)]
    pub scale: Option<f64>,
    /// Where the reference comes from, in one line.
    #[serde(default)]
    pub source: Option<String>,
    /// The reference does not exist yet: the check is a SKIP with this reason, never a pass.
    #[serde(default)]
    pub pending: Option<String>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableRef {
    /// Path from the repository root, under reference-data/.
    pub file: String,
    /// `{column: value}` selecting the row (string comparison on the printed value).
    pub row: BTreeMap<String, String>,
    pub column: String,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HistoryRef {
    /// A CSV under reference-data/ (columns `time_s` and `column`) ...
    #[serde(default)]
    pub file: Option<String>,
    /// ... or the history of a scene or builtin of this case.
    #[serde(default)]
    pub scene: Option<String>,
    pub column: String,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JsonRef {
    pub file: String,
    /// Dotted key.
    pub key: String,
}

/// `relative` and/or `absolute`; values with magnitude below `floor` count as zero (both
/// the computed and the reference value); `reason` says where the numbers come from.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ToleranceFile {
    #[serde(default)]
    pub relative: Option<f64>,
    #[serde(default)]
    pub absolute: Option<f64>,
    #[serde(default)]
    pub floor: Option<f64>,
    #[serde(default)]
    pub reason: Option<String>,
}

/// What the snapshot test pins for this case.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SnapshotSpec {
    /// Scenes whose summaries and histories are pinned.
    pub scenes: Vec<String>,
    /// History columns, sampled at `times`.
    #[serde(default)]
    pub columns: Vec<String>,
    #[serde(default)]
    pub times: Vec<f64>,
    /// Significant digits (default 6).
    #[serde(default)]
    pub digits: Option<usize>,
}

/// A history plot for the report: columns of scenes over time, references overlaid.
#[derive(Debug, Clone, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct PlotSpec {
    pub title: String,
    /// One column of several scenes ...
    #[serde(default)]
    pub column: Option<String>,
    /// ... or several columns of each scene (e.g. the energy terms).
    #[serde(default)]
    pub columns: Vec<String>,
    pub scenes: Vec<String>,
    /// Reference histories overlaid: scenes (builtins) or CSV files with the same column.
    #[serde(default)]
    pub references: Vec<String>,
    #[serde(default)]
    pub scale: Option<f64>,
    #[serde(default)]
    pub unit: Option<String>,
    /// The horizontal axis's label when the histories' `time_s` column holds something else
    /// than a time (e.g. the refinement step of an order-of-accuracy builtin): plotted as is,
    /// not in ms.
    #[serde(default)]
    pub x_label: Option<String>,
    /// Or a summary `metric` of several mesh `series` against the element size, side by side
    /// (e.g. two couplings' peak forces under refinement); `scenes` is then empty.
    #[serde(default)]
    pub series: Vec<String>,
    #[serde(default)]
    pub metric: Option<String>,
}

/// A case's `report:` block: the report-wide parts it feeds (rendered by
/// [`crate::report::paper_tables`] and [`crate::report::page`]).
#[derive(Debug, Clone, Default, PartialEq, Deserialize, serde::Serialize)]
#[serde(deny_unknown_fields)]
pub struct ReportSpec {
    /// The paper's table this case's metrics fill, next to the printed values.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub table: Option<PaperTable>,
    /// Plots of this case that the report also shows in a section of their own.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub plots: Vec<ReportPlots>,
    /// What this case's results tell the paragraph on the reading of the paper.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reading: Vec<ReadingPart>,
}

/// A table of Dokko & Kim (2004) that the report fills from a case's metrics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PaperTable {
    /// Table 1: elastic and elasto-plastic impact at 5 m/s (scenes `elastic`, `plastic`).
    PaperTable1,
    /// Table 2: impulse against initial velocity (scenes `elastic-v<v>`, `plastic-v<v>`).
    PaperTable2,
}

/// A report-wide plot section a case contributes to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ReportPlots {
    /// The Energy section: the case's plots whose title names an energy.
    EnergyBalance,
}

/// What a case tells the paragraph on which reading of the paper the suites run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ReadingPart {
    /// The largest energy balance error of scenes `elastic`, `plastic` and `literal-pairing`.
    EnergyBalance,
    /// The error that stops the literal elasto-plastic run (scene `literal-plastic`).
    LiteralError,
}

/// A parsed case with where it lives.
#[derive(Debug)]
pub struct Case {
    /// `<suite>/<case>` folder name pair.
    pub suite: String,
    pub name: String,
    pub dir: PathBuf,
    pub path: PathBuf,
    pub file: CaseFile,
}

impl Case {
    pub fn id(&self) -> &str {
        &self.file.id.value
    }
    /// The scene a measure that names none reads: the case's only scene, if it has one.
    pub fn default_scene(&self) -> Option<&str> {
        let mut names = self.file.scenes.keys();
        match (names.next(), names.next()) {
            (Some(only), None) => Some(only.as_str()),
            _ => None,
        }
    }
    pub fn loc<T>(&self, s: &Spanned<T>) -> Loc {
        Loc::of(&self.path, s)
    }
}

/// Parses a case.yaml; `path` names it in messages.
pub fn parse_case(text: &str, path: &Path) -> Result<CaseFile, CaseError> {
    parse_located(
        text,
        path,
        (
            "case file",
            "every case.yaml needs id, title, requirement, category and checks",
        ),
    )
}

/// Parses YAML text into `T`; an error names the place (`path:line:column`) and the parser's
/// message without the location it repeats.
pub fn parse_located<T: serde::de::DeserializeOwned>(
    text: &str,
    path: &Path,
    (document, needs): (&str, &str),
) -> Result<T, CaseError> {
    serde_saphyr::from_str::<T>(text).map_err(|e| {
        let (line, column) = e
            .location()
            .map(|l| (l.line(), l.column()))
            .unwrap_or((0, 0));
        // The scene parser's plain words and field names (no library wording), in terms of
        // this file.
        let (line, column, message) = impact_solver::yaml_field::describe_document(
            text,
            &impact_solver::yaml_field::parser_words(&e.to_string()),
            (line, column),
            document,
            needs,
        );
        CaseError::Parse {
            loc: Loc {
                file: path.to_path_buf(),
                line,
                column,
            },
            message,
        }
    })
}

/// Reads `verification/cases/<suite>/<case>/case.yaml` files, sorted by suite then case.
/// Returns the cases that parse and the errors of those that do not.
pub fn load_cases(cases_dir: &Path) -> (Vec<Case>, Vec<CaseError>) {
    let mut cases = Vec::new();
    let mut errors = Vec::new();
    for suite_dir in sorted_dirs(cases_dir) {
        for case_dir in sorted_dirs(&suite_dir) {
            let path = case_dir.join("case.yaml");
            if !path.is_file() {
                // Every folder under a suite is a case: one without its file is broken, not
                // left out of the matrix without a word.
                let why = if path.is_dir() {
                    "case.yaml is a folder; a case needs its case.yaml file"
                } else {
                    "this case folder has no case.yaml (every folder under verification/cases/<suite>/ is a case)"
                };
                errors.push(CaseError::Read {
                    path,
                    source: std::io::Error::other(why),
                });
                continue;
            }
            let text = match std::fs::read_to_string(&path) {
                Ok(t) => t,
                Err(source) => {
                    errors.push(CaseError::Read { path, source });
                    continue;
                }
            };
            match parse_case(&text, &path) {
                Ok(file) => cases.push(Case {
                    suite: file_name(&suite_dir),
                    name: file_name(&case_dir),
                    dir: case_dir.clone(),
                    path,
                    file,
                }),
                Err(e) => errors.push(e),
            }
        }
    }
    (cases, errors)
}

fn file_name(p: &Path) -> String {
    p.file_name()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

pub fn sorted_dirs(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.is_dir())
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}
