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

impl Energy {
    /// The work and dissipation terms (every term but the kinetic and elastic energy), in the
    /// order of the fields.
    pub fn work_terms(&self) -> [f64; 9] {
        [
            self.damping,
            self.friction,
            self.impact,
            self.fracture,
            self.body_work,
            self.driver_work,
            self.traction_work,
            self.absorbed,
            self.anelastic,
        ]
    }

    /// The terms of [`Energy::work_terms`] back into a ledger (kinetic and elastic zero).
    pub fn from_work_terms(t: &[f64]) -> Energy {
        Energy {
            damping: t[0],
            friction: t[1],
            impact: t[2],
            fracture: t[3],
            body_work: t[4],
            driver_work: t[5],
            traction_work: t[6],
            absorbed: t[7],
            anelastic: t[8],
            ..Energy::default()
        }
    }

    /// Adds the work terms of `d` (a step's increment) to these.
    pub fn add_work(&mut self, d: &Energy) {
        let (mut t, dt) = (self.work_terms(), d.work_terms());
        for (a, b) in t.iter_mut().zip(dt) {
            *a += b;
        }
        *self = Energy { kinetic: self.kinetic, elastic: self.elastic, ..Energy::from_work_terms(&t) };
    }
}

/// The module layers whose energy a model sums (docs/model.md §2): every layer of the block, or
/// the layers a rank of a split scene owns. Every energy term is summed layer by layer (a node's
/// terms in its layer, a bar's in its lower end's), and the layers' sums are added bottom up, so
/// that the ranks of a split scene, each summing its own layers, give rank 0 the one process's
/// bits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EnergyLayers {
    /// The block's internal index of the model's first node.
    pub first_node: usize,
    /// Nodes of one module layer (corners and centres).
    pub layer_nodes: usize,
    /// The block's first layer summed here.
    pub first: usize,
    /// Layers summed here.
    pub count: usize,
    /// The nodes summed here (model indices).
    pub nodes: std::ops::Range<usize>,
}

impl EnergyLayers {
    /// The layer (counted from [`EnergyLayers::first`]) whose sums take node `i`'s terms, if this
    /// model sums them.
    #[inline]
    pub fn of(&self, i: usize) -> Option<usize> {
        self.nodes.contains(&i).then(|| (self.first_node + i) / self.layer_nodes - self.first)
    }

    /// The nodes (model indices) of layer `k` summed here.
    pub fn nodes_of(&self, k: usize) -> std::ops::Range<usize> {
        let g = (self.first + k) * self.layer_nodes;
        let (lo, hi) = (g.saturating_sub(self.first_node), (g + self.layer_nodes).saturating_sub(self.first_node));
        lo.max(self.nodes.start)..hi.min(self.nodes.end)
    }
}

/// `Σ_k parts[k]`, bottom up: one step's work terms of every layer of one lane.
pub fn fold_layers<'a>(parts: impl Iterator<Item = &'a Energy>) -> Energy {
    let mut sum = Energy::default();
    for p in parts {
        sum.add_work(p);
    }
    sum
}

/// `Σ parts` bottom up: the layers' sums of one energy term (the one order every rank count
/// shares).
pub fn total(parts: &[f64]) -> f64 {
    parts.iter().fold(0.0, |s, p| s + p)
}
