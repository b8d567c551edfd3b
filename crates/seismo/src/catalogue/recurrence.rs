//! Recurrence of an event sequence: inter-event times, CV, and BPT and Weibull renewal fits.
//!
//! Definitions (intervals `x_i > 0`, in seconds or any time unit; results come out in it):
//! - mean, sample standard deviation (divisor n − 1), coefficient of variation `CV = std/mean`
//!   (periodic < 1 < clustered; 1 for a Poisson process), 95% interval of the mean by Student's t,
//!   as `stats::summarize` does;
//! - a percentile bootstrap interval of the CV (Efron & Tibshirani 1993, *An Introduction to the
//!   Bootstrap*, ch. 13), resampling with a seeded SplitMix64 generator (Steele et al. 2014,
//!   OOPSLA), percentiles of type 7;
//! - **Brownian passage time** (Matthews, Ellsworth & Reasenberg 2002, BSSA 92, 2233–2250), the
//!   inverse Gaussian with mean `μ` and aperiodicity `α`:
//!   `f(t) = sqrt(μ/(2π α² t³))·exp(−(t − μ)²/(2 μ α² t))`. Closed-form maximum likelihood
//!   (Tweedie 1957, Ann. Math. Stat. 28, 362–377): `μ̂ = mean(x)`,
//!   `α̂² = (1/n)·Σ (x − μ̂)²/(x μ̂)` (that is `μ̂/λ̂` with λ the inverse-Gaussian shape). Standard
//!   errors from the Fisher information: `se(μ̂) = μ α/√n`, `se(α̂) = α·sqrt((α² + 2)/(4n))`
//!   (`μ̂` and `λ̂` are independent, `Var λ̂ ≈ 2λ²/n`);
//! - **Weibull** `f(t) = (k/λ)(t/λ)^(k−1)·exp(−(t/λ)^k)`: the shape solves the profile equation
//!   `Σ x^k ln x / Σ x^k − 1/k − mean(ln x) = 0` (increasing in k; Newton's method kept inside a
//!   bisection bracket), then `λ̂ = (Σ x^k / n)^(1/k)` (Cohen 1965, Technometrics 7, 579–588);
//!   standard errors from the inverse of the observed information matrix;
//! - **exponential** (Poisson process) `f(t) = e^(−t/μ)/μ`, `μ̂ = mean(x)`, for reference;
//! - each fit gives its maximised log-likelihood `ℓ` and `AIC = 2k − 2ℓ` (Akaike 1974, IEEE TAC
//!   19, 716–723; k = 2 for BPT and Weibull, 1 for the exponential): the lower AIC is preferred.
//!
//! Every statistic here needs at least [`MIN_INTERVALS`] intervals. Non-finite intervals are left
//! out; negative ones are refused, and the likelihood fits refuse zero intervals.

use statrs::distribution::{ContinuousCDF, StudentsT};

use crate::catalogue::FitError;
use crate::stats::{bootstrap_sorted, percentile_sorted};

/// Fewest intervals for any recurrence statistic: 5.
///
/// A two-parameter fit on fewer is not informative: at n = 5 the standard error of the Weibull
/// shape is already about 35% of its value (`≈ 0.78·k/√n`), and a CV from four intervals rests on
/// three degrees of freedom.
pub const MIN_INTERVALS: usize = 5;

/// Times between consecutive events: the finite `times` (s) sorted, then differenced.
pub fn inter_event_times(times: &[f64]) -> Vec<f64> {
    let mut t: Vec<f64> = times.iter().copied().filter(|v| v.is_finite()).collect();
    t.sort_by(f64::total_cmp);
    t.windows(2).map(|w| w[1] - w[0]).collect()
}

/// Mean, spread and CV of recurrence intervals.
#[derive(Clone, Debug, PartialEq)]
pub struct RecurrenceStatistics {
    /// Intervals used.
    pub n: usize,
    /// Mean interval (time unit of the input).
    pub mean: f64,
    /// Sample standard deviation (divisor n − 1, time unit of the input).
    pub std: f64,
    /// Coefficient of variation `std/mean` (dimensionless).
    pub cv: f64,
    /// 95% confidence interval of the mean (Student's t), low and high.
    pub mean_ci95: (f64, f64),
}

