//! The bars of a large elastic lattice as a structured stencil: runs of bars along the rows of the
//! internal node order, whose ends follow from the run (no end list, no canonical index list).
//!
//! Internal node order (as [`crate::Model`] sorts it: by `z`, then `y`, then `x`): layer `k` is
//! corner layer `k` — rows `j = 0..=ny` of `nx + 1` corner nodes — then centre layer `k` — rows
//! `j = 0..ny` of `nx` centre nodes (none above the top corner layer). With `Cc = (nx+1)(ny+1)`
//! and `Cm = nx·ny`, corner `(i, j, k)` is node `k(Cc+Cm) + j(nx+1) + i` and centre `(i, j, k)` is
//! node `k(Cc+Cm) + Cc + j·nx + i`.
//!
//! Every bar joins a lower end to an upper end `offset` nodes further, and the bars of one
//! direction class whose lower ends lie along one row form a run of consecutive lower ends:
//! x, y and z edge bars from corner row `(j, k)`; from centre row `(j, k)` the x, y and z centre
//! bars, and the diagonals — four from the corners of rows `j` and `j + 1` down in the module's
//! layer to the centres (offset `Cc − j − dj(nx+1) − di`), four from the centres up to the corners
//! of layer `k + 1` (offset `Cm + j + dj(nx+1) + di`). Runs come layer by layer and, in a layer,
//! row by row, so a row's data is reused from cache by all its runs.
//!
//! A run's bar `m` is bar `canonical_start + m·canonical_stride` of the canonical order
//! ([`crate::geometry::Lattice::bar`]): stride 1 along axes, 8 for diagonals (one per module).
//!
//! **Slabs.** The layers are cut into slabs of at least two layers. A layer's bars write its own
//! nodes and the layer above's, so the bars of every layer but a slab's top one can run for all
//! slabs at once (phase 0), then the top layers' (phase 1, each writing two layers no other top
//! layer writes). The lattice's top layer (corners only, whose bars join nodes of that layer) is a
//! slab of its own when the layer count is odd, run in phase 0: the other layers then split
//! evenly, so two threads get the same work in each phase (21 layers in ten slabs of two and one
//! of three gave one thread six layers' bars in phase 0 and the other five). The partition
//! depends only on the block, so every thread count gives the same bits.

use std::ops::Range;

use rayon::prelude::*;

use crate::geometry::{Dims, Direction};
use crate::material::SeekableWeibull;

pub use crate::slabs::MAX_SLABS;

/// Bars of one direction class whose lower ends are `start..start + len`, upper ends `offset`
/// nodes further.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Run {
    /// Direction from lower to upper end.
    pub direction: Direction,
    /// First lower end (internal node).
    pub start: u32,
    /// Bars.
    pub len: u32,
    /// Upper end minus lower end.
    pub offset: u32,
    /// Kernel index of the first bar.
    pub first_bar: u32,
    /// Canonical index of the first bar.
    pub canonical_start: u32,
    /// Canonical index step from one bar of the run to the next.
    pub canonical_stride: u32,
}

impl Run {
    /// Kernel indices of its bars.
    pub fn bars(&self) -> Range<usize> {
        self.first_bar as usize..(self.first_bar + self.len) as usize
    }

    /// Canonical index of its bar `m`.
    pub fn canonical(&self, m: usize) -> usize {
        self.canonical_start as usize + m * self.canonical_stride as usize
    }
}

/// The nominal kernel stiffness of the bars of one run (N/m; diagonals stored `k/3`): the same
/// for every bar but the first and last, which an edge run along y or z has on the block's x
/// faces (their surface reduction, docs/model.md §1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunStiffness {
    /// Bar 0.
    pub first: f64,
    /// Bars `1..len − 1`.
    pub interior: f64,
    /// Bar `len − 1`.
    pub last: f64,
}

