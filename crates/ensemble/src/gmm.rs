//! A fault scenario's stations against the NGA-West2 ground-motion models (docs/model.md §16),
//! as the SCEC Broadband Platform validates simulations (Goulet et al. 2015): per record (a
//! station of a seed) and intensity measure, the residual ln(simulated/model) of RotD50; per
//! intensity measure, the mean bias with its 90% interval, the between-record spread, the fraction
//! of records within ±1σ, the Part-B test and the attenuation slope against R_rup.
//!
//! The inputs are the gathered `source`, `stations` and `station_spectra` tables; only stations
//! on the free surface (depth y = 0) are compared, as the models are for surface motions. Each seed's
//! rupture goes to the models as a vertical strike-slip fault (dip 90°, rake 0°) with the seed's
//! Mw (from its slip), Z_tor and width from its ruptured extent down dip; each station with its
//! R_rup, R_JB, R_x and R_y0; V_S30 the station's site for a broadband record (docs/model.md §17),
//! else the scene's S-wave speed at the surface unless given. Records are compared site by site
//! (grouped by their V_S30), and per R_rup bin by the Part-B test. Where an input lies outside a
//! model's ranges the prediction is still made and flagged (`outside`).

use std::collections::HashMap;

use stickslip_analysis::motions::GMM_PERIODS_S;
use stickslip_seismo::gmm::validation::{ModelColumn, attenuation_slope, part_b, validate_period};
use stickslip_seismo::gmm::{Imt, Mechanism, Model, Rupture, Site};
use stickslip_store::frame::Columns;
use stickslip_store::io::{read_parquet_if_present, write_parquet_atomic};
use stickslip_store::schema::{GMM_BIAS, GMM_PART_B, GMM_RESIDUALS, SOURCE, STATION_SPECTRA, STATIONS, col};
use stickslip_store::tables::gmm::{
    BiasRow, PART_B_BINS_KM, PART_B_JUDGED_MAX_S, PartBRow, ResidualRow, bias_frame, part_b_frame, residuals_frame,
};
use stickslip_store::{Folder, StoreError};

use crate::error::EnsembleError;

/// What to compare with.
#[derive(Clone, Debug, PartialEq)]
pub struct GmmOptions {
    /// The models (at least one).
    pub models: Vec<Model>,
    /// V_S30 given to the models for records without a site of their own (lattice records, m/s);
    /// `None`: each seed's S-wave speed (a homogeneous medium). A broadband record is compared at
    /// its station's V_S30.
    pub vs30_m_s: Option<f64>,
}

impl Default for GmmOptions {
    /// Every model, V_S30 the medium's S-wave speed.
    fn default() -> Self {
        GmmOptions { models: Model::ALL.to_vec(), vs30_m_s: None }
    }
}

/// One record: a station of a seed, with its rupture and its simulated motions.
#[derive(Clone, Debug)]
struct Record {
    seed: u64,
    station: String,
    rupture: Rupture,
    site: Site,
    azimuth_deg: f64,
    /// Highest frequency the record resolves (Hz), if processed.
    f_high_hz: Option<f64>,
    /// (imt, simulated RotD50).
    motions: Vec<(Imt, f64)>,
}

/// Lowest record bandwidth at which PGA is compared (Hz): PGA is carried by frequencies up to
/// about 10 Hz, which a coarse lattice filters out.
pub const PGA_MIN_BAND_HZ: f64 = 10.0;

/// The comparison: every residual row and every bias row.
#[derive(Clone, Debug, Default)]
pub struct GmmComparison {
    /// Per record, intensity measure and model (and the models' average).
    pub residuals: Vec<ResidualRow>,
    /// Per site, intensity measure and model (and the models' average).
    pub bias: Vec<BiasRow>,
    /// The Part-B test per site, intensity measure and distance bin.
    pub part_b: Vec<PartBRow>,
    /// Seeds compared.
    pub seeds: Vec<u64>,
    /// Records (station × seed) compared.
    pub records: usize,
    /// Records without a PSA in their usable band (PGA and PGV only).
    pub without_psa: usize,
    /// The range of the seeds' Mw.
    pub mw_range: [f64; 2],
    /// V_S30 given to the models (m/s), the range over seeds.
    pub vs30_range: [f64; 2],
}

fn imt_name(imt: Imt) -> (&'static str, Option<f64>) {
    match imt {
        Imt::Pga => ("PGA", None),
        Imt::Pgv => ("PGV", None),
        Imt::Psa(t) => ("PSA", Some(t)),
    }
}

