//! The spectra analysis of one seed: for every control channel it asks for, the artificial
//! accelerogram, its response spectra, Fourier spectrum and intensity measures, and the
//! attenuation of peak motions with distance from each main shock's hypocentre.
//!
//! Everything is computed at model scale; the tables rescale to the prototype (docs/model.md §9:
//! `T_p = λ·T`, `SD_p = λ·SD`, `PSV_p = PSV`, `PSA_p = PSA/λ`; Fourier amplitude unchanged at
//! `f_p = f/λ`; Arias ÷λ; durations ×λ).

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use rustfft::FftPlanner;
use stickslip_config::SpectraSettings;
use stickslip_seismo::events::Catalogue;
use stickslip_seismo::spectra::fourier::fourier_amplitude;
use stickslip_seismo::spectra::intensity::intensity;
use stickslip_seismo::spectra::response::{SpectrumError, SpectrumPlan, SpectrumScratch};
use stickslip_solver::geometry::NodeId;
use stickslip_solver::scene::{Component, Kinematic};
use stickslip_solver::{Model, Recording};
use stickslip_store::tables::spectra::{AttenuationRow, ChannelSpectra};

/// What the analysis produced for one seed.
#[derive(Clone, Debug, Default)]
pub struct SeedSpectra {
    /// One entry per control acceleration channel asked for.
    pub channels: Vec<ChannelSpectra>,
    /// Attenuation rows (if asked).
    pub attenuation: Vec<AttenuationRow>,
}

/// Plans shared by the workers, one per sampling interval.
#[derive(Default)]
pub struct PlanCache {
    plans: Mutex<HashMap<u64, Arc<SpectrumPlan>>>,
}

impl PlanCache {
    fn get(&self, dt: f64, s: &SpectraSettings) -> Result<Arc<SpectrumPlan>, SpectrumError> {
        let mut plans = self.plans.lock().expect("plan cache lock");
        if let Some(p) = plans.get(&dt.to_bits()) {
            return Ok(p.clone());
        }
        let plan = Arc::new(SpectrumPlan::new(dt, &s.periods, &s.dampings, s.reading, s.oversampling)?);
        plans.insert(dt.to_bits(), plan.clone());
        Ok(plan)
    }
}

thread_local! {
    static SCRATCH: std::cell::RefCell<(SpectrumScratch, FftPlanner<f64>)> =
        std::cell::RefCell::new((SpectrumScratch::default(), FftPlanner::new()));
}

/// Why a seed's spectra could not be computed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SpectraFailure {
    /// The shear stage was not sampled uniformly.
    #[error("spectra need a uniformly sampled record: {0}")]
    NotUniform(String),
    /// The spectra refused the record (e.g. a non-finite sample).
    #[error(transparent)]
    Spectrum(#[from] SpectrumError),
}

/// Runs the analysis for one seed's recording; the shear-stage samples must be uniformly spaced.
pub fn compute(
    rec: &Recording,
    catalogue: &Catalogue,
    model: &Model,
    settings: &SpectraSettings,
    smoothing_s: f64,
    plans: &PlanCache,
) -> Result<SeedSpectra, SpectraFailure> {
    let Some(span) = rec.uniform_shear() else {
        return Err(SpectraFailure::NotUniform(format!(
            "the shear stage was sampled every {} steps except where the skip-ahead sampled quiet phases more sparsely \
             or the stage's last step fell off the grid",
            rec.sampling.stride
        )));
    };
    let t = &rec.time_s[span.clone()];
    if t.len() < 2 {
        return Ok(SeedSpectra::default());
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    let plan = plans.get(dt, settings)?;
    let lattice = model.lattice();
    let mut channels = Vec::new();
    for (ch, accel) in rec.control.iter().filter(|(c, _)| settings.wants(c)) {
        let accel = &accel[span.clone()];
        let mut sd = vec![0.0; plan.len()];
        let fourier = SCRATCH.with(|s| -> Result<_, SpectrumError> {
            let (scratch, planner) = &mut *s.borrow_mut();
            plan.compute(accel, scratch, &mut sd)?;
            Ok(fourier_amplitude(accel, dt, settings.window, planner))
        })?;
        channels.push(ChannelSpectra {
            channel: *ch,
            position: lattice.position(ch.node),
            dt,
            t0: t[0],
            accel: accel.to_vec(),
            sd,
            intensity: intensity(accel, dt, settings.baseline),
            fourier,
        });
    }
    let attenuation = if settings.attenuation { attenuation(rec, catalogue, model, smoothing_s) } else { vec![] };
    Ok(SeedSpectra { channels, attenuation })
}

/// Peak motions of every control node in every main shock, with the distance from the shock's
/// hypocentre (its first sustained slip onset in `[start − smoothing, end]`).
fn attenuation(rec: &Recording, catalogue: &Catalogue, model: &Model, smoothing_s: f64) -> Vec<AttenuationRow> {
    let lattice = model.lattice();
    let t = &rec.time_s;
    let mut nodes: Vec<NodeId> = rec.control.iter().map(|(c, _)| c.node).collect();
    nodes.sort();
    nodes.dedup();
    let series = |node: NodeId, q: Kinematic| -> Vec<&[f64]> {
        rec.control.iter().filter(|(c, _)| c.node == node && c.quantity == q).map(|(_, v)| v.as_slice()).collect()
    };
    let mut rows = Vec::new();
    for (k, e) in catalogue.events.iter().enumerate() {
        let Some(rank) = e.kind.rank().filter(|_| e.kind.is_main()) else { continue };
        let from = e.burst.start_s - smoothing_s;
        let Some(&(_, hypo)) = rec.onsets.iter().find(|(time, _)| *time >= from && *time <= e.burst.end_s) else {
            continue;
        };
        let h = lattice.position(hypo);
        let (a, b) = (t.partition_point(|&x| x < e.burst.start_s), t.partition_point(|&x| x <= e.burst.end_s));
        for &node in &nodes {
            let p = lattice.position(node);
            let distance = ((p[0] - h[0]).powi(2) + (p[1] - h[1]).powi(2) + (p[2] - h[2]).powi(2)).sqrt();
            let peak = |comps: &[&[f64]]| -> f64 {
                if comps.is_empty() {
                    return f64::NAN;
                }
                (a..b).map(|i| comps.iter().map(|c| c[i] * c[i]).sum::<f64>().sqrt()).fold(0.0, f64::max)
            };
            rows.push(AttenuationRow {
                event: k as u32,
                rank,
                hypocentre: hypo,
                node,
                distance_m: distance,
                pga_m_s2: peak(&series(node, Kinematic::Acceleration)),
                pgv_m_s: peak(&series(node, Kinematic::Velocity)),
            });
        }
    }
    rows
}

/// File name of an accelerogram file: pipeline, seed, node, component and scale.
pub fn at2_name(pipeline: &str, seed: u64, node: NodeId, component: Component, scale: &str) -> String {
    format!("{pipeline}_seed{seed}_n{}_{}_{scale}.AT2", node.ldem(), component.name())
}
