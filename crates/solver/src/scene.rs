//! Scene files (TOML, serde) and their validation into a runnable [`Scene`].
//!
//! A scene is the physics of one run: block, material, friction, time step, the two loading
//! stages, optional rollers and what to record. Every field has a default (the paper scene of
//! SPEC §6), carries its unit in its name, and is checked before anything runs: a refused value
//! names its field, the value and the allowed range.

use serde::{Deserialize, Serialize};

use crate::error::{FieldError, SolverError};

use crate::lattice::{Dims, Lattice, NodeId};

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

/// `[friction]`: Coulomb friction with the rigid base.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct FrictionSection {
    /// Static coefficient μs. Default 5.0.
    pub mu_static: f64,
    /// Dynamic coefficient μd ≤ μs; omitted = μs (the plain law).
    pub mu_dynamic: Option<f64>,
    /// Slip-weakening distance Dc in metres (μ falls linearly from μs to μd over Dc of slip);
    /// 0 = drops at once. Default 0.
    pub slip_weakening_m: f64,
    /// Coefficient of variation of μ (Weibull, per contact node, its own random stream);
    /// 0 = uniform. Default 0.
    pub mu_cv: f64,
}

impl Default for FrictionSection {
    fn default() -> Self {
        FrictionSection { mu_static: 5.0, mu_dynamic: None, slip_weakening_m: 0.0, mu_cv: 0.0 }
    }
}

/// `[time]`: the time step, as a fraction of the critical step or in seconds.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields, default)]
pub struct TimeSection {
    /// Δt as a fraction of the critical step `2/ω_max` of the lattice actually built (random
    /// field included), in (0, 1]. Default 0.5 when `dt_s` is not given.
    pub dt_fraction: Option<f64>,
    /// Δt in seconds; refused if above the critical step. Exclusive with `dt_fraction`.
    pub dt_s: Option<f64>,
}

/// How the self-weight stage reaches equilibrium.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "snake_case")]
pub enum SettleMethod {
    /// Heavy damping until the out-of-balance force is small (the paper's way).
    #[default]
    Dynamic,
    /// Solve `K·u = weight` directly with every base node held where it stands (conjugate
    /// gradients); falls back to `dynamic` when that equilibrium is not admissible (a base node
    /// would pull on the base or its friction would not hold it).
    Static,
}

impl SettleMethod {
    /// Name as written in scene files.
    pub fn name(self) -> &'static str {
        match self {
            SettleMethod::Dynamic => "dynamic",
            SettleMethod::Static => "static",
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
    pub method: SettleMethod,
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
            method: SettleMethod::Dynamic,
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
    /// Driven nodes by position in metres. Default `[[0.0, 0.0, 0.2]]`, used only when
    /// `driver_nodes` is empty too.
    pub driver_at_m: Vec<[f64; 3]>,
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

/// A face of the block.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Face {
    /// x = 0.
    XMin,
    /// x = nx·Lc.
    XMax,
    /// y = 0.
    YMin,
    /// y = ny·Lc.
    YMax,
    /// z = 0 (the base).
    ZMin,
    /// z = nz·Lc (the top).
    ZMax,
}

/// A displacement component.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum Component {
    /// x (slip direction).
    X,
    /// y (width).
    Y,
    /// z (vertical).
    Z,
}

impl Component {
    /// Axis index 0, 1, 2.
    pub fn axis(self) -> usize {
        match self {
            Component::X => 0,
            Component::Y => 1,
            Component::Z => 2,
        }
    }

    /// `"x"`, `"y"` or `"z"`.
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self.axis()]
    }
}

/// `[[boundary]]`: rollers, i.e. displacement components held at zero on a face.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BoundarySection {
    /// The face.
    pub face: Face,
    /// Components held fixed.
    pub fix: Vec<Component>,
}

/// Interface quantities a scene can record.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq, Hash)]
#[serde(rename_all = "snake_case")]
pub enum InterfaceQuantity {
    /// τ = −ΣF_x/A (Pa).
    ShearStress,
    /// σ = ΣN/A (Pa).
    NormalStress,
    /// δ, mean x-displacement of the contact nodes (m).
    MeanSlip,
    /// Mean and max x-velocity of the contact nodes (m/s).
    SlipRate,
    /// Number of sliding contact nodes.
    SlippingNodes,
    /// Number of lifted (out of contact) contact nodes.
    LiftedNodes,
    /// Total driver force (N) and imposed displacement (m).
    Driver,
}

