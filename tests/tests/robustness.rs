//! Robustness (issue 8): every bad input of `docs/robustness.md` is a typed error or a documented,
//! tested behaviour. After every failed `step` the tracker is bit-identical to before (`fingerprint` and
//! `digest`), and its next good step gives the same report and the same bits as a clone that never saw
//! the bad input. Each case runs with both child generations (exhaustive and R-FISST sampled with the
//! default `SamplerConfig`) and, where cheap, with both scalar types.
//!
//! Cases already covered by `tests/tests/errors.rs` (f64, exhaustive) are extended here to the other
//! generation and to f32, not repeated verbatim.

use conformance::{fingerprint, with_large_stack};
use nalgebra::{SMatrix, SVector};
use tracker_core::config::{ChildGeneration, NumericalFailure, Selection};
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::sampler::SamplerConfig;
use tracker_core::{
    BirthDetection, BirthModel, Config, ConfigError, ConstantVelocity, Gaussian, LinearConfig, LinearTracker,
    NumericalError, PositionMeasurement, Real, Region, Sensor, SsaConfig, SsaTracker, StepError, StepReport,
    StoreOverflow, Tracker, TwoBody, ssa_caps,
};

/// The tracker of most cases: H = 8, N = 4, Z = 3, K = 8, B = 1.
type Small<T> = LinearTracker<T, 8, 4, 3, 8, 1>;

fn c<T: Real>(x: f64) -> T {
    T::of_f64(x)
}

fn v<T: Real>(x: f64, y: f64) -> SVector<T, 2> {
    SVector::<T, 2>::new(c(x), c(y))
}

fn gaussian<T: Real>(mean: [f64; 4], variance: f64) -> Gaussian<T, 4> {
    Gaussian {
        mean: SVector::<f64, 4>::from(mean).map(c::<T>),
        covariance: SMatrix::<T, 4, 4>::identity() * c::<T>(variance),
    }
}

/// Exhaustive children (budget 10⁶) and R-FISST's sampled children with the default sampler.
fn generations() -> [ChildGeneration; 2] {
    [
        ChildGeneration::Exhaustive { max_children_per_scan: 1_000_000 },
        ChildGeneration::Sampled(SamplerConfig::default()),
    ]
}

/// Runs `check::<f64>` and `check::<f32>` with both child generations.
macro_rules! for_scalars_and_generations {
    ($check:ident) => {
        for children in generations() {
            $check::<f64>(children);
            $check::<f32>(children);
        }
    };
}

/// Constant velocity in a 40 × 40 box, p_D = 0.9, one clutter return per scan, one birth cell (α = 0.01),
/// β = 0.01, gate 25.
fn config<T: Real, const B: usize>(children: ChildGeneration) -> LinearConfig<T, B> {
    let mut birth = BirthModel::none();
    birth.probability = c(0.01);
    birth.detection = BirthDetection::AllDetected;
    let mut cell = gaussian([10.0, 10.0, 0.0, 0.0], 25.0);
    cell.covariance[(2, 2)] = c(1.0);
    cell.covariance[(3, 3)] = c(1.0);
    if B > 0 {
        birth.cells.push(cell).unwrap();
    }
    Config {
        motion: ConstantVelocity { acceleration_noise: c(0.05) },
        measurement: PositionMeasurement::isotropic(c(0.4)),
        sensor: Sensor {
            detection_probability: c(0.9),
            clutter_rate: c(1.0),
            field_of_view: Region::Rectangle { min: [c(-20.0), c(-20.0)], max: [c(20.0), c(20.0)] },
        },
        birth,
        death_probability: c(0.01),
        gate: Some(c(25.0)),
        children,
        selection: Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        // Strict, so that a numerical failure is a rejected scan these tests can check; the default policy
        // (drop the track) has its own tests below.
        numerical_failure: NumericalFailure::Error,
        track_loss: Default::default(),
        seed: 11,
    }
}

/// Two objects after one good scan at t = 1.
fn small<T: Real>(children: ChildGeneration) -> Small<T> {
    let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([3.0, 0.0, 1.0, 0.0], 0.5)];
    let mut t = Small::<T>::with_objects(config(children), &objects, 0.0).unwrap();
    t.step(1.0, &[v(1.0, 0.0), v(4.0, 0.1)]).unwrap();
    t
}

/// The good scan after the bad one: at t = 2.
fn good_scan<T: Real>() -> [SVector<T, 2>; 2] {
    [v(2.0, 0.05), v(5.1, 0.0)]
}

fn tolerance<T: Real>() -> f64 {
    if core::mem::size_of::<T>() == 8 { 1e-9 } else { 1e-4 }
}

/// Checks what every scan must leave: finite, normalised weights; finite, symmetric covariances; existence
/// in [0, 1]; unique labels within a hypothesis; at most H hypotheses and K tracks.
fn assert_healthy<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    t: &Tracker<T, M, G, S, D, H, N, Z, K, B>,
) where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    let tol = tolerance::<T>();
    let hypotheses = t.hypotheses().len();
    assert!((1..=H).contains(&hypotheses), "{hypotheses} hypotheses");
    assert!(t.tracks().len() <= K);
    let mut total = 0.0;
    for h in t.hypotheses() {
        let w = h.weight().as_f64();
        assert!(w.is_finite() && w >= 0.0, "weight {w}");
        total += w;
        let mut labels: Vec<u32> = h.tracks().map(|tr| tr.label.0).collect();
        labels.sort_unstable();
        labels.dedup();
        assert_eq!(labels.len(), h.len(), "a label twice in one hypothesis");
    }
    assert!((total - 1.0).abs() <= tol, "weights sum to {total}");
    for track in t.tracks() {
        assert!(track.state.mean.iter().all(|x| x.is_finite_value()), "mean {:?}", track.state.mean);
        let p = &track.state.covariance;
        assert!(p.iter().all(|x| x.is_finite_value()), "covariance {p:?}");
        assert_eq!(*p, p.transpose(), "covariance not symmetric");
        let e = track.existence.as_f64();
        assert!(e >= -tol && e <= 1.0 + tol, "existence {e}");
    }
}

