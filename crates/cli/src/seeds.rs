//! Seed lists and shards as written on the command line.

use anyhow::{Context, Result};

/// Parses "1,5,10-20" into seeds.
pub fn parse_seeds(text: &str) -> Result<Vec<u64>> {
    let mut seeds = Vec::new();
    for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        if let Some((a, b)) = part.split_once('-') {
            let (a, b): (u64, u64) = (
                a.trim().parse().with_context(|| format!("--seeds: {a:?} is not a seed"))?,
                b.trim().parse().with_context(|| format!("--seeds: {b:?} is not a seed"))?,
            );
            anyhow::ensure!(a <= b, "--seeds: range {part} runs backwards");
            seeds.extend(a..=b);
        } else {
            seeds.push(part.parse().with_context(|| format!("--seeds: {part:?} is not a seed"))?);
        }
    }
    anyhow::ensure!(!seeds.is_empty(), "--seeds: no seed given");
    seeds.dedup();
    Ok(seeds)
}

/// Parses "K/N" (1 ≤ K ≤ N).
pub fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let (k, n) = text.split_once('/').ok_or_else(|| format!("{text:?}: expected K/N, e.g. 3/8"))?;
    let (k, n): (usize, usize) = (
        k.trim().parse().map_err(|_| format!("{k:?} is not a shard number"))?,
        n.trim().parse().map_err(|_| format!("{n:?} is not a shard count"))?,
    );
    if n == 0 || k == 0 || k > n {
        return Err(format!("{text}: need 1 ≤ K ≤ N"));
    }
    Ok((k, n))
}
