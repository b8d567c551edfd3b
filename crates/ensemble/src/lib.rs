//! stickslip ensemble: many seeds of a pipeline, from the solver to the output folder.
//!
//! Owns: running seeds in parallel, batched side by side ([`run`]); analysing each seed — events,
//! similarity scaling, records and their spectra — and writing its parts and files as it
//! finishes ([`seed`], [`records`]); the rupture front of each event ([`fronts`]);
//! resuming an interrupted ensemble, shards and their merge ([`merge`]); gathering the tables and
//! the statistics across seeds ([`gather`], [`summary`]). Must not know: the pipeline file's
//! syntax (it takes a validated [`stickslip_config::Pipeline`]), figures, the command line.
#![deny(missing_docs)]

pub mod catalogue;
pub mod error;
pub mod fronts;
pub mod gather;
pub mod merge;
pub mod precision;
pub mod records;
pub mod run;
pub mod seed;
pub mod set;
pub mod summary;

pub use error::EnsembleError;
pub use run::{EnsembleOptions, EnsembleReport, run_ensemble, shard};
