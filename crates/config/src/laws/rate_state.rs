//! Rate-and-state friction in `[friction]` (`law = "rate_state_aging"` or `"rate_state_slip"`):
//! its coefficients in `[friction.rate_state]` (`a`, `b`, `dc_m`, `v0_m_s`, `f0` and one start:
//! `initial_slip_rate_m_s` for steady state at that rate, `initial_state_s`, or
//! `balanced_slip_rate_m_s` for sliding at that rate under a fault's initial traction), refused outside
//! `a > 0`, `b ≥ 0`, `L > 0`, `V₀ > 0`, `0 ≤ f₀ ≤ 10`; the slip-weakening keys, `heals = false`
//! and grid rows are refused with it. A patch gives its own a, b, L or f₀ in
//! `[friction.patches.rate_state]` (the background's where left out); a start at steady state
//! at a slip rate follows the patch's L.

use serde::{Deserialize, Serialize};
use stickslip_solver::laws::{Evolution, FrictionLaw, Law, NodeFriction, RateState, RateStateNode, RateStateStart};

use super::{FrictionKeys, LawKeys, RegionKeys};
use crate::check::{Checker, num};

/// `[friction.rate_state]`: the coefficients of rate-and-state friction.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RateStateSection {
    /// The direct effect a > 0.
    pub a: f64,
    /// The evolution effect b ≥ 0 (velocity weakening where b > a).
    pub b: f64,
    /// The characteristic slip L (m), > 0.
    pub dc_m: f64,
    /// The reference slip rate V₀ (m/s), > 0.
    pub v0_m_s: f64,
    /// The steady-state friction at V₀, f₀ (0–10).
    pub f0: f64,
    /// Start at steady state at this slip rate (m/s, > 0): θ₀ = L/Vᵢ. Exclusive with
    /// `initial_state_s`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_slip_rate_m_s: Option<f64>,
    /// Start from this state θ₀ (s, > 0). Exclusive with the other starts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub initial_state_s: Option<f64>,
    /// Start each fault node sliding at this slip rate (m/s, > 0) in balance with its initial
    /// tractions: θ₀ from `σ·f(Vᵢ, θ₀) = τ` (SCEC TPV101–104's start; on a fault only).
    /// Exclusive with the other starts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub balanced_slip_rate_m_s: Option<f64>,
}

/// `[friction.patches.rate_state]`: a patch's own rate-and-state coefficients, each the
/// background's when left out.
#[derive(Clone, Copy, Debug, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct RateStatePatch {
    /// a > 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub a: Option<f64>,
    /// b ≥ 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b: Option<f64>,
    /// L (m) > 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dc_m: Option<f64>,
    /// f₀ (0–10).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub f0: Option<f64>,
}

/// Why grid rows are refused: they hold the slip-weakening coefficients.
const GRID_REFUSED: &str =
    "its rows give μs, μd and Dc ([friction.rate_state_grid] and patches with a rate_state table give a, b, L and f₀)";

/// Why the skip-ahead is refused.
const SKIP_AHEAD_REFUSED: &str = "false with a rate-and-state law (the skip-ahead predicts the next slide from a static \
     strength; under rate and state every node creeps and its state evolves between slides)";

/// The aging law's entry of the table of laws.
pub(super) const AGING: LawKeys = LawKeys {
    name: "rate_state_aging",
    about: "rate-and-state friction, aging law, coefficients in [friction.rate_state]",
    solver_law: RateState::NAME,
    law: aging,
    region,
    strength_keys: ["friction.rate_state.f0", "friction.rate_state.b, friction.rate_state.a"],
    grid_refused: Some(GRID_REFUSED),
    skip_ahead_refused: Some(SKIP_AHEAD_REFUSED),
    zone_refused: true,
};

/// The slip law's entry of the table of laws.
pub(super) const SLIP: LawKeys = LawKeys {
    name: "rate_state_slip",
    about: "rate-and-state friction, slip law, coefficients in [friction.rate_state]",
    solver_law: RateState::NAME,
    law: slip,
    region,
    strength_keys: ["friction.rate_state.f0", "friction.rate_state.b, friction.rate_state.a"],
    grid_refused: Some(GRID_REFUSED),
    skip_ahead_refused: Some(SKIP_AHEAD_REFUSED),
    zone_refused: true,
};

fn aging(ck: &mut Checker, f: &FrictionKeys) -> FrictionLaw {
    law(ck, f, Evolution::Aging, AGING.name)
}

fn slip(ck: &mut Checker, f: &FrictionKeys) -> FrictionLaw {
    law(ck, f, Evolution::Slip, SLIP.name)
}