/// Runs `bad` on `t`, checks that it fails with `expected` and leaves `t` bit-identical, then checks that
/// `t`'s next good scan (`next`) gives the same report and bits as a clone that never saw `bad`.
fn assert_rejected<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    mut t: Tracker<T, M, G, S, D, H, N, Z, K, B>,
    bad: impl FnOnce(&mut Tracker<T, M, G, S, D, H, N, Z, K, B>) -> Result<StepReport<T>, StepError>,
    expected: StepError,
    next: (f64, &[SVector<T, D>]),
) where
    T: Real,
    M: MotionModel<T, S> + Clone,
    G: MeasurementModel<T, S, D> + Clone,
{
    let before = fingerprint(&t);
    let digest = t.digest();
    let untouched = t.clone();
    assert_eq!(bad(&mut t).err(), Some(expected));
    assert_eq!(fingerprint(&t), before, "state changed after {expected:?}");
    assert_eq!(t.digest(), digest);
    let mut reference = untouched;
    let expected_report = reference.step(next.0, next.1).unwrap();
    assert_eq!(t.step(next.0, next.1).unwrap(), expected_report);
    assert_eq!(fingerprint(&t), fingerprint(&reference));
}

/// `assert_rejected` on the small tracker with the standard good scan.
fn rejected<T: Real>(
    children: ChildGeneration,
    bad: impl FnOnce(&mut Small<T>) -> Result<StepReport<T>, StepError>,
    expected: StepError,
) {
    assert_rejected(small::<T>(children), bad, expected, (2.0, &good_scan::<T>()));
}

#[test]
fn non_finite_measurement_is_rejected() {
    fn check<T: Real>(children: ChildGeneration) {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for index in 0..2 {
                let mut zs = [v::<T>(1.0, 0.0), v(4.0, 0.0)];
                zs[index][index] = c(bad);
                rejected::<T>(children, |t| t.step(2.0, &zs), StepError::NonFiniteMeasurement { index });
            }
        }
        // The first bad measurement is named.
        let zs = [v::<T>(1.0, 0.0), v(f64::NAN, 0.0), v(0.0, f64::INFINITY)];
        rejected::<T>(children, |t| t.step(2.0, &zs), StepError::NonFiniteMeasurement { index: 1 });
    }
    for_scalars_and_generations!(check);
}

#[test]
fn more_than_z_measurements_is_rejected() {
    fn check<T: Real>(children: ChildGeneration) {
        for received in [4, 1000] {
            let zs = vec![v::<T>(1.0, 0.0); received];
            rejected::<T>(children, |t| t.step(2.0, &zs), StepError::TooManyMeasurements { received, capacity: 3 });
        }
        // The capacity check comes first: a NaN among too many measurements is still "too many".
        let zs = [v::<T>(f64::NAN, 0.0); 4];
        rejected::<T>(children, |t| t.step(2.0, &zs), StepError::TooManyMeasurements { received: 4, capacity: 3 });
    }
    for_scalars_and_generations!(check);
}

#[test]
fn time_equal_to_or_before_the_last_scan_is_rejected() {
    fn check<T: Real>(children: ChildGeneration) {
        let zs = [v::<T>(1.0, 0.0)];
        for time in [1.0, 1.0 - f64::EPSILON, 0.5, 0.0, -1e300, f64::MIN] {
            rejected::<T>(children, |t| t.step(time, &zs), StepError::TimeNotAfterLastScan);
        }
        for time in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            rejected::<T>(children, |t| t.step(time, &zs), StepError::NonFiniteTime);
        }
        // Documented: any strictly later time is accepted, even one ulp later (dt = 2.2e-16 s).
        let mut t = small::<T>(children);
        t.step(1.0 + f64::EPSILON, &[v(1.0, 0.0), v(4.0, 0.1)]).unwrap();
        assert_healthy(&t);
        assert_eq!(t.time(), 1.0 + f64::EPSILON);
    }
    for_scalars_and_generations!(check);
}

#[test]
fn huge_time_gap_is_a_numerical_error_or_a_finite_prediction() {
    fn check<T: Real>(children: ChildGeneration) {
        // A gap whose covariance overflows: f64 q dt³ / 3 overflows near dt = 4e103, f32 near dt = 1.3e13.
        let overflow = if core::mem::size_of::<T>() == 8 { 1e300 } else { 1e20 };
        let error = small::<T>(children).step(overflow, &[]).unwrap_err();
        assert!(
            matches!(error, StepError::Numerical { error: NumericalError::NonFinite | NumericalError::Model(_), .. }),
            "{error:?}"
        );
        rejected::<T>(children, |t| t.step(overflow, &[]), error);
        // A gap the scalar can represent (10⁶ s, covariance ~ 10¹⁶) is processed: the objects leave the
        // field of view and the state stays finite.
        let mut t = small::<T>(children);
        t.step(1e6, &[v(1.0, 0.0)]).unwrap();
        assert_healthy(&t);
    }
    for_scalars_and_generations!(check);
}

