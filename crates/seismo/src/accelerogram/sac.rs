//! SAC binary files (header version 6, little-endian): writer and reader of one evenly sampled trace.
//!
//! Layout (IRIS SAC manual, "SAC Data File Format"): a 632-byte header — 70 4-byte floats
//! (words 0–69), 40 4-byte integers (words 70–109; the last five are logicals, 0 or 1), then
//! 24 eight-character string slots (bytes 440–631, `KEVNM` takes two slots, so 23 string
//! fields) — followed by `NPTS` 4-byte floats. Undefined fields are `−12345.0`, `−12345` and
//! `"-12345  "`. Enumerated values used here: `ITIME = 1`, `IUNKN = 5`, `IACC = 8` (acceleration
//! in **nm/s²**, SAC's own unit), `IB = 9`, `IO = 11`.
//!
//! What the writer fills: `DELTA`, `B`, `E = B + (NPTS−1)·DELTA`, `NPTS`, `DEPMIN`, `DEPMAX`,
//! `DEPMEN` (of the values as stored), `NVHDR = 6`, `IFTYPE = ITIME`, `LEVEN = 1`, `LOVROK = 1`,
//! `LPSPOL = 1`, `LCALDA = 0` (so SAC never recomputes `DIST`/`AZ` from coordinates that may be
//! plain model numbers), `IDEP` from [`SacUnit`], `KSTNM`, `KCMPNM`, `KNETWK`, `KEVNM`,
//! the reference time `NZYEAR…NZMSEC` with `IZTYPE = IO` when given with `O = 0`, `IB`
//! otherwise (else undefined and `IZTYPE = IUNKN`), `O` when the origin time is known, `EVLA`, `EVLO`, `EVDP`, `STLA`, `STLO`,
//! `STEL`, `DIST`, `CMPAZ`, `CMPINC`, `MAG`, `USER0–9` and `KUSER0–2` where given. SAC reads
//! `EVLA/EVLO/STLA/STLO` as degrees, `EVDP` and `DIST` as km and `STEL` as m: the record format
//! ([`Sac`]) leaves the degrees undefined and puts a node's position (m) in `USER7–9`.
//!
//! Times in SAC are seconds relative to the reference time: `B` is the first sample, `O` the
//! event origin on the same clock. A simulated event has no date: the record format ([`Sac`])
//! gives a record whose origin is known the nominal reference time [`NOMINAL_ORIGIN`]
//! (2000-01-01T00:00:00.000) at that origin, `O = 0` and `IZTYPE = IO`, so that a reader (ObsPy)
//! places each sample at origin + `B` + k·`DELTA` instead of at 1970-01-01.
//!
//! The reader widens header floats to f64 through their shortest decimal form (a `DELTA` written
//! from 0.01 reads as 0.01). It takes either byte order (found from `NVHDR`, which must be 6 or 7) and reads only
//! evenly sampled time series (`LEVEN = 1`, `IFTYPE = ITIME`); a version-7 footer is ignored.

use std::path::Path;

use crate::error::SeismoError;

