//! The C example (`examples/map_tracks.c`), built with the host's gcc against `librfisst.a`, prints the
//! same numbers, bit for bit, as tracker-core's `SsaTracker<f64>` built directly in Rust on the same
//! configuration and scans; and its JSON part the same prior as host-sim's planar tracker on the same
//! file. Numbers are compared as parsed doubles (`%.17g` reads back exactly), every other word as text.

use nalgebra::{SMatrix, SVector};
use std::path::{Path, PathBuf};
use std::process::Command;
use tracker_core::config::Selection;
use tracker_core::sampler::SamplerConfig;
use tracker_core::{
    BirthDetection, BirthEvents, BirthModel, ChildGeneration, Config, Gaussian, NumericalFailure, PositionMeasurement,
    PriorHypothesis, PriorObject, Region, Sensor, SsaTracker, StoreOverflow, TrackLabel, TwoBody,
};

/// `target/<profile>`, from this test's own path (`target/<profile>/deps/c_example-*`).
fn profile_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("test path");
    exe.parent().and_then(Path::parent).expect("target/<profile>").to_path_buf()
}

/// Builds `librfisst.a` (this profile), then the example with gcc; returns the executable.
fn build_example() -> PathBuf {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let profile = profile_dir();
    let mut cargo = Command::new(env!("CARGO"));
    cargo.args(["build", "--quiet", "-p", "rfisst-c", "--lib"]);
    if profile.file_name().is_some_and(|name| name == "release") {
        cargo.arg("--release");
    }
    let status = cargo.status().expect("run cargo");
    assert!(status.success(), "cargo build -p rfisst-c failed");
    let library = profile.join("librfisst.a");
    assert!(library.exists(), "{} missing", library.display());
    let out = profile.join("c-example");
    std::fs::create_dir_all(&out).expect("output directory");
    let exe = out.join("map_tracks");
    let output = Command::new("gcc")
        .args(["-std=c11", "-Wall", "-Wextra", "-Werror", "-I"])
        .arg(crate_dir.join("include"))
        .arg(crate_dir.join("examples/map_tracks.c"))
        .arg(&library)
        .args(["-lm", "-lpthread", "-ldl", "-o"])
        .arg(&exe)
        .output()
        .expect("run gcc (the host's C compiler)");
    assert!(output.status.success(), "gcc failed:\n{}", String::from_utf8_lossy(&output.stderr));
    exe
}

fn gaussian(mean: [f64; 4], variance: f64) -> Gaussian<f64, 4> {
    Gaussian { mean: SVector::from(mean), covariance: SMatrix::identity() * variance }
}

/// The example's configuration, written with tracker-core's types.
fn config() -> tracker_core::SsaConfig<f64> {
    let mut cells = heapless::Vec::new();
    let cell =
        Gaussian { mean: SVector::zeros(), covariance: SMatrix::from_diagonal(&SVector::from([1.0, 1.0, 0.5, 0.5])) };
    cells.push(cell).expect("one cell");
    Config {
        motion: TwoBody { mu: 1.0, acceleration_noise: 1e-6, max_step: 0.01, max_substeps: 1000, min_radius: 0.0 },
        measurement: PositionMeasurement { noise: SMatrix::identity() * 1e-4 },
        sensor: Sensor {
            detection_probability: 0.95,
            clutter_rate: 1.0,
            field_of_view: Region::Rectangle { min: [-2.0, -2.0], max: [2.0, 2.0] },
        },
        birth: BirthModel {
            probability: 0.01,
            cells,
            detection: BirthDetection::AllDetected,
            events: BirthEvents::FirstOrder,
            measured: None,
        },
        death_probability: 0.01,
        gate: None,
        children: ChildGeneration::Sampled(SamplerConfig::DEFAULT),
        selection: Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: NumericalFailure::DropTrack,
        track_loss: Default::default(),
        seed: 7,
    }
}

/// The example's scans.
fn scans() -> Vec<(f64, Vec<[f64; 2]>)> {
    vec![
        (0.1, vec![[0.9950, 0.0998], [-0.0912, 1.1965]]),
        (0.2, vec![[0.9801, 0.1987], [-0.1819, 1.1861]]),
        (0.3, vec![[0.9553, 0.2955], [1.5, -1.2], [-0.2715, 1.1689]]),
        (0.4, vec![[0.9211, 0.3894], [-0.3595, 1.1449]]),
        (0.5, vec![[-0.4455, 1.1142]]),
    ]
}

