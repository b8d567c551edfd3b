//! Bloch (plane-wave) dispersion of the unbounded LDEM cubic-truss lattice and the highest frequency it resolves.
//!
//! # The periodic cell
//!
//! The unbounded lattice is simple cubic with period `Lc` and a two-node basis: the corner node
//! `A` at `0` and the centre node `B` at `(½, ½, ½)·Lc`, each of lumped mass `m = ρ·Lc³/2`. One
//! cell owns 14 bars ([`cell_bars`]):
//! - 3 edge bars `A → A + Lc·e_a` and 3 centre bars `B → B + Lc·e_a`, spring constant
//!   `k_n = EA_n/Lc = α·E·Lc`;
//! - 8 diagonals `B → A + (s_x, s_y, s_z)·Lc/2`, `s = ±1`, spring constant
//!   `k_d = EA_d/(Lc·√3/2) = (4δ/3)·α·E·Lc`,
//!
//! with `δ = 9ν/(4−8ν)` and `α = (9+8δ)/(18+24δ)` ([`crate::material`]).
//!
//! # Dynamical matrix
//!
//! With `u_p(R) = U_p·exp(i(k·(R + r_p) − ωt))` (the phase of the node's own position `R + r_p`),
//! a bar from node `p` to node `q` along `d` (unit vector `e = d/|d|`, spring constant `k_b`)
//! adds `k_b·eeᵀ` to the 3×3 blocks `K_pp` and `K_qq`, and `−k_b·eeᵀ·e^{+ik·d}` to `K_pq`,
//! `−k_b·eeᵀ·e^{−ik·d}` to `K_qp` (small strain: bar force `k_b·e·eᵀ(u_q − u_p)`). Then
//! `ω²·Ũ = D(k)·Ũ` with `D(k) = M^{−1/2}·K(k)·M^{−1/2}` (6×6, Hermitian, positive semi-definite)
//! and `Ũ = M^{1/2}·U`; [`dynamical_matrix`], [`bloch_spectrum`], [`bloch_modes`].
//!
//! # Branches, identified by polarisation
//!
//! Along a cube axis and along the body diagonal ([`WaveDirection`]) every 3×3 block of `D` has
//! the wave direction `n` and every direction `⊥ n` as eigenvectors, so `D` splits exactly into a
//! longitudinal 2×2 block (polarisation `n` on both nodes) and two equal transverse 2×2 blocks.
//! The P and S branches are the lower eigenvalue of the longitudinal and of the transverse block,
//! the optical branches OP and OS the upper ones ([`Branch`]); the two never cross within a block,
//! whereas P may well cross OS, which is why branches are not found by sorting the six ω.
//! Along `x` (and `y`, `z`: cubic symmetry), with `s = sin`, `c = cos`:
//!
//! ```text
//! m·ω²_S,OS = (16/3)·k_d·{s², c²}(q·Lc/4)
//! m·ω²_P,OP = 4·k_n·s²(q·Lc/2) + (8/3)·k_d·(1 ∓ c(q·Lc/2))
//! ```
//!
//! so the phase velocities are `c_S(q) = C_s·sinc(q·Lc/4)` and
//! `c_P(q)² = C_p²·[sinc²(q·Lc/2) + (4δ/9)·sinc²(q·Lc/4)]/(1 + 4δ/9)` (`sinc x = sin x / x`), with
//! the long-wave speeds `ρ·C_p² = C11 = (2k_n + ⅔k_d)/Lc = λ+2μ` and `ρ·C_s² = C44 = ⅔k_d/Lc = λ`.
//! The Brillouin zone edge along an axis is `q = π/Lc` (wavelength `2·Lc`); along the body
//! diagonal `|k| = √3·π/Lc`. At the axis zone edge S meets OS, so the lowest optical frequency
//! along an axis is `f = √2·C_s/(π·Lc) ≈ 0.450·C_s/Lc`, the top of the S branch.
//!
//! # The usable band
//!
//! `f_max(ε)` is the lowest frequency at which the phase velocity `c = ω/q` of P or S, along any
//! of the examined directions (default `x` and `z`), departs from its long-wave value `c₀` by
//! `|c/c₀ − 1| = ε` (default [`DEFAULT_TOLERANCE`] = 5 %), found by bisection on the branch
//! ([`usable_band`]). Along an axis the S branch gives the closed form
//!
//! ```text
//! sinc(x*) = 1 − ε,  x* = q*·Lc/4,  f_S = (2(1−ε)·x*/π)·C_s/Lc,  λ/Lc = π/(2x*)
//! ```
//!
//! independent of ν: for ε = 5 %, `x* = 0.5519`, `f_S = 0.3338·C_s/Lc`, `λ = 2.85·Lc`. The P
//! branch departs at a longer wavelength (`λ = 5.11·Lc` at ν = 0.2, `4.91·Lc` at ν = 0.25) but,
//! for ν < 0.2527, at a higher frequency (`0.1858·C_p/Lc = 0.372·C_s/Lc` at ν = 0.2), so S sets
//! the limit there: `f_max = 0.3338·C_s/Lc`. Above ν = 0.2527 P sets it, with `f_max·Lc/C_s`
//! between 0.292 (ν = 0.4) and 0.334. The body diagonal departs later than the axes. The lowest
//! optical frequency, `0.4502·C_s/Lc`, is also the lowest of the fourth band over the whole zone
//! (sampled, [`lowest_optical_in_zone`]). Prototype scaling at equal E and ρ: lengths and times
//! ×λ_sim, so frequencies ÷λ_sim ([`prototype_frequency_hz`]). Paper lattice (E = 2e10 Pa,
//! ρ = 2400 kg/m³, ν = 0.2, Lc = 0.1 m): `f_max` = 5078 Hz (S), optical from 6849 Hz; at
//! λ_sim = 10⁴, 0.508 Hz and 0.685 Hz.

use std::f64::consts::PI;
use std::fmt;

use nalgebra::{Complex, Matrix6, SymmetricEigen, Vector6};

use crate::geometry::BarFamily;
use crate::material;

/// Default phase-velocity departure that bounds the usable band (5 %).
pub const DEFAULT_TOLERANCE: f64 = 0.05;

/// Grid points along a branch scanned before bisecting (the departure is smooth and monotone on
/// the acoustic branches; the scan only brackets the first crossing).
const SCAN_POINTS: usize = 512;

/// Everything that can go wrong here: a refused input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DispersionError {
    /// A parameter outside its allowed range; nothing was computed.
    #[error("{parameter} = {value} is not allowed: {allowed}")]
    InvalidParameter {
        /// Name of the parameter, e.g. `poisson`.
        parameter: &'static str,
        /// The value as given.
        value: f64,
        /// What would be accepted, e.g. `0 < poisson < 0.5`.
        allowed: String,
    },
    /// A branch of the wrong kind for the question (an optical branch has no long-wave speed).
    #[error("branch {branch} is not allowed here: {allowed}")]
    InvalidBranch {
        /// The branch as given.
        branch: Branch,
        /// What would be accepted.
        allowed: &'static str,
    },
}

