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

/// Tracks the imbalance `|E(t) - E(0) - W_ext(t)|` and the energy scale
/// `max(E(t), |W_ext(t)|, E(0))`. The reported balance error divides the imbalance by the
/// largest scale of the whole run (a running scale would make the first steps of a pulse,
/// when hardly any energy has entered yet, look like large errors); the running ratio is
/// what the blow-up guard watches.
#[derive(Debug, Clone, Copy, Default)]
pub struct BalanceMonitor {
    initial_total: Option<f64>,
    /// Largest energy scale so far, J.
    pub scale: f64,
    /// Largest imbalance so far, J.
    pub max_imbalance: f64,
}

impl BalanceMonitor {
    /// Records an instant; returns its imbalance (J) and the running ratio.
    pub fn record(&mut self, e: &Energies) -> (f64, f64) {
        let total = e.total();
        let initial = *self.initial_total.get_or_insert(total);
        self.scale = self
            .scale
            .max(total.abs())
            .max(e.external_work.abs())
            .max(initial.abs());
        let imbalance = (total - initial - e.external_work).abs();
        self.max_imbalance = self.max_imbalance.max(imbalance);
        (imbalance, self.ratio(imbalance))
    }

    /// An imbalance relative to the largest scale so far (0 while nothing has happened).
    pub fn ratio(&self, imbalance: f64) -> f64 {
        if self.scale > 0.0 {
            imbalance / self.scale
        } else {
            0.0
        }
    }

    /// The largest balance error of the run so far.
    pub fn max_error(&self) -> f64 {
        self.ratio(self.max_imbalance)
    }
}
