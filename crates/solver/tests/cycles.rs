//! Earthquake cycles (docs/model.md §20): the lattice's antiplane fault stiffness against a direct
//! solve of a slab's own operator and against the closed form of uniform slip in a half-space;
//! the quasi-dynamic integrator against the spring-slider's linear stability (Ruina 1983).
//!
//! `cargo test --release -p stickslip-solver --test cycles -- --nocapture` prints the figures.

mod common;

use nalgebra::DMatrix;
use stickslip_solver::cycles::{
    AntiplaneStencil, CycleState, FaultStiffness, Flow, QuasiDynamicFault, Tolerances, antiplane_links,
};
use stickslip_solver::laws::{Evolution, RateStateNode, RateStateStart};
use stickslip_solver::{Model, Scene};

const RHO: f64 = 2670.0;
const CS: f64 = 3464.0;

fn slab(ny: usize, nz: usize, lc: f64) -> Scene {
    common::antiplane_slab(ny, nz, lc)
}

fn stencil_of(ny: usize, nz: usize, lc: f64) -> (Model, AntiplaneStencil) {
    let model = Model::new(slab(ny, nz, lc));
    let k = model.nominal_stiffness();
    let stencil = AntiplaneStencil::from_model(&model, &k).expect("a homogeneous slab");
    (model, stencil)
}

#[test]
fn the_slabs_antiplane_stencil_carries_the_rocks_shear_modulus() {
    let (_, stencil) = stencil_of(4, 3, 100.0);
    let mu = RHO * CS * CS;
    let got = stencil.shear_modulus_pa();
    println!("antiplane shear modulus of the lattice {got:.6e} Pa against ρ·Cs² = {mu:.6e} Pa");
    assert!((got / mu - 1.0).abs() < 1e-9, "{got} against {mu}");
}

/// The face's stiffness by a direct solve of the slab's own operator (every corner and centre
/// node, links read from its bars): the face and the far face prescribed, the rest free.
fn direct_stiffness(model: &Model, ny: usize, nz: usize, lc: f64) -> DMatrix<f64> {
    let links = antiplane_links(model, &model.nominal_stiffness()).unwrap();
    let mut nodes: Vec<(usize, usize)> = links.keys().flat_map(|&(p, q)| [p, q]).collect();
    nodes.sort();
    nodes.dedup();
    let index = |p: &(usize, usize)| nodes.binary_search(p).unwrap();
    let n = nodes.len();
    let mut a = DMatrix::<f64>::zeros(n, n);
    for (&(p, q), &w) in &links {
        let (i, j) = (index(&p), index(&q));
        a[(i, i)] += w;
        a[(j, j)] += w;
        a[(i, j)] -= w;
        a[(j, i)] -= w;
    }
    let face: Vec<usize> = (0..=ny).map(|j| index(&(2 * j, 0))).collect();
    let held: Vec<bool> = nodes.iter().map(|&(_, k)| k == 0 || k == 2 * nz).collect();
    let free: Vec<usize> = (0..n).filter(|&i| !held[i]).collect();
    let aff = DMatrix::from_fn(free.len(), free.len(), |r, c| a[(free[r], free[c])]);
    let lu = aff.lu();
    let mut kmat = DMatrix::<f64>::zeros(ny + 1, ny + 1);
    for (l, &fl) in face.iter().enumerate() {
        // Face node l displaced by 1 (slip 2), everything else prescribed at 0.
        let rhs = nalgebra::DVector::from_fn(free.len(), |r, _| -a[(free[r], fl)]);
        let u_free = lu.solve(&rhs).unwrap();
        let mut u = vec![0.0; n];
        u[fl] = 1.0;
        for (r, &i) in free.iter().enumerate() {
            u[i] = u_free[r];
        }
        for (j, &fj) in face.iter().enumerate() {
            let force: f64 = (0..n).map(|c| a[(fj, c)] * u[c]).sum();
            let area = lc * lc * if j == 0 || j == ny { 0.5 } else { 1.0 };
            kmat[(j, l)] = force / area / 2.0;
        }
    }
    kmat
}

#[test]
fn the_fault_stiffness_is_the_slabs_own_static_response() {
    let (ny, nz, lc) = (12, 10, 50.0);
    let (model, stencil) = stencil_of(ny, nz, lc);
    let direct = direct_stiffness(&model, ny, nz, lc);
    let fast = FaultStiffness::antiplane(&stencil, ny + 1, ny, nz).unwrap();
    let scale = direct.iter().fold(0.0f64, |a, b| a.max(b.abs()));

    let mut worst = 0.0f64;
    for j in 0..=ny {
        for l in 0..=ny {
            worst = worst.max((fast.k[j * (ny + 1) + l] - direct[(j, l)]).abs() / scale);
        }
    }
    println!("fault stiffness by cosines against a direct solve of the slab: worst {worst:.1e} of max |K|");
    assert!(worst < 1e-10, "{worst}");
}

/// The shear traction change at depth z of uniform slip 1 m over [z1, z2] in a half-space
/// (screw dislocations at the patch's ends and their images in the free surface).
fn patch_closed_form(mu: f64, z1: f64, z2: f64, z: f64) -> f64 {
    mu / (2.0 * std::f64::consts::PI) * (1.0 / (z - z2) - 1.0 / (z - z1) + 1.0 / (z + z1) - 1.0 / (z + z2))
}

