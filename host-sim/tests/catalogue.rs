//! Integration tests of catalogue input (issue 15): `host-sim sgp4-check` against the SGP4 verification
//! cases of Vallado et al. 2006, and `host-sim catalogue` on good and malformed TLE / OMM files (one test
//! per row of docs/robustness.md's catalogue rows).

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

mod common;
use common::{BIN, TempDir, host_sim};
const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/data/sgp4-verification");

const L1: &str = "1 00005U 58002B   00179.78495062  .00000023  00000-0  28098-4 0  4753";
const L2: &str = "2 00005  34.2682 348.7242 1859667 331.7664  19.3264 10.82419157413667";

const OMM_KEYS: &str = "OBJECT_NAME,OBJECT_ID,EPOCH,MEAN_MOTION,ECCENTRICITY,INCLINATION,RA_OF_ASC_NODE,\
ARG_OF_PERICENTER,MEAN_ANOMALY,EPHEMERIS_TYPE,CLASSIFICATION_TYPE,NORAD_CAT_ID,ELEMENT_SET_NO,REV_AT_EPOCH,\
BSTAR,MEAN_MOTION_DOT,MEAN_MOTION_DDOT";
const OMM_ROW: &str = "ISS (ZARYA),1998-067A,2024-03-15T12:00:00.000000,15.5,.0005,51.64,120.5,80.1,280.2,0,U,\
25544,999,44000,.00012,.00001,0";

fn describe(output: &Output) -> String {
    format!(
        "status {:?}\nstdout:\n{}\nstderr:\n{}",
        output.status.code(),
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("read output")).expect("JSON output")
}

/// `line` (68 columns or more) with its checksum in column 69.
fn with_checksum(line: &str) -> String {
    let body = &line[..68];
    let sum: u32 = body
        .bytes()
        .map(|b| match b {
            b'0'..=b'9' => u32::from(b - b'0'),
            b'-' => 1,
            _ => 0,
        })
        .sum();
    format!("{body}{}", sum % 10)
}

/// `line` with columns `from..=to` (1-based) replaced by `text`, checksum fixed.
fn patched(line: &str, from: usize, text: &str) -> String {
    let mut s = line.to_string();
    s.replace_range(from - 1..from - 1 + text.len(), text);
    with_checksum(&s)
}

