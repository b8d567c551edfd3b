//! The paper scene shows stick-slip (issue acceptance): drops of the 1-ms-averaged shear stress
//! larger than 2 kPa, each with a jump of the mean contact displacement.

mod common;

use std::ops::ControlFlow;

use common::repo_path;
use stickslip_config::Pipeline;
use stickslip_solver::{Channel, Model, RunOptions, run_seed};

/// Centred moving average over `w` samples.
fn smooth(x: &[f64], w: usize) -> Vec<f64> {
    (0..x.len())
        .map(|i| {
            let lo = i.saturating_sub(w / 2);
            let hi = (i + w - w / 2).min(x.len());
            x[lo..hi].iter().sum::<f64>() / (hi - lo) as f64
        })
        .collect()
}

/// Peak-to-trough legs of `y` larger than `h` (zig-zag with reversal threshold `h`): (peak
/// index, trough index).
fn drops(y: &[f64], h: f64) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let (mut peak, mut trough, mut falling) = (0, 0, false);
    for i in 0..y.len() {
        if !falling {
            if y[i] > y[peak] {
                peak = i;
            } else if y[i] < y[peak] - h {
                falling = true;
                trough = i;
            }
        } else if y[i] < y[trough] {
            trough = i;
        } else if y[i] > y[trough] + h {
            out.push((peak, trough));
            falling = false;
            peak = i;
        }
    }
    if falling {
        out.push((peak, trough));
    }
    out
}

#[test]
fn paper_scene_shows_at_least_four_stress_drops_with_slip_for_each_seed() {
    let pipeline = Pipeline::load(&repo_path("pipelines/paper.toml")).unwrap();
    let model = Model::new(pipeline.scene.clone());
    for &seed in &pipeline.seeds {
        let out = run_seed(&model, seed, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
        let r = &out.recording;
        let w = (1e-3 / out.dt_s).round() as usize;
        let tau = smooth(r.get(Channel::ShearStress).unwrap(), w);
        let delta = r.get(Channel::MeanSlip).unwrap();
        let legs = drops(&tau, 2000.0);
        let mut with_slip = 0;
        for &(p, q) in &legs {
            let slip = delta[q] - delta[p];
            println!(
                "seed {seed}: drop {:6.0} Pa from t = {:.4} s to {:.4} s, slip {:.3e} m",
                tau[p] - tau[q],
                r.time_s[p],
                r.time_s[q],
                slip
            );
            if slip > 2e-7 {
                with_slip += 1;
            }
        }
        assert!(with_slip >= 4, "seed {seed}: only {with_slip} drops > 2 kPa with a slip jump");
    }
}
