//! stickslip solver: the Lattice Discrete Element Method for stick-slip on a frictional base.
//!
//! A block of cubic truss modules (Nayfeh & Hefzy) with a Weibull random Young's modulus rests on
//! a rigid base with Coulomb friction; it settles under its own weight, then a driven node shears
//! it. Layers, from the bottom:
//! - [`lattice`]: nodes, bars, boundary reductions, lumped-mass fractions (pure geometry);
//! - [`material`]: bar stiffness and the Weibull fields;
//! - [`scene`]: the scene file (TOML) and its validation;
//! - [`model`]: a scene built into flat arrays in the stepper's order, shared by all seeds;
//! - [`kernel`], [`stepper`]: the per-bar kernels and the explicit step, `L` seeds side by side;
//! - [`critical`], [`statics`]: the critical time step and static solves;
//! - [`quasistatic`]: the static self-weight start and the skip-ahead through quiet phases;
//! - [`record`], [`run`]: recorders and the two loading stages.
//!
//! The solver does no file I/O: it hands back plain arrays ([`record::Records`]).
#![deny(missing_docs)]

pub mod critical;
pub mod error;
pub mod kernel;
pub mod lattice;
pub mod material;
pub mod model;
pub mod quasistatic;
pub mod record;
pub mod run;
pub mod scene;
pub mod statics;
pub mod stepper;

pub use error::{FieldError, SolverError};
pub use lattice::{Dims, Lattice, NodeId};
pub use model::Model;
pub use record::{Channel, Records};
pub use run::{BATCH, Perturbation, RunOptions, RunOutput, run_batched, run_lanes, run_seed};
pub use scene::{Scene, SceneFile};
