//! Small fixtures for the report tests: a benchmarks folder shaped like `impact-bench all
//! --out DIR` writes it, and a reconstruction page shaped like `scripts/reconstruction/reconstruct.py`'s
//! report.md. Made up for the tests (numbers included): never read from the real folders.

#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// A fresh, empty folder under the temp dir.
pub fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("impact-report-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn svg(title: &str) -> String {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<!-- fixture -->\n<svg width=\"200\" height=\"100\" viewBox=\"0 0 200 100\" xmlns=\"http://www.w3.org/2000/svg\">\n<rect x=\"0\" y=\"0\" width=\"200\" height=\"100\" fill=\"#FFFFFF\"/>\n<text x=\"10\" y=\"50\">{title}</text>\n<polyline fill=\"none\" stroke=\"#0000FF\" points=\"10,90 100,40 190,10\"/>\n</svg>\n"
    )
}

/// Problems: `impact-fixture` (five configurations, two dominated, meshes that sort wrong as
/// text) and `pulse-fixture` (two). The stability CSV notes hold unquoted commas, as the real
/// ones do.
pub fn write_benchmarks(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    let w = |name: &str, text: &str| std::fs::write(dir.join(name), text).unwrap();
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
    w(
        "work-precision-impact-fixture.svg",
        &svg("impact-fixture plot"),
    );
    w(
        "work-precision-pulse-fixture.svg",
        &svg("pulse-fixture plot"),
    );
    w("work-precision-references.csv", "problem,reference,estimated_reference_error\nimpact-fixture,q4-sri 320x64 cfl 0.3,1.0e-5\npulse-fixture,q4-sri 40x8 cfl 0.3,3.0e-3\n");
    w(
        "throughput-kernels.csv",
        "element,material,ns_per_element_step,element_steps_per_s,target_ns,status\nq4-sri,elastic,25.0,4.0e7,<= 30,met\nq4-1pt,elastic,26.0,3.8e7,<= 15,missed\n",
    );
    w("throughput-runs.csv", "run,setup_s,loop_s,steps,ns_per_element_step,target,status\ntable1-elasto-plastic,0.0001,0.42,21364,15.4,< 0.5 s,met\n");
    w(
        "stability-cfl.csv",
        "mesh,material,cfl,status,max_balance_error,impulse_error,note\nuniform,elastic,1.2,stopped,NaN,NaN,step 96: element 20 (around x = 2.5e-3 m, y = 7.5e-3 m) has inverted\n",
    );
    w("stability-extreme.csv", "case,status,max_balance_error,impulse_error,note\nmass 0.01 kg,coarse,1.8e-2,0.0e0,5341 steps\n");
    w(
        "stability.md",
        "## CFL sweep (fixture)\n\n| mesh | material | cfl | status | note |\n|---|---|---|---|---|\n| uniform | elastic | 1.2 | stopped | step 96: element 20 has inverted |\n\nRuns below cfl 1.0 not bounded: 0\n\n## Extreme but valid inputs (fixture)\n\n| case | status |\n|---|---|\n| mass 0.01 kg | coarse |\n",
    );
}

/// A reconstruction page (`report.md`) with a table, a figure next to it (`fig/fit.svg`), a
/// link to that figure, an in-page anchor and a figure that does not exist. Returns its path.
pub fn write_reconstruction(dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir.join("fig")).unwrap();
    std::fs::write(dir.join("fig").join("fit.svg"), svg("reconstruction fit")).unwrap();
    let page = dir.join("report.md");
    std::fs::write(
        &page,
        "# Reconstruction fixture page\n\n\
         The best set (see [the residuals](#residuals-fixture)):\n\n\
         | quantity | paper | computed | residual |\n|---|---|---|---|\n| impulse (N s) | 100.0 | 101.0 | +1.0 % |\n\n\
         ![fit fixture](fig/fit.svg)\n\n\
         ## Residuals fixture\n\nThe plot as a file: [fit](fig/fit.svg). A lost one: ![lost](lost.svg)\n",
    )
    .unwrap();
    page
}

/// A verify output folder with no cases (results.json only): enough for `write_report`.
pub fn write_empty_results(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        dir.join("results.json"),
        r#"{"counts": {"ok": 0, "fail": 0, "skip": 0}, "cases": []}"#,
    )
    .unwrap();
}

