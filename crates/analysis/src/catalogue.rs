//! One seed's analysed run as tables: runs, events, sub-events, similarity.
//!
//! Schemas (every table starts with `seed` u64):
//! - **runs**: `status` str (`ok`, `failed`), `message` str, `steps` u64, `settle_steps` u64,
//!   `settle_time_s`, `simulated_time_s` (shear stage), `wall_time_s`, `dt_s`, `critical_dt_s`
//!   f64, `events` u32, `main_shocks` u32, `pipeline_hash` str;
//! - **events**: `event` u32 (index in the seed), `kind` str (`main`, `foreshock`, `aftershock`,
//!   `minor`), `label` str (`S1`, … the main shock it belongs to), then the burst measures below,
//!   `recurrence_s` (f64, null except for main shocks after the first), `sub_events` u32;
//! - **sub_events**: `event` u32, `sub_event` u32 (index in the event), then the burst measures;
//! - burst measures: `start_s`, `end_s`, `duration_s`, `drop_time_s`, `stress_drop_pa`,
//!   `slip_m`, `peak_slip_rate_m_s` f64, `peak_slipping_nodes` u32, `rupture_area_m2` f64, and
//!   one `peak_abs_accel_n<LDEM>_<component>_m_s2` f64 per recorded control acceleration;
//! - **similarity**: `event` u32, `kind`, `label` str, `lambda`, `stress_drop_pa`,
//!   `model_area_m2`, `prototype_area_m2`, `prototype_duration_s`, `prototype_recurrence_s`,
//!   `prototype_recurrence_years` (null without a recurrence), `m0_paper_dyne_cm`,
//!   `m0_consistent_dyne_cm`, `m_riera_paper_interplate`, `m_riera_paper_intraplate`,
//!   `m_riera_consistent_interplate`, `m_riera_consistent_intraplate`, `mw_paper`,
//!   `mw_consistent` f64.

use polars::prelude::DataFrame;
use stickslip_solver::scene::ControlChannel;
use stickslip_solver::{Model, RunOutput};

use crate::error::AnalysisError;
use crate::events::{Burst, Catalogue};
use crate::pipeline::Pipeline;
use crate::similarity::{AreaChoice, ModelEvent, SECONDS_PER_YEAR, moment_magnitude, riera_magnitude, scale};
use crate::tables::Frame;

/// Column name of the peak |acceleration| of a control channel.
pub fn peak_accel_column(c: &ControlChannel) -> String {
    format!("peak_abs_accel_n{}_{}_m_s2", c.node.ldem(), c.component.name())
}

/// Adds the burst measures of `bursts` to `frame`; `channels` fixes the acceleration columns.
fn burst_columns(mut f: Frame, bursts: &[&Burst], channels: &[ControlChannel]) -> Frame {
    let col = |g: &dyn Fn(&Burst) -> f64| bursts.iter().map(|b| g(b)).collect::<Vec<f64>>();
    f = f
        .f64("start_s", col(&|b| b.start_s))
        .f64("end_s", col(&|b| b.end_s))
        .f64("duration_s", col(&|b| b.duration_s()))
        .f64("drop_time_s", col(&|b| b.drop_time_s()))
        .f64("stress_drop_pa", col(&|b| b.stress_drop_pa))
        .f64("slip_m", col(&|b| b.slip_m))
        .f64("peak_slip_rate_m_s", col(&|b| b.peak_slip_rate_m_s))
        .u32("peak_slipping_nodes", bursts.iter().map(|b| b.peak_slipping_nodes).collect())
        .f64("rupture_area_m2", col(&|b| b.rupture_area_m2));
    for c in channels {
        let v = bursts
            .iter()
            .map(|b| b.peak_acceleration.iter().find(|(x, _)| x == c).map_or(f64::NAN, |(_, v)| *v))
            .collect();
        f = f.f64(&peak_accel_column(c), v);
    }
    f
}

/// Control acceleration channels recorded by the scene, in table order.
pub fn acceleration_channels(model: &Model) -> Vec<ControlChannel> {
    model
        .scene()
        .record
        .control
        .iter()
        .filter(|c| c.quantity == stickslip_solver::scene::Kinematic::Acceleration)
        .copied()
        .collect()
}

