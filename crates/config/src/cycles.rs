//! `[cycles]`: earthquake cycles on a rate-and-state fault, quasi-dynamically (docs/model.md §20;
//! the guide's faults chapter, Earthquake cycles). The scene is the fault's one side as a slab
//! one module thick (`nx = 1`; the antiplane mode), its base a `[fault]` under
//! `rate_state_aging` or `rate_state_slip`; the run loads it by the plate for `years`.

use serde::{Deserialize, Serialize};
use stickslip_solver::Scene;
use stickslip_solver::cycles::{CycleSpec, DynamicSpec, Heterogeneity, Tolerances, YEAR_S};
use stickslip_solver::laws::{NodeFriction, RateStateNode};

use crate::check::{Checker, num};
use crate::scene::LEAST_ZONE_NODES;

/// `[cycles]` as written.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct CyclesSection {
    /// `"quasi_dynamic"` (radiation damping η = μ/2c_s in place of inertia) or `"fully_dynamic"`
    /// (the lattice's explicit antiplane grid inside events, quasi-dynamic between them).
    #[serde(default = "quasi_dynamic")]
    pub mode: String,
    /// Fully dynamic: the explicit grid takes over when the largest slip rate exceeds this (m/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic_above_m_s: Option<f64>,
    /// Fully dynamic: the quasi-dynamic integration resumes when the largest slip rate falls
    /// below this (m/s), at most `dynamic_above_m_s`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub static_below_m_s: Option<f64>,
    /// Fully dynamic: the explicit grid's extent `[down dip, away from the fault]` (m), within the
    /// block; its far face and bottom absorb. Down dip it reaches at least the frictional depth.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic_block_m: Option<[f64; 2]>,
    /// Fully dynamic: the explicit grid's Kelvin–Voigt damping as a fraction γ of its step
    /// (`β = γ·Δt`), 0–1; the step shrinks by `√(1 + 2γ)`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic_damping: Option<f64>,
    /// How long the plate loads the fault (years of 365.25 days), > 0.
    pub years: f64,
    /// The plate rate V_p (m/s), > 0: the slip rate below the frictional part and of the far face.
    pub plate_rate_m_s: f64,
    /// The frictional part reaches from the free surface to this depth (m); below it the fault
    /// creeps at the plate rate. Within the block, at least 3 modules.
    pub frictional_depth_m: f64,
    /// The direct effect `a` along depth on the friction's background: `[[depth_m, a], …]` with
    /// depths increasing, linear between points and constant beyond; patches keep their own a.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub a_by_depth: Vec<[f64; 2]>,
    /// Relative tolerance of the adaptive step (1e-12–1e-3).
    #[serde(default = "relative_tolerance")]
    pub relative_tolerance: f64,
    /// The longest step (years), > 0.
    #[serde(default = "max_step_years")]
    pub max_step_years: f64,
    /// The fault is in an event while its largest slip rate exceeds this (m/s), > 0.
    #[serde(default = "event_slip_rate")]
    pub event_slip_rate_m_s: f64,
    /// The files' sampling inside events (s), > 0; between events it is `max_step_years`.
    #[serde(default = "sample_s")]
    pub sample_s: f64,
    /// On-fault stations: depths (m) within the frictional part.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stations_depth_m: Vec<f64>,
    /// The most steps the run may take (1–10⁹).
    #[serde(default = "max_steps")]
    pub max_steps: i64,
    /// Random fields of a, b and L along the fault, one draw per seed (the catalogue scene's
    /// heterogeneity); absent: the friction as given, one run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub heterogeneity: Option<HeterogeneitySection>,
}

/// `[cycles.heterogeneity]`: log-normal random fields of a, b and L along the fault, each
/// coefficient multiplied by `exp(s·g)`, `g` a unit von Kármán field along depth drawn per seed.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct HeterogeneitySection {
    /// Standard deviation of ln a (0–2; 0: a as given).
    #[serde(default)]
    pub log_a_std: f64,
    /// Standard deviation of ln b (0–2; 0: b as given).
    #[serde(default)]
    pub log_b_std: f64,
    /// Standard deviation of ln L (0–2; 0: L as given).
    #[serde(default)]
    pub log_dc_std: f64,
    /// Correlation length (m), at least 2 modules and at most the frictional depth.
    pub correlation_length_m: f64,
    /// Hurst exponent (0 < H ≤ 1).
    #[serde(default = "hurst")]
    pub hurst: f64,
}

fn hurst() -> f64 {
    0.75
}

fn quasi_dynamic() -> String {
    "quasi_dynamic".into()
}
fn relative_tolerance() -> f64 {
    1e-7
}
fn max_step_years() -> f64 {
    0.1
}
fn event_slip_rate() -> f64 {
    1e-3
}
fn sample_s() -> f64 {
    0.1
}
fn max_steps() -> i64 {
    10_000_000
}

