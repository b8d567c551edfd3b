//! What a new user meets: the numbers and paths of the README and the user guide (docs/guide/)
//! against the binary and the clone, the
//! CLI's refusals and views, the scripts' refusals, and the Python example.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

use stickslip_support::untimed;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize().unwrap()
}

fn stickslip(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip")).args(args).current_dir(cwd).output().expect("run stickslip")
}

fn text(o: &Output) -> (String, String) {
    (String::from_utf8_lossy(&o.stdout).into_owned(), String::from_utf8_lossy(&o.stderr).into_owned())
}

/// A scratch folder, removed when the test passes (see `stickslip_support::scratch_dir`).
fn scratch(name: &str) -> stickslip_support::Scratch {
    stickslip_support::scratch_dir(&format!("usability-{name}"))
}

/// `pipelines/paper.toml` run once for every test of this file (3 seeds, a few seconds).
///
/// A static is never dropped, so its folder outlives the process: it goes under cargo's scratch
/// folder for tests (`target/tmp`), named by the process, and a run removes the ones earlier runs
/// left there: those whose process is gone where `/proc` tells, else those over an hour old (a
/// run of these tests takes minutes).
fn paper() -> &'static Path {
    static OUT: OnceLock<PathBuf> = OnceLock::new();
    OUT.get_or_init(|| {
        let parent = Path::new(env!("CARGO_TARGET_TMPDIR"));
        let proc = Path::new("/proc/self").exists();
        let stale = |e: &std::fs::DirEntry| {
            let name = e.file_name().to_string_lossy().into_owned();
            let Some(pid) = name.strip_prefix("usability-paper-").and_then(|p| p.parse::<u32>().ok()) else {
                return false;
            };
            if proc {
                pid != std::process::id() && !Path::new("/proc").join(pid.to_string()).exists()
            } else {
                e.metadata()
                    .and_then(|m| m.modified())
                    .is_ok_and(|t| t.elapsed().is_ok_and(|age| age > std::time::Duration::from_secs(3600)))
            }
        };
        for e in std::fs::read_dir(parent).into_iter().flatten().flatten().filter(stale) {
            let _ = std::fs::remove_dir_all(e.path());
        }
        let dir = parent.join(format!("usability-paper-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let pipeline = repo().join("pipelines/paper.toml");
        let o = stickslip(&["pipeline", pipeline.to_str().unwrap(), "--quiet", "--out", "paper"], &dir);
        assert!(o.status.success(), "{}", text(&o).1);
        dir.join("paper")
    })
}

/// The README and every chapter of the guide, each with its path.
fn user_docs() -> Vec<(PathBuf, String)> {
    stickslip_support::user_docs()
        .into_iter()
        .map(|f| (f.clone(), std::fs::read_to_string(repo().join(f)).unwrap()))
        .collect()
}

#[test]
fn readme_calibration_table_is_what_stickslip_seeds_prints() {
    let o = stickslip(&["seeds", paper().to_str().unwrap()], &repo());
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    let (block, file) = stickslip_support::generated_block("calibration");
    let lines: Vec<&str> = out.lines().filter(|l| !l.is_empty()).collect();
    assert_eq!(lines.len(), 6, "header, rule, 3 seeds, definition:\n{out}");
    for line in lines {
        assert!(block.contains(line), "{} lacks this line of `stickslip seeds reports/paper`:\n{line}", file.display());
    }
}

#[test]
fn readme_points_only_to_files_a_clone_has() {
    // Paths written out in the text (`crates/…`, pipelines/…) are from the repository's root, in
    // the guide's chapters too; Markdown links are checked by tests/docs.rs.
    let roots = ["crates/", "docs/", "scripts/", "pipelines/", "tests/", ".ci/", "reports/reference/"];
    let mut checked = 0;
    for (doc, text) in user_docs() {
        for piece in text.split(['`', '(', ')', ' ', '\n', '[', ']']) {
            let p = piece.trim_end_matches([',', '.', ':', ';']).trim_end_matches("'s");
            let p = p.split('#').next().unwrap_or(p);
            if !roots.iter().any(|r| p.starts_with(r)) || p.contains(['<', '*', '…', '{', '$']) {
                continue;
            }
            assert!(repo().join(p).exists(), "{} points to {p}, which a clone lacks", doc.display());
            checked += 1;
        }
        for file in ["ARCHITECTURE.md", "BENCHMARKS.md", "LICENSE-MIT", "LICENSE-APACHE", "CITATION.cff"] {
            if text.contains(file) {
                assert!(repo().join(file).exists(), "{file}");
            }
        }
        for gone in ["../shared", "SPEC §"] {
            assert!(!text.contains(gone), "{} mentions {gone}", doc.display());
        }
    }
    assert!(checked > 100, "only {checked} paths found in the README and the guide");
}

#[test]
fn readme_paper_100_output_has_every_row_and_the_part_names_are_right() {
    let (block, file) = stickslip_support::generated_block("paper-100");
    let block = &block[block.find("```\n").unwrap() + 4..];
    let block = &block[..block.find("```").unwrap()];
    for row in ["S1 ", "S2 ", "S3 ", "S4 ", "S5 ", "main "] {
        assert!(
            block.lines().any(|l| l.starts_with(row)),
            "no {row:?} row in the paper-100 output of {}",
            file.display()
        );
    }
    for (doc, text) in user_docs() {
        assert!(!text.contains("seed-<seed>.parquet"), "{}: parts are seed-0000000123.parquet", doc.display());
    }
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
        "no events in 1 of 1 seed (123): an event is a burst of slip",
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

/// scenario-m6 at 100 m modules (800 × 200 × 520, 1.17·10⁹ bars) as `dir/m6-100.toml`.
fn write_m6_100(dir: &Path) {
    let scene = std::fs::read_to_string(repo().join("pipelines/scenario-m6.toml"))
        .unwrap()
        .replace("nx = 160\n", "nx = 800\n")
        .replace("ny = 40\n", "ny = 200\n")
        .replace("nz = 104\n", "nz = 520\n")
        .replace("lc_m = 500.0", "lc_m = 100.0");
    assert!(scene.contains("nx = 800\nny = 200\nnz = 520\nlc_m = 100.0"), "scenario-m6's block changed");
    std::fs::write(dir.join("m6-100.toml"), scene).unwrap();
}

/// `check` on a scene far too large for the machine prints its size, memory and time from the
/// block's counts first and refuses it, naming what does not fit and what is available, instead
/// of building it: scenario-m6 at 100 m modules (1.17·10⁹ bars, 21 GB for one seed) under a
/// 4 GB address-space limit aborted on an 8 GB allocation before printing anything.
#[test]
fn check_prints_the_cost_of_a_huge_scene_first_and_refuses_it_before_building() {
    let dir = scratch("check-huge");
    write_m6_100(&dir);
    let started = std::time::Instant::now();
    let out = Command::new("sh")
        .args(["-c", "ulimit -v 4000000 && exec \"$0\" \"$@\"", env!("CARGO_BIN_EXE_stickslip")])
        .args(["check", "m6-100.toml"])
        .env_remove("STICKSLIP_MEMORY_LIMIT")
        .current_dir(&dir)
        .output()
        .unwrap();
    let took = started.elapsed();
    let (stdout, err) = text(&out);
    assert_eq!(out.status.code(), Some(1), "not refused:\n{stdout}{err}");
    assert!(took.as_secs() < 60, "took {took:?}");
    assert!(stdout.contains("before building: 167081521 nodes, 1165481520 bars"), "{stdout}");
    assert!(stdout.contains("memory: about ") && stdout.contains("per seed at"), "{stdout}");
    assert!(stdout.contains("under the address-space limit, ulimit -v"), "{stdout}");
    for want in ["one seed of this scene", "does not fit in memory", "ulimit -v", "block.lc_m"] {
        assert!(err.contains(want), "the refusal lacks {want:?}: {err}");
    }
}

/// `check --ranks`: a scene too large for this machine split over ranks, each rank's part said
/// from the block alone before the whole is refused; a rank that cannot hold its part refused
/// with the rank and what it needs; more ranks than the block takes refused with the range.
#[test]
fn check_ranks_says_each_ranks_part_and_refuses_a_rank_that_cannot_hold_it() {
    let dir = scratch("check-ranks");
    write_m6_100(&dir);
    let check = |args: &[&str]| {
        let out = Command::new("sh")
            .args(["-c", "ulimit -v 4000000 && exec \"$0\" \"$@\"", env!("CARGO_BIN_EXE_stickslip")])
            .arg("check")
            .args(args)
            .env_remove("STICKSLIP_MEMORY_LIMIT")
            .current_dir(&dir)
            .output()
            .unwrap();
        let (stdout, err) = text(&out);
        (out.status.code(), stdout, err)
    };
    // 32 ranks of 8 GB (rank 0 also holds the whole block's model, which the analyses read):
    // each rank's part, then the whole scene refused here (check builds it).
    let (code, stdout, err) = check(&["m6-100.toml", "--ranks", "32", "--memory-per-rank", "8"]);
    assert_eq!(code, Some(1), "{stdout}{err}");
    let ranks = stdout.find("ranks: 32 slabs").expect("the ranks section");
    assert!(ranks < stdout.find("before building").unwrap(), "ranks first: {stdout}");
    assert!(stdout.contains("rank 0: module layers 0..16 (16, the base)"), "{stdout}");
    assert!(stdout.contains("rank 31: module layers"), "{stdout}");
    assert!(stdout.contains("halo: one module layer of 321001 nodes"), "{stdout}");
    assert!(stdout.contains("against 8.0 GB per rank (--memory-per-rank)"), "{stdout}");
    assert!(stdout.contains("rank 0 at about 4.9 GB"), "its part and the whole block's model: {stdout}");
    assert!(stdout.contains("run: `mpirun -n 32 stickslip pipeline …`"), "{stdout}");
    assert!(err.contains("does not fit in memory"), "{err}");
    // 2 GB per rank is too little for rank 0 of this block.
    let (code, stdout, err) = check(&["m6-100.toml", "--ranks", "32", "--memory-per-rank", "2"]);
    assert_eq!(code, Some(1), "{stdout}{err}");
    assert!(err.contains("--ranks = 32: rank 0 needs about 4.9 GB but a rank has 2.0 GB"), "{err}");
    assert!(!stdout.contains("before building"), "refused before the cost: {stdout}");
    // More ranks than the block takes, and no --ranks with --memory-per-rank.
    let (code, _, err) = check(&["m6-100.toml", "--ranks", "1000"]);
    assert_eq!(code, Some(1));
    assert!(err.contains("--ranks = 1000 is not allowed") && err.contains("takes 1 to "), "{err}");
    let (code, _, err) = check(&["m6-100.toml", "--memory-per-rank", "2"]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("--ranks <RANKS>"), "{err}");
    // The paper's small block (its bars listed) splits into slabs of one module layer: up to 5.
    let paper = repo().join("pipelines/paper.toml");
    let (code, stdout, err) = check(&[paper.to_str().unwrap(), "--ranks", "4"]);
    assert_eq!(code, Some(0), "{stdout}{err}");
    assert!(stdout.contains("ranks: 4 slabs") && stdout.contains("run: `mpirun -n 4"), "{stdout}");
    let (code, stdout, err) = check(&[paper.to_str().unwrap(), "--ranks", "6"]);
    assert_eq!(code, Some(1), "{stdout}{err}");
    assert!(
        err.contains("at least one module layer (its bars are listed)") && err.contains("takes 1 to 5 ranks"),
        "{err}"
    );
    // A scene the split run does not take (a static self-weight), refused saying so.
    let stat = dir.join("static.toml");
    let text = std::fs::read_to_string(&paper).unwrap().replace("[self_weight]", "[self_weight]\nmethod = \"static\"");
    std::fs::write(&stat, text).unwrap();
    let (code, stdout, err) = check(&[stat.to_str().unwrap(), "--ranks", "2"]);
    assert_eq!(code, Some(1), "{stdout}{err}");
    assert!(err.contains("would refuse to split") && err.contains("self_weight.method = \"dynamic\""), "{err}");
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

/// A Parquet file read with polars.
fn parquet(path: &Path) -> stickslip_support::polars::prelude::DataFrame {
    use stickslip_support::polars::prelude::{ParquetReader, SerReader};
    ParquetReader::new(std::fs::File::open(path).unwrap()).finish().unwrap()
}

/// Every `src` of a page that names a figure.
fn figures_of(html: &str) -> Vec<String> {
    html.split("src=\"figures/").skip(1).map(|s| s[..s.find('"').unwrap()].to_string()).collect()
}

#[test]
fn a_seed_outside_the_files_list_gets_every_figure() {
    let dir = scratch("outside");
    let paper = repo().join("pipelines/paper.toml");
    // `stickslip run my-scene.toml --seed 1`, the README's own step: seed 1 is not in [123, 200, 7].
    let o = stickslip(&["run", paper.to_str().unwrap(), "--seed", "1", "--out", "one", "--quiet"], &dir);
    assert!(o.status.success(), "{}", text(&o).1);
    // `stickslip pipeline … --seeds 1,2`, outside the list too.
    let o = stickslip(&["pipeline", paper.to_str().unwrap(), "--seeds", "1,2", "--out", "two", "--quiet"], &dir);
    assert!(o.status.success(), "{}", text(&o).1);
    for (folder, seeds) in [("one", "seed 1"), ("two", "seeds 1, 2")] {
        let html = std::fs::read_to_string(dir.join(folder).join("index.html")).unwrap();
        let drawn = figures_of(&html);
        for f in [
            "shear_stress.png",
            "normal_stress.png",
            "mean_slip.png",
            "acceleration_s2.png",
            "acceleration_run.png",
            "records.png",
            "fourier.png",
            "energy.png",
            "catalogue.png",
        ] {
            assert!(drawn.iter().any(|d| d == f), "{folder}: {f} not drawn; drawn {drawn:?}");
            assert!(dir.join(folder).join("figures").join(f).is_file(), "{folder}: no {f}");
        }
        for stale in ["no shear stress recorded", "no successful seed"] {
            assert!(!html.contains(stale), "{folder}: the page says {stale:?}");
        }
        assert!(html.contains(seeds), "{folder}: the captions do not name {seeds}");
    }
}

/// `plate-stickslip.toml` at the paper's 400 1/s slides stably: the pipeline says so (no advice
/// to run longer), and `check` expects it.
#[test]
fn a_scene_that_slides_is_told_stable_sliding_by_the_run_and_by_check() {
    let dir = scratch("sliding");
    let text_of = std::fs::read_to_string(repo().join("pipelines/plate-stickslip.toml"))
        .unwrap()
        .replace("damping_per_s = 50.0 ", "damping_per_s = 400.0 ")
        .replace("duration_s = 0.3\n", "duration_s = 0.15\n");
    assert!(text_of.contains("damping_per_s = 400.0") && text_of.contains("duration_s = 0.15"));
    std::fs::write(dir.join("slides.toml"), text_of).unwrap();
    let o = stickslip(&["check", "slides.toml"], &dir);
    assert!(o.status.success());
    assert!(text(&o).0.contains("→ stable sliding expected"), "{}", text(&o).0);
    let o = stickslip(&["pipeline", "slides.toml", "--seeds", "1,2", "--out", "out", "--quiet"], &dir);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{err}");
    assert!(out.contains("the base slid stably in 2 of 2 seeds (1, 2)"), "{out}");
    assert!(out.contains("stable sliding expected"), "check's reading is printed beside it: {out}");
    assert!(!out.contains("a longer [shear] duration_s"), "sliding is not cured by running longer: {out}");
    assert!(!out.contains("shock seeds"), "no main-shock table: {out}");
    // No "scaling.png" of empty panels: figures without data are skipped.
    assert!(!dir.join("out/figures/scaling.png").exists());
    let runs = std::fs::read(dir.join("out/tables/runs.parquet")).unwrap();
    assert!(runs.windows(14).any(|w| w == b"stable_sliding"), "runs.slip_regime");
}

#[test]
fn wrong_arguments_are_refused_with_what_is_allowed() {
    let paper_toml = repo().join("pipelines/paper.toml");
    let p = paper_toml.to_str().unwrap();
    let o = stickslip(&["run", p, "--seed", "-1"], &repo());
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("-1 is not a seed: seeds are whole numbers ≥ 0"), "{err}");
    assert!(!err.contains("-- -1"), "clap's tip misleads: {err}");
    let o = stickslip(&["run", p, "--seed", "1", "--threads", "0"], &repo());
    assert!(text(&o).1.contains("0 threads: give a whole number ≥ 1"), "{}", text(&o).1);
    // A negative thread count is refused with the range, not clap's tip to write `-- -1`.
    for cmd in ["run", "pipeline"] {
        let args: Vec<&str> =
            if cmd == "run" { vec![cmd, p, "--seed", "1", "--threads", "-1"] } else { vec![cmd, p, "--threads", "-1"] };
        let o = stickslip(&args, &repo());
        let (_, err) = text(&o);
        assert_eq!(o.status.code(), Some(2), "{cmd}: {err}");
        assert!(err.contains("-1 threads: give a whole number ≥ 1"), "{cmd}: {err}");
        assert!(!err.contains("-- -1"), "{cmd}: clap's tip misleads: {err}");
    }
    // A station set that the seeds cannot fill is refused before anything runs: 2 ruptures of
    // scenario-m6 give at most 2 × set.max_per = 4 of its 11 records.
    let m6 = repo().join("pipelines/scenario-m6.toml");
    let started = std::time::Instant::now();
    let o = stickslip(&["pipeline", m6.to_str().unwrap(), "--seeds", "1,2", "--out", "/nonexistent/never"], &repo());
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("set.count = 11 is not allowed with 2 seeds: at most 4 records, 2 per seed"), "{err}");
    assert!(err.contains("allowed: set.count ≤ 4") && err.contains("at least 6 seeds"), "{err}");
    assert!(started.elapsed().as_secs() < 20, "refused only after {:?}", started.elapsed());
    // A seed named twice is refused before anything runs, not dropped silently.
    let o = stickslip(&["pipeline", p, "--seeds", "1,1,2", "--out", "/nonexistent/never-written"], &repo());
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("seed 1 is named twice in \"1,1,2\""), "{err}");
    let folder = paper().to_str().unwrap().to_string();
    for (shock, want) in
        [("foo", "\"foo\" is not a main shock"), ("S0", "\"S0\" is not a main shock"), ("S9", "has a main shock S9")]
    {
        let o = stickslip(&["seeds", &folder, "--shock", shock], &repo());
        let (out, err) = text(&o);
        assert_eq!(o.status.code(), Some(1), "--shock {shock}: {out}");
        assert!(err.contains(want), "--shock {shock}: {err}");
        assert!(!out.contains("| –"), "--shock {shock}: a table of dashes: {out}");
    }
    // A seed the folder does not have is refused before any table is rewritten, the folder's
    // seeds listed compactly.
    let b_values = paper().join("tables/b_values.parquet");
    let before = std::fs::metadata(&b_values).unwrap().modified().unwrap();
    let o = stickslip(&["catalogue", &folder, "--seed", "99999"], &repo());
    let (out, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}");
    assert!(
        err.contains("--seed 99999 is not a seed of") && err.contains("(its finished seeds: 7, 123, 200)"),
        "{err}"
    );
    assert!(out.is_empty(), "nothing printed before the refusal: {out}");
    assert_eq!(std::fs::metadata(&b_values).unwrap().modified().unwrap(), before, "b_values.parquet was rewritten");
}

