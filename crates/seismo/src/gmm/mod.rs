//! NGA-West2 ground-motion models, fault-to-site distances, and the validation statistics of the
//! SCEC Broadband Platform.
//!
//! - [`Model`]: BSSA14 (Boore, Stewart, Seyhan & Atkinson 2014, [`bssa14`]), ASK14 (Abrahamson,
//!   Silva & Kamai 2014, [`ask14`]), CB14 (Campbell & Bozorgnia 2014, [`cb14`]) and CY14 (Chiou &
//!   Youngs 2014, [`cy14`]), each giving the median and the aleatory standard deviations
//!   (between-event τ, within-event φ, total σ = √(τ² + φ²), natural-log units) of RotD50 PGA, PGV
//!   and 5%-damped PSA for a [`Rupture`] and a [`Site`]. Coefficients: [`tables`](self) and
//!   `tables_nga2` (sources named there). Models are used with their California/global defaults (no
//!   regional terms) for mainshocks; an input a model needs and the caller lacks (Z_1.0, Z_2.5,
//!   Z_hyp) takes that model's own default, named in its module.
//! - Periods between two tabulated periods: the model is evaluated at both and `ln Y`, `τ` and `φ`
//!   are interpolated linearly in `ln T` (σ recomputed from them); a period outside the table
//!   (0.01–10 s for all four models) is refused.
//! - Applicability: each model's magnitude, distance and V_S30 ranges are data ([`Limits`]); a
//!   prediction outside them is still computed (the equations are smooth there) but carries
//!   [`Applicability::Outside`] naming every excursion, never silently.
//! - [`fault`]: R_rup, R_JB, R_x, R_y0, epicentral and hypocentral distances of a site from a
//!   rectangular planar fault.
//! - [`validation`]: residuals ln(sim/model), mean bias with its 90% interval, between-record
//!   spread, fraction within ±1σ, the Goulet et al. (2015) Part-B band, and attenuation slopes.
//!
//! Medians are returned in SI units (PGA and PSA in m/s², PGV in m/s), the units of the product's
//! records; the models' own units (g, cm/s) are converted with g = 9.80665 m/s². Equations and
//! sources: `docs/model.md`, section "Ground-motion models".

pub mod ask14;
pub mod bssa14;
pub mod cb14;
pub mod cy14;
pub mod fault;
mod tables;
mod tables_nga2;
pub mod validation;

use std::fmt;

use crate::error::SeismoError;
use crate::spectra::intensity::G;

/// Style of faulting, as the models classify it from the rake λ.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Mechanism {
    /// Strike-slip (and oblique slip not classified below).
    StrikeSlip,
    /// Normal: −150° < λ < −30°.
    Normal,
    /// Reverse (and reverse-oblique): 30° < λ < 150°.
    Reverse,
}

impl Mechanism {
    /// The class of a rake (degrees, any real value, wrapped to (−180°, 180°]) by the BSSA14 and
    /// ASK14 convention: reverse for 30° < λ < 150°, normal for −150° < λ < −30°, strike-slip
    /// otherwise.
    pub fn from_rake(rake_deg: f64) -> Mechanism {
        let mut r = rake_deg % 360.0;
        if r > 180.0 {
            r -= 360.0;
        } else if r <= -180.0 {
            r += 360.0;
        }
        if r > 30.0 && r < 150.0 {
            Mechanism::Reverse
        } else if r > -150.0 && r < -30.0 {
            Mechanism::Normal
        } else {
            Mechanism::StrikeSlip
        }
    }
}

/// The rupture, as the models describe it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rupture {
    /// Moment magnitude M_w.
    pub mw: f64,
    /// Style of faulting.
    pub mechanism: Mechanism,
    /// Dip δ (degrees, 0 < δ ≤ 90).
    pub dip_deg: f64,
    /// Depth to the top of the rupture Z_tor (km, ≥ 0).
    pub ztor_km: f64,
    /// Down-dip width W (km, > 0).
    pub width_km: f64,
    /// Depth of the hypocentre Z_hyp (km, ≥ 0), used by CB14 only; `None` lets CB14 estimate it
    /// from M, δ, Z_tor and W ([`cb14::hypo_depth_km`], the paper's eq. 35–37).
    pub hypo_depth_km: Option<f64>,
}

