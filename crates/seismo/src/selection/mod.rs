//! Record-set selection: N scaled records whose mean spectrum matches a target over a period range.
//!
//! **Input.** Candidates, each with an id, a group key (records of one group — e.g. one seed and
//! event — are correlated, so at most `per_group` of them are chosen), its PSA on a period grid
//! common to all candidates and the target (all at one damping, which is not checked), and its
//! usable band (lowest and highest usable period, e.g. from the filter corners: `1/f_high …
//! 1/f_low` or narrower). A record is **eligible** only if its usable band covers the whole
//! period range `[T_a, T_b]`.
//!
//! **Period range.** Given directly, or from the structure's fundamental period `T_1` as
//! `[0.2·T_1, 2·T_1]`: ASCE 7-16 §16.2.1 asks for a range whose lower bound is at most 20% of
//! the smallest first-mode period and whose upper bound is at least twice the largest, and §16.2.3
//! (amplitude scaling) asks that the average of the suite's spectra is not below 90% of the target
//! anywhere in that range; ASCE 7-16 §16.2.2 asks for at least 11 ground motions (default N = 11).
//! EN 1998-1 §3.2.3.1.2(4) asks, for recorded or artificial accelerograms, for at least 3 of them,
//! a mean zero-period spectral value not below `a_g·S`, and, in the range `0.2·T_1 … 2·T_1`, no
//! value of the mean 5%-damped elastic spectrum below 90% of the elastic response spectrum.
//! The zero-period (PGA) check of EC8 is not done here (the grid need not hold T = 0).
//!
//! **Scale factors.** Each record's own least-squares factor in log space over the `M` grid
//! periods inside the range, `ln s_i = mean_T (ln S_target(T) − ln S_i(T))`, clamped to
//! `[s_min, s_max]`. Its log residual is `r_i(T) = ln s_i + ln S_i(T) − ln S_target(T)` and its
//! misfit `e_i = mean_T r_i(T)²`.
//!
//! **Objective** (to minimise) of a set `S` of N records:
//! `J(S) = mean_T (mean_{i∈S} r_i(T))² + w·mean_{i∈S} e_i` — the mean squared log residual of the
//! set's mean log-spectrum (geometric mean) against the target, plus `w` (`spread_weight`, default
//! 0.1) times the records' own misfits, which keeps records that only cancel each other's
//! departures from being preferred over records that are each close to the target (compare the
//! mean-and-variance matching of Jayaram, Lin & Baker 2011). `w = 0` minimises the mean's misfit
//! alone.
//!
//! **Algorithm.** (1) eligibility by band, and checks that enough records and groups remain;
//! (2) a necessary check of the 90% rule: at every range period, the N largest `s_max·S_i(T)`
//! allowed by the group caps must reach 90% of the target, otherwise no choice can;
//! (3) greedy forward selection: N times, add the eligible record (group cap respected) that
//! gives the lowest `J`; (4) best-improvement swaps: replace one chosen record by one not chosen
//! (cap respected) while `J` decreases, at most `max_swap_passes` passes. Steps (3)–(4) run from
//! `starts` starts (default 8; start k forces the record with the k-th smallest own misfit in
//! first) and the set kept is the lowest-`J` one among those that step (5) can bring to the rule
//! (the lowest-`J` of all if none can); (5) the code rule on the
//! **arithmetic** mean (as ASCE 7-16 and EC8 write it), `ρ(T) = mean_i s_i·S_i(T) / S_target(T)`:
//! if `min_T ρ < 0.9`, all factors are multiplied by the smallest common `f > 1` that lifts
//! `min_T ρ` to 0.9 (to `0.9·(1+1e-9)`), each capped at `s_max` (found by bisection; `min_T ρ` is
//! non-decreasing in `f`); (6) if even all chosen records at `s_max` fall short, swaps again with
//! the objective `J + 10⁴·max(0, ln 0.9 − ln h)²`, `h = s_max·min_T mean_i S_i(T)/S_target(T)`,
//! then (5) once more; if that fails the selection is refused.
//!
//! **Cost**, with C candidates, E eligible, P grid periods, M of them in the range, G groups:
//! eligibility and scales `O(C·P)`; the necessary check `O(M·E·log E)`; greedy `O(N·E·M)`; each
//! swap pass `O(N·E·M)` (the sum of the chosen residuals is kept, so a trial swap costs `O(M)`);
//! the scale-up `O(60·N·M)`; all of (3)–(4) times `starts`. Memory `O(E·M)`. Greedy-with-swaps
//! finds a set that no single swap improves; it is not guaranteed to be the global optimum of this
//! combinatorial problem (test: on 37 of 40 random 3-of-10 problems it is, with 8 starts; 15 of 40
//! with 1 start; the worst J found is 1.9× the optimum).
//!
//! Refusals ([`Refusal`], inside [`SeismoError::Selection`]) say which rule cannot be met: too few
//! records whose band covers the range, too few groups for the cap, or the scale bound `s_max`
//! too low for the 90% rule (with the period where it fails), or — when the necessary check passes
//! but the search found no passing set — the best ratio the search reached.

