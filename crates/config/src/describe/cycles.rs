//! What `stickslip check` says of a `[cycles]` pipeline (docs/model.md §20): the run, the fault,
//! its friction along depth and the step control, from the validated pipeline alone (a cycle
//! run never builds its block).

use stickslip_solver::cycles::{DynamicSpec, Heterogeneity, YEAR_S};
use stickslip_solver::laws::{NodeFriction, RateStateNode};

use super::Section;
use crate::Pipeline;
use crate::numbers::num;

/// What `stickslip check` prints of a `[cycles]` pipeline, without building the block: the
/// slab, the fault's nodes, the friction along depth with its process zone and nucleation
/// size, the damping and the step control.
pub fn cycles(pipeline: &Pipeline) -> Section {
    let (scene, spec) = (&pipeline.scene, pipeline.cycles.as_ref().expect("a [cycles] pipeline"));
    let lc = scene.lc_m;
    let mu = scene.density_kg_m3 * scene.s_wave_speed().powi(2);
    let nodes = spec.frictional_nodes(lc, scene.dims.ny);
    let mut s = Section::default();
    s.push(
        "run",
        format!(
            "cycles: {}, {} years at the plate rate {} m/s; the antiplane mode of a slab of 1×{}×{} modules of {} m \
         ({} km down dip, {} km away from the fault), the fault's stiffness from its stencil by cosines along depth",
            if spec.dynamic.is_some() { "fully dynamic" } else { "quasi-dynamic" },
            num(spec.duration_s / YEAR_S),
            num(spec.plate_m_s),
            scene.dims.ny,
            scene.dims.nz,
            num(lc),
            num(scene.dims.ny as f64 * lc / 1e3),
            num(scene.dims.nz as f64 * lc / 1e3),
        ),
    );
    s.push(
        "fault",
        format!(
        "fault: {nodes} rate-and-state nodes from the free surface to {} km, creep at the plate rate below; radiation \
         damping η = μ/(2c_s) = {:.4e} Pa·s/m",
        num(spec.frictional_depth_m / 1e3),
        mu / (2.0 * scene.s_wave_speed())
    ),
    );
    if let (Some(fault), NodeFriction::RateState(node)) = (&scene.fault, scene.friction.base(0)) {
        let sigma = fault.normal_pa.iter().fold(0.0f64, |a, &b| a.max(b));
        let a_of = |j: usize| spec.a_at(j as f64 * lc).unwrap_or(node.a);
        let (a_min, a_max) = (0..nodes).fold((f64::INFINITY, 0.0f64), |(lo, hi), j| (lo.min(a_of(j)), hi.max(a_of(j))));
        let lambda0 = 9.0 * std::f64::consts::PI / 32.0 * mu * node.dc_m / (node.b * sigma);
        s.push(
            "friction",
            format!(
                "friction along depth: a {} … {}, b = {}, L = {} m; cohesive zone Λ0 = (9π/32)·μ·L/(b·σn) = {:.1} m \
             = {:.1} × Lc",
                num(a_min),
                num(a_max),
                num(node.b),
                num(node.dc_m),
                lambda0,
                lambda0 / lc
            ),
        );
        if node.b > a_min {
            let h = std::f64::consts::PI / 2.0 * mu * node.b * node.dc_m / ((node.b - a_min).powi(2) * sigma);
            s.push(
                "nucleation",
                format!(
                    "nucleation size h* = (π/2)·μ·b·L/((b − a)²·σn) = {:.0} m = {:.1} × Lc (Rubin & Ampuero 2005)",
                    h,
                    h / lc
                ),
            );
        }
        if let Some(h) = &spec.heterogeneity {
            s.push("heterogeneity", heterogeneity(h, pipeline, node, [a_min, a_max], mu, sigma, lc));
        }
    }
    s.push(
        "steps",
        format!(
        "steps: Dormand–Prince 5(4), relative tolerance {}, at most {} years a step, at most {} steps; an event while \
         the largest slip rate exceeds {} m/s",
        num(spec.tolerances.relative),
        num(spec.tolerances.max_step_s / YEAR_S),
        spec.max_steps,
        num(spec.event_slip_rate_m_s)
    ),
    );
    if let Some(d) = &spec.dynamic {
        let cs = scene.s_wave_speed();
        let step = DynamicSpec::STEP_FRACTION * lc / (2.0 * cs) / (1.0 + 2.0 * d.damping).sqrt();
        s.push(
            "dynamic",
            format!(
                "events: the lattice's explicit antiplane grid of {}×{} modules ({} km down dip, {} km from the fault; its \
                 bottom and far face absorbing) above a largest slip rate of {} m/s, quasi-dynamic again below {} m/s; \
                 step {:.4e} s ({} of the limit Lc/(2c_s·√(1 + 2γ))), Kelvin–Voigt damping γ = {} of the step; SH \
                 waves of 10 modules per wavelength up to {:.2} Hz",
                (d.block_m[0] / lc).round(),
                (d.block_m[1] / lc).round(),
                num(d.block_m[0] / 1e3),
                num(d.block_m[1] / 1e3),
                num(d.above_m_s),
                num(d.below_m_s),
                step,
                num(DynamicSpec::STEP_FRACTION),
                num(d.damping),
                cs / (10.0 * lc)
            ),
        );
    }
    s.push(
        "memory",
        format!(
            "memory: about {} (the fault's stiffness, {}the files' rows)",
            stickslip_solver::memory::human(spec.memory_bytes(scene)),
            if spec.dynamic.is_some() { "the explicit grid, " } else { "" }
        ),
    );
    s.push(
        "files",
        format!(
            "writes: {}seas/fltst_dpXXX at {} km, seas/global.dat, seas/devol.dat, tables/cycle_events.parquet{}",
            if spec.heterogeneity.is_some() { "per seed under seeds/seed-N/: " } else { "" },
            spec.stations_m.iter().map(|d| num(d / 1e3)).collect::<Vec<_>>().join(", "),
            if spec.heterogeneity.is_some() {
                "; over the seeds: tables/cycle_events.parquet, the catalogue tables (magnitude_frequency, b_values, \
                 recurrence_stats, aftershocks, omori, scaling) and figures/cycle_catalogue.png"
            } else {
                ""
            }
        ),
    );
    s
}

