//! A CSV file the benchmarks wrote, read back for their page (benchmarks.md): a header and
//! rows of text. `common::write_csv` quotes a value that holds a comma; a folder written
//! before it did (unquoted free-text "note" columns) still reads: extra fields of a row are
//! joined back into its last column.

use std::path::Path;

use crate::common::markdown_table;

#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// Reads `path`; an empty file or a header without columns is an error naming the file.
    pub fn read(path: &Path) -> anyhow::Result<Table> {
        let named = |e: &dyn std::fmt::Display| anyhow::anyhow!("{}: {e}", path.display());
        let mut records = csv::ReaderBuilder::new()
            .has_headers(false)
            .flexible(true)
            .from_path(path)
            .map_err(|e| named(&e))?
            .into_records();
        let header: Vec<String> = match records.next() {
            Some(h) => h
                .map_err(|e| named(&e))?
                .iter()
                .map(str::to_string)
                .collect(),
            None => Vec::new(),
        };
        if header.iter().all(|h| h.trim().is_empty()) {
            return Err(named(&"no header"));
        }
        let n = header.len();
        let mut rows = Vec::new();
        for record in records {
            let fields: Vec<&str> = record.as_ref().map_err(|e| named(e))?.iter().collect();
            let mut row: Vec<String> = fields.iter().take(n).map(|f| f.to_string()).collect();
            if fields.len() > n {
                row[n - 1] = fields[n - 1..].join(",");
            }
            row.resize(n, String::new());
            rows.push(row);
        }
        Ok(Table { header, rows })
    }

    /// The index of column `name`.
    pub fn col(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// Column `name` of row `r` ("" when the table has no such column).
    pub fn get<'a>(&self, r: &'a [String], name: &str) -> &'a str {
        self.col(name)
            .and_then(|i| r.get(i))
            .map_or("", String::as_str)
    }

    /// The table in Markdown.
    pub fn markdown(&self) -> String {
        markdown_table(&self.header, &self.rows)
    }
}

/// A cell as a number (NaN when it is none).
pub fn num(s: &str) -> f64 {
    s.trim().parse().unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unquoted_commas_go_back_into_the_last_column() {
        let dir = std::env::temp_dir().join(format!("impact-bench-csv-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("s.csv");
        std::fs::write(
            &p,
            "mesh,status,note\nuniform,stopped,step 96: element 20 (x = 1, y = 2) | inverted\nshort\n",
        )
        .unwrap();
        let t = Table::read(&p).unwrap();
        assert_eq!(
            t.rows[0][2],
            "step 96: element 20 (x = 1, y = 2) | inverted"
        );
        assert_eq!(t.rows[1], ["short", "", ""]);
        assert!(
            t.markdown().contains("y = 2) \\| inverted |"),
            "{}",
            t.markdown()
        );
        // Written by write_csv: a note with a comma and a quote is quoted and comes back whole.
        let note = "step 96: element 20 (x = 1, y = 2), \"inverted\"";
        crate::common::write_csv(
            &p,
            &["mesh", "note"],
            &[vec!["uniform".into(), note.into()]],
        )
        .unwrap();
        assert!(std::fs::read_to_string(&p).unwrap().contains("\"step 96"));
        assert_eq!(Table::read(&p).unwrap().rows, [["uniform", note]]);
        std::fs::write(&p, "").unwrap();
        assert!(Table::read(&p)
            .unwrap_err()
            .to_string()
            .contains("s.csv: no header"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
