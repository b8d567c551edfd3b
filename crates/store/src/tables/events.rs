//! One seed's event catalogue as tables: events, sub-events, and every event at prototype scale.
//!
//! Burst measures (both tables): `start_s`, `end_s`, `duration_s`, `drop_time_s`,
//! `stress_drop_pa`, `slip_m`, `peak_slip_rate_m_s` f64, `peak_slipping_nodes` u32,
//! `rupture_area_m2` f64, and one `peak_abs_accel_n<LDEM>_<component>_m_s2` f64 per recorded
//! control acceleration.

use polars::prelude::DataFrame;
use stickslip_analysis::ScaledEvent;
use stickslip_analysis::events::acceleration_channels;
use stickslip_seismo::events::{Burst, Catalogue, EventKind};
use stickslip_seismo::similarity::SECONDS_PER_YEAR;
use stickslip_solver::scene::ControlChannel;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Columns, Frame, read_back};
use crate::spec::{Scope, SeedTable, TableSpec};

const BURST: [&str; 9] = [
    col::START_S,
    col::END_S,
    col::DURATION_S,
    col::DROP_TIME_S,
    col::STRESS_DROP_PA,
    col::SLIP_M,
    col::PEAK_SLIP_RATE_M_S,
    col::PEAK_SLIPPING_NODES,
    col::RUPTURE_AREA_M2,
];

/// Stick-slip events.
pub const EVENTS_TABLE: TableSpec = TableSpec {
    name: "events",
    scope: Scope::Gathered,
    key: &[col::SEED, col::EVENT],
    columns: &[
        col::SEED,
        col::EVENT,
        col::KIND,
        col::LABEL,
        BURST[0],
        BURST[1],
        BURST[2],
        BURST[3],
        BURST[4],
        BURST[5],
        BURST[6],
        BURST[7],
        BURST[8],
        col::RECURRENCE_S,
        col::SUB_EVENTS,
    ],
    variable: Some(
        "one peak_abs_accel_n<LDEM>_<component>_m_s2 per recorded control acceleration, after rupture_area_m2",
    ),
};

/// The bursts of slip each event is made of.
pub const SUB_EVENTS_TABLE: TableSpec = TableSpec {
    name: "sub_events",
    scope: Scope::Gathered,
    key: &[col::SEED, col::EVENT, col::SUB_EVENT],
    columns: &[
        col::SEED,
        col::EVENT,
        col::SUB_EVENT,
        BURST[0],
        BURST[1],
        BURST[2],
        BURST[3],
        BURST[4],
        BURST[5],
        BURST[6],
        BURST[7],
        BURST[8],
    ],
    variable: Some("one peak_abs_accel_n<LDEM>_<component>_m_s2 per recorded control acceleration"),
};

/// Every event at prototype scale.
pub const SIMILARITY: TableSpec = TableSpec {
    name: "similarity",
    scope: Scope::Gathered,
    key: &[col::SEED, col::EVENT],
    columns: &[
        col::SEED,
        col::EVENT,
        col::KIND,
        col::LABEL,
        col::LAMBDA,
        col::STRESS_DROP_PA,
        col::MODEL_AREA_M2,
        col::PROTOTYPE_AREA_M2,
        col::PROTOTYPE_DURATION_S,
        col::PROTOTYPE_RECURRENCE_S,
        col::PROTOTYPE_RECURRENCE_YEARS,
        col::M0_PAPER_DYNE_CM,
        col::M0_CONSISTENT_DYNE_CM,
        col::M_RIERA_PAPER_INTERPLATE,
        col::M_RIERA_PAPER_INTRAPLATE,
        col::M_RIERA_CONSISTENT_INTERPLATE,
        col::M_RIERA_CONSISTENT_INTRAPLATE,
        col::MW_PAPER,
        col::MW_CONSISTENT,
    ],
    variable: None,
};

/// Column name of the peak |acceleration| of a control channel.
pub fn peak_accel_column(c: &ControlChannel) -> String {
    format!("peak_abs_accel_n{}_{}_m_s2", c.node.ldem(), c.component.name())
}

