//! What a chart is made of: a [`Sheet`] of [`Panel`]s holding lines, bands, points, markers and
//! reference lines; what rendering it drew ([`Drawn`]); and the image it drew into ([`Image`]).
//! The drawing itself is the parent module's.

use std::path::Path;

use plotters::style::RGBColor;

use crate::error::ReportError;
use crate::place::{Occupancy, PixelBox};
use crate::plot::{HEIGHT, WIDTH, colour};

/// One polyline.
#[derive(Clone, Debug)]
pub struct Line {
    /// Legend text (empty: no legend entry).
    pub label: String,
    /// Points in data coordinates; a non-finite point (or a non-positive one on a log axis)
    /// breaks the line.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub colour: RGBColor,
    /// Stroke width (px); lines of width ≤ 1 are drawn under the bands, the others over them.
    pub width: u32,
    /// Opacity 0–1 (of each 1-px copy: keep translucent lines 1 px wide).
    pub alpha: f64,
}

impl Line {
    /// A line of palette colour `i`, 2 px.
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, i: usize) -> Self {
        Line { label: label.into(), points, colour: colour(i), width: 2, alpha: 1.0 }
    }
}

/// A triangle marking a point (e.g. a main shock), with an optional label placed beside it.
#[derive(Clone, Debug)]
pub struct Marker {
    /// Where.
    pub at: (f64, f64),
    /// Text beside it (empty: none).
    pub text: String,
    /// Colour of the triangle.
    pub colour: RGBColor,
    /// Colour of the text.
    pub text_colour: RGBColor,
}

/// A dashed horizontal reference line with a label.
#[derive(Clone, Debug)]
pub struct HLine {
    /// Ordinate.
    pub y: f64,
    /// Label.
    pub text: String,
    /// Colour.
    pub colour: RGBColor,
}

/// A shaded band between two curves sharing abscissae.
#[derive(Clone, Debug)]
pub struct Band {
    /// (x, low, high).
    pub points: Vec<(f64, f64, f64)>,
    /// Colour (drawn at 25% opacity).
    pub colour: RGBColor,
    /// Legend text.
    pub label: String,
}

/// A group of points for a scatter or strip plot.
#[derive(Clone, Debug)]
pub struct Points {
    /// Legend text (empty: no legend entry).
    pub label: String,
    /// Points.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub colour: RGBColor,
    /// Marker radius (px).
    pub size: u32,
}

/// How an axis maps values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    /// Linear.
    Linear,
    /// Base-10 logarithmic (only positive values are drawn).
    Log,
}

/// One panel: axes and what they hold.
#[derive(Clone, Debug)]
pub struct Panel {
    /// Heading above the panel (empty: none).
    pub title: String,
    /// Abscissa description (empty: none).
    pub x_desc: String,
    /// Ordinate description.
    pub y_desc: String,
    /// Abscissa scale.
    pub x_scale: Scale,
    /// Ordinate scale.
    pub y_scale: Scale,
    /// Abscissa range; `None`: the data's, padded.
    pub x_range: Option<(f64, f64)>,
    /// Ordinate range; `None`: the data's, padded.
    pub y_range: Option<(f64, f64)>,
    /// Ordinate range symmetric about zero (accelerograms).
    pub symmetric_y: bool,
    /// Lines.
    pub lines: Vec<Line>,
    /// Shaded bands.
    pub bands: Vec<Band>,
    /// Point groups.
    pub points: Vec<Points>,
    /// Triangle markers.
    pub markers: Vec<Marker>,
    /// Horizontal reference lines.
    pub hlines: Vec<HLine>,
    /// The panel's name (e.g. seed and node), placed inside the axes where no data is.
    pub name: String,
    /// Tick labels of a categorical abscissa (one per integer); `None`: numbers.
    pub x_ticks: Option<fn(&f64) -> String>,
    /// Write the abscissa's tick labels (false for stacked panels above the bottom one).
    pub x_tick_labels: bool,
    /// Number of ordinate tick labels; `None`: plotters' choice.
    pub y_tick_count: Option<usize>,
    /// Minor grid lines (log axes look better with them).
    pub minor_grid: bool,
    /// Mark each point of the bold lines with a dot.
    pub dots: bool,
    /// Draw a legend of the labelled lines, bands and point groups.
    pub legend: bool,
    /// Small margins and fonts, for panels stacked in a column.
    pub compact: bool,
}

