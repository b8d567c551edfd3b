//! The scene's sections: the block, its friction, boundaries and loading, the fault, the time
//! step and what a run costs, the stiffness and the records.

use stickslip_solver::boundary::absorbing::impedances;
use stickslip_solver::inspect::FaultReading;
use stickslip_solver::inspect::{Inspection, PROBE_WARM_UP_STEPS};
use stickslip_solver::laws::{NodeFriction, RateStateStart, describe};
use stickslip_solver::memory::LONG_RUN_BAR_UPDATES;
use stickslip_solver::scene::{SettleMethod, TimeStep};
use stickslip_solver::{Model, NodeId, Scene};

use super::{N, Section, duration, position, round};
use crate::check::approx;

/// The block: modules, size, nodes, bars, contact nodes and mass.
pub fn block(model: &Model, facts: &Inspection) -> Section {
    let scene = model.scene();
    let e = model.lattice().extent();
    let mut s = Section::default();
    s.push(
        "block",
        format!(
            "block {}×{}×{} modules of Lc = {} m ({} × {} × {} m): {} nodes, {} bars, {} contact nodes, mass {} kg",
            scene.dims.nx,
            scene.dims.ny,
            scene.dims.nz,
            N(scene.lc_m),
            round(e[0]),
            round(e[1]),
            round(e[2]),
            facts.nodes,
            facts.bars,
            facts.contact_nodes,
            approx(facts.mass_kg)
        ),
    );
    s
}

/// The friction: the law and its coefficients with the CV of μ (`law`), and the friction map's
/// regions, base node by base node (`map`, when there is one).
pub fn describe_friction(model: &Model) -> Section {
    let scene = model.scene();
    let mut s = Section::default();
    let law = scene.friction.law;
    s.push(
        "law",
        format!(
            "friction: {} ({}), CV of μ {}",
            law.name(),
            describe(&law.node(1.0).coefficients(), |_, c| round(c.value).to_string()),
            N(scene.friction.mu_cv)
        ),
    );
    let Some(map) = &scene.friction.map else { return s };
    s.push("map", format!("friction map ({} base nodes):", map.nodes.len()));
    let background = map.region.iter().filter(|r| r.is_none()).count();
    if background > 0 {
        s.push("map", format!("  background ([friction]): {background} nodes"));
    }
    let span = |values: &mut dyn Iterator<Item = f64>| {
        values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)))
    };
    let contact = model.lattice().contact_nodes();
    for (i, r) in map.regions.iter().enumerate() {
        let members: Vec<usize> = (0..map.nodes.len()).filter(|&c| map.region[c] == Some(i as u16)).collect();
        if members.is_empty() {
            s.push("map", format!("  {}: no base node (covered by patches of higher priority)", r.name));
            continue;
        }
        let range = |k: usize| {
            let (lo, hi) = span(&mut members.iter().map(|&c| map.nodes[c].coefficients()[k].value));
            if lo == hi { format!("{}", N(lo)) } else { format!("{}…{}", N(lo), N(hi)) }
        };
        let (x0, x1) = span(&mut members.iter().map(|&c| model.lattice().position(contact[c])[0]));
        let (x0, x1) = (round(x0), round(x1));
        s.push(
            "map",
            format!(
                "  {} ({}): {} nodes, x {}…{} m, {}",
                r.name,
                r.kind.name(),
                members.len(),
                x0,
                x1,
                describe(&map.nodes[members[0]].coefficients(), |k, _| range(k)),
            ),
        );
    }
    s
}

/// The boundaries: the driver nodes (`drivers`), the loading plate (`plate`), the normal load
/// (`normal_load`) and the absorbing faces (`absorbing`), those the scene has.
pub fn describe_boundaries(model: &Model) -> Section {
    let scene = model.scene();
    let mut s = Section::default();
    let d = scene.drivers();
    if d.is_empty() {
        s.push("drivers", "drivers: none");
    } else {
        s.push(
            "drivers",
            format!(
                "drivers: {}{}",
                d.iter().take(12).map(|&d| position(model, d)).collect::<Vec<_>>().join("; "),
                if d.len() > 12 { format!("; … and {} more", d.len() - 12) } else { String::new() }
            ),
        );
    }
    if let Some(p) = scene.plate() {
        s.push(
            "plate",
            format!(
                "loading plate: face {} ({} nodes) on springs of {:.4e} N/m in all, moving by Eq. 12 in x",
                p.face.name(),
                p.nodes.len(),
                p.stiffness()
            ),
        );
    }
    if let Some(n) = scene.normal_load() {
        s.push("normal_load", format!("normal load: {} Pa on the top face ({:.4e} N)", N(n.pressure_pa), n.total()));
    }
    if !scene.absorbing().is_empty() {
        let (zp, zs) = impedances(scene);
        s.push(
            "absorbing",
            format!(
                "absorbing faces {} (dashpots ρCp = {:.4e} and ρCs = {:.4e} Pa·s/m per m² of face)",
                scene.absorbing().iter().map(|f| f.name()).collect::<Vec<_>>().join(", "),
                zp,
                zs
            ),
        );
    }
    s
}

