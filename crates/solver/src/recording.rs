//! Recording: only the channels a scene asks for, at its interval, as plain arrays.
//!
//! "Recording" here is always the solver's sampled output of a run ([`Recording`]); accelerogram
//! files are the seismology crate's.

use crate::geometry::NodeId;
use crate::observe::Observed;
use crate::scene::{ControlChannel, InterfaceQuantity, RecordPlan, Scene};
use crate::step::rupture::CrackKind;
use crate::trace::{Trace, Tracer};

/// A recorded scalar channel (the name carries the unit).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, bincode::Encode, bincode::Decode)]
pub enum Channel {
    /// τ = −ΣF_x/A (Pa), positive when the base resists the push.
    ShearStress,
    /// σ = ΣN/A (Pa).
    NormalStress,
    /// δ, mean x-displacement of the contact nodes (m).
    MeanSlip,
    /// Mean x-velocity of the contact nodes (m/s).
    MeanSlipRate,
    /// Max x-velocity of the contact nodes (m/s).
    MaxSlipRate,
    /// Sliding contact nodes (count).
    SlippingNodes,
    /// Lifted contact nodes (count).
    LiftedNodes,
    /// Total driver reaction in x (N).
    DriverForce,
    /// Imposed driver displacement (m).
    DriverDisplacement,
    /// Kinetic energy (J).
    Kinetic,
    /// Strain energy (J).
    Elastic,
    /// Dissipated by damping since the start (J).
    DampingDissipated,
    /// Dissipated by friction since the start (J).
    FrictionDissipated,
    /// Lost in landings since the start (J).
    ImpactDissipated,
    /// Dissipated by bars that crack since the start (J); recorded only when the scene's bars
    /// crack.
    FractureDissipated,
    /// Carried out through the absorbing faces since the start (J); recorded only when the scene
    /// has absorbing faces.
    Absorbed,
    /// Work of gravity and body forces since the start (J).
    BodyWork,
    /// Work of the drivers since the start (J).
    DriverWork,
    /// Work of a fault's initial tractions since the start (J); recorded only on a fault.
    TractionWork,
    /// Body plus driver work (J).
    ExternalWork,
    /// External work minus stored and dissipated energy (J); zero up to round-off.
    EnergyResidual,
}

impl Channel {
    /// Every channel.
    pub const ALL: [Channel; 21] = [
        Channel::ShearStress,
        Channel::NormalStress,
        Channel::MeanSlip,
        Channel::MeanSlipRate,
        Channel::MaxSlipRate,
        Channel::SlippingNodes,
        Channel::LiftedNodes,
        Channel::DriverForce,
        Channel::DriverDisplacement,
        Channel::Kinetic,
        Channel::Elastic,
        Channel::DampingDissipated,
        Channel::FrictionDissipated,
        Channel::ImpactDissipated,
        Channel::FractureDissipated,
        Channel::Absorbed,
        Channel::BodyWork,
        Channel::DriverWork,
        Channel::TractionWork,
        Channel::ExternalWork,
        Channel::EnergyResidual,
    ];

