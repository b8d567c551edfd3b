//! RotD50 and RotD100 of two horizontal components (Boore 2010, "Orientation-independent,
//! nongeometric-mean measures of seismic intensity from two horizontal components", BSSA
//! 100(4)), with the exact peaks between samples.
//!
//! The oscillator is linear, so its response to the components rotated by θ,
//! `a_θ(t) = a_x(t)·cos θ + a_y(t)·sin θ`, is `u_θ(t) = u_x(t)·cos θ + u_y(t)·sin θ`: the two
//! displacement histories are computed once (as in [`crate::spectra::response`], same
//! reading and record-end convention) and, for θ = 0°, 1°, …, 179°,
//!
//! ```text
//! SD(θ) = max_t |u_θ(t)|,   RotD100 = max_θ SD(θ),   RotD50 = median_θ SD(θ)
//! ```
//!
//! (the median of the 180 values is the mean of the 90th and 91st smallest, as numpy's and
//! pyrotd's 50th percentile). `SD(θ)` is the true peak of the reading including between
//! samples and in the free vibration after the record, to rounding: within 1e-12 of RotD100 of
//! the straightforward computation that rotates the record for every angle and takes its exact
//! one-component spectrum (tested with both readings and both record ends; largest difference
//! measured 6e-15), hence within 1e-12 relative of a dense reference like the one-component
//! spectra.
//!
//! **How the 180 peaks stay cheap.** The set of angles' peaks is the support function of the
//! trajectory `P(t) = (u_x, u_y)`: `SD(θ) = max_t |P(t)·e_θ|`. A first pass over the record
//! (side by side across oscillators, both components) records the samples that reach farthest
//! along 8 directions and in `|P|`; their symmetric convex hull `K₀` is reached by the trajectory, so
//! `SD(θ) ≥ h_{K₀}(θ)` and the peaks start there. Inside a step `|P·e_θ|` is at most
//! `max(|P₀·e_θ|, |P₁·e_θ|) + (h²/8)·ω²|Z|` and at most `|L_θ| + |Z|`, with
//! `|Z| = (|z_x|² + |z_y|²)^½` the joint amplitude of the homogeneous parts (see
//! [`crate::spectra::oscillator`]). The second pass keeps only the steps that may leave `K₀`:
//! those whose end sample is outside it and whose end points are not inside `K₀` shrunk by the
//! first margin, nor their particular solutions `L(0)`, `L(h)` inside `K₀` shrunk by `|Z|`
//! (tested first against the disc inscribed in `K₀`, side by side across oscillators, then
//! against its edges). Those raise the 180 peaks to their end sample, side by side across
//! angles, and are kept; once the peaks at the samples are complete, each kept step checks
//! its bounds angle by angle (with the joint `|Z|`, then the angle's own `|z_θ|`) and the
//! angles still in doubt are solved exactly as one-component steps of the rotated input.
//! Like the one-component passes, all of this is compiled for every build of
//! [`stickslip_isa::Isa`] and the widest the CPU has is picked at run time (the same bits;
//! `tests/builds.rs`).
//!
//! About 9× faster than the straightforward computation for a record of 11 800 samples and
//! 100 periods (`benches/response_spectra.rs`); the steps solved exactly are mostly those of
//! periods of a few Δt, where the samples say little about the peaks. A linearly polarised pair
//! has a flat hull, so every step is looked at across the angles: still exact, about 5× slower
//! (still faster than the straightforward computation).
//!
//! A [`RotDPlan`] is made once per (Δt, periods, dampings, reading) and a [`RotDScratch`] is
//! reused across records: no allocation once grown to the largest record.

use std::f64::consts::PI;

use stickslip_isa::{Isa, widest};

use crate::spectra::oscillator::Oscillator;
use crate::spectra::response::{
    Bank, CHECK, Coefficients, LANES, Reading, RecordEnd, Resampler, Running, SETTLED, SpectrumError, SpectrumPlan,
    State, check_finite, settled, step_input, step_range, suffix_max,
};

/// Number of rotation angles: θ = 0°, 1°, …, 179°.
pub const ANGLES: usize = 180;

/// Everything that depends only on (Δt, periods, dampings, reading, record end), and the
/// rotation table.
#[derive(Clone, Debug)]
pub struct RotDPlan {
    plan: SpectrumPlan,
    cos: Vec<f64>,
    sin: Vec<f64>,
}

