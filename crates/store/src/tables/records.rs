//! The records of one seed: what each record is and its band, the processed time series, the
//! intensity measures, and the attenuation of peak motions with distance.
//!
//! A record is one control node and component over one event's window (or the whole run),
//! processed (docs/model.md §8); `record` names it within its seed (`S2-n36-x`: main shock S2,
//! LDEM node 36, component x). `scale` is `model` or `prototype`. Prototype scale (docs/model.md
//! §9): times and durations ×λ, frequencies ÷λ, displacements ×λ, velocities unchanged,
//! accelerations ÷λ, Arias ÷λ. The spectra are in [`crate::tables::spectra`].

use polars::prelude::DataFrame;
use stickslip_analysis::RecordData;
use stickslip_analysis::attenuation::AttenuationRow;
use stickslip_seismo::accelerogram::processing::{Processed, RecordBand};
use stickslip_seismo::similarity::RecordScale;
use stickslip_solver::geometry::Lattice;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Frame, narrow_f32, read_back};
use crate::spec::{Scope, SeedTable, SeedView, TableSpec};

/// One row per record and scale: what it is (event, node, component), where it was cut from the
/// run, its sampling, filter corners and usable band (docs/model.md §8).
pub const RECORDS: TableSpec = TableSpec {
    name: "records",
    scope: Scope::Gathered,
    key: &[col::SEED, col::RECORD, col::SCALE],
    columns: &[
        col::SEED,
        col::RECORD,
        col::EVENT,
        col::LABEL,
        col::NODE,
        col::COMPONENT,
        col::SCALE,
        col::X_M,
        col::Y_M,
        col::Z_M,
        col::START_S,
        col::PRE_EVENT_S,
        col::DT_S,
        col::SAMPLES,
        col::WINDOW_SAMPLES,
        col::RECORDED_DT_S,
        col::RECORDED_SAMPLES,
        col::FIRST_SAMPLE_S,
        col::F_LOW_HZ,
        col::F_HIGH_HZ,
        col::USABLE_LOW_HZ,
        col::USABLE_HIGH_HZ,
    ],
    variable: None,
};

/// The processed records (acceleration, velocity, displacement) over their windows, once: model
/// scale, single precision (see [`accelerograms_frame`]).
pub const ACCELEROGRAMS: TableSpec = TableSpec {
    name: "accelerograms",
    scope: Scope::PerSeed,
    key: &[col::SEED, col::RECORD, col::TIME_S],
    columns: &[col::SEED, col::RECORD, col::TIME_S, col::ACCELERATION_M_S2, col::VELOCITY_M_S, col::DISPLACEMENT_M],
    variable: None,
};

/// Intensity measures of every processed record, both scales.
pub const INTENSITY: TableSpec = TableSpec {
    name: "intensity",
    scope: Scope::Gathered,
    key: &[col::SEED, col::RECORD, col::SCALE],
    columns: &[
        col::SEED,
        col::RECORD,
        col::EVENT,
        col::LABEL,
        col::NODE,
        col::COMPONENT,
        col::SCALE,
        col::PGA_M_S2,
        col::PGV_M_S,
        col::PGD_M,
        col::ARIAS_M_S,
        col::D5_95_S,
        col::T5_S,
        col::T95_S,
    ],
    variable: None,
};

/// Peak motions of every control node in every main shock, with the distance from its
/// hypocentre.
pub const ATTENUATION: TableSpec = TableSpec {
    name: "attenuation",
    scope: Scope::Gathered,
    key: &[col::SEED, col::EVENT, col::NODE],
    columns: &[
        col::SEED,
        col::EVENT,
        col::LABEL,
        col::HYPOCENTRE_NODE,
        col::HYPOCENTRE_X_M,
        col::NODE,
        col::DISTANCE_M,
        col::PGA_M_S2,
        col::PGV_M_S,
    ],
    variable: None,
};

/// The two scales every table of the accelerograms is written at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// As simulated.
    Model,
    /// Scaled to the prototype fault (λ).
    Prototype,
}

impl Scale {
    /// Both scales.
    pub const ALL: [Scale; 2] = [Scale::Model, Scale::Prototype];

