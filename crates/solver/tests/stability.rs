//! Stability stress tests: the solver pushed to the edges of its inputs ends in a physically
//! sensible result or a clear refusal, never in non-finite numbers. The quick ones run with
//! the suite; the heavy sweeps are `#[ignore]`d (run them with
//! `cargo test --release --test stability -- --ignored`).

mod common;

use std::ops::ControlFlow;

use common::scene_with;
use stickslip_config::PipelineFile;
use stickslip_solver::scene::SettleMethod;
use stickslip_solver::{Channel, Model, RunOptions, RunOutput, Scene, SolverError, run_seed};

fn run(scene: Scene, seed: u64, options: RunOptions) -> Result<RunOutput, SolverError> {
    let model = Model::new(scene);
    run_seed(&model, seed, options, &mut |_| ControlFlow::Continue(()))
}

/// Every recorded value is finite.
fn assert_finite(out: &RunOutput, what: &str) {
    for (ch, v) in &out.recording.channels {
        assert!(v.iter().all(|x| x.is_finite()), "{what}: {} has a non-finite sample", ch.name());
    }
    for (ch, v) in &out.recording.control {
        assert!(v.iter().all(|x| x.is_finite()), "{what}: control {ch:?} has a non-finite sample");
    }
}

fn short(f: &mut PipelineFile, duration: f64) {
    f.shear.duration_s = duration;
    f.record.interval_s = Some(2e-5);
    f.record.energy = true;
}

/// The critical step of seed 1 of the paper scene.
fn critical() -> f64 {
    let model = Model::new(Scene::paper());
    let k = model.bar_stiffness(1).unwrap();
    stickslip_solver::statics::critical_time_step(&model, &k).unwrap().dt_s
}

#[test]
fn below_the_critical_step_energy_stays_bounded_above_it_the_run_stops_and_says_why() {
    let crit = critical();
    for fraction in [0.5, 0.9, 0.99] {
        let scene = scene_with(|f| {
            short(f, 0.01);
            f.time.dt_fraction = Some(fraction);
            f.time.force = fraction > 0.95;
            f.record.interval_s = None;
        });
        let out = run(scene, 1, RunOptions::default()).unwrap_or_else(|e| panic!("Δt = {fraction}·critical: {e}"));
        assert_finite(&out, &format!("Δt = {fraction}"));
        let work = out.recording.get(Channel::ExternalWork).unwrap();
        let kinetic = out.recording.get(Channel::Kinetic).unwrap();
        let peak = kinetic.iter().fold(0.0f64, |m, v| m.max(*v));
        // The kinetic energy never exceeds the work put in.
        assert!(peak <= work.iter().fold(0.0f64, |m, v| m.max(*v)), "Δt = {fraction}: kinetic {peak:e} J");
    }
    for factor in [1.05, 1.5, 3.0] {
        let dt = factor * crit;
        let scene = scene_with(|f| {
            short(f, 0.01);
            f.time.dt_fraction = None;
            f.time.dt_s = Some(dt);
            f.record.interval_s = None;
        });
        // Refused before running…
        let refused = run(scene.clone(), 1, RunOptions::default()).unwrap_err();
        assert!(matches!(refused, SolverError::TimeStepAboveCritical { .. }), "{refused}");
        assert!(refused.to_string().contains("above the critical step"), "{refused}");
        // …and when forced, stopped with when and why.
        let forced = RunOptions { allow_unstable_time_step: true, ..RunOptions::default() };
        match run(scene, 1, forced).unwrap_err() {
            SolverError::Unstable { time_s, fraction, .. } => {
                assert!(time_s < 0.01 && (fraction / factor - 1.0).abs() < 1e-3, "{time_s} s, {fraction}");
            }
            e => panic!("Δt = {factor}·critical: expected a blow-up, got {e}"),
        }
    }
}

#[test]
fn a_modulus_field_from_homogeneous_to_fifty_percent_spread_runs_and_stiffens_the_step() {
    let mut criticals = Vec::new();
    for cv in [0.0, 0.1, 0.25, 0.5] {
        let scene = scene_with(|f| {
            short(f, 0.02);
            f.material.young_cv = cv;
        });
        let out = run(scene, 5, RunOptions::default()).unwrap_or_else(|e| panic!("CV {cv}: {e}"));
        assert_finite(&out, &format!("CV {cv}"));
        criticals.push(out.critical.dt_s);
    }
    // The stiffest bar of a wider field is stiffer: the critical step shrinks.
    assert!(criticals.windows(2).all(|w| w[1] < w[0]), "{criticals:?}");
}

