//! Rate-and-state friction (docs/model.md §4), in the regularised form the SCEC SEAS and TPV10x
//! benchmarks define (Rice & Ben-Zion 1996; Lapusta et al. 2000):
//!
//! `f(V, θ) = a·asinh(V/(2V₀)·exp(ψ/a))`, `ψ = f₀ + b·ln(V₀θ/L)`,
//!
//! with the state θ (s) evolving by the aging law `dθ/dt = 1 − Vθ/L` or the slip law
//! `dθ/dt = −(Vθ/L)·ln(Vθ/L)`. At steady state (θ = L/V) and `V ≫ V₀·exp(−ψ/a)`,
//! `f = f₀ + (a − b)·ln(V/V₀)`: velocity weakening where `b > a`.
//!
//! **In the explicit step** the law has no sticking: a node in contact slides at the slip rate
//! `V ≥ 0` that balances its step, `f(V, θ)·N + Z·V = R`, where `R` is the tangential reaction
//! that would hold it still and `Z = g·Δt/k` the step's impedance (`g` the update's stiffness,
//! `k` the slip per distance slid: 1 on the base, 2 on a fault). The state is updated by the
//! two-pass scheme of Kaneko et al. (2008): `V₁` from the balance at the step's start state `θₙ`;
//! `θ* = θ(θₙ, V₁, Δt)` by the evolution law's exact solution at constant slip rate; `V₂` from
//! the balance at `θ*`, whose friction `f(V₂, θ*)` the node slides with; and
//! `θₙ₊₁ = θ(θₙ, V₂, Δt)`, from the slip it made. A node off the base ages at `V = 0`.
//!
//! The balance is monotone in V (both terms grow with it) and is solved by Newton's method on
//! `ln V`, kept inside a bracket that geometric bisection shrinks when a Newton step leaves it
//! ([`balance`]); every logarithm and exponential is taken in log space, so θ from milliseconds to
//! millennia and `a` down to 10⁻³ neither overflow nor lose the root.

use super::{Coefficient, FrictionLaw, Law, NodeFriction, Trial};

/// How the state variable evolves.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Evolution {
    /// The aging law `dθ/dt = 1 − Vθ/L` (Dieterich): θ grows at rest.
    #[default]
    Aging,
    /// The slip law `dθ/dt = −(Vθ/L)·ln(Vθ/L)` (Ruina): θ changes only with slip.
    Slip,
}

/// Rate-and-state friction as a [`Law`]: its state variable is θ (s).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RateState;

/// The coefficients of one contact node under rate-and-state friction; converted into a
/// [`FrictionLaw`], the scene's background.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RateStateNode {
    /// The direct effect a > 0.
    pub a: f64,
    /// The evolution effect b ≥ 0.
    pub b: f64,
    /// The characteristic slip L (m), > 0.
    pub dc_m: f64,
    /// The reference slip rate V₀ (m/s), > 0.
    pub v0_m_s: f64,
    /// The reference friction f₀ at steady sliding at V₀.
    pub f0: f64,
    /// The state's evolution law.
    pub evolution: Evolution,
    /// How the run starts: steady state at a slip rate (θ₀ = L/Vᵢ, following this node's L) or a
    /// given θ₀.
    pub start: RateStateStart,
}

impl Default for RateStateStart {
    fn default() -> Self {
        RateStateStart::State(1.0)
    }
}

impl RateStateNode {
    /// The state at the start of the run θ₀ (s) of a node whose initial shear and normal
    /// tractions are `tau_pa` and `sigma_pa` (a balanced start needs them; the others do not).
    pub fn theta0_s(&self, tau_pa: f64, sigma_pa: f64) -> f64 {
        match self.start {
            RateStateStart::SteadyAt(v) => self.dc_m / v,
            RateStateStart::State(theta) => theta,
            RateStateStart::Balanced(v) => balanced_state(self, v, tau_pa, sigma_pa, 0.0),
        }
    }

    /// `ψ/a − ln(2V₀)`: `f = a·asinh(exp(ln V + this))`.
    #[inline(always)]
    fn log_scale(&self, theta: f64) -> f64 {
        (self.f0 + self.b * (self.v0_m_s * theta / self.dc_m).ln()) / self.a - (2.0 * self.v0_m_s).ln()
    }
}

