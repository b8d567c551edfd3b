//! The two rules of the chart layer, checked on the pixels of an in-memory render: nothing the
//! data draws leaves the plotting area, and labels go where no data is (or outside the axes),
//! never over each other. The scenes reproduce the figures that broke these rules: a decimated
//! stress trace with 2-px min/max reversals (its mitre joins drew a vertical line through the
//! title), the self-weight label on a trace that sits on its line, main-shock labels of several
//! seeds at nearly the same spot ("S2S2"), the paper's magnitude line through a cloud of points,
//! and a legend over the low-frequency curves of a log-log plot.

use stickslip_report::charts::{Band, Drawn, HLine, Image, Line, Marker, Panel, Points, Sheet, render};
use stickslip_report::place::PixelBox;
use stickslip_report::plot::{BLACK, colour, decimate};

/// A deterministic noise in [−1, 1].
fn noise(i: usize) -> f64 {
    ((i as f64 * 12.9898).sin() * 43758.5453).fract() * 2.0 - 1.0
}

/// A stick-slip-like trace: loading ramps with noisy bursts after each drop, decimated as the
/// figures do (min/max pairs per pixel: sharp reversals).
fn stress_trace() -> Vec<(f64, f64)> {
    let n = 40_000;
    let t: Vec<f64> = (0..n).map(|i| i as f64 * 8e-6).collect();
    let y: Vec<f64> = t
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            let phase = (t / 0.05).fract();
            let burst = if phase < 0.2 { 8.0 * (1.0 - phase / 0.2) * noise(i) } else { 0.0 };
            12.0 + 14.0 * phase + burst
        })
        .collect();
    decimate(&t, &y, 1200)
}

fn is_in(p: (u32, u32), areas: &[PixelBox]) -> bool {
    areas.iter().any(|a| a.contains((p.0 as i32, p.1 as i32)))
}

/// The pixels where two renders of the same size differ.
fn differing(a: &Image, b: &Image) -> Vec<(u32, u32)> {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let mut out = Vec::new();
    for y in 0..a.height {
        for x in 0..a.width {
            if a.pixel(x, y) != b.pixel(x, y) {
                out.push((x, y));
            }
        }
    }
    out
}

/// Data that reaches far outside fixed axes on every side, on linear and log-log axes: wide
/// traces with sharp reversals, spikes to ±1e9, gaps, a band over the edges, points and markers
/// on the edges, reference lines inside and outside the range. No text.
fn overflowing_sheet() -> Sheet {
    let mut trace = stress_trace();
    // Spikes far outside on every side, a gap, and a reversal at the top edge.
    trace.extend([(0.30, 1e9), (0.301, -1e9), (0.302, f64::NAN), (0.303, 20.0), (0.304, 29.9), (0.3041, 12.0)]);
    let mut wide = Line::new("", vec![(-1.0, 0.0), (0.1, 40.0), (0.12, -5.0), (0.2, 15.0), (2.0, 15.0)], 1);
    wide.width = 6;
    let mut thin = Line::new("", trace.iter().map(|&(t, y)| (t, y - 3.0)).collect(), 2);
    thin.width = 1;
    thin.alpha = 0.5;
    let linear = Panel {
        x_range: Some((0.0, 0.31)),
        y_range: Some((5.0, 30.0)),
        lines: vec![Line::new("", trace, 0), wide, thin],
        bands: vec![Band {
            points: (0..50).map(|i| (-0.05 + i as f64 * 0.01, 0.0, 29.0 + (i % 3) as f64)).collect(),
            colour: colour(3),
            label: String::new(),
        }],
        points: vec![Points {
            label: String::new(),
            points: vec![(0.0, 5.0), (0.31, 30.0), (0.155, 30.0), (0.155, 17.0), (0.5, 17.0)],
            colour: colour(4),
            size: 6,
        }],
        markers: vec![
            Marker { at: (0.0, 17.0), text: String::new(), colour: colour(5), text_colour: BLACK },
            Marker { at: (0.2, 30.0), text: String::new(), colour: colour(5), text_colour: BLACK },
            Marker { at: (0.2, 20.0), text: String::new(), colour: colour(5), text_colour: BLACK },
        ],
        hlines: vec![
            HLine { y: 11.77, text: String::new(), colour: BLACK },
            HLine { y: 31.0, text: String::new(), colour: BLACK },
        ],
        legend: false,
        ..Panel::linear("time (s)", "τ (kPa)")
    };
    let spectrum: Vec<(f64, f64)> =
        (0..400).map(|i| 10f64.powf(-1.0 + i as f64 * 0.015)).map(|f| (f, 1e-3 * f * f / (1.0 + f.powi(3)))).collect();
    let mut bold = Line::new("", spectrum.clone(), 1);
    bold.width = 4;
    let loglog = Panel {
        x_range: Some((1.0, 100.0)),
        y_range: Some((1e-6, 1e-3)),
        lines: vec![bold, Line::new("", spectrum.iter().map(|&(f, a)| (f, -a)).collect(), 2)],
        bands: vec![Band {
            points: spectrum.iter().map(|&(f, a)| (f, a * 0.1, a * 10.0)).collect(),
            colour: colour(0),
            label: String::new(),
        }],
        dots: true,
        legend: false,
        ..Panel::loglog("frequency (Hz)", "|X| (m/s)")
    };
    Sheet::new("Shear stress on the base", 2, vec![linear, loglog])
}

