//! Every table of the output folder, one module per subject: each declares its tables
//! ([`crate::spec::TableSpec`]), writes them from typed values and reads them back with their
//! types; a per-seed table's declaration carries its writer ([`crate::spec::SeedTable`]).
//! [`TABLES`] lists every table once, in order: the declarations ([`crate::schema::ALL`]) and the
//! writers of a seed's parts ([`SEED_TABLES`]) are read from it.

pub mod broadband;
pub mod catalogue;
pub mod cracks;
pub mod events;
pub mod fronts;
pub mod gmm;
pub mod records;
pub mod runs;
pub mod series;
pub mod set;
pub mod source;
pub mod spectra;
pub mod stats;

use crate::spec::{SeedTable, Table, TableSpec};

/// Every table, each once, in the order the README documents them ([`crate::schema::ALL`] is
/// their declarations): a per-seed table with its writer, in the order a seed's parts are
/// written ([`SEED_TABLES`]), `runs` first here and written last (from the seed's outcome: see
/// [`crate::seed::write_seed`]).
pub const TABLES: [Table; 38] = [
    Table::Elsewhere(runs::RUNS),
    Table::Seed(series::SERIES_PART),
    Table::Seed(series::CONTROL_PART),
    Table::Seed(series::FAULT_PART),
    Table::Seed(series::FAULT_STATION_SERIES_PART),
    Table::Seed(series::SKIPS_PART),
    Table::Seed(events::EVENTS_PART),
    Table::Seed(events::SUB_EVENTS_PART),
    Table::Seed(events::SIMILARITY_PART),
    Table::Seed(records::RECORDS_PART),
    Table::Seed(records::ACCELEROGRAMS_PART),
    Table::Seed(spectra::SPECTRA_PART),
    Table::Seed(spectra::ROTD_PART),
    Table::Seed(spectra::FOURIER_PART),
    Table::Seed(records::INTENSITY_PART),
    Table::Seed(records::ATTENUATION_PART),
    Table::Seed(fronts::RUPTURES_PART),
    Table::Seed(fronts::RUPTURE_ONSETS_PART),
    Table::Seed(source::SOURCE_PART),
    Table::Seed(source::FAULT_NODES_PART),
    Table::Seed(source::STATIONS_PART),
    Table::Seed(source::STATION_SPECTRA_PART),
    Table::Seed(broadband::STATION_RECORDS_PART),
    Table::Seed(cracks::CRACKS_PART),
    Table::Seed(cracks::ACOUSTIC_EMISSION_PART),
    Table::Elsewhere(stats::SUMMARY),
    Table::Elsewhere(stats::PSA_STATS),
    Table::Elsewhere(stats::ATTENUATION_FIT),
    Table::Elsewhere(set::SET),
    Table::Elsewhere(catalogue::MAGNITUDE_FREQUENCY),
    Table::Elsewhere(catalogue::B_VALUES),
    Table::Elsewhere(catalogue::RECURRENCE_STATS),
    Table::Elsewhere(catalogue::AFTERSHOCKS_TABLE),
    Table::Elsewhere(catalogue::OMORI),
    Table::Elsewhere(catalogue::SCALING),
    Table::Elsewhere(gmm::GMM_RESIDUALS),
    Table::Elsewhere(gmm::GMM_BIAS),
    Table::Elsewhere(gmm::GMM_PART_B),
];

/// Every per-seed table but `runs`, with its writer, in the order of [`TABLES`].
pub const SEED_TABLES: [SeedTable; seed_count(&TABLES)] = seed_writers(&TABLES);

/// The declarations of `tables`, in order.
pub const fn specs<const N: usize>(tables: &[Table; N]) -> [TableSpec; N] {
    let mut out = [runs::RUNS; N];
    let mut i = 0;
    while i < N {
        out[i] = tables[i].spec();
        i += 1;
    }
    out
}

/// How many of `tables` a seed's analysis writes.
const fn seed_count(tables: &[Table]) -> usize {
    let mut n = 0;
    let mut i = 0;
    while i < tables.len() {
        if let Table::Seed(_) = tables[i] {
            n += 1;
        }
        i += 1;
    }
    n
}

/// The writers of `tables` (`N` of them), in order.
const fn seed_writers<const N: usize>(tables: &[Table]) -> [SeedTable; N] {
    // Every slot is overwritten below; `runs` with no writer only fills the array meanwhile.
    let mut out = [SeedTable { spec: runs::RUNS, write: |_| Ok(None) }; N];
    let (mut i, mut n) = (0, 0);
    while i < tables.len() {
        if let Table::Seed(t) = tables[i] {
            out[n] = t;
            n += 1;
        }
        i += 1;
    }
    assert!(n == N, "one writer per per-seed table");
    out
}
