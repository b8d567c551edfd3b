//! `[broadband]`: broadband records of a fault scene's surface stations (docs/model.md §17), the
//! lattice's motion below `crossover_hz` joined to a stochastic finite-fault synthesis of the same
//! rupture above it (the SCEC Broadband Platform's Graves–Pitarka method), at each station's
//! V_S30. Every parameter of the stochastic part has the Platform's Western-US default.

use serde::{Deserialize, Serialize};
use stickslip_analysis::broadband::{BroadbandSettings, SiteSpec};
use stickslip_seismo::broadband::window::SaragoniHart;
use stickslip_seismo::broadband::{CornerSpeed, Crossover, Crust, Stochastic};
use stickslip_solver::Scene;

use crate::check::{Checker, approx};
use crate::scene::{StationSection, Vs30};

/// The V_S30 range of the site terms (BSSA14's, m/s).
pub const VS30_RANGE_M_S: [f64; 2] = [150.0, 1500.0];

/// `[broadband]` as written; absent keys take the Platform's Western-US defaults.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct BroadbandSection {
    /// Crossover frequency f_m (Hz). Default 1.
    pub crossover_hz: f64,
    /// V_S30 of every station without its own (m/s), one value or a list. Default 760.
    pub vs30_m_s: Vs30,
    /// Sampling interval of the broadband records (s). Default 0.01.
    pub interval_s: f64,
    /// Stress parameter before its area scaling (Pa). Default 5e6 (50 bar).
    pub stress_parameter_pa: f64,
    /// Exponent of the stress parameter's area scaling (0: none). Default 0.5.
    pub stress_area_exponent: f64,
    /// κ₀ (s). Default 0.04.
    pub kappa_s: f64,
    /// Q at 1 Hz; absent: 57 + 34·V_S (km/s) of the lattice.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub q0: Option<f64>,
    /// Exponent η of Q(f) = Q0·f^η. Default 0.6.
    pub q_exponent: f64,
    /// The constant of the subfault corner `Czero·(v_r/β)·β/(π·dl)`. Default 2.
    pub corner_constant: f64,
    /// Radiation coefficient of a horizontal component. Default 0.42.
    pub radiation_horizontal: f64,
    /// Radiation coefficient of the vertical component. Default 0.075.
    pub radiation_vertical: f64,
    /// Subfault size (m). Default 1000.
    pub subfault_m: f64,
    /// The stochastic part's crust: `"generic_rock"` (Boore & Joyner 1997, V_S30 620 m/s; default)
    /// or `"homogeneous"` (the lattice's half-space).
    pub crust: String,
    /// Saragoni–Hart ε. Default 0.2.
    pub window_epsilon: f64,
    /// Saragoni–Hart η. Default 0.05.
    pub window_eta: f64,
    /// Where the window reaches η, in ground-motion durations. Default 1 (the Platform's).
    pub window_duration_factor: f64,
    /// The rupture speed of the subfault corners: `"platform"` (the Platform's kinematic
    /// 0.775 ± 0.1·β, slower above 5 km, with which its stress parameter was calibrated; default) or
    /// `"lattice"` (the lattice rupture's own local speed).
    pub corner_speed: String,
}

impl Default for BroadbandSection {
    fn default() -> Self {
        let p = Stochastic::default();
        BroadbandSection {
            crossover_hz: 1.0,
            vs30_m_s: Vs30::default(),
            interval_s: p.interval_s,
            stress_parameter_pa: p.stress_parameter_pa,
            stress_area_exponent: p.stress_area_exponent,
            kappa_s: p.kappa_s,
            q0: p.q0,
            q_exponent: p.q_exponent,
            corner_constant: p.corner_constant,
            radiation_horizontal: p.radiation_horizontal,
            radiation_vertical: p.radiation_vertical,
            subfault_m: p.subfault_m,
            crust: "generic_rock".into(),
            window_epsilon: p.window.epsilon,
            window_eta: p.window.eta,
            window_duration_factor: p.window.duration_factor,
            corner_speed: "platform".into(),
        }
    }
}

/// Checks a list of V_S30 at `field`, returning the valid ones.
fn sites(ck: &mut Checker, field: &str, v: &Vs30) -> Vec<f64> {
    let values = v.values();
    if values.is_empty() {
        ck.push(field, "[]", "one V_S30 or a list of at least one");
    }
    let mut out = Vec::new();
    for (k, &x) in values.iter().enumerate() {
        let f = if matches!(v, Vs30::One(_)) { field.to_string() } else { format!("{field}[{k}]") };
        let [lo, hi] = VS30_RANGE_M_S;
        if !(x.is_finite() && (lo..=hi).contains(&x)) {
            ck.push(
                f,
                x,
                format!("{lo} ≤ V_S30 ≤ {hi} m/s, the range of the BSSA14 site terms that take each part to the site"),
            );
        } else if out.contains(&x) {
            ck.push(f, x, "each V_S30 once");
        } else {
            out.push(x);
        }
    }
    out
}

