//! The V&V report: index.html (self-contained) and report.md from a verify output folder.

use std::path::{Path, PathBuf};

use crate::definition::case::ReportPlots;
use crate::definition::check::CheckResult;
use crate::definition::check_row::CheckRow;
use crate::definition::repo::Repo;
use crate::definition::verdict::Verdict;

use super::file_name::slug;

/// Writes environment.json (commit, rustc, machine, date, wall time) next to results.json.
pub fn write_environment(repo: &Repo, out: &Path, wall_s: f64, jobs: usize) -> std::io::Result<()> {
    let env = environment(repo, wall_s, jobs);
    std::fs::write(
        out.join("environment.json"),
        serde_json::to_string_pretty(&env).map_err(std::io::Error::other)? + "\n",
    )
}

fn command(cmd: &str, args: &[&str], dir: &Path) -> String {
    std::process::Command::new(cmd)
        .args(args)
        .current_dir(dir)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".into())
}

pub fn environment(repo: &Repo, wall_s: f64, jobs: usize) -> serde_json::Value {
    let dirty = command(
        "git",
        &["status", "--porcelain", "--untracked-files=no"],
        &repo.root,
    );
    let commit = command("git", &["rev-parse", "HEAD"], &repo.root);
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into());
    serde_json::json!({
        "commit": if dirty.is_empty() || dirty == "unknown" { commit } else { format!("{commit} (with uncommitted changes)") },
        "rustc": command("rustc", &["--version"], &repo.root),
        "machine": format!("{} {}, {} cores, {cpu}", std::env::consts::OS, std::env::consts::ARCH,
            std::thread::available_parallelism().map_or(1, |n| n.get())),
        "date_utc": command("date", &["-u", "+%Y-%m-%dT%H:%M:%SZ"], &repo.root),
        "wall_time_s": wall_s,
        "jobs": jobs,
    })
}

const HTML_TEMPLATE: &str = include_str!("../../templates/report.html.j2");
const MD_TEMPLATE: &str = include_str!("../../templates/report.md.j2");

/// Where the reconstruction of the paper's lost data (issue 5, `scripts/reconstruction/reconstruct.py`)
/// writes its page, relative to the repository root.
pub const RECONSTRUCTION_PAGE: &str = "reference-data/paper/reconstruction/report.md";

/// What the report embeds besides the verify results.
#[derive(Debug, Clone, Default)]
pub struct ReportOptions {
    /// The folder written by `impact-bench all --out DIR`. None: `<from>/benchmarks` or
    /// `<out>/benchmarks`, whichever exists (the section says how to produce it when neither).
    pub benchmarks: Option<PathBuf>,
    /// The reconstruction page. None: [`RECONSTRUCTION_PAGE`] under the repository root.
    pub reconstruction: Option<PathBuf>,
}

/// Writes index.html, report.md and plots/*.svg from a verify output folder (the benchmarks
/// and the reconstruction page at their default places).
pub fn write_report(from: &Path, out: &Path) -> anyhow::Result<Vec<PathBuf>> {
    write_report_with(from, out, &ReportOptions::default())
}

/// The reconstruction page's section: the page in HTML and Markdown, or that it is missing.
fn reconstruction_context(path: &Path, root: &Path, out: &Path) -> serde_json::Value {
    let shown = path
        .strip_prefix(root)
        .unwrap_or(path)
        .display()
        .to_string();
    let Ok(text) = std::fs::read_to_string(path) else {
        return serde_json::json!({"present": false, "path": shown});
    };
    let base = path.parent().unwrap_or(Path::new("."));
    let e = crate::report::markdown::embed(
        &text,
        &crate::report::markdown::Embed {
            base,
            top_level: 3,
            anchor_prefix: "recon-",
            out,
            copy_to: "reconstruction",
            section_title: Some("Reproducing Dokko & Kim (2004)"),
        },
    );
    let written = crate::report::markdown::modified(path).unwrap_or_else(|| "unknown".into());
    serde_json::json!({
        "present": true, "path": shown, "written": written,
        "html": e.html, "md": e.md, "missing": e.missing,
    })
}

