//! The tracker's layers, checked from its source: every file under `src/` belongs to one layer
//! (the folder it is in), a module imports only from its own layer or the layers below it, and
//! no modules import each other round a cycle. The layers, bottom to top, are those of
//! `LAYERS`; docs/ARCHITECTURE.md says what each holds.
//!
//! What counts as an import: `crate::` paths (in `use` lines or inline, as `crate::a::b::c` or
//! `crate::a::{b, c}`) and `super::` paths, resolved from the file's own module. Comment lines
//! (docs) and a file's unit tests (`#[cfg(test)] mod tests` to the end of the file) are left
//! out: tests may build their cases with anything. Paths through the crate root's re-exports
//! (`crate::Scene`) or its old module paths (`crate::scene`) are refused too, since they hide
//! which layer a module reads.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The layers, bottom first.
const LAYERS: [&str; 5] = ["model", "physics", "tracking", "estimation", "studies"];

/// A module's path below the crate root, from its file's path below `src/`
/// (`model/scene.rs` is `model::scene`, `tracking/mod.rs` is `tracking`).
fn module_of(file: &str) -> Vec<String> {
    let stem = file.strip_suffix(".rs").unwrap_or(file);
    let mut parts: Vec<String> = stem.split('/').map(str::to_string).collect();
    if parts.last().is_some_and(|p| p == "mod") {
        parts.pop();
    }
    parts
}

/// The source a module's imports are read from: no comment lines, no unit tests.
fn code_of(text: &str) -> String {
    let mut out = String::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        let t = line.trim_start();
        if t.starts_with("#[cfg(test)]") && lines.peek().is_some_and(|next| next.trim_start().starts_with("mod tests"))
        {
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

/// The identifier path that starts at byte `at` of `code` (`a::b::{c, d}` gives `[a, b]` and
/// the group's first segments `[c, d]`).
fn path_at(code: &str, at: usize) -> (Vec<String>, Vec<String>) {
    let bytes = code.as_bytes();
    let mut segments = Vec::new();
    let mut i = at;
    loop {
        let start = i;
        while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
            i += 1;
        }
        if i == start {
            break;
        }
        segments.push(code[start..i].to_string());
        if code[i..].starts_with("::") {
            i += 2;
        } else {
            break;
        }
    }
    let mut group = Vec::new();
    if code[i..].starts_with('{') {
        let end = code[i..].find('}').map_or(code.len(), |e| i + e);
        for item in code[i + 1..end].split(',') {
            let first = item.trim().split("::").next().unwrap_or("").trim().to_string();
            if !first.is_empty() && first != "self" {
                group.push(first);
            }
        }
    }
    (segments, group)
}

/// Each module's imports as full paths below the crate root, with the problems found on the
/// way (paths through the root's re-exports, `super::` out of the crate).
fn imports(module: &[String], code: &str) -> (Vec<Vec<String>>, Vec<String>) {
    let mut found = Vec::new();
    let mut problems = Vec::new();
    let name = module.join("::");
    let starts = |token: &str| -> Vec<usize> {
        code.match_indices(token)
            .filter(|(i, _)| {
                *i == 0 || !code.as_bytes()[i - 1].is_ascii_alphanumeric() && code.as_bytes()[i - 1] != b'_'
            })
            .map(|(i, _)| i)
            .collect()
    };
    for i in starts("crate::") {
        let (segments, group) = path_at(code, i + "crate::".len());
        if segments.is_empty() && group.is_empty() {
            continue;
        }
        if segments.is_empty() {
            problems.push(format!("{name}: `crate::{{...}}` names the crate root's re-exports, not a layer"));
            continue;
        }
        let mut paths: Vec<Vec<String>> = vec![segments.clone()];
        if !group.is_empty() {
            paths = group.iter().map(|g| segments.iter().cloned().chain([g.clone()]).collect()).collect();
        }
        found.extend(paths);
    }
    for i in starts("super::") {
        // Count the `super::`s, then resolve from the module (a file's `super` is its parent).
        let mut j = i;
        let mut ups = 0;
        while code[j..].starts_with("super::") {
            j += "super::".len();
            ups += 1;
        }
        if i >= "super::".len() && code[..i].ends_with("super::") {
            continue; // counted with the chain's first `super::`
        }
        if ups > module.len() {
            problems.push(format!("{name}: `super::` climbs out of the crate"));
            continue;
        }
        let base: Vec<String> = module[..module.len() - ups].to_vec();
        let (segments, group) = path_at(code, j);
        let mut paths: Vec<Vec<String>> = vec![base.iter().cloned().chain(segments.iter().cloned()).collect()];
        if !group.is_empty() {
            paths = group
                .iter()
                .map(|g| base.iter().cloned().chain(segments.iter().cloned()).chain([g.clone()]).collect())
                .collect();
        }
        found.extend(paths);
    }
    (found, problems)
}

/// Every problem of a source tree given as `(path below src/, text)`: files outside the layers,
/// imports from a layer above, paths through the root, and import cycles between modules.
fn problems(files: &[(String, String)]) -> Vec<String> {
    let mut problems = Vec::new();
    let modules: BTreeSet<Vec<String>> =
        files.iter().filter(|(f, _)| f != "lib.rs").map(|(f, _)| module_of(f)).collect();
    let layer = |m: &[String]| m.first().and_then(|l| LAYERS.iter().position(|x| x == l));
    // The module a path names: its longest prefix that is a module.
    let owner = |path: &[String]| -> Option<Vec<String>> {
        (1..=path.len()).rev().map(|n| path[..n].to_vec()).find(|p| modules.contains(p))
    };
    let mut edges: BTreeMap<Vec<String>, BTreeSet<Vec<String>>> = BTreeMap::new();
    for (file, text) in files {
        if file == "lib.rs" {
            continue;
        }
        let module = module_of(file);
        let Some(own) = layer(&module) else {
            problems.push(format!("{file}: not in a layer's folder ({})", LAYERS.join(", ")));
            continue;
        };
        let (paths, mut found) = imports(&module, &code_of(text));
        problems.append(&mut found);
        for path in paths {
            let Some(target) = owner(&path) else {
                problems.push(format!(
                    "{}: `crate::{}` is not a layer's path (the crate root's re-exports and old module paths hide the layer)",
                    module.join("::"),
                    path.join("::")
                ));
                continue;
            };
            let theirs = layer(&target).expect("a module in a layer");
            if theirs > own {
                problems.push(format!(
                    "{} (layer {}) imports {} from the layer above, {}",
                    module.join("::"),
                    LAYERS[own],
                    path.join("::"),
                    LAYERS[theirs]
                ));
            }
            // A module's own submodules and its ancestors (a folder's `mod.rs` declaring them)
            // are not a cycle.
            let related = target.starts_with(&module) || module.starts_with(&target);
            if !related {
                edges.entry(module.clone()).or_default().insert(target);
            }
        }
    }
    // Cycles: a module that reaches itself.
    let mut reported = BTreeSet::new();
    for start in edges.keys() {
        let mut stack = vec![(start.clone(), vec![start.clone()])];
        let mut seen = BTreeSet::new();
        while let Some((at, trail)) = stack.pop() {
            for next in edges.get(&at).into_iter().flatten() {
                if next == start {
                    let mut cycle: Vec<String> = trail.iter().map(|m| m.join("::")).collect();
                    cycle.sort();
                    if reported.insert(cycle.clone()) {
                        problems.push(format!("import cycle: {}", cycle.join(", ")));
                    }
                } else if seen.insert(next.clone()) {
                    let mut longer = trail.clone();
                    longer.push(next.clone());
                    stack.push((next.clone(), longer));
                }
            }
        }
    }
    problems
}

fn read_tree(dir: &Path, below: &str, out: &mut Vec<(String, String)>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir).expect("src/ is readable").map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let rel = if below.is_empty() { name.clone() } else { format!("{below}/{name}") };
        if path.is_dir() {
            read_tree(&path, &rel, out);
        } else if name.ends_with(".rs") {
            out.push((rel, std::fs::read_to_string(&path).unwrap()));
        }
    }
}

