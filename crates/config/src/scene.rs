//! The scene sections of a pipeline file and their validation into a [`Scene`].
//!
//! Every field has a default (the paper scene, docs/model.md §6), carries its unit in its name,
//! and is checked before anything runs: a refused value names its field, the value and the
//! allowed range.

use serde::{Deserialize, Serialize};
use stickslip_solver::geometry::{Dims, Face, Lattice, NodeId, NodeSet};
use stickslip_solver::laws::{Coulomb, FrictionLaw, SlipWeakening, StaticDynamic};
use stickslip_solver::rupture::{Rupture, kr_from_failure_factor, max_failure_factor};
use stickslip_solver::scene::{
    Component, ControlChannel, Friction, InterfaceQuantity, Kinematic, LoadingPlate, NormalLoad, RecordPlan,
    SelfWeight, SettleMethod, Shear, SkipAhead, TimeStep,
};
use stickslip_solver::{Scene, TracePlan};

use crate::check::Checker;
pub use crate::friction_map::{GridSection, PatchSection};

/// `[block]`: the lattice.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct BlockSection {
    /// Modules along x (slip direction). Default 10.
    pub nx: i64,
    /// Modules along y (width). Default 1.
    pub ny: i64,
    /// Modules along z (height). Default 5.
    pub nz: i64,
    /// Module side Lc in metres. Default 0.1.
    pub lc_m: f64,
}

impl Default for BlockSection {
    fn default() -> Self {
        BlockSection { nx: 10, ny: 1, nz: 5, lc_m: 0.1 }
    }
}

/// `[material]`: elastic properties and the Weibull field on E.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct MaterialSection {
    /// Mean Young's modulus in Pa. Default 2.0e10.
    pub young_pa: f64,
    /// Density in kg/m³. Default 2400.
    pub density_kg_m3: f64,
    /// Poisson's ratio, 0 < ν < 0.5. Default 0.2.
    pub poisson: f64,
    /// Coefficient of variation of E (Weibull, per bar); 0 = homogeneous. Default 0.05.
    pub young_cv: f64,
}

impl Default for MaterialSection {
    fn default() -> Self {
        MaterialSection { young_pa: 2.0e10, density_kg_m3: 2400.0, poisson: 0.2, young_cv: 0.05 }
    }
}

/// `[friction]`: friction with the rigid base.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct FrictionSection {
    /// Static coefficient μs. Default 5.0.
    pub mu_static: f64,
    /// Dynamic coefficient μd ≤ μs; omitted = μs (the plain Coulomb law).
    pub mu_dynamic: Option<f64>,
    /// Slip-weakening distance Dc in metres (μ falls linearly from μs to μd over Dc of slip);
    /// 0 = drops at once. Default 0.
    pub slip_weakening_m: f64,
    /// Coefficient of variation of μ (Weibull, per contact node, its own random stream);
    /// 0 = uniform. Default 0.
    pub mu_cv: f64,
    /// Regions of the base with their own coefficients (asperities, barriers).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub patches: Vec<PatchSection>,
    /// Coefficients per base node from a CSV file.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub grid: Option<GridSection>,
}

impl Default for FrictionSection {
    fn default() -> Self {
        FrictionSection {
            mu_static: 5.0,
            mu_dynamic: None,
            slip_weakening_m: 0.0,
            mu_cv: 0.0,
            patches: Vec::new(),
            grid: None,
        }
    }
}

/// `[loading_plate]`: compliant loading — the nodes of a face tied by springs in x to a rigid
/// plate that moves by the driver law of `[shear]` (Eq. 12), the spring-block loading; absent =
/// the drivers of `[shear]` only.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct LoadingPlateSection {
    /// The face tied to the plate: `"z_max"` (the top, default), `"x_min"` (the trailing face),
    /// any face but the base.
    pub face: String,
    /// Total stiffness of the springs in N/m, shared by the face's nodes in proportion to their
    /// area. Exclusive with `modulus_pa` and `thickness_m`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stiffness_n_m: Option<f64>,
    /// Modulus of an elastic layer between face and plate in Pa (its shear modulus for the top,
    /// its Young's modulus for a face pushed along its normal): stiffness = modulus·area/thickness.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modulus_pa: Option<f64>,
    /// Thickness of that layer in metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub thickness_m: Option<f64>,
    /// Constant pressure on the top face in Pa, pressing the block onto the base in both stages
    /// (besides gravity). Default 0.
    pub normal_pressure_pa: f64,
}

impl Default for LoadingPlateSection {
    fn default() -> Self {
        LoadingPlateSection {
            face: "z_max".into(),
            stiffness_n_m: None,
            modulus_pa: None,
            thickness_m: None,
            normal_pressure_pa: 0.0,
        }
    }
}

/// The largest `time.dt_fraction` accepted without `time.force`: the critical step is computed
/// for the lattice actually built, but a step at the limit has no margin for round-off.
pub const SAFE_DT_FRACTION: f64 = 0.95;

