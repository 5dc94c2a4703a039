//! The partition's checks (issue 30): exactness against one core tracker where objects never interact and
//! through a merge, bit-identical results whatever the thread count (in one reused core on one thread), a
//! cluster at rest reading as its core, a cluster's Z overflow as a typed error naming it, and the exact and
//! ε splits.

use super::marginal::{self, ObjectPosterior};
use super::*;
use nalgebra::{SMatrix, SVector};
use std::collections::BTreeMap;
use tracker_core::config::ChildGeneration;
use tracker_core::sensor::ScanGeometry;
use tracker_core::{
    BirthDetection, BirthEvents, BirthModel, Gaussian, LinearConfig, LinearTracker, PriorHypothesis, PriorObject,
    Region, TrackLabel,
};

/// Clusters: H = 256, N = 4, Z = 8, K = 64, one birth cell.
pub(super) type Partitioned = PartitionedTracker<
    tracker_core::ConstantVelocity<f64>,
    tracker_core::PositionMeasurement<f64>,
    4,
    2,
    256,
    4,
    8,
    64,
    1,
>;
/// One tracker of every object, large enough never to prune in these scenarios.
type Single = LinearTracker<f64, 1024, 8, 16, 1024, 1>;

pub(super) fn config() -> LinearConfig<f64, 1> {
    let mut config = tracker_core::examples::config();
    config.sensor.field_of_view = Region::Everywhere { volume: 1e6 };
    config.gate = Some(16.0);
    config.children = ChildGeneration::Exhaustive { max_children_per_scan: 100_000 };
    config
}

pub(super) fn with_birth_cell(mut config: LinearConfig<f64, 1>) -> LinearConfig<f64, 1> {
    let mut cells = heapless::Vec::new();
    let cell = Gaussian { mean: SVector::from([50.0, 0.0, 0.0, 0.0]), covariance: SMatrix::identity() * 25.0 };
    cells.push(cell).expect("one cell");
    config.birth = BirthModel {
        probability: 0.05,
        cells,
        detection: BirthDetection::AllDetected,
        events: BirthEvents::FirstOrder,
        measured: None,
    };
    config
}

