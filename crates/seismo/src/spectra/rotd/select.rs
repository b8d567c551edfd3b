//! RotD50 and RotD100 from the angles they depend on only (see the module above): each angle's
//! interval from the kept steps, and the exact solves of the angles whose interval meets the range
//! of the middle or largest peak.

use super::{ANGLES, Free, Reach, Step};
use crate::spectra::oscillator::Oscillator;

/// The fraction of the largest `|P|` at the samples below which RotD50 cannot be: any angle
/// within 45.5° of P's direction sees at least `cos 45.5°·|P|`, and a closed arc of 91° holds 91 of
/// the 180 angles, so the 91st largest (the 90th smallest) peak is at least that; a relative
/// margin ([`BELOW`]) covers the roundings of the projections and of the bounds compared with it.
const MEDIAN_BELOW: f64 = 0.700_909_264_299_851 * BELOW;

/// What a lower bound of the 90th smallest peak is multiplied by before steps below it are left
/// out: a relative margin of 1e-6 for the roundings.
const BELOW: f64 = 1.0 - 1e-6;

/// A value below the 90th smallest of the 180 peaks of an oscillator whose largest `|P|²` at the
/// samples is `p2`: what no step below it can change of RotD50 and RotD100.
pub(super) fn median_floor(p2: f64) -> f64 {
    MEDIAN_BELOW * p2.sqrt()
}

/// Below the 90th smallest of the peaks `pk` by [`BELOW`]: what no step below it can change of
/// RotD50 and RotD100.
pub(super) fn below_middle(pk: &[f64], work: &mut Vec<f64>) -> f64 {
    middle(pk, work).0 * BELOW
}

/// Work arrays of [`select`].
#[derive(Default)]
pub(super) struct Selection {
    lower: Vec<f64>,
    upper: Vec<f64>,
    solved: Vec<bool>,
    pending: Vec<usize>,
    pub(super) work: Vec<f64>,
}

/// Angles whose upper bounds a step computes together when one of them may rise (see
/// [`Step::raise_bounds`]): 15 groups of 12, side by side.
const GROUP: usize = 12;
const _: () = assert!(ANGLES.is_multiple_of(GROUP));

/// Solves the angles RotD50 and RotD100 depend on, and no other: `pk` holds each angle's peak
/// at the samples (a lower bound, complete above `floor`), the kept steps give each angle a
/// tighter lower bound and, with the free vibration, an upper bound, and an angle is solved
/// exactly while its interval `[lower, upper]` meets the range `[L, U]` where the 90th…91st
/// smallest, or the largest, peak may lie (`L` from the lower bounds, `U` from the upper ones).
/// When no interval of an unsolved angle meets them, each unsolved angle lies wholly below or
/// above them, so `L` and `U` are values of solved angles and equal: the 90th, 91st and largest of
/// the lower bounds are the exact ones, and the largest is reached first at a solved angle.
/// Nothing below `floor` was looked at, and `floor` is below the 90th smallest peak: every upper
/// bound is at least `floor`, which keeps what was not looked at on its side of the middle values.
///
/// A solved angle goes through the same exact step solves, in step order, as with every angle,
/// but may start from a lower peak at the samples (steps and samples below `floor` are not looked
/// at here) and against a smaller disc, so its solves see a lower floor. `step_peak` returns
/// `max(floor, extremum)` with the extremum computed independently of the floor, except where one
/// of its early exits compares a bound with the floor without a margin; the two modes can then
/// differ only if a computed extremum falls within a rounding of such a bound, for an angle that
/// decides RotD50 or RotD100 — not seen in the tests, which compare both modes bit for bit.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn select(
    osc: &Oscillator,
    kept: &[Step],
    free: Option<&Free>,
    floor: f64,
    cos: &[f64],
    sin: &[f64],
    pk: &mut [f64],
    s: &mut Selection,
) {
    let Selection { lower, upper, solved, pending, work } = s;
    let disc = pk.iter().fold(f64::INFINITY, |m, &p| m.min(p));
    // Nor can a step that stays inside the disc below the peaks' 90th smallest lower bound
    // change anything RotD50 or RotD100 depend on.
    let below = floor.max(disc).max(below_middle(pk, work));
    let h = osc.h();
    let phases = [osc.phase(0.25 * h), osc.phase(0.5 * h), osc.phase(0.75 * h)];
    lower.clear();
    lower.extend_from_slice(pk);
    upper.clear();
    upper.extend(pk.iter().map(|&p| p.max(below)));
    for step in kept {
        step.raise_bounds(osc, below, &phases, cos, sin, lower, upper);
    }
    if let Some(free) = free {
        for t in 0..ANGLES {
            let envelope = free.envelope(cos[t], sin[t]).2;
            if envelope > pk[t] {
                upper[t] = upper[t].max(envelope * (1.0 + 1e-9));
            }
        }
    }
    solved.clear();
    solved.extend(pk.iter().zip(upper.iter()).map(|(p, u)| u <= p));
    loop {
        doubtful(lower, upper, solved, pending, work);
        if pending.is_empty() {
            // The unsolved angles take their lower bounds: on their side of the middle values.
            for t in 0..ANGLES {
                if !solved[t] {
                    pk[t] = lower[t];
                }
            }
            break;
        }
        for step in kept {
            step.solve(osc, disc, cos, sin, pk, pending);
        }
        for &t in pending.iter() {
            if let Some(free) = free {
                pk[t] = free.raise(osc, cos[t], sin[t], pk[t]);
            }
            solved[t] = true;
            (lower[t], upper[t]) = (pk[t], pk[t]);
        }
    }
}

