//! The catalogue statistics of an ensemble, from its gathered `similarity` table (every event at
//! prototype scale) and `runs` table: magnitude–frequency distributions and b-values, recurrence
//! statistics, stacked aftershock rates with Omori–Utsu fits, and scaling relations — per seed and
//! pooled over the seeds. The numerics are `stickslip_seismo::catalogue`; this module chooses the
//! inputs and the settings, written here once:
//!
//! - magnitudes in bins of [`MAGNITUDE_BIN`]; completeness by goodness of fit at
//!   [`GOF_LEVEL_PERCENT`]%, or where that level is not reached, by maximum curvature + 0.2;
//! - moment and stress drop in [`LOG_BINS_PER_DECADE`] logarithmic bins per decade;
//! - recurrence of main shocks and of all events from their start times (model-scale seconds),
//!   intervals taken within each seed and pooled; CV interval by bootstrap (2,000 resamples);
//! - aftershocks: every event after a main shock until the next main shock or the end of the run,
//!   stacked over main shocks (and seeds), rates in 5 logarithmic bins per decade, Omori–Utsu
//!   fitted from the earliest aftershock time's decade to the longest window;
//! - scaling: consistent moment (N·m) against prototype rupture area and prototype duration, and
//!   stress drop against Mw (consistent), beside the self-similar exponents 3/2, 3 and 0.

use std::collections::BTreeMap;

use polars::prelude::DataFrame;
use stickslip_seismo::catalogue::FitError;
use stickslip_seismo::catalogue::aftershocks::{
    StackedAftershocks, Window, aftershock_rate, fit_omori, stack_aftershocks,
};
use stickslip_seismo::catalogue::magnitude_frequency::{
    MAXC_CORRECTION, MIN_EVENTS_B_VALUE, log_binned_distribution, magnitude_distribution,
};
use stickslip_seismo::catalogue::recurrence::{
    cv_bootstrap_ci, fit_bpt, fit_exponential, fit_weibull, inter_event_times, recurrence_statistics,
};
use stickslip_seismo::catalogue::scaling::{
    self, SELF_SIMILAR_MOMENT_AREA, SELF_SIMILAR_MOMENT_DURATION, SELF_SIMILAR_STRESS_DROP_MAGNITUDE,
};
use stickslip_store::frame::Columns;
use stickslip_store::io::{read_parquet_if_present, write_parquet_atomic};
use stickslip_store::schema::{
    AFTERSHOCKS_TABLE, B_VALUES, EVENTS_TABLE, MAGNITUDE_FREQUENCY, OMORI, RECURRENCE_STATS, RUNS, SCALING, SIMILARITY,
    col,
};
use stickslip_store::tables::catalogue::{
    AftershockBin, BValueRow, FrequencyBin, OmoriRow, RecurrenceRow, ScalingRow, aftershocks_frame, b_values_frame,
    magnitude_frequency_frame, omori_frame, recurrence_stats_frame, scaling_frame,
};
use stickslip_store::{Folder, StoreError};

/// Magnitude bin width.
pub const MAGNITUDE_BIN: f64 = 0.1;
/// Goodness-of-fit level of the completeness magnitude (percent).
pub const GOF_LEVEL_PERCENT: f64 = 90.0;
/// Logarithmic bins per decade of moment and stress drop.
pub const LOG_BINS_PER_DECADE: usize = 5;
/// Logarithmic bins per decade of the aftershock rate.
pub const AFTERSHOCK_BINS_PER_DECADE: usize = 5;

/// The magnitude columns of the similarity table that get a distribution and a b-value.
pub const MAGNITUDES: [&str; 4] =
    [col::MW_CONSISTENT, col::MW_PAPER, col::M_RIERA_PAPER_INTERPLATE, col::M_RIERA_CONSISTENT_INTERPLATE];
