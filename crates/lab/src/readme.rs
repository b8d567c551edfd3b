//! The generated blocks of the README and the user guide: every printed output, table and
//! measured number of `README.md` and `docs/guide/*.md` that a command gives is written by the
//! command `stickslip-bench readme`, which runs the product's `stickslip` binary as a user would
//! (from the repository's root, into `reports/`) and rewrites the blocks between markers:
//!
//! ```text
//! <!-- generated: KEY (stickslip-bench readme) -->
//! …
//! <!-- end: KEY -->
//! ```
//!
//! A block lives in whichever of those files its text belongs to ([`block_files`]); each key is in
//! exactly one of them, and a key in none or in two is an error ([`locate`]). [`GENERATORS`] lists
//! the keys, what each runs and what it writes. Anything outside the markers is left alone; a
//! block's text is entirely the generator's. `--check` compares instead of writing (exit 1 and the
//! differing blocks when a file is stale), `--only KEY` regenerates some blocks. The tests of the
//! deterministic numbers (`crates/cli/tests/usability.rs`, through `stickslip_support`) read the
//! same markers in the same files.

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use stickslip_store::Folder;
use stickslip_store::io::read_parquet_if_present;
use stickslip_store::schema::{B_VALUES, OMORI, RECURRENCE_STATS, RUNS, SCALING, TableSpec};
use stickslip_store::tables::catalogue::{BValues, Omori, RecurrenceStats, Scaling};
use stickslip_store::tables::runs::Runs;

use crate::LabError;

/// The opening marker of block `key`.
pub fn opening(key: &str) -> String {
    format!("<!-- generated: {key} (stickslip-bench readme) -->")
}

/// The closing marker of block `key`.
pub fn closing(key: &str) -> String {
    format!("<!-- end: {key} -->")
}

/// The generated blocks of `text`: each key with the byte range of its content (between the
/// line of its opening marker and its closing marker), in order.
pub fn blocks(text: &str) -> Result<Vec<(String, Range<usize>)>, LabError> {
    let mut out = Vec::new();
    let mut rest = 0;
    let head = "<!-- generated: ";
    while let Some(i) = text[rest..].find(head) {
        let at = rest + i;
        let line_end = text[at..].find('\n').map(|j| at + j + 1).ok_or_else(|| setup("a marker ends the file"))?;
        let key = text[at + head.len()..line_end]
            .split_whitespace()
            .next()
            .ok_or_else(|| setup("a marker without a key"))?
            .to_string();
        let close = closing(&key);
        let end = text[line_end..]
            .find(&close)
            .map(|j| line_end + j)
            .ok_or_else(|| setup(&format!("block {key}: no closing marker {close}")))?;
        if text[line_end..end].contains(head) {
            return Err(setup(&format!("block {key} holds another block's marker")));
        }
        if out.iter().any(|(k, _)| *k == key) {
            return Err(setup(&format!("block {key} appears twice")));
        }
        out.push((key, line_end..end));
        rest = end + close.len();
    }
    Ok(out)
}

/// `text` with the content of block `key` replaced by `content` (which must end with a newline).
pub fn replace(text: &str, key: &str, content: &str) -> Result<String, LabError> {
    let (_, range) =
        blocks(text)?.into_iter().find(|(k, _)| k == key).ok_or_else(|| setup(&format!("no block {key}")))?;
    Ok(format!("{}{content}{}", &text[..range.start], &text[range.end..]))
}

fn setup(what: &str) -> LabError {
    LabError::Setup(what.to_string())
}

/// A generator: its key, what it runs, and the function that runs it.
pub struct Generator {
    /// The block's key.
    pub key: &'static str,
    /// What it runs, in words (printed).
    pub runs: &'static str,
    /// Whether its text depends on the machine (wall times, disk use): `--check` reports a
    /// difference in it but does not fail on it.
    pub measured: bool,
    /// The block's new content.
    pub make: fn(&Runner) -> Result<String, LabError>,
}