/// Reads the records of `folder` (`None` when it has no gathered source or stations table).
fn records(folder: &Folder, vs30: Option<f64>) -> Result<Option<Vec<Record>>, StoreError> {
    let (Some(src), Some(st)) =
        (read_parquet_if_present(&folder.gathered(&SOURCE))?, read_parquet_if_present(&folder.gathered(&STATIONS))?)
    else {
        return Ok(None);
    };
    let c = Columns::of(&src, SOURCE.name);
    let (seeds, mw) = (c.u64s(col::SEED)?, c.f64s(col::MW)?);
    let (y0, y1) = (c.f64s(col::RUPTURE_Y_MIN_M)?, c.f64s(col::RUPTURE_Y_MAX_M)?);
    let vs = c.f64s(col::S_SPEED_M_S)?;
    let mut ruptures: HashMap<u64, (Rupture, f64)> = HashMap::new();
    for i in 0..seeds.len() {
        let rupture = Rupture {
            mw: mw[i],
            mechanism: Mechanism::StrikeSlip,
            dip_deg: 90.0,
            ztor_km: y0[i] / 1e3,
            width_km: ((y1[i] - y0[i]) / 1e3).max(1e-3),
            hypo_depth_km: None,
        };
        ruptures.insert(seeds[i], (rupture, vs30.unwrap_or(vs[i])));
    }
    let c = Columns::of(&st, STATIONS.name);
    let (seed, name) = (c.u64s(col::SEED)?, c.strs(col::STATION)?);
    let depth = c.f64s(col::Y_M)?;
    let (r_rup, r_jb, r_x, r_y0) =
        (c.f64s(col::R_RUP_M)?, c.f64s(col::R_JB_M)?, c.f64s(col::R_X_M)?, c.f64s(col::R_Y0_M)?);
    let az = c.f64s(col::AZIMUTH_DEG)?;
    let site = if c.has(col::VS30_M_S) { c.opt_f64s(col::VS30_M_S)? } else { vec![None; seed.len()] };
    let f_high = if c.has(col::F_HIGH_HZ) { c.opt_f64s(col::F_HIGH_HZ)? } else { vec![None; seed.len()] };
    let pga = if c.has(col::PGA_ROTD50_M_S2) { c.opt_f64s(col::PGA_ROTD50_M_S2)? } else { vec![None; seed.len()] };
    let pgv = if c.has(col::PGV_ROTD50_M_S) { c.opt_f64s(col::PGV_ROTD50_M_S)? } else { vec![None; seed.len()] };
    let mut psa: HashMap<(u64, String), Vec<(f64, f64)>> = HashMap::new();
    if let Some(sp) = read_parquet_if_present(&folder.gathered(&STATION_SPECTRA))? {
        let c = Columns::of(&sp, STATION_SPECTRA.name);
        let (s, n, t, v) =
            (c.u64s(col::SEED)?, c.strs(col::STATION)?, c.f64s(col::PERIOD_S)?, c.f64s(col::ROTD50_M_S2)?);
        for i in 0..s.len() {
            // The models' own periods only: the grid between them is for matching record sets.
            if GMM_PERIODS_S.iter().any(|g| g.to_bits() == t[i].to_bits()) {
                psa.entry((s[i], n[i].clone())).or_default().push((t[i], v[i]));
            }
        }
    }
    let mut out = Vec::new();
    for i in 0..seed.len() {
        // The models predict motions at the Earth's surface: buried stations are left out.
        if depth[i].abs() > 1e-6 {
            continue;
        }
        let Some(&(rupture, vs30)) = ruptures.get(&seed[i]) else { continue };
        let mut motions = Vec::new();
        motions.extend(pga[i].filter(|v| *v > 0.0).map(|v| (Imt::Pga, v)));
        motions.extend(pgv[i].filter(|v| *v > 0.0).map(|v| (Imt::Pgv, v)));
        for &(t, v) in psa.get(&(seed[i], name[i].clone())).map_or(&[][..], |v| v) {
            if v > 0.0 {
                motions.push((Imt::Psa(t), v));
            }
        }
        out.push(Record {
            seed: seed[i],
            station: name[i].clone(),
            rupture,
            site: Site {
                r_rup_km: r_rup[i] / 1e3,
                r_jb_km: (r_jb[i] / 1e3).min(r_rup[i] / 1e3),
                r_x_km: r_x[i] / 1e3,
                r_y0_km: Some(r_y0[i] / 1e3),
                vs30_m_s: site[i].unwrap_or(vs30),
                z1_km: None,
                z25_km: None,
                vs30_measured: true,
            },
            azimuth_deg: az[i],
            f_high_hz: f_high[i],
            motions,
        });
    }
    Ok(Some(out))
}

/// The key of an intensity measure for grouping (PGA, PGV, then PSA by period).
fn imt_key(imt: Imt) -> (u8, u64) {
    match imt {
        Imt::Pga => (0, 0),
        Imt::Pgv => (1, 0),
        Imt::Psa(t) => (2, t.to_bits()),
    }
}

