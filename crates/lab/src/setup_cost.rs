//! What a run does before its first step, against what a step costs: building the lattice, one
//! seed's stiffness (the Weibull draws), the critical step, the state; then steps timed. On the
//! current rayon pool with `parallel` (as `stickslip pipeline` runs one seed on all threads).

use std::time::Instant;

use stickslip_solver::Model;
use stickslip_solver::Scene;
use stickslip_solver::statics::critical_step_on;
use stickslip_solver::step::{Batch, LaneSetup, Tracking};

use crate::LabError;

/// Seconds of each part of the set-up and of one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SetupCost {
    /// Bars of the lattice.
    pub bars: usize,
    /// `Model::new`.
    pub model_s: f64,
    /// One seed's stiffness (Weibull factors) and friction factors.
    pub stiffness_s: f64,
    /// The critical step.
    pub critical_s: f64,
    /// Its Lanczos iterations (0: the node bound alone).
    pub iterations: usize,
    /// Parameters, state and stepper allocated.
    pub state_s: f64,
    /// One step, the mean over the steps timed.
    pub step_s: f64,
}

impl SetupCost {
    /// Everything before the first step.
    pub fn setup_s(&self) -> f64 {
        self.model_s + self.stiffness_s + self.critical_s + self.state_s
    }
}

/// The set-up of `seed` of `scene` and `steps` steps, timed.
pub fn setup_cost(scene: Scene, seed: u64, steps: usize, parallel: bool) -> Result<SetupCost, LabError> {
    let err = |e: stickslip_solver::SolverError| LabError::Setup(e.to_string());
    let t = Instant::now();
    let model = Model::new(scene);
    let model_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let stiffness = model.lane_stiffness_on(seed, parallel).map_err(err)?;
    let friction = model.friction_factors(seed).map_err(err)?;
    let fault = model.fault_loads(seed).map_err(err)?;
    let stiffness_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let critical = critical_step_on(&model, &stiffness, parallel).map_err(err)?;
    let critical_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let dt = 0.5 * critical.dt_s;
    let mut batch = Batch::<1>::new(&model, &[LaneSetup { dt_s: dt, stiffness, friction, strength: None, fault }]);
    let scene = model.scene();
    batch.params.set_damping(0, scene.shear.damping_per_s);
    batch.params.set_body_acceleration(0, [0.0, 0.0, -scene.self_weight.gravity_m_s2]);
    batch.stepper.set_parallel(parallel && model.layout().splits());
    batch.stepper.set_tracking(Tracking { energy: scene.record.energy, onsets: scene.record.slip_onsets, slid: false });
    let state_s = t.elapsed().as_secs_f64();
    batch.step();
    let t = Instant::now();
    for _ in 0..steps {
        batch.step();
    }
    Ok(SetupCost {
        bars: model.bar_count(),
        model_s,
        stiffness_s,
        critical_s,
        iterations: critical.iterations,
        state_s,
        step_s: t.elapsed().as_secs_f64() / steps.max(1) as f64,
    })
}

/// A step against the memory bandwidth measured in the same run (issue 50's goal: at least 60%
/// of the bound on 50 M bars).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bandwidth {
    /// Bars of the lattice.
    pub bars: usize,
    /// Nodes of the lattice.
    pub nodes: usize,
    /// One step, the best mean over three rounds of the steps timed (s).
    pub step_s: f64,
    /// Bytes of the arrays a step reads or writes, each counted once: three time levels and the
    /// forces (96 B per node), the inverse masses (8), each bar's stiffness factor (4 with a
    /// Weibull field) and the runs' nominal stiffness.
    pub bytes: u64,
    /// A triad `a = b + s·c` over three arrays of `bytes` in all, on the same pool, the best of
    /// five, counted as STREAM counts it (24 B per element), B/s.
    pub triad_b_s: f64,
}

impl Bandwidth {
    /// The least time a step can take: its bytes at the triad's rate (s).
    pub fn bound_s(&self) -> f64 {
        self.bytes as f64 / self.triad_b_s
    }

    /// The bound over the step: the share of what memory allows.
    pub fn ratio(&self) -> f64 {
        self.bound_s() / self.step_s
    }
}

/// [`Bandwidth`] of `seed` of `scene`, `steps` steps, on the current rayon pool.
pub fn bandwidth(scene: Scene, seed: u64, steps: usize) -> Result<Bandwidth, LabError> {
    use rayon::prelude::*;
    let err = |e: stickslip_solver::SolverError| LabError::Setup(e.to_string());
    let parallel = rayon::current_num_threads() > 1;
    let model = Model::new(scene);
    let stiffness = model.lane_stiffness_on(seed, parallel).map_err(err)?;
    let friction = model.friction_factors(seed).map_err(err)?;
    let fault = model.fault_loads(seed).map_err(err)?;
    let critical = critical_step_on(&model, &stiffness, parallel).map_err(err)?;
    let (nodes, bars) = (model.node_count(), model.bar_count());
    let factors = if model.scene().young_cv > 0.0 { 4 * bars } else { 0 };
    let bytes = (nodes * (96 + 8)
        + factors
        + model.run_stiffness().len() * std::mem::size_of_val(&model.run_stiffness()[0])) as u64;
    let mut batch =
        Batch::<1>::new(&model, &[LaneSetup { dt_s: 0.5 * critical.dt_s, stiffness, friction, strength: None, fault }]);
    let scene = model.scene();
    batch.params.set_damping(0, scene.shear.damping_per_s);
    batch.params.set_body_acceleration(0, [0.0, 0.0, -scene.self_weight.gravity_m_s2]);
    batch.stepper.set_parallel(parallel && model.layout().splits());
    batch.step();
    let mut step_s = f64::INFINITY;
    for _ in 0..3 {
        let t = Instant::now();
        for _ in 0..steps {
            batch.step();
        }
        step_s = step_s.min(t.elapsed().as_secs_f64() / steps.max(1) as f64);
    }
    drop(batch);
    // The triad over the same footprint, in chunks on the pool.
    let n = (bytes / 24) as usize;
    let mut a = vec![0.0f64; n];
    let b = vec![1.0f64; n];
    let c = vec![2.0f64; n];
    let chunk = (n / (8 * rayon::current_num_threads())).max(1 << 16);
    let mut best = f64::INFINITY;
    for _ in 0..5 {
        let t = Instant::now();
        a.par_chunks_mut(chunk).zip(b.par_chunks(chunk)).zip(c.par_chunks(chunk)).for_each(|((a, b), c)| {
            for ((a, b), c) in a.iter_mut().zip(b).zip(c) {
                *a = b + 3.0 * c;
            }
        });
        best = best.min(t.elapsed().as_secs_f64());
    }
    std::hint::black_box(&a);
    Ok(Bandwidth { bars, nodes, step_s, bytes, triad_b_s: (24 * n) as f64 / best })
}
