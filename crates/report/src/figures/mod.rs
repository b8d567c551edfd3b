//! The figures of the report, each from the tables of the output folder, drawn with the chart
//! layer of [`crate::charts`] (clipped to the axes, labels placed where no data is).

mod catalogue;

mod cracks;

mod fault;

use std::path::Path;

use plotters::style::{BLACK, RGBColor};

use stickslip_seismo::events::EventKind;
use stickslip_seismo::spectra::intensity::G;
use stickslip_solver::Channel;
use stickslip_solver::scene::{Component, ControlChannel, Kinematic};
use stickslip_store::io::scan_glob;
use stickslip_store::schema::{ACCELEROGRAMS, CONTROL, FOURIER, ROTD, SERIES, SET, SPECTRA, col};
use stickslip_store::tables::records::{Accelerograms, SetTable, Spectra, read_fourier};
use stickslip_store::tables::series::{Trace, read_control, read_series_channel};

use crate::charts::{self, Band, HLine, Line, Marker, Panel, Points, Sheet};
use crate::plot::{HEIGHT, WIDTH, colour, decimate, padded_range};
use crate::{ReportError, ReportInput};

/// What drawing a figure gave.
pub enum Outcome {
    /// Drawn, with its heading and caption.
    Drawn {
        /// Heading.
        title: String,
        /// What it shows.
        caption: String,
        /// The texts drawn as titles on the image: the sheet's, then each panel's (empty ones left
        /// out).
        headings: Vec<String>,
        /// The name of each panel (empty for a panel without one), in drawing order.
        panels: Vec<String>,
        /// Labels not drawn for want of a free spot (see [`charts::DrawnPanel::dropped`]).
        dropped: Vec<String>,
    },
    /// Not drawn, and why.
    Skipped(String),
}

/// Draws one figure into a file.
pub type Draw = fn(&ReportInput, &Path) -> Result<Outcome, ReportError>;

/// Every figure, in page order.
pub const ALL: [(&str, Draw); 24] = [
    ("shear_stress.png", shear_stress),
    ("normal_stress.png", normal_stress),
    ("mean_slip.png", mean_slip),
    ("acceleration_s2.png", acceleration_s2),
    ("acceleration_run.png", acceleration_run),
    ("records.png", event_records),
    ("response_spectra_z.png", spectra_z),
    ("response_spectra_x.png", spectra_x),
    ("fourier.png", fourier),
    ("record_set.png", record_set),
    ("stress_drop_vs_duration.png", drop_vs_duration),
    ("recurrence.png", recurrence),
    ("magnitude.png", magnitude),
    ("attenuation.png", attenuation),
    ("energy.png", energy),
    ("friction_map.png", fault::friction_map),
    ("space_time.png", fault::space_time),
    ("cracks.png", cracks::crack_map),
    ("acoustic_emission.png", cracks::emission),
    ("catalogue.png", catalogue::overview),
    ("magnitude_frequency.png", catalogue::magnitude_frequency),
    ("recurrence_fits.png", catalogue::recurrence_fits),
    ("aftershocks.png", catalogue::aftershocks),
    ("scaling.png", catalogue::scaling),
];

/// At most this many nodes are drawn side by side in the accelerogram, spectrum and Fourier
/// figures; beyond it, a subset spread over the recorded ones, said in the caption.
pub const MAX_NODES: usize = 3;

fn seeds_text(seeds: &[u64]) -> String {
    let s: Vec<String> = seeds.iter().map(|s| s.to_string()).collect();
    match s.len() {
        0 => "no seed".into(),
        1 => format!("seed {}", s[0]),
        _ => format!("seeds {}", s.join(", ")),
    }
}

/// " (paper Fig. n)" for the paper's pipelines (`[report] paper_figures`), else nothing.
fn paper_fig(d: &ReportInput, n: u32) -> String {
    if d.pipeline.report.paper_figures { format!(" (paper Fig. {n})") } else { String::new() }
}

/// Draws `sheet` to `path` and returns the figure's outcome.
fn drawn(path: &Path, sheet: &Sheet, title: String, caption: String) -> Result<Outcome, ReportError> {
    let out = charts::draw(path, sheet)?;
    let headings = std::iter::once(&sheet.title)
        .chain(sheet.panels.iter().map(|p| &p.title))
        .filter(|t| !t.is_empty())
        .cloned()
        .collect();
    let dropped = out.panels.iter().flat_map(|p| p.dropped.iter().cloned()).collect();
    Ok(Outcome::Drawn { title, caption, headings, panels: out.panels.into_iter().map(|p| p.name).collect(), dropped })
}

/// (time, values) of a series column for one seed, if recorded.
fn series(d: &ReportInput, seed: u64, column: &str) -> Result<Option<Trace>, ReportError> {
    let Some(df) = d.part(&SERIES, seed)? else { return Ok(None) };
    Ok(read_series_channel(&df, column)?)
}

/// A recorded accelerogram channel the figures show.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeChannel {
    /// LDEM number.
    pub ldem: u64,
    /// Component drawn (z if recorded, else the first).
    pub component: Component,
    /// The node's position (m).
    pub at_m: [f64; 3],
}

impl NodeChannel {
    /// "node 36 at (0.2, 0.1, 0.1) m".
    pub fn name(&self) -> String {
        let [x, y, z] = self.at_m.map(|v| crate::plot::fmt_tick(&v));
        format!("node {} at ({x}, {y}, {z}) m", self.ldem)
    }
}

