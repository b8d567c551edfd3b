//! Boundary conditions of the block (docs/model.md §5, §12): everything that holds, drives or
//! loads the lattice besides its bars and the base's contact, declared in one place.
//!
//! Each kind is a file implementing [`Boundary`]: what it does to the trial of a step (a force
//! or a held component), the work it does (so the energy balance closes), how much it can raise
//! the lattice's highest eigenvalue (the critical step), and whether the quasi-static skip-ahead
//! can follow it. [`Boundaries`] holds a scene's, built once in the model, and applies them in a
//! fixed order each step — springs, pressure and tractions (forces), then the dashpots (which
//! need every force in the trial), then rollers, then drivers (held components) — before the contact with the base ([`crate::step::contact`]).
//!
//! The kinds: [`rollers`] (held components of nodes or faces), [`drivers`] (a prescribed x motion,
//! Eq. 12), [`plate`] (springs to a plate moving by Eq. 12), [`pressure`] (a constant normal
//! pressure on the top face), [`traction`] (the initial shear tractions on a fault's face),
//! [`absorbing`] (Lysmer–Kuhlemeyer dashpots on faces that let waves leave). A new kind is its file here, its field in [`Boundaries`] with its
//! calls in the `Boundaries` methods, and its keys and refusals in the configuration crate
//! (ARCHITECTURE.md lists the files).

pub mod absorbing;
pub mod drivers;
pub mod plate;
pub mod pressure;
pub mod rollers;
pub mod traction;

use crate::fault::FaultLanes;
use crate::field::{Field, Lanes};
use crate::geometry::NodeId;
use crate::ledger::Energy;
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
#[derive(Clone, Debug, PartialEq)]
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
    /// The energy terms of each lane.
    pub energy: &'a mut [Energy; L],
}

/// What a boundary condition does, for `L` seeds side by side.
pub trait Boundary {
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
}

/// The boundary conditions of a scene, in internal node order.
#[derive(Clone, Debug, Default)]
pub struct Boundaries {
    /// Held components.
    pub rollers: rollers::Rollers,
    /// Driven nodes.
    pub drivers: drivers::Drivers,
    /// The loading plate's springs.
    pub plate: plate::Plate,
    /// The normal pressure on the top face.
    pub pressure: pressure::Pressure,
    /// The initial tractions on a fault's face.
    pub traction: traction::Traction,
    /// The absorbing faces' dashpots.
    pub absorbing: absorbing::Absorbing,
}

impl Boundaries {
    /// The boundary conditions of `scene`, with `internal` mapping a canonical node to its
    /// internal index.
    pub fn new(scene: &Scene, internal: impl Fn(NodeId) -> u32) -> Boundaries {
        Boundaries {
            rollers: rollers::Rollers::new(scene, &internal),
            drivers: drivers::Drivers::new(scene, &internal),
            plate: plate::Plate::new(scene, &internal),
            pressure: pressure::Pressure::new(scene, &internal),
            traction: traction::Traction::new(scene, &internal),
            absorbing: absorbing::Absorbing::new(scene, &internal),
        }
    }

    /// Applies every boundary to the trial of a step, in order: forces (plate springs, pressure,
    /// tractions), the dashpots, then held components (rollers, drivers).
    pub(crate) fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
        self.plate.apply(s);
        self.pressure.apply(s);
        self.traction.apply(s);
        self.absorbing.apply(s);
        self.rollers.apply(s);
        self.drivers.apply(s);
    }

    /// Adds the work of every boundary over the step to the energy terms.
    pub(crate) fn work<const L: usize>(&self, w: &mut Work<'_, L>) {
        self.drivers.work(w);
        self.plate.work(w);
        self.pressure.work(w);
        self.traction.work(w);
        self.absorbing.work(w);
        self.rollers.work(w);
    }

    /// The bound on how much the boundaries raise `ω²_max` (1/s²): the sum of theirs (Weyl's
    /// inequality for a sum of positive semi-definite perturbations).
    pub fn stiffening(&self, inv_mass: &[f64]) -> f64 {
        self.rollers.stiffening(inv_mass)
            + self.drivers.stiffening(inv_mass)
            + self.plate.stiffening(inv_mass)
            + self.pressure.stiffening(inv_mass)
            + self.traction.stiffening(inv_mass)
            + self.absorbing.stiffening(inv_mass)
    }

    /// Why the skip-ahead cannot follow these boundaries, if it cannot.
    pub fn skip_ahead(&self) -> Result<(), &'static str> {
        self.rollers.skip_ahead()?;
        self.drivers.skip_ahead()?;
        self.plate.skip_ahead()?;
        self.pressure.skip_ahead()?;
        self.traction.skip_ahead()?;
        self.absorbing.skip_ahead()
    }
}
