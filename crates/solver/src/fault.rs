//! The base face as one side of a planar fault between identical media (docs/model.md §15).
//!
//! For a planar fault between two identical elastic half-spaces loaded in shear, the tangential
//! displacement is antisymmetric across the fault and the normal stress on it does not change
//! with slip; one half models both. Its fault face carries:
//! - in the normal direction, the prescribed normal traction `σn` only as the friction's normal
//!   force `N_i = σn·A_i`: its change is zero, so the face's normal displacement is free;
//! - tangentially, the initial shear traction `τ0` (a constant force `τ0·A_i` on each face node,
//!   the [`crate::boundary::traction`] boundary) and the friction reaction of the other side,
//!   which holds the node while `|R| ≤ μ·N_i` and otherwise slides it with `μ_k·N_i`;
//! - slip = twice the face's tangential displacement (the other side moves the opposite way), so
//!   the friction law's state advances by twice what the node slides.
//!
//! Displacements are measured from the prestressed equilibrium: the initial tractions are part of
//! the state at rest, not a load that deforms the block. This does not hold for a bimaterial
//! fault, a non-planar one, or where the normal stress would change (near a free surface that the
//! fault does not cross at right angles).
//!
//! The tractions of a seed are the scene's (uniform, patches, a grid) plus, optionally, a random
//! field on the shear traction with a von Kármán spectrum, drawn from the seed's own stream
//! ([`von_karman_field`]).

use std::f64::consts::PI;

use rand::rngs::ChaCha8Rng;
use rand::{Rng, SeedableRng};

use crate::error::SolverError;
use crate::field::Lanes;

/// Random stream of the prestress field (the Weibull fields use 0 and 1).
pub const STREAM_PRESTRESS: u64 = 2;
/// Random stream of the nucleation's place.
pub const STREAM_NUCLEATION: u64 = 3;

/// The validated fault of a scene: tractions on every contact node (canonical contact order).
#[derive(Clone, Debug, PartialEq)]
pub struct Fault {
    /// Initial shear traction on each contact node along x and y (Pa).
    pub shear_pa: Vec<[f64; 2]>,
    /// Normal traction on each contact node, compression positive (Pa).
    pub normal_pa: Vec<f64>,
    /// A random field added to the shear traction along x, drawn per seed.
    pub stochastic: Option<StochasticStress>,
    /// An overstressed square placed per seed, where the rupture starts.
    pub nucleation: Option<Nucleation>,
    /// A smooth overstress growing in time (SCEC TPV101–104's nucleation).
    pub overstress: Option<Overstress>,
    /// The point of the fault `(x, y)` that benchmark files measure along strike and down dip
    /// from (m).
    pub origin_m: [f64; 2],
    /// Each contact node's share of the tractions at its depth under an overburden
    /// ([`overburden_share`]); empty when the tractions do not vary with depth. `shear_pa` and
    /// `normal_pa` hold it already; the random field, the nucleation's traction and the smooth
    /// overstress of a seed are scaled by it ([`Fault::depth_scale`]).
    pub depth_scale: Vec<f64>,
    /// The overburden's gradient (Pa/m) when the tractions follow one.
    pub overburden_gradient_pa_m: Option<f64>,
}

impl Fault {
    /// Contact node `c`'s share of the tractions at its depth (1 without an overburden).
    pub fn depth_scale(&self, c: usize) -> f64 {
        self.depth_scale.get(c).copied().unwrap_or(1.0)
    }
}

