//! The catalogue figures: magnitude–frequency with the Gutenberg–Richter fit, recurrence
//! histograms with the renewal fits, stacked aftershock rates with the Omori–Utsu fit, scaling
//! relations beside the self-similar slopes, and an overview of every event (time against
//! magnitude) that stays readable from a few events to 100,000.

use std::path::Path;

use plotters::style::BLACK;
use stickslip_seismo::catalogue::recurrence::{BptFit, ExponentialFit, WeibullFit, inter_event_times};
use stickslip_store::frame::Columns;
use stickslip_store::io::read_parquet_if_present;
use stickslip_store::schema::{
    AFTERSHOCKS_TABLE, B_VALUES, MAGNITUDE_FREQUENCY, OMORI, RECURRENCE_STATS, SCALING, SIMILARITY, TableSpec, col,
};
use stickslip_store::tables::catalogue::{Aftershocks, BValues, MagnitudeFrequency, Omori, RecurrenceStats, Scaling};

use super::Outcome;
use super::common::drawn;
use crate::charts::{Line, Panel, Points, Scale, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;
use crate::plot::colour;

fn gathered(d: &ReportInput, t: TableSpec) -> Result<Option<polars::prelude::DataFrame>, ReportError> {
    Ok(read_parquet_if_present(&d.folder.gathered(&t))?)
}

/// The pooled rows of a catalogue table (`seed` null).
fn pooled(seed: &[Option<u64>]) -> impl Iterator<Item = usize> + '_ {
    (0..seed.len()).filter(|&i| seed[i].is_none())
}

/// Magnitude–frequency of the two magnitudes the report shows, with the fit.
pub fn magnitude_frequency(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (Some(mf), Some(bv)) = (gathered(d, MAGNITUDE_FREQUENCY)?, gathered(d, B_VALUES)?) else {
        return Ok(Outcome::Skipped("no catalogue tables".into()));
    };
    let (mf, bv) = (MagnitudeFrequency::read(&mf)?, BValues::read(&bv)?);
    let mut panels = Vec::new();
    let mut fits = Vec::new();
    for (quantity, name) in
        [(col::MW_CONSISTENT, "Mw (consistent moment)"), (col::M_RIERA_PAPER_INTERPLATE, "Riera M (paper's moment)")]
    {
        let rows: Vec<usize> = pooled(&mf.seed).filter(|&i| mf.quantity[i] == quantity).collect();
        if rows.is_empty() {
            continue;
        }
        let cumulative = rows.iter().map(|&i| (mf.centre[i], mf.cumulative[i])).filter(|p| p.1 > 0.0).collect();
        let incremental = rows.iter().map(|&i| (mf.centre[i], mf.incremental[i])).filter(|p| p.1 > 0.0).collect();
        let fit: Vec<(f64, f64)> = rows.iter().filter_map(|&i| Some((mf.centre[i], mf.fit_cumulative[i]?))).collect();
        let b = pooled(&bv.seed).find(|&i| bv.quantity[i] == quantity);
        let fit_text = match b {
            Some(i) => match (bv.b[i], bv.b_sigma[i], bv.mc[i]) {
                (Some(b), Some(s), Some(mc)) => format!("b = {b:.2} ± {s:.2} above Mc = {mc:.1}"),
                _ => format!("no b-value: {}", bv.reason[i].clone().unwrap_or_default()),
            },
            None => String::new(),
        };
        fits.push(format!("{name}: {fit_text}"));
        let mut lines = Vec::new();
        if !fit.is_empty() {
            lines.push(Line {
                label: "Gutenberg–Richter fit".into(),
                points: fit,
                colour: BLACK,
                width: 2,
                alpha: 1.0,
            });
        }
        panels.push(Panel {
            name: name.into(),
            y_scale: Scale::Log,
            minor_grid: true,
            points: vec![
                Points { label: "N(≥ M)".into(), points: cumulative, colour: colour(0), size: 4 },
                Points { label: "events per bin".into(), points: incremental, colour: colour(1), size: 3 },
            ],
            lines,
            ..Panel::linear("magnitude", "events")
        });
    }
    if panels.is_empty() {
        return Ok(Outcome::Skipped("no magnitudes".into()));
    }
    drawn(
        path,
        &Sheet::new("Magnitude–frequency (all seeds)", panels.len(), panels),
        "Magnitude–frequency".into(),
        format!(
            "Cumulative and incremental counts in bins of 0.1, pooled over the seeds, with the Gutenberg–Richter \
             fit (Aki–Utsu b, Shi–Bolt σ) above the completeness magnitude. {}.",
            fits.join("; ")
        ),
    )
}

