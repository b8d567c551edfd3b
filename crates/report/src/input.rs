//! What the figures and the page read of an output folder: the pipeline that made it, the tables
//! across seeds through the store's typed readers, and the per-seed parts on demand.

use std::path::Path;

use polars::prelude::DataFrame;
use stickslip_config::Pipeline;
use stickslip_config::set::{SetSettings, read_set_file};
use stickslip_store::Folder;
use stickslip_store::io::read_parquet_if_present;
use stickslip_store::schema::{
    ACOUSTIC_EMISSION, ATTENUATION, ATTENUATION_FIT, CRACKS, EVENTS_TABLE, PSA_STATS, RECORDS, RUNS, RUPTURE_ONSETS,
    RUPTURES, SIMILARITY, SOURCE, STATIONS, SUMMARY, TableSpec,
};
use stickslip_store::tables::cracks::{AcousticEmission, Cracks};
use stickslip_store::tables::events::{Events, Similarity};
use stickslip_store::tables::fronts::{RuptureOnsets, Ruptures};
use stickslip_store::tables::records::{Attenuation, Records};
use stickslip_store::tables::runs::Runs;
use stickslip_store::tables::source::{Sources, Stations};
use stickslip_store::tables::stats::{AttenuationFit, PsaStats, SummaryTable};

use crate::error::ReportError;

/// What the figures and the page read: the pipeline, the tables across seeds (typed), and the
/// per-seed parts on demand.
pub struct ReportInput<'a> {
    /// The output folder.
    pub folder: Folder,
    /// The pipeline that wrote it.
    pub pipeline: &'a Pipeline,
    /// Runs of every seed.
    pub runs: Option<Runs>,
    /// Every event.
    pub events: Option<Events>,
    /// Every event at prototype scale.
    pub similarity: Option<Similarity>,
    /// Statistics across seeds.
    pub summary: Option<SummaryTable>,
    /// PSA across seeds.
    pub psa_stats: Option<PsaStats>,
    /// Peak motions against distance.
    pub attenuation: Option<Attenuation>,
    /// Their fits.
    pub attenuation_fit: Option<AttenuationFit>,
    /// The per-event records cut by `[accelerograms]` (what, where, usable band).
    pub records: Option<Records>,
    /// The rupture front of each event (scenes that record the fault or slip onsets).
    pub ruptures: Option<Ruptures>,
    /// Each node's rupture time in each event.
    pub rupture_onsets: Option<RuptureOnsets>,
    /// Bars that softened or broke (scenes with `[rupture]`).
    pub cracks: Option<Cracks>,
    /// Acoustic-emission events (scenes with `[rupture]`).
    pub emission: Option<AcousticEmission>,
    /// The source of each seed whose fault ruptured (fault scenes).
    pub sources: Option<Sources>,
    /// The stations of each seed (fault scenes with `[[stations]]`).
    pub stations: Option<Stations>,
    /// Mean Δt over the seeds (s), if any finished.
    pub mean_dt_s: Option<f64>,
    /// The `[set]` the folder's record set was matched to: `set/set.toml`, written by `stickslip
    /// select --set FILE`, or else the pipeline's own.
    pub set: Option<SetSettings>,
    /// Whether the figures cite the paper (its figure numbers and reference values): see
    /// [`Pipeline::paper_references`].
    pub paper: bool,
    /// Why `[report] paper_figures` was not followed (the scene is not the paper's), if so.
    pub paper_note: Option<String>,
    /// Seeds drawn one by one: the successful seeds `[report] seeds` names, or else the first
    /// four that ran (see [`drawn_seeds`]).
    pub seeds: Vec<u64>,
    /// Seeds `[report] seeds` names that did not run here or failed (the page says so).
    pub not_drawn: Vec<u64>,
}

