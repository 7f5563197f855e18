//! Why a measure (or a reference read from a run) has no value: either the run did not write
//! what it reads, a history column, a summary key, the history or the summary itself (*not
//! produced*: on another code's row neither OK nor FAIL, issue 38; on `impact`'s rows a
//! FAIL like any other), or anything else (a scene that failed, a window without rows, a
//! malformed definition or reference file).

use std::fmt;

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MeasureError {
    /// The run did not write what the measure reads; the message names it.
    NotProduced(String),
    /// Any other reason the value cannot be had.
    Invalid(String),
}

impl MeasureError {
    pub fn is_not_produced(&self) -> bool {
        matches!(self, MeasureError::NotProduced(_))
    }

    /// The same kind of error, its message behind `prefix` (e.g. "reference: ").
    pub fn prefixed(self, prefix: &str) -> MeasureError {
        match self {
            MeasureError::NotProduced(m) => MeasureError::NotProduced(format!("{prefix}{m}")),
            MeasureError::Invalid(m) => MeasureError::Invalid(format!("{prefix}{m}")),
        }
    }
}

impl fmt::Display for MeasureError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MeasureError::NotProduced(m) | MeasureError::Invalid(m) => f.write_str(m),
        }
    }
}

impl From<String> for MeasureError {
    fn from(m: String) -> Self {
        MeasureError::Invalid(m)
    }
}

impl From<&str> for MeasureError {
    fn from(m: &str) -> Self {
        MeasureError::Invalid(m.to_string())
    }
}