/// What each column of [`MAGNITUDES`] is (docs/model.md §9): the same events' two moments, each
/// through two magnitude scales.
pub fn magnitude_convention(column: &str) -> &'static str {
    match column {
        col::MW_CONSISTENT => "Mw = (2/3)·log10 M0 − 10.7 of the consistent moment Δσ·L_p·A_p (the page's \"Mw\")",
        col::MW_PAPER => "Mw of the paper's moment Δσ·L_p·A_p·λ (Eq. 15 as printed)",
        col::M_RIERA_PAPER_INTERPLATE => {
            "Riera's M = 0.6536·(log10 M0 − 15.51) of the paper's moment: the \"M (paper)\" of the pipeline's \
             printout and the paper's M = 6.77"
        }
        col::M_RIERA_CONSISTENT_INTERPLATE => "Riera's M of the consistent moment",
        _ => "",
    }
}

/// Magnitude units above Mc that a b-value needs before it is read as the slope of a power law: a
/// maximum-likelihood b from a narrower range measures how closely the sizes cluster, and moves
/// with where the bins fall (on paper-100, b over 2–3 bins, 0.2–0.3 units, was 3.45–7.35 for four scales
/// that a power law would give within 2% of each other).
pub const B_VALUE_MIN_RANGE: f64 = 1.0;

/// The columns counted in logarithmic bins.
pub const LOG_QUANTITIES: [&str; 2] = [col::M0_CONSISTENT_DYNE_CM, col::STRESS_DROP_PA];

/// Dyne·cm in N·m.
const DYNE_CM: f64 = 1e-7;

/// The catalogue tables' rows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CatalogueStats {
    /// Magnitude–frequency bins.
    pub frequency: Vec<FrequencyBin>,
    /// Gutenberg–Richter fits.
    pub b_values: Vec<BValueRow>,
    /// Recurrence statistics.
    pub recurrence: Vec<RecurrenceRow>,
    /// Aftershock rate bins.
    pub aftershocks: Vec<AftershockBin>,
    /// Omori–Utsu fits.
    pub omori: Vec<OmoriRow>,
    /// Scaling relations.
    pub scaling: Vec<ScalingRow>,
}

/// The events of one seed (or of all), column by column.
#[derive(Clone, Debug, Default)]
struct Catalogue {
    start_s: Vec<f64>,
    main: Vec<bool>,
    columns: BTreeMap<&'static str, Vec<f64>>,
}

impl Catalogue {
    fn column(&self, name: &str) -> &[f64] {
        self.columns.get(name).map(Vec::as_slice).unwrap_or(&[])
    }

    fn extend(&mut self, other: &Catalogue) {
        self.start_s.extend(&other.start_s);
        self.main.extend(&other.main);
        for (k, v) in &other.columns {
            self.columns.entry(k).or_default().extend(v);
        }
    }

    fn main_times(&self) -> Vec<f64> {
        self.start_s.iter().zip(&self.main).filter(|(_, m)| **m).map(|(t, _)| *t).collect()
    }
}

/// Computes the catalogue statistics of the gathered `runs`, `events` and `similarity` tables and
/// writes the six catalogue tables of `out`.
pub fn write_catalogue(
    out: &Folder,
    runs: &DataFrame,
    events: &DataFrame,
    similarity: &DataFrame,
) -> Result<CatalogueStats, StoreError> {
    let stats = catalogue_stats(runs, events, similarity)?;
    write_catalogue_tables(out, &stats)?;
    Ok(stats)
}

/// Recomputes the catalogue tables of a gathered output folder (e.g. one written before they
/// existed); `None` if it has no gathered events yet.
pub fn rewrite_catalogue(out: &Folder) -> Result<Option<CatalogueStats>, StoreError> {
    let read = |t| read_parquet_if_present(&out.gathered(&t));
    match (read(RUNS)?, read(EVENTS_TABLE)?, read(SIMILARITY)?) {
        (Some(r), Some(e), Some(s)) => write_catalogue(out, &r, &e, &s).map(Some),
        _ => Ok(None),
    }
}

fn reason<T>(r: Result<T, FitError>) -> Result<T, String> {
    r.map_err(|e| e.to_string())
}

