//! A built scene: the lattice in the stepper's internal order, masses, nominal bar stiffness,
//! the contact nodes and the boundary conditions the stepper works on.
//!
//! Built once per scene and shared (read-only) by every seed of an ensemble; a seed only adds its
//! random factors ([`Model::bar_stiffness`], [`Model::friction_factors`]).

use crate::boundary::Boundaries;
use crate::error::SolverError;
use crate::fault::{FaultLoads, von_karman_field};
use crate::geometry::{Bar, BarFamily, Direction, Face, Lattice, NodeId};
use crate::laws::NodeFriction;
use crate::layout::{BarGroup, BarLayout, Bars, Segment};
use crate::material::{STREAM_FRICTION, STREAM_YOUNG, axial_stiffness, weibull_factors};
use crate::medium::Zone;
use crate::rupture::{crack_area, fracture_energy_factors};
use crate::scene::Scene;
use crate::split::Window;
use crate::stencil::{RunStiffness, StencilLayout};
use crate::stiffness::LaneStiffness;

/// The group a bar belongs to in kernel order: its segment (phase, slab), its cache block
/// (module layer, band of y) and its direction class, packed into 48 bits in the same order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct GroupKey {
    segment: (u8, usize),
    block: (usize, usize),
    direction: Direction,
}

impl GroupKey {
    /// Bits of each field: segment 5 (phase × 16 + slab, slab < [`SLABS`] ≤ 16), block layer 20
    /// and band 20 (below 2²⁰, a million modules along z and y at most), direction 3.
    fn pack(self) -> u64 {
        let (phase, slab) = self.segment;
        debug_assert!(slab < 16 && self.block.0 < 1 << 20 && self.block.1 < 1 << 20);
        let d = match self.direction {
            Direction::Axis(a) => u64::from(a),
            Direction::Diagonal { neg_x, neg_y } => 3 + 2 * u64::from(neg_x) + u64::from(neg_y),
        };
        ((u64::from(phase) * 16 + slab as u64) << 43) | ((self.block.0 as u64) << 23) | ((self.block.1 as u64) << 3) | d
    }

    fn unpack(key: u64) -> GroupKey {
        let segment = ((key >> 43) / 16, (key >> 43) % 16);
        let direction = match key & 7 {
            d @ 0..=2 => Direction::Axis(d as u8),
            d => Direction::Diagonal { neg_x: (d - 3) >= 2, neg_y: (d - 3) % 2 == 1 },
        };
        GroupKey {
            segment: (segment.0 as u8, segment.1 as usize),
            block: (((key >> 23) & ((1 << 20) - 1)) as usize, ((key >> 3) & ((1 << 20) - 1)) as usize),
            direction,
        }
    }
}

pub use crate::slabs::STENCIL_MIN_BARS;
/// Lattices with at least this many bars are cut into z-slabs (see [`BarLayout`]).
pub const SLAB_MIN_BARS: usize = 100_000;
/// Number of z-slabs of a large lattice (at most one per module layer).
pub const SLABS: usize = 8;
/// Lattices with at least this many nodes have their bars ordered in cache blocks.
pub const BLOCK_MIN_NODES: usize = 4096;
/// Target number of nodes of one cache block (one module layer, a band of y).
pub const BLOCK_NODES: usize = 512;

/// The scene built into flat arrays, in the stepper's internal node and bar order.
///
/// Internal node order: by `z`, then `y`, then `x` of the position (centre nodes fall between
/// the corner layers), so bars join nodes that are close in memory. Internal bar order: by
/// segment (one for a small lattice; for one with [`SLAB_MIN_BARS`] bars or more, the bars
/// inside each of [`SLABS`] z-slabs, then those across every other slab boundary, then the
/// rest), then by direction class, then by end nodes.
#[derive(Clone, Debug)]
pub struct Model {
    scene: Scene,
    lattice: Lattice,
    /// internal index → canonical id.
    to_canonical: Vec<NodeId>,
    /// canonical index → internal index.
    to_internal: Vec<u32>,
    mass: Vec<f64>,
    inv_mass: Vec<f64>,
    layout: Bars,
    /// internal bar → canonical bar index (listed bars).
    bar_canonical: Vec<u32>,
    /// Nominal stiffness of each run (stencil bars).
    run_stiffness: Vec<RunStiffness>,
    contact: Vec<u32>,
    boundaries: Boundaries,
    /// The medium's zones (one per layer, or one), docs/model.md §18.
    zones: Vec<Zone>,
    /// The zone of each bar (listed bars, kernel order), when the medium dissipates; empty
    /// otherwise.
    bar_code: Vec<u8>,
    /// The zone of each stencil run (runs go along x, depth along y or z).
    run_code: Vec<u8>,
    /// The part of the block this model holds, when the scene is split over ranks.
    window: Option<Window>,
}

