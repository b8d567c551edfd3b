//! The files of a seed beside its tables: its records in every format the pipeline asks for
//! ([`records`]) and its fault stations in the SEAS layout ([`stations`]).

pub mod records;
pub mod stations;