/// Every generated block of the README and the guide.
pub const GENERATORS: &[Generator] = &[
    Generator {
        key: "main-command",
        runs: "stickslip pipeline pipelines/paper.toml pipelines/paper-100.toml pipelines/accelerograms.toml (timed)",
        measured: true,
        make: main_command,
    },
    Generator {
        key: "paper-100",
        runs: "stickslip pipeline pipelines/paper-100.toml (its printout)",
        measured: false,
        make: paper_100,
    },
    Generator {
        key: "disk-use",
        runs: "du of reports/paper-100 and reports/accelerograms after the main command",
        measured: true,
        make: disk_use,
    },
    Generator {
        key: "paper-precise",
        runs: "stickslip pipeline pipelines/paper-precise.toml (its printout)",
        measured: false,
        make: paper_precise,
    },
    Generator {
        key: "wall-times",
        runs: "stickslip pipeline pipelines/paper-100.toml with --threads 1 and 2 (timed)",
        measured: true,
        make: wall_times,
    },
    Generator { key: "calibration", runs: "stickslip seeds reports/paper", measured: false, make: calibration },
    Generator {
        key: "slow-loading",
        runs: "stickslip pipeline pipelines/slow-loading.toml; its catalogue tables",
        measured: false,
        make: slow_loading,
    },
];

/// Runs the product's binary from the repository's root.
pub struct Runner {
    /// The `stickslip` binary.
    pub binary: PathBuf,
    /// The repository's root (where `README.md`, `docs/guide/` and `pipelines/` are).
    pub root: PathBuf,
    /// Outputs of commands already run (a command is run once per invocation).
    done: std::cell::RefCell<BTreeMap<String, (String, f64)>>,
}

impl Runner {
    /// A runner of `binary` in `root`.
    pub fn new(binary: PathBuf, root: PathBuf) -> Runner {
        Runner { binary, root, done: Default::default() }
    }

    /// Runs `stickslip args…` (once: a second call returns the first's output) and returns its
    /// standard output and wall time (s); a failure is an error with its standard error.
    pub fn run(&self, args: &[&str]) -> Result<(String, f64), LabError> {
        let key = args.join(" ");
        if let Some(done) = self.done.borrow().get(&key) {
            return Ok(done.clone());
        }
        eprintln!("  running: stickslip {key}");
        let start = Instant::now();
        let out = Command::new(&self.binary)
            .args(args)
            .current_dir(&self.root)
            .output()
            .map_err(|e| setup(&format!("running {}: {e}", self.binary.display())))?;
        let wall = start.elapsed().as_secs_f64();
        if !out.status.success() {
            return Err(setup(&format!("stickslip {key} failed:\n{}", String::from_utf8_lossy(&out.stderr))));
        }
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        self.done.borrow_mut().insert(key, (text.clone(), wall));
        Ok((text, wall))
    }

    /// An output folder of the runs, under the repository's root.
    pub fn folder(&self, rel: &str) -> Folder {
        Folder::new(self.root.join(rel))
    }
}

/// `v` to `digits` decimals with a typographic minus, as the README writes numbers.
fn minus(v: f64, digits: usize) -> String {
    format!("{v:.digits$}").replace('-', "−")
}

fn fenced(lines: &[&str]) -> String {
    format!("```\n{}\n```\n", lines.join("\n"))
}

/// The lines of `out` from the first starting with `from` to the first starting with `to`
/// (included).
fn lines_between<'a>(out: &'a str, from: &str, to: &str) -> Result<Vec<&'a str>, LabError> {
    let lines: Vec<&str> = out.lines().collect();
    let a = lines.iter().position(|l| l.starts_with(from)).ok_or_else(|| setup(&format!("no line {from:?}")))?;
    let b = lines[a..].iter().position(|l| l.starts_with(to)).ok_or_else(|| setup(&format!("no line {to:?}")))?;
    Ok(lines[a..=a + b].to_vec())
}

const MAIN: [&str; 6] = [
    "pipeline",
    "pipelines/paper.toml",
    "pipelines/paper-100.toml",
    "pipelines/accelerograms.toml",
    "--fresh",
    "--quiet",
];

/// The machine, as `/proc/cpuinfo` and the core count say.
fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|c| {
            c.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "an unknown CPU".into());
    let cores = std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1);
    format!("{cores} cores of {cpu}")
}

