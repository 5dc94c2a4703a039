//! The SSA scenario simulator and its presets.
//!
//! Objects move on planar two-body orbits from LEO to MEO (or with constant velocity for the linear
//! preset) with zero-mean Gaussian process noise. One sensor with a fixed look direction and a field of
//! view detects each object inside it with probability p_D, measures its position with Gaussian noise
//! (a noisy return that falls outside the field of view is not reported: the sensor cannot see there),
//! and adds Poisson clutter uniform over the field of view. Objects may be born (exist only from a time
//! on, and be unknown to the prior) or die (stop existing). The truth records every object's state at
//! every scan and the origin of every measurement. Everything is seeded (see [`crate::sim::rng`]).
//!
//! Units: length in km and time in s for the SSA presets; the linear preset uses abstract units.

use crate::scenario::*;
use crate::sim::rng::{Random, Stream};
use nalgebra::{SMatrix, SVector};
use tracker_core::{ConstantVelocity, MotionModel, Region, TwoBody};

/// Earth's gravitational parameter μ (km³/s²).
pub const EARTH_MU: f64 = 398_600.441_8;
/// Earth's equatorial radius (km).
pub const EARTH_RADIUS: f64 = 6_378.137;

/// The presets of `host-sim generate`.
pub const PRESETS: [&str; 5] = ["fifty-birth-death", "fifteen-compare", "debris-crossing", "linear-small", "crossings"];

/// A planar prograde Keplerian orbit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Orbit {
    /// Semi-major axis a (km).
    pub semi_major_axis: f64,
    /// Eccentricity e (< 1).
    pub eccentricity: f64,
    /// Argument of periapsis ω (rad).
    pub periapsis: f64,
    /// True anomaly ν at the epoch (rad).
    pub true_anomaly: f64,
}

impl Orbit {
    /// The state (x, y, vx, vy) at the epoch: r = p / (1 + e cos ν), v_r = √(μ/p) e sin ν,
    /// v_θ = √(μ/p) (1 + e cos ν), with p = a (1 − e²).
    pub fn state(&self, mu: f64) -> [f64; 4] {
        let (a, e, nu) = (self.semi_major_axis, self.eccentricity, self.true_anomaly);
        let p = a * (1.0 - e * e);
        let r = p / (1.0 + e * libm::cos(nu));
        let theta = self.periapsis + nu;
        let (s, c) = (libm::sin(theta), libm::cos(theta));
        let scale = libm::sqrt(mu / p);
        let (v_radial, v_transverse) = (scale * e * libm::sin(nu), scale * (1.0 + e * libm::cos(nu)));
        [r * c, r * s, v_radial * c - v_transverse * s, v_radial * s + v_transverse * c]
    }

    /// Orbital period 2π √(a³/μ) (s).
    pub fn period(&self, mu: f64) -> f64 {
        2.0 * std::f64::consts::PI * libm::sqrt(self.semi_major_axis.powi(3) / mu)
    }
}

/// One simulated object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimObject {
    /// Identifier.
    pub id: u64,
    /// State at `epoch`.
    pub state: [f64; 4],
    /// Time of `state` (s): the prior time, or the birth time for a birth.
    pub epoch: f64,
    /// Whether the prior knows the object.
    pub in_prior: bool,
    /// When the object starts to exist (`None`: before the prior).
    pub birth_time: Option<f64>,
    /// When it stops existing.
    pub death_time: Option<f64>,
}

/// Everything needed to simulate a scenario.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// Scenario name.
    pub name: String,
    /// Scenario description.
    pub description: String,
    /// Motion model (of the truth and of the tracker).
    pub motion: MotionSpec,
    /// Measurement noise covariance R.
    pub measurement_noise: [[f64; 2]; 2],
    /// Sensor.
    pub sensor: SensorSpec,
    /// Birth model given to the tracker.
    pub birth: BirthSpec,
    /// β given to the tracker.
    pub death_probability: f64,
    /// Tracker settings.
    pub tracker: TrackerSpec,
    /// Scoring.
    pub evaluation: EvaluationSpec,
    /// Prior time (s).
    pub start_time: f64,
    /// Time between scans (s).
    pub scan_interval: f64,
    /// Number of scans.
    pub scans: usize,
    /// The objects.
    pub objects: Vec<SimObject>,
    /// Standard deviations of the prior's position and velocity errors.
    pub prior_sigma: (f64, f64),
    /// Seed of every random stream.
    pub seed: u64,
}

