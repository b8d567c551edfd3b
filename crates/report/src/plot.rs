//! Plotting helpers: the bundled font, sizes, colours, decimation, axis ranges.

use std::sync::Once;

use plotters::style::FontStyle;
pub use plotters::style::{BLACK, RGBColor};

use crate::ReportError;

/// Figure width in pixels.
pub const WIDTH: u32 = 1200;
/// Figure height in pixels.
pub const HEIGHT: u32 = 700;
/// Font family every figure uses (DejaVu Sans, shipped in the binary).
pub const FONT: &str = "sans-serif";
/// Title size (px).
pub const TITLE: u32 = 30;
/// Axis description size (px).
pub const LABEL: u32 = 22;
/// Tick label size (px).
pub const TICK: u32 = 18;

static FONTS: Once = Once::new();

/// Registers the bundled DejaVu Sans as `sans-serif` (regular and bold) once, so text renders
/// on a machine with no system fonts.
pub fn register_fonts() {
    FONTS.call_once(|| {
        // The error type carries no information (it has no Debug); a failure here means the
        // bundled font bytes are broken, which the report tests would show as blank text.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold());
    });
}

/// A plotting error as an analysis error.
pub fn plot_err(figure: &str) -> impl Fn(String) -> ReportError + '_ {
    move |e| ReportError::Plot { figure: figure.to_string(), what: e }
}

/// Colour `i` of a palette readable on white (colour-blind-safe order, after Wong 2011).
pub fn colour(i: usize) -> RGBColor {
    const P: [RGBColor; 8] = [
        RGBColor(0, 114, 178),
        RGBColor(213, 94, 0),
        RGBColor(0, 158, 115),
        RGBColor(204, 121, 167),
        RGBColor(230, 159, 0),
        RGBColor(86, 180, 233),
        RGBColor(120, 120, 120),
        RGBColor(0, 0, 0),
    ];
    P[i % P.len()]
}

/// Keeps the shape of a long series for a plot `pixels` wide: per bucket, its minimum and
/// maximum in time order.
pub fn decimate(t: &[f64], y: &[f64], pixels: usize) -> Vec<(f64, f64)> {
    let n = t.len().min(y.len());
    if n <= 4 * pixels {
        return (0..n).map(|i| (t[i], y[i])).collect();
    }
    let per = n.div_ceil(2 * pixels);
    let mut out = Vec::with_capacity(4 * pixels);
    for start in (0..n).step_by(per) {
        let end = (start + per).min(n);
        let (mut lo, mut hi) = (start, start);
        for i in start..end {
            if y[i] < y[lo] {
                lo = i;
            }
            if y[i] > y[hi] {
                hi = i;
            }
        }
        let (a, b) = if lo <= hi { (lo, hi) } else { (hi, lo) };
        out.push((t[a], y[a]));
        if b != a {
            out.push((t[b], y[b]));
        }
    }
    out
}

/// Range of the finite values, padded by 5% (or ±1 around a constant).
pub fn padded_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) =
        values.filter(|v| v.is_finite()).fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    if hi - lo <= f64::EPSILON * hi.abs().max(1.0) {
        return (lo - 1.0, hi + 1.0);
    }
    let pad = 0.05 * (hi - lo);
    (lo - pad, hi + pad)
}

/// Range of the positive finite values for a log axis, padded by a factor 1.3 and widened down
/// to a power of ten when it holds none (a log axis is labelled at powers of ten).
pub fn log_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() {
        return (0.1, 1.0);
    }
    let (lo, hi) = (lo / 1.3, hi * 1.3);
    let decade = 10f64.powf(hi.log10().floor());
    (if decade >= lo { lo } else { decade * 0.9 }, hi)
}

/// Tick label formatter: plain numbers with up to 4 significant digits, scientific when tiny or
/// huge.
pub fn fmt_tick(v: &f64) -> String {
    let a = v.abs();
    if a < 1e-12 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.0e}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}