impl Model {
    /// Builds the lattice of `scene` and everything the stepper needs.
    pub fn new(scene: Scene) -> Model {
        let stencil = scene.rupture.is_none() && scene.dims.bar_count() >= STENCIL_MIN_BARS;
        Model::build(scene, stencil)
    }

    /// As [`Model::new`] with the bars listed whatever the size (for the listed kernels' tests and
    /// comparisons of the two layouts).
    pub fn with_listed_bars(scene: Scene) -> Model {
        Model::build(scene, false)
    }

    /// As [`Model::new`] with the bars as a stencil whatever the size (for tests of the stencil on
    /// small lattices); the scene's bars must not crack.
    pub fn with_stencil(scene: Scene) -> Model {
        assert!(scene.rupture.is_none(), "bars that crack are listed");
        Model::build(scene, true)
    }

    fn build(scene: Scene, stencil: bool) -> Model {
        let lattice = scene.lattice();
        let n = lattice.node_count();
        let to_canonical = internal_order(lattice.dims());
        let mut to_internal = vec![0u32; n];
        for (i, id) in to_canonical.iter().enumerate() {
            to_internal[id.index()] = i as u32;
        }
        let zones = scene.medium.zones(scene.young_pa, scene.density_kg_m3, scene.poisson);
        let mass = masses(&scene, &lattice, &zones, &to_canonical);
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();

        // Bars: a stencil for a large elastic lattice, else listed in kernel order.
        let (layout, bar_canonical) = if stencil {
            (Bars::Stencil(StencilLayout::new(lattice.dims())), Vec::new())
        } else {
            let (listed, canonical) = listed_bars(&lattice, &to_internal);
            (Bars::Listed(listed), canonical)
        };
        let contact = lattice.contact_nodes().iter().map(|id| to_internal[id.index()]).collect();
        let boundaries = Boundaries::new(&scene, |id| Some(to_internal[id.index()]));
        let mut model = Model {
            scene,
            lattice,
            to_canonical,
            to_internal,
            mass,
            inv_mass,
            layout,
            bar_canonical,
            run_stiffness: Vec::new(),
            contact,
            boundaries,
            zones,
            bar_code: Vec::new(),
            run_code: Vec::new(),
            window: None,
        };
        model.finish();
        model
    }

    /// The part `window` of the scene's block, for one rank of a split scene ([`crate::split`]):
    /// its nodes numbered from the window's first, its bars the stencil's window (or, below
    /// [`STENCIL_MIN_BARS`] bars, the listed bars with an owned end, in the block's order), the same masses,
    /// nominal stiffness and canonical indices as the whole block's; boundary conditions on the
    /// nodes it owns only, the base's contact on rank 0 only. A scene whose bars crack is listed
    /// and is not split.
    pub fn window(scene: Scene, window: Window) -> Model {
        assert!(scene.rupture.is_none(), "bars that crack are listed and are not split over ranks");
        let lattice = scene.lattice();
        let dims = lattice.dims();
        let to_canonical: Vec<NodeId> =
            (0..window.nodes).map(|i| canonical_of_internal(dims, window.global(i))).collect();
        let zones = scene.medium.zones(scene.young_pa, scene.density_kg_m3, scene.poisson);
        let mass = masses(&scene, &lattice, &zones, &to_canonical);
        let inv_mass = mass.iter().map(|m| 1.0 / m).collect();
        // A block below STENCIL_MIN_BARS lists its bars on one process: its window lists the bars
        // with an owned end, in the block's order.
        let (layout, bar_canonical) = if dims.bar_count() < STENCIL_MIN_BARS {
            let (listed, canonical) = listed_window(&lattice, &window);
            (Bars::Listed(listed), canonical)
        } else {
            (Bars::Stencil(StencilLayout::window(dims, window.lo, window.hi)), Vec::new())
        };
        // The base is rank 0's (a rank above can hold layer 0 as its halo, never the contact).
        let contact = if window.rank == 0 {
            lattice.contact_nodes().iter().map(|&id| internal_of_canonical(dims, id) as u32).collect()
        } else {
            Vec::new()
        };
        let boundaries = Boundaries::new(&scene, |id| {
            let g = internal_of_canonical(dims, id);
            window.owns(g).then(|| (g - window.first_node) as u32)
        });
        let mut model = Model {
            scene,
            lattice,
            to_canonical,
            to_internal: Vec::new(),
            mass,
            inv_mass,
            layout,
            bar_canonical,
            run_stiffness: Vec::new(),
            contact,
            boundaries,
            zones,
            bar_code: Vec::new(),
            run_code: Vec::new(),
            window: Some(window),
        };
        model.finish();
        model
    }

