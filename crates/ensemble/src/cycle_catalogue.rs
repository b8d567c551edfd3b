//! A cycle run over seeds (docs/model.md §20.6; the guide's faults chapter, A catalogue of
//! earthquake cycles): each seed draws its own random fields of the friction
//! (`[cycles.heterogeneity]`), runs the cycles under `<out>/seeds/seed-N/` and leaves a
//! `complete` file once finished; the seeds' events are gathered into
//! `<out>/tables/cycle_events.parquet` (with their seed) and the catalogue statistics of the
//! product's ensembles are computed on them ([`crate::catalogue::cycle_catalogue_stats`]): the
//! magnitude–frequency distribution and b-value above Mc, recurrence, stacked aftershocks with
//! an Omori–Utsu fit, and the scaling of moment with area and duration.
//!
//! A run interrupted resumes at its first unfinished seed: a seed whose `complete` file names the
//! pipeline's hash is read back, not run again. A seed whose run fails (its step budget spent, a
//! solver error) is left unfinished and reported; the others run on.

use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

use stickslip_config::Pipeline;
use stickslip_store::frame::Columns;
use stickslip_store::io::{read_parquet_if_present, remove_file_if_present, write_text_atomic};
use stickslip_store::{Folder, StoreError};

use crate::catalogue::{CatalogueStats, CycleCatalogue, cycle_catalogue_stats, write_catalogue_tables};
use crate::cycles::{CycleEvent, CycleReport, run_cycles, write_events};
use crate::error::EnsembleError;

/// An event is a main shock when its magnitude is within this of its seed's largest.
pub const MAIN_SHOCK_WITHIN: f64 = 1.0;

/// One seed of a cycle catalogue.
#[derive(Clone, Debug)]
pub struct SeedCycles {
    /// The seed.
    pub seed: u64,
    /// Its events.
    pub events: Vec<CycleEvent>,
    /// Its run, `None` when read back from an earlier run's files.
    pub run: Option<CycleReport>,
    /// Where its files are.
    pub out: PathBuf,
}

/// What a cycle catalogue gave.
#[derive(Clone, Debug)]
pub struct CycleCatalogueReport {
    /// The seeds finished, in the pipeline's order.
    pub seeds: Vec<SeedCycles>,
    /// The fault nodes' spacing (m).
    pub lc_m: f64,
    /// The run's length (s).
    pub duration_s: f64,
    /// The catalogue statistics of the finished seeds.
    pub stats: CatalogueStats,
    /// The seed interrupted (its files written up to there, not counted), if any.
    pub interrupted: Option<u64>,
    /// The seeds whose run failed, with why (not counted; the next run tries them again).
    pub failed: Vec<(u64, String)>,
}

/// The folder of `seed`'s run under `out`.
pub fn seed_folder(out: &Path, seed: u64) -> PathBuf {
    out.join("seeds").join(format!("seed-{seed}"))
}

