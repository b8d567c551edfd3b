//! Events do not depend on how a run is recorded: the same seed recorded at 10 µs and at 200 µs
//! (the paper scene), or at 1 ms and 0.1 ms with skip-ahead (slow loading), gives the same
//! catalogue, measure for measure; and the event trace's thinning between bursts changes
//! nothing against keeping every step.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use stickslip_analysis::events::catalogue;
use stickslip_config::Pipeline;
use stickslip_ensemble::{EnsembleOptions, run_ensemble};
use stickslip_solver::{Model, RunOptions, TracePlan, run_seed};
use stickslip_support::{read_table, repo_path, scratch_dir};

/// `file` with `edit` applied, written under `dir` as `name.toml` and loaded.
fn variant(dir: &Path, file: &str, name: &str, edit: impl FnOnce(&mut toml::Table)) -> Pipeline {
    let mut doc: toml::Table = toml::from_str(&std::fs::read_to_string(repo_path(file)).unwrap()).unwrap();
    doc.insert("name".into(), name.into());
    edit(&mut doc);
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, toml::to_string(&doc).unwrap()).unwrap();
    Pipeline::load(&path).unwrap()
}

fn set(doc: &mut toml::Table, section: &str, key: &str, value: toml::Value) {
    doc.entry(section).or_insert_with(|| toml::Value::Table(toml::Table::new()));
    doc[section].as_table_mut().unwrap().insert(key.into(), value);
}

fn run(p: &Pipeline, out: &Path) {
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: out.to_path_buf(),
        threads: 2,
        seeds: p.seeds.clone(),
        fresh: true,
        finish: true,
    };
    let report = run_ensemble(p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    assert!(report.failed.is_empty(), "{:?}", report.failed);
}

/// The events and sub-events tables of two output folders are the same, value for value.
fn same_catalogues(a: &Path, b: &Path) -> usize {
    let mut n = 0;
    for table in ["events.parquet", "sub_events.parquet"] {
        let (x, y) = (read_table(&a.join("tables").join(table)), read_table(&b.join("tables").join(table)));
        assert_eq!(x.height(), y.height(), "{table}: {} rows against {}", x.height(), y.height());
        assert!(x.equals_missing(&y), "{table} differs:\n{x}\n{y}");
        n += x.height();
    }
    n
}

#[test]
fn the_paper_scene_gives_the_same_events_recorded_every_10_or_200_microseconds() {
    let dir = scratch_dir("recording-paper");
    let edit = |interval: f64| {
        move |doc: &mut toml::Table| {
            set(doc, "seeds", "list", toml::Value::Array(vec![200.into(), 7.into()]));
            set(doc, "record", "interval_s", interval.into());
            doc.remove("accelerograms");
            doc.remove("spectra");
        }
    };
    let fine = variant(&dir, "pipelines/paper.toml", "fine", edit(1e-5));
    let coarse = variant(&dir, "pipelines/paper.toml", "coarse", edit(2e-4));
    run(&fine, &dir.join("fine"));
    run(&coarse, &dir.join("coarse"));
    let events = read_table(&dir.join("fine/tables/events.parquet"));
    let kind = events.column("kind").unwrap().str().unwrap().clone();
    let mains = (0..events.height()).filter(|&i| kind.get(i) == Some("main")).count();
    assert!(mains >= 3, "{mains} main shocks in two seeds");
    same_catalogues(&dir.join("fine"), &dir.join("coarse"));
}

#[test]
fn slow_loading_with_skip_ahead_gives_the_same_events_recorded_every_1_or_0_1_ms() {
    let dir = scratch_dir("recording-slow");
    let edit = |interval: f64| {
        move |doc: &mut toml::Table| {
            set(doc, "shear", "duration_s", 300.0.into());
            set(doc, "record", "interval_s", interval.into());
        }
    };
    let coarse = variant(&dir, "pipelines/slow-loading.toml", "coarse", edit(1e-3));
    let fine = variant(&dir, "pipelines/slow-loading.toml", "fine", edit(1e-4));
    run(&coarse, &dir.join("coarse"));
    run(&fine, &dir.join("fine"));
    let runs = read_table(&dir.join("coarse/tables/runs.parquet"));
    let skipped = runs.column("skipped_steps").unwrap().u64().unwrap().get(0).unwrap();
    assert!(skipped > 0, "the skip-ahead jumped");
    let n = same_catalogues(&dir.join("coarse"), &dir.join("fine"));
    assert!(n >= 6, "{n} events and sub-events in 300 s");
}