/// `[time]`: the time step, as a fraction of the critical step or in seconds.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields, default)]
pub struct TimeSection {
    /// Δt as a fraction of the critical step `2/ω_max` of the lattice actually built (random
    /// field included), in (0, 0.95] (up to 1 with `force`). Default 0.5 when `dt_s` is not given.
    pub dt_fraction: Option<f64>,
    /// Δt in seconds; refused if above the critical step. Exclusive with `dt_fraction`.
    pub dt_s: Option<f64>,
    /// Accept a `dt_fraction` above 0.95, up to the stability limit 1. Default false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub force: bool,
}

/// `[self_weight]`: stage 1, gravity with heavy damping until static equilibrium.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SelfWeightSection {
    /// Gravity in m/s² (acts in −z in both stages). Default 9.81.
    pub gravity_m_s2: f64,
    /// `"dynamic"` (damped settling, default) or `"static"` (direct solve).
    pub method: String,
    /// Mass-proportional damping D in 1/s during settling. Default 2500.
    pub damping_per_s: f64,
    /// Equilibrium is reached when ‖out-of-balance force‖ / ‖weight‖ falls below this.
    /// Default 1e-6.
    pub settle_tolerance: f64,
    /// Give up (error) if not settled after this long, in seconds. Default 0.1.
    pub max_duration_s: f64,
}

impl Default for SelfWeightSection {
    fn default() -> Self {
        SelfWeightSection {
            gravity_m_s2: 9.81,
            method: SettleMethod::Dynamic.name().into(),
            damping_per_s: 2500.0,
            settle_tolerance: 1e-6,
            max_duration_s: 0.1,
        }
    }
}

/// `[shear]`: stage 2, the driver of Eq. 12 with light damping.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct ShearSection {
    /// Mass-proportional damping D in 1/s during shearing. Default 400.
    pub damping_per_s: f64,
    /// Final driver velocity u̇f in m/s (+x). Default 1.1e-4.
    pub velocity_m_s: f64,
    /// Rise time t0 of Eq. 12 in seconds (velocity reaches 63% of u̇f at t0); 0 = step.
    /// Default 0.002.
    pub rise_time_s: f64,
    /// Duration of the shear stage in seconds. Default 0.32.
    pub duration_s: f64,
    /// Driven nodes by LDEM number.
    pub driver_nodes: Vec<i64>,
    /// Driven nodes by position in metres. Default `[[0.0, 0.0, 2·Lc]]`, used only when
    /// `driver_nodes` is empty too.
    pub driver_at_m: Vec<[f64; 3]>,
    /// Every node of a face driven (`"x_min"`, `"x_max"`, …), added to the lists (e.g. a prism
    /// pulled by its end). Omitted = none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub driver_face: Option<String>,
}

impl Default for ShearSection {
    fn default() -> Self {
        ShearSection {
            damping_per_s: 400.0,
            velocity_m_s: 1.1e-4,
            rise_time_s: 0.002,
            duration_s: 0.32,
            driver_nodes: Vec::new(),
            driver_at_m: Vec::new(),
            driver_face: None,
        }
    }
}

/// `[skip_ahead]`: quasi-static skip-ahead through the interseismic phase of the shear stage.
///
/// While every base node sticks or is lifted and the motion left by the last event has died
/// down, the block follows the driver as a linear elastic body; the run jumps to shortly before
/// the driver displacement at which the next base node reaches its sliding strength, lifts or
/// lands, and integrates explicitly from there. Runs one seed per stepper (no seed batching).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SkipAheadSection {
    /// Turn skip-ahead on. Default false.
    pub enabled: bool,
    /// How far the state may be from the quasi-static one when jumping: the largest change
    /// the leftover motion makes to any base node's margin to its next transition, as a
    /// fraction of that margin (so the next onset time moves by about this fraction of the
    /// time left to it). Default 1e-4.
    pub tolerance: f64,
    /// Explicit steps kept before each predicted transition. Default 20.
    pub margin_steps: i64,
    /// Sampling interval (s) while skipping, a multiple of `record.interval_s` (rounded to
    /// one): long quiet phases need few samples. Omitted = `record.interval_s`.
    pub record_interval_s: Option<f64>,
}

impl Default for SkipAheadSection {
    fn default() -> Self {
        SkipAheadSection { enabled: false, tolerance: 1e-4, margin_steps: 20, record_interval_s: None }
    }
}

