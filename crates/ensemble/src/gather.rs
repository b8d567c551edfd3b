//! Gathering the per-seed parts of an output folder into one table each, and the statistics
//! across seeds: the summary, the PSA statistics and the attenuation fits.

use std::collections::{BTreeMap, HashSet};

use polars::prelude::*;
use stickslip_seismo::fit::log_log_fit;
use stickslip_seismo::stats::percentile_sorted;
use stickslip_store::frame::Columns;
use stickslip_store::io::{scan_glob, write_parquet_atomic};
use stickslip_store::schema::{
    self, ATTENUATION, ATTENUATION_FIT, EVENTS_TABLE, PSA_STATS, ROTD, RUNS, SIMILARITY, SPECTRA, SUMMARY, col,
};
use stickslip_store::tables::runs::Runs;
use stickslip_store::tables::stats::{FitRow, PsaStatsRow, attenuation_fit_frame, psa_stats_frame, summary_frame};
use stickslip_store::{Folder, StoreError};

use crate::catalogue::write_catalogue;
use crate::summary::summary_rows;

/// The rows of `df` whose seed is in `keep`.
fn only_seeds(df: DataFrame, keep: &HashSet<u64>, table: &str) -> Result<DataFrame, StoreError> {
    let t = |e| StoreError::table(table, e);
    let mask: BooleanChunked = df
        .column(col::SEED)
        .map_err(t)?
        .u64()
        .map_err(t)?
        .iter()
        .map(|s| s.is_some_and(|s| keep.contains(&s)))
        .collect();
    df.filter(&mask).map_err(t)
}

/// Gathers the per-seed parts of the gathered tables (restricted to `seeds`, sorted by each
/// table's key) into one file each, and writes the statistics across seeds. Returns the gathered
/// runs table, if any seed has finished.
pub fn gather(out: &Folder, seeds: &[u64]) -> Result<Option<Runs>, StoreError> {
    let keep: HashSet<u64> = seeds.iter().copied().collect();
    let mut gathered: Vec<(&str, DataFrame)> = Vec::new();
    for table in schema::gathered() {
        let Some(df) = scan_glob(&out.part_glob(&table))? else { continue };
        let mut df = only_seeds(df, &keep, table.name)?
            .sort(table.key.to_vec(), SortMultipleOptions::default())
            .map_err(|e| StoreError::table(table.name, e))?;
        write_parquet_atomic(&mut df, &out.gathered(&table))?;
        gathered.push((table.name, df));
    }
    let mut spectra: Option<DataFrame> = None;
    for table in [SPECTRA, ROTD] {
        if let Some(df) = scan_glob(&out.part_glob(&table))? {
            let df = only_seeds(df, &keep, table.name)?;
            spectra = Some(match spectra {
                None => df,
                Some(all) => all.vstack(&df).map_err(|e| StoreError::table(table.name, e))?,
            });
        }
    }
    if let Some(spectra) = spectra {
        write_parquet_atomic(&mut psa_stats_frame(&psa_stats(&spectra)?)?, &out.gathered(&PSA_STATS))?;
    }
    let get = |name: &str| gathered.iter().find(|(t, _)| *t == name).map(|(_, d)| d);
    if let Some(att) = get(ATTENUATION.name) {
        write_parquet_atomic(&mut attenuation_fit_frame(&attenuation_fits(att)?)?, &out.gathered(&ATTENUATION_FIT))?;
    }
    let runs_df = get(RUNS.name);
    let runs = runs_df.map(Runs::read).transpose()?;
    if let (Some(runs), Some(events), Some(similarity)) = (&runs, get(EVENTS_TABLE.name), get(SIMILARITY.name)) {
        let mut summary = summary_frame(&summary_rows(runs, events, similarity)?)?;
        write_parquet_atomic(&mut summary, &out.gathered(&SUMMARY))?;
    }
    if let (Some(runs), Some(events), Some(similarity)) = (runs_df, get(EVENTS_TABLE.name), get(SIMILARITY.name)) {
        write_catalogue(out, runs, events, similarity)?;
    }
    Ok(runs)
}