/// Into `pending`, the angles not `solved` whose interval `[lower, upper]` meets
/// the range where the 90th…91st smallest or the largest peak may lie (see [`select`]).
#[inline(always)]
fn doubtful(lower: &[f64], upper: &[f64], solved: &[bool], pending: &mut Vec<usize>, work: &mut Vec<f64>) {
    let (l90, _) = middle(lower, work);
    let (_, u91) = middle(upper, work);
    let l180 = lower.iter().fold(0.0, |m: f64, &p| m.max(p));
    let u180 = upper.iter().fold(0.0, |m: f64, &p| m.max(p));
    pending.clear();
    pending.extend(
        (0..ANGLES).filter(|&t| {
            !solved[t] && ((lower[t] <= u91 && upper[t] >= l90) || (lower[t] <= u180 && upper[t] >= l180))
        }),
    );
}

/// The 90th and 91st smallest of the 180 values (RotD50 is their mean).
#[inline(always)]
pub(super) fn middle(values: &[f64], work: &mut Vec<f64>) -> (f64, f64) {
    work.clear();
    work.extend_from_slice(values);
    let (_, lower, above) = work.select_nth_unstable_by(ANGLES / 2 - 1, f64::total_cmp);
    let lower = *lower;
    (lower, above.iter().fold(f64::INFINITY, |m, &v| m.min(v)))
}

