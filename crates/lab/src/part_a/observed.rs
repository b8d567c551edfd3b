//! The observed side of Part A: recordings in the Broadband Platform's text format (`.bbp`: a `#`
//! header with the station's longitude, latitude, R_rup, V_S30 and usable band, then time and the
//! N-S, E-W and U-D accelerations in cm/s²) reduced to RotD50 by the product's own code, and the
//! CSV that keeps them.
//!
//! RotD50 as the product measures its stations (`stickslip_analysis::motions`): PGA by
//! `rotd50_peak` and 5%-damped PSA by `RotDPlan` (band-limited reading, [`OVERSAMPLING`]) at the
//! product's periods (`spectrum_periods`, 0.01–10 s), on the two horizontal components as
//! recorded — no filtering, no baseline correction (the Platform applies none to the observed
//! records: `obs_seismograms.py`).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use stickslip_analysis::motions::{DAMPING, rotd50_peak, spectrum_periods};
use stickslip_seismo::spectra::response::Reading;
use stickslip_seismo::spectra::rotd::{RotDPlan, RotDScratch, RotDSpectrum};

use super::{ObservedStation, PGA};

/// One recording read from a `.bbp` file.
#[derive(Clone, Debug, PartialEq)]
pub struct Recording {
    /// Station name (`# Station:`).
    pub name: String,
    /// Longitude and latitude (degrees).
    pub lon_lat: [f64; 2],
    /// "closest distance to fault" (km).
    pub r_rup_km: f64,
    /// V_S30 (m/s).
    pub vs30_m_s: f64,
    /// Low and high frequency corners of the usable band (Hz).
    pub band_hz: [f64; 2],
    /// Sampling interval (s).
    pub dt_s: f64,
    /// N-S and E-W acceleration (m/s²).
    pub horizontal_m_s2: [Vec<f64>; 2],
}

fn header_value(line: &str, key: &str) -> Option<f64> {
    let rest = line.trim_start_matches('#').trim();
    let v = rest.strip_prefix(key)?.trim_start().strip_prefix(':')?;
    v.trim().parse().ok()
}

/// Reads a `.bbp` recording (`text`, from `file` for messages). The sampling must be uniform to
/// 2% of its interval (times are printed with 4 decimals).
pub fn read_bbp(text: &str, file: &str) -> Result<Recording, String> {
    let mut name = None;
    let mut h: BTreeMap<&str, f64> = BTreeMap::new();
    let keys = [
        "longitude",
        "latitude",
        "closest distance to fault (km)",
        "Vs30 (m/s)",
        "low freq. corner (Hz)",
        "high freq. corner (Hz)",
    ];
    let (mut t, mut ns, mut ew) = (Vec::new(), Vec::new(), Vec::new());
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if line.starts_with('#') {
            if let Some(s) = line.trim_start_matches('#').trim().strip_prefix("Station:") {
                name = Some(s.trim().to_string());
            }
            for key in keys {
                if let Some(v) = header_value(line, key) {
                    h.insert(key, v);
                }
            }
            continue;
        }
        let cols: Vec<f64> = line
            .split_whitespace()
            .map(|c| c.parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| format!("{file}: line {}: {line:?} is not four numbers (time, N-S, E-W, U-D)", k + 1))?;
        if cols.len() != 4 {
            return Err(format!("{file}: line {}: {} columns, expected 4 (time, N-S, E-W, U-D)", k + 1, cols.len()));
        }
        t.push(cols[0]);
        ns.push(cols[1] * 0.01);
        ew.push(cols[2] * 0.01);
    }
    let get = |key: &str| h.get(key).copied().ok_or_else(|| format!("{file}: no header line {key:?}"));
    if t.len() < 8 {
        return Err(format!("{file}: {} samples, expected at least 8", t.len()));
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    if let Some(k) = t.windows(2).position(|w| !(dt > 0.0 && ((w[1] - w[0]) / dt - 1.0).abs() <= 0.02)) {
        return Err(format!(
            "{file}: time step {} s at sample {k} against a mean of {dt} s: a uniform sampling is expected",
            t[k + 1] - t[k]
        ));
    }
    Ok(Recording {
        name: name.ok_or_else(|| format!("{file}: no \"# Station:\" line"))?,
        lon_lat: [get("longitude")?, get("latitude")?],
        r_rup_km: get("closest distance to fault (km)")?,
        vs30_m_s: get("Vs30 (m/s)")?,
        band_hz: [get("low freq. corner (Hz)")?, get("high freq. corner (Hz)")?],
        dt_s: dt,
        horizontal_m_s2: [ns, ew],
    })
}

/// How many times a recording is read between its samples: 40, so that a recording sampled every
/// 0.02 s (11 of the 23 Landers recordings) is read 93 times per period at its shortest usable
/// period, 0.043 s (the peak on straight lines between readings within 1 − cos(π/93) = 6e-4).
/// At 4 it erred by up to 2.7% at 0.045–0.075 s against pyrotd 0.6 (frequency-domain response).
pub const OVERSAMPLING: usize = 40;

