//! BSSA14: Boore, Stewart, Seyhan & Atkinson (2014), NGA-West2 equations for RotD50 PGA, PGV and
//! 5%-damped PSA of shallow crustal earthquakes in active regions.
//!
//! ```text
//! ln Y = F_E(M, mech) + F_P(R_JB, M) + F_S(V_S30, R_JB, M, Z_1.0)                        (eq. 1)
//! F_E = e_mech + e4·(M − Mh) + e5·(M − Mh)²     M ≤ Mh                                  (eq. 2)
//!     = e_mech + e6·(M − Mh)                    M > Mh        e_mech = e1 SS, e2 NS, e3 RS
//! F_P = [c1 + c2·(M − M_ref)]·ln(R/R_ref) + (c3 + Δc3)·(R − R_ref),  R = √(R_JB² + h²)   (eq. 3–4)
//! F_S = ln F_lin + ln F_nl + F_δz1                                                      (eq. 5)
//! ln F_lin = c·ln(min(V_S30, V_c)/V_ref)                                                (eq. 6)
//! ln F_nl  = f1 + f2·ln((PGA_r + f3)/f3)                                                (eq. 7)
//! f2 = f4·[exp(f5·(min(V_S30, 760) − 360)) − exp(f5·(760 − 360))]                       (eq. 8)
//! F_δz1 = f6·δz1 if δz1 ≤ f7/f6, else f7, for T ≥ 0.65 s (0 below, and for PGA/PGV)   (eq. 9–10)
//! δz1 = Z_1.0 − μ_z1(V_S30), μ_z1 the California relation of Chiou & Youngs (2014)      (eq. 11)
//! ```
//! PGA_r is the median PGA of the same rupture and R_JB on reference rock (V_S30 = 760 m/s,
//! F_S = 0). Y is in g (PGA, PSA) or cm/s (PGV). With `Z_1.0` unknown δz1 = 0, the authors'
//! default. Global/California anelastic attenuation (Δc3 = 0). Mechanism terms e1–e3 are used (the
//! "unspecified" e0 is not offered: the rupture always has a mechanism).
//!
//! Aleatory variability (eq. 13–17), with φ and τ in natural log:
//! ```text
//! τ(M) = τ1 for M ≤ 4.5; τ1 + (τ2 − τ1)(M − 4.5) for 4.5 < M < 5.5; τ2 for M ≥ 5.5
//! φ(M) = the same with φ1, φ2
//! φ(M, R_JB) = φ(M) + Δφ_R·clamp(ln(R_JB/R1)/ln(R2/R1), 0, 1)
//! φ(M, R_JB, V_S30) = φ(M, R_JB) − Δφ_V·clamp(ln(V2/V_S30)/ln(V2/V1), 0, 1)
//! ```
//! Coefficients: `tables.rs` (source named there). Ranges (the paper's): M 3–8.5 for strike-slip
//! and reverse, 3–7 for normal faults; R_JB 0–400 km; V_S30 150–1500 m/s.

use super::tables::{BSSA14, BSSA14_PERIODS, Bssa14Row};
use super::{Estimate, Limits, Mechanism, Quantity, Range, Rupture, Site};

const M_REF: f64 = 4.5;
const R_REF: f64 = 1.0;
const V_REF: f64 = 760.0;
const F1: f64 = 0.0;
const F3: f64 = 0.1;
const V1: f64 = 225.0;
const V2: f64 = 300.0;
/// Δc3 for the global (California, Taiwan) attenuation.
const DC3: f64 = 0.0;

/// The ranges of BSSA14.
pub const LIMITS: Limits = Limits {
    mw_strike_slip: Range { quantity: Quantity::Magnitude, low: 3.0, high: 8.5 },
    mw_reverse: Range { quantity: Quantity::Magnitude, low: 3.0, high: 8.5 },
    mw_normal: Range { quantity: Quantity::Magnitude, low: 3.0, high: 7.0 },
    distance: Range { quantity: Quantity::RJb, low: 0.0, high: 400.0 },
    vs30: Range { quantity: Quantity::Vs30, low: 150.0, high: 1500.0 },
    periods_s: [0.01, 10.0],
};

const N_PSA: usize = BSSA14_PERIODS.len();

/// The tabulated PSA periods (s).
pub const PERIODS: [f64; N_PSA] = BSSA14_PERIODS;

const PGA_ROW: usize = N_PSA;