    /// `"model"` or `"prototype"`.
    pub fn name(self) -> &'static str {
        match self {
            Scale::Model => "model",
            Scale::Prototype => "prototype",
        }
    }

    /// The length and time factor of this scale: 1 or λ.
    pub fn factor(self, lambda: f64) -> f64 {
        match self {
            Scale::Model => 1.0,
            Scale::Prototype => lambda,
        }
    }
}

/// The records table of one seed: one row per record and scale.
pub fn records_frame(seed: u64, records: &[RecordData], lambda: f64) -> Result<DataFrame, StoreError> {
    let rows: Vec<(&RecordData, Scale)> = records.iter().flat_map(|r| Scale::ALL.map(|s| (r, s))).collect();
    let n = rows.len();
    let f = |g: &dyn Fn(&RecordData, f64) -> f64| -> Vec<f64> {
        rows.iter().map(|(r, s)| g(r, s.factor(lambda))).collect()
    };
    let band = |g: &dyn Fn(&RecordBand) -> f64| -> Vec<f64> {
        rows.iter().map(|(r, s)| g(&r.band.scaled(s.factor(lambda)))).collect()
    };
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .str(col::RECORD, rows.iter().map(|(r, _)| r.id.clone()).collect())
        .opt_u32(col::EVENT, rows.iter().map(|(r, _)| r.event).collect())
        .str(col::LABEL, rows.iter().map(|(r, _)| r.label.clone()).collect())
        .u32(col::NODE, rows.iter().map(|(r, _)| r.channel.node.ldem() as u32).collect())
        .static_str(col::COMPONENT, rows.iter().map(|(r, _)| r.channel.component.name()).collect())
        .static_str(col::SCALE, rows.iter().map(|(_, s)| s.name()).collect())
        .f64(col::X_M, f(&|r, l| r.position[0] * l))
        .f64(col::Y_M, f(&|r, l| r.position[1] * l))
        .f64(col::Z_M, f(&|r, l| r.position[2] * l))
        .f64(col::START_S, f(&|r, l| r.start_s * l))
        .f64(col::PRE_EVENT_S, f(&|r, l| r.pre_event_s * l))
        .f64(col::DT_S, f(&|r, l| r.processed.dt * l))
        .u32(col::SAMPLES, rows.iter().map(|(r, _)| r.processed.accel.len() as u32).collect())
        .u32(col::WINDOW_SAMPLES, rows.iter().map(|(r, _)| window(&r.processed).len() as u32).collect())
        .f64(col::RECORDED_DT_S, f(&|r, l| r.recorded_dt_s * l))
        .u32(col::RECORDED_SAMPLES, rows.iter().map(|(r, _)| r.recorded_samples).collect())
        .f64(col::FIRST_SAMPLE_S, f(&|r, l| r.processed.t_first * l))
        .f64(col::F_LOW_HZ, band(&|b| b.f_low_hz))
        .f64(col::F_HIGH_HZ, band(&|b| b.f_high_hz))
        .f64(col::USABLE_LOW_HZ, band(&|b| b.usable_low_hz))
        .f64(col::USABLE_HIGH_HZ, band(&|b| b.usable_high_hz))
        .finish(RECORDS.name)
}

/// The samples of a processed record's window: the record as cut from the run, without the
/// zero pads added before filtering (`records.first_sample_s`, `samples` and `window_samples`
/// describe them).
pub fn window(p: &Processed) -> std::ops::Range<usize> {
    p.pad_front..p.accel.len() - p.pad_end
}

/// The processed time series of one seed's records, stored once: over each record's window
/// (the pads the filter needed are described by the records table, not stored), at model scale
/// (the prototype's is the similarity rule's: times ×λ, accelerations ÷λ, velocities ×1,
/// displacements ×λ, λ = `similarity.lambda`), the time in double precision and the motion in
/// single precision — each value within 2⁻²⁴ ≈ 6e-8 of itself, far below what the record
/// resolves (its spectra, intensity measures and files are computed from the double-precision
/// record before it is stored).
pub fn accelerograms_frame(seed: u64, records: &[RecordData], _lambda: f64) -> Result<DataFrame, StoreError> {
    let (mut id, mut time, mut acc, mut vel, mut disp) = (vec![], vec![], vec![], vec![], vec![]);
    for r in records {
        let p = &r.processed;
        let w = window(p);
        id.extend(std::iter::repeat_n(r.id.as_str(), w.len()));
        time.extend(w.clone().map(|i| r.start_s + p.t_first + i as f64 * p.dt));
        let table = ACCELEROGRAMS.name;
        acc.extend(narrow_f32(table, col::ACCELERATION_M_S2, &p.accel[w.clone()])?);
        vel.extend(narrow_f32(table, col::VELOCITY_M_S, &p.vel[w.clone()])?);
        disp.extend(narrow_f32(table, col::DISPLACEMENT_M, &p.disp[w])?);
    }
    let n = id.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .str_ref(col::RECORD, id)
        .f64(col::TIME_S, time)
        .f32(col::ACCELERATION_M_S2, acc)
        .f32(col::VELOCITY_M_S, vel)
        .f32(col::DISPLACEMENT_M, disp)
        .finish(ACCELEROGRAMS.name)
}

