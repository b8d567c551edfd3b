//! Energy of the run (docs/model.md §2): strain and kinetic energy of a state, and the work and
//! dissipation accumulated step by step, so that the balance closes to round-off.
//!
//! Every force's work over step n is `F·(uₙ₊₁ − uₙ₋₁)/2`; the kinetic energy is
//! `½m|uₙ₊₁ − uₙ|²/Δt²` and the strain energy `½uₙᵀKuₙ₊₁`: the pair central differences conserve
//! exactly. Bars that crack keep that pairing with the stiffness each bar has at step n, and the
//! rupture kernel books what they dissipate ([`crate::step::rupture`]).

use std::ops::Range;

use rayon::prelude::*;

use crate::boundary;
use crate::field::Field;
use crate::geometry::Direction;
use crate::layout::Bars;
use crate::model::Model;
use crate::stencil::{Run, StencilLayout};
use crate::step::params::Params;
use crate::step::primitives::{signs, strain_energy_with};
use crate::step::state::State;
use crate::stiffness::StiffnessRef;

pub use crate::ledger::Energy;

/// `½ Σ_b k_b·e_b(a)·e_b(b)` for lane `l`: the strain energy `½aᵀKb` (J). With `a = b` it is the
/// strain energy of one state; with `a = uₙ`, `b = uₙ₊₁` it is the energy the central-difference
/// scheme conserves exactly.
pub fn strain_energy<'k, const L: usize>(
    bars: &Bars,
    k: impl Into<StiffnessRef<'k, L>>,
    a: &Field<L>,
    b: &Field<L>,
    l: usize,
) -> f64 {
    let k = k.into();
    match bars {
        Bars::Listed(layout) => {
            let StiffnessRef::PerBar(k) = k else { panic!("a listed lattice has per-bar stiffness") };
            strain_energy_with(layout, a, b, l, |bar, _| k[bar][l])
        }
        Bars::Stencil(layout) => {
            let slab_sums = per_slab(layout, false, |layers| {
                let mut sum = 0.0;
                for layer in layers {
                    let range = layout.layer_run_range(layer);
                    for (index, r) in range.clone().zip(&layout.runs()[range]) {
                        sum += run_strain_energy(index, r, k, a, b, l);
                    }
                }
                sum
            });
            0.5 * slab_sums.into_iter().sum::<f64>()
        }
    }
}

/// `Σ k·e(a)·e(b)` over the bars of one run, lane `l`, in eight partial sums.
fn run_strain_energy<const L: usize>(
    index: usize,
    r: &Run,
    k: StiffnessRef<'_, L>,
    a: &Field<L>,
    b: &Field<L>,
    l: usize,
) -> f64 {
    let (lo, hi, n) = (r.start as usize, (r.start + r.offset) as usize, r.len as usize);
    let k = |m: usize| k.of_run_bar(index, r, m, l);
    match r.direction {
        Direction::Axis(axis) => {
            let (ca, cb) = (&a.c[axis as usize], &b.c[axis as usize]);
            let (al, ah, bl, bh) = (&ca[lo..lo + n], &ca[hi..hi + n], &cb[lo..lo + n], &cb[hi..hi + n]);
            sum8(n, |m| k(m) * (ah[m][l] - al[m][l]) * (bh[m][l] - bl[m][l]))
        }
        Direction::Diagonal { neg_x, neg_y } => {
            let (sx, sy) = signs(neg_x, neg_y);
            let e = |u: &Field<L>, m: usize| {
                let (i, j) = (lo + m, hi + m);
                sx * (u.c[0][j][l] - u.c[0][i][l]) + sy * (u.c[1][j][l] - u.c[1][i][l]) + (u.c[2][j][l] - u.c[2][i][l])
            };
            sum8(n, |m| k(m) * e(a, m) * e(b, m))
        }
    }
}

/// `Σ term(i)` for `i < n` in a fixed order: eight partial sums `i mod 8` (a vector register of
/// them), combined pairwise; the order does not depend on anything but `n`.
#[inline(always)]
fn sum8(n: usize, term: impl Fn(usize) -> f64) -> f64 {
    let mut acc = [0.0; 8];
    let full = n - n % 8;
    for base in (0..full).step_by(8) {
        for q in 0..8 {
            acc[q] += term(base + q);
        }
    }
    for i in full..n {
        acc[i - full] += term(i);
    }
    ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]))
}

/// `sum(layers)` for each slab of a stencil lattice, in slab order; with `parallel`, the slabs on
/// the current rayon pool (the same partial sums whatever the thread count).
fn per_slab<T: Send>(layout: &StencilLayout, parallel: bool, sum: impl Fn(Range<usize>) -> T + Sync) -> Vec<T> {
    let slabs: Vec<Range<usize>> = layout.slabs().collect();
    if parallel { slabs.into_par_iter().map(&sum).collect() } else { slabs.into_iter().map(&sum).collect() }
}