impl InterfaceQuantity {
    /// All interface quantities.
    pub const ALL: [InterfaceQuantity; 7] = [
        InterfaceQuantity::ShearStress,
        InterfaceQuantity::NormalStress,
        InterfaceQuantity::MeanSlip,
        InterfaceQuantity::SlipRate,
        InterfaceQuantity::SlippingNodes,
        InterfaceQuantity::LiftedNodes,
        InterfaceQuantity::Driver,
    ];
}

/// Kinematic quantities recorded at control nodes.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum Kinematic {
    /// Displacement (m).
    Displacement,
    /// Velocity (m/s).
    Velocity,
    /// Acceleration (m/s²).
    Acceleration,
}

impl Kinematic {
    /// Name with unit, as used in column names.
    pub fn column(self) -> &'static str {
        match self {
            Kinematic::Displacement => "displacement_m",
            Kinematic::Velocity => "velocity_m_s",
            Kinematic::Acceleration => "acceleration_m_s2",
        }
    }
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
    /// A named set of nodes, added to the lists.
    #[serde(default)]
    pub set: Option<NodeSet>,
    /// Quantities. Default `["acceleration"]`.
    #[serde(default = "default_quantities")]
    pub quantities: Vec<Kinematic>,
    /// Components. Default `["x", "y", "z"]`.
    #[serde(default = "default_components")]
    pub components: Vec<Component>,
}

/// Named sets of control nodes (corner nodes only).
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum NodeSet {
    /// The line of top-face nodes at y = 0 (along x).
    TopLine,
    /// Every node of the top face.
    Top,
    /// Every corner node on the outer surface.
    Surface,
}

impl NodeSet {
    /// The nodes of the set in `lattice`, canonical order.
    pub fn nodes(self, lattice: &Lattice) -> Vec<NodeId> {
        let top = 2 * lattice.dims().nz;
        (0..lattice.node_count() as u32)
            .map(NodeId)
            .filter(|&id| {
                let h = lattice.half_units(id);
                let corner = matches!(lattice.kind(id), crate::lattice::NodeKind::Corner(_));
                corner
                    && match self {
                        NodeSet::TopLine => h[2] == top && h[1] == 0,
                        NodeSet::Top => h[2] == top,
                        NodeSet::Surface => lattice.on_surface(id),
                    }
            })
            .collect()
    }
}

fn default_quantities() -> Vec<Kinematic> {
    vec![Kinematic::Acceleration]
}

fn default_components() -> Vec<Component> {
    vec![Component::X, Component::Y, Component::Z]
}

/// `[record]`: what the run records and how often.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct RecordSection {
    /// Sampling interval in seconds; Δt is lowered (never raised) to make it a whole number of
    /// steps. Omitted = every step.
    pub interval_s: Option<f64>,
    /// Interface quantities. Default: all of them.
    pub interface: Vec<InterfaceQuantity>,
    /// Record the energy terms (kinetic, elastic, damping, friction, impact, external work).
    /// Default false (costs one extra pass over nodes per step).
    pub energy: bool,
    /// Also record the self-weight stage (at negative times). Default false.
    pub settling: bool,
    /// Record when each contact node starts to slide for good (10 steps in a row): the
    /// hypocentre of an event is its first such onset. Default false.
    pub slip_onsets: bool,
    /// Control nodes.
    pub control: Vec<ControlSection>,
}

impl Default for RecordSection {
    fn default() -> Self {
        RecordSection {
            interval_s: None,
            interface: InterfaceQuantity::ALL.to_vec(),
            energy: false,
            settling: false,
            slip_onsets: false,
            control: Vec::new(),
        }
    }
}