/// Histograms of the recurrence intervals (main shocks, all events) with the renewal fits.
pub fn recurrence_fits(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (Some(ev), Some(rs)) = (&d.events, gathered(d, RECURRENCE_STATS)?) else {
        return Ok(Outcome::Skipped("no catalogue tables".into()));
    };
    let rs = RecurrenceStats::read(&rs)?;
    let mut seeds: Vec<u64> = ev.seed.clone();
    seeds.dedup();
    let mut panels = Vec::new();
    let mut notes = Vec::new();
    for sequence in ["main", "all"] {
        let mut intervals = Vec::new();
        for &s in &seeds {
            let times: Vec<f64> = (0..ev.len())
                .filter(|&i| ev.seed[i] == s && (sequence == "all" || ev.kind[i].is_main()))
                .map(|i| ev.start_s[i])
                .collect();
            intervals.extend(inter_event_times(&times));
        }
        let Some(r) = pooled(&rs.seed).find(|&i| rs.sequence[i] == sequence) else { continue };
        if intervals.len() < 2 {
            notes.push(format!("{sequence}: {}", rs.reason[r].clone().unwrap_or_else(|| "too few intervals".into())));
            continue;
        }
        let max = intervals.iter().copied().fold(0.0, f64::max);
        let bins = ((intervals.len() as f64).sqrt().ceil() as usize).clamp(5, 60);
        let width = max / bins as f64;
        let mut counts = vec![0usize; bins];
        for &x in &intervals {
            counts[((x / width) as usize).min(bins - 1)] += 1;
        }
        // The histogram as a step line, and each fit's density × n × bin width.
        let mut steps = vec![(0.0, 0.0)];
        for (k, &c) in counts.iter().enumerate() {
            steps.push((k as f64 * width, c as f64));
            steps.push(((k + 1) as f64 * width, c as f64));
        }
        steps.push((max, 0.0));
        let n = intervals.len() as f64;
        let grid: Vec<f64> = (1..=200).map(|k| k as f64 * max / 200.0).collect();
        let curve = |pdf: &dyn Fn(f64) -> f64| grid.iter().map(|&t| (t, pdf(t) * n * width)).collect::<Vec<_>>();
        let mut lines =
            vec![Line { label: "intervals".into(), points: steps, colour: colour(0), width: 2, alpha: 1.0 }];
        if let (Some(mean), Some(alpha), Some(aic)) = (rs.bpt_mean_s[r], rs.bpt_aperiodicity[r], rs.bpt_aic[r]) {
            let f = BptFit {
                n: 0,
                mean,
                aperiodicity: alpha,
                mean_se: 0.0,
                aperiodicity_se: 0.0,
                log_likelihood: 0.0,
                aic,
            };
            lines.push(Line::new(format!("BPT α = {alpha:.2} (AIC {aic:.0})"), curve(&|t| f.pdf(t)), 1));
        }
        if let (Some(scale), Some(shape), Some(aic)) = (rs.weibull_scale_s[r], rs.weibull_shape[r], rs.weibull_aic[r]) {
            let f = WeibullFit { n: 0, shape, scale, shape_se: 0.0, scale_se: 0.0, log_likelihood: 0.0, aic };
            lines.push(Line::new(format!("Weibull k = {shape:.2} (AIC {aic:.0})"), curve(&|t| f.pdf(t)), 2));
        }
        if let (Some(mean), Some(aic)) = (rs.mean_s[r], rs.exponential_aic[r]) {
            let f = ExponentialFit { n: 0, mean, mean_se: 0.0, log_likelihood: 0.0, aic };
            lines.push(Line::new(format!("Poisson (AIC {aic:.0})"), curve(&|t| f.pdf(t)), 3));
        }
        let cv = match (rs.cv[r], rs.cv_low[r], rs.cv_high[r]) {
            (Some(c), Some(lo), Some(hi)) => format!("CV {c:.2} [{lo:.2}, {hi:.2}]"),
            (Some(c), _, _) => format!("CV {c:.2}"),
            _ => "no CV".into(),
        };
        let what = if sequence == "main" { "main shocks" } else { "all events" };
        notes.push(format!("{what}: {} intervals, {cv}", intervals.len()));
        panels.push(Panel {
            name: format!("{what}, {cv}"),
            lines,
            y_range: Some((0.0, counts.iter().copied().max().unwrap_or(1) as f64 * 1.25)),
            ..Panel::linear("time between events (s, model scale)", "intervals per bin")
        });
    }
    if panels.is_empty() {
        return Ok(Outcome::Skipped(format!("too few intervals ({})", notes.join("; "))));
    }
    drawn(
        path,
        &Sheet::new("Recurrence intervals and renewal fits (all seeds)", panels.len(), panels),
        "Recurrence statistics".into(),
        format!(
            "Histograms of the intervals between main shocks and between all events, within each seed and pooled, \
             with the maximum-likelihood Brownian passage time, Weibull and exponential (Poisson) densities; the \
             lowest AIC fits best; CV below 1 is periodic, above 1 clustered. {}.",
            notes.join("; ")
        ),
    )
}

