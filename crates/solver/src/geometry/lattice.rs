//! The LDEM cubic-truss lattice (Nayfeh & Hefzy): nodes, bars, boundary reductions, mass fractions.
//!
//! Pure geometry and topology: no material, no state. Node and bar orders here are the *canonical*
//! ones (the paper's LDEM numbering for nodes, a documented order for bars); the stepper may keep
//! its own internal order for speed and translates back.
//!
//! Canonical node order: the `(nx+1)(ny+1)(nz+1)` corner-lattice nodes first, `x` fastest, then
//! `y`, then `z`; then the `nx·ny·nz` centre nodes in module order (`x` fastest, then `y`, then
//! `z`). The LDEM number of a node is its canonical index plus one.
//!
//! Canonical bar order (the order in which the random field is drawn): edge bars along `x`, then
//! along `y`, then along `z` (each in corner order of their lower end); then the 8 diagonals of
//! each module (module order; corners with `x` fastest); then centre bars along `x`, `y`, `z`
//! (each in module order of their lower end).

use std::fmt;

/// Index of a node in the canonical order (0-based; LDEM number minus one).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, bincode::Encode, bincode::Decode)]
pub struct NodeId(pub u32);

impl NodeId {
    /// The index as `usize`.
    #[inline]
    pub fn index(self) -> usize {
        self.0 as usize
    }

    /// The paper's 1-based LDEM number of this node.
    pub fn ldem(self) -> u64 {
        u64::from(self.0) + 1
    }
}

impl fmt::Display for NodeId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "node {}", self.ldem())
    }
}

/// Number of modules along each axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dims {
    /// Modules along `x` (slip direction).
    pub nx: usize,
    /// Modules along `y` (width).
    pub ny: usize,
    /// Modules along `z` (height).
    pub nz: usize,
}

impl Dims {
    /// New dimensions (every count must be at least 1).
    pub fn new(nx: usize, ny: usize, nz: usize) -> Self {
        assert!(nx >= 1 && ny >= 1 && nz >= 1, "a lattice needs at least one module per axis");
        Dims { nx, ny, nz }
    }

    /// Number of modules.
    pub fn modules(&self) -> usize {
        self.nx * self.ny * self.nz
    }

    /// Number of corner-lattice nodes `(nx+1)(ny+1)(nz+1)`.
    pub fn corner_nodes(&self) -> usize {
        (self.nx + 1) * (self.ny + 1) * (self.nz + 1)
    }

    /// Closed-form node count: corner nodes plus one centre node per module.
    pub fn node_count(&self) -> usize {
        self.corner_nodes() + self.modules()
    }

    /// Closed-form bar count: edge bars, 8 diagonals per module and centre bars.
    pub fn bar_count(&self) -> usize {
        let Dims { nx, ny, nz } = *self;
        let edges = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
        let centre = (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1);
        edges + 8 * self.modules() + centre
    }

    /// Number of modules along axis `a` (0 = x, 1 = y, 2 = z).
    pub fn along(&self, a: usize) -> usize {
        [self.nx, self.ny, self.nz][a]
    }
}

/// What a node is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeKind {
    /// Corner-lattice node at `(i, j, k)·Lc`.
    Corner([usize; 3]),
    /// Centre node of module `(i, j, k)`, at `(i+½, j+½, k+½)·Lc`.
    Centre([usize; 3]),
}

/// The three bar families of the cubic module.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BarFamily {
    /// Between adjacent corner-lattice nodes, length `Lc`.
    Edge,
    /// From a centre node to a corner of its module, length `Lc·√3/2`.
    Diagonal,
    /// Between centre nodes of face-adjacent modules, length `Lc`.
    Centre,
}

impl BarFamily {
    /// `"edge"`, `"diagonal"` or `"centre"`.
    pub fn name(self) -> &'static str {
        match self {
            BarFamily::Edge => "edge",
            BarFamily::Diagonal => "diagonal",
            BarFamily::Centre => "centre",
        }
    }
}

/// Direction class of a bar: every bar of the regular lattice lies along one of seven lines.
///
/// Bars are oriented so that the direction from `ends[0]` to `ends[1]` is `+axis` for axial bars
/// and has a positive `z` component for diagonals.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Direction {
    /// Along axis 0, 1 or 2 (unit vector `e_a`).
    Axis(u8),
    /// Body diagonal `(sx, sy, 1)/√3` with `sx, sy = ±1` (`true` = negative).
    Diagonal {
        /// `x` component negative.
        neg_x: bool,
        /// `y` component negative.
        neg_y: bool,
    },
}

