//! stickslip report: the figures and the HTML page of an output folder.
//!
//! Owns: what a reader sees of a run — the paper's figures for any ensemble, spectra with bands
//! across seeds, event catalogue views, attenuation, energy, cracks and acoustic emission
//! ([`figures`], drawn with the chart
//! shapes of [`charts`]), and a plain HTML page that links them all ([`html`]). It reads only the
//! output folder, through the store's typed readers ([`ReportInput`]), and the pipeline that made
//! it. Must not know: how the tables were computed or scheduled; the command line.
//!
//! Written to `<out>/figures/*.png` and `<out>/index.html`. A figure whose data is absent is
//! skipped, not drawn empty.
#![deny(missing_docs)]

pub mod charts;
pub mod clip;
pub mod figures;
mod html;
pub mod place;
pub mod plot;

use std::path::{Path, PathBuf};

use polars::prelude::DataFrame;
use stickslip_config::Pipeline;
use stickslip_store::io::{read_parquet_if_present, write_text_atomic};
use stickslip_store::schema::{
    ACOUSTIC_EMISSION, ATTENUATION, ATTENUATION_FIT, CRACKS, EVENTS_TABLE, PSA_STATS, RECORDS, RUNS, RUPTURE_ONSETS,
    RUPTURES, SIMILARITY, SUMMARY, TableSpec,
};
use stickslip_store::tables::cracks::{AcousticEmission, Cracks};
use stickslip_store::tables::events::{Events, Similarity};
use stickslip_store::tables::fronts::{RuptureOnsets, Ruptures};
use stickslip_store::tables::records::{Attenuation, Records};
use stickslip_store::tables::runs::Runs;
use stickslip_store::tables::stats::{AttenuationFit, PsaStats, SummaryTable};
use stickslip_store::{Folder, StoreError};

/// Everything that can go wrong writing a report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A table could not be read, or the page written.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// A figure could not be drawn.
    #[error("figure {figure}: {what}")]
    Plot {
        /// The figure's file.
        figure: String,
        /// What went wrong.
        what: String,
    },
    /// A file could not be moved into place.
    #[error("{}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}

/// A figure of the report.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// File name inside `figures/`.
    pub file: String,
    /// Heading.
    pub title: String,
    /// What it shows.
    pub caption: String,
    /// The titles drawn on the image (the figure's, then each panel's).
    pub headings: Vec<String>,
    /// The name of each panel (e.g. the seed and node it shows; empty for an unnamed panel).
    pub panels: Vec<String>,
    /// Labels left out because no spot near their anchor was free of data and other labels.
    pub dropped: Vec<String>,
}

/// What the report wrote.
#[derive(Clone, Debug, PartialEq)]
pub struct ReportSummary {
    /// The page.
    pub index: PathBuf,
    /// The figures drawn.
    pub figures: Vec<Figure>,
    /// Figures skipped for lack of data, with the reason.
    pub skipped: Vec<(String, String)>,
}

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
    /// Mean Δt over the seeds (s), if any finished.
    pub mean_dt_s: Option<f64>,
    /// Seeds drawn one by one (successful, at most four unless the pipeline names them).
    pub seeds: Vec<u64>,
}

impl<'a> ReportInput<'a> {
    /// Reads the tables of `out` that the report uses.
    pub fn load(out: &Path, pipeline: &'a Pipeline) -> Result<Self, ReportError> {
        let folder = Folder::new(out);
        let table = |t: &TableSpec| read_parquet_if_present(&folder.gathered(t));
        let runs_df = table(&RUNS)?;
        let runs = runs_df.as_ref().map(Runs::read).transpose()?;
        let ok = runs.as_ref().map(Runs::ok_seeds).unwrap_or_default();
        let seeds: Vec<u64> = if pipeline.report.seeds.is_empty() {
            pipeline.seeds.iter().copied().filter(|s| ok.contains(s)).take(4).collect()
        } else {
            pipeline.report.seeds.iter().copied().filter(|s| ok.contains(s)).collect()
        };
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
        Ok(ReportInput {
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
            mean_dt_s,
            seeds,
            folder,
            pipeline,
        })
    }

    /// A per-seed part, if present.
    pub fn part(&self, table: &TableSpec, seed: u64) -> Result<Option<DataFrame>, ReportError> {
        Ok(read_parquet_if_present(&self.folder.part(table, seed))?)
    }
}

/// Draws every figure whose data is present and writes `<out>/index.html`.
pub fn write_report(out: &Path, pipeline: &Pipeline) -> Result<ReportSummary, ReportError> {
    plot::register_fonts();
    let input = ReportInput::load(out, pipeline)?;
    let dir = input.folder.figures();
    std::fs::create_dir_all(&dir).map_err(|e| ReportError::Io { path: dir.clone(), source: e })?;
    let mut drawn = Vec::new();
    let mut skipped = Vec::new();
    for (file, draw) in figures::ALL {
        let path = dir.join(file);
        // Draw into a temporary file, then rename: a reader never sees half a figure.
        let tmp = dir.join(format!(".{file}.{}.tmp.png", std::process::id()));
        match draw(&input, &tmp)? {
            figures::Outcome::Drawn { title, caption, headings, panels, dropped } => {
                std::fs::rename(&tmp, &path).map_err(|e| ReportError::Io { path: path.clone(), source: e })?;
                drawn.push(Figure { file: file.to_string(), title, caption, headings, panels, dropped });
            }
            figures::Outcome::Skipped(why) => {
                let _ = std::fs::remove_file(&tmp);
                let _ = std::fs::remove_file(&path);
                skipped.push((file.to_string(), why));
            }
        }
    }
    let index = input.folder.index();
    write_text_atomic(&index, &html::page(&input, &drawn, &skipped)?)?;
    Ok(ReportSummary { index, figures: drawn, skipped })
}
