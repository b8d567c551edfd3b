//! Ensembles: many seeds in parallel, each analysed and written as it finishes; resumable.
//!
//! Output folder layout (`<out>` is `reports/<pipeline name>` by default):
//! ```text
//! <out>/manifest.toml            pipeline name and hash of the results in this folder
//! <out>/pipeline.toml            copy of the pipeline file
//! <out>/tables/<table>/seed-<seed>.parquet   one part per seed: runs, series, control, events,
//!                                            sub_events, similarity
//! <out>/tables/<table>.parquet   runs, events, sub_events, similarity gathered over all seeds
//! <out>/tables/summary.parquet   statistics across seeds
//! ```
//! Seeds run in parallel on a rayon pool, each owning its own solver state; finished seeds go
//! through a bounded channel to the writing thread, so only a few series are in memory at once
//! (and polars is never called from inside the rayon pool). Every part is written atomically
//! (temporary file, then rename) and a seed's `runs` part is written last: a seed counts as
//! finished when that part exists. A rerun skips finished seeds and runs the rest; a folder that
//! holds results of a pipeline with another hash is refused (or discarded with `fresh`).

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use polars::prelude::*;
use rayon::prelude::*;
use stickslip_solver::{BATCH, Model, RunOptions, RunOutput, SolverError, run_batched};

use crate::catalogue::{
    RunFacts, RunRow, acceleration_channels, events_frame, runs_frame, similarity_frame, sub_events_frame,
};
use crate::error::AnalysisError;
use crate::events::{Catalogue, detect};
use crate::pipeline::Pipeline;
use crate::spectra;
use crate::spectra::records::at2_text;
use crate::spectra::stage::{PlanCache, SeedSpectra, at2_name};
use crate::spectra::tables::{
    accelerograms_frame, attenuation_fit_frame, attenuation_frame, fourier_frame, intensity_frame, psa_stats_frame,
    spectra_frame,
};
use crate::summary::summary_frame;
use crate::tables::{control_frame, scan_glob, series_frame, write_parquet_atomic, write_text_atomic};

/// Per-seed tables, in the order they are written (`runs` last marks the seed finished).
pub const SEED_TABLES: [&str; 11] = [
    "series",
    "control",
    "events",
    "sub_events",
    "similarity",
    "spectra",
    "fourier",
    "intensity",
    "accelerograms",
    "attenuation",
    "runs",
];
/// Tables gathered over all seeds into one file each.
pub const GATHERED_TABLES: [&str; 6] = ["runs", "events", "sub_events", "similarity", "intensity", "attenuation"];

/// How to run an ensemble.
#[derive(Clone, Debug)]
pub struct EnsembleOptions {
    /// Output folder.
    pub out: PathBuf,
    /// Worker threads (0: one per core).
    pub threads: usize,
    /// Seeds to run (usually the pipeline's).
    pub seeds: Vec<u64>,
    /// Discard results of another pipeline found in `out` instead of refusing.
    pub fresh: bool,
    /// Gather the tables, the statistics and the report at the end (false for one shard of a
    /// larger ensemble: `merge` does it once every shard is in).
    pub finish: bool,
}

/// The `k`-th (1-based) of `n` disjoint, contiguous slices of `seeds`, in their order: seeds
/// `⌊(k−1)·len/n⌋ … ⌊k·len/n⌋ − 1`. Every seed is in exactly one slice whatever `n`.
pub fn shard(seeds: &[u64], k: usize, n: usize) -> Vec<u64> {
    assert!(n >= 1 && (1..=n).contains(&k), "shard {k}/{n}");
    let len = seeds.len();
    seeds[(k - 1) * len / n..k * len / n].to_vec()
}

/// What an ensemble did.
#[derive(Clone, Debug, PartialEq)]
pub struct EnsembleReport {
    /// Seeds run now.
    pub ran: usize,
    /// Seeds found finished and skipped.
    pub skipped: usize,
    /// Seeds that failed, with their message (run now or before).
    pub failed: Vec<(u64, String)>,
    /// Wall time (s).
    pub wall_time_s: f64,
    /// Output folder.
    pub out: PathBuf,
    /// The report, if the pipeline asked for one.
    pub report: Option<crate::report::ReportSummary>,
    /// Wall time of the report stage (s).
    pub report_time_s: f64,
}

