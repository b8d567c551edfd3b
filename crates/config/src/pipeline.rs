//! Pipeline files: the scene and what to do with it, in one TOML file — the product's only input
//! format.
//!
//! A pipeline file has `version`, `name`, `description`, `[seeds]`, the scene sections at top
//! level (`[block]`, `[material]`, …; see [`crate::scene`]) and the analysis sections
//! (`[events]`, `[similarity]`, `[spectra]`, `[report]`; see [`crate::sections`]). Unknown keys
//! are refused with their line; every value is validated before anything runs.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use stickslip_analysis::settings::AccelerogramSettings;
use stickslip_analysis::{Settings, SpectraSettings};
use stickslip_seismo::accelerogram::processing::{MAX_CORNER_OF_NYQUIST, USABLE_LOW_FACTOR};
use stickslip_seismo::emission::ClusterParams;
use stickslip_seismo::events::EventParams;
use stickslip_seismo::similarity::SimilarityParams;
use stickslip_solver::{Scene, TracePlan};

use crate::accelerograms::AccelerogramsSection;
use crate::broadband::BroadbandSection;
use crate::check::Checker;
use crate::check::approx;
use crate::error::{ConfigError, Warning};
use crate::input::InputFile;
use crate::precision::{PrecisionTarget, TargetSection};
use crate::scene::{
    AbsorbingSection, BlockSection, BoundarySection, FaultSection, FrictionSection, LoadingPlateSection,
    MaterialSection, MediumSection, RecordSection, RuptureSection, SceneSections, SelfWeightSection, ShearSection,
    SkipAheadSection, StationSection, TimeSection,
};
use crate::sections::{
    EventsSection, ExchangeSection, ReportSection, ReportSettings, SimilaritySection, SpectraSection, shortest_period,
};
use crate::seeds::MAX_SEEDS;
use crate::set::{SetPool, SetSection, SetSettings};
use crate::station_band::{check_set_site, station_band, warn_gmm_band};

/// The pipeline-file version this build reads.
pub const PIPELINE_VERSION: i64 = 1;

/// The largest pipeline file read (bytes).
pub const MAX_PIPELINE_BYTES: u64 = 16 << 20;

/// `[seeds]`: the seeds of the ensemble, a list and/or a range.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct SeedsSection {
    /// Explicit seeds.
    #[serde(default)]
    pub list: Vec<i64>,
    /// `count` consecutive seeds starting at `first`.
    pub range: Option<SeedRange>,
    /// Run in batches until a statistic is precise enough (the seeds above are the budget).
    pub target: Option<TargetSection>,
}

/// A range of seeds.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SeedRange {
    /// First seed.
    pub first: i64,
    /// Number of seeds.
    pub count: i64,
}

/// A pipeline file as written (defaults = the paper scene).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PipelineFile {
    /// File format version (1).
    pub version: i64,
    /// Name, used for the output folder `reports/<name>/`; letters, digits, `-`, `_`.
    /// Default: the file name without extension.
    pub name: Option<String>,
    /// Free text shown in reports.
    #[serde(default)]
    pub description: String,
    /// Seeds. Default: `list = [123]`.
    #[serde(default)]
    pub seeds: SeedsSection,
    /// `[block]`.
    #[serde(default)]
    pub block: BlockSection,
    /// `[material]`.
    #[serde(default)]
    pub material: MaterialSection,
    /// `[friction]`.
    #[serde(default)]
    pub friction: FrictionSection,
    /// `[time]`.
    #[serde(default)]
    pub time: TimeSection,
    /// `[self_weight]`.
    #[serde(default)]
    pub self_weight: SelfWeightSection,
    /// `[shear]`.
    #[serde(default)]
    pub shear: ShearSection,
    /// `[[boundary]]`.
    #[serde(default)]
    pub boundary: Vec<BoundarySection>,
    /// `[record]`.
    #[serde(default)]
    pub record: RecordSection,
    /// `[skip_ahead]`.
    #[serde(default)]
    pub skip_ahead: SkipAheadSection,
    /// `[loading_plate]`: compliant loading by a plate on springs; absent = drivers only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loading_plate: Option<LoadingPlateSection>,
    /// `[rupture]`: bars that crack; absent = every bar elastic.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rupture: Option<RuptureSection>,
    /// `[fault]`: the base as one side of a planar fault with its tractions; absent = the
    /// paper's rigid base.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fault: Option<FaultSection>,
    /// `[absorbing]`: faces that let waves leave; absent = none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub absorbing: Option<AbsorbingSection>,
    /// `[[stations]]`: named points whose motion is recorded.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stations: Vec<StationSection>,
    /// `[medium]`: layers, Q and Kelvin–Voigt damping; absent = the homogeneous elastic
    /// `[material]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub medium: Option<MediumSection>,
    /// `[events]`: event detection thresholds.
    #[serde(default)]
    pub events: EventsSection,
    /// `[similarity]`: the prototype fault.
    #[serde(default)]
    pub similarity: SimilaritySection,
    /// `[accelerograms]`: records of events (or of the whole run), processed; absent = none
    /// unless `[spectra]` asks for spectra (then its defaults).
    pub accelerograms: Option<AccelerogramsSection>,
    /// `[spectra]`: spectra of the records; absent = skipped.
    pub spectra: Option<SpectraSection>,
    /// `[broadband]`: broadband records of a fault scene's surface stations; absent = the
    /// lattice's motion only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub broadband: Option<BroadbandSection>,
    /// `[set]`: a set of records matched to a design spectrum (not part of the hash: it is chosen
    /// from finished seeds and changes no seed's table).
    pub set: Option<SetSection>,
    /// `[report]`: figures and page (not part of the hash: it does not change any table).
    #[serde(default)]
    pub report: ReportSection,
    /// `[exchange]`: the scene's place on the Earth in the StationXML and QuakeML files (not part
    /// of the hash: they are written from the tables at each gathering); absent = 0° N 0° E.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exchange: Option<ExchangeSection>,
    /// `[cycles]`: earthquake cycles on the fault, loaded by the plate over years; absent = the
    /// explicit run of each seed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cycles: Option<crate::cycles::CyclesSection>,
}

