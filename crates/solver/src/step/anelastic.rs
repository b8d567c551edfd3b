//! The medium's forces beyond the elastic bars (docs/model.md §18): each bar's memory variable
//! (a constant Q by the coarse-grained relaxation of [`crate::medium::relaxation`]) and its
//! Kelvin–Voigt dashpot, added to the elastic forces before the trial update.
//!
//! A bar of kernel stiffness `k` (the unrelaxed one) and kernel elongation `e` carries the extra
//! tension `T = −k·Σ_j ζ_j + k·(β/Δt)·(eₙ − eₙ₋₁)`, each memory variable following
//! `τ_j·dζ_j/dt + ζ_j = λ_j·e`, integrated exactly over the step for `e` at the mean of `eₙ₋₁`
//! and `eₙ`: `ζ_j ← a_j·ζ_j + (1 − a_j)·λ_j·(eₙ + eₙ₋₁)/2`, `a_j = exp(−Δt/τ_j)`. The memory
//! variables are stored as `f32` (the force uses the stored value, so the ledger sees the same). The pass runs in the order of the elastic kernels' phases (segments of one
//! phase, or slabs of one phase, write disjoint nodes), serially or on the rayon pool, so every
//! node receives its terms in the same order: the same bits on any thread count. Its work,
//! `T·(eₙ₊₁ − eₙ₋₁)/2` per bar and step, is the ledger's `anelastic` term.

use rayon::prelude::*;

use crate::field::{Field, Lanes};
use crate::geometry::Direction;
use crate::layout::{BarLayout, Bars, Segment};
use crate::medium::{MECHANISMS, kelvin_voigt_step_factor};
use crate::model::Model;
use crate::stencil::{Run, StencilLayout};
use crate::step::primitives::{ForcePtr, elongation, scatter_diagonal, signs};
use crate::stiffness::StiffnessRef;

/// What the pass reads, per zone, mechanism and lane.
#[derive(Clone, Debug)]
pub struct AnelasticParams<const L: usize> {
    /// `exp(−Δt/τ_j)`, index `zone·MECHANISMS + j`.
    decay: Vec<Lanes<L>>,
    /// `(1 − exp(−Δt/τ_j))·λ_j/2`, the same index.
    gain: Vec<Lanes<L>>,
    /// `β/Δt`.
    viscous: Lanes<L>,
    /// Whether the bars carry memory variables (a Q).
    memory: bool,
}

impl<const L: usize> AnelasticParams<L> {
    /// The coefficients of `model`'s medium for steps `dt`, `None` when it does not dissipate.
    pub fn new(model: &Model, dt: &Lanes<L>) -> Option<Self> {
        let medium = &model.scene().medium;
        if !medium.is_dissipative() {
            return None;
        }
        let zones = model.zones();
        let mut decay = vec![[1.0; L]; zones.len() * MECHANISMS];
        let mut gain = vec![[0.0; L]; zones.len() * MECHANISMS];
        for (z, zone) in zones.iter().enumerate() {
            let Some(r) = &zone.relaxation else { continue };
            for j in 0..MECHANISMS {
                for l in 0..L {
                    let a = (-dt[l] / r.tau_s[j]).exp();
                    decay[z * MECHANISMS + j][l] = a;
                    gain[z * MECHANISMS + j][l] = (1.0 - a) * r.weight[j] * 0.5;
                }
            }
        }
        Some(AnelasticParams {
            decay,
            gain,
            viscous: dt.map(|dt| medium.kelvin_voigt_s / dt),
            memory: medium.attenuation.is_some(),
        })
    }

    /// Whether the bars carry memory variables.
    pub fn memory(&self) -> bool {
        self.memory
    }

