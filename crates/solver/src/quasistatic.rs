//! Quasi-static shortcuts: the self-weight equilibrium solved directly, and skip-ahead through
//! the interseismic phase of the shear stage.
//!
//! **Static self-weight.** With every base node held where it stands (all three components),
//! the gravity equilibrium `K·u = f` is one conjugate-gradient solve ([`solve_static`]). It is
//! the state damped settling converges to (base nodes land and stick where they are) if it is
//! admissible: every base node pushes on the base (`N ≥ 0`) and its friction holds it
//! (`|R_t| ≤ μs·N`). Otherwise the run settles dynamically.
//!
//! **Skip-ahead.** With a fixed set of sticking base nodes (held where they are), lifted ones
//! (free) and the driver x prescribed at `d(t)`, the damped equations of motion
//! `M·ü + D·M·u̇ + K·u = f + R` have, for a constant driver velocity `ḋ`, the exact solution
//!
//! `u(t) = u_p + d(t)·g − D·ḋ·h`,  with `K·u_p = f` (held components where they are, driver at
//! its base), `K·g = 0` (driver x = 1, everything else held at 0) and `K·h = M·g` (all held
//! components at 0),
//!
//! and the reactions follow the same combination. The motion is linear in time, so the
//! central-difference scheme reproduces it exactly (its discrete acceleration is zero). The
//! actual state is this motion plus what the last event left ringing, which mass-proportional
//! damping takes away (every mode decays as `e^{−Dt/2}`). When the leftover changes no base
//! node's margin to its next transition by more than `tolerance` of that margin, the run jumps
//! along the motion to `margin_steps` before the first driver displacement at which a sticking
//! node reaches `μs·N`, a normal reaction reaches zero or a lifted node reaches the base, and
//! integrates explicitly from there. The samples in between are the motion's, the energy terms
//! are integrated along it, and the energy of the discarded leftover is booked as damped.

use nalgebra::{Matrix3, Vector3};

use crate::error::SolverError;
use crate::kernel::Field;
use crate::model::Model;
use crate::record::{Observed, Recorder, Transition};
use crate::scene::Kinematic;
use crate::statics::{Prescribed, StaticSolution, solve_static, solve_static_from};
use crate::stepper::{Energy, Interface, Stepper};

/// Relative residual of the static solves.
const CG_TOLERANCE: f64 = 1e-9;
/// Iteration cap of the static solves.
const CG_MAX_ITERATIONS: usize = 200_000;
/// Steps between two looks for a skip.
pub(crate) const SKIP_CHECK_EVERY: u64 = 32;
/// Shortest jump worth making (steps).
const MIN_JUMP: u64 = 64;
/// Skips start once the driver ramp has reached its final velocity to this many rise times
/// (`e^{−15}` ≈ 3e-7 of it left).
const RAMP_RISE_TIMES: f64 = 15.0;

/// The gravity equilibrium of a lane with every base node held.
pub(crate) struct StaticSettle {
    /// Displacements (m).
    pub u: Field<1>,
    /// Reactions `K·u − f` (N).
    pub reactions: Field<1>,
}

/// Solves the self-weight equilibrium with every base node held at its place; `Ok(Err(why))`
/// when it is not admissible (a base node would pull on the base or slide).
pub(crate) fn settle_statically(
    model: &Model,
    stiffness: &[f64],
    friction: &[f64],
    gravity: f64,
) -> Result<Result<StaticSettle, String>, SolverError> {
    let n = model.node_count();
    let mass = model.mass();
    let mut loads = Field::<1>::zeros(n);
    for i in 0..n {
        loads.c[2][i][0] = -mass[i] * gravity;
    }
    let mut prescribed = held_rollers(model, |_, _| 0.0);
    for &node in model.contact() {
        prescribed.extend((0..3).map(|axis| Prescribed { node: node as usize, axis, value: 0.0 }));
    }
    let solution = solve_static(model, stiffness, &loads, &prescribed, CG_TOLERANCE, CG_MAX_ITERATIONS)?;
    let mu_s = model.scene().friction.mu_static;
    for (ci, &node) in model.contact().iter().enumerate() {
        let p = node as usize;
        let r = [0, 1, 2].map(|c| solution.reactions.c[c][p][0]);
        let id = model.canonical(p);
        if r[2] < 0.0 {
            return Ok(Err(format!(
                "base node LDEM {} would pull on the base (normal reaction {:.3e} N)",
                id.ldem(),
                r[2]
            )));
        }
        let (rt, limit) = (r[0].hypot(r[1]), mu_s * friction[ci] * r[2]);
        if rt > limit {
            return Ok(Err(format!(
                "friction would not hold base node LDEM {} (needs {rt:.3e} N, μs·N = {limit:.3e} N)",
                id.ldem()
            )));
        }
    }
    Ok(Ok(StaticSettle { u: solution.u, reactions: solution.reactions }))
}

