//! The scene sections of a pipeline file and their validation into a [`Scene`].
//!
//! Every field has a default (the paper scene, docs/model.md §6), carries its unit in its name,
//! and is checked before anything runs: a refused value names its field, the value and the
//! allowed range.
//!
//! The sections are declared in `sections.rs` (the body and its time step) and
//! `stage_sections.rs` (the loading stages and what they record); each part of the scene is
//! checked and built by its own module, in the order `build` calls them — the order in which a
//! refused file's errors are listed.

mod block;
mod boundaries;
mod fault;
mod friction;
mod loading;
mod medium;
mod record;
mod rupture;
mod sections;
mod stage_sections;
mod time;

use serde::Serialize;
use stickslip_solver::Scene;

use crate::check::Checker;
pub use crate::friction_map::{GridSection, PatchSection};
pub use block::MAX_NODES;
pub use boundaries::AbsorbingSection;
pub use fault::{
    FaultSection, LEAST_ZONE_NODES, StationSection, StochasticSection, TRACTION_GRID_HEADER, TractionGridSection,
    TractionPatchSection, Vs30,
};
pub use medium::{AttenuationSection, LayerSection, MAX_LAYERS, MediumSection, lowest_q, parse_velocity_file};
pub use sections::*;
pub use stage_sections::*;

/// The scene sections of a pipeline file, borrowed: what a scene is built from, and the canonical
/// form its hash is taken of (the layout results folders of earlier versions were stamped with,
/// so they stay valid).
#[derive(Clone, Copy, Debug, Serialize)]
pub struct SceneSections<'a> {
    /// `[block]`.
    pub block: &'a BlockSection,
    /// `[material]`.
    pub material: &'a MaterialSection,
    /// `[friction]`.
    pub friction: &'a FrictionSection,
    /// `[time]`.
    pub time: &'a TimeSection,
    /// `[self_weight]`.
    pub self_weight: &'a SelfWeightSection,
    /// `[shear]`.
    pub shear: &'a ShearSection,
    /// `[[boundary]]`.
    pub boundary: &'a Vec<BoundarySection>,
    /// `[record]`.
    pub record: &'a RecordSection,
    /// `[skip_ahead]`.
    pub skip_ahead: &'a SkipAheadSection,
    /// `[loading_plate]` (left out of the canonical form when absent).
    #[serde(skip_serializing_if = "is_absent")]
    pub loading_plate: &'a Option<LoadingPlateSection>,
    /// `[rupture]` (left out of the canonical form when absent, so the hashes of files without it
    /// do not change).
    #[serde(skip_serializing_if = "is_absent")]
    pub rupture: &'a Option<RuptureSection>,
    /// `[fault]` (left out of the canonical form when absent).
    #[serde(skip_serializing_if = "is_absent")]
    pub fault: &'a Option<FaultSection>,
    /// `[absorbing]` (left out of the canonical form when absent).
    #[serde(skip_serializing_if = "is_absent")]
    pub absorbing: &'a Option<AbsorbingSection>,
    /// `[[stations]]` (left out of the canonical form when empty).
    #[serde(skip_serializing_if = "is_empty")]
    pub stations: &'a Vec<StationSection>,
    /// `[medium]` (left out of the canonical form when absent).
    #[serde(skip_serializing_if = "is_absent")]
    pub medium: &'a Option<MediumSection>,
}

impl SceneSections<'_> {
    /// Whether the base carries the block (gravity or friction): then rollers and drivers must
    /// leave its contact nodes free to press and slide; without either the base is a plain
    /// support.
    pub(crate) fn base_carries(&self) -> bool {
        self.self_weight.gravity_m_s2 != 0.0 || self.friction.mu_static != 0.0
    }
}

fn is_empty<T>(x: &&Vec<T>) -> bool {
    x.is_empty()
}

fn is_absent<T>(x: &&Option<T>) -> bool {
    x.is_none()
}

/// Validates the scene sections `file` into a [`Scene`]; `None` when something was refused
/// (recorded in `ck`).
pub(crate) fn build(file: SceneSections<'_>, ck: &mut Checker) -> Option<Scene> {
    // The checks that need no lattice, section by section.
    let counts = block::counts(ck, file.block);
    block::check_material(ck, file.material, file.block.lc_m);
    let law = friction::law(ck, file.friction);
    let time_step = time::time_step(ck, file.time);
    time::check_step_count(ck, file.time, file.shear, file.self_weight);
    let self_weight = loading::self_weight(ck, file.self_weight);
    loading::check_shear(ck, file.shear, file.material);
    record::check_interval(ck, file.record, file.shear.duration_s);
    let skip_ahead = time::skip_ahead(ck, file.skip_ahead, file.record);
    let rupture = file.rupture.as_ref().map(|r| rupture::rupture(ck, r, file.material, file.block.lc_m));
    time::refuse_skip_ahead_with(ck, file.skip_ahead, rupture.is_some(), time::WITH_RUPTURE);
    time::refuse_skip_ahead_with(ck, file.skip_ahead, !file.friction.heals, time::WITH_KEPT_SLIP);
    if let Some(why) = crate::laws::of(&law).skip_ahead_refused {
        time::refuse_skip_ahead_with(ck, file.skip_ahead, true, why);
    }
    let interface = record::interface(ck, file.record);
    // Everything below needs the lattice.
    let lattice = block::lattice(ck, file.block, counts)?;
    let drivers = boundaries::drivers(ck, file, &lattice);
    let fixed = boundaries::rollers(ck, file, &lattice);
    boundaries::refuse_held_drivers(ck, &drivers, &fixed);
    let mut control = record::control_channels(ck, file.record, &lattice);
    let (stations, station_channels) = fault::stations(ck, file, &lattice);
    control.extend(station_channels);
    control.sort();
    control.dedup();
    let fault = fault::fault(ck, file, &lattice);
    let absorbing = boundaries::absorbing(ck, file);
    let medium = medium::medium(ck, file);
    let friction = friction::friction(ck, file.friction, law, &lattice);
    fault::refuse_unresolved_rate_state(ck, fault.as_ref(), &friction, file.material, file.block.lc_m);
    fault::refuse_unbalanced_start(ck, fault.as_ref(), &friction);
    let (plate, normal_load) = match file.loading_plate {
        Some(lp) => boundaries::loading_plate(ck, lp, &lattice, &fixed),
        None => (None, None),
    };
    time::refuse_skip_ahead_with(ck, file.skip_ahead, file.loading_plate.is_some(), time::WITH_PLATE);
    let record = record::plan(ck, file.record, interface, control, &lattice);
    fault::refuse_shared_station_names(
        ck,
        &file.record.fault_stations_m,
        &record.fault_stations,
        fault.as_ref(),
        &lattice,
    );
    let (b, m) = (file.block, file.material);
    Some(Scene {
        dims: lattice.dims(),
        lc_m: b.lc_m,
        young_pa: m.young_pa,
        density_kg_m3: m.density_kg_m3,
        poisson: m.poisson,
        young_cv: m.young_cv,
        friction,
        time_step,
        self_weight,
        shear: loading::shear(file.shear),
        boundaries: boundaries::specs(fixed, drivers, plate, normal_load, absorbing),
        record,
        skip_ahead,
        rupture,
        fault,
        stations,
        medium,
    })
}