#[test]
fn friction_from_zero_to_one_hundred() {
    for mu in [0.0, 0.3, 5.0, 100.0] {
        let scene = scene_with(|f| {
            short(f, 0.03);
            f.friction.mu_static = mu;
            f.self_weight.method = SettleMethod::Static.name().into();
        });
        let out = run(scene, 2, RunOptions::default()).unwrap_or_else(|e| panic!("μ = {mu}: {e}"));
        assert_finite(&out, &format!("μ = {mu}"));
        let slipping = out.recording.get(Channel::SlippingNodes).unwrap();
        let tau = out.recording.get(Channel::ShearStress).unwrap();
        let sigma = out.recording.get(Channel::NormalStress).unwrap();
        match mu {
            // No friction: nothing resists, every node in contact slides.
            0.0 => assert!(tau.iter().all(|t| t.abs() < 1e-6 * sigma[0]), "μ = 0 but τ ≠ 0"),
            // Far above the stress ratio of the block: it does not slide (a node whose normal
            // reaction passes through zero as it lifts may slip an instant, and lifted nodes move
            // with the block: the mean base displacement stays under 1% of the driver's).
            100.0 => {
                let slip = out.recording.get(Channel::MeanSlip).unwrap();
                let driver = out.recording.get(Channel::DriverDisplacement).unwrap();
                let (d, u) = (slip.iter().fold(0.0f64, |m, v| m.max(v.abs())), driver[driver.len() - 1]);
                let most = slipping.iter().fold(0.0f64, |m, &v| m.max(v));
                assert!(
                    d < 1e-2 * u,
                    "μ = 100 but the base slipped {d} m of the driver's {u} m ({most} nodes at once)"
                );
            }
            // In between τ never exceeds μ·σ.
            _ => {
                for (t, s) in tau.iter().zip(sigma) {
                    assert!(*t <= mu * s * (1.0 + 1e-9), "τ = {t} > μσ = {}", mu * s);
                }
            }
        }
    }
}

#[test]
fn without_damping_the_energy_balance_holds_over_a_long_run() {
    // Static start (no settling damping needed), no damping in shear, no slip (μ = 100): the
    // driver's work goes into kinetic and strain energy and stays there.
    let scene = scene_with(|f| {
        f.self_weight.method = SettleMethod::Static.name().into();
        f.shear.damping_per_s = 0.0;
        f.friction.mu_static = 100.0;
        f.shear.duration_s = 0.5;
        f.record.interval_s = Some(1e-4);
        f.record.energy = true;
    });
    let out = run(scene, 3, RunOptions::default()).unwrap();
    assert!(out.steps() > 40_000, "{} steps", out.steps());
    assert_finite(&out, "D = 0");
    let work = out.recording.get(Channel::ExternalWork).unwrap();
    let residual = out.recording.get(Channel::EnergyResidual).unwrap();
    let damping = out.recording.get(Channel::DampingDissipated).unwrap();
    let scale = work.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let drift = residual.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    // Bound: 1e-9 of the work, about what round-off over 50 000 steps allows.
    assert!(drift < 1e-9 * scale, "energy drift {drift:e} J of {scale:e} J");
    assert!(damping.iter().all(|&d| d == 0.0), "damping dissipated energy with D = 0");
    // The vibration the ramp started is not damped, and does not grow either: the kinetic
    // energy of the last fifth stays within twice its peak of the second fifth.
    let kinetic = out.recording.get(Channel::Kinetic).unwrap();
    let n = kinetic.len();
    let peak = |a: usize, b: usize| kinetic[a..b].iter().fold(0.0f64, |m, v| m.max(*v));
    let (early, late) = (peak(n / 5, 2 * n / 5), peak(4 * n / 5, n));
    assert!(early > 0.0 && late < 2.0 * early, "kinetic peaks {early:e} J then {late:e} J");
}

#[test]
fn poisson_ratio_up_to_045() {
    let mut criticals = Vec::new();
    for nu in [0.05, 0.25, 0.45] {
        let scene = scene_with(|f| {
            short(f, 0.02);
            f.material.poisson = nu;
        });
        let out = run(scene, 4, RunOptions::default()).unwrap_or_else(|e| panic!("ν = {nu}: {e}"));
        assert_finite(&out, &format!("ν = {nu}"));
        criticals.push(out.critical.dt_s);
    }
    // The diagonals stiffen as ν → 0.5 (δ = 9ν/(4−8ν)): the step shrinks.
    assert!(criticals.windows(2).all(|w| w[1] < w[0]), "{criticals:?}");
}

