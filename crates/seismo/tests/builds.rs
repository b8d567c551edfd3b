//! Every instruction-set build of the oscillator banks (each of `Isa::available()` pinned in
//! turn), like the solver's kernel tests: the response spectra and RotD agree bit for bit build
//! against build, and within [`PLAIN`] with a plain loop that runs one oscillator at a time
//! (measured: the one-component spectra have the loop's bits, RotD is within 5e-15).
//!
//! The plain loop is the scalar rule the banks vectorise: the Nigam–Jennings step
//! ([`Oscillator::step`]), the exact peak inside every step ([`Oscillator::step_peak`], tested
//! against dense scans in its module) and the free vibration after the record
//! ([`Oscillator::free_peak`]). Its RotD rotates the record for every angle.

mod support;

use stickslip_isa::Isa;
use stickslip_seismo::spectra::oscillator::Oscillator;
use stickslip_seismo::spectra::response::{Reading, RecordEnd, SpectrumPlan, SpectrumScratch};
use stickslip_seismo::spectra::rotd::{ANGLES, RotDPlan, RotDScratch, RotDSpectrum};
use support::{per_angle_by_rotation, random_record};

/// Relative tolerance against the plain loop: the exact peaks' stated accuracy, as in
/// `tests/spectra.rs` and `tests/rotd.rs`, not zero. One component: the loop steps with the
/// same arithmetic, so it usually gives the same bits, but the bank solves a step exactly only
/// where its rounded bounds exceed the running peak, and `step_peak` skips the parts of a step
/// that cannot beat the floor it is given, so where an interior extremum is within rounding of
/// the peak the two may keep values some ulps apart. RotD: the banks rotate the two responses,
/// the loop rotates the record (the same by linearity, not the same rounding). The builds run
/// one source and must agree exactly.
const PLAIN: f64 = 1e-12;

/// Periods from far below Δt = 0.01 s to far above it, and dampings from none to 20%: 27
/// oscillators, so the banks (padded to multiples of 8) carry padding.
const PERIODS: [f64; 9] = [0.004, 0.013, 0.02, 0.031, 0.05, 0.13, 0.4, 1.1, 3.0];
const DAMPINGS: [f64; 3] = [0.0, 0.05, 0.2];
const DT: f64 = 0.01;

/// The readings and record ends of the tests. The plain loop reads straight lines between the
/// samples only (the band-limited reading's resampled record is not public), so the
/// band-limited plans are checked build against build.
const CASES: [(Reading, RecordEnd); 4] = [
    (Reading::Linear, RecordEnd::Ramp),
    (Reading::Linear, RecordEnd::Step),
    (Reading::BandLimited, RecordEnd::Ramp),
    (Reading::BandLimited, RecordEnd::Step),
];

fn plan(reading: Reading, end: RecordEnd) -> SpectrumPlan {
    SpectrumPlan::new(DT, &PERIODS, &DAMPINGS, reading, 4).unwrap().with_record_end(end)
}

/// SD of every output of `plan` (linear reading), damping-major, one oscillator at a time:
/// from rest through the steps between samples (and the ramp to zero after the last one for
/// [`RecordEnd::Ramp`]), the peak at every step's end and inside it, then the free vibration.
fn plain_sd(plan: &SpectrumPlan, x: &[f64]) -> Vec<f64> {
    assert_eq!(plan.reading(), Reading::Linear);
    let tail = match plan.record_end() {
        RecordEnd::Ramp => x.last().map(|&a| [a, 0.0]),
        RecordEnd::Step => None,
    };
    let mut out = vec![];
    for &xi in plan.dampings() {
        for &t in plan.periods() {
            let osc = Oscillator::new(t, xi, plan.dt());
            let (mut u, mut v, mut peak) = (0.0f64, 0.0f64, 0.0f64);
            for [a0, a1] in x.windows(2).map(|w| [w[0], w[1]]).chain(tail) {
                let (u1, v1) = osc.step(u, v, a0, a1);
                peak = osc.step_peak(u, v, a0, a1, peak.max(u1.abs()));
                (u, v) = (u1, v1);
            }
            out.push(peak.max(osc.free_peak(u, v)));
        }
    }
    out
}

fn bits(x: &[f64]) -> Vec<u64> {
    x.iter().map(|v| v.to_bits()).collect()
}

/// Largest `|got − want|` relative to `scale(o)` over the outputs; panics past [`PLAIN`].
fn against_plain(got: &[f64], want: &[f64], scale: impl Fn(usize) -> f64, what: &str) -> f64 {
    assert_eq!(got.len(), want.len(), "{what}");
    let mut worst = 0.0f64;
    for (i, (a, b)) in got.iter().zip(want).enumerate() {
        let rel = (a - b).abs() / scale(i);
        assert!(rel <= PLAIN, "{what}, entry {i}: {a} vs plain {b}");
        worst = worst.max(rel);
    }
    worst
}

/// Records: two random ones, one that ends at its largest value (the ramp and the free
/// vibration hold the peak), a resonant sine at a period between two of the plan's.
fn records() -> Vec<(&'static str, Vec<f64>)> {
    let mut ends_high = random_record(250, 31);
    ends_high.push(12.0);
    let sine = (0..600).map(|i| 3.0 * (2.0 * std::f64::consts::PI * i as f64 * DT / 0.2).sin()).collect();
    vec![("random", random_record(500, 7)), ("random", random_record(173, 8)), ("ends high", ends_high), ("sine", sine)]
}

