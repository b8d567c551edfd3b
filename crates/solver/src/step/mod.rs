//! Explicit central differences with mass-proportional damping, rollers, drivers and the
//! frictional base (docs/model.md §2, §4), advancing `L` seeds side by side.
//!
//! Three things apart: the [`State`] (time levels, contact, drivers, energy: what evolves), the
//! [`Params`] (model, stiffness and friction of each seed, time step, damping, body force: what
//! the step reads) and the [`Stepper`] (scratch memory and what to track).
//!
//! One step, in this order: `bar_forces → integrate (trial) → boundary conditions (plate springs,
//! pressure, rollers, drivers: [`crate::boundary`]) → contact → energy (if tracked) → commit` (on cache-blocked lattices the first two are one pass: each
//! node is integrated right after its last bar). The trial update is
//! `u⁺ = [Δt²(f/m + b) + 2u − (1 − DΔt/2)u⁻] / (1 + DΔt/2)`; every constraint then replaces the
//! trial value of its component and its reaction `R = m(1 + DΔt/2)/Δt² · (u_constrained − u⁺)` is
//! exactly the force that makes the update satisfy the constraint. The contact rule is in
//! [`contact`]; what a committed step shows (displacement, velocity, acceleration, reactions,
//! energy at the viewed time) is read through a [`LaneView`].

pub mod anelastic;
pub mod bars;
pub mod contact;
pub mod energy;
pub mod integrate;
pub mod params;
mod primitives;
pub mod rupture;
pub mod state;
pub mod stencil;

mod view;

pub use crate::field::{Field, Lanes};
pub use crate::stiffness::{LaneStiffness, Stiffness, StiffnessRef};
pub use contact::SUSTAINED_SLIP_STEPS;
pub use energy::Energy;
pub use params::{LaneSetup, Params};
pub use state::State;
pub use view::{Blowup, Interface, LaneView, NodeContact};

use stickslip_isa::Isa;

use crate::boundary;
use crate::layout::Bars;
use crate::model::Model;
use bars::{bar_forces_finishing, bar_forces_parallel, listed_forces};
use integrate::{Levels, Update, integrate_all, integrate_range};

/// What a stepper computes besides the motion.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tracking {
    /// Accumulate the energy terms (one extra pass over the nodes per step).
    pub energy: bool,
    /// Log sustained slip onsets (see [`State::drain_onsets`]).
    pub onsets: bool,
    /// Log which contact nodes slid between two looks of the skip-ahead.
    pub slid: bool,
}

/// Which bar kernel a stepper runs, chosen once from the scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// Linear-elastic bars listed with their ends ([`bars`]): scenes without `[rupture]` below
    /// [`crate::model::STENCIL_MIN_BARS`] bars.
    Elastic,
    /// Linear-elastic bars as a stencil ([`stencil`]): larger scenes without `[rupture]`.
    Stencil,
    /// Bars that crack ([`rupture`]).
    Rupture,
}

/// The scratch memory of a step of `L` seeds, and how to run it.
pub struct Stepper<const L: usize> {
    force: Field<L>,
    parallel: bool,
    tracking: Tracking,
    kernel: Kernel,
    /// Per-segment ledgers and crack lists of the rupture kernel.
    outs: Vec<rupture::SegmentOut<L>>,
}

impl<const L: usize> Stepper<L> {
    /// A stepper for `model`, serial, tracking nothing; its kernel is the rupture kernel when the
    /// scene's bars crack, the elastic one otherwise.
    pub fn new(model: &Model) -> Self {
        let kernel = match model.layout() {
            _ if model.scene().rupture.is_some() => Kernel::Rupture,
            Bars::Stencil(_) => Kernel::Stencil,
            Bars::Listed(_) => Kernel::Elastic,
        };
        Stepper {
            force: Field::zeros(model.node_count()),
            parallel: false,
            tracking: Tracking::default(),
            kernel,
            outs: Vec::new(),
        }
    }

    /// The bar kernel this stepper runs.
    pub fn kernel(&self) -> Kernel {
        self.kernel
    }

    /// Splits each step over the current rayon pool (the numbers do not change: see
    /// [`bars::bar_forces_parallel`]). Worth it for large lattices only.
    pub fn set_parallel(&mut self, on: bool) {
        self.parallel = on;
    }

    /// What to track.
    pub fn set_tracking(&mut self, tracking: Tracking) {
        self.tracking = tracking;
    }

