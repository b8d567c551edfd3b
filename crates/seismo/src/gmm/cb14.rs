//! CB14: Campbell & Bozorgnia (2014), NGA-West2 model for RotD50 PGA, PGV and 5%-damped PSA of
//! shallow crustal earthquakes in active regions, with its California/global defaults.
//!
//! ```text
//! ln Y = f_mag + f_dis + f_flt + f_hng + f_site + f_sed + f_hyp + f_dip + f_atn               (eq. 1)
//! f_mag = c0 + c1·M + c2·(M − 4.5)₊ + c3·(M − 5.5)₊ + c4·(M − 6.5)₊,  (x)₊ = max(x, 0)      (eq. 2)
//! f_dis = (c5 + c6·M)·ln √(R_rup² + c7²)                                                  (eq. 3)
//! f_flt = (c8·F_RV + c9·F_NM)·clamp(M − 4.5, 0, 1),  c8 = 0                               (eq. 4–6)
//! f_hng = c10·f_Rx·f_Rrup·f_M·f_Z·f_δ                                                     (eq. 7–16)
//!   f_Rx = 0 (R_x < 0); h1 + h2·x + h3·x², x = R_x/R1 (0 ≤ R_x < R1);
//!          max(h4 + h5·y + h6·y², 0), y = (R_x − R1)/(R2 − R1) (R_x ≥ R1);  R1 = W cos δ, R2 = 62M − 350
//!   f_Rrup = (R_rup − R_JB)/R_rup (1 at R_rup = 0)
//!   f_M = 0 (M ≤ 5.5); (M − 5.5)·[1 + a2(M − 6.5)] (5.5 < M ≤ 6.5); 1 + a2(M − 6.5) (M > 6.5)
//!   f_Z = 1 − 0.06·Z_tor (Z_tor ≤ 16.66 km), 0 deeper;  f_δ = (90 − δ)/45
//! f_site = c11·ln(V/k1) + k2·{ln[A1100 + c(V/k1)ⁿ] − ln(A1100 + c)}     V_S30 ≤ k1
//!        = (c11 + k2·n)·ln(V/k1)                                     V_S30 > k1         (eq. 17–18)
//! f_sed = c14·(Z2.5 − 1) (Z2.5 ≤ 1 km); 0 (1 < Z2.5 ≤ 3 km);
//!         c16·k3·e^−0.75·[1 − exp(−0.25·(Z2.5 − 3))] (Z2.5 > 3 km)                        (eq. 20)
//! f_hyp = clamp(Z_hyp − 7, 0, 13)·[c17 + (c18 − c17)·clamp(M − 5.5, 0, 1)]                (eq. 21–23)
//! f_dip = c19·δ·clamp(5.5 − M, 0, 1)                                                      (eq. 24)
//! f_atn = c20·(R_rup − 80)₊                                                               (eq. 25)
//! ```
//! V = V_S30 (m/s), c = 1.88, n = 1.18, h4 = 1; A1100 is the median PGA (g) of the same rupture
//! and site on V_S30 = 1100 m/s with the Z2.5 of the California relation there (0.398 km), where
//! every k1 < 1100 m/s makes f_site linear. PSA at T < 0.25 s is raised to PGA where it falls below
//! it (eq. 1; the 0.25 s row itself is not). Y in g (PGA, PSA) or cm/s (PGV). Not carried: the
//! Japan site and basin terms (S_J = 0) and the regional anelastic attenuation (Δc20 = 0):
//! California/global.
//!
//! Aleatory variability (eq. 27–32), natural log, with φ_lnAF = 0.3 and ρ = ρ_lnPGA,lnY:
//! ```text
//! τ_lnY(M) = τ2 + (τ1 − τ2)·clamp(5.5 − M, 0, 1),  φ_lnY(M) the same with φ1, φ2; likewise for PGA
//! φ_B = √(φ_lnY² − φ_lnAF²),  φ_PGA,B = √(φ_lnPGA² − φ_lnAF²)
//! α = k2·A1100·{[A1100 + c(V/k1)ⁿ]⁻¹ − (A1100 + c)⁻¹} for V_S30 < k1, 0 otherwise        (eq. 31)
//! τ = √(τ_lnY² + α²·τ_lnPGA² + 2αρ·τ_lnY·τ_lnPGA)                                         (eq. 29)
//! φ = √(φ_B² + φ_lnAF² + α²·φ_PGA,B² + 2αρ·φ_B·φ_PGA,B)                                   (eq. 30)
//! ```
//! Inputs the rupture or site may lack, and what is used then (the paper's recommendations):
//! - Z_hyp ([`hypo_depth_km`], eq. 35–37): Z_tor + ΔZ, ln ΔZ = min(f_M + f_δ, ln(0.9·(Z_bor −
//!   Z_tor))), f_M = −4.317 + 0.984·M (M < 6.75), 2.325 (M ≥ 6.75), f_δ = 0.0445·(δ − 40) (δ ≤ 40°),
//!   0 (δ > 40°), Z_bor = Z_tor + W sin δ.
//! - Z2.5 ([`z25_california_km`], eq. 33): exp(7.089 − 1.144·ln V_S30) km.
//! - W is always given ([`Rupture::width_km`]); a caller without one can take [`width_km`] (eq. 39:
//!   min(√(10^((M − 4.07)/0.98)), (Z_bot − Z_tor)/sin δ)) with Z_bot = [`DEFAULT_ZBOT_KM`] = 15 km.
//!
//! Coefficients: `tables_nga2.rs` (sources named there). Ranges (the paper's): M 3.3–8.5 for
//! strike-slip, 3.3–8.0 for reverse and 3.3–7.5 for normal faults; R_rup 0–300 km; V_S30
//! 150–1500 m/s (and Z2.5 0–10 km, Z_tor and Z_hyp 0–20 km, δ 15–90°, not flagged).

