//! `stickslip check`: validates a pipeline file and prints what it builds, without running it.

use std::path::PathBuf;

use anyhow::Result;
use stickslip_config::Pipeline;
use stickslip_config::describe::{self, Probe, Section, describe_boundaries, describe_friction};
use stickslip_solver::Model;
use stickslip_solver::inspect::{Inspection, Statics, inspect, probe_step_time};
use stickslip_solver::memory::{counts, dt_estimate, run_steps};
use stickslip_solver::scene::TimeStep;

use crate::budget::{self, NOMINAL_RATE};

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

/// Prints every line of `section`, below the pipeline's heading.
fn print(section: &Section) {
    for line in section.texts() {
        outln!("  {line}");
    }
}

/// Prints the lines of `section` labelled `label`.
fn print_part(section: &Section, label: &str) {
    for line in section.part(label) {
        outln!("  {line}");
    }
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
    print(&describe::seeds(&pipeline));
    // What the scene costs, from the block's counts alone, before anything is built: printed
    // first, and a scene that does not fit is refused here (building it would fill memory).
    crate::commands::pipeline::check_set_capacity(&pipeline, pipeline.seeds.len())?;
    let bars = cost_before_building(&pipeline, threads, a.allow_long)?;
    let model = Model::new(scene.clone());
    let build_s = started.elapsed().as_secs_f64();
    // Every seed's lattice is the same when E is homogeneous: one critical step stands for all.
    let inspected = match a.seeds {
        _ if scene.young_cv == 0.0 => 1,
        Some(n) => n,
        None => ((INSPECT_BAR_BUDGET / bars.max(1) as f64).floor() as usize).clamp(1, 16),
    };
    let seeds: Vec<u64> = pipeline.seeds.iter().copied().take(inspected).collect();
    let statics = if a.full_statics { Statics::Full } else { Statics::for_model(&model) };
    let facts = inspect(&model, &seeds, statics)?;
    let (friction, boundaries) = (describe_friction(&model), describe_boundaries(&model));
    let (slider, steps) =
        (describe::spring_slider(scene, &facts), describe::critical_step(scene, &facts, pipeline.seeds.len()));
    print(&describe::block(&model, &facts));
    print(&describe::medium(scene));
    print_part(&friction, "law");
    if scene.is_fault() {
        let fault = describe::fault(&model, seeds[0]);
        print_part(&fault, "fault");
        if !fault.lines.is_empty() {
            print_part(&boundaries, "absorbing");
        }
        print_part(&fault, "waves");
    }
    print_part(&slider, "stress");
    print_part(&steps, "critical");
    print_part(&steps, "step");
    let probe = probe(&pipeline, &model, &facts, seeds[0], threads, build_s, a.allow_long)?;
    print(&describe::run_cost(scene, &probe));
    print_part(&steps, "record_every");
    print(&describe::stiffness(scene, &facts, seeds[0]));
    for part in ["drivers", "plate", "normal_load"] {
        print_part(&boundaries, part);
    }
    print_part(&friction, "map");
    print_part(&slider, "slider");
    let length_m = model.lattice().extent()[0];
    for section in [
        describe::stages(scene),
        describe::record(&model),
        describe::events(&pipeline),
        describe::scale(&pipeline, length_m),
        describe::accelerograms(&pipeline, length_m),
        describe::spectra(&pipeline),
        describe::broadband(&pipeline),
        describe::set(&pipeline),
        describe::skip_ahead(scene),
        describe::report(&pipeline),
    ] {
        print(&section);
    }
    Ok(())
}

/// Refuses a run that could not count its steps at the smallest Δt over the seeds inspected
/// (whatever --allow-long says), or whose record interval the seed with the largest Δt would
/// refuse, then times a probe of the steps of `first_seed` and refuses it when it is too long. `build_s` is what
/// building the lattice took.
fn probe(
    pipeline: &Pipeline,
    model: &Model,
    facts: &Inspection,
    first_seed: u64,
    threads: usize,
    build_s: f64,
    allow_long: bool,
) -> Result<Probe> {
    let scene = &pipeline.scene;
    let (lo, hi) = facts.critical_range_s();
    let dt_at = |critical: f64| match scene.time_step {
        TimeStep::Fraction(f) => f * critical,
        TimeStep::Fixed(dt) => dt,
    };
    let dt = dt_at(lo);
    let keys = |e| anyhow::anyhow!("{}", stickslip_config::keys::describe(&e));
    stickslip_solver::run::check_step_count(model, dt).map_err(keys)?;
    stickslip_solver::run::check_record_interval(model, dt_at(hi)).map_err(keys)?;
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
    let available = budget::available_memory();
    let known = available.as_ref().ok().and_then(Option::as_ref);
    let cost = describe::cost_before_building(pipeline, threads, (nodes, bars), NOMINAL_RATE, known);
    print_part(&cost, "estimate");
    available?;
    print_part(&cost, "memory");
    print_part(&cost, "fit");
    budget::check_memory(scene, 1, 1, "one seed of this scene (what check builds)")?;
    budget::check_length(scene, bars, dt, None, allow_long, "this scene")?;
    print_part(&cost, "building");
    Ok(bars)
}
