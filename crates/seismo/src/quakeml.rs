//! QuakeML 1.2 event catalogues in the Basic Event Description (Schorlemmer, Euchner, Kästli and
//! Saul 2011, "QuakeML: status of the XML-based seismological data exchange format", Annals of
//! Geophysics 54(1); schema `QuakeML-BED-1.2.xsd`, <https://quake.ethz.ch/quakeml/>), as read by
//! ObsPy's `read_events` and by catalogue tools.
//!
//! Layout written: the root `q:quakeml` (`xmlns:q="http://quakeml.org/xmlns/quakeml/1.2"`,
//! default namespace `http://quakeml.org/xmlns/bed/1.2`) holding one `eventParameters`
//! (`description`, `creationInfo`, the `event`s). Each event has its `description`, `type`,
//! `creationInfo`, one `origin` (`time`, `latitude`, `longitude`, `depth` in m, an optional
//! `comment`), its `magnitude`s (each with `mag`, `type`, the `originID` of the origin, and, when
//! its method is given, a `methodID` made from it and the method as a `comment`) and, when the
//! seismic moment M0 is given, a `focalMechanism` whose `momentTensor` carries it as
//! `scalarMoment` (N·m) with the origin as `derivedOriginID` (and the first `Mw` magnitude as
//! `momentMagnitudeID`). The event's `preferredOriginID`, `preferredMagnitudeID` (the first
//! magnitude) and `preferredFocalMechanismID` point at them.
//!
//! **Identifiers** are resource references of the schema's pattern
//! `(smi|quakeml):authority/path`: the catalogue's prefix as given (refused if it does not match),
//! then `/` and the event's id, `…/origin`, `…/magnitude/<k>`, `…/focal_mechanism`,
//! `…/moment_tensor`, and `<prefix>/method/<method>` for methods; in ids and methods every
//! character other than ASCII letters, digits and `-.*()_~'+?=,;#/` becomes `_`.
//!
//! **Refusals** ([`quakeml`]): an event type outside QuakeML 1.2's `EventType` ([`EVENT_TYPES`]),
//! a non-finite number, a latitude outside [−90, 90] or longitude outside [−180, 180], a negative
//! M0, an empty or repeated event id (after the replacement above), a date that is not an
//! `xs:dateTime`, and text longer than the schema allows (agency 64, author 128, magnitude type
//! 32 characters). Each error names the field, e.g. `events[3].longitude_deg (seed7/event0)`.
//!
//! **The nominal clock.** A simulated event has no date: time 0 of a run is
//! 2000-01-01T00:00:00Z, as in the SAC records ([`crate::accelerogram::sac::NOMINAL_ORIGIN`]);
//! [`crate::clock::UtcTime`] gives the date and time of an offset from it.

use std::collections::BTreeSet;
use std::fmt::Write as _;

use crate::error::SeismoError;
use crate::xml::{escape, is_xml_datetime};

/// The event types of QuakeML 1.2 (the enumeration `EventType` of `QuakeML-BED-1.2.xsd`).
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

/// A catalogue of events (one `eventParameters`).
#[derive(Clone, Debug)]
pub struct Catalogue {
    /// The prefix of every identifier, a resource reference such as `smi:local/stickslip/paper`.
    pub public_id_prefix: String,
    /// What the catalogue is.
    pub description: String,
    /// When it was made, ISO 8601 UTC.
    pub creation_utc: String,
    /// The agency that made it (at most 64 characters).
    pub agency_id: String,
    /// Who or what made it (at most 128 characters).
    pub author: String,
    /// The events.
    pub events: Vec<QuakeEvent>,
}

/// One event: one origin, its magnitudes and, optionally, its seismic moment.
#[derive(Clone, Debug)]
pub struct QuakeEvent {
    /// Its id, unique in the catalogue, e.g. `seed7/event0` (the suffix of its identifiers).
    pub id: String,
    /// Its type, one of [`EVENT_TYPES`], e.g. `earthquake` or `other event`.
    pub event_type: String,
    /// What it is.
    pub description: String,
    /// Origin time, ISO 8601 UTC, e.g. from [`crate::clock::UtcTime::iso`].
    pub origin_time_utc: String,
    /// Latitude of the hypocentre (degrees north).
    pub latitude_deg: f64,
    /// Longitude of the hypocentre (degrees east).
    pub longitude_deg: f64,
    /// Depth of the hypocentre (m).
    pub depth_m: f64,
    /// A comment on the origin (e.g. the scene's coordinates).
    pub origin_comment: Option<String>,
    /// Seismic moment M0 (N·m), when known.
    pub scalar_moment_n_m: Option<f64>,
    /// Magnitudes; the first is the preferred one.
    pub magnitudes: Vec<QuakeMagnitude>,
}

/// A magnitude of an event.
#[derive(Clone, Debug)]
pub struct QuakeMagnitude {
    /// Its value.
    pub value: f64,
    /// Its type, e.g. `Mw` or `M` (at most 32 characters; empty: none written).
    pub magnitude_type: String,
    /// How it was obtained, free text: written as a comment and, as an identifier, the `methodID`
    /// (empty: neither).
    pub method: String,
}

