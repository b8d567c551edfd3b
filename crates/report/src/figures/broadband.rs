//! A broadband record and the two parts it is joined from (docs/model.md §17): one station's
//! fault-normal acceleration from the lattice (low-passed), from the stochastic synthesis
//! (high-passed) and joined, each at the station's site, with their Fourier amplitude spectra
//! around the crossover.

use std::path::Path;

use plotters::style::RGBColor;
use stickslip_seismo::spectra::fourier::{Window, fourier_amplitude};
use stickslip_store::io::read_parquet_if_present;
use stickslip_store::schema::{STATION_RECORDS, STATIONS};
use stickslip_store::tables::broadband::read_station_record;
use stickslip_store::tables::source::Stations;

use super::Outcome;
use super::common::drawn;
use crate::charts::{Line, Panel, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;

/// The station drawn: of the first seed drawn, the broadband record nearest 10 km from the
/// rupture, on the lowest site.
fn pick(s: &Stations, seeds: &[u64]) -> Option<usize> {
    let first = seeds.iter().copied().find(|sd| s.seed.contains(sd))?;
    (0..s.seed.len()).filter(|&i| s.seed[i] == first && s.vs30_m_s[i].is_some()).min_by(|&a, &b| {
        let key = |i: usize| ((s.r_rup_m[i] / 1e4).ln().abs(), s.vs30_m_s[i].unwrap_or(0.0));
        key(a).partial_cmp(&key(b)).unwrap_or(std::cmp::Ordering::Equal)
    })
}

/// One station's lattice, stochastic and joined record with their Fourier spectra.
pub(super) fn broadband_record(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(bb) = d.pipeline.analysis.broadband.as_ref() else {
        return Ok(Outcome::Skipped("no [broadband] section".into()));
    };
    let Some(df) = read_parquet_if_present(&d.folder.gathered(&STATIONS))? else {
        return Ok(Outcome::Skipped("no stations table".into()));
    };
    let s = Stations::read(&df)?;
    let seeds: Vec<u64> = if d.seeds.is_empty() { s.seed.clone() } else { d.seeds.clone() };
    let Some(i) = pick(&s, &seeds) else { return Ok(Outcome::Skipped("no broadband record".into())) };
    let (seed, name) = (s.seed[i], s.station[i].clone());
    let Some(records) = d.part(&STATION_RECORDS, seed)? else {
        return Ok(Outcome::Skipped(format!("seed {seed} has no station_records table")));
    };
    let Some(r) = read_station_record(&records, &name, "z")? else {
        return Ok(Outcome::Skipped(format!("no record of {name} in seed {seed}")));
    };
    let dt = r.time_s.get(1).copied().unwrap_or(0.01) - r.time_s[0];
    let parts = [
        ("lattice, low-passed", &r.deterministic_m_s2, 0usize),
        ("stochastic, high-passed", &r.stochastic_m_s2, 1),
        ("broadband (their sum)", &r.broadband_m_s2, 2),
    ];
    // The time axis up to where the broadband record has decayed to 1% of its peak.
    let peak = r.broadband_m_s2.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let last = r.broadband_m_s2.iter().rposition(|v| v.abs() > 0.01 * peak).unwrap_or(r.time_s.len() - 1);
    let t_end = (r.time_s[last] + 2.0).min(r.time_s[r.time_s.len() - 1]);
    let mut panels = Vec::new();
    for (label, a, c) in parts.iter() {
        let mut p = Panel::linear("time from the rupture's start (s)", "acceleration (m/s²)");
        p.legend = false;
        p.symmetric_y = true;
        p.x_range = Some((0.0, t_end));
        p.title = format!("{label}: peak {:.3} m/s²", a.iter().fold(0.0f64, |m, v| m.max(v.abs())));
        let mut l = Line::new("", r.time_s.iter().copied().zip(a.iter().copied()).collect(), *c);
        l.width = 1;
        p.lines.push(l);
        panels.push(p);
    }
    let mut planner = rustfft::FftPlanner::new();
    let mut fas = Panel::loglog("frequency (Hz)", "Fourier amplitude (m/s)");
    fas.title = "Fourier amplitude spectra".into();
    let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
    for (label, a, c) in parts {
        let f = fourier_amplitude(a, dt, Window::Rectangular, &mut planner);
        // Smoothed over a sixth of an octave, for reading.
        let pts: Vec<(f64, f64)> = smoothed(&f.frequency_hz, &f.amplitude, 0.05, 0.5 / dt);
        for p in &pts {
            lo = lo.min(p.1);
            hi = hi.max(p.1);
        }
        let mut l = Line::new(label, pts, c);
        l.width = if c == 2 { 2 } else { 1 };
        fas.lines.push(l);
    }
    let lo = lo.max(hi * 1e-6);
    let f = bb.crossover.hz;
    let mut l = Line::new("crossover f_m", vec![(f, lo), (f, hi)], 5);
    l.colour = RGBColor(90, 90, 90);
    l.width = 1;
    fas.lines.push(l);
    fas.y_range = Some((lo, hi * 1.5));
    fas.x_range = Some((0.05, 0.5 / dt));
    let mut sheet = Sheet::new(format!("Broadband record: seed {seed}, station {name}, fault-normal"), 2, panels);
    sheet.panels.push(fas);
    drawn(
        path,
        &sheet,
        "A broadband record and its two parts".into(),
        format!(
            "Seed {seed}, station {name} (R_rup {:.1} km, V_S30 {} m/s), fault-normal acceleration: the lattice's \
             record low-passed and the stochastic synthesis of the same rupture high-passed, each taken to the \
             station's site, and their sum (each on its own scale); bottom right, their Fourier amplitude spectra \
             (smoothed over 1/6 octave) crossing at f_m = {} Hz. Table station_records; docs/model.md §17.",
            s.r_rup_m[i] / 1e3,
            s.vs30_m_s[i].unwrap_or(f64::NAN),
            bb.crossover.hz
        ),
    )
}

/// `(f, a)` averaged over windows of a sixth of an octave, from `f_min` to `f_max`.
fn smoothed(f: &[f64], a: &[f64], f_min: f64, f_max: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let step = 2f64.powf(1.0 / 6.0);
    let mut lo = f_min;
    while lo < f_max {
        let hi = lo * step;
        let (sum, n) =
            f.iter().zip(a).filter(|(x, _)| **x >= lo && **x < hi).fold((0.0, 0), |(s, n), (_, v)| (s + v * v, n + 1));
        if n > 0 {
            out.push(((lo * hi).sqrt(), (sum / n as f64).sqrt()));
        }
        lo = hi;
    }
    out
}