#[test]
fn imports_go_down_the_layers_and_round_no_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    read_tree(&src, "", &mut files);
    assert!(files.len() > 20, "read {} files from {}", files.len(), src.display());
    // Every layer is there, with files in it.
    for layer in LAYERS {
        assert!(files.iter().any(|(f, _)| f.starts_with(&format!("{layer}/"))), "no folder for the layer {layer}");
    }
    let problems = problems(&files);
    assert!(problems.is_empty(), "{} problems:\n{}", problems.len(), problems.join("\n"));
}

/// The checker itself finds what it is for, on a small made-up tree.
#[test]
fn the_check_finds_upward_imports_root_paths_and_cycles() {
    let tree = |files: &[(&str, &str)]| -> Vec<(String, String)> {
        files.iter().map(|(f, t)| ((*f).to_string(), (*t).to_string())).collect()
    };
    let clean = tree(&[
        ("lib.rs", "pub mod model;\npub mod studies;\n"),
        ("model/mod.rs", "pub mod a;\npub mod b;\n"),
        ("model/a.rs", "use crate::model::b::B;\n"),
        ("model/b.rs", "pub struct B;\n"),
        ("studies/mod.rs", "pub mod s;\n"),
        ("studies/s.rs", "use crate::model::{a, b::B};\nuse super::super::model::a::A;\n"),
    ]);
    assert_eq!(problems(&clean), Vec::<String>::new());

    let upward = tree(&[
        ("model/mod.rs", "pub mod a;\n"),
        ("model/a.rs", "/// [`crate::studies::s`] in a doc is no import.\nfn f() { crate::studies::s::g(); }\n"),
        ("studies/mod.rs", "pub mod s;\n"),
        ("studies/s.rs", "pub fn g() {}\n"),
    ]);
    let found = problems(&upward);
    assert_eq!(found.len(), 1, "{found:?}");
    assert!(found[0].contains("model::a (layer model) imports studies::s::g from the layer above, studies"));

    let cycle = tree(&[
        ("model/mod.rs", "pub mod a;\npub mod b;\n"),
        ("model/a.rs", "use crate::model::b::B;\npub struct A;\n"),
        ("model/b.rs", "use super::a::A;\npub struct B;\n#[cfg(test)]\nmod tests {\n    use crate::studies::S;\n}\n"),
    ]);
    assert_eq!(problems(&cycle), vec!["import cycle: model::a, model::b".to_string()]);

    let through_root =
        tree(&[("model/mod.rs", "pub mod a;\n"), ("model/a.rs", "use crate::Scene;\n"), ("stray.rs", "")]);
    let found = problems(&through_root);
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found.iter().any(|p| p.contains("stray.rs: not in a layer")));
    assert!(found.iter().any(|p| p.contains("`crate::Scene` is not a layer's path")));
}