/// Compares the stations of `folder` with the models; `None` when the folder has no fault source
/// or stations (not a fault scenario, or not finished).
pub fn compare(folder: &Folder, opts: &GmmOptions) -> Result<Option<GmmComparison>, EnsembleError> {
    let Some(records) = records(folder, opts.vs30_m_s)? else { return Ok(None) };
    if records.is_empty() {
        return Ok(None);
    }
    let mut out = GmmComparison::default();
    // Site by site: records of one V_S30 together, in ascending V_S30.
    let mut sites: Vec<f64> = records.iter().map(|r| r.site.vs30_m_s).collect();
    sites.sort_by(f64::total_cmp);
    sites.dedup();
    for vs30 in sites {
        let group: Vec<&Record> = records.iter().filter(|r| r.site.vs30_m_s == vs30).collect();
        compare_site(vs30, &group, opts, &mut out)?;
    }
    let mut seeds: Vec<u64> = records.iter().map(|r| r.seed).collect();
    seeds.sort_unstable();
    seeds.dedup();
    let range = |f: &dyn Fn(&Record) -> f64| {
        records.iter().map(f).fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], v| [lo.min(v), hi.max(v)])
    };
    out.mw_range = range(&|r| r.rupture.mw);
    out.vs30_range = range(&|r| r.site.vs30_m_s);
    out.records = records.iter().filter(|r| !r.motions.is_empty()).count();
    out.without_psa = records
        .iter()
        .filter(|r| !r.motions.is_empty() && !r.motions.iter().any(|(m, _)| matches!(m, Imt::Psa(_))))
        .count();
    out.seeds = seeds;
    Ok(Some(out))
}

/// The Part-B test of the records `who` (their simulations `sim`, each model's medians
/// `medians[k]`) in each R_rup bin that holds some.
fn part_b_bins(vs30: f64, imt: Imt, who: &[&Record], sim: &[f64], medians: &[Vec<f64>]) -> Vec<PartBRow> {
    let (name, period) = imt_name(imt);
    let judged = match imt {
        Imt::Pga => true,
        Imt::Pgv => false,
        Imt::Psa(t) => t <= PART_B_JUDGED_MAX_S * (1.0 + 1e-9),
    };
    let geo = |v: &[f64]| (v.iter().map(|x| x.ln()).sum::<f64>() / v.len() as f64).exp();
    let mut out = Vec::new();
    for bin in PART_B_BINS_KM {
        let inside: Vec<usize> =
            (0..who.len()).filter(|&i| who[i].site.r_rup_km >= bin[0] && who[i].site.r_rup_km < bin[1]).collect();
        if inside.is_empty() {
            continue;
        }
        let s: Vec<f64> = inside.iter().map(|&i| sim[i]).collect();
        let model_medians: Vec<f64> =
            medians.iter().map(|m| geo(&inside.iter().map(|&i| m[i]).collect::<Vec<f64>>())).collect();
        let Ok(p) = part_b(geo(&s), &model_medians) else { continue };
        out.push(PartBRow {
            vs30_m_s: vs30,
            imt: name,
            period_s: period,
            distance_km: bin,
            records: inside.len(),
            simulated_median: p.simulated_median,
            models_mean: p.model_mean,
            band: [p.low, p.high],
            pass: p.pass,
            judged,
        });
    }
    out
}

