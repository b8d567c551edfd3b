//! The slip-weakening family (docs/model.md §4): the kinetic coefficient as a function of the
//! slip `s` of the current slide, `μ_k(s) = μs − (μs − μd)·min(s/Dc, 1)` (Ida 1972; Andrews
//! 1976), with `μd` from the first step of slip when `Dc = 0`. Its cases:
//!
//! - **plain Coulomb** (the paper's): `μ_k = μs`;
//! - **static/dynamic**: `μ_k = μd` from the first step of slip;
//! - **linear slip weakening**: the formula above.
//!
//! A node that sticks again heals to μs. The kinetic coefficient is one formula with `Dc` a value
//! per node, not one function per case: the lane kernel then compiles to the same vector loop
//! whatever the case (per-case kernels left the plain law's loop scalar at 4 seeds, 11% slower per
//! step), and a friction map may give each region its own μs, μd and Dc.

use super::{Coefficient, Law, Trial};

/// The slip-weakening family as a [`Law`]: its state variable is the slip of the current slide.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Weakening;

/// The coefficients of one contact node: the law's (or its friction map's region's), times the
/// node's random-field factor on μ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeFriction {
    mu_static: f64,
    mu_dynamic: f64,
    dc_m: f64,
}

/// [`NodeFriction`] of `L` seeds side by side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WeakeningLanes<const L: usize> {
    mu_static: [f64; L],
    mu_dynamic: [f64; L],
    dc_m: [f64; L],
}

impl NodeFriction {
    /// Static coefficient μs, dynamic μd ≤ μs (μs for the plain law) and slip-weakening
    /// distance Dc (m; 0 = μd from the first step of slip).
    pub fn new(mu_static: f64, mu_dynamic: f64, dc_m: f64) -> NodeFriction {
        NodeFriction { mu_static, mu_dynamic, dc_m }
    }

    /// These coefficients times a field factor (Dc unchanged).
    pub fn scaled(&self, factor: f64) -> NodeFriction {
        NodeFriction { mu_static: self.mu_static * factor, mu_dynamic: self.mu_dynamic * factor, dc_m: self.dc_m }
    }

    /// Static coefficient μs.
    pub fn static_coefficient(&self) -> f64 {
        Weakening::static_coefficient(self)
    }

    /// Coefficient once fully weakened, μd.
    pub fn residual_coefficient(&self) -> f64 {
        Weakening::residual_coefficient(self)
    }

    /// Kinetic coefficient after sliding `path` metres in the current slide.
    pub fn kinetic(&self, path: f64) -> f64 {
        kinetic(self, path)
    }

    /// Slip-weakening distance Dc (m).
    pub fn weakening_distance_m(&self) -> f64 {
        self.dc_m
    }

    /// See [`Law::critical_stiffness`].
    pub fn critical_stiffness(&self, normal_n: f64) -> f64 {
        Weakening::critical_stiffness(self, normal_n)
    }

    /// See [`Law::coefficients`].
    pub fn coefficients(&self) -> Vec<Coefficient> {
        Weakening::coefficients(self)
    }
}

/// `μs − (μs − μd)·min(path/Dc, 1)`, μd when `Dc = 0`.
#[inline(always)]
fn kinetic(node: &NodeFriction, path: f64) -> f64 {
    let (ms, md, dc) = (node.mu_static, node.mu_dynamic, node.dc_m);
    if dc == 0.0 { md } else { ms - (ms - md) * (path / dc).min(1.0) }
}

impl Law for Weakening {
    type Node = NodeFriction;
    type Lanes<const L: usize> = WeakeningLanes<L>;

    fn lanes<const L: usize>(nodes: [NodeFriction; L]) -> WeakeningLanes<L> {
        WeakeningLanes {
            mu_static: nodes.map(|n| n.mu_static),
            mu_dynamic: nodes.map(|n| n.mu_dynamic),
            dc_m: nodes.map(|n| n.dc_m),
        }
    }

    #[inline(always)]
    fn lane<const L: usize>(lanes: &WeakeningLanes<L>, l: usize) -> NodeFriction {
        NodeFriction { mu_static: lanes.mu_static[l], mu_dynamic: lanes.mu_dynamic[l], dc_m: lanes.dc_m[l] }
    }

    #[inline(always)]
    fn static_coefficient(node: &NodeFriction) -> f64 {
        node.mu_static
    }

    /// μd when `Dc = 0`, else `μs − (μs − μd)·min(path/Dc, 1)`: rate-independent.
    #[inline(always)]
    fn kinetic(node: &NodeFriction, path: f64, _: &Trial) -> f64 {
        kinetic(node, path)
    }

    #[inline(always)]
    fn holding(node: &NodeFriction, sliding: bool, kinetic: f64) -> f64 {
        if sliding { kinetic } else { node.mu_static }
    }

    /// The slip path grows by the distance slid.
    #[inline(always)]
    fn advance(_: &NodeFriction, path: f64, slid_m: f64, _: f64) -> f64 {
        path + slid_m
    }

    fn residual_coefficient(node: &NodeFriction) -> f64 {
        node.mu_dynamic
    }

    /// The weakening rate `(μs − μd)·N/Dc`.
    fn critical_stiffness(node: &NodeFriction, normal_n: f64) -> f64 {
        let drop = (node.mu_static - node.mu_dynamic) * normal_n;
        if drop <= 0.0 {
            0.0
        } else if node.dc_m == 0.0 {
            f64::INFINITY
        } else {
            drop / node.dc_m
        }
    }

    fn coefficients(node: &NodeFriction) -> Vec<Coefficient> {
        vec![
            Coefficient { symbol: "μs", value: node.mu_static, unit: "" },
            Coefficient { symbol: "μd", value: node.mu_dynamic, unit: "" },
            Coefficient { symbol: "Dc", value: node.dc_m, unit: "m" },
        ]
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
