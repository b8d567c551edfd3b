//! Design response spectra (ASCE 7-16, Eurocode 8) and tabulated targets, as PSA in m/s².
//!
//! **ASCE 7-16 §11.4.6** (design response spectrum, 5% damping) from the design spectral
//! accelerations `S_DS`, `S_D1` (in g, as the code's maps and §11.4.5 give them) and the long-period
//! transition period `T_L` (s), with `T_0 = 0.2·S_D1/S_DS` and `T_S = S_D1/S_DS`:
//! ```text
//! S_a = S_DS·(0.4 + 0.6·T/T_0)        T < T_0
//! S_a = S_DS                          T_0 ≤ T ≤ T_S
//! S_a = S_D1/T                        T_S < T ≤ T_L
//! S_a = S_D1·T_L/T²                   T > T_L
//! ```
//! (values in g, returned × g = 9.80665 m/s²).
//!
//! **Eurocode 8 (EN 1998-1:2004) §3.2.2.2**, horizontal elastic response spectrum, with the design
//! ground acceleration on type A ground `a_g` (m/s²), the soil factor `S` and the corner periods
//! `T_B`, `T_C`, `T_D` of Table 3.2 (Type 1) or Table 3.3 (Type 2) for ground types A–E, and the
//! damping correction `η = √(10/(5+ξ)) ≥ 0.55` (ξ in per cent, eq. 3.6):
//! ```text
//! S_e = a_g·S·(1 + T/T_B·(2.5η − 1))  0 ≤ T ≤ T_B
//! S_e = a_g·S·η·2.5                   T_B ≤ T ≤ T_C
//! S_e = a_g·S·η·2.5·T_C/T             T_C ≤ T ≤ T_D
//! S_e = a_g·S·η·2.5·T_C·T_D/T²        T_D ≤ T ≤ 4 s
//! ```
//! | Type 1 | S | T_B | T_C | T_D |   | Type 2 | S | T_B | T_C | T_D |
//! |---|---|---|---|---|---|---|---|---|---|---|
//! | A | 1.00 | 0.15 | 0.4 | 2.0 | | A | 1.00 | 0.05 | 0.25 | 1.2 |
//! | B | 1.20 | 0.15 | 0.5 | 2.0 | | B | 1.35 | 0.05 | 0.25 | 1.2 |
//! | C | 1.15 | 0.20 | 0.6 | 2.0 | | C | 1.50 | 0.10 | 0.25 | 1.2 |
//! | D | 1.35 | 0.20 | 0.8 | 2.0 | | D | 1.80 | 0.10 | 0.30 | 1.2 |
//! | E | 1.40 | 0.15 | 0.5 | 2.0 | | E | 1.60 | 0.05 | 0.25 | 1.2 |
//!
//! EC8 defines the spectrum up to 4 s; beyond, the last branch is continued (the code's Annex A
//! gives the displacement spectrum there instead). Ground types S1 and S2 need special studies and
//! are not offered.
//!
//! **Tabulated target**: given `(T_i, PSA_i)` pairs, `ln PSA` is interpolated linearly in `ln T`
//! (log-log), only inside `[T_first, T_last]`.

use crate::error::SeismoError;
use crate::spectra::intensity::G;

/// ASCE 7-16 §11.4.6 design response spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Asce7 {
    s_ds: f64,
    s_d1: f64,
    t_l: f64,
}

impl Asce7 {
    /// From `S_DS`, `S_D1` (g, > 0) and `T_L` (s, > `T_S` = `S_D1/S_DS`).
    pub fn new(s_ds: f64, s_d1: f64, t_l: f64) -> Result<Self, SeismoError> {
        if !(s_ds > 0.0 && s_ds.is_finite()) {
            return Err(SeismoError::parameter("S_DS", format!("{s_ds} g"), "a finite S_DS > 0 g"));
        }
        if !(s_d1 > 0.0 && s_d1.is_finite()) {
            return Err(SeismoError::parameter("S_D1", format!("{s_d1} g"), "a finite S_D1 > 0 g"));
        }
        let t_s = s_d1 / s_ds;
        if !(t_l > t_s && t_l.is_finite()) {
            return Err(SeismoError::parameter(
                "T_L",
                format!("{t_l} s"),
                format!("a finite T_L > T_S = S_D1/S_DS = {t_s} s"),
            ));
        }
        Ok(Asce7 { s_ds, s_d1, t_l })
    }

