//! Elastic response spectra of a ground-acceleration record, with the exact peak between
//! samples, for the chosen reading of the samples (Nigam & Jennings 1969).
//!
//! Each oscillator `ü + 2ξωu̇ + ω²u = −a(t)` starts from rest at the first sample and is advanced
//! over each step with the exact solution for an input linear inside the step,
//! `[u, u̇]ₙ₊₁ = A·[u, u̇]ₙ + B·[aₙ, aₙ₊₁]` (coefficients computed once per oscillator at plan
//! time, see [`crate::spectra::oscillator`]). `SD = max |u(t)|` over the whole response,
//! `PSV = ω·SD`, `PSA = ω²·SD` at every period (PSA is never replaced by PGA at short periods).
//!
//! **Exact peak between samples.** Inside a step `u(τ) = L(τ) + y(τ)` with `L` linear and `y`
//! a damped harmonic of complex amplitude `z` (`|y(τ)| ≤ |z|`, `|ü(τ)| ≤ ω²|z|`). Two bounds of
//! `|u|` inside the step cost a few operations per oscillator and step:
//!
//! ```text
//! B₁ = max(|L(0)|, |L(h)|) + |z|                  (harmonic envelope),
//! B₂ = max(|uₙ|, |uₙ₊₁|) + (h²/8)·ω²|z|            (an interior extremum is within h/2 of an end).
//! ```
//!
//! A first pass runs the plain recurrence and keeps the peak at the samples, `P_s`, a value
//! the response reaches. A second pass runs it again with the bounds, and only where both
//! exceed the running peak (at least `P_s`) is the step solved exactly
//! ([`Oscillator::step_peak`]: cheaper bounds first, then the zeros of `u̇` inside the step,
//! where `|u|` is evaluated). Few steps come near `P_s`, so the work is two vector passes
//! across oscillators (structure of arrays, compiled for every build of [`stickslip_isa::Isa`]
//! — AVX-512, AVX2, baseline x86-64 — by `stickslip_isa::widest!`, the widest the CPU has
//! picked at run time; Rust never fuses a multiply and an add, so all give the same bits,
//! which `tests/builds.rs` checks build against build and against a plain loop over the
//! oscillators) and a few exact solves per oscillator: about half the time of a plain compiled
//! Nigam–Jennings loop that reads the peak at the samples only (`benches/response_spectra.rs`).
//!
//! **Accuracy.** The result is the true `max |u(t)|` of the reading, to rounding: within
//! **1e-12 relative** of a dense reference (RK4 with 2 000 to 8 000 steps per period and a
//! cubic Hermite search between steps), tested on random records for periods from Δt/200 to
//! 1000·Δt and dampings 0 to 20%, on a 1 m/s velocity impulse whose peak falls between samples,
//! on a resonant sine and on a record that ends at its largest value (largest difference
//! measured: 6e-13; checked once on a record of 41 200 samples at 0.02 to 10 s: 1.2e-13).
//!
//! **Conventions.**
//! - The oscillator is at rest at the first sample, where the input is `a₀` (no ramp before it).
//! - **Linear** reading: straight lines between samples. A sine of period T₀ sampled at Δt is
//!   then seen with its amplitude reduced by `sinc²(Δt/T₀)`.
//! - **Band-limited** reading: the samples are first resampled `oversampling` times finer by FFT
//!   zero padding (Whittaker–Shannon interpolation of the zero-padded record), so a sampled sine
//!   below Nyquist is seen at its true amplitude; the record is zero outside its span, so a
//!   record that does not start and end near zero rings at its ends.
//! - **After the record** ([`RecordEnd::Ramp`], the default): the record is continued by zeros
//!   read the same way, i.e. the input ramps from the last sample to zero over one more sample
//!   interval (for the band-limited reading: the interpolant up to the appended zero sample),
//!   and the oscillator then vibrates freely; its first free extremum is in closed form and
//!   later ones are smaller. This is what a Nigam–Jennings code gives on the record padded
//!   with trailing zeros, the usual practice (Boore 2005, "On pads and filters", BSSA 95(2));
//!   checked against eqsig 1.2.17's `pseudo_response_spectra` on a padded record (equal up to
//!   its peak read at the samples). Run on the bare record, such a code misses the free
//!   vibration altogether. [`RecordEnd::Step`] keeps the older convention of this project:
//!   free vibration from the state at the last sample (the input steps to zero there); on a
//!   record that ends at a large value it differs by several to tens of percent where the free
//!   vibration holds the peak (tested).
//!
//! A [`SpectrumPlan`] holds everything that depends only on (Δt, periods, dampings, reading,
//! record end) and is reused across records; a [`SpectrumScratch`] holds the per-record work
//! arrays, so computing a record allocates nothing once the scratch has grown to the largest
//! record.

