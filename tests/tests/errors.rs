//! Every step error leaves the tracker exactly as it was, and every invalid configuration is a typed
//! error.

use conformance::*;
use nalgebra::SMatrix;
use tracker_core::config::ChildGeneration;
use tracker_core::{
    ConfigError, LinearTracker, NumericalFailure, PriorHypothesis, PriorObject, Region, StepError, StoreOverflow,
    TrackLabel,
};

type Tracker = LinearTracker<f64, 8, 4, 3, 8, 1>;

fn tracker() -> Tracker {
    let mut config = linear_config::<1>(0.9, 1.0, 400.0);
    config.sensor.field_of_view = Region::Rectangle { min: [-20.0, -20.0], max: [20.0, 20.0] };
    let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([3.0, 0.0, 1.0, 0.0], 0.5)];
    let mut t = Tracker::with_objects(config, &objects, 0.0).unwrap();
    t.step(1.0, &[V2::new(1.0, 0.0), V2::new(4.0, 0.1)]).unwrap();
    t
}

/// Runs `bad` on a copy, checks the error and that nothing observable changed, then checks the copy
/// still tracks exactly like an untouched tracker.
fn assert_rejected(
    mut t: Tracker,
    bad: impl FnOnce(&mut Tracker) -> Result<tracker_core::StepReport<f64>, StepError>,
    expected: StepError,
) {
    let before = fingerprint(&t);
    let untouched = t.clone();
    assert_eq!(bad(&mut t).unwrap_err(), expected);
    assert_eq!(fingerprint(&t), before, "state changed after {expected:?}");
    let zs = [V2::new(2.0, 0.05), V2::new(5.1, 0.0)];
    let mut reference = untouched;
    reference.step(2.0, &zs).unwrap();
    t.step(2.0, &zs).unwrap();
    assert_eq!(fingerprint(&t), fingerprint(&reference));
}

#[test]
fn too_many_measurements() {
    let zs = [V2::new(1.0, 0.0); 4];
    assert_rejected(tracker(), |t| t.step(2.0, &zs), StepError::TooManyMeasurements { received: 4, capacity: 3 });
}

#[test]
fn non_finite_measurements() {
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        let zs = [V2::new(1.0, 0.0), V2::new(bad, 0.0)];
        assert_rejected(tracker(), |t| t.step(2.0, &zs), StepError::NonFiniteMeasurement { index: 1 });
    }
}

#[test]
fn non_finite_or_non_increasing_time() {
    assert_rejected(tracker(), |t| t.step(f64::NAN, &[]), StepError::NonFiniteTime);
    assert_rejected(tracker(), |t| t.step(f64::INFINITY, &[]), StepError::NonFiniteTime);
    assert_rejected(tracker(), |t| t.step(1.0, &[]), StepError::TimeNotAfterLastScan);
    assert_rejected(tracker(), |t| t.step(0.5, &[]), StepError::TimeNotAfterLastScan);
}

#[test]
fn measurement_outside_the_field_of_view() {
    let zs = [V2::new(1.0, 0.0), V2::new(1e6, 0.0)];
    assert_rejected(tracker(), |t| t.step(2.0, &zs), StepError::MeasurementOutsideFieldOfView { index: 1 });
}

/// The tracker of [`tracker`] with the strict numerical policy.
fn strict_tracker() -> Tracker {
    let mut config = tracker().config().clone();
    config.numerical_failure = NumericalFailure::Error;
    let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([3.0, 0.0, 1.0, 0.0], 0.5)];
    let mut t = Tracker::with_objects(config, &objects, 0.0).unwrap();
    t.step(1.0, &[V2::new(1.0, 0.0), V2::new(4.0, 0.1)]).unwrap();
    t
}

#[test]
fn huge_time_gap_is_a_numerical_error() {
    // The covariance overflows to infinity: with the strict policy a typed numerical error, not a NaN in
    // the state.
    let result = strict_tracker().step(1e300, &[]);
    assert!(matches!(result, Err(StepError::Numerical { .. })), "{result:?}");
    assert_rejected(strict_tracker(), |t| t.step(1e300, &[]), result.unwrap_err());
}

#[test]
fn huge_time_gap_drops_the_failing_tracks_by_default() {
    // The default policy drops every track whose prediction fails, reports them, and the tracker goes on.
    let mut t = tracker();
    let tracks = t.tracks().len();
    assert!(tracks >= 2);
    let report = t.step(1e300, &[]).unwrap();
    assert_eq!(report.numerical_drops.count, tracks, "every track of the store is dropped");
    assert!(matches!(report.numerical_drops.first, Some((_, _))));
    assert_eq!(t.map_hypothesis().len(), 0);
    assert!((t.hypotheses().map(|h| h.weight()).sum::<f64>() - 1.0).abs() < 1e-12);
    // Nothing is left to fail: later scans are processed.
    let report = t.step(2e300, &[V2::new(1.0, 0.0)]).unwrap();
    assert_eq!(report.numerical_drops.count, 0);
}

