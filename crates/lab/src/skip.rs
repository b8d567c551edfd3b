//! Quasi-static skip-ahead against full integration.
//!
//! Stick-slip on this block is chaotic: a change of one part in 10⁹ of Young's modulus moves the
//! third main shock by milliseconds and its drop by tens of percent (the `baseline` columns show
//! it for each seed). Comparing a whole skip run with a whole full run therefore measures chaos,
//! not the skip. So each jump is checked on its own: two runs that are identical up to that jump
//! (the same earlier jumps), one making it and one integrating through it, are compared on the
//! first slip onset and the first event after the jump started, next to a third run that
//! integrates through the jump and has its displacements scaled by `1 + 10⁻⁹` where the jump
//! ends (how much that event changes for a perturbation far smaller than the skip's). Whole
//! runs are compared on their statistics (main shocks, mean drop) next to the chaos baseline.

use std::ops::ControlFlow;
use std::time::Instant;

use polars::prelude::DataFrame;
use stickslip_analysis::events::catalogue;
use stickslip_config::PipelineFile;
use stickslip_seismo::events::{Catalogue, EventParams};
use stickslip_solver::recording::Skip;
use stickslip_solver::{Model, Perturbation, RunOptions, RunOutput, run_seed};
use stickslip_store::frame::Frame;

use crate::LabError;

/// Whole runs of one seed: full integration, skip-ahead, and full integration of a scene
/// perturbed by one part in 10⁹ (the chaos baseline).
#[derive(Clone, Debug, PartialEq)]
pub struct SkipRun {
    /// Seed.
    pub seed: u64,
    /// Wall time with every step integrated (s).
    pub full_wall_s: f64,
    /// Wall time with skip-ahead (s).
    pub skip_wall_s: f64,
    /// Shear steps.
    pub shear_steps: u64,
    /// Shear steps skipped.
    pub skipped_steps: u64,
    /// Jumps made.
    pub jumps: u64,
    /// Main shocks: full, skip, baseline.
    pub main_shocks: [u32; 3],
    /// Events: full, skip, baseline.
    pub events: [u32; 3],
    /// Mean main-shock stress drop (Pa): full, skip, baseline.
    pub mean_drop_pa: [f64; 3],
    /// Mean main-shock recurrence of the full run (s); with fewer than two main shocks the
    /// mean time between events, with fewer than two events the shear duration.
    pub recurrence_s: f64,
}

/// One jump compared with integrating through it from the same state.
#[derive(Clone, Debug, PartialEq)]
pub struct JumpCheck {
    /// Seed.
    pub seed: u64,
    /// Jump number (1 = first).
    pub jump: u64,
    /// The jump.
    pub skip: Skip,
    /// First sustained slip onset after the jump started: integrated, skipped, integrated and
    /// perturbed (s).
    pub onset_s: [Option<f64>; 3],
    /// First event after the jump started: start (s) and stress drop (Pa), integrated,
    /// skipped, integrated and perturbed.
    pub event: [Option<(f64, f64)>; 3],
    /// Time scale the onset error is measured against: the seed's recurrence (s, as in
    /// [`SkipRun::recurrence_s`]).
    pub recurrence_s: f64,
}

impl JumpCheck {
    /// `|onset difference| / recurrence` of the skipped (`side` 1) or perturbed (`side` 2) run
    /// against the integrated one (NaN when an onset is missing on either side).
    pub fn onset_error(&self, side: usize) -> f64 {
        match (self.onset_s[0], self.onset_s[side]) {
            (Some(a), Some(b)) => (b - a).abs() / self.recurrence_s,
            _ => f64::NAN,
        }
    }

    /// Relative difference of the first event's stress drop, skipped (`side` 1) or perturbed
    /// (`side` 2) against integrated (NaN when either side has none).
    pub fn drop_error(&self, side: usize) -> f64 {
        match (self.event[0], self.event[side]) {
            (Some((_, a)), Some((_, b))) => (b / a - 1.0).abs(),
            _ => f64::NAN,
        }
    }

