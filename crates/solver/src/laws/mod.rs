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
//! Coulomb law, static/dynamic friction and linear slip weakening are the cases, exponential
//! slip weakening [`Exponential`] ([`exponential`]) and rate-and-state friction [`RateState`]
//! ([`rate_state`], the aging and slip laws). Each law's builders convert into a
//! [`FrictionLaw`], the scene's choice; a friction map ([`map`]) gives regions of the base their
//! own coefficients under the same law. A new law is a file beside [`slip_weakening`]
//! implementing [`Law`] and its line in the `laws!` list below, which derives [`NodeFriction`],
//! [`FrictionLaws`] and their forwarding; its keys and refusals are a file of the configuration
//! crate (ARCHITECTURE.md lists the files).

pub mod exponential;
pub mod map;
pub mod rate_state;
pub mod slip_weakening;

use std::fmt::Debug;

pub use exponential::{Exponential, ExponentialNode, ExponentialWeakening};
pub use map::{FrictionMap, Region, RegionKind};
pub use rate_state::{Evolution, RateState, RateStateNode, RateStateStart, balanced_state};
pub use slip_weakening::{Coulomb, SlipWeakening, StaticDynamic, Weakening, WeakeningLanes, WeakeningNode};

/// A friction law of the base: its coefficients at one contact node, its one state variable
/// there, and the answers the contact rule, the static solves and `check` ask of it.
pub trait Law: Copy + Debug + Default + Send + Sync + 'static {
    /// The law's name, as `check` and messages print it.
    const NAME: &'static str;
    /// How [`Law::cohesive_zone_m`] is computed, as `check` prints it.
    const COHESIVE_ZONE: &'static str;
    /// How [`Law::critical_stiffness`] is computed, as `check` prints it.
    const CRITICAL: &'static str;
    /// Why a block slides steadily when [`Law::critical_stiffness`] is 0, and what would change
    /// it, as `check`'s verdict says it.
    const STEADY: &'static str;
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
    /// The state variable of a node that sticks (or is lifted) over a step of `dt_s` seconds,
    /// from `state`: 0 for a law that heals, `state` for one that keeps its slip, θ aged by
    /// `dt_s` for a rate-and-state law.
    fn stuck(node: &Self::Node, state: f64, dt_s: f64) -> f64;
    /// The state variable of a sliding node after it moved `slid_m` metres in a step of `dt_s`
    /// seconds.
    fn advance(node: &Self::Node, state: f64, slid_m: f64, dt_s: f64) -> f64;
    /// The state variable at the start of a run of a node whose initial shear and normal
    /// tractions are `tau_pa` and `sigma_pa` (0 off a fault): 0, no slip yet, unless the law says
    /// otherwise (θ₀ for a rate-and-state law).
    fn initial_state(_node: &Self::Node, _tau_pa: f64, _sigma_pa: f64) -> f64 {
        0.0
    }
    /// The coefficients times a random-field factor (the Weibull field on μ).
    fn scaled(node: &Self::Node, factor: f64) -> Self::Node;
    /// The same coefficients, a node that sticks healing (`true`) or keeping its state.
    fn with_healing(node: &Self::Node, heals: bool) -> Self::Node;
    /// The coefficient once fully weakened (steady sliding).
    fn residual_coefficient(node: &Self::Node) -> f64;
    /// Critical stiffness of a spring-slider of normal force `normal_n` on this node: loading
    /// stiffer than this slides stably (N/m; infinite when μ drops at once, 0 when it never drops).
    fn critical_stiffness(node: &Self::Node, normal_n: f64) -> f64;
    /// The size of the cohesive zone of a rupture front at rest on this node under normal stress
    /// `normal_pa` in a medium of shear modulus `shear_modulus_pa` (m; Day et al. 2005's
    /// estimate from the law's fracture energy), `None` when the law does not weaken over a
    /// slip. `check` compares it with the lattice's spacing.
    fn cohesive_zone_m(node: &Self::Node, shear_modulus_pa: f64, normal_pa: f64) -> Option<f64>;
    /// Its coefficients with their symbols and units, as `check` and the report print them.
    fn coefficients(node: &Self::Node) -> Vec<Coefficient>;
    /// The nucleation size of a rupture on this node's friction under normal stress `normal_pa`
    /// in a medium of shear modulus `shear_modulus_pa` (m), `None` when the law has none (a
    /// rate-and-state law's `h*`, where it weakens with slip rate).
    fn nucleation_m(_node: &Self::Node, _shear_modulus_pa: f64, _normal_pa: f64) -> Option<f64> {
        None
    }
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
    /// The slip per distance the node slides: 1 on the base, 2 on a fault (the other side
    /// moves the opposite way).
    pub slip_per_slide: f64,
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

