//! Calibration aid: sweeps assumed scene values over seeds and reports the main shocks.
//! Usage: calibrate <pipeline.toml> "<key>=<v1,v2,..>" ... (keys: z, d2, t0, frac, dur, d1)
use std::ops::ControlFlow;

use rayon::prelude::*;
use stickslip_analysis::Pipeline;
use stickslip_analysis::events::{EventParams, detect};
use stickslip_solver::{Model, RunOptions, Scene};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let base = Pipeline::load(std::path::Path::new(&args[1])).unwrap();
    let mut grid: Vec<Vec<(String, f64)>> = vec![vec![]];
    for spec in &args[2..] {
        let (k, vs) = spec.split_once('=').unwrap();
        let vals: Vec<f64> = vs.split(',').map(|v| v.parse().unwrap()).collect();
        grid = grid
            .into_iter()
            .flat_map(|g| {
                vals.iter().map(move |&v| {
                    let mut g = g.clone();
                    g.push((k.to_string(), v));
                    g
                })
            })
            .collect();
    }
    let seeds: Vec<u64> = std::env::var("SEEDS")
        .map(|s| s.split(',').map(|v| v.parse().unwrap()).collect())
        .unwrap_or(vec![123, 200, 7, 1, 2, 3]);
    let params = EventParams::default();
    for g in grid {
        let mut file = base.scene.file.clone();
        for (k, v) in &g {
            match k.as_str() {
                "z" => file.shear.driver_at_m = vec![[0.0, file.shear.driver_at_m.first().map_or(0.0, |p| p[1]), *v]],
                "y" => file.shear.driver_at_m = vec![[0.0, *v, file.shear.driver_at_m.first().map_or(0.2, |p| p[2])]],
                "d2" => file.shear.damping_per_s = *v,
                "d1" => file.self_weight.damping_per_s = *v,
                "t0" => file.shear.rise_time_s = *v,
                "frac" => file.time.dt_fraction = Some(*v),
                "dur" => file.shear.duration_s = *v,
                "vel" => file.shear.velocity_m_s = *v,
                "mud" => file.friction.mu_dynamic = Some(*v),
                "dc" => file.friction.slip_weakening_m = *v,
                _ => panic!("unknown key {k}"),
            }
        }
        let model = Model::new(Scene::try_from(file).unwrap());
        let results: Vec<_> = seeds
            .par_iter()
            .map(|&s| {
                let out =
                    stickslip_solver::run_seed(&model, s, RunOptions::default(), &mut |_| ControlFlow::Continue(()))
                        .unwrap();
                let cat = detect(&out.records, model.contact().len(), model.lattice().contact_area(), &params).unwrap();
                (s, cat)
            })
            .collect();
        let mut s2d = vec![];
        let mut s2t = vec![];
        let mut rec = vec![];
        let mut nm = vec![];
        println!("== {:?}", g);
        for (s, cat) in &results {
            let mains: Vec<_> = cat.main_shocks().collect();
            nm.push(mains.len() as f64);
            let desc: Vec<String> = mains
                .iter()
                .map(|e| {
                    format!(
                        "{:.1}kPa/{:.1}ms/{:.1}ms@{:.3}({})",
                        e.burst.stress_drop_pa / 1e3,
                        e.burst.duration_s() * 1e3,
                        e.burst.drop_time_s() * 1e3,
                        e.burst.start_s,
                        e.sub_events.len()
                    )
                })
                .collect();
            println!("  seed {s}: {} events, mains: {}", cat.events.len(), desc.join(" "));
            if let Some(e) = mains.get(1) {
                s2d.push(e.burst.stress_drop_pa);
                s2t.push(e.burst.drop_time_s());
                rec.push(e.recurrence_s.unwrap());
            }
        }
        let mean = |v: &Vec<f64>| if v.is_empty() { f64::NAN } else { v.iter().sum::<f64>() / v.len() as f64 };
        println!(
            "  SUMMARY mains {:.1}  S2 drop {:.0} Pa  S2 dur {:.2} ms  S1-S2 {:.1} ms  (n={})",
            mean(&nm),
            mean(&s2d),
            mean(&s2t) * 1e3,
            mean(&rec) * 1e3,
            s2d.len()
        );
    }
}