/// A fault scene (docs/model.md §15): tractions, where rupture starts and the cohesive zone
/// against the lattice (`fault`), and the lattice's wave speeds (`waves`); empty when the scene
/// is not a fault.
pub fn fault(model: &Model, first_seed: u64) -> Section {
    let scene = model.scene();
    let mut s = Section::default();
    let Some(r) = FaultReading::of(model) else { return s };
    let mpa = |(a, b): (f64, f64)| {
        if a == b { format!("{:.2} MPa", N(a / 1e6)) } else { format!("{:.2} … {:.2} MPa", N(a / 1e6), N(b / 1e6)) }
    };
    s.push(
        "fault",
        format!(
            "fault (the base as one side of a planar fault, slip = 2 × the face's displacement; friction heals: {}): \
             normal stress {}, initial shear stress {}",
            scene.friction.heals,
            mpa(r.normal_pa),
            mpa(r.shear_pa)
        ),
    );
    let overburden = scene.fault.as_ref().and_then(|f| f.overburden_gradient_pa_m);
    if let Some(f) = scene.fault.as_ref()
        && let Some(g) = f.overburden_gradient_pa_m
    {
        // The largest normal stress before the overburden's share (the uniform one, or the
        // deepest of a grid's), and the share of the surface row (contact node 0 is at y = 0).
        let sigma = f.normal_pa.iter().zip(&f.depth_scale).map(|(n, s)| n / s).fold(0.0, f64::max);
        s.push(
            "fault",
            format!(
                "overburden: the effective normal stress grows from the surface (y = 0) at {} Pa/m and reaches {:.2} MPa \
                 at d* = {:.0} m; shallower than d* every traction (the seed's random field, nucleation and overstress \
                 too) is scaled by g·d/σn, and the surface row (mean depth Lc/4 = {} m) keeps {:.3} of it",
                N(g),
                N(sigma / 1e6),
                N(sigma / g),
                N(0.25 * scene.lc_m),
                N(f.depth_scale[0])
            ),
        );
    }
    if let Some(n) = scene.fault.as_ref().and_then(|f| f.nucleation) {
        s.push(
            "fault",
            format!(
                "nucleation per seed: a {} m square at {:.2} MPa along x{}, its centre drawn uniformly in x {}…{} m, \
                 y {}…{} m (seed {}: at ({:.0}, {:.0}) m)",
                N(n.size_m),
                N(n.shear_pa / 1e6),
                if overburden.is_some() { " (× the overburden's share at its depth)" } else { "" },
                N(n.x_m[0]),
                N(n.x_m[1]),
                N(n.y_m[0]),
                N(n.y_m[1]),
                first_seed,
                N(n.centre(first_seed)[0]),
                N(n.centre(first_seed)[1])
            ),
        );
    }
    if let Some(o) = scene.fault.as_ref().and_then(|f| f.overstress) {
        s.push(
            "fault",
            format!(
                "smooth overstress: Δτ₀ = {:.2} MPa along x{} at ({:.0}, {:.0}) m, Δτ₀·F(r)·G(t) with F(r) = \
                 exp(r²/(r² − R²)) within R = {} m and G(t) = exp((t − T)²/(t(t − 2T))) over T = {} s",
                N(o.overstress_pa / 1e6),
                if overburden.is_some() { " (× the overburden's share)" } else { "" },
                N(o.centre_m[0]),
                N(o.centre_m[1]),
                N(o.radius_m),
                N(o.rise_s)
            ),
        );
    }
    let copies = scene.fault_copies();
    if copies > 1.0 {
        s.push(
            "fault",
            format!(
                "mirror: the base's nodes on a face across the fault are held in y, a mirror plane: the block is 1/{copies} \
                 of the fault, and the source table counts the mirror image too (ruptured area and M0 ×{copies})"
            ),
        );
    }
    if let NodeFriction::RateState(n) = scene.friction.law.background {
        // Under rate and state no node holds: each slides from the first step.
        s.push(
            "fault",
            match n.start {
                RateStateStart::Balanced(v) => format!(
                    "rate and state: every node slides from the first step at Vᵢ = {v:e} m/s, its θ₀ balancing its \
                     initial traction (σ·f(Vᵢ, θ₀) = τ0)"
                ),
                _ => "rate and state: every node slides from the first step at the rate its traction and θ₀ give"
                    .to_string(),
            },
        );
    } else {
        let per_seed = scene.fault.as_ref().is_some_and(|f| f.nucleation.is_some());
        let excess = r
            .median_s
            .map_or(String::new(), |s| format!(", median strength excess S = (τs − τ0)/(τ0 − τd) = {:.2}", N(s)));
        s.push(
            "fault",
            if r.overstressed.0 == 0 && per_seed {
                format!("before the seed's square: {} nodes can slip (above μd·σn){excess}", r.can_slip)
            } else if r.overstressed.0 == 0 {
                "⚠ no node starts above its static strength μs·σn: nothing nucleates unless a random field or a patch \
                 overstresses some ([[fault.patches]] with shear_stress_pa above μs·normal_stress_pa)"
                    .to_string()
            } else {
                format!(
                    "nucleation: {} nodes ({:.4e} m²) start above their static strength μs·σn and slide from the first \
                     step; {} nodes can slip (above μd·σn){excess}",
                    r.overstressed.0, r.overstressed.1, r.can_slip
                )
            },
        );
    }
    if let Some(l) = r.cohesive_zone_m {
        let per = l / scene.lc_m;
        s.push(
            "fault",
            format!(
                "cohesive zone Λ0 = {} ≥ {l:.4e} m = {:.1} × Lc{}",
                scene.friction.law.background.cohesive_zone_formula(),
                N(per),
                if per < 3.0 {
                    " ⚠ under-resolved (fewer than 3 nodes): rupture speed and slip rates depend on Lc"
                } else {
                    ""
                }
            ),
        );
    }
    if let Some(h) = r.nucleation_m {
        s.push(
            "fault",
            format!(
                "nucleation size h* = (π/2)·μ·b·L/((b − a)²·σn) ≥ {h:.4e} m = {:.1} × Lc (Rubin & Ampuero 2005)",
                N(h / scene.lc_m)
            ),
        );
    }
    let (zp, zs) = impedances(scene);
    let rho = scene.density_kg_m3;
    let band = scene
        .usable_band(0.05)
        .map(|b| format!(", waves within 5% of these speeds up to {:.3} Hz", N(b.f_max_hz)))
        .unwrap_or_default();
    s.push("waves", format!("lattice wave speeds Cp = {:.1} m/s, Cs = {:.1} m/s{band}", N(zp / rho), N(zs / rho)));
    s
}