use super::tables_nga2::{CB14, CB14_PERIODS, Cb14Row};
use super::{Estimate, Limits, Mechanism, Quantity, Range, Rupture, Site};

const C: f64 = 1.88;
const N: f64 = 1.18;
const H4: f64 = 1.0;
/// The reverse-faulting coefficient, zero at every period.
const C8: f64 = 0.0;
const PHI_LNAF: f64 = 0.3;
/// V_S30 of the reference rock of A1100 (m/s).
const V_REF: f64 = 1100.0;

/// The depth to the bottom of the seismogenic crust Z_bot (km) the paper suggests for eq. 39 when it
/// is unknown.
pub const DEFAULT_ZBOT_KM: f64 = 15.0;

/// The ranges of CB14.
pub const LIMITS: Limits = Limits {
    mw_strike_slip: Range { quantity: Quantity::Magnitude, low: 3.3, high: 8.5 },
    mw_reverse: Range { quantity: Quantity::Magnitude, low: 3.3, high: 8.0 },
    mw_normal: Range { quantity: Quantity::Magnitude, low: 3.3, high: 7.5 },
    distance: Range { quantity: Quantity::RRup, low: 0.0, high: 300.0 },
    vs30: Range { quantity: Quantity::Vs30, low: 150.0, high: 1500.0 },
    periods_s: [0.01, 10.0],
};

const N_PSA: usize = CB14_PERIODS.len();

/// The tabulated PSA periods (s).
pub const PERIODS: [f64; N_PSA] = CB14_PERIODS;

const PGA_ROW: usize = N_PSA;

/// Z2.5 (km) of the California V_S30 relation (eq. 33): exp(7.089 − 1.144·ln V_S30).
pub fn z25_california_km(vs30_m_s: f64) -> f64 {
    (7.089 - 1.144 * vs30_m_s.ln()).exp()
}

