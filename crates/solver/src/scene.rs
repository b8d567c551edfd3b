//! A validated scene: the physics of one run in plain Rust types (docs/model.md §1–§6).
//!
//! A scene is the block, its material and friction, the time-step rule, the two loading stages,
//! the rollers and what to record. It is built and checked by the configuration crate from a
//! pipeline file (where every field has a documented default); here it is plain data the solver
//! trusts. [`Scene::paper`] is the paper's scene (docs/model.md §6), the reference the tests and
//! benchmarks start from.

use crate::dispersion::{DispersionError, LatticeMaterial, UsableBand, usable_band};
use crate::fault::Fault;
use crate::geometry::{Dims, Face, Lattice, NodeId};
use crate::laws::{Coulomb, FrictionLaw, FrictionMap, NodeFriction};
use crate::medium::{Profile, Zone};
use crate::rupture::Rupture;

/// How Δt is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TimeStep {
    /// A fraction of the critical step of each seed's lattice.
    Fraction(f64),
    /// A fixed step in seconds (must be below every seed's critical step).
    Fixed(f64),
}

/// How the self-weight stage reaches equilibrium.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, bincode::Encode, bincode::Decode)]
pub enum SettleMethod {
    /// Heavy damping until the out-of-balance force is small (the paper's way).
    #[default]
    Dynamic,
    /// Solve `K·u = weight` directly with every base node held where it stands (conjugate
    /// gradients); falls back to `Dynamic` when that equilibrium is not admissible (a base node
    /// would pull on the base or its friction would not hold it).
    Static,
}

impl SettleMethod {
    /// Every method.
    pub const ALL: [SettleMethod; 2] = [SettleMethod::Dynamic, SettleMethod::Static];

    /// Name as written in pipeline files and tables.
    pub fn name(self) -> &'static str {
        match self {
            SettleMethod::Dynamic => "dynamic",
            SettleMethod::Static => "static",
        }
    }
}

/// Friction of the base: the law, its map, and the Weibull field on its coefficients.
#[derive(Clone, Debug, PartialEq)]
pub struct Friction {
    /// The law of the background (coefficients scaled by the node's field factor).
    pub law: FrictionLaw,
    /// Coefficient of variation of the Weibull field on μ (per contact node, its own random
    /// stream); 0 = uniform.
    pub mu_cv: f64,
    /// Regions of the base with their own μs, μd and Dc (patches, a grid); `None` = the law
    /// everywhere.
    pub map: Option<FrictionMap>,
    /// Whether a node that sticks heals to μs (the paper's cycles) or keeps its slip (the
    /// dynamic-rupture benchmarks' slip weakening, over the whole run).
    pub heals: bool,
}

impl Friction {
    /// Coefficients of contact node `c` (canonical contact order) before the field factor.
    pub fn base(&self, c: usize) -> NodeFriction {
        match &self.map {
            Some(map) => map.nodes[c],
            None => self.law.node(1.0),
        }
    }
}

/// Loading stage 1: gravity with heavy damping until static equilibrium (docs/model.md §5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SelfWeight {
    /// g (m/s²), acting in −z in both stages.
    pub gravity_m_s2: f64,
    /// Dynamic settling or a direct solve.
    pub method: SettleMethod,
    /// Mass-proportional damping D (1/s) while settling.
    pub damping_per_s: f64,
    /// Out-of-balance force over weight at which the block counts as settled.
    pub settle_tolerance: f64,
    /// Time limit (s).
    pub max_duration_s: f64,
}

/// One boundary condition of a scene as validated (docs/model.md §5, §12): what a kind of the
/// solver's [`crate::boundary`] is built from.
#[derive(Clone, Debug, PartialEq)]
pub enum BoundarySpec {
    /// Rollers: for every node, which components are held (`[x, y, z]`); only nodes with at
    /// least one, sorted.
    Rollers(Vec<(NodeId, [bool; 3])>),
    /// Driven nodes (canonical ids, sorted, unique) whose x follows the shear stage's Eq. 12.
    Drivers(Vec<NodeId>),
    /// A loading plate on springs, moving by Eq. 12.
    Plate(LoadingPlate),
    /// A normal pressure on the top face.
    Pressure(NormalLoad),
    /// Faces whose nodes carry Lysmer–Kuhlemeyer dashpots, so that waves leave the block; never
    /// the base.
    Absorbing(Vec<Face>),
}

