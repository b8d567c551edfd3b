//! `stickslip check`: validates a pipeline file and prints what it builds, without running it.

use std::path::PathBuf;

use anyhow::Result;
use stickslip_analysis::settings::RecordSpan;
use stickslip_config::Pipeline;
use stickslip_config::check::{Named, approx};
use stickslip_seismo::catalogue::compact;
use stickslip_seismo::similarity::AreaChoice;
use stickslip_seismo::spectra::fourier::Window;
use stickslip_seismo::spectra::response::Reading;
use stickslip_solver::Model;
use stickslip_solver::boundary::absorbing::impedances;
use stickslip_solver::inspect::FaultReading;
use stickslip_solver::inspect::{PROBE_WARM_UP_STEPS, Statics, inspect, probe_step_time};
use stickslip_solver::laws::describe;
use stickslip_solver::memory::{
    Batches, LONG_RUN_BAR_UPDATES, counts, dt_estimate, estimate, human, run_steps, samples,
};
use stickslip_solver::scene::{SettleMethod, TimeStep};

use crate::budget::{self, NOMINAL_RATE};
use crate::text::N;

/// Arguments of `stickslip check`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Pipeline file (TOML).
    pub pipeline: PathBuf,
    /// Compute the critical step for at most this many of the pipeline's seeds (default 16, fewer
    /// on a lattice of more than 6 million bars, where each costs about 100 steps; one when E is
    /// homogeneous, since every seed's lattice is then the same).
    #[arg(long)]
    pub seeds: Option<usize>,
    /// Solve the effective stiffness and the block's stiffness under its load on the whole
    /// lattice even when it is large (by default a lattice of more than 500 000 bars gets them
    /// on a 16×16×16 sample block and no block stiffness: each solve costs thousands of steps).
    #[arg(long)]
    pub full_statics: bool,
    /// Accept a run of more than 10¹¹ bar-updates per seed (refused otherwise, as by `pipeline`).
    #[arg(long)]
    pub allow_long: bool,
}

fn position(model: &Model, id: stickslip_solver::NodeId) -> String {
    let p = model.lattice().position(id);
    format!("LDEM {} at ({}, {}, {}) m", id.ldem(), round(p[0]), round(p[1]), round(p[2]))
}

/// Positions written without the round-off of `i·Lc` (and short when huge or tiny): to 12
/// significant digits, whatever their size (`2.8000000000000003` is 2.8, `12000000.000000002`
/// is 12000000).
fn round(v: f64) -> N {
    let r: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    N(if r.is_finite() { r } else { v })
}

