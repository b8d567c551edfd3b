//! Static and dynamic coefficients: a node holds up to μs·N and slides at μd·N from its first
//! step of slip; it heals (back to μs) when it sticks again.

use crate::laws::{Law, NodeFriction};

/// Static/dynamic friction, `μd ≤ μs`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticDynamic {
    /// μs.
    pub mu_static: f64,
    /// μd.
    pub mu_dynamic: f64,
}

impl Law for StaticDynamic {
    /// μd.
    #[inline(always)]
    fn kinetic(&self, node: &NodeFriction, _path: f64) -> f64 {
        node.mu_dynamic
    }
}
