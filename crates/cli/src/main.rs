//! `stickslip`: command-line glue over the solver and analysis crates.

use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use stickslip_analysis::Pipeline;
use stickslip_analysis::bench::accuracy::{
    AccuracyPlan, accuracy_figure, accuracy_frame, observed_order, run_accuracy,
};
use stickslip_analysis::bench::skip::{
    SkipBench, compare_skip, jumps_frame as skip_jumps_frame, runs_frame as skip_runs_frame,
};
use stickslip_analysis::ensemble::{EnsembleOptions, run_ensemble};
use stickslip_analysis::similarity::{
    ModelEvent, SECONDS_PER_YEAR, SimilarityParams, moment_magnitude, riera_magnitude, scale,
};
use stickslip_analysis::summary::digest;
use stickslip_analysis::tables::{control_frame, series_frame, skips_frame, write_parquet_atomic};
use stickslip_solver::critical::critical_time_step;
use stickslip_solver::scene::SettleMethod;
use stickslip_solver::statics::uniaxial_moduli;
use stickslip_solver::{Model, RunOptions, run_seed};

/// Earthquake stick-slip with the Lattice Discrete Element Method.
#[derive(Parser, Debug)]
#[command(name = "stickslip", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Run one seed of a pipeline's scene and write its recorded series as Parquet.
    Run {
        /// Pipeline file (TOML), e.g. pipelines/paper.toml.
        pipeline: PathBuf,
        /// Seed of the random fields.
        #[arg(long)]
        seed: u64,
        /// Output folder [default: reports/<pipeline name>/seed-<seed>].
        #[arg(long)]
        out: Option<PathBuf>,
        /// No progress bar.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Run a pipeline's seeds in parallel and write every table (resumable).
    Pipeline {
        /// Pipeline files (TOML), e.g. pipelines/paper.toml.
        #[arg(required = true)]
        pipelines: Vec<PathBuf>,
        /// Output folder [default: reports/<pipeline name>]; only with one pipeline.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Seeds to run instead of the pipeline's, e.g. "1,5,10-20".
        #[arg(long)]
        seeds: Option<String>,
        /// Worker threads [default: one per core].
        #[arg(long, default_value_t = 0)]
        threads: usize,
        /// Discard results of a different pipeline found in the output folder.
        #[arg(long)]
        fresh: bool,
        /// Run only the K-th of N disjoint slices of the seeds (K from 1), e.g. "3/8", for a job
        /// array; the tables and report are gathered by `stickslip merge`.
        #[arg(long, value_parser = parse_shard)]
        shard: Option<(usize, usize)>,
        /// No progress bar.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Check that every shard of an ensemble is in an output folder and gather its tables,
    /// statistics and report.
    Merge {
        /// The shared output folder of the shards.
        out: PathBuf,
        /// Pipeline file [default: <out>/pipeline.toml, written by the shards].
        #[arg(long)]
        pipeline: Option<PathBuf>,
        /// Number of shards, to name the incomplete ones.
        #[arg(long)]
        shards: Option<usize>,
    },
    /// Compare the tables of two output folders (wall times ignored); exit 1 if they differ.
    Compare {
        /// First folder.
        a: PathBuf,
        /// Second folder.
        b: PathBuf,
    },
    /// Scale a model event to a prototype fault (SPEC §9) and print the numbers.
    Similarity(SimilarityArgs),
    /// Response spectra, Fourier spectrum and intensity measures of an accelerogram file (PEER
    /// .AT2, or CSV with time and acceleration columns).
    Spectra(SpectraArgs),
    /// Print the schema and first rows of a Parquet table (or every part matching a glob).
    Show {
        /// A Parquet file, or a glob such as 'reports/paper/tables/events/*.parquet'.
        table: PathBuf,
        /// Rows to print.
        #[arg(long, default_value_t = 10)]
        rows: usize,
    },
    /// Benchmarks of the solver against itself (tables and figures under reports/bench/).
    #[command(subcommand)]
    Bench(BenchCommand),
    /// Check a pipeline file and print the scene it builds (nothing is run).
    Check {
        /// Pipeline file (TOML).
        pipeline: PathBuf,
        /// Seed used for the critical step of the random lattice.
        #[arg(long, default_value_t = 123)]
        seed: u64,
    },
}

#[derive(Subcommand, Debug)]
enum BenchCommand {
    /// Run time against error: the pipeline's scene over Δt fractions and lattice refinements
    /// of the same block, each against the finest run.
    Accuracy {
        /// Pipeline file (TOML).
        pipeline: PathBuf,
        /// Δt fractions of the critical step.
        #[arg(long, value_delimiter = ',', default_value = "0.9,0.5,0.25,0.1")]
        fractions: Vec<f64>,
        /// Lattice refinements (modules per side multiplied, Lc divided).
        #[arg(long, value_delimiter = ',', default_value = "1,2,4")]
        refinements: Vec<u32>,
        /// Shear duration (s) [default: the pipeline's].
        #[arg(long)]
        duration_s: Option<f64>,
        /// Output folder [default: reports/bench/<pipeline name>].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Quasi-static skip-ahead against full integration: whole runs, and each of the first
    /// jumps against integrating through it from the same state.
    Skip {
        /// Pipeline file (TOML).
        pipeline: PathBuf,
        /// Seeds [default: the pipeline's], e.g. "1,5,10-20".
        #[arg(long)]
        seeds: Option<String>,
        /// Jumps checked one by one per seed (those followed by an event first).
        #[arg(long, default_value_t = 4)]
        jumps: usize,
        /// How long the compared runs go on after a jump (s).
        #[arg(long, default_value_t = 0.05)]
        window_s: f64,
        /// Output folder [default: reports/bench/<pipeline name>].
        #[arg(long)]
        out: Option<PathBuf>,
    },
}

/// Units of a CSV accelerogram.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum CsvUnits {
    /// Standard gravity (9.80665 m/s²).
    G,
    /// m/s².
    #[value(name = "m/s2")]
    MS2,
    /// cm/s² (gal).
    #[value(name = "cm/s2")]
    CmS2,
}

/// Inputs of `stickslip spectra`.
#[derive(clap::Args, Debug)]
struct SpectraArgs {
    /// The record: a PEER .AT2 file, or a CSV file (time in s, then acceleration).
    record: PathBuf,
    /// Units of the acceleration column of a CSV file.
    #[arg(long, value_enum, default_value = "m/s2")]
    units: CsvUnits,
    /// Damping ratios, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "0.05")]
    dampings: Vec<f64>,
    /// Shortest period (s) [default: 2·Δt of the record].
    #[arg(long)]
    period_min_s: Option<f64>,
    /// Longest period (s) [default: half the record's duration].
    #[arg(long)]
    period_max_s: Option<f64>,
    /// Number of log-spaced periods.
    #[arg(long, default_value_t = 100)]
    period_count: usize,
    /// Read the samples band-limited (FFT resampled) instead of as straight lines.
    #[arg(long)]
    band_limited: bool,
    /// Remove a least-squares line from the velocity before integrating to displacement.
    #[arg(long)]
    baseline: bool,
    /// Output folder [default: reports/records/<file name>].
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Inputs of `stickslip similarity`.
#[derive(clap::Args, Debug)]
struct SimilarityArgs {
    /// Mean stress drop Δσ of the event (Pa).
    #[arg(long)]
    stress_drop_pa: f64,
    /// Model fault length L_m (m).
    #[arg(long, default_value_t = 1.0)]
    model_length_m: f64,
    /// Model rupture area A_m (m²).
    #[arg(long, default_value_t = 0.1)]
    model_area_m2: f64,
    /// Prototype fault length L_p (m).
    #[arg(long, default_value_t = 1.0e4)]
    prototype_length_m: f64,
    /// Event duration at model scale (s).
    #[arg(long)]
    duration_s: Option<f64>,
    /// Recurrence at model scale (s).
    #[arg(long)]
    recurrence_s: Option<f64>,
    /// Model loading rate u̇_m (m/s).
    #[arg(long, default_value_t = 1.1e-4)]
    model_rate_m_s: f64,
    /// Prototype loading rate u̇_p (m/s) [default: 1 cm/yr].
    #[arg(long, default_value_t = 3.17e-10)]
    prototype_rate_m_s: f64,
}

fn main() {
    // Output piped into `head` and the like: end quietly when the reader goes away, as Unix
    // tools do, instead of panicking on a broken pipe.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run { pipeline, seed, out, quiet } => run(&pipeline, seed, out, quiet),
        Command::Pipeline { pipelines, out, seeds, threads, fresh, shard, quiet } => {
            ensemble(&pipelines, out, seeds.as_deref(), threads, fresh, shard, quiet)
        }
        Command::Merge { out, pipeline, shards } => merge(&out, pipeline.as_deref(), shards),
        Command::Compare { a, b } => compare(&a, &b),
        Command::Similarity(args) => similarity(&args),
        Command::Show { table, rows } => show(&table, rows),
        Command::Spectra(args) => record_spectra(&args),
        Command::Check { pipeline, seed } => check(&pipeline, seed),
        Command::Bench(BenchCommand::Accuracy { pipeline, fractions, refinements, duration_s, out }) => {
            bench_accuracy(&pipeline, fractions, refinements, duration_s, out)
        }
        Command::Bench(BenchCommand::Skip { pipeline, seeds, jumps, window_s, out }) => {
            bench_skip(&pipeline, seeds.as_deref(), jumps, window_s, out)
        }
    };
    if let Err(e) = result {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

fn progress_bar(quiet: bool, len: u64) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
    }
    let pb = ProgressBar::new(len);
    pb.set_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:40}] {percent:>3}% ({elapsed} / ETA {eta})")
            .expect("valid template")
            .progress_chars("=> "),
    );
    pb
}