/// `asinh(exp(s))` without overflow, and its derivative in `s`, `1/sqrt(1 + exp(−2s))`.
#[inline(always)]
fn asinh_exp(s: f64) -> (f64, f64) {
    if s > 20.0 {
        // asinh(y) = ln(2y) + 1/(4y²) − …; the correction is below 1e-18 relative here.
        let e = (-2.0 * s).exp();
        (s + std::f64::consts::LN_2 + 0.25 * e, 1.0 / (1.0 + e).sqrt())
    } else if s == f64::NEG_INFINITY {
        (0.0, 0.0)
    } else {
        let y = s.exp();
        (y.asinh(), y / y.mul_add(y, 1.0).sqrt())
    }
}

/// The friction coefficient `f(V, θ)` at slip rate `v_m_s ≥ 0` and state `theta_s`.
pub fn friction(n: &RateStateNode, v_m_s: f64, theta_s: f64) -> f64 {
    n.a * asinh_exp(v_m_s.ln() + n.log_scale(theta_s)).0
}

/// The steady-state friction at slip rate `v_m_s > 0` (θ = L/V).
pub fn steady_friction(n: &RateStateNode, v_m_s: f64) -> f64 {
    friction(n, v_m_s, n.dc_m / v_m_s)
}

/// The state after `dt_s` seconds at the constant slip rate `v_m_s ≥ 0` from `theta_s`, by the
/// evolution law's exact solution: aging `L/V + (θ − L/V)·exp(−VΔt/L)` (`θ + Δt` at rest), slip
/// `(L/V)·exp(ln(Vθ/L)·exp(−VΔt/L))` (unchanged at rest).
pub fn evolve(n: &RateStateNode, theta_s: f64, v_m_s: f64, dt_s: f64) -> f64 {
    let x = v_m_s * dt_s / n.dc_m;
    match n.evolution {
        // θ·e^{−x} + (L/V)(1 − e^{−x}) = θ·e^{−x} + Δt·(1 − e^{−x})/x, exact as x → 0.
        Evolution::Aging => {
            if x == 0.0 {
                theta_s + dt_s
            } else {
                theta_s * (-x).exp() - dt_s * (-x).exp_m1() / x
            }
        }
        Evolution::Slip => {
            if x == 0.0 {
                theta_s
            } else {
                let steady = n.dc_m / v_m_s;
                steady * ((theta_s / steady).ln() * (-x).exp()).exp()
            }
        }
    }
}

/// The slip rate `V ≥ 0` balancing `f(V, θ)·N + Z·V = need` at state `theta_s`, normal force
/// `normal_n > 0` and impedance `z > 0` (N·s/m); 0 when nothing is needed.
///
/// The root lies between `need/(a·N·c + Z)` (the friction's tangent at 0 bounds it from above,
/// `c = exp(ψ/a)/(2V₀)`) and `min(need/Z, sinh(need/(aN))/c)`; Newton's method on `ln V` runs
/// inside that bracket, which each iterate narrows, and a step that would leave it is replaced
/// by the bracket's geometric midpoint. It stops when an iterate moves `ln V` by less than 1e-13.
pub fn balance(n: &RateStateNode, theta_s: f64, need: f64, normal_n: f64, z: f64) -> f64 {
    balance_from(n, theta_s, need, normal_n, z, None)
}

/// [`balance`] with Newton started from `guess` (m/s) when it lies inside the bracket: a node's
/// previous slip rate saves most iterations when its traction and state changed little.
pub fn balance_from(n: &RateStateNode, theta_s: f64, need: f64, normal_n: f64, z: f64, guess: Option<f64>) -> f64 {
    if !(need > 0.0 && normal_n > 0.0) {
        return 0.0;
    }
    let scale = n.log_scale(theta_s);
    let an = n.a * normal_n;
    // ln c, and the bracket in ln V.
    let low = need.ln() - (an * scale.exp() + z).ln();
    let low = if low.is_finite() { low } else { need.ln() - (an.ln() + scale).max(z.ln()) - std::f64::consts::LN_2 };
    let sinh_bound = {
        let r = need / an;
        // ln(sinh(r)) − ln c.
        (if r > 20.0 { r - std::f64::consts::LN_2 } else { r.sinh().ln() }) - scale
    };
    let (mut lo, mut hi) = (low, (need / z).ln().min(sinh_bound));
    if !(hi > lo) {
        return hi.exp();
    }
    let residual = |u: f64| {
        let v = u.exp();
        let (f, df) = asinh_exp(u + scale);
        (an * f + z * v - need, an * df + z * v)
    };
    let mut u = match guess.map(f64::ln) {
        Some(g) if g > lo && g < hi => g,
        _ => lo,
    };
    for _ in 0..200 {
        let (r, dr) = residual(u);
        if r == 0.0 {
            return u.exp();
        }
        if r < 0.0 {
            lo = u;
        } else {
            hi = u;
        }
        let newton = u - r / dr;
        let next = if newton > lo && newton < hi { newton } else { 0.5 * (lo + hi) };
        if (next - u).abs() < 1e-13 * (1.0 + u.abs()) || hi - lo < 1e-13 * (1.0 + lo.abs()) {
            return next.exp();
        }
        u = next;
    }
    u.exp()
}

