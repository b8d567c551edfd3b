//! The recorded series of one seed: the interface channels, the control nodes, the fault's
//! nodes, the skip log.

use polars::prelude::*;
use stickslip_solver::scene::{Component, Kinematic};
use stickslip_solver::{Lattice, Recording};

use crate::col;
use crate::error::StoreError;
use crate::frame::{Columns, Frame, narrow_f32, read_back};
use crate::spec::{Scope, SeedTable, TableSpec};

/// One row per recorded instant.
pub const SERIES: TableSpec = TableSpec {
    name: "series",
    scope: Scope::PerSeed,
    key: &[col::SEED, col::TIME_S],
    columns: &[col::SEED, col::TIME_S],
    variable: Some("one column per recorded channel (record.interface, record.energy)"),
};

/// One row per control node, component and instant.
pub const CONTROL: TableSpec = TableSpec {
    name: "control",
    scope: Scope::PerSeed,
    key: &[col::SEED, col::NODE, col::COMPONENT, col::TIME_S],
    columns: &[
        col::SEED,
        col::NODE,
        col::COMPONENT,
        col::TIME_S,
        "displacement_m",
        "velocity_m_s",
        col::ACCELERATION_M_S2,
    ],
    variable: None,
};

/// Every contact node of the base through the shear stage at the event trace's instants
/// (`record.fault`): one row per node and instant.
pub const FAULT: TableSpec = TableSpec {
    name: "fault",
    scope: Scope::PerSeed,
    key: &[col::SEED, col::NODE, col::TIME_S],
    columns: &[
        col::SEED,
        col::NODE,
        col::X_M,
        col::Y_M,
        col::TIME_S,
        col::SLIP_M,
        col::SLIP_RATE_M_S,
        col::SHEAR_STRESS_PA,
        col::NORMAL_STRESS_PA,
    ],
    variable: None,
};

/// The fault stations' time series (the benchmark files' content, `record.fault_stations_m`): one
/// row per station and instant of `record.fault_interval_s`.
pub const FAULT_STATION_SERIES: TableSpec = TableSpec {
    name: "fault_station_series",
    scope: Scope::PerSeed,
    // Two stations closer than the names' 100 m (on a finer lattice) share a name, not a node.
    key: &[col::SEED, col::STATION, col::NODE, col::TIME_S],
    columns: &[
        col::SEED,
        col::STATION,
        col::NODE,
        col::X_M,
        col::Y_M,
        col::TIME_S,
        col::SLIP_X_M,
        col::SLIP_Y_M,
        col::SLIP_RATE_X_M_S,
        col::SLIP_RATE_Y_M_S,
        col::SHEAR_STRESS_X_PA,
        col::SHEAR_STRESS_Y_PA,
        col::NORMAL_STRESS_PA,
    ],
    variable: None,
};

/// One row per quasi-static jump of the skip-ahead.
pub const SKIPS: TableSpec = TableSpec {
    name: "skips",
    scope: Scope::PerSeed,
    key: &[col::SEED, col::FROM_S],
    columns: &[col::SEED, col::FROM_S, col::TO_S, col::STEPS, col::NEXT, col::NODE],
    variable: None,
};

/// The `series` part of a seed.
pub const SERIES_PART: SeedTable =
    SeedTable { spec: SERIES, write: |s| series_frame(s.seed, &s.analysis.run.recording).map(Some) };
/// The `control` part of a seed.
pub const CONTROL_PART: SeedTable =
    SeedTable { spec: CONTROL, write: |s| control_frame(s.seed, &s.analysis.run.recording).map(Some) };
/// The `skips` part of a seed that skipped ahead.
pub const SKIPS_PART: SeedTable = SeedTable {
    spec: SKIPS,
    write: |s| {
        let rec = &s.analysis.run.recording;
        if rec.skips.is_empty() { Ok(None) } else { skips_frame(s.seed, rec).map(Some) }
    },
};
/// The `fault` part of a seed that recorded the fault, at the instants of `record.fault_interval_s`.
pub const FAULT_PART: SeedTable = SeedTable {
    spec: FAULT,
    write: |s| {
        let trace = &s.analysis.run.recording.trace;
        let keep = trace.thinned(s.model.scene().record.fault_interval_s);
        fault_frame(s.seed, trace, &keep, s.model.lattice())
    },
};

