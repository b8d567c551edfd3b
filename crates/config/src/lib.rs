//! stickslip config: pipeline files (TOML) read and validated into the domain types the other
//! crates take.
//!
//! Owns the one input format of the product: the pipeline file ([`PipelineFile`]), its sections
//! with their documented defaults (the paper scene), one [`Checker`] and one [`ConfigError`] for
//! every section, and the validated [`Pipeline`] — the solver's [`stickslip_solver::Scene`], the
//! analysis's [`stickslip_analysis::Settings`], the record set and the report settings — with the
//! hash that stamps its results. Every refused value names its field, the value and the allowed
//! range, and nothing runs; the solver's messages name physical quantities and [`keys`] names the
//! keys behind them; [`describe`] says what a pipeline builds, section by section, for `stickslip
//! check` to print. Must not know: how a scene is run, tables, figures.
#![deny(missing_docs)]

pub mod accelerograms;
pub mod broadband;
pub mod check;
pub mod cycles;
pub mod describe;
pub mod error;
pub mod friction_map;
pub mod input;
pub mod keys;
mod laws;
pub mod numbers;
pub mod pipeline;
pub mod precision;
pub mod scene;
pub mod sections;
mod seed_fields;
pub mod seeds;
pub mod set;
mod station_band;

pub use check::Checker;
pub use error::{ConfigError, FieldError, Warning};
pub use pipeline::{Pipeline, PipelineFile};
pub use sections::ReportSettings;
pub use set::SetSettings;
