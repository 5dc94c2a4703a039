//! Tests of the TDM reader and writer.

use super::*;

fn tiny() -> Scenario3d {
    let simulation = crate::sim::presets::tiny_3d(1).expect("tiny-3d");
    crate::scenario::from_simulation::to_scenario(&simulation).expect("scenario").0
}

/// Writes every sensor's TDM, reads them back and merges by time.
fn round_trip(scenario: &Scenario3d) -> Vec<Scan3dSpec> {
    let mut scans = vec![];
    for sensor in 0..scenario.sensors.len() {
        let text = write(scenario, sensor).expect("write");
        let tdm = parse(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        scans.extend(scans_of(&tdm, scenario).expect("scans").into_iter().map(|(s, _)| s));
    }
    scans.sort_by(|a, b| a.time.total_cmp(&b.time));
    scans
}

fn bits(scans: &[Scan3dSpec]) -> Vec<(u64, usize, Vec<Vec<u64>>)> {
    scans
        .iter()
        .map(|s| {
            (
                s.time.to_bits(),
                s.sensor,
                s.measurements.iter().map(|z| z.iter().map(|v| v.to_bits()).collect()).collect(),
            )
        })
        .collect()
}

#[test]
fn radar_scans_round_trip_bit_exactly() {
    let scenario = tiny();
    assert!(scenario.scans.iter().any(|s| !s.measurements.is_empty()));
    assert_eq!(bits(&round_trip(&scenario)), bits(&scenario.scans));
}

#[test]
fn range_rate_scans_with_awkward_values_round_trip_bit_exactly() {
    let mut scenario = tiny();
    scenario.measurement = Measurement3dSpec::RadarRangeRate;
    // Awkward times and values: fractions of a second, tiny and huge magnitudes, negative zero.
    let mut x: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let mut t = 0.0;
    for (k, scan) in scenario.scans.iter_mut().enumerate() {
        t += (next() >> 11) as f64 / (1u64 << 53) as f64 * 100.0 + 1e-9;
        scan.time = t;
        if k == 2 {
            scan.measurements.clear();
        }
        for z in &mut scan.measurements {
            z[1] = f64::from_bits(next()) % 180.0;
            z[2] = if k == 1 { -0.0 } else { (next() >> 11) as f64 / (1u64 << 53) as f64 * 90.0 };
            z.push(f64::from_bits(next()) % 8.0);
        }
    }
    let scans = round_trip(&scenario);
    assert_eq!(bits(&scans), bits(&scenario.scans));
    assert!(scans[2].measurements.is_empty());
}

fn error(text: &str) -> TdmError {
    parse(text).expect_err("refused")
}

const HEADER: &str = "CCSDS_TDM_VERS = 2.0\nCREATION_DATE = 2026-01-01T00:00:00\nORIGINATOR = me\n";

#[test]
fn structural_errors_name_line_and_keyword() {
    let e = error("");
    assert_eq!((e.line, e.keyword.as_str()), (1, "CCSDS_TDM_VERS"));
    let e = error("CCSDS_TDM_VERS = 3.0\n");
    assert_eq!((e.line, e.keyword.as_str()), (1, "CCSDS_TDM_VERS"));
    let e = error("CCSDS_TDM_VERS = 2.0\nORIGINATOR = me\nMETA_START\n");
    assert_eq!((e.line, e.keyword.as_str()), (3, "CREATION_DATE"));
    let e = error(&format!("{HEADER}META_START\nTIME_SYSTEM = UTC\nMETA_STOP\n"));
    assert_eq!((e.line, e.keyword.as_str()), (6, "PARTICIPANT_1"));
    let e = error(&format!("{HEADER}META_START\nPARTICIPANT_1 = a\nMETA_STOP\n"));
    assert_eq!((e.line, e.keyword.as_str()), (6, "TIME_SYSTEM"));
    let e = error(&format!("{HEADER}META_START\nTIME_SYSTEM = UTC\nPARTICIPANT_1 = a\nMETA_STOP\nDATA_START\n"));
    assert_eq!((e.line, e.keyword.as_str()), (9, "DATA_STOP"));
    let meta = format!("{HEADER}META_START\nTIME_SYSTEM = UTC\nPARTICIPANT_1 = a\nMETA_STOP\nDATA_START\n");
    let e = error(&format!("{meta}RANGE = 2026-01-01T00:00:00 nan\nDATA_STOP\n"));
    assert_eq!((e.line, e.keyword.as_str()), (9, "RANGE"));
    let e = error(&format!("{meta}RECEIVE_FREQ = 2026-01-01T00:00:00 1\nDATA_STOP\n"));
    assert_eq!((e.line, e.keyword.as_str(), e.message.as_str()), (9, "RECEIVE_FREQ", "data type not supported"));
    let e = error(&format!("{meta}RANGE = 2026-13-01T00:00:00 1\nDATA_STOP\n"));
    assert_eq!((e.line, e.keyword.as_str()), (9, "RANGE"));
    let e = error(&format!("{HEADER}META_START\nRANGE_UNITS = s\n"));
    assert_eq!((e.line, e.keyword.as_str()), (5, "RANGE_UNITS"));
    let ok = parse(&format!("{meta}COMMENT free text\nRANGE = 2026-01-01T00:00:00 1\nDATA_STOP\n")).expect("valid");
    assert_eq!(ok.segments[0].records.len(), 1);
}

#[test]
fn incomplete_or_misordered_measurements_are_refused() {
    let scenario = tiny();
    let text = write(&scenario, 0).expect("write");
    // Drop the first ANGLE_2: the measurement lacks it when the next RANGE comes.
    let lines: Vec<&str> = text.lines().collect();
    let at = lines.iter().position(|l| l.starts_with("ANGLE_2")).expect("ANGLE_2");
    let cut: String = lines.iter().enumerate().filter(|(i, _)| *i != at).map(|(_, l)| format!("{l}\n")).collect();
    let e = scans_of(&parse(&cut).expect("parses"), &scenario).expect_err("refused");
    assert_eq!((e.line, e.keyword.as_str()), (at + 1, "RANGE"), "{}", e.message);
}

#[test]
fn a_ten_megabyte_keyword_or_value_is_quoted_as_an_excerpt() {
    // Issue 33 item 7: the keyword and value were echoed whole.
    let text = write(&tiny(), 0).expect("write");
    let long = "X".repeat(10 << 20);
    let meta = text.find("META_START").expect("meta");
    for bad in [
        format!("{}META_START\n{long} = 1\n{}", &text[..meta], &text[meta + "META_START\n".len()..]),
        text.replacen("TIME_SYSTEM = UTC", &format!("TIME_SYSTEM = {long}"), 1),
    ] {
        assert_ne!(bad, text);
        let e = parse(&bad).unwrap_err();
        let shown = e.to_string();
        assert!(shown.len() < 300 && shown.contains("(10485760 bytes)"), "{}", &shown[..shown.len().min(300)]);
    }
}
