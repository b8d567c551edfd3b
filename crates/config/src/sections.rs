//! The analysis sections of a pipeline file — `[events]`, `[similarity]`, `[spectra]`,
//! `[report]` — and their validation into the settings the seismology numerics, the ensemble and
//! the report take.

use serde::{Deserialize, Serialize};
use stickslip_analysis::SpectraSettings;
use stickslip_seismo::events::EventParams;
use stickslip_seismo::similarity::{AreaChoice, SimilarityParams};
use stickslip_seismo::spectra::fourier::Window;
use stickslip_seismo::spectra::response::{Reading, log_periods};
use stickslip_solver::Scene;
use stickslip_solver::scene::InterfaceQuantity;

use crate::check::{Checker, Named, approx, num};

/// `[events]`: detector thresholds (docs/model.md §7).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct EventsSection {
    /// Smoothing window of `V` and `τ` in seconds. Default 1e-3.
    pub smoothing_s: f64,
    /// A sub-event starts when the smoothed slip rate exceeds this (m/s). Default 2e-4.
    pub v_on_m_s: f64,
    /// … and ends when it stays below this (m/s) for `quiet_s`. Default 5e-5.
    pub v_off_m_s: f64,
    /// Quiet time that ends a sub-event (s). Default 0.5e-3.
    pub quiet_s: f64,
    /// Sub-events closer than this form one event (s). Default 3e-3.
    pub merge_gap_s: f64,
    /// Events with a smaller stress drop are not catalogued (Pa). Default 500.
    pub min_drop_pa: f64,
    /// Main shocks have a drop of at least this fraction of the largest. Default 0.5.
    pub main_fraction: f64,
    /// A fault node has ruptured when its slip rate first reaches this (m/s; with
    /// `record.fault`). Default 1e-3 (the SCEC dynamic-rupture benchmarks' convention).
    #[serde(skip_serializing_if = "is_default_rupture_rate")]
    pub rupture_rate_m_s: f64,
}

fn is_default_rupture_rate(v: &f64) -> bool {
    *v == EventParams::default().rupture_rate_m_s
}

impl Default for EventsSection {
    fn default() -> Self {
        let p = EventParams::default();
        EventsSection {
            smoothing_s: p.smoothing_s,
            v_on_m_s: p.v_on_m_s,
            v_off_m_s: p.v_off_m_s,
            quiet_s: p.quiet_s,
            merge_gap_s: p.merge_gap_s,
            min_drop_pa: p.min_drop_pa,
            main_fraction: p.main_fraction,
            rupture_rate_m_s: p.rupture_rate_m_s,
        }
    }
}

impl EventsSection {
    /// The detector's parameters, every refused value recorded in `ck`.
    pub fn build(&self, ck: &mut Checker) -> EventParams {
        ck.positive("events.smoothing_s", self.smoothing_s);
        ck.positive("events.v_on_m_s", self.v_on_m_s);
        ck.positive("events.quiet_s", self.quiet_s);
        if !(self.v_off_m_s > 0.0 && self.v_off_m_s < self.v_on_m_s) {
            ck.push("events.v_off_m_s", self.v_off_m_s, "0 < v_off_m_s < v_on_m_s (hysteresis)");
        }
        ck.non_negative("events.merge_gap_s", self.merge_gap_s);
        ck.non_negative("events.min_drop_pa", self.min_drop_pa);
        ck.range("events.main_fraction", self.main_fraction, 0.0, true, 1.0, false);
        ck.positive("events.rupture_rate_m_s", self.rupture_rate_m_s);
        EventParams {
            smoothing_s: self.smoothing_s,
            v_on_m_s: self.v_on_m_s,
            v_off_m_s: self.v_off_m_s,
            quiet_s: self.quiet_s,
            merge_gap_s: self.merge_gap_s,
            min_drop_pa: self.min_drop_pa,
            main_fraction: self.main_fraction,
            rupture_rate_m_s: self.rupture_rate_m_s,
        }
    }
}

impl Named for AreaChoice {
    const ALL: &'static [Self] = &[AreaChoice::Contact, AreaChoice::Rupture];
    fn name(self) -> &'static str {
        match self {
            AreaChoice::Contact => "contact",
            AreaChoice::Rupture => "rupture",
        }
    }
}

