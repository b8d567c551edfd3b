//! Skip-ahead through the interseismic phase: jump along the quasi-static motion while what the
//! last event left ringing cannot change the next transition by more than the tolerance.

use nalgebra::Vector3;

use crate::error::SolverError;
use crate::model::Model;
use crate::quasistatic::motion::{Contact, Motion, MotionView, build_motion, configuration, first_positive_root};
use crate::quasistatic::{MIN_JUMP, RAMP_RISE_TIMES};
use crate::recording::{Recorder, Transition};
use crate::step::{LaneView, Params, State};

/// Steps between two looks for a skip.
pub(crate) const SKIP_CHECK_EVERY: u64 = 32;

/// A jump: from the viewed step `view` to `to`, with the transition predicted after it.
#[derive(Clone, Copy, Debug)]
struct JumpSpan {
    view: u64,
    to: u64,
    next: Transition,
}

/// What the skip-ahead did in one run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SkipStats {
    /// Steps not integrated.
    pub skipped_steps: u64,
    /// Jumps made.
    pub jumps: u64,
    /// Quasi-static motions solved (up to three static solves each: g and h are reused while
    /// the same nodes are held).
    pub solves: u64,
    /// Conjugate-gradient iterations of those solves.
    pub cg_iterations: u64,
}

/// The skip-ahead of one single-lane run.
pub(crate) struct Skipper {
    stiffness: Vec<f64>,
    mu_s: Vec<f64>,
    tolerance: f64,
    margin: u64,
    motion: Option<Motion>,
    /// Configuration at the previous look, and at how many looks in a row it was seen (a
    /// motion is solved only for one that lasts).
    last_key: Option<Vec<u64>>,
    same_looks: u32,
    /// Per contact node, the largest leftover seen in this configuration, decayed to
    /// `amp_time` (`[friction or height, normal]`).
    amp: Vec<[f64; 2]>,
    amp_time: f64,
    /// Looks at the current motion.
    looks: u32,
    /// Kinetic energy of the rigid block per unit velocity squared (J·s²/m²).
    rigid_ke_per_v2: f64,
    /// What it did so far.
    pub(crate) stats: SkipStats,
}

/// Where the shear stage of a lane is, for the skip-ahead.
pub(crate) struct ShearClock {
    /// Step index of shear time zero.
    pub origin: u64,
    /// Last step of the stage (view index).
    pub end: u64,
    /// Steps between samples while skipping (a multiple of the record stride).
    pub stride: u64,
}

/// Steps of a jump between two questions whether to go on (an interrupt ends a jump there).
const JUMP_POLL: u64 = 1 << 22;
/// Looks at one motion before trusting its leftover amplitude (they span
/// `MIN_LOOKS·SKIP_CHECK_EVERY` steps, a few periods of the block's slowest modes).
const MIN_LOOKS: u32 = 8;
/// Looks a configuration must last before its motion is solved.
const STABLE_LOOKS: u32 = 8;
/// Safety factor on the leftover seen at the looks (which may have caught it away from its
/// peaks).
const AMPLITUDE_SAFETY: f64 = 3.0;

/// One margin of a base node to a transition.
struct Margin {
    /// Margin now (N for forces, m for heights), > 0.
    now: f64,
    /// Leftover amplitude on it.
    leftover: f64,
    /// Driver displacement to the transition (m), infinite if never.
    to: f64,
    transition: Transition,
}

impl Margin {
    /// A margin that is never used up.
    fn free() -> Margin {
        Margin { now: 1.0, leftover: 0.0, to: f64::INFINITY, transition: Transition::End }
    }
}

impl Skipper {
    /// The skip-ahead of one lane with bar stiffness `stiffness` and friction factors `friction`.
    pub(crate) fn new(model: &Model, stiffness: Vec<f64>, friction: &[f64]) -> Skipper {
        let scene = model.scene();
        let mu_s = friction.iter().enumerate().map(|(c, &f)| model.node_friction(c, f).static_coefficient()).collect();
        Skipper {
            stiffness,
            mu_s,
            tolerance: scene.skip_ahead.tolerance,
            margin: scene.skip_ahead.margin_steps,
            motion: None,
            last_key: None,
            same_looks: 0,
            amp: vec![[0.0; 2]; model.contact().len()],
            amp_time: 0.0,
            looks: 0,
            rigid_ke_per_v2: 0.5 * model.total_mass(),
            stats: SkipStats::default(),
        }
    }