/// The characters an identifier's path may hold (ASCII letters and digits and these).
const ID_PUNCTUATION: &str = "-.*()_~'+?=,;#/";

/// `s` with every character an identifier's path may not hold replaced by `_`.
fn sanitize(s: &str) -> String {
    s.chars().map(|c| if c.is_ascii_alphanumeric() || ID_PUNCTUATION.contains(c) { c } else { '_' }).collect()
}

/// Whether `s` matches QuakeML 1.2's `ResourceIdentifier`, restricted to ASCII:
/// `(smi|quakeml):[\w\d][\w\d\-\.\*\(\)_~']{2,}/[\w\d\-\.\*\(\)_~'][\w\d\-\.\*\(\)\+\?_~'=,;#/&]*`.
fn is_resource_id(s: &str) -> bool {
    let Some(rest) = s.strip_prefix("smi:").or_else(|| s.strip_prefix("quakeml:")) else { return false };
    let Some((authority, path)) = rest.split_once('/') else { return false };
    let word = |c: char| c.is_ascii_alphanumeric() || "-.*()_~'".contains(c);
    let mut a = authority.chars();
    let mut p = path.chars();
    a.next().is_some_and(|c| c.is_ascii_alphanumeric())
        && authority.len() >= 3
        && a.all(word)
        && p.next().is_some_and(word)
        && p.all(|c| word(c) || "+?=,;#/&".contains(c))
}

fn finite(field: &str, v: f64) -> Result<f64, SeismoError> {
    if v.is_finite() { Ok(v) } else { Err(SeismoError::parameter(field, v, "a finite number")) }
}

fn date(field: &str, v: &str) -> Result<(), SeismoError> {
    if is_xml_datetime(v) {
        Ok(())
    } else {
        Err(SeismoError::parameter(field, format!("{v:?}"), "an ISO 8601 date and time, e.g. 2000-01-01T00:00:00Z"))
    }
}

fn at_most(field: &str, v: &str, max: usize) -> Result<(), SeismoError> {
    if v.chars().count() <= max {
        Ok(())
    } else {
        Err(SeismoError::parameter(field, format!("{v:?}"), format!("at most {max} characters (QuakeML 1.2)")))
    }
}

