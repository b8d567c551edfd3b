//! `stickslip pipeline` on a `[cycles]` pipeline: one run of the fault over the years asked, or
//! with `[cycles.heterogeneity]` one run per seed and the catalogue statistics over them.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use anyhow::{Context, Result, bail};
use stickslip_config::Pipeline;
use stickslip_ensemble::catalogue::CatalogueStats;
use stickslip_ensemble::cycle_catalogue::run_cycle_catalogue;
use stickslip_solver::cycles::YEAR_S;

/// Runs a `[cycles]` pipeline under `out`: over `seeds` (the pipeline's when `None`) when it
/// draws random fields of its friction, else once.
pub fn run(pipeline: &Pipeline, out: &Path, cancel: &AtomicBool, seeds: Option<&[u64]>) -> Result<()> {
    let spec = pipeline.cycles.as_ref().expect("a [cycles] pipeline");
    if spec.heterogeneity.is_none() {
        return one(pipeline, out, cancel);
    }
    let mut p = pipeline.clone();
    if let Some(s) = seeds {
        p.seeds = s.to_vec();
    }
    catalogue(&p, out, cancel)
}

/// A `[cycles]` pipeline: one run of the fault over the years asked, its files and events.
fn one(pipeline: &Pipeline, out: &Path, cancel: &AtomicBool) -> Result<()> {
    outln!("{}: earthquake cycles over the plate's loading (docs/guide/faults.md, Earthquake cycles)", pipeline.name);
    let r =
        stickslip_ensemble::cycles::run_cycles(pipeline, pipeline.seeds.first().copied().unwrap_or(0), out, cancel)?;
    outln!(
        "{}: {} fault nodes, stiffness in {:.1} s; {} steps ({} rejected, {:.2e} s to {:.3} years) in {:.1} s; {} events → {}",
        pipeline.name,
        r.nodes,
        r.stiffness_s,
        r.stats.accepted,
        r.stats.rejected,
        r.stats.min_step_s,
        r.stats.max_step_s / YEAR_S,
        r.run_s,
        r.events.len(),
        r.out.join("seas").display()
    );
    if r.stats.dynamic_phases > 0 {
        let wall = r.stats.quasi_wall_s + r.stats.dynamic_wall_s;
        outln!(
            "  fully dynamic: {} explicit phases, {} steps over {:.1} s of events, {:.1} s of the run ({:.0}%); the \
             quasi-dynamic phases {:.1} s ({:.0}%); at the hand-backs the explicit grid's friction differs from the \
             full block's static traction by at most {:.3} MPa",
            r.stats.dynamic_phases,
            r.stats.dynamic_steps,
            r.stats.dynamic_time_s,
            r.stats.dynamic_wall_s,
            100.0 * r.stats.dynamic_wall_s / wall.max(1e-9),
            r.stats.quasi_wall_s,
            100.0 * r.stats.quasi_wall_s / wall.max(1e-9),
            r.stats.handover_jump_pa / 1e6,
        );
    }
    let figure = stickslip_report::cycles::draw_cycles(out)?;
    outln!("  figure: {}", figure.path.display());
    for (i, e) in r.events.iter().enumerate() {
        let recurrence = if i > 0 {
            format!(", {:.3} years after the last", (e.onset_s - r.events[i - 1].onset_s) / YEAR_S)
        } else {
            String::new()
        };
        outln!(
            "  event {i} at {:.3} years{recurrence}: hypocentre {:.2} km, surface slip {:.4} m, peak slip rate {:.4} m/s, {:.1} s",
            e.onset_s / YEAR_S,
            e.hypocentre_depth_m / 1e3,
            e.surface_slip_m,
            e.peak_slip_rate_m_s,
            e.duration_s
        );
    }
    let intervals: Vec<f64> = r.events.windows(2).map(|w| (w[1].onset_s - w[0].onset_s) / YEAR_S).collect();
    if intervals.len() >= 2 {
        let n = intervals.len() as f64;
        let mean = intervals.iter().sum::<f64>() / n;
        let sd = (intervals.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        outln!(
            "  recurrence: {mean:.3} ± {sd:.3} years (mean ± sd of {} intervals, the start's transient included), \
             coefficient of variation {:.4}",
            intervals.len(),
            sd / mean
        );
    }
    if let Some(t) = r.interrupted_s {
        bail!(
            "{}: interrupted at {:.3} years of {:.3}; its files hold the run up to there (a cycle run starts again from \
             the beginning: it keeps no checkpoint)",
            pipeline.name,
            t / YEAR_S,
            pipeline.cycles.as_ref().map_or(0.0, |c| c.duration_s) / YEAR_S
        );
    }
    Ok(())
}

/// A catalogue of cycles over the pipeline's seeds.
fn catalogue(pipeline: &Pipeline, out: &Path, cancel: &AtomicBool) -> Result<()> {
    outln!(
        "{}: earthquake cycles on {} seed{} of a heterogeneous fault (docs/guide/faults.md, A catalogue of earthquake \
         cycles)",
        pipeline.name,
        pipeline.seeds.len(),
        if pipeline.seeds.len() == 1 { "" } else { "s" }
    );
    let r = run_cycle_catalogue(pipeline, out, cancel, |s| {
        let lc = pipeline.scene.lc_m;
        let largest = s.events.iter().map(|e| e.magnitude(lc)).fold(f64::NEG_INFINITY, f64::max);
        let smallest = s.events.iter().map(|e| e.magnitude(lc)).fold(f64::INFINITY, f64::min);
        match &s.run {
            Some(r) => outln!(
                "  seed {}: {} events, Mw {:.2} … {:.2}; {} steps ({} rejected) in {:.1} s → {}",
                s.seed,
                s.events.len(),
                smallest,
                largest,
                r.stats.accepted,
                r.stats.rejected,
                r.stiffness_s + r.run_s,
                s.out.display()
            ),
            None => outln!(
                "  seed {}: {} events, Mw {:.2} … {:.2} (finished earlier, read back from {})",
                s.seed,
                s.events.len(),
                smallest,
                largest,
                s.out.display()
            ),
        }
    })?;
    print_catalogue(&r.stats, r.seeds.len());
    outln!("  tables: {}", out.join("tables").display());
    let figure_path = out.join("figures").join("cycle_catalogue.png");
    if r.seeds.is_empty() {
        // The tables were rewritten empty: an earlier figure would contradict them.
        stickslip_store::io::remove_file_if_present(&figure_path)
            .with_context(|| format!("{}: cannot remove the earlier figure", pipeline.name))?;
    } else {
        let figure = stickslip_report::cycle_catalogue::draw_cycle_catalogue(
            out,
            stickslip_ensemble::catalogue::CYCLE_MAGNITUDE,
        )?;
        outln!("  figure: {}", figure.path.display());
    }
    for (seed, why) in &r.failed {
        errln!("  seed {seed} failed: {why}");
    }
    if !r.failed.is_empty() {
        bail!(
            "{}: {} seed(s) failed ({}); the statistics cover the {} that finished, and the same command runs the \
             failed ones again",
            pipeline.name,
            r.failed.len(),
            r.failed.iter().map(|(s, _)| s.to_string()).collect::<Vec<_>>().join(", "),
            r.seeds.len()
        );
    }
    if let Some(seed) = r.interrupted {
        bail!(
            "{}: interrupted in seed {seed}; the {} seeds before it are finished and kept, and the same command resumes \
             at seed {seed}",
            pipeline.name,
            r.seeds.len()
        );
    }
    Ok(())
}

/// The pooled statistics of a cycle catalogue, a line each.
fn print_catalogue(stats: &CatalogueStats, seeds: usize) {
    let over = if seeds == 1 { "one seed".to_string() } else { format!("{seeds} seeds") };
    for row in stats.b_values.iter().filter(|r| r.seed.is_none()) {
        match &row.fit {
            Ok(f) => outln!(
                "  Gutenberg–Richter over {over}: b = {:.3} ± {:.3} (Aki–Utsu, Shi–Bolt σ) from {} events at or \
                 above Mc = {:.2} (of {}; Mc by {})",
                f.b,
                f.b_sigma,
                f.n,
                f.mc,
                row.events,
                if row.mc_gof.is_some_and(|(m, _)| m == f.mc) {
                    "goodness of fit at 90%"
                } else {
                    "maximum curvature + 0.2"
                }
            ),
            Err(e) => outln!("  Gutenberg–Richter over {over}: no fit ({e})"),
        }
    }
    for row in stats.recurrence.iter().filter(|r| r.seed.is_none()) {
        match &row.stats {
            Ok(s) => outln!(
                "  recurrence of {} events: mean {:.3} years, CV {:.3}{} over {} intervals",
                if row.sequence == "main" { "main-shock" } else { "all" },
                s.mean / YEAR_S,
                s.cv,
                row.cv_ci95.map(|(lo, hi)| format!(" (95% {lo:.3} … {hi:.3})")).unwrap_or_default(),
                s.n
            ),
            Err(e) => outln!("  recurrence of {} events: {e}", row.sequence),
        }
    }
    for row in stats.omori.iter().filter(|r| r.seed.is_none()) {
        match &row.fit {
            Ok(f) => outln!(
                "  aftershocks: {} after {} main shocks; Omori–Utsu p = {:.3} ± {:.3}, c = {:.3e} s",
                row.aftershocks,
                row.main_shocks,
                f.p,
                f.p_se,
                f.c
            ),
            Err(e) => outln!(
                "  aftershocks: {} after {} main shocks; no Omori–Utsu fit ({e})",
                row.aftershocks,
                row.main_shocks
            ),
        }
    }
    for row in stats.scaling.iter().filter(|r| r.seed.is_none()) {
        if let Ok(f) = &row.fit {
            outln!("  scaling {}: exponent {:.3} (self-similar {})", row.relation, f.exponent(), row.self_similar);
        }
    }
}