impl Step {
    /// Raises the lower bounds of the 180 peaks to `|u_θ|` at a quarter, half and
    /// three quarters of the step (`phases`: `e^{λτ}` there), less a rounding allowance, and
    /// their upper bounds to what the step can reach: the smaller of [`Step::bound`] and the
    /// largest of those five points plus `((h/4)²/8)·ω²|z_θ|` (|ü_θ| ≤ ω²|z_θ|, so between two
    /// of the points |u_θ| stays within that of their chord), with the same allowance. Nothing
    /// when the step stays inside the disc of radius `disc`.
    ///
    /// The upper bound is at most `g + (h²/8)·ω²|z_θ|` (or 0), `g` the larger end, and
    /// `|z_θ| ≤ |Z|`; so where `g + (h²/8)·ω²|Z|` (with a relative 1e-12 on |Z| for the
    /// roundings of |z_θ|) does not exceed an angle's upper bound so far, the step cannot raise it,
    /// and the tight bounds are computed only for the groups of [`GROUP`] angles where one may
    /// rise: the same upper bounds as computing them all (for paper-100's records, a quarter of
    /// the groups of the kept steps are computed). When `|Z|²` is not comfortably a normal
    /// number (below 1e-290 its squares lose digits, and so may |z_θ|'s; above 1e290 they
    /// overflow) every group is computed.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn raise_bounds(
        &self,
        osc: &Oscillator,
        disc: f64,
        phases: &[[f64; 2]; 3],
        cos: &[f64],
        sin: &[f64],
        lower: &mut [f64],
        upper: &mut [f64],
    ) {
        let Some(r) = self.reach(osc, disc) else { return };
        let [lx0, ly0, lxh, lyh] = r.l;
        let (zx, zy) = (r.zx, r.zy);
        let q: [[f64; 2]; 3] = std::array::from_fn(|j| {
            let (f, e) = ((j + 1) as f64 * 0.25, phases[j]);
            [lx0 + (lxh - lx0) * f + zx[0] * e[0] - zx[1] * e[1], ly0 + (lyh - ly0) * f + zy[0] * e[0] - zy[1] * e[1]]
        });
        let slack = 1e-12
            * (lx0.abs() + lxh.abs() + ly0.abs() + lyh.abs() + zx[0].abs() + zx[1].abs() + zy[0].abs() + zy[1].abs());
        let inner = Inner { q, slack, quarter: r.k / 16.0 };
        let (cos, sin, lower, upper) = (&cos[..ANGLES], &sin[..ANGLES], &mut lower[..ANGLES], &mut upper[..ANGLES]);
        let normal = r.zn > 1e-145 && r.zn < 1e145;
        let beyond_z = if normal { r.k * (r.zn * (1.0 + 1e-12)) } else { f64::INFINITY };
        for g in (0..ANGLES).step_by(GROUP) {
            let mut any = false;
            for t in g..g + GROUP {
                let (c, s) = (cos[t], sin[t]);
                lower[t] = lower[t].max(inner.inside(c, s) - inner.slack);
                any |= (r.ends(c, s) + beyond_z) * (1.0 + 1e-9) > upper[t];
            }
            if any {
                for t in g..g + GROUP {
                    upper[t] = upper[t].max(self.upper_at(&r, &inner, cos[t], sin[t]));
                }
            }
        }
    }

    /// The upper bound of the largest |u_θ| inside the step at angle `(c, s)` (see
    /// [`Step::raise_bounds`]).
    #[inline(always)]
    fn upper_at(&self, r: &Reach, inner: &Inner, c: f64, s: f64) -> f64 {
        let inside = inner.inside(c, s);
        let ends = r.ends(c, s);
        let (zr, zi) = (c * r.zx[0] + s * r.zy[0], c * r.zx[1] + s * r.zy[1]);
        let pieces = inside.max(ends) + inner.quarter * (zr * zr + zi * zi).sqrt() + inner.slack;
        self.bound(r, c, s).min(pieces) * (1.0 + 1e-9)
    }

    /// [`Step::refine`] at the angles `angles` only: for each, the same test and solve.
    #[inline(always)]
    fn solve(&self, osc: &Oscillator, disc: f64, cos: &[f64], sin: &[f64], pk: &mut [f64], angles: &[usize]) {
        let Some(r) = self.reach(osc, disc) else { return };
        for &t in angles {
            if self.bound(&r, cos[t], sin[t]) * (1.0 + 1e-9) > pk[t] {
                pk[t] = self.solve_at(osc, cos[t], sin[t], pk[t]);
            }
        }
    }
}

/// The points a quarter, half and three quarters into a step, their rounding allowance, and
/// `((h/4)²/8)·ω²` (see [`Step::raise_bounds`]).
struct Inner {
    q: [[f64; 2]; 3],
    slack: f64,
    quarter: f64,
}

impl Inner {
    /// The largest `|u_θ|` of the three points at angle `(c, s)`.
    #[inline(always)]
    fn inside(&self, c: f64, s: f64) -> f64 {
        let q = &self.q;
        (c * q[0][0] + s * q[0][1]).abs().max((c * q[1][0] + s * q[1][1]).abs()).max((c * q[2][0] + s * q[2][1]).abs())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_least_91_of_the_180_angles_see_cos_45_5_degrees_of_any_direction() {
        let cos455 = 45.5f64.to_radians().cos();
        assert!((MEDIAN_BELOW / BELOW - cos455).abs() < 1e-15, "{MEDIAN_BELOW} against {cos455}");
        // Directions on, between and near the grid, and spread over the half-turn: the 91st
        // largest |cos(θ − φ)| over θ = 0°…179° (the 90th smallest) is never below cos 45.5°, and
        // at half-degree offsets it is cos 45.5° itself, so nothing larger would hold.
        let mut tightest = f64::INFINITY;
        for i in 0..36_000 {
            let phi = (i as f64 * 0.005 + 1e-7 * (i % 7) as f64).to_radians();
            let mut seen: Vec<f64> = (0..ANGLES).map(|t| ((t as f64).to_radians() - phi).cos().abs()).collect();
            seen.sort_by(f64::total_cmp);
            let ninetieth = seen[ANGLES / 2 - 1];
            assert!(ninetieth >= cos455 * (1.0 - 1e-12), "φ = {}°: {ninetieth}", phi.to_degrees());
            tightest = tightest.min(ninetieth);
        }
        assert!((tightest / cos455 - 1.0).abs() < 1e-6, "{tightest}");
    }
}
