//! A comparison with a measurement (reference kind `experiment`): the validation budget of
//! ASME V&V 20-2009 (section 1-5 and 2-1) and the area metric of Ferson, Oberkampf and
//! Ginzburg (2008).
//!
//! - The comparison error `E = S - D` (eq. 1-5.2): `S` the simulation's value, `D` the
//!   measured one.
//! - The validation uncertainty `u_val = sqrt(u_num^2 + u_input^2 + u_D^2)` (eq. 1-5.5), each a
//!   standard uncertainty:
//!   - `u_num`, the simulation's discretisation error, estimated by Richardson at first order
//!     from the same scene on a mesh coarser by 2 in each direction:
//!     `|S - S_coarse| / (2^p - 1)` with `p = 1` (conservative where the observed order is
//!     higher; the Taylor bars' quantities converge at orders 1.1 to 1.9);
//!   - `u_input`, the propagated uncertainty of the inputs by the sensitivity-coefficient method
//!     (section 4-3): each input moved by its standard uncertainty in a scene of its own,
//!     `u_input = sqrt(sum_i (S_i - S)^2)` (first-order differences, inputs independent);
//!   - `u_D`, the measurement's standard uncertainty, as the case declares it (the shot-to-shot
//!     scatter of repeated tests, the reading of a printed number).
//! - The verdict: `|E| <= k u_val` (`k` the coverage factor, 2 by default: about 95 % when `E`'s
//!   distribution is near normal). Beyond it, the model's error `delta_model` is not covered by
//!   the uncertainties: the comparison shows a model-form error of about `E`.
//! - The area metric (`area_metric`): the area between the cumulative distributions of the
//!   prediction `N(S, u_num^2 + u_input^2)` and the measurement `N(D, u_D^2)`, in the
//!   quantity's unit (Ferson et al. 2008, eq. 4; ASME V&V 10.1-2012 section 4).

use serde::{Deserialize, Serialize};

/// What a case declares for one comparison with a measurement (`validation:` of a check).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ValidationFile {
    /// Coverage factor `k` of the expanded uncertainty (default 2).
    #[serde(default)]
    pub k: Option<f64>,
    /// `u_D`: the measurement's standard uncertainty.
    pub experiment: MeasurementUncertainty,
    /// `u_num`: the scene of the same shot on a mesh coarser by 2 in each direction.
    pub numerical: SceneDelta,
    /// `u_input`: per input, a scene with that input moved by its standard uncertainty.
    #[serde(default)]
    pub input: std::collections::BTreeMap<String, SceneDelta>,
}

impl ValidationFile {
    /// What makes the declaration unable to give a standard uncertainty and a coverage
    /// factor (empty when it can): `impact lint` reports each, and a run refuses them.
    pub fn declaration_problems(&self) -> Vec<&'static str> {
        let e = &self.experiment;
        let forms = [e.relative, e.absolute];
        let mut problems = Vec::new();
        if forms.iter().flatten().count() != 1
            || forms
                .iter()
                .flatten()
                .any(|x| !(*x >= 0.0 && x.is_finite()))
        {
            problems.push("experiment: exactly one of relative, absolute, finite and >= 0");
        }
        if self.k.is_some_and(|k| !(k > 0.0 && k.is_finite())) {
            problems.push("k must be finite and > 0");
        }
        problems
    }
}

/// A standard uncertainty of the measured value: relative to it, or absolute (its unit).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasurementUncertainty {
    #[serde(default)]
    pub relative: Option<f64>,
    #[serde(default)]
    pub absolute: Option<f64>,
    /// Where it comes from.
    pub reason: String,
}

/// A scene of the case whose value differs from the compared one by one cause.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDelta {
    pub scene: String,
    /// What the scene changes and why by that much.
    pub reason: String,
}

