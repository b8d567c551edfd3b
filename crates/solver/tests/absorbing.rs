//! Absorbing faces (docs/model.md §15): plane P and S pulses at normal incidence leave through a
//! face of Lysmer–Kuhlemeyer dashpots, measured against the same pulse in a block long enough that
//! nothing comes back; the dashpots' energy closes the ledger; they leave the critical step as it
//! is.

mod common;

use common::scene_with;
use stickslip_solver::geometry::{Face, NodeKind};
use stickslip_solver::material::lattice_elastic_constants;
use stickslip_solver::statics::critical_time_step;
use stickslip_solver::step::{Batch, LaneSetup, Tracking};
use stickslip_solver::{Dims, Model, NodeId, Scene};

/// A column of `nz` modules of 100 m in rock (ρ 2670, Cp 6000, Cs 3464 m/s, ν 0.25), 2 × 2
/// across, its lateral faces symmetry planes for a plane wave along z of polarisation `axis`
/// (the P wave: each lateral face holds its normal component; the S wave along x: the lateral
/// faces hold y and z), the top face absorbing if `absorbing`.
fn column(nz: usize, axis: usize, absorbing: bool) -> Scene {
    let mut s = scene_with(|f| {
        f.block.nx = 2;
        f.block.ny = 2;
        f.block.nz = nz as i64;
        f.block.lc_m = 100.0;
        f.material.young_pa = 8.01e10;
        f.material.density_kg_m3 = 2670.0;
        f.material.poisson = 0.25;
        f.material.young_cv = 0.0;
        f.self_weight.gravity_m_s2 = 0.0;
    });
    s.dims = Dims::new(2, 2, nz);
    s.shear.drivers.clear();
    s.record.interface.clear();
    let lattice = s.lattice();
    let mut fixed = std::collections::BTreeMap::<NodeId, [bool; 3]>::new();
    for face in [Face::XMin, Face::XMax, Face::YMin, Face::YMax] {
        let (normal, _) = face.axis();
        for id in face.nodes(&lattice) {
            let m = fixed.entry(id).or_default();
            if axis == 2 {
                m[normal] = true;
            } else {
                m[1] = true;
                m[2] = true;
            }
        }
    }
    s.fixed = fixed.into_iter().collect();
    if absorbing {
        s.absorbing = vec![Face::ZMax];
    }
    s
}

fn setup(model: &Model, fraction: f64) -> LaneSetup {
    let k = model.nominal_stiffness();
    let crit = critical_time_step(model, &k).unwrap();
    LaneSetup {
        dt_s: fraction * crit.dt_s,
        stiffness: stickslip_solver::step::LaneStiffness::PerBar(k),
        friction: vec![1.0; model.contact().len()],
        strength: None,
        fault: None,
    }
}

