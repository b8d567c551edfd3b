//! CY14: Chiou & Youngs (2014), update of their NGA model for RotD50 PGA, PGV and 5%-damped PSA of
//! shallow crustal earthquakes in active regions, with its California/global defaults.
//!
//! ```text
//! ln y_ref = c1 + (c1a + c1c/cosh(2(M − 4.5)₊))·F_RV + (c1b + c1d/cosh(2(M − 4.5)₊))·F_NM
//!            + (c7 + c7b/cosh(2(M − 4.5)₊))·ΔZ_tor + (c11 + c11b/cosh(2(M − 4.5)₊))·cos²δ
//!            + c2·(M − 6) + (c2 − c3)/c_n·ln(1 + exp(c_n·(c_M − M)))
//!            + c4·ln(R_rup + c5·cosh(c6·(M − c_HM)₊)) + (c4a − c4)·ln √(R_rup² + c_RB²)
//!            + [c_γ1 + c_γ2/cosh((M − c_γ3)₊)]·R_rup
//!            + c8·max(1 − (R_rup − 40)₊/30, 0)·min((M − 5.5)₊/0.8, 1)·exp(−c8a(M − c8b)²)·ΔDPP
//!            + c9·F_HW·cos δ·[c9a + (1 − c9a)·tanh(R_x/c9b)]·[1 − √(R_JB² + Z_tor²)/(R_rup + 1)]   (eq. 11)
//! ln y = ln y_ref + φ1·min(ln(V_S30/1130), 0)
//!        + φ2·[e^{φ3(min(V_S30, 1130) − 360)} − e^{φ3(1130 − 360)}]·ln((y_ref + φ4)/φ4)
//!        + φ5·(1 − exp(−ΔZ_1.0/φ6))                                                       (eq. 12)
//! ΔZ_tor = Z_tor − E[Z_tor](M),  E[Z_tor] = max(2.704 − 1.226·(M − 5.849)₊, 0)² (F_RV = 1),
//!          max(2.673 − 1.136·(M − 4.970)₊, 0)² (otherwise)                                   (eq. 4–5)
//! ΔZ_1.0 = Z_1.0 − μ_Z1.0(V_S30) in metres, μ the California relation (eq. 1)
//! ```
//! (x)₊ = max(x, 0); y_ref is the same intensity measure on the reference rock V_S30 = 1130 m/s,
//! and y in g (PGA, PSA) or cm/s (PGV). F_RV = 1 for reverse ruptures, F_NM = 1 for normal ones, as
//! [`Mechanism`] classifies them (CY14's own classes are 30° ≤ λ ≤ 150° and −120° ≤ λ ≤ −60°: a
//! rake of −150° to −120° or −60° to −30° that [`Mechanism::from_rake`] calls normal is strike-slip
//! to CY14, so give such a rupture the mechanism CY14 expects). F_HW = 1 for R_x ≥ 0, and the
//! hanging-wall term is zero on a vertical fault (cos 90° = 0). PSA at T ≤ 0.3 s is raised to PGA
//! where it falls below it (p. 1144; the authors' verification tool prints it unraised,
//! `tests/gmm.rs`). Defaults (the authors'): ΔDPP = 0 (no directivity term; the centred
//! direct-point parameter is not computed here), and ΔZ_1.0 = 0 (no basin term) when Z_1.0 is
//! unknown, i.e. Z_1.0 = μ_Z1.0(V_S30). Not carried: the regional attenuation and site terms (Japan,
//! Italy, Wenchuan): California/global.
//!
//! Aleatory variability (eq. 13), natural log, with M_c = clamp(M, 5, 6.5) − 5:
//! ```text
//! τ = τ1 + (τ2 − τ1)·M_c/1.5,   σ_M = σ1 + (σ2 − σ1)·M_c/1.5
//! NL0 = φ2·[e^{φ3(min(V_S30, 1130) − 360)} − e^{φ3(1130 − 360)}]·y_ref/(y_ref + φ4)
//! φ_NL0 = σ_M·√(σ3·F_inferred + 0.7·F_measured + (1 + NL0)²),   τ_NL0 = |1 + NL0|·τ
//! σ = √(τ_NL0² + φ_NL0²)
//! ```
//! Coefficients: `tables_nga2.rs` (sources named there). Ranges (the paper's): M 3.5–8.5 for
//! strike-slip, 3.5–8.0 for reverse and normal faults; R_rup 0–300 km; V_S30 180–1500 m/s.

use super::tables_nga2::{CY14, CY14_PERIODS, Cy14Row};
use super::{Estimate, Limits, Mechanism, Quantity, Range, Rupture, Site};

