//! The simulated side of Part A: a scenario's output folder read back — each surface station's
//! RotD50 PGA (`stations`) and PSA (`station_spectra`, where the record is usable) per seed, and
//! each seed's Mw (`source`).

use std::collections::BTreeMap;

use stickslip_store::Folder;
use stickslip_store::frame::Columns;
use stickslip_store::io::read_parquet_if_present;
use stickslip_store::schema::{GMM_RESIDUALS, SOURCE, STATION_SPECTRA, STATIONS, col};

use super::{PGA, SimulatedStation};
use crate::LabError;

/// A scenario's stations and seeds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Scenario {
    /// Surface stations by record name.
    pub stations: BTreeMap<String, SimulatedStation>,
    /// Each seed's Mw, by seed.
    pub mw: BTreeMap<u64, f64>,
    /// The NGA-West2 models' average median for each station's record of each seed (from
    /// `gmm_residuals`, model "average": PGA and the models' periods), by record name, in the
    /// same layout as the simulations; empty when the folder has no such table.
    pub models: BTreeMap<String, SimulatedStation>,
}

fn missing(folder: &Folder, table: &str) -> LabError {
    LabError::Setup(format!(
        "{}: no gathered `{table}` table (a finished run of a fault scene with surface stations is expected)",
        folder.root().display()
    ))
}

/// Reads the gathered tables of `folder`.
pub fn read_scenario(folder: &Folder) -> Result<Scenario, LabError> {
    let src = read_parquet_if_present(&folder.gathered(&SOURCE))?.ok_or_else(|| missing(folder, SOURCE.name))?;
    let c = Columns::of(&src, SOURCE.name);
    let mw = c.u64s(col::SEED)?.into_iter().zip(c.f64s(col::MW)?).collect();
    let st = read_parquet_if_present(&folder.gathered(&STATIONS))?.ok_or_else(|| missing(folder, STATIONS.name))?;
    let c = Columns::of(&st, STATIONS.name);
    let (seed, name, depth, r_rup) =
        (c.u64s(col::SEED)?, c.strs(col::STATION)?, c.f64s(col::Y_M)?, c.f64s(col::R_RUP_M)?);
    let pga = if c.has(col::PGA_ROTD50_M_S2) { c.opt_f64s(col::PGA_ROTD50_M_S2)? } else { vec![None; seed.len()] };
    let mut stations: BTreeMap<String, SimulatedStation> = BTreeMap::new();
    let mut surface = std::collections::BTreeSet::new();
    for i in 0..seed.len() {
        if depth[i].abs() > 1e-6 {
            continue;
        }
        surface.insert((seed[i], name[i].clone()));
        let s = stations.entry(name[i].clone()).or_default();
        s.r_rup_km.push(r_rup[i] / 1e3);
        if let Some(v) = pga[i].filter(|v| *v > 0.0) {
            s.rotd50_m_s2.entry(PGA.to_bits()).or_default().push(v);
        }
    }
    if let Some(sp) = read_parquet_if_present(&folder.gathered(&STATION_SPECTRA))? {
        let c = Columns::of(&sp, STATION_SPECTRA.name);
        let (s, n, t, v) =
            (c.u64s(col::SEED)?, c.strs(col::STATION)?, c.f64s(col::PERIOD_S)?, c.f64s(col::ROTD50_M_S2)?);
        for i in 0..s.len() {
            if surface.contains(&(s[i], n[i].clone())) && v[i] > 0.0 {
                let st = stations.get_mut(&n[i]).expect("a surface station");
                st.rotd50_m_s2.entry(t[i].to_bits()).or_default().push(v[i]);
            }
        }
    }
    let mut models: BTreeMap<String, SimulatedStation> = BTreeMap::new();
    if let Some(gr) = read_parquet_if_present(&folder.gathered(&GMM_RESIDUALS))? {
        let c = Columns::of(&gr, GMM_RESIDUALS.name);
        let (s, n, imt, model) = (c.u64s(col::SEED)?, c.strs(col::STATION)?, c.strs(col::IMT)?, c.strs(col::MODEL)?);
        let (t, median) = (c.opt_f64s(col::PERIOD_S)?, c.f64s(col::MEDIAN)?);
        for i in 0..s.len() {
            let key = match (imt[i].as_str(), t[i]) {
                ("PGA", _) => PGA,
                ("PSA", Some(t)) => t,
                _ => continue,
            };
            if model[i] == "average" && surface.contains(&(s[i], n[i].clone())) && median[i] > 0.0 {
                models.entry(n[i].clone()).or_default().rotd50_m_s2.entry(key.to_bits()).or_default().push(median[i]);
            }
        }
    }
    Ok(Scenario { stations, mw, models })
}

