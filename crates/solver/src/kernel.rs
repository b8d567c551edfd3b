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
//! seed alone (`L = 1`). The kernels are compiled three times — baseline x86-64, AVX2 and AVX-512
//! — and the widest the CPU has is picked at run time; Rust never fuses a multiply and an add on
//! its own, so all three give the same bits.
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

use crate::lattice::Direction;

/// Defines `$name`, which runs the `#[inline(always)]` kernel `$kernel` compiled for the widest
/// vector instructions the CPU has — AVX-512, AVX2 or baseline x86-64, picked at run time. Rust
/// never fuses a multiply and an add on its own, so every build gives the same bits. An
/// `unsafe fn` dispatcher forwards its kernel's safety contract.
macro_rules! widest {
    ($(#[$m:meta])* fn $name:ident<const L: usize>($($a:ident: $t:ty),* $(,)?) => $kernel:ident) => {
        $(#[$m])*
        fn $name<const L: usize>($($a: $t),*) {
            // SAFETY: `$kernel` is safe; the builds differ only in instruction set.
            unsafe { $crate::kernel::widest!(@run $kernel; $($a: $t),*) }
        }
    };
    ($(#[$m:meta])* unsafe fn $name:ident<const L: usize>($($a:ident: $t:ty),* $(,)?) => $kernel:ident) => {
        $(#[$m])*
        unsafe fn $name<const L: usize>($($a: $t),*) {
            // SAFETY: the caller's contract is `$kernel`'s.
            unsafe { $crate::kernel::widest!(@run $kernel; $($a: $t),*) }
        }
    };
    (@run $kernel:ident; $($a:ident: $t:ty),*) => {{
        #[cfg(target_arch = "x86_64")]
        {
            #[target_feature(enable = "avx512f")]
            #[allow(unused_unsafe)]
            unsafe fn avx512<const L: usize>($($a: $t),*) {
                unsafe { $kernel($($a),*) }
            }
            #[target_feature(enable = "avx2")]
            #[allow(unused_unsafe)]
            unsafe fn avx2<const L: usize>($($a: $t),*) {
                unsafe { $kernel($($a),*) }
            }
            if std::is_x86_feature_detected!("avx512f") {
                return avx512($($a),*);
            }
            if std::is_x86_feature_detected!("avx2") {
                return avx2($($a),*);
            }
        }
        #[allow(unused_unsafe)]
        unsafe { $kernel($($a),*) }
    }};
}
pub(crate) use widest;

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

/// A run of bars sharing one direction class, `bars[start..end]` in kernel order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarGroup {
    /// Direction class.
    pub direction: Direction,
    /// First bar.
    pub start: usize,
    /// One past the last bar.
    pub end: usize,
}

/// A set of bars whose end nodes no other segment of the same phase touches.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// Segments of phase 0 run together, then those of phase 1, then phase 2.
    pub phase: u8,
    /// Its direction groups.
    pub groups: Vec<BarGroup>,
}

/// The bars in kernel order, checked once: every end is a node below `nodes`, every group is
/// inside the bar list, and segments of one phase touch disjoint nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct BarLayout {
    segments: Vec<Segment>,
    ends: Vec<[u32; 2]>,
    nodes: usize,
    /// Runs of nodes whose last bar is in group `g` (serial order) are
    /// `finished[finished_at[g]..finished_at[g + 1]]`; the extra last slot holds the nodes no bar
    /// touches.
    finished: Vec<Range<usize>>,
    finished_at: Vec<usize>,
}

impl BarLayout {
    /// Builds and checks a layout. Panics on an end or group out of range, or on two segments of
    /// one phase sharing a node (a programming error, not an input error).
    pub fn new(segments: Vec<Segment>, ends: Vec<[u32; 2]>, nodes: usize) -> Self {
        assert!(ends.iter().all(|e| (e[0] as usize) < nodes && (e[1] as usize) < nodes), "bar end out of range");
        for s in &segments {
            assert!(s.groups.iter().all(|g| g.start <= g.end && g.end <= ends.len()), "group out of range");
        }
        for phase in 0..3u8 {
            let mut owner = vec![usize::MAX; nodes];
            for (k, s) in segments.iter().enumerate().filter(|(_, s)| s.phase == phase) {
                for g in &s.groups {
                    for e in &ends[g.start..g.end] {
                        for &n in e {
                            let o = &mut owner[n as usize];
                            assert!(
                                *o == usize::MAX || *o == k,
                                "segments {k} and {o} of phase {phase} share node {n}"
                            );
                            *o = k;
                        }
                    }
                }
            }
        }
        let (finished, finished_at) = finishing_order(&segments, &ends, nodes);
        BarLayout { segments, ends, nodes, finished, finished_at }
    }

    /// Runs of nodes whose forces are complete once group `slot` (serial order over every
    /// segment) has run; slot `groups().count()` holds the nodes no bar touches.
    pub fn finished_after(&self, slot: usize) -> &[Range<usize>] {
        &self.finished[self.finished_at[slot]..self.finished_at[slot + 1]]
    }

    /// Segments in serial order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Bar end nodes (internal indices), kernel order.
    pub fn ends(&self) -> &[[u32; 2]] {
        &self.ends
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// Every group of every segment, in serial order.
    pub fn groups(&self) -> impl Iterator<Item = &BarGroup> {
        self.segments.iter().flat_map(|s| s.groups.iter())
    }

    fn check<const L: usize>(&self, k: &[Lanes<L>], u: &Field<L>, f: &Field<L>) {
        assert_eq!(k.len(), self.ends.len(), "one stiffness per bar");
        for c in 0..3 {
            assert!(u.c[c].len() == self.nodes && f.c[c].len() == self.nodes, "fields over the layout's nodes");
        }
    }
}

/// For every group in serial order (and one slot after them for untouched nodes), the runs of
/// nodes whose last bar is in that group, in increasing node order.
fn finishing_order(segments: &[Segment], ends: &[[u32; 2]], nodes: usize) -> (Vec<Range<usize>>, Vec<usize>) {
    let groups: Vec<&BarGroup> = segments.iter().flat_map(|s| s.groups.iter()).collect();
    let mut last = vec![groups.len(); nodes];
    for (slot, g) in groups.iter().enumerate() {
        for e in &ends[g.start..g.end] {
            for &n in e {
                last[n as usize] = slot;
            }
        }
    }
    let mut by_slot: Vec<Vec<Range<usize>>> = vec![Vec::new(); groups.len() + 1];
    for (n, &slot) in last.iter().enumerate() {
        let runs = &mut by_slot[slot];
        match runs.last_mut() {
            Some(r) if r.end == n => r.end = n + 1,
            _ => runs.push(n..n + 1),
        }
    }
    let mut finished_at = vec![0];
    let mut finished = Vec::new();
    for runs in by_slot {
        finished.extend(runs);
        finished_at.push(finished.len());
    }
    (finished, finished_at)
}

/// Raw view of the force field shared by the threads of one phase.
#[derive(Clone, Copy)]
struct ForcePtr<const L: usize>([*mut Lanes<L>; 3]);

// SAFETY: the segments run together write disjoint nodes (checked by `BarLayout::new`).
unsafe impl<const L: usize> Send for ForcePtr<L> {}
unsafe impl<const L: usize> Sync for ForcePtr<L> {}

/// Adds the internal bar forces `−K·u` to `f`, on the calling thread.
pub fn bar_forces<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], u: &Field<L>, f: &mut Field<L>) {
    layout.check(k, u, f);
    let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
    for s in &layout.segments {
        // SAFETY: checked layout, one thread.
        unsafe { segment_dispatch(s, &layout.ends, k, u, fp) };
    }
}

