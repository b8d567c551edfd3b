//! One seed's rupture fronts as tables (docs/model.md §13).
//!
//! **ruptures**, one row per event with a front: `seed` u64, `event` u32, `kind`, `label` str,
//! `hypocentre_node` u32 (LDEM), `hypocentre_x_m`, `hypocentre_y_m` f64, `hypocentre_region` str
//! (`background` or the friction map's region), `front_from` str (`slip_rate`: rupture times
//! are when each node's slip rate first reached `[events] rupture_rate_m_s`; `slip_onsets`: its
//! sustained slip onsets), `onset_s` f64 (the hypocentre's),
//! `ruptured_nodes` u32, `ruptured_area_m2`, `rupture_x_min_m`, `rupture_x_max_m`,
//! `rupture_length_m`, `spread_s` (first to last onset) f64, `rupture_speed_m_s` f64 (1/median
//! slowness of the front's one-way stretches along x; +inf: most columns at once; null: cannot be
//! told), `front_windows` u32 (the stretches measured), `speed_over_s` f64, `regime` str,
//! `p_speed_m_s`, `s_speed_m_s`, `rayleigh_speed_m_s` f64, `arrest_x_min`, `arrest_x_max`,
//! `arrest` str.
//!
//! **rupture_onsets**, one row per ruptured node and event: `seed`, `event`, `node` (LDEM),
//! `x_m`, `y_m`, `region`, `onset_s`, `distance_m` (from the hypocentre, in the base plane).

use polars::prelude::DataFrame;
use stickslip_analysis::SeedFronts;
use stickslip_seismo::events::Catalogue;
use stickslip_seismo::front::Front;

use crate::col;
use crate::error::StoreError;
use crate::frame::{Frame, read_back};
use crate::spec::{Scope, SeedTable, TableSpec};

/// How each event started and spread over the base (scenes with `record.slip_onsets`,
/// docs/model.md §13): hypocentre, ruptured area and extent, rupture speed against the lattice's
/// wave speeds, arrest at each end along x.
pub const RUPTURES: TableSpec = TableSpec {
    name: "ruptures",
    scope: Scope::Gathered,
    key: &[col::SEED, col::EVENT],
    columns: &[
        col::SEED,
        col::EVENT,
        col::KIND,
        col::LABEL,
        col::HYPOCENTRE_NODE,
        col::HYPOCENTRE_X_M,
        col::HYPOCENTRE_Y_M,
        col::HYPOCENTRE_REGION,
        col::FRONT_FROM,
        col::ONSET_S,
        col::RUPTURED_NODES,
        col::RUPTURED_AREA_M2,
        col::RUPTURE_X_MIN_M,
        col::RUPTURE_X_MAX_M,
        col::RUPTURE_LENGTH_M,
        col::SPREAD_S,
        col::RUPTURE_SPEED_M_S,
        col::FRONT_WINDOWS,
        col::SPEED_OVER_S,
        col::REGIME,
        col::P_SPEED_M_S,
        col::S_SPEED_M_S,
        col::RAYLEIGH_SPEED_M_S,
        col::ARREST_X_MIN,
        col::ARREST_X_MAX,
        col::ARREST,
    ],
    variable: None,
};

/// The onset of every ruptured contact node in every event (scenes with `record.slip_onsets`).
pub const RUPTURE_ONSETS: TableSpec = TableSpec {
    name: "rupture_onsets",
    scope: Scope::Gathered,
    key: &[col::SEED, col::EVENT, col::NODE],
    columns: &[col::SEED, col::EVENT, col::NODE, col::X_M, col::Y_M, col::REGION, col::ONSET_S, col::DISTANCE_M],
    variable: None,
};

/// The `ruptures` part of a seed whose scene records slip onsets or the fault.
pub const RUPTURES_PART: SeedTable = SeedTable {
    spec: RUPTURES,
    write: |s| s.analysis.fronts.as_ref().map(|f| ruptures_frame(s.seed, f, &s.analysis.catalogue)).transpose(),
};
/// The `rupture_onsets` part of a seed whose scene records slip onsets or the fault.
pub const RUPTURE_ONSETS_PART: SeedTable = SeedTable {
    spec: RUPTURE_ONSETS,
    write: |s| s.analysis.fronts.as_ref().map(|f| rupture_onsets_frame(s.seed, f, &s.analysis.catalogue)).transpose(),
};

