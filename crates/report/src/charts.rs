//! Chart shapes shared by the figures: lines on linear or log axes, stacked panels, strips and
//! scatters, each written to a PNG of the standard size.

use std::path::Path;

use plotters::coord::Shift;
pub use plotters::prelude::SeriesLabelPosition;
use plotters::prelude::*;

use super::plot::{FONT, LABEL, TICK, TITLE, canvas, colour, fmt_tick, log_range, padded_range, plot_err};
use crate::ReportError;

/// One polyline.
pub struct Line {
    /// Legend text (empty: no legend entry).
    pub label: String,
    /// Points.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub colour: RGBColor,
    /// Stroke width (px).
    pub width: u32,
    /// Opacity 0–1.
    pub alpha: f64,
}

impl Line {
    /// A line of palette colour `i`, 2 px.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, i: usize) -> Self {
        Line { label: label.into(), points, colour: colour(i), width: 2, alpha: 1.0 }
    }
}

/// A labelled point (e.g. a main shock marker).
pub struct Marker {
    /// Where.
    pub at: (f64, f64),
    /// Text beside it.
    pub text: String,
    /// Colour.
    pub colour: RGBColor,
}

/// A horizontal reference line with a label.
pub struct HLine {
    /// Ordinate.
    pub y: f64,
    /// Label.
    pub text: String,
    /// Colour.
    pub colour: RGBColor,
}

/// A shaded band between two curves sharing abscissae.
pub struct Band {
    /// (x, low, high).
    pub points: Vec<(f64, f64, f64)>,
    /// Colour (drawn at 25% opacity).
    pub colour: RGBColor,
    /// Legend text.
    pub label: String,
}

fn err(name: &str) -> impl Fn(String) -> ReportError + '_ {
    plot_err(name)
}

/// Draws the labels of `chart`'s series at `at`, in the report's legend style.
fn draw_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    at: SeriesLabelPosition,
    name: &str,
) -> Result<(), ReportError> {
    chart
        .configure_series_labels()
        .position(at)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.5))
        .label_font((FONT, TICK))
        .draw()
        .map_err(|e| err(name)(e.to_string()))
}

/// Lines on linear axes, with markers and horizontal references; the legend at `legend_at`.
#[allow(clippy::too_many_arguments)]
pub fn linear(
    path: &Path,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    lines: &[Line],
    markers: &[Marker],
    hlines: &[HLine],
    legend_at: SeriesLabelPosition,
) -> Result<(), ReportError> {
    let name = path.display().to_string();
    let root = canvas(path);
    let (x0, x1) = padded_range(lines.iter().flat_map(|l| l.points.iter().map(|p| p.0)));
    let (y0, y1) = padded_range(
        lines
            .iter()
            .flat_map(|l| l.points.iter().map(|p| p.1))
            .chain(hlines.iter().map(|h| h.y))
            .chain(markers.iter().map(|m| m.at.1)),
    );
    let mut chart = ChartBuilder::on(&root)
        .caption(title, (FONT, TITLE))
        .margin(18)
        .x_label_area_size(60)
        .y_label_area_size(95)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(&name)(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style((FONT, LABEL))
        .label_style((FONT, TICK))
        .x_label_formatter(&fmt_tick)
        .y_label_formatter(&fmt_tick)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| err(&name)(e.to_string()))?;
    for h in hlines {
        chart
            .draw_series(DashedLineSeries::new(vec![(x0, h.y), (x1, h.y)], 10, 6, h.colour.stroke_width(2)))
            .map_err(|e| err(&name)(e.to_string()))?;
        chart
            .draw_series(std::iter::once(Text::new(
                h.text.clone(),
                (x0 + 0.01 * (x1 - x0), h.y),
                (FONT, TICK).into_font().color(&h.colour),
            )))
            .map_err(|e| err(&name)(e.to_string()))?;
    }
    let mut legend = false;
    for l in lines {
        let style = l.colour.mix(l.alpha).stroke_width(l.width);
        let s = chart
            .draw_series(LineSeries::new(l.points.iter().copied(), style))
            .map_err(|e| err(&name)(e.to_string()))?;
        if !l.label.is_empty() {
            legend = true;
            let c = l.colour;
            s.label(l.label.clone())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], c.stroke_width(3)));
        }
    }
    for m in markers {
        chart
            .draw_series(std::iter::once(TriangleMarker::new(m.at, 9, m.colour.filled())))
            .map_err(|e| err(&name)(e.to_string()))?;
        chart
            .draw_series(std::iter::once(Text::new(
                m.text.clone(),
                (m.at.0, m.at.1 + 0.035 * (y1 - y0)),
                (FONT, TICK).into_font().color(&m.colour),
            )))
            .map_err(|e| err(&name)(e.to_string()))?;
    }
    if legend {
        draw_legend(&mut chart, legend_at, &name)?;
    }
    root.present().map_err(|e| err(&name)(e.to_string()))
}

