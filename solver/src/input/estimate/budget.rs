//! What a scene will cost before anything is allocated: elements, time steps, history rows and
//! memory, estimated from the scene alone in microseconds, so that a run the machine cannot
//! hold is refused with the estimate in the message instead of dying in an allocation.

use crate::input::error::{Error, Result};
use crate::input::scene::{DtChoice, DtUpdate, ElementKind, End, Scene};

pub use super::measures::{bytes, count, limit_above};
use super::measures::{p_wave_speed, smallest_element_length};

/// Resident bytes per element: the slope of the peak RSS (`/usr/bin/time -f %M`, one step,
/// 2 threads) between 400 x 80 and 800 x 160 meshes of the example scenes, measured
/// 2026-11-23 with batch-major states and no per-element force array: q4-sri 324 plastic /
/// 158 elastic, q4-full 325 / -, q4-1pt 196 / 154 bytes. The larger of each, rounded up by
/// ~20 % so that the estimate errs on the high side.
pub const BYTES_PER_ELEMENT_FULL: f64 = 400.0;
pub const BYTES_PER_ELEMENT_SRI: f64 = 400.0;
pub const BYTES_PER_ELEMENT_ONE_POINT: f64 = 240.0;

/// Resident bytes of a run before any mesh (the 400 x 80 runs above less their elements:
/// ~7.3 MB).
pub const BYTES_BASE: f64 = 8.0e6;

/// Bytes per history value held in memory (when it is: not for `impact simulate --out`, which
/// streams the rows to `history.csv`): an f64 in a vector that doubles as it grows.
pub const BYTES_PER_HISTORY_VALUE: f64 = 16.0;

/// Bytes of one VTK field frame per node and per element (ASCII `.vtu`: a node's coordinates,
/// displacement and velocity; an element's connectivity, offset, type, four stresses, von
/// Mises stress and plastic strain, each number in Rust's shortest round-trip digits). Measured
/// 2026-11-26 on the 80 x 16 example scene mid-run: 343 kB a frame for 1377 nodes and 1280
/// elements, 129 bytes per node or element; rounded up so that the estimate errs high (a
/// rate-dependent law adds one or two arrays per element).
pub const BYTES_PER_FIELD_ITEM: f64 = 150.0;

/// Steps beyond which a run is announced as long (~10^7: minutes to hours at the measured
/// 20-60 ns per element-step on the default meshes).
pub const MANY_STEPS: f64 = 1.0e7;

/// The cost of a scene, estimated before the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    pub elements: f64,
    pub nodes: f64,
    /// Estimated stable time step times the scene's CFL fraction (or the fixed step), s.
    pub dt: f64,
    /// The estimated stable time step itself (the bound below), s.
    pub stable_dt: f64,
    /// Time steps to the scene's end (to `time.limit` for `after_contact`); at the first
    /// step's size when [`Estimate::step_follows_mesh`] (then the run takes more: the Taylor
    /// bar of DynELA's 42CrMo4, 1,348 estimated, 48,458 run).
    pub steps: f64,
    /// Whether the step is re-estimated at every step (`time.dt.update: every-step`): it falls
    /// as the mesh deforms, so `steps` is a lower bound.
    pub step_follows_mesh: bool,
    /// History rows of the run.
    pub history_rows: f64,
    pub history_columns: usize,
    /// Whether the rows are held in memory (the library's runs) or streamed to
    /// `history.csv` as they come (`impact simulate`: [`Estimate::streamed`]).
    pub history_in_memory: bool,
    /// VTK field frames the run writes (0 without `output.fields`).
    pub field_frames: f64,
    /// Bytes of those frames on disk.
    pub field_bytes: f64,
    /// Peak resident memory, bytes.
    pub bytes: f64,
}

