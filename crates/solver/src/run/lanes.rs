//! `L` seeds side by side through the two loading stages: one [`Lane`] per seed, one stepper.

use std::ops::ControlFlow;

use crate::error::SolverError;
use crate::field::Field;
use crate::model::Model;
use crate::observe::{Observed, REMOTE};
use crate::quasistatic::{SKIP_CHECK_EVERY, ShearClock, SkipStats, Skipper, settle_statically};
use crate::recording::{Crack, Recorder};
use crate::run::checkpoint::{self, BodyRef, Checkpoint, Due, Header, LaneRef, StageAt};
use crate::run::{BarDamage, RunOptions, RunOutput, prepare};
use crate::rupture::BarLaw;
use crate::scene::ControlChannel;
use crate::scene::SettleMethod;
use crate::statics::CriticalStep;
use crate::step::rupture::{CrackKind, CrackLog, elongations};
use crate::step::{LaneSetup, LaneStiffness, LaneView, Params, State, Stepper, Tracking, park, start_drivers};
use crate::trace::Tracer;

/// Steps between two blow-up checks.
const BLOWUP_CHECK_EVERY: u64 = 16;
/// Steps between two equilibrium checks in the self-weight stage.
const SETTLE_CHECK_EVERY: u64 = 8;
/// Steps between two progress reports (which is where an interrupt is seen), at most.
const PROGRESS_EVERY: u64 = 512;
/// Bar-updates between two progress reports, at most: fewer steps between them on a large
/// lattice, so that an interrupt stops a run within about a tenth of a second of stepping
/// (512 steps of 2 million bars took 20 s).
const PROGRESS_BAR_UPDATES: u64 = 1 << 24;

/// Where a lane is.
enum Stage {
    /// Loading stage 1, until static equilibrium or `max_steps`.
    Settling { max_steps: u64 },
    /// Loading stage 2: `origin` is the step of shear time zero, `steps` the stage's length,
    /// `stride` the steps between two samples.
    Shearing { origin: u64, steps: u64, stride: u64 },
    /// Finished.
    Done { origin: u64, stride: u64, steps: u64 },
    /// Stopped, and why.
    Failed(SolverError),
}

impl Stage {
    fn running(&self) -> bool {
        matches!(self, Stage::Settling { .. } | Stage::Shearing { .. })
    }
}

/// One seed of a batch.
struct Lane {
    seed: u64,
    stage: Stage,
    critical: Option<CriticalStep>,
    recorder: Option<Recorder>,
    settle_steps: u64,
    settled_by: SettleMethod,
    settle_note: Option<String>,
    skipper: Option<Skipper>,
}

impl Lane {
    fn fail<const L: usize>(&mut self, e: SolverError, p: &mut Params<'_, L>, s: &mut State<L>, l: usize) {
        self.stage = Stage::Failed(e);
        park(p, s, l);
    }
}

/// Runs `L` seeds side by side through the same model (lane `l` gives the same numbers as
/// [`crate::run::run_seed`] of `seeds[l]`). A lane that fails does not stop the others. The
/// quasi-static skip-ahead works with `L = 1` only; wider batches integrate every step.
pub fn run_lanes<const L: usize>(
    model: &Model,
    seeds: [u64; L],
    options: RunOptions,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
) -> [Result<RunOutput, SolverError>; L] {
    run_lanes_with(model, seeds, options, progress, &mut Solo, None)
}

