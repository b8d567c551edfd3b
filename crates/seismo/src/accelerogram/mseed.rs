//! MiniSEED 2 data records (SEED 2.4 manual, chapter 8 "Fixed Section of Data Header" and the
//! data-only blockettes 100, 1000 and 1001): the version ObsPy, SeisComP and every FDSN data centre
//! read.
//!
//! One trace is a run of 4096-byte records (`2^12`, Blockette 1000's record length), each a 48-byte
//! fixed header, Blockette 1000 (encoding 5, IEEE double, big-endian word order), Blockette 1001
//! (the microseconds the 0.0001 s of the header's start time cannot hold) and, when the sampling
//! rate is not a ratio of two 16-bit integers, Blockette 100 (the actual rate as a 32-bit float),
//! then the samples from byte 128: (4096 − 128)/8 = 496 samples per record, every sample the
//! 64-bit value the product computed (nothing is lost to compression or rounding).
//!
//! **Sampling rate.** SEED's header gives the rate as a factor and a multiplier (16-bit signed
//! integers): `f/−m` when the multiplier is negative, so a rate such as 1/0.0123 s = 10000/123 Hz is
//! written exactly, and libmseed (ObsPy's reader) divides the two in double precision. A rate that
//! is no such ratio (a lattice's step is any real number) is written as the nearest ratio in the
//! header and exactly to 32-bit precision in Blockette 100, which readers prefer, as ObsPy's own
//! writer does: the relative error of the rate is then below 6·10⁻⁸.
//!
//! **Time.** A simulated event has no date: time 0 of a run's clock is the nominal
//! 2000-01-01T00:00:00Z, as in the SAC records ([`super::sac::NOMINAL_ORIGIN`]); a record starting
//! 12.3456789 s into the run starts at 2000-01-01T00:00:12.345679Z (microseconds: the header's
//! 0.0001 s plus Blockette 1001's offset). The start of each further record of a trace is the
//! first sample's time plus its sample index over the rate, so no error accumulates.
//!
//! **Codes.** Network ≤ 2 characters, station ≤ 5, location ≤ 2, channel 3 (SEED's limits; longer
//! codes are refused, naming the code). A record whose component is one letter (`X`, `Y`, `Z` of
//! the scene) gets the SEED channel code band + `N` (accelerometer) + orientation: the band code
//! from the rate ([`band_code`]) and `E`, `N`, `Z` for the scene's x (east), y (north) and z (up).

pub use crate::clock::UtcTime;
use crate::error::SeismoError;

/// Bytes per record (Blockette 1000 says 2^12).
pub const RECORD_BYTES: usize = 4096;
/// Where the samples start in a record.
pub const DATA_OFFSET: usize = 128;
/// Samples per full record.
pub const SAMPLES_PER_RECORD: usize = (RECORD_BYTES - DATA_OFFSET) / 8;

/// One trace to write: its codes, the time of its first sample and its samples.
#[derive(Clone, Copy, Debug)]
pub struct MseedTrace<'a> {
    /// Network code (≤ 2 characters).
    pub network: &'a str,
    /// Station code (≤ 5 characters).
    pub station: &'a str,
    /// Location code (≤ 2 characters, may be empty).
    pub location: &'a str,
    /// Channel code (3 characters).
    pub channel: &'a str,
    /// Time of the first sample, seconds after the nominal 2000-01-01T00:00:00Z.
    pub start_s: f64,
    /// Sampling rate (Hz).
    pub sample_rate_hz: f64,
    /// The samples (written as 64-bit floats).
    pub samples: &'a [f64],
}

/// The sampling rate of an interval `dt_s` (Hz): `1/dt`, taken to the whole number or the
/// thousandth it lies within 1e-12 of (an interval of 2e-5 s is 50 000 Hz, not
/// 49 999.999 999 999 99), so that the MiniSEED header and the StationXML inventory write the
/// rate the pipeline meant, the same in both.
pub fn sample_rate(dt_s: f64) -> f64 {
    let rate = 1.0 / dt_s;
    for q in [1.0, 1000.0] {
        let snapped = (rate * q).round() / q;
        if snapped > 0.0 && ((snapped - rate) / rate).abs() < 1e-12 {
            return snapped;
        }
    }
    rate
}

