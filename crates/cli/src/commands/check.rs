//! `stickslip check`: validates a pipeline file and prints what it builds, without running it
//! ([`stickslip_ensemble::check`] says what).

use std::path::PathBuf;

use anyhow::Result;
use stickslip_config::Pipeline;
use stickslip_ensemble::check::{CheckOptions, check};

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
    /// Say how the scene splits over this many MPI ranks (slabs of module layers along z): each
    /// rank's layers, nodes, bars and memory, and the halo traded per step; refused when a rank
    /// cannot hold its part (docs/guide/ensembles.md, "One scene over MPI ranks").
    #[arg(long)]
    pub ranks: Option<usize>,
    /// Memory of one rank for --ranks, in GB (default: this machine's available memory divided
    /// by the ranks).
    #[arg(long, requires = "ranks")]
    pub memory_per_rank: Option<f64>,
}

/// `stickslip check`.
pub fn run(a: Args) -> Result<()> {
    let pipeline = Pipeline::load(&a.pipeline)?;
    outln!("pipeline {} ({}), hash {}", pipeline.name, a.pipeline.display(), pipeline.hash);
    if pipeline.cycles.is_some() {
        for line in stickslip_config::describe::cycles(&pipeline).texts() {
            outln!("  {line}");
        }
        return Ok(());
    }
    let memory_per_rank = match a.memory_per_rank {
        Some(gb) if !(gb > 0.0 && gb.is_finite()) => {
            anyhow::bail!("--memory-per-rank = {gb} is not allowed: a positive number of GB (e.g. 4 or 0.5)")
        }
        Some(gb) => Some((gb * 1e9) as u64),
        None => None,
    };
    let options = CheckOptions {
        seeds: a.seeds,
        full_statics: a.full_statics,
        allow_long: a.allow_long,
        threads: 0,
        ranks: a.ranks,
        memory_per_rank,
    };
    check(&pipeline, &options, &mut |line| outln!("  {}", line.text))?;
    Ok(())
}
