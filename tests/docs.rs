//! The documentation holds together: every relative link of `README.md`, `ARCHITECTURE.md`,
//! `BENCHMARKS.md` and `docs/**/*.md` resolves to a file of the clone, every `#anchor` to a
//! heading of its target (GitHub's anchors), and the guide's index (`docs/guide/README.md`) lists
//! every chapter of `docs/guide/`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use stickslip_support::{repo_path, repo_root};

/// The Markdown files checked, relative to the repository's root.
fn documents() -> Vec<PathBuf> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).expect("read a folder of docs/").flatten() {
            let path = entry.path();
            if path.is_dir() {
                walk(&path, out);
            } else if path.extension().is_some_and(|x| x == "md") {
                out.push(path.strip_prefix(repo_root()).expect("under the root").to_path_buf());
            }
        }
    }
    let mut docs = Vec::new();
    walk(&repo_path("docs"), &mut docs);
    docs.sort();
    let mut all: Vec<PathBuf> = ["README.md", "ARCHITECTURE.md", "BENCHMARKS.md"].iter().map(PathBuf::from).collect();
    all.extend(docs);
    all
}

/// `text` without its code: fenced blocks blanked (their lines kept, so line numbers hold) and
/// inline code spans removed.
fn prose(text: &str) -> String {
    let mut out = String::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            out.push('\n');
            continue;
        }
        if !fenced {
            // Inline code: every other backtick-delimited piece.
            for (i, piece) in line.split('`').enumerate() {
                if i % 2 == 0 {
                    out.push_str(piece);
                }
            }
        }
        out.push('\n');
    }
    out
}

/// GitHub's anchor of a heading's text: its rendered text (link targets and code marks dropped)
/// in lower case, letters, digits, `-` and `_` kept, each space turned into `-`, everything else
/// (punctuation, symbols such as `§` or `×`) dropped.
fn slug(heading: &str) -> String {
    let mut text = String::new();
    let mut rest = heading;
    // `[text](target)` renders as `text`.
    while let Some(i) = rest.find("](") {
        let Some(j) = rest[i..].find(')') else { break };
        text.push_str(&rest[..i]);
        rest = &rest[i + j + 1..];
    }
    text.push_str(rest);
    text.trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            '-' | '_' => Some(c),
            c if c.is_alphanumeric() => Some(c),
            _ => None,
        })
        .collect()
}

/// The anchors of a Markdown text: one per heading outside code, a repeated one suffixed `-1`,
/// `-2`, … as GitHub does.
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        let hashes = line.chars().take_while(|&c| c == '#').count();
        if fenced || hashes == 0 || hashes > 6 || !line[hashes..].starts_with(' ') {
            continue;
        }
        let base = slug(line[hashes..].trim().trim_end_matches('#'));
        let mut anchor = base.clone();
        let mut n = 0;
        while seen.contains(&anchor) {
            n += 1;
            anchor = format!("{base}-{n}");
        }
        seen.insert(anchor);
    }
    seen
}

/// The targets of the Markdown links and images (`[text](target)`, `![alt](target)`) of `text`
/// outside code, each with its line number, title dropped.
fn links(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let prose = prose(text);
    let mut at = 0;
    while let Some(i) = prose[at..].find("](") {
        let start = at + i + 2;
        let Some(len) = prose[start..].find(')') else { break };
        let target = prose[start..start + len].split_whitespace().next().unwrap_or("");
        let target = target.trim_start_matches('<').trim_end_matches('>');
        let line = prose[..start].matches('\n').count() + 1;
        out.push((line, target.to_string()));
        at = start + len;
    }
    out
}

#[test]
fn slugs_follow_github() {
    // Anchors the repository's documents already link to.
    assert_eq!(slug("1. The lattice (LDEM cubic truss)"), "1-the-lattice-ldem-cubic-truss");
    assert_eq!(
        slug("3. Heterogeneity: Weibull random Young's modulus"),
        "3-heterogeneity-weibull-random-youngs-modulus"
    );
    assert_eq!(slug("Events (docs/model.md §7)"), "events-docsmodelmd-7");
    assert_eq!(slug("The paper's block, kept seated"), "the-papers-block-kept-seated");
    assert_eq!(
        slug("8. Large lattices: memory, set-up and speed at size"),
        "8-large-lattices-memory-set-up-and-speed-at-size"
    );
    assert_eq!(slug("`slip_rate` and [a link](x.md)"), "slip_rate-and-a-link");
    let a = anchors("# A\n\n## B\n```\n# not a heading\n```\n## B\n#not a heading either\n");
    assert_eq!(a.into_iter().collect::<Vec<_>>(), ["a", "b", "b-1"]);
    let l = links("[a](x.md#y) `[b](code.md)` ![c](p.png \"title\")\n```\n[d](e.md)\n```\n[f](<g h.md>)");
    assert_eq!(l, [(1, "x.md#y".to_string()), (1, "p.png".to_string()), (5, "g".to_string())]);
}

#[test]
fn every_relative_link_and_anchor_of_the_documentation_resolves() {
    let docs = documents();
    assert!(docs.iter().any(|d| d == Path::new("docs/guide/README.md")), "{docs:?}");
    let mut checked = 0;
    let mut broken = Vec::new();
    for doc in &docs {
        let text = std::fs::read_to_string(repo_path(doc.to_str().unwrap())).unwrap();
        for (line, target) in links(&text) {
            if target.contains("://") || target.starts_with("mailto:") || target.is_empty() {
                continue;
            }
            let (path, anchor) = target.split_once('#').unwrap_or((&target, ""));
            let file = if path.is_empty() {
                repo_root().join(doc)
            } else {
                repo_root().join(doc).parent().unwrap().join(path)
            };
            checked += 1;
            if !file.exists() {
                broken.push(format!("{}:{line}: {target} (no {})", doc.display(), file.display()));
                continue;
            }
            if anchor.is_empty() {
                continue;
            }
            let headings = match std::fs::read_to_string(&file) {
                Ok(t) if file.extension().is_some_and(|x| x == "md") => anchors(&t),
                _ => {
                    broken.push(format!(
                        "{}:{line}: {target} (an anchor into a file that is not Markdown)",
                        doc.display()
                    ));
                    continue;
                }
            };
            if !headings.contains(anchor) {
                broken.push(format!("{}:{line}: {target} (no heading #{anchor} in {})", doc.display(), file.display()));
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
    assert!(checked > 50, "only {checked} links checked");
}

#[test]
fn the_guide_index_lists_every_chapter() {
    let index = std::fs::read_to_string(repo_path("docs/guide/README.md")).unwrap();
    let listed: BTreeSet<String> =
        links(&index).into_iter().map(|(_, t)| t.split('#').next().unwrap().to_string()).collect();
    let mut chapters = 0;
    for entry in std::fs::read_dir(repo_path("docs/guide")).unwrap().flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if name.ends_with(".md") && name != "README.md" {
            chapters += 1;
            assert!(listed.contains(&name), "docs/guide/README.md does not list the chapter {name}");
        }
    }
    assert!(chapters >= 9, "only {chapters} chapters in docs/guide/");
    let readme = std::fs::read_to_string(repo_path("README.md")).unwrap();
    assert!(readme.contains("(docs/guide/README.md)"), "the README links to the guide's index");
}