    /// Column name with unit.
    pub fn name(self) -> &'static str {
        match self {
            Channel::ShearStress => "shear_stress_pa",
            Channel::NormalStress => "normal_stress_pa",
            Channel::MeanSlip => "mean_slip_m",
            Channel::MeanSlipRate => "mean_slip_rate_m_s",
            Channel::MaxSlipRate => "max_slip_rate_m_s",
            Channel::SlippingNodes => "slipping_nodes",
            Channel::LiftedNodes => "lifted_nodes",
            Channel::DriverForce => "driver_force_n",
            Channel::DriverDisplacement => "driver_displacement_m",
            Channel::Kinetic => "kinetic_energy_j",
            Channel::Elastic => "elastic_energy_j",
            Channel::DampingDissipated => "damping_dissipated_j",
            Channel::FrictionDissipated => "friction_dissipated_j",
            Channel::ImpactDissipated => "impact_dissipated_j",
            Channel::FractureDissipated => "fracture_dissipated_j",
            Channel::Absorbed => "absorbed_j",
            Channel::BodyWork => "body_work_j",
            Channel::DriverWork => "driver_work_j",
            Channel::TractionWork => "traction_work_j",
            Channel::ExternalWork => "external_work_j",
            Channel::EnergyResidual => "energy_residual_j",
        }
    }

    /// Whether the channel counts nodes (an integer).
    pub fn is_count(self) -> bool {
        matches!(self, Channel::SlippingNodes | Channel::LiftedNodes)
    }

    /// The energy channels, in order (the last twelve of [`Channel::ALL`]).
    pub const ENERGY: &[Channel] = Channel::ALL.split_at(9).1;

    /// Channels of `scene`'s record plan, in a fixed order: an energy term that the scene cannot
    /// have is no column (fracture without bars that crack, absorbed without absorbing faces,
    /// traction work without a fault).
    pub fn of_scene(scene: &Scene) -> Vec<Channel> {
        let plan = &scene.record;
        let has = |c: Channel| match c {
            Channel::FractureDissipated => scene.rupture.is_some(),
            Channel::Absorbed => !scene.absorbing().is_empty(),
            Channel::TractionWork => scene.is_fault(),
            _ => true,
        };
        let mut out = Vec::new();
        for q in InterfaceQuantity::ALL {
            if !plan.has(q) {
                continue;
            }
            out.extend_from_slice(match q {
                InterfaceQuantity::ShearStress => &[Channel::ShearStress][..],
                InterfaceQuantity::NormalStress => &[Channel::NormalStress],
                InterfaceQuantity::MeanSlip => &[Channel::MeanSlip],
                InterfaceQuantity::SlipRate => &[Channel::MeanSlipRate, Channel::MaxSlipRate],
                InterfaceQuantity::SlippingNodes => &[Channel::SlippingNodes],
                InterfaceQuantity::LiftedNodes => &[Channel::LiftedNodes],
                InterfaceQuantity::Driver => &[Channel::DriverForce, Channel::DriverDisplacement],
            });
        }
        if plan.energy {
            out.extend(Channel::ENERGY.iter().copied().filter(|&c| has(c)));
        }
        out
    }
}

/// How a recording was sampled.
#[derive(Clone, Copy, Debug, Default, PartialEq, bincode::Encode, bincode::Decode)]
pub struct Sampling {
    /// Time step of the run (s).
    pub step_s: f64,
    /// Steps between two samples of the shear stage: `record.interval_s / Δt` rounded (1 = every
    /// step); the interval recorded is `stride·Δt`.
    pub stride: u64,
    /// Index of the first sample of the shear stage (the samples before it, if the self-weight
    /// stage was recorded, are every step at negative times).
    pub shear_start: usize,
    /// Whether every shear-stage sample is `stride` steps after the one before. Not so when the
    /// skip-ahead samples quiet phases more sparsely.
    pub uniform: bool,
}

impl Sampling {
    /// The sampling interval of the shear stage, `stride·Δt` (s).
    pub fn interval_s(&self) -> f64 {
        self.stride as f64 * self.step_s
    }
}

/// The recorded series of one run.
#[derive(Clone, Debug, Default, PartialEq, bincode::Encode, bincode::Decode)]
pub struct Recording {
    /// Time since the start of the shear stage (s); negative in the self-weight stage.
    pub time_s: Vec<f64>,
    /// Scalar channels, each as long as `time_s`.
    pub channels: Vec<(Channel, Vec<f64>)>,
    /// Control-node channels, each as long as `time_s`.
    pub control: Vec<(ControlChannel, Vec<f64>)>,
    /// Sustained slip onsets `(time_s, contact node)`, in time order (if recorded).
    pub onsets: Vec<(f64, NodeId)>,
    /// Quasi-static skips of the shear stage (with `[skip_ahead]` on), in time order.
    pub skips: Vec<Skip>,
    /// Bars that started softening or broke (when the scene's bars crack), in time order, both
    /// loading stages (self-weight at negative times).
    pub cracks: Vec<Crack>,
    /// How the samples were taken.
    pub sampling: Sampling,
    /// The shear stage's interface signals at the solver's own steps around every burst of slip
    /// (whatever the interval): what events are measured on.
    pub trace: Trace,
}