/// The embedded SSA tracker (two-body, RK4 with at most `max_substeps` sub-steps) rejects a gap that needs
/// more sub-steps, and a state at the centre of attraction, with a typed error.
#[test]
fn ssa_tracker_rejects_a_gap_beyond_its_integrator_budget() {
    with_large_stack(|| {
        for children in generations() {
            let mu = 398_600.441_8;
            let config: SsaConfig<f64> = Config {
                motion: TwoBody {
                    mu,
                    acceleration_noise: 1e-13,
                    max_step: 20.0,
                    max_substeps: 1_000,
                    min_radius: TwoBody::DEFAULT_MIN_RADIUS,
                },
                measurement: PositionMeasurement::isotropic(0.5),
                sensor: Sensor {
                    detection_probability: 0.95,
                    clutter_rate: 1.0,
                    field_of_view: Region::Sector {
                        origin: [0.0, 0.0],
                        look_direction: 15f64.to_radians(),
                        half_angle: 15f64.to_radians(),
                        max_range: 30_000.0,
                    },
                },
                birth: BirthModel::none(),
                death_probability: 1e-4,
                gate: Some(25.0),
                children,
                selection: Selection::TopWeight,
                store_overflow: StoreOverflow::PruneChildren,
                numerical_failure: NumericalFailure::Error,
                track_loss: Default::default(),
                seed: 3,
            };
            let r: f64 = 7000.0;
            let speed = (mu / r).sqrt();
            let object = gaussian::<f64>([r, 0.0, 0.0, speed], 1.0);
            let t = Box::new(SsaTracker::<f64>::with_objects(config.clone(), &[object], 0.0).unwrap());
            // 20 s × 1000 sub-steps = 20,000 s: one second more is too long, refused before any
            // propagation whatever the numerical-failure policy; exactly that is accepted.
            let too_long = StepError::TimeStepTooLong { limit_seconds: 20_000 };
            assert_rejected(*t.clone(), |t| t.step(20_001.0, &[]), too_long, (60.0, &[]));
            let mut lenient = config.clone();
            lenient.numerical_failure = NumericalFailure::DropTrack;
            let dropping = Box::new(SsaTracker::<f64>::with_objects(lenient, &[object], 0.0).unwrap());
            assert_rejected(*dropping, |t| t.step(20_001.0, &[]), too_long, (60.0, &[]));
            let mut ok = t.clone();
            ok.step(20_000.0, &[]).unwrap();
            assert_healthy(&*ok);

            let centre = gaussian::<f64>([0.0, 0.0, 1.0, 0.0], 1.0);
            let t = Box::new(SsaTracker::<f64>::with_objects(config.clone(), &[object, centre], 0.0).unwrap());
            let singular = StepError::Numerical {
                label: tracker_core::TrackLabel(1),
                error: NumericalError::Model(tracker_core::model::ModelError::Singular),
            };
            let mut copy = t.clone();
            assert_eq!(copy.step(60.0, &[]).err(), Some(singular));
            assert_eq!(fingerprint(&*copy), fingerprint(&*t));

            // The default policy drops the object at the centre in every hypothesis, reports it, and
            // keeps tracking the other one: the tracker does not stall.
            let mut lenient = config.clone();
            lenient.numerical_failure = NumericalFailure::DropTrack;
            let mut t = Box::new(SsaTracker::<f64>::with_objects(lenient, &[object, centre], 0.0).unwrap());
            let report = t.step(60.0, &[]).unwrap();
            assert_eq!(report.numerical_drops.count, 1);
            assert_eq!(report.numerical_drops.first.map(|(label, _)| label), Some(tracker_core::TrackLabel(1)));
            for k in 2..=5 {
                // A detection of the object on its circular orbit, so that it stays confirmed.
                let time = 60.0 * k as f64;
                let angle = (mu / (r * r * r)).sqrt() * time;
                let z = SVector::from([r * angle.cos(), r * angle.sin()]);
                let report = t.step(time, &[z]).unwrap();
                assert_eq!(report.numerical_drops.count, 0);
                assert_healthy(&*t);
            }
            assert!(t.hypotheses().all(|h| h.tracks().all(|track| track.label == tracker_core::TrackLabel(0))));
            let existence = t.label_existence(tracker_core::TrackLabel(0));
            assert!(existence > 0.9, "{existence}");
        }
    });
}

#[test]
fn measurement_far_outside_the_field_of_view_is_rejected() {
    fn check<T: Real>(children: ChildGeneration) {
        let big = if core::mem::size_of::<T>() == 8 { f64::MAX } else { f32::MAX as f64 };
        for far in [20.000_1, 1e6, 1e30, big, -big] {
            let zs = [v::<T>(1.0, 0.0), v(0.0, 0.0), v(0.0, far)];
            rejected::<T>(children, |t| t.step(2.0, &zs), StepError::MeasurementOutsideFieldOfView { index: 2 });
        }
        // The boundary is inside.
        let mut t = small::<T>(children);
        t.step(2.0, &[v(20.0, -20.0)]).unwrap();
        assert_healthy(&t);
    }
    for_scalars_and_generations!(check);
}

#[test]
fn measurement_outside_a_sector_is_rejected() {
    fn check<T: Real>(children: ChildGeneration) {
        let mut config = config::<T, 1>(children);
        config.birth = BirthModel::none();
        config.sensor.field_of_view = Region::Sector {
            origin: [c(0.0), c(0.0)],
            look_direction: c(0.0),
            half_angle: c(0.5),
            max_range: c(100.0),
        };
        let objects = [gaussian([10.0, 0.0, 1.0, 0.0], 0.5)];
        let t = Small::<T>::with_objects(config, &objects, 0.0).unwrap();
        let good = [v::<T>(11.0, 0.1)];
        for (index, far) in [(0, v::<T>(-5.0, 0.0)), (0, v(150.0, 0.0)), (0, v(10.0, 10.0))] {
            assert_rejected(
                t.clone(),
                |t| t.step(1.0, &[far, good[0]]),
                StepError::MeasurementOutsideFieldOfView { index },
                (1.0, &good),
            );
        }
    }
    for_scalars_and_generations!(check);
}

