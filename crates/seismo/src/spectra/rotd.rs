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
    Bank, Coefficients, Reading, RecordEnd, Resampler, SpectrumError, SpectrumPlan, State, check_finite,
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
    x: State,
    y: State,
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
/// no edge means degenerate (nothing is inside).
#[derive(Clone, Copy, Debug)]
struct Hull {
    edges: usize,
    n: [[f64; 2]; 2 * POINTS],
    d: [f64; 2 * POINTS],
}

impl Default for Hull {
    fn default() -> Self {
        Hull { edges: 0, n: [[0.0; 2]; 2 * POINTS], d: [0.0; 2 * POINTS] }
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
            hull.n[hull.edges] = n;
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
    fn holds(&self, p: [f64; 2], margin: f64) -> bool {
        self.edges > 0 && (0..self.edges).all(|i| self.n[i][0] * p[0] + self.n[i][1] * p[1] + margin <= self.d[i])
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
        for a in [&mut out.rotd50, &mut out.rotd100, &mut out.rotd100_angle_deg] {
            a.clear();
            a.resize(n, 0.0);
        }
        out.per_angle.clear();
        out.per_angle.resize(n * ANGLES, 0.0);
        if x.is_empty() {
            return Ok(());
        }
        let ramp = self.plan.record_end() == RecordEnd::Ramp;
        let RotDScratch { x: sx, y: sy, rx, ry, ext, hull, inradius, flag, angle_flag, candidates, sorted } = scratch;
        let (xs, ys, tail) = match self.plan.reading() {
            Reading::Linear => (x, y, ramp),
            Reading::BandLimited => {
                let r = self.plan.oversampling();
                (rx.resample(x, r, ramp), ry.resample(y, r, ramp), false)
            }
        };
        let w = Work { bank: self.plan.bank(), cos: &self.cos, sin: &self.sin, x: xs, y: ys, ramp: tail };
        run(Isa::current(), &w, sx, sy, ext, hull, inradius, flag, angle_flag, candidates, out);
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
}

impl Work<'_> {
    /// The steps `(x₀, x₁, y₀, y₁)`: between samples, then the ramp to zero if asked.
    fn steps(&self) -> impl Iterator<Item = [f64; 4]> + '_ {
        let tail = match (self.ramp, self.x.last(), self.y.last()) {
            (true, Some(&a), Some(&b)) => Some([a, 0.0, b, 0.0]),
            _ => None,
        };
        self.x.windows(2).zip(self.y.windows(2)).map(|(a, b)| [a[0], a[1], b[0], b[1]]).chain(tail)
    }
}

widest! {
    /// Both passes, the refinement and the free vibration of every oscillator of `w`, the 180
    /// peaks into `out.per_angle`, in instruction set `isa`.
    #[allow(clippy::too_many_arguments)]
    fn run(
        w: &Work,
        sx: &mut State,
        sy: &mut State,
        ext: &mut Extremes,
        hull: &mut Vec<Hull>,
        inradius: &mut Vec<f64>,
        flag: &mut Vec<u8>,
        angle_flag: &mut Vec<u8>,
        candidates: &mut Vec<Step>,
        out: &mut RotDSpectrum,
    ) => run_any
}

