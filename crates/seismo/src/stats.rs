//! Statistics of a sample across seeds.
//!
//! Definitions:
//! - `std` is the sample standard deviation (divisor n − 1), `cv = std/mean`;
//! - percentiles interpolate linearly between order statistics at position `p·(n − 1)` of the
//!   sorted sample (Hyndman & Fan type 7, the default of R and NumPy);
//! - the 95% confidence interval of the mean is `mean ± t(0.975, n − 1)·std/√n` (Student's t, from
//!   statrs);
//! - for positive samples, the geometric mean `exp(mean ln x)` and the log-standard-deviation
//!   `std(ln x)` (natural log, divisor n − 1).
//!
//! Quantities that need two values (std, CV, CI) are `None` for a single value.

use statrs::distribution::{ContinuousCDF, StudentsT};

/// Summary of one sample.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Number of finite values.
    pub count: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Sample standard deviation.
    pub std: Option<f64>,
    /// Coefficient of variation.
    pub cv: Option<f64>,
    /// Smallest value.
    pub min: f64,
    /// 5th percentile.
    pub p5: f64,
    /// Median.
    pub p50: f64,
    /// 95th percentile.
    pub p95: f64,
    /// Largest value.
    pub max: f64,
    /// Lower end of the 95% confidence interval of the mean.
    pub ci95_low: Option<f64>,
    /// Upper end.
    pub ci95_high: Option<f64>,
    /// Geometric mean (positive samples only).
    pub geometric_mean: Option<f64>,
    /// Standard deviation of ln x (positive samples with n ≥ 2 only).
    pub log_std: Option<f64>,
}

/// Type-7 percentile of a sorted, non-empty sample, `p` in [0, 1].
pub fn percentile_sorted(sorted: &[f64], p: f64) -> f64 {
    let h = p * (sorted.len() - 1) as f64;
    let lo = h.floor() as usize;
    let hi = h.ceil() as usize;
    sorted[lo] + (h - lo as f64) * (sorted[hi] - sorted[lo])
}

fn mean_std(x: &[f64]) -> (f64, Option<f64>) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let std = (x.len() > 1).then(|| (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt());
    (mean, std)
}

/// Summarises the finite values of `values`; `None` if there are none.
pub fn summarize(values: &[f64]) -> Option<Summary> {
    let mut x: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if x.is_empty() {
        return None;
    }
    x.sort_by(f64::total_cmp);
    let n = x.len();
    let (mean, std) = mean_std(&x);
    let half = std.and_then(|s| {
        let t = StudentsT::new(0.0, 1.0, (n - 1) as f64).ok()?.inverse_cdf(0.975);
        Some(t * s / (n as f64).sqrt())
    });
    let positive = x[0] > 0.0;
    let (geometric_mean, log_std) = if positive {
        let logs: Vec<f64> = x.iter().map(|v| v.ln()).collect();
        let (m, s) = mean_std(&logs);
        (Some(m.exp()), s)
    } else {
        (None, None)
    };
    Some(Summary {
        count: n,
        mean,
        std,
        cv: std.map(|s| s / mean),
        min: x[0],
        p5: percentile_sorted(&x, 0.05),
        p50: percentile_sorted(&x, 0.50),
        p95: percentile_sorted(&x, 0.95),
        max: x[n - 1],
        ci95_low: half.map(|h| mean - h),
        ci95_high: half.map(|h| mean + h),
        geometric_mean,
        log_std,
    })
}

/// The two-sample Kolmogorov–Smirnov test of `a` against `b` (finite values): the statistic
/// `D = sup |F_a − F_b|` of the two empirical distribution functions and its asymptotic p-value
/// `Q_KS(λ)`, `Q_KS(λ) = 2 Σ_{k≥1} (−1)^(k−1) e^(−2k²λ²)` at
/// `λ = (√n_e + 0.12 + 0.11/√n_e)·D`, `n_e = n_a n_b/(n_a + n_b)` (Stephens 1970's correction, as
/// Press et al., *Numerical Recipes* 3rd ed. §15.3.3). `None` with fewer than two values in
/// either sample.
pub fn ks_two_sample(a: &[f64], b: &[f64]) -> Option<(f64, f64)> {
    let sorted = |x: &[f64]| {
        let mut v: Vec<f64> = x.iter().copied().filter(|v| v.is_finite()).collect();
        v.sort_by(f64::total_cmp);
        v
    };
    let (a, b) = (sorted(a), sorted(b));
    if a.len() < 2 || b.len() < 2 {
        return None;
    }
    let (na, nb) = (a.len() as f64, b.len() as f64);
    let (mut i, mut j, mut d) = (0, 0, 0.0f64);
    while i < a.len() && j < b.len() {
        let x = a[i].min(b[j]);
        while i < a.len() && a[i] <= x {
            i += 1;
        }
        while j < b.len() && b[j] <= x {
            j += 1;
        }
        d = d.max((i as f64 / na - j as f64 / nb).abs());
    }
    let ne = (na * nb / (na + nb)).sqrt();
    let lambda = (ne + 0.12 + 0.11 / ne) * d;
    Some((d, kolmogorov_q(lambda)))
}

