//! Tables of the accelerograms of one seed: the records and their metadata, the processed time
//! series, spectra, RotD spectra, Fourier spectra, intensity measures, and attenuation.
//!
//! A record is one control node and component over one event's window (or the whole run),
//! processed (docs/model.md §8); `record` names it within its seed (`S2-n36-x`: main shock S2,
//! LDEM node 36, component x). `scale` is `model` or `prototype`. Prototype scale (docs/model.md
//! §9): periods, times and durations ×λ, frequencies ÷λ, SD and displacements ×λ, PSV and
//! velocities unchanged, PSA and accelerations ÷λ, Arias ÷λ; the Fourier amplitude is unchanged
//! at f/λ. `in_band` says whether a period lies in the record's usable band.

use polars::prelude::DataFrame;
use stickslip_seismo::accelerogram::processing::{Processed, RecordBand};
use stickslip_seismo::spectra::fourier::FourierSpectrum;
use stickslip_seismo::spectra::intensity::Intensity;
use stickslip_solver::geometry::{Lattice, NodeId};
use stickslip_solver::scene::ControlChannel;

use crate::error::StoreError;
use crate::frame::{Columns, Frame, read_back};
use crate::schema::{ACCELEROGRAMS, ATTENUATION, FOURIER, INTENSITY, RECORDS, ROTD, SET, SPECTRA, col};
use crate::tables::series::Trace;

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

/// One processed record and what was computed of it (model scale).
#[derive(Clone, Debug)]
pub struct RecordData {
    /// Name within the seed, e.g. `S2-n36-x`.
    pub id: String,
    /// Index of the event in the seed's catalogue (`None` for a whole-run record).
    pub event: Option<u32>,
    /// The event's label (`S2`, `E17`) or `run`.
    pub label: String,
    /// The control channel.
    pub channel: ControlChannel,
    /// Node position (m).
    pub position: [f64; 3],
    /// Run time of the window's first sample (s, shear stage).
    pub start_s: f64,
    /// Length of the window before the event's start (s).
    pub pre_event_s: f64,
    /// The processed record (padded acceleration, velocity, displacement).
    pub processed: Processed,
    /// Filter corners and usable band.
    pub band: RecordBand,
    /// Intensity measures of the processed record.
    pub intensity: Intensity,
    /// SD (m), damping-major over the spectra's periods; empty without spectra.
    pub sd: Vec<f64>,
    /// Fourier amplitude spectrum of the processed record, without spectra `None`.
    pub fourier: Option<FourierSpectrum>,
}

