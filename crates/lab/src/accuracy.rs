//! Run time against error: one scene over time-step fractions and lattice refinements of the
//! same block, each measured against the finest run.
//!
//! A refinement `r` has `r·nx × r·ny × r·nz` modules of side `Lc/r` (the same block). The
//! modulus field is made homogeneous (CV = 0) so that refinements differ by discretisation only,
//! not by a different random draw. Every run records every step (Δt is not fitted to a record
//! interval) and the comparison interpolates onto the reference's instants.
//!
//! Errors, each against the finest run (finest lattice, smallest Δt):
//! - `linear_tau_error`: normalised L2 error of τ(t) while the reference is linear, until its
//!   first base node slides, lifts or lands (`linear_until_s`): the integrator's own accuracy;
//! - `loading_tau_error`: normalised L2 error of τ(t) over the smooth loading before the first
//!   event (up to 90% of the reference's first event onset);
//! - `s1_tau_error`, `s1_slip_error`: normalised L2 errors of τ(t) and of the mean contact
//!   displacement δ(t) over a window around the reference's first main shock S1 (from 10 ms
//!   before its start to 10 ms after its end); normalised = `‖y − y_ref‖₂ / ‖y_ref − ȳ_ref‖₂`;
//! - `e1_onset_error`: onset of the first event, over the reference's S1 recurrence scale
//!   (its onset time);
//! - `s1_drop_error`, `s1_duration_error` (relative), `s1_onset_error` (over the reference's S1
//!   onset time).

use std::ops::ControlFlow;
use std::path::Path;
use std::time::Instant;

use polars::prelude::DataFrame;
use stickslip_analysis::events::catalogue;
use stickslip_config::PipelineFile;
use stickslip_report::charts::{Line, Panel, Sheet, draw};
use stickslip_seismo::events::{Catalogue, EventParams};
use stickslip_solver::scene::{InterfaceQuantity, SettleMethod};
use stickslip_solver::{Channel, Model, RunOptions, RunOutput, run_seed};
use stickslip_store::frame::Frame;

use crate::LabError;

/// What to sweep.
#[derive(Clone, Debug)]
pub struct AccuracyPlan {
    /// Δt as fractions of each lattice's critical step.
    pub fractions: Vec<f64>,
    /// Refinement factors of the lattice.
    pub refinements: Vec<u32>,
    /// Shear duration (s) [default: the scene's].
    pub duration_s: Option<f64>,
    /// Seed (the modulus field is homogeneous; the seed only matters with a friction field).
    pub seed: u64,
}

impl Default for AccuracyPlan {
    fn default() -> Self {
        AccuracyPlan { fractions: vec![0.9, 0.5, 0.25, 0.1], refinements: vec![1, 2, 4], duration_s: None, seed: 123 }
    }
}

/// One run of the sweep and its errors against the reference.
#[derive(Clone, Debug, PartialEq)]
pub struct AccuracyRow {
    /// Refinement factor.
    pub refinement: u32,
    /// Modules.
    pub dims: [usize; 3],
    /// Module side (m).
    pub lc_m: f64,
    /// Bars.
    pub bars: usize,
    /// Δt over the critical step.
    pub dt_fraction: f64,
    /// Δt (s).
    pub dt_s: f64,
    /// Steps.
    pub steps: u64,
    /// Wall time (s).
    pub wall_s: f64,
    /// First event: onset (s) and stress drop (Pa).
    pub first_event: Option<(f64, f64)>,
    /// First main shock: onset (s), stress drop (Pa), duration (s).
    pub s1: Option<(f64, f64, f64)>,
    /// Errors against the reference (see the module doc).
    pub errors: Errors,
    /// End of the linear phase of the reference run (s): the first base node slides, lifts or
    /// lands.
    pub linear_until_s: f64,
    /// The linear-phase τ error against the smallest Δt of the same lattice (Δt convergence
    /// alone, without the lattice's own discretisation error).
    pub linear_tau_error_dt: f64,
}