/// The SEED band code of an accelerometer sampled at `rate_hz` (SEED 2.4 Appendix A, the
/// broadband family an accelerometer belongs to, its response reaching 0 Hz): `F` from 1000 Hz
/// (model-scale records above SEED's 5000 Hz keep `F`), `C` from 250, `H` from 80, `B` from 10,
/// `M` above 1, `L` at 1, `V` at 0.1 and `U` below.
pub fn band_code(rate_hz: f64) -> char {
    match rate_hz {
        r if r >= 1000.0 => 'F',
        r if r >= 250.0 => 'C',
        r if r >= 80.0 => 'H',
        r if r >= 10.0 => 'B',
        r if r > 1.05 => 'M',
        r if r > 0.5 => 'L',
        r if r > 0.05 => 'V',
        _ => 'U',
    }
}

/// The SEED channel code of a component: a 3-character code as it is, or for an axis of the scene
/// (`X`, `Y`, `Z`, either case) band + `N` + `E`/`N`/`Z`.
pub fn channel_code(component: &str, rate_hz: f64) -> Result<String, SeismoError> {
    let orientation = match component {
        c if c.len() == 3 => return Ok(c.to_string()),
        "X" | "x" => 'E',
        "Y" | "y" => 'N',
        "Z" | "z" => 'Z',
        _ => {
            return Err(SeismoError::parameter(
                "component",
                component,
                "a SEED channel code of 3 characters or an axis X, Y or Z",
            ));
        }
    };
    Ok(format!("{}N{orientation}", band_code(rate_hz)))
}

/// The header's factor and multiplier for `rate`, and whether they give it exactly (in double
/// precision, as libmseed divides them).
fn factor_multiplier(rate: f64) -> ((i16, i16), bool) {
    // A ratio p/q of 16-bit integers equal to the rate, the smallest q first.
    for q in 1..=i16::MAX as i64 {
        let p = (rate * q as f64).round();
        if p >= 1.0 && p <= i16::MAX as f64 && p / q as f64 == rate {
            return ((p as i16, -(q as i16)), true);
        }
        if rate * q as f64 > i16::MAX as f64 {
            break;
        }
    }
    // A period p/q of 16-bit integers (rates below 1 Hz), e.g. 1/120 Hz.
    let period = 1.0 / rate;
    for q in 1..=i16::MAX as i64 {
        let p = (period * q as f64).round();
        if p >= 1.0 && p <= i16::MAX as f64 && q as f64 / p == rate {
            return ((-(p as i16), q as i16), true);
        }
        if period * q as f64 > i16::MAX as f64 {
            break;
        }
    }
    // The nearest such ratio; Blockette 100 then carries the rate.
    let approx = if rate >= 1.0 {
        ((rate.round().min(i16::MAX as f64)) as i16, 1)
    } else {
        (-(period.round().clamp(1.0, i16::MAX as f64) as i16), 1)
    };
    (approx, false)
}

fn code(field: &str, value: &str, max: usize, min: usize) -> Result<Vec<u8>, SeismoError> {
    let ok = value.len() >= min
        && value.len() <= max
        && value.bytes().all(|b| b.is_ascii_uppercase() || b.is_ascii_digit() || b.is_ascii_lowercase());
    if !ok {
        return Err(SeismoError::parameter(
            field,
            value,
            format!("{min}–{max} ASCII letters or digits (MiniSEED 2's limit)"),
        ));
    }
    let mut out = value.to_ascii_uppercase().into_bytes();
    out.resize(max, b' ');
    Ok(out)
}

