//! The V&V report: index.html (self-contained) and report.md from a verify output folder.

use std::path::{Path, PathBuf};

use crate::plot::{svg_plot, Series};
use crate::repo::Repo;

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

const HTML_TEMPLATE: &str = include_str!("../templates/report.html.j2");
const MD_TEMPLATE: &str = include_str!("../templates/report.md.j2");

fn fmt(x: Option<f64>) -> String {
    crate::runner::num(x)
}

fn get_f(v: &serde_json::Value) -> Option<f64> {
    v.as_f64()
}

/// History plots of a case from the runs folder, with references overlaid.
fn case_plots(c: &serde_json::Value, runs: &Path, root: &Path) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let suite = c["suite"].as_str().unwrap_or("");
    let case = c["case"].as_str().unwrap_or("");
    let dir = runs.join(suite).join(case);
    for p in c["plots"].as_array().into_iter().flatten() {
        let title = p["title"].as_str().unwrap_or("");
        let scale = p["scale"].as_f64().unwrap_or(1.0);
        let unit = p["unit"].as_str().unwrap_or("");
        let scenes: Vec<&str> = p["scenes"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|s| s.as_str())
            .collect();
        let columns: Vec<&str> = p["columns"]
            .as_array()
            .into_iter()
            .flatten()
            .filter_map(|s| s.as_str())
            .collect();
        let (xlabel, xscale) = match p["x_label"].as_str() {
            Some(l) => (l, 1.0),
            None => ("time (ms)", 1e3),
        };
        let mut series: Vec<Series> = Vec::new();
        let load = |path: &Path, col: &str| {
            crate::check::read_csv_columns(path, col).map(|(t, v)| {
                t.iter()
                    .zip(&v)
                    .map(|(t, v)| (t * xscale, v * scale))
                    .collect::<Vec<_>>()
            })
        };
        if let Some(col) = p["column"].as_str() {
            for s in &scenes {
                if let Ok(d) = load(&dir.join(s).join("history.csv"), col) {
                    series.push((s.to_string(), d, false));
                }
            }
            for r in p["references"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(|s| s.as_str())
            {
                let path = if r.starts_with("reference-data") {
                    root.join(r)
                } else {
                    dir.join(r).join("history.csv")
                };
                if let Ok(d) = load(&path, col) {
                    let label = if r.starts_with("reference-data") {
                        format!(
                            "ref: {}",
                            r.trim_start_matches("reference-data/")
                                .trim_end_matches("/history.csv")
                        )
                    } else {
                        format!("ref: {r}")
                    };
                    series.push((label, d, true));
                }
            }
            let ylabel = if unit.is_empty() {
                col.to_string()
            } else {
                format!("{col} ({unit})")
            };
            out.push((title.to_string(), svg_plot(title, xlabel, &ylabel, &series)));
        } else {
            for s in &scenes {
                let mut series: Vec<Series> = Vec::new();
                for col in &columns {
                    if let Ok(d) = load(&dir.join(s).join("history.csv"), col) {
                        series.push((col.to_string(), d, false));
                    }
                }
                out.push((
                    format!("{title} ({s})"),
                    svg_plot(title, xlabel, unit, &series),
                ));
            }
        }
    }
    // Convergence plots: log10 |f - f_extrapolated| against log10 h (h = 1 / level).
    if let Some(series) = c["series"].as_object() {
        for (name, sd) in series {
            let levels: Vec<f64> = sd["levels"]
                .as_array()
                .into_iter()
                .flatten()
                .filter_map(get_f)
                .collect();
            for (metric, vals) in sd["metrics"].as_object().into_iter().flatten() {
                let f: Vec<f64> = vals
                    .as_array()
                    .into_iter()
                    .flatten()
                    .filter_map(get_f)
                    .collect();
                let n = f.len();
                if n < 3 || levels.len() != n {
                    continue;
                }
                let r = levels[n - 1] / levels[n - 2];
                let (p, title) = match crate::gci::assess(&f, r, None) {
                    Ok(a) => {
                        let orders: Vec<String> =
                            a.orders.iter().map(|p| format!("{p:.2}")).collect();
                        let p = a.finest_order();
                        let all = orders.join(", ");
                        (p, format!("{name}: {metric}, observed order p = {p:.2} (triplets coarse to fine: {all})"))
                    }
                    Err(_) => (
                        f64::NAN,
                        format!("{name}: {metric}, not in the asymptotic range (no order)"),
                    ),
                };
                if p.is_finite() && p > 0.0 {
                    let f_ext = f[n - 1] + (f[n - 1] - f[n - 2]) / (r.powf(p) - 1.0);
                    let pts: Vec<(f64, f64)> = levels
                        .iter()
                        .zip(&f)
                        .map(|(l, v)| ((1.0 / l).log10(), (v - f_ext).abs().log10()))
                        .filter(|q| q.1.is_finite())
                        .collect();
                    let (hx, hy) = pts[pts.len() - 1];
                    let fit: Vec<(f64, f64)> =
                        pts.iter().map(|q| (q.0, hy + p * (q.0 - hx))).collect();
                    out.push((
                        title.clone(),
                        svg_plot(
                            &title,
                            "log10 (h / h_base)",
                            "log10 |f - f_extrapolated|",
                            &[
                                ("runs".into(), pts, false),
                                (format!("slope p = {p:.2}"), fit, true),
                            ],
                        ),
                    ));
                } else {
                    let pts: Vec<(f64, f64)> = levels
                        .iter()
                        .zip(&f)
                        .map(|(l, v)| ((1.0 / l).log10(), *v))
                        .collect();
                    out.push((
                        title.clone(),
                        svg_plot(
                            &title,
                            "log10 (h / h_base)",
                            metric,
                            &[("runs".into(), pts, false)],
                        ),
                    ));
                }
            }
        }
    }
    out
}

