//! What a new user meets: the README's numbers and paths against the binary and the clone, the
//! CLI's refusals and views, the scripts' refusals, and the Python example.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

fn stickslip(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip")).args(args).current_dir(cwd).output().expect("run stickslip")
}

fn text(o: &Output) -> (String, String) {
    (String::from_utf8_lossy(&o.stdout).into_owned(), String::from_utf8_lossy(&o.stderr).into_owned())
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-usability-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `pipelines/paper.toml` run once for every test of this file (3 seeds, a few seconds).
fn paper() -> &'static Path {
    static OUT: OnceLock<PathBuf> = OnceLock::new();
    OUT.get_or_init(|| {
        let dir = scratch("paper");
        let pipeline = repo().join("pipelines/paper.toml");
        let o = stickslip(&["pipeline", pipeline.to_str().unwrap(), "--quiet", "--out", "paper"], &dir);
        assert!(o.status.success(), "{}", text(&o).1);
        dir.join("paper")
    })
}

fn readme() -> String {
    std::fs::read_to_string(repo().join("README.md")).unwrap()
}

#[test]
fn readme_calibration_table_is_what_stickslip_seeds_prints() {
    let o = stickslip(&["seeds", paper().to_str().unwrap()], &repo());
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    let readme = readme();
    let lines: Vec<&str> = out.lines().filter(|l| !l.is_empty()).collect();
    assert_eq!(lines.len(), 6, "header, rule, 3 seeds, definition:\n{out}");
    for line in lines {
        assert!(readme.contains(line), "README lacks this line of `stickslip seeds reports/paper`:\n{line}");
    }
}

#[test]
fn readme_points_only_to_files_a_clone_has() {
    let readme = readme();
    let roots = ["crates/", "docs/", "scripts/", "pipelines/", "tests/", ".ci/", "reports/reference/"];
    let mut checked = 0;
    for piece in readme.split(['`', '(', ')', ' ', '\n', '[', ']']) {
        let p = piece.trim_end_matches([',', '.', ':', ';']).trim_end_matches("'s");
        if !roots.iter().any(|r| p.starts_with(r)) || p.contains(['<', '*', '…', '{', '$']) {
            continue;
        }
        assert!(repo().join(p).exists(), "README points to {p}, which a clone lacks");
        checked += 1;
    }
    for file in ["ARCHITECTURE.md", "BENCHMARKS.md", "LICENSE-MIT", "LICENSE-APACHE", "CITATION.cff"] {
        if readme.contains(file) {
            assert!(repo().join(file).exists(), "{file}");
        }
    }
    assert!(checked > 10, "only {checked} paths found in the README");
    for gone in ["../shared", "SPEC §"] {
        assert!(!readme.contains(gone), "README mentions {gone}");
    }
}

#[test]
fn readme_paper_100_output_has_every_row_and_the_part_names_are_right() {
    let readme = readme();
    let block = readme.split("prints the main shocks across seeds").nth(1).unwrap();
    let block = &block[block.find("```\n").unwrap() + 4..];
    let block = &block[..block.find("```").unwrap()];
    for row in ["S1 ", "S2 ", "S3 ", "S4 ", "S5 ", "main "] {
        assert!(block.lines().any(|l| l.starts_with(row)), "no {row:?} row in the README's paper-100 output");
    }
    assert!(!readme.contains("seed-<seed>.parquet"), "parts are seed-0000000123.parquet");
    assert!(paper().join("tables/series/seed-0000000123.parquet").exists());
}