impl Default for PipelineFile {
    /// `version = 1` and nothing else: the paper scene with one seed.
    fn default() -> Self {
        PipelineFile {
            version: PIPELINE_VERSION,
            name: None,
            description: String::new(),
            seeds: SeedsSection::default(),
            block: BlockSection::default(),
            material: MaterialSection::default(),
            friction: FrictionSection::default(),
            time: TimeSection::default(),
            self_weight: SelfWeightSection::default(),
            shear: ShearSection::default(),
            boundary: Vec::new(),
            record: RecordSection::default(),
            skip_ahead: SkipAheadSection::default(),
            loading_plate: None,
            rupture: None,
            fault: None,
            absorbing: None,
            stations: Vec::new(),
            medium: None,
            events: EventsSection::default(),
            similarity: SimilaritySection::default(),
            accelerograms: None,
            spectra: None,
            broadband: None,
            set: None,
            report: ReportSection::default(),
            exchange: None,
            cycles: None,
        }
    }
}

/// Everything that determines one seed's results, hashed to tell results of a changed pipeline
/// apart (seeds, name, description and report are not part of it: adding seeds keeps finished
/// ones, and the report changes no table).
#[derive(Serialize)]
struct Hashed<'a> {
    scene: SceneSections<'a>,
    events: &'a EventsSection,
    similarity: &'a SimilaritySection,
    accelerograms: &'a Option<AccelerogramsSection>,
    spectra: &'a Option<SpectraSection>,
    #[serde(skip_serializing_if = "Option::is_none")]
    broadband: &'a Option<BroadbandSection>,
    #[serde(skip_serializing_if = "Option::is_none")]
    cycles: &'a Option<crate::cycles::CyclesSection>,
}

/// Top-level keys of a pipeline file that are not part of the hash.
pub const NOT_HASHED: [&str; 6] = ["version", "name", "description", "seeds", "set", "report"];

impl PipelineFile {
    /// The hash of everything that determines a seed's results, 16 hex digits (FNV-1a of the
    /// canonical TOML: equal for files that differ only in layout, comments or defaults written
    /// out, different as soon as a value changes).
    pub fn hash(&self) -> String {
        // The grid's rows are hashed, not where the file was: a copy gives the same results.
        let mut friction = self.friction.clone();
        if let Some(g) = friction.grid.as_mut() {
            g.file.clear();
        }
        if let Some(g) = friction.rate_state_grid.as_mut() {
            g.file.clear();
        }
        let mut fault = self.fault.clone();
        if let Some(g) = fault.as_mut().and_then(|f| f.grid.as_mut()) {
            g.file.clear();
        }
        let hashed = Hashed {
            scene: SceneSections { friction: &friction, fault: &fault, ..self.scene_sections() },
            events: &self.events,
            similarity: &self.similarity,
            accelerograms: &self.accelerograms,
            spectra: &self.spectra,
            broadband: &self.broadband,
            cycles: &self.cycles,
        };
        let canonical = toml::to_string(&hashed).expect("pipeline sections serialise");
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for b in canonical.bytes() {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
        format!("{h:016x}")
    }

    /// The scene sections of this file.
    pub fn scene_sections(&self) -> SceneSections<'_> {
        SceneSections {
            block: &self.block,
            material: &self.material,
            friction: &self.friction,
            time: &self.time,
            self_weight: &self.self_weight,
            shear: &self.shear,
            boundary: &self.boundary,
            record: &self.record,
            skip_ahead: &self.skip_ahead,
            loading_plate: &self.loading_plate,
            rupture: &self.rupture,
            fault: &self.fault,
            absorbing: &self.absorbing,
            medium: &self.medium,
            stations: &self.stations,
        }
    }