/// `[rupture]`: bars that crack, by the bilinear softening law of the LDEM (docs/model.md §11);
/// absent = every bar linear elastic.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct RuptureSection {
    /// Mean fracture energy Gf in J/m² (the energy a crack dissipates per unit area). Default 100
    /// (rock-like).
    pub fracture_energy_j_m2: f64,
    /// `Kr = εr/εp` > 1, where the softening branch reaches zero force. Default 3 when
    /// `failure_factor_per_sqrt_m` is not given; exclusive with it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kr: Option<f64>,
    /// Failure factor Rf in 1/√m: `εp = Rf·√(Gf/((1 − ν²)E))` (Kosteski et al.), `Kr` then follows
    /// from the energy and must exceed 1. Exclusive with `kr`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure_factor_per_sqrt_m: Option<f64>,
    /// Coefficient of variation of the Weibull field on Gf (per bar); 0 = uniform. Default 0.
    pub fracture_energy_cv: f64,
    /// Random stream of the Gf field, ≥ 2 (0 and 1 are E's and μ's); required when
    /// `fracture_energy_cv` > 0.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fracture_energy_stream: Option<i64>,
    /// Correlation of the normal scores of the E and Gf fields (Gaussian copula), −1 … 1.
    /// Default 0 (independent).
    pub young_correlation: f64,
    /// Acoustic emission: two breaks at most this far apart (m) … Omitted = 2·Lc.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ae_link_distance_m: Option<f64>,
    /// … and at most this long apart (s) belong to one event. Omitted = 10·Lc/Cp (ten transits
    /// of a P wave across a module).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ae_link_time_s: Option<f64>,
    /// Zones whose bars stay elastic, `{ face = "x_min", depth_m = 0.1 }`: every bar whose
    /// midpoint lies within `depth_m` of the face (grips, loading points). Default none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub elastic_zones: Vec<ElasticZoneSection>,
}

/// One elastic zone of `[rupture]`.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ElasticZoneSection {
    /// The face: `"x_min"`, `"x_max"`, `"y_min"`, `"y_max"`, `"z_min"`, `"z_max"`.
    pub face: String,
    /// Depth from the face (m), > 0.
    pub depth_m: f64,
}

impl Default for RuptureSection {
    fn default() -> Self {
        RuptureSection {
            fracture_energy_j_m2: 100.0,
            kr: None,
            failure_factor_per_sqrt_m: None,
            fracture_energy_cv: 0.0,
            fracture_energy_stream: None,
            young_correlation: 0.0,
            ae_link_distance_m: None,
            ae_link_time_s: None,
            elastic_zones: Vec::new(),
        }
    }
}

/// `Kr` when `[rupture]` gives neither `kr` nor a failure factor.
pub const DEFAULT_KR: f64 = 3.0;

/// `[[boundary]]`: rollers, i.e. displacement components held at zero on a face.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BoundarySection {
    /// The face: `"x_min"`, `"x_max"`, `"y_min"`, `"y_max"`, `"z_min"`, `"z_max"`.
    pub face: String,
    /// Components held fixed: `"x"`, `"y"`, `"z"`.
    pub fix: Vec<String>,
}

/// `[[record.control]]`: control nodes and what to record there.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ControlSection {
    /// Nodes by LDEM number.
    #[serde(default)]
    pub nodes: Vec<i64>,
    /// Nodes by position in metres.
    #[serde(default)]
    pub at_m: Vec<[f64; 3]>,
    /// A named set of nodes, added to the lists: `"top_line"`, `"top"`, `"surface"`.
    #[serde(default)]
    pub set: Option<String>,
    /// Quantities: `"displacement"`, `"velocity"`, `"acceleration"`. Default `["acceleration"]`.
    #[serde(default = "default_quantities")]
    pub quantities: Vec<String>,
    /// Components. Default `["x", "y", "z"]`.
    #[serde(default = "default_components")]
    pub components: Vec<String>,
}

fn default_quantities() -> Vec<String> {
    vec![Kinematic::Acceleration.name().into()]
}

fn default_components() -> Vec<String> {
    Component::ALL.iter().map(|c| c.name().to_string()).collect()
}

/// `[record]`: what the run records and how often.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct RecordSection {
    /// Sampling interval in seconds: samples are taken every `round(interval_s/Δt)` steps (Δt
    /// does not depend on it, so neither do the run and its events). Omitted = every step.
    pub interval_s: Option<f64>,
    /// Interface quantities. Default: all of them.
    pub interface: Vec<String>,
    /// Record the energy terms (kinetic, elastic, damping, friction, impact, external work).
    /// Default false (costs one extra pass over nodes per step).
    pub energy: bool,
    /// Also record the self-weight stage (at negative times). Default false.
    pub settling: bool,
    /// Record when each contact node starts to slide for good (10 steps in a row): the
    /// hypocentre of an event is its first such onset. Default false.
    pub slip_onsets: bool,
    /// Record every contact node's slip, slip rate, shear and normal stress with the event trace
    /// (every step around each burst of slip, sparsely between): the `fault` table, rupture
    /// fronts read on slip rates, space–time figures. Default false.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub fault: bool,
    /// Fault stations `[x, y]` (m) on the base, each the nearest contact node: one SEAS-format
    /// station file per station and seed. Implies `fault`. Default none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub fault_stations_m: Vec<[f64; 2]>,
    /// The `fault` table and station files keep one instant per this interval (s) of the event
    /// trace's. Omitted = every instant (every step through each burst). Rupture fronts are
    /// read on every instant whatever it says.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fault_interval_s: Option<f64>,
    /// Control nodes.
    pub control: Vec<ControlSection>,
}

impl Default for RecordSection {
    fn default() -> Self {
        RecordSection {
            interval_s: None,
            interface: InterfaceQuantity::ALL.iter().map(|q| q.name().to_string()).collect(),
            energy: false,
            settling: false,
            slip_onsets: false,
            fault: false,
            fault_stations_m: Vec::new(),
            fault_interval_s: None,
            control: Vec::new(),
        }
    }
}

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
}

