//! Band-limited resampling of a record to another interval: a windowed sinc (Kaiser window,
//! β = 8, 16 samples of the coarser interval on either side) read from a table, anti-aliased when
//! the new interval is coarser. [`crate::accelerogram::processing::Processed::resampled`] uses it
//! to put every seed's records on the pipeline's interval.

use stickslip_isa::{Isa, widest};

/// Half-width of the resampling kernel, in samples of the coarser of the two intervals.
pub const RESAMPLE_HALF_WIDTH: usize = 16;

/// Kaiser window parameter β of the resampling kernel.
pub const RESAMPLE_KAISER_BETA: f64 = 8.0;

/// Points per sample of the tabulated kernel (linear interpolation between them).
const KERNEL_TABLE_PER_SAMPLE: usize = 1024;

/// Zeroth-order modified Bessel function of the first kind, by its power series.
fn bessel_i0(x: f64) -> f64 {
    let (mut sum, mut term, q) = (1.0, 1.0, 0.25 * x * x);
    for k in 1..200 {
        term *= q / (k * k) as f64;
        sum += term;
        if term < 1e-17 * sum {
            break;
        }
    }
    sum
}

/// The kernel `sinc(s)·w(s/H)` for `s` in `[0, H]` (H = [`RESAMPLE_HALF_WIDTH`]), `w` the Kaiser
/// window of β = [`RESAMPLE_KAISER_BETA`], tabulated [`KERNEL_TABLE_PER_SAMPLE`] points per unit.
fn kernel_table() -> &'static [f64] {
    static TABLE: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let h = RESAMPLE_HALF_WIDTH as f64;
        let n = RESAMPLE_HALF_WIDTH * KERNEL_TABLE_PER_SAMPLE;
        let i0b = bessel_i0(RESAMPLE_KAISER_BETA);
        (0..=n + 1)
            .map(|i| {
                let s = i as f64 / KERNEL_TABLE_PER_SAMPLE as f64;
                if s >= h {
                    return 0.0;
                }
                let sinc = if s == 0.0 { 1.0 } else { (std::f64::consts::PI * s).sin() / (std::f64::consts::PI * s) };
                let r = s / h;
                sinc * bessel_i0(RESAMPLE_KAISER_BETA * (1.0 - r * r).sqrt()) / i0b
            })
            .collect()
    })
}

/// `x`, sampled every `dt_in` s from t = 0, at `t = i·dt_out` for `i = 0 … ⌊(n−1)·dt_in/dt_out⌋`:
/// band-limited (windowed-sinc) interpolation whose low-pass cuts off at the lower of the two
/// Nyquist frequencies, so that going to a coarser interval is anti-aliased. The kernel is
/// `r·sinc(r·u)·w(r·u/H)` with `u` the distance in input samples, `r = min(1, dt_in/dt_out)`,
/// `w` the Kaiser window (β = 8) and `H` = 16. Its gain is flat to 1e-4 up to 80% of the lower
/// Nyquist frequency, 1/2 (−6 dB) at it and below 1e-4 (−80 dB) from 1.2 times it (computed from
/// the kernel; the tests `resampling_…` check the flat part and the rejection). Samples outside
/// `x` count as zero.
pub fn resample(x: &[f64], dt_in: f64, dt_out: f64) -> Vec<f64> {
    let [y] = resample_together([x], dt_in, dt_out);
    y
}

/// [`resample`] of several series of the same length at once: the kernel's weights of each new
/// sample are computed once and applied to every series, in the same order, so each result has
/// the bits `resample` gives it alone.
pub fn resample_together<const K: usize>(xs: [&[f64]; K], dt_in: f64, dt_out: f64) -> [Vec<f64>; K] {
    let mut out: [Vec<f64>; K] = std::array::from_fn(|_| Vec::new());
    let n = xs.first().map_or(0, |x| x.len());
    assert!(xs.iter().all(|x| x.len() == n), "series resampled together have one length");
    if n == 0 {
        return out;
    }
    let m = ((n - 1) as f64 * dt_in / dt_out * (1.0 + 1e-12)).floor() as usize + 1;
    let r = (dt_in / dt_out).min(1.0);
    for y in out.iter_mut() {
        y.reserve(m);
    }
    let isa = Isa::current();
    let taps = 2 * (RESAMPLE_HALF_WIDTH as f64 / r).ceil() as usize + 1;
    if m.saturating_mul(taps) <= KEPT_WEIGHTS {
        KEPT.with_borrow_mut(|kept| {
            if !kept.hold(dt_in, dt_out, m) {
                kept.fill(dt_in, dt_out, 0, m);
            }
            add_up(isa, &xs, n, r, kept, 0..m, &mut out);
        });
    } else {
        let mut weights = Weights::default();
        for from in (0..m).step_by(WEIGHT_BLOCK) {
            let to = (from + WEIGHT_BLOCK).min(m);
            weights.fill(dt_in, dt_out, from, to);
            add_up(isa, &xs, n, r, &weights, from..to, &mut out);
        }
    }
    out
}

