//! The accelerogram figures: each control node's acceleration around S2 and over the whole run, one
//! row per seed, and the processed main-shock records (acceleration, velocity, displacement) of
//! one node.

use std::path::Path;

use stickslip_solver::scene::Kinematic;
use stickslip_store::schema::{ACCELEROGRAMS, CONTROL};
use stickslip_store::tables::records::Accelerograms;
use stickslip_store::tables::series::{Trace, read_control};

use super::Outcome;
use super::common::{NodeChannel, accelerogram_nodes, drawn, main_shocks, nodes_short, nodes_text, paper_fig, rank_of};
use crate::charts::{Line, Panel, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;
use crate::plot::{HEIGHT, WIDTH, decimate, padded_range};

/// (time, acceleration) of a control channel for one seed.
fn control(d: &ReportInput, seed: u64, node: &NodeChannel) -> Result<Option<Trace>, ReportError> {
    let Some(df) = d.part(&CONTROL, seed)? else { return Ok(None) };
    Ok(read_control(&df, node.ldem, node.component, Kinematic::Acceleration)?)
}

/// Accelerogram panels, one row per seed and one column per node, sharing the time axis: the
/// paper's Figs. 6 and 7.
fn accelerogram_sheet(title: String, x_desc: &str, rows: Vec<Vec<Panel>>, columns: usize) -> Sheet {
    let n_rows = rows.len();
    let all: Vec<(f64, f64)> =
        rows.iter().flatten().flat_map(|p| p.lines.iter().flat_map(|l| l.points.iter().copied())).collect();
    let x_range = padded_range(all.iter().map(|p| p.0));
    let mut panels = Vec::new();
    for (r, row) in rows.into_iter().enumerate() {
        let last = r + 1 == n_rows;
        for mut p in row {
            p.x_range = Some(x_range);
            p.x_tick_labels = last;
            p.x_desc = if last { x_desc.to_string() } else { String::new() };
            panels.push(p);
        }
    }
    let height = if n_rows <= 4 { HEIGHT } else { 60 + 150 * n_rows as u32 };
    Sheet::new(title, columns, panels).with_height(height)
}

fn accelerogram_panel(name: String, points: Vec<(f64, f64)>, k: usize) -> Panel {
    let mut line = Line::new("", points, k);
    line.width = 1;
    Panel {
        y_desc: "a (m/s²)".into(),
        lines: vec![line],
        name,
        symmetric_y: true,
        y_tick_count: Some(3),
        legend: false,
        compact: true,
        ..Panel::default()
    }
}

pub(super) fn acceleration_s2(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (nodes, total) = accelerogram_nodes(d);
    if nodes.is_empty() {
        return Ok(Outcome::Skipped("no control node records acceleration".into()));
    }
    let mut rows = Vec::new();
    for (k, &seed) in d.seeds.iter().enumerate() {
        let Some(&(_, s2)) = main_shocks(d, seed)?.iter().find(|(l, _)| l == "S2") else { continue };
        let (from, to) = (s2 - 0.005, s2 + 0.025);
        let mut row = Vec::new();
        for node in &nodes {
            let pts: Vec<(f64, f64)> = match control(d, seed, node)? {
                Some((t, a)) => t
                    .iter()
                    .zip(&a)
                    .filter(|(x, _)| **x >= from && **x <= to)
                    .map(|(x, y)| ((x - s2) * 1e3, *y))
                    .collect(),
                None => vec![],
            };
            row.push(accelerogram_panel(format!("seed {seed} · {}", node.name()), pts, k));
        }
        if row.iter().any(|p| !p.lines[0].points.is_empty()) {
            rows.push(row);
        }
    }
    if rows.is_empty() {
        return Ok(Outcome::Skipped("no seed has a main shock S2".into()));
    }
    let comps: Vec<&str> = nodes.iter().map(|n| n.component.name()).collect();
    let sheet = accelerogram_sheet(
        format!("Acceleration of {} ({}) around S2{}", nodes_short(&nodes), comps[0], paper_fig(d, 6)),
        "time from the start of S2 (ms)",
        rows,
        nodes.len(),
    );
    drawn(
        path,
        &sheet,
        format!("{} acceleration around S2", capitalised(&nodes_short(&nodes))),
        format!(
            "Artificial accelerograms from 5 ms before to 25 ms after the start of each seed's main shock S2, one row \
             per seed, {} (model scale; at prototype scale times ×λ and accelerations ÷λ). Each seed gives a different \
             record.",
            nodes_text(&nodes, total)
        ),
    )
}

fn capitalised(s: &str) -> String {
    let mut c = s.chars();
    c.next().map(|f| f.to_uppercase().chain(c).collect()).unwrap_or_default()
}

pub(super) fn acceleration_run(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (nodes, total) = accelerogram_nodes(d);
    if nodes.is_empty() {
        return Ok(Outcome::Skipped("no control node records acceleration".into()));
    }
    let pixels = (WIDTH as usize / nodes.len()).max(100);
    let mut rows = Vec::new();
    for (k, &seed) in d.seeds.iter().enumerate() {
        let mut row = Vec::new();
        for node in &nodes {
            let pts = control(d, seed, node)?.map(|(t, a)| decimate(&t, &a, pixels)).unwrap_or_default();
            row.push(accelerogram_panel(format!("seed {seed} · {}", node.name()), pts, k));
        }
        if row.iter().any(|p| !p.lines[0].points.is_empty()) {
            rows.push(row);
        }
    }
    if rows.is_empty() {
        return Ok(Outcome::Skipped("no accelerogram recorded".into()));
    }
    // A fault's waves reach the stations after a quiet lead: the panels span the motion, from just
    // before its first arrival to the end of the run, and the caption says when the run ends
    // while the ground still shakes.
    let span = if d.pipeline.scene.is_fault() { motion_span(&mut rows) } else { None };
    let comps: Vec<&str> = nodes.iter().map(|n| n.component.name()).collect();
    let title = match span {
        Some(_) => format!("Acceleration of {} ({})", nodes_short(&nodes), comps[0]),
        None => format!("Acceleration of {} ({}) over the whole run{}", nodes_short(&nodes), comps[0], paper_fig(d, 7)),
    };
    let sheet = accelerogram_sheet(title, "time since the start of shearing (s)", rows, nodes.len());
    let caption = match span {
        Some(MotionSpan { from_s, end_s, still_shaking }) => format!(
            "Raw acceleration of the run, one row per seed, {} (the fault's own scale; unfiltered, so it holds the \
             lattice's content above the usable band too: the stations table gives each record's band), from {:.1} s, \
             just before the first arrival, to the end of the run at {:.1} s.{}",
            nodes_text(&nodes, total),
            from_s,
            end_s,
            if still_shaking {
                " The ground still shakes when the run ends (the last tenth of the run holds more than half of a \
                 panel's peak): a longer shear.duration_s records the rest of the motion."
            } else {
                ""
            }
        ),
        None => format!(
            "Acceleration through all the main shocks, one row per seed, {} (model scale).",
            nodes_text(&nodes, total)
        ),
    };
    drawn(path, &sheet, format!("{} acceleration, whole run", capitalised(&nodes_short(&nodes))), caption)
}

/// Where the motion of accelerogram panels lies: from a twentieth of its length before the first
/// sample of any panel above 1% of that panel's peak, to the last sample.
#[derive(Clone, Copy, Debug, PartialEq)]
struct MotionSpan {
    from_s: f64,
    end_s: f64,
    /// The last tenth of the run holds more than half the peak of some panel.
    still_shaking: bool,
}

/// Cuts the panels of `rows` to their motion's span (see [`MotionSpan`]); `None` (and the panels
/// as they were) when there is no motion.
fn motion_span(rows: &mut [Vec<Panel>]) -> Option<MotionSpan> {
    let traces = || rows.iter().flatten().flat_map(|p| p.lines.iter().map(|l| &l.points));
    let end_s = traces().filter_map(|pts| pts.last().map(|p| p.0)).fold(f64::NEG_INFINITY, f64::max);
    let start_s = traces().filter_map(|pts| pts.first().map(|p| p.0)).fold(f64::INFINITY, f64::min);
    let peak = |pts: &[(f64, f64)]| pts.iter().map(|p| p.1.abs()).filter(|v| v.is_finite()).fold(0.0, f64::max);
    let onset = traces()
        .filter_map(|pts| {
            let top = peak(pts);
            (top > 0.0).then(|| pts.iter().find(|p| p.1.abs() >= 0.01 * top).map(|p| p.0)).flatten()
        })
        .fold(f64::INFINITY, f64::min);
    if !(onset.is_finite() && end_s > onset) {
        return None;
    }
    let from_s = (onset - 0.05 * (end_s - onset)).max(start_s);
    let tail = end_s - 0.1 * (end_s - start_s);
    let still_shaking = traces().any(|pts| {
        let late: Vec<(f64, f64)> = pts.iter().copied().filter(|p| p.0 >= tail).collect();
        peak(&late) > 0.5 * peak(pts)
    });
    for p in rows.iter_mut().flatten() {
        for l in &mut p.lines {
            l.points.retain(|q| q.0 >= from_s);
        }
    }
    Some(MotionSpan { from_s, end_s, still_shaking })
}

/// The processed main-shock records of one node and seed: acceleration, velocity and
/// displacement, one line per main shock, each record's usable band in the caption.
pub(super) fn event_records(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(rec) = &d.records else { return Ok(Outcome::Skipped("no [accelerograms] records".into())) };
    let (nodes, _) = accelerogram_nodes(d);
    let Some(node) = nodes.first() else { return Ok(Outcome::Skipped("no control node records acceleration".into())) };
    let cname = node.component.name();
    // The first drawn seed with main-shock records of this node.
    let is_main = |l: &str| rank_of(l).is_some();
    let rows_of = |seed: u64| -> Vec<usize> {
        let mut rows: Vec<usize> = (0..rec.seed.len())
            .filter(|&i| {
                rec.seed[i] == seed
                    && rec.node[i] == node.ldem
                    && rec.component[i] == cname
                    && rec.scale[i] == "model"
                    && is_main(&rec.label[i])
            })
            .collect();
        rows.sort_by_key(|&i| rank_of(&rec.label[i]));
        rows
    };
    let Some((seed, rows)) = d.seeds.iter().map(|&s| (s, rows_of(s))).find(|(_, r)| !r.is_empty()) else {
        return Ok(Outcome::Skipped(format!("no main-shock record of node {} ({cname})", node.ldem)));
    };
    let Some(df) = d.part(&ACCELEROGRAMS, seed)? else {
        return Ok(Outcome::Skipped(format!("no accelerograms table for seed {seed}")));
    };
    let acc = Accelerograms::read(&df)?;
    let quantities: [(&str, f64); 3] = [("a (m/s²)", 1.0), ("v (mm/s)", 1e3), ("d (µm)", 1e6)];
    let mut panels: Vec<Panel> = quantities
        .iter()
        .map(|(desc, _)| Panel {
            y_desc: desc.to_string(),
            symmetric_y: true,
            y_tick_count: Some(3),
            compact: true,
            ..Panel::default()
        })
        .collect();
    let post_s = d.pipeline.analysis.accelerograms.as_ref().map_or(f64::INFINITY, |a| a.post_event_s);
    let mut bands = Vec::new();
    for (k, &i) in rows.iter().enumerate() {
        let (record, label) = (&rec.record[i], &rec.label[i]);
        // The window around the shock, without the pads added for the filter.
        let shock = rec.start_s[i] + rec.pre_event_s[i];
        let at: Vec<usize> = (0..acc.seed.len())
            .filter(|&j| {
                acc.record[j] == *record && acc.time_s[j] >= rec.start_s[i] - 1e-12 && acc.time_s[j] <= shock + post_s
            })
            .collect();
        if at.is_empty() {
            continue;
        }
        let t: Vec<f64> = at.iter().map(|&j| (acc.time_s[j] - shock) * 1e3).collect();
        for (q, (panel, (_, factor))) in panels.iter_mut().zip(quantities).enumerate() {
            let v: Vec<f64> = at
                .iter()
                .map(|&j| factor * [acc.acceleration_m_s2[j], acc.velocity_m_s[j], acc.displacement_m[j]][q])
                .collect();
            let mut line = Line::new(if q == 0 { label.clone() } else { String::new() }, decimate(&t, &v, 2000), k);
            line.width = 1;
            panel.lines.push(line);
        }
        bands.push(format!(
            "{label} {}–{} Hz",
            crate::plot::fmt_tick(&rec.usable_low_hz[i]),
            crate::plot::fmt_tick(&rec.usable_high_hz[i])
        ));
    }
    if panels[0].lines.is_empty() {
        return Ok(Outcome::Skipped(format!("no samples of the records of seed {seed}")));
    }
    let pre_ms = d.pipeline.analysis.accelerograms.as_ref().map(|a| a.pre_event_s * 1e3);
    let sheet = accelerogram_sheet(
        format!("Main-shock records of node {} ({cname}), seed {seed}, model scale", node.ldem),
        "time from the start of the main shock (ms)",
        panels.into_iter().map(|p| vec![p]).collect(),
        1,
    );
    drawn(
        path,
        &sheet,
        format!("Main-shock records, node {}", node.ldem),
        format!(
            "The processed records of {} ({cname}) for each main shock of seed {seed} (mean removed, tapered, padded, \
             band-pass filtered inside the usable band, baseline corrected): acceleration, velocity and displacement, \
             model scale, from the start of each record's window{} to its end (the pads added for the filter not \
             drawn). Usable band of each record: {}. At \
             prototype scale times ×λ, accelerations ÷λ, displacements ×λ; every record of every seed is in the \
             accelerograms table and the AT2/SAC files.",
            node.name(),
            pre_ms.map(|p| format!(" ({} ms before the shock)", crate::plot::fmt_tick(&p))).unwrap_or_default(),
            bands.join("; ")
        ),
    )
}