/// `Q_KS(λ) = 2 Σ_{k≥1} (−1)^(k−1) e^(−2k²λ²)`, the Kolmogorov distribution's survival function
/// (1 for λ below 0.2, where the series converges slowly and Q is 1 to 12 digits).
fn kolmogorov_q(lambda: f64) -> f64 {
    if lambda < 0.2 {
        return 1.0;
    }
    let mut sum = 0.0;
    for k in 1..=100 {
        let k = f64::from(k);
        let term = (-2.0 * k * k * lambda * lambda).exp();
        sum += if k as u32 % 2 == 1 { term } else { -term };
        if term < 1e-16 {
            break;
        }
    }
    (2.0 * sum).clamp(0.0, 1.0)
}

/// SplitMix64 (Steele, Lea & Flood 2014): small, seeded, portable.
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform index in `0..n` (Lemire's multiply-shift).
    fn index(&mut self, n: usize) -> usize {
        ((self.next_u64() as u128 * n as u128) >> 64) as usize
    }
}

/// `statistic` of `resamples` bootstrap resamples of `x` (non-empty), drawn with SplitMix64
/// started at `seed`: the finite values, sorted.
pub(crate) fn bootstrap_sorted(x: &[f64], statistic: impl Fn(&[f64]) -> f64, resamples: usize, seed: u64) -> Vec<f64> {
    let n = x.len();
    let mut rng = SplitMix64(seed);
    let mut sample = vec![0.0; n];
    let mut stats: Vec<f64> = (0..resamples)
        .map(|_| {
            for s in sample.iter_mut() {
                *s = x[rng.index(n)];
            }
            statistic(&sample)
        })
        .filter(|v| v.is_finite())
        .collect();
    stats.sort_by(f64::total_cmp);
    stats
}

/// A percentile-bootstrap interval (Efron & Tibshirani 1993, ch. 13) of `statistic` over the
/// finite values of `values` at `level` (e.g. 0.95), from `resamples` resamples drawn with a
/// SplitMix64 generator started at `seed` (reproducible); percentiles of type 7. `None` with
/// fewer than two values.
pub fn bootstrap_ci(
    values: &[f64],
    statistic: impl Fn(&[f64]) -> f64,
    level: f64,
    resamples: usize,
    seed: u64,
) -> Option<(f64, f64)> {
    let x: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if x.len() < 2 || resamples == 0 {
        return None;
    }
    let stats = bootstrap_sorted(&x, statistic, resamples, seed);
    let tail = 0.5 * (1.0 - level);
    Some((percentile_sorted(&stats, tail), percentile_sorted(&stats, 1.0 - tail)))
}

