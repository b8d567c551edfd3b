//! Exponential slip weakening (docs/model.md §4): the kinetic coefficient after a slip `s` of
//! the current slide is `μ_k(s) = μd + (μs − μd)·exp(−s/Dc)`, a smooth form of slip weakening
//! with the same initial weakening rate `(μs − μd)/Dc` as the linear law but no kink at `Dc`: the
//! strength approaches μd over a few Dc (95% of the drop after 3 Dc) and the fracture energy per
//! unit area is `(τs − τd)·Dc`, twice the linear law's `(τs − τd)·Dc/2`.
//!
//! Its coefficients are the slip-weakening family's (μs, μd, Dc and whether a node heals) and
//! it keeps the same state variable, the slip of the current slide; `Dc = 0` gives μd from the
//! first step of slip.

use super::{Coefficient, FrictionLaw, Law, NodeFriction, Trial, Weakening, WeakeningLanes, WeakeningNode};

/// Exponential slip weakening as a [`Law`]: the slip-weakening family's coefficients and state,
/// its own kinetic coefficient and cohesive zone; everything else is the family's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Exponential;

/// The coefficients of one contact node under exponential slip weakening: the slip-weakening
/// family's (μs, μd, Dc and whether it heals).
pub type ExponentialNode = WeakeningNode;

/// `μd + (μs − μd)·exp(−path/Dc)`, μd when `Dc = 0`.
#[inline(always)]
fn kinetic(node: &WeakeningNode, path: f64) -> f64 {
    let (ms, md, dc) = (node.mu_static, node.mu_dynamic, node.dc_m);
    if dc == 0.0 { md } else { md + (ms - md) * (-path / dc).exp() }
}

impl Law for Exponential {
    const NAME: &'static str = "exponential slip weakening";
    const COHESIVE_ZONE: &'static str = "(9π/16)·μ·Dc/(τs − τd)";
    const CRITICAL: &'static str = "(μs − μd)·N/Dc";
    const STEADY: &'static str = "μ does not weaken with slip (μd = μs), so a seated block slides steadily (make the \
                                  dynamic friction coefficient lower than the static one)";
    type Node = WeakeningNode;
    type Lanes<const L: usize> = WeakeningLanes<L>;

    fn lanes<const L: usize>(nodes: [WeakeningNode; L]) -> WeakeningLanes<L> {
        Weakening::lanes(nodes)
    }

    #[inline(always)]
    fn lane<const L: usize>(lanes: &WeakeningLanes<L>, l: usize) -> WeakeningNode {
        Weakening::lane(lanes, l)
    }

    #[inline(always)]
    fn static_coefficient(node: &WeakeningNode) -> f64 {
        node.mu_static
    }

    #[inline(always)]
    fn kinetic(node: &WeakeningNode, path: f64, _: &Trial) -> f64 {
        kinetic(node, path)
    }

    #[inline(always)]
    fn holding(node: &WeakeningNode, sliding: bool, kinetic: f64, state: f64) -> f64 {
        Weakening::holding(node, sliding, kinetic, state)
    }

    #[inline(always)]
    fn stuck(node: &WeakeningNode, state: f64, dt_s: f64) -> f64 {
        Weakening::stuck(node, state, dt_s)
    }

    #[inline(always)]
    fn advance(node: &WeakeningNode, path: f64, slid_m: f64, dt_s: f64) -> f64 {
        Weakening::advance(node, path, slid_m, dt_s)
    }

    fn scaled(node: &WeakeningNode, factor: f64) -> WeakeningNode {
        Weakening::scaled(node, factor)
    }

    fn with_healing(node: &WeakeningNode, heals: bool) -> WeakeningNode {
        node.with_healing(heals)
    }

    fn residual_coefficient(node: &WeakeningNode) -> f64 {
        node.mu_dynamic
    }

    /// The initial weakening rate `(μs − μd)·N/Dc`, the linear law's.
    fn critical_stiffness(node: &WeakeningNode, normal_n: f64) -> f64 {
        Weakening::critical_stiffness(node, normal_n)
    }

    /// Day et al. (2005)'s `9π/16·μ·G/(τs − τd)²` with this law's fracture energy
    /// `G = (τs − τd)·Dc`: `9π/16·μ·Dc/(τs − τd)`, twice the linear law's zone for the same Dc.
    fn cohesive_zone_m(node: &WeakeningNode, shear_modulus_pa: f64, normal_pa: f64) -> Option<f64> {
        let (ts, td) = (node.mu_static * normal_pa, node.mu_dynamic * normal_pa);
        (node.dc_m > 0.0 && ts > td)
            .then(|| 9.0 * std::f64::consts::PI / 16.0 * shear_modulus_pa * node.dc_m / (ts - td))
    }

    fn coefficients(node: &WeakeningNode) -> Vec<Coefficient> {
        Weakening::coefficients(node)
    }
}

/// Exponential slip weakening from μs towards μd over a distance `dc_m`: the builder of a
/// scene's [`FrictionLaw`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExponentialWeakening {
    /// μs.
    pub mu_static: f64,
    /// μd < μs.
    pub mu_dynamic: f64,
    /// Dc (m), > 0.
    pub dc_m: f64,
}

impl From<ExponentialWeakening> for FrictionLaw {
    fn from(e: ExponentialWeakening) -> FrictionLaw {
        FrictionLaw {
            name: "exponential_weakening",
            background: NodeFriction::Exponential(ExponentialNode::new(e.mu_static, e.mu_dynamic, e.dc_m)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strength_falls_exponentially_and_its_fracture_energy_is_the_closed_form() {
        let n = ExponentialNode::new(0.6, 0.4, 0.2);
        assert_eq!(kinetic(&n, 0.0), 0.6);
        // One Dc: the drop has fallen to 1/e of itself.
        assert!((kinetic(&n, 0.2) - (0.4 + 0.2 / std::f64::consts::E)).abs() < 1e-15);
        assert!((kinetic(&n, 0.6) - 0.4) / 0.2 < 0.05 + 1e-12, "95% of the drop after 3 Dc");
        // The fracture energy per unit normal stress, ∫(μ(s) − μd) ds over a long slip, by the
        // trapezoidal rule against the closed form (μs − μd)·Dc.
        let (ds, steps) = (1e-5, 400_000);
        let mut g = 0.0;
        for i in 0..steps {
            let (a, b) = (kinetic(&n, i as f64 * ds) - 0.4, kinetic(&n, (i + 1) as f64 * ds) - 0.4);
            g += 0.5 * (a + b) * ds;
        }
        assert!((g / (0.2 * 0.2) - 1.0).abs() < 1e-6, "G = {g}");
        // μd at once without Dc; healing as the slip-weakening family.
        assert_eq!(kinetic(&ExponentialNode::new(0.6, 0.4, 0.0), 0.0), 0.4);
        let kept = Exponential::with_healing(&n, false);
        assert_eq!(Exponential::stuck(&kept, 0.1, 1e-3), 0.1);
        assert_eq!(Exponential::stuck(&n, 0.1, 1e-3), 0.0);
        assert_eq!(Exponential::holding(&kept, false, kinetic(&kept, 0.1), 0.1), kinetic(&kept, 0.1));
        assert_eq!(Exponential::holding(&n, false, kinetic(&n, 0.1), 0.1), 0.6);
    }
}