/// What the run loop asks of the processes that run it: nothing on one process ([`Solo`]); on
/// the ranks of a split scene, the halo exchange, Δt from rank 0, the checks every rank must
/// agree on and the values rank 0 records of nodes it does not hold ([`crate::run::split`]).
pub(crate) trait Hooks<const L: usize> {
    /// The set-up and critical step of `seed`.
    fn prepare(
        &mut self,
        model: &Model,
        seed: u64,
        options: RunOptions,
    ) -> Result<(LaneSetup, CriticalStep), SolverError> {
        prepare(model, seed, options)
    }
    /// After every step, before anything looks at it.
    fn after_step(&mut self, _params: &Params<'_, L>, _state: &mut State<L>) {}
    /// The first node of the scene that blew up in lane `l`, if any: its canonical id and what.
    fn blowup(&mut self, view: &LaneView<'_, '_, L>, parallel: bool) -> Option<(crate::NodeId, String)> {
        view.check_blowup_on(parallel).map(|b| (view.params.model.canonical(b.node), b.what))
    }
    /// This process's rank and how many run the seed (0 of 1 alone).
    fn place(&self) -> (usize, usize) {
        (0, 1)
    }
    /// Whether the run stops and whether it writes its checkpoint now, given whether this process
    /// was asked to stop and whether its checkpoint is due: every rank gets rank 0's answer.
    fn agree(&mut self, stop: bool, save: bool) -> (bool, bool) {
        (stop, save)
    }
    /// Whether the run resumes from its checkpoint, given the step this process's file holds:
    /// only if every rank's file holds the same.
    fn resume(&mut self, at: Option<u64>) -> bool {
        at.is_some()
    }
    /// The self-weight stage's residual force of a lane ([`LaneView::out_of_balance`]), of the
    /// whole block.
    fn out_of_balance(&mut self, view: &LaneView<'_, '_, L>) -> f64 {
        view.out_of_balance()
    }
    /// `‖m‖·g`, the weight's norm, of the whole block.
    fn weight_norm(&mut self, model: &Model, gravity: f64) -> f64 {
        model.mass().iter().map(|m| m * m).sum::<f64>().sqrt() * gravity
    }
    /// Before a sample that records the energy: on the ranks of a split scene, every rank's
    /// kinetic and elastic energy summed for rank 0 ([`Remote::energy`]); nothing on one process,
    /// whose view has them.
    fn state_energy(&mut self, _view: &LaneView<'_, '_, L>) {}
    /// Whether this process records (rank 0 of a split scene, or the only one).
    fn records(&self) -> bool {
        true
    }
    /// What this process records of nodes it does not hold.
    fn remote(&self) -> Option<&Remote> {
        None
    }
}

/// One process.
pub(crate) struct Solo;

impl<const L: usize> Hooks<L> for Solo {}

/// Values rank 0 of a split scene records of what other ranks hold, this step.
#[derive(Clone, Debug, Default)]
pub(crate) struct Remote {
    /// Control channels of nodes rank 0 does not hold.
    pub control: Vec<(ControlChannel, f64)>,
    /// The driver reaction, when another rank holds the drivers.
    pub driver_force: Option<f64>,
    /// The whole block's kinetic and elastic energy (J), summed for this sample.
    pub energy: Option<(f64, f64)>,
}

/// A lane as rank 0 shows it to the recorder: its own nodes, and the values other ranks sent.
struct Shown<'v, 'a, 'm, const L: usize> {
    view: LaneView<'a, 'm, L>,
    remote: Option<&'v Remote>,
}

impl<const L: usize> Observed for Shown<'_, '_, '_, L> {
    fn node_contact(&self, ci: usize) -> crate::step::NodeContact {
        Observed::node_contact(&self.view, ci)
    }
    fn contacts(&self) -> usize {
        Observed::contacts(&self.view)
    }
    fn driver_force(&self) -> f64 {
        self.remote.and_then(|r| r.driver_force).unwrap_or_else(|| Observed::driver_force(&self.view))
    }
    fn driver_target(&self) -> f64 {
        Observed::driver_target(&self.view)
    }
    fn energy(&self) -> crate::step::Energy {
        match self.remote.and_then(|r| r.energy) {
            Some((kinetic, elastic)) => {
                crate::step::Energy { kinetic, elastic, ..self.view.state.energy[self.view.lane] }
            }
            None => Observed::energy(&self.view),
        }
    }
    fn kinematic(&self, node: usize, q: crate::scene::Kinematic) -> [f64; 3] {
        Observed::kinematic(&self.view, node, q)
    }
    fn control(&self, ch: ControlChannel, node: usize) -> f64 {
        if node == REMOTE {
            let remote = self.remote.expect("a node held by another rank has its value sent");
            remote.control.iter().find(|(c, _)| *c == ch).expect("every remote channel is sent").1
        } else {
            Observed::control(&self.view, ch, node)
        }
    }
}