/// Loading stage 2: the driver of Eq. 12 with light damping (docs/model.md §5).
#[derive(Clone, Debug, PartialEq)]
pub struct Shear {
    /// Mass-proportional damping D (1/s) while shearing.
    pub damping_per_s: f64,
    /// Final driver velocity u̇f (m/s, +x).
    pub velocity_m_s: f64,
    /// Rise time t0 of Eq. 12 (s); 0 = a velocity step.
    pub rise_time_s: f64,
    /// Duration of the stage (s).
    pub duration_s: f64,
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

/// Compliant loading (docs/model.md §5): the nodes of a face tied by springs in x to a rigid
/// plate that moves by Eq. 12 (the driver law of [`Shear`]) from the start of the shear stage —
/// the spring-block (Burridge–Knopoff) loading. Each spring pulls its node with
/// `k_i·(x_plate + x_i⁰ − x_i)`, `x_i⁰` the node's x when shearing starts.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadingPlate {
    /// The face the springs hold.
    pub face: Face,
    /// Attached nodes (canonical ids, sorted).
    pub nodes: Vec<NodeId>,
    /// Spring stiffness of each attached node in x (N/m), order of `nodes`.
    pub stiffness_n_m: Vec<f64>,
}

impl LoadingPlate {
    /// Total stiffness of the springs (N/m).
    pub fn stiffness(&self) -> f64 {
        self.stiffness_n_m.iter().sum()
    }
}

/// A constant normal pressure on the top face, pressing the block onto the base: forces in −z on
/// the top face's nodes in proportion to their share of its area, in both stages (like gravity).
#[derive(Clone, Debug, PartialEq)]
pub struct NormalLoad {
    /// Pressure (Pa).
    pub pressure_pa: f64,
    /// Loaded nodes (canonical ids, sorted).
    pub nodes: Vec<NodeId>,
    /// Force of each in −z (N), order of `nodes`.
    pub force_n: Vec<f64>,
}

impl NormalLoad {
    /// The pressure `pressure_pa` on the top face of `lattice`.
    pub fn on_top(lattice: &Lattice, pressure_pa: f64) -> NormalLoad {
        let nodes = Face::ZMax.nodes(lattice);
        let force_n = nodes.iter().map(|&id| pressure_pa * Face::ZMax.tributary_area(lattice, id)).collect();
        NormalLoad { pressure_pa, nodes, force_n }
    }

    /// Total force (N).
    pub fn total(&self) -> f64 {
        self.force_n.iter().sum()
    }
}

/// Quasi-static skip-ahead through the interseismic phase of the shear stage (see
/// [`crate::quasistatic`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkipAhead {
    /// On or off.
    pub enabled: bool,
    /// Largest change the leftover motion may make to a base node's margin to its next
    /// transition, as a fraction of that margin.
    pub tolerance: f64,
    /// Explicit steps kept before a predicted transition.
    pub margin_steps: u64,
    /// Sampling interval while skipping (s), if coarser than the record interval.
    pub record_interval_s: Option<f64>,
}

/// A displacement component.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, bincode::Encode, bincode::Decode)]
pub enum Component {
    /// x (slip direction).
    X,
    /// y (width).
    Y,
    /// z (vertical).
    Z,
}

impl Component {
    /// Every component.
    pub const ALL: [Component; 3] = [Component::X, Component::Y, Component::Z];

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

/// Interface quantities a scene can record.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
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

    /// Name as written in pipeline files.
    pub fn name(self) -> &'static str {
        match self {
            InterfaceQuantity::ShearStress => "shear_stress",
            InterfaceQuantity::NormalStress => "normal_stress",
            InterfaceQuantity::MeanSlip => "mean_slip",
            InterfaceQuantity::SlipRate => "slip_rate",
            InterfaceQuantity::SlippingNodes => "slipping_nodes",
            InterfaceQuantity::LiftedNodes => "lifted_nodes",
            InterfaceQuantity::Driver => "driver",
        }
    }
}

