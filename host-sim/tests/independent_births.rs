//! Exactness of independent births (docs/maths.md §5.6): the core tracker against the unbounded reference
//! on a planar constant-velocity scenario built here, in which two known objects cross while four new
//! objects appear, two of them in the same scan, in three birth cells.

use host_sim::exactness::{CompareFigures, Scan, compare_scans};
use host_sim::rng::{Random, Stream};
use nalgebra::{SMatrix, SVector};
use tracker_core::model::{ConstantVelocity, PositionMeasurement, ScanGeometry};
use tracker_core::sampler::SamplerConfig;
use tracker_core::{
    BirthDetection, BirthEvents, BirthModel, ChildGeneration, Config, Gaussian, PriorObject, Region, Sensor,
    TrackLabel,
};

type Linear = Config<f64, ConstantVelocity<f64>, PositionMeasurement<f64>, 4, 3>;
const SCANS: usize = 8;
const SIGMA: f64 = 0.3;

/// (initial state at t = 0, first scan in which it exists): two prior objects, four births.
fn truth() -> Vec<([f64; 4], usize)> {
    vec![
        ([-20.0, -5.0, 4.0, 1.0], 0),
        ([-20.0, 5.0, 4.0, -1.0], 0),
        ([28.0, 28.0, 0.5, 0.0], 2), // two births in scan 2
        ([-32.0, 30.0, 0.0, -0.5], 2),
        ([30.0, -30.0, -0.5, 0.5], 4),
        ([29.0, 27.0, -0.5, 0.0], 5), // a second birth in the first cell, near the first
    ]
}

fn state_at(initial: &[f64; 4], time: f64) -> SVector<f64, 2> {
    SVector::from([initial[0] + initial[2] * time, initial[1] + initial[3] * time])
}

fn scans() -> Vec<Scan<2>> {
    let mut rng = Random::stream(3, Stream::Detection, 0);
    (1..=SCANS)
        .map(|k| {
            let time = k as f64;
            let mut zs: Vec<SVector<f64, 2>> = vec![];
            for (x, from) in truth() {
                if k >= from && rng.uniform() < 0.9 {
                    zs.push(state_at(&x, time) + SVector::from([rng.normal(), rng.normal()]) * SIGMA);
                }
            }
            for _ in 0..rng.poisson(1.5) {
                zs.push(SVector::from([rng.between(-50.0, 50.0), rng.between(-50.0, 50.0)]));
            }
            rng.shuffle(&mut zs);
            (ScanGeometry { sensor: 0, time, observer: None }, zs)
        })
        .collect()
}

fn config(children: ChildGeneration) -> Linear {
    let cell = |x: f64, y: f64| Gaussian {
        mean: SVector::from([x, y, 0.0, 0.0]),
        covariance: SMatrix::from_diagonal(&SVector::from([16.0, 16.0, 1.0, 1.0])),
    };
    let cells = [cell(30.0, 30.0), cell(-30.0, 30.0), cell(30.0, -30.0)].into_iter().collect();
    Config {
        motion: ConstantVelocity { acceleration_noise: 0.05 },
        measurement: PositionMeasurement::isotropic(SIGMA),
        sensor: Sensor {
            detection_probability: 0.9,
            clutter_rate: 1.5,
            field_of_view: Region::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] },
        },
        birth: BirthModel {
            probability: 0.05,
            cells,
            detection: BirthDetection::AllDetected,
            events: BirthEvents::Independent,
            measured: None,
        },
        death_probability: 0.01,
        gate: Some(25.0),
        children,
        selection: Default::default(),
        store_overflow: Default::default(),
        numerical_failure: Default::default(),
        seed: 5,
    }
}

fn compare(children: ChildGeneration) -> CompareFigures {
    let prior: Vec<PriorObject<f64, 4>> = truth()[..2]
        .iter()
        .enumerate()
        .map(|(i, (x, _))| PriorObject {
            label: TrackLabel(i as u32),
            state: Gaussian { mean: SVector::from(*x), covariance: SMatrix::identity() * 0.5 },
        })
        .collect();
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(move || {
            compare_scans::<_, _, 4, 2, 256, 12, 16, 1024, 3>(&config(children), &[(1.0, prior)], 0.0, 1 << 30, &scans())
                .unwrap()
        })
        .unwrap()
        .join()
        .unwrap()
}

fn check(figures: &CompareFigures, weight_tolerance: f64) {
    for s in &figures.scans {
        assert_eq!((s.core_error, s.reference_error), (None, None), "scan {}", s.scan);
        assert!(s.map_agreement && s.map_labels_agree, "scan {}: {s:?}", s.scan);
        assert!(s.map_weight_difference <= weight_tolerance, "scan {}: {s:?}", s.scan);
        assert!(s.captured_mass >= 0.999, "scan {}: {s:?}", s.scan);
    }
    assert_eq!(figures.map_agreement, 1.0);
}

#[test]
fn independent_births_scenario_brings_two_objects_in_one_scan() {
    let scans = scans();
    assert!(scans[1].1.len() >= 4, "scan 2 holds both births' measurements: {:?}", scans[1].1);
}

#[test]
fn independent_births_exhaustive_core_is_exact() {
    let figures = compare(ChildGeneration::Exhaustive { max_children_per_scan: 10_000_000 });
    check(&figures, 1e-9);
    assert!(figures.max_weight_l1 <= 1e-9, "{}", figures.max_weight_l1);
    // The MAP hypothesis ends with all six objects.
    let last = figures.scans.last().unwrap();
    assert!(last.reference_hypotheses > 1);
}

#[test]
fn independent_births_sampled_core_agrees() {
    let figures = compare(ChildGeneration::Sampled(SamplerConfig::DEFAULT));
    check(&figures, 1e-3);
}
