//! Friction laws of the base (docs/model.md §4).
//!
//! A contact node in contact sticks while the tangential reaction needed to hold it still,
//! `|R_t|`, is at most `μ_hold·N`, where `μ_hold` is the node's static coefficient μs if it was
//! sticking and its kinetic coefficient if it was sliding; otherwise it slides with a friction
//! force `μ_k·N` opposing its trial motion. The laws differ only in the kinetic coefficient as a
//! function of the slip `s` of the current slide, and all three are one family
//! ([`FrictionLaw::kinetic`]):
//!
//! - **plain Coulomb** (the paper's): `μ_k = μs`;
//! - **static/dynamic**: `μ_k = μd` from the first step of slip;
//! - **linear slip weakening** (Ida 1972; Andrews 1976): `μ_k(s) = μs − (μs − μd)·min(s/Dc, 1)`.
//!
//! A node that sticks again heals to μs. The decision itself — stick, slide or lift — is written
//! once, for one node in plain scalar code ([`crate::step::contact::resolve`]) and for `L` seeds
//! side by side in the step's lane kernel, which is tested bit for bit against it; the static
//! self-weight solve and the quasi-static skip-ahead use the same static strength
//! [`NodeFriction::mu_static`]`·N`.
//!
//! The kinetic coefficient is one formula with `Dc` a value, not one function per law: the lane
//! kernel then compiles to the same vector loop whatever the law (per-law kernels left the plain
//! law's loop scalar at 4 seeds, 11% slower per step; `cargo bench -p stickslip-lab --bench step`).
//! A law outside this family adds a variant here, its arm in [`FrictionLaw::kinetic`] and its
//! section in the configuration crate, and is checked with the step benchmark.

/// The coefficients of one contact node (the law's, times the node's random-field factor).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeFriction {
    /// Static coefficient μs: a sticking node holds while `|R_t| ≤ μs·N`.
    pub mu_static: f64,
    /// Dynamic coefficient μd (equal to μs for the plain law).
    pub mu_dynamic: f64,
}

/// The plain Coulomb law: one coefficient for sticking and sliding (`μs = μd = μ`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coulomb {
    /// μ.
    pub mu: f64,
}

/// Static and dynamic coefficients: a node holds up to μs·N and slides at μd·N from its first
/// step of slip.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StaticDynamic {
    /// μs.
    pub mu_static: f64,
    /// μd ≤ μs.
    pub mu_dynamic: f64,
}

/// Linear slip weakening from μs to μd over a slip `dc_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlipWeakening {
    /// μs.
    pub mu_static: f64,
    /// μd < μs.
    pub mu_dynamic: f64,
    /// Dc (m), > 0.
    pub dc_m: f64,
}

/// The friction law of a scene, chosen once before the run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FrictionLaw {
    /// One coefficient μ: the paper's law.
    Coulomb(Coulomb),
    /// Static μs, dynamic μd from the first step of slip.
    StaticDynamic(StaticDynamic),
    /// μ falls linearly from μs to μd over a slip Dc.
    SlipWeakening(SlipWeakening),
}

impl FrictionLaw {
    /// Kinetic coefficient of a node that has slid `path` metres in its current slide: its μd
    /// (μs for the plain law) when `Dc = 0`, else `μs − (μs − μd)·min(path/Dc, 1)`.
    #[inline(always)]
    pub fn kinetic(&self, node: &NodeFriction, path: f64) -> f64 {
        let dc = self.weakening_distance_m();
        let (ms, md) = (node.mu_static, node.mu_dynamic);
        if dc == 0.0 { md } else { ms - (ms - md) * (path / dc).min(1.0) }
    }

    /// The coefficient bounding `|R_t|` of a node in contact: μs if it was sticking, its kinetic
    /// coefficient if it was sliding (`kinetic` is `self.kinetic(node, path)`, passed in so the
    /// lane kernel computes it once).
    #[inline(always)]
    pub fn holding(&self, node: &NodeFriction, sliding: bool, kinetic: f64) -> f64 {
        if sliding { kinetic } else { node.mu_static }
    }

    /// Static coefficient μs (before any field factor).
    pub fn mu_static(&self) -> f64 {
        match self {
            FrictionLaw::Coulomb(c) => c.mu,
            FrictionLaw::StaticDynamic(s) => s.mu_static,
            FrictionLaw::SlipWeakening(s) => s.mu_static,
        }
    }

    /// Dynamic coefficient μd (before any field factor); μs for the plain law.
    pub fn mu_dynamic(&self) -> f64 {
        match self {
            FrictionLaw::Coulomb(c) => c.mu,
            FrictionLaw::StaticDynamic(s) => s.mu_dynamic,
            FrictionLaw::SlipWeakening(s) => s.mu_dynamic,
        }
    }

    /// Slip-weakening distance Dc (m); 0 for laws that drop at once or not at all.
    pub fn weakening_distance_m(&self) -> f64 {
        match self {
            FrictionLaw::SlipWeakening(s) => s.dc_m,
            _ => 0.0,
        }
    }

    /// The coefficients of a node whose random-field factor is `factor`.
    pub fn node(&self, factor: f64) -> NodeFriction {
        NodeFriction { mu_static: self.mu_static() * factor, mu_dynamic: self.mu_dynamic() * factor }
    }

    /// Name as written in tables and messages.
    pub fn name(&self) -> &'static str {
        match self {
            FrictionLaw::Coulomb(_) => "coulomb",
            FrictionLaw::StaticDynamic(_) => "static_dynamic",
            FrictionLaw::SlipWeakening(_) => "slip_weakening",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_coefficients_scale_with_the_field_factor() {
        let law = FrictionLaw::StaticDynamic(StaticDynamic { mu_static: 0.6, mu_dynamic: 0.45 });
        let n = law.node(1.5);
        assert_eq!((n.mu_static, n.mu_dynamic), (0.6 * 1.5, 0.45 * 1.5));
        assert_eq!(FrictionLaw::Coulomb(Coulomb { mu: 5.0 }).mu_dynamic(), 5.0);
    }

    #[test]
    fn kinetic_coefficients_of_each_law() {
        let node = NodeFriction { mu_static: 0.6, mu_dynamic: 0.4 };
        let plain = FrictionLaw::Coulomb(Coulomb { mu: 0.6 });
        assert_eq!(plain.kinetic(&plain.node(1.0), 1.0), 0.6);
        let sd = FrictionLaw::StaticDynamic(StaticDynamic { mu_static: 0.6, mu_dynamic: 0.4 });
        assert_eq!(sd.kinetic(&node, 0.0), 0.4);
        assert_eq!(sd.kinetic(&node, 1.0), 0.4);
        let sw = FrictionLaw::SlipWeakening(SlipWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 1e-3 });
        assert_eq!(sw.kinetic(&node, 0.0), 0.6);
        assert!((sw.kinetic(&node, 0.5e-3) - 0.5).abs() < 1e-15);
        assert_eq!(sw.kinetic(&node, 2e-3), 0.4);
        // Sticking nodes hold at μs whatever the law.
        assert_eq!(sw.holding(&node, false, sw.kinetic(&node, 0.5e-3)), 0.6);
    }
}