/// Objects at x = `xs`, moving along +x at unit speed, labelled 0, 1, ...
pub(super) fn objects(xs: &[f64]) -> Vec<PriorObject<f64, 4>> {
    xs.iter()
        .enumerate()
        .map(|(i, &x)| PriorObject {
            label: TrackLabel(i as u32),
            state: Gaussian { mean: SVector::from([x, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() },
        })
        .collect()
}

pub(super) fn z(x: f64, y: f64) -> SVector<f64, 2> {
    SVector::from([x, y])
}

pub(super) fn scan(time: f64) -> ScanGeometry<f64> {
    ScanGeometry::single(time)
}

fn single(xs: &[f64]) -> Box<Single> {
    let objects = objects(xs);
    let mut core = Box::new(Single::empty(config()));
    core.reset(&[PriorHypothesis { weight: 1.0, objects: &objects }], 0.0).expect("prior");
    core
}

fn posteriors(tracker: &Partitioned) -> BTreeMap<u32, ObjectPosterior<4>> {
    let mut out = BTreeMap::new();
    tracker.for_each_core(|_, core| marginal::add(core, &mut out)).expect("every rest loads");
    out
}

fn assert_equal(a: &BTreeMap<u32, ObjectPosterior<4>>, b: &BTreeMap<u32, ObjectPosterior<4>>) {
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    for (label, (x, y)) in a.keys().map(|l| (l, (&a[l], &b[l]))) {
        assert!((x.existence - y.existence).abs() < 1e-12, "label {label}: {} vs {}", x.existence, y.existence);
        assert!((x.mean - y.mean).amax() < 1e-12, "label {label}: {} vs {}", x.mean, y.mean);
        assert!((x.covariance - y.covariance).amax() < 1e-12, "label {label}: {} vs {}", x.covariance, y.covariance);
    }
}

/// Runs `f` on a thread with room for the single tracker.
pub(super) fn on_large_stack(f: impl FnOnce() + Send + 'static) {
    std::thread::Builder::new().stack_size(256 << 20).spawn(f).expect("thread").join().expect("no panic");
}

/// Three objects 100 apart: scans with detections, a missed one, two measurements in one gate and a far
/// clutter point (the birth cluster's, which has no birth model here).
fn apart_scans() -> Vec<(f64, Vec<SVector<f64, 2>>)> {
    vec![
        (1.0, vec![z(1.1, 0.1), z(100.9, -0.2), z(201.2, 0.3), z(500.0, 40.0)]),
        (2.0, vec![z(2.0, -0.1), z(2.6, 0.5), z(102.1, 0.1), z(201.8, -0.3)]),
        (3.0, vec![z(3.2, 0.2), z(103.0, 0.0)]),
    ]
}

#[test]
fn objects_that_never_interact_have_the_single_trackers_posteriors() {
    on_large_stack(|| assert_eq!(apart(config(), apart_scans(), false), (0, 0), "everything is in view"));
}

/// As above with the object at 200 out of the field of view (x < 150): its cluster has no measurement and
/// no track in view, so it is stepped in place, and stays exact.
#[test]
fn a_cluster_out_of_view_is_stepped_in_place_and_stays_exact() {
    let mut narrow = config();
    narrow.sensor.field_of_view = Region::Rectangle { min: [-50.0, -50.0], max: [150.0, 50.0] };
    let scans = apart_scans()
        .into_iter()
        .map(|(t, zs)| (t, zs.into_iter().filter(|z| z[0] < 150.0 && z[1].abs() < 50.0).collect()))
        .collect();
    on_large_stack(move || assert_eq!(apart(narrow, scans, false), (3, 0), "one quiet cluster at each of 3 scans"));
}

/// As above with a view skip: the quiet cluster is not stepped in a core but given its tracks' predictions
/// (docs/maths.md §13.2), and stays exact (the planar field of view gives no clearance, so nothing is
/// skipped).
#[test]
fn a_quiet_cluster_given_its_predictions_stays_exact() {
    let mut narrow = config();
    narrow.sensor.field_of_view = Region::Rectangle { min: [-50.0, -50.0], max: [150.0, 50.0] };
    let scans = apart_scans()
        .into_iter()
        .map(|(t, zs)| (t, zs.into_iter().filter(|z| z[0] < 150.0 && z[1].abs() < 50.0).collect()))
        .collect();
    on_large_stack(move || {
        assert_eq!(apart(narrow, scans, true), (3, 3), "one quiet cluster at each of 3 scans, predicted")
    });
}

/// Runs `scans` in both trackers (the partitioned one with a view skip when `skip`), checking each object's
/// posterior after every scan; returns how many clusters were quiet over the run, and how many of them were
/// given their tracks' predictions instead of a step in a core.
fn apart(config: LinearConfig<f64, 1>, scans: Vec<(f64, Vec<SVector<f64, 2>>)>, skip: bool) -> (usize, usize) {
    {
        let (mut quiet, mut predicted) = (0, 0);
        let xs = [0.0, 100.0, 200.0];
        let objects = objects(&xs);
        let mut single = Box::new(Single::empty(config.clone()));
        single.reset(&[PriorHypothesis { weight: 1.0, objects: &objects }], 0.0).expect("prior");
        let mut partitioned = Partitioned::new(config, &objects, 0.0, 0.0).expect("tracker");
        if skip {
            partitioned = partitioned.with_view_skip(|_, _| 1.0);
        }
        for (time, zs) in scans {
            let step = single.step(time, &zs).expect("single");
            assert!(
                step.hypotheses < 1024 && (step.captured_mass - 1.0).abs() < 1e-12,
                "the single tracker prunes nothing"
            );
            let report = partitioned.step(&scan(time), &zs).expect("partitioned");
            assert_eq!((report.clusters, report.merged, report.split), (3, 0, 0));
            quiet += report.quiet;
            predicted += report.predicted;
            let mut expected = BTreeMap::new();
            marginal::add(&single, &mut expected);
            assert_equal(&posteriors(&partitioned), &expected);
        }
        // The check can fail: the hypotheses did branch, and every object moved.
        assert!(partitioned.clusters()[0].rest.hypothesis_count() > 1);
        assert!(partitioned.clusters().iter().all(|c| c.rest.time() == 3.0));
        (quiet, predicted)
    }
}

/// A scan of 20 measurements, more than one cluster's Z = 8, one in the gate of each of 20 objects 100
/// apart: routed to their clusters, none lost (each object's posterior is a one-object tracker's given its
/// own measurement), none left to the birth cluster.
#[test]
fn a_scan_larger_than_z_is_routed_across_the_clusters_without_loss() {
    on_large_stack(|| {
        let xs: Vec<f64> = (0..20).map(|i| 100.0 * f64::from(i)).collect();
        let mut partitioned = Partitioned::new(config(), &objects(&xs), 0.0, 0.0).expect("tracker");
        let zs: Vec<_> = xs.iter().enumerate().map(|(i, x)| z(x + 1.3, 0.1 * i as f64 - 0.5)).collect();
        let report = partitioned.step(&scan(1.0), &zs).expect("a scan of 20 > Z = 8 measurements");
        assert_eq!((report.clusters, report.clusters_with_measurements, report.unclaimed), (20, 20, 0));
        let got = posteriors(&partitioned);
        for (i, (x, zi)) in xs.iter().zip(&zs).enumerate() {
            let mut alone = single(&[*x]);
            alone.step(1.0, std::slice::from_ref(zi)).expect("one object");
            let mut expected = BTreeMap::new();
            marginal::add(&*alone, &mut expected);
            let (want, have) = (&expected[&0], &got[&(i as u32)]);
            assert_eq!((want.existence, want.mean, want.covariance), (have.existence, have.mean, have.covariance));
            // The measurement was used: the position's variance is below the one-object tracker's without it.
            let mut unseen = single(&[*x]);
            unseen.step(1.0, &[]).expect("one object");
            let mut without = BTreeMap::new();
            marginal::add(&*unseen, &mut without);
            assert!(have.covariance[(0, 0)] < without[&0].covariance[(0, 0)], "object {i}");
        }
    });
}

/// Two objects 6 apart; at scan 1 a measurement between them gates with both.
fn merge_scans() -> Vec<(f64, Vec<SVector<f64, 2>>)> {
    vec![
        (1.0, vec![z(4.0, 0.0), z(7.2, 0.1)]),
        (2.0, vec![z(2.1, 0.0), z(8.1, -0.2)]),
        (3.0, vec![z(3.0, 0.1), z(9.0, 0.0), z(60.0, 0.0)]),
    ]
}

#[test]
fn a_merge_is_the_single_tracker_before_pruning() {
    on_large_stack(|| {
        let xs = [0.0, 6.0];
        let mut single = single(&xs);
        let mut partitioned = Partitioned::new(config(), &objects(&xs), 0.0, 0.0).expect("tracker");
        let mut merged = 0;
        for (time, zs) in merge_scans() {
            single.step(time, &zs).expect("single");
            let report = partitioned.step(&scan(time), &zs).expect("partitioned");
            merged += report.merged;
            assert_eq!(report.merge_pruned_mass, 0.0);
            assert!(report.step_pruned_mass < 1e-15, "{report:?}");
            let mut expected = BTreeMap::new();
            marginal::add(&single, &mut expected);
            assert_equal(&posteriors(&partitioned), &expected);
        }
        assert_eq!(merged, 1);
        // One cluster of both objects, whose hypotheses are the single tracker's.
        let cluster = &partitioned.clusters()[0].rest;
        assert_eq!(partitioned.clusters().len(), 1);
        let weights = |w: Vec<f64>| w.into_iter().map(|w| (w * 1e9).round()).collect::<Vec<_>>();
        assert_eq!(
            weights(cluster.weighted().map(|(w, _)| w).collect()),
            weights(single.hypotheses().map(|h| h.weight()).collect())
        );
    });
}

/// Five objects 6 apart and, at scan 1, a measurement between each pair of neighbours: the chain would
/// merge all five, more than a cluster's N = 4. The scan is taken, not refused: the first four merge and
/// the fourth measurement stays with them (the merge with the fifth declined, §13.3); nothing is lost.
#[test]
fn a_merge_beyond_the_capacity_is_declined_and_the_scan_taken() {
    on_large_stack(|| {
        let xs = [0.0, 6.0, 12.0, 18.0, 24.0];
        let mut partitioned = Partitioned::new(config(), &objects(&xs), 0.0, 0.0).expect("tracker");
        let zs = [z(4.0, 0.0), z(10.0, 0.0), z(16.0, 0.0), z(22.0, 0.0)];
        let report = partitioned.step(&scan(1.0), &zs).expect("the scan is taken");
        assert_eq!((report.merged, report.merges_declined, report.unclaimed), (3, 1, 0), "{report:?}");
        let mut sizes: Vec<usize> = partitioned.clusters().iter().map(|c| c.rest.label_count()).collect();
        sizes.sort_unstable();
        assert_eq!(sizes, [1, 4]);
        assert!(partitioned.clusters().iter().all(|c| c.rest.max_objects() <= 4));
    });
}

/// A scenario with a merge, a birth (promoted from the birth cluster) and ε-splits; and the cores the
/// tracker's pool made.
fn busy_run(epsilon: f64) -> (Vec<u64>, Vec<PartitionReport>, usize) {
    let mut tracker = Partitioned::new(with_birth_cell(config()), &objects(&[0.0, 6.0, 100.0, 200.0]), 0.0, epsilon)
        .expect("tracker");
    let scans = [
        (1.0, vec![z(4.0, 0.0), z(7.2, 0.1), z(101.0, 0.0), z(50.5, 0.2)]),
        (2.0, vec![z(2.1, 0.0), z(8.1, -0.2), z(201.9, 0.0), z(50.4, -0.1)]),
        (3.0, vec![z(3.0, 0.1), z(9.0, 0.0), z(103.2, 0.0), z(50.6, 0.1)]),
        (4.0, vec![z(4.1, 0.0), z(10.1, 0.1), z(104.0, 0.2), z(204.0, 0.0)]),
    ];
    let mut digests = vec![];
    let mut reports = vec![];
    for (time, zs) in scans {
        reports.push(tracker.step(&scan(time), &zs).expect("step"));
        digests.push(tracker.digest());
    }
    (digests, reports, tracker.pooled_cores())
}

#[test]
fn one_two_and_four_threads_give_the_same_bits() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("pool");
        pool.install(|| busy_run(0.05))
    };
    let (one, reports, cores) = run(1);
    assert!(reports.iter().any(|r| r.merged > 0), "{reports:?}");
    assert!(reports.iter().any(|r| r.born_clusters > 0), "{reports:?}");
    assert!(reports.iter().any(|r| r.split > 0), "{reports:?}");
    // Every cluster was stepped in the one core a single thread needs.
    assert!(reports.iter().all(|r| r.clusters >= 3), "{reports:?}");
    assert_eq!(cores, 1);
    for threads in [2, 4] {
        let (digests, other, _) = run(threads);
        assert_eq!((&digests, &other), (&one, &reports), "{threads} threads");
    }
}