impl RunStiffness {
    /// The nominal stiffness of bar `m` of a run of `len` bars.
    #[inline]
    pub fn at(&self, m: usize, len: usize) -> f64 {
        if m == 0 {
            self.first
        } else if m + 1 == len {
            self.last
        } else {
            self.interior
        }
    }
}

/// The runs of a lattice, by layer, with its slabs.
#[derive(Clone, Debug, PartialEq)]
pub struct StencilLayout {
    runs: Vec<Run>,
    /// Runs of layer `k`: `runs[layer_runs[k]..layer_runs[k + 1]]`.
    layer_runs: Vec<usize>,
    /// Nodes of layer `k`: `layer_nodes[k]..layer_nodes[k + 1]`.
    layer_nodes: Vec<usize>,
    /// Layers of slab `s`: `slabs[s]..slabs[s + 1]`.
    slabs: Vec<usize>,
    bars: usize,
}

impl StencilLayout {
    /// The stencil of a block of `dims` modules.
    pub fn new(dims: Dims) -> StencilLayout {
        Self::build(dims, 0, dims.nz)
    }

    /// The stencil of the layers `lo..=hi` of a block of `dims` modules, for one rank of a
    /// decomposed scene ([`crate::split`]): nodes numbered from layer `lo`'s first, runs those of
    /// layers `lo..hi` (and of `hi` too when it is the block's top layer), each with its canonical
    /// index in the whole block, so that a seed's factors are those of the whole block. Below
    /// the top, layer `hi` holds its corners and centres (the halo above) and runs no bars. The
    /// slabs are the whole block's, cut at `lo` and `hi`, so each owned node receives its bars in
    /// the whole block's order; this needs `lo + 1` not to start a slab of the block
    /// ([`crate::slabs::bounds`]), which [`crate::split::Partition`] ensures by holding one
    /// more layer below where it would.
    pub fn window(dims: Dims, lo: usize, hi: usize) -> StencilLayout {
        assert!(lo < hi && hi <= dims.nz, "layers {lo}..={hi} of a block of {} layers", dims.nz + 1);
        assert!(
            lo == 0 || !crate::slabs::bounds(dims.nz + 1).contains(&(lo + 1)),
            "a window's first owned layer {} starts a slab of the block",
            lo + 1
        );
        Self::build(dims, lo, hi)
    }

