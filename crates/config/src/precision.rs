//! `[seeds.target]`: run an ensemble in batches until a statistic is precise enough.
//!
//! The seeds of `[seeds]` are the budget, used in their order, `batch` at a time. After each batch
//! the ensemble is gathered and the 95% confidence interval of the mean of `quantity` over the
//! events of `group` (Student's t, the `ci95_low`/`ci95_high` of `summary.parquet`) is compared
//! with the target: its half-width at most `relative` × |mean|, or at most `absolute` (in the
//! quantity's unit). The run stops at the first batch that meets it, or when the budget is spent.
//! Which seeds are used depends only on the pipeline (the seeds' order, the batch size and each
//! seed's results, which do not depend on the thread count), never on timing.
//!
//! ```toml
//! [seeds]
//! range = { first = 1, count = 1000 }   # the budget
//! [seeds.target]
//! quantity = "stress_drop_pa"           # a column of the events or similarity table
//! group = "S2"                          # S1, S2, … (main shocks of that rank), "main" or "all"
//! relative = 0.02                       # 95% CI half-width ≤ 2% of the mean
//! batch = 16
//! ```

use serde::{Deserialize, Serialize};

use crate::check::Checker;

/// The quantities a target may name: the columns `summary.parquet` summarises per event group
/// (events table, then similarity table). A test of the ensemble crate checks that each is
/// summarised.
pub const TARGET_QUANTITIES: [&str; 17] = [
    "start_s",
    "duration_s",
    "drop_time_s",
    "stress_drop_pa",
    "slip_m",
    "peak_slip_rate_m_s",
    "peak_slipping_nodes",
    "rupture_area_m2",
    "recurrence_s",
    "prototype_duration_s",
    "prototype_recurrence_years",
    "m0_paper_dyne_cm",
    "m0_consistent_dyne_cm",
    "m_riera_paper_interplate",
    "m_riera_consistent_interplate",
    "mw_paper",
    "mw_consistent",
];

/// `[seeds.target]` as written.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TargetSection {
    /// The quantity (see [`TARGET_QUANTITIES`]).
    pub quantity: String,
    /// `S1`, `S2`, … (main shocks of that rank over the seeds), `main` (all main shocks) or `all`
    /// (every event). Default `main`.
    #[serde(default = "default_group")]
    pub group: String,
    /// Largest 95% CI half-width as a fraction of |mean| (e.g. 0.02).
    pub relative: Option<f64>,
    /// Largest 95% CI half-width in the quantity's unit.
    pub absolute: Option<f64>,
    /// Seeds per batch. Default 16.
    #[serde(default = "default_batch")]
    pub batch: i64,
}

fn default_group() -> String {
    "main".into()
}

fn default_batch() -> i64 {
    16
}

/// How precise the statistic must be.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Precision {
    /// Half-width ≤ this fraction of |mean|.
    Relative(f64),
    /// Half-width ≤ this value (the quantity's unit).
    Absolute(f64),
}

/// A validated `[seeds.target]`.
#[derive(Clone, Debug, PartialEq)]
pub struct PrecisionTarget {
    /// Quantity.
    pub quantity: String,
    /// Event group.
    pub group: String,
    /// The precision asked.
    pub precision: Precision,
    /// Seeds per batch.
    pub batch: usize,
}

impl PrecisionTarget {
    /// Whether an interval of half-width `half` around `mean` meets the target.
    pub fn met(&self, mean: f64, half: f64) -> bool {
        match self.precision {
            Precision::Relative(r) => half <= r * mean.abs(),
            Precision::Absolute(a) => half <= a,
        }
    }

    /// "the 95% CI half-width of the mean S2 stress_drop_pa ≤ 2% of the mean".
    pub fn describe(&self) -> String {
        let what = match self.precision {
            Precision::Relative(r) => format!("≤ {}% of the mean", crate::check::num(100.0 * r)),
            Precision::Absolute(a) => format!("≤ {}", crate::check::num(a)),
        };
        format!("the 95% CI half-width of the mean {} {} {what}", self.group, self.quantity)
    }
}

impl TargetSection {
    /// The validated target; `budget` is the number of seeds of the pipeline.
    pub fn build(&self, budget: usize, ck: &mut Checker) -> Option<PrecisionTarget> {
        let mut ok = true;
        if !TARGET_QUANTITIES.contains(&self.quantity.as_str()) {
            ck.push("seeds.target.quantity", &self.quantity, format!("one of {}", TARGET_QUANTITIES.join(", ")));
            ok = false;
        }
        let rank_ok = self.group.strip_prefix('S').is_some_and(|r| r.parse::<u32>().is_ok_and(|r| r >= 1));
        if !(rank_ok || self.group == "main" || self.group == "all") {
            ck.push("seeds.target.group", &self.group, "S1, S2, … (main shocks of that rank), \"main\" or \"all\"");
            ok = false;
        }
        let precision = match (self.relative, self.absolute) {
            (Some(r), None) => ck.positive("seeds.target.relative", r).then_some(Precision::Relative(r)),
            (None, Some(a)) => ck.positive("seeds.target.absolute", a).then_some(Precision::Absolute(a)),
            _ => {
                ck.push("seeds.target", "(relative and absolute)", "exactly one of relative, absolute");
                None
            }
        };
        let batch = ck.count("seeds.target.batch", self.batch, 2, 1_000_000, "");
        if let Some(b) = batch
            && budget < b
        {
            ck.push(
                "seeds.target.batch",
                b,
                format!("at most the pipeline's {budget} seeds (the budget), which must hold one batch"),
            );
            ok = false;
        }
        Some(PrecisionTarget {
            quantity: self.quantity.clone(),
            group: self.group.clone(),
            precision: precision?,
            batch: batch?,
        })
        .filter(|_| ok)
    }
}