use std::f64::consts::PI;
use std::sync::Arc;

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlanner};
use stickslip_isa::{Isa, widest};

use crate::spectra::oscillator::Oscillator;
pub use crate::spectra::oscillator::free_vibration_peak;

pub use crate::error::SpectrumError;

/// How the samples of a record are read between sample times.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reading {
    /// Straight lines between samples.
    Linear,
    /// FFT-resampled (band-limited) before the linear reading.
    BandLimited,
}

/// What the oscillators see after the last sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum RecordEnd {
    /// The record continued by zeros read the same way: a ramp to zero over one more sample
    /// interval, then free vibration (the usual convention).
    #[default]
    Ramp,
    /// Free vibration from the state at the last sample (the input steps to zero there).
    Step,
}

/// `n` log-spaced periods from `min` to `max` (s, inclusive; the ends are exactly `min` and
/// `max`; for 0 < min ≤ max, otherwise the plans refuse them).
pub fn log_periods(min: f64, max: f64, n: usize) -> Vec<f64> {
    match n {
        0 => vec![],
        1 => vec![min],
        _ => {
            let (a, b) = (min.ln(), max.ln());
            (0..n)
                .map(|i| match i {
                    0 => min,
                    i if i == n - 1 => max,
                    i => (a + (b - a) * i as f64 / (n - 1) as f64).exp(),
                })
                .collect()
        }
    }
}

/// Oscillators are padded to a multiple of this (the padding is at rest and never flagged), and
/// stop in groups of this many, so the loops across oscillators split evenly into vector
/// registers.
pub(crate) const LANES: usize = 8;

/// Step coefficients and bound constants of every oscillator, one array each (structure of
/// arrays, so the loops across oscillators are vector loops), in the bank's order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Coefficients {
    pub a11: Vec<f64>,
    pub a12: Vec<f64>,
    pub a21: Vec<f64>,
    pub a22: Vec<f64>,
    pub bu0: Vec<f64>,
    pub bu1: Vec<f64>,
    pub bv0: Vec<f64>,
    pub bv1: Vec<f64>,
    /// `−L(0) = ky0·a₀ + ky1·a₁`, so `y₀ = u₀ − L(0)`.
    pub ky0: Vec<f64>,
    pub ky1: Vec<f64>,
    /// `ẏ₀ = u̇₀ + kd·(a₁ − a₀)`.
    pub kd: Vec<f64>,
    /// ξω, 1/ω_d, 1/ω².
    pub xw: Vec<f64>,
    pub iwd: Vec<f64>,
    pub iw2: Vec<f64>,
    /// `((ωh)²/8)²`: the square of B₂'s factor on |z|.
    pub c2: Vec<f64>,
    /// `∫₀^∞ |h(s)| ds = coth(πξ/(2√(1−ξ²)))/ω²` of the impulse response
    /// `h(s) = e^{−ξωs}·sin(ω_d s)/ω_d`: the largest |u| an input bounded by 1 can drive from
    /// rest (∞ undamped, 0 for the padding).
    pub gain: Vec<f64>,
}

/// The oscillators of a plan in the order they settle (see [`Bank::new`]), scalar and as arrays
/// of coefficients padded to `padded`; `output[o]` is the output (damping-major) of oscillator
/// `o` of the bank.
#[derive(Clone, Debug)]
pub(crate) struct Bank {
    pub oscillators: Vec<Oscillator>,
    pub output: Vec<usize>,
    pub padded: usize,
    pub k: Coefficients,
}

