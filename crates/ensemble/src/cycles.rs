//! A pipeline's `[cycles]` run (docs/model.md §20; the guide's faults chapter, Earthquake
//! cycles): the fault built from the scene, integrated over the years asked, its files written
//! under `<out>/seas/` in the layout of the SCEC SEAS benchmarks and its events in
//! `<out>/tables/cycle_events.parquet`.
//!
//! The layout is BP1's description (Erickson et al., the SEAS BP1/BP2 problem description,
//! sections on output):
//! - `seas/fltst_dpXXX` (XXX the depth in hectometres): one per station, `#` header lines, the
//!   field list `t slip slip_rate shear_stress state` (s, m, log10 m/s, MPa, log10 s), a row every
//!   `sample_s` while the fault is in an event (the largest slip rate above the event threshold)
//!   and every `max_step_years` between events;
//! - `seas/devol.dat`: the field lists `z` and `t max_slip_rate slip`, then a first row
//!   `0 0 z₁ z₂ …` (depths about every 500 m down to the frictional depth) and one row per
//!   profile, `t`, log10 of the largest slip rate and the slip at each depth, every 5 years
//!   between events and every second inside one;
//! - `seas/global.dat` (not a BP1 file; the later benchmarks' global series): `t max_slip_rate
//!   moment_rate` (s, log10 m/s, N·m/s per metre along strike) at the stations' times.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use polars::prelude::*;
use stickslip_config::Pipeline;
use stickslip_solver::cycles::{CycleSpec, CycleState, CycleStats, Flow, FullyDynamicFault, QuasiDynamicFault, YEAR_S};
use stickslip_store::io::{write_parquet_atomic, write_text_atomic};

use crate::error::EnsembleError;

/// One event of a cycle run: from the first step the largest slip rate exceeds the threshold
/// to the first it falls below it again.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleEvent {
    /// Onset (s).
    pub onset_s: f64,
    /// Duration (s).
    pub duration_s: f64,
    /// Depth of the node that first exceeded the threshold (m).
    pub hypocentre_depth_m: f64,
    /// The largest slip rate over the fault and the event (m/s).
    pub peak_slip_rate_m_s: f64,
    /// Slip at the free surface over the event (m).
    pub surface_slip_m: f64,
    /// The largest slip of a node over the event (m).
    pub max_slip_m: f64,
    /// Depth range of the nodes that exceeded the threshold (m).
    pub ruptured_m: [f64; 2],
    /// Moment per metre along strike, `μ·Σ Δδ_j·ℓ_j` (N·m/m).
    pub moment_per_m: f64,
}

impl CycleEvent {
    /// The ruptured length down dip (m): from the shallowest to the deepest node that exceeded
    /// the event threshold, each node standing for the length it carries in the moment (one
    /// module `lc_m`, half of one at the free surface).
    pub fn length_m(&self, lc_m: f64) -> f64 {
        let surface = if self.ruptured_m[0] == 0.0 { 0.5 * lc_m } else { 0.0 };
        self.ruptured_m[1] - self.ruptured_m[0] + lc_m - surface
    }

    /// The seismic moment (N·m) of the event taken as long along strike as it is down dip (the
    /// two-dimensional run's convention, docs/model.md §20.6): `moment_per_m × length`.
    pub fn moment_n_m(&self, lc_m: f64) -> f64 {
        self.moment_per_m * self.length_m(lc_m)
    }

    /// The moment magnitude of [`CycleEvent::moment_n_m`], `(2/3)·(log10 M0 − 9.1)`.
    pub fn magnitude(&self, lc_m: f64) -> f64 {
        stickslip_analysis::source::moment_magnitude(self.moment_n_m(lc_m))
    }
}

/// What a cycle run gave.
#[derive(Clone, Debug)]
pub struct CycleReport {
    /// The events, in order.
    pub events: Vec<CycleEvent>,
    /// The step counts.
    pub stats: CycleStats,
    /// Fault nodes.
    pub nodes: usize,
    /// Their spacing (m).
    pub lc_m: f64,
    /// Seconds spent on the fault's stiffness.
    pub stiffness_s: f64,
    /// Seconds spent integrating.
    pub run_s: f64,
    /// Where the files are.
    pub out: PathBuf,
    /// The time the run was interrupted at (s), its files written up to there; `None`: it ran
    /// to the end.
    pub interrupted_s: Option<f64>,
}

