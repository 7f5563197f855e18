//! `summary.json`: the scalars of a run (whole plate, whole width, SI units; the key names
//! carry the unit).

use std::collections::BTreeMap;

use serde::Serialize;

use crate::input::scene::Geometry;
use crate::input::scene::{
    ContactLawChoice, DtUpdate, ElementKind, Enforcement, Kinematics, Load, MidSpanNode, Model,
    Scene,
};
use crate::kernels::fallback::Report;
use crate::mesh::PlateMesh;
use crate::time_loop::energy::Energies;
use crate::time_loop::history::{RunTotals, StopReason};

/// Summary keys that measure the machine, not the result (wall-clock times and the threads'
/// fallback, which depends on the machine's load): shown, never compared, never pinned.
pub const TIMING_KEYS: [&str; 5] = [
    "wall_time_s",
    "setup_time_s",
    "loop_time_s",
    "ns_per_element_step",
    "threads_fallback",
];

/// Whether `key` (a top-level key, or a flattened `key.inner` one) is one of [`TIMING_KEYS`].
pub fn is_timing_key(key: &str) -> bool {
    TIMING_KEYS.iter().any(|t| {
        key.strip_prefix(t)
            .is_some_and(|rest| rest.is_empty() || rest.starts_with('.'))
    })
}

/// Wall-clock split of a run, s, and what the element loop's team measured.
#[derive(Debug, Clone, Copy)]
pub struct Timing {
    pub setup_s: f64,
    pub loop_s: f64,
    /// The team's fallback to one thread, when it fell back.
    pub threads_fallback: Option<Report>,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Total contact impulse `sum (F_n + F_{n+1}) dt / 2`, N s.
    #[serde(rename = "impulse_Ns")]
    pub impulse: f64,
    #[serde(rename = "peak_contact_force_N")]
    pub peak_contact_force: f64,
    /// Most negative mid-span mid-plane u_y, m.
    #[serde(rename = "max_plate_displacement_m")]
    pub max_plate_displacement: f64,
    /// Most negative mid-span bottom-surface u_y, m. Away from the point force, so it
    /// converges under mesh refinement where the loaded node's displacement (log-singular in
    /// 2-D) creeps up.
    #[serde(rename = "max_bottom_displacement_m")]
    pub max_bottom_displacement: f64,
    /// Every [start, end] of contact (of the pulse, for pulse scenes), s.
    #[serde(rename = "contact_intervals_s")]
    pub contact_intervals: Vec<[f64; 2]>,
    /// End of the last contact interval, s (0 without contact).
    #[serde(rename = "contact_duration_s")]
    pub contact_duration: f64,
    /// Signed, positive toward the plate; null for pulse scenes. m/s
    #[serde(rename = "final_impactor_velocity_mps")]
    pub final_impactor_velocity: Option<f64>,
    /// Largest von Mises stress over all steps, per probe, Pa.
    #[serde(rename = "max_von_mises_Pa")]
    pub max_von_mises: BTreeMap<String, f64>,
    pub max_energy_balance_error: f64,
    #[serde(rename = "dt_s")]
    pub dt: f64,
    pub n_steps: u64,
    pub n_elements: usize,
    #[serde(rename = "wall_time_s")]
    pub wall_time: f64,

