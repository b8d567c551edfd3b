//! Comparing the tables of two output folders (e.g. a plain ensemble and a merged set of shards).

use std::path::{Path, PathBuf};

use crate::error::StoreError;
use crate::io::read_parquet;
use crate::layout::Folder;

/// Every Parquet file under `dir`, relative to it, sorted (hidden files skipped).
fn parquet_files(dir: &Path) -> Vec<PathBuf> {
    fn walk(base: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
        for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
            let p = e.path();
            let hidden = e.file_name().to_string_lossy().starts_with('.');
            if p.is_dir() {
                walk(base, &p, out);
            } else if !hidden && p.extension().is_some_and(|x| x == "parquet") {
                out.push(p.strip_prefix(base).expect("under base").to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

/// Differences between the tables of the output folders `a` and `b` (files present in one only,
/// or with other contents), ignoring the columns in `ignore`; empty when they hold the same
/// tables. A folder that does not exist, or is not the output of a pipeline, is refused.
pub fn compare_tables(a: &Path, b: &Path, ignore: &[&str]) -> Result<Vec<String>, StoreError> {
    for dir in [a, b] {
        let folder = Folder::new(dir);
        folder.require_output()?;
        if parquet_files(&folder.tables()).is_empty() {
            return Err(StoreError::NotAnOutput { path: dir.to_path_buf(), what: "no tables in tables/".into() });
        }
    }
    let (fa, fb) = (parquet_files(&a.join("tables")), parquet_files(&b.join("tables")));
    let mut diffs = Vec::new();
    for f in fa.iter().filter(|f| !fb.contains(f)) {
        diffs.push(format!("only in {}: tables/{}", a.display(), f.display()));
    }
    for f in fb.iter().filter(|f| !fa.contains(f)) {
        diffs.push(format!("only in {}: tables/{}", b.display(), f.display()));
    }
    for f in fa.iter().filter(|f| fb.contains(f)) {
        let mut x = read_parquet(&a.join("tables").join(f))?;
        let mut y = read_parquet(&b.join("tables").join(f))?;
        for c in ignore {
            if x.column(c).is_ok() && y.column(c).is_ok() {
                x = x.drop(c).map_err(|e| StoreError::table(f.display().to_string(), e))?;
                y = y.drop(c).map_err(|e| StoreError::table(f.display().to_string(), e))?;
            }
        }
        if !x.equals_missing(&y) {
            diffs.push(format!("tables/{} differs ({} vs {} rows)", f.display(), x.height(), y.height()));
        }
    }
    Ok(diffs)
}