/// Path of a seed's part of `table`.
pub fn part_path(out: &Path, table: &str, seed: u64) -> PathBuf {
    out.join("tables").join(table).join(format!("seed-{seed:010}.parquet"))
}

/// Glob of the parts of `table`.
pub fn part_glob(out: &Path, table: &str) -> PathBuf {
    out.join("tables").join(table).join("*.parquet")
}

/// Whether `seed` has finished in `out`.
pub fn is_finished(out: &Path, seed: u64) -> bool {
    part_path(out, "runs", seed).exists()
}

/// Reads the hash recorded in `<out>/manifest.toml`, if any.
pub fn manifest_hash(out: &Path) -> Result<Option<String>, AnalysisError> {
    let path = out.join("manifest.toml");
    if !path.exists() {
        return Ok(None);
    }
    let text = std::fs::read_to_string(&path).map_err(|e| AnalysisError::io(&path, e))?;
    let table: toml::Table =
        toml::from_str(&text).map_err(|e| AnalysisError::Corrupt { path: path.clone(), what: e.to_string() })?;
    Ok(table.get("pipeline_hash").and_then(|v| v.as_str()).map(str::to_string))
}

/// Claims `out` for `pipeline`: refuses (or, with `fresh`, clears) results of another pipeline,
/// then writes the manifest and a copy of the pipeline file.
pub fn prepare_output(out: &Path, pipeline: &Pipeline, fresh: bool) -> Result<(), AnalysisError> {
    if let Some(found) = manifest_hash(out)?
        && found != pipeline.hash
    {
        if !fresh {
            return Err(AnalysisError::OtherPipeline {
                out: out.to_path_buf(),
                found,
                expected: pipeline.hash.clone(),
            });
        }
        let tables = out.join("tables");
        if tables.exists() {
            std::fs::remove_dir_all(&tables).map_err(|e| AnalysisError::io(&tables, e))?;
        }
    }
    let manifest = format!(
        "# Written by stickslip {}: every table in this folder comes from this pipeline.\nname = {:?}\npipeline_hash = {:?}\n",
        env!("CARGO_PKG_VERSION"),
        pipeline.name,
        pipeline.hash
    );
    write_text_atomic(&out.join("manifest.toml"), &manifest)?;
    if let Some(src) = &pipeline.source {
        let text = std::fs::read_to_string(src).map_err(|e| AnalysisError::io(src, e))?;
        write_text_atomic(&out.join("pipeline.toml"), &text)?;
    }
    Ok(())
}

/// One seed, simulated and analysed.
struct SeedResult {
    seed: u64,
    outcome: Result<(RunOutput, Catalogue, Option<SeedSpectra>), SolverError>,
    wall_time_s: f64,
}