/// The site and its distances to the rupture (km), as the models use them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Site {
    /// Closest distance to the rupture plane R_rup (km, ≥ R_JB).
    pub r_rup_km: f64,
    /// Joyner–Boore distance R_JB, to the surface projection of the rupture (km, ≥ 0).
    pub r_jb_km: f64,
    /// R_x: horizontal distance from the top edge of the rupture, perpendicular to strike,
    /// positive on the hanging wall (km, any sign).
    pub r_x_km: f64,
    /// R_y0: horizontal distance off the end of the rupture, parallel to strike (km, ≥ 0); `None`
    /// lets ASK14 use its R_JB form of the hanging-wall taper T5.
    pub r_y0_km: Option<f64>,
    /// Time-averaged shear-wave velocity of the top 30 m V_S30 (m/s, > 0).
    pub vs30_m_s: f64,
    /// Depth to V_S = 1 km/s Z_1.0 (km, ≥ 0), used by BSSA14, ASK14 and CY14; `None` uses each
    /// model's V_S30-based default, which switches its basin term off.
    pub z1_km: Option<f64>,
    /// Depth to V_S = 2.5 km/s Z_2.5 (km, ≥ 0), used by CB14 only; `None` uses CB14's California
    /// V_S30 relation ([`cb14::z25_california_km`], the paper's eq. 33).
    pub z25_km: Option<f64>,
    /// Whether V_S30 was measured (ASK14's within-event φ uses s1m/s2m, CY14's 0.7) or inferred
    /// (s1e/s2e, σ3).
    pub vs30_measured: bool,
}

impl Site {
    /// A site at the given distances on ground of the given V_S30 (m/s), with the models' default
    /// Z_1.0 and Z_2.5 and a measured V_S30 (a simulated site's V_S30 is known exactly).
    pub fn new(distances: fault::Distances, vs30_m_s: f64) -> Site {
        Site {
            r_rup_km: distances.r_rup_km,
            r_jb_km: distances.r_jb_km,
            r_x_km: distances.r_x_km,
            r_y0_km: Some(distances.r_y0_km),
            vs30_m_s,
            z1_km: None,
            z25_km: None,
            vs30_measured: true,
        }
    }
}

/// An intensity measure: the RotD50 horizontal component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Imt {
    /// Peak ground acceleration (m/s²).
    Pga,
    /// Peak ground velocity (m/s).
    Pgv,
    /// 5%-damped pseudo-spectral acceleration at a period (s) (m/s²).
    Psa(f64),
}

impl fmt::Display for Imt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Imt::Pga => write!(f, "PGA"),
            Imt::Pgv => write!(f, "PGV"),
            Imt::Psa(t) => write!(f, "PSA({t} s)"),
        }
    }
}

/// A quantity with an applicability range.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Quantity {
    /// Moment magnitude.
    Magnitude,
    /// R_JB (km).
    RJb,
    /// R_rup (km).
    RRup,
    /// V_S30 (m/s).
    Vs30,
}

impl fmt::Display for Quantity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Quantity::Magnitude => "M_w",
            Quantity::RJb => "R_JB (km)",
            Quantity::RRup => "R_rup (km)",
            Quantity::Vs30 => "V_S30 (m/s)",
        })
    }
}

/// A closed range `[low, high]` of a quantity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// The quantity.
    pub quantity: Quantity,
    /// Smallest value covered.
    pub low: f64,
    /// Largest value covered.
    pub high: f64,
}

impl Range {
    fn contains(&self, v: f64) -> bool {
        v >= self.low && v <= self.high
    }
}

