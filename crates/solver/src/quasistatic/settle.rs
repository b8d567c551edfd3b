//! The self-weight equilibrium solved directly: `K·u = weight` with every base node held where it
//! stands, admissible when every base node pushes on the base and its friction holds it.

use crate::error::SolverError;
use crate::field::Field;
use crate::model::Model;
use crate::quasistatic::{CG_MAX_ITERATIONS, CG_TOLERANCE};
use crate::statics::{Prescribed, solve_static};

/// The gravity equilibrium of a lane with every base node held.
pub struct StaticSettle {
    /// Displacements (m).
    pub u: Field<1>,
    /// Reactions `K·u − f` (N).
    pub reactions: Field<1>,
}

/// Solves the self-weight equilibrium with every base node held at its place; `Ok(Err(why))`
/// when it is not admissible (a base node would pull on the base or slide).
pub fn settle_statically(
    model: &Model,
    stiffness: &[f64],
    friction: &[f64],
    gravity: f64,
) -> Result<Result<StaticSettle, String>, SolverError> {
    let n = model.node_count();
    let mass = model.mass();
    let mut loads = Field::<1>::zeros(n);
    for i in 0..n {
        loads.c[2][i][0] = -mass[i] * gravity;
    }
    model.boundaries().static_load(&mut loads);
    let mut prescribed = model.boundaries().held(|_, _| 0.0);
    for &node in model.contact() {
        prescribed.extend((0..3).map(|axis| Prescribed { node: node as usize, axis, value: 0.0 }));
    }
    let solution = solve_static(model, stiffness, &loads, &prescribed, CG_TOLERANCE, CG_MAX_ITERATIONS)?;
    for (ci, &node) in model.contact().iter().enumerate() {
        let p = node as usize;
        let r = [0, 1, 2].map(|c| solution.reactions.c[c][p][0]);
        let id = model.canonical(p);
        if r[2] < 0.0 {
            return Ok(Err(format!(
                "base node LDEM {} would pull on the base (normal reaction {:.3e} N)",
                id.ldem(),
                r[2]
            )));
        }
        let (rt, limit) = (r[0].hypot(r[1]), model.node_friction(ci, friction[ci]).static_coefficient() * r[2]);
        if rt > limit {
            return Ok(Err(format!(
                "friction would not hold base node LDEM {} (needs {rt:.3e} N, μs·N = {limit:.3e} N)",
                id.ldem()
            )));
        }
    }
    Ok(Ok(StaticSettle { u: solution.u, reactions: solution.reactions }))
}
