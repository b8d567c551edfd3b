//! Critical time step `2/ω_max` of the lattice actually built (random field included).
//!
//! Central differences with mass-proportional damping are stable for `Δt ≤ 2/ω_max` whatever
//! the damping (the roots of `(1+a)z² − (2 − ω²Δt²)z + (1−a)`, `a = DΔt/2 ≥ 0`, stay in the unit
//! disc exactly when `ω²Δt² ≤ 4`). `ω²_max` is the largest eigenvalue of `M^{-1/2} K M^{-1/2}` of
//! the free lattice (constraints only remove degrees of freedom, so they cannot raise it). It is
//! found by Lanczos iteration on the bar kernel, with the Ritz residual added so the result is an
//! upper bound, and capped by Gershgorin's bound. The springs of a loading plate add at most
//! `max k_i/m_i` (Weyl's inequality), which is added to the bound.

use nalgebra::{DMatrix, SymmetricEigen};
use rand::SeedableRng;
use rand::distr::{Distribution, StandardUniform};
use rand::rngs::ChaCha8Rng;
use rayon::prelude::*;

use crate::error::SolverError;
use crate::field::Field;
use crate::geometry::Direction;
use crate::layout::Bars;
use crate::model::Model;
use crate::split::{Halo, Neighbours, Window, handed_sum};
use crate::step::bars::bar_forces;
use crate::step::{LaneStiffness, StiffnessRef};

/// The critical step of one lattice.
#[derive(Clone, Copy, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct CriticalStep {
    /// Upper bound of the highest angular frequency (rad/s).
    pub omega_max: f64,
    /// `2/ω_max` (s).
    pub dt_s: f64,
    /// Lanczos iterations used (0: the node bound alone, [`node_bound`]).
    pub iterations: usize,
    /// Relative residual of the top Ritz pair (bound on the relative error of `ω²_max`); NaN for
    /// the node bound.
    pub relative_residual: f64,
}

/// The critical step of `model` with one seed's bar stiffness `k` as a run holds it: Lanczos on a
/// listed lattice ([`critical_time_step`]); on a stencil, Lanczos of at most
/// [`STENCIL_LANCZOS_ITERATIONS`] passes reading the factored stiffness, or the node bound if it
/// has not converged by then.
pub fn critical_step(model: &Model, k: &LaneStiffness) -> Result<CriticalStep, SolverError> {
    critical_step_on(model, k, false)
}

/// [`critical_step`], a stencil's bar passes split over the current rayon pool with `parallel`
/// (the same numbers either way; not from inside a pool whose other tasks are other seeds).
pub fn critical_step_on(model: &Model, k: &LaneStiffness, parallel: bool) -> Result<CriticalStep, SolverError> {
    undamped_step_on(model, k, parallel).map(|c| with_dashpots(model, c))
}

/// The step `c` of the bars alone lowered by the medium's Kelvin–Voigt dashpots
/// ([`crate::medium::kelvin_voigt_step_factor`]; unchanged without them).
fn with_dashpots(model: &Model, c: CriticalStep) -> CriticalStep {
    let beta = model.scene().medium.kelvin_voigt_s;
    if beta == 0.0 {
        return c;
    }
    CriticalStep { dt_s: c.dt_s * crate::medium::kelvin_voigt_step_factor(beta, 2.0 / c.omega_max), ..c }
}

fn undamped_step_on(model: &Model, k: &LaneStiffness, parallel: bool) -> Result<CriticalStep, SolverError> {
    match k {
        LaneStiffness::PerBar(k) if !matches!(model.layout(), Bars::Stencil(_)) => critical_time_step(model, k),
        LaneStiffness::PerBar(k) => bounded_step(model, StiffnessRef::<1>::PerBar(k.as_chunks::<1>().0), parallel),
        LaneStiffness::Factored(f) => bounded_step(
            model,
            StiffnessRef::Factored { runs: model.run_stiffness(), factors: f.as_deref().map(|f| f.as_chunks::<1>().0) },
            parallel,
        ),
    }
}

/// Most Lanczos iterations on a stencil lattice: the set-up of a run costs at most about as many
/// bar passes as this many steps.
pub const STENCIL_LANCZOS_ITERATIONS: usize = 100;

