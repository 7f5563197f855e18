//! The report's evidence section (issue 10): the statement that no validation against
//! experiment has been performed, the checks by reference kind (calibration apart from the
//! evidence), the discriminating-power table (what trivial or wrong models give for every
//! evidence check), and the reconstruction's evidence page (leave-out residuals, V&V 20
//! bands, the lost mesh) written by `scripts/reconstruction/recon_evidence.py`.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use serde_json::Value;

/// Where `scripts/reconstruction/recon_evidence.py` writes its page, relative to the repository root.
pub const EVIDENCE_PAGE: &str = "reference-data/paper/reconstruction/evidence.md";

/// The sentence the issue asks for, shown first when no check compares with a measurement.
pub const NO_VALIDATION: &str = "No validation against experiment has been performed: the \
paper's Tables 1 and 2 are computed results of the authors' program, not measurements, and the \
plate was reconstructed (calibrated) from all 26 of their numbers. A `calibration` check shows \
the fit; the evidence is the held-out residuals of the leave-out study, the one statement of \
the paper the fit did not use, and the code-verification checks.";

fn num(v: &Value) -> String {
    match v.as_f64() {
        Some(x) if x == 0.0 => "0".into(),
        Some(x) => format!("{x:.4e}"),
        None => "-".into(),
    }
}

/// Checks per reference kind and verdict, over all cases.
fn kinds_table(results: &Value) -> String {
    let mut per: BTreeMap<String, [usize; 4]> = BTreeMap::new();
    for c in results["cases"].as_array().into_iter().flatten() {
        for k in c["checks"].as_array().into_iter().flatten() {
            let kind = k["reference_kind"].as_str().unwrap_or("").to_string();
            let known = !k["known_failure"].is_null();
            let slot = match (k["status"].as_str(), known) {
                (Some("OK"), false) => 0,
                (Some("FAIL"), true) => 1,
                (Some("SKIP"), _) => 3,
                _ => 2,
            };
            per.entry(kind).or_default()[slot] += 1;
        }
    }
    let mut s = String::from(
        "| reference kind | counts as | OK | known FAIL | unexpected (FAIL, XPASS) | SKIP |\n|---|---|---|---|---|---|\n",
    );
    for (kind, n) in &per {
        let role = match kind.as_str() {
            "calibration" => "**calibration**: a number the plate was fitted to, not evidence",
            "paper" => "validation against the paper's computed results (not fitted)",
            "invariant" => "bookkeeping identity of the method",
            "acceptance" => "a bound set by the requirement",
            "analytical" => "code verification (closed form)",
            "independent code" => "code-to-code (same discrete method)",
            "regression" => "regression (pinned earlier result)",
            "other codes" => "benchmark: the band of other codes' published results",
            "other code" => "code-to-code: another production code's run (no shared readings)",
            "experiment" => "**validation** against measurements (V&V 20: within 2 u_val)",
            _ => "",
        };
        let _ = writeln!(
            s,
            "| {kind} | {role} | {} | {} | {} | {} |",
            n[0], n[1], n[2], n[3]
        );
    }
    s
}

/// The discriminating-power table of every case that declares wrong models.
fn discrimination_tables(results: &Value) -> (String, Vec<String>) {
    let mut s = String::new();
    let mut trivial_passes = Vec::new();
    for c in results["cases"].as_array().into_iter().flatten() {
        let rows = c["discrimination"].as_array().cloned().unwrap_or_default();
        if rows.is_empty() {
            continue;
        }
        let models: Vec<(String, String)> = c["wrong_models"]
            .as_object()
            .into_iter()
            .flatten()
            .map(|(k, v)| (k.clone(), v.as_str().unwrap_or("").to_string()))
            .collect();
        let _ = writeln!(
            s,
            "\n**{}/{}**. Models: {}.\n",
            c["suite"].as_str().unwrap_or(""),
            c["case"].as_str().unwrap_or(""),
            models
                .iter()
                .map(|(k, t)| format!("`{k}` = {t}"))
                .collect::<Vec<_>>()
                .join("; ")
        );
        let mut head = String::from("| check | kind | tolerance | ours |");
        let mut rule = String::from("|---|---|---|---|");
        for (m, _) in &models {
            let _ = write!(head, " {m} |");
            rule.push_str("---|");
        }
        let _ = writeln!(s, "{head}\n{rule}");
        for r in &rows {
            let mut line = format!(
                "| {} | {} | {} | {} |",
                r["check"].as_str().unwrap_or(""),
                r["kind"].as_str().unwrap_or(""),
                r["tolerance"].as_str().unwrap_or(""),
                num(&r["computed"])
            );
            for mv in r["models"].as_array().into_iter().flatten() {
                let verdict = mv["verdict"].as_str().unwrap_or("n/a");
                let shown = if verdict == "passes" {
                    "**passes**"
                } else {
                    verdict
                };
                let _ = write!(line, " {} {shown} |", num(&mv["value"]));
                let model = mv["model"].as_str().unwrap_or("");
                // calibration: fitted; invariant and acceptance: bookkeeping of the method,
                // true for any plate, so not evidence about the plate
                let evidence = !matches!(
                    r["kind"].as_str(),
                    Some("calibration" | "invariant" | "acceptance")
                );
                if verdict == "passes"
                    && evidence
                    && matches!(model, "rigid-wall" | "elastic-plate")
                {
                    trivial_passes.push(format!(
                        "{}/{}/{}: {model}",
                        c["suite"].as_str().unwrap_or(""),
                        c["case"].as_str().unwrap_or(""),
                        r["check"].as_str().unwrap_or("")
                    ));
                }
            }
            let _ = writeln!(s, "{line}");
        }
    }
    (s, trivial_passes)
}

