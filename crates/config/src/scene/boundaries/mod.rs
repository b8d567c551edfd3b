//! The boundary conditions of a scene as the configuration knows them, one file per kind: its
//! section's keys checked into what the solver's `boundary` kind is built from, and its refusals.
//! The initial tractions of a fault are the fault's (`scene::fault`).

mod absorbing;
mod drivers;
mod plate;
mod rollers;

use stickslip_solver::geometry::{Face, NodeId};
use stickslip_solver::scene::{BoundarySpec, LoadingPlate, NormalLoad};

pub use absorbing::AbsorbingSection;
pub(super) use absorbing::absorbing;
pub(super) use drivers::{drivers, refuse_held_drivers};
pub(super) use plate::loading_plate;
pub(super) use rollers::rollers;

/// The scene's list of boundaries: each kind the file gives, in one order.
pub(super) fn specs(
    fixed: Vec<(NodeId, [bool; 3])>,
    drivers: Vec<NodeId>,
    plate: Option<LoadingPlate>,
    normal_load: Option<NormalLoad>,
    absorbing: Vec<Face>,
) -> Vec<BoundarySpec> {
    let mut out = Vec::new();
    if !fixed.is_empty() {
        out.push(BoundarySpec::Rollers(fixed));
    }
    if !drivers.is_empty() {
        out.push(BoundarySpec::Drivers(drivers));
    }
    out.extend(plate.map(BoundarySpec::Plate));
    out.extend(normal_load.map(BoundarySpec::Pressure));
    if !absorbing.is_empty() {
        out.push(BoundarySpec::Absorbing(absorbing));
    }
    out
}
