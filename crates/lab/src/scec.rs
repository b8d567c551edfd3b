//! A fault scene's run against a reference solution of a SCEC/USGS dynamic-rupture benchmark
//! (TPV5: `pipelines/reference/tpv5/`, docs/model.md §15): at every on-fault station the rupture
//! time (slip-rate magnitude first above 1 mm/s, interpolated between samples), the final slip
//! and the peak slip rate; over the fault the rupture-time field at the reference's points.
//!
//! The run's side is read from its benchmark files (`<out>/scec/seed<seed>/`, written by the
//! store in the benchmarks' layout), the reference from three CSV files: `stations.csv`,
//! `rupture_times.csv`, `slip_rates.csv`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use plotters::style::RGBColor;
use stickslip_report::charts::{Line, Panel, Sheet, draw};
use stickslip_report::contour::contour;
use stickslip_seismo::scec::read_table;

/// Why a comparison could not be made.
#[derive(Debug, thiserror::Error)]
pub enum CompareError {
    /// A file could not be read.
    #[error("{path}: {why}")]
    File {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        why: String,
    },
    /// The figure could not be drawn.
    #[error("figure: {0}")]
    Figure(String),
}

/// A point of a rupture-time field: its (x, y) on the fault (m) and its rupture time (s).
pub type FieldPoint = ([f64; 2], f64);

/// A field on its grid: the distinct x and y (m) and the value at each (x, y) index.
type Grid = (Vec<f64>, Vec<f64>, BTreeMap<(i64, i64), f64>);

/// One station of the reference.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceStation {
    /// Benchmark name (`faultst-120dp075`).
    pub name: String,
    /// Along strike and down dip (km).
    pub at_km: [f64; 2],
    /// Rupture time (s).
    pub rupture_time_s: f64,
    /// Final horizontal slip (m).
    pub final_slip_m: f64,
    /// Largest horizontal slip rate (m/s).
    pub peak_slip_rate_m_s: f64,
}

/// A reference solution.
#[derive(Clone, Debug, Default)]
pub struct Reference {
    /// Its stations.
    pub stations: Vec<ReferenceStation>,
    /// Rupture time over the fault: `(along strike, down dip)` (km) and time (s; NaN: never).
    pub rupture_times: Vec<FieldPoint>,
    /// Each station's horizontal slip rate: times (s) and values (m/s).
    pub slip_rates: BTreeMap<String, (Vec<f64>, Vec<f64>)>,
    /// The benchmark's name, from the folder's (`TPV5`).
    pub problem: String,
}

fn read_csv(path: &Path) -> Result<Vec<Vec<String>>, CompareError> {
    let text =
        std::fs::read_to_string(path).map_err(|e| CompareError::File { path: path.into(), why: e.to_string() })?;
    Ok(text
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .skip(1)
        .map(|l| l.split(',').map(|c| c.trim().to_string()).collect())
        .collect())
}

fn number(cells: &[String], k: usize) -> f64 {
    cells.get(k).and_then(|c| c.parse().ok()).unwrap_or(f64::NAN)
}

impl Reference {
    /// Reads a reference from its folder.
    pub fn load(dir: &Path) -> Result<Reference, CompareError> {
        let stations = read_csv(&dir.join("stations.csv"))?
            .iter()
            .map(|c| ReferenceStation {
                name: c[0].clone(),
                at_km: [number(c, 1), number(c, 2)],
                rupture_time_s: number(c, 3),
                final_slip_m: number(c, 4),
                peak_slip_rate_m_s: number(c, 5),
            })
            .collect();
        let rupture_times = read_csv(&dir.join("rupture_times.csv"))?
            .iter()
            .map(|c| ([number(c, 0), number(c, 1)], number(c, 2)))
            .collect();
        let mut slip_rates: BTreeMap<String, (Vec<f64>, Vec<f64>)> = BTreeMap::new();
        for c in read_csv(&dir.join("slip_rates.csv"))? {
            let e = slip_rates.entry(c[0].clone()).or_default();
            e.0.push(number(&c, 1));
            e.1.push(number(&c, 3));
        }
        let problem = dir.file_name().and_then(|n| n.to_str()).unwrap_or("reference").to_uppercase();
        Ok(Reference { stations, rupture_times, slip_rates, problem })
    }
}

