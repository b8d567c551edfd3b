//! The runs table: one row per seed.

use polars::prelude::DataFrame;
use stickslip_analysis::{Diagnosis, SlipRegime};
use stickslip_seismo::events::Catalogue;
use stickslip_solver::RunOutput;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Frame, read_back};
use crate::spec::{Scope, TableSpec};

/// One row per seed: status, steps, times, Δt, events.
pub const RUNS: TableSpec = TableSpec {
    name: "runs",
    scope: Scope::Gathered,
    key: &[col::SEED],
    columns: &[
        col::SEED,
        col::STATUS,
        col::MESSAGE,
        col::STEPS,
        col::SETTLE_STEPS,
        col::SETTLE_TIME_S,
        col::SETTLED_BY,
        col::SKIPPED_STEPS,
        col::SIMULATED_TIME_S,
        col::WALL_TIME_S,
        col::DT_S,
        col::CRITICAL_DT_S,
        col::EVENTS,
        col::MAIN_SHOCKS,
        col::SLIP_REGIME,
        col::SLIDING_FROM_S,
        col::PIPELINE_HASH,
    ],
    variable: None,
};

/// Whether a seed ran to the end.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RunStatus {
    /// Finished.
    Ok,
    /// Stopped with an error (its message in the row).
    Failed,
}

impl RunStatus {
    /// `"ok"` or `"failed"`.
    pub fn name(self) -> &'static str {
        match self {
            RunStatus::Ok => "ok",
            RunStatus::Failed => "failed",
        }
    }

    /// The status written as `name`.
    pub fn parse(name: &str) -> Option<RunStatus> {
        [RunStatus::Ok, RunStatus::Failed].into_iter().find(|s| s.name() == name)
    }
}

/// One row of the runs table.
#[derive(Clone, Debug, PartialEq)]
pub struct RunRow {
    /// Seed.
    pub seed: u64,
    /// `Ok(output summary)` or the error message.
    pub outcome: Result<RunFacts, String>,
    /// Wall time of the seed (s).
    pub wall_time_s: f64,
}

/// What a successful run reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunFacts {
    /// All steps.
    pub steps: u64,
    /// Self-weight steps.
    pub settle_steps: u64,
    /// Self-weight duration (s).
    pub settle_time_s: f64,
    /// `"dynamic"` or `"static"`.
    pub settled_by: &'static str,
    /// Shear steps skipped by the quasi-static skip-ahead.
    pub skipped_steps: u64,
    /// Shear-stage duration simulated (s).
    pub simulated_time_s: f64,
    /// Δt (s).
    pub dt_s: f64,
    /// Critical Δt (s).
    pub critical_dt_s: f64,
    /// Events found.
    pub events: u32,
    /// Main shocks found.
    pub main_shocks: u32,
    /// What the base did (stick-slip, stable sliding, no slip).
    pub regime: SlipRegime,
    /// Start of the slip episode that never stopped, if the run ended in one (s).
    pub sliding_from_s: Option<f64>,
}

impl RunFacts {
    /// Facts of a finished run, its catalogue and what the base did.
    pub fn of(out: &RunOutput, cat: &Catalogue, diagnosis: &Diagnosis) -> Self {
        RunFacts {
            steps: out.steps(),
            settle_steps: out.settle_steps,
            settle_time_s: out.settle_time_s,
            settled_by: out.settled_by.name(),
            skipped_steps: out.skip.skipped_steps,
            simulated_time_s: out.recording.time_s.last().copied().unwrap_or(0.0),
            dt_s: out.dt_s,
            critical_dt_s: out.critical.dt_s,
            events: cat.events.len() as u32,
            main_shocks: cat.main_shocks().count() as u32,
            regime: diagnosis.regime,
            sliding_from_s: diagnosis.sliding_from_s,
        }
    }
}

