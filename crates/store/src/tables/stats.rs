//! Tables across seeds: the summary statistics, PSA statistics and attenuation fits.

use polars::prelude::DataFrame;
use stickslip_seismo::fit::LogFit;
use stickslip_seismo::stats::Summary;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Frame, read_back};
use crate::spec::{Scope, TableSpec};

/// Statistics across seeds of the events and similarity tables.
pub const SUMMARY: TableSpec = TableSpec {
    name: "summary",
    scope: Scope::AcrossSeeds,
    key: &[col::GROUP, col::QUANTITY],
    columns: &[
        col::GROUP,
        col::QUANTITY,
        col::COUNT,
        col::MEAN,
        col::STD,
        col::CV,
        col::MIN,
        col::P5,
        col::P50,
        col::P95,
        col::MAX,
        col::CI95_LOW,
        col::CI95_HIGH,
        col::GEOMETRIC_MEAN,
        col::LOG_STD,
    ],
    variable: None,
};

/// PSA across seeds.
pub const PSA_STATS: TableSpec = TableSpec {
    name: "psa_stats",
    scope: Scope::AcrossSeeds,
    key: &[col::SCALE, col::NODE, col::COMPONENT, col::DAMPING, col::PERIOD_S],
    columns: &[
        col::SCALE,
        col::NODE,
        col::COMPONENT,
        col::DAMPING,
        col::PERIOD_S,
        col::COUNT,
        col::MEAN_M_S2,
        col::GEOMETRIC_MEAN_M_S2,
        col::P5_M_S2,
        col::P50_M_S2,
        col::P95_M_S2,
        col::IN_BAND,
    ],
    variable: None,
};

/// Log-log fits of peak motions against distance.
pub const ATTENUATION_FIT: TableSpec = TableSpec {
    name: "attenuation_fit",
    scope: Scope::AcrossSeeds,
    key: &[col::GROUP, col::MEASURE],
    columns: &[col::GROUP, col::MEASURE, col::POINTS, col::INTERCEPT, col::SLOPE, col::R2],
    variable: None,
};

/// One row of the summary: the statistics of `quantity` over the events of `group`.
#[derive(Clone, Debug, PartialEq)]
pub struct SummaryRow {
    /// `S1`, `S2`, … (main shocks of that rank over all seeds), `main`, `all`, or `seed`.
    pub group: String,
    /// A column of the events or similarity table, or a per-seed count.
    pub quantity: String,
    /// The statistics.
    pub summary: Summary,
}

/// The summary table.
pub fn summary_frame(rows: &[SummaryRow]) -> Result<DataFrame, StoreError> {
    let n = rows.len();
    let f = |g: &dyn Fn(&Summary) -> f64| rows.iter().map(|r| g(&r.summary)).collect::<Vec<f64>>();
    let o = |g: &dyn Fn(&Summary) -> Option<f64>| rows.iter().map(|r| g(&r.summary)).collect::<Vec<Option<f64>>>();
    Frame::new(n)
        .str(col::GROUP, rows.iter().map(|r| r.group.clone()).collect())
        .str(col::QUANTITY, rows.iter().map(|r| r.quantity.clone()).collect())
        .u32(col::COUNT, rows.iter().map(|r| r.summary.count as u32).collect())
        .f64(col::MEAN, f(&|s| s.mean))
        .opt_f64(col::STD, o(&|s| s.std))
        .opt_f64(col::CV, o(&|s| s.cv))
        .f64(col::MIN, f(&|s| s.min))
        .f64(col::P5, f(&|s| s.p5))
        .f64(col::P50, f(&|s| s.p50))
        .f64(col::P95, f(&|s| s.p95))
        .f64(col::MAX, f(&|s| s.max))
        .opt_f64(col::CI95_LOW, o(&|s| s.ci95_low))
        .opt_f64(col::CI95_HIGH, o(&|s| s.ci95_high))
        .opt_f64(col::GEOMETRIC_MEAN, o(&|s| s.geometric_mean))
        .opt_f64(col::LOG_STD, o(&|s| s.log_std))
        .finish(SUMMARY.name)
}

read_back! {
    /// The summary table read back.
    pub struct SummaryTable from SUMMARY, |c| {
        /// Group of each row.
        group: Vec<String> = c.strs(col::GROUP)?,
        /// Quantity of each row.
        quantity: Vec<String> = c.strs(col::QUANTITY)?,
        /// Count.
        count: Vec<f64> = c.f64s(col::COUNT)?,
        /// Mean.
        mean: Vec<f64> = c.f64s(col::MEAN)?,
        /// Standard deviation (NaN where undefined).
        std: Vec<f64> = c.f64s(col::STD)?,
        /// Lower end of the 95% confidence interval of the mean (NaN where undefined).
        ci95_low: Vec<f64> = c.f64s(col::CI95_LOW)?,
        /// Upper end.
        ci95_high: Vec<f64> = c.f64s(col::CI95_HIGH)?,
    }
}

impl SummaryTable {
    /// The row of `quantity` in `group`, if any.
    pub fn find(&self, group: &str, quantity: &str) -> Option<usize> {
        (0..self.group.len()).find(|&i| self.group[i] == group && self.quantity[i] == quantity)
    }
}

