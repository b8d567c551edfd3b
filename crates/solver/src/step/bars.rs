//! The bar kernels: internal forces for `L` seeds side by side, and the bar layout they run on.
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
//! seed alone (`L = 1`). The kernels are compiled for every instruction set of [`Isa`] and the
//! widest the CPU has is picked at run time; all builds give the same bits.
//!
//! Large lattices are cut into slabs along z (see [`BarLayout`]); the bars inside one slab, then
//! those across every other slab boundary, then the rest, touch disjoint nodes, so each phase can
//! run its segments on several threads. The serial path walks the same segments in the same
//! order, so the forces are bit-identical whatever the thread count.
//!
//! [`bar_forces_finishing`] walks the same groups in the same order and, after each group, hands
//! over the nodes no later group touches: their forces are complete, so the caller can integrate
//! them while their data is still in cache instead of sweeping every node array once more.

use std::ops::Range;

use rayon::prelude::*;

use crate::field::{Field, Lanes};
use crate::geometry::Direction;
use crate::layout::{BarGroup, BarLayout, Segment};
use crate::step::isa::{Isa, widest};

/// Checks that `k`, `u` and `f` fit `layout` (the kernels index them without bounds checks).
fn check<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], u: &Field<L>, f: &Field<L>) {
    assert_eq!(k.len(), layout.ends().len(), "one stiffness per bar");
    for c in 0..3 {
        assert!(u.c[c].len() == layout.nodes() && f.c[c].len() == layout.nodes(), "fields over the layout's nodes");
    }
}

/// Raw view of the force field shared by the threads of one phase.
#[derive(Clone, Copy)]
struct ForcePtr<const L: usize>([*mut Lanes<L>; 3]);

// SAFETY: the segments run together write disjoint nodes (checked by `BarLayout::new`).
unsafe impl<const L: usize> Send for ForcePtr<L> {}
unsafe impl<const L: usize> Sync for ForcePtr<L> {}

/// Adds the internal bar forces `−K·u` to `f`, on the calling thread.
pub fn bar_forces<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], u: &Field<L>, f: &mut Field<L>) {
    check(layout, k, u, f);
    let isa = Isa::current();
    let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
    for s in layout.segments() {
        // SAFETY: checked layout, one thread.
        unsafe { segment_dispatch(isa, s, layout.ends(), k, u, fp) };
    }
}

/// As [`bar_forces`], running the segments of each phase on the current rayon pool. The result
/// is bit-identical to [`bar_forces`]: every node receives its contributions in the same order.
pub fn bar_forces_parallel<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], u: &Field<L>, f: &mut Field<L>) {
    check(layout, k, u, f);
    let isa = Isa::current();
    let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
    for phase in 0..3u8 {
        let segs: Vec<&Segment> = layout.segments().iter().filter(|s| s.phase == phase).collect();
        segs.par_iter().for_each(|s| {
            // SAFETY: checked layout; segments of one phase write disjoint nodes.
            unsafe { segment_dispatch(isa, s, layout.ends(), k, u, fp) }
        });
    }
}

/// As [`bar_forces`] (the same groups in the same order, so the same bits), calling
/// `finish(nodes, f)` after each group for every run of nodes whose forces are then complete.
/// Every node is handed over exactly once, after its last bar.
pub fn bar_forces_finishing<const L: usize>(
    layout: &BarLayout,
    k: &[Lanes<L>],
    u: &Field<L>,
    f: &mut Field<L>,
    mut finish: impl FnMut(Range<usize>, &mut Field<L>),
) {
    check(layout, k, u, f);
    let isa = Isa::current();
    let mut slot = 0;
    for s in layout.segments() {
        for g in &s.groups {
            let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
            // SAFETY: checked layout, one thread; `fp` is not used past this call.
            unsafe { group_dispatch(isa, g, layout.ends(), k, u, fp) };
            for r in layout.finished_after(slot) {
                finish(r.clone(), f);
            }
            slot += 1;
        }
    }
    for r in layout.finished_after(slot) {
        finish(r.clone(), f);
    }
}

widest! {
    /// Runs one group in instruction set `isa`.
    ///
    /// # Safety
    /// `layout.check` passed for these arrays, and no other thread writes the group's nodes.
    unsafe fn group_dispatch<const L: usize>(
        g: &BarGroup,
        ends: &[[u32; 2]],
        k: &[Lanes<L>],
        u: &Field<L>,
        f: ForcePtr<L>,
    ) => group_forces
}

/// Runs the groups of one segment.
///
/// # Safety
/// As [`group_dispatch`].
unsafe fn segment_dispatch<const L: usize>(
    isa: Isa,
    s: &Segment,
    ends: &[[u32; 2]],
    k: &[Lanes<L>],
    u: &Field<L>,
    f: ForcePtr<L>,
) {
    for g in &s.groups {
        // SAFETY: forwarded contract.
        unsafe { group_dispatch(isa, g, ends, k, u, f) }
    }
}

#[inline(always)]
unsafe fn group_forces<const L: usize>(g: &BarGroup, ends: &[[u32; 2]], k: &[Lanes<L>], u: &Field<L>, f: ForcePtr<L>) {
    let (e, kk) = (&ends[g.start..g.end], &k[g.start..g.end]);
    // SAFETY (all arms): ends are below the node count of u and f (checked layout).
    unsafe {
        match g.direction {
            Direction::Axis(a) => {
                let a = a as usize;
                axial(e, kk, u.c[a].as_ptr(), f.0[a]);
            }
            Direction::Diagonal { neg_x: false, neg_y: false } => diagonal::<L, false, false>(e, kk, u, f),
            Direction::Diagonal { neg_x: false, neg_y: true } => diagonal::<L, false, true>(e, kk, u, f),
            Direction::Diagonal { neg_x: true, neg_y: false } => diagonal::<L, true, false>(e, kk, u, f),
            Direction::Diagonal { neg_x: true, neg_y: true } => diagonal::<L, true, true>(e, kk, u, f),
        }
    }
}

