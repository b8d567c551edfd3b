//! What the ensemble writes of the accelerogram records: AT2 files that read back as the
//! processed record (the table holds its window, once, in single precision), spectra of the file
//! that are the table's spectra, prototype spectra that are the scaled model spectra.

use std::sync::atomic::AtomicBool;

use polars::prelude::*;
use stickslip_config::Pipeline;
use stickslip_ensemble::{EnsembleOptions, run_ensemble};
use stickslip_seismo::accelerogram::{AccelUnit, read_accelerogram};
use stickslip_seismo::spectra::response::{Reading, SpectrumPlan, SpectrumScratch};
use stickslip_support::{read_table, repo_path, scratch_dir};

fn rows(df: &DataFrame, record: &str, scale: &str) -> DataFrame {
    let m = df.column("record").unwrap().str().unwrap().equal(record)
        & df.column("scale").unwrap().str().unwrap().equal(scale);
    df.filter(&m).unwrap()
}

fn f64s(df: &DataFrame, name: &str) -> Vec<f64> {
    df.column(name).unwrap().cast(&DataType::Float64).unwrap().f64().unwrap().iter().map(|v| v.unwrap()).collect()
}

fn u32s(df: &DataFrame, name: &str) -> Vec<u32> {
    df.column(name).unwrap().u32().unwrap().iter().map(|v| v.unwrap()).collect()
}

#[test]
fn at2_files_read_back_and_prototype_spectra_are_the_scaled_model_spectra() {
    let dir = scratch_dir("spectra-outputs");
    let text = std::fs::read_to_string(repo_path("pipelines/paper.toml")).unwrap();
    let text = text.replace("list = [123, 200, 7]", "list = [123]").replace("duration_s = 0.32 ", "duration_s = 0.08 ")
        // A set any x record can meet: its files are written from the records processed again.
        + "\n[set]\ntarget = \"ec8\"\na_g_m_s2 = 1e-3\nt1_s = 10.0\ncount = 1\ncomponent = \"x\"\nscale_min = 1e-6\n\
           scale_max = 1e6\n";
    std::fs::write(dir.join("p.toml"), &text).unwrap();
    let p = Pipeline::load(&dir.join("p.toml")).unwrap();
    let out = dir.join("out");
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: out.clone(),
        threads: 1,
        seeds: vec![123],
        fresh: false,
        finish: true,
    };
    run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    let acc = read_table(&out.join("tables/accelerograms/seed-0000000123.parquet"));
    let spectra = read_table(&out.join("tables/spectra/seed-0000000123.parquet"));
    let records = read_table(&out.join("tables/records.parquet"));
    let z = records.filter(&records.column("component").unwrap().str().unwrap().equal("z")).unwrap();
    assert!(z.height() >= 2, "a z record at both scales: {records}");
    let name = z.column("record").unwrap().str().unwrap().get(0).unwrap().to_string();
    let lambda = 1.0e4;
    for scale in ["model", "prototype"] {
        let path = out.join(format!("records/paper_seed123_{name}_{scale}.AT2"));
        let head: Vec<String> = std::fs::read_to_string(&path).unwrap().lines().take(3).map(String::from).collect();
        assert!(head[1].contains(&format!("({scale} scale")), "{}", head[1]);
        assert_eq!(head[2], "ACCELERATION TIME SERIES IN UNITS OF G");
        let record = read_accelerogram(&path, AccelUnit::G).unwrap();
        // The table: the record's window at model scale (prototype: accelerations ÷λ, times ×λ).
        let l = if scale == "model" { 1.0 } else { lambda };
        let table = {
            let m = acc.column("record").unwrap().str().unwrap().equal(name.as_str());
            acc.filter(&m).unwrap()
        };
        let a: Vec<f64> = f64s(&table, "acceleration_m_s2").iter().map(|v| v / l).collect();
        let t: Vec<f64> = f64s(&table, "time_s").iter().map(|v| v * l).collect();
        let meta = rows(&records, &name, scale);
        let (samples, window) = (u32s(&meta, "samples")[0] as usize, u32s(&meta, "window_samples")[0] as usize);
        let front = (-f64s(&meta, "first_sample_s")[0] / f64s(&meta, "dt_s")[0]).round() as usize;
        assert_eq!((record.accel.len(), a.len()), (samples, window), "the file is padded, the table its window");
        assert!((record.dt / (t[1] - t[0]) - 1.0).abs() < 1e-7, "DT {} vs {}", record.dt, t[1] - t[0]);
        let scale_max = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        // The file's 8 significant digits and the table's single precision (2⁻²⁴ of each value).
        for (x, y) in record.accel[front..front + window].iter().zip(&a) {
            assert!((x - y).abs() <= (5e-8 + 6e-8) * y.abs() + 1e-12 * scale_max, "{x} vs {y}");
        }
        // The spectrum of the file as read back equals the table's rows of that scale.
        let rows5 = {
            let r = rows(&spectra, &name, scale);
            let m = r.column("damping").unwrap().f64().unwrap().equal(0.05);
            r.filter(&m).unwrap()
        };
        let periods = f64s(&rows5, "period_s");
        let psa = f64s(&rows5, "psa_m_s2");
        let plan = SpectrumPlan::new(record.dt, &periods, &[0.05], Reading::Linear, 1).unwrap();
        let mut sd = vec![0.0; plan.len()];
        plan.compute(&record.accel, &mut SpectrumScratch::default(), &mut sd).unwrap();
        // Up to the file's 8 significant digits: each sample is off by up to 5e-8 of itself,
        // which long periods (tiny PSA against the PGA) feel as 1e-7 of the PGA.
        for ((t, want), got_sd) in periods.iter().zip(&psa).zip(&sd) {
            let got = got_sd * (2.0 * std::f64::consts::PI / t).powi(2);
            assert!((got - want).abs() < 1e-6 * want + 1e-7 * scale_max, "{scale} T {t}: {got} vs {want}");
        }
        if scale == "prototype" {
            let model = rows(&spectra, &name, "model");
            let model5 = model.filter(&model.column("damping").unwrap().f64().unwrap().equal(0.05)).unwrap();
            for ((tm, am), (tp, ap)) in
                f64s(&model5, "period_s").iter().zip(f64s(&model5, "psa_m_s2")).zip(periods.iter().zip(&psa))
            {
                assert!((tp / (tm * lambda) - 1.0).abs() < 1e-12 && (ap * lambda / am - 1.0).abs() < 1e-12);
            }
        }
    }
    // The set's file is the chosen record, pads included, times its factor: the record processed
    // again from the control table is the one the analysis wrote.
    let set = read_table(&out.join("tables/set.parquet"));
    let chosen = set.column("record").unwrap().str().unwrap().get(0).unwrap().to_string();
    let factor = f64s(&set, "scale_factor")[0];
    let file = read_accelerogram(&out.join(format!("set/paper_set01_seed123_{chosen}.AT2")), AccelUnit::G).unwrap();
    let record =
        read_accelerogram(&out.join(format!("records/paper_seed123_{chosen}_prototype.AT2")), AccelUnit::G).unwrap();
    assert_eq!(file.accel.len(), record.accel.len());
    assert!((file.dt / record.dt - 1.0).abs() < 1e-7);
    let peak = record.accel.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (x, y) in file.accel.iter().zip(&record.accel) {
        assert!((x - factor * y).abs() <= 1e-7 * (factor * y).abs() + 1e-12 * factor * peak, "{x} vs {factor}·{y}");
    }
}
