//! Helpers shared by the whole-product tests in `tests/`.

use std::path::PathBuf;

use stickslip_solver::{Scene, SceneFile};

/// The repository root.
pub fn repo_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A path inside the repository.
pub fn repo_path(rel: &str) -> PathBuf {
    repo_root().join(rel)
}

/// A validated scene from a default scene file changed by `edit`.
pub fn scene_with(edit: impl FnOnce(&mut SceneFile)) -> Scene {
    let mut file = SceneFile::default();
    edit(&mut file);
    Scene::try_from(file).expect("test scene is valid")
}

/// A fresh empty folder under the system temp dir, unique per test name and process.
pub fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create scratch dir");
    dir
}