#[test]
fn sgp4_check_matches_the_verification_cases() {
    let dir = TempDir::new("check");
    let out = dir.join("sgp4.json");
    let output = host_sim(&["sgp4-check".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let report = read_json(&out);
    assert_eq!(report["cases"], 33);
    assert_eq!(report["states"], 666);
    assert_eq!(report["error_cases"], 2);
    assert_eq!(report["error_cases_matched"], 2);
    assert_eq!(report["mismatched_cases"], 0);
    let position = report["max_position_error_km"].as_f64().expect("number");
    let velocity = report["max_velocity_error_km_s"].as_f64().expect("number");
    // Measured: 2.05e-7 km and 8.53e-10 km/s (the expected states carry 8 and 9 decimals).
    assert!(position < 1e-6, "max position error {position} km");
    assert!(velocity < 1e-9, "max velocity error {velocity} km/s");
}

#[test]
fn sgp4_check_detects_a_changed_state_and_a_changed_error() {
    let dir = TempDir::new("check-bad");
    let tle = format!("{DATA}/sgp4-ver.tle");
    let text = std::fs::read_to_string(format!("{DATA}/sgp4-ver-expected.txt")).expect("expected file");
    // One position component off by 1 m.
    let state = text.replacen("7022.46529266", "7022.46629266", 1);
    assert_ne!(state, text);
    let state_file = dir.join("state.txt");
    std::fs::write(&state_file, state).expect("write");
    let out = dir.join("a.json");
    let output = host_sim(&[
        "sgp4-check".as_ref(),
        "--tle".as_ref(),
        tle.as_ref(),
        "--expected".as_ref(),
        state_file.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let error = read_json(&out)["max_position_error_km"].as_f64().expect("number");
    assert!((error - 1e-3).abs() < 1e-6, "{error}");
    // An error case that expects another error: a mismatch, exit code 1 after the report.
    let kind = text.replacen("error negative-semi-latus-rectum", "error diverging-eccentricity", 1);
    assert_ne!(kind, text);
    let kind_file = dir.join("kind.txt");
    std::fs::write(&kind_file, kind).expect("write");
    let out = dir.join("b.json");
    let output = host_sim(&[
        "sgp4-check".as_ref(),
        "--tle".as_ref(),
        tle.as_ref(),
        "--expected".as_ref(),
        kind_file.as_os_str(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(output.status.code(), Some(1), "{}", describe(&output));
    let report = read_json(&out);
    assert_eq!(report["error_cases_matched"], 1);
    assert_eq!(report["mismatched_cases"], 1);
}

fn catalogue(dir: &TempDir, name: &str, text: &[u8]) -> (Output, PathBuf) {
    let file = dir.join(name);
    std::fs::write(&file, text).expect("write catalogue");
    let out = dir.join("out").join("objects.json");
    std::fs::create_dir_all(dir.join("out")).expect("out dir");
    let _ = std::fs::remove_file(&out);
    let output = host_sim(&["catalogue".as_ref(), file.as_os_str(), "--out".as_ref(), out.as_os_str()]);
    (output, out)
}

#[test]
fn good_catalogues_in_every_format_are_read() {
    let dir = TempDir::new("good");
    let alpha5 = [patched(L1, 3, "A0001"), patched(L2, 3, "A0001")];
    let tle = format!("ISS\n{L1}\n{L2}\n\n0 ALPHA FIVE\n{}\n{}\n", alpha5[0], alpha5[1]);
    let (output, out) = catalogue(&dir, "c.tle", tle.as_bytes());
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let objects = read_json(&out);
    assert_eq!(objects[0]["name"], "ISS");
    assert_eq!(objects[1]["norad_id"], 100_001);
    assert_eq!(objects[1]["name"], "ALPHA FIVE");
    assert_eq!(objects[1]["line"], 5);
    // At the epoch, the verification case's first state.
    let r = &objects[0]["position_km"];
    assert!((r[0].as_f64().unwrap() - 7022.46529266).abs() < 1e-6, "{r}");
    let csv = format!("{OMM_KEYS}\n{OMM_ROW}\n");
    let (output, out) = catalogue(&dir, "c.csv", csv.as_bytes());
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    assert_eq!(read_json(&out)[0]["norad_id"], 25544);
    let json = omm_json(&[]);
    let (output, out) = catalogue(&dir, "c.json", json.as_bytes());
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    assert_eq!(read_json(&out)[0]["name"], "ISS (ZARYA)");
}

/// CelesTrak-style OMM JSON of one object, one key a line, with `changes` (key, JSON value or `None` to
/// drop the key) applied.
fn omm_json(changes: &[(&str, Option<&str>)]) -> String {
    let keys: Vec<&str> = OMM_KEYS.split(',').collect();
    let values: Vec<&str> = OMM_ROW.split(',').collect();
    let mut lines = vec![];
    for (key, value) in keys.iter().zip(&values) {
        let text = match changes.iter().find(|(k, _)| k == key) {
            Some((_, None)) => continue,
            Some((_, Some(v))) => v.to_string(),
            None if ["OBJECT_NAME", "OBJECT_ID", "EPOCH", "CLASSIFICATION_TYPE"].contains(key) => {
                format!("\"{value}\"")
            }
            None => format!("{}", value.parse::<f64>().expect("number")),
        };
        lines.push(format!("    \"{key}\": {text}"));
    }
    format!("[\n  {{\n{}\n  }}\n]\n", lines.join(",\n"))
}

/// A rejected catalogue: exit 2, one `error:` line holding every part of `expect`, no output file.
fn assert_rejected(dir: &TempDir, name: &str, text: &[u8], expect: &[&str]) {
    let (output, out) = catalogue(dir, name, text);
    let err = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(2), "{name}: {}", describe(&output));
    assert!(!err.contains("panicked"), "{name}: {err}");
    assert!(err.starts_with("error: ") && err.ends_with('\n') && err.lines().count() == 1, "{name}: {err:?}");
    for part in expect {
        assert!(err.contains(part), "{name}: {err:?} lacks {part:?}");
    }
    assert!(!out.exists(), "{name}: an output file was written");
}

#[test]
fn tle_with_a_bad_checksum_is_rejected() {
    let dir = TempDir::new("checksum");
    let bad = format!("{}4", &L1[..68]);
    assert_rejected(
        &dir,
        "a.tle",
        format!("NAME\n{bad}\n{L2}\n").as_bytes(),
        &["a.tle:2:", "line 1 column 69 (checksum)"],
    );
    let bad = format!("{}0", &L2[..68]);
    assert_rejected(&dir, "b.tle", format!("{L1}\n{bad}\n").as_bytes(), &["b.tle:2:", "line 2 column 69 (checksum)"]);
}

#[test]
fn tle_with_wrong_columns_is_rejected() {
    let dir = TempDir::new("columns");
    let short = &L1[..60];
    assert_rejected(&dir, "a.tle", format!("{short}\n{L2}\n").as_bytes(), &["a.tle:1:", "60 columns, expected 69"]);
    let long = format!("{L2}9");
    assert_rejected(&dir, "b.tle", format!("{L1}\n{long}\n").as_bytes(), &["b.tle:2:", "70 columns"]);
    // A field shifted by one column: column 9 must be blank.
    let shifted = patched(L1, 9, "5");
    assert_rejected(&dir, "c.tle", format!("{shifted}\n{L2}\n").as_bytes(), &["c.tle:1:", "line 1 column 9"]);
    let letters = patched(L2, 9, " 34.26x2");
    assert_rejected(
        &dir,
        "d.tle",
        format!("{L1}\n{letters}\n").as_bytes(),
        &["d.tle:2:", "columns 9-16 (inclination)"],
    );
    assert_rejected(&dir, "e.tle", format!("{L1}\n").as_bytes(), &["e.tle:1:", "line 2: missing"]);
    assert_rejected(&dir, "f.tle", format!("{L2}\n").as_bytes(), &["f.tle:1:", "without a line 1"]);
}

#[test]
fn tle_with_eccentricity_out_of_range_is_rejected() {
    let dir = TempDir::new("ecc");
    for (i, field) in ["-185966", "1.85966", " 185966", "18596+7"].iter().enumerate() {
        let line = patched(L2, 27, field);
        assert_rejected(
            &dir,
            &format!("e{i}.tle"),
            format!("{L1}\n{line}\n").as_bytes(),
            &[&format!("e{i}.tle:2:"), "columns 27-33 (eccentricity)"],
        );
    }
}

#[test]
fn tle_with_bad_catalogue_number_epoch_or_range_is_rejected() {
    let dir = TempDir::new("fields");
    let cases = [
        ("I0001 is not Alpha-5", patched(L1, 3, "I0001"), patched(L2, 3, "I0001"), "columns 3-7 (catalogue number)"),
        ("line numbers differ", L1.to_string(), patched(L2, 3, "00006"), "differs from line 1's 5"),
        ("day 367", patched(L1, 19, "00367.00000000"), L2.to_string(), "columns 19-32 (epoch)"),
        ("day 0", patched(L1, 19, "00000.50000000"), L2.to_string(), "columns 19-32 (epoch)"),
        ("inclination 190", L1.to_string(), patched(L2, 9, "190.0000"), "inclination"),
        ("mean motion 0", L1.to_string(), patched(L2, 53, " 0.00000000"), "mean motion"),
        ("B* garbage", patched(L1, 54, " 2x098-4"), L2.to_string(), "columns 54-61 (B*)"),
        ("classification X", patched(L1, 8, "X"), L2.to_string(), "classification"),
    ];
    for (i, (_why, l1, l2, expect)) in cases.iter().enumerate() {
        let file = format!("f{i}.tle");
        assert_rejected(&dir, &file, format!("{l1}\n{l2}\n").as_bytes(), &[expect, &format!("{file}:")]);
    }
}

#[test]
fn omm_json_with_a_missing_or_mistyped_field_is_rejected() {
    let dir = TempDir::new("json");
    // Keys are one a line from line 3 (OBJECT_NAME) on; MEAN_MOTION is the 4th key (line 6).
    let missing = omm_json(&[("MEAN_MOTION", None)]);
    assert_rejected(&dir, "a.json", missing.as_bytes(), &["a.json:2: MEAN_MOTION: missing"]);
    let text = omm_json(&[("ECCENTRICITY", Some("\"abc\""))]);
    assert_rejected(&dir, "b.json", text.as_bytes(), &["b.json:7: ECCENTRICITY: expected a finite number"]);
    let boolean = omm_json(&[("INCLINATION", Some("true"))]);
    assert_rejected(&dir, "c.json", boolean.as_bytes(), &["c.json:8: INCLINATION: expected a number, found a boolean"]);
    let range = omm_json(&[("ECCENTRICITY", Some("1.2"))]);
    assert_rejected(&dir, "d.json", range.as_bytes(), &["d.json:7: ECCENTRICITY: 1.2 is not in [0, 1)"]);
    let epoch = omm_json(&[("EPOCH", Some("\"2024-13-01T00:00:00\""))]);
    assert_rejected(&dir, "e.json", epoch.as_bytes(), &["e.json:5: EPOCH:"]);
    let id = omm_json(&[("NORAD_CAT_ID", Some("-5"))]);
    assert_rejected(&dir, "f.json", id.as_bytes(), &["f.json:14: NORAD_CAT_ID:"]);
    let name = omm_json(&[("OBJECT_NAME", Some("12"))]);
    assert_rejected(&dir, "g.json", name.as_bytes(), &["g.json:3: OBJECT_NAME: expected a string"]);
    let truncated = &omm_json(&[])[..200];
    assert_rejected(&dir, "h.json", truncated.as_bytes(), &["h.json:", "JSON: EOF while parsing"]);
    let theory = omm_json(&[("OBJECT_ID", Some("\"X\",\n    \"MEAN_ELEMENT_THEORY\": \"SGP4-XP\""))]);
    assert_rejected(&dir, "i.json", theory.as_bytes(), &["i.json:5: MEAN_ELEMENT_THEORY: \"SGP4-XP\" is not SGP4"]);
}

#[test]
fn omm_csv_with_a_missing_or_mistyped_field_is_rejected() {
    let dir = TempDir::new("csv");
    let without = |key: &str| {
        let keys: Vec<&str> = OMM_KEYS.split(',').collect();
        let values: Vec<&str> = OMM_ROW.split(',').collect();
        let keep: Vec<usize> = (0..keys.len()).filter(|&i| keys[i] != key).collect();
        let header: Vec<&str> = keep.iter().map(|&i| keys[i]).collect();
        let row: Vec<&str> = keep.iter().map(|&i| values[i]).collect();
        format!("{}\n{}\n", header.join(","), row.join(","))
    };
    assert_rejected(&dir, "a.csv", without("BSTAR").as_bytes(), &["a.csv:2: BSTAR: missing"]);
    let mistyped = format!("{OMM_KEYS}\n\n{}\n", OMM_ROW.replace(",15.5,", ",fifteen,"));
    assert_rejected(&dir, "b.csv", mistyped.as_bytes(), &["b.csv:3: MEAN_MOTION: expected a finite number"]);
    let short = format!("{OMM_KEYS}\n{}\n", &OMM_ROW[..OMM_ROW.rfind(',').unwrap()]);
    assert_rejected(&dir, "c.csv", short.as_bytes(), &["c.csv:2: record: 16 fields, the header has 17"]);
    let ecc = format!("{OMM_KEYS}\n{}\n", OMM_ROW.replace(",.0005,", ",-0.1,"));
    assert_rejected(&dir, "d.csv", ecc.as_bytes(), &["d.csv:2: ECCENTRICITY: -0.1 is not in [0, 1)"]);
}

#[test]
fn empty_or_non_utf8_catalogues_are_rejected() {
    let dir = TempDir::new("empty");
    assert_rejected(&dir, "a.tle", b"\n# nothing\n", &["a.tle:0: catalogue: no element set"]);
    assert_rejected(&dir, "b.tle", b"\xff\xfe1 00005U", &["b.tle: not UTF-8"]);
    assert_rejected(&dir, "c.tle", b"just a name\n", &["c.tle:1: name line: not followed by a line 1"]);
}

// ---------------------------------------------------------------------------------------------------
// generate catalogue
// ---------------------------------------------------------------------------------------------------

const CATALOGUE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/catalogue_leo.tle");
const RADARS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/sensors_radar.json");
const TELESCOPE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/sensors_telescope.json");
const START: &str = "2026-03-20T00:00:00Z";

fn generate(catalogue: &str, sensors: &str, start: &str, hours: &str, seed: &str, out: &Path) -> Output {
    host_sim(&[
        "generate".as_ref(),
        "catalogue".as_ref(),
        "--catalogue".as_ref(),
        catalogue.as_ref(),
        "--sensors".as_ref(),
        sensors.as_ref(),
        "--start".as_ref(),
        start.as_ref(),
        "--duration-hours".as_ref(),
        hours.as_ref(),
        "--seed".as_ref(),
        seed.as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ])
}

#[test]
fn generate_catalogue_truth_is_sgp4_and_deterministic() {
    use host_sim::io::catalogue::{Satellite, load, parse_omm_epoch};
    use host_sim::scenario::v2::Scenario3d;
    let dir = TempDir::new("gen-radar");
    let (a, b, c) = (dir.join("a.json"), dir.join("b.json"), dir.join("c.json"));
    for (out, seed) in [(&a, "1"), (&b, "1"), (&c, "2")] {
        let output = generate(CATALOGUE, RADARS, START, "2", seed, out);
        assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    }
    let bytes = |p: &Path| std::fs::read(p).expect("scenario");
    assert_eq!(bytes(&a), bytes(&b), "same seed, different files");
    assert_ne!(bytes(&a), bytes(&c), "another seed, the same file");
    let scenario = Scenario3d::load(&a).expect("the generated file loads");
    assert!(scenario.description.contains("SGP4"), "{}", scenario.description);
    // A catalogue's trackers: the floor under the weights, and tracks lost after 8 unseen scans in view
    // (the radars' preset sets no track loss of its own).
    use host_sim::scenario::from_simulation::{CATALOGUE_SELECTION, CATALOGUE_TRACK_LOSS};
    assert_eq!(scenario.tracker.selection, CATALOGUE_SELECTION);
    assert_eq!(scenario.tracker.lost_after_unseen_scans, CATALOGUE_TRACK_LOSS);
    assert_eq!(CATALOGUE_TRACK_LOSS.map(|n| n.get()), Some(8));
    // 2 h, a scan every 10 s (two radars every 20 s, in turn).
    assert_eq!(scenario.scans.len(), 721);
    let measurements: usize = scenario.scans.iter().map(|s| s.measurements.len()).sum();
    let truth = scenario.truth.as_ref().expect("truth");
    let detections: usize =
        truth.scans.iter().map(|s| s.origins.as_ref().map_or(0, |o| o.iter().flatten().count())).sum();
    assert!(detections > 20, "{detections} detections of {measurements} measurements");
    // Every truth state is SGP4's TEME state at the scan time.
    let satellites: Vec<Satellite> =
        load(Path::new(CATALOGUE)).expect("catalogue").into_iter().map(|e| Satellite::new(e).expect("sgp4")).collect();
    assert_eq!(truth.objects.len(), satellites.len());
    let epoch = parse_omm_epoch("2026-03-20T00:00:00").expect("epoch");
    for (k, scan) in truth.scans.iter().enumerate().step_by(97) {
        for object in &scan.objects {
            let (r, v) = satellites[object.id as usize].tracker_state(epoch, scenario.scans[k].time).expect("state");
            assert_eq!(object.state, [r[0], r[1], r[2], v[0], v[1], v[2]], "scan {k} object {}", object.id);
        }
    }
}

#[test]
fn generate_catalogue_telescope_sees_sunlit_objects_from_a_dark_site() {
    use host_sim::scenario::from_catalogue::{sun_elevation, sun_position, sunlit};
    use host_sim::scenario::v2::Scenario3d;
    use host_sim::sim::site::Site;
    use host_sim::sim::time::earth_rotation_angle;
    let dir = TempDir::new("gen-tel");
    let out = dir.join("t.json");
    let output = generate(CATALOGUE, TELESCOPE, START, "24", "3", &out);
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    // No track loss for a telescope alone: it misses the objects in the Earth's shadow.
    let scenario = Scenario3d::load(&out).expect("the generated file loads");
    assert_eq!(scenario.tracker.lost_after_unseen_scans, None);
    let jd0 = scenario.epoch_jd();
    let s = &scenario.sensors[0].site;
    let site =
        Site { latitude: s.latitude_deg.to_radians(), longitude: s.longitude_deg.to_radians(), height: s.height_km };
    // A 24 h run at the equinox: scans only in the dark part of the night (Sun below −12°).
    assert!(scenario.scans.len() > 500 && scenario.scans.len() < 1800, "{} scans", scenario.scans.len());
    let truth = scenario.truth.as_ref().expect("truth");
    let mut detections = 0;
    for (scan, t) in scenario.scans.iter().zip(&truth.scans) {
        let sun = sun_position(jd0 + scan.time / 86_400.0);
        let elevation = sun_elevation(&site, earth_rotation_angle(jd0, scan.time), sun).to_degrees();
        assert!(elevation < -12.0, "scan at {} s with the Sun at {elevation}°", scan.time);
        for id in t.origins.as_ref().expect("origins").iter().flatten() {
            let state = t.objects.iter().find(|o| o.id == *id).expect("object").state;
            assert!(sunlit([state[0], state[1], state[2]], sun), "object {id} detected in the shadow");
            detections += 1;
        }
    }
    assert!(detections > 0, "no detection");
    // Some truth objects are in the shadow at some scans: the filter had something to remove.
    let shadowed = scenario.scans.iter().zip(&truth.scans).any(|(scan, t)| {
        let sun = sun_position(jd0 + scan.time / 86_400.0);
        t.objects.iter().any(|o| !sunlit([o.state[0], o.state[1], o.state[2]], sun))
    });
    assert!(shadowed);
}

/// A sensors file of mixed kinds: the radars' file and the telescope's in one network (issue 28), the
/// telescope with its own birth region; `kinds: false` leaves the kinds out.
fn network_sensors(dir: &TempDir, kinds: bool) -> PathBuf {
    let read = |p: &str| serde_json::from_str::<Value>(&std::fs::read_to_string(p).expect("sensors")).expect("json");
    let (mut radars, telescope) = (read(RADARS), read(TELESCOPE));
    let mut sensors = radars["sensors"].as_array().expect("sensors").clone();
    for sensor in &mut sensors {
        if kinds {
            sensor["kind"] = serde_json::json!("radar");
        }
    }
    let mut optical = telescope["sensors"][0].clone();
    optical["kind"] = serde_json::json!("optical");
    optical["birth_region"] = serde_json::json!({"region": "geo", "headings": 3});
    sensors.push(optical);
    radars["measurement"] = serde_json::json!({"type": "network"});
    radars["sensors"] = Value::Array(sensors);
    let path = dir.join(if kinds { "network.json" } else { "network-no-kinds.json" });
    std::fs::write(&path, radars.to_string()).expect("write");
    path
}

#[test]
fn generate_catalogue_takes_a_network_of_mixed_kinds() {
    use host_sim::scenario::v2::{Measurement3dSpec, Scenario3d};
    let dir = TempDir::new("gen-network");
    let (sensors, out) = (network_sensors(&dir, true), dir.join("n.json"));
    let output = generate(CATALOGUE, sensors.to_str().unwrap(), START, "4", "3", &out);
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let scenario = Scenario3d::load(&out).expect("the generated file loads");
    assert_eq!(scenario.measurement, Measurement3dSpec::Network);
    // The network's own track loss (5 scans) stands; the catalogue's (8) fills in only where none is set.
    assert_eq!(scenario.tracker.lost_after_unseen_scans.map(|n| n.get()), Some(5));
    let kinds: Vec<Measurement3dSpec> = (0..3).map(|i| scenario.kind(i)).collect();
    assert_eq!(kinds, [Measurement3dSpec::Radar, Measurement3dSpec::Radar, Measurement3dSpec::Optical]);
    // The file's birth region is the scenario's, not the default.
    let region = scenario.sensors[2].birth_region.expect("birth region");
    assert_eq!(region.headings, Some(3));
    // Each scan carries its sensor's kind: 3 components for the radars, 2 for the telescope, whose frames
    // come only from a dark site (fewer than the radars').
    let mut per_sensor = [0_usize; 3];
    for scan in &scenario.scans {
        per_sensor[scan.sensor] += 1;
        let dimension = if scan.sensor == 2 { 2 } else { 3 };
        assert!(scan.measurements.iter().all(|z| z.len() == dimension), "scan at {} s", scan.time);
    }
    assert!(per_sensor[2] > 0 && per_sensor[2] < per_sensor[0], "{per_sensor:?}");
    // Without the kinds: one line naming the field, exit 2, nothing written.
    let bad = dir.join("bad.json");
    let output = generate(CATALOGUE, network_sensors(&dir, false).to_str().unwrap(), START, "1", "3", &bad);
    let err = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(err.lines().count() == 1 && err.contains("sensors[0].kind"), "{err}");
    assert!(!bad.exists());
}

#[test]
fn generate_catalogue_rejects_bad_input_with_one_line_and_no_file() {
    let dir = TempDir::new("gen-bad");
    let bad_tle = dir.join("bad.tle");
    std::fs::write(&bad_tle, format!("{}4\n{L2}\n", &L1[..68])).expect("write");
    let sensors_text = std::fs::read_to_string(RADARS).expect("sensors");
    let wrong_format = dir.join("format.json");
    std::fs::write(&wrong_format, sensors_text.replace("rfisst-sensors/1", "rfisst-sensors/9")).expect("write");
    let no_interval = dir.join("interval.json");
    std::fs::write(&no_interval, sensors_text.replace("\"scan_interval_s\": 20.0,", "")).expect("write");
    let bad_pd = dir.join("pd.json");
    std::fs::write(
        &bad_pd,
        sensors_text.replacen("\"detection_probability\": 0.9", "\"detection_probability\": 1.5", 1),
    )
    .expect("write");
    let bad_tle = bad_tle.to_string_lossy().into_owned();
    let cases: Vec<(&str, &str, &str, &str, &str)> = vec![
        (&bad_tle, RADARS, START, "1", "line 1 column 69 (checksum)"),
        (CATALOGUE, wrong_format.to_str().unwrap(), START, "1", "format: expected \"rfisst-sensors/1\""),
        (CATALOGUE, no_interval.to_str().unwrap(), START, "1", "scan_interval_s"),
        (CATALOGUE, bad_pd.to_str().unwrap(), START, "1", "sensors[0].detection_probability"),
        (CATALOGUE, RADARS, "2026-02-30T00:00:00Z", "1", "--start"),
        (CATALOGUE, RADARS, START, "0", "--duration-hours 0"),
        (CATALOGUE, RADARS, START, "NaN", "--duration-hours NaN"),
    ];
    for (catalogue, sensors, start, hours, expect) in cases {
        let out = dir.join("out.json");
        let output = generate(catalogue, sensors, start, hours, "1", &out);
        let err = String::from_utf8_lossy(&output.stderr).into_owned();
        assert_eq!(output.status.code(), Some(2), "{expect}: {}", describe(&output));
        assert!(err.starts_with("error: ") && err.lines().count() == 1 && err.contains(expect), "{expect}: {err:?}");
        assert!(!out.exists(), "{expect}: output written");
        assert!(
            std::fs::read_dir(&dir.0).expect("dir").all(|e| !e
                .expect("entry")
                .file_name()
                .to_string_lossy()
                .ends_with(".partial"))
        );
    }
    let output = host_sim(&["generate", "catalogue", "--out", dir.join("x.json").to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(String::from_utf8_lossy(&output.stderr).contains("--catalogue is required"));
}

#[test]
fn run_catalogue_tracks_a_catalogue_in_one_command() {
    let dir = TempDir::new("run-catalogue");
    let out = dir.join("out");
    let run_with = |out: &Path, hours: &str, extra: &[&str]| {
        Command::new(BIN)
            .args(["run-catalogue", "--catalogue", CATALOGUE, "--sensors", RADARS, "--start", START])
            .args(["--duration-hours", hours, "--quiet"])
            .args(extra)
            .arg("--out")
            .arg(out)
            .output()
            .expect("run host-sim")
    };
    let run = |out: &Path, hours: &str| run_with(out, hours, &[]);
    let output = run(&out, "0.25");
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    for file in ["scenario.json", "summary.json", "estimates.csv", "tracks.oem"] {
        assert!(out.join(file).is_file(), "{file} missing");
    }
    // The tracks follow the catalogue: every object is held at the end.
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).expect("summary")).expect("json");
    let cardinality = summary["final_expected_cardinality"].as_f64().expect("cardinality");
    let objects = summary["objects"].as_u64().or(summary["truth_objects"].as_u64());
    assert!((cardinality - 24.0).abs() < 0.5, "{cardinality} ({objects:?})");
    // A bad argument: one line, exit 2, nothing written.
    let bad = dir.join("bad");
    let output = run(&bad, "0");
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(!bad.exists());
    // Track loss: the catalogue's 8 scans by default, as asked with --lost-after, 0 refused.
    let lost_after = |out: &Path| read_json(&out.join("scenario.json"))["tracker"]["lost_after_unseen_scans"].clone();
    assert_eq!(lost_after(&out), 8);
    for (value, expect) in [("none", Value::Null), ("3", Value::from(3))] {
        let out = dir.join(&format!("lost-{value}"));
        let output = run_with(&out, "0.05", &["--lost-after", value]);
        assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
        assert_eq!(lost_after(&out), expect, "--lost-after {value}");
    }
    let output = run_with(&bad, "0.05", &["--lost-after", "0"]);
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(!bad.exists());
}

/// The fixture's first three objects, then an orbit inside the Earth (17 rev/day), one far inside (99
/// rev/day) and the first object again; the second object's elements are 60 days older than the start.
fn catalogue_with_bad_orbits(dir: &TempDir) -> PathBuf {
    let fixture = std::fs::read_to_string(CATALOGUE).expect("catalogue");
    let lines: Vec<&str> = fixture.lines().filter(|l| !l.starts_with('#')).take(9).collect();
    let old = patched(lines[4], 19, "26019.00000000");
    let mut text = format!("{}\n{old}\n{}\n", lines[..4].join("\n"), lines[5..9].join("\n"));
    for (name, id, mean_motion) in [("LOW 17", "90077", "17.00000000"), ("LOW 99", "90078", "99.00000000")] {
        let (l1, l2) = (with_checksum(&lines[1].replace("90001", id)), lines[2].replace("90001", id));
        text.push_str(&format!("{name}\n{l1}\n{}\n", patched(&l2, 53, mean_motion)));
    }
    text.push_str(&format!("{}\n", lines[..3].join("\n")));
    let path = dir.join("bad-orbits.tle");
    std::fs::write(&path, text).expect("write");
    path
}

#[test]
fn orbits_inside_the_earth_and_repeated_element_sets_are_dropped_and_counted() {
    // Issue 33 item 4: mean motions of 17 and 99 rev/day were accepted (truth radius down to 1,947 km) and
    // an element set given twice was two objects.
    let dir = TempDir::new("gen-dropped");
    let catalogue = catalogue_with_bad_orbits(&dir);
    let out = dir.join("scenario.json");
    let output = Command::new(BIN)
        .args(["--json", "generate", "catalogue", "--sensors", RADARS, "--start", START, "--duration-hours", "0.25"])
        .arg("--catalogue")
        .arg(&catalogue)
        .arg("--out")
        .arg(&out)
        .output()
        .expect("run host-sim");
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let err = String::from_utf8_lossy(&output.stderr);
    let warnings: Vec<&str> = err.lines().filter(|l| l.starts_with("warning: ")).collect();
    assert_eq!(warnings.len(), 4, "{err}");
    assert!(
        warnings[0].contains(":4: object 90002 (OBJECT 1): elements 60") && warnings[0].contains("30 days"),
        "{err}"
    );
    for (w, what) in warnings[1..].iter().zip([
        "object 90077 (LOW 17): dropped: the orbit enters the Earth",
        "object 90078 (LOW 99): dropped: the orbit enters the Earth",
        ":16: object 90001 (OBJECT 0): dropped: the element set of line 1 again",
    ]) {
        assert!(w.contains(what), "{what}: {err}");
    }
    assert!(err.contains("3 objects") && err.contains("3 element sets dropped"), "{err}");
    let report: Value = serde_json::from_slice(&output.stdout).expect("JSON on stdout");
    assert_eq!(report["catalogue_dropped"]["count"], 3, "{report}");
    assert_eq!(report["catalogue_dropped"]["extrapolated"], 1, "the 60-day-old elements are counted");
    let dropped = report["catalogue_dropped"]["objects"].as_array().expect("objects");
    assert_eq!(dropped.iter().map(|o| o["line"].as_u64().unwrap()).collect::<Vec<_>>(), [10, 13, 16]);
    assert_eq!(dropped[0]["name"], "LOW 17");
    assert_eq!(report["objects"], 3);
    let scenario = read_json(&out);
    assert_eq!(scenario["truth"]["objects"].as_array().expect("truth").len(), 3);
    // run-catalogue: the same list in summary.json.
    let run_out = dir.join("run");
    let output = Command::new(BIN)
        .args(["run-catalogue", "--sensors", RADARS, "--start", START, "--duration-hours", "0.1", "--quiet"])
        .arg("--catalogue")
        .arg(&catalogue)
        .arg("--out")
        .arg(&run_out)
        .output()
        .expect("run host-sim");
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let summary = read_json(&run_out.join("summary.json"));
    assert_eq!(summary["catalogue_dropped"]["count"], 3, "{summary}");
    assert_eq!(
        summary["catalogue_dropped"]["objects"][2]["reason"],
        "the element set of line 1 again (same catalogue number and epoch)"
    );
}

#[test]
fn a_sensors_file_follows_the_sensor_name_rule() {
    // Issue 33 item 7: names that export-tdm refused were accepted by generate catalogue.
    let dir = TempDir::new("gen-names");
    let text = std::fs::read_to_string(RADARS).expect("sensors");
    assert!(text.contains("\"radar-south\""));
    for (name, replacement, expect) in [
        ("twice.json", "\"radar-north\"", "sensors[1].name: \"radar-north\" names two sensors (sensors[0] too)"),
        ("newline.json", "\"radar\\nsouth\"", "sensors[1].name: \"radar\\nsouth\" cannot name a sensor"),
        ("empty.json", "\"\"", "sensors[1].name: \"\" cannot name a sensor"),
    ] {
        let sensors = dir.join(name);
        std::fs::write(&sensors, text.replacen("\"radar-south\"", replacement, 1)).expect("write");
        let out = dir.join("out.json");
        let output = generate(CATALOGUE, sensors.to_str().expect("path"), START, "0.1", "1", &out);
        let err = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{name}: {}", describe(&output));
        assert!(err.lines().count() == 1 && err.contains(expect), "{name}: {err}");
        assert!(!out.exists());
    }
}
