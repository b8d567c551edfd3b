//! Part A of the SCEC Broadband Platform's validation (Goulet et al. 2015, *Seismol. Res. Lett.*
//! 86(1), 17–26; Dreger et al. 2015): a scenario's broadband records against the recordings of a
//! real earthquake, station by station, as the Platform's own code computes it (SCECcode/bbp,
//! `bbp/src/gp/GoodFit/gen_resid_tbl_3comp.c`, `resid2uncer_varN.c` and
//! `bbp/utils/batch/combine_gof_gen.py`).
//!
//! For a period T (or PGA) and each station s whose recording is usable at T and whose simulated
//! records are too, with O_s the observed RotD50 and Y_s,k the simulated RotD50 of seed k:
//! ```text
//! r_s = ln O_s − mean_k ln Y_s,k            the residual ln(obs/sim), averaged in ln over the seeds
//! B = mean_s r_s                            the bias
//! B ± t(0.95, n − 1)·σ/√n                   its 90% interval, σ the spread of r_s (divisor n − 1)
//! ```
//! (`stickslip_seismo::gmm::validation::bias` with the observed values as the "simulated" column
//! and the seeds' geometric means as the "model": it computes ln(O/Y), the mean, the Student
//! interval and the spread). A recording is usable from `T_min = 1/f_high` to `T_max = 1/f_low` of its
//! usable band, each rounded to 0.001 s as the Platform prints them, ends included; a simulated
//! record where its own table has a value (its usable band).
//!
//! **Period bins** (the summaries of the Platform's bias plots: 0.01–0.1, 0.1–1, 1–3, 3.5–10 s):
//! each station's residuals at the periods of the bin where it is usable are averaged into one
//! residual per station, and the bias and interval are computed over those stations. No distance
//! cut (as `combine_gof_gen.py`).
//!
//! The observed side ([`observed`]) is computed once from the recordings and committed as a CSV;
//! [`geometry`] places a scenario's stations at the recordings' distances.

pub mod figure;
pub mod geometry;
pub mod observed;
pub mod simulated;

use std::collections::BTreeMap;

use stickslip_seismo::gmm::validation::{ModelColumn, bias};

/// The period bins of the summaries (s, inclusive).
pub const PERIOD_BINS_S: [[f64; 2]; 4] = [[0.01, 0.1], [0.1, 1.0], [1.0, 3.0], [3.5, 10.0]];

/// The key of PGA in the per-period maps (it is not a period).
pub const PGA: f64 = 0.0;

/// A recording's usable periods `[1/f_high, 1/f_low]` (s), each rounded to 0.001 s as the
/// Platform prints them (`"%.3f"`) before comparing.
pub fn usable_periods(f_low_hz: f64, f_high_hz: f64) -> [f64; 2] {
    let r = |t: f64| (t * 1e3).round() / 1e3;
    [r(1.0 / f_high_hz), r(1.0 / f_low_hz)]
}

/// Whether period `t` (s) lies in `band`, ends included (to 1e-9 relative, so that a period
/// printed as 0.043 matches a band end of 0.043). PGA (`t` = 0) is in every band.
pub fn in_band(t: f64, band: [f64; 2]) -> bool {
    t == PGA || (t >= band[0] * (1.0 - 1e-9) && t <= band[1] * (1.0 + 1e-9))
}

/// One station's observed motion.
#[derive(Clone, Debug, PartialEq)]
pub struct ObservedStation {
    /// Station name (the scenario's station of the same name is its simulation).
    pub name: String,
    /// Longitude and latitude (degrees).
    pub lon_lat: [f64; 2],
    /// R_rup of the recording (km).
    pub r_rup_km: f64,
    /// V_S30 of the recording's site (m/s).
    pub vs30_m_s: f64,
    /// Usable band of the recording: low and high corners (Hz).
    pub band_hz: [f64; 2],
    /// RotD50 per period (s; [`PGA`] for PGA): m/s².
    pub rotd50_m_s2: BTreeMap<u64, f64>,
}

