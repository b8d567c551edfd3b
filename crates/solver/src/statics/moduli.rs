//! How stiff the built block really is: effective E and ν of a finite block from a static solve.

use crate::error::SolverError;
use crate::field::Field;
use crate::model::Model;
use crate::statics::cg::{Prescribed, solve_static};

/// Effective moduli of a finite block under uniaxial stress, from a static solve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EffectiveModuli {
    /// Loading axis.
    pub axis: usize,
    /// Effective Young's modulus along `axis` (Pa).
    pub young_pa: f64,
    /// Effective Poisson's ratios toward the two other axes (in increasing axis order).
    pub poisson: [f64; 2],
}

/// Effective E and ν of the block of `model` (bar stiffness `k`) stretched along `axis`:
/// rollers on the three planes through the origin, the far face along `axis` moved by a strain
/// of 1e-4; E from the reaction on that face over the face area, ν from the mean displacement of
/// the two free lateral faces. It measures how stiff the built block really is (a finite block
/// is softer than the continuum it models: docs/model.md §1).
pub fn uniaxial_moduli(model: &Model, k: &[f64], axis: usize) -> Result<EffectiveModuli, SolverError> {
    let lattice = model.lattice();
    let dims = lattice.dims();
    let n = [dims.nx, dims.ny, dims.nz];
    let ext = lattice.extent();
    let strain = 1e-4;
    let mut prescribed = Vec::new();
    for i in 0..model.node_count() {
        let h = lattice.half_units(model.canonical(i));
        for a in 0..3 {
            if h[a] == 0 {
                prescribed.push(Prescribed { node: i, axis: a, value: 0.0 });
            }
        }
        if h[axis] == 2 * n[axis] {
            prescribed.push(Prescribed { node: i, axis, value: strain * ext[axis] });
        }
    }
    let loads = Field::<1>::zeros(model.node_count());
    let sol = solve_static(model, k, &loads, &prescribed, 1e-11, 50_000)?;
    let others: Vec<usize> = (0..3).filter(|&a| a != axis).collect();
    let mut force = 0.0;
    let mut lateral = [0.0; 2];
    let mut count = [0.0; 2];
    for i in 0..model.node_count() {
        let h = lattice.half_units(model.canonical(i));
        if h[axis] == 2 * n[axis] {
            force += sol.reactions.c[axis][i][0];
        }
        for (s, &a) in others.iter().enumerate() {
            if h[a] == 2 * n[a] {
                lateral[s] += sol.u.c[a][i][0];
                count[s] += 1.0;
            }
        }
    }
    let area = ext[others[0]] * ext[others[1]];
    Ok(EffectiveModuli {
        axis,
        young_pa: force / area / strain,
        poisson: [0, 1].map(|s| -(lateral[s] / count[s] / ext[others[s]]) / strain),
    })
}
