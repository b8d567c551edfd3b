//! Explicit central differences with mass-proportional damping, rollers, drivers and the
//! frictional base (SPEC §2, §4), advancing `L` seeds side by side.
//!
//! One step, in this order: `bar_forces → integrate (trial) → rollers → drivers → contact →
//! energy (if tracked) → commit` (on cache-blocked lattices the first two are one pass: each
//! node is integrated right after its last bar). The trial update is
//! `u⁺ = [Δt²(f/m + b) + 2u − (1 − DΔt/2)u⁻] / (1 + DΔt/2)`; every constraint then replaces the
//! trial value of its component and its reaction `R = m(1 + DΔt/2)/Δt² · (u_constrained − u⁺)` is
//! exactly the force that makes the update satisfy the constraint.
//!
//! Contact (per contact node and lane): a trial below the base (`z < 0`) is put back on it with a
//! normal reaction `N ≥ 0`; a node above it is lifted (`N = 0`, no friction work). A node in
//! contact sticks if the tangential reaction needed to hold it still, `|R_t|`, is at most
//! `μ·N` (μs when it was sticking, the current kinetic μ when it was sliding); otherwise it slides
//! with a friction force `μ_k·N` opposing the trial motion, `μ_k` falling linearly from μs to μd
//! over a slip of `Dc` (slip-weakening; `Dc = 0` drops at once). A sliding node whose needed
//! reaction falls within `μ_k·N` would reverse within the step, so it sticks again (and heals).
//!
//! After [`Stepper::step`] has committed step `n` (computing `uₙ₊₁`), the stepper *views* time
//! `n`: displacement `uₙ`, velocity `(uₙ₊₁ − uₙ₋₁)/2Δt`, acceleration `(uₙ₊₁ − 2uₙ + uₙ₋₁)/Δt²`,
//! reactions `Rₙ`, kinetic energy `½m|uₙ₊₁ − uₙ|²/Δt²` and strain energy `½uₙᵀKuₙ₊₁` (the pair
//! the scheme conserves exactly, so the recorded energy balance closes to round-off).

use rayon::prelude::*;

use crate::kernel::{Field, Lanes, bar_forces, bar_forces_finishing, bar_forces_parallel, strain_energy, widest};
use crate::model::Model;

/// Steps a contact node must slide in a row for its slip to count as an onset.
pub const SUSTAINED_SLIP_STEPS: u32 = 10;

/// Per-lane set-up of a stepper.
#[derive(Clone, Debug)]
pub struct LaneSetup {
    /// Time step (s).
    pub dt_s: f64,
    /// Kernel stiffness per bar (internal order), e.g. [`Model::bar_stiffness`].
    pub stiffness: Vec<f64>,
    /// Friction factor per contact node, e.g. [`Model::friction_factors`].
    pub friction: Vec<f64>,
}

/// Cumulative energy terms of one lane (J), all measured from the start of the run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Energy {
    /// `½ Σ m|uₙ₊₁ − uₙ|²/Δt²`.
    pub kinetic: f64,
    /// `½ uₙᵀ K uₙ₊₁`.
    pub elastic: f64,
    /// Dissipated by mass-proportional damping.
    pub damping: f64,
    /// Dissipated by base friction.
    pub friction: f64,
    /// Lost in inelastic landings on the base.
    pub impact: f64,
    /// Work of body forces (gravity, body-force loads).
    pub body_work: f64,
    /// Work of the drivers.
    pub driver_work: f64,
}

impl Energy {
    /// Body plus driver work.
    pub fn external_work(&self) -> f64 {
        self.body_work + self.driver_work
    }

    /// External work minus everything stored and dissipated (zero up to round-off).
    pub fn residual(&self) -> f64 {
        self.external_work() - (self.kinetic + self.elastic + self.damping + self.friction + self.impact)
    }
}

/// Interface resultants of one lane at the viewed time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Interface {
    /// Σ of the friction reactions in x (N); the base resists a +x push with a negative sum.
    pub friction_x: f64,
    /// Σ of the normal reactions (N).
    pub normal: f64,
    /// Mean x-displacement of the contact nodes (m).
    pub mean_slip: f64,
    /// Mean x-velocity of the contact nodes (m/s).
    pub mean_slip_rate: f64,
    /// Max x-velocity of the contact nodes (m/s).
    pub max_slip_rate: f64,
    /// Sliding contact nodes.
    pub slipping: usize,
    /// Lifted contact nodes.
    pub lifted: usize,
}

