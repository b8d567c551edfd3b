//! StationXML and QuakeML written by `stickslip_seismo::{stationxml, quakeml}`: the nominal clock
//! (`clock::UtcTime`), the structure of an inventory and a catalogue, escaping, exact numbers and the
//! refusals, each naming its field. (ObsPy reads and schema-validates these files in
//! `python/tests/test_obspy.py`.)

use stickslip_seismo::clock::UtcTime;
use stickslip_seismo::quakeml::{Catalogue, EVENT_TYPES, QuakeEvent, QuakeMagnitude, quakeml};
use stickslip_seismo::stationxml::{
    Channel, EARTH_RADIUS_M, Inventory, Network, Station, Units, escape, local_to_geographic, stationxml,
};

const DAY: f64 = 86_400.0;

/// The ISO 8601 time `offset_s` after the nominal time 0 of a run.
fn iso_utc(offset_s: f64) -> String {
    UtcTime::from_nominal(offset_s).unwrap().iso()
}

#[test]
fn the_nominal_clock() {
    assert_eq!(iso_utc(0.0), "2000-01-01T00:00:00.000000Z");
    assert_eq!(iso_utc(-1.0), "1999-12-31T23:59:59.000000Z");
    // 2000 is a leap year: 366 days later is 2001-01-01, and 29 February exists.
    assert_eq!(iso_utc(366.0 * DAY), "2001-01-01T00:00:00.000000Z");
    assert_eq!(iso_utc(59.0 * DAY), "2000-02-29T00:00:00.000000Z");
    assert_eq!(iso_utc(60.0 * DAY), "2000-03-01T00:00:00.000000Z");
    // 1900 and 2100 are not leap years, 2400 is.
    assert_eq!(iso_utc(-3_150_576_000.0 - DAY), "1900-02-28T00:00:00.000000Z");
    assert_eq!(iso_utc(-3_150_576_000.0), "1900-03-01T00:00:00.000000Z");
    assert_eq!(iso_utc(3_160_857_600.0 - DAY), "2100-02-28T00:00:00.000000Z");
    assert_eq!(iso_utc(12_627_878_400.0), "2400-02-29T00:00:00.000000Z");
    assert_eq!(iso_utc(1e9), "2031-09-09T01:46:40.000000Z");
    assert_eq!(iso_utc(-1e9), "1968-04-23T22:13:20.000000Z");
    // Rounded to the microsecond, carrying into the minute or back into the previous day.
    assert_eq!(iso_utc(12.3456789), "2000-01-01T00:00:12.345679Z");
    assert_eq!(iso_utc(59.9999996), "2000-01-01T00:01:00.000000Z");
    assert_eq!(iso_utc(-4e-7), "2000-01-01T00:00:00.000000Z");
    assert_eq!(iso_utc(-6e-7), "1999-12-31T23:59:59.999999Z");
    // Beyond four-digit years: year 0 is 1 BC (ISO 8601's astronomical numbering).
    assert_eq!(iso_utc(252_455_616_000.0), "10000-01-01T00:00:00.000000Z");
    assert_eq!(iso_utc(-63_082_281_600.0), "0001-01-01T00:00:00.000000Z");
    assert_eq!(iso_utc(-63_082_281_600.0 - DAY), "0000-12-31T00:00:00.000000Z");
    // What has no date is refused, not written.
    for bad in [f64::NAN, f64::INFINITY, 1e12] {
        let e = UtcTime::from_nominal(bad).unwrap_err().to_string();
        assert!(e.contains("time"), "{e}");
    }
}

#[test]
fn event_types_are_quakeml_1_2() {
    assert_eq!(EVENT_TYPES.len(), 44);
    for t in ["earthquake", "other event", "induced or triggered event", "volcanic eruption", "not existing"] {
        assert!(EVENT_TYPES.contains(&t), "{t}");
    }
}

fn channel(code: &str, rate: f64) -> Channel {
    Channel {
        code: code.into(),
        location_code: "P".into(),
        latitude_deg: 0.01,
        longitude_deg: 0.02,
        elevation_m: 1000.0,
        depth_m: 0.0,
        azimuth_deg: 90.0,
        dip_deg: 0.0,
        sample_rate_hz: rate,
        units: Units::Acceleration,
        start_utc: iso_utc(-DAY),
        description: "node 36 & friends <x>".into(),
    }
}

