//! The spectral figures: response spectra (PSA) of each node's records across seeds at model and
//! prototype scale, the Fourier amplitude of the S2 records, and the record set chosen by `[set]`
//! against its design spectrum.

use std::path::Path;

use plotters::style::{BLACK, RGBColor};

use std::collections::BTreeMap;
use stickslip_seismo::spectra::intensity::G;

use stickslip_solver::scene::Component;

use stickslip_store::io::{scan_columns, scan_glob};
use stickslip_store::schema::col;
use stickslip_store::schema::{FOURIER, ROTD, SET, SPECTRA, STATION_SPECTRA};
use stickslip_store::tables::set::SetTable;
use stickslip_store::tables::spectra::{Spectra, read_fourier};

use super::Outcome;
use super::common::{NodeChannel, accelerogram_nodes, drawn, nodes_short, nodes_text, rank_of, seeds_text};
use crate::charts::{Band, Line, Panel, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;
use crate::plot::{HEIGHT, colour};

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

/// Every record is drawn when there are at most this many per node; beyond, the spread is the
/// percentile band and only a few records are drawn, highlighted.
pub const EVERY_RECORD_UP_TO: usize = 12;

/// PSA at 5% (or the nearest damping), model and prototype scale, one row per node: the 5–95%
/// band, the median and the mean across records (per period, over the records in band there),
/// and every record thin when they are few, else the main shocks of the first seed drawn.
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
    // Records per node: every record of the node drawn when few, else the first drawn seed's.
    let records_of = |node: u64| -> Vec<(u64, String, String)> {
        let Some(rec) = &d.records else { return vec![] };
        let mut v: Vec<(u64, String, String)> = (0..rec.seed.len())
            .filter(|&i| rec.node[i] == node && rec.component[i] == cname && rec.scale[i] == "model")
            .map(|i| (rec.seed[i], rec.record[i].clone(), rec.label[i].clone()))
            .collect();
        v.sort();
        v.dedup();
        v
    };
    let all_records: Vec<Vec<(u64, String, String)>> = nodes.iter().map(|n| records_of(n.ldem)).collect();
    let few = all_records.iter().all(|r| r.len() <= EVERY_RECORD_UP_TO);
    let highlight_seed = d.seeds.first().copied();
    let spectra_rows = if few {
        scan_glob(&d.folder.part_glob(&SPECTRA))?.map(|df| Spectra::read(&df)).transpose()?
    } else {
        match highlight_seed {
            Some(seed) => d.part(&SPECTRA, seed)?.map(|df| Spectra::read(&df)).transpose()?,
            None => None,
        }
    };
    let mut panels = Vec::new();
    let mut highlighted: Vec<String> = Vec::new();
    let mut least_in_band = usize::MAX;
    for (node, records) in nodes.iter().zip(&all_records) {
        let drawn_records: Vec<&(u64, String, String)> = if few {
            records.iter().collect()
        } else {
            records.iter().filter(|r| Some(r.0) == highlight_seed && rank_of(&r.2).is_some()).take(4).collect()
        };
        // Model scale in m/s²; prototype scale in g, as engineers read a design spectrum.
        for (scale, unit_note, unit, per) in
            [("model", "model scale", "PSA (m/s²)", 1.0), ("prototype", "prototype scale (λ)", "PSA (g)", 1.0 / G)]
        {
            let mut rows: Vec<usize> = (0..stats.node.len())
                .filter(|&i| {
                    stats.node[i] == node.ldem
                        && stats.component[i] == cname
                        && stats.scale[i] == scale
                        && stats.damping[i] == damping
                })
                .collect();
            rows.sort_by(|&a, &b| stats.period_s[a].total_cmp(&stats.period_s[b]));
            // The statistics where at least half of the records are in band.
            let n_records = records.len().max(rows.iter().map(|&i| stats.count[i] as usize).max().unwrap_or(0));
            let wanted = n_records.div_ceil(2).max(1);
            let rows: Vec<usize> = rows.into_iter().filter(|&i| stats.count[i] as usize >= wanted).collect();
            least_in_band = least_in_band.min(wanted);
            let mut lines = Vec::new();
            if let Some(sp) = &spectra_rows {
                for (k, (seed, record, label)) in drawn_records.iter().enumerate() {
                    let mut pts: Vec<(f64, f64)> = (0..sp.seed.len())
                        .filter(|&i| {
                            sp.seed[i] == *seed
                                && sp.record[i] == *record
                                && sp.scale[i] == scale
                                && sp.damping[i] == damping
                                && sp.in_band[i]
                        })
                        .map(|i| (sp.period_s[i], sp.psa_m_s2[i] * per))
                        .collect();
                    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                    if few {
                        lines.push(Line {
                            label: if k == 0 { "each record".into() } else { String::new() },
                            points: pts,
                            colour: RGBColor(150, 150, 150),
                            width: 1,
                            alpha: 0.6,
                        });
                    } else {
                        let name = format!("seed {seed} {label}");
                        if scale == "model" && !highlighted.contains(&name) {
                            highlighted.push(name.clone());
                        }
                        let mut l = Line::new(name, pts, 2 + k);
                        l.width = 1;
                        lines.push(l);
                    }
                }
            }
            lines.push(Line {
                label: "median".into(),
                points: rows.iter().map(|&i| (stats.period_s[i], stats.p50[i] * per)).collect(),
                colour: colour(1),
                width: 4,
                alpha: 1.0,
            });
            lines.push(Line {
                label: "mean".into(),
                points: rows.iter().map(|&i| (stats.period_s[i], stats.mean[i] * per)).collect(),
                colour: BLACK,
                width: 2,
                alpha: 1.0,
            });
            let band = Band {
                points: rows.iter().map(|&i| (stats.period_s[i], stats.p5[i] * per, stats.p95[i] * per)).collect(),
                colour: colour(0),
                label: "5–95%".into(),
            };
            panels.push(Panel {
                title: format!("PSA at {}% damping, {unit_note}", crate::plot::fmt_tick(&(100.0 * damping))),
                name: node.name(),
                lines,
                bands: vec![band],
                ..Panel::loglog("period (s)", unit)
            });
        }
    }
    let count = all_records.iter().map(Vec::len).max().unwrap_or(0);
    let rows = nodes.len() as u32;
    let sheet = Sheet::new(String::new(), 2, panels).with_height(if rows == 1 { HEIGHT } else { 420 * rows });
    let records_text = if few {
        format!("every record thin ({count} per node)")
    } else if highlighted.is_empty() {
        format!("{count} records per node, their spread as the band")
    } else {
        format!(
            "{count} records per node, their spread as the band; drawn on it, the main shocks of {} ({})",
            highlight_seed.map(|s| format!("seed {s}")).unwrap_or_default(),
            highlighted.join(", ")
        )
    };
    drawn(
        path,
        &sheet,
        format!("Response spectra, {} ({cname})", nodes_short(&nodes)),
        format!(
            "Pseudo-spectral acceleration at {}% damping of the processed {cname} records, {}: the 5–95% band, the \
             median and the mean across records, {records_text}. Each record counts only over its usable band \
             (periods between 1/f_max of the lattice and 1/(1.25·f_low) of the filter): at each period the band, \
             median and mean are over the records in band there, drawn where at least half of them are{}. Left at \
             model scale (m/s²), right at prototype scale in g = {G} m/s² (periods ×λ, PSA ÷λ). Exact peaks for the straight-line reading \
             of the samples (Nigam–Jennings).",
            crate::plot::fmt_tick(&(100.0 * damping)),
            nodes_text(&nodes, total),
            if least_in_band < usize::MAX && least_in_band > 1 {
                format!(" ({least_in_band} or more)")
            } else {
                String::new()
            }
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
             of two; up to the top of the record's usable band; the largest value per 1/200 decade is drawn). At prototype scale the frequencies are divided by \
             λ, the amplitudes unchanged.",
            seeds_text(&d.seeds),
            nodes_text(&nodes, total)
        ),
    )
}

