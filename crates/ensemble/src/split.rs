//! Seeds of a scene split over MPI ranks (docs/model.md §19): when the process is rank 0 of
//! several, the command line installs a [`SplitSeeds`] and the ensemble runs its seeds one after
//! another through it instead of side by side, each split over every rank; everything else (the
//! analysis, the tables, the report) is rank 0's as on one process, so the folder is the same.
//!
//! A process under `mpirun` is one rank of every scene it runs, so the runner is installed once
//! per process ([`install`]).

use std::ops::ControlFlow;
use std::sync::OnceLock;

use stickslip_config::Pipeline;
use stickslip_solver::{Checkpoint, RunOptions, RunOutput, SolverError};

/// Rank 0's side of a split run: runs `seed` of `pipeline` over every rank (the others follow).
pub trait SplitSeeds: Send + Sync {
    /// Ranks the seeds are split over.
    fn ranks(&self) -> usize;
    /// Ranks on this node (rank 0's), which share its memory.
    fn local_ranks(&self) -> usize;
    /// Runs one seed; `progress` may stop it (every rank stops). With rank 0's `checkpoint`
    /// ([`crate::checkpoints::Checkpoints::of`] rank 0), every rank keeps its own beside it.
    fn run(
        &self,
        pipeline: &Pipeline,
        seed: u64,
        options: RunOptions,
        checkpoint: Option<&Checkpoint>,
        progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
    ) -> Result<RunOutput, SolverError>;
}

static RUNNER: OnceLock<Box<dyn SplitSeeds>> = OnceLock::new();

/// Makes every ensemble of this process split its seeds through `runner`; once per process.
pub fn install(runner: Box<dyn SplitSeeds>) {
    if RUNNER.set(runner).is_err() {
        panic!("a process is one rank of one split: the runner is installed once");
    }
}

/// The runner, when this process is rank 0 of a split.
pub fn installed() -> Option<&'static dyn SplitSeeds> {
    RUNNER.get().map(|b| b.as_ref())
}