/// [`run_lanes`] with `hooks` between the run loop and the processes that run it, resuming from
/// and writing `checkpoint` when given (not with the skip-ahead, whose state it does not hold).
pub(crate) fn run_lanes_with<const L: usize, H: Hooks<L>>(
    model: &Model,
    seeds: [u64; L],
    options: RunOptions,
    progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
    hooks: &mut H,
    checkpoint: Option<&Checkpoint>,
) -> [Result<RunOutput, SolverError>; L] {
    let scene = model.scene();
    let checkpoint = checkpoint.filter(|_| !scene.skip_ahead.enabled);
    if scene.skip_ahead.enabled
        && let Err(why) = model.boundaries().skip_ahead()
    {
        return seeds.map(|_| Err(SolverError::Unsupported(format!("the quasi-static skip-ahead: {why}"))));
    }
    let prepared: [_; L] = std::array::from_fn(|l| hooks.prepare(model, seeds[l], options));
    // Failed lanes still occupy a lane: give them a harmless set-up and park them.
    let Some(fallback) = prepared.iter().find_map(|p| p.as_ref().ok().map(|(s, _)| s)) else {
        return prepared.map(|p| p.map(|_| unreachable!("every lane failed")));
    };
    let fallback = prepared.iter().any(|p| p.is_err()).then(|| fallback.clone());
    let (mut setups, prepared): (Vec<LaneSetup>, Vec<Result<CriticalStep, SolverError>>) = prepared
        .into_iter()
        .map(|p| match p {
            Ok((setup, critical)) => (setup, Ok(critical)),
            Err(e) => (fallback.clone().expect("a lane failed"), Err(e)),
        })
        .unzip();
    let mut params = Params::<L>::new(model, setups.as_slice().try_into().expect("one set-up per lane"));
    // The stiffness is the params' now: the lanes' own copies go before the state is allocated
    // (a static settle or the skip-ahead takes its lane's back from the params).
    let dts: Vec<f64> = setups.iter().map(|s| s.dt_s).collect();
    for s in &mut setups {
        s.stiffness = LaneStiffness::Factored(None);
    }
    let mut state = State::<L>::for_params(&params);
    // The checkpoint this run resumes from, if every rank has one of the same step.
    let resumed = checkpoint.and_then(|c| {
        let expected = Header::of(&c.key, &seeds, model, &dts, hooks.place(), 0);
        let found = if prepared.iter().all(Result::is_ok) {
            checkpoint::read::<L>(&c.path, &expected)
                .map_err(|why| {
                    // Kept aside, not overwritten by this run's first checkpoint.
                    let aside = c.path.with_extension("ckpt.unread");
                    let kept = match std::fs::rename(&c.path, &aside) {
                        Ok(()) => format!("kept as {}", aside.display()),
                        Err(e) => format!("could not be kept aside: {e}"),
                    };
                    c.note_failure(format!("{} was not resumed ({kept}): {why}", c.path.display()))
                })
                .ok()
                .flatten()
        } else {
            None
        };
        let at = found.as_ref().map(|(steps, _)| *steps);
        if hooks.resume(at) {
            found.map(|(_, body)| body)
        } else {
            if let Some(step) = at {
                c.note_failure(format!(
                    "{} (step {step}) was not resumed: the other ranks' checkpoints are missing or hold other steps",
                    c.path.display()
                ));
            }
            None
        }
    });
    let mut stepper = Stepper::<L>::new(model);
    let skipping = scene.skip_ahead.enabled && L == 1;
    stepper.set_parallel(options.parallel_step);
    stepper.set_tracking(Tracking { energy: scene.record.energy, onsets: scene.record.slip_onsets, slid: skipping });
    let sw = scene.self_weight;
    // The whole block's bars (a rank of a split scene holds a part): every rank reports, and
    // agrees whether to stop, at the same steps.
    let bars = crate::memory::counts(scene.dims).map_or(model.bar_count() as u64, |(_, b)| b);
    let progress_every = (PROGRESS_BAR_UPDATES / (bars * L as u64).max(1)).clamp(1, PROGRESS_EVERY);
    let weight_norm = hooks.weight_norm(model, sw.gravity_m_s2);
    let mut lanes: [Lane; L] = std::array::from_fn(|l| Lane {
        seed: seeds[l],
        stage: Stage::Settling { max_steps: (sw.max_duration_s / dts[l]).ceil() as u64 },
        critical: None,
        recorder: None,
        settle_steps: 0,
        settled_by: SettleMethod::Dynamic,
        settle_note: None,
        skipper: None,
    });
    for (l, (p, setup)) in prepared.into_iter().zip(setups).enumerate() {
        let lane = &mut lanes[l];
        match p {
            Ok(critical) => {
                lane.critical = Some(critical);
                let dt = setup.dt_s;
                let stride = stride(scene.record.interval_s, dt);
                let shear_steps = whole_steps(scene.shear.duration_s, dt);
                // Reserve for the whole stage, up to a million samples (long runs grow as they go).
                let capacity = (shear_steps / stride).min(1 << 20) as usize + 2;
                lane.recorder = Some(Recorder::new(&scene.record, model, capacity));
                params.set_damping(l, sw.damping_per_s);
                params.set_body_acceleration(l, [0.0, 0.0, -sw.gravity_m_s2]);
                if skipping {
                    lane.skipper = Some(Skipper::new(model, params.lane_stiffness(l), &setup.friction));
                }
                if sw.method == SettleMethod::Static && sw.gravity_m_s2 > 0.0 && resumed.is_none() {
                    match settle_statically(model, &params.lane_stiffness(l), &setup.friction, sw.gravity_m_s2) {
                        Ok(Ok(st)) if let Some(why) = beyond_peak(model, setup.strength.as_deref(), &st.u) => {
                            lane.settle_note = Some(why)
                        }
                        Ok(Ok(st)) => {
                            start_at_rest(&params, &mut state, l, &st.u, &st.reactions);
                            lane.settled_by = SettleMethod::Static;
                            lane.stage = start_shear(&mut params, &mut state, l);
                        }
                        Ok(Err(why)) => lane.settle_note = Some(why),
                        Err(e) => lane.settle_note = Some(e.to_string()),
                    }
                }
            }
            Err(e) => lane.fail(e, &mut params, &mut state, l),
        }
    }
    if let Some(body) = resumed {
        state = body.state;
        for (l, (lane, at)) in lanes.iter_mut().zip(body.lanes).enumerate() {
            lane.stage = match at.stage {
                StageAt::Settling { max_steps } => Stage::Settling { max_steps },
                StageAt::Shearing { origin, steps, stride } => Stage::Shearing { origin, steps, stride },
                StageAt::Done { origin, stride, steps } => Stage::Done { origin, stride, steps },
            };
            if !matches!(lane.stage, Stage::Settling { .. }) {
                params.set_damping(l, scene.shear.damping_per_s);
            }
            lane.critical = at.critical;
            lane.recorder = at.recorder;
            lane.settle_steps = at.settle_steps;
            lane.settled_by = at.settled_by;
            lane.settle_note = at.settle_note;
        }
    } else if sw.gravity_m_s2 == 0.0 {
        // No gravity: nothing to settle.
        for (l, lane) in lanes.iter_mut().enumerate() {
            if matches!(lane.stage, Stage::Settling { .. }) {
                lane.stage = start_shear(&mut params, &mut state, l);
            }
        }
    }

    let mut taken = Due::new(state.steps);
    while lanes.iter().any(|lane| lane.stage.running()) {
        // Driver targets for the step about to compute u_{S+1}.
        let next = state.steps + 1;
        for (l, lane) in lanes.iter().enumerate() {
            if let Stage::Shearing { origin, .. } = lane.stage {
                let t = (next - origin) as f64 * params.dt(l);
                state.loading.target[l] = scene.shear.driver_displacement(t);
                // The step's forces act at the newest level, one step before `next`.
                state.loading.overstress[l] =
                    scene.fault.as_ref().and_then(|f| f.overstress).map_or(0.0, |o| o.ramp(t - params.dt(l)));
            }
        }
        stepper.step(&params, &mut state);
        hooks.after_step(&params, &mut state);
        let view = state.steps - 1;
        for (l, lane) in lanes.iter_mut().enumerate() {
            if !lane.stage.running() {
                continue;
            }
            if view.is_multiple_of(BLOWUP_CHECK_EVERY)
                && let Some((id, what)) =
                    hooks.blowup(&LaneView { params: &params, state: &state, lane: l }, options.parallel_step)
            {
                let (origin, stage_name) = match lane.stage {
                    Stage::Shearing { origin, .. } => (origin, "shear stage"),
                    _ => (0, "self-weight stage"),
                };
                let p = model.lattice().position(id);
                let dt = params.dt(l);
                let crit = lane.critical.map_or(f64::NAN, |c| c.dt_s);
                let e = SolverError::Unstable {
                    step: view,
                    time_s: (view as f64 - origin as f64) * dt,
                    stage: stage_name,
                    what,
                    node: format!("({:.4}, {:.4}, {:.4}) m", p[0], p[1], p[2]),
                    ldem: id.ldem(),
                    dt_s: dt,
                    fraction: dt / crit,
                };
                lane.fail(e, &mut params, &mut state, l);
                continue;
            }
            if let Some(damage) = state.rupture.as_mut()
                && let Some(r) = lane.recorder.as_mut()
            {
                for c in damage.drain(l) {
                    r.crack_steps.push((c.step, crack(model, &params, l, &c)));
                }
            }
            if scene.record.slip_onsets {
                let from = match lane.stage {
                    Stage::Shearing { origin, .. } => Some(origin),
                    Stage::Settling { .. } if scene.record.settling => Some(0),
                    _ => None,
                };
                let contact = model.contact();
                for (step, ci) in state.drain_onsets(l) {
                    if let (Some(from), Some(r)) = (from, lane.recorder.as_mut())
                        && step >= from
                    {
                        r.onset_steps.push((step, model.canonical(contact[ci as usize] as usize)));
                    }
                }
            }
            match lane.stage {
                Stage::Settling { max_steps } => {
                    if scene.record.settling && scene.record.energy {
                        hooks.state_energy(&LaneView { params: &params, state: &state, lane: l });
                    }
                    if scene.record.settling
                        && hooks.records()
                        && let Some(r) = lane.recorder.as_mut()
                    {
                        let shown = Shown {
                            view: LaneView { params: &params, state: &state, lane: l },
                            remote: hooks.remote(),
                        };
                        r.sample_view(&shown, view);
                    }
                    if view.is_multiple_of(SETTLE_CHECK_EVERY) && view > 0 {
                        let ratio =
                            hooks.out_of_balance(&LaneView { params: &params, state: &state, lane: l }) / weight_norm;
                        if ratio < sw.settle_tolerance {
                            lane.settle_steps = state.steps;
                            lane.stage = start_shear(&mut params, &mut state, l);
                        } else if view >= max_steps {
                            let e = SolverError::NotSettled {
                                max_s: sw.max_duration_s,
                                residual: ratio,
                                tolerance: sw.settle_tolerance,
                            };
                            lane.fail(e, &mut params, &mut state, l);
                        }
                    }
                }
                Stage::Shearing { origin, steps, stride } => {
                    let j = view - origin;
                    if let Some(p) = options.perturb
                        && j == (p.at_s / params.dt(l)).ceil().max(0.0) as u64
                    {
                        state.scale_lane(l, 1.0 + p.relative);
                    }
                    let recorder = lane.recorder.as_mut().expect("recorder of a running lane");
                    if j.is_multiple_of(stride) && scene.record.energy {
                        hooks.state_energy(&LaneView { params: &params, state: &state, lane: l });
                    }
                    if hooks.records() {
                        let shown = Shown {
                            view: LaneView { params: &params, state: &state, lane: l },
                            remote: hooks.remote(),
                        };
                        recorder
                            .tracer
                            .get_or_insert_with(|| {
                                Tracer::new(&scene.record.trace, model, origin, params.dt(l), &scene.record.control)
                            })
                            .observe(&shown, view);
                        // Samples on the grid of `stride` steps only (the stage's last step too
                        // when it falls on it), so that a recording is uniform.
                        if j.is_multiple_of(stride) {
                            recorder.sample_view(&shown, view);
                        }
                    }
                    if j >= steps {
                        lane.stage = Stage::Done { origin, stride, steps };
                    } else if let Some(skipper) = lane.skipper.as_mut()
                        && j.is_multiple_of(SKIP_CHECK_EVERY)
                        && options.max_jumps.is_none_or(|m| skipper.stats.jumps < m)
                    {
                        let skip_stride = scene.skip_ahead.record_interval_s.map_or(stride, |iv| {
                            let interval = scene.record.interval_s.unwrap_or(iv);
                            stride * ((iv / interval).round() as u64).max(1)
                        });
                        let clock = ShearClock { origin, end: origin + steps, stride: skip_stride };
                        let track_energy = stepper.tracking().energy;
                        // Long jumps report their progress (and see an interrupt) as they go.
                        let mut keep_going =
                            |s: u64| progress(((s - origin) as f64 / steps as f64).min(1.0)).is_continue();
                        if let Err(e) =
                            skipper.look(&params, &mut state, l, &clock, recorder, track_energy, &mut keep_going)
                        {
                            lane.fail(e, &mut params, &mut state, l);
                        }
                    }
                }
                Stage::Done { .. } | Stage::Failed(_) => {}
            }
        }
        if state.steps.is_multiple_of(progress_every) {
            let fraction = lanes
                .iter()
                .map(|lane| match lane.stage {
                    Stage::Settling { .. } => 0.0,
                    Stage::Shearing { origin, steps, .. } => ((state.steps - origin) as f64 / steps as f64).min(1.0),
                    Stage::Done { .. } | Stage::Failed(_) => 1.0,
                })
                .sum::<f64>()
                / L as f64;
            let due = checkpoint.is_some_and(|c| taken.due(c, state.steps));
            let (stop, save) = hooks.agree(progress(fraction).is_break(), due);
            // Asked to stop, a run that keeps checkpoints writes one: it resumes from here.
            if let Some(c) = checkpoint
                && (save || stop)
                && lanes.iter().all(|lane| !matches!(lane.stage, Stage::Failed(_)))
            {
                match save_checkpoint(c, hooks.place(), model, &seeds, &dts, &state, &lanes) {
                    Ok(()) => taken.taken(state.steps),
                    // Tried again a period later, not at every report.
                    Err(why) => {
                        taken.taken(state.steps);
                        c.note_failure(why)
                    }
                }
            }
            if stop {
                for (l, lane) in lanes.iter_mut().enumerate() {
                    if lane.stage.running() {
                        lane.fail(SolverError::Cancelled, &mut params, &mut state, l);
                    }
                }
            }
        }
    }

    lanes.map(|lane| match lane.stage {
        Stage::Done { origin, stride, steps } => {
            let l = seeds.iter().position(|&s| s == lane.seed).expect("lane of its seed");
            let dt = params.dt(l);
            let recorder = lane.recorder.expect("recorder of a finished lane");
            Ok(RunOutput {
                seed: lane.seed,
                dt_s: dt,
                critical: lane.critical.expect("critical step of a finished lane"),
                settle_time_s: lane.settle_steps as f64 * dt,
                settle_steps: lane.settle_steps,
                shear_steps: steps,
                settled_by: lane.settled_by,
                settle_note: lane.settle_note,
                skip: lane.skipper.as_ref().map_or_else(SkipStats::default, |s| s.stats),
                recording: recorder.finish(origin, dt, stride, model),
                damage: damage(model, &params, &state, l),
            })
        }
        Stage::Failed(e) => Err(e),
        Stage::Settling { .. } | Stage::Shearing { .. } => unreachable!("the loop ends when no lane is running"),
    })
}