/// The nodes the accelerogram figures show: every control node recording acceleration that the
/// `[accelerograms]` section cuts records of (all of them without one), at most [`MAX_NODES`]
/// spread evenly over them; and how many there were.
fn accelerogram_nodes(d: &ReportInput) -> (Vec<NodeChannel>, usize) {
    let control = &d.pipeline.scene.record.control;
    let wanted = |c: &&ControlChannel| {
        d.pipeline.accelerograms.as_ref().map_or(c.quantity == Kinematic::Acceleration, |a| a.wants(c))
    };
    let mut nodes: Vec<_> = control.iter().filter(wanted).map(|c| c.node).collect();
    nodes.sort();
    nodes.dedup();
    let lattice = d.pipeline.scene.lattice();
    let all: Vec<NodeChannel> = nodes
        .iter()
        .filter_map(|&node| {
            let comps: Vec<Component> =
                control.iter().filter(wanted).filter(|c| c.node == node).map(|c| c.component).collect();
            let component = if comps.contains(&Component::Z) { Component::Z } else { *comps.first()? };
            Some(NodeChannel { ldem: node.ldem(), component, at_m: lattice.position(node) })
        })
        .collect();
    let total = all.len();
    if total <= MAX_NODES {
        return (all, total);
    }
    (spread(total, MAX_NODES).into_iter().map(|i| all[i].clone()).collect(), total)
}

/// `max` of the indices `0..total` spread evenly over them, the first and the last included (all
/// of them when `total ≤ max`), in increasing order.
pub fn spread(total: usize, max: usize) -> Vec<usize> {
    match (total, max) {
        (t, m) if t <= m => (0..t).collect(),
        (_, 0) => vec![],
        (_, 1) => vec![0],
        (t, m) => (0..m).map(|k| (k * (t - 1) + (m - 1) / 2) / (m - 1)).collect(),
    }
}

/// How the caption says which nodes are drawn.
fn nodes_text(nodes: &[NodeChannel], total: usize) -> String {
    let names: Vec<String> = nodes.iter().map(|n| format!("{} ({})", n.name(), n.component.name())).collect();
    let list = names.join("; ");
    if total > nodes.len() {
        format!(
            "{} of the {total} control nodes recording acceleration, spread over them (the figures show at most \
             {MAX_NODES}; every node's records are in the tables): {list}",
            nodes.len()
        )
    } else if nodes.len() > 1 {
        format!("each control node in its own panel: {list}")
    } else {
        format!("control {list}")
    }
}

/// "node 36" or "nodes 36, 12".
fn nodes_short(nodes: &[NodeChannel]) -> String {
    let n: Vec<String> = nodes.iter().map(|n| n.ldem.to_string()).collect();
    if n.len() == 1 { format!("node {}", n[0]) } else { format!("nodes {}", n.join(", ")) }
}

/// (time, acceleration) of a control channel for one seed.
fn control(d: &ReportInput, seed: u64, node: &NodeChannel) -> Result<Option<Trace>, ReportError> {
    let Some(df) = d.part(&CONTROL, seed)? else { return Ok(None) };
    Ok(read_control(&df, node.ldem, node.component, Kinematic::Acceleration)?)
}

/// Main shocks of one seed: (label, start time).
fn main_shocks(d: &ReportInput, seed: u64) -> Result<Vec<(String, f64)>, ReportError> {
    let Some(ev) = &d.events else { return Ok(vec![]) };
    Ok((0..ev.len())
        .filter(|&i| ev.seed[i] == seed && ev.kind[i].is_main())
        .map(|i| (ev.kind[i].label(), ev.start_s[i]))
        .collect())
}

/// Main shocks of one seed: (label, start, end).
fn main_shocks_with_ends(d: &ReportInput, seed: u64) -> Result<Vec<(String, f64, f64)>, ReportError> {
    let Some(ev) = &d.events else { return Ok(vec![]) };
    Ok((0..ev.len())
        .filter(|&i| ev.seed[i] == seed && ev.kind[i].is_main())
        .map(|i| (ev.kind[i].label(), ev.start_s[i], ev.start_s[i] + ev.duration_s[i]))
        .collect())
}

fn value_at(t: &[f64], y: &[f64], at: f64) -> f64 {
    let i = t.partition_point(|&x| x < at).min(t.len().saturating_sub(1));
    y[i]
}

fn shear_stress(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (mut lines, mut markers) = (Vec::new(), Vec::new());
    for (k, &seed) in d.seeds.iter().enumerate() {
        let Some((t, tau)) = series(d, seed, Channel::ShearStress.name())? else { continue };
        let kpa: Vec<f64> = tau.iter().map(|v| v / 1e3).collect();
        for (label, start) in main_shocks(d, seed)? {
            markers.push(Marker {
                at: (start, value_at(&t, &kpa, start)),
                text: label,
                colour: colour(k),
                text_colour: colour(k),
            });
        }
        lines.push(Line::new(format!("seed {seed}"), decimate(&t, &kpa, WIDTH as usize), k));
    }
    if lines.is_empty() {
        return Ok(Outcome::Skipped("no shear stress recorded".into()));
    }
    if markers.len() > LONG_RUN_MAIN_SHOCKS {
        return long_shear_stress(d, path);
    }
    // Several seeds share each main-shock rank, and their S2s lie close together: each rank is
    // labelled once, above the highest of its triangles, in black (it names the triangles of
    // every seed); the chart drops any label that would still overlap another.
    if d.seeds.len() > 1 {
        let mut best: std::collections::BTreeMap<String, usize> = Default::default();
        for (i, m) in markers.iter().enumerate() {
            let e = best.entry(m.text.clone()).or_insert(i);
            if m.at.1 > markers[*e].at.1 {
                *e = i;
            }
        }
        for (i, m) in markers.iter_mut().enumerate() {
            if best.get(&m.text) == Some(&i) {
                m.text_colour = BLACK;
            } else {
                m.text.clear();
            }
        }
    }
    let panel = Panel { lines, markers, ..Panel::linear("time since the start of shearing (s)", "τ (kPa)") };
    let sheet = Sheet::new(format!("Shear stress on the base{}", paper_fig(d, 3)), 1, vec![panel]);
    drawn(
        path,
        &sheet,
        "Shear stress τ(t)".into(),
        format!(
            "Mean shear stress on the base, τ = −ΣF_x/A, for {}. Triangles mark the start of the main shocks S1, S2, … \
             found by the event detector (stress drops of at least half the largest), each rank labelled once; the \
             smaller drops between them are fore- and aftershocks.",
            seeds_text(&d.seeds)
        ),
    )
}