impl Bank {
    /// The bank of `oscillators` (given in output order), put in the order they settle after a
    /// record: by period, the more damped first, the undamped last (they never settle while
    /// input remains), so the oscillators still running are always a tail of the bank.
    fn new(oscillators: Vec<Oscillator>) -> Self {
        let mut output: Vec<usize> = (0..oscillators.len()).collect();
        let key = |o: &Oscillator| (o.damping() == 0.0, 1.0 / o.omega(), -o.damping());
        output.sort_by(|&i, &j| {
            let (a, b) = (key(&oscillators[i]), key(&oscillators[j]));
            a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)).then(a.2.total_cmp(&b.2)).then(i.cmp(&j))
        });
        let oscillators: Vec<Oscillator> = output.iter().map(|&i| oscillators[i]).collect();
        let padded = oscillators.len().div_ceil(LANES) * LANES;
        let mut k = Coefficients::default();
        for osc in &oscillators {
            let [a11, a12, a21, a22, bu0, bu1, bv0, bv1] = osc.coefficients();
            let (w, xi, h) = (osc.omega(), osc.damping(), osc.h());
            let wd = w * (1.0 - xi * xi).sqrt();
            let c = 2.0 * xi / (w * w * w * h);
            k.a11.push(a11);
            k.a12.push(a12);
            k.a21.push(a21);
            k.a22.push(a22);
            k.bu0.push(bu0);
            k.bu1.push(bu1);
            k.bv0.push(bv0);
            k.bv1.push(bv1);
            k.ky0.push(1.0 / (w * w) + c);
            k.ky1.push(-c);
            k.kd.push(1.0 / (w * w * h));
            k.xw.push(xi * w);
            k.iwd.push(1.0 / wd);
            k.iw2.push(1.0 / (w * w));
            k.c2.push(((w * h).powi(2) / 8.0).powi(2));
            k.gain.push(if xi > 0.0 {
                1.0 / (0.5 * PI * xi / (1.0 - xi * xi).sqrt()).tanh() / (w * w)
            } else {
                f64::INFINITY
            });
        }
        for a in [
            &mut k.a11,
            &mut k.a12,
            &mut k.a21,
            &mut k.a22,
            &mut k.bu0,
            &mut k.bu1,
            &mut k.bv0,
            &mut k.bv1,
            &mut k.ky0,
            &mut k.ky1,
            &mut k.kd,
            &mut k.xw,
            &mut k.iwd,
            &mut k.iw2,
            &mut k.c2,
            &mut k.gain,
        ] {
            a.resize(padded, 0.0);
        }
        Bank { oscillators, output, padded, k }
    }

    pub fn len(&self) -> usize {
        self.oscillators.len()
    }
}

/// States of every oscillator (padded): the current one, the next one, the running peak, and
/// the oscillators flagged in the last step.
#[derive(Default)]
pub(crate) struct State {
    pub u: Vec<f64>,
    pub v: Vec<f64>,
    pub u_next: Vec<f64>,
    pub v_next: Vec<f64>,
    pub peak: Vec<f64>,
    pub flag: Vec<u8>,
}

impl State {
    /// At rest, peaks zero, for `n` (padded) oscillators.
    pub fn reset(&mut self, n: usize) {
        for a in [&mut self.u, &mut self.v, &mut self.u_next, &mut self.v_next, &mut self.peak] {
            a.clear();
            a.resize(n, 0.0);
        }
        self.flag.clear();
        self.flag.resize(n, 0);
    }
}

/// Below this fraction of its peak, a bound on an oscillator's response for the rest of the
/// record lets it stop (the margin covers the rounding of the bound and of the recurrence).
pub(crate) const SETTLED: f64 = 1.0 - 1e-9;

/// Steps between two looks at which oscillators have settled.
pub(crate) const CHECK: usize = 32;

/// Which oscillators still run: the bank's tail from `first`. The first pass records when
/// `first` moved (`moves`: after step `k`, to `first`); the second pass replays it.
#[derive(Default)]
pub(crate) struct Running {
    pub first: usize,
    pub moves: Vec<(usize, usize)>,
    next: usize,
}

impl Running {
    /// Every oscillator runs.
    pub fn start(&mut self) {
        (self.first, self.next) = (0, 0);
        self.moves.clear();
    }

    /// Every oscillator runs again, for the second pass.
    pub fn replay(&mut self) {
        (self.first, self.next) = (0, 0);
    }

    /// Moves `first` past the groups of [`LANES`] at its front for which `done(group start)`,
    /// after step `k`.
    pub fn settle(&mut self, k: usize, n: usize, mut done: impl FnMut(usize) -> bool) {
        let before = self.first;
        while self.first < n && done(self.first) {
            self.first += LANES;
        }
        if self.first != before {
            self.moves.push((k, self.first));
        }
    }

    /// In the second pass, after step `k`: `first` as the first pass had it.
    pub fn replayed(&mut self, k: usize) {
        while self.next < self.moves.len() && self.moves[self.next].0 == k {
            self.first = self.moves[self.next].1;
            self.next += 1;
        }
    }

    /// Whether oscillator `o` stopped (its peak is final).
    pub fn stopped(&self, o: usize) -> bool {
        self.moves.last().is_some_and(|&(_, first)| o < first)
    }
}

