//! The rupture kernel: the bar forces of scenes with `[rupture]`, every bar following the
//! bilinear law of [`crate::rupture`] (docs/model.md §11), `L` seeds side by side.
//!
//! It is a variant of the elastic kernel ([`crate::step::bars`]), chosen once when the stepper is
//! built: a scene without rupture never runs it. The arithmetic of a bar in its elastic range is
//! the elastic kernel's with the bar's current tension stiffness in place of its undamaged one,
//! `t = k_s·p` (kernel units: `p = e·Δu` along an axis, `s·Δu` along a diagonal with the stored
//! `k/3`), so a run in which nothing has cracked gives the elastic kernel's numbers bit for bit.
//! On top of it, one lane-independent **gate** per bar decides whether the law must be looked at
//! exactly: `t·p = k_s·p² > gate` in any lane, with `gate` just below the smallest
//! `k·p_peak²` over the lanes while the bar is intact, and `−∞` once it is damaged in any lane (a
//! damaged bar is checked every step: compression uses its undamaged stiffness). The gate costs
//! one multiply and compare per lane and reads one `f64` per bar shared by the lanes; the exact
//! law, the damage state and the crack log are touched only for the few bars it lets through.
//!
//! **Exact law.** For a gated bar each lane takes [`law_step`] — which returns the elastic `t`
//! itself, bit for bit, where nothing changes — so a lane's numbers do not depend on which other
//! lanes opened the gate: lane `l` of a batch is bit-identical to that seed alone.
//!
//! **Energy ledger.** The force of a bar at step `n` is always `k_n·p_n`, `k_n` the stiffness it
//! has then (the secant in tension, the undamaged stiffness in compression). The work of that
//! force over the step, `k_n·p_n·(p_{n+1} − p_{n−1})/2`, is the change of `½·k_n·p_n·p_{n+1}` (the
//! strain energy [`strain_energy`] the energy terms report) plus `½·(k_{n−1} − k_n)·p_{n−1}·p_n`,
//! which is what the bar dissipated in the step. The kernel adds the latter to the fracture term
//! whenever a bar's stiffness changes, so the energy balance closes to round-off; it converges to
//! the law's closed form [`crate::rupture::BarLaw::dissipated`] as Δt → 0.
//!
//! Every pass (serial, fused with the integration, parallel over slabs) walks the groups of the
//! elastic kernel in the same order and keeps one ledger and crack list per segment, folded in
//! segment order: the same bits whatever the pass or thread count.

use std::ops::Range;

use rayon::prelude::*;
use stickslip_isa::{Isa, widest};

use crate::field::{Field, Lanes};
use crate::geometry::Direction;
use crate::layout::{BarGroup, BarLayout, Segment};
use crate::rupture::law_step;
use crate::step::primitives::{
    ForcePtr, add_lanes, check, elongation, project, scatter_diagonal, signs, strain_energy_with, sub_lanes,
};

/// The gate of an intact bar sits this fraction below `k·p_peak²`, so round-off in `t·p` never
/// hides a bar that passed its peak (the exact law decides).
const GATE_MARGIN: f64 = 1e-12;

/// What the rupture kernel reads and does not change: the peak elongation of each bar and lane
/// (kernel units, see [`crate::model::Model::bar_strength`]) and `Kr`.
#[derive(Clone, Debug, PartialEq)]
pub struct RuptureParams<const L: usize> {
    /// Peak elongation per bar and lane (kernel units).
    pub peak: Vec<Lanes<L>>,
    /// `εr/εp`.
    pub kr: f64,
}

/// What a bar did.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, bincode::Encode, bincode::Decode)]
pub enum CrackKind {
    /// Passed its peak: it starts softening.
    Soften,
    /// Reached `εr`: no force in tension any more.
    Break,
}

impl CrackKind {
    /// `"soften"` or `"break"`.
    pub fn name(self) -> &'static str {
        match self {
            CrackKind::Soften => "soften",
            CrackKind::Break => "break",
        }
    }
}