    /// The scene of this file (validated).
    pub fn scene(&self) -> Result<Scene, ConfigError> {
        let mut ck = Checker::default();
        let events = self.events.build(&mut ck);
        let scene = crate::scene::build(self.scene_sections(), &mut ck);
        ck.finish()?;
        let mut scene = scene.expect("no refusal means a scene");
        scene.record.trace = trace_plan(&events, scene.shear.duration_s);
        // Accelerograms are processed with `[accelerograms]` or `[spectra]` (as by the pipeline).
        scene.record.resampled = self.accelerograms.is_some() || self.spectra.is_some();
        Ok(scene)
    }
}

/// What the solver keeps of every step for the detector `events` (docs/model.md §7): steps
/// within `2·smoothing + quiet` of a step whose raw slip rate reaches half of `v_off` (so every
/// smoothing window and quiet spell the detector reads lies at full rate), and between bursts
/// one step in `smoothing/4` or in 1/200,000 of the shear stage, whichever is longer.
pub fn trace_plan(events: &EventParams, shear_duration_s: f64) -> TracePlan {
    TracePlan {
        hot_rate_m_s: 0.5 * events.v_off_m_s,
        margin_s: 2.0 * events.smoothing_s + events.quiet_s,
        quiet_interval_s: (0.25 * events.smoothing_s).max(shear_duration_s / 200_000.0),
        rupture_rate_m_s: events.rupture_rate_m_s,
    }
}

/// A validated pipeline.
#[derive(Clone, Debug)]
pub struct Pipeline {
    /// Name (output folder).
    pub name: String,
    /// Description.
    pub description: String,
    /// Seeds, in the order given, without duplicates (with a precision target: the budget, used
    /// in this order).
    pub seeds: Vec<u64>,
    /// Stop adding seeds once a statistic is precise enough (`[seeds.target]`).
    pub target: Option<PrecisionTarget>,
    /// The scene.
    pub scene: Scene,
    /// What the analysis of each seed computes: events, similarity, records, spectra, acoustic
    /// emission.
    pub analysis: Settings,
    /// A matched set, if asked.
    pub set: Option<SetSettings>,
    /// Report stage.
    pub report: ReportSettings,
    /// Hash of everything that determines a seed's results (see [`PipelineFile::hash`]).
    pub hash: String,
    /// Where it was read from.
    pub source: Option<PathBuf>,
    /// Its text as read (with [`Pipeline::load`]).
    pub text: Option<String>,
    /// The files it read (a friction grid, a CSV target), see [`crate::input`].
    pub inputs: Vec<InputFile>,
    /// Values accepted that could mislead (printed by `check` and the runs, shown in the report).
    pub warnings: Vec<Warning>,
    /// The file as read, defaults filled in.
    pub file: PipelineFile,
    /// `[cycles]`: a cycle run in place of the seeds' explicit runs.
    pub cycles: Option<stickslip_solver::cycles::CycleSpec>,
}

impl Pipeline {
    /// Reads and validates a pipeline file (a regular file of at most [`MAX_PIPELINE_BYTES`]);
    /// the files it names are read relative to its folder.
    pub fn load(path: &Path) -> Result<Pipeline, ConfigError> {
        let text = crate::input::read_regular(path, MAX_PIPELINE_BYTES)
            .map_err(|why| ConfigError::Io { path: path.to_path_buf(), source: std::io::Error::other(why) })?;
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("pipeline").to_string();
        let base = path.parent().unwrap_or(Path::new("."));
        let mut p = toml::from_str(&text)
            .map_err(|e| ConfigError::syntax(&e))
            .and_then(|file| Pipeline::from_file_in(file, &stem, base))
            .map_err(|e| ConfigError::File { path: path.to_path_buf(), source: Box::new(e) })?;
        p.source = Some(path.to_path_buf());
        p.text = Some(text);
        Ok(p)
    }

    /// Parses and validates pipeline TOML; `default_name` is used when the file has no `name`.
    pub fn from_toml(text: &str, default_name: &str) -> Result<Pipeline, ConfigError> {
        let file: PipelineFile = toml::from_str(text).map_err(|e| ConfigError::syntax(&e))?;
        Pipeline::from_file(file, default_name)
    }

