//! The comparison of a fault scenario's stations with the NGA-West2 ground-motion models
//! (docs/model.md §16), written by `stickslip gmm`.
//!
//! **gmm_residuals**, one row per seed, station, intensity measure and model (`bssa14`, `ask14`,
//! `cb14`, `cy14` and `average`: the models' mean in ln units): `seed` u64, `station` str, `imt` str (`PGA`,
//! `PGV`, `PSA`), `period_s` f64 (null for PGA and PGV), `model` str, `mw`, `r_rup_km`,
//! `r_jb_km`, `azimuth_deg`, `vs30_m_s`, `simulated` (RotD50: m/s² for PGA and PSA, m/s for PGV),
//! `median` (the model's, same unit), `sigma`, `tau`, `phi` (natural log; τ and φ null on the
//! average rows), `residual_ln`
//! (ln(simulated/median)), `residual_sigma` (residual_ln/σ) f64, `outside` str (the quantities
//! outside the model's ranges; null inside them).
//!
//! **gmm_bias**, one row per site (records grouped by their V_S30), intensity measure and model
//! over its records: `vs30_m_s` f64, `imt` str, `period_s` f64 (null for PGA and PGV), `model`
//! str, `records` u32, `mean_bias_ln`,
//! `ci90_low_ln`, `ci90_high_ln` (Student's t), `between_record_std_ln`, `within_one_sigma`
//! (fraction of records with |residual| ≤ σ) f64, `within_band` bool (|mean bias| ≤ 0.37, the
//! Broadband Platform's pass band), `part_b_pass` bool (Goulet et al. 2015's test in every distance
//! bin of `gmm_part_b`; on the average rows only, null on the others), `slope_simulated`, `slope_model`, `slope_difference`,
//! `slope_difference_se` f64 (d ln Y/d ln R_rup of the simulations and the model medians, and
//! their difference with its standard error), `outside_records` u32 (records whose prediction
//! extrapolates the model), `note` str (why a measure is not comparable: PGA beyond the records'
//! band; null otherwise).
//!
//! **gmm_part_b**, one row per site, intensity measure and R_rup bin with records: the Part-B test
//! of Goulet et al. (2015) as the Broadband Platform computes it (docs/model.md §16.3): `vs30_m_s`
//! f64, `imt` str, `period_s` f64 (null for PGA and PGV), `distance_min_km`, `distance_max_km` f64
//! (the bin, [min, max)), `records` u32, `simulated_median` (the geometric mean of RotD50 over the
//! bin's stations and seeds), `models_mean` (the arithmetic mean of the models' medians over the
//! bin), `band_low`, `band_high` (min(mean·e^−0.3665, 0.85·lowest model), max(mean·e^+0.3665,
//! 1.15·highest model)) f64 (the simulations' unit), `pass` bool, `judged` bool (PGA and PSA at
//! 0.01–3 s, as the Platform judges; 3–10 s and PGV informational).

use polars::prelude::DataFrame;

use crate::col;
use crate::error::StoreError;
use crate::frame::Frame;
use crate::spec::{Scope, TableSpec};

/// Residuals of every station's RotD50 against each model.
pub const GMM_RESIDUALS: TableSpec = TableSpec {
    name: "gmm_residuals",
    scope: Scope::AcrossSeeds,
    key: &[col::SEED, col::STATION, col::IMT, col::PERIOD_S, col::MODEL],
    columns: &[
        col::SEED,
        col::STATION,
        col::IMT,
        col::PERIOD_S,
        col::MODEL,
        col::MW,
        col::R_RUP_KM,
        col::R_JB_KM,
        col::AZIMUTH_DEG,
        col::VS30_M_S,
        col::SIMULATED,
        col::MEDIAN,
        col::SIGMA,
        col::TAU,
        col::PHI,
        col::RESIDUAL_LN,
        col::RESIDUAL_SIGMA,
        col::OUTSIDE,
    ],
    variable: None,
};

