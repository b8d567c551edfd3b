//! A seed's events (docs/model.md §7) and each at prototype scale with its magnitudes (§9).

use stickslip_seismo::events::{Catalogue, EventParams, Signals, detect};
use stickslip_seismo::similarity::{AreaChoice, Magnitudes, ModelEvent, Scaled, SimilarityParams, scale};
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

/// The prototype length ratio λ = L_p / L_m of `model`'s block.
pub fn lambda(model: &Model, similarity: &SimilarityParams) -> f64 {
    similarity.prototype_length_m / model.lattice().extent()[0]
}

/// Every event of `cat` scaled to the prototype of `similarity` (docs/model.md §9); the model's
/// loading rate is the scene's driver speed.
pub fn scaled_events(cat: &Catalogue, model: &Model, similarity: &SimilarityParams) -> Vec<ScaledEvent> {
    let lattice = model.lattice();
    let model_length = lattice.extent()[0];
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
            ScaledEvent { input, scaled, magnitudes: scaled.magnitudes() }
        })
        .collect()
}
