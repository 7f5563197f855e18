//! The developers' guide's structural rules, checked on the workspace's own sources (the
//! reference is the guide itself): no import circle between the top-level modules of any
//! crate (a module `a` imports `b` when its non-test code names `crate::b`), and no function
//! over 120 lines outside tests (a `fn` item to its closing brace, as `cargo fmt` lays it out).
//! The long functions not yet split are listed by name below; the list may only shrink: a
//! listed function that became short fails too, so that it is struck off. And the report
//! names no suite (issue 11): a case declares what the report shows of it in `report:`.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The crates' source folders, relative to the workspace root.
const CRATES: [&str; 6] = [
    "solver/src",
    "plots/src",
    "verification/src",
    "benchmarks/src",
    "python/src",
    "analytical/src",
];

/// Functions over the limit that are still to be split (issue 11), as `path::name`.
const LONG_NOT_YET_SPLIT: [&str; 0] = [];

const MAX_FN_LINES: usize = 120;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file without its test module and without whole-line comments.
fn non_test_code(text: &str) -> String {
    let code = text.split("#[cfg(test)]").next().unwrap_or("");
    code.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

fn ident_at(s: &str) -> &str {
    let end = s
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    &s[..end]
}

/// The top-level modules named by `crate::x` and `crate::{x, y::z}` in `code`.
fn crate_refs(code: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for (i, _) in code.match_indices("crate::") {
        let rest = &code[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            let (mut depth, mut item_start) = (0usize, true);
            for (j, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => item_start = true,
                    c if c.is_alphabetic() && item_start && depth == 0 => {
                        out.insert(ident_at(&group[j..]).to_string());
                        item_start = false;
                    }
                    _ => {}
                }
            }
        } else {
            out.insert(ident_at(rest).to_string());
        }
    }
    out
}

/// Module -> the modules it imports, for the crate in `src`.
fn module_graph(src: &Path) -> BTreeMap<String, BTreeSet<String>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for f in &files {
        let rel = f.strip_prefix(src).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        let module = first.trim_end_matches(".rs").to_string();
        if module == "lib" || module == "main" || module == "bin" {
            continue;
        }
        let text = std::fs::read_to_string(f).unwrap();
        let refs = crate_refs(&non_test_code(&text));
        graph.entry(module).or_default().extend(refs);
    }
    let names: BTreeSet<String> = graph.keys().cloned().collect();
    for (m, deps) in graph.iter_mut() {
        deps.retain(|d| d != m && names.contains(d));
    }
    graph
}

/// The strongly connected components with more than one module (Tarjan).
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct State<'a> {
        graph: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        found: Vec<Vec<String>>,
    }
    fn visit<'a>(s: &mut State<'a>, v: &'a str) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        for w in &s.graph[v] {
            let w = w.as_str();
            if !s.index.contains_key(w) {
                visit(s, w);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if s.stack.contains(&w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut comp = Vec::new();
            while let Some(w) = s.stack.pop() {
                comp.push(w.to_string());
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                s.found.push(comp);
            }
        }
    }
    let mut s = State {
        graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        found: Vec::new(),
    };
    for v in graph.keys() {
        if !s.index.contains_key(v.as_str()) {
            visit(&mut s, v);
        }
    }
    s.found
}

#[test]
fn no_import_circle_in_any_crate() {
    let mut problems = Vec::new();
    for c in CRATES {
        let graph = module_graph(&root().join(c));
        for comp in circles(&graph) {
            let edges: Vec<String> = comp
                .iter()
                .map(|m| {
                    let inside: Vec<&str> = graph[m]
                        .iter()
                        .filter(|d| comp.contains(d))
                        .map(|d| d.as_str())
                        .collect();
                    format!("{m} -> {}", inside.join(", "))
                })
                .collect();
            problems.push(format!("{c}: circle {comp:?} ({})", edges.join("; ")));
        }
    }
    assert!(
        problems.is_empty(),
        "import circles:\n{}",
        problems.join("\n")
    );
}

/// `(path::name, lines)` of every non-test function longer than the limit under `dir`.
fn long_functions(dir: &Path, base: &Path, out: &mut Vec<(String, usize)>) {
    let mut files = Vec::new();
    rust_files(dir, &mut files);
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        let lines: Vec<&str> = code.lines().collect();
        let rel = f
            .strip_prefix(base)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        for (i, l) in lines.iter().enumerate() {
            let Some(name) = fn_name(l) else { continue };
            let indent = &l[..l.len() - l.trim_start().len()];
            let close = format!("{indent}}}");
            let end = (i..lines.len())
                .find(|&j| (j == i && l.trim_end().ends_with('}')) || (j > i && lines[j] == close))
                .unwrap_or(i);
            let n = end - i + 1;
            if n > MAX_FN_LINES {
                out.push((format!("{rel}::{name}"), n));
            }
        }
    }
}

/// The name of the function a line opens (a body follows: not a trait's `fn f(..);`).
fn fn_name(line: &str) -> Option<&str> {
    let t = line.trim_start();
    let mut rest = t;
    for prefix in [
        "pub(crate) ",
        "pub(super) ",
        "pub ",
        "const ",
        "async ",
        "unsafe ",
    ] {
        rest = rest.strip_prefix(prefix).unwrap_or(rest);
    }
    let rest = rest.strip_prefix("fn ")?;
    if t.trim_end().ends_with(';') {
        return None;
    }
    Some(ident_at(rest))
}

