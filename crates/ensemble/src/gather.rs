//! Gathering the per-seed parts of an output folder into one table each, and the statistics
//! across seeds: the summary, the PSA statistics and the attenuation fits.

use std::collections::{BTreeMap, HashMap, HashSet};

use polars::prelude::*;
use stickslip_seismo::fit::log_log_fit;
use stickslip_seismo::stats::percentile_sorted;
use stickslip_store::frame::Columns;
use stickslip_store::io::write_parquet_atomic;
use stickslip_store::schema::{
    self, ATTENUATION, ATTENUATION_FIT, EVENTS_TABLE, GMM_BIAS, GMM_PART_B, GMM_RESIDUALS, PSA_STATS, ROTD, RUNS,
    SIMILARITY, SPECTRA, STATIONS, SUMMARY, Scope, TableSpec, col,
};
use stickslip_store::tables::runs::Runs;
use stickslip_store::tables::stats::{FitRow, PsaStatsRow, attenuation_fit_frame, psa_stats_frame, summary_frame};
use stickslip_store::{Folder, StoreError};

use crate::catalogue::write_catalogue;
use crate::summary::summary_rows;

/// The parts of the gathered tables and the PSA values of the spectra and RotD parts of the
/// seeds written by this process, kept as they are written so that gathering does not read them
/// back ([`gather`] reads from disk only the seeds finished before).
#[derive(Default)]
pub struct Gathering {
    seeds: HashSet<u64>,
    parts: HashMap<&'static str, Vec<DataFrame>>,
    psa: PsaGroups,
    psa_seen: bool,
}

impl Gathering {
    /// Keeps what gathering needs of a part of `seed` just written.
    pub fn keep(&mut self, seed: u64, table: &TableSpec, df: DataFrame) -> Result<(), StoreError> {
        self.seeds.insert(seed);
        if table.scope == Scope::Gathered {
            self.parts.entry(table.name).or_default().push(df);
        } else if *table == SPECTRA || *table == ROTD {
            self.psa.add(&df)?;
            self.psa_seen = true;
        }
        Ok(())
    }
}

/// The parts of `table` of `seeds` that exist, read lazily (only `columns`, all when empty)
/// into one frame; `None` when there is none.
fn read_parts(
    out: &Folder,
    table: &TableSpec,
    seeds: &[u64],
    columns: &[&str],
) -> Result<Option<DataFrame>, StoreError> {
    let paths: Vec<PlRefPath> = seeds
        .iter()
        .map(|&s| out.part(table, s))
        .filter(|p| p.exists())
        .map(|p| PlRefPath::new(p.display().to_string()))
        .collect();
    if paths.is_empty() {
        return Ok(None);
    }
    let t = |e| StoreError::table(table.name, e);
    let mut lf = LazyFrame::scan_parquet_files(paths.into(), ScanArgsParquet::default()).map_err(t)?;
    if !columns.is_empty() {
        lf = lf.select(columns.iter().map(|c| col(*c)).collect::<Vec<_>>());
    }
    lf.collect().map(Some).map_err(t)
}