/// With `Region::Everywhere` nothing is outside: a measurement far from every object is accepted and can
/// only be clutter, which multiplies every child by the same λ_C. Documented: the posterior equals the one
/// without that measurement (up to rounding).
#[test]
fn far_measurement_without_a_boundary_is_clutter() {
    fn check<T: Real>(children: ChildGeneration) {
        let mut config = config::<T, 1>(children);
        config.birth = BirthModel::none();
        config.sensor.field_of_view = Region::Everywhere { volume: c(1600.0) };
        let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([3.0, 0.0, 1.0, 0.0], 0.5)];
        let big = if core::mem::size_of::<T>() == 8 { 1e300 } else { 1e30 };
        for gate in [Some(c(25.0)), None] {
            config.gate = gate;
            let mut with_far = Small::<T>::with_objects(config.clone(), &objects, 0.0).unwrap();
            let mut without = with_far.clone();
            with_far.step(1.0, &[v(1.0, 0.0), v(big, -big), v(4.0, 0.1)]).unwrap();
            without.step(1.0, &[v(1.0, 0.0), v(4.0, 0.1)]).unwrap();
            assert_healthy(&with_far);
            assert_eq!(with_far.hypotheses().len(), without.hypotheses().len());
            for (a, b) in with_far.hypotheses().zip(without.hypotheses()) {
                let (wa, wb) = (a.weight().as_f64(), b.weight().as_f64());
                assert!((wa - wb).abs() <= tolerance::<T>(), "{wa} vs {wb}");
                for (x, y) in a.tracks().zip(b.tracks()) {
                    assert_eq!(x.label, y.label);
                    assert_eq!(x.state, y.state);
                }
            }
        }
    }
    for_scalars_and_generations!(check);
}

/// The embedded capacities (`tracker_core::ssa_caps`) with constant velocity.
type Embedded<T> = LinearTracker<
    T,
    { ssa_caps::HYPOTHESES },
    { ssa_caps::OBJECTS },
    { ssa_caps::MEASUREMENTS },
    { ssa_caps::TRACKS },
    { ssa_caps::BIRTH_CELLS },
>;

/// The worst scan: Z measurements (the embedded capacity), every one inside the gate of each of 16 objects, with a birth cell
/// that sees them all. Exhaustive enumeration meets its budget (a typed error, state unchanged); R-FISST's
/// sampled children bound the work at (1 + birth cells) chains of burn_in + steps Metropolis steps per
/// parent.
#[test]
fn worst_case_scan_with_every_measurement_in_every_gate() {
    fn check<T: Real>() {
        let mut config = config::<T, 8>(ChildGeneration::Exhaustive { max_children_per_scan: 100_000 });
        config.birth.cells[0] = gaussian([0.0, 0.0, 0.0, 0.0], 4.0);
        let objects: Vec<Gaussian<T, 4>> =
            (0..16).map(|i| gaussian([0.05 * (i % 4) as f64, 0.05 * (i / 4) as f64, 0.0, 0.0], 1.0)).collect();
        let scan = |k: usize| -> Vec<SVector<T, 2>> {
            (0..ssa_caps::MEASUREMENTS)
                .map(|j| v(0.02 * (j % 8) as f64 + 0.01 * k as f64, 0.02 * (j / 8) as f64))
                .collect()
        };
        let (first, second) = (scan(1), scan(2));

        let exhaustive = Box::new(Embedded::<T>::with_objects(config.clone(), &objects, 0.0).unwrap());
        let fewer = [v::<T>(0.0, 0.0), v(0.1, 0.1)];
        assert_rejected(
            *exhaustive,
            |t| t.step(1.0, &first),
            StepError::ChildBudgetExceeded { budget: 100_000 },
            (1.0, &fewer),
        );

        let sampler = SamplerConfig::default();
        config.children = ChildGeneration::Sampled(sampler);
        let mut sampled = Box::new(Embedded::<T>::with_objects(config, &objects, 0.0).unwrap());
        let per_chain = u64::from(sampler.burn_in + sampler.steps);
        let mut parents = 1;
        for (time, zs) in [(1.0, &first), (2.0, &second)] {
            let started = std::time::Instant::now();
            let report = sampled.step(time, zs).unwrap();
            eprintln!(
                "worst case ({}): {} parents, {} children, {} steps, {:?}",
                std::any::type_name::<T>(),
                parents,
                report.children,
                report.sampler_steps,
                started.elapsed()
            );
            assert!(report.sampler_steps > 0);
            assert!(report.sampler_steps <= parents * 2 * per_chain, "{} steps", report.sampler_steps);
            assert!(report.hypotheses <= ssa_caps::HYPOTHESES);
            assert_healthy(&*sampled);
            parents = report.hypotheses as u64;
        }
    }
    with_large_stack(|| {
        check::<f64>();
        check::<f32>();
    });
}

/// Documented: scans with no measurement are processed like any other. With stationary objects in view,
/// every empty scan multiplies a hypothesis's weight by (1 − p_D) per object it holds in view (and moves
/// mass to its death children), so hypotheses with fewer objects take over: after 300 empty scans the
/// expected number of objects is essentially zero, and nothing overflows.
#[test]
fn long_runs_of_empty_scans() {
    fn check<T: Real>(children: ChildGeneration) {
        let objects = [gaussian([0.0, 0.0, 0.0, 0.0], 0.5), gaussian([3.0, 0.0, 0.0, 0.0], 0.5)];
        let mut t = Small::<T>::with_objects(config(children), &objects, 0.0).unwrap();
        for k in 1..=300 {
            t.step(k as f64, &[]).unwrap();
            assert_healthy(&t);
        }
        let expected = t.expected_cardinality().as_f64();
        assert!(expected < 1e-3, "expected cardinality {expected} after 300 empty scans");
        // A detection afterwards is still processed.
        t.step(301.0, &[v(0.0, 0.0)]).unwrap();
        assert_healthy(&t);
    }
    for_scalars_and_generations!(check);
}

/// A small deterministic generator for clutter (SplitMix64).
struct SplitMix(rand_xoshiro::SplitMix64);

impl SplitMix {
    fn new(seed: u64) -> Self {
        SplitMix(rand_core::SeedableRng::seed_from_u64(seed))
    }