impl Direction {
    /// `"x"`, `"y"`, `"z"` for axial bars; `"+x+y+z"`, `"-x+y+z"`, `"+x-y+z"`, `"-x-y+z"` for
    /// the body diagonals (the direction from a bar's first end to its second).
    pub fn name(self) -> &'static str {
        match self {
            Direction::Axis(0) => "x",
            Direction::Axis(1) => "y",
            Direction::Axis(_) => "z",
            Direction::Diagonal { neg_x: false, neg_y: false } => "+x+y+z",
            Direction::Diagonal { neg_x: true, neg_y: false } => "-x+y+z",
            Direction::Diagonal { neg_x: false, neg_y: true } => "+x-y+z",
            Direction::Diagonal { neg_x: true, neg_y: true } => "-x-y+z",
        }
    }

    /// The unit vector.
    pub fn unit(self) -> [f64; 3] {
        match self {
            Direction::Axis(a) => {
                let mut e = [0.0; 3];
                e[a as usize] = 1.0;
                e
            }
            Direction::Diagonal { neg_x, neg_y } => {
                let s = 1.0 / 3f64.sqrt();
                [if neg_x { -s } else { s }, if neg_y { -s } else { s }, s]
            }
        }
    }
}

/// One bar of the lattice.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bar {
    /// End nodes, oriented along [`Direction`].
    pub ends: [NodeId; 2],
    /// Family.
    pub family: BarFamily,
    /// Direction class from `ends[0]` to `ends[1]`.
    pub direction: Direction,
    /// Surface reduction of the axial stiffness: 1 inside, 0.5 for an edge bar lying in one
    /// outer face, 0.25 for one lying on an outer edge of the block (docs/model.md §1).
    pub surface_factor: f64,
}

impl Bar {
    /// Rest length in units of `Lc` (1 or √3/2).
    pub fn length_factor(&self) -> f64 {
        match self.family {
            BarFamily::Diagonal => 3f64.sqrt() / 2.0,
            BarFamily::Edge | BarFamily::Centre => 1.0,
        }
    }
}

/// The lattice of a block of `nx × ny × nz` cubic modules of side `Lc`.
///
/// Nothing per node or per bar is stored: a node's kind and a bar's ends, family, direction and
/// surface reduction follow from its canonical index ([`Lattice::kind`], [`Lattice::bar`]), so a
/// lattice of any size costs a few words.
#[derive(Clone, Debug)]
pub struct Lattice {
    dims: Dims,
    lc: f64,
}

/// A block of the canonical bar order: `count` bars indexed `i` fastest over `extent[0]`, then
/// `j` over `extent[1]`, then `k` over `extent[2]`.
#[derive(Clone, Copy)]
struct BarRun {
    extent: [usize; 3],
}

impl BarRun {
    fn count(&self) -> usize {
        self.extent[0] * self.extent[1] * self.extent[2]
    }

    fn cell(&self, r: usize) -> [usize; 3] {
        let [e0, e1, _] = self.extent;
        [r % e0, (r / e0) % e1, r / (e0 * e1)]
    }
}

impl Lattice {
    /// Builds the lattice of `dims` modules of side `lc_m` metres.
    pub fn new(dims: Dims, lc_m: f64) -> Self {
        assert!(lc_m > 0.0 && lc_m.is_finite(), "module side must be positive");
        Lattice { dims, lc: lc_m }
    }

    /// The edge bars along axis `a`: their lower corners, every corner but those on the far face.
    fn edge_run(&self, a: usize) -> BarRun {
        let n = [self.dims.nx, self.dims.ny, self.dims.nz];
        let mut extent = n.map(|v| v + 1);
        extent[a] = n[a];
        BarRun { extent }
    }

    /// The centre bars along axis `a`: their lower modules, every module but the last along `a`.
    fn centre_run(&self, a: usize) -> BarRun {
        let n = [self.dims.nx, self.dims.ny, self.dims.nz];
        let mut extent = n;
        extent[a] = n[a] - 1;
        BarRun { extent }
    }