/// The critical step over the seeds inspected (`critical`), the time step it gives (`step`) and
/// the steps between records (`record_every`, when the record has an interval). `seeds` is the
/// pipeline's seed count.
pub fn critical_step(scene: &Scene, facts: &Inspection, seeds: usize) -> Section {
    let mut s = Section::default();
    let (lo, hi) = facts.critical_range_s();
    let which = if scene.young_cv == 0.0 {
        "for every seed (young_cv = 0: every seed's lattice is the same)".to_string()
    } else if facts.critical.len() == seeds {
        format!("over the pipeline's {} seeds", facts.critical.len())
    } else {
        format!("over its first {} of {} seeds (--seeds N for more)", facts.critical.len(), seeds)
    };
    let how = if facts.critical.iter().all(|(_, c)| c.iterations == 0) {
        " (the bound from each node's bars, docs/model.md §2)"
    } else {
        ""
    };
    s.push(
        "critical",
        format!("critical step {lo:.4e} … {hi:.4e} s {which}{how}; paper's 0.6·Lc/Cp = {:.4e} s", facts.paper_bound_s),
    );
    s.push(
        "step",
        match scene.time_step {
            TimeStep::Fraction(f) => {
                format!("time step: {f} of each seed's critical step ({:.4e} … {:.4e} s)", f * lo, f * hi)
            }
            TimeStep::Fixed(dt) => format!("time step: {dt:e} s ({:.3} of the smallest critical step)", N(dt / lo)),
        },
    );
    if let Some(iv) = scene.record.interval_s {
        let k = |dt: f64| (iv / dt).round().max(1.0);
        let (k_lo, k_hi) = match scene.time_step {
            TimeStep::Fraction(f) => (k(f * hi), k(f * lo)),
            TimeStep::Fixed(dt) => (k(dt), k(dt)),
        };
        let steps = if k_lo == k_hi { format!("{k_lo}") } else { format!("{k_lo}–{k_hi}") };
        s.push(
            "record_every",
            format!("recorded every {steps} steps (the nearest whole number to {} s; Δt does not depend on it)", N(iv)),
        );
    }
    s
}

