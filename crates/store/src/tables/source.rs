//! The source of a fault scene's run and its stations as tables (docs/model.md §15).
//!
//! **source**, one row per seed whose fault ruptured: `seed` u64, `ruptured_nodes` u32,
//! `ruptured_area_m2`, `m0_n_m`, `mw`, `mean_slip_m`, `max_slip_m`, `stress_drop_pa` (area-weighted
//! over the ruptured nodes, along the mean slip), `peak_slip_rate_m_s`,
//! `median_peak_slip_rate_m_s`, `hypocentre_x_m`, `hypocentre_y_m`, `rupture_duration_s` (when
//! the last node ruptured), `rupture_x_min_m`, `rupture_x_max_m`, `rupture_y_min_m`,
//! `rupture_y_max_m`, `shear_modulus_pa`, `s_speed_m_s`, `brune_corner_hz` f64, `fitted_corner_hz` f64
//! (the ω-square corner of the surface stations' stacked displacement spectra; null with fewer than
//! 3 surface stations); with `[broadband]` (null otherwise) the stochastic part's
//! `hf_stress_parameter_pa` (after its area scaling), `hf_subfaults` u32 (with a moment),
//! `hf_subfault_m`, `hf_frankel_c` f64.
//!
//! **fault_nodes**, one row per seed and node of the fault: `seed` u64, `node` u32 (LDEM), `x_m`,
//! `y_m`, `area_m2`, `rupture_time_s` (null: never reached `[events] rupture_rate_m_s`),
//! `peak_slip_rate_m_s`, `slip_x_m`, `slip_y_m` (across the fault, at the end), the shear
//! traction at the start and the end along x and y, `normal_stress_pa` f64.
//!
//! **stations**, one row per seed and station: `seed` u64, `station` str, `node` u32 (LDEM), `x_m`,
//! `y_m` (depth), `z_m` (distance from the fault plane), `epicentral_m`, `hypocentral_m`,
//! `r_rup_m`, `r_jb_m`, `r_x_m`, `r_y0_m`, `azimuth_deg`, `pga_m_s2`, `pgv_m_s`, `pgd_m`
//! (horizontal: largest |(x, z)| of the raw record), `pga_vertical_m_s2` f64; of the processed
//! record (docs/model.md §16.2; with `[broadband]` the broadband record of §17 at the station's
//! site): `record_kind` str (`lattice` or `broadband`), `vs30_m_s` (the site; for a lattice
//! record the V_S30 of the layered medium's profile at a surface station, null without one), `pga_rotd50_m_s2`, `pgv_rotd50_m_s`, `arias_m_s`, `d5_95_s`, `cav_m_s` (each the mean
//! of the two horizontal components'), `f_low_hz`, `f_high_hz` (its band-pass),
//! `usable_min_period_s`, `usable_max_period_s` f64 (null without a processed record),
//! `motion_note` str (why there is none; null otherwise). A station simulated on several sites
//! has one row per site, named `<station>_vs<V_S30>`.
//!
//! **station_spectra**, one row per seed, station and period in the station's usable band:
//! `seed` u64, `station` str, `period_s`, `rotd50_m_s2`, `rotd100_m_s2` f64 (5%-damped PSA of the
//! horizontal pair (x, z)).

use polars::prelude::DataFrame;
use stickslip_analysis::motions::Motion;
use stickslip_analysis::{Source, StationRow};
use stickslip_solver::Model;
use stickslip_solver::trace::FaultSummary;

use crate::col;
use crate::error::StoreError;
use crate::frame::Frame;
use crate::spec::{Scope, SeedTable, TableSpec};

/// The source of each seed whose fault ruptured.
pub const SOURCE: TableSpec = TableSpec {
    name: "source",
    scope: Scope::Gathered,
    key: &[col::SEED],
    columns: &[
        col::SEED,
        col::RUPTURED_NODES,
        col::RUPTURED_AREA,
        col::M0_N_M,
        col::MW,
        col::MEAN_SLIP_M,
        col::MAX_SLIP_M,
        col::STRESS_DROP_PA,
        col::PEAK_SLIP_RATE_M_S,
        col::MEDIAN_PEAK_SLIP_RATE_M_S,
        col::HYPOCENTRE_X_M,
        col::HYPOCENTRE_Y_M,
        col::RUPTURE_DURATION_S,
        col::RUPTURE_X_MIN_M,
        col::RUPTURE_X_MAX_M,
        col::RUPTURE_Y_MIN_M,
        col::RUPTURE_Y_MAX_M,
        col::SHEAR_MODULUS_PA,
        col::S_SPEED_M_S,
        col::BRUNE_CORNER_HZ,
        col::FITTED_CORNER_HZ,
        col::HF_STRESS_PARAMETER_PA,
        col::HF_SUBFAULTS,
        col::HF_SUBFAULT_M,
        col::HF_FRANKEL_C,
    ],
    variable: None,
};