/// Writes `accel` (m/s², every `dt` s) as the big-endian SAC of ObsPy, if python3 has ObsPy.
fn obspy_sac(path: &Path, dt: f64, accel: &[f64]) -> bool {
    let values: Vec<String> = accel.iter().map(|v| format!("{v:e}")).collect();
    let script = format!(
        "import numpy as np\nfrom obspy import Trace\nfrom obspy.io.sac import SACTrace\n\
         tr = Trace(np.array([{}], dtype=np.float32))\ntr.stats.delta = {dt}\ntr.stats.station = 'OBS'\n\
         SACTrace.from_obspy_trace(tr).write({:?}, byteorder='big')\n",
        values.join(","),
        path.to_str().unwrap()
    );
    Command::new("python3").args(["-c", &script]).output().is_ok_and(|o| o.status.success())
}

/// PGA (m/s²) that `stickslip spectra` wrote for a record, from its intensity table.
fn spectra_pga(args: &[&str], dir: &Path, out: &str) -> f64 {
    let mut all = vec!["spectra"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", out]);
    let o = stickslip(&all, dir);
    let (stdout, err) = text(&o);
    assert!(o.status.success(), "stickslip {all:?}: {err}");
    assert!(dir.join(out).join("spectra.png").is_file(), "no figure: {stdout}");
    let df = parquet(&dir.join(out).join("intensity.parquet"));
    df.column("pga_m_s2").unwrap().f64().unwrap().get(0).unwrap()
}

#[test]
fn spectra_reads_sac_text_csv_and_parquet_records_and_draws_them() {
    use stickslip_support::polars::prelude::*;
    let dir = scratch("spectra");
    // The product's own SAC record of seed 123's S2 at node 36 (z), and the same record in the
    // accelerograms table: the same peak, to the SAC's single precision.
    let sac = paper().join("records/paper_seed123_S2-n36-z_model.SAC");
    let part = paper().join("tables/accelerograms/seed-0000000123.parquet");
    let acc = parquet(&part);
    // The table holds each record once, at model scale, its motion in single precision.
    let mask = acc.column("record").unwrap().str().unwrap().equal("S2-n36-z");
    let a = acc.filter(&mask).unwrap();
    let peak = a
        .column("acceleration_m_s2")
        .unwrap()
        .cast(&DataType::Float64)
        .unwrap()
        .f64()
        .unwrap()
        .iter()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let from_sac = spectra_pga(&[sac.to_str().unwrap()], &dir, "sac");
    assert!((from_sac / peak - 1.0).abs() < 1e-6, "PGA {from_sac} from the SAC vs {peak}");
    // The same file without its extension: told by its content.
    std::fs::copy(&sac, dir.join("record")).unwrap();
    assert!((spectra_pga(&["record"], &dir, "noext") / peak - 1.0).abs() < 1e-6);
    // The record in the Parquet table, by name.
    let from_table = spectra_pga(&[part.to_str().unwrap(), "--record-name", "S2-n36-z"], &dir, "table");
    assert!((from_table / peak - 1.0).abs() < 1e-12);
    // Whitespace-separated text and CSV of a sine of 2 m/s² (0.2 g in g units).
    let dt = 0.01;
    let sine: Vec<f64> = (0..1000).map(|i| 2.0 * (2.0 * std::f64::consts::PI * i as f64 * dt).sin()).collect();
    let spaced: String = sine.iter().enumerate().map(|(i, a)| format!("{:.3}   {a:.9}\n", i as f64 * dt)).collect();
    std::fs::write(dir.join("sine.txt"), format!("# time  acceleration\n{spaced}")).unwrap();
    assert!((spectra_pga(&["sine.txt"], &dir, "txt") - 2.0).abs() < 1e-6);
    let csv: String =
        sine.iter().enumerate().map(|(i, a)| format!("{:.3},{:.9}\n", i as f64 * dt, a / 9.80665)).collect();
    std::fs::write(dir.join("sine.csv"), format!("time_s,acc_g\n{csv}")).unwrap();
    assert!((spectra_pga(&["sine.csv", "--units", "g"], &dir, "csv") - 2.0).abs() < 1e-6);
    // ObsPy's big-endian SAC (no unit: read in --units).
    if obspy_sac(&dir.join("obspy.sac"), dt, &sine) {
        assert!((spectra_pga(&["obspy.sac"], &dir, "obspy") / 2.0 - 1.0).abs() < 1e-6);
    } else {
        eprintln!("python3 with ObsPy not found: the ObsPy SAC case is skipped");
    }
    // A table of many records without a name: refused, naming some.
    let o = stickslip(&["spectra", part.to_str().unwrap()], &dir);
    assert!(text(&o).1.contains("name one with --record-name"), "{}", text(&o).1);
}

#[test]
fn model_md_contents_list_every_section() {
    let model = std::fs::read_to_string(repo().join("docs/model.md")).unwrap();
    let contents = &model[model.find("Contents:").unwrap()..model.find("\n---").unwrap()];
    for line in model.lines().filter(|l| l.starts_with("## ") && l[3..].starts_with(|c: char| c.is_ascii_digit())) {
        let number = line[3..].split('.').next().unwrap();
        assert!(contents.contains(&format!("[§{number} ")), "docs/model.md's contents omit §{number}: {line}");
    }
}

/// `stickslip select --set other.toml` rewrites the report for the new set: the page lists the
/// new set's files (every link resolves), `record_set.png` is redrawn against the new target, and
/// the printout names where the set table is.
#[test]
fn select_rewrites_the_report_for_the_new_set() {
    let dir = scratch("select");
    let acc = repo().join("pipelines/accelerograms.toml");
    let o = stickslip(&["pipeline", acc.to_str().unwrap(), "--seeds", "1-3", "--out", "acc", "--quiet"], &dir);
    // Three seeds may be too few for the pipeline's set of 11: that is not what is tested here.
    assert!(o.status.success(), "{}", text(&o).1);
    std::fs::write(
        dir.join("other.toml"),
        "[set]\ntarget = \"asce7\"\ns_ds_g = 0.05\ns_d1_g = 0.02\nt1_s = 0.1\ncount = 2\nmax_per = 2\n\
         component = \"rotd50\"\nscale_min = 0.1\nscale_max = 10.0\n",
    )
    .unwrap();
    let figure = dir.join("acc/figures/record_set.png");
    let before = std::fs::metadata(&figure).ok().and_then(|m| m.modified().ok());
    let o = stickslip(&["select", "acc", "--set", "other.toml"], &dir);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{out}{err}");
    assert!(out.contains("the set table → acc/tables/set.parquet"), "{out}");
    assert!(out.contains("report: rewritten with the new set"), "{out}");
    assert!(dir.join("acc/set/set.toml").is_file());
    let html = std::fs::read_to_string(dir.join("acc/index.html")).unwrap();
    let after = std::fs::metadata(&figure).unwrap().modified().unwrap();
    assert!(before.is_none_or(|b| after > b), "record_set.png was not redrawn");
    assert!(html.contains("ASCE 7-16, S_DS = 0.05 g"), "the page does not show the new target");
    for key in ["src=\"", "href=\""] {
        for link in html.split(key).skip(1).map(|s| &s[..s.find('"').unwrap()]) {
            assert!(dir.join("acc").join(link).exists(), "dead link {link}");
        }
    }
    // The set table's ranks follow the misfit, best first.
    let set = parquet(&dir.join("acc/tables/set.parquet"));
    let misfit: Vec<f64> = set.column("misfit").unwrap().f64().unwrap().iter().flatten().collect();
    assert!(misfit.windows(2).all(|w| w[0] <= w[1]), "{misfit:?}");
}

/// The content of the generated block `key` (see `stickslip-bench readme`), wherever it lives
/// (the README or a chapter of the guide).
fn readme_block(key: &str) -> String {
    stickslip_support::generated_block(key).0
}

#[test]
fn wall_times_are_masked_and_nothing_else() {
    assert_eq!(
        untimed("a: 3 seeds in 9.2 s → x\nreport: 17 figures in 0.8 s → y"),
        "a: 3 seeds in … s → x\nreport: 17 figures in … s → y\n"
    );
    assert_eq!(untimed("in the 2 s window"), "in the 2 s window\n");
}

/// Runs `pipelines/<name>.toml` as the README does (from a folder of its own, default output)
/// and returns its printout.
fn readme_run(name: &str) -> String {
    let dir = scratch(&format!("readme-{name}"));
    let p = repo().join(format!("pipelines/{name}.toml"));
    let o = stickslip(&["pipeline", p.to_str().unwrap(), "--quiet"], &dir);
    assert!(o.status.success(), "{}", text(&o).1);
    text(&o).0
}

#[test]
fn readme_paper_precise_printout_is_what_the_binary_prints() {
    let out = readme_run("paper-precise");
    let block = readme_block("paper-precise");
    let printed: Vec<&str> = out.lines().take(2).collect();
    let shown: Vec<&str> = block.lines().filter(|l| !l.starts_with("```")).collect();
    assert_eq!(untimed(&shown.join("\n")), untimed(&printed.join("\n")), "run stickslip-bench readme");
}

/// The 100-seed printout of the main command (the README's `paper-100` block), masked of its
/// wall times. Slow (100 seeds with records and spectra): `cargo test --release -- --ignored`.
#[test]
#[ignore]
fn readme_paper_100_printout_is_what_the_binary_prints() {
    let out = readme_run("paper-100");
    let block = readme_block("paper-100");
    let shown: Vec<&str> = block.lines().filter(|l| !l.starts_with("```")).collect();
    let first = out.lines().position(|l| l.starts_with("paper-100:")).unwrap();
    let printed: Vec<&str> = out.lines().skip(first).take(shown.len()).collect();
    assert_eq!(untimed(&shown.join("\n")), untimed(&printed.join("\n")), "run stickslip-bench readme");
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
            // Under a 4 GiB address-space limit: a scene refused before anything is built never
            // comes near it, one built first would abort on allocation (not exit with 1).
            let out = Command::new("sh")
                .args(["-c", "ulimit -v 4194304 && exec \"$0\" \"$@\"", env!("CARGO_BIN_EXE_stickslip")])
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
    // A skip-ahead run's step count bounds what it steps (slow-loading: 3.7e9 bounded, about 1e7
    // stepped), so it is never refused as long.
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(["check", repo().join("pipelines/slow-loading.toml").to_str().unwrap()])
        .current_dir(&dir)
        .output()
        .unwrap();
    let (stdout, err) = text(&out);
    assert!(out.status.success(), "a skip-ahead pipeline refused as long: {err}{stdout}");
    assert!(stdout.contains("at most") && !stdout.contains("accepted with --allow-long"), "{stdout}");
}

/// A fixed time step above the lattice's critical one is refused by `check`, as the run would
/// refuse it once built: with the step, the critical step, the seed and the keys.
#[test]
fn check_refuses_a_fixed_step_above_the_critical_one() {
    let dir = scratch("fixed-step");
    let text_in = std::fs::read_to_string(repo().join("pipelines/paper.toml")).unwrap();
    let mut doc: toml::Table = toml::from_str(&text_in).unwrap();
    let time = doc["time"].as_table_mut().unwrap();
    time.remove("dt_fraction");
    time.insert("dt_s".into(), 1e-3.into());
    std::fs::write(dir.join("fixed.toml"), toml::to_string(&doc).unwrap()).unwrap();
    let o = stickslip(&["check", "fixed.toml"], &dir);
    let (out, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}\n{err}");
    assert!(err.contains("time step 1.000000e-3 s is above the critical step") && err.contains("time.dt_s"), "{err}");
    // Below it the same file passes.
    doc["time"].as_table_mut().unwrap().insert("dt_s".into(), 1e-5.into());
    std::fs::write(dir.join("fixed.toml"), toml::to_string(&doc).unwrap()).unwrap();
    let o = stickslip(&["check", "fixed.toml"], &dir);
    assert!(o.status.success(), "{}", text(&o).1);
}

/// A fully dynamic cycle run whose explicit grid would not fit is refused before anything is
/// computed, naming its size and the keys that shrink it; `check` says what a run holds.
#[test]
fn a_cycle_run_too_large_for_memory_is_refused_before_it_starts() {
    let dir = scratch("cycles-memory");
    let text_in = std::fs::read_to_string(repo().join("pipelines/seas-bp1-fd.toml")).unwrap();
    let mut doc: toml::Table = toml::from_str(&text_in).unwrap();
    // A 400 km explicit grid at 100 m: 32 M nodes.
    let block = toml::Value::Array(vec![400000.0.into(), 400000.0.into()]);
    doc["cycles"].as_table_mut().unwrap().insert("dynamic_block_m".into(), block);
    std::fs::write(dir.join("bp1-fd.toml"), toml::to_string(&doc).unwrap()).unwrap();
    let check = stickslip(&["check", "bp1-fd.toml"], &dir);
    let (out, err) = text(&check);
    assert!(check.status.success(), "{out}\n{err}");
    assert!(out.contains("memory: about") && out.contains("the explicit grid"), "{out}");
    let o = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(["pipeline", "bp1-fd.toml", "--out", "out"])
        .current_dir(&dir)
        .env("STICKSLIP_MEMORY_LIMIT", "500M")
        .output()
        .unwrap();
    let (out, err) = text(&o);
    assert!(!o.status.success(), "{out}");
    assert!(
        err.contains("the cycle run needs about") && err.contains("cycles.dynamic_block_m") && err.contains("500M"),
        "{err}"
    );
    assert!(!dir.join("out/seas").exists(), "nothing is written");
}

/// `stickslip pipeline` on SEAS BP1-QD cut to 230 years (its first event, at 195 years): the
/// command's account, its files, and its figure read back where the files put the profiles.
#[test]
fn a_cycle_pipeline_writes_its_files_and_figure() {
    let dir = scratch("cycles");
    let text_in = std::fs::read_to_string(repo().join("pipelines/seas-bp1-qd.toml")).unwrap();
    let mut doc: toml::Table = toml::from_str(&text_in).unwrap();
    doc["cycles"].as_table_mut().unwrap().insert("years".into(), 230.0.into());
    std::fs::write(dir.join("bp1.toml"), toml::to_string(&doc).unwrap()).unwrap();
    let o = stickslip(&["pipeline", "bp1.toml", "--out", "out"], &dir);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{out}\n{err}");
    assert!(out.contains("1 events") && out.contains("event 0 at 195.1"), "{out}");
    for file in
        ["seas/fltst_dp000", "seas/fltst_dp350", "seas/devol.dat", "seas/global.dat", "tables/cycle_events.parquet"]
    {
        assert!(dir.join("out").join(file).is_file(), "{file}");
    }
    let figure = stickslip_report::cycles::draw_cycles(&dir.join("out")).unwrap();
    assert_eq!(figure.depths_km.len(), 81);
    assert_eq!((figure.depths_km[0], figure.depths_km[80]), (0.0, 39.9));
    // Slip is never negative, and none exceeds the plate's V_p·230 years = 7.26 m (the deepest
    // node creeps at nearly that rate).
    assert!(figure.slip_m[0] >= 0.0 && figure.slip_m[1] > 5.0 && figure.slip_m[1] < 7.26, "{:?}", figure.slip_m);
    assert!(figure.profiles[0] >= 40 && figure.profiles[1] >= 10, "{:?}", figure.profiles);
}
