//! Errors of the seismology numerics: unreadable accelerogram files, missing signals.

use std::path::PathBuf;

/// Everything that can go wrong in this crate.
#[derive(Debug, thiserror::Error)]
pub enum SeismoError {
    /// A file could not be read or written.
    #[error("{}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A spectrum could not be computed (a bad interval, period, damping or sample).
    #[error(transparent)]
    Spectrum(#[from] crate::spectra::response::SpectrumError),
    /// A file is not in the format it claims.
    #[error("{}: {what}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
}
