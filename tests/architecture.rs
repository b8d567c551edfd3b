//! ARCHITECTURE.md held against the code: every file it names exists, every crate of `crates/`
//! is on its map, and each crate depends only on crates above it in the map's order.

use std::collections::BTreeSet;

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
