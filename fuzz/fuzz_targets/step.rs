//! Fuzz target `step`: arbitrary configurations (inside and outside the valid ranges), priors, scan times
//! and measurements (any f64 bits: NaN, infinities, subnormals, huge values) through `Tracker::new` and
//! `Tracker::step`, for f64 and f32 and for constant-velocity and two-body motion.
//!
//! Checked on every input:
//! - nothing panics (a panic is a crash);
//! - a failed `step` leaves the tracker unchanged: `digest()` and every track's existence are the same
//!   bits before and after;
//! - a successful `step` leaves a healthy posterior: 1 to H hypotheses, no NaN log-weight, weights summing
//!   to 1, finite means and covariances, existence in [0, 1], `captured_mass` in [0, 1];
//! - replaying the same inputs on a fresh tracker gives the same digests (determinism).
#![no_main]

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use nalgebra::{SMatrix, SVector};
use tracker_core::config::Selection;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::sampler::{Proposal, SamplerConfig};
use tracker_core::{
    BirthDetection, BirthModel, ChildGeneration, Config, ConstantVelocity, Gaussian, PositionMeasurement,
    PriorHypothesis, PriorObject, Real, Region, Sensor, StoreOverflow, TrackLabel, Tracker, TwoBody,
};

const H: usize = 8;
const N: usize = 4;
const Z: usize = 6;
const K: usize = 16;
const B: usize = 2;

/// A number: any bits, or a value in a useful range, or a special value.
#[derive(Debug, Clone, Copy, Arbitrary)]
enum Num {
    /// Any f64 bit pattern.
    Bits(u64),
    /// In [0, 1].
    Unit(u16),
    /// In [-512, 512) in steps of 1/64.
    Small(i16),
    /// In [-1e6, 1e6).
    Wide(i32),
    /// 0, -0, 1, -1, NaN, ±inf, MAX, MIN_POSITIVE, subnormal, 1e-300, 1e300, EPSILON, -MAX.
    Special(u8),
}

impl Num {
    fn value(self) -> f64 {
        const SPECIAL: [f64; 15] = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            1e-300,
            1e300,
            f64::EPSILON,
            f64::MIN,
            1e-30,
        ];
        match self {
            Num::Bits(bits) => f64::from_bits(bits),
            Num::Unit(u) => f64::from(u) / f64::from(u16::MAX),
            Num::Small(i) => f64::from(i) / 64.0,
            Num::Wide(i) => f64::from(i) / 2048.0,
            Num::Special(k) => SPECIAL[usize::from(k) % SPECIAL.len()],
        }
    }

    fn of<T: Real>(self) -> T {
        T::of_f64(self.value())
    }
}

/// A 4 × 4 covariance: mostly diagonal (often valid), or symmetric from 10 numbers, or any 16 numbers.
#[derive(Debug, Clone, Copy, Arbitrary)]
enum Covariance {
    Diagonal([Num; 4]),
    Symmetric([Num; 10]),
    Raw([Num; 16]),
}

impl Covariance {
    fn matrix<T: Real>(&self) -> SMatrix<T, 4, 4> {
        match self {
            Covariance::Diagonal(d) => SMatrix::from_diagonal(&SVector::from(d.map(|n| n.of::<T>()))),
            Covariance::Symmetric(u) => {
                let mut m = SMatrix::zeros();
                let mut k = 0;
                for i in 0..4 {
                    for j in i..4 {
                        m[(i, j)] = u[k].of::<T>();
                        m[(j, i)] = m[(i, j)];
                        k += 1;
                    }
                }
                m
            }
            Covariance::Raw(r) => SMatrix::from_fn(|i, j| r[4 * i + j].of::<T>()),
        }
    }
}

#[derive(Debug, Clone, Copy, Arbitrary)]
struct GaussianIn {
    mean: [Num; 4],
    covariance: Covariance,
}

impl GaussianIn {
    fn gaussian<T: Real>(&self) -> Gaussian<T, 4> {
        Gaussian { mean: SVector::from(self.mean.map(|n| n.of::<T>())), covariance: self.covariance.matrix() }
    }
}

#[derive(Debug, Clone, Copy, Arbitrary)]
enum RegionIn {
    Everywhere(Num),
    Rectangle([Num; 4]),
    Sector([Num; 5]),
}

#[derive(Debug, Clone, Copy, Arbitrary)]
enum Generation {
    Exhaustive(u32),
    Sampled { burn_in: u8, steps: u16, proposal: u8, clusters: bool, exhaustive_limit: u16, exact_start: bool },
}

#[derive(Debug, Clone, Arbitrary)]
struct PriorIn {
    weight: Num,
    objects: Vec<(u8, GaussianIn)>,
}

#[derive(Debug, Clone, Copy, Arbitrary)]
enum TimeIn {
    /// The previous accepted time plus this.
    After(Num),
    /// This time.
    At(Num),
}