    /// The module layers whose energy terms this model sums: all, or a window's owned ones.
    pub fn energy_layers(&self) -> crate::ledger::EnergyLayers {
        let dims = self.lattice.dims();
        let layer_nodes = (dims.nx + 1) * (dims.ny + 1) + dims.nx * dims.ny;
        let (first_node, nodes) = match &self.window {
            None => (0, 0..self.node_count()),
            Some(w) => (w.first_node, w.owned.clone()),
        };
        let first = (first_node + nodes.start) / layer_nodes;
        let last = (first_node + nodes.end - 1) / layer_nodes;
        crate::ledger::EnergyLayers { first_node, layer_nodes, first, count: last + 1 - first, nodes }
    }

    /// The part of the block this model holds, when split over ranks.
    pub fn split_window(&self) -> Option<&Window> {
        self.window.as_ref()
    }

    /// The medium's zone codes and the runs' nominal stiffness, from the layout.
    fn finish(&mut self) {
        let model = self;
        if model.scene.medium.is_dissipative() {
            match &model.layout {
                Bars::Listed(_) => {
                    model.bar_code = model.bar_canonical.iter().map(|&c| model.zone_of_canonical(c as usize)).collect();
                }
                Bars::Stencil(s) => {
                    model.run_code = s.runs().iter().map(|r| model.zone_of_canonical(r.canonical(0))).collect();
                }
            }
        }
        if let Bars::Stencil(s) = &model.layout {
            let nominal = |r: &crate::stencil::Run, m: usize| model.nominal_of_canonical(r.canonical(m));
            model.run_stiffness = s
                .runs()
                .iter()
                .map(|r| {
                    let last = r.len as usize - 1;
                    RunStiffness { first: nominal(r, 0), interior: nominal(r, 1.min(last)), last: nominal(r, last) }
                })
                .collect();
        }
    }