#[test]
fn a_clusters_rest_reads_as_its_core() {
    let mut tracker =
        Partitioned::new(with_birth_cell(config()), &objects(&[0.0, 6.0, 100.0, 200.0]), 0.0, 0.0).expect("tracker");
    tracker.step(&scan(1.0), &[z(4.0, 0.0), z(7.2, 0.1), z(101.0, 0.0), z(50.5, 0.2)]).expect("step");
    let mut branched = 0;
    tracker
        .for_each_core(|c, core| {
            let (mut from_core, mut from_rest) = (BTreeMap::new(), BTreeMap::new());
            marginal::add(core, &mut from_core);
            marginal::add_weighted(|| c.rest.weighted(), &mut from_rest);
            assert_eq!(from_rest, from_core, "{}", c.id);
            assert_eq!(c.rest.read(), hypotheses::read(core), "{}", c.id);
            assert_eq!(c.rest.expected_cardinality().to_bits(), core.expected_cardinality().to_bits());
            assert_eq!((c.rest.time(), c.rest.tracks()), (core.time(), core.tracks()));
            branched += usize::from(core.hypotheses().len() > 1);
        })
        .expect("every rest loads");
    assert!(branched > 0, "some cluster holds several hypotheses");
}

#[test]
fn a_clusters_z_overflow_names_it_and_changes_nothing() {
    let mut tracker = Partitioned::new(config(), &objects(&[0.0, 100.0]), 0.0, 0.0).expect("tracker");
    tracker.step(&scan(1.0), &[z(1.0, 0.0), z(101.0, 0.0)]).expect("step");
    let before = tracker.digest();
    // Nine measurements in the gate of cluster 1 (the object at 100), one more than Z = 8.
    let crowd: Vec<_> = (0..9).map(|i| z(102.0 + 0.1 * f64::from(i), 0.0)).collect();
    assert_eq!(
        tracker.step(&scan(2.0), &crowd),
        Err(PartitionError::TooManyMeasurements { cluster: ClusterId(1), received: 9, capacity: 8 })
    );
    assert_eq!(tracker.digest(), before);
    // Nine in no gate: the birth cluster's.
    let far: Vec<_> = (0..9).map(|i| z(500.0 + f64::from(i), 0.0)).collect();
    let error = tracker.step(&scan(2.0), &far).unwrap_err();
    assert_eq!(error, PartitionError::TooManyMeasurements { cluster: ClusterId::BIRTH, received: 9, capacity: 8 });
    assert_eq!(error.to_string(), "the birth cluster: 9 measurements in its gates, more than its capacity Z = 8");
    // A scan at the same time is the scan's error.
    assert!(matches!(tracker.step(&scan(1.0), &[]), Err(PartitionError::Scan(_))));
    assert_eq!(tracker.digest(), before);
    // The tracker goes on as if nothing happened.
    tracker.step(&scan(2.0), &[z(2.0, 0.0)]).expect("step");
}

