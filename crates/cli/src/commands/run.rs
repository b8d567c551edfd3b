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
    /// Seed of the random fields (a whole number ≥ 0).
    #[arg(long, allow_negative_numbers = true, value_parser = parse_seed)]
    pub seed: u64,
    /// Output folder [default: reports/<pipeline name>/seed-<seed>].
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Worker threads [default: one per core]: a large lattice splits each step over them; the
    /// numbers are the same on any thread count.
    #[arg(long, allow_negative_numbers = true, value_parser = crate::commands::pipeline::parse_threads)]
    pub threads: Option<usize>,
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

/// A seed as given on the command line: a whole number ≥ 0 (a negative one is refused as such,
/// not taken for an option).
pub fn parse_seed(s: &str) -> Result<u64, String> {
    match s.trim().parse::<i128>() {
        Ok(v) if v < 0 => Err(format!("{v} is not a seed: seeds are whole numbers ≥ 0")),
        Ok(v) => u64::try_from(v).map_err(|_| format!("{v} is not a seed: seeds are whole numbers up to {}", u64::MAX)),
        Err(_) => Err(format!("{s:?} is not a seed: seeds are whole numbers ≥ 0")),
    }
}

/// `stickslip run`.
pub fn run(a: Args) -> Result<()> {
    anyhow::ensure!(a.threads != Some(0), "--threads 0: give at least 1 (or leave it out for one per core)");
    let pipeline = Pipeline::load(&a.pipeline)?;
    anyhow::ensure!(
        pipeline.cycles.is_none(),
        "{}: a [cycles] pipeline is one run of its fault over the years, not a seed's explicit run: \
         stickslip pipeline {}",
        pipeline.name,
        a.pipeline.display()
    );
    crate::commands::pipeline::print_warnings(&pipeline);
    stickslip_ensemble::budget::check_before_build(
        &pipeline.scene,
        1,
        1,
        a.allow_long,
        &format!("{}: seed {}", pipeline.name, a.seed),
    )?;
    let out = a.out.unwrap_or_else(|| PathBuf::from("reports").join(&pipeline.name).join(format!("seed-{}", a.seed)));
    let cancel = cancel_on_ctrl_c()?;
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: out.clone(),
        threads: a.threads.unwrap_or(0),
        seeds: vec![a.seed],
        fresh: a.fresh,
        finish: true,
    };
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
    outln!(
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
    outln!("tables → {}", folder.tables().display());
    finish(&pipeline, &out)
}

#[cfg(test)]
mod tests {
    use super::parse_seed;

    #[test]
    fn a_negative_seed_is_refused_as_a_seed() {
        assert_eq!(parse_seed("7"), Ok(7));
        assert_eq!(parse_seed("-1").unwrap_err(), "-1 is not a seed: seeds are whole numbers ≥ 0");
        assert!(parse_seed("x").unwrap_err().contains("\"x\" is not a seed"));
        assert!(parse_seed("99999999999999999999999").unwrap_err().contains("up to"));
    }
}
