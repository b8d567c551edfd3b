//! Intensity measures of an acceleration record.
//!
//! - PGA = max |a|;
//! - velocity and displacement by the trapezoidal rule from rest (v₀ = d₀ = 0); PGV = max |v|,
//!   PGD = max |d|. With the **linear baseline** correction a least-squares straight line
//!   `c₀ + c₁t` is fitted to the velocity and removed from it before it is integrated to
//!   displacement (equivalently: the constant `c₁` is removed from the acceleration and `c₀` from
//!   the initial velocity), which keeps a small offset of the record from growing into a drifting
//!   displacement; without correction the integrals are the record's own;
//! - Arias intensity `Ia = π/(2g)·∫a²dt` (trapezoidal, g = 9.80665 m/s²), in m/s;
//! - cumulative absolute velocity `CAV = ∫|a|dt` (trapezoidal), in m/s;
//! - significant duration D5–95: the time between the instants the cumulative Arias intensity
//!   reaches 5% and 95% of its total, each found by linear interpolation between samples.

/// Standard gravity (m/s²).
pub const G: f64 = 9.80665;

/// Baseline correction before integrating to displacement.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Baseline {
    /// The record's own integrals.
    None,
    /// Remove a least-squares straight line from the velocity.
    Linear,
}

/// Intensity measures of one record (units of the record: m/s² in, m/s, m out).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Intensity {
    /// Peak |acceleration|.
    pub pga: f64,
    /// Peak |velocity|.
    pub pgv: f64,
    /// Peak |displacement|.
    pub pgd: f64,
    /// Arias intensity (m/s for m/s² input).
    pub arias: f64,
    /// Cumulative absolute velocity `∫|a|dt` (m/s for m/s² input).
    pub cav: f64,
    /// Time the cumulative Arias intensity reaches 5% (s from the first sample).
    pub t5: f64,
    /// … and 95%.
    pub t95: f64,
}

impl Intensity {
    /// Significant duration D5–95 (s).
    pub fn d5_95(&self) -> f64 {
        self.t95 - self.t5
    }
}

/// Time where the non-decreasing `h` first reaches `level`, interpolated linearly.
fn crossing(h: &[f64], level: f64, dt: f64) -> f64 {
    match h.iter().position(|&v| v >= level) {
        None => (h.len().saturating_sub(1)) as f64 * dt,
        Some(0) => 0.0,
        Some(i) => {
            let (a, b) = (h[i - 1], h[i]);
            let frac = if b > a { (level - a) / (b - a) } else { 0.0 };
            (i as f64 - 1.0 + frac) * dt
        }
    }
}

/// Intensity measures of `a` sampled every `dt` seconds.
pub fn intensity(a: &[f64], dt: f64, baseline: Baseline) -> Intensity {
    let peak = |x: &[f64]| x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut v = integrate(a, dt);
    if baseline == Baseline::Linear && v.len() > 1 {
        let n = v.len() as f64;
        let t: Vec<f64> = (0..v.len()).map(|i| i as f64 * dt).collect();
        let (tm, vm) = (t.iter().sum::<f64>() / n, v.iter().sum::<f64>() / n);
        let sxy: f64 = t.iter().zip(&v).map(|(t, v)| (t - tm) * (v - vm)).sum();
        let sxx: f64 = t.iter().map(|t| (t - tm).powi(2)).sum();
        let c1 = sxy / sxx;
        let c0 = vm - c1 * tm;
        for (vi, ti) in v.iter_mut().zip(&t) {
            *vi -= c0 + c1 * ti;
        }
    }
    let d = integrate(&v, dt);
    let sq: Vec<f64> = a.iter().map(|x| x * x).collect();
    let h = integrate(&sq, dt);
    let total = h.last().copied().unwrap_or(0.0);
    Intensity {
        pga: peak(a),
        pgv: peak(&v),
        pgd: peak(&d),
        arias: std::f64::consts::PI / (2.0 * G) * total,
        cav: a.windows(2).map(|w| 0.5 * (w[0].abs() + w[1].abs()) * dt).sum(),
        t5: crossing(&h, 0.05 * total, dt),
        t95: crossing(&h, 0.95 * total, dt),
    }
}

/// Cumulative trapezoidal integral of `x` sampled every `dt`, starting from 0.
pub fn integrate(x: &[f64], dt: f64) -> Vec<f64> {
    let mut out = Vec::with_capacity(x.len());
    let mut acc = 0.0;
    for (i, v) in x.iter().enumerate() {
        if i > 0 {
            acc += 0.5 * (x[i - 1] + v) * dt;
        }
        out.push(acc);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn sine_record_has_closed_form_arias_and_significant_duration() {
        // a = A·sin(2πt/T) over 20 whole periods.
        let (amp, period, dt): (f64, f64, f64) = (3.0, 0.5, 1e-4);
        let len = 20.0 * period;
        let n = (len / dt).round() as usize + 1;
        let a: Vec<f64> = (0..n).map(|i| amp * (2.0 * PI * i as f64 * dt / period).sin()).collect();
        let im = intensity(&a, dt, Baseline::None);
        let arias = PI / (2.0 * G) * amp * amp * len / 2.0;
        assert!((im.arias / arias - 1.0).abs() < 1e-6, "Ia {} vs {arias}", im.arias);
        // CAV = A·L·2/π over whole periods.
        let cav = amp * len * 2.0 / PI;
        assert!((im.cav / cav - 1.0).abs() < 1e-6, "CAV {} vs {cav}", im.cav);
        // Husid H(t) ∝ t/2 − T·sin(4πt/T)/(8π); solve H(t) = p·L/2 by bisection.
        let husid = |t: f64| t / 2.0 - period * (4.0 * PI * t / period).sin() / (8.0 * PI);
        let solve = |p: f64| {
            let (mut lo, mut hi) = (0.0, len);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if husid(mid) < p * len / 2.0 { lo = mid } else { hi = mid }
            }
            lo
        };
        let (t5, t95) = (solve(0.05), solve(0.95));
        assert!((im.t5 - t5).abs() < 2e-5 && (im.t95 - t95).abs() < 2e-5, "{} {} vs {t5} {t95}", im.t5, im.t95);
        assert!((im.d5_95() - (t95 - t5)).abs() < 4e-5);
        assert!((im.pga - amp).abs() < 1e-6);
        // v = A·T/(2π)·(1 − cos): PGV = A·T/π.
        assert!((im.pgv / (amp * period / PI) - 1.0).abs() < 1e-4, "PGV {}", im.pgv);
    }

    #[test]
    fn linear_baseline_removes_a_constant_offset() {
        let dt = 0.01;
        let a: Vec<f64> = (0..2001).map(|i| 0.01 + (i as f64 * dt * 3.0).sin()).collect();
        let raw = intensity(&a, dt, Baseline::None);
        let fixed = intensity(&a, dt, Baseline::Linear);
        assert!(raw.pgd > 3.0 * fixed.pgd, "offset drift {} vs corrected {}", raw.pgd, fixed.pgd);
        assert_eq!(raw.pga, fixed.pga);
    }
}
