//! Sliding is not read as earthquakes (issue: "a diagnosis that mistakes sliding for
//! earthquakes"): three scenes that slide stably catalogue no main shock in any seed, their runs
//! are diagnosed as stable sliding, and `stickslip check`'s spring-slider reading does not expect
//! stick-slip of them; the shipped plate scene, which does stick and slip, keeps its events.
//!
//! The three scenes: (A) a 20×2×6 block with μs 0.6 / μd 0.45 under the rigid driver node of
//! `paper.toml` (τ levels at μd·σ, δ grows linearly); (B) `plate-stickslip.toml` with the paper's
//! 400 1/s damping; (C) `plate-stickslip.toml` on 10¹⁵ N/m springs. Before, B gave a "main shock"
//! S1 of 1.05 kPa lasting 233 ms in every seed, C one lasting the whole run, and A no event with
//! the advice to run longer while `check` expected stick-slip.

use std::ops::ControlFlow;

use stickslip_analysis::events::{FOLLOWS, SlipRegime, catalogue, diagnose};
use stickslip_config::{Pipeline, PipelineFile};
use stickslip_solver::inspect::{Regime, Statics, inspect};
use stickslip_solver::{Model, RunOptions, run_seed};
use stickslip_support::repo_path;

fn plate() -> PipelineFile {
    Pipeline::load(&repo_path("pipelines/plate-stickslip.toml")).unwrap().file
}

/// Runs `seeds` of `file` and returns each seed's main shocks, regime, sliding onset and how
/// closely the base followed its loading.
fn runs(file: &PipelineFile, seeds: &[u64]) -> Vec<(u64, usize, SlipRegime, Option<f64>, f64)> {
    let p = Pipeline::from_file(file.clone(), "case").unwrap();
    let model = Model::new(p.scene.clone());
    seeds
        .iter()
        .map(|&seed| {
            let out = run_seed(&model, seed, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
            let cat = catalogue(&out.recording, &model, &p.analysis.events);
            let d = diagnose(&out.recording, &cat, &model);
            (seed, cat.main_shocks().count(), d.regime, d.sliding_from_s, d.followed)
        })
        .collect()
}

fn check_regime(file: &PipelineFile) -> Regime {
    let p = Pipeline::from_file(file.clone(), "case").unwrap();
    let model = Model::new(p.scene.clone());
    inspect(&model, &p.seeds[..1], Statics::Full).unwrap().slider.regime()
}

#[test]
fn a_plate_scene_damped_at_400_per_second_slides_and_catalogues_no_main_shock() {
    let mut file = plate();
    file.shear.damping_per_s = 400.0;
    file.shear.duration_s = 0.15;
    assert_eq!(check_regime(&file), Regime::Overdamped);
    for (seed, mains, regime, from, followed) in runs(&file, &[1, 2, 3]) {
        assert_eq!(mains, 0, "seed {seed}: sliding catalogued as a main shock");
        assert_eq!(regime, SlipRegime::StableSliding, "seed {seed}");
        // It lets go about 67 ms into the stage (0.3-s runs) and slides with the plate after.
        let from = from.expect("a slip that never stops");
        assert!((0.05..0.09).contains(&from), "seed {seed}: sliding from {from} s");
        assert!((0.8..1.2).contains(&followed), "seed {seed}: the base slipped {followed:.2} of the plate's travel");
    }
}

/// The plate slides from the start, so no stuck stretch gives a loading rate: the slip that never
/// stops is read as sliding because the plate moves (a fault under fixed tractions keeps its
/// unfinished rupture as an event).
#[test]
fn a_plate_scene_on_stiff_springs_slides_from_the_start_and_catalogues_nothing() {
    let mut file = plate();
    file.loading_plate.as_mut().unwrap().stiffness_n_m = Some(1e15);
    file.shear.duration_s = 0.04;
    assert_eq!(check_regime(&file), Regime::Overdamped);
    for (seed, mains, regime, from, _) in runs(&file, &[1, 2]) {
        assert_eq!(mains, 0, "seed {seed}: sliding catalogued as a main shock");
        assert_eq!(regime, SlipRegime::StableSliding, "seed {seed}");
        assert!(from.expect("a slip that never stops") < 0.005, "seed {seed}: sliding from {from:?} s");
    }
}

#[test]
fn a_bigger_block_with_rock_friction_under_a_rigid_driver_slides_and_check_does_not_expect_stick_slip() {
    let mut file = Pipeline::load(&repo_path("pipelines/paper.toml")).unwrap().file;
    (file.block.nx, file.block.ny, file.block.nz) = (20, 2, 6);
    file.friction.mu_static = 0.6;
    file.friction.mu_dynamic = Some(0.45);
    file.spectra = None;
    file.accelerograms = None;
    file.record.control.clear();
    // The rigid-slider reading alone expected stick-slip; the lattice lets its base go at
    // 0.76–0.79·μs·N here (8 seeds), below the 0.78 stick-slip needs: marginal, not stick-slip.
    let regime = check_regime(&file);
    assert!(matches!(regime, Regime::Marginal | Regime::LetsGoEarly), "check: {regime:?}");
    for (seed, mains, regime, _, followed) in runs(&file, &[1, 2, 3]) {
        assert_eq!(mains, 0, "seed {seed}");
        assert_eq!(regime, SlipRegime::StableSliding, "seed {seed}: the base slipped {followed:.2} of the travel");
        assert!(followed >= FOLLOWS, "seed {seed}");
    }
}

#[test]
fn the_shipped_plate_scene_still_sticks_and_slips() {
    let file = plate();
    assert_eq!(check_regime(&file), Regime::StickSlip);
    for (seed, mains, regime, from, _) in runs(&file, &[1, 2]) {
        assert!(mains >= 4, "seed {seed}: {mains} main shocks");
        assert_eq!(regime, SlipRegime::StickSlip, "seed {seed}");
        assert!(from.is_none(), "seed {seed}: sliding from {from:?}");
    }
}