/// RotD spectra of one pair of components, damping-major like [`SpectrumPlan::compute`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RotDSpectrum {
    /// Median over the 180 angles of the spectral displacement (record length unit).
    pub rotd50: Vec<f64>,
    /// Largest spectral displacement over the angles (record length unit).
    pub rotd100: Vec<f64>,
    /// Angle of RotD100 (degrees from x towards y, 0…179; the smallest if tied).
    pub rotd100_angle_deg: Vec<f64>,
    /// Spectral displacement of every oscillator at every angle: `per_angle[o·180 + θ]`.
    pub per_angle: Vec<f64>,
    /// Spectral displacement of the x component alone, bit for bit what
    /// [`SpectrumPlan::compute`] gives for it (the same passes give both).
    pub x: Vec<f64>,
    /// … and of the y component alone.
    pub y: Vec<f64>,
}

impl RotDSpectrum {
    /// The 180 spectral displacements of output `o` (θ = 0°…179°).
    pub fn angles(&self, o: usize) -> &[f64] {
        &self.per_angle[o * ANGLES..(o + 1) * ANGLES]
    }
}

/// Work arrays of one pair of records (reuse across records: no allocation once grown).
#[derive(Default)]
pub struct RotDScratch {
    /// States of the x and y responses (with each component's own peak), in the bank's order.
    x: State,
    y: State,
    /// Which oscillators still run.
    running: Running,
    /// Largest |x|, |y| and |(x, y)| from each sample on.
    rest_x: Vec<f64>,
    rest_y: Vec<f64>,
    rest_p: Vec<f64>,
    rx: Resampler,
    ry: Resampler,
    /// Samples where |u_x|, |u_y| and |P| peak (first pass), per oscillator.
    ext: Extremes,
    /// Their symmetric hull, per oscillator.
    hull: Vec<Hull>,
    /// Radius of the disc inscribed in each hull (padded).
    inradius: Vec<f64>,
    flag: Vec<u8>,
    angle_flag: Vec<u8>,
    candidates: Vec<Step>,
    sorted: Vec<f64>,
    /// The 180 peaks of every oscillator in the bank's order, and |(x, y)| of each sample.
    per_angle: Vec<f64>,
    points: Vec<f64>,
}

/// Directions (degrees) along which the first pass records where the samples reach farthest.
const DIRECTIONS: [f64; 8] = [0.0, 22.5, 45.0, 67.5, 90.0, 112.5, 135.0, 157.5];
/// Points recorded per oscillator: one per direction, and the largest |P|.
const POINTS: usize = DIRECTIONS.len() + 1;

/// Largest |P·e| along each of [`DIRECTIONS`] and largest |P|² seen at the samples, and the
/// points `P = (u_x, u_y)` where, for every oscillator: entry `j·n + o` (structure of arrays,
/// so the first pass runs across oscillators).
#[derive(Debug, Default)]
struct Extremes {
    value: Vec<f64>,
    px: Vec<f64>,
    py: Vec<f64>,
}

impl Extremes {
    fn reset(&mut self, n: usize) {
        for a in [&mut self.value, &mut self.px, &mut self.py] {
            a.clear();
            a.resize(POINTS * n, 0.0);
        }
    }

    /// The recorded points of oscillator `o` of `n`.
    fn points(&self, o: usize, n: usize) -> [[f64; 2]; POINTS] {
        std::array::from_fn(|j| [self.px[j * n + o], self.py[j * n + o]])
    }
}

/// A convex polygon symmetric about the origin, as half-planes `n·P ≤ d` (unit outward `n`);
/// no edge means degenerate (nothing is inside). The entries past `edges` are `n = 0`,
/// `d = +∞`, which every finite point satisfies, so a point is tested against all entries at
/// once, side by side.
#[derive(Clone, Copy, Debug)]
struct Hull {
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
    fn of(points: &[[f64; 2]; POINTS]) -> Hull {
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
    fn inradius(&self) -> f64 {
        if self.edges == 0 { 0.0 } else { self.d[..self.edges].iter().fold(f64::INFINITY, |m, &d| m.min(d)).max(0.0) }
    }

    /// Whether `p` is inside with at least `margin` to spare from every edge.
    #[inline(always)]
    fn holds(&self, p: [f64; 2], margin: f64) -> bool {
        let mut inside = true;
        for i in 0..2 * POINTS {
            inside &= self.nx[i] * p[0] + self.ny[i] * p[1] + margin <= self.d[i];
        }
        self.edges > 0 && inside
    }
}

impl RotDPlan {
    /// Plans RotD spectra of pairs of records sampled every `dt` seconds, at `periods` (s) and
    /// `dampings` (see [`SpectrumPlan::new`]).
    pub fn new(
        dt: f64,
        periods: &[f64],
        dampings: &[f64],
        reading: Reading,
        oversampling: usize,
    ) -> Result<Self, SpectrumError> {
        Ok(RotDPlan::from_plan(SpectrumPlan::new(dt, periods, dampings, reading, oversampling)?))
    }

