//! Real data (issue 29 item 7): README's `host-sim track-ilrs` command on the committed laser ranges of
//! LAGEOS-2 (host-sim/data/ilrs) reproduces docs/results.md's figures within stated bounds, and tracking
//! its TDM and configuration with `host-sim track` gives the same estimates (the real-data path is the one
//! users take). Bad files are one line naming the file, line and field, exit code 2, nothing written.

use serde_json::Value;
use std::path::{Path, PathBuf};

mod common;
use common::{TempDir, host_sim, ok, p, read};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/ilrs").join(name)
}

/// README's command with the CRD file `crd`, into `out`.
fn track_ilrs(crd: &Path, out: &Path) -> std::process::Output {
    let (cpf, stations) = (data("lageos2_cpf_160213_5441.sgf"), data("slrf2014_stations.snx"));
    host_sim(&[
        "track-ilrs",
        "--crd",
        p(crd),
        "--cpf",
        p(&cpf),
        "--stations",
        p(&stations),
        "--centre-of-mass-m",
        "0.251",
        "--out",
        p(out),
    ])
}

#[test]
fn readme_gives_this_command() {
    let readme = read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../README.md"));
    let command: String =
        readme.split("track-ilrs --crd").nth(2).expect("README's real-data command").chars().take(260).collect();
    let words: Vec<&str> = command.split_whitespace().filter(|w| *w != "\\").collect();
    assert_eq!(
        words[..9],
        [
            "host-sim/data/ilrs/lageos2_20160214.npt",
            "--cpf",
            "host-sim/data/ilrs/lageos2_cpf_160213_5441.sgf",
            "--stations",
            "host-sim/data/ilrs/slrf2014_stations.snx",
            "--centre-of-mass-m",
            "0.251",
            "--out",
            "out/lageos2",
        ]
    );
}

#[test]
fn lageos2_is_tracked_to_the_figures_of_the_results_page() {
    let dir = TempDir::new("ilrs");
    let out = dir.join("lageos2");
    ok(track_ilrs(&data("lageos2_20160214.npt"), &out));
    let r: Value = serde_json::from_str(&read(&out.join("ilrs.json"))).expect("ilrs.json");
    let count = |key: &str| r[key].as_u64().expect(key);
    assert_eq!((count("normal_points_read"), count("normal_points_outside_cpf")), (95, 42));
    assert_eq!(count("normal_points_tracked"), 53, "every point of the CPF's day is tracked");
    assert_eq!(r["stations"], serde_json::json!(["7090-YARL", "7119-HA4T", "7941-MATM"]));
    let figure = |key: &str, stat: &str| r[key][stat].as_f64().expect(stat);
    // The reduction agrees with the CPF's ranges to metres (1.76 m RMS measured).
    assert!(figure("range_minus_cpf_m", "rms") < 3.0, "{}", r["range_minus_cpf_m"]);
    // The tracker fits the ranges to decimetres (0.074 m RMS, 0.193 m largest, measured).
    assert!(figure("range_minus_tracker_m", "rms") < 0.2, "{}", r["range_minus_tracker_m"]);
    assert!(figure("range_minus_tracker_m", "max_abs") < 0.5, "{}", r["range_minus_tracker_m"]);
    // From the prior's 3.3 km off to within 0.1 km of the CPF at the last point (0.045 km measured).
    let [first, last] = [0, 1].map(|i| r["position_vs_cpf_first_last_km"][i].as_f64().expect("km"));
    assert!(first > 3.0 && last < 0.1, "{first} km, {last} km");
    let passes = r["passes"].as_array().expect("passes");
    assert_eq!(passes.len(), 4);
    for pass in passes {
        let error = pass["position_vs_cpf_ric_km"][3].as_f64().expect("norm");
        assert!(error < 0.5, "{pass}");
    }
    let summary: Value = serde_json::from_str(&read(&out.join("track/summary.json"))).expect("summary");
    assert_eq!(summary["rejected_scans"], serde_json::json!([]));
    for (name, sensor) in summary["residuals"].as_object().expect("residuals") {
        assert_eq!(sensor["associated_fraction"].as_f64(), Some(1.0), "{name}");
    }
    // The same run through `track`.
    let again = dir.join("again");
    ok(host_sim(&[
        "track",
        "--tdm",
        p(&out.join("ranges.tdm")),
        "--config",
        p(&out.join("config.json")),
        "--out",
        p(&again),
    ]));
    assert_eq!(read(&again.join("estimates.csv")), read(&out.join("track/estimates.csv")));
}

#[test]
fn bad_laser_ranging_files_are_one_line_with_exit_code_2() {
    let dir = TempDir::new("ilrs-bad");
    let text = read(&data("lageos2_20160214.npt"));
    let cases = [
        (
            "     0.039237325685 std 2",
            "     0.0392x7325685 std 2",
            ":12: 11 time of flight: \"0.0392x7325685\" is not a finite number",
        ),
        ("h2 YARL       7090", "h2 YARL       7091", ":4: h2 pad number: station 7091 is not in the stations file"),
        (
            "h3 lageos2     9207002 5986    22195 0 1\nh4  1 2016  2 13 13",
            "h3 lageos1     9207002 5986    22195 0 1\nh4  1 2016  2 13 13",
            ":4: h3 target name: \"lageos1\" is not the CPF's target",
        ),
    ];
    for (k, (from, to, message)) in cases.iter().enumerate() {
        let bad = text.replacen(from, to, 1);
        assert_ne!(bad, text, "{from}");
        let file = dir.join(&format!("bad{k}.npt"));
        std::fs::write(&file, bad).expect("write");
        let out = dir.join(&format!("out{k}"));
        let run = track_ilrs(&file, &out);
        assert_eq!(run.status.code(), Some(2), "{to}");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains(&format!("{}{message}", file.display())), "{stderr}");
        assert!(!out.exists(), "{to}: nothing written");
    }
}
