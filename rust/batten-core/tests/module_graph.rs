//! The crate's modules form a DAG (DESIGN.md: dependence runs one way): no two sibling
//! modules use each other, directly or through other siblings.
//!
//! Every `crate::…` and `super::…` path in the code (comments left out) is a use of the module
//! it names. A use of module `T` from module `M` is an edge between the two children of their
//! nearest common ancestor on the ways to `M` and `T`; a child using its ancestors or a parent
//! using its children is containment, not an edge. Each set of siblings must be acyclic.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::Path;

type ModPath = Vec<String>;

/// The module path of a source file below `src/`.
fn module_of(rel: &Path) -> ModPath {
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let last = parts.pop().expect("a file name");
    let stem = last.trim_end_matches(".rs");
    if stem != "mod" && stem != "lib" {
        parts.push(stem.to_owned());
    }
    parts
}

/// The source without comments (line comments and doc comments; block comments are not used
/// in this crate's code).
fn strip_comments(src: &str) -> String {
    src.lines()
        .map(|l| match l.find("//") {
            Some(i) if !l[..i].contains('"') => &l[..i],
            _ => l,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The paths a `crate::` / `super::` occurrence at `rest` names: `a::b::C`, or each item of a
/// brace group `{a::X, b::{Y, Z}}` (first-level items are enough to find the module).
fn paths_after(rest: &str) -> Vec<Vec<String>> {
    let mut head = Vec::new();
    let mut s = rest;
    loop {
        let ident: String = s.chars().take_while(|&c| is_ident(c)).collect();
        if ident.is_empty() {
            break;
        }
        s = &s[ident.len()..];
        head.push(ident);
        if let Some(r) = s.strip_prefix("::") {
            s = r;
        } else {
            return vec![head];
        }
    }
    if let Some(group) = s.strip_prefix('{') {
        let mut depth = 0;
        let mut item = String::new();
        let mut out = Vec::new();
        for c in group.chars() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => break,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    out.push(std::mem::take(&mut item));
                    continue;
                }
                _ => {}
            }
            if depth == 0 {
                item.push(c);
            }
        }
        out.push(item);
        return out
            .iter()
            .map(|i| {
                let mut p = head.clone();
                p.extend(
                    i.trim()
                        .split("::")
                        .map(|x| x.trim().to_owned())
                        .filter(|x| !x.is_empty()),
                );
                p
            })
            .collect();
    }
    vec![head]
}

/// Every module path `from` uses in `src` (resolved against the known modules: the longest
/// known prefix of each path).
fn uses(from: &ModPath, src: &str, known: &BTreeSet<ModPath>) -> BTreeSet<ModPath> {
    let code = strip_comments(src);
    let mut out = BTreeSet::new();
    for (i, _) in code
        .match_indices("crate::")
        .chain(code.match_indices("super::"))
    {
        if i > 0 && is_ident(code[..i].chars().last().expect("a char")) {
            continue;
        }
        let (mut base, mut rest) = if code[i..].starts_with("crate::") {
            (Vec::new(), &code[i + 7..])
        } else {
            (
                from[..from.len().saturating_sub(1)].to_vec(),
                &code[i + 7..],
            )
        };
        while let Some(r) = rest.strip_prefix("super::") {
            base.pop();
            rest = r;
        }
        for p in paths_after(rest) {
            let mut full = base.clone();
            full.extend(p);
            let target = (0..=full.len())
                .rev()
                .map(|n| full[..n].to_vec())
                .find(|m| known.contains(m))
                .unwrap_or_default();
            out.insert(target);
        }
    }
    out
}

/// The module graph of the crate at `src`: per parent module, the edges among its children.
fn sibling_graphs(src: &Path) -> BTreeMap<ModPath, BTreeMap<String, BTreeSet<String>>> {
    let mut files = Vec::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in fs::read_dir(&dir).expect("read src") {
            let path = entry.expect("entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let rel = path.strip_prefix(src).expect("below src").to_path_buf();
                files.push((module_of(&rel), fs::read_to_string(&path).expect("read")));
            }
        }
    }
    let known: BTreeSet<ModPath> = files.iter().map(|(m, _)| m.clone()).collect();
    let mut graphs: BTreeMap<ModPath, BTreeMap<String, BTreeSet<String>>> = BTreeMap::new();
    for (from, text) in &files {
        for to in uses(from, text, &known) {
            let common = from.iter().zip(&to).take_while(|(a, b)| a == b).count();
            if common == from.len() || common == to.len() {
                continue; // containment: an ancestor or a descendant
            }
            graphs
                .entry(from[..common].to_vec())
                .or_default()
                .entry(from[common].clone())
                .or_default()
                .insert(to[common].clone());
        }
    }
    graphs
}

/// A cycle in `graph`, if there is one (depth-first search).
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        n: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(n.to_owned(), 1);
        path.push(n.to_owned());
        for m in graph.get(n).into_iter().flatten() {
            match state.get(m.as_str()) {
                Some(1) => {
                    let start = path.iter().position(|p| p == m).expect("on the path");
                    let mut cycle = path[start..].to_vec();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(m, graph, state, path) {
                        return Some(c);
                    }
                }
            }
        }
        path.pop();
        state.insert(n.to_owned(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in graph.keys() {
        if !state.contains_key(n.as_str()) {
            if let Some(c) = visit(n, graph, &mut state, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

#[test]
fn modules_form_a_dag() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let graphs = sibling_graphs(&src);
    let cycles: Vec<String> = graphs
        .iter()
        .filter_map(|(parent, g)| {
            find_cycle(g).map(|c| format!("in crate::{}: {}", parent.join("::"), c.join(" -> ")))
        })
        .collect();
    assert!(cycles.is_empty(), "module cycles: {cycles:#?}");
    // The graph is not empty: the checker sees the real dependencies.
    let root = &graphs[&Vec::<String>::new()];
    assert!(
        root["hull"].contains("topo") && root["topo"].contains("network"),
        "hull uses topo and topo uses network: {root:?}"
    );
}

#[test]
fn a_cycle_is_found() {
    let g: BTreeMap<String, BTreeSet<String>> = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a"]),
        ("d", vec!["a"]),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_owned(), v.into_iter().map(str::to_owned).collect()))
    .collect();
    let cycle = find_cycle(&g).expect("a -> b -> c -> a");
    assert_eq!(cycle.len(), 4, "three modules and back: {cycle:?}");
    let acyclic: BTreeMap<String, BTreeSet<String>> =
        [("a".to_owned(), BTreeSet::from(["b".to_owned()]))].into();
    assert!(find_cycle(&acyclic).is_none(), "a -> b has no cycle");
}

#[test]
fn grouped_and_relative_paths_resolve() {
    let known: BTreeSet<ModPath> = [
        vec![],
        vec!["hull".into()],
        vec!["hull".into(), "build".into()],
        vec!["hull".into(), "edges".into()],
        vec!["topo".into()],
    ]
    .into();
    let from = vec!["hull".to_owned(), "build".to_owned()];
    let src = "use super::edges::{EdgeInfo, FaceEdges};\nuse crate::{topo::Topology, error::Error};\n// use crate::nothing;\n";
    let got = uses(&from, src, &known);
    assert!(
        got.contains(&vec!["hull".to_owned(), "edges".to_owned()]),
        "{got:?}"
    );
    assert!(got.contains(&vec!["topo".to_owned()]), "{got:?}");
    assert!(
        !got.iter().any(|m| m.contains(&"nothing".to_owned())),
        "comments skipped: {got:?}"
    );
}
