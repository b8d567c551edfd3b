//! Errors of the seismology numerics: unreadable accelerogram files, missing signals.

use std::path::PathBuf;

/// Everything that can go wrong in this crate; each variant carries what is needed to act on it.
#[derive(Debug, thiserror::Error)]
pub enum SeismoError {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A parameter is outside its allowed range; nothing was computed.
    #[error("{name} = {value} is not allowed: {allowed}")]
    Parameter {
        /// The parameter, as named in the API (e.g. `f_low`, `candidates[3].psa`).
        name: String,
        /// The value given, as text.
        value: String,
        /// What is allowed, e.g. `0 < f_low < f_high (25 Hz)`.
        allowed: String,
    },
    /// No record set meets the selection rules; the reason says which rule could not be met.
    #[error("no record set can be selected: {0}")]
    Selection(crate::selection::Refusal),
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

impl SeismoError {
    /// A [`SeismoError::Parameter`] from anything printable.
    pub fn parameter(name: impl Into<String>, value: impl std::fmt::Display, allowed: impl Into<String>) -> Self {
        SeismoError::Parameter { name: name.into(), value: value.to_string(), allowed: allowed.into() }
    }
}