/// The ruptures table of one seed.
pub fn ruptures_frame(seed: u64, seed_fronts: &SeedFronts, catalogue: &Catalogue) -> Result<DataFrame, StoreError> {
    let fronts = seed_fronts.rows(catalogue);
    let (nodes, speeds, source) = (&seed_fronts.base, &seed_fronts.speeds, seed_fronts.source);
    let n = fronts.len();
    let f64s = |g: &dyn Fn(&Front) -> f64| fronts.iter().map(|e| g(e.front)).collect::<Vec<f64>>();
    let hypo = |e: &stickslip_analysis::fronts::EventFront<'_>| e.front.hypocentre.0;
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::EVENT, fronts.iter().map(|e| e.event).collect())
        .static_str(col::KIND, fronts.iter().map(|e| e.kind.name()).collect())
        .str(col::LABEL, fronts.iter().map(|e| e.kind.label()).collect())
        .u32(col::HYPOCENTRE_NODE, fronts.iter().map(|e| nodes.ids[hypo(e)].ldem() as u32).collect())
        .f64(col::HYPOCENTRE_X_M, fronts.iter().map(|e| nodes.position_m[hypo(e)][0]).collect())
        .f64(col::HYPOCENTRE_Y_M, fronts.iter().map(|e| nodes.position_m[hypo(e)][1]).collect())
        .str(col::HYPOCENTRE_REGION, fronts.iter().map(|e| nodes.region[hypo(e)].clone()).collect())
        .static_str(col::FRONT_FROM, vec![source; n])
        .f64(col::ONSET_S, f64s(&|f| f.hypocentre.1))
        .u32(col::RUPTURED_NODES, fronts.iter().map(|e| e.front.onsets.len() as u32).collect())
        .f64(col::RUPTURED_AREA_M2, f64s(&|f| f.area_m2))
        .f64(col::RUPTURE_X_MIN_M, f64s(&|f| f.x_range_m.0))
        .f64(col::RUPTURE_X_MAX_M, f64s(&|f| f.x_range_m.1))
        .f64(col::RUPTURE_LENGTH_M, f64s(&|f| f.x_range_m.1 - f.x_range_m.0))
        .f64(col::SPREAD_S, f64s(&|f| f.spread_s()))
        .opt_f64(
            col::RUPTURE_SPEED_M_S,
            fronts.iter().map(|e| Some(e.front.speed_m_s()).filter(|v| !v.is_nan())).collect(),
        )
        .u32(col::FRONT_WINDOWS, fronts.iter().map(|e| e.front.windows as u32).collect())
        .opt_f64(
            col::SPEED_OVER_S,
            fronts.iter().map(|e| Some(e.front.speed_m_s() / speeds.s_m_s).filter(|v| !v.is_nan())).collect(),
        )
        .static_str(col::REGIME, fronts.iter().map(|e| e.front.regime(speeds).name()).collect())
        .f64(col::P_SPEED_M_S, vec![speeds.p_m_s; n])
        .f64(col::S_SPEED_M_S, vec![speeds.s_m_s; n])
        .f64(col::RAYLEIGH_SPEED_M_S, vec![speeds.rayleigh_m_s; n])
        .static_str(col::ARREST_X_MIN, fronts.iter().map(|e| e.front.arrest[0].name()).collect())
        .static_str(col::ARREST_X_MAX, fronts.iter().map(|e| e.front.arrest[1].name()).collect())
        .static_str(col::ARREST, fronts.iter().map(|e| e.front.arrest_summary()).collect())
        .finish(RUPTURES.name)
}

