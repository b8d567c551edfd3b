//! The state of `L` seeds advancing together: time levels, contact, drivers, energy accumulated.
//!
//! **Time levels.** After [`crate::step::Stepper::step`] has committed step `n` (computing
//! `uₙ₊₁`), the state *views* time `n`: it holds `uₙ₋₁`, `uₙ` and `uₙ₊₁` ([`TimeLevels`]), so the
//! viewed displacement is `uₙ`, the velocity `(uₙ₊₁ − uₙ₋₁)/2Δt`, the acceleration
//! `(uₙ₊₁ − 2uₙ + uₙ₋₁)/Δt²`. The next step writes `uₙ₊₂` over `uₙ₋₁` (no longer needed) and
//! renames the three. The contact reactions, driver reactions and energy terms are those of the
//! viewed time.
//!
//! The state is plain data: the quasi-static skip-ahead reads it and, when it jumps, writes a
//! whole new lane state along the motion it followed ([`State::set_lane`]).

use crate::boundary::LoadingState;
use crate::field::{Field, Lanes};
pub use crate::ledger::Energy;
use crate::step::params::Params;
use crate::step::rupture::RuptureState;

/// Displacements around the viewed step `n`.
#[derive(Clone, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct TimeLevels<const L: usize> {
    /// `uₙ₋₁` (m).
    pub nm1: Field<L>,
    /// `uₙ` (m), the viewed displacement.
    pub n: Field<L>,
    /// `uₙ₊₁` (m), the newest.
    pub np1: Field<L>,
}

impl<const L: usize> TimeLevels<L> {
    fn zeros(n: usize) -> Self {
        TimeLevels { nm1: Field::zeros(n), n: Field::zeros(n), np1: Field::zeros(n) }
    }

    /// After the step wrote `uₙ₊₂` into `nm1`: `(nm1, n, np1) ← (n, np1, uₙ₊₂)`.
    pub(crate) fn commit(&mut self) {
        std::mem::swap(&mut self.nm1, &mut self.n);
        std::mem::swap(&mut self.n, &mut self.np1);
    }

    /// The three levels, oldest first.
    pub fn all_mut(&mut self) -> [&mut Field<L>; 3] {
        [&mut self.nm1, &mut self.n, &mut self.np1]
    }
}

/// What the base does to each contact node (index into [`crate::Model::contact`]).
#[derive(Clone, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct ContactState<const L: usize> {
    /// Whether the node slid in the last step.
    pub sliding: Vec<[bool; L]>,
    /// The friction law's state variable of each node (the slip of the current slide for slip
    /// weakening), zero when sticking.
    pub state: Vec<Lanes<L>>,
    /// Reactions at the viewed time (N): friction x, friction y, normal.
    pub reaction: [Vec<Lanes<L>>; 3],
}

/// Slip history of the contact nodes, for recorders and the skip-ahead.
#[derive(Clone, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct SlipLog<const L: usize> {
    /// Consecutive steps each contact node has been sliding.
    pub run: Vec<[u32; L]>,
    /// Sustained slip onsets `(step, contact index)` per lane since the last drain.
    pub onsets: [Vec<(u64, u32)>; L],
    /// Whether each contact node slid in any step since the last [`SlipLog::take_slid`].
    pub slid: Vec<[bool; L]>,
}

impl<const L: usize> SlipLog<L> {
    /// Which contact nodes of lane `l` slid since the last call (clears the record).
    pub fn take_slid(&mut self, l: usize) -> Vec<bool> {
        self.slid.iter_mut().map(|s| std::mem::replace(&mut s[l], false)).collect()
    }
}

/// The state of `L` seeds.
#[derive(Clone, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct State<const L: usize> {
    /// Displacements around the viewed step.
    pub u: TimeLevels<L>,
    /// Contact of the base nodes.
    pub contact: ContactState<L>,
    /// Drivers.
    pub loading: LoadingState<L>,
    /// Work and dissipation accumulated from the start of each lane's run (J); kinetic and
    /// elastic energy are functions of the time levels.
    pub energy: [Energy; L],
    /// The work terms of the last step per layer the model sums, when the energy is tracked: on
    /// a rank of a split scene, those rank 0 adds to its ledger (docs/model.md §19).
    pub energy_parts: Vec<[Energy; L]>,
    /// Slip history.
    pub log: SlipLog<L>,
    /// Damage of the bars, when they crack (docs/model.md §11).
    pub rupture: Option<RuptureState<L>>,
    /// Each bar's memory variables when the medium has a Q (docs/model.md §18), mechanism-major
    /// over the bars in kernel order; empty otherwise.
    pub anelastic: crate::step::anelastic::Memory,
    /// Committed steps (the viewed step is `steps − 1`).
    pub steps: u64,
}

impl<const L: usize> State<L> {
    /// A state at rest (`u = 0`) for `nodes` nodes, `contacts` contact nodes and `drivers`
    /// driven nodes, drivers off.
    pub fn at_rest(nodes: usize, contacts: usize, drivers: usize) -> Self {
        Self::at_rest_with_plate(nodes, contacts, drivers, 0)
    }

