//! Skipping what a scene does not need: the static self-weight start and the quasi-static
//! skip-ahead, each against the explicit integration it replaces.

mod common;

use std::ops::ControlFlow;

use common::scene_with;
use stickslip_config::PipelineFile;
use stickslip_config::scene::ControlSection;
use stickslip_solver::recording::Transition;
use stickslip_solver::scene::SettleMethod;
use stickslip_solver::{Channel, Model, RunOptions, RunOutput, Scene, run_seed};

fn run(scene: Scene, seed: u64, options: RunOptions) -> RunOutput {
    let model = Model::new(scene);
    run_seed(&model, seed, options, &mut |_| ControlFlow::Continue(())).unwrap()
}

/// The paper scene, short, recording the displacement of every surface node.
fn settle_scene(method: SettleMethod) -> Scene {
    scene_with(|f| {
        f.self_weight.method = method.name().into();
        f.shear.duration_s = 0.004;
        f.record.energy = true;
        f.record.control = vec![ControlSection {
            nodes: vec![],
            at_m: vec![],
            set: Some("surface".into()),
            quantities: vec!["displacement".into()],
            components: vec!["x".into(), "y".into(), "z".into()],
        }];
    })
}

#[test]
fn static_self_weight_reaches_the_state_damped_settling_converges_to() {
    let dynamic = run(settle_scene(SettleMethod::Dynamic), 123, RunOptions::default());
    let fixed = run(settle_scene(SettleMethod::Static), 123, RunOptions::default());
    assert_eq!(dynamic.settled_by, SettleMethod::Dynamic);
    assert_eq!(fixed.settled_by, SettleMethod::Static);
    assert_eq!(fixed.settle_steps, 0);
    assert!(dynamic.settle_steps > 500, "{} settle steps", dynamic.settle_steps);
    // Displacements of every surface node at the start of shearing: the dynamic run stopped
    // at an out-of-balance force of 1e-6 of the weight, so they agree to about that.
    let (mut diff, mut scale): (f64, f64) = (0.0, 0.0);
    for ((ca, a), (cb, b)) in dynamic.recording.control.iter().zip(&fixed.recording.control) {
        assert_eq!(ca, cb);
        diff = diff.max((a[0] - b[0]).abs());
        scale = scale.max(b[0].abs());
    }
    assert!(scale > 1e-7, "the block sags under its weight ({scale:e} m)");
    assert!(diff < 1e-4 * scale, "surface displacements differ by {diff:e} m of {scale:e} m");
    // The base carries the weight in both.
    let sigma = |o: &RunOutput| o.recording.get(Channel::NormalStress).unwrap()[0];
    assert!((sigma(&dynamic) / sigma(&fixed) - 1.0).abs() < 1e-4, "{} vs {}", sigma(&dynamic), sigma(&fixed));
    // Starting at rest in equilibrium keeps the energy balance closed: gravity's work so far is
    // the strain energy.
    let residual = fixed.recording.get(Channel::EnergyResidual).unwrap();
    let work = fixed.recording.get(Channel::ExternalWork).unwrap();
    let worst = residual.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    assert!(worst < 1e-9 * work[work.len() - 1].abs(), "energy residual {worst:e} J");
}

#[test]
fn static_self_weight_that_friction_cannot_hold_falls_back_to_settling() {
    // Without friction the base cannot hold the Poisson spreading of the loaded block.
    let scene = scene_with(|f| {
        f.self_weight.method = SettleMethod::Static.name().into();
        f.friction.mu_static = 0.0;
        f.shear.duration_s = 0.001;
        f.shear.velocity_m_s = 1e-9; // a driver at rest is refused; this one does not move in 1 ms
    });
    let out = run(scene, 1, RunOptions::default());
    assert_eq!(out.settled_by, SettleMethod::Dynamic);
    let note = out.settle_note.expect("a reason");
    assert!(note.contains("friction would not hold base node"), "{note}");
}

/// The paper block loaded 100 times slower, with a dynamic friction below the static one.
fn slow_file() -> PipelineFile {
    let mut f = PipelineFile::default();
    f.friction.mu_dynamic = Some(4.5);
    f.shear.velocity_m_s = 1.1e-6;
    f.record.interval_s = Some(1e-4);
    f.record.energy = true;
    f.record.slip_onsets = true;
    f.skip_ahead.enabled = true;
    f
}

