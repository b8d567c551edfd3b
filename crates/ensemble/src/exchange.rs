//! The output folder in seismology's exchange formats, written with the gathered tables so that
//! ObsPy and catalogue tools read a run without a converter (docs/guide/exchange.md):
//!
//! - `stations.xml`: a StationXML 1.2 inventory of every channel whose records the folder holds
//!   as MiniSEED — the event records' nodes (`N<LDEM>`, location `M` model scale / `P` prototype
//!   scale) of a block, every station of a fault scenario (`S001`, `S002`, … in the order of
//!   their names; the full name is the site's name);
//! - `catalogue.xml`: the events as QuakeML 1.2 — origin time on the nominal clock, hypocentre,
//!   M0, Mw (preferred) and, for a block, the paper's Riera magnitude as a second magnitude;
//! - `mseed/<pipeline>_seed<k>.mseed` for a fault scenario: every station's record of the seed
//!   (the three components as the analysis processed them, m/s²), one MiniSEED file per seed.
//!
//! **Coordinates.** A scene's metres are mapped to degrees about its origin on a sphere
//! ([`local_to_geographic`]): `[exchange] origin_lat_deg, origin_lon_deg`, else 0° N 0° E; every
//! station's description gives the scene's own coordinates. A block's x is east, y north, z up (the base, the fault, at z = 0,
//! depth 0 for its events); a fault scenario's x (along strike) is north, z (fault-normal) east and
//! y depth below the free surface.
//!
//! **Time.** A simulated event has no date: time 0 of a run is 2000-01-01T00:00:00Z, as in the
//! SAC and MiniSEED records. A block's catalogue is at prototype scale (times ×λ), as its
//! magnitudes are; every seed's clock starts again at that date, and the event's identifier says
//! which seed it is.

use std::collections::BTreeMap;
use std::path::PathBuf;

use polars::prelude::DataFrame;
use stickslip_config::Pipeline;
use stickslip_seismo::accelerogram::Orientation;
use stickslip_seismo::accelerogram::mseed::{MseedTrace, UtcTime, channel_code, mseed_bytes, sample_rate};
use stickslip_seismo::quakeml::{Catalogue, QuakeEvent, QuakeMagnitude, quakeml};
use stickslip_seismo::stationxml::{Channel, Inventory, Network, Station, Units, local_to_geographic, stationxml};
use stickslip_store::Folder;
use stickslip_store::frame::Columns;
use stickslip_store::io::{read_parquet_if_present, write_bytes_atomic, write_text_atomic};
use stickslip_store::schema::{
    CONTROL, EVENTS_TABLE, RECORDS, RUPTURES, SIMILARITY, SOURCE, STATION_RECORDS, STATIONS, col,
};
use stickslip_store::tables::set::ScenarioMeta;

use crate::error::EnsembleError;
use crate::scenario_set::{self, Components};

/// Network code of every record.
pub const NETWORK: &str = "SS";
/// Where the scene's origin is on the globe (degrees): `[exchange]`, else 0° N 0° E.
pub fn origin_lat_lon(pipeline: &Pipeline) -> (f64, f64) {
    pipeline.file.exchange.as_ref().map_or((0.0, 0.0), |x| (x.origin_lat_deg, x.origin_lon_deg))
}

/// The origin as the descriptions say it, e.g. `34.05N 116.5W`.
fn origin_text((lat, lon): (f64, f64)) -> String {
    format!("{}{} {}{}", lat.abs(), if lat < 0.0 { "S" } else { "N" }, lon.abs(), if lon < 0.0 { "W" } else { "E" })
}
/// The start of every station's epoch: a day before the nominal time 0 of a run.
const EPOCH_START_S: f64 = -86_400.0;

/// What [`write_exchange`] wrote.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ExchangeReport {
    /// The inventory, when any record is in MiniSEED.
    pub inventory: Option<PathBuf>,
    /// Channels in the inventory.
    pub channels: usize,
    /// The QuakeML catalogue, when the folder has events.
    pub catalogue: Option<PathBuf>,
    /// Events in the catalogue.
    pub events: usize,
    /// MiniSEED files of a fault scenario's stations.
    pub station_files: usize,
}

/// One channel of the inventory, before it is written.
#[derive(Clone, Debug)]
struct Chan {
    station: String,
    /// The station's site name.
    site: String,
    /// What the channel's location is (e.g. the scale), in its description.
    note: String,
    location: String,
    channel: String,
    /// East, north (m) and elevation (m, up) in the scene's frame.
    east_north_up: [f64; 3],
    /// Depth below the ground surface (m; a fault scenario's buried station), 0 on it or in a
    /// block.
    depth_m: f64,
    orientation: Orientation,
    rate_hz: f64,
}