fn run(path: &Path, seed: u64, out: Option<PathBuf>, quiet: bool) -> Result<()> {
    let pipeline = Pipeline::load(path)?;
    let out = out.unwrap_or_else(|| PathBuf::from("reports").join(&pipeline.name).join(format!("seed-{seed}")));
    let model = Model::new(pipeline.scene.clone());
    let pb = progress_bar(quiet, 1000);
    pb.set_message(format!("{} seed {seed}", pipeline.name));
    let start = Instant::now();
    let output = run_seed(&model, seed, RunOptions::default(), &mut |f| {
        pb.set_position((f * 1000.0) as u64);
        ControlFlow::Continue(())
    });
    pb.finish_and_clear();
    let output = output.with_context(|| format!("seed {seed} of {}", path.display()))?;
    let wall = start.elapsed().as_secs_f64();
    let mut series = series_frame(seed, &output.records)?;
    let series_path = out.join("series.parquet");
    write_parquet_atomic(&mut series, &series_path)?;
    let mut written = vec![series_path.display().to_string()];
    if !output.records.control.is_empty() {
        let mut control = control_frame(seed, &output.records)?;
        let control_path = out.join("control.parquet");
        write_parquet_atomic(&mut control, &control_path)?;
        written.push(control_path.display().to_string());
    }
    if !output.records.skips.is_empty() {
        let mut skips = skips_frame(seed, &output.records)?;
        let skips_path = out.join("skips.parquet");
        write_parquet_atomic(&mut skips, &skips_path)?;
        written.push(skips_path.display().to_string());
    }
    let steps = output.steps();
    let integrated = output.integrated_steps();
    let settle = match output.settled_by {
        SettleMethod::Static => "settled statically".to_string(),
        SettleMethod::Dynamic => format!("settle {}", output.settle_steps),
    };
    println!(
        "seed {seed}: {steps} steps ({settle} + shear {}) of Δt = {:.4e} s ({:.2} of critical {:.4e} s) in {wall:.2} s \
         ({:.3e} steps/s, {:.3e} bar-updates/s); {} samples → {}",
        output.shear_steps,
        output.dt_s,
        output.dt_s / output.critical.dt_s,
        output.critical.dt_s,
        integrated as f64 / wall,
        integrated as f64 * model.bar_count() as f64 / wall,
        output.records.len(),
        written.join(", "),
    );
    if let Some(note) = &output.settle_note {
        println!("  static settle not used ({note}): settled dynamically");
    }
    let sk = output.skip;
    if pipeline.scene.skip_ahead.enabled {
        println!(
            "  skip-ahead: {} of {} shear steps skipped in {} jumps ({} quasi-static motions, {} CG iterations)",
            sk.skipped_steps, output.shear_steps, sk.jumps, sk.solves, sk.cg_iterations
        );
    }
    Ok(())
}