/// A core holding `prior`.
fn core(
    prior: &[(f64, Vec<PriorObject<f64, 4>>)],
) -> Box<
    tracker_core::Tracker<
        f64,
        tracker_core::ConstantVelocity<f64>,
        tracker_core::PositionMeasurement<f64>,
        4,
        2,
        256,
        4,
        8,
        64,
        1,
    >,
> {
    let prior: Vec<_> = prior.iter().map(|(w, o)| PriorHypothesis { weight: *w, objects: o }).collect();
    let mut core = Box::new(tracker_core::Tracker::empty(config()));
    core.reset(&prior, 0.0).expect("prior");
    core
}

#[test]
fn independent_hypotheses_split_exactly_and_dependent_ones_only_within_epsilon() {
    let o = objects(&[0.0, 10.0]);
    let (a, b) = (o[0], o[1]);
    let b2 = PriorObject { state: Gaussian { mean: SVector::from([11.0, 0.0, 1.0, 0.0]), ..b.state }, ..b };
    // A exists with 0.7; B is at one of two places (0.6, 0.4), independently: the product of the two.
    let independent = core(&[(0.42, vec![a, b]), (0.28, vec![a, b2]), (0.18, vec![b]), (0.12, vec![b2])]);
    let factors = split::factor(&independent, 0.0).expect("it factors");
    assert_eq!(factors.moved, 0.0);
    let weights: Vec<Vec<f64>> = factors.groups.iter().map(|g| g.iter().map(|h| h.weight).collect()).collect();
    assert_eq!(weights.len(), 2);
    assert!((weights[0][0] - 0.7).abs() < 1e-12 && (weights[0][1] - 0.3).abs() < 1e-12, "{weights:?}");
    assert!((weights[1][0] - 0.6).abs() < 1e-12 && (weights[1][1] - 0.4).abs() < 1e-12, "{weights:?}");
    // Either A or B took the one measurement: dependent. The product of the marginals (A: 0.9, B: 0.1)
    // gives {A} 0.81, {B} 0.01, {A, B} 0.09, {} 0.09: total variation ½ (0.09 + 0.09 + 0.18) = 0.18.
    let dependent = core(&[(0.9, vec![a]), (0.1, vec![b])]);
    assert!(split::factor(&dependent, 0.0).is_none());
    assert!(split::factor(&dependent, 0.1).is_none());
    let loose = split::factor(&dependent, 0.2).expect("within ε");
    assert!((loose.moved - 0.18).abs() < 1e-12, "{}", loose.moved);
}

