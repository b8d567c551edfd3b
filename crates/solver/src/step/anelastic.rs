//! The medium's forces beyond the elastic bars (docs/model.md §18): each bar's memory variables
//! (a constant Q by the relaxation mechanisms of [`crate::medium::relaxation`]) and its
//! Kelvin–Voigt dashpot, added to the elastic forces before the trial update.
//!
//! A bar of kernel stiffness `k` (the unrelaxed one) and kernel elongation `e` carries the extra
//! tension `T = −k·Σ_j ζ_j + k·(β/Δt)·(eₙ − eₙ₋₁)`, each memory variable following
//! `τ_j·dζ_j/dt + ζ_j = λ_j·e`, integrated exactly over the step for `e` at the mean of `eₙ₋₁`
//! and `eₙ`: `ζ_j ← a_j·ζ_j + (1 − a_j)·λ_j·(eₙ + eₙ₋₁)/2`, `a_j = exp(−Δt/τ_j)`. The memory
//! variables are stored as `f32` (the force uses the stored value, so the ledger sees the same).
//!
//! On a stencil lattice the kernel adds `T` to each run's elastic tensions before it scatters
//! them ([`RunMedium`]): one sweep over the bars, in the kernel's slab and phase order. On a
//! listed lattice a second pass runs in the order of the elastic kernel's phases (segments of one
//! phase write disjoint nodes). Either way every node receives its terms in one order: the same
//! bits on any thread count. The work `T·(eₙ₊₁ − eₙ₋₁)/2` per bar and step is the ledger's
//! `anelastic` term.

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

    /// Coefficients given directly (tests): per zone and mechanism `decay` = `exp(−Δt/τ)` and
    /// `gain` = `(1 − exp(−Δt/τ))·λ/2`, `viscous` = `β/Δt`.
    #[cfg(test)]
    pub(crate) fn from_parts(decay: Vec<Lanes<L>>, gain: Vec<Lanes<L>>, viscous: Lanes<L>, memory: bool) -> Self {
        assert!(
            decay.len() == gain.len() && decay.len().is_multiple_of(MECHANISMS),
            "coefficients per zone and mechanism"
        );
        AnelasticParams { decay, gain, viscous, memory }
    }

    /// Whether the bars carry memory variables.
    pub fn memory(&self) -> bool {
        self.memory
    }

    /// The extra tension of a bar of stiffness `k` in lane `l` and zone offset `at`
    /// (`zone·MECHANISMS`) from its elongations `en` (now) and `ep` (a step before), advancing its
    /// memory variables `z` (none when the bars carry no Q).
    #[inline(always)]
    pub(crate) fn advance(
        &self,
        at: usize,
        l: usize,
        k: f64,
        en: f64,
        ep: f64,
        z: Option<&mut [f32; MECHANISMS]>,
    ) -> f64 {
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

/// The memory variables of every bar and lane, mechanism-major: mechanism `j` of bar `b` in lane
/// `l` at `(j·bars + b)·L + l` (so that a run's bars are consecutive for each mechanism, and the
/// stencil kernel's loops over them vectorise).
#[derive(Clone, Debug, Default, PartialEq, bincode::Encode, bincode::Decode)]
pub struct Memory {
    /// Bars times lanes: the distance between two mechanisms.
    stride: usize,
    z: Vec<f32>,
}

impl Memory {
    /// Memory variables at rest for `bars` bars of `lanes` lanes.
    pub fn at_rest(bars: usize, lanes: usize) -> Memory {
        Memory { stride: bars * lanes, z: vec![0.0; MECHANISMS * bars * lanes] }
    }

    /// The bytes they take.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.z.as_slice())
    }

    /// Their bits, for comparisons that tell −0 from 0.
    #[cfg(test)]
    pub(crate) fn bits(&self) -> Vec<u32> {
        self.z.iter().map(|z| z.to_bits()).collect()
    }

    /// The memory variables of bar-lane `q` (`bar·L + lane`).
    pub(crate) fn get(&self, q: usize) -> [f32; MECHANISMS] {
        std::array::from_fn(|j| self.z[j * self.stride + q])
    }

    /// Sets those of bar-lane `q`.
    pub(crate) fn set(&mut self, q: usize, z: [f32; MECHANISMS]) {
        for (j, z) in z.into_iter().enumerate() {
            self.z[j * self.stride + q] = z;
        }
    }
}