/// The mean of `min(1, s/d*)` over the depths `s` of `[lo, hi]` (m), `d*` the depth where an
/// effective normal stress growing from the surface at `gradient_pa_m` reaches `normal_pa`: the
/// share of a node's tractions kept at its depth when they all scale with the overburden above
/// `d*` (docs/model.md §15.3). The mean over the node's tile is exact (the share is piecewise
/// linear in depth), so the surface node, whose tile spans `[0, Lc/2]`, carries the tractions of
/// depth `Lc/4`, not zero.
pub fn overburden_share(gradient_pa_m: f64, normal_pa: f64, lo: f64, hi: f64) -> f64 {
    let d = normal_pa / gradient_pa_m;
    let share = |s: f64| (s / d).min(1.0);
    if hi <= lo {
        return share(lo);
    }
    if lo >= d {
        1.0
    } else if hi <= d {
        0.5 * (lo + hi) / d
    } else {
        (0.5 * (d * d - lo * lo) / d + (hi - d)) / (hi - lo)
    }
}

/// A random field on the initial shear traction with a von Kármán spectrum (docs/model.md §15):
/// power spectral density `∝ (1 + k²a²)^−(H+1)` in two dimensions, `a` the correlation length,
/// `H` the Hurst exponent; zero mean, standard deviation `std_pa` over the face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StochasticStress {
    /// Standard deviation over the face (Pa).
    pub std_pa: f64,
    /// Correlation length `a` (m).
    pub correlation_length_m: f64,
    /// Hurst exponent `H` (0 < H ≤ 1).
    pub hurst: f64,
}

/// A square of the fault whose shear traction along x is set to `shear_pa` (above the static
/// strength: the rupture starts there), its centre drawn per seed uniformly in `x_m × y_m` from
/// stream [`STREAM_NUCLEATION`] of the seed ([`Nucleation::centre`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nucleation {
    /// Side of the square (m).
    pub size_m: f64,
    /// Shear traction along x inside it (Pa).
    pub shear_pa: f64,
    /// Range of the centre along x (m).
    pub x_m: [f64; 2],
    /// Range of the centre along y (m).
    pub y_m: [f64; 2],
}

impl Nucleation {
    /// The square's centre `(x, y)` for `seed` (m).
    pub fn centre(&self, seed: u64) -> [f64; 2] {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(STREAM_NUCLEATION);
        let mut draw = |[lo, hi]: [f64; 2]| {
            // In [0, 1): 53 random bits.
            let u = (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
            lo + u * (hi - lo)
        };
        let x = draw(self.x_m);
        let y = draw(self.y_m);
        [x, y]
    }

    /// Whether the point `(x, y)` lies in the square centred at `centre` (edges included, to a
    /// millionth of the side).
    pub fn contains(&self, centre: [f64; 2], x: f64, y: f64) -> bool {
        let half = 0.5 * self.size_m * (1.0 + 1e-6);
        (x - centre[0]).abs() <= half && (y - centre[1]).abs() <= half
    }
}

/// A smooth overstress added to the shear traction along x, `Δτ(x, y, t) = Δτ₀·F(r)·G(t)` (SCEC
/// TPV101–104's nucleation, Kaneko et al. 2008): `r` the distance from the centre,
/// `F(r) = exp(r²/(r² − R²))` for `r < R` and 0 beyond, `G(t) = exp((t − T)²/(t(t − 2T)))` for
/// `0 < t < T`, 0 at `t = 0` and 1 from `T` on. Both are smooth (every derivative continuous), so
/// the rupture starts without the waves a sudden load sends out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Overstress {
    /// The centre `(x, y)` (m).
    pub centre_m: [f64; 2],
    /// The radius R (m), > 0.
    pub radius_m: f64,
    /// The peak overstress Δτ₀ at the centre (Pa).
    pub overstress_pa: f64,
    /// The rise time T (s), ≥ 0 (0: all of it at once).
    pub rise_s: f64,
}

impl Overstress {
    /// `F(r)` at the point `(x, y)`.
    pub fn shape(&self, x: f64, y: f64) -> f64 {
        let r2 = (x - self.centre_m[0]).powi(2) + (y - self.centre_m[1]).powi(2);
        let big = self.radius_m * self.radius_m;
        if r2 < big { (r2 / (r2 - big)).exp() } else { 0.0 }
    }

