//! The Part-A figure: the bias ln(observed/simulated) per period with its 90% interval (PGA
//! beside the shortest period), and each station's residual averaged over the period bins against
//! its rupture distance.

use std::path::Path;

use plotters::style::RGBColor;
use stickslip_report::charts::{Band, HLine, Line, Marker, Panel, Points, Scale, Sheet, draw};

use super::{ObservedStation, PGA, PartA};

/// Draws `p` (with the recordings' R_rup from `observed`) into a PNG at `path`, titled `title`.
pub fn part_a_figure(p: &PartA, observed: &[ObservedStation], title: &str, path: &Path) -> Result<(), String> {
    let rows: Vec<_> = p.periods.iter().filter(|r| r.periods_s[0] != PGA).collect();
    if rows.is_empty() {
        return Err("no period with a station in band: nothing to draw".into());
    }
    let (t0, t1) = (rows[0].periods_s[0] / 1.5, rows[rows.len() - 1].periods_s[0] * 1.3);
    let mut bias = Panel::linear("period (s)", "bias ln(observed / simulated)");
    bias.x_scale = Scale::Log;
    bias.x_range = Some((t0, t1));
    bias.title = match p.periods.iter().find(|r| r.periods_s[0] == PGA) {
        Some(pga) => format!("RotD50: bias, 90% interval; triangle: PGA {:+.2}", pga.mean),
        None => "RotD50, 5% damping: mean over stations, 90% interval".into(),
    };
    bias.bands.push(Band {
        points: rows.iter().filter_map(|r| r.ci90.map(|[lo, hi]| (r.periods_s[0], lo, hi))).collect(),
        colour: stickslip_report::plot::colour(0),
        label: "90% interval (Student)".into(),
    });
    let mut line = Line::new("bias", rows.iter().map(|r| (r.periods_s[0], r.mean)).collect(), 0);
    line.width = 3;
    bias.lines.push(line);
    bias.dots = true;
    bias.hlines.push(HLine { y: 0.0, text: String::new(), colour: RGBColor(60, 60, 60) });
    if let Some(pga) = p.periods.iter().find(|r| r.periods_s[0] == PGA) {
        bias.markers.push(Marker {
            at: (t0 * 1.2, pga.mean),
            text: format!("PGA {:+.2} (n = {})", pga.mean, pga.stations.len()),
            colour: stickslip_report::plot::colour(1),
            text_colour: RGBColor(0, 0, 0),
        });
    }
    let spread = rows
        .iter()
        .flat_map(|r| [r.mean, r.ci90.map_or(0.0, |c| c[0]), r.ci90.map_or(0.0, |c| c[1])])
        .fold(1.0f64, |m, v| m.max(v.abs()));
    bias.y_range = Some((-spread * 1.1, spread * 1.1));

    let mut dist = Panel::linear("R_rup of the recording (km)", "station residual ln(observed / simulated)");
    dist.x_scale = Scale::Log;
    dist.title = "each station, averaged over a period bin".into();
    let r_rup = |name: &str| observed.iter().find(|o| o.name == name).map_or(f64::NAN, |o| o.r_rup_km.max(0.5));
    for (k, b) in p.bins.iter().enumerate() {
        dist.points.push(Points {
            label: format!("{}–{} s", b.periods_s[0], b.periods_s[1]),
            points: b.stations.iter().zip(&b.residual_ln).map(|(s, r)| (r_rup(s), *r)).collect(),
            colour: stickslip_report::plot::colour(k + 2),
            size: 4,
        });
    }
    dist.hlines.push(HLine { y: 0.0, text: String::new(), colour: RGBColor(60, 60, 60) });
    let sheet = Sheet::new(title, 2, vec![bias, dist]);
    draw(path, &sheet).map(|_| ()).map_err(|e| e.to_string())
}
