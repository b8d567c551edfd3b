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
fn shipped_pipelines_are_valid_and_mislead_nobody() {
    for entry in std::fs::read_dir(repo_path("pipelines")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let p = Pipeline::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert!(p.warnings.is_empty(), "{}: {:?}", path.display(), p.warnings);
        }
    }
}

#[test]
fn a_bad_grid_is_refused_once_and_its_content_never_echoed() {
    let err = Pipeline::load(&repo_path("pipelines/invalid/friction_grid_nan_row.toml")).unwrap_err();
    let text = format!("{}", std::error::Error::source(&err).unwrap());
    assert_eq!(text.matches(" - ").count(), 1, "one refusal, not a second one about its row count:\n{text}");
    assert!(!text.contains("0.1,0,NaN"), "the row was echoed:\n{text}");
    let err = Pipeline::load(&repo_path("pipelines/invalid/friction_grid_not_a_grid.toml")).unwrap_err();
    let text = format!("{}", std::error::Error::source(&err).unwrap());
    assert!(!text.contains("version = 1") && !text.contains("A report seed"), "content echoed:\n{text}");
}

#[test]
fn refusals_write_numbers_short() {
    for (toml, want) in [
        ("version = 1\n[material]\ndensity_kg_m3 = 5e-324\n", "density_kg_m3 = 5e-324"),
        ("version = 1\n[block]\nlc_m = -1e300\n", "block.lc_m = -1e300"),
        ("version = 1\n[spectra]\nperiod_min_s = 1e-300\n", "period_min_s = 1e-300"),
        ("version = 1\n[spectra]\nperiod_count = 1099511627776\n", "spectra.period_count = 1099511627776"),
    ] {
        let e = Pipeline::from_toml(toml, "t").unwrap_err().to_string();
        assert!(e.contains(want), "{e}");
        assert!(!e.contains("00000000000"), "a long number: {e}");
    }
}