/// Converged Lanczos ([`lanczos`], at most [`STENCIL_LANCZOS_ITERATIONS`], each one pass over the
/// bars reading the stiffness as the kernel does) capped by the node bound ([`node_bound`]); the
/// node bound alone when Lanczos has not converged to 1e-9 by then (its `θ + residual` is an upper
/// bound only once converged: after 20 iterations it can still be 1% low).
fn bounded_step(model: &Model, k: StiffnessRef<'_, 1>, parallel: bool) -> Result<CriticalStep, SolverError> {
    let inv_mass = model.inv_mass();
    let nodes = node_bound(inv_mass, |f| k.visit(model.layout(), 0, f));
    let l = lanczos_with(model, k, Lanczos { max_iter: STENCIL_LANCZOS_ITERATIONS, check_every: 5, parallel }, nodes)?;
    if l.relative_residual <= LANCZOS_TOLERANCE {
        return Ok(l);
    }
    let bound = nodes + model.boundaries().stiffening(inv_mass);
    if !(bound > 0.0 && bound.is_finite()) {
        return Err(SolverError::Numerical(format!(
            "largest stiffness eigenvalue bound is {bound:e}: the lattice has no positive stiffness"
        )));
    }
    let omega = bound.sqrt();
    Ok(CriticalStep { omega_max: omega, dt_s: 2.0 / omega, iterations: 0, relative_residual: f64::NAN })
}

/// Computes the critical step of `model` with bar stiffness `k` (internal order, kernel units).
pub fn critical_time_step(model: &Model, k: &[f64]) -> Result<CriticalStep, SolverError> {
    let k1: &[[f64; 1]] = k.as_chunks::<1>().0;
    lanczos(model, StiffnessRef::PerBar(k1), LANCZOS_MAX_ITERATIONS, gershgorin_bound(model, k))
}

/// Most Lanczos iterations of [`critical_time_step`].
pub const LANCZOS_MAX_ITERATIONS: usize = 400;

/// Relative residual of the top Ritz pair at which Lanczos stops (converged).
pub const LANCZOS_TOLERANCE: f64 = 1e-9;

/// Lanczos on `M^{-1/2} K M^{-1/2}` of `model` with stiffness `k`, at most `max_iter` iterations
/// (fewer once the top Ritz residual is below 1e-9 of its value): `θ + residual` capped by `cap`,
/// plus the boundary conditions' stiffening.
pub fn lanczos(model: &Model, k: StiffnessRef<'_, 1>, max_iter: usize, cap: f64) -> Result<CriticalStep, SolverError> {
    lanczos_with(model, k, Lanczos { max_iter, check_every: 10, parallel: false }, cap)
}

/// How [`lanczos_with`] runs.
#[derive(Clone, Copy, Debug)]
struct Lanczos {
    /// Most iterations.
    max_iter: usize,
    /// Iterations between two looks at the top Ritz pair (the result depends on it: it stops at
    /// the first look that finds it converged).
    check_every: usize,
    /// The bar passes of a stencil on the current rayon pool (the same numbers).
    parallel: bool,
}

