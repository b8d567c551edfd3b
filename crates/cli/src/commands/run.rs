//! `stickslip run`: one seed of a pipeline, as an ensemble of one (the same folder layout, tables
//! and report as `stickslip pipeline`), with the speed of the run.

use std::path::PathBuf;

use anyhow::Result;
use stickslip_config::Pipeline;
use stickslip_ensemble::EnsembleOptions;
use stickslip_store::Folder;
use stickslip_store::io::read_parquet;
use stickslip_store::schema::RUNS;
use stickslip_store::tables::runs::Runs;

use crate::commands::pipeline::{cancel_on_ctrl_c, ensemble, finish};

/// Arguments of `stickslip run`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Pipeline file (TOML), e.g. pipelines/paper.toml.
    pub pipeline: PathBuf,
    /// Seed of the random fields.
    #[arg(long)]
    pub seed: u64,
    /// Output folder [default: reports/<pipeline name>/seed-<seed>].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Discard results of a different pipeline found in the output folder.
    #[arg(long)]
    pub fresh: bool,
    /// No progress bar.
    #[arg(long, short)]
    pub quiet: bool,
    /// Accept a run of more than 10¹¹ bar-updates (refused otherwise).
    #[arg(long)]
    pub allow_long: bool,
}

/// `stickslip run`.
pub fn run(a: Args) -> Result<()> {
    let pipeline = Pipeline::load(&a.pipeline)?;
    crate::commands::pipeline::print_warnings(&pipeline);
    crate::budget::check_before_build(
        &pipeline.scene,
        1,
        1,
        a.allow_long,
        &format!("{}: seed {}", pipeline.name, a.seed),
    )?;
    let out = a.out.unwrap_or_else(|| PathBuf::from("reports").join(&pipeline.name).join(format!("seed-{}", a.seed)));
    let cancel = cancel_on_ctrl_c()?;
    let options = EnsembleOptions { out: out.clone(), threads: 1, seeds: vec![a.seed], fresh: a.fresh, finish: true };
    let report = ensemble(&pipeline, &options, a.quiet, &cancel)?;
    if let Some((_, msg)) = report.failed.first() {
        anyhow::bail!("seed {} of {}: {msg}", a.seed, a.pipeline.display());
    }
    let folder = Folder::new(&out);
    let runs = Runs::read(&read_parquet(&folder.part(&RUNS, a.seed))?)?;
    let bars = pipeline.scene.dims.bar_count();
    let (steps, skipped, wall) = (runs.steps[0], runs.skipped_steps[0], runs.wall_time_s[0]);
    let settle = if runs.settled_by[0] == "static" {
        "settled statically".into()
    } else {
        format!("settle {}", runs.settle_steps[0])
    };
    println!(
        "seed {}: {steps} steps ({settle} + shear {}) of Δt = {:.4e} s ({:.2} of critical {:.4e} s) in {wall:.2} s \
         ({:.3e} steps/s, {:.3e} bar-updates/s){}",
        a.seed,
        steps - runs.settle_steps[0],
        runs.dt_s[0],
        runs.dt_s[0] / runs.critical_dt_s[0],
        runs.critical_dt_s[0],
        (steps - skipped) as f64 / wall,
        (steps - skipped) as f64 * bars as f64 / wall,
        if skipped > 0 { format!("; {skipped} steps skipped by the skip-ahead") } else { String::new() },
    );
    println!("tables → {}", folder.tables().display());
    finish(&pipeline, &out)
}
