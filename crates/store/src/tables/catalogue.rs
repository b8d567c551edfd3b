//! The catalogue tables: magnitude–frequency distributions and b-values, recurrence statistics,
//! aftershock rates and Omori–Utsu fits, scaling relations. Each row is for one seed or for all
//! seeds pooled (`seed` null); a statistic that cannot be made has nulls and its `reason`.

use polars::prelude::DataFrame;
use stickslip_seismo::catalogue::aftershocks::{OmoriFit, RateBin};
use stickslip_seismo::catalogue::magnitude_frequency::GutenbergRichterFit;
use stickslip_seismo::catalogue::recurrence::{BptFit, ExponentialFit, RecurrenceStatistics, WeibullFit};
use stickslip_seismo::catalogue::scaling::ScalingFit;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Frame, read_back};
use crate::spec::{Scope, TableSpec};

/// Magnitude–frequency distributions (magnitudes in bins of 0.1; moment and stress drop in
/// logarithmic bins), per seed and pooled (`seed` null), with the Gutenberg–Richter fit's
/// expected cumulative count above its Mc.
pub const MAGNITUDE_FREQUENCY: TableSpec = TableSpec {
    name: "magnitude_frequency",
    scope: Scope::AcrossSeeds,
    key: &[col::SEED, col::QUANTITY, col::BIN_CENTRE],
    columns: &[
        col::SEED,
        col::QUANTITY,
        col::BIN_LOW,
        col::BIN_CENTRE,
        col::BIN_HIGH,
        col::INCREMENTAL,
        col::CUMULATIVE,
        col::FIT_CUMULATIVE,
    ],
    variable: None,
};

/// Gutenberg–Richter fits: completeness magnitude (maximum curvature + 0.2, goodness of fit 90%)
/// and b-value (Aki–Utsu, Shi–Bolt σ), or the reason none could be made.
pub const B_VALUES: TableSpec = TableSpec {
    name: "b_values",
    scope: Scope::AcrossSeeds,
    key: &[col::SEED, col::QUANTITY],
    columns: &[
        col::SEED,
        col::QUANTITY,
        col::EVENTS,
        col::MC_MAXC,
        col::MC_GOF,
        col::GOF_PERCENT,
        col::MC,
        col::EVENTS_ABOVE_MC,
        col::B,
        col::B_SIGMA,
        col::B_BINNED,
        col::A_VALUE,
        col::REASON,
    ],
    variable: None,
};

/// Recurrence statistics of main shocks and of all events (model-scale seconds): mean, CV and
/// the BPT, Weibull and exponential renewal fits, or the reason none could be made.
pub const RECURRENCE_STATS: TableSpec = TableSpec {
    name: "recurrence_stats",
    scope: Scope::AcrossSeeds,
    key: &[col::SEED, col::SEQUENCE],
    columns: &[
        col::SEED,
        col::SEQUENCE,
        col::INTERVALS,
        col::MEAN_S,
        col::STD_S,
        col::CV,
        col::MEAN_CI95_LOW_S,
        col::MEAN_CI95_HIGH_S,
        col::CV_CI95_LOW,
        col::CV_CI95_HIGH,
        col::BPT_MEAN_S,
        col::BPT_APERIODICITY,
        col::BPT_AIC,
        col::WEIBULL_SCALE_S,
        col::WEIBULL_SHAPE,
        col::WEIBULL_AIC,
        col::EXPONENTIAL_AIC,
        col::REASON,
    ],
    variable: None,
};

/// Aftershock rate per main shock against time since it, stacked over main shocks (per seed and
/// pooled), with the Omori–Utsu fit's rate where one could be made.
pub const AFTERSHOCKS_TABLE: TableSpec = TableSpec {
    name: "aftershocks",
    scope: Scope::AcrossSeeds,
    key: &[col::SEED, col::START_S],
    columns: &[
        col::SEED,
        col::START_S,
        col::END_S,
        col::CENTRE_S,
        col::COUNT,
        col::EXPOSURE_S,
        col::RATE_PER_S,
        col::RATE_ERROR_PER_S,
        col::OMORI_RATE_PER_S,
    ],
    variable: None,
};