    /// The nominal stiffness of each run of a stencil lattice (order of its runs; empty for
    /// listed bars).
    pub fn run_stiffness(&self) -> &[RunStiffness] {
        &self.run_stiffness
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The lattice (canonical order).
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// Number of nodes.
    pub fn node_count(&self) -> usize {
        self.mass.len()
    }

    /// Number of bars.
    pub fn bar_count(&self) -> usize {
        self.layout.bar_count()
    }

    /// Internal index of a canonical node (in a window: its window index; the window must hold
    /// it).
    pub fn internal(&self, id: NodeId) -> usize {
        match &self.window {
            None => self.to_internal[id.index()] as usize,
            Some(w) => w.local(internal_of_canonical(self.lattice.dims(), id)).expect("a node the window holds"),
        }
    }

    /// Internal index of a canonical node, if this model holds it (always, unless a window).
    pub fn held(&self, id: NodeId) -> Option<usize> {
        match &self.window {
            None => Some(self.to_internal[id.index()] as usize),
            Some(w) => w.local(internal_of_canonical(self.lattice.dims(), id)),
        }
    }

    /// Canonical id of an internal node index.
    pub fn canonical(&self, internal: usize) -> NodeId {
        self.to_canonical[internal]
    }

    /// Lumped masses (kg), internal order.
    pub fn mass(&self) -> &[f64] {
        &self.mass
    }

    /// Inverse masses (1/kg), internal order.
    pub fn inv_mass(&self) -> &[f64] {
        &self.inv_mass
    }

    /// Total mass (kg).
    pub fn total_mass(&self) -> f64 {
        self.mass.iter().sum()
    }

    /// Whether the bars are ordered in cache blocks (lattices of [`BLOCK_MIN_NODES`] nodes or
    /// more): then the stepper integrates each node right after its last bar.
    pub fn cache_blocked(&self) -> bool {
        self.layout.nodes() >= BLOCK_MIN_NODES
    }

    /// The bars in kernel order: listed, or a stencil.
    pub fn layout(&self) -> &Bars {
        &self.layout
    }

    /// Canonical index of each internal bar (order of every bar `b` of the kernel's list), for a
    /// listed layout; empty for a stencil (see [`Model::canonical_bars`]).
    pub fn bar_canonical(&self) -> &[u32] {
        &self.bar_canonical
    }

    /// The canonical index of every bar, kernel order.
    pub fn canonical_bars(&self) -> Vec<u32> {
        match &self.layout {
            Bars::Listed(_) => self.bar_canonical.clone(),
            Bars::Stencil(s) => {
                s.runs().iter().flat_map(|r| (0..r.len as usize).map(move |m| r.canonical(m) as u32)).collect()
            }
        }
    }

    /// Nominal kernel stiffness of the bar of canonical index `c` (N/m): `EA/L` with the
    /// surface reduction, divided by 3 for diagonals (see [`crate::step::bars`]), times the
    /// medium's factor at its depth ([`Model::medium_factor`]).
    fn nominal_of_canonical(&self, c: usize) -> f64 {
        let s = &self.scene;
        let bar = self.lattice.bar(c);
        let ea = axial_stiffness(bar.family, s.young_pa, s.poisson, s.lc_m);
        let k = bar.surface_factor * ea / (bar.length_factor() * s.lc_m);
        let k = if bar.family == BarFamily::Diagonal { k / 3.0 } else { k };
        if s.medium.is_default() { k } else { k * self.medium_factor(&bar) }
    }

    /// A bar's depth window (m): its vertical extent, or the half-module above and below a
    /// horizontal bar, and the depth of its midpoint.
    fn depth_window(&self, bar: &Bar) -> (f64, f64, f64) {
        let extent = self.lattice.extent();
        let medium = &self.scene.medium;
        let (a, b) = (self.lattice.position(bar.ends[0]), self.lattice.position(bar.ends[1]));
        let (da, db) = (medium.depth(a, extent), medium.depth(b, extent));
        let mid = 0.5 * (da + db);
        let half = if (da - db).abs() > 0.0 { 0.5 * (da - db).abs() } else { 0.5 * self.scene.lc_m };
        (mid - half, mid + half, mid)
    }

    /// The medium's factor of a bar's stiffness: the mean E over its depth window over the
    /// scene's, times the unrelaxed modulus of the zone of its midpoint (docs/model.md §18).
    fn medium_factor(&self, bar: &Bar) -> f64 {
        let medium = &self.scene.medium;
        let (a, b, mid) = self.depth_window(bar);
        medium.young_over(&self.zones, a, b) * self.zones[medium.zone_at(mid)].unrelaxed()
    }

    /// The zone of the bar of canonical index `c`: the layer of its midpoint.
    fn zone_of_canonical(&self, c: usize) -> u8 {
        let (_, _, mid) = self.depth_window(&self.lattice.bar(c));
        self.scene.medium.zone_at(mid) as u8
    }

    /// The medium's zones (one per layer of the profile, or one).
    pub fn zones(&self) -> &[Zone] {
        &self.zones
    }

    /// The zone of each listed bar (kernel order) when the medium dissipates.
    pub fn bar_zones(&self) -> &[u8] {
        &self.bar_code
    }

    /// The zone of each stencil run (every bar of a run lies at one depth) when the medium
    /// dissipates.
    pub fn run_zones(&self) -> &[u8] {
        &self.run_code
    }

    /// Homogeneous kernel stiffness of every bar, internal order (N/m; diagonals divided by 3).
    pub fn nominal_stiffness(&self) -> Vec<f64> {
        self.canonical_bars().into_iter().map(|c| self.nominal_of_canonical(c as usize)).collect()
    }

    /// Contact nodes (internal indices).
    pub fn contact(&self) -> &[u32] {
        &self.contact
    }

    /// The boundary conditions (rollers, drivers, plate, pressure).
    pub fn boundaries(&self) -> &Boundaries {
        &self.boundaries
    }

    /// Driven nodes (internal indices).
    pub fn drivers(&self) -> &[u32] {
        self.boundaries.drivers()
    }

    /// The nodes tied to the loading plate (internal indices) and their spring stiffness in x
    /// (N/m); empty without a plate.
    pub fn plate(&self) -> &[(u32, f64)] {
        self.boundaries.plate()
    }

    /// The bar stiffness of `seed` as a run holds it: per bar for listed bars
    /// ([`Model::bar_stiffness`]), the Weibull factors as `f32` for a stencil
    /// ([`Model::stencil_factors`]).
    pub fn lane_stiffness(&self, seed: u64) -> Result<LaneStiffness, SolverError> {
        self.lane_stiffness_on(seed, false)
    }

    /// [`Model::lane_stiffness`], a stencil's factors drawn on the current rayon pool with
    /// `parallel` (the same factors either way; not from inside a pool whose other tasks are
    /// other seeds: a waiting worker could start one of them).
    pub fn lane_stiffness_on(&self, seed: u64, parallel: bool) -> Result<LaneStiffness, SolverError> {
        Ok(match &self.layout {
            Bars::Listed(_) => LaneStiffness::PerBar(self.bar_stiffness(seed)?),
            Bars::Stencil(_) => LaneStiffness::Factored(self.stencil_factors_on(seed, parallel)?),
        })
    }

    /// The homogeneous bar stiffness as a run holds it (CV = 0 whatever the scene says).
    pub fn nominal_lane_stiffness(&self) -> LaneStiffness {
        match &self.layout {
            Bars::Listed(_) => LaneStiffness::PerBar(self.nominal_stiffness()),
            Bars::Stencil(_) => LaneStiffness::Factored(None),
        }
    }

    /// The Weibull factors of E of `seed` for a stencil lattice, kernel order, rounded to `f32`:
    /// factor `c` of the seed's E stream for the bar of canonical index `c` (the same draws as
    /// [`Model::bar_stiffness`]), drawn layer by layer by seeking the stream to each run; `None`
    /// when CV = 0.
    pub fn stencil_factors(&self, seed: u64) -> Result<Option<Vec<f32>>, SolverError> {
        self.stencil_factors_on(seed, false)
    }

    /// [`Model::stencil_factors`], the layers on the current rayon pool with `parallel`.
    pub fn stencil_factors_on(&self, seed: u64, parallel: bool) -> Result<Option<Vec<f32>>, SolverError> {
        let Bars::Stencil(s) = &self.layout else { panic!("stencil factors of a listed lattice") };
        if self.scene.young_cv == 0.0 {
            return Ok(None);
        }
        let draw = crate::material::SeekableWeibull::new(self.scene.young_cv, seed, STREAM_YOUNG)?;
        Ok(Some(crate::stencil::draw_factors(s, &draw, parallel)))
    }

    /// Kernel stiffness of every bar for `seed`: nominal times the Weibull factor of E drawn in
    /// canonical bar order from the seed's E stream (none drawn when CV = 0). For a stencil, the
    /// factor is the one its kernel reads (rounded to `f32`).
    pub fn bar_stiffness(&self, seed: u64) -> Result<Vec<f64>, SolverError> {
        if let Bars::Stencil(_) = &self.layout {
            let factors = self.stencil_factors(seed)?;
            let k: crate::stiffness::StiffnessRef<'_, 1> = crate::stiffness::StiffnessRef::Factored {
                runs: &self.run_stiffness,
                factors: factors.as_deref().map(|f| f.as_chunks::<1>().0),
            };
            return Ok(k.lane(&self.layout, 0));
        }
        let phi = weibull_factors(self.scene.young_cv, seed, STREAM_YOUNG, self.lattice.bar_count())?;
        let k = |c: u32| {
            let k = self.nominal_of_canonical(c as usize);
            phi.as_ref().map_or(k, |phi| k * phi[c as usize])
        };
        Ok(match &self.layout {
            Bars::Listed(_) => self.bar_canonical.iter().map(|&c| k(c)).collect(),
            Bars::Stencil(s) => {
                s.runs().iter().flat_map(|r| (0..r.len as usize).map(move |m| r.canonical(m) as u32)).map(k).collect()
            }
        })
    }

