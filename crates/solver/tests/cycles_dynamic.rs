//! The fully dynamic cycle's explicit grid (docs/model.md §20.5): its masses against the
//! lattice's own, its SH wave speed and stability limit against their closed forms, its
//! absorbing faces, and a rate-and-state fault radiating a plane wave against the
//! radiation-damping equation that is exact for it.
//!
//! `cargo test --release -p stickslip-solver --test cycles_dynamic -- --nocapture` prints the figures.

mod common;

use stickslip_solver::cycles::{
    AntiplaneGrid, AntiplaneStencil, FaultStiffness, Flow, FullyDynamicFault, GridField, QuasiDynamicFault, Tolerances,
};
use stickslip_solver::geometry::NodeKind;
use stickslip_solver::laws::rate_state::steady_friction;
use stickslip_solver::laws::{Evolution, RateStateNode, RateStateStart};
use stickslip_solver::{Model, Scene};

const RHO: f64 = 2670.0;
const CS: f64 = 3464.0;

fn slab(ny: usize, nz: usize, lc: f64) -> Scene {
    common::antiplane_slab(ny, nz, lc)
}

fn grid(ny: usize, nz: usize, lc: f64, absorbing: bool) -> AntiplaneGrid {
    let model = Model::new(slab(4, 3, lc));
    let stencil = AntiplaneStencil::from_model(&model, &model.nominal_stiffness()).unwrap();
    AntiplaneGrid {
        ny,
        nz,
        stencil,
        density_kg_m3: RHO,
        absorbing_far: absorbing,
        absorbing_bottom: false,
        damping_s: 0.0,
    }
}

#[test]
fn the_grids_masses_are_the_lattices_lumped_masses_of_the_slab() {
    let (ny, nz) = (4, 3);
    let model = Model::new(slab(ny, nz, 100.0));
    let g = grid(ny, nz, 100.0, false);
    let mut corners = vec![0.0; (ny + 1) * (nz + 1)];
    let mut centres = vec![0.0; ny * nz];
    for (i, &m) in model.mass().iter().enumerate() {
        match model.lattice().kind(model.canonical(i)) {
            NodeKind::Corner([_, j, k]) => corners[j * (nz + 1) + k] += m,
            NodeKind::Centre([_, j, k]) => centres[j * nz + k] += m,
        }
    }
    for j in 0..=ny {
        for k in 0..=nz {
            let (got, want) = (g.corner_mass(j, k), corners[j * (nz + 1) + k]);
            assert!((got / want - 1.0).abs() < 1e-12, "corner ({j}, {k}): {got} against the model's {want}");
        }
    }
    for m in centres {
        assert!((g.centre_mass() / m - 1.0).abs() < 1e-12, "centre: {} against {m}", g.centre_mass());
    }
    let total: f64 = model.mass().iter().sum();
    println!("slab of 1 × {ny} × {nz} modules: {total:.6e} kg, every corner column and centre as the model lumps it");
}

/// A Gaussian pulse of `width` modules along z, uniform down dip (a plane SH wave), centred at
/// module `at` and travelling towards +z.
fn pulse(g: &AntiplaneGrid, at: f64, width: f64) -> GridField {
    let mut f = g.at_rest();
    let lc = g.stencil.lc_m;
    let c = g.shear_wave_m_s();
    let shape = |z: f64| (-((z - at) / width).powi(2)).exp();
    let slope = |z: f64| -2.0 * (z - at) / (width * width) * shape(z) / lc;
    let w = g.nz + 1;
    for j in 0..=g.ny {
        for k in 0..=g.nz {
            f.corner_u[j * w + k] = shape(k as f64);
            f.corner_v[j * w + k] = -c * slope(k as f64);
        }
    }
    for j in 0..g.ny {
        for k in 0..g.nz {
            f.centre_u[j * g.nz + k] = shape(k as f64 + 0.5);
            f.centre_v[j * g.nz + k] = -c * slope(k as f64 + 0.5);
        }
    }
    f
}

fn steps(g: &AntiplaneGrid, f: &mut GridField, dt: f64, n: usize) {
    let w = g.nz + 1;
    for _ in 0..n {
        g.forces(f);
        for j in 0..=g.ny {
            let m = g.corner_mass(j, 0);
            f.corner_v[j * w] += dt * f.corner_f[j * w] / m;
        }
        g.advance(f, dt);
    }
}

