//! Two numeric columns of a CSV file (a history's `time_s` and one of its columns, a digitised
//! profile's heights and radii), every error naming the file.

use std::path::Path;

/// A history file's `time_s` and `name` columns ([`read_csv_pair`]).
pub fn read_csv_columns(path: &Path, name: &str) -> Result<(Vec<f64>, Vec<f64>), String> {
    read_csv_pair(path, "time_s", name)
}

/// Two numeric columns of a CSV file, `x` and `y`, row by row; every error names the file.
pub fn read_csv_pair(path: &Path, x: &str, y: &str) -> Result<(Vec<f64>, Vec<f64>), String> {
    let shown = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
    let mut rd = csv::Reader::from_path(path).map_err(|e| shown(&e))?;
    let headers = rd.headers().map_err(|e| shown(&e))?.clone();
    let xi = headers
        .iter()
        .position(|h| h == x)
        .ok_or_else(|| shown(&format!("no {x} column")))?;
    let yi = headers
        .iter()
        .position(|h| h == y)
        .ok_or_else(|| shown(&format!("no column {y:?}")))?;
    let (mut xs, mut ys) = (Vec::new(), Vec::new());
    for rec in rd.records() {
        let rec = rec.map_err(|e| shown(&e))?;
        let p = |i: usize| {
            rec.get(i)
                .unwrap_or("")
                .trim()
                .parse::<f64>()
                .map_err(|e| shown(&e))
        };
        xs.push(p(xi)?);
        ys.push(p(yi)?);
    }
    Ok((xs, ys))
}