/// The comparison of the records of one site (`vs30`), appended to `out`.
fn compare_site(
    vs30: f64,
    records: &[&Record],
    opts: &GmmOptions,
    out: &mut GmmComparison,
) -> Result<(), EnsembleError> {
    let err = EnsembleError::Gmm;
    let mut groups: Vec<((u8, u64), Imt)> = Vec::new();
    for r in records {
        for &(imt, _) in &r.motions {
            if !groups.iter().any(|(k, _)| *k == imt_key(imt)) {
                groups.push((imt_key(imt), imt));
            }
        }
    }
    groups.sort_by_key(|(k, _)| *k);
    for (key, imt) in groups {
        let (name, period) = imt_name(imt);
        // The records that have this measure.
        let mut sim = Vec::new();
        let mut who: Vec<&Record> = Vec::new();
        for r in records {
            if let Some(&(_, v)) = r.motions.iter().find(|(m, _)| imt_key(*m) == key) {
                sim.push(v);
                who.push(r);
            }
        }
        let mut medians: Vec<Vec<f64>> = Vec::new();
        let mut sigmas: Vec<Vec<f64>> = Vec::new();
        let mut outside_counts = Vec::new();
        for &m in &opts.models {
            let (mut med, mut sig, mut outside) = (Vec::new(), Vec::new(), 0);
            for (r, &v) in who.iter().zip(&sim) {
                let p = m.predict(&r.rupture, &r.site, imt).map_err(err)?;
                let flag = match &p.applicability {
                    stickslip_seismo::gmm::Applicability::Inside => None,
                    stickslip_seismo::gmm::Applicability::Outside(ex) => {
                        outside += 1;
                        Some(ex.iter().map(|e| e.to_string()).collect::<Vec<_>>().join("; "))
                    }
                };
                out.residuals.push(ResidualRow {
                    seed: r.seed,
                    station: r.station.clone(),
                    imt: name,
                    period_s: period,
                    model: m.name(),
                    mw: r.rupture.mw,
                    r_rup_km: r.site.r_rup_km,
                    r_jb_km: r.site.r_jb_km,
                    azimuth_deg: r.azimuth_deg,
                    vs30_m_s: r.site.vs30_m_s,
                    simulated: v,
                    median: p.median(),
                    sigma: p.sigma,
                    tau: Some(p.tau),
                    phi: Some(p.phi),
                    outside: flag,
                });
                med.push(p.median());
                sig.push(p.sigma);
            }
            medians.push(med);
            sigmas.push(sig);
            outside_counts.push(outside);
        }
        let band = who.iter().filter_map(|r| r.f_high_hz).fold(f64::INFINITY, f64::min);
        let note = (matches!(imt, Imt::Pga) && band < PGA_MIN_BAND_HZ).then(|| {
            format!(
                "not comparable: the records resolve up to {:.2} Hz, PGA is carried by frequencies up to about \
                 {PGA_MIN_BAND_HZ} Hz",
                band
            )
        });
        let columns: Vec<ModelColumn> =
            medians.iter().zip(&sigmas).map(|(m, s)| ModelColumn { median: m, sigma: s }).collect();
        let v = validate_period(&sim, &columns).map_err(err)?;
        let distance: Vec<f64> = who.iter().map(|r| r.site.r_rup_km.max(1e-3)).collect();
        let slope = |median: &[f64]| {
            attenuation_slope(&distance, &sim, median)
                .ok()
                .map(|s| [Some(s.simulated), Some(s.model), Some(s.difference), s.difference_se])
        };
        for (k, &m) in opts.models.iter().enumerate() {
            let b = &v.per_model[k];
            out.bias.push(BiasRow {
                vs30_m_s: vs30,
                imt: name,
                period_s: period,
                model: m.name(),
                records: sim.len(),
                mean_bias_ln: b.mean,
                ci90_ln: b.ci90,
                between_record_std_ln: b.between_record_std,
                within_one_sigma: b.within_one_sigma,
                part_b_pass: None,
                slope: slope(&medians[k]),
                outside_records: outside_counts[k],
                note: note.clone(),
            });
        }
        // The models' average: ln medians and σ averaged per record.
        let n_models = opts.models.len() as f64;
        let avg_median: Vec<f64> =
            (0..sim.len()).map(|i| (medians.iter().map(|m| m[i].ln()).sum::<f64>() / n_models).exp()).collect();
        let avg_sigma: Vec<f64> = (0..sim.len()).map(|i| sigmas.iter().map(|s| s[i]).sum::<f64>() / n_models).collect();
        for (i, r) in who.iter().enumerate() {
            out.residuals.push(ResidualRow {
                seed: r.seed,
                station: r.station.clone(),
                imt: name,
                period_s: period,
                model: "average",
                mw: r.rupture.mw,
                r_rup_km: r.site.r_rup_km,
                r_jb_km: r.site.r_jb_km,
                azimuth_deg: r.azimuth_deg,
                vs30_m_s: r.site.vs30_m_s,
                simulated: sim[i],
                median: avg_median[i],
                sigma: avg_sigma[i],
                tau: None,
                phi: None,
                outside: None,
            });
        }
        let bins = part_b_bins(vs30, imt, &who, &sim, &medians);
        let a = &v.average;
        out.bias.push(BiasRow {
            vs30_m_s: vs30,
            imt: name,
            period_s: period,
            model: "average",
            records: sim.len(),
            mean_bias_ln: a.mean,
            ci90_ln: a.ci90,
            between_record_std_ln: a.between_record_std,
            within_one_sigma: a.within_one_sigma,
            part_b_pass: Some(bins.iter().all(|b| b.pass)),
            slope: slope(&avg_median),
            outside_records: outside_counts.iter().copied().max().unwrap_or(0),
            note,
        });
        out.part_b.extend(bins);
    }
    Ok(())
}

/// Writes the comparison's tables into `folder`'s tables (atomically, replacing earlier ones).
pub fn write(folder: &Folder, c: &GmmComparison) -> Result<(), StoreError> {
    write_parquet_atomic(&mut residuals_frame(&c.residuals)?, &folder.gathered(&GMM_RESIDUALS))?;
    write_parquet_atomic(&mut bias_frame(&c.bias)?, &folder.gathered(&GMM_BIAS))?;
    write_parquet_atomic(&mut part_b_frame(&c.part_b)?, &folder.gathered(&GMM_PART_B))?;
    Ok(())
}
