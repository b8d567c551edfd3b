//! Bar stiffness of the cubic truss (docs/model.md §1) and the Weibull random fields (docs/model.md §3).

use rand::SeedableRng;
use rand::distr::{Distribution, Open01};
use rand::rngs::ChaCha8Rng;
use statrs::function::gamma::ln_gamma;

use crate::error::SolverError;
use crate::geometry::BarFamily;

/// Random stream used for the Young's-modulus field (one factor per bar, canonical bar order).
pub const STREAM_YOUNG: u64 = 0;
/// Random stream used for the friction-coefficient field (one factor per contact node).
pub const STREAM_FRICTION: u64 = 1;

/// The cubic-truss constants `δ = 9ν/(4−8ν)` and `α = (9+8δ)/(18+24δ)`.
pub fn truss_constants(poisson: f64) -> (f64, f64) {
    let delta = 9.0 * poisson / (4.0 - 8.0 * poisson);
    let alpha = (9.0 + 8.0 * delta) / (18.0 + 24.0 * delta);
    (delta, alpha)
}

/// Axial stiffness `EA` (N) of a bar of `family` before surface reduction and random factor:
/// `α·E·Lc²` for normal (edge, centre) bars, `(2δ/√3)·α·E·Lc²` for diagonals.
pub fn axial_stiffness(family: BarFamily, young_pa: f64, poisson: f64, lc_m: f64) -> f64 {
    let (delta, alpha) = truss_constants(poisson);
    let normal = alpha * young_pa * lc_m * lc_m;
    match family {
        BarFamily::Edge | BarFamily::Centre => normal,
        BarFamily::Diagonal => 2.0 * delta / 3f64.sqrt() * normal,
    }
}

/// Isotropic elastic constants `(C11, C12, C44)` the lattice should reproduce: `λ+2μ`, `λ`, and
/// `λ` (the lattice's shear modulus on cube planes is `λ`, equal to `μ` only at ν = 0.25).
pub fn lattice_elastic_constants(young_pa: f64, poisson: f64) -> (f64, f64, f64) {
    let lame = young_pa * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    let mu = young_pa / (2.0 * (1.0 + poisson));
    (lame + 2.0 * mu, lame, lame)
}

/// A Weibull distribution of mean 1 with a given coefficient of variation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitWeibull {
    /// Shape γ.
    pub shape: f64,
    /// `Γ(1+1/γ)`, the divisor that makes the mean 1.
    pub mean_divisor: f64,
}

impl UnitWeibull {
    /// Solves `CV² + 1 = Γ(1+2/γ)/Γ(1+1/γ)²` for the shape γ (bisection on ln γ).
    ///
    /// `cv` must be in `(0, 2]`; CV = 0 means "no random field" and has no distribution.
    pub fn from_cv(cv: f64) -> Result<Self, SolverError> {
        if !(cv > 0.0 && cv <= 2.0) {
            return Err(SolverError::Numerical(format!(
                "Weibull coefficient of variation {cv} has no shape: allowed 0 < CV ≤ 2"
            )));
        }
        // g(γ) = Γ(1+2/γ)/Γ(1+1/γ)² − 1 decreases from ∞ (γ → 0) to 0 (γ → ∞).
        let excess = |g: f64| (ln_gamma(1.0 + 2.0 / g) - 2.0 * ln_gamma(1.0 + 1.0 / g)).exp_m1();
        let target = cv * cv;
        let (mut lo, mut hi) = (0.2f64.ln(), 1.0e7f64.ln());
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if excess(mid.exp()) > target {
                lo = mid;
            } else {
                hi = mid;
            }
            if hi - lo < 1e-15 {
                break;
            }
        }
        let shape = (0.5 * (lo + hi)).exp();
        Ok(UnitWeibull { shape, mean_divisor: ln_gamma(1.0 + 1.0 / shape).exp() })
    }

    /// `Φ = [−ln(1−U)]^(1/γ) / Γ(1+1/γ)` for `U` in (0, 1) (paper Eq. 11). Uses the pure-Rust
    /// `libm` so the field is bit-identical on every platform.
    #[inline]
    pub fn factor(&self, u: f64) -> f64 {
        libm::pow(-libm::log1p(-u), 1.0 / self.shape) / self.mean_divisor
    }
}

