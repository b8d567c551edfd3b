//! The bars in the order the kernels run them ([`Bars`]): a list of bars with their ends
//! ([`BarLayout`]: segments of a large lattice that can run on several threads, direction groups,
//! and which nodes each group finishes), or, for a large elastic lattice, a structured stencil
//! whose ends follow from its runs ([`crate::stencil::StencilLayout`]).
//!
//! Built once per model ([`crate::Model`]): bars are grouped by direction class (three axes, four
//! body diagonals) so each group runs one monomorphised kernel; a large lattice is cut into
//! z-slabs whose segments of one phase touch disjoint nodes, so they can run on several threads
//! and still give the serial numbers bit for bit.

use std::ops::Range;

use crate::geometry::Direction;
use crate::stencil::StencilLayout;

/// The bars of a model in kernel order, listed or as a stencil.
#[derive(Clone, Debug, PartialEq)]
pub enum Bars {
    /// Every bar with its ends (small lattices, bars that crack).
    Listed(BarLayout),
    /// Runs of a structured stencil (large elastic lattices).
    Stencil(StencilLayout),
}

impl Bars {
    /// Number of bars.
    pub fn bar_count(&self) -> usize {
        match self {
            Bars::Listed(l) => l.ends().len(),
            Bars::Stencil(s) => s.bars(),
        }
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        match self {
            Bars::Listed(l) => l.nodes(),
            Bars::Stencil(s) => s.nodes(),
        }
    }

    /// The listed layout; panics for a stencil (callers that need ends are the kernels of bars
    /// that crack, which are always listed).
    pub fn listed(&self) -> &BarLayout {
        match self {
            Bars::Listed(l) => l,
            Bars::Stencil(_) => panic!("a stencil lattice has no bar list"),
        }
    }

    /// Whether a step can be split over several threads (a large lattice).
    pub fn splits(&self) -> bool {
        match self {
            Bars::Listed(l) => l.segments().len() > 1,
            Bars::Stencil(s) => s.slabs().count() > 1,
        }
    }

    /// Calls `visit(bar, first end, second end, direction)` for every bar in kernel order, the
    /// direction being from the first end to the second.
    pub fn visit(&self, mut visit: impl FnMut(usize, usize, usize, Direction)) {
        match self {
            Bars::Listed(l) => {
                for g in l.groups() {
                    for (b, e) in l.ends()[g.start..g.end].iter().enumerate() {
                        visit(g.start + b, e[0] as usize, e[1] as usize, g.direction);
                    }
                }
            }
            Bars::Stencil(s) => s.visit(visit),
        }
    }
}

/// A run of bars sharing one direction class, `bars[start..end]` in kernel order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BarGroup {
    /// Direction class.
    pub direction: Direction,
    /// First bar.
    pub start: usize,
    /// One past the last bar.
    pub end: usize,
}

/// A set of bars whose end nodes no other segment of the same phase touches.
#[derive(Clone, Debug, PartialEq)]
pub struct Segment {
    /// Segments of phase 0 run together, then those of phase 1, then phase 2.
    pub phase: u8,
    /// Its direction groups.
    pub groups: Vec<BarGroup>,
}

/// The bars in kernel order, checked once: every end is a node below `nodes`, every group is
/// inside the bar list, and segments of one phase touch disjoint nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct BarLayout {
    segments: Vec<Segment>,
    ends: Vec<[u32; 2]>,
    nodes: usize,
    /// Runs of nodes whose last bar is in group `g` (serial order) are
    /// `finished[finished_at[g]..finished_at[g + 1]]`; the extra last slot holds the nodes no bar
    /// touches.
    finished: Vec<Range<usize>>,
    finished_at: Vec<usize>,
}

impl BarLayout {
    /// Builds and checks a layout. Panics on an end or group out of range, or on two segments of
    /// one phase sharing a node (a programming error, not an input error).
    pub fn new(segments: Vec<Segment>, ends: Vec<[u32; 2]>, nodes: usize) -> Self {
        assert!(ends.iter().all(|e| (e[0] as usize) < nodes && (e[1] as usize) < nodes), "bar end out of range");
        for s in &segments {
            assert!(s.groups.iter().all(|g| g.start <= g.end && g.end <= ends.len()), "group out of range");
        }
        for phase in 0..3u8 {
            let mut owner = vec![usize::MAX; nodes];
            for (k, s) in segments.iter().enumerate().filter(|(_, s)| s.phase == phase) {
                for g in &s.groups {
                    for e in &ends[g.start..g.end] {
                        for &n in e {
                            let o = &mut owner[n as usize];
                            assert!(
                                *o == usize::MAX || *o == k,
                                "segments {k} and {o} of phase {phase} share node {n}"
                            );
                            *o = k;
                        }
                    }
                }
            }
        }
        let (finished, finished_at) = finishing_order(&segments, &ends, nodes);
        BarLayout { segments, ends, nodes, finished, finished_at }
    }

    /// Runs of nodes whose forces are complete once group `slot` (serial order over every
    /// segment) has run; slot `groups().count()` holds the nodes no bar touches.
    pub fn finished_after(&self, slot: usize) -> &[Range<usize>] {
        &self.finished[self.finished_at[slot]..self.finished_at[slot + 1]]
    }

    /// Segments in serial order.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Bar end nodes (internal indices), kernel order.
    pub fn ends(&self) -> &[[u32; 2]] {
        &self.ends
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        self.nodes
    }

    /// Every group of every segment, in serial order.
    pub fn groups(&self) -> impl Iterator<Item = &BarGroup> {
        self.segments.iter().flat_map(|s| s.groups.iter())
    }
}

/// For every group in serial order (and one slot after them for untouched nodes), the runs of
/// nodes whose last bar is in that group, in increasing node order.
fn finishing_order(segments: &[Segment], ends: &[[u32; 2]], nodes: usize) -> (Vec<Range<usize>>, Vec<usize>) {
    let groups: Vec<&BarGroup> = segments.iter().flat_map(|s| s.groups.iter()).collect();
    let mut last = vec![groups.len(); nodes];
    for (slot, g) in groups.iter().enumerate() {
        for e in &ends[g.start..g.end] {
            for &n in e {
                last[n as usize] = slot;
            }
        }
    }
    let mut by_slot: Vec<Vec<Range<usize>>> = vec![Vec::new(); groups.len() + 1];
    for (n, &slot) in last.iter().enumerate() {
        let runs = &mut by_slot[slot];
        match runs.last_mut() {
            Some(r) if r.end == n => r.end = n + 1,
            _ => runs.push(n..n + 1),
        }
    }
    let mut finished_at = vec![0];
    let mut finished = Vec::new();
    for runs in by_slot {
        finished.extend(runs);
        finished_at.push(finished.len());
    }
    (finished, finished_at)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    #[should_panic(expected = "share node")]
    fn a_layout_with_overlapping_segments_is_refused() {
        let g = |s, e| BarGroup { direction: Direction::Axis(0), start: s, end: e };
        let _ = BarLayout::new(
            vec![Segment { phase: 0, groups: vec![g(0, 1)] }, Segment { phase: 0, groups: vec![g(1, 2)] }],
            vec![[0, 1], [1, 2]],
            3,
        );
    }
}
