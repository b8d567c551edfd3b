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

/// Merges the shards in `out`. The pipeline is `<out>/pipeline.toml` (written by every shard, its
/// input files beside it) unless `pipeline` is given; `shards` (the N of the shards; by default
/// the N the shards that ran here were given) lets a missing seed be reported as the shard that
/// should have run it, and is refused when the shards that ran here had another N.
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
    let marks = shard_marks(&folder)?;
    let counts: std::collections::BTreeSet<usize> = marks.iter().map(|m| m.1).collect();
    if let Some(n) = shards
        && !counts.is_empty()
        && counts != std::collections::BTreeSet::from([n])
    {
        return Err(EnsembleError::Incomplete {
            out: out.to_path_buf(),
            why: format!(
                "--shards {n}, but the shards that ran here were {} of {} (files in {}): give the N of --shard K/N",
                marks.iter().map(|(k, n)| format!("{k}/{n}")).collect::<Vec<_>>().join(", "),
                counts.iter().map(|n| n.to_string()).collect::<Vec<_>>().join(" and "),
                folder.shards_dir().display()
            ),
        });
    }
    // The N of the shards: as given, or as the shards that ran here say (when they agree).
    let n_shards = shards.or_else(|| (counts.len() == 1).then(|| counts.iter().copied().next()).flatten());
    if !missing.is_empty() || !mismatched.is_empty() {
        let mut why = Vec::new();
        if !missing.is_empty() {
            let mut text = format!("{} of {} seeds missing", missing.len(), p.seeds.len());
            if let Some(n) = n_shards {
                let lost: Vec<usize> =
                    (1..=n).filter(|&k| shard(&p.seeds, k, n).iter().any(|s| missing.contains(s))).collect();
                let (started, never): (Vec<usize>, Vec<usize>) =
                    lost.into_iter().partition(|&k| marks.is_empty() || marks.contains(&(k, n)));
                let join = |v: &[usize]| v.iter().map(|k| k.to_string()).collect::<Vec<_>>().join(", ");
                let mut parts = Vec::new();
                if !started.is_empty() {
                    parts.push(format!("shards {} of {n} incomplete", join(&started)));
                }
                if !never.is_empty() {
                    parts.push(format!("shards {} of {n} never started here", join(&never)));
                }
                text += &format!(" ({})", parts.join("; "));
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
    crate::exchange::write_exchange(&folder, &p)?;
    let failed = p.seeds.iter().filter(|s| found.get(s).is_some_and(|r| r.2 != "ok")).count();
    Ok(MergeReport { seeds: p.seeds.len(), failed, wall_time_s: start.elapsed().as_secs_f64(), pipeline: p, set })
}

/// The file that marks shard `k` of `n` as started in `out`.
fn mark_path(out: &Folder, k: usize, n: usize) -> std::path::PathBuf {
    out.shards_dir().join(format!("shard-{k}-of-{n}.toml"))
}

/// Claims `out` for shard `k` of `n` of `pipeline` (see [`crate::run::prepare_output`]) and marks
/// it as started, with its seeds, so that `merge` knows the shards' N and can tell a shard that
/// never started from one that did not finish.
pub fn mark_shard(out: &Path, pipeline: &Pipeline, k: usize, n: usize, seeds: &[u64]) -> Result<(), EnsembleError> {
    let folder = Folder::new(out);
    crate::run::prepare_output(&folder, pipeline, false)?;
    let text = format!(
        "# Shard {k} of {n} of pipeline {} (hash {}) started here.\nk = {k}\nn = {n}\nseeds = {}\n",
        pipeline.name,
        pipeline.hash,
        seeds.len()
    );
    stickslip_store::io::write_text_atomic(&mark_path(&folder, k, n), &text)?;
    Ok(())
}

/// The shards marked as started in `out`, `(k, n)`, sorted.
fn shard_marks(out: &Folder) -> Result<Vec<(usize, usize)>, EnsembleError> {
    let dir = out.shards_dir();
    let Ok(entries) = std::fs::read_dir(&dir) else { return Ok(vec![]) };
    let mut marks: Vec<(usize, usize)> = entries
        .flatten()
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let (k, n) = name.strip_prefix("shard-")?.strip_suffix(".toml")?.split_once("-of-")?;
            Some((k.parse().ok()?, n.parse().ok()?))
        })
        .collect();
    marks.sort();
    Ok(marks)
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
