//! Files of a run: `history.csv`, `summary.json`, VTK fields (`fields/*.vtu` + `fields.pvd`),
//! written into a staging folder and moved into place only when the run succeeds, so a
//! failed run leaves nothing half-written behind.

use std::fs;
use std::io::{BufReader, BufWriter, Read, Write};
use std::path::{Path, PathBuf};

use crate::input::error::{Error, Result};
use crate::input::estimate::budget::Estimate;
use crate::input::scene::Scene;
use crate::mesh::Mesh;
use crate::output::out_dir::{
    check_out_dir, clean_stale_staging, in_user_terms, staging_dir, OutLock,
};
use crate::run::{simulate_into, simulate_within, Outcome};
use crate::time_loop::energy::BalanceMonitor;
use crate::time_loop::history::{History, HistorySink};
use crate::time_loop::observer::{FieldFrame, Observer};
use crate::time_loop::progress::{Progress, ProgressMode};

pub use crate::output::out_dir::{OUTPUT_FILES, STOPPED_FILE};

/// Writes the history as CSV: a header of column names carrying their units, then one row
/// per output time; numbers in Rust's shortest round-trip form.
pub fn write_history(history: &History, path: &Path) -> Result<()> {
    let io = |e| Error::write(path, e);
    let mut w = BufWriter::new(fs::File::create(path).map_err(io)?);
    writeln!(w, "{}", history.columns.join(",")).map_err(io)?;
    for r in 0..history.n_rows() {
        write_row(&mut w, history.row(r)).map_err(io)?;
    }
    w.flush().map_err(io)
}

/// One CSV row of [`write_history`]'s format.
fn write_row(w: &mut impl Write, row: &[f64]) -> std::io::Result<()> {
    let mut first = true;
    for x in row {
        if !first {
            w.write_all(b",")?;
        }
        write!(w, "{x}")?;
        first = false;
    }
    w.write_all(b"\n")
}

/// The history streamed to disk as the run produces it, so that memory does not grow with
/// the run's length: the same bytes as [`write_history`] of the in-memory history. A row's
/// last value (the energy balance error) is known only when the run ends (it is divided by
/// the run's largest energy), so the rows go as raw `f64`s into a spill file beside the CSV
/// (`<name>.rows`) as they come, and [`HistorySink::finish`] writes the CSV from it, one row
/// at a time, and removes it.
pub struct HistoryFile {
    path: PathBuf,
    spill_path: PathBuf,
    spill: Option<BufWriter<fs::File>>,
    /// The columns, named with their units.
    pub columns: Vec<String>,
    /// Rows written so far.
    pub rows: u64,
    /// The last row's time, s (NaN before the first).
    pub last_time_s: f64,
    /// Whether a run that stops on an error still writes its rows so far
    /// ([`HistorySink::abandon`]).
    pub keep_partial: bool,
}

impl HistoryFile {
    /// A sink writing the CSV to `path` (nothing is created before the run begins).
    pub fn new(path: &Path) -> HistoryFile {
        let mut spill = path.as_os_str().to_owned();
        spill.push(".rows");
        HistoryFile {
            path: path.to_path_buf(),
            spill_path: spill.into(),
            spill: None,
            columns: Vec::new(),
            rows: 0,
            last_time_s: f64::NAN,
            keep_partial: false,
        }
    }

    fn write_csv(&mut self, balance: &BalanceMonitor) -> std::io::Result<()> {
        let width = self.columns.len();
        let mut spill = BufReader::new(fs::File::open(&self.spill_path)?);
        let mut w = BufWriter::new(fs::File::create(&self.path)?);
        writeln!(w, "{}", self.columns.join(","))?;
        let mut bytes = vec![0u8; 8 * width];
        let mut row = vec![0.0; width];
        for _ in 0..self.rows {
            spill.read_exact(&mut bytes)?;
            for (x, b) in row.iter_mut().zip(bytes.chunks_exact(8)) {
                *x = f64::from_le_bytes(b.try_into().expect("8 bytes"));
            }
            row[width - 1] = balance.ratio(row[width - 1]);
            write_row(&mut w, &row)?;
        }
        w.flush()
    }
}