#[test]
fn child_budget_exceeded() {
    let mut t = tracker();
    let mut config = t.config().clone();
    config.children = ChildGeneration::Exhaustive { max_children_per_scan: 5 };
    let prior: Vec<_> = t.map_hypothesis().tracks().map(|tr| tr.state).collect();
    t = Tracker::with_objects(config, &prior, 1.0).unwrap();
    let before = fingerprint(&t);
    assert_eq!(t.step(2.0, &[V2::new(2.0, 0.0), V2::new(5.0, 0.0)]), Err(StepError::ChildBudgetExceeded { budget: 5 }));
    assert_eq!(fingerprint(&t), before);
}

#[test]
fn track_store_full_with_the_error_policy() {
    let mut config = linear_config::<1>(0.9, 1.0, 400.0);
    config.store_overflow = StoreOverflow::Error;
    let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([1.0, 0.0, 1.0, 0.0], 0.5)];
    // K = N = 4: the best child fits, the next ones need more tracks.
    let mut t = LinearTracker::<f64, 8, 4, 3, 4, 1>::with_objects(config.clone(), &objects, 0.0).unwrap();
    let before = fingerprint(&t);
    let zs = [V2::new(1.0, 0.0), V2::new(2.0, 0.1)];
    assert_eq!(t.step(1.0, &zs), Err(StepError::TrackStoreFull { capacity: 4 }));
    assert_eq!(fingerprint(&t), before);

    // The default policy keeps the children that fit and reports the rest.
    config.store_overflow = StoreOverflow::PruneChildren;
    let mut pruning = LinearTracker::<f64, 8, 4, 3, 4, 1>::with_objects(config, &objects, 0.0).unwrap();
    let report = pruning.step(1.0, &zs).unwrap();
    assert!(report.children_dropped_for_store > 0);
    assert!(report.tracks <= 4);
    assert!(report.captured_mass < 1.0);
    let total: f64 = pruning.hypotheses().map(|h| h.weight()).sum();
    assert!((total - 1.0).abs() < 1e-12);
}

#[test]
fn no_viable_child_when_a_certain_detection_is_missing() {
    let mut config = linear_config::<1>(1.0, 1.0, 400.0);
    config.sensor.field_of_view = Region::Rectangle { min: [-20.0, -20.0], max: [20.0, 20.0] };
    let mut t = Tracker::with_objects(config, &[gaussian([0.0, 0.0, 1.0, 0.0], 0.5)], 0.0).unwrap();
    let before = fingerprint(&t);
    assert_eq!(t.step(1.0, &[]), Err(StepError::NoViableChild));
    assert_eq!(fingerprint(&t), before);
    // With p_D = 1 the object must take a measurement: one measurement gives exactly one child.
    let report = t.step(1.0, &[V2::new(1.0, 0.0)]).unwrap();
    assert_eq!(report.children, 1);
}

#[test]
fn invalid_configurations_are_typed_errors() {
    let object = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5)];
    let build = |edit: &dyn Fn(&mut tracker_core::LinearConfig<f64, 1>)| {
        let mut config = linear_config::<1>(0.9, 1.0, 400.0);
        edit(&mut config);
        Tracker::with_objects(config, &object, 0.0).err()
    };
    assert!(matches!(build(&|c| c.sensor.detection_probability = 0.0), Some(ConfigError::Sensor(_))));
    assert!(matches!(build(&|c| c.sensor.detection_probability = 1.01), Some(ConfigError::Sensor(_))));
    assert!(matches!(build(&|c| c.sensor.detection_probability = f64::NAN), Some(ConfigError::Sensor(_))));
    assert!(matches!(build(&|c| c.sensor.clutter_rate = -1.0), Some(ConfigError::Sensor(_))));
    assert!(matches!(build(&|c| c.sensor.clutter_rate = 0.0), Some(ConfigError::Sensor(_))));
    assert!(matches!(
        build(&|c| c.sensor.field_of_view = Region::Everywhere { volume: -1.0 }),
        Some(ConfigError::Sensor(_))
    ));
    assert!(matches!(build(&|c| c.motion.acceleration_noise = -0.1), Some(ConfigError::Motion(_))));
    assert!(matches!(build(&|c| c.motion.acceleration_noise = 0.0), Some(ConfigError::Motion(_))));
    assert_eq!(
        build(&|c| c.measurement.noise = SMatrix::<f64, 2, 2>::new(1.0, 2.0, 2.0, 1.0)),
        Some(ConfigError::MeasurementNoise)
    );
    assert_eq!(
        build(&|c| c.measurement.noise = SMatrix::<f64, 2, 2>::new(1.0, 0.1, 0.0, 1.0)),
        Some(ConfigError::MeasurementNoise)
    );
    assert_eq!(build(&|c| c.birth.probability = -0.1), Some(ConfigError::BirthProbability));
    assert_eq!(build(&|c| c.death_probability = 1.5), Some(ConfigError::DeathProbability));
    // M_b α + N β ≥ 1 with N = 4.
    assert_eq!(build(&|c| c.death_probability = 0.25), Some(ConfigError::EventProbabilities));
    assert_eq!(
        build(&|c| {
            c.birth.probability = 0.9;
            c.birth.cells.push(gaussian([0.0; 4], 1.0)).unwrap();
            c.death_probability = 0.03;
        }),
        Some(ConfigError::EventProbabilities)
    );
    assert_eq!(
        build(&|c| c.birth.cells.push(gaussian([0.0; 4], -1.0)).unwrap()),
        Some(ConfigError::BirthCell { cell: 0 })
    );
    assert_eq!(build(&|c| c.gate = Some(0.0)), Some(ConfigError::Gate));
    assert_eq!(
        build(&|c| c.children = ChildGeneration::Exhaustive { max_children_per_scan: 0 }),
        Some(ConfigError::ChildBudget)
    );
}

