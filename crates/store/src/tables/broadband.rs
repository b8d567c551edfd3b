//! The broadband records of a fault scene's surface stations (docs/model.md §17), with the two
//! parts they are joined from.
//!
//! **station_records**, one row per seed, station (record), component and sample: `seed` u64,
//! `station` str (a station simulated on several sites has one record per site,
//! `<station>_vs<V_S30>`), `component` str (`x` along strike, `y` vertical, `z` fault-normal),
//! `time_s` (from the rupture's start, every `[broadband] interval_s`), `deterministic_m_s2` (the
//! lattice's acceleration at the site, low-passed), `stochastic_m_s2` (the stochastic part at the
//! site, high-passed), `broadband_m_s2` (their sum: the record) f64, `pga_760_g` f64 (the
//! reference-rock PGA of the nonlinear site term, the same on every row of a component). The
//! records are unprocessed: the `stations` and `station_spectra` tables and the record sets
//! measure them after the records' processing.

use polars::prelude::DataFrame;
use stickslip_analysis::StationRow;
use stickslip_seismo::broadband::stochastic::COMPONENTS;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Columns, Frame};
use crate::spec::{Scope, SeedTable, TableSpec};

/// Each broadband record, component by component, with its parts.
pub const STATION_RECORDS: TableSpec = TableSpec {
    name: "station_records",
    scope: Scope::Gathered,
    key: &[col::SEED, col::STATION, col::COMPONENT, col::TIME_S],
    columns: &[
        col::SEED,
        col::STATION,
        col::COMPONENT,
        col::TIME_S,
        col::DETERMINISTIC_M_S2,
        col::STOCHASTIC_M_S2,
        col::BROADBAND_M_S2,
        col::PGA_760_G,
    ],
    variable: None,
};

/// The `station_records` part of a seed with broadband records.
pub const STATION_RECORDS_PART: SeedTable = SeedTable {
    spec: STATION_RECORDS,
    write: |s| {
        let rows = &s.analysis.stations;
        if rows.iter().all(|r| r.broadband.is_none()) {
            Ok(None)
        } else {
            station_records_frame(s.seed, rows).map(Some)
        }
    },
};

/// The station_records table of one seed.
pub fn station_records_frame(seed: u64, rows: &[StationRow]) -> Result<DataFrame, StoreError> {
    let (mut name, mut comp, mut time) = (Vec::new(), Vec::new(), Vec::new());
    let (mut det, mut sto, mut bb, mut pga) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for r in rows {
        let Some(b) = &r.broadband else { continue };
        let dt = b.record.dt_s;
        for (c, part) in b.record.components.iter().enumerate() {
            let n = part.broadband.len();
            name.extend(std::iter::repeat_n(r.station.name.clone(), n));
            comp.extend(std::iter::repeat_n(COMPONENTS[c], n));
            time.extend((0..n).map(|k| k as f64 * dt));
            det.extend_from_slice(&part.deterministic);
            sto.extend_from_slice(&part.stochastic);
            bb.extend_from_slice(&part.broadband);
            pga.extend(std::iter::repeat_n(part.pga_760_g, n));
        }
    }
    Frame::new(name.len())
        .u64(col::SEED, vec![seed; name.len()])
        .str(col::STATION, name)
        .static_str(col::COMPONENT, comp)
        .f64(col::TIME_S, time)
        .f64(col::DETERMINISTIC_M_S2, det)
        .f64(col::STOCHASTIC_M_S2, sto)
        .f64(col::BROADBAND_M_S2, bb)
        .f64(col::PGA_760_G, pga)
        .finish(STATION_RECORDS.name)
}

/// One component of a station's broadband record read back.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ComponentRecord {
    /// Instants from the rupture's start (s).
    pub time_s: Vec<f64>,
    /// The lattice's part at the site, low-passed (m/s²).
    pub deterministic_m_s2: Vec<f64>,
    /// The stochastic part at the site, high-passed (m/s²).
    pub stochastic_m_s2: Vec<f64>,
    /// The record (m/s²).
    pub broadband_m_s2: Vec<f64>,
}

/// The component `component` (`x`, `y` or `z`) of `station`'s record in a `station_records` frame
/// (one seed's part), in time order; `None` when it has none.
pub fn read_station_record(
    df: &DataFrame,
    station: &str,
    component: &str,
) -> Result<Option<ComponentRecord>, StoreError> {
    let c = Columns::of(df, STATION_RECORDS.name);
    let (names, comps) = (c.strs(col::STATION)?, c.strs(col::COMPONENT)?);
    let (t, d, s, b) = (
        c.f64s(col::TIME_S)?,
        c.f64s(col::DETERMINISTIC_M_S2)?,
        c.f64s(col::STOCHASTIC_M_S2)?,
        c.f64s(col::BROADBAND_M_S2)?,
    );
    let mut rows: Vec<usize> = (0..names.len()).filter(|&i| names[i] == station && comps[i] == component).collect();
    if rows.is_empty() {
        return Ok(None);
    }
    rows.sort_by(|&i, &j| t[i].total_cmp(&t[j]));
    let pick = |v: &[f64]| rows.iter().map(|&i| v[i]).collect();
    Ok(Some(ComponentRecord {
        time_s: pick(&t),
        deterministic_m_s2: pick(&d),
        stochastic_m_s2: pick(&s),
        broadband_m_s2: pick(&b),
    }))
}