impl Estimate {
    /// Estimates a validated scene. The stable step is the bilinear quad's bound
    /// `dt = 1 / (c_p sqrt(1/hx^2 + 1/hy^2))` on the smallest element, with the plane-strain
    /// P-wave speed `c_p`; the solver's own eigenvalue bound (eq. 15) is within a factor ~1.5.
    pub fn of(scene: &Scene) -> Estimate {
        let (nx, ny) = (scene.mesh.nx as f64, scene.mesh.ny as f64);
        let elements = nx * ny;
        let nodes = (nx + 1.0) * (ny + 1.0);
        let c_p = p_wave_speed(&scene.material);
        let hx = smallest_element_length(scene);
        let hy = scene.plate.thickness / ny;
        let dt_stable = 1.0 / (c_p * (hx.powi(-2) + hy.powi(-2)).sqrt());
        let dt = match scene.time.dt {
            DtChoice::Cfl(c) => c * dt_stable,
            DtChoice::Fixed(d) => d,
        };
        let end = match scene.time.end {
            End::At(t) => t,
            End::AfterContact { limit, .. } => limit,
        };
        let steps = (end / dt).ceil();
        let step_follows_mesh = scene.time.dt_update == DtUpdate::EveryStep;
        // Rows at most one a step; a step that falls as the mesh deforms does not cap them.
        let row_cap = if step_follows_mesh {
            f64::INFINITY
        } else {
            steps
        };
        let history_rows = match scene.output.every {
            Some(every) => (end / every).ceil().min(row_cap) + 1.0,
            None => steps + 1.0,
        };
        let history_columns =
            2 + if scene.impactor_motion().is_some() {
                3
            } else {
                0
            } + if scene.surface_impactor().is_some() {
                2
            } else {
                0
            } + 3
                + 5 * scene.output.probes.len()
                + 8;
        let per_element = match scene.mesh.element {
            ElementKind::Q4Full => BYTES_PER_ELEMENT_FULL,
            ElementKind::Q4Sri => BYTES_PER_ELEMENT_SRI,
            ElementKind::Q4OnePoint => BYTES_PER_ELEMENT_ONE_POINT,
        };
        let bytes = BYTES_BASE
            + elements * per_element
            + history_rows * history_columns as f64 * BYTES_PER_HISTORY_VALUE;
        // A frame at t = 0, then one per `fields.every` (at most one a step).
        let field_frames = match scene.output.fields_every {
            Some(every) => (end / every).ceil().min(row_cap) + 1.0,
            None => 0.0,
        };
        Estimate {
            elements,
            nodes,
            dt,
            stable_dt: dt_stable,
            steps,
            step_follows_mesh,
            history_rows,
            history_columns,
            history_in_memory: true,
            field_frames,
            field_bytes: field_frames * (nodes + elements) * BYTES_PER_FIELD_ITEM,
            bytes,
        }
    }

    /// The same run with its history streamed to a file: the rows cost no memory.
    pub fn streamed(self) -> Estimate {
        Estimate {
            bytes: self.bytes - self.history_bytes(),
            history_in_memory: false,
            ..self
        }
    }

    /// Bytes of the history held in memory (0 when it is streamed).
    pub fn history_bytes(&self) -> f64 {
        if self.history_in_memory {
            self.history_rows * self.history_columns as f64 * BYTES_PER_HISTORY_VALUE
        } else {
            0.0
        }
    }

    /// What to change in the scene to make it cheaper, for messages.
    pub fn remedy(&self) -> &'static str {
        if self.history_bytes() > 0.5 * self.bytes {
            "most of it is the history: raise output.every or shorten time.end"
        } else {
            "most of it is the mesh: coarsen mesh.nx / mesh.ny"
        }
    }

    /// One line: elements, steps, history, field frames, memory.
    pub fn describe(&self) -> String {
        let steps = if self.step_follows_mesh {
            format!(
                "at least {} steps (the first {:.2e} s; the step is re-estimated every step and falls as the mesh deforms)",
                count(self.steps),
                self.dt
            )
        } else {
            format!("about {} steps of {:.2e} s", count(self.steps), self.dt)
        };
        format!(
            "{} elements, {steps}, {} history rows x {} columns{}, {}about {} of memory",
            count(self.elements),
            count(self.history_rows),
            self.history_columns,
            if self.history_in_memory {
                ""
            } else {
                " (streamed to disk)"
            },
            if self.field_frames > 0.0 {
                format!(
                    "{} VTK field frames (about {} on disk), ",
                    count(self.field_frames),
                    bytes(self.field_bytes)
                )
            } else {
                String::new()
            },
            bytes(self.bytes)
        )
    }
}