/// `stickslip check`.
pub fn run(a: Args) -> Result<()> {
    let started = std::time::Instant::now();
    if a.seeds == Some(0) {
        anyhow::bail!("--seeds = 0 is not allowed: at least 1 (seeds whose critical step check computes)");
    }
    let pipeline = Pipeline::load(&a.pipeline)?;
    let scene = &pipeline.scene;
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    outln!("pipeline {} ({}), hash {}", pipeline.name, a.pipeline.display(), pipeline.hash);
    outln!(
        "  seeds: {} ({}{})",
        pipeline.seeds.len(),
        pipeline.seeds.iter().take(8).map(|s| s.to_string()).collect::<Vec<_>>().join(", "),
        if pipeline.seeds.len() > 8 { ", …" } else { "" }
    );
    // What the scene costs, from the block's counts alone, before anything is built: printed
    // first, and a scene that does not fit is refused here (building it would fill memory).
    crate::commands::pipeline::check_set_capacity(&pipeline, pipeline.seeds.len())?;
    let bars = cost_before_building(&pipeline, threads, a.allow_long)?;
    let model = Model::new(scene.clone());
    let build_s = started.elapsed().as_secs_f64();
    // Every seed's lattice is the same when E is homogeneous: one critical step stands for all.
    let homogeneous = scene.young_cv == 0.0;
    let inspected = match a.seeds {
        _ if homogeneous => 1,
        Some(n) => n,
        None => ((INSPECT_BAR_BUDGET / bars.max(1) as f64).floor() as usize).clamp(1, 16),
    };
    let seeds: Vec<u64> = pipeline.seeds.iter().copied().take(inspected).collect();
    let statics = if a.full_statics { Statics::Full } else { Statics::for_model(&model) };
    let facts = inspect(&model, &seeds, statics)?;
    let e = model.lattice().extent();
    outln!(
        "  block {}×{}×{} modules of Lc = {} m ({} × {} × {} m): {} nodes, {} bars, {} contact nodes, mass {} kg",
        scene.dims.nx,
        scene.dims.ny,
        scene.dims.nz,
        N(scene.lc_m),
        round(e[0]),
        round(e[1]),
        round(e[2]),
        facts.nodes,
        facts.bars,
        facts.contact_nodes,
        approx(facts.mass_kg)
    );
    let law = scene.friction.law;
    outln!(
        "  friction: {} ({}), CV of μ {}",
        law.name(),
        describe(&law.node(1.0).coefficients(), |_, c| N(c.value).to_string()),
        N(scene.friction.mu_cv)
    );
    if scene.is_fault() {
        print_fault(&model, seeds[0]);
    } else {
        outln!(
            "  self-weight normal stress {:.1} Pa, sliding strength μs·σ = {:.1} Pa",
            N(facts.self_weight_stress_pa),
            N(facts.strength_pa)
        );
    }
    let (lo, hi) = facts.critical_range_s();
    let which = if homogeneous {
        "for every seed (young_cv = 0: every seed's lattice is the same)".to_string()
    } else if facts.critical.len() == pipeline.seeds.len() {
        format!("over the pipeline's {} seeds", facts.critical.len())
    } else {
        format!("over its first {} of {} seeds (--seeds N for more)", facts.critical.len(), pipeline.seeds.len())
    };
    let how = if facts.critical.iter().all(|(_, c)| c.iterations == 0) {
        " (the bound from each node's bars, docs/model.md §2)"
    } else {
        ""
    };
    outln!("  critical step {lo:.4e} … {hi:.4e} s {which}{how}; paper's 0.6·Lc/Cp = {:.4e} s", facts.paper_bound_s);
    match scene.time_step {
        TimeStep::Fraction(f) => {
            outln!("  time step: {f} of each seed's critical step ({:.4e} … {:.4e} s)", f * lo, f * hi)
        }
        TimeStep::Fixed(dt) => outln!("  time step: {dt:e} s ({:.3} of the smallest critical step)", N(dt / lo)),
    }
    // Run length at the smallest Δt over the seeds inspected: refused when a run could not count
    // its steps (whatever --allow-long says), then a timed probe of its steps.
    let dt = match scene.time_step {
        TimeStep::Fraction(f) => f * lo,
        TimeStep::Fixed(dt) => dt,
    };
    stickslip_solver::run::check_step_count(&model, dt)
        .map_err(|e| anyhow::anyhow!("{}", stickslip_config::keys::describe(&e)))?;
    // The record interval against the largest Δt: the seed with it would refuse it.
    let dt_largest = match scene.time_step {
        TimeStep::Fraction(f) => f * hi,
        TimeStep::Fixed(dt) => dt,
    };
    stickslip_solver::run::check_record_interval(&model, dt_largest)
        .map_err(|e| anyhow::anyhow!("{}", stickslip_config::keys::describe(&e)))?;
    let (settle, shear) = run_steps(scene, dt);
    let parallel = pipeline.seeds.len() < threads && model.layout().splits();
    let per_step = probe_step_time(&model, seeds[0], dt, parallel, 0.5)?;
    let rate = Some(facts.bars as f64 / per_step);
    let updates = budget::check_length(scene, facts.bars as u64, dt, rate, a.allow_long, "this scene")?;
    let on = if parallel { format!("{threads} threads") } else { "one thread".into() };
    // With the skip-ahead the count bounds the run: the quasi-static stretches are jumped.
    let bound = if scene.skip_ahead.enabled { "at most " } else { "" };
    // A run's set-up is what check just did for one seed: the lattice, the seed's stiffness and
    // its critical step.
    let setup_s = build_s + facts.setup_s;
    outln!(
        "  run: {bound}{} steps per seed ({}shear {shear}), {bound}{updates:.3e} bar-updates; {bound}about {} per seed on \
         {on} ({} of set-up — the lattice, the seed's stiffness and critical step, as timed here — and the steps at \
         {:.3e} s each, a timed probe after {PROBE_WARM_UP_STEPS} warm-up steps: {:.3e} bar-updates/s){}",
        settle + shear,
        if settle > 0 { format!("self-weight up to {settle} + ") } else { String::new() },
        budget::duration(setup_s + per_step * (settle + shear) as f64),
        budget::duration(setup_s),
        per_step,
        facts.bars as f64 / per_step,
        if scene.skip_ahead.enabled {
            " — the skip-ahead jumps the quasi-static stretches, so the run steps far fewer"
        } else if updates > LONG_RUN_BAR_UPDATES {
            " — a long run, accepted with --allow-long"
        } else {
            ""
        }
    );
    if let Some(iv) = scene.record.interval_s {
        let k = |dt: f64| (iv / dt).round().max(1.0);
        let (k_lo, k_hi) = match scene.time_step {
            TimeStep::Fraction(f) => (k(f * hi), k(f * lo)),
            TimeStep::Fixed(dt) => (k(dt), k(dt)),
        };
        let steps = if k_lo == k_hi { format!("{k_lo}") } else { format!("{k_lo}–{k_hi}") };
        outln!("  recorded every {steps} steps (the nearest whole number to {} s; Δt does not depend on it)", N(iv));
    }
    let on = if facts.moduli_of == scene.dims {
        String::new()
    } else {
        let d = facts.moduli_of;
        format!(
            " of a {}×{}×{} sample block of this material (--full-statics solves the whole block)",
            d.nx, d.ny, d.nz
        )
    };
    if let Some(why) = &facts.unsolved {
        outln!("  effective stiffness{on}: not solved ({why}); the run does not need it");
    }
    for m in &facts.moduli {
        let name = |a: usize| ["x", "y", "z"][a];
        let others: Vec<usize> = (0..3).filter(|&a| a != m.axis).collect();
        outln!(
            "  effective stiffness along {}{on} (static solve, uniaxial stress, seed {}): E = {:.4e} Pa ({:.3} of E), \
             ν_{}{} = {:.3}, ν_{}{} = {:.3}",
            name(m.axis),
            seeds[0],
            m.young_pa,
            m.young_pa / scene.young_pa,
            name(m.axis),
            name(others[0]),
            m.poisson[0],
            name(m.axis),
            name(others[1]),
            m.poisson[1]
        );
    }
    if scene.shear.drivers.is_empty() {
        outln!("  drivers: none");
    } else {
        let d = &scene.shear.drivers;
        outln!(
            "  drivers: {}{}",
            d.iter().take(12).map(|&d| position(&model, d)).collect::<Vec<_>>().join("; "),
            if d.len() > 12 { format!("; … and {} more", d.len() - 12) } else { String::new() }
        );
    }
    if let Some(p) = &scene.plate {
        outln!(
            "  loading plate: face {} ({} nodes) on springs of {:.4e} N/m in all, moving by Eq. 12 in x",
            p.face.name(),
            p.nodes.len(),
            p.stiffness()
        );
    }
    if let Some(n) = &scene.normal_load {
        outln!("  normal load: {} Pa on the top face ({:.4e} N)", N(n.pressure_pa), n.total());
    }
    if let Some(map) = &scene.friction.map {
        outln!("  friction map ({} base nodes):", map.nodes.len());
        let background = map.region.iter().filter(|r| r.is_none()).count();
        if background > 0 {
            outln!("    background ([friction]): {background} nodes");
        }
        let span = |values: &mut dyn Iterator<Item = f64>| {
            values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)))
        };
        let contact = model.lattice().contact_nodes();
        for (i, r) in map.regions.iter().enumerate() {
            let members: Vec<usize> = (0..map.nodes.len()).filter(|&c| map.region[c] == Some(i as u16)).collect();
            if members.is_empty() {
                outln!("    {}: no base node (covered by patches of higher priority)", r.name);
                continue;
            }
            let range = |k: usize| {
                let (lo, hi) = span(&mut members.iter().map(|&c| map.nodes[c].coefficients()[k].value));
                if lo == hi { format!("{}", N(lo)) } else { format!("{}…{}", N(lo), N(hi)) }
            };
            let (x0, x1) = span(&mut members.iter().map(|&c| model.lattice().position(contact[c])[0]));
            let (x0, x1) = (round(x0), round(x1));
            outln!(
                "    {} ({}): {} nodes, x {}…{} m, {}",
                r.name,
                r.kind.name(),
                members.len(),
                x0,
                x1,
                describe(&map.nodes[members[0]].coefficients(), |k, _| range(k)),
            );
        }
    }
    // A fault has no weight on a base: the spring-slider reading is the rigid base's.
    if !scene.is_fault() {
        let sl = &facts.slider;
        if sl.block_n_m.is_nan() {
            let why = match &sl.block_note {
                Some(note) => {
                    format!("the block's stiffness under its load is a static solve of all {} bars, {note}", facts.bars)
                }
                None => format!(
                    "the block's stiffness under its load needs a static solve of all {} bars: --full-statics",
                    facts.bars
                ),
            };
            outln!(
                "  as a spring-slider: N = {:.4e} N, strength μs·N = {:.4e} N, tips at {:.4e} N; k not solved ({why}), \
                 plate springs {:.4e} N/m, k_c = (μs − μd)·N/Dc = {:.4e} N/m",
                sl.normal_n,
                sl.strength_n,
                sl.tipping_n,
                sl.plate_n_m,
                sl.critical_n_m
            );
        } else {
            outln!(
                "  as a spring-slider: N = {:.4e} N, strength μs·N = {:.4e} N, tips at {:.4e} N; k = {:.4e} N/m (block \
                 under the load {:.4e}, plate springs {:.4e}), k_c = (μs − μd)·N/Dc = {:.4e} N/m, swing damping D/(2ω) = \
                 {:.3}",
                sl.normal_n,
                sl.strength_n,
                sl.tipping_n,
                sl.k_n_m,
                sl.block_n_m,
                sl.plate_n_m,
                sl.critical_n_m,
                N(sl.damping_ratio)
            );
        }
        outln!(
            "    → {} (the rigid slider's reading; docs/model.md §12 says where a lattice block differs)",
            stickslip_config::keys::verdict(sl)
        );
    }
    let sw = &scene.self_weight;
    let sh = &scene.shear;
    if scene.is_fault() {
        outln!(
            "  run: {} s from the prestressed state at rest, D = {} 1/s, no self-weight stage{}",
            N(sh.duration_s),
            N(sh.damping_per_s),
            if sh.drivers.is_empty() { ", no driver" } else { "" }
        );
    } else {
        outln!(
            "  self-weight: {}",
            match sw.method {
                SettleMethod::Static =>
                    "solved statically (falls back to damped settling if friction cannot hold it)".into(),
                SettleMethod::Dynamic => format!(
                    "damped settling, D = {} 1/s, until out-of-balance/weight < {:e}",
                    N(sw.damping_per_s),
                    sw.settle_tolerance
                ),
            }
        );
        outln!(
            "  shear: u̇f = {} m/s (t0 = {} s), D = {} 1/s, for {} s",
            N(sh.velocity_m_s),
            N(sh.rise_time_s),
            N(sh.damping_per_s),
            N(sh.duration_s)
        );
    }
    let r = &scene.record;
    outln!(
        "  record: {}, interface {}{}{}{}",
        r.interval_s.map_or("every step".to_string(), |iv| format!("every {} s", N(iv))),
        r.interface.iter().map(|q| q.name()).collect::<Vec<_>>().join(", "),
        if r.energy { ", energy terms" } else { "" },
        if r.slip_onsets { ", slip onsets" } else { "" },
        if r.settling { ", the self-weight stage too" } else { "" },
    );
    let mut groups: Vec<(stickslip_solver::NodeId, Vec<String>)> = Vec::new();
    for c in &r.control {
        let what = format!("{} {}", c.quantity.name(), c.component.name());
        match groups.iter_mut().find(|(n, _)| *n == c.node) {
            Some((_, w)) => w.push(what),
            None => groups.push((c.node, vec![what])),
        }
    }
    // Every control node, also those given by position or by a set (the README promises it).
    let contact = model.lattice().contact_nodes();
    for (node, what) in &groups {
        outln!("  control {}: {}", position(&model, *node), what.join(", "));
    }
    for (node, _) in groups.iter().filter(|(n, _)| contact.contains(n)) {
        outln!(
            "  warning: control node {} is a base contact node: it records the motion of the frictional contact \
             (held, sliding or lifting), not of the block above it (a number written for another block size names \
             another node on this one: give at_m instead)",
            position(&model, *node)
        );
    }
    let ev = &pipeline.analysis.events;
    outln!(
        "  events: smoothing {} s, slip rate on {} / off {} m/s for {} s, merge gap {} s, min drop {} Pa, main shocks ≥ {} of the largest",
        N(ev.smoothing_s),
        N(ev.v_on_m_s),
        N(ev.v_off_m_s),
        N(ev.quiet_s),
        N(ev.merge_gap_s),
        N(ev.min_drop_pa),
        N(ev.main_fraction)
    );
    let si = &pipeline.analysis.similarity;
    let lambda = if scene.is_fault() { 1.0 } else { si.prototype_length_m / e[0] };
    if scene.is_fault() {
        outln!("  scale: its own (λ = 1); each event's Mw from its slip, M0 = μ·A·ΔD̄");
    } else {
        outln!(
            "  similarity: L_p = {} m (λ = {}), u̇_p = {:e} m/s, model area: {}",
            N(si.prototype_length_m),
            approx(lambda),
            si.prototype_rate_m_s,
            match si.area {
                AreaChoice::Contact => "the whole contact area (the paper's)",
                AreaChoice::Rupture => "each event's rupture area",
            }
        );
    }
    let stations = scene.is_fault() && !scene.stations.is_empty();
    match &pipeline.analysis.accelerograms {
        Some(a) => {
            let nodes = if a.nodes.is_empty() {
                "every control node recording acceleration".to_string()
            } else {
                a.nodes.iter().map(|n| n.ldem().to_string()).collect::<Vec<_>>().join(", ")
            };
            let span = match a.span {
                RecordSpan::Events => {
                    format!(
                        "{} events from {} s before to {} s after",
                        a.events.name(),
                        N(a.pre_event_s),
                        N(a.post_event_s)
                    )
                }
                RecordSpan::WholeRun => "the whole shear stage".into(),
            };
            let formats: Vec<&str> = a.formats.iter().map(|f| f.name()).collect();
            outln!(
                "  records: {span}, nodes {nodes}; files {}",
                if formats.is_empty() { "none".into() } else { formats.join(", ") }
            );
            outln!(
                "  usable band: up to f_max = {:.1} Hz at model scale ({:.4} Hz prototype, λ = {}): plane waves \
                 within {}% of their long-wave speed; filter {} Hz … {} Hz, order {}",
                N(a.resolved_hz),
                N(a.resolved_hz / lambda),
                approx(lambda),
                N(100.0 * a.band_tolerance),
                a.low_corner_hz.map_or("1/record length".into(), |f| N(f).to_string()),
                a.high_corner_hz.map_or("f_max".into(), |f| N(f).to_string()),
                a.order
            );
        }
        // A fault's stations are recorded and processed whatever [accelerograms] says.
        None if stations => outln!(
            "  records: the {} stations' ([[stations]]): each recorded, band-passed inside its usable band and \
             written with RotD50 PGA/PGV (stations table, record files); no event records ([accelerograms])",
            scene.stations.len()
        ),
        None => outln!("  records: off (no [accelerograms] or [spectra] section)"),
    }
    match &pipeline.analysis.spectra {
        Some(s) => outln!(
            "  spectra: {} periods {:.3e} … {:.3e} s, dampings {}, {} reading of the samples, {} window for the \
             Fourier spectrum{}{}",
            s.periods.len(),
            s.periods.first().copied().unwrap_or(f64::NAN),
            s.periods.last().copied().unwrap_or(f64::NAN),
            s.dampings.iter().map(|d| compact(*d)).collect::<Vec<_>>().join(", "),
            match s.reading {
                Reading::Linear => "linear",
                Reading::BandLimited => "band-limited",
            },
            match s.window {
                Window::Rectangular => "rectangular",
                Window::Hann => "Hann",
            },
            if s.rotd { ", RotD50/RotD100" } else { "" },
            if s.attenuation { ", attenuation" } else { "" }
        ),
        None if stations => outln!(
            "  spectra: the stations' 5%-damped RotD50 and RotD100 PSA over each one's usable band (station_spectra \
             table){}; no [spectra] section for control nodes",
            if pipeline.set.is_some() { ", which the set below is chosen by" } else { "" }
        ),
        None => outln!("  spectra: off (no [spectra] section)"),
    }
    if let Some(bb) = &pipeline.analysis.broadband {
        let f_max = scene.usable_band(stickslip_analysis::motions::DEPARTURE).map_or(f64::NAN, |b| b.f_max_hz);
        for line in bb.describe(scene.s_wave_speed(), f_max) {
            outln!("  {line}");
        }
    }
    if let Some(set) = &pipeline.set {
        let (a, b) = set.options.range.bounds().unwrap_or((f64::NAN, f64::NAN));
        outln!(
            "  set: {} records ({} at most per {}), {} spectra at {}%, periods {} … {} s{}, scale factors {} … {}; target {}",
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
        );
        if pipeline.sets_from_stations() {
            outln!(
                "    chosen from the surface stations of every seed{} (a seed is one rupture)",
                set.bins_text().map_or(String::new(), |b| format!(" at {b}"))
            );
        }
    }
    let sk = &scene.skip_ahead;
    if sk.enabled {
        outln!(
            "  skip-ahead: on (tolerance {:e}, {} explicit steps before each transition{})",
            sk.tolerance,
            sk.margin_steps,
            sk.record_interval_s.map_or(String::new(), |iv| format!(", one sample per {} s while skipping", N(iv)))
        );
    }
    outln!("  report: {}", if pipeline.report.enabled { "on" } else { "off" });
    for w in &pipeline.warnings {
        outln!("  warning: {w}");
    }
    Ok(())
}