fn is_absent<T>(x: &&Option<T>) -> bool {
    x.is_none()
}

/// Largest node count the solver accepts (node indices are 32-bit).
pub const MAX_NODES: u64 = 1 << 31;

fn describe_block(lattice: &Lattice) -> String {
    let e = lattice.extent();
    format!(
        "a node of the block (0..{} × 0..{} × 0..{} m; corner nodes every Lc = {} m, centre nodes at module centres)",
        e[0],
        e[1],
        e[2],
        lattice.lc()
    )
}

/// Resolves nodes given by LDEM number (field `ldem_field`) and by position (`at_field`).
fn resolve_nodes(
    ck: &mut Checker,
    lattice: &Lattice,
    (ldem_field, at_field): (&str, &str),
    ldem: &[i64],
    at_m: &[[f64; 3]],
) -> Vec<NodeId> {
    let mut out = Vec::new();
    for (i, &n) in ldem.iter().enumerate() {
        match u64::try_from(n).ok().and_then(|n| lattice.node_by_ldem(n)) {
            Some(id) => out.push(id),
            None => ck.push(
                format!("{ldem_field}[{i}]"),
                n,
                format!("an LDEM node number, 1 ≤ n ≤ {} for this block", lattice.node_count()),
            ),
        }
    }
    for (i, p) in at_m.iter().enumerate() {
        match lattice.node_at(*p) {
            Some(id) => out.push(id),
            None => ck.push(format!("{at_field}[{i}]"), format!("{p:?} m"), describe_block(lattice)),
        }
    }
    out
}

/// The contact node nearest to each fault station, every station outside the base (or on a node
/// already taken by another) refused.
fn fault_stations(ck: &mut Checker, at_m: &[[f64; 2]], lattice: &Lattice) -> Vec<NodeId> {
    let e = lattice.extent();
    let lc = lattice.lc();
    let mut out: Vec<(usize, NodeId)> = Vec::new();
    for (i, p) in at_m.iter().enumerate() {
        let field = format!("record.fault_stations_m[{i}]");
        let inside = (0..2).all(|a| p[a].is_finite() && p[a] >= -1e-9 * e[a] && p[a] <= e[a] * (1.0 + 1e-9));
        if !inside {
            ck.push(
                field,
                format!("{p:?} m"),
                format!("a point of the base, 0 ≤ x ≤ {} m and 0 ≤ y ≤ {} m", e[0], e[1]),
            );
            continue;
        }
        let snap = |v: f64| (v / lc).round() * lc;
        let Some(id) = lattice.node_at([snap(p[0]), snap(p[1]), 0.0]) else {
            ck.push(field, format!("{p:?} m"), "a point of the base");
            continue;
        };
        if let Some(&(j, _)) = out.iter().find(|&&(_, o)| o == id) {
            let q = lattice.position(id);
            ck.push(
                field,
                format!("{p:?} m"),
                format!("a station on its own node: station {j} is already at the nearest node ({}, {}) m", q[0], q[1]),
            );
            continue;
        }
        out.push((i, id));
    }
    out.into_iter().map(|(_, id)| id).collect()
}

/// The friction law the section describes.
fn friction_law(ck: &mut Checker, f: &FrictionSection) -> FrictionLaw {
    ck.non_negative("friction.mu_static", f.mu_static);
    if f.mu_dynamic.is_some() && f.mu_static.is_finite() {
        ck.range("friction.mu_dynamic", f.mu_dynamic.unwrap_or(0.0), 0.0, false, f.mu_static.max(0.0), false);
    }
    ck.non_negative("friction.slip_weakening_m", f.slip_weakening_m);
    match f.mu_dynamic {
        None => {
            if f.slip_weakening_m > 0.0 {
                ck.push(
                    "friction.slip_weakening_m",
                    f.slip_weakening_m,
                    "0 without friction.mu_dynamic (slip weakening from μs to μd needs μd < μs)",
                );
            }
            FrictionLaw::Coulomb(Coulomb { mu: f.mu_static })
        }
        Some(mu_dynamic) if f.slip_weakening_m > 0.0 => {
            if !(mu_dynamic < f.mu_static) {
                ck.push(
                    "friction.mu_dynamic",
                    mu_dynamic,
                    format!("below mu_static ({}) when slip_weakening_m > 0 (otherwise nothing weakens)", f.mu_static),
                );
            }
            FrictionLaw::SlipWeakening(SlipWeakening { mu_static: f.mu_static, mu_dynamic, dc_m: f.slip_weakening_m })
        }
        Some(mu_dynamic) => FrictionLaw::StaticDynamic(StaticDynamic { mu_static: f.mu_static, mu_dynamic }),
    }
}