    /// `T_0 = 0.2·S_D1/S_DS` (s).
    pub fn t0(&self) -> f64 {
        0.2 * self.s_d1 / self.s_ds
    }

    /// `T_S = S_D1/S_DS` (s).
    pub fn ts(&self) -> f64 {
        self.s_d1 / self.s_ds
    }

    /// Design spectral acceleration at `t` (s, ≥ 0), in m/s².
    pub fn psa(&self, t: f64) -> Result<f64, SeismoError> {
        check_period(t)?;
        let (t0, ts) = (self.t0(), self.ts());
        let sa_g = if t < t0 {
            self.s_ds * (0.4 + 0.6 * t / t0)
        } else if t <= ts {
            self.s_ds
        } else if t <= self.t_l {
            self.s_d1 / t
        } else {
            self.s_d1 * self.t_l / (t * t)
        };
        Ok(sa_g * G)
    }
}

/// EC8 spectrum type (§3.2.2.2(2)P): Type 1 for surface-wave magnitude above 5.5, else Type 2.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ec8Type {
    /// Table 3.2.
    Type1,
    /// Table 3.3.
    Type2,
}

/// EC8 ground type (Table 3.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroundType {
    /// Rock, v_s,30 > 800 m/s.
    A,
    /// Very dense sand, gravel or very stiff clay, 360–800 m/s.
    B,
    /// Dense or medium-dense sand, gravel or stiff clay, 180–360 m/s.
    C,
    /// Loose-to-medium cohesionless soil or soft-to-firm cohesive soil, < 180 m/s.
    D,
    /// A surface alluvium layer of C or D values, 5–20 m thick, over stiffer material.
    E,
}

/// `(S, T_B, T_C, T_D)` of Tables 3.2 and 3.3.
pub fn ec8_parameters(kind: Ec8Type, ground: GroundType) -> (f64, f64, f64, f64) {
    use GroundType::*;
    match (kind, ground) {
        (Ec8Type::Type1, A) => (1.0, 0.15, 0.4, 2.0),
        (Ec8Type::Type1, B) => (1.2, 0.15, 0.5, 2.0),
        (Ec8Type::Type1, C) => (1.15, 0.20, 0.6, 2.0),
        (Ec8Type::Type1, D) => (1.35, 0.20, 0.8, 2.0),
        (Ec8Type::Type1, E) => (1.4, 0.15, 0.5, 2.0),
        (Ec8Type::Type2, A) => (1.0, 0.05, 0.25, 1.2),
        (Ec8Type::Type2, B) => (1.35, 0.05, 0.25, 1.2),
        (Ec8Type::Type2, C) => (1.5, 0.10, 0.25, 1.2),
        (Ec8Type::Type2, D) => (1.8, 0.10, 0.30, 1.2),
        (Ec8Type::Type2, E) => (1.6, 0.05, 0.25, 1.2),
    }
}

/// EN 1998-1 §3.2.2.2 horizontal elastic response spectrum.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ec8 {
    a_g: f64,
    s: f64,
    t_b: f64,
    t_c: f64,
    t_d: f64,
    eta: f64,
}