struct Recorder<'a> {
    spec: &'a CycleSpec,
    fault: &'a QuasiDynamicFault,
    mu: f64,
    stations: Vec<(usize, f64, String)>,
    global: String,
    devol: String,
    last_row: f64,
    last_profile: f64,
    profile_nodes: Vec<usize>,
    in_event: Option<(CycleEvent, Vec<f64>)>,
    events: Vec<CycleEvent>,
}

/// `value` of node `j` and `j + 1` weighted for a station at depth `d` between them.
fn at(values: &[f64], j: usize, w: f64) -> f64 {
    if w == 0.0 || j + 1 >= values.len() { values[j] } else { (1.0 - w) * values[j] + w * values[j + 1] }
}

impl Recorder<'_> {
    /// A row of the stations and of `global.dat` at `s`, whose largest slip rate is `vmax`.
    fn row(&mut self, s: &CycleState, vmax: f64) {
        let rate: f64 = (0..s.slip_rate_m_s.len())
            .map(|j| self.mu * s.slip_rate_m_s[j] * self.fault.stiffness.node_length_m(j))
            .sum();
        let _ = writeln!(self.global, "{:.15e} {:.15e} {:.15e}", s.t_s, vmax.log10(), rate);
        for (j, w, text) in &mut self.stations {
            let v = at(&s.slip_rate_m_s, *j, *w).abs();
            let _ = writeln!(
                text,
                "{:.15e} {:.15e} {:.15e} {:.15e} {:.15e}",
                s.t_s,
                at(&s.slip_m, *j, *w),
                v.log10(),
                at(&s.shear_pa, *j, *w) / 1e6,
                at(&s.log_state, *j, *w) / std::f64::consts::LN_10
            );
        }
    }

    fn observe(&mut self, s: &CycleState) {
        let vmax = s.slip_rate_m_s.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let threshold = self.spec.event_slip_rate_m_s;
        let quiet_gap = self.spec.tolerances.max_step_s;
        let seismic = vmax > threshold;
        let gap = if seismic { self.spec.sample_s } else { quiet_gap };
        // The first step of an event is always written, so an onset is never skipped over.
        let onset = seismic && self.in_event.is_none();
        if onset || s.t_s - self.last_row >= gap || s.t_s == 0.0 {
            self.row(s, vmax);
            self.last_row = s.t_s;
        }
        let profile_gap = if seismic { 1.0 } else { 5.0 * YEAR_S };
        if onset || s.t_s == 0.0 || s.t_s - self.last_profile >= profile_gap {
            let _ = write!(self.devol, "{:.15e} {:.15e}", s.t_s, vmax.log10());
            for &j in &self.profile_nodes {
                let _ = write!(self.devol, " {:.15e}", s.slip_m[j]);
            }
            self.devol.push('\n');
            self.last_profile = s.t_s;
        }
        let lc = self.fault.stiffness.lc_m;
        match (&mut self.in_event, seismic) {
            (None, true) => {
                let hypo = (0..s.slip_rate_m_s.len())
                    .max_by(|&a, &b| s.slip_rate_m_s[a].abs().total_cmp(&s.slip_rate_m_s[b].abs()))
                    .unwrap_or(0);
                let event = CycleEvent {
                    onset_s: s.t_s,
                    duration_s: 0.0,
                    hypocentre_depth_m: hypo as f64 * lc,
                    peak_slip_rate_m_s: vmax,
                    surface_slip_m: 0.0,
                    max_slip_m: 0.0,
                    ruptured_m: [hypo as f64 * lc; 2],
                    moment_per_m: 0.0,
                };
                self.in_event = Some((event, s.slip_m.clone()));
            }
            (Some((event, _)), true) => {
                event.peak_slip_rate_m_s = event.peak_slip_rate_m_s.max(vmax);
                for (j, v) in s.slip_rate_m_s.iter().enumerate() {
                    if v.abs() > threshold {
                        let d = j as f64 * lc;
                        event.ruptured_m = [event.ruptured_m[0].min(d), event.ruptured_m[1].max(d)];
                    }
                }
            }
            (Some(_), false) => {
                let (mut event, before) = self.in_event.take().expect("an event");
                event.duration_s = s.t_s - event.onset_s;
                let slip: Vec<f64> = s.slip_m.iter().zip(&before).map(|(a, b)| a - b).collect();
                event.surface_slip_m = slip[0];
                event.max_slip_m = slip.iter().fold(0.0f64, |a, &d| a.max(d));
                event.moment_per_m =
                    (0..slip.len()).map(|j| self.mu * slip[j] * self.fault.stiffness.node_length_m(j)).sum();
                self.events.push(event);
            }
            (None, false) => {}
        }
    }
}

