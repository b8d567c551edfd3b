use super::*;

use std::f64::consts::PI;

use crate::geometry::BarFamily;

const AXES: [WaveDirection; 3] = [WaveDirection::X, WaveDirection::Y, WaveDirection::Z];
const ALL: [WaveDirection; 4] = [WaveDirection::X, WaveDirection::Y, WaveDirection::Z, WaveDirection::BodyDiagonal];

fn paper() -> LatticeMaterial {
    LatticeMaterial::new(2e10, 0.2, 2400.0, 0.1).unwrap()
}

fn material(nu: f64) -> LatticeMaterial {
    LatticeMaterial::new(2e10, nu, 2400.0, 0.1).unwrap()
}

fn sinc(x: f64) -> f64 {
    if x == 0.0 { 1.0 } else { x.sin() / x }
}

#[test]
fn cell_owns_fourteen_bars_of_the_right_lengths() {
    let m = paper();
    let bars = cell_bars(&m);
    assert_eq!(bars.len(), 14);
    for b in &bars {
        let len = b.offset_m.iter().map(|v| v * v).sum::<f64>().sqrt();
        let (want_len, want_k) = if b.family == BarFamily::Diagonal {
            (0.1 * 3f64.sqrt() / 2.0, m.diagonal_bar_stiffness_n_m())
        } else {
            (0.1, m.normal_bar_stiffness_n_m())
        };
        assert!((len - want_len).abs() < 1e-15);
        assert_eq!(b.stiffness_n_m, want_k);
    }
    assert_eq!(bars.iter().filter(|b| b.family == BarFamily::Diagonal).count(), 8);
    // EA_d/L_d with EA_d = (2δ/√3)·α·E·Lc², L_d = Lc·√3/2; at ν = 0.2 (δ = 3/4) k_d = k_n.
    assert!((m.diagonal_bar_stiffness_n_m() / m.normal_bar_stiffness_n_m() - 1.0).abs() < 1e-14);
}

#[test]
fn long_wave_speeds_of_the_paper_material() {
    let (cp, cs) = paper().long_wave_speeds_m_s();
    assert!((cp - 3042.90).abs() < 0.01, "{cp}");
    assert!((cs - 1521.45).abs() < 0.01, "{cs}");
}

/// The Bloch long-wave limit equals the continuum C11, C44 (axes) and the Christoffel speeds
/// of the body diagonal: at `q = 1e-4·q_edge` dispersion is below 1e-8 and the cancellation
/// in the 2×2 eigenvalue about 1e-8, so 1e-7 is tight.
#[test]
fn long_wave_limit_equals_the_continuum() {
    for nu in [0.05, 0.2, 0.25, 0.4, 0.49] {
        let m = material(nu);
        let (c11, _, c44) = m.elastic_constants_pa();
        for d in ALL {
            let q = 1e-4 * d.zone_edge_rad_m(m.lc_m());
            for b in [Branch::P, Branch::S] {
                let c0 = long_wave_speed_m_s(&m, d, b.polarisation());
                let p = branch_point(&m, d, b, q).unwrap();
                assert!((p.phase_velocity_m_s / c0 - 1.0).abs() < 1e-7, "ν {nu} {d} {b}: {p:?} vs {c0}");
                assert!((p.group_velocity_m_s / c0 - 1.0).abs() < 1e-7, "ν {nu} {d} {b}: {p:?}");
            }
        }
        let (cp, cs) = m.long_wave_speeds_m_s();
        assert!((cp - (c11 / 2400.0).sqrt()).abs() < 1e-9 * cp);
        assert!((cs - (c44 / 2400.0).sqrt()).abs() < 1e-9 * cs);
        assert_eq!(long_wave_speed_m_s(&m, WaveDirection::X, Polarisation::Longitudinal), cp);
        assert_eq!(long_wave_speed_m_s(&m, WaveDirection::Z, Polarisation::Transverse), cs);
    }
}

