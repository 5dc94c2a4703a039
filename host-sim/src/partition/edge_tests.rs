//! The edge's fixed pool of cluster trackers (`tracker_core::partition::ClusterPool`, issue 30 item 2)
//! against this partition at the same capacities: the same digest (time, counters, birth cluster, each
//! cluster's id and core) after every scan, the same report, over scans with merges, births, exact and ε
//! splits, declined merges and clutter; and its refusals leave it unchanged.

use super::tests::{config, objects, on_large_stack, scan, with_birth_cell, z};
use super::*;
use nalgebra::SVector;
use tracker_core::partition::{BIRTH_CLUSTER, ClusterPool, PoolError};
use tracker_core::{ConstantVelocity, LinearConfig, PositionMeasurement, PriorObject};

/// The host's test partition (H = 256, N = 4, Z = 8, K = 64, B = 1).
type Host = tests::Partitioned;
/// The same capacities in a pool of at most 32 clusters and scans of at most 64 measurements.
type Edge = ClusterPool<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 2, 256, 4, 8, 64, 1, 32, 64>;

/// A scan's time and measurements.
type Scan = (f64, Vec<SVector<f64, 2>>);

/// The report fields both trackers give.
macro_rules! common {
    ($r:expr) => {{
        let r = $r;
        [
            r.clusters,
            r.largest_cluster,
            r.merged,
            r.merges_declined,
            r.split,
            r.born_clusters,
            r.unclaimed,
            r.quiet,
            r.clusters_with_measurements,
            r.hypotheses,
            r.lost_tracks,
        ]
    }};
}

/// Runs `scans` through both; checks the digests and reports after every scan; returns the host's reports.
fn both(
    config: LinearConfig<f64, 1>,
    objects: &[PriorObject<f64, 4>],
    epsilon: f64,
    scans: &[Scan],
) -> Vec<PartitionReport> {
    let mut host = Host::new(config.clone(), objects, 0.0, epsilon).expect("host");
    let mut edge = Box::new(Edge::new(config, objects, 0.0, epsilon).expect("edge"));
    assert_eq!(edge.digest(), host.digest(), "the prior");
    let mut reports = vec![];
    for (k, (time, zs)) in scans.iter().enumerate() {
        let want = host.step(&scan(*time), zs).expect("host step");
        let have = edge.step(&scan(*time), zs).expect("edge step");
        assert_eq!(common!(&have), common!(&want), "scan {k}");
        let masses = [have.merge_pruned_mass, have.step_pruned_mass, have.split_moved_mass];
        assert_eq!(
            masses.map(f64::to_bits),
            [want.merge_pruned_mass, want.step_pruned_mass, want.split_moved_mass].map(f64::to_bits),
            "scan {k}"
        );
        assert_eq!(edge.digest(), host.digest(), "scan {k}");
        let ids: Vec<u64> = edge.clusters().iter().map(|c| c.id()).collect();
        assert_eq!(ids, host.clusters().iter().map(|c| c.id.0).collect::<Vec<_>>(), "scan {k}");
        reports.push(want);
    }
    reports
}

/// A seeded scenario: `pairs` pairs of objects crossing each other, detected with probability 0.9 and
/// noise 0.3, two clutter returns a scan, and a new object from x = 50 after scan 5 (the birth cell's).
fn crossings(pairs: usize, scans: usize, seed: u64) -> (Vec<PriorObject<f64, 4>>, Vec<Scan>) {
    let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    let mut uniform = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut objects =
        objects(&(0..2 * pairs).map(|i| 100.0 * (i / 2) as f64 + 8.0 * (i % 2) as f64).collect::<Vec<_>>());
    // Each pair closes at 1.6 a scan: they cross near scan 5.
    for (i, o) in objects.iter_mut().enumerate() {
        o.state.mean[2] = if i % 2 == 0 { 0.8 } else { -0.8 };
    }
    let mut out = vec![];
    for k in 1..=scans {
        let t = k as f64;
        let mut zs = vec![];
        for o in &objects {
            if uniform() < 0.9 {
                let (x, y) = (o.state.mean[0] + o.state.mean[2] * t, o.state.mean[1]);
                zs.push(z(x + 0.3 * (uniform() - 0.5), y + 0.3 * (uniform() - 0.5)));
            }
        }
        if k > 5 && uniform() < 0.9 {
            zs.push(z(50.0 + (t - 5.0) + 0.2 * (uniform() - 0.5), 0.1 * (uniform() - 0.5)));
        }
        for _ in 0..2 {
            zs.push(z(400.0 * uniform() - 50.0, 10.0 * (uniform() - 0.5)));
        }
        out.push((t, zs));
    }
    (objects, out)
}

