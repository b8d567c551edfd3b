//! RotD50 / RotD100 against closed forms (circular and linear polarisation) and against the
//! straightforward computation that rotates the record for every angle.

mod support;

use std::f64::consts::PI;

use stickslip_seismo::spectra::response::{Reading, RecordEnd, SpectrumError, SpectrumPlan, SpectrumScratch};
use stickslip_seismo::spectra::rotd::{ANGLES, RotDPlan, RotDScratch, RotDSpectrum};
use support::random_record;

/// The straightforward way: for every angle, rotate the record and take its (exact) spectrum.
fn per_angle_by_rotation(plan: &SpectrumPlan, x: &[f64], y: &[f64]) -> Vec<f64> {
    let (mut scratch, mut sd) = (SpectrumScratch::default(), vec![0.0; plan.len()]);
    support::per_angle_by_rotation(x, y, |rotated| {
        plan.compute(rotated, &mut scratch, &mut sd).unwrap();
        sd.clone()
    })
}

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

fn rotd(plan: &RotDPlan, x: &[f64], y: &[f64]) -> RotDSpectrum {
    let mut out = RotDSpectrum::default();
    plan.compute(x, y, &mut RotDScratch::default(), &mut out).unwrap();
    out
}

#[test]
fn rotd_agrees_with_rotating_the_record_for_every_angle() {
    let dt = 0.01;
    let (x, y) = (random_record(400, 21), random_record(400, 22));
    let periods = [0.015, 0.02, 0.05, 0.2, 1.0, 4.0];
    for (reading, end) in [
        (Reading::Linear, RecordEnd::Ramp),
        (Reading::Linear, RecordEnd::Step),
        (Reading::BandLimited, RecordEnd::Ramp),
    ] {
        let plan = SpectrumPlan::new(dt, &periods, &[0.02, 0.05], reading, 4).unwrap().with_record_end(end);
        let reference = per_angle_by_rotation(&plan, &x, &y);
        let got = rotd(&RotDPlan::from_plan(plan.clone()).every_angle(), &x, &y);
        let summary = rotd(&RotDPlan::from_plan(plan.clone()), &x, &y);
        assert!(summary.per_angle.is_empty(), "no per-angle peaks unless asked");
        for (a, b) in [
            (&summary.rotd50, &got.rotd50),
            (&summary.rotd100, &got.rotd100),
            (&summary.rotd100_angle_deg, &got.rotd100_angle_deg),
            (&summary.x, &got.x),
            (&summary.y, &got.y),
        ] {
            assert_eq!(bits(a), bits(b), "{reading:?} {end:?}: the same bits with every angle solved");
        }
        let mut worst = 0.0f64;
        for o in 0..plan.len() {
            let scale = reference[o * ANGLES..(o + 1) * ANGLES].iter().fold(0.0f64, |m, &v| m.max(v));
            for t in 0..ANGLES {
                let (a, b) = (got.per_angle[o * ANGLES + t], reference[o * ANGLES + t]);
                worst = worst.max((a - b).abs() / scale);
                assert!((a - b).abs() <= 1e-12 * scale, "{reading:?} {end:?}, output {o}, θ {t}°: {a} vs {b}");
            }
            let mut sorted = reference[o * ANGLES..(o + 1) * ANGLES].to_vec();
            sorted.sort_by(f64::total_cmp);
            let median = 0.5 * (sorted[89] + sorted[90]);
            assert!((got.rotd50[o] / median - 1.0).abs() < 1e-12);
            assert!((got.rotd100[o] / sorted[179] - 1.0).abs() < 1e-12);
            let at = got.rotd100_angle_deg[o] as usize;
            assert!((reference[o * ANGLES + at] / sorted[179] - 1.0).abs() < 1e-12, "angle of RotD100");
        }
        println!("{reading:?} {end:?}: largest difference {worst:.1e} of the output's RotD100");
    }
}

#[test]
fn rotd_at_zero_and_ninety_degrees_are_the_components_spectra() {
    let dt = 0.01;
    let (x, y) = (random_record(300, 5), random_record(300, 6));
    let plan = SpectrumPlan::new(dt, &[0.03, 0.3, 3.0], &[0.05], Reading::Linear, 1).unwrap();
    let got = rotd(&RotDPlan::from_plan(plan.clone()).every_angle(), &x, &y);
    let (mut sx, mut sy) = (vec![0.0; 3], vec![0.0; 3]);
    plan.compute(&x, &mut SpectrumScratch::default(), &mut sx).unwrap();
    plan.compute(&y, &mut SpectrumScratch::default(), &mut sy).unwrap();
    for o in 0..3 {
        assert!((got.angles(o)[0] / sx[o] - 1.0).abs() < 1e-13, "θ = 0: {} vs {}", got.angles(o)[0], sx[o]);
        assert!((got.angles(o)[90] / sy[o] - 1.0).abs() < 1e-13, "θ = 90: {} vs {}", got.angles(o)[90], sy[o]);
    }
}

