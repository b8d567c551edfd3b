//! `stickslip-bench setup` and `stickslip-bench bandwidth`: a large scene's set-up against its
//! step, and its step against what memory allows ([`stickslip_lab::setup_cost`]).

use std::path::PathBuf;

use anyhow::Result;
use stickslip_config::{Pipeline, PipelineFile};
use stickslip_lab::setup_cost::{bandwidth as measure_bandwidth, setup_cost};

/// A pipeline's scene at a given size.
#[derive(clap::Args, Debug)]
pub struct SizeArgs {
    /// Pipeline file (TOML).
    pipeline: PathBuf,
    /// Modules along x [default: the pipeline's].
    nx: Option<usize>,
    /// Modules along y.
    ny: Option<usize>,
    /// Modules along z.
    nz: Option<usize>,
    /// Steps timed (in each round, where there are rounds).
    #[arg(long, default_value_t = 20)]
    pub steps: usize,
}

impl SizeArgs {
    /// The pipeline's scene at the size asked for, and its first seed.
    pub fn scene(&self) -> Result<(stickslip_solver::Scene, u64)> {
        let p = Pipeline::load(&self.pipeline)?;
        if self.nx.is_none() && self.ny.is_none() && self.nz.is_none() {
            return Ok((p.scene, p.seeds[0]));
        }
        // Resized through the configuration, so that everything placed in the block (drivers,
        // stations, patches) is checked against the new size.
        let mut file: PipelineFile = p.file.clone();
        let b = &mut file.block;
        let size = |n: Option<usize>, was: i64| n.map_or(Ok(was), i64::try_from);
        (b.nx, b.ny, b.nz) = (size(self.nx, b.nx)?, size(self.ny, b.ny)?, size(self.nz, b.nz)?);
        let (base, size) = (self.pipeline.parent().unwrap_or(std::path::Path::new(".")), [b.nx, b.ny, b.nz]);
        let p = Pipeline::from_file_in(file, &p.name, base).map_err(|e| {
            anyhow::anyhow!("{} at {} × {} × {} modules: {e}", self.pipeline.display(), size[0], size[1], size[2])
        })?;
        Ok((p.scene, p.seeds[0]))
    }
}

/// `stickslip-bench setup`: the set-up and a step, on one thread and on all of them.
pub fn setup(a: SizeArgs) -> Result<()> {
    let (scene, seed) = a.scene()?;
    println!(
        "{:>8} {:>11} {:>8} {:>8} {:>8} {:>4} {:>8} {:>8} {:>9} {:>9} {:>11}",
        "threads",
        "bars",
        "model_s",
        "stiff_s",
        "crit_s",
        "its",
        "state_s",
        "setup_s",
        "step_s",
        "setup/step",
        "updates/s"
    );
    let all = std::thread::available_parallelism().map_or(1, |n| n.get());
    for threads in [1, all] {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build()?;
        let c = pool.install(|| setup_cost(scene.clone(), seed, a.steps, threads > 1))?;
        println!(
            "{threads:>8} {:>11} {:>8.3} {:>8.3} {:>8.3} {:>4} {:>8.3} {:>8.3} {:>9.4} {:>9.1} {:>11.3e}",
            c.bars,
            c.model_s,
            c.stiffness_s,
            c.critical_s,
            c.iterations,
            c.state_s,
            c.setup_s(),
            c.step_s,
            c.setup_s() / c.step_s,
            c.bars as f64 / c.step_s
        );
        if all == 1 {
            break;
        }
    }
    Ok(())
}

/// `stickslip-bench bandwidth`: the step against a triad over the same bytes, on every thread.
pub fn bandwidth(a: SizeArgs) -> Result<()> {
    let (scene, seed) = a.scene()?;
    let b = measure_bandwidth(scene, seed, a.steps)?;
    println!(
        "{} bars, {} nodes, {} threads: a step touches {:.1} MB and takes {:.2} ms; a triad over the same bytes \
         streams {:.1} GB/s (STREAM's count), so a step takes at least {:.2} ms: the step runs at {:.0}% of what \
         memory allows",
        b.bars,
        b.nodes,
        rayon::current_num_threads(),
        b.bytes as f64 / 1e6,
        1e3 * b.step_s,
        b.triad_b_s / 1e9,
        1e3 * b.bound_s(),
        100.0 * b.ratio()
    );
    Ok(())
}
