//! Errors of an ensemble run.

use std::path::PathBuf;

use stickslip_config::ConfigError;
use stickslip_solver::SolverError;
use stickslip_store::StoreError;

/// Everything that can go wrong running, gathering or merging an ensemble.
#[derive(Debug, thiserror::Error)]
pub enum EnsembleError {
    /// The pipeline file was refused.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The output folder could not be read or written.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// The solver failed outside a seed (e.g. building the model).
    #[error(transparent)]
    Solver(Box<SolverError>),
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
    /// No set of records could be selected (the reason says which rule could not be met), or a
    /// set record could not be written.
    #[error("set: {0}")]
    Set(stickslip_seismo::SeismoError),
    /// A ground-motion model refused a record's inputs.
    #[error("ground-motion model: {0}")]
    Gmm(stickslip_seismo::SeismoError),
    /// Something could not be set up.
    #[error("{0}")]
    Setup(String),
    /// A run refused before it is built: it would not fit in memory, or is longer than asked for
    /// (the message says what to change).
    #[error("{0}")]
    Refused(String),
    /// A file of the exchange formats (StationXML, QuakeML, MiniSEED) could not be made.
    #[error("exchange formats: {0}")]
    Exchange(stickslip_seismo::SeismoError),
}

impl From<SolverError> for EnsembleError {
    fn from(e: SolverError) -> Self {
        EnsembleError::Solver(Box::new(e))
    }
}