/// A scene as written in a file: every section optional, defaults = the paper scene.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields, default)]
pub struct SceneFile {
    /// `[block]`.
    pub block: BlockSection,
    /// `[material]`.
    pub material: MaterialSection,
    /// `[friction]`.
    pub friction: FrictionSection,
    /// `[time]`.
    pub time: TimeSection,
    /// `[self_weight]`.
    pub self_weight: SelfWeightSection,
    /// `[shear]`.
    pub shear: ShearSection,
    /// `[[boundary]]`.
    pub boundary: Vec<BoundarySection>,
    /// `[record]`.
    pub record: RecordSection,
    /// `[skip_ahead]`.
    pub skip_ahead: SkipAheadSection,
}

/// How Δt is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TimeStep {
    /// A fraction of the critical step of each seed's lattice.
    Fraction(f64),
    /// A fixed step in seconds (must be below every seed's critical step).
    Fixed(f64),
}

/// Coulomb friction law with optional slip weakening and random field.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrictionLaw {
    /// μs.
    pub mu_static: f64,
    /// μd.
    pub mu_dynamic: f64,
    /// Dc in metres (0 = immediate drop).
    pub slip_weakening_m: f64,
    /// CV of the μ field.
    pub mu_cv: f64,
}

/// Stage 1.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SelfWeight {
    /// g (m/s²).
    pub gravity_m_s2: f64,
    /// Dynamic settling or a direct solve.
    pub method: SettleMethod,
    /// D (1/s).
    pub damping_per_s: f64,
    /// Out-of-balance ratio at which the block counts as settled.
    pub settle_tolerance: f64,
    /// Time limit (s).
    pub max_duration_s: f64,
}

/// Quasi-static skip-ahead (see [`SkipAheadSection`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkipAhead {
    /// On or off.
    pub enabled: bool,
    /// Relative tolerance on the leftover motion.
    pub tolerance: f64,
    /// Explicit steps kept before a predicted transition.
    pub margin_steps: u64,
    /// Sampling interval while skipping (s), if coarser than the record interval.
    pub record_interval_s: Option<f64>,
}

/// Stage 2.
#[derive(Clone, Debug, PartialEq)]
pub struct Shear {
    /// D (1/s).
    pub damping_per_s: f64,
    /// u̇f (m/s).
    pub velocity_m_s: f64,
    /// t0 (s).
    pub rise_time_s: f64,
    /// Duration (s).
    pub duration_s: f64,
    /// Driven nodes (canonical ids, sorted, unique).
    pub drivers: Vec<NodeId>,
}

impl Shear {
    /// Driver displacement `u̇f·[t − t0(1 − e^(−t/t0))]` at stage time `t` (Eq. 12 integrated).
    pub fn driver_displacement(&self, t: f64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let t0 = self.rise_time_s;
        if t0 == 0.0 { self.velocity_m_s * t } else { self.velocity_m_s * (t + t0 * (-t / t0).exp_m1()) }
    }

    /// Driver velocity (m/s) at time `t` of the shear stage, the derivative of
    /// [`Shear::driver_displacement`].
    pub fn driver_velocity(&self, t: f64) -> f64 {
        if t <= 0.0 {
            return 0.0;
        }
        let t0 = self.rise_time_s;
        if t0 == 0.0 { self.velocity_m_s } else { -self.velocity_m_s * (-t / t0).exp_m1() }
    }
}

/// One recorded channel at a control node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ControlChannel {
    /// The node.
    pub node: NodeId,
    /// Quantity.
    pub quantity: Kinematic,
    /// Component.
    pub component: Component,
}

/// What to record.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordPlan {
    /// Sampling interval (s); `None` = every step.
    pub interval_s: Option<f64>,
    /// Interface quantities.
    pub interface: Vec<InterfaceQuantity>,
    /// Energy terms.
    pub energy: bool,
    /// Record the settling stage too.
    pub settling: bool,
    /// Record sustained slip onsets.
    pub slip_onsets: bool,
    /// Control channels, sorted and unique.
    pub control: Vec<ControlChannel>,
}

impl RecordPlan {
    /// Whether interface quantity `q` is recorded.
    pub fn has(&self, q: InterfaceQuantity) -> bool {
        self.interface.contains(&q)
    }
}