    /// Validates a pipeline file given as a value (e.g. built in code from
    /// [`PipelineFile::default`]).
    pub fn from_file(file: PipelineFile, default_name: &str) -> Result<Pipeline, ConfigError> {
        Pipeline::from_file_in(file, default_name, Path::new("."))
    }

    /// As [`Pipeline::from_file`], with files the pipeline names (a CSV target) read relative to
    /// `base`.
    pub fn from_file_in(mut file: PipelineFile, default_name: &str, base: &Path) -> Result<Pipeline, ConfigError> {
        let mut ck = Checker::default();
        let mut inputs = Vec::new();
        if let Some(grid) = file.friction.grid.as_mut()
            && grid.rows.is_empty()
        {
            inputs.extend(grid.read(base, &mut ck));
        }
        if let Some(grid) = file.friction.rate_state_grid.as_mut()
            && grid.rows.is_empty()
        {
            inputs.extend(grid.read(base, &mut ck));
        }
        if let Some(grid) = file.fault.as_mut().and_then(|f| f.grid.as_mut())
            && grid.rows.is_empty()
        {
            inputs.extend(grid.read(base, &mut ck));
        }
        if let Some(medium) = file.medium.as_mut()
            && !medium.read_from_file
        {
            inputs.extend(medium.read(base, &mut ck));
        }
        if file.version != PIPELINE_VERSION {
            ck.push("version", file.version, "1 (the pipeline format this stickslip reads)");
        }
        let name = file.name.clone().unwrap_or_else(|| default_name.to_string());
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
            ck.push("name", format!("{name:?}"), "letters, digits, '-' and '_' (it names the output folder)");
        }
        let mut seeds: Vec<u64> = Vec::new();
        for (i, &s) in file.seeds.list.iter().enumerate() {
            match u64::try_from(s) {
                Ok(s) => seeds.push(s),
                Err(_) => ck.push(format!("seeds.list[{i}]"), s, "a seed ≥ 0"),
            }
        }
        if let Some(r) = file.seeds.range {
            if r.first < 0 {
                ck.push("seeds.range.first", r.first, "a seed ≥ 0");
            } else if !(1..=10_000_000).contains(&r.count) {
                ck.push("seeds.range.count", r.count, "1 ≤ count ≤ 10000000");
            } else {
                seeds.extend((0..r.count as u64).map(|k| r.first as u64 + k));
            }
        }
        if file.seeds.list.is_empty() && file.seeds.range.is_none() {
            seeds.push(123);
        }
        let mut seen = std::collections::HashSet::new();
        seeds.retain(|s| seen.insert(*s));
        if seeds.len() as u64 > MAX_SEEDS {
            ck.push(
                "seeds",
                format!("{} seeds (list and range)", seeds.len()),
                format!("at most {MAX_SEEDS} seeds; run a larger ensemble as several pipelines or shards"),
            );
        }
        let target = file.seeds.target.as_ref().and_then(|t| t.build(seeds.len(), &mut ck));
        let events = file.events.build(&mut ck);
        let scene = crate::scene::build(file.scene_sections(), &mut ck);
        let similarity = file.similarity.build(scene.as_ref(), &mut ck);
        let report = file.report.build(&mut ck);
        if let Some(x) = &file.exchange {
            x.build(&mut ck);
        }
        for (i, s) in report.seeds.iter().enumerate() {
            if !seen.contains(s) {
                ck.push(
                    format!("report.seeds[{i}]"),
                    s,
                    "one of the pipeline's seeds ([seeds] list and range): the report draws only seeds that ran",
                );
            }
        }
        if let Some(scene) = scene.as_ref() {
            warn_gmm_band(scene, &mut ck);
        }
        let random = file.random_fields();
        if file.seeds.target.is_some() && random.is_empty() {
            ck.push(
                "seeds.target",
                "(present)",
                "a pipeline whose seeds differ: with material.young_cv = 0, friction.mu_cv = 0 and no \
                 rupture.fracture_energy_cv, fault.stochastic or fault.nucleation, every seed gives the same run, and a confidence interval of clones is 0 \
                 (give a coefficient of variation > 0, or drop [seeds.target])",
            );
        } else if random.is_empty() && seeds.len() > 1 {
            ck.warn(
                "material.young_cv",
                file.material.young_cv,
                format!(
                    "every one of the {} seeds gives the same run (material.young_cv = 0, friction.mu_cv = 0, no \
                     rupture.fracture_energy_cv, fault.stochastic, fault.nucleation or cycles.heterogeneity): the spread \
                     across seeds is 0 by construction",
                    seeds.len()
                ),
            );
        }
        let accelerograms = match (&file.accelerograms, &file.spectra, &scene) {
            (Some(a), _, Some(scene)) => Some(a.build(scene, &mut ck)),
            (None, Some(_), Some(scene)) => Some(AccelerogramsSection::default().build(scene, &mut ck)),
            _ => None,
        };
        let spectra = match (&file.spectra, &scene) {
            (Some(sp), Some(scene)) => {
                let f_max = accelerograms.as_ref().map_or(f64::INFINITY, |a| a.resolved_hz);
                Some(sp.build(scene, shortest_period(f_max, scene.record.interval_s), &mut ck))
            }
            _ => None,
        };
        let broadband = match (&file.broadband, &scene) {
            (Some(b), Some(scene)) => b.build(scene, &file.stations, &mut ck),
            _ => None,
        };
        let set = file.set.as_ref().and_then(|s| {
            let pool = scene.as_ref().map(|sc| set_pool(sc, spectra.as_ref(), &similarity, broadband.is_some()));
            s.build(base, pool.unwrap_or(SetPool::Records(None)), &mut ck)
        });
        if let Some(section) = file.set.as_ref() {
            check_set_site(&mut ck, section.vs30_m_s, broadband.as_ref());
        }
        if let (Some(set), Some(acc), Some(scene)) = (&set, &accelerograms, &scene)
            && ck.is_clean()
            && station_band(scene, broadband.is_some()).is_none()
        {
            check_set_band(&mut ck, file.set.as_ref().expect("a set"), set, acc, scene, &similarity);
        }
        let emission = match (&file.rupture, &scene) {
            (Some(r), Some(scene)) => Some(ClusterParams {
                link_distance_m: r.ae_link_distance_m.unwrap_or(2.0 * scene.lc_m),
                link_time_s: r.ae_link_time_s.unwrap_or(10.0 * scene.lc_m / scene.p_wave_speed()),
            }),
            _ => None,
        };
        let cycles = match (&file.cycles, &scene) {
            (Some(c), Some(scene)) => Some(c.build(scene, &mut ck)),
            _ => None,
        };
        let warnings = ck.take_warnings();
        ck.finish()?;
        inputs.extend(set.as_ref().and_then(|s| s.input.clone()));
        Ok(Pipeline {
            name,
            description: file.description.clone(),
            seeds,
            target,
            scene: {
                let mut scene = scene.expect("no refusal means a scene");
                scene.record.trace = trace_plan(&events, scene.shear.duration_s);
                scene.record.resampled = accelerograms.is_some();
                scene
            },
            analysis: Settings { events, similarity, accelerograms, spectra, emission, broadband },
            cycles,
            set,
            report,
            hash: file.hash(),
            source: None,
            text: None,
            inputs,
            warnings,
            file,
        })
    }
}

