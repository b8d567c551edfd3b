//! `[[boundary]]` and `[loading_plate]` checked: the rollers on faces and the plate's springs.

use stickslip_solver::geometry::{Face, Lattice, NodeId};
use stickslip_solver::scene::{Component, LoadingPlate, NormalLoad};

use super::{LoadingPlateSection, SceneSections};
use crate::check::Checker;

/// The rollers of `[[boundary]]`, merged per node and sorted. A contact node may only be held in
/// y (a symmetry plane): holding its z would keep it off the base and holding its x would take
/// the shear the base's friction should carry — unless the scene has neither gravity nor
/// friction, when the base carries nothing and rollers on it are a plain support.
pub(super) fn rollers(ck: &mut Checker, file: SceneSections<'_>, lattice: &Lattice) -> Vec<(NodeId, [bool; 3])> {
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

/// The plate and the normal load of `[loading_plate]`, every refused value recorded in `ck`.
pub(super) fn loading_plate(
    ck: &mut Checker,
    lp: &LoadingPlateSection,
    lattice: &Lattice,
    fixed: &[(NodeId, [bool; 3])],
) -> (Option<LoadingPlate>, Option<NormalLoad>) {
    let face = ck.named::<Face>("loading_plate.face", &lp.face);
    if face == Some(Face::ZMin) {
        ck.push(
            "loading_plate.face",
            "\"z_min\"",
            "a face other than the base (\"z_max\", \"x_min\", \"x_max\", \"y_min\", \"y_max\"): the base's nodes are held \
             by friction",
        );
    }
    ck.non_negative("loading_plate.normal_pressure_pa", lp.normal_pressure_pa);
    let normal_load = (lp.normal_pressure_pa > 0.0 && lp.normal_pressure_pa.is_finite())
        .then(|| NormalLoad::on_top(lattice, lp.normal_pressure_pa));
    let face = face.filter(|f| *f != Face::ZMin);
    let area = face.map(|f| {
        let e = lattice.extent();
        let (axis, _) = f.axis();
        (0..3).filter(|&a| a != axis).map(|a| e[a]).product::<f64>()
    });
    let total = match (lp.stiffness_n_m, lp.modulus_pa, lp.thickness_m) {
        (Some(k), None, None) => ck.positive("loading_plate.stiffness_n_m", k).then_some(k),
        (None, Some(g), Some(t)) => {
            let ok = ck.positive("loading_plate.modulus_pa", g) & ck.positive("loading_plate.thickness_m", t);
            ok.then(|| area.map(|a| g * a / t)).flatten()
        }
        (k, g, t) => {
            let given: Vec<String> = [("stiffness_n_m", k), ("modulus_pa", g), ("thickness_m", t)]
                .iter()
                .filter_map(|(name, v)| v.map(|v| format!("{name} = {v}")))
                .collect();
            ck.push(
                "loading_plate",
                if given.is_empty() { "no stiffness".to_string() } else { given.join(", ") },
                "either stiffness_n_m (N/m, > 0) or both modulus_pa and thickness_m",
            );
            None
        }
    };
    let (Some(face), Some(total)) = (face, total) else { return (None, normal_load) };
    let area = area.expect("a face has an area");
    let nodes = face.nodes(lattice);
    for id in &nodes {
        if let Ok(i) = fixed.binary_search_by_key(id, |(n, _)| *n)
            && fixed[i].1[0]
        {
            ck.push(
                "loading_plate.face",
                format!("\"{}\" (LDEM {} is held in x by a [[boundary]])", face.name(), id.ldem()),
                "a face whose nodes are free in x (a roller would take the springs' pull)",
            );
            break;
        }
    }
    let stiffness_n_m = nodes.iter().map(|&id| total * face.tributary_area(lattice, id) / area).collect();
    (Some(LoadingPlate { face, nodes, stiffness_n_m }), normal_load)
}