/// The kernel of [`run`], compiled once per instruction set.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn run_any(
    w: &Work,
    sx: &mut State,
    sy: &mut State,
    ext: &mut Extremes,
    hull: &mut Vec<Hull>,
    inradius: &mut Vec<f64>,
    flag: &mut Vec<u8>,
    angle_flag: &mut Vec<u8>,
    candidates: &mut Vec<Step>,
    out: &mut RotDSpectrum,
) {
    let bank = w.bank;
    let (n, len) = (bank.padded, bank.len());
    sx.reset(n);
    sy.reset(n);
    // First pass: the samples that reach farthest along the directions and in |P|.
    ext.reset(n);
    for [x0, x1, y0, y1] in w.steps() {
        first_pass_step(&bank.k, n, x0, x1, y0, y1, sx, sy, ext);
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
        let pk = &mut out.per_angle[o * ANGLES..(o + 1) * ANGLES];
        for q in &ext.points(o, n) {
            for t in 0..ANGLES {
                pk[t] = pk[t].max((w.cos[t] * q[0] + w.sin[t] * q[1]).abs());
            }
        }
    }
    // Second pass: steps that may leave the hull update the angles.
    for a in [&mut sx.u, &mut sx.v, &mut sy.u, &mut sy.v] {
        a.fill(0.0);
    }
    flag.clear();
    flag.resize(n, 0);
    angle_flag.clear();
    angle_flag.resize(ANGLES, 0);
    candidates.clear();
    for [x0, x1, y0, y1] in w.steps() {
        if second_pass_step(&bank.k, n, x0, x1, y0, y1, sx, sy, inradius, flag) {
            for o in 0..len {
                if flag[o] != 0 {
                    let step = Step {
                        o,
                        ux: [sx.u[o], sx.u_next[o]],
                        uy: [sy.u[o], sy.u_next[o]],
                        vx: sx.v[o],
                        vy: sy.v[o],
                        x: [x0, x1],
                        y: [y0, y1],
                    };
                    if step.escapes(&bank.oscillators[o], &hull[o]) {
                        step.sample(w.cos, w.sin, &mut out.per_angle[o * ANGLES..(o + 1) * ANGLES]);
                        candidates.push(step);
                    }
                }
            }
        }
        std::mem::swap(&mut sx.u, &mut sx.u_next);
        std::mem::swap(&mut sx.v, &mut sx.v_next);
        std::mem::swap(&mut sy.u, &mut sy.u_next);
        std::mem::swap(&mut sy.v, &mut sy.v_next);
    }
    // The peaks at the samples are complete: the steps that escaped the hull are looked
    // inside where their bounds exceed them.
    // The smallest peak of each oscillator bounds a disc every angle's peak contains.
    for o in 0..len {
        inradius[o] = out.per_angle[o * ANGLES..(o + 1) * ANGLES].iter().fold(f64::INFINITY, |m, &p| m.min(p));
    }
    for step in candidates.iter() {
        let o = step.o;
        let pk = &mut out.per_angle[o * ANGLES..(o + 1) * ANGLES];
        step.refine(&bank.oscillators[o], inradius[o], w.cos, w.sin, pk, angle_flag);
    }
    // Free vibration after the record, angle by angle (skipped where its envelope cannot
    // reach the peak).
    for o in 0..len {
        let osc = &bank.oscillators[o];
        let (wn, xi) = (osc.omega(), osc.damping());
        let wd = wn * (1.0 - xi * xi).sqrt();
        let pk = &mut out.per_angle[o * ANGLES..(o + 1) * ANGLES];
        for t in 0..ANGLES {
            let u = w.cos[t] * sx.u[o] + w.sin[t] * sy.u[o];
            let v = w.cos[t] * sx.v[o] + w.sin[t] * sy.v[o];
            if u.hypot((v + xi * wn * u) / wd) > pk[t] {
                pk[t] = pk[t].max(osc.free_peak(u, v));
            }
        }
    }
}