/// Writes the inventory, the catalogue and a fault scenario's station records of the gathered
/// folder `out` (see the module documentation).
pub fn write_exchange(out: &Folder, pipeline: &Pipeline) -> Result<ExchangeReport, EnsembleError> {
    let mut report = ExchangeReport::default();
    let mut channels = Vec::new();
    let events = if pipeline.scene.is_fault() {
        channels.extend(fault_station_records(out, pipeline, &mut report)?);
        fault_events(out, pipeline)?
    } else {
        if pipeline.analysis.accelerograms.as_ref().is_some_and(|a| a.formats.iter().any(|f| f.name() == "mseed")) {
            channels.extend(block_channels(out)?);
        }
        block_events(out, pipeline)?
    };
    if !channels.is_empty() {
        let path = out.root().join("stations.xml");
        report.channels = channels.len();
        write_text_atomic(&path, &inventory_text(pipeline, &channels)?)?;
        report.inventory = Some(path);
    }
    if !events.is_empty() {
        let now = UtcTime::from_nominal(0.0).map_err(EnsembleError::Exchange)?.iso();
        let cat = Catalogue {
            public_id_prefix: format!("smi:local/stickslip/{}", pipeline.name),
            description: format!(
                "stickslip pipeline {} (hash {}): simulated events; times on the nominal clock (each seed's run \
                 starts at 2000-01-01T00:00:00Z)",
                pipeline.name, pipeline.hash
            ),
            creation_utc: now,
            agency_id: "stickslip".into(),
            author: format!("stickslip {}", env!("CARGO_PKG_VERSION")),
            events,
        };
        let path = out.root().join("catalogue.xml");
        report.events = cat.events.len();
        write_text_atomic(&path, &quakeml(&cat).map_err(EnsembleError::Exchange)?)?;
        report.catalogue = Some(path);
    }
    Ok(report)
}

/// The inventory of `channels`, grouped by station.
fn inventory_text(pipeline: &Pipeline, channels: &[Chan]) -> Result<String, EnsembleError> {
    let start = UtcTime::from_nominal(EPOCH_START_S).map_err(EnsembleError::Exchange)?.iso();
    let mut by_station: BTreeMap<&str, Vec<&Chan>> = BTreeMap::new();
    for c in channels {
        by_station.entry(&c.station).or_default().push(c);
    }
    let (lat0, lon0) = origin_lat_lon(pipeline);
    let stations = by_station
        .into_iter()
        .map(|(code, chans)| {
            // The station stands where its prototype-scale (or only) channels are.
            let c0 = chans.iter().find(|c| c.location == "P").unwrap_or(&chans[0]);
            let [e, n, u] = c0.east_north_up.map(|v| v + 0.0);
            let (lat, lon) = local_to_geographic(e, n, lat0, lon0);
            let mut places: Vec<String> = chans
                .iter()
                .map(|c| {
                    let [e, n, u] = c.east_north_up.map(|v| v + 0.0);
                    format!(
                        "{}east {e} m, north {n} m, up {u} m",
                        if c.note.is_empty() { String::new() } else { format!("{}: ", c.note) }
                    )
                })
                .collect();
            places.dedup();
            Station {
                code: code.to_string(),
                latitude_deg: lat,
                longitude_deg: lon,
                // The station's ground surface; a buried sensor's depth is its channel's.
                elevation_m: u + c0.depth_m,
                site_name: c0.site.clone(),
                description: format!(
                    "{} in the scene's coordinates ({}; degrees about {} on a sphere of 6371 km)",
                    c0.site,
                    places.join("; "),
                    origin_text((lat0, lon0))
                ),
                start_utc: start.clone(),
                channels: chans
                    .iter()
                    .map(|c| {
                        let [e, n, u] = c.east_north_up;
                        let (lat, lon) = local_to_geographic(e, n, lat0, lon0);
                        Channel {
                            code: c.channel.clone(),
                            location_code: c.location.clone(),
                            latitude_deg: lat,
                            longitude_deg: lon,
                            elevation_m: u + 0.0,
                            depth_m: c.depth_m,
                            azimuth_deg: c.orientation.azimuth_deg,
                            dip_deg: c.orientation.incidence_deg - 90.0,
                            sample_rate_hz: c.rate_hz,
                            units: Units::Acceleration,
                            start_utc: start.clone(),
                            description: format!(
                                "{}{} acceleration (m/s², one count = 1 m/s²)",
                                c.site,
                                if c.note.is_empty() { String::new() } else { format!(", {}", c.note) }
                            ),
                        }
                    })
                    .collect(),
            }
        })
        .collect();
    let inv = Inventory {
        source: format!("stickslip pipeline {} (hash {})", pipeline.name, pipeline.hash),
        sender: "stickslip".into(),
        module: format!("stickslip {}", env!("CARGO_PKG_VERSION")),
        created_utc: UtcTime::from_nominal(0.0).map_err(EnsembleError::Exchange)?.iso(),
        networks: vec![Network {
            code: NETWORK.into(),
            description: format!("stickslip simulated stations of pipeline {}", pipeline.name),
            start_utc: start,
            stations,
        }],
    };
    stationxml(&inv).map_err(EnsembleError::Exchange)
}

