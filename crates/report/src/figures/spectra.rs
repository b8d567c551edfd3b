//! The spectral figures: response spectra (PSA) of each node's records across seeds at model and
//! prototype scale, the Fourier amplitude of the S2 records, and the record set chosen by `[set]`
//! against its design spectrum.

use std::path::Path;

use plotters::style::{BLACK, RGBColor};

use std::collections::BTreeMap;
use stickslip_solver::scene::Component;

use stickslip_store::io::scan_columns;
use stickslip_store::schema::col;
use stickslip_store::schema::{FOURIER, ROTD, SET, SPECTRA};
use stickslip_store::tables::set::SetTable;
use stickslip_store::tables::spectra::{Spectra, read_fourier};

use super::Outcome;
use super::common::{NodeChannel, accelerogram_nodes, drawn, nodes_short, nodes_text, seeds_text};
use crate::charts::{Band, Line, Panel, Sheet};
use crate::plot::{HEIGHT, colour};
use crate::{ReportError, ReportInput};

/// The columns of a spectra-shaped part the figures read ([`Spectra`]).
const SPECTRUM_READ: [&str; 9] = [
    col::SEED,
    col::RECORD,
    col::NODE,
    col::COMPONENT,
    col::SCALE,
    col::DAMPING,
    col::PERIOD_S,
    col::PSA_M_S2,
    col::IN_BAND,
];

pub(super) fn spectra_z(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    spectra(d, path, Component::Z)
}

pub(super) fn spectra_x(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    spectra(d, path, Component::X)
}

/// PSA at 5% (or the nearest damping), model and prototype scale, one row per node: every seed
/// thin, the mean and the 5–95% band bold.
fn spectra(d: &ReportInput, path: &Path, comp: Component) -> Result<Outcome, ReportError> {
    let (all_nodes, total) = accelerogram_nodes(d);
    let Some(stats) = &d.psa_stats else {
        return Ok(Outcome::Skipped("no spectra analysis".into()));
    };
    let cname = comp.name();
    let damping =
        stats.damping.iter().copied().min_by(|a, b| (a - 0.05).abs().total_cmp(&(b - 0.05).abs())).unwrap_or(0.05);
    let nodes: Vec<NodeChannel> = all_nodes
        .into_iter()
        .filter(|n| (0..stats.node.len()).any(|i| stats.node[i] == n.ldem && stats.component[i] == cname))
        .map(|n| NodeChannel { component: comp, ..n })
        .collect();
    if nodes.is_empty() {
        return Ok(Outcome::Skipped(format!("no {cname} spectra")));
    }
    // Every record's spectrum of this component at this damping, read once (only the columns
    // drawn) and grouped by record, in the order of the parts.
    let filter = polars::prelude::col(col::COMPONENT)
        .eq(polars::prelude::lit(cname))
        .and(polars::prelude::col(col::DAMPING).eq(polars::prelude::lit(damping)));
    let all = scan_columns(&d.folder.part_glob(&SPECTRA), &SPECTRUM_READ, Some(filter))?
        .map(|df| Spectra::read(&df))
        .transpose()?;
    // (node, seed, record) → rows, in row order.
    let mut by_record: BTreeMap<(u64, u64, &str), Vec<usize>> = BTreeMap::new();
    if let Some(sp) = &all {
        for i in 0..sp.seed.len() {
            by_record.entry((sp.node[i], sp.seed[i], sp.record[i].as_str())).or_default().push(i);
        }
    }
    let mut panels = Vec::new();
    let mut count = 0;
    for node in &nodes {
        for (scale, unit_note) in [("model", "model scale"), ("prototype", "prototype scale (λ)")] {
            let rows: Vec<usize> = (0..stats.node.len())
                .filter(|&i| {
                    stats.node[i] == node.ldem
                        && stats.component[i] == cname
                        && stats.scale[i] == scale
                        && stats.damping[i] == damping
                        && stats.in_band[i]
                })
                .collect();
            let mut lines = Vec::new();
            if let Some(sp) = &all {
                let records: Vec<&Vec<usize>> =
                    by_record.range((node.ldem, 0, "")..(node.ldem + 1, 0, "")).map(|(_, r)| r).collect();
                count = records.len();
                for idx in records {
                    let pts: Vec<(f64, f64)> = idx
                        .iter()
                        .filter(|&&i| sp.scale[i] == scale && sp.in_band[i])
                        .map(|&i| (sp.period_s[i], sp.psa_m_s2[i]))
                        .collect();
                    lines.push(Line {
                        label: String::new(),
                        points: pts,
                        colour: RGBColor(150, 150, 150),
                        width: 1,
                        alpha: 0.5,
                    });
                }
            }
            if let Some(l) = lines.first_mut() {
                l.label = "each record".into();
            }
            lines.push(Line {
                label: "mean".into(),
                points: rows.iter().map(|&i| (stats.period_s[i], stats.mean[i])).collect(),
                colour: colour(1),
                width: 4,
                alpha: 1.0,
            });
            let band = Band {
                points: rows.iter().map(|&i| (stats.period_s[i], stats.p5[i], stats.p95[i])).collect(),
                colour: colour(0),
                label: "5–95%".into(),
            };
            panels.push(Panel {
                title: format!("PSA, {unit_note}"),
                name: node.name(),
                lines,
                bands: vec![band],
                ..Panel::loglog("period (s)", "PSA (m/s²)")
            });
        }
    }
    let rows = nodes.len() as u32;
    let sheet = Sheet::new(String::new(), 2, panels).with_height(if rows == 1 { HEIGHT } else { 420 * rows });
    drawn(
        path,
        &sheet,
        format!("Response spectra, {} ({cname})", nodes_short(&nodes)),
        format!(
            "Pseudo-spectral acceleration at {:.0}% damping of the processed {cname} records, {}: every record thin \
             ({count} records per node), the mean and the 5–95% band across records bold, drawn only over the usable \
             band (periods between 1/f_max of the lattice and 1/(1.25·f_low) of the filter). Left at model scale, \
             right at prototype scale (periods ×λ, PSA ÷λ). Exact peaks for the straight-line reading of the samples \
             (Nigam–Jennings).",
            100.0 * damping,
            nodes_text(&nodes, total)
        ),
    )
}

