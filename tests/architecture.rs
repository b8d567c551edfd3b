//! ARCHITECTURE.md held against the code: every file it names exists, every crate of `crates/`
//! is on its map, and each crate depends only on crates above it in the map's order. And the
//! house rules of issue 46: no import circle between the modules of a crate, at any level, and no
//! source file over 900 lines.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use stickslip_support::repo_path;

fn architecture() -> String {
    std::fs::read_to_string(repo_path("ARCHITECTURE.md")).expect("ARCHITECTURE.md")
}

/// The crate folders in the order of the map (its first code block).
fn map_order(text: &str) -> Vec<String> {
    let block = text.split("```").nth(1).expect("the map's code block");
    block
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("crates/"))
        .map(|rest| rest.split_whitespace().next().expect("a crate name").to_string())
        .collect()
}

/// The workspace crates (`stickslip-<folder>`) a crate's `[dependencies]` name.
fn dependencies(folder: &str) -> Vec<String> {
    let toml = std::fs::read_to_string(repo_path(&format!("crates/{folder}/Cargo.toml"))).expect("Cargo.toml");
    let deps = toml.split("[dependencies]").nth(1).unwrap_or("");
    let deps = deps.split("\n[").next().unwrap_or("");
    deps.lines()
        .filter_map(|l| l.trim().strip_prefix("stickslip-"))
        .map(|l| l.split(['.', ' ', '=']).next().expect("a name").to_string())
        .collect()
}

#[test]
fn every_crate_depends_only_on_crates_above_it_on_the_map() {
    let order = map_order(&architecture());
    let on_disk: BTreeSet<String> = std::fs::read_dir(repo_path("crates"))
        .expect("crates/")
        .flatten()
        .filter(|e| e.path().join("Cargo.toml").exists())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    let mapped: BTreeSet<String> = order.iter().cloned().collect();
    assert_eq!(mapped, on_disk, "the map names every crate of crates/ once");
    assert_eq!(mapped.len(), order.len(), "no crate is on the map twice");
    for (k, folder) in order.iter().enumerate() {
        for dep in dependencies(folder) {
            let at = order.iter().position(|c| *c == dep).unwrap_or_else(|| panic!("{folder} depends on {dep}"));
            assert!(at < k, "{folder} depends on {dep}, which the map puts below it");
        }
    }
}

#[test]
fn every_file_the_map_names_exists() {
    let text = architecture();
    let mut checked = 0;
    for (k, span) in text.split('`').enumerate() {
        // Odd pieces are inside backticks; code blocks are passed over by the prefix test.
        let path = span.trim_end_matches(['.', ',', ':', ')']);
        let repo_path_like = ["crates/", "pipelines/", "tests/", "docs/"].iter().any(|p| path.starts_with(p));
        if k % 2 == 0 || !repo_path_like || path.contains(['<', ' ', '*']) {
            continue;
        }
        assert!(repo_path(path).exists(), "ARCHITECTURE.md names {path}, which does not exist");
        checked += 1;
    }
    assert!(checked >= 30, "the map names its files ({checked} checked)");
}

/// The longest a source file of `crates/` or `tests/` may be (lines).
const MAX_LINES: usize = 900;

/// Every `.rs` file under `dir`, in a stable order.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n != "target") {
                rust_files(&p, out);
            }
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

#[test]
fn no_source_file_is_over_900_lines() {
    let mut files = Vec::new();
    rust_files(&repo_path("crates"), &mut files);
    rust_files(&repo_path("tests"), &mut files);
    assert!(files.len() > 100, "the sources are found ({} files)", files.len());
    let long: Vec<String> = files
        .iter()
        .map(|f| (f, std::fs::read_to_string(f).expect("a source file").lines().count()))
        .filter(|(_, n)| *n > MAX_LINES)
        .map(|(f, n)| format!("{} ({n} lines)", f.strip_prefix(repo_path("")).unwrap_or(f).display()))
        .collect();
    assert!(long.is_empty(), "files over {MAX_LINES} lines, to split by subject: {}", long.join(", "));
}

/// A module's path inside its crate (`["step", "bars"]`; empty for the crate root).
type Module = Vec<String>;

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The module of a file from its path under `src/` (`a/b.rs` and `a/b/mod.rs` are `a::b`); `None`
/// under `src/bin/` (crates of their own).
fn module_of(rel: &str) -> Option<Module> {
    let mut parts: Module = rel.trim_end_matches(".rs").split('/').map(str::to_string).collect();
    if parts[0] == "bin" {
        return None;
    }
    let last = parts.last().expect("a file name").as_str();
    if last == "mod" || (parts.len() == 1 && (last == "lib" || last == "main")) {
        parts.pop();
    }
    Some(parts)
}

