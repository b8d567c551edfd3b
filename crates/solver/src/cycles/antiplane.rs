//! The fault's quasi-static stiffness in the lattice's antiplane mode (docs/model.md §20.2).
//!
//! **The mode.** A slab of the lattice one module thick along strike (x), its displacement along
//! x only and the same on the slab's two sides (`u(x = 0) = u(x = Lc)`, the antiplane field of an
//! infinitely long fault). Only bars with an x component carry it: an edge bar along x joins two
//! nodes the mode moves together, so it carries nothing; y and z edge bars and centre bars are
//! perpendicular to x; the eight half-diagonals of a module (corner to centre, `n_x² = 1/3`) are
//! what resist antiplane shear. Each centre node then has four links, to its module's corners
//! (projected onto the y–z plane), each the two half-diagonals from the slab's two sides;
//! eliminating the centre (it carries no load) joins the module's four corners pairwise with a
//! quarter of that link. On the corner grid the result is a nine-point stencil: `2q` to each of
//! the four axial neighbours, `q` to each diagonal one, half of those along the slab's outer
//! planes (a plane belongs to one row of modules), with `q = c/4` and `c` the centre's link.
//!
//! **The fault's response.** The block of `ny × nz` modules is the fault's one side (the base
//! z = 0 is the fault, y down dip from the free surface y = 0, z away from the fault, as the
//! dynamic fault scenes have it). The face is prescribed (the slip `δ = 2u` on the frictional
//! part, the plate's `V_p·t` below it), the far face z = nz·Lc moves with the plate and the
//! bottom face is free. The static response of the face to its own displacement is what
//! [`FaultStiffness`] holds: with the rows y = 0 and y = ny·Lc half rows, cosines `cos(mπj/ny)`
//! along the face diagonalise the stencil, and each one decays away from the fault as a
//! three-term recurrence in z, solved exactly from the far face by a backward sweep. Then
//!
//! `Δτ_j = −Σ_l K_jl·δ_l`,  `K_jl = w_l/(ny·Lc²)·Σ_m ε_m·s_m·cos(mπj/ny)·cos(mπl/ny)`,
//!
//! with `s_m` the face force of cosine m of unit amplitude, `w_l` ½ on the free surface's node
//! (and on the block's bottom) and 1 between, `ε_m` ½ for m = 0 and m = ny. A rigid motion (face, plate and far face moving
//! together) stresses nothing, so the traction on the frictional part is
//! `τ0 − K·(δ − V_p·t)` with K taken over the frictional part only.
//!
//! [`AntiplaneStencil::from_model`] reads `c` from the bars of a slab actually built, and checks
//! that they form the stencil above; `crates/solver/tests/cycles.rs` compares [`FaultStiffness`]
//! with a direct solve of that slab's own operator and with the closed form of uniform slip on
//! a patch in a half-space.

use std::collections::BTreeMap;

use nalgebra::DMatrix;
use rayon::prelude::*;

use crate::error::SolverError;
use crate::geometry::{Direction, NodeKind};
use crate::model::Model;

/// The antiplane stencil of the lattice: the link between a module's centre and one of its
/// corners (both half-diagonals from the slab's two sides), and the module side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AntiplaneStencil {
    /// The centre-to-corner link `c = 2·k_d/3` (N/m), `k_d` a half-diagonal's stiffness.
    pub link_n_per_m: f64,
    /// The module side Lc (m).
    pub lc_m: f64,
}

/// A node of a slab projected onto the y–z plane, in half modules: corners at even
/// coordinates, centres at odd ones.
pub type Projected = (usize, usize);

/// The links of a slab's antiplane operator: `(p, q) → weight` (N/m), p < q.
pub type Links = BTreeMap<(Projected, Projected), f64>;

