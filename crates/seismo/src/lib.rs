//! stickslip seismo: the seismology numerics of the product, on plain arrays.
//!
//! Owns: event detection and measures ([`events`]), similarity scaling and magnitudes
//! ([`similarity`]), statistics of samples across seeds ([`stats`]), least-squares fits
//! ([`fit`]), response and Fourier spectra and intensity measures ([`spectra`]), and the
//! accelerogram file formats ([`accelerogram`]).
//!
//! Must not know: the solver, the pipeline file, tables or figures. Every function takes slices
//! and plain parameter structs, so it can be used on any record, simulated or recorded; the
//! equations are in each module's documentation and in `docs/model.md`.
#![deny(missing_docs)]

pub mod accelerogram;
pub mod error;
pub mod events;
pub mod fit;
pub mod similarity;
pub mod spectra;
pub mod stats;

pub use error::SeismoError;
