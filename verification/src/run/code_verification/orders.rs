//! Observed orders of accuracy from a refinement sequence (Roache 1998, "Verification and
//! Validation in Computational Science and Engineering", ch. 5; Oberkampf & Roy 2010, sec. 8.2).

/// With the exact solution known: the order of each consecutive pair of levels,
/// `p_k = ln(e_k / e_{k+1}) / ln r` (errors coarse to fine, refinement ratio `r`).
pub fn pair_orders(errors: &[f64], r: f64) -> Vec<f64> {
    errors
        .windows(2)
        .map(|w| (w[0] / w[1]).ln() / r.ln())
        .collect()
}

/// Without it: the order of each consecutive triplet of solutions,
/// `p_k = ln(|f_k - f_{k+1}| / |f_{k+1} - f_{k+2}|) / ln r`, from the norms of the
/// differences `d_k = |f_k - f_{k+1}|` (coarse to fine).
pub fn difference_orders(differences: &[f64], r: f64) -> Vec<f64> {
    pair_orders(differences, r)
}

/// The largest change between consecutive observed orders (0 for fewer than two):
/// how far the sequence is from its asymptotic range.
pub fn largest_step(orders: &[f64]) -> f64 {
    orders
        .windows(2)
        .map(|w| (w[1] - w[0]).abs())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_power_law_gives_its_exponent_and_a_flat_sequence() {
        let e: Vec<f64> = (0..5).map(|k| 3.0 * 0.5f64.powi(2 * k) + 0.0).collect();
        let p = pair_orders(&e, 2.0);
        assert!(p.iter().all(|p| (p - 2.0).abs() < 1e-12), "{p:?}");
        assert!(largest_step(&p) < 1e-12);
        // A pre-asymptotic sequence (second term) shows a drift.
        let e: Vec<f64> = (0..5)
            .map(|k| 0.5f64.powi(2 * k) + 0.5f64.powi(k))
            .collect();
        let p = pair_orders(&e, 2.0);
        assert!(largest_step(&p) > 0.1, "{p:?}");
    }
}
