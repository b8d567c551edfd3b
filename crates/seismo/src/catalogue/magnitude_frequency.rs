//! Magnitude–frequency (Gutenberg–Richter) distributions, completeness magnitude and b-value.
//!
//! Gutenberg & Richter (1944, BSSA 34, 185–188): `log10 N(≥M) = a − b·M`.
//!
//! Binning: a magnitude `M` falls in the bin of centre `k·Δm` with `k = round(M/Δm)`, so bin `k`
//! holds `[k·Δm − Δm/2, k·Δm + Δm/2)`. Every estimator below works on the binned magnitudes (the
//! bin centres), as catalogue practice does (ZMAP, Wiemer 2001, SRL 72, 373–382).
//! - incremental distribution: events per bin; cumulative: `N(≥ M_k)`, events in bins `≥ k`;
//! - **b-value**, maximum likelihood of Aki (1965, Bull. Earthq. Res. Inst. 43, 237–239) with
//!   Utsu's (1966, J. Fac. Sci. Hokkaido Univ. 3, 379–441) correction for binning:
//!   `b = log10(e) / (mean(M) − (Mc − Δm/2))`, mean over the `n` binned magnitudes `M ≥ Mc`. On
//!   binned data this is biased low by −0.4% at b = 1, Δm = 0.1: below `σ_b` up to n ≈ 50 000
//!   events. The exact maximum likelihood for binned magnitudes (Bender 1983, BSSA 73, 831–851;
//!   Tinti & Mulargia 1987, BSSA 77, 2125–2134), `b = ln(1 + Δm/(mean(M) − Mc)) / (Δm·ln 10)`,
//!   is given beside it for larger catalogues;
//! - its uncertainty by Shi & Bolt (1982, BSSA 72, 1677–1687):
//!   `σ_b = ln(10)·b²·sqrt(Σ(M − mean)² / (n(n − 1)))` (their 2.30 is ln 10); Aki's `b/√n` is
//!   given too;
//! - **a-value**: `a = log10 n + b·Mc`, so that `N(≥ M) = 10^(a − b·M)` on bin centres `M ≥ Mc`;
//! - **completeness by maximum curvature** (Wiemer & Wyss 2000, BSSA 90, 859–869): `Mc` is the
//!   centre of the most populated bin of the incremental distribution (ties go to the larger
//!   magnitude), plus an optional correction, usually +0.2 (Woessner & Wiemer 2005, BSSA 95,
//!   684–698) because the mode underestimates `Mc` where incompleteness is gradual;
//! - **completeness by goodness of fit** (Wiemer & Wyss 2000): for each trial `Mi`, the b- and
//!   a-values of the events `≥ Mi` predict cumulative counts `S_k = n·10^(−b(M_k − Mi))`; with the
//!   observed cumulative counts `B_k`, `R = 100 − 100·Σ_k |B_k − S_k| / Σ_k B_k` over the bins
//!   `M_k ≥ Mi`. `Mc` is the lowest `Mi` with `R` at or above the level (90% or 95%).
//!
//! A b-value needs at least [`MIN_EVENTS_B_VALUE`] events at or above `Mc`, and at least two
//! distinct binned magnitudes among them.
//!
//! Seismic moment and stress drop span decades: [`log_binned_distribution`] counts them in bins of
//! equal width in `log10`, aligned on decades.
//!
//! Non-finite values are left out (and counted in `ignored`), as `stats::summarize` does.

use crate::catalogue::FitError;

/// Fewest events at or above `Mc` for a b-value: 50.
///
/// With `n` events the relative uncertainty of `b` is about `1/√n` (Aki 1965): 14% at 50, already
/// ±0.3 on a 95% interval for b ≈ 1; fewer gives numbers that cannot tell catalogues apart. It is
/// also the lower bound that Woessner & Wiemer (2005) found necessary for a stable `Mc`.
pub const MIN_EVENTS_B_VALUE: usize = 50;

/// The usual correction added to the maximum-curvature `Mc` (magnitude units).
pub const MAXC_CORRECTION: f64 = 0.2;

/// Most bins a distribution may have (guards against a bin width far too small for the range).
pub const MAX_BINS: usize = 1_000_000;