/// `out[j] = max |x[i]|` over `i ≥ j`, with `out[x.len()] = 0` (the input after the record).
pub(crate) fn suffix_max(x: &[f64], out: &mut Vec<f64>) {
    out.clear();
    out.resize(x.len() + 1, 0.0);
    for j in (0..x.len()).rev() {
        out[j] = out[j + 1].max(x[j].abs());
    }
}

/// The steps of a record of `n` samples: `n − 1` between samples, and one more to zero if
/// `ramp`; from the first one that can move an oscillator at rest (the step into the first
/// non-zero sample: before it, input and state are exactly zero).
pub(crate) fn step_range(x: &[f64], ramp: bool) -> std::ops::Range<usize> {
    let n = x.len();
    let steps = if n == 0 { 0 } else { n - 1 + ramp as usize };
    let first = x.iter().position(|&a| a != 0.0).map_or(steps, |i| i.saturating_sub(1)).min(steps);
    first..steps
}

/// The input at both ends of step `k` of `x` (zero after the last sample).
#[inline(always)]
pub(crate) fn step_input(x: &[f64], k: usize) -> (f64, f64) {
    (x[k], if k + 1 < x.len() { x[k + 1] } else { 0.0 })
}

/// Whether none of the [`LANES`] oscillators from `o` can raise its peak any more: from the
/// state `(u, u̇)` the free vibration stays within `A = √(u² + ((u̇ + ξωu)/ω_d)²)`, and the
/// response from rest to the rest of the input, whose largest |value| is `rest`, within
/// `rest·∫|h|`; when their sum is below the peak reached (with the [`SETTLED`] margin), every
/// later |u| is below it too, so the peak is final (this is exact: the outputs do not change).
pub(crate) fn settled(k: &Coefficients, o: usize, u: &[f64], v: &[f64], peak: &[f64], rest: f64) -> bool {
    (o..o + LANES).all(|o| {
        let w = (v[o] + k.xw[o] * u[o]) * k.iwd[o];
        let forced = if rest == 0.0 { 0.0 } else { rest * k.gain[o] };
        (u[o] * u[o] + w * w).sqrt() + forced <= SETTLED * peak[o]
    })
}

/// Everything that depends only on (Δt, periods, dampings, reading, record end).
#[derive(Clone, Debug)]
pub struct SpectrumPlan {
    dt: f64,
    periods: Vec<f64>,
    dampings: Vec<f64>,
    reading: Reading,
    oversampling: usize,
    end: RecordEnd,
    /// Whether blocks stop once settled (always, except to check that it changes nothing).
    settle: bool,
    bank: Bank,
}

/// Work arrays of one record (reuse across records: no allocation once grown).
#[derive(Default)]
pub struct SpectrumScratch {
    state: State,
    running: Running,
    rest: Vec<f64>,
    pub(crate) resampler: Resampler,
}

impl SpectrumPlan {
    /// Plans spectra of records sampled every `dt` seconds, at `periods` (s, > 0) and `dampings`
    /// (fractions of critical, 0 ≤ ξ < 1), with [`RecordEnd::Ramp`]. `oversampling` is used by
    /// the band-limited reading only (16 keeps the straight-line error below 0.05% up to a
    /// tenth of the sampling rate; 0 counts as 1).
    pub fn new(
        dt: f64,
        periods: &[f64],
        dampings: &[f64],
        reading: Reading,
        oversampling: usize,
    ) -> Result<Self, SpectrumError> {
        check(dt, periods, dampings)?;
        let oversampling = if reading == Reading::BandLimited { oversampling.max(1) } else { 1 };
        let h = dt / oversampling as f64;
        let oscillators =
            dampings.iter().flat_map(|&xi| periods.iter().map(move |&t| Oscillator::new(t, xi, h))).collect();
        Ok(SpectrumPlan {
            dt,
            periods: periods.to_vec(),
            dampings: dampings.to_vec(),
            reading,
            oversampling,
            end: RecordEnd::Ramp,
            settle: true,
            bank: Bank::new(oscillators),
        })
    }

    /// The same plan with another convention after the record's end.
    pub fn with_record_end(mut self, end: RecordEnd) -> Self {
        self.end = end;
        self
    }

    /// The same plan advancing every oscillator through every step, never stopping a block that
    /// has settled: the same outputs, bit for bit, slower (to check that stopping changes
    /// nothing).
    pub fn exhaustive(mut self) -> Self {
        self.settle = false;
        self
    }

    pub(crate) fn settles(&self) -> bool {
        self.settle
    }

    /// Sampling interval the plan is for (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Periods (s).
    pub fn periods(&self) -> &[f64] {
        &self.periods
    }

