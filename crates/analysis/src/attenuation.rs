//! The attenuation of peak motions with distance (docs/model.md §8): the peaks of every control
//! node in every main shock, with the distance from the shock's hypocentre.

use stickslip_seismo::events::Catalogue;
use stickslip_solver::geometry::NodeId;
use stickslip_solver::scene::Kinematic;
use stickslip_solver::{Model, Recording};

/// Peak motions of one node during one main shock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AttenuationRow {
    /// Index of the event in the seed.
    pub event: u32,
    /// Main-shock rank (1 for S1).
    pub rank: u32,
    /// Hypocentre: the first contact node to slide for good in the event.
    pub hypocentre: NodeId,
    /// The control node.
    pub node: NodeId,
    /// Distance from the hypocentre (m).
    pub distance_m: f64,
    /// Peak magnitude of the recorded acceleration components during the event (m/s²).
    pub pga_m_s2: f64,
    /// Peak magnitude of the recorded velocity components (m/s), NaN without velocity.
    pub pgv_m_s: f64,
}

/// Peak motions of every control node in every main shock, with the distance from the shock's
/// hypocentre (its first sustained slip onset in `[start − smoothing, end]`).
pub fn attenuation(rec: &Recording, catalogue: &Catalogue, model: &Model, smoothing_s: f64) -> Vec<AttenuationRow> {
    let lattice = model.lattice();
    let t = &rec.time_s;
    let mut nodes: Vec<NodeId> = rec.control.iter().map(|(c, _)| c.node).collect();
    nodes.sort();
    nodes.dedup();
    let series = |node: NodeId, q: Kinematic| -> Vec<&[f64]> {
        rec.control.iter().filter(|(c, _)| c.node == node && c.quantity == q).map(|(_, v)| v.as_slice()).collect()
    };
    let mut rows = Vec::new();
    for (k, e) in catalogue.events.iter().enumerate() {
        let Some(rank) = e.kind.rank().filter(|_| e.kind.is_main()) else { continue };
        let Some(hypo) = hypocentre(rec, e.burst.start_s - smoothing_s, e.burst.end_s) else { continue };
        let h = lattice.position(hypo);
        let (a, b) = (t.partition_point(|&x| x < e.burst.start_s), t.partition_point(|&x| x <= e.burst.end_s));
        for &node in &nodes {
            let p = lattice.position(node);
            let distance = ((p[0] - h[0]).powi(2) + (p[1] - h[1]).powi(2) + (p[2] - h[2]).powi(2)).sqrt();
            let peak = |comps: &[&[f64]]| -> f64 {
                if comps.is_empty() {
                    return f64::NAN;
                }
                (a..b).map(|i| comps.iter().map(|c| c[i] * c[i]).sum::<f64>().sqrt()).fold(0.0, f64::max)
            };
            rows.push(AttenuationRow {
                event: k as u32,
                rank,
                hypocentre: hypo,
                node,
                distance_m: distance,
                pga_m_s2: peak(&series(node, Kinematic::Acceleration)),
                pgv_m_s: peak(&series(node, Kinematic::Velocity)),
            });
        }
    }
    rows
}

/// The first contact node to slide for good in `[from, to]` (s), if slip onsets were recorded.
pub fn hypocentre(rec: &Recording, from: f64, to: f64) -> Option<NodeId> {
    rec.onsets.iter().find(|(time, _)| *time >= from && *time <= to).map(|&(_, n)| n)
}
