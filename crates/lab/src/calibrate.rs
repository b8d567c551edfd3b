//! Calibration aid: sweeps assumed scene values over seeds and reports the main shocks of each
//! combination (how the paper scene's assumed values were chosen, docs/model.md §6).

use std::ops::ControlFlow;

use rayon::prelude::*;
use stickslip_analysis::events::catalogue;
use stickslip_config::PipelineFile;
use stickslip_seismo::events::{Catalogue, EventParams};
use stickslip_solver::{Model, RunOptions, run_seed};

use crate::LabError;

/// The keys a sweep can vary, and what they set.
pub const KEYS: [(&str, &str); 10] = [
    ("z", "height of the driven node (m)"),
    ("y", "y of the driven node (m)"),
    ("d2", "shear.damping_per_s"),
    ("d1", "self_weight.damping_per_s"),
    ("t0", "shear.rise_time_s"),
    ("frac", "time.dt_fraction"),
    ("dur", "shear.duration_s"),
    ("vel", "shear.velocity_m_s"),
    ("mud", "friction.mu_dynamic"),
    ("dc", "friction.slip_weakening_m"),
];

/// One combination of the sweep and each seed's catalogue.
pub struct Combination {
    /// The values set.
    pub values: Vec<(String, f64)>,
    /// Each seed and its events.
    pub seeds: Vec<(u64, Catalogue)>,
}

/// Every combination of `grid` (`key → values`) applied to `base`, run over `seeds`.
pub fn sweep(base: &PipelineFile, grid: &[(String, Vec<f64>)], seeds: &[u64]) -> Result<Vec<Combination>, LabError> {
    let mut combos: Vec<Vec<(String, f64)>> = vec![vec![]];
    for (k, vals) in grid {
        if !KEYS.iter().any(|(name, _)| name == k) {
            let names: Vec<&str> = KEYS.iter().map(|(n, _)| *n).collect();
            return Err(LabError::Setup(format!("unknown key {k:?}: one of {}", names.join(", "))));
        }
        combos = combos
            .into_iter()
            .flat_map(|g| vals.iter().map(move |&v| [g.clone(), vec![(k.clone(), v)]].concat()))
            .collect();
    }
    let params = EventParams::default();
    let mut out = Vec::new();
    for values in combos {
        let mut file = base.clone();
        for (k, v) in &values {
            let at = file.shear.driver_at_m.first().copied().unwrap_or([0.0, 0.0, 0.2]);
            match k.as_str() {
                "z" => file.shear.driver_at_m = vec![[0.0, at[1], *v]],
                "y" => file.shear.driver_at_m = vec![[0.0, *v, at[2]]],
                "d2" => file.shear.damping_per_s = *v,
                "d1" => file.self_weight.damping_per_s = *v,
                "t0" => file.shear.rise_time_s = *v,
                "frac" => file.time.dt_fraction = Some(*v),
                "dur" => file.shear.duration_s = *v,
                "vel" => file.shear.velocity_m_s = *v,
                "mud" => file.friction.mu_dynamic = Some(*v),
                "dc" => file.friction.slip_weakening_m = *v,
                _ => unreachable!("keys checked above"),
            }
        }
        let model = Model::new(file.scene()?);
        let results: Result<Vec<(u64, Catalogue)>, LabError> = seeds
            .par_iter()
            .map(|&s| {
                let run = run_seed(&model, s, RunOptions::default(), &mut |_| ControlFlow::Continue(()))
                    .map_err(|e| LabError::Setup(format!("seed {s}: {e}")))?;
                Ok((s, catalogue(&run.recording, &model, &params)))
            })
            .collect();
        out.push(Combination { values, seeds: results? });
    }
    Ok(out)
}