impl HistorySink for HistoryFile {
    fn begin(&mut self, columns: &[String]) -> Result<()> {
        self.columns = columns.to_vec();
        let file = fs::File::create(&self.spill_path).map_err(|e| Error::write(&self.path, e))?;
        self.spill = Some(BufWriter::new(file));
        Ok(())
    }
    fn row(&mut self, row: &[f64]) -> Result<()> {
        let spill = self.spill.as_mut().expect("begin() comes first");
        for x in row {
            spill
                .write_all(&x.to_le_bytes())
                .map_err(|e| Error::write(&self.path, e))?;
        }
        self.rows += 1;
        self.last_time_s = row[0];
        Ok(())
    }
    fn finish(&mut self, balance: &BalanceMonitor) -> Result<()> {
        if let Some(mut spill) = self.spill.take() {
            spill.flush().map_err(|e| Error::write(&self.path, e))?;
        }
        self.write_csv(balance)
            .map_err(|e| Error::write(&self.path, e))?;
        fs::remove_file(&self.spill_path).map_err(|e| Error::write(&self.spill_path, e))
    }
    fn abandon(&mut self, balance: &BalanceMonitor) -> Result<()> {
        if self.keep_partial && self.spill.is_some() {
            self.finish(balance)?;
        }
        Ok(())
    }
    fn holds_rows(&self) -> bool {
        false
    }
}

pub fn write_json<T: serde::Serialize>(value: &T, path: &Path) -> Result<()> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::write(path, std::io::Error::other(e)))?;
    fs::write(path, text + "\n").map_err(|e| Error::write(path, e))
}

/// Writes VTK frames as they come, shows progress, passes on stop requests.
struct FileObserver<'a> {
    mesh: &'a Mesh,
    fields_dir: Option<PathBuf>,
    frames: Vec<(f64, String)>,
    progress: Progress,
    stop: Option<&'a StopHook>,
}

impl Observer for FileObserver<'_> {
    fn progress(&mut self, time: f64, end: f64) {
        self.progress.at(time, end);
    }
    fn stop_requested(&self) -> bool {
        crate::time_loop::interrupt::stop_requested() || self.stop.is_some_and(|hook| (hook.0)())
    }
    fn wants_fields(&self) -> bool {
        self.fields_dir.is_some()
    }
    fn fields(&mut self, frame: FieldFrame) -> Result<()> {
        let Some(dir) = &self.fields_dir else {
            return Ok(());
        };
        let name = format!("frame_{:05}.vtu", self.frames.len());
        write_vtu(self.mesh, &frame, &dir.join(&name))?;
        self.frames.push((frame.time, format!("fields/{name}")));
        Ok(())
    }
}

/// How `impact simulate` runs a scene file.
#[derive(Debug, Clone)]
pub struct RunOptions {
    pub progress: ProgressMode,
    /// Largest memory estimate accepted, bytes (default: what the machine has available).
    pub max_memory: Option<f64>,
    /// Write into a non-empty folder that holds no earlier run.
    pub force: bool,
    /// Also hold the history in memory ([`Outcome::history`]; the Python package's `Run.history`).
    /// Without it the history is streamed to `history.csv` as the run goes (memory does not
    /// grow with `time.end`) and `Outcome::history` holds the column names only.
    pub keep_history: bool,
    /// Asked at every stop poll beside the signal flag (e.g. Python's signal handlers).
    pub stop: Option<StopHook>,
    /// When a streamed run (`keep_history: false`) stops on an error or a stop request after
    /// its loop began, publish what it wrote: `history.csv` up to its last row, the field
    /// frames and `fields.pvd`, and `stopped.json` (why and when) instead of `summary.json`.
    pub keep_partial: bool,
}

/// A caller's own stop request, polled with the signal flag: `true` stops the run.
#[derive(Clone)]
pub struct StopHook(pub std::sync::Arc<dyn Fn() -> bool + Send + Sync>);

impl std::fmt::Debug for StopHook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("StopHook")
    }
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            progress: ProgressMode::Off,
            max_memory: None,
            force: false,
            keep_history: false,
            keep_partial: false,
            stop: None,
        }
    }
}

/// Runs a scene file and writes its outputs into `out_dir`. Nothing is left in `out_dir`
/// when it fails; earlier outputs of the same names are replaced when it succeeds.
pub fn simulate_to_dir(scene_path: &Path, out_dir: &Path, progress: bool) -> Result<Outcome> {
    let options = RunOptions {
        progress: if progress {
            ProgressMode::Bar
        } else {
            ProgressMode::Off
        },
        ..RunOptions::default()
    };
    simulate_to_dir_with(scene_path, out_dir, &options, &mut |_| {})
}

/// [`simulate_to_dir`] with options; `say` receives notes for the user (the estimate, a
/// warning for a long run, stale staging folders removed).
pub fn simulate_to_dir_with(
    scene_path: &Path,
    out_dir: &Path,
    options: &RunOptions,
    say: &mut dyn FnMut(String),
) -> Result<Outcome> {
    simulate_scene_to_dir_with(&Scene::from_file(scene_path)?, out_dir, options, say)
}

