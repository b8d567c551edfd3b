//! Energy of the run (docs/model.md §2): strain and kinetic energy of a state, and the work and
//! dissipation accumulated step by step, so that the balance closes to round-off.
//!
//! Every force's work over step n is `F·(uₙ₊₁ − uₙ₋₁)/2`; the kinetic energy is
//! `½m|uₙ₊₁ − uₙ|²/Δt²` and the strain energy `½uₙᵀKuₙ₊₁`: the pair central differences conserve
//! exactly. Bars that crack keep that pairing with the stiffness each bar has at step n, and the
//! rupture kernel books what they dissipate ([`crate::step::rupture`]).

use rayon::prelude::*;

use crate::boundary;
use crate::field::Field;
use crate::geometry::Direction;
use crate::layout::Bars;
use crate::model::Model;
use crate::stencil::Run;
use crate::step::params::Params;
use crate::step::primitives::{signs, strain_energy_with};
use crate::step::state::State;
use crate::stiffness::StiffnessRef;

pub use crate::ledger::{Energy, total};

/// `½ Σ_b k_b·e_b(a)·e_b(b)` for lane `l`: the strain energy `½aᵀKb` (J). With `a = b` it is the
/// strain energy of one state; with `a = uₙ`, `b = uₙ₊₁` it is the energy the central-difference
/// scheme conserves exactly. Summed layer by layer ([`strain_energy_layers`]).
pub fn strain_energy<'k, const L: usize>(
    model: &Model,
    k: impl Into<StiffnessRef<'k, L>>,
    a: &Field<L>,
    b: &Field<L>,
    l: usize,
) -> f64 {
    0.5 * total(&strain_energy_layers(model, k, a, b, l))
}