#[inline(always)]
unsafe fn axial<const L: usize>(ends: &[[u32; 2]], k: &[Lanes<L>], u: *const Lanes<L>, f: *mut Lanes<L>) {
    for (e, kb) in ends.iter().zip(k) {
        let (i, j) = (e[0] as usize, e[1] as usize);
        // SAFETY: i, j are node indices below the arrays' length (checked layout).
        unsafe {
            let (ui, uj) = (*u.add(i), *u.add(j));
            let mut t = [0.0; L];
            for l in 0..L {
                t[l] = kb[l] * (uj[l] - ui[l]);
            }
            let fi = &mut *f.add(i);
            for l in 0..L {
                fi[l] += t[l];
            }
            let fj = &mut *f.add(j);
            for l in 0..L {
                fj[l] -= t[l];
            }
        }
    }
}

#[inline(always)]
fn add_lanes<const L: usize>(a: &mut Lanes<L>, b: &Lanes<L>) {
    for l in 0..L {
        a[l] += b[l];
    }
}

#[inline(always)]
fn sub_lanes<const L: usize>(a: &mut Lanes<L>, b: &Lanes<L>) {
    for l in 0..L {
        a[l] -= b[l];
    }
}

#[inline(always)]
unsafe fn diagonal<const L: usize, const NX: bool, const NY: bool>(
    ends: &[[u32; 2]],
    k: &[Lanes<L>],
    u: &Field<L>,
    f: ForcePtr<L>,
) {
    // Multiplying by ±1 is exact, so this is the same arithmetic as negating.
    let sx = if NX { -1.0 } else { 1.0 };
    let sy = if NY { -1.0 } else { 1.0 };
    let (ux, uy, uz) = (u.c[0].as_ptr(), u.c[1].as_ptr(), u.c[2].as_ptr());
    let [fx, fy, fz] = f.0;
    for (e, kb) in ends.iter().zip(k) {
        let (i, j) = (e[0] as usize, e[1] as usize);
        // SAFETY: i, j are node indices below the arrays' length (checked layout), and i ≠ j.
        unsafe {
            let (xi, xj, yi, yj, zi, zj) =
                (&*ux.add(i), &*ux.add(j), &*uy.add(i), &*uy.add(j), &*uz.add(i), &*uz.add(j));
            let mut t = [0.0; L];
            for l in 0..L {
                t[l] = kb[l] * (sx * (xj[l] - xi[l]) + sy * (yj[l] - yi[l]) + (zj[l] - zi[l]));
            }
            // One array per loop: the compiler cannot tell the force arrays apart, so loops
            // that write only one of them are the ones it can turn into vector operations.
            let (tx, ty) = (t.map(|v| sx * v), t.map(|v| sy * v));
            add_lanes(&mut *fx.add(i), &tx);
            add_lanes(&mut *fy.add(i), &ty);
            add_lanes(&mut *fz.add(i), &t);
            sub_lanes(&mut *fx.add(j), &tx);
            sub_lanes(&mut *fy.add(j), &ty);
            sub_lanes(&mut *fz.add(j), &t);
        }
    }
}

/// Diagonal of the stiffness matrix per node and component, for one lane of `k`.
pub fn stiffness_diagonal<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], l: usize) -> Field<1> {
    let mut d = Field::<1>::zeros(layout.nodes());
    let ends = layout.ends();
    for g in layout.groups() {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finishing_hands_over_every_node_once_with_its_complete_force() {
        for (nx, ny, nz) in [(10, 1, 5), (40, 20, 4)] {
            let scene = crate::Scene { dims: crate::geometry::Dims::new(nx, ny, nz), ..crate::Scene::paper() };
            let m = crate::Model::new(scene);
            let n = m.node_count();
            let k: Vec<Lanes<2>> = m.bar_stiffness(3).unwrap().iter().map(|&v| [v, 0.5 * v]).collect();
            let mut u = Field::<2>::zeros(n);
            for c in 0..3 {
                for (i, v) in u.c[c].iter_mut().enumerate() {
                    let x = ((i * 7 + c * 13) % 29) as f64 * 1e-6;
                    *v = [x, -0.3 * x];
                }
            }
            let mut plain = Field::<2>::zeros(n);
            bar_forces(m.layout(), &k, &u, &mut plain);
            let mut seen = Field::<2>::zeros(n);
            let mut times = vec![0u32; n];
            let mut f = Field::<2>::zeros(n);
            bar_forces_finishing(m.layout(), &k, &u, &mut f, |r, f| {
                for i in r {
                    times[i] += 1;
                    for c in 0..3 {
                        seen.c[c][i] = f.c[c][i];
                    }
                }
            });
            assert!(times.iter().all(|&t| t == 1), "{nx}×{ny}×{nz}: every node handed over once");
            assert_eq!(seen, plain, "{nx}×{ny}×{nz}: forces complete when handed over");
            assert_eq!(f, plain, "{nx}×{ny}×{nz}: same bits as bar_forces");
        }
    }
}
