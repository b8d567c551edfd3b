//! The report page: plain HTML, no network resources, opens from disk.

// The page is built from literal HTML fragments that carry their own line ends.
#![allow(clippy::write_with_newline)]

use std::fmt::Write as _;

use stickslip_seismo::catalogue::compact;
use stickslip_solver::laws::describe;
use stickslip_store::schema::{col, seed_tables};
use stickslip_store::tables::runs::RunStatus;

use crate::error::ReportError;
use crate::fault_page;
use crate::input::ReportInput;
use crate::markup::{esc, figure_html};
use crate::summary::Figure;

/// `mean ± std` of `quantity` in `group` of the summary, scaled, or "–".
fn stat(d: &ReportInput, group: &str, quantity: &str, scale: f64, digits: usize) -> String {
    let Some(s) = &d.summary else { return "–".into() };
    match s.find(group, quantity) {
        Some(i) if s.std[i].is_finite() => {
            format!("{:.*} ± {:.*}", digits, s.mean[i] * scale, digits, s.std[i] * scale)
        }
        Some(i) => format!("{:.*}", digits, s.mean[i] * scale),
        None => "–".into(),
    }
}

fn count(d: &ReportInput, group: &str) -> String {
    let Some(s) = &d.summary else { return "0".into() };
    s.find(group, col::STRESS_DROP_PA).map_or("0".into(), |i| format!("{}", s.count[i]))
}

