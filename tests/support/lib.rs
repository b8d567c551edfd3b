//! Helpers shared by the whole-product tests in `tests/` and the crates' tests that run pipelines.

use std::path::{Path, PathBuf};

use stickslip_config::PipelineFile;
use stickslip_solver::Scene;

/// polars, for the tests that read the product's Parquet tables back (the command line's crate
/// has no polars of its own: it prints what the store and the ensemble read).
pub use polars;

/// The repository root.
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A path inside the repository.
pub fn repo_path(rel: &str) -> PathBuf {
    repo_root().join(rel)
}

/// A validated scene from the default pipeline file (the paper scene) changed by `edit`.
pub fn scene_with(edit: impl FnOnce(&mut PipelineFile)) -> Scene {
    let mut file = PipelineFile::default();
    edit(&mut file);
    file.scene().expect("test scene is valid")
}

/// A fresh empty folder under the system temp dir, unique per test name and process, removed
/// when the returned guard is dropped, unless the test is failing (then it is kept, and its path
/// printed, to look into). It reads as a `Path` (`dir.join(..)`, `&dir`).
pub fn scratch_dir(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("stickslip-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    Scratch(dir)
}

/// A test's scratch folder (see [`scratch_dir`]).
#[derive(Debug)]
pub struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("kept for a look: {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// Every file under `dir` (recursively), as paths relative to `dir`, sorted.
pub fn files_under(dir: &std::path::Path) -> Vec<PathBuf> {
    fn walk(base: &std::path::Path, dir: &std::path::Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
            let p = entry.path();
            if p.is_dir() {
                walk(base, &p, out);
            } else {
                out.push(p.strip_prefix(base).unwrap().to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

/// Every Parquet file under `dir` (recursively), as paths relative to `dir`, sorted.
pub fn parquet_files(dir: &std::path::Path) -> Vec<PathBuf> {
    files_under(dir).into_iter().filter(|p| p.extension().is_some_and(|e| e == "parquet")).collect()
}

/// Reads a Parquet file.
pub fn read_table(path: &std::path::Path) -> polars::prelude::DataFrame {
    use polars::prelude::*;
    ParquetReader::new(std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
        .finish()
        .unwrap()
}

/// Asserts that two output folders hold the same Parquet files with equal contents, ignoring
/// the columns in `ignore` (e.g. wall times).
pub fn assert_same_tables(a: &std::path::Path, b: &std::path::Path, ignore: &[&str]) {
    let files = parquet_files(a);
    assert!(!files.is_empty(), "no tables in {}", a.display());
    assert_eq!(files, parquet_files(b), "different table files in {} and {}", a.display(), b.display());
    for f in &files {
        let mut x = read_table(&a.join(f));
        let mut y = read_table(&b.join(f));
        for col in ignore {
            if x.column(col).is_ok() {
                x = x.drop(col).unwrap();
                y = y.drop(col).unwrap();
            }
        }
        assert!(x.equals_missing(&y), "{} differs:\n{x}\n{y}", f.display());
    }
}

/// The user documentation, relative to the repository's root: `README.md`, then the guide's
/// chapters `docs/guide/*.md` in name order — the files that may hold the blocks
/// `stickslip-bench readme` generates ([`stickslip_lab::readme::block_files`]).
pub fn user_docs() -> Vec<PathBuf> {
    stickslip_lab::readme::block_files(&repo_root()).expect("docs/guide")
}

/// The content of the generated block `key` (between `<!-- generated: KEY (stickslip-bench
/// readme) -->` and `<!-- end: KEY -->`), from whichever of [`user_docs`] holds it, and that
/// file, found as `stickslip-bench readme` finds it; panics when none or more than one does.
pub fn generated_block(key: &str) -> (String, PathBuf) {
    use stickslip_lab::readme::{blocks, locate, read_docs};
    let docs = read_docs(&repo_root()).expect("read the documentation files");
    let at = locate(&docs).unwrap_or_else(|e| panic!("the generated blocks: {e}"));
    let doc = at
        .get(key)
        .map(|&i| &docs[i])
        .unwrap_or_else(|| panic!("no file of README.md and docs/guide/*.md holds the block {key}"));
    let range = blocks(&doc.text)
        .expect("read once by locate")
        .into_iter()
        .find_map(|(k, r)| (k == key).then_some(r))
        .expect("located there");
    (doc.text[range].to_string(), doc.path.clone())
}

/// A printout with its wall times masked ("in 9.2 s" → "in … s"), as `stickslip-bench readme
/// --check` compares them.
pub use stickslip_lab::readme::untimed;