/// A validated scene, ready to build and run.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// The file it came from (after defaults), for echoing in reports.
    pub file: SceneFile,
    /// Module counts.
    pub dims: Dims,
    /// Module side (m).
    pub lc_m: f64,
    /// Mean Young's modulus (Pa).
    pub young_pa: f64,
    /// Density (kg/m³).
    pub density_kg_m3: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// CV of E.
    pub young_cv: f64,
    /// Friction.
    pub friction: FrictionLaw,
    /// Time step rule.
    pub time_step: TimeStep,
    /// Stage 1.
    pub self_weight: SelfWeight,
    /// Stage 2.
    pub shear: Shear,
    /// Rollers: for every node, which components are held (`[x, y, z]`); only nodes with at
    /// least one, sorted.
    pub fixed: Vec<(NodeId, [bool; 3])>,
    /// Recording.
    pub record: RecordPlan,
    /// Quasi-static skip-ahead.
    pub skip_ahead: SkipAhead,
}

/// Collects every refused field of a scene.
#[derive(Default)]
pub(crate) struct Checker {
    errors: Vec<FieldError>,
}

impl Checker {
    pub(crate) fn push(&mut self, field: impl Into<String>, value: impl ToString, allowed: impl Into<String>) {
        self.errors.push(FieldError { field: field.into(), value: value.to_string(), allowed: allowed.into() });
    }

    /// Accepts finite `v` with `lo (<|≤) v (<|≤) hi`.
    pub(crate) fn range(&mut self, field: &str, v: f64, lo: f64, lo_open: bool, hi: f64, hi_open: bool) -> bool {
        let ok = v.is_finite() && if lo_open { v > lo } else { v >= lo } && if hi_open { v < hi } else { v <= hi };
        if !ok {
            let name = field.rsplit('.').next().unwrap_or(field);
            let lo_s = if lo_open { "<" } else { "≤" };
            let hi_s = if hi_open { "<" } else { "≤" };
            let allowed = if hi.is_infinite() {
                format!("{lo} {lo_s} {name} (finite)")
            } else {
                format!("{lo} {lo_s} {name} {hi_s} {hi}")
            };
            self.push(field, v, allowed);
        }
        ok
    }

    pub(crate) fn positive(&mut self, field: &str, v: f64) -> bool {
        self.range(field, v, 0.0, true, f64::INFINITY, true)
    }

    pub(crate) fn non_negative(&mut self, field: &str, v: f64) -> bool {
        self.range(field, v, 0.0, false, f64::INFINITY, true)
    }

    pub(crate) fn finish(self) -> Result<(), SolverError> {
        if self.errors.is_empty() { Ok(()) } else { Err(SolverError::InvalidScene(self.errors)) }
    }
}

/// Largest node count the solver accepts (node indices are 32-bit).
pub const MAX_NODES: u64 = 1 << 31;

fn check_count(ck: &mut Checker, field: &str, v: i64) -> Option<usize> {
    if (1..=1_000_000).contains(&v) {
        Some(v as usize)
    } else {
        ck.push(field, v, "an integer, 1 ≤ count ≤ 1000000 (a block needs at least one module per axis)");
        None
    }
}

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

impl TryFrom<SceneFile> for Scene {
    type Error = SolverError;

