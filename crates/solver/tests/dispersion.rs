//! Properties of the dynamical matrix at random materials and wave vectors (seeded, ChaCha8).
//!
//! `D(k)` must be Hermitian and positive semi-definite, `D(−k) = conj(D(k))`, its spectrum
//! periodic under reciprocal-lattice vectors `G = (2π/Lc)·e_a` and invariant under the cubic
//! point group (axis permutations and sign flips); for small `|k|` in any direction the three
//! acoustic frequencies are `|k|·√(eig(Γ)/ρ)`, `Γ_ik = C_ijkl·n_j·n_l` (Christoffel).

use std::f64::consts::PI;

use nalgebra::{Matrix3, SymmetricEigen};
use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use stickslip_solver::dispersion::{LatticeMaterial, bloch_spectrum, dynamical_matrix};

fn random_case(rng: &mut ChaCha8Rng) -> (LatticeMaterial, [f64; 3]) {
    let nu = rng.random_range(0.01..0.49);
    let young = 10f64.powf(rng.random_range(9.0..11.0));
    let rho = rng.random_range(1000.0..8000.0);
    let lc = 10f64.powf(rng.random_range(-3.0..1.0));
    let m = LatticeMaterial::new(young, nu, rho, lc).unwrap();
    let k = [0; 3].map(|_| rng.random_range(-1.5..1.5) * PI / lc);
    (m, k)
}

fn top(m: &LatticeMaterial) -> f64 {
    (2.0 * (6.0 * m.normal_bar_stiffness_n_m() + 8.0 * m.diagonal_bar_stiffness_n_m()) / m.node_mass_kg()).sqrt()
}

#[test]
fn dynamical_matrix_is_hermitian_psd_and_periodic() {
    let mut rng = ChaCha8Rng::seed_from_u64(20260401);
    for _ in 0..300 {
        let (m, k) = random_case(&mut rng);
        let d = dynamical_matrix(&m, k);
        let w_max = top(&m);
        // Entries are sums of k_b/m ≤ ω_max²; rounding is ~1e-16 of that.
        let tol = 1e-13 * w_max * w_max;
        assert!((d - d.adjoint()).camax() < tol);
        let minus = dynamical_matrix(&m, k.map(|v| -v));
        assert!((minus - d.conjugate()).camax() < tol);
        let w = bloch_spectrum(&m, k);
        assert!(w[5] <= w_max * (1.0 + 1e-12), "Gershgorin-type bound {w_max} < {}", w[5]);
        let eig = SymmetricEigen::new(d).eigenvalues;
        assert!(eig.iter().all(|&l| l > -tol), "{eig}");
        let g = 2.0 * PI / m.lc_m();
        for a in 0..3 {
            let mut shifted = k;
            shifted[a] += g;
            let ws = bloch_spectrum(&m, shifted);
            // Cubic symmetry: permute axes and flip a sign.
            let permuted = bloch_spectrum(&m, [k[(a + 1) % 3], -k[(a + 2) % 3], k[a]]);
            for i in 0..6 {
                assert!((ws[i] - w[i]).abs() < 1e-7 * w_max, "G shift {a}: {ws:?} vs {w:?}");
                assert!((permuted[i] - w[i]).abs() < 1e-7 * w_max, "cubic: {permuted:?} vs {w:?}");
            }
        }
    }
}

#[test]
fn long_waves_in_any_direction_obey_the_christoffel_equation() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..200 {
        let (m, k) = random_case(&mut rng);
        let norm = k.iter().map(|v| v * v).sum::<f64>().sqrt();
        let n = k.map(|v| v / norm);
        let (c11, c12, c44) = m.elastic_constants_pa();
        let c = |i: usize, j: usize, k: usize, l: usize| -> f64 {
            if i == j && k == l {
                if i == k { c11 } else { c12 }
            } else if (i == k && j == l) || (i == l && j == k) {
                c44
            } else {
                0.0
            }
        };
        let gamma = Matrix3::from_fn(|i, k| {
            let mut s = 0.0;
            for j in 0..3 {
                for l in 0..3 {
                    s += c(i, j, k, l) * n[j] * n[l];
                }
            }
            s
        });
        let mut want: Vec<f64> =
            SymmetricEigen::new(gamma).eigenvalues.iter().map(|g| (g / m.density_kg_m3()).sqrt()).collect();
        want.sort_by(f64::total_cmp);
        // |k| = 1e-4·π/Lc: dispersion ~ (|k|·Lc)²/10 ≈ 1e-8; eigenvalue rounding ~1e-16/(|k|Lc)² ≈ 1e-8.
        let q = 1e-4 * PI / m.lc_m();
        let w = bloch_spectrum(&m, n.map(|v| q * v));
        for i in 0..3 {
            assert!((w[i] / q / want[i] - 1.0).abs() < 1e-6, "n {n:?}: {:?} vs {want:?}", w.map(|v| v / q));
        }
        assert!(w[3] > 100.0 * w[2], "optical branches stay finite at k → 0");
    }
}
