//! The two passes of RotD over a record, side by side across oscillators: the first records
//! where the samples reach farthest (the hull `K₀`) and when oscillators stop, the second flags
//! the steps that may leave the hull or raise a component's peak (see the module above).

use super::select::median_floor;
use crate::spectra::response::{Coefficients, LANES, SETTLED, State, settled};

/// Directions (degrees) along which the first pass records where the samples reach farthest.
pub(super) const DIRECTIONS: [f64; 8] = [0.0, 22.5, 45.0, 67.5, 90.0, 112.5, 135.0, 157.5];
/// Points recorded per oscillator: one per direction, and the largest |P|.
pub(super) const POINTS: usize = DIRECTIONS.len() + 1;

/// Largest |P·e| along each of [`DIRECTIONS`] and largest |P|² seen at the samples, and the
/// points `P = (u_x, u_y)` where, for every oscillator: entry `j·n + o` (structure of arrays,
/// so the first pass runs across oscillators).
#[derive(Debug, Default)]
pub(super) struct Extremes {
    pub(super) value: Vec<f64>,
    px: Vec<f64>,
    py: Vec<f64>,
}

impl Extremes {
    pub(super) fn reset(&mut self, n: usize) {
        for a in [&mut self.value, &mut self.px, &mut self.py] {
            a.clear();
            a.resize(POINTS * n, 0.0);
        }
    }

    /// The recorded points of oscillator `o` of `n`.
    pub(super) fn points(&self, o: usize, n: usize) -> [[f64; 2]; POINTS] {
        std::array::from_fn(|j| [self.px[j * n + o], self.py[j * n + o]])
    }
}

/// A convex polygon symmetric about the origin, as half-planes `n·P ≤ d` (unit outward `n`);
/// no edge means degenerate (nothing is inside). The entries past `edges` are `n = 0`,
/// `d = +∞`, which every finite point satisfies, so a point is tested against all entries at
/// once, side by side.
#[derive(Clone, Copy, Debug)]
pub(super) struct Hull {
    edges: usize,
    nx: [f64; 2 * POINTS],
    ny: [f64; 2 * POINTS],
    d: [f64; 2 * POINTS],
}

impl Default for Hull {
    fn default() -> Self {
        Hull { edges: 0, nx: [0.0; 2 * POINTS], ny: [0.0; 2 * POINTS], d: [f64::INFINITY; 2 * POINTS] }
    }
}

