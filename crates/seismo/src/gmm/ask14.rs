//! ASK14: Abrahamson, Silva & Kamai (2014), NGA-West2 model for RotD50 PGA, PGV and 5%-damped PSA
//! of shallow crustal earthquakes in active regions, with its California/global defaults.
//!
//! ```text
//! ln Y = f1(M, R_rup) + F_RV·f7(M) + F_N·f8(M) + F_HW·f4(R_jb, R_rup, R_x, R_y0, W, δ, Z_tor, M)
//!        + f6(Z_tor) + f5(Sa1180, V_S30) + f10(Z_1.0, V_S30)                                (eq. 1)
//! R = √(R_rup² + c4M²),  c4M = c4 (M > 5); c4 − (c4 − 1)(5 − M) (4 < M ≤ 5); 1 (M ≤ 4)
//! f1 = a1 + a5(M − M1) + a8(8.5 − M)² + [a2 + a3(M − M1)] ln R + a17 R_rup              M > M1
//!    = a1 + a4(M − M1) + a8(8.5 − M)² + [a2 + a3(M − M1)] ln R + a17 R_rup              M2 ≤ M ≤ M1
//!    = a1 + a4(M2 − M1) + a8(8.5 − M2)² + a6(M − M2) + a7(M − M2)²
//!         + [a2 + a3(M2 − M1)] ln R + a17 R_rup                                          M < M2  (eq. 2)
//! f7 = a11·clamp(M − 4, 0, 1) (a11 = 0),   f8 = a12·clamp(M − 4, 0, 1)                   (eq. 5–6)
//! f6 = a15·min(Z_tor/20, 1)
//! f5 = (a10 + b·n) ln(V*/V_lin)                                          V_S30 ≥ V_lin
//!    = a10 ln(V*/V_lin) − b ln(Sa1180 + c) + b ln(Sa1180 + c(V*/V_lin)^n)               V_S30 < V_lin  (eq. 7)
//! V* = min(V_S30, V1),  V1 = 1500 (T ≤ 0.5 s, PGA, PGV); exp(−0.35 ln(T/0.5) + ln 1500)
//!      (0.5 < T < 3 s); 800 m/s (T ≥ 3 s)                                                (eq. 8–9)
//! f4 = a13·T1·T2·T3·T4·T5 on the hanging wall (R_x > 0, δ < 90°), 0 elsewhere           (eq. 10–15)
//!   T1 = (90 − δ)/45 (δ > 30°), 60/45 (δ ≤ 30°)
//!   T2 = 1 + a2HW(M − 6.5) (M ≥ 6.5); 1 + a2HW(M − 6.5) − (1 − a2HW)(M − 6.5)² (5.5 < M < 6.5); 0 (M ≤ 5.5)
//!   T3 = h1 + h2(R_x/R1) + h3(R_x/R1)² (R_x < R1); 1 − (R_x − R1)/(R2 − R1) (R1 ≤ R_x ≤ R2); 0 (R_x > R2),
//!        R1 = W cos δ, R2 = 3R1
//!   T4 = 1 − Z_tor²/100 (Z_tor ≤ 10 km), 0 otherwise
//!   T5 = clamp(1 − (R_y0 − R_y1)/5, 0, 1), R_y1 = R_x tan 20°; without R_y0: clamp(1 − R_JB/30, 0, 1)
//! f10 = s(V_S30)·ln((Z_1.0 + 0.01)/(Z_1.0,ref(V_S30) + 0.01)), Z in km, s interpolated linearly
//!      through (150, a43), (250, a44), (400, a45), (700, a46), constant outside (the paper's
//!      application guidelines, p. 1044); Z_1.0,ref the California relation (eq. 18); 0 when Z_1.0
//!      is unknown (eq. 17)
//! ```
//! Sa1180 is the median of the same rupture and site on V_S30 = 1180 m/s (f10 = 0). Y in g (PGA,
//! PSA) or cm/s (PGV). Not carried: the aftershock term f11 (mainshocks, F_AS = 0) and the regional
//! terms f_reg (Taiwan, China, Japan): California/global, f_reg = 0.
//!
//! Aleatory variability (eq. 24–30), natural log, with ∂ = ∂ln f5/∂ln Sa1180:
//! ```text
//! φ_A(M) = s1 (M < 4); s1 + (s2 − s1)(M − 4)/2 (4 ≤ M ≤ 6); s2 (M > 6)   (s1m, s2m measured V_S30; s1e, s2e inferred)
//! τ_A(M) = s3 (M < 5); s3 + (s4 − s3)(M − 5)/2 (5 ≤ M ≤ 7); s4 (M > 7)
//! φ_B² = φ_A² − φ_amp², φ_amp = 0.4,  τ_B = τ_A
//! ∂ = 0 (V_S30 ≥ V_lin); −b·Sa1180/(Sa1180 + c) + b·Sa1180/(Sa1180 + c(V_S30/V_lin)^n) otherwise
//! φ = √(φ_B²(1 + ∂)² + φ_amp²),  τ = τ_B(1 + ∂)
//! ```
//! φ_B² is used as a square: where φ_A < φ_amp (the small-magnitude s1 at T ≥ 6 s, where b = 0
//! and so ∂ = 0) φ is then φ_A, not the 0.4 a clipped √ would give.
//! Coefficients: `tables.rs` (source named there). Ranges (the paper's): M 3–8.5, R_rup 0–300 km,
//! V_S30 180–1000 m/s.