/// The line of `stickslip check` on a fault's random fields: their range at three standard
/// deviations (a around the profile `a_range` along depth), and there the law's process zone
/// and nucleation size (`mu` the shear modulus, `sigma` the largest normal stress).
fn heterogeneity(
    h: &Heterogeneity,
    pipeline: &Pipeline,
    node: RateStateNode,
    [a_min, a_max]: [f64; 2],
    mu: f64,
    sigma: f64,
    lc: f64,
) -> String {
    let [a_lo, a_hi] = [Heterogeneity::span(h.log_a_std)[0] * a_min, Heterogeneity::span(h.log_a_std)[1] * a_max];
    let [b_lo, b_hi] = Heterogeneity::span(h.log_b_std).map(|f| f * node.b);
    let [l_lo, l_hi] = Heterogeneity::span(h.log_dc_std).map(|f| f * node.dc_m);
    let extreme = NodeFriction::RateState(RateStateNode { a: a_lo, b: b_hi, dc_m: l_lo, ..node });
    let lambda0 = extreme.cohesive_zone_m(mu, sigma).unwrap_or(f64::NAN);
    let nucleation = extreme
        .nucleation_m(mu, sigma)
        .map(|h| format!(" and the smallest nucleation size h* = {h:.0} m = {:.1} × Lc", h / lc))
        .unwrap_or_default();
    format!(
        "random fields per seed ({} seed{}: {}): {}, g unit von Kármán fields along depth, correlation length {} m, \
         Hurst exponent {}; at three standard deviations a {a_lo:.4} … {a_hi:.4}, b {b_lo:.4} … {b_hi:.4}, L \
         {l_lo:.4e} … {l_hi:.4e} m; there Λ0 = {lambda0:.1} m = {:.1} × Lc{nucleation}",
        pipeline.seeds.len(),
        if pipeline.seeds.len() == 1 { "" } else { "s" },
        pipeline.seeds.iter().take(8).map(|s| s.to_string()).collect::<Vec<_>>().join(", "),
        [("a", h.log_a_std), ("b", h.log_b_std), ("L", h.log_dc_std)]
            .iter()
            .filter(|(_, s)| *s > 0.0)
            .map(|(c, s)| format!("{c}·exp({}·g)", num(*s)))
            .collect::<Vec<_>>()
            .join(", "),
        num(h.correlation_length_m),
        num(h.hurst),
        lambda0 / lc,
    )
}
