//! The tables of whole pipeline runs: no NaN anywhere (a value that does not exist is null), for
//! finished and failed seeds alike.

/// Every float in every table under `dir` is a number or null, never NaN.
fn assert_no_nan_in_tables(dir: &std::path::Path) {
    use polars::prelude::*;
    let files = stickslip_support::parquet_files(dir);
    assert!(!files.is_empty(), "no tables under {}", dir.display());
    for f in files {
        let df = stickslip_support::read_table(&dir.join(&f));
        for col in df.columns() {
            if matches!(col.dtype(), DataType::Float64 | DataType::Float32) {
                let col = col.cast(&DataType::Float64).unwrap();
                let nan = col.f64().unwrap().iter().flatten().filter(|x| x.is_nan()).count();
                assert_eq!(nan, 0, "{}: column {} has {nan} NaN", f.display(), col.name());
            }
        }
    }
}

#[test]
fn failed_and_finished_seeds_leave_no_nan_in_any_table() {
    use std::sync::atomic::AtomicBool;
    use stickslip_config::Pipeline;
    use stickslip_ensemble::{EnsembleOptions, run_ensemble};
    let dir = stickslip_support::scratch_dir("no-nan");
    // Two seeds that settle and shear for 0.1 s (events, similarity, spectra with the first
    // event's missing recurrence), and the same scene with a settling time limit too short.
    let text = std::fs::read_to_string(stickslip_support::repo_path("pipelines/paper.toml")).unwrap();
    let mut doc: toml::Table = toml::from_str(&text).unwrap();
    doc.insert("name".into(), "no-nan".into());
    doc.insert("seeds".into(), toml::Value::Table(toml::toml! { list = [1, 2] }));
    doc["shear"].as_table_mut().unwrap().insert("duration_s".into(), 0.1.into());
    let ok_path = dir.join("ok.toml");
    std::fs::write(&ok_path, toml::to_string(&doc).unwrap()).unwrap();
    doc["self_weight"].as_table_mut().unwrap().insert("max_duration_s".into(), 1e-4.into());
    let bad_path = dir.join("bad.toml");
    std::fs::write(&bad_path, toml::to_string(&doc).unwrap()).unwrap();
    for (path, fails) in [(ok_path, false), (bad_path, true)] {
        let p = Pipeline::load(&path).unwrap();
        let out = dir.join(if fails { "bad" } else { "ok" });
        let options = EnsembleOptions {
            checkpoint_every_s: None,
            out: out.clone(),
            threads: 2,
            seeds: p.seeds.clone(),
            fresh: false,
            finish: true,
        };
        let report = run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
        assert_eq!(report.failed.len(), if fails { 2 } else { 0 }, "{:?}", report.failed);
        assert_no_nan_in_tables(&out.join("tables"));
    }
}

