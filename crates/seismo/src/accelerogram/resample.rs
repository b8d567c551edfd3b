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
    resample_into(Isa::current(), &xs, dt_in, dt_out, &mut out);
    out
}

widest! {
    /// [`resample_together`] into `out`, in instruction set `isa`.
    fn resample_into<const K: usize>(xs: &[&[f64]; K], dt_in: f64, dt_out: f64, out: &mut [Vec<f64>; K]) => resample_any
}

/// The kernel of [`resample_into`], compiled once per instruction set (the same bits).
#[inline(always)]
fn resample_any<const K: usize>(xs: &[&[f64]; K], dt_in: f64, dt_out: f64, out: &mut [Vec<f64>; K]) {
    let n = xs.first().map_or(0, |x| x.len());
    assert!(xs.iter().all(|x| x.len() == n), "series resampled together have one length");
    if n == 0 {
        return;
    }
    let m = ((n - 1) as f64 * dt_in / dt_out * (1.0 + 1e-12)).floor() as usize + 1;
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
    for y in out.iter_mut() {
        y.clear();
        y.reserve(m);
    }
    // New samples BLOCK at a time, their sums side by side (each still adds its taps in order):
    // a sum is a chain of dependent additions, and independent chains overlap.
    const BLOCK: usize = 4;
    let mut weights: [Vec<f64>; BLOCK] = std::array::from_fn(|_| Vec::new());
    let mut first = 0;
    while first < m {
        let count = BLOCK.min(m - first);
        let mut start = [0usize; BLOCK];
        for b in 0..count {
            let u = (first + b) as f64 * dt_out / dt_in;
            let lo = (u - reach).ceil().max(0.0) as usize;
            let hi = ((u + reach).floor() as usize).min(n - 1);
            let w = &mut weights[b];
            w.clear();
            w.resize((hi + 1).saturating_sub(lo), 0.0);
            for (j, w) in w.iter_mut().enumerate() {
                *w = kernel(u - (lo + j) as f64);
            }
            start[b] = lo.min(n);
        }
        let common = weights[..count].iter().map(Vec::len).min().unwrap_or(0);
        let mut sums = [[0.0; K]; BLOCK];
        if count == BLOCK {
            for j in 0..common {
                for b in 0..BLOCK {
                    let w = weights[b][j];
                    for (sum, x) in sums[b].iter_mut().zip(xs) {
                        *sum += x[start[b] + j] * w;
                    }
                }
            }
        }
        for b in 0..count {
            let from = if count == BLOCK { common } else { 0 };
            for (j, w) in weights[b].iter().enumerate().skip(from) {
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
