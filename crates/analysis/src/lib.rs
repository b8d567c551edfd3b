//! stickslip analysis: one seed's recording analysed into a typed result.
//!
//! Owns: the analysis of one finished run, [`analyse`] — its events and sub-events on the
//! solver's event trace ([`events`]), each at prototype scale with its magnitudes, the records
//! cut around the events with their processing, intensity, response, Fourier and RotD spectra
//! ([`records`]), the attenuation of peak motions with distance ([`attenuation`]), the rupture
//! front of each event ([`fronts`]), the bar breaks as acoustic emission ([`emission`]), and on a
//! fault the source from its own slip and the stations against the rupture ([`source`]) with
//! their processed RotD motions ([`motions`]) and broadband records ([`broadband`]) — and
//! what it is asked to do ([`settings`]). It is a pure function of the run, the model and the
//! settings: it can be tested without files.
//!
//! Must not know: files, tables or figures (the store writes a [`SeedAnalysis`]), the pipeline
//! file's syntax (the configuration crate builds the [`Settings`]), how seeds are scheduled.
#![deny(missing_docs)]

pub mod attenuation;
pub mod broadband;
pub mod emission;
pub mod events;
pub mod fronts;
pub mod motions;
pub mod records;
pub mod settings;
pub mod source;

use stickslip_seismo::emission::Cluster;
use stickslip_seismo::events::Catalogue;
use stickslip_solver::{Model, RunOutput};

pub use events::{Diagnosis, ScaledEvent, SlipRegime};
pub use fronts::SeedFronts;
pub use records::{PlanCache, RecordData, RecordFailure, RecordTimings, RotdData, SeedRecords};
pub use settings::{AccelerogramSettings, Settings, SpectraSettings};
pub use source::{Source, StationRow};

/// CPU seconds used so far by the calling thread (the wall clock where the system has no
/// per-thread clock): stages timed with it add up over threads without counting the time a
/// thread waits or shares its core.
pub fn thread_cpu_s() -> f64 {
    #[cfg(unix)]
    {
        let mut t = libc::timespec { tv_sec: 0, tv_nsec: 0 };
        // SAFETY: `t` is a valid timespec for the call to write; the clock id is a constant.
        if unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) } == 0 {
            return t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9;
        }
    }
    static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    START.get_or_init(std::time::Instant::now).elapsed().as_secs_f64()
}

/// Why a seed's run could not be analysed.
#[derive(Debug, thiserror::Error)]
pub enum AnalysisError {
    /// Its records could not be made.
    #[error(transparent)]
    Records(#[from] RecordFailure),
}

/// One seed's run and everything found in it.
pub struct SeedAnalysis {
    /// The run.
    pub run: RunOutput,
    /// Its events.
    pub catalogue: Catalogue,
    /// What the base did: stick-slip, stable sliding or no slip.
    pub diagnosis: events::Diagnosis,
    /// Every event at prototype scale, in catalogue order.
    pub scaled: Vec<ScaledEvent>,
    /// The prototype length ratio λ the records scale with.
    pub lambda: f64,
    /// Its records (and their spectra), if asked.
    pub records: Option<SeedRecords>,
    /// Its bar breaks as acoustic-emission events, when the bars crack.
    pub emission: Option<Vec<Cluster>>,
    /// The rupture front of each event, when the scene records slip onsets or the fault.
    pub fronts: Option<SeedFronts>,
    /// CPU seconds spent finding the events, scaling them and their fronts, and a fault's
    /// source and stations (a profile; the records' stages are in [`SeedRecords::timings`], the
    /// broadband records' in [`source::StochasticSource`]).
    pub events_s: f64,
    /// On a fault (docs/model.md §15): the source from the fault's own slip, and the stations'
    /// distances to the rupture and peak motions.
    pub source: Option<Source>,
    /// The stations of a fault scene against its rupture (empty otherwise).
    pub stations: Vec<StationRow>,
}

/// Analyses one finished run of `model` as `settings` ask; `plans` holds the spectra's plans,
/// shared by every seed of an ensemble. Setting `cancel` stops it between two records' windows
/// ([`RecordFailure::Cancelled`]).
pub fn analyse(
    run: RunOutput,
    model: &Model,
    settings: &Settings,
    plans: &PlanCache,
    cancel: &std::sync::atomic::AtomicBool,
) -> Result<SeedAnalysis, AnalysisError> {
    let started = thread_cpu_s();
    let catalogue = events::catalogue(&run.recording, model, &settings.events);
    let diagnosis = events::diagnose(&run.recording, &catalogue, model);
    let scaled = events::scaled_events(&catalogue, model, &settings.similarity);
    let mut events_s = thread_cpu_s() - started;
    let records = match &settings.accelerograms {
        Some(acc) => Some(records::compute(
            &run.recording,
            &catalogue,
            model,
            acc,
            settings.spectra.as_ref(),
            settings.events.smoothing_s,
            plans,
            cancel,
        )?),
        None => None,
    };
    let started = thread_cpu_s();
    let emission = settings.emission.as_ref().map(|p| emission::emission(&run.recording.cracks, model.lattice(), p));
    let fronts = fronts::fronts(
        &run.recording,
        &catalogue,
        model,
        settings.events.smoothing_s,
        settings.events.rupture_rate_m_s,
    );
    let lambda = events::lambda(model, &settings.similarity);
    let mut source = source::source(&run.recording, model);
    let mut stations = source.as_ref().map_or_else(Vec::new, |s| source::stations(&run.recording, model, s));
    if let (Some(src), Some(bb)) = (source.as_mut(), settings.broadband.as_ref()) {
        let (rows, stochastic) = broadband::records(stations, &run.recording, model, src, bb, run.seed);
        stations = rows;
        src.stochastic = stochastic;
    }
    if let Some(src) = source.as_mut() {
        // The surface stations (depth 0) with a processed record, each scene station once (a
        // station simulated on several sites has one lattice record).
        let mut seen = std::collections::HashSet::new();
        let surface = stations
            .iter()
            .filter(|s| s.position_m[1] == 0.0 && seen.insert(s.station.node))
            .filter_map(|s| s.motion.as_ref().ok().map(|m| (m, s.hypocentral_m)));
        src.fitted_corner_hz = motions::fitted_corner(surface).map(|b| b.corner_hz);
    }
    events_s += thread_cpu_s() - started;
    // The broadband records have their own stages in the profile.
    if let Some(h) = source.as_ref().and_then(|s| s.stochastic.as_ref()) {
        events_s -= h.synthesis_cpu_s + h.motions_cpu_s;
    }
    Ok(SeedAnalysis {
        run,
        catalogue,
        diagnosis,
        scaled,
        lambda,
        records,
        emission,
        fronts,
        events_s,
        source,
        stations,
    })
}
