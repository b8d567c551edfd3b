//! Spectra and artificial accelerograms (SPEC §8): response spectra, Fourier spectra, intensity
//! measures, accelerogram files.

pub mod fourier;
pub mod intensity;
pub mod records;
pub mod response;
pub mod stage;
pub mod tables;