fn region(sensor: &SensorSpec) -> Region<f64> {
    crate::pipeline::planar::setup::region(&sensor.field_of_view)
}

pub fn uniform_in_region(fov: &FieldOfViewSpec, random: &mut Random) -> [f64; 2] {
    match *fov {
        FieldOfViewSpec::Sector { origin, look_direction_deg, field_of_view_deg, max_range } => {
            let half = field_of_view_deg.to_radians() / 2.0;
            let angle = look_direction_deg.to_radians() + random.between(-half, half);
            // Uniform over the area: r = R √u.
            let range = max_range * libm::sqrt(random.uniform());
            [origin[0] + range * libm::cos(angle), origin[1] + range * libm::sin(angle)]
        }
        FieldOfViewSpec::Rectangle { min, max } => [random.between(min[0], max[0]), random.between(min[1], max[1])],
        FieldOfViewSpec::Everywhere { volume } => {
            // No boundary: clutter over a square of area V centred on the origin.
            let half = libm::sqrt(volume) / 2.0;
            [random.between(-half, half), random.between(-half, half)]
        }
    }
}

/// One step of the true motion: x ← f(x, dt) + w, w ~ N(0, Q(dt)).
pub fn move_object(motion: &MotionSpec, state: [f64; 4], dt: f64, random: &mut Random) -> [f64; 4] {
    if dt <= 0.0 {
        return state;
    }
    let x = SVector::<f64, 4>::from(state);
    let (next, noise) = match *motion {
        MotionSpec::TwoBody { mu, acceleration_noise, max_step, max_substeps } => {
            let model = TwoBody {
                mu,
                acceleration_noise,
                max_step,
                max_substeps: max_substeps.max(1_000_000),
                min_radius: TwoBody::DEFAULT_MIN_RADIUS,
            };
            (model.propagate(&x, dt).map(|p| p.state).unwrap_or(x), model.process_noise(&x, dt))
        }
        MotionSpec::ConstantVelocity { acceleration_noise } => {
            let model = ConstantVelocity { acceleration_noise };
            (model.propagate(&x, dt).map(|p| p.state).unwrap_or(x), model.process_noise(&x, dt))
        }
    };
    (next + random.gaussian(&noise)).into()
}