#[test]
fn thinning_the_trace_between_bursts_changes_no_event() {
    let p = Pipeline::load(&repo_path("pipelines/paper.toml")).unwrap();
    let run_with = |trace: TracePlan| {
        let mut scene = p.scene.clone();
        scene.record.trace = trace;
        let model = Model::new(scene);
        let out = run_seed(&model, 200, RunOptions::default(), &mut |_| std::ops::ControlFlow::Continue(())).unwrap();
        let cat = catalogue(&out.recording, &model, &p.analysis.events);
        (out.recording.trace.len(), out.shear_steps, cat)
    };
    let (thin_len, steps, thin) = run_with(p.scene.record.trace);
    // Every step hot: the whole shear stage at full rate.
    let (full_len, _, full) = run_with(TracePlan { hot_rate_m_s: 0.0, ..p.scene.record.trace });
    assert_eq!(full_len as u64, steps + 1);
    assert!(thin_len < full_len, "the default trace keeps {thin_len} of {full_len} steps");
    assert!(!thin.events.is_empty());
    assert_eq!(thin.events.len(), full.events.len());
    assert_eq!(thin.sub_events.len(), full.sub_events.len());
    let kinds = |c: &stickslip_seismo::events::Catalogue| c.events.iter().map(|e| e.kind).collect::<Vec<_>>();
    assert_eq!(kinds(&thin), kinds(&full));
    let bursts = |c: &stickslip_seismo::events::Catalogue| {
        c.events.iter().map(|e| e.burst.clone()).chain(c.sub_events.iter().cloned()).collect::<Vec<_>>()
    };
    for (x, y) in bursts(&thin).iter().zip(&bursts(&full)) {
        assert_eq!((x.start_s, x.end_s, x.drop_end_s), (y.start_s, y.end_s, y.drop_end_s));
        assert!((x.stress_drop_pa - y.stress_drop_pa).abs() <= 1e-9 * y.stress_drop_pa, "{x:?}\n{y:?}");
        assert_eq!((x.slip_m, x.peak_slipping_nodes), (y.slip_m, y.peak_slipping_nodes));
        assert!((x.peak_slip_rate_m_s - y.peak_slip_rate_m_s).abs() <= 1e-9 * y.peak_slip_rate_m_s.abs());
        assert_eq!(x.peak_acceleration, y.peak_acceleration);
    }
}

/// Every seed's records come at one interval, the pipeline's `record.interval_s` (2e-5 s in
/// paper.toml), although each seed records every 2 of its own steps (2.12e-5 … 2.16e-5 s): set
/// members, SAC files and engineers' tools see one Δt (docs/model.md §8).
#[test]
fn two_seeds_records_share_one_round_interval() {
    let dir = scratch_dir("recording-record-dt");
    let p = variant(&dir, "pipelines/paper.toml", "record-dt", |doc| {
        set(doc, "seeds", "list", toml::Value::Array(vec![200.into(), 7.into()]));
        set(doc, "report", "enabled", false.into());
    });
    run(&p, &dir.join("out"));
    let column = |table: &str, name: &str| -> Vec<f64> {
        let df = read_table(&dir.join("out/tables").join(table));
        df.column(name).unwrap().f64().unwrap().into_no_null_iter().collect()
    };
    let recorded: Vec<f64> = column("runs.parquet", "dt_s").iter().map(|dt| 2.0 * dt).collect();
    assert!((recorded[0] - recorded[1]).abs() > 1e-3 * recorded[0], "the seeds' own intervals {recorded:?} are alike");
    let records = read_table(&dir.join("out/tables/records.parquet"));
    let scale = records.column("scale").unwrap().str().unwrap().clone();
    let seeds: Vec<u64> = records.column("seed").unwrap().u64().unwrap().into_no_null_iter().collect();
    let dt = column("records.parquet", "dt_s");
    let model: Vec<usize> = (0..dt.len()).filter(|&i| scale.get(i) == Some("model")).collect();
    assert!(model.iter().any(|&i| seeds[i] == 200) && model.iter().any(|&i| seeds[i] == 7), "{seeds:?}");
    for &i in &model {
        assert_eq!(dt[i], 2e-5, "seed {}: record dt {} s", seeds[i], dt[i]);
    }
    // The samples of the accelerograms table are that far apart.
    let folder = stickslip_store::Folder::new(dir.join("out"));
    let acc = read_table(&folder.part(&stickslip_store::schema::ACCELEROGRAMS, 7));
    let t: Vec<f64> = acc.column("time_s").unwrap().f64().unwrap().into_no_null_iter().take(50).collect();
    assert!(t.windows(2).all(|w| ((w[1] - w[0]) / 2e-5 - 1.0).abs() < 1e-6), "{:?}", &t[..4]);
}
