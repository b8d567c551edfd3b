//! The figures of the report, each from the tables of the output folder.

mod cracks;

use std::path::Path;

use plotters::chart::SeriesLabelPosition;
use plotters::style::{BLACK, RGBColor};

use stickslip_seismo::events::EventKind;
use stickslip_seismo::spectra::intensity::G;
use stickslip_solver::Channel;
use stickslip_solver::scene::{Component, Kinematic};
use stickslip_store::io::scan_glob;
use stickslip_store::schema::{CONTROL, FOURIER, SERIES, SPECTRA, col};
use stickslip_store::tables::records::{Spectra, read_fourier};
use stickslip_store::tables::series::{Trace, read_control, read_series_channel};

use crate::charts::{self, Band, HLine, Line, Marker, Panel, Points};
use crate::plot::{WIDTH, colour, decimate};
use crate::{ReportError, ReportInput};

/// What drawing a figure gave.
pub enum Outcome {
    /// Drawn, with its heading and caption.
    Drawn {
        /// Heading.
        title: String,
        /// What it shows.
        caption: String,
    },
    /// Not drawn, and why.
    Skipped(String),
}

/// Draws one figure into a file.
pub type Draw = fn(&ReportInput, &Path) -> Result<Outcome, ReportError>;

/// Every figure, in page order.
pub const ALL: [(&str, Draw); 15] = [
    ("shear_stress.png", shear_stress),
    ("normal_stress.png", normal_stress),
    ("mean_slip.png", mean_slip),
    ("acceleration_s2.png", acceleration_s2),
    ("acceleration_run.png", acceleration_run),
    ("response_spectra_z.png", spectra_z),
    ("response_spectra_x.png", spectra_x),
    ("fourier.png", fourier),
    ("stress_drop_vs_duration.png", drop_vs_duration),
    ("recurrence.png", recurrence),
    ("magnitude.png", magnitude),
    ("attenuation.png", attenuation),
    ("energy.png", energy),
    ("cracks.png", cracks::crack_map),
    ("acoustic_emission.png", cracks::emission),
];

fn seeds_text(seeds: &[u64]) -> String {
    let s: Vec<String> = seeds.iter().map(|s| s.to_string()).collect();
    match s.len() {
        0 => "no seed".into(),
        1 => format!("seed {}", s[0]),
        _ => format!("seeds {}", s.join(", ")),
    }
}

/// (time, values) of a series column for one seed, if recorded.
fn series(d: &ReportInput, seed: u64, column: &str) -> Result<Option<Trace>, ReportError> {
    let Some(df) = d.part(&SERIES, seed)? else { return Ok(None) };
    Ok(read_series_channel(&df, column)?)
}

/// The node and component the accelerogram figures show: the first node with records (or control
/// node recording acceleration), component z if recorded.
fn accelerogram_channel(d: &ReportInput) -> Option<(u64, Component)> {
    let control = &d.pipeline.scene.record.control;
    let wanted = |c: &&stickslip_solver::scene::ControlChannel| {
        d.pipeline.accelerograms.as_ref().map_or(c.quantity == Kinematic::Acceleration, |a| a.wants(c))
    };
    let node = control.iter().find(wanted)?.node;
    let comps: Vec<_> = control.iter().filter(wanted).filter(|c| c.node == node).map(|c| c.component).collect();
    let comp = if comps.contains(&Component::Z) { Component::Z } else { *comps.first()? };
    Some((node.ldem(), comp))
}

