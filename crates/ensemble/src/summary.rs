//! Statistics across seeds (the definitions are [`stickslip_seismo::stats`]'s) as one tidy table,
//! and its digest for a terminal.
//!
//! Groups: `S1`, `S2`, … (main shocks of that rank over all seeds), `main` (all main shocks),
//! `all` (all events), and `seed` for per-seed counts (`events_per_seed`,
//! `main_shocks_per_seed` over the successful seeds).

use polars::prelude::DataFrame;
use stickslip_seismo::events::EventKind;
use stickslip_seismo::stats::summarize;
use stickslip_store::frame::Columns;
use stickslip_store::schema::{EVENTS_TABLE, SIMILARITY, col};
use stickslip_store::tables::runs::Runs;
use stickslip_store::tables::stats::{SummaryRow, SummaryTable};
use stickslip_store::{Folder, StoreError};

/// Event quantities summarised (plus every `peak_abs_accel_*` column).
pub const EVENT_QUANTITIES: [&str; 9] = [
    col::START_S,
    col::DURATION_S,
    col::DROP_TIME_S,
    col::STRESS_DROP_PA,
    col::SLIP_M,
    col::PEAK_SLIP_RATE_M_S,
    col::PEAK_SLIPPING_NODES,
    col::RUPTURE_AREA_M2,
    col::RECURRENCE_S,
];

/// Similarity quantities summarised.
pub const SIMILARITY_QUANTITIES: [&str; 8] = [
    col::PROTOTYPE_DURATION_S,
    col::PROTOTYPE_RECURRENCE_YEARS,
    col::M0_PAPER_DYNE_CM,
    col::M0_CONSISTENT_DYNE_CM,
    col::M_RIERA_PAPER_INTERPLATE,
    col::M_RIERA_CONSISTENT_INTERPLATE,
    col::MW_PAPER,
    col::MW_CONSISTENT,
];

/// Rows `(group, quantity, summary)` of one table grouped by main-shock label.
fn grouped(c: &Columns<'_>, quantities: &[String], rows: &mut Vec<SummaryRow>) -> Result<(), StoreError> {
    let (kind, label) = (c.strs(col::KIND)?, c.strs(col::LABEL)?);
    let kinds: Vec<EventKind> =
        kind.iter().zip(&label).map(|(k, l)| EventKind::parse(k, l).unwrap_or(EventKind::Minor)).collect();
    let mut ranks: Vec<u32> = kinds.iter().filter(|k| k.is_main()).filter_map(|k| k.rank()).collect();
    ranks.sort();
    ranks.dedup();
    let mut groups: Vec<(String, Vec<bool>)> =
        ranks.iter().map(|&r| (format!("S{r}"), kinds.iter().map(|k| *k == EventKind::Main(r)).collect())).collect();
    groups.push(("main".into(), kinds.iter().map(|k| k.is_main()).collect()));
    groups.push(("all".into(), vec![true; c.height()]));
    for q in quantities {
        let values = c.f64s(q)?;
        for (g, mask) in &groups {
            let sample: Vec<f64> = values.iter().zip(mask).filter(|(_, m)| **m).map(|(v, _)| *v).collect();
            if let Some(s) = summarize(&sample) {
                rows.push(SummaryRow { group: g.clone(), quantity: q.clone(), summary: s });
            }
        }
    }
    Ok(())
}

/// The summary rows from the gathered runs, events and similarity tables.
pub fn summary_rows(runs: &Runs, events: &DataFrame, similarity: &DataFrame) -> Result<Vec<SummaryRow>, StoreError> {
    let mut rows = Vec::new();
    let ev = Columns::of(events, EVENTS_TABLE.name);
    let mut event_q: Vec<String> = EVENT_QUANTITIES.iter().map(|s| s.to_string()).collect();
    event_q.extend(ev.names().into_iter().filter(|c| c.starts_with("peak_abs_accel_")));
    grouped(&ev, &event_q, &mut rows)?;
    grouped(&Columns::of(similarity, SIMILARITY.name), &SIMILARITY_QUANTITIES.map(String::from), &mut rows)?;
    let ok = runs.ok_seeds();
    for (q, counts) in [("events_per_seed", &runs.events), ("main_shocks_per_seed", &runs.main_shocks)] {
        let v: Vec<f64> =
            runs.seed.iter().zip(counts).filter(|(s, _)| ok.contains(s)).map(|(_, &c)| c as f64).collect();
        if let Some(s) = summarize(&v) {
            rows.push(SummaryRow { group: "seed".into(), quantity: q.into(), summary: s });
        }
    }
    Ok(rows)
}

