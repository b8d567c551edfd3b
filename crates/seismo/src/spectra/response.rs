//! Elastic response spectra of a ground-acceleration record, exact for the chosen reading of the
//! samples (Nigam & Jennings 1969).
//!
//! A linear oscillator `ü + 2ξωu̇ + ω²u = −a(t)` is advanced from rest over each step with the
//! *exact* solution for an input that is linear inside the step: the augmented system
//! `z = [u, u̇, a, ȧ]`, `ż = M·z` has the transition matrix `exp(M·h)` (computed once per
//! oscillator at plan time by nalgebra's Padé matrix exponential), whose first two rows give the
//! Nigam–Jennings coefficients `[u, u̇]ₙ₊₁ = A·[u, u̇]ₙ + B·[aₙ, aₙ₊₁]`.
//!
//! Traps avoided:
//! - PSA is `ω²·SD` at every period, never replaced by PGA at short periods;
//! - the peak between samples: when the period is short against Δt each step is divided into
//!   `m = ⌈40·Δt/T⌉` (rounded up to a power of two, at most 256) sub-steps of the same linear
//!   input, so the response is
//!   sampled at least 40 times per period, and at every sample where the response turns within
//!   half a sub-step (`|u̇/ü| < h/2`) the extremum of the local quadratic
//!   `u + u̇τ + ½üτ²` is taken instead of the sample (for a harmonic response this is within
//!   `(π/40)⁴/8 = 5e-6` of the true peak);
//! - the free vibration after the record's end is counted exactly: from the final state the
//!   first extremum of the damped free response is found in closed form (later ones decay), which
//!   equals appending an unbounded run of trailing zeros;
//! - two readings of the samples: **linear** (straight lines between samples, what NJ is exact
//!   for; a sine of period T0 sampled at Δt is then seen with an amplitude reduced by
//!   `sinc²(Δt/T0)`) and **band-limited** (the samples are first resampled `oversampling` times
//!   finer by FFT zero padding, i.e. Whittaker–Shannon interpolation of the zero-padded record, so
//!   a sampled sine below Nyquist is seen at its true amplitude; the record is treated as
//!   zero outside its span, so a record that does not start and end near zero rings at its ends).
//!
//! A [`SpectrumPlan`] holds everything that depends only on (Δt, periods, dampings, reading) and is
//! reused across records; a [`SpectrumScratch`] holds the per-record work arrays, so computing a
//! record allocates nothing once the scratch has grown to the largest record.

use std::sync::Arc;

use nalgebra::Matrix4;
use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};

/// How the samples of a record are read between sample times.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reading {
    /// Straight lines between samples.
    Linear,
    /// FFT-resampled (band-limited) before the linear reading.
    BandLimited,
}

/// Sub-step count for a period: the response is sampled at least this many times per period.
const SAMPLES_PER_PERIOD: f64 = 40.0;
/// Upper bound of sub-steps per step (periods far below Δt respond quasi-statically, their peaks
/// are at the samples).
const MAX_SUBSTEPS: usize = 256;

/// A set of oscillators sharing one sub-step count, coefficients in structure-of-arrays form.
#[derive(Clone, Debug)]
struct Group {
    substeps: usize,
    /// Half the sub-step (s).
    half_h: f64,
    /// ω² and 2ξω of each oscillator (for its relative acceleration).
    w2: Vec<f64>,
    cw: Vec<f64>,
    /// Index of each oscillator in the output.
    index: Vec<usize>,
    a11: Vec<f64>,
    a12: Vec<f64>,
    a21: Vec<f64>,
    a22: Vec<f64>,
    /// Weight of the input at the start / end of a sub-step on u and on u̇.
    bu0: Vec<f64>,
    bu1: Vec<f64>,
    bv0: Vec<f64>,
    bv1: Vec<f64>,
}

/// Everything that depends only on (Δt, periods, dampings, reading).
#[derive(Clone)]
pub struct SpectrumPlan {
    dt: f64,
    periods: Vec<f64>,
    dampings: Vec<f64>,
    reading: Reading,
    oversampling: usize,
    groups: Vec<Group>,
}

/// Work arrays of one record (reuse across records: no allocation once grown).
#[derive(Default)]
pub struct SpectrumScratch {
    u: Vec<f64>,
    v: Vec<f64>,
    peak: Vec<f64>,
    fine: Vec<f64>,
    spectrum: Vec<Complex<f64>>,
    fft_scratch: Vec<Complex<f64>>,
    planner: Option<FftCache>,
}

