//! The bar kernel of a stencil lattice ([`crate::stencil::StencilLayout`]): each run is a few
//! vector loops over consecutive bars and nodes, `L` seeds side by side as one flat array.
//!
//! For a run of lower ends `lo..lo+n`, upper ends `+off`, stiffness `k` (stored `k/3` for
//! diagonals, as the listed kernel):
//! - axial along `a`: `t = k·(u_a[hi] − u_a[lo])`, then `f_a[lo] += t` over the run, then
//!   `f_a[hi] −= t` over the run;
//! - diagonal `s = (sx, sy, 1)`: `t = k·(sx·Δx + sy·Δy + Δz)`, then `f[lo] += t·s` and
//!   `f[hi] −= t·s`, one component per loop.
//!
//! So a node receives its contributions in the order of the runs, and within a run first the
//! `+t` of the bar it is the lower end of, after all the run's `+t`, the `−t` of the bar it is
//! the upper end of; [`reference`] is this order written plainly and every build of the kernel is
//! tested against it bit for bit.
//!
//! The layers run slab by slab (see the layout's doc): in phase 0 every slab's layers but its top
//! one, integrating each layer as soon as its forces are complete; in phase 1 each slab's top
//! layer, integrating it and the layer above (the lattice's top layer, when it is a slab of its
//! own, runs in phase 0 and is integrated by the slab below it). On one thread the same slabs and
//! phases run in order, so the result does not depend on the thread count.
//!
//! With a dissipative medium, each run's tensions get the medium's terms before they are scattered
//! ([`RunMedium`]): a run's bars, and so their memory variables, belong to one layer, written by
//! the one task that runs it; [`reference_with_medium`] is that order written plainly.

use std::ops::Range;

use rayon::prelude::*;
use stickslip_isa::{Isa, widest};

use crate::field::{Field, Lanes};
use crate::geometry::Direction;
use crate::medium::MECHANISMS;
use crate::stencil::{Run, RunStiffness, StencilLayout};
use crate::step::anelastic::{AnelasticParams, RunMedium, Scratch};
use crate::step::integrate::{LevelsPtr, Update, integrate_raw};
use crate::step::primitives::signs;
use crate::stiffness::StiffnessRef;

/// Raw views of the arrays one pass reads and writes, shared by the slab tasks of one phase
/// (which write disjoint layers).
#[derive(Clone, Copy)]
pub(crate) struct Pass<const L: usize> {
    /// Stiffness.
    k: KPtr,
    /// Displacements now, per component, `L` per node.
    u: [*const f64; 3],
    /// Forces, per component, `L` per node.
    f: [*mut f64; 3],
    /// The medium's memory variables and dashpots, added to each run's tensions.
    medium: Option<RunMedium<L>>,
}

// SAFETY: the tasks of one phase write disjoint nodes (see the module doc).
unsafe impl<const L: usize> Send for Pass<L> {}
unsafe impl<const L: usize> Sync for Pass<L> {}

/// The stiffness one pass reads: `L` `f64` per bar, or the runs' nominal stiffness and `L` `f32`
/// factors per bar (or none).
#[derive(Clone, Copy)]
enum KPtr {
    PerBar(*const f64),
    Factored { runs: *const RunStiffness, factors: Option<*const f32> },
}

fn check<const L: usize>(layout: &StencilLayout, k: StiffnessRef<'_, L>, u: &Field<L>, f: &Field<L>) {
    if let StiffnessRef::Factored { runs, .. } = k {
        assert_eq!(runs.len(), layout.runs().len(), "one nominal stiffness per run");
    }
    if let Some(n) = k.bars() {
        assert_eq!(n, layout.bars(), "one stiffness per bar");
    }
    for c in 0..3 {
        assert!(u.c[c].len() == layout.nodes() && f.c[c].len() == layout.nodes(), "fields over the layout's nodes");
    }
}

