//! The crack catalogue of one seed (scenes with `[rupture]`, docs/model.md §11): every bar that
//! started softening or broke, and the breaks grouped into acoustic-emission events.
//!
//! **cracks**: `seed`, `time_s` f64 (negative in the self-weight stage), `kind` str (`soften`,
//! `break`), `bar` u32 (canonical index, docs/model.md §10.5), `family` str (`edge`, `diagonal`,
//! `centre`), `direction` str (`x`, `y`, `z`, `+x+y+z`, `-x+y+z`, `+x-y+z`, `-x-y+z`), `x_m`,
//! `y_m`, `z_m` f64 (the bar's midpoint), `strain` f64 (the bar's strain then), `energy_j` f64
//! (softening: the strain energy the bar held at its peak, `½·EA·εp²·L`; break: the fracture
//! energy it dissipated, `Gf·A_f`).
//!
//! **acoustic_emission**: `seed`, `cluster` u32, `start_s`, `end_s`, `duration_s` f64, `breaks`
//! u32, `x_m`, `y_m`, `z_m` f64 (the first break: hypocentre), `centroid_x_m`, `centroid_y_m`,
//! `centroid_z_m` f64 (energy-weighted), `energy_j` f64 (sum of the breaks'), `magnitude` f64
//! (`(log10 E − 4.8)/1.5`).

use polars::prelude::DataFrame;
use stickslip_seismo::emission::Cluster;
use stickslip_solver::Crack;
use stickslip_solver::geometry::Lattice;
use stickslip_solver::step::rupture::CrackKind;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Frame, read_back};
use crate::spec::{Scope, SeedTable, TableSpec};

/// Every bar that started softening or broke (scenes with `[rupture]`, docs/model.md §11).
pub const CRACKS: TableSpec = TableSpec {
    name: "cracks",
    scope: Scope::Gathered,
    key: &[col::SEED, col::TIME_S, col::BAR, col::KIND],
    columns: &[
        col::SEED,
        col::TIME_S,
        col::KIND,
        col::BAR,
        col::FAMILY,
        col::DIRECTION,
        col::X_M,
        col::Y_M,
        col::Z_M,
        col::STRAIN,
        col::ENERGY_J,
    ],
    variable: None,
};

/// Bar breaks grouped into acoustic-emission events, with their magnitudes (docs/model.md §11).
pub const ACOUSTIC_EMISSION: TableSpec = TableSpec {
    name: "acoustic_emission",
    scope: Scope::Gathered,
    key: &[col::SEED, col::CLUSTER],
    columns: &[
        col::SEED,
        col::CLUSTER,
        col::START_S,
        col::END_S,
        col::DURATION_S,
        col::BREAKS,
        col::X_M,
        col::Y_M,
        col::Z_M,
        col::CENTROID_X_M,
        col::CENTROID_Y_M,
        col::CENTROID_Z_M,
        col::ENERGY_J,
        col::MAGNITUDE,
    ],
    variable: None,
};

/// The `cracks` part of a seed whose bars crack.
pub const CRACKS_PART: SeedTable = SeedTable {
    spec: CRACKS,
    write: |s| match &s.analysis.emission {
        Some(_) => cracks_frame(s.seed, &s.analysis.run.recording.cracks, s.model.lattice()).map(Some),
        None => Ok(None),
    },
};
/// The `acoustic_emission` part of a seed whose bars crack.
pub const ACOUSTIC_EMISSION_PART: SeedTable = SeedTable {
    spec: ACOUSTIC_EMISSION,
    write: |s| s.analysis.emission.as_ref().map(|c| emission_frame(s.seed, c)).transpose(),
};

