//! What the analysis of a seed computes, as validated values: event detection, similarity,
//! records and their processing, spectra, acoustic emission (the configuration crate builds
//! these from a pipeline file's `[events]`, `[similarity]`, `[accelerograms]`, `[spectra]` and
//! `[rupture]` sections).

use stickslip_seismo::accelerogram::RecordFormat;
use stickslip_seismo::emission::ClusterParams;
use stickslip_seismo::events::EventParams;
use stickslip_seismo::similarity::SimilarityParams;
use stickslip_seismo::spectra::fourier::Window;
use stickslip_seismo::spectra::response::Reading;
use stickslip_solver::geometry::NodeId;
use stickslip_solver::scene::{ControlChannel, Kinematic};

/// Everything the analysis of one seed is asked to do.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Event detection.
    pub events: EventParams,
    /// Similarity scaling.
    pub similarity: SimilarityParams,
    /// Records, if asked (by `[accelerograms]` or `[spectra]`).
    pub accelerograms: Option<AccelerogramSettings>,
    /// Spectra of the records, if asked.
    pub spectra: Option<SpectraSettings>,
    /// How bar breaks group into acoustic-emission events, when the bars crack.
    pub emission: Option<ClusterParams>,
    /// Broadband records of a fault scene's surface stations, if asked (`[broadband]`).
    pub broadband: Option<crate::broadband::BroadbandSettings>,
}

/// Which stretches of the run become records.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RecordSpan {
    /// One record per selected event.
    Events,
    /// One record of the whole shear stage.
    WholeRun,
}

/// Which events get records.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventChoice {
    /// Main shocks only.
    Main,
    /// Every catalogued event whose stress drop is at least `min_drop_pa`.
    All,
}

/// How the record's zero level is set before processing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MeanChoice {
    /// The mean of the pre-event window (the whole record when it has none).
    PreEvent,
    /// The mean of the whole record.
    Whole,
    /// The record's own zero.
    None,
}

/// The records of a seed and their processing (docs/model.md §8).
#[derive(Clone, Debug, PartialEq)]
pub struct AccelerogramSettings {
    /// Events or the whole run.
    pub span: RecordSpan,
    /// Which events.
    pub events: EventChoice,
    /// Smallest drop of a non-main event with a record (Pa).
    pub min_drop_pa: f64,
    /// Nodes with records; empty = every control node recording acceleration.
    pub nodes: Vec<NodeId>,
    /// Window before the start (s).
    pub pre_event_s: f64,
    /// Window after the end (s).
    pub post_event_s: f64,
    /// Zero level.
    pub mean: MeanChoice,
    /// Taper fraction at each end.
    pub taper: f64,
    /// Zero pads.
    pub pad: bool,
    /// Butterworth order.
    pub order: u32,
    /// Low corner (Hz), `None` = `1/T`.
    pub low_corner_hz: Option<f64>,
    /// High corner (Hz), `None` = the lattice's `f_max`.
    pub high_corner_hz: Option<f64>,
    /// Departure that defines `f_max`.
    pub band_tolerance: f64,
    /// The lattice's `f_max` at that departure (Hz, model scale): the highest frequency a record
    /// can be used at.
    pub resolved_hz: f64,
    /// Baseline degree.
    pub baseline_degree: Option<usize>,
    /// Files per record.
    pub formats: Vec<&'static dyn RecordFormat>,
}

impl AccelerogramSettings {
    /// Whether control channel `c` gets records.
    pub fn wants(&self, c: &ControlChannel) -> bool {
        c.quantity == Kinematic::Acceleration && (self.nodes.is_empty() || self.nodes.contains(&c.node))
    }
}

/// What the spectra analysis computes.
#[derive(Clone, Debug, PartialEq)]
pub struct SpectraSettings {
    /// Damping ratios.
    pub dampings: Vec<f64>,
    /// Model-scale periods (s).
    pub periods: Vec<f64>,
    /// Reading of the samples.
    pub reading: Reading,
    /// Oversampling of the band-limited reading.
    pub oversampling: usize,
    /// Window of the Fourier spectrum.
    pub window: Window,
    /// RotD50 and RotD100 of nodes with both horizontal components.
    pub rotd: bool,
    /// Attenuation table and fit.
    pub attenuation: bool,
}
