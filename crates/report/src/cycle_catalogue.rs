//! The figure of a cycle catalogue (docs/model.md §20.6), from its tables: the pooled
//! magnitude–frequency distribution with its Gutenberg–Richter fit, every event's magnitude
//! against time (a colour per seed), and the rate of events after the main shocks, stacked over
//! them and the seeds.
//!
//! Written to `<out>/figures/cycle_catalogue.png`.

use std::path::{Path, PathBuf};

use plotters::style::BLACK;
use stickslip_store::Folder;
use stickslip_store::frame::Columns;
use stickslip_store::io::read_parquet_if_present;
use stickslip_store::schema::{AFTERSHOCKS_TABLE, B_VALUES, MAGNITUDE_FREQUENCY, TableSpec};
use stickslip_store::tables::catalogue::{Aftershocks, BValues, MagnitudeFrequency};

use crate::charts::{self, Line, Panel, Points, Scale, Sheet};
use crate::error::ReportError;
use crate::plot::{colour, register_fonts};

/// Seconds in the SEAS year.
const YEAR_S: f64 = 365.25 * 86400.0;

fn table(out: &Path, t: TableSpec) -> Result<polars::prelude::DataFrame, ReportError> {
    let path = Folder::new(out).gathered(&t);
    read_parquet_if_present(&path)?.ok_or_else(|| ReportError::Plot {
        figure: "cycle_catalogue.png".into(),
        what: format!("{} is missing", path.display()),
    })
}

/// What [`draw_cycle_catalogue`] drew.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleCatalogueFigure {
    /// The file.
    pub path: PathBuf,
    /// Events drawn.
    pub events: usize,
    /// The pooled fit as written on the figure.
    pub fit: String,
}

/// Draws `figures/cycle_catalogue.png` of the cycle catalogue written under `out`, whose
/// magnitudes are the column `quantity` of its catalogue tables.
pub fn draw_cycle_catalogue(out: &Path, quantity: &str) -> Result<CycleCatalogueFigure, ReportError> {
    register_fonts();
    let mf = MagnitudeFrequency::read(&table(out, MAGNITUDE_FREQUENCY)?)?;
    let bv = BValues::read(&table(out, B_VALUES)?)?;
    let af = Aftershocks::read(&table(out, AFTERSHOCKS_TABLE)?)?;
    let events = read_parquet_if_present(&out.join("tables").join("cycle_events.parquet"))?.ok_or_else(|| {
        ReportError::Plot {
            figure: "cycle_catalogue.png".into(),
            what: "tables/cycle_events.parquet is missing".into(),
        }
    })?;
    let c = Columns::of(&events, "cycle_events");
    let (seed, onset, magnitude) = (c.u64s("seed")?, c.f64s("onset_years")?, c.f64s("magnitude")?);

    let rows: Vec<usize> = (0..mf.seed.len()).filter(|&i| mf.seed[i].is_none() && mf.quantity[i] == quantity).collect();
    let fit_points: Vec<(f64, f64)> =
        rows.iter().filter_map(|&i| Some((mf.centre[i], mf.fit_cumulative[i]?))).collect();
    let fit = match (0..bv.seed.len()).find(|&i| bv.seed[i].is_none() && bv.quantity[i] == quantity) {
        Some(i) => match (bv.b[i], bv.b_sigma[i], bv.mc[i], bv.events_above_mc[i]) {
            (Some(b), Some(s), Some(mc), Some(n)) => format!("b = {b:.2} ± {s:.2} above Mc = {mc:.1} ({n} events)"),
            _ => format!("no b-value: {}", bv.reason[i].clone().unwrap_or_default()),
        },
        None => "no b-value".into(),
    };
    let mut lines = Vec::new();
    if !fit_points.is_empty() {
        lines.push(Line {
            label: "Gutenberg–Richter fit".into(),
            points: fit_points,
            colour: BLACK,
            width: 2,
            alpha: 1.0,
        });
    }
    let frequency = Panel {
        title: format!("Magnitude–frequency over the seeds: {fit}"),
        y_scale: Scale::Log,
        minor_grid: true,
        points: vec![
            Points {
                label: "N(≥ M)".into(),
                points: rows.iter().map(|&i| (mf.centre[i], mf.cumulative[i])).filter(|p| p.1 > 0.0).collect(),
                colour: colour(0),
                size: 4,
            },
            Points {
                label: "events per bin".into(),
                points: rows.iter().map(|&i| (mf.centre[i], mf.incremental[i])).filter(|p| p.1 > 0.0).collect(),
                colour: colour(1),
                size: 3,
            },
        ],
        lines,
        ..Panel::linear("magnitude (Mw, rupture as long along strike as down dip)", "events")
    };

    let mut seeds: Vec<u64> = seed.clone();
    seeds.dedup();
    let timeline = Panel {
        title: "Every event: magnitude against time, a colour per seed".into(),
        points: seeds
            .iter()
            .enumerate()
            .map(|(k, &s)| Points {
                label: format!("seed {s}"),
                points: (0..seed.len()).filter(|&i| seed[i] == s).map(|i| (onset[i], magnitude[i])).collect(),
                colour: colour(k),
                size: 3,
            })
            .collect(),
        ..Panel::linear("time (years)", "magnitude")
    };

    let pooled: Vec<usize> = (0..af.seed.len()).filter(|&i| af.seed[i].is_none() && af.count[i] > 0).collect();
    let aftershocks = Panel {
        title: "Events after the main shocks (within 1 of each seed's largest magnitude), stacked".into(),
        x_scale: Scale::Log,
        y_scale: Scale::Log,
        minor_grid: true,
        points: vec![Points {
            label: "rate per main shock".into(),
            points: pooled.iter().map(|&i| (af.centre_s[i] / YEAR_S, af.rate_per_s[i] * YEAR_S)).collect(),
            colour: colour(2),
            size: 4,
        }],
        ..Panel::linear("time since the main shock (years)", "events per year per main shock")
    };
    let figures = out.join("figures");
    std::fs::create_dir_all(&figures).map_err(|source| ReportError::Io { path: figures.clone(), source })?;
    let path = figures.join("cycle_catalogue.png");
    charts::draw(
        &path,
        &Sheet::new("A catalogue of earthquake cycles", 1, vec![frequency, timeline, aftershocks]).with_height(1800),
    )?;
    Ok(CycleCatalogueFigure { path, events: seed.len(), fit })
}