/// Writes the checkpoint of the lanes at the state's step.
fn save_checkpoint<const L: usize>(
    c: &Checkpoint,
    place: (usize, usize),
    model: &Model,
    seeds: &[u64; L],
    dts: &[f64],
    state: &State<L>,
    lanes: &[Lane; L],
) -> Result<(), String> {
    let header = Header::of(&c.key, seeds, model, dts, place, state.steps);
    let lanes: Vec<LaneRef<'_>> = lanes
        .iter()
        .map(|lane| LaneRef {
            stage: match lane.stage {
                Stage::Settling { max_steps } => StageAt::Settling { max_steps },
                Stage::Shearing { origin, steps, stride } => StageAt::Shearing { origin, steps, stride },
                Stage::Done { origin, stride, steps } => StageAt::Done { origin, stride, steps },
                Stage::Failed(_) => unreachable!("no checkpoint with a failed lane"),
            },
            critical: lane.critical,
            recorder: lane.recorder.as_ref(),
            settle_steps: lane.settle_steps,
            settled_by: lane.settled_by,
            settle_note: &lane.settle_note,
        })
        .collect();
    checkpoint::write(&c.path, header, &BodyRef { state, lanes: &lanes })
}

/// The bars of lane `l` past their peak, by canonical index, with what the law says they
/// dissipated.
fn damage<const L: usize>(model: &Model, params: &Params<'_, L>, state: &State<L>, l: usize) -> Vec<BarDamage> {
    let (Some(d), Some(law)) = (&state.rupture, &params.rupture) else { return Vec::new() };
    let mut out: Vec<BarDamage> = (0..model.bar_count())
        .filter(|&b| d.secant[b][l] != params.k.per_bar()[b][l])
        .map(|b| {
            let canonical = model.bar_canonical()[b];
            let bar = &model.lattice().bar(canonical as usize);
            let kernel = if bar.family == crate::geometry::BarFamily::Diagonal { 3f64.sqrt() } else { 1.0 };
            let length = bar.length_factor() * model.scene().lc_m;
            let bar_law = BarLaw { k: params.k.per_bar()[b][l], peak: law.peak[b][l], kr: law.kr };
            BarDamage {
                bar: canonical,
                reach_strain: d.reach[b][l] / (kernel * length),
                dissipated_j: bar_law.dissipated(d.reach[b][l]),
                broken: d.secant[b][l] == 0.0,
            }
        })
        .collect();
    out.sort_by_key(|d| d.bar);
    out
}