impl Simulation {
    /// Simulates the scans and writes the scenario, truth included.
    pub fn run(&self) -> Scenario {
        let fov = region(&self.sensor);
        let r = SMatrix::<f64, 2, 2>::from_fn(|i, j| self.measurement_noise[i][j]);
        let mut motion_rng: Vec<Random> =
            self.objects.iter().map(|o| Random::stream(self.seed, Stream::Motion, o.id)).collect();
        let mut detection_rng: Vec<Random> =
            self.objects.iter().map(|o| Random::stream(self.seed, Stream::Detection, o.id)).collect();
        let mut states: Vec<[f64; 4]> = self.objects.iter().map(|o| o.state).collect();
        let mut state_times: Vec<f64> = self.objects.iter().map(|o| o.epoch).collect();

        let mut scans = Vec::with_capacity(self.scans);
        let mut truth_scans = Vec::with_capacity(self.scans);
        for k in 0..self.scans {
            let time = self.start_time + (k + 1) as f64 * self.scan_interval;
            let mut measurements: Vec<([f64; 2], Option<u64>)> = vec![];
            let mut alive = vec![];
            for (i, object) in self.objects.iter().enumerate() {
                let born = object.birth_time.is_none_or(|b| b <= time);
                let dead = object.death_time.is_some_and(|d| d <= time);
                if !born || dead {
                    continue;
                }
                states[i] = move_object(&self.motion, states[i], time - state_times[i], &mut motion_rng[i]);
                state_times[i] = time;
                alive.push(TruthStateSpec { id: object.id, state: states[i] });
                let position = SVector::<f64, 2>::new(states[i][0], states[i][1]);
                // Draw the detection and the noise every scan, so the stream stays aligned.
                let detected = detection_rng[i].uniform() < self.sensor.detection_probability;
                let noise = detection_rng[i].gaussian(&r);
                if fov.contains(&position) && detected {
                    let z = position + noise;
                    if fov.contains(&z) {
                        measurements.push(([z[0], z[1]], Some(object.id)));
                    }
                }
            }
            let mut clutter_rng = Random::stream(self.seed, Stream::Clutter, k as u64);
            for _ in 0..clutter_rng.poisson(self.sensor.clutter_rate) {
                measurements.push((uniform_in_region(&self.sensor.field_of_view, &mut clutter_rng), None));
            }
            Random::stream(self.seed, Stream::Scenario, 1_000_000 + k as u64).shuffle(&mut measurements);
            scans.push(ScanSpec { time, measurements: measurements.iter().map(|m| m.0).collect() });
            truth_scans.push(TruthScanSpec { objects: alive, origins: measurements.iter().map(|m| m.1).collect() });
        }

        // The prior: one hypothesis with the known objects, their means perturbed by the prior error.
        let (sp, sv) = self.prior_sigma;
        let covariance =
            [[sp * sp, 0.0, 0.0, 0.0], [0.0, sp * sp, 0.0, 0.0], [0.0, 0.0, sv * sv, 0.0], [0.0, 0.0, 0.0, sv * sv]];
        let prior_objects = self
            .objects
            .iter()
            .filter(|o| o.in_prior)
            .map(|o| {
                let mut random = Random::stream(self.seed, Stream::Prior, o.id);
                let error = [sp * random.normal(), sp * random.normal(), sv * random.normal(), sv * random.normal()];
                let mean = [0, 1, 2, 3].map(|i| o.state[i] + error[i]);
                PriorObjectSpec { label: o.id as u32, mean, covariance }
            })
            .collect();

        Scenario {
            format: FORMAT.to_string(),
            version: None,
            name: self.name.clone(),
            description: self.description.clone(),
            motion: self.motion,
            measurement: MeasurementSpec::Position { noise_covariance: self.measurement_noise },
            sensor: self.sensor,
            birth: self.birth.clone(),
            death_probability: self.death_probability,
            tracker: self.tracker,
            prior: PriorSpec {
                time: self.start_time,
                hypotheses: vec![PriorHypothesisSpec { weight: 1.0, objects: prior_objects }],
            },
            scans,
            truth: Some(TruthSpec {
                objects: self
                    .objects
                    .iter()
                    .map(|o| TruthObjectSpec {
                        id: o.id,
                        in_prior: o.in_prior,
                        birth_time: o.birth_time,
                        death_time: o.death_time,
                    })
                    .collect(),
                scans: truth_scans,
            }),
            evaluation: self.evaluation,
        }
    }
}

/// The SSA sensor of paper 003: at the Earth's centre, looking 15° above +x with a 30° field of view.
pub fn ssa_sensor(detection_probability: f64, clutter_rate: f64, max_range: f64) -> SensorSpec {
    SensorSpec {
        detection_probability,
        clutter_rate,
        field_of_view: FieldOfViewSpec::Sector {
            origin: [0.0, 0.0],
            look_direction_deg: 15.0,
            field_of_view_deg: 30.0,
            max_range,
        },
    }
}