pub(super) fn fourier(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let (nodes, total) = accelerogram_nodes(d);
    if nodes.is_empty() {
        return Ok(Outcome::Skipped("no accelerogram".into()));
    }
    let mut panels = Vec::new();
    for node in &nodes {
        let mut lines = Vec::new();
        for (k, &seed) in d.seeds.iter().enumerate() {
            let Some(df) = d.part(&FOURIER, seed)? else { continue };
            let Some((f, a)) = read_fourier(&df, &format!("S2-n{}-{}", node.ldem, node.component.name()))? else {
                continue;
            };
            // Log-spaced thinning: keep the maximum per 1/200 decade.
            let mut pts: Vec<(f64, f64)> = Vec::new();
            let mut bucket = i64::MIN;
            for i in (0..f.len()).filter(|&i| f[i] > 0.0) {
                let b = (f[i].log10() * 200.0).floor() as i64;
                match pts.last_mut() {
                    Some(p) if b == bucket => {
                        if a[i] > p.1 {
                            *p = (f[i], a[i]);
                        }
                    }
                    _ => {
                        pts.push((f[i], a[i]));
                        bucket = b;
                    }
                }
            }
            let mut l = Line::new(format!("seed {seed}"), pts, k);
            l.width = 1;
            lines.push(l);
        }
        if !lines.is_empty() {
            panels.push(Panel {
                name: format!("{} ({})", node.name(), node.component.name()),
                lines,
                ..Panel::loglog("frequency (Hz)", "|X|·Δt (m/s)")
            });
        }
    }
    if panels.is_empty() {
        return Ok(Outcome::Skipped("no Fourier spectra".into()));
    }
    let n = panels.len();
    let columns = n.min(2);
    let rows = n.div_ceil(columns) as u32;
    let sheet = Sheet::new("Fourier amplitude of the S2 records, model scale", columns, panels)
        .with_height(if rows == 1 { HEIGHT } else { 60 + 420 * rows });
    drawn(
        path,
        &sheet,
        format!("Fourier spectra, {}", nodes_short(&nodes)),
        format!(
            "Fourier amplitude |X(f)|·Δt of the processed record of main shock S2 for {}, {} (zero-padded to a power \
             of two; the largest value per 1/200 decade is drawn). At prototype scale the frequencies are divided by \
             λ, the amplitudes unchanged.",
            seeds_text(&d.seeds),
            nodes_text(&nodes, total)
        ),
    )
}

