//! The slip-weakening family (docs/model.md §4): the kinetic coefficient as a function of the
//! slip `s` of the current slide, `μ_k(s) = μs − (μs − μd)·min(s/Dc, 1)` (Ida 1972; Andrews
//! 1976), with `μd` from the first step of slip when `Dc = 0`. Its cases:
//!
//! - **plain Coulomb** (the paper's): `μ_k = μs`;
//! - **static/dynamic**: `μ_k = μd` from the first step of slip;
//! - **linear slip weakening**: the formula above.
//!
//! A node that sticks again heals to μs (the paper's stick-slip cycles), unless the law is set not
//! to heal: then the slip accumulates over the run and a node that has slipped holds at its
//! weakened coefficient (the convention of the SCEC dynamic-rupture benchmarks, Harris et al.
//! 2009). The kinetic coefficient is one formula with `Dc` a value
//! per node, not one function per case: the lane kernel then compiles to the same vector loop
//! whatever the case (per-case kernels left the plain law's loop scalar at 4 seeds, 11% slower per
//! step), and a friction map may give each region its own μs, μd and Dc.

use super::{Coefficient, FrictionLaw, Law, NodeFriction, Trial};

/// The slip-weakening family as a [`Law`]: its state variable is the slip of the current slide.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Weakening;

/// The coefficients of one contact node under the slip-weakening family: the law's (or its
/// friction map's region's), times the node's random-field factor on μ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeakeningNode {
    pub(super) mu_static: f64,
    pub(super) mu_dynamic: f64,
    pub(super) dc_m: f64,
    /// 1 when a node that sticks keeps its slip (no healing), 0 when it heals.
    keeps: f64,
}

/// [`WeakeningNode`] of `L` seeds side by side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeakeningLanes<const L: usize> {
    mu_static: [f64; L],
    mu_dynamic: [f64; L],
    dc_m: [f64; L],
    keeps: [f64; L],
}

impl WeakeningNode {
    /// Static coefficient μs, dynamic μd ≤ μs (μs for the plain law) and slip-weakening
    /// distance Dc (m; 0 = μd from the first step of slip).
    pub fn new(mu_static: f64, mu_dynamic: f64, dc_m: f64) -> WeakeningNode {
        WeakeningNode { mu_static, mu_dynamic, dc_m, keeps: 0.0 }
    }

    /// The same coefficients, healing when a node sticks (`true`, the default) or keeping its
    /// slip (`false`).
    pub fn with_healing(self, heals: bool) -> WeakeningNode {
        WeakeningNode { keeps: if heals { 0.0 } else { 1.0 }, ..self }
    }

    /// Whether a node that sticks heals.
    pub fn heals(&self) -> bool {
        self.keeps == 0.0
    }

    /// Slip-weakening distance Dc (m).
    pub fn weakening_distance_m(&self) -> f64 {
        self.dc_m
    }

    /// Kinetic coefficient after sliding `path` metres in the current slide.
    pub fn kinetic(&self, path: f64) -> f64 {
        kinetic(self, path)
    }
}

/// `μs − (μs − μd)·min(path/Dc, 1)`, μd when `Dc = 0`.
#[inline(always)]
fn kinetic(node: &WeakeningNode, path: f64) -> f64 {
    let (ms, md, dc) = (node.mu_static, node.mu_dynamic, node.dc_m);
    if dc == 0.0 { md } else { ms - (ms - md) * (path / dc).min(1.0) }
}

impl Law for Weakening {
    const NAME: &'static str = "slip weakening";
    const COHESIVE_ZONE: &'static str = "(9π/32)·μ·Dc/(τs − τd)";
    const CRITICAL: &'static str = "(μs − μd)·N/Dc";
    const STEADY: &'static str = "μ does not weaken with slip (μd = μs), so a seated block slides steadily (make the \
                                  dynamic friction coefficient lower than the static one)";
    type Node = WeakeningNode;
    type Lanes<const L: usize> = WeakeningLanes<L>;

    fn lanes<const L: usize>(nodes: [WeakeningNode; L]) -> WeakeningLanes<L> {
        WeakeningLanes {
            mu_static: nodes.map(|n| n.mu_static),
            mu_dynamic: nodes.map(|n| n.mu_dynamic),
            dc_m: nodes.map(|n| n.dc_m),
            keeps: nodes.map(|n| n.keeps),
        }
    }

    #[inline(always)]
    fn lane<const L: usize>(lanes: &WeakeningLanes<L>, l: usize) -> WeakeningNode {
        WeakeningNode {
            mu_static: lanes.mu_static[l],
            mu_dynamic: lanes.mu_dynamic[l],
            dc_m: lanes.dc_m[l],
            keeps: lanes.keeps[l],
        }
    }

    #[inline(always)]
    fn static_coefficient(node: &WeakeningNode) -> f64 {
        node.mu_static
    }

    /// μd when `Dc = 0`, else `μs − (μs − μd)·min(path/Dc, 1)`: rate-independent.
    #[inline(always)]
    fn kinetic(node: &WeakeningNode, path: f64, _: &Trial) -> f64 {
        kinetic(node, path)
    }

    #[inline(always)]
    fn holding(node: &WeakeningNode, sliding: bool, kinetic: f64, state: f64) -> f64 {
        if sliding || (node.keeps != 0.0 && state > 0.0) { kinetic } else { node.mu_static }
    }

    /// 0 (healed) or the slip so far, as the node's coefficients say.
    #[inline(always)]
    fn stuck(node: &WeakeningNode, state: f64, _: f64) -> f64 {
        node.keeps * state
    }