    /// Damping ratios.
    pub fn dampings(&self) -> &[f64] {
        &self.dampings
    }

    /// Reading of the samples.
    pub fn reading(&self) -> Reading {
        self.reading
    }

    /// Convention after the record's end.
    pub fn record_end(&self) -> RecordEnd {
        self.end
    }

    /// Number of outputs (`dampings × periods`, damping-major).
    pub fn len(&self) -> usize {
        self.bank.len()
    }

    /// Whether the plan has no oscillator.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    pub(crate) fn bank(&self) -> &Bank {
        &self.bank
    }

    pub(crate) fn oversampling(&self) -> usize {
        self.oversampling
    }

    /// Spectral displacement `SD = max |u(t)|` (in the record's length unit, for an
    /// acceleration in that unit per s²) of `accel` for every (damping, period), damping-major,
    /// into `sd`. PSV = ω·SD, PSA = ω²·SD. An empty record gives zeros.
    ///
    /// # Panics
    /// If `sd.len() != self.len()`.
    pub fn compute(&self, accel: &[f64], scratch: &mut SpectrumScratch, sd: &mut [f64]) -> Result<(), SpectrumError> {
        assert_eq!(sd.len(), self.len(), "one output per (damping, period)");
        check_finite(accel, "record")?;
        sd.fill(0.0);
        if accel.is_empty() {
            return Ok(());
        }
        let SpectrumScratch { state: st, running, rest, resampler } = scratch;
        let x = match self.reading {
            Reading::Linear => accel,
            Reading::BandLimited => resampler.resample(accel, self.oversampling, self.end == RecordEnd::Ramp),
        };
        let ramp = self.reading == Reading::Linear && self.end == RecordEnd::Ramp;
        suffix_max(x, rest);
        run(Isa::current(), &self.bank, x, ramp, self.settle, rest, running, st);
        for (o, osc) in self.bank.oscillators.iter().enumerate() {
            // A stopped oscillator has its final peak; the others vibrate freely after the record.
            sd[self.bank.output[o]] =
                if running.stopped(o) { st.peak[o] } else { st.peak[o].max(osc.free_peak(st.u[o], st.v[o])) };
        }
        Ok(())
    }
}

/// Refuses a non-positive or non-finite interval or period, or a damping outside [0, 1).
pub(crate) fn check(dt: f64, periods: &[f64], dampings: &[f64]) -> Result<(), SpectrumError> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(SpectrumError::Interval { dt });
    }
    if let Some((index, &value)) = periods.iter().enumerate().find(|(_, t)| !(**t > 0.0 && t.is_finite())) {
        return Err(SpectrumError::Period { index, value });
    }
    if let Some((index, &value)) = dampings.iter().enumerate().find(|(_, x)| !(0.0..1.0).contains(*x)) {
        return Err(SpectrumError::Damping { index, value });
    }
    Ok(())
}

/// Refuses a record with a NaN or infinite sample.
pub(crate) fn check_finite(x: &[f64], component: &'static str) -> Result<(), SpectrumError> {
    match x.iter().position(|v| !v.is_finite()) {
        Some(index) => Err(SpectrumError::NonFinite { component, index, value: x[index] }),
        None => Ok(()),
    }
}

widest! {
    /// Advances every oscillator of `bank` from rest through `x` (read linearly between
    /// samples, then, if `ramp`, one more step to zero), keeping the exact peak |u|, in
    /// instruction set `isa`; with `settle`, the oscillators whose response can no longer reach
    /// their peak stop (`running`; `rest` is the largest |x| from each sample on). `st` ends
    /// with the peaks and the final states of the oscillators that ran to the end.
    #[allow(clippy::too_many_arguments)]
    fn run(
        bank: &Bank,
        x: &[f64],
        ramp: bool,
        settle: bool,
        rest: &[f64],
        running: &mut Running,
        st: &mut State,
    ) => run_any
}