/// Kinematic quantities recorded at control nodes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, bincode::Encode, bincode::Decode)]
pub enum Kinematic {
    /// Displacement (m).
    Displacement,
    /// Velocity (m/s).
    Velocity,
    /// Acceleration (m/s²).
    Acceleration,
}

impl Kinematic {
    /// Every quantity.
    pub const ALL: [Kinematic; 3] = [Kinematic::Displacement, Kinematic::Velocity, Kinematic::Acceleration];

    /// Name as written in pipeline files.
    pub fn name(self) -> &'static str {
        match self {
            Kinematic::Displacement => "displacement",
            Kinematic::Velocity => "velocity",
            Kinematic::Acceleration => "acceleration",
        }
    }

    /// Name with unit, as used in column names.
    pub fn column(self) -> &'static str {
        match self {
            Kinematic::Displacement => "displacement_m",
            Kinematic::Velocity => "velocity_m_s",
            Kinematic::Acceleration => "acceleration_m_s2",
        }
    }
}

/// One recorded channel at a control node.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, bincode::Encode, bincode::Decode)]
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
    /// The records are resampled to exactly `interval_s` (the pipeline processes accelerograms),
    /// so it may be no finer than half a step (refused before the run,
    /// [`crate::run::check_record_interval`]); otherwise a finer interval samples every step.
    pub resampled: bool,
    /// Interface quantities.
    pub interface: Vec<InterfaceQuantity>,
    /// Energy terms.
    pub energy: bool,
    /// Record the settling stage too.
    pub settling: bool,
    /// Record sustained slip onsets.
    pub slip_onsets: bool,
    /// Record every contact node's slip, slip rate and stresses with the event trace
    /// ([`crate::trace::FaultTrace`]).
    pub fault: bool,
    /// Fault stations: contact nodes whose slip, slip rate and stresses along x and y are kept at
    /// the trace's instants ([`crate::trace::StationTrace`]) and written as station files.
    pub fault_stations: Vec<NodeId>,
    /// Interval of the fault's written instants (s); `None` = every trace instant.
    pub fault_interval_s: Option<f64>,
    /// Control channels, sorted and unique.
    pub control: Vec<ControlChannel>,
    /// The event trace, kept whatever the interval (docs/model.md §7).
    pub trace: TracePlan,
}

impl RecordPlan {
    /// Whether interface quantity `q` is recorded.
    pub fn has(&self, q: InterfaceQuantity) -> bool {
        self.interface.contains(&q)
    }
}

/// What the event trace keeps ([`crate::trace`]; the validated form of what the pipeline's
/// `[events]` need).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TracePlan {
    /// A step is hot when `|mean slip rate| ≥` this (m/s).
    pub hot_rate_m_s: f64,
    /// Steps within this time of a hot step are kept (s).
    pub margin_s: f64,
    /// Between bursts, one step in this interval is kept (s).
    pub quiet_interval_s: f64,
    /// A contact node has ruptured once its slip rate reaches this (m/s): the rupture time of
    /// the fault summary of a fault (docs/model.md §15).
    pub rupture_rate_m_s: f64,
}

impl Default for TracePlan {
    /// The plan for the default detector (1-ms smoothing, 50 µm/s quiet threshold).
    fn default() -> Self {
        TracePlan { hot_rate_m_s: 2.5e-5, margin_s: 2.5e-3, quiet_interval_s: 2.5e-4, rupture_rate_m_s: 1e-3 }
    }
}