/// Stacked aftershock rate with the Omori–Utsu fit, or why there is none.
pub fn aftershocks(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (Some(af), Some(om)) = (gathered(d, AFTERSHOCKS_TABLE)?, gathered(d, OMORI)?) else {
        return Ok(Outcome::Skipped("no catalogue tables".into()));
    };
    let (af, om) = (Aftershocks::read(&af)?, Omori::read(&om)?);
    let Some(o) = pooled(&om.seed).next() else { return Ok(Outcome::Skipped("no Omori row".into())) };
    let rows: Vec<usize> = pooled(&af.seed).filter(|&i| af.count[i] > 0).collect();
    if rows.is_empty() {
        return Ok(Outcome::Skipped(format!(
            "no aftershocks: {}",
            om.reason[o].clone().unwrap_or_else(|| "no events after the main shocks".into())
        )));
    }
    let fit_text = match (om.p[o], om.p_se[o], om.c_s[o]) {
        (Some(p), Some(se), Some(c)) => format!("Omori–Utsu p = {p:.2} ± {se:.2}, c = {c:.2e} s"),
        _ => format!("no Omori–Utsu fit: {}", om.reason[o].clone().unwrap_or_default()),
    };
    let mut lines = vec![];
    let fit: Vec<(f64, f64)> = rows.iter().filter_map(|&i| Some((af.centre_s[i], af.omori_rate_per_s[i]?))).collect();
    if !fit.is_empty() {
        lines.push(Line { label: "Omori–Utsu fit".into(), points: fit, colour: BLACK, width: 2, alpha: 1.0 });
    }
    // Error bars as short vertical lines (± one Poisson standard error, clipped above zero).
    for &i in &rows {
        let (x, y, e) = (af.centre_s[i], af.rate_per_s[i], af.rate_error_per_s[i]);
        lines.push(Line {
            label: String::new(),
            points: vec![(x, (y - e).max(y * 0.05)), (x, y + e)],
            colour: colour(0),
            width: 1,
            alpha: 1.0,
        });
    }
    let panel = Panel {
        points: vec![Points {
            label: "rate per main shock".into(),
            points: rows.iter().map(|&i| (af.centre_s[i], af.rate_per_s[i])).collect(),
            colour: colour(0),
            size: 5,
        }],
        lines,
        ..Panel::loglog("time since the main shock (s, model scale)", "events per second per main shock")
    };
    drawn(
        path,
        &Sheet::new("Events after the main shocks (all seeds stacked)", 1, vec![panel]),
        "Aftershock decay".into(),
        format!(
            "Rate of events after each main shock until the next one (or the run's end), stacked over {} main shocks \
             ({} events), in logarithmic time bins with Poisson error bars. {fit_text}. A rate that does not fall \
             with time means the events between main shocks are precursors of the next one, not aftershocks.",
            om.main_shocks[o], om.aftershocks[o]
        ),
    )
}

