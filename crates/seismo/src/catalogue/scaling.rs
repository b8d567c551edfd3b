//! Scaling relations: least-squares power laws (moment–area, moment–duration, stress drop–magnitude).
//!
//! - **log–log** fits `log10 y = I + s·log10 x`, i.e. `y = 10^I·x^s` (moment against rupture area
//!   or duration);
//! - **semi-log** fits `log10 y = I + s·x` for an `x` that is already logarithmic (stress drop
//!   against magnitude);
//! - ordinary least squares on `X` (log10 x or x) and `Y = log10 y`: `s = S_XY/S_XX`,
//!   `I = Ȳ − s·X̄`; residual variance `σ² = Σ r²/(n − 2)`; `se(s) = σ/√S_XX`,
//!   `se(I) = σ·√(1/n + X̄²/S_XX)`; 95% interval `s ± t(0.975, n − 2)·se(s)` (Student's t, from
//!   statrs, as `stats::summarize`); `r² = 1 − Σ r²/S_YY` (Draper & Smith 1998, *Applied
//!   Regression Analysis*, ch. 1–3);
//! - **self-similar references** (Kanamori & Anderson 1975, BSSA 65, 1073–1095): constant stress
//!   drop gives `M0 ∝ A^(3/2)` and, with constant rupture speed, `M0 ∝ T³`; the stress drop is
//!   independent of magnitude (slope 0). [`ScalingFit::reference`] gives such a line through the
//!   data's centroid, for figures.
//!
//! Ordinary least squares puts all the scatter in `y`: scatter in `x` pulls the exponent towards
//! 0 by the factor `var(X_true)/var(X)` (regression dilution; Fuller 1987, *Measurement Error
//! Models*). Put the noisier quantity on `y`, or compare with the fit of `x` on `y`.
//!
//! Pairs whose `y` (or, log–log, `x`) is not finite and positive cannot be placed on the axes:
//! they are left out and counted in `dropped`. A fit needs at least [`MIN_POINTS`] pairs and some
//! spread in `x`.

use statrs::distribution::{ContinuousCDF, StudentsT};

use crate::catalogue::FitError;

/// Fewest points for a fit with an uncertainty: 3 (two parameters leave n − 2 degrees of freedom
/// for the residual variance).
pub const MIN_POINTS: usize = 3;
/// Self-similar exponent of seismic moment against rupture area, `M0 ∝ A^(3/2)`.
pub const SELF_SIMILAR_MOMENT_AREA: f64 = 1.5;
/// Self-similar exponent of seismic moment against duration, `M0 ∝ T³`.
pub const SELF_SIMILAR_MOMENT_DURATION: f64 = 3.0;
/// Self-similar slope of `log10` stress drop against magnitude: 0.
pub const SELF_SIMILAR_STRESS_DROP_MAGNITUDE: f64 = 0.0;

/// How `x` is placed on the horizontal axis (`y` always as `log10 y`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axes {
    /// `X = log10 x`: a power law `y = 10^I·x^s`.
    LogLog,
    /// `X = x`: `y = 10^(I + s·x)`.
    SemiLog,
}

impl Axes {
    fn x(self, x: f64) -> f64 {
        match self {
            Axes::LogLog => x.log10(),
            Axes::SemiLog => x,
        }
    }
}

/// A straight line on the axes: `log10 y = intercept + exponent·X`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line {
    /// Axes of the line.
    pub axes: Axes,
    /// Slope `s` (exponent of the power law).
    pub exponent: f64,
    /// `I`, `log10` of the prefactor (log10 of the unit of y).
    pub intercept: f64,
}

impl Line {
    /// `y` on the line at `x` (units of the data).
    pub fn predict(&self, x: f64) -> f64 {
        10f64.powf(self.intercept + self.exponent * self.axes.x(x))
    }
}

/// A least-squares scaling fit.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalingFit {
    /// The fitted line.
    pub line: Line,
    /// Pairs used.
    pub n: usize,
    /// Pairs left out (not placeable on the axes).
    pub dropped: usize,
    /// Standard error of the exponent.
    pub exponent_se: f64,
    /// 95% confidence interval of the exponent, (low, high).
    pub exponent_ci95: (f64, f64),
    /// Standard error of the intercept.
    pub intercept_se: f64,
    /// Coefficient of determination; `None` when `y` has no spread.
    pub r_squared: Option<f64>,
    /// Residual standard deviation σ in `log10 y` (decades).
    pub residual_std: f64,
    /// Mean `X` of the points used.
    pub x_centroid: f64,
    /// Mean `log10 y` of the points used.
    pub y_centroid: f64,
}

impl ScalingFit {
    /// The fitted exponent `s`.
    pub fn exponent(&self) -> f64 {
        self.line.exponent
    }

    /// `y` on the fitted line at `x`.
    pub fn predict(&self, x: f64) -> f64 {
        self.line.predict(x)
    }

    /// A line of slope `exponent` (e.g. [`SELF_SIMILAR_MOMENT_AREA`]) through the centroid of the
    /// points, for drawing the reference beside the fit.
    pub fn reference(&self, exponent: f64) -> Line {
        Line { axes: self.line.axes, exponent, intercept: self.y_centroid - exponent * self.x_centroid }
    }
}