/// More main shocks than this in the τ(t) figure and it is drawn as a long run: an envelope with
/// ticks, and a zoom on the largest event.
pub const LONG_RUN_MAIN_SHOCKS: usize = 40;

/// Per pixel column, the minimum and maximum of `y` (x at the column's centre).
fn envelope(t: &[f64], y: &[f64], columns: usize) -> Vec<(f64, f64, f64)> {
    let (Some(&t0), Some(&t1)) = (t.first(), t.last()) else { return vec![] };
    let width = (t1 - t0).max(f64::MIN_POSITIVE) / columns as f64;
    let mut out: Vec<(f64, f64, f64)> = Vec::with_capacity(columns);
    let mut current = usize::MAX;
    for (&x, &v) in t.iter().zip(y) {
        let k = (((x - t0) / width) as usize).min(columns - 1);
        if k != current {
            out.push((t0 + (k as f64 + 0.5) * width, v, v));
            current = k;
        } else if let Some(last) = out.last_mut() {
            last.1 = last.1.min(v);
            last.2 = last.2.max(v);
        }
    }
    out
}

/// τ(t) of a long run (first seed): the min–max envelope per pixel column with a tick per main
/// shock, and below it the stretch from the main shock before the largest drop to the one after.
fn long_shear_stress(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(&seed) = d.seeds.first() else { return Ok(Outcome::Skipped("no successful seed".into())) };
    let Some((t, tau)) = series(d, seed, Channel::ShearStress.name())? else {
        return Ok(Outcome::Skipped("no shear stress recorded".into()));
    };
    let kpa: Vec<f64> = tau.iter().map(|v| v / 1e3).collect();
    let shocks = main_shocks(d, seed)?;
    let top = kpa.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let ticks = Points {
        label: format!("main shocks ({})", shocks.len()),
        points: shocks.iter().map(|(_, s)| (*s, top * 1.04)).collect(),
        colour: colour(3),
        size: 2,
    };
    let whole = Panel {
        bands: vec![Band {
            points: envelope(&t, &kpa, WIDTH as usize),
            colour: colour(0),
            label: "min–max per pixel".into(),
        }],
        points: vec![ticks],
        ..Panel::linear("time since the start of shearing (s)", "τ (kPa)")
    };
    // The largest main shock by stress drop, and its neighbours.
    let ev = d.events.as_ref();
    let largest = ev.and_then(|ev| {
        (0..ev.len())
            .filter(|&i| ev.seed[i] == seed && ev.kind[i].is_main())
            .max_by(|&a, &b| ev.stress_drop_pa[a].total_cmp(&ev.stress_drop_pa[b]))
            .map(|i| (ev.kind[i].label(), ev.start_s[i], ev.stress_drop_pa[i]))
    });
    let mut panels = vec![whole];
    let mut zoom_text = String::new();
    if let Some((label, start, drop)) = largest {
        let before = shocks.iter().map(|s| s.1).filter(|&s| s < start).fold(t[0], f64::max);
        let after = shocks.iter().map(|s| s.1).find(|&s| s > start).unwrap_or(t[t.len() - 1]);
        let (a, b) = (t.partition_point(|&x| x < before), t.partition_point(|&x| x <= after));
        let markers: Vec<Marker> = shocks
            .iter()
            .filter(|s| s.1 >= before && s.1 <= after)
            .map(|(l, s)| Marker {
                at: (*s, value_at(&t, &kpa, *s)),
                text: l.clone(),
                colour: colour(0),
                text_colour: BLACK,
            })
            .collect();
        panels.push(Panel {
            lines: vec![Line::new("", decimate(&t[a..b], &kpa[a..b], WIDTH as usize), 0)],
            markers,
            name: format!("zoom: {label}, the largest drop ({:.2} kPa)", drop / 1e3),
            ..Panel::linear("time since the start of shearing (s)", "τ (kPa)")
        });
        zoom_text = format!(
            " Below, from the main shock before the largest drop ({label}, {:.2} kPa) to the one after it, at full \
             resolution.",
            drop / 1e3
        );
    }
    let sheet = Sheet::new(format!("Shear stress on the base, seed {seed}"), 1, panels);
    drawn(
        path,
        &sheet,
        "Shear stress τ(t)".into(),
        format!(
            "Mean shear stress on the base, τ = −ΣF_x/A, of seed {seed} over the whole run as the range of τ in each \
             pixel column (a long run: {} main shocks, each a tick above the envelope).{zoom_text}",
            shocks.len()
        ),
    )
}

