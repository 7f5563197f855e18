//! A study's outputs: per scene each declared output (a summary key) with its kind and its
//! reference cell, the cell's row taken from the output (one scene) or from the scene
//! (several) and checked to hold a number in its table.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Serialize;
use serde_saphyr::Spanned;

use crate::definition::case::Loc;
use crate::uq::declaration::{invalid, OutputFile, TableRefFile};
use crate::uq::scenes::{SceneDecl, StudyScene};

/// A cell of a reference table (file relative to the repository, row by its first column).
#[derive(Debug, Clone, Serialize)]
pub struct TableRef {
    pub file: String,
    pub row: String,
    pub column: String,
}

/// One compared quantity: an output of one scene, with its reference cell.
#[derive(Debug, Clone, Serialize)]
pub struct Output {
    /// Unique in the study: the key, and `key [scene label]` in a study of several scenes.
    pub id: String,
    /// The summary key (dotted for nested ones).
    pub key: String,
    /// Index into `Study::scenes`.
    pub scene: usize,
    pub table: Option<TableRef>,
    pub scale: Option<f64>,
    /// calibration | paper | none
    pub kind: String,
    pub label: String,
}

/// The outputs per scene, each table reference resolved to its row and checked in its file.
/// `declared`: the outputs and the file that declares them (the study's, or its base's);
/// `path`: the study's file.
pub(super) fn outputs(
    declared: (&BTreeMap<String, Spanned<OutputFile>>, &Path),
    several: bool,
    decls: &[SceneDecl],
    scenes: &[StudyScene],
    path: &Path,
) -> Result<Vec<Output>, String> {
    let (declared, from) = declared;
    let mut out = Vec::new();
    for (i, (d, s)) in decls.iter().zip(scenes).enumerate() {
        for (key, o) in declared {
            let loc = Loc::of(from, o);
            let kind = o.value.kind.as_deref().unwrap_or("none");
            if !matches!(kind, "calibration" | "paper" | "none") {
                let field = format!("outputs.{key}.kind");
                return Err(invalid(
                    &loc,
                    &field,
                    kind,
                    "must be calibration, paper or none",
                ));
            }
            let table = match &o.value.table {
                Some(t) => Some(table_ref(t, key, d, &loc, several, path)?),
                None => None,
            };
            let label = o.value.label.clone().unwrap_or_else(|| key.clone());
            let (id, label) = if several {
                (
                    format!("{key} [{}]", s.label),
                    format!("{label}, {}", s.label),
                )
            } else {
                (key.clone(), label)
            };
            out.push(Output {
                id,
                key: key.clone(),
                scene: i,
                table,
                scale: o.value.scale,
                kind: kind.to_string(),
                label,
            });
        }
    }
    Ok(out)
}

/// The table cell of one output of one scene: its row from the output (one scene) or from
/// the scene (several), and the cell must hold a number.
fn table_ref(
    t: &TableRefFile,
    key: &str,
    d: &SceneDecl,
    loc: &Loc,
    several: bool,
    path: &Path,
) -> Result<TableRef, String> {
    // the row and where it is written (on the output, or on the scene of a study of several)
    let (row, at) = match (several, &t.row, d.row) {
        (false, Some(r), _) => (r.clone(), format!("{loc}: outputs.{key}.table.row")),
        (false, None, _) => {
            return Err(format!("{loc}: outputs.{key}.table.row: missing: the row of {} (its first column's text)", t.file))
        }
        (true, Some(r), _) => {
            return Err(invalid(loc, &format!("outputs.{key}.table.row"), r, "must be left out in a study of several scenes: each scene gives its row (scenes[i].row)"))
        }
        (true, None, Some(r)) => (r.to_string(), format!("{}: {}.row", Loc::of(path, d.file), d.field)),
        (true, None, None) => {
            let at = Loc::of(path, d.file);
            return Err(format!("{at}: {}.row: missing: the row of {} for this scene (outputs.{key} has a table)", d.field, t.file));
        }
    };
    let Some(root) = path.canonicalize().ok().and_then(|p| {
        p.ancestors()
            .find(|a| a.join("reference-data").is_dir())
            .map(Path::to_path_buf)
    }) else {
        return Err(format!(
            "{loc}: outputs.{key}.table.file: no folder reference-data above the study"
        ));
    };
    let csv = root.join(&t.file);
    let first = first_column(&csv).map_err(|e| format!("{loc}: outputs.{key}.table: {e}"))?;
    let at_row = BTreeMap::from([(first, row.clone())]);
    crate::definition::check::table_value(&csv, &at_row, &t.column)
        .map_err(|e| format!("{at} = {row} (outputs.{key}): {e}"))?;
    Ok(TableRef {
        file: t.file.clone(),
        row,
        column: t.column.clone(),
    })
}

/// The name of a CSV file's first column.
fn first_column(path: &Path) -> Result<String, String> {
    let mut rd = csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let headers = rd
        .headers()
        .map_err(|e| format!("{}: {e}", path.display()))?;
    headers
        .get(0)
        .map(str::to_string)
        .ok_or_else(|| format!("{}: no columns", path.display()))
}
