//! The sections of the two loading stages and of what they record, with their documented defaults.
//!
//! `[self_weight]`, `[shear]`, `[loading_plate]`, `[[boundary]]`, `[skip_ahead]`, `[record]`.

use serde::{Deserialize, Serialize};
use stickslip_solver::scene::{Component, InterfaceQuantity, Kinematic, SettleMethod};

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
