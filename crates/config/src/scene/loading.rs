//! `[self_weight]` and `[shear]` checked: the two loading stages and the shear's drivers.

use stickslip_solver::geometry::{Face, Lattice, NodeId};
use stickslip_solver::scene::{SelfWeight, SettleMethod, Shear};

use super::block::resolve_nodes;
use super::{MaterialSection, SceneSections, SelfWeightSection, ShearSection};
use crate::check::Checker;

/// The self-weight stage of `[self_weight]`.
pub(super) fn self_weight(ck: &mut Checker, s: &SelfWeightSection) -> SelfWeight {
    ck.non_negative("self_weight.gravity_m_s2", s.gravity_m_s2);
    let method = ck.named::<SettleMethod>("self_weight.method", &s.method).unwrap_or_default();
    ck.non_negative("self_weight.damping_per_s", s.damping_per_s);
    ck.range("self_weight.settle_tolerance", s.settle_tolerance, 0.0, true, 1.0, true);
    ck.positive("self_weight.max_duration_s", s.max_duration_s);
    SelfWeight {
        gravity_m_s2: s.gravity_m_s2,
        method,
        damping_per_s: s.damping_per_s,
        settle_tolerance: s.settle_tolerance,
        max_duration_s: s.max_duration_s,
    }
}

/// Checks the numbers of `[shear]`: the driver's speed against a fraction of the wave speed of
/// `[material]`.
pub(super) fn check_shear(ck: &mut Checker, sh: &ShearSection, m: &MaterialSection) {
    ck.non_negative("shear.damping_per_s", sh.damping_per_s);
    ck.non_negative("shear.rise_time_s", sh.rise_time_s);
    ck.positive("shear.duration_s", sh.duration_s);
    // A driver at rest loads nothing: the shear stage would only ring down (refused rather than
    // run to a catalogue that is empty for no visible reason). A driver faster than a fraction of
    // the wave speed is outside the model's reach (the bound is left to the material's own
    // refusal when the material gives no wave speed).
    let cp_bound = 0.01 * (m.young_pa / m.density_kg_m3).sqrt();
    if ck.positive("shear.velocity_m_s", sh.velocity_m_s) && cp_bound.is_normal() && cp_bound > 0.0 {
        ck.range("shear.velocity_m_s", sh.velocity_m_s, 0.0, true, cp_bound, false);
    }
}

/// The driven nodes of `[shear]`, sorted and unique: its lists and face, or the default node at
/// `(0, 0, 2·Lc)` when it gives none (none when a `[loading_plate]` loads the block); a base
/// node is refused while the base carries a load.
pub(super) fn drivers(ck: &mut Checker, file: SceneSections<'_>, lattice: &Lattice) -> Vec<NodeId> {
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
pub(super) fn refuse_held_drivers(ck: &mut Checker, drivers: &[NodeId], fixed: &[(NodeId, [bool; 3])]) {
    for d in drivers {
        if let Ok(i) = fixed.binary_search_by_key(d, |(id, _)| *id)
            && fixed[i].1[0]
        {
            ck.push("shear.driver", format!("LDEM {}", d.ldem()), "a node whose x is not held by a [[boundary]]");
        }
    }
}

/// The shear stage of `[shear]` with its checked `drivers`.
pub(super) fn shear(sh: &ShearSection, drivers: Vec<NodeId>) -> Shear {
    Shear {
        damping_per_s: sh.damping_per_s,
        velocity_m_s: sh.velocity_m_s,
        rise_time_s: sh.rise_time_s,
        duration_s: sh.duration_s,
        drivers,
    }
}