/// The laws of the workspace, one line each: `Variant(LawType)`. From the list come
/// [`NodeFriction`] (a node's coefficients under any law), [`FrictionLaws`] (every contact node's
/// coefficients for `L` seeds, the one branch on the law outside the kernel's loops) and the
/// forwarding of every question to the law's own [`Law`] implementation: adding a law is its
/// file and its line here.
macro_rules! laws {
    ($($(#[$doc:meta])* $variant:ident($law:ty)),+ $(,)?) => {
        /// A contact node's coefficients under the scene's law, whatever the law: what the scene,
        /// its friction map, `check` and the figures hold and ask.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum NodeFriction {
            $($(#[$doc])* $variant(<$law as Law>::Node),)+
        }

        impl NodeFriction {
            /// The static coefficient ([`Law::static_coefficient`]).
            pub fn static_coefficient(&self) -> f64 {
                match self { $(NodeFriction::$variant(n) => <$law>::static_coefficient(n),)+ }
            }

            /// The coefficient once fully weakened ([`Law::residual_coefficient`]).
            pub fn residual_coefficient(&self) -> f64 {
                match self { $(NodeFriction::$variant(n) => <$law>::residual_coefficient(n),)+ }
            }

            /// The spring-slider's critical stiffness at normal force `normal_n`
            /// ([`Law::critical_stiffness`]).
            pub fn critical_stiffness(&self, normal_n: f64) -> f64 {
                match self { $(NodeFriction::$variant(n) => <$law>::critical_stiffness(n, normal_n),)+ }
            }

            /// The cohesive zone's size under normal stress `normal_pa` in a medium of shear
            /// modulus `shear_modulus_pa` ([`Law::cohesive_zone_m`]).
            pub fn cohesive_zone_m(&self, shear_modulus_pa: f64, normal_pa: f64) -> Option<f64> {
                match self { $(NodeFriction::$variant(n) => <$law>::cohesive_zone_m(n, shear_modulus_pa, normal_pa),)+ }
            }

            /// The nucleation size ([`Law::nucleation_m`]).
            pub fn nucleation_m(&self, shear_modulus_pa: f64, normal_pa: f64) -> Option<f64> {
                match self { $(NodeFriction::$variant(n) => <$law>::nucleation_m(n, shear_modulus_pa, normal_pa),)+ }
            }

            /// The named coefficients ([`Law::coefficients`]).
            pub fn coefficients(&self) -> Vec<Coefficient> {
                match self { $(NodeFriction::$variant(n) => <$law>::coefficients(n),)+ }
            }

            /// The coefficients times a random-field factor ([`Law::scaled`]).
            pub fn scaled(&self, factor: f64) -> NodeFriction {
                match self { $(NodeFriction::$variant(n) => NodeFriction::$variant(<$law>::scaled(n, factor)),)+ }
            }

            /// The same coefficients, healing when a node sticks or not ([`Law::with_healing`]).
            pub fn healing(&self, heals: bool) -> NodeFriction {
                match self { $(NodeFriction::$variant(n) => NodeFriction::$variant(<$law>::with_healing(n, heals)),)+ }
            }

            /// How the law's critical stiffness is computed ([`Law::CRITICAL`]).
            pub fn critical_formula(&self) -> &'static str {
                match self { $(NodeFriction::$variant(_) => <$law>::CRITICAL,)+ }
            }

            /// Why the law slides steadily without a critical stiffness ([`Law::STEADY`]).
            pub fn steady_reason(&self) -> &'static str {
                match self { $(NodeFriction::$variant(_) => <$law>::STEADY,)+ }
            }

            /// How the law's cohesive zone is computed ([`Law::COHESIVE_ZONE`]).
            pub fn cohesive_zone_formula(&self) -> &'static str {
                match self { $(NodeFriction::$variant(_) => <$law>::COHESIVE_ZONE,)+ }
            }

            /// The law's name ([`Law::NAME`]).
            pub fn law_name(&self) -> &'static str {
                match self { $(NodeFriction::$variant(_) => <$law>::NAME,)+ }
            }
        }

        /// The per-node, per-lane coefficients of the scene's law for `L` seeds, chosen once
        /// before the run: the contact kernel is monomorphised for the law in
        /// [`FrictionLaws::dispatch`].
        #[derive(Clone, Debug, PartialEq)]
        pub enum FrictionLaws<const L: usize> {
            $($(#[$doc])* $variant(Vec<<$law as Law>::Lanes<L>>),)+
        }

        impl<const L: usize> FrictionLaws<L> {
            /// The coefficients of every contact node for `L` seeds under the law of `background`
            /// (the scene's): `node(c, l)` gives contact node `c`'s coefficients in lane `l`.
            ///
            /// # Panics
            /// When a node is under another law than `background`'s (the configuration builds
            /// every node of a scene under its one law).
            pub fn new(background: &NodeFriction, contacts: usize, node: impl Fn(usize, usize) -> NodeFriction) -> Self {
                match background {
                    $(NodeFriction::$variant(_) => FrictionLaws::$variant(
                        (0..contacts)
                            .map(|c| {
                                <$law>::lanes::<L>(std::array::from_fn(|l| match node(c, l) {
                                    NodeFriction::$variant(n) => n,
                                    #[allow(unreachable_patterns)]
                                    other => panic!("one law per scene: node {c} is under {}", other.law_name()),
                                }))
                            })
                            .collect(),
                    ),)+
                }
            }

            /// Every contact node's state variable at the start of a run, lane by lane
            /// ([`Law::initial_state`]), `traction(c, l)` giving node `c`'s initial shear and
            /// normal traction in lane `l` (Pa, or forces on the node's area: a balanced start
            /// reads their ratio; zeros off a fault).
            pub fn initial_states(&self, traction: impl Fn(usize, usize) -> (f64, f64)) -> Vec<[f64; L]> {
                match self {
                    $(FrictionLaws::$variant(v) => v
                        .iter()
                        .enumerate()
                        .map(|(ci, c)| std::array::from_fn(|l| {
                            let (tau, sigma) = traction(ci, l);
                            <$law>::initial_state(&<$law>::lane(c, l), tau, sigma)
                        }))
                        .collect(),)+
                }
            }

            /// Runs `f` with the law's coefficients (the one branch on the law, outside every loop).
            #[inline]
            pub fn dispatch<F: WithLaw<L>>(&self, f: F) -> F::Out {
                match self { $(FrictionLaws::$variant(v) => f.run::<$law>(v),)+ }
            }
        }
    };
}

laws! {
    /// The slip-weakening family (Coulomb, static/dynamic, linear slip weakening).
    Weakening(Weakening),
    /// Exponential slip weakening.
    Exponential(Exponential),
    /// Rate-and-state friction (aging or slip law).
    RateState(RateState),
}

/// What runs with one law's coefficients: the contact kernel, generic over the law.
pub trait WithLaw<const L: usize> {
    /// What it returns.
    type Out;
    /// Runs with the coefficients `lanes` of law `W`.
    fn run<W: Law>(self, lanes: &[W::Lanes<L>]) -> Self::Out;
}

/// The friction law of a scene, chosen once before the run: the coefficients of its background
/// (before any random field) and the name the configuration gave it (a case of the law, e.g.
/// `coulomb` of the slip-weakening family). Each law's builders convert into it
/// (e.g. [`SlipWeakening`]`.into()`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionLaw {
    /// Name as written in tables and messages.
    pub name: &'static str,
    /// The background's coefficients before the field factor.
    pub background: NodeFriction,
}