    /// What is tracked.
    pub fn tracking(&self) -> Tracking {
        self.tracking
    }

    /// Advances every lane of `state` by one step.
    pub fn step(&mut self, p: &Params<'_, L>, state: &mut State<L>) {
        let m = p.model;
        let update = Update { inv_mass: m.inv_mass(), coef: p.coefficients(), body: p.body() };
        if self.kernel == Kernel::Rupture {
            self.rupture_forces_and_trial(p, state, &update);
        } else if let (Some(a), Bars::Stencil(layout)) = (&p.anelastic, m.layout()) {
            // The medium's memory variables and dashpots join each run's tensions in the kernel.
            let u = &mut state.u;
            let medium = anelastic::RunMedium::new(layout, m.run_zones(), a, &u.n, &mut state.anelastic);
            let levels = Levels { u: &u.np1, up: &u.n, out: &mut u.nm1 };
            stencil::forces_and_trial(
                layout,
                p.stiffness(),
                &update,
                &mut self.force,
                levels,
                Some(medium),
                self.parallel,
            );
        } else if let Some(a) = &p.anelastic {
            // A listed lattice: the elastic forces, then the medium's (reading two levels of every
            // bar), then one integration sweep.
            let (u, layout) = (&mut state.u, m.layout().listed());
            if self.parallel {
                bar_forces_parallel(layout, p.k.per_bar(), &u.np1, &mut self.force)
            } else {
                listed_forces(layout, p.k.per_bar(), &u.np1, &mut self.force)
            }
            let zeta = &mut state.anelastic;
            anelastic::forces(m, a, p.stiffness(), &u.np1, &u.n, zeta, &mut self.force, self.parallel);
            integrate_all(&update, &mut self.force, Levels { u: &u.np1, up: &u.n, out: &mut u.nm1 }, self.parallel);
        } else if let Bars::Stencil(layout) = m.layout() {
            let u = &mut state.u;
            let levels = Levels { u: &u.np1, up: &u.n, out: &mut u.nm1 };
            stencil::forces_and_trial(layout, p.stiffness(), &update, &mut self.force, levels, None, self.parallel);
        } else {
            let u = &mut state.u;
            let layout = m.layout().listed();
            // The force field is zero here: the integration clears it as it consumes it. The trial
            // `uₙ₊₂` is written over `uₙ₋₁`, no longer needed.
            if self.parallel {
                bar_forces_parallel(layout, p.k.per_bar(), &u.np1, &mut self.force);
                integrate_all(&update, &mut self.force, Levels { u: &u.np1, up: &u.n, out: &mut u.nm1 }, true);
            } else if !m.cache_blocked() {
                // A small lattice stays in cache: two plain sweeps beat handing over short runs.
                listed_forces(layout, p.k.per_bar(), &u.np1, &mut self.force);
                integrate_all(&update, &mut self.force, Levels { u: &u.np1, up: &u.n, out: &mut u.nm1 }, false);
            } else {
                // Each node is integrated as soon as its last bar has run, while its data is still in
                // cache, instead of sweeping every node array once more (the same arithmetic, so the
                // same bits).
                let isa = Isa::current();
                let (now, before, out) = (&u.np1, &u.n, &mut u.nm1);
                bar_forces_finishing(layout, p.k.per_bar(), now, &mut self.force, |r, f| {
                    integrate_range(isa, r, &update, f, Levels { u: now, up: before, out: &mut *out });
                });
            }
        }
        m.boundaries().apply(&mut boundary::Step {
            mass: m.mass(),
            cf: &p.coefficients().cf,
            dt: p.dts(),
            damping: p.dampings(),
            before: &state.u.n,
            now: &state.u.np1,
            trial: &mut state.u.nm1,
            loading: &mut state.loading,
            fault: p.fault.as_ref(),
        });
        let log = (self.tracking.slid || self.tracking.onsets).then_some((
            &mut state.log,
            self.tracking.slid,
            self.tracking.onsets,
            state.steps,
        ));
        contact::apply(p, &mut state.u.nm1, &state.u.np1, &mut state.contact, log);
        if self.tracking.energy {
            energy::accumulate(p, state, self.parallel);
        }
        state.u.commit();
        state.steps += 1;
    }
}

