//! The report's "What changed" section: the page `what-changed.md` that `impact verify
//! --baseline` writes beside the results ([`crate::review::baseline`]), embedded with its
//! plots; absent without a baseline.

use std::path::Path;

use serde_json::Value;

use crate::report::markdown::{embed, Embed};

/// The section from `from/what-changed.md` (`present: false` without `--baseline`).
pub fn context(from: &Path, out: &Path) -> Value {
    let path = from.join("what-changed.md");
    let Ok(text) = std::fs::read_to_string(&path) else {
        return serde_json::json!({"present": false});
    };
    let e = embed(
        &text,
        &Embed {
            base: from,
            top_level: 3,
            anchor_prefix: "changed-",
            out,
            // The page's plots are `what-changed/X.svg` already: copied under a folder of
            // that name, each was written twice (`what-changed/what-changed/X.svg`).
            copy_to: "",
            section_title: None,
        },
    );
    serde_json::json!({"present": true, "html": e.html, "md": e.md})
}
