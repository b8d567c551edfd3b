//! A scene split over ranks steps to the same bits as on one process (docs/model.md §19): every
//! owned node's three time levels, compared bit for bit after a few hundred steps, for 2, 3 and 4
//! ranks (threads trading halos over channels), on the paper's block grown to a stencil lattice
//! (gravity, friction on the base, a driver, a Weibull field on E, rollers) and on TPV5 at 500 m
//! (a slip-weakening fault as the base, absorbing faces, a rupture under way), the latter also in
//! a layered crust with a Q (on 2 and 3 ranks).

mod common;

use std::ops::ControlFlow;

use stickslip_solver::field::Field;
use stickslip_solver::run::{RankPart, run_split};
use stickslip_solver::split::{Halo, Partition, thread_ranks};
use stickslip_solver::statics::critical_step;
use stickslip_solver::step::{Batch, LaneSetup, start_drivers};
use stickslip_solver::{Checkpoint, Model, RunOptions, RunOutput, Scene, SolverError, run_seed};

/// The set-up of seed `seed` on `model`, with the time step `dt_s` of the whole block.
fn setup(model: &Model, seed: u64, dt_s: f64) -> LaneSetup {
    LaneSetup {
        dt_s,
        stiffness: model.lane_stiffness(seed).unwrap(),
        friction: model.friction_factors(seed).unwrap(),
        strength: None,
        fault: model.fault_loads(seed).unwrap(),
    }
}

/// A smooth start that moves every node differently (so every bar works from the first step).
fn start(p: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let w = |p: [f64; 3], s: f64| 1e-6 * ((0.37 * p[0] + 0.11 * s).sin() + (0.23 * p[1] - 0.7 * p[2]).cos());
    let u0 = [w(p, 0.0), w(p, 1.0), w(p, 2.0)];
    let u1 = [w(p, 0.1), w(p, 1.1), w(p, 2.1)];
    (u0, u1)
}

/// What a batch does on every rank before stepping: damping, gravity, drivers on.
fn prepare(batch: &mut Batch<'_, 1>, gravity: f64) {
    batch.params.set_damping(0, 50.0);
    batch.params.set_body_acceleration(0, [0.0, 0.0, -gravity]);
    batch.initialize(0, start);
    start_drivers(batch.params.model, &mut batch.state, 0);
}

/// The three levels of every node after `steps` steps on one process (internal order).
fn single(scene: &Scene, seed: u64, steps: usize, gravity: f64) -> (f64, [Field<1>; 3]) {
    let model = Model::new(scene.clone());
    let lane = setup(&model, seed, 1.0);
    let dt = 0.5 * critical_step(&model, &lane.stiffness).unwrap().dt_s;
    let mut batch = Batch::new(&model, &[LaneSetup { dt_s: dt, ..lane }]);
    prepare(&mut batch, gravity);
    for _ in 0..steps {
        batch.step();
    }
    let u = batch.state.u;
    (dt, [u.nm1, u.n, u.np1])
}

/// The same split over `ranks` ranks, each a thread; checks every owned node against `whole`.
fn split_agrees(scene: &Scene, seed: u64, steps: usize, gravity: f64, dt: f64, whole: &[Field<1>; 3], ranks: usize) {
    let partition = Partition::new(scene.dims, ranks).unwrap();
    let links = thread_ranks(ranks);
    std::thread::scope(|s| {
        for (r, mut link) in links.into_iter().enumerate() {
            let window = partition.window(r);
            let scene = scene.clone();
            s.spawn(move || {
                let model = Model::window(scene, window.clone());
                let mut batch = Batch::new(&model, &[setup(&model, seed, dt)]);
                prepare(&mut batch, gravity);
                let mut halo = Halo::default();
                for _ in 0..steps {
                    batch.step();
                    halo.exchange(&window, &mut batch.state.u.np1, &mut link);
                }
                let u = &batch.state.u;
                for (level, (mine, theirs)) in [&u.nm1, &u.n, &u.np1].into_iter().zip(whole).enumerate() {
                    for i in window.owned.clone() {
                        let g = window.global(i);
                        for c in 0..3 {
                            let (a, b) = (mine.c[c][i][0], theirs.c[c][g][0]);
                            assert!(
                                a.to_bits() == b.to_bits(),
                                "{ranks} ranks, rank {r}: level {level}, node {g}, component {c}: {a:e} against {b:e} on one process"
                            );
                        }
                    }
                }
            });
        }
    });
}