/// A crack of lane `l` as recorded: canonical bar, strain, energy (docs/model.md §11); the time is
/// set when the recorder finishes.
fn crack<const L: usize>(model: &Model, params: &Params<'_, L>, l: usize, c: &CrackLog) -> Crack {
    let b = c.bar as usize;
    let canonical = model.bar_canonical()[b];
    let bar = &model.lattice().bar(canonical as usize);
    // Kernel units: a diagonal's elongation is stored √3 times, its stiffness a third.
    let kernel = if bar.family == crate::geometry::BarFamily::Diagonal { 3f64.sqrt() } else { 1.0 };
    let length = bar.length_factor() * model.scene().lc_m;
    let law = params.rupture.as_ref().expect("cracks come from the rupture kernel");
    let (k, peak) = (params.k.per_bar()[b][l], law.peak[b][l]);
    let energy_j = match c.kind {
        CrackKind::Soften => 0.5 * k * peak * peak,
        CrackKind::Break => 0.5 * k * peak * (law.kr * peak),
    };
    Crack { time_s: 0.0, bar: canonical, kind: c.kind, strain: c.elongation / (kernel * length), energy_j }
}

/// Why a static self-weight state `u` cannot be used when the bars crack: the first bar it loads
/// past its peak elongation (the static solve is linear elastic).
fn beyond_peak(model: &Model, strength: Option<&[f64]>, u: &Field<1>) -> Option<String> {
    let peak = strength?;
    let p = elongations(model.layout().listed(), u, 0);
    let b = (0..p.len()).find(|&b| p[b] > peak[b])?;
    let bar = &model.lattice().bar(model.bar_canonical()[b] as usize);
    let at = model.lattice().bar_midpoint(bar);
    Some(format!(
        "the static self-weight would load a {} bar at ({:.3}, {:.3}, {:.3}) m past its peak strain; settled dynamically \
         so that it softens as it should",
        bar.family.name(),
        at[0],
        at[1],
        at[2]
    ))
}