/// One transition of one bar in one lane.
#[derive(Clone, Copy, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct CrackLog {
    /// The step (its viewed index once committed).
    pub step: u64,
    /// Internal bar index.
    pub bar: u32,
    /// What happened.
    pub kind: CrackKind,
    /// The bar's elongation then (kernel units).
    pub elongation: f64,
}

/// The damage of every bar and lane, and the transitions not yet taken by a recorder.
#[derive(Clone, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct RuptureState<const L: usize> {
    /// Tension stiffness now (kernel units): the undamaged one until the peak, then the secant,
    /// 0 once broken.
    pub secant: Vec<Lanes<L>>,
    /// Largest elongation reached beyond the peak (kernel units), 0 until then.
    pub reach: Vec<Lanes<L>>,
    /// Lane-independent gate per bar (see the module doc).
    pub gate: Vec<f64>,
    /// Transitions per lane since the last drain.
    pub cracks: [Vec<CrackLog>; L],
}

impl<const L: usize> RuptureState<L> {
    /// Every bar intact: secant = `k`, nothing reached, gates from `k` and the peaks.
    pub fn intact(k: &[Lanes<L>], params: &RuptureParams<L>) -> Self {
        assert_eq!(k.len(), params.peak.len(), "one peak per bar");
        let gate = k
            .iter()
            .zip(&params.peak)
            .map(|(k, p)| (0..L).map(|l| k[l] * p[l] * p[l]).fold(f64::INFINITY, f64::min) * (1.0 - GATE_MARGIN))
            .collect();
        RuptureState {
            secant: k.to_vec(),
            reach: vec![[0.0; L]; k.len()],
            gate,
            cracks: std::array::from_fn(|_| Vec::new()),
        }
    }

    /// Bars damaged (past their peak) in lane `l`.
    pub fn damaged(&self, k: &[Lanes<L>], l: usize) -> usize {
        self.secant.iter().zip(k).filter(|(s, k)| s[l] != k[l]).count()
    }

    /// Bars broken in lane `l`.
    pub fn broken(&self, l: usize) -> usize {
        self.secant.iter().filter(|s| s[l] == 0.0).count()
    }

    /// Takes lane `l`'s transitions since the last call.
    pub fn drain(&mut self, l: usize) -> std::vec::Drain<'_, CrackLog> {
        self.cracks[l].drain(..)
    }
}

/// What one segment of one pass produced: the energy its bars dissipated per lane and their
/// transitions `(bar, lane, kind, elongation)`.
#[derive(Clone, Debug, Default)]
pub struct SegmentOut<const L: usize> {
    dissipated: Vec<f64>,
    cracks: Vec<(u32, u8, CrackKind, f64)>,
}

impl<const L: usize> SegmentOut<L> {
    fn clear(&mut self) {
        self.dissipated.clear();
        self.dissipated.resize(L, 0.0);
        self.cracks.clear();
    }
}

/// Raw views of the damage state shared by the segments of one phase.
#[derive(Clone, Copy)]
struct Shared<const L: usize> {
    k0: *const Lanes<L>,
    peak: *const Lanes<L>,
    kr: f64,
    secant: *mut Lanes<L>,
    reach: *mut Lanes<L>,
    gate: *mut f64,
}

// SAFETY: the segments run together touch disjoint bars (a bar belongs to one segment), and the
// arrays outlive the pass.
unsafe impl<const L: usize> Send for Shared<L> {}
unsafe impl<const L: usize> Sync for Shared<L> {}

/// Everything a pass reads and writes besides the force field.
pub struct Pass<'a, const L: usize> {
    /// The bars.
    pub layout: &'a BarLayout,
    /// Undamaged stiffness per bar and lane (kernel units).
    pub k0: &'a [Lanes<L>],
    /// Peaks and `Kr`.
    pub params: &'a RuptureParams<L>,
    /// Damage.
    pub state: &'a mut RuptureState<L>,
    /// Displacements the forces are taken at (`uₙ`).
    pub u: &'a Field<L>,
    /// The level before (`uₙ₋₁`), for the energy ledger.
    pub older: &'a Field<L>,
}