fn lanczos_with(model: &Model, k: StiffnessRef<'_, 1>, how: Lanczos, cap: f64) -> Result<CriticalStep, SolverError> {
    let Lanczos { max_iter, check_every, parallel } = how;
    let n = model.node_count();
    let dof = 3 * n;
    let k1 = k;
    let gershgorin = cap;
    let inv_sqrt_m: Vec<f64> = model.inv_mass().iter().map(|v| v.sqrt()).collect();
    // Four vectors of 3n: q, q_prev (flat, component-major), x = M^{-1/2}q and the forces
    // (fields), x then holding w. Each iteration: the bar pass, then two fused passes over the
    // nodes (w and α = w·q, clearing the forces; w −= αq and β² = w·w), then q = w/β with the
    // next x: the same arithmetic, in the same order, as one pass per operation. On a stencil the
    // passes run block by block ([`STENCIL_BLOCK`]), on the pool with `parallel`.
    let mut x = Field::<1>::zeros(n);
    let mut f = Field::<1>::zeros(n);
    // Boundary conditions with springs (the loading plate's) add `k_i/m_i` to the diagonal of
    // node i's row: by Weyl's inequality they raise ω²_max by at most what they say.
    let plate = model.boundaries().stiffening(model.inv_mass());

    let mut rng = ChaCha8Rng::seed_from_u64(START_SEED);
    let mut q: Vec<f64> = (0..dof).map(|_| StandardUniform.sample(&mut rng)).map(|u: f64| u - 0.5).collect();
    normalize(&mut q);
    for c in 0..3 {
        for i in 0..n {
            x.c[c][i][0] = q[c * n + i] * inv_sqrt_m[i];
        }
    }
    let mut q_prev = vec![0.0; dof];
    let mut t = Tridiagonal::default();
    let max_iter = dof.min(max_iter);
    // A listed lattice's sums run over every degree of freedom in one block (in order); a
    // stencil's in blocks of `STENCIL_BLOCK`, the blocks' sums then added in order.
    let block = if matches!(model.layout(), Bars::Stencil(_)) { STENCIL_BLOCK } else { usize::MAX };
    let par = parallel && block != usize::MAX;
    for it in 1..=max_iter {
        // f = −K·M^{-1/2}q (f is zero: cleared by the pass below as it is read).
        match (model.layout(), parallel) {
            (Bars::Stencil(layout), true) => crate::step::stencil::forces_parallel(layout, k1, &x, &mut f),
            _ => bar_forces(model.layout(), k1, &x, &mut f),
        }
        // w = −M^{-1/2}f − β_prev·q_prev (into x, f cleared), α = w·q.
        let beta_prev = t.betas.last().copied().unwrap_or(0.0);
        let (q_r, qp_r, ism) = (&q, &q_prev, &inv_sqrt_m);
        let alpha = sum_blocks(blocks(&mut x, Some(&mut f), block), par, |b| {
            let mut s = -0.0;
            let mut d = b.start;
            for p in b.pieces {
                let fp = p.f.expect("pass with forces");
                for (i, (w, fi)) in p.w.iter_mut().zip(fp.iter_mut()).enumerate() {
                    let v = -fi[0] * ism[p.node + i] - beta_prev * qp_r[d];
                    w[0] = v;
                    fi[0] = 0.0;
                    s += v * q_r[d];
                    d += 1;
                }
            }
            s
        });
        // w −= α·q, β² = w·w.
        let beta2 = sum_blocks(blocks(&mut x, None, block), par, |b| {
            let mut s = -0.0;
            let mut d = b.start;
            for p in b.pieces {
                for w in p.w.iter_mut() {
                    let v = w[0] - alpha * q_r[d];
                    w[0] = v;
                    s += v * v;
                    d += 1;
                }
            }
            s
        });
        let beta: f64 = beta2.sqrt();
        if let Some(done) = t.push(alpha, beta, it, (max_iter, check_every), (gershgorin, plate)) {
            return done;
        }
        // q_prev ← q, q ← w/β, x ← M^{-1/2}q.
        std::mem::swap(&mut q_prev, &mut q);
        let next = |(b, qc): (Block<'_>, &mut [f64])| {
            let mut d = 0;
            for p in b.pieces {
                for (i, w) in p.w.iter_mut().enumerate() {
                    let v = w[0] / beta;
                    qc[d] = v;
                    w[0] = v * ism[p.node + i];
                    d += 1;
                }
            }
        };
        let bl = blocks(&mut x, None, block);
        if par {
            bl.into_par_iter().zip(q.par_chunks_mut(block)).for_each(next);
        } else {
            bl.into_iter().zip(q.chunks_mut(block)).for_each(next);
        }
    }
    Err(t.not_converged(gershgorin))
}

/// The seed of Lanczos's starting vector.
const START_SEED: u64 = 0x5eed_c417;

/// [`critical_step_on`] of the whole block, found by the ranks of a split scene together
/// (docs/model.md §19), each on its window `model` with its bars' stiffness `k`: the same bits as
/// one process. Every rank holds its owned part of Lanczos's vectors; the starting vector's
/// draws are found by seeking the generator; each bar pass reads the halo exchanged as in a step;
/// each sum is the one process's, in its order: a sum of blocks of [`STENCIL_BLOCK`] degrees of
/// freedom (each rank sums the blocks that start on it and sends the few terms of a block begun
/// on the rank before, rank 0 finishing them in order), and the starting vector's norm, one sum
/// in order, handed from rank to rank. The node bound and the plate's stiffening are maxima.
pub fn critical_step_split(
    model: &Model,
    k: &LaneStiffness,
    parallel: bool,
    ranks: &mut dyn Neighbours,
) -> Result<CriticalStep, SolverError> {
    let window = model.split_window().expect("a rank's model is a window of the block").clone();
    let k = match k {
        LaneStiffness::PerBar(k) => StiffnessRef::<1>::PerBar(k.as_chunks::<1>().0),
        LaneStiffness::Factored(f) => {
            StiffnessRef::Factored { runs: model.run_stiffness(), factors: f.as_deref().map(|f| f.as_chunks::<1>().0) }
        }
    };
    let inv_mass = model.inv_mass();
    let local = node_bound_over(inv_mass, |f| k.visit(model.layout(), 0, f), window.owned.clone());
    let nodes = max_over(ranks, local);
    let plate = max_over(ranks, model.boundaries().stiffening(inv_mass));
    let how = Lanczos { max_iter: STENCIL_LANCZOS_ITERATIONS, check_every: 5, parallel };
    let l = lanczos_split(model, &window, k, how, (nodes, plate), ranks)?;
    let c = if l.relative_residual <= LANCZOS_TOLERANCE {
        l
    } else {
        let bound = nodes + plate;
        if !(bound > 0.0 && bound.is_finite()) {
            return Err(SolverError::Numerical(format!(
                "largest stiffness eigenvalue bound is {bound:e}: the lattice has no positive stiffness"
            )));
        }
        let omega = bound.sqrt();
        CriticalStep { omega_max: omega, dt_s: 2.0 / omega, iterations: 0, relative_residual: f64::NAN }
    };
    Ok(with_dashpots(model, c))
}