/// One on-fault station of a run, read from its benchmark file.
#[derive(Clone, Debug, PartialEq)]
pub struct RunStation {
    /// Along strike and down dip (km), from its file name.
    pub at_km: [f64; 2],
    /// Time (s).
    pub time_s: Vec<f64>,
    /// Horizontal slip (m).
    pub slip_m: Vec<f64>,
    /// Slip-rate magnitude (m/s).
    pub slip_rate_m_s: Vec<f64>,
}

impl RunStation {
    /// First time the slip rate exceeds `threshold` (interpolated linearly between samples).
    pub fn rupture_time_s(&self, threshold: f64) -> f64 {
        let v = &self.slip_rate_m_s;
        for i in 0..v.len() {
            if v[i] > threshold {
                if i == 0 {
                    return self.time_s[0];
                }
                let f = (threshold - v[i - 1]) / (v[i] - v[i - 1]);
                return self.time_s[i - 1] + f * (self.time_s[i] - self.time_s[i - 1]);
            }
        }
        f64::NAN
    }
}

/// The on-fault stations and the rupture-time field a run wrote in `scec_dir`.
pub fn read_run(scec_dir: &Path) -> Result<(Vec<RunStation>, Vec<FieldPoint>), CompareError> {
    let err = |path: &Path, why: String| CompareError::File { path: path.into(), why };
    let mut stations = Vec::new();
    let entries = std::fs::read_dir(scec_dir).map_err(|e| err(scec_dir, e.to_string()))?;
    let mut paths: Vec<PathBuf> = entries.filter_map(|e| e.ok().map(|e| e.path())).collect();
    paths.sort();
    for path in paths {
        let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("").to_string();
        let Some(rest) = name.strip_prefix("faultst") else { continue };
        let Some((st, dp)) = rest.split_once("dp") else { continue };
        let (Ok(st), Ok(dp)) = (st.parse::<f64>(), dp.parse::<f64>()) else { continue };
        let text = std::fs::read_to_string(&path).map_err(|e| err(&path, e.to_string()))?;
        let (names, rows) = read_table(&text);
        let col = |n: &str| names.iter().position(|c| c == n).ok_or_else(|| err(&path, format!("no column {n}")));
        let (t, s, rh, rv) = (col("t")?, col("h-slip")?, col("h-slip-rate")?, col("v-slip-rate")?);
        stations.push(RunStation {
            at_km: [st / 10.0, dp / 10.0],
            time_s: rows.iter().map(|r| r[t]).collect(),
            slip_m: rows.iter().map(|r| r[s]).collect(),
            slip_rate_m_s: rows.iter().map(|r| r[rh].hypot(r[rv])).collect(),
        });
    }
    let cplot = scec_dir.join("cplot.dat");
    let text = std::fs::read_to_string(&cplot).map_err(|e| err(&cplot, e.to_string()))?;
    let (_, rows) = read_table(&text);
    let field = rows.iter().map(|r| ([r[0] / 1e3, r[1] / 1e3], if r[2] >= 1e9 { f64::NAN } else { r[2] })).collect();
    Ok((stations, field))
}

/// One station of the comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct StationComparison {
    /// The reference station.
    pub reference: ReferenceStation,
    /// The run's nearest station: where it is (km) and how far from the reference's (m).
    pub at_km: [f64; 2],
    /// Distance between the two (m).
    pub offset_m: f64,
    /// The run's rupture time, final slip and peak slip rate.
    pub rupture_time_s: f64,
    /// Final slip (m).
    pub final_slip_m: f64,
    /// Peak slip rate (m/s).
    pub peak_slip_rate_m_s: f64,
}

/// The comparison of one run with the reference.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// Every reference station against the run's nearest.
    pub stations: Vec<StationComparison>,
    /// Over the reference's ruptured points that the run ruptured too: the RMS and largest
    /// relative difference of the rupture time (the run's interpolated bilinearly).
    pub field_rms: f64,
    /// Largest relative difference.
    pub field_max: f64,
    /// Points compared.
    pub field_points: usize,
}

/// Bilinear interpolation of a grid field at `p` (NaN outside or next to NaN).
fn interpolate(xs: &[f64], ys: &[f64], v: &dyn Fn(usize, usize) -> f64, p: [f64; 2]) -> f64 {
    let (Some(i), Some(j)) = (
        xs.windows(2).position(|w| w[0] <= p[0] && p[0] <= w[1]),
        ys.windows(2).position(|w| w[0] <= p[1] && p[1] <= w[1]),
    ) else {
        return f64::NAN;
    };
    let (tx, ty) = ((p[0] - xs[i]) / (xs[i + 1] - xs[i]), (p[1] - ys[j]) / (ys[j + 1] - ys[j]));
    (1.0 - tx) * (1.0 - ty) * v(i, j)
        + tx * (1.0 - ty) * v(i + 1, j)
        + (1.0 - tx) * ty * v(i, j + 1)
        + tx * ty * v(i + 1, j + 1)
}

