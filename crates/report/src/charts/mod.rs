//! The chart layer every figure draws with: a [`Sheet`] of one or more [`Panel`]s (a grid), each
//! panel with linear or log axes holding lines, shaded bands, point groups, markers and
//! horizontal reference lines, plus a legend and a panel name.
//!
//! Two rules hold for everything drawn here, so a new figure gets them for free:
//!
//! - **Nothing leaves the plotting area.** Plotters positions elements in a drawing area but does
//!   not clip them, and it joins wide polylines with uncapped mitres: at a sharp reversal (the
//!   min/max pairs of a decimated trace) the inner join lies hundreds of pixels away, which drew
//!   a vertical line through the title of the shear-stress figure. So data are mapped to pixels
//!   here (in f64, through the log transform on log axes), polylines are broken at non-finite
//!   points and clipped to the plotting area ([`crate::clip`], Liang–Barsky), bands are clipped as
//!   polygons, and plotters only draws 1-px segments (a wide line is a square brush of 1-px
//!   copies, clipped again). Markers and points are drawn only when they lie wholly inside.
//! - **Labels go where no data is.** Every text a panel places — marker labels, reference-line
//!   labels, the panel name, the legend — is a box of its size in the chart's font, put by the
//!   rule of [`crate::place`]: the candidate covering the fewest data pixels and no other label.
//!   A reference-line label that cannot find a free spot goes in the right margin beside its
//!   line, a panel name or legend above the axes (the panel is redrawn with that space
//!   reserved); a marker label with no free spot near its triangle is dropped (listed in
//!   [`DrawnPanel::dropped`]).
//!
//! [`render`] draws into memory and returns what it drew ([`Drawn`]: each panel's plotting area
//! in pixels, where every label went, the data mask) so tests can check both rules on the
//! pixels; [`draw`] also writes the PNG.

use std::path::Path;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::clip::{ClipRect, clip_polygon, clip_polyline};
use crate::error::ReportError;
use crate::place::{Occupancy, PixelBox, along_hline, around_point, choose, in_area};
use crate::plot::{FONT, LABEL, TICK, TITLE, fmt_tick, log_range, log_ticks, padded_range};

mod sheet;

pub use sheet::{Band, Drawn, DrawnPanel, HLine, Image, Line, Marker, Panel, PlacedLabel, Points, Scale, Sheet};

/// Draws `sheet` into a PNG at `path`.
pub fn draw(path: &Path, sheet: &Sheet) -> Result<Drawn, ReportError> {
    let (image, drawn) = render(sheet).map_err(|e| match e {
        ReportError::Plot { what, .. } => ReportError::Plot { figure: path.display().to_string(), what },
        e => e,
    })?;
    image.save_png(path)?;
    Ok(drawn)
}

/// Space a panel keeps outside its axes for labels that found no free spot inside.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Reserve {
    /// A strip between the panel's heading and its axes (legend, name).
    top: i32,
    /// A right margin (reference-line labels).
    right: i32,
}

/// Which of a panel's labels go outside the axes. Only ever switched on, so the passes of
/// [`render`] end.
#[derive(Clone, Debug, Default)]
struct Outside {
    legend: bool,
    name: bool,
    hlines: Vec<bool>,
}

/// Draws `sheet` into memory: the image and what was drawn where.
pub fn render(sheet: &Sheet) -> Result<(Image, Drawn), ReportError> {
    crate::plot::register_fonts();
    let n = sheet.panels.len();
    let mut outside: Vec<Outside> =
        sheet.panels.iter().map(|p| Outside { hlines: vec![false; p.hlines.len()], ..Outside::default() }).collect();
    let mut reserves = vec![Reserve::default(); n];
    // Each pass draws everything; a label that finds no free spot inside switches to outside,
    // and the panel is drawn again with room for it. Decisions only switch one way, so this
    // ends after at most one pass per label; six passes is plenty in practice.
    for pass in 0..6 {
        let mut rgb = vec![255u8; 3 * sheet.width as usize * sheet.height as usize];
        let mut panels = Vec::with_capacity(n);
        let mut wanted = Vec::with_capacity(n);
        {
            let root = BitMapBackend::with_buffer(&mut rgb, (sheet.width, sheet.height)).into_drawing_area();
            root.fill(&WHITE).map_err(fail)?;
            let body = if sheet.title.is_empty() {
                root.clone()
            } else {
                root.titled(&sheet.title, (FONT, TITLE)).map_err(fail)?
            };
            let cols = sheet.columns.max(1);
            let areas = body.split_evenly((n.div_ceil(cols).max(1), cols));
            let caption = if n > 1 { TITLE - 6 } else { TITLE };
            for ((panel, area), (out, reserve)) in
                sheet.panels.iter().zip(&areas).zip(outside.iter_mut().zip(&reserves))
            {
                let (drawn, want) = draw_panel(&root, area, panel, caption, *reserve, out)?;
                panels.push(drawn);
                wanted.push(want);
            }
            root.present().map_err(fail)?;
        }
        if wanted == reserves || pass == 5 {
            return Ok((Image { width: sheet.width, height: sheet.height, rgb }, Drawn { panels }));
        }
        reserves = wanted;
    }
    unreachable!("the last pass returns")
}