/// Each chosen record's spectrum by `(seed, record)`: `(period s, PSA g, in its band)`.
type SpectraOf = BTreeMap<(u64, String), Vec<(f64, f64, bool)>>;

/// The record set chosen by `[set]` against its design spectrum, prototype scale: the target, each
/// scaled record, their mean, the rule's fraction of the target, the period range shaded.
pub(super) fn record_set(d: &ReportInput, path: &Path) -> Result<Outcome, ReportError> {
    let Some(settings) = &d.set else { return Ok(Outcome::Skipped("no [set] section".into())) };
    let Some(df) = stickslip_store::io::read_parquet_if_present(&d.folder.gathered(&SET))? else {
        return Ok(Outcome::Skipped("no set table (the selection failed or has not run)".into()));
    };
    let set = SetTable::read(&df)?;
    use stickslip_config::set::SetComponent;
    let stations = d.pipeline.sets_from_stations();
    let rotd = matches!(settings.component, SetComponent::Rotd50 | SetComponent::Rotd100);
    // A record's prototype spectrum at the set's damping, by increasing period, and whether each
    // period is in its band: a scenario station's RotD50 or RotD100 (`station_spectra`, computed
    // only where usable), or a record's spectrum (its RotD50 in the RotD table, which also holds
    // RotD100).
    let spectra: SpectraOf = if stations {
        let Some(df) = stickslip_store::io::read_parquet_if_present(&d.folder.gathered(&STATION_SPECTRA))? else {
            return Ok(Outcome::Skipped("no station_spectra table".into()));
        };
        let c = stickslip_store::frame::Columns::of(&df, STATION_SPECTRA.name);
        let (seed, name, period) = (c.u64s(col::SEED)?, c.strs(col::STATION)?, c.f64s(col::PERIOD_S)?);
        let psa =
            c.f64s(if settings.component == SetComponent::Rotd100 { col::ROTD100_M_S2 } else { col::ROTD50_M_S2 })?;
        let mut out: SpectraOf = BTreeMap::new();
        for i in 0..seed.len() {
            if set.seed.iter().zip(&set.record).any(|(s, r)| *s == seed[i] && *r == name[i]) {
                out.entry((seed[i], name[i].clone())).or_default().push((period[i], psa[i] / G, true));
            }
        }
        out
    } else {
        let table = if rotd { ROTD } else { SPECTRA };
        let prototype = polars::prelude::col(col::SCALE).eq(polars::prelude::lit("prototype"));
        let Some(sp) = scan_columns(&d.folder.part_glob(&table), &SPECTRUM_READ, Some(prototype))?
            .map(|df| Spectra::read(&df))
            .transpose()?
        else {
            return Ok(Outcome::Skipped(format!("no {} table", table.name)));
        };
        let mut out: SpectraOf = BTreeMap::new();
        for i in 0..sp.seed.len() {
            if sp.scale[i] == "prototype"
                && (!rotd || sp.component[i] == "rotd50")
                && (sp.damping[i] - settings.damping).abs() < 1e-12
                && set.seed.iter().zip(&set.record).any(|(s, r)| *s == sp.seed[i] && *r == sp.record[i])
            {
                out.entry((sp.seed[i], sp.record[i].clone())).or_default().push((
                    sp.period_s[i],
                    sp.psa_m_s2[i] / G,
                    sp.in_band[i],
                ));
            }
        }
        out
    };
    let psa_of = |seed: u64, record: &str| -> Vec<(f64, f64, bool)> {
        let mut pts = spectra.get(&(seed, record.to_string())).cloned().unwrap_or_default();
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
        scaled_all[0][..n].iter().filter_map(|&(t, _, _)| settings.target.psa(t).ok().map(|v| (t, v / G))).collect();
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
    let panel = Panel { lines, bands, y_range: Some((lo, hi)), ..Panel::loglog("period (s)", "PSA (g)") };
    let count = scaled_all.len();
    let comp = match settings.component {
        SetComponent::Rotd50 => "RotD50".to_string(),
        SetComponent::Rotd100 => "RotD100".to_string(),
        _ => set.component.first().cloned().unwrap_or_default(),
    };
    let what = if stations { "scenario's surface stations" } else { "records" };
    drawn(
        path,
        &Sheet::new(
            if stations {
                format!("Record set of {count} scenario stations matched to the target spectrum")
            } else {
                format!("Record set of {count} matched to the target spectrum, prototype scale")
            },
            1,
            vec![panel],
        ),
        "Record set matched to a design spectrum".into(),
        format!(
            "The {count} {what} chosen by [set] ({comp}, {:.0}% damping), each scaled by its factor (grey), their \
             mean, the target spectrum ({}) and {:.0}% of it, at prototype scale, in g = {G} m/s²; the shaded band is the period range \
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

/// What [`record_figure`] draws: one record's spectra.
pub struct RecordSpectraPlot<'a> {
    /// The figure's title (the record's name).
    pub title: &'a str,
    /// Periods (s).
    pub periods: &'a [f64],
    /// Damping ratios.
    pub dampings: &'a [f64],
    /// PSA (m/s²), damping-major over `periods`.
    pub psa_m_s2: &'a [f64],
    /// Fourier amplitude spectrum: frequencies (Hz) and amplitudes |X|·Δt (m/s).
    pub fourier: (&'a [f64], &'a [f64]),
    /// PSA drawn in g (else m/s²).
    pub in_g: bool,
}

/// The spectra of one record (`stickslip spectra`): PSA against period for each damping ratio,
/// and the Fourier amplitude against frequency, log–log, written as a PNG at `path`.
pub fn record_figure(path: &Path, r: &RecordSpectraPlot<'_>) -> Result<(), ReportError> {
    crate::plot::register_fonts();
    let n = r.periods.len();
    let per = if r.in_g { 1.0 / G } else { 1.0 };
    let lines: Vec<Line> = r
        .dampings
        .iter()
        .enumerate()
        .map(|(k, &xi)| {
            let pts = (0..n).map(|j| (r.periods[j], r.psa_m_s2[k * n + j] * per)).collect();
            Line::new(format!("{}% damping", crate::plot::fmt_tick(&(100.0 * xi))), pts, k)
        })
        .collect();
    let dampings: Vec<String> =
        r.dampings.iter().map(|x| format!("{}%", crate::plot::fmt_tick(&(100.0 * x)))).collect();
    let psa = Panel {
        title: format!("PSA at {} damping", dampings.join(", ")),
        lines,
        ..Panel::loglog("period (s)", if r.in_g { "PSA (g)" } else { "PSA (m/s²)" })
    };
    // The largest amplitude per 1/200 decade, as the report's Fourier figure draws it.
    let (f, a) = r.fourier;
    let mut pts: Vec<(f64, f64)> = Vec::new();
    let mut bucket = i64::MIN;
    for i in (0..f.len()).filter(|&i| f[i] > 0.0 && a[i] > 0.0) {
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
    let mut fl = Line::new("", pts, 0);
    fl.width = 1;
    let fourier = Panel {
        title: "Fourier amplitude".into(),
        lines: vec![fl],
        legend: false,
        ..Panel::loglog("frequency (Hz)", "|X|·Δt (m/s)")
    };
    crate::charts::draw(path, &Sheet::new(r.title, 2, vec![psa, fourier]))?;
    Ok(())
}
