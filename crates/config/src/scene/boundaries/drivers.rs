//! Drivers: the driven nodes of `[shear]` (its node lists and face) checked.

use stickslip_solver::geometry::{Face, Lattice, NodeId};

use crate::check::Checker;
use crate::scene::SceneSections;
use crate::scene::block::resolve_nodes;

/// The driven nodes of `[shear]`, sorted and unique: its lists and face, or the default node at
/// `(0, 0, 2·Lc)` when it gives none (none when a `[loading_plate]` loads the block); a base
/// node is refused while the base carries a load.
pub(in crate::scene) fn drivers(ck: &mut Checker, file: SceneSections<'_>, lattice: &Lattice) -> Vec<NodeId> {
    let sh = &file.shear;
    let no_drivers_given = sh.driver_nodes.is_empty() && sh.driver_at_m.is_empty();
    let (driver_ldem, driver_at): (&[i64], Vec<[f64; 3]>) =
        if no_drivers_given && (file.loading_plate.is_some() || file.fault.is_some()) {
            // The plate or the fault's tractions load the block: no default driver node.
            (&[], Vec::new())
        } else if no_drivers_given {
            (&[], vec![[0.0, 0.0, 2.0 * file.block.lc_m]])
        } else {
            (&sh.driver_nodes, sh.driver_at_m.clone())
        };
    let (driver_ldem, driver_at) = match sh.driver_face {
        Some(_) if sh.driver_nodes.is_empty() && sh.driver_at_m.is_empty() => (&[][..], Vec::new()),
        _ => (driver_ldem, driver_at),
    };
    let mut drivers = resolve_nodes(ck, lattice, ("shear.driver_nodes", "shear.driver_at_m"), driver_ldem, &driver_at);
    if let Some(face) = &sh.driver_face
        && let Some(face) = ck.named::<Face>("shear.driver_face", face)
    {
        drivers.extend(face.nodes(lattice));
    }
    drivers.sort();
    drivers.dedup();
    // Without gravity and friction the base carries nothing, and a base node may be driven.
    let base_carries = file.base_carries();
    for d in drivers.iter().filter(|_| base_carries) {
        if lattice.half_units(*d)[2] == 0 {
            ck.push(
                "shear.driver",
                format!("LDEM {} at {} m", d.ldem(), {
                    let p = lattice.position(*d).map(stickslip_seismo::catalogue::compact);
                    format!("({}, {}, {})", p[0], p[1], p[2])
                }),
                "a node above the base (z > 0): base nodes are held by friction (any node, without gravity and \
                 friction)",
            );
        }
    }
    drivers
}

/// Refuses every driven node whose x a roller of `[[boundary]]` holds (`fixed`, sorted by node).
pub(in crate::scene) fn refuse_held_drivers(ck: &mut Checker, drivers: &[NodeId], fixed: &[(NodeId, [bool; 3])]) {
    for d in drivers {
        if let Ok(i) = fixed.binary_search_by_key(d, |(id, _)| *id)
            && fixed[i].1[0]
        {
            ck.push("shear.driver", format!("LDEM {}", d.ldem()), "a node whose x is not held by a [[boundary]]");
        }
    }
}