    /// Bar `b` of the canonical order (see the module doc).
    pub fn bar(&self, b: usize) -> Bar {
        assert!(b < self.bar_count(), "bar {b} of a lattice of {}", self.bar_count());
        let n = [self.dims.nx, self.dims.ny, self.dims.nz];
        let mut r = b;
        for a in 0..3 {
            let run = self.edge_run(a);
            if r < run.count() {
                let c = run.cell(r);
                let mut c1 = c;
                c1[a] += 1;
                // Outer planes the bar lies in: those perpendicular to the other two axes.
                let planes = (0..3).filter(|&p| p != a && (c[p] == 0 || c[p] == n[p])).count() as i32;
                return Bar {
                    ends: [self.corner(c), self.corner(c1)],
                    family: BarFamily::Edge,
                    direction: Direction::Axis(a as u8),
                    surface_factor: 0.5f64.powi(planes),
                };
            }
            r -= run.count();
        }
        let diagonals = 8 * self.dims.modules();
        if r < diagonals {
            // Module by module, corners x fastest.
            let m = BarRun { extent: n }.cell(r / 8);
            let o = r % 8;
            let (di, dj, dk) = (o & 1, (o >> 1) & 1, o >> 2);
            let centre = self.centre(m);
            let corner = self.corner([m[0] + di, m[1] + dj, m[2] + dk]);
            // Oriented so the z component is positive.
            let (ends, sx, sy) =
                if dk == 1 { ([centre, corner], di == 1, dj == 1) } else { ([corner, centre], di == 0, dj == 0) };
            return Bar {
                ends,
                family: BarFamily::Diagonal,
                direction: Direction::Diagonal { neg_x: !sx, neg_y: !sy },
                surface_factor: 1.0,
            };
        }
        r -= diagonals;
        for a in 0..3 {
            let run = self.centre_run(a);
            if r < run.count() {
                let m = run.cell(r);
                let mut m1 = m;
                m1[a] += 1;
                return Bar {
                    ends: [self.centre(m), self.centre(m1)],
                    family: BarFamily::Centre,
                    direction: Direction::Axis(a as u8),
                    surface_factor: 1.0,
                };
            }
            r -= run.count();
        }
        unreachable!("bar {b} is below the bar count")
    }

    /// Number of bars.
    pub fn bar_count(&self) -> usize {
        self.dims.bar_count()
    }

    /// Module counts.
    pub fn dims(&self) -> Dims {
        self.dims
    }

    /// Module side `Lc` in metres.
    pub fn lc(&self) -> f64 {
        self.lc
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.dims.node_count()
    }

