//! CCSDS files at the command line (issue 15): `export-tdm` then `track` gives bit-identical estimates to
//! `run`, `tracks.oem` parses back to the rows of `estimates.csv`, and every bad TDM is one line naming
//! the file, line and keyword, exit code 2, with no output folder left behind.

use host_sim::io::ccsds::Instant;
use serde_json::Value;
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::{TempDir, host_sim, ok, p, read};

fn generate(dir: &TempDir, preset: &str) -> Value {
    let file = dir.join("generated.json");
    ok(host_sim(&["generate", preset, "--seed", "1", "--out", p(&file)]));
    serde_json::from_str(&read(&file)).expect("scenario JSON")
}

fn save(value: &Value, path: &Path) {
    std::fs::write(path, serde_json::to_string(value).expect("json")).expect("write scenario");
}

/// tiny-3d with a second radar (a copy of the first, another name) taking every other scan, and one empty
/// scan; without truth (the truth's per-measurement origins no longer hold).
fn two_radars(dir: &TempDir) -> Value {
    let mut s = generate(dir, "tiny-3d");
    let mut second = s["sensors"][0].clone();
    second["name"] = "radar-copy".into();
    s["sensors"].as_array_mut().expect("sensors").push(second);
    for (k, scan) in s["scans"].as_array_mut().expect("scans").iter_mut().enumerate() {
        scan["sensor"] = (k % 2).into();
        if k == 3 {
            scan["measurements"] = Value::Array(vec![]);
        }
    }
    s.as_object_mut().expect("object").remove("truth");
    s
}

/// export-tdm, then track with the same file as the configuration; returns (run dir, track dir).
fn run_and_track(dir: &TempDir, scenario: &Path, tracker: &str) -> (PathBuf, PathBuf) {
    let (run, tdm, track) = (dir.join("run"), dir.join("tdm"), dir.join("track"));
    ok(host_sim(&["run", p(scenario), "--tracker", tracker, "--out", p(&run), "--quiet"]));
    ok(host_sim(&["export-tdm", p(scenario), "--out", p(&tdm)]));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&tdm).expect("tdm dir").map(|e| e.expect("entry").path()).collect();
    files.sort();
    let mut args: Vec<String> = vec!["track".into(), "--tdm".into()];
    args.extend(files.iter().map(|f| p(f).to_string()));
    args.extend(["--config", p(scenario), "--tracker", tracker, "--out", p(&track), "--quiet"].map(String::from));
    ok(host_sim(&args));
    (run, track)
}

#[test]
fn tracking_the_tdm_export_of_two_radars_gives_the_run_estimates_bit_for_bit() {
    let dir = TempDir::new("radar");
    let scenario = dir.join("two.json");
    save(&two_radars(&dir), &scenario);
    let (run, track) = run_and_track(&dir, &scenario, "homht");
    let tdms = std::fs::read_dir(dir.join("tdm")).expect("tdm dir").count();
    assert_eq!(tdms, 2, "one TDM per sensor");
    assert!(read(&dir.join("tdm/1-radar-copy.tdm")).contains("COMMENT EMPTY_SCAN "), "the empty scan is written");
    let expected = read(&run.join("estimates.csv"));
    assert!(expected.lines().count() > 10, "estimates written");
    assert_eq!(read(&track.join("estimates.csv")), expected);
    assert!(track.join("tracks.oem").exists() && track.join("summary.json").exists());
}

#[test]
fn tracking_the_tdm_export_of_tiny_3d_gives_its_estimates_without_the_truth_column() {
    let dir = TempDir::new("tiny");
    let scenario = dir.join("tiny.json");
    save(&generate(&dir, "tiny-3d"), &scenario);
    let (run, track) = run_and_track(&dir, &scenario, "homht");
    // The truth column (within_error_bound) is empty when tracking TDMs; everything else is identical.
    let strip = |text: String| -> Vec<String> {
        text.lines().map(|l| l.rsplit_once(',').map_or(l, |(head, _)| head).to_string()).collect()
    };
    let expected = strip(read(&run.join("estimates.csv")));
    assert!(expected.len() > 10);
    assert_eq!(strip(read(&track.join("estimates.csv"))), expected);
}

