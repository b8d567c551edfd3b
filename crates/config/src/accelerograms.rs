//! `[accelerograms]`: the records a pipeline hands to engineers (docs/model.md §8): which events
//! and nodes get one, the window around each event, the standard processing and the files.
//!
//! A record is the acceleration of one control node and component from `pre_event_s` before an
//! event's start to `post_event_s` after its end (clipped to the shear stage), or the whole shear
//! stage (`records = "whole_run"`). It is processed the usual way for strong-motion data (Boore &
//! Bommer 2005; PEER NGA-West2, Ancheta et al. 2014): mean removal, cosine tapers, zero pads at each
//! end, an acausal Butterworth band-pass, optionally a polynomial baseline, then velocity and
//! displacement by the trapezoidal rule (`stickslip_seismo::accelerogram::processing`).
//!
//! **The usable band** of a record, at model scale (prototype: divided by λ):
//! - high end: the lattice's own resolution `f_max` — the frequency where the phase velocity of
//!   plane waves departs by `band_tolerance` from its long-wave value
//!   (`stickslip_solver::dispersion`) — or the given `high_corner_hz` if lower; the filter's high
//!   corner defaults to it;
//! - low end: `1.25·f_low`, the filter's low corner times the NGA-West2 factor (the lowest usable
//!   frequency of a record filtered at `f_low`), with `f_low` defaulting to `1/T` for a record of
//!   duration `T` (one cycle of the corner frequency fits in the record).

use serde::{Deserialize, Serialize};
use stickslip_analysis::settings::{AccelerogramSettings, EventChoice, MeanChoice, RecordSpan};
use stickslip_seismo::accelerogram::processing::{MAX_CORNER_OF_NYQUIST, USABLE_LOW_FACTOR};
use stickslip_seismo::accelerogram::{At2, FORMATS, Mseed, RecordFormat, Sac};
use stickslip_solver::NodeId;
use stickslip_solver::scene::{Kinematic, Scene};

use crate::check::{Checker, Named, approx};

impl Named for RecordSpan {
    const ALL: &'static [Self] = &[RecordSpan::Events, RecordSpan::WholeRun];
    fn name(self) -> &'static str {
        match self {
            RecordSpan::Events => "events",
            RecordSpan::WholeRun => "whole_run",
        }
    }
}

impl Named for EventChoice {
    const ALL: &'static [Self] = &[EventChoice::Main, EventChoice::All];
    fn name(self) -> &'static str {
        match self {
            EventChoice::Main => "main",
            EventChoice::All => "all",
        }
    }
}

impl Named for MeanChoice {
    const ALL: &'static [Self] = &[MeanChoice::PreEvent, MeanChoice::Whole, MeanChoice::None];
    fn name(self) -> &'static str {
        match self {
            MeanChoice::PreEvent => "pre_event",
            MeanChoice::Whole => "whole",
            MeanChoice::None => "none",
        }
    }
}

impl Named for &'static dyn RecordFormat {
    const ALL: &'static [Self] = FORMATS;
    fn name(self) -> &'static str {
        RecordFormat::name(self)
    }
}

/// `[accelerograms]` as written in a pipeline file.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct AccelerogramsSection {
    /// `"events"` (default: one record per selected event) or `"whole_run"`.
    pub records: String,
    /// `"main"` (default: main shocks) or `"all"` (every event with a drop ≥ `min_drop_pa`).
    pub events: String,
    /// With `events = "all"`: the smallest stress drop that gets a record (Pa). Default 0.
    pub min_drop_pa: f64,
    /// Control nodes (LDEM numbers) that get records; empty = every control node recording
    /// acceleration.
    pub nodes: Vec<i64>,
    /// Window before an event's start (s, model scale). Default 2e-3.
    pub pre_event_s: f64,
    /// Window after an event's end, to keep the coda (s, model scale). Default 20e-3.
    pub post_event_s: f64,
    /// Zero level: `"pre_event"` (default), `"whole"` or `"none"`.
    pub mean: String,
    /// Cosine taper at each end, as a fraction of the record's duration. Default 0.05.
    pub taper: f64,
    /// Zero pads of `1.5·order/f_low` at each end before filtering (Converse & Brady). Default true.
    pub pad: bool,
    /// Butterworth order of the acausal band-pass. Default 4.
    pub filter_order: i64,
    /// Low corner (Hz, model scale); 0 = `1/T` for a record of duration `T`. Default 0.
    pub low_corner_hz: f64,
    /// High corner (Hz, model scale); 0 = the lattice's `f_max`. Default 0.
    pub high_corner_hz: f64,
    /// Phase-velocity departure that defines the lattice's `f_max`. Default 0.05.
    pub band_tolerance: f64,
    /// Degree of the polynomial baseline fitted to the displacement; 0 = none. Default 0.
    pub baseline_degree: i64,
    /// Files written per record, at model and prototype scale: any of `"at2"`, `"sac"`, `"mseed"`,
    /// `"csv"`. Default `["at2", "sac", "mseed"]`. Every record is also in the `accelerograms` table.
    pub formats: Vec<String>,
}

