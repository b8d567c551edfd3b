//! Pipeline files: a scene plus what to do with it (seeds, later analysis stages).
//!
//! A pipeline file is TOML: `version`, `name`, `description`, `[seeds]`, then the scene sections
//! of [`stickslip_solver::scene`] at top level (`[block]`, `[material]`, …). Unknown keys are
//! refused, every value is validated before anything runs.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use stickslip_solver::scene::{
    BlockSection, BoundarySection, FrictionSection, MaterialSection, RecordSection, SelfWeightSection, ShearSection,
    SkipAheadSection, TimeSection,
};
use stickslip_solver::{FieldError, Scene, SceneFile, SolverError};

use crate::error::AnalysisError;
use crate::events::EventParams;
use crate::report::ReportParams;
use crate::similarity::SimilarityParams;
use crate::spectra::stage::SpectraParams;

/// The pipeline-file version this build reads.
pub const PIPELINE_VERSION: i64 = 1;

/// `[seeds]`: the seeds of the ensemble, a list and/or a range.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct SeedsSection {
    /// Explicit seeds.
    #[serde(default)]
    pub list: Vec<i64>,
    /// `count` consecutive seeds starting at `first`.
    pub range: Option<SeedRange>,
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

/// A pipeline file as written (scene sections at top level, defaults = the paper scene).
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
    /// Scene `[block]`.
    #[serde(default)]
    pub block: BlockSection,
    /// Scene `[material]`.
    #[serde(default)]
    pub material: MaterialSection,
    /// Scene `[friction]`.
    #[serde(default)]
    pub friction: FrictionSection,
    /// Scene `[time]`.
    #[serde(default)]
    pub time: TimeSection,
    /// Scene `[self_weight]`.
    #[serde(default)]
    pub self_weight: SelfWeightSection,
    /// Scene `[shear]`.
    #[serde(default)]
    pub shear: ShearSection,
    /// Scene `[[boundary]]`.
    #[serde(default)]
    pub boundary: Vec<BoundarySection>,
    /// Scene `[record]`.
    #[serde(default)]
    pub record: RecordSection,
    /// Scene `[skip_ahead]`.
    #[serde(default)]
    pub skip_ahead: SkipAheadSection,
    /// `[events]`: event detection thresholds.
    #[serde(default)]
    pub events: EventParams,
    /// `[similarity]`: the prototype fault.
    #[serde(default)]
    pub similarity: SimilarityParams,
    /// `[spectra]`: the spectra stage; absent = skipped.
    pub spectra: Option<SpectraParams>,
    /// `[report]`: figures and page (not part of the hash: it does not change any table).
    #[serde(default)]
    pub report: ReportParams,
}

/// Everything that determines one seed's results, hashed to tell results of a changed pipeline
/// apart (seeds, name and description are not part of it: adding seeds keeps finished ones).
#[derive(Serialize)]
struct Hashed<'a> {
    scene: &'a SceneFile,
    events: &'a EventParams,
    similarity: &'a SimilarityParams,
    spectra: &'a Option<SpectraParams>,
}

/// A validated pipeline.
#[derive(Clone, Debug)]
pub struct Pipeline {
    /// Name (output folder).
    pub name: String,
    /// Description.
    pub description: String,
    /// Seeds, in the order given, without duplicates.
    pub seeds: Vec<u64>,
    /// The scene.
    pub scene: Scene,
    /// Event detection.
    pub events: EventParams,
    /// Similarity scaling.
    pub similarity: SimilarityParams,
    /// Spectra stage, if asked.
    pub spectra: Option<SpectraParams>,
    /// Report stage.
    pub report: ReportParams,
    /// Hash of everything that determines a seed's results (scene, events, similarity), as 16
    /// hex digits.
    pub hash: String,
    /// Where it was read from.
    pub source: Option<PathBuf>,
}

fn refuse(field: &str, value: impl ToString, allowed: &str) -> FieldError {
    FieldError { field: field.into(), value: value.to_string(), allowed: allowed.into() }
}

impl Pipeline {
    /// Reads and validates a pipeline file.
    pub fn load(path: &Path) -> Result<Pipeline, AnalysisError> {
        let text = std::fs::read_to_string(path).map_err(|e| AnalysisError::io(path, e))?;
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("pipeline").to_string();
        let mut p = Pipeline::from_toml(&text, &stem)
            .map_err(|e| AnalysisError::Pipeline { path: path.to_path_buf(), source: Box::new(e) })?;
        p.source = Some(path.to_path_buf());
        Ok(p)
    }

