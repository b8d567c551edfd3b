//! A frequency-independent Q over a band by four relaxation mechanisms (a generalized standard
//! linear solid, as SPECFEM and SeisSol use with three), every bar carrying all four, each a
//! memory variable stored as `f32` (16 bytes per bar and seed; docs/model.md §18).
//!
//! Why not the coarse-grained scheme (Day 1998; Day & Bradley 2001), one mechanism per bar cycled
//! over a 2 × 2 × 2 block of modules with eight times its weight: tried first, a plane S wave in
//! a column of the lattice lost amplitude 15% faster than `exp(−πfx/(Qc))` at Q = 20 and 1 Hz
//! (26% at 2.5 Hz; 4% and 8% at Q = 50) and travelled 1.2% slow at the reference frequency. A
//! bar's complex stiffness then varies from module to module by up to half its value, and the
//! lattice averages such a mixture neither arithmetically nor harmonically. With every bar alike
//! the medium is homogeneous and the fit below is what the waves see.
//!
//! The body's modulus is `M(ω) = M_U·[1 − Σ_j λ_j/(1 + iωτ_j)]` with relaxation times `τ_j`
//! log-spaced from the band's lower edge over 1.3 to its upper one times 1.3 and weights `λ_j` fitted so that `Im M/Re M = 1/Q` at 64 frequencies
//! log-spaced over it: `Σ_j λ_j·(ωτ_j + 1/Q)/(1 + ω²τ_j²) = 1/Q` is linear in the `λ_j`, so the fit
//! is one non-negative least-squares solve. `M_U` is set so that the phase speed at the reference frequency
//! is the elastic one the scene gives.

use nalgebra::{Complex, DMatrix, DVector};

/// Relaxation mechanisms of every bar.
pub const MECHANISMS: usize = 4;

/// The largest total weight `Σλ_j`: the relaxed stiffness stays at least 10% of the unrelaxed
/// one (the lowest Q over a band follows from it: 2 over 0.05–5 Hz).
pub const MAX_WEIGHT: f64 = 0.9;

/// The widest band (upper over lower edge) four mechanisms hold Q flat over to 2.5%.
pub const MAX_BAND_RATIO: f64 = 100.0;

/// How far beyond the band the relaxation frequencies reach (a factor).
const EDGE: f64 = 1.3;

/// Frequencies of the fit across the band.
const FIT_POINTS: usize = 64;

/// A constant Q over a band by [`MECHANISMS`] relaxation mechanisms.
#[derive(Clone, Debug, PartialEq)]
pub struct Relaxation {
    /// The target quality factor.
    pub q: f64,
    /// The band over which Q is constant (Hz).
    pub band_hz: [f64; 2],
    /// Where the phase speed is the elastic one (Hz).
    pub reference_hz: f64,
    /// Relaxation times (s), log-spaced over the band.
    pub tau_s: [f64; MECHANISMS],
    /// Weights `λ_j`.
    pub weight: [f64; MECHANISMS],
    /// Unrelaxed modulus over the elastic one, `M_U/M₀`.
    pub unrelaxed: f64,
}

impl Relaxation {
    /// The mechanisms whose Q is `q` over `band_hz` and whose phase speed at `reference_hz` is the
    /// elastic one. The caller has checked `q > 0`, `0 < band[0] < band[1]`, `reference > 0`.
    pub fn fit(q: f64, band_hz: [f64; 2], reference_hz: f64) -> Relaxation {
        let [f0, f1] = band_hz;
        let log_spaced = |n: usize, i: usize| f0 * (f1 / f0).powf(i as f64 / (n - 1) as f64);
        // Relaxation frequencies from the band's lower edge over 1.3 to its upper one times 1.3:
        // the mechanisms at the edges then hold Q flat to the band's ends (2.4% over two decades
        // instead of 5%).
        let (r0, r1) = (f0 / EDGE, f1 * EDGE);
        let tau_s: [f64; MECHANISMS] = std::array::from_fn(|j| {
            1.0 / (2.0 * std::f64::consts::PI * r0 * (r1 / r0).powf(j as f64 / (MECHANISMS - 1) as f64))
        });
        let a = DMatrix::from_fn(FIT_POINTS, MECHANISMS, |k, j| {
            let wt = 2.0 * std::f64::consts::PI * log_spaced(FIT_POINTS, k) * tau_s[j];
            (wt + 1.0 / q) / (1.0 + wt * wt)
        });
        let b = DVector::from_element(FIT_POINTS, 1.0 / q);
        let x = non_negative_least_squares(&a, &b);
        let weight: [f64; MECHANISMS] = std::array::from_fn(|j| x[j]);
        let mut r = Relaxation { q, band_hz, reference_hz, tau_s, weight, unrelaxed: 1.0 };
        // Phase speed ∝ 1/Re(√(1/m)) with m = M/M_U: set M_U so it is c₀ at the reference.
        let m = r.relative_modulus(reference_hz);
        let slowness = (Complex::new(1.0, 0.0) / m).sqrt().re;
        r.unrelaxed = slowness * slowness;
        r
    }

    /// `M(f)/M_U` of the body.
    fn relative_modulus(&self, f: f64) -> Complex<f64> {
        let w = 2.0 * std::f64::consts::PI * f;
        let mut m = Complex::new(1.0, 0.0);
        for (t, l) in self.tau_s.iter().zip(&self.weight) {
            m -= Complex::new(*l, 0.0) / Complex::new(1.0, w * t);
        }
        m
    }

