//! What recording costs: a pipeline's scene run with everything it records, then with one thing
//! less at a time (best of a few wall times each, one seed, one thread). The fault (every contact
//! node's slip, slip rate and stresses, `record.fault`) is timed against the same run without it
//! whichever way the pipeline has it.

use std::ops::ControlFlow;
use std::time::Instant;

use stickslip_config::PipelineFile;
use stickslip_solver::scene::{InterfaceQuantity, SettleMethod};
use stickslip_solver::{Model, RunOptions, run_seed};

use crate::LabError;

/// One variant of the scene and its best wall time.
#[derive(Clone, Debug, PartialEq)]
pub struct VariantTiming {
    /// What the variant records or does.
    pub name: &'static str,
    /// Steps of its run.
    pub steps: u64,
    /// Best wall time (s).
    pub wall_s: f64,
}

fn best(file: &PipelineFile, repeats: usize) -> Result<(f64, u64), LabError> {
    let model = Model::new(file.scene()?);
    let mut best = f64::INFINITY;
    let mut steps = 0;
    for _ in 0..repeats {
        let start = Instant::now();
        let out = run_seed(&model, 123, RunOptions::default(), &mut |_| ControlFlow::Continue(()))
            .map_err(|e| LabError::Setup(e.to_string()))?;
        best = best.min(start.elapsed().as_secs_f64());
        steps = out.steps();
    }
    Ok((best, steps))
}

/// Runs the variants of `full` (the scene as in a pipeline) `repeats` times each.
pub fn recording_cost(full: &PipelineFile, repeats: usize) -> Result<Vec<VariantTiming>, LabError> {
    let mut variants: Vec<(&'static str, PipelineFile)> = vec![("as in the pipeline", full.clone())];
    let mut f = full.clone();
    let records_fault = full.record.fault || !full.record.fault_stations_m.is_empty();
    if records_fault {
        f.record.fault = false;
        f.record.fault_stations_m.clear();
        f.record.fault_interval_s = None;
        variants.push(("without the fault (per-node slip, rate, stress)", f.clone()));
    } else {
        let mut with = full.clone();
        with.record.fault = true;
        variants.push(("with the fault (per-node slip, rate, stress)", with));
    }
    f.record.energy = false;
    let energy = if records_fault { "… and without energy terms" } else { "without energy terms" };
    variants.push((energy, f.clone()));
    f.record.control.clear();
    variants.push(("… and without control nodes", f.clone()));
    f.record.slip_onsets = false;
    variants.push(("… and without slip onsets", f.clone()));
    f.record.interface = vec![InterfaceQuantity::ShearStress.name().to_string()];
    variants.push(("… recording τ only", f.clone()));
    let mut f = full.clone();
    f.self_weight.method = SettleMethod::Static.name().into();
    variants.push(("as in the pipeline, static self-weight", f));
    let mut f = full.clone();
    f.material.young_cv = 0.0;
    variants.push(("as in the pipeline, CV = 0 (no draws)", f));
    variants
        .into_iter()
        .map(|(name, f)| best(&f, repeats).map(|(wall_s, steps)| VariantTiming { name, steps, wall_s }))
        .collect()
}