fn check(path: &Path, seed: u64) -> Result<()> {
    let pipeline = Pipeline::load(path)?;
    let scene = &pipeline.scene;
    let model = Model::new(scene.clone());
    let lattice = model.lattice();
    let k = model.bar_stiffness(seed)?;
    let crit = critical_time_step(&model, &k)?;
    let e = lattice.extent();
    println!("pipeline {} ({}), scene hash {}", pipeline.name, path.display(), pipeline.hash);
    println!(
        "  seeds: {} ({}…)",
        pipeline.seeds.len(),
        pipeline.seeds.iter().take(5).map(|s| s.to_string()).collect::<Vec<_>>().join(", ")
    );
    println!(
        "  block {}×{}×{} modules of Lc = {} m ({} × {} × {} m): {} nodes, {} bars, {} contact nodes, mass {:.3} kg",
        scene.dims.nx,
        scene.dims.ny,
        scene.dims.nz,
        scene.lc_m,
        e[0],
        e[1],
        e[2],
        model.node_count(),
        model.bar_count(),
        model.contact().len(),
        model.total_mass()
    );
    let weight = model.total_mass() * scene.self_weight.gravity_m_s2;
    println!(
        "  self-weight normal stress {:.1} Pa, sliding strength μs·σ = {:.1} Pa",
        weight / lattice.contact_area(),
        scene.friction.mu_static * weight / lattice.contact_area()
    );
    println!(
        "  critical step (seed {seed}) {:.4e} s (ω_max {:.4e} rad/s, {} Lanczos iterations); paper's 0.6·Lc/Cp = {:.4e} s",
        crit.dt_s,
        crit.omega_max,
        crit.iterations,
        scene.paper_time_step_bound()
    );
    for axis in [0, 2] {
        let m = uniaxial_moduli(&model, &k, axis)?;
        let name = |a: usize| ["x", "y", "z"][a];
        let others: Vec<usize> = (0..3).filter(|&a| a != axis).collect();
        println!(
            "  effective stiffness along {} (static solve, uniaxial stress): E = {:.4e} Pa ({:.3} of E), \
             ν_{}{} = {:.3}, ν_{}{} = {:.3}",
            name(axis),
            m.young_pa,
            m.young_pa / scene.young_pa,
            name(axis),
            name(others[0]),
            m.poisson[0],
            name(axis),
            name(others[1]),
            m.poisson[1]
        );
    }
    println!(
        "  drivers: {}",
        scene
            .shear
            .drivers
            .iter()
            .map(|d| format!("LDEM {} at {:?} m", d.ldem(), lattice.position(*d)))
            .collect::<Vec<_>>()
            .join("; ")
    );
    let sw = &scene.self_weight;
    println!(
        "  self-weight: {}",
        match sw.method {
            SettleMethod::Static =>
                "solved statically (falls back to damped settling if friction cannot hold it)".into(),
            SettleMethod::Dynamic => format!(
                "damped settling, D = {} 1/s, until out-of-balance/weight < {:e}",
                sw.damping_per_s, sw.settle_tolerance
            ),
        }
    );
    let sk = &scene.skip_ahead;
    if sk.enabled {
        println!(
            "  skip-ahead: on (tolerance {:e}, {} explicit steps before each transition{})",
            sk.tolerance,
            sk.margin_steps,
            sk.record_interval_s.map_or(String::new(), |iv| format!(", one sample per {iv} s while skipping"))
        );
    }
    Ok(())
}