/// Kinetic energy of the nodes at or below `z_max` (J).
fn kinetic_below<const L: usize>(b: &Batch<'_, L>, model: &Model, z_max: f64) -> f64 {
    let v = b.view(0);
    (0..model.node_count())
        .filter(|&i| model.lattice().position(model.canonical(i))[2] <= z_max)
        .map(|i| {
            let u = v.velocity(i);
            0.5 * model.mass()[i] * (u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
        })
        .sum()
}

/// An up-going Gaussian pulse of polarisation `axis` from z0 = 15 Lc, width 4 Lc, run until it has
/// gone to the top of a 40-module column and back to where it started; the share of its energy
/// still in the column's bottom 40 modules, in the column with an absorbing top and in one of 120
/// modules (what the lattice's dispersion leaves behind), and the pulse's initial kinetic energy.
fn reflected(axis: usize) -> (f64, f64) {
    let run = |nz: usize, absorbing: bool| -> (f64, f64) {
        let scene = column(nz, axis, absorbing);
        let (c11, _, c44) = lattice_elastic_constants(scene.young_pa, scene.poisson);
        let c = (if axis == 2 { c11 } else { c44 } / scene.density_kg_m3).sqrt();
        let lc = scene.lc_m;
        let model = Model::new(scene);
        let lane = setup(&model, 0.5);
        let dt = lane.dt_s;
        let mut b = Batch::<1>::new(&model, &[lane]);
        let (amp, z0, w) = (1e-3, 15.0 * lc, 4.0 * lc);
        let pulse = move |z: f64, t: f64| amp * (-((z - z0 - c * t) / w).powi(2)).exp();
        let along = |v: f64| {
            let mut u = [0.0; 3];
            u[axis] = v;
            u
        };
        b.initialize(0, |p| (along(pulse(p[2], -dt)), along(pulse(p[2], 0.0))));
        b.step();
        let initial = kinetic_below(&b, &model, f64::INFINITY);
        let steps = (2.0 * 25.0 * lc / c / dt).round() as usize;
        for _ in 0..steps {
            b.step();
        }
        (kinetic_below(&b, &model, 40.0 * lc), initial)
    };
    let (with_face, e0) = run(40, true);
    let (tail, _) = run(120, false);
    ((with_face - tail) / e0, tail / e0)
}

#[test]
fn p_and_s_pulses_at_normal_incidence_leave_through_an_absorbing_face() {
    for (axis, name) in [(2, "P"), (0, "S")] {
        let (r, tail) = reflected(axis);
        println!(
            "{name} pulse at normal incidence: reflected energy {:.3}% (dispersion tail {:.3}%)",
            100.0 * r,
            100.0 * tail
        );
        assert!(r < 0.05, "{name}: {:.2}% of the energy reflected", 100.0 * r);
        assert!(r > -0.01, "{name}: the column with the face holds less than the tail: {r}");
    }
}

#[test]
fn the_dashpots_work_closes_the_energy_ledger() {
    // The P pulse of the test above, with the energy tracked: what the kinetic and strain energy
    // lose is what the dashpots absorbed, step by step, to round-off.
    let scene = column(40, 2, true);
    let lc = scene.lc_m;
    let (c11, _, _) = lattice_elastic_constants(scene.young_pa, scene.poisson);
    let cp = (c11 / scene.density_kg_m3).sqrt();
    let model = Model::new(scene);
    let lane = setup(&model, 0.5);
    let dt = lane.dt_s;
    let mut b = Batch::<1>::new(&model, &[lane]);
    b.stepper.set_tracking(Tracking { energy: true, ..Tracking::default() });
    let pulse = move |z: f64, t: f64| 1e-3 * (-((z - 30.0 * lc - cp * t) / (4.0 * lc)).powi(2)).exp();
    b.initialize(0, |p| ([0.0, 0.0, pulse(p[2], -dt)], [0.0, 0.0, pulse(p[2], 0.0)]));
    b.step();
    let start = b.view(0).energy();
    let total0 = start.kinetic + start.elastic;
    let mut worst: f64 = 0.0;
    for _ in 0..(30.0 * lc / cp / dt) as usize {
        b.step();
        let e = b.view(0).energy();
        // Nothing does work: stored, absorbed (and what the base took from the little that
        // reaches it) stays what the pulse started with.
        let drift = e.residual() - start.residual();
        worst = worst.max(drift.abs() / total0);
    }
    let e = b.view(0).energy();
    println!("absorbed {:.4} of the pulse, worst ledger drift {worst:.2e}", e.absorbed / total0);
    assert!(e.absorbed > 0.9 * total0, "the pulse should have left: {} of {}", e.absorbed, total0);
    assert!(worst < 1e-9, "the ledger drifts by {worst:e} of the pulse's energy");
}

#[test]
fn dashpots_leave_the_critical_step_as_it_is() {
    // A 3 × 3 × 3 block whose five faces (the base aside) all absorb, started with a random
    // displacement field: stable for 20 000 steps at 0.99 of the critical step without dashpots,
    // unstable at 1.02 — the centred dashpot neither shrinks nor widens the bound ωΔt ≤ 2.
    let run = |fraction: f64| -> f64 {
        let mut scene = column(3, 2, false);
        scene.dims = Dims::new(3, 3, 3);
        scene.fixed.clear();
        scene.absorbing = vec![Face::XMin, Face::XMax, Face::YMin, Face::YMax, Face::ZMax];
        let model = Model::new(scene);
        let lane = setup(&model, fraction);
        let mut b = Batch::<1>::new(&model, &[lane]);
        let mut state = 0x9E3779B97F4A7C15u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        let kinds: Vec<bool> = (0..model.node_count())
            .map(|i| matches!(model.lattice().kind(model.canonical(i)), NodeKind::Corner(_)))
            .collect();
        let u: Vec<[f64; 3]> = kinds.iter().map(|_| [next(), next(), next().abs()].map(|v| 1e-6 * v)).collect();
        b.state.u.n.set_lane(0, |i, c| u[i][c]);
        b.state.u.np1.set_lane(0, |i, c| u[i][c]);
        let mut largest: f64 = 0.0;
        for _ in 0..20_000 {
            b.step();
            for i in 0..model.node_count() {
                largest = largest.max(b.view(0).displacement(i).iter().fold(0.0, |a, v| a.max(v.abs())));
            }
            if !largest.is_finite() || largest > 1.0 {
                break;
            }
        }
        largest
    };
    let stable = run(0.99);
    let unstable = run(1.02);
    println!("largest displacement: {stable:.3e} m at 0.99 of the critical step, {unstable:.3e} m at 1.02");
    assert!(stable < 1e-5, "unstable below the critical step: {stable}");
    assert!(!(unstable < 1e-3), "stable above the critical step: {unstable}");
}
