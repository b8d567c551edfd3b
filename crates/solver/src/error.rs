//! Errors of the solver: numerical failures, unstable runs, cancelled runs.
//!
//! Messages name physical quantities (the time step, the settling damping), never the keys of a
//! pipeline file: whoever reads those files maps the quantities to their keys.

/// Everything that can go wrong in the solver.
#[derive(Debug, thiserror::Error)]
pub enum SolverError {
    /// The requested time step is above the critical step of the lattice actually built.
    #[error(
        "time step {dt_s:.6e} s is above the critical step {critical_s:.6e} s of this lattice \
         (seed {seed}: stiffest bar and lightest node included); use a time step at most the critical \
         one"
    )]
    TimeStepAboveCritical {
        /// Requested step.
        dt_s: f64,
        /// Critical step `2/ω_max`.
        critical_s: f64,
        /// Seed of the random field.
        seed: u64,
    },
    /// The run went numerically unstable and was stopped.
    #[error(
        "run went unstable at step {step} (t = {time_s:.6e} s, {stage}): {what} at {node} \
         (LDEM {ldem}); Δt = {dt_s:.4e} s is {fraction:.3} of the critical step"
    )]
    Unstable {
        /// Global step index at which the blow-up was detected.
        step: u64,
        /// Time since the start of the stage, in seconds.
        time_s: f64,
        /// Loading stage name.
        stage: &'static str,
        /// What was detected (non-finite value, speed above bound …).
        what: String,
        /// Node position (m).
        node: String,
        /// LDEM number of the node.
        ldem: u64,
        /// Time step used.
        dt_s: f64,
        /// Time step over the critical one.
        fraction: f64,
    },
    /// The self-weight stage did not reach static equilibrium within its time limit.
    #[error(
        "self-weight stage did not settle within {max_s} s (out-of-balance force ratio {residual:.3e} > \
         tolerance {tolerance:.1e}); raise the settling damping or the stage's time limit"
    )]
    NotSettled {
        /// The stage's time limit.
        max_s: f64,
        /// Residual ratio reached.
        residual: f64,
        /// Requested tolerance.
        tolerance: f64,
    },
    /// The scene asks for something the solver cannot do (e.g. the skip-ahead with a boundary
    /// condition its quasi-static motion does not include).
    #[error("not supported: {0}")]
    Unsupported(String),
    /// A numerical procedure found no answer.
    #[error("numerical failure: {0}")]
    Numerical(String),
    /// A stage would take more steps than the run can count: more than [`MAX_STEPS`] (beyond
    /// which the times `k·Δt` are no longer exact), or more bar updates than a 64-bit counter
    /// holds.
    #[error(
        "the {stage} of {duration_s:e} s at Δt = {dt_s:.4e} s would take {steps:.3e} steps ({bar_updates:.3e} bar \
         updates), more than the run can count (at most 2^53 steps and 2^64 bar updates); use a shorter stage or a \
         larger time step"
    )]
    TooManySteps {
        /// The stage: "self-weight stage (its time limit)" or "shear stage".
        stage: &'static str,
        /// Its duration (s).
        duration_s: f64,
        /// The time step (s).
        dt_s: f64,
        /// Steps it would take.
        steps: f64,
        /// Bar updates it would take.
        bar_updates: f64,
    },
    /// The recording interval is finer than half the time step: the run samples at most once a
    /// step, and its records would be resampled to samples invented between steps.
    #[error(
        "record.interval_s = {interval_s:e} s is finer than this run can sample: it samples every round(interval/Δt) \
         steps, at least one, at Δt = {dt_s:.4e} s, and records resampled finer would be invented between steps; \
         give record.interval_s at least Δt/2 = {:.4e} s (or leave it out: every step)",
        0.5 * dt_s
    )]
    RecordIntervalTooFine {
        /// The interval asked for (s).
        interval_s: f64,
        /// The time step (s).
        dt_s: f64,
    },
    /// The caller asked the run to stop.
    #[error("run cancelled")]
    Cancelled,
}

/// The most steps a stage may take: 2^53, the largest count whose times `k·Δt` are exact.
pub const MAX_STEPS: f64 = 9_007_199_254_740_992.0;