/// The ranges a model was developed for and its authors recommend it in.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Magnitude range of strike-slip ruptures.
    pub mw_strike_slip: Range,
    /// Magnitude range of reverse ruptures.
    pub mw_reverse: Range,
    /// Magnitude range of normal ruptures.
    pub mw_normal: Range,
    /// Distance range (the model's own distance metric).
    pub distance: Range,
    /// V_S30 range.
    pub vs30: Range,
    /// Tabulated periods (s): the first and the last.
    pub periods_s: [f64; 2],
}

impl Limits {
    /// The magnitude range for a mechanism.
    pub fn mw(&self, mechanism: Mechanism) -> Range {
        match mechanism {
            Mechanism::StrikeSlip => self.mw_strike_slip,
            Mechanism::Reverse => self.mw_reverse,
            Mechanism::Normal => self.mw_normal,
        }
    }
}

/// A value outside a model's range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Excursion {
    /// The range left.
    pub range: Range,
    /// The value given.
    pub value: f64,
}

impl fmt::Display for Excursion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = {} outside [{}, {}]", self.range.quantity, self.value, self.range.low, self.range.high)
    }
}

/// Whether a prediction is inside the model's ranges.
#[derive(Clone, Debug, PartialEq)]
pub enum Applicability {
    /// Magnitude, distance and V_S30 are all inside the model's ranges.
    Inside,
    /// The prediction extrapolates the model: every quantity outside its range.
    Outside(Vec<Excursion>),
}

impl Applicability {
    /// Whether the prediction is inside the model's ranges.
    pub fn is_inside(&self) -> bool {
        matches!(self, Applicability::Inside)
    }
}

/// A model's prediction for one rupture, site and intensity measure.
#[derive(Clone, Debug, PartialEq)]
pub struct Prediction {
    /// Natural log of the median, in SI units (ln m/s² for PGA and PSA, ln m/s for PGV).
    pub ln_median: f64,
    /// Between-event standard deviation τ (natural log).
    pub tau: f64,
    /// Within-event standard deviation φ (natural log).
    pub phi: f64,
    /// Total standard deviation σ = √(τ² + φ²) (natural log).
    pub sigma: f64,
    /// Whether the inputs are inside the model's ranges.
    pub applicability: Applicability,
}

impl Prediction {
    /// The median (m/s² for PGA and PSA, m/s for PGV).
    pub fn median(&self) -> f64 {
        self.ln_median.exp()
    }
}

/// A model's value at one tabulated intensity measure, in the model's units (ln g or ln cm/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Estimate {
    pub ln_y: f64,
    pub tau: f64,
    pub phi: f64,
}

/// The ground-motion models on offer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Model {
    /// Boore, Stewart, Seyhan & Atkinson (2014).
    Bssa14,
    /// Abrahamson, Silva & Kamai (2014).
    Ask14,
    /// Campbell & Bozorgnia (2014).
    Cb14,
    /// Chiou & Youngs (2014).
    Cy14,
}

impl Model {
    /// Every model, in the order of their names.
    pub const ALL: [Model; 4] = [Model::Bssa14, Model::Ask14, Model::Cb14, Model::Cy14];

