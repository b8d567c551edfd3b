//! `stickslip compare`: do two output folders hold the same tables?

use std::path::PathBuf;

use anyhow::Result;

/// Arguments of `stickslip compare`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// First output folder.
    pub a: PathBuf,
    /// Second output folder.
    pub b: PathBuf,
}

/// `stickslip compare`.
pub fn run(a: Args) -> Result<()> {
    let diffs = stickslip_store::compare::compare_tables(&a.a, &a.b, &["wall_time_s"])?;
    if diffs.is_empty() {
        outln!("{} and {} hold the same tables (wall times aside)", a.a.display(), a.b.display());
        return Ok(());
    }
    for d in &diffs {
        outln!("{d}");
    }
    anyhow::bail!("{} differences between {} and {}", diffs.len(), a.a.display(), a.b.display())
}