/// The events table of one seed.
pub fn events_frame(seed: u64, cat: &Catalogue, channels: &[ControlChannel]) -> Result<DataFrame, AnalysisError> {
    let n = cat.events.len();
    let bursts: Vec<&Burst> = cat.events.iter().map(|e| &e.burst).collect();
    let f = Frame::new(n)
        .u64("seed", vec![seed; n])
        .u32("event", (0..n as u32).collect())
        .str("kind", cat.events.iter().map(|e| e.kind.name().to_string()).collect())
        .str("label", cat.events.iter().map(|e| e.kind.label()).collect());
    burst_columns(f, &bursts, channels)
        .opt_f64("recurrence_s", cat.events.iter().map(|e| e.recurrence_s).collect())
        .u32("sub_events", cat.events.iter().map(|e| e.sub_events.len() as u32).collect())
        .finish("events")
}

/// The sub-events table of one seed.
pub fn sub_events_frame(seed: u64, cat: &Catalogue, channels: &[ControlChannel]) -> Result<DataFrame, AnalysisError> {
    let mut owner = Vec::new();
    let mut index = Vec::new();
    for (k, e) in cat.events.iter().enumerate() {
        for (j, _) in e.sub_events.clone().enumerate() {
            owner.push(k as u32);
            index.push(j as u32);
        }
    }
    let n = cat.sub_events.len();
    let bursts: Vec<&Burst> = cat.sub_events.iter().collect();
    let f = Frame::new(n).u64("seed", vec![seed; n]).u32("event", owner).u32("sub_event", index);
    burst_columns(f, &bursts, channels).finish("sub_events")
}

/// The similarity table of one seed: every event scaled to the prototype of the pipeline.
pub fn similarity_frame(seed: u64, cat: &Catalogue, pipeline: &Pipeline) -> Result<DataFrame, AnalysisError> {
    let scene = &pipeline.scene;
    let lattice = scene.lattice();
    let model_length = lattice.extent()[0];
    let n = cat.events.len();
    let mut rows = Vec::with_capacity(n);
    for e in &cat.events {
        let area = match pipeline.similarity.area {
            AreaChoice::Contact => lattice.contact_area(),
            AreaChoice::Rupture => e.burst.rupture_area_m2,
        };
        let input = ModelEvent {
            stress_drop_pa: e.burst.stress_drop_pa,
            model_length_m: model_length,
            model_area_m2: area,
            duration_s: Some(e.burst.duration_s()),
            recurrence_s: e.recurrence_s,
            model_rate_m_s: scene.shear.velocity_m_s,
        };
        rows.push((input, scale(&input, &pipeline.similarity)));
    }
    let col = |g: &dyn Fn(&ModelEvent, &crate::similarity::Scaled) -> f64| -> Vec<f64> {
        rows.iter().map(|(i, s)| g(i, s)).collect()
    };
    Frame::new(n)
        .u64("seed", vec![seed; n])
        .u32("event", (0..n as u32).collect())
        .str("kind", cat.events.iter().map(|e| e.kind.name().to_string()).collect())
        .str("label", cat.events.iter().map(|e| e.kind.label()).collect())
        .f64("lambda", col(&|_, s| s.lambda))
        .f64("stress_drop_pa", col(&|i, _| i.stress_drop_pa))
        .f64("model_area_m2", col(&|i, _| i.model_area_m2))
        .f64("prototype_area_m2", col(&|_, s| s.prototype_area_m2))
        .f64("prototype_duration_s", col(&|_, s| s.prototype_duration_s.unwrap_or(f64::NAN)))
        .opt_f64("prototype_recurrence_s", rows.iter().map(|(_, s)| s.prototype_recurrence_s).collect())
        .opt_f64(
            "prototype_recurrence_years",
            rows.iter().map(|(_, s)| s.prototype_recurrence_s.map(|r| r / SECONDS_PER_YEAR)).collect(),
        )
        .f64("m0_paper_dyne_cm", col(&|_, s| s.m0_paper_dyne_cm))
        .f64("m0_consistent_dyne_cm", col(&|_, s| s.m0_consistent_dyne_cm))
        .f64("m_riera_paper_interplate", col(&|_, s| riera_magnitude(s.m0_paper_dyne_cm, false)))
        .f64("m_riera_paper_intraplate", col(&|_, s| riera_magnitude(s.m0_paper_dyne_cm, true)))
        .f64("m_riera_consistent_interplate", col(&|_, s| riera_magnitude(s.m0_consistent_dyne_cm, false)))
        .f64("m_riera_consistent_intraplate", col(&|_, s| riera_magnitude(s.m0_consistent_dyne_cm, true)))
        .f64("mw_paper", col(&|_, s| moment_magnitude(s.m0_paper_dyne_cm)))
        .f64("mw_consistent", col(&|_, s| moment_magnitude(s.m0_consistent_dyne_cm)))
        .finish("similarity")
}

