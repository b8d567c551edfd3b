//! The spectra stage of a pipeline: for every seed, control node and component, the artificial
//! accelerogram at model and prototype scale, its response spectra, Fourier spectrum and
//! intensity measures, AT2 files, and the attenuation of peak motions with distance from each
//! main shock's hypocentre.
//!
//! Prototype scale (SPEC §9): times ×λ, accelerations ÷λ, velocities ×1, lengths ×λ. The spectra
//! scale exactly with them — `T_p = λ·T`, `SD_p = λ·SD`, `PSV_p = PSV`, `PSA_p = PSA/λ`; the
//! Fourier amplitude is unchanged at `f_p = f/λ`; Arias intensity ÷λ; durations ×λ — so they are
//! computed once at model scale and rescaled.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use rustfft::FftPlanner;
use serde::{Deserialize, Serialize};
use stickslip_solver::scene::{Component, ControlChannel, Kinematic};
use stickslip_solver::{FieldError, Model, NodeId, Records};

use crate::events::{Catalogue, EventKind};
use crate::spectra::fourier::{FourierSpectrum, Window, fourier_amplitude};
use crate::spectra::intensity::{Baseline, Intensity, intensity};
use crate::spectra::response::{Reading, SpectrumPlan, SpectrumScratch, log_periods};

/// `[spectra]`: the spectra stage (pipeline section; absent = stage skipped).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SpectraParams {
    /// Damping ratios (fractions of critical, 0 ≤ ξ < 1). Default `[0.05]`.
    pub dampings: Vec<f64>,
    /// Control nodes (LDEM numbers) whose accelerations get spectra, intensity measures and
    /// accelerogram files; empty = every control node recording acceleration.
    pub nodes: Vec<i64>,
    /// Explicit model-scale periods in seconds; empty = the log grid below.
    pub periods_s: Vec<f64>,
    /// Shortest period of the log grid (s, model scale). Default 1e-4.
    pub period_min_s: f64,
    /// Longest period of the log grid (s, model scale). Default 0.1.
    pub period_max_s: f64,
    /// Number of periods of the log grid. Default 100.
    pub period_count: i64,
    /// Reading of the samples: `"linear"` (default) or `"band_limited"`.
    pub reading: Reading,
    /// Oversampling of the band-limited reading. Default 16.
    pub oversampling: i64,
    /// Baseline correction for PGV and PGD: `"none"` (default) or `"linear"`.
    pub baseline: Baseline,
    /// Window of the Fourier spectrum: `"rectangular"` (default) or `"hann"`.
    pub fourier_window: Window,
    /// Write PEER `.AT2` files of every accelerogram (model and prototype scale). Default true.
    pub at2: bool,
    /// Attenuation of PGA and PGV with distance from each main shock's hypocentre (needs
    /// `record.slip_onsets = true` and control nodes recording acceleration). Default false.
    pub attenuation: bool,
}

impl Default for SpectraParams {
    fn default() -> Self {
        SpectraParams {
            dampings: vec![0.05],
            nodes: vec![],
            periods_s: vec![],
            period_min_s: 1e-4,
            period_max_s: 0.1,
            period_count: 100,
            reading: Reading::Linear,
            oversampling: 16,
            baseline: Baseline::None,
            fourier_window: Window::Rectangular,
            at2: true,
            attenuation: false,
        }
    }
}

impl SpectraParams {
    /// Whether a control channel gets spectra.
    pub fn wants(&self, c: &ControlChannel) -> bool {
        c.quantity == Kinematic::Acceleration && (self.nodes.is_empty() || self.nodes.contains(&(c.node.ldem() as i64)))
    }

    /// The model-scale period grid.
    pub fn periods(&self) -> Vec<f64> {
        if self.periods_s.is_empty() {
            log_periods(self.period_min_s, self.period_max_s, self.period_count.max(1) as usize)
        } else {
            self.periods_s.clone()
        }
    }

