//! Drivers: driven nodes whose x follows the displacement of Eq. 12 from where they stood when
//! the shear stage started (docs/model.md §5). The reaction that takes the trial there is the
//! loading force; its work is the loading's. A driver adds no stiffness (a held component), and
//! the skip-ahead's quasi-static motion follows it.

use super::{Boundary, LoadingState, Phase, Step, Work};
use crate::field::Field;
use crate::geometry::NodeId;
use crate::scene::Scene;

/// The driven nodes of the scene.
#[derive(Clone, Debug, Default)]
pub struct Drivers {
    /// Internal indices.
    pub nodes: Vec<u32>,
}

impl Drivers {
    /// The drivers of `scene`.
    pub(crate) fn new(scene: &Scene, internal: &dyn Fn(NodeId) -> Option<u32>) -> Drivers {
        Drivers { nodes: scene.drivers().iter().filter_map(|&id| internal(id)).collect() }
    }
}

impl Boundary for Drivers {
    fn phase(&self) -> Phase {
        Phase::Prescribed
    }

    /// Turns the drivers of lane `l` on, based where they stand now (the newest time level).
    fn start<const L: usize>(&self, loading: &mut LoadingState<L>, now: &Field<L>, l: usize) {
        for (d, &node) in self.nodes.iter().enumerate() {
            loading.base[d][l] = now.c[0][node as usize][l];
        }
    }

    /// x of each driven node set to its base plus the target; the reaction is the force that
    /// takes the trial there.
    fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
        let (mass, cf, d_state, trial) = (s.mass, s.cf, &mut *s.loading, &mut *s.trial);
        for (d, &node) in self.nodes.iter().enumerate() {
            let i = node as usize;
            for l in 0..L {
                if !d_state.on[l] {
                    d_state.reaction[d][l] = 0.0;
                    continue;
                }
                let target = d_state.base[d][l] + d_state.target[l];
                d_state.reaction[d][l] = (target - trial.c[0][i][l]) * mass[i] / cf[l];
                trial.c[0][i][l] = target;
            }
        }
    }

    fn work<const L: usize>(&self, w: &mut Work<'_, L>) {
        for (d, &node) in self.nodes.iter().enumerate() {
            let i = node as usize;
            let part = w.layer(i);
            for l in 0..L {
                w.parts[part][l].driver_work += 0.5 * w.loading.reaction[d][l] * (w.new.c[0][i][l] - w.old.c[0][i][l]);
            }
        }
    }
}