/// The fault nodes of `devol.dat`: about every 500 m from the surface, and the deepest node.
fn profile_nodes(nodes: usize, lc: f64) -> Vec<usize> {
    let every = ((500.0 / lc).round() as usize).max(1);
    let mut js: Vec<usize> = (0..nodes).step_by(every).collect();
    if js.last() != Some(&(nodes - 1)) {
        js.push(nodes - 1);
    }
    js
}

/// The header of a SEAS file.
fn header(
    pipeline: &Pipeline,
    fault: &QuasiDynamicFault,
    stats: &CycleStats,
    location: &str,
    columns: &[&str],
) -> String {
    let mut h = String::new();
    let _ = writeln!(h, "# This is the file header:");
    let _ = writeln!(h, "# problem={}", pipeline.description);
    let _ = writeln!(h, "# pipeline={}", pipeline.name);
    let mode = if stats.dynamic_phases > 0 || pipeline.cycles.as_ref().is_some_and(|c| c.dynamic.is_some()) {
        "fully dynamic: explicit steps inside events, quasi-dynamic between them"
    } else {
        "quasi-dynamic"
    };
    let _ = writeln!(h, "# code=stickslip {} (lattice antiplane mode, {mode})", env!("CARGO_PKG_VERSION"));
    let _ = writeln!(h, "# element_size={} m", fault.stiffness.lc_m);
    let _ = writeln!(h, "# location={location}");
    let _ = writeln!(h, "# minimum_time_step={:e}", stats.min_step_s);
    let _ = writeln!(h, "# maximum_time_step={:e}", stats.max_step_s);
    let _ = writeln!(h, "# num_time_steps={}", stats.accepted);
    for (i, c) in columns.iter().enumerate() {
        let _ = writeln!(h, "# Column #{} = {c}", i + 1);
    }
    let _ = writeln!(h, "# The line below lists the names of the data fields:");
    h
}

/// Runs the pipeline's `[cycles]` for `seed` (which draws [`CycleSpec::heterogeneity`]'s fields,
/// if any) and writes its files under `out`. When `cancel` is set the run stops at its next step
/// and the files are written up to there ([`CycleReport::interrupted_s`]).
pub fn run_cycles(
    pipeline: &Pipeline,
    seed: u64,
    out: &Path,
    cancel: &AtomicBool,
) -> Result<CycleReport, EnsembleError> {
    let spec = pipeline.cycles.as_ref().expect("a [cycles] pipeline");
    let t0 = std::time::Instant::now();
    let solver = |e| EnsembleError::Solver(Box::new(e));
    // A fully dynamic run's quasi-dynamic phases are its own fault's: one stiffness, not two.
    let full =
        spec.dynamic.map(|_| FullyDynamicFault::from_scene(&pipeline.scene, spec, seed)).transpose().map_err(solver)?;
    let own;
    let fault = match &full {
        Some(f) => &f.quasi,
        None => {
            own = QuasiDynamicFault::from_scene(&pipeline.scene, spec, seed).map_err(solver)?;
            &own
        }
    };
    let stiffness_s = t0.elapsed().as_secs_f64();
    let lc = fault.stiffness.lc_m;
    let mu = pipeline.scene.density_kg_m3 * pipeline.scene.s_wave_speed().powi(2);
    let stations = spec
        .stations_m
        .iter()
        .map(|&d| {
            let j = ((d / lc).floor() as usize).min(fault.nodes() - 1);
            (j, d / lc - j as f64, String::new())
        })
        .collect();
    let mut rec = Recorder {
        spec,
        fault,
        mu,
        stations,
        global: String::new(),
        devol: String::new(),
        last_row: f64::NEG_INFINITY,
        last_profile: f64::NEG_INFINITY,
        profile_nodes: profile_nodes(fault.nodes(), lc),
        in_event: None,
        events: Vec::new(),
    };
    let t1 = std::time::Instant::now();
    let observe = |s: &CycleState| {
        rec.observe(s);
        if cancel.load(Ordering::Relaxed) { Flow::Stop } else { Flow::Continue }
    };
    let (last, stats) = match &full {
        Some(f) => f.run(fault.start(), spec.duration_s, &spec.tolerances, spec.max_steps, observe),
        None => fault.run(fault.start(), spec.duration_s, &spec.tolerances, spec.max_steps, observe),
    }
    .map_err(solver)?;
    let interrupted_s = (last.t_s < spec.duration_s).then_some(last.t_s);
    let run_s = t1.elapsed().as_secs_f64();
    let seas = out.join("seas");
    let station_columns = ["Time (s)", "Slip (m)", "Slip rate (log10 m/s)", "Shear stress (MPa)", "State (log10 s)"];
    for (k, &d) in spec.stations_m.iter().enumerate() {
        let name = format!("fltst_dp{:03}", (d / 100.0).round() as i64);
        let mut text = header(pipeline, fault, &stats, &format!("on fault, {} km depth", d / 1e3), &station_columns);
        text.push_str("t slip slip_rate shear_stress state\n# Here is the time-series data.\n");
        text.push_str(&rec.stations[k].2);
        write_text_atomic(&seas.join(name), &text)?;
    }
    let mut g = header(
        pipeline,
        fault,
        &stats,
        "the whole fault",
        &["Time (s)", "Max slip rate (log10 m/s)", "Moment rate (N·m/s per m along strike)"],
    );
    g.push_str("t max_slip_rate moment_rate\n# Here is the time-series data.\n");
    g.push_str(&rec.global);
    write_text_atomic(&seas.join("global.dat"), &g)?;
    let mut d = header(
        pipeline,
        fault,
        &stats,
        "slip along depth",
        &["Time (s)", "Max slip rate (log10 m/s)", "Slip (m), one column per depth of the first row"],
    );
    d.push_str("# Row #1 = Depth (m) with two zeros first\nz\nt max_slip_rate slip\n# Here are the data\n0 0");
    for &j in &rec.profile_nodes {
        let _ = write!(d, " {:.6e}", j as f64 * lc);
    }
    d.push('\n');
    d.push_str(&rec.devol);
    write_text_atomic(&seas.join("devol.dat"), &d)?;
    let events = rec.events;
    write_events(&[(seed, events.as_slice())], lc, &out.join("tables").join("cycle_events.parquet"))?;
    Ok(CycleReport {
        events,
        stats,
        nodes: fault.nodes(),
        lc_m: lc,
        stiffness_s,
        run_s,
        interrupted_s,
        out: out.to_path_buf(),
    })
}