mod inputs;
mod options;
mod pool;
mod search;
#[cfg(test)]
mod tests;

use std::collections::HashMap;

use crate::error::SeismoError;
use inputs::check_inputs;
pub use options::{Candidate, Chosen, PeriodRange, Selection, SelectionOptions};
use pool::{Pool, SetState, evaluate};
use search::{common_scale_up, swap_search};

pub use crate::error::Refusal;

fn refuse(r: Refusal) -> SeismoError {
    SeismoError::Selection(r)
}

/// Weight of the rule's penalty in the repair swaps.
const RULE_PENALTY: f64 = 1e4;

/// Selects `opts.count` records from `candidates` (PSA on `periods`, s) to match `target` as the
/// module doc describes.
pub fn select(
    periods: &[f64],
    target: &[f64],
    candidates: &[Candidate],
    opts: &SelectionOptions,
) -> Result<Selection, SeismoError> {
    let (t_a, t_b, range) = check_inputs(periods, target, candidates, opts)?;
    let eps = 1e-9;
    let n = opts.count;

    // (1) Eligibility.
    let eligible: Vec<usize> = candidates
        .iter()
        .enumerate()
        .filter(|(_, c)| c.usable_min <= t_a * (1.0 + eps) && c.usable_max >= t_b * (1.0 - eps))
        .map(|(i, _)| i)
        .collect();
    if eligible.len() < n {
        return Err(refuse(Refusal::TooFewEligible {
            needed: n,
            eligible: eligible.len(),
            candidates: candidates.len(),
            t_a,
            t_b,
        }));
    }
    let mut group_ids: HashMap<&str, usize> = HashMap::new();
    let mut group_of = Vec::with_capacity(eligible.len());
    for &i in &eligible {
        let next = group_ids.len();
        group_of.push(*group_ids.entry(candidates[i].group.as_str()).or_insert(next));
    }
    let groups = group_ids.len();
    let mut group_sizes = vec![0usize; groups];
    for &g in &group_of {
        group_sizes[g] += 1;
    }
    let capacity: usize = group_sizes.iter().map(|&s| s.min(opts.per_group)).sum();
    if capacity < n {
        return Err(refuse(Refusal::TooFewGroups {
            needed: n,
            eligible: eligible.len(),
            groups,
            per_group: opts.per_group,
            capacity,
        }));
    }

    // Residuals and scales over the range.
    let m = range.len();
    let ln_target: Vec<f64> = target[range.clone()].iter().map(|v| v.ln()).collect();
    let (ln_lo, ln_hi) = (opts.scale_min.ln(), opts.scale_max.ln());
    let mut pool = Pool {
        m,
        index: eligible.clone(),
        group: group_of,
        resid: Vec::with_capacity(eligible.len() * m),
        misfit: Vec::with_capacity(eligible.len()),
        scale: Vec::with_capacity(eligible.len()),
        ratio: Vec::with_capacity(eligible.len() * m),
        candidates,
    };
    for &i in &eligible {
        let psa = &candidates[i].psa[range.clone()];
        if let Some(j) = psa.iter().position(|&v| !(v > 0.0 && v.is_finite())) {
            return Err(SeismoError::parameter(
                format!("candidates[{i}].psa[{}]", range.start + j),
                psa[j],
                "finite and > 0 inside the period range",
            ));
        }
        let ln_s = (ln_target.iter().zip(psa).map(|(t, v)| t - v.ln()).sum::<f64>() / m as f64).clamp(ln_lo, ln_hi);
        let mut e = 0.0;
        for (t, v) in ln_target.iter().zip(psa) {
            let r = ln_s + v.ln() - t;
            pool.resid.push(r);
            e += r * r;
        }
        pool.misfit.push(e / m as f64);
        pool.scale.push(ln_s.exp());
        for (v, tg) in psa.iter().zip(&target[range.clone()]) {
            pool.ratio.push(v / tg);
        }
    }

    // (2) Necessary check of the rule: the N largest s_max·S_i(T) under the group caps.
    let mut column: Vec<(f64, usize)> = Vec::with_capacity(eligible.len());
    let mut taken = vec![0usize; groups];
    for t in 0..m {
        column.clear();
        column.extend((0..eligible.len()).map(|e| (pool.ratio(e)[t], pool.group[e])));
        column.sort_by(|a, b| b.0.total_cmp(&a.0));
        taken.iter_mut().for_each(|c| *c = 0);
        let (mut sum, mut count) = (0.0, 0);
        for &(q, g) in &column {
            if count == n {
                break;
            }
            if taken[g] < opts.per_group {
                taken[g] += 1;
                sum += q;
                count += 1;
            }
        }
        let best = opts.scale_max * sum / n as f64;
        if best < opts.rule_fraction {
            return Err(refuse(Refusal::ScaleBounds {
                needed: n,
                period: periods[range.start + t],
                best_ratio: best,
                scale_max: opts.scale_max,
                rule_fraction: opts.rule_fraction,
            }));
        }
    }

    // (3)–(4) Greedy with swaps from several starts; keep the lowest J among the sets a capped
    // common scale-up can bring to the rule, or the lowest J of all if none can.
    let mut order: Vec<usize> = (0..eligible.len()).collect();
    order.sort_by(|&a, &b| pool.misfit[a].total_cmp(&pool.misfit[b]));
    let mut best: Option<(bool, f64, SetState)> = None;
    for &first in order.iter().take(opts.starts) {
        let mut st = SetState::new(&pool, groups);
        st.add(&pool, first);
        for step in 1..n {
            let mut pick: Option<(usize, f64)> = None;
            for e in 0..eligible.len() {
                if st.in_set[e] || st.per_group[pool.group[e]] >= opts.per_group {
                    continue;
                }
                let (j, _) = evaluate(&pool, &st, step + 1, None, Some(e), opts.spread_weight);
                if pick.is_none_or(|b| j < b.1) {
                    pick = Some((e, j));
                }
            }
            // Capacity ≥ N was checked, so a record is always available here.
            let Some((e, _)) = pick else { break };
            st.add(&pool, e);
        }
        swap_search(&pool, &mut st, opts, 0.0);
        let (j, q) = evaluate(&pool, &st, n, None, None, opts.spread_weight);
        let liftable = opts.scale_max * q >= opts.rule_fraction * (1.0 + 1e-9);
        if best.as_ref().is_none_or(|(l, bj, _)| (liftable, -j) > (*l, -*bj)) {
            best = Some((liftable, j, st));
        }
    }
    let Some((_, _, mut st)) = best else {
        return Err(SeismoError::parameter("starts", opts.starts, "≥ 1"));
    };
    // (5) Rule, with a common scale-up; (6) repair swaps if needed.
    let target_ratio = opts.rule_fraction * (1.0 + 1e-9);
    let mut factor = common_scale_up(&pool, &st.chosen, opts, target_ratio);
    if factor.is_none() {
        swap_search(&pool, &mut st, opts, RULE_PENALTY);
        factor = common_scale_up(&pool, &st.chosen, opts, target_ratio);
    }
    let Some(factor) = factor else {
        let (mut worst, mut at) = (f64::INFINITY, 0);
        for t in 0..m {
            let v = st.sum_ratio[t] / n as f64;
            if v < worst {
                (worst, at) = (v, t);
            }
        }
        return Err(refuse(Refusal::NotFound {
            best_ratio: opts.scale_max * worst,
            period: periods[range.start + at],
            scale_max: opts.scale_max,
            rule_fraction: opts.rule_fraction,
        }));
    };
    Ok(finish(&pool, &st, periods, target, opts, (t_a, t_b), range, factor))
}