#[derive(Debug, Clone, Arbitrary)]
struct Scan {
    time: TimeIn,
    measurements: Vec<[Num; 2]>,
    /// A budget of Metropolis moves for the scan (`Tracker::step_with_budget`), or none.
    move_budget: Option<u16>,
}

#[derive(Debug, Clone, Arbitrary)]
struct Input {
    single_precision: bool,
    two_body: bool,
    replay: bool,
    acceleration_noise: Num,
    mu: Num,
    max_step: Num,
    max_substeps: u16,
    noise: [Num; 4],
    detection: Num,
    clutter: Num,
    region: RegionIn,
    alpha: Num,
    beta: Num,
    allow_undetected_births: bool,
    cells: Vec<GaussianIn>,
    gate: Option<Num>,
    generation: Generation,
    sampled_selection: bool,
    /// A floor under the children's weights (`Selection::TopWeightWithin`) when not sampled.
    floor_decades: Option<u8>,
    store_error: bool,
    numerical_error: bool,
    seed: u64,
    prior: Vec<PriorIn>,
    prior_time: Num,
    scans: Vec<Scan>,
}

fn config<T: Real, M>(input: &Input, motion: M) -> Config<T, M, PositionMeasurement<T>, 4, B> {
    let region = match input.region {
        RegionIn::Everywhere(v) => Region::Everywhere { volume: v.of() },
        RegionIn::Rectangle([a, b, c, d]) => Region::Rectangle { min: [a.of(), b.of()], max: [c.of(), d.of()] },
        RegionIn::Sector([x, y, look, half, range]) => Region::Sector {
            origin: [x.of(), y.of()],
            look_direction: look.of(),
            half_angle: half.of(),
            max_range: range.of(),
        },
    };
    let mut birth = BirthModel::none();
    birth.probability = input.alpha.of();
    birth.detection =
        if input.allow_undetected_births { BirthDetection::AllowUndetected } else { BirthDetection::AllDetected };
    for cell in input.cells.iter().take(B) {
        let _ = birth.cells.push(cell.gaussian());
    }
    let [r00, r01, r10, r11] = input.noise.map(|n| n.of::<T>());
    Config {
        motion,
        measurement: PositionMeasurement { noise: SMatrix::<T, 2, 2>::new(r00, r01, r10, r11) },
        sensor: Sensor {
            detection_probability: input.detection.of(),
            clutter_rate: input.clutter.of(),
            field_of_view: region,
        },
        birth,
        death_probability: input.beta.of(),
        gate: input.gate.map(|g| g.of()),
        children: match input.generation {
            Generation::Exhaustive(budget) => ChildGeneration::Exhaustive { max_children_per_scan: u64::from(budget) },
            // The chain length is capped so that one input runs in milliseconds; zero stays possible.
            Generation::Sampled { burn_in, steps, proposal, clusters, exhaustive_limit, exact_start } => {
                ChildGeneration::Sampled(SamplerConfig {
                    burn_in: u32::from(burn_in),
                    steps: u32::from(steps % 1024),
                    proposal: [Proposal::Paper, Proposal::MoveOrSwap, Proposal::Informed][usize::from(proposal % 3)],
                    clusters,
                    exhaustive_limit: u64::from(exhaustive_limit),
                    exact_start,
                })
            }
        },
        selection: match (input.sampled_selection, input.floor_decades) {
            (true, _) => Selection::SampledByWeight,
            (false, Some(decades)) => Selection::TopWeightWithin { decades },
            (false, None) => Selection::TopWeight,
        },
        store_overflow: if input.store_error { StoreOverflow::Error } else { StoreOverflow::PruneChildren },
        numerical_failure: if input.numerical_error {
            tracker_core::NumericalFailure::Error
        } else {
            tracker_core::NumericalFailure::DropTrack
        },
        track_loss: Default::default(),
        seed: input.seed,
    }
}

type Fuzzed<T, M> = Tracker<T, M, PositionMeasurement<T>, 4, 2, H, N, Z, K, B>;

/// The time of a scan.
fn scan_time(scan: &Scan, previous: f64) -> f64 {
    match scan.time {
        TimeIn::After(dt) => previous + dt.value(),
        TimeIn::At(t) => t.value(),
    }
}