fn normal_stress(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(&seed) = d.seeds.first() else { return Ok(Outcome::Skipped("no successful seed".into())) };
    let Some((t, sigma)) = series(d, seed, Channel::NormalStress.name())? else {
        return Ok(Outcome::Skipped("normal stress not recorded".into()));
    };
    let scene = &d.pipeline.scene;
    let lattice = scene.lattice();
    let weight = scene.density_kg_m3 * lattice.volume() * scene.self_weight.gravity_m_s2 / lattice.contact_area() / 1e3;
    let kpa: Vec<f64> = sigma.iter().map(|v| v / 1e3).collect();
    let swing = |x: &[f64]| x.iter().map(|v| (v - weight).abs() / weight).fold(0.0, f64::max);
    let dt = if t.len() > 1 { (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64 } else { 1.0 };
    let averaged = stickslip_seismo::events::moving_average(&kpa, ((1e-3 / dt).round() as usize).max(1));
    let (raw_swing, avg_swing) = (swing(&kpa), swing(&averaged));
    let panel = Panel {
        lines: vec![Line::new(format!("seed {seed}"), decimate(&t, &kpa, WIDTH as usize), 0)],
        hlines: vec![HLine { y: weight, text: format!("self-weight ρgh = {weight:.2} kPa"), colour: BLACK }],
        ..Panel::linear("time since the start of shearing (s)", "σ (kPa)")
    };
    let sheet = Sheet::new(format!("Normal stress on the base, seed {seed}{}", paper_fig(d, 4)), 1, vec![panel]);
    let paper = if d.pipeline.report.paper_figures { "; the paper reports up to 30%" } else { "" };
    drawn(
        path,
        &sheet,
        "Normal stress σ(t)".into(),
        format!(
            "Mean normal stress ΣN/A on the base for seed {seed}, with the self-weight level. During the drops it swings \
             by up to {:.0}% of the self-weight averaged over 1 ms ({:.0}% in single samples{paper}), as nodes lift \
             off and land.",
            100.0 * avg_swing,
            100.0 * raw_swing
        ),
    )
}

fn mean_slip(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let mut lines = Vec::new();
    for (k, &seed) in d.seeds.iter().enumerate() {
        let Some((t, delta)) = series(d, seed, Channel::MeanSlip.name())? else { continue };
        let um: Vec<f64> = delta.iter().map(|v| v * 1e6).collect();
        lines.push(Line::new(format!("seed {seed}"), decimate(&t, &um, WIDTH as usize), k));
    }
    if lines.is_empty() {
        return Ok(Outcome::Skipped("mean slip not recorded".into()));
    }
    let panel = Panel { lines, ..Panel::linear("time since the start of shearing (s)", "δ (µm)") };
    let sheet = Sheet::new(format!("Mean displacement of the contact surface{}", paper_fig(d, 5)), 1, vec![panel]);
    drawn(
        path,
        &sheet,
        "Mean contact displacement δ(t)".into(),
        format!(
            "Mean x-displacement of the contact nodes for {}: the block moves in jumps at the stress drops and stands \
             still in between.",
            seeds_text(&d.seeds)
        ),
    )
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

fn acceleration_s2(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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

fn acceleration_run(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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
    let comps: Vec<&str> = nodes.iter().map(|n| n.component.name()).collect();
    let sheet = accelerogram_sheet(
        format!("Acceleration of {} ({}) over the whole run{}", nodes_short(&nodes), comps[0], paper_fig(d, 7)),
        "time since the start of shearing (s)",
        rows,
        nodes.len(),
    );
    drawn(
        path,
        &sheet,
        format!("{} acceleration, whole run", capitalised(&nodes_short(&nodes))),
        format!(
            "Acceleration through all the main shocks, one row per seed, {} (model scale).",
            nodes_text(&nodes, total)
        ),
    )
}

/// The processed main-shock records of one node and seed: acceleration, velocity and
/// displacement, one line per main shock, each record's usable band in the caption.
fn event_records(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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
    let post_s = d.pipeline.accelerograms.as_ref().map_or(f64::INFINITY, |a| a.post_event_s);
    let mut bands = Vec::new();
    for (k, &i) in rows.iter().enumerate() {
        let (record, label) = (&rec.record[i], &rec.label[i]);
        // The window around the shock, without the pads added for the filter.
        let shock = rec.start_s[i] + rec.pre_event_s[i];
        let at: Vec<usize> = (0..acc.seed.len())
            .filter(|&j| {
                acc.record[j] == *record
                    && acc.scale[j] == "model"
                    && acc.time_s[j] >= rec.start_s[i] - 1e-12
                    && acc.time_s[j] <= shock + post_s
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
    let pre_ms = d.pipeline.accelerograms.as_ref().map(|a| a.pre_event_s * 1e3);
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

fn spectra_z(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    spectra(d, path, Component::Z)
}

fn spectra_x(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    spectra(d, path, Component::X)
}

/// PSA at 5% (or the nearest damping), model and prototype scale, one row per node: every seed
/// thin, the mean and the 5–95% band bold.
fn spectra(d: &ReportInput, path: &Path, comp: Component) -> Result<Outcome, ReportError> {
    let (all_nodes, total) = accelerogram_nodes(d);
    let Some(stats) = &d.psa_stats else {
        return Ok(Outcome::Skipped("no spectra analysis".into()));
    };
    let cname = comp.name();
    let damping =
        stats.damping.iter().copied().min_by(|a, b| (a - 0.05).abs().total_cmp(&(b - 0.05).abs())).unwrap_or(0.05);
    let nodes: Vec<NodeChannel> = all_nodes
        .into_iter()
        .filter(|n| (0..stats.node.len()).any(|i| stats.node[i] == n.ldem && stats.component[i] == cname))
        .map(|n| NodeChannel { component: comp, ..n })
        .collect();
    if nodes.is_empty() {
        return Ok(Outcome::Skipped(format!("no {cname} spectra")));
    }
    let all = scan_glob(&d.folder.part_glob(&SPECTRA))?.map(|df| Spectra::read(&df)).transpose()?;
    let mut panels = Vec::new();
    let mut count = 0;
    for node in &nodes {
        for (scale, unit_note) in [("model", "model scale"), ("prototype", "prototype scale (λ)")] {
            let rows: Vec<usize> = (0..stats.node.len())
                .filter(|&i| {
                    stats.node[i] == node.ldem
                        && stats.component[i] == cname
                        && stats.scale[i] == scale
                        && stats.damping[i] == damping
                        && stats.in_band[i]
                })
                .collect();
            let mut lines = Vec::new();
            if let Some(sp) = &all {
                let mut records: Vec<(u64, &str)> = (0..sp.seed.len())
                    .filter(|&i| sp.node[i] == node.ldem && sp.component[i] == cname)
                    .map(|i| (sp.seed[i], sp.record[i].as_str()))
                    .collect();
                records.sort();
                records.dedup();
                count = records.len();
                for (s, r) in records {
                    let pts: Vec<(f64, f64)> = (0..sp.seed.len())
                        .filter(|&i| {
                            sp.seed[i] == s
                                && sp.record[i] == r
                                && sp.scale[i] == scale
                                && sp.damping[i] == damping
                                && sp.in_band[i]
                        })
                        .map(|i| (sp.period_s[i], sp.psa_m_s2[i]))
                        .collect();
                    lines.push(Line {
                        label: String::new(),
                        points: pts,
                        colour: RGBColor(150, 150, 150),
                        width: 1,
                        alpha: 0.5,
                    });
                }
            }
            if let Some(l) = lines.first_mut() {
                l.label = "each record".into();
            }
            lines.push(Line {
                label: "mean".into(),
                points: rows.iter().map(|&i| (stats.period_s[i], stats.mean[i])).collect(),
                colour: colour(1),
                width: 4,
                alpha: 1.0,
            });
            let band = Band {
                points: rows.iter().map(|&i| (stats.period_s[i], stats.p5[i], stats.p95[i])).collect(),
                colour: colour(0),
                label: "5–95%".into(),
            };
            panels.push(Panel {
                title: format!("PSA, {unit_note}"),
                name: node.name(),
                lines,
                bands: vec![band],
                ..Panel::loglog("period (s)", "PSA (m/s²)")
            });
        }
    }
    let rows = nodes.len() as u32;
    let sheet = Sheet::new(String::new(), 2, panels).with_height(if rows == 1 { HEIGHT } else { 420 * rows });
    drawn(
        path,
        &sheet,
        format!("Response spectra, {} ({cname})", nodes_short(&nodes)),
        format!(
            "Pseudo-spectral acceleration at {:.0}% damping of the processed {cname} records, {}: every record thin \
             ({count} records per node), the mean and the 5–95% band across records bold, drawn only over the usable \
             band (periods between 1/f_max of the lattice and 1/(1.25·f_low) of the filter). Left at model scale, \
             right at prototype scale (periods ×λ, PSA ÷λ). Exact peaks for the straight-line reading of the samples \
             (Nigam–Jennings).",
            100.0 * damping,
            nodes_text(&nodes, total)
        ),
    )
}

fn fourier(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (nodes, total) = accelerogram_nodes(d);
    if nodes.is_empty() {
        return Ok(Outcome::Skipped("no accelerogram".into()));
    }
    let mut panels = Vec::new();
    for node in &nodes {
        let mut lines = Vec::new();
        for (k, &seed) in d.seeds.iter().enumerate() {
            let Some(df) = d.part(&FOURIER, seed)? else { continue };
            let Some((f, a)) = read_fourier(&df, &format!("S2-n{}-{}", node.ldem, node.component.name()))? else {
                continue;
            };
            // Log-spaced thinning: keep the maximum per 1/200 decade.
            let mut pts: Vec<(f64, f64)> = Vec::new();
            let mut bucket = i64::MIN;
            for i in (0..f.len()).filter(|&i| f[i] > 0.0) {
                let b = (f[i].log10() * 200.0).floor() as i64;
                match pts.last_mut() {
                    Some(p) if b == bucket => {
                        if a[i] > p.1 {
                            *p = (f[i], a[i]);
                        }
                    }
                    _ => {
                        pts.push((f[i], a[i]));
                        bucket = b;
                    }
                }
            }
            let mut l = Line::new(format!("seed {seed}"), pts, k);
            l.width = 1;
            lines.push(l);
        }
        if !lines.is_empty() {
            panels.push(Panel {
                name: format!("{} ({})", node.name(), node.component.name()),
                lines,
                ..Panel::loglog("frequency (Hz)", "|X|·Δt (m/s)")
            });
        }
    }
    if panels.is_empty() {
        return Ok(Outcome::Skipped("no Fourier spectra".into()));
    }
    let n = panels.len();
    let columns = n.min(2);
    let rows = n.div_ceil(columns) as u32;
    let sheet = Sheet::new("Fourier amplitude of the S2 records, model scale", columns, panels)
        .with_height(if rows == 1 { HEIGHT } else { 60 + 420 * rows });
    drawn(
        path,
        &sheet,
        format!("Fourier spectra, {}", nodes_short(&nodes)),
        format!(
            "Fourier amplitude |X(f)|·Δt of the processed record of main shock S2 for {}, {} (zero-padded to a power \
             of two; the largest value per 1/200 decade is drawn). At prototype scale the frequencies are divided by \
             λ, the amplitudes unchanged.",
            seeds_text(&d.seeds),
            nodes_text(&nodes, total)
        ),
    )
}

/// The record set chosen by `[set]` against its design spectrum, prototype scale: the target, each
/// scaled record, their mean, the rule's fraction of the target, the period range shaded.
fn record_set(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(settings) = &d.pipeline.set else { return Ok(Outcome::Skipped("no [set] section".into())) };
    let Some(df) = stickslip_store::io::read_parquet_if_present(&d.folder.gathered(&SET))? else {
        return Ok(Outcome::Skipped("no set table (the selection failed or has not run)".into()));
    };
    let set = SetTable::read(&df)?;
    let rotd = settings.component == stickslip_config::set::SetComponent::Rotd50;
    let table = if rotd { ROTD } else { SPECTRA };
    let Some(sp) = scan_glob(&d.folder.part_glob(&table))?.map(|df| Spectra::read(&df)).transpose()? else {
        return Ok(Outcome::Skipped(format!("no {} table", table.name)));
    };
    // A record's prototype spectrum at the set's damping (of its RotD50 in the RotD table, which
    // also holds RotD100), by increasing period.
    let psa_of = |seed: u64, record: &str| -> Vec<(f64, f64, bool)> {
        let mut pts: Vec<(f64, f64, bool)> = (0..sp.seed.len())
            .filter(|&i| {
                sp.seed[i] == seed
                    && sp.record[i] == record
                    && sp.scale[i] == "prototype"
                    && (!rotd || sp.component[i] == "rotd50")
                    && (sp.damping[i] - settings.damping).abs() < 1e-12
            })
            .map(|i| (sp.period_s[i], sp.psa_m_s2[i], sp.in_band[i]))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts
    };
    // Each record is drawn only in its usable band; the mean only where every record is in band.
    let mut lines = Vec::new();
    let mut scaled_all: Vec<Vec<(f64, f64, bool)>> = Vec::new();
    for k in 0..set.seed.len() {
        let pts: Vec<(f64, f64, bool)> =
            psa_of(set.seed[k], &set.record[k]).into_iter().map(|(t, a, b)| (t, a * set.scale_factor[k], b)).collect();
        if pts.is_empty() {
            continue;
        }
        lines.push(Line {
            label: if lines.is_empty() { "each scaled record, in its usable band".into() } else { String::new() },
            points: pts.iter().filter(|p| p.2).map(|p| (p.0, p.1)).collect(),
            colour: RGBColor(150, 150, 150),
            width: 1,
            alpha: 0.7,
        });
        scaled_all.push(pts);
    }
    if scaled_all.is_empty() {
        return Ok(Outcome::Skipped("no spectrum of the chosen records".into()));
    }
    // The mean on the common grid (every record's spectrum has the pipeline's periods).
    let n = scaled_all.iter().map(Vec::len).min().unwrap_or(0);
    let mean: Vec<(f64, f64)> = (0..n)
        .filter(|&j| scaled_all.iter().all(|r| r[j].2))
        .map(|j| (scaled_all[0][j].0, scaled_all.iter().map(|r| r[j].1).sum::<f64>() / scaled_all.len() as f64))
        .collect();
    let target: Vec<(f64, f64)> =
        scaled_all[0][..n].iter().filter_map(|&(t, _, _)| settings.target.psa(t).ok().map(|v| (t, v))).collect();
    let fraction = settings.options.rule_fraction;
    let floor: Vec<(f64, f64)> = target.iter().map(|&(t, v)| (t, fraction * v)).collect();
    let range = settings.options.range.bounds().ok();
    let ys = lines.iter().flat_map(|l| l.points.iter().map(|p| p.1)).chain(target.iter().map(|p| p.1));
    let (lo, hi) = crate::plot::log_range(ys);
    let bands = range
        .map(|(a, b)| Band {
            points: vec![(a, lo, hi), (b, lo, hi)],
            colour: RGBColor(120, 120, 120),
            label: "period range of the match".into(),
        })
        .into_iter()
        .collect();
    lines.push(Line { label: "mean of the set".into(), points: mean, colour: colour(1), width: 3, alpha: 1.0 });
    lines.push(Line { label: settings.target_name.clone(), points: target, colour: BLACK, width: 3, alpha: 1.0 });
    lines.push(Line {
        label: format!("{:.0}% of the target", 100.0 * fraction),
        points: floor,
        colour: colour(0),
        width: 2,
        alpha: 1.0,
    });
    let panel = Panel { lines, bands, y_range: Some((lo, hi)), ..Panel::loglog("period (s)", "PSA (m/s²)") };
    let count = scaled_all.len();
    let comp = if rotd { "RotD50".to_string() } else { set.component.first().cloned().unwrap_or_default() };
    drawn(
        path,
        &Sheet::new(format!("Record set of {count} matched to the target spectrum, prototype scale"), 1, vec![panel]),
        "Record set matched to a design spectrum".into(),
        format!(
            "The {count} records chosen by [set] ({comp}, {:.0}% damping), each scaled by its factor (grey), their \
             mean, the target spectrum ({}) and {:.0}% of it, at prototype scale; the shaded band is the period range \
             of the match{}. The set table lists each record, its factor and misfit; the scaled records are under set/.",
            100.0 * settings.damping,
            settings.target_name,
            100.0 * fraction,
            range
                .map(|(a, b)| format!(" ({}–{} s)", crate::plot::fmt_tick(&a), crate::plot::fmt_tick(&b)))
                .unwrap_or_default()
        ),
    )
}

fn rank_of(label: &str) -> Option<u32> {
    label.strip_prefix('S')?.parse().ok()
}

fn drop_vs_duration(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(ev) = &d.events else { return Ok(Outcome::Skipped("no events".into())) };
    if ev.is_empty() {
        return Ok(Outcome::Skipped("no events".into()));
    }
    let (dur, drop) = (&ev.duration_s, &ev.stress_drop_pa);
    let mut groups = vec![Points {
        label: "fore- and aftershocks".into(),
        points: (0..ev.len()).filter(|&i| !ev.kind[i].is_main()).map(|i| (dur[i] * 1e3, drop[i] / 1e3)).collect(),
        colour: RGBColor(150, 150, 150),
        size: 4,
    }];
    let max_rank = ev.kind.iter().filter(|k| k.is_main()).filter_map(|k| k.rank()).max().unwrap_or(0);
    for r in 1..=max_rank {
        groups.push(Points {
            label: format!("S{r}"),
            points: (0..ev.len())
                .filter(|&i| ev.kind[i] == EventKind::Main(r))
                .map(|i| (dur[i] * 1e3, drop[i] / 1e3))
                .collect(),
            colour: colour(r as usize - 1),
            size: 6,
        });
    }
    let panel = Panel { points: groups, ..Panel::linear("duration (ms)", "stress drop (kPa)") };
    drawn(
        path,
        &Sheet::new("Stress drop against duration, all events", 1, vec![panel]),
        "Event catalogue: stress drop vs duration".into(),
        format!(
            "Every event of every seed ({} events): main shocks coloured by rank, fore- and aftershocks grey. Duration is \
             the slip burst (smoothed mean slip rate above the detector's thresholds); the stress drop is measured on the \
             1-ms-averaged τ.",
            ev.len()
        ),
    )
}

/// Deterministic jitter in [−0.15, 0.15] from an index.
fn jitter(i: usize) -> f64 {
    ((i as f64 * 0.618_033_988_75).fract() - 0.5) * 0.3
}

fn rank_ticks(v: &f64) -> String {
    let r = v.round();
    if (v - r).abs() < 1e-6 && r >= 1.0 { format!("S{}", r as i64) } else { String::new() }
}

fn recurrence(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(ev) = &d.events else { return Ok(Outcome::Skipped("no events".into())) };
    let seconds: Vec<(u32, f64)> = (0..ev.len())
        .filter(|&i| ev.kind[i].is_main())
        .filter_map(|i| Some((ev.kind[i].rank()?, ev.recurrence_s[i].filter(|r| r.is_finite())?)))
        .collect();
    if seconds.is_empty() {
        return Ok(Outcome::Skipped("fewer than two main shocks in every seed".into()));
    }
    // Milliseconds at the paper's loading rate; seconds for slowly loaded runs (where the
    // paper's 25.8 ms is not a reference any more).
    let slow = seconds.iter().map(|p| p.1).sum::<f64>() / seconds.len() as f64 > 10.0;
    let (scale, unit) = if slow { (1.0, "s") } else { (1e3, "ms") };
    let pts: Vec<(u32, f64)> = seconds.iter().map(|&(r, v)| (r, v * scale)).collect();
    let max_rank = pts.iter().map(|p| p.0).max().unwrap_or(2);
    let groups = vec![Points {
        label: "one main shock".into(),
        points: pts.iter().enumerate().map(|(i, (r, v))| (*r as f64 + jitter(i), *v)).collect(),
        colour: colour(0),
        size: 5,
    }];
    let means: Vec<(f64, f64)> = (2..=max_rank)
        .filter_map(|r| {
            let v: Vec<f64> = pts.iter().filter(|p| p.0 == r).map(|p| p.1).collect();
            (!v.is_empty()).then(|| (r as f64, v.iter().sum::<f64>() / v.len() as f64))
        })
        .collect();
    let paper = d.pipeline.report.paper_figures && !slow;
    let panel = Panel {
        points: groups,
        lines: vec![Line { label: "mean across seeds".into(), points: means, colour: colour(1), width: 3, alpha: 1.0 }],
        hlines: if paper {
            vec![HLine { y: 25.8, text: "paper: S1→S2 25.8 ms".into(), colour: BLACK }]
        } else {
            vec![]
        },
        x_ticks: Some(rank_ticks),
        ..Panel::linear("main shock", format!("time since the previous main shock ({unit})"))
    };
    drawn(
        path,
        &Sheet::new("Recurrence between main shocks", 1, vec![panel]),
        "Recurrence of the main shocks".into(),
        format!(
            "Time from the start of the previous main shock, per main shock across seeds (points jittered sideways), \
             the mean per rank{}.",
            if paper { ", and the paper's S1→S2 recurrence" } else { "" }
        ),
    )
}

fn magnitude(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(sim) = &d.similarity else { return Ok(Outcome::Skipped("no similarity table".into())) };
    let (m, mw) = (&sim.m_riera_paper_interplate, &sim.mw_consistent);
    let idx: Vec<(usize, u32)> =
        (0..sim.kind.len()).filter(|&i| sim.kind[i].is_main()).filter_map(|i| Some((i, sim.kind[i].rank()?))).collect();
    if idx.is_empty() {
        return Ok(Outcome::Skipped("no main shocks".into()));
    }
    let lambda = sim.lambda.first().copied().unwrap_or(f64::NAN);
    let groups = vec![
        Points {
            label: "Riera M, paper's M0 (Eq. 15)".into(),
            points: idx.iter().enumerate().map(|(k, (i, r))| (*r as f64 + jitter(k), m[*i])).collect(),
            colour: colour(0),
            size: 5,
        },
        Points {
            label: "Mw, consistent M0".into(),
            points: idx.iter().enumerate().map(|(k, (i, r))| (*r as f64 + jitter(k), mw[*i])).collect(),
            colour: colour(2),
            size: 5,
        },
    ];
    let paper = d.pipeline.report.paper_figures;
    let panel = Panel {
        points: groups,
        hlines: if paper {
            vec![HLine { y: 6.77, text: "paper: M = 6.77 (S2)".into(), colour: BLACK }]
        } else {
            vec![]
        },
        x_ticks: Some(rank_ticks),
        ..Panel::linear("main shock", "magnitude")
    };
    drawn(
        path,
        &Sheet::new(format!("Magnitude of the main shocks at prototype scale (λ = {lambda:.0})"), 1, vec![panel]),
        "Magnitude per main shock".into(),
        format!(
            "Riera et al.'s magnitude from the paper's seismic moment (Eq. 15, with its extra factor λ) and the moment \
             magnitude Mw from the dimensionally consistent moment Δσ·L_p·A_p, for every main shock of every seed{}.",
            if paper { ", against the paper's M = 6.77 for S2" } else { "" }
        ),
    )
}

fn attenuation(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(att) = &d.attenuation else { return Ok(Outcome::Skipped("no attenuation stage".into())) };
    if att.is_empty() {
        return Ok(Outcome::Skipped("no main shock with a hypocentre".into()));
    }
    let (label, dist, pga) = (&att.label, &att.distance_m, &att.pga_m_s2);
    let ok = |i: usize| dist[i] > 0.0 && pga[i] > 0.0;
    let max_rank = label.iter().filter_map(|l| rank_of(l)).max().unwrap_or(0);
    let groups: Vec<Points> = (1..=max_rank)
        .map(|r| Points {
            label: format!("S{r}"),
            points: (0..att.len())
                .filter(|&i| ok(i) && rank_of(&label[i]) == Some(r))
                .map(|i| (dist[i].log10(), pga[i].log10()))
                .collect(),
            colour: colour(r as usize - 1),
            size: 5,
        })
        .collect();
    let mut lines = Vec::new();
    let mut fit_text = String::from("no fit");
    if let Some(fit) = &d.attenuation_fit {
        let (g, m) = (&fit.group, &fit.measure);
        let (a, b, r2) = (&fit.intercept, &fit.slope, &fit.r2);
        if let Some(i) = (0..g.len()).find(|&i| g[i] == "main" && m[i] == col::PGA_M_S2) {
            let xs: Vec<f64> = (0..att.len()).filter(|&i| ok(i)).map(|i| dist[i].log10()).collect();
            let (x0, x1) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
            lines.push(Line {
                label: format!("fit: log PGA = {:.2} {:+.2}·log R (r² = {:.2})", a[i], b[i], r2[i]),
                points: vec![(x0, a[i] + b[i] * x0), (x1, a[i] + b[i] * x1)],
                colour: BLACK,
                width: 3,
                alpha: 1.0,
            });
            fit_text = format!("log10 PGA = {:.3} {:+.3}·log10 R, r² = {:.2}", a[i], b[i], r2[i]);
        }
    }
    let panel = Panel { points: groups, lines, ..Panel::linear("log10 distance (m)", "log10 PGA (m/s²)") };
    drawn(
        path,
        &Sheet::new("Peak acceleration against distance from the hypocentre", 1, vec![panel]),
        "Attenuation of peak acceleration".into(),
        format!(
            "Peak magnitude of the recorded acceleration of every control node during every main shock, against its \
             distance from the shock's hypocentre (the first contact node to slide for good), all seeds, model scale; \
             least-squares line over all main shocks: {fit_text}. The block is 1 m long, so these are near-field \
             distances; g = {G} m/s²."
        ),
    )
}

fn energy(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(&seed) = d.seeds.first() else { return Ok(Outcome::Skipped("no successful seed".into())) };
    let Some(df) = d.part(&SERIES, seed)? else { return Ok(Outcome::Skipped("no series".into())) };
    if read_series_channel(&df, Channel::ExternalWork.name())?.is_none() {
        return Ok(Outcome::Skipped("energy not recorded (record.energy = false)".into()));
    }
    let terms = [
        ("external work", Channel::ExternalWork),
        ("friction dissipated", Channel::FrictionDissipated),
        ("damping dissipated", Channel::DampingDissipated),
        ("elastic", Channel::Elastic),
        ("kinetic", Channel::Kinetic),
        ("lost in landings", Channel::ImpactDissipated),
        ("balance residual", Channel::EnergyResidual),
    ];
    let fracture = read_series_channel(&df, Channel::FractureDissipated.name())?.is_some();
    let terms: Vec<(&str, Channel)> =
        terms.into_iter().chain(fracture.then_some(("fracture dissipated", Channel::FractureDissipated))).collect();
    let mut lines = Vec::new();
    let mut residual = 0.0f64;
    let mut work = 0.0f64;
    for (k, (name, channel)) in terms.iter().enumerate() {
        let (t, v) =
            read_series_channel(&df, channel.name())?.expect("every energy channel is recorded with the others");
        let v: Vec<f64> = v.iter().map(|x| x * 1e3).collect();
        if *channel == Channel::EnergyResidual {
            residual = v.iter().fold(0.0, |m, x| m.max(x.abs()));
        }
        if *channel == Channel::ExternalWork {
            work = v.last().copied().unwrap_or(0.0);
        }
        lines.push(Line::new(*name, decimate(&t, &v, WIDTH as usize), k));
    }
    let panel = Panel {
        lines,
        ..Panel::linear("time since the start of shearing (s)", "energy since the start of the run (mJ)")
    };
    drawn(
        path,
        &Sheet::new(format!("Energy balance, seed {seed}"), 1, vec![panel]),
        "Energy terms".into(),
        format!(
            "Cumulative work of gravity and the driver against what is stored (elastic, kinetic) and dissipated \
             (damping, friction, landings) for seed {seed}, counted from the start of the self-weight stage. The largest \
             |residual| is {residual:.2e} mJ against {work:.3} mJ of external work: the balance closes to round-off."
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::{envelope, spread};

    #[test]
    fn the_envelope_keeps_each_columns_extremes() {
        // A sawtooth of 1,000 teeth over 100 columns: every column spans the whole tooth.
        let t: Vec<f64> = (0..100_000).map(|i| i as f64 * 1e-3).collect();
        let y: Vec<f64> = (0..100_000).map(|i| (i % 100) as f64).collect();
        let e = envelope(&t, &y, 100);
        assert_eq!(e.len(), 100);
        assert!(e.iter().all(|&(_, lo, hi)| lo == 0.0 && hi == 99.0), "{:?}", &e[..3]);
        // Column centres span the record.
        assert!((e[0].0 - 0.4999).abs() < 1e-3 && (e[99].0 - 99.4995).abs() < 1e-2, "{} {}", e[0].0, e[99].0);
    }

    #[test]
    fn a_subset_of_nodes_spans_the_recorded_ones() {
        assert_eq!(spread(2, 3), vec![0, 1], "all of them when few");
        assert_eq!(spread(12, 3), vec![0, 6, 11]);
        assert_eq!(spread(4, 3), vec![0, 2, 3]);
        assert_eq!(spread(5, 1), vec![0]);
        for total in 1..40 {
            for max in 1..6 {
                let s = spread(total, max);
                assert_eq!(s.len(), total.min(max));
                assert!(s.windows(2).all(|w| w[0] < w[1]), "{total} {max}: {s:?}");
                assert_eq!(s[0], 0);
                if max > 1 {
                    assert_eq!(*s.last().unwrap(), total - 1, "{total} {max}: the last node is shown");
                }
            }
        }
    }
}
