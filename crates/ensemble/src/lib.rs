//! stickslip ensemble: many seeds of a pipeline, from the solver to the output folder.
//!
//! Owns: running seeds in parallel, batched side by side, each analysed
//! ([`stickslip_analysis::analyse`]) and written ([`stickslip_store::seed`]) as it finishes
//! ([`run`]); resuming an interrupted ensemble, shards and their merge ([`merge`]); stopping once
//! a statistic is precise enough ([`precision`]); gathering the tables and the statistics across
//! seeds ([`gather`], [`summary`], [`catalogue`]), a fault scenario's stations against the
//! ground-motion models ([`gmm`]) and the record set ([`set`]); the folder in seismology's exchange
//! formats, StationXML, QuakeML and MiniSEED ([`exchange`]); what a finished run says when it
//! closes ([`digest`]), what a pipeline will build and cost before it runs ([`check`], [`budget`]) and one main shock seed by seed ([`seed_table`]), read from its tables for
//! the command line to print. Must not know: how one seed is analysed or written, the pipeline
//! file's syntax (it takes a validated [`stickslip_config::Pipeline`]), figures, the command line.
#![deny(missing_docs)]

pub mod budget;
pub mod catalogue;
pub mod check;
pub mod checkpoints;
pub mod cycle_catalogue;
pub mod cycles;
pub mod digest;
pub mod error;
pub mod exchange;
pub mod gather;
pub mod gmm;
pub mod merge;
pub mod precision;
pub mod run;
pub mod scenario_set;
pub mod seed_table;
pub mod set;
mod set_pool;
pub mod split;
pub mod summary;

pub use error::EnsembleError;
pub use run::{EnsembleOptions, EnsembleReport, Profile, run_ensemble, shard};