fn refuse(parameter: &'static str, value: f64, allowed: impl Into<String>) -> DispersionError {
    DispersionError::InvalidParameter { parameter, value, allowed: allowed.into() }
}

fn positive(parameter: &'static str, value: f64, unit: &str) -> Result<f64, DispersionError> {
    if !(value > 0.0 && value.is_finite()) {
        return Err(refuse(parameter, value, format!("a finite {parameter} > 0 {unit}")));
    }
    Ok(value)
}

/// The homogeneous lattice: material and module side, validated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatticeMaterial {
    young_pa: f64,
    poisson: f64,
    density_kg_m3: f64,
    lc_m: f64,
}

impl LatticeMaterial {
    /// Young's modulus `E` (Pa), Poisson's ratio `ν` (`0 < ν < 0.5`), density `ρ` (kg/m³) and
    /// module side `Lc` (m); refuses non-finite or out-of-range values, naming the parameter.
    pub fn new(young_pa: f64, poisson: f64, density_kg_m3: f64, lc_m: f64) -> Result<Self, DispersionError> {
        positive("young_pa", young_pa, "Pa")?;
        if !(poisson > 0.0 && poisson < 0.5) {
            return Err(refuse("poisson", poisson, "0 < poisson < 0.5"));
        }
        positive("density_kg_m3", density_kg_m3, "kg/m³")?;
        positive("lc_m", lc_m, "m")?;
        Ok(LatticeMaterial { young_pa, poisson, density_kg_m3, lc_m })
    }

    /// Young's modulus `E` (Pa).
    pub fn young_pa(&self) -> f64 {
        self.young_pa
    }

    /// Poisson's ratio `ν`.
    pub fn poisson(&self) -> f64 {
        self.poisson
    }

    /// Density `ρ` (kg/m³).
    pub fn density_kg_m3(&self) -> f64 {
        self.density_kg_m3
    }

    /// Module side `Lc` (m).
    pub fn lc_m(&self) -> f64 {
        self.lc_m
    }

    /// The cubic-truss constants `(δ, α)`: `δ = 9ν/(4−8ν)`, `α = (9+8δ)/(18+24δ)`
    /// ([`material::truss_constants`]).
    pub fn truss_constants(&self) -> (f64, f64) {
        material::truss_constants(self.poisson)
    }

    /// Spring constant `k_n = EA_n/Lc = α·E·Lc` (N/m) of an edge or centre bar.
    pub fn normal_bar_stiffness_n_m(&self) -> f64 {
        material::axial_stiffness(BarFamily::Edge, self.young_pa, self.poisson, self.lc_m) / self.lc_m
    }

    /// Spring constant `k_d = EA_d/(Lc·√3/2) = (4δ/3)·α·E·Lc` (N/m) of a diagonal.
    pub fn diagonal_bar_stiffness_n_m(&self) -> f64 {
        material::axial_stiffness(BarFamily::Diagonal, self.young_pa, self.poisson, self.lc_m)
            / (0.5 * 3f64.sqrt() * self.lc_m)
    }

    /// Lumped mass `ρ·Lc³/2` (kg) of either node of the cell (an interior corner or a centre).
    pub fn node_mass_kg(&self) -> f64 {
        0.5 * self.density_kg_m3 * self.lc_m.powi(3)
    }

    /// The elastic constants `(C11, C12, C44)` (Pa) of affine strain: `λ+2μ`, `λ`, `λ`
    /// ([`material::lattice_elastic_constants`]).
    pub fn elastic_constants_pa(&self) -> (f64, f64, f64) {
        material::lattice_elastic_constants(self.young_pa, self.poisson)
    }

    /// Long-wave speeds along a cube axis `(C_p, C_s) = (√(C11/ρ), √(C44/ρ))` (m/s).
    pub fn long_wave_speeds_m_s(&self) -> (f64, f64) {
        let (c11, _, c44) = self.elastic_constants_pa();
        ((c11 / self.density_kg_m3).sqrt(), (c44 / self.density_kg_m3).sqrt())
    }
}

/// The two nodes of the periodic cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CellNode {
    /// The corner node `A` at `0` (rows 0..3 of the dynamical matrix).
    Corner,
    /// The centre node `B` at `(½, ½, ½)·Lc` (rows 3..6).
    Centre,
}

impl CellNode {
    fn index(self) -> usize {
        match self {
            CellNode::Corner => 0,
            CellNode::Centre => 1,
        }
    }
}

/// One bar of the periodic cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellBar {
    /// Start node (in this cell).
    pub from: CellNode,
    /// End node (in this or a neighbouring cell).
    pub to: CellNode,
    /// Family.
    pub family: BarFamily,
    /// Vector from the start node to the end node `d` (m).
    pub offset_m: [f64; 3],
    /// Spring constant `EA/L` (N/m).
    pub stiffness_n_m: f64,
}

/// The 14 bars one cell owns: 3 edge bars, 8 diagonals, 3 centre bars (each bar of the unbounded
/// lattice belongs to exactly one cell).
pub fn cell_bars(material: &LatticeMaterial) -> Vec<CellBar> {
    let lc = material.lc_m();
    let (kn, kd) = (material.normal_bar_stiffness_n_m(), material.diagonal_bar_stiffness_n_m());
    let mut bars = Vec::with_capacity(14);
    for a in 0..3 {
        let mut d = [0.0; 3];
        d[a] = lc;
        let bar = |from, to, family| CellBar { from, to, family, offset_m: d, stiffness_n_m: kn };
        bars.push(bar(CellNode::Corner, CellNode::Corner, BarFamily::Edge));
        bars.push(bar(CellNode::Centre, CellNode::Centre, BarFamily::Centre));
    }
    for corner in 0..8 {
        let d = [0, 1, 2].map(|a| if corner >> a & 1 == 1 { 0.5 * lc } else { -0.5 * lc });
        bars.push(CellBar {
            from: CellNode::Centre,
            to: CellNode::Corner,
            family: BarFamily::Diagonal,
            offset_m: d,
            stiffness_n_m: kd,
        });
    }
    bars
}

/// `D(k)` and its derivative `∂D/∂q` along the unit vector `n` (`k = q·n`).
fn assemble(material: &LatticeMaterial, k: [f64; 3], n: [f64; 3]) -> (Matrix6<Complex<f64>>, Matrix6<Complex<f64>>) {
    let mut d = Matrix6::<Complex<f64>>::zeros();
    let mut dd = Matrix6::<Complex<f64>>::zeros();
    let m = material.node_mass_kg();
    for bar in cell_bars(material) {
        let len = bar.offset_m.iter().map(|v| v * v).sum::<f64>().sqrt();
        let e = bar.offset_m.map(|v| v / len);
        let phase_arg: f64 = (0..3).map(|a| k[a] * bar.offset_m[a]).sum();
        let proj: f64 = (0..3).map(|a| n[a] * bar.offset_m[a]).sum();
        let phase = Complex::from_polar(1.0, phase_arg);
        let (p, q) = (3 * bar.from.index(), 3 * bar.to.index());
        for i in 0..3 {
            for j in 0..3 {
                let s = bar.stiffness_n_m * e[i] * e[j] / m;
                d[(p + i, p + j)] += s;
                d[(q + i, q + j)] += s;
                d[(p + i, q + j)] -= phase * s;
                d[(q + i, p + j)] -= phase.conj() * s;
                // ∂/∂q e^{±i q n·d} = ±i (n·d) e^{±i q n·d}
                dd[(p + i, q + j)] -= Complex::new(0.0, proj) * phase * s;
                dd[(q + i, p + j)] += Complex::new(0.0, proj) * phase.conj() * s;
            }
        }
    }
    (d, dd)
}

