//! Birth and death (docs/maths.md §5, §10.4).

use conformance::*;
use tracker_core::{BirthDetection, BirthModel, Gaussian, LinearConfig, LinearTracker, TrackLabel};

type Tracker = LinearTracker<f64, 64, 4, 4, 64, 3>;

fn config_with_births(
    alpha: f64,
    beta: f64,
    cells: &[Gaussian<f64, 4>],
    detection: BirthDetection,
) -> LinearConfig<f64, 3> {
    let mut config = linear_config::<3>(0.9, 1.0, 400.0);
    config.birth = BirthModel {
        probability: alpha,
        cells: cells.iter().copied().collect(),
        detection,
        events: Default::default(),
        measured: None,
    };
    config.death_probability = beta;
    config
}

fn birth_cell() -> Gaussian<f64, 4> {
    let mut cell = gaussian([10.0, 10.0, 0.0, 0.0], 4.0);
    cell.covariance[(2, 2)] = 1.0;
    cell.covariance[(3, 3)] = 1.0;
    cell
}

#[test]
fn death_factor_is_survival_times_missed_over_death() {
    let beta = 0.05;
    let mut t = Tracker::with_objects(
        config_with_births(0.0, beta, &[], BirthDetection::AllDetected),
        &[gaussian([0.0, 0.0, 1.0, 0.0], 0.5)],
        0.0,
    )
    .unwrap();
    let report = t.step(1.0, &[]).unwrap();
    assert_eq!(report.children, 2);
    let ratio = t.cardinality_probability(1) / t.cardinality_probability(0);
    assert!(relative_difference(ratio, (1.0 - beta) * (1.0 - 0.9) / beta) < 1e-12);
}

#[test]
fn detected_birth_factor_is_alpha_pd_g_over_clutter() {
    let (alpha, beta) = (0.01, 0.02);
    let cell = birth_cell();
    let config = config_with_births(alpha, beta, &[cell], BirthDetection::AllDetected);
    let object = gaussian([0.0, 0.0, 1.0, 0.0], 0.5);
    let zs = [V2::new(1.05, 0.1), V2::new(10.8, 9.4)];
    let mut t = Tracker::with_objects(config.clone(), &[object], 0.0).unwrap();
    t.step(1.0, &zs).unwrap();
    let kf = TextbookKf { config: &config };
    let predicted = kf.predict(&object, 1.0);
    let object_posterior = kf.update(&predicted, &zs[0]);
    let holds_updated_object = |h: &tracker_core::HypothesisView<'_, f64, 4, 4>| {
        h.tracks().any(|tr| tr.label == TrackLabel(0) && (tr.state.mean - object_posterior.mean).abs().max() < 1e-12)
    };
    let born = t.hypotheses().find(|h| h.len() == 2 && holds_updated_object(h)).unwrap();
    let clutter = t.hypotheses().find(|h| h.len() == 1 && holds_updated_object(h)).unwrap();
    // FISST (36): a detected birth carries α p_D ĝ_b where the no-event companion carries P(none) λ_C.
    let g_birth = kf.likelihood(&cell, &zs[1]);
    let lambda = 1.0 / 400.0;
    let expected = alpha * 0.9 * g_birth / ((1.0 - alpha - beta) * lambda);
    assert!(relative_difference(born.weight() / clutter.weight(), expected) < 1e-12);
    // The born track is the birth pdf updated with z₂, with a fresh label.
    let new_track = born.tracks().find(|tr| tr.label != TrackLabel(0)).unwrap();
    assert_eq!(new_track.label, TrackLabel(1));
    assert!((new_track.state.mean - kf.update(&cell, &zs[1]).mean).abs().max() < 1e-12);
}

