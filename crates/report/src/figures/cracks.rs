//! The figures of bars that crack (scenes with `[rupture]`, docs/model.md §11): where bars
//! softened and broke over the block, seen on three faces, at the end and around each main shock,
//! beside the loading curve; and the acoustic-emission events' magnitudes.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use stickslip_solver::Channel;
use stickslip_solver::geometry::Lattice;

use super::Outcome;
use super::common::{drawn, main_shocks_with_ends, seeds_text, series};
use crate::charts::{Panel, Points, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;
use crate::plot::{FONT, HEIGHT, TICK, WIDTH, colour, decimate, fmt_tick, padded_range, plot_err};

/// A white canvas of the standard size. The crack map draws its projections directly with
/// plotters (the chart layer has no projection panels); every element lies inside its panel's
/// padded range by construction.
fn canvas(path: &Path) -> DrawingArea<BitMapBackend<'_>, Shift> {
    let root = BitMapBackend::new(path, (WIDTH, HEIGHT)).into_drawing_area();
    let _ = root.fill(&WHITE);
    root
}

/// Main shocks drawn (the first ones), besides the end state.
const SHOCKS_DRAWN: usize = 3;
/// Above this many bars the intact lattice is drawn as the block's outline only.
const LATTICE_DRAWN_UP_TO: usize = 20_000;

const DAMAGED: RGBColor = RGBColor(230, 159, 0);
const BROKEN: RGBColor = RGBColor(170, 20, 20);
const INTACT: RGBColor = RGBColor(205, 205, 205);

/// A state of the block to draw: its label, the time it is taken at, and the window whose new
/// transitions are drawn bold.
struct Snapshot {
    label: String,
    at_s: f64,
    window: (f64, f64),
}

/// The three projections: (name, horizontal axis, vertical axis).
const FACES: [(&str, usize, usize); 3] = [("front x–z", 0, 2), ("top x–y", 0, 1), ("end y–z", 1, 2)];

/// Broken and damaged bars over the block (front, top and end views) at the end of the first
/// report seed's run and after each of its first main shocks, beside the loading curve.
pub(super) fn crack_map(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(cracks) = &d.cracks else { return Ok(Outcome::Skipped("no crack catalogue (no [rupture])".into())) };
    let Some(&seed) = d.seeds.first() else { return Ok(Outcome::Skipped("no successful seed".into())) };
    let rows: Vec<usize> = (0..cracks.len()).filter(|&i| cracks.seed[i] == seed).collect();
    if rows.is_empty() {
        return Ok(Outcome::Skipped(format!("no bar of seed {seed} passed its peak")));
    }
    let (curve, curve_label) = loading_curve(d, seed)?;
    let end = curve.last().map_or(0.0, |p| p.0).max(rows.iter().map(|&i| cracks.time_s[i]).fold(0.0, f64::max));
    let mut snaps: Vec<Snapshot> = main_shocks_with_ends(d, seed)?
        .into_iter()
        .take(SHOCKS_DRAWN)
        .map(|(label, start, stop)| Snapshot { label: format!("after {label}"), at_s: stop, window: (start, stop) })
        .collect();
    snaps.push(Snapshot { label: "end".into(), at_s: end, window: (f64::NAN, f64::NAN) });

    let name = path.display().to_string();
    let err = plot_err(&name);
    let root = canvas(path);
    let (left, right) = root.split_horizontally(430);
    let (top, bottom) = left.split_vertically(400);
    draw_curve(&top, &curve, &curve_label, &snaps, &name)?;
    draw_counts(&bottom, d, &rows, &name)?;
    let lattice = d.pipeline.scene.lattice();
    let (title, panels) = right.split_vertically(34);
    title
        .draw(&Text::new(
            format!("Seed {seed}: damaged (orange) and broken (red) bars; bold: new in the shock"),
            (8, 8),
            (FONT, TICK).into_font(),
        ))
        .map_err(|e| err(e.to_string()))?;
    let areas = panels.split_evenly((snaps.len(), 3));
    for (r, snap) in snaps.iter().enumerate() {
        for (c, face) in FACES.iter().enumerate() {
            draw_projection(&areas[r * 3 + c], &lattice, cracks, &rows, snap, *face, &name)?;
        }
    }
    root.present().map_err(|e| err(e.to_string()))?;
    let broken = rows.iter().filter(|&&i| cracks.broke[i]).count();
    let softened = rows.len() - broken;
    Ok(Outcome::Drawn {
        title: format!("Cracks of seed {seed}"),
        caption: format!(
            "Where the bars of seed {seed} cracked (bilinear law of docs/model.md §11): {softened} bars passed their peak and \
             {broken} broke. Each row is the block seen from the front (x–z), the top (x–y) and the end (y–z) — every bar \
             drawn as its projection, intact ones grey — after each of the first main shocks and at the end; the bars that \
             softened or broke during the shock are drawn bold. Left: {curve_label} with the instants drawn, and the \
             numbers of bars past their peak (orange) and broken (red) over time."
        ),
        headings: vec![format!("Seed {seed}: damaged (orange) and broken (red) bars; bold: new in the shock")],
        panels: vec![],
        dropped: vec![],
    })
}

