//! The fault's figures (docs/model.md §12–13): the friction map of the base, and each main shock
//! in space and time (slip rate along x against time, with the nodes' rupture times).

use std::path::Path;

use plotters::style::{BLACK, RGBColor};

use stickslip_store::schema::FAULT;
use stickslip_store::tables::series::Fault;

use super::Outcome;
use super::common::{drawn, seeds_text};
use crate::charts::{Panel, Points, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;
use crate::plot::colour;

/// Main shocks drawn in the space–time figure.
const SHOCKS_DRAWN: usize = 4;

/// The friction map: the base seen from above with every contact node coloured by its region,
/// and μs, μd along x.
pub(super) fn friction_map(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let scene = &d.pipeline.scene;
    let Some(map) = &scene.friction.map else {
        return Ok(Outcome::Skipped("no friction map ([[friction.patches]] or [friction.grid])".into()));
    };
    let lattice = scene.lattice();
    let ids = lattice.contact_nodes();
    let pos: Vec<[f64; 3]> = ids.iter().map(|&id| lattice.position(id)).collect();
    let mut plan = Panel::linear("x (m)", "y (m)");
    plan.title = "Regions of the base (seen from above)".into();
    let groups: Vec<(String, Option<u16>)> = std::iter::once(("background".to_string(), None))
        .chain(map.regions.iter().enumerate().map(|(i, r)| {
            // "barrier (barrier)" says it twice: the kind only when the name does not.
            let kind = r.kind.name();
            let name = if r.name.contains(kind) { r.name.clone() } else { format!("{} ({kind})", r.name) };
            (name, Some(i as u16))
        }))
        .collect();
    for (k, (name, region)) in groups.iter().enumerate() {
        let nodes: Vec<usize> = (0..ids.len()).filter(|&c| map.region[c] == *region).collect();
        let Some(&c0) = nodes.first() else { continue };
        let f = map.nodes[c0];
        plan.points.push(Points {
            label: format!(
                "{name}: μs {}, μd {}",
                crate::plot::fmt_tick(&f.static_coefficient()),
                crate::plot::fmt_tick(&f.residual_coefficient())
            ),
            points: nodes.iter().map(|&c| (pos[c][0], pos[c][1])).collect(),
            colour: region_colour(k),
            size: 5,
        });
    }
    // The base fills the panel (half a module around it, so no node sits on an axis line); the
    // legend goes where there is room, or above the axes.
    let e = lattice.extent();
    let pad = 0.5 * lattice.lc();
    plan.x_range = Some((-pad, e[0] + pad));
    plan.y_range = Some((-pad, e[1] + pad));
    let mut along = Panel::linear("x (m)", "friction coefficient");
    along.title = "μs and μd of the nodes along x (before the seed's Weibull factor)".into();
    let row: Vec<usize> = (0..ids.len()).filter(|&c| pos[c][1] == 0.0).collect();
    for (k, (label, get)) in [("μs", 0usize), ("μd", 1usize)].iter().enumerate() {
        let v = |c: usize| {
            let n = &map.nodes[c];
            if *get == 0 { n.static_coefficient() } else { n.residual_coefficient() }
        };
        along.points.push(Points {
            label: label.to_string(),
            points: row.iter().map(|&c| (pos[c][0], v(c))).collect(),
            colour: colour(k),
            size: 4,
        });
    }
    let sheet = Sheet::new("", 1, vec![plan, along]);
    drawn(
        path,
        &sheet,
        "Friction map".into(),
        format!(
            "The base's friction map as `stickslip check` prints it: every contact node drawn where it lies on the base, \
             coloured by its region (barriers: μs above the background's; weak: at most it), and each node's μs and μd \
             along x on the line y = 0. Every seed multiplies both by its Weibull factor of μ (CV {}).",
            scene.friction.mu_cv
        ),
    )
}

fn region_colour(k: usize) -> RGBColor {
    if k == 0 { RGBColor(170, 170, 170) } else { colour(k - 1) }
}

/// Slip-rate bins of the space–time figure: lower edges (m/s), the top one open.
const RATE_BINS: [f64; 5] = [1e-3, 1e-2, 3e-2, 1e-1, 3e-1];

/// Each of the first main shocks of the first report seed in space and time: every contact node
/// on y = 0 at its x against time from the hypocentre's rupture time, coloured by its slip rate,
/// with each node's rupture time.
pub(super) fn space_time(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(r) = &d.ruptures else { return Ok(Outcome::Skipped("no rupture fronts (record.fault)".into())) };
    let Some(&seed) = d.seeds.first() else { return Ok(Outcome::Skipped("no successful seed".into())) };
    let Some(df) = d.part(&FAULT, seed)? else {
        return Ok(Outcome::Skipped(format!("seed {seed} has no fault table (record.fault)")));
    };
    let fault = Fault::read(&df)?;
    let shocks: Vec<usize> =
        (0..r.len()).filter(|&i| r.seed[i] == seed && r.kind[i] == "main").take(SHOCKS_DRAWN).collect();
    if shocks.is_empty() {
        return Ok(Outcome::Skipped(format!("no main shock of seed {seed} with a front")));
    }
    let y0 = fault.y_m.iter().copied().fold(f64::INFINITY, f64::min);
    let mut panels = Vec::new();
    for &i in &shocks {
        let t0 = r.onset_s[i];
        let (from, to) = (t0 - 1e-3, t0 + 8e-3);
        let mut bins: Vec<Vec<(f64, f64)>> = vec![Vec::new(); RATE_BINS.len() + 1];
        for k in 0..fault.time_s.len() {
            let t = fault.time_s[k];
            if fault.y_m[k] != y0 || t < from || t > to {
                continue;
            }
            let v = fault.slip_rate_m_s[k].abs();
            let b = RATE_BINS.partition_point(|&lo| v >= lo);
            bins[b].push(((t - t0) * 1e3, fault.x_m[k]));
        }
        let mut p = Panel::linear("time from the hypocentre's rupture time (ms)", "x (m)");
        p.x_range = Some(((from - t0) * 1e3, (to - t0) * 1e3));
        p.name = format!("{} ({}, {})", r.label[i], speed_text(r.rupture_speed_m_s[i], r.s_speed_m_s[i]), r.regime[i]);
        p.compact = true;
        p.legend = panels.is_empty();
        for (b, pts) in bins.into_iter().enumerate().skip(1) {
            let label = match RATE_BINS.get(b) {
                Some(hi) => format!("{:.0e}–{:.0e} m/s", RATE_BINS[b - 1], hi),
                None => format!("≥ {:.0e} m/s", RATE_BINS[b - 1]),
            };
            p.points.push(Points { label, points: pts, colour: heat(b), size: 2 });
        }
        if let Some(o) = &d.rupture_onsets {
            let front: Vec<(f64, f64)> = (0..o.seed.len())
                .filter(|&k| o.seed[k] == seed && o.event[k] == r.event[i])
                .map(|k| ((o.onset_s[k] - t0) * 1e3, o.x_m[k]))
                .collect();
            p.points.push(Points { label: "rupture time".into(), points: front, colour: BLACK, size: 3 });
        }
        let lx = d.pipeline.scene.lattice().extent()[0];
        p.y_range = Some((-0.05 * lx, 1.05 * lx));
        panels.push(p);
    }
    let n = panels.len();
    let sheet = Sheet::new(format!("Main shocks of seed {seed} along the fault"), n.min(2), panels)
        .with_height(if n > 2 { 900 } else { 600 });
    drawn(
        path,
        &sheet,
        format!("Main shocks in space and time ({})", seeds_text(&[seed])),
        format!(
            "Each of the first main shocks of seed {seed}: every contact node on the line y = 0, at its x, from 1 ms before \
             to 8 ms after the hypocentre's rupture time, coloured by its slip rate (slower than 1 mm/s not drawn); black \
             dots: each node's rupture time (its slip rate first reaching [events] rupture_rate_m_s). The panel names give \
             the rupture speed (Theil–Sen fit of rupture time against distance from the hypocentre) over the lattice's S \
             speed, and its regime against the P, S and Rayleigh speeds (docs/model.md §13)."
        ),
    )
}

fn speed_text(v: Option<f64>, c_s: f64) -> String {
    match v {
        Some(v) if v.is_infinite() => "all at once".into(),
        Some(v) => format!("{:.0} m/s = {:.2} c_s", v, v / c_s),
        None => "speed not measured".into(),
    }
}

/// Colours of the slip-rate bins, light to dark.
fn heat(b: usize) -> RGBColor {
    const C: [RGBColor; 6] = [
        RGBColor(255, 255, 255),
        RGBColor(254, 217, 118),
        RGBColor(253, 141, 60),
        RGBColor(227, 26, 28),
        RGBColor(177, 0, 38),
        RGBColor(90, 0, 60),
    ];
    C[b.min(C.len() - 1)]
}
