//! `material.plasticity.rate`: the strain-rate (and temperature) dependence of the flow
//! stress, read from YAML and validated. Absent, the plasticity is rate-independent (the
//! paper's model, and its bits).
//!
//! - `cowper_symonds: {D: 1/s, q: -}`: `sigma_y(k) [1 + (rate / D)^(1/q)]`;
//! - `johnson_cook: {A: Pa, B: Pa, n: -, C: -, reference_rate: 1/s, m: -, thermal: {...}}`:
//!   `[A + B k^n] [1 + C ln(rate / reference_rate)] [1 - T*^m]` (no `yield_stress` or
//!   `hardening` beside it: A, B and n are the flow curve), with optional adiabatic heating
//!   `thermal: {initial_temperature: K, melting_temperature: K, specific_heat: J/(kg K),
//!   taylor_quinney: -}`.
//!
//! `rate` is the equivalent plastic strain rate (1/s), `k` the equivalent plastic strain and
//! `T* = (T - T0) / (Tm - T0)` the homologous temperature. ALGORITHM.md section 4b.

use serde::Deserialize;
use serde_saphyr::Spanned;

use crate::input::error::Result;
use crate::input::scene::{Rule, Validator, NON_NEGATIVE, POSITIVE};

type Num = Spanned<f64>;

/// `rate:` as written: one key naming the law.
#[derive(Debug, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum RateFile {
    CowperSymonds(CowperSymondsFile),
    JohnsonCook(JohnsonCookFile),
}

/// `cowper_symonds: {D: 1/s, q: -}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CowperSymondsFile {
    #[serde(rename = "D")]
    pub d: Num,
    pub q: Num,
}

/// `johnson_cook: {A, B, n, C, reference_rate, m, thermal}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JohnsonCookFile {
    /// Static yield stress at the reference temperature, Pa.
    #[serde(rename = "A")]
    pub a: Num,
    /// Hardening coefficient, Pa.
    #[serde(rename = "B")]
    pub b: Num,
    /// Hardening exponent (-).
    pub n: Num,
    /// Rate coefficient (-).
    #[serde(rename = "C")]
    pub c: Num,
    /// Reference equivalent plastic strain rate, 1/s.
    pub reference_rate: Num,
    /// Thermal softening exponent (-); needed with `thermal`.
    #[serde(default)]
    pub m: Option<Num>,
    #[serde(default)]
    pub thermal: Option<Spanned<ThermalFile>>,
}

/// `thermal: {initial_temperature: K, melting_temperature: K, specific_heat: J/(kg K),
/// taylor_quinney: -}`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThermalFile {
    pub initial_temperature: Num,
    pub melting_temperature: Num,
    pub specific_heat: Num,
    pub taylor_quinney: Num,
}

/// The validated rate law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RateLaw {
    /// Cowper-Symonds: the static flow stress times `1 + (rate / d)^(1/q)`.
    CowperSymonds {
        /// 1/s
        d: f64,
        /// Exponent (-).
        q: f64,
    },
    /// Johnson-Cook's rate and temperature factors (its `A + B k^n` is the static curve,
    /// [`crate::input::scene::Hardening::Power`]).
    JohnsonCook {
        /// Rate coefficient C (-).
        c: f64,
        /// 1/s; below it the rate factor is 1 (no softening by slow flow).
        reference_rate: f64,
        thermal: Option<Thermal>,
    },
}

/// Adiabatic heating and Johnson-Cook's thermal softening.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thermal {
    /// T0, also the reference temperature of `T*`, K.
    pub initial_temperature: f64,
    /// Tm, K.
    pub melting_temperature: f64,
    /// c, J/(kg K).
    pub specific_heat: f64,
    /// beta, the fraction of the plastic work that heats (-).
    pub taylor_quinney: f64,
    /// Johnson-Cook's m (-).
    pub softening_exponent: f64,
}

impl RateLaw {
    /// The temperature model, if the law heats.
    pub fn thermal(&self) -> Option<&Thermal> {
        match self {
            RateLaw::JohnsonCook { thermal, .. } => thermal.as_ref(),
            RateLaw::CowperSymonds { .. } => None,
        }
    }
}

