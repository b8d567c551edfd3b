//! The plain Coulomb law: one coefficient μ for sticking and sliding (the paper's law).

use crate::laws::{Law, NodeFriction};

/// Coulomb friction with one coefficient (`μs = μd = μ`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coulomb {
    /// μ.
    pub mu: f64,
}

impl Law for Coulomb {
    /// μ whatever the slip (a node's μd equals its μs).
    #[inline(always)]
    fn kinetic(&self, node: &NodeFriction, _path: f64) -> f64 {
        node.mu_static
    }
}
