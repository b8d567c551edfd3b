//! The base as one side of a planar fault between identical media (docs/model.md §15), against
//! closed forms: a prestress below the strength is held exactly; a uniform overstress drops the
//! fault's traction to exactly μd·σn and radiates a plane S wave whose particle velocity on the
//! fault is `Δτ/(ρ·Cs)`, so the slip rate is `2Δτ/(ρ·Cs)` (each side moving half of it).

mod common;

use stickslip_solver::fault::Fault;
use stickslip_solver::geometry::Face;
use stickslip_solver::laws::StaticDynamic;
use stickslip_solver::material::lattice_elastic_constants;
use stickslip_solver::scene::BoundarySpec;
use stickslip_solver::statics::critical_time_step;
use stickslip_solver::step::{Batch, LaneSetup};
use stickslip_solver::{Dims, Model, Scene};

const TAU0: f64 = 81.6e6;
const SIGMA_N: f64 = 120e6;
const MU_S: f64 = 0.677;
const MU_D: f64 = 0.525;

/// A column of 2 × 2 × `nz` modules of 100 m in rock (ρ 2670, Cp 6000, Cs 3464 m/s) whose base is
/// a fault under `tau0` and σn = 120 MPa with static/dynamic friction 0.677/0.525, its lateral faces
/// symmetry planes for a plane S wave along z polarised in x (they hold y and z), its top face
/// absorbing.
fn column(nz: usize, tau0: f64) -> Scene {
    let mut s = common::column(nz, 0);
    s.friction.law = StaticDynamic { mu_static: MU_S, mu_dynamic: MU_D }.into();
    let contacts = s.lattice().contact_nodes().len();
    s.fault = Some(Fault {
        shear_pa: vec![[tau0, 0.0]; contacts],
        normal_pa: vec![SIGMA_N; contacts],
        stochastic: None,
        nucleation: None,
        overstress: None,
        origin_m: [0.0; 2],
        depth_scale: Vec::new(),
        overburden_gradient_pa_m: None,
    });
    s.set_boundary(BoundarySpec::Absorbing(vec![Face::ZMax]));
    s
}

fn batch(model: &Model) -> Batch<'_, 1> {
    let k = model.nominal_stiffness();
    let dt = 0.5 * critical_time_step(model, &k).unwrap().dt_s;
    let lane = LaneSetup {
        dt_s: dt,
        stiffness: stickslip_solver::step::LaneStiffness::PerBar(k),
        friction: vec![1.0; model.contact().len()],
        strength: None,
        fault: model.fault_loads(7).unwrap(),
    };
    Batch::<1>::new(model, &[lane])
}

#[test]
fn a_prestress_below_the_strength_is_held_exactly() {
    // τ0 = 70 MPa < μs·σn = 81.24 MPa: every node sticks and nothing moves, to the last bit.
    let model = Model::new(column(10, 70e6));
    let mut b = batch(&model);
    for _ in 0..500 {
        b.step();
    }
    let v = b.view(0);
    let moved = (0..model.node_count()).flat_map(|i| v.displacement(i)).fold(0.0f64, |m, u| m.max(u.abs()));
    assert_eq!(moved, 0.0, "a held fault moved the block by {moved} m");
    for ci in 0..model.contact().len() {
        let c = v.node_contact(ci);
        assert!(!c.slipping);
        // The friction holds the prestress: τ = −R/A = τ0.
        let area = Face::ZMin.tributary_area(model.lattice(), model.canonical(model.contact()[ci] as usize));
        assert!((-c.friction_x / area - 70e6).abs() < 1e-6, "node {ci}: {} Pa", -c.friction_x / area);
        assert!((c.normal / area - SIGMA_N).abs() < 1e-6);
    }
}

