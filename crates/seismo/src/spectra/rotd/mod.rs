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
//! **Only the angles RotD50 and RotD100 depend on.** RotD50 is the mean of the 90th and 91st
//! smallest peak and RotD100 the largest, so most angles need no exact peak, only to be known on
//! which side of those values they lie. The 90th smallest peak is at least
//! `cos 45.5°·max_t|P(t)|` (every angle within 45.5° of `P`'s direction sees that much of it, and
//! a closed arc of 91° holds 91 of the 180 angles), so steps whose bounds stay below it or below
//! the 90th smallest of the hull's projections, whichever is larger (less a margin of 1e-6), are
//! not looked at, and an oscillator stops once its response to come stays below it. Each kept
//! step then gives every angle an interval: below, `|u_θ|` a quarter, half and three quarters into
//! the step; above, the smaller of the bounds above and the largest of those five points plus
//! `((h/4)²/8)·ω²|z_θ|`. An angle is solved exactly, by the same exact step solves as when every
//! angle is, while its interval meets the range where the middle values or the largest may lie;
//! when none does, those are values of solved angles and exact ([`RotDPlan::every_angle`] solves
//! all 180 and returns them; the tests check that both give the same bits). For the paper's
//! records (8 000 samples, 100 periods at 5%) this solves about 19 angles per oscillator and
//! halves the cost.
//!
//! With every angle solved, about 9× faster than the straightforward computation for a record of
//! 11 800 samples and 100 periods (`benches/response_spectra.rs` when it was measured); the steps
//! solved exactly are mostly those of
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
    Bank, CHECK, Reading, RecordEnd, Resampler, Running, SpectrumError, SpectrumPlan, State, check_finite, step_input,
    step_range, suffix_max,
};
use passes::{Extremes, Hull, POINTS, direction_cosines, first_pass_step, pair_settled, second_pass_step};
use select::{Selection, below_middle, median_floor, middle, select};

mod passes;
mod select;

/// Number of rotation angles: θ = 0°, 1°, …, 179°.
pub const ANGLES: usize = 180;

/// Everything that depends only on (Δt, periods, dampings, reading, record end), and the
/// rotation table.
#[derive(Clone, Debug)]
pub struct RotDPlan {
    plan: SpectrumPlan,
    cos: Vec<f64>,
    sin: Vec<f64>,
    every_angle: bool,
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
    /// Spectral displacement of every oscillator at every angle, `per_angle[o·180 + θ]`, from a
    /// plan made with [`RotDPlan::every_angle`]; empty otherwise.
    pub per_angle: Vec<f64>,
    /// Spectral displacement of the x component alone, bit for bit what
    /// [`SpectrumPlan::compute`] gives for it (the same passes give both).
    pub x: Vec<f64>,
    /// … and of the y component alone.
    pub y: Vec<f64>,
}

impl RotDSpectrum {
    /// The 180 spectral displacements of output `o` (θ = 0°…179°). Panics unless the plan was
    /// made with [`RotDPlan::every_angle`].
    pub fn angles(&self, o: usize) -> &[f64] {
        assert!(
            !self.per_angle.is_empty() || self.rotd50.is_empty(),
            "per-angle peaks are returned by a plan made with RotDPlan::every_angle"
        );
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
    /// Radius of the disc inscribed in each hull (padded), the second pass's disc: without every
    /// angle, at least the floor below RotD50.
    inradius: Vec<f64>,
    flag: Vec<u8>,
    angle_flag: Vec<u8>,
    /// Below RotD50, per oscillator (see [`median_floor`]).
    floor: Vec<f64>,
    refinement: Refinement,
    selection: Selection,
    sorted: Vec<f64>,
    /// The 180 peaks of every oscillator in the bank's order, and |(x, y)| of each sample.
    per_angle: Vec<f64>,
    points: Vec<f64>,
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
        RotDPlan { plan, cos, sin, every_angle: false }
    }

