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
            if col.dtype() == &DataType::Float64 {
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
        let options =
            EnsembleOptions { out: out.clone(), threads: 2, seeds: p.seeds.clone(), fresh: false, finish: true };
        let report = run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
        assert_eq!(report.failed.len(), if fails { 2 } else { 0 }, "{:?}", report.failed);
        assert_no_nan_in_tables(&out.join("tables"));
    }
}
