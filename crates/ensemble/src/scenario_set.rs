//! A record set chosen from a fault scenario's surface stations (`[set]` on a fault scene with
//! `[[stations]]`, docs/model.md §16.5): the candidates are the stations of every finished seed
//! whose rupture's Mw and whose R_rup fall in the bins asked, each by the RotD50 or RotD100 of its
//! horizontal pair (5% damping, `station_spectra`, on the grid of
//! [`stickslip_analysis::motions::spectrum_periods`] where every candidate is usable); a seed is
//! one rupture, so `max_per` caps the records of one seed. The chosen stations are written scaled
//! (both components by the same factor) as AT2, SAC and MiniSEED files under `<out>/set/`, each component
//! processed again by the function the analysis used, from the seed's `control` table (lattice
//! records) or its `station_records` table (broadband records, docs/model.md §17, with their
//! vertical component), so the files are the records the spectra were computed on, bit for bit;
//! the `set` table gives each record's Mw, R_rup and R_JB beside its scale factor and misfit. With
//! broadband records on several sites, `[set] vs30_m_s` says which site's records are chosen.

use std::collections::{BTreeMap, HashMap};

use polars::prelude::DataFrame;
use stickslip_analysis::motions::processed_pair;
use stickslip_config::check::Named;
use stickslip_config::set::SetComponent;
use stickslip_config::{Pipeline, SetSettings};
use stickslip_seismo::accelerogram::processing::{Processed, ProcessingOptions, process, resample, resample_together};
use stickslip_seismo::accelerogram::{At2, Mseed, Orientation, RecordFile, RecordFormat, Sac};
use stickslip_solver::scene::{Component, Kinematic};
use stickslip_store::Folder;
use stickslip_store::frame::Columns;
use stickslip_store::io::{read_parquet_if_present, write_bytes_atomic, write_parquet_atomic};
use stickslip_store::schema::{CONTROL, SET, SOURCE, STATION_RECORDS, STATION_SPECTRA, STATIONS, col};
use stickslip_store::tables::broadband::{ComponentRecord, read_station_record};
use stickslip_store::tables::series::read_control;
use stickslip_store::tables::set::{ScenarioMeta, SetRow, set_frame};

use crate::error::EnsembleError;
use crate::set_pool::{Chosen, Member, Pool, SetOutcome, choose, clear_set_dir};

/// A candidate station of one seed.
#[derive(Clone)]
pub(crate) struct Station {
    pub(crate) seed: u64,
    pub(crate) name: String,
    pub(crate) node: u32,
    /// Its position x, y, z (m).
    pub(crate) position_m: [f64; 3],
    /// Band-pass corners its record was processed with (Hz).
    pub(crate) band_hz: (f64, f64),
    /// Its usable band (Hz).
    pub(crate) usable_hz: (f64, f64),
    /// Its site, when it is a broadband record.
    pub(crate) vs30_m_s: Option<f64>,
    pub(crate) scenario: ScenarioMeta,
}

/// The station code of each of a fault scenario's stations: `S` and its rank (from 1, three
/// digits) among the sorted names; MiniSEED 2 allows five characters.
pub fn station_codes(names: &[String]) -> BTreeMap<String, String> {
    let mut sorted: Vec<&String> = names.iter().collect();
    sorted.sort();
    sorted.dedup();
    sorted.into_iter().enumerate().map(|(k, n)| (n.clone(), format!("S{:03}", k + 1))).collect()
}

/// Whether `v` lies in the bin `[lo, hi]` (no bin: every value).
fn in_bin(bin: Option<(f64, f64)>, v: f64) -> bool {
    bin.is_none_or(|(lo, hi)| v >= lo && v <= hi)
}