    /// `M(f)/M₀`: the body's complex modulus over the elastic one.
    pub fn modulus(&self, f: f64) -> Complex<f64> {
        self.relative_modulus(f) * self.unrelaxed
    }

    /// The body's Q at `f` (`Re M/Im M`).
    pub fn q_at(&self, f: f64) -> f64 {
        let m = self.modulus(f);
        m.re / m.im
    }

    /// Phase speed at `f` over the elastic one: `1/Re √(M₀/M)`.
    pub fn phase_speed_ratio(&self, f: f64) -> f64 {
        1.0 / (Complex::new(1.0, 0.0) / self.modulus(f)).sqrt().re
    }

    /// Amplitude decay per metre at `f` of a wave of elastic speed `c` (1/m): `Im k`.
    pub fn decay_per_m(&self, f: f64, c: f64) -> f64 {
        let w = 2.0 * std::f64::consts::PI * f;
        (w / c * (Complex::new(1.0, 0.0) / self.modulus(f)).sqrt()).im.abs()
    }

    /// The largest relative misfit `|Q(f)/Q − 1|` over the band (64 points).
    pub fn misfit(&self) -> f64 {
        let [f0, f1] = self.band_hz;
        (0..FIT_POINTS)
            .map(|k| f0 * (f1 / f0).powf(k as f64 / (FIT_POINTS - 1) as f64))
            .map(|f| (self.q_at(f) / self.q - 1.0).abs())
            .fold(0.0, f64::max)
    }

    /// `Σλ_j`: the relaxed stiffness is `1 −` this of the unrelaxed one.
    pub fn total_weight(&self) -> f64 {
        self.weight.iter().sum()
    }

    /// The relaxed modulus over the elastic one, `M(0)/M₀` (the static stiffness).
    pub fn relaxed(&self) -> f64 {
        self.unrelaxed * (1.0 - self.weight.iter().sum::<f64>())
    }
}

/// `argmin ‖Ax − b‖` over `x ≥ 0` (Lawson & Hanson's active-set method): a weight below zero
/// would make its bars give energy back, so the fit keeps every weight non-negative.
fn non_negative_least_squares(a: &DMatrix<f64>, b: &DVector<f64>) -> DVector<f64> {
    let n = a.ncols();
    let mut x = DVector::zeros(n);
    let mut passive = vec![false; n];
    let solve_passive = |passive: &[bool]| -> DVector<f64> {
        let cols: Vec<usize> = (0..n).filter(|&j| passive[j]).collect();
        let sub = DMatrix::from_fn(a.nrows(), cols.len(), |i, c| a[(i, cols[c])]);
        let z = sub.svd(true, true).solve(b, 1e-15).expect("the SVD was computed with both factors");
        let mut full = DVector::zeros(n);
        for (c, &j) in cols.iter().enumerate() {
            full[j] = z[c];
        }
        full
    };
    for _ in 0..(3 * n) {
        let w = a.transpose() * (b - a * &x);
        let Some(j) = (0..n).filter(|&j| !passive[j] && w[j] > 1e-15).max_by(|&i, &k| w[i].total_cmp(&w[k])) else {
            break;
        };
        passive[j] = true;
        loop {
            let z = solve_passive(&passive);
            if (0..n).filter(|&j| passive[j]).all(|j| z[j] > 0.0) {
                x = z;
                break;
            }
            // Step from x towards z until the first passive weight reaches zero; drop it.
            let alpha = (0..n)
                .filter(|&j| passive[j] && z[j] <= 0.0)
                .map(|j| x[j] / (x[j] - z[j]))
                .fold(f64::INFINITY, f64::min);
            x += (&z - &x) * alpha;
            for j in 0..n {
                if passive[j] && x[j] <= 1e-18 {
                    passive[j] = false;
                    x[j] = 0.0;
                }
            }
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q_is_constant_over_two_decades_to_within_three_percent() {
        for q in [5.0, 20.0, 50.0, 200.0, 1000.0] {
            for band in [[0.05, 5.0], [0.01, 1.0], [0.1, 1.0], [0.2, 2.0]] {
                let r = Relaxation::fit(q, band, 1.0);
                assert!(r.misfit() < 0.03, "Q {q} over {band:?}: misfit {}", r.misfit());
                assert!(r.weight.iter().all(|&w| w >= 0.0), "Q {q} over {band:?}: weights {:?}", r.weight);
                assert!(r.total_weight() < MAX_WEIGHT, "Q {q} over {band:?}: weight {}", r.total_weight());
            }
        }
    }

    #[test]
    fn the_reference_frequency_keeps_the_elastic_speed_and_dispersion_follows_the_closed_form() {
        for q in [20.0, 50.0, 200.0] {
            let r = Relaxation::fit(q, [0.05, 5.0], 1.0);
            assert!((r.phase_speed_ratio(1.0) - 1.0).abs() < 1e-12);
            for f in [0.1, 0.3, 3.0] {
                let closed = 1.0 + (f / 1.0f64).ln() / (std::f64::consts::PI * q);
                let got = r.phase_speed_ratio(f);
                assert!((got / closed - 1.0).abs() < 2e-3, "Q {q} at {f} Hz: {got} vs {closed}");
            }
            assert!(r.unrelaxed > 1.0 && r.relaxed() < 1.0);
        }
    }
}
