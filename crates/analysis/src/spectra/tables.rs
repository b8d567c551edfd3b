//! Tables of the spectra stage.
//!
//! Schemas (every per-seed table starts with `seed` u64; `node` is the LDEM number (u32),
//! `component` `x`/`y`/`z`, `scale` `model` or `prototype`):
//! - **spectra**: `node`, `component`, `scale`, `damping` f64, `period_s`, `sd_m`, `psv_m_s`,
//!   `psa_m_s2` f64;
//! - **fourier** (model scale; at prototype scale divide the frequency by λ, the amplitude is
//!   the same): `node`, `component`, `frequency_hz`, `amplitude_m_s` f64;
//! - **intensity**: `node`, `component`, `scale`, `pga_m_s2`, `pgv_m_s`, `pgd_m`, `arias_m_s`,
//!   `d5_95_s`, `t5_s`, `t95_s` f64;
//! - **accelerograms**: `node`, `component`, `scale`, `time_s`, `acceleration_m_s2` f64;
//! - **attenuation** (model scale): `event` u32, `label` str, `hypocentre_node` u32,
//!   `hypocentre_x_m` f64, `node` u32, `distance_m`, `pga_m_s2`, `pgv_m_s` f64;
//! - **psa_stats** (across seeds): `scale`, `node`, `component`, `damping`, `period_s`, `count`
//!   u32, `mean_m_s2`, `geometric_mean_m_s2`, `p5_m_s2`, `p50_m_s2`, `p95_m_s2` f64;
//! - **attenuation_fit** (across seeds, `log10 y = intercept + slope·log10(distance_m)`):
//!   `group` str (`S1`, … or `main`), `measure` str (`pga_m_s2`, `pgv_m_s`), `points` u32,
//!   `intercept`, `slope`, `r2` f64.

use polars::prelude::*;
use stickslip_solver::Lattice;

use crate::error::AnalysisError;
use crate::spectra::stage::{LogFit, SeedSpectra, log_log_fit};
use crate::stats::percentile_sorted;
use crate::tables::Frame;

const SCALES: [&str; 2] = ["model", "prototype"];