/// RotD50 and RotD100 of a node's two horizontal records of one window (model scale).
#[derive(Clone, Debug)]
pub struct RotdData {
    /// Name within the seed, e.g. `S2-n36-xy`.
    pub id: String,
    /// Index of the event (`None` for the whole run).
    pub event: Option<u32>,
    /// The event's label or `run`.
    pub label: String,
    /// The node.
    pub node: NodeId,
    /// The band both components can be used in.
    pub band: RecordBand,
    /// RotD50 SD (m), damping-major.
    pub sd50: Vec<f64>,
    /// RotD100 SD (m), damping-major.
    pub sd100: Vec<f64>,
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

/// `(PSV, PSA)` of SD `v` at period `t`.
fn pseudo(v: f64, t: f64) -> (f64, f64) {
    let w = 2.0 * std::f64::consts::PI / t;
    (w * v, w * w * v)
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
        .f64(col::FIRST_SAMPLE_S, f(&|r, l| r.processed.t_first * l))
        .f64(col::F_LOW_HZ, band(&|b| b.f_low_hz))
        .f64(col::F_HIGH_HZ, band(&|b| b.f_high_hz))
        .f64(col::USABLE_LOW_HZ, band(&|b| b.usable_low_hz))
        .f64(col::USABLE_HIGH_HZ, band(&|b| b.usable_high_hz))
        .finish(RECORDS.name)
}

/// The processed time series of one seed's records, both scales.
pub fn accelerograms_frame(seed: u64, records: &[RecordData], lambda: f64) -> Result<DataFrame, StoreError> {
    let (mut id, mut scale, mut time, mut acc, mut vel, mut disp) = (vec![], vec![], vec![], vec![], vec![], vec![]);
    for r in records {
        let p = &r.processed;
        for sc in Scale::ALL {
            let l = sc.factor(lambda);
            let m = p.accel.len();
            id.extend(std::iter::repeat_n(r.id.clone(), m));
            scale.extend(std::iter::repeat_n(sc.name(), m));
            time.extend((0..m).map(|i| (r.start_s + p.t_first + i as f64 * p.dt) * l));
            acc.extend(p.accel.iter().map(|a| a / l));
            vel.extend_from_slice(&p.vel);
            disp.extend(p.disp.iter().map(|d| d * l));
        }
    }
    let n = id.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .str(col::RECORD, id)
        .static_str(col::SCALE, scale)
        .f64(col::TIME_S, time)
        .f64(col::ACCELERATION_M_S2, acc)
        .f64(col::VELOCITY_M_S, vel)
        .f64(col::DISPLACEMENT_M, disp)
        .finish(ACCELEROGRAMS.name)
}

/// The spectra table of one seed (both scales).
pub fn spectra_frame(
    seed: u64,
    records: &[RecordData],
    periods: &[f64],
    dampings: &[f64],
    lambda: f64,
) -> Result<DataFrame, StoreError> {
    let mut t = SpectrumColumns::default();
    for r in records {
        t.push(&r.id, r.channel.node, r.channel.component.name(), &r.band, &r.sd, periods, dampings, lambda);
    }
    t.frame(seed, SPECTRA.name)
}

/// The RotD table of one seed (both scales): `rotd50` rows then `rotd100` rows per record, in the
/// `component` column.
pub fn rotd_frame(
    seed: u64,
    rotd: &[RotdData],
    periods: &[f64],
    dampings: &[f64],
    lambda: f64,
) -> Result<DataFrame, StoreError> {
    let mut t = SpectrumColumns::default();
    for r in rotd {
        for (name, sd) in [("rotd50", &r.sd50), ("rotd100", &r.sd100)] {
            t.push(&r.id, r.node, name, &r.band, sd, periods, dampings, lambda);
        }
    }
    t.frame(seed, ROTD.name)
}

/// Columns of a spectra-shaped table, filled record by record.
#[derive(Default)]
struct SpectrumColumns {
    id: Vec<String>,
    node: Vec<u32>,
    comp: Vec<&'static str>,
    scale: Vec<&'static str>,
    damping: Vec<f64>,
    period: Vec<f64>,
    sd: Vec<f64>,
    psv: Vec<f64>,
    psa: Vec<f64>,
    in_band: Vec<bool>,
}

impl SpectrumColumns {
    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        id: &str,
        node: NodeId,
        comp: &'static str,
        band: &RecordBand,
        sd: &[f64],
        periods: &[f64],
        dampings: &[f64],
        lambda: f64,
    ) {
        for sc in Scale::ALL {
            let l = sc.factor(lambda);
            for (di, &d) in dampings.iter().enumerate() {
                for (pi, &t) in periods.iter().enumerate() {
                    let v = sd[di * periods.len() + pi];
                    let (psv, psa) = pseudo(v, t);
                    self.id.push(id.to_string());
                    self.node.push(node.ldem() as u32);
                    self.comp.push(comp);
                    self.scale.push(sc.name());
                    self.damping.push(d);
                    self.period.push(t * l);
                    self.sd.push(v * l);
                    self.psv.push(psv);
                    self.psa.push(psa / l);
                    self.in_band.push(band.holds_period(t));
                }
            }
        }
    }

    fn frame(self, seed: u64, table: &str) -> Result<DataFrame, StoreError> {
        let n = self.id.len();
        Frame::new(n)
            .u64(col::SEED, vec![seed; n])
            .str(col::RECORD, self.id)
            .u32(col::NODE, self.node)
            .static_str(col::COMPONENT, self.comp)
            .static_str(col::SCALE, self.scale)
            .f64(col::DAMPING, self.damping)
            .f64(col::PERIOD_S, self.period)
            .f64(col::SD_M, self.sd)
            .f64(col::PSV_M_S, self.psv)
            .f64(col::PSA_M_S2, self.psa)
            .bool(col::IN_BAND, self.in_band)
            .finish(table)
    }
}