/// The paper's block grown to 14 × 3 × 13 modules: gravity, the Coulomb base, the driver at
/// (0, 0, 0.2) m, E with its 5% Weibull field.
#[test]
fn the_paper_block_split_over_ranks_gives_the_same_bits() {
    let scene = common::scene_with(|f| {
        f.block.nx = 14;
        f.block.ny = 3;
        f.block.nz = 13;
    });
    assert!(scene.young_cv > 0.0 && !scene.drivers().is_empty());
    let steps = 400;
    let (dt, whole) = single(&scene, 7, steps, 9.81);
    // Something happened: the base slid or the block moved by more than the start.
    let moved = whole[2].c[2].iter().map(|v| v[0].abs()).fold(0.0, f64::max);
    assert!(moved > 1e-6, "the block moves ({moved:e} m)");
    for ranks in [2, 3, 4] {
        split_agrees(&scene, 7, steps, 9.81, dt, &whole, ranks);
    }
}

/// TPV5 at 500 m (100 × 50 × 40 modules): the rupture starts at the nucleation patch of rank 0's
/// base and its waves cross the cuts.
#[test]
fn tpv5_split_over_ranks_gives_the_same_bits() {
    let scene = common::pipeline("pipelines/tpv5-500m.toml").scene;
    let steps = 120;
    let (dt, whole) = single(&scene, 1, steps, 0.0);
    // The waves have crossed the first cut (layer 10 of 40 for four ranks): the nodes there move.
    let model = Model::with_stencil(scene.clone());
    let cut = Partition::new(scene.dims, 4).unwrap().owned_layers(1).start;
    let lattice = model.lattice();
    let moving = (0..model.node_count())
        .filter(|&i| (lattice.position(model.canonical(i))[2] / scene.lc_m).round() as usize == cut)
        .any(|i| (whole[2].c[0][i][0] - whole[1].c[0][i][0]).abs() > 0.0);
    assert!(moving, "the rupture's waves reach layer {cut} in {steps} steps");
    for ranks in [2, 3, 4] {
        split_agrees(&scene, 1, steps, 0.0, dt, &whole, ranks);
    }
}

/// TPV5 at 500 m in scenario-m6-crust's medium (its layers by depth and Qs = 50·Vs, four memory
/// variables per bar added in the stencil kernel): each window's zones and memory variables give
/// the one process's bits.
#[test]
fn a_layered_attenuating_medium_split_over_ranks_gives_the_same_bits() {
    let plain = common::pipeline("pipelines/tpv5-500m.toml").scene;
    let mut scene = plain.clone();
    scene.medium = common::pipeline("pipelines/scenario-m6-crust.toml").scene.medium;
    assert!(scene.medium.attenuation.is_some() && scene.medium.is_dissipative());
    let steps = 60;
    let (dt, whole) = single(&scene, 1, steps, 0.0);
    // The medium changes the motion (so the comparison below covers its terms).
    let (_, elastic) = single(&plain, 1, steps, 0.0);
    assert!(whole[2].c[0].iter().zip(&elastic[2].c[0]).any(|(a, b)| a != b), "the medium changes the motion");
    for ranks in [2, 3] {
        split_agrees(&scene, 1, steps, 0.0, dt, &whole, ranks);
    }
}

