//! A summary that judges a run without truth (issue 29 item 5): `run` and `track` write per sensor the
//! residuals and mean NIS of the MAP tracks' associated measurements with its χ² band, tracks started and
//! ended and measurements per track; a biased sensor is flagged in `consistency_warnings`, and no other.

use serde_json::Value;
use std::path::{Path, PathBuf};

mod common;
use common::{TempDir, host_sim, ok, p, read};

fn summary(dir: &Path) -> Value {
    serde_json::from_str(&read(&dir.join("summary.json"))).expect("summary JSON")
}

fn generate(dir: &TempDir, preset: &str) -> Value {
    let file = dir.join("generated.json");
    ok(host_sim(&["generate", preset, "--seed", "1", "--out", p(&file)]));
    serde_json::from_str(&read(&file)).expect("scenario JSON")
}

/// tiny-3d with a second radar (a copy of the first, another name) taking every other scan; without truth
/// (as tests/ccsds.rs's `two_radars`).
fn two_radars(dir: &TempDir) -> Value {
    let mut s = generate(dir, "tiny-3d");
    let mut second = s["sensors"][0].clone();
    second["name"] = "radar-copy".into();
    s["sensors"].as_array_mut().expect("sensors").push(second);
    for (k, scan) in s["scans"].as_array_mut().expect("scans").iter_mut().enumerate() {
        scan["sensor"] = (k % 2).into();
    }
    s.as_object_mut().expect("object").remove("truth");
    s
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("a number: {v}"))
}

/// Whether the sensor's mean NIS lies in its band.
fn in_band(sensor: &Value) -> bool {
    let (mean, band) = (f(&sensor["mean_nis"]), &sensor["nis_band"]);
    f(&band[0]) <= mean && mean <= f(&band[1])
}

#[test]
fn a_preset_run_is_judged_consistent() {
    let dir = TempDir::new("judge-run");
    let scenario = dir.join("tiny.json");
    std::fs::write(&scenario, generate(&dir, "tiny-3d").to_string()).expect("write");
    let out = dir.join("run");
    let output = ok(host_sim(&["run", p(&scenario), "--out", p(&out), "--quiet"]));
    let s = summary(&out);
    let residuals = s["residuals"].as_object().expect("residuals");
    assert_eq!(residuals.keys().collect::<Vec<_>>(), ["radar-north"]);
    let radar = &residuals["radar-north"];
    let rms: Vec<f64> = radar["rms"].as_array().expect("rms").iter().map(f).collect();
    // Range (km), azimuth and elevation (degrees): within a few σ (0.02 km, 108″ = 0.03°) of the noise.
    assert_eq!(rms.len(), 3, "{radar}");
    assert!(rms.iter().all(|&r| r > 0.0) && rms[0] < 0.5 && rms[1] < 0.5 && rms[2] < 0.5, "{rms:?}");
    assert!(in_band(radar), "{radar}");
    let fraction = f(&radar["associated_fraction"]);
    assert!(fraction > 0.5 && fraction <= 1.0, "{radar}");
    assert_eq!(radar["measurements"].as_u64(), Some(34), "tiny-3d seed 1 has 34 measurements");
    assert_eq!((s["tracks_started"].as_u64(), s["tracks_ended"].as_u64()), (Some(0), Some(0)), "{s}");
    assert!(f(&s["measurements_per_track"]) > 5.0, "{s}");
    assert_eq!(s["consistency_warnings"], Value::Array(vec![]));
    assert!(!String::from_utf8_lossy(&output.stderr).contains("warning"), "no warning line");
}

/// The two radars' TDMs, the second with `range_km` added to every range and `angle_deg` to every
/// azimuth.
fn biased_tdms(dir: &TempDir, scenario: &Path, range_km: f64, angle_deg: f64) -> Vec<PathBuf> {
    let tdm = dir.join("tdm");
    if !tdm.exists() {
        ok(host_sim(&["export-tdm", p(scenario), "--out", p(&tdm)]));
    }
    let biased = dir.join(&format!("biased-{range_km}-{angle_deg}.tdm"));
    let text: String = read(&tdm.join("1-radar-copy.tdm"))
        .lines()
        .map(|line| {
            let bias = if line.starts_with("RANGE =") {
                range_km
            } else if line.starts_with("ANGLE_1 =") {
                angle_deg
            } else {
                return format!("{line}\n");
            };
            let (head, value) = line.rsplit_once(' ').expect("keyword = epoch value");
            format!("{head} {:?}\n", value.parse::<f64>().expect("a value") + bias)
        })
        .collect();
    std::fs::write(&biased, text).expect("write biased TDM");
    vec![tdm.join("0-radar-north.tdm"), biased]
}