/// Refuses a `[set]` period range that no record's usable band can cover, before anything runs:
/// at model scale a record is usable from `1/top` (the filter's top: the lattice's f_max, the
/// high corner or 0.8 of the sampling's Nyquist) to `1/(1.25·f_low)`, with `f_low` the low corner
/// or one over the record's length — at most the shear stage.
fn check_set_band(
    ck: &mut Checker,
    section: &SetSection,
    set: &SetSettings,
    acc: &AccelerogramSettings,
    scene: &Scene,
    similarity: &SimilarityParams,
) {
    let Ok((t_a, t_b)) = set.options.range.bounds() else { return };
    let lambda = similarity.prototype_length_m / (scene.dims.nx as f64 * scene.lc_m);
    let nyquist_top =
        scene.record.interval_s.filter(|v| *v > 0.0).map_or(f64::INFINITY, |iv| MAX_CORNER_OF_NYQUIST * 0.5 / iv);
    let top = acc.high_corner_hz.unwrap_or(acc.resolved_hz).min(acc.resolved_hz).min(nyquist_top);
    let f_low = acc.low_corner_hz.unwrap_or(1.0 / scene.shear.duration_s);
    let (shortest, longest) = (lambda / top, lambda / (USABLE_LOW_FACTOR * f_low));
    if !(shortest.is_finite() && longest.is_finite()) {
        return;
    }
    let eps = 1e-9;
    let (field, value) =
        if section.t1_s > 0.0 { ("set.t1_s", section.t1_s) } else { ("set.period_min_s", section.period_min_s) };
    let outside = if t_a < shortest * (1.0 - eps) {
        Some(format!("its shortest period {} s is below {} s", approx(t_a), approx(shortest)))
    } else if t_b > longest * (1.0 + eps) {
        Some(format!("its longest period {} s is above {} s", approx(t_b), approx(longest)))
    } else {
        None
    };
    if let Some(outside) = outside {
        ck.push(
            field,
            value,
            format!(
                "a period range that records can cover: {outside}, outside every record's usable band ({} … {} s at \
                 prototype scale, λ = {}: from the band's top, the lattice's f_max, high_corner_hz or 0.8 of the \
                 sampling's Nyquist, to 1/1.25 of the longest record, the shear stage of {} s, or of low_corner_hz)",
                approx(shortest),
                approx(longest),
                approx(lambda),
                approx(scene.shear.duration_s)
            ),
        );
    }
}