/// The antiplane operator of a slab built as a [`Model`]: every bar with an x component,
/// weighted by `n_x²` (as the kernel stores it), between the projections of its ends (bars whose ends project onto one
/// point carry nothing). `k` is the bar stiffness in kernel order.
pub fn antiplane_links(model: &Model, k: &[f64]) -> Result<Links, SolverError> {
    let lattice = model.lattice();
    if lattice.dims().nx != 1 {
        return Err(SolverError::Unsupported(format!(
            "the antiplane mode is a slab one module thick along strike; this block has nx = {}",
            lattice.dims().nx
        )));
    }
    let project = |internal: usize| -> Projected {
        match lattice.kind(model.canonical(internal)) {
            NodeKind::Corner([_, j, k]) => (2 * j, 2 * k),
            NodeKind::Centre([_, j, k]) => (2 * j + 1, 2 * k + 1),
        }
    };
    let mut links = Links::new();
    model.layout().visit(|bar, a, b, direction| {
        // The kernel's stiffness of a diagonal is k/3 along the unnormalised (±1, ±1, 1), so
        // its weight is the stored value itself: (k/3)·1² = k·n_x².
        let nx2 = match direction {
            Direction::Axis(0) | Direction::Diagonal { .. } => 1.0,
            Direction::Axis(_) => 0.0,
        };
        let (p, q) = (project(a), project(b));
        if nx2 > 0.0 && p != q {
            *links.entry(if p < q { (p, q) } else { (q, p) }).or_default() += k[bar] * nx2;
        }
    });
    Ok(links)
}

impl AntiplaneStencil {
    /// The stencil of a homogeneous slab (nx = 1) built as `model` with bar stiffness `k` (kernel
    /// order); refused unless every link joins a centre to a corner of its module and all links
    /// are equal within 1e-12 (a random Young's modulus breaks the cosines).
    pub fn from_model(model: &Model, k: &[f64]) -> Result<Self, SolverError> {
        let links = antiplane_links(model, k)?;
        let Some(&first) = links.values().next() else {
            return Err(SolverError::Unsupported("the slab has no bar that carries antiplane shear".into()));
        };
        for (&(p, q), &w) in &links {
            let corner_centre = (p.0 % 2) != (q.0 % 2) && p.0.abs_diff(q.0) == 1 && p.1.abs_diff(q.1) == 1;
            if !corner_centre {
                return Err(SolverError::Unsupported(format!(
                    "the slab's antiplane operator links {p:?} and {q:?}, not a module's centre and corner"
                )));
            }
            if (w - first).abs() > 1e-12 * first {
                return Err(SolverError::Unsupported(format!(
                    "the antiplane mode's fault stiffness needs a homogeneous slab; its links range over {first:e} \
                     and {w:e} N/m (a Weibull modulus, young_cv > 0, or layers)"
                )));
            }
        }
        Ok(AntiplaneStencil { link_n_per_m: first, lc_m: model.lattice().lc() })
    }

    /// The antiplane shear modulus the stencil carries in the long-wave limit, `c/Lc` (Pa).
    pub fn shear_modulus_pa(&self) -> f64 {
        self.link_n_per_m / self.lc_m
    }

    /// The face force (N) of the cosine `cos(θ·j)` of unit amplitude along a face of `nz`
    /// modules to a far face held still, `ρ = cos θ`: interior rows
    /// `q·[(12 − 4ρ)·a_k − (2 + 2ρ)·(a_{k+1} + a_{k−1})] = 0`, `a_nz = 0`, the face's row
    /// `q·[(6 − 2ρ)·a_0 − (2 + 2ρ)·a_1]`; `a_k/a_{k−1}` by a backward sweep (it stays in [0, 1]).
    fn face_force(&self, rho: f64, nz: usize) -> f64 {
        let q = self.link_n_per_m / 4.0;
        let (alpha, beta) = (12.0 - 4.0 * rho, 2.0 + 2.0 * rho);
        let mut r = 0.0;
        for _ in 1..nz {
            r = beta / (alpha - beta * r);
        }
        q * (0.5 * alpha - beta * r)
    }
}