/// Birth cells covering the sector between `inner` and `outer` range in `count` range bands. Each cell's
/// pdf is a Gaussian: position around the band centre on the boresight (range σ = half the band,
/// cross-range σ = half the sector's width there), and velocity correlated with position through the
/// circular-orbit velocity field v(p) = √(μ/|p|) (−p_y, p_x)/|p| linearised at the centre, plus an
/// independent `velocity_sigma` for eccentric orbits and the linearisation error.
pub fn ssa_birth_cells(
    sensor: &SensorSpec,
    inner: f64,
    outer: f64,
    count: usize,
    velocity_sigma: f64,
) -> Vec<GaussianSpec> {
    let FieldOfViewSpec::Sector { origin, look_direction_deg, field_of_view_deg, .. } = sensor.field_of_view else {
        return vec![];
    };
    let look = look_direction_deg.to_radians();
    let half = field_of_view_deg.to_radians() / 2.0;
    let (c, s) = (libm::cos(look), libm::sin(look));
    let band = (outer - inner) / count as f64;
    (0..count)
        .map(|i| {
            let range = inner + (i as f64 + 0.5) * band;
            let p = SVector::<f64, 2>::new(origin[0] + range * c, origin[1] + range * s);
            // Position covariance in the boresight frame, rotated to x-y.
            let rotation = SMatrix::<f64, 2, 2>::new(c, -s, s, c);
            let along = band / 2.0;
            let across = range * libm::tan(half);
            let position_cov = rotation
                * SMatrix::<f64, 2, 2>::from_diagonal(&SVector::from([along * along, across * across]))
                * rotation.transpose();
            let velocity = |p: &SVector<f64, 2>| {
                let r = p.norm();
                SVector::<f64, 2>::new(-p[1], p[0]) * (libm::sqrt(EARTH_MU / r) / r)
            };
            // Jacobian of the velocity field by central differences.
            let mut jacobian = SMatrix::<f64, 2, 2>::zeros();
            for j in 0..2 {
                let mut dp = SVector::<f64, 2>::zeros();
                dp[j] = 1.0;
                jacobian.set_column(j, &((velocity(&(p + dp)) - velocity(&(p - dp))) / 2.0));
            }
            let velocity_cov = jacobian * position_cov * jacobian.transpose()
                + SMatrix::<f64, 2, 2>::identity() * velocity_sigma.powi(2);
            let cross = jacobian * position_cov; // Cov(v, p)
            let v = velocity(&p);
            let mut joint = SMatrix::<f64, 4, 4>::zeros();
            joint.fixed_view_mut::<2, 2>(0, 0).copy_from(&position_cov);
            joint.fixed_view_mut::<2, 2>(2, 2).copy_from(&velocity_cov);
            joint.fixed_view_mut::<2, 2>(2, 0).copy_from(&cross);
            joint.fixed_view_mut::<2, 2>(0, 2).copy_from(&cross.transpose());
            // Exactly symmetric for the scenario check: ½ (A + Aᵀ).
            let joint = (joint + joint.transpose()) * 0.5;
            let covariance: [[f64; 4]; 4] = std::array::from_fn(|i| std::array::from_fn(|j| joint[(i, j)]));
            GaussianSpec { mean: [p[0], p[1], v[0], v[1]], covariance }
        })
        .collect()
}

/// A random orbit between LEO and MEO: a in [a_min, a_max], e ≤ e_max (perigee at least 200 km up).
pub fn random_orbit(random: &mut Random, a_min: f64, a_max: f64, e_max: f64) -> Orbit {
    let semi_major_axis = random.between(a_min, a_max);
    let e_limit = (1.0 - (EARTH_RADIUS + 200.0) / semi_major_axis).clamp(0.0, e_max);
    Orbit {
        semi_major_axis,
        eccentricity: random.between(0.0, e_limit),
        periapsis: random.between(0.0, 2.0 * std::f64::consts::PI),
        true_anomaly: random.between(0.0, 2.0 * std::f64::consts::PI),
    }
}

/// Two-body motion with the SSA noise level: q = 1e-13 km²/s³ (white acceleration noise), which lets an
/// unobserved object's position wander about √(q t³/3) ≈ 1.6 km in 12 h.
pub fn ssa_motion() -> MotionSpec {
    MotionSpec::TwoBody { mu: EARTH_MU, acceleration_noise: 1e-13, max_step: 20.0, max_substeps: 20_000 }
}

fn ssa_tracker(seed: u64) -> TrackerSpec {
    TrackerSpec {
        gate: Some(25.0),
        max_children_per_scan: 2_000_000,
        store_overflow: StoreOverflowSpec::PruneChildren,
        numerical_failure: NumericalFailureSpec::DropTrack,
        lost_after_unseen_scans: None,
        seed,
        sampler: SamplerSpec::default(),
        selection: SelectionSpec::default(),
    }
}

fn ssa_evaluation() -> EvaluationSpec {
    EvaluationSpec { error_bound: 25.0, gospa_cutoff: 100.0, gospa_order: 2.0, confirmation_existence: 0.9 }
}

