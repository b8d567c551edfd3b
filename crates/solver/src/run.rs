//! Running a scene: per-seed random fields and critical steps, the self-weight stage until
//! equilibrium, the shear stage with its driver, recording, stability checks.

use std::ops::ControlFlow;

use crate::critical::{CriticalStep, critical_time_step};
use crate::error::SolverError;
use crate::model::Model;
use crate::quasistatic::{SKIP_CHECK_EVERY, ShearClock, SkipStats, Skipper, settle_statically};
use crate::record::{Recorder, Records};
use crate::scene::{SettleMethod, TimeStep};
use crate::stepper::{LaneSetup, Stepper};

/// Steps between two blow-up checks.
const BLOWUP_CHECK_EVERY: u64 = 16;
/// Steps between two equilibrium checks in the self-weight stage.
const SETTLE_CHECK_EVERY: u64 = 8;
/// Steps between two progress reports.
const PROGRESS_EVERY: u64 = 512;

/// Options that are not part of the physics.
#[derive(Clone, Copy, Debug, Default)]
pub struct RunOptions {
    /// Run even if a fixed `time.dt_s` is above the critical step (only to test that the
    /// blow-up is caught; a normal run refuses it).
    pub allow_unstable_time_step: bool,
    /// Split each step over the threads of the current rayon pool (large lattices only: a
    /// lattice cut into slabs, see [`crate::kernel::BarLayout`]); the numbers are the same.
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
    pub records: Records,
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

enum Stage {
    Settling { max_steps: u64 },
    Shearing { origin: u64, steps: u64, stride: u64 },
    Done { origin: u64 },
    Failed(SolverError),
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

fn prepare(model: &Model, seed: u64, options: RunOptions) -> Result<(LaneSetup, CriticalStep), SolverError> {
    let stiffness = model.bar_stiffness(seed)?;
    let friction = model.friction_factors(seed)?;
    let critical = critical_time_step(model, &stiffness)?;
    let mut dt_s = match model.scene().time_step {
        TimeStep::Fraction(f) => f * critical.dt_s,
        TimeStep::Fixed(dt) => {
            if dt > critical.dt_s && !options.allow_unstable_time_step {
                return Err(SolverError::TimeStepAboveCritical { dt_s: dt, critical_s: critical.dt_s, seed });
            }
            dt
        }
    };
    // A recording interval is a whole number of steps: lower Δt (never raise it) to fit.
    if let Some(interval) = model.scene().record.interval_s {
        let k = (interval / dt_s * (1.0 - 1e-12)).ceil().max(1.0);
        dt_s = interval / k;
    }
    Ok((LaneSetup { dt_s, stiffness, friction }, critical))
}

/// Runs `L` seeds side by side through the same model (lane `l` gives the same numbers as
/// [`run_seed`] of `seeds[l]`). A lane that fails does not stop the others. The quasi-static
/// skip-ahead works with `L = 1` only; wider batches integrate every step.
pub fn run_lanes<const L: usize>(
    model: &Model,
    seeds: [u64; L],
    options: RunOptions,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> [Result<RunOutput, SolverError>; L] {
    let scene = model.scene();
    let prepared = seeds.map(|seed| prepare(model, seed, options));
    // Failed lanes still occupy a lane: give them a harmless set-up and park them.
    let fallback = prepared.iter().find_map(|p| p.as_ref().ok().map(|(s, _)| s.clone()));
    let Some(fallback) = fallback else {
        return prepared.map(|p| p.map(|_| unreachable!("every lane failed")));
    };
    let setups = prepared.each_ref().map(|p| p.as_ref().map(|(s, _)| s.clone()).unwrap_or_else(|_| fallback.clone()));
    let mut stepper = Stepper::<L>::new(model, &setups);
    stepper.set_track_energy(scene.record.energy);
    stepper.set_parallel(options.parallel_step);
    stepper.set_track_onsets(scene.record.slip_onsets);
    let sw = scene.self_weight;
    let mut stages: [Stage; L] = std::array::from_fn(|l| {
        let dt = setups[l].dt_s;
        let max_steps = (sw.max_duration_s / dt).ceil() as u64;
        Stage::Settling { max_steps }
    });
    let mut criticals = [None; L];
    let mut recorders: [Option<Recorder>; L] = std::array::from_fn(|_| None);
    let mut settle_steps = [0u64; L];
    let mut settled_by = [SettleMethod::Dynamic; L];
    let mut settle_notes: [Option<String>; L] = std::array::from_fn(|_| None);
    let mut skippers: [Option<Skipper>; L] = std::array::from_fn(|_| None);
    let weight_norm: f64 = model.mass().iter().map(|m| m * m).sum::<f64>().sqrt() * sw.gravity_m_s2;
    for (l, p) in prepared.into_iter().enumerate() {
        match p {
            Ok((setup, critical)) => {
                criticals[l] = Some(critical);
                let dt = setup.dt_s;
                let stride = stride(scene.record.interval_s, dt);
                let shear_steps = whole_steps(scene.shear.duration_s, dt);
                // Reserve for the whole stage, up to a million samples (long runs grow as they go).
                let capacity = (shear_steps / stride).min(1 << 20) as usize + 2;
                recorders[l] = Some(Recorder::new(&scene.record, model, capacity));
                stepper.set_damping(l, sw.damping_per_s);
                stepper.set_body_acceleration(l, [0.0, 0.0, -sw.gravity_m_s2]);
                if scene.skip_ahead.enabled && L == 1 {
                    skippers[l] = Some(Skipper::new(model, setup.stiffness.clone(), &setup.friction));
                    stepper.set_track_slid(true);
                }
                if sw.method == SettleMethod::Static && sw.gravity_m_s2 > 0.0 {
                    match settle_statically(model, &setup.stiffness, &setup.friction, sw.gravity_m_s2) {
                        Ok(Ok(st)) => {
                            start_at_rest(&mut stepper, l, model, &st.u, &st.reactions);
                            settled_by[l] = SettleMethod::Static;
                            stages[l] = start_shear(&mut stepper, l, model);
                        }
                        Ok(Err(why)) => settle_notes[l] = Some(why),
                        Err(e) => settle_notes[l] = Some(e.to_string()),
                    }
                }
            }
            Err(e) => {
                stepper.park(l);
                stages[l] = Stage::Failed(e);
            }
        }
    }
    // No gravity: nothing to settle.
    if sw.gravity_m_s2 == 0.0 {
        for l in 0..L {
            if matches!(stages[l], Stage::Settling { .. }) {
                stages[l] = start_shear(&mut stepper, l, model);
            }
        }
    }

    loop {
        let active = stages.iter().any(|s| matches!(s, Stage::Settling { .. } | Stage::Shearing { .. }));
        if !active {
            break;
        }
        // Driver targets for the step about to compute u_{S+1}.
        let next = stepper.steps() + 1;
        for l in 0..L {
            if let Stage::Shearing { origin, .. } = stages[l] {
                let t = (next - origin) as f64 * stepper.dt(l);
                stepper.set_driver_target(l, scene.shear.driver_displacement(t));
            }
        }
        stepper.step();
        let view = stepper.steps() - 1;
        for l in 0..L {
            if !matches!(stages[l], Stage::Settling { .. } | Stage::Shearing { .. }) {
                continue;
            }
            if view.is_multiple_of(BLOWUP_CHECK_EVERY)
                && let Some(b) = stepper.check_blowup(l)
            {
                let (origin, stage_name) = match stages[l] {
                    Stage::Shearing { origin, .. } => (origin, "shear stage"),
                    _ => (0, "self-weight stage"),
                };
                let id = model.canonical(b.node);
                let p = model.lattice().position(id);
                let dt = stepper.dt(l);
                let crit = criticals[l].map_or(f64::NAN, |c| c.dt_s);
                stages[l] = Stage::Failed(SolverError::Unstable {
                    step: view,
                    time_s: (view as f64 - origin as f64) * dt,
                    stage: stage_name,
                    what: b.what,
                    node: format!("({:.4}, {:.4}, {:.4}) m", p[0], p[1], p[2]),
                    ldem: id.ldem(),
                    dt_s: dt,
                    fraction: dt / crit,
                });
                stepper.park(l);
                continue;
            }
            if scene.record.slip_onsets {
                let from = match stages[l] {
                    Stage::Shearing { origin, .. } => Some(origin),
                    Stage::Settling { .. } if scene.record.settling => Some(0),
                    _ => None,
                };
                let contact = model.contact();
                for (step, ci) in stepper.drain_onsets(l) {
                    if let (Some(from), Some(r)) = (from, recorders[l].as_mut())
                        && step >= from
                    {
                        r.onset_steps.push((step, model.canonical(contact[ci as usize] as usize)));
                    }
                }
            }
            match stages[l] {
                Stage::Settling { max_steps } => {
                    if scene.record.settling
                        && let Some(r) = recorders[l].as_mut()
                    {
                        r.sample(&stepper, l, view);
                    }
                    if view.is_multiple_of(SETTLE_CHECK_EVERY) && view > 0 {
                        let ratio = stepper.out_of_balance(l) / weight_norm;
                        if ratio < sw.settle_tolerance {
                            settle_steps[l] = stepper.steps();
                            stages[l] = start_shear(&mut stepper, l, model);
                        } else if view >= max_steps {
                            stages[l] = Stage::Failed(SolverError::NotSettled {
                                max_s: sw.max_duration_s,
                                residual: ratio,
                                tolerance: sw.settle_tolerance,
                            });
                            stepper.park(l);
                        }
                    }
                }
                Stage::Shearing { origin, steps, stride } => {
                    let j = view - origin;
                    if let Some(p) = options.perturb
                        && j == (p.at_s / stepper.dt(l)).ceil().max(0.0) as u64
                    {
                        stepper.scale_state(l, 1.0 + p.relative);
                    }
                    let recorder = recorders[l].as_mut().expect("recorder of a running lane");
                    if j.is_multiple_of(stride) || j >= steps {
                        recorder.sample(&stepper, l, view);
                    }
                    if j >= steps {
                        stages[l] = Stage::Done { origin };
                    } else if let Some(skipper) = skippers[l].as_mut()
                        && j.is_multiple_of(SKIP_CHECK_EVERY)
                        && options.max_jumps.is_none_or(|m| skipper.stats.jumps < m)
                    {
                        let skip_stride = scene.skip_ahead.record_interval_s.map_or(stride, |iv| {
                            let interval = scene.record.interval_s.unwrap_or(iv);
                            stride * ((iv / interval).round() as u64).max(1)
                        });
                        let clock = ShearClock { origin, end: origin + steps, stride: skip_stride };
                        if let Err(e) = skipper.look(&mut stepper, l, &clock, recorder) {
                            stages[l] = Stage::Failed(e);
                            stepper.park(l);
                        }
                    }
                }
                _ => {}
            }
        }
        if stepper.steps().is_multiple_of(PROGRESS_EVERY) {
            let fraction = stages
                .iter()
                .map(|s| match s {
                    Stage::Settling { .. } => 0.0,
                    Stage::Shearing { origin, steps, .. } => {
                        ((stepper.steps() - origin) as f64 / *steps as f64).min(1.0)
                    }
                    Stage::Done { .. } | Stage::Failed(_) => 1.0,
                })
                .sum::<f64>()
                / L as f64;
            if progress(fraction).is_break() {
                for (l, s) in stages.iter_mut().enumerate() {
                    if matches!(s, Stage::Settling { .. } | Stage::Shearing { .. }) {
                        *s = Stage::Failed(SolverError::Cancelled);
                        stepper.park(l);
                    }
                }
            }
        }
    }

    let mut stages = stages.map(Some);
    std::array::from_fn(|l| match stages[l].take().expect("each stage taken once") {
        Stage::Done { origin } => {
            let dt = stepper.dt(l);
            let recorder = recorders[l].take().expect("recorder of a finished lane");
            let shear_steps = recorder.steps.last().map_or(0, |&s| s - origin);
            Ok(RunOutput {
                seed: seeds[l],
                dt_s: dt,
                critical: criticals[l].expect("critical step of a finished lane"),
                settle_time_s: settle_steps[l] as f64 * dt,
                settle_steps: settle_steps[l],
                shear_steps,
                settled_by: settled_by[l],
                settle_note: settle_notes[l].take(),
                skip: skippers[l].as_ref().map_or_else(SkipStats::default, |s| s.stats),
                records: recorder.finish(origin, dt),
            })
        }
        Stage::Failed(e) => Err(e),
        Stage::Settling { .. } | Stage::Shearing { .. } => {
            unreachable!("loop ends when no lane is running")
        }
    })
}

/// Puts lane `l` at rest in a static equilibrium `u` (every base node sticking, or lifted where
/// its normal reaction is zero) as if the loads had been applied slowly: gravity's work so far
/// is `½·f·u`, the strain energy.
fn start_at_rest<const L: usize>(
    stepper: &mut Stepper<'_, L>,
    l: usize,
    model: &Model,
    u: &crate::kernel::Field<1>,
    reactions: &crate::kernel::Field<1>,
) {
    let contact = model.contact();
    let steps = stepper.steps();
    stepper.set_state(
        l,
        steps,
        |_, i, c| u.c[c][i][0],
        |ci| [0, 1, 2].map(|c| reactions.c[c][contact[ci] as usize][0]),
        |_| 0.0,
        0.0,
    );
    let b = stepper.body_acceleration(l);
    let mass = model.mass();
    let work: f64 = (0..model.node_count()).map(|i| (0..3).map(|c| mass[i] * b[c] * u.c[c][i][0]).sum::<f64>()).sum();
    stepper.energy_accumulators(l).body_work = 0.5 * work;
}

fn start_shear<const L: usize>(stepper: &mut Stepper<'_, L>, l: usize, model: &Model) -> Stage {
    let scene = model.scene();
    stepper.set_damping(l, scene.shear.damping_per_s);
    stepper.start_drivers(l);
    let dt = stepper.dt(l);
    let stride = stride(scene.record.interval_s, dt);
    Stage::Shearing { origin: stepper.steps(), steps: whole_steps(scene.shear.duration_s, dt), stride }
}

/// Steps between two samples (Δt was fitted to the interval in `prepare`).
fn stride(interval_s: Option<f64>, dt: f64) -> u64 {
    interval_s.map_or(1, |iv| ((iv / dt).round() as u64).max(1))
}

/// Steps to cover `duration` (rounded up, ignoring round-off of a duration that is a multiple).
fn whole_steps(duration: f64, dt: f64) -> u64 {
    (duration / dt * (1.0 - 1e-12)).ceil() as u64
}
