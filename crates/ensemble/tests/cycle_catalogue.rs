//! A cycle catalogue end to end (docs/model.md §20.6): a small heterogeneous fault over two
//! seeds, each seed's fault carrying its own field, the events gathered with their seed and
//! magnitude, an interrupted run keeping its finished seeds and resuming at the next.
//!
//! `cargo test --release -p stickslip-ensemble --test cycle_catalogue -- --nocapture` prints the
//! events.

use std::sync::atomic::AtomicBool;

use stickslip_config::Pipeline;
use stickslip_ensemble::cycle_catalogue::{run_cycle_catalogue, seed_folder};
use stickslip_solver::cycles::QuasiDynamicFault;
use stickslip_solver::cycles::heterogeneity::{STREAM_CYCLES_A, von_karman_line};
use stickslip_support::{read_table, scratch_dir};

/// A 20 km fault at 100 m (200 nodes), a = 0.016·exp(0.4·g) around b = 0.015, 150 years: a few
/// events a seed in a few seconds.
const PIPELINE: &str = r#"
version = 1
name = "small-catalogue"
description = "a small heterogeneous fault"
[seeds]
list = [1, 2]
[block]
nx = 1
ny = 1000
nz = 1000
lc_m = 100.0
[material]
young_pa = 8.00953008e10
density_kg_m3 = 2670.0
poisson = 0.25
young_cv = 0.0
[self_weight]
gravity_m_s2 = 0.0
[friction]
law = "rate_state_aging"
[friction.rate_state]
a = 0.016
b = 0.015
dc_m = 0.008
v0_m_s = 1e-6
f0 = 0.6
initial_slip_rate_m_s = 1e-9
[fault]
normal_stress_pa = 50e6
shear_stress_pa = 26546122.365133364
[cycles]
years = 150.0
plate_rate_m_s = 1e-9
frictional_depth_m = 20000.0
stations_depth_m = [0.0]
[cycles.heterogeneity]
log_a_std = 0.4
correlation_length_m = 2000.0
hurst = 0.3
"#;

fn column(df: &polars::prelude::DataFrame, name: &str) -> Vec<f64> {
    df.column(name).unwrap().f64().unwrap().into_no_null_iter().collect()
}

