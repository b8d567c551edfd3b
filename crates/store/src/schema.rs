//! Every table of an output folder, declared once: name, scope, sort key and columns. Writers
//! and readers use these declarations and the column constants of [`col`], never literals.

/// Column names (units in the names).
pub mod col {
    #![allow(missing_docs)]
    pub const SEED: &str = "seed";
    pub const STATUS: &str = "status";
    pub const MESSAGE: &str = "message";
    pub const STEPS: &str = "steps";
    pub const SETTLE_STEPS: &str = "settle_steps";
    pub const SETTLE_TIME_S: &str = "settle_time_s";
    pub const SETTLED_BY: &str = "settled_by";
    pub const SKIPPED_STEPS: &str = "skipped_steps";
    pub const SIMULATED_TIME_S: &str = "simulated_time_s";
    pub const WALL_TIME_S: &str = "wall_time_s";
    pub const DT_S: &str = "dt_s";
    pub const CRITICAL_DT_S: &str = "critical_dt_s";
    pub const EVENTS: &str = "events";
    pub const MAIN_SHOCKS: &str = "main_shocks";
    pub const PIPELINE_HASH: &str = "pipeline_hash";
    pub const TIME_S: &str = "time_s";
    pub const NODE: &str = "node";
    pub const COMPONENT: &str = "component";
    pub const FROM_S: &str = "from_s";
    pub const TO_S: &str = "to_s";
    pub const NEXT: &str = "next";
    pub const EVENT: &str = "event";
    pub const SUB_EVENT: &str = "sub_event";
    pub const KIND: &str = "kind";
    pub const LABEL: &str = "label";
    pub const START_S: &str = "start_s";
    pub const END_S: &str = "end_s";
    pub const DURATION_S: &str = "duration_s";
    pub const DROP_TIME_S: &str = "drop_time_s";
    pub const STRESS_DROP_PA: &str = "stress_drop_pa";
    pub const SLIP_M: &str = "slip_m";
    pub const PEAK_SLIP_RATE_M_S: &str = "peak_slip_rate_m_s";
    pub const PEAK_SLIPPING_NODES: &str = "peak_slipping_nodes";
    pub const RUPTURE_AREA_M2: &str = "rupture_area_m2";
    pub const RECURRENCE_S: &str = "recurrence_s";
    pub const SUB_EVENTS: &str = "sub_events";
    pub const LAMBDA: &str = "lambda";
    pub const MODEL_AREA_M2: &str = "model_area_m2";
    pub const PROTOTYPE_AREA_M2: &str = "prototype_area_m2";
    pub const PROTOTYPE_DURATION_S: &str = "prototype_duration_s";
    pub const PROTOTYPE_RECURRENCE_S: &str = "prototype_recurrence_s";
    pub const PROTOTYPE_RECURRENCE_YEARS: &str = "prototype_recurrence_years";
    pub const M0_PAPER_DYNE_CM: &str = "m0_paper_dyne_cm";
    pub const M0_CONSISTENT_DYNE_CM: &str = "m0_consistent_dyne_cm";
    pub const M_RIERA_PAPER_INTERPLATE: &str = "m_riera_paper_interplate";
    pub const M_RIERA_PAPER_INTRAPLATE: &str = "m_riera_paper_intraplate";
    pub const M_RIERA_CONSISTENT_INTERPLATE: &str = "m_riera_consistent_interplate";
    pub const M_RIERA_CONSISTENT_INTRAPLATE: &str = "m_riera_consistent_intraplate";
    pub const MW_PAPER: &str = "mw_paper";
    pub const MW_CONSISTENT: &str = "mw_consistent";
    pub const SCALE: &str = "scale";
    pub const DAMPING: &str = "damping";
    pub const PERIOD_S: &str = "period_s";
    pub const SD_M: &str = "sd_m";
    pub const PSV_M_S: &str = "psv_m_s";
    pub const PSA_M_S2: &str = "psa_m_s2";
    pub const FREQUENCY_HZ: &str = "frequency_hz";
    pub const AMPLITUDE_M_S: &str = "amplitude_m_s";
    pub const PGA_M_S2: &str = "pga_m_s2";
    pub const PGV_M_S: &str = "pgv_m_s";
    pub const PGD_M: &str = "pgd_m";
    pub const ARIAS_M_S: &str = "arias_m_s";
    pub const D5_95_S: &str = "d5_95_s";
    pub const T5_S: &str = "t5_s";
    pub const T95_S: &str = "t95_s";
    pub const ACCELERATION_M_S2: &str = "acceleration_m_s2";
    pub const VELOCITY_M_S: &str = "velocity_m_s";
    pub const DISPLACEMENT_M: &str = "displacement_m";
    pub const RECORD: &str = "record";
    pub const X_M: &str = "x_m";
    pub const Y_M: &str = "y_m";
    pub const Z_M: &str = "z_m";
    pub const PRE_EVENT_S: &str = "pre_event_s";
    pub const SAMPLES: &str = "samples";
    pub const FIRST_SAMPLE_S: &str = "first_sample_s";
    pub const F_LOW_HZ: &str = "f_low_hz";
    pub const F_HIGH_HZ: &str = "f_high_hz";
    pub const USABLE_LOW_HZ: &str = "usable_low_hz";
    pub const USABLE_HIGH_HZ: &str = "usable_high_hz";
    pub const IN_BAND: &str = "in_band";
    pub const SCALE_FACTOR: &str = "scale_factor";
    pub const MISFIT: &str = "misfit";
    pub const RANK: &str = "rank";
    pub const HYPOCENTRE_NODE: &str = "hypocentre_node";
    pub const HYPOCENTRE_X_M: &str = "hypocentre_x_m";
    pub const DISTANCE_M: &str = "distance_m";
    pub const HYPOCENTRE_Y_M: &str = "hypocentre_y_m";
    pub const HYPOCENTRE_REGION: &str = "hypocentre_region";
    pub const ONSET_S: &str = "onset_s";
    pub const FRONT_FROM: &str = "front_from";
    pub const SLIP_RATE_M_S: &str = "slip_rate_m_s";
    pub const SHEAR_STRESS_PA: &str = "shear_stress_pa";
    pub const NORMAL_STRESS_PA: &str = "normal_stress_pa";
    pub const RUPTURED_NODES: &str = "ruptured_nodes";
    pub const RUPTURED_AREA_M2: &str = "ruptured_area_m2";
    pub const RUPTURE_X_MIN_M: &str = "rupture_x_min_m";
    pub const RUPTURE_X_MAX_M: &str = "rupture_x_max_m";
    pub const RUPTURE_LENGTH_M: &str = "rupture_length_m";
    pub const SPREAD_S: &str = "spread_s";
    pub const RUPTURE_SPEED_M_S: &str = "rupture_speed_m_s";
    pub const FRONT_WINDOWS: &str = "front_windows";
    pub const SPEED_OVER_S: &str = "speed_over_s";
    pub const REGIME: &str = "regime";
    pub const P_SPEED_M_S: &str = "p_speed_m_s";
    pub const S_SPEED_M_S: &str = "s_speed_m_s";
    pub const RAYLEIGH_SPEED_M_S: &str = "rayleigh_speed_m_s";
    pub const ARREST_X_MIN: &str = "arrest_x_min";
    pub const ARREST_X_MAX: &str = "arrest_x_max";
    pub const ARREST: &str = "arrest";
    pub const REGION: &str = "region";
    pub const GROUP: &str = "group";
    pub const QUANTITY: &str = "quantity";
    pub const COUNT: &str = "count";
    pub const MEAN: &str = "mean";
    pub const STD: &str = "std";
    pub const CV: &str = "cv";
    pub const MIN: &str = "min";
    pub const P5: &str = "p5";
    pub const P50: &str = "p50";
    pub const P95: &str = "p95";
    pub const MAX: &str = "max";
    pub const CI95_LOW: &str = "ci95_low";
    pub const CI95_HIGH: &str = "ci95_high";
    pub const GEOMETRIC_MEAN: &str = "geometric_mean";
    pub const LOG_STD: &str = "log_std";
    pub const MEAN_M_S2: &str = "mean_m_s2";
    pub const GEOMETRIC_MEAN_M_S2: &str = "geometric_mean_m_s2";
    pub const P5_M_S2: &str = "p5_m_s2";
    pub const P50_M_S2: &str = "p50_m_s2";
    pub const P95_M_S2: &str = "p95_m_s2";
    pub const MEASURE: &str = "measure";
    pub const POINTS: &str = "points";
    pub const INTERCEPT: &str = "intercept";
    pub const SLOPE: &str = "slope";
    pub const R2: &str = "r2";
    pub const BIN_LOW: &str = "bin_low";
    pub const BIN_CENTRE: &str = "bin_centre";
    pub const BIN_HIGH: &str = "bin_high";
    pub const INCREMENTAL: &str = "incremental";
    pub const CUMULATIVE: &str = "cumulative";
    pub const FIT_CUMULATIVE: &str = "fit_cumulative";
    pub const REASON: &str = "reason";
    pub const MC_MAXC: &str = "mc_maxc";
    pub const MC_GOF: &str = "mc_gof";
    pub const GOF_PERCENT: &str = "gof_percent";
    pub const MC: &str = "mc";
    pub const EVENTS_ABOVE_MC: &str = "events_above_mc";
    pub const B: &str = "b";
    pub const B_SIGMA: &str = "b_sigma";
    pub const B_BINNED: &str = "b_binned";
    pub const A_VALUE: &str = "a";
    pub const SEQUENCE: &str = "sequence";
    pub const INTERVALS: &str = "intervals";
    pub const MEAN_S: &str = "mean_s";
    pub const STD_S: &str = "std_s";
    pub const MEAN_CI95_LOW_S: &str = "mean_ci95_low_s";
    pub const MEAN_CI95_HIGH_S: &str = "mean_ci95_high_s";
    pub const CV_CI95_LOW: &str = "cv_ci95_low";
    pub const CV_CI95_HIGH: &str = "cv_ci95_high";
    pub const BPT_MEAN_S: &str = "bpt_mean_s";
    pub const BPT_APERIODICITY: &str = "bpt_aperiodicity";
    pub const BPT_AIC: &str = "bpt_aic";
    pub const WEIBULL_SCALE_S: &str = "weibull_scale_s";
    pub const WEIBULL_SHAPE: &str = "weibull_shape";
    pub const WEIBULL_AIC: &str = "weibull_aic";
    pub const EXPONENTIAL_AIC: &str = "exponential_aic";
    pub const CENTRE_S: &str = "centre_s";
    pub const EXPOSURE_S: &str = "exposure_s";
    pub const RATE_PER_S: &str = "rate_per_s";
    pub const RATE_ERROR_PER_S: &str = "rate_error_per_s";
    pub const OMORI_RATE_PER_S: &str = "omori_rate_per_s";
    pub const AFTERSHOCKS: &str = "aftershocks";
    pub const K: &str = "k";
    pub const C_S: &str = "c_s";
    pub const P: &str = "p";
    pub const K_SE: &str = "k_se";
    pub const C_SE_S: &str = "c_se_s";
    pub const P_SE: &str = "p_se";
    pub const FIT_START_S: &str = "fit_start_s";
    pub const FIT_END_S: &str = "fit_end_s";
    pub const RELATION: &str = "relation";
    pub const EXPONENT: &str = "exponent";
    pub const EXPONENT_SE: &str = "exponent_se";
    pub const EXPONENT_CI95_LOW: &str = "exponent_ci95_low";
    pub const EXPONENT_CI95_HIGH: &str = "exponent_ci95_high";
    pub const RESIDUAL_STD: &str = "residual_std";
    pub const SELF_SIMILAR_EXPONENT: &str = "self_similar_exponent";
    pub const BAR: &str = "bar";
    pub const FAMILY: &str = "family";
    pub const DIRECTION: &str = "direction";
    pub const STRAIN: &str = "strain";
    pub const ENERGY_J: &str = "energy_j";
    pub const CLUSTER: &str = "cluster";
    pub const BREAKS: &str = "breaks";
    pub const CENTROID_X_M: &str = "centroid_x_m";
    pub const CENTROID_Y_M: &str = "centroid_y_m";
    pub const CENTROID_Z_M: &str = "centroid_z_m";
    pub const MAGNITUDE: &str = "magnitude";
}