/// The largest of every rank's `v`, on every rank.
fn max_over(ranks: &mut dyn Neighbours, v: f64) -> f64 {
    let all = ranks.gather(&[v]);
    let mut out = [all.iter().map(|x| x[0]).fold(v, f64::max)];
    ranks.broadcast(&mut out);
    out[0]
}

/// [`lanczos_with`] over the ranks: `cap` is the node bound and the plate's stiffening.
fn lanczos_split(
    model: &Model,
    w: &Window,
    k: StiffnessRef<'_, 1>,
    how: Lanczos,
    (gershgorin, plate): (f64, f64),
    ranks: &mut dyn Neighbours,
) -> Result<CriticalStep, SolverError> {
    let Lanczos { max_iter, check_every, parallel } = how;
    let whole = model.scene().dims.node_count();
    let dof = 3 * whole;
    let owned = w.owned.clone();
    let m = owned.len();
    // This rank's degrees of freedom in the flat (component-major) order: `c·N + g`.
    let starts: [usize; 3] = std::array::from_fn(|c| c * whole + w.global(owned.start));
    let ism: Vec<f64> = model.inv_mass().iter().map(|v| v.sqrt()).collect();
    let mut x = Field::<1>::zeros(model.node_count());
    let mut f = Field::<1>::zeros(model.node_count());
    let mut halo = Halo::default();
    // The starting vector's draws of this rank's degrees of freedom (one 64-bit word pair each).
    let mut rng = ChaCha8Rng::seed_from_u64(START_SEED);
    let mut q = vec![0.0; 3 * m];
    for c in 0..3 {
        rng.set_word_pos(2 * starts[c] as u128);
        for v in &mut q[c * m..(c + 1) * m] {
            let u: f64 = StandardUniform.sample(&mut rng);
            *v = u - 0.5;
        }
    }
    let squares: Vec<f64> = q.iter().map(|v| v * v).collect();
    let norm = handed_sum(ranks, std::iter::empty::<f64>().sum(), &squares, 3).sqrt();
    drop(squares);
    q.iter_mut().for_each(|v| *v /= norm);
    for c in 0..3 {
        for j in 0..m {
            x.c[c][owned.start + j][0] = q[c * m + j] * ism[owned.start + j];
        }
    }
    halo.exchange(w, &mut x, ranks);
    let mut q_prev = vec![0.0; 3 * m];
    let mut terms = vec![0.0; 3 * m];
    let mut t = Tridiagonal::default();
    let max_iter = dof.min(max_iter);
    let Bars::Stencil(layout) = model.layout() else { unreachable!("a window is a stencil") };
    for it in 1..=max_iter {
        if parallel {
            crate::step::stencil::forces_parallel(layout, k, &x, &mut f);
        } else {
            crate::step::stencil::forces(layout, k, &x, &mut f);
        }
        // w = −M^{-1/2}f − β_prev·q_prev, α = w·q.
        let beta_prev = t.betas.last().copied().unwrap_or(0.0);
        for c in 0..3 {
            for j in 0..m {
                let i = owned.start + j;
                let v = -f.c[c][i][0] * ism[i] - beta_prev * q_prev[c * m + j];
                x.c[c][i][0] = v;
                terms[c * m + j] = v * q[c * m + j];
            }
            f.c[c].iter_mut().for_each(|v| v[0] = 0.0);
        }
        let alpha = block_sum(ranks, &terms, m, starts);
        // w −= α·q, β² = w·w.
        for c in 0..3 {
            for j in 0..m {
                let i = owned.start + j;
                let v = x.c[c][i][0] - alpha * q[c * m + j];
                x.c[c][i][0] = v;
                terms[c * m + j] = v * v;
            }
        }
        let beta2 = block_sum(ranks, &terms, m, starts);
        let beta: f64 = beta2.sqrt();
        if let Some(done) = t.push(alpha, beta, it, (max_iter, check_every), (gershgorin, plate)) {
            return done;
        }
        // q_prev ← q, q ← w/β, x ← M^{-1/2}q, the halo's x from the neighbours.
        std::mem::swap(&mut q_prev, &mut q);
        for c in 0..3 {
            for j in 0..m {
                let i = owned.start + j;
                let v = x.c[c][i][0] / beta;
                q[c * m + j] = v;
                x.c[c][i][0] = v * ism[i];
            }
        }
        halo.exchange(w, &mut x, ranks);
    }
    Err(t.not_converged(gershgorin))
}