/// Adds the burst measures of `bursts` to `frame`; `channels` names the accelerations whose peaks
/// the bursts carry, in order.
fn burst_columns(mut f: Frame, bursts: &[&Burst], channels: &[ControlChannel]) -> Frame {
    let col = |g: &dyn Fn(&Burst) -> f64| bursts.iter().map(|b| g(b)).collect::<Vec<f64>>();
    f = f
        .f64(col::START_S, col(&|b| b.start_s))
        .f64(col::END_S, col(&|b| b.end_s))
        .f64(col::DURATION_S, col(&|b| b.duration_s()))
        .f64(col::DROP_TIME_S, col(&|b| b.drop_time_s()))
        .f64(col::STRESS_DROP_PA, col(&|b| b.stress_drop_pa))
        .f64(col::SLIP_M, col(&|b| b.slip_m))
        .f64(col::PEAK_SLIP_RATE_M_S, col(&|b| b.peak_slip_rate_m_s))
        .u32(col::PEAK_SLIPPING_NODES, bursts.iter().map(|b| b.peak_slipping_nodes).collect())
        .f64(col::RUPTURE_AREA_M2, col(&|b| b.rupture_area_m2));
    for (k, c) in channels.iter().enumerate() {
        let v = bursts.iter().map(|b| b.peak_acceleration.get(k).copied().unwrap_or(f64::NAN)).collect();
        f = f.f64(&peak_accel_column(c), v);
    }
    f
}

/// The `events` part of a seed.
pub const EVENTS_PART: SeedTable = SeedTable {
    spec: EVENTS_TABLE,
    write: |s| events_frame(s.seed, &s.analysis.catalogue, &acceleration_channels(s.model)).map(Some),
};
/// The `sub_events` part of a seed.
pub const SUB_EVENTS_PART: SeedTable = SeedTable {
    spec: SUB_EVENTS_TABLE,
    write: |s| sub_events_frame(s.seed, &s.analysis.catalogue, &acceleration_channels(s.model)).map(Some),
};
/// The `similarity` part of a seed.
pub const SIMILARITY_PART: SeedTable = SeedTable {
    spec: SIMILARITY,
    write: |s| similarity_frame(s.seed, &s.analysis.catalogue, &s.analysis.scaled).map(Some),
};

/// The events table of one seed.
pub fn events_frame(seed: u64, cat: &Catalogue, channels: &[ControlChannel]) -> Result<DataFrame, StoreError> {
    let n = cat.events.len();
    let bursts: Vec<&Burst> = cat.events.iter().map(|e| &e.burst).collect();
    let f = Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::EVENT, (0..n as u32).collect())
        .static_str(col::KIND, cat.events.iter().map(|e| e.kind.name()).collect())
        .str(col::LABEL, cat.events.iter().map(|e| e.kind.label()).collect());
    burst_columns(f, &bursts, channels)
        .opt_f64(col::RECURRENCE_S, cat.events.iter().map(|e| e.recurrence_s).collect())
        .u32(col::SUB_EVENTS, cat.events.iter().map(|e| e.sub_events.len() as u32).collect())
        .finish(EVENTS_TABLE.name)
}

/// The sub-events table of one seed.
pub fn sub_events_frame(seed: u64, cat: &Catalogue, channels: &[ControlChannel]) -> Result<DataFrame, StoreError> {
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
    let f = Frame::new(n).u64(col::SEED, vec![seed; n]).u32(col::EVENT, owner).u32(col::SUB_EVENT, index);
    burst_columns(f, &bursts, channels).finish(SUB_EVENTS_TABLE.name)
}