fn fail(e: impl std::fmt::Display) -> ReportError {
    ReportError::Plot { figure: "chart".into(), what: e.to_string() }
}

/// Value → pixel along one axis (f64, so points far outside stay exact for clipping).
#[derive(Clone, Copy, Debug)]
struct Axis {
    lo: f64,
    hi: f64,
    log: bool,
    /// Pixels of `lo` and `hi` (as plotters maps them: the first and last pixel of the area).
    p0: f64,
    p1: f64,
}

impl Axis {
    fn px(&self, v: f64) -> Option<f64> {
        if !v.is_finite() || (self.log && v <= 0.0) {
            return None;
        }
        let f = if self.log {
            (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        };
        Some(self.p0 + f * (self.p1 - self.p0))
    }
}

/// The pixel frame of one panel's axes.
struct Frame {
    x: Axis,
    y: Axis,
    /// The plotting area.
    area: PixelBox,
    /// The same, closed, in f64: what everything is clipped to.
    clip: ClipRect,
}

impl Frame {
    /// A data point in pixels (NaN where it cannot be drawn, which breaks a polyline).
    fn px(&self, p: (f64, f64)) -> (f64, f64) {
        match (self.x.px(p.0), self.y.px(p.1)) {
            (Some(x), Some(y)) => (x, y),
            _ => (f64::NAN, f64::NAN),
        }
    }