/// The 6×6 Hermitian dynamical matrix `D(k) = M^{−1/2}·K(k)·M^{−1/2}` (rad²/s²) at wave vector
/// `k` (rad/m); rows 0..3 are the corner node's `x, y, z`, rows 3..6 the centre node's.
pub fn dynamical_matrix(material: &LatticeMaterial, k_rad_m: [f64; 3]) -> Matrix6<Complex<f64>> {
    assemble(material, k_rad_m, [0.0; 3]).0
}

/// The six angular frequencies `ω` (rad/s) at wave vector `k` (rad/m), ascending (band order,
/// which mixes branches: use [`branch_point`] for P and S).
pub fn bloch_spectrum(material: &LatticeMaterial, k_rad_m: [f64; 3]) -> [f64; 6] {
    let eig = SymmetricEigen::new(dynamical_matrix(material, k_rad_m));
    let mut w: [f64; 6] = std::array::from_fn(|i| eig.eigenvalues[i].max(0.0).sqrt());
    w.sort_by(f64::total_cmp);
    w
}

/// Direction of propagation: the pure-mode directions of the cubic lattice used here.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum WaveDirection {
    /// Along `x` (slip direction).
    X,
    /// Along `y`.
    Y,
    /// Along `z` (height).
    Z,
    /// Along the body diagonal `(1, 1, 1)/√3`.
    BodyDiagonal,
}

impl WaveDirection {
    /// Unit vector `n` of the direction.
    pub fn unit(self) -> [f64; 3] {
        match self {
            WaveDirection::X => [1.0, 0.0, 0.0],
            WaveDirection::Y => [0.0, 1.0, 0.0],
            WaveDirection::Z => [0.0, 0.0, 1.0],
            WaveDirection::BodyDiagonal => [1.0 / 3f64.sqrt(); 3],
        }
    }

    /// One transverse polarisation (a unit vector `⊥ n`; the other is `n × t`, same branch).
    pub fn transverse(self) -> [f64; 3] {
        match self {
            WaveDirection::X | WaveDirection::Z => [0.0, 1.0, 0.0],
            WaveDirection::Y => [0.0, 0.0, 1.0],
            WaveDirection::BodyDiagonal => [1.0 / 2f64.sqrt(), -1.0 / 2f64.sqrt(), 0.0],
        }
    }

    /// Wavenumber of the Brillouin-zone edge along this direction (rad/m): `π/Lc` on an axis,
    /// `√3·π/Lc` on the body diagonal (where the ray leaves the cube `|k_a| ≤ π/Lc`).
    pub fn zone_edge_rad_m(self, lc_m: f64) -> f64 {
        let n = self.unit();
        PI / (lc_m * n.iter().fold(0.0f64, |m, v| m.max(v.abs())))
    }
}

impl fmt::Display for WaveDirection {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            WaveDirection::X => "x",
            WaveDirection::Y => "y",
            WaveDirection::Z => "z",
            WaveDirection::BodyDiagonal => "[111]",
        })
    }
}

/// Polarisation of a branch.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Polarisation {
    /// Along the wave direction.
    Longitudinal,
    /// Perpendicular to the wave direction.
    Transverse,
}

/// A dispersion branch along a pure-mode direction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Branch {
    /// Acoustic longitudinal (the P wave).
    P,
    /// Acoustic transverse (the S wave, two equal polarisations).
    S,
    /// Optical longitudinal (the two sub-lattices in antiphase at `k = 0`).
    OpticalP,
    /// Optical transverse.
    OpticalS,
}

impl Branch {
    /// Polarisation of the branch.
    pub fn polarisation(self) -> Polarisation {
        match self {
            Branch::P | Branch::OpticalP => Polarisation::Longitudinal,
            Branch::S | Branch::OpticalS => Polarisation::Transverse,
        }
    }

    /// Whether the branch is optical (non-zero frequency at `k = 0`).
    pub fn is_optical(self) -> bool {
        matches!(self, Branch::OpticalP | Branch::OpticalS)
    }
}

impl fmt::Display for Branch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Branch::P => "P",
            Branch::S => "S",
            Branch::OpticalP => "optical P",
            Branch::OpticalS => "optical S",
        })
    }
}

/// Long-wave (continuum) phase velocity (m/s) of `polarisation` along `direction`, from the
/// Christoffel equation `ρc² = pᵀΓp`, `Γ_ik = C_ijkl·n_j·n_l` of the cubic `C11, C12, C44`.
pub fn long_wave_speed_m_s(material: &LatticeMaterial, direction: WaveDirection, polarisation: Polarisation) -> f64 {
    let (c11, c12, c44) = material.elastic_constants_pa();
    let n = direction.unit();
    let p = match polarisation {
        Polarisation::Longitudinal => n,
        Polarisation::Transverse => direction.transverse(),
    };
    // Γ = (C11 − C12 − 2C44)·diag(n²) + C44·I + (C12 + C44)·n nᵀ for a cubic medium.
    let mut rho_c2 = 0.0;
    for i in 0..3 {
        for k in 0..3 {
            let mut g = (c12 + c44) * n[i] * n[k];
            if i == k {
                g += (c11 - c12 - 2.0 * c44) * n[i] * n[i] + c44;
            }
            rho_c2 += p[i] * g * p[k];
        }
    }
    (rho_c2 / material.density_kg_m3()).sqrt()
}

/// One point of a branch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BranchPoint {
    /// Wavenumber `q = |k|` (rad/m).
    pub wavenumber_rad_m: f64,
    /// Wavelength in modules `λ/Lc = 2π/(q·Lc)` (∞ at `q = 0`).
    pub wavelength_per_module: f64,
    /// Angular frequency `ω` (rad/s).
    pub omega_rad_s: f64,
    /// Frequency `f = ω/2π` (Hz).
    pub frequency_hz: f64,
    /// Phase velocity `ω/q` (m/s); the long-wave limit at `q = 0` (∞ on an optical branch).
    pub phase_velocity_m_s: f64,
    /// Group velocity `dω/dq` (m/s), from the analytic `∂D/∂q` on the branch's 2×2 block (where
    /// the branch touches its partner, at the axis zone edge for S and OS, the limit from inside
    /// the zone).
    pub group_velocity_m_s: f64,
}

