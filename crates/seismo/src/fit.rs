//! Least-squares fits used across the product: straight lines, in linear or log-log space.

/// A least-squares line `y = intercept + slope·x`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineFit {
    /// Intercept.
    pub intercept: f64,
    /// Slope.
    pub slope: f64,
    /// Coefficient of determination.
    pub r2: f64,
}

/// Least-squares fit `y = a + b·x` through `pts`, or `None` without points or with no spread in x.
pub fn line_fit(pts: &[(f64, f64)]) -> Option<LineFit> {
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = pts.iter().map(|p| (p.1 - my).powi(2)).sum();
    if !(sxx > 0.0) {
        return None;
    }
    let b = sxy / sxx;
    let r2 = if syy > 0.0 { sxy * sxy / (sxx * syy) } else { 1.0 };
    Some(LineFit { intercept: my - b * mx, slope: b, r2 })
}

/// A least-squares line `log10 y = intercept + slope·log10 x`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogFit {
    /// Intercept.
    pub intercept: f64,
    /// Slope.
    pub slope: f64,
    /// Coefficient of determination.
    pub r2: f64,
    /// Points used.
    pub points: usize,
}

/// Least-squares fit `log10 y = a + b·log10 x` over the points with x > 0 and y > 0, or `None`
/// with fewer than 3 such points or no spread in x.
pub fn log_log_fit(points: impl Iterator<Item = (f64, f64)>) -> Option<LogFit> {
    let pts: Vec<(f64, f64)> =
        points.filter(|(r, y)| *r > 0.0 && *y > 0.0 && y.is_finite()).map(|(r, y)| (r.log10(), y.log10())).collect();
    let n = pts.len();
    if n < 3 {
        return None;
    }
    line_fit(&pts).map(|l| LogFit { intercept: l.intercept, slope: l.slope, r2: l.r2, points: n })
}

/// An ω-square (Brune 1970) displacement spectrum `Ω(f) = Ω0 / (1 + (f/fc)²)` fitted to data.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BruneFit {
    /// Long-period level Ω0 (the data's unit).
    pub omega0: f64,
    /// Corner frequency fc (Hz).
    pub corner_hz: f64,
    /// RMS misfit in natural-log units over the bins fitted.
    pub rms_ln: f64,
    /// Logarithmic bins fitted.
    pub bins: usize,
}

/// Fits `Ω0 / (1 + (f/fc)²)` to a displacement amplitude spectrum between `f_lo` and `f_hi` (Hz),
/// in natural-log units: the spectrum is first averaged (geometric mean) in bins of a tenth of a
/// decade, so every frequency decade weighs the same; for each corner on a grid of 400 per decade
/// from `f_lo/3` to `3·f_hi`, ln Ω0 is the mean of `ln A + ln(1 + (f/fc)²)`, and the corner of
/// least squares wins. `None` with fewer than 5 bins or no positive amplitude.
pub fn fit_brune(frequency_hz: &[f64], amplitude: &[f64], f_lo: f64, f_hi: f64) -> Option<BruneFit> {
    if !(f_lo > 0.0 && f_hi > f_lo) {
        return None;
    }
    let per_decade = 10.0;
    let nbins = ((f_hi / f_lo).log10() * per_decade).ceil() as usize;
    let mut sums = vec![(0.0f64, 0.0f64, 0usize); nbins.max(1)];
    for (&f, &a) in frequency_hz.iter().zip(amplitude) {
        if f < f_lo || f > f_hi || !(a > 0.0) || !a.is_finite() {
            continue;
        }
        let k = (((f / f_lo).log10() * per_decade) as usize).min(sums.len() - 1);
        sums[k].0 += f.ln();
        sums[k].1 += a.ln();
        sums[k].2 += 1;
    }
    let bins: Vec<(f64, f64)> =
        sums.iter().filter(|b| b.2 > 0).map(|b| ((b.0 / b.2 as f64).exp(), b.1 / b.2 as f64)).collect();
    if bins.len() < 5 {
        return None;
    }
    let lo = (f_lo / 3.0).ln();
    let hi = (3.0 * f_hi).ln();
    let steps = ((hi - lo) / std::f64::consts::LN_10 * 400.0).ceil() as usize;
    let mut best: Option<BruneFit> = None;
    for i in 0..=steps {
        let fc = (lo + (hi - lo) * i as f64 / steps as f64).exp();
        let shape = |f: f64| (1.0 + (f / fc).powi(2)).ln();
        let ln_omega0 = bins.iter().map(|&(f, la)| la + shape(f)).sum::<f64>() / bins.len() as f64;
        let ss: f64 = bins.iter().map(|&(f, la)| (la - ln_omega0 + shape(f)).powi(2)).sum();
        let rms = (ss / bins.len() as f64).sqrt();
        if best.is_none_or(|b| rms < b.rms_ln) {
            best = Some(BruneFit { omega0: ln_omega0.exp(), corner_hz: fc, rms_ln: rms, bins: bins.len() });
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_log_fit_recovers_a_power_law() {
        let pts = (1..20).map(|i| {
            let r = i as f64 * 0.1;
            (r, 3.0 * r.powf(-1.5))
        });
        let f = log_log_fit(pts).unwrap();
        assert!((f.intercept - 3f64.log10()).abs() < 1e-12 && (f.slope + 1.5).abs() < 1e-12);
        assert!((f.r2 - 1.0).abs() < 1e-12);
        assert_eq!(f.points, 19);
    }

    #[test]
    fn a_brune_spectrum_gives_back_its_corner_and_level() {
        // Ω0 = 2, fc = 0.3 Hz, sampled every 0.01 Hz from 0.05 to 2.3 Hz; with ±20% multiplicative
        // ripple (a fixed pattern) the corner stays within 5%.
        let f: Vec<f64> = (5..=230).map(|k| k as f64 * 0.01).collect();
        let clean: Vec<f64> = f.iter().map(|f| 2.0 / (1.0 + (f / 0.3f64).powi(2))).collect();
        let b = fit_brune(&f, &clean, 0.05, 2.3).unwrap();
        assert!((b.corner_hz / 0.3 - 1.0).abs() < 0.01, "{b:?}");
        assert!((b.omega0 / 2.0 - 1.0).abs() < 0.02, "{b:?}");
        let rippled: Vec<f64> =
            clean.iter().enumerate().map(|(i, a)| a * (1.0 + 0.2 * (i as f64 * 0.7).sin())).collect();
        let b = fit_brune(&f, &rippled, 0.05, 2.3).unwrap();
        assert!((b.corner_hz / 0.3 - 1.0).abs() < 0.05, "{b:?}");
        // Too narrow a band to fit anything.
        assert!(fit_brune(&f, &clean, 0.05, 0.06).is_none());
    }
}