const C2: f64 = 1.06;
const C4: f64 = -2.1;
const C4A: f64 = -0.5;
const C_RB: f64 = 50.0;
const C11: f64 = 0.0;
/// φ6 of the basin term (m).
const PHI6: f64 = 300.0;
/// The reference rock's V_S30 (m/s).
const V_REF: f64 = 1130.0;

/// The ranges of CY14.
pub const LIMITS: Limits = Limits {
    mw_strike_slip: Range { quantity: Quantity::Magnitude, low: 3.5, high: 8.5 },
    mw_reverse: Range { quantity: Quantity::Magnitude, low: 3.5, high: 8.0 },
    mw_normal: Range { quantity: Quantity::Magnitude, low: 3.5, high: 8.0 },
    distance: Range { quantity: Quantity::RRup, low: 0.0, high: 300.0 },
    vs30: Range { quantity: Quantity::Vs30, low: 180.0, high: 1500.0 },
    periods_s: [0.01, 10.0],
};

const N_PSA: usize = CY14_PERIODS.len();

/// The tabulated PSA periods (s).
pub const PERIODS: [f64; N_PSA] = CY14_PERIODS;

const PGA_ROW: usize = N_PSA;

/// E\[Z_tor\] (km): the mean depth to the top of rupture for a magnitude and mechanism (eq. 4–5).
pub fn mean_ztor_km(mw: f64, mechanism: Mechanism) -> f64 {
    let z = match mechanism {
        Mechanism::Reverse => 2.704 - 1.226 * (mw - 5.849).max(0.0),
        Mechanism::StrikeSlip | Mechanism::Normal => 2.673 - 1.136 * (mw - 4.970).max(0.0),
    };
    z.max(0.0).powi(2)
}

/// The hanging-wall term (the last line of eq. 11).
fn f_hw(c: &Cy14Row, rupture: &Rupture, site: &Site) -> f64 {
    let (dip, rx) = (rupture.dip_deg, site.r_x_km);
    if rx < 0.0 || dip >= 90.0 {
        return 0.0;
    }
    let taper = 1.0 - site.r_jb_km.hypot(rupture.ztor_km) / (site.r_rup_km + 1.0);
    c.c9 * dip.to_radians().cos() * (c.c9a + (1.0 - c.c9a) * (rx / c.c9b).tanh()) * taper
}

/// ln y_ref: the median on the reference rock (eq. 11, ΔDPP = 0).
fn ln_y_ref(c: &Cy14Row, rupture: &Rupture, site: &Site) -> f64 {
    let (m, r) = (rupture.mw, site.r_rup_km);
    let cosh_m = (2.0 * (m - 4.5).max(0.0)).cosh();
    let style = match rupture.mechanism {
        Mechanism::Reverse => c.c1a + c.c1c / cosh_m,
        Mechanism::Normal => c.c1b + c.c1d / cosh_m,
        Mechanism::StrikeSlip => 0.0,
    };
    let d_ztor = rupture.ztor_km - mean_ztor_km(m, rupture.mechanism);
    let cos_dip = rupture.dip_deg.to_radians().cos();
    let source = c.c1
        + style
        + (c.c7 + c.c7b / cosh_m) * d_ztor
        + (C11 + c.c11b / cosh_m) * cos_dip * cos_dip
        + C2 * (m - 6.0)
        + (C2 - c.c3) / c.cn * (1.0 + (c.cn * (c.cm - m)).exp()).ln();
    let path = C4 * (r + c.c5 * (c.c6 * (m - c.chm).max(0.0)).cosh()).ln()
        + (C4A - C4) * r.hypot(C_RB).ln()
        + (c.cg1 + c.cg2 / (m - c.cg3).max(0.0).cosh()) * r;
    source + path + f_hw(c, rupture, site)
}

/// The nonlinear site coefficient φ2·[e^{φ3(min(V_S30, 1130) − 360)} − e^{φ3·770}] (≤ 0).
fn nonlinear_slope(c: &Cy14Row, vs30: f64) -> f64 {
    c.phi2 * ((c.phi3 * (vs30.min(V_REF) - 360.0)).exp() - (c.phi3 * (V_REF - 360.0)).exp())
}

/// The site terms of eq. 12 for reference-rock median `y_ref` (g or cm/s).
fn site_terms(c: &Cy14Row, vs30: f64, z1_km: Option<f64>, y_ref: f64) -> f64 {
    let f_lin = c.phi1 * (vs30 / V_REF).ln().min(0.0);
    let f_nl = nonlinear_slope(c, vs30) * ((y_ref + c.phi4) / c.phi4).ln();
    let f_z1 = match z1_km {
        Some(z1) => {
            let dz1_m = 1000.0 * (z1 - super::z1_cy14_california_km(vs30));
            c.phi5 * (1.0 - (-dz1_m / PHI6).exp())
        }
        None => 0.0,
    };
    f_lin + f_nl + f_z1
}

