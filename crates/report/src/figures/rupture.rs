//! A fault scene's rupture (docs/model.md §15): the fault seen from the side, every node coloured
//! by its final slip, with the rupture front every second (contours of the rupture time); and the
//! stations' peak ground motion against their distance to the rupture.

use std::path::Path;

use plotters::style::{BLACK, RGBColor};

use stickslip_store::schema::{FAULT_NODES, STATIONS, col};
use stickslip_store::tables::source::{FaultNodes, Stations};

use super::Outcome;
use super::common::{drawn, seeds_text, slope_se};
use crate::charts::{Line, Panel, Points, Sheet};
use crate::contour::contour;
use crate::error::ReportError;
use crate::input::ReportInput;

/// Slip bins of the map: lower edges as fractions of the largest slip.
const SLIP_BINS: [f64; 5] = [0.01, 0.2, 0.4, 0.6, 0.8];

/// The fault of the first report seed: final slip of every node (binned colours) and the rupture
/// front at every whole second.
pub(super) fn rupture_time(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(fault) = &d.pipeline.scene.fault else {
        return Ok(Outcome::Skipped("not a fault scene ([fault])".into()));
    };
    let Some(&seed) = d.seeds.first() else { return Ok(Outcome::Skipped("no successful seed".into())) };
    let Some(df) = d.part(&FAULT_NODES, seed)? else {
        return Ok(Outcome::Skipped(format!("seed {seed} has no fault_nodes table")));
    };
    let f = FaultNodes::read(&df)?;
    let [x0, y0] = fault.origin_m;
    let slip: Vec<f64> = f.slip_m.iter().map(|s| s[0].hypot(s[1])).collect();
    let max = slip.iter().copied().fold(0.0, f64::max);
    if !(max > 0.0) {
        return Ok(Outcome::Skipped(format!("nothing slipped in seed {seed}")));
    }
    // The grid of the fault's nodes (x fastest).
    let mut xs: Vec<f64> = f.x_m.clone();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    let mut ys: Vec<f64> = f.y_m.clone();
    ys.sort_by(f64::total_cmp);
    ys.dedup();
    let (nx, ny) = (xs.len(), ys.len());
    if nx * ny != f.x_m.len() {
        return Ok(Outcome::Skipped("the fault's nodes are not a grid".into()));
    }
    let km = |v: f64| v / 1e3;
    let gx: Vec<f64> = xs.iter().map(|&x| km(x - x0)).collect();
    let gy: Vec<f64> = ys.iter().map(|&y| -km(y - y0)).collect();
    let at = |i: usize, j: usize| j * nx + i;
    let mut map = Panel::linear("along strike from the origin (km)", "−depth (km)");
    map.name = format!("slip (largest {max:.2} m) and the rupture front every second");
    map.compact = true;
    let mut bins: Vec<Vec<(f64, f64)>> = vec![Vec::new(); SLIP_BINS.len()];
    for k in 0..slip.len() {
        let b = SLIP_BINS.partition_point(|&lo| slip[k] >= lo * max);
        if b > 0 {
            bins[b - 1].push((km(f.x_m[k] - x0), -km(f.y_m[k] - y0)));
        }
    }
    for (b, pts) in bins.into_iter().enumerate() {
        let hi = SLIP_BINS.get(b + 1).map_or(max, |h| h * max);
        map.points.push(Points {
            label: format!("slip {:.2}–{:.2} m", SLIP_BINS[b] * max, hi),
            points: pts,
            colour: shade(b),
            size: 2,
        });
    }
    let latest = f.rupture_time_s.iter().copied().filter(|t| t.is_finite()).fold(0.0, f64::max);
    for s in 1..=(latest.floor() as usize) {
        let level = s as f64;
        let pts = contour(&gx, &gy, |i, j| f.rupture_time_s[at(i, j)], level);
        let label = if s == 1 { "rupture front at 1, 2, … s".to_string() } else { String::new() };
        map.lines.push(Line { label, points: pts, colour: RGBColor(0, 0, 0), width: 1, alpha: 1.0 });
    }
    let sheet = Sheet::new(format!("The rupture of seed {seed}"), 1, vec![map]);
    drawn(
        path,
        &sheet,
        format!("The rupture on the fault ({})", seeds_text(&[seed])),
        format!(
            "The fault seen from the side (along strike against depth, from [fault] origin_m = [{x0}, {y0}] m): every node \
             coloured by its final slip (nodes that slipped less than 1% of the largest not drawn), and the rupture front at \
             each whole second: the contours of each node's rupture time, when its slip rate first reached [events] \
             rupture_rate_m_s (docs/model.md §15)."
        ),
    )
}

/// Colours of the slip bins, light to dark.
fn shade(b: usize) -> RGBColor {
    const C: [RGBColor; 5] = [
        RGBColor(255, 237, 160),
        RGBColor(254, 178, 76),
        RGBColor(253, 141, 60),
        RGBColor(227, 26, 28),
        RGBColor(128, 0, 38),
    ];
    C[b.min(C.len() - 1)]
}

