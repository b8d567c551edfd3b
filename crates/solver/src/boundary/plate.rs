//! The loading plate (docs/model.md §12): the nodes of a face tied by springs in x to a rigid
//! plate that moves by Eq. 12 from the start of the shear stage. Each spring pulls its node with
//! `k·(base + target − x)`, `x` its displacement now (explicit, like the bar forces); the springs
//! are external forces on the block, so their work is the loading's. A spring `k` on a node of
//! mass `m` raises `ω²_max` by at most `k/m`. The skip-ahead's motion does not include them.

use super::{Boundary, LoadingState, Phase, Step, Work};
use crate::field::Field;
use crate::geometry::NodeId;
use crate::scene::Scene;

/// The springs of the scene's loading plate (none without one).
#[derive(Clone, Debug, Default)]
pub struct Plate {
    /// Internal node and spring stiffness in x (N/m).
    pub springs: Vec<(u32, f64)>,
}

impl Plate {
    /// The plate of `scene`.
    pub(crate) fn new(scene: &Scene, internal: &dyn Fn(NodeId) -> Option<u32>) -> Plate {
        let springs = scene.plate().map_or_else(Vec::new, |p| {
            p.nodes.iter().zip(&p.stiffness_n_m).filter_map(|(id, &k)| Some((internal(*id)?, k))).collect()
        });
        Plate { springs }
    }
}

impl Boundary for Plate {
    fn phase(&self) -> Phase {
        Phase::Force
    }

    /// Starts the plate of lane `l`: each spring's rest position is where its node stands now.
    fn start<const L: usize>(&self, loading: &mut LoadingState<L>, now: &Field<L>, l: usize) {
        for (j, &(node, _)) in self.springs.iter().enumerate() {
            loading.plate_base[j][l] = now.c[0][node as usize][l];
        }
    }

    /// Each spring's force `F` moves the trial by `F·cf/m` (the update's `cf·f/m`).
    fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
        let (mass, cf, d_state, now, trial) = (s.mass, s.cf, &mut *s.loading, s.now, &mut *s.trial);
        for (j, &(node, k)) in self.springs.iter().enumerate() {
            let i = node as usize;
            for l in 0..L {
                let f = if d_state.on[l] {
                    k * (d_state.plate_base[j][l] + d_state.target[l] - now.c[0][i][l])
                } else {
                    0.0
                };
                d_state.plate_force[j][l] = f;
                trial.c[0][i][l] += f * cf[l] / mass[i];
            }
        }
    }

    fn work<const L: usize>(&self, w: &mut Work<'_, L>) {
        for (j, &(node, _)) in self.springs.iter().enumerate() {
            let i = node as usize;
            let part = w.layer(i);
            for l in 0..L {
                w.parts[part][l].driver_work +=
                    0.5 * w.loading.plate_force[j][l] * (w.new.c[0][i][l] - w.old.c[0][i][l]);
            }
        }
    }

    fn stiffening(&self, inv_mass: &[f64]) -> f64 {
        self.springs.iter().map(|&(i, k)| k * inv_mass[i as usize]).fold(0.0, f64::max)
    }

    fn skip_ahead(&self) -> Result<(), &'static str> {
        if self.springs.is_empty() {
            Ok(())
        } else {
            Err("the skip-ahead's quasi-static motion does not include the loading plate's springs")
        }
    }
}