    // Added beyond the contract.
    /// `|impulse - m (v0 - v_final)| / (m v0)`: eq. (19) makes it round-off.
    pub impulse_momentum_error: Option<f64>,
    /// `dt_s / dt_critical_s`.
    pub cfl: f64,
    #[serde(rename = "dt_critical_s")]
    pub dt_critical: f64,
    /// `every-step` when the step was re-estimated at every step (`time.dt.update`; then
    /// `dt_s`, `cfl` and `dt_critical_s` are the first step's); absent when it was fixed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dt_update: Option<&'static str>,
    /// The smallest step of a re-estimated run (the last, cut to land on the end, not
    /// counted), s.
    #[serde(rename = "dt_min_s", skip_serializing_if = "Option::is_none")]
    pub dt_min: Option<f64>,
    /// The largest step of a re-estimated run, s.
    #[serde(rename = "dt_max_s", skip_serializing_if = "Option::is_none")]
    pub dt_max: Option<f64>,
    #[serde(rename = "final_time_s")]
    pub final_time: f64,
    pub stop_reason: StopReason,
    pub element: ElementKind,
    /// Written for finite deformation only, so that small-strain summaries keep their bits.
    #[serde(skip_serializing_if = "Kinematics::is_small")]
    pub kinematics: Kinematics,
    /// Written for the axisymmetric geometry only (the same reason).
    #[serde(skip_serializing_if = "Geometry::is_plane_strain")]
    pub geometry: Geometry,
    pub model: Model,
    pub plastic: bool,
    /// e.g. `paper(length_unit=0.001 m)`, `johnson(datum_depth=0.01 m)`, `pulse`.
    pub contact_law: String,
    pub indentation_datum: Option<MidSpanNode>,
    pub force_node: Option<MidSpanNode>,
    #[serde(rename = "initial_energy_J")]
    pub initial_energy: Energies,
    #[serde(rename = "final_energy_J")]
    pub final_energy: Energies,
    #[serde(rename = "setup_time_s")]
    pub setup_time: f64,
    #[serde(rename = "loop_time_s")]
    pub loop_time: f64,
    /// Time-loop wall time per element and step, ns.
    pub ns_per_element_step: f64,
    /// Written only when the element loop's team of threads was measured slower than one
    /// thread and fell back (`crate::kernels::fallback`; a busy machine): the threads, the
    /// steps run on one thread, the comparison (s per step). The results' bits are the same
    /// either way; absent otherwise, so that other summaries keep their bits.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub threads_fallback: Option<Report>,
    /// Surface coupling: the stable step with the penalty springs over the plate's own
    /// (`1/sqrt(1 + penalty_scale)` at least).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_step_factor: Option<f64>,
    /// Surface coupling: the largest contact half-width from the nose's axis, m.
    #[serde(
        rename = "max_contact_half_width_m",
        skip_serializing_if = "Option::is_none"
    )]
    pub max_contact_half_width: Option<f64>,
    /// Surface coupling: the most nodes in contact at once (whole plate).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_nodes_in_contact: Option<f64>,
    /// Surface coupling: the largest penetration `g` of a top-surface node into the nose at
    /// any `t_n` (current positions; ALGORITHM.md 5b), m.
    #[serde(rename = "max_penetration_m", skip_serializing_if = "Option::is_none")]
    pub max_penetration: Option<f64>,
    /// Rate-dependent plasticity: the largest equivalent plastic strain rate over all steps,
    /// per probe, 1/s.
    #[serde(
        rename = "max_plastic_strain_rate_1_s",
        skip_serializing_if = "BTreeMap::is_empty"
    )]
    pub max_plastic_strain_rate: BTreeMap<String, f64>,
    /// Heating: the highest temperature of the plate's points at the end, K.
    #[serde(rename = "max_temperature_K", skip_serializing_if = "Option::is_none")]
    pub max_temperature: Option<f64>,
    /// Heating: the plastic work turned into heat, `beta W_p`, J (whole width).
    #[serde(rename = "heat_J", skip_serializing_if = "Option::is_none")]
    pub heat: Option<f64>,
    /// The scene's plausibility warnings (`crate::input::plausibility`), as printed: inputs
    /// whose units look wrong, options that do nothing here, output that swamps the run.
    /// Absent when there are none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// What the run found doubtful in its own results
    /// ([`crate::run::result_warnings`]): absent when there is nothing.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub result_warnings: Vec<String>,
    /// The rigid wall's results (`load: {wall}` only, so that other summaries keep their bits).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall: Option<WallSummary>,
}