impl CyclesSection {
    /// The run it asks for on `scene`, checked; refusals go to `ck`.
    pub fn build(&self, scene: &Scene, ck: &mut Checker) -> CycleSpec {
        let dynamic = self.mode == "fully_dynamic";
        if !dynamic && self.mode != "quasi_dynamic" {
            ck.push("cycles.mode", format!("{:?}", self.mode), "\"quasi_dynamic\" or \"fully_dynamic\"");
        }
        if !dynamic {
            let keys = [
                ("cycles.dynamic_above_m_s", self.dynamic_above_m_s.is_some()),
                ("cycles.static_below_m_s", self.static_below_m_s.is_some()),
                ("cycles.dynamic_block_m", self.dynamic_block_m.is_some()),
                ("cycles.dynamic_damping", self.dynamic_damping.is_some()),
            ];
            for (key, given) in keys {
                if given {
                    ck.push(key, "(given)", "left out unless cycles.mode = \"fully_dynamic\"");
                }
            }
        }
        ck.range("cycles.years", self.years, 0.0, true, 1e7, false);
        ck.range("cycles.plate_rate_m_s", self.plate_rate_m_s, 0.0, true, 1.0, false);
        ck.range("cycles.relative_tolerance", self.relative_tolerance, 1e-12, false, 1e-3, false);
        ck.positive("cycles.max_step_years", self.max_step_years);
        ck.positive("cycles.event_slip_rate_m_s", self.event_slip_rate_m_s);
        ck.positive("cycles.sample_s", self.sample_s);
        let steps = ck.count("cycles.max_steps", self.max_steps, 1, 1_000_000_000, "a step budget");
        let lc = scene.lc_m;
        let depth = scene.dims.ny as f64 * lc;
        if scene.dims.nx != 1 {
            ck.push(
                "block.nx",
                scene.dims.nx,
                "1 with [cycles] (the antiplane mode: a slab one module thick along strike)",
            );
        }
        if scene.dims.nz < 2 {
            ck.push("block.nz", scene.dims.nz, "at least 2 with [cycles] (the block away from the fault)");
        }
        ck.range("cycles.frictional_depth_m", self.frictional_depth_m, 3.0 * lc, false, depth, true);
        if scene.fault.is_none() {
            ck.push("fault", "none", "a [fault] with [cycles] (its base is the fault the plate loads)");
        }
        if scene.fault.as_ref().is_some_and(|f| !f.depth_scale.is_empty()) {
            ck.push(
                "fault.overburden_gradient_pa_m",
                "(present)",
                "left out with [cycles]: a cycle run checks its nucleation size h* and process zone Λ₀ against one \
                 normal stress, and does not yet take one that grows with depth",
            );
        }
        if !matches!(scene.friction.base(0), NodeFriction::RateState(_)) {
            ck.push(
                "friction.law",
                format!("{:?}", scene.friction.law.name),
                "\"rate_state_aging\" or \"rate_state_slip\" with [cycles]",
            );
        }
        if scene.young_cv != 0.0 {
            ck.push(
                "material.young_cv",
                num(scene.young_cv),
                "0 with [cycles] (the fault's stiffness is computed for a homogeneous block)",
            );
        }
        if !scene.medium.is_default() {
            ck.push(
                "medium",
                "(present)",
                "left out with [cycles] (the fault's stiffness is computed for one material)",
            );
        }
        if scene.friction.mu_cv != 0.0 {
            ck.push("friction.mu_cv", num(scene.friction.mu_cv), "0 with [cycles] (its friction is rate and state; [cycles.heterogeneity] gives random fields of a, b and L)");
        }
        let mut last = f64::NEG_INFINITY;
        for (i, [d, a]) in self.a_by_depth.iter().copied().enumerate() {
            if !(d >= 0.0 && d > last && d.is_finite()) {
                ck.push(format!("cycles.a_by_depth[{i}][0]"), num(d), "a depth ≥ 0 (m) beyond the previous point's");
            }
            ck.range(&format!("cycles.a_by_depth[{i}][1]"), a, 0.0, true, 1.0, false);
            last = d;
        }
        for (i, &d) in self.stations_depth_m.iter().enumerate() {
            if !(d >= 0.0 && d < self.frictional_depth_m) {
                ck.push(
                    format!("cycles.stations_depth_m[{i}]"),
                    num(d),
                    format!("a depth in [0, {}) m (the frictional part)", num(self.frictional_depth_m)),
                );
            }
        }
        let dynamic = dynamic.then(|| self.dynamic(scene, ck));
        let heterogeneity = self.heterogeneity.map(|h| h.build(scene, self.frictional_depth_m, ck));
        CycleSpec {
            heterogeneity,
            dynamic,
            duration_s: self.years * YEAR_S,
            plate_m_s: self.plate_rate_m_s,
            frictional_depth_m: self.frictional_depth_m,
            a_by_depth: self.a_by_depth.iter().map(|&[d, a]| (d, a)).collect(),
            tolerances: Tolerances {
                relative: self.relative_tolerance,
                slip_m: self.relative_tolerance,
                log_state: self.relative_tolerance,
                max_step_s: self.max_step_years * YEAR_S,
            },
            event_slip_rate_m_s: self.event_slip_rate_m_s,
            sample_s: self.sample_s,
            stations_m: self.stations_depth_m.clone(),
            max_steps: steps.unwrap_or(1) as u64,
        }
    }