#[test]
fn compare_refuses_a_folder_that_does_not_exist_or_holds_no_output() {
    let dir = scratch("compare");
    std::fs::create_dir_all(dir.join("empty")).unwrap();
    let p = paper().to_str().unwrap();
    for (other, want) in [("missing", "no such folder"), ("empty", "not the output folder")] {
        for args in [["compare", p, other], ["compare", other, p]] {
            let o = stickslip(&args, &dir);
            let (out, err) = text(&o);
            assert_eq!(o.status.code(), Some(1), "{out}{err}");
            assert!(err.contains(want), "{err}");
            assert!(!out.contains("only in") && !out.contains("same tables"), "{out}");
        }
    }
    let o = stickslip(&["compare", p, p], &dir);
    assert!(o.status.success());
    assert!(text(&o).0.contains("hold the same tables"));
}

#[test]
fn show_selects_columns_and_transposes_wide_tables() {
    let glob = format!("{}/tables/events/*.parquet", paper().display());
    let o = stickslip(&["show", &glob, "--rows", "3", "--columns", "seed,label,stress_drop_pa"], &repo());
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    assert!(out.contains("× 3 columns") && !out.contains("duration_s"), "{out}");
    let o = stickslip(&["show", &glob, "--rows", "3", "--transpose"], &repo());
    let (out, _) = text(&o);
    // One line per column after the schema, each value in its own aligned column.
    let rows: Vec<&str> =
        out.lines().filter(|l| !l.is_empty() && !l.starts_with(' ') && !l.contains(".parquet")).collect();
    assert!(rows.iter().any(|l| l.starts_with("stress_drop_pa ")), "{out}");
    let starts = |l: &str| -> Vec<usize> {
        let c: Vec<char> = l.chars().collect();
        (1..c.len()).filter(|&i| c[i] != ' ' && c[i - 1] == ' ').collect()
    };
    let first = starts(rows[0]);
    assert_eq!(first.len(), 3, "name and 3 values: {:?}", rows[0]);
    for l in &rows {
        assert_eq!(starts(l), first, "columns not aligned:\n{out}");
    }
    let o = stickslip(&["show", &glob, "--columns", "nope"], &repo());
    assert_eq!(o.status.code(), Some(1));
    assert!(text(&o).1.contains("no column \"nope\"; the columns are: seed, event"), "{}", text(&o).1);
}

#[test]
fn help_gives_one_default_per_option() {
    for cmd in ["pipeline", "run", "merge", "compare", "check", "show", "seeds", "similarity", "spectra", "select"] {
        let o = stickslip(&[cmd, "--help"], &repo());
        let (out, _) = text(&o);
        assert!(o.status.success(), "{cmd}");
        for line in out.lines() {
            assert!(line.matches("[default").count() <= 1, "`stickslip {cmd} --help`: {line}");
        }
    }
}

#[test]
fn similarity_values_line_up_whatever_the_combining_marks() {
    let o = stickslip(
        &["similarity", "--stress-drop-pa", "7600", "--duration-s", "0.0021", "--recurrence-s", "0.0258"],
        &repo(),
    );
    let (out, _) = text(&o);
    let combining = |c: char| matches!(u32::from(c), 0x0300..=0x036F);
    // Display column where the value starts: after the label and its padding.
    let value_column = |l: &str| -> usize {
        let cols: Vec<char> = l.chars().filter(|c| !combining(*c)).collect();
        (2..cols.len()).find(|&i| cols[i] != ' ' && cols[i - 1] == ' ' && cols[i - 2] == ' ' && i > 10).unwrap()
    };
    let rows: Vec<&str> = out.lines().filter(|l| l.starts_with("  ")).collect();
    assert!(rows.iter().any(|l| l.contains("u̇_m/u̇_p")), "{out}");
    let c0 = value_column(rows[0]);
    for l in rows {
        assert_eq!(value_column(l), c0, "misaligned: {l:?}");
    }
}

