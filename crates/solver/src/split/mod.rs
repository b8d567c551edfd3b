//! One scene split over ranks (domain decomposition, docs/model.md §19): each rank owns a slab
//! of module layers along z and steps it with the same kernels as a single process, holding one
//! layer of its neighbours' nodes (the halo) that is exchanged after every step.
//!
//! **Why z.** The internal node order is by z, then y, then x ([`crate::Model`]), so a slab of
//! layers is one range of every node array and of the stencil's runs: a rank's model is the
//! whole block's cut to a window ([`crate::Model::window`]), and a halo is one contiguous copy.
//! The slab's face is `nx·ny` modules, larger than a cut along the longest axis would give on a
//! long block; the exchange's share of a step is measured in docs/guide/benchmarks.md.
//!
//! **The same bits.** A rank owning layers `k0..k1` holds layers `k0 − 1 ..= k1`: layer `k0 − 1`
//! (below, with its bars, which write layer `k0`) and layer `k1` (above, read by the bars of
//! `k1 − 1`, running none). Its stencil runs the whole block's runs of those layers in the whole
//! block's slab and phase order ([`crate::stencil::StencilLayout::window`]), so each owned node
//! receives the same contributions in the same order as on one process, and is integrated by
//! the same arithmetic. Where `k0` starts a slab of the block, layer `k0 − 1` is a slab's top,
//! whose bars run after the rest of its slab (the second phase): the rank then holds layer
//! `k0 − 2` too, so that `k0 − 1` is the top of a slab of its window as well. Halo nodes are
//! integrated too, from incomplete forces, and overwritten by the exchange before anything reads
//! them. Boundary conditions act on owned nodes only; the base (contact, a fault) is rank 0's.
//!
//! **The exchange.** After each step a rank sends its top owned layer (or two) up and its bottom
//! owned layer down (the newest displacement level, three components, every lane), and receives its two
//! halo layers ([`Neighbours`]). The older levels of a halo node are the newest of earlier
//! exchanges, so one level per step is enough.

mod threads;

use std::ops::Range;

use crate::field::Field;
use crate::geometry::Dims;

pub use threads::{ThreadRanks, thread_ranks};

/// The module layers each rank owns, bottom up.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Partition {
    dims: Dims,
    /// Rank `r` owns module layers `starts[r]..starts[r + 1]` (the last also the block's top
    /// corner layer).
    starts: Vec<usize>,
}

/// Why a block cannot be split over a number of ranks.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PartitionError {
    /// The ranks asked for.
    pub ranks: usize,
    /// The most the block takes.
    pub most: usize,
    /// The fewest module layers a rank owns.
    pub least_layers: usize,
}

impl std::fmt::Display for PartitionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} ranks: a block is split into slabs of at least {} along z, so this one takes 1 to {} ranks",
            self.ranks,
            if self.least_layers == 1 { "one module layer" } else { "two module layers" },
            self.most
        )
    }
}

impl std::error::Error for PartitionError {}

impl Partition {
    /// Splits the block's `nz` module layers evenly, every rank at least two layers (one for a
    /// block whose bars are listed, below [`crate::slabs::STENCIL_MIN_BARS`]).
    pub fn new(dims: Dims, ranks: usize) -> Result<Partition, PartitionError> {
        match Self::cuts(dims, ranks) {
            Some(starts) => Ok(Partition { dims, starts }),
            None => Err(PartitionError { ranks, most: Self::most(dims), least_layers: Self::least_layers(dims) }),
        }
    }

    /// The most ranks `dims` can be split over.
    pub fn most(dims: Dims) -> usize {
        let least = Self::least_layers(dims);
        (1..=(dims.nz / least).max(1)).rev().find(|&r| Self::cuts(dims, r).is_some()).unwrap_or(1)
    }

    /// Whether the block's bars are listed (not a stencil) on one process, so on each rank.
    fn listed(dims: Dims) -> bool {
        dims.bar_count() < crate::slabs::STENCIL_MIN_BARS
    }

    /// The fewest module layers a rank owns: two on a stencil, whose halo below can be two layers
    /// deep and is sent by the rank below; one when the bars are listed (a halo of one layer).
    fn least_layers(dims: Dims) -> usize {
        if Self::listed(dims) { 1 } else { 2 }
    }