/// Parses "1,5,10-20" into seeds.
fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let (k, n) = text.split_once('/').ok_or_else(|| format!("{text:?}: expected K/N, e.g. 3/8"))?;
    let (k, n): (usize, usize) = (
        k.trim().parse().map_err(|_| format!("{k:?} is not a shard number"))?,
        n.trim().parse().map_err(|_| format!("{n:?} is not a shard count"))?,
    );
    if n == 0 || k == 0 || k > n {
        return Err(format!("{text}: need 1 ≤ K ≤ N"));
    }
    Ok((k, n))
}

fn bench_out(pipeline: &Pipeline, out: Option<PathBuf>) -> PathBuf {
    out.unwrap_or_else(|| PathBuf::from("reports").join("bench").join(&pipeline.name))
}

fn bench_accuracy(
    path: &Path,
    fractions: Vec<f64>,
    refinements: Vec<u32>,
    duration_s: Option<f64>,
    out: Option<PathBuf>,
) -> Result<()> {
    let pipeline = Pipeline::load(path)?;
    anyhow::ensure!(
        fractions.iter().all(|f| *f > 0.0 && *f <= 1.0),
        "--fractions: each must be in (0, 1] (fractions of the critical step)"
    );
    anyhow::ensure!(refinements.iter().all(|r| (1..=16).contains(r)), "--refinements: each must be 1 ≤ r ≤ 16");
    if let Some(d) = duration_s {
        anyhow::ensure!(d > 0.0 && d.is_finite(), "--duration-s must be a positive number of seconds");
    }
    let out = bench_out(&pipeline, out);
    let plan = AccuracyPlan { fractions, refinements, duration_s, seed: pipeline.seeds[0] };
    let rows = run_accuracy(&pipeline.scene, &pipeline.events, &plan, &mut |m| eprintln!("{m}"))?;
    let table = out.join("accuracy.parquet");
    write_parquet_atomic(&mut accuracy_frame(&rows)?, &table)?;
    let figure = out.join("accuracy.png");
    accuracy_figure(&rows, &figure)?;
    println!(
        "{:>10} {:>8} {:>10} {:>9} {:>12} {:>12} {:>12} {:>12} {:>12}",
        "lattice", "Δt/crit", "steps", "wall s", "linear τ", "loading τ", "S1 τ", "S1 drop", "E1 onset"
    );
    for r in &rows {
        println!(
            "{:>10} {:>8} {:>10} {:>9.2} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e}",
            format!("{}×{}×{}", r.dims[0], r.dims[1], r.dims[2]),
            r.dt_fraction,
            r.steps,
            r.wall_s,
            r.errors[0],
            r.errors[1],
            r.errors[2],
            r.errors[5],
            r.errors[4]
        );
    }
    for &r in &plan.refinements {
        let shown = |p: Option<f64>| p.map_or("n/a".to_string(), |p| format!("{p:.2}"));
        let order = |k: usize| shown(observed_order(&rows, r, |x| x.errors[k]));
        println!(
            "refinement {r}: observed order in Δt — τ while linear {} (against its own smallest Δt: {}), \
             before the first event {}, around S1 {}",
            order(0),
            shown(observed_order(&rows, r, |x| x.linear_tau_error_dt)),
            order(1),
            order(2)
        );
    }
    if let Some(r) = rows.first() {
        println!(
            "(the reference run is linear until t = {:.4} s: no base node slides, lifts or lands before)",
            r.linear_until_s
        );
    }
    println!("→ {}, {}", table.display(), figure.display());
    Ok(())
}

