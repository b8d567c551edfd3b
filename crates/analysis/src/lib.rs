//! stickslip analysis: pipelines, tables (Parquet), and everything done with finished runs.
#![deny(missing_docs)]

pub mod bench;
pub mod catalogue;
pub mod compare;
pub mod ensemble;
pub mod error;
pub mod events;
pub mod merge;
pub mod pipeline;
pub mod report;
pub mod similarity;
pub mod spectra;
pub mod stats;
pub mod summary;
pub mod tables;

pub use error::AnalysisError;
pub use pipeline::Pipeline;