/// optical-geo cut to four scans of three measurements each (a short debug-build run), without truth.
fn short_optical_geo(dir: &TempDir) -> Value {
    let mut s = generate(dir, "optical-geo");
    let scans: Vec<Value> = s["scans"].as_array().expect("scans")[..4]
        .iter()
        .map(|scan| {
            let mut scan = scan.clone();
            scan["measurements"] = Value::Array(scan["measurements"].as_array().expect("measurements")[..3].to_vec());
            scan
        })
        .collect();
    s["scans"] = Value::Array(scans);
    s.as_object_mut().expect("object").remove("truth");
    s
}

#[test]
fn tracking_the_tdm_export_of_an_optical_scenario_gives_the_run_estimates_bit_for_bit() {
    let dir = TempDir::new("optical");
    let s = short_optical_geo(&dir);
    let scenario = dir.join("geo.json");
    save(&s, &scenario);
    let (run, track) = run_and_track(&dir, &scenario, "rfisst");
    assert!(read(&dir.join("tdm/0-telescope.tdm")).contains("ANGLE_TYPE = RADEC"));
    let expected = read(&run.join("estimates.csv"));
    assert!(expected.lines().count() > 4);
    assert_eq!(read(&track.join("estimates.csv")), expected);
}

/// `360 + value` for a decimal `value` without an exponent, computed exactly in decimal.
fn plus_a_turn(value: &str) -> String {
    let (sign, magnitude) = value.strip_prefix('-').map_or((1, value), |m| (-1, m));
    let (whole, fraction) = magnitude.split_once('.').unwrap_or((magnitude, ""));
    let digits: i128 = format!("{whole}{fraction}").parse().expect("decimal digits");
    let sum = (360 * 10i128.pow(fraction.len() as u32) + sign * digits).to_string();
    let sum = format!("{sum:0>width$}", width = fraction.len() + 1);
    let (head, tail) = sum.split_at(sum.len() - fraction.len());
    if tail.is_empty() { head.to_string() } else { format!("{head}.{tail}") }
}

/// Every TDM under `from` copied to `to` with its negative `ANGLE_1` (azimuth or right ascension) written
/// in [0°, 360°) instead, and with `every` the others too a turn higher; returns the copies and how many
/// values moved.
fn shifted_copies(from: &Path, to: &Path, every: bool) -> (Vec<PathBuf>, usize) {
    std::fs::create_dir_all(to).expect("shifted dir");
    let mut files: Vec<PathBuf> = std::fs::read_dir(from).expect("tdm dir").map(|e| e.expect("entry").path()).collect();
    files.sort();
    let mut moved = 0;
    let copies = files
        .iter()
        .map(|file| {
            let text: Vec<String> = read(file)
                .lines()
                .map(|line| match line.strip_prefix("ANGLE_1 = ").and_then(|rest| rest.split_once(' ')) {
                    Some((time, value)) if every || value.starts_with('-') => {
                        moved += 1;
                        format!("ANGLE_1 = {time} {}", plus_a_turn(value))
                    }
                    _ => line.to_string(),
                })
                .collect();
            let copy = to.join(file.file_name().expect("file name"));
            std::fs::write(&copy, text.join("\n") + "\n").expect("write shifted TDM");
            copy
        })
        .collect();
    (copies, moved)
}

/// `track` of `files` with `config`, into `out`.
fn track(files: &[PathBuf], config: &Path, tracker: &str, out: &Path) -> Output {
    let mut args: Vec<String> = vec!["track".into(), "--tdm".into()];
    args.extend(files.iter().map(|f| p(f).to_string()));
    args.extend(["--config", p(config), "--tracker", tracker, "--out", p(out), "--quiet"].map(String::from));
    host_sim(&args)
}