impl<const L: usize> Pass<'_, L> {
    fn shared(&mut self) -> Shared<L> {
        Shared {
            k0: self.k0.as_ptr(),
            peak: self.params.peak.as_ptr(),
            kr: self.params.kr,
            secant: self.state.secant.as_mut_ptr(),
            reach: self.state.reach.as_mut_ptr(),
            gate: self.state.gate.as_mut_ptr(),
        }
    }

    fn check(&self, f: &Field<L>, outs: &mut Vec<SegmentOut<L>>) {
        check(self.layout, self.k0, self.u, f);
        let n = self.k0.len();
        assert!(
            self.params.peak.len() == n
                && self.state.secant.len() == n
                && self.state.reach.len() == n
                && self.state.gate.len() == n,
            "one damage state per bar"
        );
        for c in 0..3 {
            assert_eq!(self.older.c[c].len(), self.layout.nodes(), "older level over the layout's nodes");
        }
        outs.resize_with(self.layout.segments().len(), SegmentOut::default);
        outs.iter_mut().for_each(SegmentOut::clear);
    }
}

/// Folds the segments' outputs into the lanes' fracture energy (`dissipated[l]`) and crack logs,
/// in segment order; `step` is the step being taken.
pub(crate) fn fold<const L: usize>(
    outs: &[SegmentOut<L>],
    step: u64,
    dissipated: &mut [f64; L],
    state: &mut RuptureState<L>,
) {
    for o in outs {
        for l in 0..L {
            if o.dissipated[l] != 0.0 {
                dissipated[l] += o.dissipated[l];
            }
        }
        for &(bar, lane, kind, elongation) in &o.cracks {
            state.cracks[lane as usize].push(CrackLog { step, bar, kind, elongation });
        }
    }
}

/// Adds the internal bar forces to `f` on the calling thread; `outs` gets one entry per segment.
pub fn forces<const L: usize>(mut pass: Pass<'_, L>, f: &mut Field<L>, outs: &mut Vec<SegmentOut<L>>) {
    pass.check(f, outs);
    let isa = Isa::current();
    let s = pass.shared();
    let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
    for (seg, out) in pass.layout.segments().iter().zip(outs.iter_mut()) {
        for g in &seg.groups {
            // SAFETY: checked arrays, one thread.
            unsafe { group_dispatch(isa, g, pass.layout.ends(), pass.u, pass.older, fp, s, out) };
        }
    }
}

/// As [`forces`], the segments of each phase on the current rayon pool (the same bits).
pub fn forces_parallel<const L: usize>(mut pass: Pass<'_, L>, f: &mut Field<L>, outs: &mut Vec<SegmentOut<L>>) {
    pass.check(f, outs);
    let isa = Isa::current();
    let s = pass.shared();
    let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
    let (layout, u, older) = (pass.layout, pass.u, pass.older);
    for phase in 0..3u8 {
        let work: Vec<(&Segment, &mut SegmentOut<L>)> =
            layout.segments().iter().zip(outs.iter_mut()).filter(|(seg, _)| seg.phase == phase).collect();
        work.into_par_iter().for_each(|(seg, out)| {
            for g in &seg.groups {
                // SAFETY: checked arrays; segments of one phase touch disjoint nodes and bars.
                unsafe { group_dispatch(isa, g, layout.ends(), u, older, fp, s, out) };
            }
        });
    }
}

/// As [`forces`] (the same groups in the same order, so the same bits), calling
/// `finish(nodes, f)` after each group for every run of nodes whose forces are then complete.
pub fn forces_finishing<const L: usize>(
    mut pass: Pass<'_, L>,
    f: &mut Field<L>,
    outs: &mut Vec<SegmentOut<L>>,
    mut finish: impl FnMut(Range<usize>, &mut Field<L>),
) {
    pass.check(f, outs);
    let isa = Isa::current();
    let s = pass.shared();
    let mut slot = 0;
    for (seg, out) in pass.layout.segments().iter().zip(outs.iter_mut()) {
        for g in &seg.groups {
            let fp = ForcePtr(f.c.each_mut().map(|c| c.as_mut_ptr()));
            // SAFETY: checked arrays, one thread; `fp` is not used past this call.
            unsafe { group_dispatch(isa, g, pass.layout.ends(), pass.u, pass.older, fp, s, out) };
            for r in pass.layout.finished_after(slot) {
                finish(r.clone(), f);
            }
            slot += 1;
        }
    }
    for r in pass.layout.finished_after(slot) {
        finish(r.clone(), f);
    }
}