#[test]
fn a_pipeline_without_events_says_why_and_what_to_try() {
    let dir = scratch("no-events");
    std::fs::write(
        dir.join("short.toml"),
        "version = 1\nname = \"short\"\n[block]\nnx = 4\nny = 1\nnz = 2\n[shear]\nduration_s = 0.01\n\
         driver_at_m = [[0.0, 0.0, 0.1]]\n[record]\ninterval_s = 1e-4\n",
    )
    .unwrap();
    let o = stickslip(&["pipeline", "short.toml", "--quiet"], &dir);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    for want in [
        "no events in any seed",
        "the base never slipped fast enough",
        "sliding needs about μs·σ",
        "try: a longer [shear] duration_s",
    ] {
        assert!(out.contains(want), "missing {want:?}:\n{out}");
    }
}

#[test]
fn check_shows_nodes_by_position_every_stage_and_the_critical_range_over_the_seeds() {
    let dir = scratch("check");
    std::fs::write(
        dir.join("scene.toml"),
        "version = 1\nname = \"scene\"\n[seeds]\nrange = { first = 1, count = 8 }\n[shear]\nduration_s = 0.05\n\
         [[record.control]]\nat_m = [[0.2, 0.1, 0.1]]\n[spectra]\ndampings = [0.05]\n",
    )
    .unwrap();
    let o = stickslip(&["check", "scene.toml"], &dir);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    for want in [
        "critical step",
        "over the pipeline's 8 seeds",
        "control LDEM 36 at (0.2, 0.1, 0.1) m",
        "drivers: LDEM 45 at (0, 0, 0.2) m",
        "record: ",
        "events: smoothing",
        "records: ",
        "spectra: 100 periods",
        "similarity: L_p",
    ] {
        assert!(out.contains(want), "missing {want:?}:\n{out}");
    }
    let o = stickslip(&["check", "scene.toml", "--seeds", "2"], &dir);
    assert!(text(&o).0.contains("over its first 2 of 8 seeds"), "{}", text(&o).0);
}

#[test]
fn slurm_check_refuses_a_machine_with_a_slurm_it_did_not_create_and_changes_nothing() {
    let dir = scratch("slurm");
    let work = dir.join("work");
    let o = Command::new("bash")
        .arg(repo().join("scripts/slurm-check.sh"))
        .arg("pipelines/paper.toml")
        .arg("2")
        .current_dir(repo())
        .env("SLURM_CONF", "/etc/site/slurm.conf")
        .env("WORK", &work)
        .env("STICKSLIP", env!("CARGO_BIN_EXE_stickslip"))
        .output()
        .unwrap();
    let (out, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}{err}");
    assert!(err.contains("slurm check refused") && err.contains("SLURM_CONF is set"), "{err}");
    assert!(err.contains("Nothing was changed"), "{err}");
    assert!(!work.exists(), "the refused check created its work folder");
    assert!(!out.contains("packages"), "it went past the refusal:\n{out}");
}

#[test]
fn render_report_installs_nothing_unasked() {
    // A PATH with no chromium and an apt-get that leaves a mark if it is ever run.
    let dir = scratch("render");
    let bin = dir.join("bin");
    std::fs::create_dir_all(&bin).unwrap();
    let mark = dir.join("apt-get-ran");
    std::fs::write(bin.join("apt-get"), format!("#!/bin/sh\ntouch {}\n", mark.display())).unwrap();
    let realpath = ["/usr/bin/realpath", "/bin/realpath"].into_iter().find(|p| Path::new(p).exists()).unwrap();
    std::os::unix::fs::symlink(realpath, bin.join("realpath")).unwrap();
    Command::new("chmod").arg("+x").arg(bin.join("apt-get")).status().unwrap();
    std::fs::create_dir_all(dir.join("r")).unwrap();
    std::fs::write(dir.join("r/index.html"), "<html></html>").unwrap();
    let o = Command::new("/bin/bash")
        .arg(repo().join("scripts/render-report.sh"))
        .arg(dir.join("r"))
        .env("PATH", &bin)
        .stdin(std::process::Stdio::null())
        .output()
        .unwrap();
    let (out, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}{err}");
    assert!(err.contains("chromium is not installed") && err.contains("apt-get"), "{err}");
    assert!(err.contains("--install"), "{err}");
    assert!(!mark.exists(), "apt-get ran without being asked");
}

