//! References for the spectra tests: an RK4 integration of the oscillator under the
//! straight-line reading with thousands of steps per period, and its peak found between the
//! steps with the cubic Hermite interpolant of (u, u̇); RotD by rotating the record for every
//! angle.

#![allow(dead_code)]

use std::f64::consts::PI;

use rand::{RngExt, SeedableRng};
use stickslip_seismo::spectra::rotd::ANGLES;

/// What the reference feeds the oscillator after the last sample.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tail {
    /// A ramp to zero over one sample interval, then zeros.
    Ramp,
    /// Zeros from the last sample on (the input steps to zero).
    Step,
}

/// Peak |u| of `ü + 2ξωu̇ + ω²u = −a(t)` from rest, `a` read as straight lines between the
/// samples of `x`, continued by `tail` and `periods_after` periods of zeros; RK4 with at least
/// `per_period` steps per period (and per sample interval), the peak between steps from the
/// cubic Hermite interpolant (its error is (ωh)⁴/384 of the peak, below 1e-13 for 2000 steps
/// per period).
pub fn peak(x: &[f64], dt: f64, period: f64, xi: f64, tail: Tail, periods_after: f64, per_period: usize) -> f64 {
    let w = 2.0 * PI / period;
    let m = ((per_period as f64 * dt / period).ceil() as usize).max(per_period);
    let h = dt / m as f64;
    let f = |u: f64, v: f64, a: f64| (v, -w * w * u - 2.0 * xi * w * v - a);
    let (mut u, mut v, mut best) = (0.0f64, 0.0f64, 0.0f64);
    let after = (periods_after * period / dt).ceil() as usize + 1;
    let n = x.len();
    let input = |i: usize| if i < n { x[i] } else { 0.0 };
    // Intervals: the record's n − 1, then the tail's.
    let last = n - 1 + after;
    for i in 0..last {
        let (a0, a1) = match tail {
            Tail::Step if i + 1 >= n => (0.0, 0.0),
            _ => (input(i), input(i + 1)),
        };
        for k in 0..m {
            let at = |s: f64| a0 + (a1 - a0) * (k as f64 + s) / m as f64;
            let (k1u, k1v) = f(u, v, at(0.0));
            let (k2u, k2v) = f(u + 0.5 * h * k1u, v + 0.5 * h * k1v, at(0.5));
            let (k3u, k3v) = f(u + 0.5 * h * k2u, v + 0.5 * h * k2v, at(0.5));
            let (k4u, k4v) = f(u + h * k3u, v + h * k3v, at(1.0));
            let un = u + h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
            let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
            best = best.max(un.abs());
            if v * vn < 0.0 {
                best = best.max(hermite_extremum(u, v, un, vn, h));
            }
            (u, v) = (un, vn);
        }
    }
    best
}

/// |u| at the zero of the derivative of the cubic Hermite interpolant on [0, h] (the one
/// between the ends, where u̇ changes sign).
fn hermite_extremum(u0: f64, v0: f64, u1: f64, v1: f64, h: f64) -> f64 {
    // p(s) = u0 + v0·h·s + c2·s² + c3·s³ on s ∈ [0, 1].
    let c2 = 3.0 * (u1 - u0) - h * (2.0 * v0 + v1);
    let c3 = 2.0 * (u0 - u1) + h * (v0 + v1);
    let (a, b, c) = (3.0 * c3, 2.0 * c2, v0 * h);
    let value = |s: f64| u0 + s * (v0 * h + s * (c2 + s * c3));
    let mut best = 0.0f64;
    if a.abs() < 1e-300 {
        if b != 0.0 {
            let s = -c / b;
            if (0.0..=1.0).contains(&s) {
                best = best.max(value(s).abs());
            }
        }
        return best;
    }
    let disc = b * b - 4.0 * a * c;
    if disc >= 0.0 {
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        for s in [q / a, if q != 0.0 { c / q } else { f64::NAN }] {
            if (0.0..=1.0).contains(&s) {
                best = best.max(value(s).abs());
            }
        }
    }
    best
}

/// The straightforward RotD: for every angle θ = 0°, 1°, …, 179°, the record rotated by θ,
/// `cos θ·x + sin θ·y` (cos and sin exact at 0° and 90°), through the one-component spectrum
/// `sd`; its `m` outputs at `out[o·180 + θ]`.
pub fn per_angle_by_rotation(x: &[f64], y: &[f64], mut sd: impl FnMut(&[f64]) -> Vec<f64>) -> Vec<f64> {
    let mut out = vec![];
    let mut rotated = vec![0.0; x.len()];
    for t in 0..ANGLES {
        let (s, c) = match t {
            0 => (0.0, 1.0),
            90 => (1.0, 0.0),
            _ => (t as f64 * PI / 180.0).sin_cos(),
        };
        for (r, (a, b)) in rotated.iter_mut().zip(x.iter().zip(y)) {
            *r = c * a + s * b;
        }
        let one = sd(&rotated);
        out.resize(one.len() * ANGLES, 0.0);
        for (o, v) in one.into_iter().enumerate() {
            out[o * ANGLES + t] = v;
        }
    }
    out
}

/// A uniform random record in [−9, 9).
pub fn random_record(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| rng.random_range(-1.0..1.0) * 9.0).collect()
}