/// RotD50 of a recording's horizontal pair: PGA and PSA at the product's periods (m/s²).
pub fn observed_station(r: &Recording) -> Result<ObservedStation, String> {
    let [ns, ew] = &r.horizontal_m_s2;
    let periods = spectrum_periods();
    let plan =
        RotDPlan::new(r.dt_s, &periods, &[DAMPING], Reading::BandLimited, OVERSAMPLING).map_err(|e| format!("{e}"))?;
    let mut out = RotDSpectrum::default();
    plan.compute(ns, ew, &mut RotDScratch::default(), &mut out).map_err(|e| format!("{}: {e}", r.name))?;
    let mut rotd50 = BTreeMap::new();
    rotd50.insert(PGA.to_bits(), rotd50_peak(ns, ew));
    for (k, &t) in periods.iter().enumerate() {
        rotd50.insert(t.to_bits(), (2.0 * std::f64::consts::PI / t).powi(2) * out.rotd50[k]);
    }
    Ok(ObservedStation {
        name: r.name.clone(),
        lon_lat: r.lon_lat,
        r_rup_km: r.r_rup_km,
        vs30_m_s: r.vs30_m_s,
        band_hz: r.band_hz,
        rotd50_m_s2: rotd50,
    })
}

/// The columns of the observed CSV.
pub const CSV_COLUMNS: &str = "station,lon_deg,lat_deg,r_rup_km,vs30_m_s,f_low_hz,f_high_hz,period_s,rotd50_m_s2";

/// The observed CSV: `header` as `#` lines, then one row per station and period (period 0 for PGA).
/// Periods are written in their shortest form that reads back bit for bit.
pub fn write_csv(header: &str, stations: &[ObservedStation]) -> String {
    let mut s = String::new();
    for line in header.lines() {
        let _ = writeln!(s, "# {line}");
    }
    let _ = writeln!(s, "{CSV_COLUMNS}");
    for o in stations {
        for (&bits, &v) in &o.rotd50_m_s2 {
            let _ = writeln!(
                s,
                "{},{:.5},{:.5},{},{},{},{},{},{:.6e}",
                o.name,
                o.lon_lat[0],
                o.lon_lat[1],
                o.r_rup_km,
                o.vs30_m_s,
                o.band_hz[0],
                o.band_hz[1],
                f64::from_bits(bits),
                v
            );
        }
    }
    s
}

/// Reads the observed CSV written by [`write_csv`] (`file` for messages), stations in their
/// order of first appearance.
pub fn read_csv(text: &str, file: &str) -> Result<Vec<ObservedStation>, String> {
    let mut out: Vec<ObservedStation> = Vec::new();
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.starts_with('#') && !l.trim().is_empty());
    match lines.next() {
        Some((_, l)) if l.trim() == CSV_COLUMNS => {}
        other => {
            return Err(format!("{file}: header {:?}, expected {CSV_COLUMNS:?}", other.map(|(_, l)| l).unwrap_or("")));
        }
    }
    for (k, line) in lines {
        let c: Vec<&str> = line.split(',').map(str::trim).collect();
        let num = |i: usize| -> Result<f64, String> {
            c.get(i)
                .and_then(|v| v.parse().ok())
                .ok_or_else(|| format!("{file}: line {}: column {} is not a number", k + 1, i + 1))
        };
        if c.len() != 9 {
            return Err(format!("{file}: line {}: {} columns, expected 9", k + 1, c.len()));
        }
        let (period, value) = (num(7)?, num(8)?);
        if !(period >= 0.0 && value > 0.0) {
            return Err(format!("{file}: line {}: period {period} s, RotD50 {value}: expected ≥ 0 and > 0", k + 1));
        }
        if out.last().is_none_or(|o| o.name != c[0]) {
            out.push(ObservedStation {
                name: c[0].to_string(),
                lon_lat: [num(1)?, num(2)?],
                r_rup_km: num(3)?,
                vs30_m_s: num(4)?,
                band_hz: [num(5)?, num(6)?],
                rotd50_m_s2: BTreeMap::new(),
            });
        }
        out.last_mut().expect("pushed").rotd50_m_s2.insert(period.to_bits(), value);
    }
    Ok(out)
}