use col::*;

/// Where a table lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scope {
    /// One part per seed only (`tables/<name>/seed-N.parquet`).
    PerSeed,
    /// One part per seed, gathered over the seeds into `tables/<name>.parquet`.
    Gathered,
    /// Computed across seeds, one file `tables/<name>.parquet`.
    AcrossSeeds,
}

/// A table of the output folder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableSpec {
    /// Name (file or folder name under `tables/`).
    pub name: &'static str,
    /// Where it lives.
    pub scope: Scope,
    /// Sort key of the gathered table.
    pub key: &'static [&'static str],
    /// Columns always written, in order.
    pub columns: &'static [&'static str],
    /// Columns that depend on the pipeline (what is recorded), if any, described.
    pub variable: Option<&'static str>,
}

const BURST: [&str; 9] = [
    START_S,
    END_S,
    DURATION_S,
    DROP_TIME_S,
    STRESS_DROP_PA,
    SLIP_M,
    PEAK_SLIP_RATE_M_S,
    PEAK_SLIPPING_NODES,
    RUPTURE_AREA_M2,
];

/// One row per seed: status, steps, times, Δt, events.
pub const RUNS: TableSpec = TableSpec {
    name: "runs",
    scope: Scope::Gathered,
    key: &[SEED],
    columns: &[
        SEED,
        STATUS,
        MESSAGE,
        STEPS,
        SETTLE_STEPS,
        SETTLE_TIME_S,
        SETTLED_BY,
        SKIPPED_STEPS,
        SIMULATED_TIME_S,
        WALL_TIME_S,
        DT_S,
        CRITICAL_DT_S,
        EVENTS,
        MAIN_SHOCKS,
        PIPELINE_HASH,
    ],
    variable: None,
};