/// Every node of a fault: rupture time, peak slip rate, final slip and tractions.
pub const FAULT_NODES: TableSpec = TableSpec {
    name: "fault_nodes",
    scope: Scope::Gathered,
    key: &[col::SEED, col::NODE],
    columns: &[
        col::SEED,
        col::NODE,
        col::X_M,
        col::Y_M,
        col::AREA_M2,
        col::RUPTURE_TIME_S,
        col::PEAK_SLIP_RATE_M_S,
        col::SLIP_X_M,
        col::SLIP_Y_M,
        col::SHEAR_STRESS_X_INITIAL_PA,
        col::SHEAR_STRESS_Y_INITIAL_PA,
        col::SHEAR_STRESS_X_FINAL_PA,
        col::SHEAR_STRESS_Y_FINAL_PA,
        col::NORMAL_STRESS_PA,
    ],
    variable: None,
};

/// The stations of a fault scene against each seed's rupture.
pub const STATIONS: TableSpec = TableSpec {
    name: "stations",
    scope: Scope::Gathered,
    key: &[col::SEED, col::STATION],
    columns: &[
        col::SEED,
        col::STATION,
        col::NODE,
        col::X_M,
        col::Y_M,
        col::Z_M,
        col::EPICENTRAL_M,
        col::HYPOCENTRAL_M,
        col::R_RUP_M,
        col::R_JB_M,
        col::R_X_M,
        col::R_Y0_M,
        col::AZIMUTH_DEG,
        col::PGA_M_S2,
        col::PGV_M_S,
        col::PGD_M,
        col::PGA_VERTICAL_M_S2,
        col::RECORD_KIND,
        col::VS30_M_S,
        col::PGA_ROTD50_M_S2,
        col::PGV_ROTD50_M_S,
        col::ARIAS_M_S,
        col::D5_95_S,
        col::CAV_M_S,
        col::F_LOW_HZ,
        col::F_HIGH_HZ,
        col::USABLE_MIN_PERIOD_S,
        col::USABLE_MAX_PERIOD_S,
        col::MOTION_NOTE,
    ],
    variable: None,
};

/// RotD50 and RotD100 PSA of each station's processed horizontal pair, per seed.
pub const STATION_SPECTRA: TableSpec = TableSpec {
    name: "station_spectra",
    scope: Scope::Gathered,
    key: &[col::SEED, col::STATION, col::PERIOD_S],
    columns: &[col::SEED, col::STATION, col::PERIOD_S, col::ROTD50_M_S2, col::ROTD100_M_S2],
    variable: None,
};

/// The `source` part of a seed whose fault ruptured.
pub const SOURCE_PART: SeedTable =
    SeedTable { spec: SOURCE, write: |s| s.analysis.source.as_ref().map(|src| source_frame(s.seed, src)).transpose() };

/// The `fault_nodes` part of a seed on a fault.
pub const FAULT_NODES_PART: SeedTable = SeedTable {
    spec: FAULT_NODES,
    write: |s| {
        s.analysis.run.recording.trace.summary.as_ref().map(|f| fault_nodes_frame(s.seed, f, s.model)).transpose()
    },
};

/// The `stations` part of a seed on a fault with stations.
pub const STATIONS_PART: SeedTable = SeedTable {
    spec: STATIONS,
    write: |s| {
        if s.analysis.stations.is_empty() { Ok(None) } else { stations_frame(s.seed, &s.analysis.stations).map(Some) }
    },
};