/// The intensity table of one seed (both scales).
pub fn intensity_frame(seed: u64, records: &[RecordData], lambda: f64) -> Result<DataFrame, StoreError> {
    let mut rows = Vec::new();
    for r in records {
        for sc in Scale::ALL {
            // Computed once at model scale, scaled by the similarity rules.
            let s = RecordScale { lambda: sc.factor(lambda) };
            let i = &r.intensity;
            let scaled = [
                s.acceleration(i.pga),
                s.velocity(i.pgv),
                s.length(i.pgd),
                s.arias(i.arias),
                s.time(i.d5_95()),
                s.time(i.t5),
                s.time(i.t95),
            ];
            rows.push((r, sc, scaled));
        }
    }
    let n = rows.len();
    let col = |k: usize| rows.iter().map(|r| r.2[k]).collect::<Vec<f64>>();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .str(col::RECORD, rows.iter().map(|r| r.0.id.clone()).collect())
        .opt_u32(col::EVENT, rows.iter().map(|r| r.0.event).collect())
        .str(col::LABEL, rows.iter().map(|r| r.0.label.clone()).collect())
        .u32(col::NODE, rows.iter().map(|r| r.0.channel.node.ldem() as u32).collect())
        .static_str(col::COMPONENT, rows.iter().map(|r| r.0.channel.component.name()).collect())
        .static_str(col::SCALE, rows.iter().map(|r| r.1.name()).collect())
        .f64(col::PGA_M_S2, col(0))
        .f64(col::PGV_M_S, col(1))
        .f64(col::PGD_M, col(2))
        .f64(col::ARIAS_M_S, col(3))
        .f64(col::D5_95_S, col(4))
        .f64(col::T5_S, col(5))
        .f64(col::T95_S, col(6))
        .finish(INTENSITY.name)
}

/// The attenuation table of one seed.
pub fn attenuation_frame(seed: u64, rows: &[AttenuationRow], lattice: &Lattice) -> Result<DataFrame, StoreError> {
    let n = rows.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::EVENT, rows.iter().map(|x| x.event).collect())
        .str(col::LABEL, rows.iter().map(|x| format!("S{}", x.rank)).collect())
        .u32(col::HYPOCENTRE_NODE, rows.iter().map(|x| x.hypocentre.ldem() as u32).collect())
        .f64(col::HYPOCENTRE_X_M, rows.iter().map(|x| lattice.position(x.hypocentre)[0]).collect())
        .u32(col::NODE, rows.iter().map(|x| x.node.ldem() as u32).collect())
        .f64(col::DISTANCE_M, rows.iter().map(|x| x.distance_m).collect())
        .f64(col::PGA_M_S2, rows.iter().map(|x| x.pga_m_s2).collect())
        .f64(col::PGV_M_S, rows.iter().map(|x| x.pgv_m_s).collect())
        .finish(ATTENUATION.name)
}

/// The `records` part of a seed with records.
pub const RECORDS_PART: SeedTable = SeedTable { spec: RECORDS, write: |s| with_records(s, records_frame) };
/// The `accelerograms` part of a seed with records.
pub const ACCELEROGRAMS_PART: SeedTable =
    SeedTable { spec: ACCELEROGRAMS, write: |s| with_records(s, accelerograms_frame) };
/// The `intensity` part of a seed with records.
pub const INTENSITY_PART: SeedTable = SeedTable { spec: INTENSITY, write: |s| with_records(s, intensity_frame) };
/// The `attenuation` part of a seed whose spectra ask for it.
pub const ATTENUATION_PART: SeedTable = SeedTable {
    spec: ATTENUATION,
    write: |s| match (&s.analysis.records, &s.settings.spectra) {
        (Some(r), Some(sp)) if sp.attenuation => attenuation_frame(s.seed, &r.attenuation, s.model.lattice()).map(Some),
        _ => Ok(None),
    },
};

