//! A seed's events (docs/model.md §7) and each at prototype scale with its magnitudes (§9).

use stickslip_seismo::events::{Catalogue, EventParams, Signals, detect};
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
    detect(&signals, model.contact().len(), model.lattice().contact_area(), events)
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