/// The two-pass step of a sliding node (see the module doc): the slip rate `V₂` it slides at and
/// the state `θ*` its friction is taken at.
pub fn two_pass(n: &RateStateNode, theta_s: f64, trial: &Trial) -> (f64, f64) {
    let z = trial.g_n_m * trial.dt_s / trial.slip_per_slide;
    let v1 = balance(n, theta_s, trial.need_n, trial.normal_n, z);
    let predicted = evolve(n, theta_s, v1, trial.dt_s);
    (balance(n, predicted, trial.need_n, trial.normal_n, z), predicted)
}

/// The slip rate at which [`Law::residual_coefficient`] is taken: 1 m/s, a coseismic rate.
pub const COSEISMIC_RATE_M_S: f64 = 1.0;

impl Law for RateState {
    const NAME: &'static str = "rate-and-state friction";
    const COHESIVE_ZONE: &'static str = "(9π/32)·μ·L/(b·σ)";
    const CRITICAL: &'static str = "(b − a)·N/L";
    const STEADY: &'static str = "the friction is velocity strengthening (b ≤ a), so a seated block slides steadily \
                                  (make b larger than a)";
    type Node = RateStateNode;
    type Lanes<const L: usize> = [RateStateNode; L];

    fn lanes<const L: usize>(nodes: [RateStateNode; L]) -> [RateStateNode; L] {
        nodes
    }

    #[inline(always)]
    fn lane<const L: usize>(lanes: &[RateStateNode; L], l: usize) -> RateStateNode {
        lanes[l]
    }

    /// The strength at V₀ from the starting state, `f(V₀, θ₀)`: what the static self-weight
    /// solve and `check` take as the node's static coefficient; f₀ for a balanced start (its θ₀
    /// depends on the node's traction).
    fn static_coefficient(node: &RateStateNode) -> f64 {
        match node.start {
            RateStateStart::Balanced(_) => node.f0,
            _ => friction(node, node.v0_m_s, node.theta0_s(0.0, 0.0)),
        }
    }

    /// `f(V₂, θ*)` of the two-pass step (`need/N`, holding it, when `V₂` underflows to 0); 0 for
    /// a node not pressed on (its result is not used).
    #[inline(always)]
    fn kinetic(node: &RateStateNode, theta: f64, trial: &Trial) -> f64 {
        if !(trial.normal_n > 0.0 && trial.need_n > 0.0) {
            return 0.0;
        }
        let (v, predicted) = two_pass(node, theta, trial);
        // A slip rate below the smallest double (a strong state under a light load) holds the
        // node: its friction is all the load.
        if v == 0.0 { trial.need_n / trial.normal_n } else { friction(node, v, predicted) }
    }

    /// Its kinetic coefficient: a node holds only when the balance gives it no slip rate.
    #[inline(always)]
    fn holding(_: &RateStateNode, _: bool, kinetic: f64, _: f64) -> f64 {
        kinetic
    }

    /// A node at rest ages over the step (the slip law leaves θ as it is).
    #[inline(always)]
    fn stuck(node: &RateStateNode, theta: f64, dt_s: f64) -> f64 {
        evolve(node, theta, 0.0, dt_s)
    }

    #[inline(always)]
    fn advance(node: &RateStateNode, theta: f64, slid_m: f64, dt_s: f64) -> f64 {
        evolve(node, theta, slid_m / dt_s, dt_s)
    }

