//! `check` and `run` from Python, as `stickslip check` and `stickslip pipeline` do them: the
//! same library calls, on a worker thread with the GIL released, while the calling thread wakes
//! every 0.1 s to pass Python its progress and its signals — a Ctrl-C (`KeyboardInterrupt`) stops
//! the running seeds as the command line's first Ctrl-C does (finished seeds are kept, a second
//! run resumes) and is raised once they are written.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use pyo3::prelude::*;
use pyo3::types::PyDict;
use stickslip_config::Pipeline;
use stickslip_ensemble::check::{CheckLine, CheckOptions};
use stickslip_ensemble::digest::RunDigest;
use stickslip_ensemble::precision::run_to_precision;
use stickslip_ensemble::{EnsembleError, EnsembleOptions, EnsembleReport, budget, run_ensemble};
use stickslip_store::Folder;

use crate::errors::ensemble_error;
use crate::pipeline::load;

/// How often the calling thread wakes to check signals and report progress.
const POLL: Duration = Duration::from_millis(100);

/// Why the calling thread stopped a run.
enum Stop {
    /// A signal: Python's `KeyboardInterrupt` (or what the signal handler raised).
    Signal(PyErr),
    /// The progress callback raised this.
    Callback(PyErr),
}

/// Runs `work` on a worker thread with the GIL released; every [`POLL`] the calling thread checks
/// Python's signals (a `KeyboardInterrupt` sets `cancel`) and calls `progress(done, total)` when
/// `counts` changed (an error it raises sets `cancel` too). Returns what `work` returned, once it
/// has, and why it was stopped, if it was.
fn detached<T: Send>(
    py: Python<'_>,
    cancel: &AtomicBool,
    counts: &(AtomicUsize, AtomicUsize),
    progress: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce() -> T + Send,
) -> PyResult<(T, Option<Stop>)> {
    let mut interrupt: Option<Stop> = None;
    let mut shown = (usize::MAX, usize::MAX);
    let out = std::thread::scope(|s| -> PyResult<T> {
        let (tx, rx) = mpsc::channel();
        s.spawn(move || {
            let _ = tx.send(work());
        });
        // Shared with the detached closure (a Receiver alone is not Sync).
        let rx = std::sync::Mutex::new(rx);
        loop {
            let got = py.detach(|| rx.lock().map_err(|_| mpsc::RecvTimeoutError::Disconnected)?.recv_timeout(POLL));
            if interrupt.is_none()
                && let Err(e) = py.check_signals()
            {
                cancel.store(true, Ordering::SeqCst);
                interrupt = Some(Stop::Signal(e));
            }
            let now = (counts.0.load(Ordering::Relaxed), counts.1.load(Ordering::Relaxed));
            if let Some(cb) = progress
                && now != shown
                && now.1 > 0
            {
                shown = now;
                if let Err(e) = cb.call1(now) {
                    // A failing callback stops the run like an interrupt, and its error is raised;
                    // a Ctrl-C that lands while the callback runs is raised inside it, and is a signal.
                    cancel.store(true, Ordering::SeqCst);
                    let signal = e.is_instance_of::<pyo3::exceptions::PyKeyboardInterrupt>(py);
                    interrupt.get_or_insert(if signal { Stop::Signal(e) } else { Stop::Callback(e) });
                }
            }
            match got {
                Ok(v) => return Ok(v),
                Err(mpsc::RecvTimeoutError::Timeout) => continue,
                Err(mpsc::RecvTimeoutError::Disconnected) => {
                    return Err(pyo3::exceptions::PyRuntimeError::new_err(
                        "the worker thread stopped without a result",
                    ));
                }
            }
        }
    })?;
    Ok((out, interrupt))
}

/// The outcome of an ensemble stopped or not by the calling thread: the callback's error when it
/// raised one; the ensemble's own `Interrupted` (finished seeds and how to resume) as
/// `KeyboardInterrupt`; a signal's error if the work ended some other way.
fn settle<T>(py: Python<'_>, result: Result<T, EnsembleError>, stop: Option<Stop>) -> PyResult<T> {
    match (result, stop) {
        (_, Some(Stop::Callback(e))) => Err(e),
        (Err(e), _) => Err(ensemble_error(py, e)),
        (Ok(_), Some(Stop::Signal(e))) => Err(e),
        (Ok(v), None) => Ok(v),
    }
}

/// What `stickslip check` prints, as data: `lines` (section, part, text) in order and `facts`.
#[pyfunction]
#[pyo3(signature = (text, name, base, source=None, seeds=None, full_statics=false, allow_long=false, threads=0))]
#[allow(clippy::too_many_arguments)]
pub fn check<'py>(
    py: Python<'py>,
    text: &str,
    name: &str,
    base: PathBuf,
    source: Option<PathBuf>,
    seeds: Option<usize>,
    full_statics: bool,
    allow_long: bool,
    threads: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let pipeline = load(py, text, name, &base, source)?;
    let options = CheckOptions { seeds, full_statics, allow_long, threads, ..CheckOptions::default() };
    let (cancel, counts) = (AtomicBool::new(false), (AtomicUsize::new(0), AtomicUsize::new(0)));
    let ((lines, result), stop) = detached(py, &cancel, &counts, None, || {
        let mut lines: Vec<CheckLine> = Vec::new();
        let r = stickslip_ensemble::check::check(&pipeline, &options, &mut |l| lines.push(l));
        (lines, r)
    })?;
    let facts = settle(py, result, stop)?;
    let d = PyDict::new(py);
    d.set_item("name", &pipeline.name)?;
    d.set_item("hash", &pipeline.hash)?;
    let rows: Vec<(&str, &str, String)> = lines.into_iter().map(|l| (l.section, l.label, l.text)).collect();
    d.set_item("lines", rows)?;
    let f = PyDict::new(py);
    f.set_item("bars", facts.bars)?;
    f.set_item("critical_dt_s", facts.critical_dt_s)?;
    f.set_item("dt_s", facts.dt_s)?;
    f.set_item("steps", facts.steps)?;
    f.set_item("per_step_s", facts.per_step_s)?;
    f.set_item("setup_s", facts.setup_s)?;
    d.set_item("facts", f)?;
    Ok(d)
}