/// Selects the set of `settings` among the surface stations of the finished seeds of the
/// scenario in `out`, writes its table and files, and returns it; refuses with the rule it
/// cannot meet.
pub fn select_station_set(
    out: &Folder,
    pipeline: &Pipeline,
    settings: &SetSettings,
) -> Result<SetOutcome, EnsembleError> {
    let missing = |what: &str| {
        EnsembleError::Setup(format!("{}: no {what} to choose a set from (no finished seed?)", out.root().display()))
    };
    let source = read_parquet_if_present(&out.gathered(&SOURCE))?.ok_or_else(|| missing("source table"))?;
    let stations = read_parquet_if_present(&out.gathered(&STATIONS))?.ok_or_else(|| missing("stations table"))?;
    let spectra =
        read_parquet_if_present(&out.gathered(&STATION_SPECTRA))?.ok_or_else(|| missing("station_spectra table"))?;

    let c = Columns::of(&source, SOURCE.name);
    let mw: HashMap<u64, f64> = c.u64s(col::SEED)?.into_iter().zip(c.f64s(col::MW)?).collect();

    let c = Columns::of(&stations, STATIONS.name);
    let (seed, name, node) = (c.u64s(col::SEED)?, c.strs(col::STATION)?, c.u64s(col::NODE)?);
    let (depth, r_rup, r_jb) = (c.f64s(col::Y_M)?, c.f64s(col::R_RUP_M)?, c.f64s(col::R_JB_M)?);
    let (x_m, z_m) = (c.f64s(col::X_M)?, c.f64s(col::Z_M)?);
    let (f_low, f_high) = (c.opt_f64s(col::F_LOW_HZ)?, c.opt_f64s(col::F_HIGH_HZ)?);
    let (t_min, t_max) = (c.opt_f64s(col::USABLE_MIN_PERIOD_S)?, c.opt_f64s(col::USABLE_MAX_PERIOD_S)?);
    let site = if c.has(col::VS30_M_S) { c.opt_f64s(col::VS30_M_S)? } else { vec![None; seed.len()] };
    let mut sites: Vec<f64> = site.iter().flatten().copied().collect();
    sites.sort_by(f64::total_cmp);
    sites.dedup();
    if settings.vs30_m_s.is_none() && sites.len() > 1 {
        let listed = sites.iter().map(|v| v.to_string()).collect::<Vec<_>>().join(", ");
        return Err(EnsembleError::Setup(format!(
            "set.vs30_m_s: absent, but the stations' broadband records stand on several sites ({listed} m/s): say which \
             site's records to choose (set.vs30_m_s = one of them)"
        )));
    }
    let mut all = 0;
    let mut found: BTreeMap<(u64, String), Station> = BTreeMap::new();
    for i in 0..seed.len() {
        // Engineers' records are surface motions; a buried station is not a candidate.
        let (Some(&m), Some(lo), Some(hi), Some(t0), Some(t1)) =
            (mw.get(&seed[i]), f_low[i], f_high[i], t_min[i], t_max[i])
        else {
            continue;
        };
        if depth[i].abs() > 1e-6 {
            continue;
        }
        if settings.vs30_m_s.is_some_and(|v| site[i] != Some(v)) {
            continue;
        }
        all += 1;
        let scenario = ScenarioMeta { mw: m, r_rup_km: r_rup[i] / 1e3, r_jb_km: r_jb[i] / 1e3 };
        if !in_bin(settings.magnitude, m) || !in_bin(settings.distance_km, scenario.r_rup_km) {
            continue;
        }
        let station = Station {
            seed: seed[i],
            name: name[i].clone(),
            node: node[i] as u32,
            position_m: [x_m[i], depth[i], z_m[i]],
            band_hz: (lo, hi),
            usable_hz: (1.0 / t1, 1.0 / t0),
            vs30_m_s: site[i],
            scenario,
        };
        found.insert((seed[i], name[i].clone()), station);
    }

    // Each candidate's spectrum, then the grid every one of them covers.
    let c = Columns::of(&spectra, STATION_SPECTRA.name);
    let (s_seed, s_name, period) = (c.u64s(col::SEED)?, c.strs(col::STATION)?, c.f64s(col::PERIOD_S)?);
    let values = match settings.component {
        SetComponent::Rotd100 => c.f64s(col::ROTD100_M_S2)?,
        _ => c.f64s(col::ROTD50_M_S2)?,
    };
    let mut psa: BTreeMap<(u64, String), Vec<(f64, f64)>> = BTreeMap::new();
    for i in 0..s_seed.len() {
        let key = (s_seed[i], s_name[i].clone());
        if found.contains_key(&key) {
            psa.entry(key).or_default().push((period[i], values[i]));
        }
    }
    let mut grid: Option<Vec<f64>> = None;
    for v in psa.values() {
        let periods: Vec<f64> = v.iter().map(|p| p.0).collect();
        grid = Some(match grid {
            None => periods,
            Some(g) => g.into_iter().filter(|t| periods.iter().any(|p| p.to_bits() == t.to_bits())).collect(),
        });
    }
    let mut grid = grid.unwrap_or_default();
    grid.sort_by(f64::total_cmp);
    let mut members = Vec::new();
    for (key, v) in psa.iter().filter(|_| !grid.is_empty()) {
        let at = |t: f64| v.iter().find(|p| p.0.to_bits() == t.to_bits()).map(|p| p.1);
        let Some(values) = grid.iter().map(|&t| at(t)).collect::<Option<Vec<f64>>>() else { continue };
        if values.iter().any(|v| !(*v > 0.0)) {
            continue;
        }
        members.push(Member {
            id: format!("{}/{}", key.0, key.1),
            group: format!("seed {}", key.0),
            psa: values,
            usable_s: (grid[0], grid[grid.len() - 1]),
            meta: found[key].clone(),
        });
    }
    let note = format!(
        "surface stations{}{}: {} of {}, each by its {} ({})",
        settings.vs30_m_s.map_or(String::new(), |v| format!(" on V_S30 = {v} m/s")),
        settings.bins_text().map_or(String::new(), |b| format!(" at {b}")),
        members.len(),
        all,
        if settings.component == SetComponent::Rotd100 { "RotD100" } else { "RotD50" },
        match (grid.first(), grid.last()) {
            (Some(a), Some(b)) => format!("the grid {a:.3} … {b:.3} s, where every one is usable"),
            _ => "no period where every one is usable".into(),
        },
    );
    if members.is_empty() {
        return Err(EnsembleError::Setup(format!(
            "set: no record to choose from: {note} (widen set.magnitude_min/max or set.distance_min_km/max_km, or run \
             more seeds)"
        )));
    }
    let pool = Pool { grid, members };
    let Chosen { selection, periods, target, spectra } =
        choose(&pool, settings).map_err(|e| EnsembleError::Setup(format!("{e}; the candidates: {note}")))?;
    let chosen: Vec<&Station> = selection.records.iter().map(|c| &pool.members[c.index].meta).collect();
    let rows: Vec<SetRow> = selection
        .records
        .iter()
        .zip(&chosen)
        .map(|(c, st)| SetRow {
            seed: st.seed,
            record: st.name.clone(),
            label: "rupture".into(),
            node: st.node,
            component: settings.component.name().into(),
            scale_factor: c.scale,
            misfit: c.misfit,
            usable_hz: st.usable_hz,
            scenario: Some(st.scenario),
        })
        .collect();
    write_parquet_atomic(&mut set_frame(&rows)?, &out.gathered(&SET))?;
    clear_set_dir(out)?;
    let codes = station_codes(&name);
    write_station_files(out, pipeline, settings, &rows, &chosen, &codes)?;
    Ok(SetOutcome { selection, rows, periods, target, spectra, candidates: pool.members.len(), pool: Some(note) })
}