/// One bar passing its peak or breaking (docs/model.md §11).
#[derive(Clone, Copy, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct Crack {
    /// Time since the start of the shear stage (s).
    pub time_s: f64,
    /// Canonical bar index (docs/model.md §10.5).
    pub bar: u32,
    /// Softening or breaking.
    pub kind: CrackKind,
    /// The bar's axial strain then (at or just past `εp` or `εr`).
    pub strain: f64,
    /// Energy: for a softening, the strain energy the bar held at its peak, `½·EA·εp²·L`; for a
    /// break, the fracture energy it dissipated, `Gf·A_f = ½·EA·εp·εr·L` (J).
    pub energy_j: f64,
}

/// What ends a quasi-static skip: the transition predicted next.
#[derive(Clone, Copy, Debug, PartialEq, Eq, bincode::Encode, bincode::Decode)]
pub enum Transition {
    /// A sticking base node reaches its static friction strength.
    Slide(NodeId),
    /// A base node's normal reaction reaches zero.
    Lift(NodeId),
    /// A lifted base node comes down onto the base.
    Land(NodeId),
    /// Nothing before the end of the shear stage.
    End,
}

impl Transition {
    /// `"slide"`, `"lift"`, `"land"` or `"end"`.
    pub fn kind(self) -> &'static str {
        match self {
            Transition::Slide(_) => "slide",
            Transition::Lift(_) => "lift",
            Transition::Land(_) => "land",
            Transition::End => "end",
        }
    }

    /// The base node concerned, if any.
    pub fn node(self) -> Option<NodeId> {
        match self {
            Transition::Slide(n) | Transition::Lift(n) | Transition::Land(n) => Some(n),
            Transition::End => None,
        }
    }
}

/// One jump of the quasi-static skip-ahead: the run went from `from_s` to `to_s` (times of the
/// shear stage) without integrating, along the exact quasi-static motion.
#[derive(Clone, Copy, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct Skip {
    /// Start (s).
    pub from_s: f64,
    /// End (s): explicit integration resumes here.
    pub to_s: f64,
    /// Steps not integrated.
    pub steps: u64,
    /// The predicted transition, `margin_steps` after `to_s`.
    pub next: Transition,
}

impl Recording {
    /// Values of a scalar channel, if recorded.
    pub fn get(&self, ch: Channel) -> Option<&[f64]> {
        self.channels.iter().find(|(c, _)| *c == ch).map(|(_, v)| v.as_slice())
    }

    /// Values of a control channel, if recorded.
    pub fn control(&self, ch: ControlChannel) -> Option<&[f64]> {
        self.control.iter().find(|(c, _)| *c == ch).map(|(_, v)| v.as_slice())
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }

    /// The samples of the shear stage, if they are uniformly spaced.
    pub fn uniform_shear(&self) -> Option<std::ops::Range<usize>> {
        self.sampling.uniform.then_some(self.sampling.shear_start..self.len())
    }
}

/// Collects the channels of one lane.
#[derive(bincode::Encode, bincode::Decode)]
pub(crate) struct Recorder {
    pub(crate) records: Recording,
    /// Step index of each sample (converted to time at the end).
    pub(crate) steps: Vec<u64>,
    /// Step of each slip onset and its node.
    pub(crate) onset_steps: Vec<(u64, NodeId)>,
    /// Skips as `(from step, to step, next transition)`.
    pub(crate) skip_steps: Vec<(u64, u64, Transition)>,
    /// Cracks with the step index in place of the time.
    pub(crate) crack_steps: Vec<(u64, Crack)>,
    /// The event trace, from the first step of the shear stage.
    pub(crate) tracer: Option<Tracer>,
    control_nodes: Vec<usize>,
    area: f64,
}

