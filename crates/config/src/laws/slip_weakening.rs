//! The slip-weakening family in `[friction]` (the default law): `mu_static` alone is the plain
//! Coulomb law; with `mu_dynamic`, static/dynamic friction; with `slip_weakening_m` > 0 too,
//! linear slip weakening over that distance.

use stickslip_solver::laws::{
    Coulomb, FrictionLaw, Law, NodeFriction, SlipWeakening, StaticDynamic, Weakening, WeakeningNode,
};

use super::{FrictionKeys, LawKeys, RegionKeys};
use crate::check::{Checker, num};

/// The family's entry of the table of laws.
pub(super) const KEYS: LawKeys = LawKeys {
    name: "slip_weakening",
    about: "Coulomb, static/dynamic or linear slip weakening, by the keys given",
    solver_law: Weakening::NAME,
    law,
    region,
    strength_keys: super::MU_KEYS,
    grid_refused: None,
    skip_ahead_refused: None,
    zone_refused: false,
};

/// The case the section's keys describe.
fn law(ck: &mut Checker, f: &FrictionKeys) -> FrictionLaw {
    ck.non_negative("friction.mu_static", f.mu_static);
    if f.mu_dynamic.is_some() && f.mu_static.is_finite() {
        ck.range("friction.mu_dynamic", f.mu_dynamic.unwrap_or(0.0), 0.0, false, f.mu_static.max(0.0), false);
    }
    ck.non_negative("friction.slip_weakening_m", f.slip_weakening_m);
    match f.mu_dynamic {
        None => {
            if f.slip_weakening_m > 0.0 {
                ck.push(
                    "friction.slip_weakening_m",
                    f.slip_weakening_m,
                    "0 without friction.mu_dynamic (slip weakening from μs to μd needs μd < μs)",
                );
            }
            Coulomb { mu: f.mu_static }.into()
        }
        Some(mu_dynamic) if f.slip_weakening_m > 0.0 => {
            if !(mu_dynamic < f.mu_static) {
                ck.push(
                    "friction.mu_dynamic",
                    mu_dynamic,
                    format!(
                        "below mu_static ({}) when slip_weakening_m > 0 (otherwise nothing weakens)",
                        num(f.mu_static)
                    ),
                );
            }
            SlipWeakening { mu_static: f.mu_static, mu_dynamic, dc_m: f.slip_weakening_m }.into()
        }
        Some(mu_dynamic) => StaticDynamic { mu_static: f.mu_static, mu_dynamic }.into(),
    }
}

/// A region's μs, μd (its μs when omitted) and Dc (the background's when omitted).
fn region(ck: &mut Checker, field: &str, keys: &RegionKeys, law: &FrictionLaw) -> NodeFriction {
    let (mu_static, mu_dynamic) = super::region_coefficients(ck, field, keys);
    let background = match law.node(1.0) {
        NodeFriction::Weakening(n) => n.weakening_distance_m(),
        _ => 0.0,
    };
    let dc = keys.slip_weakening_m.unwrap_or(background);
    ck.non_negative(&format!("{field}.slip_weakening_m"), dc);
    NodeFriction::Weakening(WeakeningNode::new(mu_static, mu_dynamic, dc))
}
