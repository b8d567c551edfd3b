//! What a scene builds, without running it: sizes, loads, the critical step over seeds and the
//! effective stiffness of the built block (for `stickslip check`).

use crate::error::SolverError;
use crate::model::Model;
use crate::statics::{CriticalStep, EffectiveModuli, critical_time_step, uniaxial_moduli};

/// The facts of a built scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Inspection {
    /// Nodes.
    pub nodes: usize,
    /// Bars.
    pub bars: usize,
    /// Contact nodes (the base).
    pub contact_nodes: usize,
    /// Total mass (kg).
    pub mass_kg: f64,
    /// Contact area `nx·Lc × ny·Lc` (m²).
    pub contact_area_m2: f64,
    /// Mean normal stress of the self-weight on the base, `m·g/A` (Pa).
    pub self_weight_stress_pa: f64,
    /// Sliding strength of the whole base under its self-weight, `μs·m·g/A` (Pa).
    pub strength_pa: f64,
    /// Critical step of each seed inspected.
    pub critical: Vec<(u64, CriticalStep)>,
    /// The paper's bound `0.6·Lc/Cp` (Eq. 5, s).
    pub paper_bound_s: f64,
    /// Effective moduli along x and along z (static solves of the homogeneous-mean lattice of the
    /// first seed inspected).
    pub moduli: [EffectiveModuli; 2],
}

impl Inspection {
    /// Smallest and largest critical step over the seeds inspected (s).
    pub fn critical_range_s(&self) -> (f64, f64) {
        self.critical
            .iter()
            .map(|(_, c)| c.dt_s)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
    }
}

/// Inspects `model` for `seeds` (at least one): the critical step of each, the moduli of the
/// first.
pub fn inspect(model: &Model, seeds: &[u64]) -> Result<Inspection, SolverError> {
    assert!(!seeds.is_empty(), "inspect at least one seed");
    let scene = model.scene();
    let lattice = model.lattice();
    let mut critical = Vec::with_capacity(seeds.len());
    for &seed in seeds {
        let k = model.bar_stiffness(seed)?;
        critical.push((seed, critical_time_step(model, &k)?));
    }
    let k = model.bar_stiffness(seeds[0])?;
    let moduli = [uniaxial_moduli(model, &k, 0)?, uniaxial_moduli(model, &k, 2)?];
    let weight = model.total_mass() * scene.self_weight.gravity_m_s2;
    let area = lattice.contact_area();
    Ok(Inspection {
        nodes: model.node_count(),
        bars: model.bar_count(),
        contact_nodes: model.contact().len(),
        mass_kg: model.total_mass(),
        contact_area_m2: area,
        self_weight_stress_pa: weight / area,
        strength_pa: scene.friction.law.mu_static() * weight / area,
        critical,
        paper_bound_s: scene.paper_time_step_bound(),
        moduli,
    })
}