    fn try_from(file: SceneFile) -> Result<Self, SolverError> {
        let mut ck = Checker::default();
        let b = &file.block;
        let nx = check_count(&mut ck, "block.nx", b.nx);
        let ny = check_count(&mut ck, "block.ny", b.ny);
        let nz = check_count(&mut ck, "block.nz", b.nz);
        ck.positive("block.lc_m", b.lc_m);
        let m = &file.material;
        ck.positive("material.young_pa", m.young_pa);
        ck.positive("material.density_kg_m3", m.density_kg_m3);
        ck.range("material.poisson", m.poisson, 0.0, true, 0.5, true);
        ck.range("material.young_cv", m.young_cv, 0.0, false, 1.0, false);
        let f = &file.friction;
        ck.non_negative("friction.mu_static", f.mu_static);
        let mu_dynamic = f.mu_dynamic.unwrap_or(f.mu_static);
        if f.mu_dynamic.is_some() && f.mu_static.is_finite() {
            ck.range("friction.mu_dynamic", mu_dynamic, 0.0, false, f.mu_static.max(0.0), false);
        }
        ck.non_negative("friction.slip_weakening_m", f.slip_weakening_m);
        ck.range("friction.mu_cv", f.mu_cv, 0.0, false, 1.0, false);
        let time_step = match (file.time.dt_fraction, file.time.dt_s) {
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
                ck.range("time.dt_fraction", fr, 0.0, true, 1.0, false);
                TimeStep::Fraction(fr)
            }
        };
        let s = &file.self_weight;
        ck.non_negative("self_weight.gravity_m_s2", s.gravity_m_s2);
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
        if let Some(dt) = file.record.interval_s {
            ck.positive("record.interval_s", dt);
        }
        let sk = &file.skip_ahead;
        ck.range("skip_ahead.tolerance", sk.tolerance, 0.0, true, 0.5, false);
        if !(1..=1_000_000).contains(&sk.margin_steps) {
            ck.push("skip_ahead.margin_steps", sk.margin_steps, "an integer, 1 ≤ margin_steps ≤ 1000000");
        }
        if let Some(iv) = sk.record_interval_s {
            match file.record.interval_s {
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
        // Everything below needs the lattice.
        let (Some(nx), Some(ny), Some(nz)) = (nx, ny, nz) else {
            return Err(ck.finish().expect_err("the counts were refused"));
        };
        let dims = Dims::new(nx, ny, nz);
        let nodes = dims.node_count() as u64;
        if nodes > MAX_NODES {
            ck.push("block", format!("{nx}×{ny}×{nz} modules ({nodes} nodes)"), format!("at most {MAX_NODES} nodes"));
        }
        if !(b.lc_m > 0.0 && b.lc_m.is_finite()) || nodes > MAX_NODES {
            return Err(ck.finish().expect_err("an error was recorded"));
        }
        let lattice = Lattice::new(dims, b.lc_m);
        let (driver_ldem, driver_at): (&[i64], Vec<[f64; 3]>) =
            if sh.driver_nodes.is_empty() && sh.driver_at_m.is_empty() {
                (&[], vec![[0.0, 0.0, 2.0 * b.lc_m]])
            } else {
                (&sh.driver_nodes, sh.driver_at_m.clone())
            };
        let mut drivers =
            resolve_nodes(&mut ck, &lattice, ("shear.driver_nodes", "shear.driver_at_m"), driver_ldem, &driver_at);
        drivers.sort();
        drivers.dedup();
        for d in &drivers {
            if lattice.half_units(*d)[2] == 0 {
                ck.push(
                    "shear.driver",
                    format!("LDEM {} at {:?} m", d.ldem(), lattice.position(*d)),
                    "a node above the base (z > 0): base nodes are held by friction",
                );
            }
        }
        let mut fixed: Vec<(NodeId, [bool; 3])> = Vec::new();
        for (i, bnd) in file.boundary.iter().enumerate() {
            if bnd.fix.is_empty() {
                ck.push(format!("boundary[{i}].fix"), "[]", "at least one of \"x\", \"y\", \"z\"");
            }
            let (axis, at_max) = match bnd.face {
                Face::XMin => (0, false),
                Face::XMax => (0, true),
                Face::YMin => (1, false),
                Face::YMax => (1, true),
                Face::ZMin => (2, false),
                Face::ZMax => (2, true),
            };
            let target = if at_max { 2 * dims.along(axis) } else { 0 };
            for id in (0..lattice.node_count() as u32).map(NodeId) {
                if lattice.half_units(id)[axis] == target {
                    let mut mask = [false; 3];
                    for c in &bnd.fix {
                        mask[c.axis()] = true;
                    }
                    fixed.push((id, mask));
                }
            }
        }
        fixed.sort_by_key(|(id, _)| *id);
        let mut merged: Vec<(NodeId, [bool; 3])> = Vec::new();
        for (id, mask) in fixed {
            match merged.last_mut() {
                Some((last, m)) if *last == id => (0..3).for_each(|a| m[a] |= mask[a]),
                _ => merged.push((id, mask)),
            }
        }
        for d in &drivers {
            if let Ok(i) = merged.binary_search_by_key(d, |(id, _)| *id)
                && merged[i].1[0]
            {
                ck.push("shear.driver", format!("LDEM {}", d.ldem()), "a node whose x is not held by a [[boundary]]");
            }
        }
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
            let names = (format!("{field}nodes"), format!("{field}at_m"));
            let mut nodes = resolve_nodes(&mut ck, &lattice, (&names.0, &names.1), &c.nodes, &c.at_m);
            if let Some(set) = c.set {
                nodes.extend(set.nodes(&lattice));
            }
            for node in nodes {
                for &quantity in &c.quantities {
                    for &component in &c.components {
                        control.push(ControlChannel { node, quantity, component });
                    }
                }
            }
        }
        control.sort();
        control.dedup();
        let mut interface = file.record.interface.clone();
        interface.dedup();
        ck.finish()?;
        Ok(Scene {
            dims,
            lc_m: b.lc_m,
            young_pa: m.young_pa,
            density_kg_m3: m.density_kg_m3,
            poisson: m.poisson,
            young_cv: m.young_cv,
            friction: FrictionLaw {
                mu_static: f.mu_static,
                mu_dynamic,
                slip_weakening_m: f.slip_weakening_m,
                mu_cv: f.mu_cv,
            },
            time_step,
            self_weight: SelfWeight {
                gravity_m_s2: s.gravity_m_s2,
                method: s.method,
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
            fixed: merged,
            record: RecordPlan {
                interval_s: file.record.interval_s,
                interface,
                energy: file.record.energy,
                settling: file.record.settling,
                slip_onsets: file.record.slip_onsets,
                control,
            },
            skip_ahead: SkipAhead {
                enabled: sk.enabled,
                tolerance: sk.tolerance,
                margin_steps: sk.margin_steps.max(1) as u64,
                record_interval_s: sk.record_interval_s,
            },
            file,
        })
    }
}

impl Scene {
    /// Parses and validates a scene from TOML text.
    pub fn from_toml(text: &str) -> Result<Scene, SolverError> {
        let file: SceneFile = toml::from_str(text).map_err(|e| SolverError::Syntax(e.to_string()))?;
        Scene::try_from(file)
    }