/// The pulse's peak along the corner row j = 1 (modules), by a parabola through the three
/// largest samples.
fn peak(g: &AntiplaneGrid, f: &GridField) -> f64 {
    let row = &f.corner_u[(g.nz + 1)..2 * (g.nz + 1)];
    let k = (1..g.nz).max_by(|&a, &b| row[a].total_cmp(&row[b])).unwrap();
    let (a, b, c) = (row[k - 1], row[k], row[k + 1]);
    k as f64 + 0.5 * (a - c) / (a - 2.0 * b + c)
}

#[test]
fn a_plane_sh_wave_travels_at_the_rocks_shear_speed() {
    let g = grid(2, 1200, 10.0, false);
    assert!((g.shear_wave_m_s() / CS - 1.0).abs() < 1e-9, "{} against {CS}", g.shear_wave_m_s());
    let dt = 0.9 * g.critical_step_s();
    let mut f = pulse(&g, 300.0, 30.0);
    let start = peak(&g, &f);
    let n = 1500;
    steps(&g, &mut f, dt, n);
    let speed = (peak(&g, &f) - start) * g.stencil.lc_m / (n as f64 * dt);
    println!(
        "plane SH pulse (30 modules wide) over {:.0} modules: {speed:.2} m/s against √(μ/ρ) = {CS} m/s ({:+.3}%)",
        peak(&g, &f) - start,
        100.0 * (speed / CS - 1.0)
    );
    assert!((speed / CS - 1.0).abs() < 2e-3, "{speed}");
}

/// The growth of the largest displacement of a rough field over 4000 steps of `ratio` times the
/// grid's limit with damping `β = γ·Δt`.
fn growth(gamma: f64, ratio: f64) -> f64 {
    let mut g = grid(20, 20, 10.0, false);
    let dt = ratio * g.critical_step_damped_s(gamma);
    g.damping_s = gamma * dt;
    let mut f = g.at_rest();
    // A deterministic rough field holds the highest mode.
    let mut x = 0.3f64;
    for u in f.corner_u.iter_mut().chain(f.centre_u.iter_mut()) {
        x = (x * 3.9 * (1.0 - x)).clamp(1e-6, 1.0 - 1e-6);
        *u = x - 0.5;
    }
    let largest = |f: &GridField| {
        f.corner_u
            .iter()
            .chain(&f.centre_u)
            .fold(0.0f64, |a, u| if u.is_finite() { a.max(u.abs()) } else { f64::INFINITY })
    };
    let u0 = largest(&f);
    steps(&g, &mut f, dt, 4000);
    largest(&f) / u0
}

#[test]
fn the_grids_damping_spreads_a_pulse_as_kelvin_voigt_viscosity_does() {
    // A Gaussian exp(−(z/w)²) under u_tt = c²u_zz + βc²u_zzt keeps its shape's Gaussian spectrum,
    // each wavenumber decaying as exp(−βc²k²t/2): at time t it is a Gaussian of w'² = w² + 2βc²t,
    // its peak w/w' of the start's.
    let (lc, width) = (10.0, 30.0);
    let peak_after = |gamma: f64| {
        let mut g = grid(2, 1200, lc, false);
        let dt = 0.9 * g.critical_step_damped_s(gamma);
        g.damping_s = gamma * dt;
        let mut f = pulse(&g, 300.0, width);
        let n = (1.95 / dt) as usize;
        steps(&g, &mut f, dt, n);
        let row = &f.corner_u[(g.nz + 1)..2 * (g.nz + 1)];
        (row.iter().fold(0.0f64, |a, &u| a.max(u)), g.damping_s, n as f64 * dt)
    };
    let (undamped, _, _) = peak_after(0.0);
    let (damped, beta, t) = peak_after(0.3);
    let w = width * lc;
    let want = w / (w * w + 2.0 * beta * CS * CS * t).sqrt();
    let got = damped / undamped;
    println!(
        "γ = 0.3 (β = {beta:.3e} s) over {t:.3} s: peak {got:.4} of the undamped grid's against w/√(w² + 2βc²t) = {want:.4} \
         (undamped: {undamped:.4} of the start's)"
    );
    assert!((got / want - 1.0).abs() < 0.01, "{got} against {want}");
}

#[test]
fn the_step_is_stable_just_below_its_closed_form_limit_and_not_above() {
    for gamma in [0.0, 0.1, 0.3] {
        let (below, above) = (growth(gamma, 0.99), growth(gamma, 1.01));
        let g = grid(20, 20, 10.0, false);
        println!(
            "γ = {gamma}: largest displacement after 4000 steps ×{below:.3} at 0.99 of Lc·√(ρLc/c)/(2√(1 + 2γ)) = {:.4e} s, \
             ×{above:.3e} at 1.01",
            g.critical_step_damped_s(gamma)
        );
        // Below the limit the highest mode only swings (undamped, its amplitude bounded by
        // 1/√(1 − (ωΔt/2)²)) or decays.
        assert!(below < 20.0, "γ = {gamma}: {below}");
        assert!(above > 1e6, "γ = {gamma}: {above}");
    }
}

