//! stickslip analysis: pipelines, tables (Parquet), and everything done with finished runs.
#![deny(missing_docs)]

pub mod error;
pub mod events;
pub mod pipeline;
pub mod tables;

pub use error::AnalysisError;
pub use pipeline::Pipeline;