impl FrictionLaw {
    /// The coefficients of a node whose random-field factor is `factor`.
    pub fn node(&self, factor: f64) -> NodeFriction {
        self.background.scaled(factor)
    }

    /// Name as written in tables and messages.
    pub fn name(&self) -> &'static str {
        self.name
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_coefficients_scale_with_the_field_factor() {
        let law: FrictionLaw = StaticDynamic { mu_static: 0.6, mu_dynamic: 0.45 }.into();
        let n = law.node(1.5);
        assert_eq!((n.static_coefficient(), n.residual_coefficient()), (0.6 * 1.5, 0.45 * 1.5));
        let law: FrictionLaw = Coulomb { mu: 5.0 }.into();
        assert_eq!(law.node(1.0).residual_coefficient(), 5.0);
        assert_eq!(law.name(), "coulomb");
        let law: FrictionLaw = ExponentialWeakening { mu_static: 0.6, mu_dynamic: 0.3, dc_m: 0.1 }.into();
        assert_eq!(law.node(2.0).static_coefficient(), 1.2);
        assert_eq!(law.node(2.0).law_name(), "exponential slip weakening");
    }

    #[test]
    fn each_node_answers_with_its_own_law() {
        let linear: FrictionLaw = SlipWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 0.1 }.into();
        let exponential: FrictionLaw = ExponentialWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 0.1 }.into();
        let (l, e) = (linear.node(1.0), exponential.node(1.0));
        // The same initial weakening rate, a fracture energy twice the linear law's: the zone
        // doubles.
        assert_eq!(l.critical_stiffness(100.0), e.critical_stiffness(100.0));
        let (zl, ze) = (l.cohesive_zone_m(30e9, 1e6).unwrap(), e.cohesive_zone_m(30e9, 1e6).unwrap());
        assert!((ze / zl - 2.0).abs() < 1e-12, "{ze} {zl}");
        let lanes = FrictionLaws::<2>::new(&e, 3, |_, _| e);
        assert!(matches!(lanes, FrictionLaws::Exponential(ref v) if v.len() == 3));
    }

    #[test]
    #[should_panic(expected = "one law per scene")]
    fn a_scene_holds_one_law() {
        let linear: FrictionLaw = SlipWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 0.1 }.into();
        let exponential: FrictionLaw = ExponentialWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 0.1 }.into();
        let _ =
            FrictionLaws::<1>::new(
                &linear.node(1.0),
                2,
                |c, _| if c == 0 { linear.node(1.0) } else { exponential.node(1.0) },
            );
    }
}