#[test]
fn axis_branches_match_the_closed_forms() {
    for nu in [0.1, 0.2, 0.25, 0.45] {
        let m = material(nu);
        let (kn, kd, mass, lc) =
            (m.normal_bar_stiffness_n_m(), m.diagonal_bar_stiffness_n_m(), m.node_mass_kg(), m.lc_m());
        let scale = (4.0 * kn + 16.0 / 3.0 * kd) / mass;
        for i in 0..=16 {
            let q = PI / lc * i as f64 / 16.0;
            let s2 = |x: f64| x.sin().powi(2);
            let want = [
                (Branch::S, 16.0 / 3.0 * kd * s2(q * lc / 4.0)),
                (Branch::OpticalS, 16.0 / 3.0 * kd * (q * lc / 4.0).cos().powi(2)),
                (Branch::P, 4.0 * kn * s2(q * lc / 2.0) + 8.0 / 3.0 * kd * (1.0 - (q * lc / 2.0).cos())),
                (Branch::OpticalP, 4.0 * kn * s2(q * lc / 2.0) + 8.0 / 3.0 * kd * (1.0 + (q * lc / 2.0).cos())),
            ];
            for d in AXES {
                for (b, w) in want {
                    let p = branch_point(&m, d, b, q).unwrap();
                    assert!((p.omega_rad_s.powi(2) - w / mass).abs() < 1e-12 * scale, "ν {nu} {d} {b} q {q}");
                }
            }
            if i > 0 {
                let (delta, _) = m.truss_constants();
                let r = 4.0 * delta / 9.0;
                let (cp, cs) = m.long_wave_speeds_m_s();
                let p = branch_point(&m, WaveDirection::X, Branch::P, q).unwrap().phase_velocity_m_s;
                let s = branch_point(&m, WaveDirection::X, Branch::S, q).unwrap().phase_velocity_m_s;
                let want_p = cp * ((sinc(q * lc / 2.0).powi(2) + r * sinc(q * lc / 4.0).powi(2)) / (1.0 + r)).sqrt();
                assert!((p / want_p - 1.0).abs() < 1e-10, "ν {nu} q {q}: {p} vs {want_p}");
                assert!((s / (cs * sinc(q * lc / 4.0)) - 1.0).abs() < 1e-10, "ν {nu} q {q}");
            }
        }
    }
}

/// The full 6×6 spectrum is exactly the union of the polarisation blocks, and the measured
/// polarisation of each full eigenvector says which block it belongs to.
#[test]
fn full_spectrum_is_the_union_of_the_polarisation_blocks() {
    for nu in [0.2, 0.25, 0.4] {
        let m = material(nu);
        for d in ALL {
            let edge = d.zone_edge_rad_m(m.lc_m());
            // Away from the zone edge, where the branches of one block touch.
            for f in [0.013, 0.1, 0.37, 0.61, 0.83] {
                let q = f * edge;
                let w = |b| branch_point(&m, d, b, q).unwrap().omega_rad_s;
                let (p, s, op, os) = (w(Branch::P), w(Branch::S), w(Branch::OpticalP), w(Branch::OpticalS));
                let mut want = [p, s, s, op, os, os];
                want.sort_by(f64::total_cmp);
                let modes = bloch_modes(&m, d, q).unwrap();
                let top = want[5];
                for (mode, w) in modes.iter().zip(want) {
                    assert!((mode.omega_rad_s - w).abs() < 1e-10 * top, "ν {nu} {d} q {f}: {modes:?}");
                }
                for mode in &modes {
                    let near = |x: f64| (mode.omega_rad_s - x).abs() < 1e-9 * top;
                    // A longitudinal eigenvalue that happens to equal a transverse one may mix.
                    if (near(p) || near(op)) && !(near(s) || near(os)) {
                        assert!((mode.longitudinal_fraction - 1.0).abs() < 1e-9, "{d} {f}: {mode:?}");
                    } else if !(near(p) || near(op)) {
                        assert!(mode.longitudinal_fraction.abs() < 1e-9, "{d} {f}: {mode:?}");
                    }
                }
                if f < 0.02 {
                    for mode in &modes {
                        let acoustic = near_any(mode.omega_rad_s, &[p, s], top);
                        let want_phase = if acoustic { 1.0 } else { -1.0 };
                        assert!((mode.sublattice_phase - want_phase).abs() < 1e-3, "{d}: {mode:?}");
                    }
                }
            }
        }
    }
}

fn near_any(x: f64, set: &[f64], scale: f64) -> bool {
    set.iter().any(|&y| (x - y).abs() < 1e-9 * scale)
}

#[test]
fn group_velocity_is_the_slope_of_the_branch() {
    let m = material(0.3);
    for d in ALL {
        let edge = d.zone_edge_rad_m(m.lc_m());
        for b in [Branch::P, Branch::S, Branch::OpticalP, Branch::OpticalS] {
            for f in [0.05, 0.3, 0.55, 0.9] {
                let q = f * edge;
                let h = 1e-5 * edge;
                let w = |q| branch_point(&m, d, b, q).unwrap().omega_rad_s;
                let fd = (w(q + h) - w(q - h)) / (2.0 * h);
                let p = branch_point(&m, d, b, q).unwrap();
                let scale = long_wave_speed_m_s(&m, d, Polarisation::Longitudinal);
                assert!(
                    (p.group_velocity_m_s - fd).abs() < 1e-6 * scale,
                    "{d} {b} {f}: {} vs {fd}",
                    p.group_velocity_m_s
                );
            }
        }
    }
}