/// Draws `n` Weibull factors of mean 1 and coefficient of variation `cv` from stream `stream` of
/// `seed` (ChaCha8, portable). CV = 0 draws nothing and returns `None` (homogeneous).
pub fn weibull_factors(cv: f64, seed: u64, stream: u64, n: usize) -> Result<Option<Vec<f64>>, SolverError> {
    if cv == 0.0 {
        return Ok(None);
    }
    let dist = UnitWeibull::from_cv(cv)?;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(stream);
    Ok(Some((0..n).map(|_| dist.factor(Open01.sample(&mut rng))).collect()))
}

/// The Weibull factors of [`weibull_factors`] drawn from any position: factor `c` of the stream
/// is the `c`-th of the sequential draw (each draw takes two 32-bit words of ChaCha8, so factor `c`
/// starts at word `2c`), so disjoint stretches can be drawn independently, in any order or in
/// parallel, and give the same numbers.
#[derive(Clone, Copy, Debug)]
pub struct SeekableWeibull {
    dist: UnitWeibull,
    seed: u64,
    stream: u64,
}

impl SeekableWeibull {
    /// The factors of CV `cv` (> 0) of stream `stream` of `seed`.
    pub fn new(cv: f64, seed: u64, stream: u64) -> Result<Self, SolverError> {
        Ok(SeekableWeibull { dist: UnitWeibull::from_cv(cv)?, seed, stream })
    }

    /// Factors `start..start + out.len()` into `out`.
    pub fn fill(&self, start: u64, out: &mut [f64]) {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(self.stream);
        rng.set_word_pos(2 * u128::from(start));
        for v in out {
            *v = self.dist.factor(Open01.sample(&mut rng));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_from_cv_matches_spec_values() {
        for (cv, gamma) in [(0.05, 24.95), (0.10, 12.15), (0.20, 5.80)] {
            let w = UnitWeibull::from_cv(cv).unwrap();
            assert!((w.shape - gamma).abs() < 0.01, "cv {cv}: γ = {}", w.shape);
        }
    }

    #[test]
    fn alpha_is_one_over_two_one_plus_nu() {
        for nu in [0.05, 0.2, 0.25, 0.33, 0.45] {
            let (_, alpha) = truss_constants(nu);
            assert!((alpha - 1.0 / (2.0 * (1.0 + nu))).abs() < 1e-14);
        }
    }

    #[test]
    fn zero_cv_draws_nothing_and_same_seed_repeats() {
        assert!(weibull_factors(0.0, 1, STREAM_YOUNG, 10).unwrap().is_none());
        let a = weibull_factors(0.05, 123, STREAM_YOUNG, 100).unwrap().unwrap();
        let b = weibull_factors(0.05, 123, STREAM_YOUNG, 100).unwrap().unwrap();
        let c = weibull_factors(0.05, 200, STREAM_YOUNG, 100).unwrap().unwrap();
        let d = weibull_factors(0.05, 123, STREAM_FRICTION, 100).unwrap().unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_ne!(a, d);
    }

    #[test]
    fn seeking_gives_the_sequential_draws() {
        let all = weibull_factors(0.05, 123, STREAM_YOUNG, 1000).unwrap().unwrap();
        let seek = SeekableWeibull::new(0.05, 123, STREAM_YOUNG).unwrap();
        for (start, len) in [(0, 10), (1, 7), (17, 300), (999, 1), (500, 500)] {
            let mut out = vec![0.0; len];
            seek.fill(start as u64, &mut out);
            assert_eq!(out, all[start..start + len], "from {start}");
        }
    }
}