use super::tables::{ASK14, ASK14_PERIODS, Ask14Row};
use super::{Estimate, Limits, Mechanism, Quantity, Range, Rupture, Site};

const M2: f64 = 5.0;
const N: f64 = 1.5;
const C4: f64 = 4.5;
const A3: f64 = 0.275;
const A4: f64 = -0.1;
const A5: f64 = -0.41;
const A7: f64 = 0.0;
const A11: f64 = 0.0;
const A2HW: f64 = 0.2;
const H1: f64 = 0.25;
const H2: f64 = 1.5;
const H3: f64 = -0.75;
const PHI_AMP: f64 = 0.4;
const V_REF: f64 = 1180.0;

/// The ranges of ASK14.
pub const LIMITS: Limits = Limits {
    mw_strike_slip: Range { quantity: Quantity::Magnitude, low: 3.0, high: 8.5 },
    mw_reverse: Range { quantity: Quantity::Magnitude, low: 3.0, high: 8.5 },
    mw_normal: Range { quantity: Quantity::Magnitude, low: 3.0, high: 8.5 },
    distance: Range { quantity: Quantity::RRup, low: 0.0, high: 300.0 },
    vs30: Range { quantity: Quantity::Vs30, low: 180.0, high: 1000.0 },
    periods_s: [0.01, 10.0],
};

const N_PSA: usize = ASK14_PERIODS.len();

/// The tabulated PSA periods (s).
pub const PERIODS: [f64; N_PSA] = ASK14_PERIODS;

/// f1: magnitude and distance scaling.
fn f1(c: &Ask14Row, m: f64, r_rup: f64) -> f64 {
    let c4m = if m > 5.0 {
        C4
    } else if m > 4.0 {
        C4 - (C4 - 1.0) * (5.0 - m)
    } else {
        1.0
    };
    let ln_r = r_rup.hypot(c4m).ln();
    let m1 = c.m1;
    if m > m1 {
        c.a1 + A5 * (m - m1) + c.a8 * (8.5 - m).powi(2) + (c.a2 + A3 * (m - m1)) * ln_r + c.a17 * r_rup
    } else if m >= M2 {
        c.a1 + A4 * (m - m1) + c.a8 * (8.5 - m).powi(2) + (c.a2 + A3 * (m - m1)) * ln_r + c.a17 * r_rup
    } else {
        c.a1 + A4 * (M2 - m1)
            + c.a8 * (8.5 - M2).powi(2)
            + c.a6 * (m - M2)
            + A7 * (m - M2).powi(2)
            + (c.a2 + A3 * (M2 - m1)) * ln_r
            + c.a17 * r_rup
    }
}

/// f4: the hanging-wall term.
fn f4(c: &Ask14Row, rupture: &Rupture, site: &Site) -> f64 {
    let (m, dip, rx) = (rupture.mw, rupture.dip_deg, site.r_x_km);
    if rx <= 0.0 || dip >= 90.0 {
        return 0.0;
    }
    let t1 = if dip > 30.0 { (90.0 - dip) / 45.0 } else { 60.0 / 45.0 };
    let dm = m - 6.5;
    let t2 = if m >= 6.5 {
        1.0 + A2HW * dm
    } else if m > 5.5 {
        1.0 + A2HW * dm - (1.0 - A2HW) * dm * dm
    } else {
        0.0
    };
    let r1 = rupture.width_km * dip.to_radians().cos();
    let r2 = 3.0 * r1;
    let t3 = if rx < r1 {
        H1 + H2 * (rx / r1) + H3 * (rx / r1).powi(2)
    } else if rx <= r2 {
        1.0 - (rx - r1) / (r2 - r1)
    } else {
        0.0
    };
    let t4 = if rupture.ztor_km <= 10.0 { 1.0 - rupture.ztor_km.powi(2) / 100.0 } else { 0.0 };
    let t5 = match site.r_y0_km {
        Some(ry0) => (1.0 - (ry0 - rx * 20f64.to_radians().tan()) / 5.0).clamp(0.0, 1.0),
        None => (1.0 - site.r_jb_km / 30.0).clamp(0.0, 1.0),
    };
    c.a13 * t1 * t2 * t3 * t4 * t5
}

