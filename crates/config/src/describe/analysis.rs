//! The pipeline's other sections: what a scene costs before it is built, the events, the scale,
//! the records and spectra, the broadband, the set, the skip-ahead and the report.

use stickslip_analysis::settings::RecordSpan;
use stickslip_seismo::catalogue::compact;
use stickslip_seismo::similarity::AreaChoice;
use stickslip_seismo::spectra::fourier::Window;
use stickslip_seismo::spectra::response::Reading;
use stickslip_solver::Scene;
use stickslip_solver::memory::{Batches, dt_estimate, estimate, human, run_steps, samples};

use super::{N, Section, duration};
use crate::Pipeline;
use crate::check::{Named, approx};

/// The pipeline's seeds: how many, and the first eight.
pub fn seeds(pipeline: &Pipeline) -> Section {
    let mut s = Section::default();
    s.push(
        "seeds",
        format!(
            "seeds: {} ({}{})",
            pipeline.seeds.len(),
            pipeline.seeds.iter().take(8).map(|s| s.to_string()).collect::<Vec<_>>().join(", "),
            if pipeline.seeds.len() > 8 { ", …" } else { "" }
        ),
    );
    s
}

/// What the scene of `pipeline` costs from its block's counts alone, before anything is built:
/// nodes, bars, steps at the Δt of the paper's bound and a time at `rate` bar-updates/s
/// (`estimate`); the memory of one seed and of the ensemble on `threads` threads against
/// `available` (`memory`, and `fit` when they do not fit at once); and, for a large lattice,
/// what building it costs (`building`).
pub fn cost_before_building(
    pipeline: &Pipeline,
    threads: usize,
    (nodes, bars): (u64, u64),
    rate: f64,
    available: Option<&(u64, String)>,
) -> Section {
    let scene = &pipeline.scene;
    let mut s = Section::default();
    let dt = dt_estimate(scene);
    let (settle, shear) = run_steps(scene, dt);
    let updates = (settle + shear) as f64 * bars as f64;
    let bound = if scene.skip_ahead.enabled { "at most " } else { "" };
    // Set-up (the critical step's Lanczos passes and the Weibull draws) is about 100 steps.
    let guess = (updates + 100.0 * bars as f64) / rate;
    s.push(
        "estimate",
        format!(
            "before building: {nodes} nodes, {bars} bars (the block's counts); Δt ≈ {dt:.3e} s from the paper's \
             bound, {bound}{} steps, {bound}{updates:.3e} bar-updates per seed: about {} per seed at {rate:.1e} \
             bar-updates/s (one thread of the development machine at size; the probe below times this machine)",
            settle + shear,
            duration(guess)
        ),
    );
    let batches = Batches::of_ensemble(pipeline.seeds.len(), threads, scene.skip_ahead.enabled);
    let one = estimate(scene, Batches::ONE, samples(scene, dt)).ok();
    let all = estimate(scene, batches, samples(scene, dt)).ok();
    s.push(
        "memory",
        format!(
            "memory: about {} for one seed{}{}; available {}",
            one.map_or("more than 64 bits count".into(), |e| format!(
                "{} ({:.0} bytes per bar)",
                human(e.total),
                e.bytes_per_bar()
            )),
            all.map_or(String::new(), |e| format!(
                ", {} for its {} seeds on {threads} threads ({} at once in batches of {})",
                human(e.total),
                pipeline.seeds.len(),
                batches.concurrent,
                batches.lanes
            )),
            if one.is_some_and(|e| e.total > 1 << 30) { " (check builds one seed)" } else { "" },
            available.map_or("unknown".into(), |(b, source)| format!("{} ({source})", human(*b)))
        ),
    );
    if let (Some(e), Some((limit, _))) = (all, available)
        && e.total > *limit
    {
        s.push(
            "fit",
            "  → the pipeline's seeds do not fit at once: `stickslip pipeline` refuses them; give it fewer --threads",
        );
    }
    if bars > 20_000_000 {
        s.push(
            "building",
            format!(
                "building the lattice, each inspected seed's critical step and a timed probe (about {} each at the \
                 rate above; what is printed so far stands without them)…",
                duration(100.0 * bars as f64 / rate)
            ),
        );
    }
    s
}