#[test]
fn no_function_over_120_lines_outside_tests() {
    let root = root();
    let mut found = Vec::new();
    for c in CRATES {
        long_functions(&root.join(c), &root, &mut found);
    }
    long_functions(&root.join("benchmarks/benches"), &root, &mut found);
    let listed: BTreeSet<&str> = LONG_NOT_YET_SPLIT.into_iter().collect();
    let new: Vec<String> = found
        .iter()
        .filter(|(n, _)| !listed.contains(n.as_str()))
        .map(|(n, l)| format!("{n}: {l} lines"))
        .collect();
    let short: Vec<&str> = listed
        .iter()
        .filter(|n| !found.iter().any(|(f, _)| f == *n))
        .copied()
        .collect();
    assert!(
        new.is_empty(),
        "functions over {MAX_FN_LINES} lines (split them):\n{}",
        new.join("\n")
    );
    assert!(
        short.is_empty(),
        "no longer over the limit, strike them off LONG_NOT_YET_SPLIT: {short:?}"
    );
}

#[test]
fn the_rules_can_fail() {
    // A circle a -> b -> a is found; a chain a -> b is not.
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.insert("a".into(), ["b".to_string()].into());
    g.insert("b".into(), ["a".to_string()].into());
    g.insert("c".into(), ["a".to_string()].into());
    assert_eq!(circles(&g), vec![vec!["a".to_string(), "b".to_string()]]);
    g.insert("b".into(), BTreeSet::new());
    assert!(circles(&g).is_empty());
    // Imports are read from paths and groups, not from comments.
    let refs = crate_refs(&non_test_code(
        "use crate::{case::{Case, Loc}, jobs};\n// crate::lint\nfn f() { crate::report::x() }",
    ));
    assert_eq!(
        refs,
        ["case", "jobs", "report"]
            .map(String::from)
            .into_iter()
            .collect()
    );
    assert_eq!(
        fn_name("    pub(crate) fn run_all(x: u8) {"),
        Some("run_all")
    );
    assert_eq!(fn_name("    fn decl(&self);"), None);
}

/// The suite names that the code of `text` quotes (`"energy"`, `"table1/..."`).
fn quoted_suites<'a>(text: &str, suites: &'a [String]) -> Vec<&'a str> {
    suites
        .iter()
        .filter(|s| text.contains(&format!("\"{s}\"")) || text.contains(&format!("\"{s}/")))
        .map(String::as_str)
        .collect()
}

#[test]
fn the_report_names_no_suite() {
    let root = root();
    let mut suites: Vec<String> = std::fs::read_dir(root.join("verification/cases"))
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_dir())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    suites.sort();
    assert!(suites.len() > 3, "{suites:?}");
    // The files that render the report: src/report/ and templates/.
    let mut files = Vec::new();
    rust_files(&root.join("verification/src/report"), &mut files);
    files.extend(
        std::fs::read_dir(root.join("verification/templates"))
            .unwrap()
            .filter_map(|e| e.ok().map(|e| e.path())),
    );
    files.sort();
    assert!(
        files.iter().any(|f| f.ends_with("paper_tables.rs")),
        "{files:?}"
    );
    let mut found = Vec::new();
    for f in &files {
        // An HTML anchor (`id="energy"`) is a place in the page, not a suite looked up.
        let text = non_test_code(&std::fs::read_to_string(f).unwrap()).replace("id=\"", "id=");
        for s in quoted_suites(&text, &suites) {
            found.push(format!("{}: \"{s}\"", f.display()));
        }
    }
    // Nor in its prose: the templates' text and the cases' texts the report shows say what a
    // section or case is ("the Energy section"), not which folder it sits in ("energy suite").
    let mut shown = files.clone();
    shown.extend(case_files(&root.join("verification/cases")));
    for f in &shown {
        let text = std::fs::read_to_string(f).unwrap();
        for s in suites_in_prose(&text, &suites) {
            found.push(format!("{}: \"{s} suite\"", f.display()));
        }
    }
    assert!(
        found.is_empty(),
        "the report names suites (declare a `report:` block in the case instead): {found:?}"
    );
    // The scan finds a suite looked up by name.
    let demo = non_test_code(r#"let c = case("energy"); let t = "table1/literal";"#);
    assert_eq!(quoted_suites(&demo, &suites), ["energy", "table1"]);
    let prose =
        "error 0.26 of the largest energy, elastic, Energy suite: counted twice; the patch\nsuite";
    assert_eq!(suites_in_prose(prose, &suites), ["energy", "patch"]);
    assert!(suites_in_prose("the Energy section; a test suite", &suites).is_empty());
}

/// The suites a text names in prose as "<suite> suite" (any case, across a line break).
fn suites_in_prose<'a>(text: &str, suites: &'a [String]) -> Vec<&'a str> {
    let words = text
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .to_lowercase();
    suites
        .iter()
        .filter(|s| words.contains(&format!("{s} suite")))
        .map(String::as_str)
        .collect()
}

/// Every case.yaml under `dir`.
fn case_files(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            found.extend(case_files(&p));
        } else if p.file_name().is_some_and(|n| n == "case.yaml") {
            found.push(p);
        }
    }
    found.sort();
    found
}
