//! The medium the waves cross (docs/model.md §18): a layered crust mapped onto the lattice by
//! depth, a frequency-independent Q by memory variables ([`relaxation`]) and stiffness-
//! proportional (Kelvin–Voigt) damping. Without any of them the medium is the scene's homogeneous
//! elastic one and nothing here runs.
//!
//! **One Q for P and S.** A central-force lattice's complex moduli follow its real ones: the
//! imaginary part of the modulus tensor is a sum over bar classes, the edge bars adding only to
//! `C₁₁` and the diagonals equally to `C₁₁`, `C₁₂` and `C₄₄`, so it is isotropic only when every
//! bar carries the same Q, and then `Qp = Qs`. Splitting Q between edge bars and diagonals gives
//! `Qp ≠ Qs` along the cube axes but makes the attenuation depend on direction by up to a factor 2
//! (a shear wave along a body diagonal), so each bar carries the layer's `Qs` and P waves
//! attenuate as S waves do (twice as fast as the common `Qp = 2·Qs`), just as the lattice's Poisson
//! ratio is one value.
//!
//! **Layers.** Each layer gives thickness, Vp, Vs, ρ, Qp, Qs (the SCEC Broadband Platform's
//! velocity-file columns). The lattice matches each layer's Vs and ρ (E from Vs at the scene's
//! Poisson ratio); its Vp is then `√3·Vs` at ν = 0.25, printed beside the profile's.
//! A node's mass takes the mean density over its half-module above and below; a bar's stiffness
//! the mean E over its depth extent (a horizontal bar over the half-module above and below it), so
//! an interface on a module plane is sharp.

pub mod relaxation;

pub use relaxation::{MECHANISMS, Relaxation};

use crate::geometry::Face;
use crate::material::lattice_elastic_constants;

/// One layer of a 1D velocity model.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// Thickness (m); `f64::INFINITY` for the half-space, the last layer.
    pub thickness_m: f64,
    /// P-wave speed (m/s) of the profile (the lattice's follows from Vs).
    pub vp_m_s: f64,
    /// S-wave speed (m/s).
    pub vs_m_s: f64,
    /// Density (kg/m³).
    pub density_kg_m3: f64,
    /// P-wave quality factor of the profile (printed; the lattice carries [`Layer::qs`]).
    pub qp: f64,
    /// S-wave quality factor.
    pub qs: f64,
}

/// A 1D velocity model below one face of the block, the Earth's surface.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// Layers from the surface down; the last is the half-space.
    pub layers: Vec<Layer>,
    /// The face that is the Earth's surface (`y_min`, `y_max`, `z_min` or `z_max`).
    pub surface: Face,
}

impl Profile {
    /// Depth below the surface of a point of a block of `extent` (m).
    pub fn depth(&self, p: [f64; 3], extent: [f64; 3]) -> f64 {
        match self.surface {
            Face::YMin => p[1],
            Face::YMax => extent[1] - p[1],
            Face::ZMin => p[2],
            Face::ZMax => extent[2] - p[2],
            Face::XMin | Face::XMax => panic!("the surface of a profile is a y or z face"),
        }
    }

    /// The axis along which depth runs.
    pub fn depth_axis(&self) -> usize {
        self.surface.axis().0
    }

    /// Index of the layer at `depth` (an interface belongs to the layer below it).
    pub fn layer_at(&self, depth: f64) -> usize {
        let mut bottom = 0.0;
        for (i, l) in self.layers.iter().enumerate() {
            bottom += l.thickness_m;
            if depth < bottom {
                return i;
            }
        }
        self.layers.len() - 1
    }

    /// Depth of the top of each layer (m).
    pub fn tops(&self) -> Vec<f64> {
        let mut top = 0.0;
        self.layers
            .iter()
            .map(|l| {
                let t = top;
                top += l.thickness_m;
                t
            })
            .collect()
    }

    /// The mean of `value(layer index)` over depths `[a, b]` (clipped at the surface), weighted by
    /// thickness.
    pub fn mean_over(&self, a: f64, b: f64, value: impl Fn(usize) -> f64) -> f64 {
        let (a, b) = (a.max(0.0), b.max(0.0));
        if b <= a {
            return value(self.layer_at(a));
        }
        let (mut sum, mut top): (f64, f64) = (0.0, 0.0);
        for (i, l) in self.layers.iter().enumerate() {
            let (lo, hi) = (top.max(a), (top + l.thickness_m).min(b));
            if hi > lo {
                sum += (hi - lo) * value(i);
            }
            top += l.thickness_m;
        }
        sum / (b - a)
    }

