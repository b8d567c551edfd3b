//! The checks of a selection's inputs: the grid, the target, the candidates and the options, each
//! refused with its name, value and allowed range.

use crate::catalogue::compact;
use crate::error::SeismoError;
use crate::selection::options::{Candidate, SelectionOptions};

pub(super) fn check_inputs(
    periods: &[f64],
    target: &[f64],
    candidates: &[Candidate],
    opts: &SelectionOptions,
) -> Result<(f64, f64, std::ops::Range<usize>), SeismoError> {
    let (t_a, t_b) = opts.range.bounds()?;
    if periods.is_empty() {
        return Err(SeismoError::parameter("periods.len()", 0, "at least one period"));
    }
    for (i, &t) in periods.iter().enumerate() {
        if !(t > 0.0 && t.is_finite()) || (i > 0 && !(t > periods[i - 1])) {
            return Err(SeismoError::parameter(
                format!("periods[{i}]"),
                format!("{t} s"),
                "finite, > 0, strictly increasing",
            ));
        }
    }
    if target.len() != periods.len() {
        return Err(SeismoError::parameter(
            "target.len()",
            target.len(),
            format!("the grid's length {}", periods.len()),
        ));
    }
    if let Some(i) = target.iter().position(|&v| !(v > 0.0 && v.is_finite())) {
        return Err(SeismoError::parameter(format!("target[{i}]"), target[i], "finite and > 0"));
    }
    let (g0, g1) = (periods[0], periods[periods.len() - 1]);
    let eps = 1e-9;
    if t_a < g0 * (1.0 - eps) || t_b > g1 * (1.0 + eps) {
        return Err(SeismoError::parameter(
            "range",
            format!("[{}, {}] s", compact(t_a), compact(t_b)),
            format!(
                "inside the period grid [{}, {}] s, so the rule can be checked over all of it",
                compact(g0),
                compact(g1)
            ),
        ));
    }
    let start = periods.partition_point(|&t| t < t_a * (1.0 - eps));
    let end = periods.partition_point(|&t| t <= t_b * (1.0 + eps));
    if start >= end {
        return Err(SeismoError::parameter(
            "range",
            format!("[{}, {}] s", compact(t_a), compact(t_b)),
            "at least one grid period inside",
        ));
    }
    let positive_int = |name: &str, v: usize| {
        if v == 0 { Err(SeismoError::parameter(name, v, "≥ 1")) } else { Ok(()) }
    };
    positive_int("count", opts.count)?;
    positive_int("per_group", opts.per_group)?;
    positive_int("starts", opts.starts)?;
    if !(opts.scale_min > 0.0 && opts.scale_min <= opts.scale_max && opts.scale_max.is_finite()) {
        return Err(SeismoError::parameter(
            "scale_min, scale_max",
            format!("{}, {}", opts.scale_min, opts.scale_max),
            "0 < scale_min ≤ scale_max, finite",
        ));
    }
    if !(opts.rule_fraction > 0.0 && opts.rule_fraction <= 1.0) {
        return Err(SeismoError::parameter("rule_fraction", opts.rule_fraction, "0 < rule_fraction ≤ 1"));
    }
    if !(opts.spread_weight >= 0.0 && opts.spread_weight.is_finite()) {
        return Err(SeismoError::parameter("spread_weight", opts.spread_weight, "finite, ≥ 0"));
    }
    for (i, c) in candidates.iter().enumerate() {
        if c.psa.len() != periods.len() {
            return Err(SeismoError::parameter(
                format!("candidates[{i}].psa.len()"),
                c.psa.len(),
                format!("the grid's length {}", periods.len()),
            ));
        }
        if !(c.usable_min >= 0.0 && c.usable_min <= c.usable_max) || c.usable_min.is_infinite() {
            return Err(SeismoError::parameter(
                format!("candidates[{i}] usable band"),
                format!("[{}, {}] s", compact(c.usable_min), compact(c.usable_max)),
                "0 ≤ usable_min ≤ usable_max",
            ));
        }
    }
    Ok((t_a, t_b, start..end))
}
