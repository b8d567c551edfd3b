//! Response spectra: 100 periods at 5% on records of 4096, 11800 and 41200 points, the planned
//! (vectorised across oscillators, coefficients computed once) method against a straightforward
//! per-period implementation of the same exact recurrence, in the same run.
//!
//! `cargo bench -p stickslip-lab --bench response_spectra`

use std::f64::consts::PI;
use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use stickslip_seismo::spectra::response::{Reading, SpectrumPlan, SpectrumScratch, free_vibration_peak, log_periods};

/// Nigam–Jennings coefficients by their closed form (Nigam & Jennings 1969, as in most codes).
fn nj(omega: f64, xi: f64, h: f64) -> [f64; 8] {
    let wd = omega * (1.0 - xi * xi).sqrt();
    let (e, s, c) = ((-xi * omega * h).exp(), (wd * h).sin(), (wd * h).cos());
    let r = xi / (1.0 - xi * xi).sqrt();
    let (a11, a12) = (e * (r * s + c), e * s / wd);
    let (a21, a22) = (-omega / (1.0 - xi * xi).sqrt() * e * s, e * (c - r * s));
    let (w2, w3) = (omega * omega, omega * omega * omega);
    let p = (2.0 * xi * xi - 1.0) / (w2 * h);
    let q = 2.0 * xi / (w3 * h);
    let b11 = e * ((p + xi / omega) * s / wd + (q + 1.0 / w2) * c) - q;
    let b12 = -e * (p * s / wd + q * c) - 1.0 / w2 + q;
    let b21 = e * ((p + xi / omega) * (c - r * s) - (q + 1.0 / w2) * (wd * s + xi * omega * c)) + 1.0 / (w2 * h);
    let b22 = -e * (p * (c - r * s) - q * (wd * s + xi * omega * c)) - 1.0 / (w2 * h);
    [a11, a12, a21, a22, b11, b12, b21, b22]
}

/// One period at a time: coefficients, a scalar loop with the same sub-steps and peak rule.
fn straightforward(x: &[f64], dt: f64, periods: &[f64], xi: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for &t in periods {
        let omega = 2.0 * PI / t;
        let m = ((40.0 * dt / t).ceil() as usize).clamp(1, 256).next_power_of_two();
        let h = dt / m as f64;
        let [a11, a12, a21, a22, b11, b12, b21, b22] = nj(omega, xi, h);
        let (mut u, mut v, mut peak) = (0.0f64, 0.0f64, 0.0f64);
        for w in x.windows(2) {
            for k in 0..m {
                let s0 = w[0] + (w[1] - w[0]) * k as f64 / m as f64;
                let s1 = w[0] + (w[1] - w[0]) * (k + 1) as f64 / m as f64;
                let un = a11 * u + a12 * v + b11 * s0 + b12 * s1;
                let vn = a21 * u + a22 * v + b21 * s0 + b22 * s1;
                u = un;
                v = vn;
                let acc = -s1 - 2.0 * xi * omega * v - omega * omega * u;
                let tau = -v / acc;
                let turning = if tau.abs() < 0.5 * h { (u + 0.5 * v * tau).abs() } else { 0.0 };
                peak = peak.max(u.abs()).max(turning);
            }
        }
        out.push(peak.max(free_vibration_peak(u, v, omega, xi)));
    }
    out
}

fn bench(c: &mut Criterion) {
    let dt = 0.01;
    let periods = log_periods(0.02, 10.0, 100);
    let plan = SpectrumPlan::new(dt, &periods, &[0.05], Reading::Linear, 1);
    let mut scratch = SpectrumScratch::default();
    let mut sd = vec![0.0; plan.len()];
    let mut group = c.benchmark_group("response_spectrum_100_periods_5pct");
    group.sample_size(10);
    for n in [4096usize, 11800, 41200] {
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(n as u64);
        let x: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..1.0)).collect();
        // Both give the same spectrum.
        plan.compute(&x, &mut scratch, &mut sd);
        let reference = straightforward(&x, dt, &periods, 0.05);
        for (a, b) in sd.iter().zip(&reference) {
            assert!((a / b - 1.0).abs() < 1e-9, "planned {a} vs straightforward {b}");
        }
        group.bench_with_input(BenchmarkId::new("planned", n), &x, |b, x| {
            b.iter(|| plan.compute(black_box(x), &mut scratch, &mut sd))
        });
        group.bench_with_input(BenchmarkId::new("straightforward", n), &x, |b, x| {
            b.iter(|| black_box(straightforward(black_box(x), dt, &periods, 0.05)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
