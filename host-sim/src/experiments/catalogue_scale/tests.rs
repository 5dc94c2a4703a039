//! The experiment on a small catalogue: every key of `scale.json`, the same figures whatever the thread
//! count, a decaying element set dropped and counted.

use super::*;
use crate::io::catalogue::CatalogueEntry;

fn temp(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("rfisst-catalogue-scale-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn catalogue(objects: usize, seed: u64) -> Vec<CatalogueEntry> {
    let epoch = crate::io::catalogue::parse_omm_epoch(START).expect("epoch");
    let jd = crate::sim::time::parse_iso8601(START).expect("jd");
    crate::sim::population::synthetic_catalogue(objects, seed, epoch, jd).expect("catalogue").entries
}

/// `scale.json` of a run on `threads` threads, as JSON, and the run's report.
fn run_with(tag: &str, entries: Vec<CatalogueEntry>, hours: f64, threads: usize) -> (serde_json::Value, ScaleReport) {
    run_skip(tag, entries, hours, threads, false)
}

/// As [`run_with`], stepping every cluster at every scan when `every` (no view skip).
fn run_skip(
    tag: &str,
    entries: Vec<CatalogueEntry>,
    hours: f64,
    threads: usize,
    every: bool,
) -> (serde_json::Value, ScaleReport) {
    let dir = temp(tag);
    let settings = Settings {
        objects: entries.len(),
        hours,
        seed: 3,
        threads: Some(threads),
        quiet: true,
        step_every_cluster: every,
        weight_floor_decades: Some(9),
        lost_after_unseen_scans: Some(8),
    };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).stack_size(256 << 20).build().expect("pool");
    let report = pool.install(|| run_on(&dir, &settings, threads, entries, Instant::now())).expect("run");
    let text = std::fs::read_to_string(dir.join("scale.json")).expect("scale.json");
    for plot in ["cost_per_scan.png", "cluster_sizes.png"] {
        assert!(dir.join(plot).is_file(), "{plot}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    (serde_json::from_str(&text).expect("JSON"), report)
}

/// The figures that do not depend on the wall clock or the thread count.
fn deterministic(mut json: serde_json::Value) -> serde_json::Value {
    let object = json.as_object_mut().expect("object");
    for key in ["wall_s", "realtime_factor", "peak_rss_mib", "ms_per_scan_mean", "ms_per_scan_p99", "ms_per_scan_max"] {
        assert!(object.remove(key).is_some(), "{key}");
    }
    for key in ["cpu_s", "cpu_ms_per_scan_mean", "cpu_ms_per_scan_p99", "total_wall_s", "threads", "rss_mib_by_hour"] {
        assert!(object.remove(key).is_some(), "{key}");
    }
    json
}

#[test]
fn a_small_catalogue_writes_every_key_and_one_two_and_four_threads_agree() {
    let (json, report) = run_with("one", catalogue(40, 3), 0.1, 1);
    for key in [
        "objects",
        "scans",
        "observations",
        "hours",
        "threads",
        "wall_s",
        "realtime_factor",
        "peak_rss_mib",
        "ms_per_scan_mean",
        "ms_per_scan_p99",
        "clusters_max",
        "largest_cluster",
        "births_total",
        "births_confirmed",
        "false_tracks",
        "mean_gospa",
        "observed_objects",
        "observed_median_error_km",
        "unobserved_median_error_km",
        "label_switches",
        "dropped_objects",
    ] {
        assert!(json.get(key).is_some(), "{key} missing from scale.json");
    }
    // 0.1 h of a scan every 20 s / 3 sensors: 55 scans; some objects seen, none refused.
    assert_eq!((report.objects, report.scans, report.threads), (40, 55, 1));
    assert_eq!(report.rejected_scans, 0);
    assert!(report.observations > 0 && report.observed_objects > 0, "{report:?}");
    assert!(report.clusters_max >= 35 && report.largest_cluster >= 1, "{report:?}");
    assert_eq!(report.births_total, 1, "2 % of 40");
    assert!(report.mean_gospa.is_finite() && report.scored_scans >= 6, "{report:?}");
    let expected = deterministic(json);
    assert_eq!(deterministic(run_with("two", catalogue(40, 3), 0.1, 2).0), expected);
    assert_eq!(deterministic(run_with("four", catalogue(40, 3), 0.1, 4).0), expected);
}

#[test]
fn an_element_set_sgp4_cannot_propagate_is_dropped_and_counted() {
    let mut entries = catalogue(10, 5);
    // A decayed object: its mean perigee inside the Earth.
    let mut decayed = entries[0].clone();
    decayed.norad_id = 99_999;
    decayed.eccentricity = 0.9;
    entries.push(decayed);
    let (_, report) = run_with("dropped", entries, 0.05, 1);
    assert_eq!((report.dropped_objects, report.objects), (1, 10));
}

#[test]
fn the_view_skip_leaves_most_clusters_out_of_a_scan_and_tracks_as_stepping_every_cluster() {
    let (_, skip) = run_skip("skip", catalogue(60, 4), 0.25, 1, false);
    let (_, every) = run_skip("every", catalogue(60, 4), 0.25, 1, true);
    assert!(skip.view_skip && !every.view_skip);
    // Every cluster stepped at every scan without the skip; with it, those within a sensor's range window.
    assert!(every.clusters_stepped_mean >= 55.0, "{every:?}");
    assert!(skip.clusters_stepped_mean < 0.5 * every.clusters_stepped_mean, "{skip:?}");
    assert!(skip.observations > 0 && skip.observed_objects >= 3, "{skip:?}");
    // The same objects observed, births and tracks; the errors differ only by the longer predictions.
    let same =
        |r: &ScaleReport| (r.observations, r.observed_objects, r.births_confirmed, r.false_tracks, r.label_switches);
    assert_eq!(same(&skip), same(&every));
    assert!((skip.mean_gospa - every.mean_gospa).abs() <= 1e-3 * every.mean_gospa, "{skip:?} {every:?}");
    let (a, b) = (skip.observed_median_error_km.expect("observed"), every.observed_median_error_km.expect("observed"));
    assert!((a - b).abs() < 1e-3, "observed median error {a} km with the skip, {b} km without");
    assert_ne!(skip.digest, every.digest, "not bit-identical: the skipped clusters are predicted in longer steps");
}

#[test]
fn a_track_the_view_skip_clears_stays_out_of_that_sensors_view_until_its_clearance_ends() {
    use crate::partition::view::{clear_for, sights};
    use tracker_core::model::{Measure, MotionModel};
    // 60 objects over 1.5 h on a 5 s grid; a clearance is asked every minute for each sensor that does not
    // see the object, and the object must stay out of that sensor's view on every grid time it covers.
    let (step, points, every) = (5.0, 1080, 12);
    let mut world = world::World::new(catalogue(60, 7), 1.5, 7).expect("world");
    let scenario = world.scenario().expect("scenario");
    let (config, prior) =
        config3d::<Radars, 3, { CLUSTER.birth_cells }>(&scenario, TrackerKind::Rfisst).expect("config");
    let t0 = scenario.prior.time;
    let placed: Vec<_> = (0..points).map(|k| sights(&config, t0 + step * k as f64)).collect();
    assert_eq!(placed[0].len(), 3, "three ground sensors");
    let (mut asked, mut cleared, mut entered, mut covered) = (0, 0, 0, 0.0);
    for object in &prior[0].1 {
        let mut x = object.state.mean;
        let mut seen = vec![[false; 3]; points];
        let mut means = Vec::with_capacity(points);
        for (k, sights) in placed.iter().enumerate() {
            for s in sights {
                seen[k][s.sensor] = s.field_of_view.sees(&s.model, &s.model.measure(&x));
            }
            means.push(x);
            x = config.motion.propagate(&x, step).expect("propagates").state;
        }
        entered += usize::from(seen.iter().any(|s| s.contains(&true)));
        for k in (0..points).step_by(every) {
            for s in &placed[k] {
                if seen[k][s.sensor] {
                    continue;
                }
                asked += 1;
                let clear = clear_for(s, &means[k], ground_closing_speed);
                let last = k + (clear / step).floor() as usize;
                cleared += usize::from(clear > 0.0);
                covered += clear;
                if let Some(j) = (k..=last.min(points - 1)).find(|&j| seen[j][s.sensor]) {
                    panic!(
                        "cleared for {clear} s at {} s, in view of sensor {} at {} s",
                        k as f64 * step,
                        s.sensor,
                        j as f64 * step
                    );
                }
            }
        }
    }
    // Not vacuous: some objects come into view, and most questions out of view get a clearance.
    assert!(entered >= 5, "{entered} objects enter a field of view");
    assert!(cleared * 10 >= asked * 8, "{cleared} clearances of {asked} questions");
    eprintln!(
        "{cleared} of {asked} cleared, {:.0} s on average; {entered} objects in view at some time",
        covered / asked as f64
    );
}

#[test]
fn a_clearance_from_a_nearby_tracks_gaps_is_never_longer_than_its_own_and_means_out_of_view() {
    use crate::partition::view::{NEAR_KM, clear_for, clear_near, sights};
    use tracker_core::model::{Measure, MotionModel};
    use tracker_core::tracker::in_field_of_view;
    // Versions of each object of a catalogue, up to 13 km apart in position and velocity, take their
    // clearances from the first version's gaps while within NEAR_KM of it (docs/maths.md §13.2), at six
    // times a minute apart; a version with a clearance from a sensor is out of its view as the gate decides.
    let mut world = world::World::new(catalogue(60, 7), 0.2, 7).expect("world");
    let scenario = world.scenario().expect("scenario");
    let (config, prior) =
        config3d::<Radars, 3, { CLUSTER.birth_cells }>(&scenario, TrackerKind::Rfisst).expect("config");
    let (mut reused, mut seen, mut shorter) = (0, 0, 0.0f64);
    for minute in 0..6 {
        let dt = 60.0 * f64::from(minute);
        for s in &sights(&config, scenario.prior.time + dt) {
            for object in &prior[0].1 {
                let start = config.motion.propagate(&object.state.mean, dt).expect("propagates").state;
                let mut near = None;
                for k in 0..10 {
                    let f = f64::from(k) / 6.0;
                    let offset = nalgebra::SVector::<f64, 6>::from([6.0, -5.0, 4.0, 1e-3, -2e-3, 0.0]) * f;
                    let x = start + offset;
                    let own = clear_for(s, &x, ground_closing_speed);
                    let from_near = clear_near(s, &x, ground_closing_speed, &mut near);
                    assert!(from_near <= own * (1.0 + 1e-12), "sensor {}: {from_near} s > {own} s", s.sensor);
                    // Each gap moves by at most twice the shift, closed at 0.52 km/s at least.
                    assert!(from_near >= own - 2.0 * NEAR_KM / 0.52 - 1e-9, "{from_near} s ≪ {own} s");
                    let state = tracker_core::Gaussian { mean: x, covariance: object.state.covariance };
                    let in_view = in_field_of_view(&s.field_of_view, &s.model, &state, &s.model.measure(&x));
                    assert!(!(in_view && (own > 0.0 || from_near > 0.0)), "sensor {}: cleared in view", s.sensor);
                    seen += usize::from(in_view);
                    reused += usize::from(k > 0 && offset.norm() <= NEAR_KM && from_near > 0.0);
                    shorter = shorter.max(own - from_near);
                }
            }
        }
    }
    assert!(reused > 2000 && seen > 10, "{reused} clearances from a nearby track's gaps, {seen} in view");
    eprintln!("{reused} clearances reused, at most {shorter:.2} s shorter; {seen} in view");
}

#[test]
fn a_coasting_cluster_is_out_of_view_and_gates_nothing_as_the_full_gate_from_its_rest_decides_it() {
    use crate::partition::route::{Skip, coast, distance, gate};
    use crate::partition::view::sights;
    use crate::partition::window::Indexed;
    use nalgebra::SVector;
    use tracker_core::Track;
    // A cluster of two versions (3 km apart) of each object of a catalogue, at rest at the prior's time, is
    // gated at every scan by the full gate from its rest and from its means alone (docs/maths.md §13.2),
    // chained from its last coast while it coasts. Whenever the coast clears it, the full gate finds no
    // track in view and no measurement; a coast from the rest gives the full gate's means and clearances.
    let mut world = world::World::new(catalogue(40, 7), 0.1, 7).expect("world");
    let scenario = world.scenario().expect("scenario");
    let (config, prior) =
        config3d::<Radars, 3, { CLUSTER.birth_cells }>(&scenario, TrackerKind::Rfisst).expect("config");
    let t0 = scenario.prior.time;
    let clusters: Vec<Vec<Track<f64, 6>>> = (prior[0].1.iter())
        .map(|o| {
            let mut other = o.state;
            other.mean[0] += 3.0;
            vec![
                Track { label: o.label, state: o.state, ..Default::default() },
                Track { state: other, ..Default::default() },
            ]
        })
        .collect();
    let mut coasts: Vec<Option<(f64, Vec<SVector<f64, 6>>)>> = vec![None; clusters.len()];
    let (mut fresh, mut chained, mut in_view, mut hits, mut last) = (0, 0, 0, 0, t0);
    for k in 0..world.scans() {
        let scan = world.scan(k).expect("scan");
        let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let placed = tracker_core::tracker::place_scan(&config, &geometry, last, &scan.measurements, usize::MAX)
            .expect("placed");
        last = scan.time;
        let index = Indexed::new(&scan.measurements, distance::<Radars, 6, 3>(&placed.model));
        let sights = sights(&config, scan.time);
        let skip = Skip { sights: &sights, speed: ground_closing_speed, scanning: scan.sensor };
        for (tracks, kept) in clusters.iter().zip(&mut coasts) {
            let full = gate(&config.motion, &placed, tracks, scan.time - t0, &index, config.gate, Some(skip));
            (in_view, hits) = (in_view + usize::from(full.in_view), hits + full.measurements.len());
            let from = kept.as_ref().map(|(time, means)| (&means[..], scan.time - time));
            let Some(coasted) = coast(&config.motion, tracks, scan.time - t0, from, &skip) else {
                *kept = None;
                continue;
            };
            assert!(!full.in_view && full.measurements.is_empty(), "scan {k}: coasting, but {full:?}");
            let means = coasted.coasted.expect("means");
            if kept.is_none() {
                let predicted: Vec<_> = full.predicted.expect("predicted").iter().map(|g| g.mean).collect();
                assert_eq!((&means, &coasted.clear_for), (&predicted, &full.clear_for), "scan {k}");
                fresh += 1;
            } else {
                chained += 1;
            }
            *kept = Some((scan.time, means));
        }
    }
    // Not vacuous: tracks in view gating measurements, coasts from the rest and chained ones.
    assert!(in_view >= 20 && hits >= 20 && fresh >= 50 && chained >= 1000, "{in_view} {hits} {fresh} {chained}");
    eprintln!("{in_view} in view, {hits} measurements gated; {fresh} coasts from the rest, {chained} chained");
}

#[test]
fn a_cluster_coasts_only_while_its_state_is_at_most_the_coast_age_old() {
    // Half an hour of a 40-object catalogue: clusters coast, and each coast ends by MAX_COAST_AGE_S
    // (docs/maths.md §13.2), so the core's next prediction from a cluster's state stays short.
    use crate::partition::route::MAX_COAST_AGE_S;
    let worker = std::thread::Builder::new().stack_size(256 << 20).spawn(|| {
        let mut world = world::World::new(catalogue(40, 7), 0.5, 7).expect("world");
        let scenario = world.scenario().expect("scenario");
        let (config, prior) =
            config3d::<Radars, 3, { CLUSTER.birth_cells }>(&scenario, TrackerKind::Rfisst).expect("config");
        let mut tracker = Partitioned::<Radars, 3>::new(config, &prior[0].1, scenario.prior.time, 0.0)
            .expect("tracker")
            .with_view_skip(ground_closing_speed);
        let (mut coasting, mut oldest) = (0usize, 0.0f64);
        for k in 0..world.scans() {
            let scan = world.scan(k).expect("scan");
            let geometry = ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
            tracker.step(&geometry, &scan.measurements).expect("step");
            for c in tracker.clusters() {
                if let Some(coast) = &c.coast {
                    coasting += 1;
                    oldest = oldest.max(coast.time - c.rest.time());
                }
            }
        }
        (coasting, oldest)
    });
    let (coasting, oldest) = worker.expect("thread").join().expect("run");
    assert!(coasting >= 1000, "coasting clusters: {coasting}");
    assert!((0.5 * MAX_COAST_AGE_S..=MAX_COAST_AGE_S).contains(&oldest), "oldest coasting state: {oldest} s");
}