/// What a `[set]` of `scene` chooses from: its surface stations when it is a fault scenario with
/// some, else the records' `spectra` (their dampings and prototype-scale grid, if any).
fn set_pool<'a>(
    scene: &Scene,
    spectra: Option<&'a SpectraSettings>,
    similarity: &SimilarityParams,
    broadband: bool,
) -> SetPool<'a> {
    match station_band(scene, broadband) {
        Some((shortest, longest)) => SetPool::Stations { shortest, longest },
        None => SetPool::Records(spectra.map(|sp| prototype_grid(sp, scene, similarity))),
    }
}

/// The dampings of `spectra` and its period grid's ends at prototype scale (s), with
/// λ = L_p / (the block's length), as the ensemble scales its records.
fn prototype_grid<'a>(
    spectra: &'a SpectraSettings,
    scene: &Scene,
    similarity: &SimilarityParams,
) -> (&'a [f64], (f64, f64)) {
    let lambda = similarity.prototype_length_m / (scene.dims.nx as f64 * scene.lc_m);
    let (lo, hi) = spectra.periods.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &t| (a.min(t), b.max(t)));
    (spectra.dampings.as_slice(), (lo * lambda, hi * lambda))
}

/// What an output folder keeps of a pipeline so that it can be run or merged from there: the
/// pipeline's text with the path of every file it read pointing at that file's copy, and the
/// copies (see [`crate::input::copy_path`]).
#[derive(Clone, Debug, PartialEq)]
pub struct OutputCopy {
    /// The pipeline file's text, paths rewritten (byte for byte the file otherwise).
    pub text: String,
    /// Each file read: its path relative to the output folder, and its text.
    pub inputs: Vec<(String, String)>,
}