fn slug(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect()
}

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
    let e = crate::markdown::embed(
        &text,
        &crate::markdown::Embed {
            base,
            top_level: 3,
            anchor_prefix: "recon-",
            out,
            copy_to: "reconstruction",
            section_title: Some("Reproducing Dokko & Kim (2004)"),
        },
    );
    let written = crate::bench_report::modified(path).unwrap_or_else(|| "unknown".into());
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
    use anyhow::Context;
    let results_path = from.join("results.json");
    let results: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&results_path).with_context(|| {
            format!(
                "{}: run `impact verify --out DIR` first",
                results_path.display()
            )
        })?)
        .with_context(|| format!("{}", results_path.display()))?;
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
    let mut files = Vec::new();
    for c in results["cases"].as_array().into_iter().flatten() {
        let checks: Vec<serde_json::Value> = c["checks"].as_array().cloned().unwrap_or_default();
        let count = |s: &str| checks.iter().filter(|k| k["status"] == s).count();
        let (ok, fail, skip) = (count("OK"), count("FAIL"), count("SKIP"));
        let status = case_label(&checks);
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
        let mut modelling = Vec::new();
        for (scene, info) in c["modelling"].as_object().into_iter().flatten() {
            for (k, v) in info.as_object().into_iter().flatten() {
                modelling.push(serde_json::json!({"scene": scene, "key": k, "value": v}));
            }
        }
        let job_errors: Vec<String> = c["job_errors"]
            .as_object()
            .into_iter()
            .flatten()
            .map(|(k, v)| format!("{k}: {}", v.as_str().unwrap_or("")))
            .collect();
        let rows: Vec<serde_json::Value> = checks
            .iter()
            .map(|k| {
                let compare = match k["compare"].as_str() {
                    Some("at_most") => "<= ",
                    Some("at_least") => ">= ",
                    _ => "",
                };
                let error = error_cell(k);
                serde_json::json!({
                    "id": k["id"], "title": k["title"], "status": check_label(k),
                    "computed": fmt(get_f(&k["computed"])), "reference": fmt(get_f(&k["reference"])),
                    "compare": compare, "kind": k["reference_kind"], "source": k["reference_source"],
                    "error": error, "tolerance": k["tolerance"], "reason": k["tolerance_reason"],
                    "message": k["message"], "known": k["known_failure"],
                })
            })
            .collect();
        let plots = case_plots(c, &runs, &repo.root);
        let mut plot_files = Vec::new();
        let suite = c["suite"].as_str().unwrap_or("");
        for (i, (title, svg)) in plots.iter().enumerate() {
            if svg.starts_with("<svg") || svg.starts_with("<?xml") {
                let name = format!(
                    "plots/{}-{}-{i}.svg",
                    slug(suite),
                    slug(c["case"].as_str().unwrap_or(""))
                );
                std::fs::write(out.join(&name), svg)?;
                plot_files.push(name);
            }
            if suite == "energy" && title.to_lowercase().contains("energ") {
                energy_plots.push(svg.clone());
            }
        }
        cases.push(serde_json::json!({
            "suite": c["suite"], "case": c["case"], "id": c["id"], "title": c["title"],
            "anchor": slug(&format!("{}-{}", suite, c["case"].as_str().unwrap_or(""))),
            "requirement_id": c["requirement_id"], "requirement": c["requirement"],
            "category": c["category"], "heavy": c["heavy"], "problem": c["problem"],
            "ok": ok, "fail": fail, "skip": skip, "status": status,
            "references": refs, "modelling": modelling, "job_errors": job_errors,
            "checks": rows, "plots": plots.iter().map(|p| p.1.clone()).collect::<Vec<_>>(), "plot_files": plot_files,
        }));
    }
    let (table1, table2) = paper_tables(&results, &repo.root);
    let reading = reading_context(&results);
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
    let bench = crate::bench_report::context(bench_dir.as_deref(), out);
    let evidence = crate::evidence_report::context(&results, &repo.root, out);
    let ctx = serde_json::json!({
        "evidence": evidence,
        "changes": crate::baseline::report_context(from, out),
        "recon": recon,
        "bench": bench,
        "source": from.display().to_string(),
        "counts": results["counts"],
        "cases": cases,
        "table1": table1,
        "table2": table2,
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
    std::fs::write(out.join("index.html"), html)?;
    std::fs::write(out.join("report.md"), md)?;
    files.push(out.join("index.html"));
    files.push(out.join("report.md"));
    Ok(files)
}

fn rel(c: Option<f64>, p: Option<f64>) -> String {
    match (c, p) {
        (Some(c), Some(p)) if p != 0.0 => format!("{:+.1} %", 100.0 * (c / p - 1.0)),
        _ => "-".into(),
    }
}

fn short(x: Option<f64>) -> String {
    x.map_or("-".into(), |v| format!("{v:.4}"))
}

/// The first case of `suite` in results.json.
fn suite_case<'a>(results: &'a serde_json::Value, suite: &str) -> Option<&'a serde_json::Value> {
    results["cases"]
        .as_array()
        .into_iter()
        .flatten()
        .find(|c| c["suite"] == suite)
}

