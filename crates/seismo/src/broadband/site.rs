//! What a site does to each part of a hybrid record: the crust's amplification of the stochastic
//! part, and the V_S30 site terms that take both parts from their reference site to the
//! station's.
//!
//! **The crust of the stochastic part.** The Graves–Pitarka method amplifies its stochastic part
//! by the square-root-impedance (quarter-wavelength) amplification of a 1D crust between the
//! source and the surface, whose own V_S30 is then the reference the site terms start from (the
//! Platform's 1D models have V_S30 ≈ 500 m/s). The lattice's crust is a homogeneous half-space:
//! there that amplification is exactly 1, and its stochastic part would stand on 3464 m/s rock
//! with a κ₀ of soft rock. [`Crust::GenericRock`] gives it instead the generic rock amplification
//! of Boore & Joyner (1997, *BSSA* 87, 327–341, Table 3: the quarter-wavelength amplification of
//! their generic rock profile, V_S30 = 620 m/s, relative to a source region of β = 3.5 km/s and
//! ρ = 2.8 g/cm³), the crust the Western-US stochastic models pair with κ₀ = 0.04 s (Boore 2003;
//! Campbell 2003, *BSSA* 93, 1012–1033, who tabulates it); its reference V_S30 is 620 m/s.
//! [`Crust::Homogeneous`] keeps the half-space (amplification 1, reference V_S30 its own V_S).
//!
//! **Site terms** (the Platform's `wcc_siteamp14`): each part `× exp(F_S(V_S30) − F_S(V_ref))`
//! with F_S the BSSA14 linear and nonlinear site terms ([`crate::gmm::bssa14::site_amplification`])
//! and V_ref that part's reference site: the lattice's surface V_S for the deterministic part, the
//! crust's V_S30 for the stochastic one. The factor is tabulated at BSSA14's periods, read at
//! `f = 1/T` linearly in amplitude against ln f, held at its 10 s value below 0.1 Hz, and tapered
//! to 1 (linearly in ln f) over 0.1 → 0.05 Hz and 20 → 50 Hz; BSSA14's PGA row stands at 1000 Hz.
//! The reference-rock PGA of the nonlinear term is the peak of the stochastic part of the same
//! component before any site term, taken from its reference site to 760 m/s by the linear PGA
//! term, and used for both parts (as the Platform does).

use crate::gmm::bssa14;

/// The crust between the source and the surface for the stochastic part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Crust {
    /// Boore & Joyner (1997) generic rock, V_S30 = 620 m/s.
    GenericRock,
    /// The lattice's homogeneous half-space of the given V_S (m/s): no amplification.
    Homogeneous {
        /// The half-space's S-wave speed (m/s), its V_S30.
        s_speed_m_s: f64,
    },
}

/// Boore & Joyner (1997) generic rock amplification (Table 3), as Campbell (2003) tabulates it:
/// `(frequency Hz, amplification)`.
const GENERIC_ROCK: [(f64, f64); 12] = [
    (0.01, 1.00),
    (0.09, 1.10),
    (0.16, 1.18),
    (0.51, 1.42),
    (0.84, 1.58),
    (1.25, 1.74),
    (2.26, 2.06),
    (3.17, 2.25),
    (6.05, 2.58),
    (16.6, 3.13),
    (61.2, 4.00),
    (100.0, 4.40),
];

/// V_S30 of Boore & Joyner's generic rock (m/s).
pub const GENERIC_ROCK_VS30_M_S: f64 = 620.0;

impl Crust {
    /// Its amplification at `f` (Hz): the generic rock table interpolated linearly in ln f
    /// (constant beyond its ends), or 1.
    pub fn amplification(&self, f: f64) -> f64 {
        match self {
            Crust::Homogeneous { .. } => 1.0,
            Crust::GenericRock => interpolate_ln_f(&GENERIC_ROCK, f),
        }
    }

    /// The V_S30 its amplified motion stands on (m/s).
    pub fn vs30_m_s(&self) -> f64 {
        match self {
            Crust::Homogeneous { s_speed_m_s } => *s_speed_m_s,
            Crust::GenericRock => GENERIC_ROCK_VS30_M_S,
        }
    }

    /// Its name in a pipeline file.
    pub fn name(&self) -> &'static str {
        match self {
            Crust::Homogeneous { .. } => "homogeneous",
            Crust::GenericRock => "generic_rock",
        }
    }
}

/// `table` (ascending frequencies) at `f`, linearly in the value against ln f, constant beyond
/// its ends.
fn interpolate_ln_f(table: &[(f64, f64)], f: f64) -> f64 {
    let (first, last) = (table[0], table[table.len() - 1]);
    if !(f > first.0) {
        return first.1;
    }
    if f >= last.0 {
        return last.1;
    }
    let k = table.partition_point(|p| p.0 <= f);
    let ((f0, a0), (f1, a1)) = (table[k - 1], table[k]);
    a0 + (a1 - a0) * (f / f0).ln() / (f1 / f0).ln()
}

/// The BSSA14 site factor of one part, as a function of frequency.
#[derive(Clone, Debug, PartialEq)]
pub struct SiteFactor {
    /// `(f, factor)`, f ascending (Hz).
    table: Vec<(f64, f64)>,
}