/// `ω²` (rad²/s²) of `branch` at `q` along `direction` and its derivative `dω²/dq`.
fn branch_eigenvalue(material: &LatticeMaterial, direction: WaveDirection, branch: Branch, q: f64) -> (f64, f64) {
    let n = direction.unit();
    let (d, dd) = assemble(material, n.map(|v| q * v), n);
    let pol = match branch.polarisation() {
        Polarisation::Longitudinal => n,
        Polarisation::Transverse => direction.transverse(),
    };
    // 2×2 block on the basis (pol on the corner, pol on the centre): [[a, b], [b̄, c]].
    let block = |m: &Matrix6<Complex<f64>>, r: usize, s: usize| -> Complex<f64> {
        let mut z = Complex::new(0.0, 0.0);
        for i in 0..3 {
            for j in 0..3 {
                z += m[(3 * r + i, 3 * s + j)] * pol[i] * pol[j];
            }
        }
        z
    };
    let (a, b, c) = (block(&d, 0, 0).re, block(&d, 0, 1), block(&d, 1, 1).re);
    let (da, db, dc) = (block(&dd, 0, 0).re, block(&dd, 0, 1), block(&dd, 1, 1).re);
    let (mean, half) = (0.5 * (a + c), 0.5 * (a - c));
    let r = (half * half + b.norm_sqr()).sqrt();
    let sign = if branch.is_optical() { 1.0 } else { -1.0 };
    // Where the block is degenerate (S meets OS at the axis zone edge) r has a kink: take the
    // limit from inside the zone, where r decreases to 0 at the rate |r'| = √(h'² + |b'|²).
    let dr = if r > 1e-9 * (a.abs() + c.abs()) {
        (half * 0.5 * (da - dc) + (b.conj() * db).re) / r
    } else {
        -(0.25 * (da - dc).powi(2) + db.norm_sqr()).sqrt()
    };
    (mean + sign * r, 0.5 * (da + dc) + sign * dr)
}

/// The point of `branch` along `direction` at wavenumber `q` (rad/m), `0 ≤ q ≤` the zone edge
/// ([`WaveDirection::zone_edge_rad_m`]).
pub fn branch_point(
    material: &LatticeMaterial,
    direction: WaveDirection,
    branch: Branch,
    wavenumber_rad_m: f64,
) -> Result<BranchPoint, DispersionError> {
    let edge = direction.zone_edge_rad_m(material.lc_m());
    let q = wavenumber_rad_m;
    if !(q >= 0.0 && q <= edge) {
        return Err(refuse(
            "wavenumber_rad_m",
            q,
            format!("0 ≤ wavenumber ≤ {edge:.6} rad/m (Brillouin-zone edge along {direction})"),
        ));
    }
    Ok(point_unchecked(material, direction, branch, q))
}

fn point_unchecked(material: &LatticeMaterial, direction: WaveDirection, branch: Branch, q: f64) -> BranchPoint {
    let (w2, dw2) = branch_eigenvalue(material, direction, branch, q);
    let omega = w2.max(0.0).sqrt();
    let long_wave = long_wave_speed_m_s(material, direction, branch.polarisation());
    let (phase, group) = if q == 0.0 {
        if branch.is_optical() { (f64::INFINITY, 0.0) } else { (long_wave, long_wave) }
    } else {
        (omega / q, if omega > 0.0 { dw2 / (2.0 * omega) } else { 0.0 })
    };
    BranchPoint {
        wavenumber_rad_m: q,
        wavelength_per_module: 2.0 * PI / (q * material.lc_m()),
        omega_rad_s: omega,
        frequency_hz: omega / (2.0 * PI),
        phase_velocity_m_s: phase,
        group_velocity_m_s: group,
    }
}

/// One Bloch mode at a wave vector along a pure-mode direction, from the full 6×6 problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlochMode {
    /// Angular frequency `ω` (rad/s).
    pub omega_rad_s: f64,
    /// Share of `|Ũ|²` polarised along the wave direction (1 = longitudinal, 0 = transverse).
    pub longitudinal_fraction: f64,
    /// `Re(Ũ_Aᴴ·Ũ_B)/(|Ũ_A|·|Ũ_B|)` in the node-position phase: +1 when corner and centre move
    /// together (acoustic at small `q`), −1 in antiphase (optical); 0 if one node is still.
    pub sublattice_phase: f64,
    /// The eigenvector `Ũ` (mass-weighted, unit norm; rows as in [`dynamical_matrix`]).
    pub vector: Vector6<Complex<f64>>,
}

/// The six modes at `q` (rad/m, `0 ≤ q ≤` zone edge) along `direction`, ascending in `ω`, from
/// the eigen-decomposition of the full `D(k)`; their polarisation is measured, not assumed.
pub fn bloch_modes(
    material: &LatticeMaterial,
    direction: WaveDirection,
    wavenumber_rad_m: f64,
) -> Result<[BlochMode; 6], DispersionError> {
    branch_point(material, direction, Branch::P, wavenumber_rad_m)?;
    let n = direction.unit();
    let eig = SymmetricEigen::new(dynamical_matrix(material, n.map(|v| wavenumber_rad_m * v)));
    let mut modes: [BlochMode; 6] = std::array::from_fn(|c| {
        let v: Vector6<Complex<f64>> = eig.eigenvectors.column(c).into_owned();
        let along = |r: usize| (0..3).map(|a| v[3 * r + a] * n[a]).sum::<Complex<f64>>().norm_sqr();
        let norm = |r: usize| (0..3).map(|a| v[3 * r + a].norm_sqr()).sum::<f64>();
        let dot: Complex<f64> = (0..3).map(|a| v[a].conj() * v[3 + a]).sum();
        let scale = (norm(0) * norm(1)).sqrt();
        BlochMode {
            omega_rad_s: eig.eigenvalues[c].max(0.0).sqrt(),
            longitudinal_fraction: (along(0) + along(1)) / (norm(0) + norm(1)),
            sublattice_phase: if scale > 1e-300 { dot.re / scale } else { 0.0 },
            vector: v,
        }
    });
    modes.sort_by(|a, b| a.omega_rad_s.total_cmp(&b.omega_rad_s));
    Ok(modes)
}

/// Where an acoustic branch leaves the tolerance (or its zone edge, if it never does).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BranchLimit {
    /// Direction of propagation.
    pub direction: WaveDirection,
    /// The branch (P or S).
    pub branch: Branch,
    /// Its long-wave phase velocity `c₀` (m/s).
    pub long_wave_speed_m_s: f64,
    /// Whether `|c/c₀ − 1|` reaches the tolerance inside the Brillouin zone.
    pub reached: bool,
    /// The point where it does (or the zone edge, the branch's highest frequency, if not).
    pub point: BranchPoint,
}

impl BranchLimit {
    /// Signed departure `c/c₀ − 1` of the phase velocity at [`BranchLimit::point`].
    pub fn departure(&self) -> f64 {
        self.point.phase_velocity_m_s / self.long_wave_speed_m_s - 1.0
    }
}

/// The lowest optical frequency along the examined directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OpticalOnset {
    /// Direction along which it occurs.
    pub direction: WaveDirection,
    /// The optical branch.
    pub branch: Branch,
    /// The branch's lowest point (its minimum over `0 ≤ q ≤` zone edge).
    pub point: BranchPoint,
}