fn pass<const L: usize>(
    k: StiffnessRef<'_, L>,
    u: &Field<L>,
    f: &mut Field<L>,
    medium: Option<RunMedium<L>>,
) -> Pass<L> {
    Pass {
        k: match k {
            StiffnessRef::PerBar(k) => KPtr::PerBar(k.as_flattened().as_ptr()),
            StiffnessRef::Factored { runs, factors } => {
                KPtr::Factored { runs: runs.as_ptr(), factors: factors.map(|f| f.as_flattened().as_ptr()) }
            }
        },
        u: [0, 1, 2].map(|c| u.c[c].as_flattened().as_ptr()),
        f: f.c.each_mut().map(|c| c.as_flattened_mut().as_mut_ptr()),
        medium,
    }
}

/// Adds the internal bar forces `−K·u` to `f`, on the calling thread, in slab and phase order.
pub fn forces<'k, const L: usize>(
    layout: &StencilLayout,
    k: impl Into<StiffnessRef<'k, L>>,
    u: &Field<L>,
    f: &mut Field<L>,
) {
    let k = k.into();
    check(layout, k, u, f);
    let (isa, p) = (Isa::current(), pass(k, u, f, None));
    let mut t = vec![0.0; layout.longest_run() * L];
    for phase in 0..2 {
        for slab in layout.slabs() {
            // SAFETY: checked arrays, one thread.
            unsafe { layers_dispatch(isa, layout, layout.phase_layers(&slab, phase), p, &mut t) };
        }
    }
}

/// As [`forces`], the slabs of each phase on the current rayon pool: the same bits.
pub fn forces_parallel<const L: usize>(layout: &StencilLayout, k: StiffnessRef<'_, L>, u: &Field<L>, f: &mut Field<L>) {
    check(layout, k, u, f);
    let (isa, p) = (Isa::current(), pass(k, u, f, None));
    let slabs: Vec<Range<usize>> = layout.slabs().collect();
    for phase in 0..2 {
        slabs.par_iter().for_each_init(
            || vec![0.0; layout.longest_run() * L],
            |t, slab| {
                // SAFETY: checked arrays; the slabs of one phase write disjoint layers.
                unsafe { layers_dispatch(isa, layout, layout.phase_layers(slab, phase), p, t) };
            },
        );
    }
}

/// As [`forces`], and each node integrated by `update` as soon as its forces are complete (the
/// force field is cleared as it is consumed); with `medium`, each run's tensions carry the
/// medium's terms ([`RunMedium`], built over `levels.up`); with `parallel`, the slabs of a phase
/// on the current rayon pool. The same bits either way.
pub(crate) fn forces_and_trial<const L: usize>(
    layout: &StencilLayout,
    k: StiffnessRef<'_, L>,
    update: &Update<'_, L>,
    f: &mut Field<L>,
    levels: crate::step::integrate::Levels<'_, L>,
    medium: Option<RunMedium<L>>,
    parallel: bool,
) {
    check(layout, k, levels.u, f);
    if let Some(m) = &medium {
        assert_eq!(m.fits, (layout.bars(), layout.nodes()), "the medium's memory variables fit this layout");
    }
    let (isa, p) = (Isa::current(), pass(k, levels.u, f, medium));
    let lv = LevelsPtr {
        u: [0, 1, 2].map(|c| levels.u.c[c].as_ptr()),
        up: [0, 1, 2].map(|c| levels.up.c[c].as_ptr()),
        out: levels.out.c.each_mut().map(|c| c.as_mut_ptr()),
    };
    let f_lanes: [*mut Lanes<L>; 3] = f.c.each_mut().map(|c| c.as_mut_ptr());
    let fp = FieldPtr(f_lanes);
    let slabs: Vec<Range<usize>> = layout.slabs().collect();
    let last = slabs.len() - 1;
    let run = |s: usize, phase: u8, t: &mut Vec<f64>| {
        let slab = &slabs[s];
        let top = slab.end - 1;
        // SAFETY: checked arrays; the tasks of one phase touch disjoint layers (module doc).
        unsafe {
            if StencilLayout::top_alone(slab) {
                // The lattice's top layer alone: its bars in phase 0, its nodes integrated by the
                // slab below once that slab's top layer has run (phase 1).
                if phase == 0 {
                    layers_dispatch(isa, layout, slab.clone(), p, t);
                }
            } else if phase == 0 {
                layers_dispatch(isa, layout, slab.start..top, p, t);
                // A slab's bottom layer is complete once the layer below has run (phase 1), but
                // for the lattice's first layer.
                let first = if s == 0 { slab.start } else { slab.start + 1 };
                for layer in first..top {
                    integrate_raw(isa, layout.layer_nodes(layer), update, fp.get(), lv);
                }
            } else {
                layers_dispatch(isa, layout, top..top + 1, p, t);
                integrate_raw(isa, layout.layer_nodes(top), update, fp.get(), lv);
                if s < last {
                    integrate_raw(isa, layout.layer_nodes(top + 1), update, fp.get(), lv);
                }
            }
        }
    };
    let scratch =
        || vec![0.0; (1 + if medium.is_some() { RunMedium::<L>::SCRATCH } else { 0 }) * layout.longest_run() * L];
    for phase in 0..2u8 {
        if parallel {
            (0..slabs.len()).into_par_iter().for_each_init(scratch, |t, s| run(s, phase, t));
        } else {
            let mut t = scratch();
            for s in 0..slabs.len() {
                run(s, phase, &mut t);
            }
        }
    }
}