    /// The short name (`bssa14`, `ask14`, `cb14`, `cy14`), as a command line spells it.
    pub fn name(self) -> &'static str {
        match self {
            Model::Bssa14 => "bssa14",
            Model::Ask14 => "ask14",
            Model::Cb14 => "cb14",
            Model::Cy14 => "cy14",
        }
    }

    /// The reference of the model.
    pub fn citation(self) -> &'static str {
        match self {
            Model::Bssa14 => {
                "Boore, Stewart, Seyhan & Atkinson (2014), Earthquake Spectra 30(3):1057-1085, doi:10.1193/070113EQS184M"
            }
            Model::Ask14 => {
                "Abrahamson, Silva & Kamai (2014), Earthquake Spectra 30(3):1025-1055, doi:10.1193/070913EQS198M"
            }
            Model::Cb14 => "Campbell & Bozorgnia (2014), Earthquake Spectra 30(3):1087-1115, doi:10.1193/062913EQS175M",
            Model::Cy14 => "Chiou & Youngs (2014), Earthquake Spectra 30(3):1117-1153, doi:10.1193/072813EQS219M",
        }
    }

    /// The model of a short name (case-insensitive), or an error naming the ones on offer.
    pub fn parse(name: &str) -> Result<Model, SeismoError> {
        let lower = name.trim().to_ascii_lowercase();
        Model::ALL.into_iter().find(|m| m.name() == lower).ok_or_else(|| {
            let names: Vec<&str> = Model::ALL.iter().map(|m| m.name()).collect();
            SeismoError::parameter("model", name, format!("one of {}", names.join(", ")))
        })
    }

    /// The model's ranges.
    pub fn limits(self) -> Limits {
        match self {
            Model::Bssa14 => bssa14::LIMITS,
            Model::Ask14 => ask14::LIMITS,
            Model::Cb14 => cb14::LIMITS,
            Model::Cy14 => cy14::LIMITS,
        }
    }

    /// The tabulated PSA periods (s), increasing.
    pub fn periods(self) -> Vec<f64> {
        self.table_periods().to_vec()
    }

    fn table_periods(self) -> &'static [f64] {
        match self {
            Model::Bssa14 => &bssa14::PERIODS,
            Model::Ask14 => &ask14::PERIODS,
            Model::Cb14 => &cb14::PERIODS,
            Model::Cy14 => &cy14::PERIODS,
        }
    }

    /// Median and standard deviations of `imt` for `rupture` recorded at `site`.
    ///
    /// Refused (nothing computed): non-finite inputs, M_w outside [0, 10], δ outside (0°, 90°],
    /// Z_tor < 0, W ≤ 0, Z_hyp < 0, negative distances, R_JB > R_rup, V_S30 ≤ 0, Z_1.0 < 0,
    /// Z_2.5 < 0, a period outside the model's table. Flagged ([`Applicability::Outside`]) but
    /// computed: M_w, distance or V_S30 outside the model's [`Limits`].
    pub fn predict(self, rupture: &Rupture, site: &Site, imt: Imt) -> Result<Prediction, SeismoError> {
        check_inputs(rupture, site)?;
        let est = self.estimate(rupture, site, imt)?;
        let to_si = match imt {
            Imt::Pgv => 0.01_f64.ln(),
            Imt::Pga | Imt::Psa(_) => G.ln(),
        };
        Ok(Prediction {
            ln_median: est.ln_y + to_si,
            tau: est.tau,
            phi: est.phi,
            sigma: est.tau.hypot(est.phi),
            applicability: self.applicability(rupture, site),
        })
    }

    /// Whether `rupture` and `site` are inside the model's ranges.
    pub fn applicability(self, rupture: &Rupture, site: &Site) -> Applicability {
        let limits = self.limits();
        let distance = match limits.distance.quantity {
            Quantity::RJb => site.r_jb_km,
            _ => site.r_rup_km,
        };
        let excursions: Vec<Excursion> =
            [(limits.mw(rupture.mechanism), rupture.mw), (limits.distance, distance), (limits.vs30, site.vs30_m_s)]
                .into_iter()
                .filter(|(range, v)| !range.contains(*v))
                .map(|(range, value)| Excursion { range, value })
                .collect();
        if excursions.is_empty() { Applicability::Inside } else { Applicability::Outside(excursions) }
    }

    fn at_row(self, row: usize, rupture: &Rupture, site: &Site) -> Estimate {
        match self {
            Model::Bssa14 => bssa14::estimate(row, rupture, site),
            Model::Ask14 => ask14::estimate(row, rupture, site),
            Model::Cb14 => cb14::estimate(row, rupture, site),
            Model::Cy14 => cy14::estimate(row, rupture, site),
        }
    }

    fn estimate(self, rupture: &Rupture, site: &Site, imt: Imt) -> Result<Estimate, SeismoError> {
        let periods = self.table_periods();
        let n = periods.len();
        match imt {
            // Rows: PSA by period, then PGA, then PGV.
            Imt::Pga => Ok(self.at_row(n, rupture, site)),
            Imt::Pgv => Ok(self.at_row(n + 1, rupture, site)),
            Imt::Psa(t) => match bracket(periods, t) {
                Some(Bracket::Exact(i)) => Ok(self.at_row(i, rupture, site)),
                Some(Bracket::Between(i, w)) => {
                    let (a, b) = (self.at_row(i, rupture, site), self.at_row(i + 1, rupture, site));
                    let lerp = |x: f64, y: f64| x + w * (y - x);
                    Ok(Estimate { ln_y: lerp(a.ln_y, b.ln_y), tau: lerp(a.tau, b.tau), phi: lerp(a.phi, b.phi) })
                }
                None => Err(SeismoError::parameter(
                    "period",
                    format!("{t} s"),
                    format!("{} tabulates {} s ≤ T ≤ {} s", self.name(), periods[0], periods[n - 1]),
                )),
            },
        }
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Model::Bssa14 => "BSSA14",
            Model::Ask14 => "ASK14",
            Model::Cb14 => "CB14",
            Model::Cy14 => "CY14",
        })
    }
}