/// How events are found in the series.
pub fn events(pipeline: &Pipeline) -> Section {
    let ev = &pipeline.analysis.events;
    let mut s = Section::default();
    s.push(
        "events",
        format!(
            "events: smoothing {} s, slip rate on {} / off {} m/s for {} s, merge gap {} s, min drop {} Pa, main shocks \
             ≥ {} of the largest",
            N(ev.smoothing_s),
            N(ev.v_on_m_s),
            N(ev.v_off_m_s),
            N(ev.quiet_s),
            N(ev.merge_gap_s),
            N(ev.min_drop_pa),
            N(ev.main_fraction)
        ),
    );
    s
}

/// The prototype scale λ of a block of length `length_m` (1 for a fault, at its own scale).
fn lambda(pipeline: &Pipeline, length_m: f64) -> f64 {
    if pipeline.scene.is_fault() { 1.0 } else { pipeline.analysis.similarity.prototype_length_m / length_m }
}

/// The scale of the events: a block's similarity to its prototype, or a fault's own scale.
/// `length_m` is the block's length along x.
pub fn scale(pipeline: &Pipeline, length_m: f64) -> Section {
    let si = &pipeline.analysis.similarity;
    let mut s = Section::default();
    if pipeline.scene.is_fault() {
        s.push("scale", "scale: its own (λ = 1); each event's Mw from its slip, M0 = μ·A·ΔD̄");
    } else {
        s.push(
            "similarity",
            format!(
                "similarity: L_p = {} m (λ = {}), u̇_p = {:e} m/s, model area: {}",
                N(si.prototype_length_m),
                approx(lambda(pipeline, length_m)),
                si.prototype_rate_m_s,
                match si.area {
                    AreaChoice::Contact => "the whole contact area (the paper's)",
                    AreaChoice::Rupture => "each event's rupture area",
                }
            ),
        );
    }
    s
}

/// Whether a fault scene has stations (recorded and processed whatever `[accelerograms]` says).
fn has_stations(scene: &Scene) -> bool {
    scene.is_fault() && !scene.stations.is_empty()
}

/// The records of events (`records`) and their usable band (`band`), or a fault's stations'.
/// `length_m` is the block's length along x.
pub fn accelerograms(pipeline: &Pipeline, length_m: f64) -> Section {
    let scene = &pipeline.scene;
    let mut s = Section::default();
    let Some(a) = &pipeline.analysis.accelerograms else {
        s.push(
            "records",
            if has_stations(scene) {
                format!(
                    "records: the {} stations' ([[stations]]): each recorded, band-passed inside its usable band and \
                     written with RotD50 PGA/PGV (stations table, record files); no event records ([accelerograms])",
                    scene.stations.len()
                )
            } else {
                "records: off (no [accelerograms] or [spectra] section)".to_string()
            },
        );
        return s;
    };
    let nodes = if a.nodes.is_empty() {
        "every control node recording acceleration".to_string()
    } else {
        a.nodes.iter().map(|n| n.ldem().to_string()).collect::<Vec<_>>().join(", ")
    };
    let span = match a.span {
        RecordSpan::Events => {
            format!("{} events from {} s before to {} s after", a.events.name(), N(a.pre_event_s), N(a.post_event_s))
        }
        RecordSpan::WholeRun => "the whole shear stage".into(),
    };
    let formats: Vec<&str> = a.formats.iter().map(|f| f.name()).collect();
    s.push(
        "records",
        format!(
            "records: {span}, nodes {nodes}; files {}",
            if formats.is_empty() { "none".into() } else { formats.join(", ") }
        ),
    );
    let lambda = lambda(pipeline, length_m);
    s.push(
        "band",
        format!(
            "usable band: up to f_max = {:.1} Hz at model scale ({:.4} Hz prototype, λ = {}): plane waves within {}% \
             of their long-wave speed; filter {} Hz … {} Hz, order {}",
            N(a.resolved_hz),
            N(a.resolved_hz / lambda),
            approx(lambda),
            N(100.0 * a.band_tolerance),
            a.low_corner_hz.map_or("1/record length".into(), |f| N(f).to_string()),
            a.high_corner_hz.map_or("f_max".into(), |f| N(f).to_string()),
            a.order
        ),
    );
    s
}