    /// The paper scene of SPEC §6 (all defaults).
    pub fn paper() -> Scene {
        Scene::try_from(SceneFile::default()).expect("the default scene is valid")
    }

    /// The lattice of this scene.
    pub fn lattice(&self) -> Lattice {
        Lattice::new(self.dims, self.lc_m)
    }

    /// P-wave speed `√(C11/ρ)` of the unbounded lattice (m/s).
    pub fn p_wave_speed(&self) -> f64 {
        let (c11, _, _) = crate::material::lattice_elastic_constants(self.young_pa, self.poisson);
        (c11 / self.density_kg_m3).sqrt()
    }

    /// The paper's bound `0.6·Lc/Cp` (Eq. 5) in seconds, for comparison with the true one.
    pub fn paper_time_step_bound(&self) -> f64 {
        0.6 * self.lc_m / self.p_wave_speed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_scene_is_the_paper_block() {
        let s = Scene::paper();
        assert_eq!(s.dims, Dims::new(10, 1, 5));
        let l = s.lattice();
        assert_eq!(s.shear.drivers, vec![l.node_at([0.0, 0.0, 0.2]).unwrap()]);
    }

    #[test]
    fn refusals_name_field_value_and_range() {
        let err = Scene::from_toml("[material]\npoisson = 0.5\nyoung_pa = -1.0").unwrap_err().to_string();
        assert!(err.contains("material.poisson = 0.5"), "{err}");
        assert!(err.contains("0 < poisson < 0.5"), "{err}");
        assert!(err.contains("material.young_pa = -1"), "{err}");
        let err = Scene::from_toml("[block]\nnx = 0").unwrap_err().to_string();
        assert!(err.contains("block.nx = 0"), "{err}");
        let err = Scene::from_toml("[shear]\ndriver_at_m = [[5.0, 0.0, 0.2]]").unwrap_err().to_string();
        assert!(err.contains("shear.driver_at_m[0]"), "{err}");
    }

    #[test]
    fn driver_displacement_integrates_eq_12() {
        let s = Scene::paper().shear;
        let (t, h) = (0.01, 1e-7);
        let v = (s.driver_displacement(t + h) - s.driver_displacement(t - h)) / (2.0 * h);
        let expected = s.velocity_m_s * (1.0 - (-t / s.rise_time_s).exp());
        assert!((v - expected).abs() < 1e-9 * s.velocity_m_s.max(1.0));
    }
}