/// The record set chosen by `[set]` against its design spectrum, prototype scale: the target, each
/// scaled record, their mean, the rule's fraction of the target, the period range shaded.
pub(super) fn record_set(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(settings) = &d.pipeline.set else { return Ok(Outcome::Skipped("no [set] section".into())) };
    let Some(df) = stickslip_store::io::read_parquet_if_present(&d.folder.gathered(&SET))? else {
        return Ok(Outcome::Skipped("no set table (the selection failed or has not run)".into()));
    };
    let set = SetTable::read(&df)?;
    let rotd = settings.component == stickslip_config::set::SetComponent::Rotd50;
    let table = if rotd { ROTD } else { SPECTRA };
    let prototype = polars::prelude::col(col::SCALE).eq(polars::prelude::lit("prototype"));
    let Some(sp) = scan_columns(&d.folder.part_glob(&table), &SPECTRUM_READ, Some(prototype))?
        .map(|df| Spectra::read(&df))
        .transpose()?
    else {
        return Ok(Outcome::Skipped(format!("no {} table", table.name)));
    };
    // A record's prototype spectrum at the set's damping (of its RotD50 in the RotD table, which
    // also holds RotD100), by increasing period.
    let psa_of = |seed: u64, record: &str| -> Vec<(f64, f64, bool)> {
        let mut pts: Vec<(f64, f64, bool)> = (0..sp.seed.len())
            .filter(|&i| {
                sp.seed[i] == seed
                    && sp.record[i] == record
                    && sp.scale[i] == "prototype"
                    && (!rotd || sp.component[i] == "rotd50")
                    && (sp.damping[i] - settings.damping).abs() < 1e-12
            })
            .map(|i| (sp.period_s[i], sp.psa_m_s2[i], sp.in_band[i]))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts
    };
    // Each record is drawn only in its usable band; the mean only where every record is in band.
    let mut lines = Vec::new();
    let mut scaled_all: Vec<Vec<(f64, f64, bool)>> = Vec::new();
    for k in 0..set.seed.len() {
        let pts: Vec<(f64, f64, bool)> =
            psa_of(set.seed[k], &set.record[k]).into_iter().map(|(t, a, b)| (t, a * set.scale_factor[k], b)).collect();
        if pts.is_empty() {
            continue;
        }
        lines.push(Line {
            label: if lines.is_empty() { "each scaled record, in its usable band".into() } else { String::new() },
            points: pts.iter().filter(|p| p.2).map(|p| (p.0, p.1)).collect(),
            colour: RGBColor(150, 150, 150),
            width: 1,
            alpha: 0.7,
        });
        scaled_all.push(pts);
    }
    if scaled_all.is_empty() {
        return Ok(Outcome::Skipped("no spectrum of the chosen records".into()));
    }
    // The mean on the common grid (every record's spectrum has the pipeline's periods).
    let n = scaled_all.iter().map(Vec::len).min().unwrap_or(0);
    let mean: Vec<(f64, f64)> = (0..n)
        .filter(|&j| scaled_all.iter().all(|r| r[j].2))
        .map(|j| (scaled_all[0][j].0, scaled_all.iter().map(|r| r[j].1).sum::<f64>() / scaled_all.len() as f64))
        .collect();
    let target: Vec<(f64, f64)> =
        scaled_all[0][..n].iter().filter_map(|&(t, _, _)| settings.target.psa(t).ok().map(|v| (t, v))).collect();
    let fraction = settings.options.rule_fraction;
    let floor: Vec<(f64, f64)> = target.iter().map(|&(t, v)| (t, fraction * v)).collect();
    let range = settings.options.range.bounds().ok();
    let ys = lines.iter().flat_map(|l| l.points.iter().map(|p| p.1)).chain(target.iter().map(|p| p.1));
    let (lo, hi) = crate::plot::log_range(ys);
    let bands = range
        .map(|(a, b)| Band {
            points: vec![(a, lo, hi), (b, lo, hi)],
            colour: RGBColor(120, 120, 120),
            label: "period range of the match".into(),
        })
        .into_iter()
        .collect();
    lines.push(Line { label: "mean of the set".into(), points: mean, colour: colour(1), width: 3, alpha: 1.0 });
    lines.push(Line { label: settings.target_name.clone(), points: target, colour: BLACK, width: 3, alpha: 1.0 });
    lines.push(Line {
        label: format!("{:.0}% of the target", 100.0 * fraction),
        points: floor,
        colour: colour(0),
        width: 2,
        alpha: 1.0,
    });
    let panel = Panel { lines, bands, y_range: Some((lo, hi)), ..Panel::loglog("period (s)", "PSA (m/s²)") };
    let count = scaled_all.len();
    let comp = if rotd { "RotD50".to_string() } else { set.component.first().cloned().unwrap_or_default() };
    drawn(
        path,
        &Sheet::new(format!("Record set of {count} matched to the target spectrum, prototype scale"), 1, vec![panel]),
        "Record set matched to a design spectrum".into(),
        format!(
            "The {count} records chosen by [set] ({comp}, {:.0}% damping), each scaled by its factor (grey), their \
             mean, the target spectrum ({}) and {:.0}% of it, at prototype scale; the shaded band is the period range \
             of the match{}. The set table lists each record, its factor and misfit; the scaled records are under set/.",
            100.0 * settings.damping,
            settings.target_name,
            100.0 * fraction,
            range
                .map(|(a, b)| format!(" ({}–{} s)", crate::plot::fmt_tick(&a), crate::plot::fmt_tick(&b)))
                .unwrap_or_default()
        ),
    )
}