/// The hypocentral depth Z_hyp (km) CB14 estimates for a rupture (eq. 35–37): Z_tor + ΔZ, ΔZ from
/// M and δ, at most 90% of the rupture's depth extent W sin δ.
pub fn hypo_depth_km(rupture: &Rupture) -> f64 {
    let (m, dip, ztor) = (rupture.mw, rupture.dip_deg, rupture.ztor_km);
    let f_m = if m < 6.75 { -4.317 + 0.984 * m } else { 2.325 };
    let f_dip = if dip <= 40.0 { 0.0445 * (dip - 40.0) } else { 0.0 };
    let extent = rupture.width_km * dip.to_radians().sin();
    ztor + (f_m + f_dip).min((0.9 * extent).ln()).exp()
}

/// The down-dip width W (km) CB14 estimates for a rupture of magnitude `mw`, dip `dip_deg` and top
/// `ztor_km` in a seismogenic crust whose bottom is at `zbot_km` (eq. 39; [`DEFAULT_ZBOT_KM`] when
/// unknown): min(√(10^((M − 4.07)/0.98)), (Z_bot − Z_tor)/sin δ).
pub fn width_km(mw: f64, dip_deg: f64, ztor_km: f64, zbot_km: f64) -> f64 {
    10f64.powf((mw - 4.07) / 0.98).sqrt().min((zbot_km - ztor_km) / dip_deg.to_radians().sin())
}

/// f_hng: the hanging-wall term.
fn f_hng(c: &Cb14Row, rupture: &Rupture, site: &Site) -> f64 {
    let (m, dip, ztor, rx) = (rupture.mw, rupture.dip_deg, rupture.ztor_km, site.r_x_km);
    if rx < 0.0 || m <= 5.5 || ztor > 16.66 || dip >= 90.0 {
        return 0.0;
    }
    let r1 = rupture.width_km * dip.to_radians().cos();
    let r2 = 62.0 * m - 350.0;
    let f_rx = if rx < r1 {
        let x = rx / r1;
        c.h1 + c.h2 * x + c.h3 * x * x
    } else {
        let y = (rx - r1) / (r2 - r1);
        // `max` also maps the NaN of R2 = R1 (M ≈ 5.65 on a flat fault) to 0.
        (H4 + c.h5 * y + c.h6 * y * y).max(0.0)
    };
    let f_rrup = if site.r_rup_km == 0.0 { 1.0 } else { (site.r_rup_km - site.r_jb_km) / site.r_rup_km };
    let f_m = if m <= 6.5 { (m - 5.5) * (1.0 + c.a2 * (m - 6.5)) } else { 1.0 + c.a2 * (m - 6.5) };
    let f_z = 1.0 - 0.06 * ztor;
    let f_dip = (90.0 - dip) / 45.0;
    c.c10 * f_rx * f_rrup * f_m * f_z * f_dip
}

/// ln Y without the site terms f_site and f_sed.
fn ln_source_path(c: &Cb14Row, rupture: &Rupture, site: &Site, zhyp: f64) -> f64 {
    let (m, dip, r_rup) = (rupture.mw, rupture.dip_deg, site.r_rup_km);
    let f_mag = c.c0 + c.c1 * m + c.c2 * (m - 4.5).max(0.0) + c.c3 * (m - 5.5).max(0.0) + c.c4 * (m - 6.5).max(0.0);
    let f_dis = (c.c5 + c.c6 * m) * r_rup.hypot(c.c7).ln();
    let f_flt = match rupture.mechanism {
        Mechanism::Reverse => C8,
        Mechanism::Normal => c.c9,
        Mechanism::StrikeSlip => 0.0,
    } * (m - 4.5).clamp(0.0, 1.0);
    let f_hyp = (zhyp - 7.0).clamp(0.0, 13.0) * (c.c17 + (c.c18 - c.c17) * (m - 5.5).clamp(0.0, 1.0));
    let f_dip = c.c19 * dip * (5.5 - m).clamp(0.0, 1.0);
    let f_atn = c.c20 * (r_rup - 80.0).max(0.0);
    f_mag + f_dis + f_flt + f_hng(c, rupture, site) + f_hyp + f_dip + f_atn
}