/// The one process's blocked sum ([`sum_blocks`] of blocks of [`STENCIL_BLOCK`] degrees of
/// freedom) of `terms` (`m` per component, this rank's part of the flat order from `starts`),
/// on every rank. Each rank sends rank 0, per component, the terms of the block begun before its
/// part (a head, fewer than a block) and the sums of the blocks begun on it (as far as its part
/// goes); rank 0 adds each head's terms on to the block they continue, in order, then the blocks.
fn block_sum(ranks: &mut dyn Neighbours, terms: &[f64], m: usize, starts: [usize; 3]) -> f64 {
    let b = STENCIL_BLOCK;
    let mut mine = Vec::new();
    for c in 0..3 {
        let t = &terms[c * m..(c + 1) * m];
        let head = ((b - starts[c] % b) % b).min(m);
        mine.push(head as f64);
        mine.extend_from_slice(&t[..head]);
        let begun: Vec<&[f64]> = t[head..].chunks(b).collect();
        mine.push(begun.len() as f64);
        for piece in begun {
            mine.push(piece.iter().fold(-0.0, |s, v| s + v));
        }
    }
    let all = ranks.gather(&mine);
    let mut total = [0.0];
    if ranks.rank() == 0 {
        let mut at = vec![0usize; all.len()];
        let mut sums = Vec::new();
        let mut open: Option<f64> = None;
        for _ in 0..3 {
            for (r, v) in all.iter().enumerate() {
                let i = &mut at[r];
                let head = v[*i] as usize;
                for t in &v[*i + 1..*i + 1 + head] {
                    let s = open.as_mut().expect("a head continues a block begun before");
                    *s += t;
                }
                *i += 1 + head;
                let begun = v[*i] as usize;
                for s in &v[*i + 1..*i + 1 + begun] {
                    sums.extend(open.replace(*s));
                }
                *i += 1 + begun;
            }
        }
        sums.extend(open);
        total[0] = sums.into_iter().fold(-0.0, |total, s| total + s);
    }
    ranks.broadcast(&mut total);
    total[0]
}

/// Lanczos's tridiagonal as it grows, and its top Ritz pair when last looked at.
#[derive(Default)]
struct Tridiagonal {
    alphas: Vec<f64>,
    betas: Vec<f64>,
    best: Option<(f64, f64)>,
}

impl Tridiagonal {
    /// Adds iteration `it`'s `α` and `β`; looks at the top Ritz pair every `check_every`
    /// iterations (and at `max_iter`, or when the space is invariant) and ends the iteration when
    /// it has converged: `θ + residual` capped by the node bound `cap`, plus the plate's
    /// stiffening.
    fn push(
        &mut self,
        alpha: f64,
        beta: f64,
        it: usize,
        (max_iter, check_every): (usize, usize),
        (cap, plate): (f64, f64),
    ) -> Option<Result<CriticalStep, SolverError>> {
        self.alphas.push(alpha);
        self.betas.push(beta);
        let invariant = beta <= 1e-12 * alpha.abs().max(1e-300);
        if !(it.is_multiple_of(check_every) || it == max_iter || invariant) {
            return None;
        }
        let (theta, residual) = top_ritz(&self.alphas, &self.betas);
        self.best = Some((theta, residual));
        if !(residual <= LANCZOS_TOLERANCE * theta || invariant || it == max_iter) {
            return None;
        }
        let bound = (theta + residual).min(cap) + plate;
        if !(bound > 0.0 && bound.is_finite()) {
            return Some(Err(SolverError::Numerical(format!(
                "largest stiffness eigenvalue is {bound:e}: the lattice has no positive stiffness"
            ))));
        }
        let omega = bound.sqrt();
        Some(Ok(CriticalStep {
            omega_max: omega,
            dt_s: 2.0 / omega,
            iterations: it,
            relative_residual: residual / theta,
        }))
    }

    /// The error of an iteration that ended unconverged.
    fn not_converged(&self, cap: f64) -> SolverError {
        let (theta, residual) = self.best.unwrap_or((cap, 0.0));
        SolverError::Numerical(format!(
            "critical step: Lanczos did not converge (θ = {theta:e}, residual {residual:e})"
        ))
    }
}

/// Degrees of freedom per block of Lanczos's vector passes on a stencil lattice: each block's
/// sums run in order, then the blocks' sums in block order, so the numbers do not depend on how
/// many threads run the blocks.
const STENCIL_BLOCK: usize = 1 << 15;

/// A run of consecutive degrees of freedom of the flat vectors (component-major), as pieces of
/// the fields' components.
struct Block<'a> {
    /// Flat index of its first degree of freedom.
    start: usize,
    pieces: Vec<Piece<'a>>,
}

/// Nodes `node..node + w.len()` of one component of `x` (and of the forces).
struct Piece<'a> {
    node: usize,
    w: &'a mut [[f64; 1]],
    f: Option<&'a mut [[f64; 1]]>,
}