/// The main command, run once per `stickslip-bench readme` from empty folders: a finished folder
/// of the same pipeline would be resumed, not run (`--fresh` discards only another pipeline's
/// results), and the time would be the resume's (1.5 s instead of 10, seen). The folders it
/// writes are moved aside first (see `ensemble_cost::set_aside`) and deleted by
/// [`remove_main_set_aside`] once everything is measured; if the command fails they are put back
/// in place of what it wrote.
fn main_run(r: &Runner) -> Result<(String, f64), LabError> {
    let mut moved = Vec::new();
    if !r.done.borrow().contains_key(&MAIN.join(" ")) {
        for file in MAIN.iter().filter(|a| a.ends_with(".toml")) {
            let folder = r.root.join("reports").join(stickslip_config::Pipeline::load(&r.root.join(file))?.name);
            if let Some(aside) = crate::ensemble_cost::set_aside(&folder)? {
                moved.push((folder, aside));
            }
        }
    }
    let run = r.run(&MAIN);
    if run.is_err() {
        for (folder, aside) in &moved {
            let _ = std::fs::remove_dir_all(folder);
            let _ = std::fs::rename(aside, folder);
        }
    }
    run
}

/// Deletes the earlier report folders [`main_run`] moved aside.
pub fn remove_main_set_aside(root: &Path) {
    crate::ensemble_cost::remove_set_aside(&root.join("reports"));
}

fn main_command(r: &Runner) -> Result<String, LabError> {
    let (_, wall) = main_run(r)?;
    Ok(format!(
        "After the first build (see Install) the main command took {wall:.1} s on the machine that last ran \
         `stickslip-bench readme` ({}).\n",
        machine()
    ))
}

fn paper_100(r: &Runner) -> Result<String, LabError> {
    let (out, _) = main_run(r)?;
    Ok(fenced(&lines_between(&out, "paper-100:", "report:")?))
}

fn du(path: &Path) -> u64 {
    let Ok(meta) = std::fs::symlink_metadata(path) else { return 0 };
    if meta.is_dir() {
        std::fs::read_dir(path).map(|d| d.flatten().map(|e| du(&e.path())).sum()).unwrap_or(0)
    } else {
        meta.len()
    }
}

fn disk_use(r: &Runner) -> Result<String, LabError> {
    main_run(r)?;
    let mb = |p: &Path| du(p) as f64 / 1e6;
    let mut rows = Vec::new();
    for name in ["paper-100", "accelerograms"] {
        let root = r.root.join("reports").join(name);
        let runs = read_parquet_if_present(&Folder::new(&root).gathered(&RUNS))?
            .map(|df| Runs::read(&df))
            .transpose()?
            .ok_or_else(|| setup(&format!("no runs table in reports/{name}")))?;
        let seeds = runs.seed.len();
        rows.push(format!(
            "| `reports/{name}` | {seeds} | {:.0} MB | {:.0} MB | {:.0} MB | {:.0} MB | {:.1} MB |",
            mb(&root),
            mb(&root.join("tables")),
            mb(&root.join("records")),
            mb(&root.join("figures")),
            mb(&root) / seeds as f64
        ));
    }
    Ok(format!(
        "| folder | seeds | in all | tables | record files | figures | per seed |\n|---|---|---|---|---|---|---|\n{}\n",
        rows.join("\n")
    ))
}

fn paper_precise(r: &Runner) -> Result<String, LabError> {
    // A folder of an earlier run would be resumed ("0 run now, 16 already done"), not run: moved
    // aside, and deleted with the main command's (see `remove_main_set_aside`).
    crate::ensemble_cost::set_aside(&r.root.join("reports/paper-precise"))?;
    let (out, _) = r.run(&["pipeline", "pipelines/paper-precise.toml", "--fresh", "--quiet"])?;
    Ok(fenced(&lines_between(&out, "paper-precise:", "precision target")?))
}

