//! The rules of a reference of kind `other code` (issue 38): another production code's run,
//! made through its adapter (adapters/README.md) and stored under `reference-data/codes/<code>/`,
//! one folder per run with the adapter's `adapter.json` (the code, its version, the input it
//! ran). Such a reference names its `code` and reads a `json` value or a `history` column of
//! those files; nothing else (not a value typed in, not this run's metric) may stand for it.

use std::path::Path;

use crate::definition::case::{RefKind, ReferenceFile};

/// What is wrong with `r`'s use of kind `other code` and of `code` (empty when nothing is).
pub fn findings(root: &Path, r: &ReferenceFile) -> Vec<String> {
    let other = r.kind == Some(RefKind::OtherCode);
    let mut out = Vec::new();
    let Some(code) = r.code.as_deref() else {
        if other {
            out.push(
                "a reference of kind other code names its code (e.g. `code: calculix`)".into(),
            );
        }
        return out;
    };
    if !other {
        out.push(format!(
            "reference.code {code:?} is for kind other code only (this one is {})",
            r.kind.map_or("without a kind", |k| k.name())
        ));
        return out;
    }
    if r.value.is_some() || r.table.is_some() || r.metric.is_some() {
        out.push(format!(
            "a reference of kind other code reads {code}'s stored run (json or history), not a value, a table or this run's metric"
        ));
    }
    let files = r
        .json
        .iter()
        .map(|j| &j.file)
        .chain(r.history.iter().filter_map(|h| h.file.as_ref()));
    let mut any = false;
    for file in files {
        any = true;
        if let Err(m) = stored_run(root, code, Path::new(file)) {
            out.push(format!("reference file {file:?}: {m}"));
        }
    }
    if !any && r.pending.is_none() {
        out.push(format!(
            "a reference of kind other code reads a file of {code}'s stored run (json: {{file, key}} or history: {{file, column}})"
        ));
    }
    out
}

/// `file` lies in a folder of `reference-data/codes/<code>/` whose `adapter.json` says it is
/// `code`'s run.
fn stored_run(root: &Path, code: &str, file: &Path) -> Result<(), String> {
    let top = Path::new("reference-data/codes").join(code);
    let folder = file
        .parent()
        .filter(|d| d.starts_with(&top) && *d != top)
        .ok_or_else(|| format!("must lie in a run's folder under {}/", top.display()))?;
    let record = root.join(folder).join("adapter.json");
    let text = std::fs::read_to_string(&record).map_err(|e| {
        format!(
            "{}: {e} (the adapter's record of the run)",
            record.display()
        )
    })?;
    let json: serde_json::Value =
        serde_json::from_str(&text).map_err(|e| format!("{}: {e}", record.display()))?;
    match json.get("code").and_then(|c| c.as_str()) {
        Some(c) if c == code => Ok(()),
        other => Err(format!(
            "{} says the run is {:?}, not {code:?}'s",
            record.display(),
            other.unwrap_or("(no \"code\")")
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn reference(yaml: &str) -> ReferenceFile {
        serde_saphyr::from_str(yaml).unwrap()
    }

    /// A scratch repository with one stored run of `code` whose record says `says`.
    fn repo(code: &str, says: &str) -> std::path::PathBuf {
        static COUNT: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let k = COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let root = std::env::temp_dir().join(format!("other-code-ref-{}-{k}", std::process::id()));
        let run = root.join("reference-data/codes").join(code).join("bar");
        std::fs::create_dir_all(&run).unwrap();
        std::fs::write(
            run.join("adapter.json"),
            format!("{{\"code\": \"{says}\"}}"),
        )
        .unwrap();
        std::fs::write(run.join("summary.json"), "{\"impulse_Ns\": 1.0}").unwrap();
        root
    }

    #[test]
    fn an_other_code_reference_reads_the_stored_run_of_the_code_it_names() {
        let root = repo("calculix", "calculix");
        let ok = "{kind: other code, code: calculix, json: {file: reference-data/codes/calculix/bar/summary.json, key: impulse_Ns}, source: s}";
        assert!(findings(&root, &reference(ok)).is_empty());
        let cases = [
            // The code not named.
            ("{kind: other code, json: {file: reference-data/codes/calculix/bar/summary.json, key: impulse_Ns}, source: s}", "names its code"),
            // A code named under another kind.
            ("{kind: independent code, code: calculix, value: 1.0, source: s}", "for kind other code only"),
            // A value typed in for the other code's run.
            ("{kind: other code, code: calculix, value: 1.0, source: s}", "not a value"),
            // Another code's folder, or no run folder.
            ("{kind: other code, code: fake, json: {file: reference-data/codes/calculix/bar/summary.json, key: impulse_Ns}, source: s}", "must lie in a run's folder"),
            ("{kind: other code, code: calculix, json: {file: reference-data/independent/x/summary.json, key: impulse_Ns}, source: s}", "must lie in a run's folder"),
        ];
        for (yaml, says) in cases {
            let f = findings(&root, &reference(yaml));
            assert!(f.iter().any(|m| m.contains(says)), "{yaml}: {f:?}");
        }
        // A folder whose record is another code's.
        let root = repo("calculix", "impact");
        let f = findings(&root, &reference(ok));
        assert!(f.iter().any(|m| m.contains("not \"calculix\"'s")), "{f:?}");
    }
}
