//! The work-precision references, kept as files so that each is computed once:
//! `impact-bench references` computes them untimed (the main job runs it beside the
//! verification matrix, both untimed, before the timed benchmarks run alone), and
//! `work-precision` reads a file when this same binary wrote it for the same scene, else
//! computes the reference and writes the file. JSON numbers round-trip exactly (serde_json with
//! `float_roundtrip`), so the errors are the same bits either way.

use std::hash::{DefaultHasher, Hash, Hasher};
use std::path::{Path, PathBuf};

use impact_solver::{simulate, workers, Outcome, Quiet, Scene};
use serde::{Deserialize, Serialize};

/// What the work-precision errors need of a run (SI units).
#[derive(Serialize, Deserialize)]
pub struct Measured {
    /// Impulse N s, final impactor velocity m/s (0 without an impactor), largest plate
    /// displacement m.
    pub robust: [f64; 3],
    /// The history's times, s.
    pub time_s: Vec<f64>,
    /// The history's mid-span displacement, m.
    pub mid_uy_m: Vec<f64>,
}

impl Measured {
    pub fn of(o: &Outcome) -> Measured {
        let s = &o.summary;
        let col = |c: &str| o.history.column(c).expect("history column");
        Measured {
            robust: [
                s.impulse,
                s.final_impactor_velocity.unwrap_or(0.0),
                s.max_plate_displacement,
            ],
            time_s: col("time_s"),
            mid_uy_m: col("mid_uy_m"),
        }
    }
}

/// A reference on file, with the key of the binary and scene that made it.
#[derive(Deserialize)]
struct OnFile {
    key: String,
    reference: Measured,
}

/// How the references that are not on file run.
#[derive(Clone, Copy, PartialEq)]
pub enum Schedule {
    /// The process has the cores: the elastic ones (one thread each) side by side, the others
    /// after them, alone, with their element loop's thread team.
    Alone,
    /// Beside other untimed work: all at once, one thread each (the cores are shared anyway,
    /// and a team's spinning threads would take turns with the other work's).
    Beside,
}

/// The reference of each `(name, scene)`: read from `dir` when this binary wrote it for that
/// scene, else computed as `schedule` says and written there. Each run is the same bits
/// wherever and beside whatever it runs.
pub fn load_or_compute(
    dir: &Path,
    scenes: &[(&str, Scene)],
    schedule: Schedule,
) -> anyhow::Result<Vec<Measured>> {
    let binary = binary_hash();
    let keys: Vec<Option<String>> = scenes
        .iter()
        .map(|(_, s)| binary.map(|b| key(b, s)))
        .collect();
    let mut found: Vec<Option<Measured>> = scenes
        .iter()
        .zip(&keys)
        .map(|((name, _), k)| k.as_ref().and_then(|k| read(&path(dir, name), k)))
        .collect();
    let side_by_side =
        |(_, s): &(&str, Scene)| schedule == Schedule::Beside || s.material.plasticity.is_none();
    let missing = |i: usize, found: &[Option<Measured>]| found[i].is_none();
    let computed: Vec<Option<anyhow::Result<Outcome>>> = std::thread::scope(|t| {
        let jobs: Vec<_> = (0..scenes.len())
            .map(|i| {
                (missing(i, &found) && side_by_side(&scenes[i])).then(|| {
                    let scene = &scenes[i].1;
                    t.spawn(move || workers::with_threads(1, || run(scene)))
                })
            })
            .collect();
        jobs.into_iter()
            .map(|j| j.map(|j| j.join().expect("a reference run panicked")))
            .collect()
    });
    for (i, c) in computed.into_iter().enumerate() {
        let outcome = match c {
            Some(c) => c?,
            None if missing(i, &found) => run(&scenes[i].1)?,
            None => continue,
        };
        let reference = Measured::of(&outcome);
        if let Some(k) = &keys[i] {
            write(&path(dir, scenes[i].0), k, &reference)?;
        }
        found[i] = Some(reference);
    }
    Ok(found.into_iter().flatten().collect())
}

fn run(scene: &Scene) -> anyhow::Result<Outcome> {
    Ok(simulate(scene, &mut Quiet)?)
}

fn path(dir: &Path, name: &str) -> PathBuf {
    dir.join(format!("work-precision-reference-{name}.json"))
}

/// The file's reference when its key is `key` (None: missing, unreadable or another key).
fn read(path: &Path, key: &str) -> Option<Measured> {
    let text = std::fs::read_to_string(path).ok()?;
    let on_file: OnFile = serde_json::from_str(&text).ok()?;
    (on_file.key == key).then_some(on_file.reference)
}

/// Writes the file whole (never half-written).
fn write(path: &Path, key: &str, reference: &Measured) -> anyhow::Result<()> {
    let on_file = serde_json::json!({ "key": key, "reference": reference });
    crate::common::write_whole(path, &serde_json::to_string(&on_file)?)
}

/// A hash of this program's executable (None when it cannot be read: nothing is then read
/// or written, every reference is computed).
fn binary_hash() -> Option<u64> {
    let bytes = std::fs::read(std::env::current_exe().ok()?).ok()?;
    let mut h = DefaultHasher::new();
    bytes.hash(&mut h);
    Some(h.finish())
}

/// The key of `scene`'s reference made by the binary of hash `binary`: every field of the
/// scene (its Debug form) and the binary.
fn key(binary: u64, scene: &Scene) -> String {
    let mut h = DefaultHasher::new();
    format!("{scene:?}").hash(&mut h);
    format!("{binary:016x}-{:016x}", h.finish())
}

#[cfg(test)]
mod tests {
    //! The file round trip against the values written: every bit back, and nothing read for
    //! another key (another binary or scene).
    use super::{read, write, Measured};

    #[test]
    fn a_reference_file_gives_back_every_bit_and_only_for_its_key() {
        let dir = std::env::temp_dir().join(format!("impact-bench-refs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("r.json");
        // Values whose shortest decimal form is long, a subnormal, a negative zero.
        let awkward = [0.1 + 0.2, -1.0 / 3.0, 5e-324, -0.0, 2.0f64.sqrt() * 1e-7];
        let written = Measured {
            robust: [awkward[0], awkward[1], awkward[4]],
            time_s: awkward.to_vec(),
            mid_uy_m: awkward.iter().map(|x| -x * 1e-3).collect(),
        };
        write(&path, "k1", &written).unwrap();
        let back = read(&path, "k1").expect("the file of key k1");
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&back.robust), bits(&written.robust));
        assert_eq!(bits(&back.time_s), bits(&written.time_s));
        assert_eq!(bits(&back.mid_uy_m), bits(&written.mid_uy_m));
        assert!(read(&path, "k2").is_none(), "another key must not be read");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