    fn cuts(dims: Dims, ranks: usize) -> Option<Vec<usize>> {
        let (nz, least) = (dims.nz, Self::least_layers(dims));
        if ranks == 0 || (ranks > 1 && ranks > nz / least) {
            return None;
        }
        let mut starts: Vec<usize> = (0..ranks).map(|r| (r * nz + ranks / 2) / ranks).collect();
        starts.push(nz);
        starts.windows(2).all(|w| w[1] >= w[0] + least || ranks == 1).then_some(starts)
    }

    /// Module layers of the halo below rank `r`: one, or two where its first layer starts a slab
    /// of the block's stencil (the layer below is then a slab's top, which runs after the slab's
    /// other layers: with the layer under it the window runs it in the same phase as the block).
    /// Listed bars have no slabs: one.
    fn halo_layers(&self, r: usize) -> usize {
        match r {
            0 => 0,
            _ if Self::listed(self.dims) => 1,
            _ if crate::slabs::bounds(self.dims.nz + 1).contains(&self.starts[r]) => 2,
            _ => 1,
        }
    }

    /// Number of ranks.
    pub fn ranks(&self) -> usize {
        self.starts.len() - 1
    }

    /// The block.
    pub fn dims(&self) -> Dims {
        self.dims
    }

    /// The module layers rank `r` owns.
    pub fn owned_layers(&self, r: usize) -> Range<usize> {
        self.starts[r]..self.starts[r + 1]
    }

    /// Rank `r`'s window.
    pub fn window(&self, r: usize) -> Window {
        let Dims { nx, ny, nz } = self.dims;
        let owned = self.owned_layers(r);
        let lo = owned.start - self.halo_layers(r);
        let hi = owned.end;
        let layer = (nx + 1) * (ny + 1) + nx * ny;
        let top = if hi == nz { (nx + 1) * (ny + 1) } else { layer };
        let nodes = (hi - lo) * layer + top;
        let own_start = (owned.start - lo) * layer;
        let own_end = if hi == nz { nodes } else { (hi - lo) * layer };
        let sent_up = if r + 1 < self.ranks() { self.halo_layers(r + 1) * layer } else { 0 };
        Window {
            rank: r,
            ranks: self.ranks(),
            lo,
            hi,
            first_node: lo * layer,
            nodes,
            owned: own_start..own_end,
            layer,
            sent_up,
        }
    }
}

/// The part of the block one rank holds: module layers `lo..=hi` (its own and the halo layers on
/// each side that has a neighbour: one above, one or two below).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Window {
    /// This rank.
    pub rank: usize,
    /// Every rank.
    pub ranks: usize,
    /// First layer held (the halo below, or 0).
    pub lo: usize,
    /// Last layer held (the halo above, or the block's top corner layer).
    pub hi: usize,
    /// The block's internal index of the window's first node.
    pub first_node: usize,
    /// Nodes held.
    pub nodes: usize,
    /// The nodes this rank owns (window indices).
    pub owned: Range<usize>,
    /// Nodes of one module layer (corners and centres).
    layer: usize,
    /// Nodes of the halo below the rank above (one or two module layers), which this rank sends.
    sent_up: usize,
}

impl Window {
    /// The halo below (window indices), which the rank below sends; empty on rank 0.
    pub fn halo_below(&self) -> Range<usize> {
        0..self.owned.start
    }

    /// The halo above, which the rank above sends; empty on the top rank.
    pub fn halo_above(&self) -> Range<usize> {
        self.owned.end..self.nodes
    }

    /// What this rank sends down: its first owned layer (the halo above of the rank below).
    pub fn send_below(&self) -> Range<usize> {
        if self.rank == 0 { 0..0 } else { self.owned.start..self.owned.start + self.layer }
    }

    /// What this rank sends up: its last owned layer, or two (the halo below of the rank above).
    pub fn send_above(&self) -> Range<usize> {
        if self.rank + 1 == self.ranks { 0..0 } else { self.owned.end - self.sent_up..self.owned.end }
    }

    /// The block's internal index of window node `i`.
    pub fn global(&self, i: usize) -> usize {
        self.first_node + i
    }

