//! Accelerograms: standard processing ([`processing`]), the band a record is filtered to and used
//! in ([`band`]), and the file formats of a record.
//!
//! Every format a record can be written in is one file here implementing [`RecordFormat`] and
//! listed in [`FORMATS`]: PEER `.AT2` ([`at2`]), SAC binary ([`sac`]), MiniSEED 2 ([`mseed`]) and
//! CSV ([`csv`]); a pipeline names them in `accelerograms.formats` by [`RecordFormat::name`]. The
//! Parquet form of a record is the output folder's `accelerograms` table. [`read_accelerogram`]
//! reads them back (AT2, SAC and the product's own MiniSEED by extension or content, anything
//! else as CSV).

pub mod at2;
pub mod band;
pub mod csv;
pub mod filter;
pub mod mseed;
pub mod processing;
pub mod resample;
pub mod sac;

use std::path::Path;

use crate::error::SeismoError;

pub use at2::{At2, at2_text, parse_at2, parse_npts_dt};
pub use csv::{Csv, parse_csv};
pub use mseed::Mseed;
pub use sac::Sac;

pub use crate::spectra::intensity::G;

/// A uniformly sampled acceleration record.
#[derive(Clone, Debug, PartialEq)]
pub struct Accelerogram {
    /// Sampling interval (s).
    pub dt: f64,
    /// Accelerations (m/s²).
    pub accel: Vec<f64>,
    /// Free text describing the record.
    pub description: String,
}

/// Units of acceleration in a CSV file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelUnit {
    /// Standard gravity.
    G,
    /// m/s².
    MetrePerSecond2,
    /// cm/s² (gal).
    CentimetrePerSecond2,
}

impl AccelUnit {
    /// Factor to m/s².
    pub fn to_si(self) -> f64 {
        match self {
            AccelUnit::G => G,
            AccelUnit::MetrePerSecond2 => 1.0,
            AccelUnit::CentimetrePerSecond2 => 0.01,
        }
    }
}

/// A record as every file format takes it: one component at one scale, SI units.
#[derive(Clone, Copy, Debug)]
pub struct RecordFile<'a> {
    /// One line saying what the record is (pipeline, seed, node, component, scale, band).
    pub description: &'a str,
    /// Acceleration (m/s²).
    pub accel_m_s2: &'a [f64],
    /// Sampling interval (s).
    pub dt_s: f64,
    /// Time of the first sample on the run's clock (s).
    pub begin_s: f64,
    /// Velocity (m/s) and displacement (m) of the processed record, when known.
    pub motion: Option<(&'a [f64], &'a [f64])>,
    /// Station name, e.g. the node (`N36`).
    pub station: &'a str,
    /// Component name (`X`, `Y`, `Z`).
    pub component: &'a str,
    /// Network code.
    pub network: &'a str,
    /// Location code (`M`: model scale, `P`: prototype scale).
    pub location: &'a str,
    /// Event name (`S2`, `E17`, `run`).
    pub event: &'a str,
    /// Station position (m, the scale's coordinates), when it is a point of the scene.
    pub position_m: Option<[f64; 3]>,
    /// Orientation of the component, when it is an axis of the scene.
    pub orientation: Option<Orientation>,
    /// Moment magnitude of the event, when known.
    pub magnitude: Option<f64>,
    /// The event's origin on the record's clock (s), when known (a scenario's rupture starts at
    /// 0): SAC then carries it as `O`, with the nominal reference time [`sac::NOMINAL_ORIGIN`].
    pub origin_s: Option<f64>,
    /// Further numbers in labelled groups (e.g. `("USABLE", [low, high])` in Hz), in order.
    pub numbers: &'a [(&'a str, &'a [f64])],
}

/// Orientation of a component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orientation {
    /// Incidence from vertical (deg): 0 up, 90 horizontal.
    pub incidence_deg: f64,
    /// Azimuth (deg clockwise from north, y being north and x east).
    pub azimuth_deg: f64,
}

