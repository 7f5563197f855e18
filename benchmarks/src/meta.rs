//! meta.json in the output folder: how each benchmark last ran there, so the report can say
//! when the numbers come from `--quick` sizes. Shape (keys only added, never renamed):
//! `{"quick": true, "benchmarks": {"work-precision": {"quick": true, "sizes": "meshes ..."},
//! "throughput": {"quick": true}, ...}}`; the top-level `quick` is true when any benchmark
//! recorded there ran at quick size.

use std::path::Path;

use serde_json::{json, Map, Value};

/// Records that benchmark `name` ran (at quick size or not, with the sizes it used when it
/// says them) in `out/meta.json`, keeping what other benchmarks recorded there.
pub fn record(out: &Path, name: &str, quick: bool, sizes: Option<&str>) -> anyhow::Result<()> {
    let path = out.join("meta.json");
    let mut meta: Map<String, Value> = std::fs::read_to_string(&path)
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok())
        .unwrap_or_default();
    let mut entry = json!({ "quick": quick });
    if let Some(s) = sizes {
        entry["sizes"] = json!(s);
    }
    let benchmarks = meta
        .entry("benchmarks")
        .or_insert_with(|| json!({}))
        .as_object_mut()
        .ok_or_else(|| anyhow::anyhow!("{}: \"benchmarks\" is not an object", path.display()))?;
    benchmarks.insert(name.to_string(), entry);
    let any_quick = benchmarks.values().any(|b| b["quick"] == json!(true));
    meta.insert("quick".into(), json!(any_quick));
    std::fs::write(&path, serde_json::to_string_pretty(&meta)? + "\n")?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::record;

    #[test]
    fn records_merge_and_quick_is_any() {
        let dir = std::env::temp_dir().join(format!("impact-bench-meta-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let _ = std::fs::remove_file(dir.join("meta.json"));
        record(&dir, "throughput", false, None).unwrap();
        record(&dir, "work-precision", true, Some("meshes 10x2")).unwrap();
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("meta.json")).unwrap()).unwrap();
        assert_eq!(v["quick"], true);
        assert_eq!(v["benchmarks"]["throughput"]["quick"], false);
        assert_eq!(v["benchmarks"]["work-precision"]["sizes"], "meshes 10x2");
        // A full re-run of work-precision: nothing quick is left.
        record(&dir, "work-precision", false, Some("meshes 80x16")).unwrap();
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("meta.json")).unwrap()).unwrap();
        assert_eq!(v["quick"], false);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