/// The roller components of the scene, held at `value(node, axis)`.
fn held_rollers(model: &Model, value: impl Fn(usize, usize) -> f64) -> Vec<Prescribed> {
    let mut out = Vec::new();
    for &(node, mask) in model.fixed() {
        for axis in (0..3).filter(|&a| mask[a]) {
            out.push(Prescribed { node: node as usize, axis, value: value(node as usize, axis) });
        }
    }
    out
}

/// What a base node does during a quasi-static motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Contact {
    /// Sticks: held where it is.
    Held,
    /// Off the base.
    Lifted,
}

/// The quasi-static motion of one contact configuration: `u = Σ cₖ·basisₖ` with
/// `c = (1, d, −D·ḋ)`.
struct Motion {
    /// Which contact configuration (states, held positions, driver bases) it belongs to.
    key: Vec<u64>,
    /// `u_p`, `g`, `h`.
    basis: [Field<1>; 3],
    /// Reactions of each basis solution.
    reaction: [Field<1>; 3],
    /// `basisᵢᵀ·K·basisⱼ`.
    gram_k: Matrix3<f64>,
    /// `basisᵢᵀ·M·basisⱼ`.
    gram_m: Matrix3<f64>,
    /// `Σ m·b·basisₖ` (body force times each basis).
    body: Vector3<f64>,
    /// Per contact node.
    state: Vec<Contact>,
    /// Solver iterations of the three solves.
    iterations: usize,
}

impl Motion {
    fn u(&self, c: &Vector3<f64>, i: usize, comp: usize) -> f64 {
        c[0] * self.basis[0].c[comp][i][0] + c[1] * self.basis[1].c[comp][i][0] + c[2] * self.basis[2].c[comp][i][0]
    }

    fn r(&self, c: &Vector3<f64>, i: usize, comp: usize) -> f64 {
        c[0] * self.reaction[0].c[comp][i][0]
            + c[1] * self.reaction[1].c[comp][i][0]
            + c[2] * self.reaction[2].c[comp][i][0]
    }

    /// Reaction `[x, y, normal]` of contact node `ci` (zero when lifted).
    fn contact_reaction(&self, model: &Model, c: &Vector3<f64>, ci: usize) -> [f64; 3] {
        if self.state[ci] == Contact::Lifted {
            return [0.0; 3];
        }
        let p = model.contact()[ci] as usize;
        [0, 1, 2].map(|k| self.r(c, p, k))
    }
}

/// The contact configuration of lane `l` and its key (states, held positions, driver bases,
/// body force, damping); `None` if a base node slid since the last look (`slid`).
fn configuration<const L: usize>(
    stepper: &Stepper<'_, L>,
    l: usize,
    slid: &[bool],
) -> Option<(Vec<u64>, Vec<Contact>)> {
    let model = stepper.model();
    let mut key = Vec::with_capacity(3 * model.contact().len() + 8);
    let mut state = Vec::with_capacity(model.contact().len());
    for (ci, &node) in model.contact().iter().enumerate() {
        let r = stepper.contact_reaction(ci, l);
        if r[2] <= 0.0 {
            key.push(0);
            state.push(Contact::Lifted);
        } else if slid[ci] || stepper.is_slipping(ci, l) {
            return None;
        } else {
            let u = stepper.displacement(node as usize, l);
            key.extend([1, u[0].to_bits(), u[1].to_bits()]);
            state.push(Contact::Held);
        }
    }
    key.extend((0..model.drivers().len()).map(|d| stepper.driver_base(d, l).to_bits()));
    key.extend(stepper.body_acceleration(l).map(f64::to_bits));
    key.push(stepper.damping(l).to_bits());
    Some((key, state))
}

