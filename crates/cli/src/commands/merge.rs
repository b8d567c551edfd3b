//! `stickslip merge`: gathers the shards of an ensemble.

use std::path::PathBuf;

use anyhow::Result;

use crate::commands::pipeline::finish;

/// Arguments of `stickslip merge`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The shared output folder of the shards.
    pub out: PathBuf,
    /// Pipeline file [default: <out>/pipeline.toml, written by the shards].
    #[arg(long)]
    pub pipeline: Option<PathBuf>,
    /// Number of shards, to name the incomplete ones.
    #[arg(long)]
    pub shards: Option<usize>,
}

/// `stickslip merge`.
pub fn run(a: Args) -> Result<()> {
    let r = stickslip_ensemble::merge::merge(&a.out, a.pipeline.as_deref(), a.shards)?;
    outln!(
        "merged {} ({} failed) in {:.1} s → {}",
        crate::text::count(r.seeds, "seed", "seeds"),
        r.failed,
        r.wall_time_s,
        a.out.join("tables").display()
    );
    crate::commands::pipeline::print_warnings(&r.pipeline);
    crate::commands::pipeline::print_set_result(&r.pipeline, r.set.as_ref(), &a.out);
    finish(&r.pipeline, &a.out)?;
    let mut unfinished = Vec::new();
    if r.seeds > 0 && r.failed == r.seeds {
        unfinished.push(format!("{}: every seed failed ({}); nothing to analyse", r.pipeline.name, r.seeds));
    }
    if let Some(Err(e)) = &r.set {
        unfinished.push(format!("{}: the [set] asked for could not be chosen: {e}", r.pipeline.name));
    }
    crate::commands::pipeline::finished(unfinished)
}