/// As [`bar_forces`], running the segments of each phase on the current rayon pool. The result
/// is bit-identical to [`bar_forces`]: every node receives its contributions in the same order.
pub fn bar_forces_parallel<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], u: &Field<L>, f: &mut Field<L>) {
    layout.check(k, u, f);
    let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
    for phase in 0..3u8 {
        let segs: Vec<&Segment> = layout.segments.iter().filter(|s| s.phase == phase).collect();
        segs.par_iter().for_each(|s| {
            // SAFETY: checked layout; segments of one phase write disjoint nodes.
            unsafe { segment_dispatch(s, &layout.ends, k, u, fp) }
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
    layout.check(k, u, f);
    let mut slot = 0;
    for s in &layout.segments {
        for g in &s.groups {
            let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
            // SAFETY: checked layout, one thread; `fp` is not used past this call.
            unsafe { group_dispatch(g, &layout.ends, k, u, fp) };
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
    /// Runs one group with the widest vector instructions the CPU has.
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
    s: &Segment,
    ends: &[[u32; 2]],
    k: &[Lanes<L>],
    u: &Field<L>,
    f: ForcePtr<L>,
) {
    for g in &s.groups {
        // SAFETY: forwarded contract.
        unsafe { group_dispatch(g, ends, k, u, f) }
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

/// `½ Σ_b k_b·e_b(a)·e_b(b)` for lane `l`: the strain energy `½aᵀKb` (J). With `a = b` it is the
/// strain energy of one state; with `a = uₙ`, `b = uₙ₊₁` it is the energy the central-difference
/// scheme conserves exactly.
pub fn strain_energy<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], a: &Field<L>, b: &Field<L>, l: usize) -> f64 {
    let ends = layout.ends();
    let mut total = 0.0;
    for g in layout.groups() {
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
    use crate::{Model, Scene, SceneFile};

    #[test]
    fn finishing_hands_over_every_node_once_with_its_complete_force() {
        for (nx, ny, nz) in [(10, 1, 5), (40, 20, 4)] {
            let mut file = SceneFile::default();
            (file.block.nx, file.block.ny, file.block.nz) = (nx, ny, nz);
            let m = Model::new(Scene::try_from(file).unwrap());
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

    #[test]
    #[should_panic(expected = "share node")]
    fn a_layout_with_overlapping_segments_is_refused() {
        let g = |s, e| BarGroup { direction: Direction::Axis(0), start: s, end: e };
        let _ = BarLayout::new(
            vec![Segment { phase: 0, groups: vec![g(0, 1)] }, Segment { phase: 0, groups: vec![g(1, 2)] }],
            vec![[0, 1], [1, 2]],
            3,
        );
    }
}
