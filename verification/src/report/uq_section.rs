//! The report's uncertainty section (issue 27): the page `scripts/uq-study.py` writes with
//! `impact.uq` (`uq.md`: per study the declared inputs with their sources, one V&V 20 row per
//! comparison, the convergence of the estimates with bootstrap intervals, the Sobol' indices as
//! bar charts and the output CDFs; the rigid-plastic numbers per impact and coupling),
//! embedded as the benchmarks' page is: headings under the section, figures copied to
//! `plots/uq/` for report.md and inlined in index.html.

use std::path::Path;

use serde_json::{json, Value};

use crate::report::markdown::{embed, modified, Embed};

/// The command that writes the folder and its page.
pub const HOW: &str =
    ".venv/bin/python scripts/uq-study.py --out DIR (the main job: --out out/verification/uq)";

/// The page's file name in the study folder.
pub const PAGE: &str = "uq.md";

/// The report's section; the page's title repeats it and is dropped when embedded.
const SECTION: &str = "Uncertainty: V&V 20 budgets, Sobol' indices, rigid-plastic bounds";

/// The context of the uncertainty section from the folder `dir` (None: none found).
pub fn context(dir: Option<&Path>, out: &Path) -> Value {
    let Some(dir) = dir.filter(|d| d.is_dir()) else {
        return json!({"present": false, "how": HOW});
    };
    let path = dir.join(PAGE);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return json!({"present": false, "how": HOW, "dir": dir.display().to_string()});
    };
    let e = embed(
        &text,
        &Embed {
            base: dir,
            top_level: 3,
            anchor_prefix: "uq-",
            out,
            copy_to: "plots/uq",
            section_title: Some(SECTION),
        },
    );
    json!({
        "present": true, "dir": dir.display().to_string(), "how": HOW,
        "written": modified(&path).unwrap_or_else(|| "unknown".into()),
        "html": e.html, "md": e.md, "missing": e.missing,
    })
}
