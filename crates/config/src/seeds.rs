//! Seed lists and shards as written on a command line (`--seeds 1,5,10-20`, `--shard 3/8`).

/// The most seeds a list may hold, as in a pipeline file's `[seeds]`.
pub const MAX_SEEDS: u64 = 10_000_000;

/// Parses "1,5,10-20" into seeds, in the order given, each once; refuses a list of more than
/// [`MAX_SEEDS`] seeds before building it.
pub fn parse_seeds(text: &str) -> Result<Vec<u64>, String> {
    let not_a_seed = |s: &str| format!("--seeds: {s:?} is not a seed (a whole number 0 … {})", u64::MAX);
    let mut parts: Vec<(u64, u64)> = Vec::new();
    let mut count: u64 = 0;
    for part in text.split(',').map(str::trim).filter(|p| !p.is_empty()) {
        let (a, b) = match part.split_once('-') {
            Some((a, b)) => {
                let (a, b): (u64, u64) =
                    (a.trim().parse().map_err(|_| not_a_seed(a))?, b.trim().parse().map_err(|_| not_a_seed(b))?);
                if a > b {
                    return Err(format!("--seeds: range {part} runs backwards"));
                }
                (a, b)
            }
            None => {
                let s = part.parse().map_err(|_| not_a_seed(part))?;
                (s, s)
            }
        };
        count = count.saturating_add(b - a).saturating_add(1);
        if count > MAX_SEEDS {
            return Err(format!(
                "--seeds: {text:?} names more than {MAX_SEEDS} seeds; run a larger ensemble as shards of a pipeline \
                 file's [seeds] range, or a shorter list"
            ));
        }
        parts.push((a, b));
    }
    if parts.is_empty() {
        return Err("--seeds: no seed given".into());
    }
    // A seed named twice would run once: refused, so that the count asked is the count run.
    let mut seen = std::collections::HashSet::new();
    let mut seeds = Vec::new();
    for (k, &(a, b)) in parts.iter().enumerate() {
        for s in a..=b {
            if !seen.insert(s) {
                let first = parts.iter().position(|&(x, y)| (x..=y).contains(&s)).unwrap_or(k);
                let name = |(x, y): (u64, u64)| if x == y { format!("{x}") } else { format!("{x}-{y}") };
                return Err(format!(
                    "--seeds: seed {s} is named twice in {text:?} (by {} and by {}): each seed runs once, so name it \
                     once",
                    name(parts[first]),
                    name(parts[k])
                ));
            }
            seeds.push(s);
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_lists_keep_their_order_once_each_and_refuse_what_does_not_fit() {
        assert_eq!(parse_seeds("5, 1-3 ,7").unwrap(), vec![5, 1, 2, 3, 7]);
        // A seed named twice is refused (it used to be dropped silently).
        let e = parse_seeds("1,1,2").unwrap_err();
        assert!(e.contains("seed 1 is named twice in \"1,1,2\" (by 1 and by 1)"), "{e}");
        let e = parse_seeds("5, 1-3 ,2").unwrap_err();
        assert!(e.contains("seed 2 is named twice") && e.contains("(by 1-3 and by 2)"), "{e}");
        assert_eq!(parse_seeds("18446744073709551615").unwrap(), vec![u64::MAX]);
        for (bad, says) in [
            ("0-18446744073709551615", "more than 10000000 seeds"),
            ("1-300000000", "more than 10000000 seeds"),
            ("1-5000000,10000000-15000000", "more than 10000000 seeds"),
            ("5-1", "runs backwards"),
            ("-1", "is not a seed"),
            ("x", "is not a seed"),
            ("18446744073709551616", "is not a seed"),
            (" , ", "no seed given"),
        ] {
            let e = parse_seeds(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
        assert_eq!(parse_seeds("1-10000000").unwrap().len(), 10_000_000);
        assert_eq!(parse_shard("3/8"), Ok((3, 8)));
        assert!(parse_shard("9/8").is_err() && parse_shard("0/8").is_err() && parse_shard("3").is_err());
    }
}
