//! Every statistic of the crate on one synthetic catalogue of 100 000 events with 1 000 main
//! shocks: main shocks renewing with BPT recurrence (mean 1000 s, α = 0.3), each followed by an
//! Omori–Utsu sequence (c = 0.01 s, p = 1.1, ≈ 99 events), Gutenberg–Richter magnitudes (b = 1,
//! incomplete below 1.95), moments, areas, durations and stress drops with log-normal scatter.
//!
//! `cargo bench -p stickslip-lab --bench catalogue`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use rand_distr::{Distribution, InverseGaussian, Normal};
use stickslip_seismo::catalogue::aftershocks::{Window, aftershock_rate, fit_omori, stack_aftershocks};
use stickslip_seismo::catalogue::magnitude_frequency::{log_binned_distribution, magnitude_distribution};
use stickslip_seismo::catalogue::recurrence::{
    cv_bootstrap_ci, fit_bpt, fit_exponential, fit_weibull, inter_event_times, recurrence_statistics,
};
use stickslip_seismo::catalogue::scaling::{moment_area, moment_duration, stress_drop_magnitude};

struct Catalogue {
    main_times: Vec<f64>,
    times: Vec<f64>,
    magnitudes: Vec<f64>,
    moments: Vec<f64>,
    areas: Vec<f64>,
    durations: Vec<f64>,
    stress_drops: Vec<f64>,
}

fn catalogue() -> Catalogue {
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let (mains, per_main) = (1000, 99);
    let (c, p) = (0.01f64, 1.1f64);
    let recurrence = InverseGaussian::new(1000.0, 1000.0 / 0.09).unwrap();
    let noise = Normal::new(0.0, 0.2).unwrap();
    let (mut main_times, mut times) = (Vec::new(), Vec::new());
    let mut t0 = 0.0;
    for _ in 0..mains {
        t0 += recurrence.sample(&mut rng);
        main_times.push(t0);
        times.push(t0);
        let u = 1.0 - p;
        let (lo, hi) = (c.powf(u), (500.0 + c).powf(u));
        for _ in 0..per_main {
            let r: f64 = rng.random();
            times.push(t0 + (lo + r * (hi - lo)).powf(1.0 / u) - c);
        }
    }
    let mut magnitudes = Vec::with_capacity(times.len());
    while magnitudes.len() < times.len() {
        let m = 0.5 - (1.0 - rng.random::<f64>()).ln() / std::f64::consts::LN_10;
        if m >= 1.95 || rng.random::<f64>() < 10f64.powf(5.0 * (m - 1.95)) {
            magnitudes.push(m);
        }
    }
    let moments: Vec<f64> = magnitudes.iter().map(|m| 10f64.powf(1.5 * m + 9.1)).collect();
    let mut scatter = |x: f64| x * 10f64.powf(noise.sample(&mut rng));
    let areas: Vec<f64> = moments.iter().map(|m0| scatter((m0 / 3e6).powf(2.0 / 3.0))).collect();
    let durations: Vec<f64> = moments.iter().map(|m0| scatter((m0 / 1e17).cbrt())).collect();
    let stress_drops: Vec<f64> = magnitudes.iter().map(|_| scatter(3e6)).collect();
    Catalogue { main_times, times, magnitudes, moments, areas, durations, stress_drops }
}

fn magnitude_frequency(k: &Catalogue) {
    let d = magnitude_distribution(&k.magnitudes, 0.1).unwrap();
    let maxc = d.mc_maximum_curvature(0.0).unwrap();
    let gof = d.mc_goodness_of_fit(95.0).unwrap();
    black_box((maxc, d.b_value(gof.mc).unwrap(), gof));
    black_box(log_binned_distribution(&k.moments, 10).unwrap());
    black_box(log_binned_distribution(&k.stress_drops, 10).unwrap());
}

/// Statistics, bootstrap CI of the CV (1000 resamples) and the three renewal fits of `times`.
fn recurrence(times: &[f64], bootstrap: bool) {
    let x = inter_event_times(times);
    black_box(recurrence_statistics(&x).unwrap());
    if bootstrap {
        black_box(cv_bootstrap_ci(&x, 0.95, 1000, 1).unwrap());
    }
    let positive: Vec<f64> = x.into_iter().filter(|&v| v > 0.0).collect();
    black_box((fit_bpt(&positive).unwrap(), fit_weibull(&positive).unwrap(), fit_exponential(&positive).unwrap()));
}

fn aftershocks(k: &Catalogue) {
    let w = Window { max_time: 500.0, stop_at_next_main_shock: true, catalogue_end: f64::INFINITY };
    let s = stack_aftershocks(&k.main_times, &k.times, w).unwrap();
    black_box(aftershock_rate(&s, 1e-4, 500.0, 5).unwrap());
    black_box(fit_omori(&s, 0.0, 500.0).unwrap());
}

fn scaling(k: &Catalogue) {
    black_box(moment_area(&k.areas, &k.moments).unwrap());
    black_box(moment_duration(&k.durations, &k.moments).unwrap());
    black_box(stress_drop_magnitude(&k.magnitudes, &k.stress_drops).unwrap());
}

fn bench(c: &mut Criterion) {
    let k = catalogue();
    assert_eq!((k.times.len(), k.main_times.len()), (100_000, 1000));
    // What the statistics say about this catalogue (printed once, for the record).
    let d = magnitude_distribution(&k.magnitudes, 0.1).unwrap();
    let gof = d.mc_goodness_of_fit(95.0).unwrap();
    let f = d.b_value(gof.mc).unwrap();
    let x = inter_event_times(&k.main_times);
    let w = Window { max_time: 500.0, stop_at_next_main_shock: true, catalogue_end: f64::INFINITY };
    let o = fit_omori(&stack_aftershocks(&k.main_times, &k.times, w).unwrap(), 0.0, 500.0).unwrap();
    eprintln!(
        "maxc {:.1}, gof95 Mc {:.1}, b {:.3} ± {:.3} (n {}); main-shock CV {:.3}, BPT α {:.3}; \
         Omori c {:.4} ± {:.4}, p {:.3} ± {:.3} (n {}); M0–A exponent {:.3}",
        d.mc_maximum_curvature(0.0).unwrap(),
        gof.mc,
        f.b,
        f.b_sigma,
        f.n,
        recurrence_statistics(&x).unwrap().cv,
        fit_bpt(&x).unwrap().aperiodicity,
        o.c,
        o.c_se,
        o.p,
        o.p_se,
        o.n,
        moment_area(&k.areas, &k.moments).unwrap().exponent(),
    );
    let mut g = c.benchmark_group("catalogue_100k_events_1k_main_shocks");
    g.sample_size(20);
    g.bench_function("magnitude_frequency", |b| b.iter(|| magnitude_frequency(&k)));
    g.bench_function("recurrence_main_shocks", |b| b.iter(|| recurrence(&k.main_times, true)));
    g.bench_function("recurrence_all_events_fits", |b| b.iter(|| recurrence(&k.times, false)));
    g.bench_function("cv_bootstrap_all_events", |b| {
        let x = inter_event_times(&k.times);
        b.iter(|| black_box(cv_bootstrap_ci(&x, 0.95, 1000, 1).unwrap()))
    });
    g.bench_function("aftershocks", |b| b.iter(|| aftershocks(&k)));
    g.bench_function("scaling", |b| b.iter(|| scaling(&k)));
    g.bench_function("all", |b| {
        b.iter(|| {
            magnitude_frequency(&k);
            recurrence(&k.main_times, true);
            recurrence(&k.times, false);
            aftershocks(&k);
            scaling(&k);
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
