//! One seed from its run to its tables: events detected on the recording, scaled to the
//! prototype, its spectra; then every part written (the `runs` part last).

use std::path::Path;

use stickslip_config::Pipeline;
use stickslip_seismo::accelerogram::at2_text;
use stickslip_seismo::events::{Catalogue, EventParams, Signals, detect};
use stickslip_seismo::similarity::{AreaChoice, ModelEvent, Scaled, scale};
use stickslip_solver::scene::{ControlChannel, Kinematic};
use stickslip_solver::{Channel, Model, Recording, RunOutput};
use stickslip_store::Folder;
use stickslip_store::io::{write_parquet_atomic, write_text_atomic};
use stickslip_store::schema::{
    ACCELEROGRAMS, ATTENUATION, CONTROL, EVENTS_TABLE, FOURIER, INTENSITY, RUNS, SERIES, SIMILARITY, SKIPS, SPECTRA,
    SUB_EVENTS_TABLE,
};
use stickslip_store::tables::events::{events_frame, similarity_frame, sub_events_frame};
use stickslip_store::tables::runs::{self, RunFacts, RunRow};
use stickslip_store::tables::series::{control_frame, series_frame, skips_frame};
use stickslip_store::tables::spectra::{
    accelerograms_frame, attenuation_frame, fourier_frame, intensity_frame, spectra_frame,
};

use crate::error::EnsembleError;
use crate::spectra::{PlanCache, SeedSpectra, at2_name};

/// A seed's run and what was found in it.
pub struct Analysed {
    /// The run.
    pub run: RunOutput,
    /// Its events.
    pub catalogue: Catalogue,
    /// Every event at prototype scale.
    pub scaled: Vec<(ModelEvent, Scaled)>,
    /// Its spectra, if the pipeline asks for them.
    pub spectra: Option<SeedSpectra>,
}

/// Control acceleration channels recorded by the scene, in table order.
pub fn acceleration_channels(model: &Model) -> Vec<ControlChannel> {
    model.scene().record.control.iter().filter(|c| c.quantity == Kinematic::Acceleration).copied().collect()
}

/// Detects the events of a recording (docs/model.md §7); refuses a recording without the
/// channels the detector needs.
pub fn catalogue(rec: &Recording, model: &Model, events: &EventParams) -> Result<Catalogue, String> {
    let need = |ch: Channel, asked: &str| {
        rec.get(ch).ok_or_else(|| format!("event detection needs the channel {asked}: add it to record.interface"))
    };
    let accelerations: Vec<&[f64]> =
        rec.control.iter().filter(|(c, _)| c.quantity == Kinematic::Acceleration).map(|(_, v)| v.as_slice()).collect();
    let signals = Signals {
        time_s: &rec.time_s,
        shear_stress_pa: need(Channel::ShearStress, "shear_stress")?,
        mean_slip_m: need(Channel::MeanSlip, "mean_slip")?,
        mean_slip_rate_m_s: need(Channel::MeanSlipRate, "slip_rate")?,
        slipping_nodes: rec.get(Channel::SlippingNodes),
        accelerations: &accelerations,
    };
    Ok(detect(&signals, model.contact().len(), model.lattice().contact_area(), events))
}

/// Every event of `cat` scaled to the pipeline's prototype (docs/model.md §9).
pub fn scaled_events(cat: &Catalogue, model: &Model, pipeline: &Pipeline) -> Vec<(ModelEvent, Scaled)> {
    let lattice = model.lattice();
    let model_length = lattice.extent()[0];
    cat.events
        .iter()
        .map(|e| {
            let area = match pipeline.similarity.area {
                AreaChoice::Contact => lattice.contact_area(),
                AreaChoice::Rupture => e.burst.rupture_area_m2,
            };
            let input = ModelEvent {
                stress_drop_pa: e.burst.stress_drop_pa,
                model_length_m: model_length,
                model_area_m2: area,
                duration_s: Some(e.burst.duration_s()),
                recurrence_s: e.recurrence_s,
                model_rate_m_s: pipeline.scene.shear.velocity_m_s,
            };
            (input, scale(&input, &pipeline.similarity))
        })
        .collect()
}