#[test]
fn azimuth_and_right_ascension_in_0_360_track_bit_for_bit_as_in_180_180() {
    assert_eq!(plus_a_turn("-9.125"), "350.875");
    assert_eq!(plus_a_turn("-0.0005"), "359.9995");
    assert_eq!(plus_a_turn("-180"), "180");
    assert_eq!(plus_a_turn("12.5"), "372.5");
    // Issue 29: 6 of the 11 scans of tiny-3d (seed 1) were refused as outside the field of view. Its
    // azimuths are written in [0, 360); the telescope's right ascensions (all in [0, 180] at this epoch)
    // a turn higher, in [360, 540].
    for (preset, tracker) in [("tiny-3d", "homht"), ("optical-geo", "rfisst")] {
        let dir = TempDir::new("angles");
        let s = if preset == "optical-geo" { short_optical_geo(&dir) } else { generate(&dir, preset) };
        let scenario = dir.join("scenario.json");
        save(&s, &scenario);
        let tdm = dir.join("tdm");
        ok(host_sim(&["export-tdm", p(&scenario), "--out", p(&tdm)]));
        let mut plain: Vec<PathBuf> =
            std::fs::read_dir(&tdm).expect("tdm dir").map(|e| e.expect("entry").path()).collect();
        plain.sort();
        let (shifted, moved) = shifted_copies(&tdm, &dir.join("shifted"), preset == "optical-geo");
        assert!(moved > 0, "{preset}: no angle shifted");
        let (plain_out, shifted_out) = (dir.join("plain-out"), dir.join("shifted-out"));
        ok(track(&plain, &scenario, tracker, &plain_out));
        let output = track(&shifted, &scenario, tracker, &shifted_out);
        ok(output);
        let expected = read(&plain_out.join("estimates.csv"));
        assert!(expected.lines().count() > 4, "{preset}: estimates written");
        assert_eq!(read(&shifted_out.join("estimates.csv")), expected, "{preset}");
        let summary: Value = serde_json::from_str(&read(&shifted_out.join("summary.json"))).expect("summary");
        assert_eq!(summary["refused_scans"]["count"], 0, "{preset}: {summary}");
    }
}

/// The segments of an OEM: label → [(time, state, covariance lower triangle)].
type Segments = HashMap<u32, Vec<(Instant, [f64; 6], Vec<f64>)>>;

/// A minimal OEM reader: what `tracks.oem` holds.
fn read_oem(text: &str) -> Segments {
    let mut segments: Segments = HashMap::new();
    let mut label = None;
    let mut in_covariance = false;
    let mut cov_epoch: Option<Instant> = None;
    let mut cov_index = 0;
    let mut cov_point = 0;
    for line in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        let (key, value) = line.split_once('=').map_or((line, ""), |(k, v)| (k.trim(), v.trim()));
        match key {
            "CCSDS_OEM_VERS" => assert_eq!(value, "2.0"),
            "META_START" => in_covariance = false,
            "OBJECT_ID" => label = Some(value.parse::<u32>().expect("label")),
            "REF_FRAME" | "COV_REF_FRAME" => assert_eq!(value, "TEME"),
            "CENTER_NAME" => assert_eq!(value, "EARTH"),
            "TIME_SYSTEM" => assert_eq!(value, "UTC"),
            "COVARIANCE_START" => {
                in_covariance = true;
                cov_point = 0;
            }
            "COVARIANCE_STOP" => {
                in_covariance = false;
                cov_epoch = None;
            }
            "EPOCH" => {
                if cov_epoch.is_some() {
                    cov_point += 1;
                }
                cov_epoch = Some(Instant::parse(value).expect("covariance epoch"));
                cov_index = 0;
            }
            _ if line.starts_with("COMMENT")
                || ["CREATION_DATE", "ORIGINATOR", "OBJECT_NAME", "START_TIME", "STOP_TIME", "META_STOP"]
                    .contains(&key) => {}
            _ if in_covariance => {
                let values: Vec<f64> = line.split_whitespace().map(|v| v.parse().expect("covariance")).collect();
                let points = segments.get_mut(&label.expect("segment")).expect("ephemeris before covariance");
                let epoch = cov_epoch.as_ref().expect("EPOCH");
                let point = &mut points[cov_point];
                assert_eq!(&point.0, epoch, "covariances follow the ephemeris epochs");
                assert_eq!(values.len(), cov_index + 1, "lower triangle");
                point.2.extend(values);
                cov_index += 1;
            }
            _ => {
                let mut parts = line.split_whitespace();
                let time = Instant::parse(parts.next().expect("epoch")).expect("ephemeris epoch");
                let state: Vec<f64> = parts.map(|v| v.parse().expect("state")).collect();
                let state: [f64; 6] = state.try_into().expect("six components");
                segments.entry(label.expect("segment")).or_default().push((time, state, vec![]));
            }
        }
    }
    segments
}

