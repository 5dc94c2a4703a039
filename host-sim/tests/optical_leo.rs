//! The `optical-leo` preset (issue 31 item 5): a small one (6 objects, the first 6 minutes of twilight, half
//! of the objects unknown to the prior) is generated and run, and its unknown objects are born from
//! tracklets and confirmed.

mod common;

use host_sim::pipeline::{Profile, TrackerKind};
use host_sim::scenario::from_simulation::to_scenario;
use host_sim::sim::optical_leo::{OpticalLeoConfig, optical_leo_with};
use host_sim::sim::truth::Unknowns;

/// A small `optical-leo`: objects crossing the field in the first 6 minutes of frames.
fn small(seed: u64) -> host_sim::scenario::v2::Scenario3d {
    let config = OpticalLeoConfig {
        objects: 6,
        // Frames start when the Sun reaches −6° at the site, 1564 s after the epoch.
        duration: 1564.0 + 360.0,
        unknowns: Unknowns { missing_fraction: 0.5, breakup: 0 },
        ..OpticalLeoConfig::PRESET
    };
    let sim = optical_leo_with(seed, &config).expect("optical-leo simulates");
    to_scenario(&sim).expect("scenario").0
}

#[test]
fn a_small_optical_leo_forms_tracklets_and_confirms_its_births() {
    // The host profile's tracker is built on the stack in debug builds.
    let worker = std::thread::Builder::new().stack_size(1 << 30).spawn(small_run_check).expect("thread");
    worker.join().expect("the check passes");
}

fn small_run_check() {
    let scenario = small(3);
    assert!(scenario.births_from_tracklets_only(), "optical-leo's births come from tracklets only");
    let dir = common::TempDir::new("optical-leo");
    let (summary, clean) =
        host_sim::pipeline::orbital::run(&scenario, TrackerKind::Rfisst, Some(Profile::Host), true, &dir.0)
            .expect("run");
    assert!(clean, "every scan accepted");
    let births = &summary.births;
    assert_eq!(births.births_total, 3);
    assert!(summary.tracklets_formed >= 3, "tracklets formed: {}", summary.tracklets_formed);
    assert_eq!(births.births_confirmed, 3, "every unknown object confirmed");
    // Every confirmed born label is one of the three births (no false track).
    assert_eq!(summary.tracklet_births, Some(3));
    assert_eq!(births.false_tracks, Some(0));
}

#[test]
fn optical_leo_is_deterministic_and_its_telescope_sees_only_in_twilight() {
    let (a, b) = (small(5), small(5));
    assert_eq!(serde_json::to_string(&a).expect("json"), serde_json::to_string(&b).expect("json"));
    let first = a.scans.first().expect("frames").time;
    assert!((1564.0..1570.0).contains(&first), "the first frame at {first} s, not when the Sun is at −6°");
    assert!(a.scans.windows(2).all(|w| w[1].time - w[0].time == 2.0), "a frame every 2 s");
}

#[test]
fn the_partitioned_tracker_counts_the_tracklets_its_birth_cluster_forms() {
    let worker = std::thread::Builder::new().stack_size(1 << 28).spawn(partitioned_check).expect("thread");
    worker.join().expect("the check passes");
}

/// The same small scenario through the partitioned tracker (`run` chooses it for a catalogue larger than one
/// tracker's N): the preset's 12 × 4 tracklet cells do not fit a cluster's B = 32 and are refused at build
/// (they would never give a birth); with 8 × 4 the unclaimed measurements go to the birth cluster, whose pool
/// links them into tracklets, and each scan's report carries how many it formed.
fn partitioned_check() {
    use host_sim::partition::runner::{CLUSTER, build};
    use host_sim::pipeline::orbital::corrections::corrected_measurements;
    let mut scenario = small(3);
    let tracklets = scenario.birth.measured.as_mut().and_then(|m| m.tracklets.as_mut()).expect("tracklet births");
    assert!(tracklets.cells[0] * tracklets.cells[1] > CLUSTER.birth_cells);
    match build(TrackerKind::Rfisst, &scenario) {
        Ok(_) => panic!("tracklet cells beyond a cluster's B accepted"),
        Err(e) => assert!(e.to_string().contains("tracklet births: cells"), "{e}"),
    }
    let tracklets = scenario.birth.measured.as_mut().and_then(|m| m.tracklets.as_mut()).expect("tracklet births");
    tracklets.cells = [8, 4];
    let mut tracker = build(TrackerKind::Rfisst, &scenario).expect("partitioned");
    let mut formed = 0;
    for scan in &scenario.scans {
        let zs = corrected_measurements(&scenario, scan);
        formed += tracker.step(scan.sensor, scan.time, &zs).expect("every scan accepted").tracklets_formed;
    }
    assert!(formed >= 3, "tracklets formed by the birth cluster: {formed}");
}

/// Tracklet cells beyond the profile's free birth cells: `run` says so before it starts, with a shape that
/// fits, and writes nothing (the core would refuse the pool: no tracklet of it could give a birth).
#[test]
fn tracklet_cells_beyond_the_profiles_pool_are_refused_before_the_run_with_a_shape_that_fits() {
    let scenario = small(3);
    let dir = common::TempDir::new("optical-leo-refused");
    let out = dir.0.join("run");
    let refused = host_sim::pipeline::orbital::run(&scenario, TrackerKind::Rfisst, Some(Profile::Embedded), true, &out);
    let message = match refused {
        Ok(_) => panic!("12 × 4 tracklet cells accepted by the embedded profile's B = 8"),
        Err(e) => e.to_string(),
    };
    assert!(message.contains("tracklets.cells [12, 4]") && message.contains("8 free birth cells"), "{message}");
    assert!(message.contains("\"cells\": [2, 4]"), "{message}");
    assert!(!out.exists(), "nothing written");
}