/// The bytes of a trace as MiniSEED 2 records (see the module documentation).
pub fn mseed_bytes(trace: &MseedTrace<'_>) -> Result<Vec<u8>, SeismoError> {
    let rate = trace.sample_rate_hz;
    if !(rate.is_finite() && rate > 0.0) {
        return Err(SeismoError::parameter("sample_rate_hz", rate, "a finite rate > 0 Hz"));
    }
    if let Some(v) = trace.samples.iter().find(|v| !v.is_finite()) {
        return Err(SeismoError::parameter("samples", v, "finite values"));
    }
    let station = code("station", trace.station, 5, 1)?;
    let location = code("location", trace.location, 2, 0)?;
    let channel = code("channel", trace.channel, 3, 3)?;
    let network = code("network", trace.network, 2, 1)?;
    let ((factor, multiplier), exact) = factor_multiplier(rate);
    let chunks: Vec<&[f64]> =
        if trace.samples.is_empty() { vec![&[]] } else { trace.samples.chunks(SAMPLES_PER_RECORD).collect() };
    let mut out = Vec::with_capacity(chunks.len() * RECORD_BYTES);
    let mut first = 0usize;
    for (k, chunk) in chunks.iter().enumerate() {
        if k >= 999_999 {
            return Err(SeismoError::parameter("samples", trace.samples.len(), "at most 999 999 records per trace"));
        }
        let t = UtcTime::from_nominal(trace.start_s + first as f64 / rate)?;
        if !(0..=9999).contains(&t.year) {
            return Err(SeismoError::parameter("start_s", trace.start_s, "a time in the years 0–9999"));
        }
        let mut r = vec![0u8; RECORD_BYTES];
        r[0..6].copy_from_slice(format!("{:06}", k + 1).as_bytes());
        r[6] = b'D';
        r[7] = b' ';
        r[8..13].copy_from_slice(&station);
        r[13..15].copy_from_slice(&location);
        r[15..18].copy_from_slice(&channel);
        r[18..20].copy_from_slice(&network);
        r[20..22].copy_from_slice(&(t.year as u16).to_be_bytes());
        r[22..24].copy_from_slice(&t.day_of_year.to_be_bytes());
        r[24] = t.hour;
        r[25] = t.minute;
        r[26] = t.second;
        let (ticks, micros) = (t.microsecond / 100, (t.microsecond % 100) as i8);
        // Blockette 1001's offset is −50…+49 µs from the header's 0.0001 s.
        let (ticks, micros) = if micros >= 50 { (ticks + 1, micros - 100) } else { (ticks, micros) };
        // 10000 ticks would be the next second: keep 9999 and put the rest in the offset.
        let (ticks, micros) = if ticks == 10_000 { (9_999u32, micros + 100) } else { (ticks, micros) };
        r[28..30].copy_from_slice(&(ticks as u16).to_be_bytes());
        r[30..32].copy_from_slice(&(chunk.len() as u16).to_be_bytes());
        r[32..34].copy_from_slice(&factor.to_be_bytes());
        r[34..36].copy_from_slice(&multiplier.to_be_bytes());
        r[39] = if exact { 2 } else { 3 };
        r[44..46].copy_from_slice(&(DATA_OFFSET as u16).to_be_bytes());
        r[46..48].copy_from_slice(&48u16.to_be_bytes());
        // Blockette 1000: encoding 5 (IEEE double), word order 1 (big-endian), length 2^12.
        r[48..50].copy_from_slice(&1000u16.to_be_bytes());
        r[50..52].copy_from_slice(&56u16.to_be_bytes());
        r[52] = 5;
        r[53] = 1;
        r[54] = 12;
        // Blockette 1001: timing quality unset (0), the microsecond offset, frame count 0.
        r[56..58].copy_from_slice(&1001u16.to_be_bytes());
        r[58..60].copy_from_slice(&(if exact { 0u16 } else { 64 }).to_be_bytes());
        r[61] = micros as u8;
        if !exact {
            // Blockette 100: the actual sampling rate.
            r[64..66].copy_from_slice(&100u16.to_be_bytes());
            r[66..68].copy_from_slice(&0u16.to_be_bytes());
            r[68..72].copy_from_slice(&(rate as f32).to_be_bytes());
        }
        for (j, v) in chunk.iter().enumerate() {
            let at = DATA_OFFSET + 8 * j;
            r[at..at + 8].copy_from_slice(&v.to_be_bytes());
        }
        out.extend_from_slice(&r);
        first += chunk.len();
    }
    Ok(out)
}

/// A trace read back from records this module wrote (for tests and checks; other writers' records
/// — Steim compression, other record lengths — are for ObsPy or libmseed).
#[derive(Clone, Debug, PartialEq)]
pub struct MseedRead {
    /// Network, station, location and channel codes (trailing spaces removed).
    pub codes: [String; 4],
    /// Time of the first sample (s after the nominal 2000-01-01T00:00:00Z), to the microsecond.
    pub start: UtcTime,
    /// Sampling rate as a reader takes it: Blockette 100's when present, else factor/multiplier.
    pub sample_rate_hz: f64,
    /// Samples.
    pub samples: Vec<f64>,
}