/// Float header words (index into [`SacHeader::floats`]).
pub mod word {
    /// Sampling interval (s).
    pub const DELTA: usize = 0;
    /// Minimum of the dependent variable.
    pub const DEPMIN: usize = 1;
    /// Maximum of the dependent variable.
    pub const DEPMAX: usize = 2;
    /// Begin time (s, relative to the reference time).
    pub const B: usize = 5;
    /// End time (s).
    pub const E: usize = 6;
    /// Event origin time (s).
    pub const O: usize = 7;
    /// Station latitude (deg).
    pub const STLA: usize = 31;
    /// Station longitude (deg).
    pub const STLO: usize = 32;
    /// Station elevation (m).
    pub const STEL: usize = 33;
    /// Event latitude (deg).
    pub const EVLA: usize = 35;
    /// Event longitude (deg).
    pub const EVLO: usize = 36;
    /// Event depth (km).
    pub const EVDP: usize = 38;
    /// Event magnitude.
    pub const MAG: usize = 39;
    /// USER0; USER0–9 are words 40–49.
    pub const USER0: usize = 40;
    /// Station–event distance (km).
    pub const DIST: usize = 50;
    /// Mean of the dependent variable.
    pub const DEPMEN: usize = 56;
    /// Component azimuth (deg clockwise from north).
    pub const CMPAZ: usize = 57;
    /// Component incidence (deg from vertical).
    pub const CMPINC: usize = 58;
    /// Integer words, as indices into [`super::SacHeader::ints`] (word − 70).
    pub mod int {
        /// Reference year.
        pub const NZYEAR: usize = 0;
        /// Reference day of year.
        pub const NZJDAY: usize = 1;
        /// Reference hour.
        pub const NZHOUR: usize = 2;
        /// Reference minute.
        pub const NZMIN: usize = 3;
        /// Reference second.
        pub const NZSEC: usize = 4;
        /// Reference millisecond.
        pub const NZMSEC: usize = 5;
        /// Header version.
        pub const NVHDR: usize = 6;
        /// Number of samples.
        pub const NPTS: usize = 9;
        /// File type.
        pub const IFTYPE: usize = 15;
        /// Type of the dependent variable.
        pub const IDEP: usize = 16;
        /// Reference time equivalence.
        pub const IZTYPE: usize = 17;
        /// Evenly spaced (logical).
        pub const LEVEN: usize = 35;
        /// Positive polarity (logical).
        pub const LPSPOL: usize = 36;
        /// May be overwritten (logical).
        pub const LOVROK: usize = 37;
        /// Compute distance and azimuth from coordinates (logical).
        pub const LCALDA: usize = 38;
    }
    /// String fields, as indices into [`super::SacHeader::strings`].
    pub mod string {
        /// Station name.
        pub const KSTNM: usize = 0;
        /// Event name (16 characters).
        pub const KEVNM: usize = 1;
        /// Location code (hole).
        pub const KHOLE: usize = 2;
        /// KUSER0; KUSER0–2 are fields 16–18.
        pub const KUSER0: usize = 16;
        /// Component name.
        pub const KCMPNM: usize = 19;
        /// Network name.
        pub const KNETWK: usize = 20;
    }
}

/// Undefined float.
pub const UNDEF_F: f32 = -12345.0;
/// Undefined integer.
pub const UNDEF_I: i32 = -12345;
/// Undefined string (8 characters).
pub const UNDEF_K: &str = "-12345  ";
/// Header length (bytes).
pub const HEADER_BYTES: usize = 632;

const ITIME: i32 = 1;
const IUNKN: i32 = 5;
/// `IDEP` of an acceleration trace (values in nm/s²).
pub const IACC: i32 = 8;
const IB: i32 = 9;
const IO: i32 = 11;

/// The nominal reference time of a simulated event's records (2000-01-01T00:00:00.000, day 1):
/// a simulation has no date; this one is the event's origin, `O = 0` (see the module's notes).
pub const NOMINAL_ORIGIN: SacTime =
    SacTime { year: 2000, day_of_year: 1, hour: 0, minute: 0, second: 0, millisecond: 0 };

/// Names of the 23 string fields, in file order.
pub const STRING_FIELDS: [&str; 23] = [
    "KSTNM", "KEVNM", "KHOLE", "KO", "KA", "KT0", "KT1", "KT2", "KT3", "KT4", "KT5", "KT6", "KT7", "KT8", "KT9", "KF",
    "KUSER0", "KUSER1", "KUSER2", "KCMPNM", "KNETWK", "KDATRD", "KINST",
];

/// Unit of the values written, and the `IDEP` that says it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SacUnit {
    /// nm/s², `IDEP = IACC` — SAC's definition of an acceleration trace (values are m/s² × 1e9).
    NanometrePerSecond2,
    /// m/s² as they are, `IDEP = IUNKN` (SAC has no code for m/s²).
    MetrePerSecond2,
}