/// Analyses one finished run.
pub fn analyse(run: RunOutput, model: &Model, pipeline: &Pipeline, plans: &PlanCache) -> Result<Analysed, String> {
    let catalogue = catalogue(&run.recording, model, &pipeline.events)?;
    let scaled = scaled_events(&catalogue, model, pipeline);
    let spectra = match &pipeline.spectra {
        Some(s) => Some(
            crate::spectra::compute(&run.recording, &catalogue, model, s, pipeline.events.smoothing_s, plans)
                .map_err(|e| e.to_string())?,
        ),
        None => None,
    };
    Ok(Analysed { run, catalogue, scaled, spectra })
}

/// The prototype length ratio λ of the pipeline's block.
pub fn lambda(model: &Model, pipeline: &Pipeline) -> f64 {
    pipeline.similarity.prototype_length_m / model.lattice().extent()[0]
}

/// Writes every part of one seed, `runs` last; returns the failure message of a failed seed.
pub fn write_seed(
    out: &Folder,
    pipeline: &Pipeline,
    model: &Model,
    seed: u64,
    outcome: &Result<Analysed, String>,
    wall_time_s: f64,
) -> Result<Option<String>, EnsembleError> {
    let channels = acceleration_channels(model);
    let (row, failure) = match outcome {
        Ok(a) => {
            let rec = &a.run.recording;
            let mut frames = vec![
                (SERIES, series_frame(seed, rec)?),
                (CONTROL, control_frame(seed, rec)?),
                (EVENTS_TABLE, events_frame(seed, &a.catalogue, &channels)?),
                (SUB_EVENTS_TABLE, sub_events_frame(seed, &a.catalogue, &channels)?),
                (SIMILARITY, similarity_frame(seed, &a.catalogue, &a.scaled)?),
            ];
            if !rec.skips.is_empty() {
                frames.insert(2, (SKIPS, skips_frame(seed, rec)?));
            }
            if let (Some(s), Some(settings)) = (&a.spectra, &pipeline.spectra) {
                let lambda = lambda(model, pipeline);
                frames
                    .push((SPECTRA, spectra_frame(seed, &s.channels, &settings.periods, &settings.dampings, lambda)?));
                frames.push((FOURIER, fourier_frame(seed, &s.channels)?));
                frames.push((INTENSITY, intensity_frame(seed, &s.channels, lambda)?));
                frames.push((ACCELEROGRAMS, accelerograms_frame(seed, &s.channels, lambda)?));
                if settings.attenuation {
                    frames.push((ATTENUATION, attenuation_frame(seed, &s.attenuation, model.lattice())?));
                }
                if settings.at2 {
                    write_at2(out, pipeline, seed, s, lambda)?;
                }
            }
            for (table, df) in &mut frames {
                write_parquet_atomic(df, &out.part(table, seed))?;
            }
            (RunRow { seed, outcome: Ok(RunFacts::of(&a.run, &a.catalogue)), wall_time_s }, None)
        }
        Err(msg) => (RunRow { seed, outcome: Err(msg.clone()), wall_time_s }, Some(msg.clone())),
    };
    write_parquet_atomic(&mut runs::frame(&[row], &pipeline.hash)?, &out.part(&RUNS, seed))?;
    Ok(failure)
}

/// Writes the AT2 files of one seed (model and prototype scale) under `<out>/at2/`.
fn write_at2(out: &Folder, pipeline: &Pipeline, seed: u64, s: &SeedSpectra, lambda: f64) -> Result<(), EnsembleError> {
    let dir = out.at2_dir();
    for c in &s.channels {
        for (scale, l) in [("model", 1.0), ("prototype", lambda)] {
            let name = at2_name(&pipeline.name, seed, c.channel.node, c.channel.component, scale);
            let p = c.position;
            let description = format!(
                "stickslip pipeline {}, seed {seed}, node {} at ({}, {}, {}) m, component {}, {scale} scale \
                 (lambda = {l}: time x{l}, acceleration /{l}); acceleration in g",
                pipeline.name,
                c.channel.node.ldem(),
                p[0],
                p[1],
                p[2],
                c.channel.component.name()
            );
            let accel: Vec<f64> = c.accel.iter().map(|a| a / l).collect();
            write_text_atomic(&Path::new(&dir).join(name), &at2_text(&accel, c.dt * l, &description))?;
        }
    }
    Ok(())
}