/// Magnitude distribution on bins of width `Δm`.
#[derive(Clone, Debug, PartialEq)]
pub struct MagnitudeDistribution {
    /// Bin width Δm (magnitude units).
    pub bin_width: f64,
    /// Index `k` of the first bin (its centre is `k·Δm`).
    pub first_bin: i64,
    /// Bin centres `k·Δm`, ascending, every bin from the smallest to the largest magnitude.
    pub magnitudes: Vec<f64>,
    /// Events per bin.
    pub incremental: Vec<usize>,
    /// Events in this bin or above, `N(≥ M)`.
    pub cumulative: Vec<usize>,
    /// Non-finite magnitudes left out.
    pub ignored: usize,
}

/// A Gutenberg–Richter fit above a completeness magnitude.
#[derive(Clone, Debug, PartialEq)]
pub struct GutenbergRichterFit {
    /// Completeness magnitude used (a bin centre).
    pub mc: f64,
    /// Bin width Δm (magnitude units).
    pub bin_width: f64,
    /// Events at or above `mc`.
    pub n: usize,
    /// Mean binned magnitude of those events.
    pub mean_magnitude: f64,
    /// b-value (Aki–Utsu maximum likelihood).
    pub b: f64,
    /// Standard error of `b`, Shi & Bolt (1982).
    pub b_sigma: f64,
    /// Exact binned maximum likelihood (Bender 1983; Tinti & Mulargia 1987), unbiased by binning.
    pub b_binned: f64,
    /// Aki's (1965) standard error `b/√n`.
    pub b_sigma_aki: f64,
    /// a-value: `log10 N(≥ M) = a − b·M`.
    pub a: f64,
}

impl GutenbergRichterFit {
    /// Expected number of events at or above bin centre `m` (`m ≥ mc`): `10^(a − b·m)`.
    pub fn expected_cumulative(&self, m: f64) -> f64 {
        10f64.powf(self.a - self.b * m)
    }
}

/// One trial completeness magnitude of the goodness-of-fit method.
#[derive(Clone, Debug, PartialEq)]
pub struct GoodnessOfFitTrial {
    /// Trial `Mi` (a bin centre).
    pub mc: f64,
    /// Events at or above `Mi`.
    pub n: usize,
    /// b-value above `Mi`.
    pub b: f64,
    /// Goodness of fit `R` (percent).
    pub fit_percent: f64,
}

/// Completeness by goodness of fit.
#[derive(Clone, Debug, PartialEq)]
pub struct GoodnessOfFit {
    /// The completeness magnitude found.
    pub mc: f64,
    /// Level asked for (percent).
    pub level_percent: f64,
    /// The Gutenberg–Richter fit at `mc`.
    pub fit: GutenbergRichterFit,
    /// Every trial made, ascending in `Mi` (for figures).
    pub trials: Vec<GoodnessOfFitTrial>,
}

/// Distribution of positive values (seismic moment, stress drop) in logarithmic bins.
#[derive(Clone, Debug, PartialEq)]
pub struct LogBinnedDistribution {
    /// Bins per decade.
    pub bins_per_decade: usize,
    /// Bin edges `10^(j/bins_per_decade)` (one more than bins), in the unit of the values.
    pub edges: Vec<f64>,
    /// Values per bin `[edge j, edge j+1)`.
    pub incremental: Vec<usize>,
    /// Values per unit of the value in each bin: count / bin width (probability density × n).
    pub density: Vec<f64>,
    /// Values at or above each bin's lower edge.
    pub cumulative: Vec<usize>,
    /// Values left out because they are not finite and positive.
    pub ignored: usize,
}

fn check_bin_width(bin_width: f64) -> Result<(), FitError> {
    if !(bin_width > 0.0) || !bin_width.is_finite() {
        return Err(FitError::InvalidParameter { what: "bin width", must: "finite and positive", value: bin_width });
    }
    Ok(())
}

/// Index of the bin holding `m` (centre `k·Δm`).
pub fn bin_index(m: f64, bin_width: f64) -> i64 {
    (m / bin_width).round() as i64
}