/// The whole section as Markdown (headings from level 3).
pub fn markdown(results: &Value, evidence_page: Option<&str>) -> String {
    let measured = results["cases"]
        .as_array()
        .into_iter()
        .flatten()
        .flat_map(|c| c["checks"].as_array().into_iter().flatten())
        .filter(|k| k["reference_kind"] == "experiment")
        .count();
    let opening = if measured == 0 {
        format!("**{NO_VALIDATION}**")
    } else {
        format!(
            "**Validation against experiment: {measured} checks compare with measurements of \
             physical tests** (kind `experiment`, section \"Validation against experiments\"). \
             The paper's Tables 1 and 2 remain computed results of the authors' program, not \
             measurements, and the plate was reconstructed (calibrated) from all 26 of their \
             numbers: a `calibration` check shows the fit, the held-out residuals of the \
             leave-out study are the evidence about the paper's plate."
        )
    };
    let mut s = format!("{opening}\n\n## Checks by reference kind\n\n");
    s.push_str(&kinds_table(results));
    s.push_str(
        "\n## Discriminating power\n\nEvery evidence check (kinds paper, calibration, invariant, \
         acceptance, independent code, other codes, other code, experiment, and analytical bounds) re-evaluated on what trivial or wrong models give: a value and whether the \
         check would pass (against a measurement, within our run's 2 u_val). A check that a trivial model (a rigid wall, the elastic plate in an \
         elasto-plastic row) passes cannot tell a plate from no plate; the invariants are \
         bookkeeping of the method and hold for any plate (they discriminate slips in the \
         method, not the plate). n/a: the model has no value for that measure (a rigid wall \
         has no contact duration or peak force without a contact law; E x 0.5 / x 2 of Table 2 \
         run only in the full matrix).\n",
    );
    let (tables, trivial) = discrimination_tables(results);
    if tables.is_empty() {
        s.push_str("\n*No case in this run declares wrong models.*\n");
    } else {
        s.push_str(&tables);
        if trivial.is_empty() {
            s.push_str(
                "\nNo trivial model passes a check that counts as evidence about the plate \
                 (kind paper). Calibration checks are the fit; the invariant is the one \
                 bookkeeping identity per run type, true for any contact force.\n",
            );
        } else {
            let _ = writeln!(
                s,
                "\n**A trivial model passes evidence checks:** {}.",
                trivial.join(", ")
            );
        }
    }
    s.push_str("\n## Calibration and validation: the reconstruction's evidence\n\n");
    match evidence_page {
        Some(page) => s.push_str(page),
        None => {
            let _ = writeln!(
                s,
                "**Not yet produced:** `{EVIDENCE_PAGE}`. Run `scripts/reconstruction/recon_evidence.py`."
            );
        }
    }
    s
}

/// The section for the report templates: `{html, md}`.
pub fn context(results: &Value, root: &Path, out: &Path) -> Value {
    let path = root.join(EVIDENCE_PAGE);
    let page = std::fs::read_to_string(&path).ok().map(|t| {
        // the page's own title is the subsection's
        t.lines()
            .skip_while(|l| l.starts_with("# ") || l.trim().is_empty())
            .map(|l| {
                if l.starts_with('#') {
                    format!("#{l}")
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n")
    });
    let text = markdown(results, page.as_deref());
    let e = crate::report::markdown::embed(
        &text,
        &crate::report::markdown::Embed {
            base: path.parent().unwrap_or(root),
            top_level: 3,
            anchor_prefix: "evidence-",
            out,
            copy_to: "reconstruction",
            section_title: None,
        },
    );
    serde_json::json!({"html": e.html, "md": e.md})
}

/// Evidence checks a trivial model passes (empty when none): for the tests.
pub fn trivial_passes(results: &Value) -> Vec<String> {
    discrimination_tables(results).1
}
