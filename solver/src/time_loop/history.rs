//! The recorder of a run: what the time loop writes down at each step (`ALGORITHM.md`
//! section 8). History rows at the output times (sent to a [`HistorySink`]: held in memory or
//! streamed to a file), the probes' stresses, the contact intervals and the run's totals
//! (impulse, peak force, largest displacements and von Mises stresses).

use crate::input::error::{Error, Result};
use crate::input::scene::{DtUpdate, Scene};
use crate::mesh::PlateMesh;
use crate::physics::contacts::rigid_wall::{WallReading, WallTotals};
use crate::physics::elements::element::Formulation;
use crate::physics::materials::material::{von_mises, Stress};
use crate::time_loop::energy::{BalanceMonitor, Energies};
use crate::time_loop::schedule::Schedule;

/// A probe: the integration point nearest a named point, in the element containing it.
#[derive(Debug, Clone)]
pub struct Probe {
    pub name: String,
    pub element: usize,
    pub point: usize,
}

/// Where history rows go as the run produces them.
pub trait HistorySink {
    /// Called once, before the first row, with the column names (units in the names).
    fn begin(&mut self, columns: &[String]) -> Result<()>;
    /// One row. Its last value is the raw energy imbalance (J), which becomes the energy
    /// balance error only at the end of the run (it is divided by the run's largest energy).
    fn row(&mut self, row: &[f64]) -> Result<()>;
    /// The run ended: every row's last value becomes `balance.ratio(imbalance)`.
    fn finish(&mut self, balance: &BalanceMonitor) -> Result<()>;
    /// The run stopped on an error or a stop request after its rows so far: a sink that keeps
    /// partial output finishes them as [`HistorySink::finish`] would (the balance divided by
    /// the largest energy so far); by default nothing.
    fn abandon(&mut self, _balance: &BalanceMonitor) -> Result<()> {
        Ok(())
    }
    /// Whether the rows are held in memory (counted in the run's memory estimate).
    fn holds_rows(&self) -> bool {
        true
    }
}

/// Sampled histories: one row per output time, columns named with their units. As a
/// [`HistorySink`] it holds every row in memory.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct History {
    pub columns: Vec<String>,
    /// Row-major values, `columns.len()` per row.
    pub values: Vec<f64>,
}

impl History {
    pub fn n_rows(&self) -> usize {
        if self.columns.is_empty() {
            0
        } else {
            self.values.len() / self.columns.len()
        }
    }

    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let c = self.columns.iter().position(|n| n == name)?;
        Some(
            self.values
                .iter()
                .skip(c)
                .step_by(self.columns.len())
                .copied()
                .collect(),
        )
    }

    /// Trapezoidal integral over time of `f(value)` of a column, over the rows up to `until`
    /// (s) (e.g. the momentum deficit of a wave front). `None` without that column.
    pub fn time_integral(&self, column: &str, until: f64, f: impl Fn(f64) -> f64) -> Option<f64> {
        let t = self.column("time_s")?;
        let v = self.column(column)?;
        let mut integral = 0.0;
        for k in 1..t.len() {
            if t[k] > until {
                break;
            }
            integral += 0.5 * (f(v[k - 1]) + f(v[k])) * (t[k] - t[k - 1]);
        }
        Some(integral)
    }

    pub fn row(&self, r: usize) -> &[f64] {
        let n = self.columns.len();
        &self.values[r * n..(r + 1) * n]
    }
}

impl HistorySink for History {
    fn begin(&mut self, columns: &[String]) -> Result<()> {
        self.columns = columns.to_vec();
        self.values = Vec::with_capacity(columns.len() * 1024);
        Ok(())
    }
    fn row(&mut self, row: &[f64]) -> Result<()> {
        self.values.extend_from_slice(row);
        Ok(())
    }
    fn finish(&mut self, balance: &BalanceMonitor) -> Result<()> {
        let width = self.columns.len();
        for r in self.values.chunks_exact_mut(width) {
            r[width - 1] = balance.ratio(r[width - 1]);
        }
        Ok(())
    }
}

/// What stopped the run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    EndTime,
    AfterContact,
    TimeLimit,
}

