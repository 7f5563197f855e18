//! `impact verify --shard K/N` and `--merge` against a single run of a part of the light
//! matrix (the suites and cases of [`light`], chosen to hold every kind of output: plots,
//! convergence tables, known failures, published numbers, wrong models; the whole light
//! matrix ran twice here, about a fifth of the CI gate's test time, for no more coverage of
//! sharding): shards 1/2 and 2/2 run disjoint, non-empty shares of the jobs, and their merge
//! writes the same results.json, junit.xml, matrix.txt, runs/ files and report (index.html,
//! report.md, plots) byte for byte; an incomplete or duplicated set of shards is refused. The cost-balanced share is a
//! partition whose loads differ by at most the largest job.

use std::path::{Path, PathBuf};

use impact_verification::runner::{self, Options, Repo};
use impact_verification::shard::{self, share, Shard};

fn light() -> Options {
    Options {
        selectors: [
            "patch",
            "order-of-accuracy",
            "convergence",
            "table1",
            "taylor-bar/johnson-cook-42crmo4",
        ]
        .map(String::from)
        .to_vec(),
        filter: None,
        jobs: 2,
        include_heavy: false,
        progress: false,
    }
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("impact-shard-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The time a report was written ("report written 2026-11-23T01:07:16Z") masked: the one
/// thing besides environment.json that differs between two writes of the same results.
fn mask_time(bytes: Vec<u8>) -> Vec<u8> {
    let Ok(text) = String::from_utf8(bytes.clone()) else {
        return bytes;
    };
    match text.find("report written ") {
        Some(at) => {
            let end = at + "report written 2026-11-23T01:07:16Z".len();
            format!(
                "{}report written TIME{}",
                &text[..at],
                &text[end.min(text.len())..]
            )
            .into_bytes()
        }
        None => bytes,
    }
}

/// What verify writes for `outcome` with its report, into the same folder every time (the
/// report names its folder): every file (relative path, bytes), environment.json and
/// costs.json aside.
fn outputs(outcome: &runner::Outcome) -> Vec<(PathBuf, Vec<u8>)> {
    let dir = scratch("out");
    runner::write_outputs(outcome, &dir).unwrap();
    impact_verification::report::write_report(&dir, &dir).unwrap();
    let all = files(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    all
}

/// Every file under `dir` (relative path, bytes), environment.json and costs.json (wall
/// times) aside.
fn files(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if !["environment.json", "costs.json"]
                .iter()
                .any(|n| p.file_name().unwrap() == *n)
            {
                let bytes = mask_time(std::fs::read(&p).unwrap());
                out.push((p.strip_prefix(dir).unwrap().to_path_buf(), bytes));
            }
        }
    }
    out.sort();
    out
}

#[test]
fn shards_merged_equal_the_whole_light_matrix() {
    let repo = Repo::this();
    let whole = runner::verify(&repo, &light()).unwrap_or_else(|e| panic!("{}", e.join("\n")));
    let (a, b) = (scratch("1"), scratch("2"));
    let half = |index, dir: &Path| {
        shard::run_shard(&repo, &light(), Shard { index, count: 2 }, dir)
            .unwrap_or_else(|e| panic!("{}", e.join("\n")))
    };
    let (n1, all) = half(1, &a);
    let (n2, _) = half(2, &b);
    assert!(n1 > 0 && n2 > 0 && n1 + n2 == all, "{n1} + {n2} != {all}");

    let merged = shard::merge(&repo, &[b.clone(), a.clone()], 2)
        .unwrap_or_else(|e| panic!("{}", e.join("\n")));
    let (fw, fm) = (outputs(&whole), outputs(&merged));
    assert!(fw.len() > 3, "{} files", fw.len());
    assert!(fw.iter().any(|(p, _)| p.ends_with("index.html")));
    for ((pw, bw), (pm, bm)) in fw.iter().zip(&fm) {
        assert_eq!(pw, pm);
        assert!(
            bw == bm,
            "{} differs between the whole run and the merge",
            pw.display()
        );
    }
    assert_eq!(fw.len(), fm.len());

    let refused = |dirs: &[PathBuf]| shard::merge(&repo, dirs, 2).err().unwrap_or_default();
    let only_one = refused(std::slice::from_ref(&a));
    assert!(
        only_one.join(" ").contains("missing shard(s) 2/2"),
        "{only_one:?}"
    );
    let twice = refused(&[a.clone(), a.clone()]);
    assert!(twice.join(" ").contains("given twice"), "{twice:?}");
    for d in [a, b] {
        let _ = std::fs::remove_dir_all(d);
    }
}

#[test]
fn the_share_is_a_balanced_partition() {
    let costs: Vec<f64> = (0..23).map(|i| ((i * 37) % 11 + 1) as f64).collect();
    let largest = costs.iter().cloned().fold(0.0, f64::max);
    for count in 1..=5 {
        let shares: Vec<Vec<usize>> = (1..=count)
            .map(|index| share(&costs, Shard { index, count }))
            .collect();
        let mut all: Vec<usize> = shares.concat();
        all.sort_unstable();
        assert_eq!(all, (0..costs.len()).collect::<Vec<_>>(), "{count} shards");
        let loads: Vec<f64> = shares
            .iter()
            .map(|s| s.iter().map(|&i| costs[i]).sum())
            .collect();
        let (lo, hi) = loads
            .iter()
            .fold((f64::MAX, 0.0_f64), |(l, h), &x| (l.min(x), h.max(x)));
        assert!(hi - lo <= largest, "{count} shards: loads {loads:?}");
        assert_eq!(share(&costs, Shard { index: 1, count }), shares[0]);
    }
    assert!("0/2".parse::<Shard>().is_err() && "3/2".parse::<Shard>().is_err());
    assert_eq!("2/3".parse::<Shard>(), Ok(Shard { index: 2, count: 3 }));
}