/// f_site: the shallow site response for reference-rock PGA `a1100` (g; unused above k1).
fn f_site(c: &Cb14Row, vs30: f64, a1100: f64) -> f64 {
    let ratio = vs30 / c.k1;
    if vs30 <= c.k1 {
        c.c11 * ratio.ln() + c.k2 * ((a1100 + C * ratio.powf(N)).ln() - (a1100 + C).ln())
    } else {
        (c.c11 + c.k2 * N) * ratio.ln()
    }
}

/// f_sed: the basin response for a depth to V_S = 2.5 km/s of `z25` (km).
fn f_sed(c: &Cb14Row, z25: f64) -> f64 {
    if z25 <= 1.0 {
        c.c14 * (z25 - 1.0)
    } else if z25 <= 3.0 {
        0.0
    } else {
        c.c16 * c.k3 * (-0.75f64).exp() * (1.0 - (-0.25 * (z25 - 3.0)).exp())
    }
}

/// τ and φ of row `c` (`p` the PGA row) for reference-rock PGA `a1100` (g).
fn sigma(c: &Cb14Row, p: &Cb14Row, m: f64, vs30: f64, a1100: f64) -> (f64, f64) {
    let w = (5.5 - m).clamp(0.0, 1.0);
    let tau_y = c.tau2 + (c.tau1 - c.tau2) * w;
    let phi_y = c.phi2 + (c.phi1 - c.phi2) * w;
    let tau_pga = p.tau2 + (p.tau1 - p.tau2) * w;
    let phi_pga = p.phi2 + (p.phi1 - p.phi2) * w;
    let alpha =
        if vs30 < c.k1 { c.k2 * a1100 * (1.0 / (a1100 + C * (vs30 / c.k1).powf(N)) - 1.0 / (a1100 + C)) } else { 0.0 };
    let af2 = PHI_LNAF * PHI_LNAF;
    let phi_b = (phi_y * phi_y - af2).sqrt();
    let phi_pga_b = (phi_pga * phi_pga - af2).sqrt();
    let tau2 = tau_y * tau_y + alpha * alpha * tau_pga * tau_pga + 2.0 * alpha * c.rho * tau_y * tau_pga;
    let phi2 = phi_b * phi_b + af2 + alpha * alpha * phi_pga_b * phi_pga_b + 2.0 * alpha * c.rho * phi_b * phi_pga_b;
    (tau2.sqrt(), phi2.sqrt())
}

/// A1100: the median PGA (g) of the rupture and site on V_S30 = 1100 m/s with the Z2.5 of the
/// California relation there (f_site is linear there: every k1 < 1100 m/s).
fn a1100(rupture: &Rupture, site: &Site, zhyp: f64) -> f64 {
    let p = &CB14[PGA_ROW];
    (ln_source_path(p, rupture, site, zhyp) + f_site(p, V_REF, f64::NAN) + f_sed(p, z25_california_km(V_REF))).exp()
}

