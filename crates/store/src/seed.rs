//! Writing one seed: its fault station files and record files, every per-seed table from its
//! analysis ([`crate::tables::SEED_TABLES`]), then its `runs` row last — a seed counts as
//! finished when that part exists.

use polars::prelude::DataFrame;

use crate::error::StoreError;
use crate::files::{self, Stamp};
use crate::io::write_parquet_atomic;
use crate::layout::Folder;
use crate::spec::{SeedView, TableSpec};
use crate::tables::SEED_TABLES;
use crate::tables::runs::{self, RUNS, RunFacts, RunRow};

/// Writes every part and file of a seed that ran, `runs` last; each part written is handed to
/// `keep` (as written) for whoever gathers the seeds without reading them back.
pub fn write_seed(
    out: &Folder,
    view: &SeedView<'_>,
    stamp: &Stamp<'_>,
    wall_time_s: f64,
    keep: &mut dyn FnMut(&TableSpec, DataFrame),
) -> Result<(), StoreError> {
    files::stations::write(out, view, stamp)?;
    files::scec::write(out, view, stamp)?;
    files::records::write(out, view, stamp)?;
    for table in &SEED_TABLES {
        if let Some(mut df) = (table.write)(view)? {
            write_parquet_atomic(&mut df, &out.part(&table.spec, view.seed))?;
            keep(&table.spec, df);
        }
    }
    let a = view.analysis;
    let row = RunRow { seed: view.seed, outcome: Ok(RunFacts::of(&a.run, &a.catalogue)), wall_time_s };
    let mut df = runs::frame(&[row], stamp.hash)?;
    write_parquet_atomic(&mut df, &out.part(&RUNS, view.seed))?;
    keep(&RUNS, df);
    Ok(())
}

/// Writes the `runs` row of a seed that failed with `message` (handed to `keep` as written).
pub fn write_failed(
    out: &Folder,
    seed: u64,
    message: &str,
    hash: &str,
    wall_time_s: f64,
    keep: &mut dyn FnMut(&TableSpec, DataFrame),
) -> Result<(), StoreError> {
    let row = RunRow { seed, outcome: Err(message.to_string()), wall_time_s };
    let mut df = runs::frame(&[row], hash)?;
    write_parquet_atomic(&mut df, &out.part(&RUNS, seed))?;
    keep(&RUNS, df);
    Ok(())
}