    /// The window index of the block's internal node `g`, if the window holds it.
    pub fn local(&self, g: usize) -> Option<usize> {
        g.checked_sub(self.first_node).filter(|&i| i < self.nodes)
    }

    /// Whether this rank owns the block's internal node `g`.
    pub fn owns(&self, g: usize) -> bool {
        self.local(g).is_some_and(|i| self.owned.contains(&i))
    }
}

/// How the ranks of a split scene talk: each step's halo layers with the neighbours, and the few
/// numbers the run loop gathers to rank 0 or hands out from it ([`crate::run::run_split`]). Every
/// rank makes the same calls in the same order.
pub trait Neighbours {
    /// This rank.
    fn rank(&self) -> usize;
    /// Every rank.
    fn size(&self) -> usize;
    /// Trades one step's halo layers: `send_down`/`send_up` are this rank's layers (empty where
    /// there is no neighbour), `from_below`/`from_above` are filled with the neighbours' (same
    /// lengths as the layers they send).
    fn swap(&mut self, send_down: &[f64], send_up: &[f64], from_below: &mut [f64], from_above: &mut [f64]);
    /// Rank 0 gets every rank's `mine` in rank order (its own first); the others get nothing.
    fn gather(&mut self, mine: &[f64]) -> Vec<Vec<f64>>;
    /// Every rank gets rank 0's `data` (same length on every rank).
    fn broadcast(&mut self, data: &mut [f64]);
}

/// Buffers of one rank's exchange, reused from step to step.
#[derive(Debug, Default)]
pub struct Halo {
    send_down: Vec<f64>,
    send_up: Vec<f64>,
    from_below: Vec<f64>,
    from_above: Vec<f64>,
}

impl Halo {
    /// Trades the halo layers of `u` (a rank's newest displacement level) with the neighbours.
    pub fn exchange<const L: usize>(&mut self, window: &Window, u: &mut Field<L>, with: &mut dyn Neighbours) {
        pack(u, window.send_below(), &mut self.send_down);
        pack(u, window.send_above(), &mut self.send_up);
        self.from_below.resize(3 * L * window.halo_below().len(), 0.0);
        self.from_above.resize(3 * L * window.halo_above().len(), 0.0);
        with.swap(&self.send_down, &self.send_up, &mut self.from_below, &mut self.from_above);
        unpack(&self.from_below, window.halo_below(), u);
        unpack(&self.from_above, window.halo_above(), u);
    }
}

/// Copies nodes `r` of `u` into `out`, component by component.
fn pack<const L: usize>(u: &Field<L>, r: Range<usize>, out: &mut Vec<f64>) {
    out.clear();
    for c in 0..3 {
        out.extend_from_slice(u.c[c][r.clone()].as_flattened());
    }
}

/// The inverse of [`pack`].
fn unpack<const L: usize>(data: &[f64], r: Range<usize>, u: &mut Field<L>) {
    let n = r.len() * L;
    for c in 0..3 {
        u.c[c][r.clone()].as_flattened_mut().copy_from_slice(&data[c * n..(c + 1) * n]);
    }
}

/// One sum in the flat order of every rank's `terms` (`parts` equal parts one after another, e.g.
/// the three components, each over the rank's owned nodes in order), from `start`: each rank adds
/// its terms of a part on to the sum so far, handed from rank to rank, part by part. The same bits
/// as one process's single sum over the whole block's terms; every rank gets it.
pub(crate) fn handed_sum(ranks: &mut dyn Neighbours, start: f64, terms: &[f64], parts: usize) -> f64 {
    let m = terms.len() / parts;
    let mut sum = [start];
    for part in 0..parts {
        for r in 0..ranks.size() {
            ranks.broadcast(&mut sum);
            let mine: Vec<f64> = if ranks.rank() == r {
                vec![terms[part * m..(part + 1) * m].iter().fold(sum[0], |s, t| s + t)]
            } else {
                Vec::new()
            };
            let all = ranks.gather(&mine);
            if ranks.rank() == 0 {
                sum[0] = all[r][0];
            }
        }
    }
    ranks.broadcast(&mut sum);
    sum[0]
}