/// A timed probe of a scene's steps and what it says of a run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Probe {
    /// Bars of the lattice.
    pub bars: usize,
    /// Steps of the self-weight stage, at most, and of the shear stage.
    pub steps: (u64, u64),
    /// Bar-updates of one seed.
    pub updates: f64,
    /// Seconds per step, timed.
    pub per_step_s: f64,
    /// Seconds of a run's set-up (the lattice, the seed's stiffness and critical step).
    pub setup_s: f64,
    /// Threads the probe stepped on when more than one.
    pub threads: Option<usize>,
}

/// What one seed's run costs, from a timed probe of its steps.
pub fn run_cost(scene: &Scene, p: &Probe) -> Section {
    let (settle, shear) = p.steps;
    let on = p.threads.map_or("one thread".into(), |t| format!("{t} threads"));
    // With the skip-ahead the count bounds the run: the quasi-static stretches are jumped.
    let bound = if scene.skip_ahead.enabled { "at most " } else { "" };
    let mut s = Section::default();
    s.push(
        "run",
        format!(
            "run: {bound}{} steps per seed ({}shear {shear}), {bound}{:.3e} bar-updates; {bound}about {} per seed on \
             {on} ({} of set-up — the lattice, the seed's stiffness and critical step, as timed here — and the steps \
             at {:.3e} s each, a timed probe after {PROBE_WARM_UP_STEPS} warm-up steps: {:.3e} bar-updates/s){}",
            settle + shear,
            if settle > 0 { format!("self-weight up to {settle} + ") } else { String::new() },
            p.updates,
            duration(p.setup_s + p.per_step_s * (settle + shear) as f64),
            duration(p.setup_s),
            p.per_step_s,
            p.bars as f64 / p.per_step_s,
            if scene.skip_ahead.enabled {
                " — the skip-ahead jumps the quasi-static stretches, so the run steps far fewer"
            } else if p.updates > LONG_RUN_BAR_UPDATES {
                " — a long run, accepted with --allow-long"
            } else {
                ""
            }
        ),
    );
    s
}

/// The effective stiffness of the block along x and z (static solves of `seed`'s lattice or of a
/// sample block), or why it was not solved.
pub fn stiffness(scene: &Scene, facts: &Inspection, seed: u64) -> Section {
    let mut s = Section::default();
    let on = if facts.moduli_of == scene.dims {
        String::new()
    } else {
        let d = facts.moduli_of;
        format!(
            " of a {}×{}×{} sample block of this material (--full-statics solves the whole block)",
            d.nx, d.ny, d.nz
        )
    };
    if let Some(why) = &facts.unsolved {
        s.push("unsolved", format!("effective stiffness{on}: not solved ({why}); the run does not need it"));
    }
    for m in &facts.moduli {
        let name = |a: usize| ["x", "y", "z"][a];
        let others: Vec<usize> = (0..3).filter(|&a| a != m.axis).collect();
        s.push(
            "moduli",
            format!(
                "effective stiffness along {}{on} (static solve, uniaxial stress, seed {}): E = {:.4e} Pa ({:.3} of \
                 E), ν_{}{} = {:.3}, ν_{}{} = {:.3}",
                name(m.axis),
                seed,
                m.young_pa,
                m.young_pa / scene.young_pa,
                name(m.axis),
                name(others[0]),
                m.poisson[0],
                name(m.axis),
                name(others[1]),
                m.poisson[1]
            ),
        );
    }
    s
}