/// Bias statistics per intensity measure and model.
pub const GMM_BIAS: TableSpec = TableSpec {
    name: "gmm_bias",
    scope: Scope::AcrossSeeds,
    key: &[col::VS30_M_S, col::IMT, col::PERIOD_S, col::MODEL],
    columns: &[
        col::VS30_M_S,
        col::IMT,
        col::PERIOD_S,
        col::MODEL,
        col::RECORDS,
        col::MEAN_BIAS_LN,
        col::CI90_LOW_LN,
        col::CI90_HIGH_LN,
        col::BETWEEN_RECORD_STD_LN,
        col::WITHIN_ONE_SIGMA,
        col::WITHIN_BAND,
        col::PART_B_PASS,
        col::SLOPE_SIMULATED,
        col::SLOPE_MODEL,
        col::SLOPE_DIFFERENCE,
        col::SLOPE_DIFFERENCE_SE,
        col::OUTSIDE_RECORDS,
        col::NOTE,
    ],
    variable: None,
};

/// The Part-B test per site, intensity measure and distance bin.
pub const GMM_PART_B: TableSpec = TableSpec {
    name: "gmm_part_b",
    scope: Scope::AcrossSeeds,
    key: &[col::VS30_M_S, col::IMT, col::PERIOD_S, col::DISTANCE_MIN_KM],
    columns: &[
        col::VS30_M_S,
        col::IMT,
        col::PERIOD_S,
        col::DISTANCE_MIN_KM,
        col::DISTANCE_MAX_KM,
        col::RECORDS,
        col::SIMULATED_MEDIAN,
        col::MODELS_MEAN,
        col::BAND_LOW,
        col::BAND_HIGH,
        col::PASS,
        col::JUDGED,
    ],
    variable: None,
};

/// One row of `gmm_part_b`.
#[derive(Clone, Debug, PartialEq)]
pub struct PartBRow {
    /// The site group's V_S30 (m/s).
    pub vs30_m_s: f64,
    /// `PGA`, `PGV` or `PSA`.
    pub imt: &'static str,
    /// Period of a PSA (s).
    pub period_s: Option<f64>,
    /// The R_rup bin [min, max) (km).
    pub distance_km: [f64; 2],
    /// Records in it.
    pub records: usize,
    /// Geometric mean of the simulations.
    pub simulated_median: f64,
    /// Arithmetic mean of the models' medians.
    pub models_mean: f64,
    /// The band.
    pub band: [f64; 2],
    /// Whether the simulations' median lies in it.
    pub pass: bool,
    /// Whether the Platform judges this measure (PGA, PSA at 0.01–3 s).
    pub judged: bool,
}

/// The R_rup bins of the Part-B test (km): the Broadband Platform's distance bins of its
/// goodness-of-fit summaries.
pub const PART_B_BINS_KM: [[f64; 2]; 4] = [[0.0, 5.0], [5.0, 20.0], [20.0, 70.0], [70.0, 300.0]];

/// The longest period the Platform judges Part B at (s).
pub const PART_B_JUDGED_MAX_S: f64 = 3.0;

/// The `gmm_part_b` table.
pub fn part_b_frame(rows: &[PartBRow]) -> Result<DataFrame, StoreError> {
    let f = |g: &dyn Fn(&PartBRow) -> f64| rows.iter().map(g).collect::<Vec<f64>>();
    Frame::new(rows.len())
        .f64(col::VS30_M_S, f(&|r| r.vs30_m_s))
        .static_str(col::IMT, rows.iter().map(|r| r.imt).collect())
        .opt_f64(col::PERIOD_S, rows.iter().map(|r| r.period_s).collect())
        .f64(col::DISTANCE_MIN_KM, f(&|r| r.distance_km[0]))
        .f64(col::DISTANCE_MAX_KM, f(&|r| r.distance_km[1]))
        .u32(col::RECORDS, rows.iter().map(|r| r.records as u32).collect())
        .f64(col::SIMULATED_MEDIAN, f(&|r| r.simulated_median))
        .f64(col::MODELS_MEAN, f(&|r| r.models_mean))
        .f64(col::BAND_LOW, f(&|r| r.band[0]))
        .f64(col::BAND_HIGH, f(&|r| r.band[1]))
        .bool(col::PASS, rows.iter().map(|r| r.pass).collect())
        .bool(col::JUDGED, rows.iter().map(|r| r.judged).collect())
        .finish(GMM_PART_B.name)
}

