//! Response spectra against closed forms and dense references: resonance and sinc², impulses,
//! PSA → PGA, linearity, exact peaks between samples, the record's end, plan reuse.

mod support;

use std::f64::consts::PI;

use stickslip_seismo::spectra::response::{Reading, RecordEnd, SpectrumPlan, SpectrumScratch, log_periods};
use support::{Tail, random_record};

fn sd(plan: &SpectrumPlan, x: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; plan.len()];
    plan.compute(x, &mut SpectrumScratch::default(), &mut out).unwrap();
    out
}

fn sine(amp: f64, period: f64, dt: f64, cycles: f64) -> Vec<f64> {
    let n = (cycles * period / dt).round() as usize + 1;
    (0..n).map(|i| amp * (2.0 * PI * i as f64 * dt / period).sin()).collect()
}

fn sinc(x: f64) -> f64 {
    if x == 0.0 { 1.0 } else { (PI * x).sin() / (PI * x) }
}

#[test]
fn resonance_gives_a_over_two_xi_and_sinc_squared_for_the_straight_line_reading() {
    let (amp, xi) = (2.5, 0.05);
    let target = amp / (2.0 * xi);
    let psa = |plan: &SpectrumPlan, x: &[f64], t0: f64| sd(plan, x)[0] * (2.0 * PI / t0).powi(2);
    // Well sampled (T0 = 400 Δt), long record (300 cycles): A/(2ξ).
    let dt = 0.001;
    let t0 = 400.0 * dt;
    let plan = SpectrumPlan::new(dt, &[t0], &[xi], Reading::Linear, 1).unwrap();
    let got = psa(&plan, &sine(amp, t0, dt, 300.0), t0);
    println!("T0 = 400Δt: PSA/(A/2ξ) = {:.6}", got / target);
    assert!((got / target - 1.0).abs() < 1e-3);
    // T0 = 10 Δt: straight lines between samples see the sine reduced by sinc²(Δt/T0) …
    let t0 = 10.0 * dt;
    let x = sine(amp, t0, dt, 300.0);
    let plan = SpectrumPlan::new(dt, &[t0], &[xi], Reading::Linear, 1).unwrap();
    let linear = psa(&plan, &x, t0);
    let expected = target * sinc(0.1).powi(2);
    println!("T0 = 10Δt, linear: PSA/(A/2ξ·sinc²) = {:.6}", linear / expected);
    assert!((linear / expected - 1.0).abs() < 1e-3);
    // … the band-limited reading sees the sine itself.
    let plan = SpectrumPlan::new(dt, &[t0], &[xi], Reading::BandLimited, 16).unwrap();
    let band = psa(&plan, &x, t0);
    println!("T0 = 10Δt, band-limited: PSA/(A/2ξ) = {:.6}", band / target);
    assert!((band / target - 1.0).abs() < 1e-3);
}

#[test]
fn impulse_response_peak_matches_the_closed_form_including_free_vibration_after_the_record() {
    let dt = 0.01;
    let dv = 0.3;
    // A velocity jump Δv: one sample Δv/Δt (a triangle of area Δv in the straight-line
    // reading), in a record far shorter than the periods, so the peak comes after its end.
    let mut x = vec![0.0; 21];
    x[10] = dv / dt;
    let periods: Vec<f64> = [50.0, 80.0, 200.0, 1000.0, 5000.0].iter().map(|k| k * dt).collect();
    for xi in [0.02, 0.05, 0.10] {
        let plan = SpectrumPlan::new(dt, &periods, &[xi], Reading::Linear, 1).unwrap();
        for (t, got) in periods.iter().zip(sd(&plan, &x)) {
            let omega = 2.0 * PI / t;
            let exact = dv / omega * (-xi * xi.acos() / (1.0 - xi * xi).sqrt()).exp();
            assert!((got / exact - 1.0).abs() < 2.5e-3, "ξ {xi}, T {t}: SD {got} vs {exact}");
        }
    }
}

