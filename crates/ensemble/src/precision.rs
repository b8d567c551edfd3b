//! Ensembles that stop when precise enough (`[seeds.target]`, see `stickslip_config::precision`):
//! the pipeline's seeds are run `batch` at a time, in their order, and the ensemble is gathered
//! after each batch until the target's confidence interval is narrow enough or the seeds run out.
//! Finished seeds are kept, so an interrupted run resumes where it stopped and reaches the same
//! decision.

use std::sync::atomic::AtomicBool;

use stickslip_config::Pipeline;
use stickslip_config::precision::PrecisionTarget;
use stickslip_store::io::read_parquet_if_present;
use stickslip_store::schema::SUMMARY;
use stickslip_store::tables::stats::SummaryTable;
use stickslip_store::{Folder, StoreError};

use crate::error::EnsembleError;
use crate::run::{EnsembleOptions, EnsembleReport, run_ensemble};

/// Where the statistic stood when the run stopped.
#[derive(Clone, Debug, PartialEq)]
pub struct PrecisionOutcome {
    /// The target.
    pub target: PrecisionTarget,
    /// Whether it was met.
    pub met: bool,
    /// Seeds used (a prefix of the pipeline's seeds).
    pub seeds_used: usize,
    /// Seeds available (the budget).
    pub budget: usize,
    /// Events of the group in the statistic.
    pub count: usize,
    /// Mean of the quantity over them, if any.
    pub mean: Option<f64>,
    /// Half-width of its 95% confidence interval, if defined (two events or more).
    pub half_width: Option<f64>,
}

impl PrecisionOutcome {
    /// One line for a terminal or a page.
    pub fn describe(&self) -> String {
        let stat = match (self.mean, self.half_width) {
            (Some(m), Some(h)) => {
                // One digit past the half-width's first: 6068.4 ± 110.1, not 6068.411321 ± 1.101e2.
                let digits = if h > 0.0 { (2 - h.log10().floor() as i32).clamp(0, 12) as usize } else { 6 };
                format!("mean {m:.digits$} ± {h:.digits$} (95% CI half-width {:.2}% of the mean)", 100.0 * h / m.abs())
            }
            (Some(m), None) => format!("mean {m:.6}, no interval yet (fewer than two events)"),
            _ => "no event of the group yet".into(),
        };
        let verdict = if self.met {
            format!("met after {} of {} seeds", self.seeds_used, self.budget)
        } else {
            format!("NOT met: all {} seeds of the budget used; add seeds or relax the target", self.budget)
        };
        format!(
            "precision target ({}): {verdict}; {} {} over {} event{}: {stat}",
            self.target.describe(),
            self.target.group,
            self.target.quantity,
            self.count,
            if self.count == 1 { "" } else { "s" }
        )
    }
}

/// The statistic of `target` in the gathered summary of `out`.
fn statistic(out: &Folder, target: &PrecisionTarget) -> Result<(usize, Option<f64>, Option<f64>), StoreError> {
    let Some(df) = read_parquet_if_present(&out.gathered(&SUMMARY))? else { return Ok((0, None, None)) };
    let s = SummaryTable::read(&df)?;
    let Some(i) = s.find(&target.group, &target.quantity) else { return Ok((0, None, None)) };
    let half = (s.ci95_high[i] - s.ci95_low[i]) / 2.0;
    Ok((s.count[i] as usize, Some(s.mean[i]).filter(|m| m.is_finite()), Some(half).filter(|h| h.is_finite())))
}

/// Runs `pipeline`'s seeds in batches until `target` is met or they are all used, gathering after
/// each batch. `options.seeds` must be the pipeline's seeds (the budget, in order); `on_seed` and
/// `cancel` are passed to each batch's [`run_ensemble`]. Returns the last batch's report, with the
/// seeds counted over all batches, and where the statistic stood.
pub fn run_to_precision(
    pipeline: &Pipeline,
    target: &PrecisionTarget,
    options: &EnsembleOptions,
    on_seed: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Result<(EnsembleReport, PrecisionOutcome), EnsembleError> {
    let start = std::time::Instant::now();
    let budget = options.seeds.len();
    let out = Folder::new(&options.out);
    let mut used = 0;
    let (mut ran, mut skipped) = (0, 0);
    loop {
        used = (used + target.batch).min(budget);
        let batch = EnsembleOptions {
            checkpoint_every_s: None,
            seeds: options.seeds[..used].to_vec(),
            fresh: options.fresh && ran + skipped == 0,
            finish: true,
            ..options.clone()
        };
        let mut report = run_ensemble(pipeline, &batch, on_seed, cancel)?;
        ran += report.ran;
        skipped = used - ran;
        let (count, mean, half_width) = statistic(&out, target)?;
        let met = matches!((mean, half_width), (Some(m), Some(h)) if target.met(m, h));
        if met || used == budget {
            report.ran = ran;
            report.skipped = skipped;
            report.wall_time_s = start.elapsed().as_secs_f64();
            let outcome =
                PrecisionOutcome { target: target.clone(), met, seeds_used: used, budget, count, mean, half_width };
            return Ok((report, outcome));
        }
    }
}
