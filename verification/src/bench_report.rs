//! The report's "Performance: work-precision, throughput, stability" section, from a folder
//! written by `impact-bench all --out DIR` (benchmarks/): work-precision.csv and its plots,
//! work-precision-references.csv, throughput-kernels.csv, throughput-runs.csv, stability.md
//! (stability-cfl.csv and stability-extreme.csv when stability.md is missing).

use std::path::Path;

use serde_json::{json, Value};

use crate::markdown::{embed, svg_element, Embed};

/// The command that writes the folder.
pub const HOW: &str = "cargo run --release -p impact-benchmarks -- all --out DIR";

/// A CSV file as a header and rows of text. The benchmarks write their CSVs unquoted, and a
/// free-text last column ("note") may hold commas: extra fields are joined back into the last.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

pub fn read_table(path: &Path) -> anyhow::Result<Table> {
    let mut r = csv::ReaderBuilder::new()
        .flexible(true)
        .has_headers(true)
        .from_path(path)?;
    let header: Vec<String> = r.headers()?.iter().map(str::to_string).collect();
    anyhow::ensure!(!header.is_empty(), "{}: no header", path.display());
    let n = header.len();
    let mut rows = Vec::new();
    for rec in r.records() {
        let rec = rec?;
        let mut row: Vec<String> = rec.iter().map(str::to_string).collect();
        if row.len() > n {
            let tail = row.split_off(n - 1).join(",");
            row.push(tail);
        }
        row.resize(n, String::new());
        rows.push(row);
    }
    Ok(Table { header, rows })
}

fn md_cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

/// A Markdown table.
pub fn md_table(t: &Table) -> String {
    let mut s = format!(
        "| {} |\n|{}|\n",
        t.header
            .iter()
            .map(|h| md_cell(h))
            .collect::<Vec<_>>()
            .join(" | "),
        vec!["---"; t.header.len()].join("|")
    );
    for r in &t.rows {
        s += &format!(
            "| {} |\n",
            r.iter().map(|c| md_cell(c)).collect::<Vec<_>>().join(" | ")
        );
    }
    s
}

fn looks_numeric(s: &str) -> bool {
    let s = s.trim().trim_start_matches("<= ").trim_start_matches("< ");
    !s.is_empty() && (s.parse::<f64>().is_ok() || s.split('x').all(|p| p.parse::<u64>().is_ok()))
}

/// A table for the templates: header, rows of {v, cls} (cls: num, OK, FAIL, SKIP), and its
/// Markdown.
fn table_value(t: &Table) -> Value {
    let rows: Vec<Value> = t
        .rows
        .iter()
        .map(|r| {
            Value::Array(
                r.iter()
                    .map(|c| {
                        let cls = match c.as_str() {
                            "met" | "bounded" => "OK",
                            "missed" | "UNBOUNDED" => "FAIL",
                            "coarse" => "SKIP",
                            _ if looks_numeric(c) => "num",
                            _ => "",
                        };
                        json!({"v": c, "cls": cls})
                    })
                    .collect(),
            )
        })
        .collect();
    json!({"header": t.header, "rows": rows, "md": md_table(t)})
}

fn mesh_key(m: &str) -> (u64, u64, String) {
    let mut it = m
        .split('x')
        .map(|p| p.trim().parse::<u64>().unwrap_or(u64::MAX));
    (
        it.next().unwrap_or(u64::MAX),
        it.next().unwrap_or(u64::MAX),
        m.to_string(),
    )
}

fn num(s: &str) -> f64 {
    s.trim().parse().unwrap_or(f64::NAN)
}

/// The work-precision rows sorted by problem, element, cfl, mesh (meshes by size).
pub fn sort_work_precision(t: &mut Table) {
    let col = |name: &str| t.header.iter().position(|h| h == name);
    let (p, e, c, m) = (col("problem"), col("element"), col("cfl"), col("mesh"));
    let get =
        |r: &Vec<String>, i: Option<usize>| i.and_then(|i| r.get(i)).cloned().unwrap_or_default();
    t.rows.sort_by(|a, b| {
        get(a, p)
            .cmp(&get(b, p))
            .then_with(|| get(a, e).cmp(&get(b, e)))
            .then_with(|| num(&get(a, c)).total_cmp(&num(&get(b, c))))
            .then_with(|| mesh_key(&get(a, m)).cmp(&mesh_key(&get(b, m))))
    });
}