/// The QuakeML 1.2 text of `cat` (see the module's documentation for what is written). Refuses an
/// identifier prefix that is not a resource reference, an unknown event type, a non-finite number,
/// a latitude or longitude out of range, a negative M0, an empty or repeated event id, a date that
/// is not ISO 8601 and text longer than the schema allows, naming the field (e.g.
/// `events[2].latitude_deg (seed7/event0)`), its value and what is allowed.
pub fn quakeml(cat: &Catalogue) -> Result<String, SeismoError> {
    let prefix = cat.public_id_prefix.trim_end_matches('/');
    if !is_resource_id(prefix) {
        return Err(SeismoError::parameter(
            "public_id_prefix",
            format!("{:?}", cat.public_id_prefix),
            "a QuakeML resource reference, smi:<authority>/<path> or quakeml:<authority>/<path> (authority of \
             3 or more letters, digits or -.*()_~')",
        ));
    }
    date("creation_utc", &cat.creation_utc)?;
    at_most("agency_id", &cat.agency_id, 64)?;
    at_most("author", &cat.author, 128)?;
    let creation = format!(
        "<creationInfo><agencyID>{}</agencyID><author>{}</author><creationTime>{}</creationTime></creationInfo>",
        escape(&cat.agency_id),
        escape(&cat.author),
        escape(&cat.creation_utc)
    );
    let mut x = String::new();
    let _ = writeln!(x, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        x,
        r#"<q:quakeml xmlns:q="http://quakeml.org/xmlns/quakeml/1.2" xmlns="http://quakeml.org/xmlns/bed/1.2">"#
    );
    let _ = writeln!(x, r#"  <eventParameters publicID="{}">"#, escape(prefix));
    let _ = writeln!(x, "    <description>{}</description>", escape(&cat.description));
    let _ = writeln!(x, "    {creation}");
    let mut ids = BTreeSet::new();
    for (k, e) in cat.events.iter().enumerate() {
        let id = sanitize(&e.id);
        if e.id.is_empty() || !ids.insert(id.clone()) {
            return Err(SeismoError::parameter(
                format!("events[{k}].id"),
                format!("{:?}", e.id),
                format!("a non-empty id, unique in the catalogue once made an identifier ({id:?})"),
            ));
        }
        event(&mut x, prefix, &format!("{prefix}/{id}"), &format!("events[{k}]"), e, &creation)?;
    }
    let _ = writeln!(x, "  </eventParameters>");
    let _ = writeln!(x, "</q:quakeml>");
    Ok(x)
}

fn event(
    x: &mut String,
    prefix: &str,
    id: &str,
    path: &str,
    e: &QuakeEvent,
    creation: &str,
) -> Result<(), SeismoError> {
    let f = |name: &str| format!("{path}.{name} ({})", e.id);
    if !EVENT_TYPES.contains(&e.event_type.as_str()) {
        return Err(SeismoError::parameter(
            f("event_type"),
            format!("{:?}", e.event_type),
            "a QuakeML 1.2 EventType, e.g. \"earthquake\" or \"other event\"",
        ));
    }
    date(&f("origin_time_utc"), &e.origin_time_utc)?;
    let lat = finite(&f("latitude_deg"), e.latitude_deg)?;
    if !(-90.0..=90.0).contains(&lat) {
        return Err(SeismoError::parameter(f("latitude_deg"), lat, "−90 ≤ latitude ≤ 90 degrees"));
    }
    let lon = finite(&f("longitude_deg"), e.longitude_deg)?;
    if !(-180.0..=180.0).contains(&lon) {
        return Err(SeismoError::parameter(f("longitude_deg"), lon, "−180 ≤ longitude ≤ 180 degrees"));
    }
    let depth = finite(&f("depth_m"), e.depth_m)?;
    let m0 = match e.scalar_moment_n_m {
        Some(m0) if !(m0.is_finite() && m0 >= 0.0) => {
            return Err(SeismoError::parameter(f("scalar_moment_n_m"), m0, "a finite moment ≥ 0 N·m"));
        }
        m0 => m0,
    };
    for (k, m) in e.magnitudes.iter().enumerate() {
        finite(&f(&format!("magnitudes[{k}].value")), m.value)?;
        at_most(&f(&format!("magnitudes[{k}].magnitude_type")), &m.magnitude_type, 32)?;
    }
    let (id, origin) = (escape(id), escape(&format!("{id}/origin")));
    let _ = writeln!(x, r#"    <event publicID="{id}">"#);
    let _ = writeln!(x, "      <description><text>{}</text></description>", escape(&e.description));
    let _ = writeln!(x, "      <type>{}</type>", escape(&e.event_type));
    let _ = writeln!(x, "      <preferredOriginID>{origin}</preferredOriginID>");
    if !e.magnitudes.is_empty() {
        let _ = writeln!(x, "      <preferredMagnitudeID>{id}/magnitude/0</preferredMagnitudeID>");
    }
    if m0.is_some() {
        let _ = writeln!(x, "      <preferredFocalMechanismID>{id}/focal_mechanism</preferredFocalMechanismID>");
    }
    let _ = writeln!(x, "      {creation}");
    let _ = writeln!(x, r#"      <origin publicID="{origin}">"#);
    let _ = writeln!(x, "        <time><value>{}</value></time>", escape(&e.origin_time_utc));
    let _ = writeln!(x, "        <latitude><value>{lat}</value></latitude>");
    let _ = writeln!(x, "        <longitude><value>{lon}</value></longitude>");
    let _ = writeln!(x, "        <depth><value>{depth}</value></depth>");
    if let Some(c) = &e.origin_comment {
        let _ = writeln!(x, "        <comment><text>{}</text></comment>", escape(c));
    }
    let _ = writeln!(x, "        {creation}");
    let _ = writeln!(x, "      </origin>");
    for (k, m) in e.magnitudes.iter().enumerate() {
        let _ = writeln!(x, r#"      <magnitude publicID="{id}/magnitude/{k}">"#);
        let _ = writeln!(x, "        <mag><value>{}</value></mag>", m.value);
        if !m.magnitude_type.is_empty() {
            let _ = writeln!(x, "        <type>{}</type>", escape(&m.magnitude_type));
        }
        let _ = writeln!(x, "        <originID>{origin}</originID>");
        if !m.method.is_empty() {
            let method = escape(&format!("{prefix}/method/{}", sanitize(&m.method)));
            let _ = writeln!(x, "        <methodID>{method}</methodID>");
            let _ = writeln!(x, "        <comment><text>{}</text></comment>", escape(&m.method));
        }
        let _ = writeln!(x, "        {creation}");
        let _ = writeln!(x, "      </magnitude>");
    }
    if let Some(m0) = m0 {
        let _ = writeln!(x, r#"      <focalMechanism publicID="{id}/focal_mechanism">"#);
        let _ = writeln!(x, r#"        <momentTensor publicID="{id}/moment_tensor">"#);
        let _ = writeln!(x, "          <derivedOriginID>{origin}</derivedOriginID>");
        if let Some(k) = e.magnitudes.iter().position(|m| m.magnitude_type == "Mw") {
            let _ = writeln!(x, "          <momentMagnitudeID>{id}/magnitude/{k}</momentMagnitudeID>");
        }
        let _ = writeln!(x, "          <scalarMoment><value>{m0:e}</value></scalarMoment>");
        let _ = writeln!(x, "        </momentTensor>");
        let _ = writeln!(x, "        {creation}");
        let _ = writeln!(x, "      </focalMechanism>");
    }
    let _ = writeln!(x, "    </event>");
    Ok(())
}