impl ObservedStation {
    /// The usable periods (s), as the Platform rounds them.
    pub fn usable(&self) -> [f64; 2] {
        usable_periods(self.band_hz[0], self.band_hz[1])
    }
}

/// One station's simulated motions over the seeds.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SimulatedStation {
    /// R_rup per seed (km).
    pub r_rup_km: Vec<f64>,
    /// RotD50 per period (s bits; [`PGA`] for PGA), one value per seed that has it (m/s²).
    pub rotd50_m_s2: BTreeMap<u64, Vec<f64>>,
}

/// The bias at one period or over one bin.
#[derive(Clone, Debug, PartialEq)]
pub struct BiasRow {
    /// Period (s; 0 for PGA) or the bin's ends.
    pub periods_s: [f64; 2],
    /// Stations used.
    pub stations: Vec<String>,
    /// Each station's residual ln(obs/sim), same order.
    pub residual_ln: Vec<f64>,
    /// Mean residual (ln).
    pub mean: f64,
    /// 90% interval (Student); `None` for one station.
    pub ci90: Option<[f64; 2]>,
    /// Spread of the residuals (divisor n − 1); `None` for one station.
    pub std: Option<f64>,
}

/// Part A over every period both sides have, PGA first, then the period bins.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PartA {
    /// Per period (PGA first when both sides have it), ascending.
    pub periods: Vec<BiasRow>,
    /// Per period bin of [`PERIOD_BINS_S`] (bins without a station are left out).
    pub bins: Vec<BiasRow>,
    /// Stations of the observed set without a simulated record of the same name.
    pub unmatched: Vec<String>,
}

/// `observed` with each station's values replaced by the geometric mean over the seeds of its
/// simulated values (the periods both have; the recording's band and metadata kept): to measure
/// the simulations against another reference (the models) on the same stations and periods.
pub fn simulated_as_observed(
    observed: &[ObservedStation],
    simulated: &BTreeMap<String, SimulatedStation>,
) -> Vec<ObservedStation> {
    observed
        .iter()
        .filter_map(|o| {
            let s = simulated.get(&o.name)?;
            let rotd50_m_s2 = o
                .rotd50_m_s2
                .keys()
                .filter_map(|k| {
                    let v = s.rotd50_m_s2.get(k).filter(|v| !v.is_empty() && v.iter().all(|x| *x > 0.0))?;
                    Some((*k, (v.iter().map(|x| x.ln()).sum::<f64>() / v.len() as f64).exp()))
                })
                .collect();
            Some(ObservedStation { rotd50_m_s2, ..o.clone() })
        })
        .collect()
}

/// The residual ln(obs/sim) of a station at a period: the observed value against the geometric
/// mean of the seeds' values (`None` when either side has no value > 0).
pub fn residual(observed: f64, simulated: &[f64]) -> Option<f64> {
    if !(observed > 0.0) || simulated.is_empty() || simulated.iter().any(|v| !(*v > 0.0)) {
        return None;
    }
    let ln_sim = simulated.iter().map(|v| v.ln()).sum::<f64>() / simulated.len() as f64;
    Some(observed.ln() - ln_sim)
}

/// The statistics of residuals `r` (ln) of `stations` (`None` without any).
pub fn bias_row(periods_s: [f64; 2], stations: Vec<String>, r: Vec<f64>) -> Option<BiasRow> {
    if r.is_empty() {
        return None;
    }
    // validation::bias computes ln(Y/μ): Y = e^r and μ = 1 give back r itself, with the
    // Platform's mean, Student interval and spread (σ, unused here, set to 1).
    let y: Vec<f64> = r.iter().map(|v| v.exp()).collect();
    let ones = vec![1.0; r.len()];
    let b = bias(&y, ModelColumn { median: &ones, sigma: &ones }).ok()?;
    Some(BiasRow { periods_s, stations, residual_ln: r, mean: b.mean, ci90: b.ci90, std: b.between_record_std })
}