/// Raw force field shared by the slab tasks.
#[derive(Clone, Copy)]
struct FieldPtr<const L: usize>([*mut Lanes<L>; 3]);

impl<const L: usize> FieldPtr<L> {
    /// The pointers (a method, so closures capture the whole `Sync` wrapper).
    fn get(self) -> [*mut Lanes<L>; 3] {
        self.0
    }
}

// SAFETY: as `Pass`.
unsafe impl<const L: usize> Send for FieldPtr<L> {}
unsafe impl<const L: usize> Sync for FieldPtr<L> {}

widest! {
    /// The runs of layers `layers`, in instruction set `isa`.
    ///
    /// # Safety
    /// The arrays of `p` fit the layout, and no other thread touches the nodes these layers'
    /// bars write.
    unsafe fn layers_dispatch<const L: usize>(
        layout: &StencilLayout,
        span: Range<usize>,
        p: Pass<L>,
        t: &mut [f64],
    ) => layers
}

/// See [`layers_dispatch`].
#[inline(always)]
unsafe fn layers<const L: usize>(layout: &StencilLayout, span: Range<usize>, p: Pass<L>, t: &mut [f64]) {
    for layer in span {
        let range = layout.layer_run_range(layer);
        for (index, r) in range.clone().zip(&layout.runs()[range]) {
            // SAFETY: forwarded contract.
            unsafe { run::<L>(index, r, p, t) };
        }
    }
}