    /// Refused values, with their field names.
    pub fn check(&self, scene: &stickslip_solver::Scene, errors: &mut Vec<FieldError>) {
        let refuse = |errors: &mut Vec<FieldError>, field: &str, value: String, allowed: &str| {
            errors.push(FieldError { field: field.into(), value, allowed: allowed.into() })
        };
        if self.dampings.is_empty() {
            refuse(errors, "spectra.dampings", "[]".into(), "at least one damping ratio");
        }
        for (i, d) in self.dampings.iter().enumerate() {
            if !(0.0..1.0).contains(d) {
                refuse(errors, &format!("spectra.dampings[{i}]"), d.to_string(), "0 ≤ damping < 1");
            }
        }
        for (i, t) in self.periods_s.iter().enumerate() {
            if !(*t > 0.0 && t.is_finite()) {
                refuse(errors, &format!("spectra.periods_s[{i}]"), t.to_string(), "0 < period (finite)");
            }
        }
        if self.periods_s.is_empty() {
            if !(self.period_min_s > 0.0 && self.period_min_s.is_finite()) {
                refuse(errors, "spectra.period_min_s", self.period_min_s.to_string(), "0 < period_min_s (finite)");
            } else if !(self.period_max_s > self.period_min_s && self.period_max_s.is_finite()) {
                refuse(
                    errors,
                    "spectra.period_max_s",
                    self.period_max_s.to_string(),
                    &format!("period_min_s ({}) < period_max_s (finite)", self.period_min_s),
                );
            }
            if !(1..=10_000).contains(&self.period_count) {
                refuse(errors, "spectra.period_count", self.period_count.to_string(), "1 ≤ period_count ≤ 10000");
            }
        }
        if !(1..=64).contains(&self.oversampling) {
            refuse(errors, "spectra.oversampling", self.oversampling.to_string(), "1 ≤ oversampling ≤ 64");
        }
        let accelerations = scene.record.control.iter().filter(|c| self.wants(c)).count();
        for (i, n) in self.nodes.iter().enumerate() {
            if !scene.record.control.iter().any(|c| c.quantity == Kinematic::Acceleration && c.node.ldem() as i64 == *n)
            {
                refuse(
                    errors,
                    &format!("spectra.nodes[{i}]"),
                    n.to_string(),
                    "a control node that records acceleration ([[record.control]])",
                );
            }
        }
        if accelerations == 0 {
            refuse(
                errors,
                "spectra",
                "(present)".into(),
                "control nodes that record acceleration ([[record.control]] quantities = [\"acceleration\"])",
            );
        }
        if self.attenuation && !scene.record.slip_onsets {
            refuse(
                errors,
                "spectra.attenuation",
                "true".into(),
                "record.slip_onsets = true (the hypocentre is the first contact node to slide)",
            );
        }
    }
}

/// Everything the stage computes for one control channel (model scale).
#[derive(Clone, Debug)]
pub struct ChannelSpectra {
    /// The channel.
    pub channel: ControlChannel,
    /// Node position (m).
    pub position: [f64; 3],
    /// Sampling interval (s).
    pub dt: f64,
    /// Time of the first sample (s).
    pub t0: f64,
    /// Accelerations (m/s²).
    pub accel: Vec<f64>,
    /// SD (m), damping-major over the plan's periods.
    pub sd: Vec<f64>,
    /// Intensity measures.
    pub intensity: Intensity,
    /// Fourier amplitude spectrum.
    pub fourier: FourierSpectrum,
}

/// Peak motions of one node during one main shock.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AttenuationRow {
    /// Index of the event in the seed.
    pub event: u32,
    /// Main-shock rank (1 for S1).
    pub rank: u32,
    /// Hypocentre: the first contact node to slide for good in the event.
    pub hypocentre: NodeId,
    /// The control node.
    pub node: NodeId,
    /// Distance from the hypocentre (m).
    pub distance_m: f64,
    /// Peak magnitude of the recorded acceleration components during the event (m/s²).
    pub pga_m_s2: f64,
    /// Peak magnitude of the recorded velocity components (m/s), NaN without velocity.
    pub pgv_m_s: f64,
}

/// What the stage produced for one seed.
#[derive(Clone, Debug, Default)]
pub struct SeedSpectra {
    /// One entry per control acceleration channel.
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
    fn get(&self, dt: f64, params: &SpectraParams) -> Arc<SpectrumPlan> {
        let mut plans = self.plans.lock().expect("plan cache lock");
        plans
            .entry(dt.to_bits())
            .or_insert_with(|| {
                Arc::new(SpectrumPlan::new(
                    dt,
                    &params.periods(),
                    &params.dampings,
                    params.reading,
                    params.oversampling as usize,
                ))
            })
            .clone()
    }
}

thread_local! {
    static SCRATCH: std::cell::RefCell<(SpectrumScratch, FftPlanner<f64>)> =
        std::cell::RefCell::new((SpectrumScratch::default(), FftPlanner::new()));
}

