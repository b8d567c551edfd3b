//! Ensembles: determinism across thread counts, tables read back lazily, main shocks labelled,
//! a changed pipeline refused.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use polars::prelude::*;
use stickslip_config::Pipeline;
use stickslip_ensemble::{EnsembleOptions, run_ensemble};
use stickslip_support::{assert_same_tables, read_table, repo_path, scratch_dir};

/// The paper pipeline cut to `seeds` seeds and `duration` seconds, sampled every 50 µs.
fn short_paper(seeds: u64, duration: f64) -> String {
    let text = std::fs::read_to_string(repo_path("pipelines/paper.toml")).unwrap();
    let mut doc: toml::Table = toml::from_str(&text).unwrap();
    doc.insert("name".into(), "short".into());
    let mut s = toml::Table::new();
    s.insert("range".into(), toml::Value::Table(toml::toml! { first = 1 count = 0 }));
    s["range"].as_table_mut().unwrap().insert("count".into(), (seeds as i64).into());
    doc.insert("seeds".into(), s.into());
    doc["shear"].as_table_mut().unwrap().insert("duration_s".into(), duration.into());
    doc["record"].as_table_mut().unwrap().insert("interval_s".into(), 5e-5.into());
    toml::to_string(&doc).unwrap()
}

fn pipeline(dir: &Path, text: &str) -> Pipeline {
    let path = dir.join("short.toml");
    std::fs::write(&path, text).unwrap();
    Pipeline::load(&path).unwrap()
}

fn run(p: &Pipeline, out: &Path, threads: usize) {
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: out.to_path_buf(),
        threads,
        seeds: p.seeds.clone(),
        fresh: false,
        finish: true,
    };
    let report = run_ensemble(p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    assert_eq!(report.ran, p.seeds.len());
    assert!(report.failed.is_empty(), "{:?}", report.failed);
}

fn scan(glob: &Path) -> DataFrame {
    LazyFrame::scan_parquet(PlRefPath::new(glob.display().to_string()), ScanArgsParquet::default())
        .unwrap()
        .collect()
        .unwrap()
}

