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

#[cfg(test)]
mod tests {
    use super::*;

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