/// Where a period falls in a table.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Bracket {
    /// On a tabulated period (relative difference below 1e-9).
    Exact(usize),
    /// Between `periods[i]` and `periods[i + 1]`, at weight `w` in ln T.
    Between(usize, f64),
}

fn bracket(periods: &[f64], t: f64) -> Option<Bracket> {
    if !(t.is_finite() && t > 0.0) {
        return None;
    }
    let close = |p: f64| (t - p).abs() <= 1e-9 * p;
    if let Some(i) = periods.iter().position(|&p| close(p)) {
        return Some(Bracket::Exact(i));
    }
    let i = periods.windows(2).position(|w| w[0] < t && t < w[1])?;
    Some(Bracket::Between(i, (t / periods[i]).ln() / (periods[i + 1] / periods[i]).ln()))
}

fn check_inputs(rupture: &Rupture, site: &Site) -> Result<(), SeismoError> {
    let finite = |name: &str, v: f64, unit: &str, ok: bool, allowed: &str| {
        if v.is_finite() && ok { Ok(()) } else { Err(SeismoError::parameter(name, format!("{v}{unit}"), allowed)) }
    };
    let r = rupture;
    finite("mw", r.mw, "", (0.0..=10.0).contains(&r.mw), "0 ≤ M_w ≤ 10")?;
    finite("dip_deg", r.dip_deg, "°", r.dip_deg > 0.0 && r.dip_deg <= 90.0, "0° < dip ≤ 90°")?;
    finite("ztor_km", r.ztor_km, " km", r.ztor_km >= 0.0, "Z_tor ≥ 0 km")?;
    finite("width_km", r.width_km, " km", r.width_km > 0.0, "W > 0 km")?;
    if let Some(zhyp) = r.hypo_depth_km {
        finite("hypo_depth_km", zhyp, " km", zhyp >= 0.0, "Z_hyp ≥ 0 km")?;
    }
    let s = site;
    finite("r_jb_km", s.r_jb_km, " km", s.r_jb_km >= 0.0, "R_JB ≥ 0 km")?;
    finite("r_rup_km", s.r_rup_km, " km", s.r_rup_km >= 0.0, "R_rup ≥ 0 km")?;
    if s.r_jb_km > s.r_rup_km * (1.0 + 1e-9) + 1e-9 {
        return Err(SeismoError::parameter(
            "r_jb_km",
            format!("{} km", s.r_jb_km),
            format!("R_JB ≤ R_rup = {} km (the surface projection is never farther than the rupture)", s.r_rup_km),
        ));
    }
    finite("r_x_km", s.r_x_km, " km", true, "a finite R_x")?;
    if let Some(ry0) = s.r_y0_km {
        finite("r_y0_km", ry0, " km", ry0 >= 0.0, "R_y0 ≥ 0 km")?;
    }
    finite("vs30_m_s", s.vs30_m_s, " m/s", s.vs30_m_s > 0.0, "V_S30 > 0 m/s")?;
    if let Some(z1) = s.z1_km {
        finite("z1_km", z1, " km", z1 >= 0.0, "Z_1.0 ≥ 0 km")?;
    }
    if let Some(z25) = s.z25_km {
        finite("z25_km", z25, " km", z25 >= 0.0, "Z_2.5 ≥ 0 km")?;
    }
    Ok(())
}

