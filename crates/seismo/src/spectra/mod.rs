//! Spectra of acceleration records (docs/model.md §8): elastic response spectra with exact peaks
//! ([`response`], one oscillator's exact step in [`oscillator`]), the orientation-independent
//! RotD50/RotD100 of two horizontal components ([`rotd`]), Fourier amplitude spectra and
//! intensity measures.

pub mod fourier;
pub mod intensity;
pub mod oscillator;
pub mod response;
pub mod rotd;

use rustfft::FftPlanner;

use fourier::{FourierSpectrum, Window, fourier_amplitude};
use intensity::{Baseline, Intensity, intensity};
use response::{Reading, SpectrumError, SpectrumPlan, SpectrumScratch};

/// Everything the product computes of one accelerogram.
#[derive(Clone, Debug)]
pub struct RecordSpectra {
    /// Spectral displacement SD (m for m/s² input), damping-major over `periods`.
    pub sd: Vec<f64>,
    /// Fourier amplitude spectrum.
    pub fourier: FourierSpectrum,
    /// Intensity measures.
    pub intensity: Intensity,
}

impl RecordSpectra {
    /// The response spectra at `periods` and `dampings` (read as `reading`), the Fourier
    /// spectrum (with `window`) and the intensity measures (with `baseline`) of `accel` sampled
    /// every `dt` seconds.
    pub fn compute(
        accel: &[f64],
        dt: f64,
        periods: &[f64],
        dampings: &[f64],
        reading: Reading,
        baseline: Baseline,
        window: Window,
    ) -> Result<RecordSpectra, SpectrumError> {
        let plan = SpectrumPlan::new(dt, periods, dampings, reading, 16)?;
        let mut sd = vec![0.0; plan.len()];
        plan.compute(accel, &mut SpectrumScratch::default(), &mut sd)?;
        Ok(RecordSpectra {
            sd,
            fourier: fourier_amplitude(accel, dt, window, &mut FftPlanner::new()),
            intensity: intensity(accel, dt, baseline),
        })
    }
}