/// One run.
///
/// # Safety
/// As [`layers_dispatch`].
#[inline(always)]
unsafe fn run<const L: usize>(index: usize, r: &Run, p: Pass<L>, t: &mut [f64]) {
    let n = r.len as usize * L;
    let (lo, hi, kb) = (r.start as usize * L, (r.start + r.offset) as usize * L, r.first_bar as usize * L);
    let (t, rest) = t.split_at_mut(n);
    // SAFETY: the ranges lie inside the checked arrays; each mutable slice is dropped before the
    // next (lower and upper runs of an x run overlap) and no other thread writes them.
    unsafe {
        // The bars' stiffness as one array where there is one (per bar), or where the medium's
        // terms need it too (factored, written once into the scratch for both tensions).
        let (k, rest): (Option<&[f64]>, &mut [f64]) = match (p.k, &p.medium) {
            (KPtr::PerBar(k), _) => (Some(std::slice::from_raw_parts(k.add(kb), n)), rest),
            (KPtr::Factored { runs, factors }, Some(_)) => {
                let (k, rest) = rest.split_at_mut(n);
                let phi = factors.map(|f| std::slice::from_raw_parts(f.add(kb), n));
                run_stiffness::<L>(*runs.add(index), phi, k);
                (Some(&*k), rest)
            }
            (KPtr::Factored { .. }, None) => (None, rest),
        };
        let read = |c: usize, at: usize| std::slice::from_raw_parts(p.u[c].add(at), n);
        match r.direction {
            Direction::Axis(a) => {
                let a = a as usize;
                let (ul, uh) = (read(a, lo), read(a, hi));
                match (k, p.k) {
                    (Some(k), _) => {
                        for m in 0..n {
                            t[m] = k[m] * (uh[m] - ul[m]);
                        }
                    }
                    (None, KPtr::Factored { runs, factors }) => {
                        let rs = *runs.add(index);
                        let phi = factors.map(|f| std::slice::from_raw_parts(f.add(kb), n));
                        factored(t, rs.interior, phi, |m| uh[m] - ul[m]);
                        // The first and last bar of a run on the block's x faces: their own nominal.
                        let bars = r.len as usize;
                        for m in [0, bars - 1] {
                            let k = rs.at(m, bars);
                            if k != rs.interior {
                                for l in 0..L {
                                    let q = m * L + l;
                                    let kf = phi.map_or(k, |f| k * f64::from(f[q]));
                                    t[q] = kf * (uh[q] - ul[q]);
                                }
                            }
                        }
                    }
                    (None, KPtr::PerBar(_)) => unreachable!("per-bar stiffness is an array"),
                }
                if let (Some(md), Some(k)) = (&p.medium, k) {
                    with_medium(md, index, r, p.u, t, k, rest);
                }
                add(std::slice::from_raw_parts_mut(p.f[a].add(lo), n), t, 1.0);
                sub(std::slice::from_raw_parts_mut(p.f[a].add(hi), n), t, 1.0);
            }
            Direction::Diagonal { neg_x, neg_y } => {
                let (sx, sy) = signs(neg_x, neg_y);
                let (xl, xh, yl, yh, zl, zh) =
                    (read(0, lo), read(0, hi), read(1, lo), read(1, hi), read(2, lo), read(2, hi));
                let e = |m: usize| sx * (xh[m] - xl[m]) + sy * (yh[m] - yl[m]) + (zh[m] - zl[m]);
                match (k, p.k) {
                    (Some(k), _) => {
                        for m in 0..n {
                            t[m] = k[m] * e(m);
                        }
                    }
                    // A diagonal has no surface reduction: one nominal stiffness for the run.
                    (None, KPtr::Factored { runs, factors }) => {
                        let phi = factors.map(|f| std::slice::from_raw_parts(f.add(kb), n));
                        factored(t, (*runs.add(index)).interior, phi, e);
                    }
                    (None, KPtr::PerBar(_)) => unreachable!("per-bar stiffness is an array"),
                }
                if let (Some(md), Some(k)) = (&p.medium, k) {
                    with_medium(md, index, r, p.u, t, k, rest);
                }
                // One array per loop (see the listed kernel).
                add(std::slice::from_raw_parts_mut(p.f[0].add(lo), n), t, sx);
                add(std::slice::from_raw_parts_mut(p.f[1].add(lo), n), t, sy);
                add(std::slice::from_raw_parts_mut(p.f[2].add(lo), n), t, 1.0);
                sub(std::slice::from_raw_parts_mut(p.f[0].add(hi), n), t, sx);
                sub(std::slice::from_raw_parts_mut(p.f[1].add(hi), n), t, sy);
                sub(std::slice::from_raw_parts_mut(p.f[2].add(hi), n), t, 1.0);
            }
        }
    }
}

/// `k` = the factored stiffness of a run's bar-lanes, `nominal·f64(φ)` (the first and last bar
/// their own nominal, as [`StiffnessRef::of_run_bar`] takes it).
#[inline(always)]
fn run_stiffness<const L: usize>(rs: RunStiffness, phi: Option<&[f32]>, k: &mut [f64]) {
    match phi {
        Some(phi) => {
            for (k, f) in k.iter_mut().zip(phi) {
                *k = rs.interior * f64::from(*f);
            }
        }
        None => k.fill(rs.interior),
    }
    let bars = k.len() / L;
    for m in [0, bars - 1] {
        let nominal = rs.at(m, bars);
        for l in 0..L {
            let q = m * L + l;
            k[q] = phi.map_or(nominal, |f| nominal * f64::from(f[q]));
        }
    }
}

/// Adds the medium's tensions to the elastic ones `t` of run `index` (`r`) of stiffness `k`, in
/// the scratch `rest` (at least [`RunMedium::SCRATCH`] − 1 times `t`'s length).
///
/// # Safety
/// As [`layers_dispatch`].
#[inline(always)]
unsafe fn with_medium<const L: usize>(
    md: &RunMedium<L>,
    index: usize,
    r: &Run,
    u: [*const f64; 3],
    t: &mut [f64],
    k: &[f64],
    rest: &mut [f64],
) {
    let n = t.len();
    let (sum, rest) = rest.split_at_mut(n);
    // SAFETY: forwarded contract.
    unsafe { md.add(index, r, u, t, Scratch { k, sum, diff: &mut rest[..n] }) };
}