/// The name of a station's record on a site: its own name with one site, `<name>_vs<V_S30>` with
/// several.
fn record_name(station: &str, vs30: f64, several: bool) -> String {
    if several { format!("{station}_vs{}", approx(vs30)) } else { station.to_string() }
}

impl BroadbandSection {
    /// The stochastic part's parameters as given (unchecked).
    pub fn stochastic(&self, scene: Option<&Scene>) -> Stochastic {
        let crust = match self.crust.as_str() {
            "homogeneous" => Crust::Homogeneous { s_speed_m_s: scene.map_or(f64::NAN, Scene::s_wave_speed) },
            _ => Crust::GenericRock,
        };
        Stochastic {
            stress_parameter_pa: self.stress_parameter_pa,
            stress_area_exponent: self.stress_area_exponent,
            kappa_s: self.kappa_s,
            q0: self.q0,
            q_exponent: self.q_exponent,
            corner_constant: self.corner_constant,
            radiation_horizontal: self.radiation_horizontal,
            radiation_vertical: self.radiation_vertical,
            subfault_m: self.subfault_m,
            window: SaragoniHart {
                epsilon: self.window_epsilon,
                eta: self.window_eta,
                duration_factor: self.window_duration_factor,
            },
            interval_s: self.interval_s,
            crust,
            corner_speed: if self.corner_speed == "lattice" { CornerSpeed::Lattice } else { CornerSpeed::Platform },
        }
    }

    /// The validated settings for `scene` with its `[[stations]]`, every refusal recorded in `ck`.
    pub fn build(
        &self,
        scene: &Scene,
        stations: &[StationSection],
        checker: &mut Checker,
    ) -> Option<BroadbandSettings> {
        // Its own refusals, so that one elsewhere in the file does not make this section's
        // settings absent (and the set's checks wrong).
        let mut own = Checker::default();
        let ck = &mut own;
        if !scene.is_fault() {
            ck.push(
                "broadband",
                "a [broadband] section on a scene without [fault]",
                "a fault scene: the stochastic part is synthesized from the rupture of [fault] (its slip and rupture \
                 times)",
            );
            checker.absorb(own);
            return None;
        }
        if !["generic_rock", "homogeneous"].contains(&self.crust.as_str()) {
            ck.push("broadband.crust", format!("{:?}", self.crust), "one of generic_rock, homogeneous");
        }
        if !["platform", "lattice"].contains(&self.corner_speed.as_str()) {
            ck.push("broadband.corner_speed", format!("{:?}", self.corner_speed), "one of platform, lattice");
        }
        let p = self.stochastic(Some(scene));
        match p.check("broadband.") {
            Ok(()) => {}
            Err(stickslip_seismo::SeismoError::Parameter { name, value, allowed }) => ck.push(name, value, allowed),
            Err(other) => ck.push("broadband", other.to_string(), "parameters the stochastic part accepts"),
        }
        let f_max = scene.usable_band(stickslip_analysis::motions::DEPARTURE).map(|b| b.f_max_hz).unwrap_or(f64::NAN);
        if !(self.crossover_hz.is_finite() && self.crossover_hz > 0.0 && self.crossover_hz <= 0.5 * f_max) {
            ck.push(
                "broadband.crossover_hz",
                self.crossover_hz,
                format!(
                    "0 < f_m ≤ {} Hz, half the lattice's usable f_max of {} Hz (Lc = {} m): the lattice's part is \
                     low-passed at f_m and must be accurate an octave above it (a finer lattice raises f_max)",
                    approx(0.5 * f_max),
                    approx(f_max),
                    approx(scene.lc_m)
                ),
            );
        }
        let defaults = sites(ck, "broadband.vs30_m_s", &self.vs30_m_s);
        let lattice = scene.lattice();
        let mut specs = Vec::new();
        for st in &scene.stations {
            if lattice.position(st.node)[1] != 0.0 {
                continue;
            }
            // The section the station (or its line) came from: its own V_S30, if any.
            let section = stations.iter().enumerate().find(|(_, s)| {
                s.name == st.name
                    || st.name.strip_prefix(&format!("{}-", s.name)).is_some_and(|k| k.parse::<u64>().is_ok())
            });
            let own = section
                .and_then(|(i, s)| s.vs30_m_s.as_ref().map(|v| sites(ck, &format!("stations[{i}].vs30_m_s"), v)));
            let values = own.unwrap_or_else(|| defaults.clone());
            for &v in &values {
                specs.push(SiteSpec {
                    station: st.name.clone(),
                    record: record_name(&st.name, v, values.len() > 1),
                    vs30_m_s: v,
                });
            }
        }
        if specs.is_empty() && scene.stations.iter().all(|s| lattice.position(s.node)[1] != 0.0) {
            ck.push(
                "broadband",
                "no station on the free surface (y = 0)",
                "at least one [[stations]] point at depth y = 0: broadband records are surface motions",
            );
        }
        let names: Vec<&str> = scene.stations.iter().map(|s| s.name.as_str()).collect();
        for s in &specs {
            if s.record != s.station && names.contains(&s.record.as_str()) {
                ck.push(
                    "stations",
                    format!("{:?}", s.record),
                    "station names other than the records' <name>_vs<V_S30> (a station with several sites gives one \
                     record per site under that name)",
                );
            }
        }
        let valid = own.is_clean();
        checker.absorb(own);
        valid.then_some(BroadbandSettings { stochastic: p, crossover: Crossover::new(self.crossover_hz), sites: specs })
    }
}