/// The run's rupture-time field as a grid: sorted x's, sorted y's and the value lookup.
fn grid(field: &[FieldPoint]) -> Grid {
    let key = |v: f64| (v * 1e6).round() as i64;
    let mut xs: Vec<f64> = field.iter().map(|(p, _)| p[0]).collect();
    let mut ys: Vec<f64> = field.iter().map(|(p, _)| p[1]).collect();
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    ys.sort_by(f64::total_cmp);
    ys.dedup();
    let values = field.iter().map(|(p, t)| ((key(p[0]), key(p[1])), *t)).collect();
    (xs, ys, values)
}

/// Compares a run's benchmark files with the reference.
pub fn compare(stations: &[RunStation], field: &[FieldPoint], reference: &Reference) -> Comparison {
    let out = reference
        .stations
        .iter()
        .filter_map(|r| {
            let s = stations.iter().min_by(|a, b| {
                let d = |s: &RunStation| (s.at_km[0] - r.at_km[0]).hypot(s.at_km[1] - r.at_km[1]);
                d(a).total_cmp(&d(b))
            })?;
            Some(StationComparison {
                reference: r.clone(),
                at_km: s.at_km,
                offset_m: 1e3 * (s.at_km[0] - r.at_km[0]).hypot(s.at_km[1] - r.at_km[1]),
                rupture_time_s: s.rupture_time_s(1e-3),
                final_slip_m: *s.slip_m.last().unwrap_or(&f64::NAN),
                peak_slip_rate_m_s: s.slip_rate_m_s.iter().copied().fold(0.0, f64::max),
            })
        })
        .collect();
    let (xs, ys, values) = grid(field);
    let key = |v: f64| (v * 1e6).round() as i64;
    let v = |i: usize, j: usize| values.get(&(key(xs[i]), key(ys[j]))).copied().unwrap_or(f64::NAN);
    let mut sq = 0.0;
    let mut max: f64 = 0.0;
    let mut n = 0;
    for (p, t) in &reference.rupture_times {
        // The hypocentre's cells start at once: relative differences mean nothing there.
        if !(t.is_finite() && *t > 0.5) {
            continue;
        }
        let ours = interpolate(&xs, &ys, &v, *p);
        if ours.is_finite() {
            let rel = ours / t - 1.0;
            sq += rel * rel;
            max = max.max(rel.abs());
            n += 1;
        }
    }
    Comparison { stations: out, field_rms: (sq / n.max(1) as f64).sqrt(), field_max: max, field_points: n }
}

/// The comparison as a Markdown table (one row per station).
pub fn table(c: &Comparison) -> String {
    let mut s = String::from(
        "| station | run's node (km) | rupture time (s) | ref. | diff. | final slip (m) | ref. | diff. | peak slip rate (m/s) | ref. |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in &c.stations {
        let rel = |a: f64, b: f64| {
            if b.abs() > 0.05 { format!("{:+.1}%", 100.0 * (a / b - 1.0)) } else { format!("{:+.2} s", a - b) }
        };
        s.push_str(&format!(
            "| {} | ({:.1}, {:.1}) | {:.3} | {:.3} | {} | {:.3} | {:.3} | {:+.1}% | {:.2} | {:.2} |\n",
            r.reference.name,
            r.at_km[0],
            r.at_km[1],
            r.rupture_time_s,
            r.reference.rupture_time_s,
            rel(r.rupture_time_s, r.reference.rupture_time_s),
            r.final_slip_m,
            r.reference.final_slip_m,
            100.0 * (r.final_slip_m / r.reference.final_slip_m - 1.0),
            r.peak_slip_rate_m_s,
            r.reference.peak_slip_rate_m_s,
        ));
    }
    s.push_str(&format!(
        "\nRupture-time field at {} reference points (rupture later than 0.5 s): RMS relative difference {:.2}%, largest {:.1}%.\n",
        c.field_points,
        100.0 * c.field_rms,
        100.0 * c.field_max
    ));
    s
}

