//! `experiment catalogue` on a short, small version: every key of `catalogue.json`, sane values, the files.

use host_sim::experiments::catalogue::{Settings, build_catalogue, run_with};
use serde_json::Value;

/// Ten minutes of Tucson's night (the telescope scans), 2 planes × 3 satellites and a train of 3.
const SHORT: Settings = Settings {
    start: "2026-03-20T06:00:00Z",
    duration_hours: 0.1,
    scan_interval_s: 20.0,
    verification: false,
    planes: 2,
    per_plane: 3,
    train: 3,
    missing_fraction: 0.5,
};

#[test]
fn the_full_catalogue_has_at_least_100_objects() {
    let catalogue = build_catalogue(&Settings::FULL).expect("catalogue");
    assert!(catalogue.entries.len() >= 100, "{}", catalogue.entries.len());
}

#[test]
fn a_short_run_writes_every_figure() {
    // Trackers hold several MiB inline: a large stack, as `main` gives them.
    std::thread::Builder::new().stack_size(512 << 20).spawn(short_run).expect("thread").join().expect("no panic");
}

fn short_run() {
    let dir = std::env::temp_dir().join(format!("host-sim-catalogue-experiment-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let report = run_with(&dir, 3, true, &SHORT).expect("runs");
    let text = std::fs::read_to_string(dir.join("catalogue.json")).expect("catalogue.json");
    let json: Value = serde_json::from_str(&text).expect("JSON");
    for key in [
        "objects",
        "births_total",
        "births_confirmed",
        "false_tracks",
        "mean_gospa",
        "mean_ms_per_scan",
        "max_ms_per_scan",
    ] {
        assert!(json.get(key).is_some_and(Value::is_number), "{key}: {json}");
    }
    // One tracker for the whole network: the radars' kind and the telescope's.
    assert_eq!(json["sensor_kinds"], serde_json::json!(["radar", "optical"]), "{json}");
    assert_eq!(json["objects"], 9);
    // The train and half of the six others are missing.
    assert_eq!(report.missing_from_prior, 6);
    assert!(report.births_confirmed <= report.births_total && report.births_total <= 6);
    assert!(report.mean_gospa.is_finite() && report.mean_gospa >= 0.0, "{}", report.mean_gospa);
    // GOSPA is bounded by its cut-off c: at most c (n / 2)^(1/2) for n objects missed or false.
    let cap = 10.0 * ((9 + 20) as f64 / 2.0).sqrt();
    assert!(report.mean_gospa <= cap, "{}", report.mean_gospa);
    assert!(report.mean_ms_per_scan > 0.0 && report.max_ms_per_scan >= report.mean_ms_per_scan);
    let details = json["details"].as_array().expect("details");
    assert_eq!(details.len(), 1);
    let d = &details[0];
    assert_eq!(d["network"].as_str(), Some("network"));
    assert_eq!(d["sensors"], serde_json::json!(["radar-north", "radar-south", "telescope"]));
    assert!(d["births_confirmed"].as_u64() <= d["births_detected"].as_u64(), "{d}");
    assert_eq!(d["births_detected"].as_u64(), Some(report.births_total as u64), "{json}");
    assert_eq!(d["false_tracks"], json["false_tracks"]);
    // Each detected birth not confirmed is listed with how much it was seen.
    let unconfirmed = d["unconfirmed_births"].as_array().expect("unconfirmed_births");
    let (detected, confirmed) = (d["births_detected"].as_u64().expect("n"), d["births_confirmed"].as_u64().expect("n"));
    assert_eq!(unconfirmed.len() as u64, detected - confirmed, "{d}");
    for birth in unconfirmed {
        assert!(birth["detections"].as_u64().is_some_and(|n| n >= 1), "{birth}");
        assert!(birth["detected_from_s"].as_f64() <= birth["detected_until_s"].as_f64(), "{birth}");
    }
    // 0.1 h of the telescope's night: the three sensors in turn, one scan every 20 s / 3 from 0 to 360 s.
    let scans = d["scans"].as_u64().expect("scans");
    assert!((54..=55).contains(&scans), "{scans}");
    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("network/summary.json")).expect("summary"))
            .expect("JSON");
    assert_eq!(summary["sensor_kinds"], json["sensor_kinds"]);
    for file in [
        "catalogue.omm.json",
        "sensors-network.json",
        "network/summary.json",
        "network/tracks.oem",
        "cardinality.png",
        "gospa.png",
        "ground_tracks_network.png",
    ] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    // The sensors file written is the one a user can reload (a network of mixed kinds).
    let sensors =
        host_sim::scenario::from_catalogue::SensorsFile::load(&dir.join("sensors-network.json")).expect("sensors");
    assert_eq!(sensors.sensors.len(), 3);
    // The catalogue written is the one a user can reload.
    let entries = host_sim::io::catalogue::load(&dir.join("catalogue.omm.json")).expect("reload");
    assert_eq!(entries.len(), 9);
    let _ = std::fs::remove_dir_all(&dir);
}