/// A block's record channels, from the gathered `records` table: node, component and scale
/// (each scale its own location and rate).
fn block_channels(out: &Folder) -> Result<Vec<Chan>, EnsembleError> {
    let Some(df) = read_parquet_if_present(&out.gathered(&RECORDS))? else { return Ok(vec![]) };
    let c = Columns::of(&df, RECORDS.name);
    let (node, component, scale) = (c.u64s(col::NODE)?, c.strs(col::COMPONENT)?, c.strs(col::SCALE)?);
    let (x, y, z, dt) = (c.f64s(col::X_M)?, c.f64s(col::Y_M)?, c.f64s(col::Z_M)?, c.f64s(col::DT_S)?);
    let mut found: BTreeMap<(String, String, String), Chan> = BTreeMap::new();
    for i in 0..df.height() {
        let station = format!("N{}", node[i]);
        let location = if scale[i] == "model" { "M" } else { "P" }.to_string();
        let rate = sample_rate(dt[i]);
        let channel = channel_code(&component[i], rate).map_err(EnsembleError::Exchange)?;
        let Some(orientation) = Orientation::of_axis(&component[i]) else { continue };
        found.entry((station.clone(), location.clone(), channel.clone())).or_insert(Chan {
            site: format!("node {}", node[i]),
            note: format!("{} scale", scale[i]),
            station,
            location,
            channel,
            east_north_up: [x[i], y[i], z[i]],
            depth_m: 0.0,
            orientation,
            rate_hz: rate,
        });
    }
    Ok(found.into_values().collect())
}