/// Writes index.html, report.md and plots/*.svg from a verify output folder, with the
/// benchmarks and reconstruction page of `opts`.
pub fn write_report_with(
    from: &Path,
    out: &Path,
    opts: &ReportOptions,
) -> anyhow::Result<Vec<PathBuf>> {
    let (results, counts) = crate::report::results::read(&from.join("results.json"))?;
    let env: serde_json::Value = std::fs::read_to_string(from.join("environment.json"))
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or_else(|| serde_json::json!({}));
    let repo = std::env::current_dir()
        .ok()
        .and_then(|d| Repo::find(&d))
        .unwrap_or_else(Repo::this);
    let runs = from.join("runs");
    std::fs::create_dir_all(out.join("plots"))?;
    let mut cases = Vec::new();
    let mut energy_plots = Vec::new();
    for c in results["cases"].as_array().into_iter().flatten() {
        cases.push(case_context(c, &runs, &repo.root, out, &mut energy_plots)?);
    }
    let (table1, table2) = crate::report::paper_tables::paper_tables(&results, &repo.root);
    let reading = crate::report::paper_tables::reading_context(&results);
    let envv = serde_json::json!({
        "commit": env["commit"].as_str().unwrap_or("unknown"),
        "rustc": env["rustc"].as_str().unwrap_or("unknown"),
        "machine": env["machine"].as_str().unwrap_or("unknown"),
        "date_utc": env["date_utc"].as_str().unwrap_or("unknown"),
        "jobs": env["jobs"].as_u64().unwrap_or(0),
        "wall": format!("{:.1}", env["wall_time_s"].as_f64().unwrap_or(0.0)),
    });
    let recon_path = opts
        .reconstruction
        .clone()
        .unwrap_or_else(|| repo.root.join(RECONSTRUCTION_PAGE));
    let recon = reconstruction_context(&recon_path, &repo.root, out);
    let bench_dir = opts.benchmarks.clone().or_else(|| {
        [from.join("benchmarks"), out.join("benchmarks")]
            .into_iter()
            .find(|d| d.is_dir())
    });
    let bench = crate::report::bench_section::context(bench_dir.as_deref(), out);
    let evidence = crate::report::evidence_section::context(&results, &repo.root, out);
    let uq_dir = [from.join("uq"), out.join("uq")]
        .into_iter()
        .find(|d| d.is_dir());
    let ctx = serde_json::json!({
        "evidence": evidence,
        "experiments": crate::report::validation_section::context(&results, out),
        "codes": crate::report::codes_section::context(&results, from, &repo.root, out),
        "uq": crate::report::uq_section::context(uq_dir.as_deref(), out),
        "changes": crate::report::changes_section::context(from, out),
        "recon": recon,
        "bench": bench,
        "source": from.display().to_string(),
        "counts": counts,
        "cases": cases,
        "paper_table1": table1,
        "paper_table2": table2,
        "reading": reading,
        "energy_plots": energy_plots,
        "env": envv,
        "now": command("date", &["-u", "+%Y-%m-%dT%H:%M:%SZ"], &repo.root),
    });
    let mut jinja = minijinja::Environment::new();
    jinja.add_template("html", HTML_TEMPLATE)?;
    jinja.add_template("md", MD_TEMPLATE)?;
    let html = jinja
        .get_template("html")?
        .render(minijinja::Value::from_serialize(&ctx))?;
    let mut md_env = minijinja::Environment::new();
    md_env.set_auto_escape_callback(|_| minijinja::AutoEscape::None);
    md_env.add_template("md", MD_TEMPLATE)?;
    let md = md_env
        .get_template("md")?
        .render(minijinja::Value::from_serialize(&ctx))?;
    let _ = jinja;
    let html = crate::report::html_tokens::keep_tokens_whole(&html);
    std::fs::write(out.join("index.html"), html)?;
    std::fs::write(out.join("report.md"), md)?;
    Ok(vec![out.join("index.html"), out.join("report.md")])
}

