//! The report end to end: every figure listed in the page exists, decodes as a PNG of the
//! expected size and is not blank; every link of the page resolves to a file; figures without
//! data are skipped, not drawn empty.

use std::path::Path;
use std::sync::atomic::AtomicBool;

use stickslip_config::Pipeline;
use stickslip_ensemble::{EnsembleOptions, run_ensemble};
use stickslip_report::{ReportSummary, write_report};
use stickslip_support::{repo_path, scratch_dir};

/// Runs the pipeline `text` into `dir/out` and writes its report.
fn run(dir: &Path, text: &str) -> ReportSummary {
    std::fs::write(dir.join("p.toml"), text).unwrap();
    let p = Pipeline::load(&dir.join("p.toml")).unwrap();
    let options = EnsembleOptions {
        checkpoint_every_s: None,
        out: dir.join("out"),
        threads: 2,
        seeds: p.seeds.clone(),
        fresh: false,
        finish: true,
    };
    run_ensemble(&p, &options, &|_, _| {}, &AtomicBool::new(false)).unwrap();
    write_report(&dir.join("out"), &p).unwrap()
}

/// (width, height, variance of the grey level) of a PNG.
fn png_stats(path: &Path) -> (u32, u32, f64) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let grey: Vec<f64> = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|p| p.iter().take(3).map(|&v| v as f64).sum::<f64>() / 3.0)
        .collect();
    let mean = grey.iter().sum::<f64>() / grey.len() as f64;
    let var = grey.iter().map(|g| (g - mean).powi(2)).sum::<f64>() / grey.len() as f64;
    (info.width, info.height, var)
}

/// Every `src="…"` and `href="…"` of the page.
fn links(html: &str) -> Vec<String> {
    let mut out = Vec::new();
    for key in ["src=\"", "href=\""] {
        let mut rest = html;
        while let Some(i) = rest.find(key) {
            rest = &rest[i + key.len()..];
            let end = rest.find('"').unwrap();
            out.push(rest[..end].to_string());
            rest = &rest[end..];
        }
    }
    out
}

#[test]
fn paper_report_has_every_figure_drawn_and_every_link_resolving() {
    let dir = scratch_dir("report-paper");
    let text = std::fs::read_to_string(repo_path("pipelines/paper.toml"))
        .unwrap()
        .replace("list = [123, 200, 7]", "list = [123, 200]")
        .replace("duration_s = 0.32 ", "duration_s = 0.24 ");
    let report = run(&dir, &text);
    let out = dir.join("out");
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(report.figures.len() >= 12, "{} figures, skipped {:?}", report.figures.len(), report.skipped);
    for f in &report.figures {
        assert!(html.contains(&format!("src=\"figures/{}\"", f.file)), "{} not in the page", f.file);
        let (w, h, var) = png_stats(&out.join("figures").join(&f.file));
        assert_eq!((w, h), (1200, 700), "{}", f.file);
        assert!(var > 100.0, "{} looks blank (grey variance {var})", f.file);
        assert!(f.dropped.is_empty(), "{}: labels left out for want of room: {:?}", f.file, f.dropped);
    }
    let all = links(&html);
    assert!(all.len() > 20);
    for l in &all {
        assert!(out.join(l).is_file(), "link {l} does not resolve to a file");
    }
    for title in [
        "Shear stress",
        "Normal stress",
        "Response spectra",
        "Peak acceleration against distance",
        "Energy terms",
        "Main shocks across seeds",
    ] {
        assert!(html.contains(title), "page lacks {title}");
    }
    assert!(!html.contains("http://") && !html.contains("https://"), "the page must not load network resources");
    // The paper's pipelines name the paper's figures.
    let shear = report.figures.iter().find(|f| f.file == "shear_stress.png").unwrap();
    assert!(shear.headings.iter().any(|h| h.contains("(paper Fig. 3)")), "{:?}", shear.headings);
}

#[test]
fn a_users_scene_with_two_control_nodes_draws_both_and_cites_no_paper_figure() {
    let dir = scratch_dir("report-two-nodes");
    let paper = std::fs::read_to_string(repo_path("pipelines/paper.toml")).unwrap();
    let text = paper
        .replace("name = \"paper\"", "name = \"two-nodes\"")
        .replace("list = [123, 200, 7]", "list = [123]")
        .replace("duration_s = 0.32 ", "duration_s = 0.24 ")
        .replace("nodes = [36]", "nodes = [36, 40]")
        .replace("paper_figures = true", "paper_figures = false");
    assert_eq!(text.matches("nodes = [36, 40]").count(), 2, "the control and accelerogram nodes of paper.toml changed");
    assert!(text.contains("paper_figures = false"));
    let report = run(&dir, &text);
    for f in &report.figures {
        for h in &f.headings {
            assert!(!h.contains("paper Fig."), "{}: title {h:?} cites the paper in a user's scene", f.file);
        }
        assert!(!f.caption.contains("paper Fig."), "{}: caption cites the paper", f.file);
    }
    let drawn: Vec<&str> = report.figures.iter().map(|f| f.file.as_str()).collect();
    for file in [
        "acceleration_s2.png",
        "acceleration_run.png",
        "response_spectra_z.png",
        "response_spectra_x.png",
        "fourier.png",
    ] {
        let f = report.figures.iter().find(|f| f.file == file).unwrap_or_else(|| panic!("{file} not drawn: {drawn:?}"));
        for node in ["node 36 ", "node 40 "] {
            assert!(f.panels.iter().any(|p| p.contains(node)), "{file}: no panel of {node}: {:?}", f.panels);
            assert!(f.caption.contains(node), "{file}: the caption does not name {node}");
        }
    }
}

