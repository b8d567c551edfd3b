//! A seed's events (docs/model.md §7) and each at prototype scale with its magnitudes (§9).

use stickslip_seismo::events::{Catalogue, EventParams, Loading, Signals, detect};
use stickslip_seismo::similarity::{AreaChoice, Magnitudes, ModelEvent, Scaled, SimilarityParams, scale};
use stickslip_solver::material::lattice_elastic_constants;
use stickslip_solver::scene::{ControlChannel, Kinematic};
use stickslip_solver::{Model, Recording};

/// One event at prototype scale.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScaledEvent {
    /// What was scaled: the event at model scale.
    pub input: ModelEvent,
    /// The event at prototype scale.
    pub scaled: Scaled,
    /// Its magnitudes by both moment conventions.
    pub magnitudes: Magnitudes,
    /// On a fault (docs/model.md §15), the moment from its own slip, `μ·A·ΔD̄` with `ΔD̄` the
    /// change of the mean slip of the fault's nodes over the event and `A` the fault area (N·m),
    /// and its moment magnitude; `None` on the rigid base.
    pub slip_moment: Option<(f64, f64)>,
}

/// Control acceleration channels recorded by the scene, in table order (the events' peak
/// accelerations are in this order).
pub fn acceleration_channels(model: &Model) -> Vec<ControlChannel> {
    model.scene().record.control.iter().filter(|c| c.quantity == Kinematic::Acceleration).copied().collect()
}

/// Detects the events of a run on the solver's event trace (docs/model.md §7): every step around
/// each burst of slip, whatever the recording interval, so the catalogue does not depend on it.
pub fn catalogue(rec: &Recording, model: &Model, events: &EventParams) -> Catalogue {
    let trace = &rec.trace;
    let accelerations: Vec<&[f64]> = trace.accelerations.iter().map(|(_, v)| v.as_slice()).collect();
    let signals = Signals {
        time_s: &trace.time_s,
        shear_stress_pa: &trace.shear_stress_pa,
        mean_slip_m: &trace.mean_slip_m,
        mean_slip_rate_m_s: &trace.mean_slip_rate_m_s,
        slipping_nodes: Some(&trace.slipping_nodes),
        accelerations: &accelerations,
    };
    let loading = if model.scene().is_driven() { Loading::Driven } else { Loading::Fixed };
    detect(&signals, model.contact().len(), model.lattice().contact_area(), loading, events)
}

/// The prototype length ratio λ = L_p / L_m of `model`'s block: 1 on a fault, whose scene is at
/// its own scale.
pub fn lambda(model: &Model, similarity: &SimilarityParams) -> f64 {
    if model.scene().is_fault() { 1.0 } else { similarity.prototype_length_m / model.lattice().extent()[0] }
}

/// Every event of `cat` scaled to the prototype of `similarity` (docs/model.md §9); the model's
/// loading rate is the scene's driver speed.
pub fn scaled_events(cat: &Catalogue, model: &Model, similarity: &SimilarityParams) -> Vec<ScaledEvent> {
    let lattice = model.lattice();
    let model_length = lattice.extent()[0];
    let scene = model.scene();
    let shear_modulus = lattice_elastic_constants(scene.young_pa, scene.poisson).2;
    cat.events
        .iter()
        .map(|e| {
            let area = match similarity.area {
                AreaChoice::Contact => lattice.contact_area(),
                AreaChoice::Rupture => e.burst.rupture_area_m2,
            };
            let input = ModelEvent {
                stress_drop_pa: e.burst.stress_drop_pa,
                model_length_m: model_length,
                model_area_m2: area,
                duration_s: Some(e.burst.duration_s()),
                recurrence_s: e.recurrence_s,
                model_rate_m_s: model.scene().shear.velocity_m_s,
            };
            let scaled = scale(&input, similarity);
            let slip_moment = scene.is_fault().then(|| {
                let m0 = shear_modulus * lattice.contact_area() * e.burst.slip_m.abs();
                (m0, crate::source::moment_magnitude(m0))
            });
            ScaledEvent { input, scaled, magnitudes: scaled.magnitudes(), slip_moment }
        })
        .collect()
}

