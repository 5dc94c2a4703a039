//! Sensor networks of mixed kinds at the command line and against the reference (issue 28): `tiny-network`
//! (two radars, one with range-rate, two telescopes, an az/el and a ranging station) run, compared with the
//! unbounded reference, exported to TDMs and tracked back; bad files refused with one line.

use serde_json::Value;
use std::path::{Path, PathBuf};

mod common;
use common::{TempDir, host_sim, ok, p, read};

fn generate(dir: &TempDir, preset: &str, seed: u64) -> Value {
    let file = dir.join("generated.json");
    ok(host_sim(&["generate", preset, "--seed", &seed.to_string(), "--out", p(&file)]));
    serde_json::from_str(&read(&file)).expect("scenario JSON")
}

fn save(value: &Value, path: &Path) {
    std::fs::write(path, serde_json::to_string(value).expect("json")).expect("write scenario");
}

/// The kinds of the sensors whose scans in `scenario` carry a measurement.
fn kinds_measured(scenario: &Value) -> Vec<String> {
    let sensors = scenario["sensors"].as_array().expect("sensors");
    let mut kinds: Vec<String> = scenario["scans"]
        .as_array()
        .expect("scans")
        .iter()
        .filter(|scan| !scan["measurements"].as_array().expect("measurements").is_empty())
        .map(|scan| sensors[scan["sensor"].as_u64().expect("sensor") as usize]["kind"].as_str().expect("kind").into())
        .collect();
    kinds.sort();
    kinds.dedup();
    kinds
}

/// `tiny-network` seed 2, scans 18 to 29 (two minutes: every sensor twice): every kind measures, the
/// object unknown to the prior is born from the first radar's detection, and the reference's hypotheses
/// stay small enough for a test.
fn window(dir: &TempDir) -> Value {
    let mut s = generate(dir, "tiny-network", 2);
    let kept = |list: &Value| Value::Array(list.as_array().expect("list")[18..30].to_vec());
    s["scans"] = kept(&s["scans"]);
    s["truth"]["scans"] = kept(&s["truth"]["scans"]);
    s
}

#[test]
fn a_small_mixed_scenario_with_births_matches_the_reference() {
    let dir = TempDir::new("network-compare");
    let scenario = window(&dir);
    assert_eq!(kinds_measured(&scenario), ["az-el", "optical", "radar", "radar-range-rate", "range"]);
    assert!(scenario["birth"]["measured"].is_object(), "births from the measurements are on");
    let file = dir.join("window.json");
    save(&scenario, &file);
    let out = dir.join("compare");
    ok(host_sim(&["compare", p(&file), "--out", p(&out)]));
    let figures: Value = serde_json::from_str(&read(&out.join("compare.json"))).expect("compare.json");
    assert_eq!(figures["map_agreement"], 1.0, "{figures}");
    assert!(figures["min_captured_mass"].as_f64().expect("mass") >= 0.999, "{figures}");
    assert!(figures["max_map_weight_difference"].as_f64().expect("difference") <= 1e-12, "{figures}");
    assert_eq!(figures["reference_rejected_scans"], 0);
}

/// With track loss after one unseen scan (every track in view with no measurement in its gate leaves every
/// hypothesis at once), the window still matches the reference, which applies the same rule, and the rule
/// does fire.
#[test]
fn track_loss_matches_the_reference() {
    let dir = TempDir::new("network-compare-loss");
    let mut scenario = window(&dir);
    scenario["tracker"]["lost_after_unseen_scans"] = 1.into();
    let file = dir.join("window.json");
    save(&scenario, &file);
    let run = dir.join("run");
    ok(host_sim(&["run", p(&file), "--out", p(&run), "--quiet"]));
    let summary: Value = serde_json::from_str(&read(&run.join("summary.json"))).expect("summary.json");
    assert!(summary["lost_tracks"].as_u64().is_some_and(|n| n > 0), "the rule fires: {summary}");
    let out = dir.join("compare");
    ok(host_sim(&["compare", p(&file), "--out", p(&out)]));
    let figures: Value = serde_json::from_str(&read(&out.join("compare.json"))).expect("compare.json");
    assert_eq!(figures["map_agreement"], 1.0, "{figures}");
    assert!(figures["max_map_weight_difference"].as_f64().expect("difference") <= 1e-12, "{figures}");
    assert_eq!(figures["reference_rejected_scans"], 0);
}

