//! The records of one seed (docs/model.md §8): for every selected event (or the whole run) and
//! every control node and component asked for, the acceleration over the event's window,
//! processed, with its usable band, intensity measures, and — when `[spectra]` asks — its response
//! and Fourier spectra and the RotD50/RotD100 of the node's two horizontal components; and the
//! attenuation of peak motions with distance from each main shock's hypocentre.
//!
//! Everything is computed at model scale; the tables rescale to the prototype (docs/model.md §9).

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

use crate::attenuation::{AttenuationRow, attenuation};
use crate::settings::{AccelerogramSettings, EventChoice, MeanChoice, RecordSpan, SpectraSettings};
use crate::thread_cpu_s;
use rustfft::FftPlanner;
use stickslip_seismo::SeismoError;
use stickslip_seismo::accelerogram::processing::{
    MeanRemoval, Padding, Processed, ProcessingOptions, RecordBand, process, record_interval,
};
use stickslip_seismo::events::Catalogue;
use stickslip_seismo::spectra::fourier::{FourierSpectrum, fourier_amplitude};
use stickslip_seismo::spectra::intensity::{Baseline, Intensity, intensity};
use stickslip_seismo::spectra::response::{SpectrumError, SpectrumPlan, SpectrumScratch};
use stickslip_seismo::spectra::rotd::{RotDPlan, RotDScratch, RotDSpectrum};
use stickslip_solver::geometry::NodeId;
use stickslip_solver::scene::{Component, ControlChannel};
use stickslip_solver::{Model, Recording};

/// What the analysis produced for one seed.
#[derive(Clone, Debug, Default)]
pub struct SeedRecords {
    /// One entry per record.
    pub records: Vec<RecordData>,
    /// RotD of the nodes with both horizontal records, per window.
    pub rotd: Vec<RotdData>,
    /// Records left out, with the reason (a window clipped by the run's ends too short for any
    /// usable band).
    pub left_out: Vec<String>,
    /// Attenuation rows (if asked).
    pub attenuation: Vec<AttenuationRow>,
    /// Where the time went (a profile; not part of any table).
    pub timings: RecordTimings,
}

/// CPU seconds spent on a seed's records, by stage.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RecordTimings {
    /// Cutting, processing (mean, tapers, pads, band-pass, integrals), intensity measures and
    /// Fourier spectra.
    pub records_s: f64,
    /// Response spectra of the records computed alone (z, and x or y without its pair).
    pub spectra_s: f64,
    /// RotD50/RotD100 of each horizontal pair, whose passes also give the pair's x and y
    /// response spectra.
    pub rotd_s: f64,
    /// Records whose spectra were computed alone.
    pub alone: usize,
    /// Pairs whose RotD (and spectra) were computed.
    pub pairs: usize,
}

/// One processed record and what was computed of it (model scale).
#[derive(Clone, Debug)]
pub struct RecordData {
    /// Name within the seed, e.g. `S2-n36-x`.
    pub id: String,
    /// Index of the event in the seed's catalogue (`None` for a whole-run record).
    pub event: Option<u32>,
    /// The event's label (`S2`, `E17`) or `run`.
    pub label: String,
    /// The control channel.
    pub channel: ControlChannel,
    /// Node position (m).
    pub position: [f64; 3],
    /// Run time of the window's first sample (s, shear stage).
    pub start_s: f64,
    /// Length of the window before the event's start (s).
    pub pre_event_s: f64,
    /// The seed's own sampling interval (s) and the samples of the window as recorded, before
    /// the record was resampled to the pipeline's interval.
    pub recorded_dt_s: f64,
    /// Samples of the window as recorded (its raw window in the `control` table).
    pub recorded_samples: u32,
    /// The processed record (padded acceleration, velocity, displacement).
    pub processed: Processed,
    /// Filter corners and usable band.
    pub band: RecordBand,
    /// Intensity measures of the processed record.
    pub intensity: Intensity,
    /// SD (m), damping-major over the spectra's periods; empty without spectra.
    pub sd: Vec<f64>,
    /// Fourier amplitude spectrum of the processed record, without spectra `None`.
    pub fourier: Option<FourierSpectrum>,
}