#[test]
fn tracks_oem_parses_back_to_the_estimates() {
    let dir = TempDir::new("oem");
    let scenario_path = dir.join("tiny.json");
    let scenario = generate(&dir, "tiny-3d");
    save(&scenario, &scenario_path);
    let out = dir.join("run");
    ok(host_sim(&["run", p(&scenario_path), "--out", p(&out), "--quiet"]));
    let epoch = Instant::parse(scenario["epoch"]["utc"].as_str().expect("utc epoch")).expect("epoch");
    let segments = read_oem(&read(&out.join("tracks.oem")));
    // estimates.csv: scan,time,sensor,label,x,y,z,vx,vy,vz,existence,within_error_bound
    let rows: Vec<Vec<String>> =
        read(&out.join("estimates.csv")).lines().skip(1).map(|l| l.split(',').map(String::from).collect()).collect();
    let last_scan = rows.iter().map(|r| r[0].clone()).next_back().expect("rows");
    let mut confirmed: Vec<u32> = rows
        .iter()
        .filter(|r| r[0] == last_scan && r[10].parse::<f64>().expect("existence") >= 0.9)
        .map(|r| r[3].parse().expect("label"))
        .collect();
    confirmed.sort_unstable();
    let mut labels: Vec<u32> = segments.keys().copied().collect();
    labels.sort_unstable();
    assert!(!labels.is_empty(), "tiny-3d confirms tracks");
    assert_eq!(labels, confirmed, "one segment per confirmed track");
    for label in labels {
        let points = &segments[&label];
        // The label's rows, thinned as the OEM is: the first, each one OEM_STEP_S after the last kept, the last.
        let all: Vec<&Vec<String>> = rows.iter().filter(|r| r[3] == label.to_string()).collect();
        let time = |r: &Vec<String>| r[1].parse::<f64>().expect("time");
        let mut expected: Vec<&Vec<String>> = vec![];
        for (i, row) in all.iter().enumerate() {
            let spaced = expected.last().is_none_or(|kept| time(row) - time(kept) >= host_sim::io::oem::OEM_STEP_S);
            if spaced || i + 1 == all.len() {
                expected.push(row);
            }
        }
        assert!(expected.len() < all.len(), "label {label}: tiny-3d's 10 s scans are thinned");
        assert_eq!(points.len(), expected.len(), "label {label}: the thinned scans in the MAP");
        for ((time, state, covariance), row) in points.iter().zip(expected) {
            let t: f64 = row[1].parse().expect("time");
            assert_eq!(time.since(&epoch).map(f64::to_bits), Some(t.to_bits()), "label {label} time");
            for (i, value) in state.iter().enumerate() {
                assert_eq!(value.to_bits(), row[4 + i].parse::<f64>().expect("state").to_bits());
            }
            assert_eq!(covariance.len(), 21, "a covariance per epoch");
            assert!(covariance[0] > 0.0 && covariance[20] > 0.0, "positive variances");
        }
    }
}

