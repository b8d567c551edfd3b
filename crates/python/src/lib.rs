//! `stickslip._native`: the compiled part of the Python package `stickslip` (python/stickslip).
//!
//! The Python package is the API users call; this module gives it the product's own code, never a
//! second implementation: pipelines validated by `stickslip_config` ([`pipeline`]), checked and
//! run by `stickslip_ensemble` with the GIL released, Ctrl-C and progress handled as the command
//! line does ([`run`]), and the response spectra, RotD, similarity scaling and record readers of
//! `stickslip_seismo` on arrays ([`numerics`]). Refusals become the package's `PipelineError`
//! (field, value, allowed range) and `RunError`, defined in Python (`stickslip/errors.py`).
#![deny(missing_docs)]

use pyo3::prelude::*;

mod errors;
mod numerics;
mod pipeline;
mod run;

/// The module `stickslip._native`.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(pipeline::toml_to_json, m)?)?;
    m.add_function(wrap_pyfunction!(pipeline::json_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(pipeline::validate, m)?)?;
    m.add_function(wrap_pyfunction!(pipeline::default_toml, m)?)?;
    m.add_function(wrap_pyfunction!(run::check, m)?)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(numerics::response_spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(numerics::rotd, m)?)?;
    m.add_function(wrap_pyfunction!(numerics::similarity, m)?)?;
    m.add_function(wrap_pyfunction!(numerics::read_record, m)?)?;
    Ok(())
}
