//! Helpers of the solver's tests: scenes from the pipeline format, paths in the repository.
#![allow(dead_code)]

use std::path::PathBuf;

use stickslip_config::{Pipeline, PipelineFile};
use stickslip_solver::Scene;

/// A path inside the repository.
pub fn repo_path(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").join(rel)
}

/// A validated scene from the default pipeline file (the paper scene) changed by `edit`.
pub fn scene_with(edit: impl FnOnce(&mut PipelineFile)) -> Scene {
    let mut file = PipelineFile::default();
    edit(&mut file);
    file.scene().expect("test scene is valid")
}

/// A shipped pipeline.
pub fn pipeline(rel: &str) -> Pipeline {
    Pipeline::load(&repo_path(rel)).expect("shipped pipeline is valid")
}

/// Names of a roller section.
pub fn roller(face: &str, fix: &[&str]) -> stickslip_config::scene::BoundarySection {
    stickslip_config::scene::BoundarySection { face: face.into(), fix: fix.iter().map(|s| s.to_string()).collect() }
}
