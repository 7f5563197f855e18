//! Errors: bad input (with file, line, column, field, value and what is allowed) and run-time
//! failures (instability, the contact law's maximum), never panics.

use std::path::{Path, PathBuf};

use serde_saphyr::Spanned;

/// Where a value sits in a file, `file:line:column` (1-based line and column; line 0 = the
/// file only). Scenes and the harness's case files use this one type.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
pub struct SourceLocation {
    pub file: PathBuf,
    pub line: u64,
    pub column: u64,
}

impl std::fmt::Display for SourceLocation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line == 0 {
            write!(f, "{}", self.file.display())
        } else {
            write!(f, "{}:{}:{}", self.file.display(), self.line, self.column)
        }
    }
}

impl SourceLocation {
    /// A location naming only the file.
    pub fn file(path: &Path) -> SourceLocation {
        SourceLocation {
            file: path.to_path_buf(),
            line: 0,
            column: 0,
        }
    }

    /// Where the parser found `spanned` in `path`.
    pub fn of<T>(path: &Path, spanned: &Spanned<T>) -> SourceLocation {
        SourceLocation {
            file: path.to_path_buf(),
            line: spanned.referenced.line(),
            column: spanned.referenced.column(),
        }
    }
}

/// A scene value that parses but is not allowed.
#[derive(Debug, Clone, PartialEq)]
pub struct InvalidValue {
    pub location: SourceLocation,
    /// Dotted path of the field, e.g. `material.poisson_ratio`.
    pub field: String,
    /// The value as given.
    pub value: String,
    /// What is allowed, in words, with the unit.
    pub allowed: String,
}

#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error("{path}: cannot read the scene: {source}")]
    ReadScene {
        path: PathBuf,
        source: std::io::Error,
    },
    /// The YAML does not parse into a scene (syntax, unknown key, wrong type, missing field,
    /// duplicate key); the message of the YAML parser names the place.
    #[error("{location}: {message}")]
    ParseScene {
        location: SourceLocation,
        message: String,
    },
    #[error("{}: {} = {}: {}", .0.location, .0.field, .0.value, .0.allowed)]
    InvalidScene(Box<InvalidValue>),
    /// An override (`key = value` on the scene's dotted YAML path) the scene rules refuse;
    /// `message` is the rule's own (field, value, what is allowed).
    #[error("{}: override {key} = {value}: {message}", .file.display())]
    Override {
        file: PathBuf,
        key: String,
        value: String,
        message: String,
    },
    /// The run cannot go on (instability, contact law beyond its maximum, ...).
    #[error("run stopped at step {step} (t = {time_s:.6e} s): {what}")]
    Run {
        step: u64,
        time_s: f64,
        what: String,
    },
    /// Stopped by SIGINT/SIGTERM; `cleanup` says what was done with the outputs.
    #[error("interrupted at step {step} (t = {time_s:.6e} s){cleanup}")]
    Interrupted {
        step: u64,
        time_s: f64,
        cleanup: String,
    },
    /// The scene needs more memory than the machine has or the user allows.
    #[error("{scene}: {estimate}; {limit}")]
    TooLarge {
        scene: PathBuf,
        estimate: String,
        limit: String,
    },
    /// An output folder that writing into would harm the user's files.
    #[error("--out {path}: {why}")]
    OutputFolder { path: PathBuf, why: String },
    #[error("{path}: cannot write output: {source}")]
    WriteOutput {
        path: PathBuf,
        source: std::io::Error,
    },
}

impl Error {
    pub fn invalid(
        location: SourceLocation,
        field: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Error::InvalidScene(Box::new(InvalidValue {
            location,
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }))
    }

    pub fn write(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        Error::WriteOutput {
            path: path.into(),
            source,
        }
    }
}

pub type Result<T> = std::result::Result<T, Error>;

/// A number as a scene would write it, for messages: `7850`, `0.3`, `-1`, `1e300`, `1e-300`,
/// `NaN`, `inf` (never the hundreds of digits of `{}` for a very large or small value).
pub fn shown(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-3..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