/// PSA across records at one (scale, node, component, damping, period).
#[derive(Clone, Debug, PartialEq)]
pub struct PsaStatsRow {
    /// `model` or `prototype`.
    pub scale: String,
    /// Node (LDEM number).
    pub node: u32,
    /// Component.
    pub component: String,
    /// Damping ratio.
    pub damping: f64,
    /// Period (s).
    pub period_s: f64,
    /// Records whose usable band holds the period: the statistics are over them.
    pub count: u32,
    /// Mean, geometric mean, 5th, 50th and 95th percentiles (m/s²) of those records (NaN, written
    /// as null, when there is none).
    pub stats: [f64; 5],
    /// Whether the period is in the usable band of every record.
    pub in_band: bool,
}

/// The PSA statistics table.
pub fn psa_stats_frame(rows: &[PsaStatsRow]) -> Result<DataFrame, StoreError> {
    let n = rows.len();
    let s = |k: usize| rows.iter().map(|r| r.stats[k]).collect::<Vec<f64>>();
    Frame::new(n)
        .str(col::SCALE, rows.iter().map(|r| r.scale.clone()).collect())
        .u32(col::NODE, rows.iter().map(|r| r.node).collect())
        .str(col::COMPONENT, rows.iter().map(|r| r.component.clone()).collect())
        .f64(col::DAMPING, rows.iter().map(|r| r.damping).collect())
        .f64(col::PERIOD_S, rows.iter().map(|r| r.period_s).collect())
        .u32(col::COUNT, rows.iter().map(|r| r.count).collect())
        .f64(col::MEAN_M_S2, s(0))
        .f64(col::GEOMETRIC_MEAN_M_S2, s(1))
        .f64(col::P5_M_S2, s(2))
        .f64(col::P50_M_S2, s(3))
        .f64(col::P95_M_S2, s(4))
        .bool(col::IN_BAND, rows.iter().map(|r| r.in_band).collect())
        .finish(PSA_STATS.name)
}

read_back! {
    /// The PSA statistics read back.
    pub struct PsaStats from PSA_STATS, |c| {
        /// Scale.
        scale: Vec<String> = c.strs(col::SCALE)?,
        /// Node (LDEM number).
        node: Vec<u64> = c.u64s(col::NODE)?,
        /// Component.
        component: Vec<String> = c.strs(col::COMPONENT)?,
        /// Damping ratio.
        damping: Vec<f64> = c.f64s(col::DAMPING)?,
        /// Period (s).
        period_s: Vec<f64> = c.f64s(col::PERIOD_S)?,
        /// Records in band at the period (the statistics are over them).
        count: Vec<u64> = c.u64s(col::COUNT)?,
        /// Mean (m/s²).
        mean: Vec<f64> = c.f64s(col::MEAN_M_S2)?,
        /// Median (m/s²).
        p50: Vec<f64> = c.f64s(col::P50_M_S2)?,
        /// 5th percentile (m/s²).
        p5: Vec<f64> = c.f64s(col::P5_M_S2)?,
        /// 95th percentile (m/s²).
        p95: Vec<f64> = c.f64s(col::P95_M_S2)?,
        /// Whether the period is in the usable band of every record.
        in_band: Vec<bool> = c.bools(col::IN_BAND)?,
    }
}

/// One fit of the attenuation table.
#[derive(Clone, Debug, PartialEq)]
pub struct FitRow {
    /// `S1`, … or `main` (control nodes against the hypocentre), `stations` (a fault scene's
    /// stations against R_rup).
    pub group: String,
    /// `pga_m_s2` or `pgv_m_s`.
    pub measure: &'static str,
    /// The fit.
    pub fit: LogFit,
}

/// The attenuation fit table (`log10 y = intercept + slope·log10(distance_m)`).
pub fn attenuation_fit_frame(rows: &[FitRow]) -> Result<DataFrame, StoreError> {
    let n = rows.len();
    Frame::new(n)
        .str(col::GROUP, rows.iter().map(|r| r.group.clone()).collect())
        .static_str(col::MEASURE, rows.iter().map(|r| r.measure).collect())
        .u32(col::POINTS, rows.iter().map(|r| r.fit.points as u32).collect())
        .f64(col::INTERCEPT, rows.iter().map(|r| r.fit.intercept).collect())
        .f64(col::SLOPE, rows.iter().map(|r| r.fit.slope).collect())
        .f64(col::R2, rows.iter().map(|r| r.fit.r2).collect())
        .finish(ATTENUATION_FIT.name)
}

read_back! {
    /// The attenuation fits read back.
    pub struct AttenuationFit from ATTENUATION_FIT, |c| {
        /// Group.
        group: Vec<String> = c.strs(col::GROUP)?,
        /// Measure.
        measure: Vec<String> = c.strs(col::MEASURE)?,
        /// Points fitted.
        points: Vec<u64> = c.u64s(col::POINTS)?,
        /// Intercept.
        intercept: Vec<f64> = c.f64s(col::INTERCEPT)?,
        /// Slope.
        slope: Vec<f64> = c.f64s(col::SLOPE)?,
        /// r².
        r2: Vec<f64> = c.f64s(col::R2)?,
    }
}
