//! Tests of the catalogue readers and SGP4.

use super::files::parse;
use super::omm::parse_omm_epoch;
use super::propagation::Satellite;
use super::tle::parse_catalogue_number;

const L1: &str = "1 00005U 58002B   00179.78495062  .00000023  00000-0  28098-4 0  4753";
const L2: &str = "2 00005  34.2682 348.7242 1859667 331.7664  19.3264 10.82419157413667";

#[test]
fn alpha5_catalogue_numbers() {
    assert_eq!(parse_catalogue_number("A0001"), Some(100_001));
    assert_eq!(parse_catalogue_number("H9999"), Some(179_999));
    assert_eq!(parse_catalogue_number("J0000"), Some(180_000));
    assert_eq!(parse_catalogue_number("P0000"), Some(230_000));
    assert_eq!(parse_catalogue_number("Z9999"), Some(339_999));
    assert_eq!(parse_catalogue_number("00005"), Some(5));
    assert_eq!(parse_catalogue_number("    5"), Some(5));
    assert_eq!(parse_catalogue_number("I0001"), None);
    assert_eq!(parse_catalogue_number("O0001"), None);
    assert_eq!(parse_catalogue_number("a0001"), None);
    assert_eq!(parse_catalogue_number("     "), None);
    assert_eq!(parse_catalogue_number("0A001"), None);
}

#[test]
fn tle_fields_are_read() {
    let e = &parse("t", &format!("{L1}\n{L2}\n")).unwrap()[0];
    assert_eq!(e.norad_id, 5);
    assert_eq!(e.international_designator.as_deref(), Some("58002B"));
    assert_eq!(e.epoch.to_string(), "2000-06-27 18:50:19.733567999");
    assert_eq!(e.mean_motion_dot, 0.00000023);
    assert_eq!(e.bstar, 0.28098e-4);
    assert_eq!(e.eccentricity, 0.1859667);
    assert_eq!(e.mean_motion, 10.82419157);
    assert_eq!(e.revolution_number, 41366);
    assert_eq!(e.element_set_number, 475);
}

#[test]
fn tle_agrees_with_the_sgp4_crate_parser() {
    let ours = parse("t", &format!("{L1}\n{L2}\n")).unwrap()[0].to_sgp4();
    let theirs = sgp4::Elements::from_tle(None, L1.as_bytes(), L2.as_bytes()).unwrap();
    assert_eq!(ours.norad_id, theirs.norad_id);
    assert!((ours.datetime - theirs.datetime).num_nanoseconds().unwrap().abs() <= 1);
    for (a, b) in [
        (ours.drag_term, theirs.drag_term),
        (ours.eccentricity, theirs.eccentricity),
        (ours.mean_motion, theirs.mean_motion),
        (ours.inclination, theirs.inclination),
        (ours.mean_motion_ddot, theirs.mean_motion_ddot),
    ] {
        assert!((a - b).abs() <= 1e-15 * b.abs().max(1.0), "{a} vs {b}");
    }
}

#[test]
fn checksum_is_verified() {
    let bad = format!("{}4", &L1[..68]);
    let e = parse("f.tle", &format!("{bad}\n{L2}\n")).unwrap_err();
    assert_eq!(e.line, 1);
    assert!(e.keyword.contains("checksum"), "{e}");
}

#[test]
fn omm_json_and_csv_give_the_tle_elements() {
    let json = r#"[{"OBJECT_NAME":"X","OBJECT_ID":"1958-002B","EPOCH":"2000-06-27T18:50:19.733568",
        "MEAN_MOTION":10.82419157,"ECCENTRICITY":0.1859667,"INCLINATION":34.2682,"RA_OF_ASC_NODE":348.7242,
        "ARG_OF_PERICENTER":331.7664,"MEAN_ANOMALY":19.3264,"EPHEMERIS_TYPE":0,"CLASSIFICATION_TYPE":"U",
        "NORAD_CAT_ID":5,"ELEMENT_SET_NO":475,"REV_AT_EPOCH":41366,"BSTAR":2.8098e-5,
        "MEAN_MOTION_DOT":2.3e-7,"MEAN_MOTION_DDOT":0}]"#;
    let csv = "OBJECT_NAME,OBJECT_ID,EPOCH,MEAN_MOTION,ECCENTRICITY,INCLINATION,RA_OF_ASC_NODE,\
        ARG_OF_PERICENTER,MEAN_ANOMALY,EPHEMERIS_TYPE,CLASSIFICATION_TYPE,NORAD_CAT_ID,ELEMENT_SET_NO,\
        REV_AT_EPOCH,BSTAR,MEAN_MOTION_DOT,MEAN_MOTION_DDOT\n\
        X,1958-002B,2000-06-27T18:50:19.733568,10.82419157,.1859667,34.2682,348.7242,331.7664,19.3264,0,U,5,\
        475,41366,.28098E-4,.23E-6,0\n";
    let tle = Satellite::new(parse("t", &format!("{L1}\n{L2}\n")).unwrap().remove(0)).unwrap();
    for text in [json, csv] {
        let entries = parse("o", text).unwrap();
        assert_eq!(entries.len(), 1);
        assert_eq!(entries[0].name.as_deref(), Some("X"));
        let omm = Satellite::new(entries[0].clone()).unwrap();
        let (a, b) = (tle.teme(720.0).unwrap(), omm.teme(720.0).unwrap());
        for i in 0..3 {
            assert!((a.0[i] - b.0[i]).abs() < 1e-6, "{a:?} {b:?}");
        }
    }
}