#[test]
fn a_jump_lands_where_integrating_through_it_goes() {
    let mut file = slow_file();
    file.shear.duration_s = 2.0;
    let first = run(file.clone().scene().unwrap(), 123, RunOptions::default());
    let jump = first.recording.skips[0];
    assert!(matches!(jump.next, Transition::Slide(_)), "{jump:?}");
    assert!(jump.steps > 10_000, "{jump:?}");
    // The same run up to shortly after the jump, once integrating through it.
    file.shear.duration_s = jump.to_s + 0.02;
    let scene = file.scene().unwrap();
    let skipped = run(scene.clone(), 123, RunOptions { max_jumps: Some(1), ..RunOptions::default() });
    let integrated = run(scene, 123, RunOptions { max_jumps: Some(0), ..RunOptions::default() });
    assert_eq!(skipped.recording.skips.len(), 1);
    assert!(integrated.recording.skips.is_empty());
    // The predicted transition happens at the same step either way.
    let onset = |o: &RunOutput| o.recording.onsets.iter().map(|&(t, _)| t).find(|&t| t > jump.from_s);
    let (a, b) = (onset(&integrated).expect("an onset"), onset(&skipped).expect("an onset"));
    assert!((a - b).abs() <= skipped.dt_s * 0.5, "onsets {a} and {b}");
    assert!(b > jump.to_s, "the onset {b} comes after the jump's end {}", jump.to_s);
    // Same instants, and the shear stress agrees along the whole run to a part in 10⁶ of the
    // stress level (the leftover motion of the first loading decayed long before the jump).
    assert_eq!(integrated.recording.time_s, skipped.recording.time_s);
    let (ta, tb) =
        (integrated.recording.get(Channel::ShearStress).unwrap(), skipped.recording.get(Channel::ShearStress).unwrap());
    let level = ta.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let worst = ta.iter().zip(tb).map(|(x, y)| (x - y).abs()).fold(0.0, f64::max);
    assert!(worst < 1e-6 * level, "τ differs by {worst:e} Pa of {level:e} Pa");
    // So do the energy terms, and the balance stays closed across the jump.
    for ch in [Channel::Elastic, Channel::DriverWork, Channel::BodyWork] {
        let (x, y) = (integrated.recording.get(ch).unwrap(), skipped.recording.get(ch).unwrap());
        let (x, y) = (x[x.len() - 1], y[y.len() - 1]);
        assert!((x - y).abs() < 1e-6 * x.abs().max(1e-12), "{}: {x:e} vs {y:e}", ch.name());
    }
    let work = skipped.recording.get(Channel::ExternalWork).unwrap();
    let residual = skipped.recording.get(Channel::EnergyResidual).unwrap();
    let worst = residual.iter().fold(0.0f64, |m, r| m.max(r.abs()));
    assert!(worst < 1e-6 * work[work.len() - 1].abs(), "energy residual {worst:e} J");
}

#[test]
fn slow_loading_is_mostly_skipped_and_sampled_sparsely_when_asked() {
    let mut file = slow_file();
    file.shear.duration_s = 5.0;
    file.record.energy = false;
    file.skip_ahead.record_interval_s = Some(0.01);
    let out = run(file.scene().unwrap(), 7, RunOptions::default());
    let fraction = out.skip.skipped_steps as f64 / out.shear_steps as f64;
    assert!(fraction > 0.8, "only {:.1}% of the steps skipped", 100.0 * fraction);
    assert_eq!(out.skip.jumps as usize, out.recording.skips.len());
    let skipped: u64 = out.recording.skips.iter().map(|s| s.steps).sum();
    assert_eq!(skipped, out.skip.skipped_steps);
    // Inside a jump, one sample per 0.01 s; outside, one per 1e-4 s (each the nearest whole
    // number of steps: 100 times the stride outside).
    let t = &out.recording.time_s;
    let stride = (1e-4 / out.dt_s).round() as u64;
    let sparse = 100 * stride;
    let every = sparse as f64 * out.dt_s;
    assert!((every / 0.01 - 1.0).abs() < 0.05, "{every} s between samples in a jump");
    let long = out.recording.skips.iter().max_by_key(|s| s.steps).unwrap();
    let inside: Vec<f64> = t.iter().copied().filter(|&x| x > long.from_s + 0.02 && x < long.to_s - 0.02).collect();
    for w in inside.windows(2) {
        assert!((w[1] - w[0] - every).abs() < 1e-9, "spacing {} inside a jump", w[1] - w[0]);
    }
    let steps_outside = out.shear_steps - out.skip.skipped_steps;
    let bound = steps_outside / stride + out.recording.skips.iter().map(|s| s.steps / sparse + 1).sum::<u64>() + 2;
    assert!(t.len() as u64 <= bound, "{} samples, expected at most {bound}", t.len());
    assert!((t.len() as u64) < out.shear_steps / stride / 4, "{} samples: not sparse", t.len());
    // No NaN anywhere, and the slip rate sampled inside jumps is the quasi-static one.
    for (ch, v) in &out.recording.channels {
        assert!(v.iter().all(|x| x.is_finite()), "{} has a non-finite sample", ch.name());
    }
}

#[test]
fn skip_ahead_runs_one_seed_per_stepper_and_stays_reproducible() {
    let mut file = slow_file();
    file.shear.duration_s = 1.0;
    let model = Model::new(file.scene().unwrap());
    let seeds = [3, 4, 5, 6, 7, 8, 9, 10, 11];
    let batch =
        stickslip_solver::run_batched(&model, &seeds, RunOptions::default(), &mut |_| ControlFlow::Continue(()));
    for (seed, out) in seeds.iter().zip(batch) {
        let alone = run_seed(&model, *seed, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
        let out = out.unwrap();
        assert!(out.skip.jumps > 0, "seed {seed} made no jump");
        assert_eq!(out, alone, "seed {seed}");
    }
}