/// The loading curve of one seed: τ(t) in kPa when the base carries shear, else the driver's
/// force per area of the block's x face (a prism pulled by its end).
fn loading_curve(d: &ReportInput, seed: u64) -> Result<(Vec<(f64, f64)>, String), ReportError> {
    if let Some((t, tau)) = series(d, seed, Channel::ShearStress.name())?
        && tau.iter().any(|v| *v != 0.0)
    {
        let kpa: Vec<f64> = tau.iter().map(|v| v / 1e3).collect();
        return Ok((decimate(&t, &kpa, 400), "τ (kPa), shear stress on the base".into()));
    }
    if let Some((t, f)) = series(d, seed, Channel::DriverForce.name())? {
        let e = d.pipeline.scene.lattice().extent();
        let kpa: Vec<f64> = f.iter().map(|v| v / (e[1] * e[2]) / 1e3).collect();
        return Ok((decimate(&t, &kpa, 400), "driver force / end area (kPa)".into()));
    }
    Ok((Vec::new(), "no loading curve recorded".into()))
}

fn draw_curve(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    curve: &[(f64, f64)],
    label: &str,
    snaps: &[Snapshot],
    name: &str,
) -> Result<(), ReportError> {
    let err = plot_err(name);
    let (x0, x1) = padded_range(curve.iter().map(|p| p.0).chain(snaps.iter().map(|s| s.at_s)));
    let (y0, y1) = padded_range(curve.iter().map(|p| p.1));
    let mut chart = ChartBuilder::on(area)
        .caption(label, (FONT, TICK + 2))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc("time since the start of shearing (s)")
        .label_style((FONT, TICK - 2))
        .axis_desc_style((FONT, TICK - 2))
        .x_labels(5)
        .x_label_formatter(&fmt_tick)
        .y_label_formatter(&fmt_tick)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| err(e.to_string()))?;
    chart
        .draw_series(LineSeries::new(curve.iter().copied(), colour(0).stroke_width(2)))
        .map_err(|e| err(e.to_string()))?;
    for s in snaps {
        chart
            .draw_series(DashedLineSeries::new(vec![(s.at_s, y0), (s.at_s, y1)], 6, 4, BROKEN.stroke_width(1)))
            .map_err(|e| err(e.to_string()))?;
        let text = s.label.trim_start_matches("after ").to_string();
        chart
            .draw_series(std::iter::once(Text::new(
                text,
                (s.at_s, y1 - 0.06 * (y1 - y0)),
                (FONT, TICK - 2).into_font().color(&BROKEN),
            )))
            .map_err(|e| err(e.to_string()))?;
    }
    Ok(())
}

