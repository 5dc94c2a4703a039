//! Issue 29: a gap of 36 hours between two passes of every object. Two station-kept GEO objects of
//! `optical-geo` seen by its telescope for 30 minutes, then not at all for 36 hours, then again for 30
//! minutes: the generated scenario is accepted (its bound is 48 h) and the tracker keeps every object.

use super::presets::{OpticalGeoConfig, geo_telescope, optical_geo_with};
use super::sensor::SensorSpec;
use super::ssa::{Plan, simulate};
use super::truth::Unknowns;
use crate::pipeline::TrackerKind;

/// Frames every 90 s for 30 minutes from `start` (s).
fn pass(start: f64) -> impl Iterator<Item = (f64, usize)> {
    (0..=20).map(move |k| (start + 90.0 * f64::from(k), 0))
}

#[test]
fn a_36_hour_gap_between_passes_keeps_every_object() {
    // The host profile's tracker is large: the CLI's stack (main.rs).
    std::thread::Builder::new().stack_size(512 << 20).spawn(check).expect("thread").join().expect("no panic");
}

fn check() {
    let seed = 3;
    let config = OpticalGeoConfig {
        singles: 2,
        sweepers: 0,
        clusters: 0,
        cluster_size: 0,
        duration: 90.0,
        cadence: 90.0,
        unknowns: Unknowns::default(),
    };
    let objects = optical_geo_with(seed, &config).expect("two GEO objects").objects;
    // With little clutter the store holds few tracks: each costs 6480 RK4 sub-steps over the gap.
    let telescope = SensorSpec { clutter_rate: 0.01, ..geo_telescope() };
    let gap = 36.0 * 3600.0;
    let second = 1800.0 + gap;
    let sim = simulate(Plan {
        name: "optical-geo-36h-gap".into(),
        seed,
        epoch: "2026-03-20T02:00:00Z".into(),
        duration: second + 1800.0,
        sensors: vec![telescope],
        objects,
        groups: Vec::new(),
        schedule: pass(0.0).chain(pass(second)).collect(),
        tracks: None,
        visible: None,
    })
    .expect("simulated");
    let (scenario, _) = crate::scenario::from_simulation::to_scenario(&sim).expect("the 36 h gap is within the bound");
    let times: Vec<f64> = scenario.scans.iter().map(|s| s.time).collect();
    assert!(times.windows(2).any(|w| w[1] - w[0] >= gap), "a 36 h gap between scans");
    let out = std::env::temp_dir().join(format!("host-sim-long-gap-{}", std::process::id()));
    let (summary, clean) =
        crate::pipeline::orbital::run(&scenario, TrackerKind::Homht, None, true, &out).expect("the run");
    let estimates = std::fs::read_to_string(out.join("estimates.csv")).expect("estimates.csv");
    let _ = std::fs::remove_dir_all(&out);
    assert!(clean, "{summary:?}");
    assert_eq!(summary.refused_scans.count, 0, "{summary:?}");
    assert_eq!(summary.numerical_drops.count, 0, "{summary:?}");
    assert_eq!((summary.true_final_cardinality, summary.final_map_cardinality), (Some(2), 2), "{summary:?}");
    assert_eq!((summary.label_switches, summary.births.false_tracks), (0, Some(0)), "{summary:?}");
    // At the last scan every object has a MAP estimate within the error bound (the last column).
    let last = format!("{},", scenario.scans.len() - 1);
    let rows: Vec<&str> = estimates.lines().filter(|l| l.starts_with(&last)).collect();
    assert_eq!(rows.len(), 2, "{estimates}");
    assert!(rows.iter().all(|r| r.ends_with(",true")), "{rows:?}");
    eprintln!(
        "36 h gap: in-view misses {}, largest scan {:.0} ms (debug build)",
        summary.in_view_misses_after_confirmation, summary.max_ms_per_scan
    );
}
