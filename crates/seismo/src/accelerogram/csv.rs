//! CSV records: the writer of the product's records (time, acceleration, velocity, displacement,
//! SI) and a reader of a time column and an acceleration column in any unit.

use std::path::Path;

use super::at2::parse_number;
use super::{AccelUnit, Accelerogram, RecordFile, RecordFormat};
use crate::error::SeismoError;

/// The CSV format: a `# description` line, a header, then one row per sample:
/// `time_s,acceleration_m_s2,velocity_m_s,displacement_m` (the last two when the record has them),
/// every value in `{:.9e}`.
#[derive(Clone, Copy, Debug)]
pub struct Csv;

impl RecordFormat for Csv {
    fn name(&self) -> &'static str {
        "csv"
    }

    fn extension(&self) -> &'static str {
        "csv"
    }

    fn encode(&self, r: &RecordFile<'_>) -> Result<Vec<u8>, SeismoError> {
        let mut text = format!("# {}\n", r.description);
        match r.motion {
            Some((vel, disp)) => {
                text.push_str("time_s,acceleration_m_s2,velocity_m_s,displacement_m\n");
                for (i, a) in r.accel_m_s2.iter().enumerate() {
                    let t = r.begin_s + i as f64 * r.dt_s;
                    text.push_str(&format!("{t:.9e},{a:.9e},{:.9e},{:.9e}\n", vel[i], disp[i]));
                }
            }
            None => {
                text.push_str("time_s,acceleration_m_s2\n");
                for (i, a) in r.accel_m_s2.iter().enumerate() {
                    let t = r.begin_s + i as f64 * r.dt_s;
                    text.push_str(&format!("{t:.9e},{a:.9e}\n"));
                }
            }
        }
        Ok(text.into_bytes())
    }
}

/// Parses CSV text with a time column (s) and an acceleration column in `unit` (separated by
/// commas, semicolons, tabs or, on a line with none of these, whitespace); a header line is
/// skipped if it does not parse as numbers; `#` lines are comments. The time step must be uniform (within 1e-6).
pub fn parse_csv(text: &str, unit: AccelUnit, path: &Path) -> Result<Accelerogram, SeismoError> {
    let corrupt = |what: String| SeismoError::Format { path: path.to_path_buf(), what };
    let mut t = Vec::new();
    let mut a = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = if line.contains([',', ';', '\t']) {
            line.split([',', ';', '\t']).map(str::trim).collect()
        } else {
            line.split_whitespace().collect()
        };
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_with_header_and_units() {
        let csv = "time_s,acc_gal\n0.0,1.0\n0.02,-2.0\n0.04,3.5\n";
        let r = parse_csv(csv, AccelUnit::CentimetrePerSecond2, Path::new("r.csv")).unwrap();
        assert_eq!(r.accel, vec![0.01, -0.02, 0.035]);
        assert!((r.dt - 0.02).abs() < 1e-15);
        let bad = parse_csv("0,1\n0.01,2\n0.03,3\n", AccelUnit::G, Path::new("b.csv")).unwrap_err().to_string();
        assert!(bad.contains("not uniform"), "{bad}");
        let spaced = parse_csv("# t a\n0.0  1.0\n0.5 -2.0\n1.0   3.0\n", AccelUnit::G, Path::new("s.txt")).unwrap();
        assert_eq!(spaced.accel.len(), 3);
        assert!((spaced.dt - 0.5).abs() < 1e-15);
    }
}
