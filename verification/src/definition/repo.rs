//! The repository the harness works in: where the cases, scenes and reference data are.

use std::path::{Path, PathBuf};

/// Paths of the repository the harness works in.
#[derive(Debug, Clone)]
pub struct Repo {
    pub root: PathBuf,
}

impl Repo {
    /// The workspace root: the folder holding `verification/cases` above `start`.
    pub fn find(start: &Path) -> Option<Repo> {
        let mut dir = Some(start);
        while let Some(d) = dir {
            if d.join("verification").join("cases").is_dir() {
                return Some(Repo {
                    root: d.to_path_buf(),
                });
            }
            dir = d.parent();
        }
        None
    }
    /// The repository of this crate (for tests and a binary run from anywhere in it).
    pub fn this() -> Repo {
        let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
        Repo {
            root: manifest.parent().unwrap_or(manifest).to_path_buf(),
        }
    }
    pub fn cases_dir(&self) -> PathBuf {
        self.root.join("verification").join("cases")
    }
}