#[test]
fn the_absorbing_faces_take_a_plane_wave_out() {
    let g = grid(2, 600, 10.0, true);
    let dt = 0.9 * g.critical_step_s();
    let mut f = pulse(&g, 300.0, 30.0);
    let e0 = g.energy(&f);
    // The pulse reaches the far face after 300 modules and is past it after ~400.
    let n = (500.0 * g.stencil.lc_m / CS / dt) as usize;
    steps(&g, &mut f, dt, n);
    let left = g.energy(&f) / e0;
    println!(
        "a plane SH pulse 30 modules wide leaves {:.2e} of its energy (amplitude {:.2}%)",
        left,
        100.0 * left.sqrt()
    );
    assert!(left < 1e-3, "{left}");
}

/// One node's rate-and-state friction for the radiation test.
fn node(l: f64, v_start: f64) -> RateStateNode {
    RateStateNode {
        a: 0.010,
        b: 0.015,
        dc_m: l,
        v0_m_s: 1e-6,
        f0: 0.6,
        evolution: Evolution::Aging,
        start: RateStateStart::State(l / v_start),
    }
}

#[test]
fn a_uniformly_slipping_fault_radiates_as_radiation_damping_says() {
    for gamma in [0.0, 0.1] {
        radiates(gamma);
    }
}

/// The plane-wave fault with the grid's damping `β = γ·Δt`.
fn radiates(gamma: f64) {
    // A face of 3 nodes slipping alike sends a plane SH wave into the block; its traction is
    // then exactly τ_s − (ρc_s/2)·V, the quasi-dynamic equation with K = 0.
    let (ny, nz, lc) = (2, 2000, 10.0);
    let mut g = grid(ny, nz, lc, true);
    let step_s = 0.9 * g.critical_step_damped_s(gamma);
    g.damping_s = gamma * step_s;
    let (sigma, l, v_start) = (50e6, 0.05, 1e-3);
    let friction = node(l, v_start);
    let eta = RHO * g.shear_wave_m_s() / 2.0;
    let tau0 = sigma * steady_friction(&friction, v_start) + eta * v_start + 2e6;
    let n = ny + 1;
    let quasi = QuasiDynamicFault {
        stiffness: FaultStiffness { nodes: n, k: vec![0.0; n * n], lc_m: lc, domain: [ny, nz] },
        friction: vec![friction; n],
        normal_pa: vec![sigma; n],
        shear0_pa: vec![tau0; n],
        eta_pa_s_m: eta,
        plate_m_s: 0.0,
    };
    let duration = 5.0;
    let tol = Tolerances { relative: 1e-10, slip_m: 1e-12, log_state: 1e-10, max_step_s: 1e-3 };
    // V of the middle node at every accepted step.
    let (mut reference, mut explicit) = (Vec::new(), Vec::new());
    quasi
        .run(quasi.start(), duration, &tol, 10_000_000, |s| {
            reference.push((s.t_s, s.slip_rate_m_s[1]));
            Flow::Continue
        })
        .unwrap();
    let dynamic = FullyDynamicFault {
        quasi: quasi.clone(),
        grid: g.clone(),
        dynamic_above_m_s: 0.0,
        static_below_m_s: 0.0,
        step_s,
    };
    dynamic
        .run(quasi.start(), duration, &tol, 10_000_000, |s| {
            explicit.push((s.t_s, s.slip_rate_m_s[1]));
            Flow::Continue
        })
        .unwrap();
    let at = |series: &[(f64, f64)], t: f64| {
        let i = series.partition_point(|p| p.0 < t).clamp(1, series.len() - 1);
        let ((t0, v0), (t1, v1)) = (series[i - 1], series[i]);
        v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    };
    let mut worst: f64 = 0.0;
    for t in [0.5, 1.0, 2.0, 3.0, 4.0, 5.0] {
        let (want, got) = (at(&reference, t), at(&explicit, t));
        println!(
            "γ = {gamma}, t = {t:.1} s: V {got:.6e} m/s explicit, {want:.6e} m/s by τ_s − ηV = σf(V, θ) ({:+.3}%)",
            100.0 * (got / want - 1.0)
        );
        worst = worst.max((got / want - 1.0).abs());
    }
    let growth = at(&reference, duration) / at(&reference, 0.0);
    assert!(growth > 10.0, "the test should cross a wide range of slip rates: ×{growth}");
    assert!(worst < 0.01, "{worst}");
}