    /// RotD spectra with the oscillators, reading and record-end convention of `plan`.
    pub fn from_plan(plan: SpectrumPlan) -> Self {
        let (mut cos, mut sin) = (vec![0.0; ANGLES], vec![0.0; ANGLES]);
        for t in 0..ANGLES {
            (sin[t], cos[t]) = match t {
                0 => (0.0, 1.0),
                90 => (1.0, 0.0),
                _ => (t as f64 * PI / 180.0).sin_cos(),
            };
        }
        RotDPlan { plan, cos, sin }
    }

    /// The one-component plan (periods, dampings, reading, record end).
    pub fn plan(&self) -> &SpectrumPlan {
        &self.plan
    }

    /// Number of outputs (`dampings × periods`, damping-major).
    pub fn len(&self) -> usize {
        self.plan.len()
    }

    /// Whether the plan has no oscillator.
    pub fn is_empty(&self) -> bool {
        self.plan.is_empty()
    }

    /// RotD50, RotD100 (and its angle) and the 180 per-angle spectral displacements of the
    /// horizontal components `x` and `y` (accelerations sampled alike, in one unit) into `out`
    /// (resized to `len()` outputs). Two empty records give zeros.
    pub fn compute(
        &self,
        x: &[f64],
        y: &[f64],
        scratch: &mut RotDScratch,
        out: &mut RotDSpectrum,
    ) -> Result<(), SpectrumError> {
        if x.len() != y.len() {
            return Err(SpectrumError::Components { x: x.len(), y: y.len() });
        }
        check_finite(x, "x")?;
        check_finite(y, "y")?;
        let n = self.len();
        for a in [&mut out.rotd50, &mut out.rotd100, &mut out.rotd100_angle_deg, &mut out.x, &mut out.y] {
            a.clear();
            a.resize(n, 0.0);
        }
        out.per_angle.clear();
        out.per_angle.resize(n * ANGLES, 0.0);
        if x.is_empty() {
            return Ok(());
        }
        let ramp = self.plan.record_end() == RecordEnd::Ramp;
        let (xs, ys, tail) = match self.plan.reading() {
            Reading::Linear => (x, y, ramp),
            Reading::BandLimited => {
                let r = self.plan.oversampling();
                (scratch.rx.resample(x, r, ramp), scratch.ry.resample(y, r, ramp), false)
            }
        };
        let w = Work {
            bank: self.plan.bank(),
            cos: &self.cos,
            sin: &self.sin,
            x: xs,
            y: ys,
            ramp: tail,
            settle: self.plan.settles(),
        };
        let RotDScratch {
            x: sx,
            y: sy,
            running,
            rest_x,
            rest_y,
            rest_p,
            ext,
            hull,
            inradius,
            flag,
            angle_flag,
            candidates,
            sorted,
            per_angle,
            points,
            ..
        } = scratch;
        suffix_max(xs, rest_x);
        suffix_max(ys, rest_y);
        points.clear();
        points.extend(xs.iter().zip(ys).map(|(a, b)| a.hypot(*b)));
        suffix_max(points, rest_p);
        per_angle.clear();
        per_angle.resize(n * ANGLES, 0.0);
        let mut v = Vectors { sx, sy, running, rest: [rest_x, rest_y, rest_p], ext, hull, inradius, flag, per_angle };
        run(Isa::current(), &w, &mut v, angle_flag, candidates);
        // Each component's spectrum, and the 180 peaks, in the output's order.
        let bank = self.plan.bank();
        for (o, osc) in bank.oscillators.iter().enumerate() {
            let at = bank.output[o];
            let stopped = v.running.stopped(o);
            for (s, out) in [(&*v.sx, &mut out.x), (&*v.sy, &mut out.y)] {
                out[at] = if stopped { s.peak[o] } else { s.peak[o].max(osc.free_peak(s.u[o], s.v[o])) };
            }
            out.per_angle[at * ANGLES..(at + 1) * ANGLES].copy_from_slice(&v.per_angle[o * ANGLES..(o + 1) * ANGLES]);
        }
        // Summaries.
        for o in 0..n {
            let peaks = &out.per_angle[o * ANGLES..(o + 1) * ANGLES];
            let (mut best, mut at) = (peaks[0], 0);
            for (t, &p) in peaks.iter().enumerate() {
                if p > best {
                    (best, at) = (p, t);
                }
            }
            out.rotd100[o] = best;
            out.rotd100_angle_deg[o] = at as f64;
            sorted.clear();
            sorted.extend_from_slice(peaks);
            sorted.sort_unstable_by(f64::total_cmp);
            out.rotd50[o] = 0.5 * (sorted[ANGLES / 2 - 1] + sorted[ANGLES / 2]);
        }
        Ok(())
    }
}

/// The inputs of one computation.
struct Work<'a> {
    bank: &'a Bank,
    cos: &'a [f64],
    sin: &'a [f64],
    x: &'a [f64],
    y: &'a [f64],
    ramp: bool,
    settle: bool,
}