    /// `G(t)` at `t` seconds of the shear stage.
    pub fn ramp(&self, t_s: f64) -> f64 {
        let rise = self.rise_s;
        if t_s >= rise {
            1.0
        } else if t_s <= 0.0 {
            0.0
        } else {
            ((t_s - rise).powi(2) / (t_s * (t_s - 2.0 * rise))).exp()
        }
    }
}

/// The fault loads of one seed on every contact node (order of [`crate::Model::contact`]): the
/// shear force `τ0·A_i` along x and y and the normal force `σn·A_i` (N).
#[derive(Clone, Debug, PartialEq)]
pub struct FaultLoads {
    /// Shear force along x and y (N).
    pub shear_n: Vec<[f64; 2]>,
    /// Normal force, compression positive (N).
    pub normal_n: Vec<f64>,
    /// The smooth overstress's force along x at its peak, `Δτ₀·F(r)·A_i` (N), which
    /// [`Overstress::ramp`] scales in time; empty without one.
    pub overstress_n: Vec<f64>,
}

/// [`FaultLoads`] of `L` seeds side by side.
#[derive(Clone, Debug, PartialEq)]
pub struct FaultLanes<const L: usize> {
    /// Shear force along x and y of each contact node (N).
    pub shear_n: [Vec<Lanes<L>>; 2],
    /// Normal force of each contact node (N).
    pub normal_n: Vec<Lanes<L>>,
    /// The smooth overstress's peak force along x of each contact node (N); empty without one.
    pub overstress_n: Vec<Lanes<L>>,
}

impl<const L: usize> FaultLanes<L> {
    /// The loads of `L` seeds side by side.
    pub fn new(loads: [&FaultLoads; L]) -> Self {
        let n = loads[0].normal_n.len();
        let lanes = |f: &dyn Fn(&FaultLoads, usize) -> f64| -> Vec<Lanes<L>> {
            (0..n).map(|c| std::array::from_fn(|l| f(loads[l], c))).collect()
        };
        FaultLanes {
            shear_n: [lanes(&|s, c| s.shear_n[c][0]), lanes(&|s, c| s.shear_n[c][1])],
            normal_n: lanes(&|s, c| s.normal_n[c]),
            overstress_n: if loads[0].overstress_n.is_empty() { Vec::new() } else { lanes(&|s, c| s.overstress_n[c]) },
        }
    }
}

