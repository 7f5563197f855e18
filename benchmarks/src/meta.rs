//! meta.json in the output folder: how and where each benchmark last ran there, so the page
//! (benchmarks.md) can say when the numbers come from `--quick` sizes and on what machine.
//! Shape (keys only added, never renamed): `{"quick": true, "machine": "linux x86_64, 2
//! cores, CPU", "benchmarks": {"work-precision": {"quick": true, "sizes": "meshes ...",
//! "date_utc": "2026-11-23T06:00:00Z"}, "throughput": {"quick": true, ...}, ...}}`; the
//! top-level `quick` is true when any benchmark recorded there ran at quick size, `machine` is
//! that of the last run.

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
    let mut entry = json!({ "quick": quick, "date_utc": now_utc() });
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
    meta.insert("machine".into(), json!(machine()));
    std::fs::write(&path, serde_json::to_string_pretty(&meta)? + "\n")?;
    Ok(())
}

/// "linux x86_64, 2 cores, <CPU model>" of this machine.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            let line = t.lines().find(|l| l.starts_with("model name"))?;
            Some(line.split(':').nth(1)?.trim().to_string())
        })
        .unwrap_or_else(|| "CPU unknown".into());
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    format!(
        "{} {}, {cores} cores, {cpu}",
        std::env::consts::OS,
        std::env::consts::ARCH
    )
}

/// The time now, UTC, as 2026-11-23T06:00:00Z (from `date -u`; "unknown" without it).
fn now_utc() -> String {
    std::process::Command::new("date")
        .args(["-u", "+%Y-%m-%dT%H:%M:%SZ"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".into())
}

/// The benchmarks recorded in `dir`'s meta.json: (name, quick, sizes, date), in the page's
/// order (work-precision, throughput, stability, then any other), and the machine. Empty
/// without a readable meta.json (folders from before it existed).
pub fn read(dir: &Path) -> (Vec<Ran>, Option<String>) {
    let Some(meta) = std::fs::read_to_string(dir.join("meta.json"))
        .ok()
        .and_then(|t| serde_json::from_str::<Value>(&t).ok())
    else {
        return (Vec::new(), None);
    };
    let rank = |n: &str| ORDER.iter().position(|&k| k == n).unwrap_or(ORDER.len());
    let mut ran: Vec<Ran> = meta["benchmarks"]
        .as_object()
        .into_iter()
        .flatten()
        .map(|(name, b)| Ran {
            name: name.clone(),
            quick: b["quick"] == json!(true),
            sizes: b["sizes"].as_str().map(str::to_string),
            date_utc: b["date_utc"].as_str().map(str::to_string),
        })
        .collect();
    ran.sort_by_key(|r| (rank(&r.name), r.name.clone()));
    (ran, meta["machine"].as_str().map(str::to_string))
}

/// The benchmarks in the page's order.
pub const ORDER: [&str; 3] = ["work-precision", "throughput", "stability"];

/// How one benchmark last ran in a folder.
pub struct Ran {
    pub name: String,
    pub quick: bool,
    /// The sizes it says it used (work-precision: meshes, CFL fractions, repeats).
    pub sizes: Option<String>,
    pub date_utc: Option<String>,
}

/// "benchmarks ran at quick size (work-precision: meshes ...; throughput; stability); ..."
/// when any recorded benchmark ran with `--quick`, else None.
pub fn quick_note(ran: &[Ran]) -> Option<String> {
    let quick: Vec<String> = ran
        .iter()
        .filter(|r| r.quick)
        .map(|r| match &r.sizes {
            Some(sizes) => format!("{}: {sizes}", r.name),
            None => r.name.clone(),
        })
        .collect();
    (!quick.is_empty()).then(|| {
        format!(
            "benchmarks ran at quick size ({}); their times and errors are those of the small CI runs, not of the default sizes",
            quick.join("; ")
        )
    })
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
        assert!(v["machine"].as_str().unwrap().contains("cores"));
        // Read back in the page's order; no note without a quick run, then one naming it.
        let (ran, machine) = super::read(&dir);
        let names: Vec<&str> = ran.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["work-precision", "throughput"]);
        assert!(machine.is_some() && ran[0].date_utc.is_some());
        assert_eq!(super::quick_note(&ran), None);
        record(&dir, "stability", true, None).unwrap();
        let note = super::quick_note(&super::read(&dir).0).unwrap();
        assert!(
            note.starts_with("benchmarks ran at quick size (stability); "),
            "{note}"
        );
        let _ = std::fs::remove_dir_all(&dir);
    }
}