/// (time, acceleration) of a control channel for one seed.
fn control(d: &ReportInput, seed: u64, node: u64, comp: Component) -> Result<Option<Trace>, ReportError> {
    let Some(df) = d.part(&CONTROL, seed)? else { return Ok(None) };
    Ok(read_control(&df, node, comp, Kinematic::Acceleration)?)
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
            markers.push(Marker { at: (start, value_at(&t, &kpa, start)), text: label, colour: colour(k) });
        }
        lines.push(Line::new(format!("seed {seed}"), decimate(&t, &kpa, WIDTH as usize), k));
    }
    if lines.is_empty() {
        return Ok(Outcome::Skipped("no shear stress recorded".into()));
    }
    // Dozens of labels overlap: beyond that, triangles only.
    if markers.len() > 24 {
        markers.iter_mut().for_each(|m| m.text.clear());
    }
    charts::linear(
        path,
        "Shear stress on the base (paper Fig. 3)",
        "time since the start of shearing (s)",
        "τ (kPa)",
        &lines,
        &markers,
        &[],
        SeriesLabelPosition::LowerRight,
    )?;
    Ok(Outcome::Drawn {
        title: "Shear stress τ(t)".into(),
        caption: format!(
            "Mean shear stress on the base, τ = −ΣF_x/A, for {}. Triangles mark the start of the main shocks S1, S2, … \
             found by the event detector (stress drops of at least half the largest); the smaller drops between them are \
             fore- and aftershocks.",
            seeds_text(&d.seeds)
        ),
    })
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
    charts::linear(
        path,
        &format!("Normal stress on the base, seed {seed} (paper Fig. 4)"),
        "time since the start of shearing (s)",
        "σ (kPa)",
        &[Line::new(format!("seed {seed}"), decimate(&t, &kpa, WIDTH as usize), 0)],
        &[],
        &[HLine { y: weight, text: format!("self-weight ρgh = {weight:.2} kPa"), colour: BLACK }],
        SeriesLabelPosition::UpperLeft,
    )?;
    Ok(Outcome::Drawn {
        title: "Normal stress σ(t)".into(),
        caption: format!(
            "Mean normal stress ΣN/A on the base for seed {seed}, with the self-weight level. During the drops it swings \
             by up to {:.0}% of the self-weight averaged over 1 ms ({:.0}% in single samples; the paper reports up to \
             30%), as nodes lift off and land.",
            100.0 * avg_swing,
            100.0 * raw_swing
        ),
    })
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
    charts::linear(
        path,
        "Mean displacement of the contact surface (paper Fig. 5)",
        "time since the start of shearing (s)",
        "δ (µm)",
        &lines,
        &[],
        &[],
        SeriesLabelPosition::LowerRight,
    )?;
    Ok(Outcome::Drawn {
        title: "Mean contact displacement δ(t)".into(),
        caption: format!(
            "Mean x-displacement of the contact nodes for {}: the block moves in jumps at the stress drops and stands \
             still in between.",
            seeds_text(&d.seeds)
        ),
    })
}

fn acceleration_s2(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some((node, comp)) = accelerogram_channel(d) else {
        return Ok(Outcome::Skipped("no control node records acceleration".into()));
    };
    let mut panels = Vec::new();
    for (k, &seed) in d.seeds.iter().enumerate() {
        let Some(&(_, s2)) = main_shocks(d, seed)?.iter().find(|(l, _)| l == "S2") else { continue };
        let Some((t, a)) = control(d, seed, node, comp)? else { continue };
        let (from, to) = (s2 - 0.005, s2 + 0.025);
        let pts: Vec<(f64, f64)> =
            t.iter().zip(&a).filter(|(x, _)| **x >= from && **x <= to).map(|(x, y)| ((x - s2) * 1e3, *y)).collect();
        panels.push(Line::new(format!("seed {seed}"), pts, k));
    }
    if panels.is_empty() {
        return Ok(Outcome::Skipped("no seed has a main shock S2".into()));
    }
    charts::stacked(
        path,
        &format!("Acceleration of node {node} ({}) around S2 (paper Fig. 6)", comp.name()),
        "time from the start of S2 (ms)",
        "a (m/s²)",
        &panels,
    )?;
    Ok(Outcome::Drawn {
        title: format!("Node {node} acceleration around S2"),
        caption: format!(
            "Artificial accelerograms: the {} acceleration of control node {node} from 5 ms before to 25 ms after the \
             start of each seed's main shock S2 (model scale; at prototype scale times ×λ and accelerations ÷λ). Each seed \
             gives a different record.",
            comp.name()
        ),
    })
}