/// Reads back the records of one trace written by [`mseed_bytes`].
pub fn parse_mseed(bytes: &[u8]) -> Result<MseedRead, SeismoError> {
    let bad = |what: &str| SeismoError::parameter("MiniSEED record", what, "a record written by stickslip");
    if bytes.is_empty() || !bytes.len().is_multiple_of(RECORD_BYTES) {
        return Err(bad("length not a multiple of 4096"));
    }
    let text = |r: &[u8], a: usize, b: usize| String::from_utf8_lossy(&r[a..b]).trim_end().to_string();
    let be16 = |r: &[u8], a: usize| u16::from_be_bytes([r[a], r[a + 1]]);
    let first = &bytes[..RECORD_BYTES];
    let codes = [text(first, 18, 20), text(first, 8, 13), text(first, 13, 15), text(first, 15, 18)];
    if be16(first, 48) != 1000 || first[52] != 5 || first[53] != 1 || first[54] != 12 {
        return Err(bad("no Blockette 1000 of 64-bit big-endian floats in 4096-byte records"));
    }
    let (factor, multiplier) = (be16(first, 32) as i16 as f64, be16(first, 34) as i16 as f64);
    let nominal = match (factor > 0.0, multiplier > 0.0) {
        (true, true) => factor * multiplier,
        (true, false) => -factor / multiplier,
        (false, true) => -multiplier / factor,
        (false, false) => 1.0 / (factor * multiplier),
    };
    let sample_rate_hz = if first[39] == 3 && be16(first, 64) == 100 {
        f64::from(f32::from_be_bytes([first[68], first[69], first[70], first[71]]))
    } else {
        nominal
    };
    let year = be16(first, 20) as i32;
    let days_before_year = {
        let y = i64::from(year) - 1;
        365 * (y - 1999) + (y.div_euclid(4) - 1999 / 4) - (y.div_euclid(100) - 1999 / 100)
            + (y.div_euclid(400) - 1999 / 400)
    };
    let seconds = (days_before_year + i64::from(be16(first, 22)) - 1) as f64 * 86_400.0
        + f64::from(first[24]) * 3600.0
        + f64::from(first[25]) * 60.0
        + f64::from(first[26]);
    let micros = i64::from(be16(first, 28)) * 100 + i64::from(first[61] as i8);
    let start = UtcTime::from_nominal(seconds + micros as f64 * 1e-6)?;
    let mut samples = Vec::new();
    for r in bytes.chunks(RECORD_BYTES) {
        let n = be16(r, 30) as usize;
        let at = be16(r, 44) as usize;
        if at + 8 * n > RECORD_BYTES {
            return Err(bad("more samples than the record holds"));
        }
        samples.extend((0..n).map(|j| {
            let b = &r[at + 8 * j..at + 8 * j + 8];
            f64::from_be_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]])
        }));
    }
    Ok(MseedRead { codes, start, sample_rate_hz, samples })
}

/// The MiniSEED record format: acceleration in m/s² as 64-bit floats, the record's network,
/// station and location codes, the channel code from its component ([`channel_code`]), the first
/// sample at the run's clock on the nominal date (the event's origin, when known, at
/// 2000-01-01T00:00:00Z, as in SAC). The station metadata (position, orientation, units) is in
/// the output folder's StationXML inventory.
#[derive(Clone, Copy, Debug)]
pub struct Mseed;

impl super::RecordFormat for Mseed {
    fn name(&self) -> &'static str {
        "mseed"
    }

    fn extension(&self) -> &'static str {
        "mseed"
    }

    fn encode(&self, r: &super::RecordFile<'_>) -> Result<Vec<u8>, SeismoError> {
        let rate = sample_rate(r.dt_s);
        let channel = channel_code(r.component, rate)?;
        mseed_bytes(&MseedTrace {
            network: r.network,
            station: r.station,
            location: r.location,
            channel: &channel,
            start_s: r.begin_s - r.origin_s.unwrap_or(0.0),
            sample_rate_hz: rate,
            samples: r.accel_m_s2,
        })
    }
}
