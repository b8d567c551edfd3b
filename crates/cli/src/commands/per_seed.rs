//! `stickslip seeds`: one main shock seed by seed, as the Markdown table the README prints (so
//! the README's calibration numbers come from a command, not from memory).

use std::path::PathBuf;

use anyhow::Result;
use stickslip_config::Pipeline;
use stickslip_ensemble::seed_table::shock_table;
use stickslip_store::Folder;

/// Arguments of `stickslip seeds`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Output folder of a pipeline run, e.g. reports/paper.
    pub out: PathBuf,
    /// The main shock to tabulate (its recurrence is from the one before).
    #[arg(long, default_value = "S2")]
    pub shock: String,
}

/// `stickslip seeds`.
pub fn run(a: Args) -> Result<()> {
    let shock = a.shock.as_str();
    let rank = shock.strip_prefix('S').and_then(|n| n.parse::<u32>().ok()).filter(|&n| n >= 1);
    anyhow::ensure!(
        rank.is_some(),
        "--shock {shock:?} is not a main shock: main shocks are named S1, S2, … in time order within each seed"
    );
    let folder = Folder::new(&a.out);
    folder.require_output()?;
    let pipeline = Pipeline::load(&a.out.join("pipeline.toml"))?;
    outln!("{}", shock_table(&folder, &pipeline, shock)?);
    Ok(())
}
