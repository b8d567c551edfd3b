//! A seed's records as files, under `<out>/records/`: every record at model and prototype scale
//! in every format of `accelerograms.formats` ([`stickslip_seismo::accelerogram::FORMATS`]).

use stickslip_analysis::RecordData;
use stickslip_seismo::accelerogram::{Orientation, RecordFile, RecordFormat};

use crate::error::StoreError;
use crate::files::Stamp;
use crate::io::write_bytes_atomic;
use crate::layout::Folder;
use crate::spec::SeedView;
use crate::tables::records::Scale;

/// Name of a record's file: pipeline, seed, record and scale.
pub fn record_file_name(pipeline: &str, seed: u64, record: &str, scale: Scale, format: &dyn RecordFormat) -> String {
    format!("{pipeline}_seed{seed}_{record}_{}.{}", scale.name(), format.extension())
}

/// Writes the record files of a seed with records (nothing otherwise).
pub fn write(out: &Folder, view: &SeedView<'_>, stamp: &Stamp<'_>) -> Result<(), StoreError> {
    let (Some(records), Some(acc)) = (&view.analysis.records, &view.settings.accelerograms) else { return Ok(()) };
    let dir = out.records_dir();
    let (seed, lambda) = (view.seed, view.analysis.lambda);
    for r in &records.records {
        let magnitude = r.event.and_then(|k| view.analysis.scaled.get(k as usize)).map(|e| e.magnitudes.mw_consistent);
        for scale in Scale::ALL {
            let l = scale.factor(lambda);
            let path =
                |format: &dyn RecordFormat| dir.join(record_file_name(stamp.pipeline, seed, &r.id, scale, format));
            let file = ScaledRecord::new(r, scale, l);
            let description = file.description(stamp.pipeline, seed, r);
            let band = r.band.scaled(l);
            let numbers: [(&str, &[f64]); 3] = [
                ("FLOWHIGH", &[band.f_low_hz, band.f_high_hz]),
                ("USABLE", &[band.usable_low_hz, band.usable_high_hz]),
                ("LAMBDA", &[l]),
            ];
            let record = RecordFile {
                description: &description,
                accel_m_s2: &file.accel,
                dt_s: r.processed.dt * l,
                begin_s: (r.start_s + r.processed.t_first) * l,
                motion: Some((&r.processed.vel, &file.disp)),
                station: &format!("N{}", r.channel.node.ldem()),
                component: &r.channel.component.name().to_uppercase(),
                network: "SS",
                location: if scale == Scale::Model { "M" } else { "P" },
                event: &r.label,
                position_m: Some(file.position),
                orientation: Orientation::of_axis(r.channel.component.name()),
                magnitude,
                origin_s: None,
                numbers: &numbers,
            };
            for &format in &acc.formats {
                let bytes = format.encode(&record).map_err(|e| StoreError::Corrupt {
                    path: path(format),
                    what: format!("{} file of record {}: {e}", format.name(), r.id),
                })?;
                write_bytes_atomic(&path(format), &bytes)?;
            }
        }
    }
    Ok(())
}

/// A record's values at one scale (accelerations ÷λ, displacements and positions ×λ).
struct ScaledRecord {
    scale: Scale,
    factor: f64,
    accel: Vec<f64>,
    disp: Vec<f64>,
    position: [f64; 3],
}

impl ScaledRecord {
    fn new(r: &RecordData, scale: Scale, l: f64) -> Self {
        ScaledRecord {
            scale,
            factor: l,
            accel: r.processed.accel.iter().map(|a| a / l).collect(),
            disp: r.processed.disp.iter().map(|d| d * l).collect(),
            position: r.position.map(|x| x * l),
        }
    }

    /// The one-line description every format carries.
    fn description(&self, pipeline: &str, seed: u64, r: &RecordData) -> String {
        let (l, pos, band) = (self.factor, self.position, r.band.scaled(self.factor));
        format!(
            "stickslip {pipeline} seed {seed} record {} ({} scale, lambda = {l}): node {} at ({}, {}, {}) m, component {}, \
             band-pass {:.4}-{:.4} Hz, usable {:.4}-{:.4} Hz",
            r.id,
            self.scale.name(),
            r.channel.node.ldem(),
            pos[0],
            pos[1],
            pos[2],
            r.channel.component.name(),
            band.f_low_hz,
            band.f_high_hz,
            band.usable_low_hz,
            band.usable_high_hz,
        )
    }
}