#[test]
fn psa_tends_to_pga_at_short_periods_and_scales_linearly() {
    let dt = 0.005;
    let x = random_record(2000, 1);
    let pga = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let periods = [dt / 1000.0, dt / 100.0, dt / 10.0];
    let plan = SpectrumPlan::new(dt, &periods, &[0.05], Reading::Linear, 1).unwrap();
    let s = sd(&plan, &x);
    let psa: Vec<f64> = periods.iter().zip(&s).map(|(t, d)| d * (2.0 * PI / t).powi(2)).collect();
    println!("PSA/PGA at T = Δt/1000, Δt/100, Δt/10: {:?}", psa.iter().map(|p| p / pga).collect::<Vec<_>>());
    assert!((psa[0] / pga - 1.0).abs() < 1e-3);
    assert!((psa[1] / pga - 1.0).abs() < 1e-2);
    // Linear in the amplitude.
    let scaled: Vec<f64> = x.iter().map(|v| v * 3.7).collect();
    let plan = SpectrumPlan::new(dt, &[0.01, 0.1, 1.0, 10.0], &[0.02, 0.05], Reading::Linear, 1).unwrap();
    for (a, b) in sd(&plan, &x).iter().zip(sd(&plan, &scaled)) {
        assert!((b / a - 3.7).abs() < 1e-12 * 3.7);
    }
}

/// Relative error bound of the exact peaks against the dense reference (stated in the module
/// documentation): the reference's own error (RK4 truncation and rounding over millions of
/// steps, Hermite interpolation) is below it.
const EXACT: f64 = 1e-12;

#[test]
fn exact_peaks_agree_with_a_dense_reference_on_random_records() {
    let dt = 0.01;
    let x = random_record(300, 7);
    // From far below Δt to far above it; the reference runs 3 periods past the ramp.
    let periods = [0.004, 0.013, 0.02, 0.031, 0.05, 0.13, 0.4, 1.1, 3.0];
    for xi in [0.02, 0.05, 0.2] {
        let plan = SpectrumPlan::new(dt, &periods, &[xi], Reading::Linear, 1).unwrap();
        for (&t, got) in periods.iter().zip(sd(&plan, &x)) {
            let reference = support::peak(&x, dt, t, xi, Tail::Ramp, 3.0, 2000);
            let rel = got / reference - 1.0;
            println!("ξ {xi}, T {t}: SD {got:.12e}, reference {reference:.12e}, rel {rel:.1e}");
            assert!(rel.abs() < EXACT, "ξ {xi}, T {t}: {got} vs {reference}");
        }
    }
}

#[test]
fn exact_peaks_without_damping_and_far_from_the_step() {
    let dt = 0.005;
    let x = random_record(120, 3);
    for (t, xi) in [(dt / 40.0, 0.05), (dt / 7.3, 0.0), (0.7 * dt, 0.0), (300.0 * dt, 0.0), (1000.0 * dt, 0.01)] {
        let plan = SpectrumPlan::new(dt, &[t], &[xi], Reading::Linear, 1).unwrap();
        let got = sd(&plan, &x)[0];
        let reference = support::peak(&x, dt, t, xi, Tail::Ramp, 1.5, 8000);
        let rel = got / reference - 1.0;
        println!("T = {:.4}Δt, ξ {xi}: rel {rel:.1e}", t / dt);
        assert!(rel.abs() < EXACT, "T {t}, ξ {xi}: {got} vs {reference}");
    }
}

#[test]
fn a_velocity_impulse_half_a_sub_step_from_the_samples_is_caught() {
    // `stickslip spectra impulse.csv --dampings 0.10 --period-min-s 0.12328467394420668
    // --period-max-s 1 --period-count 1` on `0, 500, 0, 0, …` at Δt = 0.002 s: the straight-line
    // reading is a triangle of base 2Δt and height 500 m/s², i.e. a velocity impulse of
    // 500 × 0.002 = 1 m/s. The former method read the peak 1.28e-3 too low.
    let dt = 0.002;
    let mut x = vec![0.0; 600];
    x[1] = 500.0;
    let t = 0.12328467394420668;
    let plan = SpectrumPlan::new(dt, &log_periods(t, 1.0, 1), &[0.10], Reading::Linear, 1).unwrap();
    let got = sd(&plan, &x)[0];
    let reference = support::peak(&x, dt, t, 0.10, Tail::Ramp, 1.0, 4000);
    let rel = got / reference - 1.0;
    println!("SD {got:.15e}, reference {reference:.15e}, rel {rel:.1e}");
    assert!(rel.abs() < EXACT);
    // Against the ideal impulse Δv = 1 m/s (the triangle's width shifts it slightly).
    let (omega, xi) = (2.0 * PI / t, 0.10f64);
    let ideal = 1.0 / omega * (-xi * xi.acos() / (1.0 - xi * xi).sqrt()).exp();
    assert!((got / ideal - 1.0).abs() < 2e-3, "{got} vs ideal impulse {ideal}");
}

