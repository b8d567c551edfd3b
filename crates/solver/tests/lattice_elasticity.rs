//! The lattice against closed forms (docs/model.md §1): counts, masses, elastic constants, finite blocks.

mod common;

use common::scene_with;
use stickslip_solver::Model;
use stickslip_solver::geometry::{BarFamily, Dims, Lattice, NodeKind};
use stickslip_solver::material::lattice_elastic_constants;
use stickslip_solver::statics::uniaxial_moduli;
use stickslip_solver::step::{Field, bars::bar_forces};

/// docs/model.md §1 counts, written out independently of the library's closed form.
fn spec_counts(nx: usize, ny: usize, nz: usize) -> (usize, usize, usize, usize) {
    let nodes = (nx + 1) * (ny + 1) * (nz + 1) + nx * ny * nz;
    let edges = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
    let diagonals = 8 * nx * ny * nz;
    let centre = (nx - 1) * ny * nz + nx * (ny - 1) * nz + nx * ny * (nz - 1);
    (nodes, edges, diagonals, centre)
}

#[test]
fn node_and_bar_counts_follow_the_closed_forms() {
    let paper = Lattice::new(Dims::new(10, 1, 5), 0.1);
    assert_eq!((paper.node_count(), paper.bar_count()), (182, 781));
    for (nx, ny, nz) in [(1, 1, 1), (2, 3, 4), (7, 1, 3), (5, 5, 5), (40, 20, 4), (1, 9, 2)] {
        let l = Lattice::new(Dims::new(nx, ny, nz), 0.3);
        let (nodes, edges, diagonals, centre) = spec_counts(nx, ny, nz);
        let count = |f: BarFamily| l.bars().filter(|b| b.family == f).count();
        assert_eq!(l.node_count(), nodes, "{nx}×{ny}×{nz} nodes");
        assert_eq!(count(BarFamily::Edge), edges, "{nx}×{ny}×{nz} edge bars");
        assert_eq!(count(BarFamily::Diagonal), diagonals, "{nx}×{ny}×{nz} diagonals");
        assert_eq!(count(BarFamily::Centre), centre, "{nx}×{ny}×{nz} centre bars");
        // No bar twice.
        let mut ends: Vec<_> = l.bars().map(|b| (b.ends[0].min(b.ends[1]), b.ends[0].max(b.ends[1]))).collect();
        ends.sort();
        ends.dedup();
        assert_eq!(ends.len(), l.bar_count());
    }
}

#[test]
fn total_mass_is_rho_times_volume() {
    for (nx, ny, nz, lc) in [(10, 1, 5, 0.1), (3, 4, 5, 0.7), (1, 1, 1, 2.0), (20, 10, 3, 0.01)] {
        let scene = scene_with(|f| {
            f.block.nx = nx;
            f.block.ny = ny;
            f.block.nz = nz;
            f.block.lc_m = lc;
            f.shear.driver_at_m = vec![[0.0, 0.0, lc]];
        });
        let model = Model::new(scene);
        let expected = 2400.0 * model.lattice().volume();
        assert!((model.total_mass() - expected).abs() <= 1e-12 * expected, "{nx}×{ny}×{nz}: {}", model.total_mass());
    }
}

fn homogeneous_model(n: [i64; 3], poisson: f64) -> Model {
    Model::new(scene_with(|f| {
        f.block.nx = n[0];
        f.block.ny = n[1];
        f.block.nz = n[2];
        f.material.poisson = poisson;
        f.material.young_cv = 0.0;
    }))
}

/// Displacement field `u = ε·x` in internal order.
fn affine(model: &Model, eps: [[f64; 3]; 3]) -> Field<1> {
    let mut u = Field::<1>::zeros(model.node_count());
    for i in 0..model.node_count() {
        let p = model.lattice().position(model.canonical(i));
        for a in 0..3 {
            u.c[a][i][0] = (0..3).map(|b| eps[a][b] * p[b]).sum();
        }
    }
    u
}

#[test]
fn affine_strain_leaves_every_complete_node_in_equilibrium() {
    let model = homogeneous_model([5, 4, 6], 0.2);
    let eps = [[1e-4, 3e-5, -2e-5], [3e-5, -5e-5, 4e-5], [-2e-5, 4e-5, 2e-4]];
    let u = affine(&model, eps);
    let k: Vec<[f64; 1]> = model.nominal_stiffness().iter().map(|&v| [v]).collect();
    let mut f = Field::<1>::zeros(model.node_count());
    bar_forces(model.layout(), &k, &u, &mut f);
    let scale = model.nominal_stiffness().iter().fold(0.0f64, |m, v| m.max(*v)) * 2e-4 * model.lattice().lc();
    let dims = model.lattice().dims();
    let n = [dims.nx, dims.ny, dims.nz];
    let mut checked = 0;
    for i in 0..model.node_count() {
        let complete = match model.lattice().kind(model.canonical(i)) {
            NodeKind::Corner(c) => (0..3).all(|a| c[a] > 0 && c[a] < n[a]),
            NodeKind::Centre(m) => (0..3).all(|a| m[a] > 0 && m[a] + 1 < n[a]),
        };
        if complete {
            checked += 1;
            for a in 0..3 {
                assert!(f.c[a][i][0].abs() < 1e-12 * scale, "node {i} axis {a}: {}", f.c[a][i][0]);
            }
        }
    }
    assert!(checked > 50);
}