#[cfg(test)]
mod tests {
    use crate::pipeline::Pipeline;

    const SCENE: &str = r#"
version = 1
[block]
nx = 24
ny = 8
nz = 12
lc_m = 500.0
[material]
young_pa = 8.0104e10
density_kg_m3 = 2670.0
poisson = 0.25
[friction]
mu_static = 0.6
mu_dynamic = 0.525
slip_weakening_m = 0.2
heals = false
[fault]
normal_stress_pa = 120e6
shear_stress_pa = 66.5e6
[self_weight]
gravity_m_s2 = 0.0
[shear]
damping_per_s = 0.0
duration_s = 5.0
[[stations]]
name = "near"
at_m = [6000.0, 0.0, 2000.0]
[[stations]]
name = "soft"
at_m = [6000.0, 0.0, 4000.0]
vs30_m_s = 300.0
[[stations]]
name = "deep"
at_m = [6000.0, 2000.0, 2000.0]
[[stations]]
name = "line"
from_m = [1000.0, 0.0, 5000.0]
to_m = [3000.0, 0.0, 5000.0]
count = 2
"#;

    fn sites(extra: &str) -> Vec<(String, String, f64)> {
        let p = Pipeline::from_toml(&format!("{SCENE}{extra}"), "t").unwrap();
        let b = p.analysis.broadband.expect("broadband settings");
        b.sites.into_iter().map(|s| (s.station, s.record, s.vs30_m_s)).collect()
    }

    #[test]
    fn each_surface_station_gives_one_record_per_site_named_by_it_with_several() {
        // One default site: the stations' own names; a station's own V_S30 wins; the buried
        // station has none; a line's points take the line's.
        let one = sites("[broadband]\nvs30_m_s = 760.0\n");
        let mut names: Vec<(&str, f64)> = one.iter().map(|s| (s.1.as_str(), s.2)).collect();
        names.sort_by(|a, b| a.0.cmp(b.0));
        assert_eq!(names, [("line-0", 760.0), ("line-1", 760.0), ("near", 760.0), ("soft", 300.0)]);
        // Two sites: <name>_vs<V_S30>; the station with its own single site keeps its name.
        let two = sites("[broadband]\nvs30_m_s = [760.0, 400.0]\n");
        let near: Vec<&str> = two.iter().filter(|s| s.0 == "near").map(|s| s.1.as_str()).collect();
        assert_eq!(near, ["near_vs760", "near_vs400"]);
        assert!(two.iter().any(|s| s.1 == "soft" && s.2 == 300.0));
        assert!(!two.iter().any(|s| s.0 == "deep"));
    }

    #[test]
    fn the_defaults_are_the_platforms_and_change_the_hash_only_when_present() {
        let without = Pipeline::from_toml(SCENE, "t").unwrap();
        let with = Pipeline::from_toml(&format!("{SCENE}[broadband]\n"), "t").unwrap();
        assert!(without.analysis.broadband.is_none());
        assert_ne!(without.hash, with.hash);
        let b = with.analysis.broadband.unwrap();
        assert_eq!(b.crossover.hz, 1.0);
        assert_eq!(b.stochastic, stickslip_seismo::broadband::Stochastic::default());
    }
}