struct FftCache {
    planner: FftPlanner<f64>,
    forward: Option<(usize, Arc<dyn Fft<f64>>)>,
    inverse: Option<(usize, Arc<dyn Fft<f64>>)>,
}

/// `n` log-spaced periods from `min` to `max` (inclusive).
pub fn log_periods(min: f64, max: f64, n: usize) -> Vec<f64> {
    if n == 1 {
        return vec![min];
    }
    let (a, b) = (min.ln(), max.ln());
    (0..n).map(|i| (a + (b - a) * i as f64 / (n - 1) as f64).exp()).collect()
}

/// Transition of `[u, u̇]` over `h` for input linear from `a0` to `a1`: returns
/// `(a11, a12, a21, a22, bu0, bu1, bv0, bv1)`.
fn transition(omega: f64, xi: f64, h: f64) -> [f64; 8] {
    // z = [u, v, a, s] with s = ȧ constant: u̇ = v, v̇ = −ω²u − 2ξωv − a, ȧ = s, ṡ = 0.
    #[rustfmt::skip]
    let m = Matrix4::new(
        0.0, 1.0, 0.0, 0.0,
        -omega * omega, -2.0 * xi * omega, -1.0, 0.0,
        0.0, 0.0, 0.0, 1.0,
        0.0, 0.0, 0.0, 0.0,
    ) * h;
    let e = m.exp();
    // z(h) = E·[u, v, a0, (a1 − a0)/h]: the a0 weight is E[.,2] − E[.,3]/h, the a1 weight E[.,3]/h.
    [
        e[(0, 0)],
        e[(0, 1)],
        e[(1, 0)],
        e[(1, 1)],
        e[(0, 2)] - e[(0, 3)] / h,
        e[(0, 3)] / h,
        e[(1, 2)] - e[(1, 3)] / h,
        e[(1, 3)] / h,
    ]
}

impl SpectrumPlan {
    /// Plans spectra of records sampled every `dt` seconds, at `periods` (s, > 0) and `dampings`
    /// (fractions of critical, 0 ≤ ξ < 1). `oversampling` is used by the band-limited reading
    /// (16 keeps the straight-line error below 0.05% up to a tenth of the sampling rate).
    pub fn new(dt: f64, periods: &[f64], dampings: &[f64], reading: Reading, oversampling: usize) -> Self {
        assert!(dt > 0.0 && periods.iter().all(|t| *t > 0.0) && dampings.iter().all(|x| (0.0..1.0).contains(x)));
        let oversampling = if reading == Reading::BandLimited { oversampling.max(1) } else { 1 };
        let h = dt / oversampling as f64;
        let mut groups: Vec<Group> = Vec::new();
        for (k, &xi) in dampings.iter().enumerate() {
            for (j, &t) in periods.iter().enumerate() {
                // Sub-steps rounded up to a power of two, so oscillators share groups and run
                // side by side (at most twice the sub-steps each one needs).
                let m = ((SAMPLES_PER_PERIOD * h / t).ceil() as usize).clamp(1, MAX_SUBSTEPS).next_power_of_two();
                let c = transition(2.0 * std::f64::consts::PI / t, xi, h / m as f64);
                let g = match groups.iter_mut().position(|g| g.substeps == m) {
                    Some(i) => &mut groups[i],
                    None => {
                        groups.push(Group {
                            substeps: m,
                            half_h: 0.5 * h / m as f64,
                            w2: vec![],
                            cw: vec![],
                            index: vec![],
                            a11: vec![],
                            a12: vec![],
                            a21: vec![],
                            a22: vec![],
                            bu0: vec![],
                            bu1: vec![],
                            bv0: vec![],
                            bv1: vec![],
                        });
                        groups.last_mut().expect("just pushed")
                    }
                };
                g.index.push(k * periods.len() + j);
                let omega = 2.0 * std::f64::consts::PI / t;
                g.w2.push(omega * omega);
                g.cw.push(2.0 * xi * omega);
                for (dst, v) in
                    [&mut g.a11, &mut g.a12, &mut g.a21, &mut g.a22, &mut g.bu0, &mut g.bu1, &mut g.bv0, &mut g.bv1]
                        .into_iter()
                        .zip(c)
                {
                    dst.push(v);
                }
            }
        }
        SpectrumPlan { dt, periods: periods.to_vec(), dampings: dampings.to_vec(), reading, oversampling, groups }
    }

    /// Sampling interval the plan is for (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Periods (s).
    pub fn periods(&self) -> &[f64] {
        &self.periods
    }