/// A few lines for a terminal: the main shocks' stress drop, duration, recurrence and magnitude
/// across seeds (mean ± std, and the 95% confidence interval of the mean stress drop), read from
/// `<out>/tables/summary.parquet`.
pub fn digest(out: &Folder) -> Result<String, StoreError> {
    let path = out.gathered(&stickslip_store::schema::SUMMARY);
    if !path.exists() {
        return Ok("no events: no statistics".into());
    }
    let t = SummaryTable::read(&stickslip_store::io::read_parquet(&path)?)?;
    let mut groups: Vec<&String> = t.group.iter().filter(|g| g.starts_with('S')).collect();
    groups.sort_by_key(|g| g[1..].parse::<u32>().unwrap_or(u32::MAX));
    groups.dedup();
    let fmt = |i: Option<usize>, scale: f64, unit: &str, digits: usize| match i {
        Some(i) if t.std[i].is_finite() => {
            format!("{:.*} ± {:.*} {unit}", digits, t.mean[i] * scale, digits, t.std[i] * scale)
        }
        Some(i) => format!("{:.*} {unit}", digits, t.mean[i] * scale),
        None => "–".into(),
    };
    let mut lines = vec![format!(
        "{:<5} {:>5} {:>20} {:>20} {:>20} {:>20} {:>14}",
        "shock", "seeds", "stress drop", "duration", "stress falls in", "recurrence", "M (paper)"
    )];
    // Recurrences of slowly loaded runs are seconds or more.
    let rec = t.find("main", col::RECURRENCE_S).map_or(0.0, |i| t.mean[i]);
    let (rec_scale, rec_unit) = if rec.abs() >= 10.0 { (1.0, "s") } else { (1e3, "ms") };
    // A long run has many main shocks: the first ones, then the summary line.
    const SHOWN: usize = 8;
    let hidden = groups.len().saturating_sub(SHOWN);
    let main = "main".to_string();
    let mut cis = Vec::new();
    for g in groups.into_iter().take(SHOWN).chain(std::iter::once(&main)) {
        if let Some(n) = t.find(g, col::STRESS_DROP_PA)
            && t.ci95_low[n].is_finite()
        {
            cis.push(format!("{g} {:.2}–{:.2}", t.ci95_low[n] * 1e-3, t.ci95_high[n] * 1e-3));
        }
        let Some(n) = t.find(g, col::STRESS_DROP_PA) else { continue };
        if *g == main && hidden > 0 {
            lines.push(format!("… {hidden} more main shocks (their statistics in tables/summary.parquet)"));
        }
        lines.push(format!(
            "{:<5} {:>5} {:>20} {:>20} {:>20} {:>20} {:>14}",
            g,
            t.count[n],
            fmt(Some(n), 1e-3, "kPa", 2),
            fmt(t.find(g, col::DURATION_S), 1e3, "ms", 1),
            fmt(t.find(g, col::DROP_TIME_S), 1e3, "ms", 1),
            fmt(t.find(g, col::RECURRENCE_S), rec_scale, rec_unit, 1),
            fmt(t.find(g, col::M_RIERA_PAPER_INTERPLATE), 1.0, "", 2),
        ));
    }
    if !cis.is_empty() {
        lines.push(format!(
            "(± is the spread over seeds, std; 95% CI of the mean stress drop, kPa: {})",
            cis.join(", ")
        ));
    }
    // Four magnitudes are written; this is the one the paper's M = 6.77 is, not `mw_paper`.
    lines.push(format!(
        "(M (paper) is Riera's M of the paper's moment, Eq. 15 with its λ: column {} of tables/similarity.parquet; \
         {} is the Mw of the same moment)",
        col::M_RIERA_PAPER_INTERPLATE,
        col::MW_PAPER
    ));
    Ok(lines.join("\n"))
}