/// The `station_spectra` part of a seed on a fault with stations.
pub const STATION_SPECTRA_PART: SeedTable = SeedTable {
    spec: STATION_SPECTRA,
    write: |s| {
        let rows = &s.analysis.stations;
        if rows.iter().all(|r| r.record_motion().as_ref().map_or(true, |m| m.periods_s.is_empty())) {
            Ok(None)
        } else {
            station_spectra_frame(s.seed, rows).map(Some)
        }
    },
};

/// The station_spectra table of one seed.
pub fn station_spectra_frame(seed: u64, rows: &[StationRow]) -> Result<DataFrame, StoreError> {
    let (mut name, mut period, mut r50, mut r100) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for r in rows {
        let Ok(m) = r.record_motion() else { continue };
        for k in 0..m.periods_s.len() {
            name.push(r.station.name.clone());
            period.push(m.periods_s[k]);
            r50.push(m.rotd50_m_s2[k]);
            r100.push(m.rotd100_m_s2[k]);
        }
    }
    Frame::new(name.len())
        .u64(col::SEED, vec![seed; name.len()])
        .str(col::STATION, name)
        .f64(col::PERIOD_S, period)
        .f64(col::ROTD50_M_S2, r50)
        .f64(col::ROTD100_M_S2, r100)
        .finish(STATION_SPECTRA.name)
}

/// The source table of one seed.
pub fn source_frame(seed: u64, s: &Source) -> Result<DataFrame, StoreError> {
    Frame::new(1)
        .u64(col::SEED, vec![seed])
        .u32(col::RUPTURED_NODES, vec![s.ruptured_nodes as u32])
        .f64(col::RUPTURED_AREA, vec![s.area_m2])
        .f64(col::M0_N_M, vec![s.m0_n_m])
        .f64(col::MW, vec![s.mw])
        .f64(col::MEAN_SLIP_M, vec![s.mean_slip_m])
        .f64(col::MAX_SLIP_M, vec![s.max_slip_m])
        .f64(col::STRESS_DROP_PA, vec![s.stress_drop_pa])
        .f64(col::PEAK_SLIP_RATE_M_S, vec![s.peak_slip_rate_m_s])
        .f64(col::MEDIAN_PEAK_SLIP_RATE_M_S, vec![s.median_peak_slip_rate_m_s])
        .f64(col::HYPOCENTRE_X_M, vec![s.hypocentre_m[0]])
        .f64(col::HYPOCENTRE_Y_M, vec![s.hypocentre_m[1]])
        .f64(col::RUPTURE_DURATION_S, vec![s.rupture_duration_s])
        .f64(col::RUPTURE_X_MIN_M, vec![s.extent_m[0][0]])
        .f64(col::RUPTURE_X_MAX_M, vec![s.extent_m[0][1]])
        .f64(col::RUPTURE_Y_MIN_M, vec![s.extent_m[1][0]])
        .f64(col::RUPTURE_Y_MAX_M, vec![s.extent_m[1][1]])
        .f64(col::SHEAR_MODULUS_PA, vec![s.shear_modulus_pa])
        .f64(col::S_SPEED_M_S, vec![s.s_speed_m_s])
        .f64(col::BRUNE_CORNER_HZ, vec![s.brune_corner_hz])
        .opt_f64(col::FITTED_CORNER_HZ, vec![s.fitted_corner_hz])
        .opt_f64(col::HF_STRESS_PARAMETER_PA, vec![s.stochastic.as_ref().map(|h| h.stress_parameter_pa)])
        .opt_u32(col::HF_SUBFAULTS, vec![s.stochastic.as_ref().map(|h| h.subfaults as u32)])
        .opt_f64(col::HF_SUBFAULT_M, vec![s.stochastic.as_ref().map(|h| h.subfault_m)])
        .opt_f64(col::HF_FRANKEL_C, vec![s.stochastic.as_ref().map(|h| h.frankel)])
        .finish(SOURCE.name)
}