/// ln Y (g or cm/s) of row `c` on reference rock (F_S = 0).
fn ln_reference(c: &Bssa14Row, m: f64, mech: Mechanism, r_jb: f64) -> f64 {
    let e = match mech {
        Mechanism::StrikeSlip => c.e1,
        Mechanism::Normal => c.e2,
        Mechanism::Reverse => c.e3,
    };
    let f_e = if m <= c.mh { e + c.e4 * (m - c.mh) + c.e5 * (m - c.mh).powi(2) } else { e + c.e6 * (m - c.mh) };
    let r = r_jb.hypot(c.h);
    let f_p = (c.c1 + c.c2 * (m - M_REF)) * (r / R_REF).ln() + (c.c3 + DC3) * (r - R_REF);
    f_e + f_p
}

/// The site term F_S of row `c` for reference-rock PGA `pga_r` (g).
fn site_term(c: &Bssa14Row, vs30: f64, z1_km: Option<f64>, pga_r: f64) -> f64 {
    let f_lin = c.c * (vs30.min(c.vc) / V_REF).ln();
    let f2 = c.f4 * ((c.f5 * (vs30.min(760.0) - 360.0)).exp() - (c.f5 * (760.0 - 360.0)).exp());
    let f_nl = F1 + f2 * ((pga_r + F3) / F3).ln();
    let f_dz1 = match z1_km {
        Some(z1) if c.t >= 0.65 => {
            let dz1 = z1 - super::z1_cy14_california_km(vs30);
            if dz1 <= c.f7 / c.f6 { c.f6 * dz1 } else { c.f7 }
        }
        _ => 0.0,
    };
    f_lin + f_nl + f_dz1
}

/// The linear site term of PGA, `c·ln(min(V_S30, V_c)/760)` (eq. 6 at the PGA row): ln of the
/// factor from a site of `vs30_m_s` to reference rock (760 m/s) is its negative.
pub fn pga_linear_site_ln(vs30_m_s: f64) -> f64 {
    let c = &BSSA14[PGA_ROW];
    c.c * (vs30_m_s.min(c.vc) / V_REF).ln()
}

/// The BSSA14 site amplification of a site of `vs30_m_s` relative to one of `vref_m_s`,
/// `exp(F_S(V_S30) − F_S(V_ref))` with F_S the linear and nonlinear terms (eqs. 6–8; no basin
/// term), for a reference-rock PGA `pga_760_g` (g), at each tabulated PSA period: `(T, factor)`,
/// T ascending, then PGA as `(0, factor)`. The nonlinear term is evaluated at both sites, as the
/// Broadband Platform's `wcc_siteamp14` does (it vanishes at 760 m/s and above).
pub fn site_amplification(vs30_m_s: f64, vref_m_s: f64, pga_760_g: f64) -> Vec<(f64, f64)> {
    BSSA14[..=PGA_ROW]
        .iter()
        .map(|c| (c.t, (site_term(c, vs30_m_s, None, pga_760_g) - site_term(c, vref_m_s, None, pga_760_g)).exp()))
        .collect()
}

/// τ and φ of row `c`.
fn sigma(c: &Bssa14Row, m: f64, r_jb: f64, vs30: f64) -> (f64, f64) {
    let w = (m - 4.5).clamp(0.0, 1.0);
    let tau = c.tau1 + (c.tau2 - c.tau1) * w;
    let phi_m = c.phi1 + (c.phi2 - c.phi1) * w;
    let fr = if r_jb <= c.r1 { 0.0 } else { ((r_jb / c.r1).ln() / (c.r2 / c.r1).ln()).min(1.0) };
    let fv = if vs30 >= V2 { 0.0 } else { ((V2 / vs30).ln() / (V2 / V1).ln()).min(1.0) };
    (tau, phi_m + c.dphi_r * fr - c.dphi_v * fv)
}