/// Paper 003 §IV: 50 objects from LEO to MEO, the prior knows 45; 5 are born during the first quarter of
/// the run; the run lasts until every object (births included) has passed through the field of view.
pub fn fifty_birth_death(seed: u64) -> Simulation {
    let sensor = ssa_sensor(0.95, 1.0, 30_000.0);
    let mut random = Random::stream(seed, Stream::Scenario, 0);
    let orbits: Vec<Orbit> =
        (0..50).map(|i| random_orbit(&mut Random::stream(seed, Stream::Orbit, i), 6_878.0, 26_560.0, 0.02)).collect();
    let longest = orbits.iter().map(|o| o.period(EARTH_MU)).fold(0.0, f64::max);
    let mut births: Vec<usize> = (0..50).collect();
    random.shuffle(&mut births);
    births.truncate(5);
    let scan_interval = 60.0;
    let mut objects = vec![];
    let mut end: f64 = longest;
    for (i, orbit) in orbits.iter().enumerate() {
        let birth_time = births
            .contains(&i)
            .then(|| (random.between(0.0, 0.25 * longest) / scan_interval).floor() * scan_interval + 30.0);
        if let Some(b) = birth_time {
            end = end.max(b + orbit.period(EARTH_MU));
        }
        objects.push(SimObject {
            id: i as u64,
            state: orbit.state(EARTH_MU),
            epoch: birth_time.unwrap_or(0.0),
            in_prior: birth_time.is_none(),
            birth_time,
            death_time: None,
        });
    }
    Simulation {
        name: "fifty-birth-death".into(),
        description: "Paper 003 §IV: 50 planar LEO-MEO objects, the prior knows 45, 5 births; sensor at the Earth's centre looking 15° above +x with a 30° field of view".into(),
        motion: ssa_motion(),
        measurement_noise: [[0.25, 0.0], [0.0, 0.25]],
        birth: BirthSpec { probability: 1e-3, detection: BirthDetectionSpec::AllDetected, events: Default::default(), measured: None, cells: ssa_birth_cells(&sensor, 6_600.0, 30_000.0, 8, 0.3) },
        sensor,
        death_probability: 1e-4,
        tracker: ssa_tracker(seed),
        evaluation: ssa_evaluation(),
        start_time: 0.0,
        scan_interval,
        scans: (end / scan_interval).ceil() as usize + 2,
        objects,
        prior_sigma: (1.0, 2e-4),
        seed,
    }
}

/// Paper 003 §V-A: 15 objects, all starting inside the field of view; the prior knows them all.
pub fn fifteen_compare(seed: u64) -> Simulation {
    let sensor = ssa_sensor(0.95, 1.0, 30_000.0);
    let mut objects = vec![];
    let mut longest: f64 = 0.0;
    for i in 0..15u64 {
        let mut random = Random::stream(seed, Stream::Orbit, i);
        let mut orbit = random_orbit(&mut random, 6_878.0, 26_560.0, 0.02);
        // Place it inside the field of view: polar angle θ = ω + ν within 2° of the edges.
        let theta = random.between(2.0, 28.0).to_radians();
        orbit.true_anomaly = theta - orbit.periapsis;
        longest = longest.max(orbit.period(EARTH_MU));
        objects.push(SimObject {
            id: i,
            state: orbit.state(EARTH_MU),
            epoch: 0.0,
            in_prior: true,
            birth_time: None,
            death_time: None,
        });
    }
    let scan_interval = 60.0;
    Simulation {
        name: "fifteen-compare".into(),
        description:
            "Paper 003 §V-A: 15 planar LEO-MEO objects all starting in the field of view, run for the longest period"
                .into(),
        motion: ssa_motion(),
        measurement_noise: [[0.25, 0.0], [0.0, 0.25]],
        birth: BirthSpec {
            probability: 0.0,
            detection: BirthDetectionSpec::AllDetected,
            events: Default::default(),
            measured: None,
            cells: vec![],
        },
        sensor,
        death_probability: 1e-4,
        tracker: ssa_tracker(seed),
        evaluation: ssa_evaluation(),
        start_time: 0.0,
        scan_interval,
        scans: (longest / scan_interval).ceil() as usize + 2,
        objects,
        prior_sigma: (1.0, 2e-4),
        seed,
    }
}