/// A chosen station's record, processed as the analysis processed it: each component with its
/// code and name, and the time of the record's first input sample (s of the run).
pub(crate) struct Components {
    pub(crate) parts: Vec<(&'static str, &'static str, Processed)>,
    pub(crate) begin_s: f64,
}

/// `v` to three significant digits.
fn approx3(v: f64) -> String {
    let digits = (2 - v.abs().log10().floor() as i32).max(0) as usize;
    format!("{v:.digits$}")
}

/// A component's SEED channel code (band `H` at 80 Hz or more, else `B`; instrument `N`, an
/// accelerometer; orientation `1` along strike, `2` fault-normal, `Z` up) and its orientation in
/// the files: the strike taken as north, the fault-normal side as east.
pub(crate) fn channel(code: &str, dt_s: f64) -> (String, Orientation) {
    let band = if 1.0 / dt_s >= 80.0 { 'H' } else { 'B' };
    let (axis, orientation) = match code {
        "FP" => ('1', Orientation { incidence_deg: 90.0, azimuth_deg: 0.0 }),
        "FN" => ('2', Orientation { incidence_deg: 90.0, azimuth_deg: 90.0 }),
        _ => ('Z', Orientation { incidence_deg: 0.0, azimuth_deg: 0.0 }),
    };
    (format!("{band}N{axis}"), orientation)
}

