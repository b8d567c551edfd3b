//! Compute once, scale exactly: the prototype-scale record, spectra, RotD, Fourier spectrum and
//! intensity measures derived from the model-scale ones by the similarity rules
//! ([`RecordScale`]: PSA_p(λT) = PSA_m(T)/λ, SD ×λ, PSV ×1, …) equal what computing them
//! directly from the prototype record (accelerations ÷λ, Δt ×λ, periods ×λ, corners ÷λ) gives,
//! to round-off.

mod support;

use std::f64::consts::PI;

use rustfft::FftPlanner;
use stickslip_seismo::accelerogram::processing::{MeanRemoval, ProcessingOptions, RecordBand, process};
use stickslip_seismo::similarity::RecordScale;
use stickslip_seismo::spectra::fourier::{Window, fourier_amplitude};
use stickslip_seismo::spectra::intensity::{Baseline, intensity};
use stickslip_seismo::spectra::response::{Reading, SpectrumPlan, SpectrumScratch, log_periods};
use stickslip_seismo::spectra::rotd::{RotDPlan, RotDScratch, RotDSpectrum};
use support::random_record;

/// Round-off of these computations: the oscillators' recurrence over ~10⁴ steps, whose
/// coefficients differ in their last bits between the scales (ω·h is not rounded alike). The
/// test measures it as what changing Δt by one ulp does to the model's own spectra (printed,
/// 2e-12 here) and allows four times that (ω and ω·h of each scale are a few ulps apart), or this
/// floor for the other quantities.
const ROUND_OFF: f64 = 1e-12;

/// A raw record like the product's: quiet, then a burst that decays.
fn raw(n: usize, seed: u64) -> Vec<f64> {
    random_record(n, seed)
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let t = i as f64 / n as f64;
            if t < 0.1 { 0.01 * a } else { 30.0 * a * (-(t - 0.1) * 8.0).exp() }
        })
        .collect()
}

fn worst(derived: &[f64], direct: &[f64], scale: f64) -> f64 {
    assert_eq!(derived.len(), direct.len());
    derived.iter().zip(direct).fold(0.0f64, |m, (a, b)| m.max((a - b).abs() / scale))
}