/// Solves the three basis motions of configuration `state` of lane `l`, starting from the
/// previous motion where there is one (a configuration differs from the last by a node or two).
fn build_motion<const L: usize>(
    stepper: &Stepper<'_, L>,
    l: usize,
    stiffness: &[f64],
    (key, state): (Vec<u64>, Vec<Contact>),
    previous: Option<&Motion>,
) -> Result<Motion, SolverError> {
    let model = stepper.model();
    let n = model.node_count();
    let mass = model.mass();
    // Held components at their place (`now`) or at zero, the driver at its base (`now`) or at
    // `driver`.
    let constraints = |now: bool, driver: f64| {
        let mut p = held_rollers(model, |i, a| if now { stepper.displacement(i, l)[a] } else { 0.0 });
        for (ci, &node) in model.contact().iter().enumerate() {
            let u = stepper.displacement(node as usize, l);
            let axes = match state[ci] {
                Contact::Held => 0..3,
                Contact::Lifted => 0..0,
            };
            p.extend(axes.map(|axis| Prescribed {
                node: node as usize,
                axis,
                value: if now && axis < 2 { u[axis] } else { 0.0 },
            }));
        }
        for (d, &node) in model.drivers().iter().enumerate() {
            let value = if now { stepper.driver_base(d, l) } else { driver };
            p.push(Prescribed { node: node as usize, axis: 0, value });
        }
        p
    };
    let b = stepper.body_acceleration(l);
    let mut gravity = Field::<1>::zeros(n);
    for i in 0..n {
        for c in 0..3 {
            gravity.c[c][i][0] = mass[i] * b[c];
        }
    }
    let solve = |loads: &Field<1>, prescribed: &[Prescribed], initial: Option<&Field<1>>| {
        solve_static_from(model, stiffness, loads, prescribed, initial, CG_TOLERANCE, CG_MAX_ITERATIONS)
    };
    // `g` and `h` depend on which nodes are held only, not on where: reuse them when only
    // positions changed (after a slip).
    let same_pattern = previous.filter(|m| m.state == state);
    let mut iterations = 0;
    let (g, h) = match same_pattern {
        Some(m) => (
            StaticSolution {
                u: m.basis[1].clone(),
                reactions: m.reaction[1].clone(),
                iterations: 0,
                relative_residual: 0.0,
            },
            Some(StaticSolution {
                u: m.basis[2].clone(),
                reactions: m.reaction[2].clone(),
                iterations: 0,
                relative_residual: 0.0,
            }),
        ),
        None => (solve(&Field::<1>::zeros(n), &constraints(false, 1.0), previous.map(|m| &m.basis[1]))?, None),
    };
    // The actual displacement is close to u_p + d·g.
    let d_now = stepper.driver_target(l);
    let mut guess = Field::<1>::zeros(n);
    for c in 0..3 {
        for i in 0..n {
            guess.c[c][i][0] = stepper.displacement(i, l)[c] - d_now * g.u.c[c][i][0];
        }
    }
    let up = solve(&gravity, &constraints(true, 0.0), Some(&guess))?;
    let zero = Field::<1>::zeros(n);
    let mut mg = Field::<1>::zeros(n);
    for i in 0..n {
        for c in 0..3 {
            mg.c[c][i][0] = mass[i] * g.u.c[c][i][0];
        }
    }
    let h = match h {
        Some(h) => h,
        None => solve(&mg, &constraints(false, 0.0), previous.map(|m| &m.basis[2]))?,
    };
    iterations += g.iterations + up.iterations + h.iterations;
    let loads = [gravity, zero, mg];
    let basis = [up.u, g.u, h.u];
    let reaction = [up.reactions, g.reactions, h.reactions];
    let dot = |a: &Field<1>, b: &Field<1>, w: Option<&[f64]>| -> f64 {
        let mut s = 0.0;
        for c in 0..3 {
            for i in 0..n {
                s += w.map_or(1.0, |w| w[i]) * a.c[c][i][0] * b.c[c][i][0];
            }
        }
        s
    };
    let mut gram_k = Matrix3::zeros();
    let mut gram_m = Matrix3::zeros();
    let mut body = Vector3::zeros();
    for j in 0..3 {
        // K·basisⱼ = reactionⱼ + loadsⱼ.
        let mut kb = reaction[j].clone();
        for c in 0..3 {
            for i in 0..n {
                kb.c[c][i][0] += loads[j].c[c][i][0];
            }
        }
        for i in 0..3 {
            gram_k[(i, j)] = dot(&basis[i], &kb, None);
            gram_m[(i, j)] = dot(&basis[i], &basis[j], Some(mass));
        }
        body[j] = dot(&loads[0], &basis[j], None);
    }
    let gram_k = 0.5 * (gram_k + gram_k.transpose());
    Ok(Motion { key, basis, reaction, gram_k, gram_m, body, state, iterations })
}