/// The `fault_station_series` part of a seed with fault stations.
pub const FAULT_STATION_SERIES_PART: SeedTable = SeedTable {
    spec: FAULT_STATION_SERIES,
    write: |s| {
        let trace = &s.analysis.run.recording.trace;
        if trace.stations.is_empty() {
            return Ok(None);
        }
        let keep = trace.thinned(s.model.scene().record.fault_interval_s);
        let origin = s.model.scene().fault.as_ref().map(|f| f.origin_m);
        fault_station_series_frame(s.seed, trace, &keep, s.model.lattice(), origin).map(Some)
    },
};

/// The fault stations' series of one seed at the trace's instants `keep`: `seed` u64, `station`
/// str (the name of its file: `faultst…` measured from `origin` on a fault scene, `fltst_…` on a
/// rigid base), `node` u32 (LDEM), `x_m`, `y_m`, `time_s`, then slip, slip rate and shear traction
/// along x and y and the normal traction (compression positive), f64 — the values the station
/// files print, in full precision and SI units (stresses in Pa).
pub fn fault_station_series_frame(
    seed: u64,
    trace: &stickslip_solver::trace::Trace,
    keep: &[usize],
    lattice: &Lattice,
    origin: Option<[f64; 2]>,
) -> Result<DataFrame, StoreError> {
    let n = keep.len();
    let rows = trace.stations.len() * n;
    let mut f = Frame::new(rows).u64(col::SEED, vec![seed; rows]);
    let (mut name, mut node, mut x, mut y) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for st in &trace.stations {
        let p = lattice.position(st.node);
        name.extend(std::iter::repeat_n(fault_station_file(p, origin), n));
        node.extend(std::iter::repeat_n(st.node.ldem() as u32, n));
        x.extend(std::iter::repeat_n(p[0], n));
        y.extend(std::iter::repeat_n(p[1], n));
    }
    let gather = |g: &dyn Fn(&stickslip_solver::trace::StationTrace) -> &[f64]| -> Vec<f64> {
        trace.stations.iter().flat_map(|st| keep.iter().map(move |&k| g(st)[k])).collect()
    };
    f = f
        .str(col::STATION, name)
        .u32(col::NODE, node)
        .f64(col::X_M, x)
        .f64(col::Y_M, y)
        .f64(col::TIME_S, trace.stations.iter().flat_map(|_| keep.iter().map(|&k| trace.time_s[k])).collect())
        .f64(col::SLIP_X_M, gather(&|st| &st.slip_m[0]))
        .f64(col::SLIP_Y_M, gather(&|st| &st.slip_m[1]))
        .f64(col::SLIP_RATE_X_M_S, gather(&|st| &st.slip_rate_m_s[0]))
        .f64(col::SLIP_RATE_Y_M_S, gather(&|st| &st.slip_rate_m_s[1]))
        .f64(col::SHEAR_STRESS_X_PA, gather(&|st| &st.shear_stress_pa[0]))
        .f64(col::SHEAR_STRESS_Y_PA, gather(&|st| &st.shear_stress_pa[1]))
        .f64(col::NORMAL_STRESS_PA, gather(&|st| &st.normal_stress_pa));
    f.finish(FAULT_STATION_SERIES.name)
}

/// The series table of one seed: `seed`, `time_s` (f64), then one column per recorded channel
/// ([`stickslip_solver::Channel::name`]), f32 except node counts (u32). The channels are computed
/// and analysed in double precision; they are stored in single precision, each value within
/// 2⁻²⁴ ≈ 6e-8 of its own magnitude, which halves the table (they are read back only to be drawn
/// or summarised to a few digits).
pub fn series_frame(seed: u64, rec: &Recording) -> Result<DataFrame, StoreError> {
    let n = rec.len();
    let mut cols: Vec<Column> =
        vec![Column::new(col::SEED.into(), vec![seed; n]), Column::new(col::TIME_S.into(), rec.time_s.clone())];
    for (ch, values) in &rec.channels {
        if ch.is_count() {
            cols.push(Column::new(ch.name().into(), values.iter().map(|&v| v as u32).collect::<Vec<u32>>()));
        } else {
            cols.push(Column::new(ch.name().into(), narrow_f32(SERIES.name, ch.name(), values)?));
        }
    }
    DataFrame::new(n, cols).map_err(|e| StoreError::table(SERIES.name, e))
}