/// `t = (k·f64(φ))·e` over a run (`t = k·e` without factors).
#[inline(always)]
fn factored(t: &mut [f64], k: f64, phi: Option<&[f32]>, e: impl Fn(usize) -> f64) {
    match phi {
        Some(phi) => {
            for (m, (t, &f)) in t.iter_mut().zip(phi).enumerate() {
                *t = (k * f64::from(f)) * e(m);
            }
        }
        None => {
            for (m, t) in t.iter_mut().enumerate() {
                *t = k * e(m);
            }
        }
    }
}

/// `f += s·t` (the product by ±1 is exact, so `s·t` is `t` or `−t`).
#[inline(always)]
fn add(f: &mut [f64], t: &[f64], s: f64) {
    for (f, t) in f.iter_mut().zip(t) {
        *f += s * t;
    }
}

/// `f −= s·t`.
#[inline(always)]
fn sub(f: &mut [f64], t: &[f64], s: f64) {
    for (f, t) in f.iter_mut().zip(t) {
        *f -= s * t;
    }
}

/// The kernel's order written plainly, one bar and one lane at a time: run by run in slab and
/// phase order, first every bar's `+t` at its lower end, then every bar's `−t` at its upper end.
pub fn reference<'k, const L: usize>(
    layout: &StencilLayout,
    k: impl Into<StiffnessRef<'k, L>>,
    u: &Field<L>,
    f: &mut Field<L>,
) {
    ordered(layout, k.into(), u, f, |_, _, _, _, k, e| k * e);
}

/// The kernel's order with the medium's terms written plainly: each bar's tension `k·eₙ + T`,
/// `T` from [`AnelasticParams`] and the bar's elongation in `before`, advancing its memory
/// variables `zeta` (one per bar with a Q, else empty) in the same order.
#[allow(clippy::too_many_arguments)]
pub fn reference_with_medium<const L: usize>(
    layout: &StencilLayout,
    k: StiffnessRef<'_, L>,
    u: &Field<L>,
    f: &mut Field<L>,
    a: &AnelasticParams<L>,
    zones: &[u8],
    before: &Field<L>,
    zeta: &mut crate::step::anelastic::Memory,
) {
    ordered(layout, k, u, f, |index, r, m, l, k, en| {
        let (i, j) = (r.start as usize + m, (r.start + r.offset) as usize + m);
        let ep = crate::step::primitives::elongation(r.direction, before, i, j, l);
        let q = (r.first_bar as usize + m) * L + l;
        let mut z = if a.memory() { zeta.get(q) } else { [0.0; MECHANISMS] };
        let t = k * en + a.advance(zones[index] as usize * MECHANISMS, l, k, en, ep, a.memory().then_some(&mut z));
        if a.memory() {
            zeta.set(q, z);
        }
        t
    });
}

