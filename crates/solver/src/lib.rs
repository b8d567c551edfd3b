//! stickslip solver: the Lattice Discrete Element Method for stick-slip on a frictional base.
//!
//! Owns the physics: a block of cubic truss modules (Nayfeh & Hefzy) with a Weibull random
//! Young's modulus rests on a rigid base with friction; it settles under its own weight, then
//! driven nodes shear it (docs/model.md §1–§6). Must not know: files, the pipeline format,
//! tables, figures — it takes a validated [`Scene`] and hands back plain arrays
//! ([`Recording`]). Layers, from the bottom:
//! - [`geometry`]: nodes, bars, numbering, node sets (pure geometry);
//! - [`material`]: bar stiffness and the Weibull fields;
//! - [`laws`]: the friction laws of the base (one kinetic-coefficient formula);
//! - [`dispersion`]: plane waves in the unbounded lattice and the highest frequency it resolves;
//! - [`rupture`]: the bilinear softening law of bars that crack (opt-in), crack areas, the
//!   fields on the fracture energy;
//! - [`scene`]: the validated scene; [`model`]: it built into flat arrays, shared by all seeds,
//!   with its bars in kernel order ([`layout`]) and its boundary conditions ([`boundary`]:
//!   rollers, drivers, the loading plate, a normal pressure);
//! - [`field`]: vector fields over the nodes, `L` seeds side by side; [`step`]: one explicit
//!   step of `L` seeds (state, parameters and scratch apart; bar, integrate and contact kernels);
//! - [`statics`]: static solves, the critical time step, effective moduli;
//! - [`quasistatic`]: the static self-weight start and the skip-ahead through quiet phases;
//! - [`recording`], [`trace`], [`run`]: recorders, the event trace and the two loading stages; [`inspect`]: what a scene
//!   builds, for `stickslip check`.
#![deny(missing_docs)]

pub mod boundary;
pub mod cycles;
pub mod dispersion;
pub mod error;
pub mod fault;
pub mod field;
pub mod geometry;
pub mod inspect;
pub mod laws;
pub mod layout;
pub mod ledger;
pub mod material;
pub mod medium;
pub mod memory;
pub mod model;
mod observe;
pub mod quasistatic;
pub mod recording;
pub mod run;
pub mod rupture;
pub mod scene;
mod slabs;
pub mod split;
pub mod statics;
pub mod stencil;
pub mod step;
pub mod stiffness;
pub mod trace;

pub use error::SolverError;
pub use geometry::{Dims, Lattice, NodeId};
pub use model::Model;
pub use recording::{Channel, Crack, Recording, Sampling};
pub use run::{
    BATCH, BarDamage, Checkpoint, Perturbation, RunOptions, RunOutput, run_batched, run_lanes, run_seed,
    run_seed_checkpointed,
};
pub use scene::Scene;
pub use scene::TracePlan;
pub use trace::Trace;