/// A validated scene, ready to build and run.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Module counts.
    pub dims: Dims,
    /// Module side Lc (m).
    pub lc_m: f64,
    /// Mean Young's modulus (Pa).
    pub young_pa: f64,
    /// Density (kg/m³).
    pub density_kg_m3: f64,
    /// Poisson's ratio.
    pub poisson: f64,
    /// Coefficient of variation of the Weibull field on E; 0 = homogeneous.
    pub young_cv: f64,
    /// Friction of the base.
    pub friction: Friction,
    /// Time step rule.
    pub time_step: TimeStep,
    /// Stage 1.
    pub self_weight: SelfWeight,
    /// Stage 2.
    pub shear: Shear,
    /// Boundary conditions: at most one of each kind (a fault's initial tractions are the
    /// fault's); read them with [`Scene::fixed`], [`Scene::drivers`], [`Scene::plate`],
    /// [`Scene::normal_load`] and [`Scene::absorbing`], set one with [`Scene::set_boundary`].
    pub boundaries: Vec<BoundarySpec>,
    /// Recording.
    pub record: RecordPlan,
    /// Quasi-static skip-ahead.
    pub skip_ahead: SkipAhead,
    /// Bars that crack (the bilinear law of docs/model.md §11); `None`: every bar elastic.
    pub rupture: Option<Rupture>,
    /// The base face as one side of a planar fault between identical media, with its tractions
    /// (docs/model.md §15); `None`: the paper's rigid base.
    pub fault: Option<Fault>,
    /// Named stations: nodes whose displacement, velocity and acceleration (three components)
    /// are recorded (as control channels of `record.control`), sorted by node.
    pub stations: Vec<Station>,
    /// The medium: layers, Q and Kelvin–Voigt damping (docs/model.md §18); the default is the
    /// homogeneous elastic material above.
    pub medium: crate::medium::Medium,
}

/// A named station: a corner node whose motion is recorded in full.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Station {
    /// Name (unique in the scene).
    pub name: String,
    /// The node.
    pub node: NodeId,
}

impl Scene {
    /// The paper's scene (docs/model.md §6): 10×1×5 modules of 0.1 m, E = 2e10 Pa (Weibull CV 5%),
    /// ρ = 2400 kg/m³, ν = 0.2, the plain Coulomb law μ = 5, Δt = 0.5 of critical, damped settling
    /// (D = 2500/s), then shear by the node at (0, 0, 0.2) m at 1.1e-4 m/s (t0 = 2 ms, D = 400/s)
    /// for 0.32 s, every interface quantity recorded at every step. The pipeline files' defaults
    /// build exactly this scene (a configuration test checks it).
    pub fn paper() -> Scene {
        let dims = Dims::new(10, 1, 5);
        let lattice = Lattice::new(dims, 0.1);
        Scene {
            dims,
            lc_m: 0.1,
            young_pa: 2.0e10,
            density_kg_m3: 2400.0,
            poisson: 0.2,
            young_cv: 0.05,
            friction: Friction { law: Coulomb { mu: 5.0 }.into(), mu_cv: 0.0, map: None, heals: true },
            time_step: TimeStep::Fraction(0.5),
            self_weight: SelfWeight {
                gravity_m_s2: 9.81,
                method: SettleMethod::Dynamic,
                damping_per_s: 2500.0,
                settle_tolerance: 1e-6,
                max_duration_s: 0.1,
            },
            shear: Shear { damping_per_s: 400.0, velocity_m_s: 1.1e-4, rise_time_s: 0.002, duration_s: 0.32 },
            boundaries: vec![BoundarySpec::Drivers(vec![
                lattice.node_at([0.0, 0.0, 0.2]).expect("the paper's driver node"),
            ])],
            record: RecordPlan {
                interval_s: None,
                resampled: false,
                interface: InterfaceQuantity::ALL.to_vec(),
                energy: false,
                settling: false,
                slip_onsets: false,
                fault: false,
                fault_stations: Vec::new(),
                fault_interval_s: None,
                control: Vec::new(),
                trace: TracePlan::default(),
            },
            skip_ahead: SkipAhead { enabled: false, tolerance: 1e-4, margin_steps: 20, record_interval_s: None },
            rupture: None,
            fault: None,
            stations: Vec::new(),
            medium: crate::medium::Medium::default(),
        }
    }

    /// A block of `dims` modules of this scene's module side and material (mean modulus, density,
    /// Poisson's ratio, Weibull field), with nothing else: no drivers, rollers, plate, load or
    /// records (a sample for static solves of a block too large to solve whole).
    pub fn sample(&self, dims: Dims) -> Scene {
        let mut s = Scene::paper();
        s.dims = dims;
        s.lc_m = self.lc_m;
        s.young_pa = self.young_pa;
        s.density_kg_m3 = self.density_kg_m3;
        s.poisson = self.poisson;
        s.young_cv = self.young_cv;
        s.boundaries.clear();
        s.record.interface.clear();
        s
    }