/// Simulates a batch of seeds side by side (see [`run_batched`]) and analyses each; a seed's
/// wall time is its share of the batch's.
fn simulate(
    model: &Model,
    pipeline: &Pipeline,
    seeds: &[u64],
    options: RunOptions,
    cancel: &AtomicBool,
    plans: &PlanCache,
) -> Vec<SeedResult> {
    let start = Instant::now();
    let mut check = |_: f64| {
        if cancel.load(Ordering::Relaxed) {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    };
    let runs = run_batched(model, seeds, options, &mut check);
    let share = start.elapsed().as_secs_f64() / seeds.len() as f64;
    seeds
        .iter()
        .zip(runs)
        .map(|(&seed, run)| {
            let start = Instant::now();
            let outcome = run.and_then(|out| {
                let cat = detect(&out.records, model.contact().len(), model.lattice().contact_area(), &pipeline.events)
                    .map_err(|e| SolverError::Numerical(e.to_string()))?;
                let spectra = pipeline
                    .spectra
                    .as_ref()
                    .map(|p| spectra::stage::compute(&out.records, &cat, model, p, pipeline.events.smoothing_s, plans));
                Ok((out, cat, spectra))
            });
            SeedResult { seed, outcome, wall_time_s: share + start.elapsed().as_secs_f64() }
        })
        .collect()
}

fn write_seed(out: &Path, pipeline: &Pipeline, model: &Model, r: SeedResult) -> Result<Option<String>, AnalysisError> {
    let channels = acceleration_channels(model);
    let (row, failure) = match &r.outcome {
        Ok((run, cat, spectra)) => {
            let mut frames = vec![
                ("series", series_frame(r.seed, &run.records)?),
                ("control", control_frame(r.seed, &run.records)?),
                ("events", events_frame(r.seed, cat, &channels)?),
                ("sub_events", sub_events_frame(r.seed, cat, &channels)?),
                ("similarity", similarity_frame(r.seed, cat, pipeline)?),
            ];
            if let (Some(s), Some(params)) = (spectra, &pipeline.spectra) {
                let lambda = pipeline.similarity.prototype_length_m / model.lattice().extent()[0];
                frames.push(("spectra", spectra_frame(r.seed, s, &params.periods(), &params.dampings, lambda)?));
                frames.push(("fourier", fourier_frame(r.seed, s)?));
                frames.push(("intensity", intensity_frame(r.seed, s, lambda)?));
                frames.push(("accelerograms", accelerograms_frame(r.seed, s, lambda)?));
                if params.attenuation {
                    frames.push(("attenuation", attenuation_frame(r.seed, s, model.lattice())?));
                }
                if params.at2 {
                    write_at2(out, pipeline, r.seed, s, lambda)?;
                }
            }
            for (table, df) in &mut frames {
                write_parquet_atomic(df, &part_path(out, table, r.seed))?;
            }
            (RunRow { seed: r.seed, outcome: Ok(RunFacts::of(run, cat)), wall_time_s: r.wall_time_s }, None)
        }
        Err(e) => {
            let msg = e.to_string();
            (RunRow { seed: r.seed, outcome: Err(msg.clone()), wall_time_s: r.wall_time_s }, Some(msg))
        }
    };
    write_parquet_atomic(&mut runs_frame(&[row], &pipeline.hash)?, &part_path(out, "runs", r.seed))?;
    Ok(failure)
}

/// Runs the seeds of `options` that have not finished in `options.out`, then gathers the tables
/// and the statistics. `on_seed(done, total)` is called after each seed is written; setting
/// `cancel` stops the running seeds (finished ones are kept) and returns
/// [`AnalysisError::Interrupted`].
pub fn run_ensemble(
    pipeline: &Pipeline,
    options: &EnsembleOptions,
    on_seed: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Result<EnsembleReport, AnalysisError> {
    let start = Instant::now();
    let out = &options.out;
    prepare_output(out, pipeline, options.fresh)?;
    let pending: Vec<u64> = options.seeds.iter().copied().filter(|&s| !is_finished(out, s)).collect();
    remove_stale_temporaries(out, &pending)?;
    let skipped = options.seeds.len() - pending.len();
    let total = options.seeds.len();
    on_seed(skipped, total);
    let model = Model::new(pipeline.scene.clone());
    let plans = PlanCache::default();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
        .map_err(|e| AnalysisError::Setup(format!("thread pool: {e}")))?;
    let (tx, rx) = mpsc::sync_channel::<SeedResult>(2 * pool.current_num_threads());
    let mut failed = Vec::new();
    let mut done = skipped;
    let mut ran = 0;
    let mut write_error = None;
    std::thread::scope(|scope| {
        let model = &model;
        let pending = &pending;
        let plans = &plans;
        // Batches of seeds share each pass over the lattice (lanes); a scene too large for
        // that, with fewer seeds than threads, splits each step over the threads instead.
        let threads = pool.current_num_threads();
        let per_thread = pending.len().div_ceil(threads.max(1));
        let batch = if per_thread >= BATCH {
            BATCH
        } else if per_thread >= 4 {
            4
        } else {
            1
        };
        let options = RunOptions {
            parallel_step: pending.len() < threads && model.layout().segments().len() > 1,
            ..RunOptions::default()
        };
        scope.spawn(move || {
            pool.install(|| {
                pending.par_chunks(batch).for_each_with(tx, |tx, chunk| {
                    if cancel.load(Ordering::Relaxed) {
                        return;
                    }
                    for r in simulate(model, pipeline, chunk, options, cancel, plans) {
                        let _ = tx.send(r);
                    }
                });
            });
        });
        for r in rx {
            if write_error.is_some() || matches!(r.outcome, Err(SolverError::Cancelled)) {
                continue;
            }
            let seed = r.seed;
            match write_seed(out, pipeline, model, r) {
                Ok(failure) => {
                    if let Some(msg) = failure {
                        failed.push((seed, msg));
                    }
                    done += 1;
                    ran += 1;
                    on_seed(done, total);
                }
                Err(e) => {
                    cancel.store(true, Ordering::Relaxed);
                    write_error = Some(e);
                }
            }
        }
    });
    if let Some(e) = write_error {
        return Err(e);
    }
    if cancel.load(Ordering::Relaxed) {
        return Err(AnalysisError::Interrupted { done, total, out: out.clone() });
    }
    if !options.finish {
        return Ok(EnsembleReport {
            ran,
            skipped,
            failed,
            wall_time_s: start.elapsed().as_secs_f64(),
            out: out.clone(),
            report: None,
            report_time_s: 0.0,
        });
    }
    gather(out, &options.seeds)?;
    let runs = scan_glob(&out.join("tables").join("runs.parquet"))?;
    if let Some(runs) = runs {
        failed = failed_seeds(&runs)?;
    }
    let report_start = Instant::now();
    let report = if pipeline.report.enabled {
        Some(crate::report::write_report(out, pipeline, &pipeline.report)?)
    } else {
        None
    };
    Ok(EnsembleReport {
        ran,
        skipped,
        failed,
        wall_time_s: start.elapsed().as_secs_f64(),
        out: out.clone(),
        report,
        report_time_s: report_start.elapsed().as_secs_f64(),
    })
}

fn failed_seeds(runs: &DataFrame) -> Result<Vec<(u64, String)>, AnalysisError> {
    let t = |e| AnalysisError::table("runs", e);
    let seeds = runs.column("seed").map_err(t)?.u64().map_err(t)?.clone();
    let status = runs.column("status").map_err(t)?.str().map_err(t)?.clone();
    let msg = runs.column("message").map_err(t)?.str().map_err(t)?.clone();
    Ok((0..runs.height())
        .filter(|&i| status.get(i) == Some("failed"))
        .map(|i| (seeds.get(i).unwrap_or(0), msg.get(i).unwrap_or("").to_string()))
        .collect())
}

/// Gathers the per-seed parts of the small tables (restricted to `seeds`, sorted by seed) into
/// one file each, and writes the statistics across seeds.
pub fn gather(out: &Path, seeds: &[u64]) -> Result<(), AnalysisError> {
    let keep: std::collections::HashSet<u64> = seeds.iter().copied().collect();
    let mut gathered = Vec::new();
    for table in GATHERED_TABLES {
        let glob = part_glob(out, table);
        let Some(df) = scan_glob(&glob)? else {
            continue;
        };
        let sort_by: Vec<&str> = match table {
            "runs" => vec!["seed"],
            "sub_events" => vec!["seed", "event", "sub_event"],
            "intensity" => vec!["seed", "node", "component", "scale"],
            "attenuation" => vec!["seed", "event", "node"],
            _ => vec!["seed", "event"],
        };
        let t = |e| AnalysisError::table(table, e);
        let mask: BooleanChunked = df
            .column("seed")
            .map_err(t)?
            .u64()
            .map_err(t)?
            .iter()
            .map(|s| s.is_some_and(|s| keep.contains(&s)))
            .collect();
        let mut df = df.filter(&mask).map_err(t)?.sort(sort_by, SortMultipleOptions::default()).map_err(t)?;
        write_parquet_atomic(&mut df, &out.join("tables").join(format!("{table}.parquet")))?;
        gathered.push((table, df));
    }
    if let Some(spectra) = scan_glob(&part_glob(out, "spectra"))? {
        let keep_rows: BooleanChunked = spectra
            .column("seed")
            .and_then(|c| c.u64().cloned())
            .map_err(|e| AnalysisError::table("spectra", e))?
            .iter()
            .map(|s| s.is_some_and(|s| keep.contains(&s)))
            .collect();
        let spectra = spectra.filter(&keep_rows).map_err(|e| AnalysisError::table("spectra", e))?;
        write_parquet_atomic(&mut psa_stats_frame(&spectra)?, &out.join("tables").join("psa_stats.parquet"))?;
    }
    if let Some((_, att)) = gathered.iter().find(|(t, _)| *t == "attenuation") {
        write_parquet_atomic(&mut attenuation_fit_frame(att)?, &out.join("tables").join("attenuation_fit.parquet"))?;
    }
    let get = |name: &str| gathered.iter().find(|(t, _)| *t == name).map(|(_, d)| d);
    if let (Some(runs), Some(events), Some(similarity)) = (get("runs"), get("events"), get("similarity")) {
        let mut summary = summary_frame(runs, events, similarity)?;
        write_parquet_atomic(&mut summary, &out.join("tables").join("summary.parquet"))?;
    }
    Ok(())
}

/// Removes the hidden temporary files a killed writer left for `seeds` (only those: another
/// process may be writing other seeds into the same folder).
fn remove_stale_temporaries(out: &Path, seeds: &[u64]) -> Result<(), AnalysisError> {
    let prefixes: std::collections::HashSet<String> = seeds.iter().map(|s| format!(".seed-{s:010}.parquet.")).collect();
    for table in SEED_TABLES {
        let dir = out.join("tables").join(table);
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for file in entries.flatten() {
            let name = file.file_name().to_string_lossy().into_owned();
            if name.ends_with(".tmp") && name.rfind(".parquet.").is_some_and(|i| prefixes.contains(&name[..i + 9])) {
                std::fs::remove_file(file.path()).map_err(|e| AnalysisError::io(&file.path(), e))?;
            }
        }
    }
    // AT2 files: `.<pipeline>_seed<seed>_….AT2.<pid>.tmp`.
    if let Ok(entries) = std::fs::read_dir(out.join("at2")) {
        let seeds: std::collections::HashSet<u64> = seeds.iter().copied().collect();
        for file in entries.flatten() {
            let name = file.file_name().to_string_lossy().into_owned();
            let seed = name.split("_seed").nth(1).and_then(|r| r.split('_').next()).and_then(|s| s.parse().ok());
            if name.starts_with('.') && name.ends_with(".tmp") && seed.is_some_and(|s| seeds.contains(&s)) {
                std::fs::remove_file(file.path()).map_err(|e| AnalysisError::io(&file.path(), e))?;
            }
        }
    }
    Ok(())
}

/// Writes the AT2 files of one seed (model and prototype scale) under `<out>/at2/`, then an
/// empty marker part so a resumed run knows they are complete.
fn write_at2(out: &Path, pipeline: &Pipeline, seed: u64, s: &SeedSpectra, lambda: f64) -> Result<(), AnalysisError> {
    let dir = out.join("at2");
    for c in &s.channels {
        for (scale, l) in [("model", 1.0), ("prototype", lambda)] {
            let name = at2_name(&pipeline.name, seed, c.channel.node, c.channel.component, scale);
            let p = c.position;
            let description = format!(
                "stickslip pipeline {}, seed {seed}, node {} at ({}, {}, {}) m, component {}, {scale} scale \
                 (lambda = {l}: time x{l}, acceleration /{l}); acceleration in g",
                pipeline.name,
                c.channel.node.ldem(),
                p[0],
                p[1],
                p[2],
                c.channel.component.name()
            );
            let accel: Vec<f64> = c.accel.iter().map(|a| a / l).collect();
            write_text_atomic(&dir.join(name), &at2_text(&accel, c.dt * l, &description))?;
        }
    }
    Ok(())
}