#[test]
fn a_state_sgp4_cannot_make_finite_is_an_error() {
    // Found by the `catalogue` fuzz target: SGP4 accepts a mean motion of 1.6e141 revolutions a day and
    // returns NaN; the propagator refuses the state instead.
    let json = r#"[{"OBJECT_NAME":"X","OBJECT_ID":"1998-067A","EPOCH":"2024-03-15T12:00:00.000000",
        "MEAN_MOTION":1.5888888e141,"ECCENTRICITY":0.0005,"INCLINATION":51.64,"RA_OF_ASC_NODE":120.5,
        "ARG_OF_PERICENTER":80.0,"MEAN_ANOMALY":10.0,"NORAD_CAT_ID":25544,"BSTAR":0.0001,
        "MEAN_MOTION_DOT":0,"MEAN_MOTION_DDOT":0}]"#;
    let Ok(mut entries) = parse("o", json) else { return };
    let Ok(sat) = Satellite::new(entries.remove(0)) else { return };
    assert_eq!(sat.teme(0.0).map_err(|e| e.kind()), Err("non-finite-state"));
    if let Ok((r, v)) = sat.teme(1440.0) {
        assert!(r.iter().chain(&v).all(|x| x.is_finite()), "{r:?} {v:?}");
    }
}

#[test]
fn tracker_time_is_minutes_since_the_element_epoch() {
    let sat = Satellite::new(parse("t", &format!("{L1}\n{L2}\n")).unwrap().remove(0)).unwrap();
    let start = parse_omm_epoch("2000-06-28T00:00:00").unwrap();
    let minutes = sat.minutes_since_epoch(start, 600.0);
    let expected = (86_400.0 - (18.0 * 3600.0 + 50.0 * 60.0 + 19.733568)) / 60.0 + 10.0;
    assert!((minutes - expected).abs() < 1e-9, "{minutes} {expected}");
    assert_eq!(sat.tracker_state(start, 600.0).unwrap(), sat.teme(minutes).unwrap());
}

/// A catalogue of `n` copies of the element set of `L1`/`L2` (catalogue numbers 1..=n) in `format`.
fn catalogue_of(format: super::Format, n: usize) -> String {
    use std::fmt::Write;
    let mut text = String::new();
    match format {
        super::Format::OmmJson => {
            text.push('[');
            for id in 1..=n {
                let comma = if id < n { "," } else { "" };
                let _ = writeln!(
                    text,
                    "{{\"OBJECT_NAME\":\"X{id}\",\"EPOCH\":\"2000-06-27T18:50:19.733568\",\"MEAN_MOTION\":10.82419157,\
                     \n\"ECCENTRICITY\":0.1859667,\"INCLINATION\":34.2682,\"RA_OF_ASC_NODE\":348.7242,\
                     \n\"ARG_OF_PERICENTER\":331.7664,\"MEAN_ANOMALY\":19.3264,\"NORAD_CAT_ID\":{id},\"BSTAR\":2.8098e-5,\
                     \n\"MEAN_MOTION_DOT\":2.3e-7,\"MEAN_MOTION_DDOT\":0}}{comma}"
                );
            }
            text.push(']');
        }
        super::Format::OmmCsv => {
            text.push_str(
                "OBJECT_NAME,EPOCH,MEAN_MOTION,ECCENTRICITY,INCLINATION,RA_OF_ASC_NODE,ARG_OF_PERICENTER,\
                MEAN_ANOMALY,NORAD_CAT_ID,BSTAR,MEAN_MOTION_DOT,MEAN_MOTION_DDOT\n",
            );
            for id in 1..=n {
                let _ = writeln!(
                    text,
                    "X{id},2000-06-27T18:50:19.733568,10.82419157,.1859667,34.2682,348.7242,331.7664,19.3264,{id},\
                     .28098E-4,.23E-6,0"
                );
            }
        }
        super::Format::Tle => {
            for id in 1..=n {
                let _ = writeln!(text, "X{id}\n{L1}\n{L2}");
            }
        }
    }
    text
}