/// Indices of the rows of `problem` on the Pareto front: no other configuration of the
/// problem is both faster (setup + loop) and more accurate (at least as good in both, better
/// in one). Sorted from the fastest to the most accurate.
pub fn pareto(t: &Table, problem: &str) -> Vec<usize> {
    let col = |name: &str| t.header.iter().position(|h| h == name);
    let (Some(p), Some(e), Some(s), Some(l)) =
        (col("problem"), col("error"), col("setup_s"), col("loop_s"))
    else {
        return Vec::new();
    };
    let pts: Vec<(usize, f64, f64)> = t
        .rows
        .iter()
        .enumerate()
        .filter(|(_, r)| r[p] == problem)
        .map(|(i, r)| (i, num(&r[e]), num(&r[s]) + num(&r[l])))
        .filter(|(_, e, t)| e.is_finite() && t.is_finite())
        .collect();
    let mut front: Vec<(usize, f64, f64)> = pts
        .iter()
        .filter(|(_, e, t)| {
            !pts.iter()
                .any(|(_, e2, t2)| (e2 < e && t2 <= t) || (e2 <= e && t2 < t))
        })
        .copied()
        .collect();
    front.sort_by(|a, b| a.2.total_cmp(&b.2).then(b.1.total_cmp(&a.1)));
    front.into_iter().map(|f| f.0).collect()
}

/// A file's modification time, UTC, as 2025-01-31T12:00:00Z.
pub fn modified(path: &Path) -> Option<String> {
    let t = std::fs::metadata(path).ok()?.modified().ok()?;
    let secs = t.duration_since(std::time::UNIX_EPOCH).ok()?.as_secs() as i64;
    // Civil date from days since 1970-01-01 (Howard Hinnant's algorithm), UTC.
    let (days, rem) = (secs.div_euclid(86400), secs.rem_euclid(86400));
    let z = days + 719468;
    let era = z.div_euclid(146097);
    let doe = z - era * 146097;
    let yoe = (doe - doe / 1460 + doe / 36524 - doe / 146096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    Some(format!(
        "{y:04}-{m:02}-{d:02}T{:02}:{:02}:{:02}Z",
        rem / 3600,
        rem % 3600 / 60,
        rem % 60
    ))
}

/// The context of the performance section. `dir`: the benchmarks folder (None: none given
/// and none found). Plots are copied to `out/plots/` for report.md.
pub fn context(dir: Option<&Path>, out: &Path) -> Value {
    let Some(dir) = dir.filter(|d| d.is_dir()) else {
        // The templates say how to produce it; `given` is the folder asked for, if any.
        return json!({"present": false, "given": dir.map(|d| d.display().to_string()), "how": HOW});
    };
    let mut missing = Vec::new();
    let mut need = |file: &str, sub: &str| {
        let p = dir.join(file);
        if p.is_file() {
            Some(p)
        } else {
            missing.push(json!({"file": file, "sub": sub}));
            None
        }
    };
    let wp_path = need("work-precision.csv", "work-precision");
    let refs_path = need("work-precision-references.csv", "work-precision");
    let kernels_path = need("throughput-kernels.csv", "throughput");
    let runs_path = need("throughput-runs.csv", "throughput");
    let stab_md_path = dir.join("stability.md");
    let stab_md_path = stab_md_path.is_file().then_some(stab_md_path);
    if stab_md_path.is_none() {
        need("stability.md", "stability");
    }
    let mut errors = Vec::new();
    let mut load = |p: &Option<std::path::PathBuf>| -> Option<Table> {
        let p = p.as_ref()?;
        match read_table(p) {
            Ok(t) => Some(t),
            Err(e) => {
                errors.push(format!("{}: {e}", p.display()));
                None
            }
        }
    };
    let wp = load(&wp_path);
    let refs = load(&refs_path);
    let kernels = load(&kernels_path);
    let runs = load(&runs_path);
    // Optional: written by `impact-bench throughput` since the Python side-by-side was added.
    let python = load(&Some(dir.join("throughput-python.csv")).filter(|p| p.is_file()));
    let (cfl_csv, extreme_csv) = if stab_md_path.is_none() {
        let f = |n: &str| Some(dir.join(n)).filter(|p| p.is_file());
        (
            load(&f("stability-cfl.csv")),
            load(&f("stability-extreme.csv")),
        )
    } else {
        (None, None)
    };

    // Work-precision: per problem, the plot and the Pareto front; the whole table sorted.
    let mut problems: Vec<String> = Vec::new();
    if let Some(t) = &wp {
        if let Some(p) = t.header.iter().position(|h| h == "problem") {
            for r in &t.rows {
                if !problems.contains(&r[p]) {
                    problems.push(r[p].clone());
                }
            }
        }
    }
    let mut svg_names: Vec<String> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter_map(|e| e.file_name().to_str().map(str::to_string))
        .filter(|n| n.starts_with("work-precision-") && n.ends_with(".svg"))
        .collect();
    svg_names.sort();
    for n in &svg_names {
        let p = n
            .trim_start_matches("work-precision-")
            .trim_end_matches(".svg")
            .to_string();
        if !problems.contains(&p) {
            problems.push(p);
        }
    }
    problems.sort();
    let _ = std::fs::create_dir_all(out.join("plots"));
    let mut wp_problems = Vec::new();
    let mut sorted = wp.clone();
    if let Some(t) = &mut sorted {
        sort_work_precision(t);
    }
    for p in &problems {
        wp_problems.push(problem_entry(p, dir, out, sorted.as_ref()));
    }
    // The whole table, with the Pareto membership marked.
    let all = sorted.as_ref().map(|t| with_front(t, &problems));
    let levels = sorted.as_ref().map(levels_line);

    let quick = quick_note(dir);
    let stability = stab_md_path
        .as_ref()
        .and_then(|p| stability_page(p, dir, out));
    json!({
        "present": true,
        "dir": dir.display().to_string(),
        "written": wp_path.as_ref().or(kernels_path.as_ref()).or(stab_md_path.as_ref()).and_then(|p| modified(p)).unwrap_or_else(|| "unknown".into()),
        "how": HOW,
        "quick": quick,
        "wp_levels": levels,
        "wp_problems": wp_problems,
        "wp_references": refs.as_ref().map(table_value),
        "wp_all": all,
        "kernels": kernels.as_ref().map(table_value),
        "runs": runs.as_ref().map(table_value),
        "python": python.as_ref().map(table_value),
        "stability": stability,
        "stability_cfl": cfl_csv.as_ref().map(table_value),
        "stability_extreme": extreme_csv.as_ref().map(table_value),
        "missing": missing,
        "errors": errors,
    })
}

/// "benchmarks ran at quick size (work-precision: meshes ...; throughput; stability)" when
/// the folder's meta.json (written by impact-bench) records a benchmark run with `--quick`;
/// None when none did or there is no readable meta.json (folders from before it existed).
pub fn quick_note(dir: &Path) -> Option<String> {
    let meta: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("meta.json")).ok()?).ok()?;
    if meta["quick"] != json!(true) {
        return None;
    }
    // In the report's order (work-precision, throughput, stability), then any other.
    let mut benchmarks: Vec<(&String, &Value)> = meta["benchmarks"].as_object()?.iter().collect();
    let rank = |n: &str| {
        ["work-precision", "throughput", "stability"]
            .iter()
            .position(|&k| k == n)
    };
    benchmarks.sort_by_key(|(n, _)| (rank(n).unwrap_or(usize::MAX), n.to_string()));
    let runs: Vec<String> = benchmarks
        .into_iter()
        .filter(|(_, b)| b["quick"] == json!(true))
        .map(|(name, b)| match b["sizes"].as_str() {
            Some(sizes) => format!("{name}: {sizes}"),
            None => name.clone(),
        })
        .collect();
    Some(format!(
        "benchmarks ran at quick size ({}); their times and errors are those of the small CI runs, not of the default sizes",
        runs.join("; ")
    ))
}