fn law(ck: &mut Checker, f: &FrictionKeys, evolution: Evolution, name: &str) -> FrictionLaw {
    if let Some(mu_dynamic) = f.mu_dynamic {
        ck.push(
            "friction.mu_dynamic",
            mu_dynamic,
            format!("left out with law = {name:?} (its friction comes from [friction.rate_state])"),
        );
    }
    if f.slip_weakening_m != 0.0 {
        ck.push(
            "friction.slip_weakening_m",
            f.slip_weakening_m,
            format!("left out with law = {name:?} (its characteristic slip is friction.rate_state.dc_m)"),
        );
    }
    if !f.heals {
        ck.push(
            "friction.heals",
            "false",
            format!("left out with law = {name:?} (the state variable heals by its own evolution law)"),
        );
    }
    let Some(r) = f.rate_state else {
        ck.push(
            "friction.rate_state",
            "none",
            format!("a section [friction.rate_state] with a, b, dc_m, v0_m_s, f0 and a start with law = {name:?}"),
        );
        let start = RateStateStart::SteadyAt(1e-6);
        return RateStateNode { a: 0.01, b: 0.0, dc_m: 1.0, v0_m_s: 1e-6, f0: 0.6, evolution, start }.into();
    };
    ck.range("friction.rate_state.a", r.a, 0.0, true, 1.0, false);
    ck.range("friction.rate_state.b", r.b, 0.0, false, 1.0, false);
    ck.positive("friction.rate_state.dc_m", r.dc_m);
    ck.positive("friction.rate_state.v0_m_s", r.v0_m_s);
    ck.range("friction.rate_state.f0", r.f0, 0.0, false, 10.0, false);
    let given = [r.initial_slip_rate_m_s, r.initial_state_s, r.balanced_slip_rate_m_s];
    let keys = ["initial_slip_rate_m_s", "initial_state_s", "balanced_slip_rate_m_s"];
    if given.iter().flatten().count() > 1 {
        let (k, v) = (1..3).find_map(|k| given[k].map(|v| (k, v))).expect("a second start");
        ck.push(
            format!("friction.rate_state.{}", keys[k]),
            num(v),
            "left out with another start: one of initial_slip_rate_m_s (steady state at that rate), \
             initial_state_s (θ₀) or balanced_slip_rate_m_s (sliding at that rate under the initial traction)",
        );
    }
    let start = match given {
        [Some(v), ..] => {
            ck.positive("friction.rate_state.initial_slip_rate_m_s", v);
            RateStateStart::SteadyAt(v)
        }
        [None, Some(theta), _] => {
            ck.positive("friction.rate_state.initial_state_s", theta);
            RateStateStart::State(theta)
        }
        [None, None, Some(v)] => {
            ck.positive("friction.rate_state.balanced_slip_rate_m_s", v);
            RateStateStart::Balanced(v)
        }
        [None, None, None] => {
            ck.push(
                "friction.rate_state.initial_slip_rate_m_s",
                "none",
                "a start: initial_slip_rate_m_s (steady state at that rate, m/s), initial_state_s (θ₀, s) or \
                 balanced_slip_rate_m_s (sliding at that rate under the initial traction, m/s)",
            );
            RateStateStart::SteadyAt(1e-6)
        }
    };
    let law: FrictionLaw =
        RateStateNode { a: r.a, b: r.b, dc_m: r.dc_m, v0_m_s: r.v0_m_s, f0: r.f0, evolution, start }.into();
    let theta0 = law.node(1.0).coefficients().iter().find(|c| c.symbol == "θ₀").map_or(1.0, |c| c.value);
    if !(theta0.is_finite() && theta0 > 0.0) && ck.is_clean() {
        ck.push("friction.rate_state.initial_slip_rate_m_s", theta0, "a start whose state θ₀ = L/Vᵢ is finite and > 0");
    }
    law
}

/// A patch's coefficients: the background's, with those of its `rate_state` table; the
/// slip-weakening keys are refused.
fn region(ck: &mut Checker, field: &str, keys: &RegionKeys, law: &FrictionLaw) -> NodeFriction {
    let NodeFriction::RateState(background) = law.node(1.0) else { unreachable!("the law's own background") };
    for (key, given) in
        [("mu_static", keys.mu_static), ("mu_dynamic", keys.mu_dynamic), ("slip_weakening_m", keys.slip_weakening_m)]
    {
        if let Some(v) = given {
            ck.push(
                format!("{field}.{key}"),
                num(v),
                format!("left out with law = {:?} (a patch gives a, b, dc_m or f0 in its rate_state table)", law.name),
            );
        }
    }
    let Some(r) = keys.rate_state else {
        ck.push(
            format!("{field}.rate_state"),
            "none",
            format!("a table [friction.patches.rate_state] with a, b, dc_m or f0 with law = {:?}", law.name),
        );
        return NodeFriction::RateState(background);
    };
    let node = RateStateNode {
        a: r.a.unwrap_or(background.a),
        b: r.b.unwrap_or(background.b),
        dc_m: r.dc_m.unwrap_or(background.dc_m),
        f0: r.f0.unwrap_or(background.f0),
        ..background
    };
    ck.range(&format!("{field}.rate_state.a"), node.a, 0.0, true, 1.0, false);
    ck.range(&format!("{field}.rate_state.b"), node.b, 0.0, false, 1.0, false);
    ck.positive(&format!("{field}.rate_state.dc_m"), node.dc_m);
    ck.range(&format!("{field}.rate_state.f0"), node.f0, 0.0, false, 10.0, false);
    NodeFriction::RateState(node)
}
