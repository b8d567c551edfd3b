//! `stickslip`: command-line glue over the solver and analysis crates.

use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use stickslip_analysis::Pipeline;
use stickslip_analysis::tables::{control_frame, series_frame, write_parquet_atomic};
use stickslip_solver::critical::critical_time_step;
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
    /// Check a pipeline file and print the scene it builds (nothing is run).
    Check {
        /// Pipeline file (TOML).
        pipeline: PathBuf,
        /// Seed used for the critical step of the random lattice.
        #[arg(long, default_value_t = 123)]
        seed: u64,
    },
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run { pipeline, seed, out, quiet } => run(&pipeline, seed, out, quiet),
        Command::Check { pipeline, seed } => check(&pipeline, seed),
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
    let steps = output.steps();
    println!(
        "seed {seed}: {steps} steps (settle {} + shear {}) of Δt = {:.4e} s ({:.2} of critical {:.4e} s) in {wall:.2} s \
         ({:.3e} steps/s, {:.3e} bar-updates/s); {} samples → {}",
        output.settle_steps,
        output.shear_steps,
        output.dt_s,
        output.dt_s / output.critical.dt_s,
        output.critical.dt_s,
        steps as f64 / wall,
        steps as f64 * model.bar_count() as f64 / wall,
        output.records.len(),
        written.join(", "),
    );
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
    println!("pipeline {} ({}), scene hash {}", pipeline.name, path.display(), pipeline.scene_hash);
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
    Ok(())
}