/// A small valid radar TDM for tiny-3d's sensor, with `edit` applied; tracked, it must fail with exit code
/// 2, one line naming the file, `line` and `keyword`, and no output folder.
fn assert_bad_tdm(edit: impl Fn(String) -> String, line: usize, keyword: &str) {
    let dir = TempDir::new("bad");
    let config = dir.join("tiny.json");
    save(&generate(&dir, "tiny-3d"), &config);
    ok(host_sim(&["export-tdm", p(&config), "--out", p(&dir.join("tdm"))]));
    let tdm = dir.join("tdm/0-radar-north.tdm");
    std::fs::write(&tdm, edit(read(&tdm))).expect("write TDM");
    let out = dir.join("out");
    let output = host_sim(&["track", "--tdm", p(&tdm), "--config", p(&config), "--out", p(&out), "--quiet"]);
    let stderr = String::from_utf8_lossy(&output.stderr).into_owned();
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    let place = format!("{}:{line}: {keyword}: ", tdm.display());
    assert!(stderr.contains(&place), "expected {place:?} in {stderr:?}");
    assert!(!out.exists(), "nothing written");
    let leftovers: Vec<_> = std::fs::read_dir(&dir.0).expect("dir").map(|e| e.expect("entry").file_name()).collect();
    assert!(!leftovers.iter().any(|n| n.to_string_lossy().contains("partial")), "{leftovers:?}");
}

/// The line number (1-based) of the first line of `text` that starts with `prefix`.
fn line_of(prefix: &str) -> impl Fn(&str) -> usize {
    let prefix = prefix.to_string();
    move |text: &str| text.lines().position(|l| l.starts_with(&prefix)).expect("line") + 1
}

/// The exported TDM's text, to find line numbers.
fn sample_tdm() -> String {
    let dir = TempDir::new("sample");
    let config = dir.join("tiny.json");
    save(&generate(&dir, "tiny-3d"), &config);
    ok(host_sim(&["export-tdm", p(&config), "--out", p(&dir.join("tdm"))]));
    read(&dir.join("tdm/0-radar-north.tdm"))
}

#[test]
fn tdm_with_an_unknown_keyword_is_refused() {
    let line = line_of("MODE")(&sample_tdm());
    assert_bad_tdm(|t| t.replace("MODE = SEQUENTIAL", "FLAVOUR = SEQUENTIAL"), line, "FLAVOUR");
    let data = line_of("RANGE =")(&sample_tdm());
    assert_bad_tdm(|t| t.replacen("RANGE =", "RANGE_X =", 1), data, "RANGE_X");
}

#[test]
fn tdm_without_a_meta_block_is_refused() {
    let text = sample_tdm();
    let start = line_of("META_START")(&text);
    let stop = line_of("META_STOP")(&text);
    // The data block follows the header directly: DATA_START is then line start + 2 (the META block and
    // the blank line after it are removed).
    let removed = stop - start + 2;
    let data = line_of("DATA_START")(&text) - removed;
    assert_bad_tdm(
        |t| {
            let lines: Vec<&str> = t.lines().collect();
            let kept: Vec<&str> = lines[..start - 1].iter().chain(&lines[stop + 1..]).copied().collect();
            kept.join("\n") + "\n"
        },
        data,
        "DATA_START",
    );
}

