//! The files of a seed beside its tables: its records in every format the pipeline asks for
//! ([`records`]) and its fault stations in the SEAS layout ([`stations`]).

pub mod records;
pub mod stations;

/// What names a seed's files: the pipeline's name and the hash of what determines its results.
#[derive(Clone, Copy, Debug)]
pub struct Stamp<'a> {
    /// The pipeline's name (it starts every record file's name).
    pub pipeline: &'a str,
    /// The pipeline's hash.
    pub hash: &'a str,
}
