//! QuakeML 1.2 event catalogues (Schorlemmer et al. 2011, "QuakeML: status of the XML-based
//! seismological data exchange format"; the Basic Event Description schema
//! `QuakeML-BED-1.2.xsd`), read by ObsPy's `read_events` and catalogue tools.
//!
//! Each event has one origin (time, latitude, longitude, depth in m), its magnitudes (the first is
//! the preferred one), and, when its seismic moment is known, a focal mechanism whose moment
//! tensor carries it as the scalar moment (N·m). Identifiers are `smi:` resource references
//! built from the catalogue's prefix and the event's id, with characters the schema's pattern does
//! not allow replaced by `_`.

use std::fmt::Write as _;

use crate::error::SeismoError;
use crate::stationxml::escape;

/// The event types of QuakeML 1.2 (`EventType`).
pub const EVENT_TYPES: [&str; 44] = [
    "not existing",
    "not reported",
    "earthquake",
    "anthropogenic event",
    "collapse",
    "cavity collapse",
    "mine collapse",
    "building collapse",
    "explosion",
    "accidental explosion",
    "chemical explosion",
    "controlled explosion",
    "experimental explosion",
    "industrial explosion",
    "mining explosion",
    "quarry blast",
    "road cut",
    "blasting levee",
    "nuclear explosion",
    "induced or triggered event",
    "rock burst",
    "reservoir loading",
    "fluid injection",
    "fluid extraction",
    "crash",
    "plane crash",
    "train crash",
    "boat crash",
    "other event",
    "atmospheric event",
    "sonic boom",
    "sonic blast",
    "acoustic noise",
    "thunder",
    "avalanche",
    "snow avalanche",
    "debris avalanche",
    "hydroacoustic event",
    "ice quake",
    "slide",
    "landslide",
    "rockslide",
    "meteorite",
    "volcanic eruption",
];

/// A catalogue of events.
#[derive(Clone, Debug)]
pub struct Catalogue {
    /// The prefix of every identifier, e.g. `smi:local/stickslip/paper`.
    pub public_id_prefix: String,
    /// What the catalogue is.
    pub description: String,
    /// When it was made, ISO 8601 UTC.
    pub creation_utc: String,
    /// The agency that made it.
    pub agency_id: String,
    /// The program that made it.
    pub author: String,
    /// The events.
    pub events: Vec<QuakeEvent>,
}

/// One event.
#[derive(Clone, Debug)]
pub struct QuakeEvent {
    /// Its id, unique in the catalogue, e.g. `seed7/event0`.
    pub id: String,
    /// Its type, one of [`EVENT_TYPES`].
    pub event_type: String,
    /// What it is.
    pub description: String,
    /// Origin time, ISO 8601 UTC.
    pub origin_time_utc: String,
    /// Latitude of the hypocentre (degrees).
    pub latitude_deg: f64,
    /// Longitude of the hypocentre (degrees).
    pub longitude_deg: f64,
    /// Depth of the hypocentre (m).
    pub depth_m: f64,
    /// A comment on the origin (e.g. the scene's coordinates).
    pub origin_comment: Option<String>,
    /// Seismic moment (N·m), when known.
    pub scalar_moment_n_m: Option<f64>,
    /// Magnitudes, the preferred one first.
    pub magnitudes: Vec<QuakeMagnitude>,
}

/// A magnitude of an event.
#[derive(Clone, Debug)]
pub struct QuakeMagnitude {
    /// Its value.
    pub value: f64,
    /// Its type (`Mw`, `M`, …).
    pub magnitude_type: String,
    /// How it was obtained (a comment on it).
    pub method: String,
}

/// `s` with every character the schema's resource identifiers do not allow replaced by `_`.
fn sanitize(s: &str) -> String {
    s.chars().map(|c| if c.is_ascii_alphanumeric() || "-.*()_~'+?=,;#/".contains(c) { c } else { '_' }).collect()
}

fn finite(field: String, v: f64) -> Result<f64, SeismoError> {
    if v.is_finite() { Ok(v) } else { Err(SeismoError::parameter(field, v, "a finite number")) }
}