/// One row per recorded instant.
pub const SERIES: TableSpec = TableSpec {
    name: "series",
    scope: Scope::PerSeed,
    key: &[SEED, TIME_S],
    columns: &[SEED, TIME_S],
    variable: Some("one column per recorded channel (record.interface, record.energy)"),
};

/// One row per control node, component and instant.
pub const CONTROL: TableSpec = TableSpec {
    name: "control",
    scope: Scope::PerSeed,
    key: &[SEED, NODE, COMPONENT, TIME_S],
    columns: &[SEED, NODE, COMPONENT, TIME_S, "displacement_m", "velocity_m_s", ACCELERATION_M_S2],
    variable: None,
};

/// Every contact node of the base through the shear stage at the event trace's instants
/// (`record.fault`): one row per node and instant.
pub const FAULT: TableSpec = TableSpec {
    name: "fault",
    scope: Scope::PerSeed,
    key: &[SEED, NODE, TIME_S],
    columns: &[SEED, NODE, X_M, Y_M, TIME_S, SLIP_M, SLIP_RATE_M_S, SHEAR_STRESS_PA, NORMAL_STRESS_PA],
    variable: None,
};

/// One row per quasi-static jump of the skip-ahead.
pub const SKIPS: TableSpec = TableSpec {
    name: "skips",
    scope: Scope::PerSeed,
    key: &[SEED, FROM_S],
    columns: &[SEED, FROM_S, TO_S, STEPS, NEXT, NODE],
    variable: None,
};