#[test]
fn every_build_of_the_oscillator_bank_agrees_with_a_plain_loop() {
    let builds = Isa::available();
    println!("builds on this CPU: {builds:?}");
    for (reading, end) in CASES {
        let plan = plan(reading, end);
        for (name, x) in records() {
            let sd: Vec<Vec<f64>> = builds
                .iter()
                .map(|&isa| {
                    let mut sd = vec![0.0; plan.len()];
                    Isa::pinned(isa, || plan.compute(&x, &mut SpectrumScratch::default(), &mut sd)).unwrap();
                    sd
                })
                .collect();
            for (isa, got) in builds.iter().zip(&sd) {
                assert_eq!(bits(got), bits(&sd[0]), "{reading:?} {end:?}, {name}: {isa:?} against {:?}", builds[0]);
            }
            if reading == Reading::Linear {
                let want = plain_sd(&plan, &x);
                let worst = against_plain(&sd[0], &want, |o| want[o], &format!("{reading:?} {end:?}, {name}"));
                let differ = sd[0].iter().zip(&want).filter(|(a, b)| a != b).count();
                println!(
                    "{reading:?} {end:?}, {name}: {differ} of {} outputs off the plain loop's bits, largest {worst:.1e}",
                    want.len()
                );
            }
        }
    }
}

#[test]
fn every_build_of_rotd_agrees_with_the_plain_loop_on_the_rotated_record() {
    let builds = Isa::available();
    println!("builds on this CPU: {builds:?}");
    let (x, y) = (random_record(300, 21), random_record(300, 22));
    // A linearly polarised pair: a flat hull, so every step is looked at across the angles.
    let (px, py): (Vec<f64>, Vec<f64>) = x.iter().map(|a| (0.6 * a, 0.8 * a)).unzip();
    for (reading, end) in CASES {
        let plan = plan(reading, end);
        let (summary_plan, rotd_plan) =
            (RotDPlan::from_plan(plan.clone()), RotDPlan::from_plan(plan.clone()).every_angle());
        for (name, x, y) in [("random", &x, &y), ("polarised", &px, &py)] {
            let compute = |plan: &RotDPlan, isa| {
                let mut out = RotDSpectrum::default();
                Isa::pinned(isa, || plan.compute(x, y, &mut RotDScratch::default(), &mut out)).unwrap();
                out
            };
            let got: Vec<RotDSpectrum> = builds.iter().map(|&isa| compute(&rotd_plan, isa)).collect();
            let summaries: Vec<RotDSpectrum> = builds.iter().map(|&isa| compute(&summary_plan, isa)).collect();
            let first = &got[0];
            for ((isa, g), s) in builds.iter().zip(&got).zip(&summaries) {
                let what = format!("{reading:?} {end:?}, {name}: {isa:?} against {:?}", builds[0]);
                assert_eq!(bits(&g.per_angle), bits(&first.per_angle), "{what}, per angle");
                for (got, rotd) in [(g, "every angle"), (s, "RotD's angles only")] {
                    assert_eq!(bits(&got.rotd50), bits(&first.rotd50), "{what}, RotD50, {rotd}");
                    assert_eq!(bits(&got.rotd100), bits(&first.rotd100), "{what}, RotD100, {rotd}");
                    assert_eq!(bits(&got.rotd100_angle_deg), bits(&first.rotd100_angle_deg), "{what}, angle, {rotd}");
                }
            }
            if reading == Reading::Linear {
                let want = per_angle_by_rotation(x, y, |rotated| plain_sd(&plan, rotated));
                // Relative to each output's largest peak, as in `tests/rotd.rs` (an angle across
                // the polarisation has a peak near zero).
                let scale = |i: usize| {
                    let o = i / ANGLES;
                    want[o * ANGLES..(o + 1) * ANGLES].iter().fold(0.0f64, |m, &v| m.max(v))
                };
                let what = format!("{reading:?} {end:?}, {name}");
                let worst = against_plain(&first.per_angle, &want, scale, &what);
                let (mut rotd50, mut rotd100) = (vec![], vec![]);
                for o in 0..plan.len() {
                    let mut sorted = want[o * ANGLES..(o + 1) * ANGLES].to_vec();
                    sorted.sort_by(f64::total_cmp);
                    rotd50.push(0.5 * (sorted[ANGLES / 2 - 1] + sorted[ANGLES / 2]));
                    rotd100.push(sorted[ANGLES - 1]);
                }
                against_plain(&first.rotd50, &rotd50, |o| rotd100[o], &format!("{what}, RotD50"));
                against_plain(&first.rotd100, &rotd100, |o| rotd100[o], &format!("{what}, RotD100"));
                let differ = first.per_angle.iter().zip(&want).filter(|(a, b)| a != b).count();
                println!(
                    "{what}: {differ} of {} peaks off the plain loop's bits, largest {worst:.1e} of the output's RotD100",
                    want.len()
                );
            }
        }
    }
}