    /// Damping ratios.
    pub fn dampings(&self) -> &[f64] {
        &self.dampings
    }

    /// Number of outputs (`dampings × periods`, damping-major).
    pub fn len(&self) -> usize {
        self.periods.len() * self.dampings.len()
    }

    /// Whether the plan has no oscillator.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Spectral displacement `SD` (max |u|, in the record's length unit) of `accel` for every
    /// (damping, period), damping-major, into `sd`. PSV = ω·SD, PSA = ω²·SD.
    pub fn compute(&self, accel: &[f64], scratch: &mut SpectrumScratch, sd: &mut [f64]) {
        assert_eq!(sd.len(), self.len(), "one output per (damping, period)");
        sd.fill(0.0);
        if accel.is_empty() {
            return;
        }
        // The band-limited input is taken out of the scratch while the oscillators run (and put
        // back after, keeping its capacity).
        let fine = (self.reading == Reading::BandLimited).then(|| {
            resample(accel, self.oversampling, scratch);
            std::mem::take(&mut scratch.fine)
        });
        let input = fine.as_deref().unwrap_or(accel);
        for g in &self.groups {
            let n = g.index.len();
            scratch.u.clear();
            scratch.u.resize(n, 0.0);
            scratch.v.clear();
            scratch.v.resize(n, 0.0);
            scratch.peak.clear();
            scratch.peak.resize(n, 0.0);
            run_group(g, input, &mut scratch.u, &mut scratch.v, &mut scratch.peak);
            for o in 0..n {
                let (omega, xi) = self.oscillator(g.index[o]);
                let free = free_vibration_peak(scratch.u[o], scratch.v[o], omega, xi);
                sd[g.index[o]] = scratch.peak[o].max(free);
            }
        }
        if let Some(fine) = fine {
            scratch.fine = fine;
        }
    }

    /// (ω, ξ) of output `index`.
    fn oscillator(&self, index: usize) -> (f64, f64) {
        let np = self.periods.len();
        (2.0 * std::f64::consts::PI / self.periods[index % np], self.dampings[index / np])
    }
}

/// Advances every oscillator of `g` through `x` (read linearly between samples, `g.substeps`
/// sub-steps per step) and keeps the peak |u|.
fn run_group(g: &Group, x: &[f64], u: &mut [f64], v: &mut [f64], peak: &mut [f64]) {
    let m = g.substeps;
    let inv_m = 1.0 / m as f64;
    let n = u.len();
    let (a11, a12, a21, a22) = (&g.a11[..n], &g.a12[..n], &g.a21[..n], &g.a22[..n]);
    let (bu0, bu1, bv0, bv1) = (&g.bu0[..n], &g.bu1[..n], &g.bv0[..n], &g.bv1[..n]);
    let (w2, cw, half_h) = (&g.w2[..n], &g.cw[..n], g.half_h);
    // From rest, the input jumps to x[0] at t = 0 and is linear between samples.
    for w in x.windows(2) {
        let (x0, dx) = (w[0], w[1] - w[0]);
        for k in 0..m {
            let s0 = x0 + dx * (k as f64 * inv_m);
            let s1 = x0 + dx * ((k + 1) as f64 * inv_m);
            for o in 0..n {
                let (uo, vo) = (u[o], v[o]);
                let un = a11[o] * uo + a12[o] * vo + bu0[o] * s0 + bu1[o] * s1;
                let vn = a21[o] * uo + a22[o] * vo + bv0[o] * s0 + bv1[o] * s1;
                u[o] = un;
                v[o] = vn;
                // Turning within half a sub-step: the extremum of the local quadratic.
                let acc = -s1 - cw[o] * vn - w2[o] * un;
                let tau = -vn / acc;
                let turning = if tau.abs() < half_h { (un + 0.5 * vn * tau).abs() } else { 0.0 };
                let best = if turning > un.abs() { turning } else { un.abs() };
                if best > peak[o] {
                    peak[o] = best;
                }
            }
        }
    }
}

/// Largest |u| of the damped free vibration that starts from `(u0, v0)`: |u0| or the first
/// extremum (later extrema are smaller by `exp(−ξωπ/ω_d)` each).
pub fn free_vibration_peak(u0: f64, v0: f64, omega: f64, xi: f64) -> f64 {
    let wd = omega * (1.0 - xi * xi).sqrt();
    // v(t) = e^{−ξωt}[v0·cos ω_d t − (ξω v0 + ω² u0)/ω_d · sin ω_d t] vanishes where
    // tan ω_d t = v0·ω_d / (ξω v0 + ω² u0).
    let mut theta = (v0 * wd).atan2(xi * omega * v0 + omega * omega * u0);
    if theta <= 0.0 {
        theta += std::f64::consts::PI;
    }
    let t = theta / wd;
    let u1 = (-xi * omega * t).exp() * (u0 * (wd * t).cos() + (v0 + xi * omega * u0) / wd * (wd * t).sin());
    u0.abs().max(u1.abs())
}