/// What the stability check found.
#[derive(Clone, Debug, PartialEq)]
pub struct Blowup {
    /// Internal node index.
    pub node: usize,
    /// Description.
    pub what: String,
}

/// The state and scratch of `L` seeds advancing together through one model.
pub struct Stepper<'m, const L: usize> {
    model: &'m Model,
    k: Vec<Lanes<L>>,
    /// `uₙ₋₁` after a commit; scratch for the trial during a step.
    older: Field<L>,
    /// `uₙ` after a commit.
    prev: Field<L>,
    /// `uₙ₊₁` after a commit.
    cur: Field<L>,
    force: Field<L>,
    dt: Lanes<L>,
    damping: Lanes<L>,
    body: [Lanes<L>; 3],
    cf: Lanes<L>,
    c2: Lanes<L>,
    cp: Lanes<L>,
    mu_s: Vec<Lanes<L>>,
    mu_d: Vec<Lanes<L>>,
    dc: f64,
    slipping: Vec<[bool; L]>,
    /// Consecutive steps each contact node has been sliding.
    slip_run: Vec<[u32; L]>,
    /// Sustained slip onsets `(step, contact index)` per lane since the last drain.
    onsets: [Vec<(u64, u32)>; L],
    track_onsets: bool,
    /// Whether each contact node slid in any step since the last [`Stepper::take_slid`].
    slid: Vec<[bool; L]>,
    track_slid: bool,
    slip_path: Vec<Lanes<L>>,
    /// Contact reactions: friction x, friction y, normal.
    reaction: [Vec<Lanes<L>>; 3],
    driver_on: [bool; L],
    driver_target: Lanes<L>,
    driver_base: Vec<Lanes<L>>,
    driver_reaction: Vec<Lanes<L>>,
    track_energy: bool,
    parallel: bool,
    acc: [Energy; L],
    steps: u64,
}

impl<'m, const L: usize> Stepper<'m, L> {
    /// A stepper at rest (`u = 0`) with no damping, no body force and drivers off.
    pub fn new(model: &'m Model, lanes: &[LaneSetup; L]) -> Self {
        let n = model.node_count();
        let nb = model.bar_count();
        let nc = model.contact().len();
        let mut k = vec![[0.0; L]; nb];
        for (l, lane) in lanes.iter().enumerate() {
            assert_eq!(lane.stiffness.len(), nb, "one stiffness per bar");
            assert_eq!(lane.friction.len(), nc, "one friction factor per contact node");
            for (kb, &v) in k.iter_mut().zip(&lane.stiffness) {
                kb[l] = v;
            }
        }
        let f = model.scene().friction;
        let mut mu_s = vec![[0.0; L]; nc];
        let mut mu_d = vec![[0.0; L]; nc];
        for (l, lane) in lanes.iter().enumerate() {
            for c in 0..nc {
                mu_s[c][l] = f.mu_static * lane.friction[c];
                mu_d[c][l] = f.mu_dynamic * lane.friction[c];
            }
        }
        let nd = model.drivers().len();
        let mut s = Stepper {
            model,
            k,
            older: Field::zeros(n),
            prev: Field::zeros(n),
            cur: Field::zeros(n),
            force: Field::zeros(n),
            dt: lanes.each_ref().map(|lane| lane.dt_s),
            damping: [0.0; L],
            body: [[0.0; L]; 3],
            cf: [0.0; L],
            c2: [0.0; L],
            cp: [0.0; L],
            mu_s,
            mu_d,
            dc: f.slip_weakening_m,
            slipping: vec![[false; L]; nc],
            slip_run: vec![[0; L]; nc],
            onsets: std::array::from_fn(|_| Vec::new()),
            track_onsets: false,
            slid: vec![[false; L]; nc],
            track_slid: false,
            slip_path: vec![[0.0; L]; nc],
            reaction: [vec![[0.0; L]; nc], vec![[0.0; L]; nc], vec![[0.0; L]; nc]],
            driver_on: [false; L],
            driver_target: [0.0; L],
            driver_base: vec![[0.0; L]; nd],
            driver_reaction: vec![[0.0; L]; nd],
            track_energy: false,
            parallel: false,
            acc: [Energy::default(); L],
            steps: 0,
        };
        for l in 0..L {
            s.update_coefficients(l);
        }
        s
    }

