//! Oscillators that stop: each group of oscillators stops once its response can no longer
//! reach its peak (the free vibration's envelope plus the largest response the rest of the
//! input can drive, below the peak), and the steps before the first non-zero sample are
//! skipped. Both are exact, so the spectra, RotD and each component's spectrum from the RotD
//! passes are the same bits as with every oscillator advanced through every step.

mod support;

use stickslip_seismo::accelerogram::processing::{MeanRemoval, ProcessingOptions, process};
use stickslip_seismo::spectra::response::{Reading, RecordEnd, SpectrumPlan, SpectrumScratch, log_periods};
use stickslip_seismo::spectra::rotd::{RotDPlan, RotDScratch, RotDSpectrum};
use support::random_record;

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

/// A record like the product's: a quiet stretch, a burst that decays, processed (mean, tapers,
/// Converse–Brady pads, acausal band-pass), so the padded record is mostly the filter's tails.
fn processed(seed: u64, n: usize, dt: f64) -> Vec<f64> {
    let noise = random_record(n, seed);
    let raw: Vec<f64> = noise
        .iter()
        .enumerate()
        .map(|(i, a)| {
            let t = i as f64 / n as f64;
            if t < 0.1 { 0.01 * a } else { a * (-(t - 0.1) * 8.0).exp() * 30.0 }
        })
        .collect();
    let duration = (n - 1) as f64 * dt;
    let mut opts = ProcessingOptions::new(1.0 / duration, Some(0.3 / dt));
    opts.mean = MeanRemoval::PreEvent { seconds: 0.1 * duration };
    process(&raw, dt, &opts).unwrap().accel
}

/// Records: processed ones, one with a zero prefix, one ending at its largest value, a sine,
/// and silence.
fn records(dt: f64) -> Vec<(&'static str, Vec<f64>)> {
    let mut zero_prefix = vec![0.0; 300];
    zero_prefix.extend(random_record(400, 3));
    let mut ends_high = random_record(300, 4);
    ends_high.push(25.0);
    let sine = (0..800).map(|i| (2.0 * std::f64::consts::PI * i as f64 * dt / (37.0 * dt)).sin()).collect();
    vec![
        ("processed", processed(11, 620, dt)),
        ("processed", processed(12, 300, dt)),
        ("zero prefix", zero_prefix),
        ("ends high", ends_high),
        ("sine", sine),
        ("silence", vec![0.0; 50]),
    ]
}

#[test]
fn stopped_oscillators_give_the_same_spectra_bits() {
    let dt = 5.3e-5;
    let periods = log_periods(1e-4, 0.1, 100);
    for (reading, end) in [
        (Reading::Linear, RecordEnd::Ramp),
        (Reading::Linear, RecordEnd::Step),
        (Reading::BandLimited, RecordEnd::Ramp),
    ] {
        let plan = SpectrumPlan::new(dt, &periods, &[0.0, 0.02, 0.05, 0.2], reading, 4).unwrap().with_record_end(end);
        let all = plan.clone().exhaustive();
        for (name, x) in records(dt) {
            let (mut a, mut b) = (vec![0.0; plan.len()], vec![0.0; plan.len()]);
            plan.compute(&x, &mut SpectrumScratch::default(), &mut a).unwrap();
            all.compute(&x, &mut SpectrumScratch::default(), &mut b).unwrap();
            assert_eq!(bits(&a), bits(&b), "{reading:?} {end:?}, {name}");
        }
    }
}

#[test]
fn stopped_pairs_give_the_same_rotd_bits_and_each_component_its_spectrum() {
    let dt = 5.3e-5;
    let periods = log_periods(1e-4, 0.1, 60);
    let rec = records(dt);
    for (reading, end) in [(Reading::Linear, RecordEnd::Ramp), (Reading::BandLimited, RecordEnd::Ramp)] {
        let plan = SpectrumPlan::new(dt, &periods, &[0.0, 0.05], reading, 4).unwrap().with_record_end(end);
        // Stopping, with RotD's angles only and with every angle, against every angle of every
        // oscillator through every step.
        let all = RotDPlan::from_plan(plan.clone().exhaustive()).every_angle();
        let (rotd, every) = (RotDPlan::from_plan(plan.clone()), RotDPlan::from_plan(plan.clone()).every_angle());
        let pairs: Vec<(&str, Vec<f64>, Vec<f64>)> = vec![
            ("processed", rec[0].1.clone(), processed(21, 620, dt)),
            ("polarised", rec[0].1.iter().map(|a| 0.6 * a).collect(), rec[0].1.iter().map(|a| 0.8 * a).collect()),
            ("zero prefix, one silent", rec[2].1.clone(), vec![0.0; rec[2].1.len()]),
            ("sine and processed", rec[4].1.clone(), processed(22, 800, dt)[..800].to_vec()),
        ];
        for (name, x, y) in &pairs {
            let (mut a, mut b, mut e) = (RotDSpectrum::default(), RotDSpectrum::default(), RotDSpectrum::default());
            rotd.compute(x, y, &mut RotDScratch::default(), &mut a).unwrap();
            all.compute(x, y, &mut RotDScratch::default(), &mut b).unwrap();
            every.compute(x, y, &mut RotDScratch::default(), &mut e).unwrap();
            let what = format!("{reading:?} {end:?}, {name}");
            assert_eq!(bits(&e.per_angle), bits(&b.per_angle), "{what}: per angle");
            for (got, how) in [(&a, "RotD's angles only"), (&e, "every angle")] {
                assert_eq!(bits(&got.rotd50), bits(&b.rotd50), "{what}: RotD50, {how}");
                assert_eq!(bits(&got.rotd100), bits(&b.rotd100), "{what}: RotD100, {how}");
                assert_eq!(bits(&got.rotd100_angle_deg), bits(&b.rotd100_angle_deg), "{what}: angle, {how}");
            }
            for (c, got, rec) in [("x", &a.x, x), ("y", &a.y, y)] {
                let mut one = vec![0.0; plan.len()];
                plan.compute(rec, &mut SpectrumScratch::default(), &mut one).unwrap();
                assert_eq!(bits(got), bits(&one), "{what}: the {c} component's spectrum from the RotD passes");
            }
        }
    }
}

