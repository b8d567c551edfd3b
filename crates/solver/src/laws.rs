//! Friction laws of the base (docs/model.md §4).
//!
//! A contact node in contact sticks while the tangential reaction needed to hold it still,
//! `|R_t|`, is at most `μ_hold·N`, where `μ_hold` is the node's static coefficient μs if it was
//! sticking and its kinetic coefficient if it was sliding; otherwise it slides with a friction
//! force `μ_k·N` opposing its trial motion. The laws differ only in the kinetic coefficient as a
//! function of the slip `s` of the current slide, and all three are one family
//! ([`NodeFriction::kinetic`]):
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
//! The kinetic coefficient is one formula with `Dc` a value per node ([`NodeFriction::kinetic`]),
//! not one function per law: the lane kernel then compiles to the same vector loop whatever the
//! law (per-law kernels left the plain law's loop scalar at 4 seeds, 11% slower per step;
//! `cargo bench -p stickslip-lab --bench step`), and a friction map ([`FrictionMap`]) may give
//! each region of the base its own μs, μd and Dc. A law outside this family adds a variant here,
//! its parameters to [`NodeFriction`] and its section in the configuration crate, and is checked
//! with the step benchmark.

/// The coefficients of one contact node: the law's (or its friction map's region's), times the
/// node's random-field factor on μ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeFriction {
    /// Static coefficient μs: a sticking node holds while `|R_t| ≤ μs·N`.
    pub mu_static: f64,
    /// Dynamic coefficient μd (equal to μs for the plain law).
    pub mu_dynamic: f64,
    /// Slip-weakening distance Dc (m); 0 = μd from the first step of slip.
    pub dc_m: f64,
}

impl NodeFriction {
    /// Kinetic coefficient of the node after sliding `path` metres in its current slide: μd
    /// when `Dc = 0`, else `μs − (μs − μd)·min(path/Dc, 1)` (docs/model.md §4). The one formula
    /// of every law: Coulomb is `μd = μs`, static/dynamic `Dc = 0`.
    #[inline(always)]
    pub fn kinetic(&self, path: f64) -> f64 {
        let (ms, md, dc) = (self.mu_static, self.mu_dynamic, self.dc_m);
        if dc == 0.0 { md } else { ms - (ms - md) * (path / dc).min(1.0) }
    }

    /// The coefficient bounding `|R_t|` of the node in contact: μs if it was sticking, its
    /// kinetic coefficient if it was sliding (`kinetic` is `self.kinetic(path)`, passed in so the
    /// lane kernel computes it once).
    #[inline(always)]
    pub fn holding(&self, sliding: bool, kinetic: f64) -> f64 {
        if sliding { kinetic } else { self.mu_static }
    }

    /// These coefficients times a field factor (Dc unchanged).
    pub fn scaled(&self, factor: f64) -> NodeFriction {
        NodeFriction { mu_static: self.mu_static * factor, mu_dynamic: self.mu_dynamic * factor, dc_m: self.dc_m }
    }

    /// Critical stiffness of a slider of normal force `normal` (N) with these coefficients: the
    /// weakening rate `(μs − μd)·N/Dc`; infinite when μ drops at once, zero when it does not drop.
    pub fn critical_stiffness(&self, normal: f64) -> f64 {
        let drop = (self.mu_static - self.mu_dynamic) * normal;
        if drop <= 0.0 {
            0.0
        } else if self.dc_m == 0.0 {
            f64::INFINITY
        } else {
            drop / self.dc_m
        }
    }
}

/// A friction map of the base: base coefficients per contact node (canonical contact order,
/// [`crate::geometry::Lattice::contact_nodes`]) and the region each node belongs to; the field
/// factor of each seed multiplies them.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionMap {
    /// Coefficients of each contact node before the field factor.
    pub nodes: Vec<NodeFriction>,
    /// Region of each contact node: `None` = the background (the `[friction]` law), `Some(i)` =
    /// `regions[i]`.
    pub region: Vec<Option<u16>>,
    /// The regions, in precedence order as written.
    pub regions: Vec<Region>,
}

/// One region of a friction map.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// Its name (`patch[i]` or the name given).
    pub name: String,
    /// What it is as seen from the background (from its μs).
    pub kind: RegionKind,
}

/// A region's strength against the background.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RegionKind {
    /// μs above the background's: a barrier.
    Barrier,
    /// μs at most the background's: an asperity where rupture may nucleate.
    Weak,
}

impl RegionKind {
    /// Name as written in tables and messages.
    pub fn name(self) -> &'static str {
        match self {
            RegionKind::Barrier => "barrier",
            RegionKind::Weak => "weak",
        }
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
        NodeFriction {
            mu_static: self.mu_static() * factor,
            mu_dynamic: self.mu_dynamic() * factor,
            dc_m: self.weakening_distance_m(),
        }
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
        let plain = FrictionLaw::Coulomb(Coulomb { mu: 0.6 }).node(1.0);
        assert_eq!(plain.kinetic(1.0), 0.6);
        let sd = FrictionLaw::StaticDynamic(StaticDynamic { mu_static: 0.6, mu_dynamic: 0.4 }).node(1.0);
        assert_eq!(sd.kinetic(0.0), 0.4);
        assert_eq!(sd.kinetic(1.0), 0.4);
        let sw = FrictionLaw::SlipWeakening(SlipWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 1e-3 }).node(1.0);
        assert_eq!(sw.kinetic(0.0), 0.6);
        assert!((sw.kinetic(0.5e-3) - 0.5).abs() < 1e-15);
        assert_eq!(sw.kinetic(2e-3), 0.4);
        // Sticking nodes hold at μs whatever the law.
        assert_eq!(sw.holding(false, sw.kinetic(0.5e-3)), 0.6);
        // The spring-slider's critical stiffness (μs − μd)·N/Dc.
        assert!((sw.critical_stiffness(1000.0) - 0.2 * 1000.0 / 1e-3).abs() < 1e-6);
        assert_eq!(sd.critical_stiffness(1000.0), f64::INFINITY);
        assert_eq!(plain.critical_stiffness(1000.0), 0.0);
    }
}