    fn uniform(&mut self) -> f64 {
        (rand_core::Rng::next_u64(&mut self.0) >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Documented: scans of pure clutter (Z = 3 returns uniform over the field of view, no object, a birth cell
/// covering the view) may open low-weight birth hypotheses, but never break an invariant and never make a
/// confident object: the expected number of objects stays below 0.5 on every scan.
#[test]
fn all_clutter_scans() {
    fn check<T: Real>(children: ChildGeneration) {
        let mut config = config::<T, 1>(children);
        config.sensor.clutter_rate = c(3.0);
        config.birth.cells[0] = gaussian([0.0, 0.0, 0.0, 0.0], 100.0);
        config.birth.cells[0].covariance[(2, 2)] = c(1.0);
        config.birth.cells[0].covariance[(3, 3)] = c(1.0);
        let mut t = Small::<T>::with_objects(config, &[], 0.0).unwrap();
        let mut random = SplitMix::new(5);
        let mut worst: f64 = 0.0;
        for k in 1..=200 {
            let zs: Vec<SVector<T, 2>> =
                (0..3).map(|_| v(random.uniform() * 40.0 - 20.0, random.uniform() * 40.0 - 20.0)).collect();
            t.step(k as f64, &zs).unwrap();
            assert_healthy(&t);
            worst = worst.max(t.expected_cardinality().as_f64());
        }
        eprintln!("all clutter ({}, {children:?}): worst expected cardinality {worst}", std::any::type_name::<T>());
        assert!(worst < 0.5, "expected cardinality reached {worst}");
    }
    for_scalars_and_generations!(check);
}

/// K = N = 4 tracks: the best child fits, the others need more. `StoreOverflow::Error` is a typed error
/// (state unchanged); the default `PruneChildren` drops the children that do not fit and says so.
#[test]
fn track_store_exhausted() {
    fn check<T: Real>(children: ChildGeneration) {
        type Tight<T> = LinearTracker<T, 8, 4, 3, 4, 1>;
        let mut config = config::<T, 1>(children);
        config.birth = BirthModel::none();
        config.death_probability = c(0.0);
        config.store_overflow = StoreOverflow::Error;
        let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([1.0, 0.0, 1.0, 0.0], 0.5)];
        let zs = [v::<T>(1.0, 0.0), v(2.0, 0.1)];
        let t = Tight::<T>::with_objects(config.clone(), &objects, 0.0).unwrap();
        assert_rejected(t, |t| t.step(1.0, &zs), StepError::TrackStoreFull { capacity: 4 }, (1.0, &[]));

        config.store_overflow = StoreOverflow::PruneChildren;
        let mut pruning = Tight::<T>::with_objects(config, &objects, 0.0).unwrap();
        let report = pruning.step(1.0, &zs).unwrap();
        assert!(report.children_dropped_for_store > 0);
        assert!(report.tracks <= 4);
        assert!(report.captured_mass < T::one());
        assert_healthy(&pruning);
    }
    for_scalars_and_generations!(check);
}

/// Documented (H∞ pruning): when a scan has more children than H, the H of largest weight are kept and
/// renormalised; `captured_mass` reports the kept share. They are exactly the H best of a tracker with room
/// for every child.
#[test]
fn hypotheses_exhausted_keeps_the_h_best() {
    fn check<T: Real>(children: ChildGeneration) {
        let mut config = config::<T, 1>(children);
        config.birth = BirthModel::none();
        config.death_probability = c(0.0);
        config.gate = None;
        let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([3.0, 0.0, 1.0, 0.0], 0.5)];
        let zs = [v::<T>(1.0, 0.0), v(4.0, 0.1), v(2.5, 0.0)];
        let mut narrow = LinearTracker::<T, 4, 4, 3, 16, 1>::with_objects(config.clone(), &objects, 0.0).unwrap();
        let mut wide = LinearTracker::<T, 64, 4, 3, 64, 1>::with_objects(config, &objects, 0.0).unwrap();
        let narrow_report = narrow.step(1.0, &zs).unwrap();
        let wide_report = wide.step(1.0, &zs).unwrap();
        // A_2(3) = 13 children, all kept by the wide tracker.
        assert_eq!(wide_report.hypotheses, 13);
        assert_eq!(narrow_report.hypotheses, 4);
        assert_healthy(&narrow);
        let kept: f64 = wide.hypotheses().take(4).map(|h| h.weight().as_f64()).sum();
        let tol = tolerance::<T>();
        assert!((narrow_report.captured_mass.as_f64() - kept).abs() <= tol);
        for (a, b) in narrow.hypotheses().zip(wide.hypotheses()) {
            let (wa, wb) = (a.weight().as_f64(), b.weight().as_f64() / kept);
            assert!((wa - wb).abs() <= tol, "{wa} vs {wb}");
            for (x, y) in a.tracks().zip(b.tracks()) {
                assert_eq!((x.label, x.state), (y.label, y.state));
            }
        }
    }
    for_scalars_and_generations!(check);
}

#[test]
fn invalid_configuration_is_a_typed_error() {
    fn check<T: Real>(children: ChildGeneration) {
        let objects = [gaussian::<T>([0.0, 0.0, 1.0, 0.0], 0.5)];
        let build = |edit: &dyn Fn(&mut LinearConfig<T, 1>)| {
            let mut config = config::<T, 1>(children);
            edit(&mut config);
            Small::<T>::with_objects(config, &objects, 0.0).err()
        };
        let sensor = |e: Option<ConfigError>| matches!(e, Some(ConfigError::Sensor(_)));
        for pd in [-0.5, 0.0, 1.0 + 1e-6, 2.0, f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(sensor(build(&|c| c.sensor.detection_probability = T::of_f64(pd))), "p_D = {pd}");
        }
        assert_eq!(build(&|c| c.sensor.detection_probability = T::one()), None, "p_D = 1 is valid");
        assert_eq!(build(&|c| c.sensor.detection_probability = T::of_f64(1e-6)), None);
        for rate in [-1.0, 0.0, f64::NAN, f64::INFINITY] {
            assert!(sensor(build(&|c| c.sensor.clutter_rate = T::of_f64(rate))), "clutter rate {rate}");
        }
        for beta in [-1e-9, -1.0, 1.5, f64::NAN] {
            assert_eq!(build(&|c| c.death_probability = T::of_f64(beta)), Some(ConfigError::DeathProbability));
        }
        for alpha in [-1e-9, 1.5, f64::NAN, f64::INFINITY] {
            assert_eq!(build(&|c| c.birth.probability = T::of_f64(alpha)), Some(ConfigError::BirthProbability));
        }
        for q in [-0.05, 0.0, f64::NAN, f64::INFINITY] {
            // Q = q [[dt³/3, dt²/2], [dt²/2, dt]] ⊗ I is positive definite iff q > 0.
            assert!(matches!(build(&|c| c.motion.acceleration_noise = T::of_f64(q)), Some(ConfigError::Motion(_))));
        }
        // M_b α + N β with M_b = 1, N = 4: exactly 1 and above are rejected, just below is accepted.
        let events = |alpha: f64, beta: f64| {
            build(&|c| {
                c.birth.probability = T::of_f64(alpha);
                c.death_probability = T::of_f64(beta);
            })
        };
        assert_eq!(events(0.5, 0.125), Some(ConfigError::EventProbabilities));
        assert_eq!(events(1.0, 0.0), Some(ConfigError::EventProbabilities));
        assert_eq!(events(0.0, 0.25), Some(ConfigError::EventProbabilities));
        assert_eq!(events(0.5, 0.12), None);
        // R not positive definite: zero, semi-definite, indefinite, negative, asymmetric, NaN.
        for r in [
            [0.0, 0.0, 0.0, 0.0],
            [1.0, 1.0, 1.0, 1.0],
            [1.0, 2.0, 2.0, 1.0],
            [-1.0, 0.0, 0.0, 1.0],
            [1.0, 0.1, 0.0, 1.0],
        ] {
            let noise = SMatrix::<T, 2, 2>::new(c(r[0]), c(r[1]), c(r[2]), c(r[3]));
            assert_eq!(build(&|c| c.measurement.noise = noise), Some(ConfigError::MeasurementNoise), "R = {r:?}");
        }
        let nan = SMatrix::<T, 2, 2>::new(c(f64::NAN), c(0.0), c(0.0), c(1.0));
        assert_eq!(build(&|c| c.measurement.noise = nan), Some(ConfigError::MeasurementNoise));
        for gate in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(build(&|c| c.gate = Some(T::of_f64(gate))), Some(ConfigError::Gate));
        }
        let zero_steps = SamplerConfig { steps: 0, ..SamplerConfig::default() };
        assert_eq!(build(&|c| c.children = ChildGeneration::Sampled(zero_steps)), Some(ConfigError::ChildBudget));
        // Work parameters that would make one scan endless (issue 17): each above its documented limit.
        let above = |parameter, limit| Some(ConfigError::AboveLimit { parameter, limit });
        let endless_chain = SamplerConfig { steps: u32::MAX, ..SamplerConfig::default() };
        let chain_limit = u64::from(SamplerConfig::MAX_CHAIN_STEPS);
        assert_eq!(
            build(&|c| c.children = ChildGeneration::Sampled(endless_chain)),
            above("sampler burn_in + steps", chain_limit)
        );
        let long_burn_in =
            SamplerConfig { burn_in: SamplerConfig::MAX_CHAIN_STEPS, steps: 1, ..SamplerConfig::default() };
        assert_eq!(
            build(&|c| c.children = ChildGeneration::Sampled(long_burn_in)),
            above("sampler burn_in + steps", chain_limit)
        );
        let at_limit = SamplerConfig { burn_in: 0, steps: SamplerConfig::MAX_CHAIN_STEPS, ..SamplerConfig::default() };
        assert_eq!(build(&|c| c.children = ChildGeneration::Sampled(at_limit)), None);
        let endless_clusters = SamplerConfig { exhaustive_limit: u64::MAX, ..SamplerConfig::default() };
        assert_eq!(
            build(&|c| c.children = ChildGeneration::Sampled(endless_clusters)),
            above("sampler exhaustive_limit", SamplerConfig::MAX_EXHAUSTIVE_LIMIT)
        );
        let endless_homht = ChildGeneration::Exhaustive { max_children_per_scan: u64::MAX };
        assert_eq!(
            build(&|c| c.children = endless_homht),
            above("max_children_per_scan", ChildGeneration::MAX_CHILDREN_PER_SCAN)
        );
        let flat = Region::Rectangle { min: [c(0.0), c(0.0)], max: [c(0.0), c(1.0)] };
        assert!(sensor(build(&|c| c.sensor.field_of_view = flat)));
        let wide =
            Region::Sector { origin: [c(0.0), c(0.0)], look_direction: c(0.0), half_angle: c(4.0), max_range: c(1.0) };
        assert!(sensor(build(&|c| c.sensor.field_of_view = wide)));
    }
    for_scalars_and_generations!(check);

    // Q of the two-body model: same rule; and its integrator parameters.
    let mut config = SsaConfig::<f64> {
        motion: TwoBody {
            mu: 398_600.441_8,
            acceleration_noise: 0.0,
            max_step: 20.0,
            max_substeps: 100,
            min_radius: TwoBody::DEFAULT_MIN_RADIUS,
        },
        measurement: PositionMeasurement::isotropic(0.5),
        sensor: Sensor {
            detection_probability: 0.9,
            clutter_rate: 1.0,
            field_of_view: Region::Everywhere { volume: 1e6 },
        },
        birth: BirthModel::none(),
        death_probability: 0.0,
        gate: None,
        children: ChildGeneration::default(),
        selection: Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 1,
    };
    with_large_stack(move || {
        let object = [gaussian::<f64>([7000.0, 0.0, 0.0, 7.5], 1.0)];
        let build = |config: &SsaConfig<f64>| SsaTracker::<f64>::with_objects(config.clone(), &object, 0.0).err();
        assert!(matches!(build(&config), Some(ConfigError::Motion(_))));
        config.motion.acceleration_noise = 1e-13;
        assert_eq!(build(&config), None);
        config.motion.max_substeps = 0;
        assert!(matches!(build(&config), Some(ConfigError::Motion(_))));
        // A sub-step limit that would make one prediction endless (issue 17), and the limit itself.
        config.motion.max_substeps = u32::MAX;
        assert!(matches!(build(&config), Some(ConfigError::Motion(_))));
        config.motion.max_substeps = tracker_core::model::MAX_RK4_SUBSTEPS;
        assert_eq!(build(&config), None);
        config.motion.max_substeps = 100;
        config.motion.mu = -1.0;
        assert!(matches!(build(&config), Some(ConfigError::Motion(_))));
    });
}

/// Zero capacities do not compile (`CAPACITY_CHECK` in tracker/mod.rs; the compile-fail doc test is in
/// host-sim/src/soak.rs). The smallest non-zero capacities work: one hypothesis, one object, one
/// measurement, one track, no birth cell.
#[test]
fn smallest_capacities_work() {
    fn check<T: Real>(children: ChildGeneration) {
        let mut config = config::<T, 0>(children);
        config.death_probability = c(0.1);
        let mut t = LinearTracker::<T, 1, 1, 1, 1, 0>::with_objects(
            config.clone(),
            &[gaussian([0.0, 0.0, 1.0, 0.0], 0.5)],
            0.0,
        )
        .unwrap();
        for k in 1..=5 {
            let report = t.step(k as f64, &[v(k as f64, 0.0)]).unwrap();
            assert_eq!(report.hypotheses, 1);
            assert_healthy(&t);
        }
        assert_rejected(
            t,
            |t| t.step(6.0, &[v(6.0, 0.0), v(6.0, 0.1)]),
            StepError::TooManyMeasurements { received: 2, capacity: 1 },
            (6.0, &[v(6.0, 0.0)]),
        );
        // Two prior objects do not fit N = 1.
        let two = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5); 2];
        assert_eq!(
            LinearTracker::<T, 1, 1, 1, 1, 0>::with_objects(config, &two, 0.0).err(),
            Some(ConfigError::PriorTooManyObjects { hypothesis: 0 })
        );
    }
    for_scalars_and_generations!(check);
}

