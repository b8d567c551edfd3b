//! What `stickslip check` says of a pipeline, without running it: its seeds, what its scene costs
//! (refused before anything is built when it does not fit or is too long), the lattice it builds,
//! the medium, friction, fault, stress, critical step, a timed probe of the steps, stiffness,
//! drivers, stages, records, events, scaling, accelerograms, spectra, broadband records, the set,
//! the skip-ahead and the report — as labelled lines handed out in order as they are known, so the
//! command line prints the cost before the lattice is built, and Python gets them as data.

use stickslip_config::Pipeline;
use stickslip_config::describe::{self, Probe, Section, describe_boundaries, describe_friction};
use stickslip_solver::Model;
use stickslip_solver::inspect::{Inspection, Statics, inspect, probe_step_time};
use stickslip_solver::memory::{counts, dt_estimate, run_steps};
use stickslip_solver::scene::TimeStep;

use crate::budget::{self, NOMINAL_RATE};
use crate::error::EnsembleError;

/// How to check.
#[derive(Clone, Copy, Debug, Default)]
pub struct CheckOptions {
    /// Compute the critical step for at most this many seeds (`None`: 16, fewer on a lattice of
    /// more than 6 million bars; one when E is homogeneous).
    pub seeds: Option<usize>,
    /// Solve the statics on the whole lattice even when it is large.
    pub full_statics: bool,
    /// Accept a run of more than 10¹¹ bar-updates per seed.
    pub allow_long: bool,
    /// Threads a run would use (0: one per core).
    pub threads: usize,
    /// Say how the scene splits over this many ranks ([`stickslip_solver::split`]): each rank's
    /// layers, nodes, bars and memory, and the halo it trades per step; refuse a split that a rank
    /// cannot hold.
    pub ranks: Option<usize>,
    /// Memory of one rank (bytes); `None`: this machine's available memory over the ranks.
    pub memory_per_rank: Option<u64>,
}

/// One line of the check: its section, the part of the section, the text.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckLine {
    /// The section (`seeds`, `cost`, `block`, `medium`, `friction`, …).
    pub section: &'static str,
    /// The part of the section (e.g. `law` or `map` of the friction).
    pub label: &'static str,
    /// The text.
    pub text: String,
}

/// What the check measured.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckFacts {
    /// Bars of the lattice.
    pub bars: usize,
    /// The smallest and largest critical step over the seeds inspected (s).
    pub critical_dt_s: (f64, f64),
    /// The step a run takes (s), at the smallest critical step.
    pub dt_s: f64,
    /// Steps of the self-weight stage (at most) and of the shear stage.
    pub steps: (u64, u64),
    /// Seconds per step, timed on this machine.
    pub per_step_s: f64,
    /// Seconds of a run's set-up.
    pub setup_s: f64,
}