/// Below this frequency (Hz) the factor is 1.
pub const SITE_F_MIN_HZ: f64 = 0.05;
/// From here down to [`SITE_F_MIN_HZ`] it tapers to 1 (Hz); below it is held at the 10 s value.
pub const SITE_F_LOW_TOP_HZ: f64 = 0.1;
/// From here up to [`SITE_F_MAX_HZ`] it tapers to 1 (Hz).
pub const SITE_F_HIGH_BOTTOM_HZ: f64 = 20.0;
/// Above this frequency (Hz) the factor is 1.
pub const SITE_F_MAX_HZ: f64 = 50.0;

impl SiteFactor {
    /// The factor from a site of `vref_m_s` to one of `vs30_m_s`, for the reference-rock PGA
    /// `pga_760_g` (g).
    pub fn bssa14(vs30_m_s: f64, vref_m_s: f64, pga_760_g: f64) -> SiteFactor {
        let mut table: Vec<(f64, f64)> = bssa14::site_amplification(vs30_m_s, vref_m_s, pga_760_g)
            .into_iter()
            .map(|(t, a)| (if t > 0.0 { 1.0 / t } else { 1000.0 }, a))
            .collect();
        table.sort_by(|a, b| a.0.total_cmp(&b.0));
        SiteFactor { table }
    }

    /// No site term.
    pub fn none() -> SiteFactor {
        SiteFactor { table: vec![(1.0, 1.0)] }
    }

    /// The factor at `f` (Hz), with the tapers to 1 at both ends.
    pub fn at(&self, f: f64) -> f64 {
        let f = f.abs();
        if !(SITE_F_MIN_HZ..SITE_F_MAX_HZ).contains(&f) {
            return 1.0;
        }
        let inside = interpolate_ln_f(&self.table, f.max(SITE_F_LOW_TOP_HZ));
        if f < SITE_F_LOW_TOP_HZ {
            1.0 + (inside - 1.0) * (f / SITE_F_MIN_HZ).ln() / (SITE_F_LOW_TOP_HZ / SITE_F_MIN_HZ).ln()
        } else if f > SITE_F_HIGH_BOTTOM_HZ {
            inside + (1.0 - inside) * (f / SITE_F_HIGH_BOTTOM_HZ).ln() / (SITE_F_MAX_HZ / SITE_F_HIGH_BOTTOM_HZ).ln()
        } else {
            inside
        }
    }
}

/// The reference-rock PGA (g) of the nonlinear site term from the peak `pga_m_s2` of a record on
/// a site of `vref_m_s`: taken to 760 m/s by BSSA14's linear PGA term.
pub fn pga_760_g(pga_m_s2: f64, vref_m_s: f64) -> f64 {
    pga_m_s2 / crate::spectra::intensity::G * (-bssa14::pga_linear_site_ln(vref_m_s)).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_generic_rock_table_is_read_between_its_points_in_log_frequency() {
        let c = Crust::GenericRock;
        assert_eq!(c.amplification(0.84), 1.58);
        assert_eq!(c.amplification(0.001), 1.0);
        assert_eq!(c.amplification(500.0), 4.4);
        let mid = (0.84f64 * 1.25).sqrt();
        assert!((c.amplification(mid) - 0.5 * (1.58 + 1.74)).abs() < 1e-12);
        assert_eq!(Crust::Homogeneous { s_speed_m_s: 3464.0 }.amplification(5.0), 1.0);
        assert_eq!(c.vs30_m_s(), 620.0);
    }

    #[test]
    fn the_site_factor_tapers_to_one_outside_0_05_to_50_hz() {
        let s = SiteFactor::bssa14(400.0, 760.0, 0.1);
        assert_eq!(s.at(0.04), 1.0);
        assert_eq!(s.at(60.0), 1.0);
        // At 1 Hz: BSSA14's factor at T = 1 s exactly (a tabulated period).
        let at_1s = bssa14::site_amplification(400.0, 760.0, 0.1).into_iter().find(|p| p.0 == 1.0).unwrap().1;
        assert!((s.at(1.0) - at_1s).abs() < 1e-12);
        assert!(at_1s > 1.3, "{at_1s}");
        // Halfway (in ln f) through each taper: halfway to 1.
        let held = s.at(0.1);
        let half = (0.05f64 * 0.1).sqrt();
        assert!((s.at(half) - 0.5 * (1.0 + held)).abs() < 1e-12);
        // Over 20–50 Hz the factor read there moves to 1 (the Platform's taper of the local value).
        let mid = (20.0f64 * 50.0).sqrt();
        let inside = interpolate_ln_f(&s.table, mid);
        assert!((s.at(mid) - 0.5 * (1.0 + inside)).abs() < 1e-12);
        // Equal sites: 1 everywhere.
        let same = SiteFactor::bssa14(500.0, 500.0, 0.3);
        assert!([0.01, 0.07, 0.3, 3.0, 30.0].iter().all(|&f| (same.at(f) - 1.0).abs() < 1e-12));
    }

    #[test]
    fn a_pga_on_rock_above_v_c_becomes_a_larger_one_on_760_m_s() {
        // c < 0 at PGA: reference rock (760) shakes more than harder rock.
        let g = crate::spectra::intensity::G;
        assert!((pga_760_g(g, 760.0) - 1.0).abs() < 1e-12);
        assert!(pga_760_g(g, 3464.0) > 1.2);
    }
}
