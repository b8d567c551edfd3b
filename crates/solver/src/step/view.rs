//! What one lane of a committed step shows at its viewed time: kinematics, interface resultants,
//! energy, and the stability check.

use crate::step::energy::{Energy, kinetic_energy, strain_energy};
use crate::step::params::Params;
use crate::step::state::State;

/// Interface resultants of one lane at one instant (docs/model.md §4).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Interface {
    /// Σ of the friction reactions in x (N); the base resists a +x push with a negative sum.
    pub friction_x: f64,
    /// Σ of the normal reactions (N).
    pub normal: f64,
    /// Mean x-displacement of the contact nodes (m).
    pub mean_slip: f64,
    /// Mean x-velocity of the contact nodes (m/s).
    pub mean_slip_rate: f64,
    /// Max x-velocity of the contact nodes (m/s).
    pub max_slip_rate: f64,
    /// Sliding contact nodes.
    pub slipping: usize,
    /// Lifted contact nodes.
    pub lifted: usize,
}

/// One contact node as the interface sums see it. On a fault (docs/model.md §15) its slip and
/// slip rate are across the fault, twice the face's displacement and velocity, and its normal
/// reaction is the prescribed normal force.
#[derive(Clone, Copy, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct NodeContact {
    /// Friction reaction in x (N).
    pub friction_x: f64,
    /// Friction reaction in y (N).
    pub friction_y: f64,
    /// Normal reaction (N).
    pub normal: f64,
    /// Slip in x: the x-displacement (m).
    pub slip: f64,
    /// Slip in y (m).
    pub slip_y: f64,
    /// Slip rate in x: the x-velocity (m/s).
    pub slip_rate: f64,
    /// Slip rate in y (m/s).
    pub slip_rate_y: f64,
    /// Sliding.
    pub slipping: bool,
    /// Off the base.
    pub lifted: bool,
    /// The friction law's state variable ([`crate::laws::Law`]: θ (s) under rate and state).
    pub state: f64,
}

impl Interface {
    /// The resultants of the contact nodes, summed in their order.
    #[inline(always)]
    pub fn sum(nodes: impl ExactSizeIterator<Item = NodeContact>) -> Interface {
        let n = nodes.len() as f64;
        let mut s = Interface { max_slip_rate: f64::NEG_INFINITY, ..Interface::default() };
        for c in nodes {
            s.friction_x += c.friction_x;
            s.normal += c.normal;
            s.mean_slip += c.slip;
            s.mean_slip_rate += c.slip_rate;
            s.max_slip_rate = s.max_slip_rate.max(c.slip_rate);
            s.slipping += usize::from(c.slipping);
            s.lifted += usize::from(c.lifted);
        }
        s.mean_slip /= n;
        s.mean_slip_rate /= n;
        s
    }
}

/// What the stability check found.
#[derive(Clone, Debug, PartialEq)]
pub struct Blowup {
    /// Internal node index.
    pub node: usize,
    /// Description.
    pub what: String,
}

/// Lane `lane` of a committed step, at its viewed time.
pub struct LaneView<'a, 'm, const L: usize> {
    /// Parameters.
    pub params: &'a Params<'m, L>,
    /// State.
    pub state: &'a State<L>,
    /// Lane.
    pub lane: usize,
}

impl<const L: usize> LaneView<'_, '_, L> {
    /// Displacement of internal node `i` (m).
    pub fn displacement(&self, i: usize) -> [f64; 3] {
        self.state.u.n.get(i, self.lane)
    }

    /// Velocity of internal node `i`, `(uₙ₊₁ − uₙ₋₁)/2Δt` (m/s).
    pub fn velocity(&self, i: usize) -> [f64; 3] {
        let h = 0.5 / self.params.dt(self.lane);
        let (a, b) = (self.state.u.np1.get(i, self.lane), self.state.u.nm1.get(i, self.lane));
        [(a[0] - b[0]) * h, (a[1] - b[1]) * h, (a[2] - b[2]) * h]
    }

    /// Acceleration of internal node `i`, `(uₙ₊₁ − 2uₙ + uₙ₋₁)/Δt²` (m/s²).
    pub fn acceleration(&self, i: usize) -> [f64; 3] {
        let dt = self.params.dt(self.lane);
        let h = 1.0 / (dt * dt);
        let u = &self.state.u;
        let (a, b, c) = (u.np1.get(i, self.lane), u.n.get(i, self.lane), u.nm1.get(i, self.lane));
        [0, 1, 2].map(|k| (a[k] - 2.0 * b[k] + c[k]) * h)
    }

    /// Interface resultants.
    pub fn interface(&self) -> Interface {
        Interface::sum((0..self.params.model.contact().len()).map(|ci| self.node_contact(ci)))
    }

    /// Contact node `ci` (order of [`crate::Model::contact`]) at the viewed time. Inlined: the
    /// observer sums every contact node of every lane at every step, and only the fields it adds
    /// need reading.
    #[inline(always)]
    pub fn node_contact(&self, ci: usize) -> NodeContact {
        let (l, u, r) = (self.lane, &self.state.u, &self.state.contact.reaction);
        let factor = self.params.model.scene().slip_factor();
        let h = 0.5 / self.params.dt(l) * factor;
        let p = self.params.model.contact()[ci] as usize;
        NodeContact {
            friction_x: r[0][ci][l],
            friction_y: r[1][ci][l],
            normal: r[2][ci][l],
            slip: u.n.c[0][p][l] * factor,
            slip_y: u.n.c[1][p][l] * factor,
            slip_rate: (u.np1.c[0][p][l] - u.nm1.c[0][p][l]) * h,
            slip_rate_y: (u.np1.c[1][p][l] - u.nm1.c[1][p][l]) * h,
            slipping: self.state.contact.sliding[ci][l],
            lifted: r[2][ci][l] == 0.0,
            state: self.state.contact.state[ci][l],
        }
    }