impl Ec8 {
    /// From the design ground acceleration `a_g` (m/s², > 0), the spectrum type, the ground type
    /// and the viscous damping `xi_percent` (%, 0 ≤ ξ < 100; 5 gives η = 1).
    pub fn new(a_g: f64, kind: Ec8Type, ground: GroundType, xi_percent: f64) -> Result<Self, SeismoError> {
        if !(a_g > 0.0 && a_g.is_finite()) {
            return Err(SeismoError::parameter("a_g", format!("{a_g} m/s²"), "a finite a_g > 0 m/s²"));
        }
        if !(0.0..100.0).contains(&xi_percent) {
            return Err(SeismoError::parameter("xi_percent", format!("{xi_percent} %"), "0 ≤ ξ < 100 %"));
        }
        let (s, t_b, t_c, t_d) = ec8_parameters(kind, ground);
        let eta = (10.0 / (5.0 + xi_percent)).sqrt().max(0.55);
        Ok(Ec8 { a_g, s, t_b, t_c, t_d, eta })
    }

    /// Damping correction η.
    pub fn eta(&self) -> f64 {
        self.eta
    }

    /// Corner periods `(T_B, T_C, T_D)` (s).
    pub fn corners(&self) -> (f64, f64, f64) {
        (self.t_b, self.t_c, self.t_d)
    }

    /// Soil factor S.
    pub fn soil_factor(&self) -> f64 {
        self.s
    }

    /// Elastic spectral acceleration at `t` (s, ≥ 0), in m/s².
    pub fn psa(&self, t: f64) -> Result<f64, SeismoError> {
        check_period(t)?;
        let plateau = self.a_g * self.s * self.eta * 2.5;
        Ok(if t <= self.t_b {
            self.a_g * self.s * (1.0 + t / self.t_b * (2.5 * self.eta - 1.0))
        } else if t <= self.t_c {
            plateau
        } else if t <= self.t_d {
            plateau * self.t_c / t
        } else {
            plateau * self.t_c * self.t_d / (t * t)
        })
    }
}

/// A target spectrum given as `(T, PSA)` pairs, interpolated log-log.
#[derive(Clone, Debug, PartialEq)]
pub struct Tabulated {
    ln_t: Vec<f64>,
    ln_psa: Vec<f64>,
}

impl Tabulated {
    /// From at least two points with strictly increasing periods (s, > 0) and PSA > 0 (any unit;
    /// [`Tabulated::psa`] returns the same unit).
    pub fn new(periods: &[f64], psa: &[f64]) -> Result<Self, SeismoError> {
        if periods.len() != psa.len() || periods.len() < 2 {
            return Err(SeismoError::parameter(
                "periods.len(), psa.len()",
                format!("{}, {}", periods.len(), psa.len()),
                "two arrays of the same length ≥ 2",
            ));
        }
        for (i, (&t, &s)) in periods.iter().zip(psa).enumerate() {
            if !(t > 0.0 && t.is_finite()) || (i > 0 && !(t > periods[i - 1])) {
                return Err(SeismoError::parameter(
                    format!("periods[{i}]"),
                    format!("{t} s"),
                    "finite, > 0 and strictly increasing",
                ));
            }
            if !(s > 0.0 && s.is_finite()) {
                return Err(SeismoError::parameter(format!("psa[{i}]"), s, "finite and > 0 (log-log interpolation)"));
            }
        }
        Ok(Tabulated { ln_t: periods.iter().map(|t| t.ln()).collect(), ln_psa: psa.iter().map(|s| s.ln()).collect() })
    }

    /// PSA at `t` (s), inside the tabulated range.
    pub fn psa(&self, t: f64) -> Result<f64, SeismoError> {
        let (first, last) = (self.ln_t[0].exp(), self.ln_t[self.ln_t.len() - 1].exp());
        if !(t >= first * (1.0 - 1e-12) && t <= last * (1.0 + 1e-12)) {
            return Err(SeismoError::parameter(
                "period",
                format!("{t} s"),
                format!("inside the table, {first} … {last} s"),
            ));
        }
        let x = t.ln().clamp(self.ln_t[0], self.ln_t[self.ln_t.len() - 1]);
        let j = self.ln_t.partition_point(|&v| v <= x).clamp(1, self.ln_t.len() - 1);
        let (x0, x1) = (self.ln_t[j - 1], self.ln_t[j]);
        let w = (x - x0) / (x1 - x0);
        Ok((self.ln_psa[j - 1] + w * (self.ln_psa[j] - self.ln_psa[j - 1])).exp())
    }
}