/// The plain order of [`reference`] with each bar-lane's tension `tension(run index, run, bar of
/// the run, lane, stiffness, elongation)`.
fn ordered<const L: usize>(
    layout: &StencilLayout,
    k: StiffnessRef<'_, L>,
    u: &Field<L>,
    f: &mut Field<L>,
    mut tension: impl FnMut(usize, &Run, usize, usize, f64, f64) -> f64,
) {
    let mut order: Vec<usize> = Vec::new();
    for phase in 0..2 {
        for slab in layout.slabs() {
            order.extend(layout.phase_layers(&slab, phase));
        }
    }
    for layer in order {
        let range = layout.layer_run_range(layer);
        for (index, r) in range.clone().zip(&layout.runs()[range]) {
            let (lo, off) = (r.start as usize, r.offset as usize);
            let ts: Vec<Lanes<L>> = (0..r.len as usize)
                .map(|m| {
                    let (i, j) = (lo + m, lo + m + off);
                    std::array::from_fn(|l| {
                        let d = |c: usize| u.c[c][j][l] - u.c[c][i][l];
                        let e = match r.direction {
                            Direction::Axis(a) => d(a as usize),
                            Direction::Diagonal { neg_x, neg_y } => {
                                let (sx, sy) = signs(neg_x, neg_y);
                                sx * d(0) + sy * d(1) + d(2)
                            }
                        };
                        tension(index, r, m, l, k.of_run_bar(index, r, m, l), e)
                    })
                })
                .collect();
            let scale = |c: usize| match r.direction {
                Direction::Axis(a) => (c == a as usize).then_some(1.0),
                Direction::Diagonal { neg_x, neg_y } => {
                    let (sx, sy) = signs(neg_x, neg_y);
                    Some([sx, sy, 1.0][c])
                }
            };
            for c in 0..3 {
                let Some(s) = scale(c) else { continue };
                for (m, t) in ts.iter().enumerate() {
                    for l in 0..L {
                        f.c[c][lo + m][l] += s * t[l];
                    }
                }
                for (m, t) in ts.iter().enumerate() {
                    for l in 0..L {
                        f.c[c][lo + m + off][l] -= s * t[l];
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use rand::{RngExt, SeedableRng};

    use super::*;
    use crate::geometry::Dims;
    use crate::step::integrate::Coefficients;
    use crate::step::integrate::{Levels, integrate_all};

    fn random<const L: usize>(layout: &StencilLayout, seed: u64) -> (Vec<Lanes<L>>, Field<L>) {
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed);
        let k = (0..layout.bars()).map(|_| std::array::from_fn(|_| rng.random_range(0.5..2.0))).collect();
        let mut u = Field::<L>::zeros(layout.nodes());
        for c in &mut u.c {
            for v in c.iter_mut() {
                *v = std::array::from_fn(|_| rng.random_range(-1.0..1.0));
            }
        }
        (k, u)
    }

    fn bits<const L: usize>(f: &Field<L>) -> Vec<u64> {
        f.c.iter().flat_map(|c| c.iter().flat_map(|v| v.map(f64::to_bits))).collect()
    }

    /// Random nominal stiffness per run (first and last bars their own) and `f32` factors.
    fn random_factored<const L: usize>(layout: &StencilLayout, seed: u64) -> (Vec<RunStiffness>, Vec<[f32; L]>) {
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed ^ 0xfac7);
        let runs = layout
            .runs()
            .iter()
            .map(|r| {
                let interior = rng.random_range(0.5..2.0);
                match r.direction {
                    Direction::Axis(_) => RunStiffness {
                        first: if rng.random_bool(0.5) { interior } else { 0.5 * interior },
                        interior,
                        last: if rng.random_bool(0.5) { interior } else { 0.25 * interior },
                    },
                    Direction::Diagonal { .. } => RunStiffness { first: interior, interior, last: interior },
                }
            })
            .collect();
        let factors = (0..layout.bars()).map(|_| std::array::from_fn(|_| rng.random_range(0.7f32..1.3))).collect();
        (runs, factors)
    }

    fn agrees<const L: usize>(dims: Dims, seed: u64) {
        let layout = StencilLayout::new(dims);
        let (k, u) = random::<L>(&layout, seed);
        let (runs, factors) = random_factored::<L>(&layout, seed);
        for kref in [
            StiffnessRef::Factored { runs: &runs, factors: Some(&factors) },
            StiffnessRef::Factored { runs: &runs, factors: None },
        ] {
            let mut want = Field::<L>::zeros(layout.nodes());
            reference(&layout, kref, &u, &mut want);
            // The factored stiffness is the per-bar stiffness `nominal · f64(factor)`.
            let per_bar: Vec<Lanes<L>> = {
                let mut v = vec![[0.0; L]; layout.bars()];
                for (index, r) in layout.runs().iter().enumerate() {
                    for m in 0..r.len as usize {
                        v[r.first_bar as usize + m] = std::array::from_fn(|l| kref.of_run_bar(index, r, m, l));
                    }
                }
                v
            };
            let mut plain = Field::<L>::zeros(layout.nodes());
            reference(&layout, &per_bar, &u, &mut plain);
            assert_eq!(bits(&plain), bits(&want), "{dims:?} L = {L}: factored as per bar");
            for isa in Isa::available() {
                let mut f = Field::<L>::zeros(layout.nodes());
                Isa::pinned(isa, || forces(&layout, kref, &u, &mut f));
                assert_eq!(bits(&f), bits(&want), "{dims:?} L = {L} {isa:?}: factored kernel against its plain order");
            }
            let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
            let mut f = Field::<L>::zeros(layout.nodes());
            pool.install(|| forces_parallel(&layout, kref, &u, &mut f));
            assert_eq!(bits(&f), bits(&want), "{dims:?} L = {L}: on two threads");
        }
        let mut want = Field::<L>::zeros(layout.nodes());
        reference(&layout, &k, &u, &mut want);
        for isa in Isa::available() {
            let mut f = Field::<L>::zeros(layout.nodes());
            Isa::pinned(isa, || forces(&layout, &k, &u, &mut f));
            assert_eq!(bits(&f), bits(&want), "{dims:?} L = {L} {isa:?}: the kernel against its plain order");
        }
        // Fused with the integration, serial and on two threads: the forces, then the update.
        let n = layout.nodes();
        let inv_mass: Vec<f64> = (0..n).map(|i| 1.0 / (1.0 + (i % 7) as f64)).collect();
        let coef = Coefficients { cf: [1e-3; L], c2: [1.9; L], cp: [0.9; L] };
        let body = [[0.0; L], [0.0; L], [-9.81; L]];
        let update = Update { inv_mass: &inv_mass, coef: &coef, body: &body };
        let up = Field::<L>::zeros(n);
        let mut plain_f = want.clone();
        let mut plain = Field::<L>::zeros(n);
        integrate_all(&update, &mut plain_f, Levels { u: &u, up: &up, out: &mut plain }, false);
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let (mut f, mut out) = (Field::<L>::zeros(n), Field::<L>::zeros(n));
            pool.install(|| {
                forces_and_trial(
                    &layout,
                    (&k).into(),
                    &update,
                    &mut f,
                    Levels { u: &u, up: &up, out: &mut out },
                    None,
                    threads > 1,
                )
            });
            assert_eq!(bits(&out), bits(&plain), "{dims:?} L = {L}, {threads} threads: fused pass");
            assert!(f.c.iter().all(|c| c.iter().all(|v| *v == [0.0; L])), "the forces are consumed");
        }
    }

    /// The lattices and seeds both kernel tests run, for 1, 4 and 8 lanes: a one-module slab, a
    /// block, one module, a tall column.
    fn for_each_case(check: [fn(Dims, u64); 3]) {
        for (dims, seed) in
            [(Dims::new(10, 1, 5), 1), (Dims::new(7, 5, 9), 2), (Dims::new(1, 1, 1), 3), (Dims::new(3, 4, 40), 4)]
        {
            check.iter().for_each(|f| f(dims, seed));
        }
    }

    #[test]
    fn every_build_and_thread_count_agrees_with_the_plain_order() {
        for_each_case([agrees::<1>, agrees::<4>, agrees::<8>]);
    }

    /// The medium's terms in the kernel against [`reference_with_medium`]: every build and thread
    /// count, per-bar and factored stiffness, with memory variables and with dashpots only.
    fn medium_agrees<const L: usize>(dims: Dims, seed: u64) {
        use crate::step::anelastic::Memory;
        let layout = StencilLayout::new(dims);
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed ^ 0x3ed1);
        let (k, u) = random::<L>(&layout, seed);
        let (_, before) = random::<L>(&layout, seed + 100);
        let (runs, factors) = random_factored::<L>(&layout, seed);
        let zones: Vec<u8> = layout.runs().iter().map(|_| rng.random_range(0..3u8)).collect();
        let coef = |lo: f64, hi: f64, rng: &mut rand::rngs::ChaCha8Rng| -> Vec<Lanes<L>> {
            (0..3 * MECHANISMS).map(|_| std::array::from_fn(|_| rng.random_range(lo..hi))).collect()
        };
        let (decay, gain) = (coef(0.9, 1.0, &mut rng), coef(0.0, 0.05, &mut rng));
        let viscous: Lanes<L> = std::array::from_fn(|_| rng.random_range(0.0..0.1));
        let n = layout.nodes();
        let inv_mass: Vec<f64> = (0..n).map(|i| 1.0 / (1.0 + (i % 5) as f64)).collect();
        let coefficients = Coefficients { cf: [1e-3; L], c2: [1.9; L], cp: [0.9; L] };
        let body = [[0.0; L], [0.0; L], [-9.81; L]];
        let update = Update { inv_mass: &inv_mass, coef: &coefficients, body: &body };
        for memory in [true, false] {
            let a = AnelasticParams::from_parts(decay.clone(), gain.clone(), viscous, memory);
            let mut zeta0 = if memory { Memory::at_rest(layout.bars(), L) } else { Memory::default() };
            if memory {
                for q in 0..layout.bars() * L {
                    zeta0.set(q, std::array::from_fn(|_| rng.random_range(-0.1f32..0.1)));
                }
            }
            for kref in [
                StiffnessRef::Factored { runs: &runs, factors: Some(&factors) },
                StiffnessRef::Factored { runs: &runs, factors: None },
                StiffnessRef::PerBar(&k),
            ] {
                let (mut want_f, mut want_out, mut want_zeta) =
                    (Field::<L>::zeros(n), Field::<L>::zeros(n), zeta0.clone());
                reference_with_medium(&layout, kref, &u, &mut want_f, &a, &zones, &before, &mut want_zeta);
                integrate_all(&update, &mut want_f, Levels { u: &u, up: &before, out: &mut want_out }, false);
                let runs_with = |parallel: bool| {
                    let (mut f, mut out, mut zeta) = (Field::<L>::zeros(n), Field::<L>::zeros(n), zeta0.clone());
                    let medium = RunMedium::new(&layout, &zones, &a, &before, &mut zeta);
                    let levels = Levels { u: &u, up: &before, out: &mut out };
                    forces_and_trial(&layout, kref, &update, &mut f, levels, Some(medium), parallel);
                    (out, zeta)
                };
                for isa in Isa::available() {
                    let (out, zeta) = Isa::pinned(isa, || runs_with(false));
                    assert_eq!(bits(&out), bits(&want_out), "{dims:?} L = {L} {isa:?} memory {memory}: the update");
                    assert_eq!(zeta.bits(), want_zeta.bits(), "{dims:?} L = {L} {isa:?}: the memory variables");
                }
                let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
                let (out, zeta) = pool.install(|| runs_with(true));
                assert_eq!(bits(&out), bits(&want_out), "{dims:?} L = {L} memory {memory}: on two threads");
                assert_eq!(zeta.bits(), want_zeta.bits(), "{dims:?} L = {L}: the memory variables on two threads");
            }
        }
    }

    #[test]
    fn the_medium_in_the_kernel_agrees_with_its_plain_order() {
        for_each_case([medium_agrees::<1>, medium_agrees::<4>, medium_agrees::<8>]);
    }

    #[test]
    fn the_stencil_gives_the_listed_forces_to_round_off() {
        let dims = Dims::new(9, 6, 7);
        let model = crate::model::Model::new(crate::scene::Scene::paper().sample(dims));
        let layout = StencilLayout::new(dims);
        let (k, u) = random::<1>(&layout, 9);
        let mut f = Field::<1>::zeros(layout.nodes());
        forces(&layout, &k, &u, &mut f);
        // The same bars listed: each stencil bar's stiffness moved to its listed place.
        let canonical = model.canonical_bars();
        let mut by_canonical = vec![[0.0; 1]; k.len()];
        for r in layout.runs() {
            for (m, b) in r.bars().enumerate() {
                by_canonical[r.canonical(m)] = k[b];
            }
        }
        let listed_k: Vec<[f64; 1]> = canonical.iter().map(|&c| by_canonical[c as usize]).collect();
        let mut g = Field::<1>::zeros(layout.nodes());
        crate::step::bars::bar_forces(model.layout(), &listed_k, &u, &mut g);
        let scale = g.c.iter().flat_map(|c| c.iter().map(|v| v[0].abs())).fold(0.0, f64::max);
        for c in 0..3 {
            for i in 0..layout.nodes() {
                assert!((f.c[c][i][0] - g.c[c][i][0]).abs() <= 1e-13 * scale, "node {i} component {c}");
            }
        }
    }
}