/// The fault_nodes table of one seed.
pub fn fault_nodes_frame(seed: u64, f: &FaultSummary, model: &Model) -> Result<DataFrame, StoreError> {
    let n = f.nodes.len();
    let lattice = model.lattice();
    let pos: Vec<[f64; 3]> = f.nodes.iter().map(|&id| lattice.position(id)).collect();
    let pick = |g: &dyn Fn(usize) -> f64| (0..n).map(g).collect::<Vec<f64>>();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::NODE, f.nodes.iter().map(|id| id.ldem() as u32).collect())
        .f64(col::X_M, pick(&|i| pos[i][0]))
        .f64(col::Y_M, pick(&|i| pos[i][1]))
        .f64(col::AREA_M2, f.area_m2.clone())
        .opt_f64(col::RUPTURE_TIME_S, f.rupture_time_s.iter().map(|t| Some(*t).filter(|t| t.is_finite())).collect())
        .f64(col::PEAK_SLIP_RATE_M_S, f.peak_slip_rate_m_s.clone())
        .f64(col::SLIP_X_M, pick(&|i| f.final_slip_m[i][0]))
        .f64(col::SLIP_Y_M, pick(&|i| f.final_slip_m[i][1]))
        .f64(col::SHEAR_STRESS_X_INITIAL_PA, pick(&|i| f.shear_stress_pa[i][0][0]))
        .f64(col::SHEAR_STRESS_Y_INITIAL_PA, pick(&|i| f.shear_stress_pa[i][0][1]))
        .f64(col::SHEAR_STRESS_X_FINAL_PA, pick(&|i| f.shear_stress_pa[i][1][0]))
        .f64(col::SHEAR_STRESS_Y_FINAL_PA, pick(&|i| f.shear_stress_pa[i][1][1]))
        .f64(col::NORMAL_STRESS_PA, f.normal_stress_pa.clone())
        .finish(FAULT_NODES.name)
}

/// The stations table of one seed.
pub fn stations_frame(seed: u64, rows: &[StationRow]) -> Result<DataFrame, StoreError> {
    let n = rows.len();
    let pick = |g: &dyn Fn(&StationRow) -> f64| rows.iter().map(g).collect::<Vec<f64>>();
    let motion = |g: &dyn Fn(&Motion) -> f64| {
        rows.iter().map(|r| r.record_motion().as_ref().ok().map(g)).collect::<Vec<Option<f64>>>()
    };
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .str(col::STATION, rows.iter().map(|r| r.station.name.clone()).collect())
        .u32(col::NODE, rows.iter().map(|r| r.station.node.ldem() as u32).collect())
        .f64(col::X_M, pick(&|r| r.position_m[0]))
        .f64(col::Y_M, pick(&|r| r.position_m[1]))
        .f64(col::Z_M, pick(&|r| r.position_m[2]))
        .f64(col::EPICENTRAL_M, pick(&|r| r.epicentral_m))
        .f64(col::HYPOCENTRAL_M, pick(&|r| r.hypocentral_m))
        .f64(col::R_RUP_M, pick(&|r| r.r_rup_m))
        .f64(col::R_JB_M, pick(&|r| r.r_jb_m))
        .f64(col::R_X_M, pick(&|r| r.r_x_m))
        .f64(col::R_Y0_M, pick(&|r| r.r_y0_m))
        .f64(col::AZIMUTH_DEG, pick(&|r| r.azimuth_deg))
        .f64(col::PGA_M_S2, pick(&|r| r.pga_m_s2))
        .f64(col::PGV_M_S, pick(&|r| r.pgv_m_s))
        .f64(col::PGD_M, pick(&|r| r.pgd_m))
        .f64(col::PGA_VERTICAL_M_S2, pick(&|r| r.pga_vertical_m_s2))
        .static_str(
            col::RECORD_KIND,
            rows.iter().map(|r| if r.broadband.is_some() { "broadband" } else { "lattice" }).collect(),
        )
        .opt_f64(
            col::VS30_M_S,
            rows.iter().map(|r| r.broadband.as_ref().map(|b| b.vs30_m_s).or(r.site_vs30_m_s)).collect(),
        )
        .opt_f64(col::PGA_ROTD50_M_S2, motion(&|m| m.pga_rotd50_m_s2))
        .opt_f64(col::PGV_ROTD50_M_S, motion(&|m| m.pgv_rotd50_m_s))
        .opt_f64(col::ARIAS_M_S, motion(&|m| m.arias_m_s))
        .opt_f64(col::D5_95_S, motion(&|m| m.d5_95_s))
        .opt_f64(col::CAV_M_S, motion(&|m| m.cav_m_s))
        .opt_f64(col::F_LOW_HZ, motion(&|m| m.band_hz[0]))
        .opt_f64(col::F_HIGH_HZ, motion(&|m| m.band_hz[1]))
        .opt_f64(col::USABLE_MIN_PERIOD_S, motion(&|m| m.usable_s[0]))
        .opt_f64(col::USABLE_MAX_PERIOD_S, motion(&|m| m.usable_s[1]))
        .opt_str(col::MOTION_NOTE, rows.iter().map(|r| r.record_motion().as_ref().err().cloned()).collect())
        .finish(STATIONS.name)
}