/// Reference date and time of a SAC file (`NZYEAR … NZMSEC`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SacTime {
    /// Year.
    pub year: i32,
    /// Day of year, 1–366.
    pub day_of_year: i32,
    /// Hour, 0–23.
    pub hour: i32,
    /// Minute, 0–59.
    pub minute: i32,
    /// Second, 0–59.
    pub second: i32,
    /// Millisecond, 0–999.
    pub millisecond: i32,
}

/// What a SAC file says about its trace, besides the samples.
#[derive(Clone, Debug, PartialEq)]
pub struct SacMeta {
    /// Station (`KSTNM`), e.g. the node: up to 8 ASCII characters; empty = undefined.
    pub station: String,
    /// Component (`KCMPNM`), up to 8 ASCII characters; empty = undefined.
    pub component: String,
    /// Network (`KNETWK`), up to 8 ASCII characters; empty = undefined.
    pub network: String,
    /// Location code (`KHOLE`), up to 8 ASCII characters; empty = undefined.
    pub location: String,
    /// Event name (`KEVNM`), e.g. the event id: up to 16 ASCII characters; empty = undefined.
    pub event: String,
    /// Begin time `B` of the first sample relative to the reference time (s).
    pub begin: f64,
    /// Event origin time `O` relative to the reference time (s).
    pub origin: Option<f64>,
    /// Reference date and time; `None` leaves it undefined.
    pub reference: Option<SacTime>,
    /// Event latitude `EVLA` (deg, or a plain model coordinate).
    pub event_lat: Option<f64>,
    /// Event longitude `EVLO` (deg, or a plain model coordinate).
    pub event_lon: Option<f64>,
    /// Event depth `EVDP` (km, or a plain model coordinate).
    pub event_depth: Option<f64>,
    /// Station latitude `STLA` (deg, or a plain model coordinate).
    pub station_lat: Option<f64>,
    /// Station longitude `STLO` (deg, or a plain model coordinate).
    pub station_lon: Option<f64>,
    /// Station elevation `STEL` (m).
    pub station_elevation: Option<f64>,
    /// Station–event distance `DIST` (km, or a plain model distance).
    pub distance: Option<f64>,
    /// Component azimuth `CMPAZ` (deg clockwise from north).
    pub component_azimuth: Option<f64>,
    /// Component incidence `CMPINC` (deg from vertical: 90 for horizontal).
    pub component_incidence: Option<f64>,
    /// Magnitude `MAG`.
    pub magnitude: Option<f64>,
    /// `USER0`–`USER9`, free numbers (e.g. model-scale metadata).
    pub user: [Option<f64>; 10],
    /// `KUSER0`–`KUSER2`, labels for the user numbers: up to 8 ASCII characters each.
    pub user_labels: [String; 3],
    /// Unit of the stored values [nm/s², `IDEP = IACC`].
    pub unit: SacUnit,
}

impl Default for SacMeta {
    fn default() -> Self {
        SacMeta {
            station: String::new(),
            component: String::new(),
            network: String::new(),
            location: String::new(),
            event: String::new(),
            begin: 0.0,
            origin: None,
            reference: None,
            event_lat: None,
            event_lon: None,
            event_depth: None,
            station_lat: None,
            station_lon: None,
            station_elevation: None,
            distance: None,
            component_azimuth: None,
            component_incidence: None,
            magnitude: None,
            user: [None; 10],
            user_labels: [String::new(), String::new(), String::new()],
            unit: SacUnit::NanometrePerSecond2,
        }
    }
}

/// The raw header: 70 floats, 40 integers (incl. logicals), 23 string fields (trailing blanks kept).
#[derive(Clone, Debug, PartialEq)]
pub struct SacHeader {
    /// Float words 0–69.
    pub floats: [f32; 70],
    /// Integer words 70–109 (index = word − 70).
    pub ints: [i32; 40],
    /// String fields in [`STRING_FIELDS`] order.
    pub strings: Vec<String>,
}