/// The shortest prototype fault accepted (m).
pub const MIN_PROTOTYPE_LENGTH_M: f64 = 1e-3;
/// The longest prototype fault accepted (m): 2,000 km, beyond the longest ruptures known.
pub const MAX_PROTOTYPE_LENGTH_M: f64 = 2e6;
/// The slowest prototype loading rate accepted (m/s; 3e-8 mm/yr).
pub const MIN_PROTOTYPE_RATE_M_S: f64 = 1e-15;
/// The fastest prototype loading rate accepted (m/s).
pub const MAX_PROTOTYPE_RATE_M_S: f64 = 1.0;

/// `[similarity]`: the prototype fault (docs/model.md §9).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SimilaritySection {
    /// Prototype fault length L_p in metres. Default 1.0e4 (10 km, λ = 10⁴ for the paper block).
    pub prototype_length_m: f64,
    /// Prototype loading rate u̇_p in m/s. Default 3.17e-10 (1 cm/yr).
    pub prototype_rate_m_s: f64,
    /// Model area used for the moment: `"contact"` (default, the paper's) or `"rupture"` (the
    /// event's peak share of sliding contact nodes; needs `slipping_nodes` recorded).
    pub area: String,
}

impl Default for SimilaritySection {
    fn default() -> Self {
        let p = SimilarityParams::default();
        SimilaritySection {
            prototype_length_m: p.prototype_length_m,
            prototype_rate_m_s: p.prototype_rate_m_s,
            area: p.area.name().into(),
        }
    }
}

impl SimilaritySection {
    /// The scaling parameters, every refused value recorded in `ck`.
    pub fn build(&self, scene: Option<&Scene>, ck: &mut Checker) -> SimilarityParams {
        if !(MIN_PROTOTYPE_LENGTH_M..=MAX_PROTOTYPE_LENGTH_M).contains(&self.prototype_length_m) {
            ck.push(
                "similarity.prototype_length_m",
                self.prototype_length_m,
                format!(
                    "{} ≤ prototype_length_m ≤ {} (m): a fault's length; the longest ruptures known are about \
                     1,500 km (Sumatra–Andaman 2004), and a longer prototype gives magnitudes no fault has, or inf",
                    approx(MIN_PROTOTYPE_LENGTH_M),
                    approx(MAX_PROTOTYPE_LENGTH_M)
                ),
            );
        }
        ck.range(
            "similarity.prototype_rate_m_s",
            self.prototype_rate_m_s,
            MIN_PROTOTYPE_RATE_M_S,
            false,
            MAX_PROTOTYPE_RATE_M_S,
            false,
        );
        let area = ck.named::<AreaChoice>("similarity.area", &self.area).unwrap_or(AreaChoice::Contact);
        if let Some(scene) = scene
            && scene.is_fault()
            && *self != SimilaritySection::default()
        {
            ck.push(
                "similarity",
                "a [similarity] section with [fault]",
                "no [similarity] in a fault scene: it is at its own scale (λ = 1), its magnitudes come from its own slip",
            );
        }
        if area == AreaChoice::Rupture
            && let Some(scene) = scene
            && !scene.record.has(InterfaceQuantity::SlippingNodes)
        {
            ck.push(
                "similarity.area",
                "\"rupture\"",
                "\"contact\" unless record.interface has \"slipping_nodes\" (the rupture area is the peak count of \
                 sliding contact nodes; without it every area is 0 and every magnitude −∞)",
            );
        }
        SimilarityParams {
            prototype_length_m: self.prototype_length_m,
            prototype_rate_m_s: self.prototype_rate_m_s,
            area,
        }
    }
}

impl Named for Reading {
    const ALL: &'static [Self] = &[Reading::Linear, Reading::BandLimited];
    fn name(self) -> &'static str {
        match self {
            Reading::Linear => "linear",
            Reading::BandLimited => "band_limited",
        }
    }
}

impl Named for Window {
    const ALL: &'static [Self] = &[Window::Rectangular, Window::Hann];
    fn name(self) -> &'static str {
        match self {
            Window::Rectangular => "rectangular",
            Window::Hann => "hann",
        }
    }
}