fn acceleration_run(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some((node, comp)) = accelerogram_channel(d) else {
        return Ok(Outcome::Skipped("no control node records acceleration".into()));
    };
    let mut panels = Vec::new();
    for (k, &seed) in d.seeds.iter().enumerate() {
        let Some((t, a)) = control(d, seed, node, comp)? else { continue };
        panels.push(Line::new(format!("seed {seed}"), decimate(&t, &a, WIDTH as usize), k));
    }
    if panels.is_empty() {
        return Ok(Outcome::Skipped("no accelerogram recorded".into()));
    }
    charts::stacked(
        path,
        &format!("Acceleration of node {node} ({}) over the whole run (paper Fig. 7)", comp.name()),
        "time since the start of shearing (s)",
        "a (m/s²)",
        &panels,
    )?;
    Ok(Outcome::Drawn {
        title: format!("Node {node} acceleration, whole run"),
        caption: format!(
            "The {} acceleration of control node {node} through all the main shocks, one panel per seed (model scale).",
            comp.name()
        ),
    })
}

fn spectra_z(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    spectra(d, path, Component::Z)
}

fn spectra_x(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    spectra(d, path, Component::X)
}

/// PSA at 5% (or the nearest damping), model and prototype scale: every seed thin, the mean and
/// the 5–95% band bold.
fn spectra(d: &ReportInput, path: &Path, comp: Component) -> Result<Outcome, ReportError> {
    let (Some(stats), Some((node, _))) = (&d.psa_stats, accelerogram_channel(d)) else {
        return Ok(Outcome::Skipped("no spectra analysis".into()));
    };
    let cname = comp.name();
    let damping =
        stats.damping.iter().copied().min_by(|a, b| (a - 0.05).abs().total_cmp(&(b - 0.05).abs())).unwrap_or(0.05);
    if !(0..stats.node.len()).any(|i| stats.node[i] == node && stats.component[i] == cname) {
        return Ok(Outcome::Skipped(format!("no {cname} spectra of node {node}")));
    }
    let all = scan_glob(&d.folder.part_glob(&SPECTRA))?.map(|df| Spectra::read(&df)).transpose()?;
    let mut panels = Vec::new();
    let mut count = 0;
    for (scale, unit_note) in [("model", "model scale"), ("prototype", "prototype scale (λ)")] {
        let rows: Vec<usize> = (0..stats.node.len())
            .filter(|&i| {
                stats.node[i] == node
                    && stats.component[i] == cname
                    && stats.scale[i] == scale
                    && stats.damping[i] == damping
            })
            .collect();
        let rows: Vec<usize> = rows.into_iter().filter(|&i| stats.in_band[i]).collect();
        let mut lines = Vec::new();
        if let Some(sp) = &all {
            let mut records: Vec<(u64, &str)> = (0..sp.seed.len())
                .filter(|&i| sp.node[i] == node && sp.component[i] == cname)
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
            x_desc: "period (s)".into(),
            y_desc: "PSA (m/s²)".into(),
            lines,
            bands: vec![band],
            legend_at: SeriesLabelPosition::LowerLeft,
            dots: false,
        });
    }
    charts::loglog_panels(path, &panels)?;
    Ok(Outcome::Drawn {
        title: format!("Response spectra, node {node} ({cname})"),
        caption: format!(
            "Pseudo-spectral acceleration at {:.0}% damping of the processed {cname} records of node {node}: every record \
             thin ({count} records), the mean and the 5–95% band across records bold, drawn only over the usable band \
             (periods between 1/f_max of the lattice and 1/(1.25·f_low) of the filter). Left at model scale, right at \
             prototype scale (periods ×λ, PSA ÷λ). Exact peaks for the straight-line reading of the samples \
             (Nigam–Jennings).",
            100.0 * damping
        ),
    })
}