/// A SAC file read back.
#[derive(Clone, Debug, PartialEq)]
pub struct SacTrace {
    /// The whole header as stored.
    pub header: SacHeader,
    /// What the header says, in the writer's terms (undefined fields are `None` / empty).
    pub meta: SacMeta,
    /// `IDEP` as stored.
    pub idep: i32,
    /// Sampling interval (s), `DELTA` widened through its shortest decimal.
    pub dt: f64,
    /// Samples as stored.
    pub data: Vec<f32>,
}

impl SacTrace {
    /// Samples in m/s²: `IACC` values (nm/s²) × 1e-9; `IUNKN` values are taken as m/s² (what this
    /// writer means by it). Any other `IDEP` is refused.
    pub fn accel_si(&self) -> Result<Vec<f64>, SeismoError> {
        let factor = match self.idep {
            IACC => 1e-9,
            IUNKN | UNDEF_I => 1.0,
            other => {
                return Err(SeismoError::parameter(
                    "IDEP",
                    other,
                    "IACC (8, nm/s²) or IUNKN (5, read as m/s²) for an acceleration trace",
                ));
            }
        };
        Ok(self.data.iter().map(|&v| v as f64 * factor).collect())
    }
}

fn checked_string(name: &str, s: &str, width: usize) -> Result<String, SeismoError> {
    if s.is_empty() {
        let mut u = String::from("-12345");
        while u.len() < width {
            u.push(' ');
        }
        return Ok(u);
    }
    if s.len() > width || !s.bytes().all(|b| (0x20..0x7f).contains(&b)) {
        return Err(SeismoError::parameter(
            name,
            format!("{s:?}"),
            format!("at most {width} printable ASCII characters"),
        ));
    }
    Ok(format!("{s:<width$}"))
}

fn checked_f32(name: &str, v: Option<f64>) -> Result<f32, SeismoError> {
    match v {
        None => Ok(UNDEF_F),
        Some(x) if x.is_finite() && x.abs() <= f32::MAX as f64 => Ok(x as f32),
        Some(x) => Err(SeismoError::parameter(name, x, "a finite number within f32 range")),
    }
}