/// The work arrays of the passes (see [`RotDScratch`]); the 180 peaks in the bank's order.
struct Vectors<'a> {
    sx: &'a mut State,
    sy: &'a mut State,
    running: &'a mut Running,
    rest: [&'a Vec<f64>; 3],
    ext: &'a mut Extremes,
    hull: &'a mut Vec<Hull>,
    inradius: &'a mut Vec<f64>,
    flag: &'a mut Vec<u8>,
    per_angle: &'a mut Vec<f64>,
}

widest! {
    /// Both passes, the refinement and the free vibration of every oscillator of `w`: the 180
    /// peaks into `v.per_angle` and each component's own peak in `v.sx`, `v.sy`, in
    /// instruction set `isa`.
    fn run(
        w: &Work,
        v: &mut Vectors,
        angle_flag: &mut Vec<u8>,
        candidates: &mut Vec<Step>,
    ) => run_any
}

/// The kernel of [`run`], compiled once per instruction set.
#[inline(always)]
fn run_any(w: &Work, v: &mut Vectors, angle_flag: &mut Vec<u8>, candidates: &mut Vec<Step>) {
    let bank = w.bank;
    let (n, len) = (bank.padded, bank.len());
    let Vectors { sx, sy, running, rest: [rest_x, rest_y, rest_p], ext, hull, inradius, flag, per_angle } = v;
    sx.reset(n);
    sy.reset(n);
    running.start();
    // The steps, from the one into the first sample where either component is not zero.
    let steps = {
        let all = step_range(w.x, w.ramp);
        let first = w.x.iter().zip(w.y).position(|(a, b)| *a != 0.0 || *b != 0.0);
        first.map_or(all.end, |i| i.saturating_sub(1)).min(all.end)..all.end
    };
    let first = steps.start;
    // First pass: the samples that reach farthest along the directions and in |P|, and each
    // component's peak at the samples. Every CHECK steps, the oscillators whose responses can no
    // longer reach their peaks stop (each component's own, and every angle's: the disc
    // inscribed in the hull of the points so far is inside every angle's final peak).
    ext.reset(n);
    let directions = direction_cosines();
    for k in steps.clone() {
        let (x0, x1) = step_input(w.x, k);
        let (y0, y1) = step_input(w.y, k);
        first_pass_step(&bank.k, &directions, running.first, n, x0, x1, y0, y1, sx, sy, ext);
        if w.settle && (k + 1 - first).is_multiple_of(CHECK) {
            let rests = (rest_x[k + 1], rest_y[k + 1], rest_p[k + 1]);
            running.settle(k, n, |o| pair_settled(&bank.k, o, n, sx, sy, ext, rests));
            if running.first == n {
                break;
            }
        }
    }
    hull.clear();
    inradius.clear();
    inradius.resize(n, 0.0);
    for o in 0..n {
        let h = Hull::of(&ext.points(o, n));
        hull.push(h);
        inradius[o] = h.inradius();
    }
    // Every angle starts from the recorded points' projections.
    for o in 0..len {
        let pk = &mut per_angle[o * ANGLES..(o + 1) * ANGLES];
        for q in &ext.points(o, n) {
            for t in 0..ANGLES {
                pk[t] = pk[t].max((w.cos[t] * q[0] + w.sin[t] * q[1]).abs());
            }
        }
    }
    // Second pass over the same steps of the same oscillators: each component's steps whose
    // bounds exceed its peak are solved exactly, and the steps that may leave the hull update
    // the angles.
    for a in [&mut sx.u, &mut sx.v, &mut sy.u, &mut sy.v] {
        a.fill(0.0);
    }
    flag.clear();
    flag.resize(n, 0);
    angle_flag.clear();
    angle_flag.resize(ANGLES, 0);
    candidates.clear();
    running.replay();
    for k in steps {
        let (x0, x1) = step_input(w.x, k);
        let (y0, y1) = step_input(w.y, k);
        let lo = running.first;
        let [any_x, any_y, any] = second_pass_step(&bank.k, lo, n, x0, x1, y0, y1, sx, sy, inradius, flag);
        if any_x || any_y || any {
            for o in lo..len {
                let osc = &bank.oscillators[o];
                if any_x && sx.flag[o] != 0 {
                    sx.peak[o] = osc.step_peak(sx.u[o], sx.v[o], x0, x1, sx.peak[o]);
                }
                if any_y && sy.flag[o] != 0 {
                    sy.peak[o] = osc.step_peak(sy.u[o], sy.v[o], y0, y1, sy.peak[o]);
                }
                if any && flag[o] != 0 {
                    let step = Step {
                        o,
                        ux: [sx.u[o], sx.u_next[o]],
                        uy: [sy.u[o], sy.u_next[o]],
                        vx: sx.v[o],
                        vy: sy.v[o],
                        vx1: sx.v_next[o],
                        vy1: sy.v_next[o],
                        x: [x0, x1],
                        y: [y0, y1],
                    };
                    if step.escapes(osc, &hull[o]) {
                        step.sample(w.cos, w.sin, &mut per_angle[o * ANGLES..(o + 1) * ANGLES]);
                        candidates.push(step);
                    }
                }
            }
        }
        std::mem::swap(&mut sx.u, &mut sx.u_next);
        std::mem::swap(&mut sx.v, &mut sx.v_next);
        std::mem::swap(&mut sy.u, &mut sy.u_next);
        std::mem::swap(&mut sy.v, &mut sy.v_next);
        running.replayed(k);
        if running.first == n {
            break;
        }
    }
    // The peaks at the samples are complete: the steps that escaped the hull are looked
    // inside where their bounds exceed them.
    // The smallest peak of each oscillator bounds a disc every angle's peak contains.
    for o in 0..len {
        inradius[o] = per_angle[o * ANGLES..(o + 1) * ANGLES].iter().fold(f64::INFINITY, |m, &p| m.min(p));
    }
    for step in candidates.iter() {
        let o = step.o;
        let pk = &mut per_angle[o * ANGLES..(o + 1) * ANGLES];
        step.refine(&bank.oscillators[o], inradius[o], w.cos, w.sin, pk, angle_flag);
    }
    // Free vibration after the record, angle by angle (skipped where its envelope cannot reach
    // the peak, and for the oscillators that stopped: theirs cannot).
    for o in 0..len {
        if running.stopped(o) {
            continue;
        }
        let osc = &bank.oscillators[o];
        let (wn, xi) = (osc.omega(), osc.damping());
        let wd = wn * (1.0 - xi * xi).sqrt();
        let pk = &mut per_angle[o * ANGLES..(o + 1) * ANGLES];
        for t in 0..ANGLES {
            let u = w.cos[t] * sx.u[o] + w.sin[t] * sy.u[o];
            let v = w.cos[t] * sx.v[o] + w.sin[t] * sy.v[o];
            if u.hypot((v + xi * wn * u) / wd) > pk[t] {
                pk[t] = pk[t].max(osc.free_peak(u, v));
            }
        }
    }
}