#[test]
fn the_edge_pool_steps_as_the_host_partition() {
    on_large_stack(|| {
        let (mut merged, mut split, mut born, mut declined) = (0, 0, 0, 0);
        for (seed, epsilon) in [(1, 0.0), (2, 0.0), (3, 0.05), (4, 0.05)] {
            let (objects, scans) = crossings(3, 14, seed);
            for r in both(with_birth_cell(config()), &objects, epsilon, &scans) {
                (merged, split, born, declined) =
                    (merged + r.merged, split + r.split, born + r.born_clusters, declined + r.merges_declined);
            }
        }
        // The scans are the partition's hard cases (the checks above are not vacuous).
        assert!(merged > 0 && split > 0 && born > 0, "merged {merged}, split {split}, born {born}");
        // Five objects 6 apart, each pair of neighbours sharing a measurement: a merge declined (N = 4).
        let xs = [0.0, 6.0, 12.0, 18.0, 24.0];
        let scans = [(1.0, vec![z(4.0, 0.0), z(10.0, 0.0), z(16.0, 0.0), z(22.0, 0.0)]), (2.0, vec![z(1.0, 0.0)])];
        let chain: usize = both(config(), &objects(&xs), 0.0, &scans).iter().map(|r| r.merges_declined).sum();
        assert_eq!(chain, 1);
        assert!(declined > 0, "the crossings declined merges too");
    });
}

#[test]
fn the_edge_pools_refusals_name_the_cluster_and_change_nothing() {
    on_large_stack(|| {
        let mut edge = Box::new(Edge::new(config(), &objects(&[0.0, 100.0]), 0.0, 0.0).expect("edge"));
        edge.step(&scan(1.0), &[z(1.0, 0.0), z(101.0, 0.0)]).expect("step");
        let before = edge.digest();
        let crowd: Vec<_> = (0..9).map(|i| z(102.0 + 0.1 * f64::from(i), 0.0)).collect();
        let error = edge.step(&scan(2.0), &crowd).unwrap_err();
        assert_eq!(error, PoolError::TooManyMeasurements { cluster: 1, received: 9, capacity: 8 });
        let far: Vec<_> = (0..9).map(|i| z(500.0 + f64::from(i), 0.0)).collect();
        let error = edge.step(&scan(2.0), &far).unwrap_err();
        assert_eq!(error, PoolError::TooManyMeasurements { cluster: BIRTH_CLUSTER, received: 9, capacity: 8 });
        assert_eq!(error.to_string(), "the birth cluster: 9 measurements in its gates, more than its capacity Z = 8");
        let wide: Vec<_> = (0..65).map(|i| z(f64::from(i), 0.0)).collect();
        assert_eq!(edge.step(&scan(2.0), &wide).unwrap_err(), PoolError::ScanTooLarge { received: 65, capacity: 64 });
        assert!(matches!(edge.step(&scan(1.0), &[]), Err(PoolError::Scan(_))));
        assert_eq!(edge.digest(), before);
        edge.step(&scan(2.0), &[z(2.0, 0.0)]).expect("it goes on");
        // A pool of two clusters cannot take a third from the birth cluster: refused, unchanged.
        type Two = ClusterPool<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 2, 256, 4, 8, 64, 1, 2, 8>;
        let mut two = Box::new(Two::new(with_birth_cell(config()), &objects(&[0.0, 100.0]), 0.0, 0.0).expect("pool"));
        let before = two.digest();
        let error = two.step(&scan(1.0), &[z(1.0, 0.0), z(101.0, 0.0), z(50.0, 0.0)]).unwrap_err();
        assert_eq!(error, PoolError::PoolFull { capacity: 2 });
        assert_eq!(two.digest(), before);
        assert!(
            Two::new(config(), &objects(&[0.0, 1.0, 2.0]), 0.0, 0.0)
                .is_err_and(|e| e == PoolError::PoolFull { capacity: 2 })
        );
    });
}

/// The edge pool at the catalogue's cluster capacities ([`runner::CLUSTER`]), in a pool of 160 clusters and
/// scans of 64 measurements.
type OrbitalEdge<G, const D: usize> = ClusterPool<
    f64,
    tracker_core::TwoBodyJ2<f64>,
    G,
    6,
    D,
    { runner::CLUSTER.hypotheses },
    { runner::CLUSTER.objects },
    { runner::CLUSTER.measurements },
    { runner::CLUSTER.tracks },
    { runner::CLUSTER.birth_cells },
    160,
    64,
>;