/// Stress `σ = (1/Lc³) Σ w_b·k_b·(e·ε·e)·L_b²·e⊗e` of one interior module of a 3×3×3 block:
/// its 8 diagonals (weight 1), its 6 centre bars (½, shared with the neighbour) and its 12 edge
/// bars (¼, shared by four modules) — the periodic cell of the lattice.
fn cell_stress(model: &Model, eps: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let lattice = model.lattice();
    let lc = lattice.lc();
    let centre = lattice.centre([1, 1, 1]);
    let corners: Vec<_> =
        (0..8).map(|c| lattice.corner([1 + (c & 1), 1 + ((c >> 1) & 1), 1 + ((c >> 2) & 1)])).collect();
    let mut sigma = [[0.0; 3]; 3];
    let nominal = model.nominal_stiffness();
    for (b, &canon) in model.canonical_bars().iter().enumerate() {
        let bar = lattice.bar(canon as usize);
        let weight = match bar.family {
            BarFamily::Diagonal if bar.ends.contains(&centre) => 1.0,
            BarFamily::Centre if bar.ends.contains(&centre) => 0.5,
            BarFamily::Edge if bar.ends.iter().all(|e| corners.contains(e)) => 0.25,
            _ => continue,
        };
        let k = nominal[b] * if bar.family == BarFamily::Diagonal { 3.0 } else { 1.0 };
        let e = bar.direction.unit();
        let len = bar.length_factor() * lc;
        let strain: f64 = (0..3).map(|i| (0..3).map(|j| e[i] * eps[i][j] * e[j]).sum::<f64>()).sum();
        for i in 0..3 {
            for j in 0..3 {
                sigma[i][j] += weight * k * strain * len * len * e[i] * e[j] / lc.powi(3);
            }
        }
    }
    sigma
}

#[test]
fn periodic_cell_gives_c11_lambda_plus_two_mu_c12_lambda_c44_lambda() {
    for nu in [0.2, 0.25] {
        let model = homogeneous_model([3, 3, 3], nu);
        let (c11, c12, c44) = lattice_elastic_constants(2.0e10, nu);
        let s = cell_stress(&model, [[1.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]);
        assert!((s[0][0] / c11 - 1.0).abs() < 1e-12, "ν {nu}: C11 {} vs {c11}", s[0][0]);
        assert!((s[1][1] / c12 - 1.0).abs() < 1e-12, "ν {nu}: C12 {} vs {c12}", s[1][1]);
        assert!((s[2][2] / c12 - 1.0).abs() < 1e-12, "ν {nu}: C13 {} vs {c12}", s[2][2]);
        assert!(s[0][1].abs() < 1e-6 * c11);
        // Engineering shear strain γ_xy = 1.
        let s = cell_stress(&model, [[0.0, 0.5, 0.0], [0.5, 0.0, 0.0], [0.0, 0.0, 0.0]]);
        assert!((s[0][1] / c44 - 1.0).abs() < 1e-12, "ν {nu}: C44 {} vs {c44}", s[0][1]);
        if nu == 0.25 {
            let mu = 2.0e10 / (2.0 * 1.25);
            assert!((c44 / mu - 1.0).abs() < 1e-12, "at ν = 0.25 the lattice shear modulus is μ");
        }
    }
}

#[test]
fn finite_blocks_are_softer_and_approach_the_continuum_as_they_grow() {
    let young = 2.0e10;
    let nu = 0.25;
    let values: Vec<(usize, f64, f64)> = [4, 8, 16]
        .into_iter()
        .map(|n| {
            let model = homogeneous_model([n as i64; 3], nu);
            let m = uniaxial_moduli(&model, &model.nominal_stiffness(), 0).unwrap();
            let (e, v) = (m.young_pa, m.poisson[0]);
            assert!((m.poisson[0] - m.poisson[1]).abs() < 1e-9, "a cube is symmetric");
            println!("n = {n:2}: E_eff/E = {:.4}, ν_eff = {:.4}", e / young, v);
            (n, e, v)
        })
        .collect();
    for w in values.windows(2) {
        let ((n0, e0, v0), (n1, e1, v1)) = (w[0], w[1]);
        assert!(e0 < e1 && e1 < young, "E_eff must rise toward E: n={n0} {e0:e}, n={n1} {e1:e}");
        assert!((v1 - nu).abs() < (v0 - nu).abs(), "ν_eff must approach ν: n={n0} {v0}, n={n1} {v1}");
        // Roughly 1/n: doubling n about halves the gap (between 0.35 and 0.65 of it).
        let ratio = (young - e1) / (young - e0);
        assert!((0.35..0.65).contains(&ratio), "gap ratio {ratio} for n {n0} → {n1}");
    }
}