    /// The time-averaged S-wave speed of the top 30 m, `30 / Σ hᵢ/Vsᵢ` (m/s): V_S30.
    pub fn vs30(&self) -> f64 {
        1.0 / self.mean_over(0.0, 30.0, |i| 1.0 / self.layers[i].vs_m_s)
    }
}

/// How each layer's Q is given.
#[derive(Clone, Debug, PartialEq)]
pub enum QRule {
    /// One Q everywhere.
    Constant(f64),
    /// `Qs = k·Vs` with Vs in km/s (the common rule is k = 50).
    PerVs {
        /// Q per km/s of Vs.
        per_km_s: f64,
    },
    /// The profile's Qs column.
    Profile,
}

/// A constant Q over a band.
#[derive(Clone, Debug, PartialEq)]
pub struct Attenuation {
    /// The band over which Q is constant (Hz).
    pub band_hz: [f64; 2],
    /// Where the phase speeds are the elastic ones the medium gives (Hz).
    pub reference_hz: f64,
    /// Each layer's Q.
    pub q: QRule,
}

/// The medium of a scene: homogeneous and elastic by default.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Medium {
    /// A layered crust; `None`: the scene's homogeneous material.
    pub profile: Option<Profile>,
    /// Anelastic attenuation; `None`: Q = ∞.
    pub attenuation: Option<Attenuation>,
    /// Stiffness-proportional damping `β` (s): each bar carries a dashpot `β·k`. 0: none.
    pub kelvin_voigt_s: f64,
}

/// What one zone of the medium (a layer, or the homogeneous block) puts on the lattice.
#[derive(Clone, Debug, PartialEq)]
pub struct Zone {
    /// Young's modulus over the scene's.
    pub young: f64,
    /// Density over the scene's.
    pub density: f64,
    /// S-wave speed (m/s).
    pub vs_m_s: f64,
    /// The lattice's P-wave speed (m/s).
    pub vp_m_s: f64,
    /// Its relaxation mechanisms (`None`: Q = ∞).
    pub relaxation: Option<Relaxation>,
}

impl Zone {
    /// The stiffness factor of a bar of this zone's Q: the unrelaxed modulus over the elastic one.
    pub fn unrelaxed(&self) -> f64 {
        self.relaxation.as_ref().map_or(1.0, |r| r.unrelaxed)
    }

    /// Its Q (∞ without attenuation).
    pub fn q(&self) -> f64 {
        self.relaxation.as_ref().map_or(f64::INFINITY, |r| r.q)
    }
}

impl Medium {
    /// Whether the step has work to do beyond the elastic bars: memory variables or dashpots.
    pub fn is_dissipative(&self) -> bool {
        self.attenuation.is_some() || self.kelvin_voigt_s > 0.0
    }

    /// Whether the medium is the scene's homogeneous elastic material.
    pub fn is_default(&self) -> bool {
        self.profile.is_none() && !self.is_dissipative()
    }

    /// The zones of the medium: one per layer of the profile, or one for the homogeneous block of
    /// modulus `young_pa`, density `density` and Poisson ratio `poisson`.
    pub fn zones(&self, young_pa: f64, density: f64, poisson: f64) -> Vec<Zone> {
        let (c11, _, c44) = lattice_elastic_constants(young_pa, poisson);
        let (vs0, vp0) = ((c44 / density).sqrt(), (c11 / density).sqrt());
        let q_of = |vs: f64, layer: Option<&Layer>| {
            self.attenuation.as_ref().map(|a| {
                let q = match (&a.q, layer) {
                    (QRule::Constant(q), _) => *q,
                    (QRule::PerVs { per_km_s }, _) => per_km_s * vs / 1000.0,
                    (QRule::Profile, Some(l)) => l.qs,
                    (QRule::Profile, None) => panic!("Q from a profile needs a profile"),
                };
                Relaxation::fit(q, a.band_hz, a.reference_hz)
            })
        };
        match &self.profile {
            None => vec![Zone { young: 1.0, density: 1.0, vs_m_s: vs0, vp_m_s: vp0, relaxation: q_of(vs0, None) }],
            Some(p) => p
                .layers
                .iter()
                .map(|l| {
                    let young = (l.density_kg_m3 * l.vs_m_s * l.vs_m_s) / c44;
                    Zone {
                        young,
                        density: l.density_kg_m3 / density,
                        vs_m_s: l.vs_m_s,
                        vp_m_s: l.vs_m_s * vp0 / vs0,
                        relaxation: q_of(l.vs_m_s, Some(l)),
                    }
                })
                .collect(),
        }
    }