    /// Looks at lane `l` at its viewed step and, if the quasi-static motion is reached and the
    /// next transition is far enough, jumps: records the skipped samples into `recorder` and
    /// moves the lane's state to the end of the jump. Single-lane states only.
    #[allow(clippy::too_many_arguments)] // the lane's state and recording, and the run's interrupt
    pub(crate) fn look<const L: usize>(
        &mut self,
        params: &Params<'_, L>,
        state: &mut State<L>,
        l: usize,
        clock: &ShearClock,
        recorder: &mut Recorder,
        track_energy: bool,
        keep_going: &mut dyn FnMut(u64) -> bool,
    ) -> Result<(), SolverError> {
        assert_eq!(L, 1, "skip-ahead moves the step counter of the whole state");
        let model = params.model;
        let shear = &model.scene().shear;
        let view = state.steps - 1;
        let dt = params.dt(l);
        let t = |s: u64| (s as f64 - clock.origin as f64) * dt;
        let v = shear.driver_velocity(t(view));
        let slid = state.log.take_slid(l);
        if !(v > 0.0) || t(view) < RAMP_RISE_TIMES * shear.rise_time_s || view + MIN_JUMP >= clock.end {
            return Ok(());
        }
        // Cheap tests first: nothing slid, the configuration is the one of the last look, little
        // motion.
        let config = configuration(params, state, l, &slid);
        let key = config.as_ref().map(|(k, _)| k.clone());
        self.same_looks = if key.is_some() && key == self.last_key { self.same_looks + 1 } else { 0 };
        self.last_key = key;
        let known = self.motion.as_ref().is_some_and(|m| Some(&m.key) == self.last_key.as_ref());
        if !(known || self.same_looks >= STABLE_LOOKS)
            || (LaneView { params, state: &*state, lane: l }).kinetic_energy() > 100.0 * self.rigid_ke_per_v2 * v * v
        {
            return Ok(());
        }
        let config = config.expect("checked above");
        if self.motion.as_ref().is_none_or(|m| m.key != config.0) {
            let motion = build_motion(params, state, l, &self.stiffness, config, self.motion.as_ref())?;
            self.stats.solves += 1;
            self.stats.cg_iterations += motion.iterations as u64;
            self.motion = Some(motion);
            self.looks = 0;
        }
        let motion = self.motion.as_ref().expect("built above");
        let damping = params.damping(l);
        let coef = |s: u64| Vector3::new(1.0, shear.driver_displacement(t(s)), -damping * shear.driver_velocity(t(s)));
        let margins = self.margins(params, state, l, motion, &coef(view));
        // Track the leftover amplitude per node, decaying as damping takes it.
        let decay = if self.looks == 0 { 0.0 } else { (-0.5 * damping * (t(view) - self.amp_time)).exp() };
        for (amp, now) in self.amp.iter_mut().zip(&margins) {
            for k in 0..2 {
                amp[k] = (amp[k] * decay).max(now[k].as_ref().map_or(0.0, |m| m.leftover));
            }
        }
        self.amp_time = t(view);
        self.looks += 1;
        if self.looks < MIN_LOOKS {
            return Ok(());
        }
        let Some((delta, next)) = self.plan(&margins, v, damping) else { return Ok(()) };
        let to = match next {
            Transition::End => clock.end - 1,
            _ => {
                let steps = (delta / (v * dt)).floor();
                if !steps.is_finite() || steps < (self.margin + MIN_JUMP) as f64 {
                    return Ok(());
                }
                (view + steps as u64 - self.margin).min(clock.end - 1)
            }
        };
        if to < view + MIN_JUMP {
            return Ok(());
        }
        let to =
            self.jump(params, state, l, JumpSpan { view, to, next }, clock, &coef, recorder, track_energy, keep_going);
        self.stats.jumps += 1;
        self.stats.skipped_steps += to - view;
        self.last_key = None;
        self.same_looks = 0;
        self.looks = 0;
        Ok(())
    }