/// The gate with the scan's window (docs/maths.md §13.2) gates exactly the measurements it gates when it
/// compares each track with every measurement, track by track.
#[test]
fn the_gates_window_refuses_only_what_the_full_test_refuses() {
    use tracker_core::Track;
    let config = config();
    let zs: Vec<SVector<f64, 2>> =
        (0..60).map(|i| z(f64::from(i * 37 % 200) - 20.0, f64::from(i * 11 % 30) - 15.0)).collect();
    let placed = tracker_core::tracker::place_scan(&config, &scan(1.0), 0.0, &zs, usize::MAX).expect("placed");
    let windowed = window::Indexed::new(&zs, route::distance::<_, 4, 2>(&placed.model));
    let every = window::Indexed::new(&zs, |_, _| f64::NAN);
    let (mut hits, mut tracks) = (0, 0);
    for i in 0..45u32 {
        let (x, y, spread) = (f64::from(i) * 4.7 - 20.0, f64::from(i % 7) * 3.0 - 9.0, 1.0 + f64::from(i % 5) * 3.0);
        let state = Gaussian { mean: SVector::from([x, y, 1.0, 0.0]), covariance: SMatrix::identity() * spread };
        let track = [Track { label: TrackLabel(i), state, ..Default::default() }];
        let gated = route::gate(&config.motion, &placed, &track, 1.0, &windowed, config.gate, None);
        assert_eq!(gated, route::gate(&config.motion, &placed, &track, 1.0, &every, config.gate, None), "track {i}");
        hits += gated.measurements.len();
        tracks += usize::from(!gated.measurements.is_empty());
    }
    // Not vacuous: most tracks gate some measurements, none gates most of them.
    assert!(tracks > 30 && hits < 45 * 20, "{tracks} tracks gate {hits} measurements");
}
