//! What every bar kernel shares, below them all: the checks of a layout's arrays, the raw force
//! field the threads of a phase share, lane arithmetic, a diagonal's signs, projection and
//! scatter, a bar's elongation, and the strain energy summed group by group in kernel order (the
//! listed and rupture kernels' ledgers).

use crate::field::{Field, Lanes};
use crate::geometry::Direction;
use crate::layout::BarLayout;
use crate::ledger::EnergyLayers;

/// Checks that `k`, `u` and `f` fit `layout` (the kernels index them without bounds checks).
pub(crate) fn check<const L: usize>(layout: &BarLayout, k: &[Lanes<L>], u: &Field<L>, f: &Field<L>) {
    assert_eq!(k.len(), layout.ends().len(), "one stiffness per bar");
    for c in 0..3 {
        assert!(u.c[c].len() == layout.nodes() && f.c[c].len() == layout.nodes(), "fields over the layout's nodes");
    }
}

/// Raw view of the force field shared by the threads of one phase.
#[derive(Clone, Copy)]
pub(crate) struct ForcePtr<const L: usize>(pub(crate) [*mut Lanes<L>; 3]);

// SAFETY: the segments run together write disjoint nodes (checked by `BarLayout::new`).
unsafe impl<const L: usize> Send for ForcePtr<L> {}
unsafe impl<const L: usize> Sync for ForcePtr<L> {}

#[inline(always)]
pub(crate) fn add_lanes<const L: usize>(a: &mut Lanes<L>, b: &Lanes<L>) {
    for l in 0..L {
        a[l] += b[l];
    }
}

#[inline(always)]
pub(crate) fn sub_lanes<const L: usize>(a: &mut Lanes<L>, b: &Lanes<L>) {
    for l in 0..L {
        a[l] -= b[l];
    }
}

/// The x and y signs of a diagonal's direction `(sx, sy, 1)` (multiplying by ±1 is exact, so
/// this is the same arithmetic as negating).
#[inline(always)]
pub(crate) fn signs(neg_x: bool, neg_y: bool) -> (f64, f64) {
    (if neg_x { -1.0 } else { 1.0 }, if neg_y { -1.0 } else { 1.0 })
}

/// A diagonal's elongation in kernel units, `s·(u_j − u_i)` with `s = (sx, sy, 1)`, for `L`
/// lanes from the displacements `[x, y, z]` of its two ends.
#[inline(always)]
pub(crate) fn project<const L: usize>(sx: f64, sy: f64, ui: [&Lanes<L>; 3], uj: [&Lanes<L>; 3]) -> Lanes<L> {
    let mut p = [0.0; L];
    for l in 0..L {
        p[l] = sx * (uj[0][l] - ui[0][l]) + sy * (uj[1][l] - ui[1][l]) + (uj[2][l] - ui[2][l]);
    }
    p
}

/// The elongation in kernel units of bar `(i, j)` of direction `direction` in lane `l`: `e·Δu`
/// (axial) or `s·Δu` (diagonal, √3 times the elongation).
#[inline(always)]
pub(crate) fn elongation<const L: usize>(direction: Direction, u: &Field<L>, i: usize, j: usize, l: usize) -> f64 {
    let d = |c: usize| u.c[c][j][l] - u.c[c][i][l];
    match direction {
        Direction::Axis(a) => d(a as usize),
        Direction::Diagonal { neg_x, neg_y } => {
            let (sx, sy) = signs(neg_x, neg_y);
            sx * d(0) + sy * d(1) + d(2)
        }
    }
}

/// Adds a diagonal's force `t·s` to end `i` and subtracts it from end `j`.
///
/// # Safety
/// `i` and `j` are node indices below the force arrays' length, `i ≠ j`, and no other thread
/// writes them.
#[inline(always)]
pub(crate) unsafe fn scatter_diagonal<const L: usize>(
    f: ForcePtr<L>,
    i: usize,
    j: usize,
    sx: f64,
    sy: f64,
    t: &Lanes<L>,
) {
    let [fx, fy, fz] = f.0;
    // One array per loop: the compiler cannot tell the force arrays apart, so loops that write
    // only one of them are the ones it can turn into vector operations.
    let (tx, ty) = (t.map(|v| sx * v), t.map(|v| sy * v));
    // SAFETY: forwarded contract.
    unsafe {
        add_lanes(&mut *fx.add(i), &tx);
        add_lanes(&mut *fy.add(i), &ty);
        add_lanes(&mut *fz.add(i), t);
        sub_lanes(&mut *fx.add(j), &tx);
        sub_lanes(&mut *fy.add(j), &ty);
        sub_lanes(&mut *fz.add(j), t);
    }
}

/// `Σ_b k_b·e_b(a)·e_b(b)` for lane `l` with `k_b = stiffness(bar, e_b(a))`, per layer of
/// `layers` (a bar in its lower end's layer; bars of other layers skipped), each layer's bars in
/// kernel order (so every caller gets the same bits for the same stiffness).
pub(crate) fn strain_energy_with<const L: usize>(
    layout: &BarLayout,
    layers: &EnergyLayers,
    a: &Field<L>,
    b: &Field<L>,
    l: usize,
    stiffness: impl Fn(usize, f64) -> f64,
) -> Vec<f64> {
    let ends = layout.ends();
    let mut sums = vec![0.0; layers.count];
    for g in layout.groups() {
        for bar in g.start..g.end {
            let (i, j) = (ends[bar][0] as usize, ends[bar][1] as usize);
            let Some(k) = layers.of(i.min(j)) else { continue };
            let pa = elongation(g.direction, a, i, j, l);
            sums[k] += stiffness(bar, pa) * pa * elongation(g.direction, b, i, j, l);
        }
    }
    sums
}
