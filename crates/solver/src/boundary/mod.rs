//! Boundary conditions of the block (docs/model.md §5, §12): everything that holds, drives or
//! loads the lattice besides its bars and the base's contact, declared in one place.
//!
//! Each kind is a file implementing [`Boundary`]: what it does to the trial of a step (a force
//! or a held component), the work it does (so the energy balance closes), how much it can raise
//! the lattice's highest eigenvalue (the critical step), and whether the quasi-static skip-ahead
//! can follow it, what it adds to a static solve (loads, held components), and what it does when the
//! loading starts. [`Boundaries`] holds a scene's as one list, built
//! once in the model, and applies them in the order of their [`Phase`] each step — springs,
//! pressure and tractions (forces), then the dashpots (which need every force in the trial), then
//! rollers (held components), then drivers (prescribed motion) — before the contact with the base
//! ([`crate::step::contact`]); settle, the skip-ahead's motion, the critical step and the step
//! loop over the list and name no kind.
//!
//! The kinds: [`rollers`] (held components of nodes or faces), [`drivers`] (a prescribed x motion,
//! Eq. 12), [`plate`] (springs to a plate moving by Eq. 12), [`pressure`] (a constant normal
//! pressure on the top face), [`traction`] (the initial shear tractions on a fault's face),
//! [`absorbing`] (Lysmer–Kuhlemeyer dashpots on faces that let waves leave). A new kind is its file
//! here implementing [`Boundary`], its line in the `kinds!` list below (which derives [`Kind`] and
//! its forwarding), and its keys and refusals in the configuration crate (ARCHITECTURE.md lists
//! the files).

pub mod absorbing;
pub mod drivers;
pub mod plate;
pub mod pressure;
pub mod rollers;
pub mod traction;

use crate::fault::FaultLanes;
use crate::field::{Field, Lanes};
use crate::geometry::NodeId;
use crate::ledger::{Energy, EnergyLayers};
use crate::scene::Scene;

/// A prescribed displacement component of a static solve (a held roller component, a held base
/// node, a driver).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prescribed {
    /// Internal node index.
    pub node: usize,
    /// Axis 0, 1, 2.
    pub axis: usize,
    /// Value (m).
    pub value: f64,
}

/// The state of the loading boundaries (drivers and the plate) of `L` seeds: whether each lane
/// is loading, the driver target, and each driven node's and spring's base and force.
#[derive(Clone, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct LoadingState<const L: usize> {
    /// Whether the drivers of each lane are on.
    pub on: [bool; L],
    /// Driver displacement (m) relative to `base`, for the step about to be taken (or used in the
    /// last one).
    pub target: Lanes<L>,
    /// x of each driven node when the drivers started (m).
    pub base: Vec<Lanes<L>>,
    /// Reaction of each driven node in x at the viewed time (N).
    pub reaction: Vec<Lanes<L>>,
    /// x of each node on the loading plate's springs when the plate started (m).
    pub plate_base: Vec<Lanes<L>>,
    /// Force of each plate spring on its node in x at the viewed time (N).
    pub plate_force: Vec<Lanes<L>>,
    /// The fault's smooth overstress's share of its peak, `G(t)`, for the step about to be taken
    /// (0 before the shear stage and without one; [`crate::fault::Overstress::ramp`]).
    pub overstress: Lanes<L>,
}

/// What a boundary acts on in a step of `L` seeds.
pub struct Step<'a, const L: usize> {
    /// Lumped masses (kg), internal order.
    pub mass: &'a [f64],
    /// `Δt²/(1 + DΔt/2)` of each lane: a force `F` moves the trial by `F·cf/m`.
    pub cf: &'a Lanes<L>,
    /// Time step of each lane (s).
    pub dt: &'a Lanes<L>,
    /// Mass-proportional damping D of each lane (1/s).
    pub damping: &'a Lanes<L>,
    /// `uₙ`, the level before `now`.
    pub before: &'a Field<L>,
    /// `uₙ₊₁`, the newest committed displacements.
    pub now: &'a Field<L>,
    /// The trial `uₙ₊₂`, changed in place.
    pub trial: &'a mut Field<L>,
    /// The loading's state.
    pub loading: &'a mut LoadingState<L>,
    /// Each lane's fault loads, when the base is a fault.
    pub fault: Option<&'a FaultLanes<L>>,
}