/// Runs the stage for one seed's records.
pub fn compute(
    records: &Records,
    catalogue: &Catalogue,
    model: &Model,
    params: &SpectraParams,
    smoothing_s: f64,
    plans: &PlanCache,
) -> SeedSpectra {
    let t = &records.time_s;
    if t.len() < 2 {
        return SeedSpectra::default();
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    let plan = plans.get(dt, params);
    let lattice = model.lattice();
    let mut channels = Vec::new();
    for (ch, accel) in records.control.iter().filter(|(c, _)| params.wants(c)) {
        let mut sd = vec![0.0; plan.len()];
        let fourier = SCRATCH.with(|s| {
            let (scratch, planner) = &mut *s.borrow_mut();
            plan.compute(accel, scratch, &mut sd);
            fourier_amplitude(accel, dt, params.fourier_window, planner)
        });
        channels.push(ChannelSpectra {
            channel: *ch,
            position: lattice.position(ch.node),
            dt,
            t0: t[0],
            accel: accel.clone(),
            sd,
            intensity: intensity(accel, dt, params.baseline),
            fourier,
        });
    }
    let attenuation = if params.attenuation { attenuation(records, catalogue, model, smoothing_s) } else { vec![] };
    SeedSpectra { channels, attenuation }
}

/// Peak motions of every control node in every main shock, with the distance from the shock's
/// hypocentre (its first sustained slip onset in `[start − smoothing, end]`).
fn attenuation(records: &Records, catalogue: &Catalogue, model: &Model, smoothing_s: f64) -> Vec<AttenuationRow> {
    let lattice = model.lattice();
    let t = &records.time_s;
    let mut nodes: Vec<NodeId> = records.control.iter().map(|(c, _)| c.node).collect();
    nodes.sort();
    nodes.dedup();
    let series = |node: NodeId, q: Kinematic| -> Vec<&[f64]> {
        records.control.iter().filter(|(c, _)| c.node == node && c.quantity == q).map(|(_, v)| v.as_slice()).collect()
    };
    let mut rows = Vec::new();
    for (k, e) in catalogue.events.iter().enumerate() {
        let EventKind::Main(rank) = e.kind else { continue };
        let from = e.burst.start_s - smoothing_s;
        let Some(&(_, hypo)) = records.onsets.iter().find(|(time, _)| *time >= from && *time <= e.burst.end_s) else {
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

/// A least-squares line `log10 y = intercept + slope·log10 R`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LogFit {
    /// Intercept.
    pub intercept: f64,
    /// Slope.
    pub slope: f64,
    /// Coefficient of determination.
    pub r2: f64,
    /// Points used.
    pub points: usize,
}

/// Least-squares fit `log10 y = a + b·log10 R` over the points with R > 0 and y > 0, or `None`
/// with fewer than 3 points.
pub fn log_log_fit(points: impl Iterator<Item = (f64, f64)>) -> Option<LogFit> {
    let pts: Vec<(f64, f64)> =
        points.filter(|(r, y)| *r > 0.0 && *y > 0.0 && y.is_finite()).map(|(r, y)| (r.log10(), y.log10())).collect();
    let n = pts.len();
    if n < 3 {
        return None;
    }
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n as f64, pts.iter().map(|p| p.1).sum::<f64>() / n as f64);
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = pts.iter().map(|p| (p.1 - my).powi(2)).sum();
    if sxx == 0.0 {
        return None;
    }
    let b = sxy / sxx;
    let a = my - b * mx;
    let r2 = if syy > 0.0 { sxy * sxy / (sxx * syy) } else { 1.0 };
    Some(LogFit { intercept: a, slope: b, r2, points: n })
}

/// File name of an AT2 file: pipeline, seed, node, component and scale.
pub fn at2_name(pipeline: &str, seed: u64, node: NodeId, component: Component, scale: &str) -> String {
    format!("{pipeline}_seed{seed}_n{}_{}_{scale}.AT2", node.ldem(), component.name())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_log_fit_recovers_a_power_law() {
        let pts = (1..20).map(|i| {
            let r = i as f64 * 0.1;
            (r, 3.0 * r.powf(-1.5))
        });
        let f = log_log_fit(pts).unwrap();
        assert!((f.intercept - 3f64.log10()).abs() < 1e-12 && (f.slope + 1.5).abs() < 1e-12);
        assert!((f.r2 - 1.0).abs() < 1e-12);
        assert_eq!(f.points, 19);
    }
}