    /// The extra tension of a bar of stiffness `k` in lane `l` and zone offset `at`
    /// (`zone·MECHANISMS`) from its elongations `en` (now) and `ep` (a step before), advancing its
    /// memory variables `z` (none when the bars carry no Q).
    #[inline(always)]
    fn advance(&self, at: usize, l: usize, k: f64, en: f64, ep: f64, z: Option<&mut [f32; MECHANISMS]>) -> f64 {
        let mut tension = k * self.viscous[l] * (en - ep);
        if let Some(z) = z {
            let (decay, gain) = (&self.decay[at..at + MECHANISMS], &self.gain[at..at + MECHANISMS]);
            let mut sum = 0.0;
            for m in 0..MECHANISMS {
                z[m] = (decay[m][l] * f64::from(z[m]) + gain[m][l] * (en + ep)) as f32;
                sum += f64::from(z[m]);
            }
            tension -= k * sum;
        }
        tension
    }

    /// The same tension from memory variables already advanced (what the ledger pairs with the
    /// displacements of the step).
    #[inline(always)]
    fn held(&self, l: usize, k: f64, en: f64, ep: f64, z: Option<&[f32; MECHANISMS]>) -> f64 {
        let mut tension = k * self.viscous[l] * (en - ep);
        if let Some(z) = z {
            let mut sum = 0.0;
            for zm in z {
                sum += f64::from(*zm);
            }
            tension -= k * sum;
        }
        tension
    }
}

/// Memory variables and their pointer, shared by the threads of one phase (each bar is in
/// exactly one segment or run).
#[derive(Clone, Copy)]
struct MemoryPtr<const L: usize>(*mut Memory<L>);

/// The memory variables of one bar: per lane, one per mechanism.
pub type Memory<const L: usize> = [[f32; MECHANISMS]; L];
// SAFETY: writes go to disjoint bars (see the module docs).
unsafe impl<const L: usize> Send for MemoryPtr<L> {}
unsafe impl<const L: usize> Sync for MemoryPtr<L> {}

/// The levels, coefficients and outputs of one pass.
#[derive(Clone, Copy)]
struct Pass<'a, const L: usize> {
    a: &'a AnelasticParams<L>,
    k: StiffnessRef<'a, L>,
    now: &'a Field<L>,
    before: &'a Field<L>,
    zeta: MemoryPtr<L>,
    f: ForcePtr<L>,
}

