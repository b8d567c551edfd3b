//! stickslip seismo: the seismology numerics of the product, on plain arrays.
//!
//! Owns: event detection and measures ([`events`]), the statistics of catalogues of events
//! (Gutenberg–Richter, recurrence, aftershocks, scaling: [`catalogue`]), similarity scaling and magnitudes
//! ([`similarity`]), statistics of samples across seeds ([`stats`]), least-squares fits
//! ([`fit`]), response, RotD and Fourier spectra and intensity measures ([`spectra`]),
//! accelerogram processing and file formats ([`accelerogram`]), design spectra ([`design`]), the
//! selection of record sets matched to them ([`selection`]), rupture fronts ([`front`]), SEAS fault
//! station files ([`seas`]), SCEC dynamic-rupture benchmark files ([`scec`]), acoustic-emission
//! clusters of bar breaks ([`emission`]), and the NGA-West2 ground-motion models with fault-to-site
//! distances and the Broadband Platform's validation statistics ([`gmm`]), and broadband records by the
//! Platform's hybrid method ([`broadband`]), and the exchange formats of stations and events:
//! StationXML inventories ([`stationxml`]) and QuakeML catalogues ([`quakeml`]), on the product's
//! nominal clock ([`clock`]).
//!
//! Must not know: the solver, the pipeline file, tables or figures. Every function takes slices
//! and plain parameter structs, so it can be used on any record, simulated or recorded; the
//! equations are in each module's documentation and in `docs/model.md`.
#![deny(missing_docs)]

pub mod accelerogram;
pub mod broadband;
pub mod catalogue;
pub mod clock;
pub mod design;
pub mod emission;
pub mod error;
pub mod events;
pub mod fit;
pub mod front;
pub mod gmm;
pub mod quakeml;
pub mod scec;
pub mod seas;
pub mod selection;
pub mod similarity;
pub mod spectra;
pub mod stationxml;
pub mod stats;
pub mod xml;

pub use error::SeismoError;