    /// Whether the skipped run has an event after the jump exactly when the integrated one has.
    pub fn same_events(&self) -> bool {
        self.event[0].is_some() == self.event[1].is_some()
    }
}

/// What one side of a jump check saw after the jump started: the first slip onset (s), the
/// first event's start (s) and stress drop (Pa).
type AfterJump = (Option<f64>, Option<(f64, f64)>);

/// Relative perturbation of the third run of a jump check.
pub const PERTURBATION: f64 = 1e-9;

/// Settings of the comparison.
#[derive(Clone, Copy, Debug)]
pub struct SkipBench {
    /// Jumps checked per seed: those followed by an event within the window first, then the
    /// others in time order.
    pub jumps_per_seed: usize,
    /// How long after a jump's end the compared runs go on (s).
    pub window_s: f64,
}

impl Default for SkipBench {
    fn default() -> Self {
        SkipBench { jumps_per_seed: 4, window_s: 0.05 }
    }
}

fn model_of(file: PipelineFile) -> Result<Model, LabError> {
    Ok(Model::new(file.scene()?))
}

fn timed(model: &Model, seed: u64, options: RunOptions) -> Result<(RunOutput, f64), LabError> {
    let start = Instant::now();
    let out = run_seed(model, seed, options, &mut |_| ControlFlow::Continue(()))
        .map_err(|e| LabError::Setup(format!("seed {seed}: {e}")))?;
    Ok((out, start.elapsed().as_secs_f64()))
}

fn events_of(model: &Model, out: &RunOutput, events: &EventParams) -> Result<Catalogue, LabError> {
    Ok(catalogue(&out.recording, model, events))
}

fn mean_main_drop(cat: &Catalogue) -> f64 {
    let drops: Vec<f64> = cat.main_shocks().map(|e| e.burst.stress_drop_pa).collect();
    if drops.is_empty() { f64::NAN } else { drops.iter().sum::<f64>() / drops.len() as f64 }
}