/// Z_1.0 (km) of the California V_S30 relation of Chiou & Youngs (2014, eq. 1), which BSSA14 and
/// CY14 use as the centre of their basin terms: ln μ_z1 = −7.15/4 · ln((V_S30⁴ + 570.94⁴)/(1360⁴ +
/// 570.94⁴)) − ln 1000.
pub fn z1_cy14_california_km(vs30_m_s: f64) -> f64 {
    let p = |v: f64| v.powi(4);
    (-7.15 / 4.0 * ((p(vs30_m_s) + p(570.94)) / (p(1360.0) + p(570.94))).ln()).exp() / 1000.0
}

/// Z_1.0 (km) of the California V_S30 relation of ASK14 (eq. 18): exp(−7.67/4 ·
/// ln((V_S30⁴ + 610⁴)/(1360⁴ + 610⁴)))/1000.
pub fn z1_ask14_california_km(vs30_m_s: f64) -> f64 {
    let p = |v: f64| v.powi(4);
    (-7.67 / 4.0 * ((p(vs30_m_s) + p(610.0)) / (p(1360.0) + p(610.0))).ln()).exp() / 1000.0
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rupture() -> Rupture {
        Rupture {
            mw: 6.5,
            mechanism: Mechanism::StrikeSlip,
            dip_deg: 90.0,
            ztor_km: 0.0,
            width_km: 12.0,
            hypo_depth_km: None,
        }
    }

    fn site() -> Site {
        Site {
            r_rup_km: 20.0,
            r_jb_km: 20.0,
            r_x_km: 20.0,
            r_y0_km: Some(0.0),
            vs30_m_s: 760.0,
            z1_km: None,
            z25_km: None,
            vs30_measured: true,
        }
    }

    #[test]
    fn rakes_are_classified_as_the_models_do() {
        assert_eq!(Mechanism::from_rake(0.0), Mechanism::StrikeSlip);
        assert_eq!(Mechanism::from_rake(180.0), Mechanism::StrikeSlip);
        assert_eq!(Mechanism::from_rake(-180.0), Mechanism::StrikeSlip);
        assert_eq!(Mechanism::from_rake(30.0), Mechanism::StrikeSlip);
        assert_eq!(Mechanism::from_rake(30.1), Mechanism::Reverse);
        assert_eq!(Mechanism::from_rake(90.0), Mechanism::Reverse);
        assert_eq!(Mechanism::from_rake(450.0), Mechanism::Reverse);
        assert_eq!(Mechanism::from_rake(-90.0), Mechanism::Normal);
        assert_eq!(Mechanism::from_rake(270.0), Mechanism::Normal);
        assert_eq!(Mechanism::from_rake(-150.0), Mechanism::StrikeSlip);
    }

    #[test]
    fn periods_between_the_table_are_interpolated_in_log_period() {
        for model in Model::ALL {
            let p = model.periods();
            let (t0, t1) = (p[10], p[11]);
            let tm = (t0 * t1).sqrt();
            let [a, b, m] = [t0, t1, tm].map(|t| model.predict(&rupture(), &site(), Imt::Psa(t)).unwrap());
            assert!((m.ln_median - 0.5 * (a.ln_median + b.ln_median)).abs() < 1e-12, "{model}");
            assert!((m.tau - 0.5 * (a.tau + b.tau)).abs() < 1e-12);
            assert!((m.phi - 0.5 * (a.phi + b.phi)).abs() < 1e-12);
            // A tabulated period given with rounding noise is that period.
            let near = model.predict(&rupture(), &site(), Imt::Psa(t0 * (1.0 + 1e-12))).unwrap();
            assert_eq!(near.ln_median, a.ln_median);
        }
    }

    #[test]
    fn periods_outside_the_table_are_refused() {
        for model in Model::ALL {
            for t in [0.005, 10.5, 0.0, -1.0, f64::NAN] {
                let e = model.predict(&rupture(), &site(), Imt::Psa(t)).unwrap_err().to_string();
                assert!(e.contains("period"), "{e}");
            }
            assert!(model.predict(&rupture(), &site(), Imt::Psa(0.01)).is_ok());
            assert!(model.predict(&rupture(), &site(), Imt::Psa(10.0)).is_ok());
        }
    }

    #[test]
    fn bad_inputs_are_refused_naming_the_field() {
        let cases: Vec<(&str, Rupture, Site)> = vec![
            ("mw", Rupture { mw: f64::NAN, ..rupture() }, site()),
            ("dip_deg", Rupture { dip_deg: 0.0, ..rupture() }, site()),
            ("dip_deg", Rupture { dip_deg: 95.0, ..rupture() }, site()),
            ("ztor_km", Rupture { ztor_km: -1.0, ..rupture() }, site()),
            ("width_km", Rupture { width_km: 0.0, ..rupture() }, site()),
            ("hypo_depth_km", Rupture { hypo_depth_km: Some(-1.0), ..rupture() }, site()),
            ("hypo_depth_km", Rupture { hypo_depth_km: Some(f64::NAN), ..rupture() }, site()),
            ("r_jb_km", rupture(), Site { r_jb_km: -1.0, ..site() }),
            ("r_jb_km", rupture(), Site { r_jb_km: 25.0, ..site() }),
            ("r_rup_km", rupture(), Site { r_rup_km: f64::INFINITY, ..site() }),
            ("r_y0_km", rupture(), Site { r_y0_km: Some(-2.0), ..site() }),
            ("vs30_m_s", rupture(), Site { vs30_m_s: 0.0, ..site() }),
            ("z1_km", rupture(), Site { z1_km: Some(-0.1), ..site() }),
            ("z25_km", rupture(), Site { z25_km: Some(-0.1), ..site() }),
        ];
        for model in Model::ALL {
            for (field, r, s) in &cases {
                let e = model.predict(r, s, Imt::Pga).unwrap_err().to_string();
                assert!(e.starts_with(field), "{model}: {e}");
            }
        }
    }

    #[test]
    fn queries_outside_the_ranges_are_flagged_not_hidden() {
        let inside = Model::Bssa14.predict(&rupture(), &site(), Imt::Pga).unwrap();
        assert!(inside.applicability.is_inside());
        // BSSA14: normal faults only to M 7; R_JB to 400 km; V_S30 150–1500 m/s.
        let normal = Rupture { mw: 7.5, mechanism: Mechanism::Normal, ..rupture() };
        let far = Site { r_rup_km: 450.0, r_jb_km: 450.0, vs30_m_s: 100.0, ..site() };
        let p = Model::Bssa14.predict(&normal, &far, Imt::Pga).unwrap();
        let Applicability::Outside(x) = &p.applicability else { panic!("not flagged") };
        let q: Vec<Quantity> = x.iter().map(|e| e.range.quantity).collect();
        assert_eq!(q, [Quantity::Magnitude, Quantity::RJb, Quantity::Vs30]);
        assert!(x[0].to_string().contains("M_w = 7.5 outside [3, 7]"), "{}", x[0]);
        assert!(p.median().is_finite());
        // The same rupture as strike-slip is inside BSSA14's magnitude range.
        let ss = Rupture { mw: 7.5, ..rupture() };
        assert!(Model::Bssa14.applicability(&ss, &site()).is_inside());
        // ASK14: R_rup to 300 km, V_S30 180–1000 m/s, M 3–8.5.
        let a = Model::Ask14.applicability(&Rupture { mw: 2.5, ..rupture() }, &Site { vs30_m_s: 1100.0, ..site() });
        let Applicability::Outside(x) = a else { panic!("not flagged") };
        assert_eq!(x.iter().map(|e| e.range.quantity).collect::<Vec<_>>(), [Quantity::Magnitude, Quantity::Vs30]);
        // CB14: normal faults to M 7.5, reverse to 8, strike-slip to 8.5, from M 3.3; V_S30 from 150.
        let cb =
            |mw: f64, mechanism: Mechanism| Model::Cb14.applicability(&Rupture { mw, mechanism, ..rupture() }, &site());
        assert!(cb(7.5, Mechanism::Normal).is_inside() && !cb(7.6, Mechanism::Normal).is_inside());
        assert!(cb(8.0, Mechanism::Reverse).is_inside() && !cb(8.1, Mechanism::Reverse).is_inside());
        assert!(cb(8.5, Mechanism::StrikeSlip).is_inside() && !cb(3.2, Mechanism::StrikeSlip).is_inside());
        assert!(Model::Cb14.applicability(&rupture(), &Site { vs30_m_s: 150.0, ..site() }).is_inside());
        // CY14: M 3.5–8.0 reverse and normal, to 8.5 strike-slip; R_rup to 300 km; V_S30 180–1500.
        let cy =
            |mw: f64, mechanism: Mechanism| Model::Cy14.applicability(&Rupture { mw, mechanism, ..rupture() }, &site());
        assert!(cy(8.0, Mechanism::Normal).is_inside() && !cy(8.1, Mechanism::Normal).is_inside());
        assert!(cy(8.5, Mechanism::StrikeSlip).is_inside() && !cy(3.4, Mechanism::StrikeSlip).is_inside());
        let far_soft = Site { r_rup_km: 310.0, r_jb_km: 310.0, vs30_m_s: 170.0, ..site() };
        let Applicability::Outside(x) = Model::Cy14.applicability(&rupture(), &far_soft) else { panic!("not flagged") };
        assert_eq!(x.iter().map(|e| e.range.quantity).collect::<Vec<_>>(), [Quantity::RRup, Quantity::Vs30]);
    }

    #[test]
    fn names_parse_back() {
        for m in Model::ALL {
            assert_eq!(Model::parse(m.name()).unwrap(), m);
            assert_eq!(Model::parse(&m.to_string()).unwrap(), m);
        }
        let e = Model::parse("i14").unwrap_err().to_string();
        assert!(e.contains("bssa14, ask14, cb14, cy14"), "{e}");
        assert_eq!(Model::parse(" CB14 ").unwrap(), Model::Cb14);
    }

    #[test]
    fn z1_relations_match_their_definitions() {
        // Both relations give exp(0)/1000 km at V_S30 = 1360 m/s.
        assert!((z1_cy14_california_km(1360.0) - 0.001).abs() < 1e-15);
        assert!((z1_ask14_california_km(1360.0) - 0.001).abs() < 1e-15);
        // V_S30 = 760 m/s: 41.3 m (CY14) and 48.1 m (ASK14), as pygmm 0.8.0's calc_depth_1_0 gives
        // (0.041313206084911805 and 0.048123607124631845 km).
        assert!((z1_cy14_california_km(760.0) / 0.041313206084911805 - 1.0).abs() < 1e-12);
        assert!((z1_ask14_california_km(760.0) / 0.048123607124631845 - 1.0).abs() < 1e-12);
    }
}