/// The similarity table of one seed: every event of `cat` with its model-scale input, its
/// prototype-scale numbers and its magnitudes (`scaled[i]` belongs to `cat.events[i]`).
pub fn similarity_frame(seed: u64, cat: &Catalogue, scaled: &[ScaledEvent]) -> Result<DataFrame, StoreError> {
    let n = cat.events.len();
    assert_eq!(scaled.len(), n, "one scaled row per event");
    let col = |g: &dyn Fn(&ScaledEvent) -> f64| -> Vec<f64> { scaled.iter().map(g).collect() };
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::EVENT, (0..n as u32).collect())
        .static_str(col::KIND, cat.events.iter().map(|e| e.kind.name()).collect())
        .str(col::LABEL, cat.events.iter().map(|e| e.kind.label()).collect())
        .f64(col::LAMBDA, col(&|e| e.scaled.lambda))
        .f64(col::STRESS_DROP_PA, col(&|e| e.input.stress_drop_pa))
        .f64(col::MODEL_AREA_M2, col(&|e| e.input.model_area_m2))
        .f64(col::PROTOTYPE_AREA_M2, col(&|e| e.scaled.prototype_area_m2))
        .f64(col::PROTOTYPE_DURATION_S, col(&|e| e.scaled.prototype_duration_s.unwrap_or(f64::NAN)))
        .opt_f64(col::PROTOTYPE_RECURRENCE_S, scaled.iter().map(|e| e.scaled.prototype_recurrence_s).collect())
        .opt_f64(
            col::PROTOTYPE_RECURRENCE_YEARS,
            scaled.iter().map(|e| e.scaled.prototype_recurrence_s.map(|r| r / SECONDS_PER_YEAR)).collect(),
        )
        .f64(col::M0_PAPER_DYNE_CM, col(&|e| e.scaled.m0_paper_dyne_cm))
        .f64(col::M0_CONSISTENT_DYNE_CM, col(&|e| e.scaled.m0_consistent_dyne_cm))
        .f64(col::M_RIERA_PAPER_INTERPLATE, col(&|e| e.magnitudes.riera_paper_interplate))
        .f64(col::M_RIERA_PAPER_INTRAPLATE, col(&|e| e.magnitudes.riera_paper_intraplate))
        .f64(col::M_RIERA_CONSISTENT_INTERPLATE, col(&|e| e.magnitudes.riera_consistent_interplate))
        .f64(col::M_RIERA_CONSISTENT_INTRAPLATE, col(&|e| e.magnitudes.riera_consistent_intraplate))
        .f64(col::MW_PAPER, col(&|e| e.magnitudes.mw_paper))
        .f64(col::MW_CONSISTENT, col(&|e| e.magnitudes.mw_consistent))
        .finish(SIMILARITY.name)
}

/// What an event is, read back from its `kind` and `label` columns.
fn kinds(c: &Columns<'_>) -> Result<Vec<EventKind>, StoreError> {
    let (kind, label) = (c.strs(col::KIND)?, c.strs(col::LABEL)?);
    kind.iter()
        .zip(&label)
        .map(|(k, l)| {
            EventKind::parse(k, l).ok_or_else(|| StoreError::Unreadable {
                table: c.table().to_string(),
                what: format!(
                    "kind {k:?} with label {l:?} (columns {}, {}) is not an event this stickslip writes",
                    col::KIND,
                    col::LABEL
                ),
            })
        })
        .collect()
}

read_back! {
    /// The events table read back.
    pub struct Events from EVENTS_TABLE, |c| {
        /// Seed of each event.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Index of the event in its seed.
        event: Vec<u64> = c.u64s(col::EVENT)?,
        /// What each event is.
        kind: Vec<EventKind> = kinds(&c)?,
        /// Start (s).
        start_s: Vec<f64> = c.f64s(col::START_S)?,
        /// Duration (s).
        duration_s: Vec<f64> = c.f64s(col::DURATION_S)?,
        /// Stress drop (Pa).
        stress_drop_pa: Vec<f64> = c.f64s(col::STRESS_DROP_PA)?,
        /// Time since the previous main shock (s), main shocks after the first only.
        recurrence_s: Vec<Option<f64>> = c.opt_f64s(col::RECURRENCE_S)?,
        /// The `peak_abs_accel_*` columns present.
        peak_accel_columns: Vec<String> = c.names().into_iter().filter(|n| n.starts_with("peak_abs_accel_")).collect(),
    }
}

impl Events {
    /// Number of events.
    pub fn len(&self) -> usize {
        self.seed.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.seed.is_empty()
    }
}

read_back! {
    /// The similarity table read back.
    pub struct Similarity from SIMILARITY, |c| {
        /// Seed of each event.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// What each event is.
        kind: Vec<EventKind> = kinds(&c)?,
        /// λ of each row.
        lambda: Vec<f64> = c.f64s(col::LAMBDA)?,
        /// Riera's magnitude from the paper's moment, interplate.
        m_riera_paper_interplate: Vec<f64> = c.f64s(col::M_RIERA_PAPER_INTERPLATE)?,
        /// Mw from the consistent moment.
        mw_consistent: Vec<f64> = c.f64s(col::MW_CONSISTENT)?,
    }
}