    /// The margins of every base node (`[friction or height, normal]`), `None` where a margin
    /// is already used up (the motion is not admissible: no jump).
    fn margins<const L: usize>(
        &self,
        params: &Params<'_, L>,
        state: &State<L>,
        l: usize,
        motion: &Motion,
        c: &Vector3<f64>,
    ) -> Vec<[Option<Margin>; 2]> {
        let model = params.model;
        let unit = Vector3::new(0.0, 1.0, 0.0);
        let linear = |m: f64, rate: f64| if rate < 0.0 { -m / rate } else { f64::INFINITY };
        model
            .contact()
            .iter()
            .enumerate()
            .map(|(ci, &node)| {
                let p = node as usize;
                let id = model.canonical(p);
                if motion.state[ci] == Contact::Held {
                    let r = motion.contact_reaction(model, c, ci);
                    let rg = motion.contact_reaction(model, &unit, ci);
                    let actual = state.contact_reaction(ci, l);
                    let mu = self.mu_s[ci];
                    let (n, ng) = (r[2], rg[2]);
                    let rt = r[0].hypot(r[1]);
                    let eps_n = (actual[2] - n).abs();
                    let eps_t = (actual[0] - r[0]).hypot(actual[1] - r[1]);
                    let a = rg[0] * rg[0] + rg[1] * rg[1] - mu * mu * ng * ng;
                    let b = 2.0 * (r[0] * rg[0] + r[1] * rg[1] - mu * mu * n * ng);
                    let cc = rt * rt - mu * mu * n * n;
                    let friction = (mu * n - rt > 0.0).then(|| Margin {
                        now: mu * n - rt,
                        leftover: eps_t + mu * eps_n,
                        to: first_positive_root(a, b, cc).unwrap_or(f64::INFINITY),
                        transition: Transition::Slide(id),
                    });
                    let normal = (n > 0.0).then(|| Margin {
                        now: n,
                        leftover: eps_n,
                        to: linear(n, ng),
                        transition: Transition::Lift(id),
                    });
                    [friction, normal]
                } else {
                    let z = motion.u(c, p, 2);
                    let gz = motion.u(&unit, p, 2);
                    let eps = (state.displacement(p, l)[2] - z).abs();
                    let height = (z > 0.0).then(|| Margin {
                        now: z,
                        leftover: eps,
                        to: linear(z, gz),
                        transition: Transition::Land(id),
                    });
                    [height, Some(Margin::free())]
                }
            })
            .collect()
    }

    /// The next transition `(driver displacement to it, which)`, if the leftover (amplitudes
    /// in `self.amp`, times [`AMPLITUDE_SAFETY`]) can be dropped: it must stay below half of
    /// every margin on the way, and by the time a node reaches its transition the leftover the
    /// full integration would still carry must be below `tolerance` of its margin now, so the
    /// transition time moves by less than that fraction of the time to it.
    fn plan(&self, margins: &[[Option<Margin>; 2]], v: f64, damping: f64) -> Option<(f64, Transition)> {
        let mut best = (f64::INFINITY, Transition::End);
        for (node, amp) in margins.iter().zip(&self.amp) {
            for (m, &a) in node.iter().zip(amp) {
                let m = m.as_ref()?;
                let a = AMPLITUDE_SAFETY * a;
                if a > 0.5 * m.now {
                    return None;
                }
                if m.to.is_finite() {
                    let time = m.to / v;
                    if a * (-0.5 * damping * time).exp() > self.tolerance * m.now {
                        return None;
                    }
                    // Not triggered early on the way (margin taken as falling linearly).
                    for k in 1..8 {
                        let f = f64::from(k) / 8.0;
                        if a * (-0.5 * damping * f * time).exp() > 0.5 * m.now * (1.0 - f) {
                            return None;
                        }
                    }
                    if m.to < best.0 {
                        best = (m.to, m.transition);
                    }
                }
            }
        }
        Some(best)
    }