/// `[spectra]`: spectra of the records of `[accelerograms]` (absent = none), docs/model.md §8.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SpectraSection {
    /// Damping ratios (fractions of critical, 0 ≤ ξ < 1). Default `[0.05]`.
    pub dampings: Vec<f64>,
    /// Explicit model-scale periods in seconds; empty = the log grid below.
    pub periods_s: Vec<f64>,
    /// Shortest period of the log grid (s, model scale). Default 1e-4.
    pub period_min_s: f64,
    /// Longest period of the log grid (s, model scale). Default 0.1.
    pub period_max_s: f64,
    /// Number of periods of the log grid. Default 100.
    pub period_count: i64,
    /// Reading of the samples: `"linear"` (default) or `"band_limited"`.
    pub reading: String,
    /// Oversampling of the band-limited reading. Default 16.
    pub oversampling: i64,
    /// Window of the Fourier spectrum: `"rectangular"` (default) or `"hann"`.
    pub fourier_window: String,
    /// RotD50 and RotD100 (Boore 2010) of every node recording both horizontal components.
    /// Default true.
    pub rotd: bool,
    /// Attenuation of PGA and PGV with distance from each main shock's hypocentre (needs
    /// `record.slip_onsets = true`). Default false.
    pub attenuation: bool,
}

impl Default for SpectraSection {
    fn default() -> Self {
        SpectraSection {
            dampings: vec![0.05],
            periods_s: vec![],
            period_min_s: 1e-4,
            period_max_s: 0.1,
            period_count: 100,
            reading: Reading::Linear.name().into(),
            oversampling: 16,
            fourier_window: Window::Rectangular.name().into(),
            rotd: true,
            attenuation: false,
        }
    }
}

/// The longest period a spectrum may ask for (s).
const LONGEST_PERIOD_S: f64 = 1e6;

impl SpectraSection {
    /// The settings for `scene`, every refused value recorded in `ck`; `shortest` is the
    /// shortest period accepted (s) with why (see [`shortest_period`]).
    pub fn build(&self, scene: &Scene, shortest: Option<(f64, String)>, ck: &mut Checker) -> SpectraSettings {
        let (floor, why) = shortest.unwrap_or((0.0, String::new()));
        // A period so long that its frequency underflows comes back from 1/f as infinity.
        let below_ceiling = |ck: &mut Checker, field: &str, t: f64| {
            if t.is_finite() && t > LONGEST_PERIOD_S {
                ck.push(field, t, format!("a period ≤ {LONGEST_PERIOD_S:e} s (11.6 days)"));
            }
        };
        let within_bounds = |ck: &mut Checker, field: &str, t: f64| {
            if t > 0.0 && t.is_finite() && t < floor {
                ck.push(field, t, format!("a period ≥ {} s: {why}", approx(floor)));
            }
            below_ceiling(ck, field, t);
        };
        if self.dampings.is_empty() {
            ck.push("spectra.dampings", "[]", "at least one damping ratio");
        }
        for (i, &d) in self.dampings.iter().enumerate() {
            ck.range(&format!("spectra.dampings[{i}]"), d, 0.0, false, 1.0, true);
        }
        for (i, &t) in self.periods_s.iter().enumerate() {
            let field = format!("spectra.periods_s[{i}]");
            ck.positive(&field, t);
            within_bounds(ck, &field, t);
        }
        if self.periods_s.len() > 10_000 {
            ck.push("spectra.periods_s", format!("{} periods", self.periods_s.len()), "at most 10000 periods");
        }
        if self.periods_s.is_empty() {
            within_bounds(ck, "spectra.period_min_s", self.period_min_s);
            below_ceiling(ck, "spectra.period_max_s", self.period_max_s);
            if ck.positive("spectra.period_min_s", self.period_min_s)
                && !(self.period_max_s > self.period_min_s && self.period_max_s.is_finite())
            {
                ck.push(
                    "spectra.period_max_s",
                    self.period_max_s,
                    format!("period_min_s ({}) < period_max_s (finite)", num(self.period_min_s)),
                );
            }
        }
        // The grid is built only of a count that was accepted (a refused one can be 2^40).
        let count = if self.periods_s.is_empty() {
            ck.count("spectra.period_count", self.period_count, 1, 10_000, "").unwrap_or(1)
        } else {
            1
        };
        ck.count("spectra.oversampling", self.oversampling, 1, 64, "");
        let reading = ck.named("spectra.reading", &self.reading).unwrap_or(Reading::Linear);
        let window = ck.named("spectra.fourier_window", &self.fourier_window).unwrap_or(Window::Rectangular);
        let periods = if self.periods_s.is_empty() {
            log_periods(self.period_min_s, self.period_max_s, count)
        } else {
            self.periods_s.clone()
        };
        if self.attenuation && !scene.record.slip_onsets {
            ck.push(
                "spectra.attenuation",
                "true",
                "record.slip_onsets = true (the hypocentre is the first contact node to slide)",
            );
        }
        SpectraSettings {
            dampings: self.dampings.clone(),
            periods,
            reading,
            oversampling: self.oversampling.clamp(1, 64) as usize,
            window,
            rotd: self.rotd,
            attenuation: self.attenuation,
        }
    }
}

