//! The figures of the sliding interface over the run: shear stress on the base (as an envelope with
//! a zoom on the largest drop for a long run), normal stress against the self-weight, mean slip of
//! the contact surface, and the energy balance.

use std::path::Path;

use plotters::style::BLACK;

use stickslip_solver::Channel;
use stickslip_store::schema::SERIES;
use stickslip_store::tables::series::read_series_channel;

use super::Outcome;
use super::common::{drawn, main_shocks, paper_fig, seeds_text, series};
use crate::charts::{Band, HLine, Line, Marker, Panel, Points, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;
use crate::plot::{WIDTH, colour, decimate};

fn value_at(t: &[f64], y: &[f64], at: f64) -> f64 {
    let i = t.partition_point(|&x| x < at).min(t.len().saturating_sub(1));
    y[i]
}

pub(super) fn shear_stress(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (mut lines, mut markers) = (Vec::new(), Vec::new());
    for (k, &seed) in d.seeds.iter().enumerate() {
        let Some((t, tau)) = series(d, seed, Channel::ShearStress.name())? else { continue };
        let kpa: Vec<f64> = tau.iter().map(|v| v / 1e3).collect();
        for (label, start) in main_shocks(d, seed)? {
            markers.push(Marker {
                at: (start, value_at(&t, &kpa, start)),
                text: label,
                colour: colour(k),
                text_colour: colour(k),
            });
        }
        lines.push(Line::new(format!("seed {seed}"), decimate(&t, &kpa, WIDTH as usize), k));
    }
    if lines.is_empty() {
        return Ok(Outcome::Skipped("no shear stress recorded".into()));
    }
    if markers.len() > LONG_RUN_MAIN_SHOCKS {
        return long_shear_stress(d, path);
    }
    // Several seeds share each main-shock rank, and their S2s lie close together: each rank is
    // labelled once, in black (it names the triangles of every seed), at its triangle nearest the
    // rank's median time, so the labels read S1, S2, … from left to right even where one seed's
    // S3 comes before another's S2; the chart drops any label that would still overlap another.
    if d.seeds.len() > 1 {
        for (i, keep) in label_once_per_rank(&markers).into_iter().enumerate() {
            if keep {
                markers[i].text_colour = BLACK;
            } else {
                markers[i].text.clear();
            }
        }
    }
    let panel = Panel { lines, markers, ..Panel::linear("time since the start of shearing (s)", "τ (kPa)") };
    let sheet = Sheet::new(format!("Shear stress on the base{}", paper_fig(d, 3)), 1, vec![panel]);
    drawn(
        path,
        &sheet,
        "Shear stress τ(t)".into(),
        format!(
            "Mean shear stress on the base, τ = −ΣF_x/A, for {}. Triangles mark the start of the main shocks S1, S2, … \
             found by the event detector (stress drops of at least half the largest), each rank labelled once; the \
             smaller drops between them are fore- and aftershocks.",
            seeds_text(&d.seeds)
        ),
    )
}

/// For markers of several seeds labelled by rank (`S1`, `S2`, …): whether each keeps its label —
/// one per rank, rank by rank, the one nearest the median time of its rank among those after the
/// previous rank's label (so the labels read in time order).
fn label_once_per_rank(markers: &[Marker]) -> Vec<bool> {
    let mut by_rank: std::collections::BTreeMap<u32, Vec<usize>> = Default::default();
    for (i, m) in markers.iter().enumerate() {
        if let Some(r) = super::common::rank_of(&m.text) {
            by_rank.entry(r).or_default().push(i);
        }
    }
    let mut keep = vec![false; markers.len()];
    let mut after = f64::NEG_INFINITY;
    for members in by_rank.values() {
        let mut times: Vec<f64> = members.iter().map(|&i| markers[i].at.0).collect();
        times.sort_by(f64::total_cmp);
        let median = times[(times.len() - 1) / 2];
        let later: Vec<usize> = members.iter().copied().filter(|&i| markers[i].at.0 > after).collect();
        let Some(best) = later.into_iter().min_by(|&a, &b| {
            (markers[a].at.0 - median).abs().total_cmp(&(markers[b].at.0 - median).abs()).then(a.cmp(&b))
        }) else {
            continue;
        };
        keep[best] = true;
        after = markers[best].at.0;
    }
    keep
}

/// More main shocks than this in the τ(t) figure and it is drawn as a long run: an envelope with
/// ticks, and a zoom on the largest event.
pub const LONG_RUN_MAIN_SHOCKS: usize = 40;

/// Per pixel column, the minimum and maximum of `y` (x at the column's centre).
fn envelope(t: &[f64], y: &[f64], columns: usize) -> Vec<(f64, f64, f64)> {
    let (Some(&t0), Some(&t1)) = (t.first(), t.last()) else { return vec![] };
    let width = (t1 - t0).max(f64::MIN_POSITIVE) / columns as f64;
    let mut out: Vec<(f64, f64, f64)> = Vec::with_capacity(columns);
    let mut current = usize::MAX;
    for (&x, &v) in t.iter().zip(y) {
        let k = (((x - t0) / width) as usize).min(columns - 1);
        if k != current {
            out.push((t0 + (k as f64 + 0.5) * width, v, v));
            current = k;
        } else if let Some(last) = out.last_mut() {
            last.1 = last.1.min(v);
            last.2 = last.2.max(v);
        }
    }
    out
}

/// τ(t) of a long run (first seed): the min–max envelope per pixel column with a tick per main
/// shock, and below it the stretch from the main shock before the largest drop to the one after.
fn long_shear_stress(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(&seed) = d.seeds.first() else { return Ok(Outcome::Skipped("no successful seed".into())) };
    let Some((t, tau)) = series(d, seed, Channel::ShearStress.name())? else {
        return Ok(Outcome::Skipped("no shear stress recorded".into()));
    };
    let kpa: Vec<f64> = tau.iter().map(|v| v / 1e3).collect();
    let shocks = main_shocks(d, seed)?;
    let top = kpa.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let ticks = Points {
        label: format!("main shocks ({})", shocks.len()),
        points: shocks.iter().map(|(_, s)| (*s, top * 1.04)).collect(),
        colour: colour(3),
        size: 2,
    };
    let whole = Panel {
        bands: vec![Band {
            points: envelope(&t, &kpa, WIDTH as usize),
            colour: colour(0),
            label: "min–max per pixel".into(),
        }],
        points: vec![ticks],
        ..Panel::linear("time since the start of shearing (s)", "τ (kPa)")
    };
    // The largest main shock by stress drop, and its neighbours.
    let ev = d.events.as_ref();
    let largest = ev.and_then(|ev| {
        (0..ev.len())
            .filter(|&i| ev.seed[i] == seed && ev.kind[i].is_main())
            .max_by(|&a, &b| ev.stress_drop_pa[a].total_cmp(&ev.stress_drop_pa[b]))
            .map(|i| (ev.kind[i].label(), ev.start_s[i], ev.stress_drop_pa[i]))
    });
    let mut panels = vec![whole];
    let mut zoom_text = String::new();
    if let Some((label, start, drop)) = largest {
        let before = shocks.iter().map(|s| s.1).filter(|&s| s < start).fold(t[0], f64::max);
        let after = shocks.iter().map(|s| s.1).find(|&s| s > start).unwrap_or(t[t.len() - 1]);
        let (a, b) = (t.partition_point(|&x| x < before), t.partition_point(|&x| x <= after));
        let markers: Vec<Marker> = shocks
            .iter()
            .filter(|s| s.1 >= before && s.1 <= after)
            .map(|(l, s)| Marker {
                at: (*s, value_at(&t, &kpa, *s)),
                text: l.clone(),
                colour: colour(0),
                text_colour: BLACK,
            })
            .collect();
        panels.push(Panel {
            lines: vec![Line::new("", decimate(&t[a..b], &kpa[a..b], WIDTH as usize), 0)],
            markers,
            name: format!("zoom: {label}, the largest drop ({:.2} kPa)", drop / 1e3),
            ..Panel::linear("time since the start of shearing (s)", "τ (kPa)")
        });
        zoom_text = format!(
            " Below, from the main shock before the largest drop ({label}, {:.2} kPa) to the one after it, at full \
             resolution.",
            drop / 1e3
        );
    }
    let sheet = Sheet::new(format!("Shear stress on the base, seed {seed}"), 1, panels);
    drawn(
        path,
        &sheet,
        "Shear stress τ(t)".into(),
        format!(
            "Mean shear stress on the base, τ = −ΣF_x/A, of seed {seed} over the whole run as the range of τ in each \
             pixel column (a long run: {} main shocks, each a tick above the envelope).{zoom_text}",
            shocks.len()
        ),
    )
}

pub(super) fn normal_stress(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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
    let panel = Panel {
        lines: vec![Line::new(format!("seed {seed}"), decimate(&t, &kpa, WIDTH as usize), 0)],
        hlines: vec![HLine { y: weight, text: format!("self-weight ρgh = {weight:.2} kPa"), colour: BLACK }],
        ..Panel::linear("time since the start of shearing (s)", "σ (kPa)")
    };
    let sheet = Sheet::new(format!("Normal stress on the base, seed {seed}{}", paper_fig(d, 4)), 1, vec![panel]);
    let paper = if d.paper { "; the paper reports up to 30%" } else { "" };
    drawn(
        path,
        &sheet,
        "Normal stress σ(t)".into(),
        format!(
            "Mean normal stress ΣN/A on the base for seed {seed}, with the self-weight level. During the drops it swings \
             by up to {:.0}% of the self-weight averaged over 1 ms ({:.0}% in single samples{paper}), as nodes lift \
             off and land.",
            100.0 * avg_swing,
            100.0 * raw_swing
        ),
    )
}

/// The unit a displacement axis reads best in: its name and how many of it make a metre (µm for
/// a block's jumps, mm or m for a fault's metres of slip).
pub(crate) fn length_unit(largest_m: f64) -> (&'static str, f64) {
    if largest_m >= 0.1 {
        ("m", 1.0)
    } else if largest_m >= 1e-4 {
        ("mm", 1e3)
    } else {
        ("µm", 1e6)
    }
}

pub(super) fn mean_slip(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let mut traces = Vec::new();
    for &seed in &d.seeds {
        let Some((t, delta)) = series(d, seed, Channel::MeanSlip.name())? else { continue };
        traces.push((seed, t, delta));
    }
    if traces.is_empty() {
        return Ok(Outcome::Skipped("mean slip not recorded".into()));
    }
    let largest =
        traces.iter().flat_map(|(_, _, v)| v.iter().map(|x| x.abs())).filter(|x| x.is_finite()).fold(0.0, f64::max);
    let (unit, per_m) = length_unit(largest);
    let lines: Vec<Line> = traces
        .iter()
        .enumerate()
        .map(|(k, (seed, t, delta))| {
            let v: Vec<f64> = delta.iter().map(|x| x * per_m).collect();
            Line::new(format!("seed {seed}"), decimate(t, &v, WIDTH as usize), k)
        })
        .collect();
    let panel = Panel { lines, ..Panel::linear("time since the start of shearing (s)", format!("δ ({unit})")) };
    let sheet = Sheet::new(format!("Mean displacement of the contact surface{}", paper_fig(d, 5)), 1, vec![panel]);
    let caption = if d.pipeline.scene.is_fault() {
        format!(
            "Mean x-displacement of every node of the fault face (barriers included) for {}. A node's slip is twice its \
             face's displacement, and the source's mean slip is over the ruptured nodes only, so this is not the \
             source table's mean slip.",
            seeds_text(&d.seeds)
        )
    } else {
        format!(
            "Mean x-displacement of the contact nodes for {}: the block moves in jumps at the stress drops and stands \
             still in between.",
            seeds_text(&d.seeds)
        )
    };
    drawn(path, &sheet, "Mean contact displacement δ(t)".into(), caption)
}

pub(super) fn energy(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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
    let panel = Panel {
        lines,
        ..Panel::linear("time since the start of shearing (s)", "energy since the start of the run (mJ)")
    };
    drawn(
        path,
        &Sheet::new(format!("Energy balance, seed {seed}"), 1, vec![panel]),
        "Energy terms".into(),
        format!(
            "Cumulative work of gravity and the driver against what is stored (elastic, kinetic) and dissipated \
             (damping, friction, landings) for seed {seed}, counted from the start of the self-weight stage. The largest \
             |residual| is {residual:.2e} mJ against {work:.3} mJ of external work: the balance closes to round-off."
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::{envelope, label_once_per_rank};
    use crate::charts::Marker;
    use plotters::style::BLACK;

    #[test]
    fn rank_labels_sit_in_time_order() {
        // Seed A: S1 at 0.10, S2 at 0.20, S3 at 0.30; seed B (later cycles): S1 at 0.12, S2 at
        // 0.31, S3 at 0.40; seed C: S1 at 0.05, S2 at 0.15. Labelled at the highest
        // triangle the order came out S1, S3, S2.
        let m =
            |t: f64, y: f64, text: &str| Marker { at: (t, y), text: text.into(), colour: BLACK, text_colour: BLACK };
        let markers = [
            m(0.10, 1.0, "S1"),
            m(0.05, 1.0, "S1"),
            m(0.15, 1.0, "S2"),
            m(0.20, 1.0, "S2"),
            m(0.30, 5.0, "S3"),
            m(0.12, 1.0, "S1"),
            m(0.31, 9.0, "S2"),
            m(0.40, 1.0, "S3"),
        ];
        let keep = label_once_per_rank(&markers);
        let mut labelled: Vec<(f64, &str)> =
            markers.iter().zip(&keep).filter(|(_, k)| **k).map(|(m, _)| (m.at.0, m.text.as_str())).collect();
        assert_eq!(labelled.len(), 3);
        labelled.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert_eq!(labelled.iter().map(|l| l.1).collect::<Vec<_>>(), ["S1", "S2", "S3"]);
    }

    #[test]
    fn the_envelope_keeps_each_columns_extremes() {
        // A sawtooth of 1,000 teeth over 100 columns: every column spans the whole tooth.
        let t: Vec<f64> = (0..100_000).map(|i| i as f64 * 1e-3).collect();
        let y: Vec<f64> = (0..100_000).map(|i| (i % 100) as f64).collect();
        let e = envelope(&t, &y, 100);
        assert_eq!(e.len(), 100);
        assert!(e.iter().all(|&(_, lo, hi)| lo == 0.0 && hi == 99.0), "{:?}", &e[..3]);
        // Column centres span the record.
        assert!((e[0].0 - 0.4999).abs() < 1e-3 && (e[99].0 - 99.4995).abs() < 1e-2, "{} {}", e[0].0, e[99].0);
    }
}
