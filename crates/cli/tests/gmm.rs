//! A fault scenario end to end at 1 km (a smoke version of `pipelines/scenario-m6.toml`, seconds):
//! per-seed nucleation, the stations' RotD motions, `stickslip gmm` and its refusals. The
//! residuals are checked against the models evaluated here from the tables' own distances and
//! magnitudes; the scenario's statistics at 500 m are a benchmark (docs/guide/ground-motion.md, docs/model.md §16).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use stickslip_seismo::gmm::{Imt, Mechanism, Model, Rupture, Site};
use stickslip_support::polars::prelude::*;

fn stickslip(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip")).args(args).current_dir(cwd).output().expect("run stickslip")
}

fn read(path: &Path) -> DataFrame {
    ParquetReader::new(std::fs::File::open(path).unwrap()).finish().unwrap()
}

fn f64s(df: &DataFrame, name: &str) -> Vec<f64> {
    df.column(name)
        .unwrap()
        .cast(&DataType::Float64)
        .unwrap()
        .f64()
        .unwrap()
        .iter()
        .map(|v| v.unwrap_or(f64::NAN))
        .collect()
}

fn strs(df: &DataFrame, name: &str) -> Vec<String> {
    df.column(name).unwrap().str().unwrap().iter().map(|v| v.unwrap_or_default().to_string()).collect()
}

const SMOKE: &str = r#"
version = 1
name = "scenario-smoke"
[seeds]
list = [1, 2]
[block]
nx = 24
ny = 8
nz = 12
lc_m = 1000.0
[material]
young_pa = 8.0104e10
density_kg_m3 = 2670.0
poisson = 0.25
young_cv = 0.0
[friction]
mu_static = 0.677
mu_dynamic = 0.525
slip_weakening_m = 0.40
heals = false
[[friction.patches]]
name = "barrier -x"
shape = "rectangle"
x_m = [0.0, 5500.0]
mu_static = 10000.0
priority = 1
[[friction.patches]]
name = "barrier +x"
shape = "rectangle"
x_m = [16500.0, 24000.0]
mu_static = 10000.0
priority = 1
[[friction.patches]]
name = "barrier below"
shape = "rectangle"
x_m = [0.0, 24000.0]
y_m = [5500.0, 8000.0]
mu_static = 10000.0
priority = 2
[fault]
normal_stress_pa = 120e6
shear_stress_pa = 70e6
[fault.stochastic]
std_pa = 3e6
correlation_length_m = 3000.0
[fault.nucleation]
size_m = 3000.0
shear_stress_pa = 82e6
x_m = [8000.0, 14000.0]
y_m = [1500.0, 3500.0]
[absorbing]
faces = ["x_min", "x_max", "y_max", "z_max"]
[self_weight]
gravity_m_s2 = 0.0
[shear]
damping_per_s = 0.0
duration_s = 12.0
[record]
interval_s = 0.05
[[stations]]
name = "normal"
from_m = [11000.0, 0.0, 2000.0]
to_m = [11000.0, 0.0, 10000.0]
count = 5
[[stations]]
name = "buried"
at_m = [11000.0, 4000.0, 3000.0]
[events]
rupture_rate_m_s = 0.001
"#;