/// A breakup: `fragments` pieces of one LEO object with small velocity kicks, crossing the field of view
/// together. The prior knows every fragment; the cloud is dense enough that most gates overlap, so the
/// number of possible children per scan explodes (A_N(m) ≥ 10³⁰ for 30 fragments and 30 returns).
pub fn debris_crossing(seed: u64) -> Simulation {
    let fragments = 40u64;
    let sensor = ssa_sensor(0.95, 2.0, 30_000.0);
    // The parent crosses the boresight ray about 3 minutes into the run.
    let parent =
        Orbit { semi_major_axis: 7_200.0, eccentricity: 0.001, periapsis: 0.0, true_anomaly: 3.0f64.to_radians() };
    let base = parent.state(EARTH_MU);
    let objects = (0..fragments)
        .map(|i| {
            let mut random = Random::stream(seed, Stream::Orbit, i);
            let mut state = base;
            for k in 0..2 {
                state[k] += 2.0 * random.normal(); // km
                state[k + 2] += 0.005 * random.normal(); // km/s
            }
            SimObject { id: i, state, epoch: 0.0, in_prior: true, birth_time: None, death_time: None }
        })
        .collect();
    Simulation {
        name: "debris-crossing".into(),
        description: "A cloud of 40 breakup fragments (2 km, 5 m/s spread) crossing the field of view together".into(),
        motion: ssa_motion(),
        measurement_noise: [[0.25, 0.0], [0.0, 0.25]],
        birth: BirthSpec {
            probability: 0.0,
            detection: BirthDetectionSpec::AllDetected,
            events: Default::default(),
            measured: None,
            cells: vec![],
        },
        sensor,
        death_probability: 1e-4,
        tracker: TrackerSpec {
            gate: Some(25.0),
            max_children_per_scan: 2_000_000,
            store_overflow: StoreOverflowSpec::PruneChildren,
            numerical_failure: NumericalFailureSpec::DropTrack,
            lost_after_unseen_scans: None,
            seed,
            sampler: SamplerSpec::default(),
            selection: SelectionSpec::default(),
        },
        evaluation: EvaluationSpec {
            error_bound: 5.0,
            gospa_cutoff: 20.0,
            gospa_order: 2.0,
            confirmation_existence: 0.9,
        },
        start_time: 0.0,
        scan_interval: 20.0,
        scans: 20,
        objects,
        prior_sigma: (0.5, 5e-4),
        seed,
    }
}

/// A few constant-velocity objects in a rectangle, one birth and one death, for exactness checks against
/// the unbounded reference.
pub fn linear_small(seed: u64) -> Simulation {
    let sensor = SensorSpec {
        detection_probability: 0.9,
        clutter_rate: 1.0,
        field_of_view: FieldOfViewSpec::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] },
    };
    let mut objects = vec![];
    for i in 0..4u64 {
        let mut random = Random::stream(seed, Stream::Orbit, i);
        let state = [
            random.between(-30.0, 30.0),
            random.between(-30.0, 30.0),
            random.between(-2.0, 2.0),
            random.between(-2.0, 2.0),
        ];
        let is_birth = i == 3;
        objects.push(SimObject {
            id: i,
            state: if is_birth { [20.0, 20.0, -1.0, -0.5] } else { state },
            epoch: if is_birth { 2.5 } else { 0.0 },
            in_prior: !is_birth,
            birth_time: is_birth.then_some(2.5),
            death_time: (i == 0).then_some(4.5),
        });
    }
    let birth_cell = GaussianSpec {
        mean: [20.0, 20.0, 0.0, 0.0],
        covariance: [[25.0, 0.0, 0.0, 0.0], [0.0, 25.0, 0.0, 0.0], [0.0, 0.0, 4.0, 0.0], [0.0, 0.0, 0.0, 4.0]],
    };
    Simulation {
        name: "linear-small".into(),
        description: "Three constant-velocity objects (one dies at t = 4.5) and one birth at t = 2.5, 6 scans".into(),
        motion: MotionSpec::ConstantVelocity { acceleration_noise: 0.01 },
        measurement_noise: [[0.25, 0.0], [0.0, 0.25]],
        birth: BirthSpec {
            probability: 0.01,
            detection: BirthDetectionSpec::AllDetected,
            events: Default::default(),
            measured: None,
            cells: vec![birth_cell],
        },
        sensor,
        // M_b α + N β < 1 must hold for the host profile's N = 128.
        death_probability: 0.005,
        tracker: TrackerSpec {
            gate: Some(16.0),
            max_children_per_scan: 1_000_000,
            store_overflow: StoreOverflowSpec::PruneChildren,
            numerical_failure: NumericalFailureSpec::DropTrack,
            lost_after_unseen_scans: None,
            seed,
            sampler: SamplerSpec::default(),
            selection: SelectionSpec::default(),
        },
        evaluation: EvaluationSpec {
            error_bound: 3.0,
            gospa_cutoff: 10.0,
            gospa_order: 2.0,
            confirmation_existence: 0.9,
        },
        start_time: 0.0,
        scan_interval: 1.0,
        scans: 6,
        objects,
        prior_sigma: (0.3, 0.1),
        seed,
    }
}

