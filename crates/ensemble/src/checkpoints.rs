//! Seeds that keep checkpoints (docs/model.md §19, docs/guide/ensembles.md "Checkpoints"): each
//! running seed writes its state to `<out>/checkpoints/` every so often and when it is stopped
//! (Ctrl-C, a cluster's preemption or wall time), and resumes from it when the pipeline is run
//! again into the same folder, giving the numbers of a seed never stopped. A seed split over MPI
//! ranks keeps one file per rank. The file goes once the seed's tables are written.

use std::path::PathBuf;

use stickslip_solver::Checkpoint;
use stickslip_store::Folder;

/// Where and how often the seeds of one pipeline keep checkpoints.
#[derive(Clone, Debug)]
pub struct Checkpoints {
    /// The output folder.
    pub out: PathBuf,
    /// Seconds of wall clock between two checkpoints of a seed.
    pub every_s: f64,
    /// The pipeline's hash: a checkpoint of another pipeline is not resumed.
    pub key: String,
}

impl Checkpoints {
    /// The checkpoint of `seed` on `rank` of `ranks` (1: one process).
    pub fn of(&self, seed: u64, rank: usize, ranks: usize) -> Checkpoint {
        Checkpoint::new(
            Folder::new(&self.out).checkpoint(seed, rank, ranks),
            Some(self.every_s),
            None,
            self.key.clone(),
        )
    }

    /// The seeds among `seeds` whose checkpoint (on one process, or rank 0 of `ranks`) holds a
    /// run of this pipeline, with its step: those that resume.
    pub fn found(&self, seeds: &[u64], ranks: usize) -> Vec<(u64, u64)> {
        seeds.iter().filter_map(|&s| self.of(s, 0, ranks).resumes_at().map(|step| (s, step))).collect()
    }
}