#[test]
fn undetected_births_rank_below_their_companions() {
    // docs/maths.md §5.2, in the first-order model: an undetected birth in a cell weighs
    // α (1 − p_D) / P(no event) times its companion without the birth.
    let alpha = 0.01;
    let cells = [birth_cell(), gaussian([-10.0, 5.0, 0.0, 0.0], 4.0), gaussian([5.0, -10.0, 0.0, 0.0], 4.0)];
    let config = config_with_births(alpha, 0.0, &cells, BirthDetection::AllowUndetected);
    let object = gaussian([0.0, 0.0, 1.0, 0.0], 0.5);
    let mut t = LinearTracker::<f64, 512, 4, 4, 64, 3>::with_objects(config, &[object], 0.0).unwrap();
    let report = t.step(1.0, &[V2::new(1.05, 0.1)]).unwrap();
    assert_eq!(report.captured_mass, 1.0);
    let ratio = alpha * 0.1 / (1.0 - 3.0 * alpha);
    let one_object: Vec<_> = t.hypotheses().filter(|h| h.len() == 1).collect();
    let undetected: Vec<_> = t
        .hypotheses()
        .filter(|h| {
            h.len() == 2 && h.tracks().any(|tr| tr.label != TrackLabel(0) && tr.state.covariance[(0, 0)] == 4.0)
        })
        .collect();
    assert_eq!(undetected.len(), 3 * one_object.len(), "every (cell, association) has its undetected-birth child");
    for u in &undetected {
        let object_track = u.tracks().find(|tr| tr.label == TrackLabel(0)).unwrap();
        let companion = one_object.iter().find(|c| c.tracks().next().unwrap().state == object_track.state).unwrap();
        assert!(relative_difference(u.weight() / companion.weight(), ratio) < 1e-12);
        assert!(u.weight() < companion.weight());
    }
    let undetected_mass: f64 = undetected.iter().map(|h| h.weight()).sum();
    let companion_mass: f64 = one_object.iter().map(|h| h.weight()).sum();
    assert!(relative_difference(undetected_mass / companion_mass, 3.0 * ratio) < 1e-12);

    // The default (all births detected) has no such children.
    let mut detected_only = LinearTracker::<f64, 512, 4, 4, 64, 3>::with_objects(
        config_with_births(alpha, 0.0, &cells, BirthDetection::AllDetected),
        &[object],
        0.0,
    )
    .unwrap();
    detected_only.step(1.0, &[V2::new(1.05, 0.1)]).unwrap();
    assert!(detected_only.hypotheses().all(|h| h.tracks().all(|tr| tr.state.covariance[(0, 0)] != 4.0)));
}

#[test]
fn a_new_object_is_confirmed_and_a_vanished_one_dies() {
    // Object 0 is known and keeps being detected until t = 6, then vanishes; a second object appears in
    // the birth cell at t = 1 and moves at (0.5, 0).
    let config = config_with_births(0.02, 0.02, &[birth_cell()], BirthDetection::AllDetected);
    let mut t = Tracker::with_objects(config, &[gaussian([0.0, 0.0, 1.0, 0.0], 0.2)], 0.0).unwrap();
    for k in 1..=12 {
        let time = k as f64;
        let mut zs = vec![V2::new(10.0 + 0.5 * time + 0.05 * (k % 3) as f64, 10.0 - 0.04 * (k % 2) as f64)];
        if k <= 6 {
            zs.push(V2::new(time + 0.03 * (k % 2) as f64, -0.02 * (k % 3) as f64));
        }
        let report = t.step(time, &zs).unwrap();
        assert!(report.hypotheses >= 1);
        if k == 6 {
            assert!(
                (t.expected_cardinality() - 2.0).abs() < 0.05,
                "two objects at t = 6: {}",
                t.expected_cardinality()
            );
        }
    }
    let born = t.tracks().iter().map(|tr| tr.label).filter(|l| *l != TrackLabel(0)).min().unwrap();
    assert!(t.label_existence(born) > 0.99, "birth existence {}", t.label_existence(born));
    assert!(t.label_existence(TrackLabel(0)) < 0.05, "vanished object existence {}", t.label_existence(TrackLabel(0)));
    assert!((t.expected_cardinality() - 1.0).abs() < 0.05);
}