/// Bins the finite `magnitudes` on a grid of width `bin_width` (e.g. 0.1).
pub fn magnitude_distribution(magnitudes: &[f64], bin_width: f64) -> Result<MagnitudeDistribution, FitError> {
    check_bin_width(bin_width)?;
    let idx: Vec<i64> = magnitudes.iter().filter(|m| m.is_finite()).map(|&m| bin_index(m, bin_width)).collect();
    let ignored = magnitudes.len() - idx.len();
    let (Some(&lo), Some(&hi)) = (idx.iter().min(), idx.iter().max()) else {
        return Err(FitError::TooFew { what: "finite magnitudes", have: 0, need: 1 });
    };
    let nbins = (hi as i128 - lo as i128 + 1) as u128;
    if nbins > MAX_BINS as u128 {
        return Err(FitError::InvalidParameter {
            what: "bin width",
            must: "wide enough for at most 10^6 bins over the magnitude range",
            value: bin_width,
        });
    }
    let nbins = nbins as usize;
    let mut incremental = vec![0usize; nbins];
    for &k in &idx {
        incremental[(k - lo) as usize] += 1;
    }
    let mut cumulative = vec![0usize; nbins];
    let mut acc = 0;
    for i in (0..nbins).rev() {
        acc += incremental[i];
        cumulative[i] = acc;
    }
    let magnitudes = (0..nbins).map(|i| (lo + i as i64) as f64 * bin_width).collect();
    Ok(MagnitudeDistribution { bin_width, first_bin: lo, magnitudes, incremental, cumulative, ignored })
}

/// b-value of the finite `magnitudes` at or above `mc` on bins of `bin_width`; see
/// [`MagnitudeDistribution::b_value`].
pub fn b_value(magnitudes: &[f64], mc: f64, bin_width: f64) -> Result<GutenbergRichterFit, FitError> {
    magnitude_distribution(magnitudes, bin_width)?.b_value(mc)
}

impl MagnitudeDistribution {
    /// Fit of the events in bins `≥ k` (bin index, `Mc = k·Δm`).
    fn fit_at(&self, k: i64) -> Result<GutenbergRichterFit, FitError> {
        let dm = self.bin_width;
        let mc = k as f64 * dm;
        let from = (k.saturating_sub(self.first_bin)).clamp(0, self.incremental.len() as i64) as usize;
        let n = self.cumulative.get(from).copied().unwrap_or(0);
        if n < MIN_EVENTS_B_VALUE {
            return Err(FitError::TooFew { what: "events at or above Mc", have: n, need: MIN_EVENTS_B_VALUE });
        }
        let bins = &self.incremental[from..];
        let mags = &self.magnitudes[from..];
        let nf = n as f64;
        let mean = bins.iter().zip(mags).map(|(&c, &m)| c as f64 * m).sum::<f64>() / nf;
        if bins.iter().filter(|&&c| c > 0).count() < 2 {
            return Err(FitError::NoSpread { what: "binned magnitudes at or above Mc", value: mean });
        }
        let ss = bins.iter().zip(mags).map(|(&c, &m)| c as f64 * (m - mean).powi(2)).sum::<f64>();
        let b = std::f64::consts::LOG10_E / (mean - (mc - dm / 2.0));
        let b_sigma = std::f64::consts::LN_10 * b * b * (ss / (nf * (nf - 1.0))).sqrt();
        let b_binned = (1.0 + dm / (mean - mc)).ln() / (dm * std::f64::consts::LN_10);
        Ok(GutenbergRichterFit {
            mc,
            bin_width: dm,
            n,
            mean_magnitude: mean,
            b,
            b_sigma,
            b_binned,
            b_sigma_aki: b / nf.sqrt(),
            a: nf.log10() + b * mc,
        })
    }

    /// b-value (Aki–Utsu), its uncertainty (Shi–Bolt) and the a-value of the events at or above
    /// `mc` (magnitude units; rounded to the nearest bin centre).
    ///
    /// Refused with fewer than [`MIN_EVENTS_B_VALUE`] events at or above `mc`, or with one
    /// distinct binned magnitude among them.
    pub fn b_value(&self, mc: f64) -> Result<GutenbergRichterFit, FitError> {
        if !mc.is_finite() {
            return Err(FitError::InvalidParameter { what: "Mc", must: "finite", value: mc });
        }
        self.fit_at(bin_index(mc, self.bin_width))
    }