#[test]
fn a_uniform_overstress_slides_at_the_closed_form_rate_and_drops_to_dynamic_friction() {
    let scene = column(60, TAU0);
    let (_, _, c44) = lattice_elastic_constants(scene.young_pa, scene.poisson);
    let rho = scene.density_kg_m3;
    let cs = (c44 / rho).sqrt();
    let drop = TAU0 - MU_D * SIGMA_N;
    let rate = 2.0 * drop / (rho * cs);
    let model = Model::new(scene);
    let mut b = batch(&model);
    let dt = b.params.dt(0);
    let (mut sum, mut n) = (0.0, 0);
    // The mean slip rate over each tenth of the run after the start: the lattice rings at its
    // highest frequencies after the sudden start (a spread of ±15% step to step), the mean must
    // not drift.
    let mut tenths = [0.0; 10];
    let steps = 400;
    for step in 0..steps {
        b.step();
        let v = b.view(0);
        for ci in 0..model.contact().len() {
            let c = v.node_contact(ci);
            let area = Face::ZMin.tributary_area(model.lattice(), model.canonical(model.contact()[ci] as usize));
            // Every node slides at once and for good, its traction exactly the dynamic strength.
            assert!(c.slipping, "node {ci} stuck at step {step}");
            let tau = -c.friction_x / area;
            assert!((tau / (MU_D * SIGMA_N) - 1.0).abs() < 1e-12, "node {ci}: τ = {tau} Pa");
            // Slip is twice the face's displacement.
            let u = v.displacement(model.contact()[ci] as usize)[0];
            assert!((c.slip - 2.0 * u).abs() <= 1e-15 * c.slip.abs());
            if step >= 40 {
                sum += c.slip_rate;
                n += 1;
                tenths[(step - 40) * 10 / (steps - 40)] += c.slip_rate;
            }
        }
    }
    let mean = sum / n as f64;
    let per = n as f64 / 10.0;
    let (lo, hi) =
        tenths.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| (a.min(t / per), b.max(t / per)));
    println!(
        "slip rate {mean:.5} m/s (means of each tenth {lo:.4}–{hi:.4}) over {:.2} s; closed form 2Δτ/(ρCs) = {rate:.5} m/s",
        steps as f64 * dt
    );
    assert!((mean / rate - 1.0).abs() < 0.005, "slip rate {mean} vs {rate}");
    assert!(hi / rate - 1.0 < 0.01 && 1.0 - lo / rate < 0.01, "the slip rate drifts: {lo}–{hi} vs {rate}");
}

#[test]
fn a_nucleation_square_lands_where_its_seed_draws_it_and_nowhere_else() {
    use stickslip_solver::fault::Nucleation;
    // A 20 × 20-module face of 100 m: a 500 m square at 90 MPa, its centre in x, y ∈ [600, 1400] m.
    let mut s = column(2, 60e6);
    s.dims = Dims::new(20, 20, 2);
    let lattice = s.lattice();
    let contacts = lattice.contact_nodes().len();
    let n = Nucleation { size_m: 500.0, shear_pa: 90e6, x_m: [600.0, 1400.0], y_m: [600.0, 1400.0] };
    s.fault = Some(Fault {
        shear_pa: vec![[60e6, 0.0]; contacts],
        normal_pa: vec![SIGMA_N; contacts],
        stochastic: None,
        nucleation: Some(n),
        overstress: None,
        origin_m: [0.0; 2],
        depth_scale: Vec::new(),
        overburden_gradient_pa_m: None,
    });
    s.boundaries.retain(|b| !matches!(b, BoundarySpec::Rollers(_)));
    let model = Model::new(s);
    let nodes = model.lattice().contact_nodes();
    let mut centres = Vec::new();
    for seed in 1..=20u64 {
        let c = n.centre(seed);
        assert_eq!(c, n.centre(seed), "the same seed draws the same centre");
        assert!((600.0..=1400.0).contains(&c[0]) && (600.0..=1400.0).contains(&c[1]), "{c:?}");
        centres.push(c);
        let loads = model.fault_loads(seed).unwrap().unwrap();
        let mut inside = 0;
        for (k, &id) in nodes.iter().enumerate() {
            let p = model.lattice().position(id);
            let area = Face::ZMin.tributary_area(model.lattice(), id);
            let in_square = (p[0] - c[0]).abs() <= 250.0 && (p[1] - c[1]).abs() <= 250.0;
            let expected = if in_square { 90e6 } else { 60e6 } * area;
            assert!((loads.shear_n[k][0] - expected).abs() <= 1e-9 * expected, "seed {seed} node {k}");
            inside += usize::from(in_square);
        }
        // A 500 m square on a 100 m grid covers 5 × 5 or 6 × 6 nodes (fewer at no edge here).
        assert!((25..=36).contains(&inside), "seed {seed}: {inside} nodes in the square");
    }
    // The seeds spread the square over its range: both halves of each axis are reached.
    for a in 0..2 {
        assert!(centres.iter().any(|c| c[a] < 1000.0) && centres.iter().any(|c| c[a] > 1000.0), "axis {a}");
    }
}

