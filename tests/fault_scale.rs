//! Earthquakes at their own scale, whole runs (docs/model.md §15): the SCEC benchmark TPV5 at
//! 500 m through the whole product (pipeline file → run → source, stations, benchmark files)
//! against the reference solution of MDSBI at 100 m (`pipelines/reference/tpv5/`).
//!
//! At 500 m the cohesive zone spans one module and the 3 km nucleation square six, its sides
//! half-loaded (docs/model.md §15.3), so the rupture starts late and runs slow: the tolerances are
//! those of an under-resolved run (measured: field RMS 18.8%, stations 13–27% late, slips 4–16%
//! high): the rupture-time field within 25% RMS, every station's rupture time within 30% (or 0.2 s
//! near the hypocentre), every final slip between 0.95 and 1.3 times the reference's. A fault mode
//! that healed, halved the slip, lost the tractions or the absorbing faces fails these by far
//! (healing alone left slips 30–50% low at 200 m). The benchmark at 200 m, with the tolerances of a
//! resolved run, is `tpv5_at_200_m_follows_the_reference` (80 s on two threads, `--ignored`); the
//! 100 m comparison (20 min) is in docs/model.md §15.6 and docs/guide/faults.md.

use std::sync::atomic::AtomicBool;

use stickslip_config::Pipeline;
use stickslip_ensemble::{EnsembleOptions, run_ensemble};
use stickslip_lab::scec::{Reference, compare, read_run};
use stickslip_seismo::scec::read_table;

/// Runs `pipeline` (one seed) into a scratch folder named `name` and compares its benchmark files
/// with the reference: the field's RMS relative difference below `field_rms`, every station's
/// rupture time within `time` of the reference's (or 0.2 s near the hypocentre), every final slip
/// within `slip` times the reference's. Returns the scratch folder, the run's folder and the
/// pipeline.
fn follows_the_reference(
    name: &str,
    pipeline: &str,
    field_rms: f64,
    time: f64,
    slip: std::ops::Range<f64>,
) -> (stickslip_support::Scratch, std::path::PathBuf, Pipeline) {
    let dir = stickslip_support::scratch_dir(name);
    let p = Pipeline::load(&stickslip_support::repo_path(pipeline)).unwrap();
    let out = dir.join("tpv5");
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: out.clone(),
        threads: 2,
        seeds: p.seeds.clone(),
        fresh: false,
        finish: true,
    };
    let report = run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    assert!(report.failed.is_empty(), "{:?}", report.failed);

    let reference = Reference::load(&stickslip_support::repo_path("pipelines/reference/tpv5")).unwrap();
    let scec = out.join("scec").join("seed1");
    let (stations, field) = read_run(&scec).unwrap();
    assert_eq!(stations.len(), 16, "the 16 on-fault stations of the benchmark");
    let c = compare(&stations, &field, &reference);
    println!("{}", stickslip_lab::scec::table(&c));
    assert!(c.field_points > 1500, "rupture-time field compared at {} points", c.field_points);
    assert!(c.field_rms < field_rms, "rupture-time field: RMS {:.3}", c.field_rms);
    for s in &c.stations {
        let (ours, theirs) = (s.rupture_time_s, s.reference.rupture_time_s);
        assert!(
            (ours - theirs).abs() < time * theirs || (ours - theirs).abs() < 0.2,
            "{}: rupture at {ours} s against {theirs} s",
            s.reference.name
        );
        let ratio = s.final_slip_m / s.reference.final_slip_m;
        assert!(
            slip.contains(&ratio),
            "{}: final slip {} against {} m",
            s.reference.name,
            s.final_slip_m,
            s.reference.final_slip_m
        );
    }
    let lattice = p.scene.lattice();
    assert_eq!(field.len(), lattice.contact_nodes().len());
    (dir, out, p)
}

#[test]
#[ignore = "80 s on two threads: TPV5 at 200 m, 44 M bars"]
fn tpv5_at_200_m_follows_the_reference() {
    // Measured: field RMS 1.55%, stations −1.2 … +4.1%, slips +1.1 … +5.6% (docs/model.md §15.6).
    follows_the_reference("tpv5-200m", "pipelines/tpv5.toml", 0.025, 0.05, 0.97..1.08);
}

