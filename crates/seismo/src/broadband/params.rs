//! The parameters of the stochastic part, with the Broadband Platform's Western-US defaults of
//! the Graves–Pitarka method (`hfsims_cfg.py` and `hb_high_v6.0.5` of SCEC BBP 22.4; Graves &
//! Pitarka 2010, 2015 and the method's release notes of 2022).

use super::site::Crust;
use super::window::SaragoniHart;
use crate::error::SeismoError;

/// Boore & Thompson (2014, *BSSA* 104, 2541–2552) path duration for the Western US, as the
/// Platform tabulates it (`ipdur_model = 11`): `(R km, D s)`, linear between the points, the last
/// slope continued beyond 270 km.
pub const BOORE_THOMPSON_2014_WUS: [(f64, f64); 6] =
    [(0.0, 0.0), (7.0, 2.4), (45.0, 8.4), (125.0, 10.9), (175.0, 17.4), (270.0, 34.2)];

/// The path duration of [`BOORE_THOMPSON_2014_WUS`] at `r_km` (s).
pub fn path_duration_s(r_km: f64) -> f64 {
    let t = &BOORE_THOMPSON_2014_WUS;
    let r = r_km.max(0.0);
    let k = t.partition_point(|p| p.0 < r).clamp(1, t.len() - 1);
    let ((r0, d0), (r1, d1)) = (t[k - 1], t[k]);
    d0 + (d1 - d0) * (r - r0) / (r1 - r0)
}

/// Which rupture speed sets a subfault's corner frequency.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CornerSpeed {
    /// The Platform's (`hb_high`'s `rvfac`): a seed's factor drawn uniformly in 0.775 ± 0.1,
    /// × 0.6 above 5 km depth (back to 1 by 8 km) and again from max(15 km, the hypocentre's
    /// depth) to 5 km deeper, each subfault's × exp(0.1·N(0, 1)), at most 1.4: the rupture speed
    /// the method's stress parameter was calibrated with.
    Platform,
    /// The deterministic rupture's own local speed at the subfault ([`super::fault`]).
    Lattice,
}

/// The Platform's mean rupture speed over β.
pub const PLATFORM_SPEED_RATIO: f64 = 0.775;

/// Half-width of the uniform spread of a seed's speed factor around [`PLATFORM_SPEED_RATIO`].
pub const PLATFORM_SPEED_SPREAD: f64 = 0.1;

/// Standard deviation of a subfault's ln speed factor.
pub const PLATFORM_SPEED_SIGMA: f64 = 0.1;

/// The largest subfault speed factor.
pub const PLATFORM_SPEED_CAP: f64 = 1.4;

/// The Platform's depth taper of the rupture speed at `depth_m` for a hypocentre at
/// `hypocentre_depth_m`, times [`PLATFORM_SPEED_RATIO`] (its mean speed over β).
pub fn platform_speed_ratio(depth_m: f64, hypocentre_depth_m: f64) -> f64 {
    let z = depth_m / 1000.0;
    let shallow = if z < 5.0 {
        0.6
    } else if z < 8.0 {
        0.6 + 0.4 * (z - 5.0) / 3.0
    } else {
        1.0
    };
    let deep_min = (hypocentre_depth_m / 1000.0).max(15.0);
    let deep = if z <= deep_min {
        1.0
    } else if z < deep_min + 5.0 {
        1.0 - 0.4 * (z - deep_min) / 5.0
    } else {
        0.6
    };
    PLATFORM_SPEED_RATIO * shallow * deep
}

