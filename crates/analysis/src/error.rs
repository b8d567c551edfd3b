//! Errors of the analysis crate.

use std::path::{Path, PathBuf};

use stickslip_solver::SolverError;

/// Everything that can go wrong in analysis, tables and reports.
#[derive(Debug, thiserror::Error)]
pub enum AnalysisError {
    /// A file could not be read or written.
    #[error("{}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A pipeline file was refused.
    #[error("{}", path.display())]
    Pipeline {
        /// The file.
        path: PathBuf,
        /// Why.
        source: Box<SolverError>,
    },
    /// The solver failed.
    #[error(transparent)]
    Solver(Box<SolverError>),
    /// A file of ours could not be understood.
    #[error("{}: {what}", path.display())]
    Corrupt {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
    /// The output folder holds results of another pipeline.
    #[error(
        "{} holds results of another pipeline (hash {found}; this pipeline's is {expected}); nothing was run. \
         Use --fresh to discard them, or --out to write elsewhere",
        out.display()
    )]
    OtherPipeline {
        /// The folder.
        out: PathBuf,
        /// Hash found there.
        found: String,
        /// Hash of the pipeline asked for.
        expected: String,
    },
    /// The run was interrupted; finished seeds are kept.
    #[error(
        "interrupted: {done} of {total} seeds are finished in {}; run the same command again to resume",
        out.display()
    )]
    Interrupted {
        /// Seeds finished.
        done: usize,
        /// Seeds asked.
        total: usize,
        /// The folder.
        out: PathBuf,
    },
    /// A merge found seeds missing or from another pipeline.
    #[error("{}: cannot merge: {why}", out.display())]
    Incomplete {
        /// The folder.
        out: PathBuf,
        /// What is missing or mismatched.
        why: String,
    },
    /// Something could not be set up.
    #[error("{0}")]
    Setup(String),
    /// Polars failed to build, read or write a table.
    #[error("table {what}")]
    Table {
        /// Which table.
        what: String,
        /// The cause.
        source: polars::error::PolarsError,
    },
}

impl From<SolverError> for AnalysisError {
    fn from(e: SolverError) -> Self {
        AnalysisError::Solver(Box::new(e))
    }
}

impl AnalysisError {
    /// An I/O error on `path`.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        AnalysisError::Io { path: path.to_path_buf(), source }
    }

    /// A polars error while handling table `what`.
    pub fn table(what: impl Into<String>, source: polars::error::PolarsError) -> Self {
        AnalysisError::Table { what: what.into(), source }
    }
}