/// The `fault_nodes` table (or one seed's part) read back: where each node is, when it ruptured
/// and how far it slipped.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FaultNodes {
    /// Seed of each row.
    pub seed: Vec<u64>,
    /// x (m, along strike).
    pub x_m: Vec<f64>,
    /// y (m, down dip).
    pub y_m: Vec<f64>,
    /// Rupture time (s; NaN: never).
    pub rupture_time_s: Vec<f64>,
    /// Peak slip rate (m/s).
    pub peak_slip_rate_m_s: Vec<f64>,
    /// Final slip along x and y (m).
    pub slip_m: Vec<[f64; 2]>,
}

impl FaultNodes {
    /// Reads a `fault_nodes` frame.
    pub fn read(df: &DataFrame) -> Result<FaultNodes, StoreError> {
        let c = crate::frame::Columns::of(df, FAULT_NODES.name);
        let (sx, sy) = (c.f64s(col::SLIP_X_M)?, c.f64s(col::SLIP_Y_M)?);
        Ok(FaultNodes {
            seed: c.u64s(col::SEED)?,
            x_m: c.f64s(col::X_M)?,
            y_m: c.f64s(col::Y_M)?,
            rupture_time_s: c.f64s(col::RUPTURE_TIME_S)?,
            peak_slip_rate_m_s: c.f64s(col::PEAK_SLIP_RATE_M_S)?,
            slip_m: sx.into_iter().zip(sy).map(|(a, b)| [a, b]).collect(),
        })
    }
}

/// The `stations` table read back: each station's distances, peaks and usable band, per seed.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Stations {
    /// Seed of each row.
    pub seed: Vec<u64>,
    /// Station name.
    pub station: Vec<String>,
    /// Epicentral distance (m).
    pub epicentral_m: Vec<f64>,
    /// Rupture distance (m).
    pub r_rup_m: Vec<f64>,
    /// Joyner–Boore distance (m).
    pub r_jb_m: Vec<f64>,
    /// Azimuth from the strike (degrees).
    pub azimuth_deg: Vec<f64>,
    /// Peak horizontal acceleration of the raw record (m/s²).
    pub pga_m_s2: Vec<f64>,
    /// Peak horizontal velocity of the raw record (m/s).
    pub pgv_m_s: Vec<f64>,
    /// The site of a broadband record (m/s); `None` for a lattice record (or a folder written
    /// before broadband records existed).
    pub vs30_m_s: Vec<Option<f64>>,
    /// RotD50 PGA of the processed record (m/s²; NaN without one).
    pub pga_rotd50_m_s2: Vec<f64>,
    /// RotD50 PGV of the processed record (m/s; NaN without one).
    pub pgv_rotd50_m_s: Vec<f64>,
    /// The processed record's band-pass corners (Hz; NaN without one).
    pub band_hz: Vec<[f64; 2]>,
    /// The periods its spectra are usable over (s; NaN without one).
    pub usable_s: Vec<[f64; 2]>,
    /// Why the station has no processed record (empty when it has one).
    pub motion_note: Vec<String>,
}