/// The bytes of a SAC file holding `accel` (m/s², sampled every `dt` s).
pub fn sac_bytes(accel: &[f64], dt: f64, meta: &SacMeta) -> Result<Vec<u8>, SeismoError> {
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(SeismoError::parameter("dt", format!("{dt} s"), "a finite Δt > 0 s"));
    }
    if accel.is_empty() || accel.len() > i32::MAX as usize {
        return Err(SeismoError::parameter("accel.len()", accel.len(), "1 … 2³¹−1 samples"));
    }
    let factor = match meta.unit {
        SacUnit::NanometrePerSecond2 => 1e9,
        SacUnit::MetrePerSecond2 => 1.0,
    };
    let mut data = Vec::with_capacity(accel.len());
    for (i, &a) in accel.iter().enumerate() {
        let v = a * factor;
        if !(v.is_finite() && v.abs() <= f32::MAX as f64) {
            return Err(SeismoError::parameter(
                format!("accel[{i}]"),
                a,
                "finite values within f32 range once in the file's unit",
            ));
        }
        data.push(v as f32);
    }

    let mut f = [UNDEF_F; 70];
    let mut n = [UNDEF_I; 40];
    f[word::DELTA] = checked_f32("dt", Some(dt))?;
    f[word::B] = checked_f32("begin", Some(meta.begin))?;
    f[word::E] = checked_f32("begin", Some(meta.begin + (accel.len() - 1) as f64 * dt))?;
    f[word::O] = checked_f32("origin", meta.origin)?;
    let (mut lo, mut hi, mut sum) = (f32::INFINITY, f32::NEG_INFINITY, 0.0f64);
    for &v in &data {
        lo = lo.min(v);
        hi = hi.max(v);
        sum += v as f64;
    }
    f[word::DEPMIN] = lo;
    f[word::DEPMAX] = hi;
    f[word::DEPMEN] = (sum / data.len() as f64) as f32;
    f[word::STLA] = checked_f32("station_lat", meta.station_lat)?;
    f[word::STLO] = checked_f32("station_lon", meta.station_lon)?;
    f[word::STEL] = checked_f32("station_elevation", meta.station_elevation)?;
    f[word::EVLA] = checked_f32("event_lat", meta.event_lat)?;
    f[word::EVLO] = checked_f32("event_lon", meta.event_lon)?;
    f[word::EVDP] = checked_f32("event_depth", meta.event_depth)?;
    f[word::MAG] = checked_f32("magnitude", meta.magnitude)?;
    f[word::DIST] = checked_f32("distance", meta.distance)?;
    f[word::CMPAZ] = checked_f32("component_azimuth", meta.component_azimuth)?;
    f[word::CMPINC] = checked_f32("component_incidence", meta.component_incidence)?;
    for (k, u) in meta.user.iter().enumerate() {
        f[word::USER0 + k] = checked_f32(&format!("user[{k}]"), *u)?;
    }

    use word::int::*;
    n[NVHDR] = 6;
    n[NPTS] = accel.len() as i32;
    n[IFTYPE] = ITIME;
    n[IDEP] = match meta.unit {
        SacUnit::NanometrePerSecond2 => IACC,
        SacUnit::MetrePerSecond2 => IUNKN,
    };
    n[IZTYPE] = IUNKN;
    if let Some(t) = meta.reference {
        let fields = [
            ("reference.year", t.year, 0, 9999),
            ("reference.day_of_year", t.day_of_year, 1, 366),
            ("reference.hour", t.hour, 0, 23),
            ("reference.minute", t.minute, 0, 59),
            ("reference.second", t.second, 0, 59),
            ("reference.millisecond", t.millisecond, 0, 999),
        ];
        for (k, (name, v, min, max)) in fields.into_iter().enumerate() {
            if !(min..=max).contains(&v) {
                return Err(SeismoError::parameter(name, v, format!("{min} … {max}")));
            }
            n[NZYEAR + k] = v;
        }
        // The reference is the origin when `O` is 0 there, else the first sample.
        n[IZTYPE] = if meta.origin == Some(0.0) { IO } else { IB };
    }
    n[LEVEN] = 1;
    n[LPSPOL] = 1;
    n[LOVROK] = 1;
    n[LCALDA] = 0;

    let mut k: Vec<String> = vec![UNDEF_K.to_string(); 23];
    k[word::string::KEVNM] = format!("{UNDEF_K}        ");
    k[word::string::KSTNM] = checked_string("station", &meta.station, 8)?;
    k[word::string::KEVNM] = checked_string("event", &meta.event, 16)?;
    k[word::string::KHOLE] = checked_string("location", &meta.location, 8)?;
    k[word::string::KCMPNM] = checked_string("component", &meta.component, 8)?;
    k[word::string::KNETWK] = checked_string("network", &meta.network, 8)?;
    for (j, label) in meta.user_labels.iter().enumerate() {
        k[word::string::KUSER0 + j] = checked_string(&format!("user_labels[{j}]"), label, 8)?;
    }

    let mut out = Vec::with_capacity(HEADER_BYTES + 4 * data.len());
    for v in f {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for v in n {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for s in &k {
        out.extend_from_slice(s.as_bytes());
    }
    debug_assert_eq!(out.len(), HEADER_BYTES);
    for v in data {
        out.extend_from_slice(&v.to_le_bytes());
    }
    Ok(out)
}

/// The SAC format: acceleration in nm/s² (`IDEP = IACC`), the record's names in `KSTNM`,
/// `KCMPNM`, `KNETWK`, `KHOLE`, `KEVNM`; its position x, y, z (m, the scene's coordinates) in
/// `USER7`–`USER9` and its height z also in `STEL` (m) — `STLA`/`STLO` are degrees of latitude
/// and longitude, which a block has not, so they stay undefined; the component's orientation in
/// `CMPINC`/`CMPAZ`; the magnitude in `MAG`; the labelled number groups in `USER0`… in order
/// (at most seven numbers with a position), each group's label in the next of `KUSER0`–`KUSER2`.
pub const POSITION_USER: usize = 7;

/// The SAC record format (see [`POSITION_USER`] for where it puts what).
#[derive(Clone, Copy, Debug)]
pub struct Sac;

impl super::RecordFormat for Sac {
    fn name(&self) -> &'static str {
        "sac"
    }

    fn extension(&self) -> &'static str {
        "SAC"
    }

    fn encode(&self, r: &super::RecordFile<'_>) -> Result<Vec<u8>, SeismoError> {
        let mut user = [None; 10];
        let mut user_labels: [String; 3] = Default::default();
        if r.numbers.len() > user_labels.len() {
            return Err(SeismoError::parameter("numbers", r.numbers.len(), "at most 3 labelled groups (KUSER0–2)"));
        }
        let mut k = 0;
        for (g, (label, values)) in r.numbers.iter().enumerate() {
            user_labels[g] = label.to_string();
            for &v in values.iter() {
                let slot = user
                    .get_mut(k)
                    .ok_or_else(|| SeismoError::parameter("numbers", k + 1, "at most 10 numbers in all (USER0–9)"))?;
                *slot = Some(v);
                k += 1;
            }
        }
        if let Some(p) = r.position_m {
            if k > POSITION_USER {
                return Err(SeismoError::parameter(
                    "numbers",
                    k,
                    "at most 7 numbers with a position (USER0–6; the position takes USER7–9)",
                ));
            }
            for (c, v) in p.iter().enumerate() {
                user[POSITION_USER + c] = Some(*v);
            }
        }
        let meta = SacMeta {
            station: r.station.to_string(),
            component: r.component.to_string(),
            network: r.network.to_string(),
            location: r.location.to_string(),
            event: r.event.to_string(),
            // On the nominal clock the origin is 0: the first sample's time counts from it.
            begin: r.begin_s - r.origin_s.unwrap_or(0.0),
            station_elevation: r.position_m.map(|p| p[2]),
            component_incidence: r.orientation.map(|o| o.incidence_deg),
            component_azimuth: r.orientation.map(|o| o.azimuth_deg),
            magnitude: r.magnitude,
            origin: r.origin_s.map(|_| 0.0),
            reference: r.origin_s.map(|_| NOMINAL_ORIGIN),
            user,
            user_labels,
            unit: SacUnit::NanometrePerSecond2,
            ..SacMeta::default()
        };
        sac_bytes(r.accel_m_s2, r.dt_s, &meta)
    }
}

