//! Catalogues larger than a scenario file (issue 30 item 4): a streamed catalogue draws exactly the held
//! scenario's scans and truth, a streamed run scores as the held run, and a request too large for a file is
//! streamed by `run-catalogue` and refused, with the reason, by `generate catalogue`.

use host_sim::pipeline::{RunOptions, TrackerKind, run, run_streamed};
use host_sim::scenario::AnyScenario;
use host_sim::scenario::from_catalogue::{Generation, Request, generate_or_stream, generate_screened, stream};
use host_sim::scenario::v2::Scenario3d;
use serde_json::Value;
use std::path::Path;

mod common;
use common::{TempDir, host_sim, ok, p, read};

const CATALOGUE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/catalogue_leo.tle");
const RADARS: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/sensors_radar.json");
const TELESCOPE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/sensors_telescope.json");
const START: &str = "2026-03-20T00:00:00Z";

fn request<'a>(catalogue: &'a Path, sensors: &'a str, duration_hours: f64) -> Request<'a> {
    Request { catalogue, sensors: Path::new(sensors), start: START, duration_hours, seed: 5 }
}

#[test]
fn a_streamed_catalogue_draws_the_held_scenarios_scans_and_truth() {
    let catalogue = Path::new(CATALOGUE);
    // Radars, and a telescope over six hours (scans only while its site is dark, sunlit objects only).
    for (sensors, hours) in [(RADARS, 1.0), (TELESCOPE, 6.0)] {
        let (held, figures, dropped) = generate_screened(request(catalogue, sensors, hours)).expect("held");
        let mut streamed = stream(request(catalogue, sensors, hours)).expect("stream");
        let truth = held.truth.clone().expect("truth");
        assert_eq!(streamed.scans(), held.scans.len());
        for k in 0..streamed.scans() {
            assert_eq!(streamed.time(k), held.scans[k].time);
            let (scan, scan_truth) = streamed.scan(k).expect("scan");
            assert_eq!(scan, held.scans[k], "{sensors}: scan {k}");
            assert_eq!(scan_truth, truth.scans[k], "{sensors}: truth of scan {k}");
        }
        assert!(streamed.scan(0).is_err(), "a scan is drawn once, in order");
        assert!(figures.measurements > 50, "{sensors}: {} measurements", figures.measurements);
        let (configuration, streamed_dropped) = streamed.into_parts();
        assert_eq!(streamed_dropped, dropped);
        // The configuration, prior and description are the held scenario's; only its scans are not held.
        let truth =
            Some(host_sim::scenario::v2::Truth3dSpec { scans: truth.scans, ..configuration.truth.expect("truth") });
        assert_eq!(Scenario3d { scans: held.scans.clone(), truth, ..configuration }, held, "{sensors}");
    }
}

/// A summary without the figures of the machine (wall-clock times, memory).
fn figures(path: &Path) -> serde_json::Map<String, Value> {
    let mut summary: serde_json::Map<String, Value> = serde_json::from_str(&read(path)).expect("summary");
    summary.retain(|key, _| !key.contains("ms_per_scan") && !key.contains("resident"));
    summary
}

/// The rows of `estimates.csv` (after its header) whose scan is in `scans`, or every row.
fn rows(path: &Path, scans: Option<&[usize]>) -> Vec<String> {
    read(path)
        .lines()
        .skip(1)
        .filter(|row| {
            let scan: usize = row.split(',').next().and_then(|s| s.parse().ok()).expect("scan column");
            scans.is_none_or(|s| s.contains(&scan))
        })
        .map(str::to_string)
        .collect()
}