#[test]
fn rotd_from_its_angles_only_gives_the_bits_of_every_angle_solved() {
    // Pairs of every kind the summaries meet: independent, polarised at several angles, nearly
    // circular, one component silent or scaled down, a quiet start, a sine against noise; at
    // dampings from none to 20%, both readings and both record ends. RotD50, RotD100 and its
    // angle from the angles they depend on must be those of all 180 peaks solved.
    let dt = 5.3e-5;
    let periods = log_periods(1e-4, 0.1, 30);
    let mut pairs: Vec<(String, Vec<f64>, Vec<f64>)> = vec![];
    for seed in 0..4u64 {
        let (x, y) =
            (processed(100 + seed, 300 + 50 * seed as usize, dt), processed(200 + seed, 300 + 50 * seed as usize, dt));
        let phi = 0.37 + seed as f64;
        pairs.push((format!("processed {seed}"), x.clone(), y.clone()));
        pairs.push((
            format!("polarised {seed}"),
            x.iter().map(|a| phi.cos() * a).collect(),
            x.iter().map(|a| phi.sin() * a).collect(),
        ));
        pairs.push((format!("weak y {seed}"), x.clone(), y.iter().map(|a| 1e-3 * a).collect()));
        pairs.push((
            format!("nearly polarised {seed}"),
            x.clone(),
            x.iter().zip(&y).map(|(a, b)| 0.9 * a + 0.05 * b).collect(),
        ));
    }
    let rec = records(dt);
    pairs.push(("zero prefix, one silent".into(), rec[2].1.clone(), vec![0.0; rec[2].1.len()]));
    pairs.push(("sine and noise".into(), rec[4].1.clone(), processed(31, 800, dt)));
    let n = 500;
    let w = 2.0 * std::f64::consts::PI / (23.0 * dt);
    pairs.push((
        "circular".into(),
        (0..n).map(|i| (w * i as f64 * dt).cos()).collect(),
        (0..n).map(|i| (w * i as f64 * dt).sin()).collect(),
    ));
    let mut compared = 0;
    for (reading, end) in [
        (Reading::Linear, RecordEnd::Ramp),
        (Reading::Linear, RecordEnd::Step),
        (Reading::BandLimited, RecordEnd::Ramp),
    ] {
        let plan = SpectrumPlan::new(dt, &periods, &[0.0, 0.05, 0.2], reading, 4).unwrap().with_record_end(end);
        let (rotd, every) = (RotDPlan::from_plan(plan.clone()), RotDPlan::from_plan(plan).every_angle());
        let (mut s1, mut s2) = (RotDScratch::default(), RotDScratch::default());
        for (name, x, y) in &pairs {
            let n = x.len().min(y.len());
            let (mut a, mut b) = (RotDSpectrum::default(), RotDSpectrum::default());
            rotd.compute(&x[..n], &y[..n], &mut s1, &mut a).unwrap();
            every.compute(&x[..n], &y[..n], &mut s2, &mut b).unwrap();
            let what = format!("{reading:?} {end:?}, {name}");
            assert!(a.per_angle.is_empty(), "{what}");
            assert_eq!(bits(&a.rotd50), bits(&b.rotd50), "{what}: RotD50");
            assert_eq!(bits(&a.rotd100), bits(&b.rotd100), "{what}: RotD100");
            assert_eq!(bits(&a.rotd100_angle_deg), bits(&b.rotd100_angle_deg), "{what}: angle");
            assert_eq!(bits(&a.x), bits(&b.x), "{what}: x");
            assert_eq!(bits(&a.y), bits(&b.y), "{what}: y");
            compared += a.rotd50.len();
        }
    }
    println!("{compared} outputs compared");
}
