//! The join of a hybrid broadband record (Graves & Pitarka 2010; the Broadband Platform's
//! `match`): the deterministic (lattice) record low-passed and the stochastic one high-passed by
//! matched zero-phase Butterworth filters, then added.
//!
//! The Platform filters each part forward and backward with a 4th-order Butterworth filter, whose
//! gain is the square of one pass, `1/(1 + (f/f_c)^(2n))`, and moves the corners so that both
//! gains are `1/√2` at the crossover `f_m`: `f_lp = f_m·(√2 − 1)^(−1/(2n))` and
//! `f_hp = f_m·(√2 − 1)^(1/(2n))` (1.1165 and 0.8957 Hz for `f_m` = 1 Hz, n = 4). The two gains
//! then sum to 1 in power at `f_m` (two uncorrelated parts keep their energy there) and each is
//! within 1% of 1 an octave from it. Here the same gains are applied in the frequency domain to the
//! record padded with zeros on both sides (the filters are acausal), together with each part's
//! site amplification, and the pads are stripped.

use rustfft::num_complex::Complex;

use super::synth::{fft_length, plans};
use crate::error::SeismoError;

/// The matched filters crossing at `hz`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossover {
    /// Crossover frequency `f_m` (Hz), where both gains are `1/√2`.
    pub hz: f64,
    /// Order `n` of each Butterworth pass (the gain is that of a forward and a backward pass).
    pub order: u32,
}

impl Crossover {
    /// The Platform's filters: 4th order, crossing at `hz`.
    pub fn new(hz: f64) -> Crossover {
        Crossover { hz, order: 4 }
    }

    /// Refuses a crossover that is not a positive frequency below `nyquist_hz`.
    pub fn check(&self, field: &str, nyquist_hz: f64) -> Result<(), SeismoError> {
        if !(self.hz.is_finite() && self.hz > 0.0 && self.high_pass_corner() * 2.0 < nyquist_hz) {
            return Err(SeismoError::parameter(
                field,
                self.hz,
                format!("0 < f_m with the low-pass corner below half the Nyquist frequency {nyquist_hz} Hz"),
            ));
        }
        if !(1..=8).contains(&self.order) {
            return Err(SeismoError::parameter("order", self.order, "1 ≤ order ≤ 8"));
        }
        Ok(())
    }

    fn shift(&self) -> f64 {
        (std::f64::consts::SQRT_2 - 1.0).powf(1.0 / (2.0 * self.order as f64))
    }

    /// The low-pass corner `f_m·(√2 − 1)^(−1/2n)` (Hz).
    pub fn low_pass_corner(&self) -> f64 {
        self.hz / self.shift()
    }

    /// The high-pass corner `f_m·(√2 − 1)^(1/2n)` (Hz).
    pub fn high_pass_corner(&self) -> f64 {
        self.hz * self.shift()
    }

    /// Gain of the low-pass (forward and backward) at `f` (Hz).
    pub fn low_gain(&self, f: f64) -> f64 {
        1.0 / (1.0 + (f.abs() / self.low_pass_corner()).powi(2 * self.order as i32))
    }

    /// Gain of the high-pass (forward and backward) at `f` (Hz).
    pub fn high_gain(&self, f: f64) -> f64 {
        let f = f.abs();
        if f == 0.0 {
            return 0.0;
        }
        1.0 / (1.0 + (self.high_pass_corner() / f).powi(2 * self.order as i32))
    }

    /// Zero pads on each side that hold the filters' transients (s): `1.5·n/f_hp`, the
    /// Converse & Brady length of record processing.
    pub fn pad_s(&self) -> f64 {
        1.5 * self.order as f64 / self.high_pass_corner()
    }
}

/// `x` (sampled every `dt`) filtered by the real, zero-phase `gain(f)` (f ≥ 0, Hz) in the
/// frequency domain, with `pad` zeros before and after it that are stripped again: the output
/// has `x`'s length and instants.
pub fn zero_phase(x: &[f64], dt: f64, pad: usize, gain: impl Fn(f64) -> f64) -> Vec<f64> {
    if x.is_empty() {
        return Vec::new();
    }
    let len = fft_length(x.len() + 2 * pad);
    let mut buf = vec![Complex::new(0.0, 0.0); len];
    for (b, v) in buf[pad..].iter_mut().zip(x) {
        b.re = *v;
    }
    let (forward, inverse) = plans(len);
    forward.process(&mut buf);
    let df = 1.0 / (len as f64 * dt);
    let scale = 1.0 / len as f64;
    for (j, c) in buf.iter_mut().enumerate() {
        *c *= gain(j.min(len - j) as f64 * df) * scale;
    }
    inverse.process(&mut buf);
    buf[pad..pad + x.len()].iter().map(|c| c.re).collect()
}

