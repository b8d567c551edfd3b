//! MiniSEED 2 records written by `stickslip_seismo::accelerogram::mseed`, checked byte by byte at
//! the offsets of the SEED 2.4 manual (chapter 8: the fixed section of the data header; Blockettes
//! 100, 1000, 1001), and read back. ObsPy reads the same files in `python/tests/test_obspy.py`.

use stickslip_seismo::accelerogram::mseed::{
    MseedTrace, RECORD_BYTES, SAMPLES_PER_RECORD, UtcTime, band_code, channel_code, mseed_bytes, parse_mseed,
    sample_rate,
};
use stickslip_seismo::accelerogram::{Mseed, RecordFile, RecordFormat};

fn be16(b: &[u8], at: usize) -> u16 {
    u16::from_be_bytes([b[at], b[at + 1]])
}

fn trace(samples: &[f64], rate: f64, start_s: f64) -> Vec<u8> {
    mseed_bytes(&MseedTrace {
        network: "SS",
        station: "N36",
        location: "M",
        channel: "FNE",
        start_s,
        sample_rate_hz: rate,
        samples,
    })
    .unwrap()
}

#[test]
fn header_of_a_record_at_the_manuals_offsets() {
    let samples: Vec<f64> = (0..1200).map(|k| (k as f64 * 0.01).sin() * 3.7).collect();
    let b = trace(&samples, 200.0, 12.3456789);
    // 1200 samples: three records of 496, 496 and 208.
    assert_eq!(b.len(), 3 * RECORD_BYTES);
    assert_eq!(SAMPLES_PER_RECORD, 496);
    assert_eq!(&b[0..8], b"000001D ");
    assert_eq!(&b[8..20], b"N36  M FNESS");
    // BTIME: 2000, day 1, 00:00:12.3456 (+ 79 µs in Blockette 1001 → −21 µs after rounding up).
    assert_eq!(be16(&b, 20), 2000);
    assert_eq!(be16(&b, 22), 1);
    assert_eq!((b[24], b[25], b[26]), (0, 0, 12));
    let ticks = be16(&b, 28) as i64;
    let micro = b[61] as i8 as i64;
    assert_eq!(ticks * 100 + micro, 345_679);
    assert_eq!(be16(&b, 30), 496);
    // 200 Hz is exact as factor/multiplier: no Blockette 100, two blockettes.
    assert_eq!((be16(&b, 32) as i16, be16(&b, 34) as i16), (200, -1));
    assert_eq!(b[39], 2);
    assert_eq!(be16(&b, 44), 128);
    assert_eq!(be16(&b, 46), 48);
    assert_eq!((be16(&b, 48), be16(&b, 50), b[52], b[53], b[54]), (1000, 56, 5, 1, 12));
    assert_eq!((be16(&b, 56), be16(&b, 58)), (1001, 0));
    let first = f64::from_be_bytes(b[128..136].try_into().unwrap());
    assert_eq!(first, samples[0]);
    // The second record starts 496 samples later: 12.3456789 + 2.48 s.
    let r2 = &b[RECORD_BYTES..];
    assert_eq!(&r2[0..7], b"000002D");
    assert_eq!(r2[26], 14);
    assert_eq!(be16(r2, 28) as i64 * 100 + r2[61] as i8 as i64, 825_679);
    let back = parse_mseed(&b).unwrap();
    assert_eq!(back.samples, samples);
    assert_eq!(back.codes, ["SS", "N36", "M", "FNE"].map(String::from));
    assert_eq!(back.sample_rate_hz, 200.0);
    assert_eq!(back.start.iso(), "2000-01-01T00:00:12.345679Z");
}

#[test]
fn rates_exact_as_ratios_or_in_blockette_100() {
    // 1/0.0123 s = 10000/123 Hz: exact as factor 10000, multiplier −123.
    let rate = 1.0 / 0.0123;
    let b = trace(&[1.0, 2.0], rate, 0.0);
    assert_eq!((be16(&b, 32) as i16, be16(&b, 34) as i16), (10000, -123));
    assert_eq!(-(be16(&b, 32) as i16 as f64) / (be16(&b, 34) as i16 as f64), rate);
    // A period of 120 s: factor 1, multiplier −120.
    let b = trace(&[1.0], 1.0 / 120.0, 0.0);
    assert_eq!((be16(&b, 32) as i16, be16(&b, 34) as i16), (1, -120));
    // A lattice step's rate is no such ratio: Blockette 100 carries it to 32-bit precision.
    let rate = 1.0 / 1.234_567_89e-4;
    let b = trace(&[1.0; 10], rate, 0.0);
    assert_eq!(b[39], 3);
    assert_eq!(be16(&b, 58), 64);
    assert_eq!(be16(&b, 64), 100);
    let b100 = f32::from_be_bytes(b[68..72].try_into().unwrap());
    assert_eq!(b100, rate as f32);
    assert!(((b100 as f64) / rate - 1.0).abs() < 6e-8);
    assert_eq!(parse_mseed(&b).unwrap().sample_rate_hz, b100 as f64);
}