/// `catalogue` over `hours` with the radars: the held run and the streamed run give the same figures; the
/// streamed `estimates.csv` holds the held one's rows at the first scan, the first of each hour and the
/// last; its `scenario.json` holds the held scans without truth.
fn streamed_run_scores_as_held(catalogue: &Path, hours: f64, tag: &str) {
    let dir = TempDir::new(tag);
    let options = RunOptions {
        tracker: TrackerKind::Rfisst,
        profile: None,
        reference: Default::default(),
        max_hypotheses_out: 0,
        quiet: true,
    };
    let (held, _, _) = generate_screened(request(catalogue, RADARS, hours)).expect("held");
    let scans = held.scans.len();
    let hour = held.scans.iter().position(|s| s.time >= 3600.0);
    let (held_out, streamed_out) = (dir.join("held"), dir.join("streamed"));
    let (held_summary, clean) = run(&AnyScenario::V2(Box::new(held.clone())), &options, &held_out).expect("held run");
    assert!(clean);
    let streamed_run = stream(request(catalogue, RADARS, hours)).expect("stream");
    let (streamed_summary, clean, dropped) = run_streamed(streamed_run, &options, &streamed_out).expect("streamed");
    assert!(clean && dropped.count == 0);
    assert_eq!(streamed_summary.scans, held_summary.scans);
    assert_eq!(figures(&streamed_out.join("summary.json")), figures(&held_out.join("summary.json")));
    let snapshots: Vec<usize> = [Some(0), hour, Some(scans - 1)].into_iter().flatten().collect();
    let expected = rows(&held_out.join("estimates.csv"), Some(&snapshots));
    assert!(!expected.is_empty());
    assert_eq!(rows(&streamed_out.join("estimates.csv"), None), expected);
    let written = Scenario3d::load(&streamed_out.join("scenario.json")).expect("scenario.json");
    assert_eq!(written.scans, held.scans);
    assert!(written.truth.is_none());
    assert!(streamed_out.join("tracks.oem").is_file());
}

/// Runs `f` on a thread with the stack `main` gives the trackers.
fn on_a_large_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new().stack_size(512 << 20).spawn(f).expect("thread").join().expect("no panic");
}

#[test]
fn a_streamed_run_scores_as_the_held_run() {
    // 24 objects for 70 minutes: one tracker; the snapshots at 0, 1 h and the end.
    on_a_large_stack(|| streamed_run_scores_as_held(Path::new(CATALOGUE), 70.0 / 60.0, "stream-one"));
}

#[test]
fn a_streamed_partitioned_run_scores_as_the_held_run() {
    // 300 objects (more than one tracker's N): the partitioned tracker.
    let dir = TempDir::new("stream-partitioned-catalogue");
    let catalogue = dir.join("300.json");
    ok(host_sim(&["generate", "synthetic-catalogue", "--objects", "300", "--seed", "4", "--out", p(&catalogue)]));
    on_a_large_stack(move || streamed_run_scores_as_held(&catalogue, 0.1, "stream-partitioned"));
    drop(dir);
}

#[test]
fn a_catalogue_too_large_for_a_scenario_file_is_streamed() {
    let dir = TempDir::new("stream-large");
    let catalogue = dir.join("6000.json");
    ok(host_sim(&["generate", "synthetic-catalogue", "--objects", "6000", "--seed", "1", "--out", p(&catalogue)]));
    // 6,000 objects x 361 scans: about 280 MiB as a scenario file.
    let request = request(&catalogue, RADARS, 1.0);
    let Ok(Generation::Streamed(streamed)) = generate_or_stream(request) else { panic!("not streamed") };
    assert_eq!((streamed.objects(), streamed.scans()), (6000, 361));
    assert_eq!(streamed.scenario().prior.hypotheses[0].objects.len(), 6000);
    assert!(streamed.scenario().scans.is_empty());
    let Err(e) = generate_screened(request) else { panic!("a held scenario this large is refused") };
    assert!(e.to_string().contains("run-catalogue draws such a run as it goes"), "{e}");
    // A request that fits is held, its scans beyond one tracker's 32 measurements (the partitioned tracker
    // shares them among its clusters).
    let small = Request { duration_hours: 0.01, ..request };
    let Ok(Generation::Held(held)) = generate_or_stream(small) else { panic!("not held") };
    assert!(held.1.max_measurements > 32, "{} measurements at most", held.1.max_measurements);
}

#[test]
fn a_catalogue_one_tracker_holds_keeps_its_scans_within_the_trackers_limit() {
    let dir = TempDir::new("stream-cap");
    // The 24-object fixture with 40 clutter returns a scan expected: refused, held or streamed.
    let mut sensors: Value = serde_json::from_str(&read(Path::new(RADARS))).expect("sensors");
    sensors["sensors"][0]["clutter_rate"] = 40.0.into();
    let cluttered = dir.join("cluttered.json");
    std::fs::write(&cluttered, sensors.to_string()).expect("write");
    let request = request(Path::new(CATALOGUE), p(&cluttered), 0.1);
    let Err(e) = generate_screened(request) else { panic!("more than 32 measurements a scan") };
    assert!(e.to_string().contains("would carry more than 32 measurements (the tracker's limit)"), "{e}");
    let mut streamed = stream(request).expect("stream");
    let refused = (0..streamed.scans()).find_map(|k| streamed.scan(k).err()).expect("a scan is refused");
    assert!(refused.to_string().contains("would carry more than 32 measurements"), "{refused}");
}