/// V1 of eq. 9 for the row's period (PGA and PGV: 1500 m/s).
fn v1(t: f64) -> f64 {
    if t <= 0.5 {
        1500.0
    } else if t < 3.0 {
        (-0.35 * (t / 0.5).ln() + 1500f64.ln()).exp()
    } else {
        800.0
    }
}

/// f5: the site response for reference-rock median `sa1180` (g or cm/s).
fn f5(c: &Ask14Row, vs30: f64, sa1180: f64) -> f64 {
    let ratio = vs30.min(v1(c.t)) / c.v_lin;
    if vs30 >= c.v_lin {
        (c.a10 + c.b * N) * ratio.ln()
    } else {
        c.a10 * ratio.ln() - c.b * (sa1180 + c.c).ln() + c.b * (sa1180 + c.c * ratio.powf(N)).ln()
    }
}

/// f10: the soil-depth (basin) term; 0 without Z_1.0.
fn f10(c: &Ask14Row, vs30: f64, z1_km: Option<f64>) -> f64 {
    let Some(z1) = z1_km else { return 0.0 };
    let knots = [(150.0, c.a43), (250.0, c.a44), (400.0, c.a45), (700.0, c.a46)];
    let slope = if vs30 <= knots[0].0 {
        knots[0].1
    } else if vs30 >= knots[3].0 {
        knots[3].1
    } else {
        let k = knots.windows(2).find(|w| vs30 <= w[1].0).expect("inside the knots");
        k[0].1 + (k[1].1 - k[0].1) * (vs30 - k[0].0) / (k[1].0 - k[0].0)
    };
    slope * ((z1 + 0.01) / (super::z1_ask14_california_km(vs30) + 0.01)).ln()
}

/// ln Y without the site terms f5 and f10.
fn ln_source_path(c: &Ask14Row, rupture: &Rupture, site: &Site) -> f64 {
    let m = rupture.mw;
    let taper = (m - 4.0).clamp(0.0, 1.0);
    let (f7, f8) = match rupture.mechanism {
        Mechanism::Reverse => (A11 * taper, 0.0),
        Mechanism::Normal => (0.0, c.a12 * taper),
        Mechanism::StrikeSlip => (0.0, 0.0),
    };
    let f6 = c.a15 * (rupture.ztor_km / 20.0).min(1.0);
    f1(c, m, site.r_rup_km) + f4(c, rupture, site) + f6 + f7 + f8
}

/// τ and φ of row `c`.
fn sigma(c: &Ask14Row, m: f64, vs30: f64, measured: bool, sa1180: f64) -> (f64, f64) {
    let (s1, s2) = if measured { (c.s1m, c.s2m) } else { (c.s1e, c.s2e) };
    let phi_a = s1 + (s2 - s1) * ((m - 4.0) / 2.0).clamp(0.0, 1.0);
    let tau_a = c.s3 + (c.s4 - c.s3) * ((m - 5.0) / 2.0).clamp(0.0, 1.0);
    // φ_B² = φ_A² − φ_amp², negative where φ_A < φ_amp (s1 at T ≥ 6 s): kept as a square so that
    // φ = φ_A wherever ∂ = 0, as the authors' decomposition intends (OpenQuake does the same).
    let phi_b2 = phi_a * phi_a - PHI_AMP * PHI_AMP;
    let d = if vs30 >= c.v_lin {
        0.0
    } else {
        -c.b * sa1180 / (sa1180 + c.c) + c.b * sa1180 / (sa1180 + c.c * (vs30 / c.v_lin).powf(N))
    };
    let phi = (phi_b2 * (1.0 + d).powi(2) + PHI_AMP * PHI_AMP).sqrt();
    (tau_a * (1.0 + d), phi)
}