/// Omori–Utsu fits `K/(t + c)^p` of the stacked aftershocks, or the reason none could be made.
pub const OMORI: TableSpec = TableSpec {
    name: "omori",
    scope: Scope::AcrossSeeds,
    key: &[col::SEED],
    columns: &[
        col::SEED,
        col::MAIN_SHOCKS,
        col::AFTERSHOCKS,
        col::K,
        col::C_S,
        col::P,
        col::K_SE,
        col::C_SE_S,
        col::P_SE,
        col::FIT_START_S,
        col::FIT_END_S,
        col::REASON,
    ],
    variable: None,
};

/// Scaling relations (moment–area, moment–duration, stress drop–magnitude): fitted exponent with
/// its 95% interval beside the self-similar one, or the reason none could be made.
pub const SCALING: TableSpec = TableSpec {
    name: "scaling",
    scope: Scope::AcrossSeeds,
    key: &[col::SEED, col::RELATION],
    columns: &[
        col::SEED,
        col::RELATION,
        col::POINTS,
        col::EXPONENT,
        col::EXPONENT_SE,
        col::EXPONENT_CI95_LOW,
        col::EXPONENT_CI95_HIGH,
        col::INTERCEPT,
        col::R2,
        col::RESIDUAL_STD,
        col::SELF_SIMILAR_EXPONENT,
        col::REASON,
    ],
    variable: None,
};

/// The catalogue tables, written together by the gathering step.
pub const CATALOGUE: [TableSpec; 6] =
    [MAGNITUDE_FREQUENCY, B_VALUES, RECURRENCE_STATS, AFTERSHOCKS_TABLE, OMORI, SCALING];

/// A fit or the reason it could not be made.
pub type Outcome<T> = Result<T, String>;

fn ok<T, U>(rows: &[T], get: impl Fn(&T) -> Option<U>) -> Vec<Option<U>> {
    rows.iter().map(get).collect()
}

fn reason<T, F>(rows: &[T], get: impl Fn(&T) -> &Outcome<F>) -> Vec<Option<String>> {
    rows.iter().map(|r| get(r).as_ref().err().cloned()).collect()
}

/// One bin of a magnitude–frequency distribution.
#[derive(Clone, Debug, PartialEq)]
pub struct FrequencyBin {
    /// Seed, or `None` for all seeds pooled.
    pub seed: Option<u64>,
    /// The events-table or similarity-table column counted (e.g. `mw_consistent`).
    pub quantity: String,
    /// Lower edge of the bin.
    pub low: f64,
    /// Centre (magnitudes: `k·Δm`; logarithmic bins: geometric centre).
    pub centre: f64,
    /// Upper edge.
    pub high: f64,
    /// Events in the bin.
    pub incremental: u64,
    /// Events in this bin or above.
    pub cumulative: u64,
    /// Cumulative count the Gutenberg–Richter fit expects (bins at or above its Mc).
    pub fit_cumulative: Option<f64>,
}

/// The magnitude–frequency table.
pub fn magnitude_frequency_frame(rows: &[FrequencyBin]) -> Result<DataFrame, StoreError> {
    Frame::new(rows.len())
        .opt_u64(col::SEED, ok(rows, |r| r.seed))
        .str(col::QUANTITY, rows.iter().map(|r| r.quantity.clone()).collect())
        .f64(col::BIN_LOW, rows.iter().map(|r| r.low).collect())
        .f64(col::BIN_CENTRE, rows.iter().map(|r| r.centre).collect())
        .f64(col::BIN_HIGH, rows.iter().map(|r| r.high).collect())
        .u64(col::INCREMENTAL, rows.iter().map(|r| r.incremental).collect())
        .u64(col::CUMULATIVE, rows.iter().map(|r| r.cumulative).collect())
        .opt_f64(col::FIT_CUMULATIVE, ok(rows, |r| r.fit_cumulative))
        .finish(MAGNITUDE_FREQUENCY.name)
}

/// A Gutenberg–Richter fit of one magnitude column.
#[derive(Clone, Debug, PartialEq)]
pub struct BValueRow {
    /// Seed, or `None` for all seeds pooled.
    pub seed: Option<u64>,
    /// The magnitude column.
    pub quantity: String,
    /// Events with a finite magnitude.
    pub events: u64,
    /// Completeness by maximum curvature (+0.2), if the distribution has a mode.
    pub mc_maxc: Option<f64>,
    /// Completeness by goodness of fit at 90%, and the fit reached there.
    pub mc_gof: Option<(f64, f64)>,
    /// The fit above the Mc used (the larger of the two), or why none.
    pub fit: Outcome<GutenbergRichterFit>,
}