#[test]
fn the_record_is_continued_by_a_ramp_to_zero_then_free_vibration() {
    // A record that ends at its largest value: weak noise, then a last sample of 9 m/s².
    let dt = 0.01;
    let mut x: Vec<f64> = random_record(400, 11).iter().map(|v| 0.2 * v).collect();
    *x.last_mut().unwrap() = 9.0;
    let periods = [0.03, 0.1, 0.25, 0.4, 1.0, 3.0];
    let plan = SpectrumPlan::new(dt, &periods, &[0.05], Reading::Linear, 1).unwrap();
    let ramp = sd(&plan, &x);
    let step = sd(&plan.clone().with_record_end(RecordEnd::Step), &x);
    for (k, &t) in periods.iter().enumerate() {
        let with_ramp = support::peak(&x, dt, t, 0.05, Tail::Ramp, 3.0, 2000);
        let with_step = support::peak(&x, dt, t, 0.05, Tail::Step, 3.0, 2000);
        println!(
            "T {t}: ramp {:.1e}, step {:.1e} from their references; step/ramp − 1 = {:.2e}",
            ramp[k] / with_ramp - 1.0,
            step[k] / with_step - 1.0,
            step[k] / ramp[k] - 1.0
        );
        assert!((ramp[k] / with_ramp - 1.0).abs() < EXACT, "T {t}: ramp {} vs {with_ramp}", ramp[k]);
        assert!((step[k] / with_step - 1.0).abs() < EXACT, "T {t}: step {} vs {with_step}", step[k]);
    }
    // The conventions differ by many percent where the free vibration after the record holds
    // the peak: the ramp adds the triangle 9 → 0 that the step leaves out.
    assert!(ramp[0] / step[0] - 1.0 > 0.1, "T = 0.03 s: ramp {} vs step {}", ramp[0], step[0]);
}

#[test]
fn a_plan_is_reused_across_records_with_one_scratch() {
    let dt = 0.01;
    for reading in [Reading::Linear, Reading::BandLimited] {
        let plan = SpectrumPlan::new(dt, &[0.05, 0.5, 5.0], &[0.05, 0.1], reading, 8).unwrap();
        let mut scratch = SpectrumScratch::default();
        let (a, b) = (random_record(500, 1), random_record(300, 2));
        let mut out_a = vec![0.0; 6];
        let mut out_b = vec![0.0; 6];
        plan.compute(&a, &mut scratch, &mut out_a).unwrap();
        plan.compute(&b, &mut scratch, &mut out_b).unwrap();
        let mut again = vec![0.0; 6];
        plan.compute(&a, &mut scratch, &mut again).unwrap();
        assert_eq!(out_a, again, "a reused scratch changes nothing");
        assert_eq!(out_b, sd(&plan, &b));
    }
}

#[test]
fn short_and_empty_records() {
    let plan = SpectrumPlan::new(0.01, &[0.1, 1.0], &[0.05], Reading::Linear, 1).unwrap();
    assert_eq!(sd(&plan, &[]), vec![0.0, 0.0]);
    // One sample: the ramp from it to zero over one interval, then free vibration.
    for (k, got) in sd(&plan, &[2.0]).into_iter().enumerate() {
        let t = [0.1, 1.0][k];
        let reference = support::peak(&[2.0], 0.01, t, 0.05, Tail::Ramp, 2.0, 4000);
        assert!((got / reference - 1.0).abs() < EXACT, "T {t}: {got} vs {reference}");
    }
}
