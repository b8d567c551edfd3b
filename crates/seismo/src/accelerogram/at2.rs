//! PEER NGA `.AT2` files: the writer the product's records use and a reader of every PEER form.
//!
//! Layout written (the one structural-analysis tools read):
//! ```text
//! PEER NGA STRONG MOTION DATABASE RECORD
//! <description: pipeline, seed, node, component, scale, units>
//! ACCELERATION TIME SERIES IN UNITS OF G
//! NPTS=  29803, DT= 1.0738000E-05 SEC
//!   1.2345678E-03 -2.3456789E-04 …            (5 values per line, E15.7, in g)
//! ```
//! The reader accepts line 4 in every form PEER has used:
//! - NGA-West2: `NPTS=  4096, DT=   .0100 SEC` (keys, `=`, commas, a unit word);
//! - variants without the comma or unit, in either key order: `NPTS= 4096 DT= .01`;
//! - the older PEER form, numbers first and names after: `4096    0.0100    NPTS, DT`
//!   (e.g. the Kobe NIS090 record distributed with pystrata), or the two numbers alone.
//!
//! Values may use Fortran `D` exponents. A last line padded with zeros beyond `NPTS` (seen in
//! some old files) is accepted and the padding dropped; fewer values than `NPTS`, or non-zero
//! values beyond it, are refused. Values are converted from g to m/s² with g = 9.80665 m/s².

use std::path::Path;

use super::{Accelerogram, G, RecordFile, RecordFormat};
use crate::error::SeismoError;

/// The `.AT2` format: acceleration in g, the description on line 2.
#[derive(Clone, Copy, Debug)]
pub struct At2;

impl RecordFormat for At2 {
    fn name(&self) -> &'static str {
        "at2"
    }

    fn extension(&self) -> &'static str {
        "AT2"
    }

    fn encode(&self, r: &RecordFile<'_>) -> Result<Vec<u8>, SeismoError> {
        Ok(at2_text(r.accel_m_s2, r.dt_s, r.description).into_bytes())
    }
}

/// `v` as Fortran E15.7: ` -1.2345678E-03`.
fn e15_7(v: f64) -> String {
    let mut out = String::with_capacity(15);
    push_e15_7(&mut out, v);
    out
}

/// A few bytes of text on the stack (a number's digits), without an allocation.
struct Digits {
    buf: [u8; 32],
    len: usize,
}

impl std::fmt::Write for Digits {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        let end = self.len + s.len();
        self.buf.get_mut(self.len..end).ok_or(std::fmt::Error)?.copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

/// Appends `v` as Fortran E15.7 (right-aligned in 15 characters, a mantissa of eight digits, a
/// signed exponent of at least two) without allocating: a record's file is hundreds of thousands
/// of these.
fn push_e15_7(out: &mut String, v: f64) {
    use std::fmt::Write;
    if v == 0.0 || !v.is_finite() {
        let _ = write!(out, "{:>15}", if v.is_finite() { "0.0000000E+00".to_string() } else { format!("{v}") });
        return;
    }
    let (digits, exp) = eight_digits(v).unwrap_or_else(|| exact_eight_digits(v));
    // ` -1.2345678E-03`: the sign, a digit, a point, seven digits, `E`, a signed exponent.
    let mut text = [b' '; 16];
    let mut end = 16;
    let mut e = exp.unsigned_abs();
    for _ in 0..if e >= 100 { 3 } else { 2 } {
        end -= 1;
        text[end] = b'0' + (e % 10) as u8;
        e /= 10;
    }
    end -= 1;
    text[end] = if exp < 0 { b'-' } else { b'+' };
    end -= 1;
    text[end] = b'E';
    let mut d = digits;
    for k in 0..8 {
        if k == 7 {
            end -= 1;
            text[end] = b'.';
        }
        end -= 1;
        text[end] = b'0' + (d % 10) as u8;
        d /= 10;
    }
    if v < 0.0 {
        end -= 1;
        text[end] = b'-';
    }
    let start = end.min(16 - 15);
    out.push_str(std::str::from_utf8(&text[start..]).expect("ASCII"));
}

/// [`eight_digits`] as `{:.7E}` prints them, for any finite non-zero `v`.
fn exact_eight_digits(v: f64) -> (u32, i32) {
    use std::fmt::Write;
    let mut d = Digits { buf: [0; 32], len: 0 };
    // `{:.7E}` prints a sign, one digit, a point, seven digits, `E` and an integer exponent, at
    // most 15 bytes for an f64.
    write!(d, "{:.7E}", v.abs()).expect("an f64 in E format fits in 32 bytes");
    let s = std::str::from_utf8(&d.buf[..d.len]).expect("ASCII");
    let (mantissa, exp) = s.split_once('E').expect("E format");
    let digits = mantissa.bytes().filter(u8::is_ascii_digit).fold(0u32, |n, b| n * 10 + u32::from(b - b'0'));
    (digits, exp.parse().expect("an integer exponent"))
}

/// Powers of ten, 1e-300 to 1e300, each the double nearest to it (parsed, not multiplied).
fn pow10(n: i32) -> f64 {
    static TABLE: std::sync::OnceLock<Vec<f64>> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| (-300..=300).map(|k| format!("1e{k}").parse().expect("a power of ten")).collect())
        [(n + 300) as usize]
}