    fn update_coefficients(&mut self, l: usize) {
        let dt = self.dt[l];
        let a = 0.5 * self.damping[l] * dt;
        self.cf[l] = dt * dt / (1.0 + a);
        self.c2[l] = 2.0 / (1.0 + a);
        self.cp[l] = (1.0 - a) / (1.0 + a);
    }

    /// The model.
    pub fn model(&self) -> &'m Model {
        self.model
    }

    /// Committed steps.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Time step of lane `l` (s).
    pub fn dt(&self, l: usize) -> f64 {
        self.dt[l]
    }

    /// Mass-proportional damping of lane `l` (1/s).
    pub fn damping(&self, l: usize) -> f64 {
        self.damping[l]
    }

    /// Sets the mass-proportional damping D (1/s) of lane `l`.
    pub fn set_damping(&mut self, l: usize, d: f64) {
        self.damping[l] = d;
        self.update_coefficients(l);
    }

    /// Sets the body acceleration (m/s², e.g. gravity `[0, 0, −g]`) of lane `l`.
    pub fn set_body_acceleration(&mut self, l: usize, b: [f64; 3]) {
        for (c, v) in b.into_iter().enumerate() {
            self.body[c][l] = v;
        }
    }

    /// Body acceleration of lane `l`.
    pub fn body_acceleration(&self, l: usize) -> [f64; 3] {
        [self.body[0][l], self.body[1][l], self.body[2][l]]
    }

    /// Turns on the drivers of lane `l`: from now on their x is held at the newest x plus the
    /// target set by [`Stepper::set_driver_target`].
    pub fn start_drivers(&mut self, l: usize) {
        self.driver_on[l] = true;
        self.driver_target[l] = 0.0;
        for (d, &node) in self.model.drivers().iter().enumerate() {
            self.driver_base[d][l] = self.cur.c[0][node as usize][l];
        }
    }

    /// Sets, for the next step of lane `l`, the driver displacement (m) relative to where the
    /// drivers were when started.
    pub fn set_driver_target(&mut self, l: usize, target: f64) {
        self.driver_target[l] = target;
    }

    /// Splits each step over the current rayon pool (the numbers do not change: see
    /// [`crate::kernel::bar_forces_parallel`]). Worth it for large lattices only.
    pub fn set_parallel(&mut self, on: bool) {
        self.parallel = on;
    }

    /// Turns on (or off) the recording of sustained slip onsets (see [`Stepper::drain_onsets`]).
    pub fn set_track_onsets(&mut self, on: bool) {
        self.track_onsets = on;
    }

    /// Takes the sustained slip onsets of lane `l` recorded since the last call: `(step,
    /// contact index)`, the step being the first of a run of [`SUSTAINED_SLIP_STEPS`] sliding
    /// steps (shorter flickers of a node at its strength are not onsets).
    pub fn drain_onsets(&mut self, l: usize) -> std::vec::Drain<'_, (u64, u32)> {
        self.onsets[l].drain(..)
    }

    /// Turns on (or off) the tracking of which contact nodes slid between two calls of
    /// [`Stepper::take_slid`].
    pub(crate) fn set_track_slid(&mut self, on: bool) {
        self.track_slid = on;
    }

    /// Which contact nodes of lane `l` slid since the last call (clears the record).
    pub(crate) fn take_slid(&mut self, l: usize) -> Vec<bool> {
        self.slid.iter_mut().map(|s| std::mem::replace(&mut s[l], false)).collect()
    }

    /// Turns on (or off) the per-step energy accounting (one extra pass over the nodes).
    pub fn set_track_energy(&mut self, on: bool) {
        self.track_energy = on;
    }

    /// Sets the initial state of lane `l` from the undeformed position of each node:
    /// `f(p) = (u at t = −Δt, u at t = 0)`.
    pub fn initialize(&mut self, l: usize, f: impl Fn([f64; 3]) -> ([f64; 3], [f64; 3])) {
        let lattice = self.model.lattice();
        for i in 0..self.model.node_count() {
            let (before, now) = f(lattice.position(self.model.canonical(i)));
            for c in 0..3 {
                self.prev.c[c][i][l] = before[c];
                self.cur.c[c][i][l] = now[c];
            }
        }
    }

    /// Replaces the state of lane `l` by a known motion, as if `steps` steps had been committed:
    /// displacements `u(k, node, component)` at the viewed step `steps − 1` and its neighbours
    /// (`k` = −1, 0, +1 relative to it), the contact reactions `[friction x, friction y, normal]`
    /// and driver reactions at the viewed time, every base node sticking (or lifted, where its
    /// normal reaction is zero). Changing `steps` moves time for every lane: single-lane
    /// steppers only.
    pub(crate) fn set_state(
        &mut self,
        l: usize,
        steps: u64,
        u: impl Fn(i64, usize, usize) -> f64,
        contact_reaction: impl Fn(usize) -> [f64; 3],
        driver_reaction: impl Fn(usize) -> f64,
        driver_target: f64,
    ) {
        assert!(L == 1 || steps == self.steps, "only a single-lane stepper can move in time");
        for (k, field) in [(-1i64, &mut self.older), (0, &mut self.prev), (1, &mut self.cur)] {
            for (c, comp) in field.c.iter_mut().enumerate() {
                for (i, v) in comp.iter_mut().enumerate() {
                    v[l] = u(k, i, c);
                }
            }
        }
        for ci in 0..self.slipping.len() {
            let r = contact_reaction(ci);
            for c in 0..3 {
                self.reaction[c][ci][l] = r[c];
            }
            self.slipping[ci][l] = false;
            self.slip_run[ci][l] = 0;
            self.slip_path[ci][l] = 0.0;
            self.slid[ci][l] = false;
        }
        for d in 0..self.driver_reaction.len() {
            self.driver_reaction[d][l] = driver_reaction(d);
        }
        self.driver_target[l] = driver_target;
        self.steps = steps;
    }

    /// Multiplies every displacement of lane `l` (the three time levels) by `factor`.
    pub fn scale_state(&mut self, l: usize, factor: f64) {
        for field in [&mut self.older, &mut self.prev, &mut self.cur] {
            for comp in &mut field.c {
                for v in comp.iter_mut() {
                    v[l] *= factor;
                }
            }
        }
    }

    /// The cumulative energy terms of lane `l` (work and dissipation; kinetic and elastic
    /// energy are state, see [`Stepper::energy`]).
    pub(crate) fn energy_accumulators(&mut self, l: usize) -> &mut Energy {
        &mut self.acc[l]
    }

    /// Whether energy is being tracked.
    pub(crate) fn tracks_energy(&self) -> bool {
        self.track_energy
    }

    /// Base nodes of lane `l` sliding in the last step.
    pub fn slipping_count(&self, l: usize) -> usize {
        self.slipping.iter().filter(|s| s[l]).count()
    }

    /// Whether contact node `ci` of lane `l` slid in the last step.
    pub(crate) fn is_slipping(&self, ci: usize, l: usize) -> bool {
        self.slipping[ci][l]
    }

    /// Reaction `[friction x, friction y, normal]` of contact node `ci`, lane `l`, at the viewed
    /// time (N).
    pub(crate) fn contact_reaction(&self, ci: usize, l: usize) -> [f64; 3] {
        [self.reaction[0][ci][l], self.reaction[1][ci][l], self.reaction[2][ci][l]]
    }

    /// Where driver `d` of lane `l` was when the drivers started (m, x).
    pub(crate) fn driver_base(&self, d: usize, l: usize) -> f64 {
        self.driver_base[d][l]
    }

    /// Kinetic energy of lane `l` at the viewed time (J), one pass over the nodes.
    pub fn kinetic_energy(&self, l: usize) -> f64 {
        let mass = self.model.mass();
        let mut ke = 0.0;
        for c in 0..3 {
            let (a, b) = (&self.cur.c[c], &self.prev.c[c]);
            for i in 0..mass.len() {
                let v = a[i][l] - b[i][l];
                ke += mass[i] * v * v;
            }
        }
        0.5 * ke / (self.dt[l] * self.dt[l])
    }

    /// Zeroes the whole state of lane `l` and stops it from doing anything (used when a lane has
    /// failed, so it cannot feed non-finite values into the shared arithmetic).
    pub fn park(&mut self, l: usize) {
        for field in [&mut self.older, &mut self.prev, &mut self.cur] {
            for comp in &mut field.c {
                for v in comp.iter_mut() {
                    v[l] = 0.0;
                }
            }
        }
        self.driver_on[l] = false;
        self.set_body_acceleration(l, [0.0; 3]);
    }

    /// Advances every lane by one step.
    pub fn step(&mut self) {
        let m = self.model;
        // The force field is zero here: `integrate_trial` clears it as it consumes it.
        if self.parallel {
            bar_forces_parallel(m.layout(), &self.k, &self.cur, &mut self.force);
            self.integrate_trial();
        } else if !m.cache_blocked() {
            // A small lattice stays in cache: two plain sweeps beat handing over short runs.
            bar_forces(m.layout(), &self.k, &self.cur, &mut self.force);
            self.integrate_trial();
        } else {
            // Each node is integrated as soon as its last bar has run, while its data is still in
            // cache, instead of sweeping every node array once more (the same arithmetic, so the
            // same bits).
            let inv_mass = m.inv_mass();
            let coef = Coefficients { cf: self.cf, c2: self.c2, cp: self.cp };
            let (body, cur, prev, older) = (self.body, &self.cur, &self.prev, &mut self.older);
            bar_forces_finishing(m.layout(), &self.k, cur, &mut self.force, |r, f| {
                for c in 0..3 {
                    integrate_dispatch(
                        &inv_mass[r.clone()],
                        &coef,
                        body[c],
                        &mut f.c[c][r.clone()],
                        &cur.c[c][r.clone()],
                        &prev.c[c][r.clone()],
                        &mut older.c[c][r.clone()],
                    );
                }
            });
        }
        self.apply_fixed();
        self.apply_drivers();
        self.apply_contact();
        if self.track_energy {
            self.accumulate_energy();
        }
        // Commit: older ← uₙ₋₁, prev ← uₙ, cur ← uₙ₊₁.
        std::mem::swap(&mut self.older, &mut self.prev);
        std::mem::swap(&mut self.prev, &mut self.cur);
        self.steps += 1;
    }

    /// Trial update of every node (into `older`), clearing the force field for the next step.
    fn integrate_trial(&mut self) {
        let inv_mass = self.model.inv_mass();
        let coef = Coefficients { cf: self.cf, c2: self.c2, cp: self.cp };
        for c in 0..3 {
            let body = self.body[c];
            let (f, u, up, out) = (&mut self.force.c[c], &self.cur.c[c], &self.prev.c[c], &mut self.older.c[c]);
            if self.parallel {
                // Nodes are independent here: chunks of them on the pool, the same arithmetic.
                const CHUNK: usize = 4096;
                inv_mass
                    .par_chunks(CHUNK)
                    .zip(f.par_chunks_mut(CHUNK))
                    .zip(u.par_chunks(CHUNK))
                    .zip(up.par_chunks(CHUNK))
                    .zip(out.par_chunks_mut(CHUNK))
                    .for_each(|((((im, f), u), up), out)| integrate_dispatch(im, &coef, body, f, u, up, out));
            } else {
                integrate_dispatch(inv_mass, &coef, body, f, u, up, out);
            }
        }
    }

    fn apply_fixed(&mut self) {
        for &(node, mask) in self.model.fixed() {
            for c in 0..3 {
                if mask[c] {
                    self.older.c[c][node as usize] = self.cur.c[c][node as usize];
                }
            }
        }
    }

    fn apply_drivers(&mut self) {
        let mass = self.model.mass();
        for (d, &node) in self.model.drivers().iter().enumerate() {
            let p = node as usize;
            for l in 0..L {
                if !self.driver_on[l] {
                    self.driver_reaction[d][l] = 0.0;
                    continue;
                }
                let target = self.driver_base[d][l] + self.driver_target[l];
                self.driver_reaction[d][l] = (target - self.older.c[0][p][l]) * mass[p] / self.cf[l];
                self.older.c[0][p][l] = target;
            }
        }
    }

    /// Contact of every base node, all lanes at once without branches (each lane takes the
    /// stick, slide or lifted result by selection; the arithmetic of a lane is the same whatever
    /// its neighbours do).
    fn apply_contact(&mut self) {
        let [ox, oy, oz] = &mut self.older.c;
        let mut c = ContactArrays {
            mass: self.model.mass(),
            nodes: self.model.contact(),
            cf: &self.cf,
            mu_s: &self.mu_s,
            mu_d: &self.mu_d,
            dc: self.dc,
            older: [ox, oy, oz],
            cur: [&self.cur.c[0], &self.cur.c[1]],
            slipping: &mut self.slipping,
            slip_path: &mut self.slip_path,
            reaction: &mut self.reaction,
        };
        contact_dispatch(&mut c);
        if self.track_slid {
            for (any, now) in self.slid.iter_mut().zip(&self.slipping) {
                for l in 0..L {
                    any[l] |= now[l];
                }
            }
        }
        if self.track_onsets {
            for ci in 0..self.slipping.len() {
                for l in 0..L {
                    let run = &mut self.slip_run[ci][l];
                    if self.slipping[ci][l] {
                        *run += 1;
                        if *run == SUSTAINED_SLIP_STEPS {
                            self.onsets[l].push((self.steps + 1 - u64::from(SUSTAINED_SLIP_STEPS), ci as u32));
                        }
                    } else {
                        *run = 0;
                    }
                }
            }
        }
    }

    /// Adds the work and dissipation of step n, `F·(uₙ₊₁ − uₙ₋₁)/2` for every force, to the
    /// accumulators (`older` holds uₙ₊₁, `prev` uₙ₋₁ before the commit).
    fn accumulate_energy(&mut self) {
        let mass = self.model.mass();
        let mut damp = [0.0; L];
        let mut body = [0.0; L];
        for c in 0..3 {
            let (new, old) = (&self.older.c[c], &self.prev.c[c]);
            let bc = self.body[c];
            for i in 0..mass.len() {
                for l in 0..L {
                    let d2 = new[i][l] - old[i][l];
                    damp[l] += mass[i] * d2 * d2;
                    body[l] += mass[i] * bc[l] * d2;
                }
            }
        }
        for l in 0..L {
            let e = &mut self.acc[l];
            e.damping += damp[l] * self.damping[l] / (4.0 * self.dt[l]);
            e.body_work += 0.5 * body[l];
        }
        for (ci, &node) in self.model.contact().iter().enumerate() {
            let p = node as usize;
            for l in 0..L {
                let d2 = |c: usize| self.older.c[c][p][l] - self.prev.c[c][p][l];
                let e = &mut self.acc[l];
                e.friction -= 0.5 * (self.reaction[0][ci][l] * d2(0) + self.reaction[1][ci][l] * d2(1));
                e.impact -= 0.5 * self.reaction[2][ci][l] * d2(2);
            }
        }
        for (d, &node) in self.model.drivers().iter().enumerate() {
            let p = node as usize;
            for l in 0..L {
                self.acc[l].driver_work +=
                    0.5 * self.driver_reaction[d][l] * (self.older.c[0][p][l] - self.prev.c[0][p][l]);
            }
        }
    }

    /// Displacement of internal node `i`, lane `l`, at the viewed time (m).
    pub fn displacement(&self, i: usize, l: usize) -> [f64; 3] {
        self.prev.get(i, l)
    }

    /// Velocity of internal node `i`, lane `l`, at the viewed time (m/s).
    pub fn velocity(&self, i: usize, l: usize) -> [f64; 3] {
        let h = 0.5 / self.dt[l];
        let (a, b) = (self.cur.get(i, l), self.older.get(i, l));
        [(a[0] - b[0]) * h, (a[1] - b[1]) * h, (a[2] - b[2]) * h]
    }

    /// Acceleration of internal node `i`, lane `l`, at the viewed time (m/s²).
    pub fn acceleration(&self, i: usize, l: usize) -> [f64; 3] {
        let h = 1.0 / (self.dt[l] * self.dt[l]);
        let (a, b, c) = (self.cur.get(i, l), self.prev.get(i, l), self.older.get(i, l));
        [0, 1, 2].map(|k| (a[k] - 2.0 * b[k] + c[k]) * h)
    }

    /// Newest displacement field (all lanes), `uₙ₊₁`.
    pub fn newest(&self) -> &Field<L> {
        &self.cur
    }

    /// Interface resultants of lane `l` at the viewed time.
    pub fn interface(&self, l: usize) -> Interface {
        let contact = self.model.contact();
        let h = 0.5 / self.dt[l];
        let mut s = Interface { max_slip_rate: f64::NEG_INFINITY, ..Interface::default() };
        for (ci, &node) in contact.iter().enumerate() {
            let p = node as usize;
            s.friction_x += self.reaction[0][ci][l];
            s.normal += self.reaction[2][ci][l];
            s.mean_slip += self.prev.c[0][p][l];
            let v = (self.cur.c[0][p][l] - self.older.c[0][p][l]) * h;
            s.mean_slip_rate += v;
            s.max_slip_rate = s.max_slip_rate.max(v);
            s.slipping += usize::from(self.slipping[ci][l]);
            s.lifted += usize::from(self.reaction[2][ci][l] == 0.0);
        }
        let n = contact.len() as f64;
        s.mean_slip /= n;
        s.mean_slip_rate /= n;
        s
    }

    /// Sum of the driver reactions in x (N) of lane `l` at the viewed time.
    pub fn driver_force(&self, l: usize) -> f64 {
        self.driver_reaction.iter().map(|r| r[l]).sum()
    }

    /// Driver target displacement (m) of lane `l` used in the last step.
    pub fn driver_target(&self, l: usize) -> f64 {
        self.driver_target[l]
    }

    /// Energy terms of lane `l` at the viewed time (a pass over all bars and nodes).
    pub fn energy(&self, l: usize) -> Energy {
        let m = self.model;
        let mut e = self.acc[l];
        e.kinetic = self.kinetic_energy(l);
        e.elastic = strain_energy(m.layout(), &self.k, &self.prev, &self.cur, l);
        e
    }

    /// Out-of-balance force of lane `l` at the viewed time, `‖m·a + c·v‖₂` over all nodes and
    /// components (N): zero at static equilibrium.
    pub fn out_of_balance(&self, l: usize) -> f64 {
        let mass = self.model.mass();
        let (dt, d) = (self.dt[l], self.damping[l]);
        let (ha, hv) = (1.0 / (dt * dt), d * 0.5 / dt);
        let mut sum = 0.0;
        for c in 0..3 {
            let (a, b, o) = (&self.cur.c[c], &self.prev.c[c], &self.older.c[c]);
            for i in 0..mass.len() {
                let r = mass[i] * ((a[i][l] - 2.0 * b[i][l] + o[i][l]) * ha + (a[i][l] - o[i][l]) * hv);
                sum += r * r;
            }
        }
        sum.sqrt()
    }

    /// Checks lane `l` for a blow-up in the last step: a non-finite displacement, or a node that
    /// moved more than `0.01·Lc` in one step (a particle speed no linear-elastic rock reaches).
    pub fn check_blowup(&self, l: usize) -> Option<Blowup> {
        let bound = 0.01 * self.model.scene().lc_m;
        for c in 0..3 {
            let (a, b) = (&self.cur.c[c], &self.prev.c[c]);
            for i in 0..a.len() {
                let (x, y) = (a[i][l], b[i][l]);
                if !x.is_finite() {
                    return Some(Blowup { node: i, what: format!("non-finite {} displacement", ["x", "y", "z"][c]) });
                }
                let jump = (x - y).abs();
                if jump > bound {
                    return Some(Blowup {
                        node: i,
                        what: format!(
                            "{} displacement changed by {jump:.3e} m in one step (bound 0.01·Lc = {bound:.3e} m)",
                            ["x", "y", "z"][c]
                        ),
                    });
                }
            }
        }
        None
    }
}

