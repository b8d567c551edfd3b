//! Exponential slip weakening in `[friction]` (`law = "exponential_weakening"`): μ falls from
//! `mu_static` towards `mu_dynamic` as `exp(−slip/slip_weakening_m)`; both are required, with
//! `mu_dynamic` below `mu_static` and `slip_weakening_m` above 0 (otherwise it is a case of the
//! slip-weakening family, which says so).

use stickslip_solver::laws::{Exponential, ExponentialNode, ExponentialWeakening, FrictionLaw, Law, NodeFriction};

use super::{FrictionKeys, LawKeys, RegionKeys};
use crate::check::{Checker, num};

/// The law's entry of the table of laws.
pub(super) const KEYS: LawKeys = LawKeys {
    name: "exponential_weakening",
    about: "μ falls from mu_static towards mu_dynamic as exp(−slip/slip_weakening_m)",
    solver_law: Exponential::NAME,
    law,
    region,
    strength_keys: super::MU_KEYS,
    grid_refused: None,
    skip_ahead_refused: None,
    zone_refused: false,
};

fn law(ck: &mut Checker, f: &FrictionKeys) -> FrictionLaw {
    ck.non_negative("friction.mu_static", f.mu_static);
    let Some(mu_dynamic) = f.mu_dynamic else {
        ck.push(
            "friction.mu_dynamic",
            "none",
            "a value below mu_static with law = \"exponential_weakening\" (the level μ weakens towards)",
        );
        return ExponentialWeakening { mu_static: f.mu_static, mu_dynamic: f.mu_static, dc_m: 1.0 }.into();
    };
    if !(mu_dynamic >= 0.0 && mu_dynamic < f.mu_static) {
        ck.push(
            "friction.mu_dynamic",
            mu_dynamic,
            format!("0 ≤ mu_dynamic < mu_static ({}) with law = \"exponential_weakening\"", num(f.mu_static)),
        );
    }
    if !(f.slip_weakening_m > 0.0 && f.slip_weakening_m.is_finite()) {
        ck.push(
            "friction.slip_weakening_m",
            f.slip_weakening_m,
            "a finite distance > 0 m with law = \"exponential_weakening\" (without one μ drops at once: \
             leave out law for static/dynamic friction)",
        );
    }
    ExponentialWeakening { mu_static: f.mu_static, mu_dynamic, dc_m: f.slip_weakening_m }.into()
}

/// A region's μs, μd (its μs when omitted) and Dc (the background's when omitted, > 0).
fn region(ck: &mut Checker, field: &str, keys: &RegionKeys, law: &FrictionLaw) -> NodeFriction {
    let (mu_static, mu_dynamic) = super::region_coefficients(ck, field, keys);
    let background = law.node(1.0).coefficients().iter().find(|c| c.symbol == "Dc").map_or(0.0, |c| c.value);
    let dc = keys.slip_weakening_m.unwrap_or(background);
    if !(dc > 0.0 && dc.is_finite()) {
        ck.push(format!("{field}.slip_weakening_m"), dc, "a finite distance > 0 m under exponential weakening");
    }
    NodeFriction::Exponential(ExponentialNode::new(mu_static, mu_dynamic, dc))
}