/// [`simulate_to_dir_with`] for a scene already read (the Python package's
/// `simulate(..., out=DIR)` writes through this, so its files and protections are the CLI's).
pub fn simulate_scene_to_dir_with(
    scene: &Scene,
    out_dir: &Path,
    options: &RunOptions,
    say: &mut dyn FnMut(String),
) -> Result<Outcome> {
    check_out_dir(out_dir, options.force)?;
    let (_lock, stale_lock) = OutLock::take(out_dir)?;
    if let Some(path) = stale_lock {
        say(format!(
            "removed {}, left by a run that was killed",
            path.display()
        ));
    }
    let estimate = if options.keep_history {
        Estimate::of(scene)
    } else {
        Estimate::of(scene).streamed()
    };
    for warning in &scene.warnings {
        say(format!("warning: {warning}"));
    }
    crate::input::estimate::budget::check(scene, &estimate, options.max_memory)?;
    say(format!("simulate: {}", estimate.describe()));
    for (path, failure) in clean_stale_staging(out_dir) {
        say(match failure {
            None => format!("removed {}, left by a run that was killed", path.display()),
            Some(why) => format!(
                "warning: {} was left by a run that was killed and cannot be removed: {why}",
                path.display()
            ),
        });
    }
    let staging = staging_dir(out_dir);
    let what = format!(
        "{} elements",
        crate::input::estimate::budget::count(estimate.elements)
    );
    let result = run_into(
        scene,
        &staging,
        Progress::start(options.progress, &what),
        options,
    )
    .and_then(|outcome| {
        publish(&staging, out_dir)?;
        Ok(outcome)
    });
    let kept = result.is_err()
        && staging.join(STOPPED_FILE).exists()
        && publish(&staging, out_dir).is_ok();
    if kept {
        say(format!(
            "kept the partial output in {} (history.csv up to the stop, {STOPPED_FILE}; no summary.json)",
            out_dir.display()
        ));
    }
    if let Ok(Outcome { summary, .. }) = &result {
        if let Some(fallback) = summary.threads_fallback {
            say(fallback.note(summary.n_steps));
        }
    }
    let removed = fs::remove_dir_all(&staging).is_ok();
    result.map_err(|e| match in_user_terms(e, &staging, out_dir) {
        Error::Interrupted { step, time_s, .. } => Error::Interrupted {
            step,
            time_s,
            cleanup: if kept {
                format!("; kept the partial output in {}", out_dir.display())
            } else {
                format!(
                    "; {} the staging folder {}; {} was left as it was",
                    if removed { "removed" } else { "no" },
                    staging.display(),
                    out_dir.display()
                )
            },
        },
        other => other,
    })
}

fn run_into(
    scene: &Scene,
    staging: &Path,
    progress: Progress,
    options: &RunOptions,
) -> Result<Outcome> {
    let _ = fs::remove_dir_all(staging);
    fs::create_dir_all(staging).map_err(|e| Error::write(staging, e))?;
    let mesh = crate::mesh::PlateMesh::of_scene(scene);
    let fields_dir = scene.output.fields_every.map(|_| staging.join("fields"));
    if let Some(dir) = &fields_dir {
        fs::create_dir_all(dir).map_err(|e| Error::write(dir, e))?;
    }
    let mut observer = FileObserver {
        mesh: &mesh.mesh,
        fields_dir,
        frames: Vec::new(),
        progress,
        stop: options.stop.as_ref(),
    };
    let history_path = staging.join("history.csv");
    let outcome = if options.keep_history {
        simulate_within(scene, &mut observer, options.max_memory).and_then(|outcome| {
            write_history(&outcome.history, &history_path)?;
            Ok(outcome)
        })
    } else {
        let mut file = HistoryFile::new(&history_path);
        file.keep_partial = options.keep_partial;
        let result = simulate_into(scene, &mut observer, options.max_memory, &mut file).map(
            |(summary, mesh)| Outcome {
                summary,
                history: History {
                    columns: file.columns.clone(),
                    values: Vec::new(),
                },
                mesh,
            },
        );
        if let (Err(e), true) = (&result, options.keep_partial && history_path.exists()) {
            write_stopped(e, &file, &observer.frames, staging)?;
        }
        result
    };
    observer.progress.finish();
    let outcome = outcome?;
    write_json(&outcome.summary, &staging.join("summary.json"))?;
    if !observer.frames.is_empty() {
        write_pvd(&observer.frames, &staging.join("fields.pvd"))?;
    }
    Ok(outcome)
}

/// What a run that stopped before its end kept (`RunOptions::keep_partial`): `stopped.json`
/// (the error, the rows written and the last row's time) and the frames' `fields.pvd`.
fn write_stopped(
    error: &Error,
    history: &HistoryFile,
    frames: &[(f64, String)],
    staging: &Path,
) -> Result<()> {
    let stopped = serde_json::json!({
        "error": error.to_string(),
        "history_rows": history.rows,
        "last_row_time_s": history.last_time_s,
        "what": "the partial output of a run that stopped before its end: history.csv holds its rows up to the stop (the energy balance error divided by the largest energy so far), fields/ its frames; there is no summary.json",
    });
    write_json(&stopped, &staging.join(STOPPED_FILE))?;
    if !frames.is_empty() {
        write_pvd(frames, &staging.join("fields.pvd"))?;
    }
    Ok(())
}