/// At the axis zone edge S touches OS: the group velocity there is the limit from inside the
/// zone, `dω/dq = ω₀·(Lc/4)·cos(π/4)` with `ω₀² = (16/3)·k_d/m`, not the zero of a symmetric
/// average.
#[test]
fn group_velocity_at_the_degenerate_zone_edge_is_the_inner_limit() {
    let m = material(0.2);
    let edge = PI / m.lc_m();
    let w0 = (16.0 / 3.0 * m.diagonal_bar_stiffness_n_m() / m.node_mass_kg()).sqrt();
    let want = w0 * m.lc_m() / 4.0 * (PI / 4.0).cos();
    let s = branch_point(&m, WaveDirection::X, Branch::S, edge).unwrap();
    assert!((s.group_velocity_m_s / want - 1.0).abs() < 1e-9, "{s:?} vs {want}");
    let os = branch_point(&m, WaveDirection::X, Branch::OpticalS, edge).unwrap();
    assert!((os.group_velocity_m_s / -want - 1.0).abs() < 1e-9, "{os:?}");
    let h = 1e-6 * edge;
    let w = |q| branch_point(&m, WaveDirection::X, Branch::S, q).unwrap().omega_rad_s;
    assert!(((w(edge) - w(edge - h)) / h / want - 1.0).abs() < 1e-5);
}

#[test]
fn f_max_is_where_the_phase_velocity_departs_by_the_tolerance() {
    for nu in [0.1, 0.2, 0.25, 0.3, 0.45] {
        let m = material(nu);
        for tol in [0.01, DEFAULT_TOLERANCE, 0.08] {
            let band = usable_band(&m, tol).unwrap();
            assert_eq!(band.branches.len(), 4);
            for b in &band.branches {
                assert!(b.reached);
                assert!((b.departure().abs() - tol).abs() < 1e-9, "ν {nu} ε {tol}: {b:?}");
                // Below it the branch stays inside the tolerance (dispersion is monotone).
                for i in 1..50 {
                    let q = b.point.wavenumber_rad_m * i as f64 / 50.0;
                    let p = branch_point(&m, b.direction, b.branch, q).unwrap();
                    assert!((p.phase_velocity_m_s / b.long_wave_speed_m_s - 1.0).abs() < tol);
                }
                assert!(b.point.frequency_hz >= band.f_max_hz);
            }
            // The S limit along an axis: sinc(x*) = 1 − ε, f = 2(1−ε)x*/π · Cs/Lc for any ν.
            let mut lo_hi = (0.0, PI / 2.0);
            for _ in 0..100 {
                let mid = 0.5 * (lo_hi.0 + lo_hi.1);
                if sinc(mid) > 1.0 - tol { lo_hi.0 = mid } else { lo_hi.1 = mid }
            }
            let x = lo_hi.0;
            let s = band.branches.iter().find(|b| b.branch == Branch::S).unwrap();
            let want = 2.0 * (1.0 - tol) * x / PI * band.cs_m_s / m.lc_m();
            assert!((s.point.frequency_hz / want - 1.0).abs() < 1e-9, "ν {nu} ε {tol}");
            assert!((s.point.wavelength_per_module - PI / (2.0 * x)).abs() < 1e-8);
        }
    }
    // The paper lattice at 5 %: S along x at 0.3338·Cs/Lc, and P above ν ≈ 0.2527.
    let band = usable_band(&paper(), DEFAULT_TOLERANCE).unwrap();
    assert_eq!((band.limiting.branch, band.limiting.direction), (Branch::S, WaveDirection::X));
    assert!((band.f_max_per_cs_over_lc(&paper()) - 0.3338).abs() < 5e-5);
    assert!((band.f_max_hz - 5078.4).abs() < 0.1, "{}", band.f_max_hz);
    assert_eq!(usable_band(&material(0.25), 0.05).unwrap().limiting.branch, Branch::S);
    assert_eq!(usable_band(&material(0.26), 0.05).unwrap().limiting.branch, Branch::P);
}

/// `f_max ∝ C_s/Lc`: E ×4 doubles the speeds, Lc ÷2 doubles the frequency again.
#[test]
fn f_max_scales_with_cs_over_lc() {
    let a = usable_band(&paper(), 0.05).unwrap();
    let b = usable_band(&LatticeMaterial::new(8e10, 0.2, 2400.0, 0.05).unwrap(), 0.05).unwrap();
    assert!((b.f_max_hz / a.f_max_hz - 4.0).abs() < 1e-9);
    assert!((b.optical.point.frequency_hz / a.optical.point.frequency_hz - 4.0).abs() < 1e-9);
    assert!((b.limiting.point.wavelength_per_module - a.limiting.point.wavelength_per_module).abs() < 1e-9);
}