/// Part A of `simulated` (per station name) against `observed`.
pub fn part_a(observed: &[ObservedStation], simulated: &BTreeMap<String, SimulatedStation>) -> PartA {
    let mut out = PartA::default();
    // Per period: (station index, residual).
    let mut per_period: BTreeMap<u64, Vec<(usize, f64)>> = BTreeMap::new();
    for (i, o) in observed.iter().enumerate() {
        let Some(sim) = simulated.get(&o.name) else {
            out.unmatched.push(o.name.clone());
            continue;
        };
        let band = o.usable();
        for (&bits, &value) in &o.rotd50_m_s2 {
            let t = f64::from_bits(bits);
            if !in_band(t, band) {
                continue;
            }
            if let Some(r) = sim.rotd50_m_s2.get(&bits).and_then(|s| residual(value, s)) {
                per_period.entry(bits).or_default().push((i, r));
            }
        }
    }
    for (&bits, rs) in &per_period {
        let t = f64::from_bits(bits);
        let names = rs.iter().map(|(i, _)| observed[*i].name.clone()).collect();
        out.periods.extend(bias_row([t, t], names, rs.iter().map(|p| p.1).collect()));
    }
    for bin in PERIOD_BINS_S {
        let mut by_station: BTreeMap<usize, Vec<f64>> = BTreeMap::new();
        for (&bits, rs) in &per_period {
            let t = f64::from_bits(bits);
            if t != PGA && t >= bin[0] * (1.0 - 1e-9) && t <= bin[1] * (1.0 + 1e-9) {
                for &(i, r) in rs {
                    by_station.entry(i).or_default().push(r);
                }
            }
        }
        let names = by_station.keys().map(|&i| observed[i].name.clone()).collect();
        let r = by_station.values().map(|v| v.iter().sum::<f64>() / v.len() as f64).collect();
        out.bins.extend(bias_row(bin, names, r));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn station(name: &str, band_hz: [f64; 2], values: &[(f64, f64)]) -> ObservedStation {
        ObservedStation {
            name: name.into(),
            lon_lat: [0.0, 0.0],
            r_rup_km: 10.0,
            vs30_m_s: 400.0,
            band_hz,
            rotd50_m_s2: values.iter().map(|&(t, v)| (t.to_bits(), v)).collect(),
        }
    }

    fn sim(values: &[(f64, &[f64])]) -> SimulatedStation {
        SimulatedStation {
            r_rup_km: vec![10.0],
            rotd50_m_s2: values.iter().map(|&(t, v)| (t.to_bits(), v.to_vec())).collect(),
        }
    }

    #[test]
    fn the_usable_band_is_rounded_as_the_platform_prints_it() {
        // 1/23 Hz = 0.043478 s prints as 0.043; 1/0.07 Hz = 14.2857 s as 14.286.
        assert_eq!(usable_periods(0.07, 23.0), [0.043, 14.286]);
        assert!(in_band(0.043, [0.043, 14.286]));
        assert!(!in_band(0.04, [0.043, 14.286]));
        assert!(in_band(PGA, [0.043, 14.286]));
    }

    #[test]
    fn a_station_residual_is_against_the_seeds_geometric_mean() {
        // ln 4 − (ln 1 + ln 4)/2 = ln 2.
        let r = residual(4.0, &[1.0, 4.0]).unwrap();
        assert!((r - 2f64.ln()).abs() < 1e-12);
        assert_eq!(residual(0.0, &[1.0]), None);
        assert_eq!(residual(1.0, &[]), None);
        assert_eq!(residual(1.0, &[1.0, 0.0]), None);
    }

    #[test]
    fn bias_and_interval_match_a_hand_computation() {
        // r = 0.1, 0.3, 0.5: mean 0.3, s = 0.2, t(0.95, 2) = 2.919986, half-width 2.919986·0.2/√3.
        let row = bias_row([1.0, 1.0], vec!["a".into(), "b".into(), "c".into()], vec![0.1, 0.3, 0.5]).unwrap();
        assert!((row.mean - 0.3).abs() < 1e-12);
        assert!((row.std.unwrap() - 0.2).abs() < 1e-12);
        let h = 2.919986 * 0.2 / 3f64.sqrt();
        let [lo, hi] = row.ci90.unwrap();
        assert!((lo - (0.3 - h)).abs() < 1e-6 && (hi - (0.3 + h)).abs() < 1e-6, "{lo} {hi}");
        let one = bias_row([1.0, 1.0], vec!["a".into()], vec![0.2]).unwrap();
        assert_eq!((one.mean, one.ci90, one.std), (0.2, None, None));
        assert_eq!(bias_row([1.0, 1.0], vec![], vec![]), None);
    }

    #[test]
    fn only_stations_usable_at_a_period_count_and_bins_average_per_station_first() {
        // a: usable 0.05–10 s; b: usable 0.5–10 s (its 0.1 s is left out).
        let obs = vec![
            station("a", [0.1, 20.0], &[(PGA, 2.0), (0.1, 2.0), (0.2, 8.0), (1.0, 1.0)]),
            station("b", [0.1, 2.0], &[(PGA, 1.0), (0.1, 1.0), (1.0, 3.0)]),
            station("c", [0.1, 20.0], &[(0.1, 1.0)]),
        ];
        let sims: BTreeMap<String, SimulatedStation> = [
            ("a".to_string(), sim(&[(PGA, &[1.0]), (0.1, &[1.0, 1.0]), (0.2, &[2.0]), (1.0, &[1.0])])),
            ("b".to_string(), sim(&[(PGA, &[1.0]), (0.1, &[0.5]), (1.0, &[1.0])])),
        ]
        .into_iter()
        .collect();
        let p = part_a(&obs, &sims);
        assert_eq!(p.unmatched, vec!["c".to_string()]);
        let at = |t: f64| p.periods.iter().find(|r| r.periods_s[0] == t).unwrap();
        assert_eq!(at(PGA).stations, vec!["a", "b"]);
        assert!((at(PGA).mean - 0.5 * 2f64.ln()).abs() < 1e-12);
        // 0.1 s: only a (b's band starts at 0.5 s).
        assert_eq!(at(0.1).stations, vec!["a"]);
        assert!((at(0.1).mean - 2f64.ln()).abs() < 1e-12);
        assert_eq!(at(1.0).stations, vec!["a", "b"]);
        // The 0.1–1 s bin: a averages ln 2 (0.1), ln 4 (0.2), 0 (1 s) = ln 2; b has ln 3 at 1 s.
        let bin = p.bins.iter().find(|b| b.periods_s == [0.1, 1.0]).unwrap();
        assert_eq!(bin.stations, vec!["a", "b"]);
        assert!((bin.residual_ln[0] - 2f64.ln()).abs() < 1e-12);
        assert!((bin.residual_ln[1] - 3f64.ln()).abs() < 1e-12);
        // PGA is in no bin; bins without stations are left out.
        assert!(p.bins.iter().all(|b| b.periods_s != [3.5, 10.0]));
        // The simulations as observations: the seeds' geometric mean, only where both have a value.
        let as_obs = simulated_as_observed(&obs, &sims);
        assert_eq!(as_obs.iter().map(|o| o.name.as_str()).collect::<Vec<_>>(), vec!["a", "b"]);
        assert_eq!(as_obs[0].rotd50_m_s2.len(), 4);
        assert!((as_obs[0].rotd50_m_s2[&0.2f64.to_bits()] - 2.0).abs() < 1e-12);
        assert_eq!(as_obs[1].band_hz, [0.1, 2.0]);
    }
}
