//! benchmarks.md, the benchmarks' own page, written into the output folder after every
//! `impact-bench` run from what the folder holds (so `stability`, `work-precision` and
//! `throughput` run one by one into one folder still give one page of all three): on what
//! machine and at which sizes each benchmark ran (meta.json), the targets met or missed, what
//! each benchmark measures, its tables and the work-precision plots beside it (relative
//! links). `impact verify --report` embeds the page as it is (headings shifted, plots copied).

use std::fmt::Write;
use std::path::{Path, PathBuf};

use crate::common::markdown_table;
use crate::meta;
use crate::page_work_precision;
use crate::table::Table;

/// The page's file name in the output folder.
pub const PAGE: &str = "benchmarks.md";

/// The page's title (the report's section of the same words drops it when embedding).
const TITLE: &str = "Performance: work-precision, throughput, stability";

/// The files the page is made from, each with the subcommand that writes it.
const FILES: [(&str, &str); 8] = [
    ("work-precision.csv", "work-precision"),
    ("work-precision-references.csv", "work-precision"),
    ("throughput-kernels.csv", "throughput"),
    ("throughput-runs.csv", "throughput"),
    ("throughput-python.csv", "throughput"),
    ("stability-cfl.csv", "stability"),
    ("stability-extreme.csv", "stability"),
    ("stability.md", "stability"),
];

/// The folder's files as they are read: what is missing or unreadable is noted for the page.
struct Folder<'a> {
    dir: &'a Path,
    missing: Vec<String>,
    errors: Vec<String>,
}

impl Folder<'_> {
    /// `name` when it is in the folder (else noted as missing, with its subcommand).
    fn file(&mut self, name: &str) -> Option<PathBuf> {
        let p = self.dir.join(name);
        if p.is_file() {
            return Some(p);
        }
        let sub = FILES.iter().find(|f| f.0 == name).map_or("all", |f| f.1);
        self.missing
            .push(format!("`{name}` (`impact-bench {sub} --out DIR`)"));
        None
    }

    fn table(&mut self, name: &str) -> Option<Table> {
        let path = self.file(name)?;
        self.read(&path)
    }

    /// `name` when it is in the folder, not noted when it is not (a benchmark `all` does not
    /// run: its section says how to make it).
    fn optional_table(&mut self, name: &str) -> Option<Table> {
        let path = self.dir.join(name);
        path.is_file().then(|| self.read(&path)).flatten()
    }

    fn read(&mut self, path: &Path) -> Option<Table> {
        match Table::read(path) {
            Ok(t) => Some(t),
            Err(e) => {
                self.errors.push(e.to_string());
                None
            }
        }
    }
}

/// Writes `dir/benchmarks.md` (staged beside it, then moved in) and returns its path.
pub fn write(dir: &Path) -> anyhow::Result<PathBuf> {
    let text = page(dir);
    let path = dir.join(PAGE);
    crate::common::write_whole(&path, &text)?;
    Ok(path)
}

/// The page's Markdown.
fn page(dir: &Path) -> String {
    let mut f = Folder {
        dir,
        missing: Vec::new(),
        errors: Vec::new(),
    };
    let wp = f.table("work-precision.csv");
    let refs = f.table("work-precision-references.csv");
    let kernels = f.table("throughput-kernels.csv");
    let runs = f.table("throughput-runs.csv");
    let python = f.table("throughput-python.csv");
    let threads = f.optional_table("threads.csv");
    for csv in ["stability-cfl.csv", "stability-extreme.csv"] {
        f.file(csv);
    }
    let stability = f
        .file("stability.md")
        .and_then(|p| std::fs::read_to_string(p).ok());
    let body = [
        page_work_precision::section(dir, wp.as_ref(), refs.as_ref()),
        throughput(kernels.as_ref(), runs.as_ref(), python.as_ref()),
        threads_section(threads.as_ref()),
        stability_section(stability.as_deref()),
    ]
    .concat();
    let mut s = format!("# {TITLE}\n\n");
    s += &provenance(dir);
    s += &targets(kernels.as_ref(), runs.as_ref());
    if !f.missing.is_empty() {
        let _ = writeln!(s, "**Not in this folder:** {}.\n", f.missing.join("; "));
    }
    if !f.errors.is_empty() {
        let _ = writeln!(s, "**Unreadable:** {}.\n", f.errors.join("; "));
    }
    s + &body
}

/// Who wrote the page, on what machine, and how each benchmark ran (meta.json).
fn provenance(dir: &Path) -> String {
    let (ran, machine) = meta::read(dir);
    let mut s = String::from(
        "*Written by `impact-bench` (benchmarks/) from the files in this folder; `cargo run --release -p impact-benchmarks -- all --out DIR` writes them all (`--quick`: the small CI sizes). Times are wall-clock seconds on the machine and at the load the benchmarks ran with.*\n\n",
    );
    let _ = writeln!(
        s,
        "**Machine:** {}.\n",
        machine.as_deref().unwrap_or("not recorded (no meta.json)")
    );
    if !ran.is_empty() {
        let rows: Vec<Vec<String>> = ran
            .iter()
            .map(|r| {
                let size = if r.quick { "quick" } else { "default" };
                vec![
                    r.name.clone(),
                    r.date_utc.clone().unwrap_or_else(|| "-".into()),
                    match &r.sizes {
                        Some(sizes) => format!("{size}: {sizes}"),
                        None => size.into(),
                    },
                ]
            })
            .collect();
        s += &markdown_table(&["benchmark", "last run (UTC)", "sizes"], &rows);
        s += "\n";
    }
    if let Some(note) = meta::quick_note(&ran) {
        let _ = writeln!(s, "**Note:** {note}.\n");
    }
    s
}