/// The same sheet with its data removed: only the axes, ticks and titles.
fn without_data(sheet: &Sheet) -> Sheet {
    let mut empty = sheet.clone();
    for p in &mut empty.panels {
        p.lines.clear();
        p.bands.clear();
        p.points.clear();
        p.markers.clear();
        p.hlines.clear();
    }
    empty
}

#[test]
fn no_drawn_pixel_leaves_the_plotting_area() {
    let sheet = overflowing_sheet();
    let (full, drawn) = render(&sheet).unwrap();
    let (bare, bare_drawn) = render(&without_data(&sheet)).unwrap();
    let areas: Vec<PixelBox> = drawn.panels.iter().map(|p| p.area).collect();
    assert_eq!(areas, bare_drawn.panels.iter().map(|p| p.area).collect::<Vec<_>>(), "same axes with and without data");
    let diff = differing(&full, &bare);
    let outside: Vec<&(u32, u32)> = diff.iter().filter(|p| !is_in(**p, &areas)).collect();
    assert!(
        outside.is_empty(),
        "{} data pixels outside the plotting areas {areas:?}, e.g. {:?}",
        outside.len(),
        &outside[..outside.len().min(10)]
    );
    // Not vacuous: the data covers a good part of each panel.
    for a in &areas {
        let inside = diff.iter().filter(|p| a.contains((p.0 as i32, p.1 as i32))).count();
        assert!(inside > 5_000, "only {inside} data pixels in {a:?}");
    }
    // The mask the labels are placed against holds every pixel the data drew.
    let unmarked: Vec<&(u32, u32)> =
        diff.iter().filter(|&&(x, y)| !drawn.panels.iter().any(|p| p.data.is_marked((x as i32, y as i32)))).collect();
    assert!(
        unmarked.is_empty(),
        "{} drawn pixels missing from the data mask, e.g. {:?}",
        unmarked.len(),
        &unmarked[..unmarked.len().min(10)]
    );
}