/// `|v|` rounded to eight significant digits as `(d, e)`, `|v| ≈ d·10^(e−7)` with
/// `10⁷ ≤ d < 10⁸`, the digits `{:.7E}` prints; `None` where this shortcut cannot be sure of them,
/// for `{:.7E}` to decide ([`exact_eight_digits`]; its exact arithmetic is several times slower).
///
/// `|v|·10^(7−e)` is computed in doubles: the power within half an ulp, the product within half an
/// ulp more, so within 3e-16 of its value relative, 3e-8 absolute below 10⁸. Its rounding to an
/// integer is then certain unless its fraction lies within 1e-6 of one half (a tie or nearly);
/// those, and magnitudes outside 1e-290…1e290 (where the powers would leave the table or the
/// normal numbers), are left to `{:.7E}`.
fn eight_digits(v: f64) -> Option<(u32, i32)> {
    let a = v.abs();
    if !(1e-290..=1e290).contains(&a) {
        return None;
    }
    let mut e = a.log10().floor() as i32;
    // log10 may miss a power of ten by one either way.
    for _ in 0..3 {
        let scaled = a * pow10(7 - e);
        if scaled < 1e7 {
            e -= 1;
        } else if scaled >= 1e8 {
            e += 1;
        } else {
            let whole = scaled.floor();
            let fraction = scaled - whole;
            if (fraction - 0.5).abs() < 1e-6 {
                return None;
            }
            let d = whole as u32 + u32::from(fraction > 0.5);
            return Some(if d == 100_000_000 { (10_000_000, e + 1) } else { (d, e) });
        }
    }
    None
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
            push_e15_7(&mut out, v / G);
        }
        out.push('\n');
    }
    out
}

pub(crate) fn parse_number(s: &str) -> Option<f64> {
    s.trim().trim_end_matches(',').replace(['D', 'd'], "E").parse().ok()
}

/// `NPTS` and `DT` from line 4 of an AT2 file, in any of the forms the module doc lists.
pub fn parse_npts_dt(line: &str) -> Option<(f64, f64)> {
    let upper = line.to_ascii_uppercase();
    let tokens: Vec<&str> = upper
        .split(|c: char| c.is_whitespace() || c == ',' || c == '=' || c == ':')
        .filter(|t| !t.is_empty())
        .collect();
    let number = |t: &str| parse_number(t.strip_suffix("SEC").unwrap_or(t));
    let (mut npts, mut dt) = (None, None);
    for w in tokens.windows(2) {
        match w[0] {
            "NPTS" => npts = npts.or(number(w[1])),
            "DT" => dt = dt.or(number(w[1])),
            _ => {}
        }
    }
    match (npts, dt) {
        (Some(n), Some(d)) => Some((n, d)),
        (None, None) => {
            // Numbers first (old PEER form) or numbers alone.
            let mut nums = tokens.iter().filter_map(|t| number(t));
            Some((nums.next()?, nums.next()?))
        }
        _ => None,
    }
}