/// One row of the runs table.
#[derive(Clone, Debug, PartialEq)]
pub struct RunRow {
    /// Seed.
    pub seed: u64,
    /// `Ok(output summary)` or the error message.
    pub outcome: Result<RunFacts, String>,
    /// Wall time of the seed (s).
    pub wall_time_s: f64,
}

/// What a successful run reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunFacts {
    /// All steps.
    pub steps: u64,
    /// Self-weight steps.
    pub settle_steps: u64,
    /// Self-weight duration (s).
    pub settle_time_s: f64,
    /// `"dynamic"` or `"static"`.
    pub settled_by: &'static str,
    /// Shear steps skipped by the quasi-static skip-ahead.
    pub skipped_steps: u64,
    /// Shear-stage duration simulated (s).
    pub simulated_time_s: f64,
    /// Δt (s).
    pub dt_s: f64,
    /// Critical Δt (s).
    pub critical_dt_s: f64,
    /// Events found.
    pub events: u32,
    /// Main shocks found.
    pub main_shocks: u32,
}

impl RunFacts {
    /// Facts of a finished run and its catalogue.
    pub fn of(out: &RunOutput, cat: &Catalogue) -> Self {
        RunFacts {
            steps: out.steps(),
            settle_steps: out.settle_steps,
            settle_time_s: out.settle_time_s,
            settled_by: out.settled_by.name(),
            skipped_steps: out.skip.skipped_steps,
            simulated_time_s: out.records.time_s.last().copied().unwrap_or(0.0),
            dt_s: out.dt_s,
            critical_dt_s: out.critical.dt_s,
            events: cat.events.len() as u32,
            main_shocks: cat.main_shocks().count() as u32,
        }
    }
}

/// The runs table of some rows.
pub fn runs_frame(rows: &[RunRow], pipeline_hash: &str) -> Result<DataFrame, AnalysisError> {
    let n = rows.len();
    let fact = |g: &dyn Fn(&RunFacts) -> f64| -> Vec<f64> {
        rows.iter().map(|r| r.outcome.as_ref().map_or(f64::NAN, g)).collect()
    };
    let count =
        |g: &dyn Fn(&RunFacts) -> u64| -> Vec<u64> { rows.iter().map(|r| r.outcome.as_ref().map_or(0, g)).collect() };
    Frame::new(n)
        .u64("seed", rows.iter().map(|r| r.seed).collect())
        .str("status", rows.iter().map(|r| if r.outcome.is_ok() { "ok" } else { "failed" }.to_string()).collect())
        .str("message", rows.iter().map(|r| r.outcome.as_ref().err().cloned().unwrap_or_default()).collect())
        .u64("steps", count(&|f| f.steps))
        .u64("settle_steps", count(&|f| f.settle_steps))
        .f64("settle_time_s", fact(&|f| f.settle_time_s))
        .str("settled_by", rows.iter().map(|r| r.outcome.as_ref().map_or("", |f| f.settled_by).to_string()).collect())
        .u64("skipped_steps", count(&|f| f.skipped_steps))
        .f64("simulated_time_s", fact(&|f| f.simulated_time_s))
        .f64("wall_time_s", rows.iter().map(|r| r.wall_time_s).collect())
        .f64("dt_s", fact(&|f| f.dt_s))
        .f64("critical_dt_s", fact(&|f| f.critical_dt_s))
        .u32("events", count(&|f| f.events as u64).into_iter().map(|v| v as u32).collect())
        .u32("main_shocks", count(&|f| f.main_shocks as u64).into_iter().map(|v| v as u32).collect())
        .str("pipeline_hash", vec![pipeline_hash.to_string(); n])
        .finish("runs")
}
