//! Tables of the spectra analysis: spectra, Fourier spectra, intensity measures, accelerograms and
//! attenuation of one seed.
//!
//! `node` is the LDEM number (u32), `component` `x`/`y`/`z`, `scale` `model` or `prototype`.
//! Prototype scale (docs/model.md §9): periods and times ×λ, SD ×λ, PSV unchanged, PSA and
//! accelerations ÷λ, PGD ×λ, Arias ÷λ, durations ×λ; the Fourier amplitude is unchanged at f/λ.

use polars::prelude::DataFrame;
use stickslip_seismo::spectra::fourier::FourierSpectrum;
use stickslip_seismo::spectra::intensity::Intensity;
use stickslip_solver::geometry::{Lattice, NodeId};
use stickslip_solver::scene::{Component, ControlChannel};

use crate::error::StoreError;
use crate::frame::{Columns, Frame, read_back};
use crate::schema::{ACCELEROGRAMS, ATTENUATION, FOURIER, INTENSITY, SPECTRA, col};
use crate::tables::series::Trace;

/// The two scales every table of the spectra analysis is written at.
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

/// What the spectra analysis computed for one control channel (model scale).
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
    /// SD (m), damping-major over the analysis's periods.
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

/// The spectra table of one seed (both scales).
pub fn spectra_frame(
    seed: u64,
    channels: &[ChannelSpectra],
    periods: &[f64],
    dampings: &[f64],
    lambda: f64,
) -> Result<DataFrame, StoreError> {
    let (mut node, mut comp, mut scale, mut damp, mut per, mut sd, mut psv, mut psa) =
        (vec![], vec![], vec![], vec![], vec![], vec![], vec![], vec![]);
    for c in channels {
        for sc in Scale::ALL {
            let l = sc.factor(lambda);
            for (di, &d) in dampings.iter().enumerate() {
                for (pi, &t) in periods.iter().enumerate() {
                    let v = c.sd[di * periods.len() + pi];
                    let omega = 2.0 * std::f64::consts::PI / t;
                    node.push(c.channel.node.ldem() as u32);
                    comp.push(c.channel.component.name());
                    scale.push(sc.name());
                    damp.push(d);
                    per.push(t * l);
                    sd.push(v * l);
                    psv.push(omega * v);
                    psa.push(omega * omega * v / l);
                }
            }
        }
    }
    let n = node.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::NODE, node)
        .static_str(col::COMPONENT, comp)
        .static_str(col::SCALE, scale)
        .f64(col::DAMPING, damp)
        .f64(col::PERIOD_S, per)
        .f64(col::SD_M, sd)
        .f64(col::PSV_M_S, psv)
        .f64(col::PSA_M_S2, psa)
        .finish(SPECTRA.name)
}

/// The Fourier table of one seed (model scale).
pub fn fourier_frame(seed: u64, channels: &[ChannelSpectra]) -> Result<DataFrame, StoreError> {
    let (mut node, mut comp, mut f, mut a) = (vec![], vec![], vec![], vec![]);
    for c in channels {
        let m = c.fourier.frequency_hz.len();
        node.extend(std::iter::repeat_n(c.channel.node.ldem() as u32, m));
        comp.extend(std::iter::repeat_n(c.channel.component.name(), m));
        f.extend_from_slice(&c.fourier.frequency_hz);
        a.extend_from_slice(&c.fourier.amplitude);
    }
    let n = node.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::NODE, node)
        .static_str(col::COMPONENT, comp)
        .f64(col::FREQUENCY_HZ, f)
        .f64(col::AMPLITUDE_M_S, a)
        .finish(FOURIER.name)
}

/// The intensity table of one seed (both scales).
pub fn intensity_frame(seed: u64, channels: &[ChannelSpectra], lambda: f64) -> Result<DataFrame, StoreError> {
    let mut rows = Vec::new();
    for c in channels {
        for sc in Scale::ALL {
            let l = sc.factor(lambda);
            let i = &c.intensity;
            rows.push((c, sc, [i.pga / l, i.pgv, i.pgd * l, i.arias / l, i.d5_95() * l, i.t5 * l, i.t95 * l]));
        }
    }
    let n = rows.len();
    let col = |k: usize| rows.iter().map(|r| r.2[k]).collect::<Vec<f64>>();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
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

/// The accelerograms of one seed at both scales.
pub fn accelerograms_frame(seed: u64, channels: &[ChannelSpectra], lambda: f64) -> Result<DataFrame, StoreError> {
    let (mut node, mut comp, mut scale, mut time, mut acc) = (vec![], vec![], vec![], vec![], vec![]);
    for c in channels {
        for sc in Scale::ALL {
            let l = sc.factor(lambda);
            let m = c.accel.len();
            node.extend(std::iter::repeat_n(c.channel.node.ldem() as u32, m));
            comp.extend(std::iter::repeat_n(c.channel.component.name(), m));
            scale.extend(std::iter::repeat_n(sc.name(), m));
            time.extend((0..m).map(|i| (c.t0 + i as f64 * c.dt) * l));
            acc.extend(c.accel.iter().map(|a| a / l));
        }
    }
    let n = node.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::NODE, node)
        .static_str(col::COMPONENT, comp)
        .static_str(col::SCALE, scale)
        .f64(col::TIME_S, time)
        .f64(col::ACCELERATION_M_S2, acc)
        .finish(ACCELEROGRAMS.name)
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
    /// The spectra table read back (one or many seeds).
    pub struct Spectra from SPECTRA, |c| {
        /// Seed of each row.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Node (LDEM number).
        node: Vec<u64> = c.u64s(col::NODE)?,
        /// Component.
        component: Vec<String> = c.strs(col::COMPONENT)?,
        /// Scale.
        scale: Vec<String> = c.strs(col::SCALE)?,
        /// Damping ratio.
        damping: Vec<f64> = c.f64s(col::DAMPING)?,
        /// Period (s).
        period_s: Vec<f64> = c.f64s(col::PERIOD_S)?,
        /// PSA (m/s²).
        psa_m_s2: Vec<f64> = c.f64s(col::PSA_M_S2)?,
    }
}

/// One channel's Fourier spectrum from a fourier part: (frequency, amplitude), if present.
pub fn read_fourier(df: &DataFrame, node_ldem: u64, component: Component) -> Result<Option<Trace>, StoreError> {
    let c = Columns::of(df, FOURIER.name);
    let (n, comp) = (c.u64s(col::NODE)?, c.strs(col::COMPONENT)?);
    let (f, a) = (c.f64s(col::FREQUENCY_HZ)?, c.f64s(col::AMPLITUDE_M_S)?);
    let idx: Vec<usize> = (0..c.height()).filter(|&i| n[i] == node_ldem && comp[i] == component.name()).collect();
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
/// the pipeline's columns without `seed`, `node`, `component`, `scale` — **spectra** `damping`,
/// `period_s`, `sd_m`, `psv_m_s`, `psa_m_s2`; **fourier** `frequency_hz`, `amplitude_m_s`;
/// **intensity** one row of `pga_m_s2`, `pgv_m_s`, `pgd_m`, `arias_m_s`, `d5_95_s`, `t5_s`,
/// `t95_s`.
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
            let v = sd[di * periods.len() + pi];
            let w = 2.0 * std::f64::consts::PI / t;
            d.push(xi);
            p.push(t);
            psv.push(w * v);
            psa.push(w * w * v);
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