/// Stick-slip events.
pub const EVENTS_TABLE: TableSpec = TableSpec {
    name: "events",
    scope: Scope::Gathered,
    key: &[SEED, EVENT],
    columns: &[
        SEED,
        EVENT,
        KIND,
        LABEL,
        BURST[0],
        BURST[1],
        BURST[2],
        BURST[3],
        BURST[4],
        BURST[5],
        BURST[6],
        BURST[7],
        BURST[8],
        RECURRENCE_S,
        SUB_EVENTS,
    ],
    variable: Some(
        "one peak_abs_accel_n<LDEM>_<component>_m_s2 per recorded control acceleration, after rupture_area_m2",
    ),
};

/// The bursts of slip each event is made of.
pub const SUB_EVENTS_TABLE: TableSpec = TableSpec {
    name: "sub_events",
    scope: Scope::Gathered,
    key: &[SEED, EVENT, SUB_EVENT],
    columns: &[
        SEED, EVENT, SUB_EVENT, BURST[0], BURST[1], BURST[2], BURST[3], BURST[4], BURST[5], BURST[6], BURST[7],
        BURST[8],
    ],
    variable: Some("one peak_abs_accel_n<LDEM>_<component>_m_s2 per recorded control acceleration"),
};

/// Every event at prototype scale.
pub const SIMILARITY: TableSpec = TableSpec {
    name: "similarity",
    scope: Scope::Gathered,
    key: &[SEED, EVENT],
    columns: &[
        SEED,
        EVENT,
        KIND,
        LABEL,
        LAMBDA,
        STRESS_DROP_PA,
        MODEL_AREA_M2,
        PROTOTYPE_AREA_M2,
        PROTOTYPE_DURATION_S,
        PROTOTYPE_RECURRENCE_S,
        PROTOTYPE_RECURRENCE_YEARS,
        M0_PAPER_DYNE_CM,
        M0_CONSISTENT_DYNE_CM,
        M_RIERA_PAPER_INTERPLATE,
        M_RIERA_PAPER_INTRAPLATE,
        M_RIERA_CONSISTENT_INTERPLATE,
        M_RIERA_CONSISTENT_INTRAPLATE,
        MW_PAPER,
        MW_CONSISTENT,
    ],
    variable: None,
};