    fn build(dims: Dims, lo: usize, hi: usize) -> StencilLayout {
        let Dims { nx, ny, nz } = dims;
        let (cc, cm) = ((nx + 1) * (ny + 1), nx * ny);
        let layer = |k: usize| (k - lo) * (cc + cm);
        let corner = |i: usize, j: usize, k: usize| layer(k) + j * (nx + 1) + i;
        let centre = |i: usize, j: usize, k: usize| layer(k) + cc + j * nx + i;
        // Canonical blocks: edges along x, y, z; diagonals; centre bars along x, y, z.
        let ex = nx * (ny + 1) * (nz + 1);
        let ey = (nx + 1) * ny * (nz + 1);
        let ez = (nx + 1) * (ny + 1) * nz;
        let diag = ex + ey + ez;
        let c0 = diag + 8 * nx * ny * nz;
        let cx = (nx - 1) * ny * nz;
        let cy = nx * (ny - 1) * nz;
        let mut runs = Vec::new();
        let mut layer_runs = vec![0];
        let mut bars = 0usize;
        let mut push =
            |runs: &mut Vec<Run>, direction, start: usize, len: usize, offset: usize, canon: usize, stride| {
                if len == 0 {
                    return;
                }
                runs.push(Run {
                    direction,
                    start: start as u32,
                    len: len as u32,
                    offset: offset as u32,
                    first_bar: bars as u32,
                    canonical_start: canon as u32,
                    canonical_stride: stride,
                });
                bars += len;
            };
        let (x, y, z) = (Direction::Axis(0), Direction::Axis(1), Direction::Axis(2));
        // Layer `hi` runs its bars only when it is the block's top layer.
        let ran = if hi == nz { hi + 1 } else { hi };
        for k in lo..=hi {
            for j in 0..=ny {
                if k >= ran {
                    break;
                }
                let c = corner(0, j, k);
                push(&mut runs, x, c, nx, 1, nx * (j + (ny + 1) * k), 1);
                if j < ny {
                    push(&mut runs, y, c, nx + 1, nx + 1, ex + (nx + 1) * (j + ny * k), 1);
                }
                if k < nz {
                    push(&mut runs, z, c, nx + 1, cc + cm, ex + ey + (nx + 1) * (j + (ny + 1) * k), 1);
                }
                if j == ny || k == nz {
                    continue;
                }
                let module0 = diag + 8 * nx * (j + ny * k);
                for (dj, di) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    let d = Direction::Diagonal { neg_x: di == 1, neg_y: dj == 1 };
                    push(
                        &mut runs,
                        d,
                        corner(di, j + dj, k),
                        nx,
                        cc - j - dj * (nx + 1) - di,
                        module0 + 2 * dj + di,
                        8,
                    );
                }
                let m = centre(0, j, k);
                push(&mut runs, x, m, nx - 1, 1, c0 + (nx - 1) * (j + ny * k), 1);
                if j + 1 < ny {
                    push(&mut runs, y, m, nx, nx, c0 + cx + nx * (j + (ny - 1) * k), 1);
                }
                if k + 1 < nz {
                    push(&mut runs, z, m, nx, cc + cm, c0 + cx + cy + nx * (j + ny * k), 1);
                }
                for (dj, di) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    let d = Direction::Diagonal { neg_x: di == 0, neg_y: dj == 0 };
                    push(&mut runs, d, m, nx, cm + j + dj * (nx + 1) + di, module0 + 4 + 2 * dj + di, 8);
                }
            }
            layer_runs.push(runs.len());
        }
        let top = if hi == nz { cc } else { cc + cm };
        let layer_nodes = (lo..=hi).map(layer).chain([layer(hi) + top]).collect();
        // The block's slabs, cut to the window.
        let layers = hi - lo + 1;
        let mut slabs = vec![0];
        slabs.extend(crate::slabs::bounds(nz + 1).into_iter().filter(|&b| lo < b && b <= hi).map(|b| b - lo));
        slabs.push(layers);
        StencilLayout { runs, layer_runs, layer_nodes, slabs, bars }
    }

    /// Every run, in kernel order.
    pub fn runs(&self) -> &[Run] {
        &self.runs
    }

    /// Number of bars.
    pub fn bars(&self) -> usize {
        self.bars
    }

    /// Number of nodes.
    pub fn nodes(&self) -> usize {
        *self.layer_nodes.last().expect("at least one layer")
    }

    /// Number of layers.
    pub fn layers(&self) -> usize {
        self.layer_nodes.len() - 1
    }

    /// The runs of layer `k`.
    pub fn layer_runs(&self, k: usize) -> &[Run] {
        &self.runs[self.layer_run_range(k)]
    }

    /// The indices of the runs of layer `k` (into [`StencilLayout::runs`]).
    pub fn layer_run_range(&self, k: usize) -> Range<usize> {
        self.layer_runs[k]..self.layer_runs[k + 1]
    }

    /// The nodes of layer `k` (internal indices).
    pub fn layer_nodes(&self, k: usize) -> Range<usize> {
        self.layer_nodes[k]..self.layer_nodes[k + 1]
    }

    /// The layers of each slab, bottom up.
    pub fn slabs(&self) -> impl Iterator<Item = Range<usize>> + '_ {
        self.slabs.windows(2).map(|w| w[0]..w[1])
    }

    /// The layers whose bars slab `slab` runs in `phase` (0 or 1): all but its top one in phase 0
    /// and the top one in phase 1, or, for the lattice's top layer alone (whose bars write only
    /// its own nodes), that layer in phase 0 and nothing in phase 1.
    pub fn phase_layers(&self, slab: &Range<usize>, phase: u8) -> Range<usize> {
        match (Self::top_alone(slab), phase) {
            (true, 0) => slab.clone(),
            (true, _) => slab.end..slab.end,
            (false, 0) => slab.start..slab.end - 1,
            (false, _) => slab.end - 1..slab.end,
        }
    }

    /// Whether `slab` is the lattice's top layer alone (the only slab of one layer).
    pub fn top_alone(slab: &Range<usize>) -> bool {
        slab.len() == 1
    }

    /// Longest run (bars).
    pub fn longest_run(&self) -> usize {
        self.runs.iter().map(|r| r.len as usize).max().unwrap_or(0)
    }

    /// Calls `visit(bar, lower end, upper end, direction)` for every bar in kernel order.
    pub fn visit(&self, mut visit: impl FnMut(usize, usize, usize, Direction)) {
        for r in &self.runs {
            let (lo, off) = (r.start as usize, r.offset as usize);
            for (m, b) in r.bars().enumerate() {
                visit(b, lo + m, lo + m + off, r.direction);
            }
        }
    }
}