#[test]
fn python_example_reads_the_tables() {
    let has = Command::new("python3").args(["-c", "import polars, pyarrow"]).output().is_ok_and(|o| o.status.success());
    if !has {
        eprintln!("python3 with polars and pyarrow not found: scripts/read_tables.py not run");
        return;
    }
    let png = paper().join("tau.png");
    let plot = Command::new("python3").args(["-c", "import matplotlib"]).output().is_ok_and(|o| o.status.success());
    let mut c = Command::new("python3");
    c.arg(repo().join("scripts/read_tables.py")).arg(paper());
    if plot {
        c.arg(&png);
    }
    let o = c.output().unwrap();
    let (out, err) = text(&o);
    assert!(o.status.success(), "{out}{err}");
    assert!(out.contains("runs.status: large_string") || out.contains("runs.status: string"), "{out}");
    // 0.32 s every 2e-5 s taken as two steps of each seed's own Δt (half its critical step):
    // about 15,000 samples, a few hundred more or fewer from seed to seed.
    let line = out.lines().find(|l| l.starts_with("samples per seed: {7: ")).unwrap_or_else(|| panic!("{out}"));
    let counts: Vec<u64> =
        line.split([':', ',', '}']).filter_map(|x| x.trim().parse::<u64>().ok()).step_by(2).collect();
    assert_eq!(counts.len(), 3, "{line}");
    assert!(counts.iter().all(|&n| (14_000..16_100).contains(&n)), "{line}");
    if plot {
        assert!(png.exists());
    }
}

#[test]
fn scenes_too_large_or_too_long_are_refused_before_anything_is_built() {
    // Every file of pipelines/invalid/ refused by the command line: by check, pipeline and run,
    // with the message its `# expect:` lines give, under a fixed memory limit.
    let dir = scratch("budget");
    let invalid = repo().join("pipelines/invalid");
    let mut checked = 0;
    for entry in std::fs::read_dir(&invalid).unwrap() {
        let path = entry.unwrap().path();
        let file_text = std::fs::read_to_string(&path).unwrap_or_default();
        if !file_text.lines().any(|l| l.starts_with("# refused by: stickslip")) {
            continue;
        }
        let expected: Vec<&str> = file_text.lines().filter_map(|l| l.strip_prefix("# expect: ")).collect();
        let file = path.to_str().unwrap();
        let out_dir = dir.join("out");
        let out_dir = out_dir.to_str().unwrap();
        for args in [
            vec!["check", file],
            vec!["pipeline", file, "--out", out_dir, "--quiet"],
            vec!["run", file, "--seed", "1", "--out", out_dir, "--quiet"],
        ] {
            let start = std::time::Instant::now();
            let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
                .args(&args)
                .env("STICKSLIP_MEMORY_LIMIT", "16G")
                .current_dir(&dir)
                .output()
                .unwrap();
            let (stdout, err) = text(&out);
            assert_eq!(out.status.code(), Some(1), "{args:?} accepted:\n{stdout}{err}");
            for want in &expected {
                assert!(err.contains(want), "{args:?}: message lacks {want:?}:\n{err}");
            }
            assert!(start.elapsed().as_secs_f64() < 10.0, "{args:?}: refused only after {:?}", start.elapsed());
            assert!(!dir.join("out").exists(), "{args:?}: nothing may be written for a refused scene");
        }
        checked += 1;
    }
    assert!(checked >= 2, "only {checked} files refused by the command line");
    // The flag lets the long run through check: its length and time are printed, not refused.
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(["check", invalid.join("run_too_long.toml").to_str().unwrap(), "--allow-long"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let (stdout, err) = text(&out);
    assert!(out.status.success(), "{err}");
    assert!(stdout.contains("a long run, accepted with --allow-long") && stdout.contains("memory: about"), "{stdout}");
}
