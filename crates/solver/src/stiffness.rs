//! The bar stiffness a step reads, for `L` seeds side by side.
//!
//! A listed lattice stores each bar's kernel stiffness (N/m, diagonals `k/3`, see
//! [`crate::step::bars`]) as an `f64` per bar and lane. A stencil lattice stores only what varies
//! from seed to seed: each bar's Weibull factor of E as an `f32` per bar and lane, or nothing at
//! all when the scene is homogeneous (CV = 0); its nominal stiffness follows from its run
//! ([`RunStiffness`]). The kernels multiply the two in `f64` (`k = nominal · f64(factor)`), the
//! energy sums use the same product, so the energy balance closes as before; the field seen is the
//! Weibull field rounded to `f32` (6e-8 of each factor).

use crate::field::Lanes;
use crate::geometry::Direction;
use crate::layout::Bars;
use crate::stencil::{Run, RunStiffness};

/// One seed's bar stiffness as its run is set up ([`crate::Model::lane_stiffness`]).
#[derive(Clone, Debug, PartialEq)]
pub enum LaneStiffness {
    /// Kernel stiffness of every bar (N/m), kernel order.
    PerBar(Vec<f64>),
    /// A stencil lattice's Weibull factors of E, kernel order, as `f32`; `None`: homogeneous.
    Factored(Option<Vec<f32>>),
}

impl LaneStiffness {
    /// Bytes it holds.
    pub fn bytes(&self) -> usize {
        match self {
            LaneStiffness::PerBar(k) => 8 * k.len(),
            LaneStiffness::Factored(f) => f.as_ref().map_or(0, |f| 4 * f.len()),
        }
    }
}

/// The bar stiffness of `L` seeds side by side.
#[derive(Clone, Debug, PartialEq)]
pub enum Stiffness<const L: usize> {
    /// Kernel stiffness per bar and lane (N/m), kernel order.
    PerBar(Vec<Lanes<L>>),
    /// Weibull factor per bar and lane of a stencil lattice, or none (homogeneous).
    Factored(Option<Vec<[f32; L]>>),
}

impl<const L: usize> Stiffness<L> {
    /// The lanes' stiffness side by side (every lane of one kind).
    pub fn interleave(bars: usize, lanes: [&LaneStiffness; L]) -> Self {
        match lanes[0] {
            LaneStiffness::PerBar(_) => {
                let mut k = vec![[0.0; L]; bars];
                for (l, lane) in lanes.iter().enumerate() {
                    let LaneStiffness::PerBar(v) = lane else {
                        panic!("every lane of a batch has one kind of stiffness")
                    };
                    assert_eq!(v.len(), bars, "one stiffness per bar");
                    for (kb, &v) in k.iter_mut().zip(v) {
                        kb[l] = v;
                    }
                }
                Stiffness::PerBar(k)
            }
            LaneStiffness::Factored(None) => {
                assert!(
                    lanes.iter().all(|l| matches!(l, LaneStiffness::Factored(None))),
                    "every lane of a batch has one kind of stiffness"
                );
                Stiffness::Factored(None)
            }
            LaneStiffness::Factored(Some(_)) => {
                let mut k = vec![[0.0f32; L]; bars];
                for (l, lane) in lanes.iter().enumerate() {
                    let LaneStiffness::Factored(Some(v)) = lane else {
                        panic!("every lane of a batch has one kind of stiffness")
                    };
                    assert_eq!(v.len(), bars, "one factor per bar");
                    for (kb, &v) in k.iter_mut().zip(v) {
                        kb[l] = v;
                    }
                }
                Stiffness::Factored(Some(k))
            }
        }
    }

    /// What a kernel reads, with the runs' nominal stiffness `runs` (ignored per bar).
    pub fn view<'a>(&'a self, runs: &'a [RunStiffness]) -> StiffnessRef<'a, L> {
        match self {
            Stiffness::PerBar(k) => StiffnessRef::PerBar(k),
            Stiffness::Factored(f) => StiffnessRef::Factored { runs, factors: f.as_deref() },
        }
    }