/// Parses a memory size: `16G`, `500M`, `2.5GB`, `1e9` (bytes; powers of 1000).
pub fn parse_bytes(text: &str) -> Option<f64> {
    let t = text.trim();
    let split = t
        .find(|c: char| c.is_ascii_alphabetic() && c != 'e' && c != 'E')
        .unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let x: f64 = number.trim().parse().ok()?;
    let scale = match unit.trim().to_ascii_lowercase().trim_end_matches('b') {
        "" => 1.0,
        "k" => 1e3,
        "m" => 1e6,
        "g" => 1e9,
        "t" => 1e12,
        _ => return None,
    };
    (x.is_finite() && x > 0.0).then_some(x * scale)
}

/// Memory the machine can give a new process now (`MemAvailable` of /proc/meminfo), bytes;
/// `None` where that is unknown.
pub fn available_memory() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024.0)
}

/// Refuses a scene whose estimated time step makes no run
/// ([`super::time_step::check_steps`]) or whose memory estimate exceeds `max_memory`
/// or, without it, the memory the machine has available (every run checks this before
/// allocating: `crate::simulate`).
pub fn check(scene: &Scene, estimate: &Estimate, max_memory: Option<f64>) -> Result<()> {
    super::time_step::check_steps(scene, estimate.dt)?;
    let (limit, whose) = match max_memory {
        Some(m) => (m, "the limit --max-memory"),
        None => match available_memory() {
            Some(m) => (m, "the memory available on this machine"),
            None => return Ok(()),
        },
    };
    if estimate.bytes <= limit {
        return Ok(());
    }
    Err(Error::TooLarge {
        scene: scene.source.clone(),
        estimate: format!("this run needs {}", estimate.describe()),
        limit: format!(
            "that is more than {whose} ({}); {}, or pass --max-memory {} to run it anyway",
            bytes(limit),
            estimate.remedy(),
            limit_above(estimate.bytes)
        ),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_print_in_powers_of_1000() {
        assert_eq!(parse_bytes("16G"), Some(16e9));
        assert_eq!(parse_bytes("2.5GB"), Some(2.5e9));
        assert_eq!(parse_bytes("500m"), Some(500e6));
        assert_eq!(parse_bytes("1e9"), Some(1e9));
        assert_eq!(parse_bytes("lots"), None);
        assert_eq!(parse_bytes("-1G"), None);
        assert_eq!(bytes(1.6e12), "1.60 TB");
        assert_eq!(bytes(900.009e9), "900 GB");
        assert_eq!(bytes(23.122e9), "23.1 GB");
        assert_eq!(bytes(512.0), "512 B");
        assert_eq!(limit_above(989.2e9), "990G");
        assert_eq!(limit_above(2.31e9), "2.4G");
        assert_eq!(parse_bytes(&limit_above(989.2e9)), Some(990e9));
    }

    #[test]
    fn a_step_that_follows_the_mesh_is_a_lower_bound_and_does_not_cap_the_rows() {
        // DynELA's 42CrMo4 bar (update: every-step): 1,348 steps at the first step's size,
        // 48,458 run. The estimate says "at least", and its rows (one per output.every) are
        // not capped by the steps it cannot know.
        let text = include_str!("../../../../verification/scenes/taylor-bar-42crmo4.yaml");
        let mut scene = Scene::from_yaml(text, std::path::Path::new("bar.yaml")).unwrap();
        let e = Estimate::of(&scene);
        assert!(e.step_follows_mesh);
        assert!(e.describe().contains("at least"), "{}", e.describe());
        scene.output.every = Some(e.dt / 4.0);
        assert!(Estimate::of(&scene).history_rows > 4.0 * e.steps);
        // A fixed step's count is an estimate ("about") and caps the rows.
        scene.time.dt_update = DtUpdate::Once;
        let fixed = Estimate::of(&scene);
        assert!(fixed.describe().contains("about") && !fixed.describe().contains("at least"));
        assert_eq!(fixed.history_rows, fixed.steps + 1.0);
    }
}