impl Hull {
    /// The symmetric convex hull of `±points` (zero points ignored).
    pub(super) fn of(points: &[[f64; 2]; POINTS]) -> Hull {
        let mut p = [[0.0; 2]; 2 * POINTS];
        let mut m = 0;
        for q in points {
            if q[0] != 0.0 || q[1] != 0.0 {
                p[m] = *q;
                p[m + 1] = [-q[0], -q[1]];
                m += 2;
            }
        }
        let p = &mut p[..m];
        p.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
        // Andrew's monotone chain, counter-clockwise, collinear points dropped.
        let cross =
            |o: [f64; 2], a: [f64; 2], b: [f64; 2]| (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
        let mut h = [[0.0; 2]; 4 * POINTS + 1];
        let mut k = 0;
        for &q in p.iter() {
            while k >= 2 && cross(h[k - 2], h[k - 1], q) <= 0.0 {
                k -= 1;
            }
            h[k] = q;
            k += 1;
        }
        let lower = k + 1;
        for &q in p.iter().rev().skip(1) {
            while k >= lower && cross(h[k - 2], h[k - 1], q) <= 0.0 {
                k -= 1;
            }
            h[k] = q;
            k += 1;
        }
        let vertices = k.saturating_sub(1);
        let mut hull = Hull::default();
        if vertices < 3 {
            return hull;
        }
        for i in 0..vertices.min(2 * POINTS) {
            let (a, b) = (h[i], h[i + 1]);
            let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
            let len = ex.hypot(ey);
            let n = [ey / len, -ex / len];
            (hull.nx[hull.edges], hull.ny[hull.edges]) = (n[0], n[1]);
            hull.d[hull.edges] = n[0] * a[0] + n[1] * a[1];
            hull.edges += 1;
        }
        hull
    }

    /// Radius of the inscribed disc about the origin (0 if degenerate).
    pub(super) fn inradius(&self) -> f64 {
        if self.edges == 0 { 0.0 } else { self.d[..self.edges].iter().fold(f64::INFINITY, |m, &d| m.min(d)).max(0.0) }
    }

    /// Whether `p` is inside with at least `margin` to spare from every edge.
    #[inline(always)]
    pub(super) fn holds(&self, p: [f64; 2], margin: f64) -> bool {
        let mut inside = true;
        for i in 0..2 * POINTS {
            inside &= self.nx[i] * p[0] + self.ny[i] * p[1] + margin <= self.d[i];
        }
        self.edges > 0 && inside
    }
}

/// Whether none of the [`LANES`] oscillators from `o` (of `n`) can raise any of its peaks any
/// more: each component's (see [`settled`]) and every angle's — from the states the free
/// vibration of `u_θ` stays within the joint amplitude `|Z| = (A_x² + A_y²)^½` and the forced
/// response within `rest_p·∫|h|` (`rest_p` the largest |(a_x, a_y)| to come), and when their
/// sum is inside the disc inscribed in the hull of the points recorded so far, it is inside
/// every angle's final peak. Without `every_angle`, once that sum is below [`median_floor`] of
/// the largest |P| so far: the angles it could still raise stay below RotD50.
#[allow(clippy::too_many_arguments)]
pub(super) fn pair_settled(
    k: &Coefficients,
    o: usize,
    n: usize,
    x: &State,
    y: &State,
    e: &Extremes,
    (rx, ry, rp): (f64, f64, f64),
    every_angle: bool,
) -> bool {
    if !(settled(k, o, &x.u, &x.v, &x.peak, rx) && settled(k, o, &y.u, &y.v, &y.peak, ry)) {
        return false;
    }
    (o..o + LANES).all(|o| {
        let wx = (x.v[o] + k.xw[o] * x.u[o]) * k.iwd[o];
        let wy = (y.v[o] + k.xw[o] * y.u[o]) * k.iwd[o];
        let forced = if rp == 0.0 { 0.0 } else { rp * k.gain[o] };
        let reach = (x.u[o] * x.u[o] + wx * wx + y.u[o] * y.u[o] + wy * wy).sqrt() + forced;
        if !every_angle {
            // Below RotD50 (see `median_floor`), no angle that RotD50 and RotD100 depend on moves.
            return reach <= median_floor(e.value[(POINTS - 1) * n + o]);
        }
        // The disc is inside the extent along every direction: a cheap test first.
        let extent = (0..DIRECTIONS.len()).fold(f64::INFINITY, |m, j| m.min(e.value[j * n + o]));
        reach <= SETTLED * extent && reach <= SETTLED * Hull::of(&e.points(o, n)).inradius()
    })
}

/// `(cos, sin)` of each of [`DIRECTIONS`].
pub(super) fn direction_cosines() -> [(f64, f64); DIRECTIONS.len()] {
    DIRECTIONS.map(|d| {
        let (s, c) = d.to_radians().sin_cos();
        (c, s)
    })
}

/// First pass, one step of oscillators `lo..n`: both recurrences in place with each
/// component's peak at the samples, and the samples where |u_x|, |u_y| and |P| peak
/// (`directions` from [`direction_cosines`]).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn first_pass_step(
    k: &Coefficients,
    directions: &[(f64, f64); DIRECTIONS.len()],
    lo: usize,
    n: usize,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    sx: &mut State,
    sy: &mut State,
    ext: &mut Extremes,
) {
    let (a11, a12, a21, a22) = (&k.a11[lo..n], &k.a12[lo..n], &k.a21[lo..n], &k.a22[lo..n]);
    let (bu0, bu1, bv0, bv1) = (&k.bu0[lo..n], &k.bu1[lo..n], &k.bv0[lo..n], &k.bv1[lo..n]);
    let (ux, vx, px) = (&mut sx.u[lo..n], &mut sx.v[lo..n], &mut sx.peak[lo..n]);
    let (uy, vy, py) = (&mut sy.u[lo..n], &mut sy.v[lo..n], &mut sy.peak[lo..n]);
    for o in 0..n - lo {
        let (u0, v0) = (ux[o], vx[o]);
        let u1 = a11[o] * u0 + a12[o] * v0 + bu0[o] * x0 + bu1[o] * x1;
        vx[o] = a21[o] * u0 + a22[o] * v0 + bv0[o] * x0 + bv1[o] * x1;
        ux[o] = u1;
        px[o] = px[o].max(u1.abs());
        let (u0, v0) = (uy[o], vy[o]);
        let w1 = a11[o] * u0 + a12[o] * v0 + bu0[o] * y0 + bu1[o] * y1;
        vy[o] = a21[o] * u0 + a22[o] * v0 + bv0[o] * y0 + bv1[o] * y1;
        uy[o] = w1;
        py[o] = py[o].max(w1.abs());
    }
    for j in 0..POINTS {
        let (c, s) = if j < DIRECTIONS.len() { directions[j] } else { (0.0, 0.0) };
        let value = &mut ext.value[j * n + lo..(j + 1) * n];
        let px = &mut ext.px[j * n + lo..(j + 1) * n];
        let py = &mut ext.py[j * n + lo..(j + 1) * n];
        let (ux, uy) = (&ux[..n - lo], &uy[..n - lo]);
        for o in 0..n - lo {
            let (u, w) = (ux[o], uy[o]);
            let along = if j < DIRECTIONS.len() { (c * u + s * w).abs() } else { u * u + w * w };
            let take = along > value[o];
            value[o] = if take { along } else { value[o] };
            px[o] = if take { u } else { px[o] };
            py[o] = if take { w } else { py[o] };
        }
    }
}