#[test]
fn births_are_reported_when_a_parent_is_full() {
    let config = config_with_births(0.01, 0.0, &[birth_cell()], BirthDetection::AllDetected);
    let objects: Vec<_> = (0..4).map(|i| gaussian([i as f64, 0.0, 0.0, 0.0], 0.2)).collect();
    let mut t = Tracker::with_objects(config, &objects, 0.0).unwrap();
    let report = t.step(1.0, &[V2::new(10.0, 10.0)]).unwrap();
    assert_eq!(report.births_beyond_object_capacity, 1);
}

#[test]
fn independent_births_bring_several_objects_in_one_scan_with_the_exact_weight() {
    // docs/maths.md §5.6: each cell gives birth with probability α, independently; a child with births in
    // cells l₁ and l₂ that take z₁ and z₂ weighs, against the child where both are clutter,
    // (α p_D ĝ₁ / ((1 − α) λ_C)) (α p_D ĝ₂ / ((1 − α) λ_C)).
    let alpha = 0.2;
    let cells = [birth_cell(), gaussian([-10.0, 5.0, 0.0, 0.0], 4.0)];
    let mut config = config_with_births(alpha, 0.0, &cells, BirthDetection::AllDetected);
    config.birth.events = tracker_core::BirthEvents::Independent;
    let object = gaussian([0.0, 0.0, 1.0, 0.0], 0.5);
    let zs = [V2::new(1.05, 0.1), V2::new(10.8, 9.4), V2::new(-9.5, 5.5)];
    let mut t = Tracker::with_objects(config.clone(), &[object], 0.0).unwrap();
    let report = t.step(1.0, &zs).unwrap();
    // Three columns (the object, two cells) and three rows: Σ_k C(3,k)² k! = 34 associations.
    assert_eq!(report.children, 34);
    assert!((report.captured_mass - 1.0).abs() < 1e-12);
    let kf = TextbookKf { config: &config };
    let object_posterior = kf.update(&kf.predict(&object, 1.0), &zs[0]);
    let holds_updated_object = |h: &tracker_core::HypothesisView<'_, f64, 4, 4>| {
        h.tracks().any(|tr| tr.label == TrackLabel(0) && (tr.state.mean - object_posterior.mean).abs().max() < 1e-12)
    };
    let both = t.hypotheses().find(|h| h.len() == 3 && holds_updated_object(h)).unwrap();
    let none = t.hypotheses().find(|h| h.len() == 1 && holds_updated_object(h)).unwrap();
    let lambda = 1.0 / 400.0;
    let odds = |cell: &Gaussian<f64, 4>, z: &V2| alpha * 0.9 * kf.likelihood(cell, z) / ((1.0 - alpha) * lambda);
    let expected = odds(&cells[0], &zs[1]) * odds(&cells[1], &zs[2]);
    assert!(relative_difference(both.weight() / none.weight(), expected) < 1e-12);
    // Each born track is its cell's pdf updated with its measurement, with a fresh label.
    for (cell, z) in cells.iter().zip(&zs[1..]) {
        let updated = kf.update(cell, z).mean;
        assert!(both.tracks().any(|tr| tr.label != TrackLabel(0) && (tr.state.mean - updated).abs().max() < 1e-12));
    }
    assert_eq!(t.map_hypothesis().len(), 3, "both births are in the MAP hypothesis");
}

#[test]
fn independent_births_must_be_detected() {
    let mut config = config_with_births(0.02, 0.0, &[birth_cell()], BirthDetection::AllowUndetected);
    config.birth.events = tracker_core::BirthEvents::Independent;
    let result = Tracker::with_objects(config, &[], 0.0);
    assert!(matches!(result, Err(tracker_core::ConfigError::IndependentBirthsUndetected)), "{result:?}");
}