/// The speed targets (of the kernels and the whole elasto-plastic run) and whether each is met.
fn targets(kernels: Option<&Table>, runs: Option<&Table>) -> String {
    let mut rows = Vec::new();
    if let Some(t) = kernels {
        for r in t.rows.iter().filter(|r| t.get(r, "target_ns") != "-") {
            rows.push(vec![
                format!("kernel {} {}", t.get(r, "element"), t.get(r, "material")),
                format!("{} ns per element-step", t.get(r, "ns_per_element_step")),
                format!("{} ns", t.get(r, "target_ns")),
                t.get(r, "status").to_string(),
            ]);
        }
    }
    if let Some(t) = runs {
        for r in t.rows.iter().filter(|r| t.get(r, "target") != "-") {
            let total =
                crate::table::num(t.get(r, "setup_s")) + crate::table::num(t.get(r, "loop_s"));
            rows.push(vec![
                format!("whole run {}", t.get(r, "run")),
                format!("{total:.3} s (setup + loop)"),
                t.get(r, "target").to_string(),
                t.get(r, "status").to_string(),
            ]);
        }
    }
    if rows.is_empty() {
        return String::new();
    }
    let met = rows.iter().filter(|r| r[3] == "met").count();
    format!(
        "**Targets** (speed): {met} of {} met.\n\n{}\n",
        rows.len(),
        markdown_table(&["target", "measured", "target value", "status"], &rows)
    )
}

/// The throughput section from its three CSVs.
fn throughput(kernels: Option<&Table>, runs: Option<&Table>, python: Option<&Table>) -> String {
    let mut s = String::from("## Throughput\n\n");
    let parts = [
        (kernels, "Element kernels (internal force + material update) on the 80 x 16 paper mesh, ns per element-step on one thread (best of the timed batches) against the targets, which are per core; the plastic kernels also on two threads, as a run uses them ('elastic' is the path the solver uses, the stiffness matrix for every element, the faster one: compare elastic-stress-path; throughput-kernels.csv):"),
        (runs, "Whole runs of the Table 1 paper scenes, 80 x 16 q4-sri, 3 ms (in the main job also the Kamoulakos Taylor bar with its step fixed and re-estimated every step, and `taylor-bar-step-re-estimation`: the difference of their ns per element-step, what re-estimating the step costs), best of the runs, `loop_spread` = slowest / fastest loop - 1 (throughput-runs.csv):"),
        (python, "The same scene in the independent Python FE, side by side (throughput-python.csv; solver wall times, the Python process adds interpreter start-up and imports; the impulses' difference shows both ran the same problem):"),
    ];
    for (t, what) in parts {
        if let Some(t) = t {
            let _ = write!(s, "{what}\n\n{}\n", t.markdown());
        }
    }
    s
}

/// The threads section: threads.csv (`impact-bench threads`), or how to make it.
fn threads_section(threads: Option<&Table>) -> String {
    let mut s = String::from("## Threads on a busy machine\n\nThe Table 1 elasto-plastic run (80 x 16 q4-sri, 3 ms) on one thread, on the team of threads that never falls back and on the default (the team, falling back to one thread while it is measured slower: `solver/src/kernels/fallback.rs`), interleaved, idle and with the other cores busy (spinning processes); wall times in s, the minimum and the median of the runs; target: busy, the default at most 1.1 x one thread; idle, at most 1.05 x the team without fallback");
    match threads {
        Some(t) => {
            let _ = write!(s, " (threads.csv):\n\n{}\n", t.markdown());
        }
        None => s += ": not measured in this folder (`impact-bench threads --out DIR`, not part of `all`: it loads the machine on purpose).\n\n",
    }
    s
}

/// The stability section: stability.md (which `impact-bench stability` writes with the CFL
/// sweep, the measured critical ratio and the extreme inputs) one heading level down.
fn stability_section(page: Option<&str>) -> String {
    let mut s = String::from("## Stability\n\nEvery run must stay bounded (energy balance and impulse identity within their bounds) or stop with a clear error; a silent blow-up is a failure. The CFL sweep's rows are in stability-cfl.csv, the extreme inputs' in stability-extreme.csv; the measured critical ratio is on this page only.\n\n");
    if let Some(text) = page {
        for line in text.lines() {
            if line.starts_with('#') {
                s.push('#');
            }
            s += line;
            s.push('\n');
        }
        s.push('\n');
    }
    s
}
