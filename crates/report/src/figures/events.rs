//! The figures of the events of every seed: stress drop against duration (every event), the
//! recurrence and magnitude of the main shocks, and the attenuation of their peak acceleration with
//! distance from the hypocentre.

use std::path::Path;

use plotters::style::{BLACK, RGBColor};

use stickslip_seismo::events::EventKind;
use stickslip_seismo::spectra::intensity::G;
use stickslip_store::schema::col;

use super::Outcome;
use super::common::{drawn, rank_of, slope_se};
use crate::charts::{HLine, Line, Panel, Points, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;
use crate::plot::colour;

pub(super) fn drop_vs_duration(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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
    let panel = Panel { points: groups, ..Panel::linear("duration (ms)", "stress drop (kPa)") };
    drawn(
        path,
        &Sheet::new("Stress drop against duration, all events", 1, vec![panel]),
        "Event catalogue: stress drop vs duration".into(),
        format!(
            "Every event of every seed ({} events): main shocks coloured by rank, fore- and aftershocks grey. Duration is \
             the slip burst (smoothed mean slip rate above the detector's thresholds); the stress drop is measured on the \
             1-ms-averaged τ.",
            ev.len()
        ),
    )
}

/// Deterministic jitter in [−0.15, 0.15] from an index.
fn jitter(i: usize) -> f64 {
    ((i as f64 * 0.618_033_988_75).fract() - 0.5) * 0.3
}

fn rank_ticks(v: &f64) -> String {
    let r = v.round();
    if (v - r).abs() < 1e-6 && r >= 1.0 { format!("S{}", r as i64) } else { String::new() }
}

pub(super) fn recurrence(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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
    let paper = d.paper && !slow;
    let panel = Panel {
        points: groups,
        lines: vec![Line { label: "mean across seeds".into(), points: means, colour: colour(1), width: 3, alpha: 1.0 }],
        hlines: if paper {
            vec![HLine { y: 25.8, text: "paper: S1→S2 25.8 ms".into(), colour: BLACK }]
        } else {
            vec![]
        },
        x_ticks: Some(rank_ticks),
        ..Panel::linear("main shock", format!("time since the previous main shock ({unit})"))
    };
    drawn(
        path,
        &Sheet::new("Recurrence between main shocks", 1, vec![panel]),
        "Recurrence of the main shocks".into(),
        format!(
            "Time from the start of the previous main shock, per main shock across seeds (points jittered sideways), \
             the mean per rank{}.",
            if paper { ", and the paper's S1→S2 recurrence" } else { "" }
        ),
    )
}

pub(super) fn magnitude(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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
    let paper = d.paper;
    let panel = Panel {
        points: groups,
        hlines: if paper {
            vec![HLine { y: 6.77, text: "paper: M = 6.77 (S2)".into(), colour: BLACK }]
        } else {
            vec![]
        },
        x_ticks: Some(rank_ticks),
        ..Panel::linear("main shock", "magnitude")
    };
    drawn(
        path,
        &Sheet::new(format!("Magnitude of the main shocks at prototype scale (λ = {lambda:.0})"), 1, vec![panel]),
        "Magnitude per main shock".into(),
        format!(
            "Riera et al.'s magnitude from the paper's seismic moment (Eq. 15, with its extra factor λ) and the moment \
             magnitude Mw from the dimensionally consistent moment Δσ·L_p·A_p, for every main shock of every seed{}.",
            if paper { ", against the paper's M = 6.77 for S2" } else { "" }
        ),
    )
}

pub(super) fn attenuation(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
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
                .map(|i| (dist[i], pga[i]))
                .collect(),
            colour: colour(r as usize - 1),
            size: 5,
        })
        .filter(|g| !g.points.is_empty())
        .collect();
    if groups.is_empty() {
        return Ok(Outcome::Skipped("no positive distance and peak acceleration".into()));
    }
    let mut lines = Vec::new();
    let mut fit_text = String::from("no fit");
    if let Some(fit) = &d.attenuation_fit {
        let (g, m) = (&fit.group, &fit.measure);
        let (a, b, r2, n) = (&fit.intercept, &fit.slope, &fit.r2, &fit.points);
        if let Some(i) = (0..g.len()).find(|&i| g[i] == "main" && m[i] == col::PGA_M_S2) {
            let xs: Vec<f64> = (0..att.len()).filter(|&i| ok(i)).map(|i| dist[i]).collect();
            let (x0, x1) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
            let se = slope_se(b[i], r2[i], n[i] as f64);
            lines.push(Line {
                label: format!("fit: PGA ∝ R^({:.2} ± {:.2}), r² = {:.2}", b[i], se, r2[i]),
                points: [x0, x1].iter().map(|&x| (x, 10f64.powf(a[i] + b[i] * x.log10()))).collect(),
                colour: BLACK,
                width: 3,
                alpha: 1.0,
            });
            fit_text = format!(
                "log10 PGA = {:.3} {:+.3}·log10 R (slope ± {:.3}, one standard error; r² = {:.2}, {} points): {}",
                a[i],
                b[i],
                se,
                r2[i],
                n[i],
                trend(b[i], se)
            );
        }
    }
    let panel = Panel { points: groups, lines, ..Panel::loglog("distance from the hypocentre R (m)", "PGA (m/s²)") };
    drawn(
        path,
        &Sheet::new("Peak acceleration against distance from the hypocentre", 1, vec![panel]),
        "Peak acceleration against distance".into(),
        format!(
            "Peak magnitude of the recorded acceleration of every control node during every main shock, against its \
             distance from the shock's hypocentre (the first contact node to slide for good), all seeds, model scale, \
             log–log; least-squares line of log10 PGA on log10 R over all main shocks: {fit_text}. The block is \
             {} m long, so these are near-field distances; g = {G} m/s².",
            crate::plot::fmt_tick(&d.pipeline.scene.lattice().extent()[0])
        ),
    )
}

/// What a slope of log PGA on log R says, given its standard error: a fall with distance only
/// when the slope is negative by more than two standard errors.
fn trend(b: f64, se: f64) -> &'static str {
    if b + 2.0 * se < 0.0 {
        "PGA falls with distance"
    } else if b - 2.0 * se > 0.0 {
        "PGA grows with distance over this range (no attenuation)"
    } else {
        "no trend with distance can be told (the slope is within two standard errors of zero)"
    }
}

#[cfg(test)]
mod tests {
    use super::trend;
    use crate::figures::common::slope_se;

    #[test]
    fn a_positive_or_insignificant_slope_is_not_called_attenuation() {
        // r² = 0.04 over 300 points, slope +0.2: se = 0.2·√(24/298) = 0.057, so it grows.
        let se = slope_se(0.2, 0.04, 300.0);
        assert!((se - 0.2 * (24.0f64 / 298.0).sqrt()).abs() < 1e-12);
        assert!(trend(0.2, se).contains("no attenuation"));
        assert_eq!(trend(-1.0, 0.1), "PGA falls with distance");
        assert!(trend(-0.05, 0.1).starts_with("no trend"));
        assert!(slope_se(1.0, 0.5, 2.0).is_infinite());
    }
}
