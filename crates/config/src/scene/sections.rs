//! The sections of the body and its time step: block, material, friction, time, rupture.
//!
//! Each field's default is the paper scene's.

use serde::{Deserialize, Serialize};

use crate::friction_map::{GridSection, PatchSection};

/// `[block]`: the lattice.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct BlockSection {
    /// Modules along x (slip direction). Default 10.
    pub nx: i64,
    /// Modules along y (width). Default 1.
    pub ny: i64,
    /// Modules along z (height). Default 5.
    pub nz: i64,
    /// Module side Lc in metres. Default 0.1.
    pub lc_m: f64,
}

impl Default for BlockSection {
    fn default() -> Self {
        BlockSection { nx: 10, ny: 1, nz: 5, lc_m: 0.1 }
    }
}

/// `[material]`: elastic properties and the Weibull field on E.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct MaterialSection {
    /// Mean Young's modulus in Pa. Default 2.0e10.
    pub young_pa: f64,
    /// Density in kg/m³. Default 2400.
    pub density_kg_m3: f64,
    /// Poisson's ratio, 0 < ν < 0.5. Default 0.2.
    pub poisson: f64,
    /// Coefficient of variation of E (Weibull, per bar); 0 = homogeneous. Default 0.05.
    pub young_cv: f64,
}

impl Default for MaterialSection {
    fn default() -> Self {
        MaterialSection { young_pa: 2.0e10, density_kg_m3: 2400.0, poisson: 0.2, young_cv: 0.05 }
    }
}

/// `[friction]`: friction with the rigid base.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct FrictionSection {
    /// The law: `"slip_weakening"` (the default: Coulomb, static/dynamic or linear slip
    /// weakening by the keys given), `"exponential_weakening"`, or `"rate_state_aging"` /
    /// `"rate_state_slip"` (coefficients in `[friction.rate_state]`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub law: Option<String>,
    /// Static coefficient μs. Default 5.0.
    pub mu_static: f64,
    /// Dynamic coefficient μd ≤ μs; omitted = μs (the plain Coulomb law).
    pub mu_dynamic: Option<f64>,
    /// Slip-weakening distance Dc in metres (μ falls linearly from μs to μd over Dc of slip);
    /// 0 = drops at once. Default 0.
    pub slip_weakening_m: f64,
    /// Coefficient of variation of μ (Weibull, per contact node, its own random stream);
    /// 0 = uniform. Default 0.
    pub mu_cv: f64,
    /// Regions of the base with their own coefficients (asperities, barriers).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub patches: Vec<PatchSection>,
    /// Coefficients per base node from a CSV file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<GridSection>,
    /// Whether a node that sticks again heals to μs (the paper's stick-slip cycles) or keeps the
    /// slip it has (slip weakening over the whole run, the SCEC benchmarks' law). Default true.
    #[serde(skip_serializing_if = "is_true")]
    pub heals: bool,
    /// `[friction.rate_state]`: the coefficients of a rate-and-state law.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rate_state: Option<crate::laws::RateStateSection>,
    /// `[friction.rate_state_grid]`: rate-and-state coefficients per base node from a CSV file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rate_state_grid: Option<crate::friction_map::RateStateGridSection>,
}

fn is_true(v: &bool) -> bool {
    *v
}

impl Default for FrictionSection {
    fn default() -> Self {
        FrictionSection {
            law: None,
            mu_static: 5.0,
            mu_dynamic: None,
            slip_weakening_m: 0.0,
            mu_cv: 0.0,
            patches: Vec::new(),
            grid: None,
            heals: true,
            rate_state: None,
            rate_state_grid: None,
        }
    }
}

/// The largest `time.dt_fraction` accepted without `time.force`: the critical step is computed
/// for the lattice actually built, but a step at the limit has no margin for round-off.
pub const SAFE_DT_FRACTION: f64 = 0.95;

/// `[time]`: the time step, as a fraction of the critical step or in seconds.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields, default)]
pub struct TimeSection {
    /// Δt as a fraction of the critical step `2/ω_max` of the lattice actually built (random
    /// field included), in (0, 0.95] (up to 1 with `force`). Default 0.5 when `dt_s` is not given.
    pub dt_fraction: Option<f64>,
    /// Δt in seconds; refused if above the critical step. Exclusive with `dt_fraction`.
    pub dt_s: Option<f64>,
    /// Accept a `dt_fraction` above 0.95, up to the stability limit 1. Default false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub force: bool,
}

/// `[rupture]`: bars that crack, by the bilinear softening law of the LDEM (docs/model.md §11);
/// absent = every bar linear elastic.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct RuptureSection {
    /// Mean fracture energy Gf in J/m² (the energy a crack dissipates per unit area). Default 100
    /// (rock-like).
    pub fracture_energy_j_m2: f64,
    /// `Kr = εr/εp` > 1, where the softening branch reaches zero force. Default 3 when
    /// `failure_factor_per_sqrt_m` is not given; exclusive with it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kr: Option<f64>,
    /// Failure factor Rf in 1/√m: `εp = Rf·√(Gf/((1 − ν²)E))` (Kosteski et al.), `Kr` then follows
    /// from the energy and must exceed 1. Exclusive with `kr`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure_factor_per_sqrt_m: Option<f64>,
    /// Coefficient of variation of the Weibull field on Gf (per bar); 0 = uniform. Default 0.
    pub fracture_energy_cv: f64,
    /// Random stream of the Gf field, ≥ 2 (0 and 1 are E's and μ's); required when
    /// `fracture_energy_cv` > 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fracture_energy_stream: Option<i64>,
    /// Correlation of the normal scores of the E and Gf fields (Gaussian copula), −1 … 1.
    /// Default 0 (independent).
    pub young_correlation: f64,
    /// Acoustic emission: two breaks at most this far apart (m) … Omitted = 2·Lc.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ae_link_distance_m: Option<f64>,
    /// … and at most this long apart (s) belong to one event. Omitted = 10·Lc/Cp (ten transits
    /// of a P wave across a module).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ae_link_time_s: Option<f64>,
    /// Zones whose bars stay elastic, `{ face = "x_min", depth_m = 0.1 }`: every bar whose
    /// midpoint lies within `depth_m` of the face (grips, loading points). Default none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub elastic_zones: Vec<ElasticZoneSection>,
}

/// One elastic zone of `[rupture]`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ElasticZoneSection {
    /// The face: `"x_min"`, `"x_max"`, `"y_min"`, `"y_max"`, `"z_min"`, `"z_max"`.
    pub face: String,
    /// Depth from the face (m), > 0.
    pub depth_m: f64,
}

impl Default for RuptureSection {
    fn default() -> Self {
        RuptureSection {
            fracture_energy_j_m2: 100.0,
            kr: None,
            failure_factor_per_sqrt_m: None,
            fracture_energy_cv: 0.0,
            fracture_energy_stream: None,
            young_correlation: 0.0,
            ae_link_distance_m: None,
            ae_link_time_s: None,
            elastic_zones: Vec::new(),
        }
    }
}

/// `Kr` when `[rupture]` gives neither `kr` nor a failure factor.
pub const DEFAULT_KR: f64 = 3.0;
