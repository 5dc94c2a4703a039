//! Nothing the tracker does not take passes in silence (issues 33 and 29): tracks the core drops for a
//! numerical failure are in summary.json (`numerical_drops`), on stderr and in scans.jsonl, with exit
//! code 0; a scan the core refuses for its input is reported (`refused_scans`) and the run goes on.

use serde_json::{Value, json};
use std::path::Path;
use std::process::Output;

mod common;
use common::{TempDir, host_sim};

fn p(path: &Path) -> &str {
    path.to_str().expect("utf-8 path")
}

fn describe(output: &Output) -> String {
    format!(
        "stdout:\n{}\nstderr:\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).expect("json")
}

/// Planar two-body: an object on a 7000 km circular orbit seen at 10, 20 and 30 s, and a prior object at
/// the centre, where gravity is singular: the core drops it at the first scan.
fn centre_object_scenario() -> Value {
    let mu: f64 = 398_600.441_8;
    let r: f64 = 7000.0;
    let speed = (mu / r).sqrt();
    let omega = speed / r;
    let covariance = json!([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1e-4, 0.0], [0.0, 0.0, 0.0, 1e-4]]);
    let scans: Vec<Value> = [10.0, 20.0, 30.0_f64]
        .iter()
        .map(|&t| json!({ "time": t, "measurements": [[r * (omega * t).cos(), r * (omega * t).sin()]] }))
        .collect();
    json!({
        "format": "rfisst-scenario/1",
        "name": "centre-object",
        "description": "a prior object at the centre of a two-body field",
        "motion": { "type": "two-body", "mu": mu, "acceleration_noise": 1e-9, "max_step": 20.0, "max_substeps": 1000 },
        "measurement": { "type": "position", "noise_covariance": [[0.01, 0.0], [0.0, 0.01]] },
        "sensor": {
            "detection_probability": 0.9,
            "clutter_rate": 0.1,
            "field_of_view": { "type": "rectangle", "min": [-10000.0, -10000.0], "max": [10000.0, 10000.0] }
        },
        "birth": { "probability": 0.0, "detection": "all-detected", "cells": [] },
        "death_probability": 0.0,
        "tracker": { "gate": 25.0, "max_children_per_scan": 100000, "store_overflow": "prune-children", "seed": 1 },
        "prior": {
            "time": 0.0,
            "hypotheses": [{
                "weight": 1.0,
                "objects": [
                    { "label": 0, "mean": [r, 0.0, 0.0, speed], "covariance": covariance },
                    { "label": 1, "mean": [0.0, 0.0, 1.0, 0.0], "covariance": covariance }
                ]
            }]
        },
        "scans": scans
    })
}

#[test]
fn a_track_dropped_for_a_numerical_failure_is_reported() {
    let dir = TempDir::new("drops");
    let file = dir.join("centre.json");
    std::fs::write(&file, centre_object_scenario().to_string()).expect("write scenario");
    for tracker in ["homht", "rfisst"] {
        let out = dir.join(tracker);
        let output = host_sim(&["run", p(&file), "--tracker", tracker, "--quiet", "--out", p(&out)]);
        assert_eq!(output.status.code(), Some(0), "{tracker}: {}", describe(&output));
        // The judge's `warning: sensor` line aside (issue 29: this hand-made scenario's NIS is below its band).
        let err: String = String::from_utf8_lossy(&output.stderr)
            .lines()
            .filter(|l| !l.starts_with("warning: sensor "))
            .map(|l| format!("{l}\n"))
            .collect();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("warning: scan 0 (t = 10): 1 track(s) dropped for a numerical failure"), "{err}");
        assert!(err.contains("the first track 1 (motion model: "), "{err}");
        let summary = read_json(&out.join("summary.json"));
        let drops = &summary["numerical_drops"];
        assert_eq!(drops["count"], json!(1), "{summary}");
        let first = &drops["tracks"][0];
        assert_eq!((&first["scan"], &first["time"], &first["label"]), (&json!(0), &json!(10.0), &json!(1)), "{drops}");
        assert_eq!(first["dropped"], json!(1));
        assert!(first["reason"].as_str().is_some_and(|r| r.starts_with("motion model: ")), "{drops}");
        assert_eq!(summary["final_map_cardinality"], json!(1), "the other object is tracked: {summary}");
        let lines = std::fs::read_to_string(out.join("scans.jsonl")).expect("scans.jsonl");
        let per_scan: Vec<Value> =
            lines.lines().map(|l| serde_json::from_str::<Value>(l).expect("json")["numerical_drops"].clone()).collect();
        assert_eq!(per_scan, [json!(1), json!(0), json!(0)]);
    }
}

/// tiny-3d exported to TDM, with the elevation of the first measurement of the sixth scan set to 5°, below
/// the radar's 15° mask.
#[test]
fn a_scan_the_core_refuses_in_the_middle_of_a_tdm_is_reported_and_the_run_goes_on() {
    let dir = TempDir::new("refused");
    let config = dir.join("tiny.json");
    let output = host_sim(&["generate", "tiny-3d", "--seed", "1", "--out", p(&config)]);
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let tdm_dir = dir.join("tdm");
    let output = host_sim(&["export-tdm", p(&config), "--out", p(&tdm_dir)]);
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let tdm = tdm_dir.join("0-radar-north.tdm");
    let text = std::fs::read_to_string(&tdm).expect("tdm");
    let mut times: Vec<&str> =
        text.lines().filter_map(|l| l.strip_prefix("ANGLE_2 = ")?.split_once(' ').map(|(t, _)| t)).collect();
    times.dedup();
    assert!(times.len() >= 8, "{times:?}");
    let middle = times[5];
    let mut edited = false;
    let lines: Vec<String> = text
        .lines()
        .map(|l| match l.strip_prefix("ANGLE_2 = ").and_then(|rest| rest.split_once(' ')) {
            Some((t, _)) if t == middle && !edited => {
                edited = true;
                format!("ANGLE_2 = {t} 5.0")
            }
            _ => l.to_string(),
        })
        .collect();
    std::fs::write(&tdm, lines.join("\n") + "\n").expect("write tdm");
    let out = dir.join("out");
    let output = host_sim(&["track", "--tdm", p(&tdm), "--config", p(&config), "--quiet", "--out", p(&out)]);
    // Before issue 29: exit 3, the tracker "rejected" the scan.
    assert_eq!(output.status.code(), Some(0), "{}", describe(&output));
    let err = String::from_utf8_lossy(&output.stderr).to_string();
    assert!(err.contains("sensor radar-north) refused: measurement") && err.contains("the run goes on"), "{err}");
    let summary = read_json(&out.join("summary.json"));
    let refused = &summary["refused_scans"];
    assert_eq!(refused["count"], json!(1), "{summary}");
    let reason = &refused["reasons"][0];
    assert_eq!(reason["sensor"], json!("radar-north"));
    assert!(reason["reason"].as_str().is_some_and(|r| r.contains("outside the field of view")), "{refused}");
    let scan = reason["scan"].as_u64().expect("scan index") as usize;
    // The scans after it are tracked: estimates at the last scan.
    let estimates = std::fs::read_to_string(out.join("estimates.csv")).expect("estimates");
    let last = summary["scans"].as_u64().expect("scans") - 1;
    assert!(scan < last as usize);
    assert!(estimates.lines().any(|l| l.starts_with(&format!("{last},"))), "{estimates}");
    assert_eq!(summary["final_map_cardinality"], json!(3), "{summary}");
}
