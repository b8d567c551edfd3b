//! Exponential slip weakening (docs/model.md §4): the kinetic coefficient after a slip `s` of
//! the current slide is `μ_k(s) = μd + (μs − μd)·exp(−s/Dc)`, a smooth form of slip weakening
//! with the same initial weakening rate `(μs − μd)/Dc` as the linear law but no kink at `Dc`: the
//! strength approaches μd over a few Dc (95% of the drop after 3 Dc) and the fracture energy per
//! unit area is `(τs − τd)·Dc`, twice the linear law's `(τs − τd)·Dc/2`.
//!
//! Its coefficients are the slip-weakening family's (μs, μd, Dc and whether a node heals) and
//! it keeps the same state variable, the slip of the current slide; `Dc = 0` gives μd from the
//! first step of slip.

use super::{Coefficient, FrictionLaw, Law, NodeFriction, Trial};

/// Exponential slip weakening as a [`Law`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Exponential;

/// The coefficients of one contact node under exponential slip weakening.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExponentialNode {
    mu_static: f64,
    mu_dynamic: f64,
    dc_m: f64,
    /// 1 when a node that sticks keeps its slip (no healing), 0 when it heals.
    keeps: f64,
}

/// [`ExponentialNode`] of `L` seeds side by side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExponentialLanes<const L: usize> {
    mu_static: [f64; L],
    mu_dynamic: [f64; L],
    dc_m: [f64; L],
    keeps: [f64; L],
}

impl ExponentialNode {
    /// Static coefficient μs, dynamic μd ≤ μs and the weakening distance Dc (m; 0 = μd from the
    /// first step of slip); a node that sticks heals.
    pub fn new(mu_static: f64, mu_dynamic: f64, dc_m: f64) -> ExponentialNode {
        ExponentialNode { mu_static, mu_dynamic, dc_m, keeps: 0.0 }
    }

    /// Kinetic coefficient after sliding `path` metres in the current slide.
    pub fn kinetic(&self, path: f64) -> f64 {
        kinetic(self, path)
    }
}

/// `μd + (μs − μd)·exp(−path/Dc)`, μd when `Dc = 0`.
#[inline(always)]
fn kinetic(node: &ExponentialNode, path: f64) -> f64 {
    let (ms, md, dc) = (node.mu_static, node.mu_dynamic, node.dc_m);
    if dc == 0.0 { md } else { md + (ms - md) * (-path / dc).exp() }
}

impl Law for Exponential {
    const NAME: &'static str = "exponential slip weakening";
    const COHESIVE_ZONE: &'static str = "(9π/16)·μ·Dc/(τs − τd)";
    type Node = ExponentialNode;
    type Lanes<const L: usize> = ExponentialLanes<L>;

    fn lanes<const L: usize>(nodes: [ExponentialNode; L]) -> ExponentialLanes<L> {
        ExponentialLanes {
            mu_static: nodes.map(|n| n.mu_static),
            mu_dynamic: nodes.map(|n| n.mu_dynamic),
            dc_m: nodes.map(|n| n.dc_m),
            keeps: nodes.map(|n| n.keeps),
        }
    }

    #[inline(always)]
    fn lane<const L: usize>(lanes: &ExponentialLanes<L>, l: usize) -> ExponentialNode {
        ExponentialNode {
            mu_static: lanes.mu_static[l],
            mu_dynamic: lanes.mu_dynamic[l],
            dc_m: lanes.dc_m[l],
            keeps: lanes.keeps[l],
        }
    }

    #[inline(always)]
    fn static_coefficient(node: &ExponentialNode) -> f64 {
        node.mu_static
    }

    #[inline(always)]
    fn kinetic(node: &ExponentialNode, path: f64, _: &Trial) -> f64 {
        kinetic(node, path)
    }

    #[inline(always)]
    fn holding(node: &ExponentialNode, sliding: bool, kinetic: f64, state: f64) -> f64 {
        if sliding || (node.keeps != 0.0 && state > 0.0) { kinetic } else { node.mu_static }
    }

