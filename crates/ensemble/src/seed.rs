//! One seed from its run to its tables: events detected on the recording, scaled to the
//! prototype, its records and their spectra; then every part and file written (the `runs` part
//! last).

use stickslip_config::Pipeline;
use stickslip_config::accelerograms::RecordFormat;
use stickslip_seismo::accelerogram::at2_text;
use stickslip_seismo::accelerogram::sac::{SacMeta, SacUnit, sac_bytes};
use stickslip_seismo::emission::{Cluster, clusters};
use stickslip_seismo::events::{Catalogue, EventParams, Signals, detect};
use stickslip_seismo::seas::{StationHeader, StationSeries, station_file_name, station_text};
use stickslip_seismo::similarity::{AreaChoice, ModelEvent, Scaled, moment_magnitude, scale};
use stickslip_solver::scene::{ControlChannel, Kinematic};
use stickslip_solver::{Model, Recording, RunOutput};
use stickslip_store::Folder;
use stickslip_store::io::{write_bytes_atomic, write_parquet_atomic, write_text_atomic};
use stickslip_store::schema::{
    ACCELEROGRAMS, ACOUSTIC_EMISSION, ATTENUATION, CONTROL, CRACKS, EVENTS_TABLE, FAULT, FOURIER, INTENSITY, RECORDS,
    ROTD, RUNS, RUPTURE_ONSETS, RUPTURES, SERIES, SIMILARITY, SKIPS, SPECTRA, SUB_EVENTS_TABLE,
};
use stickslip_store::tables::cracks::{breaks, cracks_frame, emission_frame};
use stickslip_store::tables::events::{events_frame, similarity_frame, sub_events_frame};
use stickslip_store::tables::fronts::{rupture_onsets_frame, ruptures_frame};
use stickslip_store::tables::records::{
    RecordData, Scale, accelerograms_frame, attenuation_frame, fourier_frame, intensity_frame, records_frame,
    rotd_frame, spectra_frame,
};
use stickslip_store::tables::runs::{self, RunFacts, RunRow};
use stickslip_store::tables::series::{control_frame, fault_frame, series_frame, skips_frame};

use crate::error::EnsembleError;
use crate::fronts::{SeedFronts, fronts};
use crate::records::{PlanCache, SeedRecords};

/// A seed's run and what was found in it.
pub struct Analysed {
    /// The run.
    pub run: RunOutput,
    /// Its events.
    pub catalogue: Catalogue,
    /// Every event at prototype scale.
    pub scaled: Vec<(ModelEvent, Scaled)>,
    /// Its records (and their spectra), if the pipeline asks for them.
    pub records: Option<SeedRecords>,
    /// Its bar breaks as acoustic-emission events, when the bars crack.
    pub emission: Option<Vec<Cluster>>,
    /// The rupture front of each event, when the scene records slip onsets.
    pub fronts: Option<SeedFronts>,
}

/// Control acceleration channels recorded by the scene, in table order.
pub fn acceleration_channels(model: &Model) -> Vec<ControlChannel> {
    model.scene().record.control.iter().filter(|c| c.quantity == Kinematic::Acceleration).copied().collect()
}