/// The cracks table of one seed.
pub fn cracks_frame(seed: u64, cracks: &[Crack], lattice: &Lattice) -> Result<DataFrame, StoreError> {
    let n = cracks.len();
    let bars: Vec<_> = cracks.iter().map(|c| lattice.bar(c.bar as usize)).collect();
    let mid: Vec<[f64; 3]> = bars.iter().map(|b| lattice.bar_midpoint(b)).collect();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .f64(col::TIME_S, cracks.iter().map(|c| c.time_s).collect())
        .static_str(col::KIND, cracks.iter().map(|c| c.kind.name()).collect())
        .u32(col::BAR, cracks.iter().map(|c| c.bar).collect())
        .static_str(col::FAMILY, bars.iter().map(|b| b.family.name()).collect())
        .static_str(col::DIRECTION, bars.iter().map(|b| b.direction.name()).collect())
        .f64(col::X_M, mid.iter().map(|m| m[0]).collect())
        .f64(col::Y_M, mid.iter().map(|m| m[1]).collect())
        .f64(col::Z_M, mid.iter().map(|m| m[2]).collect())
        .f64(col::STRAIN, cracks.iter().map(|c| c.strain).collect())
        .f64(col::ENERGY_J, cracks.iter().map(|c| c.energy_j).collect())
        .finish(CRACKS.name)
}

/// The acoustic-emission table of one seed.
pub fn emission_frame(seed: u64, clusters: &[Cluster]) -> Result<DataFrame, StoreError> {
    let n = clusters.len();
    let col = |g: &dyn Fn(&Cluster) -> f64| clusters.iter().map(g).collect::<Vec<f64>>();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::CLUSTER, (0..n as u32).collect())
        .f64(col::START_S, col(&|c| c.start_s))
        .f64(col::END_S, col(&|c| c.end_s))
        .f64(col::DURATION_S, col(&|c| c.end_s - c.start_s))
        .u32(col::BREAKS, clusters.iter().map(|c| c.breaks.len() as u32).collect())
        .f64(col::X_M, col(&|c| c.hypocentre[0]))
        .f64(col::Y_M, col(&|c| c.hypocentre[1]))
        .f64(col::Z_M, col(&|c| c.hypocentre[2]))
        .f64(col::CENTROID_X_M, col(&|c| c.centroid[0]))
        .f64(col::CENTROID_Y_M, col(&|c| c.centroid[1]))
        .f64(col::CENTROID_Z_M, col(&|c| c.centroid[2]))
        .f64(col::ENERGY_J, col(&|c| c.energy_j))
        // A cluster of breaks that released no energy has no magnitude (log10 0): null, not −∞.
        .opt_f64(col::MAGNITUDE, clusters.iter().map(|c| c.magnitude.is_finite().then_some(c.magnitude)).collect())
        .finish(ACOUSTIC_EMISSION.name)
}

read_back! {
    /// The cracks table read back.
    pub struct Cracks from CRACKS, |c| {
        /// Seed of each row.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Time (s).
        time_s: Vec<f64> = c.f64s(col::TIME_S)?,
        /// Whether the row is a break (else a softening).
        broke: Vec<bool> = c.strs(col::KIND)?.iter().map(|k| k == CrackKind::Break.name()).collect(),
        /// Canonical bar index.
        bar: Vec<u64> = c.u64s(col::BAR)?,
        /// Bar family.
        family: Vec<String> = c.strs(col::FAMILY)?,
        /// Midpoint x (m).
        x_m: Vec<f64> = c.f64s(col::X_M)?,
        /// Midpoint y (m).
        y_m: Vec<f64> = c.f64s(col::Y_M)?,
        /// Midpoint z (m).
        z_m: Vec<f64> = c.f64s(col::Z_M)?,
        /// Energy (J).
        energy_j: Vec<f64> = c.f64s(col::ENERGY_J)?,
    }
}

impl Cracks {
    /// Number of rows.
    pub fn len(&self) -> usize {
        self.seed.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.seed.is_empty()
    }
}

read_back! {
    /// The acoustic-emission table read back.
    pub struct AcousticEmission from ACOUSTIC_EMISSION, |c| {
        /// Seed of each event.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Time of its first break (s).
        start_s: Vec<f64> = c.f64s(col::START_S)?,
        /// Breaks in it.
        breaks: Vec<u64> = c.u64s(col::BREAKS)?,
        /// Energy (J).
        energy_j: Vec<f64> = c.f64s(col::ENERGY_J)?,
        /// Magnitude.
        magnitude: Vec<f64> = c.f64s(col::MAGNITUDE)?,
    }
}

impl AcousticEmission {
    /// Number of events.
    pub fn len(&self) -> usize {
        self.seed.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.seed.is_empty()
    }
}