/// Checks `pipeline`, handing each line to `emit` as soon as it is known; refuses (before the
/// lattice is built) a scene that does not fit in memory or whose run is too long.
pub fn check(
    pipeline: &Pipeline,
    options: &CheckOptions,
    emit: &mut dyn FnMut(CheckLine),
) -> Result<CheckFacts, EnsembleError> {
    let started = std::time::Instant::now();
    if options.seeds == Some(0) {
        return Err(EnsembleError::Refused(
            "--seeds = 0 is not allowed: at least 1 (seeds whose critical step check computes)".into(),
        ));
    }
    let scene = &pipeline.scene;
    let threads = match options.threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n,
    };
    let mut out = Out { emit };
    out.all("seeds", &describe::seeds(pipeline));
    // What the scene costs, from the block's counts alone, before anything is built: handed out
    // first, and a scene that does not fit is refused here (building it would fill memory).
    if let Some(ranks) = options.ranks {
        split_over(pipeline, ranks, options.memory_per_rank, &mut out)?;
    }
    let bars = cost_before_building(pipeline, threads, options.allow_long, &mut out)?;
    let model = Model::new(scene.clone());
    let build_s = started.elapsed().as_secs_f64();
    // Every seed's lattice is the same when E is homogeneous: one critical step stands for all.
    let inspected = match options.seeds {
        _ if scene.young_cv == 0.0 => 1,
        Some(n) => n,
        None => ((INSPECT_BAR_BUDGET / bars.max(1) as f64).floor() as usize).clamp(1, 16),
    };
    let seeds: Vec<u64> = pipeline.seeds.iter().copied().take(inspected).collect();
    let statics = if options.full_statics { Statics::Full } else { Statics::for_model(&model) };
    let facts = inspect(&model, &seeds, statics)?;
    let (friction, boundaries) = (describe_friction(&model), describe_boundaries(&model));
    let (slider, steps) =
        (describe::spring_slider(scene, &facts), describe::critical_step(scene, &facts, pipeline.seeds.len()));
    out.all("block", &describe::block(&model, &facts));
    out.all("medium", &describe::medium(scene));
    out.part("friction", &friction, "law");
    if scene.is_fault() {
        let fault = describe::fault(&model, seeds[0]);
        out.part("fault", &fault, "fault");
        if !fault.lines.is_empty() {
            out.part("boundaries", &boundaries, "absorbing");
        }
        out.part("fault", &fault, "waves");
    }
    out.part("stress", &slider, "stress");
    out.part("step", &steps, "critical");
    out.part("step", &steps, "step");
    let probe = probe(pipeline, &model, &facts, seeds[0], threads, build_s, options.allow_long)?;
    out.all("cost", &describe::run_cost(scene, &probe));
    out.part("step", &steps, "record_every");
    out.all("stiffness", &describe::stiffness(scene, &facts, seeds[0]));
    for label in ["drivers", "plate", "normal_load"] {
        out.part("boundaries", &boundaries, label);
    }
    out.part("friction", &friction, "map");
    out.part("stress", &slider, "slider");
    let length_m = model.lattice().extent()[0];
    for (name, section) in [
        ("stages", describe::stages(scene)),
        ("record", describe::record(&model)),
        ("events", describe::events(pipeline)),
        ("scale", describe::scale(pipeline, length_m)),
        ("accelerograms", describe::accelerograms(pipeline, length_m)),
        ("spectra", describe::spectra(pipeline)),
        ("broadband", describe::broadband(pipeline)),
        ("set", describe::set(pipeline)),
        ("skip_ahead", describe::skip_ahead(scene)),
        ("report", describe::report(pipeline)),
    ] {
        out.all(name, &section);
    }
    let (lo, hi) = facts.critical_range_s();
    Ok(CheckFacts {
        bars: probe.bars,
        critical_dt_s: (lo, hi),
        dt_s: step_at(scene, lo),
        steps: probe.steps,
        per_step_s: probe.per_step_s,
        setup_s: probe.setup_s,
    })
}

/// Where the lines go.
struct Out<'a> {
    emit: &'a mut dyn FnMut(CheckLine),
}

impl Out<'_> {
    /// Every line of `s`, in `section`.
    fn all(&mut self, section: &'static str, s: &Section) {
        for l in &s.lines {
            (self.emit)(CheckLine { section, label: l.label, text: l.text.clone() });
        }
    }

    /// The lines of `s` labelled `label`, in `section`.
    fn part(&mut self, section: &'static str, s: &Section, label: &str) {
        for l in s.lines.iter().filter(|l| l.label == label) {
            (self.emit)(CheckLine { section, label: l.label, text: l.text.clone() });
        }
    }
}

/// The step of a run whose critical step is `critical`.
fn step_at(scene: &stickslip_solver::Scene, critical: f64) -> f64 {
    match scene.time_step {
        TimeStep::Fraction(f) => f * critical,
        TimeStep::Fixed(dt) => dt,
    }
}

