//! Bar breaks as acoustic-emission events (docs/model.md §11): the solver's breaks placed at
//! their bars' midpoints and grouped into clusters.

use stickslip_seismo::emission::{Break, Cluster, ClusterParams, clusters};
use stickslip_solver::Crack;
use stickslip_solver::geometry::Lattice;
use stickslip_solver::step::rupture::CrackKind;

/// The bar breaks of a crack list as the acoustic-emission clustering takes them.
pub fn breaks(cracks: &[Crack], lattice: &Lattice) -> Vec<Break> {
    cracks
        .iter()
        .filter(|c| c.kind == CrackKind::Break)
        .map(|c| Break {
            time_s: c.time_s,
            position: lattice.bar_midpoint(&lattice.bar(c.bar as usize)),
            energy_j: c.energy_j,
        })
        .collect()
}

/// The acoustic-emission events of a seed's cracks.
pub fn emission(cracks: &[Crack], lattice: &Lattice, params: &ClusterParams) -> Vec<Cluster> {
    clusters(&breaks(cracks, lattice), params)
}