fn wall_times(r: &Runner) -> Result<String, LabError> {
    let mut walls = Vec::new();
    let outs = ["1", "2"].map(|threads| (threads, format!("reports/bench/readme-paper-100-threads-{threads}")));
    for (threads, out) in &outs {
        // A folder left by an earlier, interrupted run would be resumed, not run: moved aside
        // (not deleted just before a timed run, see `ensemble_cost::set_aside`).
        crate::ensemble_cost::set_aside(&r.root.join(out))?;
        let (_, wall) =
            r.run(&["pipeline", "pipelines/paper-100.toml", "--fresh", "--quiet", "--threads", threads, "--out", out])?;
        walls.push(wall);
    }
    // Deleted after both runs, not between them.
    for (_, out) in &outs {
        let _ = std::fs::remove_dir_all(r.root.join(out));
    }
    crate::ensemble_cost::remove_set_aside(&r.root.join("reports/bench"));
    Ok(format!(
        "Ensemble wall time of `paper-100` (100 seeds, with each main shock's records and their response spectra \
         and RotD, and the report) on the machine that last ran `stickslip-bench readme` ({}): {:.1} s with \
         `--threads 1`, {:.1} s with `--threads 2` ({:.2}×).\n",
        machine(),
        walls[0],
        walls[1],
        walls[0] / walls[1]
    ))
}

fn calibration(r: &Runner) -> Result<String, LabError> {
    main_run(r)?;
    let (out, _) = r.run(&["seeds", "reports/paper"])?;
    Ok(format!("{}\n", out.trim_end()))
}