/// Second pass, one step of oscillators `lo..n`: both recurrences into the next states, each
/// component's bounds against its own peak (flags in `sx.flag`, `sy.flag`, as
/// [`crate::spectra::response`] computes them), and whether the joint step may leave the disc
/// inscribed in the hull (`flag`). Returns whether any is flagged, per kind.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn second_pass_step(
    k: &Coefficients,
    lo: usize,
    n: usize,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    sx: &mut State,
    sy: &mut State,
    inradius: &[f64],
    flag: &mut [u8],
) -> [bool; 3] {
    let any = joint_step(k, lo, n, x0, x1, y0, y1, sx, sy, inradius, flag);
    [component_bounds(k, lo, n, x0, x1, sx), component_bounds(k, lo, n, y0, y1, sy), any]
}

/// Both recurrences of oscillators `lo..n` into the next states, flagging where the joint step
/// may leave the disc inscribed in the hull; returns whether any is flagged.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn joint_step(
    k: &Coefficients,
    lo: usize,
    n: usize,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    sx: &mut State,
    sy: &mut State,
    inradius: &[f64],
    flag: &mut [u8],
) -> bool {
    let (a11, a12, a21, a22) = (&k.a11[lo..n], &k.a12[lo..n], &k.a21[lo..n], &k.a22[lo..n]);
    let (bu0, bu1, bv0, bv1) = (&k.bu0[lo..n], &k.bu1[lo..n], &k.bv0[lo..n], &k.bv1[lo..n]);
    let (ky0, ky1, kd, xw) = (&k.ky0[lo..n], &k.ky1[lo..n], &k.kd[lo..n], &k.xw[lo..n]);
    let (iwd, iw2, c2) = (&k.iwd[lo..n], &k.iw2[lo..n], &k.c2[lo..n]);
    let (ux, vx, uxn, vxn) = (&sx.u[lo..n], &sx.v[lo..n], &mut sx.u_next[lo..n], &mut sx.v_next[lo..n]);
    let (uy, vy, uyn, vyn) = (&sy.u[lo..n], &sy.v[lo..n], &mut sy.u_next[lo..n], &mut sy.v_next[lo..n]);
    let (inradius, flag) = (&inradius[lo..n], &mut flag[lo..n]);
    let (dx, dy) = (x1 - x0, y1 - y0);
    let mut any = 0u8;
    for o in 0..n - lo {
        let (u0, v0, w0, q0) = (ux[o], vx[o], uy[o], vy[o]);
        let u1 = a11[o] * u0 + a12[o] * v0 + bu0[o] * x0 + bu1[o] * x1;
        vxn[o] = a21[o] * u0 + a22[o] * v0 + bv0[o] * x0 + bv1[o] * x1;
        uxn[o] = u1;
        let w1 = a11[o] * w0 + a12[o] * q0 + bu0[o] * y0 + bu1[o] * y1;
        vyn[o] = a21[o] * w0 + a22[o] * q0 + bv0[o] * y0 + bv1[o] * y1;
        uyn[o] = w1;
        // |z_x|² + |z_y|² at the step's start, and −L of each component at both ends.
        let (lx, ly) = (ky0[o] * x0 + ky1[o] * x1, ky0[o] * y0 + ky1[o] * y1);
        let (yx, yy) = (u0 + lx, w0 + ly);
        let sxx = (v0 + kd[o] * dx + xw[o] * yx) * iwd[o];
        let syy = (q0 + kd[o] * dy + xw[o] * yy) * iwd[o];
        let zz = yx * yx + sxx * sxx + yy * yy + syy * syy;
        let (lxh, lyh) = (lx + iw2[o] * dx, ly + iw2[o] * dy);
        let p2 = (u0 * u0 + w0 * w0).max(u1 * u1 + w1 * w1);
        let l2 = (lx * lx + ly * ly).max(lxh * lxh + lyh * lyh);
        // min(√p2 + √(c2·zz), √l2 + √zz) beyond the disc, shrunk so that every step the
        // square roots would flag is flagged (see `beyond`).
        let r = inradius[o] * SHRUNK;
        let f = (beyond(p2, c2[o] * zz, r * r) & beyond(l2, zz, r * r)) as u8;
        flag[o] = f;
        any |= f;
    }
    any != 0
}