/// Refuses a run that could not count its steps at the smallest Δt over the seeds inspected
/// (whatever `allow_long` says), or whose record interval the seed with the largest Δt would
/// refuse, then times a probe of the steps of `first_seed` and refuses it when it is too long.
/// `build_s` is what building the lattice took.
fn probe(
    pipeline: &Pipeline,
    model: &Model,
    facts: &Inspection,
    first_seed: u64,
    threads: usize,
    build_s: f64,
    allow_long: bool,
) -> Result<Probe, EnsembleError> {
    let scene = &pipeline.scene;
    let (lo, hi) = facts.critical_range_s();
    let dt = step_at(scene, lo);
    let keys = |e| EnsembleError::Refused(stickslip_config::keys::describe(&e));
    // A fixed step above a seed's critical step is refused by the run once it is built; say so
    // now, with the seed whose lattice refuses it.
    if let stickslip_solver::scene::TimeStep::Fixed(fixed) = scene.time_step
        && let Some((seed, c)) =
            facts.critical.iter().filter(|(_, c)| fixed > c.dt_s).min_by(|a, b| a.1.dt_s.total_cmp(&b.1.dt_s))
    {
        return Err(keys(stickslip_solver::SolverError::TimeStepAboveCritical {
            dt_s: fixed,
            critical_s: c.dt_s,
            seed: *seed,
        }));
    }
    stickslip_solver::run::check_step_count(model, dt).map_err(keys)?;
    stickslip_solver::run::check_record_interval(model, step_at(scene, hi)).map_err(keys)?;
    let parallel = pipeline.seeds.len() < threads && model.layout().splits();
    let per_step = probe_step_time(model, first_seed, dt, parallel, 0.5)?;
    let rate = Some(facts.bars as f64 / per_step);
    let updates = budget::check_length(scene, facts.bars as u64, dt, rate, allow_long, "this scene")?;
    // A run's set-up is what check just did for one seed: the lattice, the seed's stiffness and
    // its critical step.
    Ok(Probe {
        bars: facts.bars,
        steps: run_steps(scene, dt),
        updates,
        per_step_s: per_step,
        setup_s: build_s + facts.setup_s,
        threads: parallel.then_some(threads),
    })
}

/// Bars × seeds whose critical steps `check` computes by default (each costs about 100 steps of
/// its lattice): 16 seeds up to 6 million bars, fewer above, one at 100 million.
const INSPECT_BAR_BUDGET: f64 = 1e8;

/// Hands out what `pipeline`'s scene costs from its block's counts alone — nodes, bars, steps at
/// the Δt of the paper's bound, a time at [`NOMINAL_RATE`], the memory of one seed and of the
/// ensemble against what is available — and refuses it, before anything is built, when one seed
/// does not fit (check builds one) or its run is too long. Returns the bar count.
fn cost_before_building(
    pipeline: &Pipeline,
    threads: usize,
    allow_long: bool,
    out: &mut Out<'_>,
) -> Result<u64, EnsembleError> {
    let scene = &pipeline.scene;
    let (nodes, bars) = counts(scene.dims).map_err(|e| {
        EnsembleError::Refused(format!(
            "this scene: {e}: use fewer modules (pipeline keys: block.nx, block.ny, block.nz)"
        ))
    })?;
    let dt = dt_estimate(scene);
    budget::check_count(scene, bars, dt, "this scene")?;
    let available = budget::available_memory();
    let known = available.as_ref().ok().and_then(Option::as_ref);
    let cost = describe::cost_before_building(pipeline, threads, (nodes, bars), NOMINAL_RATE, known);
    out.part("cost", &cost, "estimate");
    available?;
    out.part("cost", &cost, "memory");
    out.part("cost", &cost, "fit");
    budget::check_memory(scene, 1, 1, "one seed of this scene (what check builds)")?;
    budget::check_length(scene, bars, dt, None, allow_long, "this scene")?;
    out.part("cost", &cost, "building");
    Ok(bars)
}