    /// The per-bar stiffness; panics for a stencil's factors (callers are the kernels of listed
    /// lattices and of bars that crack, which are always listed).
    pub fn per_bar(&self) -> &[Lanes<L>] {
        match self {
            Stiffness::PerBar(k) => k,
            Stiffness::Factored(_) => panic!("a stencil lattice's stiffness is factored"),
        }
    }

    /// Bytes it holds.
    pub fn bytes(&self) -> usize {
        match self {
            Stiffness::PerBar(k) => std::mem::size_of_val(k.as_slice()),
            Stiffness::Factored(f) => f.as_ref().map_or(0, |f| std::mem::size_of_val(f.as_slice())),
        }
    }
}

/// The bar stiffness a kernel reads.
#[derive(Clone, Copy, Debug)]
pub enum StiffnessRef<'a, const L: usize> {
    /// Per bar and lane, kernel order.
    PerBar(&'a [Lanes<L>]),
    /// A stencil's runs: each bar's nominal stiffness from its run, times its factor per lane.
    Factored {
        /// Nominal stiffness of each run (order of the layout's runs).
        runs: &'a [RunStiffness],
        /// Factor per bar and lane, kernel order; `None`: all 1.
        factors: Option<&'a [[f32; L]]>,
    },
}

impl<'a, const L: usize> From<&'a [Lanes<L>]> for StiffnessRef<'a, L> {
    fn from(k: &'a [Lanes<L>]) -> Self {
        StiffnessRef::PerBar(k)
    }
}

impl<'a, const L: usize> From<&'a Vec<Lanes<L>>> for StiffnessRef<'a, L> {
    fn from(k: &'a Vec<Lanes<L>>) -> Self {
        StiffnessRef::PerBar(k)
    }
}

impl<const L: usize> StiffnessRef<'_, L> {
    /// Kernel stiffness of bar `m` of run `r` (the `index`-th run of the layout), lane `l`:
    /// `nominal · f64(factor)` for factored stiffness.
    #[inline]
    pub fn of_run_bar(&self, index: usize, r: &Run, m: usize, l: usize) -> f64 {
        match self {
            StiffnessRef::PerBar(k) => k[r.first_bar as usize + m][l],
            StiffnessRef::Factored { runs, factors } => {
                let nominal = runs[index].at(m, r.len as usize);
                match factors {
                    Some(f) => nominal * f64::from(f[r.first_bar as usize + m][l]),
                    None => nominal,
                }
            }
        }
    }

    /// Number of bars it covers (`None` for a homogeneous stencil, which stores none).
    pub fn bars(&self) -> Option<usize> {
        match self {
            StiffnessRef::PerBar(k) => Some(k.len()),
            StiffnessRef::Factored { factors, .. } => factors.map(|f| f.len()),
        }
    }

    /// Calls `visit(first end, second end, direction, k)` for every bar of `bars`, lane `l`.
    pub fn visit(&self, bars: &Bars, l: usize, mut visit: impl FnMut(usize, usize, Direction, f64)) {
        match (self, bars) {
            (StiffnessRef::PerBar(k), _) => bars.visit(|b, i, j, d| visit(i, j, d, k[b][l])),
            (StiffnessRef::Factored { .. }, Bars::Stencil(s)) => {
                for (index, r) in s.runs().iter().enumerate() {
                    let (lo, off) = (r.start as usize, r.offset as usize);
                    for m in 0..r.len as usize {
                        visit(lo + m, lo + m + off, r.direction, self.of_run_bar(index, r, m, l));
                    }
                }
            }
            (StiffnessRef::Factored { .. }, Bars::Listed(_)) => panic!("a listed lattice has per-bar stiffness"),
        }
    }

    /// Lane `l` of every bar, kernel order (N/m).
    pub fn lane(&self, bars: &Bars, l: usize) -> Vec<f64> {
        let mut k = Vec::with_capacity(bars.bar_count());
        self.visit(bars, l, |_, _, _, v| k.push(v));
        k
    }
}