/// Runs `seeds` of `scene` with skip-ahead off, on, and off with a perturbed modulus; then
/// checks the first jumps of each seed one by one. `scene` is used as given otherwise (slip
/// onsets are recorded whatever it says).
pub fn compare_skip(
    file: &PipelineFile,
    events: &EventParams,
    seeds: &[u64],
    bench: SkipBench,
    progress: &mut dyn FnMut(&str),
) -> Result<(Vec<SkipRun>, Vec<JumpCheck>), LabError> {
    let mut base = file.clone();
    base.record.slip_onsets = true;
    let with = |on: bool, perturb: bool, duration: Option<f64>| {
        let mut file = base.clone();
        file.skip_ahead.enabled = on;
        if perturb {
            file.material.young_pa *= 1.0 + 1e-9;
        }
        if let Some(d) = duration {
            file.shear.duration_s = d;
        }
        model_of(file)
    };
    let (full_model, skip_model, baseline_model) =
        (with(false, false, None)?, with(true, false, None)?, with(false, true, None)?);
    let mut runs = Vec::new();
    let mut checks = Vec::new();
    for &seed in seeds {
        progress(&format!("seed {seed}: full, skip-ahead and perturbed runs"));
        let (full, full_wall_s) = timed(&full_model, seed, RunOptions::default())?;
        let (skip, skip_wall_s) = timed(&skip_model, seed, RunOptions::default())?;
        let (baseline, _) = timed(&baseline_model, seed, RunOptions::default())?;
        let cats = [
            events_of(&full_model, &full, events)?,
            events_of(&skip_model, &skip, events)?,
            events_of(&baseline_model, &baseline, events)?,
        ];
        // The main-shock recurrence, else the mean time between events, else the run.
        let mains: Vec<f64> = cats[0].main_shocks().map(|e| e.burst.start_s).collect();
        let all: Vec<f64> = cats[0].events.iter().map(|e| e.burst.start_s).collect();
        let mean_gap = |s: &[f64]| (s.len() >= 2).then(|| (s[s.len() - 1] - s[0]) / (s.len() - 1) as f64);
        let recurrence_s = mean_gap(&mains).or(mean_gap(&all)).unwrap_or(file.shear.duration_s);
        runs.push(SkipRun {
            seed,
            full_wall_s,
            skip_wall_s,
            shear_steps: full.shear_steps,
            skipped_steps: skip.skip.skipped_steps,
            jumps: skip.skip.jumps,
            main_shocks: cats.each_ref().map(|c| c.main_shocks().count() as u32),
            events: cats.each_ref().map(|c| c.events.len() as u32),
            mean_drop_pa: cats.each_ref().map(mean_main_drop),
            recurrence_s,
        });
        // The jumps that end just before an event first (where an error would show most), then
        // the others in time order.
        let skips = &skip.recording.skips;
        let leads_to_event = |j: &Skip| {
            cats[1].events.iter().any(|e| e.burst.start_s >= j.to_s && e.burst.start_s <= j.to_s + bench.window_s)
        };
        let mut order: Vec<usize> = (0..skips.len()).filter(|&k| leads_to_event(&skips[k])).collect();
        order.extend((0..skips.len()).filter(|&k| !leads_to_event(&skips[k])));
        order.truncate(bench.jumps_per_seed);
        order.sort_unstable();
        for (n, &k) in order.iter().enumerate() {
            let jump = &skips[k];
            progress(&format!("seed {seed}: jump {} ({} of {} checked)", k + 1, n + 1, order.len()));
            let until = (jump.to_s + bench.window_s).min(file.shear.duration_s);
            let model = with(true, false, Some(until))?;
            let side = |jumps: u64, perturb: bool| -> Result<AfterJump, LabError> {
                let perturb = perturb.then_some(Perturbation { at_s: jump.to_s, relative: PERTURBATION });
                let options = RunOptions { max_jumps: Some(jumps), perturb, ..RunOptions::default() };
                let (out, _) = timed(&model, seed, options)?;
                let onset = out.recording.onsets.iter().map(|&(t, _)| t).find(|&t| t >= jump.from_s);
                let cat = events_of(&model, &out, events)?;
                let event = cat
                    .events
                    .iter()
                    .find(|e| e.burst.start_s >= jump.from_s)
                    .map(|e| (e.burst.start_s, e.burst.stress_drop_pa));
                Ok((onset, event))
            };
            let (a, b, c) = (side(k as u64, false)?, side(k as u64 + 1, false)?, side(k as u64, true)?);
            checks.push(JumpCheck {
                seed,
                jump: k as u64 + 1,
                skip: *jump,
                onset_s: [a.0, b.0, c.0],
                event: [a.1, b.1, c.1],
                recurrence_s,
            });
        }
    }
    Ok((runs, checks))
}

