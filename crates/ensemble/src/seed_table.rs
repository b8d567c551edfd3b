//! One main shock seed by seed, as the Markdown table the README prints (`stickslip seeds`: the
//! README's calibration numbers come from a command, not from memory).

use polars::prelude::{DataFrame, DataType, PolarsError};
use stickslip_config::Pipeline;
use stickslip_store::io::scan_glob;
use stickslip_store::schema::{EVENTS_TABLE, RUNS, SERIES, SIMILARITY, col};
use stickslip_store::{Folder, StoreError};

use crate::EnsembleError;

/// Window of the averaged normal stress (s).
const AVERAGE_S: f64 = 1e-3;

/// The Markdown table of main shock `shock` (`S1`, `S2`, …) of every seed in `folder`, run with
/// `pipeline`: stress drop, duration, recurrence, magnitude and normal-stress range, one line
/// per row, and the note on the σ range below it. Refused when no seed has that main shock.
pub fn shock_table(folder: &Folder, pipeline: &Pipeline, shock: &str) -> Result<String, EnsembleError> {
    let out = folder.root();
    let model = stickslip_solver::Model::new(pipeline.scene.clone());
    let sigma0 = model.total_mass() * pipeline.scene.self_weight.gravity_m_s2 / model.lattice().contact_area();
    let read = |t| -> Result<DataFrame, EnsembleError> {
        scan_glob(&folder.part_glob(t))?
            .ok_or_else(|| EnsembleError::Setup(format!("no {} tables in {}", t.name, out.display())))
    };
    let runs = read(&RUNS)?;
    let events = read(&EVENTS_TABLE)?;
    let similarity = read(&SIMILARITY)?;
    let series = read(&SERIES)?;
    let labels = strings(&events, col::LABEL)?;
    let kinds = strings(&events, col::KIND)?;
    if !(0..labels.len()).any(|i| kinds[i] == "main" && labels[i] == shock) {
        return Err(no_such_shock(out, &labels, &kinds, shock));
    }
    let prev =
        shock.strip_prefix('S').and_then(|n| n.parse::<u32>().ok()).filter(|&n| n > 1).map(|n| format!("S{}", n - 1));
    let mut lines = vec![
        format!(
            "| seed | main shocks | {shock} stress drop | {shock} duration | {shock} stress falls in | {} | {shock} M (paper) | σ range, raw | σ range, {} ms mean |",
            prev.as_ref().map_or("recurrence".into(), |p| format!("{p} → {shock} recurrence")),
            AVERAGE_S * 1e3
        ),
        "|---|---|---|---|---|---|---|---|---|".to_string(),
    ];
    let find = |df: &DataFrame, seed: u64| -> Result<Option<usize>, EnsembleError> {
        let (s, k, l) = (seeds_of(df)?, strings(df, col::KIND)?, strings(df, col::LABEL)?);
        Ok((0..s.len()).find(|&i| s[i] == seed && k[i] == "main" && l[i] == shock))
    };
    let run_seeds = seeds_of(&runs)?;
    let mains: Vec<Option<u32>> =
        runs.column(col::MAIN_SHOCKS).and_then(|c| Ok(c.u32()?.iter().collect())).map_err(polars(col::MAIN_SHOCKS))?;
    let (series_seed, series_t, series_sigma) =
        (seeds_of(&series)?, floats(&series, col::TIME_S), floats(&series, "normal_stress_pa"));
    for (r, &seed) in run_seeds.iter().enumerate() {
        let value = |df: &DataFrame, row: Option<usize>, c: &str, scale: f64, digits: usize, unit: &str| -> String {
            row.and_then(|i| floats(df, c).get(i).copied())
                .filter(|v| v.is_finite())
                .map_or("–".into(), |v| format!("{:.*}{unit}", digits, v * scale))
        };
        let (ev, si) = (find(&events, seed)?, find(&similarity, seed)?);
        let rows: Vec<usize> = (0..series_seed.len()).filter(|&i| series_seed[i] == seed).collect();
        let (raw, averaged) = if series_sigma.is_empty() {
            ("–".into(), "–".into())
        } else {
            let t: Vec<f64> = rows.iter().map(|&i| series_t[i]).collect();
            let sigma: Vec<f64> = rows.iter().map(|&i| series_sigma[i]).collect();
            swing(&t, &sigma, sigma0)
        };
        lines.push(format!(
            "| {seed} | {} | {} | {} | {} | {} | {} | {raw} | {averaged} |",
            mains[r].map_or("–".into(), |n| n.to_string()),
            value(&events, ev, col::STRESS_DROP_PA, 1e-3, 2, " kPa"),
            value(&events, ev, col::DURATION_S, 1e3, 1, " ms"),
            value(&events, ev, col::DROP_TIME_S, 1e3, 1, " ms"),
            value(&events, ev, col::RECURRENCE_S, 1e3, 1, " ms"),
            value(&similarity, si, col::M_RIERA_PAPER_INTERPLATE, 1.0, 2, ""),
        ));
    }
    lines.push(format!(
        "\nσ range: lowest and highest normal stress of the shear stage (t ≥ 0) as a change from the self-weight \
         σ0 = ρgh = {:.2} kPa; raw samples, and averaged over a centred {} ms window",
        sigma0 * 1e-3,
        AVERAGE_S * 1e3
    ));
    Ok(lines.join("\n"))
}