    /// All bars in canonical order.
    pub fn bars(&self) -> impl ExactSizeIterator<Item = Bar> + '_ {
        (0..self.bar_count()).map(|b| self.bar(b))
    }

    /// What node `id` is.
    pub fn kind(&self, id: NodeId) -> NodeKind {
        let Dims { nx, ny, .. } = self.dims;
        let i = id.index();
        let corners = self.dims.corner_nodes();
        if i < corners {
            NodeKind::Corner([i % (nx + 1), (i / (nx + 1)) % (ny + 1), i / ((nx + 1) * (ny + 1))])
        } else {
            let m = i - corners;
            NodeKind::Centre([m % nx, (m / nx) % ny, m / (nx * ny)])
        }
    }

    /// Block extent in metres `(nx·Lc, ny·Lc, nz·Lc)`.
    pub fn extent(&self) -> [f64; 3] {
        [self.dims.nx as f64 * self.lc, self.dims.ny as f64 * self.lc, self.dims.nz as f64 * self.lc]
    }

    /// Id of the corner-lattice node `(i, j, k)`.
    pub fn corner(&self, c: [usize; 3]) -> NodeId {
        let Dims { nx, ny, .. } = self.dims;
        NodeId((c[0] + (nx + 1) * (c[1] + (ny + 1) * c[2])) as u32)
    }

    /// Id of the centre node of module `(i, j, k)`.
    pub fn centre(&self, m: [usize; 3]) -> NodeId {
        let Dims { nx, ny, .. } = self.dims;
        NodeId((self.dims.corner_nodes() + m[0] + nx * (m[1] + ny * m[2])) as u32)
    }

    /// Position of a node in metres (undeformed).
    pub fn position(&self, id: NodeId) -> [f64; 3] {
        match self.kind(id) {
            NodeKind::Corner(c) => c.map(|v| v as f64 * self.lc),
            NodeKind::Centre(m) => m.map(|v| (v as f64 + 0.5) * self.lc),
        }
    }

    /// Midpoint of a bar (m).
    pub fn bar_midpoint(&self, bar: &Bar) -> [f64; 3] {
        let (a, b) = (self.half_units(bar.ends[0]), self.half_units(bar.ends[1]));
        [0, 1, 2].map(|c| (a[c] + b[c]) as f64 * 0.25 * self.lc)
    }

    /// Position in units of `Lc/2` (exact integers), used for ordering and lookup.
    pub fn half_units(&self, id: NodeId) -> [usize; 3] {
        match self.kind(id) {
            NodeKind::Corner(c) => c.map(|v| 2 * v),
            NodeKind::Centre(m) => m.map(|v| 2 * v + 1),
        }
    }

    /// The node at `p` (metres), within `1e-6·Lc`; `None` if no node is there.
    pub fn node_at(&self, p: [f64; 3]) -> Option<NodeId> {
        let tol = 1e-6;
        let h = p.map(|v| 2.0 * v / self.lc);
        let r = h.map(f64::round);
        if (0..3).any(|a| (h[a] - r[a]).abs() > tol || r[a] < 0.0) {
            return None;
        }
        let r = r.map(|v| v as usize);
        let n = [self.dims.nx, self.dims.ny, self.dims.nz];
        if (0..3).any(|a| r[a] > 2 * n[a]) {
            return None;
        }
        if r.iter().all(|v| v % 2 == 0) {
            Some(self.corner(r.map(|v| v / 2)))
        } else if r.iter().all(|v| v % 2 == 1) {
            Some(self.centre(r.map(|v| v / 2)))
        } else {
            None
        }
    }

    /// The node with the paper's 1-based LDEM number `n`.
    pub fn node_by_ldem(&self, n: u64) -> Option<NodeId> {
        (n >= 1 && n <= self.node_count() as u64).then(|| NodeId((n - 1) as u32))
    }

    /// Lumped mass of a node in units of `ρ·Lc³`: a centre node ½; a corner node ½ halved once
    /// for every outer plane of the block it lies on.
    pub fn mass_fraction(&self, id: NodeId) -> f64 {
        match self.kind(id) {
            NodeKind::Centre(_) => 0.5,
            NodeKind::Corner(c) => 0.5 * 0.5f64.powi(self.outer_planes(c) as i32),
        }
    }

    /// Number of outer planes of the block the corner node `c` lies on (0 to 3).
    pub fn outer_planes(&self, c: [usize; 3]) -> usize {
        let n = [self.dims.nx, self.dims.ny, self.dims.nz];
        (0..3).filter(|&a| c[a] == 0 || c[a] == n[a]).count()
    }

    /// The contact nodes: corner-lattice nodes of the bottom face `z = 0`, in canonical order.
    pub fn contact_nodes(&self) -> Vec<NodeId> {
        (0..self.contact_count() as u32).map(NodeId).collect()
    }

    /// The number of contact nodes, `(nx + 1)(ny + 1)`.
    pub fn contact_count(&self) -> usize {
        (self.dims.nx + 1) * (self.dims.ny + 1)
    }

    /// Contact node `c` (`contact_nodes()[c]`, without building the list).
    pub fn contact_node(&self, c: usize) -> NodeId {
        assert!(c < self.contact_count(), "contact node {c} of {}", self.contact_count());
        NodeId(c as u32)
    }

    /// Whether a node lies on the outer surface of the block.
    pub fn on_surface(&self, id: NodeId) -> bool {
        match self.kind(id) {
            NodeKind::Centre(_) => false,
            NodeKind::Corner(c) => self.outer_planes(c) > 0,
        }
    }

    /// Contact area `nx·Lc × ny·Lc` in m².
    pub fn contact_area(&self) -> f64 {
        let e = self.extent();
        e[0] * e[1]
    }

    /// Block volume in m³.
    pub fn volume(&self) -> f64 {
        let e = self.extent();
        e[0] * e[1] * e[2]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_block_counts() {
        let l = Lattice::new(Dims::new(10, 1, 5), 0.1);
        assert_eq!(l.node_count(), 182);
        assert_eq!(l.bar_count(), 781);
        assert_eq!(l.bar_count(), 781);
        assert_eq!(l.contact_nodes().len(), 22);
    }

    #[test]
    fn ldem_node_36_is_where_the_paper_puts_it() {
        let l = Lattice::new(Dims::new(10, 1, 5), 0.1);
        let n = l.node_by_ldem(36).unwrap();
        let p = l.position(n);
        for (a, b) in p.iter().zip([0.2, 0.1, 0.1]) {
            assert!((a - b).abs() < 1e-12);
        }
        assert_eq!(l.node_at([0.2, 0.1, 0.1]), Some(n));
        assert_eq!(l.node_at([0.05, 0.05, 0.05]), Some(l.centre([0, 0, 0])));
        assert_eq!(l.node_at([0.05, 0.0, 0.05]), None);
        assert_eq!(l.node_at([1.2, 0.0, 0.0]), None);
        assert_eq!(l.node_by_ldem(0), None);
        assert_eq!(l.node_by_ldem(183), None);
    }

    /// The canonical bar order built by loops over the block, as the module doc states it.
    fn bars_by_loops(l: &Lattice) -> Vec<Bar> {
        let Dims { nx, ny, nz } = l.dims();
        let n = [nx, ny, nz];
        let mut bars = Vec::new();
        for a in 0..3 {
            for k in 0..=nz {
                for j in 0..=ny {
                    for i in 0..=nx {
                        let c = [i, j, k];
                        if c[a] == n[a] {
                            continue;
                        }
                        let mut c1 = c;
                        c1[a] += 1;
                        let planes = (0..3).filter(|&b| b != a && (c[b] == 0 || c[b] == n[b])).count() as i32;
                        bars.push(Bar {
                            ends: [l.corner(c), l.corner(c1)],
                            family: BarFamily::Edge,
                            direction: Direction::Axis(a as u8),
                            surface_factor: 0.5f64.powi(planes),
                        });
                    }
                }
            }
        }
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let centre = l.centre([i, j, k]);
                    for dk in 0..2 {
                        for dj in 0..2 {
                            for di in 0..2 {
                                let corner = l.corner([i + di, j + dj, k + dk]);
                                let (ends, sx, sy) = if dk == 1 {
                                    ([centre, corner], di == 1, dj == 1)
                                } else {
                                    ([corner, centre], di == 0, dj == 0)
                                };
                                bars.push(Bar {
                                    ends,
                                    family: BarFamily::Diagonal,
                                    direction: Direction::Diagonal { neg_x: !sx, neg_y: !sy },
                                    surface_factor: 1.0,
                                });
                            }
                        }
                    }
                }
            }
        }
        for a in 0..3 {
            for k in 0..nz {
                for j in 0..ny {
                    for i in 0..nx {
                        let m = [i, j, k];
                        if m[a] + 1 == n[a] {
                            continue;
                        }
                        let mut m1 = m;
                        m1[a] += 1;
                        bars.push(Bar {
                            ends: [l.centre(m), l.centre(m1)],
                            family: BarFamily::Centre,
                            direction: Direction::Axis(a as u8),
                            surface_factor: 1.0,
                        });
                    }
                }
            }
        }
        bars
    }

    #[test]
    fn bars_and_nodes_computed_from_their_index_are_the_canonical_order() {
        for dims in
            [Dims::new(10, 1, 5), Dims::new(3, 2, 4), Dims::new(1, 1, 1), Dims::new(1, 5, 2), Dims::new(4, 3, 1)]
        {
            let l = Lattice::new(dims, 0.1);
            let by_loops = bars_by_loops(&l);
            assert_eq!(by_loops.len(), l.bar_count(), "{dims:?}: the closed-form count");
            assert!(l.bars().eq(by_loops.iter().copied()), "{dims:?}: bar(b) is the b-th bar of the loops");
            let Dims { nx, ny, nz } = dims;
            let mut id = 0;
            for k in 0..=nz {
                for j in 0..=ny {
                    for i in 0..=nx {
                        assert_eq!(l.kind(NodeId(id)), NodeKind::Corner([i, j, k]));
                        id += 1;
                    }
                }
            }
            for k in 0..nz {
                for j in 0..ny {
                    for i in 0..nx {
                        assert_eq!(l.kind(NodeId(id)), NodeKind::Centre([i, j, k]));
                        id += 1;
                    }
                }
            }
            assert_eq!(id as usize, l.node_count());
        }
    }

    #[test]
    fn every_bar_joins_nodes_at_its_length_and_direction() {
        let l = Lattice::new(Dims::new(3, 2, 4), 0.25);
        for b in l.bars() {
            let p0 = l.position(b.ends[0]);
            let p1 = l.position(b.ends[1]);
            let d: Vec<f64> = (0..3).map(|a| p1[a] - p0[a]).collect();
            let len = d.iter().map(|v| v * v).sum::<f64>().sqrt();
            assert!((len - b.length_factor() * l.lc()).abs() < 1e-12);
            let e = b.direction.unit();
            for a in 0..3 {
                assert!((d[a] / len - e[a]).abs() < 1e-12, "{b:?}");
            }
        }
    }
}
