//! The initial tractions on a fault's face (docs/model.md §15): a constant force `τ0·A_i` along x
//! and y on every node of the base face, from the start of the run, in each seed's own values
//! ([`crate::fault::FaultLanes`], carried by the step's parameters). Measured from the prestressed
//! equilibrium, the force is what the prestressed body pulls on the fault with; the friction of
//! the other side balances it while the node sticks. A smooth overstress
//! ([`crate::fault::Overstress`]) adds its peak force along x times its ramp `G(t)`. Its work is the ledger's `traction_work`; it
//! adds no stiffness. The skip-ahead's motion does not include it.

use super::{Boundary, Phase, Step, Work};
use crate::geometry::NodeId;
use crate::scene::Scene;

/// The nodes of a fault's face (internal indices, order of [`crate::Model::contact`]); empty on
/// the rigid base.
#[derive(Clone, Debug, Default)]
pub struct Traction {
    /// Internal node of each contact node, when the base is a fault.
    pub nodes: Vec<u32>,
}

impl Traction {
    /// The loaded nodes of `scene`: the contact nodes when the base is a fault.
    pub(crate) fn new(scene: &Scene, internal: &dyn Fn(NodeId) -> Option<u32>) -> Traction {
        if !scene.is_fault() {
            return Traction::default();
        }
        Traction { nodes: scene.lattice().contact_nodes().into_iter().filter_map(internal).collect() }
    }
}

impl Boundary for Traction {
    fn phase(&self) -> Phase {
        Phase::Force
    }

    fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
        let Some(f) = s.fault else { return };
        for (ci, &node) in self.nodes.iter().enumerate() {
            let i = node as usize;
            for axis in 0..2 {
                let force = &f.shear_n[axis][ci];
                for l in 0..L {
                    s.trial.c[axis][i][l] += force[l] * s.cf[l] / s.mass[i];
                }
            }
        }
        let g = &s.loading.overstress;
        for (peak, &node) in f.overstress_n.iter().zip(&self.nodes) {
            let i = node as usize;
            for l in 0..L {
                s.trial.c[0][i][l] += peak[l] * g[l] * s.cf[l] / s.mass[i];
            }
        }
    }

    fn work<const L: usize>(&self, w: &mut Work<'_, L>) {
        let Some(f) = w.fault else { return };
        for (ci, &node) in self.nodes.iter().enumerate() {
            let i = node as usize;
            let part = w.layer(i);
            for l in 0..L {
                let mut sum = 0.0;
                for axis in 0..2 {
                    sum += f.shear_n[axis][ci][l] * (w.new.c[axis][i][l] - w.old.c[axis][i][l]);
                }
                if let Some(peak) = f.overstress_n.get(ci) {
                    sum += peak[l] * w.loading.overstress[l] * (w.new.c[0][i][l] - w.old.c[0][i][l]);
                }
                w.parts[part][l].traction_work += 0.5 * sum;
            }
        }
    }

    fn skip_ahead(&self) -> Result<(), &'static str> {
        if self.nodes.is_empty() {
            Ok(())
        } else {
            Err("the skip-ahead's quasi-static motion does not include a fault's tractions")
        }
    }
}
