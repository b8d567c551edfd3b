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

#[test]
fn abutting_traction_patches_share_the_nodes_on_their_seam() {
    // TPV5 at 500 m with two patches side by side, their seam on the column of nodes at x = 3 km
    // and their lower side on the row at y = 1 km: each node takes the average of what covers its
    // tile (docs/model.md §15.3) — half of each on the seam, a quarter of each and half of the
    // 70 MPa below at its corner, whatever the order of priority.
    let base = std::fs::read_to_string(repo_path("pipelines/tpv5-500m.toml")).unwrap();
    let dir = std::env::temp_dir().join(format!("stickslip-seam-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (a, b) in [(5, 6), (6, 5)] {
        let text = format!(
            "{base}\n[[fault.patches]]\nname = \"A\"\nshape = \"rectangle\"\nx_m = [1000.0, 3000.0]\ny_m = [1000.0, \
             3000.0]\nshear_stress_pa = 90e6\npriority = {a}\n\n[[fault.patches]]\nname = \"B\"\nshape = \
             \"rectangle\"\nx_m = [3000.0, 5000.0]\ny_m = [1000.0, 3000.0]\nshear_stress_pa = 60e6\npriority = {b}\n"
        );
        let path = dir.join("seam.toml");
        std::fs::write(&path, text).unwrap();
        let p = Pipeline::load(&path).unwrap();
        let fault = p.scene.fault.as_ref().unwrap();
        let lattice = p.scene.lattice();
        let at = |x: f64, y: f64| {
            let c = lattice
                .contact_nodes()
                .iter()
                .position(|&id| {
                    let q = lattice.position(id);
                    q[0] == x && q[1] == y
                })
                .unwrap();
            fault.shear_pa[c][0]
        };
        assert_eq!(at(2000.0, 2000.0), 90e6);
        assert_eq!(at(4000.0, 2000.0), 60e6);
        assert!((at(3000.0, 2000.0) - 75e6).abs() < 1e-6, "seam: {}", at(3000.0, 2000.0));
        assert!((at(3000.0, 1000.0) - 72.5e6).abs() < 1e-6, "corner: {}", at(3000.0, 1000.0));
        // One patch alone on its side: half of it over what lies below.
        assert!((at(2000.0, 1000.0) - 80e6).abs() < 1e-6, "side: {}", at(2000.0, 1000.0));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `[fault] overburden_gradient_pa_m`: every traction of a node, the seed's random field and
/// nucleation square included, is the one without it times the mean over the node's tile of
/// `min(1, g·d/σn)` (docs/model.md §15.3), computed here by a midpoint sum.
#[test]
fn an_overburden_scales_every_traction_by_its_depths_share() {
    // scenario-m6 (uniform σn, a random field, a nucleation square) on 1 km modules.
    // Without its broadband records and set, which 1 km modules cannot carry.
    let text = std::fs::read_to_string(repo_path("pipelines/scenario-m6.toml")).unwrap();
    let base = text[..text.find("\n[broadband]").unwrap()]
        .replace("nx = 160\nny = 40\nnz = 104\nlc_m = 500.0", "nx = 80\nny = 20\nnz = 52\nlc_m = 1000.0");
    assert!(base.contains("lc_m = 1000.0"), "the block was not coarsened");
    let with =
        base.replace("shear_stress_pa = 66.5e6\n", "shear_stress_pa = 66.5e6\noverburden_gradient_pa_m = 16380.0\n");
    assert_ne!(with, base);
    let dir = std::env::temp_dir().join(format!("stickslip-overburden-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let load = |name: &str, text: &str| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        Pipeline::load(&path).unwrap()
    };
    let (plain, deep) = (load("plain.toml", &base), load("overburden.toml", &with));
    let (g, sigma, lc) = (16_380.0, 120e6, 1000.0);
    let share = |y: f64| {
        let (lo, hi) = ((y - 0.5 * lc).max(0.0), (y + 0.5 * lc).min(20_000.0));
        let n = 10_000;
        (0..n).map(|i| (g * (lo + (i as f64 + 0.5) * (hi - lo) / n as f64) / sigma).min(1.0)).sum::<f64>() / n as f64
    };
    let (fp, fd) = (plain.scene.fault.as_ref().unwrap(), deep.scene.fault.as_ref().unwrap());
    let (mp, md) =
        (stickslip_solver::Model::new(plain.scene.clone()), stickslip_solver::Model::new(deep.scene.clone()));
    let lattice = md.lattice();
    let nodes = lattice.contact_nodes();
    for seed in [1, 2] {
        let (lp, ld) = (mp.fault_loads(seed).unwrap().unwrap(), md.fault_loads(seed).unwrap().unwrap());
        for (c, &id) in nodes.iter().enumerate() {
            let s = share(lattice.position(id)[1]);
            assert!((fd.depth_scale[c] - s).abs() < 1e-7, "node {c}: share {} against {s}", fd.depth_scale[c]);
            assert!((fd.normal_pa[c] - s * fp.normal_pa[c]).abs() < 1e-7 * sigma, "node {c}: normal");
            assert!((ld.normal_n[c] - s * lp.normal_n[c]).abs() <= 1e-7 * lp.normal_n[c], "node {c}: normal force");
            // The random field and the nucleation square scale with the node's share too.
            let (a, b) = (ld.shear_n[c][0], lp.shear_n[c][0]);
            assert!((a - s * b).abs() <= 1e-7 * b.abs(), "seed {seed} node {c}: shear {a} against {s}·{b}");
        }
    }
    // The surface row carries the tractions of depth Lc/4; below d* = 7326 m, all of them.
    assert!((fd.normal_pa[0] - g * 250.0).abs() < 1e-6);
    assert_eq!(fd.normal_pa[nodes.len() - 1], sigma);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A set for an ASCE 7-16 target of fewer than the 11 ground motions its §16.2.2 asks for runs,
/// with a warning that quotes the rule; 11 gives none.
#[test]
fn an_asce7_set_of_fewer_than_eleven_records_is_warned_of_with_the_rule() {
    let dir = std::env::temp_dir().join(format!("stickslip-asce7-count-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(repo_path("pipelines/scenario-m6.toml")).unwrap();
    assert!(text.contains("target = \"asce7\"") && text.contains("count = 11\n"), "scenario-m6's set changed");
    std::fs::write(dir.join("p.toml"), text.replace("count = 11\n", "count = 7\n")).unwrap();
    let p = Pipeline::load(&dir.join("p.toml")).unwrap();
    let w = p.warnings.iter().find(|w| w.field == "set.count").unwrap_or_else(|| panic!("{:?}", p.warnings));
    assert_eq!(w.value, "7");
    assert!(w.why.contains("ASCE 7-16 §16.2.2 asks for at least 11 ground motions"), "{}", w.why);
    let shipped = Pipeline::load(&repo_path("pipelines/scenario-m6.toml")).unwrap();
    assert!(!shipped.warnings.iter().any(|w| w.field == "set.count"), "{:?}", shipped.warnings);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_rate_and_state_patch_gives_its_nodes_its_own_coefficients_and_steady_start() {
    // A velocity-strengthening patch (b < a) with its own L in a velocity-weakening background,
    // both starting at steady state at 1 nm/s: the patch's θ₀ follows its own L.
    use stickslip_solver::laws::{Law, NodeFriction, RateState};
    let text = r#"
version = 1
[friction]
law = "rate_state_slip"
[friction.rate_state]
a = 0.010
b = 0.015
dc_m = 0.008
v0_m_s = 1e-6
f0 = 0.6
initial_slip_rate_m_s = 1e-9
[[friction.patches]]
shape = "rectangle"
x_m = [0.0, 0.45]
[friction.patches.rate_state]
b = 0.005
dc_m = 0.02
"#;
    let p = Pipeline::from_toml(text, "patch").unwrap();
    let scene = &p.scene;
    let lattice = scene.lattice();
    let (mut inside, mut outside) = (0, 0);
    for (c, &id) in lattice.contact_nodes().iter().enumerate() {
        let NodeFriction::RateState(n) = scene.friction.base(c) else { panic!("node {c} is not under rate and state") };
        let theta0 = RateState::initial_state(&n, 0.0, 0.0);
        if lattice.position(id)[0] <= 0.45 {
            inside += 1;
            assert_eq!((n.a, n.b, n.dc_m, n.f0), (0.010, 0.005, 0.02, 0.6));
            assert!((theta0 - 0.02 / 1e-9).abs() < 1e-3, "{theta0}");
            assert_eq!(RateState::critical_stiffness(&n, 1.0), 0.0, "velocity strengthening");
        } else {
            outside += 1;
            assert_eq!((n.a, n.b, n.dc_m), (0.010, 0.015, 0.008));
            assert!((theta0 - 0.008 / 1e-9).abs() < 1e-3, "{theta0}");
        }
    }
    assert!(inside > 0 && outside > 0, "{inside} {outside}");
}

/// `[friction.rate_state_grid]` gives each base node the a, b, L and f₀ of its row, keeps V₀ and
/// the start of `[friction.rate_state]`, and is refused under another law, with a missing row or
/// a ≤ 0 (naming the file's row).
#[test]
fn a_rate_state_grid_gives_each_base_node_its_rows_coefficients() {
    use stickslip_solver::laws::NodeFriction;
    let text = std::fs::read_to_string(repo_path("pipelines/paper-rate-state.toml")).unwrap();
    let dir = std::env::temp_dir().join(format!("stickslip-rs-grid-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // The paper block's 11 × 2 base nodes, every 0.1 m; each row's coefficients its own.
    let coefficients = |i: usize, j: usize| {
        let k = (i + 11 * j) as f64;
        [0.08 + 1e-3 * k, 0.15 - 5e-4 * k, 1e-8 * (1.0 + 0.1 * k), 0.9 + 0.01 * k]
    };
    let rows = |skip: Option<usize>, a: Option<f64>| {
        let mut csv = String::from("# a test grid\nx_m, y_m, a, b, dc_m, f0\n");
        for j in (0..2).rev() {
            for i in 0..11 {
                if Some(i + 11 * j) == skip {
                    continue;
                }
                let [ca, b, l, f0] = coefficients(i, j);
                let ca = if i == 3 && j == 1 { a.unwrap_or(ca) } else { ca };
                csv += &format!("{}, {}, {ca}, {b}, {l}, {f0}\n", 0.1 * i as f64, 0.1 * j as f64);
            }
        }
        csv
    };
    let load = |name: &str, text: &str, csv: &str| {
        std::fs::write(dir.join(format!("{name}.csv")), csv).unwrap();
        let path = dir.join(format!("{name}.toml"));
        let grid = format!("\n[friction.rate_state_grid]\nfile = \"{name}.csv\"\n");
        std::fs::write(&path, text.to_string() + &grid).unwrap();
        Pipeline::load(&path)
    };
    let p = load("grid", &text, &rows(None, None)).unwrap();
    let lattice = p.scene.lattice();
    for (c, &id) in lattice.contact_nodes().iter().enumerate() {
        let [x, y, _] = lattice.position(id);
        let (i, j) = ((x / 0.1).round() as usize, (y / 0.1).round() as usize);
        let NodeFriction::RateState(n) = p.scene.friction.base(c) else { panic!("node {c}: rate and state") };
        let [a, b, l, f0] = coefficients(i, j);
        assert_eq!((n.a, n.b, n.dc_m, n.f0), (a, b, l, f0), "node {c} at ({x}, {y})");
        assert_eq!(n.v0_m_s, 1e-6, "node {c}: V₀ from [friction.rate_state]");
    }
    // An output folder keeps a copy of the grid, and its pipeline reads that copy.
    let copy = p.output_copy().unwrap();
    let at = "inputs/friction.rate_state_grid.file/grid.csv";
    assert_eq!(copy.inputs.iter().map(|(path, _)| path.as_str()).collect::<Vec<_>>(), [at]);
    assert!(copy.text.contains(&format!("file = \"{at}\"")), "{}", copy.text);
    // The grid's rows are hashed: another coefficient, another hash.
    let other = load("other", &text, &rows(None, Some(0.2))).unwrap();
    assert_ne!(p.hash, other.hash);
    let refused = |name: &str, text: &str, csv: &str, field: &str, why: &str| {
        let e = load(name, text, csv).unwrap_err();
        let e = format!("{}", std::error::Error::source(&e).unwrap());
        assert!(e.contains(field) && e.contains(why), "{name}: {e}");
    };
    let slip_weakening = text.replace("law = \"rate_state_aging\"", "law = \"slip_weakening\"");
    let slip_weakening = slip_weakening[..slip_weakening.find("[friction.rate_state]").unwrap()].to_string()
        + &slip_weakening[slip_weakening.find("[time]").unwrap()..];
    refused("sw", &slip_weakening, &rows(None, None), "friction.rate_state_grid", "left out with law");
    refused("missing", &text, &rows(Some(5), None), "friction.rate_state_grid.file", "one row per base node");
    refused("negative", &text, &rows(None, Some(-0.01)), "friction.rate_state_grid.file row", "a");
    let _ = std::fs::remove_dir_all(&dir);
}
