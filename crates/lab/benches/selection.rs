//! Record-set selection: 11 records from 1 000 candidates of 100 periods (EC8 target, T₁ = 1 s).
//!
//! `cargo bench -p stickslip-lab --bench selection`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use stickslip_seismo::design::{Ec8, Ec8Type, GroundType};
use stickslip_seismo::selection::{Candidate, PeriodRange, SelectionOptions, select};

/// 1 000 candidates: target × exp(a + b·ln T + c·sin(2 ln T + φ)) with random a, b, c, φ, in 300
/// groups, 5% of them with a usable band that stops at 1.5 s (not eligible for 0.2–2 s).
fn problem() -> (Vec<f64>, Vec<f64>, Vec<Candidate>) {
    let periods: Vec<f64> = (0..100).map(|i| 0.02 * 500f64.powf(i as f64 / 99.0)).collect(); // 0.02–10 s
    let ec8 = Ec8::new(2.5, Ec8Type::Type1, GroundType::C, 5.0).expect("valid EC8 parameters");
    let target: Vec<f64> = periods.iter().map(|&t| ec8.psa(t).expect("period ≥ 0")).collect();
    let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(2024);
    let candidates = (0..1000)
        .map(|i| {
            let a = 1.2 * (rng.random::<f64>() - 0.5);
            let b = 0.8 * (rng.random::<f64>() - 0.5);
            let c = 0.6 * (rng.random::<f64>() - 0.5);
            let phi = std::f64::consts::TAU * rng.random::<f64>();
            let psa = target
                .iter()
                .zip(&periods)
                .map(|(v, t)| v * (a + b * t.ln() + c * (2.0 * t.ln() + phi).sin()).exp())
                .collect();
            Candidate {
                id: format!("r{i}"),
                group: format!("seed{}/event{}", i % 300, i % 7),
                psa,
                usable_min: 0.01,
                usable_max: if rng.random::<f64>() < 0.05 { 1.5 } else { 10.0 },
            }
        })
        .collect();
    (periods, target, candidates)
}

fn bench(c: &mut Criterion) {
    let (periods, target, candidates) = problem();
    let opts = SelectionOptions::new(PeriodRange::Fundamental { t1: 1.0 });
    let sel = select(&periods, &target, &candidates, &opts).expect("a set exists");
    eprintln!(
        "selected {} of {} eligible: min ratio {:.3} at {:.3} s, mean log misfit {:.2e}, J {:.2e}, common scale {:.3}",
        sel.records.len(),
        sel.eligible,
        sel.min_ratio,
        sel.min_ratio_period,
        sel.mean_log_misfit,
        sel.objective,
        sel.common_scale
    );
    c.bench_function("select 11 of 1000 candidates x 100 periods", |b| {
        b.iter(|| select(black_box(&periods), black_box(&target), black_box(&candidates), &opts))
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = bench
}
criterion_main!(benches);
