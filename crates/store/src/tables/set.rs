//! A set of records matched to a design spectrum, in the order chosen (`[set]`).

use polars::prelude::DataFrame;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Frame, read_back};
use crate::spec::{Scope, TableSpec};

/// A set of records matched to a design spectrum (prototype scale), in the order chosen.
pub const SET: TableSpec = TableSpec {
    name: "set",
    scope: Scope::AcrossSeeds,
    key: &[col::RANK],
    columns: &[
        col::RANK,
        col::SEED,
        col::RECORD,
        col::LABEL,
        col::NODE,
        col::COMPONENT,
        col::SCALE_FACTOR,
        col::MISFIT,
        col::USABLE_LOW_HZ,
        col::USABLE_HIGH_HZ,
        col::MW,
        col::R_RUP_KM,
        col::R_JB_KM,
    ],
    variable: None,
};

/// One record of a matched set.
#[derive(Clone, Debug, PartialEq)]
pub struct SetRow {
    /// Seed.
    pub seed: u64,
    /// Record name within its seed (`S2-n36-x`, or `S2-n36-xy` for a RotD50 pair; a scenario's
    /// station name).
    pub record: String,
    /// Event label (a scenario's seed is one rupture: `rupture`).
    pub label: String,
    /// Node (LDEM number).
    pub node: u32,
    /// Component (`x`, `y`, `z`, `rotd50` or `rotd100`).
    pub component: String,
    /// Amplitude scale factor.
    pub scale_factor: f64,
    /// Mean squared log residual of the scaled record over the range.
    pub misfit: f64,
    /// Usable band at prototype scale (Hz).
    pub usable_hz: (f64, f64),
    /// A scenario's station: the seed's rupture as the ground-motion models see it, its moment
    /// magnitude and the station's rupture and Joyner–Boore distances (km).
    pub scenario: Option<ScenarioMeta>,
}

/// What a scenario's record is: its rupture's magnitude and its station's distances.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScenarioMeta {
    /// Moment magnitude of the seed's rupture.
    pub mw: f64,
    /// Rupture distance R_rup (km).
    pub r_rup_km: f64,
    /// Joyner–Boore distance R_JB (km).
    pub r_jb_km: f64,
}

/// The set table, in the order the records were chosen.
pub fn set_frame(rows: &[SetRow]) -> Result<DataFrame, StoreError> {
    let n = rows.len();
    Frame::new(n)
        .u32(col::RANK, (1..=n as u32).collect())
        .u64(col::SEED, rows.iter().map(|r| r.seed).collect())
        .str(col::RECORD, rows.iter().map(|r| r.record.clone()).collect())
        .str(col::LABEL, rows.iter().map(|r| r.label.clone()).collect())
        .u32(col::NODE, rows.iter().map(|r| r.node).collect())
        .str(col::COMPONENT, rows.iter().map(|r| r.component.clone()).collect())
        .f64(col::SCALE_FACTOR, rows.iter().map(|r| r.scale_factor).collect())
        .f64(col::MISFIT, rows.iter().map(|r| r.misfit).collect())
        .f64(col::USABLE_LOW_HZ, rows.iter().map(|r| r.usable_hz.0).collect())
        .f64(col::USABLE_HIGH_HZ, rows.iter().map(|r| r.usable_hz.1).collect())
        .opt_f64(col::MW, rows.iter().map(|r| r.scenario.map(|s| s.mw)).collect())
        .opt_f64(col::R_RUP_KM, rows.iter().map(|r| r.scenario.map(|s| s.r_rup_km)).collect())
        .opt_f64(col::R_JB_KM, rows.iter().map(|r| r.scenario.map(|s| s.r_jb_km)).collect())
        .finish(SET.name)
}

read_back! {
    /// The set table read back.
    pub struct SetTable from SET, |c| {
        /// Seed of each record.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Record name within its seed.
        record: Vec<String> = c.strs(col::RECORD)?,
        /// Component.
        component: Vec<String> = c.strs(col::COMPONENT)?,
        /// Scale factor.
        scale_factor: Vec<f64> = c.f64s(col::SCALE_FACTOR)?,
        /// Misfit.
        misfit: Vec<f64> = c.f64s(col::MISFIT)?,
    }
}