/// A prior track 300 km along its orbit from its object (what a short-arc birth is after an hour's coast)
/// with a covariance that does not cover it: `tiny-network` as generated (track loss after 5 unseen scans)
/// drops it once the sensors looking at it see nothing there, and scores better than the same file with
/// `lost_after_unseen_scans` removed, where the track stays for the whole run (docs/results.md, `network`).
#[test]
fn a_track_that_left_its_object_is_lost_and_the_run_scores_better() {
    let dir = TempDir::new("network-loss");
    let mut scenario = generate(&dir, "tiny-network", 2);
    assert_eq!(scenario["tracker"]["lost_after_unseen_scans"], 5, "the network preset manages tracks");
    let object = &mut scenario["prior"]["hypotheses"][0]["objects"][0];
    let mean: Vec<f64> = object["mean"].as_array().expect("mean").iter().flat_map(Value::as_f64).collect();
    let speed = mean[3..].iter().map(|v| v * v).sum::<f64>().sqrt();
    for i in 0..3 {
        object["mean"][i] = (mean[i] + 300.0 * mean[3 + i] / speed).into();
    }
    let mean_gospa = |scenario: &Value, name: &str| -> (f64, u64) {
        let file = dir.join(&format!("{name}.json"));
        save(scenario, &file);
        let out = dir.join(name);
        ok(host_sim(&["run", p(&file), "--out", p(&out), "--quiet"]));
        let summary: Value = serde_json::from_str(&read(&out.join("summary.json"))).expect("summary.json");
        (summary["mean_gospa"].as_f64().expect("gospa"), summary["lost_tracks"].as_u64().unwrap_or(0))
    };
    let (managed, lost) = mean_gospa(&scenario, "managed");
    scenario["tracker"].as_object_mut().expect("tracker").remove("lost_after_unseen_scans");
    let (exact, never) = mean_gospa(&scenario, "exact");
    assert!(lost >= 1 && never == 0, "lost {lost}, without the rule {never}");
    assert!(managed < exact, "mean GOSPA with track loss {managed} against {exact} without");
}

#[test]
fn tiny_network_confirms_its_birth_and_reports_its_kinds() {
    let dir = TempDir::new("network-run");
    let file = dir.join("tiny.json");
    save(&generate(&dir, "tiny-network", 2), &file);
    let out = dir.join("run");
    ok(host_sim(&["run", p(&file), "--out", p(&out), "--quiet"]));
    let summary: Value = serde_json::from_str(&read(&out.join("summary.json"))).expect("summary.json");
    let kinds: Vec<&str> =
        summary["sensor_kinds"].as_array().expect("sensor_kinds").iter().flat_map(Value::as_str).collect();
    assert_eq!(kinds, ["radar", "radar-range-rate", "optical", "az-el", "range"]);
    assert_eq!((summary["births_total"].as_u64(), summary["births_confirmed"].as_u64()), (Some(1), Some(1)));
    assert_eq!(summary["false_tracks"], 0, "{summary}");
    assert_eq!(summary["refused_scans"]["count"], 0);
    // Every sensor's residuals are judged in its own components.
    for (sensor, components) in [("radar-south", 4), ("az-el-station", 2), ("ranging-station", 1)] {
        let rms = summary["residuals"][sensor]["rms"].as_array().unwrap_or_else(|| panic!("{sensor}: {summary}"));
        assert_eq!(rms.len(), components, "{sensor}");
    }
    for sky in ["sky_4_az-el-station.png", "sky_5_ranging-station.png", "sky_2_telescope-west.png"] {
        assert!(out.join(sky).exists(), "{sky}");
    }
}

/// export-tdm, then track with the same file as the configuration: one TDM per sensor with the keywords
/// of its kind, and the run's estimates bit for bit.
#[test]
fn tracking_the_tdm_export_of_a_network_gives_the_run_estimates_bit_for_bit() {
    let dir = TempDir::new("network-tdm");
    let mut scenario = generate(&dir, "tiny-network", 2);
    scenario.as_object_mut().expect("object").remove("truth");
    let file = dir.join("network.json");
    save(&scenario, &file);
    let (run, tdm, track) = (dir.join("run"), dir.join("tdm"), dir.join("track"));
    ok(host_sim(&["run", p(&file), "--out", p(&run), "--quiet"]));
    ok(host_sim(&["export-tdm", p(&file), "--out", p(&tdm)]));
    let mut files: Vec<PathBuf> = std::fs::read_dir(&tdm).expect("tdm dir").map(|e| e.expect("entry").path()).collect();
    files.sort();
    assert_eq!(files.len(), 6);
    let text = |i: usize| read(&files[i]);
    assert!(text(1).contains("ANGLE_TYPE = AZEL") && text(1).contains("DOPPLER_INSTANTANEOUS = "));
    assert!(text(2).contains("ANGLE_TYPE = RADEC") && !text(2).contains("RANGE = "));
    assert!(text(4).contains("ANGLE_TYPE = AZEL") && text(4).contains("PATH = 2,1") && !text(4).contains("RANGE = "));
    assert!(!text(5).contains("ANGLE_TYPE") && !text(5).contains("ANGLE_1 = ") && text(5).contains("RANGE = "));
    let mut args: Vec<String> = vec!["track".into(), "--tdm".into()];
    args.extend(files.iter().map(|f| p(f).to_string()));
    args.extend(["--config", p(&file), "--out", p(&track), "--quiet"].map(String::from));
    ok(host_sim(&args));
    let expected = read(&run.join("estimates.csv"));
    assert!(expected.lines().count() > 10, "estimates written");
    assert_eq!(read(&track.join("estimates.csv")), expected);
}

