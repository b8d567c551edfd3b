//! Pipeline files from Python: TOML ⇄ the JSON the package's `Pipeline` holds as a dict, and
//! validation by `stickslip_config`, with a TOML error turned into the field it is about.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use pyo3::types::PyDict;
use stickslip_config::{FieldError, Pipeline, PipelineFile};

use crate::errors::{config_error, pipeline_error};

/// Parses TOML text into JSON text (tables as objects, in the file's order).
#[pyfunction]
pub fn toml_to_json(py: Python<'_>, text: &str) -> PyResult<String> {
    let value: toml::Value = toml::from_str(text).map_err(|e| syntax_error(py, text, &e))?;
    serde_json::to_string(&value).map_err(|e| pipeline_error(py, e.to_string(), &[]))
}

/// Writes JSON text (an object) as TOML text.
#[pyfunction]
pub fn json_to_toml(py: Python<'_>, json: &str) -> PyResult<String> {
    let value: toml::Value = serde_json::from_str(json).map_err(|e| {
        pipeline_error(py, format!("a pipeline must be a table of keys and values that TOML can hold: {e}"), &[])
    })?;
    toml::to_string(&value).map_err(|e| {
        pipeline_error(py, format!("a pipeline must be a table of keys and values that TOML can hold: {e}"), &[])
    })
}

/// The pipeline file with every default, as TOML.
#[pyfunction]
pub fn default_toml(py: Python<'_>) -> PyResult<String> {
    toml::to_string(&PipelineFile::default()).map_err(|e| pipeline_error(py, e.to_string(), &[]))
}

/// Validates pipeline TOML `text` (named `name` when it has no `name`; files it names read from
/// `base`) and returns its name, hash, seeds and warnings.
#[pyfunction]
#[pyo3(signature = (text, name, base, source=None))]
pub fn validate<'py>(
    py: Python<'py>,
    text: &str,
    name: &str,
    base: PathBuf,
    source: Option<PathBuf>,
) -> PyResult<Bound<'py, PyDict>> {
    let p = load(py, text, name, &base, source)?;
    let d = PyDict::new(py);
    d.set_item("name", &p.name)?;
    d.set_item("hash", &p.hash)?;
    d.set_item("seeds", &p.seeds)?;
    d.set_item("fault", p.scene.is_fault())?;
    let warnings: Vec<(String, String, String)> =
        p.warnings.iter().map(|w| (w.field.clone(), w.value.clone(), w.why.clone())).collect();
    d.set_item("warnings", warnings)?;
    Ok(d)
}

/// A validated pipeline from TOML text, as `stickslip pipeline` reads a file: `source` is the
/// file it came from, if any (the output folder keeps a copy of `text` either way).
pub fn load(py: Python<'_>, text: &str, name: &str, base: &Path, source: Option<PathBuf>) -> PyResult<Pipeline> {
    let file: PipelineFile = toml::from_str(text).map_err(|e| syntax_error(py, text, &e))?;
    let mut p = Pipeline::from_file_in(file, name, base).map_err(|e| config_error(py, e))?;
    p.source = source;
    p.text = Some(text.to_string());
    Ok(p)
}

/// A TOML error as a refused field: the dotted key of the line it points at (its `[table]`
/// header and key), the value written there and what TOML or the pipeline's schema expected.
fn syntax_error(py: Python<'_>, text: &str, e: &toml::de::Error) -> PyErr {
    // Rust's type names as a user reads them.
    let message =
        [("i64", "an integer"), ("u64", "a whole number ≥ 0"), ("f64", "a number"), ("usize", "a whole number ≥ 0")]
            .iter()
            .fold(e.message().trim().to_string(), |m, (rust, words)| {
                m.replace(&format!("expected {rust}"), &format!("expected {words}"))
            });
    let Some(span) = e.span() else { return pipeline_error(py, message, &[]) };
    let field = field_at(text, span.start);
    let line_start = text[..span.start.min(text.len())].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[line_start..].find('\n').map_or(text.len(), |i| line_start + i);
    let line = &text[line_start..line_end];
    let value = line.split_once('=').map_or(line, |(_, v)| v).trim().to_string();
    let allowed = match message.split_once("expected ") {
        Some((_, expected)) => format!("expected {expected}"),
        None => message.clone(),
    };
    let line_no = text[..line_start].matches('\n').count() + 1;
    let full = format!("line {line_no}: {message}");
    match field {
        Some(field) => pipeline_error(py, full, &[FieldError { field, value, allowed }]),
        None => pipeline_error(py, full, &[]),
    }
}

/// The dotted key of the `key = value` line holding byte `at`: the last `[table]` or
/// `[[array]]` header above it, then the key.
fn field_at(text: &str, at: usize) -> Option<String> {
    let at = at.min(text.len());
    let line_start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    let line = text[line_start..].lines().next().unwrap_or("").trim();
    // A table header of its own (an unknown `[table]`): the table is the field.
    if line.starts_with('[') && !line.contains('=') {
        return Some(line.trim_matches(|c| c == '[' || c == ']').trim().to_string());
    }
    let key = line.split_once('=').map(|(k, _)| k.trim().trim_matches('"').to_string());
    let table = text[..line_start].lines().rev().find_map(|l| {
        let l = l.trim();
        l.starts_with('[').then(|| l.trim_matches(|c| c == '[' || c == ']').trim().to_string())
    });
    match (table, key) {
        (Some(t), Some(k)) => Some(format!("{t}.{k}")),
        (None, Some(k)) => Some(k),
        (Some(t), None) => Some(t),
        (None, None) => None,
    }
}