/// The paper scene with every length multiplied by `s` and everything else scaled so that the
/// problem is the same in dimensionless form: times × s, velocities unchanged, accelerations
/// (gravity) and damping rates ÷ s.
fn scaled(s: f64) -> Scene {
    scene_with(|f| {
        f.block.lc_m *= s;
        f.self_weight.gravity_m_s2 /= s;
        f.self_weight.damping_per_s /= s;
        f.self_weight.max_duration_s *= s;
        f.self_weight.method = SettleMethod::Static.name().into();
        f.shear.damping_per_s /= s;
        f.shear.rise_time_s *= s;
        // Up to the first slip event: after it, round-off differences grow chaotically.
        f.shear.duration_s = 0.05 * s;
        f.shear.driver_at_m = vec![[0.0, 0.0, 0.2 * s]];
        f.record.interval_s = Some(2e-5 * s);
    })
}

#[test]
fn the_same_problem_at_one_millimetre_and_one_hundred_metres_gives_the_same_numbers() {
    let base = run(scaled(1.0), 9, RunOptions::default()).unwrap();
    for s in [0.01, 1000.0] {
        let out = run(scaled(s), 9, RunOptions::default()).unwrap();
        assert_eq!(out.steps(), base.steps(), "Lc = {} m", 0.1 * s);
        assert!((out.dt_s / (s * base.dt_s) - 1.0).abs() < 1e-9);
        // Stresses are the same (σ = ρ·g·h with g·h fixed), displacements scale with s.
        for (ch, unit) in [(Channel::ShearStress, 1.0), (Channel::NormalStress, 1.0), (Channel::MeanSlip, s)] {
            let (a, b) = (base.recording.get(ch).unwrap(), out.recording.get(ch).unwrap());
            let level = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let worst = a.iter().zip(b).map(|(x, y)| (x - y / unit).abs()).fold(0.0, f64::max);
            assert!(worst < 1e-9 * level, "Lc = {} m: {} differs by {worst:e} of {level:e}", 0.1 * s, ch.name());
        }
    }
}

/// Heavy: Δt from 0.1 to 1.0 of critical over the paper's whole shear stage, all finite.
#[test]
#[ignore]
fn heavy_time_step_sweep_over_the_whole_run() {
    for k in 1..=10 {
        let fraction = f64::from(k) / 10.0;
        let scene = scene_with(|f| {
            f.time.dt_fraction = Some(fraction);
            f.record.interval_s = None;
            f.record.energy = true;
        });
        let out = run(scene, 11, RunOptions::default()).unwrap_or_else(|e| panic!("Δt = {fraction}: {e}"));
        assert_finite(&out, &format!("Δt = {fraction}"));
    }
}

/// Heavy: CV and μ grids over the whole shear stage.
#[test]
#[ignore]
fn heavy_field_and_friction_grid() {
    for cv in [0.0, 0.05, 0.2, 0.5, 1.0] {
        for mu in [0.1, 1.0, 5.0, 20.0, 100.0] {
            let scene = scene_with(|f| {
                f.material.young_cv = cv;
                f.friction.mu_static = mu;
                f.friction.mu_cv = 0.2;
            });
            let out = run(scene, 12, RunOptions::default()).unwrap_or_else(|e| panic!("CV {cv}, μ {mu}: {e}"));
            assert_finite(&out, &format!("CV {cv}, μ {mu}"));
        }
    }
}

/// Heavy: the largest lattice that fits comfortably (about 2.9 million bars, 1.5 GB), a
/// hundred steps of shear with the parallel step.
#[test]
#[ignore]
fn heavy_largest_lattice() {
    let scene = scene_with(|f| {
        f.block.nx = 200;
        f.block.ny = 20;
        f.block.nz = 50;
        f.self_weight.method = SettleMethod::Static.name().into();
        f.shear.duration_s = 100.0 * 1.0e-5;
        f.record.interval_s = None;
    });
    let model = Model::new(scene);
    assert!(model.bar_count() > 2_000_000, "{} bars", model.bar_count());
    let options = RunOptions { parallel_step: true, ..RunOptions::default() };
    let out = run_seed(&model, 13, options, &mut |_| ControlFlow::Continue(())).unwrap();
    assert_finite(&out, "largest lattice");
}
