//! The spectra of one seed's records: response spectra of every record, RotD50 and RotD100 of
//! each node's horizontal pair (both scales), Fourier amplitude spectra (model scale); and the
//! same tables of one external record (`stickslip spectra`).
//!
//! Prototype scale (docs/model.md §9): periods ×λ, SD ×λ, PSV unchanged, PSA ÷λ; the Fourier
//! amplitude is unchanged at f/λ. `in_band` says whether a period lies in the record's usable
//! band.

use polars::prelude::DataFrame;
use stickslip_analysis::{RecordData, RotdData};
use stickslip_seismo::accelerogram::processing::RecordBand;
use stickslip_seismo::similarity::RecordScale;
use stickslip_seismo::spectra::fourier::FourierSpectrum;
use stickslip_seismo::spectra::intensity::Intensity;
use stickslip_solver::geometry::NodeId;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Columns, Frame, narrow_f32, read_back};
use crate::spec::{Scope, SeedTable, SeedView, TableSpec};
use crate::tables::records::{INTENSITY, Scale};
use crate::tables::series::Trace;

/// The columns of a spectra-shaped table (`spectra`, `rotd`).
const SPECTRUM_COLUMNS: &[&str] = &[
    col::SEED,
    col::RECORD,
    col::NODE,
    col::COMPONENT,
    col::SCALE,
    col::DAMPING,
    col::PERIOD_S,
    col::SD_M,
    col::PSV_M_S,
    col::PSA_M_S2,
    col::IN_BAND,
];

/// Response spectra of every record, both scales, with whether each period is in its band.
pub const SPECTRA: TableSpec = TableSpec {
    name: "spectra",
    scope: Scope::PerSeed,
    key: &[col::SEED, col::RECORD, col::SCALE, col::DAMPING, col::PERIOD_S],
    columns: SPECTRUM_COLUMNS,
    variable: None,
};

/// RotD50 and RotD100 (`component`) of the two horizontal records of a node, both scales.
pub const ROTD: TableSpec = TableSpec {
    name: "rotd",
    scope: Scope::PerSeed,
    key: &[col::SEED, col::RECORD, col::COMPONENT, col::SCALE, col::DAMPING, col::PERIOD_S],
    columns: SPECTRUM_COLUMNS,
    variable: None,
};

/// Fourier amplitude spectra of the processed records (model scale).
pub const FOURIER: TableSpec = TableSpec {
    name: "fourier",
    scope: Scope::PerSeed,
    key: &[col::SEED, col::RECORD, col::FREQUENCY_HZ],
    columns: &[col::SEED, col::RECORD, col::FREQUENCY_HZ, col::AMPLITUDE_M_S],
    variable: None,
};

/// The `spectra` part of a seed whose records have spectra.
pub const SPECTRA_PART: SeedTable = SeedTable {
    spec: SPECTRA,
    write: |s| match spectra_of(s) {
        Some((r, p, d)) => spectra_frame(s.seed, &r.records, p, d, s.analysis.lambda).map(Some),
        None => Ok(None),
    },
};
/// The `rotd` part of a seed whose spectra ask for RotD.
pub const ROTD_PART: SeedTable = SeedTable {
    spec: ROTD,
    write: |s| match spectra_of(s) {
        Some((r, p, d)) if s.settings.spectra.as_ref().is_some_and(|sp| sp.rotd) => {
            rotd_frame(s.seed, &r.rotd, p, d, s.analysis.lambda).map(Some)
        }
        _ => Ok(None),
    },
};
/// The `fourier` part of a seed whose records have spectra.
pub const FOURIER_PART: SeedTable = SeedTable {
    spec: FOURIER,
    write: |s| match spectra_of(s) {
        Some((r, _, _)) => fourier_frame(s.seed, &r.records).map(Some),
        None => Ok(None),
    },
};

/// A seed's records with the spectra's periods and dampings, when it has both.
fn spectra_of<'a>(s: &SeedView<'a>) -> Option<(&'a stickslip_analysis::SeedRecords, &'a [f64], &'a [f64])> {
    let (r, sp) = (s.analysis.records.as_ref()?, s.settings.spectra.as_ref()?);
    Some((r, &sp.periods, &sp.dampings))
}

/// `(PSV, PSA)` of SD `v` at period `t`.
fn pseudo(v: f64, t: f64) -> (f64, f64) {
    let w = 2.0 * std::f64::consts::PI / t;
    (w * v, w * w * v)
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
struct SpectrumColumns<'a> {
    id: Vec<&'a str>,
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

impl<'a> SpectrumColumns<'a> {
    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        id: &'a str,
        node: NodeId,
        comp: &'static str,
        band: &RecordBand,
        sd: &[f64],
        periods: &[f64],
        dampings: &[f64],
        lambda: f64,
    ) {
        for sc in Scale::ALL {
            // Computed once at model scale, scaled by the similarity rules (PSA_p(λT) = PSA_m(T)/λ).
            let s = RecordScale { lambda: sc.factor(lambda) };
            for (di, &d) in dampings.iter().enumerate() {
                for (pi, &t) in periods.iter().enumerate() {
                    let v = sd[di * periods.len() + pi];
                    let (psv, psa) = pseudo(v, t);
                    self.id.push(id);
                    self.node.push(node.ldem() as u32);
                    self.comp.push(comp);
                    self.scale.push(sc.name());
                    self.damping.push(d);
                    self.period.push(s.time(t));
                    self.sd.push(s.length(v));
                    self.psv.push(s.velocity(psv));
                    self.psa.push(s.acceleration(psa));
                    self.in_band.push(band.holds_period(t));
                }
            }
        }
    }

    fn frame(self, seed: u64, table: &str) -> Result<DataFrame, StoreError> {
        let n = self.id.len();
        Frame::new(n)
            .u64(col::SEED, vec![seed; n])
            .str_ref(col::RECORD, self.id)
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

/// The Fourier table of one seed (model scale): the amplitudes in single precision (each within
/// 2⁻²⁴ ≈ 6e-8 of its own magnitude: they are read to be drawn and compared in log units), the
/// frequencies in double.
pub fn fourier_frame(seed: u64, records: &[RecordData]) -> Result<DataFrame, StoreError> {
    let (mut id, mut f, mut a) = (vec![], vec![], vec![]);
    for r in records {
        let Some(fs) = &r.fourier else { continue };
        id.extend(std::iter::repeat_n(r.id.as_str(), fs.frequency_hz.len()));
        f.extend_from_slice(&fs.frequency_hz);
        a.extend(narrow_f32(FOURIER.name, col::AMPLITUDE_M_S, &fs.amplitude)?);
    }
    let n = id.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .str_ref(col::RECORD, id)
        .f64(col::FREQUENCY_HZ, f)
        .f32(col::AMPLITUDE_M_S, a)
        .finish(FOURIER.name)
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