    /// Peak elongation of every bar for `seed` when the scene's bars crack (docs/model.md §11), in
    /// kernel units (internal order; a diagonal's is √3 times its elongation, see
    /// [`crate::step::bars`]): `εp·√(ΦG/ΦE)·L`, with `εp` the homogeneous critical strain and the
    /// seed's factors of the E and Gf fields; infinite for the bars of an elastic zone. `None`
    /// without `[rupture]`.
    pub fn bar_strength(&self, seed: u64) -> Result<Option<Vec<f64>>, SolverError> {
        let Some(r) = &self.scene.rupture else { return Ok(None) };
        let s = &self.scene;
        let eps = r.peak_strain(s.young_pa, s.poisson, s.lc_m);
        let n = self.bar_count();
        let young = weibull_factors(s.young_cv, seed, STREAM_YOUNG, n)?;
        let toughness = fracture_energy_factors(r, s.young_cv, seed, n)?;
        let factor = |v: &Option<Vec<f64>>, c: usize| v.as_ref().map_or(1.0, |v| v[c]);
        Ok(Some(
            self.bar_canonical
                .iter()
                .map(|&c| {
                    let c = c as usize;
                    let bar = &self.lattice.bar(c);
                    if r.stays_elastic(&self.lattice, bar) {
                        return f64::INFINITY;
                    }
                    let kernel = if bar.family == BarFamily::Diagonal { 3f64.sqrt() } else { 1.0 };
                    let ratio = factor(&toughness, c) / factor(&young, c);
                    eps * ratio.sqrt() * bar.length_factor() * s.lc_m * kernel
                })
                .collect(),
        ))
    }