/// Whether none of the [`LANES`] oscillators from `o` (of `n`) can raise any of its peaks any
/// more: each component's (see [`settled`]) and every angle's — from the states the free
/// vibration of `u_θ` stays within the joint amplitude `|Z| = (A_x² + A_y²)^½` and the forced
/// response within `rest_p·∫|h|` (`rest_p` the largest |(a_x, a_y)| to come), and when their
/// sum is inside the disc inscribed in the hull of the points recorded so far, it is inside
/// every angle's final peak.
#[allow(clippy::too_many_arguments)]
fn pair_settled(
    k: &Coefficients,
    o: usize,
    n: usize,
    x: &State,
    y: &State,
    e: &Extremes,
    (rx, ry, rp): (f64, f64, f64),
) -> bool {
    if !(settled(k, o, &x.u, &x.v, &x.peak, rx) && settled(k, o, &y.u, &y.v, &y.peak, ry)) {
        return false;
    }
    (o..o + LANES).all(|o| {
        let wx = (x.v[o] + k.xw[o] * x.u[o]) * k.iwd[o];
        let wy = (y.v[o] + k.xw[o] * y.u[o]) * k.iwd[o];
        let forced = if rp == 0.0 { 0.0 } else { rp * k.gain[o] };
        let reach = (x.u[o] * x.u[o] + wx * wx + y.u[o] * y.u[o] + wy * wy).sqrt() + forced;
        // The disc is inside the extent along every direction: a cheap test first.
        let extent = (0..DIRECTIONS.len()).fold(f64::INFINITY, |m, j| m.min(e.value[j * n + o]));
        reach <= SETTLED * extent && reach <= SETTLED * Hull::of(&e.points(o, n)).inradius()
    })
}

