//! `stickslip pipeline`: every seed of one or more pipelines, their tables and report.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use stickslip_config::Pipeline;
use stickslip_config::set::SetCapacity;
use stickslip_ensemble::checkpoints::Checkpoints;
use stickslip_ensemble::digest::RunDigest;
use stickslip_ensemble::precision::run_to_precision;
use stickslip_ensemble::set::SetOutcome;
use stickslip_ensemble::{EnsembleOptions, EnsembleReport, run_ensemble, shard};
use stickslip_store::Folder;

use crate::progress;
use crate::text::count;
use stickslip_config::seeds::{parse_seeds, parse_shard};

/// Arguments of `stickslip pipeline`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Pipeline files (TOML), e.g. pipelines/paper.toml.
    #[arg(required = true)]
    pub pipelines: Vec<PathBuf>,
    /// Output folder [default: reports/<pipeline name>]; only with one pipeline.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Seeds to run instead of the pipeline's, e.g. "1,5,10-20".
    #[arg(long)]
    pub seeds: Option<String>,
    /// Worker threads [default: one per core].
    #[arg(long, allow_negative_numbers = true, value_parser = crate::commands::pipeline::parse_threads)]
    pub threads: Option<usize>,
    /// Discard results of a different pipeline found in the output folder.
    #[arg(long)]
    pub fresh: bool,
    /// Run only the K-th of N disjoint slices of the seeds (K from 1), e.g. "3/8", for a job
    /// array; the tables and report are gathered by `stickslip merge`.
    #[arg(long, value_parser = parse_shard)]
    pub shard: Option<(usize, usize)>,
    /// No progress bar.
    #[arg(long, short)]
    pub quiet: bool,
    /// Accept runs of more than 10¹¹ bar-updates per seed (refused otherwise: `stickslip check`
    /// prints a run's length and time).
    #[arg(long)]
    pub allow_long: bool,
    /// Keep each running seed's checkpoint in <out>/checkpoints/, written every MINUTES of wall
    /// clock and when the run is stopped (Ctrl-C, SIGTERM): the same command run again resumes
    /// each seed where it stopped, with the numbers of a run never stopped. Each seed then runs
    /// alone, not in batches of four side by side.
    #[arg(long, value_name = "MINUTES", allow_negative_numbers = true, value_parser = parse_minutes)]
    pub checkpoint_every: Option<f64>,
}

/// A positive number of minutes.
fn parse_minutes(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(m) if m.is_finite() && m > 0.0 => Ok(m),
        _ => Err(format!("`{s}` is not a number of minutes above 0 (e.g. 30)")),
    }
}

/// Stops the running seeds at the first Ctrl-C or SIGTERM (finished ones are kept, running ones
/// that keep checkpoints write one), at once at a second that comes a second or more later (a
/// cluster may send its SIGTERM twice at once: both stop the seeds as they should).
pub fn cancel_on_ctrl_c() -> Result<Arc<AtomicBool>> {
    let cancel = Arc::new(AtomicBool::new(false));
    let flag = cancel.clone();
    let first = std::sync::OnceLock::new();
    ctrlc::set_handler(move || {
        let at = *first.get_or_init(Instant::now);
        if flag.swap(true, Ordering::SeqCst) {
            if at.elapsed().as_secs_f64() >= 1.0 {
                std::process::exit(130);
            }
            return;
        }
        errln!(
            "\ninterrupt: finishing the seeds being written, and writing the running seeds' checkpoints if they keep \
             them (Ctrl-C again, a second later, to stop at once)"
        );
    })
    .context("installing the Ctrl-C handler")?;
    Ok(cancel)
}

/// Runs an ensemble of `pipeline` with a progress bar (hidden with `quiet`).
pub fn ensemble(
    pipeline: &Pipeline,
    options: &EnsembleOptions,
    quiet: bool,
    cancel: &AtomicBool,
) -> Result<EnsembleReport> {
    let pb =
        progress::bar(quiet, options.seeds.len() as u64, "{msg} [{bar:40}] {pos}/{len} seeds ({elapsed}, ETA {eta})");
    pb.set_message(pipeline.name.clone());
    let report = run_ensemble(pipeline, options, &|done, _| pb.set_position(done as u64), cancel);
    pb.finish_and_clear();
    Ok(report?)
}