/// The control-node table of one seed (long: one row per node, component and instant; an empty
/// frame with the schema when nothing was recorded): `seed`, `node` u32 (LDEM number),
/// `component` str, `time_s`, then `displacement_m`, `velocity_m_s`, `acceleration_m_s2` (null
/// where not recorded).
pub fn control_frame(seed: u64, rec: &Recording) -> Result<DataFrame, StoreError> {
    let n = rec.len();
    let mut pairs: Vec<(u64, Component)> = rec.control.iter().map(|(c, _)| (c.node.ldem(), c.component)).collect();
    pairs.sort();
    pairs.dedup();
    let rows = pairs.len() * n;
    let mut seed_col = Vec::with_capacity(rows);
    let mut node_col = Vec::with_capacity(rows);
    let mut comp_col: Vec<&str> = Vec::with_capacity(rows);
    let mut time_col = Vec::with_capacity(rows);
    let mut values: [Vec<Option<f64>>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    for &(node, comp) in &pairs {
        seed_col.extend(std::iter::repeat_n(seed, n));
        node_col.extend(std::iter::repeat_n(node as u32, n));
        comp_col.extend(std::iter::repeat_n(comp.name(), n));
        time_col.extend_from_slice(&rec.time_s);
        for (q, out) in Kinematic::ALL.iter().zip(values.iter_mut()) {
            let found =
                rec.control.iter().find(|(c, _)| c.node.ldem() == node && c.component == comp && c.quantity == *q);
            match found {
                Some((_, v)) => out.extend(v.iter().map(|&x| Some(x))),
                None => out.extend(std::iter::repeat_n(None, n)),
            }
        }
    }
    let mut cols = vec![
        Column::new(col::SEED.into(), seed_col),
        Column::new(col::NODE.into(), node_col),
        Column::new(col::COMPONENT.into(), comp_col),
        Column::new(col::TIME_S.into(), time_col),
    ];
    for (q, v) in Kinematic::ALL.iter().zip(values) {
        cols.push(Column::new(q.column().into(), v));
    }
    DataFrame::new(rows, cols).map_err(|e| StoreError::table(CONTROL.name, e))
}

/// The skip log of one seed (one row per quasi-static jump): `seed`, `from_s`, `to_s` (shear-stage
/// times), `steps` u64 (not integrated), `next` str (`slide`, `lift`, `land`, `end`: the
/// transition predicted just after `to_s`), `node` u32 (its LDEM number, null for `end`).
pub fn skips_frame(seed: u64, rec: &Recording) -> Result<DataFrame, StoreError> {
    let s = &rec.skips;
    let n = s.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .f64(col::FROM_S, s.iter().map(|k| k.from_s).collect())
        .f64(col::TO_S, s.iter().map(|k| k.to_s).collect())
        .u64(col::STEPS, s.iter().map(|k| k.steps).collect())
        .static_str(col::NEXT, s.iter().map(|k| k.next.kind()).collect())
        .opt_u32(col::NODE, s.iter().map(|k| k.next.node().map(|id| id.ldem() as u32)).collect())
        .finish(SKIPS.name)
}

/// A time history: (times, values).
pub type Trace = (Vec<f64>, Vec<f64>);

/// The times and one channel of a series part, if it was recorded.
pub fn read_series_channel(df: &DataFrame, channel: &str) -> Result<Option<Trace>, StoreError> {
    let c = Columns::of(df, SERIES.name);
    if !c.has(channel) {
        return Ok(None);
    }
    Ok(Some((c.f64s(col::TIME_S)?, c.f64s(channel)?)))
}

/// The largest value of each of `channels` over every series part matching `glob`: `None` for a
/// channel not recorded (or without a value), and for all of them when no part can be read.
/// Channels are stored in single precision: read as f64 by a cast.
pub fn largest_in_series(glob: &std::path::Path, channels: &[&str]) -> Vec<Option<f64>> {
    let series = crate::io::scan_glob(glob).ok().flatten();
    let largest = |name: &str| -> Option<f64> {
        let column = series.as_ref()?.column(name).ok()?.cast(&DataType::Float64).ok()?;
        let values = column.f64().ok()?.iter().flatten().collect::<Vec<_>>();
        values.into_iter().reduce(f64::max)
    };
    channels.iter().map(|c| largest(c)).collect()
}

/// One quantity of one control node and component from a control part, if recorded.
pub fn read_control(
    df: &DataFrame,
    node_ldem: u64,
    component: Component,
    quantity: Kinematic,
) -> Result<Option<Trace>, StoreError> {
    let c = Columns::of(df, CONTROL.name);
    let nodes = c.u64s(col::NODE)?;
    let comps = c.strs(col::COMPONENT)?;
    let idx: Vec<usize> = (0..c.height()).filter(|&i| nodes[i] == node_ldem && comps[i] == component.name()).collect();
    if idx.is_empty() {
        return Ok(None);
    }
    let t = c.f64s(col::TIME_S)?;
    let v = c.opt_f64s(quantity.column())?;
    if idx.iter().all(|&i| v[i].is_none()) {
        return Ok(None);
    }
    Ok(Some((idx.iter().map(|&i| t[i]).collect(), idx.iter().map(|&i| v[i].unwrap_or(f64::NAN)).collect())))
}

/// The fault table of one seed (long: one row per contact node and kept instant, the trace's
/// instants `keep`): `seed`, `node` u32 (LDEM), `x_m`, `y_m`, `time_s`, `slip_m`,
/// `slip_rate_m_s`, `shear_stress_pa`, `normal_stress_pa`; `None` when the run did not record
/// the fault.
pub fn fault_frame(
    seed: u64,
    trace: &stickslip_solver::Trace,
    keep: &[usize],
    lattice: &Lattice,
) -> Result<Option<DataFrame>, StoreError> {
    let Some(f) = &trace.fault else { return Ok(None) };
    let n = keep.len();
    let rows = n * f.nodes.len();
    let per_node = |g: &dyn Fn(usize) -> f64| -> Vec<f64> {
        (0..f.nodes.len()).flat_map(|i| std::iter::repeat_n(g(i), n)).collect()
    };
    let flat = |v: &[Vec<f64>]| -> Vec<f64> { v.iter().flat_map(|s| keep.iter().map(|&k| s[k])).collect() };
    Frame::new(rows)
        .u64(col::SEED, vec![seed; rows])
        .u32(col::NODE, f.nodes.iter().flat_map(|id| std::iter::repeat_n(id.ldem() as u32, n)).collect())
        .f64(col::X_M, per_node(&|i| lattice.position(f.nodes[i])[0]))
        .f64(col::Y_M, per_node(&|i| lattice.position(f.nodes[i])[1]))
        .f64(col::TIME_S, (0..f.nodes.len()).flat_map(|_| keep.iter().map(|&k| trace.time_s[k])).collect())
        .f64(col::SLIP_M, flat(&f.slip_m))
        .f64(col::SLIP_RATE_M_S, flat(&f.slip_rate_m_s))
        .f64(col::SHEAR_STRESS_PA, flat(&f.shear_stress_pa))
        .f64(col::NORMAL_STRESS_PA, flat(&f.normal_stress_pa))
        .finish(FAULT.name)
        .map(Some)
}

read_back! {
    /// The fault table read back.
    pub struct Fault from FAULT, |c| {
        /// Node (LDEM) of each row.
        node: Vec<u64> = c.u64s(col::NODE)?,
        /// Its x (m).
        x_m: Vec<f64> = c.f64s(col::X_M)?,
        /// Its y (m).
        y_m: Vec<f64> = c.f64s(col::Y_M)?,
        /// Time (s).
        time_s: Vec<f64> = c.f64s(col::TIME_S)?,
        /// Slip rate (m/s).
        slip_rate_m_s: Vec<f64> = c.f64s(col::SLIP_RATE_M_S)?,
    }
}

/// The name of a fault station's file (without `.dat`) at the base point `p` (m): on a fault
/// (`origin` its `[fault] origin_m`) the SCEC benchmarks' `faultst<strike>dp<depth>`, on the rigid
/// base the SEAS layout's `fltst_strk…dp…`. The `fault_station_series` table names its rows so, and
/// `crate::files` the stations' `.dat` files.
pub fn fault_station_file(p: [f64; 3], origin: Option<[f64; 2]>) -> String {
    match origin {
        Some([x0, y0]) => stickslip_seismo::scec::fault_station_name(p[0] - x0, p[1] - y0),
        None => stickslip_seismo::seas::station_file_name(p[0], p[1]),
    }
}