/// `(cos, sin)` of each of [`DIRECTIONS`].
fn direction_cosines() -> [(f64, f64); DIRECTIONS.len()] {
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
fn first_pass_step(
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
fn second_pass_step(
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
        let b2 = p2.sqrt() + (c2[o] * zz).sqrt();
        let b1 = l2.sqrt() + zz.sqrt();
        let f = (b2.min(b1) > inradius[o]) as u8;
        flag[o] = f;
        any |= f;
    }
    any != 0
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

/// One step of one oscillator, both components: states at its start (and displacements at its
/// end), inputs at both ends.
#[derive(Clone, Copy, Debug)]
struct Step {
    o: usize,
    ux: [f64; 2],
    uy: [f64; 2],
    vx: f64,
    vy: f64,
    /// Velocities at the step's end.
    vx1: f64,
    vy1: f64,
    x: [f64; 2],
    y: [f64; 2],
}

impl Step {
    /// Whether the step may leave `hull` (the end sample, or the bounds inside the step).
    #[inline(always)]
    fn escapes(&self, osc: &Oscillator, hull: &Hull) -> bool {
        let (lx0, lxh, zx) = osc.envelope(self.ux[0], self.vx, self.x[0], self.x[1]);
        let (ly0, lyh, zy) = osc.envelope(self.uy[0], self.vy, self.y[0], self.y[1]);
        let zn = (zx[0] * zx[0] + zx[1] * zx[1] + zy[0] * zy[0] + zy[1] * zy[1]).sqrt();
        let r = (osc.h() * osc.omega()).powi(2) / 8.0 * zn;
        let (p0, p1) = ([self.ux[0], self.uy[0]], [self.ux[1], self.uy[1]]);
        !(hull.holds(p1, 0.0)
            && ((hull.holds(p0, r) && hull.holds(p1, r)) || (hull.holds([lx0, ly0], zn) && hull.holds([lxh, lyh], zn))))
    }

    /// Raises the 180 peaks `pk` to the end sample's |u_θ|.
    #[inline(always)]
    fn sample(&self, cos: &[f64], sin: &[f64], pk: &mut [f64]) {
        let (cos, sin, pk) = (&cos[..ANGLES], &sin[..ANGLES], &mut pk[..ANGLES]);
        for t in 0..ANGLES {
            pk[t] = pk[t].max((cos[t] * self.ux[1] + sin[t] * self.uy[1]).abs());
        }
    }

    /// Raises the 180 peaks `pk` to the exact peak inside the step, for the angles whose
    /// bounds exceed their peak: first against the disc of radius `disc` (the smallest peak),
    /// then with the joint amplitude `|Z|` side by side across angles, then with the angle's
    /// own `|z_θ|`.
    #[inline(always)]
    fn refine(&self, osc: &Oscillator, disc: f64, cos: &[f64], sin: &[f64], pk: &mut [f64], angle_flag: &mut [u8]) {
        let (lx0, lxh, zx) = osc.envelope(self.ux[0], self.vx, self.x[0], self.x[1]);
        let (ly0, lyh, zy) = osc.envelope(self.uy[0], self.vy, self.y[0], self.y[1]);
        let k = (osc.h() * osc.omega()).powi(2) / 8.0;
        let zn = (zx[0] * zx[0] + zx[1] * zx[1] + zy[0] * zy[0] + zy[1] * zy[1]).sqrt();
        let r = k * zn;
        let (p0, p1) = ([self.ux[0], self.uy[0]], [self.ux[1], self.uy[1]]);
        // Inside the disc of radius `disc` (every angle's peak is at least that), nothing to do.
        let reach_p = (p0[0] * p0[0] + p0[1] * p0[1]).max(p1[0] * p1[0] + p1[1] * p1[1]).sqrt() + r;
        let reach_l = (lx0 * lx0 + ly0 * ly0).max(lxh * lxh + lyh * lyh).sqrt() + zn;
        if reach_p.min(reach_l) <= disc {
            return;
        }
        let (cos, sin, pk, angle_flag) = (&cos[..ANGLES], &sin[..ANGLES], &mut pk[..ANGLES], &mut angle_flag[..ANGLES]);
        // Side by side across angles, with the angle's own |z_θ|: the bounds of |u_θ| inside the
        // step against its peak; and an interior extremum is a zero of u̇_θ, of which there is
        // none when u̇_θ keeps one sign at both ends and stays farther from zero than
        // (h²/8)·ω³|z_θ| bounds its departure from the chord (twice that, and a rounding
        // allowance, as step_peak's own test sees slightly different roundings): the step's
        // largest |u_θ| is then at an end, already in the peak, and step_peak would return it
        // unchanged. The angles left are solved exactly.
        //
        // The harmonic part y_θ(τ) = e^{−ξωτ}·|z_θ|·cos(ω_dτ + arg z_θ) reaches |z_θ| inside the
        // step only where cos does, i.e. where Im(z_θ·e^{iω_dτ}) changes sign (ω_d·h < π: at most
        // once); elsewhere |y_θ| stays below its larger end value without the decay, so
        // |u_θ| ≤ max|L_θ| + max(|Re z_θ|, |Re(z_θ·e^{iω_dh})|). Each bound, when it cannot beat
        // the peak with a relative margin of 1e-9, means step_peak would return the peak.
        let curve = 2.0 * k * osc.omega();
        let rounding = 1e-9 * (self.vx.abs() + self.vy.abs() + self.vx1.abs() + self.vy1.abs());
        let (tc, ts, turns) = match osc.turn() {
            Some((c, s)) => (c, s, true),
            None => (1.0, 0.0, false),
        };
        let mut any = 0u8;
        for t in 0..ANGLES {
            let (c, s) = (cos[t], sin[t]);
            let (zr, zi) = (c * zx[0] + s * zy[0], c * zx[1] + s * zy[1]);
            let z = (zr * zr + zi * zi).sqrt();
            let g = (c * p0[0] + s * p0[1]).abs().max((c * p1[0] + s * p1[1]).abs());
            let l = (c * lx0 + s * ly0).abs().max((c * lxh + s * lyh).abs());
            let (v0, v1) = (c * self.vx + s * self.vy, c * self.vx1 + s * self.vy1);
            let monotone = (v0 * v1 > 0.0) & (v0.abs().min(v1.abs()) > curve * z + rounding);
            let (er, ei) = (zr * tc - zi * ts, zr * ts + zi * tc);
            let harmonic = if turns & (zi * ei > 0.0) { zr.abs().max(er.abs()) } else { z };
            let doubt = |bound: f64| bound * (1.0 + 1e-9) > pk[t];
            let f = (doubt(g + k * z) & doubt(l + harmonic) & !monotone) as u8;
            angle_flag[t] = f;
            any |= f;
        }
        if any == 0 {
            return;
        }
        for t in 0..ANGLES {
            if angle_flag[t] != 0 {
                let (c, s) = (cos[t], sin[t]);
                pk[t] = osc.step_peak(
                    c * p0[0] + s * p0[1],
                    c * self.vx + s * self.vy,
                    c * self.x[0] + s * self.y[0],
                    c * self.x[1] + s * self.y[1],
                    pk[t],
                );
            }
        }
    }
}