/// One row per record and scale: what it is (event, node, component), where it was cut from the
/// run, its sampling, filter corners and usable band (docs/model.md §8).
pub const RECORDS: TableSpec = TableSpec {
    name: "records",
    scope: Scope::Gathered,
    key: &[SEED, RECORD, SCALE],
    columns: &[
        SEED,
        RECORD,
        EVENT,
        LABEL,
        NODE,
        COMPONENT,
        SCALE,
        X_M,
        Y_M,
        Z_M,
        START_S,
        PRE_EVENT_S,
        DT_S,
        SAMPLES,
        FIRST_SAMPLE_S,
        F_LOW_HZ,
        F_HIGH_HZ,
        USABLE_LOW_HZ,
        USABLE_HIGH_HZ,
    ],
    variable: None,
};

/// The processed records (acceleration, velocity, displacement), both scales.
pub const ACCELEROGRAMS: TableSpec = TableSpec {
    name: "accelerograms",
    scope: Scope::PerSeed,
    key: &[SEED, RECORD, SCALE, TIME_S],
    columns: &[SEED, RECORD, SCALE, TIME_S, ACCELERATION_M_S2, VELOCITY_M_S, DISPLACEMENT_M],
    variable: None,
};

/// Response spectra of every record, both scales, with whether each period is in its band.
pub const SPECTRA: TableSpec = TableSpec {
    name: "spectra",
    scope: Scope::PerSeed,
    key: &[SEED, RECORD, SCALE, DAMPING, PERIOD_S],
    columns: &[SEED, RECORD, NODE, COMPONENT, SCALE, DAMPING, PERIOD_S, SD_M, PSV_M_S, PSA_M_S2, IN_BAND],
    variable: None,
};

/// RotD50 and RotD100 (`component`) of the two horizontal records of a node, both scales.
pub const ROTD: TableSpec = TableSpec {
    name: "rotd",
    scope: Scope::PerSeed,
    key: &[SEED, RECORD, COMPONENT, SCALE, DAMPING, PERIOD_S],
    columns: &[SEED, RECORD, NODE, COMPONENT, SCALE, DAMPING, PERIOD_S, SD_M, PSV_M_S, PSA_M_S2, IN_BAND],
    variable: None,
};

/// Fourier amplitude spectra of the processed records (model scale).
pub const FOURIER: TableSpec = TableSpec {
    name: "fourier",
    scope: Scope::PerSeed,
    key: &[SEED, RECORD, FREQUENCY_HZ],
    columns: &[SEED, RECORD, FREQUENCY_HZ, AMPLITUDE_M_S],
    variable: None,
};