#[test]
fn tpv5_at_500_m_follows_the_reference() {
    let (_dir, out, p) = follows_the_reference("tpv5-500m", "pipelines/tpv5-500m.toml", 0.25, 0.30, 0.95..1.3);
    let scec = out.join("scec").join("seed1");

    // The off-fault stations in the benchmark's layout, and the rupture-time file over every node.
    for name in ["body030st-120dp000", "body030st120dp000", "body030st-120dp075", "body030st120dp075"] {
        let text = std::fs::read_to_string(scec.join(format!("{name}.dat"))).unwrap();
        let (names, rows) = read_table(&text);
        assert_eq!(names, ["t", "h-disp", "h-vel", "v-disp", "v-vel", "n-disp", "n-vel"]);
        assert!(rows.len() > 400 && rows.iter().all(|r| r.len() == 7 && r.iter().all(|v| v.is_finite())));
        // The waves reached the station: it moved.
        assert!(rows.iter().any(|r| r[2].abs() > 0.1), "{name}: no ground velocity above 0.1 m/s");
    }
    // The source from the fault's own slip: TPV5 is an Mw ≈ 7 event with a 7–9 MPa drop.
    let source = stickslip_support::read_table(&out.join("tables").join("source.parquet"));
    let get = |c: &str| source.column(c).unwrap().f64().unwrap().get(0).unwrap();
    let (mw, drop) = (get("mw"), get("stress_drop_pa"));
    assert!((6.95..7.2).contains(&mw), "Mw {mw}");
    assert!((6e6..9e6).contains(&drop), "stress drop {drop} Pa");
    // Ruptured: the whole 30 × 15 km fault, and nothing in the barrier.
    let area = get("ruptured_area_m2");
    assert!((0.9 * 450e6..1.1 * 450e6).contains(&area), "ruptured area {area} m²");

    // Its report page says the same: Mw and stress drop from the source table, and none of the
    // block's similarity magnitudes (which put this rupture at M 5.65 / Mw 5.87).
    let report = stickslip_report::write_report(&out, &p).unwrap();
    let html = std::fs::read_to_string(&report.index).unwrap();
    assert!(html.contains(&format!("<td>{mw:.2}</td>")), "the page does not give Mw {mw:.2}");
    assert!(html.contains(&format!("<td>{:.2}</td>", drop / 1e6)), "the page does not give Δσ {drop} Pa");
    assert!(!html.contains("Main shocks across seeds") && !html.contains("M (paper's M0)"));
    assert!(!out.join("figures/magnitude.png").exists() && !out.join("figures/scaling.png").exists());
}

/// Broadband records (docs/model.md §17) are the same on one thread and on two: TPV5 at 500 m for
/// its first 3 s, two seeds (their stochastic parts differ: the random phases come from the
/// seed), every table compared value for value.
#[test]
fn broadband_records_are_the_same_on_any_thread_count() {
    let dir = stickslip_support::scratch_dir("broadband-threads");
    let text = std::fs::read_to_string(stickslip_support::repo_path("pipelines/tpv5-500m.toml"))
        .unwrap()
        .replace("duration_s = 12.0", "duration_s = 3.0")
        .replace("[seeds]\nlist = [1]", "[seeds]\nlist = [1, 2]")
        + "\n[broadband]\nvs30_m_s = [760.0, 400.0]\n";
    let file = dir.join("tpv5-broadband.toml");
    std::fs::write(&file, text).unwrap();
    let p = Pipeline::load(&file).unwrap();
    assert_eq!(p.seeds, [1, 2], "the pipeline's seeds");
    for threads in [1, 2] {
        let out = dir.join(format!("threads-{threads}"));
        let options = EnsembleOptions {
            checkpoint_every_s: None,
            out,
            threads,
            seeds: p.seeds.clone(),
            fresh: false,
            finish: true,
        };
        let report = run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
        assert!(report.failed.is_empty(), "{:?}", report.failed);
    }
    stickslip_support::assert_same_tables(&dir.join("threads-1"), &dir.join("threads-2"), &["wall_time_s"]);
    // The two seeds' stochastic parts differ; the lattice's (the same rupture, TPV5 has no random
    // field) do not on 760 m/s, where the site term is linear (on 400 m/s its nonlinear part reads
    // the stochastic part's peak).
    let records = stickslip_support::read_table(&dir.join("threads-1/tables/station_records.parquet"));
    let seed = records.column("seed").unwrap().u64().unwrap().clone();
    let station = records.column("station").unwrap().str().unwrap().clone();
    let sto = records.column("stochastic_m_s2").unwrap().f64().unwrap().clone();
    let det = records.column("deterministic_m_s2").unwrap().f64().unwrap().clone();
    let half = (0..seed.len()).filter(|&i| seed.get(i) == Some(1)).count();
    assert_eq!(half * 2, seed.len());
    assert!((0..half).all(|i| seed.get(i) == Some(1) && station.get(i) == station.get(i + half)));
    assert!((0..half).any(|i| sto.get(i) != sto.get(i + half)));
    let rock: Vec<usize> = (0..half).filter(|&i| station.get(i).is_some_and(|s| s.ends_with("_vs760"))).collect();
    assert!(!rock.is_empty());
    assert!(rock.iter().all(|&i| det.get(i) == det.get(i + half)));
}