/// `summary.json`'s `wall`: what an analyst of a Taylor test reads (forces N and energies J of
/// the whole ring, or of `plate.width` in plane strain; lengths m). The wall force's history is
/// the `contact_force_N` column.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WallSummary {
    /// The largest bearing force (the `bearing_force_N` column: the body's own force on the
    /// wall through the nodes it holds, without the one-step stops of landing nodes), N. It
    /// converges as the step falls (ALGORITHM.md 5c).
    #[serde(rename = "peak_force_N")]
    pub peak_force: f64,
    /// The largest wall force of one step (`peak_contact_force_N`, the `contact_force_N`
    /// column's peak), N: it holds the kinematic stop of the landing nodes, `m v / h`, an
    /// artefact of the method that grows as `1 / dt` (the bottom row's at `t_0`:
    /// `2 m_b V / dt`).
    #[serde(rename = "peak_step_force_N")]
    pub peak_step_force: f64,
    /// When the body left the wall for good, s; null while it is still on it at the end.
    #[serde(rename = "release_time_s")]
    pub release_time: Option<f64>,
    /// The bar's length on the axis at the end: the distance between the bottom and the top
    /// axis nodes (the `bar_length_m` column's last value; after release the gap to the wall
    /// is not counted), m.
    #[serde(rename = "final_length_m")]
    pub final_length: f64,
    /// `final_length_m / plate.thickness` (-).
    pub length_ratio: f64,
    /// Taylor's undeformed length `X` at the end: the length of the bar's rear part whose side
    /// stays within 0.5 % of its initial radius, measured from the top of the side down to the
    /// highest point where the side's distance from the axis reaches 1.005 times the initial
    /// radius (interpolated between the side's nodes; the `undeformed_length_m` column's last
    /// value; ALGORITHM.md 5c), m.
    #[serde(rename = "undeformed_length_m")]
    pub undeformed_length: f64,
    /// The foot's radius at the end: the largest current distance from the axis of a node
    /// that has touched the wall during the run (the side rolled onto it included; the
    /// `foot_radius_m` column's last value; the half-width in plane strain), m.
    #[serde(rename = "foot_radius_m")]
    pub foot_radius: f64,
    /// `foot_radius_m / (plate.length / 2)` (-).
    pub foot_radius_ratio: f64,
    /// The largest foot radius of the run (the `foot_radius_m` column's largest value over
    /// every step), m: at least `foot_radius_m`.
    #[serde(rename = "max_foot_radius_m")]
    pub max_foot_radius: f64,
    /// The body's mean velocity away from the wall at the end (momentum over mass, positive
    /// away from the wall), m/s, once the body has left the wall for good (`release_time_s`
    /// not null); null while it is still on the wall.
    #[serde(rename = "rebound_velocity_mps")]
    pub rebound_velocity: Option<f64>,
    /// The kinetic energy the wall took out (its dissipation, the `contact_energy_J` column), J.
    #[serde(rename = "dissipated_energy_J")]
    pub dissipated_energy: f64,
    /// The largest equivalent plastic strain at the end (plastic materials; else null).
    pub max_equivalent_plastic_strain: Option<f64>,
    /// The bar's side at the end, as a digitised Taylor profile gives it (ALGORITHM.md 5c).
    pub final_outline: FinalOutline,
}

/// `wall.final_outline`: the side's nodes (the reference's outer surface) at the end, bottom to
/// top, m.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FinalOutline {
    /// Each node's height above the bottom axis node (the impact face's centre), m.
    #[serde(rename = "height_m")]
    pub height: Vec<f64>,
    /// Each node's distance from the axis (the half-width in plane strain), m.
    #[serde(rename = "radius_m")]
    pub radius: Vec<f64>,
}

impl WallSummary {
    fn new(scene: &Scene, t: &RunTotals) -> Option<WallSummary> {
        let w = t.wall.as_ref()?;
        let radius = 0.5 * scene.plate.length;
        Some(WallSummary {
            peak_force: w.peak_bearing_force,
            peak_step_force: t.peak_force,
            release_time: w.release_time,
            final_length: w.length,
            length_ratio: w.length / scene.plate.thickness,
            undeformed_length: w.undeformed_length,
            foot_radius: w.foot_radius,
            foot_radius_ratio: w.foot_radius / radius,
            max_foot_radius: w.max_foot_radius,
            rebound_velocity: w.rebound_velocity,
            dissipated_energy: w.dissipated,
            max_equivalent_plastic_strain: w.max_plastic_strain,
            final_outline: FinalOutline {
                height: w.outline.iter().map(|p| p[0]).collect(),
                radius: w.outline.iter().map(|p| p[1]).collect(),
            },
        })
    }
}

