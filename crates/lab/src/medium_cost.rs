//! What the medium costs a step (docs/model.md §18): a pipeline's scene at a given size stepped
//! with its medium elastic, with a constant Q (four memory variables per bar), and with Q and
//! Kelvin–Voigt dashpots, the variants taken in turn and the whole sequence repeated (best time of
//! each), with the bytes per bar each variant's state adds.

use std::time::Instant;

use stickslip_solver::medium::{Attenuation, Medium, QRule};
use stickslip_solver::statics::critical_step_on;
use stickslip_solver::step::{Batch, LaneSetup};
use stickslip_solver::{Model, Scene};

use crate::LabError;

/// One variant's best step time.
#[derive(Clone, Debug, PartialEq)]
pub struct MediumTiming {
    /// What the medium is.
    pub name: &'static str,
    /// Bars of the lattice.
    pub bars: usize,
    /// Best wall time of one step of every lane (s).
    pub step_s: f64,
    /// Bytes per bar and lane the medium's state adds to the step's (memory variables, listed
    /// zones).
    pub extra_bytes_per_bar: f64,
}

/// The variants of `scene`: its homogeneous elastic self, Q = 50 over 0.05–5 Hz, and that with
/// β = 1% of the step.
fn variants(scene: &Scene) -> Vec<(&'static str, Scene)> {
    let mut elastic = scene.clone();
    elastic.medium = Medium::default();
    let q = Medium {
        attenuation: Some(Attenuation { band_hz: [0.05, 5.0], reference_hz: 1.0, q: QRule::Constant(50.0) }),
        ..Medium::default()
    };
    let mut with_q = scene.clone();
    with_q.medium = q.clone();
    let mut with_kv = scene.clone();
    with_kv.medium = Medium { kelvin_voigt_s: 1e-6, ..q };
    vec![("elastic", elastic), ("Q (4 memory variables per bar)", with_q), ("Q and Kelvin–Voigt", with_kv)]
}

/// Times `steps` steps of each variant of `scene` with `lanes` seeds side by side (1, 4 or 8, as
/// a pipeline batches them), `rounds` times in turn, on the current rayon pool split over its
/// threads when `parallel`.
pub fn medium_cost(
    scene: &Scene,
    steps: usize,
    rounds: usize,
    parallel: bool,
    lanes: usize,
) -> Result<Vec<MediumTiming>, LabError> {
    match lanes {
        1 => medium_cost_lanes::<1>(scene, steps, rounds, parallel),
        4 => medium_cost_lanes::<4>(scene, steps, rounds, parallel),
        8 => medium_cost_lanes::<8>(scene, steps, rounds, parallel),
        _ => Err(LabError::Setup(format!("lanes = {lanes}: 1, 4 or 8 seeds side by side"))),
    }
}

fn medium_cost_lanes<const L: usize>(
    scene: &Scene,
    steps: usize,
    rounds: usize,
    parallel: bool,
) -> Result<Vec<MediumTiming>, LabError> {
    let variants = variants(scene);
    let mut best = vec![f64::INFINITY; variants.len()];
    let mut extra = vec![0.0; variants.len()];
    let mut bars = 0;
    for _ in 0..rounds.max(1) {
        for (v, (_, s)) in variants.iter().enumerate() {
            let model = Model::new(s.clone());
            bars = model.bar_count();
            let k = model.nominal_lane_stiffness();
            let critical = critical_step_on(&model, &k, parallel).map_err(|e| LabError::Setup(e.to_string()))?;
            let lane = LaneSetup {
                dt_s: 0.5 * critical.dt_s,
                stiffness: k,
                friction: model.friction_factors(1).map_err(|e| LabError::Setup(e.to_string()))?,
                strength: None,
                fault: None,
            };
            let lanes: [LaneSetup; L] = std::array::from_fn(|_| lane.clone());
            let mut b = Batch::<L>::new(&model, &lanes);
            b.stepper.set_parallel(parallel);
            // A small displacement everywhere, so that every bar has work (no branch skips it).
            let lc = s.lc_m;
            for l in 0..L {
                b.initialize(l, |p| {
                    let u = 1e-6 * lc * ((p[0] * 0.37 + p[1] * 0.11 + p[2] * 0.23) / lc + l as f64).sin();
                    ([u, -u, 0.5 * u], [u, -u, 0.5 * u])
                });
            }
            for _ in 0..3 {
                b.step();
            }
            let start = Instant::now();
            for _ in 0..steps {
                b.step();
            }
            best[v] = best[v].min(start.elapsed().as_secs_f64() / steps as f64);
            // The memory variables are per bar and lane, a listed lattice's zones per bar.
            extra[v] =
                b.state.anelastic.bytes() as f64 / (bars * L) as f64 + model.bar_zones().len() as f64 / bars as f64;
        }
    }
    Ok(variants
        .iter()
        .enumerate()
        .map(|(v, (name, _))| MediumTiming { name, bars, step_s: best[v], extra_bytes_per_bar: extra[v] })
        .collect())
}
