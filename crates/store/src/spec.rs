//! What a table is: its name, scope, sort key and columns ([`TableSpec`]); for a per-seed table,
//! the function that makes a seed's part from the seed's analysis ([`SeedTable`]); and a table as
//! the one list of every table holds it ([`Table`]).

use polars::prelude::DataFrame;
use stickslip_analysis::{SeedAnalysis, Settings};
use stickslip_solver::Model;

use crate::error::StoreError;

/// Where a table lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// One part per seed only (`tables/<name>/seed-N.parquet`).
    PerSeed,
    /// One part per seed, gathered over the seeds into `tables/<name>.parquet`.
    Gathered,
    /// Computed across seeds, one file `tables/<name>.parquet`.
    AcrossSeeds,
}

/// A table of the output folder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableSpec {
    /// Name (file or folder name under `tables/`).
    pub name: &'static str,
    /// Where it lives.
    pub scope: Scope,
    /// Sort key of the gathered table.
    pub key: &'static [&'static str],
    /// Columns always written, in order.
    pub columns: &'static [&'static str],
    /// Columns that depend on the pipeline (what is recorded), if any, described.
    pub variable: Option<&'static str>,
}

/// One seed's analysis, as the per-seed tables read it.
#[derive(Clone, Copy)]
pub struct SeedView<'a> {
    /// The seed.
    pub seed: u64,
    /// Its run and what the analysis found in it.
    pub analysis: &'a SeedAnalysis,
    /// The model it ran on.
    pub model: &'a Model,
    /// What the analysis was asked to do.
    pub settings: &'a Settings,
}

/// Makes a seed's part of a table; `None` when the seed has nothing for it (a scene without
/// fronts has no `ruptures` part).
pub type SeedWriter = fn(&SeedView<'_>) -> Result<Option<DataFrame>, StoreError>;

/// A per-seed table: its declaration and its writer.
#[derive(Clone, Copy)]
pub struct SeedTable {
    /// The declaration.
    pub spec: TableSpec,
    /// The writer of a seed's part.
    pub write: SeedWriter,
}

/// A table as the one list of every table ([`crate::tables::TABLES`]) holds it.
#[derive(Clone, Copy)]
pub enum Table {
    /// A per-seed table whose parts a seed's analysis writes.
    Seed(SeedTable),
    /// A table written elsewhere: `runs` (per seed, last, from the seed's outcome) and the tables
    /// computed across seeds.
    Elsewhere(TableSpec),
}

impl Table {
    /// The declaration.
    pub const fn spec(&self) -> TableSpec {
        match self {
            Table::Seed(t) => t.spec,
            Table::Elsewhere(spec) => *spec,
        }
    }
}