/// The Fourier table of one seed (model scale).
pub fn fourier_frame(seed: u64, records: &[RecordData]) -> Result<DataFrame, StoreError> {
    let (mut id, mut f, mut a) = (vec![], vec![], vec![]);
    for r in records {
        let Some(fs) = &r.fourier else { continue };
        id.extend(std::iter::repeat_n(r.id.clone(), fs.frequency_hz.len()));
        f.extend_from_slice(&fs.frequency_hz);
        a.extend_from_slice(&fs.amplitude);
    }
    let n = id.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .str(col::RECORD, id)
        .f64(col::FREQUENCY_HZ, f)
        .f64(col::AMPLITUDE_M_S, a)
        .finish(FOURIER.name)
}

/// The intensity table of one seed (both scales).
pub fn intensity_frame(seed: u64, records: &[RecordData], lambda: f64) -> Result<DataFrame, StoreError> {
    let mut rows = Vec::new();
    for r in records {
        for sc in Scale::ALL {
            let l = sc.factor(lambda);
            let i = &r.intensity;
            rows.push((r, sc, [i.pga / l, i.pgv, i.pgd * l, i.arias / l, i.d5_95() * l, i.t5 * l, i.t95 * l]));
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
        /// Lowest usable frequency (Hz).
        usable_low_hz: Vec<f64> = c.f64s(col::USABLE_LOW_HZ)?,
        /// Highest usable frequency (Hz).
        usable_high_hz: Vec<f64> = c.f64s(col::USABLE_HIGH_HZ)?,
    }
}

read_back! {
    /// The spectra (or RotD) table read back (one or many seeds).
    pub struct Spectra from SPECTRA, |c| {
        /// Seed of each row.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Record name within its seed.
        record: Vec<String> = c.strs(col::RECORD)?,
        /// Node (LDEM number).
        node: Vec<u64> = c.u64s(col::NODE)?,
        /// Component (`rotd50`, `rotd100` in the RotD table).
        component: Vec<String> = c.strs(col::COMPONENT)?,
        /// Scale.
        scale: Vec<String> = c.strs(col::SCALE)?,
        /// Damping ratio.
        damping: Vec<f64> = c.f64s(col::DAMPING)?,
        /// Period (s).
        period_s: Vec<f64> = c.f64s(col::PERIOD_S)?,
        /// PSA (m/s²).
        psa_m_s2: Vec<f64> = c.f64s(col::PSA_M_S2)?,
        /// Whether the period is in the record's usable band.
        in_band: Vec<bool> = c.bools(col::IN_BAND)?,
    }
}

read_back! {
    /// The processed records read back (one or many seeds).
    pub struct Accelerograms from ACCELEROGRAMS, |c| {
        /// Seed of each row.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Record name within its seed.
        record: Vec<String> = c.strs(col::RECORD)?,
        /// Scale.
        scale: Vec<String> = c.strs(col::SCALE)?,
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

/// One record's Fourier spectrum from a fourier part: (frequency, amplitude), if present.
pub fn read_fourier(df: &DataFrame, record: &str) -> Result<Option<Trace>, StoreError> {
    let c = Columns::of(df, FOURIER.name);
    let ids = c.strs(col::RECORD)?;
    let (f, a) = (c.f64s(col::FREQUENCY_HZ)?, c.f64s(col::AMPLITUDE_M_S)?);
    let idx: Vec<usize> = (0..c.height()).filter(|&i| ids[i] == record).collect();
    if idx.is_empty() {
        return Ok(None);
    }
    Ok(Some((idx.iter().map(|&i| f[i]).collect(), idx.iter().map(|&i| a[i]).collect())))
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

/// The spectra, Fourier and intensity tables of one external record (`stickslip spectra`):
/// the pipeline's columns without `seed`, `record`, `node`, `component`, `scale`, `in_band` —
/// **spectra** `damping`, `period_s`, `sd_m`, `psv_m_s`, `psa_m_s2`; **fourier** `frequency_hz`,
/// `amplitude_m_s`; **intensity** one row of `pga_m_s2`, `pgv_m_s`, `pgd_m`, `arias_m_s`,
/// `d5_95_s`, `t5_s`, `t95_s`.
pub fn record_frames(
    periods: &[f64],
    dampings: &[f64],
    sd: &[f64],
    fourier: &FourierSpectrum,
    i: &Intensity,
) -> Result<[DataFrame; 3], StoreError> {
    let (mut d, mut p, mut psv, mut psa) = (vec![], vec![], vec![], vec![]);
    for (di, &xi) in dampings.iter().enumerate() {
        for (pi, &t) in periods.iter().enumerate() {
            let (v, a) = pseudo(sd[di * periods.len() + pi], t);
            d.push(xi);
            p.push(t);
            psv.push(v);
            psa.push(a);
        }
    }
    let n = d.len();
    let spectra = Frame::new(n)
        .f64(col::DAMPING, d)
        .f64(col::PERIOD_S, p)
        .f64(col::SD_M, sd.to_vec())
        .f64(col::PSV_M_S, psv)
        .f64(col::PSA_M_S2, psa)
        .finish(SPECTRA.name)?;
    let m = fourier.frequency_hz.len();
    let fourier = Frame::new(m)
        .f64(col::FREQUENCY_HZ, fourier.frequency_hz.clone())
        .f64(col::AMPLITUDE_M_S, fourier.amplitude.clone())
        .finish(FOURIER.name)?;
    let intensity = Frame::new(1)
        .f64(col::PGA_M_S2, vec![i.pga])
        .f64(col::PGV_M_S, vec![i.pgv])
        .f64(col::PGD_M, vec![i.pgd])
        .f64(col::ARIAS_M_S, vec![i.arias])
        .f64(col::D5_95_S, vec![i.d5_95()])
        .f64(col::T5_S, vec![i.t5])
        .f64(col::T95_S, vec![i.t95])
        .finish(INTENSITY.name)?;
    Ok([spectra, fourier, intensity])
}

/// One record of a matched set.
#[derive(Clone, Debug, PartialEq)]
pub struct SetRow {
    /// Seed.
    pub seed: u64,
    /// Record name within its seed (`S2-n36-x`, or `S2-n36-xy` for a RotD50 pair).
    pub record: String,
    /// Event label.
    pub label: String,
    /// Node (LDEM number).
    pub node: u32,
    /// Component (`x`, `y`, `z` or `rotd50`).
    pub component: String,
    /// Amplitude scale factor.
    pub scale_factor: f64,
    /// Mean squared log residual of the scaled record over the range.
    pub misfit: f64,
    /// Usable band at prototype scale (Hz).
    pub usable_hz: (f64, f64),
}

/// The set table, in the order the records were chosen.
pub fn set_frame(rows: &[SetRow]) -> Result<DataFrame, StoreError> {
    let n = rows.len();
    Frame::new(n)
        .u32(col::RANK, (1..=n as u32).collect())
        .u64(col::SEED, rows.iter().map(|r| r.seed).collect())
        .str(col::RECORD, rows.iter().map(|r| r.record.clone()).collect())
        .str(col::LABEL, rows.iter().map(|r| r.label.clone()).collect())
        .u32(col::NODE, rows.iter().map(|r| r.node).collect())
        .str(col::COMPONENT, rows.iter().map(|r| r.component.clone()).collect())
        .f64(col::SCALE_FACTOR, rows.iter().map(|r| r.scale_factor).collect())
        .f64(col::MISFIT, rows.iter().map(|r| r.misfit).collect())
        .f64(col::USABLE_LOW_HZ, rows.iter().map(|r| r.usable_hz.0).collect())
        .f64(col::USABLE_HIGH_HZ, rows.iter().map(|r| r.usable_hz.1).collect())
        .finish(SET.name)
}

read_back! {
    /// The set table read back.
    pub struct SetTable from SET, |c| {
        /// Seed of each record.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Record name within its seed.
        record: Vec<String> = c.strs(col::RECORD)?,
        /// Component.
        component: Vec<String> = c.strs(col::COMPONENT)?,
        /// Scale factor.
        scale_factor: Vec<f64> = c.f64s(col::SCALE_FACTOR)?,
        /// Misfit.
        misfit: Vec<f64> = c.f64s(col::MISFIT)?,
    }
}
