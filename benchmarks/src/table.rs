//! A CSV file the benchmarks wrote, read back for their page (benchmarks.md): a header and
//! rows of text. The benchmarks write their CSVs unquoted (`common::write_csv`), and a
//! free-text last column ("note") may hold commas: extra fields are joined back into the last.

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
        let text = std::fs::read_to_string(path)
            .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
        let mut lines = text.lines();
        let header: Vec<String> = lines
            .next()
            .filter(|h| !h.trim().is_empty())
            .ok_or_else(|| anyhow::anyhow!("{}: no header", path.display()))?
            .split(',')
            .map(str::to_string)
            .collect();
        let n = header.len();
        let rows = lines
            .filter(|l| !l.is_empty())
            .map(|l| {
                let mut row: Vec<String> = l.splitn(n, ',').map(str::to_string).collect();
                row.resize(n, String::new());
                row
            })
            .collect();
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
        std::fs::write(&p, "").unwrap();
        assert!(Table::read(&p)
            .unwrap_err()
            .to_string()
            .contains("s.csv: no header"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