/// Factor `c` of `draw` for every bar (kernel order) of canonical index `c`, rounded to `f32`,
/// layer by layer (on the current rayon pool with `parallel`). A layer's axial runs are stretches of consecutive
/// canonical indices; its diagonal runs of one row share the row's modules, whose `8·nx` factors
/// are drawn once and dealt to the eight runs.
pub fn draw_factors(layout: &StencilLayout, draw: &SeekableWeibull, parallel: bool) -> Vec<f32> {
    let mut out = vec![0.0f32; layout.bars()];
    // Split the output by layer (each layer's bars are consecutive in kernel order).
    let mut chunks = Vec::with_capacity(layout.layers());
    let mut rest = out.as_mut_slice();
    for k in 0..layout.layers() {
        let runs = layout.layer_runs(k);
        let n = runs.iter().map(|r| r.len as usize).sum::<usize>();
        let (chunk, tail) = rest.split_at_mut(n);
        chunks.push((runs, chunk));
        rest = tail;
    }
    let layer = |(runs, chunk): (&[Run], &mut [f32])| {
        let base = runs.first().map_or(0, |r| r.first_bar as usize);
        let mut buf = Vec::new();
        // The diagonal factors of the current row: canonical indices `row..row + row_buf.len()`.
        let (mut row, mut row_buf) = (u64::MAX, Vec::<f64>::new());
        for r in runs {
            let (cs, len) = (u64::from(r.canonical_start), r.len as usize);
            let dst = &mut chunk[r.first_bar as usize - base..][..len];
            if r.canonical_stride == 1 {
                buf.resize(len, 0.0);
                draw.fill(cs, &mut buf);
                for (d, &v) in dst.iter_mut().zip(&buf) {
                    *d = v as f32;
                }
            } else {
                let stride = u64::from(r.canonical_stride);
                if !(row <= cs && cs < row + stride && row_buf.len() == stride as usize * len) {
                    // The first diagonal run of a row starts at the row's first module.
                    row = cs;
                    row_buf.resize(stride as usize * len, 0.0);
                    draw.fill(row, &mut row_buf);
                }
                let offset = (cs - row) as usize;
                for (m, d) in dst.iter_mut().enumerate() {
                    *d = row_buf[offset + m * stride as usize] as f32;
                }
            }
        }
    };
    if parallel {
        chunks.into_par_iter().for_each(layer);
    } else {
        chunks.into_iter().for_each(layer);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use crate::scene::Scene;

    #[test]
    fn every_bar_once_with_the_ends_and_canonical_index_of_the_lattice() {
        for dims in
            [Dims::new(10, 1, 5), Dims::new(3, 2, 4), Dims::new(1, 1, 1), Dims::new(1, 4, 2), Dims::new(5, 3, 1)]
        {
            let model = Model::new(Scene::paper().sample(dims));
            let lattice = model.lattice();
            let s = StencilLayout::new(dims);
            assert_eq!(s.bars(), dims.bar_count(), "{dims:?}");
            assert_eq!(s.nodes(), dims.node_count(), "{dims:?}");
            let mut seen = vec![false; s.bars()];
            let mut next = 0;
            for r in s.runs() {
                assert_eq!(r.first_bar as usize, next, "{dims:?}: runs are consecutive in kernel order");
                next += r.len as usize;
                for m in 0..r.len as usize {
                    let c = r.canonical(m);
                    assert!(!seen[c], "{dims:?}: canonical bar {c} twice");
                    seen[c] = true;
                    let bar = lattice.bar(c);
                    let (lo, hi) = (r.start as usize + m, (r.start + r.offset) as usize + m);
                    assert_eq!(
                        [lo, hi],
                        bar.ends.map(|id| model.internal(id)),
                        "{dims:?}: run {r:?} bar {m} is canonical bar {c} {bar:?}"
                    );
                    assert_eq!(r.direction, bar.direction, "{dims:?}");
                }
            }
            assert!(seen.iter().all(|&s| s), "{dims:?}: every bar");
            // The factors drawn run by run are the canonical draws, and the runs' nominal
            // stiffness is every bar's.
            let draws = crate::material::weibull_factors(0.05, 7, 0, s.bars()).unwrap().unwrap();
            let seek = SeekableWeibull::new(0.05, 7, 0).unwrap();
            let factors = draw_factors(&s, &seek, true);
            assert_eq!(factors, draw_factors(&s, &seek, false), "{dims:?}: serial and parallel draws");
            let nominal = Model::with_listed_bars(model.scene().clone());
            let stencil_model = Model::with_stencil(model.scene().clone());
            let listed_k: Vec<f64> = {
                let k = nominal.nominal_stiffness();
                let mut by_canonical = vec![0.0; k.len()];
                for (b, &c) in nominal.bar_canonical().iter().enumerate() {
                    by_canonical[c as usize] = k[b];
                }
                by_canonical
            };
            for (index, r) in s.runs().iter().enumerate() {
                for m in 0..r.len as usize {
                    let c = r.canonical(m);
                    assert_eq!(factors[r.first_bar as usize + m], draws[c] as f32, "{dims:?}: bar {c}");
                    let rs = stencil_model.run_stiffness();
                    assert_eq!(rs[index].at(m, r.len as usize), listed_k[c], "{dims:?}: nominal of bar {c}");
                }
            }
            // Layers hold consecutive nodes; slabs at least two layers each, but the top layer
            // alone when the layer count is odd (five or more).
            assert_eq!(s.layer_nodes(0).start, 0);
            assert_eq!(s.layer_nodes(s.layers() - 1).end, s.nodes());
            let slabs: Vec<_> = s.slabs().collect();
            let top_alone = s.layers() % 2 == 1 && s.layers() >= 5;
            assert_eq!(slabs.last().map(|sl| sl.len() == 1), Some(top_alone), "{dims:?}: {slabs:?}");
            assert!(slabs[..slabs.len() - usize::from(top_alone)].iter().all(|sl| sl.len() >= 2));
            // A layer's bars start in it and end in it or the next.
            for k in 0..s.layers() {
                for r in s.layer_runs(k) {
                    let (lo, hi) = (r.start as usize, (r.start + r.offset + r.len - 1) as usize);
                    assert!(s.layer_nodes(k).contains(&lo), "{dims:?}: layer {k} run {r:?}");
                    let upper = s.layer_nodes(k).start..s.layer_nodes((k + 1).min(s.layers() - 1)).end;
                    assert!(upper.contains(&hi), "{dims:?}: layer {k} run {r:?} ends beyond the next layer");
                }
            }
        }
    }
}