/// One comparison's budget, as results.json and the report carry it (the quantity's unit).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ValidationRow {
    /// `S`, `D` and `E = S - D`.
    pub simulation: f64,
    pub measurement: f64,
    pub comparison_error: f64,
    pub u_num: f64,
    pub u_input: f64,
    pub u_d: f64,
    pub u_val: f64,
    pub k: f64,
    /// Each input's `S_i - S`, by the input's name.
    pub input_deltas: Vec<(String, f64)>,
    /// The area metric of this comparison (`area_metric`).
    pub area: f64,
    /// The table under reference-data/ the measurement was read from (the report pools the
    /// comparisons of one table, i.e. one material, over its cases); none when the
    /// measurement is a value written in the case.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measurement_file: Option<String>,
    /// The row of that table (its one selecting value, a shot's id), when one column selects it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measurement_row: Option<String>,
}

impl ValidationRow {
    /// The budget of `S` against `D` from `S_coarse` and each input's `S_i`; `Err` names a
    /// declaration that cannot give a standard uncertainty.
    pub fn new(
        spec: &ValidationFile,
        (simulation, measurement): (f64, f64),
        coarse: f64,
        inputs: Vec<(String, f64)>,
    ) -> Result<ValidationRow, String> {
        let problems = spec.declaration_problems();
        if !problems.is_empty() {
            return Err(format!("validation: {}", problems.join("; ")));
        }
        let e = &spec.experiment;
        // Exactly one of the two is given (declaration_problems).
        let u_d = e
            .absolute
            .unwrap_or_else(|| e.relative.unwrap_or(0.0) * measurement.abs());
        if !u_d.is_finite() {
            return Err(format!(
                "validation: u_D = {u_d:e} from the measurement {measurement:e} is not finite"
            ));
        }
        let k = spec.k.unwrap_or(2.0);
        // Richardson at first order from a refinement ratio of 2: |S - S_coarse| / (2 - 1).
        let u_num = (simulation - coarse).abs();
        let input_deltas: Vec<(String, f64)> = inputs
            .into_iter()
            .map(|(name, value)| (name, value - simulation))
            .collect();
        let u_input = input_deltas.iter().map(|(_, d)| d * d).sum::<f64>().sqrt();
        let u_val = (u_num * u_num + u_input * u_input + u_d * u_d).sqrt();
        let spread = (u_num * u_num + u_input * u_input).sqrt();
        Ok(ValidationRow {
            simulation,
            measurement,
            comparison_error: simulation - measurement,
            u_num,
            u_input,
            u_d,
            u_val,
            k,
            input_deltas,
            area: area_metric((simulation, spread), (measurement, u_d)),
            measurement_file: None,
            measurement_row: None,
        })
    }

    /// Whether `|E| <= k u_val`.
    pub fn covered(&self) -> bool {
        self.comparison_error.abs() <= self.k * self.u_val
    }
}

/// The standard normal cumulative distribution (erfc by the Numerical Recipes Chebyshev fit,
/// relative error below 1.2e-7 everywhere).
fn normal_cdf(z: f64) -> f64 {
    let x = z / std::f64::consts::SQRT_2;
    let t = 1.0 / (1.0 + 0.5 * x.abs());
    let poly = -x * x - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let erfc = t * poly.exp();
    if x >= 0.0 {
        1.0 - 0.5 * erfc
    } else {
        0.5 * erfc
    }
}

/// The area between the cumulative distributions of `N(a.0, a.1^2)` and `N(b.0, b.1^2)` (their
/// unit): `int |F_a(x) - F_b(x)| dx`, by the trapezoidal rule on 4000 intervals over the means
/// +- 10 of the larger deviation. Two points (zero deviations) give `|a.0 - b.0|`; a zero
/// deviation is a step.
pub fn area_metric(a: (f64, f64), b: (f64, f64)) -> f64 {
    let spread = a.1.max(b.1);
    if spread == 0.0 {
        return (a.0 - b.0).abs();
    }
    let cdf = |(mean, sd): (f64, f64), x: f64| {
        if sd == 0.0 {
            if x < mean {
                0.0
            } else {
                1.0
            }
        } else {
            normal_cdf((x - mean) / sd)
        }
    };
    let lo = a.0.min(b.0) - 10.0 * spread;
    let hi = a.0.max(b.0) + 10.0 * spread;
    const N: usize = 4000;
    let h = (hi - lo) / N as f64;
    let gap = |i: usize| {
        let x = lo + h * i as f64;
        (cdf(a, x) - cdf(b, x)).abs()
    };
    h * (0.5 * (gap(0) + gap(N)) + (1..N).map(gap).sum::<f64>())
}