/// Checks the label rule on what a sheet drew: every label inside the axes covers no data pixel,
/// every label lies inside the image, no two labels overlap, none was dropped.
fn assert_labels_clear(drawn: &Drawn, img: (u32, u32)) {
    let image = PixelBox::at(0, 0, (img.0 as i32, img.1 as i32));
    let all: Vec<(usize, &stickslip_report::charts::PlacedLabel)> =
        drawn.panels.iter().enumerate().flat_map(|(k, p)| p.labels.iter().map(move |l| (k, l))).collect();
    for (k, l) in &all {
        let p = &drawn.panels[*k];
        assert!(image.holds(&l.bbox), "{:?} leaves the image", l.text);
        assert_eq!(p.data.count(&l.bbox), 0, "{:?} at {:?} covers data (outside: {})", l.text, l.bbox, l.outside);
        if l.outside {
            assert!(!l.bbox.intersects(&p.area), "{:?} is said to be outside the axes but lies on them", l.text);
        } else {
            assert!(p.area.holds(&l.bbox), "{:?} is said to be inside the axes but is not", l.text);
        }
    }
    for (i, (_, a)) in all.iter().enumerate() {
        for (_, b) in &all[i + 1..] {
            assert!(!a.bbox.intersects(&b.bbox), "{:?} overprints {:?}", a.text, b.text);
        }
    }
    for p in &drawn.panels {
        assert!(p.dropped.is_empty(), "labels dropped in panel {:?}: {:?}", p.name, p.dropped);
    }
}

fn texts(drawn: &Drawn) -> Vec<String> {
    drawn.panels.iter().flat_map(|p| p.labels.iter().map(|l| l.text.clone())).collect()
}

#[test]
fn a_reference_label_on_a_busy_trace_goes_where_no_data_is() {
    // σ(t): the trace sits on the self-weight line and bursts around it over the whole width.
    let trace: Vec<(f64, f64)> = stress_trace()
        .into_iter()
        .map(|(t, y)| (t, 11.77 + (y - 12.0 - 7.0 * (t / 0.05).fract() * 2.0) * 1.5))
        .collect();
    let panel = Panel {
        lines: vec![Line::new("seed 123", trace, 0)],
        hlines: vec![HLine { y: 11.77, text: "self-weight ρgh = 11.77 kPa".into(), colour: BLACK }],
        ..Panel::linear("time (s)", "σ (kPa)")
    };
    let sheet = Sheet::new("Normal stress on the base", 1, vec![panel]);
    let (img, drawn) = render(&sheet).unwrap();
    assert_labels_clear(&drawn, (img.width, img.height));
    let t = texts(&drawn);
    assert!(t.iter().any(|s| s.contains("self-weight")), "the reference label is drawn: {t:?}");
    assert!(t.iter().any(|s| s.contains("seed 123")), "the legend is drawn: {t:?}");
}

#[test]
fn marker_labels_of_several_seeds_never_overprint() {
    // Four seeds whose S1…S4 lie within a few pixels of each other, every one labelled.
    let mut lines = Vec::new();
    let mut markers = Vec::new();
    for k in 0..4 {
        let trace: Vec<(f64, f64)> = stress_trace().into_iter().map(|(t, y)| (t + 0.002 * k as f64, y)).collect();
        for s in 1..=4 {
            let at = 0.05 * s as f64 + 0.002 * k as f64 - 1e-4;
            markers.push(Marker {
                at: (at, 25.8 + 0.1 * k as f64),
                text: format!("S{s}"),
                colour: colour(k),
                text_colour: colour(k),
            });
        }
        lines.push(Line::new(format!("seed {k}"), trace, k));
    }
    let sheet = Sheet::new("Shear stress", 1, vec![Panel { lines, markers, ..Panel::linear("time (s)", "τ (kPa)") }]);
    let (_, drawn) = render(&sheet).unwrap();
    let p = &drawn.panels[0];
    // Overlapping labels are dropped rather than overprinted, so only check the placed ones here.
    let placed: Vec<&PixelBox> = p.labels.iter().map(|l| &l.bbox).collect();
    for (i, a) in placed.iter().enumerate() {
        for b in &placed[i + 1..] {
            assert!(!a.intersects(b), "labels overprint: {:?}", texts(&drawn));
        }
    }
    for s in 1..=4 {
        assert!(
            p.labels.iter().any(|l| l.text == format!("S{s}")),
            "S{s} is labelled at least once: {:?}",
            texts(&drawn)
        );
    }
    for l in &p.labels {
        assert_eq!(p.data.count(&l.bbox), 0, "{:?} covers data", l.text);
    }
}