/// PSA across records per (scale, node, component, damping, period), over the records whose
/// usable band holds that period: how many, their mean, geometric mean and type-7 percentiles
/// 5/50/95 (null where no record is in band), and whether every record is in band there. A record
/// cut short (a window clipped by the end of the run has a narrow band) leaves the statistics of
/// the others alone at the periods it does not reach.
pub fn psa_stats(spectra: &DataFrame) -> Result<Vec<PsaStatsRow>, StoreError> {
    let c = Columns::of(spectra, SPECTRA.name);
    let scale = c.strs(col::SCALE)?;
    let node = c.f64s(col::NODE)?;
    let comp = c.strs(col::COMPONENT)?;
    let damping = c.f64s(col::DAMPING)?;
    let period = c.f64s(col::PERIOD_S)?;
    let psa = c.f64s(col::PSA_M_S2)?;
    let in_band = c.bools(col::IN_BAND)?;
    /// One spectral ordinate across seeds; f64 keys as bits so they order and compare exactly.
    #[derive(PartialEq, Eq, PartialOrd, Ord)]
    struct Key {
        scale: String,
        node: u32,
        component: String,
        damping: u64,
        period: u64,
    }
    // Per ordinate: the finite values in band, and whether every record is in band.
    let mut groups: BTreeMap<Key, (Vec<f64>, bool)> = BTreeMap::new();
    for i in 0..c.height() {
        let key = Key {
            scale: scale[i].clone(),
            node: node[i] as u32,
            component: comp[i].clone(),
            damping: damping[i].to_bits(),
            period: period[i].to_bits(),
        };
        let g = groups.entry(key).or_insert((Vec::new(), true));
        if in_band[i] && psa[i].is_finite() {
            g.0.push(psa[i]);
        }
        g.1 &= in_band[i];
    }
    let mut rows = Vec::new();
    for (key, (mut v, every)) in groups {
        v.sort_by(f64::total_cmp);
        let n = v.len() as f64;
        let stats = if v.is_empty() {
            [f64::NAN; 5]
        } else {
            [
                v.iter().sum::<f64>() / n,
                if v[0] > 0.0 { (v.iter().map(|x| x.ln()).sum::<f64>() / n).exp() } else { f64::NAN },
                percentile_sorted(&v, 0.05),
                percentile_sorted(&v, 0.50),
                percentile_sorted(&v, 0.95),
            ]
        };
        rows.push(PsaStatsRow {
            scale: key.scale,
            node: key.node,
            component: key.component,
            damping: f64::from_bits(key.damping),
            period_s: f64::from_bits(key.period),
            count: v.len() as u32,
            stats,
            in_band: every,
        });
    }
    Ok(rows)
}

/// Log-log fits of PGA and PGV against distance, per main-shock rank and over all main shocks.
pub fn attenuation_fits(att: &DataFrame) -> Result<Vec<FitRow>, StoreError> {
    let c = Columns::of(att, ATTENUATION.name);
    let label = c.strs(col::LABEL)?;
    let dist = c.f64s(col::DISTANCE_M)?;
    let mut labels: Vec<String> = label.clone();
    labels.sort_by_key(|l| l.trim_start_matches('S').parse::<u32>().unwrap_or(u32::MAX));
    labels.dedup();
    labels.push("main".into());
    let mut rows = Vec::new();
    for measure in [col::PGA_M_S2, col::PGV_M_S] {
        let y = c.f64s(measure)?;
        for g in &labels {
            let pts = (0..c.height()).filter(|&i| g == "main" || &label[i] == g).map(|i| (dist[i], y[i]));
            if let Some(fit) = log_log_fit(pts) {
                rows.push(FitRow { group: g.clone(), measure, fit });
            }
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three records at two periods; the third is cut short (its band stops below the long
    /// period), so the long period's statistics are those of the other two, not missing.
    #[test]
    fn psa_statistics_at_a_period_are_over_the_records_in_band_there() {
        let df = df!(
            col::SCALE => ["model"; 6],
            col::NODE => [36u32; 6],
            col::COMPONENT => ["z"; 6],
            col::DAMPING => [0.05; 6],
            col::PERIOD_S => [0.01, 0.01, 0.01, 0.1, 0.1, 0.1],
            col::PSA_M_S2 => [1.0, 2.0, 3.0, 10.0, 20.0, 1000.0],
            col::IN_BAND => [true, true, true, true, true, false],
        )
        .unwrap();
        let rows = psa_stats(&df).unwrap();
        assert_eq!(rows.len(), 2);
        let (short, long) = (&rows[0], &rows[1]);
        assert_eq!((short.period_s, short.count, short.in_band), (0.01, 3, true));
        assert!((short.stats[0] - 2.0).abs() < 1e-12 && (short.stats[3] - 2.0).abs() < 1e-12);
        assert_eq!((long.period_s, long.count, long.in_band), (0.1, 2, false));
        assert!((long.stats[0] - 15.0).abs() < 1e-12, "mean {} (the clipped record's 1000 left out)", long.stats[0]);
        // Type-7 percentiles of [10, 20]: 10.5 and 19.5.
        assert!((long.stats[2] - 10.5).abs() < 1e-12 && (long.stats[4] - 19.5).abs() < 1e-12);
        // No record in band: a row with no statistic (null in the table), not one over records out of band.
        let none = df!(
            col::SCALE => ["model"],
            col::NODE => [36u32],
            col::COMPONENT => ["z"],
            col::DAMPING => [0.05],
            col::PERIOD_S => [1.0],
            col::PSA_M_S2 => [5.0],
            col::IN_BAND => [false],
        )
        .unwrap();
        let r = &psa_stats(&none).unwrap()[0];
        assert_eq!(r.count, 0);
        assert!(r.stats.iter().all(|v| v.is_nan()));
    }
}