widest! {
    /// New samples `new` of the series `xs` (of `n` samples) with `weights`, appended to `out`,
    /// in instruction set `isa`.
    fn add_up<const K: usize>(
        xs: &[&[f64]; K],
        n: usize,
        r: f64,
        weights: &Weights,
        new: std::ops::Range<usize>,
        out: &mut [Vec<f64>; K],
    ) => add_up_any
}

/// The kernel's weights of new samples `first..first + lo.len()` between two intervals: new
/// sample `i` reads input samples from `lo[i − first]` on, with the weights
/// `w[at[i − first]..at[i − first + 1]]`, as far as the kernel reaches whatever the record's length
/// (a record uses those of them that fall inside it).
#[derive(Default)]
struct Weights {
    /// `(dt_in, dt_out)` as bits.
    key: (u64, u64),
    first: usize,
    lo: Vec<usize>,
    at: Vec<usize>,
    w: Vec<f64>,
}

/// Weights kept per thread for the next record between the same intervals (a seed's records
/// share theirs): at most this many (8 MB); a longer record computes its own, a block at a time.
const KEPT_WEIGHTS: usize = 1 << 20;

/// New samples whose weights are computed together when a record's are not kept.
const WEIGHT_BLOCK: usize = 4096;

thread_local! {
    static KEPT: std::cell::RefCell<Weights> = std::cell::RefCell::new(Weights::default());
}

impl Weights {
    /// Makes these the weights of new samples `from..to` from `dt_in` to `dt_out`.
    fn fill(&mut self, dt_in: f64, dt_out: f64, from: usize, to: usize) {
        fill_weights(Isa::current(), self, dt_in, dt_out, from, to);
    }

    /// Whether these are the weights of new samples `0..m` from `dt_in` to `dt_out`.
    fn hold(&self, dt_in: f64, dt_out: f64, m: usize) -> bool {
        self.key == (dt_in.to_bits(), dt_out.to_bits()) && self.first == 0 && self.lo.len() >= m
    }
}

widest! {
    /// [`Weights::fill`] in instruction set `isa`.
    fn fill_weights(weights: &mut Weights, dt_in: f64, dt_out: f64, from: usize, to: usize) => fill_any
}

/// The kernel of [`fill_weights`], compiled once per instruction set (the same bits).
#[inline(always)]
fn fill_any(weights: &mut Weights, dt_in: f64, dt_out: f64, from: usize, to: usize) {
    let table = kernel_table();
    let r = (dt_in / dt_out).min(1.0);
    let reach = RESAMPLE_HALF_WIDTH as f64 / r;
    let per = KERNEL_TABLE_PER_SAMPLE as f64;
    // The kernel at `u` input samples from the centre: linear between the table's points, zero
    // past its end. Written without branches so that the taps of a sample run side by side.
    let kernel = |u: f64| -> f64 {
        let pos = (r * u).abs() * per;
        let i = pos as usize;
        let inside = i < table.len() - 1;
        let k = if inside { i } else { 0 };
        // SAFETY: `k + 1 < table.len()` (k = 0 when not inside, and the table has two points
        // or more).
        let (a, b) = unsafe { (*table.get_unchecked(k), *table.get_unchecked(k + 1)) };
        let f = pos - i as f64;
        if inside { a + f * (b - a) } else { 0.0 }
    };
    let Weights { key, first, lo: los, at, w } = weights;
    *key = (dt_in.to_bits(), dt_out.to_bits());
    *first = from;
    los.clear();
    at.clear();
    w.clear();
    at.push(0);
    for i in from..to {
        let u = i as f64 * dt_out / dt_in;
        let lo = (u - reach).ceil().max(0.0) as usize;
        let hi = (u + reach).floor() as usize;
        los.push(lo);
        let start = w.len();
        w.resize(start + (hi + 1 - lo), 0.0);
        for (j, w) in w[start..].iter_mut().enumerate() {
            *w = kernel(u - (lo + j) as f64);
        }
        at.push(w.len());
    }
}

