//! The usable band: where the acoustic branches depart from their long-wave speed by the
//! tolerance, where the optical branches start, and the prototype scaling of a frequency.

use std::f64::consts::PI;

use crate::dispersion::branch::{BranchPoint, branch_eigenvalue, long_wave_speed_m_s, point_unchecked};
use crate::dispersion::cell::bloch_spectrum;
use crate::dispersion::direction::{Branch, WaveDirection};
use crate::dispersion::error::{DispersionError, positive, refuse};
use crate::dispersion::lattice::LatticeMaterial;

/// Default phase-velocity departure that bounds the usable band (5 %).
pub const DEFAULT_TOLERANCE: f64 = 0.05;

/// Grid points along a branch scanned before bisecting (the departure is smooth and monotone on
/// the acoustic branches; the scan only brackets the first crossing).
const SCAN_POINTS: usize = 512;

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

pub(super) fn check_tolerance(tolerance: f64) -> Result<f64, DispersionError> {
    if !(tolerance > 0.0 && tolerance < 1.0) {
        return Err(refuse("tolerance", tolerance, "0 < tolerance < 1 (a fraction: 0.05 = 5 %)"));
    }
    Ok(tolerance)
}

/// Bisects `[lo, hi]` (with `pred(lo)` false and `pred(hi)` true) to relative width 1e-15.
pub(super) fn bisect(mut lo: f64, mut hi: f64, pred: impl Fn(f64) -> bool) -> f64 {
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
