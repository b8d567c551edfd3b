//! StationXML and QuakeML written by `stickslip_seismo::{stationxml, quakeml}`: their structure,
//! escaping, exact numbers and refusals. ObsPy reads and schema-validates the files a run writes
//! in `python/tests/test_obspy.py`.

use stickslip_seismo::quakeml::{Catalogue, QuakeEvent, QuakeMagnitude, quakeml};
use stickslip_seismo::stationxml::{
    Channel, EARTH_RADIUS_M, Inventory, Network, Station, Units, local_to_geographic, stationxml,
};

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
        start_utc: "1999-12-31T00:00:00.000000Z".into(),
        description: "node 36 & friends <x>".into(),
    }
}

fn inventory(stations: Vec<Station>) -> Inventory {
    Inventory {
        source: "test".into(),
        sender: "stickslip".into(),
        module: "stickslip test".into(),
        created_utc: "2000-01-01T00:00:00.000000Z".into(),
        networks: vec![Network {
            code: "SS".into(),
            description: "test network".into(),
            start_utc: "1999-12-31T00:00:00.000000Z".into(),
            stations,
        }],
    }
}

fn station(code: &str, channels: Vec<Channel>) -> Station {
    Station {
        code: code.into(),
        latitude_deg: 0.01,
        longitude_deg: 0.02,
        elevation_m: 1000.0,
        site_name: "node 36".into(),
        description: "a \"quoted\" site".into(),
        start_utc: "1999-12-31T00:00:00.000000Z".into(),
        channels,
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
fn inventory_structure_escaping_and_exact_rates() {
    let rate = 1.0 / 0.0123;
    let inv = inventory(vec![
        station("N36", vec![channel("MNE", rate), channel("MNN", rate), channel("MNZ", rate)]),
        station("S001", vec![channel("HN1", 200.0)]),
    ]);
    let xml = stationxml(&inv).unwrap();
    assert!(xml.starts_with(r#"<?xml version="1.0" encoding="UTF-8"?>"#));
    assert!(xml.contains(r#"<FDSNStationXML xmlns="http://www.fdsn.org/xml/station/1" schemaVersion="1.2">"#));
    assert_eq!(xml.matches("<Station ").count(), 2);
    assert_eq!(xml.matches("<Channel ").count(), 4);
    assert_eq!(xml.matches("<Stage number=\"1\">").count(), 4, "one stage per channel");
    // Every sample rate reads back as the same f64.
    let rates: Vec<f64> = values(&xml, "SampleRate").iter().map(|v| v.parse().unwrap()).collect();
    assert_eq!(rates, [rate, rate, rate, 200.0]);
    assert!(values(&xml, "Name").contains(&"M/S**2"));
    assert!(xml.contains("node 36 &amp; friends &lt;x&gt;"));
    assert!(xml.contains("a &quot;quoted&quot; site"));
    assert!(!xml.contains("& "), "an unescaped ampersand");
}

#[test]
fn inventory_refusals_name_the_field() {
    let refused = |s: Station| stationxml(&inventory(vec![s])).unwrap_err().to_string();
    let e = refused(station("N 36", vec![]));
    assert!(e.contains("station") && e.contains("N 36"), "{e}");
    let e = refused(Station { latitude_deg: 91.0, ..station("N36", vec![]) });
    assert!(e.contains("latitude_deg") && e.contains("91") && e.contains("90"), "{e}");
    let e = refused(station("N36", vec![Channel { dip_deg: -95.0, ..channel("MNZ", 50.0) }]));
    assert!(e.contains("N36.P.MNZ") && e.contains("dip_deg") && e.contains("-95"), "{e}");
    let e = refused(station("N36", vec![channel("MNZ", 0.0)]));
    assert!(e.contains("sample_rate_hz") && e.contains("> 0"), "{e}");
    let e = refused(station("N36", vec![Channel { azimuth_deg: f64::NAN, ..channel("MNZ", 50.0) }]));
    assert!(e.contains("azimuth_deg") && e.contains("NaN"), "{e}");
}

#[test]
fn local_coordinates_on_the_sphere() {
    let (lat, lon) = local_to_geographic(1000.0, 2000.0, 0.0, 0.0);
    assert!((lat - (2000.0 / EARTH_RADIUS_M).to_degrees()).abs() < 1e-15);
    assert!((lon - (1000.0 / EARTH_RADIUS_M).to_degrees()).abs() < 1e-15);
    // At 60° N a parallel is half as long: the same metres east are twice the degrees.
    let (_, lon60) = local_to_geographic(1000.0, 0.0, 60.0, 10.0);
    assert!((lon60 - 10.0 - 2.0 * lon).abs() < 1e-12);
}

fn catalogue(events: Vec<QuakeEvent>) -> Catalogue {
    Catalogue {
        public_id_prefix: "smi:local/stickslip/test".into(),
        description: "test & catalogue".into(),
        creation_utc: "2000-01-01T00:00:00.000000Z".into(),
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
        origin_time_utc: "2000-01-01T00:10:21.478734Z".into(),
        latitude_deg: 0.0,
        longitude_deg: 0.018,
        depth_m: 0.0,
        origin_comment: Some("x 2000 m".into()),
        scalar_moment_n_m: Some(7.6e18),
        magnitudes: vec![
            QuakeMagnitude { value: 4.85, magnitude_type: "Mw".into(), method: "Hanks & Kanamori".into() },
            QuakeMagnitude { value: 6.778, magnitude_type: "M".into(), method: "Riera".into() },
        ],
    }
}

#[test]
fn catalogue_structure_ids_and_numbers() {
    let xml = quakeml(&catalogue(vec![event("seed7/event0"), event("seed 7/event 1")])).unwrap();
    assert!(xml.contains(r#"xmlns="http://quakeml.org/xmlns/bed/1.2""#));
    assert_eq!(xml.matches("<event ").count(), 2);
    assert_eq!(xml.matches("<magnitude ").count(), 4);
    assert_eq!(xml.matches("<momentTensor ").count(), 2);
    assert!(xml.contains(r#"<event publicID="smi:local/stickslip/test/seed7/event0">"#));
    // Characters a resource identifier may not hold become '_'.
    assert!(xml.contains(r#"<event publicID="smi:local/stickslip/test/seed_7/event_1">"#));
    assert!(
        xml.contains("<preferredMagnitudeID>smi:local/stickslip/test/seed7/event0/magnitude/0</preferredMagnitudeID>")
    );
    let mags: Vec<f64> = values(&xml, "mag")
        .iter()
        .map(|v| v.trim_start_matches("<value>").trim_end_matches("</value>").parse().unwrap())
        .collect();
    assert_eq!(mags, [4.85, 6.778, 4.85, 6.778]);
    assert!(xml.contains("<scalarMoment><value>7.6e18</value></scalarMoment>"));
    assert!(xml.contains("S2 &lt;main&gt;") && xml.contains("Hanks &amp; Kanamori"));
}

#[test]
fn catalogue_refusals_name_the_event_and_field() {
    let refused = |e: QuakeEvent| quakeml(&catalogue(vec![e])).unwrap_err().to_string();
    let e = refused(QuakeEvent { event_type: "stick-slip".into(), ..event("seed1/event2") });
    assert!(e.contains("seed1/event2") && e.contains("event_type") && e.contains("stick-slip"), "{e}");
    let e = refused(QuakeEvent { longitude_deg: 190.0, ..event("seed1/event2") });
    assert!(e.contains("longitude_deg") && e.contains("190"), "{e}");
    let e = refused(QuakeEvent { scalar_moment_n_m: Some(f64::INFINITY), ..event("a") });
    assert!(e.contains("scalar_moment_n_m") && e.contains("inf"), "{e}");
    let mut bad = event("a");
    bad.magnitudes[1].value = f64::NAN;
    let e = refused(bad);
    assert!(e.contains("magnitudes[1]"), "{e}");
    let e = quakeml(&Catalogue { public_id_prefix: "local/x".into(), ..catalogue(vec![]) }).unwrap_err().to_string();
    assert!(e.contains("public_id_prefix") && e.contains("smi:"), "{e}");
}