/// `frame(seed, records, λ)` of a seed with records.
fn with_records(
    s: &SeedView<'_>,
    frame: fn(u64, &[RecordData], f64) -> Result<DataFrame, StoreError>,
) -> Result<Option<DataFrame>, StoreError> {
    s.analysis.records.as_ref().map(|r| frame(s.seed, &r.records, s.analysis.lambda)).transpose()
}

read_back! {
    /// The records table read back (one or many seeds).
    pub struct Records from RECORDS, |c| {
        /// Seed of each row.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Record name within its seed.
        record: Vec<String> = c.strs(col::RECORD)?,
        /// Event index (`None` for a whole-run record).
        event: Vec<Option<f64>> = c.opt_f64s(col::EVENT)?,
        /// Event label or `run`.
        label: Vec<String> = c.strs(col::LABEL)?,
        /// Node (LDEM number).
        node: Vec<u64> = c.u64s(col::NODE)?,
        /// Component.
        component: Vec<String> = c.strs(col::COMPONENT)?,
        /// Scale.
        scale: Vec<String> = c.strs(col::SCALE)?,
        /// Time of the window's first sample in the run (s; before any padding).
        start_s: Vec<f64> = c.f64s(col::START_S)?,
        /// Part of the window before the event's start (s).
        pre_event_s: Vec<f64> = c.f64s(col::PRE_EVENT_S)?,
        /// Sampling interval (s).
        dt_s: Vec<f64> = c.f64s(col::DT_S)?,
        /// Samples of the window (the record without its pads).
        window_samples: Vec<u64> = c.u64s(col::WINDOW_SAMPLES)?,
        /// Sampling interval of the run's own record of the window, before resampling (s).
        recorded_dt_s: Vec<f64> = c.f64s(col::RECORDED_DT_S)?,
        /// Samples of the run's own record of the window (the raw window in `control`).
        recorded_samples: Vec<u64> = c.u64s(col::RECORDED_SAMPLES)?,
        /// Low corner of the band-pass (Hz).
        f_low_hz: Vec<f64> = c.f64s(col::F_LOW_HZ)?,
        /// High corner of the band-pass (Hz).
        f_high_hz: Vec<f64> = c.f64s(col::F_HIGH_HZ)?,
        /// Lowest usable frequency (Hz).
        usable_low_hz: Vec<f64> = c.f64s(col::USABLE_LOW_HZ)?,
        /// Highest usable frequency (Hz).
        usable_high_hz: Vec<f64> = c.f64s(col::USABLE_HIGH_HZ)?,
    }
}

read_back! {
    /// The processed records read back (one or many seeds), model scale, over their windows.
    pub struct Accelerograms from ACCELEROGRAMS, |c| {
        /// Seed of each row.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Record name within its seed.
        record: Vec<String> = c.strs(col::RECORD)?,
        /// Time (s).
        time_s: Vec<f64> = c.f64s(col::TIME_S)?,
        /// Acceleration (m/s²).
        acceleration_m_s2: Vec<f64> = c.f64s(col::ACCELERATION_M_S2)?,
        /// Velocity (m/s).
        velocity_m_s: Vec<f64> = c.f64s(col::VELOCITY_M_S)?,
        /// Displacement (m).
        displacement_m: Vec<f64> = c.f64s(col::DISPLACEMENT_M)?,
    }
}

read_back! {
    /// The attenuation table read back.
    pub struct Attenuation from ATTENUATION, |c| {
        /// Main shock of each row (`S1`, …).
        label: Vec<String> = c.strs(col::LABEL)?,
        /// Distance from the hypocentre (m).
        distance_m: Vec<f64> = c.f64s(col::DISTANCE_M)?,
        /// Peak acceleration (m/s²).
        pga_m_s2: Vec<f64> = c.f64s(col::PGA_M_S2)?,
        /// Peak velocity (m/s), NaN where not recorded.
        pgv_m_s: Vec<f64> = c.f64s(col::PGV_M_S)?,
    }
}

impl Attenuation {
    /// Rows.
    pub fn len(&self) -> usize {
        self.label.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.label.is_empty()
    }
}
