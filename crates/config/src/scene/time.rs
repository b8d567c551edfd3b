//! `[time]` and `[skip_ahead]` checked: the time step, and the skip-ahead through quiet phases.

use stickslip_solver::scene::{SkipAhead, TimeStep};

use stickslip_solver::error::MAX_STEPS;

use super::{RecordSection, SAFE_DT_FRACTION, SelfWeightSection, ShearSection, SkipAheadSection, TimeSection};
use crate::check::{Checker, approx};

/// The time step of `[time]`.
pub(super) fn time_step(ck: &mut Checker, t: &TimeSection) -> TimeStep {
    match (t.dt_fraction, t.dt_s) {
        (Some(_), Some(_)) => {
            ck.push("time", "both dt_fraction and dt_s", "one of time.dt_fraction or time.dt_s");
            TimeStep::Fraction(0.5)
        }
        (None, Some(dt)) => {
            ck.positive("time.dt_s", dt);
            TimeStep::Fixed(dt)
        }
        (fraction, None) => {
            let fr = fraction.unwrap_or(0.5);
            if t.force {
                ck.range("time.dt_fraction", fr, 0.0, true, 1.0, false);
            } else if ck.range("time.dt_fraction", fr, 0.0, true, 1.0, false) && fr > SAFE_DT_FRACTION {
                ck.push(
                    "time.dt_fraction",
                    fr,
                    format!(
                        "0 < dt_fraction ≤ {SAFE_DT_FRACTION} (a step at the stability limit has no margin for \
                         round-off; time.force = true accepts up to 1)"
                    ),
                );
            }
            TimeStep::Fraction(fr)
        }
    }
}

/// Refuses a fixed `time.dt_s` that would make a stage take more steps than the run can count
/// (more than 2^53; the solver refuses the same of a step given as a fraction, once the critical
/// step of each seed is known).
pub(super) fn check_step_count(ck: &mut Checker, t: &TimeSection, sh: &ShearSection, sw: &SelfWeightSection) {
    let (None, Some(dt)) = (t.dt_fraction, t.dt_s) else { return };
    if !(dt > 0.0 && dt.is_finite()) {
        return;
    }
    for (field, duration) in [("shear.duration_s", sh.duration_s), ("self_weight.max_duration_s", sw.max_duration_s)] {
        if duration > 0.0 && duration / dt > MAX_STEPS {
            ck.push(
                "time.dt_s",
                dt,
                format!(
                    "a step that covers {field} = {} s in at most 2^53 steps (the most a run can count): \
                     dt_s ≥ {} s",
                    approx(duration),
                    approx(duration / MAX_STEPS)
                ),
            );
            return;
        }
    }
}

/// The skip-ahead of `[skip_ahead]`, its sampling interval checked against `record.interval_s`.
pub(super) fn skip_ahead(ck: &mut Checker, sk: &SkipAheadSection, r: &RecordSection) -> SkipAhead {
    ck.range("skip_ahead.tolerance", sk.tolerance, 0.0, true, 0.5, false);
    ck.count("skip_ahead.margin_steps", sk.margin_steps, 1, 1_000_000, "");
    if let Some(iv) = sk.record_interval_s {
        match r.interval_s {
            Some(base) if base > 0.0 => {
                ck.range("skip_ahead.record_interval_s", iv, base, false, f64::INFINITY, true);
            }
            _ => {
                ck.push(
                    "skip_ahead.record_interval_s",
                    iv,
                    "only with record.interval_s set (a multiple of it, ≥ record.interval_s)",
                );
            }
        }
    }
    SkipAhead {
        enabled: sk.enabled,
        tolerance: sk.tolerance,
        margin_steps: sk.margin_steps.max(1) as u64,
        record_interval_s: sk.record_interval_s,
    }
}

/// What [`refuse_skip_ahead_with`] says of `[rupture]`.
pub(super) const WITH_RUPTURE: &str =
    "false with [rupture] (the skip-ahead follows the linear elastic motion; a bar past its peak is not linear)";

/// What [`refuse_skip_ahead_with`] says of `friction.heals = false`.
pub(super) const WITH_KEPT_SLIP: &str = "false with friction.heals = false (the skip-ahead predicts the next slide from μs; a node that keeps its slip holds \
     less)";

/// What [`refuse_skip_ahead_with`] says of `[loading_plate]`.
pub(super) const WITH_PLATE: &str =
    "false with [loading_plate] (the skip-ahead's quasi-static motion does not include the plate's springs yet)";

/// Refuses an enabled skip-ahead when a section its quasi-static motion leaves out is `present`,
/// saying `allowed` ([`WITH_RUPTURE`], [`WITH_PLATE`]).
pub(super) fn refuse_skip_ahead_with(ck: &mut Checker, sk: &SkipAheadSection, present: bool, allowed: &str) {
    if present && sk.enabled {
        ck.push("skip_ahead.enabled", "true", allowed);
    }
}
