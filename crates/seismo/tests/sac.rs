//! SAC files written by `stickslip_seismo::accelerogram::sac` read back by a minimal reader written here from the
//! IRIS SAC manual ("SAC Data File Format"), sharing no code with the writer: byte offsets are
//! typed from the manual's tables (word n of the header starts at byte 4·n; strings start at
//! byte 440, KEVNM is 16 bytes, every other string 8).

use std::path::Path;

use stickslip_seismo::accelerogram::sac::{SacMeta, SacTime, SacUnit, sac_bytes, write_sac};

/// Little-endian float at header word `w`.
fn f(b: &[u8], w: usize) -> f32 {
    f32::from_le_bytes(b[4 * w..4 * w + 4].try_into().unwrap())
}
/// Little-endian integer at header word `w` (70–109).
fn i(b: &[u8], w: usize) -> i32 {
    i32::from_le_bytes(b[4 * w..4 * w + 4].try_into().unwrap())
}
/// String of `len` bytes at byte `at`.
fn k(b: &[u8], at: usize, len: usize) -> String {
    String::from_utf8(b[at..at + len].to_vec()).unwrap()
}

// Float words (manual): DELTA 0, DEPMIN 1, DEPMAX 2, SCALE 3, ODELTA 4, B 5, E 6, O 7, A 8,
// T0–T9 10–19, F 20, STLA 31, STLO 32, STEL 33, STDP 34, EVLA 35, EVLO 36, EVEL 37, EVDP 38,
// MAG 39, USER0–9 40–49, DIST 50, AZ 51, BAZ 52, GCARC 53, DEPMEN 56, CMPAZ 57, CMPINC 58.
// Integer words: NZYEAR 70, NZJDAY 71, NZHOUR 72, NZMIN 73, NZSEC 74, NZMSEC 75, NVHDR 76,
// NORID 77, NEVID 78, NPTS 79, IFTYPE 85, IDEP 86, IZTYPE 87, LEVEN 105, LPSPOL 106, LOVROK 107,
// LCALDA 108. Strings: KSTNM 440, KEVNM 448 (16), KHOLE 464, KO 472, KA 480, KT0–KT9 488–560,
// KF 568, KUSER0 576, KUSER1 584, KUSER2 592, KCMPNM 600, KNETWK 608, KDATRD 616, KINST 624;
// data from byte 632. Enumerations: ITIME 1, IUNKN 5, IACC 8, IB 9.

#[test]
fn header_fields_and_data_read_by_an_independent_reader() {
    let dt = 0.005;
    let accel: Vec<f64> = (0..1001).map(|n| 0.7 * (n as f64 * 0.031).sin() - 0.1).collect();
    let meta = SacMeta {
        station: "N0042".into(),
        component: "HNE".into(),
        network: "SS".into(),
        event: "seed3-event17".into(),
        begin: -1.5,
        origin: Some(0.25),
        reference: Some(SacTime { year: 2024, day_of_year: 45, hour: 12, minute: 30, second: 5, millisecond: 250 }),
        event_lat: Some(0.5),
        event_lon: Some(1.25),
        event_depth: Some(0.75),
        station_lat: Some(2.0),
        station_lon: Some(-3.0),
        distance: Some(2.5),
        user: [Some(1e-3), Some(42.0), None, None, None, None, None, None, None, Some(9.5)],
        user_labels: ["lscale".into(), "tscale".into(), "model".into()],
        ..SacMeta::default()
    };
    let b = sac_bytes(&accel, dt, &meta).unwrap();
    assert_eq!(b.len(), 632 + 4 * 1001);
    assert_eq!(i(&b, 76), 6, "NVHDR");
    assert_eq!(i(&b, 79), 1001, "NPTS");
    assert_eq!(i(&b, 85), 1, "IFTYPE = ITIME");
    assert_eq!(i(&b, 86), 8, "IDEP = IACC");
    assert_eq!(i(&b, 87), 9, "IZTYPE = IB");
    assert_eq!((i(&b, 105), i(&b, 107), i(&b, 108)), (1, 1, 0), "LEVEN, LOVROK, LCALDA");
    assert_eq!([i(&b, 70), i(&b, 71), i(&b, 72), i(&b, 73), i(&b, 74), i(&b, 75)], [2024, 45, 12, 30, 5, 250]);
    assert_eq!(f(&b, 0), 0.005f32, "DELTA");
    assert_eq!(f(&b, 5), -1.5, "B");
    assert!((f(&b, 6) - (-1.5 + 1000.0 * 0.005)).abs() < 1e-6, "E = B + (NPTS−1)·DELTA");
    assert_eq!(f(&b, 7), 0.25, "O");
    assert_eq!((f(&b, 35), f(&b, 36), f(&b, 38)), (0.5, 1.25, 0.75), "EVLA EVLO EVDP");
    assert_eq!((f(&b, 31), f(&b, 32), f(&b, 50)), (2.0, -3.0, 2.5), "STLA STLO DIST");
    assert_eq!((f(&b, 40), f(&b, 41), f(&b, 42), f(&b, 49)), (1e-3f32, 42.0, -12345.0, 9.5), "USER0 1 2 9");
    for w in [3, 4, 8, 10, 19, 20, 33, 34, 37, 39, 51, 52, 53, 57, 58] {
        assert_eq!(f(&b, w), -12345.0, "undefined float word {w}");
    }
    for w in [77, 78, 89, 90, 91, 92, 93, 94, 95, 96] {
        assert_eq!(i(&b, w), -12345, "undefined integer word {w}");
    }
    assert_eq!(k(&b, 440, 8), "N0042   ");
    assert_eq!(k(&b, 448, 16), "seed3-event17   ");
    assert_eq!(k(&b, 464, 8), "-12345  ", "KHOLE");
    assert_eq!(k(&b, 576, 8) + &k(&b, 584, 8) + &k(&b, 592, 8), "lscale  tscale  model   ");
    assert_eq!(k(&b, 600, 8), "HNE     ");
    assert_eq!(k(&b, 608, 8), "SS      ");
    assert_eq!(k(&b, 624, 8), "-12345  ", "KINST");
    // Data: nm/s² as f32, and DEPMIN/DEPMAX/DEPMEN of those values.
    let data: Vec<f32> = (0..1001).map(|n| f(&b, 158 + n)).collect();
    for (a, d) in accel.iter().zip(&data) {
        assert_eq!(*d, (a * 1e9) as f32);
    }
    let min = data.iter().cloned().fold(f32::INFINITY, f32::min);
    let max = data.iter().cloned().fold(f32::NEG_INFINITY, f32::max);
    let mean = data.iter().map(|&v| v as f64).sum::<f64>() / 1001.0;
    assert_eq!((f(&b, 1), f(&b, 2)), (min, max));
    assert!((f(&b, 56) as f64 - mean).abs() <= 1e-6 * mean.abs());
}