#[test]
fn partitions_cover_the_block_and_refuse_thin_slabs() {
    // A block whose bars are listed (a rank owns one layer or more) and a stencil (two or more).
    for (nxy, least) in [(4, 1), (50, 2)] {
        for nz in [4, 5, 13, 40, 41, 97] {
            let dims = stickslip_solver::Dims::new(nxy, nxy, nz);
            assert_eq!(dims.bar_count() < stickslip_solver::model::STENCIL_MIN_BARS, least == 1);
            let most = (1..=nz).take_while(|&r| Partition::new(dims, r).is_ok()).last().unwrap();
            assert_eq!(most, (nz / least).max(1), "{nz} layers split over {most} ranks at most");
            for ranks in 1..=most {
                let p = Partition::new(dims, ranks).unwrap();
                let mut next = 0;
                for r in 0..ranks {
                    let owned = p.owned_layers(r);
                    assert_eq!(owned.start, next);
                    assert!(owned.len() >= least || ranks == 1, "{ranks} ranks: rank {r} owns {owned:?}");
                    next = owned.end;
                    let w = p.window(r);
                    assert_eq!(w.nodes, w.halo_below().len() + w.owned.len() + w.halo_above().len());
                }
                assert_eq!(next, nz);
            }
            let e = Partition::new(dims, most + 1).unwrap_err();
            assert!(e.to_string().contains(&format!("1 to {most} ranks")), "{e}");
        }
    }
    let dims = stickslip_solver::Dims::new(4, 4, 40);
    assert!(Partition::new(dims, 0).is_err());
}