/// The runs table of some rows.
pub fn frame(rows: &[RunRow], pipeline_hash: &str) -> Result<DataFrame, StoreError> {
    let n = rows.len();
    let fact = |g: &dyn Fn(&RunFacts) -> f64| -> Vec<f64> {
        rows.iter().map(|r| r.outcome.as_ref().map_or(f64::NAN, g)).collect()
    };
    let count =
        |g: &dyn Fn(&RunFacts) -> u64| -> Vec<u64> { rows.iter().map(|r| r.outcome.as_ref().map_or(0, g)).collect() };
    let status = |r: &RunRow| if r.outcome.is_ok() { RunStatus::Ok } else { RunStatus::Failed };
    Frame::new(n)
        .u64(col::SEED, rows.iter().map(|r| r.seed).collect())
        .static_str(col::STATUS, rows.iter().map(|r| status(r).name()).collect())
        .str(col::MESSAGE, rows.iter().map(|r| r.outcome.as_ref().err().cloned().unwrap_or_default()).collect())
        .u64(col::STEPS, count(&|f| f.steps))
        .u64(col::SETTLE_STEPS, count(&|f| f.settle_steps))
        .f64(col::SETTLE_TIME_S, fact(&|f| f.settle_time_s))
        .static_str(col::SETTLED_BY, rows.iter().map(|r| r.outcome.as_ref().map_or("", |f| f.settled_by)).collect())
        .u64(col::SKIPPED_STEPS, count(&|f| f.skipped_steps))
        .f64(col::SIMULATED_TIME_S, fact(&|f| f.simulated_time_s))
        .f64(col::WALL_TIME_S, rows.iter().map(|r| r.wall_time_s).collect())
        .f64(col::DT_S, fact(&|f| f.dt_s))
        .f64(col::CRITICAL_DT_S, fact(&|f| f.critical_dt_s))
        .u32(col::EVENTS, count(&|f| f.events as u64).into_iter().map(|v| v as u32).collect())
        .u32(col::MAIN_SHOCKS, count(&|f| f.main_shocks as u64).into_iter().map(|v| v as u32).collect())
        .static_str(col::SLIP_REGIME, rows.iter().map(|r| r.outcome.as_ref().map_or("", |f| f.regime.name())).collect())
        .opt_f64(
            col::SLIDING_FROM_S,
            rows.iter().map(|r| r.outcome.as_ref().ok().and_then(|f| f.sliding_from_s)).collect(),
        )
        .str(col::PIPELINE_HASH, vec![pipeline_hash.to_string(); n])
        .finish(RUNS.name)
}

read_back! {
    /// The runs table read back.
    pub struct Runs from RUNS, |c| {
        /// Seeds.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Status of each.
        status: Vec<RunStatus> = c.strs(col::STATUS)?.iter().map(|s| RunStatus::parse(s).unwrap_or(RunStatus::Failed)).collect(),
        /// Error message of each failed seed (empty for finished ones).
        message: Vec<String> = c.strs(col::MESSAGE)?,
        /// Hash of the pipeline each seed ran.
        pipeline_hash: Vec<String> = c.strs(col::PIPELINE_HASH)?,
        /// Main shocks of each seed.
        main_shocks: Vec<u64> = c.u64s(col::MAIN_SHOCKS)?,
        /// Events of each seed.
        events: Vec<u64> = c.u64s(col::EVENTS)?,
        /// What the base did in each seed (`stick_slip`, `stable_sliding`, …; empty for a failed
        /// seed or a folder written before the column existed).
        slip_regime: Vec<String> = if c.has(col::SLIP_REGIME) { c.strs(col::SLIP_REGIME)? } else { vec![String::new(); c.height()] },
        /// Start of the sliding that never stopped (s), per seed.
        sliding_from_s: Vec<Option<f64>> = if c.has(col::SLIDING_FROM_S) { c.opt_f64s(col::SLIDING_FROM_S)? } else { vec![None; c.height()] },
        /// Steps of each seed, integrated or skipped.
        steps: Vec<u64> = c.u64s(col::STEPS)?,
        /// Steps skipped by the quasi-static skip-ahead.
        skipped_steps: Vec<u64> = c.u64s(col::SKIPPED_STEPS)?,
        /// Steps of the self-weight stage.
        settle_steps: Vec<u64> = c.u64s(col::SETTLE_STEPS)?,
        /// How the self-weight stage settled.
        settled_by: Vec<String> = c.strs(col::SETTLED_BY)?,
        /// Δt (s), NaN for a failed seed.
        dt_s: Vec<f64> = c.f64s(col::DT_S)?,
        /// Critical Δt (s), NaN for a failed seed.
        critical_dt_s: Vec<f64> = c.f64s(col::CRITICAL_DT_S)?,
        /// Wall time (s).
        wall_time_s: Vec<f64> = c.f64s(col::WALL_TIME_S)?,
    }
}

impl Runs {
    /// Seeds that finished.
    pub fn ok_seeds(&self) -> Vec<u64> {
        self.seed.iter().zip(&self.status).filter(|(_, s)| **s == RunStatus::Ok).map(|(s, _)| *s).collect()
    }

    /// Seeds that failed, with their message.
    pub fn failed(&self) -> Vec<(u64, String)> {
        (0..self.seed.len())
            .filter(|&i| self.status[i] == RunStatus::Failed)
            .map(|i| (self.seed[i], self.message[i].clone()))
            .collect()
    }
}