    fn initial_state(node: &RateStateNode, tau_pa: f64, sigma_pa: f64) -> f64 {
        node.theta0_s(tau_pa, sigma_pa)
    }

    /// a, b and f₀ times the factor: the steady-state friction `f₀ + (a − b)·ln(V/V₀)` scales
    /// with it.
    fn scaled(node: &RateStateNode, factor: f64) -> RateStateNode {
        RateStateNode { a: node.a * factor, b: node.b * factor, f0: node.f0 * factor, ..*node }
    }

    /// The law heals by its own evolution: the same coefficients.
    fn with_healing(node: &RateStateNode, _: bool) -> RateStateNode {
        *node
    }

    /// The steady-state friction at 1 m/s.
    fn residual_coefficient(node: &RateStateNode) -> f64 {
        steady_friction(node, COSEISMIC_RATE_M_S)
    }

    /// `(b − a)·N/L` (Ruina 1983; Rice & Ruina 1983), 0 where `b ≤ a` (velocity strengthening).
    fn critical_stiffness(node: &RateStateNode, normal_n: f64) -> f64 {
        ((node.b - node.a) * normal_n / node.dc_m).max(0.0)
    }

    /// The process zone at rest `Λ₀ = (9π/32)·μ·L/(b·σ)` (Day et al. 2005; the SEAS benchmarks'
    /// resolution criterion), `None` without an evolution effect.
    fn cohesive_zone_m(node: &RateStateNode, shear_modulus_pa: f64, normal_pa: f64) -> Option<f64> {
        (node.b > 0.0 && normal_pa > 0.0)
            .then(|| 9.0 * std::f64::consts::PI / 32.0 * shear_modulus_pa * node.dc_m / (node.b * normal_pa))
    }

    /// `h* = (π/2)·μ·b·L/((b − a)²·σ)` (Rubin & Ampuero 2005, the SEAS benchmarks' nucleation
    /// size), `None` where `b ≤ a`.
    fn nucleation_m(node: &RateStateNode, shear_modulus_pa: f64, normal_pa: f64) -> Option<f64> {
        (node.b > node.a && normal_pa > 0.0).then(|| {
            std::f64::consts::FRAC_PI_2 * shear_modulus_pa * node.b * node.dc_m
                / ((node.b - node.a).powi(2) * normal_pa)
        })
    }

    fn coefficients(node: &RateStateNode) -> Vec<Coefficient> {
        vec![
            Coefficient { symbol: "a", value: node.a, unit: "" },
            Coefficient { symbol: "b", value: node.b, unit: "" },
            Coefficient { symbol: "L", value: node.dc_m, unit: "m" },
            Coefficient { symbol: "V₀", value: node.v0_m_s, unit: "m/s" },
            Coefficient { symbol: "f₀", value: node.f0, unit: "" },
            match node.start {
                RateStateStart::Balanced(v) => Coefficient { symbol: "Vᵢ (θ₀ balanced)", value: v, unit: "m/s" },
                _ => Coefficient { symbol: "θ₀", value: node.theta0_s(0.0, 0.0), unit: "s" },
            },
        ]
    }
}

/// How a rate-and-state law starts: at steady state at a slip rate, from a given state, or from
/// the state with which the node's initial traction slides it at a slip rate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RateStateStart {
    /// θ₀ = L/Vᵢ: steady state at slip rate Vᵢ (m/s).
    SteadyAt(f64),
    /// θ₀ (s).
    State(f64),
    /// θ₀ such that `σ·f(Vᵢ, θ₀) = τ` on each node, from its initial tractions
    /// ([`balanced_state`]): the node starts sliding at Vᵢ (m/s) in balance, as SCEC TPV101–104
    /// start.
    Balanced(f64),
}

/// `θ₀` with which a node slides at `v` under shear `tau` and normal stress `sigma` with
/// radiation damping `eta` (SEAS BP1–BP3's start; TPV101's with `eta = 0`):
/// `(L/V₀)·exp{(a/b)·ln[(2V₀/V)·sinh((τ − ηV)/(aσ))] − f₀/b}`; steady state `L/V` when b = 0.
pub fn balanced_state(n: &RateStateNode, v: f64, tau: f64, sigma: f64, eta: f64) -> f64 {
    if n.b == 0.0 {
        return n.dc_m / v;
    }
    let x = (tau - eta * v) / (n.a * sigma);
    let ln_sinh = if x > 20.0 { x - std::f64::consts::LN_2 } else { x.sinh().ln() };
    (n.dc_m / n.v0_m_s) * ((n.a / n.b) * ((2.0 * n.v0_m_s / v).ln() + ln_sinh) - n.f0 / n.b).exp()
}

