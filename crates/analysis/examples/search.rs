//! Calibration aid: random search over the assumed scene values, scored against the paper's
//! S2 stress drop, S2 duration and S1→S2 recurrence (averaged over seeds).
use std::ops::ControlFlow;

use rand::{RngExt, SeedableRng};
use rayon::prelude::*;
use stickslip_analysis::Pipeline;
use stickslip_analysis::events::{EventParams, detect};
use stickslip_solver::{Model, RunOptions, Scene};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let base = Pipeline::load(std::path::Path::new(&args[1])).unwrap();
    let n: usize = args[2].parse().unwrap();
    let seeds = [123u64, 200, 7, 1];
    let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(args.get(3).map_or(1, |s| s.parse().unwrap()));
    let configs: Vec<(f64, f64, f64, f64)> = (0..n)
        .map(|_| {
            let z = [0.1, 0.2, 0.3, 0.4][rng.random_range(0..4)];
            let d2 = 10f64.powf(rng.random_range(0.7..3.0));
            let t0 = 10f64.powf(rng.random_range(-3.5..-1.7));
            let d1 = 2500.0;
            (z, d2, t0, d1)
        })
        .collect();
    let params = EventParams::default();
    let mut scored: Vec<(f64, String)> = configs
        .par_iter()
        .map(|&(z, d2, t0, d1)| {
            let mut file = base.scene.file.clone();
            file.shear.driver_at_m = vec![[0.0, 0.0, z]];
            file.shear.damping_per_s = d2;
            file.shear.rise_time_s = t0;
            file.self_weight.damping_per_s = d1;
            file.shear.duration_s = 0.2;
            let model = Model::new(Scene::try_from(file).unwrap());
            let mut loss = 0.0;
            let mut desc = String::new();
            for &s in &seeds {
                let out =
                    stickslip_solver::run_seed(&model, s, RunOptions::default(), &mut |_| ControlFlow::Continue(()))
                        .unwrap();
                let cat = detect(&out.records, model.contact().len(), model.lattice().contact_area(), &params).unwrap();
                let mains: Vec<_> = cat.main_shocks().collect();
                let big = cat.events.iter().filter(|e| e.burst.stress_drop_pa > 2000.0).count();
                let l = |a: f64, b: f64| (a / b).ln().powi(2);
                let mut ls = if mains.len() >= 4 { 0.0 } else { 0.5 * (4 - mains.len()) as f64 };
                if big < 4 {
                    ls += 0.5 * (4 - big) as f64;
                }
                if let Some(e) = mains.get(1) {
                    ls += l(e.burst.stress_drop_pa, 7600.0)
                        + l(e.burst.duration_s(), 2.1e-3)
                        + l(e.recurrence_s.unwrap(), 25.8e-3);
                    desc += &format!(
                        " [{}: {} mains, S2 {:.1}kPa {:.1}ms rec {:.1}ms]",
                        s,
                        mains.len(),
                        e.burst.stress_drop_pa / 1e3,
                        e.burst.duration_s() * 1e3,
                        e.recurrence_s.unwrap() * 1e3
                    );
                } else {
                    ls += 5.0;
                    desc += &format!(" [{}: {} mains]", s, mains.len());
                }
                loss += ls;
            }
            (loss / seeds.len() as f64, format!("z={z} d2={d2:.0} t0={t0:.4} d1={d1:.0}:{desc}"))
        })
        .collect();
    scored.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (l, d) in scored.iter().take(15) {
        println!("{l:.3} {d}");
    }
}