/// Bars × seeds whose critical steps `check` computes by default (each costs about 100 steps of
/// its lattice): 16 seeds up to 6 million bars, fewer above, one at 100 million.
const INSPECT_BAR_BUDGET: f64 = 1e8;

/// Prints what `pipeline`'s scene costs from its block's counts alone — nodes, bars, steps at the
/// Δt of the paper's bound, a time at [`NOMINAL_RATE`], the memory of one seed and of the
/// ensemble against what is available — and refuses it, before anything is built, when one seed
/// does not fit (check builds one) or its run is too long. Returns the bar count.
fn cost_before_building(pipeline: &Pipeline, threads: usize, allow_long: bool) -> Result<u64> {
    let scene = &pipeline.scene;
    let (nodes, bars) = counts(scene.dims).map_err(|e| {
        anyhow::anyhow!("this scene: {e}: use fewer modules (pipeline keys: block.nx, block.ny, block.nz)")
    })?;
    let dt = dt_estimate(scene);
    budget::check_count(scene, bars, dt, "this scene")?;
    let (settle, shear) = run_steps(scene, dt);
    let updates = (settle + shear) as f64 * bars as f64;
    let bound = if scene.skip_ahead.enabled { "at most " } else { "" };
    // Set-up (the critical step's Lanczos passes and the Weibull draws) is about 100 steps.
    let guess = (updates + 100.0 * bars as f64) / NOMINAL_RATE;
    outln!(
        "  before building: {nodes} nodes, {bars} bars (the block's counts); Δt ≈ {dt:.3e} s from the paper's bound, \
         {bound}{} steps, {bound}{updates:.3e} bar-updates per seed: about {} per seed at {NOMINAL_RATE:.1e} \
         bar-updates/s (one thread of the development machine at size; the probe below times this machine)",
        settle + shear,
        budget::duration(guess)
    );
    let available = budget::available_memory()?;
    let batches = Batches::of_ensemble(pipeline.seeds.len(), threads, scene.skip_ahead.enabled);
    let one = estimate(scene, Batches::ONE, samples(scene, dt)).ok();
    let all = estimate(scene, batches, samples(scene, dt)).ok();
    outln!(
        "  memory: about {} for one seed{}{}; available {}",
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
        available.as_ref().map_or("unknown".into(), |(b, source)| format!("{} ({source})", human(*b)))
    );
    if let (Some(e), Some((limit, _))) = (all, &available)
        && e.total > *limit
    {
        outln!(
            "    → the pipeline's seeds do not fit at once: `stickslip pipeline` refuses them; give it fewer --threads"
        );
    }
    budget::check_memory(scene, 1, 1, "one seed of this scene (what check builds)")?;
    budget::check_length(scene, bars, dt, None, allow_long, "this scene")?;
    if bars > 20_000_000 {
        outln!(
            "  building the lattice, each inspected seed's critical step and a timed probe (about {} each at the rate \
             above; what is printed so far stands without them)…",
            budget::duration(100.0 * bars as f64 / NOMINAL_RATE)
        );
    }
    Ok(bars)
}

