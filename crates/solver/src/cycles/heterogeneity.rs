//! Random fields of rate-and-state coefficients along a cycle run's fault, drawn per seed
//! (docs/model.md §20.6): the catalogue scene's heterogeneity.
//!
//! Each of a, b and L may be multiplied by a log-normal factor `exp(s·g_j)`, `g` a unit Gaussian
//! field along depth with a one-dimensional von Kármán spectrum `∝ (1 + k²a²)^−(H + 1/2)` (the
//! spectrum of a line through a two-dimensional von Kármán field of Hurst exponent `H`). The
//! factor keeps each coefficient's sign (a > 0, b ≥ 0, L > 0 by construction) and its median;
//! its mean is `exp(s²/2)` times the background's. The three fields come from their own streams
//! of the seed, so a field of L is the same whether or not a field of a is asked for too.

use rand::SeedableRng;
use rand::rngs::ChaCha8Rng;
use std::f64::consts::PI;

use crate::error::SolverError;
use crate::fault::{complex_gaussian, standardise, twiddles};
use crate::laws::RateStateNode;

/// The random stream of the field of ln a.
pub const STREAM_CYCLES_A: u64 = 20;
/// The random stream of the field of ln b.
pub const STREAM_CYCLES_B: u64 = 21;
/// The random stream of the field of ln L.
pub const STREAM_CYCLES_L: u64 = 22;

/// Log-normal random fields of a, b and L along the fault, per seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Heterogeneity {
    /// Standard deviation of ln a (0: a as given).
    pub log_a_std: f64,
    /// Standard deviation of ln b (0: b as given).
    pub log_b_std: f64,
    /// Standard deviation of ln L (0: L as given).
    pub log_dc_std: f64,
    /// Correlation length of the fields (m).
    pub correlation_length_m: f64,
    /// Hurst exponent of the fields (0 < H ≤ 1).
    pub hurst: f64,
}

impl Heterogeneity {
    /// Multiplies the coefficients of `nodes` (spaced `spacing_m` along depth) by the fields of
    /// `seed`.
    pub fn apply(&self, nodes: &mut [RateStateNode], spacing_m: f64, seed: u64) -> Result<(), SolverError> {
        let n = nodes.len();
        let fields =
            [(self.log_a_std, STREAM_CYCLES_A), (self.log_b_std, STREAM_CYCLES_B), (self.log_dc_std, STREAM_CYCLES_L)];
        for (k, (std, stream)) in fields.into_iter().enumerate() {
            if std == 0.0 {
                continue;
            }
            let g = von_karman_line(n, spacing_m, self.correlation_length_m, self.hurst, seed, stream)?;
            for (node, g) in nodes.iter_mut().zip(g) {
                let factor = (std * g).exp();
                match k {
                    0 => node.a *= factor,
                    1 => node.b *= factor,
                    _ => node.dc_m *= factor,
                }
            }
        }
        Ok(())
    }

    /// The smallest and largest factor a field of standard deviation `std` takes at three
    /// standard deviations: `exp(∓3·std)`.
    pub fn span(std: f64) -> [f64; 2] {
        [(-3.0 * std).exp(), (3.0 * std).exp()]
    }
}