/// Puts lane `l` at rest in a static equilibrium `u` (every base node sticking, or lifted where
/// its normal reaction is zero) as if the loads had been applied slowly: gravity's work so far
/// is `½·f·u`, the strain energy.
fn start_at_rest<const L: usize>(
    params: &Params<'_, L>,
    state: &mut State<L>,
    l: usize,
    u: &Field<1>,
    reactions: &Field<1>,
) {
    let model = params.model;
    let contact = model.contact();
    let steps = state.steps;
    state.set_lane(
        l,
        steps,
        |_, i, c| u.c[c][i][0],
        |ci| [0, 1, 2].map(|c| reactions.c[c][contact[ci] as usize][0]),
        |_| 0.0,
        0.0,
    );
    // The law's state at the start of the run (θ₀ of a rate-and-state law; 0, no slip, else).
    for (state, initial) in state.contact.state.iter_mut().zip(params.initial_states()) {
        state[l] = initial[l];
    }
    let b = params.body_acceleration(l);
    let mass = model.mass();
    let work: f64 = (0..model.node_count()).map(|i| (0..3).map(|c| mass[i] * b[c] * u.c[c][i][0]).sum::<f64>()).sum();
    state.energy[l].body_work = 0.5 * work;
}

fn start_shear<const L: usize>(params: &mut Params<'_, L>, state: &mut State<L>, l: usize) -> Stage {
    let model = params.model;
    let scene = model.scene();
    params.set_damping(l, scene.shear.damping_per_s);
    start_drivers(model, state, l);
    let dt = params.dt(l);
    let stride = stride(scene.record.interval_s, dt);
    Stage::Shearing { origin: state.steps, steps: whole_steps(scene.shear.duration_s, dt), stride }
}

/// Steps between two samples: the interval's nearest whole number of steps (Δt does not
/// depend on it).
fn stride(interval_s: Option<f64>, dt: f64) -> u64 {
    interval_s.map_or(1, |iv| ((iv / dt).round() as u64).max(1))
}

/// Steps to cover `duration` (rounded up, ignoring round-off of a duration that is a multiple).
fn whole_steps(duration: f64, dt: f64) -> u64 {
    (duration / dt * (1.0 - 1e-12)).ceil() as u64
}
