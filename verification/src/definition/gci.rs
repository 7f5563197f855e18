//! The grid convergence index done as Roache (1998, "Verification and Validation in
//! Computational Science and Engineering", ch. 5) and Celik et al. (2008, "Procedure for
//! estimation and reporting of uncertainty due to discretization in CFD applications",
//! J. Fluids Eng. 130:078001) ask:
//! - the observed order of every triplet of consecutive levels is reported;
//! - the increments `f_{k+1} - f_k` must keep one sign (monotone convergence) and every
//!   convergence ratio `R = (f_{k+2} - f_{k+1}) / (f_{k+1} - f_k)` lie in (0, 1); otherwise the
//!   series is not asymptotic: a failure with the evidence, not an order;
//! - the safety factor Fs = 1.25 only with at least three grids whose observed orders all lie
//!   within 10 % of the formal order (then p = the finest triplet's order); otherwise Fs = 3
//!   with p capped at the formal order.

/// The assessment of one refinement series (levels coarse to fine, constant ratio `r`).
#[derive(Debug, Clone, PartialEq)]
pub struct Assessment {
    /// Observed order of each consecutive triplet, coarse to fine.
    pub orders: Vec<f64>,
    /// Convergence ratio of each triplet.
    pub ratios: Vec<f64>,
    /// The GCI, when a formal order was given.
    pub gci: Option<Gci>,
}

/// The fine-grid grid convergence index and how it was formed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gci {
    /// The safety factor used (1.25 or 3).
    pub safety_factor: f64,
    /// The order used (the finest triplet's, capped at formal when Fs = 3).
    pub order_used: f64,
    /// Relative: `Fs |(f_n - f_{n-1}) / f_n| / (r^p - 1)`.
    pub value: f64,
}

impl Assessment {
    /// The finest triplet's observed order.
    pub fn finest_order(&self) -> f64 {
        self.orders[self.orders.len() - 1]
    }
}

/// Fraction of the formal order within which every observed order must lie for Fs = 1.25.
pub const ASYMPTOTIC_BAND: f64 = 0.1;

/// Assesses `values` (coarse to fine, refinement ratio `r` > 1), with the GCI when the
/// `formal` order is given. `Err` with the evidence when the series is not in the asymptotic
/// range (or too short).
pub fn assess(values: &[f64], r: f64, formal: Option<f64>) -> Result<Assessment, String> {
    if values.len() < 3 {
        return Err(format!(
            "a GCI needs at least three levels, got {}",
            values.len()
        ));
    }
    if !(r > 1.0 && formal.is_none_or(|p| p > 0.0)) {
        return Err(format!(
            "refinement ratio {r} must be > 1 and the formal order {formal:?} > 0"
        ));
    }
    let increments: Vec<f64> = values.windows(2).map(|w| w[1] - w[0]).collect();
    let ratios: Vec<f64> = increments.windows(2).map(|w| w[1] / w[0]).collect();
    let orders: Vec<f64> = ratios
        .iter()
        .map(|q| (1.0 / q.abs()).ln() / r.ln())
        .collect();
    let evidence = || {
        format!(
            "values {}; increments {}; convergence ratios {}; triplet orders {}",
            list(values),
            list(&increments),
            list(&ratios),
            list(&orders)
        )
    };
    let sign = increments[0].signum();
    if increments.iter().any(|d| *d == 0.0 || d.signum() != sign) {
        return Err(format!(
            "not asymptotic: the increments change sign or vanish (oscillatory or stalled): {}",
            evidence()
        ));
    }
    if ratios.iter().any(|q| !(*q > 0.0 && *q < 1.0)) {
        return Err(format!(
            "not asymptotic: a convergence ratio lies outside (0, 1) (diverging): {}",
            evidence()
        ));
    }
    let f_fine = values[values.len() - 1];
    let last = increments[increments.len() - 1];
    let gci = formal.map(|formal| fine_grid_index(&orders, formal, last / f_fine, r));
    Ok(Assessment {
        orders,
        ratios,
        gci,
    })
}