#[allow(clippy::too_many_arguments)]
fn finish(
    pool: &Pool,
    st: &SetState,
    periods: &[f64],
    target: &[f64],
    opts: &SelectionOptions,
    bounds: (f64, f64),
    range: std::ops::Range<usize>,
    factor: f64,
) -> Selection {
    let n = st.chosen.len() as f64;
    let m = pool.m;
    let ln_target: Vec<f64> = target[range.clone()].iter().map(|v| v.ln()).collect();
    let mut mean = vec![0.0; periods.len()];
    let mut mean_resid = vec![0.0; m];
    let mut records = Vec::with_capacity(st.chosen.len());
    let mut spread = 0.0;
    for &e in &st.chosen {
        let c = &pool.candidates[pool.index[e]];
        let scale = (pool.scale[e] * factor).min(opts.scale_max);
        for (acc, v) in mean.iter_mut().zip(&c.psa) {
            *acc += scale * v / n;
        }
        let mut misfit = 0.0;
        for (t, (v, lt)) in c.psa[range.clone()].iter().zip(&ln_target).enumerate() {
            let r = scale.ln() + v.ln() - lt;
            mean_resid[t] += r / n;
            misfit += r * r / m as f64;
        }
        spread += misfit / n;
        records.push(Chosen { index: pool.index[e], id: c.id.clone(), group: c.group.clone(), scale, misfit });
    }
    let (mut min_ratio, mut at) = (f64::INFINITY, range.start);
    for i in range.clone() {
        let r = mean[i] / target[i];
        if r < min_ratio {
            (min_ratio, at) = (r, i);
        }
    }
    let mean_log_misfit = mean_resid.iter().map(|r| r * r).sum::<f64>() / m as f64;
    Selection {
        records,
        range: bounds,
        range_indices: range,
        mean,
        min_ratio,
        min_ratio_period: periods[at],
        mean_log_misfit,
        objective: mean_log_misfit + opts.spread_weight * spread,
        common_scale: factor,
        eligible: pool.index.len(),
    }
}
