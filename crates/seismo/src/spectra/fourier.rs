//! Fourier amplitude spectrum of a sampled record.
//!
//! Definition: the record (optionally multiplied by a window) is zero-padded to the next power of
//! two `N ≥ n`, `X_k = Σ_i x_i·e^{−2πi·ik/N}`, and the amplitude is `|X_k|·Δt` — the sampled
//! estimate of the continuous Fourier transform, in the record's unit times seconds (m/s for an
//! acceleration in m/s²) — at `f_k = k/(N·Δt)`, `k = 0 … N/2` (one-sided, not doubled). Zero
//! padding interpolates the spectrum; it adds no resolution. The Hann window (`w_i =
//! sin²(πi/(n−1))`) is not renormalised: it lowers amplitudes (by 2 on average for a stationary
//! signal) in exchange for less leakage.

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

/// Window applied before the transform.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Window {
    /// No window.
    Rectangular,
    /// Hann window over the record.
    Hann,
}

/// A one-sided Fourier amplitude spectrum.
#[derive(Clone, Debug, PartialEq)]
pub struct FourierSpectrum {
    /// Frequencies (Hz).
    pub frequency_hz: Vec<f64>,
    /// Amplitudes `|X|·Δt`.
    pub amplitude: Vec<f64>,
}

impl FourierSpectrum {
    /// Keeps the frequencies at or below `f_hz` (a record's usable band ends there: above it
    /// the amplitudes are its filter's roll-off, not the motion).
    pub fn keep_up_to(&mut self, f_hz: f64) {
        let n = self.frequency_hz.partition_point(|&f| f <= f_hz);
        self.frequency_hz.truncate(n);
        self.amplitude.truncate(n);
    }
}

/// Fourier amplitude spectrum of `x` sampled every `dt` seconds.
pub fn fourier_amplitude(x: &[f64], dt: f64, window: Window, planner: &mut FftPlanner<f64>) -> FourierSpectrum {
    let n = x.len();
    if n == 0 {
        return FourierSpectrum { frequency_hz: vec![], amplitude: vec![] };
    }
    let big = n.next_power_of_two();
    let mut buf: Vec<Complex<f64>> = (0..big)
        .map(|i| {
            let w = match window {
                Window::Rectangular => 1.0,
                Window::Hann if n > 1 => (std::f64::consts::PI * i as f64 / (n - 1) as f64).sin().powi(2),
                Window::Hann => 1.0,
            };
            Complex::new(if i < n { x[i] * w } else { 0.0 }, 0.0)
        })
        .collect();
    planner.plan_fft_forward(big).process(&mut buf);
    let half = big / 2;
    FourierSpectrum {
        frequency_hz: (0..=half).map(|k| k as f64 / (big as f64 * dt)).collect(),
        amplitude: buf[..=half].iter().map(|c| c.norm() * dt).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeping_a_band_keeps_its_top_frequency_and_drops_the_rest() {
        let mut planner = FftPlanner::new();
        let mut fs = fourier_amplitude(&[1.0; 16], 0.01, Window::Rectangular, &mut planner);
        assert_eq!(fs.frequency_hz.len(), 9); // 0, 6.25, …, 50 Hz
        let whole = fs.clone();
        fs.keep_up_to(25.0);
        assert_eq!(fs.frequency_hz, &whole.frequency_hz[..5]);
        assert_eq!(fs.amplitude, &whole.amplitude[..5]);
        fs.keep_up_to(24.9);
        assert_eq!(fs.frequency_hz.last(), Some(&18.75));
        fs.keep_up_to(-1.0);
        assert!(fs.frequency_hz.is_empty() && fs.amplitude.is_empty());
    }

    #[test]
    fn sine_peak_and_a_naive_dft_agree() {
        let dt = 0.01;
        let n = 1000;
        // On bin 51 of the padded 1024-point transform.
        let f0 = 51.0 / (1024.0 * dt);
        let a = 2.0;
        let x: Vec<f64> = (0..n).map(|i| a * (2.0 * std::f64::consts::PI * f0 * i as f64 * dt).sin()).collect();
        let s = fourier_amplitude(&x, dt, Window::Rectangular, &mut FftPlanner::new());
        assert_eq!(s.frequency_hz.len(), 1024 / 2 + 1);
        // Against a plain DFT at a few bins.
        for k in [0usize, 7, 51, 200, 512] {
            let (mut re, mut im) = (0.0, 0.0);
            for (i, v) in x.iter().enumerate() {
                let ph = -2.0 * std::f64::consts::PI * (i * k) as f64 / 1024.0;
                re += v * ph.cos();
                im += v * ph.sin();
            }
            let naive = (re * re + im * im).sqrt() * dt;
            assert!((s.amplitude[k] - naive).abs() < 1e-9 * naive.max(1.0), "bin {k}");
        }
        // A sine of amplitude A lasting L seconds peaks at about A·L/2 (leakage of the 1000
        // samples into the padded 1024-point grid keeps it within 2%).
        let peak = s.amplitude.iter().cloned().fold(0.0, f64::max);
        assert!((peak / (a * n as f64 * dt / 2.0) - 1.0).abs() < 0.02, "peak {peak}");
        assert!((s.frequency_hz[51] - f0).abs() < 1e-12);
    }
}