#[test]
fn optical_branches_start_at_the_axis_zone_edge() {
    for nu in [0.1, 0.2, 0.25, 0.4] {
        let m = material(nu);
        let band = usable_band(&m, DEFAULT_TOLERANCE).unwrap();
        let want = 2f64.sqrt() * band.cs_m_s / (PI * m.lc_m());
        let o = band.optical;
        assert_eq!(o.branch, Branch::OpticalS);
        assert!((o.point.frequency_hz / want - 1.0).abs() < 1e-9, "ν {nu}: {o:?}");
        assert!((o.point.wavenumber_rad_m * m.lc_m() / PI - 1.0).abs() < 1e-9);
        // The optical branches exist: non-zero at k = 0.
        let gamma = bloch_spectrum(&m, [0.0; 3]);
        assert!(gamma[..3].iter().all(|w| w.abs() < 1e-6 * gamma[5]));
        assert!(gamma[3..].iter().all(|w| *w > 0.1 * gamma[5]));
        // Sampled over the whole zone the fourth band goes no lower.
        let (f4, _) = lowest_optical_in_zone(&m, 9).unwrap();
        assert!((f4 / o.point.frequency_hz - 1.0).abs() < 1e-9, "ν {nu}: {f4}");
        assert!(band.resolved_hz() == band.f_max_hz);
    }
}

#[test]
fn prototype_scale_divides_frequencies() {
    assert!((prototype_frequency_hz(5078.4, 1e4).unwrap() - 0.50784).abs() < 1e-12);
    assert!(prototype_frequency_hz(1.0, 0.0).is_err());
}

fn refused_param(e: DispersionError) -> &'static str {
    match e {
        DispersionError::InvalidParameter { parameter, .. } => parameter,
        DispersionError::InvalidBranch { .. } => "branch",
    }
}

#[test]
fn out_of_range_inputs_are_refused_by_name() {
    let new = LatticeMaterial::new;
    for nu in [0.0, 0.5, -0.1, 0.7, f64::NAN] {
        let e = new(2e10, nu, 2400.0, 0.1).unwrap_err();
        assert_eq!(refused_param(e.clone()), "poisson");
        assert!(e.to_string().contains("0 < poisson < 0.5"), "{e}");
    }
    for v in [0.0, -1.0, f64::INFINITY, f64::NAN] {
        assert_eq!(refused_param(new(v, 0.2, 2400.0, 0.1).unwrap_err()), "young_pa");
        assert_eq!(refused_param(new(2e10, 0.2, v, 0.1).unwrap_err()), "density_kg_m3");
        assert_eq!(refused_param(new(2e10, 0.2, 2400.0, v).unwrap_err()), "lc_m");
    }
    let e = new(2e10, 0.2, 2400.0, -0.1).unwrap_err();
    assert_eq!(e.to_string(), "lc_m = -0.1 is not allowed: a finite lc_m > 0 m");
    let m = paper();
    for t in [0.0, 1.0, -0.05, f64::NAN] {
        assert_eq!(refused_param(usable_band(&m, t).unwrap_err()), "tolerance");
    }
    let edge = WaveDirection::X.zone_edge_rad_m(0.1);
    for q in [-1.0, edge * 1.0001, f64::NAN] {
        assert_eq!(refused_param(branch_point(&m, WaveDirection::X, Branch::S, q).unwrap_err()), "wavenumber_rad_m");
        assert!(bloch_modes(&m, WaveDirection::X, q).is_err());
    }
    assert!(branch_point(&m, WaveDirection::BodyDiagonal, Branch::S, edge * 1.7).is_ok());
    assert_eq!(refused_param(departure_limit(&m, WaveDirection::X, Branch::OpticalS, 0.05).unwrap_err()), "branch");
    assert_eq!(refused_param(optical_minimum(&m, WaveDirection::X, Branch::P).unwrap_err()), "branch");
    assert_eq!(refused_param(usable_band_along(&m, 0.05, &[]).unwrap_err()), "directions");
    assert_eq!(refused_param(lowest_optical_in_zone(&m, 1).unwrap_err()), "samples_per_axis");
    assert_eq!(refused_param(prototype_frequency_hz(-1.0, 1e4).unwrap_err()), "model_hz");
    assert_eq!(refused_param(prototype_frequency_hz(1.0, f64::NAN).unwrap_err()), "length_scale");
}