/// RotD50 and RotD100 of a node's two horizontal records of one window (model scale).
#[derive(Clone, Debug)]
pub struct RotdData {
    /// Name within the seed, e.g. `S2-n36-xy`.
    pub id: String,
    /// Index of the event (`None` for the whole run).
    pub event: Option<u32>,
    /// The event's label or `run`.
    pub label: String,
    /// The node.
    pub node: NodeId,
    /// The band both components can be used in.
    pub band: RecordBand,
    /// RotD50 SD (m), damping-major.
    pub sd50: Vec<f64>,
    /// RotD100 SD (m), damping-major.
    pub sd100: Vec<f64>,
}

/// Plans shared by the workers, one per sampling interval.
#[derive(Default)]
pub struct PlanCache {
    spectra: Mutex<HashMap<u64, Arc<SpectrumPlan>>>,
    rotd: Mutex<HashMap<u64, Arc<RotDPlan>>>,
}

impl PlanCache {
    fn spectrum(&self, dt: f64, s: &SpectraSettings) -> Result<Arc<SpectrumPlan>, SpectrumError> {
        let mut plans = self.spectra.lock().expect("plan cache lock");
        if let Some(p) = plans.get(&dt.to_bits()) {
            return Ok(p.clone());
        }
        let plan = Arc::new(SpectrumPlan::new(dt, &s.periods, &s.dampings, s.reading, s.oversampling)?);
        plans.insert(dt.to_bits(), plan.clone());
        Ok(plan)
    }

    fn rotd(&self, dt: f64, s: &SpectraSettings) -> Result<Arc<RotDPlan>, SpectrumError> {
        let mut plans = self.rotd.lock().expect("plan cache lock");
        if let Some(p) = plans.get(&dt.to_bits()) {
            return Ok(p.clone());
        }
        let plan = Arc::new(RotDPlan::new(dt, &s.periods, &s.dampings, s.reading, s.oversampling)?);
        plans.insert(dt.to_bits(), plan.clone());
        Ok(plan)
    }
}

struct Scratch {
    spectrum: SpectrumScratch,
    rotd: RotDScratch,
    fft: FftPlanner<f64>,
}

thread_local! {
    static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::new(Scratch {
        spectrum: SpectrumScratch::default(),
        rotd: RotDScratch::default(),
        fft: FftPlanner::new(),
    });
}

/// Why a seed's records could not be made.
#[derive(Debug, thiserror::Error)]
pub enum RecordFailure {
    /// The shear stage was not sampled uniformly.
    #[error("records need a uniformly sampled run: {0}")]
    NotUniform(String),
    /// The numerics refused a record.
    #[error("record {record}: {source}")]
    Numerics {
        /// The record.
        record: String,
        /// Why.
        source: SeismoError,
    },
    /// The records' interval is far finer than the run's own sampling: resampling would invent
    /// samples between the steps (and a tiny interval would not fit in memory).
    #[error(
        "record.interval_s = {requested_s:e} s is {:.3e} times finer than this run's own sampling ({recorded_s:e} s, \
         at least one step): records are resampled to it, not invented between steps; give a record.interval_s of at \
         least half the run's step",
        recorded_s / requested_s
    )]
    IntervalTooFine {
        /// The interval asked for (s).
        requested_s: f64,
        /// The run's own sampling interval (s).
        recorded_s: f64,
    },
    /// The caller asked the analysis to stop.
    #[error("analysis cancelled")]
    Cancelled,
}

/// One window of the run that becomes records.
struct Window {
    event: Option<u32>,
    label: String,
    /// Sample range within the recording.
    samples: std::ops::Range<usize>,
    pre_event_s: f64,
}

/// The windows of the run: one per selected event, or the whole shear stage.
fn windows(t: &[f64], offset: usize, catalogue: &Catalogue, acc: &AccelerogramSettings) -> Vec<Window> {
    if acc.span == RecordSpan::WholeRun {
        return vec![Window { event: None, label: "run".into(), samples: offset..offset + t.len(), pre_event_s: 0.0 }];
    }
    let mut out = Vec::new();
    for (k, e) in catalogue.events.iter().enumerate() {
        let main = e.kind.is_main();
        let chosen = match acc.events {
            EventChoice::Main => main,
            EventChoice::All => main || e.burst.stress_drop_pa >= acc.min_drop_pa,
        };
        if !chosen {
            continue;
        }
        let label = match e.kind.rank().filter(|_| main) {
            Some(rank) => format!("S{rank}"),
            None => format!("E{k}"),
        };
        let a = t.partition_point(|&x| x < e.burst.start_s - acc.pre_event_s);
        let b = t.partition_point(|&x| x <= e.burst.end_s + acc.post_event_s);
        if b < a + 2 {
            continue;
        }
        let pre = (e.burst.start_s - t[a]).max(0.0);
        out.push(Window { event: Some(k as u32), label, samples: offset + a..offset + b, pre_event_s: pre });
    }
    out
}