/// The catalogue statistics of the events in `similarity` (gathered similarity table, which
/// carries start times through `events`) of the seeds finished in `runs`.
pub fn catalogue_stats(
    runs: &DataFrame,
    events: &DataFrame,
    similarity: &DataFrame,
) -> Result<CatalogueStats, StoreError> {
    let r = Columns::of(runs, RUNS.name);
    let run_end: BTreeMap<u64, f64> = r.u64s(col::SEED)?.into_iter().zip(r.f64s(col::SIMULATED_TIME_S)?).collect();
    let e = Columns::of(events, EVENTS_TABLE.name);
    let s = Columns::of(similarity, SIMILARITY.name);
    let seeds = s.u64s(col::SEED)?;
    if e.height() != s.height() || e.u64s(col::SEED)? != seeds {
        return Err(StoreError::Corrupt {
            path: SIMILARITY.name.into(),
            what: "the events and similarity tables list different events".into(),
        });
    }
    let start = e.f64s(col::START_S)?;
    let kind = s.strs(col::KIND)?;
    let mut columns: BTreeMap<&'static str, Vec<f64>> = BTreeMap::new();
    for name in MAGNITUDES.into_iter().chain(LOG_QUANTITIES).chain([col::PROTOTYPE_AREA_M2, col::PROTOTYPE_DURATION_S])
    {
        columns.insert(name, s.f64s(name)?);
    }
    let mut per_seed: BTreeMap<u64, Catalogue> = run_end.keys().map(|&k| (k, Catalogue::default())).collect();
    for i in 0..seeds.len() {
        let c = per_seed.entry(seeds[i]).or_default();
        c.start_s.push(start[i]);
        c.main.push(kind[i] == "main");
        for (k, v) in &columns {
            c.columns.entry(k).or_default().push(v[i]);
        }
    }
    let per_seed =
        per_seed.into_iter().map(|(k, c)| (k, (c, run_end.get(&k).copied().unwrap_or(f64::INFINITY)))).collect();
    Ok(statistics(&per_seed, &MAGNITUDES, true))
}

/// Per seed (when there are several) and pooled: the distributions and b-values of
/// `magnitudes`, the recurrence of main shocks and of all events, the stacked aftershocks with
/// their Omori–Utsu fit and the scaling relations (stress drop against magnitude only when
/// `stress_drop`). Each seed's catalogue comes with its run's end (s).
fn statistics(
    per_seed: &BTreeMap<u64, (Catalogue, f64)>,
    magnitudes: &[&'static str],
    stress_drop: bool,
) -> CatalogueStats {
    let mut out = CatalogueStats::default();
    let mut pooled = Catalogue::default();
    let mut pooled_main = Vec::new();
    let mut pooled_all = Vec::new();
    let mut stacks = Vec::new();
    for (&seed, (c, end)) in per_seed {
        pooled.extend(c);
        let main = inter_event_times(&c.main_times());
        let all = inter_event_times(&c.start_s);
        let stack = stack(c, *end);
        if per_seed.len() > 1 {
            distributions(Some(seed), c, magnitudes, &mut out);
            out.recurrence.push(recurrence(Some(seed), "main", &main));
            out.recurrence.push(recurrence(Some(seed), "all", &all));
            aftershocks(Some(seed), c.main_times().len(), &stack, &mut out);
            scalings(Some(seed), c, stress_drop, &mut out);
        }
        pooled_main.extend(main);
        pooled_all.extend(all);
        stacks.push(stack);
    }
    distributions(None, &pooled, magnitudes, &mut out);
    out.recurrence.push(recurrence(None, "main", &pooled_main));
    out.recurrence.push(recurrence(None, "all", &pooled_all));
    let mut stacked = StackedAftershocks { times: Vec::new(), windows: Vec::new(), counts: Vec::new() };
    for st in stacks.into_iter().flatten() {
        stacked.times.extend(st.times);
        stacked.windows.extend(st.windows);
        stacked.counts.extend(st.counts);
    }
    stacked.times.sort_by(f64::total_cmp);
    aftershocks(None, pooled.main_times().len(), &Ok(stacked), &mut out);
    scalings(None, &pooled, stress_drop, &mut out);
    out
}

/// One seed's events of a cycle run, for [`cycle_catalogue_stats`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CycleCatalogue {
    /// The seed.
    pub seed: u64,
    /// The run's end (s).
    pub end_s: f64,
    /// Each event's onset (s).
    pub onset_s: Vec<f64>,
    /// Its moment magnitude.
    pub magnitude: Vec<f64>,
    /// Its seismic moment (N·m).
    pub moment_n_m: Vec<f64>,
    /// Its rupture area (m²).
    pub area_m2: Vec<f64>,
    /// Its duration (s).
    pub duration_s: Vec<f64>,
    /// Whether it is a main shock.
    pub main: Vec<bool>,
}