/// What a boundary's work over a step is read from and added to (before the commit).
pub struct Work<'a, const L: usize> {
    /// `uₙ₊₁` of the step.
    pub new: &'a Field<L>,
    /// `uₙ₋₁` of the step.
    pub old: &'a Field<L>,
    /// The loading's state.
    pub loading: &'a LoadingState<L>,
    /// Time step of each lane (s).
    pub dt: &'a Lanes<L>,
    /// Each lane's fault loads, when the base is a fault.
    pub fault: Option<&'a FaultLanes<L>>,
    /// The module layers the model sums (docs/model.md §2).
    pub layers: &'a EnergyLayers,
    /// This step's energy terms of each layer and lane, which each boundary adds to.
    pub parts: &'a mut [[Energy; L]],
}

impl<const L: usize> Work<'_, L> {
    /// The index in [`Work::parts`] of node `i`'s layer (a boundary acts on nodes the model sums),
    /// found once per node, before its lanes.
    #[inline]
    pub fn layer(&self, i: usize) -> usize {
        self.layers.of(i).expect("a boundary node is one the model sums")
    }
}

/// When a boundary acts within a step: forces first, then dashpots (which need every force in
/// the trial), then held components, then prescribed motion (over anything held before).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Phase {
    /// Adds forces to the trial.
    Force,
    /// Adds forces proportional to the trial's velocity.
    Dashpot,
    /// Holds components where they are.
    Held,
    /// Moves components as prescribed.
    Prescribed,
}

/// What a boundary condition does, for `L` seeds side by side.
pub trait Boundary {
    /// When it acts within a step.
    fn phase(&self) -> Phase;