/// Memory variables and their pointer, shared by the threads of one phase (each bar is in
/// exactly one segment or run).
#[derive(Clone, Copy)]
struct MemoryPtr(*mut f32, usize);

// SAFETY: writes go to disjoint bars (see the module docs).
unsafe impl Send for MemoryPtr {}
unsafe impl Sync for MemoryPtr {}

/// The levels, coefficients and outputs of one pass.
#[derive(Clone, Copy)]
struct Pass<'a, const L: usize> {
    a: &'a AnelasticParams<L>,
    k: StiffnessRef<'a, L>,
    now: &'a Field<L>,
    before: &'a Field<L>,
    zeta: MemoryPtr,
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
            let q = bar * L + l;
            let at = |j: usize| q + j * self.zeta.1;
            let mut z = [0.0; MECHANISMS];
            if self.a.memory {
                // SAFETY: forwarded contract.
                z = std::array::from_fn(|j| unsafe { *self.zeta.0.add(at(j)) });
            }
            t[l] = self.a.advance(zone * MECHANISMS, l, k[l], en, ep, self.a.memory.then_some(&mut z));
            if self.a.memory {
                for (j, z) in z.into_iter().enumerate() {
                    // SAFETY: forwarded contract.
                    unsafe { *self.zeta.0.add(at(j)) = z };
                }
            }
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

/// Adds the medium's extra bar forces of a listed lattice at level `now` (with `before` one step
/// earlier) to `f` and advances the memory variables `zeta` (one per bar and lane when the bars
/// carry a Q, else empty); with `parallel`, the segments of each phase on the current rayon pool
/// (the same bits). A stencil lattice adds them inside its kernel ([`RunMedium`]).
#[allow(clippy::too_many_arguments)]
pub fn forces<const L: usize>(
    model: &Model,
    a: &AnelasticParams<L>,
    k: StiffnessRef<'_, L>,
    now: &Field<L>,
    before: &Field<L>,
    zeta: &mut Memory,
    f: &mut Field<L>,
    parallel: bool,
) {
    let n = model.node_count();
    assert!(now.len() == n && before.len() == n && f.len() == n, "one displacement and force per node");
    check_memory::<L>(model.bar_count(), a, zeta);
    let layout = model.layout().listed();
    let pass = Pass {
        a,
        k,
        now,
        before,
        zeta: MemoryPtr(zeta.z.as_mut_ptr(), zeta.stride),
        f: ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr())),
    };
    let zones = model.bar_zones();
    assert_eq!(zones.len(), layout.ends().len(), "one zone per bar");
    for phase in 0..3u8 {
        let segs: Vec<&Segment> = layout.segments().iter().filter(|s| s.phase == phase).collect();
        // SAFETY: a checked layout; segments of one phase touch disjoint nodes and bars.
        let each = |s: &&Segment| unsafe { pass.segment(s, layout, zones) };
        if parallel { segs.par_iter().for_each(each) } else { segs.iter().for_each(each) }
    }
}

/// The scratch arrays of one run, each `L` per bar of the run.
pub(crate) struct Scratch<'a> {
    /// Stiffness, as the kernel takes it.
    pub k: &'a [f64],
    /// `eₙ + eₙ₋₁`.
    pub sum: &'a mut [f64],
    /// `eₙ − eₙ₋₁`.
    pub diff: &'a mut [f64],
}