/// The kernel of [`add_up`], compiled once per instruction set (the same bits).
#[inline(always)]
fn add_up_any<const K: usize>(
    xs: &[&[f64]; K],
    n: usize,
    r: f64,
    weights: &Weights,
    new: std::ops::Range<usize>,
    out: &mut [Vec<f64>; K],
) {
    // The weights of new sample `i` that fall inside the record, and where they start in it.
    let taps = |i: usize| -> (&[f64], usize) {
        let k = i - weights.first;
        let lo = weights.lo[k];
        let all = &weights.w[weights.at[k]..weights.at[k + 1]];
        (&all[..all.len().min(n.saturating_sub(lo))], lo.min(n))
    };
    // New samples BLOCK at a time, their sums side by side (each still adds its taps in order):
    // a sum is a chain of dependent additions, and independent chains overlap.
    const BLOCK: usize = 4;
    let mut first = new.start;
    while first < new.end {
        let count = BLOCK.min(new.end - first);
        let mut w: [&[f64]; BLOCK] = [&[]; BLOCK];
        let mut start = [0usize; BLOCK];
        for b in 0..count {
            (w[b], start[b]) = taps(first + b);
        }
        let common = w[..count].iter().map(|w| w.len()).min().unwrap_or(0);
        let mut sums = [[0.0; K]; BLOCK];
        if count == BLOCK {
            for j in 0..common {
                for b in 0..BLOCK {
                    let w = w[b][j];
                    for (sum, x) in sums[b].iter_mut().zip(xs) {
                        *sum += x[start[b] + j] * w;
                    }
                }
            }
        }
        for b in 0..count {
            let from = if count == BLOCK { common } else { 0 };
            for (j, w) in w[b].iter().enumerate().skip(from) {
                for (sum, x) in sums[b].iter_mut().zip(xs) {
                    *sum += x[start[b] + j] * w;
                }
            }
            for (y, sum) in out.iter_mut().zip(sums[b]) {
                y.push(r * sum);
            }
        }
        first += count;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plain reading of the kernel: every new sample's taps weighed and added in order.
    fn plain(x: &[f64], dt_in: f64, dt_out: f64) -> Vec<f64> {
        let n = x.len();
        let m = ((n - 1) as f64 * dt_in / dt_out * (1.0 + 1e-12)).floor() as usize + 1;
        let (table, r) = (kernel_table(), (dt_in / dt_out).min(1.0));
        let reach = RESAMPLE_HALF_WIDTH as f64 / r;
        let kernel = |u: f64| {
            let pos = (r * u).abs() * KERNEL_TABLE_PER_SAMPLE as f64;
            let i = pos as usize;
            if i + 1 < table.len() { table[i] + (pos - i as f64) * (table[i + 1] - table[i]) } else { 0.0 }
        };
        (0..m)
            .map(|i| {
                let u = i as f64 * dt_out / dt_in;
                let lo = (u - reach).ceil().max(0.0) as usize;
                let hi = ((u + reach).floor() as usize).min(n - 1);
                r * (lo..=hi).fold(0.0, |sum, k| sum + x[k] * kernel(u - k as f64))
            })
            .collect()
    }

    fn record(n: usize, seed: u64) -> Vec<f64> {
        let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        (0..n)
            .map(|_| {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect()
    }

    fn bits(x: &[f64]) -> Vec<u64> {
        x.iter().map(|v| v.to_bits()).collect()
    }

    #[test]
    fn kept_and_blocked_weights_give_the_plain_sums_bits() {
        // Records that share their intervals (the kept weights, reused by a shorter record, then
        // grown for a longer one), another pair of intervals in between, coarser and finer, and
        // one too long for the kept weights (computed a block at a time).
        let cases = [
            (3000, 5.37e-5, 5e-5),
            (1200, 5.37e-5, 5e-5),
            (3600, 5.37e-5, 5e-5),
            (900, 4.1e-5, 5e-5),
            (3500, 5.37e-5, 5e-5),
            (2000, 1.0, 1.3),
            (40_000, 5.37e-5, 5e-5),
            (700, 5.37e-5, 5e-5),
        ];
        for (i, &(n, dt_in, dt_out)) in cases.iter().enumerate() {
            let x = record(n, i as u64);
            let v: Vec<f64> = x.iter().map(|a| 0.5 * a).collect();
            let [a, b] = resample_together([&x, &v], dt_in, dt_out);
            assert_eq!(bits(&a), bits(&plain(&x, dt_in, dt_out)), "case {i}: {n} samples, {dt_in} → {dt_out}");
            assert_eq!(bits(&b), bits(&plain(&v, dt_in, dt_out)), "case {i}, the second series");
        }
    }
}