/// Which reading of the paper the suites run and what the literal reading costs, from this
/// run's own results: the energy balance of the default and literal pairings (energy suite)
/// and the error that stops the literal elasto-plastic run (table1 suite).
fn reading_context(results: &serde_json::Value) -> serde_json::Value {
    let case = |suite: &str| suite_case(results, suite);
    let balance = |scene: &str| {
        case("energy").and_then(|c| c["metrics"][scene]["max_energy_balance_error"].as_f64())
    };
    let literal_error = case("table1")
        .and_then(|c| c["modelling"]["literal-plastic"]["expected error"].as_str())
        .filter(|m| !m.is_empty());
    serde_json::json!({
        "present": balance("literal-pairing").is_some() || literal_error.is_some(),
        "default_elastic": fmt(balance("elastic")),
        "default_plastic": fmt(balance("plastic")),
        "literal_elastic": fmt(balance("literal-pairing")),
        "literal_plastic_error": literal_error.unwrap_or("the run did not stop (see table1/literal-reading-plastic-breaks)"),
    })
}

/// Table 1 and Table 2 rows: the paper's printed values next to the computed ones.
fn paper_tables(
    results: &serde_json::Value,
    root: &Path,
) -> (Vec<serde_json::Value>, Vec<serde_json::Value>) {
    let find = |suite: &str| suite_case(results, suite).cloned();
    let metric = |c: &Option<serde_json::Value>, scene: &str, key: &str| {
        c.as_ref().and_then(|c| c["metrics"][scene][key].as_f64())
    };
    let t1 = find("table1");
    let path1 = root.join("reference-data/paper/table1.csv");
    let mut table1 = Vec::new();
    let rows1 = [
        ("impulse", "Impulse (N s)", "impulse_Ns", 1.0),
        (
            "max_contact_load",
            "Max. contact load (kN)",
            "peak_contact_force_N",
            1e-3,
        ),
        (
            "max_plate_displacement",
            "Max. displacement (mm)",
            "max_plate_displacement_m",
            1e3,
        ),
        (
            "contact_duration",
            "Contact duration (ms)",
            "contact_duration_s",
            1e3,
        ),
        (
            "impactor_final_velocity",
            "Final impactor velocity (m/s)",
            "final_impactor_velocity_mps",
            1.0,
        ),
        (
            "max_effective_stress_point_a",
            "Max. von Mises at A (MPa)",
            "max_von_mises_Pa.A",
            1e-6,
        ),
    ];
    for (q, label, key, scale) in rows1 {
        let mut sel = std::collections::BTreeMap::new();
        sel.insert("quantity".to_string(), q.to_string());
        let p = |col: &str| crate::check::table_value(&path1, &sel, col).ok();
        let ce = metric(&t1, "elastic", key).map(|v| v * scale);
        let cp = metric(&t1, "plastic", key).map(|v| v * scale);
        let (pe, pp) = (p("elastic"), p("elasto_plastic"));
        table1.push(serde_json::json!({
            "label": label, "pe": short(pe), "ce": short(ce), "de": rel(ce, pe),
            "pp": short(pp), "cp": short(cp), "dp": rel(cp, pp),
            "pr": short(p("ratio_ep_e")), "cr": short(cp.zip(ce).map(|(a, b)| a / b)),
        }));
    }
    let t2 = find("momentum-impulse");
    let path2 = root.join("reference-data/paper/table2.csv");
    let mut table2 = Vec::new();
    for v in ["1.25", "2.5", "5", "7.5", "10", "12.5", "15"] {
        let mut sel = std::collections::BTreeMap::new();
        sel.insert("initial_velocity_mps".to_string(), v.to_string());
        let p = |col: &str| crate::check::table_value(&path2, &sel, col).ok();
        let ce = metric(&t2, &format!("elastic-v{v}"), "impulse_Ns");
        let cp = metric(&t2, &format!("plastic-v{v}"), "impulse_Ns");
        let id = [format!("elastic-v{v}"), format!("plastic-v{v}")]
            .iter()
            .filter_map(|s| {
                let i = metric(&t2, s, "impulse_Ns")?;
                let m = metric(&t2, s, "momentum_change_Ns")?;
                Some((i - m).abs() / i)
            })
            .fold(None, |a: Option<f64>, b| Some(a.map_or(b, |a| a.max(b))));
        let (pe, pp) = (p("elastic_impulse_Ns"), p("ep_impulse_Ns"));
        table2.push(serde_json::json!({
            "v": v, "pe": short(pe), "ce": short(ce), "de": rel(ce, pe),
            "pp": short(pp), "cp": short(cp), "dp": rel(cp, pp), "id": fmt(id),
        }));
    }
    (table1, table2)
}