    /// The same plan solving every angle's peak exactly and returning the 180 of them in
    /// [`RotDSpectrum::per_angle`] (slower). Without it only the angles RotD50 and RotD100
    /// depend on are solved, `per_angle` is left empty, and RotD50, RotD100, its angle and each
    /// component's spectrum are the same bits either way.
    pub fn every_angle(mut self) -> Self {
        self.every_angle = true;
        self
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

    /// RotD50, RotD100 (and its angle), each component's spectrum and, with
    /// [`RotDPlan::every_angle`], the 180 per-angle spectral displacements of the horizontal
    /// components `x` and `y` (accelerations sampled alike, in one unit) into `out` (resized to
    /// `len()` outputs). Two empty records give zeros.
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
        if self.every_angle {
            out.per_angle.resize(n * ANGLES, 0.0);
        }
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
            every_angle: self.every_angle,
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
            floor,
            refinement,
            selection,
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
        let mut v =
            Vectors { sx, sy, running, rest: [rest_x, rest_y, rest_p], ext, hull, inradius, floor, flag, per_angle };
        run(Isa::current(), &w, &mut v, angle_flag, refinement, selection);
        // Each component's spectrum, the summaries and (if asked) the 180 peaks, in the output's
        // order. Without every angle, the angles not solved are below RotD100 and on their side
        // of RotD50's two middle values (see `select`): the largest, its first angle and the
        // middle of the sorted peaks are those of the solved peaks.
        let bank = self.plan.bank();
        for (o, osc) in bank.oscillators.iter().enumerate() {
            let at = bank.output[o];
            let stopped = v.running.stopped(o);
            for (s, out) in [(&*v.sx, &mut out.x), (&*v.sy, &mut out.y)] {
                out[at] = if stopped { s.peak[o] } else { s.peak[o].max(osc.free_peak(s.u[o], s.v[o])) };
            }
            let peaks = &v.per_angle[o * ANGLES..(o + 1) * ANGLES];
            if self.every_angle {
                out.per_angle[at * ANGLES..(at + 1) * ANGLES].copy_from_slice(peaks);
            }
            let (mut best, mut angle) = (peaks[0], 0);
            for (t, &p) in peaks.iter().enumerate() {
                if p > best {
                    (best, angle) = (p, t);
                }
            }
            out.rotd100[at] = best;
            out.rotd100_angle_deg[at] = angle as f64;
            let (ninetieth, ninety_first) = middle(peaks, sorted);
            out.rotd50[at] = 0.5 * (ninetieth + ninety_first);
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
    every_angle: bool,
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
    floor: &'a mut Vec<f64>,
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
        refinement: &mut Refinement,
        selection: &mut Selection,
    ) => run_any
}

/// The kernel of [`run`], compiled once per instruction set.
#[inline(always)]
fn run_any(
    w: &Work,
    v: &mut Vectors,
    angle_flag: &mut Vec<u8>,
    refinement: &mut Refinement,
    selection: &mut Selection,
) {
    let bank = w.bank;
    let (n, len) = (bank.padded, bank.len());
    let Vectors { sx, sy, running, rest: [rest_x, rest_y, rest_p], ext, hull, inradius, floor, flag, per_angle } = v;
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
            running.settle(k, n, |o| pair_settled(&bank.k, o, n, sx, sy, ext, rests, w.every_angle));
            if running.first == n {
                break;
            }
        }
    }
    hull.clear();
    inradius.clear();
    inradius.resize(n, 0.0);
    floor.clear();
    floor.resize(n, 0.0);
    for o in 0..n {
        let h = Hull::of(&ext.points(o, n));
        hull.push(h);
        inradius[o] = h.inradius();
        // Without every angle, the steps that stay inside the disc below RotD50 need no look.
        if !w.every_angle {
            floor[o] = median_floor(ext.value[(POINTS - 1) * n + o]);
            inradius[o] = inradius[o].max(floor[o]);
        }
    }
    // Every angle starts from the recorded points' projections.
    for o in 0..len {
        let pk = &mut per_angle[o * ANGLES..(o + 1) * ANGLES];
        for q in &ext.points(o, n) {
            for t in 0..ANGLES {
                pk[t] = pk[t].max((w.cos[t] * q[0] + w.sin[t] * q[1]).abs());
            }
        }
        // Without every angle, the 90th smallest of these is below RotD50 too: a larger disc
        // for the second pass.
        if !w.every_angle {
            floor[o] = floor[o].max(below_middle(pk, &mut selection.work));
            inradius[o] = inradius[o].max(floor[o]);
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
    let candidates = &mut refinement.candidates;
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
    // inside where their bounds exceed them, oscillator by oscillator (each one's steps in
    // their order), then the free vibration after the record (for the oscillators that did not
    // stop: theirs cannot reach the peaks).
    refinement.group(len);
    let Refinement { steps, starts, .. } = &*refinement;
    for o in 0..len {
        let osc = &bank.oscillators[o];
        let pk = &mut per_angle[o * ANGLES..(o + 1) * ANGLES];
        let kept = &steps[starts[o]..starts[o + 1]];
        let free = (!running.stopped(o)).then(|| Free::new(osc, [sx.u[o], sx.v[o]], [sy.u[o], sy.v[o]]));
        if w.every_angle {
            // The smallest peak bounds a disc every angle's peak contains.
            let disc = pk.iter().fold(f64::INFINITY, |m, &p| m.min(p));
            for step in kept {
                step.refine(osc, disc, w.cos, w.sin, pk, angle_flag);
            }
            if let Some(free) = &free {
                for t in 0..ANGLES {
                    pk[t] = free.raise(osc, w.cos[t], w.sin[t], pk[t]);
                }
            }
        } else {
            select(osc, kept, free.as_ref(), floor[o], w.cos, w.sin, pk, selection);
        }
    }
}

/// The free vibration of both components after the record, from their states at its end.
struct Free {
    x: [f64; 2],
    y: [f64; 2],
    /// ξω and 1/ω_d.
    xw: f64,
    wd: f64,
}

impl Free {
    fn new(osc: &Oscillator, x: [f64; 2], y: [f64; 2]) -> Self {
        let (wn, xi) = (osc.omega(), osc.damping());
        Free { x, y, xw: xi * wn, wd: wn * (1.0 - xi * xi).sqrt() }
    }

    /// The rotated state at angle `(c, s)` and its free vibration's envelope (its largest |u| is
    /// at most that).
    #[inline(always)]
    fn envelope(&self, c: f64, s: f64) -> (f64, f64, f64) {
        let u = c * self.x[0] + s * self.y[0];
        let v = c * self.x[1] + s * self.y[1];
        (u, v, u.hypot((v + self.xw * u) / self.wd))
    }

    /// `peak` raised to the free vibration's largest |u| at angle `(c, s)` (looked for only where
    /// the envelope exceeds it).
    #[inline(always)]
    fn raise(&self, osc: &Oscillator, c: f64, s: f64, peak: f64) -> f64 {
        let (u, v, envelope) = self.envelope(c, s);
        if envelope > peak { peak.max(osc.free_peak(u, v)) } else { peak }
    }
}

/// Work arrays of the refinement (reused across records).
#[derive(Default)]
struct Refinement {
    /// The steps that may leave the hull, in step order across oscillators.
    candidates: Vec<Step>,
    /// The same grouped by oscillator, each group in step order, and where each group starts.
    steps: Vec<Step>,
    starts: Vec<usize>,
    fill: Vec<usize>,
}

impl Refinement {
    /// Groups the candidates by oscillator (`len` of them), keeping their order in each group.
    fn group(&mut self, len: usize) {
        let Refinement { candidates, steps, starts, fill } = self;
        starts.clear();
        starts.resize(len + 1, 0);
        for c in candidates.iter() {
            starts[c.o + 1] += 1;
        }
        for o in 0..len {
            starts[o + 1] += starts[o];
        }
        fill.clear();
        fill.extend_from_slice(&starts[..len]);
        steps.clear();
        steps.resize(candidates.len(), Step::default());
        for c in candidates.iter() {
            steps[fill[c.o]] = *c;
            fill[c.o] += 1;
        }
    }
}

/// One step of one oscillator, both components: states at its start (and displacements at its
/// end), inputs at both ends.
#[derive(Clone, Copy, Debug, Default)]
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

    /// What the step's bounds at every angle share, or `None` when the step stays inside the
    /// disc of radius `disc` (every angle's peak is at least that): nothing to do.
    #[inline(always)]
    fn reach(&self, osc: &Oscillator, disc: f64) -> Option<Reach> {
        let (lx0, lxh, zx) = osc.envelope(self.ux[0], self.vx, self.x[0], self.x[1]);
        let (ly0, lyh, zy) = osc.envelope(self.uy[0], self.vy, self.y[0], self.y[1]);
        let k = (osc.h() * osc.omega()).powi(2) / 8.0;
        let zn = (zx[0] * zx[0] + zx[1] * zx[1] + zy[0] * zy[0] + zy[1] * zy[1]).sqrt();
        let r = k * zn;
        let (p0, p1) = ([self.ux[0], self.uy[0]], [self.ux[1], self.uy[1]]);
        let reach_p = (p0[0] * p0[0] + p0[1] * p0[1]).max(p1[0] * p1[0] + p1[1] * p1[1]).sqrt() + r;
        let reach_l = (lx0 * lx0 + ly0 * ly0).max(lxh * lxh + lyh * lyh).sqrt() + zn;
        if reach_p.min(reach_l) <= disc {
            return None;
        }
        let (tc, ts, turns) = match osc.turn() {
            Some((c, s)) => (c, s, true),
            None => (1.0, 0.0, false),
        };
        Some(Reach {
            l: [lx0, ly0, lxh, lyh],
            zx,
            zy,
            p0,
            p1,
            k,
            curve: 2.0 * k * osc.omega(),
            rounding: 1e-9 * (self.vx.abs() + self.vy.abs() + self.vx1.abs() + self.vy1.abs()),
            zn,
            turn: (tc, ts, turns),
        })
    }

    /// The largest `|u_θ|` inside the step can be at angle `(c, s)`, by the cheapest bounds;
    /// zero when the step has no interior extremum at that angle (its largest |u_θ| is then at
    /// an end, a sample already in the peak).
    ///
    /// With the angle's own `|z_θ|`: an interior extremum is a zero of u̇_θ, of which there is
    /// none when u̇_θ keeps one sign at both ends and stays farther from zero than
    /// (h²/8)·ω³|z_θ| bounds its departure from the chord (twice that, and a rounding allowance,
    /// as step_peak's own test sees slightly different roundings). The harmonic part
    /// y_θ(τ) = e^{−ξωτ}·|z_θ|·cos(ω_dτ + arg z_θ) reaches |z_θ| inside the step only where cos
    /// does, i.e. where Im(z_θ·e^{iω_dτ}) changes sign (ω_d·h < π: at most once); elsewhere |y_θ|
    /// stays below its larger end value without the decay, so
    /// |u_θ| ≤ max|L_θ| + max(|Re z_θ|, |Re(z_θ·e^{iω_dh})|). Otherwise |u_θ| is at most the
    /// chord's end plus (h²/8)·ω²|z_θ|, and at most max|L_θ| + |z_θ|. Compared with a peak with
    /// a relative margin of 1e-9: when the bound cannot beat it, step_peak would return the peak.
    #[inline(always)]
    fn bound(&self, r: &Reach, c: f64, s: f64) -> f64 {
        let [lx0, ly0, lxh, lyh] = r.l;
        let (zr, zi) = (c * r.zx[0] + s * r.zy[0], c * r.zx[1] + s * r.zy[1]);
        let z = (zr * zr + zi * zi).sqrt();
        let g = r.ends(c, s);
        let l = (c * lx0 + s * ly0).abs().max((c * lxh + s * lyh).abs());
        let (v0, v1) = (c * self.vx + s * self.vy, c * self.vx1 + s * self.vy1);
        let monotone = (v0 * v1 > 0.0) & (v0.abs().min(v1.abs()) > r.curve * z + r.rounding);
        let (tc, ts, turns) = r.turn;
        let (er, ei) = (zr * tc - zi * ts, zr * ts + zi * tc);
        let harmonic = if turns & (zi * ei > 0.0) { zr.abs().max(er.abs()) } else { z };
        if monotone { 0.0 } else { (g + r.k * z).min(l + harmonic) }
    }

    /// The exact `max(peak, largest |u_θ| inside the step)` at angle `(c, s)`: the step of the
    /// rotated input, as one component's.
    #[inline(always)]
    fn solve_at(&self, osc: &Oscillator, c: f64, s: f64, peak: f64) -> f64 {
        osc.step_peak(
            c * self.ux[0] + s * self.uy[0],
            c * self.vx + s * self.vy,
            c * self.x[0] + s * self.y[0],
            c * self.x[1] + s * self.y[1],
            peak,
        )
    }

    /// Raises the 180 peaks `pk` to the exact peak inside the step, for the angles whose
    /// bounds exceed their peak: first against the disc of radius `disc` (the smallest peak),
    /// then angle by angle (see [`Step::bound`]), side by side across angles.
    #[inline(always)]
    fn refine(&self, osc: &Oscillator, disc: f64, cos: &[f64], sin: &[f64], pk: &mut [f64], angle_flag: &mut [u8]) {
        let Some(r) = self.reach(osc, disc) else { return };
        let (cos, sin, pk, angle_flag) = (&cos[..ANGLES], &sin[..ANGLES], &mut pk[..ANGLES], &mut angle_flag[..ANGLES]);
        let mut any = 0u8;
        for t in 0..ANGLES {
            let f = (self.bound(&r, cos[t], sin[t]) * (1.0 + 1e-9) > pk[t]) as u8;
            angle_flag[t] = f;
            any |= f;
        }
        if any == 0 {
            return;
        }
        for t in 0..ANGLES {
            if angle_flag[t] != 0 {
                pk[t] = self.solve_at(osc, cos[t], sin[t], pk[t]);
            }
        }
    }
}

impl Reach {
    /// The larger `|u_θ|` of the step's two ends at angle `(c, s)`.
    #[inline(always)]
    fn ends(&self, c: f64, s: f64) -> f64 {
        (c * self.p0[0] + s * self.p0[1]).abs().max((c * self.p1[0] + s * self.p1[1]).abs())
    }
}

/// What a kept step's bounds share across angles (see [`Step::reach`]).
struct Reach {
    /// `L_x(0)`, `L_y(0)`, `L_x(h)`, `L_y(h)`.
    l: [f64; 4],
    zx: [f64; 2],
    zy: [f64; 2],
    p0: [f64; 2],
    p1: [f64; 2],
    /// (ωh)²/8, and twice that times ω.
    k: f64,
    curve: f64,
    rounding: f64,
    /// `(cos, sin)` of ω_d·h and whether it is below π.
    turn: (f64, f64, bool),
    /// The joint amplitude `|Z| = (|z_x|² + |z_y|²)^½`.
    zn: f64,
}