    /// Completeness magnitude by maximum curvature: the centre of the most populated bin (ties to
    /// the larger magnitude) plus `correction` (magnitude units, e.g. [`MAXC_CORRECTION`] or 0),
    /// rounded to the bin grid.
    pub fn mc_maximum_curvature(&self, correction: f64) -> Result<f64, FitError> {
        if !correction.is_finite() {
            return Err(FitError::InvalidParameter { what: "Mc correction", must: "finite", value: correction });
        }
        let mut best = 0;
        for (i, &c) in self.incremental.iter().enumerate() {
            if c >= self.incremental[best] {
                best = i;
            }
        }
        let k = (self.first_bin + best as i64).saturating_add(bin_index(correction, self.bin_width));
        Ok(k as f64 * self.bin_width)
    }

    /// Completeness magnitude by goodness of fit at `level_percent` (90 or 95 usually): the lowest
    /// trial `Mi` whose Gutenberg–Richter fit explains that share of the observed cumulative
    /// distribution. Trials run over every bin with at least [`MIN_EVENTS_B_VALUE`] events at or
    /// above it; [`FitError::LevelNotReached`] when none reaches the level.
    pub fn mc_goodness_of_fit(&self, level_percent: f64) -> Result<GoodnessOfFit, FitError> {
        if !(level_percent > 0.0 && level_percent <= 100.0) {
            return Err(FitError::InvalidParameter {
                what: "level",
                must: "in (0, 100] percent",
                value: level_percent,
            });
        }
        let mut trials = Vec::new();
        let mut found = None;
        for from in 0..self.incremental.len() {
            if self.cumulative[from] < MIN_EVENTS_B_VALUE {
                break;
            }
            let Ok(fit) = self.fit_at(self.first_bin + from as i64) else { continue };
            let nf = fit.n as f64;
            let (mut resid, mut total) = (0.0, 0.0);
            for i in from..self.incremental.len() {
                let observed = self.cumulative[i] as f64;
                let predicted = nf * 10f64.powf(-fit.b * (self.magnitudes[i] - fit.mc));
                resid += (observed - predicted).abs();
                total += observed;
            }
            let fit_percent = 100.0 - 100.0 * resid / total;
            trials.push(GoodnessOfFitTrial { mc: fit.mc, n: fit.n, b: fit.b, fit_percent });
            if found.is_none() && fit_percent >= level_percent {
                found = Some(fit);
            }
        }
        if trials.is_empty() {
            let have = self.cumulative.first().copied().unwrap_or(0);
            return Err(FitError::TooFew { what: "events for any trial Mc", have, need: MIN_EVENTS_B_VALUE });
        }
        match found {
            Some(fit) => Ok(GoodnessOfFit { mc: fit.mc, level_percent, fit, trials }),
            None => {
                let best = trials.iter().max_by(|a, b| a.fit_percent.total_cmp(&b.fit_percent)).expect("non-empty");
                Err(FitError::LevelNotReached { level_percent, best_percent: best.fit_percent, best_mc: best.mc })
            }
        }
    }
}

