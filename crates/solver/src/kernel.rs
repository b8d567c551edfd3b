//! The per-bar kernels: internal forces and strain energy, for `L` seeds side by side.
//!
//! Kinematics are small-strain (linearised): a bar's elongation is `e·(u_j − u_i)` with `e` its
//! undeformed unit vector, so the internal force is exactly linear in the displacements (what
//! makes the static solve and the critical step exact). Bars are grouped by direction class
//! (three axes, four body diagonals); each group runs a kernel monomorphised for its direction,
//! chosen once per group, with no branch inside the loop:
//! - axial bars touch one component: `t = k·(u_j − u_i)`, `f_i += t`, `f_j −= t`;
//! - diagonals `(sx, sy, 1)/√3` use the stored stiffness `k/3`: `t = (k/3)·(s·Δu)`,
//!   `f_i += t·s`, `f_j −= t·s`.
//!
//! Every array is `[f64; L]` per node or bar: lane `l` is an independent seed. All lanes run the
//! same arithmetic in the same order, so lane `l` of a batch is bit-identical to a run of that
//! seed alone (`L = 1`).

use crate::lattice::Direction;
use crate::model::BarGroup;

/// One `f64` per lane.
pub type Lanes<const L: usize> = [f64; L];

/// A vector field over the nodes, structure of arrays: `c[axis][node][lane]`.
#[derive(Clone, Debug, PartialEq)]
pub struct Field<const L: usize> {
    /// Components x, y, z.
    pub c: [Vec<Lanes<L>>; 3],
}

impl<const L: usize> Field<L> {
    /// A zero field over `n` nodes.
    pub fn zeros(n: usize) -> Self {
        Field { c: [vec![[0.0; L]; n], vec![[0.0; L]; n], vec![[0.0; L]; n]] }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.c[0].len()
    }

    /// Whether the field has no nodes.
    pub fn is_empty(&self) -> bool {
        self.c[0].is_empty()
    }

    /// Sets every value to zero.
    pub fn fill_zero(&mut self) {
        for comp in &mut self.c {
            comp.fill([0.0; L]);
        }
    }

    /// Value of lane `l` at `node`.
    pub fn get(&self, node: usize, l: usize) -> [f64; 3] {
        [self.c[0][node][l], self.c[1][node][l], self.c[2][node][l]]
    }
}

/// Adds the internal bar forces `−K·u` to `f`.
pub fn bar_forces<const L: usize>(
    groups: &[BarGroup],
    ends: &[[u32; 2]],
    k: &[Lanes<L>],
    u: &Field<L>,
    f: &mut Field<L>,
) {
    for g in groups {
        let (e, kk) = (&ends[g.start..g.end], &k[g.start..g.end]);
        match g.direction {
            Direction::Axis(a) => {
                let a = a as usize;
                axial(e, kk, &u.c[a], &mut f.c[a]);
            }
            Direction::Diagonal { neg_x: false, neg_y: false } => diagonal::<L, false, false>(e, kk, u, f),
            Direction::Diagonal { neg_x: false, neg_y: true } => diagonal::<L, false, true>(e, kk, u, f),
            Direction::Diagonal { neg_x: true, neg_y: false } => diagonal::<L, true, false>(e, kk, u, f),
            Direction::Diagonal { neg_x: true, neg_y: true } => diagonal::<L, true, true>(e, kk, u, f),
        }
    }
}

#[inline(always)]
fn axial<const L: usize>(ends: &[[u32; 2]], k: &[Lanes<L>], u: &[Lanes<L>], f: &mut [Lanes<L>]) {
    for (e, kb) in ends.iter().zip(k) {
        let (i, j) = (e[0] as usize, e[1] as usize);
        let (ui, uj) = (u[i], u[j]);
        let mut t = [0.0; L];
        for l in 0..L {
            t[l] = kb[l] * (uj[l] - ui[l]);
        }
        for l in 0..L {
            f[i][l] += t[l];
        }
        for l in 0..L {
            f[j][l] -= t[l];
        }
    }
}