    /// The rollers: for every node, which components are held (`[x, y, z]`); only nodes with
    /// at least one, sorted.
    pub fn fixed(&self) -> &[(NodeId, [bool; 3])] {
        self.boundaries
            .iter()
            .find_map(|b| if let BoundarySpec::Rollers(r) = b { Some(&r[..]) } else { None })
            .unwrap_or(&[])
    }

    /// The driven nodes of the shear stage (canonical ids, sorted, unique).
    pub fn drivers(&self) -> &[NodeId] {
        self.boundaries
            .iter()
            .find_map(|b| if let BoundarySpec::Drivers(d) = b { Some(&d[..]) } else { None })
            .unwrap_or(&[])
    }

    /// The loading plate on springs, besides (or instead of) the drivers.
    pub fn plate(&self) -> Option<&LoadingPlate> {
        self.boundaries.iter().find_map(|b| if let BoundarySpec::Plate(p) = b { Some(p) } else { None })
    }

    /// The normal pressure on the top face.
    pub fn normal_load(&self) -> Option<&NormalLoad> {
        self.boundaries.iter().find_map(|b| if let BoundarySpec::Pressure(n) = b { Some(n) } else { None })
    }

    /// The faces whose nodes carry Lysmer–Kuhlemeyer dashpots ([`crate::boundary::absorbing`]).
    pub fn absorbing(&self) -> &[Face] {
        self.boundaries
            .iter()
            .find_map(|b| if let BoundarySpec::Absorbing(a) = b { Some(&a[..]) } else { None })
            .unwrap_or(&[])
    }

    /// Sets the scene's boundary of `spec`'s kind to `spec` (in place of one it had).
    pub fn set_boundary(&mut self, spec: BoundarySpec) {
        let kind = std::mem::discriminant(&spec);
        match self.boundaries.iter_mut().find(|b| std::mem::discriminant(*b) == kind) {
            Some(b) => *b = spec,
            None => self.boundaries.push(spec),
        }
    }

    /// Whether the base face is one side of a fault between identical media (docs/model.md §15)
    /// rather than the paper's rigid base.
    pub fn is_fault(&self) -> bool {
        self.fault.is_some()
    }

    /// Whether a moving driver loads the block in the shear stage: driven nodes or a loading
    /// plate, moving at a positive speed. A fault scene without either (TPV5) is loaded only by
    /// its fixed initial tractions.
    pub fn is_driven(&self) -> bool {
        (!self.drivers().is_empty() || self.plate().is_some()) && self.shear.velocity_m_s > 0.0
    }

    /// Slip across the base face per unit of its tangential displacement: 2 on a symmetric
    /// fault (the other side moves the opposite way), 1 on the rigid base.
    pub fn slip_factor(&self) -> f64 {
        if self.is_fault() { 2.0 } else { 1.0 }
    }

