//! The report's file names and anchors made from suite and case names.

/// A file-name-safe form of a suite or case name (ASCII letters and digits, `-` for the rest).
pub(crate) fn slug(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect()
}
