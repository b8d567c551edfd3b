//! The scene the kernel benchmarks step (`benches/step.rs`, `benches/rupture.rs`): the paper's
//! block at any size, driven at one node, and one seed's lane at half its critical step.

use stickslip_config::PipelineFile;
use stickslip_config::scene::RuptureSection;
use stickslip_solver::Model;
use stickslip_solver::statics::critical_time_step;
use stickslip_solver::step::LaneSetup;

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
    let k = m.bar_stiffness(seed).expect("stiffness");
    let dt = 0.5 * critical_time_step(m, &k).expect("critical step").dt_s;
    LaneSetup {
        dt_s: dt,
        stiffness: k,
        friction: m.friction_factors(seed).expect("friction"),
        strength: m.bar_strength(seed).expect("strength"),
    }
}