/// `each(rank, model, partition, link)` on `ranks` threads as ranks of `scene` split over them
/// (each with its window's model): every rank's result, in rank order.
fn on_thread_ranks<T: Send>(
    scene: &Scene,
    ranks: usize,
    each: impl Fn(usize, &Model, &Partition, &mut stickslip_solver::split::ThreadRanks) -> T + Sync,
) -> Vec<T> {
    let partition = Partition::new(scene.dims, ranks).unwrap();
    let links = thread_ranks(ranks);
    std::thread::scope(|s| {
        let handles: Vec<_> = links
            .into_iter()
            .enumerate()
            .map(|(r, mut link)| {
                let (scene, partition, each) = (scene.clone(), partition.clone(), &each);
                s.spawn(move || {
                    let model = Model::window(scene, partition.window(r));
                    each(r, &model, &partition, &mut link)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    })
}

/// A seed run on `ranks` threads as ranks of a split scene: rank 0's output.
fn run_split_threads(scene: &Scene, seed: u64, ranks: usize) -> Result<RunOutput, SolverError> {
    run_split_checkpointed(scene, seed, ranks, None, None)
}

/// [`run_split_threads`], each rank keeping its checkpoint in `folder` (when given), rank 0
/// asking to stop at its `stop_at`-th progress report (when given).
fn run_split_checkpointed(
    scene: &Scene,
    seed: u64,
    ranks: usize,
    folder: Option<&std::path::Path>,
    stop_at: Option<usize>,
) -> Result<RunOutput, SolverError> {
    let mut outs = on_thread_ranks(scene, ranks, |r, model, partition, link| {
        let checkpoint = folder
            .map(|f| Checkpoint::new(f.join(format!("rank-{r}-of-{ranks}.ckpt")), None, Some(1 << 30), "test".into()));
        let mut reports = 0;
        let mut progress = |_| {
            reports += 1;
            if Some(reports) == stop_at { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
        };
        let part = RankPart { model, partition };
        run_split(part, seed, RunOptions::default(), &mut progress, link, checkpoint.as_ref())
    });
    assert!(
        outs[1..].iter().all(|o| o.as_ref().is_none_or(Result::is_err)),
        "only rank 0 has the output; the others have nothing, or their error"
    );
    outs.swap_remove(0).expect("rank 0's output")
}

/// TPV5 at 500 m for 3 s of its rupture, with its energy ledger: rank 0's output (the recording of
/// the fault, the interface and energy series, the stations spread over every rank, the critical
/// step, the steps) is the one process's, printed with every digit, on 2, 3 and 4 ranks.
#[test]
fn a_split_run_of_tpv5_gives_the_one_process_output() {
    let mut scene = common::pipeline("pipelines/tpv5-500m.toml").scene;
    scene.shear.duration_s = 3.0;
    scene.record.energy = true;
    assert!(!scene.record.control.is_empty());
    let one =
        run_seed(&Model::new(scene.clone()), 1, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    assert!(one.recording.len() > 100 && one.recording.control.iter().any(|(_, v)| v.iter().any(|&x| x != 0.0)));
    let want = format!("{one:?}");
    for ranks in [2, 3, 4] {
        let split = run_split_threads(&scene, 1, ranks).unwrap();
        assert!(format!("{split:?}") == want, "{ranks} ranks: the output differs from one process's");
    }
}

/// The 2.8 M-bar block (its loading plate on the top rank, stations added on three ranks), with
/// and without its energy ledger: the same output on 2 ranks.
#[test]
fn a_split_run_of_the_large_block_gives_the_one_process_output() {
    use stickslip_solver::scene::{Component, ControlChannel, Kinematic};
    let mut scene = common::pipeline("pipelines/large-block.toml").scene;
    scene.shear.duration_s = 0.002;
    scene.record.energy = false;
    let lattice = scene.lattice();
    for z in [0.4, 1.0, 1.8] {
        let node = lattice.node_at([10.0, 2.5, z]).unwrap();
        for quantity in [Kinematic::Displacement, Kinematic::Acceleration] {
            scene.record.control.push(ControlChannel { node, quantity, component: Component::X });
        }
    }
    let one =
        run_seed(&Model::new(scene.clone()), 1, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    let split = run_split_threads(&scene, 1, 2).unwrap();
    assert!(format!("{split:?}") == format!("{one:?}"), "the output differs from one process's");
    scene.record.energy = true;
    let one =
        run_seed(&Model::new(scene.clone()), 1, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    let split = run_split_threads(&scene, 1, 2).unwrap();
    assert!(format!("{split:?}") == format!("{one:?}"), "with the energy: the output differs from one process's");
}

/// The paper's scene (`pipelines/paper.toml`, its first seed, 50 modules: its bars listed, its
/// energy ledger, settling and driver): rank 0's output is the one process's on 2, 3 and 4 ranks
/// (the most its five layers take is five).
#[test]
fn a_split_run_of_the_paper_scene_gives_the_one_process_output() {
    let mut scene = common::pipeline("pipelines/paper.toml").scene;
    scene.shear.duration_s = 0.1;
    assert!(scene.record.energy && scene.self_weight.gravity_m_s2 > 0.0 && scene.young_cv > 0.0);
    assert!(scene.dims.bar_count() < stickslip_solver::model::STENCIL_MIN_BARS, "its bars are listed");
    let one =
        run_seed(&Model::new(scene.clone()), 123, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    assert!(one.settle_steps > 0 && !one.recording.onsets.is_empty(), "it settled, then slid");
    for ranks in [2, 3, 4] {
        let split = run_split_threads(&scene, 123, ranks).unwrap();
        assert!(format!("{split:?}") == format!("{one:?}"), "{ranks} ranks: the output differs from one process's");
    }
}

/// TPV5 at 500 m split over 2 ranks, stopped part way (each rank writes its checkpoint as it
/// stops) and resumed: the one process's output, bit for bit. A checkpoint of another rank count
/// is not resumed: 3 ranks start over (and give the same output).
#[test]
fn a_split_run_stopped_and_resumed_from_its_checkpoints_gives_the_one_process_output() {
    let mut scene = common::pipeline("pipelines/tpv5-500m.toml").scene;
    scene.shear.duration_s = 3.0;
    let one =
        run_seed(&Model::new(scene.clone()), 1, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    let folder = std::env::temp_dir().join(format!("stickslip-split-checkpoint-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    let stopped = run_split_checkpointed(&scene, 1, 2, Some(&folder), Some(3));
    assert!(matches!(stopped, Err(SolverError::Cancelled)), "{stopped:?}");
    let at: Vec<Option<u64>> = (0..2)
        .map(|r| Checkpoint::new(folder.join(format!("rank-{r}-of-2.ckpt")), None, None, "test".into()).resumes_at())
        .collect();
    assert!(at[0].is_some_and(|s| s > 0 && s < one.steps()) && at[0] == at[1], "{at:?} of {} steps", one.steps());
    let resumed = run_split_checkpointed(&scene, 1, 2, Some(&folder), None).unwrap();
    assert!(format!("{resumed:?}") == format!("{one:?}"), "the resumed output differs from one process's");
    let fresh = run_split_checkpointed(&scene, 1, 3, Some(&folder), None).unwrap();
    assert!(format!("{fresh:?}") == format!("{one:?}"));
    std::fs::remove_dir_all(&folder).unwrap();
}

/// The critical step found by the ranks together is the one process's, bit for bit: the paper's
/// block grown to 20 × 10 × 60 modules (a Weibull field on E), over 2, 7 and 20 ranks, down to
/// parts of 3 module layers, fewer degrees of freedom than a block of Lanczos's sums (so a block
/// runs over several ranks).
#[test]
fn the_critical_step_found_by_the_ranks_together_is_the_one_process_s() {
    use stickslip_solver::statics::critical::critical_step_split;
    use stickslip_solver::statics::critical_step_on;
    let mut scene = Scene::paper();
    scene.dims = stickslip_solver::Dims::new(20, 10, 60);
    assert!(scene.young_cv > 0.0);
    let one = Model::new(scene.clone());
    let k = one.lane_stiffness(7).unwrap();
    let want = critical_step_on(&one, &k, false).unwrap();
    assert!(want.iterations > 0, "converged Lanczos, not the node bound: {want:?}");
    for ranks in [2, 7, 20] {
        let got = on_thread_ranks(&scene, ranks, |r, model, _, link| {
            let k = model.lane_stiffness(7).unwrap();
            critical_step_split(model, &k, r % 2 == 1, link).unwrap()
        });
        for (r, c) in got.iter().enumerate() {
            assert!(format!("{c:?}") == format!("{want:?}"), "{ranks} ranks, rank {r}: {c:?} against {want:?}");
        }
    }
}

/// The paper's block grown to 60 × 6 × 20 modules (gravity, a Coulomb base, a driver, a Weibull
/// field on E): its self-weight stage settles dynamically on every rank together (the equilibrium
/// check's sum handed from rank to rank), then it is sheared: the one process's output on 2 and
/// 3 ranks; a static self-weight is refused, saying why.
#[test]
fn a_split_run_with_a_self_weight_stage_gives_the_one_process_output() {
    use stickslip_solver::scene::{Component, ControlChannel, Kinematic};
    let mut scene = Scene::paper();
    scene.dims = stickslip_solver::Dims::new(60, 6, 20);
    scene.shear.duration_s = 0.01;
    assert!(scene.self_weight.gravity_m_s2 > 0.0 && scene.dims.bar_count() >= 100_000);
    // The settling recorded too, with its energy ledger and a station near the top (another rank's).
    scene.record.settling = true;
    scene.record.energy = true;
    let top = scene.lattice().node_at([3.0, 0.3, 1.9]).unwrap();
    scene.record.control.push(ControlChannel { node: top, quantity: Kinematic::Acceleration, component: Component::Z });
    let one =
        run_seed(&Model::new(scene.clone()), 2, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    assert!(one.settle_steps > 0, "a self-weight stage");
    for ranks in [2, 3] {
        let split = run_split_threads(&scene, 2, ranks).unwrap();
        assert!(format!("{split:?}") == format!("{one:?}"), "{ranks} ranks: the output differs from one process's");
    }
    scene.self_weight.method = stickslip_solver::scene::SettleMethod::Static;
    let e = run_split_threads(&scene, 2, 2).unwrap_err();
    assert!(e.to_string().contains("self_weight.method = \"dynamic\""), "{e}");
}