/// The stochastic (high-frequency) part's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stochastic {
    /// Stress parameter before its scaling with the rupture's area (Pa). Default 5 MPa (50 bar).
    pub stress_parameter_pa: f64,
    /// Exponent x of the area scaling `(A0/A)^x` (0: none). Default 0.5 (the method's 2022 release).
    pub stress_area_exponent: f64,
    /// High-frequency diminution κ₀ (s). Default 0.04.
    pub kappa_s: f64,
    /// Q at 1 Hz (`Q(f) = Q0·f^η`); `None`: `57 + 34·β` with β in km/s (the Platform's rule).
    pub q0: Option<f64>,
    /// Exponent η of Q(f). Default 0.6.
    pub q_exponent: f64,
    /// The corner-frequency constant `Czero` of `fc = Czero·(v_r/β)·β/(π·dl)`. Default 2.0.
    pub corner_constant: f64,
    /// Radiation coefficient of each horizontal component. Default 0.42: the root mean square of
    /// the Platform's conically averaged S radiation projected on a horizontal component for a
    /// vertical strike-slip source (0.36–0.52 with azimuth).
    pub radiation_horizontal: f64,
    /// Radiation coefficient of the vertical component. Default 0.075 (the Platform's 0.06–0.09).
    pub radiation_vertical: f64,
    /// Target subfault size (m). Default 1000.
    pub subfault_m: f64,
    /// The envelope: Saragoni–Hart, ε = 0.2, η = 0.05, reaching η at one ground-motion
    /// duration (the Platform's; Boore 2003 uses two).
    pub window: SaragoniHart,
    /// Sampling interval of the synthesis and of the broadband record (s). Default 0.01.
    pub interval_s: f64,
    /// The crust of the stochastic part. Default generic rock.
    pub crust: Crust,
    /// The rupture speed of the subfault corners. Default the Platform's.
    pub corner_speed: CornerSpeed,
}

impl Default for Stochastic {
    fn default() -> Self {
        Stochastic {
            stress_parameter_pa: 5e6,
            stress_area_exponent: 0.5,
            kappa_s: 0.04,
            q0: None,
            q_exponent: 0.6,
            corner_constant: 2.0,
            radiation_horizontal: 0.42,
            radiation_vertical: 0.075,
            subfault_m: 1000.0,
            window: SaragoniHart { epsilon: 0.2, eta: 0.05, duration_factor: 1.0 },
            interval_s: 0.01,
            crust: Crust::GenericRock,
            corner_speed: CornerSpeed::Platform,
        }
    }
}

impl Stochastic {
    /// `Q0` for a crust of S-wave speed `s_speed_m_s`: the given one or `57 + 34·β` (β in km/s).
    pub fn q0_for(&self, s_speed_m_s: f64) -> f64 {
        self.q0.unwrap_or(57.0 + 34.0 * s_speed_m_s / 1000.0)
    }

    /// The stress parameter for a rupture of magnitude `mw` over `area_m2` (Pa):
    /// `Δσ_p·(A0/A)^x`, with A0 the average of Leonard (2014), `10^(M − 3.99)` km², and, for
    /// M ≥ 6.71, Hanks & Bakun (2002), `10^(0.75·(M − 3.07))` km² (the Platform's `ispar_adjust
    /// = 1`).
    pub fn stress_parameter(&self, mw: f64, area_m2: f64) -> f64 {
        if self.stress_area_exponent == 0.0 || !(area_m2 > 0.0) {
            return self.stress_parameter_pa;
        }
        let leonard = 10f64.powf(mw - 3.99);
        let a0_km2 = if mw >= 6.71 { 0.5 * (leonard + 10f64.powf(0.75 * (mw - 3.07))) } else { leonard };
        self.stress_parameter_pa * (a0_km2 * 1e6 / area_m2).powf(self.stress_area_exponent)
    }