/// Gathers the per-seed parts of the gathered tables of `seeds` (sorted by each table's key)
/// into one file each, and writes the statistics across seeds. Returns the gathered runs table,
/// if any seed has finished. The parts in `memory` (seeds written by this process) are not read
/// back; every other part is read once, with only the columns needed.
pub fn gather(out: &Folder, seeds: &[u64], memory: Gathering) -> Result<Option<Runs>, StoreError> {
    let Gathering { seeds: held, mut parts, psa: mut groups, mut psa_seen } = memory;
    let on_disk: Vec<u64> = seeds.iter().copied().filter(|s| !held.contains(s)).collect();
    let mut gathered: Vec<(&str, DataFrame)> = Vec::new();
    for table in schema::gathered() {
        let t = |e| StoreError::table(table.name, e);
        let mut frames = parts.remove(table.name).unwrap_or_default();
        frames.extend(read_parts(out, &table, &on_disk, &[])?);
        let Some(mut df) = frames.pop() else { continue };
        for f in &frames {
            df.vstack_mut(f).map_err(t)?;
        }
        let mut df = df.sort(table.key.to_vec(), SortMultipleOptions::default()).map_err(t)?;
        write_parquet_atomic(&mut df, &out.gathered(&table))?;
        gathered.push((table.name, df));
    }
    // Only the columns the statistics read.
    let columns = [col::SCALE, col::NODE, col::COMPONENT, col::DAMPING, col::PERIOD_S, col::PSA_M_S2, col::IN_BAND];
    for table in [SPECTRA, ROTD] {
        if let Some(df) = read_parts(out, &table, &on_disk, &columns)? {
            groups.add(&df)?;
            psa_seen = true;
        }
    }
    if psa_seen {
        write_parquet_atomic(&mut psa_stats_frame(&groups.rows())?, &out.gathered(&PSA_STATS))?;
    }
    let get = |name: &str| gathered.iter().find(|(t, _)| *t == name).map(|(_, d)| d);
    let mut fits = Vec::new();
    if let Some(att) = get(ATTENUATION.name) {
        fits.extend(attenuation_fits(att)?);
    }
    if let Some(stations) = get(STATIONS.name) {
        fits.extend(station_attenuation_fits(stations)?);
    }
    if !fits.is_empty() {
        write_parquet_atomic(&mut attenuation_fit_frame(&fits)?, &out.gathered(&ATTENUATION_FIT))?;
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
    // A fault scenario's stations against the ground-motion models, with the defaults of
    // `stickslip gmm` (both models, V_S30 the medium's S-wave speed).
    // Without one, an earlier comparison's tables go: they would describe other seeds.
    let written = match get(STATIONS.name).map(|_| crate::gmm::compare(out, &crate::gmm::GmmOptions::default())) {
        Some(Ok(Some(c))) => {
            crate::gmm::write(out, &c)?;
            true
        }
        Some(Err(crate::error::EnsembleError::Store(e))) => return Err(e),
        // A model refusing a record's inputs does not undo the ensemble: the comparison is left
        // out here, and `stickslip gmm` says why.
        Some(Ok(None) | Err(_)) | None => false,
    };
    if !written {
        for table in [GMM_RESIDUALS, GMM_BIAS, GMM_PART_B] {
            let path = out.gathered(&table);
            if path.exists() {
                std::fs::remove_file(&path).map_err(|e| StoreError::io(&path, e))?;
            }
        }
    }
    Ok(runs)
}

/// PSA across records per (scale, node, component, damping, period), over the records whose
/// usable band holds that period: how many, their mean, geometric mean and type-7 percentiles
/// 5/50/95 (null where no record is in band), and whether every record is in band there. A record
/// cut short (a window clipped by the end of the run has a narrow band) leaves the statistics of
/// the others alone at the periods it does not reach.
pub fn psa_stats(spectra: &DataFrame) -> Result<Vec<PsaStatsRow>, StoreError> {
    let mut groups = PsaGroups::default();
    groups.add(spectra)?;
    Ok(groups.rows())
}

/// One spectral ordinate across seeds (scale, node, component, damping, period), strings
/// interned and f64 as bits, so they compare exactly.
type PsaKey = (u32, u32, u32, u64, u64);

/// The PSA values of spectra-shaped tables grouped per spectral ordinate, added part by part
/// (any order: each group's values are sorted before its statistics), then [`PsaGroups::rows`].
#[derive(Default)]
pub struct PsaGroups {
    names: Vec<String>,
    index: HashMap<PsaKey, usize>,
    keys: Vec<PsaKey>,
    groups: Vec<(Vec<f64>, bool)>,
}

impl PsaGroups {
    fn intern(&mut self, s: Option<&str>) -> u32 {
        let s = s.unwrap_or("");
        match self.names.iter().position(|n| n == s) {
            Some(i) => i as u32,
            None => {
                self.names.push(s.to_string());
                (self.names.len() - 1) as u32
            }
        }
    }

    /// Adds the rows of a spectra or RotD table (its scale, node, component, damping, period,
    /// PSA and in-band columns).
    pub fn add(&mut self, spectra: &DataFrame) -> Result<(), StoreError> {
        let t = |e| StoreError::table(SPECTRA.name, e);
        let c = Columns::of(spectra, SPECTRA.name);
        let strs = |name: &str| -> Result<StringChunked, StoreError> {
            Ok(spectra.column(name).map_err(t)?.str().map_err(t)?.clone())
        };
        let (scale, comp) = (strs(col::SCALE)?, strs(col::COMPONENT)?);
        let node = c.u64s(col::NODE)?;
        let damping = c.f64s(col::DAMPING)?;
        let period = c.f64s(col::PERIOD_S)?;
        let psa = c.f64s(col::PSA_M_S2)?;
        let in_band = c.bools(col::IN_BAND)?;
        for (i, (s, k)) in scale.iter().zip(comp.iter()).enumerate() {
            let key = (self.intern(s), node[i] as u32, self.intern(k), damping[i].to_bits(), period[i].to_bits());
            let g = match self.index.get(&key) {
                Some(&g) => g,
                None => {
                    self.index.insert(key, self.groups.len());
                    self.groups.push((Vec::new(), true));
                    self.keys.push(key);
                    self.groups.len() - 1
                }
            };
            // Per ordinate: the finite values in band, and whether every record is in band.
            if in_band[i] && psa[i].is_finite() {
                self.groups[g].0.push(psa[i]);
            }
            self.groups[g].1 &= in_band[i];
        }
        Ok(())
    }

    /// The statistics of every group, ordered by scale, node, component, damping and period.
    pub fn rows(self) -> Vec<PsaStatsRow> {
        /// One spectral ordinate across seeds; f64 keys as bits so they order and compare exactly.
        #[derive(PartialEq, Eq, PartialOrd, Ord)]
        struct Key {
            scale: String,
            node: u32,
            component: String,
            damping: u64,
            period: u64,
        }
        let names = &self.names;
        let mut ordered: BTreeMap<Key, (Vec<f64>, bool)> = BTreeMap::new();
        for ((s, n, k, d, p), g) in self.keys.into_iter().zip(self.groups) {
            let (scale, component) = (names[s as usize].clone(), names[k as usize].clone());
            ordered.insert(Key { scale, node: n, component, damping: d, period: p }, g);
        }
        let mut rows = Vec::new();
        for (key, (mut v, every)) in ordered {
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
        rows
    }
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

/// Log-log fits of a fault scene's stations' peak horizontal motions (PGA, PGV of the raw records,
/// the largest |(x, z)|) against their rupture distance R_rup, over every seed: group
/// `stations`.
pub fn station_attenuation_fits(stations: &DataFrame) -> Result<Vec<FitRow>, StoreError> {
    let c = Columns::of(stations, STATIONS.name);
    let r = c.f64s(col::R_RUP_M)?;
    let mut rows = Vec::new();
    for measure in [col::PGA_M_S2, col::PGV_M_S] {
        let y = c.f64s(measure)?;
        // A seed whose fault did not rupture puts its stations at R_rup = ∞: not a point.
        if let Some(fit) = log_log_fit(r.iter().copied().zip(y).filter(|(r, _)| r.is_finite())) {
            rows.push(FitRow { group: "stations".into(), measure, fit });
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