#[test]
fn a_reference_label_through_a_point_cloud_and_a_legend_over_curves_find_free_room() {
    // magnitude.png: the paper's M = 6.77 runs through the clouds of points of each rank.
    let mut riera = Vec::new();
    let mut mw = Vec::new();
    for r in 1..=5 {
        for i in 0..100 {
            let x = r as f64 + 0.3 * noise(i + 7 * r);
            riera.push((x, 6.75 + 0.06 * noise(i * 3 + r)));
            mw.push((x, 3.85 + 0.06 * noise(i * 5 + r)));
        }
    }
    let magnitude = Panel {
        points: vec![
            Points { label: "Riera M".into(), points: riera, colour: colour(0), size: 5 },
            Points { label: "Mw".into(), points: mw, colour: colour(2), size: 5 },
        ],
        hlines: vec![HLine { y: 6.77, text: "paper: M = 6.77 (S2)".into(), colour: BLACK }],
        ..Panel::linear("main shock", "magnitude")
    };
    // fourier.png: curves of several seeds over the whole width, high at low frequencies.
    let lines: Vec<Line> = (0..3)
        .map(|k| {
            let pts = (0..300)
                .map(|i| (i, 10f64.powf(i as f64 * 0.01)))
                .map(|(i, f)| (f, (1.0 + 0.1 * k as f64) * 1e-2 / (1.0 + f / 30.0) * (1.0 + 0.3 * noise(i + 100 * k))))
                .collect();
            let mut l = Line::new(format!("seed {k}"), pts, k);
            l.width = 1;
            l
        })
        .collect();
    let fourier = Panel {
        name: "node 36 at (0.2, 0.1, 0.1) m (z)".into(),
        lines,
        ..Panel::loglog("frequency (Hz)", "|X|·Δt (m/s)")
    };
    let sheet = Sheet::new("", 2, vec![magnitude, fourier]);
    let (img, drawn) = render(&sheet).unwrap();
    assert_labels_clear(&drawn, (img.width, img.height));
    let t = texts(&drawn);
    for want in ["paper: M = 6.77", "seed 0 | seed 1 | seed 2", "node 36", "Riera M | Mw"] {
        assert!(t.iter().any(|s| s.contains(want)), "{want:?} drawn: {t:?}");
    }
}

/// The grid of magnitude_frequency.png (a linear magnitude axis beside a log count axis, minor
/// grid on): vertical grid lines at the magnitude labels only, not plotters' ten minor lines per
/// label (which drew a dense light band); the log axis keeps its minor lines at 2…9 × 10^k.
#[test]
fn a_linear_axis_beside_a_log_axis_has_grid_lines_at_its_labels_only() {
    use stickslip_report::charts::Scale;
    let panel = Panel {
        y_scale: Scale::Log,
        minor_grid: true,
        x_range: Some((3.05, 4.05)),
        y_range: Some((0.8, 150.0)),
        legend: false,
        ..Panel::linear("magnitude", "events")
    };
    let (img, drawn) = render(&Sheet::new("", 1, vec![panel])).unwrap();
    let a = drawn.panels[0].area;
    // Grid lines crossing the middle row (columns) and the middle column (rows), away from the
    // axes: any non-white pixel there is a grid line.
    let (row, col) = ((a.y0 + a.y1) as u32 / 2 + 3, (a.x0 + a.x1) as u32 / 2 + 3);
    let lines =
        |pixels: Vec<[u8; 3]>| pixels.windows(2).filter(|w| w[0] == [255, 255, 255] && w[1] != [255, 255, 255]).count();
    let vertical = lines((a.x0 as u32 + 2..a.x1 as u32 - 2).map(|x| img.pixel(x, row)).collect());
    let horizontal = lines((a.y0 as u32 + 2..a.y1 as u32 - 2).map(|y| img.pixel(col, y)).collect());
    // 3.1, 3.2, …, 4.0: ten labels, so at most ten vertical lines (and at least a few).
    assert!((5..=11).contains(&vertical), "{vertical} vertical grid lines");
    // 1, 10, 100 and the minor lines at 2…9 × 10^k (and 0.9): about 20.
    assert!((15..=30).contains(&horizontal), "{horizontal} horizontal grid lines");
}
