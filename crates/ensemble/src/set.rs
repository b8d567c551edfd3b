//! A set of an ensemble's records matched to a design spectrum (`[set]`,
//! `stickslip_seismo::selection`), at prototype scale: the candidates are the records of every
//! finished seed (each horizontal component, one component, or each node's x–y pair by its
//! RotD50), with the usable band each was processed to; the chosen records are written scaled, as
//! AT2 and SAC files under `<out>/set/`, with the `set` table.
//!
//! A fault scenario's set is chosen from its surface stations instead ([`crate::scenario_set`]):
//! each station's horizontal pair by its RotD50 or RotD100, inside the magnitude and distance
//! bins asked.

use std::collections::{BTreeMap, HashMap};

use stickslip_analysis::records::processing_options;
use stickslip_config::set::{SetComponent, SetGroup};
use stickslip_config::{Pipeline, SetSettings};
use stickslip_seismo::accelerogram::processing::process;
use stickslip_seismo::accelerogram::{At2, RecordFile, RecordFormat, Sac};
use stickslip_solver::scene::{Component, Kinematic};
use stickslip_store::Folder;
use stickslip_store::io::{read_parquet_if_present, scan_columns, write_bytes_atomic, write_parquet_atomic};
use stickslip_store::schema::{CONTROL, RECORDS, ROTD, SET, SPECTRA, col};
use stickslip_store::tables::records::Records;
use stickslip_store::tables::series::read_control;
use stickslip_store::tables::set::{SetRow, set_frame};
use stickslip_store::tables::spectra::Spectra;

use crate::error::EnsembleError;
pub use crate::set_pool::SetOutcome;
use crate::set_pool::{Chosen, Member, Pool, choose, clear_set_dir};

/// One candidate's data besides its spectrum.
struct Meta {
    seed: u64,
    record: String,
    label: String,
    node: u32,
    component: String,
    usable_hz: (f64, f64),
}

/// Selects the set of `settings` among the records of the finished seeds in `out`, writes its
/// table and files, and returns it; refuses with the rule it cannot meet.
pub fn select_set(out: &Folder, pipeline: &Pipeline, settings: &SetSettings) -> Result<SetOutcome, EnsembleError> {
    if pipeline.sets_from_stations() {
        return crate::scenario_set::select_station_set(out, pipeline, settings);
    }
    let missing =
        |what: &str| EnsembleError::Setup(format!("{}: no {what} to choose a set from", out.root().display()));
    let records = read_parquet_if_present(&out.gathered(&RECORDS))?.ok_or_else(|| missing("records table"))?;
    let records = Records::read(&records)?;
    let rotd = settings.component == SetComponent::Rotd50;
    let table = if rotd { ROTD } else { SPECTRA };
    // Only the prototype rows and the columns read, each part once.
    let columns = [
        col::SEED,
        col::RECORD,
        col::NODE,
        col::COMPONENT,
        col::SCALE,
        col::DAMPING,
        col::PERIOD_S,
        col::PSA_M_S2,
        col::IN_BAND,
    ];
    let prototype = polars::prelude::col(col::SCALE).eq(polars::prelude::lit("prototype"));
    let spectra = scan_columns(&out.part_glob(&table), &columns, Some(prototype))?
        .ok_or_else(|| missing(&format!("{} table", table.name)))?;
    let spectra = Spectra::read(&spectra)?;
    // Band of each record at prototype scale; a RotD pair takes the narrower of its two.
    let mut band: HashMap<(u64, String), (f64, f64, String, u32)> = HashMap::new();
    for i in 0..records.seed.len() {
        if records.scale[i] != "prototype" {
            continue;
        }
        let key = if rotd {
            let pair = records.record[i].rsplit_once('-').map_or(String::new(), |(head, _)| format!("{head}-xy"));
            (records.seed[i], pair)
        } else {
            (records.seed[i], records.record[i].clone())
        };
        let e = band.entry(key).or_insert((0.0, f64::INFINITY, records.label[i].clone(), records.node[i] as u32));
        e.0 = e.0.max(records.usable_low_hz[i]);
        e.1 = e.1.min(records.usable_high_hz[i]);
    }
    let wanted = |comp: &str| match settings.component {
        SetComponent::Horizontal => comp == "x" || comp == "y",
        SetComponent::X => comp == "x",
        SetComponent::Y => comp == "y",
        SetComponent::Z => comp == "z",
        SetComponent::Rotd50 => comp == "rotd50",
        // Refused by the configuration for the records of events.
        SetComponent::Rotd100 => false,
    };
    let mut grid: Vec<f64> = Vec::new();
    let mut psa: BTreeMap<(u64, String), (String, Vec<f64>)> = BTreeMap::new();
    for i in 0..spectra.seed.len() {
        if spectra.scale[i] != "prototype"
            || (spectra.damping[i] - settings.damping).abs() > 1e-12
            || !wanted(&spectra.component[i])
        {
            continue;
        }
        let e = psa
            .entry((spectra.seed[i], spectra.record[i].clone()))
            .or_insert_with(|| (spectra.component[i].clone(), vec![]));
        e.1.push(spectra.psa_m_s2[i]);
        if psa.len() == 1 {
            grid.push(spectra.period_s[i]);
        }
    }
    let mut members = Vec::new();
    for ((seed, record), (component, values)) in psa {
        let Some(&(lo, hi, ref label, node)) = band.get(&(seed, record.clone())) else { continue };
        if values.len() != grid.len() {
            continue;
        }
        let group = match settings.per {
            SetGroup::Event => format!("seed {seed} / {label}"),
            SetGroup::Seed => format!("seed {seed}"),
        };
        members.push(Member {
            id: format!("{seed}/{record}"),
            group,
            psa: values,
            usable_s: (1.0 / hi, if lo > 0.0 { 1.0 / lo } else { f64::INFINITY }),
            meta: Meta { seed, record, label: label.clone(), node, component, usable_hz: (lo, hi) },
        });
    }
    let pool = Pool { grid, members };
    let Chosen { selection, periods, target, spectra } = choose(&pool, settings)?;
    let rows: Vec<SetRow> = selection
        .records
        .iter()
        .map(|c| {
            let m = &pool.members[c.index].meta;
            SetRow {
                seed: m.seed,
                record: m.record.clone(),
                label: m.label.clone(),
                node: m.node,
                component: m.component.clone(),
                scale_factor: c.scale,
                misfit: c.misfit,
                usable_hz: m.usable_hz,
                scenario: None,
            }
        })
        .collect();
    write_parquet_atomic(&mut set_frame(&rows)?, &out.gathered(&SET))?;
    clear_set_dir(out)?;
    write_set_files(out, pipeline, settings, &rows, &records)?;
    Ok(SetOutcome { selection, rows, periods, target, spectra, candidates: pool.members.len(), pool: None })
}