/// The lattice record of `st` from the seed's control table: the last 2/f_low of the run at the
/// interval asked, the horizontal pair and the vertical component when it was recorded.
pub(crate) fn lattice_components(
    control: &DataFrame,
    seed: u64,
    st: &Station,
    interval_s: Option<f64>,
) -> Result<Components, EnsembleError> {
    let read = |component| -> Result<(Vec<f64>, Vec<f64>), EnsembleError> {
        read_control(control, st.node as u64, component, Kinematic::Acceleration)?.ok_or_else(|| {
            EnsembleError::Setup(format!("seed {seed}, station {}: no acceleration in the control table", st.name))
        })
    };
    let ((t, x), (_, z)) = (read(Component::X)?, read(Component::Z)?);
    // The vertical, when the control table holds it; the scene's y points down: up is −y.
    let up: Option<Vec<f64>> = read_control(control, st.node as u64, Component::Y, Kinematic::Acceleration)?
        .filter(|(_, y)| y.len() == t.len())
        .map(|(_, y)| y.iter().map(|v| -v).collect());
    if t.len() < 8 || z.len() != t.len() {
        return Err(EnsembleError::Setup(format!(
            "seed {seed}, station {}: its control record has {} samples, too few to write",
            st.name,
            t.len()
        )));
    }
    // The record the analysis processed: the last 2/f_low of the run (the shear stage, two
    // cycles of the low corner), at the run's own interval (a whole number of steps)...
    let length = stickslip_analysis::motions::LOW_CORNER_CYCLES / st.band_hz.0;
    let last = t.len() - 1;
    let k0 = t.iter().position(|&v| v >= t[last] - length - 0.5 * (t[last] - t[last - 1])).unwrap_or(0);
    let dt = (t[last] - t[k0]) / (last - k0) as f64;
    // ... written at exactly the interval asked (record.interval_s), resampled band-limited: the
    // record's usable band (≤ f_max, a few Hz) lies far below either interval's Nyquist.
    let up = up.as_deref().unwrap_or(&[]);
    let (x, z, up, dt) = match interval_s {
        Some(iv) if (iv - dt).abs() > 1e-9 * dt => {
            let [x, z] = resample_together([&x[k0..], &z[k0..]], dt, iv);
            let up = if up.is_empty() { Vec::new() } else { resample(&up[k0..], dt, iv) };
            (x, z, up, iv)
        }
        _ => (x[k0..].to_vec(), z[k0..].to_vec(), up.get(k0..).unwrap_or(&[]).to_vec(), dt),
    };
    let fail = |e: String| EnsembleError::Setup(format!("seed {seed}, station {}: {e}", st.name));
    let (px, pz) = processed_pair(&x, &z, dt, st.band_hz.0, st.band_hz.1).map_err(fail)?;
    let mut parts = vec![("FP", "fault-parallel (x)", px), ("FN", "fault-normal (z)", pz)];
    if !up.is_empty() {
        let py = process(&up, dt, &ProcessingOptions::new(st.band_hz.0, Some(st.band_hz.1)))
            .map_err(|e| fail(format!("y: {e}")))?;
        parts.push(("UP", "vertical (up, −y)", py));
    }
    Ok(Components { parts, begin_s: t[k0] })
}

/// The broadband record of `st` from the seed's station_records table: the whole record at its
/// interval, the horizontal pair as the analysis processed it and the vertical component with the
/// same processing.
pub(crate) fn broadband_components(records: &DataFrame, seed: u64, st: &Station) -> Result<Components, EnsembleError> {
    let read = |component: &str| -> Result<ComponentRecord, EnsembleError> {
        read_station_record(records, &st.name, component)?.ok_or_else(|| {
            EnsembleError::Setup(format!(
                "seed {seed}, station {}: no {component} in the station_records table",
                st.name
            ))
        })
    };
    let (x, y, z) = (read("x")?, read("y")?, read("z")?);
    if x.time_s.len() < 8 {
        return Err(EnsembleError::Setup(format!(
            "seed {seed}, station {}: its broadband record is too short",
            st.name
        )));
    }
    // The analysis processed the record at its own interval, which is the first instant after 0.
    let dt = x.time_s[1] - x.time_s[0];
    let fail = |e: String| EnsembleError::Setup(format!("seed {seed}, station {}: {e}", st.name));
    let (px, pz) =
        processed_pair(&x.broadband_m_s2, &z.broadband_m_s2, dt, st.band_hz.0, st.band_hz.1).map_err(fail)?;
    // The scene's y points down from the free surface: up is −y.
    let up: Vec<f64> = y.broadband_m_s2.iter().map(|v| -v).collect();
    let py = process(&up, dt, &ProcessingOptions::new(st.band_hz.0, Some(st.band_hz.1)))
        .map_err(|e| fail(format!("y: {e}")))?;
    Ok(Components {
        parts: vec![("FP", "fault-parallel (x)", px), ("FN", "fault-normal (z)", pz), ("UP", "vertical (up, −y)", py)],
        begin_s: x.time_s[0],
    })
}