/// Scalars gathered over every step.
#[derive(Debug, Clone, PartialEq)]
pub struct RunTotals {
    pub impulse: f64,
    pub peak_force: f64,
    pub max_downward_mid: f64,
    pub max_downward_bottom: f64,
    pub contact_intervals: Vec<[f64; 2]>,
    pub final_impactor_velocity: Option<f64>,
    /// Surface coupling: the largest contact half-width (m) and number of nodes in contact.
    pub max_patch: Option<[f64; 2]>,
    /// The stable step of the plate alone (without contact springs), s.
    pub dt_plate: f64,
    pub max_von_mises: Vec<(String, f64)>,
    /// Largest equivalent plastic strain rate over all steps, per probe, 1/s (rate-dependent
    /// materials only; else empty).
    pub max_plastic_strain_rate: Vec<(String, f64)>,
    /// Highest temperature over the plate's points at the end (heating only rises), K.
    pub max_temperature: Option<f64>,
    /// Surface coupling: the largest penetration of a top-surface node into the nose at any
    /// `t_n`, m.
    pub max_penetration: Option<f64>,
    pub max_balance_error: f64,
    /// The first step, s.
    pub dt: f64,
    pub dt_critical: f64,
    /// The smallest and largest step of a run whose step is re-estimated at every step
    /// (`time.dt.update: every-step`), s; `None` when the step is fixed.
    pub dt_range: Option<[f64; 2]>,
    pub n_steps: u64,
    pub final_time: f64,
    pub stop: StopReason,
    pub initial_energy: Energies,
    pub final_energy: Energies,
    /// The rigid wall's results (wall scenes only).
    pub wall: Option<WallTotals>,
}

/// What a probe reads at `t_n`.
#[derive(Debug, Clone, Copy)]
pub struct ProbeReading {
    /// `[xx, yy, zz, xy]`, Pa.
    pub stress: Stress,
    /// A rate-dependent material's equivalent plastic strain rate over the last step, 1/s.
    pub plastic_strain_rate: Option<f64>,
    /// A heating material's temperature, K.
    pub temperature: Option<f64>,
}

/// The state of the run at `t_n` that the recorder samples.
pub(crate) struct Sample<'a> {
    pub t: f64,
    /// Contact (or applied) force `F_n`, N.
    pub force: f64,
    /// Indentation, impactor displacement (m) and velocity (m/s); impact scenes only.
    pub impactor: Option<[f64; 3]>,
    /// Contact half-width (m) and nodes in contact; surface coupling only.
    pub patch: Option<[f64; 2]>,
    /// The wall's reading (`WallReading::COLUMNS`); wall only.
    pub wall: Option<[f64; 5]>,
    /// Mid-span `u_y` at the top, mid-plane and bottom, m.
    pub uy: [f64; 3],
    pub energies: &'a Energies,
    /// `|E(t_n) - E(0) - W_ext(t_n)|`, J.
    pub imbalance: f64,
}

/// Writes down the run as it goes: history rows into a sink, probes, contact intervals and
/// the totals.
pub(crate) struct Recorder<'s> {
    probes: Vec<Probe>,
    sink: &'s mut dyn HistorySink,
    rows: Schedule,
    /// Reused for every row (no allocation in the loop).
    row: Vec<f64>,
    in_contact: bool,
    separated_at: Option<f64>,
    /// The force at the previous step, N (None before the first).
    last_force: Option<f64>,
    /// Whether rows carry the step (`dt_s`: `time.dt.update: every-step`).
    step_column: bool,
    totals: RunTotals,
}