    /// Refuses a parameter outside its range, naming it as `prefix` + the pipeline key.
    pub fn check(&self, prefix: &str) -> Result<(), SeismoError> {
        let field = |name: &str| format!("{prefix}{name}");
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 { Ok(()) } else { Err(SeismoError::parameter(field(name), v, "> 0")) }
        };
        positive("stress_parameter_pa", self.stress_parameter_pa)?;
        if !(self.stress_area_exponent.is_finite() && (0.0..=1.5).contains(&self.stress_area_exponent)) {
            return Err(SeismoError::parameter(
                field("stress_area_exponent"),
                self.stress_area_exponent,
                "0 ≤ x ≤ 1.5 (1.5 scales the stress parameter as a static stress drop; 0 turns the scaling off)",
            ));
        }
        if !(self.kappa_s.is_finite() && (0.0..=0.2).contains(&self.kappa_s)) {
            return Err(SeismoError::parameter(
                field("kappa_s"),
                self.kappa_s,
                "0 ≤ κ₀ ≤ 0.2 s (hard rock about 0.006, Western-US rock 0.04)",
            ));
        }
        if let Some(q) = self.q0 {
            positive("q0", q)?;
        }
        if !(self.q_exponent.is_finite() && (0.0..=1.0).contains(&self.q_exponent)) {
            return Err(SeismoError::parameter(field("q_exponent"), self.q_exponent, "0 ≤ η ≤ 1"));
        }
        positive("corner_constant", self.corner_constant)?;
        positive("radiation_horizontal", self.radiation_horizontal)?;
        positive("radiation_vertical", self.radiation_vertical)?;
        positive("subfault_m", self.subfault_m)?;
        self.window.check(prefix)?;
        if !(self.interval_s.is_finite() && self.interval_s > 0.0 && self.interval_s <= 0.02) {
            return Err(SeismoError::parameter(
                field("interval_s"),
                self.interval_s,
                "0 < Δt ≤ 0.02 s (a broadband record carries at least 25 Hz)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_path_duration_follows_its_table() {
        assert_eq!(path_duration_s(0.0), 0.0);
        assert!((path_duration_s(7.0) - 2.4).abs() < 1e-12);
        assert!((path_duration_s(26.0) - (2.4 + 6.0 * 19.0 / 38.0)).abs() < 1e-12);
        // Beyond 270 km the last slope, 16.8/95 s/km.
        assert!((path_duration_s(370.0) - (34.2 + 100.0 * 16.8 / 95.0)).abs() < 1e-12);
    }

    #[test]
    fn the_stress_parameter_scales_with_the_area_as_the_platform_does() {
        let p = Stochastic::default();
        // M 7.22 on 80 × 15 km: A0 = ½(10^3.23 + 10^3.1125) = 1497 km², 50·√(1497/1200) = 55.8 bar.
        let s = p.stress_parameter(7.22, 80e3 * 15e3);
        assert!((s / 1e5 - 55.85).abs() < 0.05, "{}", s / 1e5);
        // Below M 6.71 Leonard alone: M 6 on its own A0 keeps 50 bar.
        let a0 = 10f64.powf(6.0 - 3.99) * 1e6;
        assert!((p.stress_parameter(6.0, a0) - 5e6).abs() < 1e-6);
        let off = Stochastic { stress_area_exponent: 0.0, ..p };
        assert_eq!(off.stress_parameter(6.0, 1.0), 5e6);
        // Q0 of the lattice's rock: 57 + 34·3.464 = 174.8.
        assert!((p.q0_for(3464.0) - 174.776).abs() < 1e-9);
    }

    #[test]
    fn the_platform_rupture_speed_is_slow_near_the_surface_and_deep() {
        assert!((platform_speed_ratio(2000.0, 8000.0) - 0.465).abs() < 1e-12);
        assert!((platform_speed_ratio(6500.0, 8000.0) - 0.775 * 0.8).abs() < 1e-12);
        assert!((platform_speed_ratio(10_000.0, 8000.0) - 0.775).abs() < 1e-12);
        assert!((platform_speed_ratio(17_500.0, 8000.0) - 0.775 * 0.8).abs() < 1e-12);
        assert!((platform_speed_ratio(21_000.0, 18_000.0) - 0.775 * (1.0 - 0.4 * 0.6)).abs() < 1e-12);
    }

    #[test]
    fn bad_values_are_refused_by_name() {
        let cases = [
            (Stochastic { kappa_s: -0.01, ..Default::default() }, "broadband.kappa_s"),
            (Stochastic { q0: Some(0.0), ..Default::default() }, "broadband.q0"),
            (Stochastic { interval_s: 0.05, ..Default::default() }, "broadband.interval_s"),
            (Stochastic { stress_parameter_pa: f64::NAN, ..Default::default() }, "broadband.stress_parameter_pa"),
        ];
        for (p, field) in cases {
            let e = p.check("broadband.").unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
        assert!(Stochastic::default().check("broadband.").is_ok());
    }
}
