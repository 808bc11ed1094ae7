//! The shape of `src/` as ARCHITECTURE.md states it, checked on the source:
//!
//! * layers depend only downwards: `model` < `models` (the generated
//!   catalogue) < `dynamics` < `orbit` < `bifurcation` < `study` < `output` (< `cli`, the
//!   binary, which only uses the library's public API);
//! * the modules' `use crate::…` graph has no cycle;
//! * no source file passes 800 lines.
//!
//! References in doc comments and in a file's `#[cfg(test)]` module do not
//! count: they are not dependencies of the library.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

const LAYERS: [&str; 7] = [
    "model",
    "models",
    "dynamics",
    "orbit",
    "bifurcation",
    "study",
    "output",
];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("read src") {
        let path = entry.expect("dir entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// `src/orbit/motion.rs` → `orbit::motion`; `src/study/map/run.rs` →
/// `study::map`; `src/model/mod.rs` → `model`.
fn module_of(src: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(src).expect("under src");
    let mut parts: Vec<String> = rel
        .with_extension("")
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts.truncate(2);
    parts.join("::")
}

/// The library code of a file: without comments and without the trailing
/// `#[cfg(test)]` module.
fn library_code(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with("#[cfg(test)]") {
            break;
        }
        if t.starts_with("//") {
            continue;
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}

/// Every `crate::a::b` in `code`, as the module it names (`a::b`, or `a` for
/// a one-level module or an item of a layer's root).
fn dependencies(code: &str, modules: &BTreeSet<String>) -> BTreeSet<String> {
    let mut deps = BTreeSet::new();
    for (at, _) in code.match_indices("crate::") {
        let rest = &code[at + "crate::".len()..];
        let path: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
            .collect();
        let segments: Vec<&str> = path.split("::").filter(|s| !s.is_empty()).collect();
        let two = segments
            .iter()
            .take(2)
            .copied()
            .collect::<Vec<_>>()
            .join("::");
        if modules.contains(&two) {
            deps.insert(two);
        } else if let Some(first) = segments.first() {
            if modules.contains(*first) {
                deps.insert(first.to_string());
            }
        }
    }
    deps
}

fn layer(module: &str) -> Option<usize> {
    let top = module.split("::").next()?;
    LAYERS.iter().position(|l| *l == top)
}

struct Tree {
    /// module → the modules its library code uses.
    graph: BTreeMap<String, BTreeSet<String>>,
    /// file → line count.
    lines: Vec<(PathBuf, usize)>,
}

fn tree() -> Tree {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let src = root.join("src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let modules: BTreeSet<String> = files.iter().map(|f| module_of(&src, f)).collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut lines = Vec::new();
    for f in &files {
        let text = fs::read_to_string(f).expect("read source");
        lines.push((
            f.strip_prefix(root).unwrap().to_path_buf(),
            text.lines().count(),
        ));
        let module = module_of(&src, f);
        let deps = dependencies(&library_code(&text), &modules);
        let entry = graph.entry(module.clone()).or_default();
        entry.extend(deps.into_iter().filter(|d| *d != module));
    }
    Tree { graph, lines }
}

#[test]
fn layers_depend_only_downwards() {
    let t = tree();
    let mut wrong = Vec::new();
    for (module, deps) in &t.graph {
        let Some(from) = layer(module) else { continue };
        for d in deps {
            if layer(d).is_some_and(|to| to > from) {
                wrong.push(format!("{module} uses {d}"));
            }
        }
    }
    assert!(
        t.graph.contains_key("orbit::motion") && t.graph.contains_key("study::map"),
        "the module list is wrong: {:?}",
        t.graph.keys().collect::<Vec<_>>()
    );
    assert!(wrong.is_empty(), "upward dependencies: {wrong:#?}");
}

#[test]
fn module_graph_has_no_cycle() {
    let t = tree();
    // Depth-first search with colours; report the first cycle found.
    fn visit(
        m: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(m.to_string(), 1);
        stack.push(m.to_string());
        for d in graph.get(m).into_iter().flatten() {
            match state.get(d.as_str()).copied().unwrap_or(0) {
                1 => {
                    let start = stack.iter().position(|s| s == d).unwrap_or(0);
                    let mut cycle = stack[start..].to_vec();
                    cycle.push(d.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(d, graph, state, stack) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(m.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    let edges: usize = t.graph.values().map(BTreeSet::len).sum();
    assert!(
        edges > 20,
        "too few dependencies found ({edges}): the scan is broken"
    );
    for m in t.graph.keys() {
        if state.get(m.as_str()).copied().unwrap_or(0) == 0 {
            let cycle = visit(m, &t.graph, &mut state, &mut Vec::new());
            assert!(
                cycle.is_none(),
                "dependency cycle: {}",
                cycle.unwrap().join(" -> ")
            );
        }
    }
}

#[test]
fn no_source_file_passes_800_lines() {
    let t = tree();
    let long: Vec<String> = t
        .lines
        .iter()
        .filter(|(_, n)| *n > 800)
        .map(|(f, n)| format!("{} ({n} lines)", f.display()))
        .collect();
    assert!(long.is_empty(), "files over 800 lines: {long:?}");
}

#[test]
fn the_scan_sees_a_cycle_and_an_upward_use() {
    // The checks above must be able to fail: a made-up pair of modules.
    let modules: BTreeSet<String> = ["orbit::motion", "orbit::attractor", "output::report"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let code = "/// [`crate::output::report`]\nuse crate::orbit::attractor::find;\n#[cfg(test)]\nuse crate::output::report;";
    let deps = dependencies(&library_code(code), &modules);
    assert_eq!(
        deps.into_iter().collect::<Vec<_>>(),
        vec!["orbit::attractor"]
    );
    let deps = dependencies("use crate::output::report::Report;", &modules);
    assert!(deps.contains("output::report"));
    assert!(layer("output::report") > layer("orbit::motion"));
}
