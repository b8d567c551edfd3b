//! What an ensemble costs end to end (`stickslip-bench ensemble`): the wall time of
//! `stickslip pipeline` on 1 and 2 threads for two builds of the product run alternately in one
//! session (a previous build against this one), the size of what each writes, where the time
//! goes (a profile by stage, in this process on one thread), and the time of gathering and
//! reporting a large folder with each build (`stickslip merge`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use stickslip_config::Pipeline;
use stickslip_ensemble::{EnsembleOptions, Profile, run_ensemble};

use crate::LabError;

type Result<T> = std::result::Result<T, LabError>;

fn setup(what: impl std::fmt::Display) -> LabError {
    LabError::Setup(what.to_string())
}

/// One build of the product to time.
#[derive(Clone, Debug)]
pub struct Build {
    /// What to call it in the tables.
    pub label: String,
    /// Its `stickslip` binary.
    pub binary: PathBuf,
}

/// Runs `build pipeline <pipeline> --fresh --threads <threads> --out <out> --quiet` into an empty
/// `out` (an earlier one set aside first, see [`set_aside`]: `--fresh` discards only another
/// pipeline's results, and a finished folder of the same pipeline would be resumed, not run) and
/// returns its wall time (s) and what it printed.
pub fn time_pipeline(build: &Build, pipeline: &Path, threads: usize, out: &Path) -> Result<(f64, String)> {
    set_aside(out)?;
    let start = Instant::now();
    let o = Command::new(&build.binary)
        .args(["pipeline", &pipeline.display().to_string(), "--fresh", "--quiet", "--threads"])
        .arg(threads.to_string())
        .arg("--out")
        .arg(out)
        .output()
        .map_err(|e| setup(format!("running {}: {e}", build.binary.display())))?;
    let wall = start.elapsed().as_secs_f64();
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    if !o.status.success() {
        return Err(setup(format!("{} pipeline failed: {text}{}", build.label, String::from_utf8_lossy(&o.stderr))));
    }
    Ok((wall, text))
}

/// Moves an earlier `out` aside (renamed to a sibling `<name>.set-aside-<n>`) instead of deleting
/// it just before a timed run: on an ext4 file system without a journal (this project's
/// development machine), creating files within a minute or so of deleting many makes the kernel
/// step over each recently freed inode one by one (`recently_deleted` in its inode allocator),
/// which was seen to add up to a second of system time to a run of paper-100 (1 234 files).
/// [`remove_set_aside`] deletes them once the timing is done (they take the disk of every repeat
/// until then).
pub fn set_aside(out: &Path) -> Result<()> {
    if !out.exists() {
        return Ok(());
    }
    let name = out.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
    for n in 0.. {
        let aside = out.with_file_name(format!("{name}.set-aside-{n}"));
        if !aside.exists() {
            return std::fs::rename(out, &aside).map_err(|e| setup(format!("moving {} aside: {e}", out.display())));
        }
    }
    unreachable!("some name is free")
}

/// Deletes the folders [`set_aside`] moved aside in `dir`.
pub fn remove_set_aside(dir: &Path) {
    for e in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        if e.file_name().to_string_lossy().contains(".set-aside-") {
            std::fs::remove_dir_all(e.path()).ok();
        }
    }
}

/// Runs `build merge <out>` and returns its wall time and what it printed.
pub fn time_merge(build: &Build, out: &Path) -> Result<(f64, String)> {
    let start = Instant::now();
    let o = Command::new(&build.binary)
        .arg("merge")
        .arg(out)
        .output()
        .map_err(|e| setup(format!("running {}: {e}", build.binary.display())))?;
    let wall = start.elapsed().as_secs_f64();
    let text = String::from_utf8_lossy(&o.stdout).to_string();
    if !o.status.success() {
        return Err(setup(format!("{} merge failed: {text}{}", build.label, String::from_utf8_lossy(&o.stderr))));
    }
    Ok((wall, text))
}

/// The first number after `key` in `text` (e.g. the seconds of "report: 17 figures in 0.8 s").
pub fn number_after(text: &str, key: &str) -> Option<f64> {
    let rest = &text[text.find(key)? + key.len()..];
    let start = rest.find(|c: char| c.is_ascii_digit())?;
    let num: String = rest[start..].chars().take_while(|c| c.is_ascii_digit() || *c == '.').collect();
    num.parse().ok()
}

/// Bytes under `dir`, in all and per entry of `dir` and of `dir/tables` (largest first).
pub fn sizes(dir: &Path) -> (u64, Vec<(String, u64)>) {
    fn walk(p: &Path) -> u64 {
        match std::fs::metadata(p) {
            Ok(m) if m.is_dir() => std::fs::read_dir(p).into_iter().flatten().flatten().map(|e| walk(&e.path())).sum(),
            Ok(m) => m.len(),
            Err(_) => 0,
        }
    }
    let mut parts = Vec::new();
    for base in [dir.to_path_buf(), dir.join("tables")] {
        for e in std::fs::read_dir(&base).into_iter().flatten().flatten() {
            let p = e.path();
            if p == dir.join("tables") {
                continue;
            }
            let name = p.strip_prefix(dir).unwrap_or(&p).display().to_string();
            parts.push((name, walk(&p)));
        }
    }
    parts.sort_by_key(|p| std::cmp::Reverse(p.1));
    (walk(dir), parts)
}

/// The profile of one ensemble run in this process on `threads` threads (fresh, into `out`),
/// with the report's time; returns (profile, wall time of the ensemble, report time).
pub fn profile(pipeline: &Pipeline, threads: usize, out: &Path) -> Result<(Profile, f64, f64)> {
    let options =
        EnsembleOptions { out: out.to_path_buf(), threads, seeds: pipeline.seeds.clone(), fresh: true, finish: true };
    set_aside(out)?;
    let r = run_ensemble(pipeline, &options, &|_, _| {}, &AtomicBool::new(false)).map_err(setup)?;
    let start = Instant::now();
    stickslip_report::write_report(out, pipeline)?;
    Ok((r.profile, r.wall_time_s, start.elapsed().as_secs_f64()))
}
