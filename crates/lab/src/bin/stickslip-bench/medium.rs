//! `stickslip-bench medium`: what the medium costs a step ([`stickslip_lab::medium_cost`]).

use anyhow::Result;

use crate::large::SizeArgs;

/// The pipeline's scene at the given size (e.g. `large-block.toml 200 50 20` for 2.8 M bars,
/// `500 150 48` for 50 M) elastic, with Q = 50 over 0.05–5 Hz, and with Q and Kelvin–Voigt
/// dashpots, taken in turn, best of the rounds.
#[derive(clap::Args, Debug)]
pub struct MediumArgs {
    /// The scene and the steps timed per variant and round.
    #[command(flatten)]
    size: SizeArgs,
    /// Rounds of the three variants.
    #[arg(long, default_value_t = 2)]
    rounds: usize,
    /// Threads (the step split over them).
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Seeds stepped side by side, as a pipeline batches them: 1, 4 or 8.
    #[arg(long, default_value_t = 1)]
    lanes: usize,
}

/// Runs the benchmark and prints its table.
pub fn run(a: MediumArgs) -> Result<()> {
    let (scene, _) = a.size.scene()?;
    let steps = a.size.steps;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(a.threads).build()?;
    let timings =
        pool.install(|| stickslip_lab::medium_cost::medium_cost(&scene, steps, a.rounds, a.threads > 1, a.lanes))?;
    let elastic = timings[0].step_s;
    println!("{} seed(s) side by side", a.lanes);
    println!("{:<32} {:>11} {:>10} {:>9} {:>14}", "medium", "bars", "step_ms", "ratio", "bytes/bar +");
    for t in &timings {
        println!(
            "{:<32} {:>11} {:>10.2} {:>9.2} {:>14.1}",
            t.name,
            t.bars,
            1e3 * t.step_s,
            t.step_s / elastic,
            t.extra_bytes_per_bar
        );
    }
    Ok(())
}