/// The magnitude column of a cycle run's catalogue.
pub const CYCLE_MAGNITUDE: &str = "magnitude";

/// The catalogue statistics of a cycle run's seeds, as [`catalogue_stats`] computes them for an
/// ensemble's events (no stress drop: a cycle event has none of its own).
pub fn cycle_catalogue_stats(seeds: &[CycleCatalogue]) -> CatalogueStats {
    let per_seed = seeds
        .iter()
        .map(|c| {
            let mut columns = BTreeMap::new();
            columns.insert(CYCLE_MAGNITUDE, c.magnitude.clone());
            columns.insert(col::M0_CONSISTENT_DYNE_CM, c.moment_n_m.iter().map(|m| m / DYNE_CM).collect());
            columns.insert(col::PROTOTYPE_AREA_M2, c.area_m2.clone());
            columns.insert(col::PROTOTYPE_DURATION_S, c.duration_s.clone());
            (c.seed, (Catalogue { start_s: c.onset_s.clone(), main: c.main.clone(), columns }, c.end_s))
        })
        .collect();
    statistics(&per_seed, &[CYCLE_MAGNITUDE], false)
}

/// Writes the six catalogue tables of `stats` under `out`'s tables.
pub fn write_catalogue_tables(out: &Folder, stats: &CatalogueStats) -> Result<(), StoreError> {
    let frames = [
        (MAGNITUDE_FREQUENCY, magnitude_frequency_frame(&stats.frequency)?),
        (B_VALUES, b_values_frame(&stats.b_values)?),
        (RECURRENCE_STATS, recurrence_stats_frame(&stats.recurrence)?),
        (AFTERSHOCKS_TABLE, aftershocks_frame(&stats.aftershocks)?),
        (OMORI, omori_frame(&stats.omori)?),
        (SCALING, scaling_frame(&stats.scaling)?),
    ];
    for (table, mut df) in frames {
        write_parquet_atomic(&mut df, &out.gathered(&table))?;
    }
    Ok(())
}