/// `x` (and `f`) cut into blocks of `block` degrees of freedom in flat order.
fn blocks<'a>(x: &'a mut Field<1>, f: Option<&'a mut Field<1>>, block: usize) -> Vec<Block<'a>> {
    let mut out = Vec::new();
    let mut current = Block { start: 0, pieces: Vec::new() };
    let (mut filled, mut flat) = (0, 0);
    let mut fs = f.map(|f| f.c.each_mut().map(|c| c.as_mut_slice()));
    for (c, xc) in x.c.iter_mut().enumerate() {
        let mut w = xc.as_mut_slice();
        let mut fc = fs.as_mut().map(|fs| std::mem::take(&mut fs[c]));
        let mut node = 0;
        while !w.is_empty() {
            let take = (block - filled).min(w.len());
            let (head, tail) = std::mem::take(&mut w).split_at_mut(take);
            w = tail;
            let f_head = fc.as_mut().map(|fc| {
                let (head, tail) = std::mem::take(fc).split_at_mut(take);
                *fc = tail;
                head
            });
            current.pieces.push(Piece { node, w: head, f: f_head });
            node += take;
            filled += take;
            flat += take;
            if filled == block {
                out.push(std::mem::replace(&mut current, Block { start: flat, pieces: Vec::new() }));
                filled = 0;
            }
        }
    }
    if !current.pieces.is_empty() {
        out.push(current);
    }
    out
}

/// `Σ sum(block)` over `blocks`, each block's sum in order and the blocks' in order (the same bits
/// with `parallel` or without: it only runs the blocks on the current rayon pool).
fn sum_blocks<'a>(blocks: Vec<Block<'a>>, parallel: bool, sum: impl Fn(Block<'a>) -> f64 + Sync + Send) -> f64 {
    let partial: Vec<f64> =
        if parallel { blocks.into_par_iter().map(sum).collect() } else { blocks.into_iter().map(sum).collect() };
    partial.into_iter().fold(-0.0, |total, s| total + s)
}

/// Largest Ritz value of the Lanczos tridiagonal and its residual `β_m·|s_m|`.
fn top_ritz(alphas: &[f64], betas: &[f64]) -> (f64, f64) {
    let m = alphas.len();
    let t = DMatrix::from_fn(m, m, |i, j| {
        if i == j {
            alphas[i]
        } else if i + 1 == j {
            betas[i]
        } else if j + 1 == i {
            betas[j]
        } else {
            0.0
        }
    });
    let eig = SymmetricEigen::new(t);
    let (imax, theta) = eig
        .eigenvalues
        .iter()
        .copied()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |acc, (i, v)| if v > acc.1 { (i, v) } else { acc });
    let s_last = eig.eigenvectors[(m - 1, imax)];
    (theta, (betas[m - 1] * s_last).abs())
}

/// Gershgorin bound of `M^{-1/2} K M^{-1/2}`: max over rows of the absolute row sum.
pub fn gershgorin_bound(model: &Model, k: &[f64]) -> f64 {
    let n = model.node_count();
    let inv_sqrt_m: Vec<f64> = model.inv_mass().iter().map(|v| v.sqrt()).collect();
    let mut rows = vec![0.0; 3 * n];
    model.layout().visit(|b, i, j, direction| {
        let kb = k[b];
        // Block k·s⊗s (axial: one entry; diagonal: stored k/3, |s_c s_d| = 1).
        for (a, b) in [(i, j), (j, i)] {
            let scale_self = inv_sqrt_m[a] * inv_sqrt_m[a];
            let scale_other = inv_sqrt_m[a] * inv_sqrt_m[b];
            match direction {
                Direction::Axis(ax) => rows[ax as usize * n + a] += kb * (scale_self + scale_other),
                Direction::Diagonal { .. } => {
                    for c in 0..3 {
                        rows[c * n + a] += 3.0 * kb * (scale_self + scale_other);
                    }
                }
            }
        }
    });
    rows.into_iter().fold(0.0, f64::max)
}

/// A proven upper bound of `ω²_max` from each node's own bars, in one pass over them
/// (docs/model.md §2). A bar `b` between `i` and `j` of kernel stiffness `k` (diagonals stored
/// `k/3` with `s = (±1, ±1, 1)`) stores `k·(s·(u_j − u_i))²` in `uᵀKu`, and
/// `(a − b)² ≤ (1 + t)a² + (1 + 1/t)b²` for any `t > 0`; with `t = m_i/m_j`,
/// `uᵀKu ≤ Σ_i m_i·u_iᵀA_iu_i`, `A_i = Σ_{b∋i} k_b(1/m_i + 1/m_j)·s_b s_bᵀ`, so
/// `ω²_max ≤ max_i λ_max(A_i)` (exact for a chain of two masses). `bars` calls its argument with
/// `(i, j, direction, k)` for every bar.
pub fn node_bound(inv_mass: &[f64], bars: impl FnOnce(&mut dyn FnMut(usize, usize, Direction, f64))) -> f64 {
    node_bound_over(inv_mass, bars, 0..inv_mass.len())
}

