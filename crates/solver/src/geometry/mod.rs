//! Geometry and numbering of the LDEM lattice (docs/model.md §1): nodes, bars, node sets.

pub mod lattice;
pub mod sets;

pub use lattice::{Bar, BarFamily, Dims, Direction, Lattice, NodeId, NodeKind};
pub use sets::{Face, NodeSet};
