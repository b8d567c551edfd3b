//! Diagnostic: runs a scene for one seed and plots τ, σ, δ, V and node counts (calibration aid).
use std::ops::ControlFlow;

use plotters::prelude::*;
use stickslip_analysis::Pipeline;
use stickslip_solver::{Channel, Model, RunOptions, run_seed};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let pipeline = Pipeline::load(std::path::Path::new(&args[1])).unwrap();
    let seed: u64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(123);
    let out = args.get(3).cloned().unwrap_or("/tmp/diag.png".into());
    let (t0, t1): (f64, f64) = match (args.get(4), args.get(5)) {
        (Some(a), Some(b)) => (a.parse().unwrap(), b.parse().unwrap()),
        _ => (f64::NEG_INFINITY, f64::INFINITY),
    };
    plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular()).map_err(|_| ()).unwrap();
    let model = Model::new(pipeline.scene.clone());
    let run = run_seed(&model, seed, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    let r = &run.records;
    let idx: Vec<usize> = (0..r.len()).filter(|&i| r.time_s[i] >= t0 && r.time_s[i] <= t1).collect();
    let t: Vec<f64> = idx.iter().map(|&i| r.time_s[i]).collect();
    let panels = [
        (Channel::ShearStress, "tau (Pa)"),
        (Channel::NormalStress, "sigma (Pa)"),
        (Channel::MeanSlip, "delta (m)"),
        (Channel::MeanSlipRate, "V mean (m/s)"),
        (Channel::MaxSlipRate, "V max (m/s)"),
        (Channel::LiftedNodes, "lifted"),
        (Channel::SlippingNodes, "slipping"),
    ];
    let root = BitMapBackend::new(&out, (1400, 1600)).into_drawing_area();
    root.fill(&WHITE).unwrap();
    let areas = root.split_evenly((panels.len(), 1));
    for ((ch, label), area) in panels.iter().zip(areas.iter()) {
        let v: Vec<f64> = idx.iter().map(|&i| r.get(*ch).unwrap()[i]).collect();
        let (lo, hi) = v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
        let pad = (hi - lo).max(1e-30) * 0.05;
        let mut chart = ChartBuilder::on(area)
            .margin(5)
            .x_label_area_size(25)
            .y_label_area_size(90)
            .build_cartesian_2d(t[0]..*t.last().unwrap(), (lo - pad)..(hi + pad))
            .unwrap();
        chart.configure_mesh().y_desc(*label).y_label_formatter(&|y| format!("{y:.3e}")).draw().unwrap();
        chart.draw_series(LineSeries::new(t.iter().copied().zip(v.iter().copied()), &BLUE)).unwrap();
    }
    root.present().unwrap();
    println!("wrote {out}");
}