fn fourier(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some((node, comp)) = accelerogram_channel(d) else {
        return Ok(Outcome::Skipped("no accelerogram".into()));
    };
    let cname = comp.name();
    let mut lines = Vec::new();
    for (k, &seed) in d.seeds.iter().enumerate() {
        let Some(df) = d.part(&FOURIER, seed)? else { continue };
        let Some((f, a)) = read_fourier(&df, &format!("S2-n{node}-{cname}"))? else { continue };
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
    if lines.is_empty() {
        return Ok(Outcome::Skipped("no Fourier spectra".into()));
    }
    charts::loglog_panels(
        path,
        &[Panel {
            title: format!("Fourier amplitude of node {node} ({cname}), model scale"),
            x_desc: "frequency (Hz)".into(),
            y_desc: "|X|·Δt (m/s)".into(),
            lines,
            bands: vec![],
            legend_at: SeriesLabelPosition::LowerLeft,
            dots: false,
        }],
    )?;
    Ok(Outcome::Drawn {
        title: format!("Fourier spectra, node {node} ({cname})"),
        caption: format!(
            "Fourier amplitude |X(f)|·Δt of the processed {cname} record of node {node} in main shock S2 for {} \
             (zero-padded to a power of two; the largest value per 1/200 decade is drawn). At prototype scale the \
             frequencies are divided by λ, the amplitudes unchanged.",
            seeds_text(&d.seeds)
        ),
    })
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
    charts::scatter(
        path,
        "Stress drop against duration, all events",
        "duration (ms)",
        "stress drop (kPa)",
        &groups,
        &[],
        &[],
        None,
        SeriesLabelPosition::LowerRight,
    )?;
    Ok(Outcome::Drawn {
        title: "Event catalogue: stress drop vs duration".into(),
        caption: format!(
            "Every event of every seed ({} events): main shocks coloured by rank, fore- and aftershocks grey. Duration is \
             the slip burst (smoothed mean slip rate above the detector's thresholds); the stress drop is measured on the \
             1-ms-averaged τ.",
            ev.len()
        ),
    })
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
    let lines = [Line { label: "mean across seeds".into(), points: means, colour: colour(1), width: 3, alpha: 1.0 }];
    let paper = [HLine { y: 25.8, text: "paper: S1→S2 25.8 ms".into(), colour: BLACK }];
    charts::scatter(
        path,
        "Recurrence between main shocks",
        "main shock",
        &format!("time since the previous main shock ({unit})"),
        &groups,
        &lines,
        if slow { &[] } else { &paper },
        Some(&rank_ticks),
        SeriesLabelPosition::UpperRight,
    )?;
    Ok(Outcome::Drawn {
        title: "Recurrence of the main shocks".into(),
        caption: "Time from the start of the previous main shock, per main shock across seeds (points jittered \
                  sideways), the mean per rank, and the paper's S1→S2 recurrence."
            .into(),
    })
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
    let paper = [HLine { y: 6.77, text: "paper: M = 6.77 (S2)".into(), colour: BLACK }];
    charts::scatter(
        path,
        &format!("Magnitude of the main shocks at prototype scale (λ = {lambda:.0})"),
        "main shock",
        "magnitude",
        &groups,
        &[],
        &paper,
        Some(&rank_ticks),
        SeriesLabelPosition::MiddleRight,
    )?;
    Ok(Outcome::Drawn {
        title: "Magnitude per main shock".into(),
        caption: "Riera et al.'s magnitude from the paper's seismic moment (Eq. 15, with its extra factor λ) and the \
                  moment magnitude Mw from the dimensionally consistent moment Δσ·L_p·A_p, for every main shock of every \
                  seed, against the paper's M = 6.77 for S2."
            .into(),
    })
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
    charts::scatter(
        path,
        "Peak acceleration against distance from the hypocentre",
        "log10 distance (m)",
        "log10 PGA (m/s²)",
        &groups,
        &lines,
        &[],
        None,
        SeriesLabelPosition::UpperLeft,
    )?;
    Ok(Outcome::Drawn {
        title: "Attenuation of peak acceleration".into(),
        caption: format!(
            "Peak magnitude of the recorded acceleration of every control node during every main shock, against its \
             distance from the shock's hypocentre (the first contact node to slide for good), all seeds, model scale; \
             least-squares line over all main shocks: {fit_text}. The block is 1 m long, so these are near-field \
             distances; g = {G} m/s²."
        ),
    })
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
    charts::linear(
        path,
        &format!("Energy balance, seed {seed}"),
        "time since the start of shearing (s)",
        "energy since the start of the run (mJ)",
        &lines,
        &[],
        &[],
        SeriesLabelPosition::UpperLeft,
    )?;
    Ok(Outcome::Drawn {
        title: "Energy terms".into(),
        caption: format!(
            "Cumulative work of gravity and the driver against what is stored (elastic, kinetic) and dissipated \
             (damping, friction, landings) for seed {seed}, counted from the start of the self-weight stage. The largest \
             |residual| is {residual:.2e} mJ against {work:.3} mJ of external work: the balance closes to round-off."
        ),
    })
}