/// Writes a SAC file (see [`sac_bytes`]).
pub fn write_sac(path: &Path, accel: &[f64], dt: f64, meta: &SacMeta) -> Result<(), SeismoError> {
    let bytes = sac_bytes(accel, dt, meta)?;
    std::fs::write(path, bytes).map_err(|source| SeismoError::Io { path: path.to_path_buf(), source })
}

/// Reads a SAC file.
pub fn read_sac(path: &Path) -> Result<SacTrace, SeismoError> {
    let bytes = std::fs::read(path).map_err(|source| SeismoError::Io { path: path.to_path_buf(), source })?;
    parse_sac(&bytes, path)
}

/// Parses the bytes of a SAC file; `path` only names it in errors.
pub fn parse_sac(bytes: &[u8], path: &Path) -> Result<SacTrace, SeismoError> {
    let corrupt = |what: String| SeismoError::Format { path: path.to_path_buf(), what };
    if bytes.len() < HEADER_BYTES {
        return Err(corrupt(format!("{} bytes: a SAC header has {HEADER_BYTES}", bytes.len())));
    }
    let word_at = |w: usize| -> [u8; 4] { [bytes[4 * w], bytes[4 * w + 1], bytes[4 * w + 2], bytes[4 * w + 3]] };
    let nvhdr_word = word_at(70 + word::int::NVHDR);
    let little = match (i32::from_le_bytes(nvhdr_word), i32::from_be_bytes(nvhdr_word)) {
        (6 | 7, _) => true,
        (_, 6 | 7) => false,
        (le, _) => return Err(corrupt(format!("NVHDR = {le}: not a SAC file of header version 6 or 7"))),
    };
    let f32_at = |w: usize| if little { f32::from_le_bytes(word_at(w)) } else { f32::from_be_bytes(word_at(w)) };
    let i32_at = |w: usize| if little { i32::from_le_bytes(word_at(w)) } else { i32::from_be_bytes(word_at(w)) };
    let mut floats = [0.0f32; 70];
    for (w, v) in floats.iter_mut().enumerate() {
        *v = f32_at(w);
    }
    let mut ints = [0i32; 40];
    for (w, v) in ints.iter_mut().enumerate() {
        *v = i32_at(70 + w);
    }
    let mut strings = Vec::with_capacity(23);
    let mut at = 440;
    for k in 0..23 {
        let width = if k == word::string::KEVNM { 16 } else { 8 };
        strings.push(String::from_utf8_lossy(&bytes[at..at + width]).into_owned());
        at += width;
    }
    use word::int::*;
    if ints[LEVEN] != 1 || ints[IFTYPE] != ITIME {
        return Err(corrupt(format!(
            "LEVEN = {}, IFTYPE = {}: only evenly sampled time series (LEVEN = 1, IFTYPE = ITIME = 1) are read",
            ints[LEVEN], ints[IFTYPE]
        )));
    }
    let npts = ints[NPTS];
    if npts < 0 {
        return Err(corrupt(format!("NPTS = {npts}")));
    }
    let npts = npts as usize;
    if bytes.len() < HEADER_BYTES + 4 * npts {
        return Err(corrupt(format!("NPTS = {npts} but the file holds {} data bytes", bytes.len() - HEADER_BYTES)));
    }
    let delta = floats[word::DELTA];
    if !(delta > 0.0 && delta.is_finite()) {
        return Err(corrupt(format!("DELTA = {delta} must be positive")));
    }
    let data: Vec<f32> = (0..npts).map(|i| f32_at(HEADER_BYTES / 4 + i)).collect();

    let opt = |w: usize| (floats[w] != UNDEF_F).then_some(widen(floats[w]));
    let text = |k: usize| {
        let t = strings[k].trim_end_matches(['\0', ' ']).to_string();
        if t == "-12345" { String::new() } else { t }
    };
    let reference = (ints[NZYEAR..=NZMSEC].iter().all(|&v| v != UNDEF_I)).then(|| SacTime {
        year: ints[NZYEAR],
        day_of_year: ints[NZJDAY],
        hour: ints[NZHOUR],
        minute: ints[NZMIN],
        second: ints[NZSEC],
        millisecond: ints[NZMSEC],
    });
    let idep = ints[IDEP];
    let mut user = [None; 10];
    for (k, u) in user.iter_mut().enumerate() {
        *u = opt(word::USER0 + k);
    }
    let meta = SacMeta {
        station: text(word::string::KSTNM),
        component: text(word::string::KCMPNM),
        network: text(word::string::KNETWK),
        location: text(word::string::KHOLE),
        event: text(word::string::KEVNM),
        begin: widen(floats[word::B]),
        origin: opt(word::O),
        reference,
        event_lat: opt(word::EVLA),
        event_lon: opt(word::EVLO),
        event_depth: opt(word::EVDP),
        station_lat: opt(word::STLA),
        station_lon: opt(word::STLO),
        station_elevation: opt(word::STEL),
        distance: opt(word::DIST),
        component_azimuth: opt(word::CMPAZ),
        component_incidence: opt(word::CMPINC),
        magnitude: opt(word::MAG),
        user,
        user_labels: [text(word::string::KUSER0), text(word::string::KUSER0 + 1), text(word::string::KUSER0 + 2)],
        unit: if idep == IACC { SacUnit::NanometrePerSecond2 } else { SacUnit::MetrePerSecond2 },
    };
    Ok(SacTrace { header: SacHeader { floats, ints, strings }, meta, idep, dt: widen(delta), data })
}

