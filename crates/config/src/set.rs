//! `[set]`: a set of records matched to a design spectrum, chosen from an ensemble's records
//! (`stickslip_seismo::selection`), at prototype scale.
//!
//! The target is ASCE 7-16 (§11.4.6: `S_DS`, `S_D1` in g and `T_L` in s), Eurocode 8 (EN 1998-1
//! §3.2.2.2: `a_g` in m/s², spectrum type 1 or 2, ground type A–E) or a CSV table of period (s)
//! and PSA (m/s²). The period range is given, or `[0.2·T₁, 2·T₁]` from the structure's
//! fundamental period `T₁` (ASCE 7-16 §16.2.1, EN 1998-1 §3.2.3.1.2). `count` records (ASCE 7-16
//! §16.2.2 asks for 11), at most `max_per` of one event (or seed), each scaled by a factor within
//! `[scale_min, scale_max]`, whose mean spectrum minimises the log misfit over the range and is
//! nowhere in it below 90% of the target. Only records whose usable band covers the range are
//! eligible.
//!
//! Not part of the pipeline's hash: the set is chosen from finished seeds each time the ensemble
//! is gathered, and changes no seed's tables.

use std::path::Path;

/// Ground motions ASCE 7-16 §16.2.2 asks of a suite for nonlinear response history analysis.
pub const ASCE7_MIN_RECORDS: usize = 11;

use serde::{Deserialize, Serialize};
use stickslip_seismo::design::{Asce7, DesignSpectrum, Ec8, Ec8Type, GroundType, Tabulated};
use stickslip_seismo::selection::{PeriodRange, SelectionOptions};

use crate::check::{Checker, Named, approx, num};
use crate::error::{ConfigError, FieldError};
use crate::input::InputFile;

/// Which spectrum of a record is matched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SetComponent {
    /// Each horizontal component (x and y) is a candidate on its own.
    Horizontal,
    /// x only.
    X,
    /// y only.
    Y,
    /// z only.
    Z,
    /// The x–y pair of a node, by its RotD50 spectrum (both components are scaled alike); a
    /// scenario station's horizontal pair (x, z).
    Rotd50,
    /// A scenario station's horizontal pair (x, z) by its RotD100 spectrum, the maximum direction
    /// of ASCE 7-16 §16.2.3 (both components scaled alike).
    Rotd100,
}

impl Named for SetComponent {
    const ALL: &'static [Self] = &[
        SetComponent::Horizontal,
        SetComponent::X,
        SetComponent::Y,
        SetComponent::Z,
        SetComponent::Rotd50,
        SetComponent::Rotd100,
    ];
    fn name(self) -> &'static str {
        match self {
            SetComponent::Horizontal => "horizontal",
            SetComponent::X => "x",
            SetComponent::Y => "y",
            SetComponent::Z => "z",
            SetComponent::Rotd50 => "rotd50",
            SetComponent::Rotd100 => "rotd100",
        }
    }
}

/// What one group of records (at most `max_per` chosen) is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SetGroup {
    /// The records of one event of one seed.
    Event,
    /// The records of one seed.
    Seed,
}

