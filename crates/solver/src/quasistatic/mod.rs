//! Quasi-static shortcuts: the self-weight equilibrium solved directly ([`settle`]), and skip-ahead
//! through the interseismic phase of the shear stage ([`skip`], along a [`motion`]).
//!
//! **Static self-weight.** With every base node held where it stands (all three components),
//! the gravity equilibrium `K·u = f` is one conjugate-gradient solve ([`solve_static`]). It is
//! the state damped settling converges to (base nodes land and stick where they are) if it is
//! admissible: every base node pushes on the base (`N ≥ 0`) and its friction holds it
//! (`|R_t| ≤ μs·N`). Otherwise the run settles dynamically.
//!
//! **Skip-ahead.** With a fixed set of sticking base nodes (held where they are), lifted ones
//! (free) and the driver x prescribed at `d(t)`, the damped equations of motion
//! `M·ü + D·M·u̇ + K·u = f + R` have, for a constant driver velocity `ḋ`, the exact solution
//!
//! `u(t) = u_p + d(t)·g − D·ḋ·h`,  with `K·u_p = f` (held components where they are, driver at
//! its base), `K·g = 0` (driver x = 1, everything else held at 0) and `K·h = M·g` (all held
//! components at 0),
//!
//! and the reactions follow the same combination. The motion is linear in time, so the
//! central-difference scheme reproduces it exactly (its discrete acceleration is zero). The
//! actual state is this motion plus what the last event left ringing, which mass-proportional
//! damping takes away (every mode decays as `e^{−Dt/2}`). When the leftover changes no base
//! node's margin to its next transition by more than `tolerance` of that margin, the run jumps
//! along the motion to `margin_steps` before the first driver displacement at which a sticking
//! node reaches `μs·N`, a normal reaction reaches zero or a lifted node reaches the base, and
//! integrates explicitly from there. The samples in between are the motion's, the energy terms
//! are integrated along it, and the energy of the discarded leftover is booked as damped.

pub mod motion;
pub mod settle;
pub mod skip;

pub use settle::{StaticSettle, settle_statically};
pub use skip::SkipStats;
pub(crate) use skip::{SKIP_CHECK_EVERY, ShearClock, Skipper};

/// Relative residual of the static solves.
pub(crate) const CG_TOLERANCE: f64 = 1e-9;
/// Iteration cap of the static solves.
pub(crate) const CG_MAX_ITERATIONS: usize = 200_000;
/// Shortest jump worth making (steps).
const MIN_JUMP: u64 = 64;
/// Skips start once the driver ramp has reached its final velocity to this many rise times
/// (`e^{−15}` ≈ 3e-7 of it left).
const RAMP_RISE_TIMES: f64 = 15.0;