/// Scaling relations beside the self-similar slopes.
pub fn scaling(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (Some(sc), Some(sim)) = (gathered(d, SCALING)?, gathered(d, SIMILARITY)?) else {
        return Ok(Outcome::Skipped("no catalogue tables".into()));
    };
    let sc = Scaling::read(&sc)?;
    let c = Columns::of(&sim, SIMILARITY.name);
    let m0: Vec<f64> = c.f64s(col::M0_CONSISTENT_DYNE_CM)?.iter().map(|m| m * 1e-7).collect();
    let area = c.f64s(col::PROTOTYPE_AREA_M2)?;
    let duration = c.f64s(col::PROTOTYPE_DURATION_S)?;
    let drop = c.f64s(col::STRESS_DROP_PA)?;
    let mw = c.f64s(col::MW_CONSISTENT)?;
    let relations = [
        ("moment_area", "rupture area (m², prototype)", "M0 (N·m)", &area, &m0, true),
        ("moment_duration", "duration (s, prototype)", "M0 (N·m)", &duration, &m0, true),
        ("stress_drop_magnitude", "Mw", "stress drop (Pa)", &mw, &drop, false),
    ];
    let mut panels = Vec::new();
    let mut notes = Vec::new();
    for (relation, x_desc, y_desc, x, y, loglog) in relations {
        let Some(r) = pooled(&sc.seed).find(|&i| sc.relation[i] == relation) else { continue };
        let pts: Vec<(f64, f64)> =
            x.iter().zip(y.iter()).map(|(&a, &b)| (a, b)).filter(|p| p.0.is_finite() && p.1 > 0.0).collect();
        if pts.is_empty() {
            // Nothing to draw: no empty panel.
            continue;
        }
        let (x_lo, x_hi) = pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.0), b.max(p.0)));
        let mut lines = Vec::new();
        let ends = [x_lo, x_hi];
        let x_of = |v: f64| if loglog { v.log10() } else { v };
        let note = match (sc.exponent[r], sc.intercept[r], sc.exponent_low[r], sc.exponent_high[r]) {
            (Some(s), Some(i), Some(lo), Some(hi)) if x_hi > x_lo => {
                lines.push(Line::new(
                    format!("fit: exponent {s:.2} [{lo:.2}, {hi:.2}]"),
                    ends.iter().map(|&v| (v, 10f64.powf(i + s * x_of(v)))).collect(),
                    1,
                ));
                // The self-similar slope through the centroid of the points.
                let n = pts.len() as f64;
                let (cx, cy) = pts.iter().fold((0.0, 0.0), |(a, b), p| (a + x_of(p.0) / n, b + p.1.log10() / n));
                let ss = sc.self_similar[r];
                lines.push(Line {
                    label: format!("self-similar exponent {ss}"),
                    points: ends.iter().map(|&v| (v, 10f64.powf(cy + ss * (x_of(v) - cx)))).collect(),
                    colour: BLACK,
                    width: 1,
                    alpha: 1.0,
                });
                format!("{relation}: {s:.2} [{lo:.2}, {hi:.2}] (self-similar {ss})")
            }
            _ => format!("{relation}: {}", sc.reason[r].clone().unwrap_or_else(|| "no fit".into())),
        };
        let fitted = sc.exponent[r].is_some();
        notes.push(note);
        // A third of the sheet's width: the panel says why there is no fit in a few words (the
        // caption has the whole reason).
        let why = sc.reason[r].as_deref().unwrap_or("");
        let short = match (why.contains("no spread"), relation) {
            (true, "moment_area") => "no fit: one area for every event".to_string(),
            (true, _) => "no fit: no spread".to_string(),
            (false, _) if why.contains("needed") => "no fit: too few events".to_string(),
            _ => "no fit".to_string(),
        };
        panels.push(Panel {
            name: if fitted { String::new() } else { short },
            points: vec![Points { label: String::new(), points: pts, colour: colour(0), size: 3 }],
            lines,
            x_scale: if loglog { Scale::Log } else { Scale::Linear },
            y_scale: Scale::Log,
            minor_grid: true,
            ..Panel::linear(x_desc, y_desc)
        });
    }
    if panels.is_empty() {
        return Ok(Outcome::Skipped("no events to scale".into()));
    }
    drawn(
        path,
        &Sheet::new("Scaling relations (all seeds)", panels.len(), panels),
        "Scaling relations".into(),
        format!(
            "Consistent seismic moment against prototype rupture area and duration, and stress drop against Mw, every \
             event of every seed, with the least-squares fit in log–log (95% interval of the exponent) and the \
             self-similar slope through the points' centroid. {}. With the paper's whole-contact area every event has \
             the same area, so stress drop against Mw has slope 1.5 by construction.",
            notes.join("; ")
        ),
    )
}