impl Default for AccelerogramsSection {
    fn default() -> Self {
        AccelerogramsSection {
            records: RecordSpan::Events.name().into(),
            events: EventChoice::Main.name().into(),
            min_drop_pa: 0.0,
            nodes: vec![],
            pre_event_s: 2e-3,
            post_event_s: 20e-3,
            mean: MeanChoice::PreEvent.name().into(),
            taper: 0.05,
            pad: true,
            filter_order: 4,
            low_corner_hz: 0.0,
            high_corner_hz: 0.0,
            band_tolerance: 0.05,
            baseline_degree: 0,
            formats: vec![At2.name().into(), Sac.name().into(), Mseed.name().into()],
        }
    }
}

impl AccelerogramsSection {
    /// The settings for `scene`, every refused value recorded in `ck`.
    pub fn build(&self, scene: &Scene, ck: &mut Checker) -> AccelerogramSettings {
        let span = ck.named("accelerograms.records", &self.records).unwrap_or(RecordSpan::Events);
        let events = ck.named("accelerograms.events", &self.events).unwrap_or(EventChoice::Main);
        ck.non_negative("accelerograms.min_drop_pa", self.min_drop_pa);
        let window_ok = ck.non_negative("accelerograms.pre_event_s", self.pre_event_s)
            & ck.non_negative("accelerograms.post_event_s", self.post_event_s);
        let mean = ck.named("accelerograms.mean", &self.mean).unwrap_or(MeanChoice::PreEvent);
        ck.range("accelerograms.taper", self.taper, 0.0, false, 0.5, false);
        let order = ck.count("accelerograms.filter_order", self.filter_order, 1, 16, "").unwrap_or(4) as u32;
        let corners_ok = ck.non_negative("accelerograms.low_corner_hz", self.low_corner_hz)
            & ck.non_negative("accelerograms.high_corner_hz", self.high_corner_hz);
        if self.low_corner_hz > 0.0 && self.high_corner_hz > 0.0 && self.high_corner_hz <= self.low_corner_hz {
            ck.push(
                "accelerograms.high_corner_hz",
                self.high_corner_hz,
                format!("above low_corner_hz ({} Hz), or 0 for the lattice's f_max", approx(self.low_corner_hz)),
            );
        }
        let tolerance_ok = ck.range("accelerograms.band_tolerance", self.band_tolerance, 0.0, true, 0.5, true);
        let baseline_degree = match self.baseline_degree {
            0 => None,
            d => ck.count("accelerograms.baseline_degree", d, 2, 10, " (or 0 for none)"),
        };
        if self.min_drop_pa > 0.0 && events == EventChoice::Main {
            ck.push(
                "accelerograms.min_drop_pa",
                self.min_drop_pa,
                "0 with events = \"main\" (the threshold chooses among all events: set events = \"all\")",
            );
        }
        let formats = ck.named_list("accelerograms.formats", &self.formats);
        let nodes = self.nodes(scene, ck);
        let (resolved_hz, top) = self.band(scene, ck);
        let shortest = self.pre_event_s + self.post_event_s;
        let run = scene.shear.duration_s;
        if span == RecordSpan::Events && window_ok && shortest >= run {
            ck.push(
                "accelerograms.post_event_s",
                self.post_event_s,
                format!(
                    "a window shorter than the shear stage: pre_event_s + post_event_s = {} s ≥ shear.duration_s = \
                     {} s makes every event's record the whole run (for that, records = \"whole_run\")",
                    approx(shortest),
                    approx(run)
                ),
            );
        }
        let low = if self.low_corner_hz > 0.0 { self.low_corner_hz } else { 1.0 / shortest };
        if span == RecordSpan::Events && window_ok && corners_ok && tolerance_ok && !(USABLE_LOW_FACTOR * low < top) {
            ck.push(
                "accelerograms.post_event_s",
                self.post_event_s,
                format!(
                    "a window (pre_event_s + post_event_s = {} s) long enough for a usable band: the low corner \
                     {} Hz × {USABLE_LOW_FACTOR} must stay below the band's top {top:.1} Hz (the lattice's f_max, \
                     high_corner_hz or 0.8 of the sampling's Nyquist)",
                    approx(shortest),
                    approx(low)
                ),
            );
        }
        AccelerogramSettings {
            span,
            events,
            min_drop_pa: self.min_drop_pa,
            nodes,
            pre_event_s: self.pre_event_s,
            post_event_s: self.post_event_s,
            mean,
            taper: self.taper,
            pad: self.pad,
            order,
            low_corner_hz: (self.low_corner_hz > 0.0).then_some(self.low_corner_hz),
            high_corner_hz: (self.high_corner_hz > 0.0).then_some(self.high_corner_hz),
            band_tolerance: self.band_tolerance,
            resolved_hz,
            baseline_degree,
            formats,
        }
    }

