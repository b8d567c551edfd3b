//! The trial update of central differences with mass-proportional damping (docs/model.md §2):
//! `u⁺ = [Δt²(f/m + b) + 2u − (1 − DΔt/2)u⁻] / (1 + DΔt/2)` for every node and lane.

use std::ops::Range;

use rayon::prelude::*;
use stickslip_isa::{Isa, widest};

use crate::field::{Field, Lanes};

/// What the update reads besides the time levels: inverse masses, the per-lane coefficients and
/// the body acceleration.
#[derive(Clone, Copy)]
pub struct Update<'a, const L: usize> {
    /// Inverse lumped mass of each node (1/kg).
    pub inv_mass: &'a [f64],
    /// Coefficients of the update, per lane.
    pub coef: &'a Coefficients<L>,
    /// Body acceleration per axis and lane (m/s²).
    pub body: &'a [Lanes<L>; 3],
}

/// The three fields the update touches: `u = uₙ` and `up = uₙ₋₁` read, `out` written.
pub struct Levels<'a, const L: usize> {
    /// `uₙ`.
    pub u: &'a Field<L>,
    /// `uₙ₋₁`.
    pub up: &'a Field<L>,
    /// `uₙ₊₁` (the trial).
    pub out: &'a mut Field<L>,
}

/// The three time levels the fused integration reads and writes, shared by the slab tasks of one
/// phase of the stencil kernel ([`crate::step::stencil`]), which write disjoint layers.
#[derive(Clone, Copy)]
pub(crate) struct LevelsPtr<const L: usize> {
    /// `uₙ`.
    pub u: [*const Lanes<L>; 3],
    /// `uₙ₋₁`.
    pub up: [*const Lanes<L>; 3],
    /// The trial, written.
    pub out: [*mut Lanes<L>; 3],
}

// SAFETY: the tasks of one phase write disjoint nodes (see the stencil kernel's module doc).
unsafe impl<const L: usize> Send for LevelsPtr<L> {}
unsafe impl<const L: usize> Sync for LevelsPtr<L> {}

/// Per-lane coefficients of the trial update `u⁺ = cf·(f/m + b) + c2·u − cp·u⁻`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Coefficients<const L: usize> {
    /// `Δt²/(1 + DΔt/2)`.
    pub cf: Lanes<L>,
    /// `2/(1 + DΔt/2)`.
    pub c2: Lanes<L>,
    /// `(1 − DΔt/2)/(1 + DΔt/2)`.
    pub cp: Lanes<L>,
}

/// Trial update of every node, clearing the force field `f` as it is consumed; with `parallel`,
/// chunks of nodes on the current rayon pool (the same arithmetic).
pub fn integrate_all<const L: usize>(up: &Update<'_, L>, f: &mut Field<L>, levels: Levels<'_, L>, parallel: bool) {
    let isa = Isa::current();
    for c in 0..3 {
        let (f, u, prev, out) = (&mut f.c[c], &levels.u.c[c], &levels.up.c[c], &mut levels.out.c[c]);
        let one = One { inv_mass: up.inv_mass, coef: up.coef, body: up.body[c] };
        if parallel {
            // Nodes are independent here: chunks of them on the pool, the same arithmetic.
            const CHUNK: usize = 4096;
            up.inv_mass
                .par_chunks(CHUNK)
                .zip(f.par_chunks_mut(CHUNK))
                .zip(u.par_chunks(CHUNK))
                .zip(prev.par_chunks(CHUNK))
                .zip(out.par_chunks_mut(CHUNK))
                .for_each(|((((im, f), u), prev), out)| {
                    integrate_dispatch(isa, &One { inv_mass: im, ..one }, f, u, prev, out)
                });
        } else {
            integrate_dispatch(isa, &one, f, u, prev, out);
        }
    }
}

/// As [`integrate_all`] for the nodes `range` only (the fused pass integrates a node right after
/// its last bar), in instruction set `isa`.
pub fn integrate_range<const L: usize>(
    isa: Isa,
    range: Range<usize>,
    up: &Update<'_, L>,
    f: &mut Field<L>,
    levels: Levels<'_, L>,
) {
    for c in 0..3 {
        let r = range.clone();
        let one = One { inv_mass: &up.inv_mass[r.clone()], coef: up.coef, body: up.body[c] };
        integrate_dispatch(
            isa,
            &one,
            &mut f.c[c][r.clone()],
            &levels.u.c[c][r.clone()],
            &levels.up.c[c][r.clone()],
            &mut levels.out.c[c][r],
        );
    }
}

/// As [`integrate_range`], on fields shared with other threads: `f` the forces, `levels` the
/// time levels.
///
/// # Safety
/// `range` lies inside every array, and no other thread reads or writes the nodes of `range` of
/// `f` and `levels.out` meanwhile.
pub(crate) unsafe fn integrate_raw<const L: usize>(
    isa: Isa,
    range: Range<usize>,
    up: &Update<'_, L>,
    f: [*mut Lanes<L>; 3],
    levels: LevelsPtr<L>,
) {
    let (start, n) = (range.start, range.len());
    for c in 0..3 {
        let one = One { inv_mass: &up.inv_mass[range.clone()], coef: up.coef, body: up.body[c] };
        // SAFETY: forwarded contract.
        unsafe {
            integrate_dispatch(
                isa,
                &one,
                std::slice::from_raw_parts_mut(f[c].add(start), n),
                std::slice::from_raw_parts(levels.u[c].add(start), n),
                std::slice::from_raw_parts(levels.up[c].add(start), n),
                std::slice::from_raw_parts_mut(levels.out[c].add(start), n),
            );
        }
    }
}

/// The update of one component over a run of nodes.
#[derive(Clone, Copy)]
struct One<'a, const L: usize> {
    inv_mass: &'a [f64],
    coef: &'a Coefficients<L>,
    body: Lanes<L>,
}

widest! {
    /// The trial update of one component over a run of nodes, in instruction set `isa`; clears
    /// `f` as it reads it.
    fn integrate_dispatch<const L: usize>(
        one: &One<'_, L>,
        f: &mut [Lanes<L>],
        u: &[Lanes<L>],
        up: &[Lanes<L>],
        out: &mut [Lanes<L>],
    ) => integrate
}

#[inline(always)]
fn integrate<const L: usize>(
    one: &One<'_, L>,
    f: &mut [Lanes<L>],
    u: &[Lanes<L>],
    up: &[Lanes<L>],
    out: &mut [Lanes<L>],
) {
    // The coefficients as local values, so they stay in registers through the loop.
    let (inv_mass, body) = (one.inv_mass, one.body);
    let (cf, c2, cp) = (one.coef.cf, one.coef.c2, one.coef.cp);
    let n = inv_mass.len();
    let (f, u, up, out) = (&mut f[..n], &u[..n], &up[..n], &mut out[..n]);
    for i in 0..n {
        let im = inv_mass[i];
        let (fi, ui, upi) = (f[i], u[i], up[i]);
        let mut o = [0.0; L];
        for l in 0..L {
            o[l] = cf[l] * (fi[l] * im + body[l]) + c2[l] * ui[l] - cp[l] * upi[l];
        }
        out[i] = o;
        f[i] = [0.0; L];
    }
}