/// `½ Σ m|a − b|²/Δt²` for lane `l` (J).
pub fn kinetic_energy<const L: usize>(model: &Model, a: &Field<L>, b: &Field<L>, l: usize, dt: f64) -> f64 {
    let mass = model.mass();
    if let Bars::Stencil(layout) = model.layout() {
        let sums = per_slab(layout, false, |layers| {
            let nodes = layout.layer_nodes(layers.start).start..layout.layer_nodes(layers.end - 1).end;
            let mut ke = 0.0;
            for c in 0..3 {
                let (a, b, m) = (&a.c[c][nodes.clone()], &b.c[c][nodes.clone()], &mass[nodes.clone()]);
                ke += sum8(m.len(), |i| {
                    let v = a[i][l] - b[i][l];
                    m[i] * v * v
                });
            }
            ke
        });
        return 0.5 * sums.into_iter().sum::<f64>() / (dt * dt);
    }
    let mut ke = 0.0;
    for c in 0..3 {
        let (a, b) = (&a.c[c], &b.c[c]);
        for i in 0..mass.len() {
            let v = a[i][l] - b[i][l];
            ke += mass[i] * v * v;
        }
    }
    0.5 * ke / (dt * dt)
}

/// Adds the work and dissipation of step n, `F·(uₙ₊₁ − uₙ₋₁)/2` for every force, to the
/// accumulators. Called before the commit, when `state.u.nm1` holds the new uₙ₊₁ and `state.u.n`
/// holds uₙ₋₁.
pub(crate) fn accumulate<const L: usize>(p: &Params<'_, L>, state: &mut State<L>, parallel: bool) {
    let State { u, contact, loading, energy, anelastic: state_anelastic, .. } = state;
    let (new, old) = (&u.nm1, &u.n);
    let model = p.model;
    let mass = model.mass();
    let mut damp = [0.0; L];
    let mut body = [0.0; L];
    if let Bars::Stencil(layout) = model.layout() {
        // Slab by slab, each in eight partial sums per lane: the same sums on any thread count.
        let sums = per_slab(layout, parallel, |layers| {
            let nodes = layout.layer_nodes(layers.start).start..layout.layer_nodes(layers.end - 1).end;
            let m = &mass[nodes.clone()];
            let mut out = [[0.0; L]; 2];
            for c in 0..3 {
                let (new, old, bc) = (&new.c[c][nodes.clone()], &old.c[c][nodes.clone()], p.body()[c]);
                for l in 0..L {
                    out[0][l] += sum8(m.len(), |i| {
                        let d2 = new[i][l] - old[i][l];
                        m[i] * d2 * d2
                    });
                    out[1][l] += sum8(m.len(), |i| m[i] * bc[l] * (new[i][l] - old[i][l]));
                }
            }
            out
        });
        for [d, b] in sums {
            for l in 0..L {
                damp[l] += d[l];
                body[l] += b[l];
            }
        }
    } else {
        for c in 0..3 {
            let (new, old) = (&new.c[c], &old.c[c]);
            let bc = p.body()[c];
            for i in 0..mass.len() {
                for l in 0..L {
                    let d2 = new[i][l] - old[i][l];
                    damp[l] += mass[i] * d2 * d2;
                    body[l] += mass[i] * bc[l] * d2;
                }
            }
        }
    }
    for l in 0..L {
        let e = &mut energy[l];
        e.damping += damp[l] * p.damping(l) / (4.0 * p.dt(l));
        e.body_work += 0.5 * body[l];
    }
    let reaction = &contact.reaction;
    // On a fault the normal force is the friction's only: it does no work (docs/model.md §15).
    let normal_work = !model.scene().is_fault();
    for (ci, &node) in model.contact().iter().enumerate() {
        let i = node as usize;
        for l in 0..L {
            let d2 = |c: usize| new.c[c][i][l] - old.c[c][i][l];
            let e = &mut energy[l];
            e.friction -= 0.5 * (reaction[0][ci][l] * d2(0) + reaction[1][ci][l] * d2(1));
            if normal_work {
                e.impact -= 0.5 * reaction[2][ci][l] * d2(2);
            }
        }
    }
    if let Some(a) = &p.anelastic {
        let w = crate::step::anelastic::work(model, a, p.stiffness(), [new, &u.np1, old], state_anelastic);
        for l in 0..L {
            energy[l].anelastic += w[l];
        }
    }
    model.boundaries().work(&mut boundary::Work { new, old, loading, dt: p.dts(), fault: p.fault.as_ref(), energy });
}
