//! FDSN StationXML 1.2 inventories: networks, stations and channels with their place,
//! orientation, sampling rate, units and response, as read by ObsPy's `read_inventory` and by FDSN
//! tools (FDSN, "FDSN StationXML", <https://docs.fdsn.org/projects/stationxml>; schema
//! <https://www.fdsn.org/xml/station/fdsn-station-1.2.xsd>).
//!
//! Layout written: `FDSNStationXML` (namespace `http://www.fdsn.org/xml/station/1`,
//! `schemaVersion="1.2"`) holding `Source`, `Sender`, `Module`, `Created`, then each `Network`
//! (`Description`) with its `Station`s (`Description`, `Latitude`, `Longitude`, `Elevation`,
//! `Site/Name`) and their `Channel`s (`Description`, `Latitude`, `Longitude`, `Elevation`,
//! `Depth`, `Azimuth`, `Dip`, `Type` GEOPHYSICAL and SYNTHESIZED, `SampleRate`, `Sensor`,
//! `Response`), in the schema's order.
//!
//! **Response.** The samples of a simulated record are the physical values themselves (one count
//! = one m/s², m/s or m). Every channel's response says so twice, as the schema and ObsPy want
//! it: an `InstrumentSensitivity` of 1 at 1 Hz from the channel's unit to `COUNTS`, and one
//! stage — a pole-zero stage (`LAPLACE (RADIANS/SECOND)`, no poles, no zeros, normalisation
//! factor 1 at 1 Hz) of gain 1 at 1 Hz between the same units. ObsPy's `remove_response` of an
//! acceleration channel with `output="ACC"` then returns the samples unchanged (when it is not
//! told to taper or remove the mean, which it does by default).
//!
//! **Numbers** are written in Rust's shortest round-trip form (`Display` of `f64`), so a sampling
//! rate such as 1/0.0123 Hz reads back as the same `f64`. Text is escaped ([`escape`]).
//!
//! **Refusals** ([`stationxml`]): a code that is empty (but a location code may be) or longer than
//! 8 characters, or holds anything but printable ASCII other than a space or a `.` (the separator
//! of the `NET.STA.LOC.CHA` ids ObsPy matches responses by); a latitude outside [−90, 90) — the
//! schema excludes 90 — or a longitude outside [−180, 180]; an azimuth outside [0, 360), a dip
//! outside [−90, 90]; a sampling rate that is not a finite number > 0; a non-finite elevation or
//! depth; a date that is not an `xs:dateTime`; an inventory with no network (the schema needs
//! one). Each error names the field (its place in the inventory and the codes), the value and
//! what is allowed.

use std::fmt::Write as _;

use crate::error::SeismoError;
pub use crate::xml::escape;
use crate::xml::is_xml_datetime;

/// Mean radius of the Earth (m), the sphere on which [`local_to_geographic`] puts a scene.
pub const EARTH_RADIUS_M: f64 = 6_371_000.0;

/// An inventory: who made it and its networks (the document's root).
#[derive(Clone, Debug)]
pub struct Inventory {
    /// Where the metadata comes from (`Source`).
    pub source: String,
    /// Who sends it (`Sender`).
    pub sender: String,
    /// The program that wrote it (`Module`).
    pub module: String,
    /// When it was made, ISO 8601 UTC, e.g. `2000-01-01T00:00:00Z` (`Created`).
    pub created_utc: String,
    /// Its networks (at least one).
    pub networks: Vec<Network>,
}

/// A network of stations.
#[derive(Clone, Debug)]
pub struct Network {
    /// Network code (1–8 characters).
    pub code: String,
    /// What the network is.
    pub description: String,
    /// Start of its epoch, ISO 8601 UTC.
    pub start_utc: String,
    /// Its stations.
    pub stations: Vec<Station>,
}

/// A station.
#[derive(Clone, Debug)]
pub struct Station {
    /// Station code (1–8 characters).
    pub code: String,
    /// Latitude (degrees north, WGS84).
    pub latitude_deg: f64,
    /// Longitude (degrees east, WGS84).
    pub longitude_deg: f64,
    /// Elevation (m).
    pub elevation_m: f64,
    /// The site's name (`Site/Name`).
    pub site_name: String,
    /// Free text, e.g. the scene's own coordinates.
    pub description: String,
    /// Start of its epoch, ISO 8601 UTC.
    pub start_utc: String,
    /// Its channels.
    pub channels: Vec<Channel>,
}