fn bench_skip(path: &Path, seeds: Option<&str>, jumps: usize, window_s: f64, out: Option<PathBuf>) -> Result<()> {
    let pipeline = Pipeline::load(path)?;
    anyhow::ensure!(window_s > 0.0 && window_s.is_finite(), "--window-s must be a positive number of seconds");
    let seeds = match seeds {
        Some(s) => parse_seeds(s)?,
        None => pipeline.seeds.clone(),
    };
    let out = bench_out(&pipeline, out);
    let bench = SkipBench { jumps_per_seed: jumps, window_s };
    let (runs, checks) = compare_skip(&pipeline.scene, &pipeline.events, &seeds, bench, &mut |m| eprintln!("{m}"))?;
    let runs_path = out.join("skip_runs.parquet");
    write_parquet_atomic(&mut skip_runs_frame(&runs)?, &runs_path)?;
    let jumps_path = out.join("skip_jumps.parquet");
    write_parquet_atomic(&mut skip_jumps_frame(&checks)?, &jumps_path)?;
    let (full, skip): (f64, f64) = runs.iter().fold((0.0, 0.0), |a, r| (a.0 + r.full_wall_s, a.1 + r.skip_wall_s));
    let (skipped, steps): (u64, u64) = runs.iter().fold((0, 0), |a, r| (a.0 + r.skipped_steps, a.1 + r.shear_steps));
    println!(
        "{} seeds: full integration {full:.2} s, with skip-ahead {skip:.2} s ({:.2}×); {:.1}% of {} shear steps skipped in {} jumps",
        runs.len(),
        full / skip,
        100.0 * skipped as f64 / steps.max(1) as f64,
        steps,
        runs.iter().map(|r| r.jumps).sum::<u64>()
    );
    for r in &runs {
        println!(
            "  seed {}: main shocks full/skip/perturbed {}/{}/{}, mean main drop {:.0}/{:.0}/{:.0} Pa",
            r.seed,
            r.main_shocks[0],
            r.main_shocks[1],
            r.main_shocks[2],
            r.mean_drop_pa[0],
            r.mean_drop_pa[1],
            r.mean_drop_pa[2]
        );
    }
    let max = |f: &dyn Fn(&stickslip_analysis::bench::skip::JumpCheck) -> f64| {
        checks.iter().map(f).filter(|v| v.is_finite()).fold(f64::NAN, f64::max)
    };
    let shown = |v: f64| if v.is_nan() { "n/a".to_string() } else { format!("{v:.2e}") };
    let with_events = checks.iter().filter(|c| c.event[0].is_some() && c.event[1].is_some()).count();
    println!(
        "{} jumps checked one by one: onset error ≤ {} of the recurrence (run perturbed by 1e-9: {}); \
         {with_events} followed by an event: drop error ≤ {} (perturbed run {}); event or none alike in {}/{}",
        checks.len(),
        shown(max(&|c| c.onset_error(1))),
        shown(max(&|c| c.onset_error(2))),
        shown(max(&|c| c.drop_error(1))),
        shown(max(&|c| c.drop_error(2))),
        checks.iter().filter(|c| c.same_events()).count(),
        checks.len()
    );
    println!("→ {}, {}", runs_path.display(), jumps_path.display());
    Ok(())
}