/// One work-precision problem: its plot (copied to `out/plots/`), its Pareto front with the
/// total time, and how many configurations it has.
fn problem_entry(p: &str, dir: &Path, out: &Path, sorted: Option<&Table>) -> Value {
    let svg_path = dir.join(format!("work-precision-{p}.svg"));
    let (svg, svg_file) = match std::fs::read_to_string(&svg_path)
        .ok()
        .and_then(|s| svg_element(&s))
    {
        Some(svg) => {
            let name = format!(
                "plots/benchmarks-work-precision-{}.svg",
                crate::markdown::slug(p)
            );
            let _ = std::fs::write(out.join(&name), &svg);
            (svg, name)
        }
        None => (String::new(), String::new()),
    };
    let mut front = Value::Null;
    let mut n_configs = 0;
    if let Some(t) = sorted {
        let idx = pareto(t, p);
        let col = |name: &str| t.header.iter().position(|h| h == name);
        if let Some(pc) = col("problem") {
            n_configs = t.rows.iter().filter(|r| r[pc] == *p).count();
        }
        let keep: Vec<usize> = [
            "element", "mesh", "cfl", "dt_s", "error", "setup_s", "loop_s",
        ]
        .iter()
        .filter_map(|c| col(c))
        .collect();
        let (s, l) = (col("setup_s"), col("loop_s"));
        let mut header: Vec<String> = keep.iter().map(|&i| t.header[i].clone()).collect();
        header.push("total_s".into());
        let rows = idx
            .iter()
            .map(|&i| {
                let r = &t.rows[i];
                let mut row: Vec<String> = keep.iter().map(|&k| r[k].clone()).collect();
                let total = s
                    .zip(l)
                    .map(|(s, l)| num(&r[s]) + num(&r[l]))
                    .unwrap_or(f64::NAN);
                row.push(format!("{total:.4e}"));
                row
            })
            .collect();
        front = table_value(&Table { header, rows });
    }
    json!({"name": p, "svg": svg, "svg_file": svg_file, "pareto": front, "n": n_configs})
}

