//! Accelerogram files: PEER NGA `.AT2` (write and read) and CSV (read).
//!
//! AT2 layout written here (the one structural-analysis tools read):
//! ```text
//! PEER NGA STRONG MOTION DATABASE RECORD
//! <description: pipeline, seed, node, component, scale, units>
//! ACCELERATION TIME SERIES IN UNITS OF G
//! NPTS=  29803, DT= 1.0738000E-05 SEC
//!   1.2345678E-03 -2.3456789E-04 …            (5 values per line, E15.7, in g)
//! ```
//! The reader accepts that header, the older `NPTS DT` two-number form of line 4, and Fortran
//! `D` exponents; values are converted to m/s² with g = 9.80665 m/s².

use std::path::Path;

use crate::error::SeismoError;
use crate::spectra::intensity::G;

/// A uniformly sampled acceleration time history (an accelerogram).
#[derive(Clone, Debug, PartialEq)]
pub struct Accelerogram {
    /// Sampling interval (s).
    pub dt: f64,
    /// Accelerations (m/s²).
    pub accel: Vec<f64>,
    /// Free text describing the record.
    pub description: String,
}

/// Units of acceleration in a CSV file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelUnit {
    /// Standard gravity.
    G,
    /// m/s².
    MetrePerSecond2,
    /// cm/s² (gal).
    CentimetrePerSecond2,
}

impl AccelUnit {
    /// Factor to m/s².
    pub fn to_si(self) -> f64 {
        match self {
            AccelUnit::G => G,
            AccelUnit::MetrePerSecond2 => 1.0,
            AccelUnit::CentimetrePerSecond2 => 0.01,
        }
    }
}

/// `v` as Fortran E15.7: ` -1.2345678E-03`.
fn e15_7(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{:>15}", if v.is_finite() { "0.0000000E+00".to_string() } else { format!("{v}") });
    }
    let s = format!("{v:.7E}");
    let (mantissa, exp) = s.split_once('E').expect("E format");
    let exp: i32 = exp.parse().expect("exponent");
    let sign = if exp < 0 { '-' } else { '+' };
    format!("{:>15}", format!("{mantissa}E{sign}{:02}", exp.abs()))
}

/// The text of an AT2 file for `accel` (m/s²) sampled every `dt` seconds.
pub fn at2_text(accel: &[f64], dt: f64, description: &str) -> String {
    let mut out = String::with_capacity(accel.len() * 16 + 256);
    out.push_str("PEER NGA STRONG MOTION DATABASE RECORD\n");
    out.push_str(description.lines().next().unwrap_or(""));
    out.push('\n');
    out.push_str("ACCELERATION TIME SERIES IN UNITS OF G\n");
    out.push_str(&format!("NPTS= {:>7}, DT= {} SEC\n", accel.len(), e15_7(dt).trim()));
    for chunk in accel.chunks(5) {
        for v in chunk {
            out.push_str(&e15_7(v / G));
        }
        out.push('\n');
    }
    out
}

fn parse_number(s: &str) -> Option<f64> {
    s.trim().trim_end_matches(',').replace(['D', 'd'], "E").parse().ok()
}

/// Parses the text of an AT2 file.
pub fn parse_at2(text: &str, path: &Path) -> Result<Accelerogram, SeismoError> {
    let corrupt = |what: String| SeismoError::Format { path: path.to_path_buf(), what };
    let lines: Vec<&str> = text.lines().collect();
    if lines.len() < 4 {
        return Err(corrupt("an AT2 file has 4 header lines".into()));
    }
    let units = lines[2].to_ascii_uppercase();
    if !units.contains("UNITS OF G") {
        return Err(corrupt(format!("line 3 should say the units are g, found {:?}", lines[2])));
    }
    let header = lines[3].to_ascii_uppercase();
    let (npts, dt) = if header.contains("NPTS") {
        let value_after = |key: &str| -> Option<f64> {
            let rest = &header[header.find(key)? + key.len()..];
            let rest = rest.trim_start_matches(['=', ' ']);
            let token: String = rest.chars().take_while(|c| !c.is_whitespace() && *c != ',').collect();
            parse_number(&token)
        };
        (value_after("NPTS"), value_after("DT"))
    } else {
        let mut it = header.split_whitespace().map(parse_number);
        (it.next().flatten(), it.next().flatten())
    };
    let (Some(npts), Some(dt)) = (npts, dt) else {
        return Err(corrupt(format!("line 4 should give NPTS and DT, found {:?}", lines[3])));
    };
    if !(dt > 0.0) {
        return Err(corrupt(format!("DT = {dt} must be positive")));
    }
    let mut accel = Vec::with_capacity(npts as usize);
    for (k, line) in lines[4..].iter().enumerate() {
        for token in line.split_whitespace() {
            let v = parse_number(token).ok_or_else(|| corrupt(format!("line {}: {token:?} is not a number", k + 5)))?;
            accel.push(v * G);
        }
    }
    if accel.len() != npts as usize {
        return Err(corrupt(format!("NPTS = {npts} but {} values follow", accel.len())));
    }
    Ok(Accelerogram { dt, accel, description: lines[1].trim().to_string() })
}