#[test]
fn exponential_weakening_slips_as_its_closed_form() {
    // A uniform overstress on the column with exponential slip weakening: the face radiates a
    // plane S wave, so the traction is τ0 − (ρCs/2)·V, and with τ = τd + Δτs·exp(−D/Dc) the slip
    // obeys dD/dt = k(a − b·exp(−D/Dc)), k = 2/(ρCs), a = τ0 − τd, b = Δτs; with w = exp(D/Dc)
    // it is linear, dw/dt = (k/Dc)(a·w − b), so D(t) = Dc·ln(b/a + (1 − b/a)·exp(k·a·t/Dc)).
    use stickslip_solver::laws::ExponentialWeakening;
    let dc = 0.4;
    let mut scene = column(60, TAU0);
    scene.friction.law = ExponentialWeakening { mu_static: MU_S, mu_dynamic: MU_D, dc_m: dc }.into();
    let (_, _, c44) = lattice_elastic_constants(scene.young_pa, scene.poisson);
    let rho = scene.density_kg_m3;
    let k = 2.0 / (rho * (c44 / rho).sqrt());
    let (a, b) = (TAU0 - MU_D * SIGMA_N, (MU_S - MU_D) * SIGMA_N);
    let closed = |t: f64| dc * (b / a + (1.0 - b / a) * (k * a * t / dc).exp()).ln();
    // The time at which the closed form has slipped `d`.
    let time_of = |d: f64| dc / (k * a) * (((d / dc).exp() - b / a) / (1.0 - b / a)).ln();
    let model = Model::new(scene);
    let mut bt = batch(&model);
    let dt = bt.params.dt(0);
    // The lag of the lattice behind the closed form, in steps: the central-difference step
    // applies the friction of a slip one level old, so the discrete slip trails by a fraction of
    // a step, and must not drift.
    let (mut lag_lo, mut lag_hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let steps = 400;
    for step in 1..=steps {
        bt.step();
        let t = step as f64 * dt;
        // Once the slip is a few centimetres (the start's first steps ring), every tenth of the run.
        if step % 40 == 0 {
            let v = bt.view(0);
            let want = closed(t);
            for ci in 0..model.contact().len() {
                let lag = (t - time_of(v.node_contact(ci).slip)) / dt;
                (lag_lo, lag_hi) = (lag_lo.min(lag), lag_hi.max(lag));
            }
            println!("t = {t:.3} s: slip {:.4} m, closed form {want:.4} m", v.node_contact(0).slip);
        }
    }
    assert!(closed(steps as f64 * dt) > 5.0 * dc, "the run weakens fully");
    println!("the lattice's slip trails the closed form by {lag_lo:.3}–{lag_hi:.3} steps of {dt:.5} s");
    assert!(lag_lo > 0.0 && lag_hi < 1.0, "slip lags the closed form by {lag_lo}–{lag_hi} steps");
    assert!(lag_hi - lag_lo < 0.2, "the lag drifts: {lag_lo}–{lag_hi} steps");
}

#[test]
fn rate_state_friction_slides_at_the_rate_that_balances_the_radiated_wave() {
    // A uniform overstress on the column with rate-and-state friction: the face radiates a plane
    // S wave, so the traction is τ0 − (ρCs/2)·V, and once θ has relaxed over a few L of slip the
    // fault slides at the steady rate where τ0 − (ρCs/2)·V = σn·f_ss(V),
    // f_ss = f₀ + (a − b)·ln(V/V₀) (solved here by bisection), velocity weakening (aging law)
    // or strengthening (slip law) alike: the radiation damping ρCs/2 outweighs σn·(a − b)/V.
    use stickslip_solver::laws::rate_state::steady_friction;
    use stickslip_solver::laws::{Evolution, RateStateNode, RateStateStart};
    for (evolution, a, b, dc_m) in [(Evolution::Aging, 0.010, 0.015, 0.05), (Evolution::Slip, 0.020, 0.010, 0.005)] {
        let law = RateStateNode { a, b, dc_m, v0_m_s: 1e-6, f0: 0.5, evolution, start: RateStateStart::SteadyAt(1e-6) };
        let mut scene = column(60, TAU0);
        scene.friction.law = law.into();
        let (_, _, c44) = lattice_elastic_constants(scene.young_pa, scene.poisson);
        let rho = scene.density_kg_m3;
        let eta = 0.5 * rho * (c44 / rho).sqrt();
        let node = law;
        let excess = |v: f64| TAU0 - eta * v - SIGMA_N * steady_friction(&node, v);
        let (mut lo, mut hi) = (1e-3f64, 10.0f64);
        for _ in 0..200 {
            let mid = (lo * hi).sqrt();
            if excess(mid) > 0.0 { lo = mid } else { hi = mid }
        }
        let rate = lo;
        let model = Model::new(scene);
        let mut bt = batch(&model);
        let steps = 400;
        let (mut sum, mut n) = (0.0, 0);
        for step in 1..=steps {
            bt.step();
            if step > steps / 2 {
                let v = bt.view(0);
                for ci in 0..model.contact().len() {
                    sum += v.node_contact(ci).slip_rate;
                    n += 1;
                }
            }
        }
        let mean = sum / n as f64;
        let slip = bt.view(0).node_contact(0).slip;
        println!(
            "{evolution:?} (a = {a}, b = {b}): slip rate {mean:.5} m/s over the second half, steady closed form \
             {rate:.5} m/s; slip {slip:.3} m = {:.0} L",
            slip / dc_m
        );
        assert!(slip > 20.0 * dc_m, "θ has relaxed: {slip} m");
        assert!((mean / rate - 1.0).abs() < 0.005, "{evolution:?}: slip rate {mean} vs {rate}");
    }
}

#[test]
fn a_balanced_rate_state_start_slides_at_its_initial_rate_from_the_benchmarks_state() {
    // TPV101's velocity-weakening friction under its tractions (τ0 = 75 MPa, σn = 120 MPa), each
    // node starting in balance at Vᵢ = 1e-12 m/s: θ₀ is the benchmark description's
    // 1.606238999213454e9 s, and with no overstress the fault creeps on at Vᵢ (the aging over a
    // second changes θ by 1e-9 of itself).
    use stickslip_solver::laws::{Evolution, RateStateNode, RateStateStart};
    let vi = 1e-12;
    let law = RateStateNode {
        a: 0.008,
        b: 0.012,
        dc_m: 0.02,
        v0_m_s: 1e-6,
        f0: 0.6,
        evolution: Evolution::Aging,
        start: RateStateStart::Balanced(vi),
    };
    let mut scene = column(10, 75e6);
    scene.friction.law = law.into();
    let model = Model::new(scene);
    let mut b = batch(&model);
    for ci in 0..model.contact().len() {
        let theta0 = b.view(0).node_contact(ci).state;
        assert!((theta0 / 1.606238999213454e9 - 1.0).abs() < 1e-12, "node {ci}: θ₀ = {theta0} s");
    }
    let (mut slip0, mut t0) = (0.0, 0.0);
    let steps = 400;
    for step in 1..=steps {
        b.step();
        if step == steps / 2 {
            slip0 = b.view(0).node_contact(0).slip;
            t0 = step as f64;
        }
    }
    let dt = 0.5 * critical_time_step(&model, &model.nominal_stiffness()).unwrap().dt_s;
    let rate = (b.view(0).node_contact(0).slip - slip0) / ((steps as f64 - t0) * dt);
    println!("balanced start: slip rate {rate:e} m/s over the second half (Vᵢ = {vi:e})");
    assert!((rate / vi - 1.0).abs() < 1e-3, "slip rate {rate:e} m/s, not Vᵢ");
}

#[test]
fn a_smooth_overstress_loads_a_held_fault_as_its_ramp() {
    // A held fault (75 MPa < μs·σn = 81.24 MPa) under TPV101's overstress shape, 5 MPa over
    // T = 0.05 s on a radius far larger than the column: each step's friction holds the traction
    // τ0 + Δτ₀·F(r)·G(t) exactly, G within the step's own bounds; once grown, exactly 75 MPa.
    use std::ops::ControlFlow;
    use stickslip_solver::fault::Overstress;
    use stickslip_solver::{RunOptions, run_seed};
    let mut scene = column(10, 70e6);
    let o = Overstress { centre_m: [0.0, 0.0], radius_m: 1e6, overstress_pa: 5e6, rise_s: 0.05 };
    scene.fault.as_mut().unwrap().overstress = Some(o);
    scene.shear.duration_s = 0.08;
    scene.record.interval_s = None;
    scene.record.fault_stations = vec![model_node(&scene)];
    let model = Model::new(scene);
    let out = run_seed(&model, 7, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    let st = &out.recording.trace.stations[0];
    let t = &out.recording.trace.time_s;
    let dt = t[1] - t[0];
    let f = o.shape(0.0, 0.0);
    let mut worst: f64 = 0.0;
    for (k, tau) in st.shear_stress_pa[0].iter().enumerate() {
        let (lo, hi) = (70e6 + 5e6 * f * o.ramp(t[k] - dt), 70e6 + 5e6 * f * o.ramp(t[k] + dt));
        assert!(*tau >= lo - 1.0 && *tau <= hi + 1.0, "t = {} s: τ = {tau} Pa outside {lo}…{hi}", t[k]);
        worst = worst.max((tau - 70e6 - 5e6 * f * o.ramp(t[k])).abs());
    }
    let last = *st.shear_stress_pa[0].last().unwrap();
    println!("held fault under the ramp: largest difference from τ0 + Δτ₀·G(t) {worst:.3e} Pa; at the end {last} Pa");
    assert!((last - 70e6 - 5e6 * f).abs() < 1e-3, "at the end τ = {last} Pa");
    assert!(st.slip_rate_m_s[0].iter().all(|v| *v == 0.0), "a held node slid");
}

/// The base node at the origin, where the overstress is centred.
fn model_node(scene: &Scene) -> stickslip_solver::NodeId {
    scene.lattice().contact_nodes()[0]
}
