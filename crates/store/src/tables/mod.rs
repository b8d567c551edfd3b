//! Every table of the output folder, one module per subject: each declares its tables
//! ([`crate::spec::TableSpec`]), writes them from typed values and reads them back with their
//! types; a per-seed table's declaration carries its writer ([`crate::spec::SeedTable`]), and
//! [`SEED_TABLES`] lists them in the order a seed's parts are written.

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

use crate::spec::SeedTable;

/// Every per-seed table but `runs` (written last, from the seed's outcome: see
/// [`crate::seed::write_seed`]), in the order of [`crate::schema::ALL`].
pub const SEED_TABLES: [SeedTable; 24] = [
    series::SERIES_PART,
    series::CONTROL_PART,
    series::FAULT_PART,
    series::FAULT_STATION_SERIES_PART,
    series::SKIPS_PART,
    events::EVENTS_PART,
    events::SUB_EVENTS_PART,
    events::SIMILARITY_PART,
    records::RECORDS_PART,
    records::ACCELEROGRAMS_PART,
    spectra::SPECTRA_PART,
    spectra::ROTD_PART,
    spectra::FOURIER_PART,
    records::INTENSITY_PART,
    records::ATTENUATION_PART,
    fronts::RUPTURES_PART,
    fronts::RUPTURE_ONSETS_PART,
    source::SOURCE_PART,
    source::FAULT_NODES_PART,
    source::STATIONS_PART,
    source::STATION_SPECTRA_PART,
    broadband::STATION_RECORDS_PART,
    cracks::CRACKS_PART,
    cracks::ACOUSTIC_EMISSION_PART,
];