/// TPV101's nucleation through the whole product (pipeline file → run → benchmark files): the
/// hypocentre's history up to its peak slip rate is local (the same to four digits on a 16 × 7.6 ×
/// 2 km block of velocity-weakening friction as on the benchmark's 56 × 20.5 × 20 km, 9 s on two
/// threads against 30 min), so a cut of `pipelines/tpv101.toml` to that block and 1.6 s meets the
/// reference (`pipelines/reference/tpv101/`, Tatva at 100 m) there: rupture at 0.5713 s against
/// 0.5693 s (+0.3%), peak slip rate 4.565 m/s at 1.358 s against 4.522 m/s at 1.405 s (+1.0%). The
/// whole benchmark at 100 m against the reference is in docs/guide/faults.md.
#[test]
fn tpv101_nucleates_at_its_hypocentre_as_the_reference() {
    let dir = stickslip_support::scratch_dir("tpv101-hypocentre");
    let text = std::fs::read_to_string(stickslip_support::repo_path("pipelines/tpv101.toml")).unwrap();
    let (patch, fault) = (text.find("\n[[friction.patches]]").unwrap(), text.find("\n[fault]\n").unwrap());
    let (stations, events) = (text.find("fault_stations_m = [").unwrap(), text.find("]\n\n[events]").unwrap());
    let cut =
        format!("{}{}fault_stations_m = [[8000.0, 0.0]{}", &text[..patch], &text[fault..stations], &text[events..])
            .replace("nx = 560", "nx = 160")
            .replace("ny = 205", "ny = 76")
            .replace("nz = 200", "nz = 20")
            .replace("duration_s = 12.0", "duration_s = 1.6")
            .replace("a = 0.016 ", "a = 0.008 ")
            .replace("28000.0", "8000.0");
    let file = dir.join("tpv101-hypocentre.toml");
    std::fs::write(&file, cut).unwrap();
    let p = Pipeline::load(&file).unwrap();
    let out = dir.join("out");
    run_first_seed(&p, &out);

    let (stations, _) = read_run(&out.join("scec").join("seed1")).unwrap();
    let reference = Reference::load(&stickslip_support::repo_path("pipelines/reference/tpv101")).unwrap();
    let c = compare(&stations, &[], &reference);
    let s = c.stations.iter().find(|s| s.reference.name == "faultst000dp075").unwrap();
    assert!(s.offset_m < 1.0, "the run's station is not at the hypocentre");
    let (t, r) = (s.rupture_time_s / s.reference.rupture_time_s, s.peak_slip_rate_m_s / s.reference.peak_slip_rate_m_s);
    println!(
        "hypocentre: rupture {:.4} s ({:+.2}%), peak slip rate {:.3} m/s ({:+.2}%)",
        s.rupture_time_s,
        100.0 * (t - 1.0),
        s.peak_slip_rate_m_s,
        100.0 * (r - 1.0)
    );
    assert!((t - 1.0).abs() < 0.03, "rupture at {} s against {} s", s.rupture_time_s, s.reference.rupture_time_s);
    assert!(
        (r - 1.0).abs() < 0.05,
        "peak slip rate {} against {} m/s",
        s.peak_slip_rate_m_s,
        s.reference.peak_slip_rate_m_s
    );

    // The station file in TPV101's layout: nine columns, log θ from the benchmark's 9.20581.
    let text = std::fs::read_to_string(out.join("scec/seed1/faultst000dp075.dat")).unwrap();
    let (names, rows) = read_table(&text);
    assert_eq!(&names[7..], ["n-stress", "log-theta"]);
    assert_eq!(rows[0][7..], [120.0, 9.20581]);

    // The block is the half below the mirror plane: the source counts both halves.
    let nodes = stickslip_support::read_table(&out.join("tables").join("fault_nodes.parquet"));
    let (area, time) =
        (nodes.column("area_m2").unwrap().f64().unwrap(), nodes.column("rupture_time_s").unwrap().f64().unwrap());
    let half: f64 =
        (0..nodes.height()).filter(|&i| time.get(i).is_some_and(f64::is_finite)).map(|i| area.get(i).unwrap()).sum();
    let source = stickslip_support::read_table(&out.join("tables").join("source.parquet"));
    let whole = source.column("ruptured_area_m2").unwrap().f64().unwrap().get(0).unwrap();
    assert!(half > 0.0 && (whole / half - 2.0).abs() < 1e-12, "source area {whole} m² for a half of {half} m²");
}