/// Validates the scene sections `file` into a [`Scene`]; `None` when something was refused
/// (recorded in `ck`).
pub(crate) fn build(file: SceneSections<'_>, ck: &mut Checker) -> Option<Scene> {
    let b = &file.block;
    let blurb = " (a block needs at least one module per axis)";
    let nx = ck.count("block.nx", b.nx, 1, 1_000_000, blurb);
    let ny = ck.count("block.ny", b.ny, 1, 1_000_000, blurb);
    let nz = ck.count("block.nz", b.nz, 1, 1_000_000, blurb);
    ck.positive("block.lc_m", b.lc_m);
    let m = &file.material;
    ck.positive("material.young_pa", m.young_pa);
    ck.positive("material.density_kg_m3", m.density_kg_m3);
    ck.range("material.poisson", m.poisson, 0.0, true, 0.5, true);
    ck.range("material.young_cv", m.young_cv, 0.0, false, 1.0, false);
    let f = &file.friction;
    let law = friction_law(ck, f);
    ck.range("friction.mu_cv", f.mu_cv, 0.0, false, 1.0, false);
    let t = &file.time;
    let time_step = match (t.dt_fraction, t.dt_s) {
        (Some(_), Some(_)) => {
            ck.push("time", "both dt_fraction and dt_s", "one of time.dt_fraction or time.dt_s");
            TimeStep::Fraction(0.5)
        }
        (None, Some(dt)) => {
            ck.positive("time.dt_s", dt);
            TimeStep::Fixed(dt)
        }
        (fraction, None) => {
            let fr = fraction.unwrap_or(0.5);
            if t.force {
                ck.range("time.dt_fraction", fr, 0.0, true, 1.0, false);
            } else if ck.range("time.dt_fraction", fr, 0.0, true, 1.0, false) && fr > SAFE_DT_FRACTION {
                ck.push(
                    "time.dt_fraction",
                    fr,
                    format!(
                        "0 < dt_fraction ≤ {SAFE_DT_FRACTION} (a step at the stability limit has no margin for \
                         round-off; time.force = true accepts up to 1)"
                    ),
                );
            }
            TimeStep::Fraction(fr)
        }
    };
    let s = &file.self_weight;
    ck.non_negative("self_weight.gravity_m_s2", s.gravity_m_s2);
    let method = ck.named::<SettleMethod>("self_weight.method", &s.method).unwrap_or_default();
    ck.non_negative("self_weight.damping_per_s", s.damping_per_s);
    ck.range("self_weight.settle_tolerance", s.settle_tolerance, 0.0, true, 1.0, true);
    ck.positive("self_weight.max_duration_s", s.max_duration_s);
    let sh = &file.shear;
    ck.non_negative("shear.damping_per_s", sh.damping_per_s);
    ck.non_negative("shear.rise_time_s", sh.rise_time_s);
    ck.positive("shear.duration_s", sh.duration_s);
    if ck.non_negative("shear.velocity_m_s", sh.velocity_m_s) && m.young_pa > 0.0 && m.density_kg_m3 > 0.0 {
        // A driver faster than a fraction of the wave speed is outside the model's reach.
        let cp_bound = 0.01 * (m.young_pa / m.density_kg_m3).sqrt();
        ck.range("shear.velocity_m_s", sh.velocity_m_s, 0.0, false, cp_bound, false);
    }
    let r = &file.record;
    if let Some(dt) = r.interval_s {
        ck.positive("record.interval_s", dt);
    }
    let sk = &file.skip_ahead;
    ck.range("skip_ahead.tolerance", sk.tolerance, 0.0, true, 0.5, false);
    ck.count("skip_ahead.margin_steps", sk.margin_steps, 1, 1_000_000, "");
    if let Some(iv) = sk.record_interval_s {
        match r.interval_s {
            Some(base) if base > 0.0 => {
                ck.range("skip_ahead.record_interval_s", iv, base, false, f64::INFINITY, true);
            }
            _ => {
                ck.push(
                    "skip_ahead.record_interval_s",
                    iv,
                    "only with record.interval_s set (a multiple of it, ≥ record.interval_s)",
                );
            }
        }
    }
    let rupture = file.rupture.as_ref().map(|ru| rupture(ck, ru, m, b.lc_m));
    if rupture.is_some() && sk.enabled {
        ck.push(
            "skip_ahead.enabled",
            "true",
            "false with [rupture] (the skip-ahead follows the linear elastic motion; a bar past its peak is not linear)",
        );
    }
    let mut interface: Vec<InterfaceQuantity> = ck.named_list("record.interface", &r.interface);
    interface.dedup();
    // Everything below needs the lattice.
    let (Some(nx), Some(ny), Some(nz)) = (nx, ny, nz) else { return None };
    let dims = Dims::new(nx, ny, nz);
    let nodes = dims.node_count() as u64;
    if nodes > MAX_NODES {
        ck.push("block", format!("{nx}×{ny}×{nz} modules ({nodes} nodes)"), format!("at most {MAX_NODES} nodes"));
    }
    if !(b.lc_m > 0.0 && b.lc_m.is_finite()) || nodes > MAX_NODES {
        return None;
    }
    let lattice = Lattice::new(dims, b.lc_m);
    let no_drivers_given = sh.driver_nodes.is_empty() && sh.driver_at_m.is_empty();
    let (driver_ldem, driver_at): (&[i64], Vec<[f64; 3]>) = if no_drivers_given && file.loading_plate.is_some() {
        // The plate loads the block: no default driver node.
        (&[], Vec::new())
    } else if no_drivers_given {
        (&[], vec![[0.0, 0.0, 2.0 * b.lc_m]])
    } else {
        (&sh.driver_nodes, sh.driver_at_m.clone())
    };
    let (driver_ldem, driver_at) = match sh.driver_face {
        Some(_) if sh.driver_nodes.is_empty() && sh.driver_at_m.is_empty() => (&[][..], Vec::new()),
        _ => (driver_ldem, driver_at),
    };
    let mut drivers = resolve_nodes(ck, &lattice, ("shear.driver_nodes", "shear.driver_at_m"), driver_ldem, &driver_at);
    if let Some(face) = &sh.driver_face
        && let Some(face) = ck.named::<Face>("shear.driver_face", face)
    {
        drivers.extend(face.nodes(&lattice));
    }
    drivers.sort();
    drivers.dedup();
    // Without gravity and friction the base carries nothing, and a base node may be driven.
    let base_carries = file.self_weight.gravity_m_s2 != 0.0 || file.friction.mu_static != 0.0;
    for d in drivers.iter().filter(|_| base_carries) {
        if lattice.half_units(*d)[2] == 0 {
            ck.push(
                "shear.driver",
                format!("LDEM {} at {:?} m", d.ldem(), lattice.position(*d)),
                "a node above the base (z > 0): base nodes are held by friction (any node, without gravity and \
                 friction)",
            );
        }
    }
    let fixed = rollers(ck, file, &lattice);
    for d in &drivers {
        if let Ok(i) = fixed.binary_search_by_key(d, |(id, _)| *id)
            && fixed[i].1[0]
        {
            ck.push("shear.driver", format!("LDEM {}", d.ldem()), "a node whose x is not held by a [[boundary]]");
        }
    }
    let control = control_channels(ck, file, &lattice);
    let map = crate::friction_map::build(ck, &lattice, &law, &f.patches, f.grid.as_ref());
    let (plate, normal_load) = match file.loading_plate {
        Some(lp) => loading_plate(ck, lp, &lattice, &fixed),
        None => (None, None),
    };
    if file.loading_plate.is_some() && sk.enabled {
        ck.push(
            "skip_ahead.enabled",
            "true",
            "false with [loading_plate] (the skip-ahead's quasi-static motion does not include the plate's springs yet)",
        );
    }
    Some(Scene {
        dims,
        lc_m: b.lc_m,
        young_pa: m.young_pa,
        density_kg_m3: m.density_kg_m3,
        poisson: m.poisson,
        young_cv: m.young_cv,
        friction: Friction { law, mu_cv: f.mu_cv, map },
        time_step,
        self_weight: SelfWeight {
            gravity_m_s2: s.gravity_m_s2,
            method,
            damping_per_s: s.damping_per_s,
            settle_tolerance: s.settle_tolerance,
            max_duration_s: s.max_duration_s,
        },
        shear: Shear {
            damping_per_s: sh.damping_per_s,
            velocity_m_s: sh.velocity_m_s,
            rise_time_s: sh.rise_time_s,
            duration_s: sh.duration_s,
            drivers,
        },
        fixed,
        record: RecordPlan {
            interval_s: r.interval_s,
            interface,
            energy: r.energy,
            settling: r.settling,
            slip_onsets: r.slip_onsets,
            fault: r.fault || !r.fault_stations_m.is_empty(),
            fault_stations: fault_stations(ck, &r.fault_stations_m, &lattice),
            fault_interval_s: r.fault_interval_s.filter(|&v| ck.positive("record.fault_interval_s", v)),
            control,
            trace: TracePlan::default(),
        },
        plate,
        normal_load,
        skip_ahead: SkipAhead {
            enabled: sk.enabled,
            tolerance: sk.tolerance,
            margin_steps: sk.margin_steps.max(1) as u64,
            record_interval_s: sk.record_interval_s,
        },
        rupture,
    })
}