/// Prints the set of `[set]`, or why none could be chosen.
pub fn print_set_result(pipeline: &Pipeline, set: Option<&Result<SetOutcome, String>>, out: &Path) {
    match (set, &pipeline.set) {
        (Some(Ok(o)), Some(s)) => crate::commands::select::print_set(o, &s.target_name, &Folder::new(out)),
        (Some(Err(e)), _) => outln!("set: none chosen: {e}"),
        _ => {}
    }
}

/// Prints the statistics and writes the report of a finished (or merged) folder.
pub fn finish(pipeline: &Pipeline, out: &Path) -> Result<()> {
    let folder = Folder::new(out);
    outln!("{}", RunDigest::of(pipeline, &folder)?);
    if pipeline.scene.is_fault() {
        // A fault's ruptures (said above, from its own slip) against the ground-motion models:
        // how its stations shook.
        let opts = stickslip_ensemble::gmm::GmmOptions::default();
        match stickslip_ensemble::gmm::compare(&folder, &opts) {
            Ok(Some(c)) => crate::commands::gmm::print(&c, &opts),
            Ok(None) => {}
            Err(stickslip_ensemble::EnsembleError::Store(e)) => return Err(e.into()),
            Err(e) => outln!("no comparison with the ground-motion models: {e}"),
        }
    }
    if pipeline.report.enabled {
        let start = Instant::now();
        let r = stickslip_report::write_report(out, pipeline)?;
        outln!(
            "report: {} in {:.1} s → {}{}",
            count(r.figures.len(), "figure", "figures"),
            start.elapsed().as_secs_f64(),
            r.index.display(),
            if r.skipped.is_empty() {
                String::new()
            } else {
                format!(" ({} skipped for lack of data)", r.skipped.len())
            }
        );
    }
    Ok(())
}

/// Refuses, before anything runs, a set of a scenario's stations that `seeds` seeds cannot fill:
/// each seed is one rupture giving at most `set.max_per` of the surface stations that can lie in
/// the distance bin ([`SetCapacity`]).
pub fn check_set_capacity(pipeline: &Pipeline, seeds: usize) -> Result<()> {
    let Some(set) = pipeline.set.as_ref().filter(|_| pipeline.sets_from_stations()) else { return Ok(()) };
    let c = SetCapacity::of(set, &pipeline.scene, seeds);
    let count = set.options.count;
    if c.records < count {
        let within = set.distance_km.map_or(String::new(), |(_, hi)| {
            format!(" that can lie within set.distance_max_km = {hi} km (R_rup is at least a station's distance from the fault plane)")
        });
        let need = if c.per_seed == 0 {
            "no number of seeds".to_string()
        } else {
            format!("at least {} seeds", count.div_ceil(c.per_seed))
        };
        bail!(
            "{}: set.count = {count} is not allowed with {seeds} seed{}: at most {} records, {} per seed (one rupture: \
             set.max_per = {}, of the {} of {} surface stations{within}), whatever the magnitudes; allowed: set.count \
             ≤ {} for these seeds — or run {need} (--seeds, [seeds]), or widen the distance bin",
            pipeline.name,
            if seeds == 1 { "" } else { "s" },
            c.records,
            c.per_seed,
            set.options.per_group,
            c.stations,
            c.surface,
            c.records
        );
    }
    Ok(())
}

/// Parses `--threads N`: a whole number of threads ≥ 1 (a negative number is read as a value, so
/// that it is refused with the range rather than taken by clap for an unknown flag).
pub fn parse_threads(s: &str) -> Result<usize, String> {
    match s.trim().parse::<i128>() {
        Ok(v) if v >= 1 => usize::try_from(v).map_err(|_| format!("{v} threads: at most {}", usize::MAX)),
        Ok(v) => Err(format!("{v} threads: give a whole number ≥ 1 (or leave --threads out for one per core)")),
        Err(_) => Err(format!("{s:?} is not a number of threads: give a whole number ≥ 1")),
    }
}