impl Named for SetGroup {
    const ALL: &'static [Self] = &[SetGroup::Event, SetGroup::Seed];
    fn name(self) -> &'static str {
        match self {
            SetGroup::Event => "event",
            SetGroup::Seed => "seed",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum TargetKind {
    Asce7,
    Ec8,
    Csv,
}

impl Named for TargetKind {
    const ALL: &'static [Self] = &[TargetKind::Asce7, TargetKind::Ec8, TargetKind::Csv];
    fn name(self) -> &'static str {
        match self {
            TargetKind::Asce7 => "asce7",
            TargetKind::Ec8 => "ec8",
            TargetKind::Csv => "csv",
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Ground(GroundType);

impl Named for Ground {
    const ALL: &'static [Self] = &[
        Ground(GroundType::A),
        Ground(GroundType::B),
        Ground(GroundType::C),
        Ground(GroundType::D),
        Ground(GroundType::E),
    ];
    fn name(self) -> &'static str {
        match self.0 {
            GroundType::A => "A",
            GroundType::B => "B",
            GroundType::C => "C",
            GroundType::D => "D",
            GroundType::E => "E",
        }
    }
}

/// `[set]` as written in a pipeline file (or a file given to `stickslip select`).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub struct SetSection {
    /// `"asce7"` (default), `"ec8"` or `"csv"`.
    pub target: String,
    /// ASCE 7: design spectral acceleration at short periods `S_DS` (g). Default 1.0.
    pub s_ds_g: f64,
    /// ASCE 7: design spectral acceleration at 1 s `S_D1` (g). Default 0.6.
    pub s_d1_g: f64,
    /// ASCE 7: long-period transition period `T_L` (s). Default 8.
    pub t_l_s: f64,
    /// EC8: design ground acceleration on type A ground `a_g` (m/s²). Default 2.5.
    pub a_g_m_s2: f64,
    /// EC8: spectrum type, 1 (surface-wave magnitude above 5.5) or 2. Default 1.
    pub ec8_type: i64,
    /// EC8: ground type `"A"` … `"E"`. Default `"B"`.
    pub ground: String,
    /// CSV target: a file of `period_s, psa_m_s2` rows (a header line allowed), relative to the
    /// pipeline file.
    pub target_csv: String,
    /// Fundamental period `T₁` (s): the range is `[0.2·T₁, 2·T₁]`; 0 = use `period_min_s`,
    /// `period_max_s`. Default 1.0.
    pub t1_s: f64,
    /// Lower end of the period range (s), with `t1_s = 0`.
    pub period_min_s: f64,
    /// Upper end of the period range (s), with `t1_s = 0`.
    pub period_max_s: f64,
    /// Number of records. Default 11.
    pub count: i64,
    /// At most this many records of one group. Default 2.
    pub max_per: i64,
    /// A group is an `"event"` (default) or a `"seed"`.
    pub per: String,
    /// Smallest amplitude scale factor. Default 0.25.
    pub scale_min: f64,
    /// Largest amplitude scale factor. Default 4.
    pub scale_max: f64,
    /// The spectrum matched: `"horizontal"` (default), `"x"`, `"y"`, `"z"` or `"rotd50"`.
    pub component: String,
    /// Damping ratio of the spectra matched (one of `[spectra] dampings`). Default 0.05.
    pub damping: f64,
    /// A scenario's stations only: smallest moment magnitude of the seed's rupture.
    pub magnitude_min: Option<f64>,
    /// A scenario's stations only: largest moment magnitude of the seed's rupture.
    pub magnitude_max: Option<f64>,
    /// A scenario's stations only: smallest rupture distance R_rup (km).
    pub distance_min_km: Option<f64>,
    /// A scenario's stations only: largest rupture distance R_rup (km).
    pub distance_max_km: Option<f64>,
    /// A scenario's broadband stations only: the site (V_S30, m/s) of the records chosen, one of
    /// `[broadband]`'s; needed when the stations stand on several sites.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vs30_m_s: Option<f64>,
}

impl Default for SetSection {
    fn default() -> Self {
        SetSection {
            target: TargetKind::Asce7.name().into(),
            s_ds_g: 1.0,
            s_d1_g: 0.6,
            t_l_s: 8.0,
            a_g_m_s2: 2.5,
            ec8_type: 1,
            ground: "B".into(),
            target_csv: String::new(),
            t1_s: 1.0,
            period_min_s: 0.0,
            period_max_s: 0.0,
            count: 11,
            max_per: 2,
            per: SetGroup::Event.name().into(),
            scale_min: 0.25,
            scale_max: 4.0,
            component: SetComponent::Horizontal.name().into(),
            damping: 0.05,
            vs30_m_s: None,
            magnitude_min: None,
            magnitude_max: None,
            distance_min_km: None,
            distance_max_km: None,
        }
    }
}

/// A validated `[set]`.
#[derive(Clone, Debug, PartialEq)]
pub struct SetSettings {
    /// The target spectrum (PSA in m/s²).
    pub target: DesignSpectrum,
    /// What the target is, for captions (e.g. "ASCE 7-16, S_DS = 1 g, S_D1 = 0.6 g, T_L = 8 s").
    pub target_name: String,
    /// Selection options (range, count, caps, scale bounds).
    pub options: SelectionOptions,
    /// What a group is.
    pub per: SetGroup,
    /// The spectrum matched.
    pub component: SetComponent,
    /// Damping ratio.
    pub damping: f64,
    /// The CSV target's file as read (a CSV target only).
    pub input: Option<InputFile>,
    /// A scenario's stations only: the rupture's moment magnitude bin `[min, max]` (either end
    /// open as ±∞).
    pub magnitude: Option<(f64, f64)>,
    /// A scenario's stations only: the rupture distance bin `[min, max]` (km).
    pub distance_km: Option<(f64, f64)>,
    /// A scenario's broadband stations only: the site of the records chosen (V_S30, m/s).
    pub vs30_m_s: Option<f64>,
}

impl SetSettings {
    /// The magnitude and distance bins as text (`Mw 6–6.5, R_rup ≤ 30 km`); `None` without
    /// either.
    pub fn bins_text(&self) -> Option<String> {
        let text = |what: &str, unit: &str, bin: Option<(f64, f64)>| {
            let (lo, hi) = bin?;
            Some(match (lo.is_finite(), hi.is_finite()) {
                (true, true) => format!("{what} {lo}–{hi}{unit}"),
                (true, false) => format!("{what} ≥ {lo}{unit}"),
                _ => format!("{what} ≤ {hi}{unit}"),
            })
        };
        let bins: Vec<String> =
            [text("Mw", "", self.magnitude), text("R_rup", " km", self.distance_km)].into_iter().flatten().collect();
        (!bins.is_empty()).then(|| bins.join(", "))
    }
}

/// The most records a set of a scenario's surface stations can hold over `seeds` seeds, known
/// before anything runs, and why: each seed is one rupture giving at most `max_per` records, of
/// the surface stations that can fall in the distance bin (a station `z` m from the fault plane
/// has R_rup ≥ z, so one farther than the bin's far end never does). The magnitude bin can only
/// lower it.
#[derive(Clone, Debug, PartialEq)]
pub struct SetCapacity {
    /// Records at most.
    pub records: usize,
    /// Records at most from one seed.
    pub per_seed: usize,
    /// Surface stations that can fall in the distance bin.
    pub stations: usize,
    /// Surface stations.
    pub surface: usize,
}

impl SetCapacity {
    /// Of `set` chosen from `scene`'s surface stations over `seeds` seeds.
    pub fn of(set: &SetSettings, scene: &stickslip_solver::Scene, seeds: usize) -> SetCapacity {
        let lattice = scene.lattice();
        let far_m = set.distance_km.map_or(f64::INFINITY, |(_, hi)| hi * 1e3);
        let surface: Vec<f64> = scene
            .stations
            .iter()
            .map(|s| lattice.position(s.node))
            .filter(|p| p[1] == 0.0)
            .map(|p| p[2].abs())
            .collect();
        let stations = surface.iter().filter(|&&z| z <= far_m * (1.0 + 1e-12)).count();
        let per_seed = stations.min(set.options.per_group);
        SetCapacity { records: per_seed.saturating_mul(seeds), per_seed, stations, surface: surface.len() }
    }
}

/// What a `[set]` chooses from, and the spectra it is matched on.
#[derive(Clone, Copy, Debug)]
pub enum SetPool<'a> {
    /// The records of events (`[accelerograms]`, `[spectra]`): the spectra's dampings and
    /// prototype-scale period grid `(shortest, longest)` (s); `None` without `[spectra]`.
    Records(Option<(&'a [f64], (f64, f64))>),
    /// The surface stations of a fault scenario (`stations`, `station_spectra`): 5%-damped RotD50
    /// and RotD100 of each station's horizontal pair, usable from `shortest` to `longest` (s).
    Stations {
        /// Shortest usable period (s).
        shortest: f64,
        /// Longest usable period (s).
        longest: f64,
    },
}

/// Reads the `[set]` section of a TOML file (a pipeline file, or a file holding only that
/// section) and builds it against `pool` (see [`SetSection::build`]), a CSV target relative to
/// the file.
pub fn read_set_file(path: &Path, pool: SetPool) -> Result<SetSettings, ConfigError> {
    #[derive(Deserialize)]
    struct SetFile {
        set: Option<SetSection>,
    }
    let text = std::fs::read_to_string(path).map_err(|e| ConfigError::Io { path: path.to_path_buf(), source: e })?;
    let file = |e: ConfigError| ConfigError::File { path: path.to_path_buf(), source: Box::new(e) };
    // Only the [set] table is read: the rest of a pipeline file is the pipeline's business.
    let doc: toml::Table = toml::from_str(&text).map_err(|e| file(ConfigError::Syntax(e.to_string())))?;
    let only = toml::Table::from_iter(doc.get("set").map(|v| ("set".to_string(), v.clone())));
    let f: SetFile =
        toml::Value::Table(only).try_into().map_err(|e: toml::de::Error| file(ConfigError::Syntax(e.to_string())))?;
    let section = f.set.ok_or_else(|| {
        file(ConfigError::Invalid(vec![FieldError {
            field: "set".into(),
            value: "absent".into(),
            allowed: "a [set] section (see pipelines/accelerograms.toml)".into(),
        }]))
    })?;
    let mut ck = Checker::default();
    let base = path.parent().unwrap_or(Path::new("."));
    let built = section.build(base, pool, &mut ck);
    ck.finish().map_err(file)?;
    built.ok_or_else(|| file(ConfigError::Syntax("the set could not be built".into())))
}

impl SetSection {
    /// The settings; a CSV target is read relative to `base` (the pipeline file's folder).
    /// `pool` says what the set is chosen from: the records' spectra (their dampings and
    /// prototype-scale period grid, which must hold the period range), or a scenario's stations
    /// (5% damping, RotD50 or RotD100, the range inside their usable band; magnitude and distance
    /// bins allowed). Every refused value is recorded in `ck`; `None` when the target could not be
    /// built.
    pub fn build(&self, base: &Path, pool: SetPool, ck: &mut Checker) -> Option<SetSettings> {
        // The stations' spectra have the one damping of their motions.
        const STATION_DAMPINGS: [f64; 1] = [stickslip_analysis::motions::DAMPING];
        let (dampings, spectra) = match pool {
            SetPool::Records(spectra) => (spectra.map(|s| s.0), spectra.map(|s| s.1)),
            SetPool::Stations { shortest, longest } => (Some(&STATION_DAMPINGS[..]), Some((shortest, longest))),
        };
        let stations = matches!(pool, SetPool::Stations { .. });
        let kind = ck.named::<TargetKind>("set.target", &self.target)?;
        let (target, target_name, input) = self.target(kind, base, ck);
        let range = self.period_range(spectra, stations, ck);
        let count = ck.count("set.count", self.count, 1, 1000, "").unwrap_or(11);
        if kind == TargetKind::Asce7 && count < ASCE7_MIN_RECORDS {
            ck.warn(
                "set.count",
                count,
                format!(
                    "ASCE 7-16 §16.2.2 asks for at least {ASCE7_MIN_RECORDS} ground motions (each a pair of horizontal \
                     components) for a nonlinear response history analysis: a set of {count} is chosen and scaled to \
                     this target, but it is not a suite ASCE 7-16 accepts (set.count = {ASCE7_MIN_RECORDS} or more)"
                ),
            );
        }
        let max_per = ck.count("set.max_per", self.max_per, 1, 1000, "").unwrap_or(2);
        let per = ck.named("set.per", &self.per).unwrap_or(SetGroup::Event);
        if ck.positive("set.scale_min", self.scale_min)
            && !(self.scale_max >= self.scale_min && self.scale_max.is_finite())
        {
            ck.push("set.scale_max", self.scale_max, format!("at least scale_min ({}), finite", num(self.scale_min)));
        }
        let component = self.component(stations, ck);
        let magnitude = checked_bin(
            ck,
            ("set.magnitude_min", self.magnitude_min),
            ("set.magnitude_max", self.magnitude_max),
            (-2.0, 10.0),
            stations,
        );
        let distance_km = checked_bin(
            ck,
            ("set.distance_min_km", self.distance_min_km),
            ("set.distance_max_km", self.distance_max_km),
            (0.0, 1e4),
            stations,
        );
        match dampings {
            Some(d) if !d.iter().any(|&x| (x - self.damping).abs() <= 1e-12) => {
                ck.push("set.damping", self.damping, format!("one of the spectra's dampings {d:?}"));
            }
            None => ck.push("set", "(present)", "a [spectra] section (the set is matched on the records' spectra)"),
            _ => {}
        }
        let options = SelectionOptions {
            count,
            per_group: max_per,
            scale_min: self.scale_min,
            scale_max: self.scale_max,
            ..SelectionOptions::new(range)
        };
        Some(SetSettings {
            target: target?,
            target_name,
            options,
            per,
            component,
            damping: self.damping,
            input,
            magnitude,
            distance_km,
            vs30_m_s: self.vs30_m_s,
        })
    }

    /// The target spectrum of `kind` with its name, and the CSV file it was read from (for the
    /// pipeline's hash); `None` for a target refused.
    fn target(
        &self,
        kind: TargetKind,
        base: &Path,
        ck: &mut Checker,
    ) -> (Option<DesignSpectrum>, String, Option<InputFile>) {
        let mut input = None;
        let (target, name) = match kind {
            TargetKind::Asce7 => {
                let ok = ck.positive("set.s_ds_g", self.s_ds_g) & ck.positive("set.s_d1_g", self.s_d1_g);
                let t_s = self.s_d1_g / self.s_ds_g;
                if ok && !(self.t_l_s > t_s && self.t_l_s.is_finite()) {
                    ck.push("set.t_l_s", self.t_l_s, format!("T_L > T_S = S_D1/S_DS = {} s (finite)", num(t_s)));
                }
                let name = format!(
                    "ASCE 7-16, S_DS = {} g, S_D1 = {} g, T_L = {} s",
                    num(self.s_ds_g),
                    num(self.s_d1_g),
                    num(self.t_l_s)
                );
                (Asce7::new(self.s_ds_g, self.s_d1_g, self.t_l_s).ok().map(DesignSpectrum::Asce7), name)
            }
            TargetKind::Ec8 => {
                ck.positive("set.a_g_m_s2", self.a_g_m_s2);
                let kind = match self.ec8_type {
                    1 => Some(Ec8Type::Type1),
                    2 => Some(Ec8Type::Type2),
                    _ => {
                        ck.push("set.ec8_type", self.ec8_type, "1 or 2");
                        None
                    }
                };
                let ground = ck.named::<Ground>("set.ground", &self.ground);
                let name = format!(
                    "EN 1998-1 type {} spectrum, a_g = {} m/s², ground {}",
                    self.ec8_type,
                    num(self.a_g_m_s2),
                    self.ground
                );
                let xi = 100.0 * self.damping;
                let spectrum = match (kind, ground) {
                    (Some(k), Some(g)) => Ec8::new(self.a_g_m_s2, k, g.0, xi).ok().map(DesignSpectrum::Ec8),
                    _ => None,
                };
                (spectrum, name)
            }
            TargetKind::Csv => {
                let name = format!("target spectrum {}", self.target_csv);
                match read_target_csv(&self.target_csv, base, ck) {
                    Some((tab, file)) => {
                        input = Some(file);
                        (Some(DesignSpectrum::Tabulated(tab)), name)
                    }
                    None => (None, name),
                }
            }
        };
        (target, name, input)
    }

    /// The period range the set is matched over (`t1_s`, or `period_min_s` … `period_max_s`),
    /// refused outside the periods of the `spectra` ((shortest, longest) at prototype scale, or of
    /// the stations' usable band).
    fn period_range(&self, spectra: Option<(f64, f64)>, stations: bool, ck: &mut Checker) -> PeriodRange {
        let range = if self.t1_s > 0.0 {
            ck.positive("set.t1_s", self.t1_s);
            PeriodRange::Fundamental { t1: self.t1_s }
        } else {
            if ck.positive("set.period_min_s", self.period_min_s)
                && !(self.period_max_s > self.period_min_s && self.period_max_s.is_finite())
            {
                ck.push(
                    "set.period_max_s",
                    self.period_max_s,
                    format!("above period_min_s ({} s)", num(self.period_min_s)),
                );
            }
            PeriodRange::Explicit { t_a: self.period_min_s, t_b: self.period_max_s }
        };
        if let (Some((lo, hi)), Ok((t_a, t_b))) = (spectra, range.bounds()) {
            // Relative slack: the grid's ends are exact, a range given by hand may round.
            if t_a < lo * (1.0 - 1e-9) || t_b > hi * (1.0 + 1e-9) {
                let field = if self.t1_s > 0.0 { "set.t1_s" } else { "set.period_min_s" };
                let value = if self.t1_s > 0.0 { self.t1_s } else { self.period_min_s };
                let within = if stations && lo > 0.011 {
                    format!(
                        "the stations' usable periods ({} … {} s: from the lattice's f_max, at most 0.8 of the \
                         record interval's Nyquist, to 1/1.25 of half the shear stage; a [broadband] section makes \
                         the stations' records usable from 0.01 s, docs/model.md §17)",
                        approx(lo),
                        approx(hi)
                    )
                } else if stations {
                    format!(
                        "the stations' usable periods ({} … {} s: from 0.01 s, the broadband records', to 1/1.25 of \
                         half the shear stage: a longer shear stage reaches longer periods)",
                        approx(lo),
                        approx(hi)
                    )
                } else {
                    format!(
                        "the spectra's periods ({} … {} s at prototype scale: [spectra] period_min_s, period_max_s × \
                         λ)",
                        approx(lo),
                        approx(hi)
                    )
                };
                ck.push(
                    field,
                    value,
                    format!(
                        "a period range ({} … {} s{}) inside {within}",
                        approx(t_a),
                        approx(t_b),
                        if stations { "" } else { " at prototype scale" }
                    ),
                );
            }
        }
        range
    }

    /// The component the set is chosen by: a pair (RotD50, RotD100) for a scenario's stations,
    /// not RotD100 for the records of events.
    fn component(&self, stations: bool, ck: &mut Checker) -> SetComponent {
        let component = ck.named("set.component", &self.component).unwrap_or(SetComponent::Horizontal);
        let pair = matches!(component, SetComponent::Rotd50 | SetComponent::Rotd100);
        if stations && !pair {
            ck.push(
                "set.component",
                &self.component,
                "\"rotd50\" or \"rotd100\" for a scenario's stations (their horizontal pair, both components \
                 scaled alike; ASCE 7-16 §16.2.3 matches the maximum direction, RotD100)",
            );
        } else if !stations && component == SetComponent::Rotd100 {
            ck.push(
                "set.component",
                &self.component,
                "\"horizontal\", \"x\", \"y\", \"z\" or \"rotd50\" for the records of events (\"rotd100\" is for a \
                 scenario's stations: a fault scene with [[stations]] on the surface)",
            );
        }
        component
    }
}

/// A CSV target: rows `period_s, psa_m_s2` (comma, semicolon or tab; `#` comments and one header
/// line allowed), the file `given` relative to `base` (see [`crate::input`]); refusals never echo
/// its content.
fn read_target_csv(given: &str, base: &Path, ck: &mut Checker) -> Option<(Tabulated, InputFile)> {
    let field = "set.target_csv";
    let what = "a CSV file of period_s, psa_m_s2 rows";
    let file = crate::input::read(ck, field, given, base, what)?;
    let (mut t, mut psa) = (Vec::new(), Vec::new());
    for (k, line) in file.text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line.split([',', ';', '\t']).map(str::trim).collect();
        let number = |i: usize| cells.get(i).and_then(|c| c.parse::<f64>().ok());
        match (number(0), number(1)) {
            (Some(a), Some(b)) => {
                t.push(a);
                psa.push(b);
            }
            _ if t.is_empty() && k == 0 => continue,
            _ => {
                ck.push(field, format!("{given:?} line {}", k + 1), format!("{what}: two numbers on each line"));
                return None;
            }
        }
    }
    match Tabulated::new(&t, &psa) {
        Ok(tab) => Some((tab, file)),
        Err(e) => {
            ck.push(field, format!("{given:?}"), format!("{what}: {e}"));
            None
        }
    }
}

/// A magnitude or distance bin `[lo, hi]` from its two optional ends (an absent end open),
/// each inside `limits`, `lo < hi`; refused unless the set is chosen from a scenario's
/// stations. `None` when neither end is given.
fn checked_bin(
    ck: &mut Checker,
    (lo_field, lo): (&str, Option<f64>),
    (hi_field, hi): (&str, Option<f64>),
    limits: (f64, f64),
    stations: bool,
) -> Option<(f64, f64)> {
    if lo.is_none() && hi.is_none() {
        return None;
    }
    if !stations {
        let (field, value) = if let Some(v) = lo { (lo_field, v) } else { (hi_field, hi.unwrap_or(f64::NAN)) };
        ck.push(
            field,
            value,
            "absent: magnitude and distance bins choose among a scenario's stations (a fault scene with \
             [[stations]] on the surface), not among the records of events",
        );
        return None;
    }
    let lo_ok = lo.is_none_or(|v| ck.range(lo_field, v, limits.0, false, limits.1, false));
    let hi_ok = hi.is_none_or(|v| ck.range(hi_field, v, limits.0, false, limits.1, false));
    let (a, b) = (lo.unwrap_or(f64::NEG_INFINITY), hi.unwrap_or(f64::INFINITY));
    if lo_ok && hi_ok && a >= b {
        ck.push(hi_field, b, format!("above {lo_field} ({})", num(a)));
    }
    Some((a, b))
}