/// Checks that `zeta` holds one memory variable per mechanism, bar and lane of `model` when the
/// bars carry a Q, and none otherwise.
fn check_memory<const L: usize>(bars: usize, a: &AnelasticParams<L>, zeta: &Memory) {
    let bars = if a.memory { bars } else { 0 };
    assert!(zeta.z.len() == MECHANISMS * bars * L && zeta.stride == bars * L, "one memory variable per bar");
}

/// What the stencil kernel reads to add the medium's tensions to a run's elastic ones before it
/// scatters them (one sweep over the bars: [`crate::step::stencil`]).
#[derive(Clone, Copy)]
pub(crate) struct RunMedium<const L: usize> {
    a: *const AnelasticParams<L>,
    /// The zone of each run.
    zones: *const u8,
    /// `uₙ₋₁`, per component, `L` per node.
    before: [*const f64; 3],
    /// The memory variables and the distance between two mechanisms.
    zeta: MemoryPtr,
    /// The bars and nodes of the layout it was built for (checked by the kernel).
    pub(crate) fits: (usize, usize),
}

// SAFETY: a run's bars (and so their memory variables) belong to one layer, and the tasks of one
// phase run disjoint layers (see `step::stencil`'s module doc); `before` is only read.
unsafe impl<const L: usize> Send for RunMedium<L> {}
unsafe impl<const L: usize> Sync for RunMedium<L> {}

impl<const L: usize> RunMedium<L> {
    /// The scratch arrays [`RunMedium::add`] takes (as [`Scratch`]).
    pub(crate) const SCRATCH: usize = 3;

    /// The medium of the stencil lattice `layout` with coefficients `a`, the zone of each run
    /// `zones`, the level `before` one step before the kernel's and the memory variables `zeta`.
    /// The pointers stay valid while `a`, `zones`, `before` and `zeta` are neither moved nor
    /// dropped.
    pub(crate) fn new(
        layout: &StencilLayout,
        zones: &[u8],
        a: &AnelasticParams<L>,
        before: &Field<L>,
        zeta: &mut Memory,
    ) -> Self {
        assert_eq!(zones.len(), layout.runs().len(), "one zone per run");
        assert!(zones.iter().all(|&z| (z as usize + 1) * MECHANISMS <= a.decay.len()), "zones the coefficients hold");
        assert!(before.len() == layout.nodes(), "one displacement per node");
        check_memory::<L>(layout.bars(), a, zeta);
        RunMedium {
            a,
            zones: zones.as_ptr(),
            before: [0, 1, 2].map(|c| before.c[c].as_flattened().as_ptr()),
            zeta: MemoryPtr(zeta.z.as_mut_ptr(), zeta.stride),
            fits: (layout.bars(), layout.nodes()),
        }
    }

    /// Adds to the elastic tensions `t` of run `index` (`r`, `L` per bar) the medium's, from the
    /// elongations of `u` (the kernel's level, flat per component) and of the level before, with
    /// the stiffness `k` as the kernel takes it, advancing the run's memory variables:
    /// `t ← t + T`, `T` as [`AnelasticParams::advance`] computes it (the same operations in the
    /// same order, so the same bits), in one loop over the run's bar-lanes that vectorises.
    ///
    /// # Safety
    /// The run lies inside `u` and the arrays `self` points to, `t` and `k` hold the run, and no
    /// other thread touches its bars.
    #[inline(always)]
    pub(crate) unsafe fn add(&self, index: usize, r: &Run, u: [*const f64; 3], t: &mut [f64], scratch: Scratch<'_>) {
        let n = r.len as usize * L;
        let (sum, diff) = (&mut scratch.sum[..n], &mut scratch.diff[..n]);
        let (lo, hi) = (r.start as usize * L, (r.start + r.offset) as usize * L);
        // SAFETY: forwarded contract.
        unsafe {
            let read = |p: *const f64, at: usize| std::slice::from_raw_parts(p.add(at), n);
            let b = self.before;
            match r.direction {
                Direction::Axis(c) => {
                    let c = c as usize;
                    let (ul, uh, bl, bh) = (read(u[c], lo), read(u[c], hi), read(b[c], lo), read(b[c], hi));
                    for q in 0..n {
                        let (en, ep) = (uh[q] - ul[q], bh[q] - bl[q]);
                        (sum[q], diff[q]) = (en + ep, en - ep);
                    }
                }
                Direction::Diagonal { neg_x, neg_y } => {
                    let (sx, sy) = signs(neg_x, neg_y);
                    let [xl, yl, zl] = [0, 1, 2].map(|c| read(u[c], lo));
                    let [xh, yh, zh] = [0, 1, 2].map(|c| read(u[c], hi));
                    for q in 0..n {
                        let en = sx * (xh[q] - xl[q]) + sy * (yh[q] - yl[q]) + (zh[q] - zl[q]);
                        (sum[q], diff[q]) = (en, en);
                    }
                    let [xl, yl, zl] = [0, 1, 2].map(|c| read(b[c], lo));
                    let [xh, yh, zh] = [0, 1, 2].map(|c| read(b[c], hi));
                    for q in 0..n {
                        let ep = sx * (xh[q] - xl[q]) + sy * (yh[q] - yl[q]) + (zh[q] - zl[q]);
                        (sum[q], diff[q]) = (sum[q] + ep, diff[q] - ep);
                    }
                }
            }
            self.terms(index, r, t, scratch.k, sum, diff);
        }
    }