    /// Crack-area share `A_f` (m²) of every bar, internal order (docs/model.md §11): the area of
    /// a crack plane normal to an axis that the bar stands for.
    pub fn crack_areas(&self) -> Vec<f64> {
        let s = &self.scene;
        self.bar_canonical
            .iter()
            .map(|&c| {
                let bar = &self.lattice.bar(c as usize);
                let ea = bar.surface_factor * axial_stiffness(bar.family, s.young_pa, s.poisson, s.lc_m);
                crack_area(ea, bar.length_factor() * s.lc_m, s.young_pa, s.poisson, s.lc_m)
            })
            .collect()
    }

    /// Friction factors of the contact nodes (order of [`Model::contact`]) for `seed`: the
    /// Weibull field on μ drawn in canonical contact order from the seed's friction stream, or
    /// all ones when its CV is 0.
    pub fn friction_factors(&self, seed: u64) -> Result<Vec<f64>, SolverError> {
        let n = self.contact.len();
        Ok(weibull_factors(self.scene.friction.mu_cv, seed, STREAM_FRICTION, n)?.unwrap_or_else(|| vec![1.0; n]))
    }

    /// The fault's loads on every contact node for `seed` (docs/model.md §15): `τ0·A_i` along x
    /// and y, with the seed's von Kármán field added to x when the scene has one and the seed's
    /// nucleation square's traction set inside it (both scaled by the node's share under an
    /// overburden, [`Fault::depth_scale`]), and
    /// `σn·A_i`, `A_i` the node's share of the base, with the smooth overstress's peak force
    /// `Δτ₀·F(r)·A_i` when the scene has one. `None` on the rigid base.
    pub fn fault_loads(&self, seed: u64) -> Result<Option<FaultLoads>, SolverError> {
        let Some(fault) = &self.scene.fault else { return Ok(None) };
        if self.contact.is_empty() {
            // A rank above the base of a split scene.
            return Ok(None);
        }
        let lattice = &self.lattice;
        let nodes = lattice.contact_nodes();
        let area: Vec<f64> = nodes.iter().map(|&id| Face::ZMin.tributary_area(lattice, id)).collect();
        let dims = lattice.dims();
        let field = match &fault.stochastic {
            Some(st) => Some(von_karman_field(
                dims.nx + 1,
                dims.ny + 1,
                self.scene.lc_m,
                st.correlation_length_m,
                st.hurst,
                seed,
            )?),
            None => None,
        };
        let nucleation = fault.nucleation.map(|n| (n, n.centre(seed)));
        // Contact nodes come in canonical order: x fastest, then y, the grid of the field.
        let shear_n = (0..nodes.len())
            .map(|c| {
                // An overburden scales the seed's parts as it scales the scene's tractions.
                let scale = fault.depth_scale(c);
                let extra = match (&field, &fault.stochastic) {
                    (Some(f), Some(st)) => st.std_pa * f[c] * scale,
                    _ => 0.0,
                };
                let mut tau_x = fault.shear_pa[c][0] + extra;
                if let Some((n, centre)) = nucleation {
                    let p = lattice.position(nodes[c]);
                    if n.contains(centre, p[0], p[1]) {
                        tau_x = n.shear_pa * scale;
                    }
                }
                [tau_x * area[c], fault.shear_pa[c][1] * area[c]]
            })
            .collect();
        let normal_n = (0..nodes.len()).map(|c| fault.normal_pa[c] * area[c]).collect();
        let overstress_n = match &fault.overstress {
            Some(o) => (0..nodes.len())
                .map(|c| {
                    let p = lattice.position(nodes[c]);
                    o.overstress_pa * o.shape(p[0], p[1]) * area[c] * fault.depth_scale(c)
                })
                .collect(),
            None => Vec::new(),
        };
        Ok(Some(FaultLoads { shear_n, normal_n, overstress_n }))
    }

