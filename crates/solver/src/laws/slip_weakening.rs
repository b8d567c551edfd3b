//! Linear slip weakening (Ida 1972; Andrews 1976): while a node slides, its coefficient falls
//! linearly from μs to μd over a slip Dc, `μ_k(s) = μs − (μs − μd)·min(s/Dc, 1)`, with s the slip
//! of the current slide; a node that sticks again heals to μs.

use crate::laws::{Law, NodeFriction};

/// Linear slip weakening from μs to μd over `dc_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipWeakening {
    /// μs.
    pub mu_static: f64,
    /// μd.
    pub mu_dynamic: f64,
    /// Dc (m), > 0.
    pub dc_m: f64,
}

impl Law for SlipWeakening {
    /// `μs − (μs − μd)·min(path/Dc, 1)`.
    #[inline(always)]
    fn kinetic(&self, node: &NodeFriction, path: f64) -> f64 {
        let (ms, md) = (node.mu_static, node.mu_dynamic);
        ms - (ms - md) * (path / self.dc_m).min(1.0)
    }
}