/// CB14 at table row `row` (PSA rows by period, then PGA, then PGV).
pub(super) fn estimate(row: usize, rupture: &Rupture, site: &Site) -> Estimate {
    let c = &CB14[row];
    let p = &CB14[PGA_ROW];
    let vs30 = site.vs30_m_s;
    let zhyp = rupture.hypo_depth_km.unwrap_or_else(|| hypo_depth_km(rupture));
    let z25 = site.z25_km.unwrap_or_else(|| z25_california_km(vs30));
    let a1100 = a1100(rupture, site, zhyp);
    let ln_at = |c: &Cb14Row| ln_source_path(c, rupture, site, zhyp) + f_site(c, vs30, a1100) + f_sed(c, z25);
    let mut ln_y = ln_at(c);
    if c.t > 0.0 && c.t < 0.25 {
        ln_y = ln_y.max(ln_at(p));
    }
    let (tau, phi) = sigma(c, p, rupture.mw, vs30, a1100);
    Estimate { ln_y, tau, phi }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rupture() -> Rupture {
        Rupture {
            mw: 7.0,
            mechanism: Mechanism::Reverse,
            dip_deg: 45.0,
            ztor_km: 0.0,
            width_km: 20.0,
            hypo_depth_km: Some(8.0),
        }
    }

    fn site() -> Site {
        Site {
            r_rup_km: 5.0,
            r_jb_km: 0.0,
            r_x_km: 5.0,
            r_y0_km: Some(0.0),
            vs30_m_s: 760.0,
            z1_km: None,
            z25_km: None,
            vs30_measured: true,
        }
    }

    #[test]
    fn the_table_has_pga_then_pgv_after_increasing_periods() {
        assert_eq!(CB14[PGA_ROW].t, 0.0);
        assert_eq!(CB14[PGA_ROW + 1].t, -1.0);
        assert_eq!(CB14.len(), N_PSA + 2);
        assert!(PERIODS.windows(2).all(|w| w[0] < w[1]));
        assert!(PERIODS.iter().zip(&CB14).all(|(p, c)| *p == c.t));
        assert_eq!((PERIODS[0], PERIODS[N_PSA - 1], N_PSA), (0.01, 10.0, 21));
        // A1100's rock is above k1 for every row, so its site term is linear and needs no A1100.
        assert!(CB14.iter().all(|c| c.k1 < V_REF));
        // φ_lnY > φ_lnAF everywhere, so φ_B is real.
        assert!(CB14.iter().all(|c| c.phi1.min(c.phi2) > PHI_LNAF));
    }

    #[test]
    fn magnitude_scaling_is_continuous_at_its_hinges() {
        let s = site();
        for c in &CB14 {
            for hinge in [4.5, 5.5, 6.5] {
                let at = |m: f64| ln_source_path(c, &Rupture { mw: m, ..rupture() }, &s, 8.0);
                let (lo, hi) = (at(hinge - 1e-9), at(hinge + 1e-9));
                assert!((lo - hi).abs() < 1e-6, "T = {}: ln Y jumps by {} at M = {hinge}", c.t, hi - lo);
            }
        }
    }

    #[test]
    fn the_reference_rock_site_term_vanishes_at_k1_and_is_continuous_there() {
        // At V_S30 = k1 both branches of f_site are zero, whatever A1100; α is zero from k1 up.
        for c in &CB14 {
            for a1100 in [0.01, 0.5, 2.0] {
                assert!(f_site(c, c.k1, a1100).abs() < 1e-12, "T = {}", c.t);
                assert!((f_site(c, c.k1 * (1.0 - 1e-9), a1100) - f_site(c, c.k1 * (1.0 + 1e-9), a1100)).abs() < 1e-6);
            }
            let p = &CB14[PGA_ROW];
            let (t_lin, p_lin) = sigma(c, p, 6.0, c.k1, 0.3);
            assert!((t_lin - c.tau2).abs() < 1e-12 && (p_lin - c.phi2).abs() < 1e-12, "T = {}", c.t);
        }
    }

    #[test]
    fn a1100_is_the_models_own_pga_on_its_reference_rock() {
        // With Z2.5 left to the California relation, the PGA predicted on V_S30 = 1100 m/s is A1100.
        let (r, s) = (rupture(), site());
        let rock = Site { vs30_m_s: V_REF, z25_km: None, ..s };
        assert!((estimate(PGA_ROW, &r, &rock).ln_y - a1100(&r, &s, 8.0).ln()).abs() < 1e-12);
        // ... whatever the site's own V_S30 and Z2.5 are.
        let soft = Site { vs30_m_s: 200.0, z25_km: Some(5.0), ..s };
        assert_eq!(a1100(&r, &soft, 8.0), a1100(&r, &s, 8.0));
    }

    #[test]
    fn soft_soil_responds_nonlinearly_to_strong_rock_motion() {
        // k2 < 0 below 3 s: the amplification of a soft site falls as A1100 grows.
        let c = CB14.iter().find(|c| c.t == 0.2).unwrap();
        assert!(f_site(c, 200.0, 0.5) < f_site(c, 200.0, 0.05));
        // Above 3 s k2 = 0: linear.
        let c = CB14.iter().find(|c| c.t == 5.0).unwrap();
        assert_eq!(f_site(c, 200.0, 0.5), f_site(c, 200.0, 0.05));
    }

    #[test]
    fn the_basin_term_follows_its_three_branches() {
        let c = CB14.iter().find(|c| c.t == 3.0).unwrap();
        assert!((f_sed(c, 0.5) - c.c14 * -0.5).abs() < 1e-15);
        assert_eq!(f_sed(c, 1.0), 0.0);
        assert_eq!(f_sed(c, 2.0), 0.0);
        assert_eq!(f_sed(c, 3.0), 0.0);
        let deep = c.c16 * c.k3 * (-0.75f64).exp() * (1.0 - (-0.25f64).exp());
        assert!((f_sed(c, 4.0) - deep).abs() < 1e-15);
        // The default Z2.5 at 1100 m/s is the 0.398 km the authors use for A1100.
        assert!((z25_california_km(V_REF) - 0.398).abs() < 5e-4, "{}", z25_california_km(V_REF));
    }

    #[test]
    fn the_hanging_wall_term_vanishes_where_the_paper_says() {
        let c = &CB14[PGA_ROW];
        let (r, s) = (rupture(), site());
        // Above the rupture (R_x < R1 = 20 cos 45°): f_Rx = h1 + h2 x + h3 x², f_Rrup = 1 (R_JB = 0),
        // f_M = 1 + a2/2, f_Z = 1, f_δ = 1.
        let x = 5.0 / (20.0 * 45f64.to_radians().cos());
        let expected = c.c10 * (c.h1 + c.h2 * x + c.h3 * x * x) * (1.0 + 0.5 * c.a2);
        assert!((f_hng(c, &r, &s) - expected).abs() < 1e-12);
        assert!(f_hng(c, &r, &s) > 0.0);
        // Footwall, vertical fault, small magnitude, deep top: zero.
        assert_eq!(f_hng(c, &r, &Site { r_x_km: -5.0, ..s }), 0.0);
        assert_eq!(f_hng(c, &Rupture { dip_deg: 90.0, ..r }, &s), 0.0);
        assert_eq!(f_hng(c, &Rupture { mw: 5.5, ..r }, &s), 0.0);
        assert_eq!(f_hng(c, &Rupture { ztor_km: 16.7, ..r }, &s), 0.0);
        // The quadratic taper beyond R1 reaches zero at y = (R_x − R1)/(R2 − R1) ≈ 1.4 (R2 = 62M − 350
        // = 84 km) and is clipped there, never negative.
        let at_rx = |rx: f64| f_hng(c, &r, &Site { r_x_km: rx, r_jb_km: rx - 14.0, r_rup_km: rx - 13.0, ..s });
        assert!(at_rx(100.0) > 0.0);
        assert_eq!(at_rx(150.0), 0.0);
        // Continuous at R_x = R1: f1(R1) = h1 + h2 + h3 = 1.000 for PGA, f2(R1) = h4 = 1.
        let r1 = 20.0 * 45f64.to_radians().cos();
        let at = |rx: f64| f_hng(c, &r, &Site { r_x_km: rx, r_jb_km: 0.0, ..s });
        assert!((at(r1 - 1e-9) - at(r1 + 1e-9)).abs() < 2e-3 * c.c10);
    }

    #[test]
    fn the_default_hypocentre_follows_eq_35_to_37() {
        // M 7, δ 45°: ln ΔZ = min(2.325, ln(0.9·20 sin 45°)) = 2.325 (ΔZ = 10.2 km < 12.7 km).
        let r = Rupture { mw: 7.0, ..rupture() };
        assert!((hypo_depth_km(&r) - 2.325f64.exp()).abs() < 1e-12);
        // A narrow rupture caps ΔZ at 90% of its depth extent.
        let narrow = Rupture { width_km: 5.0, ztor_km: 2.0, ..r };
        assert!((hypo_depth_km(&narrow) - (2.0 + 0.9 * 5.0 * 45f64.to_radians().sin())).abs() < 1e-12);
        // M 5, δ 30°: ln ΔZ = −4.317 + 4.92 + 0.0445·(−10).
        let small = Rupture { mw: 5.0, dip_deg: 30.0, ..r };
        assert!((hypo_depth_km(&small) - (-4.317 + 0.984 * 5.0 - 0.445f64).exp()).abs() < 1e-12);
        // Eq. 39: M 6.5 is √(10^(2.43/0.98)) = 17.4 km wide unless the crust is thinner.
        assert!((width_km(6.5, 90.0, 0.0, 100.0) - 10f64.powf(2.43 / 0.98).sqrt()).abs() < 1e-12);
        assert_eq!(width_km(6.5, 30.0, 0.0, DEFAULT_ZBOT_KM), width_km(6.5, 90.0, 0.0, 100.0));
        assert!((width_km(7.5, 90.0, 3.0, DEFAULT_ZBOT_KM) - 12.0).abs() < 1e-12);
    }

    #[test]
    fn short_period_psa_is_raised_to_pga_below_0_25_s() {
        // Far from a large rupture on soft soil PSA(0.01 s) falls below PGA: it is raised to it.
        let r = Rupture { mw: 7.5, mechanism: Mechanism::StrikeSlip, dip_deg: 90.0, ..rupture() };
        let s = Site { r_rup_km: 150.0, r_jb_km: 150.0, r_x_km: 150.0, vs30_m_s: 180.0, ..site() };
        let pga = estimate(PGA_ROW, &r, &s).ln_y;
        let a1100 = a1100(&r, &s, 8.0);
        let z25 = z25_california_km(180.0);
        let mut raised = 0;
        for (i, c) in CB14.iter().enumerate().take(N_PSA) {
            let raw = ln_source_path(c, &r, &s, 8.0) + f_site(c, 180.0, a1100) + f_sed(c, z25);
            let e = estimate(i, &r, &s).ln_y;
            if c.t < 0.25 {
                assert_eq!(e, raw.max(pga), "T = {}", c.t);
                raised += (raw < pga) as usize;
            } else {
                assert_eq!(e, raw, "T = {}", c.t);
            }
        }
        assert!(raised > 0, "the case does not exercise the floor");
    }

    #[test]
    fn sigma_on_linear_ground_is_the_magnitude_dependent_one() {
        let c = &CB14[PGA_ROW];
        // Above k1: α = 0, τ = τ_lnY, φ = φ_lnY.
        let (t, p) = sigma(c, c, 5.0, 1000.0, 0.3);
        assert!((t - 0.5 * (c.tau1 + c.tau2)).abs() < 1e-12);
        assert!((p - 0.5 * (c.phi1 + c.phi2)).abs() < 1e-12);
        // For PGA itself (ρ = 1) on soft soil τ = τ_lnPGA·|1 + α|.
        let a1100 = 0.4;
        let alpha = c.k2 * a1100 * (1.0 / (a1100 + C * (200.0 / c.k1).powf(N)) - 1.0 / (a1100 + C));
        let (t, _) = sigma(c, c, 7.0, 200.0, a1100);
        assert!((t - c.tau2 * (1.0 + alpha).abs()).abs() < 1e-12);
    }
}