/// The plate and the normal load of `[loading_plate]`, every refused value recorded in `ck`.
fn loading_plate(
    ck: &mut Checker,
    lp: &LoadingPlateSection,
    lattice: &Lattice,
    fixed: &[(NodeId, [bool; 3])],
) -> (Option<LoadingPlate>, Option<NormalLoad>) {
    let face = ck.named::<Face>("loading_plate.face", &lp.face);
    if face == Some(Face::ZMin) {
        ck.push(
            "loading_plate.face",
            "\"z_min\"",
            "a face other than the base (\"z_max\", \"x_min\", \"x_max\", \"y_min\", \"y_max\"): the base's nodes are held \
             by friction",
        );
    }
    ck.non_negative("loading_plate.normal_pressure_pa", lp.normal_pressure_pa);
    let normal_load = (lp.normal_pressure_pa > 0.0 && lp.normal_pressure_pa.is_finite())
        .then(|| NormalLoad::on_top(lattice, lp.normal_pressure_pa));
    let face = face.filter(|f| *f != Face::ZMin);
    let area = face.map(|f| {
        let e = lattice.extent();
        let (axis, _) = f.axis();
        (0..3).filter(|&a| a != axis).map(|a| e[a]).product::<f64>()
    });
    let total = match (lp.stiffness_n_m, lp.modulus_pa, lp.thickness_m) {
        (Some(k), None, None) => ck.positive("loading_plate.stiffness_n_m", k).then_some(k),
        (None, Some(g), Some(t)) => {
            let ok = ck.positive("loading_plate.modulus_pa", g) & ck.positive("loading_plate.thickness_m", t);
            ok.then(|| area.map(|a| g * a / t)).flatten()
        }
        (k, g, t) => {
            let given: Vec<String> = [("stiffness_n_m", k), ("modulus_pa", g), ("thickness_m", t)]
                .iter()
                .filter_map(|(name, v)| v.map(|v| format!("{name} = {v}")))
                .collect();
            ck.push(
                "loading_plate",
                if given.is_empty() { "no stiffness".to_string() } else { given.join(", ") },
                "either stiffness_n_m (N/m, > 0) or both modulus_pa and thickness_m",
            );
            None
        }
    };
    let (Some(face), Some(total)) = (face, total) else { return (None, normal_load) };
    let area = area.expect("a face has an area");
    let nodes = face.nodes(lattice);
    for id in &nodes {
        if let Ok(i) = fixed.binary_search_by_key(id, |(n, _)| *n)
            && fixed[i].1[0]
        {
            ck.push(
                "loading_plate.face",
                format!("\"{}\" (LDEM {} is held in x by a [[boundary]])", face.name(), id.ldem()),
                "a face whose nodes are free in x (a roller would take the springs' pull)",
            );
            break;
        }
    }
    let stiffness_n_m = nodes.iter().map(|&id| total * face.tributary_area(lattice, id) / area).collect();
    (Some(LoadingPlate { face, nodes, stiffness_n_m }), normal_load)
}