widest! {
    /// Runs one group in instruction set `isa`.
    ///
    /// # Safety
    /// The pass's arrays were checked against the layout, and no other thread touches the
    /// group's nodes or bars.
    #[allow(clippy::too_many_arguments)]
    unsafe fn group_dispatch<const L: usize>(
        g: &BarGroup,
        ends: &[[u32; 2]],
        u: &Field<L>,
        older: &Field<L>,
        f: ForcePtr<L>,
        s: Shared<L>,
        out: &mut SegmentOut<L>,
    ) => group_forces
}

#[inline(always)]
unsafe fn group_forces<const L: usize>(
    g: &BarGroup,
    ends: &[[u32; 2]],
    u: &Field<L>,
    older: &Field<L>,
    f: ForcePtr<L>,
    s: Shared<L>,
    out: &mut SegmentOut<L>,
) {
    let bars = g.start..g.end;
    // SAFETY (all arms): ends are below the node count of u, older and f, and the group's bars
    // below the length of the damage arrays (checked pass).
    unsafe {
        match g.direction {
            Direction::Axis(a) => axial(bars, ends, a as usize, u, older, f, s, out),
            Direction::Diagonal { neg_x: false, neg_y: false } => {
                diagonal::<L, false, false>(bars, ends, u, older, f, s, out)
            }
            Direction::Diagonal { neg_x: false, neg_y: true } => {
                diagonal::<L, false, true>(bars, ends, u, older, f, s, out)
            }
            Direction::Diagonal { neg_x: true, neg_y: false } => {
                diagonal::<L, true, false>(bars, ends, u, older, f, s, out)
            }
            Direction::Diagonal { neg_x: true, neg_y: true } => {
                diagonal::<L, true, true>(bars, ends, u, older, f, s, out)
            }
        }
    }
}

/// Whether any lane's `t·p` passes the gate: the largest over the lanes against it (a vector
/// max and one compare, where a chain of per-lane compares does not vectorise).
#[inline(always)]
fn gated<const L: usize>(t: &Lanes<L>, p: &Lanes<L>, gate: f64) -> bool {
    let mut top = t[0] * p[0];
    for l in 1..L {
        top = top.max(t[l] * p[l]);
    }
    top > gate
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn axial<const L: usize>(
    bars: Range<usize>,
    ends: &[[u32; 2]],
    a: usize,
    u: &Field<L>,
    older: &Field<L>,
    f: ForcePtr<L>,
    s: Shared<L>,
    out: &mut SegmentOut<L>,
) {
    let (uc, oc, fc) = (u.c[a].as_ptr(), older.c[a].as_ptr(), f.0[a]);
    for b in bars {
        // SAFETY: b is below the bar count and i, j below the node count (checked pass).
        unsafe {
            let e = *ends.get_unchecked(b);
            let (i, j) = (e[0] as usize, e[1] as usize);
            let (ui, uj) = (*uc.add(i), *uc.add(j));
            let ks = *s.secant.add(b);
            let mut p = [0.0; L];
            let mut t = [0.0; L];
            for l in 0..L {
                p[l] = uj[l] - ui[l];
                t[l] = ks[l] * p[l];
            }
            if gated(&t, &p, *s.gate.add(b)) {
                let before = || {
                    let (oi, oj) = (*oc.add(i), *oc.add(j));
                    std::array::from_fn(|l| oj[l] - oi[l])
                };
                t = exact(b, p, t, before, s, out);
            }
            add_lanes(&mut *fc.add(i), &t);
            sub_lanes(&mut *fc.add(j), &t);
        }
    }
}

#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn diagonal<const L: usize, const NX: bool, const NY: bool>(
    bars: Range<usize>,
    ends: &[[u32; 2]],
    u: &Field<L>,
    older: &Field<L>,
    f: ForcePtr<L>,
    s: Shared<L>,
    out: &mut SegmentOut<L>,
) {
    let (sx, sy) = signs(NX, NY);
    let (ux, uy, uz) = (u.c[0].as_ptr(), u.c[1].as_ptr(), u.c[2].as_ptr());
    let (ox, oy, oz) = (older.c[0].as_ptr(), older.c[1].as_ptr(), older.c[2].as_ptr());
    for b in bars {
        // SAFETY: b is below the bar count, i, j below the node count (checked pass), i ≠ j.
        unsafe {
            let e = *ends.get_unchecked(b);
            let (i, j) = (e[0] as usize, e[1] as usize);
            let p = project(sx, sy, [&*ux.add(i), &*uy.add(i), &*uz.add(i)], [&*ux.add(j), &*uy.add(j), &*uz.add(j)]);
            let ks = *s.secant.add(b);
            let mut t = [0.0; L];
            for l in 0..L {
                t[l] = ks[l] * p[l];
            }
            if gated(&t, &p, *s.gate.add(b)) {
                let before = || {
                    project(sx, sy, [&*ox.add(i), &*oy.add(i), &*oz.add(i)], [&*ox.add(j), &*oy.add(j), &*oz.add(j)])
                };
                t = exact(b, p, t, before, s, out);
            }
            scatter_diagonal(f, i, j, sx, sy, &t);
        }
    }
}