#[test]
fn uniform_slip_on_a_patch_stresses_the_fault_as_in_a_half_space() {
    let lc = 50.0;
    let (_, stencil) = stencil_of(4, 3, lc);
    let mu = stencil.shear_modulus_pa();
    // A patch from 5 to 10 km in a block 200 km deep and 200 km wide.
    let (j1, j2) = (100usize, 200usize);
    let nodes = 301;
    let (z1, z2) = ((j1 as f64 - 0.5) * lc, (j2 as f64 + 0.5) * lc);
    let mut worst = 0.0f64;
    for (ny, nz) in [(2000, 2000), (4000, 4000)] {
        let k = FaultStiffness::antiplane(&stencil, nodes, ny, nz).unwrap();
        let slip: Vec<f64> = (0..nodes).map(|j| if (j1..=j2).contains(&j) { 1.0 } else { 0.0 }).collect();
        let mut dtau = vec![0.0; nodes];
        k.traction_change(&slip, &mut dtau);
        println!("block {} km deep and wide:", ny as f64 * lc / 1e3);
        for j in [0usize, 50, 150, 175, 215, 250, 300] {
            let z = j as f64 * lc;
            let exact = patch_closed_form(mu, z1, z2, z);
            let rel = dtau[j] / exact - 1.0;
            println!(
                "  z = {:5.2} km: Δτ = {:9.5} kPa, closed form {:9.5} kPa ({:+.2}%)",
                z / 1e3,
                dtau[j] / 1e3,
                exact / 1e3,
                100.0 * rel
            );
            if ny == 4000 {
                worst = worst.max(rel.abs());
            }
        }
    }
    assert!(worst < 0.01, "{worst}");
}

/// One node on a spring of stiffness k (Pa/m): the spring-slider in the quasi-dynamic form,
/// started `perturbation` off steady state at the plate rate.
fn spring_slider(k: f64, a: f64, b: f64, perturbation: f64, evolution: Evolution) -> (QuasiDynamicFault, CycleState) {
    let (sigma, l, vp) = (50e6, 0.008, 1e-9);
    let node = RateStateNode {
        a,
        b,
        dc_m: l,
        v0_m_s: 1e-6,
        f0: 0.6,
        evolution,
        start: RateStateStart::State(l / vp * (1.0 + perturbation)),
    };
    let steady = stickslip_solver::laws::rate_state::steady_friction(&node, vp);
    let eta = RHO * CS / 2.0;
    let fault = QuasiDynamicFault {
        stiffness: FaultStiffness { nodes: 1, k: vec![k], lc_m: 1.0, domain: [1, 1] },
        friction: vec![node],
        normal_pa: vec![sigma],
        shear0_pa: vec![sigma * steady + eta * vp],
        eta_pa_s_m: eta,
        plate_m_s: vp,
    };
    let start = fault.start();
    (fault, start)
}

#[test]
fn a_spring_slider_oscillates_at_its_critical_stiffness_with_the_linear_period_under_both_laws() {
    let (a, b, sigma, l, vp) = (0.010, 0.015, 50e6, 0.008, 1e-9);
    let kc = (b - a) * sigma / l;
    let period = 2.0 * std::f64::consts::PI * l / vp * (a / (b - a)).sqrt();
    let tol = Tolerances { relative: 1e-10, slip_m: 1e-12, log_state: 1e-10, max_step_s: period / 200.0 };
    // Growth or decay of ln V's swing over 10 periods, and the period from its up-crossings.
    let swing = |ratio: f64, evolution: Evolution| {
        let (fault, start) = spring_slider(ratio * kc, a, b, 1e-3, evolution);
        let mut crossings = Vec::new();
        let (mut first, mut last) = (0.0f64, 0.0f64);
        let mut prev: Option<(f64, f64)> = None;
        fault
            .run(start, 10.0 * period, &tol, 10_000_000, |s| {
                let x = (s.slip_rate_m_s[0] / vp).ln();
                if s.t_s < period {
                    first = first.max(x.abs());
                }
                if s.t_s > 9.0 * period {
                    last = last.max(x.abs());
                }
                if let Some((t0, x0)) = prev
                    && x0 < 0.0
                    && x >= 0.0
                {
                    crossings.push(t0 + (s.t_s - t0) * (-x0) / (x - x0));
                }
                prev = Some((s.t_s, x));
                Flow::Continue
            })
            .unwrap();
        let measured = (crossings.last().unwrap() - crossings[0]) / (crossings.len() - 1) as f64;
        (first, last, measured)
    };
    let (f, l_, t) = swing(1.0, Evolution::Aging);
    println!(
        "k = k_c: |ln V/Vp| {f:.3e} in the first period, {l_:.3e} in the tenth; period {:.5} years against 2π(L/Vp)√(a/(b−a)) = {:.5} years",
        t / stickslip_solver::cycles::YEAR_S,
        period / stickslip_solver::cycles::YEAR_S
    );
    assert!((t / period - 1.0).abs() < 2e-3, "{t} against {period}");
    assert!((l_ / f - 1.0).abs() < 0.05, "neutral: {f} → {l_}");
    let (f, l_, _) = swing(1.1, Evolution::Aging);
    println!("k = 1.1 k_c: {f:.3e} → {l_:.3e}");
    assert!(l_ < 0.5 * f);
    let (f, l_, _) = swing(0.9, Evolution::Aging);
    println!("k = 0.9 k_c: {f:.3e} → {l_:.3e}");
    assert!(l_ > 2.0 * f);
    // The slip law linearises to the same system (θ̇/θ ≈ −(V/L)·(v + φ) for both laws).
    let (f, l_, t) = swing(1.0, Evolution::Slip);
    println!("slip law, k = k_c: {f:.3e} → {l_:.3e}; period {:.5} years", t / stickslip_solver::cycles::YEAR_S);
    assert!((t / period - 1.0).abs() < 2e-3, "{t} against {period}");
    assert!((l_ / f - 1.0).abs() < 0.05, "neutral: {f} → {l_}");
}