fn station(code: &str, channels: Vec<Channel>) -> Station {
    Station {
        code: code.into(),
        latitude_deg: 0.01,
        longitude_deg: 0.02,
        elevation_m: 1000.0,
        site_name: "node 36".into(),
        description: "a \"quoted\" site, x 'east'".into(),
        start_utc: iso_utc(-DAY),
        channels,
    }
}

fn inventory(stations: Vec<Station>) -> Inventory {
    Inventory {
        source: "test".into(),
        sender: "stickslip".into(),
        module: "stickslip test".into(),
        created_utc: "2000-01-01T00:00:00Z".into(),
        networks: vec![Network {
            code: "SS".into(),
            description: "test network".into(),
            start_utc: iso_utc(-DAY),
            stations,
        }],
    }
}

/// The text between `<tag>` and `</tag>` at each occurrence.
fn values<'a>(xml: &'a str, tag: &str) -> Vec<&'a str> {
    let (open, close) = (format!("<{tag}>"), format!("</{tag}>"));
    xml.match_indices(&open)
        .map(|(i, _)| {
            let from = i + open.len();
            &xml[from..from + xml[from..].find(&close).unwrap()]
        })
        .collect()
}

#[test]
fn escaping() {
    assert_eq!(escape(r#"a & b < c > d "e" 'f'"#), "a &amp; b &lt; c &gt; d &quot;e&quot; &apos;f&apos;");
    assert_eq!(escape("tab\tline\nbell\u{7}"), "tab\tline\nbell\u{FFFD}");
    assert_eq!(escape("m/s² ✓"), "m/s² ✓");
}

#[test]
fn inventory_structure_escaping_and_exact_rates() {
    let rate = 1.0 / 0.0123;
    let inv = inventory(vec![
        station("N36", vec![channel("MNE", rate), channel("MNN", rate), channel("MNZ", rate)]),
        station(
            "S001",
            vec![Channel { units: Units::Velocity, location_code: String::new(), ..channel("HH1", 200.0) }],
        ),
    ]);
    let xml = stationxml(&inv).unwrap();
    assert!(xml.starts_with(r#"<?xml version="1.0" encoding="UTF-8"?>"#));
    assert!(xml.contains(r#"<FDSNStationXML xmlns="http://www.fdsn.org/xml/station/1" schemaVersion="1.2">"#));
    assert!(xml.trim_end().ends_with("</FDSNStationXML>"));
    assert_eq!(xml.matches("<Network ").count(), 1);
    assert_eq!(xml.matches("<Station ").count(), 2);
    assert_eq!(xml.matches("<Channel ").count(), 4);
    assert_eq!(xml.matches("</Channel>").count(), 4);
    assert_eq!(xml.matches("<Response>").count(), 4, "a response per channel");
    assert_eq!(xml.matches("<InstrumentSensitivity>").count(), 4);
    assert_eq!(xml.matches(r#"<Stage number="1">"#).count(), 4, "one stage per channel");
    assert_eq!(xml.matches("<Pole>").count() + xml.matches("<Zero>").count(), 0);
    assert!(xml.contains(r#"<Channel code="HH1" locationCode="" startDate="1999-12-31T00:00:00.000000Z">"#));
    // Every sample rate reads back as the same f64.
    let rates: Vec<f64> = values(&xml, "SampleRate").iter().map(|v| v.parse().unwrap()).collect();
    assert_eq!(rates, [rate, rate, rate, 200.0]);
    assert!(rates[0].to_bits() == (1.0f64 / 0.0123).to_bits());
    // Units: the input of the sensitivity and of the stage; counts out.
    let names = values(&xml, "Name");
    assert_eq!(names.iter().filter(|n| **n == "M/S**2").count(), 3 * 2);
    assert_eq!(names.iter().filter(|n| **n == "M/S").count(), 2);
    assert_eq!(names.iter().filter(|n| **n == "COUNTS").count(), 4 * 2);
    assert!(values(&xml, "Value").iter().all(|v| *v == "1"));
    assert_eq!(values(&xml, "Azimuth"), ["90"; 4]);
    assert_eq!(values(&xml, "Latitude"), ["0.01"; 6]);
    // Text escaped.
    assert!(xml.contains("node 36 &amp; friends &lt;x&gt;"));
    assert!(xml.contains("a &quot;quoted&quot; site, x &apos;east&apos;"));
    assert!(!xml.contains("& ") && !xml.contains("<x>"), "unescaped text");
}

#[test]
fn inventory_refusals_name_the_field() {
    let refused = |s: Station| stationxml(&inventory(vec![s])).unwrap_err().to_string();
    let e = refused(station("N 36", vec![]));
    assert!(e.contains("networks[0].stations[0].code") && e.contains("\"N 36\""), "{e}");
    let e = refused(station("", vec![]));
    assert!(e.contains("stations[0].code") && e.contains("1 to 8"), "{e}");
    let e = refused(station("N36", vec![Channel { location_code: "0.0".into(), ..channel("MNZ", 50.0) }]));
    assert!(e.contains("channels[0].location_code") && e.contains("\"0.0\""), "{e}");
    let e = refused(Station { latitude_deg: 91.0, ..station("N36", vec![]) });
    assert!(e.contains("latitude_deg (SS.N36)") && e.contains("91") && e.contains("90"), "{e}");
    // StationXML 1.2's latitude excludes 90.
    let e = refused(Station { latitude_deg: 90.0, ..station("N36", vec![]) });
    assert!(e.contains("latitude_deg") && e.contains("< 90"), "{e}");
    let e = refused(Station { longitude_deg: -180.5, ..station("N36", vec![]) });
    assert!(e.contains("longitude_deg") && e.contains("-180.5"), "{e}");
    let e = refused(station("N36", vec![Channel { dip_deg: -95.0, ..channel("MNZ", 50.0) }]));
    assert!(e.contains("channels[0].dip_deg (SS.N36.P.MNZ)") && e.contains("-95"), "{e}");
    let e = refused(station("N36", vec![channel("MNE", 50.0), Channel { azimuth_deg: 360.0, ..channel("MNN", 50.0) }]));
    assert!(e.contains("channels[1].azimuth_deg (SS.N36.P.MNN)") && e.contains("< 360"), "{e}");
    let e = refused(station("N36", vec![Channel { azimuth_deg: f64::NAN, ..channel("MNZ", 50.0) }]));
    assert!(e.contains("azimuth_deg") && e.contains("NaN"), "{e}");
    for bad in [0.0, -10.0, f64::INFINITY, f64::NAN] {
        let e = refused(station("N36", vec![channel("MNZ", bad)]));
        assert!(e.contains("sample_rate_hz") && e.contains("> 0"), "{e}");
    }
    let e = refused(station("N36", vec![Channel { depth_m: f64::NEG_INFINITY, ..channel("MNZ", 50.0) }]));
    assert!(e.contains("depth_m") && e.contains("-inf"), "{e}");
    let e = refused(station("N36", vec![Channel { start_utc: "2000-02-30T00:00:00Z".into(), ..channel("MNZ", 50.0) }]));
    assert!(e.contains("start_utc") && e.contains("2000-02-30"), "{e}");
    let e = stationxml(&Inventory { created_utc: "yesterday".into(), ..inventory(vec![]) }).unwrap_err().to_string();
    assert!(e.contains("created_utc") && e.contains("yesterday"), "{e}");
    let e = stationxml(&Inventory { networks: vec![], ..inventory(vec![]) }).unwrap_err().to_string();
    assert!(e.contains("networks") && e.contains("at least one"), "{e}");
    // The edges of the ranges are taken.
    let edges = station(
        "N36",
        vec![Channel {
            latitude_deg: -90.0,
            longitude_deg: 180.0,
            azimuth_deg: 0.0,
            dip_deg: 90.0,
            location_code: String::new(),
            ..channel("MNZ", 1e-3)
        }],
    );
    stationxml(&inventory(vec![Station { longitude_deg: -180.0, ..edges }])).unwrap();
}

#[test]
fn local_coordinates_on_the_sphere() {
    let (lat, lon) = local_to_geographic(1000.0, 2000.0, 0.0, 0.0);
    assert!((lat - (2000.0 / EARTH_RADIUS_M).to_degrees()).abs() < 1e-15);
    assert!((lon - (1000.0 / EARTH_RADIUS_M).to_degrees()).abs() < 1e-15);
    // One degree of the meridian is 2πR/360 = 111 194.9 m.
    let (lat1, _) = local_to_geographic(0.0, 111_194.926_644_558_73, 10.0, 20.0);
    assert!((lat1 - 11.0).abs() < 1e-12, "{lat1}");
    // At 60° N a parallel is half as long: the same metres east are twice the degrees.
    let (lat60, lon60) = local_to_geographic(1000.0, 0.0, 60.0, 10.0);
    assert_eq!(lat60, 60.0);
    assert!((lon60 - 10.0 - 2.0 * lon).abs() < 1e-12);
}

fn catalogue(events: Vec<QuakeEvent>) -> Catalogue {
    Catalogue {
        public_id_prefix: "smi:local/stickslip/test".into(),
        description: "test & catalogue".into(),
        creation_utc: iso_utc(0.0),
        agency_id: "stickslip".into(),
        author: "stickslip test".into(),
        events,
    }
}

fn event(id: &str) -> QuakeEvent {
    QuakeEvent {
        id: id.into(),
        event_type: "earthquake".into(),
        description: "S2 <main>".into(),
        origin_time_utc: iso_utc(621.478734),
        latitude_deg: 0.0,
        longitude_deg: 0.018,
        depth_m: 0.0,
        origin_comment: Some("x 2000 m".into()),
        scalar_moment_n_m: Some(7.6e18),
        magnitudes: vec![
            QuakeMagnitude { value: 4.85, magnitude_type: "Mw".into(), method: "Hanks & Kanamori 1979".into() },
            QuakeMagnitude { value: 6.778, magnitude_type: "M".into(), method: "Riera".into() },
        ],
    }
}

#[test]
fn catalogue_structure_ids_and_numbers() {
    let second = QuakeEvent {
        event_type: "other event".into(),
        scalar_moment_n_m: None,
        origin_comment: None,
        magnitudes: vec![QuakeMagnitude { value: -0.5, magnitude_type: "M".into(), method: String::new() }],
        ..event("seed 7/event 1")
    };
    let xml = quakeml(&catalogue(vec![event("seed7/event0"), second])).unwrap();
    assert!(xml.contains(
        r#"<q:quakeml xmlns:q="http://quakeml.org/xmlns/quakeml/1.2" xmlns="http://quakeml.org/xmlns/bed/1.2">"#
    ));
    assert!(xml.contains(r#"<eventParameters publicID="smi:local/stickslip/test">"#));
    assert_eq!(xml.matches("<event ").count(), 2);
    assert_eq!(xml.matches("<origin ").count(), 2);
    assert_eq!(xml.matches("<magnitude ").count(), 3);
    assert_eq!(xml.matches("<originID>").count(), 3);
    assert_eq!(xml.matches("<methodID>").count(), 2);
    assert_eq!(xml.matches("<focalMechanism ").count(), 1);
    assert_eq!(xml.matches("<momentTensor ").count(), 1);
    assert_eq!(xml.matches("<preferredOriginID>").count(), 2);
    assert_eq!(xml.matches("<preferredMagnitudeID>").count(), 2);
    assert_eq!(xml.matches("<preferredFocalMechanismID>").count(), 1);
    assert_eq!(values(&xml, "type"), ["earthquake", "Mw", "M", "other event", "M"]);
    let id = "smi:local/stickslip/test/seed7/event0";
    assert!(xml.contains(&format!(r#"<event publicID="{id}">"#)));
    assert!(xml.contains(&format!("<preferredOriginID>{id}/origin</preferredOriginID>")));
    assert!(xml.contains(&format!("<preferredMagnitudeID>{id}/magnitude/0</preferredMagnitudeID>")));
    assert!(xml.contains(&format!("<preferredFocalMechanismID>{id}/focal_mechanism</preferredFocalMechanismID>")));
    assert!(xml.contains(&format!("<derivedOriginID>{id}/origin</derivedOriginID>")));
    assert!(xml.contains(&format!("<momentMagnitudeID>{id}/magnitude/0</momentMagnitudeID>")));
    assert!(xml.contains("<methodID>smi:local/stickslip/test/method/Hanks___Kanamori_1979</methodID>"));
    // Characters an identifier may not hold become '_'.
    assert!(xml.contains(r#"<event publicID="smi:local/stickslip/test/seed_7/event_1">"#));
    let mags: Vec<f64> = values(&xml, "mag")
        .iter()
        .map(|v| v.trim_start_matches("<value>").trim_end_matches("</value>").parse().unwrap())
        .collect();
    assert_eq!(mags, [4.85, 6.778, -0.5]);
    assert!(xml.contains("<scalarMoment><value>7.6e18</value></scalarMoment>"));
    assert!(xml.contains("<time><value>2000-01-01T00:10:21.478734Z</value></time>"));
    assert!(xml.contains("<longitude><value>0.018</value></longitude>"));
    assert!(
        xml.contains("S2 &lt;main&gt;") && xml.contains("Hanks &amp; Kanamori") && xml.contains("test &amp; catalogue")
    );
    assert!(!xml.contains("& ") && !xml.contains("<main>"), "unescaped text");
}

#[test]
fn catalogue_refusals_name_the_event_and_field() {
    let refused = |e: QuakeEvent| quakeml(&catalogue(vec![e])).unwrap_err().to_string();
    let e = refused(QuakeEvent { event_type: "stick-slip".into(), ..event("seed1/event2") });
    assert!(e.contains("events[0].event_type (seed1/event2)") && e.contains("stick-slip"), "{e}");
    let e = refused(QuakeEvent { event_type: "Earthquake".into(), ..event("a") });
    assert!(e.contains("event_type"), "{e}");
    let e = refused(QuakeEvent { longitude_deg: 190.0, ..event("seed1/event2") });
    assert!(e.contains("longitude_deg (seed1/event2)") && e.contains("190"), "{e}");
    let e = refused(QuakeEvent { latitude_deg: -90.5, ..event("a") });
    assert!(e.contains("latitude_deg") && e.contains("-90.5"), "{e}");
    let e = refused(QuakeEvent { depth_m: f64::NAN, ..event("a") });
    assert!(e.contains("depth_m") && e.contains("NaN"), "{e}");
    let e = refused(QuakeEvent { scalar_moment_n_m: Some(f64::INFINITY), ..event("a") });
    assert!(e.contains("scalar_moment_n_m") && e.contains("inf"), "{e}");
    let e = refused(QuakeEvent { scalar_moment_n_m: Some(-1.0), ..event("a") });
    assert!(e.contains("scalar_moment_n_m") && e.contains("≥ 0"), "{e}");
    let e = refused(QuakeEvent { origin_time_utc: "2000-01-01 00:00:00".into(), ..event("a") });
    assert!(e.contains("origin_time_utc") && e.contains("ISO 8601"), "{e}");
    let mut bad = event("a");
    bad.magnitudes[1].value = f64::NAN;
    let e = refused(bad);
    assert!(e.contains("events[0].magnitudes[1].value (a)"), "{e}");
    let mut bad = event("a");
    bad.magnitudes[0].magnitude_type = "M".repeat(33);
    assert!(refused(bad).contains("magnitudes[0].magnitude_type"));
    let e = refused(QuakeEvent { id: String::new(), ..event("a") });
    assert!(e.contains("events[0].id"), "{e}");
    // Two ids that become the same identifier.
    let e = quakeml(&catalogue(vec![event("seed 1"), event("seed_1")])).unwrap_err().to_string();
    assert!(e.contains("events[1].id") && e.contains("unique"), "{e}");
    for prefix in ["local/x", "smi:lo/x", "smi:local", "smi:local/", "http://x/y", "smi:lo cal/x"] {
        let e = quakeml(&Catalogue { public_id_prefix: prefix.into(), ..catalogue(vec![]) }).unwrap_err().to_string();
        assert!(e.contains("public_id_prefix") && e.contains("smi:"), "{prefix}: {e}");
    }
    let e = quakeml(&Catalogue { agency_id: "a".repeat(65), ..catalogue(vec![]) }).unwrap_err().to_string();
    assert!(e.contains("agency_id") && e.contains("64"), "{e}");
    let e = quakeml(&Catalogue { creation_utc: "2000-13-01T00:00:00Z".into(), ..catalogue(vec![]) })
        .unwrap_err()
        .to_string();
    assert!(e.contains("creation_utc"), "{e}");
    // A trailing '/' of the prefix is dropped; time zones and fractions of a second are dates.
    let xml = quakeml(&Catalogue {
        public_id_prefix: "quakeml:local.test/a/".into(),
        creation_utc: "2000-01-01T01:00:00.5+01:00".into(),
        ..catalogue(vec![event("x")])
    })
    .unwrap();
    assert!(xml.contains(r#"<event publicID="quakeml:local.test/a/x">"#));
}