/// The QuakeML text of `cat`, refusing an unknown event type, a non-finite number or a latitude
/// or longitude out of range, naming the event and field.
pub fn quakeml(cat: &Catalogue) -> Result<String, SeismoError> {
    let prefix = match cat.public_id_prefix.split_once(':') {
        Some((scheme @ ("smi" | "quakeml"), rest)) if rest.contains('/') => format!("{scheme}:{}", sanitize(rest)),
        _ => String::new(),
    };
    if prefix.is_empty() {
        return Err(SeismoError::parameter(
            "public_id_prefix",
            &cat.public_id_prefix,
            "smi:<authority>/<path> or quakeml:<authority>/<path>",
        ));
    }
    let mut x = String::new();
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        x,
        r#"<q:quakeml xmlns:q="http://quakeml.org/xmlns/quakeml/1.2" xmlns="http://quakeml.org/xmlns/bed/1.2">"#
    );
    let _ = writeln!(x, r#"  <eventParameters publicID="{prefix}">"#);
    let _ = writeln!(x, "    <description>{}</description>", escape(&cat.description));
    let _ = writeln!(
        x,
        "    <creationInfo><agencyID>{}</agencyID><author>{}</author><creationTime>{}</creationTime></creationInfo>",
        escape(&cat.agency_id),
        escape(&cat.author),
        escape(&cat.creation_utc)
    );
    for e in &cat.events {
        event(&mut x, &prefix, e)?;
    }
    let _ = writeln!(x, "  </eventParameters>");
    let _ = writeln!(x, "</q:quakeml>");
    Ok(x)
}

fn event(x: &mut String, prefix: &str, e: &QuakeEvent) -> Result<(), SeismoError> {
    let f = |name: &str| format!("event {}: {name}", e.id);
    if !EVENT_TYPES.contains(&e.event_type.as_str()) {
        return Err(SeismoError::parameter(
            f("event_type"),
            &e.event_type,
            "a QuakeML 1.2 event type, e.g. earthquake",
        ));
    }
    let lat = finite(f("latitude_deg"), e.latitude_deg)?;
    let lon = finite(f("longitude_deg"), e.longitude_deg)?;
    if !(-90.0..=90.0).contains(&lat) {
        return Err(SeismoError::parameter(f("latitude_deg"), lat, "−90 … 90 degrees"));
    }
    if !(-180.0..=180.0).contains(&lon) {
        return Err(SeismoError::parameter(f("longitude_deg"), lon, "−180 … 180 degrees"));
    }
    let depth = finite(f("depth_m"), e.depth_m)?;
    let id = format!("{prefix}/{}", sanitize(&e.id));
    let origin = format!("{id}/origin");
    let _ = writeln!(x, r#"    <event publicID="{id}">"#);
    let _ = writeln!(x, "      <type>{}</type>", e.event_type);
    let _ = writeln!(x, "      <description><text>{}</text></description>", escape(&e.description));
    let _ = writeln!(x, "      <preferredOriginID>{origin}</preferredOriginID>");
    if !e.magnitudes.is_empty() {
        let _ = writeln!(x, "      <preferredMagnitudeID>{id}/magnitude/0</preferredMagnitudeID>");
    }
    if e.scalar_moment_n_m.is_some() {
        let _ = writeln!(x, "      <preferredFocalMechanismID>{id}/focal_mechanism</preferredFocalMechanismID>");
    }
    let _ = writeln!(x, r#"      <origin publicID="{origin}">"#);
    let _ = writeln!(x, "        <time><value>{}</value></time>", escape(&e.origin_time_utc));
    let _ = writeln!(x, "        <latitude><value>{lat}</value></latitude>");
    let _ = writeln!(x, "        <longitude><value>{lon}</value></longitude>");
    let _ = writeln!(x, "        <depth><value>{depth}</value></depth>");
    if let Some(c) = &e.origin_comment {
        let _ = writeln!(x, "        <comment><text>{}</text></comment>", escape(c));
    }
    let _ = writeln!(x, "      </origin>");
    for (k, m) in e.magnitudes.iter().enumerate() {
        let value = finite(f(&format!("magnitudes[{k}]")), m.value)?;
        let _ = writeln!(x, r#"      <magnitude publicID="{id}/magnitude/{k}">"#);
        let _ = writeln!(x, "        <mag><value>{value}</value></mag>");
        let _ = writeln!(x, "        <type>{}</type>", escape(&m.magnitude_type));
        let _ = writeln!(x, "        <originID>{origin}</originID>");
        let _ = writeln!(x, "        <methodID>{prefix}/method/{}</methodID>", sanitize(&m.magnitude_type));
        let _ = writeln!(x, "        <comment><text>{}</text></comment>", escape(&m.method));
        let _ = writeln!(x, "      </magnitude>");
    }
    if let Some(m0) = e.scalar_moment_n_m {
        let m0 = finite(f("scalar_moment_n_m"), m0)?;
        let _ = writeln!(x, r#"      <focalMechanism publicID="{id}/focal_mechanism">"#);
        let _ = writeln!(x, r#"        <momentTensor publicID="{id}/moment_tensor">"#);
        let _ = writeln!(x, "          <derivedOriginID>{origin}</derivedOriginID>");
        let _ = writeln!(x, "          <scalarMoment><value>{m0:e}</value></scalarMoment>");
        let _ = writeln!(x, "        </momentTensor>");
        let _ = writeln!(x, "      </focalMechanism>");
    }
    let _ = writeln!(x, "    </event>");
    Ok(())
}
