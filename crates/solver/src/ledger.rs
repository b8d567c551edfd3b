//! The energy ledger of a run (docs/model.md §2): the cumulative work and dissipation terms of one
//! lane, which the step, the boundary conditions and the rupture kernel add to.

/// Cumulative energy terms of one lane (J), all measured from the start of the run.
#[derive(Clone, Copy, Debug, Default, PartialEq, bincode::Encode, bincode::Decode)]
pub struct Energy {
    /// `½ Σ m|uₙ₊₁ − uₙ|²/Δt²`.
    pub kinetic: f64,
    /// `½ uₙᵀ K uₙ₊₁`.
    pub elastic: f64,
    /// Dissipated by mass-proportional damping.
    pub damping: f64,
    /// Dissipated by base friction.
    pub friction: f64,
    /// Lost in inelastic landings on the base.
    pub impact: f64,
    /// Dissipated by bars that crack (docs/model.md §11; 0 without rupture).
    pub fracture: f64,
    /// Work of body forces (gravity, body-force loads) and of the normal load.
    pub body_work: f64,
    /// Work of the drivers and the loading plate's springs.
    pub driver_work: f64,
    /// Work of the initial tractions on a fault's face (docs/model.md §15; 0 on the rigid base).
    pub traction_work: f64,
    /// Carried out of the block by the absorbing faces' dashpots (0 without them).
    pub absorbed: f64,
    /// Taken by the medium's memory variables and dashpots (docs/model.md §18; 0 in an elastic
    /// medium): the work of their forces, dissipated or held in the relaxing springs.
    pub anelastic: f64,
}

impl Energy {
    /// Body, driver and traction work.
    pub fn external_work(&self) -> f64 {
        self.body_work + self.driver_work + self.traction_work
    }

    /// External work minus everything stored and dissipated (zero up to round-off).
    pub fn residual(&self) -> f64 {
        self.external_work()
            - (self.kinetic
                + self.elastic
                + self.damping
                + self.friction
                + self.impact
                + self.fracture
                + self.absorbed
                + self.anelastic)
    }
}