/// A block's events at prototype scale, from the gathered `similarity`, `events` and (when the
/// fronts were found) `ruptures` tables.
fn block_events(out: &Folder, pipeline: &Pipeline) -> Result<Vec<QuakeEvent>, EnsembleError> {
    let (Some(sim), Some(ev)) =
        (read_parquet_if_present(&out.gathered(&SIMILARITY))?, read_parquet_if_present(&out.gathered(&EVENTS_TABLE))?)
    else {
        return Ok(vec![]);
    };
    let c = Columns::of(&ev, EVENTS_TABLE.name);
    let start: BTreeMap<(u64, u64), f64> =
        c.u64s(col::SEED)?.into_iter().zip(c.u64s(col::EVENT)?).zip(c.f64s(col::START_S)?).collect();
    let hypocentre: BTreeMap<(u64, u64), (f64, f64)> = match read_parquet_if_present(&out.gathered(&RUPTURES))? {
        Some(r) => {
            let c = Columns::of(&r, RUPTURES.name);
            let keys = c.u64s(col::SEED)?.into_iter().zip(c.u64s(col::EVENT)?);
            let (hx, hy) = (c.opt_f64s(col::HYPOCENTRE_X_M)?, c.opt_f64s(col::HYPOCENTRE_Y_M)?);
            keys.zip(hx.into_iter().zip(hy)).filter_map(|(k, (x, y))| Some((k, (x?, y?)))).collect()
        }
        None => BTreeMap::new(),
    };
    let c = Columns::of(&sim, SIMILARITY.name);
    let (seed, event, kind, label) = (c.u64s(col::SEED)?, c.u64s(col::EVENT)?, c.strs(col::KIND)?, c.strs(col::LABEL)?);
    let (lambda, m0_dyne_cm) = (c.f64s(col::LAMBDA)?, c.f64s(col::M0_CONSISTENT_DYNE_CM)?);
    let (mw, riera) = (c.f64s(col::MW_CONSISTENT)?, c.f64s(col::M_RIERA_PAPER_INTERPLATE)?);
    let dims = pipeline.scene.dims;
    let centre = [dims.nx as f64 * pipeline.scene.lc_m / 2.0, dims.ny as f64 * pipeline.scene.lc_m / 2.0];
    let (lat0, lon0) = origin_lat_lon(pipeline);
    let mut events = Vec::new();
    for i in 0..sim.height() {
        let key = (seed[i], event[i]);
        let Some(&t) = start.get(&key) else { continue };
        let l = lambda[i];
        let (located, [hx, hy]) = match hypocentre.get(&key) {
            Some(&(x, y)) => (true, [x, y]),
            None => (false, centre),
        };
        let (lat, lon) = local_to_geographic(hx * l, hy * l, lat0, lon0);
        let values = [mw[i], riera[i], m0_dyne_cm[i]];
        if values.iter().any(|v| !v.is_finite()) {
            continue;
        }
        events.push(QuakeEvent {
            id: format!("seed{}/event{}", seed[i], event[i]),
            event_type: "earthquake".into(),
            description: format!(
                "stickslip {} seed {} event {} ({}, {}): simulated stick-slip event of the block at prototype scale \
                 (lambda = {l})",
                pipeline.name, seed[i], event[i], label[i], kind[i]
            ),
            origin_time_utc: UtcTime::from_nominal(t * l).map_err(EnsembleError::Exchange)?.iso(),
            latitude_deg: lat,
            longitude_deg: lon,
            depth_m: 0.0,
            origin_comment: Some(if located {
                format!(
                    "hypocentre on the base of the block (the fault): x {} m, y {} m at prototype scale",
                    hx * l,
                    hy * l
                )
            } else {
                format!(
                    "hypocentre not located (no rupture front found): the centre of the base, x {} m, y {} m at \
                     prototype scale",
                    hx * l,
                    hy * l
                )
            }),
            scalar_moment_n_m: Some(m0_dyne_cm[i] * 1e-7),
            magnitudes: vec![
                QuakeMagnitude {
                    value: mw[i],
                    magnitude_type: "Mw".into(),
                    method: "moment magnitude of the consistently scaled moment (stickslip similarity)".into(),
                },
                QuakeMagnitude {
                    value: riera[i],
                    magnitude_type: "M".into(),
                    method: "Riera magnitude of the paper, interplate".into(),
                },
            ],
        });
    }
    Ok(events)
}

/// A fault scenario's ruptures, one per seed, from the gathered `source` table.
fn fault_events(out: &Folder, pipeline: &Pipeline) -> Result<Vec<QuakeEvent>, EnsembleError> {
    let Some(src) = read_parquet_if_present(&out.gathered(&SOURCE))? else { return Ok(vec![]) };
    let c = Columns::of(&src, SOURCE.name);
    let (seed, m0, mw) = (c.u64s(col::SEED)?, c.f64s(col::M0_N_M)?, c.f64s(col::MW)?);
    let (hx, hy) = (c.opt_f64s(col::HYPOCENTRE_X_M)?, c.opt_f64s(col::HYPOCENTRE_Y_M)?);
    let (lat0, lon0) = origin_lat_lon(pipeline);
    let mut events = Vec::new();
    for i in 0..src.height() {
        let (Some(x), Some(y)) = (hx[i], hy[i]) else { continue };
        if !(m0[i].is_finite() && mw[i].is_finite()) {
            continue;
        }
        // Along strike (x) is north, the fault plane z = 0 east; y is depth.
        let (lat, lon) = local_to_geographic(0.0, x, lat0, lon0);
        events.push(QuakeEvent {
            id: format!("seed{}", seed[i]),
            event_type: "earthquake".into(),
            description: format!("stickslip {} seed {}: simulated rupture of the fault", pipeline.name, seed[i]),
            origin_time_utc: UtcTime::from_nominal(0.0).map_err(EnsembleError::Exchange)?.iso(),
            latitude_deg: lat,
            longitude_deg: lon,
            depth_m: y.abs(),
            origin_comment: Some(format!("hypocentre on the fault: {x} m along strike, {} m deep", y.abs())),
            scalar_moment_n_m: Some(m0[i]),
            magnitudes: vec![QuakeMagnitude {
                value: mw[i],
                magnitude_type: "Mw".into(),
                method: "moment magnitude of the moment summed over the fault (Hanks and Kanamori 1979)".into(),
            }],
        });
    }
    Ok(events)
}

