//! `stickslip select`: a set of an ensemble's records matched to a design spectrum.

use std::path::PathBuf;

use anyhow::{Context, Result};
use stickslip_config::Pipeline;
use stickslip_config::set::read_set_file;
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

/// Where a set chosen with `--set FILE` keeps its `[set]` section, so the report draws the set
/// against the target it was matched to (a CSV target is copied beside it).
pub const SET_FILE: &str = "set.toml";

/// `stickslip select`.
pub fn run(a: Args) -> Result<()> {
    let folder = Folder::new(&a.folder);
    folder.require_output()?;
    let pipeline = Pipeline::load(&folder.pipeline_copy())
        .with_context(|| format!("reading the pipeline of {}", a.folder.display()))?;
    let settings = match &a.set {
        Some(path) => read_set_file(path, pipeline.set_pool())?,
        None => pipeline.set.clone().with_context(|| {
            format!("the pipeline of {} has no [set] section: give one with --set FILE", a.folder.display())
        })?,
    };
    let outcome = select_set(&folder, &pipeline, &settings)?;
    print_set(&outcome, &settings.target_name, &folder);
    if let Some(path) = &a.set {
        keep_set_section(path, &folder)?;
    }
    // The page and its record-set figure show the set just chosen, not the one before.
    if pipeline.report.enabled {
        let r = stickslip_report::write_report(&a.folder, &pipeline)?;
        outln!("report: rewritten with the new set → {}", r.index.display());
    }
    Ok(())
}

/// Writes the `[set]` section of `path` to `<folder>/set/set.toml` (with a CSV target copied
/// beside it), for the report.
fn keep_set_section(path: &std::path::Path, folder: &Folder) -> Result<()> {
    let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let doc: toml::Table = toml::from_str(&text).with_context(|| format!("{}", path.display()))?;
    let mut set = doc.get("set").and_then(|v| v.as_table()).cloned().context("no [set] section")?;
    let dir = folder.set_dir();
    if let Some(csv) = set.get("target_csv").and_then(|v| v.as_str()).filter(|c| !c.is_empty()) {
        let from = path.parent().unwrap_or(std::path::Path::new(".")).join(csv);
        let bytes = std::fs::read(&from).with_context(|| format!("reading {}", from.display()))?;
        stickslip_store::io::write_bytes_atomic(&dir.join("target.csv"), &bytes)?;
        set.insert("target_csv".into(), toml::Value::String("target.csv".into()));
    }
    let mut out = toml::Table::new();
    out.insert("set".into(), toml::Value::Table(set));
    let text = format!(
        "# The [set] of `stickslip select --set {}`: what the set in this folder was matched to.\n{}",
        path.display(),
        toml::to_string(&out)?
    );
    stickslip_store::io::write_text_atomic(&dir.join(SET_FILE), &text)?;
    Ok(())
}

/// Prints a chosen set.
pub fn print_set(o: &SetOutcome, target: &str, folder: &Folder) {
    let s = &o.selection;
    outln!(
        "set: {} of {} records ({} eligible), periods {:.3} … {:.3} s, matched to {target}",
        s.records.len(),
        o.candidates,
        s.eligible,
        s.range.0,
        s.range.1
    );
    outln!(
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
    if let Some(pool) = &o.pool {
        outln!("  from the {pool}");
    }
    if o.rows.iter().any(|r| r.scenario.is_some()) {
        let width = o.rows.iter().map(|r| r.record.chars().count()).max().unwrap_or(6).max(7);
        outln!(
            "  {:>4}  {:>10}  {:<width$}  {:>5}  {:>9}  {:>8}  {:>8}",
            "rank",
            "seed",
            "station",
            "Mw",
            "R_rup km",
            "scale",
            "misfit"
        );
        for (k, r) in o.rows.iter().enumerate() {
            let m = r.scenario.expect("every row of a scenario's set");
            outln!(
                "  {:>4}  {:>10}  {:<width$}  {:>5.2}  {:>9.1}  {:>8.3}  {:>8.4}",
                k + 1,
                r.seed,
                r.record,
                m.mw,
                m.r_rup_km,
                r.scale_factor,
                r.misfit
            );
        }
    } else {
        outln!("  {:>4}  {:>10}  {:<14} {:>8}  {:>8}", "rank", "seed", "record", "scale", "misfit");
        for (k, r) in o.rows.iter().enumerate() {
            outln!("  {:>4}  {:>10}  {:<14} {:>8.3}  {:>8.4}", k + 1, r.seed, r.record, r.scale_factor, r.misfit);
        }
    }
    outln!(
        "  the set table → {}; its scaled records (AT2, SAC) → {}",
        folder.gathered(&stickslip_store::schema::SET).display(),
        folder.set_dir().display()
    );
}