/// The b-values table.
pub fn b_values_frame(rows: &[BValueRow]) -> Result<DataFrame, StoreError> {
    let fit = |g: fn(&GutenbergRichterFit) -> f64| ok(rows, move |r| r.fit.as_ref().ok().map(g));
    Frame::new(rows.len())
        .opt_u64(col::SEED, ok(rows, |r| r.seed))
        .str(col::QUANTITY, rows.iter().map(|r| r.quantity.clone()).collect())
        .u64(col::EVENTS, rows.iter().map(|r| r.events).collect())
        .opt_f64(col::MC_MAXC, ok(rows, |r| r.mc_maxc))
        .opt_f64(col::MC_GOF, ok(rows, |r| r.mc_gof.map(|g| g.0)))
        .opt_f64(col::GOF_PERCENT, ok(rows, |r| r.mc_gof.map(|g| g.1)))
        .opt_f64(col::MC, fit(|f| f.mc))
        .opt_u64(col::EVENTS_ABOVE_MC, ok(rows, |r| r.fit.as_ref().ok().map(|f| f.n as u64)))
        .opt_f64(col::B, fit(|f| f.b))
        .opt_f64(col::B_SIGMA, fit(|f| f.b_sigma))
        .opt_f64(col::B_BINNED, fit(|f| f.b_binned))
        .opt_f64(col::A_VALUE, fit(|f| f.a))
        .opt_str(col::REASON, reason(rows, |r| &r.fit))
        .finish(B_VALUES.name)
}

/// Recurrence statistics of one sequence of events.
#[derive(Clone, Debug, PartialEq)]
pub struct RecurrenceRow {
    /// Seed, or `None` for all seeds pooled (intervals within each seed, pooled).
    pub seed: Option<u64>,
    /// `main` (main shocks) or `all` (every event).
    pub sequence: &'static str,
    /// Intervals available.
    pub intervals: u64,
    /// Mean, spread and CV, or why not.
    pub stats: Outcome<RecurrenceStatistics>,
    /// 95% bootstrap interval of the CV.
    pub cv_ci95: Option<(f64, f64)>,
    /// Brownian passage time fit.
    pub bpt: Outcome<BptFit>,
    /// Weibull fit.
    pub weibull: Outcome<WeibullFit>,
    /// Exponential (Poisson) fit, the reference.
    pub exponential: Outcome<ExponentialFit>,
}

/// The recurrence statistics table.
pub fn recurrence_stats_frame(rows: &[RecurrenceRow]) -> Result<DataFrame, StoreError> {
    let st = |g: fn(&RecurrenceStatistics) -> f64| ok(rows, move |r| r.stats.as_ref().ok().map(g));
    let bpt = |g: fn(&BptFit) -> f64| ok(rows, move |r| r.bpt.as_ref().ok().map(g));
    let wb = |g: fn(&WeibullFit) -> f64| ok(rows, move |r| r.weibull.as_ref().ok().map(g));
    let why = rows
        .iter()
        .map(|r| {
            let parts: Vec<String> = [
                r.stats.as_ref().err().map(|e| format!("statistics: {e}")),
                r.bpt.as_ref().err().map(|e| format!("BPT: {e}")),
                r.weibull.as_ref().err().map(|e| format!("Weibull: {e}")),
            ]
            .into_iter()
            .flatten()
            .collect();
            (!parts.is_empty()).then(|| parts.join("; "))
        })
        .collect();
    Frame::new(rows.len())
        .opt_u64(col::SEED, ok(rows, |r| r.seed))
        .static_str(col::SEQUENCE, rows.iter().map(|r| r.sequence).collect())
        .u64(col::INTERVALS, rows.iter().map(|r| r.intervals).collect())
        .opt_f64(col::MEAN_S, st(|s| s.mean))
        .opt_f64(col::STD_S, st(|s| s.std))
        .opt_f64(col::CV, st(|s| s.cv))
        .opt_f64(col::MEAN_CI95_LOW_S, st(|s| s.mean_ci95.0))
        .opt_f64(col::MEAN_CI95_HIGH_S, st(|s| s.mean_ci95.1))
        .opt_f64(col::CV_CI95_LOW, ok(rows, |r| r.cv_ci95.map(|c| c.0)))
        .opt_f64(col::CV_CI95_HIGH, ok(rows, |r| r.cv_ci95.map(|c| c.1)))
        .opt_f64(col::BPT_MEAN_S, bpt(|f| f.mean))
        .opt_f64(col::BPT_APERIODICITY, bpt(|f| f.aperiodicity))
        .opt_f64(col::BPT_AIC, bpt(|f| f.aic))
        .opt_f64(col::WEIBULL_SCALE_S, wb(|f| f.scale))
        .opt_f64(col::WEIBULL_SHAPE, wb(|f| f.shape))
        .opt_f64(col::WEIBULL_AIC, wb(|f| f.aic))
        .opt_f64(col::EXPONENTIAL_AIC, ok(rows, |r| r.exponential.as_ref().ok().map(|f| f.aic)))
        .opt_str(col::REASON, why)
        .finish(RECURRENCE_STATS.name)
}

