//! Small fixtures for the report tests: a benchmarks folder with the page `impact-bench all
//! --out DIR` writes there, and a reconstruction page shaped like `scripts/reconstruction/reconstruct.py`'s
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

/// A benchmarks folder with the page `impact-bench` writes (`benchmarks.md`, shaped like
/// benchmarks/src/page.rs's: the title repeating the report's section, a targets table with
/// met and missed, a work-precision plot beside it, a stability table with `coarse`) and one
/// of its CSVs. The page's own content is tested in benchmarks/src/page_tests.rs.
pub fn write_benchmarks(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    let w = |name: &str, text: &str| std::fs::write(dir.join(name), text).unwrap();
    w(
        "work-precision-impact-fixture.svg",
        &svg("impact-fixture plot"),
    );
    w(
        "throughput-runs.csv",
        "run,setup_s,loop_s,steps,ns_per_element_step,target,status\ntable1-elasto-plastic,0.0001,0.42,21364,15.4,< 0.5 s,met\n",
    );
    w(
        "benchmarks.md",
        "# Performance: work-precision, throughput, stability\n\n\
         **Machine:** fixture machine, 2 cores.\n\n\
         **Targets** (fixture): 1 of 2 met.\n\n\
         | target | measured | target value | status |\n|---|---|---|---|\n\
         | kernel q4-sri elastic | 25.0 ns per element-step | <= 6.0 ns | missed |\n\
         | whole run table1-elasto-plastic | 0.420 s (setup + loop) | < 0.5 s | met |\n\n\
         ## Work-precision: run time against error\n\n\
         ### impact-fixture\n\n\
         ![work-precision impact-fixture](work-precision-impact-fixture.svg)\n\n\
         Pareto front: 1 of 1 configurations (see [the targets](#targets-fixture)).\n\n\
         | element | mesh | error |\n|---|---|---|\n| q4-sri | 20x4 | 2.0e-3 |\n\n\
         ## Stability\n\n### Extreme but valid inputs (fixture)\n\n\
         | case | status |\n|---|---|\n| mass 0.01 kg | coarse |\n\n\
         ## Targets fixture\n\nA lost plot: ![lost](work-precision-lost.svg)\n",
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
    assert!(
        html.contains("src=\"data:image/svg+xml;base64,"),
        "the figure inlined"
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

    // Performance: the page impact-bench wrote, embedded under the section (its title, which
    // repeats the section's, dropped), its plot inlined and copied, its cells styled.
    assert!(html.contains(
        "<h2 id=\"performance\">Performance: work-precision, throughput, stability</h2>"
    ));
    assert!(!html.contains("No benchmark results") && !html.contains("No benchmark page"));
    assert!(
        html.contains("<h3 id=\"perf-work-precision-run-time-against-error\">Work-precision: run time against error</h3>")
            && html.contains("<h4 id=\"perf-impact-fixture\">impact-fixture</h4>")
            && html.contains("<h4 id=\"perf-extreme-but-valid-inputs-fixture\">"),
        "page headings one level under the section"
    );
    assert!(
        !html.contains("id=\"perf-performance"),
        "the page's title repeats the section's: dropped"
    );
    assert!(
        html.contains("<img id=\"perf-fig-work-precision-impact-fixture-svg\"")
            && html.contains("href=\"#perf-targets-fixture\""),
        "the plot inlined, the page's anchors kept apart"
    );
    assert_eq!(
        html.matches("src=\"data:image/svg+xml;base64,").count(),
        2,
        "the reconstruction's figure and the benchmark plot, each once"
    );
    assert!(
        html.contains("<td class=\"FAIL\">missed</td>")
            && html.contains("<td class=\"OK\">met</td>")
            && html.contains("<td class=\"SKIP\">coarse</td>")
            && html.contains("<td class=\"num\"><span class=\"tok\">2.0e-3</span></td>"),
        "targets and statuses coloured as the report's own tables"
    );
    assert!(
        md.contains("### Work-precision: run time against error\n")
            && md.contains("#### impact-fixture\n")
            && md.contains("#### Extreme but valid inputs (fixture)\n"),
        "{md}"
    );
    assert_eq!(
        md.matches("Performance: work-precision, throughput, stability")
            .count(),
        1,
        "{md}"
    );
    assert!(
        md.contains("| kernel q4-sri elastic | 25.0 ns per element-step | <= 6.0 ns | missed |")
    );
    assert!(md.contains(
        "![work-precision impact-fixture](plots/benchmarks/work-precision-impact-fixture.svg)"
    ));
    assert!(out
        .join("plots/benchmarks/work-precision-impact-fixture.svg")
        .is_file());
    assert!(
        md.contains("Files it links to that are not next to it: `work-precision-lost.svg`."),
        "{md}"
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
        !html.contains("id=\"perf-") && !md.contains("### Work-precision"),
        "no performance content invented"
    );
}
