//! The two searches over the pool: best-improvement swaps, and the smallest common scale-up that
//! meets the rule.

use crate::selection::options::SelectionOptions;
use crate::selection::pool::{Pool, SetState, evaluate};

/// Best-improvement swaps on `J + penalty·max(0, ln φ − ln(s_max·min ratio))²`.
pub(super) fn swap_search(pool: &Pool, st: &mut SetState, opts: &SelectionOptions, penalty: f64) {
    let n = st.chosen.len();
    let (w, cap) = (opts.spread_weight, opts.per_group);
    let ln_rule = opts.rule_fraction.ln();
    let score = |(j, q): (f64, f64)| {
        if penalty == 0.0 {
            return j;
        }
        let short = (ln_rule - (opts.scale_max * q).ln()).max(0.0);
        j + penalty * short * short
    };
    let mut current = score(evaluate(pool, st, n, None, None, w));
    for _ in 0..opts.max_swap_passes {
        let mut best: Option<(usize, usize, f64)> = None;
        for pos in 0..n {
            let out = st.chosen[pos];
            for e in 0..pool.index.len() {
                if st.in_set[e] || (pool.group[e] != pool.group[out] && st.per_group[pool.group[e]] >= cap) {
                    continue;
                }
                let s = score(evaluate(pool, st, n, Some(out), Some(e), w));
                if s < best.map_or(current, |b| b.2) - 1e-14 * current.abs().max(1e-300) {
                    best = Some((pos, e, s));
                }
            }
        }
        match best {
            Some((pos, e, s)) => {
                st.swap(pool, pos, e);
                current = s;
            }
            None => break,
        }
    }
}

/// Smallest common factor `f ≥ 1` (each scale capped at `s_max`) with `min_T ρ ≥ target_ratio`,
/// or `None` if even all at `s_max` fall short.
pub(super) fn common_scale_up(
    pool: &Pool,
    chosen: &[usize],
    opts: &SelectionOptions,
    target_ratio: f64,
) -> Option<f64> {
    let m = pool.m;
    let n = chosen.len() as f64;
    let min_ratio = |f: f64| -> f64 {
        let mut worst = f64::INFINITY;
        for t in 0..m {
            let mut sum = 0.0;
            for &e in chosen {
                sum += (pool.scale[e] * f).min(opts.scale_max) * pool.ratio(e)[t];
            }
            worst = worst.min(sum / n);
        }
        worst
    };
    if min_ratio(1.0) >= target_ratio {
        return Some(1.0);
    }
    let smallest = chosen.iter().map(|&e| pool.scale[e]).fold(f64::INFINITY, f64::min);
    let mut hi = opts.scale_max / smallest;
    if min_ratio(hi) < target_ratio {
        return None;
    }
    let mut lo = 1.0;
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if min_ratio(mid) >= target_ratio {
            hi = mid
        } else {
            lo = mid
        }
        if hi - lo <= 1e-13 * hi {
            break;
        }
    }
    Some(hi)
}