#[test]
fn degenerate_covariances_are_typed_errors() {
    fn check<T: Real>(children: ChildGeneration) {
        let good = gaussian::<T>([0.0, 0.0, 1.0, 0.0], 0.5);
        // Rank one: u uᵀ with u = (1, 1, 1, 1).
        let rank_one = Gaussian { mean: good.mean, covariance: SMatrix::<T, 4, 4>::repeat(T::one()) };
        let mut asymmetric = good;
        asymmetric.covariance[(0, 1)] = c(1e-3);
        let mut negative = good;
        negative.covariance[(3, 3)] = c(-0.5);
        let mut infinite = good;
        infinite.covariance[(2, 2)] = T::INFINITY;
        let mut nan_mean = good;
        nan_mean.mean[0] = c(f64::NAN);
        let zero = Gaussian { mean: good.mean, covariance: SMatrix::<T, 4, 4>::zeros() };
        for bad in [rank_one, asymmetric, negative, infinite, nan_mean, zero] {
            // Prior.
            assert_eq!(
                Small::<T>::with_objects(config(children), &[good, bad], 0.0).err(),
                Some(ConfigError::PriorObject { hypothesis: 0, object: 1 }),
                "prior {bad:?}"
            );
            // Birth cell.
            let mut config = config::<T, 1>(children);
            config.birth.cells[0] = bad;
            assert_eq!(
                Small::<T>::with_objects(config, &[good], 0.0).err(),
                Some(ConfigError::BirthCell { cell: 0 }),
                "birth cell {bad:?}"
            );
        }
        // R: rank one (exactly: the second Cholesky pivot is 0.25 − 0.5² = 0).
        let mut config = config::<T, 1>(children);
        config.measurement.noise = SMatrix::<T, 2, 2>::repeat(c(0.25));
        assert_eq!(Small::<T>::with_objects(config, &[good], 0.0).err(), Some(ConfigError::MeasurementNoise));
    }
    for_scalars_and_generations!(check);
}