/// Band-limited resampling of `x` by `r` into `scratch.fine`: zero-pad to a power of two at least
/// twice the length (so the periodic FFT does not wrap the end onto the start), FFT, insert zeros
/// above Nyquist, inverse FFT, keep the `r·(n−1)+1` samples spanning the record.
fn resample(x: &[f64], r: usize, scratch: &mut SpectrumScratch) {
    let n = x.len();
    let big = (2 * n).next_power_of_two();
    let fine_len = big * r;
    let cache =
        scratch.planner.get_or_insert_with(|| FftCache { planner: FftPlanner::new(), forward: None, inverse: None });
    let forward = match &cache.forward {
        Some((len, f)) if *len == big => f.clone(),
        _ => {
            let f = cache.planner.plan_fft_forward(big);
            cache.forward = Some((big, f.clone()));
            f
        }
    };
    let inverse = match &cache.inverse {
        Some((len, f)) if *len == fine_len => f.clone(),
        _ => {
            let f = cache.planner.plan_fft_inverse(fine_len);
            cache.inverse = Some((fine_len, f.clone()));
            f
        }
    };
    let buf = &mut scratch.spectrum;
    buf.clear();
    buf.resize(fine_len, Complex::new(0.0, 0.0));
    for (b, &v) in buf.iter_mut().zip(x) {
        *b = Complex::new(v, 0.0);
    }
    let need = forward.get_inplace_scratch_len().max(inverse.get_inplace_scratch_len());
    if scratch.fft_scratch.len() < need {
        scratch.fft_scratch.resize(need, Complex::new(0.0, 0.0));
    }
    forward.process_with_scratch(&mut buf[..big], &mut scratch.fft_scratch);
    // Move the negative frequencies to the top of the longer spectrum, split the Nyquist bin.
    let half = big / 2;
    for k in (half + 1..big).rev() {
        buf[k + fine_len - big] = buf[k];
        buf[k] = Complex::new(0.0, 0.0);
    }
    let nyq = buf[half] * 0.5;
    buf[half] = nyq;
    buf[fine_len - half] = nyq;
    inverse.process_with_scratch(buf, &mut scratch.fft_scratch);
    let scale = 1.0 / big as f64;
    let keep = r * (n - 1) + 1;
    scratch.fine.clear();
    scratch.fine.extend(buf[..keep].iter().map(|c| c.re * scale));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_vibration_peak_matches_a_scan() {
        for (u0, v0, xi) in [(1.0, 0.0, 0.05), (0.0, 1.0, 0.05), (-0.3, 2.0, 0.1), (0.5, -3.0, 0.02), (0.0, 0.0, 0.05)]
        {
            let omega = 7.0;
            let wd = omega * (1.0f64 - xi * xi).sqrt();
            let mut best = 0.0f64;
            for i in 0..200_000 {
                let t = i as f64 * 1e-5;
                let u = (-xi * omega * t).exp() * (u0 * (wd * t).cos() + (v0 + xi * omega * u0) / wd * (wd * t).sin());
                best = best.max(u.abs());
            }
            let exact = free_vibration_peak(u0, v0, omega, xi);
            assert!((exact - best).abs() <= 1e-6 * best.max(1e-12), "{u0} {v0}: {exact} vs scan {best}");
        }
    }

    #[test]
    fn band_limited_resampling_reproduces_a_sampled_sine_between_samples() {
        let dt = 0.01;
        let n = 4000;
        let f0 = 7.3;
        let x: Vec<f64> = (0..n).map(|i| (2.0 * std::f64::consts::PI * f0 * i as f64 * dt).sin()).collect();
        let mut s = SpectrumScratch::default();
        resample(&x, 8, &mut s);
        assert_eq!(s.fine.len(), 8 * (n - 1) + 1);
        // Away from the ends the interpolant is the sine itself.
        for j in (8 * 1000..8 * 3000).step_by(13) {
            let t = j as f64 * dt / 8.0;
            let want = (2.0 * std::f64::consts::PI * f0 * t).sin();
            assert!((s.fine[j] - want).abs() < 2e-3, "sample {j}: {} vs {want}", s.fine[j]);
        }
    }
}