/// Every `.bbp` recording of `folder`, by file name.
pub fn read_folder(folder: &Path) -> Result<Vec<Recording>, String> {
    let mut files: Vec<_> = std::fs::read_dir(folder)
        .map_err(|e| format!("{}: {e}", folder.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "bbp"))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(format!("{}: no .bbp file", folder.display()));
    }
    files
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()))?;
            read_bbp(&text, &p.display().to_string())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bbp(dt: f64, n: usize, f: impl Fn(f64) -> [f64; 2]) -> String {
        let mut s = String::from(
            "# Strong motion recording\n# Station: st1\n#    longitude: -116.5\n#    latitude: 34.25\n\
             #    closest distance to fault (km): 12.5\n#    Vs30 (m/s): 345\n#    low freq. corner (Hz): 0.070\n\
             #    high freq. corner (Hz): 23.0\n# Column 1: Time (s)\n",
        );
        for i in 0..n {
            let t = 1.5 + i as f64 * dt;
            let [a, b] = f(t);
            let _ = writeln!(s, "{t:.4}\t{a:.6e}\t{b:.6e}\t{:.6e}", 0.5 * a);
        }
        s
    }

    #[test]
    fn a_bbp_file_is_read_in_si_units_with_its_header() {
        let r = read_bbp(&bbp(0.01, 100, |t| [100.0 * t, -50.0]), "x.bbp").unwrap();
        assert_eq!(r.name, "st1");
        assert_eq!((r.lon_lat, r.r_rup_km, r.vs30_m_s, r.band_hz), ([-116.5, 34.25], 12.5, 345.0, [0.07, 23.0]));
        assert!((r.dt_s - 0.01).abs() < 1e-12);
        // cm/s² → m/s².
        assert!((r.horizontal_m_s2[0][0] - 1.5).abs() < 1e-9 && (r.horizontal_m_s2[1][3] + 0.5).abs() < 1e-12);
    }

    #[test]
    fn bad_recordings_are_refused_with_the_file_and_the_reason() {
        let e = read_bbp(&bbp(0.01, 100, |_| [1.0, 1.0]).replace("#    Vs30 (m/s): 345\n", ""), "x.bbp").unwrap_err();
        assert!(e.contains("x.bbp") && e.contains("Vs30"), "{e}");
        let mut gap = bbp(0.01, 100, |_| [1.0, 1.0]);
        gap = gap.replace("1.5500\t", "1.5600\t");
        let e = read_bbp(&gap, "x.bbp").unwrap_err();
        assert!(e.contains("uniform"), "{e}");
        let e = read_bbp("# Station: a\n1 2 3\n", "y.bbp").unwrap_err();
        assert!(e.contains("3 columns"), "{e}");
    }

    #[test]
    fn rotd50_of_a_pair_polarised_along_one_axis_is_its_peak_times_cos_45() {
        // A 2 Hz tone along N-S only: every rotation sees it scaled by |cos θ|, so each RotD50
        // is the one-component value times the median |cos θ| (cos 45°, to half a degree).
        let r =
            read_bbp(&bbp(0.005, 4000, |t| [100.0 * (2.0 * std::f64::consts::PI * 2.0 * t).sin(), 0.0]), "x").unwrap();
        let o = observed_station(&r).unwrap();
        let pga = o.rotd50_m_s2[&PGA.to_bits()];
        assert!((pga / 1.0 - std::f64::consts::FRAC_1_SQRT_2).abs() < 0.01, "{pga}");
        let periods = spectrum_periods();
        let plan = stickslip_seismo::spectra::response::SpectrumPlan::new(
            r.dt_s,
            &periods,
            &[DAMPING],
            Reading::BandLimited,
            4,
        )
        .unwrap();
        let mut sd = vec![0.0; periods.len()];
        plan.compute(&r.horizontal_m_s2[0], &mut Default::default(), &mut sd).unwrap();
        for (k, &t) in periods.iter().enumerate() {
            let one = (2.0 * std::f64::consts::PI / t).powi(2) * sd[k];
            let ratio = o.rotd50_m_s2[&t.to_bits()] / one;
            assert!((ratio - std::f64::consts::FRAC_1_SQRT_2).abs() < 0.01, "T = {t}: {ratio}");
        }
    }

    #[test]
    fn the_csv_reads_back_bit_for_bit() {
        let r = read_bbp(&bbp(0.01, 500, |t| [(7.0 * t).sin() * 30.0, (3.0 * t).cos() * 20.0]), "x").unwrap();
        let o = observed_station(&r).unwrap();
        let text = write_csv("observed\nline two", std::slice::from_ref(&o));
        assert!(text.starts_with("# observed\n# line two\n"));
        let back = read_csv(&text, "o.csv").unwrap();
        assert_eq!(back.len(), 1);
        assert_eq!(back[0].name, "st1");
        assert_eq!(back[0].rotd50_m_s2.keys().collect::<Vec<_>>(), o.rotd50_m_s2.keys().collect::<Vec<_>>());
        for (k, v) in &o.rotd50_m_s2 {
            assert!((back[0].rotd50_m_s2[k] / v - 1.0).abs() < 1e-6);
        }
        assert!(read_csv("a,b\n", "o.csv").unwrap_err().contains("header"));
    }
}
