//! A history file as `impact simulate` writes it (and another code's adapter, and a
//! `--results-from` folder): a header naming each column with its unit, `time_s` first, then
//! rows of numbers. Read column by column for `impact diff` and `--baseline`, or as a
//! [`History`] for the checks; anything else is refused naming the file, and for a bad field
//! its line and column.

use std::path::Path;

use impact_solver::History;

/// (name, values) per column, `time_s` first. A refusal names the file and the row (the
/// line of the file: the header is row 1), and for a bad field its column's name and place.
pub fn read_columns(path: &Path) -> Result<Vec<(String, Vec<f64>)>, String> {
    let at = |line: u64, what: String| format!("{}: row {line}, {what}", path.display());
    let mut rd = csv::ReaderBuilder::new()
        .flexible(true)
        .from_path(path)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let names: Vec<String> = rd
        .headers()
        .map_err(|e| at(1, e.to_string()))?
        .iter()
        .map(|h| h.trim().to_string())
        .collect();
    if names.first().map(String::as_str) != Some("time_s") {
        let found = names.first();
        return Err(format!(
            "{}: the first column is not time_s (found {found:?}; the first column must be time_s)",
            path.display()
        ));
    }
    let mut cols: Vec<(String, Vec<f64>)> = names.into_iter().map(|n| (n, Vec::new())).collect();
    for (row, rec) in rd.records().enumerate() {
        let line = row as u64 + 2;
        let rec = rec.map_err(|e| at(line, e.to_string()))?;
        if rec.len() != cols.len() {
            let what = format!("{} fields where the header has {}", rec.len(), cols.len());
            return Err(at(line, what));
        }
        for (c, field) in rec.iter().enumerate() {
            let x = field.trim().parse::<f64>().map_err(|_| {
                let what = format!(
                    "column {}: {field:?} is not a number (field {} of the row)",
                    cols[c].0,
                    c + 1
                );
                at(line, what)
            })?;
            cols[c].1.push(x);
        }
    }
    if cols[0].1.is_empty() {
        return Err(format!("{}: no rows", path.display()));
    }
    Ok(cols)
}

/// The file as a [`History`] (row-major, as a run keeps it).
pub fn read_history(path: &Path) -> Result<History, String> {
    let cols = read_columns(path)?;
    let rows = cols[0].1.len();
    let values = (0..rows)
        .flat_map(|i| cols.iter().map(move |(_, v)| v[i]))
        .collect();
    let columns = cols.into_iter().map(|(name, _)| name).collect();
    Ok(History { columns, values })
}
