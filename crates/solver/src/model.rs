//! A built scene: the lattice in the stepper's internal order, masses, nominal bar stiffness,
//! and the node sets (contact, drivers, rollers, control) the stepper works on.
//!
//! Built once per scene and shared (read-only) by every seed of an ensemble; a seed only adds its
//! random factors ([`Model::bar_stiffness`], [`Model::friction_factors`]).

use crate::error::SolverError;
use crate::lattice::{BarFamily, Direction, Lattice, NodeId};
use crate::material::{STREAM_FRICTION, STREAM_YOUNG, axial_stiffness, weibull_factors};
use crate::scene::Scene;

/// A run of bars sharing one direction class, `bars[start..end]` in internal order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarGroup {
    /// Direction class.
    pub direction: Direction,
    /// First bar (internal index).
    pub start: usize,
    /// One past the last bar.
    pub end: usize,
}

/// The scene built into flat arrays, in the stepper's internal node and bar order.
///
/// Internal node order: by `z`, then `y`, then `x` of the position (centre nodes fall between
/// the corner layers), so bars join nodes that are close in memory. Internal bar order: grouped by
/// direction class (seven groups), sorted by end nodes inside a group.
#[derive(Clone, Debug)]
pub struct Model {
    scene: Scene,
    lattice: Lattice,
    /// internal index → canonical id.
    to_canonical: Vec<NodeId>,
    /// canonical index → internal index.
    to_internal: Vec<u32>,
    mass: Vec<f64>,
    inv_mass: Vec<f64>,
    groups: Vec<BarGroup>,
    ends: Vec<[u32; 2]>,
    /// internal bar → canonical bar index.
    bar_canonical: Vec<u32>,
    /// Kernel stiffness of each internal bar for a homogeneous field: `EA/L` (surface reduction
    /// applied), divided by 3 for diagonals (see [`crate::kernel`]).
    nominal_k: Vec<f64>,
    contact: Vec<u32>,
    drivers: Vec<u32>,
    fixed: Vec<(u32, [bool; 3])>,
}

impl Model {
    /// Builds the lattice of `scene` and everything the stepper needs.
    pub fn new(scene: Scene) -> Model {
        let lattice = scene.lattice();
        let n = lattice.node_count();
        let mut to_canonical: Vec<NodeId> = (0..n as u32).map(NodeId).collect();
        to_canonical.sort_by_key(|&id| {
            let h = lattice.half_units(id);
            (h[2], h[1], h[0])
        });
        let mut to_internal = vec![0u32; n];
        for (i, id) in to_canonical.iter().enumerate() {
            to_internal[id.index()] = i as u32;
        }
        let rho_lc3 = scene.density_kg_m3 * scene.lc_m.powi(3);
        let mass: Vec<f64> = to_canonical.iter().map(|&id| lattice.mass_fraction(id) * rho_lc3).collect();
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();

        // Bars: internal ends, grouped by direction, sorted inside groups.
        let mut order: Vec<(Direction, [u32; 2], u32)> = lattice
            .bars()
            .iter()
            .enumerate()
            .map(|(b, bar)| {
                let e = bar.ends.map(|id| to_internal[id.index()]);
                (bar.direction, e, b as u32)
            })
            .collect();
        order.sort_by_key(|&(d, e, _)| (d, e[0].min(e[1]), e[0].max(e[1])));
        let mut groups: Vec<BarGroup> = Vec::new();
        for (i, (d, _, _)) in order.iter().enumerate() {
            match groups.last_mut() {
                Some(g) if g.direction == *d => g.end = i + 1,
                _ => groups.push(BarGroup { direction: *d, start: i, end: i + 1 }),
            }
        }
        let ends = order.iter().map(|&(_, e, _)| e).collect();
        let bar_canonical: Vec<u32> = order.iter().map(|&(_, _, b)| b).collect();
        let nominal_k = bar_canonical
            .iter()
            .map(|&b| {
                let bar = &lattice.bars()[b as usize];
                let ea = axial_stiffness(bar.family, scene.young_pa, scene.poisson, scene.lc_m);
                let k = bar.surface_factor * ea / (bar.length_factor() * scene.lc_m);
                if bar.family == BarFamily::Diagonal { k / 3.0 } else { k }
            })
            .collect();
        let contact = lattice.contact_nodes().iter().map(|id| to_internal[id.index()]).collect();
        let drivers = scene.shear.drivers.iter().map(|id| to_internal[id.index()]).collect();
        let fixed = scene.fixed.iter().map(|(id, m)| (to_internal[id.index()], *m)).collect();
        Model {
            scene,
            lattice,
            to_canonical,
            to_internal,
            mass,
            inv_mass,
            groups,
            ends,
            bar_canonical,
            nominal_k,
            contact,
            drivers,
            fixed,
        }
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The lattice (canonical order).
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.mass.len()
    }

    /// Number of bars.
    pub fn bar_count(&self) -> usize {
        self.ends.len()
    }

    /// Internal index of a canonical node.
    pub fn internal(&self, id: NodeId) -> usize {
        self.to_internal[id.index()] as usize
    }

    /// Canonical id of an internal node index.
    pub fn canonical(&self, internal: usize) -> NodeId {
        self.to_canonical[internal]
    }

    /// Lumped masses (kg), internal order.
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }

    /// Inverse masses (1/kg), internal order.
    pub fn inv_mass(&self) -> &[f64] {
        &self.inv_mass
    }

    /// Total mass (kg).
    pub fn total_mass(&self) -> f64 {
        self.mass.iter().sum()
    }

    /// Bar groups (direction classes) in internal bar order.
    pub fn groups(&self) -> &[BarGroup] {
        &self.groups
    }

    /// Bar end nodes (internal indices), internal bar order.
    pub fn ends(&self) -> &[[u32; 2]] {
        &self.ends
    }

    /// Canonical index of each internal bar.
    pub fn bar_canonical(&self) -> &[u32] {
        &self.bar_canonical
    }

    /// Homogeneous kernel stiffness per internal bar (N/m; diagonals divided by 3).
    pub fn nominal_stiffness(&self) -> &[f64] {
        &self.nominal_k
    }

    /// Contact nodes (internal indices).
    pub fn contact(&self) -> &[u32] {
        &self.contact
    }

    /// Driven nodes (internal indices).
    pub fn drivers(&self) -> &[u32] {
        &self.drivers
    }

    /// Nodes with held components (internal indices).
    pub fn fixed(&self) -> &[(u32, [bool; 3])] {
        &self.fixed
    }

    /// Kernel stiffness of every bar for `seed`: nominal times the Weibull factor of E drawn in
    /// canonical bar order from the seed's E stream (none drawn when CV = 0).
    pub fn bar_stiffness(&self, seed: u64) -> Result<Vec<f64>, SolverError> {
        let mut k = self.nominal_k.clone();
        if let Some(phi) = weibull_factors(self.scene.young_cv, seed, STREAM_YOUNG, self.bar_count())? {
            for (kb, &canon) in k.iter_mut().zip(&self.bar_canonical) {
                *kb *= phi[canon as usize];
            }
        }
        Ok(k)
    }

    /// Friction factors of the contact nodes (order of [`Model::contact`]) for `seed`: the
    /// Weibull field on μ drawn in canonical contact order from the seed's friction stream, or
    /// all ones when its CV is 0.
    pub fn friction_factors(&self, seed: u64) -> Result<Vec<f64>, SolverError> {
        let n = self.contact.len();
        Ok(weibull_factors(self.scene.friction.mu_cv, seed, STREAM_FRICTION, n)?.unwrap_or_else(|| vec![1.0; n]))
    }
}