/// What the base did over a seed's shear stage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlipRegime {
    /// Bursts of slip with stress drops, the base stuck between them.
    StickSlip,
    /// Stick-slip, then stable sliding to the end of the run.
    StickSlipThenSliding,
    /// The base slid along with its loading, without an earthquake.
    StableSliding,
    /// No event, and the base did not keep up with its loading: it held (or the block tipped).
    NoSlip,
}

impl SlipRegime {
    /// Every regime.
    pub const ALL: [SlipRegime; 4] =
        [SlipRegime::StickSlip, SlipRegime::StickSlipThenSliding, SlipRegime::StableSliding, SlipRegime::NoSlip];

    /// `"stick_slip"`, `"stick_slip_then_sliding"`, `"stable_sliding"`, `"no_slip"`.
    pub fn name(self) -> &'static str {
        match self {
            SlipRegime::StickSlip => "stick_slip",
            SlipRegime::StickSlipThenSliding => "stick_slip_then_sliding",
            SlipRegime::StableSliding => "stable_sliding",
            SlipRegime::NoSlip => "no_slip",
        }
    }

    /// The regime written as `name`.
    pub fn parse(name: &str) -> Option<SlipRegime> {
        SlipRegime::ALL.into_iter().find(|r| r.name() == name)
    }
}

/// The run's diagnosis: its regime, when it started sliding for good, and how closely the base
/// followed its loading over the second half of the shear stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diagnosis {
    /// The regime.
    pub regime: SlipRegime,
    /// Start of the slip episode that never stopped, if the run ended in one (s).
    pub sliding_from_s: Option<f64>,
    /// Slip of the base over the second half of the shear stage divided by the loading's
    /// displacement over it: about 1 for a base that slides with its loading (steadily or in
    /// bursts), near 0 for one that holds.
    pub followed: f64,
}

/// The share of its loading's displacement the base must have slipped over the second half of
/// the shear stage, without an event, to be read as sliding stably.
pub const FOLLOWS: f64 = 0.5;

/// Reads what the base did from the catalogue and the event trace: stick-slip when it has
/// events; stable sliding when a slip episode never stopped ([`Catalogue::sliding`]) or, with no
/// event, when the base slipped at least [`FOLLOWS`] of its loading's displacement over the
/// second half of the shear stage (as with a rigid driver whose slips stay slower than the
/// detector's threshold); no slip otherwise.
pub fn diagnose(rec: &Recording, cat: &Catalogue, model: &Model) -> Diagnosis {
    let trace = &rec.trace;
    let shear = &model.scene().shear;
    let followed = match (trace.time_s.first(), trace.time_s.last()) {
        (Some(&t0), Some(&t1)) if t1 > t0 => {
            let mid = 0.5 * (t0 + t1);
            let i = trace.time_s.partition_point(|&t| t < mid).min(trace.time_s.len() - 1);
            let slip = trace.mean_slip_m[trace.mean_slip_m.len() - 1] - trace.mean_slip_m[i];
            let load = shear.driver_displacement(t1) - shear.driver_displacement(trace.time_s[i]);
            if load > 0.0 { slip / load } else { 0.0 }
        }
        _ => 0.0,
    };
    let sliding_from_s = cat.sliding.as_ref().map(|s| s.burst.start_s);
    let regime = match (cat.events.is_empty(), sliding_from_s.is_some()) {
        (false, false) => SlipRegime::StickSlip,
        (false, true) => SlipRegime::StickSlipThenSliding,
        (true, true) => SlipRegime::StableSliding,
        (true, false) if followed >= FOLLOWS => SlipRegime::StableSliding,
        (true, false) => SlipRegime::NoSlip,
    };
    Diagnosis { regime, sliding_from_s, followed }
}