fn slow_loading(r: &Runner) -> Result<String, LabError> {
    r.run(&["pipeline", "pipelines/slow-loading.toml", "--fresh", "--quiet"])?;
    let folder = r.folder("reports/slow-loading");
    let read = |t: &TableSpec| -> Result<polars::prelude::DataFrame, LabError> {
        read_parquet_if_present(&folder.gathered(t))?.ok_or_else(|| setup(&format!("no {} table", t.name)))
    };
    let bv = BValues::read(&read(&B_VALUES)?)?;
    let rs = RecurrenceStats::read(&read(&RECURRENCE_STATS)?)?;
    let om = Omori::read(&read(&OMORI)?)?;
    let sc = Scaling::read(&read(&SCALING)?)?;
    let runs = Runs::read(&read(&RUNS)?)?;
    let (events, mains) = (runs.events.iter().sum::<u64>(), runs.main_shocks.iter().sum::<u64>());
    let pooled = |seed: &[Option<u64>]| (0..seed.len()).filter(|&i| seed[i].is_none()).collect::<Vec<_>>();
    let b = pooled(&bv.seed)
        .into_iter()
        .find(|&i| bv.quantity[i] == "mw_consistent")
        .ok_or_else(|| setup("no pooled b-value of mw_consistent"))?;
    let b_cell = match (bv.b[b], bv.b_sigma[b], bv.mc[b]) {
        (Some(v), Some(s), Some(mc)) => {
            format!("{v:.2} ± {s:.2} above Mc {mc:.1} ({} events)", bv.events_above_mc[b].unwrap_or(0))
        }
        _ => format!("no b-value: {}", bv.reason[b].clone().unwrap_or_default()),
    };
    let rec = |sequence: &str| -> Result<String, LabError> {
        let i = pooled(&rs.seed)
            .into_iter()
            .find(|&i| rs.sequence[i] == sequence)
            .ok_or_else(|| setup(&format!("no pooled recurrence row of {sequence}")))?;
        Ok(match (rs.cv[i], rs.cv_low[i], rs.cv_high[i]) {
            (Some(c), Some(lo), Some(hi)) => format!("{c:.2} [{lo:.2}, {hi:.2}]"),
            (Some(c), _, _) => format!("{c:.2}"),
            _ => format!("no CV: {}", rs.reason[i].clone().unwrap_or_default()),
        })
    };
    let main_row = pooled(&rs.seed).into_iter().find(|&i| rs.sequence[i] == "main");
    let bpt = main_row
        .and_then(|i| {
            let aics = [("BPT", rs.bpt_aic[i]), ("Weibull", rs.weibull_aic[i]), ("Poisson", rs.exponential_aic[i])];
            let best = aics.iter().filter_map(|(n, a)| a.map(|a| (*n, a))).min_by(|a, b| a.1.total_cmp(&b.1))?;
            Some(format!(
                "; {} preferred by AIC{}",
                best.0,
                rs.bpt_aperiodicity[i].map(|a| format!(" (BPT α = {a:.2})")).unwrap_or_default()
            ))
        })
        .unwrap_or_default();
    let o = pooled(&om.seed).into_iter().next().ok_or_else(|| setup("no pooled Omori row"))?;
    let (omori, omori_reading) = match (om.p[o], om.p_se[o]) {
        (Some(p), Some(se)) => (
            format!("{} ± {se:.2} ({} events after {} main shocks)", minus(p, 2), om.aftershocks[o], om.main_shocks[o]),
            if p + 2.0 * se < 0.5 {
                "no aftershock decay: activity after a main shock does not fall (it grows toward the next one when p < 0) — the small events are precursory slips of the next main shock, not aftershocks"
            } else {
                "activity falls after a main shock, as aftershocks do"
            },
        ),
        _ => (format!("no fit: {}", om.reason[o].clone().unwrap_or_default()), "—"),
    };
    let relation = |name: &str| -> String {
        match pooled(&sc.seed).into_iter().find(|&i| sc.relation[i] == name) {
            Some(i) => match (sc.exponent[i], sc.exponent_low[i], sc.exponent_high[i]) {
                (Some(e), Some(lo), Some(hi)) => {
                    format!(
                        "{} [{}, {}] (self-similar {})",
                        minus(e, 2),
                        minus(lo, 2),
                        minus(hi, 2),
                        sc.self_similar[i]
                    )
                }
                _ => format!("no fit: {}", sc.reason[i].clone().unwrap_or_default()),
            },
            None => "no row".into(),
        }
    };
    let rows = [
        format!(
            "| b (Mw, consistent moment) | {b_cell} | far steeper than the b ≈ 1 of natural catalogues: with the \
             paper's full-contact area every event's moment is its stress drop times one area, and drops vary only \
             within a factor of a few, so sizes are characteristic, not power-law |"
        ),
        format!(
            "| main-shock recurrence CV | {}{bpt} | periodic below 1, Poisson at 1, clustered above (the paper scene's \
             fast loading gives CV 0.10: quasi-periodic) |",
            rec("main")?
        ),
        format!("| all-event recurrence CV | {} | |", rec("all")?),
        format!("| Omori p | {omori} | {omori_reading} |"),
        format!(
            "| moment–duration exponent | {} | durations hardly grow with moment when every event slips the whole \
             block |",
            relation("moment_duration")
        ),
        format!(
            "| moment–area | {} | with the contact area every event has the same area: set `[similarity] area = \
             \"rupture\"` (with `slipping_nodes` recorded) for per-event areas; stress drop against Mw then has slope \
             1.5 by construction |",
            relation("moment_area")
        ),
    ];
    Ok(format!(
        "From `stickslip pipeline pipelines/slow-loading.toml` ({} seed, {events} events, {mains} main shocks) and \
         `stickslip catalogue reports/slow-loading`:\n\n| statistic | value | reading |\n|---|---|---|\n{}\n",
        runs.seed.len(),
        rows.join("\n")
    ))
}

/// The files that may hold generated blocks, relative to the repository's root `root`:
/// `README.md`, then every `docs/guide/*.md` in name order.
pub fn block_files(root: &Path) -> Result<Vec<PathBuf>, LabError> {
    let guide = root.join("docs/guide");
    let entries = std::fs::read_dir(&guide).map_err(|e| setup(&format!("{}: {e}", guide.display())))?;
    let mut chapters: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "md") && p.is_file())
        .filter_map(|p| p.strip_prefix(root).ok().map(Path::to_path_buf))
        .collect();
    chapters.sort();
    Ok(std::iter::once(PathBuf::from("README.md")).chain(chapters).collect())
}

/// One file of [`block_files`]: its path relative to the repository's root and its text.
#[derive(Clone, Debug, PartialEq)]
pub struct Doc {
    /// Relative to the repository's root.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
}