    /// How many copies of the modelled fault the whole fault is: 2 for each face across the
    /// fault (`y = 0`, `y = max`) whose every base node is held in y on a fault scene — a rigid
    /// frictionless wall, which is a mirror plane of the displacement field, so the block is one
    /// half of a scene symmetric about it (TPV101's below its hypocentre). 1 otherwise.
    pub fn fault_copies(&self) -> f64 {
        if !self.is_fault() {
            return 1.0;
        }
        let lattice = self.lattice();
        let held: std::collections::HashSet<NodeId> =
            self.fixed().iter().filter(|(_, mask)| mask[1]).map(|(id, _)| *id).collect();
        let contact = lattice.contact_nodes();
        let mirror = |row: usize| {
            let mut on = contact.iter().filter(|&&id| lattice.half_units(id)[1] == row).peekable();
            on.peek().is_some() && on.all(|id| held.contains(id))
        };
        let mut copies = 1.0;
        for row in [0, 2 * self.dims.ny] {
            if mirror(row) {
                copies *= 2.0;
            }
        }
        copies
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

    /// S-wave speed `√(C44/ρ)` of the unbounded lattice (m/s).
    pub fn s_wave_speed(&self) -> f64 {
        let (_, _, c44) = crate::material::lattice_elastic_constants(self.young_pa, self.poisson);
        (c44 / self.density_kg_m3).sqrt()
    }

    /// The paper's bound `0.6·Lc/Cp` (Eq. 5) in seconds, for comparison with the true one.
    pub fn paper_time_step_bound(&self) -> f64 {
        0.6 * self.lc_m / self.p_wave_speed()
    }

    /// The usable band of the homogeneous lattice of this scene (mean Young's modulus): the
    /// highest frequency whose plane waves travel within `tolerance` of the long-wave speeds
    /// ([`crate::dispersion::usable_band`], docs/model.md §8).
    ///
    /// In a layered medium, the band where the lattice is slowest ([`Scene::slowest_carried`]).
    pub fn usable_band(&self, tolerance: f64) -> Result<UsableBand, DispersionError> {
        self.zone_band(&self.slowest_carried(), tolerance)
    }

    /// The slowest medium the lattice carries, as a zone: without a profile the block's; with one,
    /// the slowest `√(mean E/mean ρ)` over a module's depth (windows one module deep, every half
    /// module down the block), what a bar and its nodes hold where layers are thinner than a module.
    pub fn slowest_carried(&self) -> Zone {
        let zones = self.zones();
        let Some(p) = &self.medium.profile else { return zones[0].clone() };
        let depth = self.lattice().extent()[p.depth_axis()];
        let mut slowest: Option<Zone> = None;
        let mut top = 0.0;
        while top < depth {
            let young = p.mean_over(top, top + self.lc_m, |i| zones[i].young);
            let density = p.mean_over(top, top + self.lc_m, |i| zones[i].density);
            let ratio = (young / density).sqrt();
            if slowest.as_ref().is_none_or(|z| ratio < (z.young / z.density).sqrt()) {
                let vs = zones[0].vs_m_s / (zones[0].young / zones[0].density).sqrt() * ratio;
                let vp = zones[0].vp_m_s / zones[0].vs_m_s * vs;
                slowest = Some(Zone { young, density, vs_m_s: vs, vp_m_s: vp, relaxation: None });
            }
            top += 0.5 * self.lc_m;
        }
        slowest.unwrap_or_else(|| zones[0].clone())
    }

    /// The usable band of one zone of the medium ([`Scene::zones`]).
    pub fn zone_band(&self, zone: &Zone, tolerance: f64) -> Result<UsableBand, DispersionError> {
        let m = LatticeMaterial::new(
            self.young_pa * zone.young,
            self.poisson,
            self.density_kg_m3 * zone.density,
            self.lc_m,
        )?;
        usable_band(&m, tolerance)
    }

    /// The zones of the medium: one per layer of its profile, or the homogeneous block
    /// (docs/model.md §18).
    pub fn zones(&self) -> Vec<Zone> {
        self.medium.zones(self.young_pa, self.density_kg_m3, self.poisson)
    }

    /// Depth below the medium's surface of a point (m; 0 without a profile).
    pub fn depth_of(&self, p: [f64; 3]) -> f64 {
        self.medium.depth(p, self.lattice().extent())
    }

    /// V_S30 of the profile (m/s) when the scene has one: every surface station's site, and the
    /// reference site of the lattice's part of a broadband record (as the Broadband Platform takes
    /// its 1D model's V_S30 for its low-frequency part: below 1 Hz the top tens of metres the
    /// lattice averages away change the motion little, the deeper crust it carries does).
    pub fn site_vs30_m_s(&self) -> Option<f64> {
        self.medium.profile.as_ref().map(Profile::vs30)
    }

    /// The S-wave speed the lattice carries at its surface (m/s): the scene's without a profile,
    /// else the travel-time mean over the top module (`Lc / ∫ dz/Vs`), what a station on the
    /// lattice stands on.
    pub fn lattice_surface_vs_m_s(&self) -> f64 {
        match &self.medium.profile {
            None => self.s_wave_speed(),
            Some(p) => 1.0 / p.mean_over(0.0, self.lc_m, |i| 1.0 / p.layers[i].vs_m_s),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_scene_is_the_paper_block() {
        let s = Scene::paper();
        assert_eq!(s.dims, Dims::new(10, 1, 5));
        assert_eq!(s.drivers()[0].ldem(), 45);
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
