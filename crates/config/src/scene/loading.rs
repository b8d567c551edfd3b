//! `[self_weight]` and `[shear]` checked: the two loading stages (the shear's drivers are a
//! boundary: `boundaries::drivers`).

use stickslip_solver::scene::{SelfWeight, SettleMethod, Shear};

use super::{MaterialSection, SelfWeightSection, ShearSection};
use crate::check::Checker;

/// The self-weight stage of `[self_weight]`.
pub(super) fn self_weight(ck: &mut Checker, s: &SelfWeightSection) -> SelfWeight {
    ck.non_negative("self_weight.gravity_m_s2", s.gravity_m_s2);
    let method = ck.named::<SettleMethod>("self_weight.method", &s.method).unwrap_or_default();
    ck.non_negative("self_weight.damping_per_s", s.damping_per_s);
    ck.range("self_weight.settle_tolerance", s.settle_tolerance, 0.0, true, 1.0, true);
    ck.positive("self_weight.max_duration_s", s.max_duration_s);
    SelfWeight {
        gravity_m_s2: s.gravity_m_s2,
        method,
        damping_per_s: s.damping_per_s,
        settle_tolerance: s.settle_tolerance,
        max_duration_s: s.max_duration_s,
    }
}

/// Checks the numbers of `[shear]`: the driver's speed against a fraction of the wave speed of
/// `[material]`.
pub(super) fn check_shear(ck: &mut Checker, sh: &ShearSection, m: &MaterialSection) {
    ck.non_negative("shear.damping_per_s", sh.damping_per_s);
    ck.non_negative("shear.rise_time_s", sh.rise_time_s);
    ck.positive("shear.duration_s", sh.duration_s);
    // A driver at rest loads nothing: the shear stage would only ring down (refused rather than
    // run to a catalogue that is empty for no visible reason). A driver faster than a fraction of
    // the wave speed is outside the model's reach (the bound is left to the material's own
    // refusal when the material gives no wave speed).
    let cp_bound = 0.01 * (m.young_pa / m.density_kg_m3).sqrt();
    if ck.positive("shear.velocity_m_s", sh.velocity_m_s) && cp_bound.is_normal() && cp_bound > 0.0 {
        ck.range("shear.velocity_m_s", sh.velocity_m_s, 0.0, true, cp_bound, false);
    }
}

/// The shear stage of `[shear]` with its checked `drivers`.
pub(super) fn shear(sh: &ShearSection) -> Shear {
    Shear {
        damping_per_s: sh.damping_per_s,
        velocity_m_s: sh.velocity_m_s,
        rise_time_s: sh.rise_time_s,
        duration_s: sh.duration_s,
    }
}