/// Smallest `x > 0` with `a·x² + b·x + c = 0`, if any.
fn first_positive_root(a: f64, b: f64, c: f64) -> Option<f64> {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 {
        return None;
    }
    let roots: Vec<f64> = if a.abs() <= 1e-14 * scale {
        if b == 0.0 { vec![] } else { vec![-c / b] }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            vec![]
        } else {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            if q == 0.0 { vec![0.0] } else { vec![q / a, c / q] }
        }
    };
    roots.into_iter().filter(|&x| x > 0.0 && x.is_finite()).min_by(f64::total_cmp)
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
    pub(crate) fn new(model: &Model, stiffness: Vec<f64>, friction: &[f64]) -> Skipper {
        let scene = model.scene();
        let mu_s = friction.iter().map(|f| f * scene.friction.mu_static).collect();
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
    /// moves the stepper to the end of the jump. Single-lane steppers only.
    pub(crate) fn look<const L: usize>(
        &mut self,
        stepper: &mut Stepper<'_, L>,
        l: usize,
        clock: &ShearClock,
        recorder: &mut Recorder,
    ) -> Result<(), SolverError> {
        assert_eq!(L, 1, "skip-ahead moves the step counter of the whole stepper");
        let model = stepper.model();
        let shear = &model.scene().shear;
        let view = stepper.steps() - 1;
        let dt = stepper.dt(l);
        let t = |s: u64| (s as f64 - clock.origin as f64) * dt;
        let v = shear.driver_velocity(t(view));
        let slid = stepper.take_slid(l);
        if !(v > 0.0) || t(view) < RAMP_RISE_TIMES * shear.rise_time_s || view + MIN_JUMP >= clock.end {
            return Ok(());
        }
        // Cheap tests first: nothing slid, the configuration is the one of the last look, little
        // motion.
        let config = configuration(stepper, l, &slid);
        let key = config.as_ref().map(|(k, _)| k.clone());
        self.same_looks = if key.is_some() && key == self.last_key { self.same_looks + 1 } else { 0 };
        self.last_key = key;
        let known = self.motion.as_ref().is_some_and(|m| Some(&m.key) == self.last_key.as_ref());
        if !(known || self.same_looks >= STABLE_LOOKS)
            || stepper.kinetic_energy(l) > 100.0 * self.rigid_ke_per_v2 * v * v
        {
            return Ok(());
        }
        let config = config.expect("checked above");
        if self.motion.as_ref().is_none_or(|m| m.key != config.0) {
            let motion = build_motion(stepper, l, &self.stiffness, config, self.motion.as_ref())?;
            self.stats.solves += 1;
            self.stats.cg_iterations += motion.iterations as u64;
            self.motion = Some(motion);
            self.looks = 0;
        }
        let motion = self.motion.as_ref().expect("built above");
        let damping = stepper.damping(l);
        let coef = |s: u64| Vector3::new(1.0, shear.driver_displacement(t(s)), -damping * shear.driver_velocity(t(s)));
        let margins = self.margins(stepper, l, motion, &coef(view));
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
        self.jump(stepper, l, motion, view, to, clock, next, &coef, recorder);
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
        stepper: &Stepper<'_, L>,
        l: usize,
        motion: &Motion,
        c: &Vector3<f64>,
    ) -> Vec<[Option<Margin>; 2]> {
        let model = stepper.model();
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
                    let actual = stepper.contact_reaction(ci, l);
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
                    let eps = (stepper.displacement(p, l)[2] - z).abs();
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
        stepper: &mut Stepper<'_, L>,
        l: usize,
        motion: &Motion,
        view: u64,
        to: u64,
        clock: &ShearClock,
        next: Transition,
        coef: &impl Fn(u64) -> Vector3<f64>,
        recorder: &mut Recorder,
    ) {
        let model = stepper.model();
        let dt = stepper.dt(l);
        let damping = stepper.damping(l);
        let kinetic = |a: &Vector3<f64>, b: &Vector3<f64>| 0.5 * (b - a).dot(&(motion.gram_m * (b - a))) / (dt * dt);
        let elastic = |a: &Vector3<f64>, b: &Vector3<f64>| 0.5 * a.dot(&(motion.gram_k * b));
        let driver_r =
            |c: &Vector3<f64>| model.drivers().iter().map(|&d| motion.r(c, d as usize, 0)).collect::<Vec<_>>();
        let driver_x = |c: &Vector3<f64>| model.drivers().first().map_or(0.0, |&d| motion.u(c, d as usize, 0));
        let mut acc = *stepper.energy_accumulators(l);
        let track = stepper.tracks_energy();
        if track {
            // Hand-over at `view`: the leftover's energy counts as damped, gravity's work along
            // the jump from the actual state to the motion's is added.
            let (c0, c1) = (coef(view), coef(view + 1));
            let e = stepper.energy(l);
            let mass = model.mass();
            let b = stepper.body_acceleration(l);
            let mut actual = 0.0;
            for i in 0..model.node_count() {
                let (u0, u1) = (stepper.displacement(i, l), stepper.newest().get(i, l));
                for k in 0..3 {
                    actual += mass[i] * b[k] * (u0[k] + u1[k]);
                }
            }
            let body_jump = 0.5 * ((c0 + c1).dot(&motion.body) - actual);
            acc.body_work += body_jump;
            acc.damping += e.kinetic + e.elastic - kinetic(&c0, &c1) - elastic(&c0, &c1) + body_jump;
        }
        for s in view + 1..=to {
            let (cm, c, cp) = (coef(s - 1), coef(s), coef(s + 1));
            if track {
                let d2 = cp - cm;
                acc.damping += damping / (4.0 * dt) * d2.dot(&(motion.gram_m * d2));
                acc.body_work += 0.5 * d2.dot(&motion.body);
                let dx = driver_x(&cp) - driver_x(&cm);
                acc.driver_work += 0.5 * driver_r(&c).iter().sum::<f64>() * dx;
            }
            if (s - clock.origin).is_multiple_of(clock.stride) {
                let shown = MotionView {
                    model,
                    motion,
                    c: [cm, c, cp],
                    dt,
                    acc,
                    kinetic: kinetic(&c, &cp),
                    elastic: elastic(&c, &cp),
                };
                recorder.sample_view(&shown, s);
            }
        }
        recorder.skip_steps.push((view, to, next));
        let (cm, c, cp) = (coef(to - 1), coef(to), coef(to + 1));
        let cs = [cm, c, cp];
        let dr = driver_r(&c);
        let target = cp[1];
        stepper.set_state(
            l,
            to + 1,
            |k, i, comp| motion.u(&cs[(k + 1) as usize], i, comp),
            |ci| motion.contact_reaction(model, &c, ci),
            |d| dr[d],
            target,
        );
        *stepper.energy_accumulators(l) = acc;
    }
}