/// Bars past their peak and broken, cumulative over time.
fn draw_counts(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    d: &ReportInput,
    rows: &[usize],
    name: &str,
) -> Result<(), ReportError> {
    let err = plot_err(name);
    let cracks = d.cracks.as_ref().expect("checked by the caller");
    let step = |broke: bool| -> Vec<(f64, f64)> {
        let mut t: Vec<f64> = rows.iter().filter(|&&i| cracks.broke[i] == broke).map(|&i| cracks.time_s[i]).collect();
        t.sort_by(f64::total_cmp);
        let mut out = Vec::with_capacity(2 * t.len());
        for (k, &x) in t.iter().enumerate() {
            out.push((x, k as f64));
            out.push((x, (k + 1) as f64));
        }
        out
    };
    let (soft, broke) = (step(false), step(true));
    let (x0, x1) = padded_range(soft.iter().chain(&broke).map(|p| p.0));
    let top = soft.len().max(broke.len()) as f64 / 2.0;
    let mut chart = ChartBuilder::on(area)
        .caption("bars past their peak / broken", (FONT, TICK))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, 0.0..(top * 1.08).max(1.0))
        .map_err(|e| err(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .label_style((FONT, TICK - 2))
        .axis_desc_style((FONT, TICK - 2))
        .x_labels(5)
        .y_labels(4)
        .x_label_formatter(&fmt_tick)
        .y_label_formatter(&fmt_tick)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| err(e.to_string()))?;
    for (pts, c) in [(soft, DAMAGED), (broke, BROKEN)] {
        chart.draw_series(LineSeries::new(pts, c.stroke_width(2))).map_err(|e| err(e.to_string()))?;
    }
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn draw_projection(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    lattice: &Lattice,
    cracks: &stickslip_store::tables::cracks::Cracks,
    rows: &[usize],
    snap: &Snapshot,
    (face, h, v): (&str, usize, usize),
    name: &str,
) -> Result<(), ReportError> {
    let err = plot_err(name);
    let e = lattice.extent();
    let pad = 0.04 * e[h].max(e[v]);
    // Keep the block's proportions: shrink the panel to the aspect of the face (caption 20 px).
    let (w, ht) = area.dim_in_pixel();
    let (w, ht) = (w.saturating_sub(12) as f64, ht.saturating_sub(32) as f64);
    let aspect = (e[h] + 2.0 * pad) / (e[v] + 2.0 * pad);
    let (pw, ph) = if w / ht > aspect { (ht * aspect, ht) } else { (w, w / aspect) };
    let area = area.clone().shrink((((w - pw) / 2.0) as u32, 0), ((pw + 12.0) as u32, (ph + 32.0) as u32));
    let mut chart = ChartBuilder::on(&area)
        .caption(format!("{}: {face}", snap.label), (FONT, TICK - 4))
        .margin(6)
        .build_cartesian_2d(-pad..e[h] + pad, -pad..e[v] + pad)
        .map_err(|e| err(e.to_string()))?;
    let seg = |bar: usize| {
        let b = &lattice.bar(bar);
        let (p, q) = (lattice.position(b.ends[0]), lattice.position(b.ends[1]));
        vec![(p[h], p[v]), (q[h], q[v])]
    };
    if lattice.bar_count() <= LATTICE_DRAWN_UP_TO {
        chart
            .draw_series((0..lattice.bar_count()).map(|b| PathElement::new(seg(b), INTACT.stroke_width(1))))
            .map_err(|e| err(e.to_string()))?;
    } else {
        let outline = vec![(0.0, 0.0), (e[h], 0.0), (e[h], e[v]), (0.0, e[v]), (0.0, 0.0)];
        chart
            .draw_series(std::iter::once(PathElement::new(outline, INTACT.stroke_width(1))))
            .map_err(|e| err(e.to_string()))?;
    }
    let (w0, w1) = snap.window;
    let fresh = |t: f64| t >= w0 && t <= w1;
    // Damaged first, broken over them; the shock's own transitions bold, on top.
    for (broke, c) in [(false, DAMAGED), (true, BROKEN)] {
        for bold in [false, true] {
            let width = if bold { 4 } else { 2 };
            let bars = rows.iter().filter(|&&i| {
                cracks.broke[i] == broke && cracks.time_s[i] <= snap.at_s && fresh(cracks.time_s[i]) == bold
            });
            chart
                .draw_series(bars.map(|&i| PathElement::new(seg(cracks.bar[i] as usize), c.stroke_width(width))))
                .map_err(|e| err(e.to_string()))?;
        }
    }
    Ok(())
}

/// The magnitude of every acoustic-emission event over time, one colour per seed drawn.
pub(super) fn emission(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(ae) = &d.emission else { return Ok(Outcome::Skipped("no acoustic emission (no [rupture])".into())) };
    let mut groups = Vec::new();
    let mut total = 0;
    for (k, &seed) in d.seeds.iter().enumerate() {
        let pts: Vec<(f64, f64)> =
            (0..ae.len()).filter(|&i| ae.seed[i] == seed).map(|i| (ae.start_s[i], ae.magnitude[i])).collect();
        total += pts.len();
        if !pts.is_empty() {
            groups.push(Points { label: format!("seed {seed}"), points: pts, colour: colour(k), size: 5 });
        }
    }
    if groups.is_empty() {
        return Ok(Outcome::Skipped("no bar broke".into()));
    }
    let (lo, hi) = (0..ae.len())
        .map(|i| ae.magnitude[i])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), m| (a.min(m), b.max(m)));
    let panel = Panel {
        points: groups,
        ..Panel::linear("time since the start of shearing (s)", "magnitude (log10 E = 1.5 M + 4.8, E in J)")
    };
    drawn(
        path,
        &Sheet::new("Acoustic emission: bar breaks close in space and time", 1, vec![panel]),
        "Acoustic emission".into(),
        format!(
            "Bar breaks of {} grouped into acoustic-emission events (breaks within the link distance and time of one \
             another, docs/model.md §11): {total} events, magnitudes {lo:.2} to {hi:.2} from the fracture energy the \
             broken bars dissipated, M = (log10 E − 4.8)/1.5 with E in joules (Gutenberg–Richter).",
            seeds_text(&d.seeds)
        ),
    )
}