impl Orientation {
    /// The orientation of axis `x`, `y` or `z` of the scene (x east, y north, z up).
    pub fn of_axis(axis: &str) -> Option<Orientation> {
        match axis {
            "x" => Some(Orientation { incidence_deg: 90.0, azimuth_deg: 90.0 }),
            "y" => Some(Orientation { incidence_deg: 90.0, azimuth_deg: 0.0 }),
            "z" => Some(Orientation { incidence_deg: 0.0, azimuth_deg: 0.0 }),
            _ => None,
        }
    }
}

/// A file format of records: a new format is a file implementing this and its entry in
/// [`FORMATS`].
pub trait RecordFormat: std::fmt::Debug + Sync {
    /// Name in pipeline files (`accelerograms.formats`).
    fn name(&self) -> &'static str;
    /// File extension.
    fn extension(&self) -> &'static str;
    /// The bytes of the file holding `record`.
    fn encode(&self, record: &RecordFile<'_>) -> Result<Vec<u8>, SeismoError>;
}

impl PartialEq for dyn RecordFormat {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

/// Every record format, in the order the documentation lists them.
pub const FORMATS: &[&dyn RecordFormat] = &[&At2, &Sac, &Mseed, &Csv];

/// The format named `name` (as in [`RecordFormat::name`]).
pub fn format_named(name: &str) -> Option<&'static dyn RecordFormat> {
    FORMATS.iter().copied().find(|f| f.name() == name)
}

/// Whether `bytes` are a SAC file: its header version (`NVHDR`, 6 or 7) where SAC keeps it, in
/// either byte order (a text file has no NUL bytes there).
pub fn is_sac(bytes: &[u8]) -> bool {
    let at = 4 * (70 + 6);
    bytes.len() >= sac::HEADER_BYTES && {
        let w = [bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]];
        matches!(i32::from_le_bytes(w), 6 | 7) || matches!(i32::from_be_bytes(w), 6 | 7)
    }
}

/// Reads an accelerogram file, its format told by its content: MiniSEED as this product writes it
/// (by the extension `.mseed`; values in m/s²), SAC (either byte order, as this
/// product and ObsPy write it; `IACC` values in nm/s², values of unknown unit in `unit`), PEER
/// `.AT2` (by extension or its `PEER` first line), otherwise text: a time column and an
/// acceleration column in `unit`, separated by commas, semicolons, tabs or whitespace (the
/// product's CSV records included).
pub fn read_accelerogram(path: &Path, unit: AccelUnit) -> Result<Accelerogram, SeismoError> {
    let bytes = std::fs::read(path).map_err(|source| SeismoError::Io { path: path.to_path_buf(), source })?;
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("mseed")) {
        let trace = mseed::parse_mseed(&bytes)
            .map_err(|e| SeismoError::Format { path: path.to_path_buf(), what: e.to_string() })?;
        let description = trace.codes.iter().filter(|s| !s.is_empty()).cloned().collect::<Vec<_>>().join(".");
        return Ok(Accelerogram { dt: 1.0 / trace.sample_rate_hz, accel: trace.samples, description });
    }
    if is_sac(&bytes) {
        let trace = sac::parse_sac(&bytes, path)?;
        let m = &trace.meta;
        let description = [&m.network, &m.station, &m.location, &m.component, &m.event]
            .iter()
            .filter(|s| !s.is_empty())
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join(" ");
        let accel = if trace.idep == sac::IACC {
            trace.accel_si()?
        } else {
            // A trace that does not say its unit: the unit the caller gives.
            trace.accel_si()?.iter().map(|v| v * unit.to_si()).collect()
        };
        return Ok(Accelerogram { dt: trace.dt, accel, description });
    }
    let text = String::from_utf8(bytes).map_err(|_| SeismoError::Format {
        path: path.to_path_buf(),
        what: "neither a SAC file (no SAC header) nor text (AT2, CSV or columns of numbers)".into(),
    })?;
    let is_at2 = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("at2")) || text.starts_with("PEER");
    if is_at2 { parse_at2(&text, path) } else { parse_csv(&text, unit, path) }
}
