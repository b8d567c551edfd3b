//! Whole runs: reproducibility, the random field, refusals and blow-ups.

mod common;

use std::ops::ControlFlow;

use common::{repo_path, scene_with};
use stickslip_config::{Pipeline, PipelineFile};
use stickslip_solver::scene::BoundarySpec;
use stickslip_solver::statics::critical_time_step;
use stickslip_solver::{Model, RunOptions, Scene, SolverError, run_lanes, run_seed};

fn go(_: f64) -> ControlFlow<()> {
    ControlFlow::Continue(())
}

/// The paper scene, shortened to keep the test fast.
fn short_paper(duration_s: f64) -> Scene {
    let mut file = Pipeline::load(&repo_path("pipelines/paper.toml")).unwrap().file;
    file.shear.duration_s = duration_s;
    file.scene().unwrap()
}

#[test]
fn same_seed_gives_bit_identical_series_on_any_thread_and_in_any_batch() {
    let model = Model::new(short_paper(0.03));
    let a = run_seed(&model, 123, RunOptions::default(), &mut go).unwrap();
    let b = run_seed(&model, 123, RunOptions::default(), &mut go).unwrap();
    assert_eq!(a, b, "two runs of seed 123 differ");
    // Two seeds on two threads at once, against the same seeds one after the other.
    let (c, d) = std::thread::scope(|s| {
        let h1 = s.spawn(|| run_seed(&model, 123, RunOptions::default(), &mut go).unwrap());
        let h2 = s.spawn(|| run_seed(&model, 200, RunOptions::default(), &mut go).unwrap());
        (h1.join().unwrap(), h2.join().unwrap())
    });
    assert_eq!(a, c, "seed 123 on a second thread differs");
    let e = run_seed(&model, 200, RunOptions::default(), &mut go).unwrap();
    assert_eq!(d, e, "seed 200 on a second thread differs");
    assert_ne!(a.recording, e.recording, "different seeds must differ");
    // Four seeds advanced side by side in one stepper give each seed's own numbers.
    let seeds = [123, 200, 7, 31];
    let batch = run_lanes::<4>(&model, seeds, RunOptions::default(), &mut go);
    for (seed, out) in seeds.iter().zip(batch) {
        let alone = run_seed(&model, *seed, RunOptions::default(), &mut go).unwrap();
        assert_eq!(out.unwrap(), alone, "seed {seed} in a batch of 4 differs from its own run");
    }
}