/// The kernel of [`run`], compiled once per instruction set.
#[inline(always)]
fn run_any(bank: &Bank, x: &[f64], ramp: bool, settle: bool, rest: &[f64], running: &mut Running, st: &mut State) {
    let n = bank.padded;
    st.reset(n);
    running.start();
    let steps = step_range(x, ramp);
    let first = steps.start;
    // First pass: the peak at the samples, a value the response reaches, so no step whose
    // bounds stay below it can hold the true peak; the second pass refines only the others.
    // Every CHECK steps, the oscillators whose response can no longer reach their peak stop.
    for k in steps.clone() {
        let (x0, x1) = step_input(x, k);
        step_samples(&bank.k, running.first, n, x0, x1, st);
        if settle && (k + 1 - first).is_multiple_of(CHECK) {
            running.settle(k, n, |o| settled(&bank.k, o, &st.u, &st.v, &st.peak, rest[k + 1]));
            if running.first == n {
                break;
            }
        }
    }
    st.u.fill(0.0);
    st.v.fill(0.0);
    running.replay();
    for k in steps {
        let (x0, x1) = step_input(x, k);
        let lo = running.first;
        if step_bounds(&bank.k, lo, n, x0, x1, st) {
            for o in lo..bank.len() {
                if st.flag[o] != 0 {
                    st.peak[o] = bank.oscillators[o].step_peak(st.u[o], st.v[o], x0, x1, st.peak[o]);
                }
            }
        }
        std::mem::swap(&mut st.u, &mut st.u_next);
        std::mem::swap(&mut st.v, &mut st.v_next);
        running.replayed(k);
        if running.first == n {
            break;
        }
    }
}

/// One step of oscillators `lo..n`, keeping the peak at the samples (in place).
#[inline(always)]
fn step_samples(k: &Coefficients, lo: usize, n: usize, x0: f64, x1: f64, st: &mut State) {
    let (a11, a12, a21, a22) = (&k.a11[lo..n], &k.a12[lo..n], &k.a21[lo..n], &k.a22[lo..n]);
    let (bu0, bu1, bv0, bv1) = (&k.bu0[lo..n], &k.bu1[lo..n], &k.bv0[lo..n], &k.bv1[lo..n]);
    let (u, v, pk) = (&mut st.u[lo..n], &mut st.v[lo..n], &mut st.peak[lo..n]);
    for o in 0..n - lo {
        let (u0, v0) = (u[o], v[o]);
        let u1 = a11[o] * u0 + a12[o] * v0 + bu0[o] * x0 + bu1[o] * x1;
        v[o] = a21[o] * u0 + a22[o] * v0 + bv0[o] * x0 + bv1[o] * x1;
        u[o] = u1;
        pk[o] = pk[o].max(u1.abs());
    }
}

/// One step of oscillators `lo..n` from `(st.u, st.v)` into `(st.u_next, st.v_next)`, flagging
/// where both bounds of |u| inside the step exceed the peak; returns whether any is flagged.
#[inline(always)]
fn step_bounds(k: &Coefficients, lo: usize, n: usize, x0: f64, x1: f64, st: &mut State) -> bool {
    let (a11, a12, a21, a22) = (&k.a11[lo..n], &k.a12[lo..n], &k.a21[lo..n], &k.a22[lo..n]);
    let (bu0, bu1, bv0, bv1) = (&k.bu0[lo..n], &k.bu1[lo..n], &k.bv0[lo..n], &k.bv1[lo..n]);
    let (ky0, ky1, kd, xw) = (&k.ky0[lo..n], &k.ky1[lo..n], &k.kd[lo..n], &k.xw[lo..n]);
    let (iwd, iw2, c2) = (&k.iwd[lo..n], &k.iw2[lo..n], &k.c2[lo..n]);
    let (u, v, un, vn) = (&st.u[lo..n], &st.v[lo..n], &mut st.u_next[lo..n], &mut st.v_next[lo..n]);
    let (pk, flag) = (&st.peak[lo..n], &mut st.flag[lo..n]);
    let dx = x1 - x0;
    let mut any = 0u8;
    for o in 0..n - lo {
        let (u0, v0) = (u[o], v[o]);
        let u1 = a11[o] * u0 + a12[o] * v0 + bu0[o] * x0 + bu1[o] * x1;
        vn[o] = a21[o] * u0 + a22[o] * v0 + bv0[o] * x0 + bv1[o] * x1;
        un[o] = u1;
        // The homogeneous part's amplitude |z|² at the step's start.
        let q = ky0[o] * x0 + ky1[o] * x1;
        let y0 = u0 + q;
        let s = (v0 + kd[o] * dx + xw[o] * y0) * iwd[o];
        let z2 = y0 * y0 + s * s;
        // B₂ > peak: (peak − max|u_end|)² < ((ωh)²/8)²·|z|² (the peak includes both ends).
        let g2 = pk[o] - u0.abs().max(u1.abs());
        let b2 = g2 * g2 < c2[o] * z2;
        // B₁ > peak: peak − max|L| < |z|.
        let g1 = pk[o] - q.abs().max((q + iw2[o] * dx).abs());
        let b1 = (g1 < 0.0) | (g1 * g1 < z2);
        let f = (b1 & b2) as u8;
        flag[o] = f;
        any |= f;
    }
    any != 0
}