/// The quasi-static motion at one step, as a recorder sees it.
struct MotionView<'a> {
    model: &'a Model,
    motion: &'a Motion,
    /// Coefficients at the step before, the step, the step after.
    c: [Vector3<f64>; 3],
    dt: f64,
    acc: Energy,
    kinetic: f64,
    elastic: f64,
}

impl Observed for MotionView<'_> {
    fn interface(&self) -> Interface {
        let contact = self.model.contact();
        let m = self.motion;
        let [cm, c, cp] = &self.c;
        let mut s = Interface { max_slip_rate: f64::NEG_INFINITY, ..Interface::default() };
        for (ci, &node) in contact.iter().enumerate() {
            let p = node as usize;
            let r = m.contact_reaction(self.model, c, ci);
            s.friction_x += r[0];
            s.normal += r[2];
            s.mean_slip += m.u(c, p, 0);
            let v = (m.u(cp, p, 0) - m.u(cm, p, 0)) * 0.5 / self.dt;
            s.mean_slip_rate += v;
            s.max_slip_rate = s.max_slip_rate.max(v);
            s.lifted += usize::from(m.state[ci] == Contact::Lifted);
        }
        let n = contact.len() as f64;
        s.mean_slip /= n;
        s.mean_slip_rate /= n;
        s
    }

    fn driver_force(&self) -> f64 {
        self.model.drivers().iter().map(|&d| self.motion.r(&self.c[1], d as usize, 0)).sum()
    }

    fn driver_target(&self) -> f64 {
        self.c[2][1]
    }

    fn energy(&self) -> Energy {
        Energy { kinetic: self.kinetic, elastic: self.elastic, ..self.acc }
    }

    fn kinematic(&self, node: usize, q: Kinematic) -> [f64; 3] {
        let m = self.motion;
        let [cm, c, cp] = &self.c;
        [0, 1, 2].map(|k| match q {
            Kinematic::Displacement => m.u(c, node, k),
            Kinematic::Velocity => (m.u(cp, node, k) - m.u(cm, node, k)) * 0.5 / self.dt,
            Kinematic::Acceleration => {
                (m.u(cp, node, k) - 2.0 * m.u(c, node, k) + m.u(cm, node, k)) / (self.dt * self.dt)
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::first_positive_root;

    #[test]
    fn roots() {
        // (x − 2)(x − 3)
        assert_eq!(first_positive_root(1.0, -5.0, 6.0), Some(2.0));
        // (x + 1)(x − 4)
        assert_eq!(first_positive_root(1.0, -3.0, -4.0), Some(4.0));
        // linear 2x − 1
        assert_eq!(first_positive_root(0.0, 2.0, -1.0), Some(0.5));
        assert_eq!(first_positive_root(1.0, 0.0, 1.0), None);
        assert_eq!(first_positive_root(0.0, 1.0, 1.0), None);
    }
}