/// The exact law for bar `b` in every lane: returns the law's force in place of `t` (the same
/// bits where nothing changes; `p` and `t` go by value so that the hot loop never takes their
/// address and keeps them in registers), updates the damage, adds the energy the bar dissipated in the step
/// (`before()` gives its elongation one level back) and logs its transitions.
///
/// # Safety
/// `b` is below the length of the damage arrays, and no other thread touches bar `b`.
#[cold]
#[inline(never)]
unsafe fn exact<const L: usize>(
    b: usize,
    p: Lanes<L>,
    mut t: Lanes<L>,
    before: impl Fn() -> Lanes<L>,
    s: Shared<L>,
    out: &mut SegmentOut<L>,
) -> Lanes<L> {
    // SAFETY: forwarded contract.
    let (k0, peak, secant, reach) =
        unsafe { (&*s.k0.add(b), &*s.peak.add(b), &mut *s.secant.add(b), &mut *s.reach.add(b)) };
    let mut older: Option<Lanes<L>> = None;
    let mut damaged = false;
    for l in 0..L {
        let ks_old = secant[l];
        let (force, ks, r) = law_step(k0[l], ks_old, reach[l], peak[l], s.kr, p[l]);
        t[l] = force;
        secant[l] = ks;
        reach[l] = r;
        damaged |= ks != k0[l];
        if ks_old == k0[l] && ks == k0[l] {
            continue;
        }
        // The stiffness the bar had at the last step and has now (undamaged in compression).
        let pb = older.get_or_insert_with(&before)[l];
        let k_then = if pb > 0.0 { ks_old } else { k0[l] };
        let k_now = if p[l] > 0.0 { ks } else { k0[l] };
        if k_then != k_now {
            out.dissipated[l] += 0.5 * (k_then - k_now) * pb * p[l];
        }
        if ks_old == k0[l] {
            out.cracks.push((b as u32, l as u8, CrackKind::Soften, p[l]));
        }
        if ks_old != 0.0 && ks == 0.0 {
            out.cracks.push((b as u32, l as u8, CrackKind::Break, p[l]));
        }
    }
    if damaged {
        // SAFETY: forwarded contract.
        unsafe { *s.gate.add(b) = f64::NEG_INFINITY };
    }
    t
}

/// `½ Σ_b k_b·p_b(a)·p_b(b)` for lane `l` with `k_b` the stiffness each bar has at `a`'s
/// elongation (secant in tension, undamaged in compression): the strain energy the rupture
/// kernel's ledger pairs with (see the module doc). The sums of
/// [`crate::step::energy::strain_energy`] with that stiffness, so the two agree bit for bit while
/// nothing is damaged.
pub fn strain_energy<const L: usize>(
    layout: &BarLayout,
    layers: &crate::ledger::EnergyLayers,
    k0: &[Lanes<L>],
    secant: &[Lanes<L>],
    a: &Field<L>,
    b: &Field<L>,
    l: usize,
) -> f64 {
    let sums =
        strain_energy_with(layout, layers, a, b, l, |bar, pa| if pa > 0.0 { secant[bar][l] } else { k0[bar][l] });
    0.5 * crate::ledger::total(&sums)
}

