//! Every table of an output folder: each is declared once, with its columns and (for a per-seed
//! table) its writer, in its module of [`crate::tables`], and listed once, in
//! [`crate::tables::TABLES`]; writers and readers use those declarations and the column constants
//! of [`col`], never literals.

pub use crate::col;
pub use crate::spec::{Scope, SeedTable, SeedView, SeedWriter, Table, TableSpec};
pub use crate::tables::broadband::STATION_RECORDS;
pub use crate::tables::catalogue::{
    AFTERSHOCKS_TABLE, B_VALUES, CATALOGUE, MAGNITUDE_FREQUENCY, OMORI, RECURRENCE_STATS, SCALING,
};
pub use crate::tables::cracks::{ACOUSTIC_EMISSION, CRACKS};
pub use crate::tables::events::{EVENTS_TABLE, SIMILARITY, SUB_EVENTS_TABLE};
pub use crate::tables::fronts::{RUPTURE_ONSETS, RUPTURES};
pub use crate::tables::gmm::{GMM_BIAS, GMM_PART_B, GMM_RESIDUALS};
pub use crate::tables::records::{ACCELEROGRAMS, ATTENUATION, INTENSITY, RECORDS};
pub use crate::tables::runs::RUNS;
pub use crate::tables::series::{CONTROL, FAULT, FAULT_STATION_SERIES, SERIES, SKIPS};
pub use crate::tables::set::SET;
pub use crate::tables::source::{FAULT_NODES, SOURCE, STATION_SPECTRA, STATIONS};
pub use crate::tables::spectra::{FOURIER, ROTD, SPECTRA};
pub use crate::tables::stats::{ATTENUATION_FIT, PSA_STATS, SUMMARY};
use crate::tables::{TABLES, specs};

/// Every table, in the order the README documents them (that of [`crate::tables::TABLES`]).
pub const ALL: [TableSpec; TABLES.len()] = specs(&TABLES);

/// Per-seed tables in the order a seed's parts are written: `runs` last, so a seed counts as
/// finished when its `runs` part exists.
pub fn seed_tables() -> impl Iterator<Item = TableSpec> {
    ALL.into_iter().filter(|t| t.scope != Scope::AcrossSeeds && *t != RUNS).chain([RUNS])
}

/// Tables gathered over the seeds into one file each, in the order they are gathered.
pub fn gathered() -> impl Iterator<Item = TableSpec> {
    ALL.into_iter().filter(|t| t.scope == Scope::Gathered)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_is_consistent() {
        let mut names: Vec<&str> = ALL.iter().map(|t| t.name).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), ALL.len(), "table names are unique");
        for t in ALL {
            for k in t.key {
                assert!(t.columns.contains(k) || t.variable.is_some(), "{}: key {k} is a column", t.name);
            }
            let per_seed = t.scope != Scope::AcrossSeeds;
            assert_eq!(
                per_seed,
                seed_tables().any(|s| s == t),
                "{} is a per-seed table exactly when it has parts",
                t.name
            );
            assert_eq!(
                t.scope == Scope::Gathered,
                gathered().any(|s| s == t),
                "{} is gathered exactly when so declared",
                t.name
            );
            if per_seed {
                assert_eq!(t.columns[0], col::SEED, "{}: per-seed tables start with seed", t.name);
            }
        }
        assert_eq!(seed_tables().last(), Some(RUNS), "runs is written last");
        let written: Vec<TableSpec> = crate::tables::SEED_TABLES.iter().map(|t| t.spec).chain([RUNS]).collect();
        assert_eq!(written, seed_tables().collect::<Vec<_>>(), "every per-seed table has its writer, in order");
    }
}