/// Runs the pipeline's `[cycles]` for each of its seeds (reading back those an earlier run
/// finished), calling `finished` after each, then gathers the events and writes the catalogue
/// tables under `out`.
pub fn run_cycle_catalogue(
    pipeline: &Pipeline,
    out: &Path,
    cancel: &AtomicBool,
    mut finished: impl FnMut(&SeedCycles),
) -> Result<CycleCatalogueReport, EnsembleError> {
    let spec = pipeline.cycles.as_ref().expect("a [cycles] pipeline");
    let lc = pipeline.scene.lc_m;
    let mut seeds = Vec::new();
    let mut interrupted = None;
    let mut failed = Vec::new();
    for &seed in &pipeline.seeds {
        let dir = seed_folder(out, seed);
        let marker = dir.join("complete");
        let done = std::fs::read_to_string(&marker).is_ok_and(|t| t.lines().next() == Some(pipeline.hash.as_str()));
        let events_path = dir.join("tables").join("cycle_events.parquet");
        let s = if done {
            SeedCycles { seed, events: read_events(&events_path)?, run: None, out: dir }
        } else {
            // A seed run again is unfinished until it ends: an earlier marker must not vouch for
            // what this run leaves behind if it stops.
            remove_file_if_present(&marker)?;
            let r = match run_cycles(pipeline, seed, &dir, cancel) {
                Ok(r) => r,
                Err(EnsembleError::Solver(e)) => {
                    failed.push((seed, e.to_string()));
                    continue;
                }
                Err(e) => return Err(e),
            };
            if r.interrupted_s.is_some() {
                interrupted = Some(seed);
                break;
            }
            let text = format!(
                "{}\npipeline {} seed {seed}: {} events over {} years; {} steps accepted, {} rejected, {:.1} s\n",
                pipeline.hash,
                pipeline.name,
                r.events.len(),
                spec.duration_s / stickslip_solver::cycles::YEAR_S,
                r.stats.accepted,
                r.stats.rejected,
                r.stiffness_s + r.run_s
            );
            write_text_atomic(&marker, &text)?;
            SeedCycles { seed, events: r.events.clone(), run: Some(r), out: dir }
        };
        finished(&s);
        seeds.push(s);
    }
    let lists: Vec<(u64, &[CycleEvent])> = seeds.iter().map(|s| (s.seed, s.events.as_slice())).collect();
    write_events(&lists, lc, &out.join("tables").join("cycle_events.parquet"))?;
    let catalogues: Vec<CycleCatalogue> = seeds.iter().map(|s| catalogue(s, lc, spec.duration_s)).collect();
    let stats = cycle_catalogue_stats(&catalogues);
    write_catalogue_tables(&Folder::new(out), &stats)?;
    Ok(CycleCatalogueReport { seeds, lc_m: lc, duration_s: spec.duration_s, stats, interrupted, failed })
}

/// A seed's events as the catalogue statistics take them: rupture area `length²` (the
/// two-dimensional run's convention), main shocks within [`MAIN_SHOCK_WITHIN`] of the seed's
/// largest magnitude.
fn catalogue(s: &SeedCycles, lc: f64, end_s: f64) -> CycleCatalogue {
    let magnitude: Vec<f64> = s.events.iter().map(|e| e.magnitude(lc)).collect();
    let largest = magnitude.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    CycleCatalogue {
        seed: s.seed,
        end_s,
        onset_s: s.events.iter().map(|e| e.onset_s).collect(),
        moment_n_m: s.events.iter().map(|e| e.moment_n_m(lc)).collect(),
        area_m2: s.events.iter().map(|e| e.length_m(lc).powi(2)).collect(),
        duration_s: s.events.iter().map(|e| e.duration_s).collect(),
        main: magnitude.iter().map(|&m| m >= largest - MAIN_SHOCK_WITHIN).collect(),
        magnitude,
    }
}

/// The events of a seed's `cycle_events` table.
fn read_events(path: &Path) -> Result<Vec<CycleEvent>, EnsembleError> {
    let df = read_parquet_if_present(path)?.ok_or_else(|| {
        EnsembleError::Store(StoreError::Corrupt {
            path: path.to_path_buf(),
            what: "a seed marked complete has no cycle_events table; remove its folder to run it again".into(),
        })
    })?;
    let c = Columns::of(&df, "cycle_events");
    let f = |name: &str| c.f64s(name).map_err(EnsembleError::Store);
    let (onset, duration, hypo, peak) =
        (f("onset_s")?, f("duration_s")?, f("hypocentre_depth_m")?, f("peak_slip_rate_m_s")?);
    let (surface, max, top, bottom, moment) =
        (f("surface_slip_m")?, f("max_slip_m")?, f("ruptured_top_m")?, f("ruptured_bottom_m")?, f("moment_per_m_n")?);
    Ok((0..df.height())
        .map(|i| CycleEvent {
            onset_s: onset[i],
            duration_s: duration[i],
            hypocentre_depth_m: hypo[i],
            peak_slip_rate_m_s: peak[i],
            surface_slip_m: surface[i],
            max_slip_m: max[i],
            ruptured_m: [top[i], bottom[i]],
            moment_per_m: moment[i],
        })
        .collect())
}