/// The shortest period a spectrum may ask for, with why: a hundredth of the shortest period the
/// lattice resolves (`1/f_max`, the records' usable band ends there) and of the records' sampling
/// interval. A response spectrum at a period much shorter than both reads nothing but the peak
/// acceleration, and its oscillator costs steps in proportion to the sampling interval over the
/// period (2e-17 s would run for hours).
pub fn shortest_period(f_max_hz: f64, interval_s: Option<f64>) -> Option<(f64, String)> {
    let lattice = (f_max_hz > 0.0 && f_max_hz.is_finite()).then(|| 0.01 / f_max_hz);
    let sampling = interval_s.filter(|v| *v > 0.0 && v.is_finite()).map(|v| 0.01 * v);
    let floor = lattice.into_iter().chain(sampling).fold(0.0f64, f64::max);
    (floor > 0.0).then(|| {
        let mut why = Vec::new();
        if let Some(t) = lattice {
            why.push(format!(
                "a hundredth of the shortest period the lattice resolves (1/f_max = {} s)",
                approx(100.0 * t)
            ));
        }
        if let Some(t) = sampling {
            why.push(format!("a hundredth of record.interval_s ({} s)", approx(100.0 * t)));
        }
        (
            floor,
            format!(
                "{}; a spectrum at shorter periods reads only the peak acceleration and costs ever more steps",
                why.join(" and ")
            ),
        )
    })
}

/// `[exchange]`: where the scene lies on the Earth in the files written for seismology's tools
/// (the StationXML inventory, the QuakeML catalogue). Not part of the hash: those files are
/// written again from the tables each time the seeds are gathered.
#[derive(Clone, Debug, Default, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct ExchangeSection {
    /// Latitude of the scene's origin (degrees, −90 < φ < 90). Default 0.
    pub origin_lat_deg: f64,
    /// Longitude of the scene's origin (degrees, −180 ≤ λ ≤ 180). Default 0.
    pub origin_lon_deg: f64,
}

impl ExchangeSection {
    /// Checks the origin; returns (latitude, longitude) in degrees.
    pub fn build(&self, ck: &mut Checker) -> (f64, f64) {
        let (lat, lon) = (self.origin_lat_deg, self.origin_lon_deg);
        if !(lat.is_finite() && lat.abs() < 90.0) {
            ck.push("exchange.origin_lat_deg", lat, "−90 < latitude < 90 degrees (the poles have no east)");
        }
        if !(lon.is_finite() && lon.abs() <= 180.0) {
            ck.push("exchange.origin_lon_deg", lon, "−180 ≤ longitude ≤ 180 degrees");
        }
        (lat, lon)
    }
}

/// `[report]`: the report.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct ReportSection {
    /// Write the report after the tables. Default true.
    pub enabled: bool,
    /// Seeds drawn one by one in the time-history figures; empty = the first four successful
    /// seeds of the pipeline.
    pub seeds: Vec<i64>,
    /// This pipeline reproduces the paper: titles name the paper's figure ("paper Fig. 3") and
    /// the paper's reference values are drawn (M = 6.77, the S1→S2 recurrence of 25.8 ms, the
    /// 30% swing of σ). Default false: a user's own scene is not compared with the paper's.
    pub paper_figures: bool,
}

impl Default for ReportSection {
    fn default() -> Self {
        ReportSection { enabled: true, seeds: vec![], paper_figures: false }
    }
}

/// What the report draws (a validated `[report]`).
#[derive(Clone, Debug, PartialEq)]
pub struct ReportSettings {
    /// Write the report.
    pub enabled: bool,
    /// Seeds drawn one by one; empty = the first four successful seeds.
    pub seeds: Vec<u64>,
    /// Name the paper's figures in titles and draw the paper's reference values.
    pub paper_figures: bool,
}

impl ReportSection {
    /// The report's settings, every refused value recorded in `ck`.
    pub fn build(&self, ck: &mut Checker) -> ReportSettings {
        let mut seeds = Vec::new();
        for (i, &s) in self.seeds.iter().enumerate() {
            match u64::try_from(s) {
                Ok(s) => seeds.push(s),
                Err(_) => ck.push(format!("report.seeds[{i}]"), s, "a seed ≥ 0"),
            }
        }
        ReportSettings { enabled: self.enabled, seeds, paper_figures: self.paper_figures }
    }
}
