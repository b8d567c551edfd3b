//! Running a scene: per-seed random fields and critical steps, the self-weight stage until
//! equilibrium, the shear stage with its driver, recording, stability checks.

mod checkpoint;
mod lanes;
mod split;

use std::ops::ControlFlow;

use crate::error::{MAX_STEPS, SolverError};
use crate::model::Model;
use crate::quasistatic::SkipStats;
use crate::recording::Recording;
use crate::scene::{SettleMethod, TimeStep};
use crate::statics::{CriticalStep, critical_step_on};
use crate::step::LaneSetup;

pub use checkpoint::Checkpoint;
pub use lanes::run_lanes;
pub use split::{RankPart, run_split, split_refusal};

/// Options that are not part of the physics.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOptions {
    /// Run even if a fixed `time.dt_s` is above the critical step (only to test that the
    /// blow-up is caught; a normal run refuses it).
    pub allow_unstable_time_step: bool,
    /// Split each step over the threads of the current rayon pool (large lattices only: a
    /// lattice cut into slabs, see [`crate::step::bars::BarLayout`]); the numbers are the same.
    pub parallel_step: bool,
    /// With `[skip_ahead]` on, stop skipping after this many jumps (to compare a jump with
    /// integrating through it from the same state).
    pub max_jumps: Option<u64>,
    /// Scale the displacement state by `1 + relative` at shear time `at_s` (the first step at
    /// or after it): a perturbation for sensitivity studies.
    pub perturb: Option<Perturbation>,
}

/// A relative perturbation of the displacement state at one instant of the shear stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perturbation {
    /// Shear-stage time (s).
    pub at_s: f64,
    /// Relative change of every displacement.
    pub relative: f64,
}

/// Seeds advanced side by side in one batch (the widest lane count, eight `f64` = one AVX-512
/// register per node component).
pub const BATCH: usize = 8;

/// Runs `seeds` in batches of [`BATCH`], then 4, then one at a time for the rest: every seed
/// gives the same numbers as [`run_seed`] (lanes are independent), several seeds share each
/// pass over the lattice. Results are in the order of `seeds`. With `[skip_ahead]` on, every
/// seed runs alone (a jump moves the whole stepper in time).
pub fn run_batched(
    model: &Model,
    seeds: &[u64],
    options: RunOptions,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> Vec<Result<RunOutput, SolverError>> {
    let mut out = Vec::with_capacity(seeds.len());
    let mut rest = seeds;
    let single = model.scene().skip_ahead.enabled;
    while !rest.is_empty() {
        if single {
            out.extend(run_lanes::<1>(model, [rest[0]], options, progress));
            rest = &rest[1..];
        } else if rest.len() >= BATCH {
            let chunk: [u64; BATCH] = rest[..BATCH].try_into().expect("length checked");
            out.extend(run_lanes::<BATCH>(model, chunk, options, progress));
            rest = &rest[BATCH..];
        } else if rest.len() >= 4 {
            let chunk: [u64; 4] = rest[..4].try_into().expect("length checked");
            out.extend(run_lanes::<4>(model, chunk, options, progress));
            rest = &rest[4..];
        } else {
            out.extend(run_lanes::<1>(model, [rest[0]], options, progress));
            rest = &rest[1..];
        }
    }
    out
}

/// What one seed's run produced.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOutput {
    /// Seed of the random fields.
    pub seed: u64,
    /// Time step used (s).
    pub dt_s: f64,
    /// Critical step of this seed's lattice (s).
    pub critical: CriticalStep,
    /// Duration of the self-weight stage (s).
    pub settle_time_s: f64,
    /// Steps of the self-weight stage.
    pub settle_steps: u64,
    /// Steps of the shear stage (integrated or skipped).
    pub shear_steps: u64,
    /// How the self-weight stage reached equilibrium.
    pub settled_by: SettleMethod,
    /// Why a static settle asked for was not used (the run settled dynamically instead).
    pub settle_note: Option<String>,
    /// What the quasi-static skip-ahead did (zeros when off).
    pub skip: SkipStats,
    /// Recorded series.
    pub recording: Recording,
    /// Every bar past its peak at the end of the run (when the scene's bars crack), by canonical
    /// index.
    pub damage: Vec<BarDamage>,
}

/// A bar past its peak at the end of a run (docs/model.md §11).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarDamage {
    /// Canonical bar index.
    pub bar: u32,
    /// Largest strain it reached.
    pub reach_strain: f64,
    /// Energy it dissipated by the law's closed form `Gf·A_f·(κ − εp)/(εr − εp)` (J).
    pub dissipated_j: f64,
    /// Whether it reached `εr`.
    pub broken: bool,
}

impl RunOutput {
    /// All steps, integrated or skipped.
    pub fn steps(&self) -> u64 {
        self.settle_steps + self.shear_steps
    }

    /// Steps actually integrated.
    pub fn integrated_steps(&self) -> u64 {
        self.steps() - self.skip.skipped_steps
    }
}

