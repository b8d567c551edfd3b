//! Earthquake cycles on a rate-and-state fault, quasi-dynamically (docs/model.md §20.3).
//!
//! The fault's nodes carry slip δ and state θ; their traction is the prestress, the lattice's
//! quasi-static response to slip ahead of or behind the plate, and radiation damping:
//!
//! `τ_j = τ0_j − Σ_l K_jl·(δ_l − V_p·t) − η·V_j = σ_j·f(V_j, θ_j)`,  `η = μ/(2c_s)`,
//!
//! solved for `V_j` node by node ([`crate::laws::rate_state::balance_from`], Newton on ln V in a
//! bracket, started from the node's previous rate). Then `dδ/dt = V` and, in ln θ,
//! `d ln θ/dt = 1/θ − V/L` (aging) or `−(V/L)·ln(Vθ/L)` (slip law). The system is integrated by
//! the Dormand–Prince 5(4) pair with an adaptive step (Hairer, Nørsett & Wanner 1993, II.4): a
//! step is accepted when its error estimate is within `relative·|y| + absolute` on every
//! component, and the next step is `0.9·err^(−1/5)` times this one (between 0.2 and 5 times). The
//! one rule covers both phases: decades between events, milliseconds inside them, the step set
//! by the state's and the slip's own rates of change (the role Lapusta et al. 2000's
//! `ξ·L/V_max` plays).

use rayon::prelude::*;

use crate::error::SolverError;
use crate::laws::Evolution;
use crate::laws::rate_state::{RateStateNode, RateStateStart, balance_from, balanced_state};

use super::antiplane::FaultStiffness;

/// A fault under rate-and-state friction loaded by the plate, in the antiplane mode.
#[derive(Clone, Debug)]
pub struct QuasiDynamicFault {
    /// The lattice's quasi-static response of the frictional part.
    pub stiffness: FaultStiffness,
    /// Each node's friction (its start gives θ₀).
    pub friction: Vec<RateStateNode>,
    /// The effective normal stress on each node (Pa, compression positive).
    pub normal_pa: Vec<f64>,
    /// The shear traction on each node while it keeps up with the plate (Pa).
    pub shear0_pa: Vec<f64>,
    /// Radiation damping η (Pa·s/m): `μ/(2c_s)`.
    pub eta_pa_s_m: f64,
    /// The plate rate V_p (m/s): the slip below the frictional part and the far face's motion.
    pub plate_m_s: f64,
}

/// The step control.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance of every component.
    pub relative: f64,
    /// Absolute tolerance of slip (m).
    pub slip_m: f64,
    /// Absolute tolerance of ln θ.
    pub log_state: f64,
    /// The longest step (s).
    pub max_step_s: f64,
}

impl Default for Tolerances {
    fn default() -> Self {
        Tolerances { relative: 1e-7, slip_m: 1e-7, log_state: 1e-7, max_step_s: 0.1 * YEAR_S }
    }
}

/// One Julian year (s), the SEAS benchmarks' year.
pub const YEAR_S: f64 = 365.25 * 24.0 * 3600.0;

/// The fault at one accepted step.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleState {
    /// Time (s).
    pub t_s: f64,
    /// Slip of each node (m).
    pub slip_m: Vec<f64>,
    /// ln θ of each node (θ in s).
    pub log_state: Vec<f64>,
    /// Slip rate of each node (m/s).
    pub slip_rate_m_s: Vec<f64>,
    /// Shear traction of each node (Pa), radiation damping included: `σ·f(V, θ)`.
    pub shear_pa: Vec<f64>,
}

/// What a run took.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CycleStats {
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected steps.
    pub rejected: u64,
    /// Shortest accepted step (s).
    pub min_step_s: f64,
    /// Longest accepted step (s).
    pub max_step_s: f64,
    /// Explicit steps inside events (fully dynamic runs).
    pub dynamic_steps: u64,
    /// Explicit phases (fully dynamic runs).
    pub dynamic_phases: u64,
    /// Simulated time in explicit phases (s).
    pub dynamic_time_s: f64,
    /// Wall-clock time in explicit phases (s).
    pub dynamic_wall_s: f64,
    /// Wall-clock time in quasi-dynamic phases (s; fully dynamic runs).
    pub quasi_wall_s: f64,
    /// The largest difference, over the fault and the explicit phases' ends, between the
    /// friction the explicit grid ends with and what the full block's static stiffness gives
    /// for the same slip, `τ0 − K·(δ − V_p·t) − η·V` (Pa): the truncated grid's share.
    pub handover_jump_pa: f64,
}

/// What the observer asks of the run after a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flow {
    /// Go on.
    Continue,
    /// Stop here (an interrupted run, a full catalogue).
    Stop,
}