#[test]
fn tdm_with_times_out_of_order_is_refused() {
    // The first scan's lines moved after the second scan's: its RANGE is then out of order.
    let text = sample_tdm();
    let first = line_of("RANGE =")(&text);
    let lines: Vec<&str> = text.lines().collect();
    let t0 = lines[first - 1].split_whitespace().nth(2).expect("time").to_string();
    let scan0: Vec<usize> = (0..lines.len()).filter(|&i| lines[i].contains(&format!("= {t0} "))).collect();
    let t1 = lines[scan0[scan0.len() - 1] + 1].split_whitespace().nth(2).expect("time").to_string();
    let scan1: Vec<usize> = (0..lines.len()).filter(|&i| lines[i].contains(&format!("= {t1} "))).collect();
    let moved_to = first + scan1.len(); // the first moved line, 1-based
    assert_bad_tdm(
        move |t| {
            let lines: Vec<&str> = t.lines().collect();
            let mut out: Vec<&str> = lines[..scan0[0]].to_vec();
            out.extend(scan1.iter().map(|&i| lines[i]));
            out.extend(scan0.iter().map(|&i| lines[i]));
            out.extend(&lines[scan1[scan1.len() - 1] + 1..]);
            out.join("\n") + "\n"
        },
        moved_to,
        "RANGE",
    );
}

#[test]
fn tdm_with_a_time_before_the_epoch_is_refused() {
    let text = sample_tdm();
    let first = line_of("RANGE =")(&text);
    let lines: Vec<&str> = text.lines().collect();
    let t0 = lines[first - 1].split_whitespace().nth(2).expect("time").to_string();
    let earlier = format!("1999{}", &t0[4..]);
    assert_bad_tdm(move |t| t.replacen(&format!("RANGE = {t0}"), &format!("RANGE = {earlier}"), 1), first, "RANGE");
}

#[test]
fn tdm_with_an_unsupported_time_system_is_refused() {
    let line = line_of("TIME_SYSTEM")(&sample_tdm());
    assert_bad_tdm(|t| t.replace("TIME_SYSTEM = UTC", "TIME_SYSTEM = UT1"), line, "TIME_SYSTEM");
}

#[test]
fn tdm_with_an_unsupported_angle_type_is_refused() {
    let line = line_of("ANGLE_TYPE")(&sample_tdm());
    assert_bad_tdm(|t| t.replace("ANGLE_TYPE = AZEL", "ANGLE_TYPE = XEYN"), line, "ANGLE_TYPE");
    // RADEC is supported, but not for the configuration's radar.
    assert_bad_tdm(|t| t.replace("ANGLE_TYPE = AZEL", "ANGLE_TYPE = RADEC"), line, "ANGLE_TYPE");
}

#[test]
fn tdm_naming_an_unknown_sensor_is_refused() {
    let line = line_of("PARTICIPANT_1")(&sample_tdm());
    assert_bad_tdm(|t| t.replace("PARTICIPANT_1 = radar-north", "PARTICIPANT_1 = radar-west"), line, "PARTICIPANT_1");
}

/// Every exported TDM under `from` copied to `to` with each line rewritten by `edit` (`None` keeps it).
fn edited_copies(from: &Path, to: &Path, mut edit: impl FnMut(&str) -> Option<String>) -> Vec<PathBuf> {
    std::fs::create_dir_all(to).expect("copy dir");
    let mut files: Vec<PathBuf> = std::fs::read_dir(from).expect("tdm dir").map(|e| e.expect("entry").path()).collect();
    files.sort();
    files
        .iter()
        .map(|file| {
            let text: Vec<String> =
                read(file).lines().map(|line| edit(line).unwrap_or_else(|| line.to_string())).collect();
            let copy = to.join(file.file_name().expect("file name"));
            std::fs::write(&copy, text.join("\n") + "\n").expect("write TDM copy");
            copy
        })
        .collect()
}

/// `(keyword, time, value)` of a data line, `("COMMENT EMPTY_SCAN", time, "")` of an empty scan's line.
fn data_of(line: &str) -> Option<(&str, &str, &str)> {
    if let Some(time) = line.strip_prefix("COMMENT EMPTY_SCAN ") {
        return Some(("COMMENT EMPTY_SCAN", time, ""));
    }
    let (key, rest) = line.split_once(" = ")?;
    if !["RANGE", "ANGLE_1", "ANGLE_2", "DOPPLER_INSTANTANEOUS"].contains(&key) {
        return None;
    }
    let (time, value) = rest.split_once(' ')?;
    Some((key, time, value))
}

