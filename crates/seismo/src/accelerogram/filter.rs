//! The zero-phase Butterworth band-pass of record processing ([`super::processing`]): applied in
//! the frequency domain over the record's length, its FFT plans and gains kept per thread for the
//! next record of the same length and filter.

use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

/// Gain of the acausal band-pass at frequency `f` (Hz): `1/√(1+(f_low/f)^(2n)) · 1/√(1+(f/f_high)^(2n))`.
pub fn butterworth_gain(f: f64, f_low: f64, f_high: Option<f64>, order: u32) -> f64 {
    let f = f.abs();
    if f == 0.0 {
        return 0.0;
    }
    let n2 = 2.0 * order as f64;
    let high_pass = 1.0 / (1.0 + (f_low / f).powf(n2)).sqrt();
    let low_pass = f_high.map_or(1.0, |fh| 1.0 / (1.0 + (f / fh).powf(n2)).sqrt());
    high_pass * low_pass
}

/// Applies the zero-phase band-pass to `x` in place (circularly over its length). Unchecked:
/// [`super::processing::process`] validates the corners, order and Δt before calling it.
pub fn bandpass_in_place(x: &mut [f64], dt: f64, f_low: f64, f_high: Option<f64>, order: u32) {
    let m = x.len();
    if m == 0 {
        return;
    }
    // The plans and the gains are this thread's for the next record of the same length and
    // filter (a seed's components share them): the same values, made once.
    BANDPASS.with_borrow_mut(|kept| {
        let key = (m, dt.to_bits(), f_low.to_bits(), f_high.map(f64::to_bits), order);
        if kept.key != Some(key) {
            let df = 1.0 / (m as f64 * dt);
            kept.gain.clear();
            kept.gain.extend((0..m).map(|k| butterworth_gain(k.min(m - k) as f64 * df, f_low, f_high, order)));
            // A planner of its own, as each record had: one that planned other lengths may build
            // this one from other pieces, which rounds differently.
            let mut planner = FftPlanner::<f64>::new();
            kept.forward = Some(planner.plan_fft_forward(m));
            kept.inverse = Some(planner.plan_fft_inverse(m));
            kept.key = Some(key);
        }
        let buf = &mut kept.buffer;
        buf.clear();
        buf.extend(x.iter().map(|&v| Complex::new(v, 0.0)));
        kept.forward.as_ref().expect("planned above").process(buf);
        for (c, &g) in buf.iter_mut().zip(&kept.gain) {
            *c *= g;
        }
        kept.inverse.as_ref().expect("planned above").process(buf);
        let scale = 1.0 / m as f64;
        for (v, c) in x.iter_mut().zip(buf.iter()) {
            *v = c.re * scale;
        }
    });
}

/// The band-pass's FFT plans and gains of the last record a thread filtered.
#[derive(Default)]
struct Bandpass {
    /// (length, Δt, f_low, f_high, order), bits of the floats.
    key: Option<(usize, u64, u64, Option<u64>, u32)>,
    forward: Option<std::sync::Arc<dyn rustfft::Fft<f64>>>,
    inverse: Option<std::sync::Arc<dyn rustfft::Fft<f64>>>,
    gain: Vec<f64>,
    buffer: Vec<Complex<f64>>,
}

thread_local! {
    static BANDPASS: std::cell::RefCell<Bandpass> = std::cell::RefCell::new(Bandpass::default());
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    #[test]
    fn the_kept_plans_and_gains_give_a_fresh_filters_bits() {
        // The band-pass as each record had it: its own planner, gains computed bin by bin.
        let fresh = |x: &[f64], dt: f64, f_low: f64, f_high: Option<f64>, order: u32| {
            let m = x.len();
            let mut planner = FftPlanner::<f64>::new();
            let (forward, inverse) = (planner.plan_fft_forward(m), planner.plan_fft_inverse(m));
            let mut buf: Vec<Complex<f64>> = x.iter().map(|&v| Complex::new(v, 0.0)).collect();
            forward.process(&mut buf);
            for (k, c) in buf.iter_mut().enumerate() {
                *c *= butterworth_gain(k.min(m - k) as f64 * (1.0 / (m as f64 * dt)), f_low, f_high, order);
            }
            inverse.process(&mut buf);
            buf.iter().map(|c| (c.re * (1.0 / m as f64)).to_bits()).collect::<Vec<u64>>()
        };
        // Lengths, intervals and filters changing and coming back (the kept ones reused or
        // replaced).
        let sine = |f: f64, n: usize| -> Vec<f64> { (0..n).map(|i| (2.0 * PI * f * i as f64 * 1e-3).sin()).collect() };
        let (a, b) = (sine(37.0, 1009), sine(11.0, 2048));
        let cases = [
            (&a, 1e-3, 1.0, Some(200.0), 4),
            (&a, 1e-3, 1.0, Some(200.0), 4),
            (&b, 1e-3, 1.0, Some(200.0), 4),
            (&a, 1e-3, 2.0, None, 4),
            (&a, 1.1e-3, 2.0, None, 4),
            (&a, 1.1e-3, 2.0, None, 2),
            (&a, 1e-3, 1.0, Some(200.0), 4),
        ];
        for (x, dt, f_low, f_high, order) in cases {
            let mut y = x.clone();
            bandpass_in_place(&mut y, dt, f_low, f_high, order);
            let got: Vec<u64> = y.iter().map(|v| v.to_bits()).collect();
            assert_eq!(got, fresh(x, dt, f_low, f_high, order), "Δt {dt}, {f_low}–{f_high:?} Hz, order {order}");
        }
    }

    #[test]
    fn gain_is_minus_3_db_at_the_corners() {
        let (fl, fh, n) = (0.1, 25.0, 4);
        let far = |f: f64| 1.0 / (1.0 + (f / fh).powi(8)).sqrt(); // the other skirt at f
        assert!((butterworth_gain(fl, fl, Some(fh), n) - far(fl) / 2f64.sqrt()).abs() < 1e-15);
        let near = 1.0 / (1.0 + (fl / fh).powi(8)).sqrt();
        assert!((butterworth_gain(fh, fl, Some(fh), n) - near / 2f64.sqrt()).abs() < 1e-15);
        // One decade below f_low: 1/√(1+10⁸) ≈ 1e-4 (80 dB/decade for n = 4).
        assert!((butterworth_gain(0.01, fl, None, n) - 1.0 / (1.0f64 + 1e8).sqrt()).abs() < 1e-18);
        assert_eq!(butterworth_gain(0.0, fl, Some(fh), n), 0.0);
    }
}
