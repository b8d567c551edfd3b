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
use stickslip_isa::{Isa, widest};

use crate::field::{Field, Lanes};
use crate::geometry::Direction;
use crate::layout::{BarGroup, BarLayout, Bars, Segment};
use crate::step::primitives::{ForcePtr, add_lanes, check, project, scatter_diagonal, signs, sub_lanes};
use crate::stiffness::StiffnessRef;

/// Adds the internal bar forces `−K·u` to `f`, on the calling thread, whatever the layout.
pub fn bar_forces<'k, const L: usize>(bars: &Bars, k: impl Into<StiffnessRef<'k, L>>, u: &Field<L>, f: &mut Field<L>) {
    let k = k.into();
    match bars {
        Bars::Listed(layout) => {
            let StiffnessRef::PerBar(k) = k else { panic!("a listed lattice has per-bar stiffness") };
            listed_forces(layout, k, u, f)
        }
        Bars::Stencil(layout) => crate::step::stencil::forces(layout, k, u, f),
    }
}

/// Adds the internal bar forces `−K·u` of a listed layout to `f`, on the calling thread.
pub fn listed_forces<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], u: &Field<L>, f: &mut Field<L>) {
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
            add_lanes(&mut *f.add(i), &t);
            sub_lanes(&mut *f.add(j), &t);
        }
    }
}

#[inline(always)]
unsafe fn diagonal<const L: usize, const NX: bool, const NY: bool>(
    ends: &[[u32; 2]],
    k: &[Lanes<L>],
    u: &Field<L>,
    f: ForcePtr<L>,
) {
    let (sx, sy) = signs(NX, NY);
    let (ux, uy, uz) = (u.c[0].as_ptr(), u.c[1].as_ptr(), u.c[2].as_ptr());
    for (e, kb) in ends.iter().zip(k) {
        let (i, j) = (e[0] as usize, e[1] as usize);
        // SAFETY: i, j are node indices below the arrays' length (checked layout), and i ≠ j.
        unsafe {
            let p = project(sx, sy, [&*ux.add(i), &*uy.add(i), &*uz.add(i)], [&*ux.add(j), &*uy.add(j), &*uz.add(j)]);
            let mut t = [0.0; L];
            for l in 0..L {
                t[l] = kb[l] * p[l];
            }
            scatter_diagonal(f, i, j, sx, sy, &t);
        }
    }
}