/// Every number of two `estimates.csv` texts within `tolerance` of each other, every other field equal.
fn assert_estimates_close(got: &str, want: &str, tolerance: f64) -> f64 {
    assert_eq!(got.lines().count(), want.lines().count(), "rows");
    let mut worst = 0.0_f64;
    for (a, b) in got.lines().zip(want.lines()) {
        for (x, y) in a.split(',').zip(b.split(',')) {
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) => worst = worst.max((x - y).abs()),
                _ => assert_eq!(x, y, "{a} / {b}"),
            }
        }
    }
    assert!(worst <= tolerance, "largest difference {worst} > {tolerance}");
    worst
}

fn exported(dir: &TempDir, scenario: &Value) -> (PathBuf, PathBuf) {
    let config = dir.join("scenario.json");
    save(scenario, &config);
    let tdm = dir.join("tdm");
    ok(host_sim(&["export-tdm", p(&config), "--out", p(&tdm)]));
    (config, tdm)
}

fn tdm_files(dir: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir).expect("tdm dir").map(|e| e.expect("entry").path()).collect();
    files.sort();
    files
}

#[test]
fn tdm_in_tai_or_gps_and_with_corrections_to_apply_track_back_to_the_plain_estimates() {
    use host_sim::sim::fk5::tai_minus_utc;
    let dir = TempDir::new("reduction");
    let (config, tdm) = exported(&dir, &generate(&dir, "tiny-3d"));
    let plain_out = dir.join("plain-out");
    ok(track(&tdm_files(&tdm), &config, "homht", &plain_out));
    let expected = read(&plain_out.join("estimates.csv"));
    // TAI and GPS: every time moved by the offset of its date, exactly; bit-identical estimates.
    for (system, gps) in [("TAI", false), ("GPS", true)] {
        let copies = edited_copies(&tdm, &dir.join(system), |line| {
            if line == "TIME_SYSTEM = UTC" {
                return Some(format!("TIME_SYSTEM = {system}"));
            }
            let (key, time, value) = data_of(line)?;
            let utc = Instant::parse(time).expect("time");
            let offset = tai_minus_utc(utc.julian_date()).expect("leap seconds") - if gps { 19.0 } else { 0.0 };
            let moved = utc.shifted_millis((offset * 1000.0) as i64);
            Some(if value.is_empty() { format!("{key} {moved}") } else { format!("{key} = {moved} {value}") })
        });
        let out = dir.join(&format!("{system}-out"));
        ok(track(&copies, &config, "homht", &out));
        assert_eq!(read(&out.join("estimates.csv")), expected, "{system}");
    }
    // A 19 km range correction still to be added (CORRECTIONS_APPLIED = NO): the values written 19 km short.
    let corrected = edited_copies(&tdm, &dir.join("corrected"), |line| {
        if line == "TIME_SYSTEM = UTC" {
            return Some("TIME_SYSTEM = UTC\nCORRECTION_RANGE = 19\nCORRECTIONS_APPLIED = NO".into());
        }
        match data_of(line)? {
            ("RANGE", time, value) => Some(format!("RANGE = {time} {}", value.parse::<f64>().expect("range") - 19.0)),
            _ => None,
        }
    });
    let out = dir.join("corrected-out");
    ok(track(&corrected, &config, "homht", &out));
    let worst = assert_estimates_close(&read(&out.join("estimates.csv")), &expected, 1e-6);
    eprintln!("CORRECTION_RANGE 19 km, CORRECTIONS_APPLIED = NO: largest estimate difference {worst:e}");
    // Already applied: the values are read as they are.
    let applied = edited_copies(&tdm, &dir.join("applied"), |line| {
        (line == "TIME_SYSTEM = UTC")
            .then(|| "TIME_SYSTEM = UTC\nCORRECTION_RANGE = 19\nCORRECTIONS_APPLIED = YES".into())
    });
    let out = dir.join("applied-out");
    ok(track(&applied, &config, "homht", &out));
    assert_eq!(read(&out.join("estimates.csv")), expected);
}