/// Peak horizontal ground motion of every station against its rupture distance, one point per
/// station and seed (fault scenes with `[[stations]]`).
pub(super) fn ground_motion(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    if d.pipeline.scene.fault.is_none() {
        return Ok(Outcome::Skipped("not a fault scene ([fault])".into()));
    }
    let Some(df) = stickslip_store::io::read_parquet_if_present(&d.folder.gathered(&STATIONS))? else {
        return Ok(Outcome::Skipped("no stations table ([[stations]])".into()));
    };
    let s = Stations::read(&df)?;
    if s.seed.is_empty() {
        return Ok(Outcome::Skipped("no station recorded".into()));
    }
    let km: Vec<f64> = s.r_rup_m.iter().map(|r| (r / 1e3).max(0.1)).collect();
    let mut pga = Panel::loglog("rupture distance R_rup (km)", "PGA, horizontal (m/s²)");
    pga.points.push(Points {
        label: "the lattice's record, unfiltered".into(),
        points: km.iter().copied().zip(s.pga_m_s2.iter().copied()).filter(|p| p.1 > 0.0).collect(),
        colour: crate::plot::colour(0),
        size: 4,
    });
    // Broadband records (docs/model.md §17): their RotD50 PGA, at each record's site.
    let broadband: Vec<(f64, f64)> = (0..km.len())
        .filter(|&i| s.vs30_m_s[i].is_some())
        .map(|i| (km[i], s.pga_rotd50_m_s2[i]))
        .filter(|p| p.1 > 0.0)
        .collect();
    if !broadband.is_empty() {
        pga.points.push(Points {
            label: "broadband records, RotD50".into(),
            points: broadband,
            colour: crate::plot::colour(2),
            size: 4,
        });
    }
    let f_max = d.pipeline.scene.usable_band(stickslip_analysis::motions::DEPARTURE).map_or(f64::NAN, |b| b.f_max_hz);
    pga.title = format!("the lattice resolves up to {f_max:.2} Hz");
    let mut pgv = Panel::loglog("rupture distance R_rup (km)", "PGV, horizontal (m/s)");
    pgv.points.push(Points {
        label: "stations".into(),
        points: km.iter().copied().zip(s.pgv_m_s.iter().copied()).filter(|p| p.1 > 0.0).collect(),
        colour: crate::plot::colour(1),
        size: 4,
    });
    // The stations' fits of the attenuation_fit table (log10 y = a + b·log10 R_rup in metres).
    let mut fit_text = Vec::new();
    if let Some(fit) = &d.attenuation_fit {
        let (lo, hi) = km
            .iter()
            .filter(|x| x.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
        for (panel, measure, name) in [(&mut pga, col::PGA_M_S2, "PGA"), (&mut pgv, col::PGV_M_S, "PGV")] {
            let Some(i) = (0..fit.group.len()).find(|&i| fit.group[i] == "stations" && fit.measure[i] == measure)
            else {
                continue;
            };
            let (a, b, r2, n) = (fit.intercept[i], fit.slope[i], fit.r2[i], fit.points[i]);
            let se = slope_se(b, r2, n as f64);
            panel.lines.push(Line {
                label: format!("fit: {name} ∝ R_rup^({b:.2} ± {se:.2})"),
                points: [lo, hi].iter().map(|&x| (x, 10f64.powf(a + b * (1e3 * x).log10()))).collect(),
                colour: BLACK,
                width: 2,
                alpha: 1.0,
            });
            fit_text.push(format!("{name} ∝ R_rup^({b:.2} ± {se:.2}) (one standard error, r² = {r2:.2}, {n} points)"));
        }
    }
    let fits = if fit_text.is_empty() {
        String::from("no fit (fewer than 3 stations with a positive peak)")
    } else {
        format!(
            "least-squares lines of log10 peak on log10 R_rup over every station and seed (table attenuation_fit, group stations): {}",
            fit_text.join("; ")
        )
    };
    let mut seeds: Vec<u64> = s.seed.clone();
    seeds.sort();
    seeds.dedup();
    let sheet = Sheet::new("Peak ground motion against distance", 2, vec![pga, pgv]);
    drawn(
        path,
        &sheet,
        format!("Peak ground motion against distance ({})", seeds_text(&seeds)),
        format!(
            "Every station of every seed: the largest horizontal (x and z) acceleration and velocity of the lattice's \
             record over the run against the station's rupture distance (to the nearest node whose slip rate reached \
             [events] rupture_rate_m_s; docs/model.md §15); {fits}. The lattice resolves waves up to {f_max:.2} Hz: its \
             PGA misses what is carried above (PGA lives at 1–10 Hz) and is not a recorded motion's PGA{}.",
            if s.vs30_m_s.iter().any(Option::is_some) {
                "; the broadband records' RotD50 PGA (the lattice below 1 Hz joined to a stochastic synthesis of the \
                 same rupture, at each record's V_S30; docs/model.md §17) is drawn beside it"
            } else {
                " (a [broadband] section gives records with a PGA, docs/model.md §17)"
            }
        ),
    )
}