/// Fs = 1.25 with p = the finest order when every triplet's order lies within 10 % of
/// `formal`, else Fs = 3 with p capped at `formal`; `relative_change` = (f_n - f_{n-1}) / f_n.
fn fine_grid_index(orders: &[f64], formal: f64, relative_change: f64, r: f64) -> Gci {
    let finest = orders[orders.len() - 1];
    let near_formal = orders
        .iter()
        .all(|p| (p - formal).abs() <= ASYMPTOTIC_BAND * formal);
    let (safety_factor, order_used) = if near_formal {
        (1.25, finest)
    } else {
        (3.0, finest.min(formal))
    };
    Gci {
        safety_factor,
        order_used,
        value: safety_factor * relative_change.abs() / (r.powf(order_used) - 1.0),
    }
}

fn list(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| format!("{x:.4e}")).collect();
    format!("[{}]", items.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn power_law(h: &[f64], p: f64) -> Vec<f64> {
        h.iter().map(|h| 1.0 + 3.0 * h.powf(p)).collect()
    }

    #[test]
    fn an_asymptotic_series_gets_fs_1_25_and_its_order() {
        let f = power_law(&[0.5, 0.25, 0.125, 0.0625], 2.0);
        let a = assess(&f, 2.0, Some(2.0)).unwrap();
        assert!(a.orders.iter().all(|p| (p - 2.0).abs() < 1e-9), "{a:?}");
        let g = a.gci.unwrap();
        assert_eq!(g.safety_factor, 1.25);
        let expected = 1.25 * ((f[3] - f[2]) / f[3]).abs() / 3.0;
        assert!((g.value / expected - 1.0).abs() < 1e-9);
        assert!(assess(&f, 2.0, None).unwrap().gci.is_none());
    }

    #[test]
    fn an_order_far_from_formal_gets_fs_3_and_the_order_capped() {
        // Order 3.7 against formal 2: Fs 3 with p = 2.
        let f = power_law(&[0.5, 0.25, 0.125], 3.7);
        let g = assess(&f, 2.0, Some(2.0)).unwrap().gci.unwrap();
        assert_eq!((g.safety_factor, g.order_used), (3.0, 2.0));
        // Order 1.5 against formal 2: Fs 3 with its own order.
        let f = power_law(&[0.5, 0.25, 0.125], 1.5);
        let g = assess(&f, 2.0, Some(2.0)).unwrap().gci.unwrap();
        assert_eq!(g.safety_factor, 3.0);
        assert!((g.order_used - 1.5).abs() < 1e-9);
        // Orders 0.5 then 2.0: not all within 10 %, Fs 3 although the finest is formal.
        let f = [
            1.0,
            1.5,
            1.5 + 0.5 / 2f64.sqrt(),
            1.5 + 0.5 / 2f64.sqrt() + 0.5 / 2f64.sqrt() / 4.0,
        ];
        let a = assess(&f, 2.0, Some(2.0)).unwrap();
        assert!((a.orders[0] - 0.5).abs() < 1e-9 && (a.orders[1] - 2.0).abs() < 1e-9);
        assert_eq!(a.gci.unwrap().safety_factor, 3.0);
    }

    #[test]
    fn oscillating_or_diverging_series_fail_with_the_evidence() {
        let e = assess(&[1.0, 1.1, 1.05, 1.07], 2.0, Some(2.0)).unwrap_err();
        assert!(
            e.contains("change sign") && e.contains("triplet orders"),
            "{e}"
        );
        let e = assess(&[1.0, 1.1, 1.3], 2.0, Some(2.0)).unwrap_err();
        assert!(e.contains("outside (0, 1)"), "{e}");
        assert!(assess(&[1.0, 1.1], 2.0, None).is_err());
    }
}
