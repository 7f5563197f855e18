//! Energy bookkeeping of a run (whole plate, whole width, J) and the balance error.

/// The energy terms at one instant, J.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Energies {
    pub plate_kinetic: f64,
    pub impactor_kinetic: f64,
    pub strain: f64,
    pub plastic_work: f64,
    pub hourglass: f64,
    pub contact: f64,
    /// Work done on the plate by a prescribed pulse.
    pub external_work: f64,
}

impl Energies {
    /// Energy held or dissipated in the system: everything but the external work.
    pub fn total(&self) -> f64 {
        self.plate_kinetic
            + self.impactor_kinetic
            + self.strain
            + self.plastic_work
            + self.hourglass
            + self.contact
    }

    pub fn as_row(&self) -> [f64; 7] {
        [
            self.plate_kinetic,
            self.impactor_kinetic,
            self.strain,
            self.plastic_work,
            self.hourglass,
            self.contact,
            self.external_work,
        ]
    }

    pub const COLUMNS: [&'static str; 7] = [
        "plate_kinetic_J",
        "impactor_kinetic_J",
        "strain_energy_J",
        "plastic_work_J",
        "hourglass_energy_J",
        "contact_energy_J",
        "external_work_J",
    ];
}

/// Tracks `|E(t) - E(0) - W_ext(t)| / max_{s <= t} max(E(s), |W_ext(s)|, E(0))`.
#[derive(Debug, Clone, Copy, Default)]
pub struct BalanceMonitor {
    initial_total: Option<f64>,
    scale: f64,
    pub max_error: f64,
}

impl BalanceMonitor {
    /// Records an instant and returns its balance error.
    pub fn record(&mut self, e: &Energies) -> f64 {
        let total = e.total();
        let initial = *self.initial_total.get_or_insert(total);
        self.scale = self
            .scale
            .max(total.abs())
            .max(e.external_work.abs())
            .max(initial.abs());
        let error = if self.scale > 0.0 {
            (total - initial - e.external_work).abs() / self.scale
        } else {
            0.0
        };
        self.max_error = self.max_error.max(error);
        error
    }
}