/// The rupture onsets table of one seed.
pub fn rupture_onsets_frame(
    seed: u64,
    seed_fronts: &SeedFronts,
    catalogue: &Catalogue,
) -> Result<DataFrame, StoreError> {
    let fronts = seed_fronts.rows(catalogue);
    let nodes = &seed_fronts.base;
    let rows: Vec<(u32, usize, f64, f64)> = fronts
        .iter()
        .flat_map(|e| {
            let h = nodes.position_m[e.front.hypocentre.0];
            e.front.onsets.iter().map(move |&(i, t)| {
                let p = nodes.position_m[i];
                (e.event, i, t, (p[0] - h[0]).hypot(p[1] - h[1]))
            })
        })
        .collect();
    let n = rows.len();
    Frame::new(n)
        .u64(col::SEED, vec![seed; n])
        .u32(col::EVENT, rows.iter().map(|r| r.0).collect())
        .u32(col::NODE, rows.iter().map(|r| nodes.ids[r.1].ldem() as u32).collect())
        .f64(col::X_M, rows.iter().map(|r| nodes.position_m[r.1][0]).collect())
        .f64(col::Y_M, rows.iter().map(|r| nodes.position_m[r.1][1]).collect())
        .str(col::REGION, rows.iter().map(|r| nodes.region[r.1].clone()).collect())
        .f64(col::ONSET_S, rows.iter().map(|r| r.2).collect())
        .f64(col::DISTANCE_M, rows.iter().map(|r| r.3).collect())
        .finish(RUPTURE_ONSETS.name)
}

read_back! {
    /// The ruptures table read back.
    pub struct Ruptures from RUPTURES, |c| {
        /// Seed of each row.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Event index in its seed's catalogue.
        event: Vec<u64> = c.u64s(col::EVENT)?,
        /// Event label (`S1`, `F2`, …).
        label: Vec<String> = c.strs(col::LABEL)?,
        /// Kind (`main`, …).
        kind: Vec<String> = c.strs(col::KIND)?,
        /// Hypocentre x (m).
        hypocentre_x_m: Vec<f64> = c.f64s(col::HYPOCENTRE_X_M)?,
        /// Hypocentre region.
        hypocentre_region: Vec<String> = c.strs(col::HYPOCENTRE_REGION)?,
        /// Onset of the hypocentre (s).
        onset_s: Vec<f64> = c.f64s(col::ONSET_S)?,
        /// Rupture speed (m/s), `None` without a fit.
        rupture_speed_m_s: Vec<Option<f64>> = c.opt_f64s(col::RUPTURE_SPEED_M_S)?,
        /// Regime name.
        regime: Vec<String> = c.strs(col::REGIME)?,
        /// Arrest toward −x.
        arrest_x_min: Vec<String> = c.strs(col::ARREST_X_MIN)?,
        /// Arrest toward +x.
        arrest_x_max: Vec<String> = c.strs(col::ARREST_X_MAX)?,
        /// Smallest x of the ruptured nodes (m).
        rupture_x_min_m: Vec<f64> = c.f64s(col::RUPTURE_X_MIN_M)?,
        /// Largest x (m).
        rupture_x_max_m: Vec<f64> = c.f64s(col::RUPTURE_X_MAX_M)?,
        /// S speed of the lattice (m/s).
        s_speed_m_s: Vec<f64> = c.f64s(col::S_SPEED_M_S)?,
        /// P speed (m/s).
        p_speed_m_s: Vec<f64> = c.f64s(col::P_SPEED_M_S)?,
        /// Rayleigh speed (m/s).
        rayleigh_speed_m_s: Vec<f64> = c.f64s(col::RAYLEIGH_SPEED_M_S)?,
    }
}

read_back! {
    /// The rupture onsets table read back.
    pub struct RuptureOnsets from RUPTURE_ONSETS, |c| {
        /// Seed of each row.
        seed: Vec<u64> = c.u64s(col::SEED)?,
        /// Event index.
        event: Vec<u64> = c.u64s(col::EVENT)?,
        /// Node x (m).
        x_m: Vec<f64> = c.f64s(col::X_M)?,
        /// Onset (s).
        onset_s: Vec<f64> = c.f64s(col::ONSET_S)?,
    }
}

impl Ruptures {
    /// Rows.
    pub fn len(&self) -> usize {
        self.seed.len()
    }

    /// Whether there is none.
    pub fn is_empty(&self) -> bool {
        self.seed.is_empty()
    }
}