const EXPONENT: Rule = Rule {
    allowed: "must be a finite number > 0 (an exponent)",
    ok: |v| v.is_finite() && v > 0.0,
};
const FRACTION: Rule = Rule {
    allowed: "must lie in [0, 1] (the fraction of the plastic work that heats)",
    ok: |v| (0.0..=1.0).contains(&v),
};

/// Johnson-Cook's static curve `A + B k^n`: (A Pa, B Pa, n).
pub type PowerCurve = (f64, f64, f64);

/// The 42CrMo4 steel of DynELA's Taylor bar sample (Pantale, DynELA v4 documentation,
/// "DynELA impact sample cases", its table of Johnson-Cook parameters: A = 806 MPa,
/// B = 614 MPa, n = 0.168, C = 0.0089, m = 1.1, reference rate 1 1/s, T0 = 20 C,
/// Tm = 1540 C, c = 460 J/(kg K), Taylor-Quinney 0.9; rho = 7830 kg/m^3, E = 206.9 GPa):
/// its static curve and its law with heating.
pub fn johnson_cook_42crmo4() -> (PowerCurve, RateLaw) {
    (
        (806e6, 614e6, 0.168),
        RateLaw::JohnsonCook {
            c: 0.0089,
            reference_rate: 1.0,
            thermal: Some(Thermal {
                initial_temperature: 293.15,
                melting_temperature: 1813.15,
                specific_heat: 460.0,
                taylor_quinney: 0.9,
                softening_exponent: 1.1,
            }),
        },
    )
}

impl Validator<'_> {
    /// The law of `rate:`, and for Johnson-Cook its static curve.
    pub(super) fn rate_law(&self, r: &RateFile) -> Result<(RateLaw, Option<PowerCurve>)> {
        let f = |k: &str| format!("material.plasticity.rate.{k}");
        match r {
            RateFile::CowperSymonds(cs) => Ok((
                RateLaw::CowperSymonds {
                    d: self.check(&cs.d, &f("cowper_symonds.D"), POSITIVE)?,
                    q: self.check(&cs.q, &f("cowper_symonds.q"), EXPONENT)?,
                },
                None,
            )),
            RateFile::JohnsonCook(jc) => {
                let g = |k: &str| f(&format!("johnson_cook.{k}"));
                let curve = (
                    self.check(&jc.a, &g("A"), POSITIVE)?,
                    self.check(&jc.b, &g("B"), NON_NEGATIVE)?,
                    self.check(&jc.n, &g("n"), EXPONENT)?,
                );
                let m =
                    jc.m.as_ref()
                        .map(|m| self.check(m, &g("m"), EXPONENT))
                        .transpose()?;
                let thermal = match &jc.thermal {
                    None => None,
                    Some(t) => Some(self.thermal(t, m)?),
                };
                let law = RateLaw::JohnsonCook {
                    c: self.check(&jc.c, &g("C"), NON_NEGATIVE)?,
                    reference_rate: self.check(
                        &jc.reference_rate,
                        &g("reference_rate"),
                        POSITIVE,
                    )?,
                    thermal,
                };
                Ok((law, Some(curve)))
            }
        }
    }

    fn thermal(&self, t: &Spanned<ThermalFile>, m: Option<f64>) -> Result<Thermal> {
        let g = |k: &str| format!("material.plasticity.rate.johnson_cook.thermal.{k}");
        let th = &t.value;
        let initial = self.check(&th.initial_temperature, &g("initial_temperature"), POSITIVE)?;
        let melting = self.check(&th.melting_temperature, &g("melting_temperature"), POSITIVE)?;
        if melting <= initial {
            return self.fail(
                &th.melting_temperature,
                &g("melting_temperature"),
                crate::input::error::shown(melting),
                format!(
                    "must be above initial_temperature = {} K",
                    crate::input::error::shown(initial)
                ),
            );
        }
        let Some(m) = m else {
            return self.fail(
                t,
                "material.plasticity.rate.johnson_cook.m",
                "missing",
                "the thermal softening exponent m (> 0) is needed with thermal",
            );
        };
        Ok(Thermal {
            initial_temperature: initial,
            melting_temperature: melting,
            specific_heat: self.check(&th.specific_heat, &g("specific_heat"), POSITIVE)?,
            taylor_quinney: self.check(&th.taylor_quinney, &g("taylor_quinney"), FRACTION)?,
            softening_exponent: m,
        })
    }
}
