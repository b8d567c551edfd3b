//! Friction laws of the base (docs/model.md §4).
//!
//! A contact node in contact sticks while the tangential reaction needed to hold it still,
//! `|R_t|`, is at most its law's holding coefficient times `N`; otherwise it slides with a
//! friction force `μ_k·N` opposing its trial motion. That decision — stick, slide or lift — is
//! written once, in [`crate::step::contact`], for any [`Law`]: it asks the law for the
//! coefficient that bounds a node in contact ([`Law::holding`]), the kinetic coefficient of a
//! sliding node ([`Law::kinetic`]) and the node's state after it slid ([`Law::advance`]); the
//! static self-weight solve and the skip-ahead ask for its static strength
//! ([`Law::static_coefficient`]); `check` and the figures ask for its critical stiffness and its
//! named coefficients. Nothing else names a law's fields.
//!
//! A law keeps **one state variable per contact node** (the slip of the current slide for slip
//! weakening; θ for a rate-and-state law); what a node that sticks keeps of it is the law's
//! ([`Law::stuck`]: the paper's slip weakening heals, resetting it to 0; without healing, the
//! benchmark convention of dynamic-rupture codes, the slip accumulates over the run). Its coefficients at a
//! node are its [`Law::Node`]; for `L` seeds side by side, its [`Law::Lanes`] holds one array per
//! coefficient, so the lane kernel loads each coefficient of all lanes at once and compiles to
//! one vector loop (`cargo bench -p stickslip-lab --bench step`).
//!
//! The laws: the slip-weakening family [`Weakening`] ([`slip_weakening`]), of which the plain
//! Coulomb law, static/dynamic friction and linear slip weakening are the cases
//! ([`FrictionLaw`], the scene's choice); a friction map ([`map`]) gives regions of the base their
//! own coefficients. A new law is a file beside [`slip_weakening`] implementing [`Law`], its
//! variant in [`FrictionLaws`] and its arm in [`FrictionLaws::dispatch`] (ARCHITECTURE.md lists the
//! files).

pub mod map;
pub mod slip_weakening;

use std::fmt::Debug;

pub use map::{FrictionMap, Region, RegionKind};
pub use slip_weakening::{Coulomb, SlipWeakening, StaticDynamic, Weakening, WeakeningLanes, WeakeningNode};

/// A friction law of the base: its coefficients at one contact node, its one state variable
/// there, and the answers the contact rule, the static solves and `check` ask of it.
pub trait Law: Copy + Debug + Default + Send + Sync + 'static {
    /// Its coefficients at one contact node of one seed.
    type Node: Copy + Debug + PartialEq + Send + Sync;
    /// Its coefficients at one contact node for `L` seeds: one array per coefficient.
    type Lanes<const L: usize>: Copy + Debug + PartialEq + Send + Sync;

    /// The coefficients of `L` seeds side by side.
    fn lanes<const L: usize>(nodes: [Self::Node; L]) -> Self::Lanes<L>;
    /// Lane `l`'s coefficients.
    fn lane<const L: usize>(lanes: &Self::Lanes<L>, l: usize) -> Self::Node;
    /// The static coefficient: a node at rest holds while `|R_t| ≤ μ·N`.
    fn static_coefficient(node: &Self::Node) -> f64;
    /// The kinetic coefficient of a node sliding this step whose state variable is `state`;
    /// `trial` says what the node would do without friction (what a rate-dependent law solves
    /// its slip rate from).
    fn kinetic(node: &Self::Node, state: f64, trial: &Trial) -> f64;
    /// The coefficient bounding `|R_t|` of a node in contact whose state variable is `state`:
    /// `kinetic` (its kinetic coefficient at that state, computed once by the caller) if it was
    /// sliding; if it was sticking, the static one, or, for a law that does not heal and a node
    /// that has slipped, `kinetic`.
    fn holding(node: &Self::Node, sliding: bool, kinetic: f64, state: f64) -> f64;
    /// The state variable of a node that sticks this step, from `state`: 0 for a law that heals,
    /// `state` for one that keeps its slip.
    fn stuck(node: &Self::Node, state: f64) -> f64;
    /// The state variable of a sliding node after it moved `slid_m` metres in a step of `dt_s`
    /// seconds.
    fn advance(node: &Self::Node, state: f64, slid_m: f64, dt_s: f64) -> f64;
    /// The coefficients times a random-field factor (the Weibull field on μ).
    fn scaled(node: &Self::Node, factor: f64) -> Self::Node;
    /// The coefficient once fully weakened (steady sliding).
    fn residual_coefficient(node: &Self::Node) -> f64;
    /// Critical stiffness of a spring-slider of normal force `normal_n` on this node: loading
    /// stiffer than this slides stably (N/m; infinite when μ drops at once, 0 when it never drops).
    fn critical_stiffness(node: &Self::Node, normal_n: f64) -> f64;
    /// Its coefficients with their symbols and units, as `check` and the report print them.
    fn coefficients(node: &Self::Node) -> Vec<Coefficient>;
}