/// The bilinear law of `[rupture]`, every refused value recorded in `ck`.
fn rupture(ck: &mut Checker, r: &RuptureSection, m: &MaterialSection, lc_m: f64) -> Rupture {
    ck.positive("rupture.fracture_energy_j_m2", r.fracture_energy_j_m2);
    let lattice_ok = m.poisson > 0.0 && m.poisson < 0.5 && lc_m > 0.0 && lc_m.is_finite();
    let kr = match (r.kr, r.failure_factor_per_sqrt_m) {
        (Some(_), Some(_)) => {
            ck.push(
                "rupture",
                "both kr and failure_factor_per_sqrt_m",
                "one of rupture.kr or rupture.failure_factor_per_sqrt_m (with a failure factor, Kr follows from the energy)",
            );
            DEFAULT_KR
        }
        (Some(kr), None) => {
            ck.range("rupture.kr", kr, 1.0, true, f64::INFINITY, true);
            kr
        }
        (None, Some(rf)) => {
            if ck.positive("rupture.failure_factor_per_sqrt_m", rf) && lattice_ok {
                let kr = kr_from_failure_factor(rf, m.poisson, lc_m);
                if !(kr > 1.0) {
                    ck.push(
                        "rupture.failure_factor_per_sqrt_m",
                        rf,
                        format!(
                            "0 < failure_factor_per_sqrt_m < {:.6} for this lattice (it gives Kr = 2(1 − ν²)/((2 + 4δ)·α·Lc·Rf²) \
                             = {kr:.4}; the softening branch needs Kr > 1)",
                            max_failure_factor(m.poisson, lc_m)
                        ),
                    );
                }
                kr
            } else {
                DEFAULT_KR
            }
        }
        (None, None) => DEFAULT_KR,
    };
    ck.range("rupture.fracture_energy_cv", r.fracture_energy_cv, 0.0, false, 1.0, false);
    let stream = match (r.fracture_energy_stream, r.fracture_energy_cv > 0.0) {
        (None, true) => {
            ck.push(
                "rupture.fracture_energy_stream",
                "(missing)",
                format!(
                    "a random stream ≥ 2 for the Weibull field on Gf (fracture_energy_cv = {}); streams 0 and 1 draw the \
                     fields on E and μ",
                    r.fracture_energy_cv
                ),
            );
            None
        }
        (Some(s), true) => {
            if s < 2 {
                ck.push(
                    "rupture.fracture_energy_stream",
                    s,
                    "an integer ≥ 2 (streams 0 and 1 draw the fields on E and μ; the Gf field needs its own)",
                );
            }
            u64::try_from(s).ok()
        }
        (Some(s), false) => {
            ck.push("rupture.fracture_energy_stream", s, "only with rupture.fracture_energy_cv > 0 (no field to draw)");
            None
        }
        (None, false) => None,
    };
    if ck.range("rupture.young_correlation", r.young_correlation, -1.0, false, 1.0, false)
        && r.young_correlation != 0.0
        && !(m.young_cv > 0.0 && r.fracture_energy_cv > 0.0)
    {
        ck.push(
            "rupture.young_correlation",
            r.young_correlation,
            "0 unless material.young_cv and rupture.fracture_energy_cv are both > 0 (a correlation needs two fields)",
        );
    }
    if let Some(d) = r.ae_link_distance_m {
        ck.positive("rupture.ae_link_distance_m", d);
    }
    if let Some(t) = r.ae_link_time_s {
        ck.non_negative("rupture.ae_link_time_s", t);
    }
    let mut elastic_zones = Vec::new();
    for (i, z) in r.elastic_zones.iter().enumerate() {
        let face = ck.named::<Face>(&format!("rupture.elastic_zones[{i}].face"), &z.face);
        if ck.positive(&format!("rupture.elastic_zones[{i}].depth_m"), z.depth_m)
            && let Some(face) = face
        {
            elastic_zones.push((face, z.depth_m));
        }
    }
    Rupture {
        fracture_energy_j_m2: r.fracture_energy_j_m2,
        kr,
        failure_factor_per_sqrt_m: r.failure_factor_per_sqrt_m,
        fracture_energy_cv: r.fracture_energy_cv,
        fracture_energy_stream: stream,
        young_correlation: r.young_correlation,
        elastic_zones,
    }
}