/// First pass, one step: both recurrences in place, and the samples where |u_x|, |u_y| and |P|
/// peak.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn first_pass_step(
    k: &Coefficients,
    n: usize,
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    sx: &mut State,
    sy: &mut State,
    ext: &mut Extremes,
) {
    let (a11, a12, a21, a22) = (&k.a11[..n], &k.a12[..n], &k.a21[..n], &k.a22[..n]);
    let (bu0, bu1, bv0, bv1) = (&k.bu0[..n], &k.bu1[..n], &k.bv0[..n], &k.bv1[..n]);
    let (ux, vx, uy, vy) = (&mut sx.u[..n], &mut sx.v[..n], &mut sy.u[..n], &mut sy.v[..n]);
    for o in 0..n {
        let (u0, v0) = (ux[o], vx[o]);
        ux[o] = a11[o] * u0 + a12[o] * v0 + bu0[o] * x0 + bu1[o] * x1;
        vx[o] = a21[o] * u0 + a22[o] * v0 + bv0[o] * x0 + bv1[o] * x1;
        let (u0, v0) = (uy[o], vy[o]);
        uy[o] = a11[o] * u0 + a12[o] * v0 + bu0[o] * y0 + bu1[o] * y1;
        vy[o] = a21[o] * u0 + a22[o] * v0 + bv0[o] * y0 + bv1[o] * y1;
    }
    for j in 0..POINTS {
        let (c, s) = if j < DIRECTIONS.len() {
            let (s, c) = DIRECTIONS[j].to_radians().sin_cos();
            (c, s)
        } else {
            (0.0, 0.0)
        };
        let value = &mut ext.value[j * n..(j + 1) * n];
        let px = &mut ext.px[j * n..(j + 1) * n];
        let py = &mut ext.py[j * n..(j + 1) * n];
        let (ux, uy) = (&ux[..n], &uy[..n]);
        for o in 0..n {
            let (u, w) = (ux[o], uy[o]);
            let along = if j < DIRECTIONS.len() { (c * u + s * w).abs() } else { u * u + w * w };
            let take = along > value[o];
            value[o] = if take { along } else { value[o] };
            px[o] = if take { u } else { px[o] };
            py[o] = if take { w } else { py[o] };
        }
    }
}

/// Second pass, one step: both recurrences into the next states, flagging the oscillators whose
/// step may leave the disc inscribed in their hull; returns whether any is flagged.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn second_pass_step(
    k: &Coefficients,
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
    let (a11, a12, a21, a22) = (&k.a11[..n], &k.a12[..n], &k.a21[..n], &k.a22[..n]);
    let (bu0, bu1, bv0, bv1) = (&k.bu0[..n], &k.bu1[..n], &k.bv0[..n], &k.bv1[..n]);
    let (ky0, ky1, kd, xw) = (&k.ky0[..n], &k.ky1[..n], &k.kd[..n], &k.xw[..n]);
    let (iwd, iw2, c2) = (&k.iwd[..n], &k.iw2[..n], &k.c2[..n]);
    let (ux, vx, uxn, vxn) = (&sx.u[..n], &sx.v[..n], &mut sx.u_next[..n], &mut sx.v_next[..n]);
    let (uy, vy, uyn, vyn) = (&sy.u[..n], &sy.v[..n], &mut sy.u_next[..n], &mut sy.v_next[..n]);
    let (inradius, flag) = (&inradius[..n], &mut flag[..n]);
    let (dx, dy) = (x1 - x0, y1 - y0);
    let mut any = 0u8;
    for o in 0..n {
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

/// One step of one oscillator, both components: states at its start (and displacements at its
/// end), inputs at both ends.
#[derive(Clone, Copy, Debug)]
struct Step {
    o: usize,
    ux: [f64; 2],
    uy: [f64; 2],
    vx: f64,
    vy: f64,
    x: [f64; 2],
    y: [f64; 2],
}

impl Step {
    /// Whether the step may leave `hull` (the end sample, or the bounds inside the step).
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
        let mut any = 0u8;
        for t in 0..ANGLES {
            let (c, s) = (cos[t], sin[t]);
            let g = (c * p0[0] + s * p0[1]).abs().max((c * p1[0] + s * p1[1]).abs());
            let l = (c * lx0 + s * ly0).abs().max((c * lxh + s * lyh).abs());
            let f = ((g + r > pk[t]) & (l + zn > pk[t])) as u8;
            angle_flag[t] = f;
            any |= f;
        }
        if any == 0 {
            return;
        }
        for t in 0..ANGLES {
            if angle_flag[t] == 0 {
                continue;
            }
            let (c, s) = (cos[t], sin[t]);
            let (zr, zi) = (c * zx[0] + s * zy[0], c * zx[1] + s * zy[1]);
            let z = (zr * zr + zi * zi).sqrt();
            let g = (c * p0[0] + s * p0[1]).abs().max((c * p1[0] + s * p1[1]).abs());
            let l = (c * lx0 + s * ly0).abs().max((c * lxh + s * lyh).abs());
            if g + k * z > pk[t] && l + z > pk[t] {
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
