//! `[block]` and `[material]` checked, the lattice built, and the nodes a file names found on it.

use stickslip_solver::geometry::{Dims, Lattice, NodeId};

use super::{BlockSection, MaterialSection};
use crate::check::{Checker, approx};

/// Largest node count the solver accepts (node indices are 32-bit).
pub const MAX_NODES: u64 = 1 << 31;

/// Largest bar count the solver accepts (bar indices are 32-bit).
pub const MAX_BARS: u64 = u32::MAX as u64;

/// The module counts of `[block]` (`None` where refused), its `lc_m` checked too.
pub(super) fn counts(ck: &mut Checker, b: &BlockSection) -> [Option<usize>; 3] {
    let blurb = " (a block needs at least one module per axis)";
    let nx = ck.count("block.nx", b.nx, 1, 1_000_000, blurb);
    let ny = ck.count("block.ny", b.ny, 1, 1_000_000, blurb);
    let nz = ck.count("block.nz", b.nz, 1, 1_000_000, blurb);
    ck.positive("block.lc_m", b.lc_m);
    [nx, ny, nz]
}

/// Whether `v` is a positive, finite number the arithmetic keeps its digits for (not
/// subnormal: 5e-324 is a number, but a mass or stiffness made of it is 0 after one product).
fn normal(v: f64) -> bool {
    v.is_normal() && v > 0.0
}

/// Checks `[material]`, and that with the module side `lc_m` it gives nodes a mass, bars a
/// stiffness and the lattice a frequency the arithmetic can hold.
pub(super) fn check_material(ck: &mut Checker, m: &MaterialSection, lc_m: f64) {
    let young = ck.positive("material.young_pa", m.young_pa);
    let density = ck.positive("material.density_kg_m3", m.density_kg_m3);
    ck.range("material.poisson", m.poisson, 0.0, true, 0.5, true);
    ck.range("material.young_cv", m.young_cv, 0.0, false, 1.0, false);
    if !(lc_m > 0.0 && lc_m.is_finite()) {
        return;
    }
    // A node's mass is a share of ρ·Lc³; a bar's stiffness a share of E·Lc; ω² ∝ E/(ρ·Lc²).
    // The shares are within 1e-3 … 1, and a lattice's numbers must stay normal through them.
    let room = 1e-6;
    let (mass, stiffness) = (m.density_kg_m3 * lc_m.powi(3), m.young_pa * lc_m);
    if density && !(normal(mass * room) && (mass / room).is_finite()) {
        ck.push(
            "material.density_kg_m3",
            m.density_kg_m3,
            format!(
                "a density that gives the nodes a mass the arithmetic can hold: ρ·Lc³ = {} kg with Lc = {} m \
                 (between 1e-302 and 1e302 kg)",
                approx(mass),
                approx(lc_m)
            ),
        );
        return;
    }
    if young && !(normal(stiffness * room) && (stiffness / room).is_finite()) {
        ck.push(
            "material.young_pa",
            m.young_pa,
            format!(
                "a modulus that gives the bars a stiffness the arithmetic can hold: E·Lc = {} N/m with Lc = {} m \
                 (between 1e-302 and 1e302 N/m)",
                approx(stiffness),
                approx(lc_m)
            ),
        );
        return;
    }
    let omega2 = stiffness / mass;
    if young && density && !(normal(omega2 * room) && (omega2 / room).is_finite()) {
        ck.push(
            "material.young_pa",
            m.young_pa,
            format!(
                "a modulus and density whose lattice has a frequency the arithmetic can hold: E/(ρ·Lc²) = {} 1/s² \
                 (between 1e-302 and 1e302 1/s²; material.density_kg_m3 = {})",
                approx(omega2),
                approx(m.density_kg_m3)
            ),
        );
    }
}

/// The lattice of `[block]` from its checked `counts`; `None` when a count or `lc_m` was refused
/// or the block has more than [`MAX_NODES`] nodes (recorded in `ck`).
pub(super) fn lattice(ck: &mut Checker, b: &BlockSection, counts: [Option<usize>; 3]) -> Option<Lattice> {
    let [Some(nx), Some(ny), Some(nz)] = counts else { return None };
    let dims = Dims::new(nx, ny, nz);
    // Counted with checked arithmetic (at most 10⁶ modules per axis fit in 64 bits anyway).
    let (nodes, bars) = stickslip_solver::memory::counts(dims).unwrap_or((u64::MAX, u64::MAX));
    if nodes > MAX_NODES {
        ck.push("block", format!("{nx}×{ny}×{nz} modules ({nodes} nodes)"), format!("at most {MAX_NODES} nodes"));
    } else if bars > MAX_BARS {
        ck.push("block", format!("{nx}×{ny}×{nz} modules ({bars} bars)"), format!("at most {MAX_BARS} bars"));
    }
    if !(b.lc_m > 0.0 && b.lc_m.is_finite()) || nodes > MAX_NODES || bars > MAX_BARS {
        return None;
    }
    Some(Lattice::new(dims, b.lc_m))
}

fn describe_block(lattice: &Lattice) -> String {
    let e = lattice.extent();
    format!(
        "a node of the block (0..{} × 0..{} × 0..{} m; corner nodes every Lc = {} m, centre nodes at module centres)",
        approx(e[0]),
        approx(e[1]),
        approx(e[2]),
        approx(lattice.lc())
    )
}

/// Resolves nodes given by LDEM number (field `ldem_field`) and by position (`at_field`).
pub(super) fn resolve_nodes(
    ck: &mut Checker,
    lattice: &Lattice,
    (ldem_field, at_field): (&str, &str),
    ldem: &[i64],
    at_m: &[[f64; 3]],
) -> Vec<NodeId> {
    let mut out = Vec::new();
    for (i, &n) in ldem.iter().enumerate() {
        match u64::try_from(n).ok().and_then(|n| lattice.node_by_ldem(n)) {
            Some(id) => out.push(id),
            None => ck.push(
                format!("{ldem_field}[{i}]"),
                n,
                format!("an LDEM node number, 1 ≤ n ≤ {} for this block", lattice.node_count()),
            ),
        }
    }
    for (i, p) in at_m.iter().enumerate() {
        match lattice.node_at(*p) {
            Some(id) => out.push(id),
            None => ck.push(format!("{at_field}[{i}]"), format!("{p:?} m"), describe_block(lattice)),
        }
    }
    out
}