/// Files under `dir` with extension `ext`, sorted, relative to `out`; per-seed parts and record
/// files only of the seeds of this run's `runs` table (a file of another seed left in the folder
/// is not this run's, and is not linked).
fn files(d: &ReportInput, dir: &str, ext: &str) -> Vec<String> {
    let ran: Option<std::collections::HashSet<u64>> = d.runs.as_ref().map(|r| r.seed.iter().copied().collect());
    let of_this_run = |name: &str| {
        let Some(ran) = &ran else { return true };
        let part = name.strip_prefix("seed-").and_then(|r| r.split('.').next()).and_then(|s| s.parse::<u64>().ok());
        let record = name
            .strip_prefix(&format!("{}_seed", d.pipeline.name))
            .and_then(|r| r.split('_').next())
            .and_then(|s| s.parse::<u64>().ok());
        match (dir, part, record) {
            ("records", _, Some(seed)) => ran.contains(&seed),
            ("records", _, None) => false,
            (_, Some(seed), _) if dir.starts_with("tables/") => ran.contains(&seed),
            _ => true,
        }
    };
    let mut v: Vec<String> = std::fs::read_dir(d.folder.root().join(dir))
        .map(|r| {
            r.flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .filter(|n| !n.starts_with('.') && n.ends_with(ext) && of_this_run(n))
                .map(|n| format!("{dir}/{n}"))
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

/// The page. A fault scene's leads with its source and stations and leaves out what measures a
/// block by the paper's similarity scaling (`left_out`).
pub(crate) fn page(
    d: &ReportInput,
    figures: &[Figure],
    skipped: &[(String, String)],
    left_out: &[(String, String)],
) -> Result<String, ReportError> {
    let fault = d.pipeline.scene.is_fault();
    let mut h = String::new();
    let w = &mut h;
    head(w, d);
    runs_section(w, d, fault);
    warnings_section(w, d);
    if fault {
        fault_page::source_section(w, d, figures);
        fault_page::stations_section(w, d);
    }
    parameters_section(w, d, fault);
    if !fault {
        main_shocks(w, d);
    }
    figures_section(w, figures, skipped, left_out, fault);
    tables_and_files(w, d, fault);
    Ok(h)
}

/// The document's head and style, the title and the pipeline's description.
fn head(w: &mut String, d: &ReportInput) {
    let p = d.pipeline;
    let _ = write!(
        w,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>stickslip: {name}</title>\n<style>\n\
         body {{ font-family: 'DejaVu Sans', Arial, sans-serif; margin: 2em auto; max-width: 1250px; color: #222; line-height: 1.45; }}\n\
         table {{ border-collapse: collapse; margin: 0.5em 0 1.5em; }}\n\
         th, td {{ border: 1px solid #bbb; padding: 0.25em 0.6em; text-align: right; }}\n\
         th {{ background: #eef; }} td.l, th.l {{ text-align: left; }}\n\
         figure {{ margin: 1.5em 0; }} figure img {{ width: 100%; max-width: 1200px; border: 1px solid #ddd; }}\n\
         figcaption {{ font-size: 0.95em; color: #333; max-width: 1200px; }}\n\
         pre {{ background: #f6f6f6; padding: 1em; overflow-x: auto; font-size: 0.85em; }}\n\
         code {{ background: #f2f2f2; padding: 0 0.2em; }}\n</style>\n</head>\n<body>\n",
        name = esc(&p.name)
    );
    let _ = write!(w, "<h1>stickslip report: {}</h1>\n<p>{}</p>\n", esc(&p.name), esc(&p.description));
}

/// The seeds run (ok and failed), where the tables are, and for a block what its base did.
fn runs_section(w: &mut String, d: &ReportInput, fault: bool) {
    let p = d.pipeline;
    let ok_failed = match &d.runs {
        Some(r) => {
            let ok = r.status.iter().filter(|x| **x == RunStatus::Ok).count();
            (ok, r.status.len() - ok)
        }
        None => (0, 0),
    };
    let _ = write!(
        w,
        "<p>Pipeline hash <code>{}</code>; {} seeds run ({} ok, {} failed). Tables in <code>tables/</code>, figures in \
         <code>figures/</code>, the pipeline file as run: <a href=\"pipeline.toml\">pipeline.toml</a>.</p>\n",
        esc(&p.hash),
        ok_failed.0 + ok_failed.1,
        ok_failed.0,
        ok_failed.1
    );
    // A fault's rupture is said by its source section.
    if let Some(r) = d.runs.as_ref().filter(|_| !fault) {
        let regimes: Vec<(&str, &str)> = vec![
            ("stick_slip", "stick-slip"),
            ("stick_slip_then_sliding", "stick-slip, then stable sliding to the end"),
            ("stable_sliding", "stable sliding (no earthquake: nothing catalogued)"),
            ("no_slip", "no slip (the base held, or the block tipped)"),
        ];
        let parts: Vec<String> = regimes
            .iter()
            .filter_map(|(key, words)| {
                let n = r.slip_regime.iter().filter(|g| g == key).count();
                (n > 0).then(|| format!("{words} in {n}"))
            })
            .collect();
        if !parts.is_empty() {
            let _ = write!(
                w,
                "<p>What the base did, seed by seed (<code>runs.slip_regime</code>; docs/model.md §7): {}.</p>\n",
                esc(&parts.join("; "))
            );
        }
    }
}

/// The pipeline's warnings and the report's seeds that did not run, if any.
fn warnings_section(w: &mut String, d: &ReportInput) {
    let p = d.pipeline;
    let mut warnings: Vec<String> = p.warnings.iter().map(|w| w.to_string()).collect();
    if !d.not_drawn.is_empty() {
        warnings.push(format!(
            "report.seeds = {:?}: seeds {} did not run here (or failed); the figures draw seeds {:?} instead",
            p.report.seeds,
            d.not_drawn.iter().map(|s| s.to_string()).collect::<Vec<_>>().join(", "),
            d.seeds
        ));
    }
    if !warnings.is_empty() {
        let _ = write!(w, "<h2>Warnings</h2>\n<p>Values this pipeline was run with that could mislead:</p>\n<ul>\n");
        for text in &warnings {
            let _ = writeln!(w, "<li>{}</li>", esc(text));
        }
        let _ = write!(w, "</ul>\n");
    }
}

/// The table of parameters: the block, material, friction and time step, then a fault's or a
/// block's own rows.
fn parameters_section(w: &mut String, d: &ReportInput, fault: bool) {
    let s = &d.pipeline.scene;
    let lattice = s.lattice();
    let e = lattice.extent();
    let _ = write!(w, "<h2>Parameters</h2>\n<table>\n");
    let mut rows: Vec<(&str, String)> = vec![
        (
            "block",
            format!(
                "{}×{}×{} modules of Lc = {} m ({} × {} × {} m), {} nodes, {} bars",
                s.dims.nx,
                s.dims.ny,
                s.dims.nz,
                s.lc_m,
                compact(e[0]),
                compact(e[1]),
                compact(e[2]),
                lattice.node_count(),
                lattice.bar_count()
            ),
        ),
        (
            "material",
            format!(
                "E = {:e} Pa (Weibull CV {}), ρ = {} kg/m³, ν = {}",
                s.young_pa, s.young_cv, s.density_kg_m3, s.poisson
            ),
        ),
        (
            "friction",
            format!(
                "{}, CV of μ = {}",
                describe(&s.friction.law.node(1.0).coefficients(), |_, c| c.value.to_string()),
                s.friction.mu_cv
            ),
        ),
        (
            "time step",
            match s.time_step {
                stickslip_solver::scene::TimeStep::Fraction(f) => format!(
                    "{f} of the critical step of each seed's lattice{}",
                    d.mean_dt_s.map(|dt| format!(" (Δt = {dt:.4e} s on average)")).unwrap_or_default()
                ),
                stickslip_solver::scene::TimeStep::Fixed(dt) => format!("Δt = {dt:e} s"),
            },
        ),
    ];
    if fault {
        rows = fault_page::parameters(d, rows);
    } else {
        rows.extend(block_stages(d));
    }
    for (k, v) in rows {
        let _ = writeln!(w, "<tr><th class=\"l\">{}</th><td class=\"l\">{}</td></tr>", esc(k), esc(&v));
    }
    let _ = write!(w, "</table>\n");
}

/// The figures, those not drawn for lack of data and those left out on a fault scene.
fn figures_section(
    w: &mut String,
    figures: &[Figure],
    skipped: &[(String, String)],
    left_out: &[(String, String)],
    fault: bool,
) {
    let _ = write!(w, "<h2>Figures</h2>\n");
    for f in figures.iter().filter(|f| !(fault && f.file == fault_page::RUPTURE_FIGURE)) {
        let _ = write!(w, "{}", figure_html(f));
    }
    if !skipped.is_empty() {
        let _ = write!(w, "<p>Not drawn (their data is absent from this run):</p>\n<ul>\n");
        for (f, why) in skipped {
            let _ = writeln!(w, "<li><code>{}</code>: {}</li>", esc(f), esc(why));
        }
        let _ = write!(w, "</ul>\n");
    }
    if !left_out.is_empty() {
        let _ = write!(
            w,
            "<p>Left out on a fault scene: these figures measure a block's events by the paper's similarity scaling \
             (magnitudes at a prototype scale λ, a catalogue's statistics), while a fault is at its own scale and its \
             rupture is measured from its slip (the source above):</p>\n<ul>\n"
        );
        for (f, why) in left_out {
            let _ = writeln!(w, "<li><code>{}</code>: {}</li>", esc(f), esc(why));
        }
        let _ = write!(w, "</ul>\n");
    }
}

/// The rows of a block's loading stages: self-weight (when there is gravity), the shear stage
/// (its drivers or plate), the paper's similarity scaling.
fn block_stages(d: &ReportInput) -> Vec<(&'static str, String)> {
    let p = d.pipeline;
    let s = &p.scene;
    let e = s.lattice().extent();
    let sw = &s.self_weight;
    let loading = if !s.drivers().is_empty() {
        format!(", driver LDEM {}", s.drivers().iter().map(|n| n.ldem().to_string()).collect::<Vec<_>>().join(", "))
    } else if let Some(plate) = s.plate() {
        format!(", a loading plate on face {} through springs", plate.face.name())
    } else {
        String::new()
    };
    vec![
        (
            "self-weight stage",
            if sw.gravity_m_s2 == 0.0 {
                "none (g = 0)".to_string()
            } else {
                format!(
                    "g = {} m/s², D = {} 1/s, settled at {:e}",
                    sw.gravity_m_s2, sw.damping_per_s, sw.settle_tolerance
                )
            },
        ),
        (
            "shear stage",
            format!(
                "D = {} 1/s, u̇f = {} m/s, t0 = {} s, {} s{loading}",
                s.shear.damping_per_s, s.shear.velocity_m_s, s.shear.rise_time_s, s.shear.duration_s,
            ),
        ),
        (
            "similarity",
            format!(
                "L_p = {} m (λ = {}), u̇_p = {:e} m/s",
                p.analysis.similarity.prototype_length_m,
                compact(p.analysis.similarity.prototype_length_m / e[0]),
                p.analysis.similarity.prototype_rate_m_s
            ),
        ),
    ]
}

/// The table of main shocks across seeds (a block's events, at model and prototype scale).
fn main_shocks(w: &mut String, d: &ReportInput) {
    let reference = if d.paper {
        " Paper (seed 200, S2): stress drop 7.6 kPa, duration 2.1 ms, S1→S2 recurrence 25.8 ms, M = 6.77; at \
         prototype scale 21 s and 2.83 years."
            .to_string()
    } else {
        d.paper_note.as_ref().map(|n| format!(" {}.", esc(n))).unwrap_or_default()
    };
    let _ = write!(
        w,
        "<h2>Main shocks across seeds</h2>\n<p>Mean ± standard deviation across seeds (model scale unless said).\
         {reference}</p>\n<table>\n<tr><th class=\"l\">shock</th><th>events</th>\
         <th>stress drop (kPa)</th><th>duration (ms)</th><th>stress falls in (ms)</th><th>recurrence (ms)</th>\
         <th>M (paper's M0)</th><th>Mw (consistent M0)</th><th>prototype duration (s)</th>\
         <th>prototype recurrence (years)</th></tr>\n"
    );
    let mut groups: Vec<String> = match &d.summary {
        Some(sm) => sm.group.iter().filter(|g| g.starts_with('S')).cloned().collect(),
        None => vec![],
    };
    groups.sort_by_key(|g| g[1..].parse::<u32>().unwrap_or(u32::MAX));
    groups.dedup();
    groups.push("main".into());
    groups.push("all".into());
    for g in &groups {
        let _ = writeln!(
            w,
            "<tr><th class=\"l\">{}</th><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            esc(g),
            count(d, g),
            stat(d, g, col::STRESS_DROP_PA, 1e-3, 2),
            stat(d, g, col::DURATION_S, 1e3, 1),
            stat(d, g, col::DROP_TIME_S, 1e3, 1),
            stat(d, g, col::RECURRENCE_S, 1e3, 1),
            stat(d, g, col::M_RIERA_PAPER_INTERPLATE, 1.0, 2),
            stat(d, g, col::MW_CONSISTENT, 1.0, 2),
            stat(d, g, col::PROTOTYPE_DURATION_S, 1.0, 1),
            stat(d, g, col::PROTOTYPE_RECURRENCE_YEARS, 1.0, 2),
        );
    }
    let _ = write!(w, "</table>\n");
}

/// The tables, record files, the pipeline file and the conventions.
fn tables_and_files(w: &mut String, d: &ReportInput, fault: bool) {
    let p = d.pipeline;
    let _ = write!(
        w,
        "<h2>Tables</h2>\n<p>Parquet files; every per-seed table also reads lazily over all seeds with a glob such as <code>tables/series/*.parquet</code>.</p>\n<ul>\n"
    );
    for f in files(d, "tables", ".parquet") {
        let _ = writeln!(w, "<li><a href=\"{0}\">{0}</a></li>", esc(&f));
    }
    let _ = write!(w, "</ul>\n<p>Per-seed parts:</p>\n<ul>\n");
    for table in seed_tables().map(|t| t.name) {
        let parts = files(d, &format!("tables/{table}"), ".parquet");
        match parts.len() {
            0 => {}
            n if n <= 12 => {
                let links: Vec<String> = parts.iter().map(|f| format!("<a href=\"{0}\">{0}</a>", esc(f))).collect();
                let _ = writeln!(w, "<li><code>{table}</code>: {}</li>", links.join(", "));
            }
            n => {
                let _ = writeln!(
                    w,
                    "<li><code>{table}</code>: {n} files <code>tables/{table}/seed-*.parquet</code>, e.g. <a href=\"{0}\">{0}</a></li>",
                    esc(&parts[0])
                );
            }
        }
    }
    let _ = write!(w, "</ul>\n");
    for (dir, what) in [
        (
            "records",
            "Accelerogram records: one per event, node and component, processed (band-pass inside the usable band); named pipeline_seed_record_scale",
        ),
        ("set", "The record set matched to the design spectrum, scaled"),
    ] {
        let mut listed: Vec<String> = [".AT2", ".SAC", ".csv"].iter().flat_map(|ext| files(d, dir, ext)).collect();
        listed.sort();
        if listed.is_empty() {
            continue;
        }
        let _ = write!(
            w,
            "<h2>{what}</h2>\n<p>{} files in <code>{dir}/</code>: PEER .AT2 (g), SAC (nm/s²) or CSV (SI); model scale \
             and prototype scale (times ×λ, accelerations ÷λ).</p>\n<ul>\n",
            listed.len()
        );
        for f in listed.iter().take(60) {
            let _ = writeln!(w, "<li><a href=\"{0}\">{0}</a></li>", esc(f));
        }
        if listed.len() > 60 {
            let _ = writeln!(w, "<li>… and {} more</li>", listed.len() - 60);
        }
        let _ = write!(w, "</ul>\n");
    }
    if let Some(src) = &p.source
        && let Ok(text) = std::fs::read_to_string(src)
    {
        let _ = write!(w, "<h2>Pipeline file</h2>\n<pre>{}</pre>\n", esc(&text));
    }
    let conventions = if fault {
        "τ is the fault's shear traction; times are counted from the start of the run; a node's slip is twice \
         its face's displacement; Mw = (2/3)·(log10 M0 − 9.1) with M0 = Σ μ·A·|D| over the ruptured nodes (μ at each node's depth)"
    } else {
        "τ is positive when the base resists the push; times are counted from the start of the shear stage; \
         \"M (paper's M0)\" uses Eq. 15 as printed (Δσ·L_p·A_p·λ), Mw the consistent moment Δσ·L_p·A_p"
    };
    let _ = write!(
        w,
        "<p><small>Written by stickslip {}. Conventions: {conventions}.</small></p>\n</body>\n</html>\n",
        env!("CARGO_PKG_VERSION")
    );
}