#[test]
fn invalid_priors_are_typed_errors() {
    let config = linear_config::<1>(0.9, 1.0, 400.0);
    let good = PriorObject { label: TrackLabel(0), state: gaussian([0.0; 4], 1.0) };
    let mut degenerate = good;
    degenerate.state.covariance[(0, 0)] = 0.0;
    let mut nan = good;
    nan.state.mean[2] = f64::NAN;
    let build = |prior: &[PriorHypothesis<'_, f64, 4>], time: f64| Tracker::new(config.clone(), prior, time).err();
    assert_eq!(build(&[], 0.0), Some(ConfigError::PriorEmpty));
    assert_eq!(build(&[PriorHypothesis { weight: 1.0, objects: &[good] }], f64::NAN), Some(ConfigError::PriorTime));
    assert_eq!(
        build(&[PriorHypothesis { weight: -1.0, objects: &[good] }], 0.0),
        Some(ConfigError::PriorWeight { hypothesis: 0 })
    );
    assert_eq!(build(&[PriorHypothesis { weight: 0.0, objects: &[good] }], 0.0), Some(ConfigError::PriorWeightTotal));
    // Each weight is finite, their sum is not.
    let huge = [PriorHypothesis { weight: 1e308, objects: &[good] }, PriorHypothesis { weight: 1e308, objects: &[] }];
    assert_eq!(build(&huge, 0.0), Some(ConfigError::PriorWeightTotal));
    assert_eq!(
        build(&[PriorHypothesis { weight: 1.0, objects: &[degenerate] }], 0.0),
        Some(ConfigError::PriorObject { hypothesis: 0, object: 0 })
    );
    assert_eq!(
        build(&[PriorHypothesis { weight: 1.0, objects: &[nan] }], 0.0),
        Some(ConfigError::PriorObject { hypothesis: 0, object: 0 })
    );
    assert_eq!(
        build(&[PriorHypothesis { weight: 1.0, objects: &[good, good] }], 0.0),
        Some(ConfigError::PriorDuplicateLabel { hypothesis: 0 })
    );
    let five: Vec<_> = (0..5).map(|i| PriorObject { label: TrackLabel(i), ..good }).collect();
    assert_eq!(
        build(&[PriorHypothesis { weight: 1.0, objects: &five }], 0.0),
        Some(ConfigError::PriorTooManyObjects { hypothesis: 0 })
    );
    let one = [good];
    let many = vec![PriorHypothesis { weight: 1.0, objects: &one[..] }; 9];
    assert_eq!(build(&many, 0.0), Some(ConfigError::PriorTooManyHypotheses));
    // K = 8 tracks: three hypotheses of four distinct tracks each need 12.
    let sets: Vec<Vec<PriorObject<f64, 4>>> = (0..3)
        .map(|h| {
            (0..4)
                .map(|i| PriorObject { label: TrackLabel(i), state: gaussian([h as f64, i as f64, 0.0, 0.0], 1.0) })
                .collect()
        })
        .collect();
    let prior: Vec<_> = sets.iter().map(|objects| PriorHypothesis { weight: 1.0, objects }).collect();
    assert_eq!(build(&prior, 0.0), Some(ConfigError::PriorTrackStoreFull));
}
