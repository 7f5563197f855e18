//! Measurements a validation case holds and does not compare (issue 40, section 3: "where the
//! model misses, show it and say why"). A case lists rows of a measurement table (shots) under
//! `not_compared`, each group with why it is left out: a run the solver cannot finish (an
//! element inverts), a material with no constants fitted to other tests, a comparison that
//! could not fail for a wrong model. The report shows them beside the comparisons
//! (`crate::report::validation_section`), and the lint keeps the account whole: every row of a
//! table that the validation cases read is compared by a check or declared here, never both,
//! so a shot cannot drop out of the report unseen.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::definition::case::{Case, Loc, NotComparedFile, RefKind};

/// One row left out, as results.json carries it.
#[derive(Debug, Clone, Serialize)]
pub struct NotComparedRow {
    /// The table, from the repository root.
    pub file: String,
    /// The row's key column and value.
    pub key: String,
    pub row: String,
    pub why: String,
    /// The row's cells as written, by column (SI units, as the table's header names them).
    pub cells: BTreeMap<String, String>,
}

/// A CSV table as written: its header and records.
struct Table {
    headers: Vec<String>,
    records: Vec<Vec<String>>,
}

impl Table {
    fn read(path: &Path) -> Result<Table, String> {
        let mut rd =
            csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let headers = rd
            .headers()
            .map_err(|e| format!("{}: {e}", path.display()))?
            .iter()
            .map(str::to_string)
            .collect();
        let records = rd
            .records()
            .map(|r| {
                r.map(|r| r.iter().map(|c| c.trim().to_string()).collect())
                    .map_err(|e| format!("{}: {e}", path.display()))
            })
            .collect::<Result<_, _>>()?;
        Ok(Table { headers, records })
    }

    /// The values of column `key`, in the table's order.
    fn keys(&self, path: &Path, key: &str) -> Result<Vec<&str>, String> {
        let i = self
            .headers
            .iter()
            .position(|h| h == key)
            .ok_or_else(|| format!("{}: no column {key:?}", path.display()))?;
        Ok(self
            .records
            .iter()
            .map(|r| r.get(i).map_or("", String::as_str))
            .collect())
    }
}

/// The rows `entry` declares, with their cells; `Err` names a table, column or row that does
/// not exist.
pub fn rows(root: &Path, entry: &NotComparedFile) -> Result<Vec<NotComparedRow>, String> {
    let path = root.join(&entry.file);
    let table = Table::read(&path)?;
    let keys = table.keys(&path, &entry.key)?;
    entry
        .rows
        .iter()
        .map(|row| {
            let at = keys.iter().position(|k| k == row).ok_or_else(|| {
                format!("{}: no row with {} = {row:?}", path.display(), entry.key)
            })?;
            Ok(NotComparedRow {
                file: entry.file.clone(),
                key: entry.key.clone(),
                row: row.clone(),
                why: entry.why.clone(),
                cells: table
                    .headers
                    .iter()
                    .cloned()
                    .zip(table.records[at].iter().cloned())
                    .collect(),
            })
        })
        .collect()
}

/// A table row by file, key column and key value.
type RowId = (String, String, String);

/// The rows the cases' checks against a measurement read (`reference.table` with a one-column
/// `row`), each with the first check's location.
fn compared(cases: &[Case]) -> BTreeMap<RowId, Loc> {
    let mut out = BTreeMap::new();
    for case in cases {
        for c in &case.file.checks {
            let Some(r) = &c.value.reference else {
                continue;
            };
            let (Some(RefKind::Experiment), Some(t)) = (r.value.kind, &r.value.table) else {
                continue;
            };
            if let [(key, row)] = t.row.iter().collect::<Vec<_>>()[..] {
                out.entry((t.file.clone(), key.clone(), row.clone()))
                    .or_insert_with(|| case.loc(c));
            }
        }
    }
    out
}

/// The lint's rules for `not_compared` (module documentation), each finding with where it is:
/// each entry names rows that exist and says why; no row is declared twice or both declared
/// and compared; every row of a table the validation cases read is one or the other (that
/// finding is the first reading case's, which then shows as a broken case).
pub fn findings(root: &Path, cases: &[Case]) -> Vec<(Loc, String)> {
    let compared = compared(cases);
    let mut out = Vec::new();
    let mut declared: BTreeMap<RowId, Loc> = BTreeMap::new();
    // Per table: its key column and the first case that reads it.
    let mut tables: BTreeMap<String, (String, PathBuf)> = BTreeMap::new();
    for ((file, key, _), loc) in &compared {
        tables
            .entry(file.clone())
            .or_insert_with(|| (key.clone(), loc.file.clone()));
    }
    for case in cases {
        for entry in &case.file.not_compared {
            let loc = case.loc(entry);
            let mut say =
                |message: String| out.push((loc.clone(), format!("not_compared: {message}")));
            let e = &entry.value;
            if e.why.trim().is_empty() || e.rows.is_empty() {
                say(
                    "each entry names at least one row and says why it is left out (why: ...)"
                        .into(),
                );
            }
            if let Err(m) = rows(root, e) {
                say(m);
                continue;
            }
            tables
                .entry(e.file.clone())
                .or_insert_with(|| (e.key.clone(), case.path.clone()));
            for row in &e.rows {
                let id = (e.file.clone(), e.key.clone(), row.clone());
                if let Some(check) = compared.get(&id) {
                    say(format!(
                        "{} = {row} is compared by the check at {check}: a row is compared or left out, not both",
                        e.key
                    ));
                }
                if let Some(first) = declared.insert(id, loc.clone()) {
                    say(format!("{} = {row} is declared already at {first}", e.key));
                }
            }
        }
    }
    out.extend(unaccounted(root, &tables, &compared, &declared));
    out
}

/// Every row of each table read that no check compares and no case declares.
fn unaccounted(
    root: &Path,
    tables: &BTreeMap<String, (String, PathBuf)>,
    compared: &BTreeMap<RowId, Loc>,
    declared: &BTreeMap<RowId, Loc>,
) -> Vec<(Loc, String)> {
    let mut out = Vec::new();
    for (file, (key, first_reader)) in tables {
        let path = root.join(file);
        let Ok(table) = Table::read(&path) else {
            continue; // the check's own reference or the entry names the unreadable table
        };
        let Ok(keys) = table.keys(&path, key) else {
            continue;
        };
        // In the table's order.
        let missing: Vec<&str> = keys
            .into_iter()
            .filter(|k| {
                let id = (file.clone(), key.clone(), k.to_string());
                !compared.contains_key(&id) && !declared.contains_key(&id)
            })
            .collect();
        if !missing.is_empty() {
            out.push((
                Loc::file(first_reader),
                format!(
                    "{file}: {} row(s) neither compared by a check nor declared under a case's not_compared (with why): {} = {}",
                    missing.len(),
                    key,
                    missing.join(", ")
                ),
            ));
        }
    }
    out
}