    /// The factor of E at depth window `[a, b]` (mean over it; one point when `a == b`) and the
    /// zone at `mid` (its Q), for a lattice of `zones` built by [`Medium::zones`].
    pub fn young_over(&self, zones: &[Zone], a: f64, b: f64) -> f64 {
        match &self.profile {
            None => zones[0].young,
            Some(p) => p.mean_over(a, b, |i| zones[i].young),
        }
    }

    /// The factor of density over depths `[a, b]`.
    pub fn density_over(&self, zones: &[Zone], a: f64, b: f64) -> f64 {
        match &self.profile {
            None => zones[0].density,
            Some(p) => p.mean_over(a, b, |i| zones[i].density),
        }
    }

    /// The zone at depth `d`.
    pub fn zone_at(&self, d: f64) -> usize {
        self.profile.as_ref().map_or(0, |p| p.layer_at(d))
    }

    /// Depth of a point of a block of `extent` (0 without a profile).
    pub fn depth(&self, p: [f64; 3], extent: [f64; 3]) -> f64 {
        self.profile.as_ref().map_or(0.0, |pr| pr.depth(p, extent))
    }

    /// The axis depth runs along (z without a profile).
    pub fn depth_axis(&self) -> usize {
        self.profile.as_ref().map_or(2, Profile::depth_axis)
    }
}

/// The stable step with Kelvin–Voigt damping `β` over the undamped one `Δt_c = 2/ω_max`:
/// `√(1 + ξ²) − ξ` with `ξ = β·ω_max/2 = β/Δt_c`. Central differences with the dashpot's
/// velocity taken backward, `(eₙ − eₙ₋₁)/Δt`, have the characteristic polynomial
/// `z² − (2 − ω²Δt² − βω²Δt)z + (1 − βω²Δt)`, whose roots stay in the unit disc exactly when
/// `ω²Δt(Δt + 2β) ≤ 4`, i.e. `Δt ≤ (2/ω)(√(1 + ξ²) − ξ)`.
pub fn kelvin_voigt_step_factor(beta_s: f64, dt_critical_s: f64) -> f64 {
    let xi = beta_s / dt_critical_s;
    (1.0 + xi * xi).sqrt() - xi
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_layers() -> Profile {
        let l = |h: f64, vs: f64, rho: f64| Layer {
            thickness_m: h,
            vp_m_s: vs * 1.8,
            vs_m_s: vs,
            density_kg_m3: rho,
            qp: 100.0,
            qs: 50.0,
        };
        Profile { layers: vec![l(10.0, 300.0, 2000.0), l(f64::INFINITY, 1200.0, 2400.0)], surface: Face::ZMax }
    }

    #[test]
    fn vs30_is_the_travel_time_average() {
        // 10 m at 300 m/s and 20 m at 1200 m/s: 30/(10/300 + 20/1200) = 600 m/s.
        assert!((two_layers().vs30() - 600.0).abs() < 1e-9);
    }

    #[test]
    fn depth_windows_average_the_layers() {
        let p = two_layers();
        assert_eq!(p.layer_at(9.99), 0);
        assert_eq!(p.layer_at(10.0), 1);
        let rho = p.mean_over(5.0, 15.0, |i| p.layers[i].density_kg_m3);
        assert!((rho - 2200.0).abs() < 1e-9);
        assert_eq!(p.depth([0.0, 0.0, 80.0], [100.0, 100.0, 100.0]), 20.0);
    }

    #[test]
    fn kelvin_voigt_lowers_the_step_as_the_closed_form_says() {
        assert_eq!(kelvin_voigt_step_factor(0.0, 1e-3), 1.0);
        let f = kelvin_voigt_step_factor(1e-3, 1e-3);
        assert!((f - (2f64.sqrt() - 1.0)).abs() < 1e-15);
    }
}