impl<const L: usize> Pass<'_, L> {
    /// One bar: its extra tension from the levels and its memory variable, scattered to its ends.
    ///
    /// # Safety
    /// `bar` is below the memory's length when the bars carry memory; `i`, `j` are nodes below
    /// the fields' length; no other thread writes this bar or these nodes.
    #[inline(always)]
    unsafe fn bar(&self, bar: usize, zone: usize, k: &Lanes<L>, direction: Direction, i: usize, j: usize) {
        let mut t = [0.0; L];
        for l in 0..L {
            let (en, ep) = (elongation(direction, self.now, i, j, l), elongation(direction, self.before, i, j, l));
            // SAFETY: forwarded contract.
            let z = self.a.memory.then(|| unsafe { &mut (*self.zeta.0.add(bar))[l] });
            t[l] = self.a.advance(zone * MECHANISMS, l, k[l], en, ep, z);
        }
        // SAFETY: forwarded contract.
        unsafe { scatter(self.f, direction, i, j, &t) };
    }

    /// The bars of one listed segment.
    ///
    /// # Safety
    /// As [`Pass::bar`] for every bar of the segment.
    unsafe fn segment(&self, s: &Segment, layout: &BarLayout, zones: &[u8]) {
        let StiffnessRef::PerBar(k) = self.k else { panic!("a listed lattice has per-bar stiffness") };
        for g in &s.groups {
            for b in g.start..g.end {
                let [i, j] = layout.ends()[b];
                // SAFETY: forwarded contract.
                unsafe { self.bar(b, zones[b] as usize, &k[b], g.direction, i as usize, j as usize) };
            }
        }
    }

    /// The bars of the stencil layers `layers`.
    ///
    /// # Safety
    /// As [`Pass::bar`] for every bar of those layers.
    unsafe fn layers(&self, layout: &StencilLayout, layers: std::ops::Range<usize>, zones: &[u8]) {
        for layer in layers {
            let range = layout.layer_run_range(layer);
            for (index, r) in range.clone().zip(&layout.runs()[range]) {
                // SAFETY: forwarded contract.
                unsafe { self.run(index, r, zones[index] as usize) };
            }
        }
    }

    /// # Safety
    /// As [`Pass::bar`] for every bar of the run.
    unsafe fn run(&self, index: usize, r: &Run, zone: usize) {
        let (lo, hi) = (r.start as usize, (r.start + r.offset) as usize);
        let StiffnessRef::Factored { runs, factors } = self.k else {
            // Per-bar stiffness on a stencil (a test's): the general path.
            for m in 0..r.len as usize {
                let k: Lanes<L> = std::array::from_fn(|l| self.k.of_run_bar(index, r, m, l));
                // SAFETY: forwarded contract.
                unsafe { self.bar(r.first_bar as usize + m, zone, &k, r.direction, lo + m, hi + m) };
            }
            return;
        };
        // The direction, the run's stiffness and the zone's coefficients hoisted out of the loop.
        let (n, nominal) = (r.len as usize, &runs[index]);
        let at = zone * MECHANISMS;
        let (sx, sy, axis) = match r.direction {
            Direction::Axis(a) => (0.0, 0.0, Some(a as usize)),
            Direction::Diagonal { neg_x, neg_y } => {
                let (sx, sy) = signs(neg_x, neg_y);
                (sx, sy, None)
            }
        };
        let (u, v) = (&self.now.c, &self.before.c);
        for m in 0..n {
            let (i, j, bar) = (lo + m, hi + m, r.first_bar as usize + m);
            let base = nominal.at(m, n);
            let mut t = [0.0; L];
            for l in 0..L {
                let k = factors.map_or(base, |f| base * f64::from(f[bar][l]));
                let (en, ep) = match axis {
                    Some(a) => (u[a][j][l] - u[a][i][l], v[a][j][l] - v[a][i][l]),
                    None => (
                        sx * (u[0][j][l] - u[0][i][l]) + sy * (u[1][j][l] - u[1][i][l]) + (u[2][j][l] - u[2][i][l]),
                        sx * (v[0][j][l] - v[0][i][l]) + sy * (v[1][j][l] - v[1][i][l]) + (v[2][j][l] - v[2][i][l]),
                    ),
                };
                // SAFETY: forwarded contract (the run's bars are below the memory's length).
                let z = self.a.memory.then(|| unsafe { &mut (*self.zeta.0.add(bar))[l] });
                t[l] = self.a.advance(at, l, k, en, ep, z);
            }
            // SAFETY: forwarded contract.
            unsafe { scatter(self.f, r.direction, i, j, &t) };
        }
    }
}

/// Adds `t` along a bar of `direction` to end `i` and subtracts it from end `j`.
///
/// # Safety
/// As [`scatter_diagonal`].
#[inline(always)]
unsafe fn scatter<const L: usize>(f: ForcePtr<L>, direction: Direction, i: usize, j: usize, t: &Lanes<L>) {
    match direction {
        Direction::Axis(a) => {
            let c = f.0[a as usize];
            // SAFETY: forwarded contract.
            unsafe {
                crate::step::primitives::add_lanes(&mut *c.add(i), t);
                crate::step::primitives::sub_lanes(&mut *c.add(j), t);
            }
        }
        Direction::Diagonal { neg_x, neg_y } => {
            let (sx, sy) = signs(neg_x, neg_y);
            // SAFETY: forwarded contract.
            unsafe { scatter_diagonal(f, i, j, sx, sy, t) };
        }
    }
}