/// What the disc's radius is multiplied by in [`joint_step`]: a relative margin far above the
/// roundings of either way of testing `√a + √b > r`, so that the test without square roots flags
/// every step the one with them would (and, within 1e-9 of the disc's edge, a few more, which
/// then go through the hull's own test, [`super::Step::escapes`]).
const SHRUNK: f64 = 1.0 - 1e-9;

/// Whether `√a + √b > √r2` (`a`, `b`, `r2` ≥ 0) without square roots (four a step and
/// oscillator were a tenth of the second pass): with `d = r2 − a − b`, `(√a + √b)² =
/// a + b + 2√(ab)` exceeds `r2` when `d < 0`, and otherwise exactly when `4ab > d²`. Where those
/// products could leave the normal numbers (`r2` outside 1e-140…1e140, radii below 1e-70 or
/// above 1e70 in the record's unit), it answers yes: a flag only asks for a closer look.
#[inline(always)]
fn beyond(a: f64, b: f64, r2: f64) -> bool {
    let d = r2 - a - b;
    let outside = (r2 > 0.0) & (r2 < f64::INFINITY) & !((r2 > 1e-140) & (r2 < 1e140));
    (d < 0.0) | (4.0 * a * b > d * d) | outside
}

/// One component's bounds of |u| inside the step just taken (from `s.u`, `s.v` to `s.u_next`),
/// against its own peak, for oscillators `lo..n`: the flags of `response::step_bounds`, from the
/// same arithmetic; returns whether any is flagged.
#[inline(always)]
fn component_bounds(k: &Coefficients, lo: usize, n: usize, x0: f64, x1: f64, s: &mut State) -> bool {
    let (ky0, ky1, kd, xw) = (&k.ky0[lo..n], &k.ky1[lo..n], &k.kd[lo..n], &k.xw[lo..n]);
    let (iwd, iw2, c2) = (&k.iwd[lo..n], &k.iw2[lo..n], &k.c2[lo..n]);
    let (u, v, un) = (&s.u[lo..n], &s.v[lo..n], &s.u_next[lo..n]);
    let (pk, flag) = (&s.peak[lo..n], &mut s.flag[lo..n]);
    let dx = x1 - x0;
    let mut any = 0u8;
    for o in 0..n - lo {
        let (u0, v0, u1) = (u[o], v[o], un[o]);
        let q = ky0[o] * x0 + ky1[o] * x1;
        let y0 = u0 + q;
        let w = (v0 + kd[o] * dx + xw[o] * y0) * iwd[o];
        let z2 = y0 * y0 + w * w;
        let g2 = pk[o] - u0.abs().max(u1.abs());
        let b2 = g2 * g2 < c2[o] * z2;
        let g1 = pk[o] - q.abs().max((q + iw2[o] * dx).abs());
        let b1 = (g1 < 0.0) | (g1 * g1 < z2);
        let f = (b1 & b2) as u8;
        flag[o] = f;
        any |= f;
    }
    any != 0
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{RngExt, SeedableRng};

    /// `beyond` is the square-root test `√a + √b > r` to rounding, and with the disc shrunk by
    /// [`SHRUNK`] it flags every pair the square roots flag against the whole disc: on random
    /// magnitudes over many decades, on pairs placed within a few roundings of the disc's edge,
    /// and at the ends (a zero term, a zero radius, an infinite radius).
    #[test]
    fn the_test_without_square_roots_flags_whatever_the_square_roots_flag() {
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(7);
        let sqrt_test = |a: f64, b: f64, r: f64| a.sqrt() + b.sqrt() > r;
        let (mut tried, mut near, mut extra) = (0, 0, 0);
        for i in 0..400_000 {
            let scale = 10f64.powi(rng.random_range(-30..10));
            let (a, b) = (rng.random_range(0.0..1.0) * scale, rng.random_range(0.0..1.0) * scale);
            let r = if i % 2 == 0 {
                rng.random_range(0.0..3.0) * scale.sqrt()
            } else {
                // On the edge, give or take a few roundings.
                near += 1;
                (a.sqrt() + b.sqrt()) * (1.0 + rng.random_range(-8.0..8.0) * f64::EPSILON)
            };
            tried += 1;
            let exact = sqrt_test(a, b, r);
            if exact {
                assert!(beyond(a, b, (r * SHRUNK).powi(2)), "a = {a:e}, b = {b:e}, r = {r:e}: flagged by √ only");
            }
            let plain = beyond(a, b, r * r);
            if plain != exact {
                // Only within roundings of the edge.
                let s = a.sqrt() + b.sqrt();
                assert!((s / r - 1.0).abs() < 1e-12, "a = {a:e}, b = {b:e}, r = {r:e}: {plain} against {exact}");
            }
            extra += (!exact && beyond(a, b, (r * SHRUNK).powi(2))) as usize;
        }
        // The shrunk disc flags a few more, all near the edge.
        assert!(near > 100_000 && extra < near, "{tried} tried, {near} near the edge, {extra} more flagged");
        for (a, b) in [(0.0, 4.0), (4.0, 0.0), (1.0, 1.0)] {
            assert!(beyond(a, b, 1.9 * 1.9) && !beyond(a, b, 2.1 * 2.1), "{a}, {b}");
        }
        assert!(beyond(1e-30, 0.0, 0.0) && !beyond(0.0, 0.0, 0.0), "a zero radius");
        assert!(!beyond(1e300, 1e300, f64::INFINITY), "an infinite radius");
        // Where 4ab and d² would underflow or overflow (on the edge: √a + √b just above r), the
        // step is flagged.
        for (a, r) in [(1e-200, (4e-200f64).sqrt() * (1.0 - 1e-12)), (1e200, (4e200f64).sqrt() * (1.0 - 1e-12))] {
            assert!(sqrt_test(a, a, r) && beyond(a, a, (r * SHRUNK).powi(2)), "a = b = {a:e}, r = {r:e}");
        }
        assert!(beyond(0.0, 5e-324, (2e-162f64).powi(2)), "a subnormal term");
    }
}
