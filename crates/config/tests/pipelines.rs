//! Every pipeline file in the repository: the shipped ones are valid, every file in
//! `pipelines/invalid/` is refused with the message its `# expect:` lines give.

use std::path::PathBuf;

use stickslip_config::Pipeline;

fn repo_path(rel: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").join(rel)
}

#[test]
fn every_invalid_pipeline_is_refused_with_its_expected_message() {
    let dir = repo_path("pipelines/invalid");
    let mut checked = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        if text.lines().any(|l| l.starts_with("# refused by: stickslip")) {
            // Refused by the command line (memory, run length), not by the file: valid here,
            // checked by the cli's tests.
            Pipeline::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            continue;
        }
        let expected: Vec<&str> = text.lines().filter_map(|l| l.strip_prefix("# expect: ")).collect();
        assert!(!expected.is_empty(), "{}: no '# expect:' line", path.display());
        let err = match Pipeline::load(&path) {
            Ok(_) => panic!("{} was accepted", path.display()),
            Err(e) => format!("{e}: {}", std::error::Error::source(&e).map(|s| s.to_string()).unwrap_or_default()),
        };
        for want in expected {
            assert!(err.contains(want), "{}: message lacks {want:?}:\n{err}", path.display());
        }
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} invalid files");
}

#[test]
fn shipped_pipelines_are_valid() {
    for entry in std::fs::read_dir(repo_path("pipelines")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            Pipeline::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
    }
}
