//! What a report wrote: each figure drawn with its headings and captions, the page, and the
//! figures skipped for lack of data.

use std::path::PathBuf;

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
    /// Figures that do not apply to this scene (the paper's similarity figures on a fault scene:
    /// [`crate::figures::LEFT_OUT_ON_A_FAULT`]), with the reason.
    pub left_out: Vec<(String, String)>,
}
