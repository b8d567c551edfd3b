//! `stickslip pipeline`: every seed of one or more pipelines, their tables and report.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use stickslip_config::Pipeline;
use stickslip_config::set::SetCapacity;
use stickslip_ensemble::precision::run_to_precision;
use stickslip_ensemble::set::SetOutcome;
use stickslip_ensemble::summary::digest;
use stickslip_ensemble::{EnsembleOptions, EnsembleReport, run_ensemble, shard};
use stickslip_store::Folder;

use crate::progress;
use crate::text::{count, seed_list};
use stickslip_analysis::SlipRegime;
use stickslip_config::seeds::{parse_seeds, parse_shard};
use stickslip_seismo::catalogue::compact;
use stickslip_store::tables::runs::Runs;

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
}

/// Stops the running seeds at the first Ctrl-C (finished ones are kept), at once at the second.
pub fn cancel_on_ctrl_c() -> Result<Arc<AtomicBool>> {
    let cancel = Arc::new(AtomicBool::new(false));
    let flag = cancel.clone();
    ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(130);
        }
        errln!("\ninterrupt: finishing the seeds being written (Ctrl-C again to stop at once)");
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
    // Whether any seed has an event (the gathered table) or has run at all (a series part):
    // no part is read for this.
    let events =
        stickslip_store::io::read_parquet_if_present(&folder.gathered(&stickslip_store::schema::EVENTS_TABLE))?;
    let ran = stickslip_store::io::any_part(&folder.part_glob(&stickslip_store::schema::SERIES));
    let regimes = Regimes::of(&folder)?;
    if pipeline.scene.is_fault() {
        // A fault's events are its ruptures: the source from its own slip says what they were, and
        // the stations against the ground-motion models how they shook.
        if let Some(text) = source_digest(&folder)? {
            outln!("{text}");
        } else {
            outln!("{}", no_events(pipeline, &folder, &regimes));
        }
        let opts = stickslip_ensemble::gmm::GmmOptions::default();
        match stickslip_ensemble::gmm::compare(&folder, &opts) {
            Ok(Some(c)) => crate::commands::gmm::print(&c, &opts),
            Ok(None) => {}
            Err(stickslip_ensemble::EnsembleError::Store(e)) => return Err(e.into()),
            Err(e) => outln!("no comparison with the ground-motion models: {e}"),
        }
    } else if events.is_some_and(|e| e.height() > 0) || !ran {
        outln!("{}", digest(&folder)?);
        if let Some(text) = regimes.sliding_text() {
            outln!("{text}");
            outln!("  as a spring-slider (stickslip check): {}", slider_verdict(pipeline));
        }
    } else {
        outln!("{}", no_events(pipeline, &folder, &regimes));
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

/// The ruptures of a fault scene, seed by seed, from the `source` table (`None` without one).
fn source_digest(folder: &Folder) -> Result<Option<String>> {
    use stickslip_store::schema::{SOURCE, col};
    let Some(df) = stickslip_store::io::read_parquet_if_present(&folder.gathered(&SOURCE))? else { return Ok(None) };
    let c = stickslip_store::frame::Columns::of(&df, SOURCE.name);
    let seeds = c.u64s(col::SEED)?;
    if seeds.is_empty() {
        return Ok(None);
    }
    let (mw, drop, slip) = (c.f64s(col::MW)?, c.f64s(col::STRESS_DROP_PA)?, c.f64s(col::MEAN_SLIP_M)?);
    let (rate, dur) = (c.f64s(col::MEDIAN_PEAK_SLIP_RATE_M_S)?, c.f64s(col::RUPTURE_DURATION_S)?);
    let (hx, hy) = (c.f64s(col::HYPOCENTRE_X_M)?, c.f64s(col::HYPOCENTRE_Y_M)?);
    let brune = c.f64s(col::BRUNE_CORNER_HZ)?;
    let fitted =
        if c.has(col::FITTED_CORNER_HZ) { c.opt_f64s(col::FITTED_CORNER_HZ)? } else { vec![None; seeds.len()] };
    let mut text = format!(
        "ruptures (the source table, from each seed's own slip; docs/model.md §15–16)\n{:>6} {:>6} {:>12} {:>10} \
         {:>18} {:>11} {:>18} {:>20}",
        "seed",
        "Mw",
        "stress drop",
        "mean slip",
        "median peak rate",
        "duration",
        "corner Brune/fit",
        "hypocentre (x, y)"
    );
    for i in 0..seeds.len() {
        let corner = match fitted[i] {
            Some(f) => format!("{:.2}/{:.2} Hz", brune[i], f),
            None => format!("{:.2}/– Hz", brune[i]),
        };
        text.push_str(&format!(
            "\n{:>6} {:>6.2} {:>8.2} MPa {:>8.2} m {:>14.2} m/s {:>9.2} s {:>18} {:>9.1}, {:.1} km",
            seeds[i],
            mw[i],
            drop[i] / 1e6,
            slip[i],
            rate[i],
            dur[i],
            corner,
            hx[i] / 1e3,
            hy[i] / 1e3
        ));
    }
    Ok(Some(text))
}

/// What the base did in each finished seed, from the runs table (`slip_regime`).
struct Regimes {
    /// Seeds of each regime.
    by: Vec<(SlipRegime, Vec<u64>)>,
    /// Start of the sliding that never stopped, per seed that ended sliding.
    sliding_from: Vec<(u64, f64)>,
    /// Finished seeds.
    seeds: usize,
}

impl Regimes {
    fn of(folder: &Folder) -> Result<Regimes> {
        let runs = stickslip_store::io::read_parquet_if_present(&folder.gathered(&stickslip_store::schema::RUNS))?
            .map(|df| Runs::read(&df))
            .transpose()?;
        let mut by: Vec<(SlipRegime, Vec<u64>)> = SlipRegime::ALL.iter().map(|&r| (r, Vec::new())).collect();
        let mut sliding_from = Vec::new();
        let mut seeds = 0;
        if let Some(r) = runs {
            for i in 0..r.seed.len() {
                let Some(regime) = SlipRegime::parse(&r.slip_regime[i]) else { continue };
                seeds += 1;
                by.iter_mut().find(|(g, _)| *g == regime).expect("every regime").1.push(r.seed[i]);
                if let Some(t) = r.sliding_from_s[i] {
                    sliding_from.push((r.seed[i], t));
                }
            }
        }
        Ok(Regimes { by, sliding_from, seeds })
    }

    fn seeds(&self, regime: SlipRegime) -> &[u64] {
        &self.by.iter().find(|(g, _)| *g == regime).expect("every regime").1
    }

    /// "in 3 of 8 seeds (1, 4, 7)".
    fn among(&self, seeds: &[u64]) -> String {
        format!("in {} of {} ({})", seeds.len(), count(self.seeds, "seed", "seeds"), seed_list(seeds))
    }

    /// The range of the sliding onsets, "from t = 0.067 … 0.068 s".
    fn onset_text(&self, seeds: &[u64]) -> String {
        let t: Vec<f64> = self.sliding_from.iter().filter(|(s, _)| seeds.contains(s)).map(|p| p.1).collect();
        let (lo, hi) = t.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
        let (a, b) = (format!("{lo:.3}"), format!("{hi:.3}"));
        match t.len() {
            0 => String::new(),
            _ if a == b => format!(" from t = {a} s"),
            _ => format!(" from t = {a} … {b} s"),
        }
    }

    /// What to say about seeds that slid stably, if any did.
    fn sliding_text(&self) -> Option<String> {
        let (sliding, then) = (self.seeds(SlipRegime::StableSliding), self.seeds(SlipRegime::StickSlipThenSliding));
        if sliding.is_empty() && then.is_empty() {
            return None;
        }
        let mut lines = vec![
            "stable sliding: the base slid along with its loading, without stopping — not an earthquake, so none of it \
             is in the catalogue (no main shock, no magnitude)"
                .to_string(),
        ];
        if !sliding.is_empty() {
            lines.push(format!("  sliding only {}{}", self.among(sliding), self.onset_text(sliding)));
        }
        if !then.is_empty() {
            lines.push(format!("  stick-slip, then sliding to the end {}{}", self.among(then), self.onset_text(then)));
        }
        Some(lines.join("\n"))
    }
}

/// What `stickslip check` expects of the scene, as a spring-slider.
fn slider_verdict(pipeline: &Pipeline) -> String {
    let model = stickslip_solver::Model::new(pipeline.scene.clone());
    let statics = stickslip_solver::inspect::Statics::for_model(&model);
    match stickslip_solver::inspect::spring_slider(&model, pipeline.seeds[0], statics) {
        Ok(slider) => stickslip_config::keys::verdict(&slider),
        Err(e) => format!("not assessed ({e})"),
    }
}

/// Why a finished ensemble has no event, from what its seeds did and recorded, and what to try.
fn no_events(pipeline: &Pipeline, folder: &Folder, regimes: &Regimes) -> String {
    use stickslip_solver::Channel;
    let ev = &pipeline.analysis.events;
    let sh = &pipeline.scene.shear;
    let series = stickslip_store::io::scan_glob(&folder.part_glob(&stickslip_store::schema::SERIES)).ok().flatten();
    let largest = |c: Channel| -> Option<f64> {
        // Channels are stored in single precision: read as f64 by a cast.
        let column = series.as_ref()?.column(c.name()).ok()?.cast(&polars::prelude::DataType::Float64).ok()?;
        let values = column.f64().ok()?.iter().flatten().collect::<Vec<_>>();
        values.into_iter().reduce(f64::max)
    };
    let sliding = regimes.seeds(SlipRegime::StableSliding);
    let mut lines = Vec::new();
    if !sliding.is_empty() {
        lines.push(format!(
            "no events: the base slid stably {}{} — it kept up with its loading without stopping, so there is no \
             stick-slip to catalogue (stable sliding is not an earthquake).",
            regimes.among(sliding),
            regimes.onset_text(sliding)
        ));
    }
    let held = regimes.seeds(SlipRegime::NoSlip);
    if !held.is_empty() || sliding.is_empty() {
        lines.push(format!(
            "no events{}: an event is a burst of slip of the base — the mean slip rate, smoothed over \
             events.smoothing_s, must rise above events.v_on_m_s and τ must then drop by at least events.min_drop_pa.",
            if held.is_empty() { String::new() } else { format!(" {}", regimes.among(held)) }
        ));
        match largest(Channel::MeanSlipRate) {
            Some(v) => lines.push(format!(
                "  largest mean slip rate recorded (unsmoothed): {v:.3e} m/s against v_on = {} m/s{}",
                compact(ev.v_on_m_s),
                if v < ev.v_on_m_s { ": the base never slipped fast enough" } else { "" }
            )),
            None => lines.push("  the slip rate is not recorded (add \"slip_rate\" to record.interface)".into()),
        }
        if let Some(tau) = largest(Channel::ShearStress) {
            let model = stickslip_solver::Model::new(pipeline.scene.clone());
            let sigma = model.total_mass() * pipeline.scene.self_weight.gravity_m_s2 / model.lattice().contact_area();
            let mu = pipeline.scene.friction.law.node(1.0).static_coefficient();
            lines.push(format!(
                "  largest shear stress τ: {tau:.4e} Pa; sliding needs about μs·σ = {:.4e} Pa (μs = {}, self-weight σ = \
                 {sigma:.4e} Pa)",
                mu * sigma,
                compact(mu)
            ));
        }
        if let Some(lifted) = largest(Channel::LiftedNodes) {
            let contacts = pipeline.scene.lattice().contact_nodes().len();
            if lifted >= 0.5 * contacts as f64 {
                lines.push(format!(
                    "  up to {lifted:.0} of {contacts} base nodes were lifted at once: the load tips the block over \
                     rather than sliding it"
                ));
            }
        }
        lines.push(format!(
            "  the shear stage lasted {} s: the loading moved about {:.3e} m at {} m/s",
            compact(sh.duration_s),
            sh.driver_displacement(sh.duration_s),
            compact(sh.velocity_m_s)
        ));
    }
    lines.push(format!("  as a spring-slider (stickslip check): {}", slider_verdict(pipeline)));
    let figure = folder.figures().join("shear_stress.png");
    let look = if pipeline.report.enabled {
        format!("look at {} (written with the report below) and", figure.display())
    } else {
        "look at the series table and".to_string()
    };
    if sliding.is_empty() {
        lines.push(format!(
            "  try: a longer [shear] duration_s (or a faster velocity_m_s) so τ reaches the strength; a lower [friction] \
             mu_static; a lower [events] v_on_m_s or min_drop_pa for small events; and {look} `stickslip check` for \
             what the scene builds"
        ));
    } else {
        let softer = if pipeline.scene.plate.is_some() {
            "softer [loading_plate] springs"
        } else {
            "a [loading_plate] on springs instead of rigid driver nodes"
        };
        lines.push(format!(
            "  for stick-slip a slip must outrun its loading and stop again: {softer}, less [shear] damping_per_s, a \
             larger μs − μd (the spring-slider reading above says which matters here); {look} `stickslip check`"
        ));
    }
    lines.join("\n")
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

/// `stickslip pipeline`.
pub fn run(a: Args) -> Result<()> {
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
    // Memory and run length of every pipeline before any is built.
    let threads = a.threads.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let mut runs = Vec::new();
    for pipeline in &pipelines {
        let mut seeds = given.clone().unwrap_or_else(|| pipeline.seeds.clone());
        if let Some((k, n)) = a.shard {
            seeds = shard(&seeds, k, n);
        }
        // A shard's seeds are part of the set's; the merge chooses it from them all.
        if a.shard.is_none() {
            check_set_capacity(pipeline, seeds.len())?;
        }
        let what = format!("{}: {} seed{}", pipeline.name, seeds.len(), if seeds.len() == 1 { "" } else { "s" });
        crate::budget::check_before_build(&pipeline.scene, seeds.len(), threads, a.allow_long, &what)?;
        runs.push(seeds);
    }
    let cancel = cancel_on_ctrl_c()?;
    let mut unfinished = Vec::new();
    for (pipeline, seeds) in pipelines.iter().zip(runs) {
        let out = a.out.clone().unwrap_or_else(|| PathBuf::from("reports").join(&pipeline.name));
        if let Some((k, n)) = a.shard {
            stickslip_ensemble::merge::mark_shard(&out, pipeline, k, n, &seeds)?;
        }
        let options = EnsembleOptions {
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