/// The frequency band the lattice resolves as a continuum, and where it ends.
#[derive(Clone, Debug, PartialEq)]
pub struct UsableBand {
    /// Phase-velocity departure `ε` that defines the band.
    pub tolerance: f64,
    /// `f_max` (Hz): the lowest frequency at which P or S departs by `ε` from its long-wave speed.
    pub f_max_hz: f64,
    /// The branch and direction that set `f_max`, and its wavelength, phase and group velocity.
    pub limiting: BranchLimit,
    /// Every examined acoustic branch (P and S along each direction).
    pub branches: Vec<BranchLimit>,
    /// Long-wave P speed along a cube axis `√(C11/ρ)` (m/s).
    pub cp_m_s: f64,
    /// Long-wave S speed along a cube axis `√(C44/ρ)` (m/s).
    pub cs_m_s: f64,
    /// The lowest optical frequency along the examined directions.
    pub optical: OpticalOnset,
    /// Each examined acoustic branch at the optical onset frequency (`None` if the branch's
    /// highest frequency lies below it).
    pub at_optical: Vec<(WaveDirection, Branch, Option<BranchPoint>)>,
}

impl UsableBand {
    /// `f_max·Lc/C_s`: the dimensionless coefficient of `f_max ∝ C_s/Lc`.
    pub fn f_max_per_cs_over_lc(&self, material: &LatticeMaterial) -> f64 {
        self.f_max_hz * material.lc_m() / self.cs_m_s
    }

    /// The band the lattice resolves (Hz): `f_max`, or the optical onset if it is lower (only for
    /// large tolerances).
    pub fn resolved_hz(&self) -> f64 {
        self.f_max_hz.min(self.optical.point.frequency_hz)
    }
}

fn check_tolerance(tolerance: f64) -> Result<f64, DispersionError> {
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(refuse("tolerance", tolerance, "0 < tolerance < 1 (a fraction: 0.05 = 5 %)"));
    }
    Ok(tolerance)
}

/// Bisects `[lo, hi]` (with `pred(lo)` false and `pred(hi)` true) to relative width 1e-15.
fn bisect(mut lo: f64, mut hi: f64, pred: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if pred(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
        if hi - lo <= 1e-15 * hi {
            break;
        }
    }
    hi
}

/// Where the phase velocity of the acoustic `branch` (P or S) along `direction` first departs by
/// `tolerance` from its long-wave value: a scan of the branch brackets the first crossing of
/// `|c(q)/c₀ − 1| = ε`, bisection finds it.
pub fn departure_limit(
    material: &LatticeMaterial,
    direction: WaveDirection,
    branch: Branch,
    tolerance: f64,
) -> Result<BranchLimit, DispersionError> {
    check_tolerance(tolerance)?;
    if branch.is_optical() {
        return Err(DispersionError::InvalidBranch {
            branch,
            allowed: "an acoustic branch (P or S): an optical branch has no long-wave speed",
        });
    }
    let c0 = long_wave_speed_m_s(material, direction, branch.polarisation());
    let edge = direction.zone_edge_rad_m(material.lc_m());
    let departs = |q: f64| {
        let p = point_unchecked(material, direction, branch, q);
        (p.phase_velocity_m_s / c0 - 1.0).abs() >= tolerance
    };
    let mut prev = 0.0;
    for i in 1..=SCAN_POINTS {
        let q = edge * i as f64 / SCAN_POINTS as f64;
        if departs(q) {
            let q = bisect(prev, q, departs);
            let point = point_unchecked(material, direction, branch, q);
            return Ok(BranchLimit { direction, branch, long_wave_speed_m_s: c0, reached: true, point });
        }
        prev = q;
    }
    let point = point_unchecked(material, direction, branch, edge);
    Ok(BranchLimit { direction, branch, long_wave_speed_m_s: c0, reached: false, point })
}

