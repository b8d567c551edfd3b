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
/// until then). Returns where it was moved, if it existed.
pub fn set_aside(out: &Path) -> Result<Option<PathBuf>> {
    if !out.exists() {
        return Ok(None);
    }
    let name = out.file_name().map(|n| n.to_string_lossy().to_string()).unwrap_or_default();
    for n in 0.. {
        let aside = out.with_file_name(format!("{name}.set-aside-{n}"));
        if !aside.exists() {
            std::fs::rename(out, &aside).map_err(|e| setup(format!("moving {} aside: {e}", out.display())))?;
            return Ok(Some(aside));
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

/// One rung of [`floors`]: the pipeline, or a variant of it that leaves out an analysis stage
/// and everything after it.
#[derive(Clone, Debug)]
pub struct Floor {
    /// What the rung adds to the one before, for the table.
    pub label: String,
    /// Its pipeline file.
    pub pipeline: PathBuf,
}

/// The rungs of `stickslip-bench ensemble --floors`, cheapest first, the pipeline as given last:
/// variants of `pipeline` (its file as read) without records (no `[accelerograms]`, `[spectra]`
/// or `[set]`), without spectra (no `[spectra]` — no response or Fourier spectra, no
/// attenuation — and no `[set]`) and without RotD (`[spectra] rotd = false`, no `[set]`, which
/// may match RotD50), only those that differ from the pipeline; the stepping and what it records
/// are left as they are. The wall time of each rung against the one before says what a stage
/// adds to a run. Every variant is validated before any is written into `dir` (as TOML). A
/// pipeline that reads input files (a friction grid, a CSV target) is refused: they are found
/// relative to the pipeline's own folder.
pub fn floors(pipeline: &Pipeline, dir: &Path) -> Result<Vec<Floor>> {
    let (Some(text), Some(source)) = (pipeline.text.as_deref(), pipeline.source.as_ref()) else {
        return Err(setup("--floors needs a pipeline read from a file"));
    };
    if !pipeline.inputs.is_empty() {
        return Err(setup(format!(
            "--floors: {} reads input files ({}), which its variants, written to {}, would not find",
            pipeline.name,
            pipeline.inputs.iter().map(|f| f.path.display().to_string()).collect::<Vec<_>>().join(", "),
            dir.display()
        )));
    }
    let full: toml::Table = toml::from_str(text).map_err(|e| setup(format!("the pipeline file: {e}")))?;
    let without = |keys: &[&str]| {
        let mut t = full.clone();
        for k in keys {
            t.remove(*k);
        }
        t
    };
    // What the pipeline computes, as validated (`[spectra]` without `[accelerograms]` still makes
    // records, with the default settings).
    let analysis = &pipeline.analysis;
    let (records, spectra) = (analysis.accelerograms.is_some(), analysis.spectra.is_some());
    let rotd = analysis.spectra.as_ref().is_some_and(|s| s.rotd);
    let set = pipeline.set.is_some();
    let mut variants: Vec<(&str, toml::Table)> = Vec::new();
    if records {
        variants.push((
            "stepping, events and series (no [accelerograms], [spectra] or [set])",
            without(&["accelerograms", "spectra", "set"]),
        ));
    }
    if spectra {
        let mut t = without(&["spectra", "set"]);
        t.entry("accelerograms").or_insert_with(|| toml::Value::Table(toml::Table::new()));
        variants.push(("+ records: processing, intensity measures, the accelerograms table (no [spectra])", t));
    }
    if rotd {
        let mut t = without(&["set"]);
        if let Some(toml::Value::Table(s)) = t.get_mut("spectra") {
            s.insert("rotd".into(), toml::Value::Boolean(false));
        }
        variants.push(("+ response spectra of each record alone, Fourier spectra (rotd = false)", t));
    }
    let bodies = variants
        .iter()
        .enumerate()
        .map(|(k, (_, t))| {
            let body = toml::to_string(t).map_err(|e| setup(format!("writing a variant: {e}")))?;
            Pipeline::from_toml(&body, &pipeline.name)
                .map_err(|e| setup(format!("--floors: variant {k} of {} is refused: {e}", pipeline.name)))?;
            Ok(body)
        })
        .collect::<Result<Vec<String>>>()?;
    std::fs::create_dir_all(dir).map_err(|e| setup(format!("{}: {e}", dir.display())))?;
    let mut rungs = Vec::new();
    for (k, ((label, _), body)) in variants.iter().zip(bodies).enumerate() {
        let path = dir.join(format!("{}-floor-{k}.toml", pipeline.name));
        if let Err(e) = std::fs::write(&path, body) {
            std::fs::remove_dir_all(dir).ok();
            return Err(setup(format!("{}: {e}", path.display())));
        }
        rungs.push(Floor { label: label.to_string(), pipeline: path });
    }
    let last = if rotd {
        "RotD"
    } else if spectra {
        "response and Fourier spectra"
    } else if records {
        "records"
    } else {
        ""
    };
    let label = match (last, set) {
        ("", _) => "the pipeline as given".to_string(),
        (stage, false) => format!("the pipeline as given (+ {stage})"),
        (stage, true) => format!("the pipeline as given (+ {stage} and the record set)"),
    };
    rungs.push(Floor { label, pipeline: source.clone() });
    Ok(rungs)
}

/// The profile of one ensemble run in this process on `threads` threads (fresh, into `out`),
/// with the report's time; returns (profile, wall time of the ensemble, report time).
pub fn profile(pipeline: &Pipeline, threads: usize, out: &Path) -> Result<(Profile, f64, f64)> {
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: out.to_path_buf(),
        threads,
        seeds: pipeline.seeds.clone(),
        fresh: true,
        finish: true,
    };
    set_aside(out)?;
    let r = run_ensemble(pipeline, &options, &|_, _| {}, &AtomicBool::new(false)).map_err(setup)?;
    let start = Instant::now();
    stickslip_report::write_report(out, pipeline)?;
    Ok((r.profile, r.wall_time_s, start.elapsed().as_secs_f64()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pipeline(name: &str) -> Pipeline {
        Pipeline::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../pipelines").join(name)).unwrap()
    }

    /// `text` as a pipeline file of its own (beside the system's temporary files), loaded.
    fn edited(tag: &str, text: &str) -> (Pipeline, PathBuf) {
        let file = std::env::temp_dir().join(format!("stickslip-floors-{tag}-{}.toml", std::process::id()));
        std::fs::write(&file, text).unwrap();
        (Pipeline::load(&file).unwrap(), file)
    }

    #[test]
    fn the_floors_of_paper_100_leave_out_records_then_spectra_then_rotd_and_nothing_else() {
        let dir = std::env::temp_dir().join(format!("stickslip-floors-{}", std::process::id()));
        let full = pipeline("paper-100.toml");
        assert!(full.analysis.spectra.as_ref().is_some_and(|s| s.rotd) && full.analysis.accelerograms.is_some());
        let rungs = floors(&full, &dir);
        let loaded: Option<Vec<Pipeline>> =
            rungs.as_ref().ok().map(|r| r.iter().map(|f| Pipeline::load(&f.pipeline).unwrap()).collect());
        std::fs::remove_dir_all(&dir).unwrap();
        let (rungs, loaded) = (rungs.unwrap(), loaded.unwrap());
        assert_eq!(loaded.len(), 4);
        assert_eq!(rungs[3].pipeline, full.source.clone().unwrap());
        assert_eq!(rungs[3].label, "the pipeline as given (+ RotD)");
        let records = |p: &Pipeline| p.analysis.accelerograms.is_some();
        let spectra = |p: &Pipeline| p.analysis.spectra.clone();
        assert!(!records(&loaded[0]) && spectra(&loaded[0]).is_none());
        assert!(records(&loaded[1]) && spectra(&loaded[1]).is_none());
        assert!(records(&loaded[2]) && spectra(&loaded[2]).is_some_and(|s| !s.rotd));
        // Everything else is the pipeline's own, sections and defaults.
        for p in &loaded {
            let mut file = p.file.clone();
            file.accelerograms.clone_from(&full.file.accelerograms);
            file.spectra.clone_from(&full.file.spectra);
            assert_eq!(file, full.file);
            assert_eq!(p.seeds, full.seeds);
        }
    }

    #[test]
    fn spectra_without_accelerograms_still_have_their_records_in_the_floors() {
        let dir = std::env::temp_dir().join(format!("stickslip-floors-spectra-{}", std::process::id()));
        let text = pipeline("paper-100.toml").text.unwrap();
        let (a, b) = (text.find("[accelerograms]").unwrap(), text.find("[spectra]").unwrap());
        let (p, file) = edited("spectra", &format!("{}{}", &text[..a], &text[b..]));
        let rungs = floors(&p, &dir);
        let loaded: Option<Vec<Pipeline>> =
            rungs.as_ref().ok().map(|r| r.iter().map(|f| Pipeline::load(&f.pipeline).unwrap()).collect());
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_file(file).unwrap();
        let loaded = loaded.unwrap();
        // The rung without spectra keeps the records `[spectra]` made with the default settings.
        assert!(loaded[0].analysis.accelerograms.is_none() && loaded[1].analysis.accelerograms.is_some());
    }

    #[test]
    fn a_pipeline_without_analysis_is_its_only_floor() {
        let dir = std::env::temp_dir().join(format!("stickslip-floors-none-{}", std::process::id()));
        let text = pipeline("paper-100.toml").text.unwrap();
        let (p, file) = edited("none", &text[..text.find("[accelerograms]").unwrap()]);
        let rungs = floors(&p, &dir).unwrap();
        std::fs::remove_dir_all(&dir).ok();
        std::fs::remove_file(file).unwrap();
        assert_eq!(rungs.len(), 1);
        assert_eq!(rungs[0].label, "the pipeline as given");
    }

    #[test]
    fn a_variant_the_configuration_refuses_writes_nothing() {
        let dir = std::env::temp_dir().join(format!("stickslip-floors-refused-{}", std::process::id()));
        let mut p = pipeline("paper-100.toml");
        // An unknown key in `[spectra]`: the variant that keeps the section is refused, the
        // others are not, and none is written.
        let text = p.text.take().unwrap();
        p.text = Some(text.replace("period_count = 100", "period_count = 100\nno_such_key = 1"));
        let e = floors(&p, &dir).unwrap_err().to_string();
        assert!(e.contains("variant") && e.contains("refused"), "{e}");
        assert!(!dir.exists(), "files left behind: {}", dir.display());
    }
}
