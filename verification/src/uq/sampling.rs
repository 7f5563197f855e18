//! A study's sampling plan, checked: the method (Sobol' or Latin hypercube) and the doubling
//! sample sizes, the optional coarser mesh of the sampled runs, the convergence criteria, and
//! the mesh levels of the numerical uncertainty.

use std::path::Path;

use serde_saphyr::Spanned;

use crate::definition::case::Loc;
use crate::uq::declaration::{invalid, Convergence, Sampling};

pub(super) fn check_sampling(s: &Spanned<Sampling>, path: &Path) -> Result<(), String> {
    let loc = Loc::of(path, s);
    let v = &s.value;
    if !matches!(v.method.as_str(), "sobol" | "lhs") {
        return Err(invalid(
            &loc,
            "sampling.method",
            &v.method,
            "must be sobol (scrambled Sobol', Saltelli's design) or lhs (Latin hypercube)",
        ));
    }
    let doubling = v.sizes.windows(2).all(|w| w[1] == 2 * w[0]);
    if v.sizes.is_empty() || !v.sizes[0].is_power_of_two() || v.sizes[0] < 4 || !doubling {
        return Err(invalid(
            &loc,
            "sampling.sizes",
            format!("{:?}", v.sizes),
            "must be powers of two >= 4, each twice the one before (nested Sobol' designs)",
        ));
    }
    Ok(())
}

/// `sampling.mesh`, when given, is one of the mesh levels below the declared mesh.
pub(super) fn check_sampling_mesh(
    s: &Spanned<Sampling>,
    levels: &[f64],
    path: &Path,
) -> Result<(), String> {
    match s.value.mesh {
        Some(m) if !(m < 1.0 && levels.contains(&m)) => Err(invalid(
            &Loc::of(path, s),
            "sampling.mesh",
            m,
            &format!("must be one of the mesh levels below 1 ({levels:?})"),
        )),
        _ => Ok(()),
    }
}

pub(super) fn check_convergence(c: &Spanned<Convergence>, path: &Path) -> Result<(), String> {
    let loc = Loc::of(path, c);
    for (name, x) in [
        ("mean", c.value.mean),
        ("std", c.value.std),
        ("total_index", c.value.total_index),
    ] {
        if !(x.is_finite() && x > 0.0) {
            return Err(invalid(
                &loc,
                &format!("convergence.{name}"),
                x,
                "must be a finite number > 0",
            ));
        }
    }
    Ok(())
}

pub(super) fn check_levels(l: &Spanned<Vec<f64>>, path: &Path) -> Result<(), String> {
    let loc = Loc::of(path, l);
    let v = &l.value;
    let ratio_ok = v.windows(2).all(|w| (w[1] / w[0] - 2.0).abs() < 1e-12);
    if v.len() < 3 || v.last() != Some(&1.0) || !ratio_ok {
        return Err(invalid(&loc, "mesh_levels", format!("{v:?}"), "must be at least three levels, each twice the one before, ending at 1 (the declared mesh)"));
    }
    Ok(())
}