    /// [`State::at_rest`] with `plate` nodes on the loading plate's springs.
    pub fn at_rest_with_plate(nodes: usize, contacts: usize, drivers: usize, plate: usize) -> Self {
        State {
            u: TimeLevels::zeros(nodes),
            contact: ContactState {
                sliding: vec![[false; L]; contacts],
                state: vec![[0.0; L]; contacts],
                reaction: [vec![[0.0; L]; contacts], vec![[0.0; L]; contacts], vec![[0.0; L]; contacts]],
            },
            loading: LoadingState {
                on: [false; L],
                target: [0.0; L],
                base: vec![[0.0; L]; drivers],
                reaction: vec![[0.0; L]; drivers],
                plate_base: vec![[0.0; L]; plate],
                plate_force: vec![[0.0; L]; plate],
                overstress: [0.0; L],
            },
            energy: [Energy::default(); L],
            energy_parts: Vec::new(),
            log: SlipLog {
                run: vec![[0; L]; contacts],
                onsets: std::array::from_fn(|_| Vec::new()),
                slid: vec![[false; L]; contacts],
            },
            rupture: None,
            anelastic: Default::default(),
            steps: 0,
        }
    }

    /// A state at rest for the parameters `p`: every contact node at its law's initial state
    /// ([`crate::laws::Law::initial_state`]), every bar intact when the scene's bars crack.
    pub fn for_params(p: &Params<'_, L>) -> Self {
        let m = p.model;
        let mut s = State::at_rest_with_plate(m.node_count(), m.contact().len(), m.drivers().len(), m.plate().len());
        s.contact.state = p.initial_states();
        s.rupture = p.rupture.as_ref().map(|r| RuptureState::intact(p.k.per_bar(), r));
        if p.anelastic.as_ref().is_some_and(|a| a.memory()) {
            s.anelastic = crate::step::anelastic::Memory::at_rest(m.bar_count(), L);
        }
        s
    }

    /// Displacement of internal node `i`, lane `l`, at the viewed time (m).
    pub fn displacement(&self, i: usize, l: usize) -> [f64; 3] {
        self.u.n.get(i, l)
    }

    /// Reaction `[friction x, friction y, normal]` of contact node `ci`, lane `l`, at the viewed
    /// time (N).
    pub fn contact_reaction(&self, ci: usize, l: usize) -> [f64; 3] {
        let r = &self.contact.reaction;
        [r[0][ci][l], r[1][ci][l], r[2][ci][l]]
    }

    /// The loading force in x (N) of lane `l` at the viewed time: the drivers' reactions plus
    /// the plate springs' pull.
    pub fn driver_force(&self, l: usize) -> f64 {
        self.loading.reaction.iter().chain(&self.loading.plate_force).map(|r| r[l]).sum()
    }

    /// Takes the sustained slip onsets of lane `l` recorded since the last call: `(step,
    /// contact index)`, the step being the first of a run of sliding steps (see
    /// [`crate::step::SUSTAINED_SLIP_STEPS`]).
    pub fn drain_onsets(&mut self, l: usize) -> std::vec::Drain<'_, (u64, u32)> {
        self.log.onsets[l].drain(..)
    }

    /// Replaces the state of lane `l` by a known motion, as if `steps` steps had been committed:
    /// displacements `u(k, node, axis)` at the viewed step `steps − 1` and its neighbours
    /// (`k` = −1, 0, +1 relative to it), the contact reactions `[friction x, friction y, normal]`
    /// and driver reactions at the viewed time, every base node sticking (or lifted, where its
    /// normal reaction is zero). Changing `steps` moves time for every lane: single-lane states
    /// only.
    pub fn set_lane(
        &mut self,
        l: usize,
        steps: u64,
        u: impl Fn(i64, usize, usize) -> f64,
        contact_reaction: impl Fn(usize) -> [f64; 3],
        driver_reaction: impl Fn(usize) -> f64,
        driver_target: f64,
    ) {
        assert!(L == 1 || steps == self.steps, "only a single-lane state can move in time");
        for (k, field) in (-1i64..).zip(self.u.all_mut()) {
            field.set_lane(l, |i, c| u(k, i, c));
        }
        for ci in 0..self.contact.sliding.len() {
            let r = contact_reaction(ci);
            for c in 0..3 {
                self.contact.reaction[c][ci][l] = r[c];
            }
            self.contact.sliding[ci][l] = false;
            self.contact.state[ci][l] = 0.0;
            self.log.run[ci][l] = 0;
            self.log.slid[ci][l] = false;
        }
        for d in 0..self.loading.reaction.len() {
            self.loading.reaction[d][l] = driver_reaction(d);
        }
        self.loading.target[l] = driver_target;
        self.steps = steps;
    }

    /// Multiplies every displacement of lane `l` (the three time levels) by `factor`.
    pub fn scale_lane(&mut self, l: usize, factor: f64) {
        for field in self.u.all_mut() {
            field.scale_lane(l, factor);
        }
    }

    /// Zeroes the displacements of lane `l` and turns its drivers off (a failed lane must not
    /// feed non-finite values into the shared arithmetic).
    pub fn zero_lane(&mut self, l: usize) {
        for field in self.u.all_mut() {
            field.set_lane(l, |_, _| 0.0);
        }
        self.loading.on[l] = false;
    }
}
