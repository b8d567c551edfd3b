//! stickslip lab: how fast and how accurate the product is, measured.
//!
//! Owns every benchmark and calibration aid: run time against error ([`accuracy`]), the
//! statistical convergence of event measures over seeds ([`convergence`]), the
//! quasi-static skip-ahead against full integration ([`skip`]), what recording costs
//! ([`recording_cost`]), what a run does before its first step ([`setup_cost`]), what an
//! ensemble costs end to end against a previous build ([`ensemble_cost`]), the LAMMPS
//! side-by-side ([`peer`], with `lammps/compare.sh`), sweeps of assumed values ([`calibrate`]),
//! a fault run against a SCEC dynamic-rupture benchmark ([`scec`]), Part A of the Broadband
//! Platform's validation — a scenario against a real earthquake's recordings ([`part_a`]) — the
//! README's generated outputs, tables and measured numbers ([`readme`]), and the criterion
//! benchmarks of the kernels and spectra (`benches/`). Speed is measured here, never asserted in
//! tests. Must not know: the command line (it returns rows and writes tables and figures where it
//! is told).
#![deny(missing_docs)]

pub mod accuracy;
pub mod broadband_cost;
pub mod calibrate;
pub mod convergence;
pub mod ensemble_cost;
pub mod kernel_scene;
pub mod medium_cost;
pub mod part_a;
pub mod peer;
pub mod readme;
pub mod recording_cost;
pub mod scec;
pub mod setup_cost;
pub mod skip;

use stickslip_config::ConfigError;
use stickslip_report::ReportError;
use stickslip_store::StoreError;

/// Everything that can go wrong in a benchmark.
#[derive(Debug, thiserror::Error)]
pub enum LabError {
    /// A pipeline or variant of it was refused.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// A table could not be written.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// A figure could not be drawn.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// A run failed or the benchmark cannot be set up.
    #[error("{0}")]
    Setup(String),
}