/// A polars error reading column `what`, as the store says it.
fn polars(what: &str) -> impl Fn(PolarsError) -> EnsembleError {
    let what = what.to_string();
    move |e| EnsembleError::Store(StoreError::table(what.clone(), e))
}

/// The seed column of a table.
fn seeds_of(df: &DataFrame) -> Result<Vec<u64>, EnsembleError> {
    df.column(col::SEED).and_then(|c| Ok(c.u64()?.iter().flatten().collect())).map_err(polars(col::SEED))
}

/// A text column of a table, nulls as empty.
fn strings(df: &DataFrame, c: &str) -> Result<Vec<String>, EnsembleError> {
    df.column(c)
        .and_then(|column| Ok(column.str()?.iter().map(|v| v.unwrap_or_default().to_string()).collect()))
        .map_err(polars(c))
}

/// A column of a table as f64, nulls as NaN; empty when absent.
fn floats(df: &DataFrame, c: &str) -> Vec<f64> {
    df.column(c)
        .ok()
        .and_then(|c| c.cast(&DataType::Float64).ok())
        .and_then(|c| c.f64().ok().map(|c| c.iter().map(|v| v.unwrap_or(f64::NAN)).collect()))
        .unwrap_or_default()
}

/// Why no seed of `out` has main shock `shock`: which main shocks its seeds have.
fn no_such_shock(out: &std::path::Path, labels: &[String], kinds: &[String], shock: &str) -> EnsembleError {
    let mut ranks: Vec<u32> = (0..labels.len())
        .filter(|&i| kinds[i] == "main")
        .filter_map(|i| labels[i].strip_prefix('S')?.parse().ok())
        .collect();
    ranks.sort_unstable();
    ranks.dedup();
    EnsembleError::Setup(format!(
        "no seed of {} has a main shock {shock}: {}",
        out.display(),
        match ranks.last() {
            Some(1) => "its seeds have S1 only".to_string(),
            Some(last) => format!("its seeds have S1 … S{last}"),
            None => "it has no main shock at all".to_string(),
        }
    ))
}

/// The range of σ/σ0 − 1 over t ≥ 0, raw and as a centred moving average, as "−60…+140%".
fn swing(t: &[f64], sigma: &[f64], sigma0: f64) -> (String, String) {
    let start = t.iter().position(|&v| v >= 0.0).unwrap_or(t.len());
    let (t, sigma) = (&t[start..], &sigma[start..]);
    if sigma.len() < 2 {
        return ("–".into(), "–".into());
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    let half = ((AVERAGE_S / dt / 2.0).round() as usize).max(1);
    let mut cum = vec![0.0; sigma.len() + 1];
    for (i, v) in sigma.iter().enumerate() {
        cum[i + 1] = cum[i] + v;
    }
    let averaged: Vec<f64> = (half..sigma.len().saturating_sub(half))
        .map(|i| (cum[i + half + 1] - cum[i - half]) / (2 * half + 1) as f64)
        .collect();
    let range = |v: &[f64]| -> String {
        let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        if !lo.is_finite() || !hi.is_finite() {
            return "–".into();
        }
        let pct = |x: f64| 100.0 * (x / sigma0 - 1.0);
        format!("{:+.0}…{:+.0}%", pct(lo), pct(hi)).replace('-', "−")
    };
    (range(sigma), range(&averaged))
}

#[cfg(test)]
mod tests {
    use super::swing;

    #[test]
    fn swing_of_a_square_wave() {
        // σ0 = 10; samples every 0.1 ms alternate 5 and 15 in 2-ms halves: raw −50…+50%, the 1-ms
        // average reaches the plateaus too.
        let t: Vec<f64> = (0..400).map(|i| i as f64 * 1e-4).collect();
        let s: Vec<f64> = (0..400).map(|i| if (i / 20) % 2 == 0 { 5.0 } else { 15.0 }).collect();
        let (raw, avg) = swing(&t, &s, 10.0);
        assert_eq!(raw, "−50…+50%");
        assert_eq!(avg, "−50…+50%");
    }
}
