//! Integration tests of the `host-sim` command line: help, `generate`, `run`, `compare`, the
//! hand-written fixture of `docs/scenario-format.md`, exit codes and one-line errors for malformed files.
//!
//! The unbounded reference tracker grows its hypotheses exponentially: on the full 6-scan `linear-small`
//! it takes about 26 s in a debug build, so the tests that run it (`run --tracker reference`, `compare`)
//! use `linear-small` cut to its first 4 scans (about 0.1 s).

use host_sim::scenario::Scenario;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::Output;

mod common;
use common::{TempDir, host_sim};
const FIXTURE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/hand_written.json");
const DOC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/scenario-format.md");
const FIXTURE_3D: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/hand_written_3d.json");

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

fn describe(output: &Output) -> String {
    format!("status {:?}\nstdout:\n{}\nstderr:\n{}", output.status.code(), stdout(output), stderr(output))
}

fn assert_success(output: &Output) {
    assert_eq!(output.status.code(), Some(0), "{}", describe(output));
    assert!(!stderr(output).contains("panicked"), "{}", describe(output));
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn write_json(path: &Path, value: &Value) {
    std::fs::write(path, serde_json::to_string_pretty(value).expect("serialise")).expect("write scenario");
}

fn fixture() -> Value {
    read_json(Path::new(FIXTURE))
}

/// `host-sim generate linear-small` into `dir`, cut to its first `scans` scans when given.
fn linear_small(dir: &TempDir, scans: Option<usize>) -> PathBuf {
    let path = dir.join("linear-small.json");
    let output = host_sim(&["generate".as_ref(), "linear-small".as_ref(), "--out".as_ref(), path.as_os_str()]);
    assert_success(&output);
    if let Some(n) = scans {
        let mut scenario = read_json(&path);
        scenario["scans"].as_array_mut().expect("scans").truncate(n);
        scenario["truth"]["scans"].as_array_mut().expect("truth scans").truncate(n);
        write_json(&path, &scenario);
    }
    path
}

fn assert_nonempty_file(path: &Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(!bytes.is_empty(), "{} is empty", path.display());
    bytes
}

/// Checks the files `run` writes: summary.json, scans.jsonl, estimates.csv and the plots.
fn check_run_outputs(out: &Path, tracker: &str, scans: usize) -> Value {
    let summary = read_json(&out.join("summary.json"));
    for key in [
        "scans",
        "tracker",
        "mean_gospa",
        "final_expected_cardinality",
        "true_final_cardinality",
        "births_total",
        "births_confirmed",
        "mean_ms_per_scan",
        "max_ms_per_scan",
        "peak_hypotheses",
    ] {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}: {summary}");
    }
    assert_eq!(summary["tracker"], json!(tracker));
    assert_eq!(summary["scans"], json!(scans));
    assert!(summary["mean_gospa"].as_f64().is_some_and(f64::is_finite), "{summary}");
    assert!(summary["final_expected_cardinality"].as_f64().is_some_and(f64::is_finite), "{summary}");
    assert!(summary["peak_hypotheses"].as_u64().is_some_and(|h| h > 0), "{summary}");
    assert_eq!(summary["rejected_scans"], json!([]));

    let jsonl = std::fs::read_to_string(out.join("scans.jsonl")).expect("scans.jsonl");
    let lines: Vec<&str> = jsonl.lines().collect();
    assert_eq!(lines.len(), scans, "one line per scan");
    for (k, line) in lines.iter().enumerate() {
        let value: Value = serde_json::from_str(line).unwrap_or_else(|e| panic!("scans.jsonl line {k}: {e}"));
        assert_eq!(value["scan"], json!(k));
        assert!(value["hypotheses"].is_array() && value["tracks"].is_array(), "{value}");
    }

    let csv = std::fs::read_to_string(out.join("estimates.csv")).expect("estimates.csv");
    let mut rows = csv.lines();
    assert_eq!(rows.next(), Some("scan,time,label,x,y,vx,vy,existence,within_error_bound"));
    let rows: Vec<&str> = rows.collect();
    assert!(!rows.is_empty(), "estimates.csv has no rows");
    for row in rows {
        assert_eq!(row.split(',').count(), 9, "row {row}");
    }

    for plot in ["truth_vs_map", "hypothesis_weights", "expected_cardinality"] {
        let png = assert_nonempty_file(&out.join(format!("{plot}.png")));
        assert!(png.starts_with(b"\x89PNG"), "{plot}.png is not a PNG");
        let svg = String::from_utf8(assert_nonempty_file(&out.join(format!("{plot}.svg")))).expect("svg is text");
        assert!(svg.contains("<svg"), "{plot}.svg is not an SVG");
    }
    summary
}

#[test]
fn help_works_for_every_command() {
    let output = host_sim(&["--help"]);
    assert_success(&output);
    let help = stdout(&output);
    assert!(help.contains("Usage"), "{help}");
    // Every subcommand listed under "Commands:" (clap's own `help` aside).
    let commands: Vec<String> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next().map(str::to_string))
        .filter(|c| c != "help")
        .collect();
    for expected in ["generate", "run", "compare"] {
        assert!(commands.iter().any(|c| c == expected), "{expected} missing from {commands:?}");
    }
    for command in &commands {
        let output = host_sim(&[command.as_str(), "--help"]);
        assert_success(&output);
        assert!(stdout(&output).contains("Usage: host-sim"), "{command}: {}", describe(&output));
    }
    let output = host_sim(&["--version"]);
    assert_success(&output);
    assert!(stdout(&output).starts_with("host-sim "), "{}", describe(&output));
}

#[test]
fn bad_arguments_exit_2() {
    let scale = ["experiment", "catalogue-scale", "--out", "/nonexistent-rfisst/scale"];
    let with = |extra: &'static [&'static str]| -> Vec<&'static str> { scale.iter().chain(extra).copied().collect() };
    let scale_cases = [
        with(&[]),
        with(&["--objects", "0", "--hours", "1"]),
        with(&["--objects", "10", "--hours", "-1"]),
        with(&["--objects", "10", "--hours", "1", "--threads", "0"]),
        with(&["--objects", "10", "--hours", "1", "--runs", "2"]),
        vec!["experiment", "fifty", "--out", "/nonexistent-rfisst/fifty", "--objects", "10"],
        with(&["--objects", "10", "--hours", "1", "--weight-floor", "256"]),
        with(&["--objects", "10", "--hours", "1", "--weight-floor", "all"]),
        vec!["experiment", "fifty", "--out", "/nonexistent-rfisst/fifty", "--weight-floor", "9"],
        with(&["--objects", "10", "--hours", "1", "--lost-after", "0"]),
        with(&["--objects", "10", "--hours", "1", "--lost-after", "never"]),
        vec!["experiment", "fifty", "--out", "/nonexistent-rfisst/fifty", "--lost-after", "8"],
    ];
    let plain = [&[][..], &["frobnicate"], &["generate", "linear-small"], &["run", FIXTURE], &["run", "--bogus"]];
    for args in plain.into_iter().chain(scale_cases.iter().map(Vec::as_slice)) {
        let output = host_sim(args);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {}", describe(&output));
        assert!(!stderr(&output).contains("panicked"), "{args:?}: {}", describe(&output));
    }
}

#[test]
fn generate_writes_every_preset() {
    let dir = TempDir::new("generate");
    for preset in ["fifty-birth-death", "fifteen-compare", "debris-crossing", "linear-small"] {
        let path = dir.join(&format!("{preset}.json"));
        let output = host_sim(&["generate".as_ref(), preset.as_ref(), "--out".as_ref(), path.as_os_str()]);
        assert_success(&output);
        assert!(stderr(&output).starts_with("wrote "), "{preset}: {}", describe(&output));
        let value = read_json(&path);
        assert_eq!(value["format"], json!("rfisst-scenario/1"), "{preset}");
        assert_eq!(value["name"], json!(preset));
        let scans = value["scans"].as_array().expect("scans");
        assert!(!scans.is_empty(), "{preset}: no scans");
        assert_eq!(value["truth"]["scans"].as_array().map(Vec::len), Some(scans.len()), "{preset}");
        // The file passes the loader's checks too.
        let scenario = Scenario::load(&path).unwrap_or_else(|e| panic!("{preset}: {e}"));
        assert_eq!(scenario.scans.len(), scans.len());
        std::fs::remove_file(&path).expect("remove");
    }
}

#[test]
fn generate_is_deterministic_per_seed() {
    let dir = TempDir::new("seed");
    let run = |name: &str, seed: &str| {
        let path = dir.join(name);
        let output = host_sim(&[
            "generate".as_ref(),
            "debris-crossing".as_ref(),
            "--seed".as_ref(),
            seed.as_ref(),
            "--out".as_ref(),
            path.as_os_str(),
        ]);
        assert_success(&output);
        std::fs::read(path).expect("read")
    };
    assert_eq!(run("a.json", "11"), run("b.json", "11"));
    assert_ne!(run("a.json", "11"), run("c.json", "12"));
}

#[test]
fn generate_unknown_preset_exits_2() {
    let dir = TempDir::new("unknown-preset");
    let path = dir.join("x.json");
    let output = host_sim(&["generate".as_ref(), "sixty-objects".as_ref(), "--out".as_ref(), path.as_os_str()]);
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    // clap's usage message: the bad value and every preset.
    let err = stderr(&output);
    assert!(err.starts_with("error: invalid value 'sixty-objects'"), "{err}");
    for preset in ["fifty-birth-death", "fifteen-compare", "debris-crossing", "linear-small"] {
        assert!(err.contains(preset), "lists {preset}: {err}");
    }
    assert!(!path.exists());
}

#[test]
fn help_lists_every_preset_experiment_tracker_and_profile() {
    for (command, values) in [
        (
            "generate",
            &[
                "fifty-birth-death",
                "fifteen-compare",
                "debris-crossing",
                "linear-small",
                "radar-leo",
                "optical-geo",
                "optical-leo",
                "optical-heo",
                "tiny-3d",
            ][..],
        ),
        ("experiment", &["fifty", "fifteen", "scaling", "debris", "ablation", "catalogue-scale", "all"]),
        ("run", &["reference", "homht", "rfisst", "embedded", "host"]),
        ("compare", &["reference", "homht", "rfisst", "embedded", "host"]),
    ] {
        let output = host_sim(&[command, "--help"]);
        assert_success(&output);
        let help = stdout(&output);
        for value in values {
            assert!(help.contains(value), "{command} --help misses {value}:\n{help}");
        }
    }
}