/// A contact node's step without friction: what a rate-dependent law needs to find its slip rate
/// (with `g` the update's stiffness, the node slides at `(need − μ·N)/(g·Δt)`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trial {
    /// The tangential reaction that would hold the node still (N).
    pub need_n: f64,
    /// The normal reaction (N).
    pub normal_n: f64,
    /// The update's stiffness `m(1 + DΔt/2)/Δt²` (N/m).
    pub g_n_m: f64,
    /// The time step (s).
    pub dt_s: f64,
}

/// One named coefficient of a law.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficient {
    /// Symbol as printed (`μs`, `Dc`).
    pub symbol: &'static str,
    /// Value.
    pub value: f64,
    /// Unit (empty for a plain number).
    pub unit: &'static str,
}

/// `coefficients` as `μs = 0.6, μd = 0.45, Dc = 0 m`; `value` prints each value (e.g. a range).
pub fn describe(coefficients: &[Coefficient], value: impl Fn(usize, &Coefficient) -> String) -> String {
    coefficients
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let v = value(i, c);
            if c.unit.is_empty() { format!("{} = {v}", c.symbol) } else { format!("{} = {v} {}", c.symbol, c.unit) }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A contact node's coefficients under the scene's law, whatever the law: what the scene, its
/// friction map, `check` and the figures hold and ask.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NodeFriction {
    /// The slip-weakening family.
    Weakening(WeakeningNode),
}

/// Runs `$body` with `$n` bound to the law's node and `$W` to the law's type.
macro_rules! with_node {
    ($node:expr, |$n:ident: $W:ident| $body:expr) => {
        match $node {
            NodeFriction::Weakening($n) => {
                type $W = Weakening;
                $body
            }
        }
    };
}

impl NodeFriction {
    /// The static coefficient ([`Law::static_coefficient`]).
    pub fn static_coefficient(&self) -> f64 {
        with_node!(self, |n: W| W::static_coefficient(n))
    }

    /// The coefficient once fully weakened ([`Law::residual_coefficient`]).
    pub fn residual_coefficient(&self) -> f64 {
        with_node!(self, |n: W| W::residual_coefficient(n))
    }

    /// The spring-slider's critical stiffness at normal force `normal_n` ([`Law::critical_stiffness`]).
    pub fn critical_stiffness(&self, normal_n: f64) -> f64 {
        with_node!(self, |n: W| W::critical_stiffness(n, normal_n))
    }

    /// The named coefficients ([`Law::coefficients`]).
    pub fn coefficients(&self) -> Vec<Coefficient> {
        with_node!(self, |n: W| W::coefficients(n))
    }

    /// The coefficients times a random-field factor ([`Law::scaled`]).
    pub fn scaled(&self, factor: f64) -> NodeFriction {
        match self {
            NodeFriction::Weakening(n) => NodeFriction::Weakening(Weakening::scaled(n, factor)),
        }
    }

    /// The same coefficients, healing when a node sticks or not.
    pub fn healing(&self, heals: bool) -> NodeFriction {
        match self {
            NodeFriction::Weakening(n) => NodeFriction::Weakening(n.with_healing(heals)),
        }
    }
}

/// The per-node, per-lane coefficients of the scene's law for `L` seeds, chosen once before the
/// run: the contact kernel is monomorphised for the law in [`FrictionLaws::dispatch`].
#[derive(Clone, Debug, PartialEq)]
pub enum FrictionLaws<const L: usize> {
    /// The slip-weakening family.
    Weakening(Vec<<Weakening as Law>::Lanes<L>>),
}