/// Writes every station record of every seed of a fault scenario as MiniSEED and returns their
/// channels.
fn fault_station_records(
    out: &Folder,
    pipeline: &Pipeline,
    report: &mut ExchangeReport,
) -> Result<Vec<Chan>, EnsembleError> {
    let Some(stations) = read_parquet_if_present(&out.gathered(&STATIONS))? else { return Ok(vec![]) };
    let c = Columns::of(&stations, STATIONS.name);
    let (seed, name, node) = (c.u64s(col::SEED)?, c.strs(col::STATION)?, c.u64s(col::NODE)?);
    let (x, y, z) = (c.f64s(col::X_M)?, c.f64s(col::Y_M)?, c.f64s(col::Z_M)?);
    let (f_low, f_high) = (c.opt_f64s(col::F_LOW_HZ)?, c.opt_f64s(col::F_HIGH_HZ)?);
    let site = if c.has(col::VS30_M_S) { c.opt_f64s(col::VS30_M_S)? } else { vec![None; seed.len()] };
    let codes = scenario_set::station_codes(&name);
    let mut by_seed: BTreeMap<u64, Vec<usize>> = BTreeMap::new();
    for i in 0..seed.len() {
        by_seed.entry(seed[i]).or_default().push(i);
    }
    let dir = out.root().join("mseed");
    let mut channels: BTreeMap<(String, String), Chan> = BTreeMap::new();
    for (s, rows) in by_seed {
        // A broadband record (a site's V_S30) is in the station_records table, a lattice record in
        // the control table; each read once, when a station needs it.
        let (mut control, mut broadband): (Option<Option<DataFrame>>, Option<Option<DataFrame>>) = (None, None);
        let mut bytes = Vec::new();
        for i in rows {
            let (Some(lo), Some(hi)) = (f_low[i], f_high[i]) else { continue };
            let st = scenario_set::Station {
                seed: s,
                name: name[i].clone(),
                node: node[i] as u32,
                position_m: [x[i], y[i], z[i]],
                band_hz: (lo, hi),
                usable_hz: (lo, hi),
                vs30_m_s: site[i],
                scenario: ScenarioMeta { mw: f64::NAN, r_rup_km: f64::NAN, r_jb_km: f64::NAN },
            };
            let (slot, table) =
                if st.vs30_m_s.is_some() { (&mut broadband, STATION_RECORDS) } else { (&mut control, CONTROL) };
            if slot.is_none() {
                *slot = Some(read_parquet_if_present(&out.part(&table, s))?);
            }
            let Some(Some(frame)) = slot.as_ref() else { continue };
            let components = components_of(frame, &st, pipeline)?;
            let code = &codes[&name[i]];
            for (part, _, p) in &components.parts {
                let (channel, orientation) = scenario_set::channel(part, p.dt);
                let trace = MseedTrace {
                    network: NETWORK,
                    station: code,
                    location: "",
                    channel: &channel,
                    start_s: components.begin_s + p.t_first,
                    sample_rate_hz: sample_rate(p.dt),
                    samples: &p.accel,
                };
                bytes.extend(mseed_bytes(&trace).map_err(EnsembleError::Exchange)?);
                let site_name = match site[i] {
                    Some(v) => format!("{} (V_S30 {v} m/s)", name[i]),
                    None => name[i].clone(),
                };
                channels.entry((code.clone(), channel.clone())).or_insert(Chan {
                    station: code.clone(),
                    site: site_name,
                    note: String::new(),
                    location: String::new(),
                    channel,
                    east_north_up: [z[i], x[i], -y[i]],
                    depth_m: y[i].max(0.0),
                    orientation,
                    rate_hz: sample_rate(p.dt),
                });
            }
        }
        if !bytes.is_empty() {
            write_bytes_atomic(&dir.join(format!("{}_seed{s}.mseed", pipeline.name)), &bytes)?;
            report.station_files += 1;
        }
    }
    Ok(channels.into_values().collect())
}

/// The processed components of a station's record in the seed's `frame`.
fn components_of(
    frame: &DataFrame,
    st: &scenario_set::Station,
    pipeline: &Pipeline,
) -> Result<Components, EnsembleError> {
    if st.vs30_m_s.is_some() {
        scenario_set::broadband_components(frame, st.seed, st)
    } else {
        scenario_set::lattice_components(frame, st.seed, st, pipeline.scene.record.interval_s)
    }
}
