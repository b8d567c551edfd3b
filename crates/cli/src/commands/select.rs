//! `stickslip select`: a set of an ensemble's records matched to a design spectrum.

use std::path::PathBuf;

use anyhow::{Context, Result};
use stickslip_config::Pipeline;
use stickslip_config::check::Checker;
use stickslip_config::set::SetSection;
use stickslip_ensemble::set::{SetOutcome, select_set};
use stickslip_store::Folder;

/// Arguments of `stickslip select`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Output folder of a finished ensemble (its records and spectra are the candidates).
    pub folder: PathBuf,
    /// A TOML file with a `[set]` section (the target, period range, count, caps, scale bounds;
    /// see `pipelines/accelerograms.toml`) [default: the `[set]` of the folder's pipeline].
    #[arg(long)]
    pub set: Option<PathBuf>,
}

/// A file with a `[set]` section (a pipeline file, or a file holding only that section).
#[derive(serde::Deserialize)]
struct SetFile {
    set: SetSection,
}

/// `stickslip select`.
pub fn run(a: Args) -> Result<()> {
    let folder = Folder::new(&a.folder);
    folder.require_output()?;
    let pipeline = Pipeline::load(&folder.pipeline_copy())
        .with_context(|| format!("reading the pipeline of {}", a.folder.display()))?;
    let settings = match &a.set {
        Some(path) => {
            let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
            let file: SetFile = toml::from_str(&text).with_context(|| format!("{}", path.display()))?;
            let mut ck = Checker::default();
            let base = path.parent().unwrap_or(std::path::Path::new("."));
            let s = file.set.build(base, pipeline.set_grid(), &mut ck);
            ck.finish().with_context(|| format!("{}", path.display()))?;
            s.context("the set could not be built")?
        }
        None => pipeline.set.clone().with_context(|| {
            format!("the pipeline of {} has no [set] section: give one with --set FILE", a.folder.display())
        })?,
    };
    let outcome = select_set(&folder, &pipeline, &settings)?;
    print_set(&outcome, &settings.target_name, &folder);
    Ok(())
}

/// Prints a chosen set.
pub fn print_set(o: &SetOutcome, target: &str, folder: &Folder) {
    let s = &o.selection;
    println!(
        "set: {} of {} records ({} eligible), periods {:.3} … {:.3} s, matched to {target}",
        s.records.len(),
        o.candidates,
        s.eligible,
        s.range.0,
        s.range.1
    );
    println!(
        "  mean / target ≥ {:.1}% over the range (at T = {:.3} s), mean squared log misfit {:.4}{}",
        100.0 * s.min_ratio,
        s.min_ratio_period,
        s.mean_log_misfit,
        if s.common_scale > 1.0 {
            format!(", every factor raised ×{:.3} for the 90% rule", s.common_scale)
        } else {
            String::new()
        }
    );
    println!("  {:>4}  {:>10}  {:<14} {:>8}  {:>8}", "rank", "seed", "record", "scale", "misfit");
    for (k, r) in o.rows.iter().enumerate() {
        println!("  {:>4}  {:>10}  {:<14} {:>8.3}  {:>8.4}", k + 1, r.seed, r.record, r.scale_factor, r.misfit);
    }
    println!("  scaled records (AT2, SAC) and the set table → {}", folder.set_dir().display());
}