impl<const L: usize> Stepper<L> {
    /// The rupture kernel's bar forces and the trial update, in the same three ways as the
    /// elastic ones; then the energy the bars dissipated and their transitions, folded in segment
    /// order.
    fn rupture_forces_and_trial(&mut self, p: &Params<'_, L>, state: &mut State<L>, update: &Update<'_, L>) {
        let m = p.model;
        let State { u, rupture: damage, energy, steps, .. } = state;
        let damage = damage.as_mut().expect("the rupture kernel runs on a state with damage");
        let params = p.rupture.as_ref().expect("the rupture kernel runs with the law's parameters");
        let (now, before, out) = (&u.np1, &u.n, &mut u.nm1);
        let pass = rupture::Pass {
            layout: m.layout().listed(),
            k0: p.k.per_bar(),
            params,
            state: &mut *damage,
            u: now,
            older: before,
        };
        if self.parallel {
            rupture::forces_parallel(pass, &mut self.force, &mut self.outs);
            integrate_all(update, &mut self.force, Levels { u: now, up: before, out }, true);
        } else if !m.cache_blocked() {
            rupture::forces(pass, &mut self.force, &mut self.outs);
            integrate_all(update, &mut self.force, Levels { u: now, up: before, out }, false);
        } else {
            let isa = Isa::current();
            rupture::forces_finishing(pass, &mut self.force, &mut self.outs, |r, f| {
                integrate_range(isa, r, update, f, Levels { u: now, up: before, out: &mut *out });
            });
        }
        let mut dissipated = [0.0; L];
        rupture::fold(&self.outs, *steps, &mut dissipated, damage);
        for l in 0..L {
            if dissipated[l] != 0.0 {
                energy[l].fracture += dissipated[l];
            }
        }
    }
}

/// Turns on the drivers of lane `l`: from now on their x is held at where they are now (the
/// newest time level) plus the target of [`state::DriverState::target`].
pub fn start_drivers<const L: usize>(model: &Model, state: &mut State<L>, l: usize) {
    let (loading, now) = (&mut state.loading, &state.u.np1);
    loading.on[l] = true;
    loading.target[l] = 0.0;
    model.boundaries().start(loading, now, l);
}

/// Stops lane `l` from doing anything (a failed lane): zero displacements, drivers off, no body
/// force.
pub fn park<const L: usize>(p: &mut Params<'_, L>, state: &mut State<L>, l: usize) {
    state.zero_lane(l);
    p.set_body_acceleration(l, [0.0; 3]);
}

/// Parameters, state and scratch of `L` seeds together, for stepping by hand (tests,
/// benchmarks, tools): [`crate::run`] drives the same three through the loading stages.
pub struct Batch<'m, const L: usize> {
    /// What the step reads.
    pub params: Params<'m, L>,
    /// What evolves.
    pub state: State<L>,
    /// Scratch and tracking.
    pub stepper: Stepper<L>,
}

impl<'m, const L: usize> Batch<'m, L> {
    /// `L` seeds of `model` at rest, no damping, no body force, drivers off.
    pub fn new(model: &'m Model, lanes: &[LaneSetup; L]) -> Self {
        Batch {
            params: Params::new(model, lanes),
            state: State::at_rest_with_plate(
                model.node_count(),
                model.contact().len(),
                model.drivers().len(),
                model.plate().len(),
            ),
            stepper: Stepper::new(model),
        }
        .with_damage()
    }

    /// Gives the state its intact damage arrays when the bars crack.
    fn with_damage(mut self) -> Self {
        self.state = State::for_params(&self.params);
        self
    }

    /// One step of every lane.
    pub fn step(&mut self) {
        self.stepper.step(&self.params, &mut self.state);
    }

    /// Lane `l` at its viewed time.
    pub fn view(&self, l: usize) -> LaneView<'_, 'm, L> {
        LaneView { params: &self.params, state: &self.state, lane: l }
    }

    /// Sets the start of lane `l` from the undeformed position of each node:
    /// `f(p) = (u one step before the start, u at the start)`.
    pub fn initialize(&mut self, l: usize, f: impl Fn([f64; 3]) -> ([f64; 3], [f64; 3])) {
        let model = self.params.model;
        let lattice = model.lattice();
        let at = |i: usize| f(lattice.position(model.canonical(i)));
        self.state.u.n.set_lane(l, |i, c| at(i).0[c]);
        self.state.u.np1.set_lane(l, |i, c| at(i).1[c]);
    }
}