/// The median of the finite values (NaN when there are none).
pub fn median(values: &[f64]) -> f64 {
    let mut x: Vec<f64> = values.iter().copied().filter(|v| v.is_finite()).collect();
    if x.is_empty() {
        return f64::NAN;
    }
    x.sort_by(f64::total_cmp);
    percentile_sorted(&x, 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// D against scipy.stats.ks_2samp, the p-value against scipy.stats.kstwobign.sf at the
    /// corrected λ (an independent implementation of the same series).
    #[test]
    fn ks_two_sample_matches_scipy() {
        let a: Vec<f64> = (0..10).map(|i| f64::from(i + 1)).collect();
        let b: Vec<f64> = (0..12).map(|i| f64::from(i + 6)).collect();
        let (d, p) = ks_two_sample(&a, &b).unwrap();
        assert!((d - 0.5833333333333333).abs() < 1e-12, "D {d}");
        assert!((p - 0.028179342648742944).abs() < 1e-9, "p {p}");
        let a: Vec<f64> = (0..20).map(|i| 0.1 * f64::from(i)).collect();
        let b: Vec<f64> = (0..15).map(|i| 0.05 + 0.13 * f64::from(i)).collect();
        let (d, p) = ks_two_sample(&a, &b).unwrap();
        assert!((d - 1.0 / 15.0).abs() < 1e-12, "D {d}");
        assert!(p > 0.999_999, "p {p}");
        // λ = 1.44907 (n = m = 64, D = 0.25): 0.030002 in scipy.
        assert!((kolmogorov_q(1.4490749214937526) - 0.03000196344344173).abs() < 1e-9);
        assert!(ks_two_sample(&[1.0], &a).is_none());
    }

    /// The bootstrap interval of the mean of a large normal sample is the Student interval
    /// within a few percent of its width, and the same seed gives the same interval.
    #[test]
    fn bootstrap_interval_of_the_mean_matches_students() {
        let x: Vec<f64> = (0..400).map(|i| (f64::from(i) + 0.5) / 400.0).map(probit).collect();
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let (lo, hi) = bootstrap_ci(&x, mean, 0.95, 4000, 7).unwrap();
        let s = summarize(&x).unwrap();
        let (slo, shi) = (s.ci95_low.unwrap(), s.ci95_high.unwrap());
        let width = shi - slo;
        assert!((lo - slo).abs() < 0.06 * width && (hi - shi).abs() < 0.06 * width, "{lo} {hi} vs {slo} {shi}");
        assert_eq!(bootstrap_ci(&x, mean, 0.95, 4000, 7), Some((lo, hi)));
        assert!((median(&[3.0, 1.0, f64::NAN, 2.0]) - 2.0).abs() < 1e-15);
    }

    /// The standard normal quantile, from statrs.
    fn probit(p: f64) -> f64 {
        use statrs::distribution::Normal;
        Normal::new(0.0, 1.0).unwrap().inverse_cdf(p)
    }

    #[test]
    fn small_table_by_hand() {
        // x = 2, 4, 4, 4, 5, 5, 7, 9: mean 5, sample variance 32/7.
        let s = summarize(&[4.0, 2.0, 4.0, 5.0, 9.0, 4.0, 7.0, 5.0, f64::NAN]).unwrap();
        assert_eq!(s.count, 8);
        assert!((s.mean - 5.0).abs() < 1e-15);
        let sd = (32.0f64 / 7.0).sqrt();
        assert!((s.std.unwrap() - sd).abs() < 1e-14);
        assert!((s.cv.unwrap() - sd / 5.0).abs() < 1e-14);
        assert_eq!((s.min, s.max), (2.0, 9.0));
        // Type 7: h = p·7. p5: h = 0.35 → 2 + 0.35·(4 − 2) = 2.7; p50: h = 3.5 → 4.5;
        // p95: h = 6.65 → 7 + 0.65·(9 − 7) = 8.3.
        assert!((s.p5 - 2.7).abs() < 1e-12 && (s.p50 - 4.5).abs() < 1e-12 && (s.p95 - 8.3).abs() < 1e-12);
        // t(0.975, 7) = 2.364624252; half width = t·sd/√8.
        let half = 2.364_624_252 * sd / 8f64.sqrt();
        assert!((s.ci95_low.unwrap() - (5.0 - half)).abs() < 1e-8);
        assert!((s.ci95_high.unwrap() - (5.0 + half)).abs() < 1e-8);
        // Geometric mean (2·4·4·4·5·5·7·9)^(1/8).
        let g = (2.0f64 * 4.0 * 4.0 * 4.0 * 5.0 * 5.0 * 7.0 * 9.0).powf(1.0 / 8.0);
        assert!((s.geometric_mean.unwrap() - g).abs() < 1e-12);
    }

    #[test]
    fn single_and_signed_samples() {
        let s = summarize(&[3.0]).unwrap();
        assert_eq!((s.count, s.std, s.ci95_low, s.log_std), (1, None, None, None));
        assert!((s.geometric_mean.unwrap() - 3.0).abs() < 1e-15);
        let s = summarize(&[-1.0, 1.0]).unwrap();
        assert_eq!(s.geometric_mean, None);
        assert!(summarize(&[f64::NAN]).is_none());
    }
}