/// What runs with one law's coefficients: the contact kernel, generic over the law.
pub trait WithLaw<const L: usize> {
    /// What it returns.
    type Out;
    /// Runs with the coefficients `lanes` of law `W`.
    fn run<W: Law>(self, lanes: &[W::Lanes<L>]) -> Self::Out;
}

impl<const L: usize> FrictionLaws<L> {
    /// The coefficients of every contact node for `L` seeds: `node(c, l)` gives contact node `c`'s
    /// coefficients in lane `l` (every node under the one law of the scene).
    pub fn new(contacts: usize, node: impl Fn(usize, usize) -> NodeFriction) -> Self {
        let weakening = |c: usize, l: usize| match node(c, l) {
            NodeFriction::Weakening(n) => n,
        };
        FrictionLaws::Weakening(
            (0..contacts).map(|c| Weakening::lanes::<L>(std::array::from_fn(|l| weakening(c, l)))).collect(),
        )
    }

    /// Runs `f` with the law's coefficients (the one branch on the law, outside every loop).
    #[inline]
    pub fn dispatch<F: WithLaw<L>>(&self, f: F) -> F::Out {
        match self {
            FrictionLaws::Weakening(v) => f.run::<Weakening>(v),
        }
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
    fn mu_static(&self) -> f64 {
        match self {
            FrictionLaw::Coulomb(c) => c.mu,
            FrictionLaw::StaticDynamic(s) => s.mu_static,
            FrictionLaw::SlipWeakening(s) => s.mu_static,
        }
    }

    /// Dynamic coefficient μd (before any field factor); μs for the plain law.
    fn mu_dynamic(&self) -> f64 {
        match self {
            FrictionLaw::Coulomb(c) => c.mu,
            FrictionLaw::StaticDynamic(s) => s.mu_dynamic,
            FrictionLaw::SlipWeakening(s) => s.mu_dynamic,
        }
    }

    /// Slip-weakening distance Dc (m); 0 for laws that drop at once or not at all.
    fn weakening_distance_m(&self) -> f64 {
        match self {
            FrictionLaw::SlipWeakening(s) => s.dc_m,
            _ => 0.0,
        }
    }

    /// The coefficients of a node whose random-field factor is `factor`.
    pub fn node(&self, factor: f64) -> NodeFriction {
        NodeFriction::Weakening(WeakeningNode::new(
            self.mu_static() * factor,
            self.mu_dynamic() * factor,
            self.weakening_distance_m(),
        ))
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
        assert_eq!((n.static_coefficient(), n.residual_coefficient()), (0.6 * 1.5, 0.45 * 1.5));
        assert_eq!(FrictionLaw::Coulomb(Coulomb { mu: 5.0 }).node(1.0).residual_coefficient(), 5.0);
    }

    #[test]
    fn kinetic_coefficients_of_each_law() {
        let weakening = |law: FrictionLaw| match law.node(1.0) {
            NodeFriction::Weakening(n) => n,
        };
        let plain = weakening(FrictionLaw::Coulomb(Coulomb { mu: 0.6 }));
        assert_eq!(plain.kinetic(1.0), 0.6);
        let sd = weakening(FrictionLaw::StaticDynamic(StaticDynamic { mu_static: 0.6, mu_dynamic: 0.4 }));
        assert_eq!(sd.kinetic(0.0), 0.4);
        assert_eq!(sd.kinetic(1.0), 0.4);
        let sw = weakening(FrictionLaw::SlipWeakening(SlipWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 1e-3 }));
        assert_eq!(sw.kinetic(0.0), 0.6);
        assert!((sw.kinetic(0.5e-3) - 0.5).abs() < 1e-15);
        assert_eq!(sw.kinetic(2e-3), 0.4);
        // Sticking nodes hold at μs whatever the law.
        assert_eq!(Weakening::holding(&sw, false, sw.kinetic(0.5e-3), 0.5e-3), 0.6);
        assert_eq!(Weakening::stuck(&sw, 0.5e-3), 0.0);
        // Without healing a stuck node keeps its slip and holds at its weakened coefficient; one
        // that never slipped holds at μs.
        let kept = sw.with_healing(false);
        assert_eq!(Weakening::stuck(&kept, 0.5e-3), 0.5e-3);
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