impl Stations {
    /// Reads a `stations` frame.
    pub fn read(df: &DataFrame) -> Result<Stations, StoreError> {
        let c = crate::frame::Columns::of(df, STATIONS.name);
        let pair = |a: Vec<f64>, b: Vec<f64>| a.into_iter().zip(b).map(|(a, b)| [a, b]).collect::<Vec<_>>();
        Ok(Stations {
            seed: c.u64s(col::SEED)?,
            station: c.opt_strs(col::STATION)?.into_iter().map(Option::unwrap_or_default).collect(),
            epicentral_m: c.f64s(col::EPICENTRAL_M)?,
            r_rup_m: c.f64s(col::R_RUP_M)?,
            r_jb_m: c.f64s(col::R_JB_M)?,
            azimuth_deg: c.f64s(col::AZIMUTH_DEG)?,
            pga_m_s2: c.f64s(col::PGA_M_S2)?,
            pgv_m_s: c.f64s(col::PGV_M_S)?,
            vs30_m_s: if c.has(col::VS30_M_S) { c.opt_f64s(col::VS30_M_S)? } else { vec![None; c.height()] },
            pga_rotd50_m_s2: c.f64s(col::PGA_ROTD50_M_S2)?,
            pgv_rotd50_m_s: c.f64s(col::PGV_ROTD50_M_S)?,
            band_hz: pair(c.f64s(col::F_LOW_HZ)?, c.f64s(col::F_HIGH_HZ)?),
            usable_s: pair(c.f64s(col::USABLE_MIN_PERIOD_S)?, c.f64s(col::USABLE_MAX_PERIOD_S)?),
            motion_note: c.opt_strs(col::MOTION_NOTE)?.into_iter().map(Option::unwrap_or_default).collect(),
        })
    }
}

/// The `source` table read back: one row per seed whose fault ruptured.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sources {
    /// Seed of each row.
    pub seed: Vec<u64>,
    /// Nodes that ruptured.
    pub ruptured_nodes: Vec<u64>,
    /// Ruptured area (m²).
    pub ruptured_area_m2: Vec<f64>,
    /// Seismic moment (N·m).
    pub m0_n_m: Vec<f64>,
    /// Moment magnitude.
    pub mw: Vec<f64>,
    /// Mean slip over the ruptured nodes (m).
    pub mean_slip_m: Vec<f64>,
    /// Largest slip (m).
    pub max_slip_m: Vec<f64>,
    /// Stress drop (Pa).
    pub stress_drop_pa: Vec<f64>,
    /// Largest peak slip rate (m/s).
    pub peak_slip_rate_m_s: Vec<f64>,
    /// Median of the ruptured nodes' peak slip rates (m/s).
    pub median_peak_slip_rate_m_s: Vec<f64>,
    /// Hypocentre along strike and down dip (m).
    pub hypocentre_m: Vec<[f64; 2]>,
    /// When the last node ruptured (s).
    pub rupture_duration_s: Vec<f64>,
    /// Brune corner frequency (Hz).
    pub brune_corner_hz: Vec<f64>,
    /// Corner frequency fitted to the moment-rate spectrum (Hz), when fitted (and when the column
    /// exists: folders written before it have none).
    pub fitted_corner_hz: Vec<Option<f64>>,
}

impl Sources {
    /// Reads a `source` frame.
    pub fn read(df: &DataFrame) -> Result<Sources, StoreError> {
        let c = crate::frame::Columns::of(df, SOURCE.name);
        let (hx, hy) = (c.f64s(col::HYPOCENTRE_X_M)?, c.f64s(col::HYPOCENTRE_Y_M)?);
        Ok(Sources {
            seed: c.u64s(col::SEED)?,
            ruptured_nodes: c.u64s(col::RUPTURED_NODES)?,
            ruptured_area_m2: c.f64s(col::RUPTURED_AREA)?,
            m0_n_m: c.f64s(col::M0_N_M)?,
            mw: c.f64s(col::MW)?,
            mean_slip_m: c.f64s(col::MEAN_SLIP_M)?,
            max_slip_m: c.f64s(col::MAX_SLIP_M)?,
            stress_drop_pa: c.f64s(col::STRESS_DROP_PA)?,
            peak_slip_rate_m_s: c.f64s(col::PEAK_SLIP_RATE_M_S)?,
            median_peak_slip_rate_m_s: c.f64s(col::MEDIAN_PEAK_SLIP_RATE_M_S)?,
            hypocentre_m: hx.into_iter().zip(hy).map(|(x, y)| [x, y]).collect(),
            rupture_duration_s: c.f64s(col::RUPTURE_DURATION_S)?,
            brune_corner_hz: c.f64s(col::BRUNE_CORNER_HZ)?,
            fitted_corner_hz: if c.has(col::FITTED_CORNER_HZ) {
                c.opt_f64s(col::FITTED_CORNER_HZ)?
            } else {
                vec![None; c.height()]
            },
        })
    }
}