impl Recorder {
    pub(crate) fn new(plan: &RecordPlan, model: &crate::model::Model, capacity: usize) -> Self {
        let channels =
            Channel::of_scene(model.scene()).into_iter().map(|c| (c, Vec::with_capacity(capacity))).collect();
        let control = plan.control.iter().map(|&c| (c, Vec::with_capacity(capacity))).collect();
        Recorder {
            records: Recording {
                time_s: Vec::with_capacity(capacity),
                channels,
                control,
                onsets: Vec::new(),
                skips: Vec::new(),
                cracks: Vec::new(),
                sampling: Sampling::default(),
                trace: Trace::default(),
            },
            tracer: None,
            onset_steps: Vec::new(),
            skip_steps: Vec::new(),
            crack_steps: Vec::new(),
            steps: Vec::with_capacity(capacity),
            control_nodes: plan.control.iter().map(|c| model.held(c.node).unwrap_or(crate::observe::REMOTE)).collect(),
            area: model.lattice().contact_area(),
        }
    }

    /// Records what `s` shows, step index `step`.
    pub(crate) fn sample_view(&mut self, s: &impl Observed, step: u64) {
        self.steps.push(step);
        let needs_interface = self.records.channels.iter().any(|(c, _)| !Channel::ENERGY.contains(c));
        let face = if needs_interface { s.interface() } else { Default::default() };
        let energy = if self.records.channels.iter().any(|(c, _)| Channel::ENERGY.contains(c)) {
            Some(s.energy())
        } else {
            None
        };
        for (ch, values) in &mut self.records.channels {
            let e = || energy.expect("energy computed when an energy channel is recorded");
            values.push(match ch {
                Channel::ShearStress => -face.friction_x / self.area,
                Channel::NormalStress => face.normal / self.area,
                Channel::MeanSlip => face.mean_slip,
                Channel::MeanSlipRate => face.mean_slip_rate,
                Channel::MaxSlipRate => face.max_slip_rate,
                Channel::SlippingNodes => face.slipping as f64,
                Channel::LiftedNodes => face.lifted as f64,
                Channel::DriverForce => s.driver_force(),
                Channel::DriverDisplacement => s.driver_target(),
                Channel::Kinetic => e().kinetic,
                Channel::Elastic => e().elastic,
                Channel::DampingDissipated => e().damping,
                Channel::FrictionDissipated => e().friction,
                Channel::ImpactDissipated => e().impact,
                Channel::FractureDissipated => e().fracture,
                Channel::Absorbed => e().absorbed,
                Channel::BodyWork => e().body_work,
                Channel::DriverWork => e().driver_work,
                Channel::TractionWork => e().traction_work,
                Channel::ExternalWork => e().external_work(),
                Channel::EnergyResidual => e().residual(),
            });
        }
        for ((ch, values), &node) in self.records.control.iter_mut().zip(&self.control_nodes) {
            values.push(s.control(*ch, node));
        }
    }

    /// Finishes: times from step indices, with `origin` the step index of shear time zero, `dt`
    /// the time step and `stride` the steps between two samples of the shear stage.
    pub(crate) fn finish(mut self, origin: u64, dt: f64, stride: u64, model: &crate::model::Model) -> Recording {
        let shear_start = self.steps.partition_point(|&s| s < origin);
        let uniform = self.steps[shear_start..].windows(2).all(|w| w[1] - w[0] == stride);
        self.records.sampling = Sampling { step_s: dt, stride, shear_start, uniform };
        if let Some(tracer) = self.tracer.take() {
            self.records.trace = tracer.finish(dt, model);
        }
        self.records.time_s = self.steps.iter().map(|&s| (s as f64 - origin as f64) * dt).collect();
        self.records.onsets = self.onset_steps.iter().map(|&(s, n)| ((s as f64 - origin as f64) * dt, n)).collect();
        let t = |s: u64| (s as f64 - origin as f64) * dt;
        self.records.cracks = self.crack_steps.iter().map(|&(s, c)| Crack { time_s: t(s), ..c }).collect();
        self.records.skips = self
            .skip_steps
            .iter()
            .map(|&(from, to, next)| Skip { from_s: t(from), to_s: t(to), steps: to - from, next })
            .collect();
        self.records
    }
}