/// Writes the events of each seed as the `cycle_events` table at `path`.
pub(crate) fn write_events(seeds: &[(u64, &[CycleEvent])], lc_m: f64, path: &Path) -> Result<(), EnsembleError> {
    let mut df = events_frame(seeds, lc_m)
        .map_err(|e| EnsembleError::Store(stickslip_store::StoreError::table("cycle_events", e)))?;
    write_parquet_atomic(&mut df, path)?;
    Ok(())
}

/// The events of each seed as the `cycle_events` table: their seed, their number within it and
/// the recurrence from the seed's previous event.
fn events_frame(seeds: &[(u64, &[CycleEvent])], lc: f64) -> PolarsResult<DataFrame> {
    let events: Vec<&CycleEvent> = seeds.iter().flat_map(|(_, e)| e.iter()).collect();
    let col = |name: &str, f: &dyn Fn(&CycleEvent) -> f64| {
        Column::new(name.into(), events.iter().map(|e| f(e)).collect::<Vec<f64>>())
    };
    let mut seed = Vec::with_capacity(events.len());
    let mut number = Vec::with_capacity(events.len());
    let mut recurrence: Vec<Option<f64>> = Vec::with_capacity(events.len());
    for (s, list) in seeds {
        for (i, e) in list.iter().enumerate() {
            seed.push(*s);
            number.push(i as u32);
            recurrence.push((i > 0).then(|| (e.onset_s - list[i - 1].onset_s) / YEAR_S));
        }
    }
    DataFrame::new(
        events.len(),
        vec![
            Column::new("seed".into(), seed),
            Column::new("event".into(), number),
            col("onset_s", &|e| e.onset_s),
            col("onset_years", &|e| e.onset_s / YEAR_S),
            Column::new("recurrence_years".into(), recurrence),
            col("duration_s", &|e| e.duration_s),
            col("hypocentre_depth_m", &|e| e.hypocentre_depth_m),
            col("peak_slip_rate_m_s", &|e| e.peak_slip_rate_m_s),
            col("surface_slip_m", &|e| e.surface_slip_m),
            col("max_slip_m", &|e| e.max_slip_m),
            col("ruptured_top_m", &|e| e.ruptured_m[0]),
            col("ruptured_bottom_m", &|e| e.ruptured_m[1]),
            col("moment_per_m_n", &|e| e.moment_per_m),
            col("length_m", &|e| e.length_m(lc)),
            col("moment_n_m", &|e| e.moment_n_m(lc)),
            col("magnitude", &|e| e.magnitude(lc)),
        ],
    )
}