/// Least-squares fit of `log10 y` against `X` (see [`Axes`]) over paired `x`, `y`.
pub fn fit(x: &[f64], y: &[f64], axes: Axes) -> Result<ScalingFit, FitError> {
    if x.len() != y.len() {
        return Err(FitError::InvalidParameter {
            what: "length of y",
            must: "equal to the length of x",
            value: y.len() as f64,
        });
    }
    let placeable =
        |xi: f64, yi: f64| yi.is_finite() && yi > 0.0 && xi.is_finite() && (axes == Axes::SemiLog || xi > 0.0);
    let (xs, ys): (Vec<f64>, Vec<f64>) =
        x.iter().zip(y).filter(|&(&a, &b)| placeable(a, b)).map(|(&a, &b)| (axes.x(a), b.log10())).unzip();
    let n = xs.len();
    if n < MIN_POINTS {
        return Err(FitError::TooFew { what: "points placeable on the axes", have: n, need: MIN_POINTS });
    }
    if xs.iter().all(|&v| v == xs[0]) {
        // The value as given (not its logarithm): "every value is 1e7", not "7".
        let value = x.iter().copied().find(|&a| a.is_finite()).unwrap_or(xs[0]);
        return Err(FitError::NoSpread { what: "the abscissae", value });
    }
    let nf = n as f64;
    let xm = xs.iter().sum::<f64>() / nf;
    let ym = ys.iter().sum::<f64>() / nf;
    let (mut sxx, mut sxy, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in xs.iter().zip(&ys) {
        let (dx, dy) = (a - xm, b - ym);
        sxx += dx * dx;
        sxy += dx * dy;
        syy += dy * dy;
    }
    let slope = sxy / sxx;
    let intercept = ym - slope * xm;
    let ss_res: f64 = xs.iter().zip(&ys).map(|(a, b)| (b - intercept - slope * a).powi(2)).sum();
    let var = ss_res / (nf - 2.0);
    let se = (var / sxx).sqrt();
    let t = StudentsT::new(0.0, 1.0, nf - 2.0).map(|d| d.inverse_cdf(0.975)).unwrap_or(1.96);
    Ok(ScalingFit {
        line: Line { axes, exponent: slope, intercept },
        n,
        dropped: x.len() - n,
        exponent_se: se,
        exponent_ci95: (slope - t * se, slope + t * se),
        intercept_se: (var * (1.0 / nf + xm * xm / sxx)).sqrt(),
        r_squared: (syy > 0.0).then(|| (1.0 - ss_res / syy).clamp(0.0, 1.0)),
        residual_std: var.sqrt(),
        x_centroid: xm,
        y_centroid: ym,
    })
}

/// Seismic moment (N·m or dyne·cm) against rupture area (m²): `M0 ∝ A^s`, self-similar s = 3/2.
pub fn moment_area(area_m2: &[f64], moment: &[f64]) -> Result<ScalingFit, FitError> {
    fit(area_m2, moment, Axes::LogLog)
}

/// Seismic moment (N·m or dyne·cm) against duration (s): `M0 ∝ T^s`, self-similar s = 3.
pub fn moment_duration(duration_s: &[f64], moment: &[f64]) -> Result<ScalingFit, FitError> {
    fit(duration_s, moment, Axes::LogLog)
}

/// Stress drop (Pa) against magnitude: `log10 Δσ = I + s·M`, self-similar s = 0.
pub fn stress_drop_magnitude(magnitude: &[f64], stress_drop_pa: &[f64]) -> Result<ScalingFit, FitError> {
    fit(magnitude, stress_drop_pa, Axes::SemiLog)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::ChaCha8Rng;
    use rand::{RngExt, SeedableRng};
    use rand_distr::{Distribution, Normal};

    /// `n` points, x log-uniform over `decades` from 1, y = 10^i·x^s·10^(N(0, σ)).
    fn noisy(seed: u64, n: usize, decades: f64, s: f64, i: f64, sigma: f64) -> (Vec<f64>, Vec<f64>) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let noise = Normal::new(0.0, sigma).unwrap();
        (0..n)
            .map(|_| {
                let x = 10f64.powf(decades * rng.random::<f64>());
                (x, 10f64.powf(i + s * x.log10() + noise.sample(&mut rng)))
            })
            .unzip()
    }

    #[test]
    fn exact_power_laws() {
        let a: Vec<f64> = (1..=20).map(|k| 1e4 * k as f64).collect();
        let m0: Vec<f64> = a.iter().map(|v| 3e9 * v.powf(1.5)).collect();
        let f = moment_area(&a, &m0).unwrap();
        assert!((f.exponent() - 1.5).abs() < 1e-12 && (f.line.intercept - 3e9f64.log10()).abs() < 1e-10);
        assert!(f.exponent_se < 1e-10 && (f.r_squared.unwrap() - 1.0).abs() < 1e-12);
        assert!((f.predict(2e4) / m0[1] - 1.0).abs() < 1e-10);
        let t: Vec<f64> = (1..=10).map(|k| 0.1 * k as f64).collect();
        let m0: Vec<f64> = t.iter().map(|v| 1e17 * v.powi(3)).collect();
        let f = moment_duration(&t, &m0).unwrap();
        assert!((f.exponent() - 3.0).abs() < 1e-12);
        // The self-similar reference through the centroid is the fit itself here.
        let r = f.reference(SELF_SIMILAR_MOMENT_DURATION);
        assert!((r.predict(0.5) / f.predict(0.5) - 1.0).abs() < 1e-10);
        // Constant stress drop: slope 0, r² undefined.
        let f = stress_drop_magnitude(&[3.0, 4.0, 5.0, 6.0], &[1e6; 4]).unwrap();
        assert_eq!((f.exponent(), f.r_squared), (0.0, None));
        assert!((f.predict(7.0) - 1e6).abs() < 1e-6);
    }

    #[test]
    fn noisy_power_law_within_its_interval() {
        // 300 points over 2 decades, 0.3 decade scatter: se(s) ≈ 0.3/√(300·(2²/12)) ≈ 0.030.
        let (t, m0) = noisy(71, 300, 2.0, 3.0, 17.0, 0.3);
        let f = moment_duration(&t, &m0).unwrap();
        assert!(f.exponent_ci95.0 < 3.0 && 3.0 < f.exponent_ci95.1, "{:?}", f.exponent_ci95);
        assert!((f.exponent_se / 0.030 - 1.0).abs() < 0.15, "se {}", f.exponent_se);
        assert!((f.residual_std / 0.3 - 1.0).abs() < 0.15);
        assert!((f.line.intercept - 17.0).abs() < 3.0 * f.intercept_se);
        let r2 = f.r_squared.unwrap();
        assert!(r2 > 0.9 && r2 < 1.0);
        // Stress drop independent of magnitude: slope 0 inside its interval.
        let mut rng = ChaCha8Rng::seed_from_u64(72);
        let noise = Normal::new(0.0, 0.4).unwrap();
        let mags: Vec<f64> = (0..200).map(|_| 3.0 + 3.0 * rng.random::<f64>()).collect();
        let sd: Vec<f64> = mags.iter().map(|_| 10f64.powf(6.5 + noise.sample(&mut rng))).collect();
        let f = stress_drop_magnitude(&mags, &sd).unwrap();
        assert!(f.exponent_ci95.0 < 0.0 && 0.0 < f.exponent_ci95.1, "{:?}", f.exponent_ci95);
    }

    #[test]
    fn interval_covers_the_exponent_95_percent_of_the_time() {
        // 400 samples of 10 points (t with 8 degrees of freedom): coverage 95% ± 1.1% (binomial);
        // accept 91.5%–98.5%.
        let hits = (0..400)
            .filter(|&seed| {
                let (a, m0) = noisy(1000 + seed, 10, 1.0, 1.5, 9.0, 0.2);
                let f = moment_area(&a, &m0).unwrap();
                f.exponent_ci95.0 < 1.5 && 1.5 < f.exponent_ci95.1
            })
            .count();
        assert!((366..=394).contains(&hits), "coverage {hits}/400");
    }

    #[test]
    fn refusals_and_dropped_pairs() {
        assert!(matches!(moment_area(&[], &[]), Err(FitError::TooFew { have: 0, .. })));
        assert_eq!(
            moment_area(&[1.0, 2.0], &[1.0, 2.0]),
            Err(FitError::TooFew { what: "points placeable on the axes", have: 2, need: MIN_POINTS })
        );
        assert!(matches!(moment_area(&[2.0; 5], &[1.0, 2.0, 3.0, 4.0, 5.0]), Err(FitError::NoSpread { .. })));
        // The message gives the value as given, not its logarithm.
        let e = moment_area(&[1e7; 5], &[1.0, 2.0, 3.0, 4.0, 5.0]).unwrap_err().to_string();
        assert_eq!(e, "the abscissae: no spread (every value is 1e7)");
        assert_eq!(super::super::compact(0.010000000000000002), "0.01");
        assert_eq!(super::super::compact(0.6000000000000001), "0.6");
        assert_eq!(super::super::compact(6068.411321), "6068.41");
        assert!(matches!(moment_area(&[1.0, 2.0], &[1.0]), Err(FitError::InvalidParameter { .. })));
        // Zero area, negative moment and NaN are left out: 3 of 6 remain.
        let f = moment_area(&[0.0, 1.0, 2.0, 4.0, 8.0, f64::NAN], &[1.0, 1.0, -8.0, 8.0, 22.6, 1.0]).unwrap();
        assert_eq!((f.n, f.dropped), (3, 3));
        // Semi-log keeps a negative or zero x (magnitudes can be).
        let f = stress_drop_magnitude(&[-1.0, 0.0, 1.0], &[10.0, 100.0, 1000.0]).unwrap();
        assert!((f.exponent() - 1.0).abs() < 1e-12 && f.n == 3);
    }
}