/// Births from the measurements only (docs/maths.md §5.8) in the planar region, with death probability β,
/// λ_B `expected_births` and α at most `max_probability` per measurement.
fn measured_births_config(beta: f64, expected_births: f64, max_probability: f64) -> LinearConfig<f64, 3> {
    use tracker_core::model::AdmissibleRegion;
    use tracker_core::pool::MeasuredBirths;
    let mut config = config_with_births(0.0, beta, &[], BirthDetection::AllDetected);
    config.birth.events = tracker_core::BirthEvents::Independent;
    config.birth.measured =
        Some(MeasuredBirths { expected_births, max_probability, ..MeasuredBirths::new(AdmissibleRegion::planar(2.0)) });
    config
}

#[test]
fn measured_births_confirm_new_objects_anywhere_within_three_detections() {
    // docs/maths.md §5.8: no birth cell is given; the tracker makes cells from the measurements no track
    // explains and predicts them to the next scans, where they are independent-birth cells (§5.6).
    let mut t = Tracker::with_objects(measured_births_config(0.01, 1.0, 0.5), &[], 0.0).unwrap();
    let truth = |k: f64| [V2::new(-8.0 + 1.5 * k, 3.0), V2::new(6.0, -7.0 + 0.5 * k)];
    // Scan 1 makes two cells (nothing explains either measurement); nothing is born yet.
    let report = t.step(1.0, &truth(1.0)).unwrap();
    assert_eq!(report.birth_pool.added, 2);
    assert_eq!(t.map_hypothesis().len(), 0);
    // Scan 2: both cells give birth in the MAP hypothesis; scan 3 confirms both (existence ≥ 0.5).
    t.step(2.0, &truth(2.0)).unwrap();
    t.step(3.0, &truth(3.0)).unwrap();
    let map = t.map_hypothesis();
    assert_eq!(map.len(), 2, "both objects born");
    for z in truth(3.0) {
        let track = map.tracks().find(|tr| (tr.state.mean.xy() - z).norm() < 1.0).expect("a track on each object");
        assert!(t.label_existence(track.label) >= 0.5, "confirmed by the third detection");
    }
    // The measurements now explained by tracks make no new cells.
    let report = t.step(4.0, &truth(4.0)).unwrap();
    assert_eq!(report.birth_pool.added, 0, "{:?}", report.birth_pool);
}

#[test]
fn an_object_born_from_one_candidate_at_different_scans_keeps_one_label() {
    // docs/maths.md §5.8, "One label per candidate": the candidate made from scan 1's measurement gives birth
    // at scan 2 in the hypotheses that take scan 2's measurement, and at scan 3 in those that called it
    // clutter. Both births are one object: one label, however different their states.
    let mut t = Tracker::with_objects(measured_births_config(0.0, 0.2, 0.2), &[], 0.0).unwrap();
    let truth = |k: f64| V2::new(-8.0 + 1.5 * k, 3.0);
    for k in 1..=3 {
        t.step(f64::from(k), &[truth(f64::from(k))]).unwrap();
    }
    // Born at scan 2 (updated twice, or missed at scan 3) or at scan 3: every hypothesis of one object
    // holds it under label 0.
    let single: Vec<_> =
        t.hypotheses().filter(|h| h.len() == 1).flat_map(|h| h.tracks().copied().collect::<Vec<_>>()).collect();
    assert!(single.len() >= 3, "born at scan 2 and seen, born at scan 2 and missed, born at scan 3");
    assert!(single.iter().all(|track| track.label == TrackLabel(0)), "{single:?}");
    let means: Vec<f64> = single.iter().map(|track| track.state.mean[0]).collect();
    assert!(means.iter().any(|&x| x != means[0]), "born at different scans: different states");
    // A hypothesis that holds the object and takes scan 3's measurement as a second birth from the same
    // candidate: the second object gets a fresh label.
    let double = t.hypotheses().find(|h| h.len() == 2).expect("a second birth from the candidate");
    let labels: Vec<_> = double.tracks().map(|track| track.label).collect();
    assert_eq!(labels, [TrackLabel(0), TrackLabel(1)]);
}

