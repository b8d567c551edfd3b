//! Static equilibrium `K·u = f` with prescribed displacement components, by Jacobi-preconditioned
//! conjugate gradients on the bar kernel (matrix-free).

pub use crate::boundary::Prescribed;
use crate::error::SolverError;
use crate::field::Field;
use crate::model::Model;
use crate::step::bars::{bar_forces, stiffness_diagonal};

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
    solve_static_from(model, k, loads, prescribed, None, tolerance, max_iterations)
}

/// [`solve_static`] starting from `initial` (its free components; a good guess saves
/// iterations). The tolerance is on `‖f − K·u‖/‖f − K·u₀‖` with `u₀` the start without the
/// guess, so a guess does not change what "converged" means.
pub fn solve_static_from(
    model: &Model,
    k: &[f64],
    loads: &Field<1>,
    prescribed: &[Prescribed],
    initial: Option<&Field<1>>,
    tolerance: f64,
    max_iterations: usize,
) -> Result<StaticSolution, SolverError> {
    let n = model.node_count();
    let k1: Vec<[f64; 1]> = k.iter().map(|&v| [v]).collect();
    // 1 on free components, 0 on prescribed ones: the loops below run over everything.
    let mut free = [vec![1.0; n], vec![1.0; n], vec![1.0; n]];
    let mut u = Field::<1>::zeros(n);
    for p in prescribed {
        free[p.axis][p.node] = 0.0;
        u.c[p.axis][p.node][0] = p.value;
    }
    let diag = stiffness_diagonal(model.layout(), &k1, 0);
    let sys = System { model, k1: &k1, free: &free };
    // Jacobi preconditioner, zero on prescribed components.
    let inv_diag: [Vec<f64>; 3] = std::array::from_fn(|c| {
        (0..n).map(|i| if diag.c[c][i][0] > 0.0 { free[c][i] / diag.c[c][i][0] } else { 0.0 }).collect()
    });
    let mut scratch = Field::<1>::zeros(n);
    let mut r = Field::<1>::zeros(n);
    sys.residual(&u, loads, &mut scratch, &mut r);
    let b_norm = dot(&r, &r).sqrt();
    if let Some(guess) = initial.filter(|_| b_norm > 0.0) {
        for c in 0..3 {
            for i in 0..n {
                if free[c][i] > 0.0 {
                    u.c[c][i][0] = guess.c[c][i][0];
                }
            }
        }
        sys.residual(&u, loads, &mut scratch, &mut r);
    }
    let iterations = if b_norm == 0.0 {
        0
    } else {
        conjugate_gradients(&sys, &inv_diag, &mut u, &mut r, b_norm, tolerance, max_iterations)?
    };
    let relative_residual = if b_norm > 0.0 { dot(&r, &r).sqrt() / b_norm } else { 0.0 };
    let mut reactions = Field::<1>::zeros(n);
    sys.stiffness(&u, &mut reactions);
    for c in 0..3 {
        for i in 0..n {
            reactions.c[c][i][0] -= loads.c[c][i][0];
        }
    }
    Ok(StaticSolution { u, reactions, iterations, relative_residual })
}

fn dot(a: &Field<1>, b: &Field<1>) -> f64 {
    let mut s = 0.0;
    for c in 0..3 {
        for (x, y) in a.c[c].iter().zip(&b.c[c]) {
            s += x[0] * y[0];
        }
    }
    s
}

/// The operator of a static solve: `A·x = mask ⊙ (K·x)`.
struct System<'a> {
    model: &'a Model,
    k1: &'a [[f64; 1]],
    free: &'a [Vec<f64>; 3],
}

impl System<'_> {
    /// `y = K·x`.
    fn stiffness(&self, x: &Field<1>, y: &mut Field<1>) {
        y.fill_zero();
        bar_forces(self.model.layout(), self.k1, x, y);
        for comp in &mut y.c {
            for v in comp.iter_mut() {
                v[0] = -v[0];
            }
        }
    }

    /// `y = mask ⊙ y` in place.
    fn finish(&self, y: &mut Field<1>) {
        for c in 0..3 {
            for (v, w) in y.c[c].iter_mut().zip(&self.free[c]) {
                v[0] *= w;
            }
        }
    }

    fn apply(&self, x: &Field<1>, y: &mut Field<1>) {
        self.stiffness(x, y);
        self.finish(y);
    }

    /// `r = mask ⊙ (f − K·u)`.
    fn residual(&self, u: &Field<1>, loads: &Field<1>, ku: &mut Field<1>, r: &mut Field<1>) {
        self.stiffness(u, ku);
        for c in 0..3 {
            for i in 0..u.c[c].len() {
                r.c[c][i][0] = loads.c[c][i][0] - ku.c[c][i][0];
            }
        }
        self.finish(r);
    }
}

fn conjugate_gradients(
    sys: &System<'_>,
    inv_diag: &[Vec<f64>; 3],
    u: &mut Field<1>,
    r: &mut Field<1>,
    b_norm: f64,
    tolerance: f64,
    max_iterations: usize,
) -> Result<usize, SolverError> {
    let n = u.c[0].len();
    let mut z = Field::<1>::zeros(n);
    let mut rz = 0.0;
    for c in 0..3 {
        for i in 0..n {
            z.c[c][i][0] = r.c[c][i][0] * inv_diag[c][i];
            rz += r.c[c][i][0] * z.c[c][i][0];
        }
    }
    let mut p = z.clone();
    let mut ap = Field::<1>::zeros(n);
    let mut iterations = 0;
    let mut rel = dot(r, r).sqrt() / b_norm;
    while rel > tolerance {
        if iterations >= max_iterations {
            return Err(not_converged(max_iterations, rel));
        }
        sys.apply(&p, &mut ap);
        let pap = dot(&p, &ap);
        if !(pap > 0.0) {
            return Err(SolverError::Numerical(format!(
                "static solve: stiffness not positive definite on the free components (pᵀKp = {pap:e}); \
                 the constraints leave a rigid-body motion free"
            )));
        }
        let alpha = rz / pap;
        let (mut rr, mut rz_new) = (0.0, 0.0);
        for c in 0..3 {
            let (uc, rc, pc, apc, zc, id) = (&mut u.c[c], &mut r.c[c], &p.c[c], &ap.c[c], &mut z.c[c], &inv_diag[c]);
            for i in 0..n {
                uc[i][0] += alpha * pc[i][0];
                let ri = rc[i][0] - alpha * apc[i][0];
                rc[i][0] = ri;
                let zi = ri * id[i];
                zc[i][0] = zi;
                rr += ri * ri;
                rz_new += ri * zi;
            }
        }
        iterations += 1;
        rel = rr.sqrt() / b_norm;
        let beta = rz_new / rz;
        rz = rz_new;
        for c in 0..3 {
            let (pc, zc) = (&mut p.c[c], &z.c[c]);
            for i in 0..n {
                pc[i][0] = zc[i][0] + beta * pc[i][0];
            }
        }
    }
    Ok(iterations)
}

fn not_converged(max_iterations: usize, rel: f64) -> SolverError {
    SolverError::Numerical(format!(
        "static solve did not converge in {max_iterations} iterations (relative residual {rel:.3e})"
    ))
}