/// Parses CSV text with a time column (s) and an acceleration column in `unit`; a header line
/// is skipped if it does not parse as numbers. The time step must be uniform (within 1e-6).
pub fn parse_csv(text: &str, unit: AccelUnit, path: &Path) -> Result<Accelerogram, SeismoError> {
    let corrupt = |what: String| SeismoError::Format { path: path.to_path_buf(), what };
    let mut t = Vec::new();
    let mut a = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split([',', ';', '\t']).map(str::trim).collect();
        if fields.len() < 2 {
            return Err(corrupt(format!("line {}: expected time and acceleration columns", k + 1)));
        }
        match (parse_number(fields[0]), parse_number(fields[1])) {
            (Some(ti), Some(ai)) => {
                t.push(ti);
                a.push(ai * unit.to_si());
            }
            _ if t.is_empty() => continue, // header
            _ => return Err(corrupt(format!("line {}: {line:?} is not two numbers", k + 1))),
        }
    }
    if t.len() < 2 {
        return Err(corrupt("a record needs at least two samples".into()));
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    for w in t.windows(2) {
        if ((w[1] - w[0]) - dt).abs() > 1e-6 * dt.abs().max(1e-300) {
            return Err(corrupt(format!("time step not uniform: {} s between {} and {}", w[1] - w[0], w[0], w[1])));
        }
    }
    if !(dt > 0.0) {
        return Err(corrupt("time must increase".into()));
    }
    Ok(Accelerogram { dt, accel: a, description: path.display().to_string() })
}

/// Reads an accelerogram file: `.AT2` by extension (or content), otherwise CSV in `csv_unit`.
pub fn read_accelerogram(path: &Path, csv_unit: AccelUnit) -> Result<Accelerogram, SeismoError> {
    let text = std::fs::read_to_string(path).map_err(|e| SeismoError::Io { path: path.to_path_buf(), source: e })?;
    let is_at2 = path.extension().is_some_and(|e| e.eq_ignore_ascii_case("at2")) || text.starts_with("PEER");
    if is_at2 { parse_at2(&text, path) } else { parse_csv(&text, csv_unit, path) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at2_round_trip_within_printed_precision() {
        let dt = 1.0738e-5;
        let accel: Vec<f64> =
            (0..1234).map(|i| 37.0 * ((i as f64) * 0.37).sin() * (-(i as f64) / 800.0).exp()).collect();
        let text = at2_text(&accel, dt, "test record, model scale, m/s² written as g");
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[3], "NPTS=    1234, DT= 1.0738000E-05 SEC");
        assert_eq!(lines[4].len(), 75, "5 values of 15 characters");
        let back = parse_at2(&text, Path::new("x.AT2")).unwrap();
        assert_eq!(back.accel.len(), accel.len());
        assert!((back.dt - dt).abs() < 1e-12);
        for (a, b) in accel.iter().zip(&back.accel) {
            // E15.7 keeps 8 significant digits.
            assert!((a - b).abs() <= 5e-8 * a.abs() + 1e-300, "{a} vs {b}");
        }
    }

    #[test]
    fn reads_old_header_fortran_exponents_and_csv() {
        let text = "PEER\nold\nACCELERATION TIME SERIES IN UNITS OF G\n 3 0.01\n 0.1D+00 -0.2D+00 0.5E-1\n";
        let r = parse_at2(text, Path::new("o.at2")).unwrap();
        assert_eq!(r.accel.len(), 3);
        assert!((r.accel[1] + 0.2 * G).abs() < 1e-12 && (r.dt - 0.01).abs() < 1e-15);
        let csv = "time_s,acc_gal\n0.0,1.0\n0.02,-2.0\n0.04,3.5\n";
        let r = parse_csv(csv, AccelUnit::CentimetrePerSecond2, Path::new("r.csv")).unwrap();
        assert_eq!(r.accel, vec![0.01, -0.02, 0.035]);
        assert!((r.dt - 0.02).abs() < 1e-15);
        let bad = parse_csv("0,1\n0.01,2\n0.03,3\n", AccelUnit::G, Path::new("b.csv")).unwrap_err().to_string();
        assert!(bad.contains("not uniform"), "{bad}");
        let short = parse_at2(
            "PEER\nx\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 4, DT= 0.01 SEC\n1 2 3\n",
            Path::new("s"),
        );
        assert!(short.unwrap_err().to_string().contains("NPTS = 4 but 3 values"));
    }
}