#[test]
fn figures_without_data_are_skipped_not_drawn_empty() {
    let dir = scratch_dir("report-bare");
    // No spectra, no energy, no control nodes: those figures are skipped and listed as such.
    let report = run(&dir, "version = 1\nname = \"bare\"\n[seeds]\nlist = [1]\n[shear]\nduration_s = 0.1\n");
    let skipped: Vec<&str> = report.skipped.iter().map(|(f, _)| f.as_str()).collect();
    for f in [
        "response_spectra_z.png",
        "fourier.png",
        "attenuation.png",
        "energy.png",
        "acceleration_s2.png",
        "records.png",
        "record_set.png",
    ] {
        assert!(skipped.contains(&f), "{f} should be skipped: {skipped:?}");
        assert!(!dir.join("out/figures").join(f).exists(), "{f} drawn without data");
    }
    let html = std::fs::read_to_string(dir.join("out/index.html")).unwrap();
    assert!(html.contains("Not drawn (their data is absent from this run)"));
    assert!(dir.join("out/figures/shear_stress.png").exists());
}

/// A copy of `paper.toml` made into one's own scene keeps `paper_figures = true`: on another block
/// the paper's figure numbers and reference values would mislead, so they are left out and the
/// page says why.
#[test]
fn a_copy_of_paper_toml_on_another_block_cites_no_paper_figure() {
    let dir = scratch_dir("report-copy");
    let text = std::fs::read_to_string(repo_path("pipelines/paper.toml"))
        .unwrap()
        .replace("name = \"paper\"", "name = \"my-scene\"")
        .replace("list = [123, 200, 7]", "list = [1]")
        .replace("nx = 10", "nx = 12")
        .replace("duration_s = 0.32 ", "duration_s = 0.12 ");
    assert!(text.contains("paper_figures = true") && text.contains("nx = 12"));
    let report = run(&dir, &text);
    for f in &report.figures {
        for h in &f.headings {
            assert!(!h.contains("paper Fig."), "{}: {h:?} cites the paper on the user's block", f.file);
        }
        for reference in ["paper Fig.", "M = 6.77", "25.8 ms", "the paper reports"] {
            assert!(!f.caption.contains(reference), "{}: {}", f.file, f.caption);
        }
    }
    let html = std::fs::read_to_string(dir.join("out/index.html")).unwrap();
    assert!(!html.contains("M = 6.77") && !html.contains("Paper (seed 200, S2)"), "the paper's reference on the page");
    assert!(html.contains("not the paper's scene (block 12×1×5 modules"), "the page does not say why");
}

#[test]
fn the_page_renders_in_headless_chromium() {
    if std::env::var_os("STICKSLIP_NO_BROWSER").is_some() {
        println!("STICKSLIP_NO_BROWSER set: browser check skipped");
        return;
    }
    let have = std::process::Command::new("chromium").arg("--version").output().is_ok_and(|o| o.status.success());
    assert!(
        have,
        "chromium is not installed: .ci/run installs it (apt-get install chromium); set STICKSLIP_NO_BROWSER=1 to skip \
         this check on a machine without it"
    );
    let dir = scratch_dir("report-browser");
    let text = std::fs::read_to_string(repo_path("pipelines/paper.toml"))
        .unwrap()
        .replace("list = [123, 200, 7]", "list = [123]")
        .replace("duration_s = 0.32 ", "duration_s = 0.12 ");
    run(&dir, &text);
    let shot = dir.join("shot.png");
    let out = std::process::Command::new(repo_path("scripts/render-report.sh"))
        .arg(dir.join("out"))
        .arg(&shot)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let (w, _, var) = png_stats(&shot);
    assert_eq!(w, 1300);
    assert!(var > 100.0, "blank screenshot");
}