/// The keys of a pipeline file that name files, with where their values stand in the text.
#[derive(Deserialize, Default)]
#[serde(default)]
struct PathKeys {
    friction: FrictionPathKeys,
    fault: Option<FrictionPathKeys>,
    set: Option<SetPathKeys>,
    medium: Option<MediumPathKeys>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct MediumPathKeys {
    profile_file: Option<toml::Spanned<String>>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct FrictionPathKeys {
    grid: Option<GridPathKey>,
    rate_state_grid: Option<GridPathKey>,
}

#[derive(Deserialize)]
struct GridPathKey {
    file: toml::Spanned<String>,
}

#[derive(Deserialize, Default)]
#[serde(default)]
struct SetPathKeys {
    target_csv: Option<toml::Spanned<String>>,
}

impl Pipeline {
    /// The copy an output folder keeps of this pipeline (read with [`Pipeline::load`]; `None`
    /// for a pipeline built in code): its text, with each file it read copied under `inputs/`
    /// and its path rewritten to the copy, so that `stickslip merge` (or a rerun) from the output
    /// folder reads the same files.
    pub fn output_copy(&self) -> Option<OutputCopy> {
        let text = self.text.as_ref()?;
        let keys: PathKeys = toml::from_str(text).ok()?;
        let mut spans: Vec<(&str, std::ops::Range<usize>)> = Vec::new();
        if let Some(g) = &keys.friction.grid {
            spans.push(("friction.grid.file", g.file.span()));
        }
        if let Some(g) = &keys.friction.rate_state_grid {
            spans.push(("friction.rate_state_grid.file", g.file.span()));
        }
        if let Some(g) = keys.fault.as_ref().and_then(|f| f.grid.as_ref()) {
            spans.push(("fault.grid.file", g.file.span()));
        }
        if let Some(t) = keys.set.as_ref().and_then(|s| s.target_csv.as_ref()) {
            spans.push(("set.target_csv", t.span()));
        }
        if let Some(t) = keys.medium.as_ref().and_then(|m| m.profile_file.as_ref()) {
            spans.push(("medium.profile_file", t.span()));
        }
        spans.sort_by_key(|(_, r)| std::cmp::Reverse(r.start));
        let mut out = text.clone();
        let mut inputs = Vec::new();
        for (field, span) in spans {
            let Some(input) = self.inputs.iter().find(|i| i.field == field) else { continue };
            let copy = crate::input::copy_path(field, &input.given);
            out.replace_range(span, &toml::Value::String(copy.clone()).to_string());
            inputs.push((copy, input.text.clone()));
        }
        Some(OutputCopy { text: out, inputs })
    }

    /// What a `[set]` is chosen from and checked against: a fault scenario's surface stations
    /// (their usable periods), or the records' spectra (their dampings and prototype-scale period
    /// grid).
    pub fn set_pool(&self) -> SetPool<'_> {
        set_pool(
            &self.scene,
            self.analysis.spectra.as_ref(),
            &self.analysis.similarity,
            self.analysis.broadband.is_some(),
        )
    }

    /// Whether a `[set]` is chosen from a fault scenario's surface stations (not the records of
    /// events).
    pub fn sets_from_stations(&self) -> bool {
        station_band(&self.scene, self.analysis.broadband.is_some()).is_some()
    }

    /// Whether the report compares this pipeline with the paper (its figure numbers and its
    /// reference values: M = 6.77, 25.8 ms, 7.6 kPa): `Ok(true)` with `[report] paper_figures`
    /// on the paper's block — its modules, Lc, material, gravity, driver speed and prototype
    /// length (λ = 10⁴), whatever its friction and loading —, `Ok(false)` without the flag, and
    /// `Err(why)` with the flag on another block (a copy of `paper.toml` made into one's own
    /// scene), where the paper's numbers would mislead.
    pub fn paper_references(&self) -> Result<bool, String> {
        if !self.report.paper_figures {
            return Ok(false);
        }
        let paper = Pipeline::from_file(PipelineFile::default(), "paper").expect("the default pipeline is valid");
        let (s, p) = (&self.scene, &paper.scene);
        let lambda = |x: &Pipeline| x.analysis.similarity.prototype_length_m;
        let mut differs = Vec::new();
        if s.dims != p.dims || s.lc_m != p.lc_m {
            differs.push(format!(
                "block {}×{}×{} modules of {} m (the paper's: {}×{}×{} of {} m)",
                s.dims.nx, s.dims.ny, s.dims.nz, s.lc_m, p.dims.nx, p.dims.ny, p.dims.nz, p.lc_m
            ));
        }
        if (s.young_pa, s.density_kg_m3, s.poisson, s.young_cv) != (p.young_pa, p.density_kg_m3, p.poisson, p.young_cv)
        {
            differs.push("material".into());
        }
        if s.self_weight.gravity_m_s2 != p.self_weight.gravity_m_s2 {
            differs.push("gravity".into());
        }
        if s.shear.velocity_m_s != p.shear.velocity_m_s {
            differs
                .push(format!("driver speed {} m/s (the paper's: {} m/s)", s.shear.velocity_m_s, p.shear.velocity_m_s));
        }
        if lambda(self) != lambda(&paper) {
            differs.push(format!("prototype length {} m (the paper's: {} m)", lambda(self), lambda(&paper)));
        }
        if differs.is_empty() {
            Ok(true)
        } else {
            Err(format!(
                "[report] paper_figures is on, but this is not the paper's scene ({}): the paper's figure numbers and \
                 reference values are left out",
                differs.join(", ")
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_from_list_and_range_without_duplicates() {
        let p = Pipeline::from_toml("version = 1\n[seeds]\nlist = [5, 7]\nrange = { first = 6, count = 3 }\n", "t")
            .unwrap();
        assert_eq!(p.seeds, vec![5, 7, 6, 8]);
        assert_eq!(p.name, "t");
    }

    #[test]
    fn hash_ignores_layout_but_not_values() {
        let a = Pipeline::from_toml("version = 1\n[material]\nyoung_cv = 0.05\n", "a").unwrap();
        let b = Pipeline::from_toml("version = 1 # same\n", "b").unwrap();
        let c = Pipeline::from_toml("version = 1\n[material]\nyoung_cv = 0.06\n", "c").unwrap();
        assert_eq!(a.hash, b.hash);
        assert_ne!(a.hash, c.hash);
        let d = Pipeline::from_toml("version = 1\n[seeds]\nlist = [1, 2]\n", "d").unwrap();
        assert_eq!(a.hash, d.hash, "the seed list is not part of the hash");
        let e = Pipeline::from_toml("version = 1\n[events]\nmin_drop_pa = 100.0\n", "e").unwrap();
        assert_ne!(a.hash, e.hash, "event thresholds are");
    }

    #[test]
    fn the_paper_is_cited_only_on_its_own_block() {
        let flag = "[report]\npaper_figures = true\n";
        let on = |extra: &str| Pipeline::from_toml(&format!("version = 1\n{flag}{extra}"), "p").unwrap();
        assert_eq!(on("").paper_references(), Ok(true));
        // Its friction and loading may change (paper-seated.toml): the block is the paper's.
        assert_eq!(
            on("[friction]\nmu_static = 0.7\nmu_dynamic = 0.1\nslip_weakening_m = 8e-7\n").paper_references(),
            Ok(true)
        );
        // A copy of paper.toml made into one's own scene: a bigger block, or λ = 100.
        let bigger = on("[block]\nnx = 20\nny = 2\nnz = 6\n").paper_references().unwrap_err();
        assert!(bigger.contains("block 20×2×6 modules"), "{bigger}");
        let small = on("[similarity]\nprototype_length_m = 100.0\n").paper_references().unwrap_err();
        assert!(small.contains("prototype length 100 m"), "{small}");
        assert_eq!(Pipeline::from_toml("version = 1\n", "p").unwrap().paper_references(), Ok(false));
    }

    #[test]
    fn paper_figures_is_off_by_default_and_not_part_of_the_hash() {
        let a = Pipeline::from_toml("version = 1\n", "a").unwrap();
        assert!(!a.report.paper_figures, "a user's own scene is not compared with the paper");
        let b = Pipeline::from_toml("version = 1\n[report]\npaper_figures = true\n", "b").unwrap();
        assert!(b.report.paper_figures);
        assert_eq!(a.hash, b.hash, "the report changes no table");
    }

    #[test]
    fn every_top_level_key_is_hashed_or_said_not_to_be() {
        // A file with every section present: each top-level key is in the hash's canonical form
        // or in NOT_HASHED, so a new section cannot be left out of the hash by accident.
        let file = PipelineFile {
            accelerograms: Some(AccelerogramsSection::default()),
            spectra: Some(SpectraSection::default()),
            set: Some(SetSection::default()),
            rupture: Some(RuptureSection::default()),
            ..PipelineFile::default()
        };
        let table: toml::Table = toml::from_str(&toml::to_string(&file).unwrap()).unwrap();
        let scene_keys = [
            "block",
            "material",
            "friction",
            "time",
            "self_weight",
            "shear",
            "boundary",
            "record",
            "skip_ahead",
            "rupture",
        ];
        let hashed_keys = ["events", "similarity", "accelerograms", "spectra"];
        for key in table.keys() {
            assert!(
                scene_keys.contains(&key.as_str())
                    || hashed_keys.contains(&key.as_str())
                    || NOT_HASHED.contains(&key.as_str()),
                "top-level key {key} is neither hashed nor listed in NOT_HASHED"
            );
        }
        // And every section changes the hash.
        let base = file.hash();
        let mut f = file.clone();
        f.skip_ahead.tolerance = 2e-4;
        assert_ne!(f.hash(), base);
        let mut f = file.clone();
        f.spectra.as_mut().unwrap().rotd = false;
        assert_ne!(f.hash(), base);
        let mut f = file.clone();
        f.accelerograms.as_mut().unwrap().post_event_s = 0.05;
        assert_ne!(f.hash(), base);
        let mut f = file.clone();
        f.set.as_mut().unwrap().count = 7;
        assert_eq!(f.hash(), base, "the set is not part of the hash");
        let mut f = file.clone();
        f.rupture.as_mut().unwrap().fracture_energy_j_m2 = 50.0;
        assert_ne!(f.hash(), base);
        let f = PipelineFile { rupture: None, ..file.clone() };
        assert_ne!(f.hash(), base, "rupture on or off");
    }

    #[test]
    fn hash_of_the_paper_pipeline_is_the_one_results_are_stamped_with() {
        // The hash of a published pipeline must not change with a refactor, or every results
        // folder made with it would be refused. This is the hash of pipelines/paper.toml since it
        // asks for its records in MiniSEED too (a changed file, so a new hash: old folders are
        // refused and say so).
        let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../pipelines/paper.toml")).unwrap();
        let p = Pipeline::from_toml(&text, "paper").unwrap();
        assert_eq!(p.hash, PAPER_HASH);
    }

    /// See `hash_of_the_paper_pipeline_is_the_one_results_are_stamped_with`.
    const PAPER_HASH: &str = "303fe5cfde29cb31";

    #[test]
    fn the_default_file_builds_the_paper_scene() {
        assert_eq!(PipelineFile::default().scene().unwrap(), Scene::paper());
    }

    #[test]
    fn wrong_version_and_name_are_refused() {
        let e = Pipeline::from_toml("version = 2\nname = \"a b\"\n", "x").unwrap_err().to_string();
        assert!(e.contains("version = 2"), "{e}");
        assert!(e.contains("name = \"a b\""), "{e}");
    }
}