/// One log-log panel.
pub struct Panel {
    /// Heading.
    pub title: String,
    /// Abscissa description.
    pub x_desc: String,
    /// Ordinate description.
    pub y_desc: String,
    /// Lines (width ≤ 1 drawn under the bands, the others over them).
    pub lines: Vec<Line>,
    /// Shaded bands.
    pub bands: Vec<Band>,
    /// Where the legend goes.
    pub legend_at: SeriesLabelPosition,
    /// Mark each point of the bold lines with a dot.
    pub dots: bool,
}

/// Draws a log-log panel into `area`.
fn loglog_into(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    name: &str,
    panel: &Panel,
    caption_size: u32,
) -> Result<(), ReportError> {
    let Panel { title, x_desc, y_desc, lines, bands, legend_at, dots } = panel;
    let (x0, x1) = log_range(lines.iter().flat_map(|l| l.points.iter().map(|p| p.0)));
    let (y0, y1) = log_range(
        lines
            .iter()
            .flat_map(|l| l.points.iter().map(|p| p.1))
            .chain(bands.iter().flat_map(|b| b.points.iter().flat_map(|p| [p.1, p.2]))),
    );
    let mut chart = ChartBuilder::on(area)
        .caption(title.as_str(), (FONT, caption_size))
        .margin(18)
        .x_label_area_size(60)
        .y_label_area_size(95)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(|e| err(name)(e.to_string()))?;
    chart
        .configure_mesh()
        .x_desc(x_desc.as_str())
        .y_desc(y_desc.as_str())
        .axis_desc_style((FONT, LABEL))
        .label_style((FONT, TICK))
        .x_label_formatter(&fmt_tick)
        .y_label_formatter(&fmt_tick)
        .draw()
        .map_err(|e| err(name)(e.to_string()))?;
    // Thin lines first, the bands over them, the bold lines on top.
    let (thin, bold): (Vec<&Line>, Vec<&Line>) = lines.iter().partition(|l| l.width <= 1);
    let mut legend = !bands.is_empty();
    for (bold_pass, group) in [(false, &thin), (true, &bold)] {
        if bold_pass {
            for b in bands {
                let mut poly: Vec<(f64, f64)> = b.points.iter().map(|p| (p.0, p.2)).collect();
                poly.extend(b.points.iter().rev().map(|p| (p.0, p.1)));
                let c = b.colour;
                chart
                    .draw_series(std::iter::once(Polygon::new(poly, c.mix(0.25).filled())))
                    .map_err(|e| err(name)(e.to_string()))?
                    .label(b.label.clone())
                    .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 24, y + 6)], c.mix(0.25).filled()));
            }
        }
        for l in group.iter() {
            let style = l.colour.mix(l.alpha).stroke_width(l.width);
            let s = chart
                .draw_series(LineSeries::new(l.points.iter().copied().filter(|p| p.0 > 0.0 && p.1 > 0.0), style))
                .map_err(|e| err(name)(e.to_string()))?;
            if !l.label.is_empty() {
                legend = true;
                let c = l.colour.mix(l.alpha.max(0.6));
                s.label(l.label.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], c.stroke_width(3)));
            }
            if bold_pass && *dots {
                let c = l.colour;
                chart
                    .draw_series(
                        l.points.iter().filter(|p| p.0 > 0.0 && p.1 > 0.0).map(|&p| Circle::new(p, 5, c.filled())),
                    )
                    .map_err(|e| err(name)(e.to_string()))?;
            }
        }
    }
    if legend {
        draw_legend(&mut chart, legend_at.clone(), name)?;
    }
    Ok(())
}

/// Lines and bands on log-log axes, in one or more side-by-side panels.
pub fn loglog_panels(path: &Path, panels: &[Panel]) -> Result<(), ReportError> {
    let name = path.display().to_string();
    let root = canvas(path);
    let areas = root.split_evenly((1, panels.len().max(1)));
    let size = if panels.len() > 1 { TITLE - 6 } else { TITLE };
    for (panel, area) in panels.iter().zip(&areas) {
        loglog_into(area, &name, panel, size)?;
    }
    root.present().map_err(|e| err(&name)(e.to_string()))
}