/// One case's part of the report context: counts, status, references, the modelling table,
/// failed runs, the check rows and the plots (written to `out/plots/`; with `report: {plots:
/// [energy-balance]}` its energy plots also go to `energy_plots`).
fn case_context(
    c: &serde_json::Value,
    runs: &Path,
    root: &Path,
    out: &Path,
    energy_plots: &mut Vec<String>,
) -> std::io::Result<serde_json::Value> {
    let checks: Vec<serde_json::Value> = c["checks"].as_array().cloned().unwrap_or_default();
    let count = |s: &str| checks.iter().filter(|k| k["status"] == s).count();
    let mut refs: Vec<String> = checks
        .iter()
        .map(|k| {
            format!(
                "{}: {}",
                k["reference_kind"].as_str().unwrap_or(""),
                k["reference_source"].as_str().unwrap_or("")
            )
        })
        .collect();
    refs.sort();
    refs.dedup();
    let job_errors: Vec<String> = c["job_errors"]
        .as_object()
        .into_iter()
        .flatten()
        .map(|(k, v)| format!("{k}: {}", v.as_str().unwrap_or("")))
        .collect();
    let rows: Vec<serde_json::Value> = checks.iter().map(check_row).collect();
    let suite = c["suite"].as_str().unwrap_or("");
    let case = c["case"].as_str().unwrap_or("");
    let plots = crate::report::case_plots::case_plots(c, runs, root);
    let energy_section = crate::report::paper_tables::declared(c)
        .is_some_and(|r| r.plots.contains(&ReportPlots::EnergyBalance));
    let mut plot_files = Vec::new();
    for (i, (title, svg)) in plots.iter().enumerate() {
        if svg.starts_with("<svg") || svg.starts_with("<?xml") {
            let name = format!("plots/{}-{}-{i}.svg", slug(suite), slug(case));
            std::fs::write(out.join(&name), svg)?;
            plot_files.push(name);
        }
        if energy_section && title.to_lowercase().contains("energ") {
            energy_plots.push(svg.clone());
        }
    }
    Ok(serde_json::json!({
        "suite": c["suite"], "case": c["case"], "id": c["id"], "title": c["title"],
        "anchor": slug(&format!("{suite}-{case}")),
        "requirement_id": c["requirement_id"], "requirement": c["requirement"],
        "category": c["category"], "heavy": c["heavy"], "problem": c["problem"],
        "ok": count("OK"), "fail": count("FAIL"), "skip": count("SKIP"),
        "status": case_label(&checks),
        "references": refs, "modelling": modelling_rows(&c["modelling"]), "job_errors": job_errors,
        "checks": rows, "plots": plots.iter().map(|p| p.1.clone()).collect::<Vec<_>>(),
        "plot_files": plot_files,
        "ratings": crate::report::case_plots::reference_ratings(c, runs, root),
    }))
}

/// One row of a case's check table: the typed check read back from results.json, its cells
/// from the formatter the terminal and JUnit share.
fn check_row(k: &serde_json::Value) -> serde_json::Value {
    let Ok(typed) = serde_json::from_value::<CheckResult>(k.clone()) else {
        return serde_json::json!({"id": k["id"], "status": "FAIL", "computed": "-", "reference": "-",
            "error": "-", "message": "this check in results.json does not read back: write it again with impact verify"});
    };
    let row = CheckRow::of(&typed);
    serde_json::json!({
        "id": typed.id, "title": typed.title, "status": row.verdict.label(),
        "computed": row.computed, "reference": row.reference,
        "kind": typed.reference_kind, "source": typed.reference_source,
        "error": row.error, "tolerance": row.tolerance, "reason": typed.tolerance_reason,
        "message": typed.message, "known": typed.known_failure,
    })
}

/// The modelling table of a case (results.json's scene -> what -> value), one row per
/// `what`: a value shared by every scene once ("all 12 scenes"), else each distinct value
/// once with the scenes that share it, so a mesh or dt series reads as one row.
fn modelling_rows(modelling: &serde_json::Value) -> Vec<serde_json::Value> {
    let scenes: Vec<(&String, &serde_json::Value)> =
        modelling.as_object().into_iter().flatten().collect();
    let mut keys: Vec<&String> = Vec::new();
    for (_, info) in &scenes {
        for k in info.as_object().into_iter().flatten().map(|(k, _)| k) {
            if !keys.contains(&k) {
                keys.push(k);
            }
        }
    }
    let mut rows = Vec::new();
    for key in keys {
        // (value, scenes with it), in the scenes' order.
        let mut values: Vec<(&str, Vec<&str>)> = Vec::new();
        for (scene, info) in &scenes {
            let Some(v) = info[key.as_str()].as_str() else {
                continue;
            };
            match values.iter_mut().find(|(w, _)| *w == v) {
                Some((_, s)) => s.push(scene),
                None => values.push((v, vec![scene])),
            }
        }
        let shared = values.len() == 1 && values[0].1.len() == scenes.len();
        let lines: Vec<serde_json::Value> = values
            .iter()
            .map(|(v, s)| {
                let which = match (shared, s.len()) {
                    (true, 1) => String::new(),
                    (true, n) => format!("all {n} scenes"),
                    (false, _) => s.join(", "),
                };
                serde_json::json!({"scenes": which, "value": v})
            })
            .collect();
        rows.push(serde_json::json!({"key": key, "lines": lines}));
    }
    rows
}

