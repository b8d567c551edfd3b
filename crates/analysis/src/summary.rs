//! Statistics across seeds (see [`crate::stats`] for the definitions) as one tidy table.
//!
//! **summary** schema: `group` str, `quantity` str (a column name of the events or similarity
//! table, with its unit), `count` u32, `mean`, `std`, `cv`, `min`, `p5`, `p50`, `p95`, `max`,
//! `ci95_low`, `ci95_high`, `geometric_mean`, `log_std` f64 (null where undefined). Values are in
//! the unit of the quantity. Groups: `S1`, `S2`, … (main shocks of that rank over all seeds),
//! `main` (all main shocks), `all` (all events), and `seed` for per-seed counts
//! (`events_per_seed`, `main_shocks_per_seed` over the successful seeds).

use polars::prelude::*;

use crate::error::AnalysisError;
use crate::stats::{Summary, summarize};
use crate::tables::Frame;

/// Event quantities summarised (plus every `peak_abs_accel_*` column).
const EVENT_QUANTITIES: [&str; 9] = [
    "start_s",
    "duration_s",
    "drop_time_s",
    "stress_drop_pa",
    "slip_m",
    "peak_slip_rate_m_s",
    "peak_slipping_nodes",
    "rupture_area_m2",
    "recurrence_s",
];

/// Similarity quantities summarised.
const SIMILARITY_QUANTITIES: [&str; 8] = [
    "prototype_duration_s",
    "prototype_recurrence_years",
    "m0_paper_dyne_cm",
    "m0_consistent_dyne_cm",
    "m_riera_paper_interplate",
    "m_riera_consistent_interplate",
    "mw_paper",
    "mw_consistent",
];

fn floats(df: &DataFrame, name: &str) -> Result<Vec<f64>, AnalysisError> {
    let t = |e| AnalysisError::table(format!("summary ({name})"), e);
    let c = df.column(name).map_err(t)?.cast(&DataType::Float64).map_err(t)?;
    Ok(c.f64().map_err(t)?.iter().map(|v| v.unwrap_or(f64::NAN)).collect())
}

fn strings(df: &DataFrame, name: &str) -> Result<Vec<String>, AnalysisError> {
    let t = |e| AnalysisError::table(format!("summary ({name})"), e);
    Ok(df.column(name).map_err(t)?.str().map_err(t)?.iter().map(|v| v.unwrap_or("").to_string()).collect())
}

/// Rows `(group, quantity, summary)` of one table grouped by main-shock label.
fn grouped(
    df: &DataFrame,
    quantities: &[String],
    rows: &mut Vec<(String, String, Summary)>,
) -> Result<(), AnalysisError> {
    let kind = strings(df, "kind")?;
    let label = strings(df, "label")?;
    let mut labels: Vec<u32> = (0..df.height())
        .filter(|&i| kind[i] == "main")
        .filter_map(|i| label[i].trim_start_matches('S').parse().ok())
        .collect();
    labels.sort();
    labels.dedup();
    let mut groups: Vec<(String, Vec<bool>)> = labels
        .iter()
        .map(|k| {
            let name = format!("S{k}");
            let mask = (0..df.height()).map(|i| kind[i] == "main" && label[i] == name).collect();
            (name, mask)
        })
        .collect();
    groups.push(("main".into(), kind.iter().map(|k| k == "main").collect()));
    groups.push(("all".into(), vec![true; df.height()]));
    for q in quantities {
        let values = floats(df, q)?;
        for (g, mask) in &groups {
            let sample: Vec<f64> = values.iter().zip(mask).filter(|(_, m)| **m).map(|(v, _)| *v).collect();
            if let Some(s) = summarize(&sample) {
                rows.push((g.clone(), q.clone(), s));
            }
        }
    }
    Ok(())
}