impl<'s> Recorder<'s> {
    pub(crate) fn new(
        scene: &Scene,
        probes: Vec<Probe>,
        sink: &'s mut dyn HistorySink,
        dt: f64,
        dt_critical: f64,
        dt_plate: f64,
    ) -> Result<Self> {
        let columns = history_columns(scene, &probes);
        sink.begin(&columns)?;
        let totals = RunTotals {
            impulse: 0.0,
            peak_force: 0.0,
            max_downward_mid: 0.0,
            max_downward_bottom: 0.0,
            contact_intervals: Vec::new(),
            final_impactor_velocity: None,
            max_patch: scene.surface_impactor().map(|_| [0.0, 0.0]),
            dt_plate,
            max_von_mises: probes.iter().map(|p| (p.name.clone(), 0.0)).collect(),
            max_plastic_strain_rate: match scene.rate_law() {
                Some(_) => probes.iter().map(|p| (p.name.clone(), 0.0)).collect(),
                None => Vec::new(),
            },
            max_temperature: None,
            max_penetration: None,
            max_balance_error: 0.0,
            dt,
            dt_critical,
            dt_range: None,
            n_steps: 0,
            final_time: 0.0,
            stop: StopReason::EndTime,
            initial_energy: Energies::default(),
            final_energy: Energies::default(),
            wall: None,
        };
        Ok(Recorder {
            rows: Schedule::of(scene.output.every, scene.time.dt_update),
            row: Vec::with_capacity(columns.len()),
            probes,
            sink,
            in_contact: false,
            separated_at: None,
            last_force: None,
            step_column: scene.time.dt_update == DtUpdate::EveryStep,
            totals,
        })
    }

    /// Contact intervals: `[first t_n with F > 0, first later t_n with F = 0]`; the peak force;
    /// the impulse's trapezoid `(F_{n-1} + F_n) dt / 2` (N s) over the previous step `dt` (s).
    pub(crate) fn contact(&mut self, t: f64, force: f64, dt: f64) {
        if let Some(last) = self.last_force {
            self.totals.impulse += 0.5 * (last + force) * dt;
        }
        self.last_force = Some(force);
        if force > 0.0 {
            if !self.in_contact {
                self.totals.contact_intervals.push([t, t]);
                self.in_contact = true;
            }
            self.separated_at = None;
            self.totals.peak_force = self.totals.peak_force.max(force);
        } else if self.in_contact {
            self.close_interval(t);
            self.in_contact = false;
            self.separated_at = Some(t);
        }
    }

    /// When contact last ended (None while in contact or before any), s.
    pub(crate) fn separated_at(&self) -> Option<f64> {
        self.separated_at
    }

    /// Records step `n` (`last`: the run stops after it; `dt` its step, s): the largest
    /// displacements and probe stresses (and rates), and a history row when one is due.
    /// `read` reads a probe at `t_n`.
    pub(crate) fn sample(
        &mut self,
        n: u64,
        dt: f64,
        last: bool,
        at: &Sample,
        read: impl Fn(&Probe) -> ProbeReading,
    ) -> Result<()> {
        let [top, mid, bottom] = at.uy;
        self.totals.max_downward_mid = self.totals.max_downward_mid.min(mid);
        self.totals.max_downward_bottom = self.totals.max_downward_bottom.min(bottom);
        if let (Some(max), Some(patch)) = (&mut self.totals.max_patch, at.patch) {
            *max = [max[0].max(patch[0]), max[1].max(patch[1])];
        }
        let want_row = self.rows.due_at(n, at.t, dt) || last;
        let row = &mut self.row;
        row.clear();
        if want_row {
            row.push(at.t);
            if self.step_column {
                row.push(dt);
            }
            row.push(at.force);
            if let Some(impactor) = at.impactor {
                row.extend(impactor);
            }
            if let Some(patch) = at.patch {
                row.extend(patch);
            }
            if let Some(wall) = at.wall {
                row.extend(wall);
            }
            row.extend([top, mid, bottom]);
        }
        // Each probe read once: its maxima every step, its columns when a row is due.
        for (k, p) in self.probes.iter().enumerate() {
            let r = read(p);
            let vm = von_mises(&r.stress);
            let max = &mut self.totals.max_von_mises[k].1;
            *max = max.max(vm);
            if let (Some(rate), Some(max)) = (
                r.plastic_strain_rate,
                self.totals.max_plastic_strain_rate.get_mut(k),
            ) {
                max.1 = max.1.max(rate);
            }
            if want_row {
                let st = r.stress;
                row.extend([st[0], st[1], st[3], st[2], vm]);
                row.extend(r.plastic_strain_rate);
                row.extend(r.temperature);
            }
        }
        if !want_row {
            return Ok(());
        }
        row.extend(at.energies.as_row());
        row.push(at.imbalance); // divided by the run's largest energy at the end
        self.sink.row(row)
    }