/// Moves the staged files into `out_dir`, replacing earlier outputs of the same names.
fn publish(staging: &Path, out_dir: &Path) -> Result<()> {
    fs::create_dir_all(out_dir).map_err(|e| Error::write(out_dir, e))?;
    for name in OUTPUT_FILES {
        let target = out_dir.join(name);
        if target.is_dir() {
            fs::remove_dir_all(&target).map_err(|e| Error::write(&target, e))?;
        } else if target.exists() {
            fs::remove_file(&target).map_err(|e| Error::write(&target, e))?;
        }
        let staged = staging.join(name);
        if staged.exists() {
            fs::rename(&staged, &target).map_err(|e| Error::write(&target, e))?;
        }
    }
    Ok(())
}

/// One VTK UnstructuredGrid (ASCII XML) frame: nodal displacement and velocity (and the
/// nose's force on the nodes under the surface coupling), element stress (average of the
/// integration points), von Mises stress and equivalent plastic strain.
fn write_vtu(mesh: &Mesh, frame: &FieldFrame, path: &Path) -> Result<()> {
    let io = |e| Error::write(path, e);
    let mut w = BufWriter::new(fs::File::create(path).map_err(io)?);
    let (np, nc) = (mesh.coords.len(), mesh.elements.len());
    let mut s = String::with_capacity(64 * (np + nc));
    use std::fmt::Write as _;
    let _ = writeln!(s, "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nc}\">");
    let _ = writeln!(
        s,
        "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
    );
    for p in &mesh.coords {
        let _ = writeln!(s, "{} {} 0", p[0], p[1]);
    }
    s.push_str("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n");
    for e in &mesh.elements {
        let _ = writeln!(s, "{} {} {} {}", e[0], e[1], e[2], e[3]);
    }
    s.push_str("</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n");
    for i in 1..=nc {
        let _ = writeln!(s, "{}", 4 * i);
    }
    s.push_str("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for _ in 0..nc {
        s.push_str("9\n");
    }
    s.push_str("</DataArray>\n</Cells>\n<PointData Vectors=\"displacement_m\">\n");
    let mut vectors = vec![
        ("displacement_m", &frame.displacement),
        ("velocity_mps", &frame.velocity),
    ];
    if let Some(f) = &frame.contact_force {
        vectors.push(("contact_force_N", f));
    }
    for (name, data) in vectors {
        let _ = writeln!(s, "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"3\" format=\"ascii\">");
        for d in data {
            let _ = writeln!(s, "{} {} 0", d[0], d[1]);
        }
        s.push_str("</DataArray>\n");
    }
    s.push_str("</PointData>\n<CellData Scalars=\"von_mises_Pa\">\n");
    let stress_names = ["sxx_Pa", "syy_Pa", "szz_Pa", "sxy_Pa"];
    for (c, name) in stress_names.iter().enumerate() {
        scalar_array(&mut s, name, frame.stress.iter().map(|st| st[c]));
    }
    scalar_array(&mut s, "von_mises_Pa", frame.von_mises.iter().copied());
    scalar_array(&mut s, "eqps", frame.eqps.iter().copied());
    if let Some(rate) = &frame.plastic_strain_rate {
        scalar_array(&mut s, "plastic_strain_rate_1_s", rate.iter().copied());
    }
    if let Some(t) = &frame.temperature {
        scalar_array(&mut s, "temperature_K", t.iter().copied());
    }
    s.push_str("</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    w.write_all(s.as_bytes()).map_err(io)?;
    w.flush().map_err(io)
}

fn scalar_array(s: &mut String, name: &str, values: impl Iterator<Item = f64>) {
    use std::fmt::Write as _;
    let _ = writeln!(
        s,
        "<DataArray type=\"Float64\" Name=\"{name}\" format=\"ascii\">"
    );
    for v in values {
        let _ = writeln!(s, "{v}");
    }
    s.push_str("</DataArray>\n");
}

/// The ParaView collection indexing the frames by time.
fn write_pvd(frames: &[(f64, String)], path: &Path) -> Result<()> {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n",
    );
    for (t, file) in frames {
        s.push_str(&format!(
            "<DataSet timestep=\"{t}\" part=\"0\" file=\"{file}\"/>\n"
        ));
    }
    s.push_str("</Collection>\n</VTKFile>\n");
    fs::write(path, s).map_err(|e| Error::write(path, e))
}
