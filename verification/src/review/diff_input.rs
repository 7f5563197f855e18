//! What `impact diff` reads from a run folder, refused when it cannot be compared:
//! `summary.json` must be a JSON object, and `history.csv` must have `time_s` first, strictly
//! increasing, and finite numbers everywhere (a NaN compares as no difference at all, and a
//! history written twice over would be called identical to the run).

use std::path::Path;

use anyhow::{bail, Context, Result};
use serde_json::Value;

/// A run's `summary.json`, which must be a JSON object.
pub fn read_summary(dir: &Path) -> Result<Value> {
    let path = dir.join("summary.json");
    let text = std::fs::read_to_string(&path).with_context(|| {
        format!(
            "{}: cannot read (is {} the --out folder of `impact simulate`?)",
            path.display(),
            dir.display()
        )
    })?;
    let value: Value =
        serde_json::from_str(&text).with_context(|| format!("{}: not JSON", path.display()))?;
    if !value.is_object() {
        bail!(
            "{}: expected a JSON object (key: value, as `impact simulate` writes), found {}",
            path.display(),
            json_kind(&value)
        );
    }
    Ok(value)
}

/// What a JSON value is, in words: `an array`, `a number`, `null`, ...
pub fn json_kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// (name, values) per column of a history CSV file, `time_s` first
/// ([`crate::definition::history_csv::read_columns`]).
pub fn history_columns(path: &Path) -> Result<Vec<(String, Vec<f64>)>> {
    if !path.is_file() {
        bail!(
            "{}: cannot read (is {} the --out folder of `impact simulate`?)",
            path.display(),
            path.parent().unwrap_or(Path::new(".")).display()
        );
    }
    crate::definition::history_csv::read_columns(path).map_err(anyhow::Error::msg)
}

/// Refuses a history that cannot be compared: a value that is not finite (NaN, inf), or a
/// `time_s` that does not strictly increase (a time running backwards or repeated). Rows are
/// numbered as in the file, the header being row 1.
pub fn check_comparable(path: &Path, cols: &[(String, Vec<f64>)]) -> Result<()> {
    for (name, values) in cols {
        if let Some(i) = values.iter().position(|x| !x.is_finite()) {
            bail!(
                "{}: row {}, column {name}: {} is not a finite number; a history with NaN or inf cannot be compared (the run that wrote it went wrong)",
                path.display(),
                i + 2,
                values[i]
            );
        }
    }
    let t = &cols[0].1;
    if let Some(i) = (1..t.len()).find(|&i| t[i] <= t[i - 1]) {
        bail!(
            "{}: row {}, column time_s: {:e} s after {:e} s in row {}: time_s must be strictly increasing (a history written twice over, or rows out of order?)",
            path.display(),
            i + 2,
            t[i],
            t[i - 1],
            i + 1
        );
    }
    Ok(())
}