fn track(dir: &TempDir, scenario: &Path, tdms: &[PathBuf], tag: &str) -> (Value, String) {
    let out = dir.join(tag);
    let mut args: Vec<String> = vec!["track".into(), "--tdm".into()];
    args.extend(tdms.iter().map(|f| p(f).to_string()));
    args.extend(["--config", p(scenario), "--out", p(&out), "--quiet"].map(String::from));
    let output = ok(host_sim(&args));
    (summary(&out), String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn a_biased_sensor_is_flagged_and_no_other() {
    let dir = TempDir::new("judge-bias");
    let scenario = dir.join("two.json");
    std::fs::write(&scenario, two_radars(&dir).to_string()).expect("write");
    // Unbiased: both consistent.
    let (plain, stderr) = track(&dir, &scenario, &biased_tdms(&dir, &scenario, 0.0, 0.0), "plain");
    assert_eq!(plain["consistency_warnings"], Value::Array(vec![]), "{}\n{stderr}", plain["residuals"]);
    assert!(in_band(&plain["residuals"]["radar-copy"]) && in_band(&plain["residuals"]["radar-north"]));
    // 10 km and 0.1°: far beyond every gate, none of the sensor's measurements is associated.
    let (biased, stderr) = track(&dir, &scenario, &biased_tdms(&dir, &scenario, 10.0, 0.1), "biased");
    assert_eq!(biased["consistency_warnings"], serde_json::json!(["radar-copy"]), "{}", biased["residuals"]);
    assert_eq!(biased["residuals"]["radar-copy"]["associated_fraction"], 0.0);
    assert!(in_band(&biased["residuals"]["radar-north"]), "{}", biased["residuals"]);
    let warnings: Vec<&str> = stderr.lines().filter(|l| l.starts_with("warning: sensor")).collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(warnings[0].starts_with("warning: sensor radar-copy: none of its 17 measurements"), "{stderr}");
    // 60 m (3 σ) on the range alone: within the gate, flagged by its mean NIS above the band.
    let (small, stderr) = track(&dir, &scenario, &biased_tdms(&dir, &scenario, 0.06, 0.0), "small");
    assert_eq!(small["consistency_warnings"], serde_json::json!(["radar-copy"]), "{}", small["residuals"]);
    let copy = &small["residuals"]["radar-copy"];
    assert!(f(&copy["mean_nis"]) > f(&copy["nis_band"][1]), "{copy}");
    assert!(stderr.contains("warning: sensor radar-copy: mean NIS"), "{stderr}");
}

/// A planar (version 1) run of a core tracker is judged too: its one sensor is `sensor`; a 1.5 σ offset on
/// every x is flagged by the mean NIS.
#[test]
fn a_planar_run_is_judged_and_an_offset_flagged() {
    let dir = TempDir::new("judge-planar");
    let file = dir.join("crossings.json");
    ok(host_sim(&["generate", "crossings", "--seed", "1", "--out", p(&file)]));
    let out = dir.join("run");
    ok(host_sim(&["run", p(&file), "--out", p(&out), "--quiet"]));
    let s = summary(&out);
    let sensor = &s["residuals"]["sensor"];
    assert_eq!(sensor["rms"].as_array().map(Vec::len), Some(2), "{s}");
    assert!(in_band(sensor), "{sensor}");
    assert_eq!(s["consistency_warnings"], Value::Array(vec![]));
    assert!(s["tracks_started"].as_u64().is_some() && f(&s["measurements_per_track"]) > 1.0, "{s}");
    assert!(out.join("residuals_0_sensor.png").exists());
    // σ = 0.5 on x: every x moved by 0.75.
    let mut shifted: Value = serde_json::from_str(&read(&file)).expect("scenario JSON");
    for scan in shifted["scans"].as_array_mut().expect("scans") {
        for z in scan["measurements"].as_array_mut().expect("measurements") {
            z[0] = (f(&z[0]) + 0.75).into();
        }
    }
    let biased = dir.join("biased.json");
    std::fs::write(&biased, shifted.to_string()).expect("write");
    let out = dir.join("biased");
    let output = ok(host_sim(&["run", p(&biased), "--out", p(&out), "--quiet"]));
    let s = summary(&out);
    assert_eq!(s["consistency_warnings"], serde_json::json!(["sensor"]), "{}", s["residuals"]);
    assert!(String::from_utf8_lossy(&output.stderr).contains("warning: sensor sensor: mean NIS"));
}
