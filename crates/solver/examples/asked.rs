//! What recording costs: the paper pipeline's scene run with everything it records, then with
//! one thing less at a time (best of `REPEATS` wall times each, one seed, one thread).
//!
//! `cargo run --release -p stickslip-solver --example asked [-- PIPELINE_SCENE_TOML]`
//! (default `pipelines/paper.toml`; the pipeline-only sections are ignored).

use std::ops::ControlFlow;
use std::time::Instant;

use stickslip_solver::scene::{InterfaceQuantity, SettleMethod};
use stickslip_solver::{Model, RunOptions, Scene, SceneFile, run_seed};

const REPEATS: usize = 7;

fn best(file: &SceneFile) -> (f64, u64) {
    let model = Model::new(Scene::try_from(file.clone()).expect("valid variant"));
    let mut best = f64::INFINITY;
    let mut steps = 0;
    for _ in 0..REPEATS {
        let start = Instant::now();
        let out = run_seed(&model, 123, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
        best = best.min(start.elapsed().as_secs_f64());
        steps = out.steps();
    }
    (best, steps)
}

fn main() {
    let path = std::env::args().nth(1).unwrap_or_else(|| "pipelines/paper.toml".into());
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    // Keep the scene sections of the pipeline file.
    let mut doc: toml::Table = toml::from_str(&text).unwrap();
    for key in ["version", "name", "description", "seeds", "events", "similarity", "spectra", "report"] {
        doc.remove(key);
    }
    let full: SceneFile = toml::from_str(&toml::to_string(&doc).unwrap()).unwrap();
    let mut variants: Vec<(&str, SceneFile)> = vec![("as in the pipeline", full.clone())];
    let mut f = full.clone();
    f.record.energy = false;
    variants.push(("without energy terms", f.clone()));
    f.record.control.clear();
    variants.push(("… and without control nodes", f.clone()));
    f.record.slip_onsets = false;
    variants.push(("… and without slip onsets", f.clone()));
    f.record.interface = vec![InterfaceQuantity::ShearStress];
    variants.push(("… recording τ only", f.clone()));
    let mut f = full.clone();
    f.self_weight.method = SettleMethod::Static;
    variants.push(("as in the pipeline, static self-weight", f));
    let mut f = full.clone();
    f.material.young_cv = 0.0;
    variants.push(("as in the pipeline, CV = 0 (no draws)", f));
    let results: Vec<(f64, u64)> = variants.iter().map(|(_, f)| best(f)).collect();
    let base = results[0].0;
    println!("{:<44} {:>10} {:>10} {:>10}", "variant", "steps", "wall (ms)", "speed-up");
    for ((name, _), (wall, steps)) in variants.iter().zip(&results) {
        println!("{name:<44} {steps:>10} {:>10.1} {:>9.2}×", wall * 1e3, base / wall);
    }
}
