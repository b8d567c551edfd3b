//! The loading plate: `[loading_plate]` checked into the plate's springs and the normal pressure
//! on the top face.

use stickslip_solver::geometry::{Face, Lattice, NodeId};
use stickslip_solver::scene::{LoadingPlate, NormalLoad};

use crate::check::Checker;
use crate::scene::LoadingPlateSection;

/// The plate and the normal load of `[loading_plate]`, every refused value recorded in `ck`.
pub(in crate::scene) fn loading_plate(
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