/// τ and φ of row `c` for reference-rock median `y_ref`.
fn sigma(c: &Cy14Row, m: f64, vs30: f64, measured: bool, y_ref: f64) -> (f64, f64) {
    let mc = m.clamp(5.0, 6.5) - 5.0;
    let tau = c.tau1 + (c.tau2 - c.tau1) * mc / 1.5;
    let sig_m = c.sig1 + (c.sig2 - c.sig1) * mc / 1.5;
    let nl0 = nonlinear_slope(c, vs30) * y_ref / (y_ref + c.phi4);
    let s3 = if measured { 0.7 } else { c.sig3 };
    let phi = sig_m * (s3 + (1.0 + nl0).powi(2)).sqrt();
    ((1.0 + nl0).abs() * tau, phi)
}

/// CY14 at table row `row` (PSA rows by period, then PGA, then PGV).
pub(super) fn estimate(row: usize, rupture: &Rupture, site: &Site) -> Estimate {
    let c = &CY14[row];
    let ln_at = |c: &Cy14Row| {
        let ln_ref = ln_y_ref(c, rupture, site);
        (ln_ref, ln_ref + site_terms(c, site.vs30_m_s, site.z1_km, ln_ref.exp()))
    };
    let (ln_ref, mut ln_y) = ln_at(c);
    if c.t > 0.0 && c.t <= 0.3 {
        ln_y = ln_y.max(ln_at(&CY14[PGA_ROW]).1);
    }
    let (tau, phi) = sigma(c, rupture.mw, site.vs30_m_s, site.vs30_measured, ln_ref.exp());
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
            hypo_depth_km: None,
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
        assert_eq!(CY14[PGA_ROW].t, 0.0);
        assert_eq!(CY14[PGA_ROW + 1].t, -1.0);
        assert_eq!(CY14.len(), N_PSA + 2);
        assert!(PERIODS.windows(2).all(|w| w[0] < w[1]));
        assert!(PERIODS.iter().zip(&CY14).all(|(p, c)| *p == c.t));
        assert_eq!((PERIODS[0], PERIODS[N_PSA - 1], N_PSA), (0.01, 10.0, 24));
        // The nonlinear term only ever lowers the amplification (φ2 ≤ 0, φ3 < 0).
        assert!(CY14.iter().all(|c| c.phi2 <= 0.0 && c.phi3 < 0.0));
        // PGA's coefficients are those of 0.01 s.
        let (p, s) = (&CY14[PGA_ROW], &CY14[0]);
        assert_eq!((p.c1, p.c3, p.phi2, p.phi4, p.tau1, p.sig3), (s.c1, s.c3, s.phi2, s.phi4, s.tau1, s.sig3));
    }

    #[test]
    fn the_reference_rock_has_no_site_term() {
        // At V_S30 = 1130 m/s and Z_1.0 unknown (or on the relation's centre) every site term vanishes,
        // whatever y_ref.
        let mu = super::super::z1_cy14_california_km(V_REF);
        for c in &CY14 {
            for y in [1e-4, 0.3, 3.0] {
                assert!(site_terms(c, V_REF, None, y).abs() < 1e-12, "T = {}", c.t);
                assert!(site_terms(c, V_REF, Some(mu), y).abs() < 1e-12, "T = {}", c.t);
                assert!(site_terms(c, 1500.0, None, y).abs() < 1e-12, "T = {}: stiffer rock is capped", c.t);
            }
            // ... and σ is the linear one: NL0 = 0.
            let (t, p) = sigma(c, 7.0, V_REF, true, 0.5);
            assert!((t - c.tau2).abs() < 1e-12 && (p - c.sig2 * 1.7f64.sqrt()).abs() < 1e-12, "T = {}", c.t);
        }
    }

    #[test]
    fn y_ref_is_the_models_own_median_on_its_reference_rock() {
        // On V_S30 = 1130 m/s with Z_1.0 unknown, the prediction is y_ref itself (PGA, PGV and
        // T > 0.3 s, where the PSA ≥ PGA rule cannot intervene).
        let (r, s) = (rupture(), site());
        let rock = Site { vs30_m_s: V_REF, z1_km: None, ..s };
        for (i, c) in CY14.iter().enumerate().filter(|(_, c)| c.t == 0.0 || c.t == -1.0 || c.t > 0.3) {
            assert!((estimate(i, &r, &rock).ln_y - ln_y_ref(c, &r, &s)).abs() < 1e-12, "T = {}", c.t);
        }
    }

    #[test]
    fn the_basin_term_saturates_at_phi5_and_is_zero_on_the_relation() {
        let c = CY14.iter().find(|c| c.t == 3.0).unwrap();
        let (vs30, y) = (300.0, 0.1);
        let mu = super::super::z1_cy14_california_km(vs30);
        let base = site_terms(c, vs30, None, y);
        let basin = |z1: f64| site_terms(c, vs30, Some(z1), y) - base;
        assert!(basin(mu).abs() < 1e-12);
        // ΔZ_1.0 = 300 m: φ5·(1 − 1/e).
        assert!((basin(mu + 0.3) - c.phi5 * (1.0 - (-1f64).exp())).abs() < 1e-12);
        assert!((basin(mu + 10.0) - c.phi5).abs() < 1e-12);
        // Shallower than the relation: negative.
        assert!(basin(mu * 0.5) < 0.0);
    }

    #[test]
    fn the_hanging_wall_term_vanishes_where_the_paper_says() {
        let c = &CY14[PGA_ROW];
        let (r, s) = (rupture(), site());
        // Above a surface-breaking rupture (R_JB = Z_tor = 0) the distance taper is 1.
        let expected = c.c9 * 45f64.to_radians().cos() * (c.c9a + (1.0 - c.c9a) * (5.0 / c.c9b).tanh());
        assert!((f_hw(c, &r, &s) - expected).abs() < 1e-12);
        assert!(f_hw(c, &r, &s) > 0.0);
        assert_eq!(f_hw(c, &r, &Site { r_x_km: -0.1, ..s }), 0.0);
        assert_eq!(f_hw(c, &Rupture { dip_deg: 90.0, ..r }, &s), 0.0);
    }

    #[test]
    fn the_mean_top_of_rupture_follows_eq_4_and_5() {
        assert!((mean_ztor_km(5.0, Mechanism::Reverse) - 2.704f64.powi(2)).abs() < 1e-12);
        assert!((mean_ztor_km(4.0, Mechanism::StrikeSlip) - 2.673f64.powi(2)).abs() < 1e-12);
        assert!((mean_ztor_km(6.0, Mechanism::Normal) - (2.673 - 1.136 * 1.03f64).powi(2)).abs() < 1e-12);
        // Large ruptures break the surface on average.
        assert_eq!(mean_ztor_km(8.5, Mechanism::Reverse), 0.0);
        assert!((mean_ztor_km(8.0, Mechanism::Reverse) - (2.704 - 1.226 * 2.151f64).powi(2)).abs() < 1e-12);
        assert_eq!(mean_ztor_km(7.5, Mechanism::StrikeSlip), 0.0);
    }

    #[test]
    fn short_period_psa_is_raised_to_pga_up_to_0_3_s() {
        let r = Rupture { mw: 7.5, mechanism: Mechanism::StrikeSlip, dip_deg: 90.0, ..rupture() };
        let s = Site { r_rup_km: 150.0, r_jb_km: 150.0, r_x_km: 150.0, vs30_m_s: 180.0, ..site() };
        let pga = estimate(PGA_ROW, &r, &s).ln_y;
        let mut raised = 0;
        for (i, c) in CY14.iter().enumerate().take(N_PSA) {
            let ln_ref = ln_y_ref(c, &r, &s);
            let raw = ln_ref + site_terms(c, 180.0, None, ln_ref.exp());
            let e = estimate(i, &r, &s).ln_y;
            if c.t <= 0.3 {
                assert_eq!(e, raw.max(pga), "T = {}", c.t);
                raised += (raw < pga) as usize;
            } else {
                assert_eq!(e, raw, "T = {}", c.t);
            }
        }
        assert!(raised > 0, "the case does not exercise the floor");
    }

    #[test]
    fn sigma_grows_with_the_nonlinear_site_response_only_through_nl0() {
        let c = &CY14[PGA_ROW];
        // Inferred V_S30 uses σ3, measured 0.7.
        let (_, p_meas) = sigma(c, 4.0, V_REF, true, 0.1);
        let (_, p_inf) = sigma(c, 4.0, V_REF, false, 0.1);
        assert!((p_meas - c.sig1 * 1.7f64.sqrt()).abs() < 1e-12);
        assert!((p_inf - c.sig1 * (c.sig3 + 1.0).sqrt()).abs() < 1e-12);
        // Soft soil and strong rock motion: NL0 < 0 shrinks τ by |1 + NL0|.
        let y = 0.5;
        let nl0 = nonlinear_slope(c, 200.0) * y / (y + c.phi4);
        assert!(nl0 < 0.0);
        let (t, _) = sigma(c, 6.5, 200.0, true, y);
        assert!((t - c.tau2 * (1.0 + nl0).abs()).abs() < 1e-12);
    }
}
