//! Earthquake cycles: centuries of plate loading between ruptures on a rate-and-state fault
//! (docs/model.md §20).
//!
//! The explicit step cannot cross the interseismic phase (10¹¹ steps a century at 50 m), so the
//! cycle runs on the fault alone: the lattice's quasi-static response to slip is computed once
//! ([`antiplane`]: the antiplane mode of a slab one module thick, its fault stiffness `K` from
//! the lattice's own stencil), and the fault's slip and state are integrated with an adaptive
//! step through both phases, inertia replaced by radiation damping ([`quasi_dynamic`]). A scene's
//! `[cycles]` run ([`spec`]) builds its fault from the scene's friction and tractions; the SEAS
//! benchmarks' files and the catalogue of events are written from the accepted steps by the
//! ensemble crate.

pub mod antiplane;
pub mod dynamic;
pub mod heterogeneity;
pub mod quasi_dynamic;
pub mod spec;

pub use crate::laws::balanced_state;
pub use antiplane::{AntiplaneStencil, FaultStiffness, antiplane_links};
pub use dynamic::{AntiplaneGrid, FullyDynamicFault, GridField};
pub use heterogeneity::Heterogeneity;
pub use quasi_dynamic::{CycleState, CycleStats, Flow, QuasiDynamicFault, Tolerances, YEAR_S};
pub use spec::{CycleSpec, DynamicSpec, scene_stencil};