/// The two parts of a hybrid record filtered and amplified, and their sum.
#[derive(Clone, Debug, PartialEq)]
pub struct Joined {
    /// The deterministic part, site-amplified and low-passed.
    pub low: Vec<f64>,
    /// The stochastic part, site-amplified and high-passed.
    pub high: Vec<f64>,
    /// Their sum: the broadband record.
    pub broadband: Vec<f64>,
}

/// Joins `low` and `high` (one component each, sampled every `dt` from the same instant; the
/// shorter is padded with zeros) at `crossover`, each multiplied by its own site amplification
/// (`low_site(f)`, `high_site(f)`, real, f ≥ 0 in Hz) in the same pass.
pub fn join(
    low: &[f64],
    high: &[f64],
    dt: f64,
    crossover: Crossover,
    low_site: impl Fn(f64) -> f64,
    high_site: impl Fn(f64) -> f64,
) -> Joined {
    let n = low.len().max(high.len());
    let mut lo = low.to_vec();
    let mut hi = high.to_vec();
    lo.resize(n, 0.0);
    hi.resize(n, 0.0);
    let pad = (crossover.pad_s() / dt).ceil() as usize;
    let low = zero_phase(&lo, dt, pad, |f| crossover.low_gain(f) * low_site(f));
    let high = zero_phase(&hi, dt, pad, |f| crossover.high_gain(f) * high_site(f));
    let broadband = low.iter().zip(&high).map(|(a, b)| a + b).collect();
    Joined { low, high, broadband }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_platform_corners_cross_at_one_over_root_two() {
        let c = Crossover::new(1.0);
        assert!((c.high_pass_corner() - 0.8957).abs() < 1e-4, "{}", c.high_pass_corner());
        assert!((c.low_pass_corner() - 1.1165).abs() < 1e-4, "{}", c.low_pass_corner());
        let r = std::f64::consts::FRAC_1_SQRT_2;
        assert!((c.low_gain(1.0) - r).abs() < 1e-12 && (c.high_gain(1.0) - r).abs() < 1e-12);
        // Power-complementary at the crossover; each within 1% of 1 an octave away.
        assert!((c.low_gain(1.0).powi(2) + c.high_gain(1.0).powi(2) - 1.0).abs() < 1e-12);
        assert!(c.low_gain(0.5) > 0.99 && c.high_gain(2.0) > 0.99);
        assert!(c.low_gain(4.0) < 1e-3 && c.high_gain(0.25) < 1e-3);
    }

    #[test]
    fn a_sine_far_from_the_crossover_goes_through_one_filter_only() {
        let dt = 0.01;
        let n = 6000;
        let sine = |f: f64| (0..n).map(|k| (2.0 * std::f64::consts::PI * f * k as f64 * dt).sin()).collect::<Vec<_>>();
        let (slow, fast) = (sine(0.2), sine(5.0));
        let c = Crossover::new(1.0);
        let j = join(&slow, &fast, dt, c, |_| 1.0, |_| 2.0);
        // Away from the record's ends (the pads' transients), the slow sine passes the low-pass and
        // the fast one passes the high-pass doubled by its site factor.
        for k in 2000..4000 {
            assert!((j.low[k] - slow[k]).abs() < 2e-3, "{k}: {} vs {}", j.low[k], slow[k]);
            assert!((j.high[k] - 2.0 * fast[k]).abs() < 2e-3);
            assert!((j.broadband[k] - j.low[k] - j.high[k]).abs() < 1e-15);
        }
        // The wrong filter rejects each.
        let swapped = join(&fast, &slow, dt, c, |_| 1.0, |_| 1.0);
        assert!(swapped.low[2000..4000].iter().all(|v| v.abs() < 1e-3));
        assert!(swapped.high[2000..4000].iter().all(|v| v.abs() < 1e-3));
    }
}