/// The response and Fourier spectra of the records, or a fault's stations' spectra.
pub fn spectra(pipeline: &Pipeline) -> Section {
    let mut s = Section::default();
    let text = match &pipeline.analysis.spectra {
        Some(sp) => format!(
            "spectra: {} periods {:.3e} … {:.3e} s, dampings {}, {} reading of the samples, {} window for the Fourier \
             spectrum{}{}",
            sp.periods.len(),
            sp.periods.first().copied().unwrap_or(f64::NAN),
            sp.periods.last().copied().unwrap_or(f64::NAN),
            sp.dampings.iter().map(|d| compact(*d)).collect::<Vec<_>>().join(", "),
            match sp.reading {
                Reading::Linear => "linear",
                Reading::BandLimited => "band-limited",
            },
            match sp.window {
                Window::Rectangular => "rectangular",
                Window::Hann => "Hann",
            },
            if sp.rotd { ", RotD50/RotD100" } else { "" },
            if sp.attenuation { ", attenuation" } else { "" }
        ),
        None if has_stations(&pipeline.scene) => format!(
            "spectra: the stations' 5%-damped RotD50 and RotD100 PSA over each one's usable band (station_spectra \
             table){}; no [spectra] section for control nodes",
            if pipeline.set.is_some() { ", which the set below is chosen by" } else { "" }
        ),
        None => "spectra: off (no [spectra] section)".to_string(),
    };
    s.push("spectra", text);
    s
}

/// The broadband records of a fault's stations, when asked for.
pub fn broadband(pipeline: &Pipeline) -> Section {
    let mut s = Section::default();
    if let Some(bb) = &pipeline.analysis.broadband {
        let scene = &pipeline.scene;
        let f_max = scene.usable_band(stickslip_analysis::motions::DEPARTURE).map_or(f64::NAN, |b| b.f_max_hz);
        for line in bb.describe(scene.s_wave_speed(), f_max) {
            s.push("broadband", line);
        }
    }
    s
}

/// The record set matched to a design spectrum, when asked for.
pub fn set(pipeline: &Pipeline) -> Section {
    let mut s = Section::default();
    let Some(set) = &pipeline.set else { return s };
    let (a, b) = set.options.range.bounds().unwrap_or((f64::NAN, f64::NAN));
    s.push(
        "set",
        format!(
            "set: {} records ({} at most per {}), {} spectra at {}%, periods {} … {} s{}, scale factors {} … {}; target \
             {}",
            set.options.count,
            set.options.per_group,
            set.per.name(),
            set.component.name(),
            N(100.0 * set.damping),
            N(a),
            N(b),
            if pipeline.sets_from_stations() { "" } else { " (prototype)" },
            N(set.options.scale_min),
            N(set.options.scale_max),
            set.target_name
        ),
    );
    if pipeline.sets_from_stations() {
        s.push(
            "set",
            format!(
                "  chosen from the surface stations of every seed{} (a seed is one rupture)",
                set.bins_text().map_or(String::new(), |b| format!(" at {b}"))
            ),
        );
    }
    s
}

/// The quasi-static skip-ahead, when on.
pub fn skip_ahead(scene: &Scene) -> Section {
    let mut s = Section::default();
    let sk = &scene.skip_ahead;
    if sk.enabled {
        s.push(
            "skip_ahead",
            format!(
                "skip-ahead: on (tolerance {:e}, {} explicit steps before each transition{})",
                sk.tolerance,
                sk.margin_steps,
                sk.record_interval_s.map_or(String::new(), |iv| format!(", one sample per {} s while skipping", N(iv)))
            ),
        );
    }
    s
}

/// Whether the report is written (`report`), and the pipeline's warnings (`warning`).
pub fn report(pipeline: &Pipeline) -> Section {
    let mut s = Section::default();
    s.push("report", format!("report: {}", if pipeline.report.enabled { "on" } else { "off" }));
    for w in &pipeline.warnings {
        s.push("warning", format!("warning: {w}"));
    }
    s
}
