//! What can go wrong in the dispersion of the lattice: a refused input.

use crate::dispersion::direction::Branch;

/// Everything that can go wrong here: a refused input.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum DispersionError {
    /// A parameter outside its allowed range; nothing was computed.
    #[error("{parameter} = {value} is not allowed: {allowed}")]
    InvalidParameter {
        /// Name of the parameter, e.g. `poisson`.
        parameter: &'static str,
        /// The value as given.
        value: f64,
        /// What would be accepted, e.g. `0 < poisson < 0.5`.
        allowed: String,
    },
    /// A branch of the wrong kind for the question (an optical branch has no long-wave speed).
    #[error("branch {branch} is not allowed here: {allowed}")]
    InvalidBranch {
        /// The branch as given.
        branch: Branch,
        /// What would be accepted.
        allowed: &'static str,
    },
}

pub(super) fn refuse(parameter: &'static str, value: f64, allowed: impl Into<String>) -> DispersionError {
    DispersionError::InvalidParameter { parameter, value, allowed: allowed.into() }
}

pub(super) fn positive(parameter: &'static str, value: f64, unit: &str) -> Result<f64, DispersionError> {
    if !(value > 0.0 && value.is_finite()) {
        return Err(refuse(parameter, value, format!("a finite {parameter} > 0 {unit}")));
    }
    Ok(value)
}
