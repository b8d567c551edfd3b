//! The branches along a pure-mode direction: long-wave speeds, a point of a branch (frequency,
//! phase and group velocity) from its polarisation block, and the full six Bloch modes.

use std::f64::consts::PI;

use nalgebra::{Complex, Matrix6, SymmetricEigen, Vector6};

use crate::dispersion::cell::{assemble, dynamical_matrix};
use crate::dispersion::direction::{Branch, Polarisation, WaveDirection};
use crate::dispersion::error::{DispersionError, refuse};
use crate::dispersion::lattice::LatticeMaterial;

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
pub(super) fn branch_eigenvalue(
    material: &LatticeMaterial,
    direction: WaveDirection,
    branch: Branch,
    q: f64,
) -> (f64, f64) {
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

pub(super) fn point_unchecked(
    material: &LatticeMaterial,
    direction: WaveDirection,
    branch: Branch,
    q: f64,
) -> BranchPoint {
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