/// Per-lane coefficients of the trial update `u⁺ = cf·(f/m + b) + c2·u − cp·u⁻`.
struct Coefficients<const L: usize> {
    cf: Lanes<L>,
    c2: Lanes<L>,
    cp: Lanes<L>,
}

widest! {
    /// The trial update of one component over every node, with the widest vector instructions the
    /// CPU has; clears `f` as it reads it.
    fn integrate_dispatch<const L: usize>(
        inv_mass: &[f64],
        k: &Coefficients<L>,
        body: Lanes<L>,
        f: &mut [Lanes<L>],
        u: &[Lanes<L>],
        up: &[Lanes<L>],
        out: &mut [Lanes<L>],
    ) => integrate
}

#[inline(always)]
fn integrate<const L: usize>(
    inv_mass: &[f64],
    k: &Coefficients<L>,
    body: Lanes<L>,
    f: &mut [Lanes<L>],
    u: &[Lanes<L>],
    up: &[Lanes<L>],
    out: &mut [Lanes<L>],
) {
    let n = inv_mass.len();
    let (f, u, up, out) = (&mut f[..n], &u[..n], &up[..n], &mut out[..n]);
    for i in 0..n {
        let im = inv_mass[i];
        let (fi, ui, upi) = (f[i], u[i], up[i]);
        let mut o = [0.0; L];
        for l in 0..L {
            o[l] = k.cf[l] * (fi[l] * im + body[l]) + k.c2[l] * ui[l] - k.cp[l] * upi[l];
        }
        out[i] = o;
        f[i] = [0.0; L];
    }
}

