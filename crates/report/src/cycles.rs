//! The figure of a `[cycles]` run (docs/model.md §20), from its SEAS files: the slip along depth
//! over the cycles (every 5 years between events in blue, every 5 s inside them in red: a row of
//! `devol.dat` whose largest slip rate exceeds 1 mm/s, the benchmarks' usual picture) and the
//! fault's largest slip rate against time.
//!
//! Written to `<out>/figures/cycles.png`.

use std::path::{Path, PathBuf};

use plotters::style::RGBColor;

use crate::charts::{self, Line, Panel, Scale, Sheet};
use crate::error::ReportError;
use crate::plot::{decimate, register_fonts};

/// Seconds in the SEAS year.
const YEAR_S: f64 = 365.25 * 86400.0;

/// The numeric rows of a SEAS text file (lines starting with `#` or a letter skipped).
fn rows(path: &Path) -> Result<Vec<Vec<f64>>, ReportError> {
    let text = std::fs::read_to_string(path).map_err(|source| ReportError::Io { path: path.to_path_buf(), source })?;
    Ok(text
        .lines()
        .filter(|l| l.starts_with(|c: char| c.is_ascii_digit() || c == '-'))
        .map(|l| l.split_whitespace().filter_map(|x| x.parse().ok()).collect())
        .collect())
}

/// What [`draw_cycles`] drew.
#[derive(Clone, Debug, PartialEq)]
pub struct CyclesFigure {
    /// The file.
    pub path: PathBuf,
    /// Profiles drawn between events and inside them.
    pub profiles: [usize; 2],
    /// The range of the slip drawn (m).
    pub slip_m: [f64; 2],
    /// The depths of the profiles (km).
    pub depths_km: Vec<f64>,
}

/// Draws `figures/cycles.png` of the cycle run written under `out`.
pub fn draw_cycles(out: &Path) -> Result<CyclesFigure, ReportError> {
    register_fonts();
    let seas = out.join("seas");
    let devol = rows(&seas.join("devol.dat"))?;
    let global = rows(&seas.join("global.dat"))?;
    let Some((depths, profiles)) = devol.split_first() else {
        return Err(ReportError::Plot { figure: "cycles.png".into(), what: "seas/devol.dat has no rows".into() });
    };
    // The first row is `0 0` and the depths; a profile's row is t, log10 of the largest slip
    // rate and the slip at each depth.
    let depth_km: Vec<f64> = depths.iter().skip(2).map(|d| d / 1e3).collect();
    let mut slip = Panel {
        title: "Slip along depth: every 5 years between events (blue), every 5 s inside them (red)".into(),
        x_desc: "slip (m)".into(),
        y_desc: "depth (km, negative down)".into(),
        legend: false,
        ..Panel::default()
    };
    let mut last_seismic = f64::NEG_INFINITY;
    let (mut profiles_drawn, mut slip_range) = ([0usize; 2], [f64::INFINITY, f64::NEG_INFINITY]);
    for p in profiles {
        let (t, seismic) = (p[0], p[1] > -3.0);
        if seismic && t - last_seismic < 5.0 {
            continue;
        }
        if seismic {
            last_seismic = t;
        }
        let points: Vec<(f64, f64)> = p.iter().skip(2).zip(&depth_km).map(|(s, d)| (*s, -d)).collect();
        profiles_drawn[usize::from(seismic)] += 1;
        for &(s, _) in &points {
            slip_range = [slip_range[0].min(s), slip_range[1].max(s)];
        }
        let mut line = Line::new("", points, 0);
        if seismic {
            line.colour = RGBColor(200, 30, 30);
        }
        line.width = 1;
        line.alpha = if seismic { 0.6 } else { 0.8 };
        slip.lines.push(line);
    }
    let t: Vec<f64> = global.iter().map(|r| r[0] / YEAR_S).collect();
    let v: Vec<f64> = global.iter().map(|r| 10f64.powf(r[1])).collect();
    let rate = Panel {
        title: "The fault's largest slip rate".into(),
        x_desc: "time (years)".into(),
        y_desc: "slip rate (m/s)".into(),
        y_scale: Scale::Log,
        minor_grid: true,
        legend: false,
        lines: vec![Line::new("", decimate(&t, &v, 4000), 0)],
        ..Panel::default()
    };
    let path = out.join("figures").join("cycles.png");
    let figures = out.join("figures");
    std::fs::create_dir_all(&figures).map_err(|source| ReportError::Io { path: figures.clone(), source })?;
    charts::draw(&path, &Sheet::new("Earthquake cycles", 1, vec![slip, rate]).with_height(1400))?;
    Ok(CyclesFigure { path, profiles: profiles_drawn, slip_m: slip_range, depths_km: depth_km })
}