/// One time bin of a stacked aftershock rate.
#[derive(Clone, Debug, PartialEq)]
pub struct AftershockBin {
    /// Seed, or `None` for all seeds pooled.
    pub seed: Option<u64>,
    /// The bin (times since the main shock, s).
    pub bin: RateBin,
    /// Rate of the Omori–Utsu fit at the bin's centre, if one was made.
    pub omori_rate: Option<f64>,
}

/// The aftershocks table.
pub fn aftershocks_frame(rows: &[AftershockBin]) -> Result<DataFrame, StoreError> {
    let b = |g: fn(&RateBin) -> f64| rows.iter().map(|r| g(&r.bin)).collect::<Vec<f64>>();
    Frame::new(rows.len())
        .opt_u64(col::SEED, ok(rows, |r| r.seed))
        .f64(col::START_S, b(|b| b.start))
        .f64(col::END_S, b(|b| b.end))
        .f64(col::CENTRE_S, b(|b| b.centre))
        .u64(col::COUNT, rows.iter().map(|r| r.bin.count as u64).collect())
        .f64(col::EXPOSURE_S, b(|b| b.exposure))
        .f64(col::RATE_PER_S, b(|b| b.rate))
        .f64(col::RATE_ERROR_PER_S, b(|b| b.rate_error))
        .opt_f64(col::OMORI_RATE_PER_S, ok(rows, |r| r.omori_rate))
        .finish(AFTERSHOCKS_TABLE.name)
}

/// An Omori–Utsu fit.
#[derive(Clone, Debug, PartialEq)]
pub struct OmoriRow {
    /// Seed, or `None` for all seeds pooled.
    pub seed: Option<u64>,
    /// Main shocks stacked.
    pub main_shocks: u64,
    /// Aftershocks in their windows.
    pub aftershocks: u64,
    /// The fit, or why none.
    pub fit: Outcome<OmoriFit>,
}

/// The Omori table.
pub fn omori_frame(rows: &[OmoriRow]) -> Result<DataFrame, StoreError> {
    let fit = |g: fn(&OmoriFit) -> f64| ok(rows, move |r| r.fit.as_ref().ok().map(g));
    Frame::new(rows.len())
        .opt_u64(col::SEED, ok(rows, |r| r.seed))
        .u64(col::MAIN_SHOCKS, rows.iter().map(|r| r.main_shocks).collect())
        .u64(col::AFTERSHOCKS, rows.iter().map(|r| r.aftershocks).collect())
        .opt_f64(col::K, fit(|f| f.k))
        .opt_f64(col::C_S, fit(|f| f.c))
        .opt_f64(col::P, fit(|f| f.p))
        .opt_f64(col::K_SE, fit(|f| f.k_se))
        .opt_f64(col::C_SE_S, fit(|f| f.c_se))
        .opt_f64(col::P_SE, fit(|f| f.p_se))
        .opt_f64(col::FIT_START_S, fit(|f| f.t_start))
        .opt_f64(col::FIT_END_S, fit(|f| f.t_end))
        .opt_str(col::REASON, reason(rows, |r| &r.fit))
        .finish(OMORI.name)
}

/// One scaling relation.
#[derive(Clone, Debug, PartialEq)]
pub struct ScalingRow {
    /// Seed, or `None` for all seeds pooled.
    pub seed: Option<u64>,
    /// `moment_area`, `moment_duration` or `stress_drop_magnitude`.
    pub relation: &'static str,
    /// The self-similar exponent it is compared with.
    pub self_similar: f64,
    /// The fit, or why none.
    pub fit: Outcome<ScalingFit>,
}