/// The errors of one run against the reference (NaN where undefined; zeros for the reference).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Errors {
    /// Normalised L2 error of τ(t) while the reference is linear.
    pub linear_tau: f64,
    /// … over the loading before the first event.
    pub loading_tau: f64,
    /// … around the reference's S1.
    pub s1_tau: f64,
    /// Normalised L2 error of δ(t) around S1.
    pub s1_slip: f64,
    /// Onset of the first event, over the reference's S1 onset time.
    pub e1_onset: f64,
    /// S1 stress drop, relative.
    pub s1_drop: f64,
    /// S1 duration, relative.
    pub s1_duration: f64,
    /// S1 onset, over the reference's S1 onset time.
    pub s1_onset: f64,
}

impl Errors {
    /// All undefined.
    pub const UNDEFINED: Errors = Errors {
        linear_tau: f64::NAN,
        loading_tau: f64::NAN,
        s1_tau: f64::NAN,
        s1_slip: f64::NAN,
        e1_onset: f64::NAN,
        s1_drop: f64::NAN,
        s1_duration: f64::NAN,
        s1_onset: f64::NAN,
    };

    /// Every error with its table column name.
    pub fn named(&self) -> [(&'static str, f64); 8] {
        [
            ("linear_tau_error", self.linear_tau),
            ("loading_tau_error", self.loading_tau),
            ("s1_tau_error", self.s1_tau),
            ("s1_slip_error", self.s1_slip),
            ("e1_onset_error", self.e1_onset),
            ("s1_drop_error", self.s1_drop),
            ("s1_duration_error", self.s1_duration),
            ("s1_onset_error", self.s1_onset),
        ]
    }
}

struct Run {
    row: AccuracyRow,
    out: RunOutput,
    cat: Catalogue,
}

/// `file` as the same block in `r`× finer modules (`r·nx × r·ny × r·nz` of side `Lc/r`), at Δt
/// fraction `f`, for `duration` if given, settled statically (the exact equilibrium: damped
/// settling stops at a tolerance that does not shrink with Δt). Drivers, rollers and control
/// points by position carry over; node numbers do not, so `bench` (the benchmark's name) refuses
/// a driver given by number.
pub(crate) fn refined(
    file: &PipelineFile,
    r: u32,
    f: f64,
    duration: Option<f64>,
    bench: &str,
) -> Result<PipelineFile, LabError> {
    let mut file = file.clone();
    let r64 = i64::from(r);
    file.block.nx *= r64;
    file.block.ny *= r64;
    file.block.nz *= r64;
    file.block.lc_m /= f64::from(r);
    file.time.dt_fraction = Some(f);
    file.time.dt_s = None;
    if let Some(d) = duration {
        file.shear.duration_s = d;
    }
    if !file.shear.driver_nodes.is_empty() {
        return Err(LabError::Setup(format!(
            "bench {bench} needs the driver given by position (shear.driver_at_m), not by node number"
        )));
    }
    file.self_weight.method = SettleMethod::Static.name().into();
    Ok(file)
}

/// The scene of refinement `r` and fraction `f`.
fn variant(file: &PipelineFile, r: u32, f: f64, duration: Option<f64>) -> Result<Model, LabError> {
    let mut file = refined(file, r, f, duration, "accuracy")?;
    file.material.young_cv = 0.0;
    file.record.interval_s = None;
    file.record.interface = [
        InterfaceQuantity::ShearStress,
        InterfaceQuantity::MeanSlip,
        InterfaceQuantity::SlipRate,
        InterfaceQuantity::SlippingNodes,
        InterfaceQuantity::LiftedNodes,
    ]
    .map(|q| q.name().to_string())
    .to_vec();
    file.record.energy = false;
    file.record.settling = false;
    file.record.slip_onsets = false;
    file.record.control.clear();
    file.skip_ahead.enabled = false;
    let scene = file.scene().map_err(|e| LabError::Setup(format!("refinement {r}, Δt fraction {f}: {e}")))?;
    Ok(Model::new(scene))
}

/// Linear interpolation of `(t, y)` at `tq` (clamped at the ends).
fn interpolate(t: &[f64], y: &[f64], tq: f64) -> f64 {
    match t.partition_point(|&x| x < tq) {
        0 => y[0],
        i if i >= t.len() => y[t.len() - 1],
        i => {
            let w = (tq - t[i - 1]) / (t[i] - t[i - 1]);
            y[i - 1] + w * (y[i] - y[i - 1])
        }
    }
}

/// `‖y − y_ref‖₂ / ‖y_ref − ȳ_ref‖₂` over the reference instants in `[a, b]`.
fn normalised_l2(reference: &RunOutput, run: &RunOutput, ch: Channel, (a, b): (f64, f64)) -> f64 {
    let (tr, yr) = (&reference.recording.time_s, reference.recording.get(ch).expect("recorded"));
    let (t, y) = (&run.recording.time_s, run.recording.get(ch).expect("recorded"));
    let idx: Vec<usize> = (0..tr.len()).filter(|&i| tr[i] >= a && tr[i] <= b).collect();
    if idx.len() < 2 {
        return f64::NAN;
    }
    let mean = idx.iter().map(|&i| yr[i]).sum::<f64>() / idx.len() as f64;
    let (mut num, mut den) = (0.0, 0.0);
    for &i in &idx {
        let d = interpolate(t, y, tr[i]) - yr[i];
        num += d * d;
        den += (yr[i] - mean) * (yr[i] - mean);
    }
    (num / den).sqrt()
}

/// Runs the sweep (one run at a time, so wall times are not disturbed); `progress` is told
/// what runs.
pub fn run_accuracy(
    file: &PipelineFile,
    events: &EventParams,
    plan: &AccuracyPlan,
    progress: &mut dyn FnMut(&str),
) -> Result<Vec<AccuracyRow>, LabError> {
    let mut runs: Vec<Run> = Vec::new();
    for &r in &plan.refinements {
        for &f in &plan.fractions {
            let model = variant(file, r, f, plan.duration_s)?;
            let d = model.scene().dims;
            progress(&format!(
                "refinement {r} ({}×{}×{}, {} bars), Δt = {f} of critical",
                d.nx,
                d.ny,
                d.nz,
                model.bar_count()
            ));
            let start = Instant::now();
            let out = run_seed(&model, plan.seed, RunOptions::default(), &mut |_| ControlFlow::Continue(()))
                .map_err(|e| LabError::Setup(format!("refinement {r}, Δt fraction {f}: {e}")))?;
            let wall_s = start.elapsed().as_secs_f64();
            let cat = catalogue(&out.recording, &model, events);
            let first_event = cat.events.first().map(|e| (e.burst.start_s, e.burst.stress_drop_pa));
            let s1 = cat.main_shocks().next().map(|e| (e.burst.start_s, e.burst.stress_drop_pa, e.burst.duration_s()));
            let row = AccuracyRow {
                refinement: r,
                dims: [d.nx, d.ny, d.nz],
                lc_m: model.scene().lc_m,
                bars: model.bar_count(),
                dt_fraction: f,
                dt_s: out.dt_s,
                steps: out.steps(),
                wall_s,
                first_event,
                s1,
                errors: Errors::UNDEFINED,
                linear_until_s: f64::NAN,
                linear_tau_error_dt: f64::NAN,
            };
            runs.push(Run { row, out, cat });
        }
    }
    // The reference: the finest lattice at the smallest Δt.
    let reference = runs
        .iter()
        .enumerate()
        .max_by(|(_, a), (_, b)| a.row.refinement.cmp(&b.row.refinement).then(b.row.dt_s.total_cmp(&a.row.dt_s)))
        .map(|(i, _)| i)
        .ok_or_else(|| LabError::Setup("bench accuracy: nothing to run".into()))?;
    let rf = &runs[reference];
    let (e1_ref, s1_ref) = (rf.row.first_event, rf.row.s1);
    let s1_window = rf.cat.main_shocks().next().map(|e| (e.burst.start_s - 0.01, e.burst.end_s + 0.01));
    let loading = e1_ref.map_or((0.0, rf.out.recording.time_s.last().copied().unwrap_or(0.0)), |(t, _)| (0.0, 0.9 * t));
    // Until the first base node slides, lifts or lands the system is linear and smooth.
    let linear_phase = |out: &RunOutput| {
        let r = &out.recording;
        let (slipping, lifted) =
            (r.get(Channel::SlippingNodes).expect("recorded"), r.get(Channel::LiftedNodes).expect("recorded"));
        let end = (1..r.len()).find(|&i| slipping[i] > 0.0 || lifted[i] != lifted[0]).unwrap_or(r.len() - 1);
        (0.0, r.time_s[end.saturating_sub(1)])
    };
    let linear = linear_phase(&rf.out);
    let mut rows = Vec::with_capacity(runs.len());
    for run in &runs {
        let mut row = run.row.clone();
        row.linear_until_s = linear.1;
        // Against the smallest Δt of the same lattice.
        let own = runs
            .iter()
            .filter(|x| x.row.refinement == run.row.refinement)
            .min_by(|a, b| a.row.dt_s.total_cmp(&b.row.dt_s))
            .expect("the run itself");
        row.linear_tau_error_dt = normalised_l2(&own.out, &run.out, Channel::ShearStress, linear_phase(&own.out));
        let l2 = |ch, w: Option<(f64, f64)>| w.map_or(f64::NAN, |w| normalised_l2(&rf.out, &run.out, ch, w));
        let rel = |a: f64, b: f64| (a / b - 1.0).abs();
        row.errors = Errors {
            linear_tau: l2(Channel::ShearStress, Some(linear)),
            loading_tau: l2(Channel::ShearStress, Some(loading)),
            s1_tau: l2(Channel::ShearStress, s1_window),
            s1_slip: l2(Channel::MeanSlip, s1_window),
            e1_onset: match (row.first_event, e1_ref, s1_ref) {
                (Some(a), Some(b), Some(s)) => (a.0 - b.0).abs() / s.0,
                _ => f64::NAN,
            },
            s1_drop: match (row.s1, s1_ref) {
                (Some(a), Some(b)) => rel(a.1, b.1),
                _ => f64::NAN,
            },
            s1_duration: match (row.s1, s1_ref) {
                (Some(a), Some(b)) => rel(a.2, b.2),
                _ => f64::NAN,
            },
            s1_onset: match (row.s1, s1_ref) {
                (Some(a), Some(b)) => (a.0 - b.0).abs() / b.0,
                _ => f64::NAN,
            },
        };
        rows.push(row);
    }
    Ok(rows)
}

/// Observed order of convergence in Δt for refinement `r`: the slope of `log(error)` against
/// `log(Δt)` (least squares over the runs with a finite positive error) of `error(row)`.
pub fn observed_order(rows: &[AccuracyRow], r: u32, error: impl Fn(&AccuracyRow) -> f64) -> Option<f64> {
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|x| x.refinement == r && error(x).is_finite() && error(x) > 0.0)
        .map(|x| (x.dt_s.ln(), error(x).ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The sweep as a table: `refinement` u32, `nx`, `ny`, `nz` u32, `lc_m` f64, `bars` u64,
/// `dt_fraction`, `dt_s` f64, `steps` u64, `wall_s` f64, `e1_onset_s`, `e1_drop_pa`,
/// `s1_onset_s`, `s1_drop_pa`, `s1_duration_s` f64 (null: no such event), `linear_until_s`,
/// `linear_tau_error_dt` f64, then the errors
/// ([`Errors::named`], f64, NaN where undefined; the reference row has zeros).
pub fn accuracy_frame(rows: &[AccuracyRow]) -> Result<DataFrame, LabError> {
    let u32s = |f: &dyn Fn(&AccuracyRow) -> u32| rows.iter().map(f).collect::<Vec<u32>>();
    let f64s = |f: &dyn Fn(&AccuracyRow) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    let opt = |f: &dyn Fn(&AccuracyRow) -> Option<f64>| rows.iter().map(f).collect::<Vec<Option<f64>>>();
    let mut frame = Frame::new(rows.len())
        .u32("refinement", u32s(&|r| r.refinement))
        .u32("nx", u32s(&|r| r.dims[0] as u32))
        .u32("ny", u32s(&|r| r.dims[1] as u32))
        .u32("nz", u32s(&|r| r.dims[2] as u32))
        .f64("lc_m", f64s(&|r| r.lc_m))
        .u64("bars", rows.iter().map(|r| r.bars as u64).collect())
        .f64("dt_fraction", f64s(&|r| r.dt_fraction))
        .f64("dt_s", f64s(&|r| r.dt_s))
        .u64("steps", rows.iter().map(|r| r.steps).collect())
        .f64("wall_s", f64s(&|r| r.wall_s))
        .opt_f64("e1_onset_s", opt(&|r| r.first_event.map(|e| e.0)))
        .opt_f64("e1_drop_pa", opt(&|r| r.first_event.map(|e| e.1)))
        .opt_f64("s1_onset_s", opt(&|r| r.s1.map(|e| e.0)))
        .opt_f64("s1_drop_pa", opt(&|r| r.s1.map(|e| e.1)))
        .opt_f64("s1_duration_s", opt(&|r| r.s1.map(|e| e.2)))
        .f64("linear_until_s", f64s(&|r| r.linear_until_s))
        .f64("linear_tau_error_dt", f64s(&|r| r.linear_tau_error_dt));
    for (k, (name, _)) in Errors::UNDEFINED.named().iter().enumerate() {
        frame = frame.f64(name, f64s(&|r| r.errors.named()[k].1));
    }
    Ok(frame.finish("accuracy")?)
}

/// Error against wall time, log-log: one line per refinement through its Δt fractions, and the
/// Pareto front (no other run is both faster and more accurate) in black; panels: τ while the
/// reference is linear, τ before the first event, τ around S1.
pub fn accuracy_figure(rows: &[AccuracyRow], path: &Path) -> Result<(), LabError> {
    stickslip_report::plot::register_fonts();
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| LabError::Setup(format!("{}: {e}", dir.display())))?;
    }
    let mut refinements: Vec<u32> = rows.iter().map(|r| r.refinement).collect();
    refinements.sort_unstable();
    refinements.dedup();
    let panel = |error: fn(&Errors) -> f64, title: &str| {
        let mut lines: Vec<Line> = refinements
            .iter()
            .enumerate()
            .map(|(i, &r)| {
                let mut pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|x| x.refinement == r && error(&x.errors).is_finite() && error(&x.errors) > 0.0)
                    .map(|x| (x.wall_s, error(&x.errors)))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                let d = rows.iter().find(|x| x.refinement == r).map_or([0; 3], |x| x.dims);
                Line::new(format!("{}×{}×{} (Δt 0.9 → 0.1)", d[0], d[1], d[2]), pts, i)
            })
            .collect();
        let mut all: Vec<(f64, f64)> = rows
            .iter()
            .filter(|x| error(&x.errors).is_finite() && error(&x.errors) > 0.0)
            .map(|x| (x.wall_s, error(&x.errors)))
            .collect();
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut front: Vec<(f64, f64)> = Vec::new();
        for p in all {
            if front.last().is_none_or(|q| p.1 < q.1) {
                front.push(p);
            }
        }
        let mut pareto = Line::new("Pareto front", front, 0);
        pareto.colour = stickslip_report::plot::BLACK;
        pareto.width = 1;
        lines.push(pareto);
        Panel { title: title.to_string(), lines, dots: true, ..Panel::loglog("wall time (s)", "normalised L2 error") }
    };
    draw(
        path,
        &Sheet::new(
            "",
            3,
            vec![
                panel(|e| e.linear_tau, "τ(t) while linear"),
                panel(|e| e.loading_tau, "τ(t) before the first event"),
                panel(|e| e.s1_tau, "τ(t) around S1"),
            ],
        ),
    )?;
    Ok(())
}