impl QuasiDynamicFault {
    /// Number of fault nodes.
    pub fn nodes(&self) -> usize {
        self.stiffness.nodes
    }

    /// The state at t = 0: no slip, each node's θ₀, and the rates and tractions they balance.
    pub fn start(&self) -> CycleState {
        let n = self.nodes();
        let slip = vec![0.0; n];
        let log_state: Vec<f64> = (self.friction.iter().enumerate())
            .map(|(i, f)| match f.start {
                // Balanced with the radiation damping's share of the traction.
                RateStateStart::Balanced(v) => {
                    balanced_state(f, v, self.shear0_pa[i], self.normal_pa[i], self.eta_pa_s_m).ln()
                }
                _ => f.theta0_s(self.shear0_pa[i], self.normal_pa[i]).ln(),
            })
            .collect();
        let mut s =
            CycleState { t_s: 0.0, slip_m: slip, log_state, slip_rate_m_s: vec![0.0; n], shear_pa: vec![0.0; n] };
        let mut scratch = Scratch::new(n);
        self.rates(0.0, &s.slip_m, &s.log_state, None, &mut s.slip_rate_m_s, &mut scratch);
        self.damped(&scratch.stress, &s.slip_rate_m_s, &mut s.shear_pa);
        s
    }

    /// The shear traction with radiation damping, `τ − η·V` (= `σ·f(V, θ)` at the balance), from
    /// the tractions `stress` and slip rates `v` of one evaluation.
    fn damped(&self, stress: &[f64], v: &[f64], out: &mut [f64]) {
        for ((o, tau), v) in out.iter_mut().zip(stress).zip(v) {
            *o = tau - self.eta_pa_s_m * v;
        }
    }

    /// The slip rates at time `t` for slip and ln θ (`guess`: the previous rates), the
    /// tractions without radiation damping in `scratch.stress` and θ in `scratch.theta`.
    fn rates(
        &self,
        t: f64,
        slip: &[f64],
        log_state: &[f64],
        guess: Option<&[f64]>,
        v: &mut [f64],
        scratch: &mut Scratch,
    ) {
        let Scratch { stress, behind, theta } = scratch;
        for (b, d) in behind.iter_mut().zip(slip) {
            *b = d - self.plate_m_s * t;
        }
        let behind = &*behind;
        // Each node's traction and slip rate on its own: one parallel pass, the same numbers on
        // any thread count.
        let node = |j: usize, ((v, stress), theta): ((&mut f64, &mut f64), &mut f64)| {
            let tau = self.shear0_pa[j] + self.stiffness.traction_change_at(j, behind);
            *stress = tau;
            *theta = log_state[j].exp();
            let g = guess.map(|g| g[j].abs()).filter(|g| *g > 0.0);
            let speed = balance_from(&self.friction[j], *theta, tau.abs(), self.normal_pa[j], self.eta_pa_s_m, g);
            *v = speed.copysign(tau);
        };
        if self.nodes() >= PARALLEL_NODES {
            v.par_iter_mut()
                .zip(stress.par_iter_mut())
                .zip(theta.par_iter_mut())
                .enumerate()
                .with_min_len(PARALLEL_NODES / 2)
                .for_each(|(j, node_out)| node(j, node_out));
        } else {
            v.iter_mut().zip(stress.iter_mut()).zip(theta.iter_mut()).enumerate().for_each(|(j, o)| node(j, o));
        }
    }

    /// The derivative of `y = (δ, ln θ)` at `t`, the slip rates left in `v`.
    fn derivative(
        &self,
        t: f64,
        y: &[f64],
        guess: Option<&[f64]>,
        v: &mut [f64],
        dy: &mut [f64],
        scratch: &mut Scratch,
    ) {
        let n = self.nodes();
        let (slip, log_state) = y.split_at(n);
        self.rates(t, slip, log_state, guess, v, scratch);
        for j in 0..n {
            let f = &self.friction[j];
            let speed = v[j].abs();
            dy[j] = v[j];
            dy[n + j] = match f.evolution {
                Evolution::Aging => 1.0 / scratch.theta[j] - speed / f.dc_m,
                Evolution::Slip => {
                    if speed == 0.0 {
                        0.0
                    } else {
                        -(speed / f.dc_m) * (speed.ln() + log_state[j] - f.dc_m.ln())
                    }
                }
            };
        }
    }