/// "N configurations: elements ...; meshes ...; CFL fractions ..." of the work-precision table.
fn levels_line(t: &Table) -> String {
    let vals = |name: &str| -> Vec<String> {
        let Some(c) = t.header.iter().position(|h| h == name) else {
            return Vec::new();
        };
        let mut v: Vec<String> = Vec::new();
        for r in &t.rows {
            if !v.contains(&r[c]) {
                v.push(r[c].clone());
            }
        }
        v
    };
    let mut meshes = vals("mesh");
    meshes.sort_by_key(|m| mesh_key(m));
    let mut cfls = vals("cfl");
    cfls.sort_by(|a, b| num(a).total_cmp(&num(b)));
    format!(
        "{} configurations: elements {}; meshes {}; CFL fractions {}",
        t.rows.len(),
        vals("element").join(", "),
        meshes.join(", "),
        cfls.join(", ")
    )
}

/// The whole work-precision table with a column `pareto` marking the fronts of `problems`.
fn with_front(t: &Table, problems: &[String]) -> Value {
    let mut on = std::collections::BTreeSet::new();
    for p in problems {
        on.extend(pareto(t, p));
    }
    let mut t2 = t.clone();
    t2.header.push("pareto".into());
    for (i, r) in t2.rows.iter_mut().enumerate() {
        r.push(if on.contains(&i) {
            "front".into()
        } else {
            String::new()
        });
    }
    table_value(&t2)
}

/// stability.md embedded (headings from level 4, its files copied to `out/benchmarks/`).
fn stability_page(path: &Path, dir: &Path, out: &Path) -> Option<Value> {
    let text = std::fs::read_to_string(path).ok()?;
    let e = embed(
        &text,
        &Embed {
            base: dir,
            top_level: 4,
            anchor_prefix: "bench-",
            out,
            copy_to: "benchmarks",
            section_title: None,
        },
    );
    Some(json!({"html": e.html, "md": e.md}))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn t(rows: &[&str]) -> Table {
        Table {
            header: "problem,element,mesh,cfl,dt_s,error,setup_s,loop_s"
                .split(',')
                .map(str::to_string)
                .collect(),
            rows: rows
                .iter()
                .map(|r| r.split(',').map(str::to_string).collect())
                .collect(),
        }
    }

    #[test]
    fn pareto_keeps_the_non_dominated() {
        let t = t(&[
            "a,q4-sri,10x2,0.9,1e-6,1e-1,0,1.0",  // fastest
            "a,q4-sri,20x4,0.9,1e-6,1e-2,0,2.0",  // more accurate, slower: front
            "a,q4-full,20x4,0.9,1e-6,5e-2,0,2.5", // dominated by the row above
            "a,q4-1pt,80x16,0.9,1e-6,1e-3,0,9.0", // most accurate
            "b,q4-sri,10x2,0.9,1e-6,1e-9,0,0.1",
        ]);
        assert_eq!(pareto(&t, "a"), vec![0, 1, 3]);
        assert_eq!(pareto(&t, "b"), vec![4]);
    }

    #[test]
    fn sort_by_problem_element_cfl_then_mesh_size() {
        let mut t = t(&[
            "b,q4-sri,10x2,0.3,0,0,0,0",
            "a,q4-sri,160x32,0.3,0,0,0,0",
            "a,q4-sri,20x4,0.3,0,0,0,0",
            "a,q4-sri,10x2,0.9,0,0,0,0",
            "a,q4-1pt,10x2,0.9,0,0,0,0",
        ]);
        sort_work_precision(&mut t);
        let keys: Vec<String> = t
            .rows
            .iter()
            .map(|r| format!("{} {} {} {}", r[0], r[1], r[3], r[2]))
            .collect();
        assert_eq!(
            keys,
            [
                "a q4-1pt 0.9 10x2",
                "a q4-sri 0.3 20x4",
                "a q4-sri 0.3 160x32",
                "a q4-sri 0.9 10x2",
                "b q4-sri 0.3 10x2"
            ]
        );
    }

    #[test]
    fn unquoted_commas_go_back_into_the_last_column() {
        let dir = std::env::temp_dir().join(format!("impact-bench-csv-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("s.csv");
        std::fs::write(
            &p,
            "mesh,status,note\nuniform,stopped,step 96: element 20 (x = 1, y = 2) | inverted\n",
        )
        .unwrap();
        let t = read_table(&p).unwrap();
        assert_eq!(
            t.rows[0][2],
            "step 96: element 20 (x = 1, y = 2) | inverted"
        );
        assert!(md_table(&t).contains("y = 2) \\| inverted |"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
