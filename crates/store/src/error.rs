//! Errors of the output folder: files that cannot be read or written, tables that do not parse.

use std::path::{Path, PathBuf};

/// Everything that can go wrong reading or writing an output folder.
#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// A file could not be read or written.
    #[error("{}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Polars failed to build, read or write a table.
    #[error("table {what}")]
    Table {
        /// Which table.
        what: String,
        /// The cause.
        source: polars::error::PolarsError,
    },
    /// A file of ours could not be understood.
    #[error("{}: {what}", path.display())]
    Corrupt {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
    /// A table holds a value this stickslip does not write (a kind or label it cannot read back).
    #[error("table {table}: {what}")]
    Unreadable {
        /// Which table.
        table: String,
        /// What is wrong.
        what: String,
    },
    /// A value a table cannot hold as it stores it (e.g. beyond single precision's range).
    #[error("table {table}: {what}")]
    OutOfRange {
        /// Which table.
        table: String,
        /// What is wrong.
        what: String,
    },
    /// A folder that is not an output folder.
    #[error("{}: {what}", path.display())]
    NotAnOutput {
        /// The folder.
        path: PathBuf,
        /// What is missing.
        what: String,
    },
}

impl StoreError {
    /// An I/O error on `path`.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        StoreError::Io { path: path.to_path_buf(), source }
    }

    /// A polars error while handling table `what`.
    pub fn table(what: impl Into<String>, source: polars::error::PolarsError) -> Self {
        StoreError::Table { what: what.into(), source }
    }
}
