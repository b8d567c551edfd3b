//! What the page of a fault scene (`[fault]`, docs/model.md §15) shows in place of the paper's
//! block: the source of each seed's rupture (the `source` table) with its rupture figure, the
//! stations (the `stations` table) and the fault's parameters. Every number is the table's,
//! rounded for the page.

// The page is built from literal HTML fragments that carry their own line ends.
#![allow(clippy::write_with_newline)]

use std::fmt::Write as _;

use stickslip_seismo::catalogue::compact;
use stickslip_store::tables::source::Sources;

use crate::input::ReportInput;
use crate::markup::{esc, figure_html};
use crate::summary::Figure;

/// Rows of a per-seed table shown on the page; the rest are in the table's file.
pub(crate) const MAX_ROWS: usize = 60;

/// Mean and sample standard deviation of the finite `values` (the deviation NaN for fewer than 2).
fn mean_std(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, if v.len() > 1 { var.sqrt() } else { f64::NAN })
}

/// One source column: its heading, how a value is written, and the value of row `i`.
struct Column {
    heading: &'static str,
    digits: usize,
    /// Written with an exponent (`5.382e19`).
    exponent: bool,
    value: fn(&Sources, usize) -> f64,
}

const SOURCE_COLUMNS: [Column; 10] = [
    Column { heading: "Mw", digits: 2, exponent: false, value: |s, i| s.mw[i] },
    Column { heading: "M0 (N·m)", digits: 3, exponent: true, value: |s, i| s.m0_n_m[i] },
    Column { heading: "stress drop (MPa)", digits: 2, exponent: false, value: |s, i| s.stress_drop_pa[i] / 1e6 },
    Column { heading: "ruptured area (km²)", digits: 1, exponent: false, value: |s, i| s.ruptured_area_m2[i] / 1e6 },
    Column { heading: "mean slip (m)", digits: 2, exponent: false, value: |s, i| s.mean_slip_m[i] },
    Column { heading: "largest slip (m)", digits: 2, exponent: false, value: |s, i| s.max_slip_m[i] },
    Column { heading: "rupture duration (s)", digits: 2, exponent: false, value: |s, i| s.rupture_duration_s[i] },
    Column { heading: "peak slip rate (m/s)", digits: 2, exponent: false, value: |s, i| s.peak_slip_rate_m_s[i] },
    Column {
        heading: "median peak slip rate (m/s)",
        digits: 2,
        exponent: false,
        value: |s, i| s.median_peak_slip_rate_m_s[i],
    },
    Column { heading: "ruptured nodes", digits: 0, exponent: false, value: |s, i| s.ruptured_nodes[i] as f64 },
];

fn number(v: f64, digits: usize, exponent: bool) -> String {
    if !v.is_finite() {
        "–".into()
    } else if exponent {
        format!("{v:.digits$e}")
    } else {
        format!("{v:.digits$}")
    }
}