/// Runs one seed. `progress` receives the fraction done (0..1) now and then and may stop the
/// run by returning `ControlFlow::Break(())`.
pub fn run_seed(
    model: &Model,
    seed: u64,
    options: RunOptions,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> Result<RunOutput, SolverError> {
    let [out] = run_lanes::<1>(model, [seed], options, progress);
    out
}

/// [`run_seed`], resuming from `checkpoint`'s file when it holds this seed's run and writing it
/// as the checkpoint says and when the run is asked to stop ([`Checkpoint`]): a run stopped and
/// resumed gives the numbers of one never stopped. The caller removes the file once the output
/// is kept ([`Checkpoint::remove`]).
pub fn run_seed_checkpointed(
    model: &Model,
    seed: u64,
    options: RunOptions,
    checkpoint: &Checkpoint,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> Result<RunOutput, SolverError> {
    let [out] = lanes::run_lanes_with::<1, _>(model, [seed], options, progress, &mut lanes::Solo, Some(checkpoint));
    out
}

pub(crate) fn prepare(model: &Model, seed: u64, options: RunOptions) -> Result<(LaneSetup, CriticalStep), SolverError> {
    // With the step split over the pool, the pool is this seed's: the set-up may use it too.
    let stiffness = model.lane_stiffness_on(seed, options.parallel_step)?;
    let friction = model.friction_factors(seed)?;
    let strength = model.bar_strength(seed)?;
    let fault = model.fault_loads(seed)?;
    let critical = critical_step_on(model, &stiffness, options.parallel_step)?;
    let dt_s = time_step(model, seed, &critical, options)?;
    Ok((LaneSetup { dt_s, stiffness, friction, strength, fault }, critical))
}

/// The seed's Δt from its `critical` step (the scene's fraction of it, or its fixed step, refused
/// above it), with the step count and the recording interval checked.
pub(crate) fn time_step(
    model: &Model,
    seed: u64,
    critical: &CriticalStep,
    options: RunOptions,
) -> Result<f64, SolverError> {
    // Δt never depends on the recording interval (which samples every `round(interval/Δt)`
    // steps): the same seed gives the same run whatever it records.
    let dt_s = match model.scene().time_step {
        TimeStep::Fraction(f) => f * critical.dt_s,
        TimeStep::Fixed(dt) => {
            if dt > critical.dt_s && !options.allow_unstable_time_step {
                return Err(SolverError::TimeStepAboveCritical { dt_s: dt, critical_s: critical.dt_s, seed });
            }
            dt
        }
    };
    check_step_count(model, dt_s)?;
    check_record_interval(model, dt_s)?;
    Ok(dt_s)
}

/// Refuses a time step `dt_s` with which a stage of `model`'s scene would take more steps than
/// the run can count ([`SolverError::TooManySteps`]).
pub fn check_step_count(model: &Model, dt_s: f64) -> Result<(), SolverError> {
    let scene = model.scene();
    // The whole block's bars, when `model` is a rank's part of it.
    let bars = if model.split_window().is_some() { scene.dims.bar_count() } else { model.bar_count() } as f64;
    let stages = [
        ("self-weight stage (its time limit)", scene.self_weight.max_duration_s),
        ("shear stage", scene.shear.duration_s),
    ];
    let mut total = 0.0;
    for (stage, duration_s) in stages {
        let steps = (duration_s / dt_s).ceil();
        total += steps;
        if !(steps <= MAX_STEPS && total * bars < u64::MAX as f64) {
            return Err(SolverError::TooManySteps { stage, duration_s, dt_s, steps, bar_updates: steps * bars });
        }
    }
    Ok(())
}

/// Refuses a recording interval finer than half the time step `dt_s` when the records are
/// resampled to it ([`crate::scene::RecordPlan::resampled`], [`SolverError::RecordIntervalTooFine`]):
/// a run samples every `round(interval/Δt)` steps, at least one, so its records would be
/// resampled to an interval between its steps (and an absurd one would not fit in memory).
/// Checked before the first step, once Δt is known. Without records, a finer interval samples
/// every step.
pub fn check_record_interval(model: &Model, dt_s: f64) -> Result<(), SolverError> {
    let record = &model.scene().record;
    match record.interval_s {
        Some(interval_s) if record.resampled && interval_s < 0.5 * dt_s => {
            Err(SolverError::RecordIntervalTooFine { interval_s, dt_s })
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn a_record_interval_finer_than_half_the_step_is_refused_before_the_run() {
        let mut scene = Scene::paper();
        scene.record.resampled = true;
        scene.record.interval_s = Some(0.5e-5);
        assert!(check_record_interval(&Model::new(scene.clone()), 1e-5).is_ok(), "half a step: sampled every step");
        scene.record.interval_s = Some(0.49e-5);
        let e = check_record_interval(&Model::new(scene.clone()), 1e-5).unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("record.interval_s = 4.9e-6 s") && text.contains("at least Δt/2 = 5.0000e-6 s"),
            "{text}"
        );
        // Without records resampled to it, the run samples every step.
        scene.record.resampled = false;
        assert!(check_record_interval(&Model::new(scene.clone()), 1e-5).is_ok());
        // The run of a seed stops there, before its first step.
        scene.record.resampled = true;
        scene.record.interval_s = Some(1e-17);
        let out = run_seed(&Model::new(scene), 1, RunOptions::default(), &mut |_| ControlFlow::Continue(()));
        assert!(matches!(out, Err(SolverError::RecordIntervalTooFine { interval_s: 1e-17, .. })), "{:?}", out.err());
    }

    #[test]
    fn a_stage_longer_than_the_run_can_count_is_refused_before_it_starts() {
        let model = Model::new(Scene::paper());
        assert!(check_step_count(&model, 1e-5).is_ok(), "the paper scene's 32 000 steps");
        let e = check_step_count(&model, 1e-25).unwrap_err();
        assert!(matches!(e, SolverError::TooManySteps { stage: "self-weight stage (its time limit)", .. }), "{e}");
        let mut scene = Scene::paper();
        scene.shear.duration_s = 3e11;
        let e = check_step_count(&Model::new(scene), 1e-5).unwrap_err();
        assert!(matches!(e, SolverError::TooManySteps { stage: "shear stage", .. }), "{e}");
        assert!(e.to_string().contains("more than the run can count"), "{e}");
    }
}
