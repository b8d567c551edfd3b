//! A fault scenario's stations against the NGA-West2 ground-motion models (docs/model.md §16):
//! the mean bias ln(simulated/model) of RotD50 PSA against period with the Broadband Platform's
//! ±0.37 pass band, and every record's residual against its rupture distance.

use std::path::Path;

use plotters::style::RGBColor;
use stickslip_store::frame::Columns;
use stickslip_store::schema::{GMM_BIAS, GMM_RESIDUALS, col};
use stickslip_store::tables::gmm::BIAS_BAND_LN;

use super::Outcome;
use super::common::drawn;
use crate::charts::{Band, HLine, Line, Panel, Points, Scale, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;

/// The NGA-West2 models drawn beside their average.
const MODELS: [&str; 4] = ["bssa14", "ask14", "cb14", "cy14"];

/// Where PGA and PGV are drawn on the period axis (s): left of the shortest period, labelled.
const PGA_AT_S: f64 = 0.0062;
const PGV_AT_S: f64 = 0.0078;

/// The bias of the scenario's RotD50 against each model and their average, per period (PGA and
/// PGV at the left edge), one panel per site, and the residuals against distance.
pub(super) fn gmm_bias(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(df) = stickslip_store::io::read_parquet_if_present(&d.folder.gathered(&GMM_BIAS))? else {
        return Ok(Outcome::Skipped(
            "no gmm_bias table (a fault scene with [[stations]]; `stickslip gmm` writes it)".into(),
        ));
    };
    let c = Columns::of(&df, GMM_BIAS.name);
    let (imt, period, model) = (c.strs(col::IMT)?, c.opt_f64s(col::PERIOD_S)?, c.strs(col::MODEL)?);
    let (mean, lo, hi) = (c.f64s(col::MEAN_BIAS_LN)?, c.opt_f64s(col::CI90_LOW_LN)?, c.opt_f64s(col::CI90_HIGH_LN)?);
    let records = c.u64s(col::RECORDS)?;
    let site = if c.has(col::VS30_M_S) { c.f64s(col::VS30_M_S)? } else { vec![f64::NAN; imt.len()] };
    let mut sites: Vec<f64> = site.clone();
    sites.sort_by(f64::total_cmp);
    sites.dedup_by(|a, b| a.to_bits() == b.to_bits());
    let mut panels = Vec::new();
    let mut ts_all: Vec<f64> = Vec::new();
    let mut n = 0;
    for &v in &sites {
        let here = |i: usize| site[i].to_bits() == v.to_bits();
        let psa = |m: &str| -> Vec<usize> {
            let mut i: Vec<usize> = (0..imt.len())
                .filter(|&i| here(i) && imt[i] == "PSA" && model[i] == m && period[i].is_some())
                .collect();
            i.sort_by(|&a, &b| period[a].unwrap_or(0.0).total_cmp(&period[b].unwrap_or(0.0)));
            i
        };
        let avg = psa("average");
        if avg.is_empty() {
            continue;
        }
        let ts: Vec<f64> = avg.iter().map(|&i| period[i].unwrap_or(0.0)).collect();
        ts_all.extend(&ts);
        n = n.max(avg.iter().map(|&i| records.get(i).copied().unwrap_or(0)).max().unwrap_or(0));
        let (t0, t1) = (ts[0].min(PGA_AT_S) / 1.3, ts[ts.len() - 1] * 1.3);
        let mut bias = Panel::linear("period (s)", "mean bias ln(simulated / model)");
        bias.x_scale = Scale::Log;
        bias.minor_grid = false;
        bias.x_range = Some((t0, t1));
        bias.title = if v.is_finite() { format!("V_S30 {v} m/s") } else { "RotD50 PSA, 5% damping".into() };
        bias.bands.push(Band {
            points: vec![(t0, -BIAS_BAND_LN, BIAS_BAND_LN), (t1, -BIAS_BAND_LN, BIAS_BAND_LN)],
            colour: RGBColor(150, 150, 150),
            label: format!("pass band ±{BIAS_BAND_LN}"),
        });
        bias.bands.push(Band {
            points: avg.iter().filter_map(|&i| Some((period[i]?, lo[i]?, hi[i]?))).collect(),
            colour: crate::plot::colour(0),
            label: "90% interval (average)".into(),
        });
        for (k, m) in MODELS.into_iter().enumerate() {
            let rows = psa(m);
            if !rows.is_empty() {
                let mut l = Line::new(
                    m.to_uppercase(),
                    rows.iter().map(|&i| (period[i].unwrap_or(0.0), mean[i])).collect(),
                    k + 1,
                );
                l.width = 1;
                bias.lines.push(l);
            }
        }
        let mut l =
            Line::new("average of the models", avg.iter().map(|&i| (period[i].unwrap_or(0.0), mean[i])).collect(), 0);
        l.width = 3;
        bias.dots = true;
        bias.lines.push(l);
        // PGA and PGV against the models' average, at the left edge.
        for (k, (what, at)) in [("PGA", PGA_AT_S), ("PGV", PGV_AT_S)].into_iter().enumerate() {
            if let Some(i) = (0..imt.len()).find(|&i| here(i) && imt[i] == what && model[i] == "average") {
                bias.points.push(Points {
                    label: format!("{what} (drawn at {at} s)"),
                    points: vec![(at, mean[i])],
                    colour: crate::plot::colour(k + 6),
                    size: 6,
                });
            }
        }
        bias.hlines.push(HLine { y: 0.0, text: String::new(), colour: RGBColor(60, 60, 60) });
        let spread =
            avg.iter().flat_map(|&i| [Some(mean[i]), lo[i], hi[i]]).flatten().fold(1.0f64, |m, v| m.max(v.abs()));
        bias.y_range = Some((-(spread * 1.1).max(1.0), (spread * 1.1).max(1.0)));
        panels.push(bias);
    }
    if panels.is_empty() {
        return Ok(Outcome::Skipped("no PSA in any station's usable band".into()));
    }
    let ts = ts_all;

    // Residuals against distance (the models' average) for PGA, PGV and PSA at 1 s.
    let mut dist = Panel::linear("rupture distance R_rup (km)", "residual ln(simulated / model)");
    dist.x_scale = Scale::Log;
    dist.title = "each record, models' average".into();
    if let Some(rd) = stickslip_store::io::read_parquet_if_present(&d.folder.gathered(&GMM_RESIDUALS))? {
        let c = Columns::of(&rd, GMM_RESIDUALS.name);
        let (imt, period, model) = (c.strs(col::IMT)?, c.opt_f64s(col::PERIOD_S)?, c.strs(col::MODEL)?);
        let (r, res) = (c.f64s(col::R_RUP_KM)?, c.f64s(col::RESIDUAL_LN)?);
        let pick = |which: &dyn Fn(usize) -> bool| -> Vec<(f64, f64)> {
            (0..imt.len()).filter(|&i| model[i] == "average" && which(i)).map(|i| (r[i].max(0.1), res[i])).collect()
        };
        let one_s = ts.iter().copied().min_by(|a, b| (a.ln().abs()).total_cmp(&b.ln().abs())).unwrap_or(1.0);
        let groups: [(String, &dyn Fn(usize) -> bool); 3] = [
            ("PGA".to_string(), &|i| imt[i] == "PGA"),
            ("PGV".to_string(), &|i| imt[i] == "PGV"),
            (format!("PSA({one_s} s)"), &|i| imt[i] == "PSA" && period[i] == Some(one_s)),
        ];
        for (k, (label, which)) in groups.into_iter().enumerate() {
            dist.points.push(Points { label, points: pick(which), colour: crate::plot::colour(k + 3), size: 4 });
        }
        let (r0, r1) = r.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(v.max(0.1)), hi.max(*v)));
        let (r0, r1) = (r0 / 1.3, r1 * 1.3);
        dist.x_range = Some((r0, r1));
        dist.bands.push(Band {
            points: vec![(r0, -BIAS_BAND_LN, BIAS_BAND_LN), (r1, -BIAS_BAND_LN, BIAS_BAND_LN)],
            colour: RGBColor(150, 150, 150),
            label: String::new(),
        });
        dist.hlines.push(HLine { y: 0.0, text: String::new(), colour: RGBColor(60, 60, 60) });
    }
    panels.push(dist);
    let columns = if panels.len() > 2 { 3 } else { 2 };
    let sheet = Sheet::new("Simulated ground motion against the NGA-West2 models", columns, panels);
    drawn(
        path,
        &sheet,
        "Ground motion against the NGA-West2 models".into(),
        format!(
            "Left, one panel per site (V_S30): the mean over the records (up to {n}: stations × seeds) of \
             ln(simulated/model) for 5%-damped RotD50 PSA at each period in the stations' usable band, and for PGA \
             and PGV (the dots at the left edge), against BSSA14, ASK14, CB14, CY14 and their average (ln medians \
             averaged), with the average's 90% interval and the Broadband Platform's ±{BIAS_BAND_LN} pass band. \
             Right: each record's residual against the models' average, by rupture distance. Tables gmm_bias, \
             gmm_part_b and gmm_residuals; docs/model.md §16."
        ),
    )
}