/// Finite intervals, refusing negative (and, if `positive`, zero) ones and too few.
fn usable(intervals: &[f64], positive: bool) -> Result<Vec<f64>, FitError> {
    let mut x = Vec::with_capacity(intervals.len());
    for (index, &v) in intervals.iter().enumerate() {
        if !v.is_finite() {
            continue;
        }
        if v < 0.0 || (positive && v == 0.0) {
            let must = if positive { "positive" } else { "non-negative" };
            return Err(FitError::InvalidValue { what: "interval", index, value: v, must });
        }
        x.push(v);
    }
    if x.len() < MIN_INTERVALS {
        return Err(FitError::TooFew { what: "finite intervals", have: x.len(), need: MIN_INTERVALS });
    }
    Ok(x)
}

fn mean_std(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    (mean, (x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt())
}

/// Mean, standard deviation, CV and the 95% interval of the mean of `intervals` (any time unit).
pub fn recurrence_statistics(intervals: &[f64]) -> Result<RecurrenceStatistics, FitError> {
    let x = usable(intervals, false)?;
    let (mean, std) = mean_std(&x);
    if !(mean > 0.0) {
        return Err(FitError::NoSpread { what: "intervals (all zero, CV undefined)", value: 0.0 });
    }
    let n = x.len();
    let t = StudentsT::new(0.0, 1.0, (n - 1) as f64).map(|d| d.inverse_cdf(0.975)).unwrap_or(1.96);
    let half = t * std / (n as f64).sqrt();
    Ok(RecurrenceStatistics { n, mean, std, cv: std / mean, mean_ci95: (mean - half, mean + half) })
}

/// Percentile-bootstrap interval of the CV of `intervals` at `level` (e.g. 0.95), from
/// `resamples` (at least 100, 1000 is usual) resamples drawn with `seed`. Returns (low, high).
pub fn cv_bootstrap_ci(intervals: &[f64], level: f64, resamples: usize, seed: u64) -> Result<(f64, f64), FitError> {
    if !(level > 0.0 && level < 1.0) {
        return Err(FitError::InvalidParameter { what: "level", must: "in (0, 1)", value: level });
    }
    if resamples < 100 {
        return Err(FitError::InvalidParameter { what: "resamples", must: "at least 100", value: resamples as f64 });
    }
    let x = usable(intervals, false)?;
    recurrence_statistics(&x)?;
    let cv = |sample: &[f64]| {
        let (m, sd) = mean_std(sample);
        if m > 0.0 { sd / m } else { f64::NAN }
    };
    let cvs = bootstrap_sorted(&x, cv, resamples, seed);
    if cvs.len() < resamples / 2 {
        return Err(FitError::Degenerate {
            what: "CV bootstrap",
            why: format!("{} of {resamples} resamples had a zero mean", resamples - cvs.len()),
        });
    }
    Ok((percentile_sorted(&cvs, (1.0 - level) / 2.0), percentile_sorted(&cvs, (1.0 + level) / 2.0)))
}

/// Brownian passage time (inverse Gaussian) fit.
#[derive(Clone, Debug, PartialEq)]
pub struct BptFit {
    /// Intervals used.
    pub n: usize,
    /// Mean recurrence μ (time unit of the input).
    pub mean: f64,
    /// Aperiodicity α (dimensionless; the CV of the distribution).
    pub aperiodicity: f64,
    /// Standard error of μ.
    pub mean_se: f64,
    /// Standard error of α.
    pub aperiodicity_se: f64,
    /// Maximised log-likelihood (densities in 1/time unit).
    pub log_likelihood: f64,
    /// Akaike information criterion, `4 − 2ℓ`.
    pub aic: f64,
}

impl BptFit {
    /// Probability density at `t` (1/time unit); 0 for `t ≤ 0`.
    pub fn pdf(&self, t: f64) -> f64 {
        bpt_pdf(t, self.mean, self.aperiodicity)
    }
}

fn bpt_pdf(t: f64, mu: f64, alpha: f64) -> f64 {
    if !(t > 0.0) {
        return 0.0;
    }
    bpt_log_pdf(t, mu, alpha).exp()
}

/// `ln f(t)`, in log form so that far tails do not underflow to `ln 0`.
fn bpt_log_pdf(t: f64, mu: f64, alpha: f64) -> f64 {
    let a2 = alpha * alpha;
    0.5 * (mu / (2.0 * std::f64::consts::PI * a2)).ln() - 1.5 * t.ln() - (t - mu).powi(2) / (2.0 * mu * a2 * t)
}

/// Maximum-likelihood BPT fit of `intervals` (all finite ones must be positive).
pub fn fit_bpt(intervals: &[f64]) -> Result<BptFit, FitError> {
    let x = usable(intervals, true)?;
    let n = x.len();
    let nf = n as f64;
    let mu = x.iter().sum::<f64>() / nf;
    let a2 = x.iter().map(|&v| (v - mu).powi(2) / (v * mu)).sum::<f64>() / nf;
    if !(a2 > 0.0) {
        return Err(FitError::NoSpread { what: "intervals (BPT aperiodicity 0)", value: mu });
    }
    let alpha = a2.sqrt();
    let ll = x.iter().map(|&v| bpt_log_pdf(v, mu, alpha)).sum::<f64>();
    if !ll.is_finite() {
        return Err(FitError::Degenerate {
            what: "BPT fit",
            why: format!("log-likelihood not finite (μ = {mu}, α = {alpha})"),
        });
    }
    Ok(BptFit {
        n,
        mean: mu,
        aperiodicity: alpha,
        mean_se: mu * alpha / nf.sqrt(),
        aperiodicity_se: alpha * ((a2 + 2.0) / (4.0 * nf)).sqrt(),
        log_likelihood: ll,
        aic: 4.0 - 2.0 * ll,
    })
}

/// Weibull fit.
#[derive(Clone, Debug, PartialEq)]
pub struct WeibullFit {
    /// Intervals used.
    pub n: usize,
    /// Shape k (dimensionless; > 1 quasi-periodic, 1 Poisson, < 1 clustered).
    pub shape: f64,
    /// Scale λ (time unit of the input).
    pub scale: f64,
    /// Standard error of k (observed information).
    pub shape_se: f64,
    /// Standard error of λ (observed information).
    pub scale_se: f64,
    /// Maximised log-likelihood (densities in 1/time unit).
    pub log_likelihood: f64,
    /// Akaike information criterion, `4 − 2ℓ`.
    pub aic: f64,
}

impl WeibullFit {
    /// Probability density at `t` (1/time unit); 0 for `t ≤ 0`.
    pub fn pdf(&self, t: f64) -> f64 {
        if !(t > 0.0) {
            return 0.0;
        }
        let (k, l) = (self.shape, self.scale);
        let z = t / l;
        k / l * z.powf(k - 1.0) * (-z.powf(k)).exp()
    }

    /// Mean `λ·Γ(1 + 1/k)` (time unit of the input).
    pub fn mean(&self) -> f64 {
        self.scale * statrs::function::gamma::gamma(1.0 + 1.0 / self.shape)
    }
}

/// Largest Weibull shape accepted before the fit is called degenerate (a CV below about 1e-6).
const WEIBULL_MAX_SHAPE: f64 = 1e6;

/// Maximum-likelihood Weibull fit of `intervals` (all finite ones must be positive).
pub fn fit_weibull(intervals: &[f64]) -> Result<WeibullFit, FitError> {
    let x = usable(intervals, true)?;
    let n = x.len();
    let nf = n as f64;
    let max = x.iter().copied().fold(0.0, f64::max);
    if x.iter().all(|&v| v == max) {
        return Err(FitError::NoSpread { what: "intervals (Weibull shape infinite)", value: max });
    }
    // Work with y = x/max ≤ 1: y^k cannot overflow, and the profile equation is scale-free.
    let ly: Vec<f64> = x.iter().map(|&v| (v / max).ln()).collect();
    let mean_ly = ly.iter().sum::<f64>() / nf;
    // g(k) and g'(k) of the profile equation.
    let g = |k: f64| {
        let (mut s0, mut s1, mut s2) = (0.0, 0.0, 0.0);
        for &l in &ly {
            let w = (k * l).exp();
            s0 += w;
            s1 += w * l;
            s2 += w * l * l;
        }
        let r = s1 / s0;
        (r - 1.0 / k - mean_ly, s2 / s0 - r * r + 1.0 / (k * k), s0)
    };
    // Start near the usual k ≈ CV^(−1.086) and bracket the root.
    let (m, sd) = mean_std(&x);
    let mut k = (sd / m).powf(-1.086).clamp(1e-3, 1e5);
    let (mut lo, mut hi) = (k, k);
    while g(lo).0 > 0.0 {
        lo /= 2.0;
        if lo < 1e-9 {
            return Err(FitError::Degenerate { what: "Weibull fit", why: "shape runs to 0".into() });
        }
    }
    while g(hi).0 < 0.0 {
        hi *= 2.0;
        if hi > WEIBULL_MAX_SHAPE {
            return Err(FitError::Degenerate {
                what: "Weibull fit",
                why: format!("shape above {WEIBULL_MAX_SHAPE:e}: intervals are periodic to round-off"),
            });
        }
    }
    for _ in 0..200 {
        let (gk, dg, _) = g(k);
        if gk < 0.0 {
            lo = k;
        } else {
            hi = k;
        }
        let newton = k - gk / dg;
        let next = if newton > lo && newton < hi && dg > 0.0 { newton } else { 0.5 * (lo + hi) };
        let done = (next - k).abs() <= 1e-13 * k || hi - lo <= 1e-13 * hi;
        k = next;
        if done {
            break;
        }
    }
    let (_, _, s0) = g(k);
    let scale = max * (s0 / nf).powf(1.0 / k);
    // Log-likelihood and observed information in (k, λ), with z = x/λ, L = ln z.
    let (mut ll, mut hkk, mut hkl, mut hll) = (0.0, 0.0, 0.0, 0.0);
    for &v in &x {
        let l = (v / scale).ln();
        let zk = (k * l).exp();
        ll += k.ln() - scale.ln() + (k - 1.0) * l - zk;
        hkk += -1.0 / (k * k) - zk * l * l;
        hkl += (zk - 1.0 + k * zk * l) / scale;
        hll += -(k / (scale * scale)) * (zk - 1.0) - (k * k / (scale * scale)) * zk;
    }
    let det = hkk * hll - hkl * hkl;
    if !(det > 0.0) || !(hkk < 0.0) || !ll.is_finite() {
        return Err(FitError::Degenerate {
            what: "Weibull fit",
            why: format!("observed information not positive definite at k = {k}, λ = {scale}"),
        });
    }
    // Covariance = (−H)⁻¹.
    let (var_k, var_l) = (-hll / det, -hkk / det);
    Ok(WeibullFit {
        n,
        shape: k,
        scale,
        shape_se: var_k.sqrt(),
        scale_se: var_l.sqrt(),
        log_likelihood: ll,
        aic: 4.0 - 2.0 * ll,
    })
}

/// Exponential (Poisson-process) fit, the reference a renewal model must beat.
#[derive(Clone, Debug, PartialEq)]
pub struct ExponentialFit {
    /// Intervals used.
    pub n: usize,
    /// Mean interval μ (time unit of the input).
    pub mean: f64,
    /// Standard error of μ, `μ/√n`.
    pub mean_se: f64,
    /// Maximised log-likelihood, `−n ln μ − n`.
    pub log_likelihood: f64,
    /// Akaike information criterion, `2 − 2ℓ`.
    pub aic: f64,
}

impl ExponentialFit {
    /// Probability density at `t` (1/time unit); 0 for `t < 0`.
    pub fn pdf(&self, t: f64) -> f64 {
        if t < 0.0 { 0.0 } else { (-t / self.mean).exp() / self.mean }
    }
}

/// Maximum-likelihood exponential fit of `intervals` (all finite ones must be positive).
pub fn fit_exponential(intervals: &[f64]) -> Result<ExponentialFit, FitError> {
    let x = usable(intervals, true)?;
    let nf = x.len() as f64;
    let mu = x.iter().sum::<f64>() / nf;
    let ll = -nf * mu.ln() - nf;
    Ok(ExponentialFit { n: x.len(), mean: mu, mean_se: mu / nf.sqrt(), log_likelihood: ll, aic: 2.0 - 2.0 * ll })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand::rngs::ChaCha8Rng;
    use rand_distr::{Distribution, Exp, InverseGaussian, Normal, Weibull};

    fn bpt_sample(seed: u64, mu: f64, alpha: f64, n: usize) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let d = InverseGaussian::new(mu, mu / (alpha * alpha)).unwrap();
        (0..n).map(|_| d.sample(&mut rng)).collect()
    }

    fn weibull_sample(seed: u64, scale: f64, shape: f64, n: usize) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let d = Weibull::new(scale, shape).unwrap();
        (0..n).map(|_| d.sample(&mut rng)).collect()
    }

    #[test]
    fn intervals_and_statistics_by_hand() {
        assert_eq!(inter_event_times(&[3.0, 1.0, f64::NAN, 6.0]), vec![2.0, 3.0]);
        // Intervals 2, 4, 4, 4, 5, 5, 7, 9 (stats.rs's table): mean 5, std √(32/7).
        let s = recurrence_statistics(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]).unwrap();
        let sd = (32.0f64 / 7.0).sqrt();
        assert!((s.mean - 5.0).abs() < 1e-15 && (s.std - sd).abs() < 1e-14 && (s.cv - sd / 5.0).abs() < 1e-14);
        let half = 2.364_624_252 * sd / 8f64.sqrt();
        assert!((s.mean_ci95.0 - (5.0 - half)).abs() < 1e-8 && (s.mean_ci95.1 - (5.0 + half)).abs() < 1e-8);
    }

    #[test]
    fn too_few_and_bad_intervals_are_refused_with_the_reason() {
        assert!(matches!(fit_weibull(&[]), Err(FitError::TooFew { have: 0, .. })));
        assert!(inter_event_times(&[]).is_empty());
        let four = [1.0, 2.0, 3.0, f64::NAN, 4.0];
        let want = FitError::TooFew { what: "finite intervals", have: 4, need: MIN_INTERVALS };
        assert_eq!(recurrence_statistics(&four), Err(want.clone()));
        assert_eq!(fit_bpt(&four), Err(want.clone()));
        assert_eq!(fit_weibull(&four), Err(want.clone()));
        assert_eq!(fit_exponential(&four), Err(want));
        let zero = [1.0, 2.0, 0.0, 3.0, 4.0, 5.0];
        assert!(recurrence_statistics(&zero).is_ok());
        assert!(matches!(fit_weibull(&zero), Err(FitError::InvalidValue { index: 2, .. })));
        assert!(matches!(recurrence_statistics(&[1.0, -1.0, 1.0, 1.0, 1.0]), Err(FitError::InvalidValue { .. })));
        let equal = [2.0; 6];
        assert!(matches!(fit_bpt(&equal), Err(FitError::NoSpread { .. })));
        assert!(matches!(fit_weibull(&equal), Err(FitError::NoSpread { .. })));
        assert_eq!(recurrence_statistics(&equal).unwrap().cv, 0.0);
        assert!(matches!(recurrence_statistics(&[0.0; 6]), Err(FitError::NoSpread { .. })));
        assert!(matches!(cv_bootstrap_ci(&zero, 0.95, 10, 1), Err(FitError::InvalidParameter { .. })));
    }

    #[test]
    fn periodic_with_jitter_has_cv_near_zero() {
        // Events at i·T + ε, ε ~ N(0, 0.01·T): intervals have std √2·0.01·T, so CV ≈ 0.0141.
        // Tolerance: 3 standard errors of a normal-sample CV, CV/√(2n) each, n = 1000.
        let mut rng = ChaCha8Rng::seed_from_u64(21);
        let jitter = Normal::new(0.0, 0.01).unwrap();
        let times: Vec<f64> = (0..1001).map(|i| i as f64 + jitter.sample(&mut rng)).collect();
        let s = recurrence_statistics(&inter_event_times(&times)).unwrap();
        let want = 2f64.sqrt() * 0.01;
        assert!((s.cv - want).abs() < 3.0 * want / (2.0 * 1000f64).sqrt(), "CV {}", s.cv);
        assert!(s.cv < 0.02);
        let w = fit_weibull(&inter_event_times(&times)).unwrap();
        assert!(w.shape > 50.0, "shape {}", w.shape);
    }

    #[test]
    fn poisson_sequence_has_cv_one() {
        // Exponential intervals: the sample CV has standard error 1/√n (delta method), so
        // |CV − 1| < 3/√n; the 95% bootstrap interval covers 1 and is about ±2/√n wide.
        let n = 2000;
        let mut rng = ChaCha8Rng::seed_from_u64(22);
        let exp = Exp::new(1.0 / 50.0).unwrap();
        let mut t = 0.0;
        let times: Vec<f64> = (0..=n)
            .map(|_| {
                t += exp.sample(&mut rng);
                t
            })
            .collect();
        let x = inter_event_times(&times);
        let s = recurrence_statistics(&x).unwrap();
        assert!((s.cv - 1.0).abs() < 3.0 / (n as f64).sqrt(), "CV {}", s.cv);
        let (lo, hi) = cv_bootstrap_ci(&x, 0.95, 1000, 7).unwrap();
        assert!(lo < 1.0 && 1.0 < hi, "[{lo}, {hi}]");
        let width = (hi - lo) / (2.0 * 1.96 / (n as f64).sqrt());
        assert!(width > 0.7 && width < 1.5, "relative width {width}");
        assert!((s.mean - 50.0).abs() < 3.0 * 50.0 / (n as f64).sqrt());
        // Same seed, same interval.
        assert_eq!(cv_bootstrap_ci(&x, 0.95, 1000, 7).unwrap(), (lo, hi));
        // On Poisson data the Weibull shape is 1 within its error.
        let w = fit_weibull(&x).unwrap();
        assert!((w.shape - 1.0).abs() < 3.0 * w.shape_se, "k = {} ± {}", w.shape, w.shape_se);
    }

    #[test]
    fn bpt_parameters_are_recovered() {
        let (mu, alpha, n) = (100.0, 0.5, 2000);
        let x = bpt_sample(31, mu, alpha, n);
        let f = fit_bpt(&x).unwrap();
        assert!((f.mean - mu).abs() < 3.0 * f.mean_se, "μ = {} ± {}", f.mean, f.mean_se);
        assert!(
            (f.aperiodicity - alpha).abs() < 3.0 * f.aperiodicity_se,
            "α = {} ± {}",
            f.aperiodicity,
            f.aperiodicity_se
        );
        // The right model wins on AIC, and both renewal models beat Poisson.
        let w = fit_weibull(&x).unwrap();
        let e = fit_exponential(&x).unwrap();
        assert!(f.aic < w.aic && w.aic < e.aic, "AIC bpt {} weibull {} exp {}", f.aic, w.aic, e.aic);
        // ℓ agrees with its closed form at the optimum, (n/2)ln λ − (n/2)ln 2π − (3/2)Σ ln x − n/2.
        let (nf, lambda) = (n as f64, f.mean / (f.aperiodicity * f.aperiodicity));
        let closed = nf / 2.0 * (lambda / (2.0 * std::f64::consts::PI)).ln()
            - 1.5 * x.iter().map(|v| v.ln()).sum::<f64>()
            - nf / 2.0;
        assert!((f.log_likelihood - closed).abs() < 1e-8 * closed.abs());
    }

    #[test]
    fn weibull_parameters_are_recovered() {
        let (scale, shape, n) = (3.0, 2.5, 2000);
        let x = weibull_sample(41, scale, shape, n);
        let f = fit_weibull(&x).unwrap();
        assert!((f.shape - shape).abs() < 3.0 * f.shape_se, "k = {} ± {}", f.shape, f.shape_se);
        assert!((f.scale - scale).abs() < 3.0 * f.scale_se, "λ = {} ± {}", f.scale, f.scale_se);
        // Observed-information errors agree with the asymptotic ones, 0.78 k/√n and 1.05 λ/(k√n).
        assert!((f.shape_se / (0.780 * shape / (n as f64).sqrt()) - 1.0).abs() < 0.1);
        assert!((f.scale_se / (1.053 * scale / (shape * (n as f64).sqrt())) - 1.0).abs() < 0.1);
        let b = fit_bpt(&x).unwrap();
        assert!(f.aic < b.aic, "AIC weibull {} bpt {}", f.aic, b.aic);
        // Scale invariance: minutes instead of seconds.
        let g = fit_weibull(&x.iter().map(|v| v * 60.0).collect::<Vec<_>>()).unwrap();
        assert!((g.shape - f.shape).abs() < 1e-9 * f.shape && (g.scale / 60.0 - f.scale).abs() < 1e-9 * f.scale);
        assert!((f.mean() - x.iter().sum::<f64>() / n as f64).abs() < 3.0 * 0.45 * scale / (n as f64).sqrt());
    }

    #[test]
    fn standard_errors_cover_the_truth_over_seeds() {
        // 200 samples of 100 intervals: |θ̂ − θ| < 1.96·se in about 95% of them. With 200 trials
        // the count has binomial sd ≈ 3; accept 87%–99.5% (asymptotic errors at n = 100).
        let (mut bpt_hits, mut wei_hits) = (0, 0);
        for seed in 0..200 {
            let f = fit_bpt(&bpt_sample(1000 + seed, 10.0, 0.3, 100)).unwrap();
            bpt_hits += usize::from((f.aperiodicity - 0.3).abs() < 1.96 * f.aperiodicity_se);
            let w = fit_weibull(&weibull_sample(2000 + seed, 10.0, 3.0, 100)).unwrap();
            wei_hits += usize::from((w.shape - 3.0).abs() < 1.96 * w.shape_se);
        }
        assert!((174..=199).contains(&bpt_hits), "BPT α coverage {bpt_hits}/200");
        assert!((174..=199).contains(&wei_hits), "Weibull k coverage {wei_hits}/200");
    }

    #[test]
    fn clustered_sequences_fit_without_underflow() {
        // Intervals log-uniform over 12 decades (aftershock clustering): CV ≫ 1, Weibull shape
        // < 1, and the BPT likelihood stays finite although its density underflows at the ends.
        let mut rng = ChaCha8Rng::seed_from_u64(81);
        let x: Vec<f64> = (0..5000).map(|_| 10f64.powf(12.0 * rand::RngExt::random::<f64>(&mut rng) - 9.0)).collect();
        assert!(recurrence_statistics(&x).unwrap().cv > 3.0);
        let b = fit_bpt(&x).unwrap();
        let w = fit_weibull(&x).unwrap();
        assert!(b.log_likelihood.is_finite() && b.aperiodicity > 10.0);
        assert!(w.shape < 0.2 && w.aic < b.aic, "k {} AIC {} vs {}", w.shape, w.aic, b.aic);
    }

    #[test]
    fn pdfs_integrate_to_one() {
        let b = fit_bpt(&bpt_sample(51, 2.0, 0.7, 500)).unwrap();
        let w = fit_weibull(&weibull_sample(52, 2.0, 1.7, 500)).unwrap();
        let e = fit_exponential(&weibull_sample(53, 2.0, 1.0, 500)).unwrap();
        // Midpoint rule on (0, 60], step 1e-3.
        let integral = |f: &dyn Fn(f64) -> f64| (0..60_000).map(|i| f((i as f64 + 0.5) * 1e-3) * 1e-3).sum::<f64>();
        assert!((integral(&|t| b.pdf(t)) - 1.0).abs() < 1e-4);
        assert!((integral(&|t| w.pdf(t)) - 1.0).abs() < 1e-4);
        assert!((integral(&|t| e.pdf(t)) - 1.0).abs() < 1e-4);
        assert_eq!((b.pdf(0.0), w.pdf(-1.0), e.pdf(-1.0)), (0.0, 0.0, 0.0));
    }
}
