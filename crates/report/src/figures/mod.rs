//! The figures of the report, each from the tables of the output folder, drawn with the chart
//! layer of [`crate::charts`] (clipped to the axes, labels placed where no data is).
//!
//! This module is the registry: every figure in page order ([`ALL`]), the signature of one
//! ([`Draw`]) and what drawing it gave ([`Outcome`]). The figures live by topic: the sliding
//! interface (`interface`), accelerograms and records (`records`), spectra (`spectra`), main
//! shocks across seeds (`events`), the fault (`fault`), a fault scene's rupture (`rupture`), its stations against the
//! ground-motion models (`gmm`), cracks
//! (`cracks`) and the event catalogue
//! (`catalogue`); what several topics share is in `common`.

mod broadband;
mod catalogue;
mod common;
mod cracks;
mod events;
mod fault;
mod gmm;
mod interface;
mod records;
mod rupture;
mod spectra;

use std::path::Path;

use crate::error::ReportError;
use crate::input::ReportInput;

pub use common::{MAX_NODES, NodeChannel, spread};
pub use interface::LONG_RUN_MAIN_SHOCKS;
pub use spectra::{EVERY_RECORD_UP_TO, RecordSpectraPlot, record_figure};

/// What drawing a figure gave.
pub enum Outcome {
    /// Drawn, with its heading and caption.
    Drawn {
        /// Heading.
        title: String,
        /// What it shows.
        caption: String,
        /// The texts drawn as titles on the image: the sheet's, then each panel's (empty ones left
        /// out).
        headings: Vec<String>,
        /// The name of each panel (empty for a panel without one), in drawing order.
        panels: Vec<String>,
        /// Labels not drawn for want of a free spot (see [`crate::charts::DrawnPanel::dropped`]).
        dropped: Vec<String>,
    },
    /// Not drawn, and why.
    Skipped(String),
}

/// The figures a fault scene's page leaves out, and why: they measure events by the paper's
/// similarity scaling of a block (magnitudes at a prototype scale λ, stress drop against
/// duration, a catalogue's statistics), while a fault scene is at its own scale and its rupture is
/// measured from the fault's slip (the `source` table, which the page leads with).
pub const LEFT_OUT_ON_A_FAULT: [(&str, &str); 9] = [
    ("acceleration_s2.png", "the paper's window around a block's second main shock"),
    ("stress_drop_vs_duration.png", "the paper's stress drop against slip-burst duration"),
    ("recurrence.png", "the paper's recurrence of a block's main shocks"),
    ("magnitude.png", "magnitudes at the paper's prototype scale λ"),
    ("catalogue.png", "an event catalogue's magnitudes from the similarity scaling"),
    ("magnitude_frequency.png", "a Gutenberg–Richter fit, which needs a catalogue, not one rupture per seed"),
    ("recurrence_fits.png", "renewal fits of a catalogue's recurrence"),
    ("aftershocks.png", "Omori–Utsu decay of a catalogue's aftershocks"),
    ("scaling.png", "the similarity scaling of moment with area and duration"),
];

/// Why a fault scene's page leaves `file` out, if it does.
pub fn left_out_on_a_fault(file: &str) -> Option<&'static str> {
    LEFT_OUT_ON_A_FAULT.iter().find(|(f, _)| *f == file).map(|(_, why)| *why)
}

/// Draws one figure into a file.
pub type Draw = fn(&ReportInput, &Path) -> Result<Outcome, ReportError>;

/// Every figure, in page order.
pub const ALL: [(&str, Draw); 28] = [
    ("shear_stress.png", interface::shear_stress),
    ("normal_stress.png", interface::normal_stress),
    ("mean_slip.png", interface::mean_slip),
    ("acceleration_s2.png", records::acceleration_s2),
    ("acceleration_run.png", records::acceleration_run),
    ("records.png", records::event_records),
    ("response_spectra_z.png", spectra::spectra_z),
    ("response_spectra_x.png", spectra::spectra_x),
    ("fourier.png", spectra::fourier),
    ("record_set.png", spectra::record_set),
    ("stress_drop_vs_duration.png", events::drop_vs_duration),
    ("recurrence.png", events::recurrence),
    ("magnitude.png", events::magnitude),
    ("attenuation.png", events::attenuation),
    ("energy.png", interface::energy),
    ("friction_map.png", fault::friction_map),
    ("space_time.png", fault::space_time),
    ("rupture_time.png", rupture::rupture_time),
    ("ground_motion.png", rupture::ground_motion),
    ("broadband_record.png", broadband::broadband_record),
    ("gmm_bias.png", gmm::gmm_bias),
    ("cracks.png", cracks::crack_map),
    ("acoustic_emission.png", cracks::emission),
    ("catalogue.png", catalogue::overview),
    ("magnitude_frequency.png", catalogue::magnitude_frequency),
    ("recurrence_fits.png", catalogue::recurrence_fits),
    ("aftershocks.png", catalogue::aftershocks),
    ("scaling.png", catalogue::scaling),
];