/// Writes the chosen records, scaled, at prototype scale: AT2 and SAC (scale factor and usable
/// band in `USER0`–`USER2`), one file per component (both of a RotD50 pair). Each record is
/// processed again from its raw window in the seed's `control` table with the corners of the
/// `records` table, which gives the record the analysis had, bit for bit, pads included (the
/// `accelerograms` table keeps only its window, in single precision).
fn write_set_files(
    out: &Folder,
    pipeline: &Pipeline,
    settings: &SetSettings,
    rows: &[SetRow],
    records: &Records,
) -> Result<(), EnsembleError> {
    let dir = out.set_dir();
    let Some(acc_settings) = &pipeline.analysis.accelerograms else { return Ok(()) };
    let lambda = pipeline.analysis.similarity.prototype_length_m / pipeline.scene.lattice().extent()[0];
    let mut by_seed: BTreeMap<u64, Vec<(usize, &SetRow)>> = BTreeMap::new();
    for (k, r) in rows.iter().enumerate() {
        by_seed.entry(r.seed).or_default().push((k, r));
    }
    for (seed, chosen) in by_seed {
        let Some(control) = read_parquet_if_present(&out.part(&CONTROL, seed))? else { continue };
        for (k, r) in chosen {
            let names: Vec<String> = match r.record.strip_suffix("-xy") {
                Some(head) => vec![format!("{head}-x"), format!("{head}-y")],
                None => vec![r.record.clone()],
            };
            for name in names {
                let Some(i) = (0..records.seed.len())
                    .find(|&i| records.seed[i] == seed && records.record[i] == name && records.scale[i] == "model")
                else {
                    continue;
                };
                let Some(component) = Component::ALL.into_iter().find(|c| c.name() == records.component[i]) else {
                    continue;
                };
                let Some((t, raw)) = read_control(&control, records.node[i], component, Kinematic::Acceleration)?
                else {
                    continue;
                };
                let Some(k0) = t.iter().position(|&x| x == records.start_s[i]) else { continue };
                let n = records.recorded_samples[i] as usize;
                if k0 + n > raw.len() || n < 2 {
                    continue;
                }
                let opts =
                    processing_options(acc_settings, records.f_low_hz[i], records.f_high_hz[i], records.pre_event_s[i]);
                // The record as analysed: processed at the run's own interval, then resampled to
                // the pipeline's (the same function, so the same bits).
                let p = process(&raw[k0..k0 + n], records.recorded_dt_s[i], &opts)
                    .map_err(|e| EnsembleError::Setup(format!("seed {seed}, record {name}: {e}")))?
                    .resampled(records.dt_s[i]);
                // Times and accelerations at prototype scale as the similarity rules give them.
                let time = |j: usize| (records.start_s[i] + p.t_first + j as f64 * p.dt) * lambda;
                let dt = time(1) - time(0);
                let a: Vec<f64> = p.accel.iter().map(|v| r.scale_factor * (v / lambda)).collect();
                let stem = format!("{}_set{:02}_seed{seed}_{name}", pipeline.name, k + 1);
                let description = format!(
                    "stickslip {} set record {} of {}: seed {seed} {name} x {:.4} (prototype scale), matched to {}",
                    pipeline.name,
                    k + 1,
                    rows.len(),
                    r.scale_factor,
                    settings.target_name
                );
                let component = name.rsplit('-').next().unwrap_or("").to_uppercase();
                let numbers: [(&str, &[f64]); 2] =
                    [("SCALE", &[r.scale_factor]), ("USABLE", &[r.usable_hz.0, r.usable_hz.1])];
                let record = RecordFile {
                    description: &description,
                    accel_m_s2: &a,
                    dt_s: dt,
                    begin_s: time(0),
                    motion: None,
                    station: &format!("N{}", r.node),
                    component: &component,
                    network: "SS",
                    location: "P",
                    event: &r.label,
                    position_m: None,
                    orientation: None,
                    magnitude: None,
                    origin_s: None,
                    numbers: &numbers,
                };
                // AT2 and SAC always, and the pipeline's other record formats (MiniSEED: the
                // channel of the prototype-scale event record, in the folder's inventory).
                let extra = acc_settings.formats.iter().copied().filter(|f| !matches!(f.name(), "at2" | "sac" | "csv"));
                for format in [&At2 as &dyn RecordFormat, &Sac].into_iter().chain(extra) {
                    let bytes = format.encode(&record).map_err(EnsembleError::Set)?;
                    write_bytes_atomic(&dir.join(format!("{stem}.{}", format.extension())), &bytes)?;
                }
            }
        }
    }
    Ok(())
}