    /// Integrates from `state` to `until_s`, calling `observe` after every accepted step (and
    /// once at the start); stops early when it answers [`Flow::Stop`].
    pub fn run(
        &self,
        mut state: CycleState,
        until_s: f64,
        tol: &Tolerances,
        max_steps: u64,
        mut observe: impl FnMut(&CycleState) -> Flow,
    ) -> Result<(CycleState, CycleStats), SolverError> {
        let n = self.nodes();
        let m = 2 * n;
        let mut y: Vec<f64> = state.slip_m.iter().chain(&state.log_state).copied().collect();
        let mut v = state.slip_rate_m_s.clone();
        let mut k: [Vec<f64>; 7] = std::array::from_fn(|_| vec![0.0; m]);
        let mut vs = vec![0.0; n];
        let mut stage = vec![0.0; m];
        let mut scratch = Scratch::new(n);
        self.derivative(state.t_s, &y, Some(&v), &mut vs, &mut k[0], &mut scratch);
        let mut stats = CycleStats { min_step_s: f64::INFINITY, ..CycleStats::default() };
        // A first step the state's own time scale allows.
        let vmax = v.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let mut h = (1e-3 * self.friction.iter().map(|f| f.dc_m).fold(f64::INFINITY, f64::min) / vmax.max(1e-30))
            .min(tol.max_step_s);
        if observe(&state) == Flow::Stop {
            return Ok((state, stats));
        }
        let mut t = state.t_s;
        while t < until_s {
            if stats.accepted + stats.rejected >= max_steps {
                return Err(SolverError::Numerical(format!(
                    "the cycle run reached {max_steps} steps at t = {:.6e} s ({:.3} years) before {:.3} years",
                    t,
                    t / YEAR_S,
                    until_s / YEAR_S
                )));
            }
            let h_now = h.min(until_s - t);
            for s in 1..7 {
                for i in 0..m {
                    let mut acc = 0.0;
                    for (r, kr) in k.iter().enumerate().take(s) {
                        acc += A[s][r] * kr[i];
                    }
                    stage[i] = y[i] + h_now * acc;
                }
                self.derivative(t + C[s] * h_now, &stage, Some(&v), &mut vs, &mut k[s], &mut scratch);
            }
            // Stage 7 is at the fifth-order solution (FSAL): `stage` holds it, `scratch` and
            // `vs` its tractions and rates.
            let mut err: f64 = 0.0;
            for i in 0..m {
                let e: f64 = h_now * (0..7).map(|r| E[r] * k[r][i]).sum::<f64>();
                let atol = if i < n { tol.slip_m } else { tol.log_state };
                let scale = atol + tol.relative * y[i].abs().max(stage[i].abs());
                err = err.max((e / scale).abs());
            }
            if !err.is_finite() {
                h = 0.2 * h_now;
                stats.rejected += 1;
                if h < 1e-12 {
                    return Err(SolverError::Numerical(format!(
                        "the cycle run's step fell below 1e-12 s at t = {t:.6e} s"
                    )));
                }
                continue;
            }
            let factor = (0.9 * err.powf(-0.2)).clamp(0.2, 5.0);
            if err <= 1.0 {
                t += h_now;
                y.copy_from_slice(&stage);
                let (first, rest) = k.split_at_mut(1);
                first[0].copy_from_slice(&rest[5]);
                v.copy_from_slice(&vs);
                stats.accepted += 1;
                stats.min_step_s = stats.min_step_s.min(h_now);
                stats.max_step_s = stats.max_step_s.max(h_now);
                state.t_s = t;
                state.slip_m.copy_from_slice(&y[..n]);
                state.log_state.copy_from_slice(&y[n..]);
                state.slip_rate_m_s.copy_from_slice(&v);
                self.damped(&scratch.stress, &v, &mut state.shear_pa);
                h = (h_now * factor).min(tol.max_step_s);
                if observe(&state) == Flow::Stop {
                    break;
                }
            } else {
                stats.rejected += 1;
                h = h_now * factor.min(1.0);
            }
        }
        Ok((state, stats))
    }
}

/// Faults of this many nodes or more solve their nodes on the thread pool (BP1 at 50 m, 800
/// nodes: 1.5× on 2 threads; at 100 m, 400 nodes, the pool's overhead eats the gain).
const PARALLEL_NODES: usize = 512;

/// Buffers of a right-hand side.
struct Scratch {
    stress: Vec<f64>,
    behind: Vec<f64>,
    theta: Vec<f64>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Scratch { stress: vec![0.0; n], behind: vec![0.0; n], theta: vec![0.0; n] }
    }
}

/// Dormand–Prince nodes.
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
/// Dormand–Prince stages (row 6 is the fifth-order solution's weights).
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0, 0.0, 0.0],
    [9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0, 0.0],
    [35.0 / 384.0, 0.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0],
];
/// Fifth-order minus fourth-order weights: the error estimate.
const E: [f64; 7] = [
    35.0 / 384.0 - 5179.0 / 57600.0,
    0.0,
    500.0 / 1113.0 - 7571.0 / 16695.0,
    125.0 / 192.0 - 393.0 / 640.0,
    -2187.0 / 6784.0 + 92097.0 / 339200.0,
    11.0 / 84.0 - 187.0 / 2100.0,
    -1.0 / 40.0,
];