/// A block on its base read as a spring-slider: the self-weight's normal stress and the
/// base's strength (`stress`), the slider and the verdict on stick-slip (`slider`); empty for a
/// fault, which has no weight on a base.
pub fn spring_slider(scene: &Scene, facts: &Inspection) -> Section {
    let mut s = Section::default();
    if scene.is_fault() {
        return s;
    }
    s.push(
        "stress",
        format!(
            "self-weight normal stress {:.1} Pa, sliding strength μs·σ = {:.1} Pa",
            N(facts.self_weight_stress_pa),
            N(facts.strength_pa)
        ),
    );
    let sl = &facts.slider;
    if sl.block_n_m.is_nan() {
        let why = match &sl.block_note {
            Some(note) => {
                format!("the block's stiffness under its load is a static solve of all {} bars, {note}", facts.bars)
            }
            None => format!(
                "the block's stiffness under its load needs a static solve of all {} bars: --full-statics",
                facts.bars
            ),
        };
        s.push(
            "slider",
            format!(
                "as a spring-slider: N = {:.4e} N, strength μs·N = {:.4e} N, tips at {:.4e} N; k not solved ({why}), \
                 plate springs {:.4e} N/m, k_c = {} = {:.4e} N/m",
                sl.normal_n, sl.strength_n, sl.tipping_n, sl.plate_n_m, sl.critical_formula, sl.critical_n_m
            ),
        );
    } else {
        s.push(
            "slider",
            format!(
                "as a spring-slider: N = {:.4e} N, strength μs·N = {:.4e} N, tips at {:.4e} N; k = {:.4e} N/m (block \
                 under the load {:.4e}, plate springs {:.4e}), k_c = {} = {:.4e} N/m, swing damping \
                 D/(2ω) = {:.3}",
                sl.normal_n,
                sl.strength_n,
                sl.tipping_n,
                sl.k_n_m,
                sl.block_n_m,
                sl.plate_n_m,
                sl.critical_formula,
                sl.critical_n_m,
                N(sl.damping_ratio)
            ),
        );
    }
    s.push(
        "slider",
        format!(
            "  → {} (the rigid slider's reading; docs/model.md §12 says where a lattice block differs)",
            crate::keys::verdict(sl, &scene.friction.law)
        ),
    );
    s
}

/// The loading stages: a block's self-weight and shear stages, or a fault's run from its
/// prestressed state.
pub fn stages(scene: &Scene) -> Section {
    let mut s = Section::default();
    let sw = &scene.self_weight;
    let sh = &scene.shear;
    if scene.is_fault() {
        s.push(
            "run",
            format!(
                "run: {} s from the prestressed state at rest, D = {} 1/s, no self-weight stage{}",
                N(sh.duration_s),
                N(sh.damping_per_s),
                if scene.drivers().is_empty() { ", no driver" } else { "" }
            ),
        );
        return s;
    }
    s.push(
        "self_weight",
        format!(
            "self-weight: {}",
            match sw.method {
                SettleMethod::Static =>
                    "solved statically (falls back to damped settling if friction cannot hold it)".into(),
                SettleMethod::Dynamic => format!(
                    "damped settling, D = {} 1/s, until out-of-balance/weight < {:e}",
                    N(sw.damping_per_s),
                    sw.settle_tolerance
                ),
            }
        ),
    );
    s.push(
        "shear",
        format!(
            "shear: u̇f = {} m/s (t0 = {} s), D = {} 1/s, for {} s",
            N(sh.velocity_m_s),
            N(sh.rise_time_s),
            N(sh.damping_per_s),
            N(sh.duration_s)
        ),
    );
    s
}

/// What is recorded: the interface's channels (`record`), every control node with its quantities
/// (`control`, also those given by position or by a set, as the README promises) and a warning
/// for a control node on the base (`warning`).
pub fn record(model: &Model) -> Section {
    let scene = model.scene();
    let r = &scene.record;
    let mut s = Section::default();
    s.push(
        "record",
        format!(
            "record: {}, interface {}{}{}{}",
            r.interval_s.map_or("every step".to_string(), |iv| format!("every {} s", N(iv))),
            r.interface.iter().map(|q| q.name()).collect::<Vec<_>>().join(", "),
            if r.energy { ", energy terms" } else { "" },
            if r.slip_onsets { ", slip onsets" } else { "" },
            if r.settling { ", the self-weight stage too" } else { "" },
        ),
    );
    let mut groups: Vec<(NodeId, Vec<String>)> = Vec::new();
    for c in &r.control {
        let what = format!("{} {}", c.quantity.name(), c.component.name());
        match groups.iter_mut().find(|(n, _)| *n == c.node) {
            Some((_, w)) => w.push(what),
            None => groups.push((c.node, vec![what])),
        }
    }
    let contact = model.lattice().contact_nodes();
    for (node, what) in &groups {
        s.push("control", format!("control {}: {}", position(model, *node), what.join(", ")));
    }
    for (node, _) in groups.iter().filter(|(n, _)| contact.contains(n)) {
        s.push(
            "warning",
            format!(
                "warning: control node {} is a base contact node: it records the motion of the frictional contact \
                 (held, sliding or lifting), not of the block above it (a number written for another block size \
                 names another node on this one: give at_m instead)",
                position(model, *node)
            ),
        );
    }
    s
}

