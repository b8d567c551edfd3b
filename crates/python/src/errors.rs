//! Rust errors as the package's Python exceptions (`stickslip.errors`): a refused pipeline as
//! `PipelineError(message, errors)` with every `(field, value, allowed)`, anything else that stops
//! a run as `RunError(message)`, an interrupted run as `KeyboardInterrupt`.

use pyo3::exceptions::{PyFileNotFoundError, PyKeyboardInterrupt, PyOSError};
use pyo3::prelude::*;
use stickslip_config::{ConfigError, FieldError};
use stickslip_ensemble::EnsembleError;

/// An exception of `stickslip.errors` named `class`, built from `args`.
fn package_error<'py, A>(py: Python<'py>, class: &str, args: A) -> PyErr
where
    A: pyo3::call::PyCallArgs<'py>,
{
    match py.import("stickslip.errors").and_then(|m| m.getattr(class)).and_then(|c| c.call1(args)) {
        Ok(e) => PyErr::from_value(e),
        Err(e) => e,
    }
}

/// A refused pipeline: the message and each refused field.
pub fn pipeline_error(py: Python<'_>, message: String, fields: &[FieldError]) -> PyErr {
    let list: Vec<(String, String, String)> =
        fields.iter().map(|f| (f.field.clone(), f.value.clone(), f.allowed.clone())).collect();
    package_error(py, "PipelineError", (message, list))
}

/// A configuration error as the Python exception a user expects: the file that cannot be read as
/// `FileNotFoundError` / `OSError`, refused values and TOML that does not parse as `PipelineError`.
pub fn config_error(py: Python<'_>, e: ConfigError) -> PyErr {
    match e {
        ConfigError::File { source, .. } => config_error(py, *source),
        ConfigError::Io { path, source } => {
            let message = format!("{}: {source}", path.display());
            if source.kind() == std::io::ErrorKind::NotFound || !path.exists() {
                PyFileNotFoundError::new_err(message)
            } else {
                PyOSError::new_err(message)
            }
        }
        ConfigError::Invalid(fields) => pipeline_error(py, ConfigError::Invalid(fields.clone()).to_string(), &fields),
        ConfigError::Syntax(message) => pipeline_error(py, message, &[]),
    }
}

/// An ensemble's error: a refused pipeline as `PipelineError`, an interrupted run as
/// `KeyboardInterrupt` (finished seeds are kept), anything else as `RunError`.
pub fn ensemble_error(py: Python<'_>, e: EnsembleError) -> PyErr {
    match e {
        EnsembleError::Config(c) => config_error(py, c),
        EnsembleError::Interrupted { .. } => PyKeyboardInterrupt::new_err(e.to_string()),
        other => package_error(py, "RunError", (other.to_string(),)),
    }
}