fn parse_seeds(text: &str) -> Result<Vec<u64>> {
    let mut seeds = Vec::new();
    for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        if let Some((a, b)) = part.split_once('-') {
            let (a, b): (u64, u64) = (
                a.trim().parse().with_context(|| format!("--seeds: {a:?} is not a seed"))?,
                b.trim().parse().with_context(|| format!("--seeds: {b:?} is not a seed"))?,
            );
            anyhow::ensure!(a <= b, "--seeds: range {part} runs backwards");
            seeds.extend(a..=b);
        } else {
            seeds.push(part.parse().with_context(|| format!("--seeds: {part:?} is not a seed"))?);
        }
    }
    anyhow::ensure!(!seeds.is_empty(), "--seeds: no seed given");
    seeds.dedup();
    Ok(seeds)
}

fn ensemble(
    paths: &[PathBuf],
    out: Option<PathBuf>,
    seeds: Option<&str>,
    threads: usize,
    fresh: bool,
    shard: Option<(usize, usize)>,
    quiet: bool,
) -> Result<()> {
    anyhow::ensure!(out.is_none() || paths.len() == 1, "--out needs exactly one pipeline");
    anyhow::ensure!(
        !(fresh && shard.is_some()),
        "--fresh with --shard would discard the other shards' results: clear the folder by hand"
    );
    // Validate every file before running any.
    let pipelines = paths.iter().map(|p| Pipeline::load(p)).collect::<Result<Vec<_>, _>>()?;
    let cancel = Arc::new(AtomicBool::new(false));
    {
        let cancel = cancel.clone();
        ctrlc::set_handler(move || {
            if cancel.swap(true, Ordering::SeqCst) {
                std::process::exit(130);
            }
            eprintln!("\ninterrupt: finishing the seeds being written (Ctrl-C again to stop at once)");
        })
        .context("installing the Ctrl-C handler")?;
    }
    for pipeline in &pipelines {
        let mut seeds = match seeds {
            Some(s) => parse_seeds(s)?,
            None => pipeline.seeds.clone(),
        };
        if let Some((k, n)) = shard {
            seeds = stickslip_analysis::ensemble::shard(&seeds, k, n);
        }
        let out = out.clone().unwrap_or_else(|| PathBuf::from("reports").join(&pipeline.name));
        let pb = progress_bar(quiet, seeds.len() as u64);
        pb.set_style(
            ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} seeds ({elapsed}, ETA {eta})")
                .expect("valid template")
                .progress_chars("=> "),
        );
        pb.set_message(pipeline.name.clone());
        let options = EnsembleOptions { out: out.clone(), threads, seeds, fresh, finish: shard.is_none() };
        let report = run_ensemble(pipeline, &options, &|done, _| pb.set_position(done as u64), &cancel);
        pb.finish_and_clear();
        let report = report?;
        println!(
            "{}{}: {} seeds ({} run now, {} already done, {} failed) in {:.1} s → {}",
            pipeline.name,
            shard.map_or(String::new(), |(k, n)| format!(" shard {k}/{n}")),
            report.ran + report.skipped,
            report.ran,
            report.skipped,
            report.failed.len(),
            report.wall_time_s,
            report.out.join("tables").display()
        );
        for (seed, msg) in report.failed.iter().take(5) {
            println!("  seed {seed} failed: {msg}");
        }
        if shard.is_some() {
            println!("  merge the shards with: stickslip merge {}", out.display());
            continue;
        }
        println!("{}", digest(&out)?);
        if let Some(r) = &report.report {
            println!(
                "report: {} figures in {:.1} s → {}{}",
                r.figures.len(),
                report.report_time_s,
                r.index.display(),
                if r.skipped.is_empty() {
                    String::new()
                } else {
                    format!(" ({} skipped for lack of data)", r.skipped.len())
                }
            );
        }
    }
    Ok(())
}