/// Diagonal of the stiffness matrix per node and component, for one lane of `k`.
pub fn stiffness_diagonal<'k, const L: usize>(bars: &Bars, k: impl Into<StiffnessRef<'k, L>>, l: usize) -> Field<1> {
    let mut d = Field::<1>::zeros(bars.nodes());
    k.into().visit(bars, l, |i, j, direction, k| {
        for node in [i, j] {
            match direction {
                Direction::Axis(a) => d.c[a as usize][node][0] += k,
                // k stored as k/3 and s_c² = 1: each component's diagonal gains k/3.
                Direction::Diagonal { .. } => {
                    for c in 0..3 {
                        d.c[c][node][0] += k;
                    }
                }
            }
        }
    });
    d
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finishing_hands_over_every_node_once_with_its_complete_force() {
        for (nx, ny, nz) in [(10, 1, 5), (40, 20, 4)] {
            let scene =
                crate::scene::Scene { dims: crate::geometry::Dims::new(nx, ny, nz), ..crate::scene::Scene::paper() };
            let m = crate::model::Model::new(scene);
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
            bar_forces_finishing(m.layout().listed(), &k, &u, &mut f, |r, f| {
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

    /// The bar forces written plainly: every bar in kernel order, one lane at a time, the
    /// arithmetic of the module doc.
    fn reference<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], u: &Field<L>) -> Field<L> {
        let mut f = Field::<L>::zeros(layout.nodes());
        for g in layout.groups() {
            for (e, kb) in layout.ends()[g.start..g.end].iter().zip(&k[g.start..g.end]) {
                let (i, j) = (e[0] as usize, e[1] as usize);
                for l in 0..L {
                    match g.direction {
                        Direction::Axis(a) => {
                            let a = a as usize;
                            let t = kb[l] * (u.c[a][j][l] - u.c[a][i][l]);
                            f.c[a][i][l] += t;
                            f.c[a][j][l] -= t;
                        }
                        Direction::Diagonal { neg_x, neg_y } => {
                            let sx = if neg_x { -1.0 } else { 1.0 };
                            let sy = if neg_y { -1.0 } else { 1.0 };
                            let d = |c: usize| u.c[c][j][l] - u.c[c][i][l];
                            let t = kb[l] * (sx * d(0) + sy * d(1) + d(2));
                            let tc = [sx * t, sy * t, t];
                            for c in 0..3 {
                                f.c[c][i][l] += tc[c];
                                f.c[c][j][l] -= tc[c];
                            }
                        }
                    }
                }
            }
        }
        f
    }

    /// A random displacement field and stiffness for `L` lanes.
    fn random_state<const L: usize>(m: &crate::model::Model, seed: u64) -> (Vec<Lanes<L>>, Field<L>) {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed);
        let k0 = m.nominal_stiffness();
        let k = k0.iter().map(|&v| std::array::from_fn(|_| v * rng.random_range(0.8..1.2))).collect();
        let mut u = Field::<L>::zeros(m.node_count());
        for c in 0..3 {
            for v in u.c[c].iter_mut() {
                *v = std::array::from_fn(|_| rng.random_range(-1e-6..1e-6));
            }
        }
        (k, u)
    }

    fn model(nx: usize, ny: usize, nz: usize) -> crate::model::Model {
        let scene =
            crate::scene::Scene { dims: crate::geometry::Dims::new(nx, ny, nz), ..crate::scene::Scene::paper() };
        crate::model::Model::with_listed_bars(scene)
    }

    fn every_pass_agrees<const L: usize>(m: &crate::model::Model, seed: u64) {
        let (k, u) = random_state::<L>(m, seed);
        let want = reference(m.layout().listed(), &k, &u);
        let n = m.node_count();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        for isa in Isa::available() {
            Isa::pinned(isa, || {
                let mut f = Field::<L>::zeros(n);
                bar_forces(m.layout(), &k, &u, &mut f);
                assert_eq!(f, want, "plain pass, {isa:?}, {L} lanes");
                let mut f = Field::<L>::zeros(n);
                bar_forces_finishing(m.layout().listed(), &k, &u, &mut f, |_, _| {});
                assert_eq!(f, want, "finishing pass, {isa:?}, {L} lanes");
                let mut f = Field::<L>::zeros(n);
                pool.install(|| bar_forces_parallel(m.layout().listed(), &k, &u, &mut f));
                assert_eq!(f, want, "parallel pass, {isa:?}, {L} lanes");
            });
        }
    }

    #[test]
    fn every_build_and_pass_of_the_bar_kernel_agrees_with_the_plain_reference() {
        // The paper lattice (one segment), a cache-blocked one, and one cut into z-slabs.
        for (nx, ny, nz) in [(10, 1, 5), (40, 20, 4), (40, 20, 10)] {
            let m = model(nx, ny, nz);
            every_pass_agrees::<1>(&m, 1);
            every_pass_agrees::<8>(&m, 2);
        }
        assert!(model(40, 20, 10).layout().listed().segments().len() > 1, "the last lattice is cut into slabs");
    }

    #[test]
    fn fused_pass_gives_the_plain_pass_and_integration_in_every_build() {
        use crate::step::integrate::Coefficients;
        use crate::step::integrate::{Levels, Update, integrate_all, integrate_range};
        let m = model(40, 20, 4);
        assert!(m.cache_blocked());
        let (k, u) = random_state::<4>(&m, 5);
        let (_, up) = random_state::<4>(&m, 6);
        let coef = Coefficients {
            cf: [1e-11, 2e-11, 3e-11, 4e-11],
            c2: [1.99, 1.98, 1.97, 1.96],
            cp: [0.99, 0.98, 0.97, 0.96],
        };
        let body = [[0.0; 4], [0.0; 4], [-9.81, -9.81, -1.0, 0.0]];
        let update = Update { inv_mass: m.inv_mass(), coef: &coef, body: &body };
        // The trial written plainly.
        let f = reference(m.layout().listed(), &k, &u);
        let mut want = Field::<4>::zeros(m.node_count());
        for c in 0..3 {
            for i in 0..m.node_count() {
                for l in 0..4 {
                    let im = m.inv_mass()[i];
                    want.c[c][i][l] = coef.cf[l] * (f.c[c][i][l] * im + body[c][l]) + coef.c2[l] * u.c[c][i][l]
                        - coef.cp[l] * up.c[c][i][l];
                }
            }
        }
        for isa in Isa::available() {
            Isa::pinned(isa, || {
                let mut f = Field::<4>::zeros(m.node_count());
                let mut plain = Field::<4>::zeros(m.node_count());
                bar_forces(m.layout(), &k, &u, &mut f);
                integrate_all(&update, &mut f, Levels { u: &u, up: &up, out: &mut plain }, false);
                assert_eq!(plain, want, "plain pass and integration, {isa:?}");
                assert!(f.c.iter().all(|c| c.iter().all(|v| *v == [0.0; 4])), "the force field is cleared");
                let mut f = Field::<4>::zeros(m.node_count());
                let mut fused = Field::<4>::zeros(m.node_count());
                bar_forces_finishing(m.layout().listed(), &k, &u, &mut f, |r, f| {
                    integrate_range(isa, r, &update, f, Levels { u: &u, up: &up, out: &mut fused });
                });
                assert_eq!(fused, want, "fused pass, {isa:?}");
            });
        }
    }
}