/// Reads every file of [`block_files`] under `root`.
pub fn read_docs(root: &Path) -> Result<Vec<Doc>, LabError> {
    block_files(root)?
        .into_iter()
        .map(|path| {
            let text = std::fs::read_to_string(root.join(&path))
                .map_err(|e| setup(&format!("{}: {e}", root.join(&path).display())))?;
            Ok(Doc { path, text })
        })
        .collect()
}

/// Which of `docs` holds each block: key → index into `docs`. A key found in two files is an
/// error (and, by [`blocks`], one found twice in a file).
pub fn locate(docs: &[Doc]) -> Result<BTreeMap<String, usize>, LabError> {
    let mut found: BTreeMap<String, usize> = BTreeMap::new();
    for (i, doc) in docs.iter().enumerate() {
        for (key, _) in blocks(&doc.text).map_err(|e| setup(&format!("{}: {e}", doc.path.display())))? {
            if let Some(&j) = found.get(&key) {
                return Err(setup(&format!(
                    "block {key} is in both {} and {}: a key belongs to one file",
                    docs[j].path.display(),
                    doc.path.display()
                )));
            }
            found.insert(key, i);
        }
    }
    Ok(found)
}

/// `text` with the wall times of a printout masked ("in 4.9 s" → "in … s"): a printout's time
/// differs from run to run, its numbers do not, so a block is stale only when those differ.
pub fn untimed(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split(' ').collect();
        let masked: Vec<&str> = (0..words.len())
            .map(|k| {
                let timed =
                    k > 0 && words[k - 1] == "in" && words.get(k + 1) == Some(&"s") && words[k].parse::<f64>().is_ok();
                if timed { "…" } else { words[k] }
            })
            .collect();
        out.push_str(&masked.join(" "));
        out.push('\n');
    }
    out
}

/// What [`rewrite`] found for one block.
pub struct BlockOutcome {
    /// The key.
    pub key: &'static str,
    /// The file holding it, relative to the repository's root.
    pub file: PathBuf,
    /// Whether the new text differs from the file's (wall times of printouts aside).
    pub changed: bool,
    /// Whether its text depends on the machine.
    pub measured: bool,
}

