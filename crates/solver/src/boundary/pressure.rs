//! A constant normal pressure on the top face, pressing the block onto the base: forces in −z on
//! the face's nodes in proportion to their share of its area, in both stages (like gravity). Its
//! work is counted with the body forces'; it adds no stiffness, and the static self-weight solve
//! includes it. The skip-ahead's motion does not include it.

use super::{Boundary, Phase, Step, Work};
use crate::field::Field;
use crate::geometry::NodeId;
use crate::scene::Scene;

/// The nodal forces of the scene's normal pressure (none without one).
#[derive(Clone, Debug, Default)]
pub struct Pressure {
    /// Internal node and its force in z (N, negative: pressing down).
    pub loads: Vec<(u32, f64)>,
}

impl Pressure {
    /// The pressure of `scene`.
    pub(crate) fn new(scene: &Scene, internal: &dyn Fn(NodeId) -> Option<u32>) -> Pressure {
        let loads = scene.normal_load().map_or_else(Vec::new, |n| {
            n.nodes.iter().zip(&n.force_n).filter_map(|(id, &f)| Some((internal(*id)?, -f))).collect()
        });
        Pressure { loads }
    }
}

impl Boundary for Pressure {
    fn phase(&self) -> Phase {
        Phase::Force
    }

    /// Adds its forces to the loads of a static solve.
    fn static_load(&self, loads: &mut Field<1>) {
        for &(node, f) in &self.loads {
            loads.c[2][node as usize][0] += f;
        }
    }

    fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
        let (mass, cf, trial) = (s.mass, s.cf, &mut *s.trial);
        for &(node, f) in &self.loads {
            let i = node as usize;
            for l in 0..L {
                trial.c[2][i][l] += f * cf[l] / mass[i];
            }
        }
    }

    fn work<const L: usize>(&self, w: &mut Work<'_, L>) {
        for &(node, f) in &self.loads {
            let i = node as usize;
            let part = w.layer(i);
            for l in 0..L {
                w.parts[part][l].body_work += 0.5 * f * (w.new.c[2][i][l] - w.old.c[2][i][l]);
            }
        }
    }

    fn skip_ahead(&self) -> Result<(), &'static str> {
        if self.loads.is_empty() {
            Ok(())
        } else {
            Err("the skip-ahead's quasi-static motion does not include the normal pressure")
        }
    }
}
