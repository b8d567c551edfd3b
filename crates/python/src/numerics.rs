//! The product's numerics on arrays from Python: the exact piecewise-linear oscillator's response
//! spectra and RotD (the functions `stickslip spectra` and the analysis call), the paper's
//! similarity scaling with its magnitudes, and the record files the product reads.

use std::path::PathBuf;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stickslip_seismo::accelerogram::{AccelUnit, read_accelerogram};
use stickslip_seismo::similarity::{AreaChoice, ModelEvent, SimilarityParams, scale};
use stickslip_seismo::spectra::response::{Reading, SpectrumPlan, SpectrumScratch};
use stickslip_seismo::spectra::rotd::{RotDPlan, RotDScratch, RotDSpectrum};

/// Oversampling of a band-limited reading, as the CLI's `spectra` uses.
const OVERSAMPLING: usize = 16;

fn reading(band_limited: bool) -> Reading {
    if band_limited { Reading::BandLimited } else { Reading::Linear }
}

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Spectral displacements SD (m for m/s²) of `accel` sampled every `dt` s, damping-major over
/// `periods` × `dampings`, as `stickslip spectra` computes them.
#[pyfunction]
#[pyo3(signature = (accel, dt, periods, dampings, band_limited=false))]
pub fn response_spectrum(
    py: Python<'_>,
    accel: Vec<f64>,
    dt: f64,
    periods: Vec<f64>,
    dampings: Vec<f64>,
    band_limited: bool,
) -> PyResult<Vec<f64>> {
    py.detach(|| {
        let plan = SpectrumPlan::new(dt, &periods, &dampings, reading(band_limited), OVERSAMPLING)?;
        let mut sd = vec![0.0; plan.len()];
        plan.compute(&accel, &mut SpectrumScratch::default(), &mut sd)?;
        Ok(sd)
    })
    .map_err(|e: stickslip_seismo::spectra::response::SpectrumError| value_error(e))
}

/// RotD50 SD, RotD100 SD, the azimuth of RotD100 (degrees), x's SD and y's SD.
type RotDArrays = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

/// RotD50 and RotD100 spectral displacements of the horizontal pair `x`, `y` (damping-major),
/// the azimuth of RotD100 and each component's own SD.
#[pyfunction]
#[pyo3(signature = (x, y, dt, periods, dampings, band_limited=false))]
pub fn rotd(
    py: Python<'_>,
    x: Vec<f64>,
    y: Vec<f64>,
    dt: f64,
    periods: Vec<f64>,
    dampings: Vec<f64>,
    band_limited: bool,
) -> PyResult<RotDArrays> {
    let s = py
        .detach(|| {
            let plan = RotDPlan::new(dt, &periods, &dampings, reading(band_limited), OVERSAMPLING)?;
            let mut out = RotDSpectrum::default();
            plan.compute(&x, &y, &mut RotDScratch::default(), &mut out)?;
            Ok(out)
        })
        .map_err(|e: stickslip_seismo::spectra::response::SpectrumError| value_error(e))?;
    Ok((s.rotd50, s.rotd100, s.rotd100_angle_deg, s.x, s.y))
}

/// One model event scaled to its prototype by the paper's similarity rules, with its moments and
/// magnitudes (Riera's and Mw).
#[pyfunction]
#[pyo3(signature = (stress_drop_pa, model_length_m, model_area_m2, model_rate_m_s, duration_s=None, recurrence_s=None, prototype_length_m=1.0e4, prototype_rate_m_s=3.17e-10))]
#[allow(clippy::too_many_arguments)]
pub fn similarity<'py>(
    py: Python<'py>,
    stress_drop_pa: f64,
    model_length_m: f64,
    model_area_m2: f64,
    model_rate_m_s: f64,
    duration_s: Option<f64>,
    recurrence_s: Option<f64>,
    prototype_length_m: f64,
    prototype_rate_m_s: f64,
) -> PyResult<Bound<'py, PyDict>> {
    for (name, v) in [
        ("stress_drop_pa", stress_drop_pa),
        ("model_length_m", model_length_m),
        ("model_area_m2", model_area_m2),
        ("model_rate_m_s", model_rate_m_s),
        ("prototype_length_m", prototype_length_m),
        ("prototype_rate_m_s", prototype_rate_m_s),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(crate::errors::pipeline_error(
                py,
                format!("{name} = {v} is not allowed: a finite value > 0"),
                &[stickslip_config::FieldError {
                    field: name.into(),
                    value: v.to_string(),
                    allowed: "a finite value > 0".into(),
                }],
            ));
        }
    }
    let event = ModelEvent { stress_drop_pa, model_length_m, model_area_m2, duration_s, recurrence_s, model_rate_m_s };
    let params = SimilarityParams { prototype_length_m, prototype_rate_m_s, area: AreaChoice::Contact };
    let s = scale(&event, &params);
    let m = s.magnitudes();
    let d = PyDict::new(py);
    d.set_item("lambda", s.lambda)?;
    d.set_item("prototype_area_m2", s.prototype_area_m2)?;
    d.set_item("prototype_duration_s", s.prototype_duration_s)?;
    d.set_item("prototype_recurrence_s", s.prototype_recurrence_s)?;
    d.set_item("m0_paper_dyne_cm", s.m0_paper_dyne_cm)?;
    d.set_item("m0_consistent_dyne_cm", s.m0_consistent_dyne_cm)?;
    d.set_item("m_riera_paper_interplate", m.riera_paper_interplate)?;
    d.set_item("m_riera_paper_intraplate", m.riera_paper_intraplate)?;
    d.set_item("m_riera_consistent_interplate", m.riera_consistent_interplate)?;
    d.set_item("m_riera_consistent_intraplate", m.riera_consistent_intraplate)?;
    d.set_item("mw_paper", m.mw_paper)?;
    d.set_item("mw_consistent", m.mw_consistent)?;
    Ok(d)
}

/// A record file as the product reads it (SAC, PEER AT2, its own MiniSEED, text columns):
/// `(dt, accel in m/s², description)`; `units` of a text file: `"m/s2"`, `"cm/s2"` or `"g"`.
#[pyfunction]
#[pyo3(signature = (path, units="m/s2"))]
pub fn read_record(path: PathBuf, units: &str) -> PyResult<(f64, Vec<f64>, String)> {
    let unit = match units {
        "m/s2" => AccelUnit::MetrePerSecond2,
        "cm/s2" => AccelUnit::CentimetrePerSecond2,
        "g" => AccelUnit::G,
        other => {
            return Err(value_error(format!("units = {other:?} is not allowed: one of \"m/s2\", \"cm/s2\", \"g\"")));
        }
    };
    if !path.exists() {
        return Err(pyo3::exceptions::PyFileNotFoundError::new_err(format!("{}: no such file", path.display())));
    }
    let r = read_accelerogram(&path, unit).map_err(value_error)?;
    Ok((r.dt, r.accel, r.description))
}
