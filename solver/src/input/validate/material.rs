//! `material`: the elastic constants, the plasticity's flow curve (linear, tabulated or
//! Johnson-Cook's) and its strain-rate law (`material.plasticity.rate`, `ALGORITHM.md`
//! section 4b).

use serde_saphyr::Spanned;

use crate::input::error::{shown, Error, Result};
use crate::input::scene::{
    Hardening, HardeningFile, Material, MaterialFile, Plasticity, PlasticityFile, PowerCurve,
    RateFile, RateLaw, Thermal, ThermalFile,
};

use super::{Rule, Validator, NON_NEGATIVE, POISSON, POSITIVE};

const EXPONENT: Rule = Rule {
    allowed: "must be a finite number > 0 (an exponent)",
    ok: |v| v.is_finite() && v > 0.0,
};
const FRACTION: Rule = Rule {
    allowed: "must lie in [0, 1] (the fraction of the plastic work that heats)",
    ok: |v| (0.0..=1.0).contains(&v),
};

impl Validator<'_> {
    pub(super) fn material(&self, m: MaterialFile) -> Result<Material> {
        let youngs_modulus = self.check(&m.youngs_modulus, "material.youngs_modulus", POSITIVE)?;
        let plasticity = match m.plasticity {
            None => None,
            Some(p) => Some(self.plasticity(&p, youngs_modulus)?),
        };
        Ok(Material {
            density: self.check(&m.density, "material.density", POSITIVE)?,
            youngs_modulus,
            poisson_ratio: self.check(&m.poisson_ratio, "material.poisson_ratio", POISSON)?,
            plasticity,
        })
    }

    fn plasticity(&self, p: &Spanned<PlasticityFile>, youngs_modulus: f64) -> Result<Plasticity> {
        let (rate, power) = match &p.value.rate {
            None => (None, None),
            Some(r) => {
                let (law, power) = self.rate_law(&r.value)?;
                (Some(law), power)
            }
        };
        if let Some((a, b, n)) = power {
            return self.johnson_cook_curve(p, rate, (a, b, n));
        }
        let missing = |key: &str| {
            self.fail(
                p,
                &format!("material.plasticity.{key}"),
                "missing",
                "needed unless rate: {johnson_cook: {A, B, n, ...}} gives the flow curve",
            )
        };
        let Some(ys) = &p.value.yield_stress else {
            return missing("yield_stress");
        };
        let Some(h) = &p.value.hardening else {
            return missing("hardening");
        };
        let yield_stress = self.check(ys, "material.plasticity.yield_stress", POSITIVE)?;
        Ok(Plasticity {
            yield_stress,
            hardening: self.hardening(h, yield_stress, youngs_modulus)?,
            rate,
        })
    }

    /// Johnson-Cook's flow curve `A + B k^n`: `yield_stress` and `hardening` must be absent.
    fn johnson_cook_curve(
        &self,
        p: &Spanned<PlasticityFile>,
        rate: Option<RateLaw>,
        (a, b, n): (f64, f64, f64),
    ) -> Result<Plasticity> {
        let given = [
            (
                "yield_stress",
                p.value.yield_stress.as_ref().map(|v| self.at(v)),
            ),
            ("hardening", p.value.hardening.as_ref().map(|v| self.at(v))),
        ];
        if let Some((key, Some(at))) = given.into_iter().find(|(_, at)| at.is_some()) {
            return Err(Error::invalid(
                at,
                &format!("material.plasticity.{key}"),
                "given",
                "must be left out with rate: {johnson_cook}: A, B and n are the flow curve",
            ));
        }
        Ok(Plasticity {
            yield_stress: a,
            hardening: Hardening::Power {
                coefficient: b,
                exponent: n,
            },
            rate,
        })
    }

    fn hardening(
        &self,
        h: &Spanned<HardeningFile>,
        yield_stress: f64,
        youngs_modulus: f64,
    ) -> Result<Hardening> {
        let field = "material.plasticity.hardening";
        match &h.value {
            HardeningFile::Linear(et) => {
                self.read_number(et, &format!("{field}.linear"), Some(et.value));
                let (at, et) = (et, &et.value);
                if !(et.is_finite() && *et >= 0.0 && *et < youngs_modulus) {
                    return self.fail(
                        at,
                        &format!("{field}.linear"),
                        shown(*et),
                        format!(
                            "tangent modulus must lie in [0, youngs_modulus = {youngs_modulus:e}) Pa"
                        ),
                    );
                }
                Ok(Hardening::Linear {
                    tangent_modulus: *et,
                })
            }
            HardeningFile::Table(rows) => self.hardening_table(h, rows, yield_stress),
        }
    }

    fn hardening_table(
        &self,
        at: &Spanned<HardeningFile>,
        rows: &[[f64; 2]],
        yield_stress: f64,
    ) -> Result<Hardening> {
        let field = "material.plasticity.hardening.table";
        let show = |r: &[f64; 2]| format!("[{:e}, {:e}]", r[0], r[1]);
        let Some(first) = rows.first() else {
            return self.fail(
                at,
                field,
                "[]",
                "needs at least one [eqps, flow stress] row",
            );
        };
        if first[0] != 0.0 || (first[1] - yield_stress).abs() > 1e-9 * yield_stress {
            return self.fail(
                at,
                &format!("{field}[0]"),
                show(first),
                format!("must be [0, yield_stress] = [0, {yield_stress:e}]"),
            );
        }
        for (k, pair) in rows.windows(2).enumerate() {
            let (a, b) = (pair[0], pair[1]);
            if !(b[0].is_finite() && b[1].is_finite() && b[0] > a[0] && b[1] >= a[1]) {
                return self.fail(
                    at,
                    &format!("{field}[{}]", k + 1),
                    show(&b),
                    format!(
                        "rows must have increasing plastic strain and non-decreasing stress (previous row {})",
                        show(&a)
                    ),
                );
            }
        }
        Ok(Hardening::Table(
            rows.iter().map(|r| (r[0], r[1])).collect(),
        ))
    }

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
                shown(melting),
                format!("must be above initial_temperature = {} K", shown(initial)),
            );
        }
        let reference = match &th.reference_temperature {
            None => initial,
            Some(r) => {
                let reference = self.check(r, &g("reference_temperature"), POSITIVE)?;
                if reference > initial {
                    return self.fail(
                        r,
                        &g("reference_temperature"),
                        shown(reference),
                        format!("must not be above initial_temperature = {} K: Johnson-Cook's T* = (T - Tr) / (Tm - Tr) is used from the reference temperature up (a shot colder than the tests of the fit is not modelled)", shown(initial)),
                    );
                }
                reference
            }
        };
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
            reference_temperature: reference,
            melting_temperature: melting,
            specific_heat: self.check(&th.specific_heat, &g("specific_heat"), POSITIVE)?,
            taylor_quinney: self.check(&th.taylor_quinney, &g("taylor_quinney"), FRACTION)?,
            softening_exponent: m,
        })
    }
}