/// The quasi-static stiffness of a fault's frictional part in the antiplane mode: `Δτ = −K·δ`
/// over its nodes (Pa per metre of slip), row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct FaultStiffness {
    /// Number of fault nodes, from the free surface down (`j = 0 … n − 1`, depth `j·Lc`).
    pub nodes: usize,
    /// `K` (Pa/m), `k[j·n + l]`.
    pub k: Vec<f64>,
    /// The module side (m).
    pub lc_m: f64,
    /// The block: modules down dip (`ny`) and away from the fault (`nz`).
    pub domain: [usize; 2],
}

impl FaultStiffness {
    /// `K` over the first `nodes` face nodes of a block of `ny × nz` modules with `stencil`.
    pub fn antiplane(stencil: &AntiplaneStencil, nodes: usize, ny: usize, nz: usize) -> Result<Self, SolverError> {
        if nodes == 0 || nodes > ny + 1 || nz < 2 {
            return Err(SolverError::Unsupported(format!(
                "a fault of {nodes} nodes on a block of {ny} × {nz} modules (the fault's nodes are at most ny + 1, \
                 the block at least 2 modules deep)"
            )));
        }
        let lc = stencil.lc_m;
        let modes: Vec<(f64, f64)> = (0..=ny)
            .into_par_iter()
            .map(|m| {
                let theta = std::f64::consts::PI * m as f64 / ny as f64;
                let eps = if m == 0 || m == ny { 0.5 } else { 1.0 };
                (theta, eps * stencil.face_force(theta.cos(), nz))
            })
            .collect();
        let scale = 1.0 / (ny as f64 * lc * lc);
        // K = C·diag(ε·s)·Cᵀ·diag(w)·scale, C[j][m] = cos(mπj/ny): one matrix product.
        let cosines = DMatrix::from_fn(nodes, modes.len(), |j, m| (modes[m].0 * j as f64).cos());
        let weighted = DMatrix::from_fn(modes.len(), nodes, |m, l| {
            let w = if l == 0 || l == ny { 0.5 } else { 1.0 };
            modes[m].1 * (modes[m].0 * l as f64).cos() * w * scale
        });
        let product = cosines * weighted;
        let k: Vec<f64> =
            (0..nodes).flat_map(|j| (0..nodes).map(move |l| (j, l))).map(|(j, l)| product[(j, l)]).collect();
        Ok(FaultStiffness { nodes, k, lc_m: lc, domain: [ny, nz] })
    }

    /// `Δτ = −K·δ` at every node (Pa) for slip `delta` (m).
    pub fn traction_change(&self, delta: &[f64], out: &mut [f64]) {
        for (j, t) in out.iter_mut().enumerate() {
            *t = self.traction_change_at(j, delta);
        }
    }

    /// `Δτ_j = −Σ_l K_jl·δ_l` at node `j` (Pa).
    pub fn traction_change_at(&self, j: usize, delta: &[f64]) -> f64 {
        let n = self.nodes;
        -dot(&self.k[j * n..(j + 1) * n], delta)
    }

    /// The fault length each node stands for (m): `Lc`, half of it at the free surface.
    pub fn node_length_m(&self, j: usize) -> f64 {
        if j == 0 { 0.5 * self.lc_m } else { self.lc_m }
    }
}

/// `a·b` with eight partial sums (the compiler vectorises them; the order is fixed, so the
/// result does not depend on the thread count).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 8];
    let (ca, cb) = (a.chunks_exact(8), b.chunks_exact(8));
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        for i in 0..8 {
            acc[i] += x[i] * y[i];
        }
    }
    let mut tail = 0.0;
    for (x, y) in ra.iter().zip(rb) {
        tail += x * y;
    }
    ((acc[0] + acc[4]) + (acc[1] + acc[5])) + ((acc[2] + acc[6]) + (acc[3] + acc[7])) + tail
}