/// A case's status: the worst of its checks' verdicts (FAIL, XPASS, FAIL*, OK, then SKIP).
fn case_label(checks: &[serde_json::Value]) -> &'static str {
    let verdicts: Vec<Verdict> = checks
        .iter()
        .filter_map(|k| serde_json::from_value::<CheckResult>(k.clone()).ok())
        .map(|k| Verdict::of_check(&k))
        .collect();
    [
        Verdict::Fail,
        Verdict::UnexpectedPass,
        Verdict::KnownFail,
        Verdict::Ok,
    ]
    .into_iter()
    .find(|v| verdicts.contains(v))
    .unwrap_or(Verdict::Skip)
    .label()
}

#[cfg(test)]
mod label_tests {
    //! The report's status labels (a known failure is FAIL*, amber, in every table; XPASS
    //! apart) and the one-sided checks' margin, on hand-written results.json check objects.
    use super::*;
    use serde_json::json;

    fn check(status: &str, known: bool) -> serde_json::Value {
        json!({"id": "c", "title": "t", "status": status, "computed": 1.0, "reference": 1.0,
               "error": 0.0, "error_kind": "absolute", "compare": "within", "tolerance": "abs 1e-3",
               "tolerance_reason": "r", "reference_kind": "analytical", "reference_source": "s",
               "message": "", "known_failure": if known { json!("why") } else { json!(null) }})
    }

    #[test]
    fn known_failures_read_fail_star_and_the_worst_check_sets_the_case() {
        assert_eq!(check_row(&check("FAIL", true))["status"], "FAIL*");
        assert_eq!(check_row(&check("FAIL", false))["status"], "FAIL");
        assert_eq!(check_row(&check("OK", true))["status"], "XPASS");
        let (ok, star, fail) = (
            check("OK", false),
            check("FAIL", true),
            check("FAIL", false),
        );
        assert_eq!(case_label(&[ok.clone(), star.clone()]), "FAIL*");
        assert_eq!(case_label(&[ok.clone(), star, fail]), "FAIL");
        assert_eq!(case_label(&[ok]), "OK");
        assert_eq!(case_label(&[check("SKIP", false)]), "SKIP");
    }

    #[test]
    fn one_sided_checks_show_the_margin_not_an_error() {
        let mut at_most = check("OK", false);
        at_most["compare"] = json!("at_most");
        (at_most["computed"], at_most["reference"], at_most["error"]) =
            (json!(1.0e-7), json!(1.0e-6), json!(68.0));
        let row = check_row(&at_most);
        assert_eq!(
            row["error"],
            format!("margin {}", crate::definition::check_row::num(Some(9.0e-7)))
        );
        assert_eq!(
            row["reference"],
            format!("<= {}", crate::definition::check_row::num(Some(1.0e-6)))
        );
    }

    #[test]
    fn modelling_tables_show_each_value_once_with_its_scenes() {
        // A dt series of three scenes on one mesh: one row per "what", the shared value once.
        let m = json!({
            "dt-1": {"mesh": "80 x 16 q4-sri", "dt": "1e-7 s"},
            "dt-2": {"mesh": "80 x 16 q4-sri", "dt": "5e-8 s"},
            "dt-4": {"mesh": "80 x 16 q4-sri", "dt": "2.5e-8 s"},
        });
        let rows = modelling_rows(&m);
        assert_eq!(rows.len(), 2, "{rows:?}");
        assert_eq!(rows[0]["key"], "dt");
        let dt = rows[0]["lines"].as_array().unwrap();
        assert_eq!(dt.len(), 3);
        assert_eq!(dt[0], json!({"scenes": "dt-1", "value": "1e-7 s"}));
        assert_eq!(
            rows[1]["lines"],
            json!([{"scenes": "all 3 scenes", "value": "80 x 16 q4-sri"}])
        );
    }
}
