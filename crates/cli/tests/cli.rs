//! The `stickslip` binary end to end: outputs read back with polars, errors and exit codes.

use std::path::Path;
use std::process::{Command, Output};

use stickslip_support::polars::prelude::*;

fn stickslip(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip")).args(args).current_dir(cwd).output().expect("run stickslip")
}

/// A scratch folder, removed when the test passes (see `stickslip_support::scratch_dir`).
fn scratch(name: &str) -> stickslip_support::Scratch {
    stickslip_support::scratch_dir(&format!("cli-{name}"))
}

const SMALL: &str = r#"
version = 1
name = "small"
[block]
nx = 4
ny = 1
nz = 2
[shear]
duration_s = 0.01
driver_at_m = [[0.0, 0.0, 0.1]]
[record]
interval_s = 1e-4
energy = true
[[record.control]]
nodes = [12]
quantities = ["displacement", "acceleration"]
components = ["x", "z"]
"#;

fn read(path: &Path) -> DataFrame {
    ParquetReader::new(std::fs::File::open(path).unwrap()).finish().unwrap()
}

#[test]
fn run_writes_series_and_control_tables_that_read_back() {
    let dir = scratch("run");
    std::fs::write(dir.join("small.toml"), SMALL).unwrap();
    let out = stickslip(&["run", "small.toml", "--seed", "7", "--out", "out"], &dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.starts_with("seed 7: ") && stdout.contains("steps/s"), "{stdout}");
    // One seed is an ensemble of one: the layout and tables of `stickslip pipeline`.
    for f in ["manifest.toml", "pipeline.toml", "tables/runs.parquet", "tables/events.parquet", "index.html"] {
        assert!(dir.join("out").join(f).exists(), "run wrote no {f}");
    }
    let series = read(&dir.join("out/tables/series/seed-0000000007.parquet"));
    // 0.01 s every 1e-4 s taken as a whole number of steps (Δt is the scene's own, not fitted
    // to the interval): the nearest multiple of Δt, from t = 0 to the last one within the stage.
    let time = series.column("time_s").unwrap().f64().unwrap().clone();
    let every = time.get(1).unwrap() - time.get(0).unwrap();
    assert!((every / 1e-4 - 1.0).abs() < 0.1, "sampled every {every} s");
    let last = time.get(series.height() - 1).unwrap();
    assert!(last > 0.01 - every && last < 0.01 + every, "last sample at {last} s");
    let samples = (last / every).round() as usize + 1;
    assert_eq!(series.height(), samples);
    assert!((1..samples).all(|i| ((time.get(i).unwrap() - time.get(i - 1).unwrap()) / every - 1.0).abs() < 1e-6));
    for col in
        ["seed", "time_s", "shear_stress_pa", "normal_stress_pa", "mean_slip_m", "slipping_nodes", "kinetic_energy_j"]
    {
        assert!(series.column(col).is_ok(), "series lacks {col}");
    }
    assert_eq!(series.column("slipping_nodes").unwrap().dtype(), &DataType::UInt32);
    assert_eq!(series.column("normal_stress_pa").unwrap().dtype(), &DataType::Float32, "channels in single precision");
    let sigma =
        series.column("normal_stress_pa").unwrap().cast(&DataType::Float64).unwrap().f64().unwrap().mean().unwrap();
    let expected = 2400.0 * 9.81 * 0.2; // ρ·g·h
    assert!((sigma / expected - 1.0).abs() < 0.01, "mean σ {sigma} vs ρgh {expected}");
    let control = read(&dir.join("out/tables/control/seed-0000000007.parquet"));
    assert_eq!(control.height(), 2 * samples, "one node × two components × every sample");
    let acc = control.column("acceleration_m_s2").unwrap();
    assert_eq!(acc.null_count(), 0);
    let vel = control.column("velocity_m_s").unwrap();
    assert_eq!(vel.null_count(), control.height(), "velocity was not asked for");
    // The catalogue statistics of a catalogue far too small: each says why, none is NaN.
    let out = stickslip(&["catalogue", "out"], &dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(stdout.contains("Gutenberg–Richter") && stdout.contains("no fit:") && !stdout.contains("NaN"), "{stdout}");
    let b = read(&dir.join("out/tables/b_values.parquet"));
    assert_eq!(b.column("reason").unwrap().null_count(), 0, "every b-value row says why it has no fit");
    let out = stickslip(&["catalogue", "no-such-folder"], &dir);
    assert!(!out.status.success() && String::from_utf8_lossy(&out.stderr).contains("no-such-folder"));
}

#[test]
fn default_output_folder_is_under_reports() {
    let dir = scratch("default-out");
    std::fs::write(dir.join("small.toml"), SMALL).unwrap();
    let out = stickslip(&["run", "small.toml", "--seed", "3", "--quiet"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(dir.join("reports/small/seed-3/tables/series/seed-0000000003.parquet").exists());
}

#[test]
fn bad_arguments_and_bad_files_fail_with_a_clear_message() {
    let dir = scratch("errors");
    let out = stickslip(&["run", "x.toml"], &dir);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--seed"));
    let out = stickslip(&["run", "missing.toml", "--seed", "1"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("missing.toml") && err.contains("no such file"), "{err}");
    std::fs::write(dir.join("bad.toml"), "version = 1\n[material]\npoisson = 0.7\n").unwrap();
    let out = stickslip(&["run", "bad.toml", "--seed", "1"], &dir);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("material.poisson = 0.7") && err.contains("0 < poisson < 0.5"), "{err}");
    assert!(!dir.join("reports").exists(), "nothing may be written for a refused file");
    let out = stickslip(&["frobnicate"], &dir);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn similarity_calculator_prints_the_papers_numbers() {
    let dir = scratch("similarity");
    let out = stickslip(
        &[
            "similarity",
            "--stress-drop-pa",
            "7600",
            "--model-length-m",
            "1",
            "--model-area-m2",
            "0.1",
            "--prototype-length-m",
            "10000",
            "--duration-s",
            "0.0021",
            "--recurrence-s",
            "0.0258",
        ],
        &dir,
    );
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    let snapshot = include_str!("snapshots/similarity_paper_s2.txt");
    assert_eq!(text, snapshot, "output changed; if on purpose, update tests/snapshots/similarity_paper_s2.txt");
    // The figures docs/model.md §9 pins: 7.6e25 dyne·cm, M = 6.778, 7.6e21, 21 s, 2.83 years.
    for want in ["7.6000e25 dyne·cm", "6.778", "7.6000e21 dyne·cm", "21.0000 s", "2.837 years"] {
        assert!(text.contains(want), "missing {want}:\n{text}");
    }
    // A negative number is a value, not a flag: refused with its range.
    for args in [["similarity", "--stress-drop-pa", "-5"], ["similarity", "--stress-drop-pa=-5", "--duration-s=1"]] {
        let bad = stickslip(&args, &dir);
        assert_eq!(bad.status.code(), Some(1));
        let err = String::from_utf8_lossy(&bad.stderr);
        assert!(err.contains("--stress-drop-pa = -5 is not allowed: a positive, finite number"), "{err}");
    }
}

#[test]
fn spectra_of_an_outside_record_in_csv() {
    let dir = scratch("record");
    let mut csv = String::from("time_s,acc_gal\n");
    for i in 0..=2000 {
        let t = i as f64 * 0.005;
        csv.push_str(&format!("{t},{}\n", 150.0 * (2.0 * std::f64::consts::PI * t / 0.5).sin()));
    }
    std::fs::write(dir.join("rec.csv"), csv).unwrap();
    let out = stickslip(&["spectra", "rec.csv", "--units", "cm/s2", "--dampings", "0.02,0.05", "--out", "o"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let intensity = read(&dir.join("o/intensity.parquet"));
    let pga = intensity.column("pga_m_s2").unwrap().f64().unwrap().get(0).unwrap();
    assert!((pga - 1.5).abs() < 1e-9, "PGA {pga} m/s² for 150 gal");
    let spectra = read(&dir.join("o/spectra.parquet"));
    assert_eq!(spectra.height(), 200);
    assert!(dir.join("o/fourier.parquet").exists());
    let bad = stickslip(&["spectra", "rec.csv", "--units", "furlongs"], &dir);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("possible values"));
}

#[test]
fn figures_render_the_same_without_any_system_font() {
    // fontconfig pointed at an empty configuration: no system font can be found, and the
    // figures must come out byte for byte the same (the text uses the bundled DejaVu Sans).
    let dir = scratch("fonts");
    std::fs::write(dir.join("small.toml"), SMALL).unwrap();
    std::fs::create_dir_all(dir.join("empty")).unwrap();
    std::fs::write(
        dir.join("fonts.conf"),
        "<?xml version=\"1.0\"?>\n<!DOCTYPE fontconfig SYSTEM \"fonts.dtd\">\n<fontconfig></fontconfig>\n",
    )
    .unwrap();
    let run = |out: &str, no_fonts: bool| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_stickslip"));
        c.args(["pipeline", "small.toml", "--quiet", "--out", out]).current_dir(&dir);
        if no_fonts {
            c.env("FONTCONFIG_FILE", dir.join("fonts.conf"))
                .env("FONTCONFIG_PATH", dir.join("empty"))
                .env("XDG_DATA_HOME", dir.join("empty"))
                .env("XDG_DATA_DIRS", dir.join("empty"));
        }
        let o = c.output().unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    run("with", false);
    run("without", true);
    let a = std::fs::read(dir.join("with/figures/shear_stress.png")).unwrap();
    let b = std::fs::read(dir.join("without/figures/shear_stress.png")).unwrap();
    assert_eq!(a, b, "figures differ without system fonts");
}

/// `stickslip catalogue` says which magnitude column each b-value is of, over how many bins above
/// Mc it was fitted, and warns when that is too narrow a range for a Gutenberg–Richter slope (the
/// paper's scene: a characteristic size, a b from two or three bins).
#[test]
fn the_b_value_names_its_column_and_warns_when_fitted_from_too_few_bins() {
    let dir = scratch("catalogue-bins");
    let text = std::fs::read_to_string(stickslip_support::repo_path("pipelines/paper.toml"))
        .unwrap()
        .replace("list = [123, 200, 7]", "range = [1, 24]")
        .replace("[report]\n", "[report]\nenabled = false\n");
    assert!(text.contains("range = [1, 24]"), "paper.toml's seeds changed");
    std::fs::write(dir.join("p.toml"), text).unwrap();
    let out = stickslip(&["pipeline", "p.toml", "--out", "out", "--quiet"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let out = stickslip(&["catalogue", "out"], &dir);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    // The pooled fit of mw_consistent, from the tables the command rewrote.
    let b = read(&dir.join("out/tables/b_values.parquet"));
    let pooled = |df: &DataFrame, i: usize| {
        df.column("seed").unwrap().u64().unwrap().get(i).is_none()
            && df.column("quantity").unwrap().str().unwrap().get(i) == Some("mw_consistent")
    };
    let row = (0..b.height()).find(|&i| pooled(&b, i)).expect("a pooled mw_consistent row");
    let mc = b.column("mc").unwrap().f64().unwrap().get(row).expect("paper scene: a b-value is fitted");
    let f = read(&dir.join("out/tables/magnitude_frequency.parquet"));
    let centre = f.column("bin_centre").unwrap().f64().unwrap();
    let incremental = f.column("incremental").unwrap().cast(&DataType::UInt64).unwrap();
    let incremental = incremental.u64().unwrap();
    let top = (0..f.height())
        .filter(|&i| pooled(&f, i) && incremental.get(i).unwrap() > 0)
        .map(|i| centre.get(i).unwrap())
        .fold(f64::NEG_INFINITY, f64::max);
    let bins = ((top - mc) / 0.1).round() as i64 + 1;
    assert!((1..10).contains(&bins), "the paper's sizes cluster: {bins} bins from Mc {mc} to {top}");
    assert!(stdout.contains(&format!("in {bins} bins (Mc to {top:.1})")), "{stdout}");
    assert!(
        stdout.contains(&format!("warning: mw_consistent: b fitted from {bins} magnitude bins above Mc")),
        "{stdout}"
    );
    assert!(stdout.contains("at least 1.0 unit above Mc (10 bins of 0.1)"), "{stdout}");
    assert!(stdout.contains("m_riera_paper_interplate: Riera's M") && stdout.contains("\"M (paper)\""), "{stdout}");
}
