//! Plotting helpers: the bundled font, sizes, colours, decimation, axis ranges.

use std::sync::Once;

use plotters::style::FontStyle;
pub use plotters::style::{BLACK, RGBColor};

use crate::error::ReportError;

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
    // Halves first, so that a span near f64::MAX does not overflow.
    let pad = 0.1 * (0.5 * hi - 0.5 * lo);
    ((lo - pad).max(-f64::MAX), (hi + pad).min(f64::MAX))
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

/// The ticks of a log axis over `lo..hi` (positive): labelled ticks (`.0`) and unlabelled minor
/// grid lines (`.1`). Over two decades or more, a labelled tick at each power of ten (every
/// second, third, … when there are more than eight) and minor lines at 2…9 × 10^k up to five
/// decades; over less, labels at 1, 2 and 5 × 10^k (or every integer multiple when those give
/// fewer than two) and minor lines at the other multiples. Labels never sit at neighbouring
/// minor positions (as 0.09 and 0.1 did).
pub fn log_ticks(lo: f64, hi: f64) -> (Vec<f64>, Vec<f64>) {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return (vec![], vec![]);
    }
    let inside = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
    let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let multiples = |ms: &[u32]| -> Vec<f64> {
        (k0..=k1).flat_map(|k| ms.iter().map(move |&m| m as f64 * 10f64.powi(k))).filter(|&v| inside(v)).collect()
    };
    let decades = multiples(&[1]);
    let all: Vec<u32> = (1..=9).collect();
    if decades.len() >= 2 {
        let step = decades.len().div_ceil(8);
        // Keep the powers of ten whose exponent is a multiple of the step, so the labels are
        // evenly spaced and round.
        let bold: Vec<f64> =
            decades.iter().copied().filter(|v| (v.log10().round() as i64).rem_euclid(step as i64) == 0).collect();
        let light = if k1 - k0 <= 5 {
            multiples(&all).into_iter().filter(|v| !bold.iter().any(|b| (b / v - 1.0).abs() < 1e-9)).collect()
        } else {
            decades.into_iter().filter(|v| !bold.iter().any(|b| (b / v - 1.0).abs() < 1e-9)).collect()
        };
        return (bold, light);
    }
    let mut bold = multiples(&[1, 2, 5]);
    if bold.len() < 2 {
        bold = multiples(&all);
    }
    let light = multiples(&all).into_iter().filter(|v| !bold.iter().any(|b| (b / v - 1.0).abs() < 1e-9)).collect();
    (bold, light)
}

/// Tick label formatter: plain numbers with up to 4 significant digits, scientific when tiny or
/// huge (with up to 3 significant digits, so that 3.5e5, 4e5 and 4.5e5 read apart).
pub fn fmt_tick(v: &f64) -> String {
    let a = v.abs();
    if a < 1e-12 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.2e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa =
            if mantissa.contains('.') { mantissa.trim_end_matches('0').trim_end_matches('.') } else { mantissa };
        format!("{mantissa}e{exponent}")
    } else {
        let s = format!("{v:.4}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::{fmt_tick, log_ticks};

    #[test]
    fn log_axes_are_labelled_at_round_values_only() {
        // Three decades: a label per power of ten, minor lines at 2…9 ×.
        let (bold, light) = log_ticks(0.003, 2.0);
        let labels: Vec<String> = bold.iter().map(fmt_tick).collect();
        assert_eq!(labels, ["0.01", "0.1", "1"]);
        assert!(light.iter().any(|v| (v - 0.09).abs() < 1e-12) && light.iter().any(|v| (v - 0.004).abs() < 1e-12));
        assert!(!light.iter().any(|v| (v - 0.1).abs() < 1e-12), "a label is not also a minor line");
        // Less than a decade: 1, 2, 5 ×.
        let (bold, light) = log_ticks(1.5, 9.0);
        assert_eq!(bold.iter().map(fmt_tick).collect::<Vec<_>>(), ["2", "5"]);
        assert_eq!(light.len(), 6);
        // Twenty decades: at most eight labels, evenly spaced; no minor line at 2…9 ×.
        let (bold, light) = log_ticks(1e-10, 1e10);
        assert!(bold.len() <= 8 && bold.len() >= 5, "{bold:?}");
        assert!(light.iter().all(|v| (v.log10() - v.log10().round()).abs() < 1e-9));
        assert_eq!(log_ticks(0.0, 1.0), (vec![], vec![]));
    }

    #[test]
    fn large_and_tiny_ticks_keep_the_digits_that_tell_them_apart() {
        // The δ(t) axis of a fault in µm read "4e5 4e5 4e5" and "1e6 1e6" before.
        let labels: Vec<String> = [3.5e5, 4e5, 4.5e5, 1.2e6, 1e6, -2.25e-5].iter().map(fmt_tick).collect();
        assert_eq!(labels, ["3.5e5", "4e5", "4.5e5", "1.2e6", "1e6", "-2.25e-5"]);
        assert_eq!(fmt_tick(&12345.0), "12345");
        assert_eq!(fmt_tick(&0.25), "0.25");
        assert_eq!(fmt_tick(&0.0), "0");
    }
}