/// The lines the example prints for a posterior, numbers in Rust's round-trip form.
fn posterior(tracker: &SsaTracker<f64>, label: &str) -> Vec<String> {
    let map = tracker.map_hypothesis();
    let mut lines = vec![format!(
        "{label} hypotheses {} expected_cardinality {:?} map_weight {:?} map_cardinality {}",
        tracker.hypotheses().len(),
        tracker.expected_cardinality(),
        map.weight(),
        map.len()
    )];
    for t in map.tracks() {
        let (m, p) = (&t.state.mean, &t.state.covariance);
        lines.push(format!(
            "  track {} existence {:?} mean {:?} {:?} {:?} {:?} var {:?} {:?}",
            t.label.0,
            t.existence,
            m[0],
            m[1],
            m[2],
            m[3],
            p[(0, 0)],
            p[(1, 1)]
        ));
    }
    lines
}

/// Compares two lines word by word: numbers by their bits, other words as text.
fn same(c: &str, rust: &str) -> bool {
    let (a, b): (Vec<&str>, Vec<&str>) = (c.split_whitespace().collect(), rust.split_whitespace().collect());
    a.len() == b.len()
        && a.iter().zip(&b).all(|(x, y)| match (x.parse::<f64>(), y.parse::<f64>()) {
            (Ok(x), Ok(y)) => x.to_bits() == y.to_bits(),
            _ => x == y,
        })
}

fn assert_lines(c: &[&str], rust: &[String]) {
    assert_eq!(c.len(), rust.len(), "C:\n{}\nRust:\n{}", c.join("\n"), rust.join("\n"));
    for (c_line, rust_line) in c.iter().zip(rust) {
        assert!(same(c_line, rust_line), "C and Rust differ:\n  C:    {c_line}\n  Rust: {rust_line}");
    }
}

/// Runs `f` on a thread with room for trackers built on the stack (unoptimised builds copy them).
fn with_big_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new().stack_size(256 << 20).spawn(f).expect("thread").join().expect("no panic");
}

#[test]
fn c_example_prints_tracker_core_numbers_bit_for_bit() {
    with_big_stack(c_example_matches_rust);
}

fn c_example_matches_rust() {
    let exe = build_example();

    // A small planar scenario for the JSON part: fifty-birth-death, seed 1, two scans.
    let mut simulation = host_sim::sim::planar::preset("fifty-birth-death", 1).expect("preset");
    simulation.scans = 2;
    let scenario = simulation.run();
    let file = profile_dir().join("c-example/fifty-birth-death.json");
    scenario.save(&file).expect("save the scenario");

    let output = Command::new(&exe).arg(&file).output().expect("run the C example");
    assert!(output.status.success(), "the C example failed:\n{}", String::from_utf8_lossy(&output.stderr));
    let text = String::from_utf8(output.stdout).expect("UTF-8 output");
    let lines: Vec<&str> = text.lines().collect();

    // Rust, on the same input.
    let objects = [
        PriorObject { label: TrackLabel(0), state: gaussian([1.0, 0.0, 0.0, 1.0], 1e-3) },
        PriorObject { label: TrackLabel(1), state: gaussian([0.0, 1.2, -0.9128709291752769, 0.0], 1e-3) },
    ];
    let mut tracker = Box::new(
        SsaTracker::<f64>::new(config(), &[PriorHypothesis { weight: 1.0, objects: &objects }], 0.0).expect("tracker"),
    );
    let mut expected = vec![format!(
        "RFISST_SSA_F64 handle: {} bytes, aligned to {}",
        rfisst::rfisst_tracker_size(1),
        rfisst::rfisst_tracker_align(1)
    )];
    for (k, (time, zs)) in scans().into_iter().enumerate() {
        let zs: Vec<SVector<f64, 2>> = zs.into_iter().map(SVector::from).collect();
        tracker.step(time, &zs).expect("step");
        expected.extend(posterior(&tracker, &format!("scan {}", k + 1)));
    }
    let before = tracker.digest();
    let error = tracker.step(0.6, &[SVector::from([0.5, f64::NAN])]).expect_err("NaN measurement");
    assert_eq!(tracker.digest(), before);
    expected
        .push(format!("rejected: the tracker rejected the scan (the tracker is unchanged) ({error}); unchanged yes"));
    expected.push(
        "rejected: a size or count argument is wrong (dimension: the tracker's measurement dimension is 2)".into(),
    );
    let json_tracker =
        Box::new(host_sim::pipeline::digest::planar::tracker::<f64>(&scenario).expect("host-sim tracker"));
    expected.extend(posterior(&json_tracker, "json prior"));

    assert_lines(&lines, &expected);
    // The scans did something: two objects tracked, more than one hypothesis.
    assert!(text.contains("scan 5 hypotheses ") && text.contains("  track 1 existence "), "{text}");
}

/// The README's "From C" section shows the example's `main` as it is in the file this test builds.
#[test]
fn the_readme_shows_the_example_main_as_it_is() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let example = std::fs::read_to_string(root.join("bindings/c/examples/map_tracks.c")).expect("example");
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README");
    let main = example.find("int main(int argc").map(|at| example[at..].trim_end()).expect("a main");
    assert!(readme.contains(main), "README.md's From C section differs from bindings/c/examples/map_tracks.c");
}
