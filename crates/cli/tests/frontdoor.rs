//! The front door's promises, end to end: seed lists that cannot panic or run a seed twice, input
//! files that cannot hang, `--fresh` that leaves nothing of the discarded run, an exit status that
//! tells a failed ensemble from a good one, and a sharded run (through the Slurm scripts) of a
//! pipeline with a friction grid that merges to the plain run's tables.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use stickslip_support::{assert_same_tables, files_under, repo_path, scratch_dir};

fn stickslip(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip")).args(args).current_dir(cwd).output().expect("run stickslip")
}

/// `stickslip args` in `cwd`, killed after `limit` (then it hung): its output and wall time.
fn within(args: &[&str], cwd: &Path, limit: Duration) -> (Output, Duration) {
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .current_dir(cwd)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            let _ = child.kill();
            panic!("stickslip {args:?} did not end within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    (child.wait_with_output().unwrap(), start.elapsed())
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn out(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// A short paper scene (events within 0.1 s), seeds 1–4.
const SHORT: &str = r#"
version = 1
name = "short"
[seeds]
range = { first = 1, count = 4 }
[shear]
duration_s = 0.1
[record]
interval_s = 5e-5
[report]
enabled = false
"#;

#[test]
fn seed_lists_refuse_what_does_not_fit_or_repeats_and_run_each_seed_once() {
    let dir = scratch_dir("frontdoor-seeds");
    std::fs::write(dir.join("p.toml"), SHORT).unwrap();
    for (seeds, says) in [("0-18446744073709551615", "more than 10000000 seeds"), ("1-300000000", "more than 10000000")]
    {
        let (o, took) = within(&["pipeline", "p.toml", "--seeds", seeds, "--quiet"], &dir, Duration::from_secs(20));
        assert_eq!(o.status.code(), Some(1), "{seeds}: {}", err(&o));
        assert!(err(&o).contains(says), "{seeds}: {}", err(&o));
        assert!(took < Duration::from_secs(5), "{seeds} took {took:?} to refuse");
        assert!(!dir.join("reports").exists(), "{seeds}: something was written");
    }
    // A seed named twice is refused (it would run once: the user may have meant another).
    let o = stickslip(&["pipeline", "p.toml", "--seeds", "2,3,2", "--quiet", "--out", "o"], &dir);
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    assert!(err(&o).contains("seed 2 is named twice"), "{}", err(&o));
    assert!(!dir.join("o").exists(), "something was written");
    let o = stickslip(&["pipeline", "p.toml", "--seeds", "2,3", "--quiet", "--out", "o"], &dir);
    assert!(o.status.success(), "{}", err(&o));
    assert!(out(&o).contains("short: 2 seeds (2 run now"), "{}", out(&o));
    let runs: Vec<_> = std::fs::read_dir(dir.join("o/tables/runs")).unwrap().collect();
    assert_eq!(runs.len(), 2, "seed 2 once, seed 3 once");
}

#[test]
fn input_files_that_never_end_are_refused_at_once() {
    let dir = scratch_dir("frontdoor-inputs");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.csv")).unwrap();
    let fifo = std::ffi::CString::new(dir.join("fifo.csv").to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path.
    assert_eq!(unsafe { libc::mkfifo(fifo.as_ptr(), 0o600) }, 0);
    std::fs::write(dir.join("secret.csv"), "the first line of a private file\n").unwrap();
    for (key, file, says) in [
        ("[friction.grid]\nfile", "zero.csv", "not a regular file"),
        ("[friction.grid]\nfile", "fifo.csv", "not a regular file"),
        ("[friction.grid]\nfile", "/dev/zero", "no absolute path"),
        ("[friction.grid]\nfile", "secret.csv", "its first line (after # comments) is not that header"),
        ("[set]\ntarget = \"csv\"\ntarget_csv", "fifo.csv", "not a regular file"),
        ("[set]\ntarget = \"csv\"\ntarget_csv", "secret.csv", "two arrays of the same length"),
    ] {
        let text = format!("version = 1\n[[record.control]]\nnodes = [36]\n[spectra]\n{key} = {file:?}\n");
        std::fs::write(dir.join("p.toml"), text).unwrap();
        let (o, took) = within(&["check", "p.toml"], &dir, Duration::from_secs(30));
        assert_eq!(o.status.code(), Some(1), "{file}: {}", err(&o));
        assert!(err(&o).contains(says), "{file}: {}", err(&o));
        assert!(!err(&o).contains("private file"), "{file}: the file's content was echoed: {}", err(&o));
        assert!(took < Duration::from_secs(10), "{file} took {took:?}");
    }
    // The pipeline file itself.
    let (o, _) = within(&["check", "fifo.csv"], &dir, Duration::from_secs(10));
    assert_eq!(o.status.code(), Some(1));
    assert!(err(&o).contains("not a regular file"), "{}", err(&o));
}

#[test]
fn a_pipeline_whose_every_seed_fails_exits_non_zero_after_writing_its_tables() {
    let dir = scratch_dir("frontdoor-failed");
    // Δt far above the critical step: every seed is refused by the solver.
    std::fs::write(dir.join("p.toml"), format!("{SHORT}[time]\ndt_s = 1e-3\n")).unwrap();
    let o = stickslip(&["pipeline", "p.toml", "--quiet", "--out", "o"], &dir);
    assert_eq!(o.status.code(), Some(1), "{}{}", out(&o), err(&o));
    assert!(err(&o).contains("every seed failed (4)"), "{}", err(&o));
    assert!(out(&o).contains("seed 1 failed: time step"), "{}", out(&o));
    assert!(dir.join("o/tables/runs.parquet").exists(), "the failures are still tabled");
    // A shard whose every seed failed fails too (a Slurm afterok merge does not run).
    let o = stickslip(&["pipeline", "p.toml", "--quiet", "--out", "s", "--shard", "1/2"], &dir);
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    assert!(err(&o).contains("every seed of the shard failed"), "{}", err(&o));
    let o = stickslip(&["pipeline", "p.toml", "--quiet", "--out", "s", "--shard", "2/2"], &dir);
    assert_eq!(o.status.code(), Some(1));
    let o = stickslip(&["merge", "s"], &dir);
    assert_eq!(o.status.code(), Some(1), "{}", err(&o));
    assert!(err(&o).contains("every seed failed"), "{}", err(&o));
}

/// A record interval far finer than the step, with records resampled to it (the fuzz's
/// 1.3e17-byte resampling), is refused once Δt is known and before the first step: by `check`,
/// and by each seed of `pipeline` and `run`, naming record.interval_s, its value and the least
/// allowed. Without records it samples every step.
#[test]
fn a_record_interval_finer_than_half_the_step_is_refused_before_stepping() {
    let dir = scratch_dir("frontdoor-fine-records");
    let records = "[[record.control]]\nnodes = [36]\n[accelerograms]\n";
    let fine = SHORT.replace("interval_s = 5e-5", "interval_s = 1e-9");
    std::fs::write(dir.join("p.toml"), format!("{fine}{records}")).unwrap();
    // pipeline prints each seed's failure on stdout, run and check on stderr.
    let says = |o: &Output| {
        let e = format!("{}{}", out(o), err(o));
        assert!(e.contains("record.interval_s = 1e-9 s is finer than this run can sample"), "{e}");
        assert!(
            e.contains("give record.interval_s at least Δt/2 = ") && e.contains("pipeline keys: record.interval_s"),
            "{e}"
        );
    };
    let (o, _) = within(&["check", "p.toml"], &dir, Duration::from_secs(30));
    assert_eq!(o.status.code(), Some(1), "{}", out(&o));
    says(&o);
    assert!(!out(&o).contains("run: "), "refused before the run's length is probed:\n{}", out(&o));
    for args in [
        &["pipeline", "p.toml", "--quiet", "--out", "o"][..],
        &["run", "p.toml", "--seed", "1", "--out", "r", "--quiet"],
    ] {
        // A 0.1-s stage at 1e-9 s would be 1e8 samples: refused in well under its run time.
        let (o, took) = within(args, &dir, Duration::from_secs(60));
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", out(&o));
        says(&o);
        assert!(took < Duration::from_secs(10), "{args:?} took {took:?}");
    }
    // Half a step is still sampled every step: accepted; and without records, any interval.
    let half = SHORT.replace("interval_s = 5e-5", "interval_s = 5.5e-6");
    for text in [format!("{half}{records}"), fine] {
        std::fs::write(dir.join("p.toml"), text).unwrap();
        let o = stickslip(&["check", "p.toml"], &dir);
        assert!(o.status.success(), "{}", err(&o));
    }
}

/// `stickslip pipeline p.toml | head -1`: the reader goes away after a line, and the run still
/// writes its tables and report and exits normally (a broken pipe killed it at its next print,
/// before the report). `check`, which only reads, may end at once.
#[test]
fn a_reader_that_goes_away_does_not_stop_the_run_before_its_outputs() {
    let dir = scratch_dir("frontdoor-epipe");
    let text =
        SHORT.replace("range = { first = 1, count = 4 }", "list = [1, 2]").replace("enabled = false", "enabled = true");
    std::fs::write(dir.join("p.toml"), text).unwrap();
    for command in ["pipeline", "run"] {
        let mut args = vec![command, "p.toml", "--out", command];
        if command == "run" {
            args.extend(["--seed", "1"]);
        }
        let mut child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
            .args(&args)
            .current_dir(&dir)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // The read end closed before the command prints a line (`head -0`).
        drop(child.stdout.take());
        let o = child.wait_with_output().unwrap();
        assert_eq!(o.status.code(), Some(0), "{command}: {:?}\n{}", o.status, err(&o));
        assert!(dir.join(command).join("index.html").exists(), "{command}: no report");
        assert!(dir.join(command).join("tables/runs.parquet").exists(), "{command}: no runs table");
    }
}

/// `check` writes the block's mass and the friction map's patch extents short: not
/// `mass 5184.000 kg` or `2.136e16` with three decimals, not `x 0.8999999999999999…` on a
/// lattice of Lc = 0.3 m.
#[test]
fn check_writes_the_mass_and_patch_extents_short() {
    let dir = scratch_dir("frontdoor-check-numbers");
    let text =
        std::fs::read_to_string(repo_path("pipelines/fault-barrier.toml")).unwrap().replace("lc_m = 0.1", "lc_m = 0.3");
    assert!(text.contains("lc_m = 0.3"));
    std::fs::write(dir.join("p.toml"), text).unwrap();
    let o = stickslip(&["check", "p.toml", "--seeds", "1"], &dir);
    assert!(o.status.success(), "{}", err(&o));
    let printed = out(&o);
    assert!(printed.contains("82 contact nodes, mass 5184 kg"), "{printed}");
    assert!(printed.contains("patch (weak): 6 nodes, x 0.3…0.9 m"), "{printed}");
    assert!(printed.contains("barrier (barrier): 8 nodes, x 3…3.9 m"), "{printed}");
}

#[test]
fn fresh_leaves_nothing_of_the_discarded_run() {
    let dir = scratch_dir("frontdoor-fresh");
    let with_records = format!(
        "{}\n[[record.control]]\nnodes = [36]\ncomponents = [\"z\"]\n[accelerograms]\nformats = [\"at2\"]\n",
        SHORT.replace("enabled = false", "enabled = true")
    );
    std::fs::write(dir.join("a.toml"), with_records.replace("name = \"short\"", "name = \"a\"")).unwrap();
    let o = stickslip(&["pipeline", "a.toml", "--quiet", "--out", "o"], &dir);
    assert!(o.status.success(), "{}", err(&o));
    let records = std::fs::read_dir(dir.join("o/records")).unwrap().count();
    assert!(records > 0, "the first run wrote records");
    assert!(std::fs::read_to_string(dir.join("o/index.html")).unwrap().contains("records/a_seed"));
    // Another pipeline (other hash, no records) into the same folder with --fresh.
    let other = SHORT.replace("name = \"short\"", "name = \"a\"").replace("enabled = false", "enabled = true");
    std::fs::write(dir.join("b.toml"), format!("{other}[events]\nmin_drop_pa = 600.0\n")).unwrap();
    let o = stickslip(&["pipeline", "b.toml", "--quiet", "--out", "o"], &dir);
    assert_eq!(o.status.code(), Some(1), "another pipeline's folder is refused without --fresh");
    let o = stickslip(&["pipeline", "b.toml", "--quiet", "--out", "o", "--fresh"], &dir);
    assert!(o.status.success(), "{}", err(&o));
    let left: Vec<_> = files_under(&dir.join("o")).into_iter().filter(|f| f.starts_with("records")).collect();
    assert!(left.is_empty(), "records of the discarded run survived: {left:?}");
    let page = std::fs::read_to_string(dir.join("o/index.html")).unwrap();
    assert!(!page.contains("records/"), "the page links records of the discarded run");
}

/// A paper block on a friction grid (a CSV file beside the pipeline), four seeds.
fn grid_pipeline(dir: &Path) {
    let mut csv = String::from("x_m,y_m,mu_static,mu_dynamic,slip_weakening_m\n");
    for i in 0..=10 {
        for j in 0..=1 {
            let mu = if i < 4 { 4.5 } else { 5.0 };
            csv += &format!("{},{},{mu},{mu},0\n", i as f64 * 0.1, j as f64 * 0.1);
        }
    }
    std::fs::create_dir_all(dir.join("grids")).unwrap();
    std::fs::write(dir.join("grids/mu.csv"), csv).unwrap();
    let text = SHORT.replace("name = \"short\"", "name = \"grid\"")
        + "[friction]\nmu_static = 5.0\n[friction.grid]\nfile = \"grids/mu.csv\"\n";
    std::fs::write(dir.join("grid.toml"), text).unwrap();
}

#[test]
fn a_sharded_grid_pipeline_merges_through_the_slurm_scripts_to_the_plain_run() {
    let dir = scratch_dir("frontdoor-shards");
    let src = dir.join("src");
    grid_pipeline(&src);
    let o = stickslip(&["pipeline", "src/grid.toml", "--quiet", "--out", "plain"], &dir);
    assert!(o.status.success(), "{}", err(&o));
    // Three shards, as a Slurm job array runs them (ensemble.sbatch per task), then the merge job.
    let bin = env!("CARGO_BIN_EXE_stickslip");
    for k in 1..=3 {
        let o = Command::new("bash")
            .arg(repo_path("pipelines/slurm/ensemble.sbatch"))
            .current_dir(&dir)
            .env("PIPELINE", src.join("grid.toml"))
            .env("OUT", dir.join("sharded"))
            .env("SHARDS", "3")
            .env("SLURM_ARRAY_TASK_ID", k.to_string())
            .env("STICKSLIP", bin)
            .output()
            .unwrap();
        assert!(o.status.success(), "shard {k}: {}", err(&o));
    }
    // The pipeline's own folder is gone by the time the merge runs: the output folder has all
    // it needs (the pipeline copy points at its copy of the grid).
    std::fs::remove_dir_all(&src).unwrap();
    let copy = std::fs::read_to_string(dir.join("sharded/pipeline.toml")).unwrap();
    assert!(copy.contains("file = \"inputs/friction.grid.file/mu.csv\""), "{copy}");
    assert!(dir.join("sharded/inputs/friction.grid.file/mu.csv").is_file());
    // A wrong shard count is refused, naming the shards that ran.
    let o = stickslip(&["merge", "sharded", "--shards", "2"], &dir);
    assert_eq!(o.status.code(), Some(1));
    assert!(err(&o).contains("--shards 2, but the shards that ran here were 1/3, 2/3, 3/3"), "{}", err(&o));
    let o = Command::new("bash")
        .arg(repo_path("pipelines/slurm/merge.sbatch"))
        .current_dir(&dir)
        .env("OUT", dir.join("sharded"))
        .env("SHARDS", "3")
        .env("STICKSLIP", bin)
        .output()
        .unwrap();
    assert!(o.status.success(), "merge.sbatch: {}", err(&o));
    assert!(out(&o).contains("merged 4 seeds (0 failed)"), "{}", out(&o));
    assert_same_tables(&dir.join("sharded/tables"), &dir.join("plain/tables"), &["wall_time_s"]);
}

#[test]
fn merge_names_the_shard_that_never_ran() {
    let dir = scratch_dir("frontdoor-missing-shard");
    std::fs::write(dir.join("p.toml"), SHORT).unwrap();
    for k in ["1/3", "3/3"] {
        let o = stickslip(&["pipeline", "p.toml", "--quiet", "--out", "o", "--shard", k], &dir);
        assert!(o.status.success(), "{}", err(&o));
    }
    let o = stickslip(&["merge", "o"], &dir);
    assert_eq!(o.status.code(), Some(1));
    assert!(err(&o).contains("shards 2 of 3 never started here"), "{}", err(&o));
}

#[test]
fn check_warns_of_what_it_accepts_but_could_mislead() {
    let dir = scratch_dir("frontdoor-warn");
    // Records sampled every 2e-4 s: 0.8 of Nyquist is 2000 Hz, below the lattice's 5078 Hz.
    let text = "version = 1\n[record]\ninterval_s = 2e-4\n[[record.control]]\nnodes = [36]\n[accelerograms]\n";
    std::fs::write(dir.join("p.toml"), text).unwrap();
    let o = stickslip(&["check", "p.toml"], &dir);
    assert!(o.status.success(), "{}", err(&o));
    assert!(
        out(&o).contains(
            "warning: record.interval_s = 0.0002: records sampled every 0.0002 s are band-limited to 2000.0 Hz"
        ),
        "{}",
        out(&o)
    );
    // Clones: no random field, several seeds.
    std::fs::write(dir.join("c.toml"), "version = 1\n[seeds]\nlist = [1, 2]\n[material]\nyoung_cv = 0.0\n").unwrap();
    let o = stickslip(&["check", "c.toml"], &dir);
    assert!(out(&o).contains("every one of the 2 seeds gives the same run"), "{}", out(&o));
}
