//! The periodic cell (two nodes, 14 bars) and its dynamical matrix `D(k)`, with the six
//! frequencies at a wave vector.

use nalgebra::{Complex, Matrix6, SymmetricEigen};

use crate::dispersion::lattice::LatticeMaterial;
use crate::geometry::BarFamily;

/// The two nodes of the periodic cell.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CellNode {
    /// The corner node `A` at `0` (rows 0..3 of the dynamical matrix).
    Corner,
    /// The centre node `B` at `(½, ½, ½)·Lc` (rows 3..6).
    Centre,
}

impl CellNode {
    fn index(self) -> usize {
        match self {
            CellNode::Corner => 0,
            CellNode::Centre => 1,
        }
    }
}

/// One bar of the periodic cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CellBar {
    /// Start node (in this cell).
    pub from: CellNode,
    /// End node (in this or a neighbouring cell).
    pub to: CellNode,
    /// Family.
    pub family: BarFamily,
    /// Vector from the start node to the end node `d` (m).
    pub offset_m: [f64; 3],
    /// Spring constant `EA/L` (N/m).
    pub stiffness_n_m: f64,
}

/// The 14 bars one cell owns: 3 edge bars, 8 diagonals, 3 centre bars (each bar of the unbounded
/// lattice belongs to exactly one cell).
pub fn cell_bars(material: &LatticeMaterial) -> Vec<CellBar> {
    let lc = material.lc_m();
    let (kn, kd) = (material.normal_bar_stiffness_n_m(), material.diagonal_bar_stiffness_n_m());
    let mut bars = Vec::with_capacity(14);
    for a in 0..3 {
        let mut d = [0.0; 3];
        d[a] = lc;
        let bar = |from, to, family| CellBar { from, to, family, offset_m: d, stiffness_n_m: kn };
        bars.push(bar(CellNode::Corner, CellNode::Corner, BarFamily::Edge));
        bars.push(bar(CellNode::Centre, CellNode::Centre, BarFamily::Centre));
    }
    for corner in 0..8 {
        let d = [0, 1, 2].map(|a| if corner >> a & 1 == 1 { 0.5 * lc } else { -0.5 * lc });
        bars.push(CellBar {
            from: CellNode::Centre,
            to: CellNode::Corner,
            family: BarFamily::Diagonal,
            offset_m: d,
            stiffness_n_m: kd,
        });
    }
    bars
}

/// `D(k)` and its derivative `∂D/∂q` along the unit vector `n` (`k = q·n`).
pub(super) fn assemble(
    material: &LatticeMaterial,
    k: [f64; 3],
    n: [f64; 3],
) -> (Matrix6<Complex<f64>>, Matrix6<Complex<f64>>) {
    let mut d = Matrix6::<Complex<f64>>::zeros();
    let mut dd = Matrix6::<Complex<f64>>::zeros();
    let m = material.node_mass_kg();
    for bar in cell_bars(material) {
        let len = bar.offset_m.iter().map(|v| v * v).sum::<f64>().sqrt();
        let e = bar.offset_m.map(|v| v / len);
        let phase_arg: f64 = (0..3).map(|a| k[a] * bar.offset_m[a]).sum();
        let proj: f64 = (0..3).map(|a| n[a] * bar.offset_m[a]).sum();
        let phase = Complex::from_polar(1.0, phase_arg);
        let (p, q) = (3 * bar.from.index(), 3 * bar.to.index());
        for i in 0..3 {
            for j in 0..3 {
                let s = bar.stiffness_n_m * e[i] * e[j] / m;
                d[(p + i, p + j)] += s;
                d[(q + i, q + j)] += s;
                d[(p + i, q + j)] -= phase * s;
                d[(q + i, p + j)] -= phase.conj() * s;
                // ∂/∂q e^{±i q n·d} = ±i (n·d) e^{±i q n·d}
                dd[(p + i, q + j)] -= Complex::new(0.0, proj) * phase * s;
                dd[(q + i, p + j)] += Complex::new(0.0, proj) * phase.conj() * s;
            }
        }
    }
    (d, dd)
}

/// The 6×6 Hermitian dynamical matrix `D(k) = M^{−1/2}·K(k)·M^{−1/2}` (rad²/s²) at wave vector
/// `k` (rad/m); rows 0..3 are the corner node's `x, y, z`, rows 3..6 the centre node's.
pub fn dynamical_matrix(material: &LatticeMaterial, k_rad_m: [f64; 3]) -> Matrix6<Complex<f64>> {
    assemble(material, k_rad_m, [0.0; 3]).0
}

/// The six angular frequencies `ω` (rad/s) at wave vector `k` (rad/m), ascending (band order,
/// which mixes branches: use [`branch_point`] for P and S).
pub fn bloch_spectrum(material: &LatticeMaterial, k_rad_m: [f64; 3]) -> [f64; 6] {
    let eig = SymmetricEigen::new(dynamical_matrix(material, k_rad_m));
    let mut w: [f64; 6] = std::array::from_fn(|i| eig.eigenvalues[i].max(0.0).sqrt());
    w.sort_by(f64::total_cmp);
    w
}