    /// [`RunMedium::add`] with `eₙ + eₙ₋₁` and `eₙ − eₙ₋₁` of the run's bar-lanes in `sum` and
    /// `diff`.
    ///
    /// # Safety
    /// As [`RunMedium::add`].
    #[inline(always)]
    unsafe fn terms(&self, index: usize, r: &Run, t: &mut [f64], k: &[f64], sum: &[f64], diff: &[f64]) {
        let bars = r.len as usize;
        let n = bars * L;
        let (t, k, sum, diff) = (&mut t[..n], &k[..n], &sum[..n], &diff[..n]);
        // SAFETY: forwarded contract.
        let a = unsafe { &*self.a };
        let viscous = &a.viscous;
        if !a.memory {
            for m in 0..bars {
                for l in 0..L {
                    let q = m * L + l;
                    t[q] += k[q] * viscous[l] * diff[q];
                }
            }
            return;
        }
        // SAFETY: forwarded contract (the zone is one the coefficients hold, checked in `new`).
        let (at, [z0, z1, z2, z3]) = unsafe {
            let first = r.first_bar as usize * L;
            let z = |j: usize| std::slice::from_raw_parts_mut(self.zeta.0.add(j * self.zeta.1 + first), bars * L);
            (*self.zones.add(index) as usize * MECHANISMS, [z(0), z(1), z(2), z(3)])
        };
        let (decay, gain) = (&a.decay[at..at + MECHANISMS], &a.gain[at..at + MECHANISMS]);
        for m in 0..bars {
            for l in 0..L {
                let q = m * L + l;
                let mut held = 0.0;
                for (j, z) in [&mut z0[q], &mut z1[q], &mut z2[q], &mut z3[q]].into_iter().enumerate() {
                    *z = (decay[j][l] * f64::from(*z) + gain[j][l] * sum[q]) as f32;
                    held += f64::from(*z);
                }
                t[q] += k[q] * viscous[l] * diff[q] - k[q] * held;
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
    zeta: &Memory,
) -> Vec<Lanes<L>> {
    let mut sums = vec![[0.0; L]; layers.count];
    let mut add = |bar: usize, kb: &Lanes<L>, direction: Direction, i: usize, j: usize| {
        let Some(k) = layers.of(i.min(j)) else { return };
        let sum = &mut sums[k];
        for l in 0..L {
            let e = |u: &Field<L>| elongation(direction, u, i, j, l);
            let (en1, en, ep) = (e(new), e(now), e(old));
            let z = a.memory.then(|| zeta.get(bar * L + l));
            let t = a.held(l, kb[l], en, ep, z.as_ref());
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