/// What the contact update reads and writes.
struct ContactArrays<'a, const L: usize> {
    mass: &'a [f64],
    nodes: &'a [u32],
    cf: &'a Lanes<L>,
    mu_s: &'a [Lanes<L>],
    mu_d: &'a [Lanes<L>],
    dc: f64,
    older: [&'a mut Vec<Lanes<L>>; 3],
    cur: [&'a Vec<Lanes<L>>; 2],
    slipping: &'a mut [[bool; L]],
    slip_path: &'a mut [Lanes<L>],
    reaction: &'a mut [Vec<Lanes<L>>; 3],
}

widest! {
    /// The contact update with the widest vector instructions the CPU has.
    fn contact_dispatch<const L: usize>(c: &mut ContactArrays<'_, L>) => contact
}

#[inline(always)]
fn contact<const L: usize>(c: &mut ContactArrays<'_, L>) {
    let dc = c.dc;
    for (ci, &node) in c.nodes.iter().enumerate() {
        let p = node as usize;
        let m = c.mass[p];
        let (xt, yt, zt) = (c.older[0][p], c.older[1][p], c.older[2][p]);
        let (xn, yn) = (c.cur[0][p], c.cur[1][p]);
        let (slipping, path) = (c.slipping[ci], c.slip_path[ci]);
        let (mu_s, mu_d) = (c.mu_s[ci], c.mu_d[ci]);
        let (mut ox, mut oy, mut oz) = ([0.0; L], [0.0; L], [0.0; L]);
        let (mut rxo, mut ryo, mut no) = ([0.0; L], [0.0; L], [0.0; L]);
        let (mut slip_o, mut path_o) = ([false; L], [0.0; L]);
        for l in 0..L {
            let g = m / c.cf[l];
            let touching = zt[l] < 0.0;
            let normal = -zt[l] * g;
            let (rx, ry) = ((xn[l] - xt[l]) * g, (yn[l] - yt[l]) * g);
            let need = (rx * rx + ry * ry).sqrt();
            let (ms, md) = (mu_s[l], mu_d[l]);
            let mu_k = if dc == 0.0 { md } else { ms - (ms - md) * (path[l] / dc).min(1.0) };
            let limit = if slipping[l] { mu_k } else { ms } * normal;
            let stick = need <= limit;
            // Sliding: friction μ_k·N against the trial motion (unused when sticking).
            let scale = mu_k * normal / need;
            let (fx, fy) = (rx * scale, ry * scale);
            let (x1, y1) = (xt[l] + fx / g, yt[l] + fy / g);
            let (sx, sy) = (x1 - xn[l], y1 - yn[l]);
            let slides = touching && !stick;
            ox[l] = if !touching {
                xt[l]
            } else if stick {
                xn[l]
            } else {
                x1
            };
            oy[l] = if !touching {
                yt[l]
            } else if stick {
                yn[l]
            } else {
                y1
            };
            oz[l] = if touching { 0.0 } else { zt[l] };
            rxo[l] = if !touching {
                0.0
            } else if stick {
                rx
            } else {
                fx
            };
            ryo[l] = if !touching {
                0.0
            } else if stick {
                ry
            } else {
                fy
            };
            no[l] = if touching { normal } else { 0.0 };
            slip_o[l] = slides;
            path_o[l] = if slides { path[l] + (sx * sx + sy * sy).sqrt() } else { 0.0 };
        }
        (c.older[0][p], c.older[1][p], c.older[2][p]) = (ox, oy, oz);
        (c.reaction[0][ci], c.reaction[1][ci], c.reaction[2][ci]) = (rxo, ryo, no);
        (c.slipping[ci], c.slip_path[ci]) = (slip_o, path_o);
    }
}