/// The whole-run rows as a table: `seed` u64, `full_wall_s`, `skip_wall_s`, `speedup` f64,
/// `shear_steps`, `skipped_steps`, `jumps` u64, `main_full`, `main_skip`, `main_baseline`,
/// `events_full`, `events_skip`, `events_baseline` u32, `mean_drop_full_pa`,
/// `mean_drop_skip_pa`, `mean_drop_baseline_pa`, `recurrence_s` f64.
pub fn runs_frame(rows: &[SkipRun]) -> Result<DataFrame, LabError> {
    let col = |f: &dyn Fn(&SkipRun) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    let cnt = |f: &dyn Fn(&SkipRun) -> u64| rows.iter().map(f).collect::<Vec<u64>>();
    let small = |f: &dyn Fn(&SkipRun) -> u32| rows.iter().map(f).collect::<Vec<u32>>();
    Ok(Frame::new(rows.len())
        .u64("seed", cnt(&|r| r.seed))
        .f64("full_wall_s", col(&|r| r.full_wall_s))
        .f64("skip_wall_s", col(&|r| r.skip_wall_s))
        .f64("speedup", col(&|r| r.full_wall_s / r.skip_wall_s))
        .u64("shear_steps", cnt(&|r| r.shear_steps))
        .u64("skipped_steps", cnt(&|r| r.skipped_steps))
        .u64("jumps", cnt(&|r| r.jumps))
        .u32("main_full", small(&|r| r.main_shocks[0]))
        .u32("main_skip", small(&|r| r.main_shocks[1]))
        .u32("main_baseline", small(&|r| r.main_shocks[2]))
        .u32("events_full", small(&|r| r.events[0]))
        .u32("events_skip", small(&|r| r.events[1]))
        .u32("events_baseline", small(&|r| r.events[2]))
        .f64("mean_drop_full_pa", col(&|r| r.mean_drop_pa[0]))
        .f64("mean_drop_skip_pa", col(&|r| r.mean_drop_pa[1]))
        .f64("mean_drop_baseline_pa", col(&|r| r.mean_drop_pa[2]))
        .f64("recurrence_s", col(&|r| r.recurrence_s))
        .finish("skip_runs")?)
}

/// The per-jump checks as a table: `seed`, `jump` u64, `from_s`, `to_s` f64, `steps` u64,
/// `next` str, `onset_integrated_s`, `onset_skipped_s`, `onset_perturbed_s` f64 (null: none
/// in the window), `onset_error`, `onset_error_perturbed` f64 (fractions of the recurrence),
/// `event_integrated_s`, `drop_integrated_pa`, `event_skipped_s`, `drop_skipped_pa`,
/// `drop_perturbed_pa` f64 (null: no event), `drop_error`, `drop_error_perturbed` f64
/// (relative), `recurrence_s` f64.
pub fn jumps_frame(rows: &[JumpCheck]) -> Result<DataFrame, LabError> {
    let opt = |f: &dyn Fn(&JumpCheck) -> Option<f64>| rows.iter().map(f).collect::<Vec<Option<f64>>>();
    Ok(Frame::new(rows.len())
        .u64("seed", rows.iter().map(|r| r.seed).collect())
        .u64("jump", rows.iter().map(|r| r.jump).collect())
        .f64("from_s", rows.iter().map(|r| r.skip.from_s).collect())
        .f64("to_s", rows.iter().map(|r| r.skip.to_s).collect())
        .u64("steps", rows.iter().map(|r| r.skip.steps).collect())
        .str("next", rows.iter().map(|r| r.skip.next.kind().to_string()).collect())
        .opt_f64("onset_integrated_s", opt(&|r| r.onset_s[0]))
        .opt_f64("onset_skipped_s", opt(&|r| r.onset_s[1]))
        .opt_f64("onset_perturbed_s", opt(&|r| r.onset_s[2]))
        .f64("onset_error", rows.iter().map(|r| r.onset_error(1)).collect())
        .f64("onset_error_perturbed", rows.iter().map(|r| r.onset_error(2)).collect())
        .opt_f64("event_integrated_s", opt(&|r| r.event[0].map(|e| e.0)))
        .opt_f64("drop_integrated_pa", opt(&|r| r.event[0].map(|e| e.1)))
        .opt_f64("event_skipped_s", opt(&|r| r.event[1].map(|e| e.0)))
        .opt_f64("drop_skipped_pa", opt(&|r| r.event[1].map(|e| e.1)))
        .opt_f64("drop_perturbed_pa", opt(&|r| r.event[2].map(|e| e.1)))
        .f64("drop_error", rows.iter().map(|r| r.drop_error(1)).collect())
        .f64("drop_error_perturbed", rows.iter().map(|r| r.drop_error(2)).collect())
        .f64("recurrence_s", rows.iter().map(|r| r.recurrence_s).collect())
        .finish("skip_jumps")?)
}