impl Summary {
    pub fn new(scene: &Scene, mesh: &PlateMesh, t: &RunTotals, timing: Timing) -> Summary {
        let n_elements = mesh.mesh.elements.len();
        let impactor = scene.impactor();
        let impulse_momentum_error = scene
            .impactor_motion()
            .zip(t.final_impactor_velocity)
            .map(|((m, v0), vf)| (t.impulse - m * (v0 - vf)).abs() / (m * v0));
        let contact_law = match &scene.load {
            Load::Pulse(_) => "pulse".to_string(),
            Load::Traction(_) => "traction".to_string(),
            Load::Wall(_) => "wall".to_string(),
            Load::SurfaceImpactor(i) => match i.contact.enforcement {
                Enforcement::Kinematic => "surface(kinematic)".to_string(),
                Enforcement::Penalty => {
                    format!(
                        "surface(penalty, penalty_scale={})",
                        i.contact.penalty_scale
                    )
                }
            },
            Load::Impactor(i) => match i.contact_law {
                ContactLawChoice::Paper { length_unit } => {
                    format!("paper(length_unit={length_unit} m)")
                }
                ContactLawChoice::Johnson { datum_depth } => {
                    format!("johnson(datum_depth={datum_depth} m)")
                }
            },
        };
        Summary {
            impulse: t.impulse,
            peak_contact_force: t.peak_force,
            max_plate_displacement: t.max_downward_mid,
            max_bottom_displacement: t.max_downward_bottom,
            contact_intervals: t.contact_intervals.clone(),
            contact_duration: t.contact_intervals.last().map_or(0.0, |i| i[1]),
            final_impactor_velocity: t.final_impactor_velocity,
            max_von_mises: t.max_von_mises.iter().cloned().collect(),
            max_energy_balance_error: t.max_balance_error,
            dt: t.dt,
            n_steps: t.n_steps,
            n_elements,
            wall_time: timing.setup_s + timing.loop_s,
            impulse_momentum_error,
            cfl: t.dt / t.dt_critical,
            dt_critical: t.dt_critical,
            dt_update: t.dt_range.map(|_| DtUpdate::EveryStep.name()),
            dt_min: t.dt_range.map(|r| r[0]),
            dt_max: t.dt_range.map(|r| r[1]),
            final_time: t.final_time,
            stop_reason: t.stop,
            element: scene.mesh.element,
            kinematics: scene.kinematics,
            geometry: scene.geometry,
            model: scene.mesh.model,
            plastic: scene.is_plastic(),
            contact_law,
            indentation_datum: impactor.map(|i| i.indentation_datum),
            force_node: impactor.map(|i| i.force_node),
            initial_energy: t.initial_energy,
            final_energy: t.final_energy,
            setup_time: timing.setup_s,
            loop_time: timing.loop_s,
            ns_per_element_step: 1e9 * timing.loop_s
                / (n_elements as f64 * t.n_steps.max(1) as f64),
            threads_fallback: timing.threads_fallback,
            contact_step_factor: t.max_patch.map(|_| t.dt_critical / t.dt_plate),
            max_contact_half_width: t.max_patch.map(|p| p[0]),
            max_nodes_in_contact: t.max_patch.map(|p| p[1]),
            max_penetration: t.max_penetration,
            max_plastic_strain_rate: t.max_plastic_strain_rate.iter().cloned().collect(),
            max_temperature: t.max_temperature,
            heat: scene
                .rate_law()
                .and_then(|r| r.thermal())
                .map(|th| th.taylor_quinney * t.final_energy.plastic_work),
            warnings: scene.warnings.iter().map(ToString::to_string).collect(),
            result_warnings: crate::run::result_warnings::result_warnings(scene, t),
            wall: WallSummary::new(scene, t),
        }
    }
}