/// How a record is processed (docs/model.md §8): `acc`'s mean removal, tapers, pads, filter
/// order and baseline, filtered to `f_low_hz`…`f_high_hz`, with `pre_event_s` of its window
/// before the event. The same record processed with the same options gives the same numbers,
/// bit for bit (the store keeps each record's window in single precision; the exact record is
/// this function of its raw window in the `control` table and the `records` table's corners).
pub fn processing_options(
    acc: &AccelerogramSettings,
    f_low_hz: f64,
    f_high_hz: f64,
    pre_event_s: f64,
) -> ProcessingOptions {
    let mean = match acc.mean {
        MeanChoice::PreEvent if pre_event_s > 0.0 => MeanRemoval::PreEvent { seconds: pre_event_s },
        MeanChoice::PreEvent | MeanChoice::Whole => MeanRemoval::WholeRecord,
        MeanChoice::None => MeanRemoval::Off,
    };
    ProcessingOptions {
        mean,
        taper_start: acc.taper,
        taper_end: acc.taper,
        padding: if acc.pad { Padding::Auto } else { Padding::None },
        f_low: f_low_hz,
        f_high: Some(f_high_hz),
        order: acc.order,
        baseline_degree: acc.baseline_degree,
    }
}

/// Runs the analysis for one seed's recording; `cancel` stops it between windows.
#[allow(clippy::too_many_arguments)] // the seed's inputs, its settings, and the shared plans and interrupt
pub fn compute(
    rec: &Recording,
    catalogue: &Catalogue,
    model: &Model,
    acc: &AccelerogramSettings,
    spectra: Option<&SpectraSettings>,
    smoothing_s: f64,
    plans: &PlanCache,
    cancel: &AtomicBool,
) -> Result<SeedRecords, RecordFailure> {
    let Some(span) = rec.uniform_shear() else {
        return Err(RecordFailure::NotUniform(format!(
            "the shear stage was sampled every {} steps except where the skip-ahead sampled quiet phases more sparsely \
             or the stage's last step fell off the grid",
            rec.sampling.stride
        )));
    };
    let mut out = SeedRecords::default();
    if spectra.is_some_and(|s| s.attenuation) {
        out.attenuation = attenuation(rec, catalogue, model, smoothing_s);
    }
    let t = &rec.time_s[span.clone()];
    if t.len() < 2 {
        return Ok(out);
    }
    // The seed's own interval (a whole number of its steps, so it differs from seed to seed) and
    // the one every record is written at: the pipeline's `record.interval_s`, or a round one
    // below the usable band (docs/model.md §8).
    let dt_recorded = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    let dt = record_interval(model.scene().record.interval_s, acc.resolved_hz);
    // Resampling follows a run's own interval up to twice finer (seeds' strides differ by a
    // step); past that it would only interpolate between steps.
    if dt < 0.5 * dt_recorded {
        return Err(RecordFailure::IntervalTooFine { requested_s: dt, recorded_s: dt_recorded });
    }
    let lattice = model.lattice();
    for w in windows(t, span.start, catalogue, acc) {
        // Each window is a few records and their spectra: the latency of an interrupt.
        if cancel.load(Ordering::Relaxed) {
            return Err(RecordFailure::Cancelled);
        }
        let started = thread_cpu_s();
        let first = out.records.len();
        let mut horizontal: HashMap<NodeId, [Option<usize>; 2]> = HashMap::new();
        for (ch, accel) in rec.control.iter().filter(|(c, _)| acc.wants(c)) {
            let id = format!("{}-n{}-{}", w.label, ch.node.ldem(), ch.component.name());
            let raw = &accel[w.samples.clone()];
            let duration = (raw.len() - 1) as f64 * dt_recorded;
            // The band's high corner within 80% of the Nyquist frequency of both intervals.
            let coarser = dt_recorded.max(dt);
            let band = match RecordBand::new(duration, coarser, acc.resolved_hz, acc.low_corner_hz, acc.high_corner_hz)
            {
                Ok(b) => b,
                Err(e) => {
                    out.left_out.push(format!("{id}: {e}"));
                    continue;
                }
            };
            let numerics = |source: SeismoError| RecordFailure::Numerics { record: id.clone(), source };
            let opts = processing_options(acc, band.f_low_hz, band.f_high_hz, w.pre_event_s);
            let processed = process(raw, dt_recorded, &opts).map_err(numerics)?.resampled(dt);
            let intensity = intensity(&processed.accel, dt, Baseline::None);
            // The response spectra come below: a node's x and y records from the passes of
            // their RotD, the others alone.
            // Up to the top of the usable band: above it the amplitudes are the filter's roll-off.
            let fourier = spectra.map(|s| {
                let mut fs = SCRATCH
                    .with(|scratch| fourier_amplitude(&processed.accel, dt, s.window, &mut scratch.borrow_mut().fft));
                fs.keep_up_to(band.usable_high_hz);
                fs
            });
            match ch.component {
                Component::X => horizontal.entry(ch.node).or_default()[0] = Some(out.records.len()),
                Component::Y => horizontal.entry(ch.node).or_default()[1] = Some(out.records.len()),
                Component::Z => {}
            }
            out.records.push(RecordData {
                id,
                event: w.event,
                label: w.label.clone(),
                channel: *ch,
                position: lattice.position(ch.node),
                start_s: t[w.samples.start - span.start],
                pre_event_s: w.pre_event_s,
                recorded_dt_s: dt_recorded,
                recorded_samples: raw.len() as u32,
                processed,
                band,
                intensity,
                sd: Vec::new(),
                fourier,
            });
        }
        out.timings.records_s += thread_cpu_s() - started;
        let Some(s) = spectra else { continue };
        let started = thread_cpu_s();
        if s.rotd {
            let mut pairs: Vec<(NodeId, usize, usize)> =
                horizontal.into_iter().filter_map(|(n, [x, y])| Some((n, x?, y?))).collect();
            pairs.sort();
            for (node, ix, iy) in pairs {
                let (x, y) = (&out.records[ix], &out.records[iy]);
                let id = format!("{}-n{}-xy", w.label, node.ldem());
                let numerics = |source: SeismoError| RecordFailure::Numerics { record: id.clone(), source };
                let plan = plans.rotd(dt, s).map_err(|e| numerics(e.into()))?;
                let mut r = RotDSpectrum::default();
                SCRATCH
                    .with(|scratch| {
                        plan.compute(&x.processed.accel, &y.processed.accel, &mut scratch.borrow_mut().rotd, &mut r)
                    })
                    .map_err(|e| numerics(e.into()))?;
                out.rotd.push(RotdData {
                    id,
                    event: w.event,
                    label: w.label.clone(),
                    node,
                    band: x.band.intersect(&y.band),
                    sd50: r.rotd50,
                    sd100: r.rotd100,
                });
                // The same passes gave each component's own spectrum, bit for bit.
                out.records[ix].sd = r.x;
                out.records[iy].sd = r.y;
                out.timings.pairs += 1;
            }
        }
        out.timings.rotd_s += thread_cpu_s() - started;
        let started = thread_cpu_s();
        for r in out.records[first..].iter_mut().filter(|r| r.sd.is_empty()) {
            let numerics = |source: SeismoError| RecordFailure::Numerics { record: r.id.clone(), source };
            let plan = plans.spectrum(dt, s).map_err(|e| numerics(e.into()))?;
            let mut sd = vec![0.0; plan.len()];
            SCRATCH
                .with(|scratch| plan.compute(&r.processed.accel, &mut scratch.borrow_mut().spectrum, &mut sd))
                .map_err(|e| numerics(e.into()))?;
            r.sd = sd;
            out.timings.alone += 1;
        }
        out.timings.spectra_s += thread_cpu_s() - started;
    }
    Ok(out)
}