#[test]
fn tables_do_not_depend_on_the_thread_count_and_read_back_lazily() {
    let dir = scratch_dir("ensemble-threads");
    let p = pipeline(&dir, &short_paper(16, 0.12));
    run(&p, &dir.join("one"), 1);
    run(&p, &dir.join("two"), 2);
    assert_same_tables(&dir.join("one"), &dir.join("two"), &["wall_time_s"]);

    // Every per-seed table reads back lazily over all seeds with a glob.
    let tables = dir.join("one/tables");
    let runs = scan(&tables.join("runs/*.parquet"));
    assert_eq!(runs.height(), 16);
    let steps: u64 = runs.column("steps").unwrap().u64().unwrap().sum().unwrap();
    assert!(steps > 16 * 10_000);
    // 0.12 s every 50 µs as a whole number of each seed's steps: from t = 0 to the last sample
    // within the stage.
    let mut samples = 0;
    for part in std::fs::read_dir(tables.join("series")).unwrap() {
        let series = read_table(&part.unwrap().path());
        let time = series.column("time_s").unwrap().f64().unwrap().clone();
        let every = time.get(1).unwrap() - time.get(0).unwrap();
        assert!((every / 5e-5 - 1.0).abs() < 0.15, "sampled every {every} s");
        let last = time.get(series.height() - 1).unwrap();
        assert!(last > 0.12 - every && last < 0.12 + every, "last sample at {last} s");
        assert_eq!(series.height(), (last / every).round() as usize + 1);
        samples += series.height();
    }
    assert_eq!(scan(&tables.join("series/*.parquet")).height(), samples);
    let mut pairs: Vec<_> = p.scene.record.control.iter().map(|c| (c.node, c.component)).collect();
    pairs.sort();
    pairs.dedup();
    assert_eq!(scan(&tables.join("control/*.parquet")).height(), samples * pairs.len());
    // One record per main shock and component of node 36 (x, y, z); spectra of each at two
    // scales, three dampings, 100 periods; RotD50 and RotD100 of each x–y pair.
    let mains: u64 = runs.column("main_shocks").unwrap().cast(&DataType::UInt64).unwrap().u64().unwrap().sum().unwrap();
    let records = read_table(&tables.join("records.parquet"));
    assert_eq!(records.height() as u64, mains * 3 * 2, "three components, two scales");
    assert_eq!(scan(&tables.join("spectra/*.parquet")).height() as u64, mains * 3 * 2 * 3 * 100);
    assert_eq!(scan(&tables.join("rotd/*.parquet")).height() as u64, mains * 2 * 2 * 3 * 100);
    assert_eq!(read_table(&tables.join("psa_stats.parquet")).height(), 5 * 2 * 3 * 100);
    // Each record once (model scale), over its window: the pads are described, not stored.
    let model = records.filter(&records.column("scale").unwrap().str().unwrap().equal("model")).unwrap();
    let window: u64 =
        model.column("window_samples").unwrap().cast(&DataType::UInt64).unwrap().u64().unwrap().sum().unwrap();
    let padded: u64 = model.column("samples").unwrap().cast(&DataType::UInt64).unwrap().u64().unwrap().sum().unwrap();
    assert!(window > 0 && 5 * window < padded, "windows {window} of {padded} padded samples");
    assert_eq!(scan(&tables.join("accelerograms/*.parquet")).height() as u64, window);
    assert_eq!(
        std::fs::read_dir(dir.join("one/records")).unwrap().count() as u64,
        mains * 3 * 2 * 3,
        "AT2, SAC and MiniSEED"
    );
    let events = scan(&tables.join("events/*.parquet"));
    let n_events: u32 = runs.column("events").unwrap().u32().unwrap().sum().unwrap();
    assert_eq!(events.height(), n_events as usize);
    assert_eq!(read_table(&tables.join("events.parquet")).height(), n_events as usize);
    assert_eq!(scan(&tables.join("similarity/*.parquet")).height(), n_events as usize);
    let subs: u32 = events.column("sub_events").unwrap().u32().unwrap().sum().unwrap();
    assert_eq!(scan(&tables.join("sub_events/*.parquet")).height(), subs as usize);
    let summary = read_table(&tables.join("summary.parquet"));
    assert!(summary.height() > 10);
}

#[test]
fn paper_pipeline_main_shocks_are_found_and_labelled_in_time_order() {
    let dir = scratch_dir("ensemble-paper");
    let p = Pipeline::load(&repo_path("pipelines/paper.toml")).unwrap();
    run(&p, &dir.join("out"), 2);
    let events = read_table(&dir.join("out/tables/events.parquet"));
    for &seed in &p.seeds {
        let mask = events.column("seed").unwrap().u64().unwrap().equal(seed);
        let e = events.filter(&mask).unwrap();
        let kind = e.column("kind").unwrap().str().unwrap().clone();
        let label = e.column("label").unwrap().str().unwrap().clone();
        let start = e.column("start_s").unwrap().f64().unwrap().clone();
        let mains: Vec<(String, f64)> = (0..e.height())
            .filter(|&i| kind.get(i) == Some("main"))
            .map(|i| (label.get(i).unwrap().to_string(), start.get(i).unwrap()))
            .collect();
        println!("seed {seed}: {mains:?}");
        assert!(mains.len() >= 2, "seed {seed}: {} main shocks", mains.len());
        for (k, (l, _)) in mains.iter().enumerate() {
            assert_eq!(l, &format!("S{}", k + 1));
        }
        assert!(mains.windows(2).all(|w| w[0].1 < w[1].1), "labels in time order");
    }
}