/// The f64 nearest to the shortest decimal that reads back as `v`: a DELTA of 0.01 written as f32
/// reads as 0.01, not 0.009999999776.
fn widen(v: f32) -> f64 {
    v.to_string().parse().unwrap_or(v as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn meta() -> SacMeta {
        SacMeta {
            station: "N0042".into(),
            component: "HNE".into(),
            network: "SS".into(),
            event: "s3-e17".into(),
            begin: -0.5,
            origin: Some(0.25),
            event_lat: Some(0.125), // values exact in f32, so the round trip is exact
            event_depth: Some(3.5),
            user: [Some(0.0009765625), None, None, None, None, None, None, None, None, Some(-2.0)],
            user_labels: ["scale".into(), String::new(), String::new()],
            ..SacMeta::default()
        }
    }

    #[test]
    fn round_trip_keeps_meta_and_samples() {
        let accel: Vec<f64> = (0..500).map(|i| 0.3 * (i as f64 * 0.05).sin()).collect();
        let bytes = sac_bytes(&accel, 0.01, &meta()).unwrap();
        assert_eq!(bytes.len(), HEADER_BYTES + 4 * 500);
        let back = parse_sac(&bytes, Path::new("mem.sac")).unwrap();
        assert_eq!(back.meta, meta());
        assert_eq!(back.idep, IACC);
        for (a, b) in accel.iter().zip(back.accel_si().unwrap()) {
            assert!((a - b).abs() <= 1e-7 * a.abs().max(1e-6), "{a} vs {b}"); // f32 keeps 24 bits
        }
        let mut m = meta();
        m.unit = SacUnit::MetrePerSecond2;
        let back = parse_sac(&sac_bytes(&accel, 0.01, &m).unwrap(), Path::new("m")).unwrap();
        assert_eq!(back.idep, IUNKN);
        assert_eq!(back.data[7], accel[7] as f32);
        // Decimal values of up to 7 significant digits come back exactly (shortest-decimal widening).
        let m = SacMeta { event_lat: Some(0.12), distance: Some(12.345), begin: 1.0738e-5, ..meta() };
        let back = parse_sac(&sac_bytes(&accel, 1.0738e-5, &m).unwrap(), Path::new("m")).unwrap();
        assert_eq!((back.meta.event_lat, back.meta.distance, back.meta.begin), (Some(0.12), Some(12.345), 1.0738e-5));
        assert_eq!(back.dt, 1.0738e-5);
    }

    #[test]
    fn reads_big_endian_and_refuses_bad_input() {
        let le = sac_bytes(&[1.0, 2.0, 3.0], 0.5, &meta()).unwrap();
        // Swap every 4-byte word of the numeric part (header words and data), keep the strings.
        let mut be = le.clone();
        for w in (0..110).chain(158..161) {
            be[4 * w..4 * w + 4].reverse();
        }
        let back = parse_sac(&be, Path::new("be")).unwrap();
        assert_eq!(back.data, vec![1e9, 2e9, 3e9]);
        assert_eq!(back.meta.station, "N0042");

        let long = SacMeta { station: "NODE-000123".into(), ..SacMeta::default() };
        let e = sac_bytes(&[1.0], 0.1, &long).unwrap_err().to_string();
        assert!(e.contains("station") && e.contains("NODE-000123") && e.contains("at most 8"), "{e}");
        let e = sac_bytes(&[1.0], -0.1, &SacMeta::default()).unwrap_err().to_string();
        assert!(e.contains("dt = -0.1 s"), "{e}");
        let e = parse_sac(&le[..600], Path::new("short.sac")).unwrap_err().to_string();
        assert!(e.contains("short.sac") && e.contains("632"), "{e}");
        let e = parse_sac(&le[..HEADER_BYTES + 8], Path::new("t.sac")).unwrap_err().to_string();
        assert!(e.contains("NPTS = 3"), "{e}");
    }
}
