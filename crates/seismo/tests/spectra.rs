//! Response spectra, intensity measures and records against closed forms (docs/model.md §8).

use std::f64::consts::PI;

use rand::{RngExt, SeedableRng};
use stickslip_seismo::spectra::response::{Reading, SpectrumPlan, SpectrumScratch};

fn sd(plan: &SpectrumPlan, x: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; plan.len()];
    plan.compute(x, &mut SpectrumScratch::default(), &mut out);
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
    let plan = SpectrumPlan::new(dt, &[t0], &[xi], Reading::Linear, 1);
    let got = psa(&plan, &sine(amp, t0, dt, 300.0), t0);
    println!("T0 = 400Δt: PSA/(A/2ξ) = {:.6}", got / target);
    assert!((got / target - 1.0).abs() < 1e-3);
    // T0 = 10 Δt: straight lines between samples see the sine reduced by sinc²(Δt/T0) …
    let t0 = 10.0 * dt;
    let x = sine(amp, t0, dt, 300.0);
    let plan = SpectrumPlan::new(dt, &[t0], &[xi], Reading::Linear, 1);
    let linear = psa(&plan, &x, t0);
    let expected = target * sinc(0.1).powi(2);
    println!("T0 = 10Δt, linear: PSA/(A/2ξ·sinc²) = {:.6}", linear / expected);
    assert!((linear / expected - 1.0).abs() < 1e-3);
    // … the band-limited reading sees the sine itself.
    let plan = SpectrumPlan::new(dt, &[t0], &[xi], Reading::BandLimited, 16);
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
        let plan = SpectrumPlan::new(dt, &periods, &[xi], Reading::Linear, 1);
        for (t, got) in periods.iter().zip(sd(&plan, &x)) {
            let omega = 2.0 * PI / t;
            let exact = dv / omega * (-xi * xi.acos() / (1.0 - xi * xi).sqrt()).exp();
            assert!((got / exact - 1.0).abs() < 2.5e-3, "ξ {xi}, T {t}: SD {got} vs {exact}");
        }
    }
}

fn random_record(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| rng.random_range(-1.0..1.0) * 9.0).collect()
}

#[test]
fn psa_tends_to_pga_at_short_periods_and_scales_linearly() {
    let dt = 0.005;
    let x = random_record(2000, 1);
    let pga = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let periods = [dt / 1000.0, dt / 100.0, dt / 10.0];
    let plan = SpectrumPlan::new(dt, &periods, &[0.05], Reading::Linear, 1);
    let s = sd(&plan, &x);
    let psa: Vec<f64> = periods.iter().zip(&s).map(|(t, d)| d * (2.0 * PI / t).powi(2)).collect();
    println!("PSA/PGA at T = Δt/1000, Δt/100, Δt/10: {:?}", psa.iter().map(|p| p / pga).collect::<Vec<_>>());
    assert!((psa[0] / pga - 1.0).abs() < 1e-3);
    assert!((psa[1] / pga - 1.0).abs() < 1e-2);
    // Linear in the amplitude.
    let scaled: Vec<f64> = x.iter().map(|v| v * 3.7).collect();
    let plan = SpectrumPlan::new(dt, &[0.01, 0.1, 1.0, 10.0], &[0.02, 0.05], Reading::Linear, 1);
    for (a, b) in sd(&plan, &x).iter().zip(sd(&plan, &scaled)) {
        assert!((b / a - 3.7).abs() < 1e-12 * 3.7);
    }
}

/// Reference: RK4 with 4000 steps per period or per sample (whichever is finer) on the
/// straight-line reading, continued 3 periods past the record's end.
fn brute_force(x: &[f64], dt: f64, period: f64, xi: f64) -> f64 {
    let w = 2.0 * PI / period;
    let m = ((4000.0 * dt / period).ceil() as usize).max(4000);
    let h = dt / m as f64;
    let f = |u: f64, v: f64, a: f64| (v, -w * w * u - 2.0 * xi * w * v - a);
    let (mut u, mut v, mut peak) = (0.0f64, 0.0f64, 0.0f64);
    let extra = (3.0 * period / dt).ceil() as usize;
    let input = |i: usize| if i < x.len() { x[i] } else { 0.0 };
    for i in 0..x.len() - 1 + extra {
        let (a0, a1) = (input(i), input(i + 1));
        for k in 0..m {
            let at = |s: f64| a0 + (a1 - a0) * (k as f64 + s) / m as f64;
            let (k1u, k1v) = f(u, v, at(0.0));
            let (k2u, k2v) = f(u + 0.5 * h * k1u, v + 0.5 * h * k1v, at(0.5));
            let (k3u, k3v) = f(u + 0.5 * h * k2u, v + 0.5 * h * k2v, at(0.5));
            let (k4u, k4v) = f(u + h * k3u, v + h * k3v, at(1.0));
            u += h / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
            v += h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
            peak = peak.max(u.abs());
        }
    }
    peak
}

#[test]
fn exact_method_agrees_with_a_brute_force_integration_on_a_random_record() {
    let dt = 0.01;
    let x = random_record(400, 7);
    let periods = [0.005, 0.02, 0.05, 0.13, 0.4, 1.1, 3.0];
    let plan = SpectrumPlan::new(dt, &periods, &[0.05], Reading::Linear, 1);
    for (t, got) in periods.iter().zip(sd(&plan, &x)) {
        let reference = brute_force(&x, dt, *t, 0.05);
        println!("T = {t}: SD {got:.6e}, brute force {reference:.6e}, rel {:.1e}", (got / reference - 1.0).abs());
        assert!((got / reference - 1.0).abs() < 1e-4, "T {t}: {got} vs {reference}");
    }
}

#[test]
fn a_plan_is_reused_across_records_with_one_scratch() {
    let dt = 0.01;
    let plan = SpectrumPlan::new(dt, &[0.05, 0.5, 5.0], &[0.05], Reading::BandLimited, 8);
    let mut scratch = SpectrumScratch::default();
    let (a, b) = (random_record(500, 1), random_record(300, 2));
    let mut out_a = vec![0.0; 3];
    let mut out_b = vec![0.0; 3];
    plan.compute(&a, &mut scratch, &mut out_a);
    plan.compute(&b, &mut scratch, &mut out_b);
    let mut again = vec![0.0; 3];
    plan.compute(&a, &mut scratch, &mut again);
    assert_eq!(out_a, again, "a reused scratch changes nothing");
    assert_eq!(out_b, sd(&plan, &b));
}