/// Everything a successful step must leave.
fn assert_healthy<T: Real, M: MotionModel<T, 4>>(tracker: &Fuzzed<T, M>)
where
    PositionMeasurement<T>: MeasurementModel<T, 4, 2>,
{
    let tolerance = if core::mem::size_of::<T>() == 8 { 1e-6 } else { 1e-3 };
    let count = tracker.hypotheses().len();
    assert!((1..=H).contains(&count), "{count} hypotheses");
    let mut total = 0.0;
    for h in tracker.hypotheses() {
        let log_weight = h.log_weight().as_f64();
        assert!(!log_weight.is_nan(), "NaN log-weight");
        let weight = h.weight().as_f64();
        assert!(weight.is_finite() && weight >= 0.0, "weight {weight}");
        total += weight;
    }
    assert!((total - 1.0).abs() <= tolerance, "weights sum to {total}");
    for track in tracker.tracks() {
        let state = &track.state;
        assert!(state.mean.iter().chain(state.covariance.iter()).all(|v| v.is_finite_value()), "{state:?}");
        let existence = track.existence.as_f64();
        assert!((-tolerance..=1.0 + tolerance).contains(&existence), "existence {existence}");
    }
}

/// The bits of a tracker's state: its digest and every track's existence.
fn state<T: Real, M: MotionModel<T, 4>>(tracker: &Fuzzed<T, M>) -> (u64, Vec<u64>, usize) {
    let existence = tracker.tracks().iter().map(|t| t.existence.as_f64().to_bits()).collect();
    (tracker.digest(), existence, tracker.tracks().len())
}

/// Builds the tracker of `input` and runs its scans; returns the digest after every scan (or `None` when
/// the configuration is rejected).
fn run<T: Real, M: MotionModel<T, 4> + Clone>(input: &Input, motion: M) -> Option<Vec<u64>> {
    let config = config::<T, M>(input, motion);
    let objects: Vec<Vec<PriorObject<T, 4>>> = input
        .prior
        .iter()
        .take(H + 1)
        .map(|h| {
            h.objects
                .iter()
                .take(N + 1)
                .map(|(label, g)| PriorObject { label: TrackLabel(u32::from(*label)), state: g.gaussian() })
                .collect()
        })
        .collect();
    let prior: Vec<PriorHypothesis<'_, T, 4>> = input
        .prior
        .iter()
        .zip(&objects)
        .map(|(h, objects)| PriorHypothesis { weight: h.weight.of(), objects })
        .collect();
    let prior_time = input.prior_time.value();
    let mut tracker = Box::new(Fuzzed::<T, M>::new(config, &prior, prior_time).ok()?);
    assert_healthy(&*tracker);
    let mut digests = vec![tracker.digest()];
    let mut previous = prior_time;
    for scan in input.scans.iter().take(12) {
        let time = scan_time(scan, previous);
        let measurements: Vec<SVector<T, 2>> =
            scan.measurements.iter().take(Z + 2).map(|z| SVector::from(z.map(|n| n.of::<T>()))).collect();
        let before = state(&*tracker);
        let budget = scan.move_budget.map_or(u64::MAX, u64::from);
        match tracker.step_with_budget(time, &measurements, budget) {
            Ok(report) => {
                assert_healthy(&*tracker);
                assert!(report.sampler_steps <= budget, "{} moves over a budget of {budget}", report.sampler_steps);
                let captured = report.captured_mass.as_f64();
                assert!((0.0..=1.0 + 1e-3).contains(&captured), "captured mass {captured}");
                assert_eq!(tracker.time(), time);
                previous = time;
            }
            Err(error) => {
                assert_eq!(state(&*tracker), before, "the state changed after {error:?}");
                let _ = error.to_string();
            }
        }
        digests.push(tracker.digest());
    }
    Some(digests)
}

fn run_twice<T: Real, M: MotionModel<T, 4> + Clone>(input: &Input, motion: M) {
    let first = run::<T, M>(input, motion.clone());
    if input.replay && first.is_some() {
        assert_eq!(run::<T, M>(input, motion), first, "not deterministic");
    }
}

fuzz_target!(|input: Input| {
    if input.two_body {
        // At most 2000 RK4 sub-steps per prediction keeps one input fast; zero stays possible.
        let substeps = u32::from(input.max_substeps % 2048);
        if input.single_precision {
            let motion = TwoBody {
                mu: input.mu.of::<f32>(),
                acceleration_noise: input.acceleration_noise.of(),
                max_step: input.max_step.of(),
                max_substeps: substeps,
                min_radius: TwoBody::DEFAULT_MIN_RADIUS,
            };
            run_twice::<f32, _>(&input, motion);
        } else {
            let motion = TwoBody {
                mu: input.mu.of::<f64>(),
                acceleration_noise: input.acceleration_noise.of(),
                max_step: input.max_step.of(),
                max_substeps: substeps,
                min_radius: TwoBody::DEFAULT_MIN_RADIUS,
            };
            run_twice::<f64, _>(&input, motion);
        }
    } else if input.single_precision {
        run_twice::<f32, _>(&input, ConstantVelocity { acceleration_noise: input.acceleration_noise.of::<f32>() });
    } else {
        run_twice::<f64, _>(&input, ConstantVelocity { acceleration_noise: input.acceleration_noise.of::<f64>() });
    }
});