/// The time (s) to read `text` of `n` records.
fn reading_time(text: &str, n: usize) -> f64 {
    let start = std::time::Instant::now();
    assert_eq!(parse("t", text).unwrap().len(), n);
    start.elapsed().as_secs_f64()
}

/// Reading 8n records takes about 8 times as long as n, not 64 (an OMM JSON of 10,000 records took 85
/// times as long as 1,000 when each record's line was counted from the start of the file). The shortest
/// of five alternating readings of each size, so that a busy machine slows both alike.
#[test]
fn reading_time_grows_linearly_with_the_records() {
    let n = 400;
    for format in [super::Format::OmmJson, super::Format::OmmCsv, super::Format::Tle] {
        let (small, large) = (catalogue_of(format, n), catalogue_of(format, 8 * n));
        assert_eq!(super::detect(&small), format);
        let (mut t_small, mut t_large) = (f64::INFINITY, f64::INFINITY);
        for _ in 0..5 {
            t_small = t_small.min(reading_time(&small, n));
            t_large = t_large.min(reading_time(&large, 8 * n));
        }
        let ratio = t_large / t_small;
        assert!(ratio < 30.0, "{format:?}: 8 times the records took {ratio:.1} times as long");
    }
}

#[test]
fn a_tab_in_a_tle_line_is_named() {
    // Issue 33 item 7: "name line: not followed by a line 1".
    for (text, keyword) in [
        (format!("NAME\n{}\n{L2}\n", L1.replacen(' ', "\t", 1)), "line 1"),
        (format!("NAME\n{L1}\n{}\n", L2.replacen(' ', "\t", 1)), "line 2"),
        (format!("{}\n{L2}\n", L1.replacen("  ", " \t", 1)), "line 1"),
    ] {
        let e = parse("t", &text).unwrap_err();
        assert_eq!(e.keyword, keyword, "{e}");
        assert!(e.message.contains("contains a tab"), "{e}");
    }
    let e = parse("t", &format!("NAME\nOTHER NAME\n{L1}\n{L2}\n")).unwrap_err();
    assert_eq!((e.line, e.message.as_str()), (1, "not followed by a line 1: line 2 does not start with \"1 \""));
}

#[test]
fn a_ten_megabyte_omm_value_is_quoted_as_an_excerpt() {
    let long = "Z".repeat(10 << 20);
    let base = catalogue_of(super::Format::OmmJson, 1);
    for (key, from) in [("EPOCH", "2000-06-27T18:50:19.733568"), ("OBJECT_NAME", "X1")] {
        let text = base.replacen(from, &long, 1);
        let e = parse("t", &text).unwrap_err();
        assert_eq!(e.keyword, key);
        assert!(e.to_string().len() < 200, "{}", &e.to_string()[..300]);
    }
    let text = base.replacen("\"EPOCH\"", &format!("\"{long}\":1,\"EPOCH\""), 1);
    assert_eq!(parse("t", &text).unwrap().len(), 1, "unknown OMM keywords are ignored");
}

/// The reading times of the note (issue 33): `cargo test --release -p host-sim --lib -- --ignored
/// catalogue_reading_benchmark --nocapture` prints the time to parse 1k, 10k and 100k OMM JSON records, 100k
/// OMM CSV records and a million-line TLE file (shortest of three).
#[test]
#[ignore = "a benchmark: run in release with --nocapture"]
fn catalogue_reading_benchmark() {
    let cases = [
        (super::Format::OmmJson, 1_000),
        (super::Format::OmmJson, 10_000),
        (super::Format::OmmJson, 100_000),
        (super::Format::OmmCsv, 100_000),
        (super::Format::Tle, 333_333),
    ];
    for (format, n) in cases {
        let text = catalogue_of(format, n);
        let seconds = (0..3).map(|_| reading_time(&text, n)).fold(f64::INFINITY, f64::min);
        println!("{format:?}: {n} records, {} lines, {} MB: {seconds:.3} s", text.lines().count(), text.len() >> 20);
        if format == super::Format::OmmJson {
            // Of which serde_json's own parse into a value tree.
            let start = std::time::Instant::now();
            let value: serde_json::Value = serde_json::from_str(&text).unwrap();
            let parsed = start.elapsed().as_secs_f64();
            drop(value);
            println!("  of which serde_json::Value: {parsed:.3} s");
        }
    }
}