/// The lowest point of an optical branch along `direction` (grid scan, then golden section).
pub fn optical_minimum(
    material: &LatticeMaterial,
    direction: WaveDirection,
    branch: Branch,
) -> Result<BranchPoint, DispersionError> {
    if !branch.is_optical() {
        return Err(DispersionError::InvalidBranch { branch, allowed: "an optical branch (optical P or S)" });
    }
    let edge = direction.zone_edge_rad_m(material.lc_m());
    let w2 = |q: f64| branch_eigenvalue(material, direction, branch, q).0;
    let grid: Vec<f64> = (0..=SCAN_POINTS).map(|i| edge * i as f64 / SCAN_POINTS as f64).collect();
    let best = (0..grid.len()).min_by(|&a, &b| w2(grid[a]).total_cmp(&w2(grid[b]))).expect("non-empty grid");
    let (mut lo, mut hi) = (grid[best.saturating_sub(1)], grid[(best + 1).min(SCAN_POINTS)]);
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..100 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if w2(x1) <= w2(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    let q = [lo, hi, grid[best]].into_iter().min_by(|&a, &b| w2(a).total_cmp(&w2(b))).expect("three candidates");
    Ok(point_unchecked(material, direction, branch, q))
}

/// The point of the acoustic `branch` along `direction` at frequency `f` (Hz), or `None` if the
/// branch never reaches `f` inside the zone (the branch's frequency rises monotonically along the
/// pure-mode directions; the first crossing of a scan is bisected).
pub fn branch_point_at_frequency(
    material: &LatticeMaterial,
    direction: WaveDirection,
    branch: Branch,
    frequency_hz: f64,
) -> Result<Option<BranchPoint>, DispersionError> {
    if !(frequency_hz >= 0.0 && frequency_hz.is_finite()) {
        return Err(refuse("frequency_hz", frequency_hz, "a finite frequency ≥ 0 Hz"));
    }
    if branch.is_optical() {
        return Err(DispersionError::InvalidBranch { branch, allowed: "an acoustic branch (P or S)" });
    }
    let edge = direction.zone_edge_rad_m(material.lc_m());
    let above = |q: f64| point_unchecked(material, direction, branch, q).frequency_hz >= frequency_hz;
    let mut prev = 0.0;
    for i in 1..=SCAN_POINTS {
        let q = edge * i as f64 / SCAN_POINTS as f64;
        if above(q) {
            let q = bisect(prev, q, above);
            return Ok(Some(point_unchecked(material, direction, branch, q)));
        }
        prev = q;
    }
    Ok(None)
}

/// The usable band along `x` and `z` (the slip and height directions of the block).
pub fn usable_band(material: &LatticeMaterial, tolerance: f64) -> Result<UsableBand, DispersionError> {
    usable_band_along(material, tolerance, &[WaveDirection::X, WaveDirection::Z])
}

/// The usable band along the given directions: `f_max` over P and S of every direction, and the
/// lowest optical frequency over OP and OS of every direction.
pub fn usable_band_along(
    material: &LatticeMaterial,
    tolerance: f64,
    directions: &[WaveDirection],
) -> Result<UsableBand, DispersionError> {
    check_tolerance(tolerance)?;
    if directions.is_empty() {
        return Err(refuse("directions", 0.0, "at least one direction"));
    }
    let mut branches = Vec::new();
    let mut optical: Option<OpticalOnset> = None;
    for &direction in directions {
        for branch in [Branch::P, Branch::S] {
            branches.push(departure_limit(material, direction, branch, tolerance)?);
        }
        for branch in [Branch::OpticalP, Branch::OpticalS] {
            let point = optical_minimum(material, direction, branch)?;
            if optical.is_none_or(|o| point.omega_rad_s < o.point.omega_rad_s) {
                optical = Some(OpticalOnset { direction, branch, point });
            }
        }
    }
    let limiting = *branches
        .iter()
        .min_by(|a, b| a.point.omega_rad_s.total_cmp(&b.point.omega_rad_s))
        .expect("at least one direction");
    let optical = optical.expect("at least one direction");
    let at_optical = branches
        .iter()
        .map(|b| {
            let p = branch_point_at_frequency(material, b.direction, b.branch, optical.point.frequency_hz)?;
            Ok((b.direction, b.branch, p))
        })
        .collect::<Result<Vec<_>, DispersionError>>()?;
    let (cp_m_s, cs_m_s) = material.long_wave_speeds_m_s();
    Ok(UsableBand {
        tolerance,
        f_max_hz: limiting.point.frequency_hz,
        limiting,
        branches,
        cp_m_s,
        cs_m_s,
        optical,
        at_optical,
    })
}

/// The lowest frequency (Hz) of the fourth band (the lowest optical one in band order) over the
/// whole Brillouin zone, and the wave vector (rad/m) where it occurs: the frequency above which
/// some wave vector carries more than three modes. Sampled on `samples_per_axis` points per axis
/// of the irreducible wedge `0 ≤ k_z ≤ k_y ≤ k_x ≤ π/Lc` (which includes the points Γ, X, M, R).
pub fn lowest_optical_in_zone(
    material: &LatticeMaterial,
    samples_per_axis: usize,
) -> Result<(f64, [f64; 3]), DispersionError> {
    if samples_per_axis < 2 {
        return Err(refuse("samples_per_axis", samples_per_axis as f64, "at least 2"));
    }
    let step = PI / material.lc_m() / (samples_per_axis - 1) as f64;
    let mut best = (f64::INFINITY, [0.0; 3]);
    for i in 0..samples_per_axis {
        for j in 0..=i {
            for l in 0..=j {
                let k = [i as f64 * step, j as f64 * step, l as f64 * step];
                let w = bloch_spectrum(material, k)[3];
                if w < best.0 {
                    best = (w, k);
                }
            }
        }
    }
    Ok((best.0 / (2.0 * PI), best.1))
}

/// Prototype frequency (Hz) of a model frequency under length scale `λ_sim` at equal E and ρ:
/// wave speeds are kept, lengths and times scale by `λ_sim`, so frequencies divide by it.
pub fn prototype_frequency_hz(model_hz: f64, length_scale: f64) -> Result<f64, DispersionError> {
    positive("length_scale", length_scale, "(prototype length / model length)")?;
    if !(model_hz >= 0.0 && model_hz.is_finite()) {
        return Err(refuse("model_hz", model_hz, "a finite frequency ≥ 0 Hz"));
    }
    Ok(model_hz / length_scale)
}

#[cfg(test)]
mod tests {
    use super::*;

    const AXES: [WaveDirection; 3] = [WaveDirection::X, WaveDirection::Y, WaveDirection::Z];
    const ALL: [WaveDirection; 4] = [WaveDirection::X, WaveDirection::Y, WaveDirection::Z, WaveDirection::BodyDiagonal];

    fn paper() -> LatticeMaterial {
        LatticeMaterial::new(2e10, 0.2, 2400.0, 0.1).unwrap()
    }

    fn material(nu: f64) -> LatticeMaterial {
        LatticeMaterial::new(2e10, nu, 2400.0, 0.1).unwrap()
    }

    fn sinc(x: f64) -> f64 {
        if x == 0.0 { 1.0 } else { x.sin() / x }
    }

    #[test]
    fn cell_owns_fourteen_bars_of_the_right_lengths() {
        let m = paper();
        let bars = cell_bars(&m);
        assert_eq!(bars.len(), 14);
        for b in &bars {
            let len = b.offset_m.iter().map(|v| v * v).sum::<f64>().sqrt();
            let (want_len, want_k) = if b.family == BarFamily::Diagonal {
                (0.1 * 3f64.sqrt() / 2.0, m.diagonal_bar_stiffness_n_m())
            } else {
                (0.1, m.normal_bar_stiffness_n_m())
            };
            assert!((len - want_len).abs() < 1e-15);
            assert_eq!(b.stiffness_n_m, want_k);
        }
        assert_eq!(bars.iter().filter(|b| b.family == BarFamily::Diagonal).count(), 8);
        // EA_d/L_d with EA_d = (2δ/√3)·α·E·Lc², L_d = Lc·√3/2; at ν = 0.2 (δ = 3/4) k_d = k_n.
        assert!((m.diagonal_bar_stiffness_n_m() / m.normal_bar_stiffness_n_m() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn long_wave_speeds_of_the_paper_material() {
        let (cp, cs) = paper().long_wave_speeds_m_s();
        assert!((cp - 3042.90).abs() < 0.01, "{cp}");
        assert!((cs - 1521.45).abs() < 0.01, "{cs}");
    }

    /// The Bloch long-wave limit equals the continuum C11, C44 (axes) and the Christoffel speeds
    /// of the body diagonal: at `q = 1e-4·q_edge` dispersion is below 1e-8 and the cancellation
    /// in the 2×2 eigenvalue about 1e-8, so 1e-7 is tight.
    #[test]
    fn long_wave_limit_equals_the_continuum() {
        for nu in [0.05, 0.2, 0.25, 0.4, 0.49] {
            let m = material(nu);
            let (c11, _, c44) = m.elastic_constants_pa();
            for d in ALL {
                let q = 1e-4 * d.zone_edge_rad_m(m.lc_m());
                for b in [Branch::P, Branch::S] {
                    let c0 = long_wave_speed_m_s(&m, d, b.polarisation());
                    let p = branch_point(&m, d, b, q).unwrap();
                    assert!((p.phase_velocity_m_s / c0 - 1.0).abs() < 1e-7, "ν {nu} {d} {b}: {p:?} vs {c0}");
                    assert!((p.group_velocity_m_s / c0 - 1.0).abs() < 1e-7, "ν {nu} {d} {b}: {p:?}");
                }
            }
            let (cp, cs) = m.long_wave_speeds_m_s();
            assert!((cp - (c11 / 2400.0).sqrt()).abs() < 1e-9 * cp);
            assert!((cs - (c44 / 2400.0).sqrt()).abs() < 1e-9 * cs);
            assert_eq!(long_wave_speed_m_s(&m, WaveDirection::X, Polarisation::Longitudinal), cp);
            assert_eq!(long_wave_speed_m_s(&m, WaveDirection::Z, Polarisation::Transverse), cs);
        }
    }

    #[test]
    fn axis_branches_match_the_closed_forms() {
        for nu in [0.1, 0.2, 0.25, 0.45] {
            let m = material(nu);
            let (kn, kd, mass, lc) =
                (m.normal_bar_stiffness_n_m(), m.diagonal_bar_stiffness_n_m(), m.node_mass_kg(), m.lc_m());
            let scale = (4.0 * kn + 16.0 / 3.0 * kd) / mass;
            for i in 0..=16 {
                let q = PI / lc * i as f64 / 16.0;
                let s2 = |x: f64| x.sin().powi(2);
                let want = [
                    (Branch::S, 16.0 / 3.0 * kd * s2(q * lc / 4.0)),
                    (Branch::OpticalS, 16.0 / 3.0 * kd * (q * lc / 4.0).cos().powi(2)),
                    (Branch::P, 4.0 * kn * s2(q * lc / 2.0) + 8.0 / 3.0 * kd * (1.0 - (q * lc / 2.0).cos())),
                    (Branch::OpticalP, 4.0 * kn * s2(q * lc / 2.0) + 8.0 / 3.0 * kd * (1.0 + (q * lc / 2.0).cos())),
                ];
                for d in AXES {
                    for (b, w) in want {
                        let p = branch_point(&m, d, b, q).unwrap();
                        assert!((p.omega_rad_s.powi(2) - w / mass).abs() < 1e-12 * scale, "ν {nu} {d} {b} q {q}");
                    }
                }
                if i > 0 {
                    let (delta, _) = m.truss_constants();
                    let r = 4.0 * delta / 9.0;
                    let (cp, cs) = m.long_wave_speeds_m_s();
                    let p = branch_point(&m, WaveDirection::X, Branch::P, q).unwrap().phase_velocity_m_s;
                    let s = branch_point(&m, WaveDirection::X, Branch::S, q).unwrap().phase_velocity_m_s;
                    let want_p =
                        cp * ((sinc(q * lc / 2.0).powi(2) + r * sinc(q * lc / 4.0).powi(2)) / (1.0 + r)).sqrt();
                    assert!((p / want_p - 1.0).abs() < 1e-10, "ν {nu} q {q}: {p} vs {want_p}");
                    assert!((s / (cs * sinc(q * lc / 4.0)) - 1.0).abs() < 1e-10, "ν {nu} q {q}");
                }
            }
        }
    }

    /// The full 6×6 spectrum is exactly the union of the polarisation blocks, and the measured
    /// polarisation of each full eigenvector says which block it belongs to.
    #[test]
    fn full_spectrum_is_the_union_of_the_polarisation_blocks() {
        for nu in [0.2, 0.25, 0.4] {
            let m = material(nu);
            for d in ALL {
                let edge = d.zone_edge_rad_m(m.lc_m());
                // Away from the zone edge, where the branches of one block touch.
                for f in [0.013, 0.1, 0.37, 0.61, 0.83] {
                    let q = f * edge;
                    let w = |b| branch_point(&m, d, b, q).unwrap().omega_rad_s;
                    let (p, s, op, os) = (w(Branch::P), w(Branch::S), w(Branch::OpticalP), w(Branch::OpticalS));
                    let mut want = [p, s, s, op, os, os];
                    want.sort_by(f64::total_cmp);
                    let modes = bloch_modes(&m, d, q).unwrap();
                    let top = want[5];
                    for (mode, w) in modes.iter().zip(want) {
                        assert!((mode.omega_rad_s - w).abs() < 1e-10 * top, "ν {nu} {d} q {f}: {modes:?}");
                    }
                    for mode in &modes {
                        let near = |x: f64| (mode.omega_rad_s - x).abs() < 1e-9 * top;
                        // A longitudinal eigenvalue that happens to equal a transverse one may mix.
                        if (near(p) || near(op)) && !(near(s) || near(os)) {
                            assert!((mode.longitudinal_fraction - 1.0).abs() < 1e-9, "{d} {f}: {mode:?}");
                        } else if !(near(p) || near(op)) {
                            assert!(mode.longitudinal_fraction.abs() < 1e-9, "{d} {f}: {mode:?}");
                        }
                    }
                    if f < 0.02 {
                        for mode in &modes {
                            let acoustic = near_any(mode.omega_rad_s, &[p, s], top);
                            let want_phase = if acoustic { 1.0 } else { -1.0 };
                            assert!((mode.sublattice_phase - want_phase).abs() < 1e-3, "{d}: {mode:?}");
                        }
                    }
                }
            }
        }
    }

    fn near_any(x: f64, set: &[f64], scale: f64) -> bool {
        set.iter().any(|&y| (x - y).abs() < 1e-9 * scale)
    }

    #[test]
    fn group_velocity_is_the_slope_of_the_branch() {
        let m = material(0.3);
        for d in ALL {
            let edge = d.zone_edge_rad_m(m.lc_m());
            for b in [Branch::P, Branch::S, Branch::OpticalP, Branch::OpticalS] {
                for f in [0.05, 0.3, 0.55, 0.9] {
                    let q = f * edge;
                    let h = 1e-5 * edge;
                    let w = |q| branch_point(&m, d, b, q).unwrap().omega_rad_s;
                    let fd = (w(q + h) - w(q - h)) / (2.0 * h);
                    let p = branch_point(&m, d, b, q).unwrap();
                    let scale = long_wave_speed_m_s(&m, d, Polarisation::Longitudinal);
                    assert!(
                        (p.group_velocity_m_s - fd).abs() < 1e-6 * scale,
                        "{d} {b} {f}: {} vs {fd}",
                        p.group_velocity_m_s
                    );
                }
            }
        }
    }

    /// At the axis zone edge S touches OS: the group velocity there is the limit from inside the
    /// zone, `dω/dq = ω₀·(Lc/4)·cos(π/4)` with `ω₀² = (16/3)·k_d/m`, not the zero of a symmetric
    /// average.
    #[test]
    fn group_velocity_at_the_degenerate_zone_edge_is_the_inner_limit() {
        let m = material(0.2);
        let edge = PI / m.lc_m();
        let w0 = (16.0 / 3.0 * m.diagonal_bar_stiffness_n_m() / m.node_mass_kg()).sqrt();
        let want = w0 * m.lc_m() / 4.0 * (PI / 4.0).cos();
        let s = branch_point(&m, WaveDirection::X, Branch::S, edge).unwrap();
        assert!((s.group_velocity_m_s / want - 1.0).abs() < 1e-9, "{s:?} vs {want}");
        let os = branch_point(&m, WaveDirection::X, Branch::OpticalS, edge).unwrap();
        assert!((os.group_velocity_m_s / -want - 1.0).abs() < 1e-9, "{os:?}");
        let h = 1e-6 * edge;
        let w = |q| branch_point(&m, WaveDirection::X, Branch::S, q).unwrap().omega_rad_s;
        assert!(((w(edge) - w(edge - h)) / h / want - 1.0).abs() < 1e-5);
    }

    #[test]
    fn f_max_is_where_the_phase_velocity_departs_by_the_tolerance() {
        for nu in [0.1, 0.2, 0.25, 0.3, 0.45] {
            let m = material(nu);
            for tol in [0.01, DEFAULT_TOLERANCE, 0.08] {
                let band = usable_band(&m, tol).unwrap();
                assert_eq!(band.branches.len(), 4);
                for b in &band.branches {
                    assert!(b.reached);
                    assert!((b.departure().abs() - tol).abs() < 1e-9, "ν {nu} ε {tol}: {b:?}");
                    // Below it the branch stays inside the tolerance (dispersion is monotone).
                    for i in 1..50 {
                        let q = b.point.wavenumber_rad_m * i as f64 / 50.0;
                        let p = branch_point(&m, b.direction, b.branch, q).unwrap();
                        assert!((p.phase_velocity_m_s / b.long_wave_speed_m_s - 1.0).abs() < tol);
                    }
                    assert!(b.point.frequency_hz >= band.f_max_hz);
                }
                // The S limit along an axis: sinc(x*) = 1 − ε, f = 2(1−ε)x*/π · Cs/Lc for any ν.
                let mut lo_hi = (0.0, PI / 2.0);
                for _ in 0..100 {
                    let mid = 0.5 * (lo_hi.0 + lo_hi.1);
                    if sinc(mid) > 1.0 - tol { lo_hi.0 = mid } else { lo_hi.1 = mid }
                }
                let x = lo_hi.0;
                let s = band.branches.iter().find(|b| b.branch == Branch::S).unwrap();
                let want = 2.0 * (1.0 - tol) * x / PI * band.cs_m_s / m.lc_m();
                assert!((s.point.frequency_hz / want - 1.0).abs() < 1e-9, "ν {nu} ε {tol}");
                assert!((s.point.wavelength_per_module - PI / (2.0 * x)).abs() < 1e-8);
            }
        }
        // The paper lattice at 5 %: S along x at 0.3338·Cs/Lc, and P above ν ≈ 0.2527.
        let band = usable_band(&paper(), DEFAULT_TOLERANCE).unwrap();
        assert_eq!((band.limiting.branch, band.limiting.direction), (Branch::S, WaveDirection::X));
        assert!((band.f_max_per_cs_over_lc(&paper()) - 0.3338).abs() < 5e-5);
        assert!((band.f_max_hz - 5078.4).abs() < 0.1, "{}", band.f_max_hz);
        assert_eq!(usable_band(&material(0.25), 0.05).unwrap().limiting.branch, Branch::S);
        assert_eq!(usable_band(&material(0.26), 0.05).unwrap().limiting.branch, Branch::P);
    }

    /// `f_max ∝ C_s/Lc`: E ×4 doubles the speeds, Lc ÷2 doubles the frequency again.
    #[test]
    fn f_max_scales_with_cs_over_lc() {
        let a = usable_band(&paper(), 0.05).unwrap();
        let b = usable_band(&LatticeMaterial::new(8e10, 0.2, 2400.0, 0.05).unwrap(), 0.05).unwrap();
        assert!((b.f_max_hz / a.f_max_hz - 4.0).abs() < 1e-9);
        assert!((b.optical.point.frequency_hz / a.optical.point.frequency_hz - 4.0).abs() < 1e-9);
        assert!((b.limiting.point.wavelength_per_module - a.limiting.point.wavelength_per_module).abs() < 1e-9);
    }

    #[test]
    fn optical_branches_start_at_the_axis_zone_edge() {
        for nu in [0.1, 0.2, 0.25, 0.4] {
            let m = material(nu);
            let band = usable_band(&m, DEFAULT_TOLERANCE).unwrap();
            let want = 2f64.sqrt() * band.cs_m_s / (PI * m.lc_m());
            let o = band.optical;
            assert_eq!(o.branch, Branch::OpticalS);
            assert!((o.point.frequency_hz / want - 1.0).abs() < 1e-9, "ν {nu}: {o:?}");
            assert!((o.point.wavenumber_rad_m * m.lc_m() / PI - 1.0).abs() < 1e-9);
            // The optical branches exist: non-zero at k = 0.
            let gamma = bloch_spectrum(&m, [0.0; 3]);
            assert!(gamma[..3].iter().all(|w| w.abs() < 1e-6 * gamma[5]));
            assert!(gamma[3..].iter().all(|w| *w > 0.1 * gamma[5]));
            // Sampled over the whole zone the fourth band goes no lower.
            let (f4, _) = lowest_optical_in_zone(&m, 9).unwrap();
            assert!((f4 / o.point.frequency_hz - 1.0).abs() < 1e-9, "ν {nu}: {f4}");
            assert!(band.resolved_hz() == band.f_max_hz);
        }
    }

    #[test]
    fn prototype_scale_divides_frequencies() {
        assert!((prototype_frequency_hz(5078.4, 1e4).unwrap() - 0.50784).abs() < 1e-12);
        assert!(prototype_frequency_hz(1.0, 0.0).is_err());
    }

    fn refused_param(e: DispersionError) -> &'static str {
        match e {
            DispersionError::InvalidParameter { parameter, .. } => parameter,
            DispersionError::InvalidBranch { .. } => "branch",
        }
    }

    #[test]
    fn out_of_range_inputs_are_refused_by_name() {
        let new = LatticeMaterial::new;
        for nu in [0.0, 0.5, -0.1, 0.7, f64::NAN] {
            let e = new(2e10, nu, 2400.0, 0.1).unwrap_err();
            assert_eq!(refused_param(e.clone()), "poisson");
            assert!(e.to_string().contains("0 < poisson < 0.5"), "{e}");
        }
        for v in [0.0, -1.0, f64::INFINITY, f64::NAN] {
            assert_eq!(refused_param(new(v, 0.2, 2400.0, 0.1).unwrap_err()), "young_pa");
            assert_eq!(refused_param(new(2e10, 0.2, v, 0.1).unwrap_err()), "density_kg_m3");
            assert_eq!(refused_param(new(2e10, 0.2, 2400.0, v).unwrap_err()), "lc_m");
        }
        let e = new(2e10, 0.2, 2400.0, -0.1).unwrap_err();
        assert_eq!(e.to_string(), "lc_m = -0.1 is not allowed: a finite lc_m > 0 m");
        let m = paper();
        for t in [0.0, 1.0, -0.05, f64::NAN] {
            assert_eq!(refused_param(usable_band(&m, t).unwrap_err()), "tolerance");
        }
        let edge = WaveDirection::X.zone_edge_rad_m(0.1);
        for q in [-1.0, edge * 1.0001, f64::NAN] {
            assert_eq!(
                refused_param(branch_point(&m, WaveDirection::X, Branch::S, q).unwrap_err()),
                "wavenumber_rad_m"
            );
            assert!(bloch_modes(&m, WaveDirection::X, q).is_err());
        }
        assert!(branch_point(&m, WaveDirection::BodyDiagonal, Branch::S, edge * 1.7).is_ok());
        assert_eq!(refused_param(departure_limit(&m, WaveDirection::X, Branch::OpticalS, 0.05).unwrap_err()), "branch");
        assert_eq!(refused_param(optical_minimum(&m, WaveDirection::X, Branch::P).unwrap_err()), "branch");
        assert_eq!(refused_param(usable_band_along(&m, 0.05, &[]).unwrap_err()), "directions");
        assert_eq!(refused_param(lowest_optical_in_zone(&m, 1).unwrap_err()), "samples_per_axis");
        assert_eq!(refused_param(prototype_frequency_hz(-1.0, 1e4).unwrap_err()), "model_hz");
        assert_eq!(refused_param(prototype_frequency_hz(1.0, f64::NAN).unwrap_err()), "length_scale");
    }
}