/// Intensity measures of every processed record, both scales.
pub const INTENSITY: TableSpec = TableSpec {
    name: "intensity",
    scope: Scope::Gathered,
    key: &[SEED, RECORD, SCALE],
    columns: &[
        SEED, RECORD, EVENT, LABEL, NODE, COMPONENT, SCALE, PGA_M_S2, PGV_M_S, PGD_M, ARIAS_M_S, D5_95_S, T5_S, T95_S,
    ],
    variable: None,
};

/// Peak motions of every control node in every main shock, with the distance from its
/// hypocentre.
pub const ATTENUATION: TableSpec = TableSpec {
    name: "attenuation",
    scope: Scope::Gathered,
    key: &[SEED, EVENT, NODE],
    columns: &[SEED, EVENT, LABEL, HYPOCENTRE_NODE, HYPOCENTRE_X_M, NODE, DISTANCE_M, PGA_M_S2, PGV_M_S],
    variable: None,
};

/// How each event started and spread over the base (scenes with `record.slip_onsets`,
/// docs/model.md §13): hypocentre, ruptured area and extent, rupture speed against the lattice's
/// wave speeds, arrest at each end along x.
pub const RUPTURES: TableSpec = TableSpec {
    name: "ruptures",
    scope: Scope::Gathered,
    key: &[SEED, EVENT],
    columns: &[
        SEED,
        EVENT,
        KIND,
        LABEL,
        HYPOCENTRE_NODE,
        HYPOCENTRE_X_M,
        HYPOCENTRE_Y_M,
        HYPOCENTRE_REGION,
        FRONT_FROM,
        ONSET_S,
        RUPTURED_NODES,
        RUPTURED_AREA_M2,
        RUPTURE_X_MIN_M,
        RUPTURE_X_MAX_M,
        RUPTURE_LENGTH_M,
        SPREAD_S,
        RUPTURE_SPEED_M_S,
        FRONT_WINDOWS,
        SPEED_OVER_S,
        REGIME,
        P_SPEED_M_S,
        S_SPEED_M_S,
        RAYLEIGH_SPEED_M_S,
        ARREST_X_MIN,
        ARREST_X_MAX,
        ARREST,
    ],
    variable: None,
};

/// The onset of every ruptured contact node in every event (scenes with `record.slip_onsets`).
pub const RUPTURE_ONSETS: TableSpec = TableSpec {
    name: "rupture_onsets",
    scope: Scope::Gathered,
    key: &[SEED, EVENT, NODE],
    columns: &[SEED, EVENT, NODE, X_M, Y_M, REGION, ONSET_S, DISTANCE_M],
    variable: None,
};

/// Every bar that started softening or broke (scenes with `[rupture]`, docs/model.md §11).
pub const CRACKS: TableSpec = TableSpec {
    name: "cracks",
    scope: Scope::Gathered,
    key: &[SEED, TIME_S, BAR, KIND],
    columns: &[SEED, TIME_S, KIND, BAR, FAMILY, DIRECTION, X_M, Y_M, Z_M, STRAIN, ENERGY_J],
    variable: None,
};

/// Bar breaks grouped into acoustic-emission events, with their magnitudes (docs/model.md §11).
pub const ACOUSTIC_EMISSION: TableSpec = TableSpec {
    name: "acoustic_emission",
    scope: Scope::Gathered,
    key: &[SEED, CLUSTER],
    columns: &[
        SEED,
        CLUSTER,
        START_S,
        END_S,
        DURATION_S,
        BREAKS,
        X_M,
        Y_M,
        Z_M,
        CENTROID_X_M,
        CENTROID_Y_M,
        CENTROID_Z_M,
        ENERGY_J,
        MAGNITUDE,
    ],
    variable: None,
};

/// Statistics across seeds of the events and similarity tables.
pub const SUMMARY: TableSpec = TableSpec {
    name: "summary",
    scope: Scope::AcrossSeeds,
    key: &[GROUP, QUANTITY],
    columns: &[
        GROUP,
        QUANTITY,
        COUNT,
        MEAN,
        STD,
        CV,
        MIN,
        P5,
        P50,
        P95,
        MAX,
        CI95_LOW,
        CI95_HIGH,
        GEOMETRIC_MEAN,
        LOG_STD,
    ],
    variable: None,
};