/// One row of `gmm_residuals`.
#[derive(Clone, Debug, PartialEq)]
pub struct ResidualRow {
    /// Seed.
    pub seed: u64,
    /// Station.
    pub station: String,
    /// `PGA`, `PGV` or `PSA`.
    pub imt: &'static str,
    /// Period of a PSA (s).
    pub period_s: Option<f64>,
    /// `bssa14`, `ask14`, `cb14`, `cy14` or `average`.
    pub model: &'static str,
    /// The seed's Mw.
    pub mw: f64,
    /// Distances (km) and azimuth (degrees).
    pub r_rup_km: f64,
    /// R_JB (km).
    pub r_jb_km: f64,
    /// Azimuth from the strike (degrees).
    pub azimuth_deg: f64,
    /// V_S30 given to the model (m/s).
    pub vs30_m_s: f64,
    /// Simulated RotD50.
    pub simulated: f64,
    /// The model's median.
    pub median: f64,
    /// σ (ln).
    pub sigma: f64,
    /// τ (ln); `None` for the models' average.
    pub tau: Option<f64>,
    /// φ (ln); `None` for the models' average.
    pub phi: Option<f64>,
    /// Quantities outside the model's ranges (`None`: inside).
    pub outside: Option<String>,
}

/// One row of `gmm_bias`.
#[derive(Clone, Debug, PartialEq)]
pub struct BiasRow {
    /// The site group's V_S30 (m/s).
    pub vs30_m_s: f64,
    /// `PGA`, `PGV` or `PSA`.
    pub imt: &'static str,
    /// Period of a PSA (s).
    pub period_s: Option<f64>,
    /// `bssa14`, `ask14`, `cb14`, `cy14` or `average`.
    pub model: &'static str,
    /// Records.
    pub records: usize,
    /// Mean bias (ln).
    pub mean_bias_ln: f64,
    /// Its 90% interval.
    pub ci90_ln: Option<[f64; 2]>,
    /// Between-record standard deviation (ln).
    pub between_record_std_ln: Option<f64>,
    /// Fraction within ±1σ.
    pub within_one_sigma: f64,
    /// Goulet et al.'s Part-B test (average rows).
    pub part_b_pass: Option<bool>,
    /// Attenuation slopes: simulated, model, difference and its standard error.
    pub slope: Option<[Option<f64>; 4]>,
    /// Records whose prediction extrapolates the model.
    pub outside_records: usize,
    /// Why the measure cannot be compared (PGA beyond the records' band); `None` otherwise.
    pub note: Option<String>,
}

/// The pass band of the mean bias (ln units) of the SCEC Broadband Platform's validation.
pub const BIAS_BAND_LN: f64 = 0.37;

/// The between-record standard deviation of recorded motions, ln units: a simulation's spread is
/// expected inside it.
pub const RECORD_SPREAD_LN: [f64; 2] = [0.4, 0.8];

/// The share of records expected within ±1σ of a model (68% for a normal spread; 60% asked).
pub const WITHIN_ONE_SIGMA_MIN: f64 = 0.6;

/// The largest difference of attenuation slopes (ln per ln R_rup) taken as following the models.
pub const SLOPE_TOLERANCE: f64 = 0.2;