/// Regenerates the blocks of `docs` (those of `only`, or all) with `runner`; returns the new
/// texts (in the order of `docs`) and what changed. Every generator's key must be in exactly one
/// file, and every block in the files must have a generator.
pub fn rewrite(docs: &[Doc], runner: &Runner, only: &[String]) -> Result<(Vec<Doc>, Vec<BlockOutcome>), LabError> {
    let place = locate(docs)?;
    for k in place.keys() {
        if !GENERATORS.iter().any(|g| g.key == k) {
            return Err(setup(&format!("{} has a block {k} that no generator writes", docs[place[k]].path.display())));
        }
    }
    for k in only {
        if !GENERATORS.iter().any(|g| g.key == k) {
            let keys: Vec<&str> = GENERATORS.iter().map(|g| g.key).collect();
            return Err(setup(&format!("--only {k}: no such block (blocks: {})", keys.join(", "))));
        }
    }
    for g in GENERATORS {
        if !place.contains_key(g.key) {
            let files: Vec<String> = docs.iter().map(|d| d.path.display().to_string()).collect();
            return Err(setup(&format!(
                "no file holds the block {} ({}); looked in {}",
                g.key,
                opening(g.key),
                files.join(", ")
            )));
        }
    }
    let mut out = docs.to_vec();
    let mut outcomes = Vec::new();
    for g in GENERATORS.iter().filter(|g| only.is_empty() || only.iter().any(|k| k == g.key)) {
        let doc = &mut out[place[g.key]];
        eprintln!("{} ({}): {}", g.key, doc.path.display(), g.runs);
        let content = (g.make)(runner)?;
        let old = blocks(&doc.text)?.into_iter().find(|(k, _)| k == g.key).map(|(_, r)| doc.text[r].to_string());
        outcomes.push(BlockOutcome {
            key: g.key,
            file: doc.path.clone(),
            changed: old.as_deref().map(untimed) != Some(untimed(&content)),
            measured: g.measured,
        });
        doc.text = replace(&doc.text, g.key, &content)?;
    }
    Ok((out, outcomes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_are_found_and_replaced_leaving_the_rest_alone() {
        let text = format!(
            "intro\n{}\nold a\n{}\nmiddle\n{}\n```\nold b\n```\n{}\nend\n",
            opening("a"),
            closing("a"),
            opening("b"),
            closing("b")
        );
        let found = blocks(&text).unwrap();
        assert_eq!(found.iter().map(|(k, _)| k.as_str()).collect::<Vec<_>>(), ["a", "b"]);
        assert_eq!(&text[found[0].1.clone()], "old a\n");
        let new = replace(&text, "b", "new b\n").unwrap();
        assert_eq!(new, text.replace("```\nold b\n```\n", "new b\n"));
        assert!(new.starts_with("intro\n") && new.ends_with("end\n") && new.contains("old a"));
        // Malformed: no closing marker, a block twice, a block inside another.
        assert!(blocks(&format!("{}\nx\n", opening("a"))).is_err());
        let twice = format!("{}\n{}\n{}\n{}\n", opening("a"), closing("a"), opening("a"), closing("a"));
        assert!(blocks(&twice).is_err());
        let nested = format!("{}\n{}\n{}\n{}\n", opening("a"), opening("b"), closing("b"), closing("a"));
        assert!(blocks(&nested).is_err());
        assert!(replace(&text, "c", "x\n").is_err());
    }

    #[test]
    fn the_readme_and_the_guide_hold_every_generated_block_once() {
        let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
        let docs = read_docs(root).unwrap();
        assert_eq!(docs[0].path, Path::new("README.md"));
        assert!(docs.iter().any(|d| d.path == Path::new("docs/guide/README.md")), "the guide's index");
        let place = locate(&docs).unwrap();
        for g in GENERATORS {
            assert!(place.contains_key(g.key), "no file holds {}", opening(g.key));
        }
        assert_eq!(place.len(), GENERATORS.len(), "{place:?}");
        // The main command's time belongs beside the main command.
        assert_eq!(docs[place["main-command"]].path, Path::new("README.md"));
    }

    #[test]
    fn a_key_in_two_files_is_refused() {
        let doc = |path: &str, key: &str| Doc {
            path: PathBuf::from(path),
            text: format!("x\n{}\nold\n{}\n", opening(key), closing(key)),
        };
        let place = locate(&[doc("README.md", "a"), doc("docs/guide/b.md", "b")]).unwrap();
        assert_eq!((place["a"], place["b"]), (0, 1));
        let twice = locate(&[doc("README.md", "a"), doc("docs/guide/b.md", "a")]);
        let err = twice.err().unwrap().to_string();
        assert!(err.contains("README.md") && err.contains("docs/guide/b.md"), "{err}");
        // A key no file holds is refused by rewrite before anything runs.
        let runner = Runner::new(PathBuf::from("/nonexistent/stickslip"), PathBuf::from("/nonexistent"));
        let err = rewrite(&[doc("README.md", "main-command")], &runner, &[]).err().unwrap().to_string();
        assert!(err.contains("no file holds the block"), "{err}");
    }

    #[test]
    fn only_the_wall_times_of_a_printout_are_masked() {
        assert_eq!(
            untimed("a: 3 seeds in 9.2 s → x\nreport: 17 figures in 0.8 s → y"),
            untimed("a: 3 seeds in 4.1 s → x\nreport: 17 figures in 0.2 s → y")
        );
        assert_ne!(untimed("a: 3 seeds in 9.2 s"), untimed("a: 4 seeds in 9.2 s"));
        assert_eq!(untimed("in the 2 s window"), "in the 2 s window\n");
    }

    #[test]
    fn lines_between_takes_the_printout() {
        let out = "x\npaper-100: 100 seeds\nshock\nS1\nreport: 17 figures\nafter\n";
        assert_eq!(
            lines_between(out, "paper-100:", "report:").unwrap(),
            ["paper-100: 100 seeds", "shock", "S1", "report: 17 figures"]
        );
        assert!(lines_between(out, "nothing", "report:").is_err());
    }
}
