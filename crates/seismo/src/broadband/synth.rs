//! One stochastic realization of a target Fourier amplitude spectrum (Boore 2003, §"Simulation
//! of time series"): Gaussian white noise, shaped in time by a window, transformed, normalised so
//! that its mean squared amplitude spectrum is 1, multiplied by the target amplitude spectrum and
//! transformed back.
//!
//! With `N_j` the DFT of the windowed noise and `N'_j = N_j/√(mean_j |N_j|²)`, the record's DFT is
//! `X_j = A(f_j)·N'_j/Δt`, so that its Fourier amplitude `Δt·|X_j|` is `A(f_j)` on average over
//! realizations and `∫x²dt = 2∫A²df` (Parseval) — the energy random-vibration theory assigns to the
//! same spectrum. The target is real (zero phase): the shaping spreads the window's start and end
//! over the impulse response of `A`, so the window sits `lead` samples into a longer, zero-padded
//! buffer that holds that spread on both sides.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use rand::Rng;
use rand_distr::{Distribution, StandardNormal};
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

pub(crate) use crate::accelerogram::processing::fast_len as fft_length;

/// The forward and inverse FFT of one length, planned once for the whole process by a planner of
/// their own: whichever thread plans a length first, every thread uses the same plan, so a
/// realization has the same bits on any number of threads.
pub(crate) fn plans(n: usize) -> (Arc<dyn Fft<f64>>, Arc<dyn Fft<f64>>) {
    type Plans = HashMap<usize, (Arc<dyn Fft<f64>>, Arc<dyn Fft<f64>>)>;
    static PLANS: OnceLock<Mutex<Plans>> = OnceLock::new();
    let mut kept = PLANS.get_or_init(Default::default).lock().unwrap_or_else(|p| p.into_inner());
    kept.entry(n)
        .or_insert_with(|| {
            let mut planner = FftPlanner::new();
            (planner.plan_fft_forward(n), planner.plan_fft_inverse(n))
        })
        .clone()
}

/// The frequencies (Hz) of the bins `0 ..= len/2` of a buffer of `len` samples at `dt`, at which
/// [`realization`] reads its target.
pub fn bin_frequencies(len: usize, dt: f64) -> impl Iterator<Item = f64> {
    let df = 1.0 / (len as f64 * dt);
    (0..=len / 2).map(move |j| j as f64 * df)
}

/// One realization: `len` samples at `dt` whose Fourier amplitude follows `amplitude` (m/s for an
/// acceleration in m/s²), given at the bins `0 ..= len/2` ([`bin_frequencies`]), under the
/// envelope `window`, which starts at sample `lead`. `len` must hold `lead + window.len()`; the
/// noise is drawn from `rng`, one standard normal per window sample, in order.
pub fn realization(
    window: &[f64],
    lead: usize,
    len: usize,
    dt: f64,
    amplitude: &[f64],
    rng: &mut impl Rng,
) -> Vec<f64> {
    assert_eq!(amplitude.len(), len / 2 + 1, "one amplitude per bin from 0 to len/2");
    assert!(lead + window.len() <= len, "the window fits in the buffer");
    let mut buf = vec![Complex::new(0.0, 0.0); len];
    for (b, w) in buf[lead..].iter_mut().zip(window) {
        let z: f64 = StandardNormal.sample(rng);
        b.re = z * w;
    }
    let (forward, inverse) = plans(len);
    forward.process(&mut buf);
    let mean_square = buf.iter().map(|c| c.norm_sqr()).sum::<f64>() / len as f64;
    if !(mean_square > 0.0) {
        return vec![0.0; len];
    }
    // X_j = A(f_j)·N_j/√(mean |N|²)/Δt, and the inverse DFT's 1/len.
    let scale = 1.0 / (mean_square.sqrt() * dt * len as f64);
    for (j, c) in buf.iter_mut().enumerate() {
        *c *= amplitude[j.min(len - j)] * scale;
    }
    inverse.process(&mut buf);
    buf.iter().map(|c| c.re).collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand::rngs::ChaCha8Rng;

    #[test]
    fn the_energy_is_that_of_the_target_spectrum() {
        // Parseval: ∫x²dt = 2∫A²df whatever the realization (the noise spectrum is normalised per
        // realization), for a flat target between 1 and 10 Hz.
        let (dt, len) = (0.01, 4096);
        let window = crate::broadband::window::SaragoniHart::default().samples(5.0, dt);
        let a: Vec<f64> = bin_frequencies(len, dt).map(|f| if (1.0..=10.0).contains(&f) { 0.3 } else { 0.0 }).collect();
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let runs = 20;
        let energy: f64 = (0..runs)
            .map(|_| realization(&window, 500, len, dt, &a, &mut rng).iter().map(|v| v * v).sum::<f64>() * dt)
            .sum::<f64>()
            / runs as f64;
        let df = 1.0 / (len as f64 * dt);
        // Bins j and len − j (the negative frequency) each carry A²·df.
        let target: f64 = (0..len).map(|j| a[j.min(len - j)].powi(2)).sum::<f64>() * df;
        // The normalisation is over every bin and the band holds 18% of them, so one realization's
        // energy in the band scatters by several per cent (about 180 independent bins: the window
        // of 10 s correlates neighbouring bins); the mean of 20 within about 2%.
        assert!((energy / target - 1.0).abs() < 0.05, "{energy} vs {target}");
    }

    #[test]
    fn the_same_generator_gives_the_same_bits() {
        let window = crate::broadband::window::SaragoniHart::default().samples(2.0, 0.01);
        let run = || {
            let mut rng = ChaCha8Rng::seed_from_u64(42);
            let a: Vec<f64> = bin_frequencies(1024, 0.01).map(|f| f / (1.0 + f * f)).collect();
            realization(&window, 100, 1024, 0.01, &a, &mut rng)
        };
        assert_eq!(run(), run());
    }
}