/// A channel of a station.
#[derive(Clone, Debug)]
pub struct Channel {
    /// Channel code (SEED: band, instrument, orientation; 1–8 characters).
    pub code: String,
    /// Location code (0–8 characters: may be empty).
    pub location_code: String,
    /// Latitude (degrees north).
    pub latitude_deg: f64,
    /// Longitude (degrees east).
    pub longitude_deg: f64,
    /// Elevation (m).
    pub elevation_m: f64,
    /// Depth below the station's surface (m).
    pub depth_m: f64,
    /// Azimuth of the component (degrees clockwise from north, in [0, 360)).
    pub azimuth_deg: f64,
    /// Dip of the component (degrees down from horizontal: −90 is up, 90 down).
    pub dip_deg: f64,
    /// Sampling rate (Hz).
    pub sample_rate_hz: f64,
    /// Units of the samples (one count is one unit).
    pub units: Units,
    /// Start of its epoch, ISO 8601 UTC.
    pub start_utc: String,
    /// Free text.
    pub description: String,
}

/// Units of a channel's samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Units {
    /// Acceleration, m/s² (`M/S**2`).
    Acceleration,
    /// Velocity, m/s (`M/S`).
    Velocity,
    /// Displacement, m (`M`).
    Displacement,
}

impl Units {
    /// The SEED/StationXML unit name, as ObsPy's `remove_response` recognises it.
    pub fn name(self) -> &'static str {
        match self {
            Units::Acceleration => "M/S**2",
            Units::Velocity => "M/S",
            Units::Displacement => "M",
        }
    }

    /// What the unit is, in words.
    pub fn description(self) -> &'static str {
        match self {
            Units::Acceleration => "Acceleration in meters per second squared",
            Units::Velocity => "Velocity in meters per second",
            Units::Displacement => "Displacement in meters",
        }
    }
}

/// The point `x_east_m` east and `y_north_m` north of (`origin_lat_deg`, `origin_lon_deg`), as
/// (latitude, longitude) in degrees on a sphere of radius [`EARTH_RADIUS_M`] (6 371 000 m).
///
/// Equirectangular about the origin: latitude = φ₀ + y/R, longitude = λ₀ + x/(R cos φ₀), in
/// radians. Distances are exact along the origin's meridian and parallel and good to a part in
/// 10⁵ within ~30 km of an origin at the equator (the error grows as (d/R)² and with tan φ₀); it
/// is meant for scenes that give only local coordinates, not for geodesy. The longitude is not
/// wrapped into [−180, 180] and is undefined at a pole (cos φ₀ = 0).
pub fn local_to_geographic(x_east_m: f64, y_north_m: f64, origin_lat_deg: f64, origin_lon_deg: f64) -> (f64, f64) {
    let lat = origin_lat_deg + (y_north_m / EARTH_RADIUS_M).to_degrees();
    let lon = origin_lon_deg + (x_east_m / (EARTH_RADIUS_M * origin_lat_deg.to_radians().cos())).to_degrees();
    (lat, lon)
}

/// Refuses a code that is empty (unless `may_be_empty`) or longer than 8 characters, or that
/// holds a space, a `.` or anything but printable ASCII.
fn check_code(field: &str, v: &str, may_be_empty: bool) -> Result<(), SeismoError> {
    let ok = (may_be_empty || !v.is_empty()) && v.len() <= 8 && v.chars().all(|c| c.is_ascii_graphic() && c != '.');
    if ok {
        Ok(())
    } else {
        let allowed = if may_be_empty {
            "0 to 8 printable ASCII characters, no space or '.'"
        } else {
            "1 to 8 printable ASCII characters, no space or '.'"
        };
        Err(SeismoError::parameter(field, format!("{v:?}"), allowed))
    }
}

/// Refuses `v` unless finite and `lo ≤ v ≤ hi` (`v < hi` when `hi_open`).
fn check_range(field: &str, v: f64, lo: f64, hi: f64, hi_open: bool, allowed: &str) -> Result<f64, SeismoError> {
    let ok = v.is_finite() && v >= lo && if hi_open { v < hi } else { v <= hi };
    if ok { Ok(v) } else { Err(SeismoError::parameter(field, v, allowed)) }
}