/// Adds the medium's extra bar forces at level `now` (with `before` one step earlier) to `f` and
/// advances the memory variables `zeta` (one per bar and lane when the bars carry a Q, else
/// empty); with `parallel`, the units of each phase on the current rayon pool (the same bits).
#[allow(clippy::too_many_arguments)]
pub fn forces<const L: usize>(
    model: &Model,
    a: &AnelasticParams<L>,
    k: StiffnessRef<'_, L>,
    now: &Field<L>,
    before: &Field<L>,
    zeta: &mut [Memory<L>],
    f: &mut Field<L>,
    parallel: bool,
) {
    let n = model.node_count();
    assert!(now.len() == n && before.len() == n && f.len() == n, "one displacement and force per node");
    assert_eq!(zeta.len(), if a.memory { model.bar_count() } else { 0 }, "one memory variable per bar");
    let pass = Pass {
        a,
        k,
        now,
        before,
        zeta: MemoryPtr(zeta.as_mut_ptr()),
        f: ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr())),
    };
    match model.layout() {
        Bars::Listed(layout) => {
            let zones = model.bar_zones();
            assert_eq!(zones.len(), layout.ends().len(), "one zone per bar");
            for phase in 0..3u8 {
                let segs: Vec<&Segment> = layout.segments().iter().filter(|s| s.phase == phase).collect();
                // SAFETY: a checked layout; segments of one phase touch disjoint nodes and bars.
                let each = |s: &&Segment| unsafe { pass.segment(s, layout, zones) };
                if parallel { segs.par_iter().for_each(each) } else { segs.iter().for_each(each) }
            }
        }
        Bars::Stencil(layout) => {
            let zones = model.run_zones();
            assert_eq!(zones.len(), layout.runs().len(), "one zone per run");
            let slabs: Vec<std::ops::Range<usize>> = layout.slabs().collect();
            for phase in 0..2 {
                // SAFETY: the slabs of one phase write disjoint layers of nodes and their own bars.
                let each =
                    |s: &std::ops::Range<usize>| unsafe { pass.layers(layout, layout.phase_layers(s, phase), zones) };
                if parallel { slabs.par_iter().for_each(each) } else { slabs.iter().for_each(each) }
            }
        }
    }
}

/// The work `Σ T·(eₙ₊₁ − eₙ₋₁)/2` of the extra tensions over one step, per layer of `layers` (a
/// bar in its lower end's) and lane (J): `new` is `uₙ₊₁`, `now` is `uₙ`, `old` is `uₙ₋₁` and
/// `zeta` the memory variables of step n. Bars in kernel order: the same sums on any thread and
/// rank count.
pub fn work<const L: usize>(
    model: &Model,
    layers: &crate::ledger::EnergyLayers,
    a: &AnelasticParams<L>,
    k: StiffnessRef<'_, L>,
    [new, now, old]: [&Field<L>; 3],
    zeta: &[Memory<L>],
) -> Vec<Lanes<L>> {
    let mut sums = vec![[0.0; L]; layers.count];
    let mut add = |bar: usize, kb: &Lanes<L>, direction: Direction, i: usize, j: usize| {
        let Some(k) = layers.of(i.min(j)) else { return };
        let sum = &mut sums[k];
        for l in 0..L {
            let e = |u: &Field<L>| elongation(direction, u, i, j, l);
            let (en1, en, ep) = (e(new), e(now), e(old));
            let t = a.held(l, kb[l], en, ep, a.memory.then(|| &zeta[bar][l]));
            sum[l] += 0.5 * t * (en1 - ep);
        }
    };
    match (model.layout(), k) {
        (Bars::Listed(layout), StiffnessRef::PerBar(k)) => {
            for g in layout.groups() {
                for b in g.start..g.end {
                    let [i, j] = layout.ends()[b];
                    add(b, &k[b], g.direction, i as usize, j as usize);
                }
            }
        }
        (Bars::Stencil(layout), k) => {
            for (index, r) in layout.runs().iter().enumerate() {
                let (lo, hi) = (r.start as usize, (r.start + r.offset) as usize);
                for m in 0..r.len as usize {
                    let kb: Lanes<L> = std::array::from_fn(|l| k.of_run_bar(index, r, m, l));
                    add(r.first_bar as usize + m, &kb, r.direction, lo + m, hi + m);
                }
            }
        }
        (Bars::Listed(_), _) => panic!("a listed lattice has per-bar stiffness"),
    }
    sums
}

/// The stable step of `model` with its Kelvin–Voigt damping over the undamped one `dt_critical`.
pub fn step_factor(model: &Model, dt_critical_s: f64) -> f64 {
    kelvin_voigt_step_factor(model.scene().medium.kelvin_voigt_s, dt_critical_s)
}