    /// The control nodes recorded (`nodes`, every one recording acceleration when empty), refused
    /// when a node records no acceleration or is driven, or when the skip-ahead would sample
    /// them unevenly.
    fn nodes(&self, scene: &Scene, ck: &mut Checker) -> Vec<NodeId> {
        let control = &scene.record.control;
        let mut nodes = Vec::new();
        for (i, &n) in self.nodes.iter().enumerate() {
            match control.iter().find(|c| c.quantity == Kinematic::Acceleration && c.node.ldem() as i64 == n) {
                Some(c) => nodes.push(c.node),
                None => ck.push(
                    format!("accelerograms.nodes[{i}]"),
                    n,
                    "a control node that records acceleration ([[record.control]])",
                ),
            }
        }
        // A driven node's acceleration is prescribed (Eq. 12), not a response of the block.
        let drivers = scene.drivers();
        let describe = |id: NodeId| {
            let p = scene.lattice().position(id);
            format!("LDEM {} at ({}, {}, {}) m", id.ldem(), approx(p[0]), approx(p[1]), approx(p[2]))
        };
        let driven_why = "a node that is not driven by [shear]: a driven node's acceleration is the prescribed \
                          motion (Eq. 12), and its record would be the driver's, not the block's response";
        if self.nodes.is_empty() {
            let mut driven: Vec<NodeId> = control
                .iter()
                .filter(|c| c.quantity == Kinematic::Acceleration && drivers.contains(&c.node))
                .map(|c| c.node)
                .collect();
            driven.dedup();
            if !driven.is_empty() {
                ck.push(
                    "record.control",
                    driven.iter().map(|&id| describe(id)).collect::<Vec<_>>().join("; "),
                    format!(
                        "{driven_why}; leave it out of [[record.control]], or list the nodes to record in \
                         accelerograms.nodes"
                    ),
                );
            }
        }
        for (i, &n) in self.nodes.iter().enumerate() {
            if let Some(&id) = drivers.iter().find(|d| d.ldem() as i64 == n) {
                ck.push(format!("accelerograms.nodes[{i}]"), describe(id), driven_why);
            }
        }
        if !control.iter().any(|c| c.quantity == Kinematic::Acceleration) {
            ck.push(
                "accelerograms",
                "(present)",
                "control nodes that record acceleration ([[record.control]] quantities = [\"acceleration\"])",
            );
        }
        if scene.skip_ahead.enabled
            && scene.skip_ahead.record_interval_s.is_some_and(|iv| Some(iv) != scene.record.interval_s)
        {
            ck.push(
                "accelerograms",
                "(present)",
                "uniformly sampled records: without skip_ahead.record_interval_s (the skip-ahead would sample quiet \
                 phases more sparsely, and records need one sampling interval)",
            );
        }
        nodes
    }

    /// The lattice's f_max at `band_tolerance` and the top of the records' band: the lattice's
    /// f_max, `high_corner_hz`, or 0.8 of the sampling's Nyquist, the lowest (warned when the
    /// sampling cuts the lattice's band).
    fn band(&self, scene: &Scene, ck: &mut Checker) -> (f64, f64) {
        let resolved_hz = match scene.usable_band(self.band_tolerance.clamp(1e-6, 0.49)) {
            Ok(b) => b.f_max_hz,
            Err(e) => {
                ck.push("accelerograms", "(present)", format!("a lattice whose dispersion can be computed: {e}"));
                f64::INFINITY
            }
        };
        let top = self.high_corner_hz.clamp(0.0, resolved_hz);
        let top = if top > 0.0 { top } else { resolved_hz };
        // The sampling cuts the band too: the filter's corner stays below 0.8 of Nyquist.
        let interval = scene.record.interval_s.filter(|v| *v > 0.0 && v.is_finite());
        let sampled_top = interval.map_or(f64::INFINITY, |iv| MAX_CORNER_OF_NYQUIST * 0.5 / iv);
        if let Some(iv) = interval
            && sampled_top < resolved_hz
            && resolved_hz.is_finite()
        {
            ck.warn(
                "record.interval_s",
                iv,
                format!(
                    "records sampled every {} s are band-limited to {:.1} Hz ({MAX_CORNER_OF_NYQUIST} of Nyquist), \
                     below the lattice's f_max = {:.1} Hz: the peaks between samples are missed, so PGA and the \
                     short-period spectra read low; record every {} s or less to keep the lattice's band",
                    approx(iv),
                    sampled_top,
                    resolved_hz,
                    approx(MAX_CORNER_OF_NYQUIST * 0.5 / resolved_hz)
                ),
            );
        }
        let top = top.min(sampled_top);
        (resolved_hz, top)
    }
}