fn scenario() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-gmm-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("smoke.toml"), SMOKE).unwrap();
    let out = stickslip(&["pipeline", "smoke.toml", "--out", "out", "-q", "--threads", "2"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    dir
}

#[test]
fn a_scenario_s_stations_are_compared_with_the_models_as_they_predict() {
    let dir = scenario();
    let tables = dir.join("out/tables");
    // Each seed nucleates where its own draw puts it.
    let source = read(&tables.join("source.parquet"));
    let hx = f64s(&source, "hypocentre_x_m");
    assert_eq!(hx.len(), 2, "both seeds ruptured");
    assert_ne!(hx[0], hx[1], "two seeds, two hypocentres");
    let mw = f64s(&source, "mw");
    // The surface stations have processed motions and PSA in their usable band only.
    let st = read(&tables.join("stations.parquet"));
    let names = strs(&st, "station");
    let pgv = f64s(&st, "pgv_rotd50_m_s");
    let tmin = f64s(&st, "usable_min_period_s");
    let tmax = f64s(&st, "usable_max_period_s");
    assert!(pgv.iter().all(|v| *v > 0.0), "{pgv:?}");
    let sp = read(&tables.join("station_spectra.parquet"));
    let (sp_name, sp_t) = (strs(&sp, "station"), f64s(&sp, "period_s"));
    assert!(!sp_t.is_empty());
    for (n, t) in sp_name.iter().zip(&sp_t) {
        let i = names.iter().position(|s| s == n).unwrap();
        assert!(*t >= tmin[i] * (1.0 - 1e-9) && *t <= tmax[i], "{n}: {t} s outside [{}, {}]", tmin[i], tmax[i]);
    }
    // The pipeline compared them already (both models, V_S30 = Vs); `stickslip gmm` again with one
    // model and a V_S30 of 760 m/s rewrites the tables.
    assert!(tables.join("gmm_bias.parquet").exists() && dir.join("out/figures/gmm_bias.png").exists());
    let out = stickslip(&["gmm", "out", "--models", "bssa14", "--vs30", "760"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("PGV") && text.contains("PSA("), "{text}");
    let res = read(&tables.join("gmm_residuals.parquet"));
    let (model, imt, station) = (strs(&res, "model"), strs(&res, "imt"), strs(&res, "station"));
    assert!(model.iter().all(|m| m == "bssa14" || m == "average"));
    assert!(station.iter().all(|s| s.starts_with("normal-")), "the buried station is not compared");
    let seed: Vec<f64> = f64s(&res, "seed");
    let (period, r_rup, sim, median, resid) = (
        f64s(&res, "period_s"),
        f64s(&res, "r_rup_km"),
        f64s(&res, "simulated"),
        f64s(&res, "median"),
        f64s(&res, "residual_ln"),
    );
    let (y0, y1) = (f64s(&source, "rupture_y_min_m"), f64s(&source, "rupture_y_max_m"));
    let (st_seed, rjb, rx, ry0) = (f64s(&st, "seed"), f64s(&st, "r_jb_m"), f64s(&st, "r_x_m"), f64s(&st, "r_y0_m"));
    let mut checked = 0;
    for i in (0..model.len()).filter(|&i| model[i] == "bssa14") {
        let k = (seed[i] as usize) - 1;
        let j = (0..names.len()).find(|&j| names[j] == station[i] && st_seed[j] == seed[i]).unwrap();
        let rupture = Rupture {
            mw: mw[k],
            mechanism: Mechanism::StrikeSlip,
            dip_deg: 90.0,
            ztor_km: y0[k] / 1e3,
            width_km: (y1[k] - y0[k]) / 1e3,
            hypo_depth_km: None,
        };
        let site = Site {
            r_rup_km: r_rup[i],
            r_jb_km: rjb[j] / 1e3,
            r_x_km: rx[j] / 1e3,
            r_y0_km: Some(ry0[j] / 1e3),
            vs30_m_s: 760.0,
            z1_km: None,
            z25_km: None,
            vs30_measured: true,
        };
        let m = match imt[i].as_str() {
            "PGA" => Imt::Pga,
            "PGV" => Imt::Pgv,
            _ => Imt::Psa(period[i]),
        };
        let p = Model::Bssa14.predict(&rupture, &site, m).unwrap();
        assert!(
            (median[i] / p.median() - 1.0).abs() < 1e-9,
            "{} {}: {} vs {}",
            station[i],
            imt[i],
            median[i],
            p.median()
        );
        assert!((resid[i] - (sim[i] / median[i]).ln()).abs() < 1e-9);
        checked += 1;
    }
    assert!(checked >= 2 * 5 * 3, "PGA, PGV and PSA of every surface station and seed: {checked}");
    // The bias table: one row per measure for the model and one for the average.
    let bias = read(&tables.join("gmm_bias.parquet"));
    let (bm, bmean) = (strs(&bias, "model"), f64s(&bias, "mean_bias_ln"));
    for (m, b) in bm.iter().zip(&bmean) {
        assert!(m == "bssa14" || m == "average");
        assert!(b.is_finite());
    }
    a_scenario_s_set_is_chosen_by_magnitude_and_distance(&dir, &names, &st_seed, &f64s(&st, "r_rup_m"), &mw);
    let _ = std::fs::remove_dir_all(&dir);
}

/// `stickslip select` on the scenario: 4 stations by RotD50, at most 2 of a seed, R_rup ≤ 7 km,
/// matched to ASCE 7 over 1–4 s (the smoke's usable band is 0.86–4.8 s); the files are the
/// analysed records scaled, read back with the SAC reader and measured again.
fn a_scenario_s_set_is_chosen_by_magnitude_and_distance(
    dir: &Path,
    names: &[String],
    st_seed: &[f64],
    r_rup_m: &[f64],
    mw: &[f64],
) {
    use stickslip_seismo::accelerogram::sac::read_sac;
    use stickslip_seismo::spectra::response::Reading;
    use stickslip_seismo::spectra::rotd::{RotDPlan, RotDScratch, RotDSpectrum};
    let set = "[set]\ntarget = \"asce7\"\nt1_s = 0.0\nperiod_min_s = 1.0\nperiod_max_s = 4.0\ncount = 4\nmax_per = 2\n\
               per = \"seed\"\ncomponent = \"rotd50\"\nscale_min = 0.001\nscale_max = 1000.0\nmagnitude_min = 3.0\n\
               distance_max_km = 7.0\n";
    std::fs::write(dir.join("set.toml"), set).unwrap();
    let out = stickslip(&["select", "out", "--set", "set.toml"], dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("surface stations at Mw ≥ 3, R_rup ≤ 7 km"), "{text}");
    let tables = dir.join("out/tables");
    let chosen = read(&tables.join("set.parquet"));
    let (seed, station, scale) = (f64s(&chosen, "seed"), strs(&chosen, "record"), f64s(&chosen, "scale_factor"));
    let (set_mw, set_r) = (f64s(&chosen, "mw"), f64s(&chosen, "r_rup_km"));
    assert_eq!(seed.len(), 4);
    for k in 0..4 {
        assert!(seed.iter().filter(|s| **s == seed[k]).count() <= 2, "at most 2 of a seed: {seed:?}");
        let j = (0..names.len()).find(|&j| names[j] == station[k] && st_seed[j] == seed[k]).unwrap();
        assert!((set_r[k] - r_rup_m[j] / 1e3).abs() < 1e-9 && set_r[k] <= 7.0, "{} km", set_r[k]);
        assert_eq!(set_mw[k], mw[seed[k] as usize - 1]);
    }
    // The best record's two components, read back: their RotD50 is the station's, scaled.
    let spectra = read(&tables.join("station_spectra.parquet"));
    let (sp_seed, sp_name, sp_t, sp_v) =
        (f64s(&spectra, "seed"), strs(&spectra, "station"), f64s(&spectra, "period_s"), f64s(&spectra, "rotd50_m_s2"));
    let stem = format!("scenario-smoke_set01_seed{}_{}", seed[0], station[0]);
    let listing: Vec<_> = std::fs::read_dir(dir.join("out/set")).unwrap().flatten().map(|e| e.file_name()).collect();
    let fp = read_sac(&dir.join(format!("out/set/{stem}_FP.SAC"))).unwrap_or_else(|e| panic!("{e}: {listing:?}"));
    let fn_ = read_sac(&dir.join(format!("out/set/{stem}_FN.SAC"))).unwrap();
    assert!((fp.meta.magnitude.unwrap() as f64 - set_mw[0]).abs() < 1e-5);
    assert!((fp.dt - 0.05).abs() < 1e-9 && (fn_.dt - 0.05).abs() < 1e-9, "record.interval_s = 0.05: {}", fp.dt);
    // The vertical component beside the pair, up (−y of the scene), SEED channel BNZ (20 Hz).
    let up = read_sac(&dir.join(format!("out/set/{stem}_UP.SAC"))).unwrap_or_else(|e| panic!("{e}: {listing:?}"));
    assert_eq!((up.meta.component.as_str(), up.meta.component_incidence), ("BNZ", Some(0.0)));
    assert_eq!((fp.meta.component.as_str(), fn_.meta.component.as_str()), ("BN1", "BN2"));
    assert!((up.dt - 0.05).abs() < 1e-9 && up.data.iter().any(|v| *v != 0.0));
    // The rupture's start is the origin, at the nominal reference time; the station's position in
    // USER7–9 (m).
    use stickslip_seismo::accelerogram::sac::NOMINAL_ORIGIN;
    assert_eq!((fp.meta.origin, fp.meta.reference), (Some(0.0), Some(NOMINAL_ORIGIN)));
    assert!(fp.meta.begin.is_finite() && fp.meta.begin < 12.0, "the first sample (its pad's): {}", fp.meta.begin);
    assert!(fp.meta.user[7..].iter().all(Option::is_some) && fp.meta.user[8] == Some(0.0), "{:?}", fp.meta.user);
    assert!(dir.join(format!("out/set/{stem}_FP.AT2")).exists() && dir.join(format!("out/set/{stem}_FN.AT2")).exists());
    let mut checked = 0;
    for i in (0..sp_seed.len()).filter(|&i| sp_seed[i] == seed[0] && sp_name[i] == station[0]) {
        let t = sp_t[i];
        if !(1.0..=4.0).contains(&t) {
            continue;
        }
        let plan = RotDPlan::new(fp.dt, &[t], &[0.05], Reading::BandLimited, 4).unwrap();
        let mut r = RotDSpectrum::default();
        plan.compute(&fp.accel_si().unwrap(), &fn_.accel_si().unwrap(), &mut RotDScratch::default(), &mut r).unwrap();
        let psa = (2.0 * std::f64::consts::PI / t).powi(2) * r.rotd50[0];
        // The files are at exactly the interval asked (0.05 s, where the run recorded each step
        // of 0.0509 s): resampled band-limited before processing, which moves RotD50 in the band
        // by about 1e-4.
        assert!((psa / (scale[0] * sp_v[i]) - 1.0).abs() < 1e-3, "T = {t} s: {psa} vs {} × {}", scale[0], sp_v[i]);
        checked += 1;
    }
    assert!(checked >= 5, "the set's grid holds the log grid between the models' periods: {checked}");
    // Bins no rupture falls in: refused, saying how many stations there were.
    std::fs::write(dir.join("set.toml"), set.replace("magnitude_min = 3.0", "magnitude_min = 9.0")).unwrap();
    let out = stickslip(&["select", "out", "--set", "set.toml"], dir);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no record to choose from: surface stations at Mw ≥ 9, R_rup ≤ 7 km: 0 of 10"), "{err}");
}

#[test]
fn gmm_refuses_what_it_cannot_compare() {
    let dir = std::env::temp_dir().join(format!("stickslip-gmm-refusals-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (args, expect) in [
        (vec!["gmm", ".", "--vs30", "50"], "--vs30 = 50: a V_S30 from 100 to 5000 m/s"),
        (vec!["gmm", ".", "--models", "i14"], "--models"),
        (vec!["gmm", ".", "--models", "bssa14,bssa14"], "given twice"),
        (vec!["gmm", "."], "not"),
    ] {
        let out = stickslip(&args, &dir);
        assert!(!out.status.success(), "{args:?} was accepted");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(expect), "{args:?}: {err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_scenario_too_short_for_any_model_period_is_told_before_it_runs() {
    let dir = std::env::temp_dir().join(format!("stickslip-gmm-short-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // At 1 km the lattice resolves up to 1.16 Hz: PSA from 0.86 s. 12 s of run: usable to
    // 12/2.5 = 4.8 s; 2.4 s of run: to 0.96 s, a band between the models' 0.75 s and 1 s.
    for (duration, warned) in [("12.0", false), ("2.4", true)] {
        let text = SMOKE.replace("duration_s = 12.0", &format!("duration_s = {duration}"));
        std::fs::write(dir.join("short.toml"), text).unwrap();
        let out = stickslip(&["check", "short.toml"], &dir);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let said = String::from_utf8_lossy(&out.stdout).contains("holds none of the ground-motion");
        assert_eq!(said, warned, "duration {duration}: {}", String::from_utf8_lossy(&out.stdout));
    }
    // 0.6 s of run: usable to 0.24 s, below the shortest period: the band is empty, refused.
    std::fs::write(dir.join("short.toml"), SMOKE.replace("duration_s = 12.0", "duration_s = 0.6")).unwrap();
    let out = stickslip(&["check", "short.toml"], &dir);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("material.young_pa") && err.contains("usable band is empty"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_scenario_s_set_is_refused_before_it_runs_where_it_cannot_be_chosen() {
    let dir = std::env::temp_dir().join(format!("stickslip-gmm-set-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let with = |set: &str| format!("{SMOKE}\n[set]\n{set}\n");
    for (file, expect) in [
        // The stations' pairs are matched by RotD50 or RotD100, not one component.
        (
            with("component = \"x\"\nt1_s = 0.0\nperiod_min_s = 1.0\nperiod_max_s = 4.0"),
            "set.component = x is not allowed: \"rotd50\" or \"rotd100\"",
        ),
        // T₁ = 1 s asks for 0.2–2 s; the smoke's stations are usable from 0.86 s.
        (
            with("component = \"rotd100\"\nt1_s = 1.0"),
            "set.t1_s = 1 is not allowed: a period range (0.2 … 2 s) inside the stations' usable periods",
        ),
        (
            with("component = \"rotd50\"\nmagnitude_min = 6.5\nmagnitude_max = 6.0"),
            "set.magnitude_max = 6 is not allowed: above set.magnitude_min",
        ),
        (with("component = \"rotd50\"\ndistance_min_km = -1.0"), "set.distance_min_km = -1"),
        // Bins and RotD100 belong to scenarios, not to the records of events.
        (
            "version = 1\n[spectra]\n[set]\nmagnitude_min = 5.0\n".to_string(),
            "set.magnitude_min = 5 is not allowed: absent",
        ),
        ("version = 1\n[spectra]\n[set]\ncomponent = \"rotd100\"\n".to_string(), "set.component = rotd100"),
    ] {
        std::fs::write(dir.join("p.toml"), &file).unwrap();
        let out = stickslip(&["check", "p.toml"], &dir);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "accepted: {file}");
        assert!(err.contains(expect), "expected {expect:?} in: {err}");
    }
    // A set the stations can give is accepted, and check says where it comes from.
    std::fs::write(
        dir.join("p.toml"),
        with(
            "component = \"rotd100\"\nt1_s = 0.0\nperiod_min_s = 1.0\nperiod_max_s = 4.0\ndistance_max_km = 30.0\ncount = 4",
        ),
    )
    .unwrap();
    let out = stickslip(&["check", "p.toml"], &dir);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("chosen from the surface stations of every seed"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}