/// Parameters of [`crossings_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrossingsConfig {
    /// Times of the three crossings (s).
    pub times: [f64; 3],
    /// When the births appear, relative to their crossing (s; negative: before it).
    pub birth_offset: f64,
}

impl CrossingsConfig {
    /// The `crossings` preset.
    pub const PRESET: CrossingsConfig = CrossingsConfig { times: [8.0, 15.0, 22.0], birth_offset: -2.0 };
}

/// The crossing points of [`crossings`]: (x, y, members, the member that is born).
const CROSSINGS: [([f64; 2], u64, Option<u64>); 3] =
    [([-20.0, -15.0], 3, Some(1)), ([20.0, 10.0], 3, Some(2)), ([0.0, 25.0], 2, None)];

/// Eight constant-velocity objects in three crossings (3, 3 and 2 objects through one point at t = 8,
/// 15 and 22), p_D 0.8, 15 clutter returns per scan, 30 scans. Two objects are births: one member of
/// each of the first two crossings appears 2 s before its crossing, inside the birth cell centred on
/// that crossing point (position σ 5, velocity σ 2, one cell per crossing).
pub fn crossings(seed: u64) -> Simulation {
    crossings_with(seed, &CrossingsConfig::PRESET)
}

/// [`crossings`] with other crossing and birth times.
pub fn crossings_with(seed: u64, config: &CrossingsConfig) -> Simulation {
    let sensor = SensorSpec {
        detection_probability: 0.8,
        clutter_rate: 15.0,
        field_of_view: FieldOfViewSpec::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] },
    };
    let mut objects = vec![];
    let mut cells = vec![];
    for ((point, members, born), time) in CROSSINGS.into_iter().zip(config.times) {
        let mut random = Random::stream(seed, Stream::Orbit, objects.len() as u64);
        // Headings spread over half a turn so that the members cross at clearly different angles.
        let start = random.between(0.0, std::f64::consts::PI);
        for m in 0..members {
            let id = objects.len() as u64;
            let heading = start + m as f64 * std::f64::consts::PI / members as f64 + random.between(-0.2, 0.2);
            let speed = random.between(1.5, 2.5);
            let v = [speed * libm::cos(heading), speed * libm::sin(heading)];
            let is_birth = born == Some(m);
            let epoch = if is_birth { time + config.birth_offset } else { 0.0 };
            let state = [point[0] - v[0] * (time - epoch), point[1] - v[1] * (time - epoch), v[0], v[1]];
            objects.push(SimObject {
                id,
                state,
                epoch,
                in_prior: !is_birth,
                birth_time: is_birth.then_some(epoch),
                death_time: None,
            });
        }
        if born.is_some() {
            cells.push(GaussianSpec {
                mean: [point[0], point[1], 0.0, 0.0],
                covariance: [[25.0, 0.0, 0.0, 0.0], [0.0, 25.0, 0.0, 0.0], [0.0, 0.0, 4.0, 0.0], [0.0, 0.0, 0.0, 4.0]],
            });
        }
    }
    Simulation {
        name: "crossings".into(),
        description: "Eight constant-velocity objects in three crossings, two born inside a birth cell during a crossing; p_D 0.8, 15 clutter returns per scan, 30 scans".into(),
        motion: MotionSpec::ConstantVelocity { acceleration_noise: 0.01 },
        measurement_noise: [[0.25, 0.0], [0.0, 0.25]],
        birth: BirthSpec { probability: 0.01, detection: BirthDetectionSpec::AllDetected, events: Default::default(), measured: None, cells },
        sensor,
        death_probability: 0.005,
        tracker: TrackerSpec {
            gate: Some(16.0),
            max_children_per_scan: 1_000_000,
            store_overflow: StoreOverflowSpec::PruneChildren,
            numerical_failure: NumericalFailureSpec::DropTrack,
            lost_after_unseen_scans: None,
            seed,
            sampler: SamplerSpec::default(),
            selection: SelectionSpec::default(),
        },
        evaluation: EvaluationSpec {
            error_bound: 3.0,
            gospa_cutoff: 10.0,
            gospa_order: 2.0,
            confirmation_existence: 0.5,
        },
        start_time: 0.0,
        scan_interval: 1.0,
        scans: 30,
        objects,
        prior_sigma: (0.3, 0.1),
        seed,
    }
}