    #[allow(clippy::too_many_arguments)]
    fn jump<const L: usize>(
        &self,
        params: &Params<'_, L>,
        state: &mut State<L>,
        l: usize,
        JumpSpan { view, to: planned, next }: JumpSpan,
        clock: &ShearClock,
        coef: &impl Fn(u64) -> Vector3<f64>,
        recorder: &mut Recorder,
        track: bool,
        keep_going: &mut dyn FnMut(u64) -> bool,
    ) -> u64 {
        let motion: &Motion = self.motion.as_ref().expect("a jump follows a motion");
        let model = params.model;
        let dt = params.dt(l);
        let damping = params.damping(l);
        let kinetic = |a: &Vector3<f64>, b: &Vector3<f64>| 0.5 * (b - a).dot(&(motion.gram_m * (b - a))) / (dt * dt);
        let elastic = |a: &Vector3<f64>, b: &Vector3<f64>| 0.5 * a.dot(&(motion.gram_k * b));
        let driver_r =
            |c: &Vector3<f64>| model.drivers().iter().map(|&d| motion.r(c, d as usize, 0)).collect::<Vec<_>>();
        let driver_x = |c: &Vector3<f64>| model.drivers().first().map_or(0.0, |&d| motion.u(c, d as usize, 0));
        let mut acc = state.energy[l];
        if track {
            // Hand-over at `view`: the leftover's energy counts as damped, gravity's work along
            // the jump from the actual state to the motion's is added.
            let (c0, c1) = (coef(view), coef(view + 1));
            let e = LaneView { params, state: &*state, lane: l }.energy();
            let mass = model.mass();
            let b = params.body_acceleration(l);
            let mut actual = 0.0;
            for i in 0..model.node_count() {
                let (u0, u1) = (state.displacement(i, l), state.u.np1.get(i, l));
                for k in 0..3 {
                    actual += mass[i] * b[k] * (u0[k] + u1[k]);
                }
            }
            let body_jump = 0.5 * ((c0 + c1).dot(&motion.body) - actual);
            acc.body_work += body_jump;
            acc.damping += e.kinetic + e.elastic - kinetic(&c0, &c1) - elastic(&c0, &c1) + body_jump;
        }
        // A jump walks every step it skips (energy sums, samples): over a very slow loading that
        // is billions of steps, so it asks every `JUMP_POLL` steps whether to go on, and an
        // interrupt ends it where it is (the run then stops at its next progress check).
        let mut to = planned;
        for s in view + 1..=planned {
            let (cm, c, cp) = (coef(s - 1), coef(s), coef(s + 1));
            if track {
                let d2 = cp - cm;
                acc.damping += damping / (4.0 * dt) * d2.dot(&(motion.gram_m * d2));
                acc.body_work += 0.5 * d2.dot(&motion.body);
                let dx = driver_x(&cp) - driver_x(&cm);
                acc.driver_work += 0.5 * driver_r(&c).iter().sum::<f64>() * dx;
            }
            let traced = recorder.tracer.as_ref().is_some_and(|t| t.on_grid(s));
            let sampled = (s - clock.origin).is_multiple_of(clock.stride);
            if traced || sampled {
                let shown = MotionView {
                    model,
                    motion,
                    c: [cm, c, cp],
                    dt,
                    acc,
                    kinetic: kinetic(&c, &cp),
                    elastic: elastic(&c, &cp),
                };
                if sampled {
                    recorder.sample_view(&shown, s);
                }
                if traced && let Some(t) = recorder.tracer.as_mut() {
                    t.observe(&shown, s);
                }
            }
            // Step `s` is complete (its energy and sample): the jump may end here.
            if s < planned && (s - view).is_multiple_of(JUMP_POLL) && !keep_going(s) {
                to = s;
                break;
            }
        }
        recorder.skip_steps.push((view, to, next));
        let (cm, c, cp) = (coef(to - 1), coef(to), coef(to + 1));
        let cs = [cm, c, cp];
        let dr = driver_r(&c);
        let target = cp[1];
        state.set_lane(
            l,
            to + 1,
            |k, i, comp| motion.u(&cs[(k + 1) as usize], i, comp),
            |ci| motion.contact_reaction(model, &c, ci),
            |d| dr[d],
            target,
        );
        state.energy[l] = acc;
        to
    }
}