/// The checks common to every report with both fixtures embedded.
pub fn assert_sections_present(out: &Path) {
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();

    // Reconstruction page: rendered (table, shifted headings with ids), figures inlined.
    assert!(html.contains("<h2 id=\"reconstruction\">Reproducing Dokko &amp; Kim (2004)</h2>"));
    assert!(!html.contains("Not yet produced"), "the page exists");
    assert!(
        html.contains(
            "<h3 id=\"recon-reconstruction-fixture-page\">Reconstruction fixture page</h3>"
        ),
        "page headings one level under the section"
    );
    assert!(
        html.contains("<h4 id=\"recon-residuals-fixture\">")
            && html.contains("href=\"#recon-residuals-fixture\"")
    );
    assert!(
        html.contains("<td>impulse (N s)</td>") && html.contains("<th>residual</th>"),
        "the page's table as HTML"
    );
    assert_eq!(
        html.matches("src=\"data:image/svg+xml;base64,").count(),
        1,
        "the figure inlined, once"
    );
    assert!(
        html.contains("<img id=\"recon-fig-fig-fit-svg\"")
            && html.contains("<a href=\"#recon-fig-fig-fit-svg\">fit</a>"),
        "the link to the SVG jumps to its figure"
    );
    assert!(
        html.contains("figure lost.svg not found") && html.contains("<code>lost.svg</code>"),
        "a missing figure is said, not invented"
    );
    // ... and in report.md: embedded, links pointing at the copies next to report.md.
    assert!(md.contains("## Reproducing Dokko & Kim (2004)"));
    assert!(
        md.contains("### Reconstruction fixture page\n") && md.contains("#### Residuals fixture\n")
    );
    assert!(md.contains("| impulse (N s) | 100.0 | 101.0 | +1.0 % |"));
    assert!(
        md.contains("![fit fixture](reconstruction/fig/fit.svg)")
            && md.contains("[fit](reconstruction/fig/fit.svg)")
    );
    assert!(out.join("reconstruction/fig/fit.svg").is_file());

    // Performance: plots inline, Pareto fronts, the sorted table, throughput, stability.
    assert!(html.contains(
        "<h2 id=\"performance\">Performance: work-precision, throughput, stability</h2>"
    ));
    assert!(!html.contains("No benchmark results"));
    for p in ["impact-fixture", "pulse-fixture"] {
        assert!(html.contains(&format!("{p} plot")), "plot of {p} inline");
        assert!(md.contains(&format!(
            "![work-precision {p}](plots/benchmarks-work-precision-{p}.svg)"
        )));
        assert!(out
            .join(format!("plots/benchmarks-work-precision-{p}.svg"))
            .is_file());
    }
    assert!(
        !html.contains("<?xml version"),
        "inline SVGs lose their XML prolog"
    );
    // impact-fixture: q4-full 20x4 (slower and worse than q4-sri 20x4) and q4-sri 10x2 cfl 0.3
    // (slower and worse than q4-sri 20x4) are off the front; three are on it, fastest first.
    assert!(md.contains("Pareto front: 3 of 5 configurations"), "{md}");
    let front = "| q4-1pt | 10x2 | 0.9 | 1.2e-6 | 1.0e-1 | 1.0e-6 | 1.0e-3 | 1.0010e-3 |\n\
                 | q4-sri | 20x4 | 0.9 | 6.0e-7 | 2.0e-3 | 1.0e-5 | 2.0e-2 | 2.0010e-2 |\n\
                 | q4-sri | 160x32 | 0.9 | 1.0e-7 | 1.0e-4 | 1.0e-4 | 9.0e0 | 9.0001e0 |\n";
    assert!(md.contains(front), "{md}");
    assert!(md.contains("Pareto front: 2 of 2 configurations"));
    // The whole table: problem, element, cfl, mesh (by size: 20x4 before 160x32).
    let order = [
        "| impact-fixture | q4-1pt | 10x2 |",
        "| impact-fixture | q4-full | 20x4 |",
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
    assert!(
        at.windows(2).all(|w| w[0] < w[1]),
        "sorted by problem, element, cfl, mesh: {at:?}"
    );
    assert!(html.contains("<details><summary>All 7 configurations (work-precision.csv)"));
    assert!(
        md.contains("| impact-fixture | q4-sri 320x64 cfl 0.3 | 1.0e-5 |"),
        "references table"
    );
    assert!(
        html.contains("<td class=\"FAIL\">missed</td>")
            && html.contains("<td class=\"OK\">met</td>"),
        "throughput targets coloured"
    );
    assert!(md.contains("| table1-elasto-plastic | 0.0001 | 0.42 | 21364 | 15.4 | < 0.5 s | met |"));
    assert!(
        html.contains("<h4 id=\"bench-cfl-sweep-fixture\">CFL sweep (fixture)</h4>")
            && html.contains("<td>step 96: element 20 has inverted</td>"),
        "stability.md rendered"
    );
    assert!(
        md.contains("#### CFL sweep (fixture)\n")
            && md.contains("#### Extreme but valid inputs (fixture)\n")
    );

    // Still one file that opens offline.
    let offline = html.replace("http://www.w3.org/2000/svg", "");
    assert!(
        !offline.contains("<script")
            && !offline.contains("http://")
            && !offline.contains("https://"),
        "the report must open offline"
    );
}

/// The checks of a report with neither fixture: both sections say how to produce them.
pub fn assert_sections_missing(out: &Path, benchmarks_given: Option<&Path>) {
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        html.contains("<b>Not yet produced:</b>")
            && html.contains("Run <code>scripts/reconstruction/reconstruct.py</code>")
    );
    assert!(
        md.contains("**Not yet produced:**")
            && md.contains("Run `scripts/reconstruction/reconstruct.py`")
    );
    assert!(
        !html.contains("id=\"recon-") && !md.contains("](reconstruction/"),
        "nothing shown in the page's place"
    );
    assert!(
        html.contains("<b>No benchmark results:</b>") && md.contains("**No benchmark results:**")
    );
    assert!(
        md.contains("`cargo run --release -p impact-benchmarks -- all --out DIR`")
            && md.contains("scripts/main-job.sh")
    );
    if let Some(d) = benchmarks_given {
        assert!(md.contains(&format!("the folder `{}` does not exist", d.display())));
    } else {
        assert!(md.contains("no folder was given (`--benchmarks DIR`)"));
    }
    assert!(
        !html.contains("perf-wp-") && !md.contains("### Work-precision"),
        "no performance content invented"
    );
}