/// The simulation of a preset, by name.
pub fn preset(name: &str, seed: u64) -> Option<Simulation> {
    <Preset as clap::ValueEnum>::from_str(name, false).ok().map(|p| p.simulation(seed))
}

/// The presets, by the names of [`PRESETS`] (`host-sim generate <PRESET>`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Preset {
    /// Paper 003 §IV: 50 objects, 45 in the prior, 5 births.
    FiftyBirthDeath,
    /// Paper 003 §V-A: 15 objects starting in the field of view.
    FifteenCompare,
    /// A breakup cloud crossing the field of view.
    DebrisCrossing,
    /// A few constant-velocity objects in a rectangle, six scans.
    LinearSmall,
    /// Eight constant-velocity objects in three crossings, two births, heavy clutter, 30 scans.
    Crossings,
}

impl Preset {
    /// The simulation of this preset with `seed`.
    pub fn simulation(self, seed: u64) -> Simulation {
        match self {
            Preset::FiftyBirthDeath => fifty_birth_death(seed),
            Preset::FifteenCompare => fifteen_compare(seed),
            Preset::DebrisCrossing => debris_crossing(seed),
            Preset::LinearSmall => linear_small(seed),
            Preset::Crossings => crossings(seed),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circular_orbit_state_has_circular_speed() {
        let orbit = Orbit { semi_major_axis: 7000.0, eccentricity: 0.0, periapsis: 1.0, true_anomaly: 0.5 };
        let s = orbit.state(EARTH_MU);
        let r = (s[0] * s[0] + s[1] * s[1]).sqrt();
        let v = (s[2] * s[2] + s[3] * s[3]).sqrt();
        assert!((r - 7000.0).abs() < 1e-9 && (v - (EARTH_MU / 7000.0).sqrt()).abs() < 1e-12);
        assert!((s[0] * s[2] + s[1] * s[3]).abs() < 1e-6, "velocity is tangential");
    }

    #[test]
    fn every_preset_simulates_a_valid_scenario() {
        for name in PRESETS {
            let mut simulation = preset(name, 3).unwrap();
            simulation.scans = simulation.scans.min(40);
            let scenario = simulation.run();
            scenario.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
            assert_eq!(scenario.scans.len(), simulation.scans);
        }
    }

    #[test]
    fn the_same_seed_gives_the_same_scenario() {
        let mut a = linear_small(5);
        a.scans = 4;
        assert_eq!(a.run(), a.clone().run());
        let mut b = linear_small(6);
        b.scans = 4;
        assert_ne!(a.run().scans, b.run().scans);
    }

    #[test]
    fn fifteen_objects_start_in_the_field_of_view() {
        let simulation = fifteen_compare(1);
        let fov = region(&simulation.sensor);
        for object in &simulation.objects {
            assert!(fov.contains(&SVector::<f64, 2>::new(object.state[0], object.state[1])));
        }
    }
}