/// ASK14 at table row `row` (PSA rows by period, then PGA, then PGV).
pub(super) fn estimate(row: usize, rupture: &Rupture, site: &Site) -> Estimate {
    let c = &ASK14[row];
    let base = ln_source_path(c, rupture, site);
    let sa1180 = (base + f5(c, V_REF, f64::NAN)).exp();
    let ln_y = base + f5(c, site.vs30_m_s, sa1180) + f10(c, site.vs30_m_s, site.z1_km);
    let (tau, phi) = sigma(c, rupture.mw, site.vs30_m_s, site.vs30_measured, sa1180);
    Estimate { ln_y, tau, phi }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_table_has_pga_then_pgv_after_increasing_periods() {
        assert_eq!(ASK14[N_PSA].t, 0.0);
        assert_eq!(ASK14[N_PSA + 1].t, -1.0);
        assert_eq!(ASK14.len(), N_PSA + 2);
        assert!(PERIODS.windows(2).all(|w| w[0] < w[1]));
        assert!(PERIODS.iter().zip(&ASK14).all(|(p, c)| *p == c.t));
        assert_eq!((PERIODS[0], PERIODS[N_PSA - 1], N_PSA), (0.01, 10.0, 22));
        // Reference rock is above V_lin for every row, so Sa1180 never needs itself.
        assert!(ASK14.iter().all(|c| c.v_lin < V_REF));
    }

    #[test]
    fn magnitude_scaling_is_continuous_at_its_hinges() {
        for c in &ASK14 {
            for hinge in [M2, c.m1, 4.0, 5.0] {
                let (lo, hi) = (f1(c, hinge - 1e-9, 30.0), f1(c, hinge + 1e-9, 30.0));
                assert!((lo - hi).abs() < 1e-6, "T = {}: f1 jumps by {} at M = {hinge}", c.t, hi - lo);
            }
        }
    }

    #[test]
    fn v1_follows_its_three_branches() {
        assert_eq!(v1(0.5), 1500.0);
        // The middle branch ends at 1500·6^−0.35 = 801.4 m/s, the paper's 800 m/s rounded.
        assert!((v1(3.0 - 1e-12) - 1500.0 * 6f64.powf(-0.35)).abs() < 1e-9, "{}", v1(3.0 - 1e-12));
        assert!((v1(1.0) - 1500.0 * 2f64.powf(-0.35)).abs() < 1e-9);
        assert_eq!(v1(3.0), 800.0);
        assert_eq!(v1(-1.0), 1500.0);
        assert_eq!(v1(0.0), 1500.0);
    }

    #[test]
    fn the_hanging_wall_term_vanishes_where_the_paper_says() {
        let c = &ASK14[N_PSA];
        let r = Rupture {
            mw: 7.0,
            mechanism: Mechanism::Reverse,
            dip_deg: 45.0,
            ztor_km: 0.0,
            width_km: 20.0,
            hypo_depth_km: None,
        };
        let s = Site {
            r_rup_km: 5.0,
            r_jb_km: 0.0,
            r_x_km: 5.0,
            r_y0_km: Some(0.0),
            vs30_m_s: 760.0,
            z1_km: None,
            z25_km: None,
            vs30_measured: true,
        };
        // On the hanging wall above the rupture: all tapers positive. T1 = 1, T2 = 1.1, T4 = 1,
        // T5 = 1 and T3 at R_x/R1 = 5/(20 cos 45°).
        let x = 5.0 / (20.0 * 45f64.to_radians().cos());
        let t3 = H1 + H2 * x + H3 * x * x;
        assert!((f4(c, &r, &s) - c.a13 * 1.1 * t3).abs() < 1e-12);
        // Footwall, vertical fault, small magnitude, deep top, far along strike: zero.
        assert_eq!(f4(c, &r, &Site { r_x_km: -5.0, ..s }), 0.0);
        assert_eq!(f4(c, &Rupture { dip_deg: 90.0, ..r }, &s), 0.0);
        assert_eq!(f4(c, &Rupture { mw: 5.5, ..r }, &s), 0.0);
        assert_eq!(f4(c, &Rupture { ztor_km: 10.5, ..r }, &s), 0.0);
        assert_eq!(f4(c, &r, &Site { r_y0_km: Some(5.0 + 5.0 * 20f64.to_radians().tan()), ..s }), 0.0);
        assert_eq!(f4(c, &r, &Site { r_x_km: 3.0 * 20.0 * 45f64.to_radians().cos() + 0.1, ..s }), 0.0);
    }

    #[test]
    fn sigma_on_linear_ground_is_the_magnitude_dependent_one() {
        // On ground stiffer than V_lin the derivative vanishes: φ = φ_A, τ = τ_A.
        let c = &ASK14[N_PSA];
        let (tau, phi) = sigma(c, 6.0, 1000.0, true, 0.3);
        assert!((tau - 0.5 * (c.s3 + c.s4)).abs() < 1e-12);
        assert!((phi - c.s2m).abs() < 1e-12);
        let (_, phi) = sigma(c, 3.5, 1000.0, false, 0.3);
        assert!((phi - c.s1e).abs() < 1e-12);
    }
}