#[test]
fn each_seed_draws_its_own_fault_and_the_catalogue_resumes_where_it_stopped() {
    let dir = scratch_dir("cycle-catalogue");
    let path = dir.join("small.toml");
    std::fs::write(&path, PIPELINE).unwrap();
    let pipeline = Pipeline::load(&path).unwrap();
    let spec = pipeline.cycles.as_ref().unwrap();

    // Each seed's fault: a = 0.016·exp(0.4·g) with g the seed's own field, b and L as given.
    let g = von_karman_line(200, 100.0, 2000.0, 0.3, 1, STREAM_CYCLES_A).unwrap();
    let fault = QuasiDynamicFault::from_scene(&pipeline.scene, spec, 1).unwrap();
    assert_eq!(fault.friction.len(), 200);
    for (node, g) in fault.friction.iter().zip(&g) {
        assert!((node.a - 0.016 * (0.4 * g).exp()).abs() < 1e-15, "{} against {}", node.a, 0.016 * (0.4 * g).exp());
        assert_eq!((node.b, node.dc_m), (0.015, 0.008));
    }
    let other = QuasiDynamicFault::from_scene(&pipeline.scene, spec, 2).unwrap();
    assert!(fault.friction.iter().zip(&other.friction).filter(|(x, y)| x.a != y.a).count() > 190);

    // Interrupted before it starts: nothing finished, the error names the seed.
    let out = dir.join("out");
    let r = run_cycle_catalogue(&pipeline, &out, &AtomicBool::new(true), |_| {}).unwrap();
    assert_eq!((r.interrupted, r.seeds.len()), (Some(1), 0));
    assert!(!seed_folder(&out, 1).join("complete").exists());

    // Run whole: both seeds run; then again: both read back, the same catalogue.
    let mut ran = Vec::new();
    let first = run_cycle_catalogue(&pipeline, &out, &AtomicBool::new(false), |s| ran.push(s.run.is_some())).unwrap();
    assert_eq!((first.interrupted, ran.as_slice()), (None, [true, true].as_slice()));
    let events = read_table(&out.join("tables/cycle_events.parquet"));
    let seeds: Vec<u64> = events.column("seed").unwrap().u64().unwrap().into_no_null_iter().collect();
    for s in &first.seeds {
        println!("seed {}: {} events", s.seed, s.events.len());
        for e in &s.events {
            println!(
                "  {:.3} years, {:.2}–{:.2} km, Mw {:.3}",
                e.onset_s / stickslip_solver::cycles::YEAR_S,
                e.ruptured_m[0] / 1e3,
                e.ruptured_m[1] / 1e3,
                e.magnitude(100.0)
            );
        }
        assert!(!s.events.is_empty(), "seed {} has no event in 150 years", s.seed);
        assert_eq!(seeds.iter().filter(|&&k| k == s.seed).count(), s.events.len());
    }
    assert_ne!(
        first.seeds[0].events.iter().map(|e| e.onset_s).collect::<Vec<_>>(),
        first.seeds[1].events.iter().map(|e| e.onset_s).collect::<Vec<_>>(),
        "two seeds, two faults, two histories"
    );
    // Each event's magnitude is its moment per metre times its length (a rupture as long along
    // strike as down dip) through Hanks & Kanamori.
    let (per_m, length, moment, mw) = (
        column(&events, "moment_per_m_n"),
        column(&events, "length_m"),
        column(&events, "moment_n_m"),
        column(&events, "magnitude"),
    );
    let (top, bottom) = (column(&events, "ruptured_top_m"), column(&events, "ruptured_bottom_m"));
    for i in 0..mw.len() {
        // The surface node carries half a module.
        let surface = if top[i] == 0.0 { 50.0 } else { 0.0 };
        assert_eq!(length[i], bottom[i] - top[i] + 100.0 - surface);
        assert!((moment[i] - per_m[i] * length[i]).abs() <= 1e-12 * moment[i]);
        assert!((mw[i] - 2.0 / 3.0 * (moment[i].log10() - 9.1)).abs() < 1e-12);
    }
    // The catalogue tables hold each seed's fit and the pooled one.
    let b = read_table(&out.join("tables/b_values.parquet"));
    assert_eq!(b.height(), 3, "{b}");

    let mut again = Vec::new();
    let second =
        run_cycle_catalogue(&pipeline, &out, &AtomicBool::new(false), |s| again.push(s.run.is_some())).unwrap();
    assert_eq!(again, [false, false], "finished seeds are read back, not run again");
    for (a, b) in first.seeds.iter().zip(&second.seeds) {
        assert_eq!(a.events, b.events);
    }
    assert_eq!(read_table(&out.join("tables/cycle_events.parquet")), events);

    // A changed pipeline (another hash) runs its seeds again.
    let changed = PIPELINE.replace("years = 150.0", "years = 20.0");
    std::fs::write(&path, changed).unwrap();
    let shorter = Pipeline::load(&path).unwrap();
    let mut third = Vec::new();
    run_cycle_catalogue(&shorter, &out, &AtomicBool::new(false), |s| third.push(s.run.is_some())).unwrap();
    assert_eq!(third, [true, true]);
    // Back to the first pipeline, interrupted at once: seed 1's marker (the shorter run's) is
    // gone with the files it vouched for, so the next run runs it again.
    let r = run_cycle_catalogue(&pipeline, &out, &AtomicBool::new(true), |_| {}).unwrap();
    assert_eq!(r.interrupted, Some(1));
    assert!(!seed_folder(&out, 1).join("complete").exists());
    assert!(seed_folder(&out, 2).join("complete").exists());
}

#[test]
#[ignore = "the shipped catalogue: 3 seeds × 400 years, about 40 minutes; run with --ignored"]
fn the_shipped_catalogue_gives_the_documented_statistics() {
    // The guide's faults chapter (A catalogue of earthquake cycles) and the README: 918 events,
    // b = 0.57 ± 0.02 above Mc = 3.3, main-shock recurrence CV 1.16. The history is chaotic, so
    // the figures are held as statistics: the count within 10%, b within twice its σ.
    let pipeline = Pipeline::load(&stickslip_support::repo_path("pipelines/cycles-catalogue.toml")).unwrap();
    let dir = scratch_dir("cycle-catalogue-shipped");
    let r = run_cycle_catalogue(&pipeline, &dir.join("out"), &AtomicBool::new(false), |_| {}).unwrap();
    let events: usize = r.seeds.iter().map(|s| s.events.len()).sum();
    let pooled = r.stats.b_values.iter().find(|b| b.seed.is_none()).unwrap();
    let fit = pooled.fit.as_ref().unwrap();
    let main = r.stats.recurrence.iter().find(|x| x.seed.is_none() && x.sequence == "main").unwrap();
    let cv = main.stats.as_ref().unwrap().cv;
    println!("{events} events; b = {:.3} ± {:.3} above {:.1}; main-shock CV {cv:.3}", fit.b, fit.b_sigma, fit.mc);
    assert!((events as f64 - 918.0).abs() < 92.0, "{events} events");
    assert!((fit.b - 0.57).abs() < 2.0 * 0.017, "b = {}", fit.b);
    assert!(fit.b < 0.8, "b = {} would meet the issue's goal: update the docs", fit.b);
    assert!((cv - 1.16).abs() < 0.2, "CV {cv}");
}