/// Runs a short paper pipeline (spectra, attenuation, energy), a short skip-ahead one and the
/// tension prism (cracks), the asperity fault and TPV5 at 500 m (source, fault nodes, stations), and checks every table against the store's registry: each declared
/// column is written, nothing undeclared is, and every typed reader reads what its writer wrote.
#[test]
fn every_table_matches_its_declaration_and_reads_back_typed() {
    use std::sync::atomic::AtomicBool;

    use stickslip_config::Pipeline;
    use stickslip_ensemble::{EnsembleOptions, run_ensemble};
    use stickslip_solver::Channel;
    use stickslip_solver::scene::{Component, Kinematic};
    use stickslip_store::Folder;
    use stickslip_store::io::read_parquet;
    use stickslip_store::schema::{self, Scope};
    use stickslip_store::tables::cracks::{AcousticEmission, Cracks};
    use stickslip_store::tables::events::{Events, Similarity};
    use stickslip_store::tables::fronts::{RuptureOnsets, Ruptures};
    use stickslip_store::tables::records::{Accelerograms, Attenuation, Records};
    use stickslip_store::tables::runs::Runs;
    use stickslip_store::tables::series::{Fault, read_control, read_series_channel};
    use stickslip_store::tables::set::SetTable;
    use stickslip_store::tables::source::{FaultNodes, Stations};
    use stickslip_store::tables::spectra::{Spectra, read_fourier};
    use stickslip_store::tables::stats::{AttenuationFit, PsaStats, SummaryTable};

    let dir = stickslip_support::scratch_dir("registry");
    let paper = std::fs::read_to_string(stickslip_support::repo_path("pipelines/paper.toml"))
        .unwrap()
        .replace("list = [123, 200, 7]", "list = [123, 200]")
        .replace("duration_s = 0.32 ", "duration_s = 0.12 ")
        // A set any record can meet: every declared table is then written.
        + "\n[set]\ntarget = \"ec8\"\na_g_m_s2 = 1e-3\nt1_s = 10.0\ncount = 1\ncomponent = \"x\"\nscale_min = 1e-6\n\
           scale_max = 1e6\n";
    let skip = "version = 1\nname = \"skip\"\n[seeds]\nlist = [7]\n[friction]\nmu_dynamic = 4.5\n[shear]\n\
                velocity_m_s = 1.1e-6\nduration_s = 3.0\n[record]\ninterval_s = 1e-4\n[skip_ahead]\nenabled = true\n";
    // The tension prism, one seed: the crack catalogue and its acoustic-emission events.
    let tension = std::fs::read_to_string(stickslip_support::repo_path("pipelines/rupture-tension.toml"))
        .unwrap()
        .replace("list = [1, 2, 3, 4]", "list = [1]");
    // The asperity fault, one seed: the fault table, its station files and fronts read on slip rates.
    let fault = std::fs::read_to_string(stickslip_support::repo_path("pipelines/fault-asperity.toml"))
        .unwrap()
        .replace("range = { first = 1, count = 8 }", "list = [1]")
        .replace("duration_s = 0.3", "duration_s = 0.12");
    // TPV5 at 500 m for its first 3 s: the source, the fault's nodes and the off-fault stations,
    // with broadband records on one site.
    let quake = std::fs::read_to_string(stickslip_support::repo_path("pipelines/tpv5-500m.toml"))
        .unwrap()
        .replace("duration_s = 12.0", "duration_s = 3.0")
        + "\n[broadband]\nvs30_m_s = 760.0\n";
    let mut seen = std::collections::BTreeSet::new();
    for (name, text) in [
        ("paper", paper.as_str()),
        ("skip", skip),
        ("tension", tension.as_str()),
        ("fault", fault.as_str()),
        ("quake", quake.as_str()),
    ] {
        std::fs::write(dir.join(format!("{name}.toml")), text).unwrap();
        let p = Pipeline::load(&dir.join(format!("{name}.toml"))).unwrap();
        let out = dir.join(name);
        let options = EnsembleOptions {
            checkpoint_every_s: None,
            out: out.clone(),
            threads: 2,
            seeds: p.seeds.clone(),
            fresh: false,
            finish: true,
        };
        run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
        let folder = Folder::new(&out);
        for spec in schema::ALL {
            let mut files = Vec::new();
            if spec.scope != Scope::AcrossSeeds {
                files.extend(p.seeds.iter().map(|&s| folder.part(&spec, s)).filter(|f| f.exists()));
            }
            if spec.scope != Scope::PerSeed && folder.gathered(&spec).exists() {
                files.push(folder.gathered(&spec));
            }
            for f in files {
                seen.insert(spec.name);
                let df = read_parquet(&f).unwrap();
                let names: Vec<String> = df.get_column_names().iter().map(|c| c.to_string()).collect();
                for c in spec.columns {
                    assert!(names.iter().any(|n| n == c), "{}: declared column {c} not written", f.display());
                }
                for n in &names {
                    let declared = spec.columns.contains(&n.as_str())
                        || (spec.name == "series" && Channel::ALL.iter().any(|ch| ch.name() == n))
                        || (spec.variable.is_some() && n.starts_with("peak_abs_accel_"));
                    assert!(declared, "{}: column {n} is not declared in the registry", f.display());
                }
                match spec.name {
                    "runs" => assert!(!Runs::read(&df).unwrap().seed.is_empty()),
                    "events" => {
                        Events::read(&df).unwrap();
                    }
                    "similarity" => {
                        Similarity::read(&df).unwrap();
                    }
                    "summary" => assert_eq!(
                        SummaryTable::read(&df).unwrap().find("main", "stress_drop_pa").is_some(),
                        name == "paper" || name == "fault" || name == "quake",
                        "main shocks in the paper and fault runs only (and the quake's one rupture)"
                    ),
                    "psa_stats" => assert!(!PsaStats::read(&df).unwrap().mean.is_empty()),
                    "attenuation" => assert!(!Attenuation::read(&df).unwrap().is_empty()),
                    "attenuation_fit" => assert!(!AttenuationFit::read(&df).unwrap().slope.is_empty()),
                    "spectra" | "rotd" => assert!(!Spectra::read(&df).unwrap().psa_m_s2.is_empty()),
                    "records" => assert!(!Records::read(&df).unwrap().record.is_empty()),
                    "accelerograms" => assert!(!Accelerograms::read(&df).unwrap().time_s.is_empty()),
                    "set" => assert_eq!(SetTable::read(&df).unwrap().record.len(), 1),
                    "cracks" => assert!(!Cracks::read(&df).unwrap().is_empty()),
                    "acoustic_emission" => assert!(!AcousticEmission::read(&df).unwrap().is_empty()),
                    "fourier" => {
                        // Every bin of the record's usable band, and none above it.
                        let (f, _) = read_fourier(&df, "S1-n36-z").unwrap().expect("S1's z record");
                        let seed = df.column("seed").unwrap().u64().unwrap().get(0).unwrap();
                        let records = folder.part(&stickslip_store::tables::records::RECORDS, seed);
                        let r = Records::read(&read_parquet(&records).unwrap()).unwrap();
                        let i =
                            (0..r.record.len()).find(|&i| r.record[i] == "S1-n36-z" && r.scale[i] == "model").unwrap();
                        let (top, df_hz) = (f[f.len() - 1], f[1] - f[0]);
                        assert!(
                            top <= r.usable_high_hz[i] && top + df_hz > r.usable_high_hz[i],
                            "{top} Hz, band {}",
                            r.usable_high_hz[i]
                        );
                    }
                    // The skip-ahead pipeline has no control node: its part is empty, with the schema.
                    "control" => assert_eq!(
                        read_control(&df, 36, Component::Z, Kinematic::Acceleration).unwrap().is_some(),
                        name == "paper"
                    ),
                    "ruptures" => {
                        let r = Ruptures::read(&df).unwrap();
                        assert!(!r.is_empty(), "{name}: no rupture front");
                        assert!(r.hypocentre_region.iter().all(|g| !g.is_empty()));
                    }
                    "rupture_onsets" => assert!(!RuptureOnsets::read(&df).unwrap().onset_s.is_empty()),
                    "fault" => {
                        let f = Fault::read(&df).unwrap();
                        assert_eq!(f.node.len() % 82, 0, "every contact node at every kept instant");
                        let stations = folder.fault_stations_dir(1);
                        assert_eq!(std::fs::read_dir(&stations).unwrap().count(), 4, "{}", stations.display());
                    }
                    "fault_nodes" => {
                        let f = FaultNodes::read(&df).unwrap();
                        assert_eq!(f.x_m.len(), 101 * 51, "every node of the fault plane");
                        assert!(f.rupture_time_s.iter().any(|t| t.is_finite()), "nothing ruptured");
                    }
                    "stations" => {
                        let s = Stations::read(&df).unwrap();
                        assert_eq!(s.station.len(), 4 + 19, "the benchmark's four and the surface line");
                        // 1–19 km off the fault plane: R_rup (to the part ruptured in 3 s) is no less.
                        assert!(s.r_rup_m.iter().all(|r| (999.0..25000.0).contains(r)), "{:?}", s.r_rup_m);
                    }
                    "fault_station_series" if name == "quake" => {
                        // The 16 on-fault stations at every kept instant, the values the benchmark
                        // files print: the last slip of the hypocentre's station, read from both.
                        let c = stickslip_store::frame::Columns::of(&df, "fault_station_series");
                        let station = c.strs(stickslip_store::col::STATION).unwrap();
                        let slip = c.f64s(stickslip_store::col::SLIP_X_M).unwrap();
                        let mut names = station.clone();
                        names.sort();
                        names.dedup();
                        assert_eq!(names.len(), 16, "{names:?}");
                        let last = (0..station.len()).rfind(|&i| station[i] == "faultst000dp075").unwrap();
                        let file = std::fs::read_to_string(out.join("scec/seed1/faultst000dp075.dat")).unwrap();
                        let row = file.lines().last().unwrap();
                        let h_slip: f64 = row.split_whitespace().nth(1).unwrap().parse().unwrap();
                        assert!(
                            (slip[last] - h_slip).abs() <= 1e-6 * h_slip.abs().max(1e-3),
                            "{} vs {h_slip}",
                            slip[last]
                        );
                    }
                    "station_records" => {
                        // Three components of every surface station's record, each the sum of its
                        // parts, at the broadband interval from t = 0.
                        let c = stickslip_store::frame::Columns::of(&df, "station_records");
                        let station = c.strs(stickslip_store::col::STATION).unwrap();
                        let t = c.f64s(stickslip_store::col::TIME_S).unwrap();
                        let (d, s_, b) = (
                            c.f64s(stickslip_store::col::DETERMINISTIC_M_S2).unwrap(),
                            c.f64s(stickslip_store::col::STOCHASTIC_M_S2).unwrap(),
                            c.f64s(stickslip_store::col::BROADBAND_M_S2).unwrap(),
                        );
                        assert!((0..b.len()).all(|i| (b[i] - d[i] - s_[i]).abs() <= 1e-12 * b[i].abs().max(1e-9)));
                        let first = station[0].clone();
                        let rows: Vec<usize> = (0..station.len()).filter(|&i| station[i] == first).collect();
                        assert_eq!(rows.len(), 3 * 301, "3 components × 3 s at 0.01 s");
                        assert!((t[rows[1]] - 0.01).abs() < 1e-15);
                        let r = stickslip_store::tables::broadband::read_station_record(&df, &first, "y").unwrap();
                        assert_eq!(r.unwrap().time_s.len(), 301);
                    }
                    "gmm_part_b" => {
                        let c = stickslip_store::frame::Columns::of(&df, "gmm_part_b");
                        let (lo, hi) = (
                            c.f64s(stickslip_store::col::BAND_LOW).unwrap(),
                            c.f64s(stickslip_store::col::BAND_HIGH).unwrap(),
                        );
                        let mean = c.f64s(stickslip_store::col::MODELS_MEAN).unwrap();
                        assert!((0..lo.len()).all(|i| lo[i] < mean[i] && mean[i] < hi[i]));
                        // Broadband records are compared from 0.01 s.
                        let t = c.opt_f64s(stickslip_store::col::PERIOD_S).unwrap();
                        assert!(t.contains(&Some(0.01)), "{t:?}");
                    }
                    "source" => {
                        let m0 = df.column(stickslip_store::col::M0_N_M).unwrap().f64().unwrap().get(0).unwrap();
                        assert!(m0 > 1e18, "TPV5's first 3 s: M0 {m0} N·m");
                    }
                    "series" => {
                        assert!(read_series_channel(&df, Channel::ShearStress.name()).unwrap().is_some())
                    }
                    _ => {}
                }
            }
        }
    }
    let all: std::collections::BTreeSet<&str> = schema::ALL.iter().map(|t| t.name).collect();
    assert_eq!(seen, all, "every declared table is written by one of the five pipelines");
}