    /// Parses and validates pipeline TOML; `default_name` is used when the file has no `name`.
    pub fn from_toml(text: &str, default_name: &str) -> Result<Pipeline, SolverError> {
        let file: PipelineFile = toml::from_str(text).map_err(|e| SolverError::Syntax(e.to_string()))?;
        let mut errors = Vec::new();
        if file.version != PIPELINE_VERSION {
            errors.push(refuse("version", file.version, "1 (the pipeline format this stickslip reads)"));
        }
        let name = file.name.clone().unwrap_or_else(|| default_name.to_string());
        if name.is_empty() || !name.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_') {
            errors.push(refuse(
                "name",
                format!("{name:?}"),
                "letters, digits, '-' and '_' (it names the output folder)",
            ));
        }
        let mut seeds: Vec<u64> = Vec::new();
        for (i, &s) in file.seeds.list.iter().enumerate() {
            match u64::try_from(s) {
                Ok(s) => seeds.push(s),
                Err(_) => errors.push(refuse(&format!("seeds.list[{i}]"), s, "a seed ≥ 0")),
            }
        }
        if let Some(r) = file.seeds.range {
            if r.first < 0 {
                errors.push(refuse("seeds.range.first", r.first, "a seed ≥ 0"));
            } else if !(1..=10_000_000).contains(&r.count) {
                errors.push(refuse("seeds.range.count", r.count, "1 ≤ count ≤ 10000000"));
            } else {
                seeds.extend((0..r.count as u64).map(|k| r.first as u64 + k));
            }
        }
        if file.seeds.list.is_empty() && file.seeds.range.is_none() {
            seeds.push(123);
        }
        let mut seen = std::collections::HashSet::new();
        seeds.retain(|s| seen.insert(*s));
        let scene_file = SceneFile {
            block: file.block.clone(),
            material: file.material.clone(),
            friction: file.friction.clone(),
            time: file.time.clone(),
            self_weight: file.self_weight.clone(),
            shear: file.shear.clone(),
            boundary: file.boundary.clone(),
            record: file.record.clone(),
            skip_ahead: file.skip_ahead.clone(),
        };
        check_events(&file.events, &mut errors);
        check_similarity(&file.similarity, &mut errors);
        let scene = match Scene::try_from(scene_file) {
            Ok(s) => Some(s),
            Err(SolverError::InvalidScene(mut e)) => {
                errors.append(&mut e);
                None
            }
            Err(other) => return Err(other),
        };
        if !errors.is_empty() {
            return Err(SolverError::InvalidScene(errors));
        }
        let scene = scene.expect("no errors means a scene");
        if let Some(sp) = &file.spectra {
            sp.check(&scene, &mut errors);
            if !errors.is_empty() {
                return Err(SolverError::InvalidScene(errors));
            }
        }
        let hash = hash_toml(&Hashed {
            scene: &scene.file,
            events: &file.events,
            similarity: &file.similarity,
            spectra: &file.spectra,
        });
        Ok(Pipeline {
            name,
            description: file.description,
            seeds,
            scene,
            events: file.events,
            similarity: file.similarity,
            spectra: file.spectra,
            report: file.report,
            hash,
            source: None,
        })
    }
}

fn positive(errors: &mut Vec<FieldError>, field: &str, v: f64) {
    if !(v > 0.0 && v.is_finite()) {
        errors.push(refuse(field, v, &format!("0 < {} (finite)", field.rsplit('.').next().unwrap_or(field))));
    }
}

fn check_events(e: &EventParams, errors: &mut Vec<FieldError>) {
    positive(errors, "events.smoothing_s", e.smoothing_s);
    positive(errors, "events.v_on_m_s", e.v_on_m_s);
    positive(errors, "events.quiet_s", e.quiet_s);
    if !(e.v_off_m_s > 0.0 && e.v_off_m_s < e.v_on_m_s) {
        errors.push(refuse("events.v_off_m_s", e.v_off_m_s, "0 < v_off_m_s < v_on_m_s (hysteresis)"));
    }
    if !(e.merge_gap_s >= 0.0 && e.merge_gap_s.is_finite()) {
        errors.push(refuse("events.merge_gap_s", e.merge_gap_s, "0 ≤ merge_gap_s (finite)"));
    }
    if !(e.min_drop_pa >= 0.0 && e.min_drop_pa.is_finite()) {
        errors.push(refuse("events.min_drop_pa", e.min_drop_pa, "0 ≤ min_drop_pa (finite)"));
    }
    if !(e.main_fraction > 0.0 && e.main_fraction <= 1.0) {
        errors.push(refuse("events.main_fraction", e.main_fraction, "0 < main_fraction ≤ 1"));
    }
}

fn check_similarity(s: &SimilarityParams, errors: &mut Vec<FieldError>) {
    positive(errors, "similarity.prototype_length_m", s.prototype_length_m);
    positive(errors, "similarity.prototype_rate_m_s", s.prototype_rate_m_s);
}

/// FNV-1a (64 bit) of the canonical TOML of `value`: equal for files that differ only in
/// layout, comments or defaults written out, different as soon as a value changes.
fn hash_toml<T: Serialize>(value: &T) -> String {
    let canonical = toml::to_string(value).expect("pipeline sections serialise");
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in canonical.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    format!("{h:016x}")
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
    fn wrong_version_and_name_are_refused() {
        let e = Pipeline::from_toml("version = 2\nname = \"a b\"\n", "x").unwrap_err().to_string();
        assert!(e.contains("version = 2"), "{e}");
        assert!(e.contains("name = \"a b\""), "{e}");
    }
}