/// A check's status as the report shows it: `FAIL*` for a declared known failure (amber),
/// `XPASS` for a known failure that passes, else the status.
fn check_label(k: &serde_json::Value) -> &'static str {
    let known = !k["known_failure"].is_null();
    match (k["status"].as_str(), known) {
        (Some("FAIL"), true) => "FAIL*",
        (Some("FAIL"), false) => "FAIL",
        (Some("OK"), true) => "XPASS",
        (Some("OK"), false) => "OK",
        _ => "SKIP",
    }
}

/// A case's status: the worst of its checks' (FAIL, XPASS, FAIL*, OK, then SKIP).
fn case_label(checks: &[serde_json::Value]) -> &'static str {
    let labels: Vec<&str> = checks.iter().map(check_label).collect();
    ["FAIL", "XPASS", "FAIL*", "OK"]
        .into_iter()
        .find(|l| labels.contains(l))
        .unwrap_or("SKIP")
}

/// The error column: the error (relative or absolute) of a two-sided check; for a one-sided
/// bound the margin to the bound, bound minus computed for `<=` and computed minus bound for
/// `>=` (positive: inside), since an "error" against a bound reads as a miss.
fn error_cell(k: &serde_json::Value) -> String {
    let (computed, bound) = (get_f(&k["computed"]), get_f(&k["reference"]));
    let margin = match (k["compare"].as_str(), computed, bound) {
        (Some("at_most"), Some(c), Some(b)) => Some(b - c),
        (Some("at_least"), Some(c), Some(b)) => Some(c - b),
        _ => None,
    };
    if let Some(m) = margin {
        return format!("margin {}", fmt(Some(m)));
    }
    match get_f(&k["error"]) {
        Some(e) => format!(
            "{}{}",
            fmt(Some(e)),
            if k["error_kind"] == "relative" {
                " rel"
            } else {
                ""
            }
        ),
        None => "-".into(),
    }
}

#[cfg(test)]
mod label_tests {
    //! The report's status labels (a known failure is FAIL*, amber, in every table; XPASS
    //! apart) and the one-sided checks' margin, on hand-written results.json check objects.
    use super::*;
    use serde_json::json;

    fn check(status: &str, known: bool) -> serde_json::Value {
        json!({"status": status, "known_failure": if known { json!("why") } else { json!(null) }})
    }

    #[test]
    fn known_failures_read_fail_star_and_the_worst_check_sets_the_case() {
        assert_eq!(check_label(&check("FAIL", true)), "FAIL*");
        assert_eq!(check_label(&check("FAIL", false)), "FAIL");
        assert_eq!(check_label(&check("OK", true)), "XPASS");
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
        let at_most = json!({"compare": "at_most", "computed": 1.0e-7, "reference": 1.0e-6,
                             "error": 68.0, "error_kind": "absolute"});
        assert_eq!(
            error_cell(&at_most),
            format!("margin {}", fmt(Some(9.0e-7)))
        );
        let at_least = json!({"compare": "at_least", "computed": 3.0, "reference": 5.0});
        assert_eq!(error_cell(&at_least), format!("margin {}", fmt(Some(-2.0))));
        let within = json!({"compare": "within", "computed": 1.1, "reference": 1.0,
                            "error": 0.1, "error_kind": "relative"});
        assert_eq!(error_cell(&within), format!("{} rel", fmt(Some(0.1))));
    }
}