    /// The slip path grows by the distance slid.
    #[inline(always)]
    fn advance(_: &WeakeningNode, path: f64, slid_m: f64, _: f64) -> f64 {
        path + slid_m
    }

    /// μs and μd times the factor, Dc unchanged.
    fn scaled(node: &WeakeningNode, factor: f64) -> WeakeningNode {
        WeakeningNode { mu_static: node.mu_static * factor, mu_dynamic: node.mu_dynamic * factor, ..*node }
    }

    fn with_healing(node: &WeakeningNode, heals: bool) -> WeakeningNode {
        node.with_healing(heals)
    }

    fn residual_coefficient(node: &WeakeningNode) -> f64 {
        node.mu_dynamic
    }

    /// `9π/32·μ·Dc/(τs − τd)` (Day et al. 2005, for linear weakening); `None` when μ drops at
    /// once or not at all.
    fn cohesive_zone_m(node: &WeakeningNode, shear_modulus_pa: f64, normal_pa: f64) -> Option<f64> {
        let (ts, td) = (node.mu_static * normal_pa, node.mu_dynamic * normal_pa);
        (node.dc_m > 0.0 && ts > td)
            .then(|| 9.0 * std::f64::consts::PI / 32.0 * shear_modulus_pa * node.dc_m / (ts - td))
    }

    /// The weakening rate `(μs − μd)·N/Dc`.
    fn critical_stiffness(node: &WeakeningNode, normal_n: f64) -> f64 {
        let drop = (node.mu_static - node.mu_dynamic) * normal_n;
        if drop <= 0.0 {
            0.0
        } else if node.dc_m == 0.0 {
            f64::INFINITY
        } else {
            drop / node.dc_m
        }
    }

    fn coefficients(node: &WeakeningNode) -> Vec<Coefficient> {
        vec![
            Coefficient { symbol: "μs", value: node.mu_static, unit: "" },
            Coefficient { symbol: "μd", value: node.mu_dynamic, unit: "" },
            Coefficient { symbol: "Dc", value: node.dc_m, unit: "m" },
        ]
    }
}

/// The slip-weakening family's cases: each a builder of the scene's [`FrictionLaw`].
fn case(name: &'static str, mu_static: f64, mu_dynamic: f64, dc_m: f64) -> FrictionLaw {
    FrictionLaw { name, background: NodeFriction::Weakening(WeakeningNode::new(mu_static, mu_dynamic, dc_m)) }
}

impl From<Coulomb> for FrictionLaw {
    fn from(c: Coulomb) -> FrictionLaw {
        case("coulomb", c.mu, c.mu, 0.0)
    }
}

impl From<StaticDynamic> for FrictionLaw {
    fn from(s: StaticDynamic) -> FrictionLaw {
        case("static_dynamic", s.mu_static, s.mu_dynamic, 0.0)
    }
}

impl From<SlipWeakening> for FrictionLaw {
    fn from(s: SlipWeakening) -> FrictionLaw {
        case("slip_weakening", s.mu_static, s.mu_dynamic, s.dc_m)
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinetic_coefficients_of_each_law() {
        let weakening = |law: FrictionLaw| match law.node(1.0) {
            NodeFriction::Weakening(n) => n,
            other => panic!("{other:?}"),
        };
        let plain = weakening(Coulomb { mu: 0.6 }.into());
        assert_eq!(plain.kinetic(1.0), 0.6);
        let sd = weakening(StaticDynamic { mu_static: 0.6, mu_dynamic: 0.4 }.into());
        assert_eq!(sd.kinetic(0.0), 0.4);
        assert_eq!(sd.kinetic(1.0), 0.4);
        let sw = weakening(SlipWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 1e-3 }.into());
        assert_eq!(sw.kinetic(0.0), 0.6);
        assert!((sw.kinetic(0.5e-3) - 0.5).abs() < 1e-15);
        assert_eq!(sw.kinetic(2e-3), 0.4);
        // Sticking nodes hold at μs whatever the law.
        assert_eq!(Weakening::holding(&sw, false, sw.kinetic(0.5e-3), 0.5e-3), 0.6);
        assert_eq!(Weakening::stuck(&sw, 0.5e-3, 1e-3), 0.0);
        // Without healing a stuck node keeps its slip and holds at its weakened coefficient; one
        // that never slipped holds at μs.
        let kept = sw.with_healing(false);
        assert_eq!(Weakening::stuck(&kept, 0.5e-3, 1e-3), 0.5e-3);
        assert!((Weakening::holding(&kept, false, kept.kinetic(0.5e-3), 0.5e-3) - 0.5).abs() < 1e-15);
        assert_eq!(Weakening::holding(&kept, false, kept.kinetic(0.0), 0.0), 0.6);
        let sd_kept = sd.with_healing(false);
        assert_eq!(Weakening::holding(&sd_kept, false, sd_kept.kinetic(0.0), 0.0), 0.6);
        assert_eq!(Weakening::holding(&sd_kept, false, sd_kept.kinetic(1e-9), 1e-9), 0.4);
        // The spring-slider's critical stiffness (μs − μd)·N/Dc.
        assert!((Weakening::critical_stiffness(&sw, 1000.0) - 0.2 * 1000.0 / 1e-3).abs() < 1e-6);
        assert_eq!(Weakening::critical_stiffness(&sd, 1000.0), f64::INFINITY);
        assert_eq!(Weakening::critical_stiffness(&plain, 1000.0), 0.0);
    }
}