#[test]
fn weibull_field_has_mean_one_and_the_cv_asked_over_a_large_lattice() {
    for cv in [0.05, 0.2] {
        let model = Model::new(scene_with(|f| {
            f.block.nx = 40;
            f.block.ny = 20;
            f.block.nz = 20;
            f.material.young_cv = cv;
        }));
        let k = model.bar_stiffness(99).unwrap();
        let phi: Vec<f64> = k.iter().zip(model.nominal_stiffness()).map(|(a, b)| a / b).collect();
        let n = phi.len() as f64;
        let mean = phi.iter().sum::<f64>() / n;
        let sd = (phi.iter().map(|p| (p - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        println!("CV {cv}: {} bars, mean {mean:.5}, CV {:.5}", phi.len(), sd / mean);
        assert!((mean - 1.0).abs() < 0.01, "mean {mean}");
        assert!((sd / mean / cv - 1.0).abs() < 0.01, "CV {} for {cv}", sd / mean);
    }
    // CV = 0 draws nothing: the stiffness is the nominal one exactly.
    let model = Model::new(scene_with(|f| f.material.young_cv = 0.0));
    assert_eq!(model.bar_stiffness(5).unwrap(), model.nominal_stiffness());
}

#[test]
fn time_step_above_critical_is_refused_before_running() {
    let model = Model::new(scene_with(|f| f.time.dt_s = Some(1e-4)));
    let err = run_seed(&model, 1, RunOptions::default(), &mut go).unwrap_err();
    assert!(matches!(err, SolverError::TimeStepAboveCritical { .. }), "{err}");
    let msg = err.to_string();
    assert!(msg.contains("1.000000e-4 s is above the critical step"), "{msg}");
}

#[test]
fn a_run_forced_past_the_critical_step_is_stopped_with_when_and_where() {
    let probe = Model::new(scene_with(|_| {}));
    let crit = critical_time_step(&probe, &probe.bar_stiffness(3).unwrap()).unwrap().dt_s;
    let model = Model::new(scene_with(|f| f.time.dt_s = Some(1.02 * crit)));
    let options = RunOptions { allow_unstable_time_step: true, ..RunOptions::default() };
    let err = run_seed(&model, 3, options, &mut go).unwrap_err();
    let msg = err.to_string();
    println!("{msg}");
    match err {
        SolverError::Unstable { step, fraction, .. } => {
            assert!(step > 0 && step < 100_000);
            assert!((fraction - 1.02).abs() < 1e-9);
        }
        other => panic!("expected a blow-up, got {other}"),
    }
    assert!(msg.contains("went unstable at step") && msg.contains("self-weight stage"), "{msg}");
}

#[test]
fn a_blow_up_is_reported_at_the_same_step_and_node_on_one_thread_and_two() {
    let large = |f: &mut PipelineFile| {
        (f.block.nx, f.block.ny, f.block.nz) = (40, 20, 10);
        f.shear.driver_at_m = vec![[0.0, 0.0, 0.1]];
    };
    let probe = Model::new(scene_with(large));
    let crit = critical_time_step(&probe, &probe.bar_stiffness(3).unwrap()).unwrap().dt_s;
    let model = Model::new(scene_with(|f| {
        large(f);
        f.time.dt_s = Some(1.02 * crit);
    }));
    assert!(model.lattice().node_count() > 1 << 14, "more than one chunk of the parallel scan");
    let unstable = |parallel_step: bool| {
        let options = RunOptions { allow_unstable_time_step: true, parallel_step, ..RunOptions::default() };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        let err = pool.install(|| run_seed(&model, 3, options, &mut go)).unwrap_err();
        assert!(matches!(err, SolverError::Unstable { .. }), "{err}");
        err.to_string()
    };
    assert_eq!(unstable(true), unstable(false));
}

#[test]
fn the_parallel_step_of_a_large_lattice_gives_the_serial_numbers() {
    use stickslip_solver::statics::critical_step;
    use stickslip_solver::step::{Batch, LaneSetup};
    let model = Model::new(scene_with(|f| {
        (f.block.nx, f.block.ny, f.block.nz) = (40, 20, 10);
        f.shear.driver_at_m = vec![[0.0, 0.0, 0.1]];
    }));
    assert!(model.layout().splits(), "a lattice this large is cut into slabs");
    let k = model.lane_stiffness(9).unwrap();
    let dt = 0.5 * critical_step(&model, &k).unwrap().dt_s;
    let lane =
        LaneSetup { dt_s: dt, stiffness: k, friction: model.friction_factors(9).unwrap(), strength: None, fault: None };
    let run = |parallel: bool| {
        let mut s = Batch::<1>::new(&model, std::slice::from_ref(&lane).try_into().unwrap());
        s.params.set_damping(0, 2500.0);
        s.params.set_body_acceleration(0, [0.0, 0.0, -9.81]);
        s.stepper.set_parallel(parallel);
        for _ in 0..60 {
            s.step();
        }
        s.state.u.np1.clone()
    };
    let serial = run(false);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let parallel = pool.install(|| run(true));
    assert!(serial.c[2].iter().any(|v| v[0] != 0.0));
    assert_eq!(serial, parallel, "the parallel step must give the serial numbers bit for bit");
}

#[test]
fn the_skip_ahead_is_refused_with_a_boundary_its_motion_leaves_out() {
    use stickslip_solver::geometry::Face;
    use stickslip_solver::scene::LoadingPlate;
    let mut scene = short_paper(0.01);
    let lattice = scene.lattice();
    let nodes = Face::XMin.nodes(&lattice);
    scene.set_boundary(BoundarySpec::Plate(LoadingPlate {
        face: Face::XMin,
        stiffness_n_m: vec![1e6; nodes.len()],
        nodes,
    }));
    scene.skip_ahead.enabled = true;
    let err = run_seed(&Model::new(scene), 1, RunOptions::default(), &mut go).unwrap_err();
    assert!(
        matches!(&err, SolverError::Unsupported(why) if why.contains("plate")),
        "a plate with the skip-ahead is refused, naming the plate: {err}"
    );
}