#[test]
fn a_linearly_polarised_record_gives_cos_theta_minus_phi_times_its_spectrum() {
    let dt = 0.01;
    let a = random_record(300, 9);
    let periods = [0.02, 0.1, 0.7, 2.5];
    let plan = SpectrumPlan::new(dt, &periods, &[0.05], Reading::Linear, 1).unwrap();
    let mut one = vec![0.0; plan.len()];
    plan.compute(&a, &mut SpectrumScratch::default(), &mut one).unwrap();
    let rotd_plan = RotDPlan::from_plan(plan).every_angle();
    for phi_deg in [0.0, 30.0, 117.3] {
        let phi = f64::to_radians(phi_deg);
        let x: Vec<f64> = a.iter().map(|v| v * phi.cos()).collect();
        let y: Vec<f64> = a.iter().map(|v| v * phi.sin()).collect();
        let got = rotd(&rotd_plan, &x, &y);
        for o in 0..periods.len() {
            for t in 0..ANGLES {
                let want = (f64::to_radians(t as f64) - phi).cos().abs() * one[o];
                let have = got.angles(o)[t];
                assert!(
                    (have - want).abs() <= 1e-12 * one[o],
                    "φ {phi_deg}°, T {}, θ {t}°: {have} vs {want}",
                    periods[o]
                );
            }
            // RotD100 is the spectrum itself, at the whole degree nearest the polarisation.
            let nearest = phi_deg.round();
            let want = (f64::to_radians(nearest) - phi).cos().abs() * one[o];
            assert!((got.rotd100[o] / want - 1.0).abs() < 1e-12, "{} vs {want}", got.rotd100[o]);
            assert_eq!(got.rotd100_angle_deg[o], nearest);
        }
    }
}

#[test]
fn a_circularly_polarised_harmonic_gives_rotd50_equal_to_rotd100() {
    // x = A cos Ωt, y = A sin Ωt at the oscillator's own period, under an envelope that rises
    // and falls as sin² over 20 cycles around 60 flat ones: every rotated component is the
    // same harmonic with another phase, so every angle has the same peak, the steady
    // amplitude. (Away from resonance the ramps leave a free vibration at the oscillator's
    // period that decays slowly and differs between angles, and a lighter damping than 5% is
    // still building up to the steady amplitude after 60 cycles: physics, not numerics.) The
    // periods are 100 and 74 samples long, so the crests fall at every phase against the
    // samples and the peaks between samples are what makes the angles agree.
    for (t0, dt) in [(0.5, 0.005), (0.37, 0.005)] {
        let n = (100.0 * t0 / dt) as usize + 1;
        let w = 2.0 * PI / t0;
        let end = (n - 1) as f64 * dt;
        let envelope =
            |t: f64| (0.5 * PI * (t / (20.0 * t0)).min((end - t) / (20.0 * t0)).clamp(0.0, 1.0)).sin().powi(2);
        let x: Vec<f64> = (0..n).map(|i| 2.0 * envelope(i as f64 * dt) * (w * i as f64 * dt).cos()).collect();
        let y: Vec<f64> = (0..n).map(|i| 2.0 * envelope(i as f64 * dt) * (w * i as f64 * dt).sin()).collect();
        for reading in [Reading::Linear, Reading::BandLimited] {
            let plan = RotDPlan::new(dt, &[t0], &[0.05, 0.1, 0.2], reading, 8).unwrap();
            let got = rotd(&plan, &x, &y);
            for o in 0..3 {
                let ratio = got.rotd100[o] / got.rotd50[o];
                println!("T0 {t0}, {reading:?}, output {o}: RotD100/RotD50 − 1 = {:.1e}", ratio - 1.0);
                assert!((ratio - 1.0).abs() < 1e-8, "T0 {t0}, {reading:?}, output {o}: {ratio}");
            }
        }
    }
}

#[test]
fn a_scratch_is_reused_and_bad_records_are_refused() {
    let plan = RotDPlan::new(0.01, &[0.05, 0.5], &[0.05], Reading::Linear, 1).unwrap();
    let mut scratch = RotDScratch::default();
    let (a, b, c) = (random_record(200, 1), random_record(200, 2), random_record(350, 3));
    let (mut first, mut other, mut again) = (RotDSpectrum::default(), RotDSpectrum::default(), RotDSpectrum::default());
    plan.compute(&a, &b, &mut scratch, &mut first).unwrap();
    plan.compute(&c, &c, &mut scratch, &mut other).unwrap();
    plan.compute(&a, &b, &mut scratch, &mut again).unwrap();
    assert_eq!(first, again);
    assert_eq!(other, rotd(&plan, &c, &c));
    assert_eq!(plan.compute(&a, &c, &mut scratch, &mut other), Err(SpectrumError::Components { x: 200, y: 350 }));
    let mut bad = b.clone();
    bad[17] = f64::NAN;
    assert!(matches!(
        plan.compute(&a, &bad, &mut scratch, &mut other),
        Err(SpectrumError::NonFinite { component: "y", index: 17, .. })
    ));
    plan.compute(&[], &[], &mut scratch, &mut other).unwrap();
    assert_eq!(other.rotd50, vec![0.0, 0.0]);
}
