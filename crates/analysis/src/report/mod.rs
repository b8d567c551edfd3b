//! The report of a pipeline run: the paper's figures for any ensemble, spectra with bands across
//! seeds, event catalogue views, attenuation, energy, and a plain HTML page that links them all.
//!
//! Written to `<out>/figures/*.png` and `<out>/index.html` after the tables are gathered. Every
//! figure reads the tables on disk; a figure whose data is absent is skipped, not drawn empty.

pub(crate) mod charts;
mod figures;
mod html;
pub mod plot;

use std::path::{Path, PathBuf};

use polars::prelude::*;
use serde::{Deserialize, Serialize};

use crate::ensemble::part_path;
use crate::error::AnalysisError;
use crate::pipeline::Pipeline;
use crate::tables::read_parquet;

/// `[report]`: the report stage (pipeline section).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct ReportParams {
    /// Write the report after the tables. Default true.
    pub enabled: bool,
    /// Seeds drawn one by one in the time-history figures; empty = the first four successful
    /// seeds of the pipeline.
    pub seeds: Vec<i64>,
}

impl Default for ReportParams {
    fn default() -> Self {
        ReportParams { enabled: true, seeds: vec![] }
    }
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
}

/// What the report stage wrote.
#[derive(Clone, Debug, PartialEq)]
pub struct ReportSummary {
    /// The page.
    pub index: PathBuf,
    /// The figures drawn.
    pub figures: Vec<Figure>,
    /// Figures skipped for lack of data, with the reason.
    pub skipped: Vec<(String, String)>,
}

/// Tables the report reads, loaded once.
pub(crate) struct Data<'a> {
    pub out: &'a Path,
    pub pipeline: &'a Pipeline,
    pub runs: Option<DataFrame>,
    pub events: Option<DataFrame>,
    pub similarity: Option<DataFrame>,
    pub summary: Option<DataFrame>,
    pub psa_stats: Option<DataFrame>,
    pub attenuation: Option<DataFrame>,
    pub attenuation_fit: Option<DataFrame>,
    /// Seeds drawn one by one (successful, at most four).
    pub seeds: Vec<u64>,
}

impl<'a> Data<'a> {
    fn load(out: &'a Path, pipeline: &'a Pipeline, params: &ReportParams) -> Result<Self, AnalysisError> {
        let table = |name: &str| -> Result<Option<DataFrame>, AnalysisError> {
            let p = out.join("tables").join(format!("{name}.parquet"));
            if p.exists() { read_parquet(&p).map(Some) } else { Ok(None) }
        };
        let runs = table("runs")?;
        let ok: Vec<u64> = match &runs {
            Some(r) => {
                let seeds = col_u64(r, "seed")?;
                let status = col_str(r, "status")?;
                seeds.into_iter().zip(status).filter(|(_, s)| s == "ok").map(|(s, _)| s).collect()
            }
            None => vec![],
        };
        let wanted: Vec<u64> = if params.seeds.is_empty() {
            pipeline.seeds.iter().copied().filter(|s| ok.contains(s)).take(4).collect()
        } else {
            params.seeds.iter().filter_map(|&s| u64::try_from(s).ok()).filter(|s| ok.contains(s)).collect()
        };
        Ok(Data {
            out,
            pipeline,
            runs,
            events: table("events")?,
            similarity: table("similarity")?,
            summary: table("summary")?,
            psa_stats: table("psa_stats")?,
            attenuation: table("attenuation")?,
            attenuation_fit: table("attenuation_fit")?,
            seeds: wanted,
        })
    }

    /// A per-seed part, if present.
    pub fn part(&self, table: &str, seed: u64) -> Result<Option<DataFrame>, AnalysisError> {
        let p = part_path(self.out, table, seed);
        if p.exists() { read_parquet(&p).map(Some) } else { Ok(None) }
    }
}

/// Column `name` as f64 (cast), nulls as NaN.
pub(crate) fn col_f64(df: &DataFrame, name: &str) -> Result<Vec<f64>, AnalysisError> {
    let t = |e| AnalysisError::table(format!("report ({name})"), e);
    let c = df.column(name).map_err(t)?.cast(&DataType::Float64).map_err(t)?;
    Ok(c.f64().map_err(t)?.iter().map(|v| v.unwrap_or(f64::NAN)).collect())
}

/// Column `name` as u64 (cast).
pub(crate) fn col_u64(df: &DataFrame, name: &str) -> Result<Vec<u64>, AnalysisError> {
    let t = |e| AnalysisError::table(format!("report ({name})"), e);
    let c = df.column(name).map_err(t)?.cast(&DataType::UInt64).map_err(t)?;
    Ok(c.u64().map_err(t)?.iter().map(|v| v.unwrap_or(0)).collect())
}

/// Column `name` as strings.
pub(crate) fn col_str(df: &DataFrame, name: &str) -> Result<Vec<String>, AnalysisError> {
    let t = |e| AnalysisError::table(format!("report ({name})"), e);
    Ok(df.column(name).map_err(t)?.str().map_err(t)?.iter().map(|v| v.unwrap_or("").to_string()).collect())
}

/// Whether `df` has column `name`.
pub(crate) fn has(df: &DataFrame, name: &str) -> bool {
    df.column(name).is_ok()
}

/// Draws every figure whose data is present and writes `<out>/index.html`.
pub fn write_report(out: &Path, pipeline: &Pipeline, params: &ReportParams) -> Result<ReportSummary, AnalysisError> {
    plot::register_fonts();
    let data = Data::load(out, pipeline, params)?;
    let dir = out.join("figures");
    std::fs::create_dir_all(&dir).map_err(|e| AnalysisError::io(&dir, e))?;
    let mut drawn = Vec::new();
    let mut skipped = Vec::new();
    for (file, draw) in figures::ALL {
        let path = dir.join(file);
        // Draw into a temporary file, then rename: a reader never sees half a figure.
        let tmp = dir.join(format!(".{file}.{}.tmp.png", std::process::id()));
        match draw(&data, &tmp)? {
            figures::Outcome::Drawn { title, caption } => {
                std::fs::rename(&tmp, &path).map_err(|e| AnalysisError::io(&path, e))?;
                drawn.push(Figure { file: file.to_string(), title, caption });
            }
            figures::Outcome::Skipped(why) => {
                let _ = std::fs::remove_file(&tmp);
                let _ = std::fs::remove_file(&path);
                skipped.push((file.to_string(), why));
            }
        }
    }
    let index = out.join("index.html");
    crate::tables::write_text_atomic(&index, &html::page(&data, &drawn, &skipped)?)?;
    Ok(ReportSummary { index, figures: drawn, skipped })
}