#[test]
fn a_changed_pipeline_is_refused_and_fresh_starts_over() {
    let dir = scratch_dir("ensemble-changed");
    let p = pipeline(&dir, &short_paper(2, 0.03));
    run(&p, &dir.join("out"), 2);
    let changed = pipeline(&dir, &short_paper(2, 0.03).replace("young_cv = 0.05", "young_cv = 0.06"));
    assert_ne!(p.hash, changed.hash);
    let mut options = EnsembleOptions {
        checkpoint_every_s: None,
        out: dir.join("out"),
        threads: 2,
        seeds: changed.seeds.clone(),
        fresh: false,
        finish: true,
    };
    let err = run_ensemble(&changed, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap_err().to_string();
    assert!(err.contains("holds results of another pipeline") && err.contains("--fresh"), "{err}");
    options.fresh = true;
    let report = run_ensemble(&changed, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    assert_eq!((report.ran, report.skipped), (2, 0));
    // The same pipeline again: nothing to run.
    options.fresh = false;
    let report = run_ensemble(&changed, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    assert_eq!((report.ran, report.skipped), (0, 2));
}

#[test]
fn shards_in_any_order_merge_to_the_plain_ensemble() {
    use stickslip_ensemble::merge::merge;
    use stickslip_ensemble::shard;
    let dir = scratch_dir("ensemble-shards");
    let p = pipeline(&dir, &short_paper(10, 0.06));
    std::fs::copy(dir.join("short.toml"), dir.join("copy.toml")).unwrap();
    run(&p, &dir.join("plain"), 2);
    let n = 4;
    for (out, order) in [("forward", (1..=n).collect::<Vec<_>>()), ("reverse", (1..=n).rev().collect())] {
        for k in order {
            let options = EnsembleOptions {
                checkpoint_every_s: None,
                out: dir.join(out),
                threads: 1,
                seeds: shard(&p.seeds, k, n),
                fresh: false,
                finish: false,
            };
            run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
        }
        // A shard run twice (e.g. a requeued array task) changes nothing.
        let again = EnsembleOptions {
            checkpoint_every_s: None,
            out: dir.join(out),
            threads: 2,
            seeds: shard(&p.seeds, 2, n),
            fresh: false,
            finish: false,
        };
        assert_eq!(run_ensemble(&p, &again, &|_, _| {}, &AtomicBool::new(false)).unwrap().ran, 0);
        let merged = merge(&dir.join(out), None, Some(n)).unwrap();
        assert_eq!(merged.seeds, 10);
        assert_same_tables(&dir.join("plain"), &dir.join(out), &["wall_time_s"]);
    }
    // An incomplete set of shards is refused, naming the missing shard.
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: dir.join("partial"),
        threads: 2,
        seeds: shard(&p.seeds, 1, n),
        fresh: false,
        finish: false,
    };
    run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    let err = merge(&dir.join("partial"), None, Some(n)).unwrap_err().to_string();
    assert!(err.contains("seeds missing") && err.contains("shards 2, 3, 4 of 4 incomplete"), "{err}");
}

/// `short_paper` with a `[seeds.target]` on the main shocks' stress drop.
fn with_target(text: &str, relative: f64, batch: i64) -> String {
    let mut doc: toml::Table = toml::from_str(text).unwrap();
    let seeds = doc["seeds"].as_table_mut().unwrap();
    let mut t = toml::Table::new();
    t.insert("quantity".into(), "stress_drop_pa".into());
    t.insert("group".into(), "main".into());
    t.insert("relative".into(), relative.into());
    t.insert("batch".into(), batch.into());
    seeds.insert("target".into(), t.into());
    toml::to_string(&doc).unwrap()
}

fn run_precise(p: &Pipeline, out: &Path, threads: usize) -> stickslip_ensemble::precision::PrecisionOutcome {
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: out.to_path_buf(),
        threads,
        seeds: p.seeds.clone(),
        fresh: false,
        finish: true,
    };
    let target = p.target.as_ref().expect("a target");
    let (report, outcome) =
        stickslip_ensemble::precision::run_to_precision(p, target, &options, &|_, _| {}, &AtomicBool::new(false))
            .unwrap();
    assert_eq!(report.ran + report.skipped, outcome.seeds_used);
    outcome
}

#[test]
fn a_precision_target_stops_at_the_same_seed_whatever_the_threads_and_says_when_it_cannot_be_met() {
    let dir = scratch_dir("ensemble-precision");
    // Loose enough to be met before the budget of 12 seeds: the main shocks' drops spread by
    // ~20% (S1 larger than the rest), so a 15% half-width needs a few batches of 3 seeds.
    let p = pipeline(&dir, &with_target(&short_paper(12, 0.12), 0.15, 3));
    let one = run_precise(&p, &dir.join("one"), 1);
    let two = run_precise(&p, &dir.join("two"), 2);
    assert!(one.met, "{}", one.describe());
    assert!(one.seeds_used < 12 && one.seeds_used.is_multiple_of(3), "{}", one.describe());
    assert_eq!(one, two, "the seeds used must not depend on the thread count");
    let h = one.half_width.unwrap();
    assert!(h <= 0.15 * one.mean.unwrap().abs(), "{}", one.describe());
    // The gathered tables hold exactly the seeds used.
    let runs = read_table(&dir.join("one/tables/runs.parquet"));
    assert_eq!(runs.height(), one.seeds_used);
    // Resuming the finished folder reaches the same decision without running a seed.
    let again = run_precise(&p, &dir.join("one"), 2);
    assert_eq!(again.seeds_used, one.seeds_used);

    // An impossible target spends the whole budget and says so.
    let q = pipeline(&dir, &with_target(&short_paper(6, 0.12), 1e-9, 3));
    let out = run_precise(&q, &dir.join("impossible"), 2);
    assert!(!out.met && out.seeds_used == 6, "{}", out.describe());
    assert!(out.describe().contains("NOT met: all 6 seeds of the budget used"), "{}", out.describe());
}

#[test]
fn every_target_quantity_is_summarised() {
    use stickslip_config::precision::TARGET_QUANTITIES;
    use stickslip_ensemble::summary::{EVENT_QUANTITIES, SIMILARITY_QUANTITIES};
    for q in TARGET_QUANTITIES {
        assert!(EVENT_QUANTITIES.contains(&q) || SIMILARITY_QUANTITIES.contains(&q), "{q} is not summarised");
    }
    assert_eq!(TARGET_QUANTITIES.len(), EVENT_QUANTITIES.len() + SIMILARITY_QUANTITIES.len());
}

/// Seeds keeping checkpoints, stopped as they run (as Ctrl-C or a cluster's SIGTERM stops them)
/// and run again into the same folder: they resume from their checkpoints, and the tables are
/// those of an ensemble never stopped; the checkpoints go once the seeds are written.
#[test]
fn seeds_stopped_and_resumed_from_their_checkpoints_give_the_same_tables() {
    use stickslip_ensemble::checkpoints::Checkpoints;
    use stickslip_ensemble::error::EnsembleError;
    let dir = scratch_dir("ensemble-checkpoints");
    let p = pipeline(&dir, &short_paper(2, 0.1));
    run(&p, &dir.join("plain"), 2);
    let out = dir.join("stopped");
    let options = EnsembleOptions {
        // At every progress report (512 steps here).
        checkpoint_every_s: Some(1e-9),
        out: out.clone(),
        threads: 2,
        seeds: p.seeds.clone(),
        fresh: false,
        finish: true,
    };
    let cancel = AtomicBool::new(false);
    let checkpoints = Checkpoints { out: out.clone(), every_s: 1e-9, key: p.hash.clone() };
    std::thread::scope(|s| {
        // Stops the seeds once the first checkpoint is written.
        s.spawn(|| {
            while checkpoints.found(&p.seeds, 1).is_empty() {
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            cancel.store(true, std::sync::atomic::Ordering::SeqCst);
        });
        let e = run_ensemble(&p, &options, &|_, _| {}, &cancel).unwrap_err();
        assert!(matches!(e, EnsembleError::Interrupted { .. }), "{e}");
    });
    let found = checkpoints.found(&p.seeds, 1);
    assert!(!found.is_empty() && found.iter().all(|&(_, step)| step > 0), "{found:?}");
    let report = run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    assert_eq!(report.ran + report.skipped, 2);
    assert!(report.checkpoint_notes.is_empty(), "{:?}", report.checkpoint_notes);
    assert!(checkpoints.found(&p.seeds, 1).is_empty(), "the checkpoints are removed once the seeds are written");
    assert_same_tables(&dir.join("plain"), &out, &["wall_time_s"]);
}
