//! Ensembles: many seeds in parallel, each analysed and written as it finishes; resumable.
//!
//! Seeds run in parallel on a rayon pool, each batch of seeds owning its own solver state;
//! finished seeds go through a bounded channel to the writing thread, so only a few recordings
//! are in memory at once (and polars is never called from inside the rayon pool). Every part is
//! written atomically (temporary file, then rename) and a seed's `runs` part is written last: a
//! seed counts as finished when that part exists. A rerun skips finished seeds and runs the rest;
//! a folder that holds results of a pipeline with another hash is refused (or discarded with
//! `fresh`). The layout of the folder is [`stickslip_store::layout`]'s.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use rayon::prelude::*;
use stickslip_analysis::records::RecordFailure;
use stickslip_analysis::{AnalysisError, PlanCache, SeedAnalysis, analyse, thread_cpu_s};
use stickslip_config::Pipeline;
use stickslip_solver::{Model, RunOptions, SolverError, run_batched, run_seed_checkpointed};
use stickslip_store::files::Stamp;
use stickslip_store::io::write_text_atomic;
use stickslip_store::seed::{write_failed, write_seed};
use stickslip_store::{Folder, Manifest, SeedView};

use crate::checkpoints::Checkpoints;
use crate::error::EnsembleError;
use crate::gather::{Gathering, gather};
use crate::set::{SetOutcome, select_set};

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
    /// Gather the tables and the statistics at the end (false for one shard of a larger
    /// ensemble: `merge` does it once every shard is in).
    pub finish: bool,
    /// Write each seed's checkpoint every so many seconds of wall clock, and when stopped, in
    /// `out/checkpoints/`, and resume a seed from its checkpoint (docs/model.md §19); seeds then
    /// run one at a time, each step over the threads. `None`: no checkpoints (a stopped seed
    /// starts over).
    pub checkpoint_every_s: Option<f64>,
}

/// What an ensemble did.
#[derive(Clone, Debug)]
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
    /// Integrated steps per second of wall time, over the seeds run now (0 if none).
    pub steps_per_s: f64,
    /// The set of `[set]`, if asked: chosen, or why none could be.
    pub set: Option<Result<SetOutcome, String>>,
    /// Where the time of the seeds run now went, summed over the threads.
    pub profile: Profile,
    /// Checkpoints that could not be written or read (the seed ran on), with why.
    pub checkpoint_notes: Vec<(u64, String)>,
}

/// CPU seconds spent by stage, summed over the seeds run now and the threads that ran them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Profile {
    /// Stepping the solver (each seed's share of its batch).
    pub stepping_s: f64,
    /// Finding the events, their similarity scaling and fronts.
    pub events_s: f64,
    /// Cutting and processing the records, their intensity measures and Fourier spectra.
    pub records_s: f64,
    /// Response spectra of the records computed alone.
    pub spectra_s: f64,
    /// RotD of each horizontal pair (with the pair's own spectra, from the same passes).
    pub rotd_s: f64,
    /// The stochastic synthesis of broadband records and their joins.
    pub broadband_s: f64,
    /// The broadband records' processing and measures (RotD, intensity).
    pub broadband_motions_s: f64,
    /// Writing each seed's parts and files (the writing thread).
    pub writing_s: f64,
    /// Gathering the tables and the statistics across seeds at the end.
    pub gather_s: f64,
    /// Records whose spectra were computed alone.
    pub alone: usize,
    /// Horizontal pairs whose RotD (and the pair's spectra) were computed.
    pub pairs: usize,
}