/// `edit` applied to tiny-network seed 2: `run` exits 2 with one line holding `message`.
fn assert_refused(edit: impl Fn(&mut Value), message: &str) {
    let dir = TempDir::new("network-bad");
    let mut scenario = generate(&dir, "tiny-network", 2);
    edit(&mut scenario);
    let file = dir.join("bad.json");
    save(&scenario, &file);
    let output = host_sim(&["run", p(&file), "--out", p(&dir.join("out")), "--quiet"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{message}: {stderr}");
    assert!(stderr.contains(message), "expected {message:?} in {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
}

/// The first scan of the ranging station (sensor 5) with a measurement.
fn first_range_scan(scenario: &Value) -> usize {
    let scans = scenario["scans"].as_array().expect("scans");
    scans.iter().position(|s| s["sensor"] == 5 && !s["measurements"].as_array().expect("list").is_empty()).expect("one")
}

#[test]
fn measurements_of_the_wrong_kind_and_bad_kinds_are_refused() {
    assert_refused(
        |s| {
            let k = first_range_scan(s);
            s["scans"][k]["measurements"][0] = serde_json::json!([1000.0, 10.0, 20.0]);
        },
        "has 3 components, a range measurement has 1",
    );
    assert_refused(
        |s| {
            s["sensors"][4].as_object_mut().expect("sensor").remove("kind");
        },
        "sensors[4].kind: required when the measurement type is network",
    );
    assert_refused(|s| s["sensors"][4]["kind"] = "sonar".into(), "unknown sensor kind \"sonar\"");
    assert_refused(|s| s["sensors"][4]["kind"] = "network".into(), "unknown sensor kind \"network\"");
    // A range-only sensor's field of view needs its range window, and an az/el one has none.
    assert_refused(
        |s| {
            s["sensors"][5]["field_of_view"].as_object_mut().expect("fov").remove("range_km");
        },
        "sensors[5].field_of_view.range_km: required for range",
    );
    assert_refused(
        |s| s["sensors"][4]["field_of_view"]["range_km"] = serde_json::json!([0.0, 10.0]),
        "sensors[4].field_of_view.range_km: not part of the field of view of a sensor of kind az-el",
    );
    assert_refused(
        |s| s["sensors"][5]["field_of_view"]["range_km"] = serde_json::json!([300.0, 300.0]),
        "the field of view has no volume",
    );
}

#[test]
fn kinds_outside_a_network_must_match_its_measurement_type() {
    let dir = TempDir::new("network-single");
    let mut scenario = generate(&dir, "tiny-3d", 1);
    scenario["sensors"][0]["kind"] = "radar".into();
    let file = dir.join("same.json");
    save(&scenario, &file);
    ok(host_sim(&["run", p(&file), "--out", p(&dir.join("same")), "--quiet"]));
    scenario["sensors"][0]["kind"] = "optical".into();
    save(&scenario, &file);
    let output = host_sim(&["run", p(&file), "--out", p(&dir.join("other")), "--quiet"]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("differs from the measurement type \"radar\""));
    scenario["sensors"][0]["kind"] = "radar".into();
    scenario["sensors"][0]["birth_region"] = serde_json::json!({"region": "geo"});
    save(&scenario, &file);
    let output = host_sim(&["run", p(&file), "--out", p(&dir.join("region")), "--quiet"]);
    assert_eq!(output.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&output.stderr).contains("sensors[0].birth_region: only a sensor of a network"));
}

/// `soak --scenario ssa-network` (issue 33 item 8): the fused tracker on the whole network, observed past
/// the preset's end; healthy and its report complete (the 100,000-scan figures are in docs/robustness.md).
#[test]
fn a_short_network_soak_is_healthy() {
    let dir = TempDir::new("soak-network");
    let out = dir.join("soak.json");
    ok(host_sim(&["soak", "--scenario", "ssa-network", "--scans", "120", "--quiet", "--out", p(&out)]));
    let report: Value = serde_json::from_str(&read(&out)).expect("soak JSON");
    assert_eq!(report["scenario"], "ssa-network");
    assert_eq!(report["scans"], 120);
    assert_eq!(report["nan_count"], 0);
    assert_eq!(report["errors_by_kind"], serde_json::json!({}));
    assert_eq!(report["numerical_drops"], 0);
    // Every kind's measurements went through the one tracker.
    assert!(report["measurements"].as_u64().expect("measurements") > 100, "{report}");
    assert!(report["tracking"]["in_view_tracked_fraction"].as_f64().expect("fraction") > 0.5, "{report}");
}