/// The code of a file without comments and with every string and char literal emptied.
fn strip_literals(text: &str) -> String {
    let c: Vec<char> = text.chars().collect();
    let at = |i: usize| c.get(i).copied().unwrap_or('\0');
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < c.len() {
        let prev_ident = i > 0 && is_ident(c[i - 1]);
        if c[i] == '/' && at(i + 1) == '/' {
            while i < c.len() && c[i] != '\n' {
                i += 1;
            }
        } else if c[i] == '/' && at(i + 1) == '*' {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && at(i + 1) == '*' {
                    depth += 1;
                    i += 2;
                } else if c[i] == '*' && at(i + 1) == '/' {
                    depth -= 1;
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    i += 1;
                }
            }
            out.push(' ');
        } else if c[i] == 'r'
            && (!prev_ident || (c[i - 1] == 'b' && (i < 2 || !is_ident(c[i - 2]))))
            && (at(i + 1) == '"'
                || (at(i + 1) == '#' && (i + 1..c.len()).find(|&k| c[k] != '#').is_some_and(|k| c[k] == '"')))
        {
            let mut hashes = 0;
            i += 1;
            while at(i) == '#' {
                hashes += 1;
                i += 1;
            }
            i += 1;
            while i < c.len() && !(c[i] == '"' && (1..=hashes).all(|h| at(i + h) == '#')) {
                i += 1;
            }
            i += 1 + hashes;
            out.push_str("\"\"");
        } else if c[i] == '"' {
            i += 1;
            while i < c.len() && c[i] != '"' {
                i += if c[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("\"\"");
        } else if c[i] == '\'' && (at(i + 1) == '\\' || at(i + 2) == '\'') {
            i += 1;
            while i < c.len() && c[i] != '\'' {
                i += if c[i] == '\\' { 2 } else { 1 };
            }
            i += 1;
            out.push_str("' '");
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// Skips whitespace from byte `i`.
fn skip_space(s: &str, mut i: usize) -> usize {
    while s[i..].starts_with(char::is_whitespace) {
        i += s[i..].chars().next().expect("a char").len_utf8();
    }
    i
}

/// The identifier at byte `i` and the byte after it.
fn ident_at(s: &str, i: usize) -> (&str, usize) {
    let end = s[i..].find(|c: char| !is_ident(c)).map_or(s.len(), |k| i + k);
    (&s[i..end], end)
}

/// The code of a file (comments and literals stripped) without its `#[cfg(test)]` modules, and
/// the names of the test modules it declares in files of their own (`#[cfg(test)] mod tests;`):
/// a test may reach across layers.
fn strip(text: &str) -> (String, Vec<String>) {
    let s = strip_literals(text);
    let (mut out, mut test_files, mut at) = (String::new(), Vec::new(), 0);
    while let Some(k) = s[at..].find("#[cfg(test)]") {
        let start = at + k;
        let mut i = skip_space(&s, start + "#[cfg(test)]".len());
        if s[i..].starts_with("pub") {
            i = skip_space(&s, i + 3);
            if s[i..].starts_with('(') {
                i = skip_space(&s, i + s[i..].find(')').expect("pub(…)") + 1);
            }
        }
        let is_mod = s[i..].starts_with("mod") && !s[i + 3..].starts_with(is_ident);
        if !is_mod {
            out.push_str(&s[at..i]);
            at = i;
            continue;
        }
        let (name, j) = ident_at(&s, skip_space(&s, i + 3));
        let j = skip_space(&s, j);
        out.push_str(&s[at..start]);
        if s[j..].starts_with(';') {
            test_files.push(name.to_string());
            at = j + 1;
        } else {
            let mut depth = 0;
            let mut k = j;
            for (n, ch) in s[j..].char_indices() {
                depth += match ch {
                    '{' => 1,
                    '}' => -1,
                    _ => 0,
                };
                k = j + n + ch.len_utf8();
                if depth == 0 && ch == '}' {
                    break;
                }
            }
            at = k;
        }
    }
    out.push_str(&s[at..]);
    (out, test_files)
}

/// The paths of a `use` tree: `a::{b, c::{D, E as F}}` gives `a::b`, `a::c::D`, `a::c::E`.
fn expand(prefix: &[String], body: &str) -> Vec<Vec<String>> {
    let body = body.trim();
    if body.is_empty() {
        return Vec::new();
    }
    let segments = |s: &str| -> Vec<String> {
        let s = s.split(" as ").next().unwrap_or(s);
        s.split("::").map(str::trim).filter(|x| !x.is_empty()).map(str::to_string).collect()
    };
    let Some(open) = body.find('{') else {
        let mut p = prefix.to_vec();
        p.extend(segments(body));
        return vec![p];
    };
    let mut head = prefix.to_vec();
    head.extend(segments(&body[..open]));
    let inner = &body[open + 1..body.rfind('}').unwrap_or(body.len())];
    let (mut items, mut depth, mut cur) = (Vec::new(), 0, String::new());
    for ch in inner.chars() {
        match ch {
            ',' if depth == 0 => items.push(std::mem::take(&mut cur)),
            _ => {
                depth += match ch {
                    '{' => 1,
                    '}' => -1,
                    _ => 0,
                };
                cur.push(ch);
            }
        }
    }
    items.push(cur);
    items.iter().flat_map(|it| expand(&head, it)).collect()
}

/// The `use` declarations of a file's code: where each starts and ends, its tree, and whether it is
/// `pub` (a re-export).
fn use_declarations(s: &str) -> Vec<(usize, usize, String, bool)> {
    let mut found = Vec::new();
    let mut at = 0;
    while let Some(k) = s[at..].find("use") {
        let i = at + k;
        at = i + 3;
        let bounded = (i == 0 || !s[..i].ends_with(is_ident)) && s[i + 3..].starts_with(char::is_whitespace);
        if !bounded {
            continue;
        }
        let Some(end) = s[i..].find(';').map(|e| i + e) else { break };
        let before = s[..i].trim_end();
        let before = if before.ends_with(')') { before[..before.rfind('(').unwrap_or(0)].trim_end() } else { before };
        let public = before.ends_with("pub") && !before[..before.len() - 3].ends_with(is_ident);
        found.push((i, end, s[i + 3..end].to_string(), public));
        at = end + 1;
    }
    found
}

/// Every path a file's code names (`use` trees expanded, then every `a::b…` elsewhere).
fn references(s: &str) -> Vec<Vec<String>> {
    let uses = use_declarations(s);
    let mut paths: Vec<Vec<String>> = uses.iter().flat_map(|(_, _, tree, _)| expand(&[], tree)).collect();
    let mut body = String::new();
    let mut at = 0;
    for (start, end, _, _) in &uses {
        body.push_str(&s[at..*start]);
        at = end + 1;
    }
    body.push_str(&s[at..]);
    let b = body.as_str();
    let mut i = 0;
    while i < b.len() {
        let ch = b[i..].chars().next().expect("a char");
        let starts =
            is_ident(ch) && !ch.is_ascii_digit() && (i == 0 || !b[..i].ends_with(|c: char| is_ident(c) || c == ':'));
        if !starts {
            i += ch.len_utf8();
            continue;
        }
        let (first, mut j) = ident_at(b, i);
        let mut path = vec![first.to_string()];
        loop {
            let k = skip_space(b, j);
            if !b[k..].starts_with("::") {
                break;
            }
            let k = skip_space(b, k + 2);
            let (next, e) = ident_at(b, k);
            if next.is_empty() {
                break;
            }
            path.push(next.to_string());
            j = e;
        }
        if path.len() > 1 {
            paths.push(path);
        }
        i = j;
    }
    paths
}

/// One crate's import graph between its files: each module (file) and the modules it imports,
/// with the paths that make each import.
struct Graph {
    modules: BTreeSet<Module>,
    edges: BTreeMap<Module, BTreeMap<Module, BTreeSet<String>>>,
}

/// The module a path names from module `start`: the deepest module it passes through, or the
/// module that defines a name re-exported (`pub use`) by the module it reaches.
fn walk(
    modules: &BTreeSet<Module>,
    reexports: &BTreeMap<(Module, String), Vec<String>>,
    start: &Module,
    segments: &[String],
    seen: &mut Vec<(Module, String)>,
) -> Module {
    let mut cur = start.clone();
    for s in segments {
        match s.as_str() {
            "self" => continue,
            "super" => {
                cur.pop();
                continue;
            }
            "crate" => {
                cur.clear();
                continue;
            }
            _ => {}
        }
        let mut child = cur.clone();
        child.push(s.clone());
        if modules.contains(&child) {
            cur = child;
            continue;
        }
        let key = (cur.clone(), s.clone());
        if let Some(p) = reexports.get(&key).filter(|_| !seen.contains(&key)) {
            let mut first = cur.clone();
            first.push(p[0].clone());
            if ["crate", "super", "self"].contains(&p[0].as_str()) || modules.contains(&first) {
                seen.push(key);
                return walk(modules, reexports, &cur, &p[..p.len() - 1], seen);
            }
        }
        break;
    }
    cur
}

/// The import graph of the crate whose sources are in `src`.
fn import_graph(src: &Path) -> Graph {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut code: BTreeMap<Module, String> = BTreeMap::new();
    let mut tests: BTreeSet<Module> = BTreeSet::new();
    for f in &files {
        let rel = f.strip_prefix(src).expect("under src").to_string_lossy().replace('\\', "/");
        let Some(m) = module_of(&rel) else { continue };
        let (text, test_files) = strip(&std::fs::read_to_string(f).expect("a source file"));
        for t in test_files {
            let mut child = m.clone();
            child.push(t);
            tests.insert(child);
        }
        code.insert(m, text);
    }
    code.retain(|m, _| !tests.iter().any(|t| m.starts_with(t)));
    let modules: BTreeSet<Module> = code.keys().cloned().collect();
    let mut reexports = BTreeMap::new();
    for (m, text) in &code {
        for (_, _, tree, public) in use_declarations(text) {
            for p in expand(&[], &tree).into_iter().filter(|_| public) {
                let last = p.last().expect("a path").clone();
                if last != "*" && last != "self" {
                    reexports.insert((m.clone(), last), p);
                }
            }
        }
    }
    let mut edges: BTreeMap<Module, BTreeMap<Module, BTreeSet<String>>> = BTreeMap::new();
    for (m, text) in &code {
        for p in references(text) {
            let mut first = m.clone();
            first.push(p[0].clone());
            if !["crate", "super", "self"].contains(&p[0].as_str()) && !modules.contains(&first) {
                continue;
            }
            let t = walk(&modules, &reexports, m, &p, &mut Vec::new());
            if t != *m && !t.is_empty() {
                edges.entry(m.clone()).or_default().entry(t).or_default().insert(p.join("::"));
            }
        }
    }
    Graph { modules, edges }
}

/// The strongly connected components of more than one node (Tarjan).
fn circles(nodes: &BTreeSet<Module>, edges: &BTreeMap<Module, BTreeSet<Module>>) -> Vec<Vec<Module>> {
    struct Tarjan<'a> {
        edges: &'a BTreeMap<Module, BTreeSet<Module>>,
        index: BTreeMap<Module, usize>,
        low: BTreeMap<Module, usize>,
        stack: Vec<Module>,
        out: Vec<Vec<Module>>,
    }
    impl Tarjan<'_> {
        fn visit(&mut self, v: &Module) {
            let n = self.index.len();
            self.index.insert(v.clone(), n);
            self.low.insert(v.clone(), n);
            self.stack.push(v.clone());
            for w in self.edges.get(v).into_iter().flatten() {
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let low = self.low[v].min(self.low[w]);
                    self.low.insert(v.clone(), low);
                } else if self.stack.contains(w) {
                    let low = self.low[v].min(self.index[w]);
                    self.low.insert(v.clone(), low);
                }
            }
            if self.low[v] == self.index[v] {
                let mut comp = Vec::new();
                loop {
                    let w = self.stack.pop().expect("on the stack");
                    let done = w == *v;
                    comp.push(w);
                    if done {
                        break;
                    }
                }
                if comp.len() > 1 {
                    comp.sort();
                    self.out.push(comp);
                }
            }
        }
    }
    let mut t = Tarjan { edges, index: BTreeMap::new(), low: BTreeMap::new(), stack: Vec::new(), out: Vec::new() };
    for v in nodes {
        if !t.index.contains_key(v) {
            t.visit(v);
        }
    }
    t.out
}

/// Every import circle of a crate, at every level: between the children (each with its whole
/// subtree) of the crate root and of each folder module, the folder's own file (lib.rs, mod.rs)
/// left out — declaring and re-exporting its children is not an import. Each circle is named
/// with the imports that close it.
fn import_circles(crate_dir: &str, g: &Graph) -> Vec<String> {
    let folders: BTreeSet<Module> = g.modules.iter().flat_map(|m| (0..m.len()).map(|k| m[..k].to_vec())).collect();
    let mut found = Vec::new();
    for folder in &folders {
        let n = folder.len();
        let child = |m: &Module| (m.len() > n && m.starts_with(folder)).then(|| m[..=n].to_vec());
        let nodes: BTreeSet<Module> = g.modules.iter().filter_map(child).collect();
        let mut edges: BTreeMap<Module, BTreeSet<Module>> = BTreeMap::new();
        for (m, targets) in &g.edges {
            let Some(a) = child(m) else { continue };
            for t in targets.keys() {
                if let Some(b) = child(t).filter(|b| *b != a) {
                    edges.entry(a.clone()).or_default().insert(b);
                }
            }
        }
        for comp in circles(&nodes, &edges) {
            let names: Vec<String> = comp.iter().map(|c| c[n..].join("/")).collect();
            let mut why = Vec::new();
            for (m, targets) in &g.edges {
                for (t, paths) in targets {
                    let (a, b) = (child(m), child(t));
                    if a.as_ref().is_some_and(|a| comp.contains(a))
                        && b.as_ref().is_some_and(|b| comp.contains(b))
                        && a != b
                    {
                        let paths: Vec<&str> = paths.iter().map(String::as_str).collect();
                        why.push(format!("    {} -> {}: {}", m.join("::"), t.join("::"), paths.join(", ")));
                    }
                }
            }
            found.push(format!(
                "{crate_dir}/src/{}: {}\n{}",
                folder.iter().map(|f| format!("{f}/")).collect::<String>(),
                names.join(" <-> "),
                why.join("\n")
            ));
        }
    }
    found
}

#[test]
fn no_import_circle_between_the_modules_of_a_crate() {
    let mut crates: Vec<PathBuf> = std::fs::read_dir(repo_path("crates"))
        .expect("crates/")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.join("src").is_dir())
        .collect();
    crates.sort();
    assert!(crates.len() >= 10, "the crates are found");
    let (mut found, mut imports) = (Vec::new(), 0);
    for dir in &crates {
        let name = format!("crates/{}", dir.file_name().expect("a folder").to_string_lossy());
        let g = import_graph(&dir.join("src"));
        imports += g.edges.values().map(BTreeMap::len).sum::<usize>();
        found.extend(import_circles(&name, &g));
    }
    assert!(imports > 500, "the imports are read ({imports})");
    assert!(found.is_empty(), "import circles (break each into layers):\n{}", found.join("\n"));
}

