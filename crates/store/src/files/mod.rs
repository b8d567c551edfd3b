//! The files of a seed beside its tables: its records in every format the pipeline asks for
//! ([`records`]), its fault stations in the SEAS layout ([`stations`]) on the rigid base, and on a
//! fault the SCEC benchmarks' station and rupture-time files ([`scec`]).

pub mod records;
pub mod scec;
pub mod stations;

pub use crate::tables::series::fault_station_file;

/// What names a seed's files: the pipeline's name and the hash of what determines its results.
#[derive(Clone, Copy, Debug)]
pub struct Stamp<'a> {
    /// The pipeline's name (it starts every record file's name).
    pub pipeline: &'a str,
    /// The pipeline's hash.
    pub hash: &'a str,
}