fn peak(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

#[test]
fn prototype_values_derived_by_similarity_equal_those_computed_directly() {
    let (dt, n) = (5.35e-5, 620);
    let periods = log_periods(1e-4, 0.1, 100);
    let dampings = [0.02, 0.05];
    for lambda in [1.0e4, 37.3] {
        let s = RecordScale { lambda };
        let (rx, ry) = (raw(n, 1), raw(n, 2));
        let duration = (n - 1) as f64 * dt;
        let band = RecordBand::new(duration, dt, 5078.0, None, None).unwrap();
        let opts = |b: &RecordBand| {
            let mut o = ProcessingOptions::new(b.f_low_hz, Some(b.f_high_hz));
            o.mean = MeanRemoval::PreEvent { seconds: 0.1 * duration };
            o
        };
        // The record: processed at model scale, and processed directly at prototype scale.
        let (m, my) = (process(&rx, dt, &opts(&band)).unwrap(), process(&ry, dt, &opts(&band)).unwrap());
        let pband = band.scaled(lambda);
        let raw_p = |r: &[f64]| r.iter().map(|&a| s.acceleration(a)).collect::<Vec<f64>>();
        let mut popts = opts(&pband);
        popts.mean = MeanRemoval::PreEvent { seconds: s.time(0.1 * duration) };
        let (p, py) =
            (process(&raw_p(&rx), s.time(dt), &popts).unwrap(), process(&raw_p(&ry), s.time(dt), &popts).unwrap());
        assert_eq!((p.pad_front, p.accel.len()), (m.pad_front, m.accel.len()), "λ {lambda}: the same pads");
        let pga = peak(&m.accel);
        let derived: Vec<f64> = m.accel.iter().map(|&a| s.acceleration(a)).collect();
        let e_acc = worst(&derived, &p.accel, s.acceleration(pga));
        let derived: Vec<f64> = m.disp.iter().map(|&d| s.length(d)).collect();
        let e_disp = worst(&derived, &p.disp, s.length(peak(&m.disp)));
        // Response spectra: SD ×λ, PSA ÷λ at the period ×λ.
        let plan_m = SpectrumPlan::new(dt, &periods, &dampings, Reading::Linear, 1).unwrap();
        let pp: Vec<f64> = periods.iter().map(|&t| s.time(t)).collect();
        let plan_p = SpectrumPlan::new(s.time(dt), &pp, &dampings, Reading::Linear, 1).unwrap();
        let (mut sd_m, mut sd_p) = (vec![0.0; plan_m.len()], vec![0.0; plan_p.len()]);
        plan_m.compute(&m.accel, &mut SpectrumScratch::default(), &mut sd_m).unwrap();
        plan_p.compute(&p.accel, &mut SpectrumScratch::default(), &mut sd_p).unwrap();
        let psa = |sd: &[f64], t: &[f64]| -> Vec<f64> {
            sd.iter().enumerate().map(|(o, v)| (2.0 * PI / t[o % t.len()]).powi(2) * v).collect()
        };
        let (psa_m, psa_p) = (psa(&sd_m, &periods), psa(&sd_p, &pp));
        // The spectra's own round-off: Δt one ulp larger.
        let nudged = SpectrumPlan::new(dt * (1.0 + f64::EPSILON), &periods, &dampings, Reading::Linear, 1).unwrap();
        let mut sd_n = vec![0.0; nudged.len()];
        nudged.compute(&m.accel, &mut SpectrumScratch::default(), &mut sd_n).unwrap();
        let ulp = sd_m.iter().zip(&sd_n).fold(0.0f64, |w, (a, b)| w.max((a - b).abs() / a));
        let spectra_round_off = (4.0 * ulp).max(ROUND_OFF);
        let mut e_sd = 0.0f64;
        let mut e_psa = 0.0f64;
        for o in 0..sd_m.len() {
            e_sd = e_sd.max((s.length(sd_m[o]) - sd_p[o]).abs() / sd_p[o]);
            e_psa = e_psa.max((s.acceleration(psa_m[o]) - psa_p[o]).abs() / psa_p[o]);
            let t = periods[o % periods.len()];
            assert_eq!(band.holds_period(t), pband.holds_period(s.time(t)), "λ {lambda}, T {t}: in band alike");
        }
        // RotD50 / RotD100 of the pair, ×λ.
        let (rot_m, rot_p) = (RotDPlan::from_plan(plan_m.clone()), RotDPlan::from_plan(plan_p.clone()));
        let (mut a, mut b) = (RotDSpectrum::default(), RotDSpectrum::default());
        rot_m.compute(&m.accel, &my.accel, &mut RotDScratch::default(), &mut a).unwrap();
        rot_p.compute(&p.accel, &py.accel, &mut RotDScratch::default(), &mut b).unwrap();
        let mut e_rotd = 0.0f64;
        for o in 0..a.rotd50.len() {
            e_rotd = e_rotd.max((s.length(a.rotd50[o]) - b.rotd50[o]).abs() / b.rotd100[o]);
            e_rotd = e_rotd.max((s.length(a.rotd100[o]) - b.rotd100[o]).abs() / b.rotd100[o]);
        }
        // Fourier amplitude: the same values at f/λ.
        let mut fft = FftPlanner::new();
        let fm = fourier_amplitude(&m.accel, dt, Window::Rectangular, &mut fft);
        let fp = fourier_amplitude(&p.accel, s.time(dt), Window::Rectangular, &mut fft);
        let derived: Vec<f64> = fm.frequency_hz.iter().map(|&f| s.frequency(f)).collect();
        let e_freq = worst(&derived, &fp.frequency_hz, s.frequency(*fm.frequency_hz.last().unwrap()));
        let derived: Vec<f64> = fm.amplitude.iter().map(|&v| s.velocity(v)).collect();
        let e_fourier = worst(&derived, &fp.amplitude, peak(&fm.amplitude));
        // Intensity measures.
        let (im, ip) = (intensity(&m.accel, dt, Baseline::None), intensity(&p.accel, s.time(dt), Baseline::None));
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        let e_int = [
            rel(s.acceleration(im.pga), ip.pga),
            rel(s.velocity(im.pgv), ip.pgv),
            rel(s.length(im.pgd), ip.pgd),
            rel(s.arias(im.arias), ip.arias),
            rel(s.time(im.t5), ip.t5),
            rel(s.time(im.t95), ip.t95),
        ]
        .into_iter()
        .fold(0.0f64, f64::max);
        println!(
            "λ {lambda}: Δt one ulp off changes SD by up to {ulp:.1e}; derived against direct: record {e_acc:.1e} (disp {e_disp:.1e}), SD {e_sd:.1e}, PSA {e_psa:.1e}, RotD {e_rotd:.1e}, \
             Fourier {e_fourier:.1e} (f {e_freq:.1e}), intensity {e_int:.1e}"
        );
        for (what, e, tol) in [
            ("record", e_acc, ROUND_OFF),
            ("displacement", e_disp, ROUND_OFF),
            ("SD", e_sd, spectra_round_off),
            ("PSA", e_psa, spectra_round_off),
            ("RotD", e_rotd, spectra_round_off),
            ("Fourier frequency", e_freq, ROUND_OFF),
            ("Fourier amplitude", e_fourier, ROUND_OFF),
            ("intensity", e_int, ROUND_OFF),
        ] {
            assert!(e <= tol, "λ {lambda}: {what} derived vs direct differs by {e:.2e} (round-off {tol:.1e})");
        }
    }
}
