//! Rollers: `[[boundary]]` checked into held components of faces' nodes.

use stickslip_solver::geometry::{Face, Lattice, NodeId};
use stickslip_solver::scene::Component;

use crate::check::Checker;
use crate::scene::SceneSections;

/// The rollers of `[[boundary]]`, merged per node and sorted. A contact node may only be held in
/// y (a symmetry plane): holding its z would keep it off the base and holding its x would take
/// the shear the base's friction should carry — unless the scene has neither gravity nor
/// friction, when the base carries nothing and rollers on it are a plain support.
pub(in crate::scene) fn rollers(
    ck: &mut Checker,
    file: SceneSections<'_>,
    lattice: &Lattice,
) -> Vec<(NodeId, [bool; 3])> {
    let mut fixed: Vec<(NodeId, [bool; 3])> = Vec::new();
    for (i, bnd) in file.boundary.iter().enumerate() {
        if bnd.fix.is_empty() {
            ck.push(format!("boundary[{i}].fix"), "[]", "at least one of \"x\", \"y\", \"z\"");
        }
        let Some(face) = ck.named::<Face>(&format!("boundary[{i}].face"), &bnd.face) else { continue };
        let comps: Vec<Component> = ck.named_list(&format!("boundary[{i}].fix"), &bnd.fix);
        let mut mask = [false; 3];
        for c in &comps {
            mask[c.axis()] = true;
        }
        let nodes = face.nodes(lattice);
        let on_base = nodes.iter().any(|&id| lattice.half_units(id)[2] == 0);
        // Without gravity and friction the base carries nothing, and rollers on it are a plain
        // support (e.g. a wave guide).
        let base_carries = file.base_carries();
        if on_base && base_carries && (mask[0] || mask[2]) {
            let held: Vec<&str> = comps.iter().filter(|c| c.axis() != 1).map(|c| c.name()).collect();
            ck.push(
                format!("boundary[{i}]"),
                format!("face = \"{}\", fix = {:?}", bnd.face, bnd.fix),
                format!(
                    "no roller in {} on contact nodes (this face holds base nodes): it would {}; a face with base \
                     nodes may hold only \"y\" (or anything, without gravity and friction)",
                    held.join(" and "),
                    if mask[2] {
                        "keep them off the base, so the contact never acts"
                    } else {
                        "take the shear that the base's friction should carry"
                    }
                ),
            );
        }
        fixed.extend(nodes.into_iter().map(|id| (id, mask)));
    }
    fixed.sort_by_key(|(id, _)| *id);
    let mut merged: Vec<(NodeId, [bool; 3])> = Vec::new();
    for (id, mask) in fixed {
        match merged.last_mut() {
            Some((last, m)) if *last == id => (0..3).for_each(|a| m[a] |= mask[a]),
            _ => merged.push((id, mask)),
        }
    }
    merged
}