/// BSSA14 at table row `row` (PSA rows by period, then PGA, then PGV).
pub(super) fn estimate(row: usize, rupture: &Rupture, site: &Site) -> Estimate {
    let (m, mech, r_jb, vs30) = (rupture.mw, rupture.mechanism, site.r_jb_km, site.vs30_m_s);
    let c = &BSSA14[row];
    let pga_r = ln_reference(&BSSA14[PGA_ROW], m, mech, r_jb).exp();
    let ln_y = ln_reference(c, m, mech, r_jb) + site_term(c, vs30, site.z1_km, pga_r);
    let (tau, phi) = sigma(c, m, r_jb, vs30);
    Estimate { ln_y, tau, phi }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_has_pga_then_pgv_after_increasing_periods() {
        assert_eq!(BSSA14[PGA_ROW].t, 0.0);
        assert_eq!(BSSA14[PGA_ROW + 1].t, -1.0);
        assert_eq!(BSSA14.len(), N_PSA + 2);
        assert!(PERIODS.windows(2).all(|w| w[0] < w[1]));
        assert!(PERIODS.iter().zip(&BSSA14).all(|(p, c)| *p == c.t));
        assert_eq!((PERIODS[0], PERIODS[N_PSA - 1], N_PSA), (0.01, 10.0, 105));
        // The basin coefficients are tabulated (not the −9.9 placeholder) exactly where the basin
        // term applies.
        assert!(BSSA14.iter().all(|c| (c.t >= 0.65) == (c.f6 != -9.9)));
    }

    #[test]
    fn the_site_amplification_is_one_between_equal_sites_and_follows_the_linear_term_on_rock() {
        for (t, a) in site_amplification(500.0, 500.0, 0.3) {
            assert!((a - 1.0).abs() < 1e-12, "{t}: {a}");
        }
        // Above 760 m/s the nonlinear term vanishes: the ratio is that of the linear terms, with
        // V_S30 capped at V_c (both sites above V_c: no amplification at all).
        let amp = site_amplification(760.0, 1200.0, 0.5);
        for ((t, a), c) in amp.iter().zip(&BSSA14) {
            let expected = (c.c * ((760.0f64).min(c.vc) / 760.0).ln() - c.c * (1200.0f64.min(c.vc) / 760.0).ln()).exp();
            assert!((a - expected).abs() < 1e-12 * expected, "{t}");
        }
        assert!(site_amplification(1600.0, 3464.0, 0.5).iter().all(|(_, a)| (a - 1.0).abs() < 1e-12));
        // A soft site amplifies less under strong shaking (the nonlinear term, f4 < 0 at PGA).
        let weak = site_amplification(300.0, 760.0, 0.01).last().unwrap().1;
        let strong = site_amplification(300.0, 760.0, 0.8).last().unwrap().1;
        assert!(weak > strong && strong > 0.5, "{weak} {strong}");
        assert_eq!(site_amplification(400.0, 760.0, 0.1).last().unwrap().0, 0.0);
        assert!((pga_linear_site_ln(760.0)).abs() < 1e-15);
    }

    #[test]
    fn reference_rock_has_no_site_term() {
        // At V_S30 = 760 m/s both F_lin and F_nl vanish, whatever PGA_r.
        for c in &BSSA14 {
            assert!(site_term(c, 760.0, None, 0.5).abs() < 1e-12);
        }
    }

    #[test]
    fn the_basin_term_is_linear_in_delta_z1_up_to_its_cap_from_0_65_s() {
        let vs30 = 400.0;
        let mu = super::super::z1_cy14_california_km(vs30);
        let c = BSSA14.iter().find(|c| c.t == 2.0).unwrap();
        let basin = |z1: Option<f64>| site_term(c, vs30, z1, 0.1) - site_term(c, vs30, None, 0.1);
        // On the relation's centre, and without Z_1.0: no basin term.
        assert!(basin(Some(mu)).abs() < 1e-12);
        // A shallower basin: f6·δz1 (f6 > 0 at 2 s, so negative).
        assert!(c.f6 > 0.0);
        assert!((basin(Some(mu * 0.5)) - c.f6 * (-0.5 * mu)).abs() < 1e-12);
        // A deep basin: capped at f7.
        assert!((basin(Some(mu + 2.0 * c.f7 / c.f6)) - c.f7).abs() < 1e-12);
        // Below 0.65 s (and for PGA, PGV) Z_1.0 changes nothing.
        for c in BSSA14.iter().filter(|c| c.t < 0.65) {
            assert_eq!(site_term(c, vs30, Some(1.0), 0.1), site_term(c, vs30, None, 0.1));
        }
    }

    #[test]
    fn sigma_follows_its_piecewise_definition() {
        let c = &BSSA14[PGA_ROW];
        // Small M, near, stiff: τ1 and φ1.
        assert_eq!(sigma(c, 4.0, 10.0, 760.0), (c.tau1, c.phi1));
        // Large M, far (R_JB ≥ R2), soft (V_S30 ≤ V1): τ2 and φ2 + Δφ_R − Δφ_V.
        let (t, p) = sigma(c, 7.0, 300.0, 200.0);
        assert_eq!(t, c.tau2);
        assert!((p - (c.phi2 + c.dphi_r - c.dphi_v)).abs() < 1e-15);
        // Halfway in M, geometric middle in R and V.
        let (t, p) = sigma(c, 5.0, (c.r1 * c.r2).sqrt(), (V1 * V2).sqrt());
        assert!((t - 0.5 * (c.tau1 + c.tau2)).abs() < 1e-15);
        assert!((p - (0.5 * (c.phi1 + c.phi2) + 0.5 * c.dphi_r - 0.5 * c.dphi_v)).abs() < 1e-12);
    }
}