    /// The explicit phases of a fully dynamic run, checked.
    fn dynamic(&self, scene: &Scene, ck: &mut Checker) -> DynamicSpec {
        let above = self.dynamic_above_m_s.unwrap_or(DynamicSpec::ABOVE_M_S);
        let below = self.static_below_m_s.unwrap_or(DynamicSpec::BELOW_M_S.min(above));
        ck.positive("cycles.dynamic_above_m_s", above);
        ck.range("cycles.static_below_m_s", below, 0.0, true, above, false);
        let lc = scene.lc_m;
        let extent = [scene.dims.ny as f64 * lc, scene.dims.nz as f64 * lc];
        let default_block =
            [(1.5 * self.frictional_depth_m).min(extent[0]), (1.5 * self.frictional_depth_m).min(extent[1])];
        let block = self.dynamic_block_m.unwrap_or(default_block);
        ck.range("cycles.dynamic_block_m[0]", block[0], self.frictional_depth_m, false, extent[0], false);
        ck.range("cycles.dynamic_block_m[1]", block[1], 4.0 * lc, false, extent[1], false);
        let damping = self.dynamic_damping.unwrap_or(DynamicSpec::DAMPING);
        ck.range("cycles.dynamic_damping", damping, 0.0, false, 1.0, false);
        DynamicSpec { above_m_s: above, below_m_s: below, block_m: block, damping }
    }
}

impl HeterogeneitySection {
    /// The fields it asks for, checked: each spread within 0–2 and one of them > 0, a
    /// correlation length the nodes resolve, and the process zone resolved where L is
    /// smallest and b largest at three standard deviations (`Λ₀ ≥ 3·Lc` there).
    fn build(&self, scene: &Scene, frictional_depth_m: f64, ck: &mut Checker) -> Heterogeneity {
        let keys = [
            ("cycles.heterogeneity.log_a_std", self.log_a_std),
            ("cycles.heterogeneity.log_b_std", self.log_b_std),
            ("cycles.heterogeneity.log_dc_std", self.log_dc_std),
        ];
        for (key, v) in keys {
            ck.range(key, v, 0.0, false, 2.0, false);
        }
        if keys.iter().all(|(_, v)| *v == 0.0) {
            ck.push(
                "cycles.heterogeneity",
                "(all spreads 0)",
                "at least one of log_a_std, log_b_std, log_dc_std > 0 (or leave the section out)",
            );
        }
        let lc = scene.lc_m;
        ck.range(
            "cycles.heterogeneity.correlation_length_m",
            self.correlation_length_m,
            2.0 * lc,
            false,
            frictional_depth_m,
            false,
        );
        ck.range("cycles.heterogeneity.hurst", self.hurst, 0.0, true, 1.0, false);
        if let (Some(fault), NodeFriction::RateState(node)) = (&scene.fault, scene.friction.base(0))
            && self.log_dc_std >= 0.0
            && self.log_b_std >= 0.0
        {
            let (_, _, c44) = stickslip_solver::material::lattice_elastic_constants(scene.young_pa, scene.poisson);
            let sigma = fault.normal_pa.iter().copied().fold(0.0, f64::max);
            let dc = node.dc_m * Heterogeneity::span(self.log_dc_std)[0];
            let b = node.b * Heterogeneity::span(self.log_b_std)[1];
            let extreme = NodeFriction::RateState(RateStateNode { dc_m: dc, b, ..node });
            let zone = extreme.cohesive_zone_m(c44, sigma).unwrap_or(f64::INFINITY);
            if zone < LEAST_ZONE_NODES * lc {
                ck.push(
                    "block.lc_m",
                    num(lc),
                    format!(
                        "at most Λ₀/{LEAST_ZONE_NODES} = {:.4e} m where the fields make the process zone smallest (L = \
                         {:.4e} m and b = {:.4e} at three standard deviations): Λ₀ = (9π/32)·μ·L/(b·σn) = {:.4e} m \
                         (smaller spreads, a longer dc_m or smaller modules resolve it)",
                        zone / LEAST_ZONE_NODES,
                        dc,
                        b,
                        zone
                    ),
                );
            }
        }
        Heterogeneity {
            log_a_std: self.log_a_std,
            log_b_std: self.log_b_std,
            log_dc_std: self.log_dc_std,
            correlation_length_m: self.correlation_length_m,
            hurst: self.hurst,
        }
    }
}