/// [`node_bound`] over `nodes` only (a rank's owned nodes, whose bars it holds every one of).
fn node_bound_over(
    inv_mass: &[f64],
    bars: impl FnOnce(&mut dyn FnMut(usize, usize, Direction, f64)),
    nodes: std::ops::Range<usize>,
) -> f64 {
    // Upper triangle of A_i: xx, yy, zz, xy, xz, yz.
    let mut a = vec![[0.0f64; 6]; inv_mass.len()];
    bars(&mut |i, j, direction, k| {
        let w = k * (inv_mass[i] + inv_mass[j]);
        for n in [i, j] {
            let an = &mut a[n];
            match direction {
                Direction::Axis(ax) => an[ax as usize] += w,
                Direction::Diagonal { neg_x, neg_y } => {
                    let (sx, sy) = (if neg_x { -1.0 } else { 1.0 }, if neg_y { -1.0 } else { 1.0 });
                    an[0] += w;
                    an[1] += w;
                    an[2] += w;
                    an[3] += w * sx * sy;
                    an[4] += w * sx;
                    an[5] += w * sy;
                }
            }
        }
    });
    let top = a[nodes].iter().map(sym3_max_eigenvalue).fold(0.0, f64::max);
    // The closed form's round-off, a few ulps of the largest entry: covered many times over.
    top * (1.0 + 1e-12)
}