/// TPV101 at 100 m, the benchmark as posed (`pipelines/tpv101.toml`, about 30 min on two threads),
/// against the reference, held to what it does (docs/guide/faults.md): slips at 12 s within 2.5%
/// (measured +0.5 … +1.6%; goal 5%), rupture times within 6% and the field within 6% RMS (measured
/// −4.6 … −5.5% and 4.9%: the front runs early, the goal of 3% is not met), the peak slip rate
/// within 5% at the hypocentre and at (0, 12 km) (measured +1.0% and −0.7%) and within 40% farther
/// out (+19% and +36%: a sharper spike at the front than the reference's).
#[test]
#[ignore = "30 min on two threads: TPV101 at 100 m, 320 M bars"]
fn tpv101_at_100_m_follows_the_reference() {
    let dir = stickslip_support::scratch_dir("tpv101-100m");
    let p = Pipeline::load(&stickslip_support::repo_path("pipelines/tpv101.toml")).unwrap();
    let out = dir.join("tpv101");
    run_first_seed(&p, &out);
    let reference = Reference::load(&stickslip_support::repo_path("pipelines/reference/tpv101")).unwrap();
    let (stations, field) = read_run(&out.join("scec").join("seed1")).unwrap();
    let c = compare(&stations, &field, &reference);
    println!("{}", stickslip_lab::scec::table(&c));
    assert!(c.field_points > 300 && c.field_rms < 0.06, "field: RMS {} at {} points", c.field_rms, c.field_points);
    for s in &c.stations {
        let r = &s.reference;
        assert!(s.offset_m < 1.0, "{}: no run station there", r.name);
        assert!((s.rupture_time_s / r.rupture_time_s - 1.0).abs() < 0.06, "{}: rupture {}", r.name, s.rupture_time_s);
        assert!((s.final_slip_m / r.final_slip_m - 1.0).abs() < 0.025, "{}: slip {}", r.name, s.final_slip_m);
        let peak = s.peak_slip_rate_m_s / r.peak_slip_rate_m_s;
        let within = if r.at_km[0] == 0.0 { 0.05 } else { 0.4 };
        assert!((peak - 1.0).abs() < within, "{}: peak slip rate {}", r.name, s.peak_slip_rate_m_s);
    }
}

/// Runs the first seed of `p` on two threads into `out`.
fn run_first_seed(p: &Pipeline, out: &std::path::Path) {
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: out.to_path_buf(),
        threads: 2,
        seeds: p.seeds[..1].to_vec(),
        fresh: false,
        finish: true,
    };
    let report = run_ensemble(p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    assert!(report.failed.is_empty(), "{:?}", report.failed);
}