/// Documented limitation: positive definiteness is checked by a Cholesky factorisation in the scalar's own
/// arithmetic, so a matrix that is singular only in exact arithmetic passes when rounding leaves its pivots
/// positive. R = 0.16 [[1, 1], [1, 1]] has the f64 pivot 0.16 − (0.16 / 0.4)² = 2.8e-17 > 0 and is accepted.
/// It is harmless: the innovation covariance S = H P Hᵀ + R is positive definite through P.
#[test]
fn numerically_singular_noise_passes_the_check_and_is_harmless() {
    for children in generations() {
        let mut config = config::<f64, 1>(children);
        config.measurement.noise = SMatrix::<f64, 2, 2>::repeat(0.16);
        let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([3.0, 0.0, 1.0, 0.0], 0.5)];
        let mut t = Small::<f64>::with_objects(config, &objects, 0.0).unwrap();
        for k in 1..=15 {
            let x = k as f64;
            t.step(x, &[v(x, 0.0), v(3.0 + x, 0.0)]).unwrap();
            assert_healthy(&t);
        }
        assert!(t.expected_cardinality() > 1.9);
    }
}

/// A prior covariance so large that its prediction overflows is a typed numerical error at the first scan,
/// and the tracker is unchanged (its next scan, with a shorter gap, gives what an untouched clone gives);
/// a tiny (but positive definite) covariance is processed.
#[test]
fn covariance_at_the_edge_of_the_scalar_range() {
    fn check<T: Real>(children: ChildGeneration) {
        // P⁻ = P + dt² P_v: 1e308 + 1e308 overflows f64, 2e38 + 2e38 overflows f32.
        let huge = if core::mem::size_of::<T>() == 8 { 1e308 } else { 2e38 };
        let objects = [gaussian::<T>([0.0, 0.0, 1.0, 0.0], 0.5), gaussian([3.0, 0.0, 1.0, 0.0], huge)];
        let mut t = Small::<T>::with_objects(config(children), &objects, 0.0).unwrap();
        let (before, untouched) = (fingerprint(&t), t.clone());
        let error = t.step(1.0, &[v(1.0, 0.0)]).unwrap_err();
        assert!(matches!(error, StepError::Numerical { label: tracker_core::TrackLabel(1), .. }), "{error:?}");
        assert_eq!(fingerprint(&t), before);
        let mut reference = untouched;
        let next = [v::<T>(0.1, 0.0)];
        assert_eq!(t.step(0.1, &next), reference.step(0.1, &next));
        assert_eq!(fingerprint(&t), fingerprint(&reference));

        let tiny = if core::mem::size_of::<T>() == 8 { 1e-300 } else { 1e-30 };
        let objects = [gaussian::<T>([0.0, 0.0, 1.0, 0.0], tiny)];
        let mut t = Small::<T>::with_objects(config(children), &objects, 0.0).unwrap();
        t.step(1.0, &[v(1.0, 0.0), v(15.0, 15.0)]).unwrap();
        assert_healthy(&t);
    }
    for_scalars_and_generations!(check);
}