/// The pipelines of `a`, every file validated before any runs, with the seeds of `--seeds`;
/// refuses options that do not go together, and prints each pipeline's warnings.
fn load(a: &Args) -> Result<(Vec<Pipeline>, Option<Vec<u64>>)> {
    anyhow::ensure!(a.out.is_none() || a.pipelines.len() == 1, "--out needs exactly one pipeline");
    anyhow::ensure!(
        !(a.fresh && a.shard.is_some()),
        "--fresh with --shard would discard the other shards' results: clear the folder by hand"
    );
    anyhow::ensure!(a.threads != Some(0), "--threads 0: give at least 1 (or leave it out for one per core)");
    let given = a.seeds.as_deref().map(parse_seeds).transpose().map_err(anyhow::Error::msg)?;
    // Validate every file before running any.
    let pipelines = a.pipelines.iter().map(|p| Pipeline::load(p)).collect::<Result<Vec<_>, _>>()?;
    for p in &pipelines {
        anyhow::ensure!(
            p.target.is_none() || (a.seeds.is_none() && a.shard.is_none()),
            "{}: a pipeline with [seeds.target] chooses its own seeds in batches: run it without --seeds and --shard",
            p.name
        );
    }
    for p in &pipelines {
        print_warnings(p);
        if let Some(given) = &given {
            let drawn: Vec<String> =
                p.report.seeds.iter().filter(|s| !given.contains(*s)).map(|s| s.to_string()).collect();
            if !drawn.is_empty() && p.report.enabled {
                errln!(
                    "warning: {}: report.seeds {} are not among --seeds: the report draws the first seeds that ran \
                     instead",
                    p.name,
                    drawn.join(", ")
                );
            }
        }
    }
    Ok((pipelines, given))
}

/// The seeds each of `pipelines` runs (the pipeline's, or `given`, sliced by `--shard`), once
/// the memory and run length of every pipeline are checked before any is built.
fn seeds_to_run(a: &Args, pipelines: &[Pipeline], given: Option<&[u64]>) -> Result<Vec<Vec<u64>>> {
    let threads = a.threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let mut runs = Vec::new();
    for pipeline in pipelines {
        if let Some(spec) = &pipeline.cycles {
            // One run of the fault alone: its stiffness is nodes² numbers, the block is never built;
            // what it holds is checked against the memory available.
            if a.shard.is_some() || stickslip_ensemble::split::installed().is_some() {
                bail!(
                    "{}: a [cycles] pipeline runs on one process (its seeds one after another); leave out --shard and \
                     mpirun",
                    pipeline.name
                );
            }
            stickslip_ensemble::budget::check_cycles(&pipeline.scene, spec, &pipeline.name)?;
            runs.push(Vec::new());
            continue;
        }
        let mut seeds = given.map(<[u64]>::to_vec).unwrap_or_else(|| pipeline.seeds.clone());
        if let Some((k, n)) = a.shard {
            seeds = shard(&seeds, k, n);
        }
        // A shard's seeds are part of the set's; the merge chooses it from them all.
        if a.shard.is_none() {
            check_set_capacity(pipeline, seeds.len())?;
        }
        let what = format!("{}: {} seed{}", pipeline.name, seeds.len(), if seeds.len() == 1 { "" } else { "s" });
        match stickslip_ensemble::split::installed() {
            // Each seed split over the ranks: rank 0's part, not the whole scene, on this node.
            Some(split) => stickslip_ensemble::budget::check_before_build_split(
                &pipeline.scene,
                split.ranks(),
                split.local_ranks(),
                a.allow_long,
                &what,
            )?,
            None => stickslip_ensemble::budget::check_before_build(
                &pipeline.scene,
                seeds.len(),
                threads,
                a.allow_long,
                &what,
            )?,
        }
        runs.push(seeds);
    }
    Ok(runs)
}

