//! Exploration: runs the paper scene (optionally overridden by a TOML file) and prints a digest.
use std::ops::ControlFlow;
use stickslip_solver::{Channel, Model, RunOptions, Scene, run_seed};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let scene = match args.get(1) {
        Some(p) => Scene::from_toml(&std::fs::read_to_string(p).unwrap()).unwrap(),
        None => Scene::paper(),
    };
    let seed: u64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(123);
    let model = Model::new(scene);
    let t = std::time::Instant::now();
    let out = run_seed(&model, seed, RunOptions::default(), &mut |_| {
        ControlFlow::Continue(())
    })
    .unwrap();
    let wall = t.elapsed().as_secs_f64();
    println!(
        "dt {:.4e} crit {:.4e} settle {:.4e}s ({} steps) shear steps {} wall {:.3}s",
        out.dt_s, out.critical.dt_s, out.settle_time_s, out.settle_steps, out.shear_steps, wall
    );
    let r = &out.records;
    let tau = r.get(Channel::ShearStress).unwrap();
    let sig = r.get(Channel::NormalStress).unwrap();
    let del = r.get(Channel::MeanSlip).unwrap();
    let slip = r.get(Channel::SlippingNodes).unwrap();
    let lift = r.get(Channel::LiftedNodes).unwrap();
    // 1 ms moving average of tau, then drops > 2 kPa.
    let dt = r.time_s[1] - r.time_s[0];
    let w = ((1e-3 / dt).round() as usize).max(1);
    let mut sm = vec![0.0; r.len()];
    let mut acc = 0.0;
    for i in 0..r.len() {
        acc += tau[i];
        if i >= w {
            acc -= tau[i - w];
        }
        sm[i] = acc / (i.min(w - 1) + 1) as f64;
    }
    let (mut imax, mut i) = (0usize, 0usize);
    let mut last_onset: Option<f64> = None;
    while i < r.len() {
        if sm[i] > sm[imax] {
            imax = i;
        }
        if sm[imax] - sm[i] > 2000.0 {
            // find local min
            let mut j = i;
            while j + 1 < r.len() && sm[j + 1] <= sm[j] + 50.0 {
                j += 1;
                if sm[j] < sm[i] {
                    i = j;
                }
            }
            let mut k = imax;
            while k < r.len() && sm[k] > sm[i] {
                if sm[k] == sm[i] {
                    break;
                }
                k += 1;
            }
            let onset = r.time_s[imax];
            println!(
                "EVENT onset {:.4} s  tau {:.0} -> {:.0} drop {:.0} Pa, to min {:.4} s (dur {:.4}), slip {:.3e} m, recurrence {:?}",
                onset,
                sm[imax],
                sm[i],
                sm[imax] - sm[i],
                r.time_s[i],
                r.time_s[i] - onset,
                del[i] - del[imax],
                last_onset.map(|t| onset - t)
            );
            last_onset = Some(onset);
            imax = i;
        }
        i += 1;
    }
    if std::env::var("QUIET").is_ok() {
        return;
    }
    let every = (r.len() / 150).max(1);
    for i in (0..r.len()).step_by(every) {
        println!(
            "{:8.5} tau {:9.1} sig {:9.1} delta {:10.3e} slip {:3} lift {:3}",
            r.time_s[i], tau[i], sig[i], del[i], slip[i], lift[i]
        );
    }
    if let Some(res) = r.get(Channel::EnergyResidual) {
        let ext = r.get(Channel::ExternalWork).unwrap();
        println!(
            "energy residual {:e} of external {:e}",
            res.last().unwrap(),
            ext.last().unwrap()
        );
    }
}