/// Elongation of every bar in kernel units for lane `l` (axial: `e·Δu`; diagonal: `s·Δu`, √3
/// times the elongation).
pub fn elongations<const L: usize>(layout: &BarLayout, u: &Field<L>, l: usize) -> Vec<f64> {
    let ends = layout.ends();
    let mut out = vec![0.0; ends.len()];
    for g in layout.groups() {
        for bar in g.start..g.end {
            out[bar] = elongation(g.direction, u, ends[bar][0] as usize, ends[bar][1] as usize, l);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rupture::{BarHistory, BarLaw};

    fn model(nx: usize, ny: usize, nz: usize) -> crate::model::Model {
        let scene =
            crate::scene::Scene { dims: crate::geometry::Dims::new(nx, ny, nz), ..crate::scene::Scene::paper() };
        crate::model::Model::with_listed_bars(scene)
    }

    /// A state with bars in every regime: displacements large enough that many bars pass their
    /// peak, some break, some are compressed; a history from an earlier, different state.
    fn random_case<const L: usize>(
        m: &crate::model::Model,
        seed: u64,
    ) -> (Vec<Lanes<L>>, RuptureParams<L>, RuptureState<L>, Field<L>, Field<L>) {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed);
        let k0: Vec<Lanes<L>> =
            m.nominal_stiffness().iter().map(|&v| std::array::from_fn(|_| v * rng.random_range(0.8..1.2))).collect();
        let peak: Vec<Lanes<L>> =
            (0..m.bar_count()).map(|_| std::array::from_fn(|_| 1e-6 * rng.random_range(0.5..1.5))).collect();
        let params = RuptureParams { peak, kr: 3.0 };
        let mut state = RuptureState::intact(&k0, &params);
        let field = |rng: &mut rand::rngs::ChaCha8Rng, amp: f64| {
            let mut u = Field::<L>::zeros(m.node_count());
            for c in 0..3 {
                for v in u.c[c].iter_mut() {
                    *v = std::array::from_fn(|_| rng.random_range(-amp..amp));
                }
            }
            u
        };
        // A history: apply the law once at an earlier state (some bars damaged, some broken).
        let earlier = field(&mut rng, 2e-6);
        for l in 0..L {
            for (b, p) in elongations(m.layout().listed(), &earlier, l).into_iter().enumerate() {
                let law = BarLaw { k: k0[b][l], peak: params.peak[b][l], kr: params.kr };
                let h = BarHistory { secant: state.secant[b][l], reach: state.reach[b][l] };
                let (_, h, _) = law.force(h, p);
                state.secant[b][l] = h.secant;
                state.reach[b][l] = h.reach;
                if h.secant != k0[b][l] {
                    state.gate[b] = f64::NEG_INFINITY;
                }
            }
        }
        (k0, params, state, field(&mut rng, 2e-6), field(&mut rng, 2e-6))
    }

    /// The kernel written plainly: every bar in kernel order, one lane at a time, the law of
    /// [`BarLaw::force`] for every bar, the ledger increment wherever the stiffness changes.
    fn reference<const L: usize>(
        m: &crate::model::Model,
        k0: &[Lanes<L>],
        params: &RuptureParams<L>,
        state: &mut RuptureState<L>,
        u: &Field<L>,
        older: &Field<L>,
    ) -> (Field<L>, [f64; L], Vec<(u32, usize, CrackKind)>) {
        let layout = m.layout().listed();
        let mut f = Field::<L>::zeros(layout.nodes());
        let mut dissipated = [0.0; L];
        let mut cracks = Vec::new();
        let ends = layout.ends();
        for l in 0..L {
            let (now, then) = (elongations(layout, u, l), elongations(layout, older, l));
            for g in layout.groups() {
                for b in g.start..g.end {
                    let law = BarLaw { k: k0[b][l], peak: params.peak[b][l], kr: params.kr };
                    let h = BarHistory { secant: state.secant[b][l], reach: state.reach[b][l] };
                    let (t, next, transition) = law.force(h, now[b]);
                    let k_then = if then[b] > 0.0 { h.secant } else { law.k };
                    let k_now = if now[b] > 0.0 { next.secant } else { law.k };
                    if k_then != k_now {
                        dissipated[l] += 0.5 * (k_then - k_now) * then[b] * now[b];
                    }
                    use crate::rupture::Transition as T;
                    if matches!(transition, T::Softened | T::SoftenedAndBroke) {
                        cracks.push((b as u32, l, CrackKind::Soften));
                    }
                    if matches!(transition, T::Broke | T::SoftenedAndBroke) {
                        cracks.push((b as u32, l, CrackKind::Break));
                    }
                    state.secant[b][l] = next.secant;
                    state.reach[b][l] = next.reach;
                    let (i, j) = (ends[b][0] as usize, ends[b][1] as usize);
                    match g.direction {
                        Direction::Axis(a) => {
                            f.c[a as usize][i][l] += t;
                            f.c[a as usize][j][l] -= t;
                        }
                        Direction::Diagonal { neg_x, neg_y } => {
                            let tc = [if neg_x { -t } else { t }, if neg_y { -t } else { t }, t];
                            for c in 0..3 {
                                f.c[c][i][l] += tc[c];
                                f.c[c][j][l] -= tc[c];
                            }
                        }
                    }
                }
            }
        }
        cracks.sort_by_key(|&(b, l, k)| (l, b, k));
        (f, dissipated, cracks)
    }

    /// The kernel's ledger, summed per segment in segment order, against the plain per-lane sum:
    /// equal to round-off (the order of additions differs).
    fn agrees<const L: usize>(m: &crate::model::Model, seed: u64) {
        let (k0, params, state0, u, older) = random_case::<L>(m, seed);
        let mut want_state = state0.clone();
        let (want, want_diss, want_cracks) = reference(m, &k0, &params, &mut want_state, &u, &older);
        assert!(want_cracks.len() > 10, "the case has transitions");
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
        for isa in Isa::available() {
            Isa::pinned(isa, || {
                for pass in 0..3 {
                    let mut state = state0.clone();
                    let mut f = Field::<L>::zeros(m.node_count());
                    let mut outs = Vec::new();
                    let p = Pass {
                        layout: m.layout().listed(),
                        k0: &k0,
                        params: &params,
                        state: &mut state,
                        u: &u,
                        older: &older,
                    };
                    match pass {
                        0 => forces(p, &mut f, &mut outs),
                        1 => forces_finishing(p, &mut f, &mut outs, |_, _| {}),
                        _ => pool.install(|| forces_parallel(p, &mut f, &mut outs)),
                    }
                    assert_eq!(f, want, "forces, pass {pass}, {isa:?}, {L} lanes");
                    assert_eq!(state.secant, want_state.secant, "secants, pass {pass}, {isa:?}");
                    assert_eq!(state.reach, want_state.reach, "reach, pass {pass}, {isa:?}");
                    let mut diss = [0.0; L];
                    fold(&outs, 7, &mut diss, &mut state);
                    for l in 0..L {
                        let scale = want_diss[l].abs().max(1e-30);
                        assert!(
                            (diss[l] - want_diss[l]).abs() <= 1e-12 * scale,
                            "ledger lane {l}: {} vs {}",
                            diss[l],
                            want_diss[l]
                        );
                    }
                    let mut cracks: Vec<(u32, usize, CrackKind)> =
                        (0..L).flat_map(|l| state.cracks[l].iter().map(move |c| (c.bar, l, c.kind))).collect();
                    cracks.sort_by_key(|&(b, l, k)| (l, b, k));
                    assert_eq!(cracks, want_cracks, "transitions, pass {pass}, {isa:?}");
                    for (b, s) in state.secant.iter().enumerate() {
                        if (0..L).any(|l| s[l] != k0[b][l]) {
                            assert_eq!(state.gate[b], f64::NEG_INFINITY, "a damaged bar is always gated");
                        }
                    }
                }
            });
        }
    }

    #[test]
    fn every_build_and_pass_of_the_rupture_kernel_agrees_with_the_plain_law() {
        for (nx, ny, nz) in [(10, 1, 5), (40, 20, 4), (40, 20, 10)] {
            let m = model(nx, ny, nz);
            agrees::<1>(&m, 1);
            agrees::<8>(&m, 2);
        }
    }

    #[test]
    fn a_lane_does_not_depend_on_its_neighbours() {
        // Lane 3 of a batch of 4 against the same seed alone: forces, damage, ledger and
        // transitions bit for bit, although other lanes open gates lane 3 alone would not.
        let m = model(10, 1, 5);
        let (k0, params, state, u, older) = random_case::<4>(&m, 9);
        let one = |x: &[Lanes<4>]| -> Vec<Lanes<1>> { x.iter().map(|v| [v[3]]).collect() };
        let field1 = |x: &Field<4>| Field::<1> { c: x.c.each_ref().map(|c| one(c)) };
        let params1 = RuptureParams { peak: one(&params.peak), kr: params.kr };
        let mut alone = RuptureState::<1>::intact(&one(&k0), &params1);
        alone.secant = one(&state.secant);
        alone.reach = one(&state.reach);
        for (b, s) in alone.secant.iter().enumerate() {
            if s[0] != k0[b][3] {
                alone.gate[b] = f64::NEG_INFINITY;
            }
        }
        let (k1, u1, o1) = (one(&k0), field1(&u), field1(&older));
        let mut batch = state.clone();
        let (mut f4, mut outs4) = (Field::<4>::zeros(m.node_count()), Vec::new());
        forces(
            Pass { layout: m.layout().listed(), k0: &k0, params: &params, state: &mut batch, u: &u, older: &older },
            &mut f4,
            &mut outs4,
        );
        let (mut f1, mut outs1) = (Field::<1>::zeros(m.node_count()), Vec::new());
        forces(
            Pass { layout: m.layout().listed(), k0: &k1, params: &params1, state: &mut alone, u: &u1, older: &o1 },
            &mut f1,
            &mut outs1,
        );
        assert_eq!(field1(&f4), f1);
        assert_eq!(one(&batch.secant), alone.secant);
        let (mut d4, mut d1) = ([0.0; 4], [0.0; 1]);
        fold(&outs4, 0, &mut d4, &mut batch);
        fold(&outs1, 0, &mut d1, &mut alone);
        assert_eq!(d4[3].to_bits(), d1[0].to_bits());
        assert_eq!(batch.cracks[3], alone.cracks[0]);
        assert!(!alone.cracks[0].is_empty());
    }

    #[test]
    fn while_nothing_is_damaged_the_rupture_kernel_gives_the_elastic_forces_bit_for_bit() {
        for (nx, ny, nz) in [(10, 1, 5), (40, 20, 4)] {
            let m = model(nx, ny, nz);
            let (k0, mut params, _, u, older) = random_case::<8>(&m, 4);
            // Peaks far above every elongation: every gate stays shut.
            params.peak.iter_mut().for_each(|p| *p = [1.0; 8]);
            let mut state = RuptureState::intact(&k0, &params);
            let mut want = Field::<8>::zeros(m.node_count());
            crate::step::bars::bar_forces(m.layout(), &k0, &u, &mut want);
            let mut f = Field::<8>::zeros(m.node_count());
            let mut outs = Vec::new();
            forces(
                Pass { layout: m.layout().listed(), k0: &k0, params: &params, state: &mut state, u: &u, older: &older },
                &mut f,
                &mut outs,
            );
            assert_eq!(f, want);
            for l in 0..8 {
                assert_eq!(
                    strain_energy(m.layout().listed(), &m.energy_layers(), &k0, &state.secant, &u, &older, l).to_bits(),
                    crate::step::energy::strain_energy(&m, &k0, &u, &older, l).to_bits()
                );
            }
            assert!(outs.iter().all(|o| o.cracks.is_empty() && o.dissipated.iter().all(|&d| d == 0.0)));
        }
    }
}