/// `Σ_b k_b·e_b(a)·e_b(b)` of the bars whose lower end is in each layer the model sums
/// ([`Model::energy_layers`]), bottom up.
pub fn strain_energy_layers<'k, const L: usize>(
    model: &Model,
    k: impl Into<StiffnessRef<'k, L>>,
    a: &Field<L>,
    b: &Field<L>,
    l: usize,
) -> Vec<f64> {
    let (k, layers) = (k.into(), model.energy_layers());
    match model.layout() {
        Bars::Listed(layout) => {
            let StiffnessRef::PerBar(k) = k else { panic!("a listed lattice has per-bar stiffness") };
            strain_energy_with(layout, &layers, a, b, l, |bar, _| k[bar][l])
        }
        Bars::Stencil(layout) => {
            // The stencil's layers are the window's: layer 0 is the block's `first_node / layer_nodes`.
            let lo = layers.first_node / layers.layer_nodes;
            let sum = |g: usize| {
                let mut sum = 0.0;
                let range = layout.layer_run_range(g - lo);
                for (index, r) in range.clone().zip(&layout.runs()[range]) {
                    sum += run_strain_energy(index, r, k, a, b, l);
                }
                sum
            };
            (layers.first..layers.first + layers.count).map(sum).collect()
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

/// `½ Σ m|a − b|²/Δt²` for lane `l` (J), summed layer by layer ([`kinetic_energy_layers`]).
pub fn kinetic_energy<const L: usize>(model: &Model, a: &Field<L>, b: &Field<L>, l: usize, dt: f64) -> f64 {
    0.5 * total(&kinetic_energy_layers(model, a, b, l)) / (dt * dt)
}

/// `Σ m|a − b|²` of lane `l` over the nodes of each layer the model sums, bottom up: per layer
/// and component, eight partial sums.
pub fn kinetic_energy_layers<const L: usize>(model: &Model, a: &Field<L>, b: &Field<L>, l: usize) -> Vec<f64> {
    let (mass, layers) = (model.mass(), model.energy_layers());
    (0..layers.count)
        .map(|k| {
            let nodes = layers.nodes_of(k);
            let m = &mass[nodes.clone()];
            let mut ke = 0.0;
            for c in 0..3 {
                let (a, b) = (&a.c[c][nodes.clone()], &b.c[c][nodes.clone()]);
                ke += sum8(m.len(), |i| {
                    let v = a[i][l] - b[i][l];
                    m[i] * v * v
                });
            }
            ke
        })
        .collect()
}

/// Adds the work and dissipation of step n, `F·(uₙ₊₁ − uₙ₋₁)/2` for every force, to the
/// accumulators. Called before the commit, when `state.u.nm1` holds the new uₙ₊₁ and `state.u.n`
/// holds uₙ₋₁. Each term is summed layer by layer ([`Model::energy_layers`]) into
/// [`State::energy_parts`]; on one process the layers' increments are added to the ledger here, on
/// a rank of a split scene rank 0 adds every rank's ([`crate::run::run_split`]).
pub(crate) fn accumulate<const L: usize>(p: &Params<'_, L>, state: &mut State<L>, parallel: bool) {
    let State { u, contact, loading, energy, anelastic: state_anelastic, energy_parts, .. } = state;
    let (new, old) = (&u.nm1, &u.n);
    let model = p.model;
    let (mass, layers) = (model.mass(), model.energy_layers());
    // Damping and body forces: per layer, per component, eight partial sums per lane.
    let layer = |k: usize| {
        let nodes = layers.nodes_of(k);
        let m = &mass[nodes.clone()];
        let mut out = [Energy::default(); L];
        let (mut damp, mut body) = ([0.0; L], [0.0; L]);
        for c in 0..3 {
            let (new, old, bc) = (&new.c[c][nodes.clone()], &old.c[c][nodes.clone()], p.body()[c]);
            for l in 0..L {
                damp[l] += sum8(m.len(), |i| {
                    let d2 = new[i][l] - old[i][l];
                    m[i] * d2 * d2
                });
                body[l] += sum8(m.len(), |i| m[i] * bc[l] * (new[i][l] - old[i][l]));
            }
        }
        for l in 0..L {
            out[l].damping = damp[l] * p.damping(l) / (4.0 * p.dt(l));
            out[l].body_work = 0.5 * body[l];
        }
        out
    };
    // The layers' terms, in the state's buffer (kept from step to step: no allocation per step).
    let mut parts = std::mem::take(energy_parts);
    parts.clear();
    if parallel {
        (0..layers.count).into_par_iter().map(layer).collect_into_vec(&mut parts);
    } else {
        parts.extend((0..layers.count).map(layer));
    }
    let reaction = &contact.reaction;
    // On a fault the normal force is the friction's only: it does no work (docs/model.md §15).
    let normal_work = !model.scene().is_fault();
    for (ci, &node) in model.contact().iter().enumerate() {
        let i = node as usize;
        let Some(k) = layers.of(i) else { continue };
        for l in 0..L {
            let d2 = |c: usize| new.c[c][i][l] - old.c[c][i][l];
            let e = &mut parts[k][l];
            e.friction -= 0.5 * (reaction[0][ci][l] * d2(0) + reaction[1][ci][l] * d2(1));
            if normal_work {
                e.impact -= 0.5 * reaction[2][ci][l] * d2(2);
            }
        }
    }
    if let Some(a) = &p.anelastic {
        let w = crate::step::anelastic::work(model, &layers, a, p.stiffness(), [new, &u.np1, old], state_anelastic);
        for (part, w) in parts.iter_mut().zip(w) {
            for l in 0..L {
                part[l].anelastic += w[l];
            }
        }
    }
    model.boundaries().work(&mut boundary::Work {
        new,
        old,
        loading,
        dt: p.dts(),
        fault: p.fault.as_ref(),
        layers: &layers,
        parts: &mut parts,
    });
    if model.split_window().is_none() {
        for l in 0..L {
            energy[l].add_work(&crate::ledger::fold_layers(parts.iter().map(|p| &p[l])));
        }
    }
    *energy_parts = parts;
}