/// Writes each chosen station's components scaled by its factor, as AT2, SAC and MiniSEED: `FP` the
/// fault-parallel component (x, along strike), `FN` the fault-normal one (z) and `UP` the
/// vertical one (up, −y) when recorded; the magnitude in the header, the factor, the usable band and
/// the distances in the SAC `USER` numbers.
fn write_station_files(
    out: &Folder,
    pipeline: &Pipeline,
    settings: &SetSettings,
    rows: &[SetRow],
    chosen: &[&Station],
    codes: &BTreeMap<String, String>,
) -> Result<(), EnsembleError> {
    let dir = out.set_dir();
    let mut by_seed: BTreeMap<u64, Vec<usize>> = BTreeMap::new();
    for (k, r) in rows.iter().enumerate() {
        by_seed.entry(r.seed).or_default().push(k);
    }
    for (seed, ks) in by_seed {
        let broadband = ks.iter().any(|&k| chosen[k].vs30_m_s.is_some());
        let table = if broadband { STATION_RECORDS } else { CONTROL };
        let Some(frame) = read_parquet_if_present(&out.part(&table, seed))? else {
            return Err(EnsembleError::Setup(format!(
                "seed {seed}: no {} table to write the set's records from",
                table.name
            )));
        };
        for k in ks {
            let (r, st) = (&rows[k], chosen[k]);
            let components = if st.vs30_m_s.is_some() {
                broadband_components(&frame, seed, st)?
            } else {
                lattice_components(&frame, seed, st, pipeline.scene.record.interval_s)?
            };
            let m = st.scenario;
            for (code, long, p) in &components.parts {
                let a: Vec<f64> = p.accel.iter().map(|v| r.scale_factor * v).collect();
                let stem = format!("{}_set{:02}_seed{seed}_{}_{code}", pipeline.name, k + 1, st.name);
                let site = st.vs30_m_s.map_or(String::new(), |v| format!(", V_S30 {v} m/s"));
                let (seed_channel, orientation) = channel(code, p.dt);
                let description = format!(
                    "stickslip {} set record {} of {}: seed {seed} station {} {long} ({seed_channel}), Mw {:.2} (the \
                     rupture's moment magnitude, also in MAG), R_rup {:.1} km{site}, x {:.4}, usable {} … {} s \
                     (band-pass {:.4} … {:.4} Hz), matched to {}",
                    pipeline.name,
                    k + 1,
                    rows.len(),
                    st.name,
                    m.mw,
                    m.r_rup_km,
                    r.scale_factor,
                    approx3(1.0 / r.usable_hz.1),
                    approx3(1.0 / r.usable_hz.0),
                    st.band_hz.0,
                    st.band_hz.1,
                    settings.target_name
                );
                let numbers: [(&str, &[f64]); 3] = [
                    ("SCALE", &[r.scale_factor]),
                    ("USABLE", &[r.usable_hz.0, r.usable_hz.1]),
                    ("RRUP_RJB", &[m.r_rup_km, m.r_jb_km]),
                ];
                let station = &format!("S{k:02}", k = k + 1);
                let record = RecordFile {
                    description: &description,
                    accel_m_s2: &a,
                    dt_s: p.dt,
                    begin_s: components.begin_s + p.t_first,
                    motion: None,
                    station,
                    component: &seed_channel,
                    network: "SS",
                    location: "P",
                    event: &format!("seed{seed}"),
                    position_m: Some(st.position_m),
                    orientation: Some(orientation),
                    magnitude: Some(m.mw),
                    // The rupture starts at t = 0 on the run's clock.
                    origin_s: Some(0.0),
                    numbers: &numbers,
                };
                for format in [&At2 as &dyn RecordFormat, &Sac] {
                    let bytes = format.encode(&record).map_err(EnsembleError::Set)?;
                    write_bytes_atomic(&dir.join(format!("{stem}.{}", format.extension())), &bytes)?;
                }
                // MiniSEED under the station's own code, whose channel the inventory describes
                // (`exchange`): the set rank and scale factor are in the file's name and the set table.
                let code = codes.get(&st.name).map_or(station.as_str(), String::as_str);
                let mseed = RecordFile { station: code, location: "", ..record };
                let bytes = Mseed.encode(&mseed).map_err(EnsembleError::Set)?;
                write_bytes_atomic(&dir.join(format!("{stem}.{}", Mseed.extension())), &bytes)?;
            }
        }
    }
    Ok(())
}