/// A field over a grid of `nx × ny` points `spacing_m` apart, `x` fastest: zero mean, unit
/// standard deviation, with the 2-D von Kármán spectrum `(1 + k²a²)^−(H+1)` (Frankel & Clayton
/// 1986; Mai & Beroza 2002 for faults), drawn from stream [`STREAM_PRESTRESS`] of `seed`.
///
/// Spectral synthesis on a grid padded to twice the face (so the periodic wrap-around of the
/// discrete transform does not tie opposite edges together): each wavenumber gets a complex
/// Gaussian amplitude of standard deviation `√PSD(k)` (Box–Muller on ChaCha8 draws), the field is
/// the real part of the inverse transform over the face, then centred and scaled to unit standard
/// deviation. The transform is a plain separable DFT with `libm` twiddles, so the field is
/// bit-identical on every platform.
pub fn von_karman_field(
    nx: usize,
    ny: usize,
    spacing_m: f64,
    correlation_length_m: f64,
    hurst: f64,
    seed: u64,
) -> Result<Vec<f64>, SolverError> {
    if nx == 0 || ny == 0 {
        return Ok(Vec::new());
    }
    let (px, py) = (2 * nx, 2 * ny);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(STREAM_PRESTRESS);
    let a = correlation_length_m;
    let wavenumber = |i: usize, n: usize| {
        let j = if i <= n / 2 { i as f64 } else { i as f64 - n as f64 };
        2.0 * PI * j / (n as f64 * spacing_m)
    };
    // Spectrum: complex Gaussian coefficients, kx fastest.
    let mut re = vec![0.0; px * py];
    let mut im = vec![0.0; px * py];
    for j in 0..py {
        let ky = wavenumber(j, py);
        for i in 0..px {
            let kx = wavenumber(i, px);
            let k2 = kx * kx + ky * ky;
            let amp = if i == 0 && j == 0 { 0.0 } else { libm::pow(1.0 + k2 * a * a, -0.5 * (hurst + 1.0)) };
            (re[j * px + i], im[j * px + i]) = complex_gaussian(&mut rng, amp);
        }
    }
    // Inverse DFT along x for every row, then along y for the face's columns only.
    let (cx, sx) = twiddles(px);
    let (cy, sy) = twiddles(py);
    // rows[j][x] for x < nx.
    let mut row_re = vec![0.0; py * nx];
    let mut row_im = vec![0.0; py * nx];
    for j in 0..py {
        for x in 0..nx {
            let (mut sr, mut si) = (0.0, 0.0);
            for i in 0..px {
                let t = (i * x) % px;
                let (c, s) = (cx[t], sx[t]);
                let (r, m) = (re[j * px + i], im[j * px + i]);
                sr += r * c - m * s;
                si += r * s + m * c;
            }
            row_re[j * nx + x] = sr;
            row_im[j * nx + x] = si;
        }
    }
    let mut field = vec![0.0; nx * ny];
    for y in 0..ny {
        for x in 0..nx {
            let mut sr = 0.0;
            for j in 0..py {
                let t = (j * y) % py;
                sr += row_re[j * nx + x] * cy[t] - row_im[j * nx + x] * sy[t];
            }
            field[y * nx + x] = sr;
        }
    }
    standardise(field).ok_or_else(|| {
        SolverError::Unsupported(format!(
            "a von Kármán field on {nx} × {ny} points has no variance (correlation length {a} m, spacing {spacing_m} m)"
        ))
    })
}

/// A complex Gaussian coefficient of standard deviation `amp` (Box–Muller on two uniform draws
/// in (0, 1] of 53 random bits each, with `libm`: the same on every platform).
pub(crate) fn complex_gaussian(rng: &mut ChaCha8Rng, amp: f64) -> (f64, f64) {
    let mut uniform = || ((rng.next_u64() >> 11) as f64 + 1.0) * (1.0 / (1u64 << 53) as f64);
    let (u1, u2) = (uniform(), uniform());
    let r = libm::sqrt(-2.0 * libm::log(u1));
    (amp * r * libm::cos(2.0 * PI * u2), amp * r * libm::sin(2.0 * PI * u2))
}

/// `cos` and `sin` of `2πk/n` for k < n, with `libm`.
pub(crate) fn twiddles(n: usize) -> (Vec<f64>, Vec<f64>) {
    (0..n).map(|k| (libm::cos(2.0 * PI * k as f64 / n as f64), libm::sin(2.0 * PI * k as f64 / n as f64))).unzip()
}