/// `stickslip pipeline`.
pub fn run(a: Args) -> Result<()> {
    let (pipelines, given) = load(&a)?;
    if let Some(split) = stickslip_ensemble::split::installed() {
        let ranks = split.ranks();
        for p in pipelines.iter().filter(|p| p.cycles.is_none()) {
            if let Some(why) = stickslip_solver::run::split_refusal(&p.scene, ranks) {
                bail!("{}: its seeds cannot be split over {ranks} MPI ranks: {why}", p.name);
            }
        }
        outln!(
            "each seed split over {ranks} MPI ranks (slabs of module layers along z; docs/guide/ensembles.md, One scene over MPI ranks)"
        );
    }
    if a.checkpoint_every.is_some()
        && let Some(p) = pipelines.iter().find(|p| p.target.is_some())
    {
        bail!(
            "--checkpoint-every: {} runs to a precision target ([target]), whose batches of seeds keep no checkpoints \
             yet; leave out --checkpoint-every (its finished seeds are kept all the same)",
            p.name
        );
    }
    if a.checkpoint_every.is_some()
        && let Some(p) = pipelines.iter().find(|p| p.scene.skip_ahead.enabled)
    {
        bail!(
            "--checkpoint-every: {} has skip_ahead.enabled = true, whose state a checkpoint does not hold; set it to \
             false or leave out --checkpoint-every",
            p.name
        );
    }
    let runs = seeds_to_run(&a, &pipelines, given.as_deref())?;
    let cancel = cancel_on_ctrl_c()?;
    let mut unfinished = Vec::new();
    for (pipeline, seeds) in pipelines.iter().zip(runs) {
        let out = a.out.clone().unwrap_or_else(|| PathBuf::from("reports").join(&pipeline.name));
        if pipeline.cycles.is_some() {
            super::cycles::run(pipeline, &out, &cancel, given.as_deref())?;
            continue;
        }
        if let Some((k, n)) = a.shard {
            stickslip_ensemble::merge::mark_shard(&out, pipeline, k, n, &seeds)?;
        }
        if let Some(minutes) = a.checkpoint_every {
            let ranks = stickslip_ensemble::split::installed().map_or(1, |s| s.ranks());
            let c = Checkpoints { out: out.clone(), every_s: 60.0 * minutes, key: pipeline.hash.clone() };
            let folder = Folder::new(&out);
            let pending: Vec<u64> = seeds.iter().copied().filter(|&s| !folder.is_finished(s)).collect();
            for (seed, step) in c.found(&pending, ranks) {
                outln!("seed {seed} resumes from its checkpoint at step {step}");
            }
        }
        let options = EnsembleOptions {
            checkpoint_every_s: a.checkpoint_every.map(|m| 60.0 * m),
            out: out.clone(),
            threads: a.threads.unwrap_or(0),
            seeds,
            fresh: a.fresh,
            finish: a.shard.is_none(),
        };
        let (report, precision) = match &pipeline.target {
            Some(target) => {
                let pb = progress::bar(
                    a.quiet,
                    options.seeds.len() as u64,
                    "{msg} [{bar:40}] {pos}/{len} seeds of the budget ({elapsed})",
                );
                pb.set_message(pipeline.name.clone());
                let r = run_to_precision(pipeline, target, &options, &|done, _| pb.set_position(done as u64), &cancel);
                pb.finish_and_clear();
                let (report, outcome) = r?;
                (report, Some(outcome))
            }
            None => (ensemble(pipeline, &options, a.quiet, &cancel)?, None),
        };
        outln!(
            "{}{}: {} ({} run now, {} already done, {} failed) in {:.1} s → {}",
            pipeline.name,
            a.shard.map_or(String::new(), |(k, n)| format!(" shard {k}/{n}")),
            count(report.ran + report.skipped, "seed", "seeds"),
            report.ran,
            report.skipped,
            report.failed.len(),
            report.wall_time_s,
            report.out.join("tables").display()
        );
        for (seed, msg) in report.failed.iter().take(5) {
            outln!("  seed {seed} failed: {msg}");
        }
        for (seed, msg) in &report.checkpoint_notes {
            errln!("warning: seed {seed}'s checkpoint: {msg}");
        }
        if let Some(p) = &precision {
            outln!("{}", p.describe());
        }
        let total = report.ran + report.skipped;
        let nothing = total > 0 && report.failed.len() == total;
        if a.shard.is_some() {
            if nothing {
                unfinished.push(format!("{}: every seed of the shard failed ({total})", pipeline.name));
            } else {
                outln!("  merge the shards with: stickslip merge {}", out.display());
            }
            continue;
        }
        print_set_result(pipeline, report.set.as_ref(), &out);
        finish(pipeline, &out)?;
        if nothing {
            unfinished.push(format!("{}: every seed failed ({total}); nothing to analyse", pipeline.name));
        }
        if let Some(Err(e)) = &report.set {
            unfinished.push(format!("{}: the [set] asked for could not be chosen: {e}", pipeline.name));
        }
    }
    finished(unfinished)
}

/// `Ok` when every pipeline gave what it asked for, else an error listing what did not (the
/// tables and reports are written either way): exit status 1, so a dependent job does not run.
pub fn finished(unfinished: Vec<String>) -> Result<()> {
    if unfinished.is_empty() { Ok(()) } else { anyhow::bail!("{}", unfinished.join("\n  ")) }
}

/// Prints a pipeline's warnings (values accepted that could mislead) to stderr.
pub fn print_warnings(pipeline: &Pipeline) {
    for w in &pipeline.warnings {
        errln!("warning: {}: {w}", pipeline.name);
    }
}
