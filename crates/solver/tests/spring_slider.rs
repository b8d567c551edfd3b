//! A block on the loading plate's springs against the mass-on-a-spring closed form
//! (docs/model.md §5).
//!
//! An 8×1×1 block (0.8 × 0.1 × 0.1 m, 19.2 kg) tied at its top to a plate by springs of total
//! stiffness `k` = 4e6 N/m, far softer than the block itself (~10⁹ N/m), on a frictionless base:
//! it swings as a rigid mass on a spring, `x(t) = v·t − (v/ω)·sin ωt`.
//!
//! The textbook spring-slider with friction (drop `2(μs − μd)·N`, the slip-weakening stability
//! boundary `k_c = (μs − μd)·N/Dc`) is not asserted here: a lattice block on a rigid base is not a
//! rigid slider. Its base nodes chatter on the base (6–7 of 18 lifted at any time in steady
//! sliding without damping), so the steady Coulomb pull is 0.76·μ·N instead of μ·N, and the
//! trailing nodes reach μs first, so static/dynamic friction lets go at 0.73–0.81·μs·N. The
//! `stickslip check` criterion is the rigid slider's, with that caveat printed.

mod common;

use std::ops::ControlFlow;

use common::scene_with;
use stickslip_config::scene::LoadingPlateSection;
use stickslip_solver::{Channel, Model, RunOptions, Scene, run_seed};

const K: f64 = 4e6;
const NX: i64 = 8;

/// The 8×1×1 block on a frictionless base, undamped, its top on the plate's springs, the plate
/// moving at `v` from the start.
fn slider(v: f64, duration_s: f64) -> Scene {
    scene_with(|f| {
        f.block.nx = NX;
        f.block.ny = 1;
        f.block.nz = 1;
        f.material.young_cv = 0.0;
        f.friction.mu_static = 0.0;
        f.shear.damping_per_s = 0.0;
        f.shear.velocity_m_s = v;
        f.shear.rise_time_s = 0.0;
        f.shear.duration_s = duration_s;
        f.loading_plate = Some(LoadingPlateSection { stiffness_n_m: Some(K), ..Default::default() });
        f.record.interface = vec!["driver".into(), "slip_rate".into(), "mean_slip".into()];
        f.record.energy = true;
    })
}

#[test]
fn frictionless_block_on_the_plate_swings_as_a_mass_on_a_spring() {
    // μ = 0: the plate's springs alone move the block, M·ẍ = k·(v·t − x), so from rest
    // x(t) = v·t − (v/ω)·sin ωt with ω = √(k/M) (the block is 10³ times stiffer than the springs).
    let v = 1e-3;
    let model = Model::new(slider(v, 0.05));
    let mass: f64 = model.mass().iter().sum();
    let omega = (K / mass).sqrt();
    let out = run_seed(&model, 1, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
    let r = &out.recording;
    let slip = r.get(Channel::MeanSlip).unwrap();
    let amplitude = v / omega;
    let mut worst: f64 = 0.0;
    for (i, &t) in r.time_s.iter().enumerate() {
        let want = v * t - amplitude * (omega * t).sin();
        worst = worst.max((slip[i] - slip[0] - want).abs());
    }
    println!("ω = {omega:.2} rad/s, swing v/ω = {amplitude:.3e} m, worst error {worst:.3e} m");
    assert!(worst < 0.02 * amplitude, "the block follows v·t − (v/ω)·sin ωt to 2% of the swing: {worst:.3e} m");
    // The springs' work is booked: the energy balance closes.
    let residual = r.get(Channel::EnergyResidual).unwrap();
    let work = r.get(Channel::ExternalWork).unwrap();
    let last = residual.len() - 1;
    println!("energy residual {:.3e} J of {:.3e} J external work", residual[last], work[last]);
    assert!(residual[last].abs() < 1e-6 * work[last].abs().max(1e-9), "energy balance with the plate");
}