    /// Coefficients of contact node `c` (order of [`Model::contact`]) whose field factor is
    /// `factor`: its region's (or the law's) μs and μd times the factor, and its Dc.
    pub fn node_friction(&self, c: usize, factor: f64) -> NodeFriction {
        self.scene.friction.base(c).scaled(factor).healing(self.scene.friction.heals)
    }
}

/// The canonical id of every internal node: nodes sorted by `z`, then `y`, then `x` of their
/// position, written in closed form (layer `k`: corner rows `j = 0..=ny` of `nx + 1` corners, then
/// centre rows `j = 0..ny` of `nx` centres; see [`crate::stencil`]).
/// The lumped mass of each node of `nodes` (kg): its share of the modules around it, with the
/// medium's density over the module's depth.
fn masses(scene: &Scene, lattice: &Lattice, zones: &[Zone], nodes: &[NodeId]) -> Vec<f64> {
    let rho_lc3 = scene.density_kg_m3 * scene.lc_m.powi(3);
    let (extent, half) = (lattice.extent(), 0.5 * scene.lc_m);
    nodes
        .iter()
        .map(|&id| {
            let d = scene.medium.depth(lattice.position(id), extent);
            lattice.mass_fraction(id) * rho_lc3 * scene.medium.density_over(zones, d - half, d + half)
        })
        .collect()
}

/// The internal index of canonical node `id` (the order of [`internal_order`]).
pub(crate) fn internal_of_canonical(dims: crate::geometry::Dims, id: NodeId) -> usize {
    let crate::geometry::Dims { nx, ny, nz } = dims;
    let (cc, cm) = ((nx + 1) * (ny + 1), nx * ny);
    let c = id.index();
    let corners = cc * (nz + 1);
    if c < corners { (c / cc) * (cc + cm) + c % cc } else { ((c - corners) / cm) * (cc + cm) + cc + (c - corners) % cm }
}

/// The canonical node of internal index `g` (the order of [`internal_order`]).
pub(crate) fn canonical_of_internal(dims: crate::geometry::Dims, g: usize) -> NodeId {
    let crate::geometry::Dims { nx, ny, nz } = dims;
    let (cc, cm) = ((nx + 1) * (ny + 1), nx * ny);
    let (k, r) = (g / (cc + cm), g % (cc + cm));
    let i = if r < cc { k * cc + r } else { cc * (nz + 1) + k * cm + (r - cc) };
    NodeId(i as u32)
}

fn internal_order(dims: crate::geometry::Dims) -> Vec<NodeId> {
    let crate::geometry::Dims { nx, ny, nz } = dims;
    let corners = (nx + 1) * (ny + 1) * (nz + 1);
    let mut out = Vec::with_capacity(dims.node_count());
    for k in 0..=nz {
        out.extend((0..(nx + 1) * (ny + 1)).map(|c| NodeId((c + (nx + 1) * (ny + 1) * k) as u32)));
        if k < nz {
            out.extend((0..nx * ny).map(|m| NodeId((corners + m + nx * ny * k) as u32)));
        }
    }
    out
}

/// The bars of `lattice` listed in kernel order (see [`Model`]), with the canonical index of each.
/// The number of bars of `lattice` with an end `window` owns: a listed window's
/// ([`Model::window`]).
pub fn window_bar_count(lattice: &Lattice, window: &crate::split::Window) -> usize {
    let dims = lattice.dims();
    (0..lattice.bar_count())
        .filter(|&b| lattice.bar(b).ends.iter().any(|&id| window.owns(internal_of_canonical(dims, id))))
        .count()
}

/// The block's listed bars ([`listed_bars`]) that have an end `window` owns, in the block's kernel
/// order (the same segments and groups, those left empty dropped), their ends as window indices,
/// with their canonical indices: each owned node receives its bars in the one process's order.
fn listed_window(lattice: &Lattice, window: &crate::split::Window) -> (BarLayout, Vec<u32>) {
    let block: Vec<NodeId> = internal_order(lattice.dims());
    let mut to_internal = vec![0u32; block.len()];
    for (i, id) in block.iter().enumerate() {
        to_internal[id.index()] = i as u32;
    }
    let (whole, canonical) = listed_bars(lattice, &to_internal);
    let local = |g: u32| window.local(g as usize).expect("a bar with an owned end lies in the window") as u32;
    let (mut segments, mut ends, mut bar_canonical) = (Vec::new(), Vec::new(), Vec::new());
    for s in whole.segments() {
        let mut groups = Vec::new();
        for g in &s.groups {
            let start = ends.len();
            for b in g.start..g.end {
                let [i, j] = whole.ends()[b];
                if window.owns(i as usize) || window.owns(j as usize) {
                    ends.push([local(i), local(j)]);
                    bar_canonical.push(canonical[b]);
                }
            }
            if ends.len() > start {
                groups.push(BarGroup { direction: g.direction, start, end: ends.len() });
            }
        }
        if !groups.is_empty() {
            segments.push(Segment { phase: s.phase, groups });
        }
    }
    (BarLayout::new(segments, ends, window.nodes), bar_canonical)
}