#[test]
fn the_import_graph_sees_re_exports_and_circles_inside_a_folder() {
    let dir = std::env::temp_dir().join(format!("stickslip-architecture-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let write = |rel: &str, text: &str| {
        let p = dir.join(rel);
        std::fs::create_dir_all(p.parent().expect("a folder")).expect("mkdir");
        std::fs::write(p, text).expect("write");
    };
    write("lib.rs", "pub mod a;\npub mod b;\npub mod k;\npub use a::A;\n");
    // a → b directly; b → a through the root's re-export of a::A; x ↔ y inside the folder k, the
    // test module and the string left out.
    write("a.rs", "pub struct A;\npub fn f() { crate::b::g(); }\n");
    write("b.rs", "use crate::A; // the root's re-export of a::A\npub fn g() {}\n");
    write("k/mod.rs", "mod x;\nmod y;\npub use x::X;\n");
    write("k/x.rs", "pub struct X;\nfn f() { super::y::g(); }\n#[cfg(test)]\nmod tests { use crate::k::y; }\n");
    write("k/y.rs", "use crate::k::X;\npub fn g() { let s = \"crate::b::g\"; }\n");
    let g = import_graph(&dir);
    let found = import_circles("demo", &g);
    std::fs::remove_dir_all(&dir).expect("clean up");
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].starts_with("demo/src/: a <-> b\n") && found[0].contains("b -> a: crate::A"), "{}", found[0]);
    assert!(
        found[1].starts_with("demo/src/k/: x <-> y\n") && found[1].contains("k::y -> k::x: crate::k::X"),
        "{}",
        found[1]
    );
    let y_imports: Vec<&Module> = g.edges[&vec!["k".to_string(), "y".to_string()]].keys().collect();
    assert_eq!(y_imports, [&vec!["k".to_string(), "x".to_string()]], "a string names nothing");
}
