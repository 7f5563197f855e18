//! The distributions an uncertainty study declares for its inputs (issue 27): uniform, normal,
//! lognormal (by mean and coefficient of variation) and a normal or lognormal truncated to
//! `[lower, upper]`; each checked with the place it is declared. The Python package maps the
//! unit hypercube onto them (`impact._distributions`).

use std::path::Path;

use serde::{Deserialize, Serialize};
use serde_saphyr::Spanned;

use crate::definition::case::Loc;

#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Uniform {
    pub lower: f64,
    pub upper: f64,
}

#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Normal {
    pub mean: f64,
    pub std: f64,
}

/// A lognormal distribution by its mean and coefficient of variation (std / mean).
#[derive(Debug, Clone, Copy, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Lognormal {
    pub mean: f64,
    pub cov: f64,
}

#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Truncated {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<Normal>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lognormal: Option<Lognormal>,
    pub lower: f64,
    pub upper: f64,
}

/// One uncertain input: exactly one distribution, and where it comes from.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InputFile {
    #[serde(default)]
    pub uniform: Option<Uniform>,
    #[serde(default)]
    pub normal: Option<Normal>,
    #[serde(default)]
    pub lognormal: Option<Lognormal>,
    #[serde(default)]
    pub truncated: Option<Truncated>,
    pub source: Option<Spanned<String>>,
}

#[derive(Debug, Clone, Serialize)]
pub struct Input {
    pub key: String,
    /// `uniform`, `normal`, `lognormal` or `truncated`, and its parameters.
    pub kind: &'static str,
    pub distribution: serde_json::Value,
    pub source: String,
    /// Where it is declared, `file:line:col`.
    pub at: String,
}

fn finite_positive(loc: &Loc, field: &str, x: f64) -> Result<(), String> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(format!("{loc}: {field} = {x}: must be a finite number > 0"))
    }
}

fn finite(loc: &Loc, field: &str, x: f64) -> Result<(), String> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(format!("{loc}: {field} = {x}: must be a finite number"))
    }
}

fn normal(loc: &Loc, field: &str, n: &Normal) -> Result<(), String> {
    finite(loc, &format!("{field}.mean"), n.mean)?;
    finite_positive(loc, &format!("{field}.std"), n.std)
}

fn lognormal(loc: &Loc, field: &str, l: &Lognormal) -> Result<(), String> {
    finite_positive(loc, &format!("{field}.mean"), l.mean)?;
    finite_positive(loc, &format!("{field}.cov"), l.cov)
}

fn uniform(loc: &Loc, field: &str, u: &Uniform) -> Result<(), String> {
    finite(loc, &format!("{field}.lower"), u.lower)?;
    finite(loc, &format!("{field}.upper"), u.upper)?;
    if u.upper > u.lower {
        Ok(())
    } else {
        Err(format!(
            "{loc}: {field}.upper = {}: must be > lower ({})",
            u.upper, u.lower
        ))
    }
}

fn truncated(loc: &Loc, field: &str, t: &Truncated) -> Result<(), String> {
    let centre = match (&t.normal, &t.lognormal) {
        (Some(n), None) => {
            normal(loc, &format!("{field}.normal"), n)?;
            n.mean
        }
        (None, Some(l)) => {
            lognormal(loc, &format!("{field}.lognormal"), l)?;
            l.mean
        }
        _ => {
            return Err(format!(
            "{loc}: {field}: needs exactly one of normal or lognormal (the distribution truncated)"
        ))
        }
    };
    uniform(
        loc,
        field,
        &Uniform {
            lower: t.lower,
            upper: t.upper,
        },
    )?;
    if !(t.lower < centre && centre < t.upper) {
        return Err(format!(
            "{loc}: {field} = [{}, {}]: must hold the mean {centre}",
            t.lower, t.upper
        ));
    }
    Ok(())
}

/// Checks one input's declaration and returns it for the study.
pub fn validate(key: &str, spec: &Spanned<InputFile>, path: &Path) -> Result<Input, String> {
    let loc = Loc::of(path, spec);
    let f = &spec.value;
    let field = format!("inputs.{key}");
    let source = match &f.source {
        Some(s) if !s.value.trim().is_empty() => s.value.clone(),
        _ => {
            return Err(format!(
            "{loc}: {field}.source: missing: every input names where its distribution comes from"
        ))
        }
    };
    let given = [
        f.uniform.is_some(),
        f.normal.is_some(),
        f.lognormal.is_some(),
        f.truncated.is_some(),
    ];
    if given.iter().filter(|b| **b).count() != 1 {
        return Err(format!(
            "{loc}: {field}: needs exactly one of uniform, normal, lognormal, truncated"
        ));
    }
    let (kind, distribution) = if let Some(u) = &f.uniform {
        uniform(&loc, &format!("{field}.uniform"), u)?;
        ("uniform", serde_json::to_value(u))
    } else if let Some(n) = &f.normal {
        normal(&loc, &format!("{field}.normal"), n)?;
        ("normal", serde_json::to_value(n))
    } else if let Some(l) = &f.lognormal {
        lognormal(&loc, &format!("{field}.lognormal"), l)?;
        ("lognormal", serde_json::to_value(l))
    } else {
        let t = f.truncated.as_ref().expect("one of four");
        truncated(&loc, &format!("{field}.truncated"), t)?;
        ("truncated", serde_json::to_value(t))
    };
    Ok(Input {
        key: key.to_string(),
        kind,
        distribution: distribution.map_err(|e| e.to_string())?,
        source,
        at: loc.to_string(),
    })
}

/// The centre of a validated distribution: its mean, or the middle of a uniform range.
pub fn centre(d: &serde_json::Value) -> f64 {
    let inner = d.get("normal").or_else(|| d.get("lognormal")).unwrap_or(d);
    match inner.get("mean").and_then(|m| m.as_f64()) {
        Some(m) => m,
        None => 0.5 * (d["lower"].as_f64().unwrap_or(0.0) + d["upper"].as_f64().unwrap_or(0.0)),
    }
}