/// Claims `out` for `pipeline`: refuses (or, with `fresh`, discards every result of — tables,
/// records, station files, set, figures, page) a folder holding results of another pipeline,
/// then writes the manifest, a copy of the pipeline file and copies of the files it read (so the
/// folder can be merged or rerun on its own, see [`Pipeline::output_copy`]).
pub fn prepare_output(out: &Folder, pipeline: &Pipeline, fresh: bool) -> Result<(), EnsembleError> {
    if let Some(found) = out.read_manifest()?
        && found.pipeline_hash != pipeline.hash
    {
        if !fresh {
            return Err(EnsembleError::OtherPipeline {
                out: out.root().to_path_buf(),
                found: found.pipeline_hash,
                expected: pipeline.hash.clone(),
            });
        }
        out.discard_results()?;
    }
    out.write_manifest(&Manifest { name: pipeline.name.clone(), pipeline_hash: pipeline.hash.clone() })?;
    if let Some(copy) = pipeline.output_copy() {
        for (rel, text) in &copy.inputs {
            write_text_atomic(&out.root().join(rel), text)?;
        }
        write_text_atomic(&out.pipeline_copy(), &copy.text)?;
    }
    Ok(())
}

/// Why a seed has no results.
#[derive(Debug, thiserror::Error)]
enum SeedFailure {
    /// The run failed (or was cancelled).
    #[error(transparent)]
    Run(#[from] SolverError),
    /// Its run could not be analysed.
    #[error("analysis: {0}")]
    Analysis(#[from] AnalysisError),
}

/// One seed, simulated and analysed.
struct SeedResult {
    seed: u64,
    outcome: Result<SeedAnalysis, SeedFailure>,
    wall_time_s: f64,
    /// Its share of its batch's stepping (CPU seconds).
    stepping_s: f64,
    /// Why its checkpoint could not be written or resumed, if so.
    checkpoint_note: Option<String>,
}

/// What every batch of an ensemble shares.
#[derive(Clone, Copy)]
struct Job<'a> {
    model: &'a Model,
    pipeline: &'a Pipeline,
    options: RunOptions,
    cancel: &'a AtomicBool,
    plans: &'a PlanCache,
    checkpoints: Option<&'a Checkpoints>,
}

/// Simulates a batch of seeds side by side (see [`run_batched`]) and analyses each, the analyses
/// as tasks of the pool (a thread with no batch left to step takes them), each sent to `tx` as
/// soon as it is done; a seed's wall time is its share of the batch's and its analysis.
fn simulate(job: &Job<'_>, seeds: &[u64], tx: &mpsc::SyncSender<SeedResult>) {
    let Job { model, pipeline, options, cancel, plans, checkpoints } = *job;
    let start = Instant::now();
    let cpu = thread_cpu_s();
    let mut check = |_: f64| {
        if cancel.load(Ordering::Relaxed) {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    };
    let mut notes = vec![None; seeds.len()];
    let runs: Vec<_> = match (crate::split::installed(), checkpoints) {
        // Split over MPI ranks: one seed at a time, every rank on it.
        (Some(split), _) => seeds
            .iter()
            .zip(&mut notes)
            .map(|(&seed, note)| {
                let c = checkpoints.map(|c| c.of(seed, 0, split.ranks()));
                let out = split.run(pipeline, seed, options, c.as_ref(), &mut check);
                *note = c.and_then(|c| c.failure());
                out
            })
            .collect(),
        (None, Some(c)) => seeds
            .iter()
            .zip(&mut notes)
            .map(|(&seed, note)| {
                let c = c.of(seed, 0, 1);
                let out = run_seed_checkpointed(model, seed, options, &c, &mut check);
                *note = c.failure();
                out
            })
            .collect(),
        (None, None) => run_batched(model, seeds, options, &mut check),
    };
    let share = start.elapsed().as_secs_f64() / seeds.len() as f64;
    let stepping = (thread_cpu_s() - cpu) / seeds.len() as f64;
    seeds.par_iter().zip(runs).zip(notes).for_each_with(tx.clone(), |tx, ((&seed, run), checkpoint_note)| {
        let start = Instant::now();
        let outcome = run
            .map_err(SeedFailure::from)
            .and_then(|out| analyse(out, model, &pipeline.analysis, plans, cancel).map_err(SeedFailure::from));
        let _ = tx.send(SeedResult {
            seed,
            outcome,
            wall_time_s: share + start.elapsed().as_secs_f64(),
            stepping_s: stepping,
            checkpoint_note,
        });
    });
}

/// Runs the seeds of `options` that have not finished in `options.out`, then (with
/// `options.finish`) gathers the tables and the statistics. `on_seed(done, total)` is called after
/// each seed is written; setting `cancel` stops the running seeds (finished ones are kept) and
/// returns [`EnsembleError::Interrupted`].
pub fn run_ensemble(
    pipeline: &Pipeline,
    options: &EnsembleOptions,
    on_seed: &(dyn Fn(usize, usize) + Sync),
    cancel: &AtomicBool,
) -> Result<EnsembleReport, EnsembleError> {
    let start = Instant::now();
    let out = Folder::new(&options.out);
    prepare_output(&out, pipeline, options.fresh)?;
    let pending: Vec<u64> = options.seeds.iter().copied().filter(|&s| !out.is_finished(s)).collect();
    out.remove_stale_temporaries(&pending)?;
    let skipped = options.seeds.len() - pending.len();
    let total = options.seeds.len();
    on_seed(skipped, total);
    let model = Model::new(pipeline.scene.clone());
    let plans = PlanCache::default();
    let checkpoints = options.checkpoint_every_s.map(|every_s| Checkpoints {
        out: options.out.clone(),
        every_s,
        key: pipeline.hash.clone(),
    });
    let mut checkpoint_notes = Vec::new();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
        .map_err(|e| EnsembleError::Setup(format!("thread pool: {e}")))?;
    let (tx, rx) = mpsc::sync_channel::<SeedResult>(2 * pool.current_num_threads());
    let mut failed = Vec::new();
    let mut done = skipped;
    let mut ran = 0;
    let mut integrated_steps = 0u64;
    let mut write_error = None;
    let mut gathering = Gathering::default();
    let mut profile = Profile::default();
    std::thread::scope(|scope| {
        let model = &model;
        let pending = &pending;
        let plans = &plans;
        // Batches of seeds share each pass over the lattice (lanes); a scene too large for
        // that, with fewer seeds than threads, splits each step over the threads instead. Four
        // lanes: as fast per bar-update as eight on every lattice of the step benchmark
        // (BENCHMARKS.md §1; the same CPU time for paper-100 measured), and twice as many
        // batches to share among the threads, so the last ones end closer together.
        // A seed that keeps checkpoints runs alone (its lane's state is the file's).
        let threads = pool.current_num_threads();
        let per_thread = pending.len().div_ceil(threads.max(1));
        let batch = if per_thread >= 4 && checkpoints.is_none() { 4 } else { 1 };
        let split = crate::split::installed().is_some();
        let options = RunOptions {
            parallel_step: (split || pending.len() < threads) && model.layout().splits(),
            ..RunOptions::default()
        };
        let job = Job { model, pipeline, options, cancel, plans, checkpoints: checkpoints.as_ref() };
        scope.spawn(move || {
            pool.install(|| {
                if split {
                    // Split over MPI ranks: the seeds in order, one at a time, each step on the
                    // pool.
                    for &seed in pending {
                        if cancel.load(Ordering::Relaxed) {
                            return;
                        }
                        simulate(&job, &[seed], &tx);
                    }
                    return;
                }
                pending.par_chunks(batch).for_each_with(tx, |tx, chunk| {
                    if cancel.load(Ordering::Relaxed) {
                        return;
                    }
                    simulate(&job, chunk, tx);
                });
            });
        });
        let stamp = Stamp { pipeline: &pipeline.name, hash: &pipeline.hash };
        for r in rx {
            let cancelled = matches!(
                r.outcome,
                Err(SeedFailure::Run(SolverError::Cancelled))
                    | Err(SeedFailure::Analysis(AnalysisError::Records(RecordFailure::Cancelled)))
            );
            if let Some(note) = &r.checkpoint_note {
                checkpoint_notes.push((r.seed, note.clone()));
            }
            if write_error.is_some() || cancelled {
                continue;
            }
            let mut kept: Result<(), stickslip_store::StoreError> = Ok(());
            let mut keep = |t: &stickslip_store::TableSpec, df| {
                if kept.is_ok() {
                    kept = gathering.keep(r.seed, t, df);
                }
            };
            let writing = thread_cpu_s();
            profile.stepping_s += r.stepping_s;
            let written = match &r.outcome {
                Ok(a) => {
                    integrated_steps += a.run.integrated_steps();
                    profile.events_s += a.events_s;
                    if let Some(h) = a.source.as_ref().and_then(|s| s.stochastic.as_ref()) {
                        profile.broadband_s += h.synthesis_cpu_s;
                        profile.broadband_motions_s += h.motions_cpu_s;
                    }
                    if let Some(t) = a.records.as_ref().map(|r| r.timings) {
                        profile.records_s += t.records_s;
                        profile.spectra_s += t.spectra_s;
                        profile.rotd_s += t.rotd_s;
                        profile.alone += t.alone;
                        profile.pairs += t.pairs;
                    }
                    let view = SeedView { seed: r.seed, analysis: a, model, settings: &pipeline.analysis };
                    write_seed(&out, &view, &stamp, r.wall_time_s, &mut keep)
                }
                Err(e) => {
                    // The solver's message with the pipeline keys behind its advice.
                    let msg = match e {
                        SeedFailure::Run(e) => stickslip_config::keys::describe(e),
                        other => other.to_string(),
                    };
                    let written = write_failed(&out, r.seed, &msg, &pipeline.hash, r.wall_time_s, &mut keep);
                    failed.push((r.seed, msg));
                    written
                }
            };
            let written = written.and(kept);
            profile.writing_s += thread_cpu_s() - writing;
            // Written: its checkpoints have served (every rank's, on a folder every rank sees).
            let ranks = crate::split::installed().map_or(1, |s| s.ranks());
            let written = written.and_then(|()| {
                (0..ranks).try_for_each(|rank| {
                    stickslip_store::io::remove_file_if_present(&out.checkpoint(r.seed, rank, ranks))
                })
            });
            match written {
                Ok(()) => {
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
        return Err(e.into());
    }
    if cancel.load(Ordering::Relaxed) {
        return Err(EnsembleError::Interrupted { done, total, out: options.out.clone() });
    }
    let mut set = None;
    let gathering_started = thread_cpu_s();
    if options.finish
        && let Some(runs) = gather(&out, &options.seeds, gathering)?
    {
        failed = runs.failed();
        set = pipeline.set.as_ref().map(|s| select_set(&out, pipeline, s).map_err(|e| e.to_string()));
        crate::exchange::write_exchange(&out, pipeline)?;
    }
    profile.gather_s = thread_cpu_s() - gathering_started;
    let wall_time_s = start.elapsed().as_secs_f64();
    Ok(EnsembleReport {
        ran,
        skipped,
        failed,
        wall_time_s,
        out: options.out.clone(),
        steps_per_s: if ran > 0 { integrated_steps as f64 / wall_time_s } else { 0.0 },
        set,
        profile,
        checkpoint_notes,
    })
}

/// The `k`-th (1-based) of `n` disjoint, contiguous slices of `seeds`, in their order: seeds
/// `⌊(k−1)·len/n⌋ … ⌊k·len/n⌋ − 1`. Every seed is in exactly one slice whatever `n`.
pub fn shard(seeds: &[u64], k: usize, n: usize) -> Vec<u64> {
    assert!(n >= 1 && (1..=n).contains(&k), "shard {k}/{n}");
    let len = seeds.len();
    seeds[(k - 1) * len / n..k * len / n].to_vec()
}