/// What a finished run did, and what its folder's closing summary says.
struct Finished {
    report: EnsembleReport,
    digest: String,
    precision: Option<String>,
    report_page: Option<PathBuf>,
}

/// Runs `pipeline` into `out` as `stickslip pipeline` does: the ensemble (or the precision
/// target's batches), then the comparison with the ground-motion models of a fault scenario and
/// the report page.
fn run_and_finish(
    pipeline: &Pipeline,
    options: &EnsembleOptions,
    counts: &(AtomicUsize, AtomicUsize),
    cancel: &AtomicBool,
) -> Result<Finished, EnsembleError> {
    let on_seed = |done: usize, total: usize| {
        counts.0.store(done, Ordering::Relaxed);
        counts.1.store(total, Ordering::Relaxed);
    };
    let (report, precision) = match &pipeline.target {
        Some(target) => {
            let (r, outcome) = run_to_precision(pipeline, target, options, &on_seed, cancel)?;
            (r, Some(outcome.describe()))
        }
        None => (run_ensemble(pipeline, options, &on_seed, cancel)?, None),
    };
    let folder = Folder::new(&options.out);
    let digest = RunDigest::of(pipeline, &folder)?.to_string();
    if pipeline.scene.is_fault() {
        // The tables of the comparison, as the command line writes them.
        let _ = stickslip_ensemble::gmm::compare(&folder, &Default::default())?;
    }
    let report_page = if pipeline.report.enabled {
        let r = stickslip_report::write_report(&options.out, pipeline)
            .map_err(|e| EnsembleError::Setup(format!("report: {e}")))?;
        Some(r.index)
    } else {
        None
    };
    Ok(Finished { report, digest, precision, report_page })
}

/// Runs a pipeline's seeds into `out` (see the package's `stickslip.run`).
#[pyfunction]
#[pyo3(signature = (text, name, base, out, source=None, seeds=None, threads=0, fresh=false, allow_long=false, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn run<'py>(
    py: Python<'py>,
    text: &str,
    name: &str,
    base: PathBuf,
    out: PathBuf,
    source: Option<PathBuf>,
    seeds: Option<Vec<u64>>,
    threads: usize,
    fresh: bool,
    allow_long: bool,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let started = Instant::now();
    let pipeline = load(py, text, name, &base, source)?;
    if pipeline.target.is_some() && seeds.is_some() {
        return Err(ensemble_error(
            py,
            EnsembleError::Setup(format!(
                "{}: a pipeline with [seeds.target] chooses its own seeds in batches: run it without seeds",
                pipeline.name
            )),
        ));
    }
    let seeds = seeds.unwrap_or_else(|| pipeline.seeds.clone());
    let workers = if threads == 0 { std::thread::available_parallelism().map_or(1, |n| n.get()) } else { threads };
    let what = format!("{}: {} seed{}", pipeline.name, seeds.len(), if seeds.len() == 1 { "" } else { "s" });
    budget::check_before_build(&pipeline.scene, seeds.len(), workers, allow_long, &what)
        .map_err(|e| ensemble_error(py, e))?;
    let options = EnsembleOptions { checkpoint_every_s: None, out: out.clone(), threads, seeds, fresh, finish: true };
    let (cancel, counts) = (AtomicBool::new(false), (AtomicUsize::new(0), AtomicUsize::new(0)));
    let (result, stop) =
        detached(py, &cancel, &counts, progress.as_ref(), || run_and_finish(&pipeline, &options, &counts, &cancel))?;
    let finished = settle(py, result, stop)?;
    let r = &finished.report;
    let d = PyDict::new(py);
    d.set_item("pipeline", &pipeline.name)?;
    d.set_item("out", &r.out)?;
    d.set_item("ran", r.ran)?;
    d.set_item("skipped", r.skipped)?;
    d.set_item("failed", r.failed.clone())?;
    d.set_item("run_wall_time_s", r.wall_time_s)?;
    d.set_item("wall_time_s", started.elapsed().as_secs_f64())?;
    d.set_item("steps_per_s", r.steps_per_s)?;
    d.set_item("digest", &finished.digest)?;
    d.set_item("precision", finished.precision)?;
    d.set_item("report", finished.report_page)?;
    d.set_item(
        "set",
        r.set.as_ref().map(|s| match s {
            Ok(_) => "chosen".to_string(),
            Err(e) => format!("none chosen: {e}"),
        }),
    )?;
    Ok(d)
}
