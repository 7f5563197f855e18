//! Files of a run: `history.csv`, `summary.json`, VTK fields (`fields/*.vtu` + `fields.pvd`),
//! written into a staging folder and moved into place only when the run succeeds, so a
//! failed run leaves nothing half-written behind.

use std::fs;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::error::{Error, Result};
use crate::integrator::{FieldFrame, History, Observer};
use crate::mesh::Mesh;
use crate::scene::Scene;
use crate::{simulate, Outcome};

/// Files `impact simulate` writes into its output folder.
pub const OUTPUT_FILES: [&str; 4] = ["history.csv", "summary.json", "fields", "fields.pvd"];

/// Writes the history as CSV: a header of column names carrying their units, then one row
/// per output time; numbers in Rust's shortest round-trip form.
pub fn write_history(history: &History, path: &Path) -> Result<()> {
    let io = |e| Error::write(path, e);
    let mut w = BufWriter::new(fs::File::create(path).map_err(io)?);
    writeln!(w, "{}", history.columns.join(",")).map_err(io)?;
    for r in 0..history.n_rows() {
        let mut first = true;
        for x in history.row(r) {
            if !first {
                w.write_all(b",").map_err(io)?;
            }
            write!(w, "{x}").map_err(io)?;
            first = false;
        }
        w.write_all(b"\n").map_err(io)?;
    }
    w.flush().map_err(io)
}

pub fn write_json<T: serde::Serialize>(value: &T, path: &Path) -> Result<()> {
    let text = serde_json::to_string_pretty(value)
        .map_err(|e| Error::write(path, std::io::Error::other(e)))?;
    fs::write(path, text + "\n").map_err(|e| Error::write(path, e))
}

/// Writes VTK frames as they come and a progress bar on a terminal.
struct FileObserver<'a> {
    mesh: &'a Mesh,
    fields_dir: Option<PathBuf>,
    frames: Vec<(f64, String)>,
    bar: Option<ProgressBar>,
}

impl Observer for FileObserver<'_> {
    fn progress(&mut self, time: f64, end: f64) {
        if let Some(bar) = &self.bar {
            bar.set_position((1000.0 * time / end).round() as u64);
            bar.set_message(format!("t = {:.4} ms", time * 1e3));
        }
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

/// Runs a scene file and writes its outputs into `out_dir`. Nothing is left in `out_dir`
/// when it fails; earlier outputs of the same names are replaced when it succeeds.
pub fn simulate_to_dir(scene_path: &Path, out_dir: &Path, progress: bool) -> Result<Outcome> {
    let scene = Scene::from_file(scene_path)?;
    let staging = staging_dir(out_dir);
    let result = run_into(&scene, &staging, progress).and_then(|outcome| {
        publish(&staging, out_dir)?;
        Ok(outcome)
    });
    let _ = fs::remove_dir_all(&staging);
    result
}

fn staging_dir(out_dir: &Path) -> PathBuf {
    let name = out_dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "out".into());
    let parent = out_dir
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    parent.join(format!(".{name}.partial-{}", std::process::id()))
}

fn run_into(scene: &Scene, staging: &Path, progress: bool) -> Result<Outcome> {
    let _ = fs::remove_dir_all(staging);
    fs::create_dir_all(staging).map_err(|e| Error::write(staging, e))?;
    let mesh = crate::mesh::PlateMesh::new(&scene.plate, &scene.mesh);
    let fields_dir = scene.output.fields_every.map(|_| staging.join("fields"));
    if let Some(dir) = &fields_dir {
        fs::create_dir_all(dir).map_err(|e| Error::write(dir, e))?;
    }
    let bar = progress.then(|| {
        let bar = ProgressBar::with_draw_target(Some(1000), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template("{bar:40} {percent:>3}% {msg} ({elapsed})")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        bar
    });
    let mut observer = FileObserver {
        mesh: &mesh.mesh,
        fields_dir,
        frames: Vec::new(),
        bar,
    };
    let outcome = simulate(scene, &mut observer);
    if let Some(bar) = &observer.bar {
        bar.finish_and_clear();
    }
    let outcome = outcome?;
    write_history(&outcome.history, &staging.join("history.csv"))?;
    write_json(&outcome.summary, &staging.join("summary.json"))?;
    if !observer.frames.is_empty() {
        write_pvd(&observer.frames, &staging.join("fields.pvd"))?;
    }
    Ok(outcome)
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

/// One VTK UnstructuredGrid (ASCII XML) frame: nodal displacement and velocity, element
/// stress (average of the integration points), von Mises stress and equivalent plastic strain.
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
    for (name, data) in [
        ("displacement_m", &frame.displacement),
        ("velocity_mps", &frame.velocity),
    ] {
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