/// The source section: one row per seed whose fault ruptured (mean ± standard deviation over them
/// when there are several), the seeds that did not rupture, and the rupture figure.
pub(crate) fn source_section(w: &mut String, d: &ReportInput, figures: &[Figure]) {
    let _ = write!(
        w,
        "<h2>Source</h2>\n<p>The rupture of each seed, from its fault's own slip (table <a \
         href=\"tables/source.parquet\">source</a>; docs/model.md §15): the seismic moment M0 = Σ μ·A·|D| (μ the rigidity at each node's depth) over the \
         nodes whose slip rate reached [events] rupture_rate_m_s, Mw = (2/3)·(log10 M0 − 9.1) (Hanks &amp; Kanamori), \
         the stress drop averaged over them by area, the rupture duration when the last of them ruptured, the \
         hypocentre where the first did.</p>\n"
    );
    let Some(s) = d.sources.as_ref().filter(|s| !s.seed.is_empty()) else {
        let _ = write!(w, "<p>No seed's fault ruptured: the source table is empty or absent.</p>\n");
        return;
    };
    let _ = write!(w, "<table>\n<tr><th class=\"l\">seed</th>");
    for c in &SOURCE_COLUMNS {
        let _ = write!(w, "<th>{}</th>", esc(c.heading));
    }
    let _ = write!(w, "<th>hypocentre x, y (km)</th></tr>\n");
    for i in 0..s.seed.len().min(MAX_ROWS) {
        let _ = write!(w, "<tr><th class=\"l\">{}</th>", s.seed[i]);
        for c in &SOURCE_COLUMNS {
            let _ = write!(w, "<td>{}</td>", number((c.value)(s, i), c.digits, c.exponent));
        }
        let [x, y] = s.hypocentre_m[i];
        let _ = write!(w, "<td>{}, {}</td></tr>\n", number(x / 1e3, 2, false), number(y / 1e3, 2, false));
    }
    if s.seed.len() > 1 {
        let _ = write!(w, "<tr><th class=\"l\">{} seeds, mean ± sd</th>", s.seed.len());
        for c in &SOURCE_COLUMNS {
            let (m, sd) = mean_std((0..s.seed.len()).map(|i| (c.value)(s, i)));
            let _ = write!(w, "<td>{} ± {}</td>", number(m, c.digits, c.exponent), number(sd, c.digits, c.exponent));
        }
        let _ = write!(w, "<td></td></tr>\n");
    }
    let _ = write!(w, "</table>\n");
    if s.seed.len() > MAX_ROWS {
        let _ = write!(w, "<p>The first {MAX_ROWS} of {} seeds; every row is in the table.</p>\n", s.seed.len());
    }
    let origin = d.pipeline.scene.fault.as_ref().map_or([0.0, 0.0], |f| f.origin_m);
    let _ = write!(
        w,
        "<p>Coordinates on the fault: x along strike, y down dip (the depth below the free surface y = 0); [fault] \
         origin_m = [{}, {}] m is where the stations' and the figures' distances are measured from.</p>\n",
        compact(origin[0]),
        compact(origin[1])
    );
    if let Some(runs) = &d.runs {
        let quiet: Vec<String> =
            runs.ok_seeds().into_iter().filter(|seed| !s.seed.contains(seed)).map(|seed| seed.to_string()).collect();
        if !quiet.is_empty() {
            let _ = write!(
                w,
                "<p>Seeds that ran but whose fault did not rupture (no node reached [events] rupture_rate_m_s): {}.</p>\n",
                esc(&quiet.join(", "))
            );
        }
    }
    if let Some(f) = figures.iter().find(|f| f.file == RUPTURE_FIGURE) {
        let _ = write!(w, "{}", figure_html(f));
    }
}

/// The figure the source section shows (and the figure list does not repeat).
pub(crate) const RUPTURE_FIGURE: &str = "rupture_time.png";

/// The stations section: the first drawn seed's stations, their distances, peaks and band.
pub(crate) fn stations_section(w: &mut String, d: &ReportInput) {
    let Some(st) = d.stations.as_ref().filter(|s| !s.seed.is_empty()) else { return };
    let Some(seed) = d.seeds.iter().copied().find(|seed| st.seed.contains(seed)).or_else(|| st.seed.first().copied())
    else {
        return;
    };
    // Nearest first (ties by name), as a reader scans a station list.
    let mut rows: Vec<usize> = (0..st.seed.len()).filter(|&i| st.seed[i] == seed).collect();
    rows.sort_by(|&a, &b| st.r_rup_m[a].total_cmp(&st.r_rup_m[b]).then_with(|| st.station[a].cmp(&st.station[b])));
    let notes = rows.iter().any(|&i| !st.motion_note[i].is_empty());
    let mut seeds = st.seed.clone();
    seeds.sort_unstable();
    seeds.dedup();
    let which = if seeds.len() > 1 {
        format!("seed {seed} (one of {} seeds; every seed's rows are in the table)", seeds.len())
    } else {
        format!("seed {seed}")
    };
    let _ = write!(
        w,
        "<h2>Stations</h2>\n<p>{} stations of {which} (table <a href=\"tables/stations.parquet\">stations</a>; \
         docs/model.md §15–16): distances to the rupture (R_rup to the nearest ruptured node, R_JB to its surface \
         projection, epicentral to the hypocentre), the largest horizontal (x, z) acceleration and velocity of the \
         raw record, RotD50 PGA and PGV of the processed record, its band-pass and the periods its spectra are usable \
         over (the lattice carries waves faithfully only below its f_max: what the raw record holds above it is the \
         lattice's, not the ground's).</p>\n<table>\n<tr><th class=\"l\">station</th><th>R_rup (km)</th>\
         <th>R_JB (km)</th><th>epicentral (km)</th><th>azimuth (°)</th><th>PGA (m/s²)</th><th>PGV (m/s)</th>\
         <th>RotD50 PGA (m/s²)</th><th>RotD50 PGV (m/s)</th><th>band-pass (Hz)</th><th>usable periods (s)</th>{}\
         </tr>\n",
        rows.len(),
        if notes { "<th class=\"l\">why no processed record</th>" } else { "" }
    );
    let km = |v: f64| number(v / 1e3, 1, false);
    let pair = |p: [f64; 2], digits: usize| {
        if p.iter().all(|v| v.is_finite()) {
            format!("{}–{}", number(p[0], digits, false), number(p[1], digits, false))
        } else {
            "–".into()
        }
    };
    for &i in rows.iter().take(MAX_ROWS) {
        let _ = writeln!(
            w,
            "<tr><th class=\"l\">{}</th><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>\
             <td>{}</td><td>{}</td><td>{}</td>{}</tr>",
            esc(&st.station[i]),
            km(st.r_rup_m[i]),
            km(st.r_jb_m[i]),
            km(st.epicentral_m[i]),
            number(st.azimuth_deg[i], 0, false),
            number(st.pga_m_s2[i], 3, false),
            number(st.pgv_m_s[i], 3, false),
            number(st.pga_rotd50_m_s2[i], 3, false),
            number(st.pgv_rotd50_m_s[i], 3, false),
            pair(st.band_hz[i], 2),
            pair(st.usable_s[i], 2),
            if notes { format!("<td class=\"l\">{}</td>", esc(&st.motion_note[i])) } else { String::new() }
        );
    }
    let _ = write!(w, "</table>\n");
    if rows.len() > MAX_ROWS {
        let _ = write!(w, "<p>The first {MAX_ROWS} of {} stations; every row is in the table.</p>\n", rows.len());
    }
}