/// The `gmm_residuals` table.
pub fn residuals_frame(rows: &[ResidualRow]) -> Result<DataFrame, StoreError> {
    let f = |g: &dyn Fn(&ResidualRow) -> f64| rows.iter().map(g).collect::<Vec<f64>>();
    Frame::new(rows.len())
        .u64(col::SEED, rows.iter().map(|r| r.seed).collect())
        .str(col::STATION, rows.iter().map(|r| r.station.clone()).collect())
        .static_str(col::IMT, rows.iter().map(|r| r.imt).collect())
        .opt_f64(col::PERIOD_S, rows.iter().map(|r| r.period_s).collect())
        .static_str(col::MODEL, rows.iter().map(|r| r.model).collect())
        .f64(col::MW, f(&|r| r.mw))
        .f64(col::R_RUP_KM, f(&|r| r.r_rup_km))
        .f64(col::R_JB_KM, f(&|r| r.r_jb_km))
        .f64(col::AZIMUTH_DEG, f(&|r| r.azimuth_deg))
        .f64(col::VS30_M_S, f(&|r| r.vs30_m_s))
        .f64(col::SIMULATED, f(&|r| r.simulated))
        .f64(col::MEDIAN, f(&|r| r.median))
        .f64(col::SIGMA, f(&|r| r.sigma))
        .opt_f64(col::TAU, rows.iter().map(|r| r.tau).collect())
        .opt_f64(col::PHI, rows.iter().map(|r| r.phi).collect())
        .f64(col::RESIDUAL_LN, f(&|r| (r.simulated / r.median).ln()))
        .f64(col::RESIDUAL_SIGMA, f(&|r| (r.simulated / r.median).ln() / r.sigma))
        .opt_str(col::OUTSIDE, rows.iter().map(|r| r.outside.clone()).collect())
        .finish(GMM_RESIDUALS.name)
}

/// The `gmm_bias` table.
pub fn bias_frame(rows: &[BiasRow]) -> Result<DataFrame, StoreError> {
    let slope = |k: usize| rows.iter().map(|r| r.slope.and_then(|s| s[k])).collect::<Vec<Option<f64>>>();
    Frame::new(rows.len())
        .f64(col::VS30_M_S, rows.iter().map(|r| r.vs30_m_s).collect())
        .static_str(col::IMT, rows.iter().map(|r| r.imt).collect())
        .opt_f64(col::PERIOD_S, rows.iter().map(|r| r.period_s).collect())
        .static_str(col::MODEL, rows.iter().map(|r| r.model).collect())
        .u32(col::RECORDS, rows.iter().map(|r| r.records as u32).collect())
        .f64(col::MEAN_BIAS_LN, rows.iter().map(|r| r.mean_bias_ln).collect())
        .opt_f64(col::CI90_LOW_LN, rows.iter().map(|r| r.ci90_ln.map(|c| c[0])).collect())
        .opt_f64(col::CI90_HIGH_LN, rows.iter().map(|r| r.ci90_ln.map(|c| c[1])).collect())
        .opt_f64(col::BETWEEN_RECORD_STD_LN, rows.iter().map(|r| r.between_record_std_ln).collect())
        .f64(col::WITHIN_ONE_SIGMA, rows.iter().map(|r| r.within_one_sigma).collect())
        .bool(col::WITHIN_BAND, rows.iter().map(|r| r.mean_bias_ln.abs() <= BIAS_BAND_LN).collect())
        .opt_bool(col::PART_B_PASS, rows.iter().map(|r| r.part_b_pass).collect())
        .opt_f64(col::SLOPE_SIMULATED, slope(0))
        .opt_f64(col::SLOPE_MODEL, slope(1))
        .opt_f64(col::SLOPE_DIFFERENCE, slope(2))
        .opt_f64(col::SLOPE_DIFFERENCE_SE, slope(3))
        .u32(col::OUTSIDE_RECORDS, rows.iter().map(|r| r.outside_records as u32).collect())
        .opt_str(col::NOTE, rows.iter().map(|r| r.note.clone()).collect())
        .finish(GMM_BIAS.name)
}