fn listed_bars(lattice: &Lattice, to_internal: &[u32]) -> (BarLayout, Vec<u32>) {
    let n = lattice.node_count();
    // Bars: internal ends, by segment, then direction, then ends.
    let dims = lattice.dims();
    let slabs = if lattice.bar_count() >= SLAB_MIN_BARS { SLABS.min(dims.nz) } else { 1 };
    // z-slab of a node: bands of (2nz+1)/slabs ≥ 2 half-units, so a bar (which spans at most
    // two half-units in z) joins at most two neighbouring slabs.
    let slab = |id: NodeId| lattice.half_units(id)[2] * slabs / (2 * dims.nz + 1);
    let segment_of = |bar: &Bar| -> (u8, usize) {
        let (a, b) = (slab(bar.ends[0]), slab(bar.ends[1]));
        if a == b {
            (0, a)
        } else {
            let low = a.min(b);
            (1 + (low % 2) as u8, low)
        }
    };
    // Cache blocks (lattices of BLOCK_MIN_NODES nodes or more): all the bars whose first node
    // lies in one module layer and one band of y, so the seven direction groups of a block
    // reuse its node data from cache instead of sweeping the whole lattice seven times.
    let band = if n >= BLOCK_MIN_NODES { (BLOCK_NODES / (2 * dims.nx + 1)).max(1) } else { usize::MAX };
    let block_of = |bar: &Bar| -> (usize, usize) {
        if band == usize::MAX {
            return (0, 0);
        }
        let h = lattice.half_units(bar.ends[0]);
        (h[2] / 2, h[1] / (2 * band))
    };
    // Kernel order: by segment, block, direction class, then lower internal end (unique within
    // a direction class), sorted as 16-byte records (group key, lower end, canonical index).
    let mut order: Vec<(u64, u32, u32)> = (0..lattice.bar_count())
        .map(|b| {
            let bar = lattice.bar(b);
            let e = bar.ends.map(|id| to_internal[id.index()]);
            (
                GroupKey { segment: segment_of(&bar), block: block_of(&bar), direction: bar.direction }.pack(),
                e[0].min(e[1]),
                b as u32,
            )
        })
        .collect();
    order.sort_unstable_by_key(|&(key, low, _)| (key, low));
    let mut segments: Vec<((u8, usize), Segment)> = Vec::new();
    let mut last_block = None;
    for (i, &(key, _, _)) in order.iter().enumerate() {
        let GroupKey { segment: seg, block, direction: d } = GroupKey::unpack(key);
        if segments.last().is_none_or(|(s, _)| *s != seg) {
            segments.push((seg, Segment { phase: seg.0, groups: Vec::new() }));
            last_block = None;
        }
        let groups = &mut segments.last_mut().expect("just pushed").1.groups;
        match groups.last_mut() {
            Some(g) if g.direction == d && last_block == Some(block) => g.end = i + 1,
            _ => groups.push(BarGroup { direction: d, start: i, end: i + 1 }),
        }
        last_block = Some(block);
    }
    let bar_canonical: Vec<u32> = order.iter().map(|&(_, _, b)| b).collect();
    drop(order);
    let ends = bar_canonical.iter().map(|&b| lattice.bar(b as usize).ends.map(|id| to_internal[id.index()])).collect();
    (BarLayout::new(segments.into_iter().map(|(_, s)| s).collect(), ends, n), bar_canonical)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Dims;

    #[test]
    fn the_internal_order_is_the_nodes_sorted_by_z_y_x() {
        for dims in [Dims::new(10, 1, 5), Dims::new(3, 4, 2), Dims::new(1, 1, 1), Dims::new(5, 2, 7)] {
            let lattice = Lattice::new(dims, 0.1);
            let mut sorted: Vec<NodeId> = (0..dims.node_count() as u32).map(NodeId).collect();
            sorted.sort_by_key(|&id| {
                let h = lattice.half_units(id);
                (h[2], h[1], h[0])
            });
            assert_eq!(internal_order(dims), sorted, "{dims:?}");
        }
    }
}