/// Any of the design spectra of this module.
#[derive(Clone, Debug, PartialEq)]
pub enum DesignSpectrum {
    /// ASCE 7-16 §11.4.6.
    Asce7(Asce7),
    /// EN 1998-1 §3.2.2.2.
    Ec8(Ec8),
    /// Log-log interpolated table.
    Tabulated(Tabulated),
}

impl DesignSpectrum {
    /// PSA at `t` (s): m/s² for the code spectra, the table's unit for a table.
    pub fn psa(&self, t: f64) -> Result<f64, SeismoError> {
        match self {
            DesignSpectrum::Asce7(s) => s.psa(t),
            DesignSpectrum::Ec8(s) => s.psa(t),
            DesignSpectrum::Tabulated(s) => s.psa(t),
        }
    }

    /// PSA on a period grid.
    pub fn on_grid(&self, periods: &[f64]) -> Result<Vec<f64>, SeismoError> {
        periods.iter().map(|&t| self.psa(t)).collect()
    }
}

fn check_period(t: f64) -> Result<(), SeismoError> {
    if !(t >= 0.0 && t.is_finite()) {
        return Err(SeismoError::parameter("period", format!("{t} s"), "a finite period ≥ 0 s"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn asce7_at_every_corner_by_hand() {
        // S_DS = 1.0 g, S_D1 = 0.6 g, T_L = 8 s → T_0 = 0.2·0.6/1.0 = 0.12 s, T_S = 0.6 s.
        let s = Asce7::new(1.0, 0.6, 8.0).unwrap();
        assert!(close(s.t0(), 0.12) && close(s.ts(), 0.6));
        // T = 0: 1.0·(0.4 + 0) = 0.4 g.
        assert!(close(s.psa(0.0).unwrap(), 0.4 * G));
        // T = 0.06 (half of T_0): 1.0·(0.4 + 0.6·0.5) = 0.7 g.
        assert!(close(s.psa(0.06).unwrap(), 0.7 * G));
        // T = T_0 = 0.12: plateau 1.0 g; T = T_S = 0.6: still 1.0 g (S_D1/T_S = 0.6/0.6 = 1.0).
        assert!(close(s.psa(0.12).unwrap(), G) && close(s.psa(0.6).unwrap(), G));
        // T = 2 s: 0.6/2 = 0.3 g; T = T_L = 8: 0.6/8 = 0.075 g.
        assert!(close(s.psa(2.0).unwrap(), 0.3 * G) && close(s.psa(8.0).unwrap(), 0.075 * G));
        // T = 10 s: 0.6·8/100 = 0.048 g (continuous at T_L: 0.6·8/64 = 0.075).
        assert!(close(s.psa(10.0).unwrap(), 0.048 * G));
        let e = Asce7::new(1.0, 0.6, 0.5).unwrap_err().to_string();
        assert!(e.contains("T_L = 0.5 s") && e.contains("T_S = S_D1/S_DS = 0.6 s"), "{e}");
        let e = Asce7::new(-1.0, 0.6, 8.0).unwrap_err().to_string();
        assert!(e.contains("S_DS = -1 g") && e.contains("> 0"), "{e}");
        assert!(s.psa(-1.0).unwrap_err().to_string().contains("period = -1 s"));
    }

    #[test]
    fn ec8_type1_ground_c_at_every_corner_by_hand() {
        // a_g = 0.25 g = 2.4516625 m/s², Type 1, ground C: S = 1.15, T_B = 0.2, T_C = 0.6, T_D = 2.0; ξ = 5% → η = 1.
        let a_g = 0.25 * G;
        let s = Ec8::new(a_g, Ec8Type::Type1, GroundType::C, 5.0).unwrap();
        assert_eq!(s.eta(), 1.0);
        let plateau = a_g * 1.15 * 2.5; // 7.0485296875 m/s²
        assert!(close(s.psa(0.0).unwrap(), a_g * 1.15)); // a_g·S
        assert!(close(s.psa(0.1).unwrap(), a_g * 1.15 * (1.0 + 0.5 * 1.5))); // 1 + (0.1/0.2)(2.5−1)
        assert!(close(s.psa(0.2).unwrap(), plateau) && close(s.psa(0.6).unwrap(), plateau));
        assert!(close(s.psa(1.2).unwrap(), plateau * 0.5)); // T_C/T = 0.6/1.2
        assert!(close(s.psa(2.0).unwrap(), plateau * 0.3)); // 0.6/2.0
        assert!(close(s.psa(4.0).unwrap(), plateau * 0.6 * 2.0 / 16.0)); // T_C·T_D/T² = 1.2/16 = 0.075
    }

    #[test]
    fn ec8_type2_and_damping_correction() {
        // Type 2, ground D: S = 1.8, T_B = 0.1, T_C = 0.3, T_D = 1.2; ξ = 10% → η = √(10/15) = 0.8165.
        let s = Ec8::new(1.0, Ec8Type::Type2, GroundType::D, 10.0).unwrap();
        let eta = (10.0f64 / 15.0).sqrt();
        assert!(close(s.eta(), eta));
        assert!(close(s.psa(0.1).unwrap(), 1.8 * 2.5 * eta)); // plateau at T_B
        assert!(close(s.psa(0.05).unwrap(), 1.8 * (1.0 + 0.5 * (2.5 * eta - 1.0))));
        assert!(close(s.psa(0.6).unwrap(), 1.8 * 2.5 * eta * 0.5)); // T_C/T = 0.3/0.6
        assert!(close(s.psa(2.4).unwrap(), 1.8 * 2.5 * eta * 0.3 * 1.2 / 5.76)); // T_C·T_D/T²
        // ξ = 30% → √(10/35) = 0.5345 < 0.55 → η = 0.55.
        assert_eq!(Ec8::new(1.0, Ec8Type::Type1, GroundType::A, 30.0).unwrap().eta(), 0.55);
        // Every table entry: plateau / a_g = 2.5·S at ξ = 5%.
        for (g, s1, s2) in [(GroundType::A, 1.0, 1.0), (GroundType::B, 1.2, 1.35), (GroundType::E, 1.4, 1.6)] {
            let p1 = Ec8::new(1.0, Ec8Type::Type1, g, 5.0).unwrap();
            let p2 = Ec8::new(1.0, Ec8Type::Type2, g, 5.0).unwrap();
            assert!(
                close(p1.psa(p1.corners().0).unwrap(), 2.5 * s1) && close(p2.psa(p2.corners().1).unwrap(), 2.5 * s2)
            );
        }
        let e = Ec8::new(1.0, Ec8Type::Type1, GroundType::A, -2.0).unwrap_err().to_string();
        assert!(e.contains("xi_percent = -2 %"), "{e}");
    }

    #[test]
    fn tabulated_is_log_log() {
        // 2.0 at 1 s, 0.5 at 4 s: ln PSA(2 s) = ln 2 + (ln 2/ln 4)·(ln 0.5 − ln 2) = ln 2 − ln 2 = 0 → 1.0.
        let t = Tabulated::new(&[0.5, 1.0, 4.0], &[2.0, 2.0, 0.5]).unwrap();
        assert!(close(t.psa(2.0).unwrap(), 1.0));
        assert!(close(t.psa(0.7).unwrap(), 2.0) && close(t.psa(4.0).unwrap(), 0.5));
        assert!(t.psa(5.0).unwrap_err().to_string().contains("inside the table, 0.5 … 4 s"));
        let e = Tabulated::new(&[1.0, 1.0], &[1.0, 2.0]).unwrap_err().to_string();
        assert!(e.contains("periods[1]"), "{e}");
        assert!(Tabulated::new(&[1.0, 2.0], &[1.0, 0.0]).unwrap_err().to_string().contains("psa[1] = 0"));
    }
}
