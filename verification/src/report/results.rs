//! The report's reading of results.json: a malformed file is refused naming the file, the key
//! and what was expected (the templates would otherwise fail on it with their own words), and
//! the counts are recounted from the check rows (the stored `counts` are not trusted: an
//! edited or half-written file could claim "5 OK" over rows that say otherwise).

use std::path::Path;

use anyhow::{bail, Context, Result};
use serde_json::Value;

use crate::definition::check::CheckResult;
use crate::definition::verdict::Tally;
use crate::review::diff_input::json_kind;
use crate::run::matrix::Counts;

/// results.json read, checked, and its counts recounted from the rows.
pub fn read(path: &Path) -> Result<(Value, Counts)> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: run `impact verify --out DIR` first", path.display()))?;
    let results: Value =
        serde_json::from_str(&text).with_context(|| format!("{}: not JSON", path.display()))?;
    let counts = recount(&results).with_context(|| format!("{}", path.display()))?;
    Ok((results, counts))
}

/// The counts of the rows of `results` (an object with `cases`, each an object with `suite`,
/// `case` and `checks`, each check a full check row).
pub fn recount(results: &Value) -> Result<Counts> {
    if !results.is_object() {
        bail!(
            "top level: expected a JSON object, found {}",
            json_kind(results)
        );
    }
    let cases = array(results, "cases", "cases")?;
    let mut tally = Tally::default();
    let mut seen: Vec<(&str, &str)> = Vec::new();
    for (i, case) in cases.iter().enumerate() {
        let at = format!("cases[{i}]");
        if !case.is_object() {
            bail!(
                "{at}: expected an object (one case), found {}",
                json_kind(case)
            );
        }
        let suite = string(case, "suite", &at)?;
        let name = string(case, "case", &at)?;
        let checks = array(case, "checks", &format!("{at}.checks"))?;
        if let Some(first) = seen.iter().position(|c| *c == (suite, name)) {
            bail!("{at}: {suite}/{name} is listed twice (also cases[{first}]): its checks would count twice");
        }
        seen.push((suite, name));
        for (j, check) in checks.iter().enumerate() {
            let id = check["id"].as_str().unwrap_or("?");
            let row: CheckResult = serde_json::from_value(check.clone()).with_context(|| {
                format!("{at}.checks[{j}] ({suite}/{name} check {id}): not a check row")
            })?;
            tally.add(crate::definition::verdict::Verdict::of_check(&row));
        }
        // The report shows the case by its id.
        string(case, "id", &at)?;
    }
    Ok(Counts::from_tally(&tally))
}

/// `v[key]`, which must be an array (`at` names it in the message).
fn array<'a>(v: &'a Value, key: &str, at: &str) -> Result<&'a Vec<Value>> {
    match v.get(key) {
        None => bail!("{at}: missing (expected an array)"),
        Some(Value::Array(items)) => Ok(items),
        Some(other) => bail!("{at}: expected an array, found {}", json_kind(other)),
    }
}

/// `v[key]`, which must be a string.
fn string<'a>(v: &'a Value, key: &str, at: &str) -> Result<&'a str> {
    match v.get(key) {
        Some(Value::String(s)) => Ok(s),
        None => bail!("{at}.{key}: missing (expected a string)"),
        Some(other) => bail!("{at}.{key}: expected a string, found {}", json_kind(other)),
    }
}
