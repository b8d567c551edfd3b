//! What can go wrong writing a report: a table unreadable, a figure undrawable, a file not moved
//! into place.

use std::path::PathBuf;

use stickslip_store::StoreError;

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