    /// Whether a box of half-size `r` around pixel `c` lies wholly inside.
    fn holds(&self, c: (f64, f64), r: f64) -> bool {
        c.0.is_finite()
            && c.1.is_finite()
            && self.clip.contains((c.0 - r, c.1 - r))
            && self.clip.contains((c.0 + r, c.1 + r))
    }
}

/// Clearance kept free around data for labels (px).
const CLEAR: i32 = 2;
/// Padding inside a label's box (px).
const PAD: i32 = 3;

fn range(scale: Scale, values: impl Iterator<Item = f64>) -> (f64, f64) {
    match scale {
        Scale::Linear => padded_range(values),
        Scale::Log => log_range(values),
    }
}

/// Largest magnitude an axis spans: plotters' tick search does not end on an infinite or
/// overflowing range (a friction coefficient of 1.8e308 padded by 5% is infinite).
const AXIS_LIMIT: f64 = 1e300;

/// An axis range plotters can draw: finite, increasing, within ±[`AXIS_LIMIT`] (positive on a log
/// axis); anything else falls back to the unit range.
fn drawable((lo, hi): (f64, f64), scale: Scale) -> (f64, f64) {
    let (lo, hi) = (lo.clamp(-AXIS_LIMIT, AXIS_LIMIT), hi.clamp(-AXIS_LIMIT, AXIS_LIMIT));
    let ok = lo.is_finite() && hi.is_finite() && hi > lo && (hi - lo).is_finite();
    match scale {
        Scale::Linear if ok => (lo, hi),
        Scale::Log if ok && lo > 0.0 => (lo.max(1.0 / AXIS_LIMIT), hi),
        Scale::Linear => (0.0, 1.0),
        Scale::Log => (0.1, 1.0),
    }
}

/// Draws a 1-px polyline (already clipped, pixel coordinates).
fn stroke_1px(
    root: &DrawingArea<BitMapBackend<'_>, Shift>,
    run: &[(f64, f64)],
    style: ShapeStyle,
) -> Result<(), ReportError> {
    let pts: Vec<(i32, i32)> = run.iter().map(|p| (p.0.round() as i32, p.1.round() as i32)).collect();
    root.draw(&PathElement::new(pts, style)).map_err(fail)
}

/// Draws a polyline `width` px wide, clipped to the frame, and marks it in `data`. A wide line
/// is a square brush: `width²` copies of the 1-px line shifted by whole pixels, each clipped
/// (no joins, so no mitre can reach outside).
fn stroke(
    root: &DrawingArea<BitMapBackend<'_>, Shift>,
    f: &Frame,
    points: &[(f64, f64)],
    colour: RGBColor,
    width: u32,
    alpha: f64,
    data: &mut Occupancy,
) -> Result<(), ReportError> {
    let px: Vec<(f64, f64)> = points.iter().map(|&p| f.px(p)).collect();
    let style = colour.mix(alpha).stroke_width(1);
    let w = width.max(1) as i32;
    let offsets: Vec<i32> = (0..w).map(|k| k - (w - 1) / 2).collect();
    for run in clip_polyline(&px, &f.clip) {
        for pair in run.windows(2) {
            data.mark_segment(pair[0], pair[1], w / 2 + CLEAR);
        }
        if w == 1 {
            stroke_1px(root, &run, style)?;
            continue;
        }
        for &dx in &offsets {
            for &dy in &offsets {
                let shifted: Vec<(f64, f64)> = run.iter().map(|p| (p.0 + dx as f64, p.1 + dy as f64)).collect();
                for part in clip_polyline(&shifted, &f.clip) {
                    stroke_1px(root, &part, style)?;
                }
            }
        }
    }
    Ok(())
}

/// Draws a band clipped to the frame and marks its pixels.
fn fill_band(
    root: &DrawingArea<BitMapBackend<'_>, Shift>,
    f: &Frame,
    band: &Band,
    data: &mut Occupancy,
) -> Result<(), ReportError> {
    // Runs of points that map to pixels (a NaN or, on a log axis, a non-positive bound breaks it).
    let px: Vec<Option<(f64, f64, f64)>> =
        band.points.iter().map(|&(x, lo, hi)| Some((f.x.px(x)?, f.y.px(lo)?, f.y.px(hi)?))).collect();
    for run in px.split(|p| p.is_none()) {
        let run: Vec<(f64, f64, f64)> = run.iter().flatten().copied().collect();
        if run.len() < 2 {
            continue;
        }
        let mut poly: Vec<(f64, f64)> = run.iter().map(|p| (p.0, p.2)).collect();
        poly.extend(run.iter().rev().map(|p| (p.0, p.1)));
        let clipped = clip_polygon(&poly, &f.clip);
        if clipped.len() >= 3 {
            let pts: Vec<(i32, i32)> = clipped.iter().map(|p| (p.0.round() as i32, p.1.round() as i32)).collect();
            root.draw(&Polygon::new(pts, band.colour.mix(0.25).filled())).map_err(fail)?;
        }
        // Its pixels, column by column between neighbouring samples.
        for w in run.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (xa, xb) = (a.0.min(b.0).max(f.clip.x0), a.0.max(b.0).min(f.clip.x1));
            let mut x = xa.ceil();
            while x <= xb {
                let t = if b.0 != a.0 { (x - a.0) / (b.0 - a.0) } else { 0.0 };
                let (lo, hi) = (a.1 + t * (b.1 - a.1), a.2 + t * (b.2 - a.2));
                let (top, bottom) = (lo.min(hi).max(f.clip.y0), lo.max(hi).min(f.clip.y1));
                if top <= bottom {
                    // One pixel more on every side: plotters fills the polygon of rounded
                    // vertices, which can reach half a pixel past the exact edge.
                    data.mark_box(PixelBox {
                        x0: x as i32 - 1,
                        y0: top.floor() as i32 - 1,
                        x1: x as i32 + 2,
                        y1: bottom.ceil() as i32 + 2,
                    });
                }
                x += 1.0;
            }
        }
    }
    Ok(())
}

/// A text item to place: its text, colour, and box size with padding.
struct TextItem {
    text: String,
    colour: RGBColor,
    size: (i32, i32),
}

fn text_item(
    root: &DrawingArea<BitMapBackend<'_>, Shift>,
    text: &str,
    colour: RGBColor,
) -> Result<TextItem, ReportError> {
    let (w, h) = root.estimate_text_size(text, &(FONT, TICK).into_font().into()).map_err(fail)?;
    Ok(TextItem { text: text.to_string(), colour, size: (w as i32 + 2 * PAD, h as i32 + 2 * PAD) })
}

fn put_text(root: &DrawingArea<BitMapBackend<'_>, Shift>, item: &TextItem, at: &PixelBox) -> Result<(), ReportError> {
    let style = (FONT, TICK).into_font().color(&item.colour).pos(Pos::new(HPos::Left, VPos::Top));
    root.draw(&Text::new(item.text.clone(), (at.x0 + PAD, at.y0 + PAD), style)).map_err(fail)
}