    /// Sum of the driver reactions in x (N).
    pub fn driver_force(&self) -> f64 {
        self.state.driver_force(self.lane)
    }

    /// Driver target displacement (m) used in the last step.
    pub fn driver_target(&self) -> f64 {
        self.state.loading.target[self.lane]
    }

    /// Kinetic energy `½m|uₙ₊₁ − uₙ|²/Δt²` (J), one pass over the nodes.
    pub fn kinetic_energy(&self) -> f64 {
        let u = &self.state.u;
        kinetic_energy(self.params.model, &u.np1, &u.n, self.lane, self.params.dt(self.lane))
    }

    /// Energy terms (a pass over all bars and nodes).
    pub fn energy(&self) -> Energy {
        let u = &self.state.u;
        let mut e = self.state.energy[self.lane];
        e.kinetic = self.kinetic_energy();
        let model = self.params.model;
        e.elastic = match &self.state.rupture {
            None => strain_energy(model, self.params.stiffness(), &u.n, &u.np1, self.lane),
            Some(r) => crate::step::rupture::strain_energy(
                model.layout().listed(),
                &model.energy_layers(),
                self.params.k.per_bar(),
                &r.secant,
                &u.n,
                &u.np1,
                self.lane,
            ),
        };
        e
    }

    /// Out-of-balance force `‖m·a + c·v‖₂` over all nodes and components (N): zero at static
    /// equilibrium.
    pub fn out_of_balance(&self) -> f64 {
        let mut sum = 0.0;
        self.out_of_balance_terms(0..self.params.model.node_count(), |t| sum += t);
        sum.sqrt()
    }

    /// The squared terms of [`LaneView::out_of_balance`] of `nodes`, component by component,
    /// each node in order, handed to `add`.
    pub(crate) fn out_of_balance_terms(&self, nodes: std::ops::Range<usize>, mut add: impl FnMut(f64)) {
        let (l, u) = (self.lane, &self.state.u);
        let mass = self.params.model.mass();
        let (dt, d) = (self.params.dt(l), self.params.damping(l));
        let (ha, hv) = (1.0 / (dt * dt), d * 0.5 / dt);
        for c in 0..3 {
            let (a, b, o) = (&u.np1.c[c], &u.n.c[c], &u.nm1.c[c]);
            for i in nodes.clone() {
                let r = mass[i] * ((a[i][l] - 2.0 * b[i][l] + o[i][l]) * ha + (a[i][l] - o[i][l]) * hv);
                add(r * r);
            }
        }
    }

    /// A blow-up in the last step: a non-finite displacement, or a node that moved more than
    /// `0.01·Lc` in one step (a particle speed no linear-elastic rock reaches).
    pub fn check_blowup(&self) -> Option<Blowup> {
        self.check_blowup_on(false)
    }

    /// [`LaneView::check_blowup`], the nodes scanned on the current rayon pool with `parallel`
    /// (the same first node found either way).
    pub fn check_blowup_on(&self, parallel: bool) -> Option<Blowup> {
        let u = &self.state.u;
        for c in 0..3 {
            let Some(i) = self.first_blowup(c, 0..u.np1.len(), parallel) else { continue };
            let (x, y) = (u.np1.c[c][i][self.lane], u.n.c[c][i][self.lane]);
            return Some(Blowup { node: i, what: self.blowup_what(c, x, y) });
        }
        None
    }

    /// The first of `nodes` whose component `c` is not finite or moved more than `0.01·Lc` in
    /// the last step.
    pub(crate) fn first_blowup(&self, c: usize, nodes: std::ops::Range<usize>, parallel: bool) -> Option<usize> {
        use rayon::prelude::*;
        let (l, u) = (self.lane, &self.state.u);
        let bound = 0.01 * self.params.model.scene().lc_m;
        let (a, b) = (&u.np1.c[c], &u.n.c[c]);
        let bad = |i: usize| !a[i][l].is_finite() || (a[i][l] - b[i][l]).abs() > bound;
        if parallel {
            // Chunks on the pool, each scanned as the serial loop scans it: rayon's
            // `find_first` over single nodes consults a shared atomic at every node (13× the
            // serial loop's time on 2 threads).
            const CHUNK: usize = 1 << 14;
            let (start, n) = (nodes.start, nodes.len());
            (0..n.div_ceil(CHUNK))
                .into_par_iter()
                .find_map_first(|k| (start + k * CHUNK..start + ((k + 1) * CHUNK).min(n)).find(|&i| bad(i)))
        } else {
            nodes.into_iter().find(|&i| bad(i))
        }
    }

    /// What a blow-up of component `c` from `y` to `x` in one step is.
    pub(crate) fn blowup_what(&self, c: usize, x: f64, y: f64) -> String {
        let bound = 0.01 * self.params.model.scene().lc_m;
        if !x.is_finite() {
            format!("non-finite {} displacement", ["x", "y", "z"][c])
        } else {
            format!(
                "{} displacement changed by {:.3e} m in one step (bound 0.01·Lc = {bound:.3e} m)",
                ["x", "y", "z"][c],
                (x - y).abs()
            )
        }
    }
}
