//! Rock-like friction gives earthquakes when the block is loaded through springs
//! (`pipelines/plate-stickslip.toml`, docs/model.md §12), and does not with the paper's damping,
//! where `stickslip check` predicts stable sliding.

use std::ops::ControlFlow;

use stickslip_analysis::events::catalogue;
use stickslip_config::Pipeline;
use stickslip_solver::inspect::{Statics, inspect};
use stickslip_solver::{Model, RunOptions, run_seed};
use stickslip_support::repo_path;

#[test]
fn rock_like_friction_on_a_loading_plate_gives_repeated_stick_slip_in_every_seed() {
    let p = Pipeline::load(&repo_path("pipelines/plate-stickslip.toml")).unwrap();
    let model = Model::new(p.scene.clone());
    let facts = inspect(&model, &p.seeds[..1], Statics::Full).unwrap();
    assert!(facts.slider.verdict().starts_with("stick-slip expected"), "{}", facts.slider.verdict());
    let mut recurrences = Vec::new();
    for &seed in &p.seeds[..4] {
        let out = run_seed(&model, seed, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
        let cat = catalogue(&out.recording, &model, &p.analysis.events);
        let mains: Vec<_> = cat.main_shocks().collect();
        // 0.3 s at 1 mm/s: the springs reload 2.3 kPa in about 46 ms, so at least four main shocks.
        assert!(mains.len() >= 4, "seed {seed}: {} main shocks", mains.len());
        for e in &mains {
            assert!(e.burst.stress_drop_pa > 1000.0, "seed {seed}: a main shock of {:.0} Pa", e.burst.stress_drop_pa);
        }
        recurrences.extend(mains.windows(2).map(|w| w[1].burst.start_s - w[0].burst.start_s));
    }
    // Regular cycles: the recurrence varies by less than 20% (coefficient of variation).
    let n = recurrences.len() as f64;
    let mean = recurrences.iter().sum::<f64>() / n;
    let sd = (recurrences.iter().map(|r| (r - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    println!("recurrence {:.1} ± {:.1} ms over {} intervals", mean * 1e3, sd * 1e3, recurrences.len());
    assert!(sd / mean < 0.2, "recurrence CV {:.3}", sd / mean);
}

#[test]
fn the_paper_damping_makes_the_plate_scene_slide_stably_and_check_says_so() {
    let mut file = Pipeline::load(&repo_path("pipelines/plate-stickslip.toml")).unwrap().file;
    file.shear.damping_per_s = 400.0;
    let scene = file.scene().unwrap();
    let model = Model::new(scene);
    let facts = inspect(&model, &[1], Statics::Full).unwrap();
    let verdict = facts.slider.verdict();
    assert!(verdict.starts_with("stable sliding expected despite k < k_c"), "{verdict}");
    assert!((facts.slider.damping_ratio - 0.70).abs() < 0.02, "D/(2ω) = {}", facts.slider.damping_ratio);
}

/// The paper's block kept seated (`pipelines/paper-seated.toml`): rock-like slip-weakening
/// friction, loaded by a plate on its trailing face. The guide (docs/guide/paper.md) compares its 8 seeds with the
/// paper's 7.6 kPa, 2.1 ms and 25.8 ms (measured: 7.82 kPa, 2.13 ms, 24.6 ms); here 2 seeds must
/// stay within the spread those 8 seeds showed, and no base node may lift during a main shock.
#[test]
fn the_seated_paper_block_recurs_like_the_paper_without_lifting() {
    let p = Pipeline::load(&repo_path("pipelines/paper-seated.toml")).unwrap();
    let model = Model::new(p.scene.clone());
    let facts = inspect(&model, &p.seeds[..1], Statics::Full).unwrap();
    assert!(facts.slider.verdict().starts_with("stick-slip expected"), "{}", facts.slider.verdict());
    let (mut drops, mut s2, mut recurrences) = (Vec::new(), Vec::new(), Vec::new());
    for &seed in &p.seeds[..2] {
        let out = run_seed(&model, seed, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
        let cat = catalogue(&out.recording, &model, &p.analysis.events);
        let rec = &out.recording;
        let lifted = rec.get(stickslip_solver::Channel::LiftedNodes).unwrap();
        for e in cat.main_shocks() {
            drops.push(e.burst.stress_drop_pa);
            recurrences.extend(e.recurrence_s);
            if e.kind.rank() == Some(2) {
                s2.push(e.burst.duration_s());
            }
            let (a, b) = (
                rec.time_s.partition_point(|&t| t < e.burst.start_s),
                rec.time_s.partition_point(|&t| t <= e.burst.end_s),
            );
            let most = lifted[a..b].iter().fold(0.0f64, |m, &v| m.max(v));
            assert!(most == 0.0, "seed {seed}: {most} base nodes lifted during a main shock");
        }
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    println!(
        "drop {:.2} kPa, S2 {:.2} ms, recurrence {:.1} ms",
        mean(&drops) / 1e3,
        mean(&s2) * 1e3,
        mean(&recurrences) * 1e3
    );
    assert!(drops.len() >= 20, "{} main shocks in 2 seeds", drops.len());
    assert!((6.5e3..9.0e3).contains(&mean(&drops)), "mean drop {} Pa", mean(&drops));
    assert!((1.8e-3..2.5e-3).contains(&mean(&s2)), "S2 duration {} s", mean(&s2));
    assert!((22e-3..27e-3).contains(&mean(&recurrences)), "recurrence {} s", mean(&recurrences));
}