/// One small panel per series, stacked, sharing the x range (the paper's Figs. 6 and 7).
pub fn stacked(path: &Path, title: &str, x_desc: &str, y_desc: &str, panels: &[Line]) -> Result<(), ReportError> {
    let name = path.display().to_string();
    let root = canvas(path);
    let (top, rest) = root.split_vertically(50);
    top.titled(title, (FONT, TITLE)).map_err(|e| err(&name)(e.to_string()))?;
    let _ = top;
    let (x0, x1) = padded_range(panels.iter().flat_map(|l| l.points.iter().map(|p| p.0)));
    let areas = rest.split_evenly((panels.len().max(1), 1));
    for (k, (l, area)) in panels.iter().zip(&areas).enumerate() {
        let last = k + 1 == panels.len();
        let (y0, y1) = padded_range(l.points.iter().map(|p| p.1));
        let ymax = y0.abs().max(y1.abs());
        let mut chart = ChartBuilder::on(area)
            .margin_left(18)
            .margin_right(18)
            .margin_top(4)
            .x_label_area_size(if last { 55 } else { 8 })
            .y_label_area_size(95)
            .build_cartesian_2d(x0..x1, -ymax..ymax)
            .map_err(|e| err(&name)(e.to_string()))?;
        let no_label = |_: &f64| String::new();
        let mut mesh = chart.configure_mesh();
        mesh.y_desc(y_desc)
            .axis_desc_style((FONT, TICK + 2))
            .label_style((FONT, TICK))
            .y_labels(3)
            .y_label_formatter(&fmt_tick);
        mesh.light_line_style(WHITE.mix(0.0));
        if last {
            mesh.x_desc(x_desc).x_label_formatter(&fmt_tick);
        } else {
            mesh.x_label_formatter(&no_label);
        }
        mesh.draw().map_err(|e| err(&name)(e.to_string()))?;
        chart
            .draw_series(LineSeries::new(l.points.iter().copied(), l.colour.stroke_width(1)))
            .map_err(|e| err(&name)(e.to_string()))?;
        chart
            .draw_series(std::iter::once(Text::new(
                l.label.clone(),
                (x0 + 0.01 * (x1 - x0), 0.93 * ymax),
                (FONT, TICK).into_font().color(&l.colour),
            )))
            .map_err(|e| err(&name)(e.to_string()))?;
    }
    root.present().map_err(|e| err(&name)(e.to_string()))
}

/// A group of points for a scatter or strip plot.
pub struct Points {
    /// Legend text.
    pub label: String,
    /// Points.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub colour: RGBColor,
    /// Marker radius (px).
    pub size: u32,
}

/// Scatter plot with optional fitted lines and horizontal references; `x_ticks` labels
/// categorical abscissae; the legend at `legend_at`.
#[allow(clippy::too_many_arguments)]
pub fn scatter(
    path: &Path,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    groups: &[Points],
    lines: &[Line],
    hlines: &[HLine],
    x_ticks: Option<&dyn Fn(&f64) -> String>,
    legend_at: SeriesLabelPosition,
) -> Result<(), ReportError> {
    let name = path.display().to_string();
    let root = canvas(path);
    let (x0, x1) = padded_range(groups.iter().flat_map(|g| g.points.iter().map(|p| p.0)));
    let (y0, y1) =
        padded_range(groups.iter().flat_map(|g| g.points.iter().map(|p| p.1)).chain(hlines.iter().map(|h| h.y)));
    let mut chart = ChartBuilder::on(&root)
        .caption(title, (FONT, TITLE))
        .margin(18)
        .x_label_area_size(60)
        .y_label_area_size(95)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(&name)(e.to_string()))?;
    let fmt: &dyn Fn(&f64) -> String = x_ticks.unwrap_or(&fmt_tick);
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style((FONT, LABEL))
        .label_style((FONT, TICK))
        .x_label_formatter(fmt)
        .y_label_formatter(&fmt_tick)
        .light_line_style(WHITE.mix(0.0));
    if x_ticks.is_some() {
        mesh.x_labels(((x1 - x0).round() as usize + 1).min(20));
    }
    mesh.draw().map_err(|e| err(&name)(e.to_string()))?;
    for h in hlines {
        chart
            .draw_series(DashedLineSeries::new(vec![(x0, h.y), (x1, h.y)], 10, 6, h.colour.stroke_width(2)))
            .map_err(|e| err(&name)(e.to_string()))?;
        chart
            .draw_series(std::iter::once(Text::new(
                h.text.clone(),
                (x0 + 0.01 * (x1 - x0), h.y + 0.045 * (y1 - y0)),
                (FONT, TICK).into_font().color(&h.colour),
            )))
            .map_err(|e| err(&name)(e.to_string()))?;
    }
    for g in groups {
        let (c, size) = (g.colour, g.size);
        chart
            .draw_series(g.points.iter().map(|&p| Circle::new(p, size, c.mix(0.75).filled())))
            .map_err(|e| err(&name)(e.to_string()))?
            .label(g.label.clone())
            .legend(move |(x, y)| Circle::new((x + 10, y), size, c.filled()));
    }
    for l in lines {
        let c = l.colour;
        chart
            .draw_series(LineSeries::new(l.points.iter().copied(), c.stroke_width(l.width)))
            .map_err(|e| err(&name)(e.to_string()))?
            .label(l.label.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], c.stroke_width(3)));
    }
    draw_legend(&mut chart, legend_at, &name)?;
    root.present().map_err(|e| err(&name)(e.to_string()))
}
