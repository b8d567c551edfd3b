//! The scene the kernel benchmarks step (`benches/step.rs`, `benches/rupture.rs`): the paper's
//! block at any size, driven at one node, one seed's lane at half its critical step, and a batch
//! of seeds settling under self-weight.

use stickslip_config::PipelineFile;
use stickslip_config::scene::RuptureSection;
use stickslip_solver::Model;
use stickslip_solver::statics::critical_step;
use stickslip_solver::step::{Batch, LaneSetup};

/// The paper's scene with `nx × ny × nz` modules, with `[rupture]` at its defaults if asked.
pub fn model(nx: i64, ny: i64, nz: i64, rupture: bool) -> Model {
    let mut f = PipelineFile::default();
    (f.block.nx, f.block.ny, f.block.nz) = (nx, ny, nz);
    f.shear.driver_at_m = vec![[0.0, 0.0, 0.1]];
    if rupture {
        f.rupture = Some(RuptureSection::default());
    }
    Model::new(f.scene().expect("the paper's scene at any size is valid"))
}

/// Seed `seed`'s lane of `m`: its stiffness, friction, strength, and half its critical step.
pub fn setup(m: &Model, seed: u64) -> LaneSetup {
    let k = m.lane_stiffness(seed).expect("stiffness");
    let dt = 0.5 * critical_step(m, &k).expect("critical step").dt_s;
    LaneSetup {
        dt_s: dt,
        stiffness: k,
        friction: m.friction_factors(seed).expect("friction"),
        strength: m.bar_strength(seed).expect("strength"),
        fault: m.fault_loads(seed).expect("fault loads"),
    }
}

/// Seeds 1…L of `m` side by side under self-weight with the paper's damping (400/s), 50 steps in.
pub fn settling_batch<const L: usize>(m: &Model) -> Batch<'_, L> {
    let lanes: [LaneSetup; L] = std::array::from_fn(|l| setup(m, l as u64 + 1));
    let mut s = Batch::<L>::new(m, &lanes);
    for l in 0..L {
        s.params.set_damping(l, 400.0);
        s.params.set_body_acceleration(l, [0.0, 0.0, -9.81]);
    }
    for _ in 0..50 {
        s.step();
    }
    s
}