/// Counts the finite, positive `values` (seismic moment in N·m or dyne·cm, stress drop in Pa: any
/// unit, edges come out in it) in `bins_per_decade` logarithmic bins per decade, aligned on powers
/// of ten.
pub fn log_binned_distribution(values: &[f64], bins_per_decade: usize) -> Result<LogBinnedDistribution, FitError> {
    if bins_per_decade == 0 || bins_per_decade > 1000 {
        return Err(FitError::InvalidParameter {
            what: "bins per decade",
            must: "between 1 and 1000",
            value: bins_per_decade as f64,
        });
    }
    let bpd = bins_per_decade as f64;
    let edge = |j: i64| 10f64.powf(j as f64 / bpd);
    let idx: Vec<i64> = values
        .iter()
        .filter(|v| v.is_finite() && **v > 0.0)
        .map(|&v| {
            let mut j = (v.log10() * bpd).floor() as i64;
            if v < edge(j) {
                j -= 1;
            } else if v >= edge(j + 1) {
                j += 1;
            }
            j
        })
        .collect();
    let ignored = values.len() - idx.len();
    let (Some(&lo), Some(&hi)) = (idx.iter().min(), idx.iter().max()) else {
        return Err(FitError::TooFew { what: "finite positive values", have: 0, need: 1 });
    };
    let nbins = (hi - lo + 1) as usize;
    let mut incremental = vec![0usize; nbins];
    for &j in &idx {
        incremental[(j - lo) as usize] += 1;
    }
    let edges: Vec<f64> = (0..=nbins).map(|i| edge(lo + i as i64)).collect();
    let density = incremental.iter().zip(edges.windows(2)).map(|(&c, e)| c as f64 / (e[1] - e[0])).collect();
    let mut cumulative = vec![0usize; nbins];
    let mut acc = 0;
    for i in (0..nbins).rev() {
        acc += incremental[i];
        cumulative[i] = acc;
    }
    Ok(LogBinnedDistribution { bins_per_decade, edges, incremental, density, cumulative, ignored })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::ChaCha8Rng;
    use rand::{RngExt, SeedableRng};

    /// Gutenberg–Richter sample with b = `b`: continuous magnitudes above `m_min`, complete above
    /// `m_complete`, below it detected with probability `10^(γ(M − m_complete))`. Draws until
    /// `n_complete` events at or above `m_complete` are kept.
    fn gr_catalogue(seed: u64, b: f64, m_min: f64, m_complete: f64, gamma: f64, n_complete: usize) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let beta = b * std::f64::consts::LN_10;
        let mut out = Vec::new();
        let mut complete = 0;
        while complete < n_complete {
            let u: f64 = rng.random();
            let m = m_min - (1.0 - u).ln() / beta;
            if m >= m_complete {
                complete += 1;
                out.push(m);
            } else if rng.random::<f64>() < 10f64.powf(gamma * (m - m_complete)) {
                out.push(m);
            }
        }
        out
    }

    #[test]
    fn bins_and_cumulative_by_hand() {
        // 2.04 → 2.0, 2.06 → 2.1, 2.26 → 2.3, NaN left out.
        let d = magnitude_distribution(&[2.04, 2.06, 2.1, 2.26, f64::NAN, 2.0], 0.1).unwrap();
        assert_eq!(d.first_bin, 20);
        assert_eq!(d.incremental, vec![2, 2, 0, 1]);
        assert_eq!(d.cumulative, vec![5, 3, 1, 1]);
        assert_eq!(d.ignored, 1);
        for (m, want) in d.magnitudes.iter().zip([2.0, 2.1, 2.2, 2.3]) {
            assert!((m - want).abs() < 1e-12);
        }
        assert!(matches!(magnitude_distribution(&[1.0], 0.0), Err(FitError::InvalidParameter { .. })));
        assert!(matches!(magnitude_distribution(&[f64::NAN], 0.1), Err(FitError::TooFew { need: 1, .. })));
        assert!(matches!(magnitude_distribution(&[0.0, 10.0], 1e-6), Err(FitError::InvalidParameter { .. })));
    }

    #[test]
    fn b_value_formulas_by_hand() {
        // 60 events: 40 at 3.0, 20 at 3.1 → mean 3.0333…, b = log10 e / (mean − 2.95).
        let mags: Vec<f64> = (0..60).map(|i| if i < 40 { 3.0 } else { 3.1 }).collect();
        let f = b_value(&mags, 3.0, 0.1).unwrap();
        let mean = (40.0 * 3.0 + 20.0 * 3.1) / 60.0;
        let b = std::f64::consts::LOG10_E / (mean - 2.95);
        assert_eq!(f.n, 60);
        assert!((f.b - b).abs() < 1e-12);
        let ss = 40.0 * (3.0f64 - mean).powi(2) + 20.0 * (3.1f64 - mean).powi(2);
        assert!((f.b_sigma - 10f64.ln() * b * b * (ss / (60.0 * 59.0)).sqrt()).abs() < 1e-8);
        assert!((f.a - (60f64.log10() + b * 3.0)).abs() < 1e-12);
        let exact = (1.0 + 0.1 / (mean - 3.0)).ln() / (0.1 * 10f64.ln());
        assert!((f.b_binned - exact).abs() < 1e-12);
        assert!((f.expected_cumulative(3.0) - 60.0).abs() < 1e-9);
    }

    #[test]
    fn refusals_state_their_reason() {
        assert!(matches!(b_value(&[], 2.0, 0.1), Err(FitError::TooFew { have: 0, .. })));
        let d = magnitude_distribution(&[2.0, 2.1], 0.1).unwrap();
        assert!(d.mc_maximum_curvature(f64::MAX).is_ok() && d.b_value(1e300).is_err());
        let few = gr_catalogue(1, 1.0, 2.0, 2.0, 0.0, 49);
        assert_eq!(
            b_value(&few, 2.0, 0.1),
            Err(FitError::TooFew { what: "events at or above Mc", have: 49, need: MIN_EVENTS_B_VALUE })
        );
        let one = vec![3.0; 100];
        assert!(matches!(b_value(&one, 3.0, 0.1), Err(FitError::NoSpread { .. })));
        let d = magnitude_distribution(&one, 0.1).unwrap();
        assert!(matches!(d.mc_goodness_of_fit(90.0), Err(FitError::TooFew { .. })));
        assert!(matches!(d.mc_goodness_of_fit(0.0), Err(FitError::InvalidParameter { .. })));
        assert!(matches!(d.b_value(f64::NAN), Err(FitError::InvalidParameter { .. })));
        // Two clusters (100 events at 2.0, 100 at 4.0): the only trial possible (at 2.0; above
        // it one magnitude is left) explains far less than 90%.
        let two: Vec<f64> = (0..200).map(|i| if i < 100 { 2.0 } else { 4.0 }).collect();
        let d = magnitude_distribution(&two, 0.1).unwrap();
        match d.mc_goodness_of_fit(90.0) {
            Err(FitError::LevelNotReached { level_percent, best_percent, best_mc }) => {
                assert_eq!(level_percent, 90.0);
                assert!(best_percent < 90.0 && (best_mc - 2.0).abs() < 1e-9, "{best_percent} at {best_mc}");
            }
            other => panic!("{other:?}"),
        }
    }

    /// The acceptance test: b = 1, 10 000 events complete above 1.95 (so the first complete bin is
    /// 2.0), incomplete below with detection probability 10^(5(M − 1.95)) (10% detected at 1.75).
    /// Maximum curvature and goodness of fit at 90% and 95% find Mc within one bin of 2.0; b is
    /// within 3 Shi–Bolt σ of 1.
    #[test]
    fn recovers_b_and_mc_of_a_gutenberg_richter_sample() {
        let dm = 0.1;
        for seed in [11, 12, 13] {
            let mags = gr_catalogue(seed, 1.0, 0.5, 1.95, 5.0, 10_000);
            let d = magnitude_distribution(&mags, dm).unwrap();
            let maxc = d.mc_maximum_curvature(0.0).unwrap();
            assert!((maxc - 2.0).abs() <= dm + 1e-9, "seed {seed}: maxc {maxc}");
            let corrected = d.mc_maximum_curvature(MAXC_CORRECTION).unwrap();
            assert!((corrected - maxc - 0.2).abs() < 1e-9);
            for level in [90.0, 95.0] {
                let gof = d.mc_goodness_of_fit(level).unwrap();
                assert!((gof.mc - 2.0).abs() <= dm + 1e-9, "seed {seed}: gof{level} {}", gof.mc);
                assert!(gof.trials.iter().any(|t| t.fit_percent >= level));
            }
            let f = d.b_value(2.0).unwrap();
            assert_eq!(f.n, 10_000);
            // σ_b ≈ b/√n = 0.01; the estimator's binning bias (−0.004) is inside 3σ.
            assert!((f.b_sigma - 0.01).abs() < 0.002, "σ_b {}", f.b_sigma);
            assert!((f.b - 1.0).abs() < 3.0 * f.b_sigma, "seed {seed}: b = {} ± {}", f.b, f.b_sigma);
            assert!((f.b_binned - 1.0).abs() < 3.0 * f.b_sigma, "seed {seed}: exact binned b = {}", f.b_binned);
            // a = log10 N + b·Mc = 4 + 2 for the truth; its error is dominated by Mc·σ_b.
            let sigma_a = 2.0 * f.b_sigma + std::f64::consts::LOG10_E / 100.0;
            assert!((f.a - 6.0).abs() < 3.0 * sigma_a, "a = {}", f.a);
        }
    }

    /// Where incompleteness is gradual (detection 10^(3(M − 1.95)), 50% at 1.85), goodness of fit
    /// at 90% is known to come out low (Woessner & Wiemer 2005): two bins here, while 95% and
    /// maximum curvature stay within one. Kept as a documented property, not a defect.
    #[test]
    fn gradual_incompleteness_pulls_the_90_percent_level_low() {
        let d = magnitude_distribution(&gr_catalogue(11, 1.0, 0.5, 1.95, 3.0, 10_000), 0.1).unwrap();
        assert!((d.mc_goodness_of_fit(90.0).unwrap().mc - 1.8).abs() < 1e-9);
        assert!((d.mc_goodness_of_fit(95.0).unwrap().mc - 1.9).abs() < 1e-9);
        assert!((d.mc_maximum_curvature(0.0).unwrap() - 2.0).abs() <= 0.1 + 1e-9);
        // Fitting from the 90% Mc biases b low by far more than its σ: Mc matters.
        let low = d.b_value(1.8).unwrap();
        assert!(1.0 - low.b > 10.0 * low.b_sigma, "b = {} ± {}", low.b, low.b_sigma);
    }

    #[test]
    fn shi_bolt_sigma_matches_the_spread_over_seeds() {
        // 200 catalogues of 500 complete events: the scatter of b̂ is σ_b within sampling error
        // (the standard deviation of 200 draws is known to ±5%; allow ±15%).
        let mut bs = Vec::new();
        let mut sig = Vec::new();
        let mut exact = 0.0;
        for seed in 0..200 {
            let f = b_value(&gr_catalogue(100 + seed, 1.0, 1.95, 1.95, 0.0, 500), 2.0, 0.1).unwrap();
            bs.push(f.b);
            sig.push(f.b_sigma);
            exact += f.b_binned / 200.0;
        }
        let mean = bs.iter().sum::<f64>() / 200.0;
        let sd = (bs.iter().map(|b| (b - mean).powi(2)).sum::<f64>() / 199.0).sqrt();
        let sigma = sig.iter().sum::<f64>() / 200.0;
        assert!((sd / sigma - 1.0).abs() < 0.15, "scatter {sd}, Shi–Bolt {sigma}");
        assert!((mean - 1.0).abs() < 3.0 * sd / 200f64.sqrt() + 0.01, "mean b {mean}");
        // The exact binned estimator is unbiased to within its O(1/n) small-sample bias.
        assert!((exact - 1.0).abs() < 3.0 * sd / 200f64.sqrt(), "mean exact b {exact}");
    }

    #[test]
    fn log_bins_of_moment() {
        let v = [1.0, 9.99, 10.0, 31.0, 100.0, 0.0, -3.0, f64::INFINITY];
        let d = log_binned_distribution(&v, 2).unwrap();
        assert_eq!(d.ignored, 3);
        // Edges 1, 3.16, 10, 31.6, 100, 316.
        assert_eq!(d.incremental, vec![1, 1, 2, 0, 1]);
        assert_eq!(d.cumulative, vec![5, 4, 3, 1, 1]);
        assert!((d.edges[0] - 1.0).abs() < 1e-12 && (d.edges[5] - 10f64.powf(2.5)).abs() < 1e-9);
        assert!((d.density[0] - 1.0 / (10f64.sqrt() - 1.0)).abs() < 1e-12);
        assert!(matches!(log_binned_distribution(&v, 0), Err(FitError::InvalidParameter { .. })));
        assert!(matches!(log_binned_distribution(&[0.0], 5), Err(FitError::TooFew { .. })));
    }

    #[test]
    fn moment_power_law_in_log_bins() {
        // M0 with a Pareto tail of exponent β = 2b/3 = 2/3 (b = 1): N(≥ M0) ∝ M0^(−2/3), so
        // cumulative counts drop by 10^(2/3) per decade (within Poisson error of the counts).
        let mags = gr_catalogue(5, 1.0, 2.0, 2.0, 0.0, 20_000);
        let m0: Vec<f64> = mags.iter().map(|m| 10f64.powf(1.5 * m + 16.1)).collect();
        let d = log_binned_distribution(&m0, 5).unwrap();
        let at = |x: f64| m0.iter().filter(|&&v| v >= x).count() as f64;
        let x0 = d.edges[1];
        let ratio = at(x0) / at(10.0 * x0);
        let want = 10f64.powf(2.0 / 3.0);
        // Relative error of the ratio ≈ 1/√(count above 10·x0) ≈ 1/√4000.
        assert!((ratio / want - 1.0).abs() < 3.0 / at(10.0 * x0).sqrt(), "{ratio} vs {want}");
        assert_eq!(d.cumulative[1] as f64, at(x0));
    }
}
