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
}
