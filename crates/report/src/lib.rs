//! stickslip report: the figures and the HTML page of an output folder.
//!
//! Owns: what a reader sees of a run — the paper's figures for any ensemble, spectra with bands
//! across seeds, event catalogue views, attenuation, energy, cracks and acoustic emission
//! ([`figures`], drawn with the chart shapes of [`charts`]), and a plain HTML page that links them
//! all ([`html`]). It reads only the output folder, through the store's typed readers
//! ([`ReportInput`]), and the pipeline that made it. Must not know: how the tables were computed or
//! scheduled; the command line.
//!
//! Written to `<out>/figures/*.png` and `<out>/index.html`. A figure whose data is absent is
//! skipped, not drawn empty.
//!
//! This file is the hub, [`write_report`]: it loads the input, draws every figure of
//! [`figures::ALL`] and writes the page. The types it shares with the figures and the page have
//! their own modules, re-exported here: what is read ([`ReportInput`], `input.rs`), what can go
//! wrong ([`ReportError`], `error.rs`) and what was written ([`Figure`], [`ReportSummary`],
//! `summary.rs`).
#![deny(missing_docs)]

pub mod charts;
pub mod clip;
pub mod contour;
pub mod cycle_catalogue;
pub mod cycles;
mod error;
mod fault_page;
pub mod figures;
mod html;
mod input;
mod markup;
pub mod place;
pub mod plot;
mod summary;

use std::path::Path;

use stickslip_config::Pipeline;
use stickslip_store::io::write_text_atomic;

pub use error::ReportError;
pub use input::ReportInput;
pub use summary::{Figure, ReportSummary};

/// Draws every figure whose data is present and writes `<out>/index.html`.
pub fn write_report(out: &Path, pipeline: &Pipeline) -> Result<ReportSummary, ReportError> {
    plot::register_fonts();
    let input = ReportInput::load(out, pipeline)?;
    let dir = input.folder.figures();
    std::fs::create_dir_all(&dir).map_err(|e| ReportError::Io { path: dir.clone(), source: e })?;
    let mut drawn = Vec::new();
    let mut skipped = Vec::new();
    // A fault scene's page leaves out the figures of the paper's similarity scaling (their data
    // exists, measured on the block's own scale, and would contradict the source table).
    let fault = pipeline.scene.is_fault();
    let applies = |file: &str| !(fault && figures::left_out_on_a_fault(file).is_some());
    let left_out: Vec<(String, String)> = figures::ALL
        .iter()
        .filter_map(|(file, _)| {
            let why = figures::left_out_on_a_fault(file).filter(|_| fault)?;
            Some((file.to_string(), why.to_string()))
        })
        .collect();
    // The figures are drawn on the available cores, each into a temporary file (then renamed:
    // a reader never sees half a figure); the page lists them in their order.
    let next = std::sync::atomic::AtomicUsize::new(0);
    let outcomes: Vec<std::sync::Mutex<Option<Result<figures::Outcome, ReportError>>>> =
        figures::ALL.iter().map(|_| std::sync::Mutex::new(None)).collect();
    let tmp = |file: &str| dir.join(format!(".{file}.{}.tmp.png", std::process::id()));
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get()).min(figures::ALL.len());
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some((file, draw)) = figures::ALL.get(k) else { break };
                    let outcome = if applies(file) {
                        draw(&input, &tmp(file))
                    } else {
                        Ok(figures::Outcome::Skipped(String::new()))
                    };
                    *outcomes[k].lock().expect("figure outcome") = Some(outcome);
                }
            });
        }
    });
    let outcomes: Vec<Result<figures::Outcome, ReportError>> =
        outcomes.into_iter().map(|o| o.into_inner().expect("figure outcome").expect("every figure drawn")).collect();
    if let Some(k) = outcomes.iter().position(|o| o.is_err()) {
        for (file, _) in &figures::ALL {
            let _ = std::fs::remove_file(tmp(file));
        }
        return Err(outcomes.into_iter().nth(k).and_then(Result::err).expect("the error"));
    }
    for ((file, _), outcome) in figures::ALL.iter().zip(outcomes) {
        let path = dir.join(file);
        let tmp = tmp(file);
        match outcome? {
            figures::Outcome::Drawn { title, caption, headings, panels, dropped } => {
                std::fs::rename(&tmp, &path).map_err(|e| ReportError::Io { path: path.clone(), source: e })?;
                drawn.push(Figure { file: file.to_string(), title, caption, headings, panels, dropped });
            }
            figures::Outcome::Skipped(why) => {
                let _ = std::fs::remove_file(&tmp);
                let _ = std::fs::remove_file(&path);
                if applies(file) {
                    skipped.push((file.to_string(), why));
                }
            }
        }
    }
    let index = input.folder.index();
    write_text_atomic(&index, &html::page(&input, &drawn, &skipped, &left_out)?)?;
    Ok(ReportSummary { index, figures: drawn, skipped, left_out })
}