impl Default for Panel {
    fn default() -> Self {
        Panel {
            title: String::new(),
            x_desc: String::new(),
            y_desc: String::new(),
            x_scale: Scale::Linear,
            y_scale: Scale::Linear,
            x_range: None,
            y_range: None,
            symmetric_y: false,
            lines: vec![],
            bands: vec![],
            points: vec![],
            markers: vec![],
            hlines: vec![],
            name: String::new(),
            x_ticks: None,
            x_tick_labels: true,
            y_tick_count: None,
            minor_grid: false,
            dots: false,
            legend: true,
            compact: false,
        }
    }
}

impl Panel {
    /// A panel with linear axes.
    pub fn linear(x_desc: impl Into<String>, y_desc: impl Into<String>) -> Self {
        Panel { x_desc: x_desc.into(), y_desc: y_desc.into(), ..Panel::default() }
    }

    /// A panel with log-log axes and a minor grid.
    pub fn loglog(x_desc: impl Into<String>, y_desc: impl Into<String>) -> Self {
        Panel { x_scale: Scale::Log, y_scale: Scale::Log, minor_grid: true, ..Panel::linear(x_desc, y_desc) }
    }
}

/// A figure: a title over a grid of panels, filled row by row.
#[derive(Clone, Debug)]
pub struct Sheet {
    /// Title over the whole figure (empty: none).
    pub title: String,
    /// Panels per row.
    pub columns: usize,
    /// The panels.
    pub panels: Vec<Panel>,
    /// Image width (px).
    pub width: u32,
    /// Image height (px).
    pub height: u32,
}

impl Sheet {
    /// A sheet of the standard size.
    pub fn new(title: impl Into<String>, columns: usize, panels: Vec<Panel>) -> Self {
        Sheet { title: title.into(), columns: columns.max(1), panels, width: WIDTH, height: HEIGHT }
    }

    /// The same sheet `height` pixels high.
    pub fn with_height(mut self, height: u32) -> Self {
        self.height = height;
        self
    }
}

/// A label as drawn.
#[derive(Clone, Debug, PartialEq)]
pub struct PlacedLabel {
    /// Its text (a legend: its entries joined by " | ").
    pub text: String,
    /// Its box in pixels, padding included.
    pub bbox: PixelBox,
    /// Data pixels under it (0 unless no free spot existed inside the axes).
    pub data_pixels: u32,
    /// Whether it went outside the axes (right margin or the strip above them).
    pub outside: bool,
}

/// What one panel drew.
#[derive(Clone, Debug)]
pub struct DrawnPanel {
    /// The plotting area in image pixels (plotters' `plotting_area().get_pixel_range()`):
    /// every data pixel lies inside.
    pub area: PixelBox,
    /// The panel's name.
    pub name: String,
    /// Every label placed.
    pub labels: Vec<PlacedLabel>,
    /// Labels not drawn because every spot near their anchor covered data or another label.
    pub dropped: Vec<String>,
    /// The pixels covered by data (lines with their width plus a 2-px clearance, bands, points,
    /// markers, reference lines).
    pub data: Occupancy,
}

/// What a sheet drew.
#[derive(Clone, Debug)]
pub struct Drawn {
    /// One per panel, in the sheet's order.
    pub panels: Vec<DrawnPanel>,
}

/// An RGB image in memory.
#[derive(Clone, Debug)]
pub struct Image {
    /// Width (px).
    pub width: u32,
    /// Height (px).
    pub height: u32,
    /// Pixels, row by row, three bytes each.
    pub rgb: Vec<u8>,
}

impl Image {
    /// The colour of pixel `(x, y)`.
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y as usize * self.width as usize + x as usize);
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }

    /// Writes the image as a PNG.
    pub fn save_png(&self, path: &Path) -> Result<(), ReportError> {
        let io = |e: std::io::Error| ReportError::Io { path: path.to_path_buf(), source: e };
        let file = std::fs::File::create(path).map_err(io)?;
        let mut enc = png::Encoder::new(std::io::BufWriter::new(file), self.width, self.height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        // The encoder's default (its fastest deflate, one filter for every row) wrote figures
        // three times the size of zlib's default level with a filter chosen row by row.
        enc.set_compression(png::Compression::Default);
        enc.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let fail =
            |e: png::EncodingError| ReportError::Plot { figure: path.display().to_string(), what: e.to_string() };
        let mut w = enc.write_header().map_err(fail)?;
        w.write_image_data(&self.rgb).map_err(fail)?;
        w.finish().map_err(fail)
    }
}