/// Hands out how `pipeline`'s scene splits over `ranks` ranks, from the block alone (nothing is
/// built): each rank's module layers, the nodes and bars it holds and its memory for one seed,
/// and the halo it trades per step; refuses a number of ranks the block cannot be split into, a
/// scene whose bars crack, and a split whose largest rank needs more than `per_rank` bytes (or
/// this machine's available memory over the ranks).
fn split_over(
    pipeline: &Pipeline,
    ranks: usize,
    per_rank: Option<u64>,
    out: &mut Out<'_>,
) -> Result<(), EnsembleError> {
    use stickslip_solver::memory::{estimate_rank, human, samples};
    use stickslip_solver::split::Partition;
    let scene = &pipeline.scene;
    let line = |text: String| CheckLine { section: "ranks", label: "ranks", text };
    if scene.rupture.is_some() {
        return Err(EnsembleError::Refused(
            "--ranks: a scene whose bars crack ([rupture]) lists its bars and is not split over ranks; leave out --ranks".into(),
        ));
    }
    let dims = scene.dims;
    let partition = Partition::new(dims, ranks).map_err(|e| {
        EnsembleError::Refused(format!(
            "--ranks = {ranks} is not allowed: a block splits into slabs of at least {} along z, so this one \
             (block.nz = {}) takes 1 to {} ranks",
            if e.least_layers == 1 { "one module layer (its bars are listed)" } else { "two module layers" },
            dims.nz,
            e.most
        ))
    })?;
    let samples = samples(scene, dt_estimate(scene));
    let mut largest = (0usize, 0u64);
    let mut per: Vec<String> = Vec::new();
    for r in 0..ranks {
        let w = partition.window(r);
        let m = estimate_rank(scene, &partition, r, samples)
            .map_err(|e| EnsembleError::Refused(format!("--ranks = {ranks}: {e}")))?;
        if m.total > largest.1 {
            largest = (r, m.total);
        }
        let layers = partition.owned_layers(r);
        per.push(format!(
            "rank {r}: module layers {}..{} ({}{}), {} nodes held ({} owned), {} bars, about {}{}",
            layers.start,
            layers.end,
            layers.len(),
            if r == 0 { ", the base" } else { "" },
            w.nodes,
            w.owned.len(),
            m.bars,
            human(m.total),
            if r == 0 { " (with the whole block's model, which the analyses read, and the recording)" } else { "" }
        ));
    }
    let layer_nodes = (dims.nx + 1) * (dims.ny + 1) + dims.nx * dims.ny;
    (out.emit)(line(format!(
        "ranks: {ranks} slabs of module layers along z, each rank holding one more layer on each side that has a neighbour (docs/model.md §19)"
    )));
    for p in per {
        (out.emit)(line(format!("  {p}")));
    }
    (out.emit)(line(format!(
        "  halo: one module layer of {layer_nodes} nodes each way per neighbour per step, {} (two layers up to a rank whose first layer starts a slab of the stencil)",
        human(24 * layer_nodes as u64)
    )));
    let (limit, whose) = match per_rank {
        Some(b) => (b, "--memory-per-rank".to_string()),
        None => match budget::available_memory()? {
            Some((b, source)) => {
                (b / ranks as u64, format!("this machine's available memory over {ranks} ranks ({source})"))
            }
            None => (u64::MAX, "no memory limit known".to_string()),
        },
    };
    (out.emit)(line(format!(
        "  largest: rank {} at about {} against {} per rank ({whose})",
        largest.0,
        human(largest.1),
        if limit == u64::MAX { "no limit".to_string() } else { human(limit) }
    )));
    if let Some(why) = stickslip_solver::run::split_refusal(scene, ranks) {
        return Err(EnsembleError::Refused(format!(
            "--ranks = {ranks}: `stickslip pipeline` under mpirun would refuse to split this scene's seeds: {why}"
        )));
    }
    (out.emit)(line(format!(
        "  run: `mpirun -n {ranks} stickslip pipeline …` (built with --features mpi) splits each seed so (docs/guide/ensembles.md, One scene over MPI ranks)"
    )));
    if largest.1 > limit {
        return Err(EnsembleError::Refused(format!(
            "--ranks = {ranks}: rank {} needs about {} but a rank has {} ({whose}); use more ranks (up to {}) or more memory per rank",
            largest.0,
            human(largest.1),
            human(limit),
            Partition::most(dims)
        )));
    }
    Ok(())
}