    #[inline(always)]
    fn stuck(node: &ExponentialNode, state: f64) -> f64 {
        node.keeps * state
    }

    #[inline(always)]
    fn advance(_: &ExponentialNode, path: f64, slid_m: f64, _: f64) -> f64 {
        path + slid_m
    }

    fn scaled(node: &ExponentialNode, factor: f64) -> ExponentialNode {
        ExponentialNode { mu_static: node.mu_static * factor, mu_dynamic: node.mu_dynamic * factor, ..*node }
    }

    fn with_healing(node: &ExponentialNode, heals: bool) -> ExponentialNode {
        ExponentialNode { keeps: if heals { 0.0 } else { 1.0 }, ..*node }
    }

    fn residual_coefficient(node: &ExponentialNode) -> f64 {
        node.mu_dynamic
    }

    /// The initial weakening rate `(μs − μd)·N/Dc`, the linear law's.
    fn critical_stiffness(node: &ExponentialNode, normal_n: f64) -> f64 {
        let drop = (node.mu_static - node.mu_dynamic) * normal_n;
        if drop <= 0.0 {
            0.0
        } else if node.dc_m == 0.0 {
            f64::INFINITY
        } else {
            drop / node.dc_m
        }
    }

    /// Day et al. (2005)'s `9π/16·μ·G/(τs − τd)²` with this law's fracture energy
    /// `G = (τs − τd)·Dc`: `9π/16·μ·Dc/(τs − τd)`, twice the linear law's zone for the same Dc.
    fn cohesive_zone_m(node: &ExponentialNode, shear_modulus_pa: f64, normal_pa: f64) -> Option<f64> {
        let (ts, td) = (node.mu_static * normal_pa, node.mu_dynamic * normal_pa);
        (node.dc_m > 0.0 && ts > td)
            .then(|| 9.0 * std::f64::consts::PI / 16.0 * shear_modulus_pa * node.dc_m / (ts - td))
    }

    fn coefficients(node: &ExponentialNode) -> Vec<Coefficient> {
        vec![
            Coefficient { symbol: "μs", value: node.mu_static, unit: "" },
            Coefficient { symbol: "μd", value: node.mu_dynamic, unit: "" },
            Coefficient { symbol: "Dc", value: node.dc_m, unit: "m" },
        ]
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
        assert_eq!(n.kinetic(0.0), 0.6);
        // One Dc: the drop has fallen to 1/e of itself.
        assert!((n.kinetic(0.2) - (0.4 + 0.2 / std::f64::consts::E)).abs() < 1e-15);
        assert!((n.kinetic(0.6) - 0.4) / 0.2 < 0.05 + 1e-12, "95% of the drop after 3 Dc");
        // The fracture energy per unit normal stress, ∫(μ(s) − μd) ds over a long slip, by the
        // trapezoidal rule against the closed form (μs − μd)·Dc.
        let (ds, steps) = (1e-5, 400_000);
        let mut g = 0.0;
        for i in 0..steps {
            let (a, b) = (n.kinetic(i as f64 * ds) - 0.4, n.kinetic((i + 1) as f64 * ds) - 0.4);
            g += 0.5 * (a + b) * ds;
        }
        assert!((g / (0.2 * 0.2) - 1.0).abs() < 1e-6, "G = {g}");
        // μd at once without Dc; healing as the slip-weakening family.
        assert_eq!(ExponentialNode::new(0.6, 0.4, 0.0).kinetic(0.0), 0.4);
        let kept = Exponential::with_healing(&n, false);
        assert_eq!(Exponential::stuck(&kept, 0.1), 0.1);
        assert_eq!(Exponential::stuck(&n, 0.1), 0.0);
        assert_eq!(Exponential::holding(&kept, false, kept.kinetic(0.1), 0.1), kept.kinetic(0.1));
        assert_eq!(Exponential::holding(&n, false, n.kinetic(0.1), 0.1), 0.6);
    }
}
