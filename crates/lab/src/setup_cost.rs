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