/// Detects the events of a run on the solver's event trace (docs/model.md §7): every step around
/// each burst of slip, whatever the recording interval, so the catalogue does not depend on it.
pub fn catalogue(rec: &Recording, model: &Model, events: &EventParams) -> Catalogue {
    let trace = &rec.trace;
    let accelerations: Vec<&[f64]> = trace.accelerations.iter().map(|(_, v)| v.as_slice()).collect();
    let signals = Signals {
        time_s: &trace.time_s,
        shear_stress_pa: &trace.shear_stress_pa,
        mean_slip_m: &trace.mean_slip_m,
        mean_slip_rate_m_s: &trace.mean_slip_rate_m_s,
        slipping_nodes: Some(&trace.slipping_nodes),
        accelerations: &accelerations,
    };
    detect(&signals, model.contact().len(), model.lattice().contact_area(), events)
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
    let catalogue = catalogue(&run.recording, model, &pipeline.events);
    let scaled = scaled_events(&catalogue, model, pipeline);
    let records = match &pipeline.accelerograms {
        Some(acc) => Some(
            crate::records::compute(
                &run.recording,
                &catalogue,
                model,
                acc,
                pipeline.spectra.as_ref(),
                pipeline.events.smoothing_s,
                plans,
            )
            .map_err(|e| e.to_string())?,
        ),
        None => None,
    };
    let emission = pipeline.emission.as_ref().map(|p| clusters(&breaks(&run.recording.cracks, model.lattice()), p));
    let fronts =
        fronts(&run.recording, &catalogue, model, pipeline.events.smoothing_s, pipeline.events.rupture_rate_m_s);
    Ok(Analysed { run, catalogue, scaled, records, emission, fronts })
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
            let keep = rec.trace.thinned(model.scene().record.fault_interval_s);
            if let Some(df) = fault_frame(seed, &rec.trace, &keep, model.lattice())? {
                frames.push((FAULT, df));
                write_station_files(out, pipeline, model, seed, &rec.trace, &keep)?;
            }
            if !rec.skips.is_empty() {
                frames.insert(2, (SKIPS, skips_frame(seed, rec)?));
            }
            if let Some(f) = &a.fronts {
                let rows = f.rows(&a.catalogue);
                frames.push((RUPTURES, ruptures_frame(seed, &rows, &f.base.nodes(), &f.speeds, f.source)?));
                frames.push((RUPTURE_ONSETS, rupture_onsets_frame(seed, &rows, &f.base.nodes())?));
            }
            if let Some(clusters) = &a.emission {
                frames.push((CRACKS, cracks_frame(seed, &rec.cracks, model.lattice())?));
                frames.push((ACOUSTIC_EMISSION, emission_frame(seed, clusters)?));
            }
            if let (Some(r), Some(acc)) = (&a.records, &pipeline.accelerograms) {
                let lambda = lambda(model, pipeline);
                frames.push((RECORDS, records_frame(seed, &r.records, lambda)?));
                frames.push((ACCELEROGRAMS, accelerograms_frame(seed, &r.records, lambda)?));
                frames.push((INTENSITY, intensity_frame(seed, &r.records, lambda)?));
                if let Some(settings) = &pipeline.spectra {
                    let (p, d) = (&settings.periods, &settings.dampings);
                    frames.push((SPECTRA, spectra_frame(seed, &r.records, p, d, lambda)?));
                    frames.push((FOURIER, fourier_frame(seed, &r.records)?));
                    if settings.rotd {
                        frames.push((ROTD, rotd_frame(seed, &r.rotd, p, d, lambda)?));
                    }
                    if settings.attenuation {
                        frames.push((ATTENUATION, attenuation_frame(seed, &r.attenuation, model.lattice())?));
                    }
                }
                write_record_files(out, pipeline, seed, &r.records, &a.scaled, &acc.formats, lambda)?;
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

/// Writes one SEAS-layout station file per fault station of the scene (docs/model.md §13) under
/// `<out>/fault_stations/seed<seed>/`.
fn write_station_files(
    out: &Folder,
    pipeline: &Pipeline,
    model: &Model,
    seed: u64,
    trace: &stickslip_solver::Trace,
    keep: &[usize],
) -> Result<(), EnsembleError> {
    let Some(f) = &trace.fault else { return Ok(()) };
    let stations = &model.scene().record.fault_stations;
    if stations.is_empty() {
        return Ok(());
    }
    let dir = out.fault_stations_dir(seed);
    let problem = format!("stickslip pipeline {} seed {seed} (hash {})", pipeline.name, pipeline.hash);
    let code = format!("stickslip {}", env!("CARGO_PKG_VERSION"));
    for &id in stations {
        let Some(i) = f.nodes.iter().position(|&n| n == id) else { continue };
        let p = model.lattice().position(id);
        let location = format!(
            "on the base (the fault), x = {} m along strike, y = {} m across; contact node LDEM {}",
            p[0],
            p[1],
            id.ldem()
        );
        let header =
            StationHeader { problem: &problem, code: &code, element_size_m: model.scene().lc_m, location: &location };
        let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<f64>>();
        let (t, slip, rate) = (pick(&trace.time_s), pick(&f.slip_m[i]), pick(&f.slip_rate_m_s[i]));
        let (tau, sigma) = (pick(&f.shear_stress_pa[i]), pick(&f.normal_stress_pa[i]));
        let series = StationSeries {
            time_s: &t,
            slip_m: &slip,
            slip_rate_m_s: &rate,
            shear_stress_pa: &tau,
            normal_stress_pa: &sigma,
        };
        write_text_atomic(
            &dir.join(format!("{}.dat", station_file_name(p[0], p[1]))),
            &station_text(&header, &series),
        )?;
    }
    Ok(())
}

/// Name of a record's file: pipeline, seed, record and scale.
pub fn record_file_name(pipeline: &str, seed: u64, record: &str, scale: Scale, format: RecordFormat) -> String {
    format!("{pipeline}_seed{seed}_{record}_{}.{}", scale.name(), format.extension())
}

/// Writes the files of one seed's records (each format asked for, model and prototype scale)
/// under `<out>/records/`.
fn write_record_files(
    out: &Folder,
    pipeline: &Pipeline,
    seed: u64,
    records: &[RecordData],
    scaled: &[(ModelEvent, Scaled)],
    formats: &[RecordFormat],
    lambda: f64,
) -> Result<(), EnsembleError> {
    let dir = out.records_dir();
    for r in records {
        let p = &r.processed;
        for scale in Scale::ALL {
            let l = scale.factor(lambda);
            let band = r.band.scaled(l);
            let pos = r.position.map(|x| x * l);
            let description = format!(
                "stickslip {} seed {seed} record {} ({} scale, lambda = {l}): node {} at ({}, {}, {}) m, component {}, \
                 band-pass {:.4}-{:.4} Hz, usable {:.4}-{:.4} Hz",
                pipeline.name,
                r.id,
                scale.name(),
                r.channel.node.ldem(),
                pos[0],
                pos[1],
                pos[2],
                r.channel.component.name(),
                band.f_low_hz,
                band.f_high_hz,
                band.usable_low_hz,
                band.usable_high_hz,
            );
            let accel: Vec<f64> = p.accel.iter().map(|a| a / l).collect();
            let dt = p.dt * l;
            for &format in formats {
                let path = dir.join(record_file_name(&pipeline.name, seed, &r.id, scale, format));
                match format {
                    RecordFormat::At2 => write_text_atomic(&path, &at2_text(&accel, dt, &description))?,
                    RecordFormat::Csv => {
                        let mut text =
                            format!("# {description}\ntime_s,acceleration_m_s2,velocity_m_s,displacement_m\n");
                        for i in 0..accel.len() {
                            let t = (r.start_s + p.t_first) * l + i as f64 * dt;
                            text.push_str(&format!(
                                "{t:.9e},{:.9e},{:.9e},{:.9e}\n",
                                accel[i],
                                p.vel[i],
                                p.disp[i] * l
                            ));
                        }
                        write_text_atomic(&path, &text)?;
                    }
                    RecordFormat::Sac => {
                        let magnitude = r
                            .event
                            .and_then(|k| scaled.get(k as usize))
                            .map(|(_, s)| moment_magnitude(s.m0_consistent_dyne_cm));
                        let meta = sac_meta(r, scale, l, magnitude);
                        let bytes = sac_bytes(&accel, dt, &meta)
                            .map_err(|e| EnsembleError::Setup(format!("SAC file of record {}: {e}", r.id)))?;
                        write_bytes_atomic(&path, &bytes)?;
                    }
                }
            }
        }
    }
    Ok(())
}

/// SAC header of a record: station = node, component, event = label, begin = run time of the
/// first sample (the run's time as the reference), station position in model coordinates (m ×
/// λ: `STLA`/`STLO`/`STEL` hold x, y, z), the band in `USER0`–`USER3` (Hz: corners, usable range).
fn sac_meta(r: &RecordData, scale: Scale, l: f64, magnitude: Option<f64>) -> SacMeta {
    let band = r.band.scaled(l);
    SacMeta {
        station: format!("N{}", r.channel.node.ldem()),
        component: r.channel.component.name().to_uppercase(),
        network: "SS".into(),
        location: if scale == Scale::Model { "M".into() } else { "P".into() },
        event: r.label.clone(),
        begin: (r.start_s + r.processed.t_first) * l,
        station_lat: Some(r.position[0] * l),
        station_lon: Some(r.position[1] * l),
        station_elevation: Some(r.position[2] * l),
        component_incidence: Some(if r.channel.component.name() == "z" { 0.0 } else { 90.0 }),
        component_azimuth: Some(match r.channel.component.name() {
            "x" => 90.0,
            "y" => 0.0,
            _ => 0.0,
        }),
        magnitude,
        user: [
            Some(band.f_low_hz),
            Some(band.f_high_hz),
            Some(band.usable_low_hz),
            Some(band.usable_high_hz),
            Some(l),
            None,
            None,
            None,
            None,
            None,
        ],
        user_labels: ["FLOWHIGH".into(), "USABLE".into(), "LAMBDA".into()],
        unit: SacUnit::NanometrePerSecond2,
        ..SacMeta::default()
    }
}
