//! The benchmarks' page (benchmarks.md) on a fixture folder shaped like `impact-bench all
//! --out DIR` writes it (numbers made up): every CSV is named with its content, the Pareto
//! fronts and the sorted table are those of the rows, the targets say met or missed, the plots
//! it links exist, and what is missing is said with the command that writes it.

use std::path::{Path, PathBuf};

use crate::page;

fn fixture(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("impact-bench-page-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    let w = |f: &str, text: &str| std::fs::write(d.join(f), text).unwrap();
    // impact-fixture: five configurations, two dominated; meshes that sort wrong as text.
    w(
        "work-precision.csv",
        "problem,element,mesh,cfl,dt_s,error,setup_s,loop_s\n\
         pulse-fixture,q4-sri,20x4,0.9,6.0e-7,2.0e-2,1.0e-5,2.0e-2\n\
         impact-fixture,q4-sri,160x32,0.9,1.0e-7,1.0e-4,1.0e-4,9.0e0\n\
         impact-fixture,q4-sri,20x4,0.9,6.0e-7,2.0e-3,1.0e-5,2.0e-2\n\
         impact-fixture,q4-full,20x4,0.9,6.0e-7,4.0e-2,1.0e-5,3.0e-2\n\
         impact-fixture,q4-sri,10x2,0.3,4.0e-7,9.0e-3,1.0e-5,4.0e-2\n\
         impact-fixture,q4-1pt,10x2,0.9,1.2e-6,1.0e-1,1.0e-6,1.0e-3\n\
         pulse-fixture,q4-sri,10x2,0.9,1.2e-6,1.0e-1,1.0e-6,2.0e-3\n",
    );
    for p in ["impact-fixture", "pulse-fixture"] {
        w(
            &format!("work-precision-{p}.svg"),
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20\" height=\"10\"></svg>\n",
        );
    }
    w("work-precision-references.csv", "problem,reference,estimated_reference_error\nimpact-fixture,q4-sri 320x64 cfl 0.3,1.0e-5\n");
    w("throughput-kernels.csv", "element,material,ns_per_element_step,element_steps_per_s,target_ns,status\nq4-sri,elastic,25.0,4.0e7,<= 30.0,met\nq4-1pt,elastic,26.0,3.8e7,<= 15.0,missed\nq4-full,elastic,30.0,3.3e7,-,-\n");
    w("throughput-runs.csv", "run,setup_s,loop_s,steps,ns_per_element_step,target,status\ntable1-elastic,0.0001,0.40,21364,15.0,-,-\ntable1-elasto-plastic,0.0001,0.42,21364,15.4,< 0.5 s,met\n");
    w("throughput-python.csv", "scene,rust_s,python_solver_s,python_process_s,python_over_rust,impulse_rel_diff,note\ntable1-elastic,0.400,12.000,13.100,30.0,1.0e-6,same scene file, same element, mesh and dt\n");
    w("stability-cfl.csv", "mesh,material,cfl,status,max_balance_error,impulse_error,note\nuniform,elastic,1.2,stopped,NaN,NaN,step 96: element 20 (x = 1, y = 2) has inverted\n");
    w("stability-extreme.csv", "case,status,max_balance_error,impulse_error,note\nmass 0.01 kg,coarse,1.8e-2,0.0e0,5341 steps\n");
    w("stability.md", "## CFL sweep (fixture)\n\n| mesh | status |\n|---|---|\n| uniform | stopped |\n\n## Measured critical ratio (fixture)\n\n| mesh | critical cfl |\n|---|---|\n| uniform | 1.150 .. 1.160 |\n");
    d
}

fn written(dir: &Path) -> String {
    let p = page::write(dir).unwrap();
    assert_eq!(p, dir.join("benchmarks.md"));
    std::fs::read_to_string(p).unwrap()
}

#[test]
fn the_page_shows_every_file_of_the_folder() {
    let dir = fixture("all");
    crate::meta::record(&dir, "work-precision", true, Some("meshes 10x2, 20x4")).unwrap();
    let md = written(&dir);
    assert!(md.starts_with("# Performance: work-precision, throughput, stability\n"));
    // Every CSV's content with its file named, and the stability page one level down.
    for headline in [
        "## Work-precision: run time against error",
        "(work-precision-references.csv)",
        "All 7 configurations (work-precision.csv)",
        "## Throughput",
        "throughput-kernels.csv):",
        "(throughput-runs.csv)",
        "(throughput-python.csv",
        "## Stability",
        "stability-cfl.csv",
        "stability-extreme.csv",
        "### CFL sweep (fixture)\n",
        "### Measured critical ratio (fixture)\n",
        "| uniform | 1.150 .. 1.160 |",
    ] {
        assert!(md.contains(headline), "{headline} missing:\n{md}");
    }
    assert!(!md.contains("Not in this folder"), "{md}");
    // Machine and sizes from meta.json, and the quick note.
    assert!(
        md.contains("**Machine:** ") && md.contains(" cores, "),
        "{md}"
    );
    assert!(md.contains("| work-precision | 20"), "{md}");
    assert!(
        md.contains("**Note:** benchmarks ran at quick size (work-precision: meshes 10x2, 20x4); ")
    );
    // Targets: two kernels and the elasto-plastic run; one missed.
    assert!(md.contains("**Targets** (speed): 2 of 3 met."), "{md}");
    assert!(
        md.contains("| kernel q4-1pt elastic | 26.0 ns per element-step | <= 15.0 ns | missed |")
    );
    assert!(
        md.contains("| whole run table1-elasto-plastic | 0.420 s (setup + loop) | < 0.5 s | met |")
    );
    // Unquoted commas of the Python note stay in its last column.
    assert!(md.contains("| 30.0 | 1.0e-6 | same scene file, same element, mesh and dt |"));
    // Each linked plot is in the folder.
    for p in ["impact-fixture", "pulse-fixture"] {
        let link = format!("![work-precision {p}](work-precision-{p}.svg)");
        assert!(md.contains(&link), "{link}");
        assert!(dir.join(format!("work-precision-{p}.svg")).is_file());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn pareto_fronts_and_the_sorted_table() {
    let dir = fixture("front");
    let md = written(&dir);
    // q4-full 20x4 and q4-sri 10x2 cfl 0.3 are slower and worse than q4-sri 20x4: off the
    // front; three are on it, fastest first.
    assert!(md.contains("Pareto front: 3 of 5 configurations"), "{md}");
    let front = "| q4-1pt | 10x2 | 0.9 | 1.2e-6 | 1.0e-1 | 1.0e-6 | 1.0e-3 | 1.0010e-3 |\n\
                 | q4-sri | 20x4 | 0.9 | 6.0e-7 | 2.0e-3 | 1.0e-5 | 2.0e-2 | 2.0010e-2 |\n\
                 | q4-sri | 160x32 | 0.9 | 1.0e-7 | 1.0e-4 | 1.0e-4 | 9.0e0 | 9.0001e0 |\n";
    assert!(md.contains(front), "{md}");
    assert!(md.contains("Pareto front: 2 of 2 configurations"));
    // The whole table: problem, element, cfl, mesh (by size: 20x4 before 160x32).
    let order = [
        "| impact-fixture | q4-1pt | 10x2 | 0.9 | 1.2e-6 | 1.0e-1 | 1.0e-6 | 1.0e-3 | front |",
        "| impact-fixture | q4-full | 20x4 | 0.9 | 6.0e-7 | 4.0e-2 | 1.0e-5 | 3.0e-2 |  |",
        "| impact-fixture | q4-sri | 10x2 | 0.3 |",
        "| impact-fixture | q4-sri | 20x4 | 0.9 |",
        "| impact-fixture | q4-sri | 160x32 | 0.9 |",
        "| pulse-fixture | q4-sri | 10x2 |",
        "| pulse-fixture | q4-sri | 20x4 |",
    ];
    let at: Vec<usize> = order
        .iter()
        .map(|r| md.find(r).unwrap_or_else(|| panic!("{r} missing:\n{md}")))
        .collect();
    assert!(at.windows(2).all(|w| w[0] < w[1]), "sorted: {at:?}");
    assert!(
        md.contains("7 configurations: elements q4-1pt, q4-full, q4-sri; meshes 10x2, 20x4, 160x32; CFL fractions 0.3, 0.9."),
        "{md}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn what_is_missing_is_said_with_its_command() {
    let dir = fixture("missing");
    for f in [
        "work-precision.csv",
        "throughput-runs.csv",
        "stability.md",
        "work-precision-pulse-fixture.svg",
    ] {
        std::fs::remove_file(dir.join(f)).unwrap();
    }
    std::fs::write(dir.join("throughput-python.csv"), "").unwrap();
    let md = written(&dir);
    assert!(md.contains("**Not in this folder:** `work-precision.csv` (`impact-bench work-precision --out DIR`); `throughput-runs.csv` (`impact-bench throughput --out DIR`); `stability.md` (`impact-bench stability --out DIR`)."), "{md}");
    assert!(
        md.contains("**Unreadable:** ") && md.contains("throughput-python.csv: no header"),
        "{md}"
    );
    assert!(md.contains("**Machine:** not recorded (no meta.json)."));
    // The plot that is left is shown; no front is invented without the table.
    assert!(md.contains("![work-precision impact-fixture](work-precision-impact-fixture.svg)"));
    assert!(
        !md.contains("pulse-fixture") && !md.contains("Pareto front:"),
        "{md}"
    );
    assert!(!dir
        .read_dir()
        .unwrap()
        .flatten()
        .any(|e| e.file_name().to_string_lossy().contains("partial")));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_threads_table_is_shown_when_measured_and_its_command_when_not() {
    let dir = fixture("threads");
    let md = written(&dir);
    // `all` does not write threads.csv: the section says how to make it, nothing is "missing".
    assert!(md.contains("## Threads on a busy machine\n"), "{md}");
    assert!(md.contains("not measured in this folder (`impact-bench threads --out DIR`"));
    assert!(!md.contains("Not in this folder"), "{md}");
    std::fs::write(
        dir.join("threads.csv"),
        "load,load_average_1min_before,run,threads,runs,min_wall_s,median_wall_s,min_over_one_thread,runs_that_fell_back,target,status\nbusy: 1 spinning process(es),0.50,default,2,5,0.612,0.650,1.02,5,<= 1.1 x one-thread,met\n",
    )
    .unwrap();
    let md = written(&dir);
    assert!(md.contains("(threads.csv):\n\n| load |"), "{md}");
    assert!(md.contains("| busy: 1 spinning process(es) | 0.50 | default | 2 | 5 | 0.612 |"));
    assert!(!md.contains("not measured in this folder"));
    let _ = std::fs::remove_dir_all(&dir);
}