#[cfg(test)]
mod tests {
    //! The V&V 20 budget and the area metric, against ASME V&V 10.1-2012's worked example and
    //! closed forms.
    use super::*;

    fn spec(relative: Option<f64>, absolute: Option<f64>) -> ValidationFile {
        ValidationFile {
            k: None,
            experiment: MeasurementUncertainty {
                relative,
                absolute,
                reason: String::new(),
            },
            numerical: SceneDelta {
                scene: "coarse".into(),
                reason: String::new(),
            },
            input: Default::default(),
        }
    }

    #[test]
    fn the_area_metric_of_the_vv10_1_example() {
        // ASME V&V 10.1-2012, validation approach 1 (tapered cantilever tip deflection): the
        // model N(-14.2, (0.71/3)^2) mm against the experiment N(-15.0, (0.75/3)^2) mm: area
        // metric 0.800 mm (5.3 % of the experimental mean).
        let d = area_metric((-14.2, 0.71 / 3.0), (-15.0, 0.75 / 3.0));
        assert!((d - 0.800).abs() < 5e-4, "{d}");
    }

    #[test]
    fn the_area_of_equal_spreads_is_the_distance_of_the_means() {
        // Two normals of equal deviation are translates: the area is |mu_a - mu_b| exactly.
        for (gap, sd) in [(0.3, 1.0), (2.0, 0.1), (0.0, 0.5)] {
            let d = area_metric((1.0 + gap, sd), (1.0, sd));
            assert!((d - gap).abs() < 1e-6 * (1.0 + gap), "{gap} {sd}: {d}");
        }
        // A step against a normal at the same mean: the mean absolute deviation sd sqrt(2/pi).
        let d = area_metric((0.0, 0.0), (0.0, 1.0));
        assert!(
            (d - (2.0 / std::f64::consts::PI).sqrt()).abs() < 1e-4,
            "{d}"
        );
        assert_eq!(area_metric((3.0, 0.0), (1.0, 0.0)), 2.0);
    }

    #[test]
    fn the_budget_adds_in_quadrature_and_the_verdict_uses_k() {
        // S = 10, D = 9: E = 1; u_num = |10 - 10.3| = 0.3; inputs +0.4, -0.0 -> u_input 0.4;
        // u_D = 5 % of 9 = 0.45; u_val = sqrt(0.09 + 0.16 + 0.2025) = 0.6727; k u_val = 1.345.
        let row = ValidationRow::new(
            &spec(Some(0.05), None),
            (10.0, 9.0),
            10.3,
            vec![("speed".into(), 10.4), ("E".into(), 10.0)],
        )
        .unwrap();
        assert_eq!(row.comparison_error, 1.0);
        assert!((row.u_num - 0.3).abs() < 1e-12);
        assert!((row.u_input - 0.4).abs() < 1e-12);
        assert!((row.u_d - 0.45).abs() < 1e-12);
        assert!((row.u_val - 0.4525f64.sqrt()).abs() < 1e-12);
        assert!(row.covered());
        // The same with k = 1 is not covered: a check that can fail.
        let mut one = spec(Some(0.05), None);
        one.k = Some(1.0);
        let row = ValidationRow::new(&one, (10.0, 9.0), 10.3, vec![]).unwrap();
        assert!(!row.covered());
    }

    #[test]
    fn an_uncertainty_needs_exactly_one_form() {
        assert!(ValidationRow::new(&spec(None, None), (1.0, 1.0), 1.0, vec![]).is_err());
        // A relative u_D of a measurement that is not a number refuses too.
        let relative = spec(Some(0.1), None);
        assert!(ValidationRow::new(&relative, (1.0, f64::INFINITY), 1.0, vec![]).is_err());
        assert!(ValidationRow::new(&spec(Some(0.1), Some(0.1)), (1.0, 1.0), 1.0, vec![]).is_err());
        assert!(ValidationRow::new(&spec(None, Some(-1.0)), (1.0, 1.0), 1.0, vec![]).is_err());
    }
}