/// The parameters of a fault scene: its block, material and friction, the fault's tractions, the
/// time step, the run, and the stations.
pub(crate) fn parameters(d: &ReportInput, common: Vec<(&'static str, String)>) -> Vec<(&'static str, String)> {
    let s = &d.pipeline.scene;
    let mut rows = common;
    if let Some(f) = &s.fault {
        let span = |v: &mut dyn Iterator<Item = f64>| {
            v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)))
        };
        let mpa = |(a, b): (f64, f64)| {
            if a == b {
                format!("{} MPa", compact(a / 1e6))
            } else {
                format!("{}–{} MPa", compact(a / 1e6), compact(b / 1e6))
            }
        };
        let normal = span(&mut f.normal_pa.iter().copied());
        let shear = span(&mut f.shear_pa.iter().map(|t| t[0].hypot(t[1])));
        let mut text = format!(
            "normal stress {}, initial shear stress {} over its nodes (background and patches, before any random field)",
            mpa(normal),
            mpa(shear)
        );
        if let Some(g) = f.overburden_gradient_pa_m {
            let _ = write!(
                text,
                "; growing with depth as an overburden of {} Pa/m (every traction here, the random field and the \
                 nucleation too, scaled by its node's share at its depth, docs/model.md §15.3)",
                compact(g)
            );
        }
        if let Some(r) = &f.stochastic {
            let _ = write!(
                text,
                "; a von Kármán field per seed, standard deviation {} MPa, correlation length {} m, Hurst {}",
                compact(r.std_pa / 1e6),
                compact(r.correlation_length_m),
                compact(r.hurst)
            );
        }
        if let Some(n) = &f.nucleation {
            let _ = write!(
                text,
                "; nucleation per seed: a {} m square at {} MPa, centred in x {}–{} m, y {}–{} m",
                compact(n.size_m),
                compact(n.shear_pa / 1e6),
                compact(n.x_m[0]),
                compact(n.x_m[1]),
                compact(n.y_m[0]),
                compact(n.y_m[1])
            );
        }
        rows.push(("fault", text));
    }
    let sh = &s.shear;
    rows.push((
        "run",
        format!(
            "{} s from the prestressed state at rest, damping D = {} 1/s, no self-weight stage{}{}",
            compact(sh.duration_s),
            compact(sh.damping_per_s),
            if s.absorbing().is_empty() {
                String::new()
            } else {
                format!(", absorbing faces {}", s.absorbing().iter().map(|f| f.name()).collect::<Vec<_>>().join(", "))
            },
            if s.drivers().is_empty() {
                String::new()
            } else {
                format!(
                    ", drivers LDEM {}",
                    s.drivers().iter().map(|n| n.ldem().to_string()).collect::<Vec<_>>().join(", ")
                )
            }
        ),
    ));
    if !s.stations.is_empty() {
        rows.push((
            "stations",
            format!("{} ([[stations]]), recorded every {}", s.stations.len(), interval(s.record.interval_s)),
        ));
    }
    rows.push(("scale", "its own (λ = 1): the paper's similarity scaling does not apply".into()));
    rows
}

fn interval(iv: Option<f64>) -> String {
    iv.map_or("step".into(), |v| format!("{} s", compact(v)))
}