    /// The run stopped on an error after its rows so far: the sink keeps them or not
    /// ([`HistorySink::abandon`]).
    pub(crate) fn abandon(&mut self, balance: &BalanceMonitor) -> Result<()> {
        self.sink.abandon(balance)
    }

    /// The run stopped after step `n` at `t` (`at` its last sample): closes the open contact
    /// interval and the history, returns the totals.
    pub(crate) fn finish(
        &mut self,
        n: u64,
        stop: StopReason,
        at: &Sample,
        initial_energy: Energies,
        balance: &BalanceMonitor,
    ) -> Result<RunTotals> {
        let totals = &mut self.totals;
        totals.stop = stop;
        totals.n_steps = n;
        totals.final_time = at.t;
        totals.final_energy = *at.energies;
        totals.final_impactor_velocity = at.impactor.map(|i| i[2]);
        totals.max_balance_error = balance.max_error();
        totals.initial_energy = initial_energy;
        if self.in_contact {
            self.close_interval(at.t);
        }
        self.sink.finish(balance)?;
        Ok(self.totals.clone())
    }

    fn close_interval(&mut self, t: f64) {
        if let Some(last) = self.totals.contact_intervals.last_mut() {
            last[1] = t;
        }
    }
}

/// The history's columns, in `ALGORITHM.md` section 8's order.
pub fn history_columns(scene: &Scene, probes: &[Probe]) -> Vec<String> {
    let mut c: Vec<String> = vec!["time_s".into()];
    if scene.time.dt_update == DtUpdate::EveryStep {
        c.push("dt_s".into());
    }
    c.push("contact_force_N".into());
    if scene.impactor_motion().is_some() {
        c.extend(
            [
                "indentation_m",
                "impactor_displacement_m",
                "impactor_velocity_mps",
            ]
            .map(String::from),
        );
    }
    if scene.surface_impactor().is_some() {
        c.extend(["contact_half_width_m", "nodes_in_contact"].map(String::from));
    }
    if scene.wall().is_some() {
        c.extend(WallReading::COLUMNS.map(String::from));
    }
    c.extend(["top_uy_m", "mid_uy_m", "bottom_uy_m"].map(String::from));
    let rate = scene.rate_law();
    for p in probes {
        for q in ["sxx_Pa", "syy_Pa", "sxy_Pa", "szz_Pa", "von_mises_Pa"] {
            c.push(format!("{}_{q}", p.name));
        }
        if rate.is_some() {
            c.push(format!("{}_plastic_strain_rate_1_s", p.name));
        }
        if rate.and_then(|r| r.thermal()).is_some() {
            c.push(format!("{}_temperature_K", p.name));
        }
    }
    c.extend(Energies::COLUMNS.map(String::from));
    c.push("energy_balance_error".into());
    c
}

/// Finds each probe's element and nearest integration point.
pub(crate) fn locate_probes<F: Formulation>(
    scene: &Scene,
    mesh: &PlateMesh,
    formulation: &F,
) -> Result<Vec<Probe>> {
    scene
        .output
        .probes
        .iter()
        .map(|(name, at)| {
            let point = mesh.fold(*at);
            let element = mesh.element_containing(point).ok_or_else(|| {
                Error::invalid(
                    crate::input::error::SourceLocation::file(&scene.source),
                    format!("output.probes.{name}"),
                    format!("({}, {})", at[0], at[1]),
                    "must lie inside the plate",
                )
            })?;
            let coords = mesh.mesh.element_coords(element);
            let distance = |xi: &[f64; 2]| {
                let n = crate::physics::elements::element::shape(*xi);
                let x: f64 = (0..4).map(|a| n[a] * coords[a][0]).sum();
                let y: f64 = (0..4).map(|a| n[a] * coords[a][1]).sum();
                (x - point[0]).powi(2) + (y - point[1]).powi(2)
            };
            let xis = formulation.point_xi();
            let nearest = (0..xis.len())
                .min_by(|&a, &b| distance(&xis[a]).total_cmp(&distance(&xis[b])))
                .unwrap_or(0);
            Ok(Probe {
                name: name.clone(),
                element,
                point: nearest,
            })
        })
        .collect()
}