/// The rollers of `[[boundary]]`, merged per node and sorted. A contact node may only be held in
/// y (a symmetry plane): holding its z would keep it off the base and holding its x would take
/// the shear the base's friction should carry — unless the scene has neither gravity nor
/// friction, when the base carries nothing and rollers on it are a plain support.
fn rollers(ck: &mut Checker, file: SceneSections<'_>, lattice: &Lattice) -> Vec<(NodeId, [bool; 3])> {
    let mut fixed: Vec<(NodeId, [bool; 3])> = Vec::new();
    for (i, bnd) in file.boundary.iter().enumerate() {
        if bnd.fix.is_empty() {
            ck.push(format!("boundary[{i}].fix"), "[]", "at least one of \"x\", \"y\", \"z\"");
        }
        let Some(face) = ck.named::<Face>(&format!("boundary[{i}].face"), &bnd.face) else { continue };
        let comps: Vec<Component> = ck.named_list(&format!("boundary[{i}].fix"), &bnd.fix);
        let mut mask = [false; 3];
        for c in &comps {
            mask[c.axis()] = true;
        }
        let nodes = face.nodes(lattice);
        let on_base = nodes.iter().any(|&id| lattice.half_units(id)[2] == 0);
        // Without gravity and friction the base carries nothing, and rollers on it are a plain
        // support (e.g. a wave guide).
        let base_carries = file.self_weight.gravity_m_s2 != 0.0 || file.friction.mu_static != 0.0;
        if on_base && base_carries && (mask[0] || mask[2]) {
            let held: Vec<&str> = comps.iter().filter(|c| c.axis() != 1).map(|c| c.name()).collect();
            ck.push(
                format!("boundary[{i}]"),
                format!("face = \"{}\", fix = {:?}", bnd.face, bnd.fix),
                format!(
                    "no roller in {} on contact nodes (this face holds base nodes): it would {}; a face with base \
                     nodes may hold only \"y\" (or anything, without gravity and friction)",
                    held.join(" and "),
                    if mask[2] {
                        "keep them off the base, so the contact never acts"
                    } else {
                        "take the shear that the base's friction should carry"
                    }
                ),
            );
        }
        fixed.extend(nodes.into_iter().map(|id| (id, mask)));
    }
    fixed.sort_by_key(|(id, _)| *id);
    let mut merged: Vec<(NodeId, [bool; 3])> = Vec::new();
    for (id, mask) in fixed {
        match merged.last_mut() {
            Some((last, m)) if *last == id => (0..3).for_each(|a| m[a] |= mask[a]),
            _ => merged.push((id, mask)),
        }
    }
    merged
}

/// The control channels of `[[record.control]]`, sorted and unique.
fn control_channels(ck: &mut Checker, file: SceneSections<'_>, lattice: &Lattice) -> Vec<ControlChannel> {
    let mut control = Vec::new();
    for (i, c) in file.record.control.iter().enumerate() {
        let field = format!("record.control[{i}].");
        if c.nodes.is_empty() && c.at_m.is_empty() && c.set.is_none() {
            ck.push(
                format!("{field}nodes"),
                "[]",
                "at least one node (nodes = [LDEM numbers], at_m = [[x, y, z]] or set = \"top_line\" | \"top\" | \"surface\")",
            );
        }
        if c.quantities.is_empty() {
            ck.push(
                format!("{field}quantities"),
                "[]",
                "at least one of \"displacement\", \"velocity\", \"acceleration\"",
            );
        }
        if c.components.is_empty() {
            ck.push(format!("{field}components"), "[]", "at least one of \"x\", \"y\", \"z\"");
        }
        let quantities: Vec<Kinematic> = ck.named_list(&format!("{field}quantities"), &c.quantities);
        let components: Vec<Component> = ck.named_list(&format!("{field}components"), &c.components);
        let names = (format!("{field}nodes"), format!("{field}at_m"));
        let mut nodes = resolve_nodes(ck, lattice, (&names.0, &names.1), &c.nodes, &c.at_m);
        if let Some(set) = &c.set
            && let Some(set) = ck.named::<NodeSet>(&format!("{field}set"), set)
        {
            nodes.extend(set.nodes(lattice));
        }
        for node in nodes {
            for &quantity in &quantities {
                for &component in &components {
                    control.push(ControlChannel { node, quantity, component });
                }
            }
        }
    }
    control.sort();
    control.dedup();
    control
}