#[inline(always)]
fn sign<const NEG: bool>(v: f64) -> f64 {
    if NEG { -v } else { v }
}

#[inline(always)]
fn diagonal<const L: usize, const NX: bool, const NY: bool>(
    ends: &[[u32; 2]],
    k: &[Lanes<L>],
    u: &Field<L>,
    f: &mut Field<L>,
) {
    let [ux, uy, uz] = &u.c;
    let [fx, fy, fz] = &mut f.c;
    for (e, kb) in ends.iter().zip(k) {
        let (i, j) = (e[0] as usize, e[1] as usize);
        let mut t = [0.0; L];
        for l in 0..L {
            let s = sign::<NX>(ux[j][l] - ux[i][l]) + sign::<NY>(uy[j][l] - uy[i][l]) + (uz[j][l] - uz[i][l]);
            t[l] = kb[l] * s;
        }
        for l in 0..L {
            let (tx, ty) = (sign::<NX>(t[l]), sign::<NY>(t[l]));
            fx[i][l] += tx;
            fx[j][l] -= tx;
            fy[i][l] += ty;
            fy[j][l] -= ty;
            fz[i][l] += t[l];
            fz[j][l] -= t[l];
        }
    }
}

/// `½ Σ_b k_b·e_b(a)·e_b(b)` for lane `l`: the strain energy `½aᵀKb` (J). With `a = b` it is the
/// strain energy of one state; with `a = uₙ`, `b = uₙ₊₁` it is the energy the central-difference
/// scheme conserves exactly.
pub fn strain_energy<const L: usize>(
    groups: &[BarGroup],
    ends: &[[u32; 2]],
    k: &[Lanes<L>],
    a: &Field<L>,
    b: &Field<L>,
    l: usize,
) -> f64 {
    let mut total = 0.0;
    for g in groups {
        let range = g.start..g.end;
        let mut sum = 0.0;
        match g.direction {
            Direction::Axis(ax) => {
                let (ca, cb) = (&a.c[ax as usize], &b.c[ax as usize]);
                for (e, kb) in ends[range.clone()].iter().zip(&k[range]) {
                    let (i, j) = (e[0] as usize, e[1] as usize);
                    sum += kb[l] * (ca[j][l] - ca[i][l]) * (cb[j][l] - cb[i][l]);
                }
            }
            Direction::Diagonal { neg_x, neg_y } => {
                let (sx, sy) = (if neg_x { -1.0 } else { 1.0 }, if neg_y { -1.0 } else { 1.0 });
                let proj = |u: &Field<L>, i: usize, j: usize| {
                    sx * (u.c[0][j][l] - u.c[0][i][l])
                        + sy * (u.c[1][j][l] - u.c[1][i][l])
                        + (u.c[2][j][l] - u.c[2][i][l])
                };
                for (e, kb) in ends[range.clone()].iter().zip(&k[range]) {
                    let (i, j) = (e[0] as usize, e[1] as usize);
                    sum += kb[l] * proj(a, i, j) * proj(b, i, j);
                }
            }
        }
        total += sum;
    }
    0.5 * total
}

/// Diagonal of the stiffness matrix per node and component, for one lane of `k`.
pub fn stiffness_diagonal<const L: usize>(
    groups: &[BarGroup],
    ends: &[[u32; 2]],
    k: &[Lanes<L>],
    n: usize,
    l: usize,
) -> Field<1> {
    let mut d = Field::<1>::zeros(n);
    for g in groups {
        for (e, kb) in ends[g.start..g.end].iter().zip(&k[g.start..g.end]) {
            for &node in e {
                match g.direction {
                    Direction::Axis(a) => d.c[a as usize][node as usize][0] += kb[l],
                    Direction::Diagonal { .. } => {
                        for a in 0..3 {
                            d.c[a][node as usize][0] += kb[l];
                        }
                    }
                }
            }
        }
    }
    d
}