/// The scaling table.
pub fn scaling_frame(rows: &[ScalingRow]) -> Result<DataFrame, StoreError> {
    let fit = |g: fn(&ScalingFit) -> f64| ok(rows, move |r| r.fit.as_ref().ok().map(g));
    Frame::new(rows.len())
        .opt_u64(col::SEED, ok(rows, |r| r.seed))
        .static_str(col::RELATION, rows.iter().map(|r| r.relation).collect())
        .opt_u32(col::POINTS, ok(rows, |r| r.fit.as_ref().ok().map(|f| f.n as u32)))
        .opt_f64(col::EXPONENT, fit(|f| f.line.exponent))
        .opt_f64(col::EXPONENT_SE, fit(|f| f.exponent_se))
        .opt_f64(col::EXPONENT_CI95_LOW, fit(|f| f.exponent_ci95.0))
        .opt_f64(col::EXPONENT_CI95_HIGH, fit(|f| f.exponent_ci95.1))
        .opt_f64(col::INTERCEPT, fit(|f| f.line.intercept))
        .opt_f64(col::R2, ok(rows, |r| r.fit.as_ref().ok().and_then(|f| f.r_squared)))
        .opt_f64(col::RESIDUAL_STD, fit(|f| f.residual_std))
        .f64(col::SELF_SIMILAR_EXPONENT, rows.iter().map(|r| r.self_similar).collect())
        .opt_str(col::REASON, reason(rows, |r| &r.fit))
        .finish(SCALING.name)
}

read_back! {
    /// The magnitude–frequency table read back.
    pub struct MagnitudeFrequency from MAGNITUDE_FREQUENCY, |c| {
        /// Seed (`None`: pooled).
        seed: Vec<Option<u64>> = c.opt_u64s(col::SEED)?,
        /// Quantity.
        quantity: Vec<String> = c.strs(col::QUANTITY)?,
        /// Bin centre.
        centre: Vec<f64> = c.f64s(col::BIN_CENTRE)?,
        /// Events in the bin.
        incremental: Vec<f64> = c.f64s(col::INCREMENTAL)?,
        /// Events in the bin or above.
        cumulative: Vec<f64> = c.f64s(col::CUMULATIVE)?,
        /// Fitted cumulative count.
        fit_cumulative: Vec<Option<f64>> = c.opt_f64s(col::FIT_CUMULATIVE)?,
    }
}

read_back! {
    /// The b-values table read back.
    pub struct BValues from B_VALUES, |c| {
        /// Seed (`None`: pooled).
        seed: Vec<Option<u64>> = c.opt_u64s(col::SEED)?,
        /// Magnitude column.
        quantity: Vec<String> = c.strs(col::QUANTITY)?,
        /// Events.
        events: Vec<u64> = c.u64s(col::EVENTS)?,
        /// Mc used.
        mc: Vec<Option<f64>> = c.opt_f64s(col::MC)?,
        /// Events at or above Mc.
        events_above_mc: Vec<Option<u64>> = c.opt_u64s(col::EVENTS_ABOVE_MC)?,
        /// b.
        b: Vec<Option<f64>> = c.opt_f64s(col::B)?,
        /// σ_b.
        b_sigma: Vec<Option<f64>> = c.opt_f64s(col::B_SIGMA)?,
        /// a.
        a: Vec<Option<f64>> = c.opt_f64s(col::A_VALUE)?,
        /// Why no fit.
        reason: Vec<Option<String>> = c.opt_strs(col::REASON)?,
    }
}