/// The medium (docs/model.md §18): the layers with what the lattice carries in each, the Q band
/// and its fit, the dashpots; empty for the homogeneous elastic `[material]`.
pub fn medium(scene: &Scene) -> Section {
    let mut s = Section::default();
    let medium = &scene.medium;
    if medium.is_default() {
        return s;
    }
    let zones = scene.zones();
    let band = |z: &stickslip_solver::medium::Zone| scene.zone_band(z, 0.05).map_or(f64::NAN, |b| b.f_max_hz);
    match &medium.profile {
        Some(p) => {
            s.push(
                "medium",
                format!(
                    "medium: {} layers below {} (the Earth's surface), V_S30 {:.0} m/s; the lattice takes each layer's Vs and ρ, \
                     its Vp follows at ν = {} (√3·Vs at 0.25); a surface station stands in the lattice on Vs {:.0} m/s (the \
                     top module's travel-time mean)",
                    p.layers.len(),
                    p.surface.name(),
                    p.vs30(),
                    N(scene.poisson),
                    scene.lattice_surface_vs_m_s()
                ),
            );
            for ((i, (l, top)), z) in p.layers.iter().zip(p.tops()).enumerate().zip(&zones) {
                let bottom =
                    if l.thickness_m.is_finite() { format!("{} m", N(top + l.thickness_m)) } else { "∞".into() };
                s.push(
                    "medium",
                    format!(
                        "  layer {i}: {}–{bottom}, Vs {:.0} m/s, Vp {:.0} m/s (profile {:.0}), ρ {:.0} kg/m³, Q {} (profile Qp \
                         {:.0}, Qs {:.0}); a lattice of it would carry waves to {:.3} Hz{}",
                        N(top),
                        l.vs_m_s,
                        z.vp_m_s,
                        l.vp_m_s,
                        l.density_kg_m3,
                        if z.q().is_finite() { format!("{:.0}", z.q()) } else { "∞".into() },
                        l.qp,
                        l.qs,
                        band(z),
                        if l.thickness_m < scene.lc_m { " (thinner than a module: averaged into its bars)" } else { "" }
                    ),
                );
            }
        }
        None => s.push(
            "medium",
            format!(
                "medium: the homogeneous [material] (Vs {:.0} m/s), Q {}; the lattice carries waves to {:.3} Hz",
                zones[0].vs_m_s,
                if zones[0].q().is_finite() { format!("{:.0}", zones[0].q()) } else { "∞".into() },
                band(&zones[0])
            ),
        ),
    }
    if medium.profile.is_some() {
        let slowest = scene.slowest_carried();
        s.push(
            "medium",
            format!(
                "  the lattice's slowest module carries Vs {:.0} m/s: waves within 5% of their speeds to {:.3} Hz there",
                slowest.vs_m_s,
                band(&slowest)
            ),
        );
    }
    if let Some(a) = &medium.attenuation {
        let misfit = zones.iter().filter_map(|z| z.relaxation.as_ref()).map(|r| r.misfit()).fold(0.0, f64::max);
        s.push(
            "medium",
            format!(
                "attenuation: constant Q over {}–{} Hz (phase speeds the profile's at {} Hz) by {} relaxation mechanisms on \
                 every bar, Q flat within {:.1}%; one Q for P and S (Qp = Qs: a central-force lattice carries one); \
                 +{} bytes per bar and seed",
                N(a.band_hz[0]),
                N(a.band_hz[1]),
                N(a.reference_hz),
                stickslip_solver::medium::MECHANISMS,
                100.0 * misfit,
                4 * stickslip_solver::medium::MECHANISMS
            ),
        );
    }
    if medium.kelvin_voigt_s > 0.0 {
        s.push(
            "medium",
            format!(
                "Kelvin–Voigt damping: β = {} s on every bar (damping ratio β·ω/2 of a mode ω); the stable step is \
                 (√(1 + ξ²) − ξ) of the undamped one, ξ = β/Δt_c (in the step below)",
                N(medium.kelvin_voigt_s)
            ),
        );
    }
    s
}