/// Parses the text of an AT2 file; `path` only names it in errors.
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
    let Some((npts, dt)) = parse_npts_dt(lines[3]) else {
        return Err(corrupt(format!("line 4 should give NPTS and DT, found {:?}", lines[3])));
    };
    if !(npts >= 0.0 && npts.fract() == 0.0 && npts <= 1e9) {
        return Err(corrupt(format!("NPTS = {npts} must be a whole number of samples")));
    }
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(corrupt(format!("DT = {dt} must be positive")));
    }
    let npts = npts as usize;
    let mut accel = Vec::with_capacity(npts);
    for (k, line) in lines[4..].iter().enumerate() {
        for token in line.split_whitespace() {
            let v = parse_number(token).ok_or_else(|| corrupt(format!("line {}: {token:?} is not a number", k + 5)))?;
            if accel.len() >= npts && v != 0.0 {
                return Err(corrupt(format!("NPTS = {npts} but non-zero values follow the last one (line {})", k + 5)));
            }
            accel.push(v * G);
        }
    }
    if accel.len() < npts {
        return Err(corrupt(format!("NPTS = {npts} but {} values follow", accel.len())));
    }
    accel.truncate(npts);
    Ok(Accelerogram { dt, accel, description: lines[1].trim().to_string() })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The formatting as first written (three strings per value), the oracle of `push_e15_7`.
    fn e15_7_by_strings(v: f64) -> String {
        if v == 0.0 || !v.is_finite() {
            return format!("{:>15}", if v.is_finite() { "0.0000000E+00".to_string() } else { format!("{v}") });
        }
        let s = format!("{v:.7E}");
        let (mantissa, exp) = s.split_once('E').unwrap_or((&s, "0"));
        let exp: i32 = exp.parse().unwrap_or(0);
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{:>15}", format!("{mantissa}E{sign}{:02}", exp.abs()))
    }

    #[test]
    fn e15_7_without_allocations_writes_the_bytes_of_the_string_formatting() {
        let mut values = vec![
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
            5e-324,
            -5e-324,
            1.0,
            -1.0,
            9.99999995,
            9.999999949999,
            -9.99999995e-100,
            9.99999995e99,
            1e100,
            1e-100,
            1e-99,
            0.1,
            1.5e-5,
        ];
        // Every decade from the subnormals to the largest, both signs, with a spread of mantissas.
        let mut x = 0x2545_f491_4f6c_dd1d_u64;
        for e in -324..=308 {
            for _ in 0..8 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let m = 1.0 + (x >> 11) as f64 / (1u64 << 53) as f64 * 9.0;
                let v = m * 10f64.powi(e);
                values.push(if x & 1 == 0 { v } else { -v });
            }
        }
        // Ties and near-ties at the eighth digit, and the edges of every decade.
        for k in -20..=20 {
            let p = 10f64.powi(k);
            for m in [12345678.5, 12345679.5, 99999999.5, 99999999.49999, 10000000.5, 9999999.5, 1e7, 1e8] {
                values.push(m * p);
                values.push(-m * p);
            }
            values.push(9.99999995 * p);
            values.push(p);
            values.push(f64::from_bits(p.to_bits() - 1));
            values.push(f64::from_bits(p.to_bits() + 1));
        }
        // Random bit patterns: every exponent, every mantissa.
        for _ in 0..200_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            values.push(f64::from_bits(x));
        }
        // The shortcut decides nearly every value of a record's range, not only the easy ones.
        let decided = values.iter().filter(|v| (1e-290..=1e290).contains(&v.abs())).map(|&v| eight_digits(v).is_some());
        let (yes, all) = decided.fold((0, 0), |(y, n), d| (y + usize::from(d), n + 1));
        assert!(yes as f64 > 0.999 * all as f64 - 200.0, "{yes} of {all} decided by the shortcut");
        for v in values {
            let mut pushed = String::from("x");
            push_e15_7(&mut pushed, v);
            assert_eq!(&pushed[1..], e15_7_by_strings(v), "{v:e}");
            assert_eq!(e15_7(v), e15_7_by_strings(v), "{v:e}");
        }
    }

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

    /// A record of `npts` values `k·1e-3 g` under the given line 4.
    fn at2_with_line4(line4: &str, npts: usize) -> String {
        let mut s =
            format!("PEER NGA STRONG MOTION DATABASE RECORD\nx\nACCELERATION TIME HISTORY IN UNITS OF G\n{line4}\n");
        for chunk in (0..npts).collect::<Vec<_>>().chunks(5) {
            for k in chunk {
                s.push_str(&format!("{:>15.6E}", *k as f64 * 1e-3));
            }
            s.push('\n');
        }
        s
    }

    #[test]
    fn every_peer_form_of_line_4_is_read() {
        let forms = [
            ("4096    0.0100    NPTS, DT", 4096, 0.01), // old PEER (Kobe NIS090, pystrata)
            ("NPTS=  4096, DT=   .0100 SEC", 4096, 0.01), // NGA-West2
            ("NPTS= 4096 DT= .01", 4096, 0.01),
            ("NPTS=4096,DT=.0050SEC", 4096, 0.005),
            ("DT= .0200 SEC, NPTS= 1000", 1000, 0.02),
            ("  1000   .0050", 1000, 0.005),
            ("npts= 12, dt= 1.0D-02 sec", 12, 0.01),
        ];
        for (line4, npts, dt) in forms {
            let r =
                parse_at2(&at2_with_line4(line4, npts), Path::new("f.at2")).unwrap_or_else(|e| panic!("{line4}: {e}"));
            assert_eq!(r.accel.len(), npts, "{line4}");
            assert!((r.dt - dt).abs() < 1e-15, "{line4}: dt {}", r.dt);
            assert!((r.accel[7] - 7e-3 * G).abs() < 1e-12, "{line4}");
        }
        for bad in ["NPTS= 4096, DT= SEC", "4096 NPTS", "NPTS= 40.5, DT= .01", "NPTS= 10, DT= -0.01"] {
            let e = parse_at2(&at2_with_line4(bad, 10), Path::new("bad.at2")).unwrap_err().to_string();
            assert!(
                e.contains("bad.at2") && (e.contains("line 4") || e.contains("NPTS") || e.contains("DT")),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn first_lines_of_kobe_nis090_as_distributed_with_pystrata() {
        // The first 4 + 2 lines of pystrata's tests/data/NIS090.AT2, NPTS cut to the 10 values shown.
        let text = "PEER NGA STRONG MOTION DATABASE RECORD\n\
                    KOBE 01/16/95 2046, NISHI-AKASHI, 090 (CUE)\n\
                    ACCELERATION TIME HISTORY IN UNITS OF G\n\
                    10    0.0100    NPTS, DT\n   \
                    0.233833E-06   0.299033E-06   0.515835E-06   0.667785E-06   0.490847E-06\n  \
                    -0.377832E-06  -0.127271E-05  -0.110085E-05  -0.163851E-05  -0.447914E-05\n";
        let r = parse_at2(text, Path::new("NIS090.AT2")).unwrap();
        assert_eq!(r.accel.len(), 10);
        assert_eq!(r.dt, 0.01);
        assert!((r.accel[9] + 0.447914e-5 * G).abs() < 1e-15);
        assert_eq!(r.description, "KOBE 01/16/95 2046, NISHI-AKASHI, 090 (CUE)");
    }

    #[test]
    fn zero_padding_past_npts_is_dropped_other_surplus_refused() {
        let text =
            "PEER\nx\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 3, DT= 0.01 SEC\n0.1D+00 -0.2D+00 0.5E-1 0.0 0.0\n";
        let r = parse_at2(text, Path::new("o.at2")).unwrap();
        assert_eq!(r.accel.len(), 3);
        assert!((r.accel[1] + 0.2 * G).abs() < 1e-12);
        let text = text.replace("0.0 0.0", "0.0 0.1");
        let e = parse_at2(&text, Path::new("o.at2")).unwrap_err().to_string();
        assert!(e.contains("non-zero values follow"), "{e}");
        let short = parse_at2(
            "PEER\nx\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS= 4, DT= 0.01 SEC\n1 2 3\n",
            Path::new("s"),
        );
        assert!(short.unwrap_err().to_string().contains("NPTS = 4 but 3 values"));
    }
}