/// A fault scene (`[fault]`) is at its own scale: its page leads with the source of its rupture
/// (the `source` table's numbers) and its stations, and leaves out what measures a block by the
/// paper's similarity scaling — the main-shock table with model-scale magnitudes, the magnitude,
/// catalogue and scaling figures, the self-weight and driver lines.
#[test]
fn a_fault_scenes_page_leads_with_its_source_and_leaves_the_similarity_out() {
    let dir = scratch_dir("report-fault");
    let text = std::fs::read_to_string(repo_path("pipelines/tpv5-500m.toml")).unwrap();
    let report = run(&dir, &text);
    let out = dir.join("out");
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    let table = |name: &str| stickslip_support::read_table(&out.join("tables").join(format!("{name}.parquet")));
    let source = table("source");
    let get = |c: &str| source.column(c).unwrap().f64().unwrap().get(0).unwrap();
    let (mw, drop, area) = (get("mw"), get("stress_drop_pa"), get("ruptured_area_m2"));
    assert!((6.95..7.2).contains(&mw), "TPV5 is an Mw ≈ 7 rupture: {mw}");
    // The page's numbers are the table's.
    for cell in [
        format!("<td>{mw:.2}</td>"),
        format!("<td>{:.3e}</td>", get("m0_n_m")),
        format!("<td>{:.2}</td>", drop / 1e6),
        format!("<td>{:.1}</td>", area / 1e6),
        format!("<td>{:.2}</td>", get("rupture_duration_s")),
        format!("<td>{:.2}</td>", get("peak_slip_rate_m_s")),
    ] {
        assert!(html.contains(&cell), "the source table's {cell} is not on the page");
    }
    // The source and the stations come first, the rupture figure with the source.
    let at = |s: &str| html.find(s).unwrap_or_else(|| panic!("the page lacks {s}"));
    assert!(at("<h2>Source</h2>") < at("src=\"figures/rupture_time.png\""));
    assert!(at("src=\"figures/rupture_time.png\"") < at("<h2>Stations</h2>"));
    assert!(at("<h2>Stations</h2>") < at("<h2>Parameters</h2>"));
    assert_eq!(html.matches("src=\"figures/rupture_time.png\"").count(), 1, "the rupture figure shown twice");
    // The nearest station's distance and peaks, from the stations table.
    let st = table("stations");
    let names: Vec<String> =
        st.column("station").unwrap().str().unwrap().iter().map(|s| s.unwrap().to_string()).collect();
    let col =
        |c: &str| st.column(c).unwrap().f64().unwrap().iter().map(|v| v.unwrap_or(f64::NAN)).collect::<Vec<f64>>();
    let (r_rup, pga, pgv) = (col("r_rup_m"), col("pga_m_s2"), col("pgv_m_s"));
    let near = (0..names.len()).min_by(|&a, &b| r_rup[a].total_cmp(&r_rup[b])).unwrap();
    let row = format!("<tr><th class=\"l\">{}</th><td>{:.1}</td>", names[near], r_rup[near] / 1e3);
    assert!(html.contains(&row), "no row {row}");
    assert!(
        html.contains(&format!("<td>{:.3}</td><td>{:.3}</td>", pga[near], pgv[near])),
        "PGA, PGV of {}",
        names[near]
    );
    assert!(at(&row) < at("<h2>Parameters</h2>"));
    // What does not apply to a fault.
    for absent in [
        "Main shocks across seeds",
        "M (paper's M0)",
        "prototype duration",
        ">self-weight stage<",
        ">shear stage<",
        "driver LDEM",
        "<th class=\"l\">similarity</th>",
        "What the base did",
    ] {
        assert!(!html.contains(absent), "a fault's page shows {absent:?}");
    }
    for (file, _) in stickslip_report::figures::LEFT_OUT_ON_A_FAULT {
        assert!(!report.figures.iter().any(|f| f.file == file), "{file} drawn on a fault's page");
        assert!(!out.join("figures").join(file).exists(), "{file} written");
        assert!(report.left_out.iter().any(|(f, _)| f == file), "{file} not said to be left out");
        assert!(!report.skipped.iter().any(|(f, _)| f == file), "{file} said to lack data");
    }
    assert!(html.contains("Left out on a fault scene"));
    // Slip in metres, the acceleration cut to its motion and said to be cut off by the run's end.
    let slip = report.figures.iter().find(|f| f.file == "mean_slip.png").unwrap();
    assert!(slip.caption.contains("twice its face's displacement"), "{}", slip.caption);
    let acc = report.figures.iter().find(|f| f.file == "acceleration_run.png").unwrap();
    assert!(acc.caption.contains("to the end of the run at 12.0 s"), "{}", acc.caption);
    assert!(acc.caption.contains("still shakes"), "{}", acc.caption);
    assert!(acc.panels.iter().all(|p| p.ends_with(" km")), "{:?}", acc.panels);
    for f in &report.figures {
        assert!(f.dropped.is_empty(), "{}: labels left out: {:?}", f.file, f.dropped);
    }
}