    /// Acts on the trial of a step: adds its forces (`F·cf/m` per node) or replaces the trial
    /// of the components it holds (recording the reaction). Called after the bar forces and
    /// the integration, before the contact with the base.
    fn apply<const L: usize>(&self, s: &mut Step<'_, L>);

    /// Adds the work it did over the step, `F·(uₙ₊₁ − uₙ₋₁)/2`, to the energy terms.
    fn work<const L: usize>(&self, w: &mut Work<'_, L>);

    /// A bound on how much it raises `ω²_max` of the lattice (1/s²): 0 for held components and
    /// constant forces; a spring `k` on a node of mass `m` adds at most `k/m` (Weyl).
    fn stiffening(&self, inv_mass: &[f64]) -> f64 {
        let _ = inv_mass;
        0.0
    }

    /// `Err(why)` when the quasi-static skip-ahead's motion cannot follow it.
    fn skip_ahead(&self) -> Result<(), &'static str> {
        Ok(())
    }

    /// Adds its constant forces to the loads of a static solve (the self-weight's).
    fn static_load(&self, loads: &mut Field<1>) {
        let _ = loads;
    }

    /// The components it holds, as constraints of a static solve, each at `value(node, axis)`.
    fn held(&self, value: &dyn Fn(usize, usize) -> f64) -> Vec<Prescribed> {
        let _ = value;
        Vec::new()
    }

    /// Starts its loading in lane `l` from the displacements `now` (when the shear stage starts).
    fn start<const L: usize>(&self, loading: &mut LoadingState<L>, now: &Field<L>, l: usize) {
        let _ = (loading, now, l);
    }
}

/// The kinds of boundary, one line each in the order their work is added to the energy terms:
/// from the list come [`Kind`] and its forwarding of every question to the kind's own
/// [`Boundary`] implementation.
macro_rules! kinds {
    ($($(#[$doc:meta])* $variant:ident($kind:ty)),+ $(,)?) => {
        /// One boundary condition of a scene.
        #[derive(Clone, Debug)]
        pub enum Kind {
            $($(#[$doc])* $variant($kind),)+
        }

        impl Kind {
            /// Every kind's boundary on `scene` (empty where the scene has none), in the list's
            /// order.
            fn every(scene: &Scene, internal: &dyn Fn(NodeId) -> Option<u32>) -> Vec<Kind> {
                vec![$(Kind::$variant(<$kind>::new(scene, internal)),)+]
            }
        }

        impl Boundary for Kind {
            fn phase(&self) -> Phase {
                match self { $(Kind::$variant(b) => b.phase(),)+ }
            }
            #[inline]
            fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
                match self { $(Kind::$variant(b) => b.apply(s),)+ }
            }
            #[inline]
            fn work<const L: usize>(&self, w: &mut Work<'_, L>) {
                match self { $(Kind::$variant(b) => b.work(w),)+ }
            }
            fn stiffening(&self, inv_mass: &[f64]) -> f64 {
                match self { $(Kind::$variant(b) => b.stiffening(inv_mass),)+ }
            }
            fn skip_ahead(&self) -> Result<(), &'static str> {
                match self { $(Kind::$variant(b) => b.skip_ahead(),)+ }
            }
            fn static_load(&self, loads: &mut Field<1>) {
                match self { $(Kind::$variant(b) => b.static_load(loads),)+ }
            }
            fn held(&self, value: &dyn Fn(usize, usize) -> f64) -> Vec<Prescribed> {
                match self { $(Kind::$variant(b) => b.held(value),)+ }
            }
            fn start<const L: usize>(&self, loading: &mut LoadingState<L>, now: &Field<L>, l: usize) {
                match self { $(Kind::$variant(b) => b.start(loading, now, l),)+ }
            }
        }
    };
}

kinds! {
    /// Driven nodes.
    Drivers(drivers::Drivers),
    /// The loading plate's springs.
    Plate(plate::Plate),
    /// The normal pressure on the top face.
    Pressure(pressure::Pressure),
    /// The initial tractions on a fault's face.
    Traction(traction::Traction),
    /// The absorbing faces' dashpots.
    Absorbing(absorbing::Absorbing),
    /// Held components.
    Rollers(rollers::Rollers),
}

/// The boundary conditions of a scene, in internal node order: one list, applied by phase.
#[derive(Clone, Debug, Default)]
pub struct Boundaries {
    /// Every kind's, in the order their work is added up.
    list: Vec<Kind>,
    /// Indices into `list` in the order they act on a step (by phase, then list order).
    applied: Vec<usize>,
}

impl Boundaries {
    /// The boundary conditions of `scene` on the nodes `internal` maps to an internal index (every
    /// node, or those a rank owns: [`crate::split`]).
    pub fn new(scene: &Scene, internal: impl Fn(NodeId) -> Option<u32>) -> Boundaries {
        let list = Kind::every(scene, &internal);
        let mut applied: Vec<usize> = (0..list.len()).collect();
        applied.sort_by_key(|&i| list[i].phase());
        Boundaries { list, applied }
    }

    /// Every boundary, in the order their work is added up.
    pub fn iter(&self) -> impl Iterator<Item = &Kind> {
        self.list.iter()
    }

    /// Applies every boundary to the trial of a step, by phase: forces (plate springs, pressure,
    /// tractions), the dashpots, held components (rollers), prescribed motion (drivers).
    pub(crate) fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
        for &i in &self.applied {
            self.list[i].apply(s);
        }
    }

    /// Adds the work of every boundary over the step to the energy terms.
    pub(crate) fn work<const L: usize>(&self, w: &mut Work<'_, L>) {
        for b in &self.list {
            b.work(w);
        }
    }

    /// The bound on how much the boundaries raise `ω²_max` (1/s²): the sum of theirs (Weyl's
    /// inequality for a sum of positive semi-definite perturbations).
    pub fn stiffening(&self, inv_mass: &[f64]) -> f64 {
        self.list.iter().map(|b| b.stiffening(inv_mass)).sum()
    }

    /// Why the skip-ahead cannot follow these boundaries, if it cannot.
    pub fn skip_ahead(&self) -> Result<(), &'static str> {
        self.list.iter().try_for_each(|b| b.skip_ahead())
    }

    /// Adds every boundary's constant forces to the loads of a static solve.
    pub(crate) fn static_load(&self, loads: &mut Field<1>) {
        for b in &self.list {
            b.static_load(loads);
        }
    }

    /// Every held component as a constraint of a static solve, each at `value(node, axis)`.
    pub(crate) fn held(&self, value: impl Fn(usize, usize) -> f64) -> Vec<Prescribed> {
        self.list.iter().flat_map(|b| b.held(&value)).collect()
    }

    /// Starts the loading of lane `l` from the displacements `now`.
    pub(crate) fn start<const L: usize>(&self, loading: &mut LoadingState<L>, now: &Field<L>, l: usize) {
        for b in &self.list {
            b.start(loading, now, l);
        }
    }

    /// The driven nodes (internal indices).
    pub fn drivers(&self) -> &[u32] {
        self.list.iter().find_map(|b| if let Kind::Drivers(d) = b { Some(&d.nodes[..]) } else { None }).unwrap_or(&[])
    }

    /// The nodes tied to the loading plate and their spring stiffness in x (N/m).
    pub fn plate(&self) -> &[(u32, f64)] {
        self.list.iter().find_map(|b| if let Kind::Plate(p) = b { Some(&p.springs[..]) } else { None }).unwrap_or(&[])
    }
}