/// A unit Gaussian field on `n` points spaced `spacing_m`, zero mean and unit standard deviation
/// over the points, with the one-dimensional von Kármán spectrum `(1 + k²a²)^−(H + 1/2)`, `a` the
/// correlation length. Spectral synthesis on `max(2n, n + 4a/spacing)` points (so the periodic
/// wrap-around does not tie the ends together), complex Gaussian coefficients by Box–Muller on ChaCha8 draws of `seed`'s
/// `stream`, a plain DFT with `libm` twiddles: bit-identical on every platform.
pub fn von_karman_line(
    n: usize,
    spacing_m: f64,
    correlation_length_m: f64,
    hurst: f64,
    seed: u64,
    stream: u64,
) -> Result<Vec<f64>, SolverError> {
    if n == 0 {
        return Ok(Vec::new());
    }
    // At least twice the line, and four correlation lengths beyond it: the transform's period
    // then ties the line's ends together by less than exp(−4) at H = 1/2.
    let p = (2 * n).max(n + (4.0 * correlation_length_m / spacing_m).ceil() as usize);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(stream);
    let a = correlation_length_m;
    let (mut re, mut im) = (vec![0.0; p], vec![0.0; p]);
    for i in 0..p {
        let j = if i <= p / 2 { i as f64 } else { i as f64 - p as f64 };
        let k = 2.0 * PI * j / (p as f64 * spacing_m);
        let amp = if i == 0 { 0.0 } else { libm::pow(1.0 + k * k * a * a, -0.5 * (hurst + 0.5)) };
        (re[i], im[i]) = complex_gaussian(&mut rng, amp);
    }
    let (cos, sin) = twiddles(p);
    let field: Vec<f64> = (0..n)
        .map(|x| {
            (0..p)
                .map(|i| {
                    let t = (i * x) % p;
                    re[i] * cos[t] - im[i] * sin[t]
                })
                .sum()
        })
        .collect();
    standardise(field).ok_or_else(|| {
        SolverError::Unsupported(format!(
            "a von Kármán field on {n} points has no variance (correlation length {a} m, spacing {spacing_m} m)"
        ))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn correlation(f: &[f64], lag: usize) -> f64 {
        let n = f.len() - lag;
        (0..n).map(|i| f[i] * f[i + lag]).sum::<f64>() / n as f64
    }

    #[test]
    fn the_line_is_unit_and_correlated_as_its_spectrum_says() {
        // H = 1/2: the spectrum (1 + k²a²)⁻¹ is the exponential correlation exp(−r/a). 100 seeds of
        // 2000 points 100 m apart, a = 2 km (the line 100 a long: centring each line biases the
        // correlation by about −2a/L = −0.02); the mean over seeds within 0.05 of exp(−r/a).
        let (seeds, n, a) = (100, 2000, 2000.0);
        let lags = [10usize, 20, 40, 200];
        let mut mean = [0.0; 4];
        for seed in 0..seeds {
            let f = von_karman_line(n, 100.0, a, 0.5, seed, STREAM_CYCLES_L).unwrap();
            let m = f.iter().sum::<f64>() / n as f64;
            let var = f.iter().map(|v| (v - m).powi(2)).sum::<f64>() / n as f64;
            assert!(m.abs() < 1e-12 && (var - 1.0).abs() < 1e-12);
            for (k, &lag) in lags.iter().enumerate() {
                mean[k] += correlation(&f, lag) / seeds as f64;
            }
        }
        for (k, &lag) in lags.iter().enumerate() {
            let expected = (-(lag as f64 * 100.0) / a).exp();
            println!("lag {} m: {:.4} against exp(−r/a) = {expected:.4}", lag * 100, mean[k]);
            assert!((mean[k] - expected).abs() < 0.05, "lag {} m: {} against {expected}", lag * 100, mean[k]);
        }
    }

    #[test]
    fn a_field_multiplies_its_coefficient_only_and_keeps_its_median() {
        let node = RateStateNode {
            a: 0.01,
            b: 0.015,
            dc_m: 0.008,
            v0_m_s: 1e-6,
            f0: 0.6,
            evolution: crate::laws::Evolution::Aging,
            start: crate::laws::RateStateStart::SteadyAt(1e-9),
        };
        let mut nodes = vec![node; 301];
        let h =
            Heterogeneity { log_a_std: 0.0, log_b_std: 0.0, log_dc_std: 0.5, correlation_length_m: 500.0, hurst: 0.5 };
        h.apply(&mut nodes, 100.0, 7).unwrap();
        assert!(nodes.iter().all(|n| n.a == 0.01 && n.b == 0.015 && n.f0 == 0.6));
        let g = von_karman_line(301, 100.0, 500.0, 0.5, 7, STREAM_CYCLES_L).unwrap();
        for (n, g) in nodes.iter().zip(&g) {
            assert!((n.dc_m.ln() - (0.008f64.ln() + 0.5 * g)).abs() < 1e-12);
        }
        let logs: Vec<f64> = nodes.iter().map(|n| n.dc_m.ln()).collect();
        let mean = logs.iter().sum::<f64>() / 301.0;
        let sd = (logs.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 301.0).sqrt();
        assert!((mean - 0.008f64.ln()).abs() < 1e-12 && (sd - 0.5).abs() < 1e-12);
    }
}