#[test]
fn metre_unit_and_undefined_reference_by_the_independent_reader() {
    let meta = SacMeta { station: "A".into(), unit: SacUnit::MetrePerSecond2, ..SacMeta::default() };
    let dir = std::env::temp_dir().join(format!("accel-sac-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("a.sac");
    write_sac(&path, &[0.5, -0.25, 1.0], 0.01, &meta).unwrap();
    let b = std::fs::read(Path::new(&path)).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!(i(&b, 86), 5, "IDEP = IUNKN for m/s²");
    assert_eq!(i(&b, 87), 5, "IZTYPE = IUNKN without a reference time");
    assert_eq!(i(&b, 70), -12345, "NZYEAR undefined");
    assert_eq!(f(&b, 7), -12345.0, "O undefined");
    assert_eq!(k(&b, 448, 16), "-12345          ", "KEVNM undefined");
    assert_eq!([f(&b, 158), f(&b, 159), f(&b, 160)], [0.5, -0.25, 1.0]);
    assert_eq!((f(&b, 1), f(&b, 2), f(&b, 56)), (-0.25, 1.0, (1.25f64 / 3.0) as f32)); // (0.5 − 0.25 + 1)/3
}

/// A record's position is not latitude and longitude: `STLA`/`STLO` (degrees) stay undefined,
/// x, y, z (m) go to `USER7`–`USER9` after the labelled numbers, the height also to `STEL` (m).
#[test]
fn a_records_position_is_metres_in_user7_to_9_not_degrees() {
    use stickslip_seismo::accelerogram::sac::{POSITION_USER, parse_sac};
    use stickslip_seismo::accelerogram::{RecordFile, RecordFormat, Sac};
    let accel = [0.0, 1.0, -0.5, 0.25];
    let numbers: [(&str, &[f64]); 3] = [("FILTER", &[0.5, 400.0]), ("USABLE", &[0.63, 51.0]), ("LAMBDA", &[100.0])];
    let record = RecordFile {
        description: "test",
        accel_m_s2: &accel,
        dt_s: 0.01,
        begin_s: 0.0,
        motion: None,
        station: "N36",
        component: "Z",
        network: "SS",
        location: "P",
        event: "S2",
        position_m: Some([20.0, 10.0, 10.0]),
        orientation: None,
        magnitude: None,
        origin_s: None,
        numbers: &numbers,
    };
    let bytes = Sac.encode(&record).unwrap();
    // Words 31 and 32 (STLA, STLO) hold SAC's undefined value.
    assert_eq!((f(&bytes, 31), f(&bytes, 32)), (-12345.0, -12345.0), "STLA STLO");
    assert_eq!(f(&bytes, 33), 10.0, "STEL");
    let t = parse_sac(&bytes, Path::new("t.SAC")).unwrap();
    assert_eq!(t.meta.station_lat, None);
    assert_eq!(t.meta.station_lon, None);
    assert_eq!(POSITION_USER, 7);
    assert_eq!(&t.meta.user[..5], &[Some(0.5), Some(400.0), Some(0.63), Some(51.0), Some(100.0)]);
    assert_eq!(&t.meta.user[7..], &[Some(20.0), Some(10.0), Some(10.0)]);
    // Numbers that would reach the position's slots are refused.
    let many: [(&str, &[f64]); 1] = [("MANY", &[1.0; 8])];
    assert!(Sac.encode(&RecordFile { numbers: &many, ..record }).is_err());
}