/// A legend entry: its sample glyph and text.
enum Sample {
    Line(RGBColor),
    Patch(RGBColor),
    Dot(RGBColor, u32),
}

/// Width of a legend entry's sample glyph and the gap after it (px).
const SAMPLE_W: i32 = 26;
const SAMPLE_GAP: i32 = 6;

fn draw_sample(root: &DrawingArea<BitMapBackend<'_>, Shift>, s: &Sample, x: i32, y: i32) -> Result<(), ReportError> {
    match s {
        Sample::Line(c) => root.draw(&Rectangle::new([(x, y - 1), (x + SAMPLE_W - 2, y + 1)], c.filled())),
        Sample::Patch(c) => root.draw(&Rectangle::new([(x, y - 6), (x + SAMPLE_W - 2, y + 6)], c.mix(0.25).filled())),
        Sample::Dot(c, r) => root.draw(&Circle::new((x + SAMPLE_W / 2, y), (*r).min(6) as i32, c.filled())),
    }
    .map_err(fail)
}

/// Builds the axes of `panel` in `area`, draws its mesh, and returns the plotting area.
fn axes(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    panel: &Panel,
    x: (f64, f64),
    y: (f64, f64),
    reserve_right: i32,
) -> Result<PixelBox, ReportError> {
    let has_x_desc = !panel.x_desc.is_empty();
    let x_area = match (panel.x_tick_labels, has_x_desc) {
        (false, _) => 8,
        (true, false) => 35,
        (true, true) => {
            if panel.compact {
                55
            } else {
                60
            }
        }
    };
    let mut builder = ChartBuilder::on(area);
    builder
        .margin_left(18)
        .margin_right(18 + reserve_right)
        .margin_top(if panel.compact { 4 } else { 10 })
        .margin_bottom(if panel.compact { 2 } else { 8 })
        .x_label_area_size(x_area)
        .y_label_area_size(95);
    let no_label = |_: &f64| String::new();
    let x_fmt: &dyn Fn(&f64) -> String = match (panel.x_tick_labels, panel.x_ticks.as_ref()) {
        (false, _) => &no_label,
        (true, Some(f)) => f,
        (true, None) => &fmt_tick,
    };
    let desc = if panel.compact { TICK + 2 } else { LABEL };
    let light = if panel.minor_grid { RGBColor(235, 235, 235).mix(1.0) } else { WHITE.mix(0.0) };
    // A linear axis has grid lines at its labels only (plotters' default of ten minor lines per
    // label drew dense bands, as on the magnitude axis); a log axis has its own minor lines below.
    let light_lines = |scale: Scale| if scale == Scale::Linear { 1 } else { 10 };
    macro_rules! mesh {
        ($xspec:expr, $yspec:expr) => {{
            let mut chart = builder.build_cartesian_2d($xspec, $yspec).map_err(fail)?;
            let mut mesh = chart.configure_mesh();
            mesh.y_desc(panel.y_desc.as_str())
                .axis_desc_style((FONT, desc))
                .label_style((FONT, TICK))
                .x_label_formatter(x_fmt)
                .y_label_formatter(&fmt_tick)
                .light_line_style(light)
                .x_max_light_lines(light_lines(panel.x_scale))
                .y_max_light_lines(light_lines(panel.y_scale));
            if has_x_desc && panel.x_tick_labels {
                mesh.x_desc(panel.x_desc.as_str());
            }
            if panel.x_ticks.is_some() {
                mesh.x_labels(((x.1 - x.0).round() as usize + 1).min(20));
            }
            if let Some(n) = panel.y_tick_count {
                mesh.y_labels(if panel.y_scale == Scale::Linear { label_hint(y, n) } else { n });
            }
            mesh.draw().map_err(fail)?;
            chart.plotting_area().get_pixel_range()
        }};
    }
    // Log axes: labels at round values only, minor grid lines at the other multiples
    // (plotters' own log ticks crowd each other and draw dense bands of minor lines).
    let (xb, xl) = log_ticks(x.0, x.1);
    let (yb, yl) = log_ticks(y.0, y.1);
    let (xr, yr) = match (panel.x_scale, panel.y_scale) {
        (Scale::Linear, Scale::Linear) => mesh!(x.0..x.1, y.0..y.1),
        (Scale::Log, Scale::Log) => mesh!(
            (x.0..x.1).log_scale().with_key_points(xb).with_light_points(xl),
            (y.0..y.1).log_scale().with_key_points(yb).with_light_points(yl)
        ),
        (Scale::Linear, Scale::Log) => {
            mesh!(x.0..x.1, (y.0..y.1).log_scale().with_key_points(yb).with_light_points(yl))
        }
        (Scale::Log, Scale::Linear) => {
            mesh!((x.0..x.1).log_scale().with_key_points(xb).with_light_points(xl), y.0..y.1)
        }
    };
    Ok(PixelBox { x0: xr.start, y0: yr.start, x1: xr.end, y1: yr.end })
}