fn similarity(a: &SimilarityArgs) -> Result<()> {
    for (name, v) in [
        ("--stress-drop-pa", a.stress_drop_pa),
        ("--model-length-m", a.model_length_m),
        ("--model-area-m2", a.model_area_m2),
        ("--prototype-length-m", a.prototype_length_m),
        ("--model-rate-m-s", a.model_rate_m_s),
        ("--prototype-rate-m-s", a.prototype_rate_m_s),
    ] {
        anyhow::ensure!(v > 0.0 && v.is_finite(), "{name} = {v}: must be positive");
    }
    let params = SimilarityParams {
        prototype_length_m: a.prototype_length_m,
        prototype_rate_m_s: a.prototype_rate_m_s,
        ..SimilarityParams::default()
    };
    let e = ModelEvent {
        stress_drop_pa: a.stress_drop_pa,
        model_length_m: a.model_length_m,
        model_area_m2: a.model_area_m2,
        duration_s: a.duration_s,
        recurrence_s: a.recurrence_s,
        model_rate_m_s: a.model_rate_m_s,
    };
    let s = scale(&e, &params);
    let row = |k: &str, v: String| println!("  {k:<44} {v}");
    println!("similarity (SPEC §9): λ = L_p/L_m");
    row("λ", format!("{:.6e}", s.lambda));
    row("prototype rupture area A_p = λ²·A_m", format!("{:.4e} m²", s.prototype_area_m2));
    if let Some(d) = s.prototype_duration_s {
        row("prototype duration λ·t_m", format!("{d:.4} s"));
    }
    if let Some(r) = s.prototype_recurrence_s {
        row("prototype recurrence Δt_m·λ·u̇_m/u̇_p", format!("{r:.4e} s = {:.3} years", r / SECONDS_PER_YEAR));
    }
    row("M0, paper's Eq. 15 (Δσ·L_p·A_p·λ)", format!("{:.4e} dyne·cm", s.m0_paper_dyne_cm));
    row("  Riera M, interplate (X = 0)", format!("{:.3}", riera_magnitude(s.m0_paper_dyne_cm, false)));
    row("  Riera M, intraplate (X = 1)", format!("{:.3}", riera_magnitude(s.m0_paper_dyne_cm, true)));
    row("  Mw (Hanks & Kanamori)", format!("{:.3}", moment_magnitude(s.m0_paper_dyne_cm)));
    row("M0, consistent (Δσ·L_p·A_p)", format!("{:.4e} dyne·cm", s.m0_consistent_dyne_cm));
    row("  Riera M, interplate (X = 0)", format!("{:.3}", riera_magnitude(s.m0_consistent_dyne_cm, false)));
    row("  Riera M, intraplate (X = 1)", format!("{:.3}", riera_magnitude(s.m0_consistent_dyne_cm, true)));
    row("  Mw (Hanks & Kanamori)", format!("{:.3}", moment_magnitude(s.m0_consistent_dyne_cm)));
    Ok(())
}

