//! Statics of the lattice: static equilibrium by conjugate gradients, the critical time step, and
//! the effective moduli of the built block.

pub mod cg;
pub mod critical;
pub mod moduli;

pub use cg::{Prescribed, StaticSolution, solve_static, solve_static_from};
pub use critical::{CriticalStep, critical_step, critical_step_on, critical_time_step, node_bound};
pub use moduli::{EffectiveModuli, uniaxial_moduli};
