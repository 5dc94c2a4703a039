//! Integration tests of the `host-sim` command line: help, `generate`, `run`, `compare`, the
//! hand-written fixture of `docs/scenario-format.md`, exit codes and one-line errors for malformed files.
//!
//! The unbounded reference tracker grows its hypotheses exponentially: on the full 6-scan `linear-small`
//! it takes about 26 s in a debug build, so the tests that run it (`run --tracker reference`, `compare`)
//! use `linear-small` cut to its first 4 scans (about 0.1 s).

use host_sim::scenario::Scenario;
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

const BIN: &str = env!("CARGO_BIN_EXE_host-sim");
const FIXTURE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/hand_written.json");
const DOC: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/scenario-format.md");

/// A fresh directory under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!("host-sim-cli-{}-{tag}-{n}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).expect("create temp dir");
        TempDir(path)
    }

    fn join(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn host_sim<S: AsRef<std::ffi::OsStr>>(args: &[S]) -> Output {
    Command::new(BIN).args(args).output().expect("run host-sim")
}

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
    for args in [&[][..], &["frobnicate"], &["generate", "linear-small"], &["run", FIXTURE], &["run", "--bogus"]] {
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
    let err = stderr(&output);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("error: unknown preset \"sixty-objects\""), "{err}");
    assert!(err.contains("linear-small"), "lists the presets: {err}");
    assert!(!path.exists());
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
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    assert_success(&output);
    let summary = check_run_outputs(&out, "homht", 6);
    // linear-small: one birth, one death, 3 objects at the end.
    assert_eq!(summary["births_total"], json!(1));
    assert_eq!(summary["true_final_cardinality"], json!(3));
    // stdout is the summary.
    let printed: Value = serde_json::from_str(&stdout(&output)).expect("stdout is JSON");
    assert_eq!(printed, summary);
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
fn rejected_scans_exit_3_with_outputs() {
    let dir = TempDir::new("rejected");
    let mut scenario = fixture();
    // Outside the 100 x 100 rectangle: valid JSON, but the tracker rejects scan 1.
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
        assert_eq!(output.status.code(), Some(3), "{tracker}: {}", describe(&output));
        let err = stderr(&output);
        assert!(err.contains("scan 1") && err.contains("outside the field of view"), "{err}");
        assert!(err.lines().last().is_some_and(|l| l.starts_with("error: ")), "{err}");
        let summary = read_json(&out.join("summary.json"));
        assert_eq!(summary["rejected_scans"].as_array().map(Vec::len), Some(1), "{summary}");
        assert_eq!(summary["rejected_scans"][0]["scan"], json!(1));
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
        mutated("fraction in an integer field", "tracker.seed: invalid type: floating point", |v| {
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
        mutated("GOSPA order below 1", "evaluation.gospa_order: must be >= 1", |v| {
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