/// The label count to ask plotters for so that a linear axis over `y` asked for `n` labels gets
/// at least 3 (0 and one each side on a symmetric axis): plotters' search can give fewer than
/// asked (one, 0 alone, on ±4…5 asked for 3), so the count is raised until it gives 3, to `2n + 1`
/// at most.
pub fn label_hint(y: (f64, f64), n: usize) -> usize {
    if !(y.0.is_finite() && y.1.is_finite() && y.1 > y.0) {
        return n;
    }
    let axis = RangedCoordf64::from(y.0..y.1);
    (n..=2 * n + 1).find(|&hint| axis.key_points(hint).len() >= 3.min(n)).unwrap_or(n)
}

/// Draws one panel into `area` (drawing on `root` in image pixels) and returns what it drew and
/// the room it wants outside its axes.
fn draw_panel(
    root: &DrawingArea<BitMapBackend<'_>, Shift>,
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    panel: &Panel,
    caption: u32,
    reserve: Reserve,
    out: &mut Outside,
) -> Result<(DrawnPanel, Reserve), ReportError> {
    let (img_w, img_h) = root.dim_in_pixel();
    let xs = panel
        .lines
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.0))
        .chain(panel.bands.iter().flat_map(|b| b.points.iter().map(|p| p.0)))
        .chain(panel.points.iter().flat_map(|g| g.points.iter().map(|p| p.0)))
        .chain(panel.markers.iter().map(|m| m.at.0));
    let x = drawable(panel.x_range.unwrap_or_else(|| range(panel.x_scale, xs)), panel.x_scale);
    let ys = panel
        .lines
        .iter()
        .flat_map(|l| l.points.iter().map(|p| p.1))
        .chain(panel.bands.iter().flat_map(|b| b.points.iter().flat_map(|p| [p.1, p.2])))
        .chain(panel.points.iter().flat_map(|g| g.points.iter().map(|p| p.1)))
        .chain(panel.markers.iter().map(|m| m.at.1))
        .chain(panel.hlines.iter().map(|h| h.y));
    let mut y = panel.y_range.unwrap_or_else(|| range(panel.y_scale, ys));
    // Headroom over the data for the labels of markers (a peak's marker sits at the top of the
    // trace, and its label goes above it): a tenth of the height more.
    if panel.y_range.is_none() && panel.y_scale == Scale::Linear && panel.markers.iter().any(|m| !m.text.is_empty()) {
        y.1 += 0.1 * (y.1 - y.0);
    }
    if panel.symmetric_y && panel.y_scale == Scale::Linear {
        let m = y.0.abs().max(y.1.abs());
        y = (-m, m);
    }
    let y = drawable(y, panel.y_scale);

    // Heading, the strip kept for outside labels, then the axes.
    let mut rest = area.clone();
    if !panel.title.is_empty() {
        rest = rest.titled(&panel.title, (FONT, caption)).map_err(fail)?;
    }
    let (strip_x, strip_y) = rest.get_pixel_range();
    let strip = PixelBox { x0: strip_x.start, y0: strip_y.start, x1: strip_x.end, y1: strip_y.start + reserve.top };
    let (_, below) = rest.split_vertically(reserve.top);
    let plot = axes(&below, panel, x, y, reserve.right)?;
    let f = Frame {
        x: Axis { lo: x.0, hi: x.1, log: panel.x_scale == Scale::Log, p0: plot.x0 as f64, p1: (plot.x1 - 1) as f64 },
        y: Axis { lo: y.0, hi: y.1, log: panel.y_scale == Scale::Log, p0: (plot.y1 - 1) as f64, p1: plot.y0 as f64 },
        area: plot,
        clip: ClipRect { x0: plot.x0 as f64, y0: plot.y0 as f64, x1: (plot.x1 - 1) as f64, y1: (plot.y1 - 1) as f64 },
    };
    let mut data = Occupancy::new(img_w, img_h);

    // Data: thin lines, bands, reference lines, bold lines (with dots), points, markers.
    let (thin, bold): (Vec<&Line>, Vec<&Line>) = panel.lines.iter().partition(|l| l.width <= 1);
    for l in &thin {
        stroke(root, &f, &l.points, l.colour, l.width, l.alpha, &mut data)?;
    }
    for b in &panel.bands {
        fill_band(root, &f, b, &mut data)?;
    }
    for h in &panel.hlines {
        let Some(py) = f.y.px(h.y).filter(|py| *py >= f.clip.y0 && *py <= f.clip.y1) else { continue };
        let style = h.colour.stroke_width(1);
        let mut x0 = f.clip.x0;
        while x0 < f.clip.x1 {
            let x1 = (x0 + 10.0).min(f.clip.x1);
            for dy in [0.0, 1.0] {
                let yy = (py + dy).min(f.clip.y1);
                stroke_1px(root, &[(x0, yy), (x1, yy)], style)?;
            }
            x0 += 16.0;
        }
        data.mark_segment((f.clip.x0, py), (f.clip.x1, py), 1 + CLEAR);
    }
    for l in &bold {
        stroke(root, &f, &l.points, l.colour, l.width, l.alpha, &mut data)?;
        if panel.dots {
            for p in l.points.iter().map(|&p| f.px(p)).filter(|&c| f.holds(c, 5.0)) {
                let c = (p.0.round() as i32, p.1.round() as i32);
                root.draw(&Circle::new(c, 5, l.colour.filled())).map_err(fail)?;
                data.mark_box(PixelBox::at(c.0 - 5 - CLEAR, c.1 - 5 - CLEAR, (11 + 2 * CLEAR, 11 + 2 * CLEAR)));
            }
        }
    }
    for g in &panel.points {
        let r = g.size as i32;
        for c in g.points.iter().map(|&p| f.px(p)).filter(|&c| f.holds(c, r as f64)) {
            let c = (c.0.round() as i32, c.1.round() as i32);
            root.draw(&Circle::new(c, r, g.colour.mix(0.75).filled())).map_err(fail)?;
            data.mark_box(PixelBox::at(c.0 - r - CLEAR, c.1 - r - CLEAR, (2 * (r + CLEAR) + 1, 2 * (r + CLEAR) + 1)));
        }
    }
    const TRIANGLE: i32 = 9;
    let mut marker_px = Vec::new();
    for m in &panel.markers {
        let c = f.px(m.at);
        if !f.holds(c, TRIANGLE as f64) {
            continue;
        }
        let c = (c.0.round() as i32, c.1.round() as i32);
        root.draw(&TriangleMarker::new(c, TRIANGLE, m.colour.filled())).map_err(fail)?;
        data.mark_box(PixelBox::at(c.0 - TRIANGLE, c.1 - TRIANGLE, (2 * TRIANGLE + 1, 2 * TRIANGLE + 1)));
        marker_px.push((m, c));
    }

    // Labels, by the rule of crate::place: marker labels first (they belong to a spot), then the
    // reference-line labels, the panel name, the legend (the most movable).
    let mut placed: Vec<PlacedLabel> = Vec::new();
    let mut dropped: Vec<String> = Vec::new();
    let boxes = |placed: &[PlacedLabel]| placed.iter().map(|l| l.bbox).collect::<Vec<_>>();
    for (m, c) in marker_px.iter().filter(|(m, _)| !m.text.is_empty()) {
        let item = text_item(root, &m.text, m.text_colour)?;
        // Beside the triangle first, then further away above or below it.
        let mut cands = around_point(*c, TRIANGLE, 2, item.size);
        for k in 1..=4 {
            let up = item.size.1 * k + 4 * k;
            cands.extend(around_point((c.0, c.1 - up), TRIANGLE, 2, item.size).into_iter().take(3));
            cands.extend(around_point((c.0, c.1 + up), TRIANGLE, 2, item.size).into_iter().skip(5).take(3));
        }
        match choose(&cands, &plot, &data, &boxes(&placed)) {
            Some((i, 0)) => {
                put_text(root, &item, &cands[i])?;
                placed.push(PlacedLabel { text: item.text, bbox: cands[i], data_pixels: 0, outside: false });
            }
            // Every spot near it is on data or on another label: a label there could not be
            // read, and a label far away would name the wrong triangle.
            _ => dropped.push(item.text),
        }
    }
    let mut want = Reserve::default();
    let margin =
        PixelBox { x0: plot.x1 + 4, y0: area.get_pixel_range().1.start, x1: area.get_pixel_range().0.end, y1: plot.y1 };
    for (k, h) in panel.hlines.iter().enumerate().filter(|(_, h)| !h.text.is_empty()) {
        let Some(py) = f.y.px(h.y).filter(|py| *py >= f.clip.y0 && *py <= f.clip.y1) else { continue };
        let py = py.round() as i32;
        let item = text_item(root, &h.text, h.colour)?;
        if !out.hlines[k] {
            let cands = along_hline(py, plot.x0, plot.x1, 4, item.size);
            match choose(&cands, &plot, &data, &boxes(&placed)) {
                Some((i, 0)) => {
                    put_text(root, &item, &cands[i])?;
                    placed.push(PlacedLabel { text: item.text, bbox: cands[i], data_pixels: 0, outside: false });
                    continue;
                }
                _ => out.hlines[k] = true,
            }
        }
        // In the right margin, beside the end of its line (or just above or below it).
        want.right = want.right.max(item.size.0 + 8);
        let (w, hgt) = item.size;
        let cands: Vec<PixelBox> = [0, -hgt, hgt, -2 * hgt, 2 * hgt]
            .iter()
            .map(|d| PixelBox::at(plot.x1 + 6, py - hgt / 2 + d, (w, hgt)))
            .collect();
        match choose(&cands, &margin, &data, &boxes(&placed)) {
            Some((i, n)) => {
                put_text(root, &item, &cands[i])?;
                placed.push(PlacedLabel { text: item.text, bbox: cands[i], data_pixels: n, outside: true });
            }
            None if reserve.right >= want.right => dropped.push(item.text),
            None => {} // drawn in the next pass, with the margin
        }
    }

    // The panel name and the legend: inside where no data is, else in the strip above the axes.
    let mut strip_items: Vec<(TextItem, Option<Sample>)> = Vec::new();
    if !panel.name.is_empty() {
        let item = text_item(root, &panel.name, BLACK)?;
        let mut cands = in_area(&plot, 4, 12, item.size);
        if cands.len() > 1 {
            cands.swap(0, 1); // a name reads best at the upper left
        }
        let mut inside = false;
        if !out.name
            && let Some((i, 0)) = choose(&cands, &plot, &data, &boxes(&placed))
        {
            put_text(root, &item, &cands[i])?;
            placed.push(PlacedLabel { text: item.text.clone(), bbox: cands[i], data_pixels: 0, outside: false });
            inside = true;
        }
        if !inside {
            out.name = true;
            strip_items.push((item, None));
        }
    }
    if panel.legend {
        let mut entries: Vec<(TextItem, Sample)> = Vec::new();
        for l in panel.lines.iter().filter(|l| !l.label.is_empty()) {
            entries.push((text_item(root, &l.label, BLACK)?, Sample::Line(l.colour)));
        }
        for b in panel.bands.iter().filter(|b| !b.label.is_empty()) {
            entries.push((text_item(root, &b.label, BLACK)?, Sample::Patch(b.colour)));
        }
        for g in panel.points.iter().filter(|g| !g.label.is_empty()) {
            entries.push((text_item(root, &g.label, BLACK)?, Sample::Dot(g.colour, g.size)));
        }
        if !entries.is_empty() {
            let row_h = entries.iter().map(|e| e.0.size.1).max().unwrap_or(0);
            let w = entries.iter().map(|e| e.0.size.0).max().unwrap_or(0) + SAMPLE_W + SAMPLE_GAP + 2 * PAD;
            let size = (w, row_h * entries.len() as i32 + 2 * PAD);
            let cands = in_area(&plot, 6, 12, size);
            let mut inside = false;
            if !out.legend
                && let Some((i, 0)) = choose(&cands, &plot, &data, &boxes(&placed))
            {
                let b = cands[i];
                root.draw(&Rectangle::new([(b.x0, b.y0), (b.x1 - 1, b.y1 - 1)], WHITE.mix(0.9).filled()))
                    .map_err(fail)?;
                root.draw(&Rectangle::new([(b.x0, b.y0), (b.x1 - 1, b.y1 - 1)], BLACK.mix(0.5))).map_err(fail)?;
                for (k, (item, sample)) in entries.iter().enumerate() {
                    let top = b.y0 + PAD + k as i32 * row_h;
                    draw_sample(root, sample, b.x0 + 2 * PAD, top + row_h / 2)?;
                    let at = PixelBox::at(b.x0 + PAD + SAMPLE_W + SAMPLE_GAP, top, item.size);
                    put_text(root, item, &at)?;
                }
                let text = entries.iter().map(|e| e.0.text.as_str()).collect::<Vec<_>>().join(" | ");
                placed.push(PlacedLabel { text, bbox: b, data_pixels: 0, outside: false });
                inside = true;
            }
            if !inside {
                out.legend = true;
                strip_items.extend(entries.into_iter().map(|(t, s)| (t, Some(s))));
            }
        }
    }
    // The strip: the items flow left to right over the width of the axes, wrapping; an item wider
    // than the axes starts further left, over the tick labels (at the panel's own left edge at
    // most), so that it ends where the axes end rather than in the next panel or off the image.
    if !strip_items.is_empty() {
        let row_h = strip_items.iter().map(|e| e.0.size.1).max().unwrap_or(0);
        let left_edge = area.get_pixel_range().0.start;
        let (mut cx, mut row) = (plot.x0, 0);
        let mut spots = Vec::new();
        for (item, sample) in &strip_items {
            let w = item.size.0 + if sample.is_some() { SAMPLE_W + SAMPLE_GAP } else { 0 } + 8;
            if cx + w > plot.x1 && cx > plot.x0 {
                cx = plot.x0;
                row += 1;
            }
            if cx == plot.x0 && cx + w > plot.x1 {
                cx = (plot.x1 - w).max(left_edge);
            }
            spots.push((cx, row));
            cx += w;
        }
        want.top = (row + 1) * row_h + 4;
        if reserve.top >= want.top {
            for ((item, sample), (sx, r)) in strip_items.iter().zip(spots) {
                let top = strip.y0 + 2 + r * row_h;
                let mut tx = sx;
                if let Some(s) = sample {
                    draw_sample(root, s, sx + PAD, top + row_h / 2)?;
                    tx += SAMPLE_W + SAMPLE_GAP;
                }
                let b = PixelBox::at(tx, top, item.size);
                put_text(root, item, &b)?;
                placed.push(PlacedLabel {
                    text: item.text.clone(),
                    bbox: b,
                    data_pixels: data.count(&b),
                    outside: true,
                });
            }
        }
    }
    let want = Reserve { top: want.top.max(reserve.top), right: want.right.max(reserve.right) };
    Ok((DrawnPanel { area: f.area, name: panel.name.clone(), labels: placed, dropped, data }, want))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_axis_asked_for_three_labels_gets_three() {
        let labels = |m: f64| RangedCoordf64::from(-m..m).key_points(label_hint((-m, m), 3));
        // ±4.6 asked for 3 labels: plotters' own search gave 0 alone.
        assert_eq!(RangedCoordf64::from(-4.6..4.6).key_points(3), vec![0.0]);
        assert_eq!(labels(4.6), vec![-4.0, -2.0, 0.0, 2.0, 4.0]);
        assert_eq!(labels(2.4), vec![-2.0, 0.0, 2.0]);
        for m in [1e-7, 0.3, 0.99, 3.3, 4.0, 4.99, 9.99, 45.0, 77.0, 4e9] {
            let t = labels(m);
            assert!((3..=7).contains(&t.len()), "±{m}: {t:?}");
        }
    }

    /// A friction coefficient of 1.8e308 (a fuzzed pipeline) made the friction map's axis
    /// infinite, and plotters' tick search never ended: every such range is drawn at once.
    #[test]
    fn huge_or_infinite_ranges_are_drawn_at_once() {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            type Case = (Vec<(f64, f64)>, Option<(f64, f64)>, Scale);
            let cases: Vec<Case> = vec![
                (vec![(0.0, 0.3), (1.0, 1.7e308)], None, Scale::Linear),
                (vec![(0.0, -f64::MAX), (1.0, f64::MAX)], None, Scale::Linear),
                (vec![(0.0, 1.0), (1.0, 2.0)], Some((0.0, f64::INFINITY)), Scale::Linear),
                (vec![(0.0, 1.0), (1.0, 1.7e308)], None, Scale::Log),
            ];
            for (points, y_range, y_scale) in cases {
                let mut p = Panel::linear("x", "y");
                p.y_scale = y_scale;
                p.y_range = y_range;
                p.lines.push(Line::new("a", points, 0));
                render(&Sheet::new("t", 1, vec![p])).unwrap();
            }
            tx.send(()).unwrap();
        });
        assert!(rx.recv_timeout(std::time::Duration::from_secs(60)).is_ok(), "a chart took over a minute");
    }
}