fn distributions(seed: Option<u64>, c: &Catalogue, magnitudes: &[&'static str], out: &mut CatalogueStats) {
    for &quantity in magnitudes {
        let m = c.column(quantity);
        let events = m.iter().filter(|v| v.is_finite()).count() as u64;
        let dist = magnitude_distribution(m, MAGNITUDE_BIN);
        let (mut mc_maxc, mut mc_gof) = (None, None);
        let fit = match &dist {
            Err(e) => Err(e.to_string()),
            Ok(d) => {
                mc_maxc = d.mc_maximum_curvature(MAXC_CORRECTION).ok();
                let gof = d.mc_goodness_of_fit(GOF_LEVEL_PERCENT);
                if let Ok(g) = &gof {
                    mc_gof = Some((g.mc, g.trials.iter().find(|t| t.mc == g.mc).map_or(f64::NAN, |t| t.fit_percent)));
                }
                let fit = match (gof, mc_maxc) {
                    _ if (events as usize) < MIN_EVENTS_B_VALUE => Err(FitError::TooFew {
                        what: "events in the catalogue (a b-value needs them at or above Mc)",
                        have: events as usize,
                        need: MIN_EVENTS_B_VALUE,
                    }
                    .to_string()),
                    (Ok(g), _) => Ok(g.fit),
                    (Err(_), Some(mc)) => reason(d.b_value(mc)),
                    (Err(e), None) => Err(e.to_string()),
                };
                let fitted = fit.as_ref().ok();
                for i in 0..d.magnitudes.len() {
                    let centre = d.magnitudes[i];
                    out.frequency.push(FrequencyBin {
                        seed,
                        quantity: quantity.to_string(),
                        low: centre - MAGNITUDE_BIN / 2.0,
                        centre,
                        high: centre + MAGNITUDE_BIN / 2.0,
                        incremental: d.incremental[i] as u64,
                        cumulative: d.cumulative[i] as u64,
                        fit_cumulative: fitted.filter(|f| centre >= f.mc - 1e-9).map(|f| f.expected_cumulative(centre)),
                    });
                }
                fit
            }
        };
        out.b_values.push(BValueRow { seed, quantity: quantity.to_string(), events, mc_maxc, mc_gof, fit });
    }
    for quantity in LOG_QUANTITIES {
        let Ok(d) = log_binned_distribution(c.column(quantity), LOG_BINS_PER_DECADE) else { continue };
        for i in 0..d.incremental.len() {
            let (low, high) = (d.edges[i], d.edges[i + 1]);
            out.frequency.push(FrequencyBin {
                seed,
                quantity: quantity.to_string(),
                low,
                centre: (low * high).sqrt(),
                high,
                incremental: d.incremental[i] as u64,
                cumulative: d.cumulative[i] as u64,
                fit_cumulative: None,
            });
        }
    }
}

fn recurrence(seed: Option<u64>, sequence: &'static str, intervals: &[f64]) -> RecurrenceRow {
    RecurrenceRow {
        seed,
        sequence,
        intervals: intervals.len() as u64,
        stats: reason(recurrence_statistics(intervals)),
        cv_ci95: cv_bootstrap_ci(intervals, 0.95, 2000, 1).ok(),
        bpt: reason(fit_bpt(intervals)),
        weibull: reason(fit_weibull(intervals)),
        exponential: reason(fit_exponential(intervals)),
    }
}

fn stack(c: &Catalogue, end: f64) -> Result<StackedAftershocks, FitError> {
    let window = Window { max_time: end, stop_at_next_main_shock: true, catalogue_end: end };
    stack_aftershocks(&c.main_times(), &c.start_s, window)
}

fn aftershocks(
    seed: Option<u64>,
    main_shocks: usize,
    stack: &Result<StackedAftershocks, FitError>,
    out: &mut CatalogueStats,
) {
    let (aftershocks, fit) = match stack {
        Err(e) => (0, Err(e.to_string())),
        Ok(st) => {
            let first = st.times.first().copied().unwrap_or(0.0);
            let longest = st.windows.iter().copied().fold(0.0, f64::max);
            let fit = if st.times.is_empty() {
                Err(FitError::TooFew { what: "aftershocks", have: 0, need: 1 }.to_string())
            } else {
                let t_min = 10f64.powf(first.log10().floor());
                let fit = reason(fit_omori(st, t_min, longest));
                if let Ok(bins) = aftershock_rate(st, t_min, longest, AFTERSHOCK_BINS_PER_DECADE) {
                    for bin in bins {
                        let omori_rate = fit.as_ref().ok().map(|f| f.rate(bin.centre));
                        out.aftershocks.push(AftershockBin { seed, bin, omori_rate });
                    }
                }
                fit
            };
            (st.times.len() as u64, fit)
        }
    };
    out.omori.push(OmoriRow { seed, main_shocks: main_shocks as u64, aftershocks, fit });
}

fn scalings(seed: Option<u64>, c: &Catalogue, stress_drop: bool, out: &mut CatalogueStats) {
    let moment: Vec<f64> = c.column(col::M0_CONSISTENT_DYNE_CM).iter().map(|m| m * DYNE_CM).collect();
    let relations = [
        ("moment_area", SELF_SIMILAR_MOMENT_AREA, scaling::moment_area(c.column(col::PROTOTYPE_AREA_M2), &moment)),
        (
            "moment_duration",
            SELF_SIMILAR_MOMENT_DURATION,
            scaling::moment_duration(c.column(col::PROTOTYPE_DURATION_S), &moment),
        ),
        (
            "stress_drop_magnitude",
            SELF_SIMILAR_STRESS_DROP_MAGNITUDE,
            scaling::stress_drop_magnitude(c.column(col::MW_CONSISTENT), c.column(col::STRESS_DROP_PA)),
        ),
    ];
    for (relation, self_similar, fit) in relations {
        if relation == "stress_drop_magnitude" && !stress_drop {
            continue;
        }
        out.scaling.push(ScalingRow { seed, relation, self_similar, fit: reason(fit) });
    }
}