/// The figure: rupture-time contours every second, run against reference, and the horizontal
/// slip rate at four stations.
pub fn figure(
    path: &Path,
    label: &str,
    stations: &[RunStation],
    field: &[FieldPoint],
    reference: &Reference,
) -> Result<(), CompareError> {
    let mut map = Panel::linear("along strike (km)", "−depth (km)");
    map.name = format!("rupture front every second: {label} (red) and the reference (grey)");
    let (xs, ys, values) = grid(field);
    let key = |v: f64| (v * 1e6).round() as i64;
    let neg: Vec<f64> = ys.iter().map(|y| -y).collect();
    // A reference read at scattered points (lines and a coarse grid, TPV101's) is contoured on its
    // 1.5 km grid only: the lines' points would leave most cells of the full grid empty.
    let (rx, ry, _) = grid(&reference.rupture_times);
    let thinned: Vec<FieldPoint>;
    let points = if reference.rupture_times.len() * 2 < rx.len() * ry.len() {
        let on = |v: f64| ((v / 1.5).round() * 1.5 - v).abs() < 1e-6;
        thinned = reference.rupture_times.iter().copied().filter(|(p, _)| on(p[0]) && on(p[1])).collect();
        &thinned
    } else {
        &reference.rupture_times
    };
    let (rx, ry, rv) = grid(points);
    let rneg: Vec<f64> = ry.iter().map(|y| -y).collect();
    for s in 1..=9 {
        let level = s as f64;
        let ours = contour(&xs, &neg, |i, j| values.get(&(key(xs[i]), key(ys[j]))).copied().unwrap_or(f64::NAN), level);
        let theirs = contour(&rx, &rneg, |i, j| rv.get(&(key(rx[i]), key(ry[j]))).copied().unwrap_or(f64::NAN), level);
        map.lines.push(Line {
            label: if s == 1 { "reference".into() } else { String::new() },
            points: theirs,
            colour: RGBColor(150, 150, 150),
            width: 3,
            alpha: 1.0,
        });
        map.lines.push(Line {
            label: if s == 1 { label.into() } else { String::new() },
            points: ours,
            colour: RGBColor(200, 30, 30),
            width: 1,
            alpha: 1.0,
        });
    }
    let mut panels = vec![map];
    // TPV5's four stations, or the reference's first four.
    let tpv5 = ["faultst000dp075", "faultst-075dp075", "faultst075dp075", "faultst000dp000"];
    let chosen: Vec<&ReferenceStation> = if tpv5.iter().all(|n| reference.stations.iter().any(|s| s.name == *n)) {
        tpv5.iter().filter_map(|n| reference.stations.iter().find(|s| s.name == *n)).collect()
    } else {
        reference.stations.iter().take(4).collect()
    };
    for r in chosen {
        let name = r.name.as_str();
        let Some(s) = stations.iter().min_by(|a, b| {
            let d = |s: &RunStation| (s.at_km[0] - r.at_km[0]).hypot(s.at_km[1] - r.at_km[1]);
            d(a).total_cmp(&d(b))
        }) else {
            continue;
        };
        let mut p = Panel::linear("time (s)", "slip rate (m/s)");
        p.name = format!("{name}: run's node at ({:.1}, {:.1}) km", s.at_km[0], s.at_km[1]);
        p.compact = true;
        if let Some((t, v)) = reference.slip_rates.get(name) {
            p.lines.push(Line {
                label: "reference".into(),
                points: t.iter().copied().zip(v.iter().copied()).collect(),
                colour: RGBColor(150, 150, 150),
                width: 3,
                alpha: 1.0,
            });
        }
        p.lines.push(Line {
            label: label.into(),
            points: s.time_s.iter().copied().zip(s.slip_rate_m_s.iter().copied()).collect(),
            colour: RGBColor(200, 30, 30),
            width: 1,
            alpha: 1.0,
        });
        panels.push(p);
    }
    let problem = reference.problem.as_str();
    let mut sheet = Sheet::new(format!("{problem}: {label} against the reference"), 1, vec![panels.remove(0)]);
    sheet = sheet.with_height(560);
    draw(path, &sheet).map_err(|e| CompareError::Figure(e.to_string()))?;
    let series = Sheet::new(format!("{problem} slip rates: {label} against the reference"), 2, panels).with_height(800);
    let series_path =
        path.with_file_name(format!("{}_slip_rates.png", path.file_stem().and_then(|s| s.to_str()).unwrap_or("tpv5")));
    draw(&series_path, &series).map_err(|e| CompareError::Figure(e.to_string()))?;
    Ok(())
}
