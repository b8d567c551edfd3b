//! The boundary conditions of a scene as the configuration knows them, one file per kind: its
//! section's keys checked into what the solver's `boundary` kind is built from, and its refusals.
//! The initial tractions of a fault are the fault's (`scene::fault`).

mod absorbing;
mod drivers;
mod plate;
mod rollers;

pub use absorbing::AbsorbingSection;
pub(super) use absorbing::absorbing;
pub(super) use drivers::{drivers, refuse_held_drivers};
pub(super) use plate::loading_plate;
pub(super) use rollers::rollers;