/// `field` centred and scaled to unit standard deviation over its points; `None` when it has no
/// variance.
pub(crate) fn standardise(field: Vec<f64>) -> Option<Vec<f64>> {
    let n = field.len() as f64;
    let mean = field.iter().sum::<f64>() / n;
    let var = field.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    if !(var > 0.0) {
        return None;
    }
    let sd = var.sqrt();
    Some(field.into_iter().map(|v| (v - mean) / sd).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_overburden_share_is_the_mean_of_its_factor_over_the_tile() {
        // Against a midpoint sum of min(1, g·s/σ) over [lo, hi] (error ~1e-8 at 20 000 points),
        // for tiles above, across and below d* = σ/g = 7326 m.
        let (g, sigma) = (16_380.0, 120e6);
        let numeric = |lo: f64, hi: f64| {
            let n = 20_000;
            (0..n).map(|i| (g * (lo + (i as f64 + 0.5) * (hi - lo) / n as f64) / sigma).min(1.0)).sum::<f64>()
                / n as f64
        };
        for (lo, hi) in [(0.0, 250.0), (750.0, 1250.0), (7000.0, 7500.0), (7200.0, 7400.0), (8000.0, 8500.0)] {
            let (exact, sum) = (overburden_share(g, sigma, lo, hi), numeric(lo, hi));
            assert!((exact - sum).abs() < 1e-7, "[{lo}, {hi}]: {exact} against {sum}");
        }
        // The surface row of 500 m modules: the tractions of depth Lc/4.
        assert!((overburden_share(g, sigma, 0.0, 250.0) - g * 125.0 / sigma).abs() < 1e-15);
        assert_eq!(overburden_share(g, sigma, 8000.0, 8500.0), 1.0);
    }

    /// Correlation of a field with itself shifted by `lag` points along x, averaged over the grid.
    fn correlation_x(f: &[f64], nx: usize, ny: usize, lag: usize) -> f64 {
        let mut s = 0.0;
        let mut n = 0.0;
        for y in 0..ny {
            for x in 0..nx - lag {
                s += f[y * nx + x] * f[y * nx + x + lag];
                n += 1.0;
            }
        }
        s / n
    }

    #[test]
    fn the_field_is_reproducible_centred_and_unit() {
        let a = von_karman_field(40, 20, 100.0, 1000.0, 0.75, 7).unwrap();
        let b = von_karman_field(40, 20, 100.0, 1000.0, 0.75, 7).unwrap();
        let c = von_karman_field(40, 20, 100.0, 1000.0, 0.75, 8).unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
        let mean = a.iter().sum::<f64>() / a.len() as f64;
        let var = a.iter().map(|v| v * v).sum::<f64>() / a.len() as f64;
        assert!(mean.abs() < 1e-12 && (var - 1.0).abs() < 1e-12);
    }

    #[test]
    fn correlation_falls_with_lag_on_the_scale_of_the_correlation_length() {
        // Averaged over seeds, the correlation at a lag of a tenth of `a` is high and at several
        // `a` low: the field is smooth on the scale asked for.
        let (nx, ny, dx, a) = (64, 32, 100.0, 800.0);
        let (mut near, mut far) = (0.0, 0.0);
        let seeds = 20;
        for seed in 0..seeds {
            let f = von_karman_field(nx, ny, dx, a, 0.8, seed).unwrap();
            near += correlation_x(&f, nx, ny, 1) / seeds as f64;
            far += correlation_x(&f, nx, ny, 32) / seeds as f64;
        }
        assert!(near > 0.8, "correlation at 0.125 a: {near}");
        assert!(far.abs() < 0.25, "correlation at 4 a: {far}");
    }

    #[test]
    fn the_smooth_overstress_has_tpv101s_shape_and_ramp() {
        // F(R/2) = exp((1/4)/(1/4 − 1)) = exp(−1/3), G(T/2) = exp((1/4)/(−3/4)) = exp(−1/3); both 1
        // at the centre and from T on, 0 at R and at t = 0.
        let o = super::Overstress { centre_m: [1_000.0, 2_000.0], radius_m: 3_000.0, overstress_pa: 25e6, rise_s: 1.0 };
        let third = (-1.0f64 / 3.0).exp();
        assert_eq!(o.shape(1_000.0, 2_000.0), 1.0);
        assert!((o.shape(2_500.0, 2_000.0) - third).abs() < 1e-15);
        assert!((o.shape(1_000.0, 500.0) - third).abs() < 1e-15);
        assert_eq!(o.shape(4_000.0, 2_000.0), 0.0);
        assert_eq!(o.ramp(0.0), 0.0);
        assert!((o.ramp(0.5) - third).abs() < 1e-15);
        assert_eq!(o.ramp(1.0), 1.0);
        assert_eq!(o.ramp(7.0), 1.0);
        assert!(o.ramp(1e-3) < 1e-200 && o.ramp(0.999) > 0.999);
    }
}