/// PSA across seeds.
pub const PSA_STATS: TableSpec = TableSpec {
    name: "psa_stats",
    scope: Scope::AcrossSeeds,
    key: &[SCALE, NODE, COMPONENT, DAMPING, PERIOD_S],
    columns: &[
        SCALE,
        NODE,
        COMPONENT,
        DAMPING,
        PERIOD_S,
        COUNT,
        MEAN_M_S2,
        GEOMETRIC_MEAN_M_S2,
        P5_M_S2,
        P50_M_S2,
        P95_M_S2,
        IN_BAND,
    ],
    variable: None,
};

/// A set of records matched to a design spectrum (prototype scale), in the order chosen.
pub const SET: TableSpec = TableSpec {
    name: "set",
    scope: Scope::AcrossSeeds,
    key: &[RANK],
    columns: &[RANK, SEED, RECORD, LABEL, NODE, COMPONENT, SCALE_FACTOR, MISFIT, USABLE_LOW_HZ, USABLE_HIGH_HZ],
    variable: None,
};

/// Log-log fits of peak motions against distance.
pub const ATTENUATION_FIT: TableSpec = TableSpec {
    name: "attenuation_fit",
    scope: Scope::AcrossSeeds,
    key: &[GROUP, MEASURE],
    columns: &[GROUP, MEASURE, POINTS, INTERCEPT, SLOPE, R2],
    variable: None,
};

/// Magnitude–frequency distributions (magnitudes in bins of 0.1; moment and stress drop in
/// logarithmic bins), per seed and pooled (`seed` null), with the Gutenberg–Richter fit's
/// expected cumulative count above its Mc.
pub const MAGNITUDE_FREQUENCY: TableSpec = TableSpec {
    name: "magnitude_frequency",
    scope: Scope::AcrossSeeds,
    key: &[SEED, QUANTITY, BIN_CENTRE],
    columns: &[SEED, QUANTITY, BIN_LOW, BIN_CENTRE, BIN_HIGH, INCREMENTAL, CUMULATIVE, FIT_CUMULATIVE],
    variable: None,
};

/// Gutenberg–Richter fits: completeness magnitude (maximum curvature + 0.2, goodness of fit 90%)
/// and b-value (Aki–Utsu, Shi–Bolt σ), or the reason none could be made.
pub const B_VALUES: TableSpec = TableSpec {
    name: "b_values",
    scope: Scope::AcrossSeeds,
    key: &[SEED, QUANTITY],
    columns: &[
        SEED,
        QUANTITY,
        EVENTS,
        MC_MAXC,
        MC_GOF,
        GOF_PERCENT,
        MC,
        EVENTS_ABOVE_MC,
        B,
        B_SIGMA,
        B_BINNED,
        A_VALUE,
        REASON,
    ],
    variable: None,
};

/// Recurrence statistics of main shocks and of all events (model-scale seconds): mean, CV and
/// the BPT, Weibull and exponential renewal fits, or the reason none could be made.
pub const RECURRENCE_STATS: TableSpec = TableSpec {
    name: "recurrence_stats",
    scope: Scope::AcrossSeeds,
    key: &[SEED, SEQUENCE],
    columns: &[
        SEED,
        SEQUENCE,
        INTERVALS,
        MEAN_S,
        STD_S,
        CV,
        MEAN_CI95_LOW_S,
        MEAN_CI95_HIGH_S,
        CV_CI95_LOW,
        CV_CI95_HIGH,
        BPT_MEAN_S,
        BPT_APERIODICITY,
        BPT_AIC,
        WEIBULL_SCALE_S,
        WEIBULL_SHAPE,
        WEIBULL_AIC,
        EXPONENTIAL_AIC,
        REASON,
    ],
    variable: None,
};