fn check_finite(field: &str, v: f64) -> Result<f64, SeismoError> {
    if v.is_finite() { Ok(v) } else { Err(SeismoError::parameter(field, v, "a finite number")) }
}

fn check_date(field: &str, v: &str) -> Result<(), SeismoError> {
    if is_xml_datetime(v) {
        Ok(())
    } else {
        Err(SeismoError::parameter(field, format!("{v:?}"), "an ISO 8601 date and time, e.g. 2000-01-01T00:00:00Z"))
    }
}

const LATITUDE: &str = "−90 ≤ latitude < 90 degrees (StationXML 1.2 excludes 90)";
const LONGITUDE: &str = "−180 ≤ longitude ≤ 180 degrees";

/// The StationXML 1.2 text of `inv`: every channel with a unit response (see the module's
/// documentation). Refuses a code, coordinate, angle, rate or date the schema (or ObsPy's matching
/// of ids) would not take, naming the field (e.g.
/// `networks[0].stations[1].channels[2].dip_deg (SS.N36.P.MNZ)`), its value and what is allowed.
pub fn stationxml(inv: &Inventory) -> Result<String, SeismoError> {
    check_date("created_utc", &inv.created_utc)?;
    if inv.networks.is_empty() {
        return Err(SeismoError::parameter("networks", "none", "at least one network (the schema needs one)"));
    }
    let mut x = String::new();
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(x, r#"<FDSNStationXML xmlns="http://www.fdsn.org/xml/station/1" schemaVersion="1.2">"#);
    let _ = writeln!(x, "  <Source>{}</Source>", escape(&inv.source));
    let _ = writeln!(x, "  <Sender>{}</Sender>", escape(&inv.sender));
    let _ = writeln!(x, "  <Module>{}</Module>", escape(&inv.module));
    let _ = writeln!(x, "  <Created>{}</Created>", escape(&inv.created_utc));
    for (i, n) in inv.networks.iter().enumerate() {
        let path = format!("networks[{i}]");
        check_code(&format!("{path}.code"), &n.code, false)?;
        check_date(&format!("{path}.start_utc ({})", n.code), &n.start_utc)?;
        let _ = writeln!(x, r#"  <Network code="{}" startDate="{}">"#, escape(&n.code), escape(&n.start_utc));
        let _ = writeln!(x, "    <Description>{}</Description>", escape(&n.description));
        for (j, s) in n.stations.iter().enumerate() {
            station(&mut x, &format!("{path}.stations[{j}]"), &n.code, s)?;
        }
        let _ = writeln!(x, "  </Network>");
    }
    let _ = writeln!(x, "</FDSNStationXML>");
    Ok(x)
}

fn station(x: &mut String, path: &str, network: &str, s: &Station) -> Result<(), SeismoError> {
    check_code(&format!("{path}.code"), &s.code, false)?;
    let f = |name: &str| format!("{path}.{name} ({network}.{})", s.code);
    let lat = check_range(&f("latitude_deg"), s.latitude_deg, -90.0, 90.0, true, LATITUDE)?;
    let lon = check_range(&f("longitude_deg"), s.longitude_deg, -180.0, 180.0, false, LONGITUDE)?;
    let elev = check_finite(&f("elevation_m"), s.elevation_m)?;
    check_date(&f("start_utc"), &s.start_utc)?;
    let _ = writeln!(x, r#"    <Station code="{}" startDate="{}">"#, escape(&s.code), escape(&s.start_utc));
    let _ = writeln!(x, "      <Description>{}</Description>", escape(&s.description));
    let _ = writeln!(x, "      <Latitude>{lat}</Latitude>");
    let _ = writeln!(x, "      <Longitude>{lon}</Longitude>");
    let _ = writeln!(x, "      <Elevation>{elev}</Elevation>");
    let _ = writeln!(x, "      <Site>");
    let _ = writeln!(x, "        <Name>{}</Name>", escape(&s.site_name));
    let _ = writeln!(x, "      </Site>");
    for (k, c) in s.channels.iter().enumerate() {
        channel(x, &format!("{path}.channels[{k}]"), &format!("{network}.{}", s.code), c)?;
    }
    let _ = writeln!(x, "    </Station>");
    Ok(())
}

fn channel(x: &mut String, path: &str, station: &str, c: &Channel) -> Result<(), SeismoError> {
    check_code(&format!("{path}.code"), &c.code, false)?;
    check_code(&format!("{path}.location_code"), &c.location_code, true)?;
    let f = |name: &str| format!("{path}.{name} ({station}.{}.{})", c.location_code, c.code);
    let lat = check_range(&f("latitude_deg"), c.latitude_deg, -90.0, 90.0, true, LATITUDE)?;
    let lon = check_range(&f("longitude_deg"), c.longitude_deg, -180.0, 180.0, false, LONGITUDE)?;
    let elev = check_finite(&f("elevation_m"), c.elevation_m)?;
    let depth = check_finite(&f("depth_m"), c.depth_m)?;
    let azimuth = check_range(&f("azimuth_deg"), c.azimuth_deg, 0.0, 360.0, true, "0 ≤ azimuth < 360 degrees")?;
    let dip = check_range(&f("dip_deg"), c.dip_deg, -90.0, 90.0, false, "−90 ≤ dip ≤ 90 degrees")?;
    let rate = c.sample_rate_hz;
    if !(rate.is_finite() && rate > 0.0) {
        return Err(SeismoError::parameter(f("sample_rate_hz"), rate, "a finite rate > 0 Hz"));
    }
    check_date(&f("start_utc"), &c.start_utc)?;
    let _ = writeln!(
        x,
        r#"      <Channel code="{}" locationCode="{}" startDate="{}">"#,
        escape(&c.code),
        escape(&c.location_code),
        escape(&c.start_utc)
    );
    let _ = writeln!(x, "        <Description>{}</Description>", escape(&c.description));
    let _ = writeln!(x, "        <Latitude>{lat}</Latitude>");
    let _ = writeln!(x, "        <Longitude>{lon}</Longitude>");
    let _ = writeln!(x, "        <Elevation>{elev}</Elevation>");
    let _ = writeln!(x, "        <Depth>{depth}</Depth>");
    let _ = writeln!(x, "        <Azimuth>{azimuth}</Azimuth>");
    let _ = writeln!(x, "        <Dip>{dip}</Dip>");
    let _ = writeln!(x, "        <Type>GEOPHYSICAL</Type>");
    let _ = writeln!(x, "        <Type>SYNTHESIZED</Type>");
    let _ = writeln!(x, "        <SampleRate>{rate}</SampleRate>");
    let _ = writeln!(x, "        <Sensor>");
    let _ = writeln!(x, "          <Type>simulated</Type>");
    let _ = writeln!(
        x,
        "          <Description>simulated record: one count is one {}</Description>",
        escape(c.units.name())
    );
    let _ = writeln!(x, "        </Sensor>");
    let units = |tag: &str, name: &str, text: &str| {
        format!("<{tag}><Name>{}</Name><Description>{}</Description></{tag}>", escape(name), escape(text))
    };
    let input = units("InputUnits", c.units.name(), c.units.description());
    let output = units("OutputUnits", "COUNTS", "Digital counts");
    let _ = writeln!(x, "        <Response>");
    let _ = writeln!(x, "          <InstrumentSensitivity>");
    let _ = writeln!(x, "            <Value>1</Value>");
    let _ = writeln!(x, "            <Frequency>1</Frequency>");
    let _ = writeln!(x, "            {input}");
    let _ = writeln!(x, "            {output}");
    let _ = writeln!(x, "          </InstrumentSensitivity>");
    let _ = writeln!(x, r#"          <Stage number="1">"#);
    let _ = writeln!(x, "            <PolesZeros>");
    let _ = writeln!(x, "              {input}");
    let _ = writeln!(x, "              {output}");
    let _ = writeln!(x, "              <PzTransferFunctionType>LAPLACE (RADIANS/SECOND)</PzTransferFunctionType>");
    let _ = writeln!(x, "              <NormalizationFactor>1</NormalizationFactor>");
    let _ = writeln!(x, "              <NormalizationFrequency>1</NormalizationFrequency>");
    let _ = writeln!(x, "            </PolesZeros>");
    let _ = writeln!(x, "            <StageGain>");
    let _ = writeln!(x, "              <Value>1</Value>");
    let _ = writeln!(x, "              <Frequency>1</Frequency>");
    let _ = writeln!(x, "            </StageGain>");
    let _ = writeln!(x, "          </Stage>");
    let _ = writeln!(x, "        </Response>");
    let _ = writeln!(x, "      </Channel>");
    Ok(())
}