#[test]
fn right_ascensions_in_eme2000_track_back_to_the_teme_estimates() {
    use host_sim::sim::fk5::{Reduction, apply, tt_of_utc};
    let dir = TempDir::new("eme2000");
    let s = short_optical_geo(&dir);
    let (config, tdm) = exported(&dir, &s);
    let plain_out = dir.join("plain-out");
    ok(track(&tdm_files(&tdm), &config, "rfisst", &plain_out));
    let mut right_ascension: Option<f64> = None;
    let mut largest_turn = 0.0_f64;
    let copies = edited_copies(&tdm, &dir.join("eme2000"), |line| {
        if line == "REFERENCE_FRAME = TEME" {
            return Some("REFERENCE_FRAME = EME2000".into());
        }
        match data_of(line)? {
            ("ANGLE_1", _, value) => {
                right_ascension = Some(value.parse().expect("angle"));
                Some(String::new())
            }
            ("ANGLE_2", time, value) => {
                let (alpha, delta) = (
                    right_ascension.take().expect("ANGLE_1 first").to_radians(),
                    value.parse::<f64>().expect("angle").to_radians(),
                );
                let jd = Instant::parse(time).expect("time").julian_date();
                let m = Reduction::at(tt_of_utc(jd).expect("leap seconds")).teme_to_j2000();
                let u = apply(&m, [delta.cos() * alpha.cos(), delta.cos() * alpha.sin(), delta.sin()]);
                let (a, d) = (u[1].atan2(u[0]), u[2].atan2(u[0].hypot(u[1])));
                largest_turn = largest_turn.max((a - alpha).abs());
                Some(format!("ANGLE_1 = {time} {}\nANGLE_2 = {time} {}", a.to_degrees(), d.to_degrees()))
            }
            _ => None,
        }
    });
    // The empty lines left where ANGLE_1 was are blank lines, which a TDM may hold.
    assert!(largest_turn.to_degrees() > 0.1, "precession since 2000: {} deg", largest_turn.to_degrees());
    let out = dir.join("eme2000-out");
    ok(track(&copies, &config, "rfisst", &out));
    let worst =
        assert_estimates_close(&read(&out.join("estimates.csv")), &read(&plain_out.join("estimates.csv")), 1e-6);
    eprintln!(
        "EME2000 right ascensions turned {:.3} deg: largest estimate difference {worst:e}",
        largest_turn.to_degrees()
    );
}

#[test]
fn tdm_frames_time_systems_and_corrections_that_cannot_be_read_are_refused() {
    let text = sample_tdm();
    let line = line_of("TIME_SYSTEM")(&text);
    assert_bad_tdm(
        |t| t.replace("TIME_SYSTEM = UTC", "TIME_SYSTEM = UTC\nREFERENCE_FRAME = MOD"),
        line + 1,
        "REFERENCE_FRAME",
    );
    assert_bad_tdm(
        |t| t.replace("TIME_SYSTEM = UTC", "TIME_SYSTEM = UTC\nCORRECTION_RANGE = 0.5"),
        line + 1,
        "CORRECTION_RANGE",
    );
    assert_bad_tdm(
        |t| t.replace("TIME_SYSTEM = UTC", "TIME_SYSTEM = UTC\nCORRECTIONS_APPLIED = MAYBE"),
        line + 1,
        "CORRECTIONS_APPLIED",
    );
    assert_bad_tdm(
        |t| {
            t.replace(
                "TIME_SYSTEM = UTC",
                "TIME_SYSTEM = UTC\nCORRECTION_ABERRATION_YEARLY = 0.001\nCORRECTIONS_APPLIED = NO",
            )
        },
        line + 1,
        "CORRECTION_ABERRATION",
    );
}
