//! A run stopped and resumed from its checkpoint gives the numbers of a run never stopped, bit
//! for bit (docs/model.md §19): the paper's scene stopped while its self-weight settles and while
//! it is sheared (its recording, slip onsets and ledger), and a checkpoint that is not this run's
//! (another pipeline, a truncated file) is not resumed: the run starts over, and says why.

use std::ops::ControlFlow;
use std::path::PathBuf;

use stickslip_solver::{Checkpoint, Model, RunOptions, RunOutput, Scene, SolverError, run_seed, run_seed_checkpointed};

fn folder(name: &str) -> PathBuf {
    let f = std::env::temp_dir().join(format!("stickslip-checkpoint-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&f);
    f
}

fn uninterrupted(model: &Model) -> RunOutput {
    run_seed(model, 3, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap()
}

/// Runs seed 3 with `checkpoint` until `stop` says (given the fraction done) to stop; returns
/// the fraction at the stop.
fn stopped(model: &Model, checkpoint: &Checkpoint, mut stop: impl FnMut(f64) -> bool) -> f64 {
    let mut at = f64::NAN;
    let out = run_seed_checkpointed(model, 3, RunOptions::default(), checkpoint, &mut |f| {
        at = f;
        if stop(f) { ControlFlow::Break(()) } else { ControlFlow::Continue(()) }
    });
    assert!(matches!(out, Err(SolverError::Cancelled)), "{:?}", out.map(|o| o.steps()));
    at
}

fn resumed(model: &Model, checkpoint: &Checkpoint) -> (RunOutput, f64) {
    let mut first = None;
    let out = run_seed_checkpointed(model, 3, RunOptions::default(), checkpoint, &mut |f| {
        first.get_or_insert(f);
        ControlFlow::Continue(())
    })
    .unwrap();
    (out, first.unwrap())
}

#[test]
fn the_paper_scene_stopped_while_settling_or_shearing_resumes_to_the_same_bits() {
    let mut scene = Scene::paper();
    scene.record.energy = true;
    scene.record.slip_onsets = true;
    let model = Model::new(scene);
    let one = uninterrupted(&model);
    assert!(one.settle_steps > 512 && one.recording.onsets.len() > 3, "a run with a settling stage and events");
    let want = format!("{one:?}");
    let dir = folder("paper");
    let file = dir.join("seed-3.ckpt");
    // Every 4096 steps, and as it stops.
    let c = Checkpoint::new(file.clone(), None, Some(4096), "paper".into());
    // Stopped while settling (no fraction of the shear stage yet): its first report, at 512 steps.
    let at = stopped(&model, &c, |_| true);
    assert_eq!(at, 0.0, "stopped in the self-weight stage");
    assert_eq!(c.resumes_at(), Some(512), "a checkpoint written as it stopped");
    let (out, first) = resumed(&model, &c);
    assert!(format!("{out:?}") == want, "resumed in the self-weight stage: the output differs");
    // Its first report is the next, 1024 steps in: in the shear stage, just begun.
    assert!(first > 0.0 && first < 0.01, "{first}");
    // Stopped half way through the shear stage, after a checkpoint every 4096 steps.
    std::fs::remove_file(&file).unwrap();
    let mut periodic = None;
    let at = stopped(&model, &c, |f| {
        periodic = periodic.or(c.resumes_at());
        f > 0.5
    });
    assert!(periodic.is_some_and(|s| (4096..4096 + 512).contains(&s)), "the first periodic checkpoint: {periodic:?}");
    assert!(at > 0.5 && at < 0.6, "{at}");
    assert!(c.resumes_at().is_some_and(|s| s > 4096 + 512));
    let (out, first) = resumed(&model, &c);
    assert!(format!("{out:?}") == want, "resumed in the shear stage: the output differs");
    assert!(first > 0.5, "the resumed run starts where it stopped, not at {first}");
    assert!(c.failure().is_none(), "{:?}", c.failure());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_checkpoint_of_another_run_or_a_truncated_one_is_not_resumed() {
    let model = Model::new(Scene::paper());
    let one = uninterrupted(&model);
    let dir = folder("other");
    let file = dir.join("seed-3.ckpt");
    let c = Checkpoint::new(file.clone(), None, None, "one pipeline".into());
    stopped(&model, &c, |f| f > 0.3);
    // Another pipeline's key: the run starts over and says why.
    let other = Checkpoint::new(file.clone(), None, None, "another pipeline".into());
    assert_eq!(other.resumes_at(), None);
    let (out, first) = resumed(&model, &other);
    assert_eq!(first, 0.0, "started over");
    assert!(format!("{out:?}") == format!("{one:?}"));
    let why = other.failure().expect("says why the file was not resumed");
    assert!(
        why.contains("seed-3.ckpt was not resumed (kept as ") && why.contains("it was written for another run"),
        "{why}"
    );
    assert!(file.with_extension("ckpt.unread").exists(), "the file not resumed is kept aside, not overwritten");
    // Truncated: not resumed either.
    stopped(&model, &c, |f| f > 0.3);
    let bytes = std::fs::read(&file).unwrap();
    std::fs::write(&file, &bytes[..bytes.len() - 100]).unwrap();
    let (out, first) = resumed(&model, &c);
    assert_eq!(first, 0.0, "started over");
    assert!(format!("{out:?}") == format!("{one:?}"));
    let why = c.failure().expect("says why");
    assert!(why.contains("bytes long, not the"), "{why}");
    std::fs::remove_dir_all(&dir).unwrap();
}