/// The summary table from the gathered runs, events and similarity tables.
pub fn summary_frame(runs: &DataFrame, events: &DataFrame, similarity: &DataFrame) -> Result<DataFrame, AnalysisError> {
    let mut rows = Vec::new();
    let mut event_q: Vec<String> = EVENT_QUANTITIES.iter().map(|s| s.to_string()).collect();
    event_q
        .extend(events.get_column_names().iter().map(|c| c.to_string()).filter(|c| c.starts_with("peak_abs_accel_")));
    grouped(events, &event_q, &mut rows)?;
    grouped(similarity, &SIMILARITY_QUANTITIES.map(String::from), &mut rows)?;
    let ok: Vec<bool> = strings(runs, "status")?.iter().map(|s| s == "ok").collect();
    for (q, col) in [("events_per_seed", "events"), ("main_shocks_per_seed", "main_shocks")] {
        let v: Vec<f64> = floats(runs, col)?.into_iter().zip(&ok).filter(|(_, k)| **k).map(|(v, _)| v).collect();
        if let Some(s) = summarize(&v) {
            rows.push(("seed".into(), q.into(), s));
        }
    }
    let n = rows.len();
    let f = |g: &dyn Fn(&Summary) -> f64| rows.iter().map(|(_, _, s)| g(s)).collect::<Vec<f64>>();
    let o = |g: &dyn Fn(&Summary) -> Option<f64>| rows.iter().map(|(_, _, s)| g(s)).collect::<Vec<Option<f64>>>();
    Frame::new(n)
        .str("group", rows.iter().map(|r| r.0.clone()).collect())
        .str("quantity", rows.iter().map(|r| r.1.clone()).collect())
        .u32("count", rows.iter().map(|r| r.2.count as u32).collect())
        .f64("mean", f(&|s| s.mean))
        .opt_f64("std", o(&|s| s.std))
        .opt_f64("cv", o(&|s| s.cv))
        .f64("min", f(&|s| s.min))
        .f64("p5", f(&|s| s.p5))
        .f64("p50", f(&|s| s.p50))
        .f64("p95", f(&|s| s.p95))
        .f64("max", f(&|s| s.max))
        .opt_f64("ci95_low", o(&|s| s.ci95_low))
        .opt_f64("ci95_high", o(&|s| s.ci95_high))
        .opt_f64("geometric_mean", o(&|s| s.geometric_mean))
        .opt_f64("log_std", o(&|s| s.log_std))
        .finish("summary")
}

/// A few lines for a terminal: mean ± std across seeds of the main shocks' stress drop,
/// duration, recurrence and magnitude, read from `<out>/tables/summary.parquet`.
pub fn digest(out: &std::path::Path) -> Result<String, AnalysisError> {
    let path = out.join("tables").join("summary.parquet");
    if !path.exists() {
        return Ok("no events: no statistics".into());
    }
    let df = crate::tables::read_parquet(&path)?;
    let group = strings(&df, "group")?;
    let quantity = strings(&df, "quantity")?;
    let mean = floats(&df, "mean")?;
    let std = floats(&df, "std")?;
    let count = floats(&df, "count")?;
    let find = |g: &str, q: &str| (0..df.height()).find(|&i| group[i] == g && quantity[i] == q);
    let mut groups: Vec<&String> = group.iter().filter(|g| g.starts_with('S')).collect();
    groups.sort_by_key(|g| g[1..].parse::<u32>().unwrap_or(u32::MAX));
    groups.dedup();
    let fmt = |i: Option<usize>, scale: f64, unit: &str, digits: usize| match i {
        Some(i) if std[i].is_finite() => {
            format!("{:.*} ± {:.*} {unit}", digits, mean[i] * scale, digits, std[i] * scale)
        }
        Some(i) => format!("{:.*} {unit}", digits, mean[i] * scale),
        None => "–".into(),
    };
    let mut lines = vec![format!(
        "{:<5} {:>5} {:>20} {:>20} {:>20} {:>20} {:>14}",
        "shock", "seeds", "stress drop", "duration", "stress falls in", "recurrence", "M (paper)"
    )];
    // Recurrences of slowly loaded runs are seconds or more.
    let rec = find("main", "recurrence_s").map_or(0.0, |i| mean[i]);
    let (rec_scale, rec_unit) = if rec.abs() >= 10.0 { (1.0, "s") } else { (1e3, "ms") };
    // A long run has many main shocks: the first ones, then the summary line.
    const SHOWN: usize = 8;
    let hidden = groups.len().saturating_sub(SHOWN);
    for g in groups.into_iter().take(SHOWN).chain(std::iter::once(&"main".to_string())) {
        let Some(n) = find(g, "stress_drop_pa") else { continue };
        if g == "main" && hidden > 0 {
            lines.push(format!("… {hidden} more main shocks (their statistics in tables/summary.parquet)"));
        }
        lines.push(format!(
            "{:<5} {:>5} {:>20} {:>20} {:>20} {:>20} {:>14}",
            g,
            count[n],
            fmt(Some(n), 1e-3, "kPa", 2),
            fmt(find(g, "duration_s"), 1e3, "ms", 1),
            fmt(find(g, "drop_time_s"), 1e3, "ms", 1),
            fmt(find(g, "recurrence_s"), rec_scale, rec_unit, 1),
            fmt(find(g, "m_riera_paper_interplate"), 1.0, "", 2),
        ));
    }
    Ok(lines.join("\n"))
}