impl<'a> ReportInput<'a> {
    /// Reads the tables of `out` that the report uses.
    pub fn load(out: &Path, pipeline: &'a Pipeline) -> Result<Self, ReportError> {
        let folder = Folder::new(out);
        let table = |t: &TableSpec| read_parquet_if_present(&folder.gathered(t));
        let runs_df = table(&RUNS)?;
        let runs = runs_df.as_ref().map(Runs::read).transpose()?;
        let ok = runs.as_ref().map(Runs::ok_seeds).unwrap_or_default();
        let seeds = drawn_seeds(&ok, &pipeline.seeds, &pipeline.report.seeds);
        let not_drawn: Vec<u64> = pipeline.report.seeds.iter().copied().filter(|s| !ok.contains(s)).collect();
        let mean_dt_s = match &runs_df {
            Some(df) => {
                let dt: Vec<f64> = stickslip_store::frame::Columns::of(df, RUNS.name)
                    .f64s(stickslip_store::schema::col::DT_S)?
                    .into_iter()
                    .filter(|x| x.is_finite())
                    .collect();
                (!dt.is_empty()).then(|| dt.iter().sum::<f64>() / dt.len() as f64)
            }
            None => None,
        };
        let (paper, paper_note) = match pipeline.paper_references() {
            Ok(p) => (p, None),
            Err(why) => (false, Some(why)),
        };
        let set = chosen_set(&folder, pipeline);
        Ok(ReportInput {
            set,
            paper,
            paper_note,
            runs,
            events: table(&EVENTS_TABLE)?.as_ref().map(Events::read).transpose()?,
            similarity: table(&SIMILARITY)?.as_ref().map(Similarity::read).transpose()?,
            summary: table(&SUMMARY)?.as_ref().map(SummaryTable::read).transpose()?,
            psa_stats: table(&PSA_STATS)?.as_ref().map(PsaStats::read).transpose()?,
            attenuation: table(&ATTENUATION)?.as_ref().map(Attenuation::read).transpose()?,
            attenuation_fit: table(&ATTENUATION_FIT)?.as_ref().map(AttenuationFit::read).transpose()?,
            records: table(&RECORDS)?.as_ref().map(Records::read).transpose()?,
            ruptures: table(&RUPTURES)?.as_ref().map(Ruptures::read).transpose()?,
            rupture_onsets: table(&RUPTURE_ONSETS)?.as_ref().map(RuptureOnsets::read).transpose()?,
            cracks: table(&CRACKS)?.as_ref().map(Cracks::read).transpose()?,
            emission: table(&ACOUSTIC_EMISSION)?.as_ref().map(AcousticEmission::read).transpose()?,
            sources: table(&SOURCE)?.as_ref().map(Sources::read).transpose()?,
            stations: table(&STATIONS)?.as_ref().map(Stations::read).transpose()?,
            mean_dt_s,
            seeds,
            not_drawn,
            folder,
            pipeline,
        })
    }

    /// A per-seed part, if present.
    pub fn part(&self, table: &TableSpec, seed: u64) -> Result<Option<DataFrame>, ReportError> {
        Ok(read_parquet_if_present(&self.folder.part(table, seed))?)
    }
}

/// The `[set]` of `<folder>/set/set.toml` (what `stickslip select --set FILE` matched the set to),
/// or the pipeline's when there is none (or it no longer builds).
fn chosen_set(folder: &Folder, pipeline: &Pipeline) -> Option<SetSettings> {
    let kept = folder.set_dir().join("set.toml");
    kept.is_file().then(|| read_set_file(&kept, pipeline.set_pool()).ok()).flatten().or_else(|| pipeline.set.clone())
}

/// How many seeds the time-history figures draw when `[report] seeds` does not name them.
pub const DRAWN_SEEDS: usize = 4;

/// The seeds the time-history figures draw, from the seeds that ran (`ok`, successful): those of
/// `named` (`[report] seeds`) that ran; when it names none that ran (or nothing), the first
/// [`DRAWN_SEEDS`] that ran — the pipeline's own seeds first, in its order, then the others
/// (`stickslip run --seed N`, `pipeline --seeds …` outside the file's list) in increasing order.
pub fn drawn_seeds(ok: &[u64], pipeline: &[u64], named: &[u64]) -> Vec<u64> {
    let chosen: Vec<u64> = named.iter().copied().filter(|s| ok.contains(s)).collect();
    if !chosen.is_empty() {
        return chosen;
    }
    let mut others: Vec<u64> = ok.iter().copied().filter(|s| !pipeline.contains(s)).collect();
    others.sort_unstable();
    others.dedup();
    pipeline.iter().copied().filter(|s| ok.contains(s)).chain(others).take(DRAWN_SEEDS).collect()
}

#[cfg(test)]
mod tests {
    use super::drawn_seeds;

    #[test]
    fn the_seeds_drawn_are_those_that_ran() {
        // `stickslip run paper.toml --seed 1`: a seed outside the file's list.
        assert_eq!(drawn_seeds(&[1], &[123, 200, 7], &[]), vec![1]);
        // The file's order first, then the others in increasing order, four at most.
        assert_eq!(drawn_seeds(&[9, 2, 7, 123, 5], &[123, 200, 7], &[]), vec![123, 7, 2, 5]);
        // Named seeds that ran; a list naming none that ran falls back to those that did.
        assert_eq!(drawn_seeds(&[1, 2, 3], &[1, 2, 3], &[3, 8]), vec![3]);
        assert_eq!(drawn_seeds(&[1, 2], &[123], &[8]), vec![1, 2]);
        assert!(drawn_seeds(&[], &[1], &[]).is_empty());
    }
}