#[cfg(test)]
mod tests {
    use polars::prelude::*;
    use stickslip_store::io::write_parquet_atomic;

    use super::*;

    #[test]
    fn surface_stations_are_gathered_per_name_over_the_seeds() {
        let root = std::env::temp_dir().join(format!("stickslip-part-a-{}", std::process::id()));
        let folder = Folder::new(&root);
        let mut src = df!(col::SEED => [1u64, 2], col::MW => [7.1, 7.3]).unwrap();
        write_parquet_atomic(&mut src, &folder.gathered(&SOURCE)).unwrap();
        let mut st = df!(
            col::SEED => [1u64, 1, 2, 2],
            col::STATION => ["a", "deep", "a", "deep"],
            col::Y_M => [0.0, 500.0, 0.0, 500.0],
            col::R_RUP_M => [1500.0, 800.0, 1500.0, 800.0],
            col::PGA_ROTD50_M_S2 => [Some(2.0), Some(1.0), None, Some(1.0)]
        )
        .unwrap();
        write_parquet_atomic(&mut st, &folder.gathered(&STATIONS)).unwrap();
        let mut sp = df!(
            col::SEED => [1u64, 2, 2, 1],
            col::STATION => ["a", "a", "a", "deep"],
            col::PERIOD_S => [0.1, 0.1, 1.0, 0.1],
            col::ROTD50_M_S2 => [3.0, 4.0, 5.0, 9.0]
        )
        .unwrap();
        write_parquet_atomic(&mut sp, &folder.gathered(&STATION_SPECTRA)).unwrap();
        let mut gr = df!(
            col::SEED => [1u64, 2, 1, 1, 1],
            col::STATION => ["a", "a", "a", "a", "a"],
            col::IMT => ["PSA", "PSA", "PSA", "PGA", "PGV"],
            col::PERIOD_S => [Some(0.1), Some(0.1), Some(0.1), None, None],
            col::MODEL => ["average", "average", "bssa14", "average", "average"],
            col::MEDIAN => [2.0, 2.5, 9.0, 3.0, 0.5]
        )
        .unwrap();
        write_parquet_atomic(&mut gr, &folder.gathered(&GMM_RESIDUALS)).unwrap();
        let s = read_scenario(&folder).unwrap();
        std::fs::remove_dir_all(&root).unwrap();
        assert_eq!(s.mw, [(1, 7.1), (2, 7.3)].into_iter().collect());
        // The buried station is left out; seed 2 has no PGA.
        assert_eq!(s.stations.keys().collect::<Vec<_>>(), vec!["a"]);
        let a = &s.stations["a"];
        assert_eq!(a.r_rup_km, vec![1.5, 1.5]);
        assert_eq!(a.rotd50_m_s2[&PGA.to_bits()], vec![2.0]);
        assert_eq!(a.rotd50_m_s2[&0.1f64.to_bits()], vec![3.0, 4.0]);
        assert_eq!(a.rotd50_m_s2[&1.0f64.to_bits()], vec![5.0]);
        // The models' average only, PGA and PSA (not PGV).
        let m = &s.models["a"].rotd50_m_s2;
        assert_eq!(m.len(), 2);
        assert_eq!(m[&0.1f64.to_bits()], vec![2.0, 2.5]);
        assert_eq!(m[&PGA.to_bits()], vec![3.0]);
    }

    #[test]
    fn a_folder_without_tables_is_refused_with_its_path() {
        let e = read_scenario(&Folder::new("/nonexistent/run")).unwrap_err().to_string();
        assert!(e.contains("/nonexistent/run") && e.contains("source"), "{e}");
    }
}