/// A field of view whose volume rounds to 0 or to infinity passes validation, but the clutter intensity
/// λ_C = Λ_C / V is then infinite or 0, ln λ_C is ±inf, and the baseline m ln λ_C of an empty scan is
/// 0 × ±inf = NaN. Expected: a typed `ConfigError::Sensor` when the tracker is built. Actual: the tracker
/// is built and the next scan is accepted with NaN log-weights. Found by the `step` fuzz target
/// (fuzz/artifacts/step/crash-f4a8da60239bf62e846e3a9b3dbeb32963241fcd: a sector of subnormal range).
#[test]
fn degenerate_clutter_intensity_is_rejected() {
    fn check<T: Real>(children: ChildGeneration, region: Region<T>) -> Option<String> {
        let mut config = config::<T, 1>(children);
        config.sensor.field_of_view = region;
        let objects = [gaussian([0.0, 0.0, 1.0, 0.0], 0.5)];
        match Small::<T>::with_objects(config, &objects, 0.0) {
            Err(ConfigError::Sensor(_)) => None,
            Err(error) => Some(format!("{region:?}: {error:?}")),
            Ok(mut t) => {
                let intensity = t.config().sensor.clutter_intensity();
                let result = t.step(1.0, &[]);
                let weights: Vec<f64> = t.hypotheses().map(|h| h.log_weight().as_f64()).collect();
                Some(format!(
                    "{region:?} accepted (λ_C = {intensity:?}); empty scan: {result:?}, log-weights {weights:?}"
                ))
            }
        }
    }
    let mut failures = vec![];
    for children in generations() {
        // V = (2e200)² = inf: λ_C = 0.
        failures.extend(check::<f64>(children, Region::Rectangle { min: [-1e200, -1e200], max: [1e200, 1e200] }));
        // V = θ R² = 0 (R² underflows): λ_C = inf.
        let sector = Region::Sector { origin: [0.0, 0.0], look_direction: 0.0, half_angle: 0.5, max_range: 1e-200 };
        failures.extend(check::<f64>(children, sector));
        // V subnormal: λ_C = 1 / 1e-320 = inf.
        failures.extend(check::<f64>(children, Region::Everywhere { volume: 1e-320 }));
        // f32: V = (2e20)² = 4e40 = inf.
        failures.extend(check::<f32>(children, Region::Rectangle { min: [-1e20, -1e20], max: [1e20, 1e20] }));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// With p_D = 1 every object must take a measurement, so when the measurements are far from every object
/// (no gate) every child has a log-weight of huge magnitude. The kept children are normalised by
/// subtracting ln Σ w̃ from each ln w̃; at |ln w̃| beyond 2²⁴ (f32) or 2⁵³ (f64) the spacing of the
/// scalar exceeds ln(number of children), so every normalised log-weight rounds to 0 and the weights sum to
/// the number of hypotheses. Expected: weights that sum to 1 (or a typed numerical error). Actual: two
/// hypotheses of weight 1 each. Found by the `step` fuzz target
/// (fuzz/artifacts/step/crash-212204e411a1a52a2a1bfe841104e22097a0b112: f32, two-body, p_D = 1).
#[test]
fn huge_log_weights_stay_normalised() {
    fn check<T: Real>(children: ChildGeneration, far: f64) -> Option<String> {
        let mut config = config::<T, 1>(children);
        config.birth = BirthModel::none();
        config.death_probability = c(0.0);
        config.gate = None;
        config.sensor.detection_probability = T::one();
        config.sensor.field_of_view = Region::Everywhere { volume: c(1e4) };
        let objects = [gaussian([0.0, 0.0, 0.0, 0.0], 1.0), gaussian([0.0, 1.0, 0.0, 0.0], 1.0)];
        let mut t = Small::<T>::with_objects(config, &objects, 0.0).unwrap();
        // Two children of equal weight: (z₁→o₁, z₂→o₂) and (z₁→o₂, z₂→o₁), ln w̃ ≈ −far² / 4.
        match t.step(1.0, &[v(far, 0.0), v(far, 1.0)]) {
            Err(StepError::Numerical { .. }) => None,
            Err(error) => Some(format!("{}: {error:?}", std::any::type_name::<T>())),
            Ok(_) => {
                let total: f64 = t.hypotheses().map(|h| h.weight().as_f64()).sum();
                ((total - 1.0).abs() > tolerance::<T>()).then(|| {
                    format!(
                        "{}, far = {far}: {} hypotheses, weights sum to {total}",
                        std::any::type_name::<T>(),
                        t.hypotheses().len()
                    )
                })
            }
        }
    }
    let mut failures = vec![];
    for children in generations() {
        failures.extend(check::<f32>(children, 1e4));
        failures.extend(check::<f64>(children, 1e9));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