/// Aftershock rate per main shock against time since it, stacked over main shocks (per seed and
/// pooled), with the Omori–Utsu fit's rate where one could be made.
pub const AFTERSHOCKS_TABLE: TableSpec = TableSpec {
    name: "aftershocks",
    scope: Scope::AcrossSeeds,
    key: &[SEED, START_S],
    columns: &[SEED, START_S, END_S, CENTRE_S, COUNT, EXPOSURE_S, RATE_PER_S, RATE_ERROR_PER_S, OMORI_RATE_PER_S],
    variable: None,
};

/// Omori–Utsu fits `K/(t + c)^p` of the stacked aftershocks, or the reason none could be made.
pub const OMORI: TableSpec = TableSpec {
    name: "omori",
    scope: Scope::AcrossSeeds,
    key: &[SEED],
    columns: &[SEED, MAIN_SHOCKS, AFTERSHOCKS, K, C_S, P, K_SE, C_SE_S, P_SE, FIT_START_S, FIT_END_S, REASON],
    variable: None,
};

/// Scaling relations (moment–area, moment–duration, stress drop–magnitude): fitted exponent with
/// its 95% interval beside the self-similar one, or the reason none could be made.
pub const SCALING: TableSpec = TableSpec {
    name: "scaling",
    scope: Scope::AcrossSeeds,
    key: &[SEED, RELATION],
    columns: &[
        SEED,
        RELATION,
        POINTS,
        EXPONENT,
        EXPONENT_SE,
        EXPONENT_CI95_LOW,
        EXPONENT_CI95_HIGH,
        INTERCEPT,
        R2,
        RESIDUAL_STD,
        SELF_SIMILAR_EXPONENT,
        REASON,
    ],
    variable: None,
};

/// The catalogue tables, written together by the gathering step.
pub const CATALOGUE: [TableSpec; 6] =
    [MAGNITUDE_FREQUENCY, B_VALUES, RECURRENCE_STATS, AFTERSHOCKS_TABLE, OMORI, SCALING];

/// Every table, in the order the README documents them.
pub const ALL: [TableSpec; 29] = [
    RUNS,
    SERIES,
    CONTROL,
    FAULT,
    SKIPS,
    EVENTS_TABLE,
    SUB_EVENTS_TABLE,
    SIMILARITY,
    RECORDS,
    ACCELEROGRAMS,
    SPECTRA,
    ROTD,
    FOURIER,
    INTENSITY,
    ATTENUATION,
    RUPTURES,
    RUPTURE_ONSETS,
    CRACKS,
    ACOUSTIC_EMISSION,
    SUMMARY,
    PSA_STATS,
    ATTENUATION_FIT,
    SET,
    MAGNITUDE_FREQUENCY,
    B_VALUES,
    RECURRENCE_STATS,
    AFTERSHOCKS_TABLE,
    OMORI,
    SCALING,
];

/// Per-seed tables in the order a seed's parts are written: `runs` last, so a seed counts as
/// finished when its `runs` part exists.
pub fn seed_tables() -> impl Iterator<Item = TableSpec> {
    ALL.into_iter().filter(|t| t.scope != Scope::AcrossSeeds && *t != RUNS).chain([RUNS])
}

/// Tables gathered over the seeds into one file each, in the order they are gathered.
pub fn gathered() -> impl Iterator<Item = TableSpec> {
    ALL.into_iter().filter(|t| t.scope == Scope::Gathered)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn registry_is_consistent() {
        let mut names: Vec<&str> = ALL.iter().map(|t| t.name).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), ALL.len(), "table names are unique");
        for t in ALL {
            for k in t.key {
                assert!(t.columns.contains(k) || t.variable.is_some(), "{}: key {k} is a column", t.name);
            }
            let per_seed = t.scope != Scope::AcrossSeeds;
            assert_eq!(
                per_seed,
                seed_tables().any(|s| s == t),
                "{} is a per-seed table exactly when it has parts",
                t.name
            );
            assert_eq!(
                t.scope == Scope::Gathered,
                gathered().any(|s| s == t),
                "{} is gathered exactly when so declared",
                t.name
            );
            if per_seed {
                assert_eq!(t.columns[0], SEED, "{}: per-seed tables start with seed", t.name);
            }
        }
        assert_eq!(seed_tables().last(), Some(RUNS), "runs is written last");
    }
}