#[test]
fn the_rate_an_interval_means() {
    // 1/2e-5 is 49 999.999 999 999 99 in f64: the pipeline meant 50 kHz.
    assert_eq!(sample_rate(2e-5), 50_000.0);
    assert_eq!(sample_rate(0.005), 200.0);
    assert_eq!(sample_rate(0.0123), 1.0 / 0.0123, "no whole number or thousandth within 1e-12");
    assert_eq!(sample_rate(1.234_567_89e-4), 1.0 / 1.234_567_89e-4);
}

#[test]
fn nominal_clock_to_calendar() {
    let iso = |s: f64| UtcTime::from_nominal(s).unwrap().iso();
    assert_eq!(iso(0.0), "2000-01-01T00:00:00.000000Z");
    assert_eq!(iso(-1.0), "1999-12-31T23:59:59.000000Z");
    // 2000 is a leap year: day 60 is 29 February, 366 days later is 2001-01-01.
    assert_eq!(iso(59.0 * 86_400.0 + 0.5), "2000-02-29T00:00:00.500000Z");
    assert_eq!(iso(366.0 * 86_400.0), "2001-01-01T00:00:00.000000Z");
    assert_eq!(UtcTime::from_nominal(366.0 * 86_400.0 - 1.0).unwrap().day_of_year, 366);
    // A century of loading (2100 is not a leap year).
    let t = UtcTime::from_nominal(36_525.0 * 86_400.0 + 59.0 * 86_400.0).unwrap();
    assert_eq!((t.year, t.month, t.day, t.day_of_year), (2100, 3, 1, 60));
    assert_eq!(iso(0.999_999_6), "2000-01-01T00:00:01.000000Z");
    assert!(UtcTime::from_nominal(f64::NAN).is_err());
}

#[test]
fn codes_and_channels() {
    assert_eq!(band_code(200.0), 'H');
    assert_eq!(band_code(8100.0), 'F');
    assert_eq!(band_code(40.0), 'B');
    assert_eq!(channel_code("X", 200.0).unwrap(), "HNE");
    assert_eq!(channel_code("z", 50.0).unwrap(), "BNZ");
    assert_eq!(channel_code("HN1", 50.0).unwrap(), "HN1");
    let e = channel_code("radial", 50.0).unwrap_err().to_string();
    assert!(e.contains("component") && e.contains("radial"), "{e}");
    let bad = |network: &str, station: &str| {
        mseed_bytes(&MseedTrace {
            network,
            station,
            location: "",
            channel: "HNZ",
            start_s: 0.0,
            sample_rate_hz: 100.0,
            samples: &[0.0],
        })
        .unwrap_err()
        .to_string()
    };
    let e = bad("SS", "N123456");
    assert!(e.contains("station") && e.contains("N123456") && e.contains("1–5"), "{e}");
    let e = bad("SSX", "A");
    assert!(e.contains("network") && e.contains("SSX"), "{e}");
    let e = mseed_bytes(&MseedTrace {
        network: "SS",
        station: "A",
        location: "",
        channel: "HNZ",
        start_s: 0.0,
        sample_rate_hz: 100.0,
        samples: &[0.0, f64::NAN],
    })
    .unwrap_err()
    .to_string();
    assert!(e.contains("samples") && e.contains("NaN"), "{e}");
}

#[test]
fn the_record_format_places_the_origin_at_the_nominal_time() {
    let accel = [0.1, -0.2, 0.3];
    let record = RecordFile {
        description: "test",
        accel_m_s2: &accel,
        dt_s: 0.005,
        begin_s: 7.25,
        motion: None,
        station: "S01",
        component: "HN1",
        network: "SS",
        location: "P",
        event: "seed1",
        position_m: None,
        orientation: None,
        magnitude: None,
        origin_s: Some(2.0),
        numbers: &[],
    };
    let back = parse_mseed(&Mseed.encode(&record).unwrap()).unwrap();
    assert_eq!(back.start.iso(), "2000-01-01T00:00:05.250000Z");
    assert_eq!(back.samples, accel);
    assert_eq!(back.codes[3], "HN1");
    let x = RecordFile { component: "X", dt_s: 1.0 / 8192.0, ..record };
    assert_eq!(parse_mseed(&Mseed.encode(&x).unwrap()).unwrap().codes[3], "FNE");
}
