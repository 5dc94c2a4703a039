//! `host-sim generate synthetic-catalogue` (issue 30 item 4) and the observed / unobserved objects' errors of
//! `run-catalogue` (issue 30 item 5), at the command line.

use serde_json::Value;
use std::collections::{BTreeMap, BTreeSet};

mod common;
use common::{TempDir, host_sim, ok, p, read};

const RADARS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/sensors_radar.json");

fn generate(dir: &TempDir, name: &str, objects: &str, seed: &str) -> std::path::PathBuf {
    let out = dir.join(name);
    ok(host_sim(&["generate", "synthetic-catalogue", "--objects", objects, "--seed", seed, "--out", p(&out)]));
    out
}

#[test]
fn a_synthetic_catalogue_is_deterministic_and_reads_back() {
    let dir = TempDir::new("synthetic");
    let a = generate(&dir, "a.json", "400", "7");
    let b = generate(&dir, "b.json", "400", "7");
    let c = generate(&dir, "c.json", "400", "8");
    assert_eq!(read(&a), read(&b), "same seed, same bytes");
    assert_ne!(read(&a), read(&c));
    // `host-sim catalogue` reads it: 400 objects, unique numbers, every one with an SGP4 state.
    let report = dir.join("report.json");
    ok(host_sim(&["catalogue", p(&a), "--out", p(&report)]));
    let objects: Vec<Value> = serde_json::from_str(&read(&report)).expect("JSON");
    assert_eq!(objects.len(), 400);
    let ids: BTreeSet<u64> = objects.iter().map(|o| o["norad_id"].as_u64().expect("id")).collect();
    assert_eq!(ids.len(), 400);
    for o in &objects {
        assert!(o["sgp4_error"].is_null(), "{o}");
        let r = o["position_km"].as_array().expect("position");
        let radius = r.iter().map(|x| x.as_f64().unwrap().powi(2)).sum::<f64>().sqrt();
        assert!(radius > 6378.137 + 190.0, "{o}");
    }
    // Bad requests: one line, exit 2, nothing written.
    for args in
        [&["--objects", "0"][..], &["--objects", "400001"], &["--objects", "5", "--epoch", "2026-02-30T00:00:00"], &[]]
    {
        let out = dir.join("bad.json");
        let output = host_sim(&[&["generate", "synthetic-catalogue", "--out", p(&out)][..], args].concat());
        let err = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(!out.exists());
    }
}

/// (label or id, position) of every line of `estimates.csv` at scan `scan`.
fn map_at(estimates: &str, scan: usize) -> BTreeMap<u64, [f64; 3]> {
    estimates
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|f| f[0].parse::<usize>().ok() == Some(scan))
        .map(|f| (f[3].parse().unwrap(), [4, 5, 6].map(|i| f[i].parse::<f64>().unwrap())))
        .collect()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { (v[n / 2 - 1] + v[n / 2]) / 2.0 }
}

#[test]
fn run_catalogue_reports_observed_and_unobserved_objects_apart() {
    let dir = TempDir::new("observed");
    let catalogue = generate(&dir, "syn.json", "60", "2");
    let out = dir.join("run");
    ok(host_sim(&[
        "run-catalogue",
        "--catalogue",
        p(&catalogue),
        "--sensors",
        RADARS,
        "--start",
        "2026-03-20T00:00:00Z",
        "--duration-hours",
        "1",
        "--quiet",
        "--out",
        p(&out),
    ]));
    let summary: Value = serde_json::from_str(&read(&out.join("summary.json"))).expect("summary");
    let observed = summary["observed_objects"].as_u64().expect("observed_objects") as usize;
    let unobserved = summary["unobserved_objects"].as_u64().expect("unobserved_objects") as usize;
    assert_eq!(observed + unobserved, 60);
    assert!(observed >= 5 && unobserved >= 5, "{observed} {unobserved}");
    let observed_km = summary["observed_median_error_km"].as_f64().expect("observed median");
    let unobserved_km = summary["unobserved_median_error_km"].as_f64().expect("unobserved median");
    // Recomputed from the files: truth and origins of scenario.json, MAP tracks of estimates.csv at the last
    // scan (every object in the prior, so each is matched by its label).
    let scenario: Value = serde_json::from_str(&read(&out.join("scenario.json"))).expect("scenario");
    let truth = scenario["truth"]["scans"].as_array().expect("truth scans");
    let seen: BTreeSet<u64> =
        truth.iter().flat_map(|s| s["origins"].as_array().expect("origins").iter().filter_map(Value::as_u64)).collect();
    assert_eq!(seen.len(), observed);
    let last = truth.len() - 1;
    let map = map_at(&read(&out.join("estimates.csv")), last);
    let (mut seen_errors, mut unseen_errors) = (vec![], vec![]);
    for object in truth[last]["objects"].as_array().expect("objects") {
        let id = object["id"].as_u64().unwrap();
        let state: Vec<f64> = object["state"].as_array().unwrap().iter().map(|x| x.as_f64().unwrap()).collect();
        let track = map.get(&id).expect("a track per object");
        let error = (0..3).map(|i| (state[i] - track[i]).powi(2)).sum::<f64>().sqrt();
        if seen.contains(&id) { seen_errors.push(error) } else { unseen_errors.push(error) }
    }
    assert!((median(seen_errors) - observed_km).abs() < 1e-6, "{observed_km}");
    assert!((median(unseen_errors) - unobserved_km).abs() < 1e-6, "{unobserved_km}");
    assert!(observed_km < 1.0 && observed_km < unobserved_km, "{observed_km} {unobserved_km}");
    assert!(out.join("observed_errors.png").is_file() && out.join("observed_errors.svg").is_file());
}

#[test]
fn a_catalogue_larger_than_one_tracker_runs_partitioned() {
    // Issue 30: 2,000 objects were refused with "prior hypothesis 0: more objects than the capacity N";
    // a prior larger than one tracker's N now goes to the partitioned tracker (docs/maths.md §13).
    let dir = TempDir::new("capacity");
    let catalogue = generate(&dir, "syn.json", "300", "1");
    let start = "2026-03-20T00:00:00Z";
    for profile in ["host", "embedded"] {
        let out = dir.join(profile);
        let output = host_sim(&[
            "run-catalogue",
            "--catalogue",
            p(&catalogue),
            "--sensors",
            RADARS,
            "--start",
            start,
            "--duration-hours",
            "0.01",
            "--quiet",
            "--profile",
            profile,
            "--out",
            p(&out),
        ]);
        let err = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(0), "{err}");
        let n = if profile == "host" { 256 } else { 64 };
        assert!(err.contains("300 prior objects") && err.contains(&format!("N = {n}")), "{err}");
        assert!(err.contains("partitioned tracker"), "{err}");
        assert!(out.join("summary.json").is_file());
    }
}
