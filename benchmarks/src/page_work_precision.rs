//! The work-precision part of the benchmarks' page: per problem its plot and its Pareto front
//! (`pareto::front`), the references of the errors, and the whole table sorted, from
//! work-precision.csv, work-precision-references.csv and the work-precision-*.svg beside them.

use std::fmt::Write;
use std::path::Path;

use crate::pareto;
use crate::table::{num, Table};

/// What the benchmark measures, for the page.
const ABOUT: &str = "Each configuration (element, mesh, CFL fraction) of each problem is run and timed (setup + time loop, the minimum of its runs: `runs` in the table, their spread `loop_spread` = slowest / fastest loop - 1) and its error measured against a reference computed once, untimed (finer mesh, see the table of references): for the impact problems the largest relative error of impulse, final impactor velocity and maximum displacement; for the pulse the RMS error of the mid-span displacement history relative to its peak; for the plane-strain P wave (wave-p, 4 x ny elements through 20 mm) the relative error of the measured wave speed against the closed form c_P, an analytical reference. Lower left is better.";

/// The section, from the folder `dir` and its tables (None: the file is missing).
pub fn section(dir: &Path, wp: Option<&Table>, refs: Option<&Table>) -> String {
    let mut s = String::from("## Work-precision: run time against error\n\n");
    s += ABOUT;
    let sorted = wp.map(|t| {
        let mut t = t.clone();
        sort(&mut t);
        t
    });
    if let Some(t) = &sorted {
        let _ = write!(s, " {}.", levels_line(t));
    }
    s += "\n\n";
    let problems = problems(dir, sorted.as_ref());
    for p in &problems {
        s += &problem(dir, p, sorted.as_ref());
    }
    if let Some(r) = refs {
        let _ = write!(
            s,
            "**References** of the errors (work-precision-references.csv), with their own estimated error:\n\n{}\n",
            r.markdown()
        );
    }
    if let Some(t) = &sorted {
        let _ = write!(
            s,
            "<details><summary>All {} configurations (work-precision.csv), sorted by problem, element, CFL, mesh; <code>front</code>: on its problem's Pareto front</summary>\n\n{}\n</details>\n\n",
            t.rows.len(),
            with_front(t, &problems).markdown()
        );
    }
    s
}

/// The problems of the table and of the plots in `dir`, sorted.
fn problems(dir: &Path, t: Option<&Table>) -> Vec<String> {
    let mut names: Vec<String> = t
        .map(|t| {
            t.rows
                .iter()
                .map(|r| t.get(r, "problem").to_string())
                .collect()
        })
        .unwrap_or_default();
    names.extend(
        std::fs::read_dir(dir)
            .into_iter()
            .flatten()
            .flatten()
            .filter_map(|e| e.file_name().to_str().map(str::to_string))
            .filter_map(|n| {
                let p = n.strip_prefix("work-precision-")?.strip_suffix(".svg")?;
                Some(p.to_string())
            }),
    );
    names.sort();
    names.dedup();
    names
}

/// Indices of the rows of `problem` on its Pareto front (error against setup + loop time),
/// fastest first.
fn front(t: &Table, problem: &str) -> Vec<usize> {
    let rows: Vec<usize> = (0..t.rows.len())
        .filter(|&i| t.get(&t.rows[i], "problem") == problem)
        .collect();
    let points: Vec<(f64, f64)> = rows
        .iter()
        .map(|&i| {
            let r = &t.rows[i];
            let time = num(t.get(r, "setup_s")) + num(t.get(r, "loop_s"));
            (num(t.get(r, "error")), time)
        })
        .collect();
    pareto::front(&points)
        .into_iter()
        .map(|k| rows[k])
        .collect()
}

/// One problem: its plot and its Pareto front with the total time.
fn problem(dir: &Path, p: &str, t: Option<&Table>) -> String {
    let svg = format!("work-precision-{p}.svg");
    let mut s = format!("### {p}\n\n");
    if dir.join(&svg).is_file() {
        let _ = writeln!(s, "![work-precision {p}]({svg})\n");
    } else {
        let _ = writeln!(s, "No plot (`{svg}`) in the folder.\n");
    }
    let Some(t) = t else {
        return s;
    };
    let idx = front(t, p);
    let n = t.rows.iter().filter(|r| t.get(r, "problem") == p).count();
    let keep = [
        "element", "mesh", "cfl", "dt_s", "error", "setup_s", "loop_s",
    ];
    let mut header: Vec<String> = keep.iter().map(|c| c.to_string()).collect();
    header.push("total_s".into());
    let rows = idx
        .iter()
        .map(|&i| {
            let r = &t.rows[i];
            let mut row: Vec<String> = keep.iter().map(|c| t.get(r, c).to_string()).collect();
            let total = num(t.get(r, "setup_s")) + num(t.get(r, "loop_s"));
            row.push(format!("{total:.4e}"));
            row
        })
        .collect();
    let _ = write!(
        s,
        "Pareto front: {} of {n} configurations, those that no other is both faster and more accurate than; fastest first.\n\n{}\n",
        idx.len(),
        Table { header, rows }.markdown()
    );
    s
}

/// A mesh "20x4" as (20, 4) for sorting by size (text after, unparsable last).
fn mesh_key(m: &str) -> (u64, u64, String) {
    let mut it = m
        .split('x')
        .map(|p| p.trim().parse::<u64>().unwrap_or(u64::MAX));
    let nx = it.next().unwrap_or(u64::MAX);
    (nx, it.next().unwrap_or(u64::MAX), m.to_string())
}

/// The rows sorted by problem, element, cfl, mesh (meshes by size).
fn sort(t: &mut Table) {
    let key = |r: &Vec<String>| {
        let g = |c| t.get(r, c).to_string();
        (
            g("problem"),
            g("element"),
            num(&g("cfl")),
            mesh_key(&g("mesh")),
        )
    };
    let mut keyed: Vec<_> = t.rows.iter().map(|r| (key(r), r.clone())).collect();
    keyed.sort_by(|(a, _), (b, _)| {
        (&a.0, &a.1)
            .cmp(&(&b.0, &b.1))
            .then_with(|| a.2.total_cmp(&b.2))
            .then_with(|| a.3.cmp(&b.3))
    });
    t.rows = keyed.into_iter().map(|(_, r)| r).collect();
}

/// "N configurations: elements ...; meshes ...; CFL fractions ..." of the table.
fn levels_line(t: &Table) -> String {
    let vals = |name: &str| -> Vec<String> {
        let mut v: Vec<String> = Vec::new();
        for r in &t.rows {
            let c = t.get(r, name).to_string();
            if !v.contains(&c) {
                v.push(c);
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

/// The table with a column `pareto` marking the rows on their problem's front.
fn with_front(t: &Table, problems: &[String]) -> Table {
    let on: Vec<usize> = problems.iter().flat_map(|p| front(t, p)).collect();
    let mut t2 = t.clone();
    t2.header.push("pareto".into());
    for (i, r) in t2.rows.iter_mut().enumerate() {
        r.push(if on.contains(&i) { "front" } else { "" }.into());
    }
    t2
}