fn show(path: &Path, rows: usize) -> Result<()> {
    // SAFETY: set before any other thread exists (polars reads these when formatting).
    unsafe {
        std::env::set_var("POLARS_FMT_MAX_ROWS", rows.to_string());
        std::env::set_var("POLARS_FMT_MAX_COLS", "60");
        std::env::set_var("POLARS_FMT_STR_LEN", "40");
        std::env::set_var("POLARS_TABLE_WIDTH", "400");
    }
    let text = stickslip_analysis::tables::describe(path, rows)?;
    println!("{text}");
    Ok(())
}

fn record_spectra(a: &SpectraArgs) -> Result<()> {
    use stickslip_analysis::spectra::fourier::Window;
    use stickslip_analysis::spectra::intensity::Baseline;
    use stickslip_analysis::spectra::records::{AccelUnit, read_record};
    use stickslip_analysis::spectra::response::{Reading, log_periods};
    use stickslip_analysis::spectra::tables::record_tables;
    let unit = match a.units {
        CsvUnits::G => AccelUnit::G,
        CsvUnits::MS2 => AccelUnit::MetrePerSecond2,
        CsvUnits::CmS2 => AccelUnit::CentimetrePerSecond2,
    };
    let record = read_record(&a.record, unit)?;
    let duration = record.dt * (record.accel.len().saturating_sub(1)) as f64;
    let tmin = a.period_min_s.unwrap_or(2.0 * record.dt);
    let tmax = a.period_max_s.unwrap_or(0.5 * duration);
    anyhow::ensure!(tmin > 0.0 && tmax > tmin, "periods: need 0 < --period-min-s ({tmin}) < --period-max-s ({tmax})");
    anyhow::ensure!(a.period_count >= 1, "--period-count must be at least 1");
    for d in &a.dampings {
        anyhow::ensure!((0.0..1.0).contains(d), "--dampings: {d} is not in [0, 1)");
    }
    let periods = log_periods(tmin, tmax, a.period_count);
    let reading = if a.band_limited { Reading::BandLimited } else { Reading::Linear };
    let baseline = if a.baseline { Baseline::Linear } else { Baseline::None };
    let [mut spectra, mut fourier, mut intensity] =
        record_tables(&record, &periods, &a.dampings, reading, baseline, Window::Rectangular)?;
    let stem = a.record.file_stem().and_then(|s| s.to_str()).unwrap_or("record").to_string();
    let out = a.out.clone().unwrap_or_else(|| PathBuf::from("reports").join("records").join(&stem));
    for (name, df) in [("spectra", &mut spectra), ("fourier", &mut fourier), ("intensity", &mut intensity)] {
        write_parquet_atomic(df, &out.join(format!("{name}.parquet")))?;
    }
    println!(
        "{}: {} samples every {:.6e} s ({:.4} s){}",
        a.record.display(),
        record.accel.len(),
        record.dt,
        duration,
        if record.description.is_empty() { String::new() } else { format!(" — {}", record.description) }
    );
    println!("{}", stickslip_analysis::tables::describe(&out.join("intensity.parquet"), 1)?);
    println!(
        "spectra ({} periods from {tmin:.4e} s to {tmax:.4e} s, dampings {:?}) → {}",
        periods.len(),
        a.dampings,
        out.display()
    );
    Ok(())
}

fn merge(out: &Path, pipeline: Option<&Path>, shards: Option<usize>) -> Result<()> {
    let r = stickslip_analysis::merge::merge(out, pipeline, shards)?;
    println!(
        "merged {} seeds ({} failed) in {:.1} s → {}",
        r.seeds,
        r.failed,
        r.wall_time_s,
        out.join("tables").display()
    );
    println!("{}", digest(out)?);
    if let Some(rep) = &r.report {
        println!("report: {} figures → {}", rep.figures.len(), rep.index.display());
    }
    Ok(())
}

fn compare(a: &Path, b: &Path) -> Result<()> {
    let diffs = stickslip_analysis::compare::compare_tables(a, b, &["wall_time_s"])?;
    if diffs.is_empty() {
        println!("{} and {} hold the same tables (wall times aside)", a.display(), b.display());
        return Ok(());
    }
    for d in &diffs {
        println!("{d}");
    }
    anyhow::bail!("{} differences between {} and {}", diffs.len(), a.display(), b.display())
}