/// Runs `scenario` through `run-catalogue`'s partitioned tracker and the edge pool of its capacities;
/// checks the reports after every scan and the digests after most; returns the scans and the merges,
/// births and splits.
fn orbital<G: crate::pipeline::orbital::tracker::ScenarioNetwork<D>, const D: usize>(
    scenario: &crate::scenario::v2::Scenario3d,
) -> [usize; 4] {
    use crate::pipeline::orbital::{corrections, tracker};
    let (config, prior) = tracker::config3d::<G, D, { runner::CLUSTER.birth_cells }>(
        scenario,
        crate::pipeline::tracker::TrackerKind::Rfisst,
    )
    .expect("config");
    let objects = prior[0].1.as_slice();
    let mut host = runner::Partitioned::<G, D>::new(config.clone(), objects, scenario.prior.time, 0.0).expect("host");
    let mut edge = Box::new(OrbitalEdge::<G, D>::new(config, objects, scenario.prior.time, 0.0).expect("edge"));
    let mut counts = [0; 4];
    for (k, scan) in scenario.scans.iter().enumerate() {
        let zs: Vec<SVector<f64, D>> =
            corrections::corrected_measurements(scenario, scan).iter().map(|z| tracker::padded::<D>(z)).collect();
        let geometry = tracker_core::sensor::ScanGeometry { sensor: scan.sensor, time: scan.time, observer: None };
        let want = host.step(&geometry, &zs).expect("host step");
        let have = edge.step(&geometry, &zs).expect("edge step");
        assert_eq!(common!(&have), common!(&want), "scan {k}");
        // The whole state's digest at every scan that merged, split or gave birth, and every tenth.
        if k % 10 == 0 || want.merged + want.split + want.born_clusters > 0 || k + 1 == scenario.scans.len() {
            assert_eq!(edge.digest(), host.digest(), "scan {k}");
        }
        counts = [counts[0] + 1, counts[1] + want.merged, counts[2] + want.born_clusters, counts[3] + want.split];
    }
    counts
}

/// The 24-object fixture catalogue seen by the two radars for 40 minutes, through `run-catalogue`'s
/// partition and the edge pool: the same bits at every scan.
#[test]
fn the_edge_pool_tracks_a_catalogue_as_the_host_partition() {
    use crate::scenario::from_catalogue::{Request, generate_screened};
    let fixtures = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures");
    let (catalogue, sensors) = (format!("{fixtures}/catalogue_leo.tle"), format!("{fixtures}/sensors_radar.json"));
    let request = Request {
        catalogue: std::path::Path::new(&catalogue),
        sensors: std::path::Path::new(&sensors),
        start: "2026-03-20T00:00:00Z",
        duration_hours: 2.0 / 3.0,
        seed: 5,
    };
    let (scenario, _, _) = generate_screened(request).expect("scenario");
    on_large_stack(move || {
        let [scans, merged, born, split] = crate::with_measurement!(scenario.measurement, orbital, (&scenario));
        assert!(scans > 200, "{scans} scans");
        eprintln!("catalogue: {scans} scans, {merged} merges, {born} births, {split} splits");
    });
}

/// A smaller `radar-leo` (20 single objects and 8 crossing pairs over an hour) with a third of its
/// objects unknown to the prior and a break-up of six fragments: births from the measurements, and crossing
/// objects and fragments close enough to share gates. (`cargo run --release -p benches --example edge_pool`
/// runs the whole preset, 2,161 scans, and compares the final digests.)
#[test]
fn the_edge_pool_starts_and_merges_tracks_as_the_host_partition() {
    use crate::scenario::from_simulation::to_scenario;
    use crate::sim::presets::{RadarLeoConfig, radar_leo_with};
    let unknowns = crate::sim::truth::Unknowns { missing_fraction: 0.3, breakup: 6 };
    let config =
        RadarLeoConfig { singles: 20, pairs: 8, duration: 3600.0, min_passes: 1, unknowns, ..RadarLeoConfig::PRESET };
    let sim = radar_leo_with(3, &config).expect("simulation");
    let (scenario, _) = to_scenario(&sim).expect("scenario");
    on_large_stack(move || {
        let [scans, merged, born, split] = crate::with_measurement!(scenario.measurement, orbital, (&scenario));
        eprintln!("radar-leo: {scans} scans, {merged} merges, {born} births, {split} splits");
        assert!(born > 0 && merged > 0, "{scans} scans, {merged} merges, {born} births, {split} splits");
    });
}

/// Two objects 100 apart, the second never detected: with track loss after 3 scans in view unseen, its
/// track is dropped at the third scan, and both trackers count it.
#[test]
fn a_lost_track_is_dropped_and_counted_as_in_the_edge_pool() {
    on_large_stack(|| {
        let mut config = config();
        config.track_loss = tracker_core::TrackLoss::AfterUnseenScans(core::num::NonZeroU16::new(3).expect("3"));
        let scans: Vec<Scan> = (1..=5).map(|k| (k as f64, vec![z(k as f64, 0.0)])).collect();
        let lost: Vec<usize> =
            both(config, &objects(&[0.0, 100.0]), 0.0, &scans).iter().map(|r| r.lost_tracks).collect();
        assert_eq!(lost, [0, 0, 1, 0, 0]);
    });
}
