//! Static equilibrium `K·u = f` with prescribed displacement components, by Jacobi-preconditioned
//! conjugate gradients on the bar kernel (matrix-free).

use crate::error::SolverError;
use crate::kernel::{Field, bar_forces, stiffness_diagonal};
use crate::model::Model;

/// A prescribed displacement component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Prescribed {
    /// Internal node index.
    pub node: usize,
    /// Axis 0, 1, 2.
    pub axis: usize,
    /// Value (m).
    pub value: f64,
}

/// Result of a static solve.
#[derive(Clone, Debug)]
pub struct StaticSolution {
    /// Displacements (m), internal order.
    pub u: Field<1>,
    /// Reactions `K·u − f` (N): the forces the constraints apply; zero at free components up to
    /// the solver tolerance.
    pub reactions: Field<1>,
    /// CG iterations.
    pub iterations: usize,
    /// Final `‖r‖/‖b‖` on the free components.
    pub relative_residual: f64,
}

/// Solves `K·u = loads` for the free components, with `prescribed` components fixed.
pub fn solve_static(
    model: &Model,
    k: &[f64],
    loads: &Field<1>,
    prescribed: &[Prescribed],
    tolerance: f64,
    max_iterations: usize,
) -> Result<StaticSolution, SolverError> {
    let n = model.node_count();
    let k1: Vec<[f64; 1]> = k.iter().map(|&v| [v]).collect();
    let mut free = [vec![true; n], vec![true; n], vec![true; n]];
    let mut u = Field::<1>::zeros(n);
    for p in prescribed {
        free[p.axis][p.node] = false;
        u.c[p.axis][p.node][0] = p.value;
    }
    let apply = |x: &Field<1>, y: &mut Field<1>| {
        y.fill_zero();
        bar_forces(model.layout(), &k1, x, y);
        for comp in &mut y.c {
            for v in comp.iter_mut() {
                v[0] = -v[0];
            }
        }
    };
    let diag = stiffness_diagonal(model.layout(), &k1, 0);
    let dot = |a: &Field<1>, b: &Field<1>| -> f64 {
        (0..3).map(|c| (0..n).filter(|&i| free[c][i]).map(|i| a.c[c][i][0] * b.c[c][i][0]).sum::<f64>()).sum()
    };
    let mut ku = Field::<1>::zeros(n);
    apply(&u, &mut ku);
    // r = f − K·u on free components, 0 on prescribed ones.
    let mut r = Field::<1>::zeros(n);
    for c in 0..3 {
        for i in 0..n {
            if free[c][i] {
                r.c[c][i][0] = loads.c[c][i][0] - ku.c[c][i][0];
            }
        }
    }
    let b_norm = {
        let mut b = Field::<1>::zeros(n);
        for c in 0..3 {
            for i in 0..n {
                if free[c][i] {
                    b.c[c][i][0] = loads.c[c][i][0] - ku.c[c][i][0];
                }
            }
        }
        dot(&b, &b).sqrt()
    };
    let precondition = |r: &Field<1>, z: &mut Field<1>| {
        for c in 0..3 {
            for i in 0..n {
                z.c[c][i][0] = if free[c][i] && diag.c[c][i][0] > 0.0 { r.c[c][i][0] / diag.c[c][i][0] } else { 0.0 };
            }
        }
    };
    let mut z = Field::<1>::zeros(n);
    precondition(&r, &mut z);
    let mut p = z.clone();
    let mut rz = dot(&r, &z);
    let mut ap = Field::<1>::zeros(n);
    let mut iterations = 0;
    let mut rel = if b_norm > 0.0 { 1.0 } else { 0.0 };
    while rel > tolerance {
        if iterations >= max_iterations {
            return Err(SolverError::Numerical(format!(
                "static solve did not converge in {max_iterations} iterations (relative residual {rel:.3e})"
            )));
        }
        apply(&p, &mut ap);
        let pap = dot(&p, &ap);
        if !(pap > 0.0) {
            return Err(SolverError::Numerical(format!(
                "static solve: stiffness not positive definite on the free components (pᵀKp = {pap:e}); \
                 the constraints leave a rigid-body motion free"
            )));
        }
        let alpha = rz / pap;
        for c in 0..3 {
            for i in 0..n {
                if free[c][i] {
                    u.c[c][i][0] += alpha * p.c[c][i][0];
                    r.c[c][i][0] -= alpha * ap.c[c][i][0];
                }
            }
        }
        iterations += 1;
        rel = dot(&r, &r).sqrt() / b_norm;
        precondition(&r, &mut z);
        let rz_new = dot(&r, &z);
        let beta = rz_new / rz;
        rz = rz_new;
        for c in 0..3 {
            for i in 0..n {
                p.c[c][i][0] = if free[c][i] { z.c[c][i][0] + beta * p.c[c][i][0] } else { 0.0 };
            }
        }
    }
    let mut reactions = Field::<1>::zeros(n);
    apply(&u, &mut reactions);
    for c in 0..3 {
        for i in 0..n {
            reactions.c[c][i][0] -= loads.c[c][i][0];
        }
    }
    Ok(StaticSolution { u, reactions, iterations, relative_residual: rel })
}

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
/// is softer than the continuum it models: SPEC §1).
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
