//! Friction laws of the base (docs/model.md §4): one file per law, one enum to choose it.
//!
//! A contact node in contact sticks while the tangential reaction needed to hold it still,
//! `|R_t|`, is at most `μ_hold·N`, where `μ_hold` is the node's static coefficient μs if it was
//! sticking and its kinetic coefficient if it was sliding; otherwise it slides with a friction
//! force `μ_k·N` opposing its trial motion. What differs between laws is only the kinetic
//! coefficient `μ_k` as a function of the slip accumulated in the current slide ([`Law::kinetic`]).
//! The decision itself — stick, slide or lift — is written once, for one node in plain scalar
//! code ([`crate::step::contact::resolve`]) and for `L` seeds side by side in the step's lane
//! kernel, which is tested bit for bit against it; the static self-weight solve and the
//! quasi-static skip-ahead use the same static strength [`NodeFriction::mu_static`]`·N`.
//!
//! Adding a law: a file here with a zero-sized marker type implementing [`Law`] and a parameter
//! struct, a variant of [`FrictionLaw`], and its section in the configuration crate.

mod coulomb;
mod slip_weakening;
mod static_dynamic;

pub use coulomb::Coulomb;
pub use slip_weakening::SlipWeakening;
pub use static_dynamic::StaticDynamic;

/// The coefficients of one contact node (the law's, times the node's random-field factor).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeFriction {
    /// Static coefficient μs: a sticking node holds while `|R_t| ≤ μs·N`.
    pub mu_static: f64,
    /// Dynamic coefficient μd (equal to μs for the plain law).
    pub mu_dynamic: f64,
}

/// A friction law, as the step kernel calls it: monomorphised, so the per-node loop has no branch
/// on the law.
pub trait Law: Copy + Send + Sync + 'static {
    /// Kinetic coefficient of a node that has slid `path` metres in its current slide.
    fn kinetic(&self, node: &NodeFriction, path: f64) -> f64;

    /// The coefficient bounding `|R_t|` of a node in contact: μs if it was sticking, its kinetic
    /// coefficient if it was sliding (`kinetic` is `self.kinetic(node, path)`, passed in so the
    /// lane kernel computes it once).
    #[inline(always)]
    fn holding(&self, node: &NodeFriction, sliding: bool, kinetic: f64) -> f64 {
        if sliding { kinetic } else { node.mu_static }
    }
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
        assert_eq!(Coulomb { mu: 0.6 }.kinetic(&NodeFriction { mu_static: 0.6, mu_dynamic: 0.6 }, 1.0), 0.6);
        assert_eq!(StaticDynamic { mu_static: 0.6, mu_dynamic: 0.4 }.kinetic(&node, 0.0), 0.4);
        let sw = SlipWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 1e-3 };
        assert_eq!(sw.kinetic(&node, 0.0), 0.6);
        assert!((sw.kinetic(&node, 0.5e-3) - 0.5).abs() < 1e-15);
        assert_eq!(sw.kinetic(&node, 2e-3), 0.4);
        // Sticking nodes hold at μs whatever the law.
        assert_eq!(sw.holding(&node, false, sw.kinetic(&node, 0.5e-3)), 0.6);
    }
}