/// The spectra table of one seed (both scales).
pub fn spectra_frame(
    seed: u64,
    s: &SeedSpectra,
    periods: &[f64],
    dampings: &[f64],
    lambda: f64,
) -> Result<DataFrame, AnalysisError> {
    let (mut node, mut comp, mut scale, mut damp, mut per, mut sd, mut psv, mut psa) =
        (vec![], vec![], vec![], vec![], vec![], vec![], vec![], vec![]);
    for c in &s.channels {
        for (k, sc) in SCALES.iter().enumerate() {
            let l = if k == 0 { 1.0 } else { lambda };
            for (di, &d) in dampings.iter().enumerate() {
                for (pi, &t) in periods.iter().enumerate() {
                    let v = c.sd[di * periods.len() + pi];
                    let omega = 2.0 * std::f64::consts::PI / t;
                    node.push(c.channel.node.ldem() as u32);
                    comp.push(c.channel.component.name().to_string());
                    scale.push(sc.to_string());
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
        .u64("seed", vec![seed; n])
        .u32("node", node)
        .str("component", comp)
        .str("scale", scale)
        .f64("damping", damp)
        .f64("period_s", per)
        .f64("sd_m", sd)
        .f64("psv_m_s", psv)
        .f64("psa_m_s2", psa)
        .finish("spectra")
}

/// The Fourier table of one seed (model scale).
pub fn fourier_frame(seed: u64, s: &SeedSpectra) -> Result<DataFrame, AnalysisError> {
    let (mut node, mut comp, mut f, mut a) = (vec![], vec![], vec![], vec![]);
    for c in &s.channels {
        let m = c.fourier.frequency_hz.len();
        node.extend(std::iter::repeat_n(c.channel.node.ldem() as u32, m));
        comp.extend(std::iter::repeat_n(c.channel.component.name().to_string(), m));
        f.extend_from_slice(&c.fourier.frequency_hz);
        a.extend_from_slice(&c.fourier.amplitude);
    }
    let n = node.len();
    Frame::new(n)
        .u64("seed", vec![seed; n])
        .u32("node", node)
        .str("component", comp)
        .f64("frequency_hz", f)
        .f64("amplitude_m_s", a)
        .finish("fourier")
}

/// The intensity table of one seed (both scales).
pub fn intensity_frame(seed: u64, s: &SeedSpectra, lambda: f64) -> Result<DataFrame, AnalysisError> {
    let mut rows = Vec::new();
    for c in &s.channels {
        for (k, sc) in SCALES.iter().enumerate() {
            let l = if k == 0 { 1.0 } else { lambda };
            let i = &c.intensity;
            rows.push((c, *sc, [i.pga / l, i.pgv, i.pgd * l, i.arias / l, i.d5_95() * l, i.t5 * l, i.t95 * l]));
        }
    }
    let n = rows.len();
    let col = |k: usize| rows.iter().map(|r| r.2[k]).collect::<Vec<f64>>();
    Frame::new(n)
        .u64("seed", vec![seed; n])
        .u32("node", rows.iter().map(|r| r.0.channel.node.ldem() as u32).collect())
        .str("component", rows.iter().map(|r| r.0.channel.component.name().to_string()).collect())
        .str("scale", rows.iter().map(|r| r.1.to_string()).collect())
        .f64("pga_m_s2", col(0))
        .f64("pgv_m_s", col(1))
        .f64("pgd_m", col(2))
        .f64("arias_m_s", col(3))
        .f64("d5_95_s", col(4))
        .f64("t5_s", col(5))
        .f64("t95_s", col(6))
        .finish("intensity")
}

/// The accelerograms of one seed at both scales.
pub fn accelerograms_frame(seed: u64, s: &SeedSpectra, lambda: f64) -> Result<DataFrame, AnalysisError> {
    let (mut node, mut comp, mut scale, mut time, mut acc) = (vec![], vec![], vec![], vec![], vec![]);
    for c in &s.channels {
        for (k, sc) in SCALES.iter().enumerate() {
            let l = if k == 0 { 1.0 } else { lambda };
            let m = c.accel.len();
            node.extend(std::iter::repeat_n(c.channel.node.ldem() as u32, m));
            comp.extend(std::iter::repeat_n(c.channel.component.name().to_string(), m));
            scale.extend(std::iter::repeat_n(sc.to_string(), m));
            time.extend((0..m).map(|i| (c.t0 + i as f64 * c.dt) * l));
            acc.extend(c.accel.iter().map(|a| a / l));
        }
    }
    let n = node.len();
    Frame::new(n)
        .u64("seed", vec![seed; n])
        .u32("node", node)
        .str("component", comp)
        .str("scale", scale)
        .f64("time_s", time)
        .f64("acceleration_m_s2", acc)
        .finish("accelerograms")
}

/// The attenuation table of one seed.
pub fn attenuation_frame(seed: u64, s: &SeedSpectra, lattice: &Lattice) -> Result<DataFrame, AnalysisError> {
    let r = &s.attenuation;
    let n = r.len();
    Frame::new(n)
        .u64("seed", vec![seed; n])
        .u32("event", r.iter().map(|x| x.event).collect())
        .str("label", r.iter().map(|x| format!("S{}", x.rank)).collect())
        .u32("hypocentre_node", r.iter().map(|x| x.hypocentre.ldem() as u32).collect())
        .f64("hypocentre_x_m", r.iter().map(|x| lattice.position(x.hypocentre)[0]).collect())
        .u32("node", r.iter().map(|x| x.node.ldem() as u32).collect())
        .f64("distance_m", r.iter().map(|x| x.distance_m).collect())
        .f64("pga_m_s2", r.iter().map(|x| x.pga_m_s2).collect())
        .f64("pgv_m_s", r.iter().map(|x| x.pgv_m_s).collect())
        .finish("attenuation")
}

fn col_f64(df: &DataFrame, name: &str) -> Result<Vec<f64>, AnalysisError> {
    let t = |e| AnalysisError::table(name.to_string(), e);
    let c = df.column(name).map_err(t)?.cast(&DataType::Float64).map_err(t)?;
    Ok(c.f64().map_err(t)?.iter().map(|v| v.unwrap_or(f64::NAN)).collect())
}

fn col_str(df: &DataFrame, name: &str) -> Result<Vec<String>, AnalysisError> {
    let t = |e| AnalysisError::table(name.to_string(), e);
    Ok(df.column(name).map_err(t)?.str().map_err(t)?.iter().map(|v| v.unwrap_or("").to_string()).collect())
}

/// PSA across seeds per (scale, node, component, damping, period): mean, geometric mean, and
/// type-7 percentiles 5/50/95.
pub fn psa_stats_frame(spectra: &DataFrame) -> Result<DataFrame, AnalysisError> {
    let scale = col_str(spectra, "scale")?;
    let node = col_f64(spectra, "node")?;
    let comp = col_str(spectra, "component")?;
    let damping = col_f64(spectra, "damping")?;
    let period = col_f64(spectra, "period_s")?;
    let psa = col_f64(spectra, "psa_m_s2")?;
    /// One spectral ordinate across seeds; f64 keys as bits so they order and compare exactly.
    #[derive(PartialEq, Eq, PartialOrd, Ord)]
    struct Key {
        scale: String,
        node: u32,
        component: String,
        damping: u64,
        period: u64,
    }
    let mut groups: std::collections::BTreeMap<Key, Vec<f64>> = Default::default();
    for i in 0..spectra.height() {
        let key = Key {
            scale: scale[i].clone(),
            node: node[i] as u32,
            component: comp[i].clone(),
            damping: damping[i].to_bits(),
            period: period[i].to_bits(),
        };
        groups.entry(key).or_default().push(psa[i]);
    }
    let mut keys = Vec::new();
    let mut stats: [Vec<f64>; 5] = Default::default();
    let mut counts = Vec::new();
    for (key, mut v) in groups {
        v.retain(|x| x.is_finite());
        if v.is_empty() {
            continue;
        }
        v.sort_by(f64::total_cmp);
        let n = v.len() as f64;
        counts.push(v.len() as u32);
        stats[0].push(v.iter().sum::<f64>() / n);
        stats[1].push(if v[0] > 0.0 { (v.iter().map(|x| x.ln()).sum::<f64>() / n).exp() } else { f64::NAN });
        stats[2].push(percentile_sorted(&v, 0.05));
        stats[3].push(percentile_sorted(&v, 0.50));
        stats[4].push(percentile_sorted(&v, 0.95));
        keys.push(key);
    }
    let n = keys.len();
    let [mean, geo, p5, p50, p95] = stats;
    Frame::new(n)
        .str("scale", keys.iter().map(|k| k.scale.clone()).collect())
        .u32("node", keys.iter().map(|k| k.node).collect())
        .str("component", keys.iter().map(|k| k.component.clone()).collect())
        .f64("damping", keys.iter().map(|k| f64::from_bits(k.damping)).collect())
        .f64("period_s", keys.iter().map(|k| f64::from_bits(k.period)).collect())
        .u32("count", counts)
        .f64("mean_m_s2", mean)
        .f64("geometric_mean_m_s2", geo)
        .f64("p5_m_s2", p5)
        .f64("p50_m_s2", p50)
        .f64("p95_m_s2", p95)
        .finish("psa_stats")
}

/// Log-log fits of PGA and PGV against distance, per main-shock rank and over all main shocks.
pub fn attenuation_fit_frame(att: &DataFrame) -> Result<DataFrame, AnalysisError> {
    let label = col_str(att, "label")?;
    let dist = col_f64(att, "distance_m")?;
    let mut labels: Vec<String> = label.clone();
    labels.sort_by_key(|l| l.trim_start_matches('S').parse::<u32>().unwrap_or(u32::MAX));
    labels.dedup();
    labels.push("main".into());
    let mut rows: Vec<(String, String, LogFit)> = Vec::new();
    for measure in ["pga_m_s2", "pgv_m_s"] {
        let y = col_f64(att, measure)?;
        for g in &labels {
            let pts = (0..att.height()).filter(|&i| g == "main" || &label[i] == g).map(|i| (dist[i], y[i]));
            if let Some(fit) = log_log_fit(pts) {
                rows.push((g.clone(), measure.to_string(), fit));
            }
        }
    }
    let n = rows.len();
    Frame::new(n)
        .str("group", rows.iter().map(|r| r.0.clone()).collect())
        .str("measure", rows.iter().map(|r| r.1.clone()).collect())
        .u32("points", rows.iter().map(|r| r.2.points as u32).collect())
        .f64("intercept", rows.iter().map(|r| r.2.intercept).collect())
        .f64("slope", rows.iter().map(|r| r.2.slope).collect())
        .f64("r2", rows.iter().map(|r| r.2.r2).collect())
        .finish("attenuation_fit")
}

/// Spectra, Fourier and intensity tables of one external record (`stickslip spectra`).
///
/// Columns as the pipeline's tables without `seed`, `node`, `component`, `scale`: **spectra**
/// `damping`, `period_s`, `sd_m`, `psv_m_s`, `psa_m_s2`; **fourier** `frequency_hz`,
/// `amplitude_m_s`; **intensity** one row of `pga_m_s2`, `pgv_m_s`, `pgd_m`, `arias_m_s`,
/// `d5_95_s`, `t5_s`, `t95_s`.
pub fn record_tables(
    record: &crate::spectra::records::Record,
    periods: &[f64],
    dampings: &[f64],
    reading: crate::spectra::response::Reading,
    baseline: crate::spectra::intensity::Baseline,
    window: crate::spectra::fourier::Window,
) -> Result<[DataFrame; 3], AnalysisError> {
    use crate::spectra::response::{SpectrumPlan, SpectrumScratch};
    let plan = SpectrumPlan::new(record.dt, periods, dampings, reading, 16);
    let mut sd = vec![0.0; plan.len()];
    plan.compute(&record.accel, &mut SpectrumScratch::default(), &mut sd);
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
        .f64("damping", d)
        .f64("period_s", p)
        .f64("sd_m", sd)
        .f64("psv_m_s", psv)
        .f64("psa_m_s2", psa)
        .finish("spectra")?;
    let fas =
        crate::spectra::fourier::fourier_amplitude(&record.accel, record.dt, window, &mut rustfft::FftPlanner::new());
    let m = fas.frequency_hz.len();
    let fourier =
        Frame::new(m).f64("frequency_hz", fas.frequency_hz).f64("amplitude_m_s", fas.amplitude).finish("fourier")?;
    let i = crate::spectra::intensity::intensity(&record.accel, record.dt, baseline);
    let intensity = Frame::new(1)
        .f64("pga_m_s2", vec![i.pga])
        .f64("pgv_m_s", vec![i.pgv])
        .f64("pgd_m", vec![i.pgd])
        .f64("arias_m_s", vec![i.arias])
        .f64("d5_95_s", vec![i.d5_95()])
        .f64("t5_s", vec![i.t5])
        .f64("t95_s", vec![i.t95])
        .finish("intensity")?;
    Ok([spectra, fourier, intensity])
}