#[test]
fn run_homht_on_linear_small_writes_every_output() {
    let dir = TempDir::new("run-homht");
    let file = linear_small(&dir, None);
    let out = dir.join("out");
    let output = host_sim(&[
        "run".as_ref(),
        file.as_os_str(),
        "--tracker".as_ref(),
        "homht".as_ref(),
        "--json".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_success(&output);
    let summary = check_run_outputs(&out, "homht", 6);
    // linear-small: one birth, one death, 3 objects at the end.
    assert_eq!(summary["births_total"], json!(1));
    assert_eq!(summary["true_final_cardinality"], json!(3));
    // With --json, stdout is the summary.
    let printed: Value = serde_json::from_str(&stdout(&output)).expect("stdout is JSON");
    assert_eq!(printed, summary);
}

/// Without --json, `run` prints a short summary a person reads: the headline figures and where the files
/// are, a few lines and no JSON.
#[test]
fn run_prints_a_short_human_summary() {
    let dir = TempDir::new("run-human");
    let file = linear_small(&dir, Some(4));
    let out = dir.join("out");
    let output = host_sim(&["run".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    let text = stdout(&output);
    assert!(text.contains("mean GOSPA") && text.contains(&out.display().to_string()), "{text}");
    assert!(!text.contains('{') && text.lines().count() <= 8, "{text}");
}

#[test]
fn run_reference_quiet_on_short_linear_small_writes_every_output() {
    let dir = TempDir::new("run-reference");
    let file = linear_small(&dir, Some(4));
    let out = dir.join("out");
    let output = host_sim(&[
        "run".as_ref(),
        file.as_os_str(),
        "--tracker".as_ref(),
        "reference".as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_success(&output);
    let summary = check_run_outputs(&out, "reference", 4);
    assert_eq!(summary["profile"], json!("unbounded"));
}

#[test]
fn compare_on_short_linear_small_writes_compare_json() {
    let dir = TempDir::new("compare");
    let file = linear_small(&dir, Some(4));
    let out = dir.join("out");
    let output =
        host_sim(&["compare".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    let compare = read_json(&out.join("compare.json"));
    for key in ["mean_captured_mass", "min_captured_mass", "mean_weight_l1", "map_agreement"] {
        let value = compare[key].as_f64().unwrap_or_else(|| panic!("compare.json lacks {key}: {compare}"));
        assert!(value.is_finite() && value >= 0.0, "{key} = {value}");
    }
    let captured = compare["mean_captured_mass"].as_f64().unwrap_or(0.0);
    assert!(captured > 0.0 && captured <= 1.0 + 1e-9, "mean_captured_mass = {captured}");
    for tracker in ["bounded", "reference"] {
        for key in ["mean_gospa", "mean_ms_per_scan", "max_ms_per_scan"] {
            assert!(compare[tracker][key].as_f64().is_some_and(f64::is_finite), "{tracker}.{key}: {compare}");
        }
    }
    assert_eq!(compare["per_scan"].as_array().map(Vec::len), Some(4));
}

#[test]
fn hand_written_fixture_loads_and_runs() {
    let scenario = Scenario::load(Path::new(FIXTURE)).expect("the fixture validates");
    assert_eq!(scenario.scans.len(), 3);
    assert_eq!(scenario.truth.as_ref().map(|t| t.objects.len()), Some(2));
    let dir = TempDir::new("fixture");
    for tracker in ["homht", "rfisst", "reference"] {
        let out = dir.join(tracker);
        let output = host_sim(&[
            "run".as_ref(),
            FIXTURE.as_ref(),
            "--tracker".as_ref(),
            tracker.as_ref(),
            "--quiet".as_ref(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        assert_success(&output);
        let summary = check_run_outputs(&out, tracker, 3);
        assert_eq!(summary["true_final_cardinality"], json!(2));
        let cardinality = summary["final_expected_cardinality"].as_f64().unwrap_or(f64::NAN);
        assert!((cardinality - 2.0).abs() < 0.1, "{tracker}: expected cardinality {cardinality}");
    }
}

#[test]
fn documented_example_is_the_fixture() {
    let doc = std::fs::read_to_string(DOC).expect("docs/scenario-format.md");
    let start = doc.find("```json\n").expect("a json block") + "```json\n".len();
    let end = start + doc[start..].find("```").expect("end of the json block");
    let example: Value = serde_json::from_str(&doc[start..end]).expect("the documented example is JSON");
    assert_eq!(example, fixture());
}

#[test]
fn refused_scans_are_reported_and_the_run_goes_on() {
    let dir = TempDir::new("rejected");
    let mut scenario = fixture();
    // Outside the 100 x 100 rectangle: valid JSON, but the tracker refuses scan 1 (issue 29: reported,
    // exit 0, the next scan tracked).
    scenario["scans"][1]["measurements"][0] = json!([60.0, 0.0]);
    let file = dir.join("outside.json");
    write_json(&file, &scenario);
    for tracker in ["homht", "reference"] {
        let out = dir.join(tracker);
        let output = host_sim(&[
            "run".as_ref(),
            file.as_os_str(),
            "--tracker".as_ref(),
            tracker.as_ref(),
            "--quiet".as_ref(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        assert_eq!(output.status.code(), Some(0), "{tracker}: {}", describe(&output));
        let err = stderr(&output);
        assert!(err.contains("scan 1") && err.contains("outside the field of view"), "{err}");
        // One line for the refused scan (the truth-free judge may add its own `warning: sensor` line).
        assert_eq!(err.lines().filter(|l| !l.starts_with("warning: sensor ")).count(), 1, "{err}");
        let summary = read_json(&out.join("summary.json"));
        assert_eq!(summary["rejected_scans"].as_array().map(Vec::len), Some(1), "{summary}");
        assert_eq!(summary["rejected_scans"][0]["scan"], json!(1));
        assert_eq!(summary["refused_scans"]["count"], json!(1), "{summary}");
        let refused = &summary["refused_scans"]["reasons"][0];
        assert_eq!((&refused["scan"], &refused["time"], &refused["sensor"]), (&json!(1), &json!(2.0), &Value::Null));
        assert!(refused["reason"].as_str().is_some_and(|r| r.contains("outside the field of view")), "{summary}");
        // The scan after it is tracked: both objects held.
        assert_eq!(summary["final_map_cardinality"], json!(2), "{summary}");
    }
}

/// One malformed input.
struct Case {
    name: &'static str,
    text: String,
    /// Extra arguments of `run`.
    args: &'static [&'static str],
    /// A distinctive part of the error line.
    expect: &'static str,
}

fn mutated(name: &'static str, expect: &'static str, mutate: impl FnOnce(&mut Value)) -> Case {
    let mut value = fixture();
    mutate(&mut value);
    Case { name, text: serde_json::to_string_pretty(&value).expect("serialise"), args: &[], expect }
}

fn raw(name: &'static str, expect: &'static str, text: impl Into<String>) -> Case {
    Case { name, text: text.into(), args: &[], expect }
}

fn array(value: &mut Value) -> &mut Vec<Value> {
    value.as_array_mut().expect("an array")
}

fn object(value: &mut Value) -> &mut serde_json::Map<String, Value> {
    value.as_object_mut().expect("an object")
}

fn malformed_cases() -> Vec<Case> {
    let text = std::fs::read_to_string(FIXTURE).expect("fixture");
    let first_measurement = "[1.1, 0.2]";
    assert!(text.contains(first_measurement));
    let mut cases = vec![
        raw("truncated JSON", "EOF while parsing", &text[..text.len() / 2]),
        raw("empty file", "invalid scenario JSON: EOF while parsing a value", ""),
        raw("not an object (array)", "invalid type", "[1, 2, 3]"),
        raw("not an object (number)", "invalid type: integer `42`", "42"),
        raw("not an object (string)", "invalid type: string", "\"rfisst-scenario/1\""),
        raw(
            "number too large to be finite",
            "scans[0].measurements[0][0]: number out of range",
            text.replace(first_measurement, "[1e999, 0.2]"),
        ),
        raw(
            "NaN is not JSON",
            "scans[0].measurements[0][0]: expected value",
            text.replace(first_measurement, "[NaN, 0.2]"),
        ),
        raw(
            "Infinity is not JSON",
            "scans[0].measurements[0][0]: expected value",
            text.replace(first_measurement, "[Infinity, 0.2]"),
        ),
        mutated("missing field scans", "missing field `scans`", |v| {
            object(v).remove("scans");
        }),
        mutated("measured births with first-order events", "birth.measured: needs birth.events", |v| {
            v["birth"]["measured"] =
                serde_json::json!({"expected_births": 0.5, "max_probability": 0.2, "lifetime": 5.0});
        }),
        mutated("measured births with max_probability 1", "birth.measured: measured births: max_probability", |v| {
            v["birth"]["events"] = "independent".into();
            v["birth"]["measured"] =
                serde_json::json!({"expected_births": 0.5, "max_probability": 1.0, "lifetime": 5.0});
        }),
        mutated("missing nested field", "sensor: missing field `clutter_rate`", |v| {
            object(&mut v["sensor"]).remove("clutter_rate");
        }),
        mutated("missing variant tag", "motion: missing field `type`", |v| {
            object(&mut v["motion"]).remove("type");
        }),
        mutated("unknown top-level field (typo)", "unknown field `death_probabilty`", |v| {
            let beta = object(v).remove("death_probability").expect("beta");
            object(v).insert("death_probabilty".into(), beta);
        }),
        mutated("unknown nested field (typo)", "sensor.clutter_rat: unknown field `clutter_rat`", |v| {
            let rate = object(&mut v["sensor"]).remove("clutter_rate").expect("rate");
            object(&mut v["sensor"]).insert("clutter_rat".into(), rate);
        }),
        mutated("unknown variant", "sensor.field_of_view.type: unknown variant `circle`", |v| {
            v["sensor"]["field_of_view"]["type"] = json!("circle");
        }),
        mutated("unknown enum value", "tracker.store_overflow: unknown variant `drop`", |v| {
            v["tracker"]["store_overflow"] = json!("drop");
        }),
        mutated("string where a number is expected", "sensor.clutter_rate: invalid type: string", |v| {
            v["sensor"]["clutter_rate"] = json!("1.0");
        }),
        mutated("fraction in an integer field", "tracker.seed: must be an integer in 0..=18446744073709551615", |v| {
            v["tracker"]["seed"] = json!(7.5);
        }),
        mutated("negative label", "prior.hypotheses[0].objects[1].label: invalid value: integer `-1`", |v| {
            v["prior"]["hypotheses"][0]["objects"][1]["label"] = json!(-1);
        }),
        mutated("mean with 3 entries", "prior.hypotheses[0].objects[0].mean: invalid length 3", |v| {
            array(&mut v["prior"]["hypotheses"][0]["objects"][0]["mean"]).pop();
        }),
        mutated("mean with 5 entries", "prior.hypotheses[0].objects[0].mean: trailing characters", |v| {
            array(&mut v["prior"]["hypotheses"][0]["objects"][0]["mean"]).push(json!(5.0));
        }),
        mutated("rectangle corner with 1 entry", "sensor.field_of_view: invalid length 1", |v| {
            v["sensor"]["field_of_view"]["min"] = json!([-50.0]);
        }),
        mutated("measurement with 3 entries", "scans[1].measurements[0]: trailing characters", |v| {
            array(&mut v["scans"][1]["measurements"][0]).push(json!(0.0));
        }),
        mutated("3 x 3 noise covariance", "measurement: invalid length 3", |v| {
            v["measurement"]["noise_covariance"] = json!([[0.25, 0.0, 0.0], [0.0, 0.25, 0.0], [0.0, 0.0, 0.25]]);
        }),
        mutated("truth state with 2 entries", "truth.scans[2].objects[1].state: invalid length 2", |v| {
            v["truth"]["scans"][2]["objects"][1]["state"] = json!([10.0, 7.0]);
        }),
        mutated("negative clutter_rate", "sensor.clutter_rate: -1 is not finite and > 0", |v| {
            v["sensor"]["clutter_rate"] = json!(-1.0);
        }),
        mutated("zero clutter_rate", "sensor.clutter_rate: 0 is not finite and > 0", |v| {
            v["sensor"]["clutter_rate"] = json!(0.0);
        }),
        mutated("detection_probability 0", "sensor.detection_probability: 0 is not in (0, 1]", |v| {
            v["sensor"]["detection_probability"] = json!(0.0);
        }),
        mutated("detection_probability 1.5", "sensor.detection_probability: 1.5 is not in (0, 1]", |v| {
            v["sensor"]["detection_probability"] = json!(1.5);
        }),
        mutated("birth probability above 1", "birth.probability: 1.5 is not in [0, 1]", |v| {
            v["birth"]["probability"] = json!(1.5);
        }),
        mutated("negative death probability", "death_probability: -0.1 is not in [0, 1]", |v| {
            v["death_probability"] = json!(-0.1);
        }),
        mutated("zero gate", "tracker.gate: 0 is not finite and > 0", |v| {
            v["tracker"]["gate"] = json!(0.0);
        }),
        mutated("zero child budget", "tracker.max_children_per_scan: must be > 0", |v| {
            v["tracker"]["max_children_per_scan"] = json!(0);
        }),
        mutated("empty rectangle", "sensor.field_of_view: max must exceed min on both axes", |v| {
            v["sensor"]["field_of_view"]["max"] = json!([50.0, -60.0]);
        }),
        mutated(
            "sector wider than 360 degrees",
            "sensor.field_of_view.field_of_view_deg: 400 is not in (0, 360]",
            |v| {
                v["sensor"]["field_of_view"] = json!({
                    "type": "sector", "origin": [0.0, 0.0], "look_direction_deg": 0.0,
                    "field_of_view_deg": 400.0, "max_range": 100.0
                });
            },
        ),
        mutated("zero RK4 sub-steps", "motion.max_substeps: must be > 0", |v| {
            v["motion"] = json!({
                "type": "two-body", "mu": 398600.4418, "acceleration_noise": 1e-13,
                "max_step": 20.0, "max_substeps": 0
            });
        }),
        mutated("non-symmetric covariance", "measurement.noise_covariance: is not symmetric", |v| {
            v["measurement"]["noise_covariance"] = json!([[0.25, 0.1], [0.0, 0.25]]);
        }),
        mutated(
            "non-positive-definite covariance (negative variance)",
            "prior.hypotheses[0].objects[1].covariance: is not positive definite",
            |v| {
                v["prior"]["hypotheses"][0]["objects"][1]["covariance"][0][0] = json!(-1.0);
            },
        ),
        mutated(
            "non-positive-definite covariance (indefinite)",
            "birth.cells[0].covariance: is not positive definite",
            |v| {
                v["birth"]["cells"][0]["covariance"][0][1] = json!(30.0);
                v["birth"]["cells"][0]["covariance"][1][0] = json!(30.0);
            },
        ),
        mutated("scan times out of order", "scans[2].time: 1.5 is not after the previous time 2", |v| {
            v["scans"][2]["time"] = json!(1.5);
        }),
        mutated("scan time equal to the prior time", "scans[0].time: 0 is not after the previous time 0", |v| {
            v["scans"][0]["time"] = json!(0.0);
        }),
        mutated("truth scans count mismatch", "truth.scans: has 2 entries for 3 scans", |v| {
            array(&mut v["truth"]["scans"]).pop();
        }),
        mutated("origins count mismatch", "truth.scans[0].origins: has 2 entries for 3 measurements", |v| {
            array(&mut v["truth"]["scans"][0]["origins"]).pop();
        }),
        mutated("origin refers to an unknown object", "truth.scans[0].origins[0]: object 9 does not exist", |v| {
            v["truth"]["scans"][0]["origins"][0] = json!(9);
        }),
        mutated("origin refers to an absent object", "truth.scans[0].origins[2]: object 1 does not exist", |v| {
            array(&mut v["truth"]["scans"][0]["objects"]).pop();
        }),
        mutated("truth state of an unknown object", "truth.scans[1].objects[1].id: unknown object id 5", |v| {
            v["truth"]["scans"][1]["objects"][1]["id"] = json!(5);
        }),
        mutated("duplicate truth object id", "truth.objects[1].id: id 0 appears twice", |v| {
            v["truth"]["objects"][1]["id"] = json!(0);
        }),
        mutated("duplicate prior label", "prior.hypotheses[0].objects[1].label: label 0 appears twice", |v| {
            v["prior"]["hypotheses"][0]["objects"][1]["label"] = json!(0);
        }),
        mutated("prior weights all zero", "prior.hypotheses: weights sum to zero", |v| {
            v["prior"]["hypotheses"][0]["weight"] = json!(0.0);
        }),
        mutated("negative prior weight", "prior.hypotheses[0].weight: -1 is not finite and >= 0", |v| {
            v["prior"]["hypotheses"][0]["weight"] = json!(-1.0);
        }),
        mutated("no prior hypothesis", "prior.hypotheses: needs at least one hypothesis", |v| {
            v["prior"]["hypotheses"] = json!([]);
        }),
        mutated("wrong format tag", "format: expected \"rfisst-scenario/1\", found \"rfisst-scenario/2\"", |v| {
            v["format"] = json!("rfisst-scenario/2");
        }),
        mutated("partial evaluation section", "evaluation: missing field `gospa_order`", |v| {
            object(&mut v["evaluation"]).remove("gospa_order");
        }),
        mutated("GOSPA order below 1", "evaluation.gospa_order: 0.5 is not in [1, 100]", |v| {
            v["evaluation"]["gospa_order"] = json!(0.5);
        }),
        // Reported when the tracker is built: 1 × 0.01 + 64 × 0.02 ≥ 1 with the embedded N = 64.
        mutated("M_b alpha + N beta >= 1 (embedded)", "M_b alpha + N beta must be < 1", |v| {
            v["death_probability"] = json!(0.02);
        }),
        mutated(
            "more birth cells than the embedded capacity",
            "birth.cells: 9 cells exceed this tracker's capacity of 8",
            |v| {
                let cell = v["birth"]["cells"][0].clone();
                v["birth"]["cells"] = Value::Array(vec![cell; 9]);
            },
        ),
        mutated("more prior hypotheses than H", "prior has more hypotheses than the capacity H", |v| {
            let hypothesis = v["prior"]["hypotheses"][0].clone();
            v["prior"]["hypotheses"] = Value::Array(vec![hypothesis; 33]);
        }),
    ];
    // Metric parameters that would make GOSPA overflow (written as null before).
    cases.push(mutated("GOSPA order 400", "evaluation.gospa_order: 400 is not in [1, 100]", |v| {
        v["evaluation"] =
            json!({"error_bound": 10.0, "gospa_cutoff": 50.0, "gospa_order": 400.0, "confirmation_existence": 0.9});
    }));
    cases.push(mutated("GOSPA cut-off to the order overflows", "evaluation.gospa_cutoff: 1e200^2", |v| {
        v["evaluation"] =
            json!({"error_bound": 10.0, "gospa_cutoff": 1e200, "gospa_order": 2.0, "confirmation_existence": 0.9});
    }));
    cases.push(mutated("error bound 1e308", "evaluation.error_bound: 1e308 is not in", |v| {
        v["evaluation"] =
            json!({"error_bound": 1e308, "gospa_cutoff": 50.0, "gospa_order": 2.0, "confirmation_existence": 0.9});
    }));
    cases.push(mutated(
        "prior weights whose sum overflows",
        "prior.hypotheses: the sum of the weights overflows",
        |v| {
            let first = v["prior"]["hypotheses"][0].clone();
            v["prior"]["hypotheses"] = json!([first.clone(), first]);
            v["prior"]["hypotheses"][0]["weight"] = json!(1e308);
            v["prior"]["hypotheses"][1]["weight"] = json!(1e308);
        },
    ));
    cases.push(mutated("R = 1e308", "measurement.noise_covariance: entry 1e308 is beyond ±1e150", |v| {
        v["measurement"]["noise_covariance"] = json!([[1e308, 0.0], [0.0, 1e308]]);
    }));
    cases.push(mutated("prior covariance 1e200", "prior.hypotheses[0].objects[0].covariance: entry", |v| {
        v["prior"]["hypotheses"][0]["objects"][0]["covariance"][0][0] = json!(1e200);
    }));
    cases.push(mutated(
        "prior label u32::MAX",
        "prior.hypotheses[0].objects[1].label: 4294967295 is above 2147483647",
        |v| {
            v["prior"]["hypotheses"][0]["objects"][1]["label"] = json!(4294967295u32);
        },
    ));
    // 0.01 + 64 × 0.008 < 1 but 0.01 + 128 × 0.008 ≥ 1: only the host profile's N = 128 rejects it.
    let mut host = mutated("M_b alpha + N beta >= 1 (host)", "M_b alpha + N beta must be < 1", |v| {
        v["death_probability"] = json!(0.008);
    });
    host.args = &["--profile", "host"];
    cases.push(host);
    cases
}

fn check_malformed(output: &Output, expect: &str) -> Result<(), String> {
    let err = stderr(output);
    if output.status.code() != Some(2) {
        return Err(format!("exit code {:?}, expected 2", output.status.code()));
    }
    if err.contains("panicked") {
        return Err("panicked".into());
    }
    if err.lines().count() != 1 || !err.ends_with('\n') {
        return Err("stderr is not exactly one line".into());
    }
    if !err.starts_with("error: ") {
        return Err("stderr does not start with \"error: \"".into());
    }
    if !err.contains(expect) {
        return Err(format!("stderr does not contain {expect:?}"));
    }
    Ok(())
}

#[test]
fn malformed_files_exit_2_with_one_error_line() {
    let dir = TempDir::new("malformed");
    let out = dir.join("out");
    let mut failures = vec![];
    let cases = malformed_cases();
    for (i, case) in cases.iter().enumerate() {
        let file = dir.join(&format!("case-{i}.json"));
        std::fs::write(&file, &case.text).expect("write case");
        let mut args: Vec<&std::ffi::OsStr> =
            vec!["run".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()];
        args.extend(case.args.iter().map(|a| std::ffi::OsStr::new(*a)));
        let output = host_sim(&args);
        if let Err(why) = check_malformed(&output, case.expect) {
            failures.push(format!("{}: {why}\n{}", case.name, describe(&output)));
        }
    }
    assert!(failures.is_empty(), "{} of {} cases failed:\n{}", failures.len(), cases.len(), failures.join("\n"));
}

#[test]
fn missing_file_exits_2_for_run_and_compare() {
    let dir = TempDir::new("missing");
    let file = dir.join("does-not-exist.json");
    for command in ["run", "compare"] {
        let output = host_sim(&[
            command.as_ref(),
            file.as_os_str(),
            "--quiet".as_ref(),
            "--out".as_ref(),
            dir.join("out").as_os_str(),
        ]);
        assert!(check_malformed(&output, "does-not-exist.json").is_ok(), "{command}: {}", describe(&output));
    }
}

#[test]
fn compare_rejects_a_malformed_file_with_exit_2() {
    let dir = TempDir::new("compare-malformed");
    let mut scenario = fixture();
    scenario["scans"][0]["time"] = json!(0.0);
    let file = dir.join("bad.json");
    write_json(&file, &scenario);
    let output = host_sim(&[
        "compare".as_ref(),
        file.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        dir.join("out").as_os_str(),
    ]);
    if let Err(why) = check_malformed(&output, "scans[0].time") {
        panic!("{why}\n{}", describe(&output));
    }
}

#[test]
fn trailing_characters_exit_2() {
    let dir = TempDir::new("trailing");
    let file = dir.join("trailing.json");
    let text = std::fs::read_to_string(FIXTURE).expect("fixture") + "\n{\"format\": 1}\n";
    std::fs::write(&file, text).expect("write");
    let output = host_sim(&[
        "run".as_ref(),
        file.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        dir.join("out").as_os_str(),
    ]);
    if let Err(why) = check_malformed(&output, "trailing characters") {
        panic!("{why}\n{}", describe(&output));
    }
}

#[test]
fn reference_rejects_a_parent_whose_events_are_impossible() {
    let dir = TempDir::new("reference-beta");
    let mut scenario = fixture();
    // 1 × 0.01 + 2 × 0.6 > 1 for the two objects in view: every scan is rejected, naming the rule.
    scenario["death_probability"] = json!(0.6);
    let file = dir.join("beta.json");
    write_json(&file, &scenario);
    let out = dir.join("out");
    let output = run_reference(&file, &out, &[]);
    assert_eq!(output.status.code(), Some(3), "{}", describe(&output));
    let summary = read_json(&out.join("summary.json"));
    let rejected = summary["rejected_scans"].as_array().expect("rejected_scans");
    assert_eq!(rejected.len(), 3, "{summary}");
    assert!(rejected[0]["error"].as_str().is_some_and(|e| e.contains("M_b alpha")), "{summary}");
    // M_b α ≥ 1 leaves no parent a "no event" probability: rejected when the tracker is built.
    scenario["death_probability"] = json!(0.0);
    scenario["birth"]["probability"] = json!(1.0);
    write_json(&file, &scenario);
    let output = run_reference(&file, &out, &[]);
    if let Err(why) = check_malformed(&output, "M_b alpha") {
        panic!("{why}\n{}", describe(&output));
    }
}

#[test]
fn reference_has_no_object_capacity() {
    // β = 0.03: M_b α + N β = 0.01 + 64 × 0.03 ≥ 1 for the embedded profile's N, but the reference uses
    // each parent's objects in view (here 2): 0.01 + 2 × 0.03 < 1.
    let dir = TempDir::new("reference-no-n");
    let mut scenario = fixture();
    scenario["death_probability"] = json!(0.03);
    let file = dir.join("beta.json");
    write_json(&file, &scenario);
    let output = run_reference(&file, &dir.join("reference"), &[]);
    assert_success(&output);
    let output = host_sim(&[
        "run".as_ref(),
        file.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        dir.join("homht").as_os_str(),
    ]);
    if let Err(why) = check_malformed(&output, "M_b alpha + N beta") {
        panic!("{why}\n{}", describe(&output));
    }
}

/// `host-sim run FILE --tracker reference --quiet --out OUT` with `extra` arguments.
fn run_reference(file: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args: Vec<&std::ffi::OsStr> = vec!["run".as_ref(), file.as_os_str(), "--tracker".as_ref()];
    args.extend(["reference", "--quiet", "--out"].map(std::ffi::OsStr::new));
    args.push(out.as_os_str());
    args.extend(extra.iter().map(std::ffi::OsStr::new));
    host_sim(&args)
}

/// Three constant-velocity objects in three scans of five measurements (p_D 0.7, clutter 1.8, one birth
/// cell, β 0.012, no gate): hundreds of thousands of children at the second scan, ~10⁸ at the third.
fn three_objects_three_scans() -> Value {
    let covariance =
        |p: f64, v: f64| json!([[p, 0.0, 0.0, 0.0], [0.0, p, 0.0, 0.0], [0.0, 0.0, v, 0.0], [0.0, 0.0, 0.0, v]]);
    let starts = [[0.0, 0.0, 1.0, 0.0], [20.0, 5.0, 0.0, -1.0], [-15.0, -10.0, 0.5, 0.5]];
    let objects: Vec<Value> = starts
        .iter()
        .enumerate()
        .map(|(label, mean)| json!({"label": label, "mean": mean, "covariance": covariance(1.0, 0.25)}))
        .collect();
    let scans: Vec<Value> = (1..=3)
        .map(|k| {
            let t = f64::from(k);
            let zs: Vec<[f64; 2]> = vec![
                [t + 0.3, -0.2],
                [20.4, 5.0 - t - 0.1],
                [-15.0 + 0.5 * t, -10.0 + 0.5 * t],
                [-31.0 + 7.0 * t, 12.5 - 5.0 * t],
                [40.0 - 9.0 * t, -44.0 + 11.0 * t],
            ];
            json!({"time": t, "measurements": zs})
        })
        .collect();
    json!({
        "format": "rfisst-scenario/1",
        "name": "three-objects-three-scans",
        "motion": {"type": "constant-velocity", "acceleration_noise": 0.01},
        "measurement": {"type": "position", "noise_covariance": [[0.25, 0.0], [0.0, 0.25]]},
        "sensor": {
            "detection_probability": 0.7,
            "clutter_rate": 1.8,
            "field_of_view": {"type": "rectangle", "min": [-50.0, -50.0], "max": [50.0, 50.0]}
        },
        "birth": {"probability": 0.01, "cells": [{"mean": [0.0, 0.0, 0.0, 0.0], "covariance": covariance(400.0, 4.0)}]},
        "death_probability": 0.012,
        "tracker": {"gate": null, "max_children_per_scan": 100000, "seed": 1},
        "prior": {"time": 0.0, "hypotheses": [{"weight": 1.0, "objects": objects}]},
        "scans": scans
    })
}

#[test]
fn reference_over_its_memory_budget_reports_the_scans_and_finishes() {
    const BUDGET_MIB: u64 = 16;
    let dir = TempDir::new("reference-budget");
    let file = dir.join("three.json");
    write_json(&file, &three_objects_three_scans());
    let out = dir.join("out");
    let output = run_reference(&file, &out, &["--reference-budget-mib", &BUDGET_MIB.to_string()]);
    assert_success(&output);
    let summary = read_json(&out.join("summary.json"));
    assert_eq!(summary["rejected_scans"], json!([]), "{summary}");
    // The second and third scans (0-based 1 and 2) need far more than 16 MiB.
    assert_eq!(summary["reference_budget_reached_scans"], json!([1, 2]), "{summary}");
    // Peak resident memory (VmHWM, Linux only): within 1.25 × the budget plus the baseline of the same
    // binary on a scenario far below the budget (code, the parsed scenario, the plots).
    if let Some(peak) = summary["peak_resident_kib"].as_u64() {
        let baseline_out = dir.join("baseline");
        assert_success(&run_reference(Path::new(FIXTURE), &baseline_out, &[]));
        let baseline = read_json(&baseline_out.join("summary.json"))["peak_resident_kib"].as_u64().expect("VmHWM");
        let limit = BUDGET_MIB * 1024 * 5 / 4 + baseline;
        assert!(peak <= limit, "peak {peak} KiB > 1.25 × {BUDGET_MIB} MiB + baseline {baseline} KiB");
    }
    // compare runs the reference with the same budget, and finishes too.
    let output = host_sim(&[
        "compare".as_ref(),
        file.as_os_str(),
        "--quiet".as_ref(),
        "--reference-budget-mib".as_ref(),
        BUDGET_MIB.to_string().as_ref(),
        "--out".as_ref(),
        dir.join("compare").as_os_str(),
    ]);
    assert!(matches!(output.status.code(), Some(0 | 3)), "{}", describe(&output));
    let compare = read_json(&dir.join("compare").join("compare.json"));
    assert_eq!(compare["reference"]["budget_reached_scans"], json!([1, 2]), "{compare}");
}

#[test]
fn a_key_with_an_escaped_line_break_gives_a_one_line_error() {
    let dir = TempDir::new("escaped-key");
    let file = dir.join("key.json");
    std::fs::write(&file, r#"{"format":"rfisst-scenario/1","sensor":{"a\nb":1}}"#).expect("write");
    let output = host_sim(&["run".as_ref(), file.as_os_str(), "--out".as_ref(), dir.join("out").as_os_str()]);
    if let Err(why) = check_malformed(&output, "sensor.a\\nb") {
        panic!("{why}\n{}", describe(&output));
    }
}

#[test]
fn a_value_with_control_characters_gives_a_one_line_error() {
    // Found by fuzzing: the format check printed the value with its carriage return.
    let dir = TempDir::new("escaped-value");
    let fixture = std::fs::read_to_string(FIXTURE).expect("fixture");
    for (name, from, to, field) in [
        ("format.json", r#""rfisst-scenario/1""#, r#""rfisst-scen\rio/1""#, "rfisst-scen\\rio/1"),
        ("variant.json", r#""constant-velocity""#, r#""constant\u000bvelocity""#, "constant\\u{b}velocity"),
    ] {
        assert!(fixture.contains(from), "{name}: the fixture has no {from}");
        let file = dir.join(name);
        std::fs::write(&file, fixture.replacen(from, to, 1)).expect("write");
        let output = host_sim(&["run".as_ref(), file.as_os_str(), "--out".as_ref(), dir.join("out").as_os_str()]);
        if let Err(why) = check_malformed(&output, field) {
            panic!("{name}: {why}\n{}", describe(&output));
        }
    }
}

#[test]
fn unicode_separators_and_bidi_controls_are_escaped() {
    let dir = TempDir::new("escaped-unicode");
    for (name, key, shown) in [
        ("line-separator.json", "a\u{2028}b", "a\\u{2028}b"),
        ("paragraph-separator.json", "a\u{2029}b", "a\\u{2029}b"),
        ("right-to-left-override.json", "a\u{202e}b", "a\\u{202e}b"),
        ("isolate.json", "a\u{2066}b", "a\\u{2066}b"),
        ("zero-width-space.json", "a\u{200b}b", "a\\u{200b}b"),
    ] {
        let file = dir.join(name);
        let text = format!(r#"{{"format":"rfisst-scenario/1","sensor":{{"{key}":1}}}}"#);
        std::fs::write(&file, text).expect("write");
        let output = host_sim(&["run".as_ref(), file.as_os_str(), "--out".as_ref(), dir.join("out").as_os_str()]);
        if let Err(why) = check_malformed(&output, &format!("sensor.{shown}")) {
            panic!("{name}: {why}\n{}", describe(&output));
        }
        let err = stderr(&output);
        assert!(!err.contains(['\u{2028}', '\u{2029}', '\u{202e}', '\u{2066}', '\u{200b}']), "{name}: raw {err:?}");
    }
}

#[test]
fn a_byte_order_mark_is_skipped() {
    let dir = TempDir::new("bom");
    let file = dir.join("bom.json");
    let text = "\u{feff}".to_string() + &std::fs::read_to_string(FIXTURE).expect("fixture");
    std::fs::write(&file, text).expect("write");
    let out = dir.join("out");
    let output = host_sim(&["run".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    assert_eq!(read_json(&out.join("summary.json"))["scans"], json!(3));
}

#[test]
fn a_file_beyond_the_size_limit_is_rejected_before_parsing() {
    let dir = TempDir::new("size-limit");
    // /dev/zero never ends: only the first 256 MiB + 1 bytes are read.
    let output = host_sim(&["run", "/dev/zero", "--quiet", "--out", dir.join("out").to_str().expect("utf-8")]);
    if let Err(why) = check_malformed(&output, "/dev/zero: longer than the limit of 256 MiB") {
        panic!("{why}\n{}", describe(&output));
    }
}

#[test]
fn soak_scan_count_is_bounded() {
    let dir = TempDir::new("soak-scans");
    let out = dir.join("soak.json");
    for scans in ["0", "10000001", "1000000000000", "18446744073709551615"] {
        let output =
            host_sim(&["soak".as_ref(), "--scans".as_ref(), scans.as_ref(), "--out".as_ref(), out.as_os_str()]);
        if let Err(why) = check_malformed(&output, &format!("--scans {scans}: must be in [1, 10000000]")) {
            panic!("{scans}: {why}\n{}", describe(&output));
        }
        assert!(!out.exists());
        let output = host_sim(&[
            "soak".as_ref(),
            "--scenario".as_ref(),
            "radar-leo".as_ref(),
            "--scans".as_ref(),
            scans.as_ref(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        if let Err(why) = check_malformed(&output, &format!("--scans {scans}: must be in [1, 10000000]")) {
            panic!("radar-leo {scans}: {why}\n{}", describe(&output));
        }
        assert!(!out.exists());
    }
}

/// The truth's process noise of a 3-D soak (docs/maths.md §8.6) must be a density, and the planar soak has none.
#[test]
fn soak_truth_process_noise_is_checked() {
    let dir = TempDir::new("soak-truth-noise");
    let out = dir.join("soak.json");
    for (scenario, q, expect) in [
        ("optical-geo", "0", "--truth-process-noise 0: must be finite and > 0"),
        ("optical-geo", "NaN", "--truth-process-noise NaN: must be finite and > 0"),
        ("planar", "1e-12", "--truth-process-noise: only for the 3-D soaks"),
    ] {
        let output = host_sim(&[
            "soak".as_ref(),
            "--scenario".as_ref(),
            scenario.as_ref(),
            "--scans".as_ref(),
            "10".as_ref(),
            "--truth-process-noise".as_ref(),
            q.as_ref(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        if let Err(why) = check_malformed(&output, expect) {
            panic!("{scenario} {q}: {why}\n{}", describe(&output));
        }
        assert!(!out.exists());
    }
}

/// A short soak on the radar geometry (issue 17 item 7): healthy, every object kept, the new keys present.
#[test]
fn a_short_radar_soak_keeps_its_objects() {
    let dir = TempDir::new("soak-radar");
    let out = dir.join("soak.json");
    let scans = 300;
    let output = host_sim(&[
        "soak".as_ref(),
        "--scenario".as_ref(),
        "radar-leo".as_ref(),
        "--scans".as_ref(),
        scans.to_string().as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_success(&output);
    let report: Value = serde_json::from_str(&std::fs::read_to_string(&out).expect("report")).expect("json");
    assert_eq!(report["scenario"], "radar-leo");
    assert_eq!(report["scans"], scans);
    assert_eq!(report["nan_count"], 0);
    assert_eq!(report["errors_by_kind"], serde_json::json!({}));
    assert_eq!(report["numerical_drops"], 0);
    assert!(report["max_over_median"].as_f64().expect("ratio") >= 1.0);
    let (start, end) = (report["peak_resident_kib_start"].as_u64(), report["peak_resident_kib_end"].as_u64());
    if let (Some(start), Some(end)) = (start, end) {
        assert!(start > 0 && end >= start, "{start} {end}");
    }
    let objects = report["tracking"]["objects"].as_u64().expect("objects");
    assert_eq!(report["truth"]["final_alive"], objects);
    let expected = report["final_expected_cardinality"].as_f64().expect("cardinality");
    assert!((expected - objects as f64).abs() < 0.5, "{expected} of {objects}");
    assert_eq!(report["tracking"]["final_missing_labels"], 0);
    // The objects the radars see are where the tracker has them.
    assert!(report["tracking"]["in_view"].as_u64().expect("in view") > 100);
    let fraction = report["tracking"]["in_view_tracked_fraction"].as_f64().expect("fraction");
    assert!(fraction > 0.95, "{fraction}");
    assert!(report["measurements"].as_u64().expect("measurements") > 0);
}

#[test]
fn experiment_seeds_beyond_u64_are_an_error() {
    let dir = TempDir::new("seed-overflow");
    let output = host_sim(&[
        "experiment".as_ref(),
        "fifty".as_ref(),
        "--seed".as_ref(),
        "18446744073709551615".as_ref(),
        "--runs".as_ref(),
        "2".as_ref(),
        "--out".as_ref(),
        dir.join("out").as_os_str(),
    ]);
    if let Err(why) = check_malformed(&output, "--seed 18446744073709551615 --runs 2: the last seed would pass") {
        panic!("{why}\n{}", describe(&output));
    }
}

#[test]
fn without_scans_the_summary_reports_the_prior() {
    let dir = TempDir::new("no-scans");
    let mut scenario = fixture();
    scenario["scans"] = json!([]);
    scenario["truth"]["scans"] = json!([]);
    let file = dir.join("empty.json");
    write_json(&file, &scenario);
    for tracker in ["homht", "reference"] {
        let out = dir.join(tracker);
        let output = host_sim(&[
            "run".as_ref(),
            file.as_os_str(),
            "--tracker".as_ref(),
            tracker.as_ref(),
            "--quiet".as_ref(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        assert_success(&output);
        let summary = read_json(&out.join("summary.json"));
        // The prior holds two objects with weight 1.
        assert_eq!(summary["final_expected_cardinality"], json!(2.0), "{tracker}: {summary}");
        assert_eq!(summary["final_map_cardinality"], json!(2), "{tracker}: {summary}");
        assert_eq!(summary["scans"], json!(0));
    }
}

#[test]
fn the_reference_does_not_apply_the_profiles_object_capacity() {
    // 0.01 + 64 × 0.03 ≥ 1 (the embedded N), but 0.01 + 2 × 0.03 < 1 for the two objects of the fixture.
    let dir = TempDir::new("reference-no-n");
    let mut scenario = fixture();
    scenario["death_probability"] = json!(0.03);
    let file = dir.join("beta.json");
    write_json(&file, &scenario);
    let run = |tracker: &str| {
        host_sim(&[
            "run".as_ref(),
            file.as_os_str(),
            "--tracker".as_ref(),
            tracker.as_ref(),
            "--quiet".as_ref(),
            "--out".as_ref(),
            dir.join(tracker).as_os_str(),
        ])
    };
    assert_success(&run("reference"));
    let output = run("homht");
    if let Err(why) = check_malformed(&output, "M_b alpha + N beta must be < 1") {
        panic!("{why}\n{}", describe(&output));
    }
}

#[test]
fn an_output_that_cannot_be_written_exits_1() {
    let dir = TempDir::new("unwritable");
    let blocker = dir.join("file");
    std::fs::write(&blocker, "not a directory").expect("write");
    let below = blocker.join("out");
    for args in [
        vec!["run".as_ref(), FIXTURE.as_ref(), "--quiet".as_ref(), "--out".as_ref(), below.as_os_str()],
        vec!["generate".as_ref(), "linear-small".as_ref(), "--out".as_ref(), below.as_os_str()],
        vec!["sampler-check".as_ref(), "--cases".as_ref(), "1".as_ref(), "--out".as_ref(), below.as_os_str()],
    ] {
        let output = host_sim(&args);
        assert_eq!(output.status.code(), Some(1), "{args:?}: {}", describe(&output));
        let err = stderr(&output);
        assert!(err.starts_with("error: ") && err.lines().count() == 1, "{args:?}: {err}");
        assert!(err.contains("file/out"), "{args:?}: names the path: {err}");
    }
}

/// The keys of every JSON object of `value`, by path (`summary`, `summary.birth_confirmation_scans[]`, ...).
fn key_paths(value: &Value, path: &str, out: &mut std::collections::BTreeSet<String>) {
    match value {
        Value::Object(map) => {
            for (key, inner) in map {
                let inner_path = format!("{path}.{key}");
                out.insert(inner_path.clone());
                key_paths(inner, &inner_path, out);
            }
        }
        Value::Array(items) => items.iter().for_each(|item| key_paths(item, &format!("{path}[]"), out)),
        _ => {}
    }
}

fn keys_of(value: &Value) -> Vec<String> {
    let mut out = std::collections::BTreeSet::new();
    key_paths(value, "", &mut out);
    out.into_iter().collect()
}

/// The keys of `summary.json` and of a `scans.jsonl` line are those the files had before their records were
/// typed (listed from the output of `host-sim run` at commit 18b844d; since issue 29 with the five keys
/// that judge a run without truth), and the records read back unchanged.
#[test]
fn run_outputs_keep_their_keys_and_read_back_unchanged() {
    use host_sim::io::report::{RunSummary, ScanLine};
    let dir = TempDir::new("keys");
    let out = dir.join("out");
    let output = host_sim(&["run".as_ref(), FIXTURE.as_ref(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    let text = std::fs::read_to_string(out.join("summary.json")).expect("summary");
    let summary: Value = serde_json::from_str(&text).expect("json");
    let expected_summary = [
        "birth_confirmation_scans",
        "birth_confirmations",
        "births_confirmed",
        "births_total",
        "consistency_warnings",
        "error_bound",
        "false_tracks",
        "final_expected_cardinality",
        "final_map_cardinality",
        "gospa_cutoff",
        "gospa_order",
        "in_view_misses_after_confirmation",
        "in_view_red_stars",
        "label_switches",
        "max_detections_to_confirm",
        "max_labels_per_birth",
        "max_ms_per_scan",
        "mean_captured_mass",
        "mean_detections_to_confirm",
        "mean_gospa",
        "mean_ms_per_scan",
        "mean_ospa",
        "measurements_per_track",
        "min_captured_mass",
        "numerical_drops",
        "out_of_view_red_stars",
        "peak_hypotheses",
        "peak_resident_kib",
        "profile",
        "reference_budget_reached_scans",
        "refused_scans",
        "rejected_scans",
        "residuals",
        "scans",
        "scenario",
        "tracker",
        "tracks_ended",
        "tracks_started",
        "true_final_cardinality",
    ];
    let mut top: Vec<&str> = summary.as_object().expect("object").keys().map(String::as_str).collect();
    top.sort_unstable();
    assert_eq!(top, expected_summary);
    let typed: RunSummary = serde_json::from_str(&text).expect("a RunSummary");
    assert_eq!(serde_json::to_value(&typed).expect("value"), summary);

    let lines = std::fs::read_to_string(out.join("scans.jsonl")).expect("scans");
    let first: Value = serde_json::from_str(lines.lines().next().expect("a line")).expect("json");
    assert_eq!(
        keys_of(&first),
        [
            ".existence",
            ".existence[].existence",
            ".existence[].label",
            ".expected_cardinality",
            ".hypotheses",
            ".hypotheses[].tracks",
            ".hypotheses[].weight",
            ".hypotheses_total",
            ".numerical_drops",
            ".scan",
            ".time",
            ".tracks",
            ".tracks[].covariance",
            ".tracks[].existence",
            ".tracks[].label",
            ".tracks[].mean",
        ]
    );
    for line in lines.lines() {
        let value: Value = serde_json::from_str(line).expect("json");
        let typed: ScanLine = serde_json::from_str(line).expect("a ScanLine");
        assert_eq!(serde_json::to_value(&typed).expect("value"), value);
    }
}

/// The same for `compare.json` (keys listed from `host-sim compare` at commit 18b844d).
#[test]
fn compare_json_keeps_its_keys_and_reads_back_unchanged() {
    use host_sim::io::report::CompareReport;
    let dir = TempDir::new("compare-keys");
    let file = linear_small(&dir, Some(3));
    let out = dir.join("out");
    let output = host_sim(&[
        "compare".as_ref(),
        file.as_os_str(),
        "--quiet".as_ref(),
        "--json".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_success(&output);
    let text = std::fs::read_to_string(out.join("compare.json")).expect("compare");
    let value: Value = serde_json::from_str(&text).expect("json");
    assert_eq!(
        keys_of(&value),
        [
            ".bounded",
            ".bounded.max_ms_per_scan",
            ".bounded.mean_gospa",
            ".bounded.mean_ms_per_scan",
            ".bounded.tracker",
            ".bounded_tracker",
            ".map_agreement",
            ".mean_captured_mass",
            ".mean_weight_l1",
            ".min_captured_mass",
            ".per_scan",
            ".per_scan[].bounded_error",
            ".per_scan[].bounded_hypotheses",
            ".per_scan[].bounded_ms",
            ".per_scan[].captured_mass",
            ".per_scan[].map_agreement",
            ".per_scan[].reference_error",
            ".per_scan[].reference_hypotheses",
            ".per_scan[].reference_ms",
            ".per_scan[].scan",
            ".per_scan[].time",
            ".per_scan[].weight_l1",
            ".profile",
            ".reference",
            ".reference.budget_reached_scans",
            ".reference.max_ms_per_scan",
            ".reference.mean_gospa",
            ".reference.mean_ms_per_scan",
            ".reference.tracker",
            ".scans",
            ".scenario",
        ]
    );
    let typed: CompareReport = serde_json::from_str(&text).expect("a CompareReport");
    assert_eq!(serde_json::to_value(&typed).expect("value"), value);
    // The printed figures are the file's without `per_scan`.
    let printed: Value = serde_json::from_str(&stdout(&output)).expect("printed json");
    let mut brief = value.clone();
    brief.as_object_mut().expect("object").remove("per_scan");
    assert_eq!(printed, brief);
}

/// The same for the reports of `sampler-check` and `soak` (keys listed from their outputs at commit 18b844d,
/// with the soak's `scenario`, `max_over_median`, `peak_resident_kib_*` and `numerical_drops` of issue 17).
#[test]
fn sampler_check_and_soak_reports_keep_their_keys_and_read_back_unchanged() {
    use host_sim::io::report::{SamplerCheckReport, SoakReport};
    let dir = TempDir::new("report-keys");
    let file = dir.join("sc.json");
    let output =
        host_sim(&["sampler-check".as_ref(), "--cases".as_ref(), "3".as_ref(), "--out".as_ref(), file.as_os_str()]);
    assert_success(&output);
    let text = std::fs::read_to_string(&file).expect("report");
    let value: Value = serde_json::from_str(&text).expect("json");
    let scores = [
        "mean_captured_mass",
        "mean_sampler_steps_per_case",
        "mean_weight_l1",
        "min_captured_case",
        "min_captured_mass",
        "top1_found_fraction",
    ];
    let mut expected: Vec<String> = scores.iter().map(|k| format!(".{k}")).collect();
    expected.extend(scores.iter().map(|k| format!(".pure_sampling.{k}")));
    expected.extend(
        ["cases", "max_children_per_case", "mean_children_per_case", "pure_sampling", "sampler", "seed"]
            .map(|k| format!(".{k}")),
    );
    expected.extend(
        ["burn_in", "clusters", "exact_start", "exhaustive_limit", "proposal", "steps"]
            .map(|k| format!(".sampler.{k}")),
    );
    expected.sort();
    assert_eq!(keys_of(&value), expected);
    let typed: SamplerCheckReport = serde_json::from_str(&text).expect("a SamplerCheckReport");
    assert_eq!(serde_json::to_value(&typed).expect("value"), value);

    let file = dir.join("soak.json");
    let output = host_sim(&[
        "soak".as_ref(),
        "--scans".as_ref(),
        "3".as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        file.as_os_str(),
    ]);
    assert_success(&output);
    let text = std::fs::read_to_string(&file).expect("report");
    let value: Value = serde_json::from_str(&text).expect("json");
    let mut expected: Vec<String> = [
        "births_beyond_object_capacity",
        "children_dropped_for_store",
        "errors_by_kind",
        "final_expected_cardinality",
        "first_error",
        "first_non_finite_scan",
        "hypothesis_capacity",
        "max_abs_cardinality_error",
        "max_hypotheses",
        "max_measurements_per_scan",
        "max_ms_per_scan",
        "mean_abs_cardinality_error",
        "max_over_median",
        "mean_ms_per_scan",
        "mean_ms_per_scan_first_tenth",
        "mean_ms_per_scan_last_tenth",
        "measurement_capacity",
        "measurements",
        "nan_count",
        "non_finite_scans",
        "numerical_drops",
        "p50_ms_per_scan",
        "p99_ms_per_scan",
        "peak_resident_kib_end",
        "peak_resident_kib_start",
        "scans",
        "scenario",
        "seed",
        "setup",
        "track_store_capacity",
        "track_store_high_water",
        "truth",
        "wall_seconds",
    ]
    .iter()
    .map(|k| format!(".{k}"))
    .collect();
    expected.extend(
        [
            "birth_rate_per_scan",
            "death_rate_per_object_per_scan",
            "motion",
            "scan_interval_s",
            "sensor",
            "tracker",
            "tracker_birth_cells",
            "tracker_birth_probability_per_cell",
            "tracker_death_probability",
        ]
        .map(|k| format!(".setup.{k}")),
    );
    expected.extend(["births", "deaths", "final_alive", "initial_objects", "max_alive"].map(|k| format!(".truth.{k}")));
    expected.sort();
    assert_eq!(keys_of(&value), expected);
    let typed: SoakReport = serde_json::from_str(&text).expect("a SoakReport");
    assert_eq!(serde_json::to_value(&typed).expect("value"), value);
}

// ---------------------------------------------------------------------------------------------------
// Version 2 (3-D) scenario files
// ---------------------------------------------------------------------------------------------------

/// `host-sim generate tiny-3d --seed 1` into `dir` (one radar, 3 LEO objects, 11 scans).
fn tiny_3d(dir: &TempDir) -> PathBuf {
    let path = dir.join("tiny-3d.json");
    let output = host_sim(&["generate".as_ref(), "tiny-3d".as_ref(), "--out".as_ref(), path.as_os_str()]);
    assert_success(&output);
    assert!(stderr(&output).starts_with("wrote "), "{}", describe(&output));
    path
}

#[test]
fn v2_tiny_3d_generates_loads_and_runs_with_every_summary_key() {
    let dir = TempDir::new("v2-run");
    let file = tiny_3d(&dir);
    let value = read_json(&file);
    assert_eq!((value["format"].clone(), value["version"].clone()), (json!("rfisst-scenario/2"), json!(2)));
    let scans = value["scans"].as_array().expect("scans").len();
    assert_eq!(value["truth"]["scans"].as_array().map(Vec::len), Some(scans));
    let out = dir.join("out");
    let output = host_sim(&[
        "run".as_ref(),
        file.as_os_str(),
        "--tracker".as_ref(),
        "rfisst".as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_success(&output);
    let summary = read_json(&out.join("summary.json"));
    // The keys of the planar presets, and those of 3-D runs.
    for key in [
        "scenario",
        "tracker",
        "profile",
        "scans",
        "mean_gospa",
        "mean_ospa",
        "final_expected_cardinality",
        "final_map_cardinality",
        "true_final_cardinality",
        "label_switches",
        "in_view_red_stars",
        "out_of_view_red_stars",
        "mean_ms_per_scan",
        "max_ms_per_scan",
        "peak_hypotheses",
        "rejected_scans",
        "sensors",
    ] {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}: {summary}");
    }
    assert_eq!(summary["sensors"], json!(1));
    assert_eq!(summary["scans"], json!(scans));
    assert_eq!(summary["rejected_scans"], json!([]));
    assert_eq!(summary["true_final_cardinality"], json!(3));
    // Three well-separated objects seen at every scan: the MAP estimates are within a few km (cut-off 10 km).
    let gospa = summary["mean_gospa"].as_f64().expect("mean_gospa");
    assert!(gospa.is_finite() && gospa < 2.0, "mean_gospa {gospa} km");
    assert_eq!(summary["final_map_cardinality"], json!(3), "{summary}");
    assert!(summary["mean_ms_per_scan"].as_f64().is_some_and(|ms| ms > 0.0));

    let csv = std::fs::read_to_string(out.join("estimates.csv")).expect("estimates.csv");
    let mut rows = csv.lines();
    assert_eq!(rows.next(), Some("scan,time,sensor,label,x,y,z,vx,vy,vz,existence,within_error_bound"));
    let rows: Vec<&str> = rows.collect();
    assert_eq!(rows.len(), 3 * scans, "three MAP tracks per scan");
    assert!(rows.iter().all(|r| r.split(',').count() == 12), "{csv}");

    for plot in ["sky_0_radar-north", "expected_cardinality", "gospa", "residuals_0_radar-north"] {
        let png = assert_nonempty_file(&out.join(format!("{plot}.png")));
        assert!(png.starts_with(b"\x89PNG"), "{plot}.png is not a PNG");
    }
}

#[test]
fn v2_generate_is_deterministic_and_compare_agrees_with_the_reference() {
    let dir = TempDir::new("v2-compare");
    let file = tiny_3d(&dir);
    let again = dir.join("again.json");
    let output = host_sim(&["generate".as_ref(), "tiny-3d".as_ref(), "--out".as_ref(), again.as_os_str()]);
    assert_success(&output);
    assert_eq!(std::fs::read(&file).expect("read"), std::fs::read(&again).expect("read"));
    // The first three scans: the reference's children grow as ~40× per scan.
    let mut scenario: serde_json::Value = serde_json::from_slice(&std::fs::read(&file).expect("read")).expect("json");
    scenario["scans"].as_array_mut().expect("scans").truncate(3);
    scenario["truth"]["scans"].as_array_mut().expect("truth scans").truncate(3);
    let short = dir.join("short.json");
    std::fs::write(&short, serde_json::to_vec(&scenario).expect("json")).expect("write");
    let out = dir.join("out");
    let output =
        host_sim(&["compare".as_ref(), short.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("compare.json")).expect("compare.json")).expect("json");
    assert_eq!(summary["scans"], 3, "{summary}");
    assert_eq!(summary["map_agreement"], 1.0, "{summary}");
    assert!(summary["min_captured_mass"].as_f64().expect("mass") >= 0.999, "{summary}");
    assert_eq!(summary["core_rejected_scans"], 0, "{summary}");
    let output = host_sim(&[
        "run".as_ref(),
        file.as_os_str(),
        "--tracker".as_ref(),
        "reference".as_ref(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    if let Err(why) = check_malformed(&output, "--tracker reference: not yet supported on version 2") {
        panic!("{why}\n{}", describe(&output));
    }
}

#[test]
fn v1_files_with_or_without_version_1_still_run() {
    let dir = TempDir::new("v1-version");
    let out = dir.join("out");
    let mut value = fixture();
    object(&mut value).insert("version".into(), json!(1));
    let file = dir.join("v1.json");
    write_json(&file, &value);
    let output = host_sim(&["run".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    assert!(read_json(&out.join("summary.json")).get("sensors").is_none(), "version 1 summaries have no sensors key");
}

fn v2_cases(base: &Value) -> Vec<(&'static str, &'static str, Value)> {
    let case = |name, expect, mutate: &dyn Fn(&mut Value)| {
        let mut value = base.clone();
        mutate(&mut value);
        (name, expect, value)
    };
    vec![
        case("unknown version", "version: 3 is not a known format version", &|v| v["version"] = json!(3)),
        case("scan names an unknown sensor", "scans[2].sensor: unknown sensor 4: there are 1 sensors", &|v| {
            v["scans"][2]["sensor"] = json!(4)
        }),
        case("latitude beyond 90", "sensors[0].site.latitude_deg: 91 is not in [-90, 90]", &|v| {
            v["sensors"][0]["site"]["latitude_deg"] = json!(91.0)
        }),
        case("observer inside the Earth", "sensors[0].site.height_km: -2 km: the observer is inside the Earth", &|v| {
            v["sensors"][0]["site"]["height_km"] = json!(-2.0)
        }),
        case("measured elevation beyond 90", "scans[1].measurements[0]: elevation 95 is not in [-90, 90]", &|v| {
            v["scans"][1]["measurements"][0][2] = json!(95.0)
        }),
        case("negative measured range", "scans[1].measurements[0]: range -5 is not in [0, inf]", &|v| {
            v["scans"][1]["measurements"][0][0] = json!(-5.0)
        }),
        case("measurement of the wrong dimension", "has 2 components, a radar measurement has 3", &|v| {
            v["scans"][1]["measurements"][0] = json!([1000.0, 10.0])
        }),
        case("negative range window", "sensors[0].field_of_view.range_km: negative range -100", &|v| {
            v["sensors"][0]["field_of_view"]["range_km"] = json!([-100.0, 3000.0])
        }),
        case("box of zero elevation extent", "the field of view has no volume", &|v| {
            v["sensors"][0]["field_of_view"]["shape"] =
                json!({"type": "box", "azimuth_deg": 0.0, "half_width_deg": 180.0, "elevation_deg": [30.0, 30.0]})
        }),
        case(
            "cone of zero half angle",
            "half_angle_deg: 0 is not in (0, 180]: the field of view has no volume",
            &|v| {
                v["sensors"][0]["field_of_view"]["shape"] =
                    json!({"type": "cone", "azimuth_deg": 0.0, "elevation_deg": 45.0, "half_angle_deg": 0.0})
            },
        ),
        case("shape below the elevation mask", "nothing of the shape", &|v| {
            v["sensors"][0]["field_of_view"]["shape"] =
                json!({"type": "cone", "azimuth_deg": 0.0, "elevation_deg": 20.0, "half_angle_deg": 5.0});
            v["sensors"][0]["field_of_view"]["min_elevation_deg"] = json!(40.0)
        }),
        case("cone boresight elevation beyond 90", "shape.elevation_deg: 100 is not in [-90, 90]", &|v| {
            v["sensors"][0]["field_of_view"]["shape"] =
                json!({"type": "cone", "azimuth_deg": 0.0, "elevation_deg": 100.0, "half_angle_deg": 5.0})
        }),
        case("scan gap beyond the motion model's bound", "beyond the motion model's bound of 5 s", &|v| {
            v["motion"]["max_step"] = json!(5.0);
            v["motion"]["max_substeps"] = json!(1)
        }),
        case("missing noise component", "sensors[0].noise.elevation_arcsec: required for radar", &|v| {
            object(&mut v["sensors"][0]["noise"]).remove("elevation_arcsec");
        }),
        case("noise of another measurement type", "noise.declination_arcsec: not part of a radar measurement", &|v| {
            v["sensors"][0]["noise"]["declination_arcsec"] = json!(1.0)
        }),
        case("zero detection probability", "sensors[0].detection_probability: 0 is not in (0, 1]", &|v| {
            v["sensors"][0]["detection_probability"] = json!(0.0)
        }),
        case("bad epoch", "epoch.utc: epoch is not an ISO-8601 UTC time", &|v| {
            object(&mut v["epoch"]).remove("julian_date");
            v["epoch"]["utc"] = json!("yesterday")
        }),
        case("epochs that disagree", "epoch: utc", &|v| v["epoch"]["julian_date"] = json!(2461120.0)),
        case("unknown field", "unknown field `sensor_count`", &|v| {
            object(v).insert("sensor_count".into(), json!(1));
        }),
        case("scans out of order", "scans[3].time: 20 is not after the previous time 20", &|v| {
            v["scans"][3]["time"] = json!(20.0)
        }),
    ]
}

#[test]
fn v2_malformed_files_exit_2_with_one_error_line() {
    let dir = TempDir::new("v2-malformed");
    let base = read_json(&tiny_3d(&dir));
    let out = dir.join("out");
    let mut failures = vec![];
    let mut texts: Vec<(&str, &str, String)> = v2_cases(&base)
        .into_iter()
        .map(|(name, expect, value)| (name, expect, serde_json::to_string(&value).expect("serialise")))
        .collect();
    // A non-finite number cannot be written as JSON: the parser's message.
    let text = serde_json::to_string(&base).expect("serialise");
    let q = "\"q\":1e-12";
    assert!(text.contains(q), "the preset's process noise");
    texts.push((
        "non-finite process noise",
        "motion.process_noise.q: number out of range",
        text.replace(q, "\"q\":1e999"),
    ));
    let z = "\"measurements\":[[";
    assert!(text.contains(z), "a scan with measurements");
    texts.push((
        "non-finite measurement",
        "scans[0].measurements[0][0]: number out of range",
        text.replacen(z, "\"measurements\":[[1e999,", 1),
    ));
    for (i, (name, expect, text)) in texts.iter().enumerate() {
        let file = dir.join(&format!("case-{i}.json"));
        std::fs::write(&file, text).expect("write case");
        let output =
            host_sim(&["run".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
        if let Err(why) = check_malformed(&output, expect) {
            failures.push(format!("{name}: {why}\n{}", describe(&output)));
        }
    }
    assert!(failures.is_empty(), "{} of {} cases failed:\n{}", failures.len(), texts.len(), failures.join("\n"));
}

#[test]
fn v2_documented_example_is_the_fixture_and_runs() {
    let doc = std::fs::read_to_string(DOC).expect("docs/scenario-format.md");
    let section = &doc[doc.find("## Example (version 2)").expect("the version 2 example")..];
    let start = section.find("```json\n").expect("a json block") + "```json\n".len();
    let end = start + section[start..].find("```").expect("end of the json block");
    let example: Value = serde_json::from_str(&section[start..end]).expect("the documented example is JSON");
    assert_eq!(example, read_json(Path::new(FIXTURE_3D)));
    let dir = TempDir::new("v2-fixture");
    let out = dir.join("out");
    let output =
        host_sim(&["run".as_ref(), FIXTURE_3D.as_ref(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    let summary = read_json(&out.join("summary.json"));
    assert_eq!((summary["scans"].clone(), summary["sensors"].clone()), (json!(2), json!(1)));
    assert_eq!(summary["final_map_cardinality"], json!(1), "{summary}");
    assert!(summary["mean_gospa"].as_f64().is_some_and(|g| g < 1.0), "{summary}");
}

#[test]
fn v2_digest_replays_radar_scans_and_needs_the_truth() {
    let dir = TempDir::new("v2-digest");
    let file = tiny_3d(&dir);
    let digest =
        |file: &Path, scans: &str| host_sim(&["digest".as_ref(), file.as_os_str(), "--scans".as_ref(), scans.as_ref()]);
    let output = digest(&file, "5");
    assert_success(&output);
    let text = stdout(&output);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 6, "{text}");
    assert!(lines[0].starts_with("scan 0 hypotheses ") && lines[5].starts_with("final scans 5 digest "), "{text}");
    assert_eq!(stdout(&digest(&file, "5")), text, "deterministic");
    // Without the truth the prior cannot be restricted to the detected objects: one line, exit code 2.
    let mut value = read_json(&file);
    object(&mut value).remove("truth");
    let bare = dir.join("no-truth.json");
    write_json(&bare, &value);
    let output = digest(&bare, "5");
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert!(stderr(&output).contains("truth"), "{}", describe(&output));
    assert_eq!(stderr(&output).trim_end().lines().count(), 1, "{}", describe(&output));
}

#[test]
fn v2_digest_writes_the_network_excerpt_and_refuses_one_for_other_scenarios() {
    let dir = TempDir::new("v2-excerpt");
    let file = dir.join("tiny-network.json");
    assert_success(&host_sim(&["generate".as_ref(), "tiny-network".as_ref(), "--out".as_ref(), file.as_os_str()]));
    let excerpt = dir.join("network.rs");
    let digest = |file: &Path| {
        let args: [&std::ffi::OsStr; 6] = [
            "digest".as_ref(),
            file.as_os_str(),
            "--scans".as_ref(),
            "4".as_ref(),
            "--excerpt".as_ref(),
            excerpt.as_os_str(),
        ];
        host_sim(&args)
    };
    let output = digest(&file);
    assert_success(&output);
    assert!(stdout(&output).starts_with("scan 0 ") && stdout(&output).contains("final scans 4 digest "));
    let source = std::fs::read_to_string(&excerpt).expect("the excerpt is written");
    assert!(source.contains("pub const SCANS: [Scan; 4] = [") && source.contains("Network::unconfigured()"));
    // The same digest without --excerpt.
    let plain = host_sim(&["digest".as_ref(), file.as_os_str(), "--scans".as_ref(), "4".as_ref()]);
    assert_eq!(stdout(&plain), stdout(&output));
    // A radar scenario has no network excerpt: one line, exit code 2.
    let output = digest(&tiny_3d(&dir));
    assert_eq!(output.status.code(), Some(2), "{}", describe(&output));
    assert_eq!(stderr(&output).trim_end().lines().count(), 1, "{}", describe(&output));
}

// ---------------------------------------------------------------------------------------------------
// Births: detections to confirmation and false tracks
// ---------------------------------------------------------------------------------------------------

/// Checks the birth keys of a summary against the scenario file: one record per object outside the
/// prior, the first detection and the detections to confirmation counted from the truth's origins, and the
/// mean and the largest of those.
fn check_birth_keys(file: &Value, summary: &Value) {
    let births: Vec<u64> = file["truth"]["objects"]
        .as_array()
        .expect("truth objects")
        .iter()
        .filter(|o| o["in_prior"] == json!(false))
        .map(|o| o["id"].as_u64().expect("id"))
        .collect();
    let records = summary["birth_confirmations"].as_array().expect("birth_confirmations");
    assert_eq!(summary["births_total"], json!(births.len()), "{summary}");
    assert_eq!(records.iter().map(|r| r["object"].as_u64().expect("object")).collect::<Vec<_>>(), births);
    let origins: Vec<Vec<Option<u64>>> = file["truth"]["scans"]
        .as_array()
        .expect("truth scans")
        .iter()
        .map(|s| s["origins"].as_array().expect("origins").iter().map(Value::as_u64).collect())
        .collect();
    let mut confirmed = vec![];
    for r in records {
        let id = r["object"].as_u64();
        let detected_at = |k: usize| origins[k].contains(&id);
        let first = (0..origins.len()).find(|&k| detected_at(k));
        assert_eq!(r["first_detection_scan"], json!(first), "{r}");
        if let Some(c) = r["confirmation_scan"].as_u64().map(|c| c as usize) {
            let detections = (0..=c).filter(|&k| detected_at(k)).count();
            assert_eq!(r["detections_to_confirm"], json!(detections), "{r}");
            let first = first.expect("confirmed only once detected");
            assert!(first <= c, "{r}");
            let scans = c - first + 1;
            assert_eq!(r["scans_to_confirm"], json!(scans), "{r}");
            assert!(r["confirmed_labels"].as_u64().is_some_and(|n| n >= 1), "{r}");
            confirmed.push(detections);
        } else {
            assert_eq!((r["detections_to_confirm"].clone(), r["scans_to_confirm"].clone()), (json!(null), json!(null)));
            assert_eq!(r["confirmed_labels"], json!(0), "{r}");
        }
    }
    let most_labels = records.iter().filter_map(|r| r["confirmed_labels"].as_u64()).filter(|&n| n > 0).max();
    assert_eq!(summary["max_labels_per_birth"], json!(most_labels), "{summary}");
    assert_eq!(summary["births_confirmed"], json!(confirmed.len()), "{summary}");
    if confirmed.is_empty() {
        assert_eq!(summary["mean_detections_to_confirm"], json!(null));
        assert_eq!(summary["max_detections_to_confirm"], json!(null));
    } else {
        let mean = confirmed.iter().sum::<usize>() as f64 / confirmed.len() as f64;
        assert!((summary["mean_detections_to_confirm"].as_f64().expect("mean") - mean).abs() < 1e-12, "{summary}");
        assert_eq!(summary["max_detections_to_confirm"], json!(confirmed.iter().max()));
    }
    assert!(summary["false_tracks"].as_u64().is_some(), "{summary}");
}

#[test]
fn birth_keys_of_a_planar_run_match_the_truth() {
    let dir = TempDir::new("birth-keys");
    let file = linear_small(&dir, None);
    let out = dir.join("out");
    let output = host_sim(&["run".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    let summary = read_json(&out.join("summary.json"));
    // linear-small: one birth (object 3, at t = 2.5).
    assert_eq!(summary["births_total"], json!(1), "{summary}");
    check_birth_keys(&read_json(&file), &summary);
}

#[test]
fn birth_keys_of_a_3d_run_with_an_object_missing_from_the_prior() {
    let dir = TempDir::new("birth-keys-3d");
    let file = tiny_3d(&dir);
    // Object 0 leaves the prior: a birth the tracker (no birth cells) cannot confirm.
    let mut value = read_json(&file);
    value["truth"]["objects"][0]["in_prior"] = json!(false);
    array(&mut value["prior"]["hypotheses"][0]["objects"]).retain(|o| o["label"] != json!(0));
    write_json(&file, &value);
    let out = dir.join("out");
    let output = host_sim(&["run".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), out.as_os_str()]);
    assert_success(&output);
    let summary = read_json(&out.join("summary.json"));
    assert_eq!((summary["births_total"].clone(), summary["births_confirmed"].clone()), (json!(1), json!(0)));
    assert!(summary["birth_confirmations"][0]["first_detection_scan"].as_u64().is_some(), "{summary}");
    check_birth_keys(&value, &summary);
    assert_eq!(summary["false_tracks"], json!(0), "{summary}");
}

#[test]
fn generate_unknowns_need_a_3d_preset_and_a_fraction_in_range() {
    let dir = TempDir::new("unknowns");
    let path = dir.join("x.json");
    for args in [
        &["generate", "linear-small", "--missing-fraction", "0.2"][..],
        &["generate", "tiny-3d", "--breakup", "3"],
        &["generate", "optical-geo", "--breakup", "3"],
        &["generate", "optical-leo", "--breakup", "3"],
        &["generate", "optical-heo", "--missing-fraction", "0.2"],
        &["generate", "radar-leo", "--missing-fraction", "1.5"],
    ] {
        let mut args: Vec<&std::ffi::OsStr> = args.iter().map(|a| a.as_ref()).collect();
        args.extend(["--out".as_ref(), path.as_os_str()]);
        let output = host_sim(&args);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {}", describe(&output));
        assert_eq!(stderr(&output).lines().count(), 1, "{}", describe(&output));
        assert!(!path.exists());
    }
}

/// `run FILE` where FILE holds `text`; the one error line (checked as [`check_malformed`] does).
fn run_error(dir: &TempDir, name: &str, text: &str, expect: &str) -> String {
    let file = dir.join(name);
    std::fs::write(&file, text).expect("write");
    let output = host_sim(&[
        "run".as_ref(),
        file.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        dir.join("out").as_os_str(),
    ]);
    if let Err(why) = check_malformed(&output, expect) {
        panic!("{name}: {why}\n{}", describe(&output));
    }
    stderr(&output)
}

#[test]
fn ten_megabyte_keys_and_values_are_quoted_as_short_excerpts() {
    // Issue 33 item 7: a 10 MB unknown key or value was echoed whole, a 10-20 MB stderr line.
    let dir = TempDir::new("excerpt");
    let fixture = std::fs::read_to_string(FIXTURE).expect("fixture");
    let long = "K".repeat(10 << 20);
    let cases = [
        ("key.json", fixture.replacen("\"name\"", &format!("\"{long}\": 1, \"name\""), 1), "(10485760 bytes)`"),
        ("nested-key.json", fixture.replacen("\"gate\"", &format!("\"{long}\": 1, \"gate\""), 1), "(10485760 bytes)`"),
        ("value.json", fixture.replacen("\"rfisst-scenario/1\"", &format!("\"{long}\""), 1), "(10485760 bytes)"),
        ("number.json", fixture.replacen("16.0", &format!("\"{long}\""), 1), "(10485760 bytes)"),
    ];
    for (name, text, expect) in cases {
        let err = run_error(&dir, name, &text, expect);
        assert!(err.len() < 600, "{name}: {} bytes: {}", err.len(), &err[..err.len().min(600)]);
    }
}

#[test]
fn overflowing_seeds_say_what_a_seed_is() {
    let dir = TempDir::new("seed-range");
    let fixture = std::fs::read_to_string(FIXTURE).expect("fixture");
    assert!(fixture.contains("\"seed\": 7"));
    for (name, seed) in [("float.json", "1e30"), ("beyond.json", "18446744073709551616"), ("negative.json", "-1")] {
        let text = fixture.replacen("\"seed\": 7", &format!("\"seed\": {seed}"), 1);
        let err = run_error(&dir, name, &text, "tracker.seed: must be an integer in 0..=18446744073709551615");
        assert!(!err.contains("invalid type"), "{err}");
    }
    let text = fixture.replacen("\"seed\": 7", "\"seed\": 18446744073709551615", 1);
    let file = dir.join("max.json");
    std::fs::write(&file, text).expect("write");
    assert_success(&host_sim(&[
        "run".as_ref(),
        file.as_os_str(),
        "--quiet".as_ref(),
        "--out".as_ref(),
        dir.join("max").as_os_str(),
    ]));
}

#[test]
fn huge_numbers_are_printed_in_scientific_form() {
    // Issue 33 item 7: `--duration-hours 1e308` printed 309 digits.
    let dir = TempDir::new("readable");
    let file = dir.join("beta.json");
    write_json(&file, &fixture_value_with(|v| v["death_probability"] = json!(1e300)));
    let output =
        host_sim(&["run".as_ref(), file.as_os_str(), "--quiet".as_ref(), "--out".as_ref(), dir.join("o").as_os_str()]);
    check_malformed(&output, "death_probability: 1e300 is not in [0, 1]")
        .unwrap_or_else(|why| panic!("{why}\n{}", describe(&output)));
    let output = host_sim(&[
        "generate",
        "catalogue",
        "--catalogue",
        "x.tle",
        "--sensors",
        "s.json",
        "--start",
        "2026-01-01T00:00:00Z",
        "--duration-hours",
        "1e308",
        "--out",
        dir.join("c.json").to_str().expect("path"),
    ]);
    check_malformed(&output, "--duration-hours 1e308: must be in (0, 744]")
        .unwrap_or_else(|why| panic!("{why}\n{}", describe(&output)));
    assert!(stderr(&output).len() < 100, "{}", stderr(&output));
}

fn fixture_value_with(change: impl FnOnce(&mut Value)) -> Value {
    let mut value = fixture();
    change(&mut value);
    value
}

#[test]
fn one_sensor_name_rule_for_run_and_export_tdm() {
    // Issue 33 item 7: names that export-tdm refused were accepted by run.
    let dir = TempDir::new("sensor-names");
    let base = read_json(Path::new(FIXTURE_3D));
    let mut two = base.clone();
    let sensor = two["sensors"][0].clone();
    array(&mut two["sensors"]).push(sensor);
    let cases: Vec<(&str, Value, &str)> = vec![
        ("duplicate", two, "sensors[1].name: \"radar-north\" names two sensors (sensors[0] too)"),
        ("empty", fixture_3d_name(&base, ""), "sensors[0].name: \"\" cannot name a sensor"),
        ("newline", fixture_3d_name(&base, "radar\nnorth"), "sensors[0].name: \"radar\\nnorth\" cannot name a sensor"),
        ("blanks", fixture_3d_name(&base, " radar"), "sensors[0].name: \" radar\" cannot name a sensor"),
    ];
    for (name, value, expect) in cases {
        let file = dir.join(&format!("{name}.json"));
        write_json(&file, &value);
        for command in ["run", "export-tdm"] {
            let output = host_sim(&[command.as_ref(), file.as_os_str(), "--out".as_ref(), dir.join("out").as_os_str()]);
            if let Err(why) = check_malformed(&output, expect) {
                panic!("{name}, {command}: {why}\n{}", describe(&output));
            }
            assert!(!dir.join("out").exists(), "{name}, {command}: output written");
        }
    }
}

fn fixture_3d_name(base: &Value, name: &str) -> Value {
    let mut value = base.clone();
    value["sensors"][0]["name"] = json!(name);
    value
}