/// Every event of the first seed drawn: time against magnitude, main shocks marked.
pub fn overview(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (Some(ev), Some(sim)) = (&d.events, &d.similarity) else { return Ok(Outcome::Skipped("no events".into())) };
    let Some(&seed) = d.seeds.first() else { return Ok(Outcome::Skipped("no successful seed".into())) };
    let rows: Vec<usize> = (0..ev.len()).filter(|&i| ev.seed[i] == seed).collect();
    if rows.is_empty() {
        return Ok(Outcome::Skipped(format!("seed {seed} has no events")));
    }
    let (mut main, mut other) = (Vec::new(), Vec::new());
    for &i in &rows {
        let p = (ev.start_s[i], sim.mw_consistent[i]);
        if ev.kind[i].is_main() { main.push(p) } else { other.push(p) }
    }
    let floor =
        rows.iter().map(|&i| sim.mw_consistent[i]).filter(|m| m.is_finite()).fold(f64::INFINITY, f64::min) - 0.1;
    // A stem per event while they can be told apart (at most one per few pixels); beyond, the
    // points alone carry the catalogue.
    let mut lines = Vec::new();
    if rows.len() <= 300 {
        for p in main.iter().chain(&other) {
            lines.push(Line {
                label: String::new(),
                points: vec![(p.0, floor), *p],
                colour: colour(7),
                width: 1,
                alpha: 1.0,
            });
        }
    }
    let size = if rows.len() > 2000 { 2 } else { 4 };
    let panel = Panel {
        lines,
        points: vec![
            Points { label: format!("other events ({})", other.len()), points: other, colour: colour(0), size },
            Points { label: format!("main shocks ({})", main.len()), points: main, colour: colour(3), size: size + 1 },
        ],
        ..Panel::linear("time since the start of shearing (s, model scale)", "Mw (consistent moment)")
    };
    drawn(
        path,
        &Sheet::new(format!("Catalogue of seed {seed}"), 1, vec![panel]),
        "Catalogue overview".into(),
        format!(
            "Every event of seed {seed} ({} events) at its start time and moment magnitude, main shocks in red; a stem \
             per event up to 300 events, points alone beyond.",
            rows.len()
        ),
    )
}