/// FFT plans and buffers of the band-limited reading.
#[derive(Default)]
pub(crate) struct Resampler {
    planner: Option<FftPlanner<f64>>,
    forward: Option<(usize, Arc<dyn Fft<f64>>)>,
    inverse: Option<(usize, Arc<dyn Fft<f64>>)>,
    spectrum: Vec<Complex<f64>>,
    fft_scratch: Vec<Complex<f64>>,
    fine: Vec<f64>,
}

impl Resampler {
    /// Band-limited resampling of `x` by `r`: zero-pad to a power of two at least twice the
    /// length (so the periodic FFT does not wrap the end onto the start), FFT, insert zeros
    /// above Nyquist, inverse FFT, keep the `r·(n−1)+1` samples spanning the record — and, if
    /// `append_zero`, the `r` more up to the first zero of the padding (set to exactly 0).
    pub(crate) fn resample(&mut self, x: &[f64], r: usize, append_zero: bool) -> &[f64] {
        let n = x.len();
        if r == 1 {
            // The interpolant at the samples is the samples (and the spectrum's move below would
            // zero the negative frequencies in place, halving the record).
            self.fine.clear();
            self.fine.extend_from_slice(x);
            if append_zero {
                self.fine.push(0.0);
            }
            return &self.fine;
        }
        let big = (2 * n).next_power_of_two();
        let fine_len = big * r;
        let planner = self.planner.get_or_insert_with(FftPlanner::new);
        let forward = match &self.forward {
            Some((len, f)) if *len == big => f.clone(),
            _ => {
                let f = planner.plan_fft_forward(big);
                self.forward = Some((big, f.clone()));
                f
            }
        };
        let inverse = match &self.inverse {
            Some((len, f)) if *len == fine_len => f.clone(),
            _ => {
                let f = planner.plan_fft_inverse(fine_len);
                self.inverse = Some((fine_len, f.clone()));
                f
            }
        };
        let buf = &mut self.spectrum;
        buf.clear();
        buf.resize(fine_len, Complex::new(0.0, 0.0));
        for (b, &v) in buf.iter_mut().zip(x) {
            *b = Complex::new(v, 0.0);
        }
        let need = forward.get_inplace_scratch_len().max(inverse.get_inplace_scratch_len());
        if self.fft_scratch.len() < need {
            self.fft_scratch.resize(need, Complex::new(0.0, 0.0));
        }
        forward.process_with_scratch(&mut buf[..big], &mut self.fft_scratch);
        // Move the negative frequencies to the top of the longer spectrum, split the Nyquist bin.
        let half = big / 2;
        for k in (half + 1..big).rev() {
            buf[k + fine_len - big] = buf[k];
            buf[k] = Complex::new(0.0, 0.0);
        }
        let nyq = buf[half] * 0.5;
        buf[half] = nyq;
        buf[fine_len - half] = nyq;
        inverse.process_with_scratch(buf, &mut self.fft_scratch);
        let scale = 1.0 / big as f64;
        let keep = if append_zero { r * n + 1 } else { r * (n - 1) + 1 };
        self.fine.clear();
        self.fine.extend(buf[..keep].iter().map(|c| c.re * scale));
        if append_zero {
            self.fine[keep - 1] = 0.0;
        }
        &self.fine
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_limited_resampling_by_one_keeps_the_samples() {
        let x: Vec<f64> = (0..300).map(|i| (0.37 * i as f64).sin() + 0.1 * (i % 7) as f64).collect();
        let mut s = Resampler::default();
        assert_eq!(s.resample(&x, 1, false), &x[..]);
        let with_zero = s.resample(&x, 1, true).to_vec();
        assert_eq!((&with_zero[..300], with_zero.len(), with_zero[300]), (&x[..], 301, 0.0));
        // By 2, the even samples are the record's (to FFT rounding).
        let fine = s.resample(&x, 2, false).to_vec();
        assert!(x.iter().enumerate().all(|(i, v)| (fine[2 * i] - v).abs() < 1e-12));
    }

    #[test]
    fn band_limited_resampling_reproduces_a_sampled_sine_between_samples() {
        let dt = 0.01;
        let n = 4000;
        let f0 = 7.3;
        let x: Vec<f64> = (0..n).map(|i| (2.0 * std::f64::consts::PI * f0 * i as f64 * dt).sin()).collect();
        let mut s = Resampler::default();
        let fine = s.resample(&x, 8, false).to_vec();
        assert_eq!(fine.len(), 8 * (n - 1) + 1);
        // Away from the ends the interpolant is the sine itself.
        for j in (8 * 1000..8 * 3000).step_by(13) {
            let t = j as f64 * dt / 8.0;
            let want = (2.0 * std::f64::consts::PI * f0 * t).sin();
            assert!((fine[j] - want).abs() < 2e-3, "sample {j}: {} vs {want}", fine[j]);
        }
        // With the appended zero: the same samples, then the interpolant up to the zero.
        let padded = s.resample(&x, 8, true);
        assert_eq!(padded.len(), 8 * n + 1);
        assert_eq!(&padded[..fine.len()], &fine[..]);
        assert_eq!(padded[8 * n], 0.0);
    }

    #[test]
    fn oscillators_stop_once_the_response_cannot_reach_the_peak() {
        // A burst in the middle of a long silence-like tail (what a padded record is): the
        // short periods settle soon after the burst, the longest ring on; none stops before the
        // burst has passed, and the undamped ones only once no input is left (the ramp's step:
        // their free vibration keeps its amplitude).
        let dt = 1e-3;
        let n = 4000;
        let x: Vec<f64> = (0..n)
            .map(|i| {
                let t = i as f64 * dt;
                let e = ((t - 0.5) / 0.05).powi(2);
                (-e).exp() * (2.0 * std::f64::consts::PI * 20.0 * t).sin() + 1e-6 * (i as f64 * 0.37).sin()
            })
            .collect();
        let periods = log_periods(0.005, 2.0, 16);
        let plan = SpectrumPlan::new(dt, &periods, &[0.05, 0.0], Reading::Linear, 1).unwrap();
        let (mut st, mut running, mut rest) = (State::default(), Running::default(), Vec::new());
        suffix_max(&x, &mut rest);
        run(Isa::current(), &plan.bank, &x, true, true, &rest, &mut running, &mut st);
        // The bank: the damped oscillators by period (two groups of 8), then the undamped.
        let moves = running.moves.clone();
        println!("after which step the first running oscillator moved, and where to: {moves:?} ({n} samples)");
        assert!(moves[0].0 > 500 && moves[0].0 < 700 && moves[0].1 == 8, "the short periods settle after the burst");
        assert!(moves[1].0 > moves[0].0 && moves[1].0 < n && moves[1].1 == 16, "the long periods settle later");
        assert!(moves[2..].iter().all(|&(k, _)| k >= n - 1), "undamped oscillators settle on no input: {moves:?}");
    }

    #[test]
    fn log_periods_hit_the_requested_ends_exactly() {
        for (min, max, n) in [(0.01, 10.0, 100), (0.02, 10.0, 100), (1e-4, 0.1, 37), (0.3, 0.3, 5), (0.05, 2.0, 2)] {
            let p = log_periods(min, max, n);
            assert_eq!(p.len(), n);
            assert_eq!((p[0], p[n - 1]), (min, max), "ends of {min}…{max} ({n})");
            assert!(p.windows(2).all(|w| w[1] >= w[0]), "increasing");
            let ratio = (max / min).powf(1.0 / (n - 1) as f64);
            for w in p.windows(2) {
                assert!((w[1] / w[0] / ratio - 1.0).abs() < 1e-12, "log spacing");
            }
        }
        assert_eq!(log_periods(0.12328467394420668, 1.0, 1), vec![0.12328467394420668]);
        assert!(log_periods(0.1, 1.0, 0).is_empty());
    }

    #[test]
    fn refused_inputs_are_errors() {
        let r = |dt: f64, p: &[f64], d: &[f64]| SpectrumPlan::new(dt, p, d, Reading::Linear, 1).err();
        assert_eq!(r(0.0, &[1.0], &[0.05]), Some(SpectrumError::Interval { dt: 0.0 }));
        assert_eq!(r(0.01, &[1.0, -1.0], &[0.05]), Some(SpectrumError::Period { index: 1, value: -1.0 }));
        assert!(matches!(r(0.01, &[f64::NAN], &[0.05]), Some(SpectrumError::Period { index: 0, .. })));
        assert_eq!(r(0.01, &[1.0], &[1.0]), Some(SpectrumError::Damping { index: 0, value: 1.0 }));
        let plan = SpectrumPlan::new(0.01, &[1.0], &[0.05], Reading::Linear, 1).unwrap();
        let mut sd = [0.0];
        let e = plan.compute(&[0.0, f64::INFINITY], &mut SpectrumScratch::default(), &mut sd);
        assert_eq!(e, Err(SpectrumError::NonFinite { component: "record", index: 1, value: f64::INFINITY }));
    }
}