read_back! {
    /// The recurrence statistics read back.
    pub struct RecurrenceStats from RECURRENCE_STATS, |c| {
        /// Seed (`None`: pooled).
        seed: Vec<Option<u64>> = c.opt_u64s(col::SEED)?,
        /// `main` or `all`.
        sequence: Vec<String> = c.strs(col::SEQUENCE)?,
        /// Intervals.
        intervals: Vec<u64> = c.u64s(col::INTERVALS)?,
        /// Mean (s).
        mean_s: Vec<Option<f64>> = c.opt_f64s(col::MEAN_S)?,
        /// CV.
        cv: Vec<Option<f64>> = c.opt_f64s(col::CV)?,
        /// CV 95% interval, low.
        cv_low: Vec<Option<f64>> = c.opt_f64s(col::CV_CI95_LOW)?,
        /// CV 95% interval, high.
        cv_high: Vec<Option<f64>> = c.opt_f64s(col::CV_CI95_HIGH)?,
        /// BPT mean (s).
        bpt_mean_s: Vec<Option<f64>> = c.opt_f64s(col::BPT_MEAN_S)?,
        /// BPT aperiodicity.
        bpt_aperiodicity: Vec<Option<f64>> = c.opt_f64s(col::BPT_APERIODICITY)?,
        /// BPT AIC.
        bpt_aic: Vec<Option<f64>> = c.opt_f64s(col::BPT_AIC)?,
        /// Weibull scale (s).
        weibull_scale_s: Vec<Option<f64>> = c.opt_f64s(col::WEIBULL_SCALE_S)?,
        /// Weibull shape.
        weibull_shape: Vec<Option<f64>> = c.opt_f64s(col::WEIBULL_SHAPE)?,
        /// Weibull AIC.
        weibull_aic: Vec<Option<f64>> = c.opt_f64s(col::WEIBULL_AIC)?,
        /// Exponential AIC.
        exponential_aic: Vec<Option<f64>> = c.opt_f64s(col::EXPONENTIAL_AIC)?,
        /// Why not.
        reason: Vec<Option<String>> = c.opt_strs(col::REASON)?,
    }
}

read_back! {
    /// The aftershocks table read back.
    pub struct Aftershocks from AFTERSHOCKS_TABLE, |c| {
        /// Seed (`None`: pooled).
        seed: Vec<Option<u64>> = c.opt_u64s(col::SEED)?,
        /// Bin centre (s after the main shock).
        centre_s: Vec<f64> = c.f64s(col::CENTRE_S)?,
        /// Events in the bin.
        count: Vec<u64> = c.u64s(col::COUNT)?,
        /// Rate per main shock (1/s).
        rate_per_s: Vec<f64> = c.f64s(col::RATE_PER_S)?,
        /// Its Poisson error.
        rate_error_per_s: Vec<f64> = c.f64s(col::RATE_ERROR_PER_S)?,
        /// The fit's rate.
        omori_rate_per_s: Vec<Option<f64>> = c.opt_f64s(col::OMORI_RATE_PER_S)?,
    }
}

read_back! {
    /// The Omori fits read back.
    pub struct Omori from OMORI, |c| {
        /// Seed (`None`: pooled).
        seed: Vec<Option<u64>> = c.opt_u64s(col::SEED)?,
        /// Main shocks.
        main_shocks: Vec<u64> = c.u64s(col::MAIN_SHOCKS)?,
        /// Aftershocks.
        aftershocks: Vec<u64> = c.u64s(col::AFTERSHOCKS)?,
        /// p.
        p: Vec<Option<f64>> = c.opt_f64s(col::P)?,
        /// σ_p.
        p_se: Vec<Option<f64>> = c.opt_f64s(col::P_SE)?,
        /// c (s).
        c_s: Vec<Option<f64>> = c.opt_f64s(col::C_S)?,
        /// Why not.
        reason: Vec<Option<String>> = c.opt_strs(col::REASON)?,
    }
}

read_back! {
    /// The scaling table read back.
    pub struct Scaling from SCALING, |c| {
        /// Seed (`None`: pooled).
        seed: Vec<Option<u64>> = c.opt_u64s(col::SEED)?,
        /// Relation.
        relation: Vec<String> = c.strs(col::RELATION)?,
        /// Points.
        points: Vec<Option<u64>> = c.opt_u64s(col::POINTS)?,
        /// Exponent.
        exponent: Vec<Option<f64>> = c.opt_f64s(col::EXPONENT)?,
        /// 95% interval low.
        exponent_low: Vec<Option<f64>> = c.opt_f64s(col::EXPONENT_CI95_LOW)?,
        /// 95% interval high.
        exponent_high: Vec<Option<f64>> = c.opt_f64s(col::EXPONENT_CI95_HIGH)?,
        /// Intercept (log10).
        intercept: Vec<Option<f64>> = c.opt_f64s(col::INTERCEPT)?,
        /// Self-similar exponent.
        self_similar: Vec<f64> = c.f64s(col::SELF_SIMILAR_EXPONENT)?,
        /// Why not.
        reason: Vec<Option<String>> = c.opt_strs(col::REASON)?,
    }
}