/// Largest eigenvalue of the symmetric 3×3 matrix of upper triangle `[xx, yy, zz, xy, xz, yz]`
/// (the trigonometric closed form).
fn sym3_max_eigenvalue(m: &[f64; 6]) -> f64 {
    let [a, b, c, d, e, f] = *m;
    let p1 = d * d + e * e + f * f;
    if p1 == 0.0 {
        return a.max(b).max(c);
    }
    let q = (a + b + c) / 3.0;
    let p2 = (a - q).powi(2) + (b - q).powi(2) + (c - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    // B = (A − qI)/p; r = det(B)/2.
    let (ba, bb, bc, bd, be, bf) = ((a - q) / p, (b - q) / p, (c - q) / p, d / p, e / p, f / p);
    let det = ba * (bb * bc - bf * bf) - bd * (bd * bc - bf * be) + be * (bd * bf - bb * be);
    let r = (det / 2.0).clamp(-1.0, 1.0);
    q + 2.0 * p * (r.acos() / 3.0).cos()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn normalize(v: &mut [f64]) {
    let n = dot(v, v).sqrt();
    v.iter_mut().for_each(|x| *x /= n);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Dims;
    use crate::scene::Scene;

    /// Dense `M^{-1/2} K M^{-1/2}` built from unit vectors through the kernel.
    fn dense_max_eigenvalue(model: &Model, k: &[f64]) -> f64 {
        let n = model.node_count();
        let dof = 3 * n;
        let k1: Vec<[f64; 1]> = k.iter().map(|&v| [v]).collect();
        let mut a = DMatrix::zeros(dof, dof);
        let inv_sqrt_m: Vec<f64> = model.inv_mass().iter().map(|v| v.sqrt()).collect();
        for col in 0..dof {
            let mut x = Field::<1>::zeros(n);
            x.c[col / n][col % n][0] = inv_sqrt_m[col % n];
            let mut f = Field::<1>::zeros(n);
            bar_forces(model.layout(), &k1, &x, &mut f);
            for row in 0..dof {
                a[(row, col)] = -f.c[row / n][row % n][0] * inv_sqrt_m[row % n];
            }
        }
        SymmetricEigen::new(a).eigenvalues.iter().copied().fold(f64::NEG_INFINITY, f64::max)
    }

    #[test]
    fn lanczos_bound_matches_dense_eigensolve_and_spec_ratios() {
        for (nu, cv, seed) in [(0.2, 0.0, 1), (0.25, 0.0, 1), (0.2, 0.05, 123), (0.2, 0.2, 7)] {
            let model = Model::new(Scene { poisson: nu, young_cv: cv, ..Scene::paper() });
            let k = model.bar_stiffness(seed).unwrap();
            let dense = dense_max_eigenvalue(&model, &k);
            let crit = critical_time_step(&model, &k).unwrap();
            let lanczos = crit.omega_max * crit.omega_max;
            assert!(lanczos >= dense * (1.0 - 1e-12), "ν {nu} cv {cv}: bound {lanczos} below {dense}");
            assert!(lanczos <= dense * (1.0 + 1e-6), "ν {nu} cv {cv}: bound {lanczos} loose vs {dense}");
            let paper = model.scene().paper_time_step_bound();
            let ratio = paper / crit.dt_s;
            // docs/model.md §2: Eq. 5 is ≈ 9% below the true limit at ν = 0.2 and ≈ 1% above it at 0.25.
            if cv == 0.0 && nu == 0.2 {
                assert!((ratio - 0.91).abs() < 0.02, "ν = 0.2: Eq.5 / true = {ratio}");
            }
            if cv == 0.0 && nu == 0.25 {
                assert!((ratio - 1.01).abs() < 0.02, "ν = 0.25: Eq.5 / true = {ratio}");
            }
        }
    }
    #[test]
    fn a_stencils_blocked_passes_give_one_bound_on_any_thread_count_and_the_listed_one() {
        let scene = Scene { poisson: 0.25, young_cv: 0.05, ..Scene::paper() }.sample(Dims::new(40, 20, 10));
        let stencil = Model::with_stencil(scene.clone());
        assert!(3 * stencil.node_count() > STENCIL_BLOCK, "more than one block, each across two components");
        let k = stencil.lane_stiffness(5).unwrap();
        let serial = critical_step_on(&stencil, &k, false).unwrap();
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        let parallel = pool.install(|| critical_step_on(&stencil, &k, true)).unwrap();
        assert_eq!(serial.dt_s.to_bits(), parallel.dt_s.to_bits(), "{serial:?} against {parallel:?}");
        assert_eq!(serial.iterations, parallel.iterations);
        assert!(serial.iterations > 0, "Lanczos converged: {serial:?}");
        // The same lattice listed, its sums in one block: the same bound to the Lanczos tolerance
        // and the stencil's f32 Weibull factors (≈ 6e-8 relative in ω²).
        let listed = Model::with_listed_bars(scene);
        let reference = critical_time_step(&listed, &listed.bar_stiffness(5).unwrap()).unwrap();
        let ratio = serial.omega_max / reference.omega_max;
        assert!((ratio - 1.0).abs() < 1e-6, "stencil ω_max / listed = {ratio}");
    }

    #[test]
    fn the_node_bound_is_above_the_dense_eigensolve() {
        let scenes = [
            (Dims::new(10, 1, 5), 0.2, 0.0),
            (Dims::new(10, 1, 5), 0.2, 0.05),
            (Dims::new(6, 5, 4), 0.25, 0.0),
            (Dims::new(6, 5, 4), 0.25, 0.05),
            (Dims::new(7, 6, 5), 0.2, 0.2),
        ];
        for (dims, nu, cv) in scenes {
            let model = Model::new(Scene { poisson: nu, young_cv: cv, ..Scene::paper() }.sample(dims));
            let k = model.bar_stiffness(5).unwrap();
            let dense = dense_max_eigenvalue(&model, &k);
            let bound = node_bound(model.inv_mass(), |f| model.layout().visit(|b, i, j, d| f(i, j, d, k[b])));
            eprintln!(
                "{dims:?} ν {nu} cv {cv}: node bound / true ω² = {:.4}, Δt ratio {:.4}",
                bound / dense,
                (dense / bound).sqrt()
            );
            assert!(bound >= dense * (1.0 - 1e-12), "{dims:?}: {bound} below {dense}");
        }
    }

    #[test]
    #[ignore]
    fn lanczos_convergence_experiment() {
        for (dims, nu, cv) in [
            (Dims::new(6, 5, 4), 0.25, 0.05),
            (Dims::new(10, 1, 5), 0.2, 0.05),
            (Dims::new(40, 20, 10), 0.25, 0.05),
            (Dims::new(100, 30, 12), 0.25, 0.05),
            (Dims::new(100, 30, 12), 0.25, 0.0),
            (Dims::new(200, 50, 20), 0.25, 0.0),
            (Dims::new(200, 50, 20), 0.25, 0.05),
        ] {
            let model = Model::new(Scene { poisson: nu, young_cv: cv, ..Scene::paper() }.sample(dims));
            let k = model.bar_stiffness(5).unwrap();
            let k1: &[[f64; 1]] = k.as_chunks::<1>().0;
            let full = lanczos(&model, StiffnessRef::PerBar(k1), 400, f64::INFINITY).unwrap();
            let nb = node_bound(model.inv_mass(), |f| model.layout().visit(|b, i, j, d| f(i, j, d, k[b])));
            let w2 = full.omega_max.powi(2);
            eprintln!(
                "{dims:?}: 400 its {} → ω² {w2:.6e} (res {:.2e}); node bound ×{:.4}",
                full.iterations,
                full.relative_residual,
                nb / w2
            );
            for it in [10, 20, 30, 40, 60, 100] {
                let c = lanczos(&model, StiffnessRef::PerBar(k1), it, f64::INFINITY).unwrap();
                eprintln!(
                    "   {it:3} its: (θ+r)/ω²₄₀₀ = {:.5}, r/θ = {:.3e}",
                    c.omega_max.powi(2) / w2,
                    c.relative_residual
                );
            }
        }
    }
}
