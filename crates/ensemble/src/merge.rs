//! Merging the shards of an ensemble run anywhere (e.g. a Slurm job array) into one dataset.
//!
//! Shards write per-seed parts into one shared folder (see [`crate::run`]); `merge` checks that
//! every seed of the pipeline is there and comes from the same pipeline hash, then gathers the
//! tables (scanning the parts lazily with a glob) and the statistics.

use std::path::Path;
use std::time::Instant;

use polars::prelude::*;
use stickslip_config::Pipeline;
use stickslip_store::schema::{RUNS, col};
use stickslip_store::{Folder, StoreError};

use crate::error::EnsembleError;
use crate::gather::{Gathering, gather};
use crate::run::shard;
use crate::set::{SetOutcome, select_set};

/// What `merge` did.
#[derive(Clone, Debug)]
pub struct MergeReport {
    /// The pipeline merged.
    pub pipeline: Pipeline,
    /// Seeds merged.
    pub seeds: usize,
    /// Seeds that failed in their run (they are rows of the runs table).
    pub failed: usize,
    /// Wall time (s).
    pub wall_time_s: f64,
    /// The set of `[set]`, if asked: chosen, or why none could be.
    pub set: Option<Result<SetOutcome, String>>,
}

/// Merges the shards in `out`. The pipeline is `<out>/pipeline.toml` (written by every shard)
/// unless `pipeline` is given; `shards` (the N of the shards) lets a missing seed be reported as
/// the shard that should have run it.
pub fn merge(out: &Path, pipeline: Option<&Path>, shards: Option<usize>) -> Result<MergeReport, EnsembleError> {
    let start = Instant::now();
    let folder = Folder::new(out);
    let hash = folder.require_output()?.pipeline_hash;
    let path = pipeline.map(Path::to_path_buf).unwrap_or_else(|| folder.pipeline_copy());
    let p = Pipeline::load(&path)?;
    if p.hash != hash {
        return Err(EnsembleError::OtherPipeline { out: out.to_path_buf(), found: hash, expected: p.hash });
    }
    // Only the three columns the check needs are read from the runs parts.
    let glob = folder.part_glob(&RUNS);
    let present: Vec<(u64, String, String)> = if std::fs::read_dir(glob.parent().expect("parent")).is_ok() {
        let t = |e| StoreError::table(RUNS.name, e);
        let lf = LazyFrame::scan_parquet(PlRefPath::new(glob.display().to_string()), ScanArgsParquet::default())
            .map_err(t)?;
        let df = lf.select([col(col::SEED), col(col::PIPELINE_HASH), col(col::STATUS)]).collect().map_err(t)?;
        let c = stickslip_store::frame::Columns::of(&df, RUNS.name);
        let (seeds, hashes, status) = (c.u64s(col::SEED)?, c.strs(col::PIPELINE_HASH)?, c.strs(col::STATUS)?);
        (0..df.height()).map(|i| (seeds[i], hashes[i].clone(), status[i].clone())).collect()
    } else {
        vec![]
    };
    let found: std::collections::HashMap<u64, &(u64, String, String)> = present.iter().map(|r| (r.0, r)).collect();
    let missing: Vec<u64> = p.seeds.iter().copied().filter(|s| !found.contains_key(s)).collect();
    let mismatched: Vec<u64> = p.seeds.iter().copied().filter(|s| found.get(s).is_some_and(|r| r.1 != hash)).collect();
    if !missing.is_empty() || !mismatched.is_empty() {
        let mut why = Vec::new();
        if !missing.is_empty() {
            let mut text = format!("{} of {} seeds missing", missing.len(), p.seeds.len());
            if let Some(n) = shards {
                let lost: std::collections::BTreeSet<usize> =
                    (1..=n).filter(|&k| shard(&p.seeds, k, n).iter().any(|s| missing.contains(s))).collect();
                text += &format!(
                    " (shards {} of {n} incomplete)",
                    lost.iter().map(|k| k.to_string()).collect::<Vec<_>>().join(", ")
                );
            }
            text += &format!(": {}", list(&missing));
            why.push(text);
        }
        if !mismatched.is_empty() {
            why.push(format!(
                "{} seeds come from another pipeline hash than {hash}: {}",
                mismatched.len(),
                list(&mismatched)
            ));
        }
        return Err(EnsembleError::Incomplete { out: out.to_path_buf(), why: why.join("; ") });
    }
    gather(&folder, &p.seeds, Gathering::default())?;
    let set = p.set.as_ref().map(|s| select_set(&folder, &p, s).map_err(|e| e.to_string()));
    let failed = p.seeds.iter().filter(|s| found.get(s).is_some_and(|r| r.2 != "ok")).count();
    Ok(MergeReport { seeds: p.seeds.len(), failed, wall_time_s: start.elapsed().as_secs_f64(), pipeline: p, set })
}

/// At most 20 seeds, then a count.
fn list(seeds: &[u64]) -> String {
    let head: Vec<String> = seeds.iter().take(20).map(|s| s.to_string()).collect();
    if seeds.len() > 20 { format!("{} … ({} more)", head.join(", "), seeds.len() - 20) } else { head.join(", ") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_are_disjoint_and_cover_every_seed() {
        let seeds: Vec<u64> = (100..137).collect();
        for n in [1, 2, 5, 8, 37, 50] {
            let mut all: Vec<u64> = (1..=n).flat_map(|k| shard(&seeds, k, n)).collect();
            assert_eq!(all, seeds, "n = {n}: slices are contiguous and in order");
            all.dedup();
            assert_eq!(all.len(), seeds.len());
        }
        assert_eq!(shard(&seeds, 2, 8), (104..109).collect::<Vec<u64>>());
    }
}
