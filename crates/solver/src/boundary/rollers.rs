//! Rollers: held displacement components of nodes or faces (`[[boundary]]`). A held component
//! keeps the value it had, so it does no work and adds no stiffness; the skip-ahead's static
//! solves hold it too.

use super::{Boundary, Phase, Prescribed, Step, Work};
use crate::geometry::NodeId;
use crate::scene::Scene;

/// The held components of the scene's nodes.
#[derive(Clone, Debug, Default)]
pub struct Rollers {
    /// Internal node and which of x, y, z it holds.
    pub nodes: Vec<(u32, [bool; 3])>,
}

impl Rollers {
    /// The rollers of `scene`.
    pub(crate) fn new(scene: &Scene, internal: &dyn Fn(NodeId) -> Option<u32>) -> Rollers {
        Rollers { nodes: scene.fixed().iter().filter_map(|(id, m)| Some((internal(*id)?, *m))).collect() }
    }
}

impl Boundary for Rollers {
    fn phase(&self) -> Phase {
        Phase::Held
    }

    /// The held components as constraints of a static solve, each at `value(node, axis)`.
    fn held(&self, value: &dyn Fn(usize, usize) -> f64) -> Vec<Prescribed> {
        let mut out = Vec::new();
        for &(node, mask) in &self.nodes {
            for axis in (0..3).filter(|&a| mask[a]) {
                out.push(Prescribed { node: node as usize, axis, value: value(node as usize, axis) });
            }
        }
        out
    }

    /// Held components keep the value they had (the trial's `uₙ₊₁` ← `uₙ`).
    fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
        for &(node, mask) in &self.nodes {
            for c in 0..3 {
                if mask[c] {
                    s.trial.c[c][node as usize] = s.now.c[c][node as usize];
                }
            }
        }
    }

    /// A held component does not move: no work.
    fn work<const L: usize>(&self, _: &mut Work<'_, L>) {}
}