/// A scene's law from the background's coefficients.
impl From<RateStateNode> for FrictionLaw {
    fn from(n: RateStateNode) -> FrictionLaw {
        let name = match n.evolution {
            Evolution::Aging => "rate_state_aging",
            Evolution::Slip => "rate_state_slip",
        };
        FrictionLaw { name, background: NodeFriction::RateState(n) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn node(evolution: Evolution) -> RateStateNode {
        RateStateNode {
            a: 0.010,
            b: 0.015,
            dc_m: 0.008,
            v0_m_s: 1e-6,
            f0: 0.6,
            evolution,
            start: RateStateStart::SteadyAt(1e-9),
        }
    }

    #[test]
    fn steady_state_is_the_closed_form_and_a_fixed_point_of_both_laws() {
        for evolution in [Evolution::Aging, Evolution::Slip] {
            let n = node(evolution);
            for k in -12..=1 {
                let v = 10f64.powi(k);
                // The regularised form differs from the logarithm by (2V₀/V)²·exp(−2ψ/a)/4,
                // below 1e-40 at these rates.
                let closed = n.f0 + (n.a - n.b) * (v / n.v0_m_s).ln();
                assert!((steady_friction(&n, v) - closed).abs() < 1e-12, "V = {v}: {}", steady_friction(&n, v));
                let theta = n.dc_m / v;
                for dt in [1e-6, 1.0, 1e6] {
                    let next = evolve(&n, theta, v, dt);
                    assert!((next / theta - 1.0).abs() < 1e-12, "{evolution:?} V = {v}, Δt = {dt}: {next} vs {theta}");
                }
            }
        }
    }

    #[test]
    fn a_velocity_step_jumps_by_a_ln_v2_v1_then_relaxes_over_l() {
        let (v1, v2) = (1e-6, 1e-4);
        for evolution in [Evolution::Aging, Evolution::Slip] {
            let n = RateStateNode { start: RateStateStart::SteadyAt(v1), ..node(evolution) };
            let before = friction(&n, v1, n.theta0_s(0.0, 0.0));
            let jump = friction(&n, v2, n.theta0_s(0.0, 0.0)) - before;
            assert!((jump - n.a * (v2 / v1).ln()).abs() < 1e-12, "{evolution:?}: jump {jump}");
            // 1000 steps over 20 L of slip: the aging law's exact solution of θ(δ), and friction
            // back to the new steady state.
            let dt = 20.0 * n.dc_m / v2 / 1000.0;
            let mut theta = n.theta0_s(0.0, 0.0);
            for i in 1..=1000 {
                theta = evolve(&n, theta, v2, dt);
                if evolution == Evolution::Aging {
                    let delta = v2 * dt * f64::from(i);
                    let exact = n.dc_m / v2 + (n.theta0_s(0.0, 0.0) - n.dc_m / v2) * (-delta / n.dc_m).exp();
                    assert!((theta / exact - 1.0).abs() < 1e-12, "step {i}: {theta} vs {exact}");
                }
            }
            let after = friction(&n, v2, theta);
            let drop = steady_friction(&n, v2) - after;
            assert!(drop.abs() < 1e-4 * n.b, "{evolution:?}: {after} vs steady {}", steady_friction(&n, v2));
            // The peak relaxes by b·ln(V₂/V₁) in all: the steady states differ by (a − b)·ln.
            assert!((after - before - (n.a - n.b) * (v2 / v1).ln()).abs() < 1e-5);
        }
    }

    #[test]
    fn the_balance_is_solved_across_twenty_decades_of_state_load_and_impedance() {
        let mut worst: f64 = 0.0;
        for evolution in [Evolution::Aging, Evolution::Slip] {
            for a in [1e-3, 0.01, 0.025] {
                let n = RateStateNode { a, ..node(evolution) };
                for theta in [1e-3, 1.0, 1e4, 1e8, 1e12] {
                    for need in [1e-6, 1e-3, 0.3, 0.6, 0.9, 5.0] {
                        for z in [1e3, 1e6, 1e9, 1e12, 1e15] {
                            let normal = 1.0;
                            let v = balance(&n, theta, need, normal, z);
                            assert!(v >= 0.0 && v.is_finite(), "θ {theta} need {need} Z {z}: V = {v}");
                            if v == 0.0 {
                                // The root is below the smallest double: the friction there
                                // already exceeds the load.
                                let tiny = f64::from_bits(1);
                                assert!(friction(&n, tiny, theta) * normal + z * tiny >= need, "a {a} θ {theta}");
                                continue;
                            }
                            let load = friction(&n, v, theta) * normal + z * v;
                            let error = (load - need).abs() / need;
                            worst = worst.max(error);
                            assert!(error < 1e-9, "a {a} θ {theta} need {need} Z {z}: V = {v}, load {load}");
                        }
                    }
                }
            }
        }
        assert!(worst < 1e-9, "{worst}");
        // Nothing needed, or not pressed on: no slip.
        assert_eq!(balance(&node(Evolution::Aging), 1.0, 0.0, 1.0, 1e6), 0.0);
        assert_eq!(balance(&node(Evolution::Aging), 1.0, 1.0, 0.0, 1e6), 0.0);
    }

    #[test]
    fn a_node_at_rest_ages_and_the_coefficients_scale_with_the_field() {
        let aging = node(Evolution::Aging);
        assert_eq!(RateState::stuck(&aging, 5.0, 0.5), 5.5);
        assert_eq!(RateState::stuck(&node(Evolution::Slip), 5.0, 0.5), 5.0);
        assert_eq!(RateState::initial_state(&aging, 0.0, 0.0), 0.008 / 1e-9);
        let doubled = RateState::scaled(&aging, 2.0);
        let v = 1e-3;
        assert!((steady_friction(&doubled, v) - 2.0 * steady_friction(&aging, v)).abs() < 1e-12);
        // k_c = (b − a)·N/L; none when velocity strengthening.
        assert!((RateState::critical_stiffness(&aging, 1.0) - 0.005 / 0.008).abs() < 1e-12);
        let strengthening = RateStateNode { b: 0.005, ..aging };
        assert_eq!(RateState::critical_stiffness(&strengthening, 1.0), 0.0);
        // SEAS BP1's Λ₀ at μ = 32.04 GPa, σ = 50 MPa: (9π/32)·μ·L/(bσ) = 300.6 m.
        let zone = RateState::cohesive_zone_m(&aging, 32.04e9, 50e6).unwrap();
        assert!((zone - 9.0 * std::f64::consts::PI / 32.0 * 32.04e9 * 0.008 / (0.015 * 50e6)).abs() < 1e-9);
        assert!((zone - 301.9).abs() < 0.5, "{zone}");
        // h* = (π/2)·μ·b·L/((b − a)²σ) in BP1's velocity-weakening zone (a = 0.010): 4.83 km.
        let h = RateState::nucleation_m(&aging, 32.04e9, 50e6).unwrap();
        assert!((h - std::f64::consts::FRAC_PI_2 * 32.04e9 * 0.015 * 0.008 / (0.005f64.powi(2) * 50e6)).abs() < 1e-6);
        assert!((h - 4831.2).abs() < 1.0, "{h}");
        assert_eq!(RateState::nucleation_m(&strengthening, 32.04e9, 50e6), None);
    }

    #[test]
    fn the_two_pass_step_slides_at_the_rate_its_friction_balances() {
        let n = node(Evolution::Aging);
        let theta = n.theta0_s(0.0, 0.0);
        let (g, dt) = (1e9, 1e-4);
        let trial = Trial { need_n: 0.75, normal_n: 1.0, g_n_m: g, dt_s: dt, slip_per_slide: 2.0 };
        let mu = RateState::kinetic(&n, theta, &trial);
        let (v, predicted) = two_pass(&n, theta, &trial);
        // The slide the contact rule makes with that friction, (need − μN)/g, times the slip per
        // slide over Δt, is V₂.
        let slid = 2.0 * (trial.need_n - mu * trial.normal_n) / g;
        assert!((slid / dt / v - 1.0).abs() < 1e-9, "{} vs {v}", slid / dt);
        assert!(predicted < theta, "a fast slide lowers θ");
        let next = RateState::advance(&n, theta, slid, dt);
        assert!((next / evolve(&n, theta, v, dt) - 1.0).abs() < 1e-9);
    }
}