#[test]
fn measured_birth_settings_are_checked_and_a_full_pool_loses_nothing_else() {
    use tracker_core::model::AdmissibleRegion;
    use tracker_core::pool::MeasuredBirths;
    use tracker_core::{BirthEvents, ConfigError};
    let measured = MeasuredBirths::new(AdmissibleRegion::planar(2.0));
    let with = |events, measured, cells: &[Gaussian<f64, 4>]| {
        let mut config = config_with_births(0.0, 0.0, cells, BirthDetection::AllDetected);
        config.birth.events = events;
        config.birth.measured = Some(measured);
        Tracker::with_objects(config, &[], 0.0).map(|_| ())
    };
    assert!(matches!(with(BirthEvents::FirstOrder, measured, &[]), Err(ConfigError::MeasuredBirths(_))));
    let bad = MeasuredBirths { max_probability: 1.0, ..measured };
    assert!(matches!(with(BirthEvents::Independent, bad, &[]), Err(ConfigError::MeasuredBirths(_))));
    let bad = MeasuredBirths { lifetime: f64::NAN, ..measured };
    assert!(matches!(with(BirthEvents::Independent, bad, &[]), Err(ConfigError::MeasuredBirths(_))));
    // The B = 3 cells all fixed: no room for cells from measurements.
    let full = [birth_cell(), birth_cell(), birth_cell()];
    assert!(matches!(with(BirthEvents::Independent, measured, &full), Err(ConfigError::MeasuredBirths(_))));
    assert_eq!(with(BirthEvents::Independent, measured, &full[..2]), Ok(()));
    // A tracklet's ranges × rates cells must fit beside the fixed cells, else it could never give a birth.
    let tracklets = |cells| MeasuredBirths {
        tracklets: Some(tracker_core::pool::TrackletBirths {
            frames: 3,
            max_span: 10.0,
            limits: tracker_core::model::LinkLimits {
                max_chi_squared: 13.8,
                max_rate: 1.0,
                max_acceleration: 0.1,
                max_jerk: 0.0,
            },
            region: AdmissibleRegion::planar(2.0),
            cells,
            single_frame: false,
        }),
        ..measured
    };
    assert_eq!(with(BirthEvents::Independent, tracklets([3, 1]), &[]), Ok(()));
    assert_eq!(with(BirthEvents::Independent, tracklets([2, 1]), &full[..1]), Ok(()));
    let refused = with(BirthEvents::Independent, tracklets([3, 1]), &full[..1]);
    assert!(matches!(refused, Err(ConfigError::MeasuredBirths(reason)) if reason.contains("tracklet")), "{refused:?}");

    // Four unexplained measurements (equal α) for a pool of three cells: each new cell goes in, the oldest
    // gives way to the fourth; counted, the scan fine.
    let mut config = config_with_births(0.0, 0.0, &[], BirthDetection::AllDetected);
    config.birth.events = BirthEvents::Independent;
    config.birth.measured = Some(MeasuredBirths { min_unexplained: 0.0, ..measured });
    let mut t = Tracker::with_objects(config, &[], 0.0).unwrap();
    let zs: Vec<V2> = (0..4).map(|i| V2::new(-40.0 + 20.0 * i as f64, 0.0)).collect();
    let report = t.step(1.0, &zs).unwrap();
    assert_eq!((report.birth_pool.added, report.birth_pool.evicted), (4, 1), "{:?}", report.birth_pool);
    let digest = t.digest();
    assert!(t.step(0.5, &zs).is_err(), "a scan back in time fails");
    assert_eq!(t.digest(), digest, "and leaves the tracker as it was");
    assert!(t.step(2.0, &zs).is_ok());
}