/// What `check` says of a fault scene (docs/model.md §15): tractions, where rupture starts, the
/// cohesive zone against the lattice, the absorbing faces and the lattice's wave speeds.
fn print_fault(model: &Model, first_seed: u64) {
    let scene = model.scene();
    let Some(r) = FaultReading::of(model) else { return };
    let mpa = |(a, b): (f64, f64)| {
        if a == b { format!("{:.2} MPa", N(a / 1e6)) } else { format!("{:.2} … {:.2} MPa", N(a / 1e6), N(b / 1e6)) }
    };
    outln!(
        "  fault (the base as one side of a planar fault, slip = 2 × the face's displacement; friction heals: {}): \
         normal stress {}, initial shear stress {}",
        scene.friction.heals,
        mpa(r.normal_pa),
        mpa(r.shear_pa)
    );
    if let Some(n) = scene.fault.as_ref().and_then(|f| f.nucleation) {
        outln!(
            "  nucleation per seed: a {} m square at {:.2} MPa along x, its centre drawn uniformly in x {}…{} m, \
             y {}…{} m (seed {}: at ({:.0}, {:.0}) m)",
            N(n.size_m),
            N(n.shear_pa / 1e6),
            N(n.x_m[0]),
            N(n.x_m[1]),
            N(n.y_m[0]),
            N(n.y_m[1]),
            first_seed,
            N(n.centre(first_seed)[0]),
            N(n.centre(first_seed)[1])
        );
    }
    let per_seed = scene.fault.as_ref().is_some_and(|f| f.nucleation.is_some());
    let excess =
        r.median_s.map_or(String::new(), |s| format!(", median strength excess S = (τs − τ0)/(τ0 − τd) = {:.2}", N(s)));
    if r.overstressed.0 == 0 && per_seed {
        outln!("  before the seed's square: {} nodes can slip (above μd·σn){excess}", r.can_slip);
    } else if r.overstressed.0 == 0 {
        outln!(
            "  ⚠ no node starts above its static strength μs·σn: nothing nucleates unless a random field or a patch \
             overstresses some ([[fault.patches]] with shear_stress_pa above μs·normal_stress_pa)"
        );
    } else {
        outln!(
            "  nucleation: {} nodes ({:.4e} m²) start above their static strength μs·σn and slide from the first step; \
             {} nodes can slip (above μd·σn){excess}",
            r.overstressed.0,
            r.overstressed.1,
            r.can_slip
        );
    }
    if let Some(l) = r.cohesive_zone_m {
        let per = l / scene.lc_m;
        outln!(
            "  cohesive zone Λ0 = (9π/32)·μ·Dc/(τs − τd) ≥ {l:.4e} m = {:.1} × Lc{}",
            N(per),
            if per < 3.0 {
                " ⚠ under-resolved (fewer than 3 nodes): rupture speed and slip rates depend on Lc"
            } else {
                ""
            }
        );
    }
    let (zp, zs) = impedances(scene);
    let rho = scene.density_kg_m3;
    if !scene.absorbing.is_empty() {
        outln!(
            "  absorbing faces {} (dashpots ρCp = {:.4e} and ρCs = {:.4e} Pa·s/m per m² of face)",
            scene.absorbing.iter().map(|f| f.name()).collect::<Vec<_>>().join(", "),
            zp,
            zs
        );
    }
    let band = scene
        .usable_band(0.05)
        .map(|b| format!(", waves within 5% of these speeds up to {:.3} Hz", N(b.f_max_hz)))
        .unwrap_or_default();
    outln!("  lattice wave speeds Cp = {:.1} m/s, Cs = {:.1} m/s{band}", N(zp / rho), N(zs / rho));
}

#[cfg(test)]
mod tests {
    use super::{N, round};

    #[test]
    fn positions_are_written_without_round_off_at_any_size() {
        assert_eq!(round(0.1 * 28.0).to_string(), "2.8");
        assert_eq!(round(3.0 * 0.1).to_string(), "0.3");
        assert_eq!(round(1.2e7 + 2.0 * f64::EPSILON * 1.2e7).to_string(), "12000000");
        assert_eq!(round(0.1 * 3.0 * 1e-6).to_string(), N(3e-7).to_string());
        assert_eq!(round(0.0).to_string(), "0");
        assert_eq!(round(1e300).to_string(), "1e300");
    }
}
