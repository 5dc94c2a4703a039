//! Shared inputs of the benches: fixed association matrices and scenarios, built deterministically so that
//! every run measures the same work.
//!
//! - [`crossing_matrix`]: a dense crossing as one association matrix (the sampler benches).
//! - [`worst_case`]: a tracker at its caps with a scan that fills them (the instruction-count benches):
//!   H prior hypotheses of (N − 1) objects over K distinct tracks, and Z measurements that are all inside
//!   the gate of every object and every birth cell, so every association matrix is dense.
//! - [`radar_worst_case`]: the same for the 3-D [`RadarTracker`]: a dense cluster of LEO objects in the
//!   field of view of one of two ground radars (two-body + J2, range/azimuth/elevation).

use nalgebra::{SMatrix, SVector};
use rand_core::{Rng, SeedableRng};
use rand_xoshiro::SplitMix64;
use tracker_core::association::AssociationMatrix;
use tracker_core::config::{ChildGeneration, Selection};
use tracker_core::model::{EARTH_MU as MU, ProcessNoise};
use tracker_core::sampler::SamplerConfig;
use tracker_core::sensor::LookShape;
use tracker_core::sensor::{EarthRotation, GroundSite, Placement, Platform, ScanGeometry, SiteSensor};
use tracker_core::{
    BirthDetection, BirthModel, Config, Gaussian, Measure, MixedSensor, MotionModel, Network, NetworkConfig,
    NetworkTracker, PositionMeasurement, PriorHypothesis, PriorObject, RadarConfig, RadarNetwork, RadarTracker, Real,
    Region, Sensor, SensorKind, StepError, StepReport, StoreOverflow, TrackLabel, Tracker, TwoBody, TwoBodyJ2,
    ssa_caps,
};

/// The next output of the SplitMix64 stream whose state is `state` (advanced), for deterministic bench
/// inputs.
pub fn splitmix(state: &mut u64) -> u64 {
    let mut stream = SplitMix64::seed_from_u64(*state);
    let value = stream.next_u64();
    *state = u64::from_le_bytes(stream.state());
    value
}

/// A uniform draw in [0, 1) from [`splitmix`].
pub fn uniform(state: &mut u64) -> f64 {
    (splitmix(state) >> 11) as f64 / (1u64 << 53) as f64
}

/// A `rows × columns` association matrix like a dense crossing: each measurement is inside the gate of
/// `in_gate` objects around its own (entries from −2 to +8 nats), impossible elsewhere.
pub fn crossing_matrix<const N: usize, const Z: usize>(
    rows: usize,
    columns: usize,
    in_gate: usize,
    seed: u64,
) -> AssociationMatrix<f64, N, Z> {
    let mut state = seed;
    let mut m = AssociationMatrix::new(rows, columns, 0.0);
    let mut column_entries = vec![vec![f64::NEG_INFINITY; rows]; columns];
    for row in 0..rows {
        let centre = row * columns / rows.max(1);
        for k in 0..in_gate {
            let column = (centre + k).min(columns - 1);
            let u = (splitmix(&mut state) >> 11) as f64 / (1u64 << 53) as f64;
            if let Some(entry) = column_entries[column].get_mut(row) {
                *entry = -2.0 + 10.0 * u;
            }
        }
    }
    for (column, entries) in column_entries.iter().enumerate() {
        m.set_column(column, entries, false);
    }
    m
}

/// Earth's gravitational parameter μ (km³/s²), as in the SSA scenarios.
pub const EARTH_MU: f64 = 398_600.441_8;

/// Range (km) along the boresight of the worst-case cluster of objects.
const CLUSTER_RANGE: f64 = 7_000.0;

/// Seconds from the prior to the worst-case scan (one SSA scan interval).
pub const WORST_CASE_DT: f64 = 60.0;

/// The two-body model of the SSA scenarios (host-sim's `fifty-birth-death`).
pub fn ssa_motion<T: Real>() -> TwoBody<T> {
    TwoBody {
        mu: T::of_f64(EARTH_MU),
        acceleration_noise: T::of_f64(1e-13),
        max_step: T::of_f64(20.0),
        max_substeps: 20_000,
        min_radius: TwoBody::DEFAULT_MIN_RADIUS,
    }
}

/// The state (x, y, vx, vy) of a circular orbit at the worst-case cluster at the prior time.
fn cluster_state() -> [f64; 4] {
    let look = 15f64.to_radians();
    let (c, s) = (look.cos(), look.sin());
    let v = (EARTH_MU / CLUSTER_RANGE).sqrt();
    [CLUSTER_RANGE * c, CLUSTER_RANGE * s, -v * s, v * c]
}

fn gaussian<T: Real>(mean: [f64; 4], variances: [f64; 4]) -> Gaussian<T, 4> {
    Gaussian {
        mean: SVector::from(mean.map(T::of_f64)),
        covariance: SMatrix::from_diagonal(&SVector::from(variances.map(T::of_f64))),
    }
}

/// The default SSA configuration (host-sim's `fifty-birth-death` parameters: p_D 0.95, one clutter return
/// per scan over the 30° sector out to 30,000 km, gate 25, α = 1e-3 in `cells` birth cells, β = 1e-4, R-FISST
/// sampled children with the default sampler), with every birth cell centred on the worst-case cluster at
/// the scan time.
pub fn worst_case_config<T: Real, const B: usize>(cells: usize) -> Config<T, TwoBody<T>, PositionMeasurement<T>, 4, B> {
    let motion = ssa_motion::<f64>();
    let centre = motion
        .propagate(&SVector::from(cluster_state()), WORST_CASE_DT)
        .map(|p| p.state)
        .unwrap_or_else(|_| SVector::from(cluster_state()));
    let mut birth_cells = heapless::Vec::new();
    for _ in 0..cells.min(B) {
        let _ = birth_cells.push(gaussian([centre[0], centre[1], centre[2], centre[3]], [400.0, 400.0, 1e-2, 1e-2]));
    }
    Config {
        motion: ssa_motion(),
        measurement: PositionMeasurement::isotropic(T::of_f64(0.5)),
        sensor: Sensor {
            detection_probability: T::of_f64(0.95),
            clutter_rate: T::of_f64(1.0),
            field_of_view: Region::Sector {
                origin: [T::zero(), T::zero()],
                look_direction: T::of_f64(15f64.to_radians()),
                half_angle: T::of_f64(15f64.to_radians()),
                max_range: T::of_f64(30_000.0),
            },
        },
        birth: BirthModel {
            probability: T::of_f64(1e-3),
            cells: birth_cells,
            detection: BirthDetection::AllDetected,
            events: Default::default(),
            measured: None,
        },
        death_probability: T::of_f64(1e-4),
        gate: Some(T::of_f64(25.0)),
        children: ChildGeneration::Sampled(SamplerConfig::default()),
        selection: Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 1,
    }
}

/// A two-body tracker with position measurements and the given capacities (the SSA tracker's shape).
pub type TwoBodyTracker<T, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> =
    Tracker<T, TwoBody<T>, PositionMeasurement<T>, 4, 2, H, N, Z, K, B>;

/// A tracker at its caps and the scan that fills them (see [`worst_case`]).
pub struct WorstCase<T: Real, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> {
    /// The tracker, boxed (it is large).
    pub tracker: Box<TwoBodyTracker<T, H, N, Z, K, B>>,
    /// Z measurements, all inside every gate.
    pub measurements: Vec<SVector<T, 2>>,
    /// Time of the scan.
    pub time: f64,
    /// The scan's budget of Metropolis moves (`u64::MAX`: none).
    pub move_budget: u64,
}

impl<T: Real, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>
    WorstCase<T, H, N, Z, K, B>
{
    /// Processes the worst-case scan.
    ///
    /// # Errors
    /// The tracker's.
    pub fn step(&mut self) -> Result<StepReport<T>, StepError> {
        self.tracker.step_with_budget(self.time, &self.measurements, self.move_budget)
    }
}

/// The worst case of a two-body tracker at capacities (H, N, Z, K, B) in the default SSA configuration:
///
/// - the prior holds H hypotheses of `objects` objects each (at most N; N − 1 keeps births possible,
///   which is the most expensive case: one chain per birth cell besides the no-event chain), drawn from
///   K / N versions of each object, so the store holds `objects` × K / N of its K tracks;
/// - all objects sit in one cluster (position σ 10 km, within ±1 km of each other), the B birth cells
///   are centred on it, and the Z measurements fall within ±2 km of its predicted centre, so every
///   (measurement, object) and (measurement, birth cell) entry is inside the gate: every association
///   matrix is dense, one cluster, sampled.
///
/// # Panics
/// If the configuration or the prior is rejected (a bug in this function).
pub fn worst_case<T: Real, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
    objects: usize,
) -> WorstCase<T, H, N, Z, K, B> {
    let objects = objects.min(N);
    let versions = (K / N).max(1);
    let mut state = 0x5eed_u64;
    let base = cluster_state();
    // versions × objects distinct tracks.
    let tracks: Vec<Vec<PriorObject<T, 4>>> = (0..objects)
        .map(|label| {
            let offset = [uniform(&mut state) * 2.0 - 1.0, uniform(&mut state) * 2.0 - 1.0];
            (0..versions)
                .map(|version| {
                    let shift = 0.05 * version as f64;
                    let mean = [base[0] + offset[0] + shift, base[1] + offset[1] - shift, base[2], base[3]];
                    PriorObject { label: TrackLabel(label as u32), state: gaussian(mean, [100.0, 100.0, 1e-4, 1e-4]) }
                })
                .collect()
        })
        .collect();
    let hypotheses: Vec<Vec<PriorObject<T, 4>>> = (0..H)
        .map(|h| {
            (0..objects)
                .map(|label| {
                    // Within each block of `versions` hypotheses every object takes every version once.
                    let mut key = ((h / versions) as u64) << 32 | label as u64;
                    tracks[label][(h + (splitmix(&mut key) % versions as u64) as usize) % versions]
                })
                .collect()
        })
        .collect();
    let prior: Vec<PriorHypothesis<'_, T, 4>> = hypotheses
        .iter()
        .enumerate()
        .map(|(h, objects)| PriorHypothesis { weight: T::of_f64(1.0 / (1.0 + h as f64)), objects })
        .collect();
    let config = worst_case_config::<T, B>(B);
    let tracker = Box::new(Tracker::new(config, &prior, 0.0).expect("worst-case prior"));
    let centre = ssa_motion::<f64>().propagate(&SVector::from(base), WORST_CASE_DT).expect("two-body").state;
    let measurements = (0..Z)
        .map(|_| {
            let dx = uniform(&mut state) * 4.0 - 2.0;
            let dy = uniform(&mut state) * 4.0 - 2.0;
            SVector::from([T::of_f64(centre[0] + dx), T::of_f64(centre[1] + dy)])
        })
        .collect();
    WorstCase { tracker, measurements, time: WORST_CASE_DT, move_budget: u64::MAX }
}

/// Seconds from the prior to the 3-D worst-case scan.
pub const RADAR_WORST_CASE_DT: f64 = 10.0;

/// Two ground radars 400 km apart (σ 20 m, 0.02°; a 60° cone about the zenith above a 10° mask, range
/// 200–3000 km; p_D 0.95, one clutter return per scan), Earth rotation angle 0.3 rad at the epoch.
pub fn radar_network<T: Real>() -> RadarNetwork<T> {
    let c = T::of_f64;
    let degree = 1f64.to_radians();
    let detection = Sensor {
        detection_probability: c(0.95),
        clutter_rate: c(1.0),
        field_of_view: Region::Look {
            shape: LookShape::Cone { azimuth: T::zero(), elevation: c(90.0 * degree), half_angle: c(60.0 * degree) },
            min_elevation: c(10.0 * degree),
            range: Some([c(200.0), c(3000.0)]),
            range_rate: None,
        },
    };
    let site = |latitude: f64, longitude: f64| SiteSensor {
        platform: Platform::Ground(GroundSite {
            latitude: c(latitude * degree),
            longitude: c(longitude * degree),
            height: c(0.3),
        }),
        sigma: [c(0.02), c(0.02 * degree), c(0.02 * degree)],
        detection,
    };
    RadarNetwork::new(EarthRotation::new(c(0.3)), &[site(40.0, -105.0), site(37.0, -103.0)]).expect("valid network")
}

/// The J2 model of the 3-D benches: 20 s RK4 sub-steps, RIC process noise.
pub fn radar_motion<T: Real>() -> TwoBodyJ2<T> {
    let c = T::of_f64;
    TwoBodyJ2 {
        mu: c(tracker_core::model::EARTH_MU),
        j2: c(tracker_core::model::EARTH_J2),
        radius: c(tracker_core::model::EARTH_RADIUS),
        min_radius: c(tracker_core::model::EARTH_MIN_RADIUS),
        noise: ProcessNoise::Ric { radial: c(1e-12), in_track: c(1e-11), cross_track: c(1e-12) },
        max_step: c(20.0),
        max_substeps: 2000,
    }
}

/// A circular LEO state 900 km from radar 0 at azimuth 30°, elevation 50° at the prior time.
fn radar_cluster_state() -> [f64; 6] {
    let network = radar_network::<f64>();
    let placed = network.place(&ScanGeometry::single(0.0)).expect("placement");
    let o = placed.placed().observer;
    let enu = placed.placed().enu;
    let (azimuth, elevation, range) = (30f64.to_radians(), 50f64.to_radians(), 900.0);
    let (e, n, u) = (azimuth.sin() * elevation.cos(), azimuth.cos() * elevation.cos(), elevation.sin());
    let p: [f64; 3] = core::array::from_fn(|k| o[k] + range * (e * enu[0][k] + n * enu[1][k] + u * enu[2][k]));
    let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
    // Velocity along East, made horizontal, at circular speed.
    let east = enu[0];
    let along = (east[0] * p[0] + east[1] * p[1] + east[2] * p[2]) / r;
    let w: [f64; 3] = core::array::from_fn(|k| east[k] - along * p[k] / r);
    let norm = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    let speed = (MU / r).sqrt();
    [p[0], p[1], p[2], w[0] * speed / norm, w[1] * speed / norm, w[2] * speed / norm]
}

fn gaussian6<T: Real>(mean: [f64; 6], variances: [f64; 6]) -> Gaussian<T, 6> {
    Gaussian {
        mean: SVector::from(mean.map(T::of_f64)),
        covariance: SMatrix::from_diagonal(&SVector::from(variances.map(T::of_f64))),
    }
}

/// The 3-D tracker at its caps and the scan that fills them (see [`radar_worst_case`]).
pub struct RadarWorstCase<T: Real> {
    /// The tracker, boxed (it is large).
    pub tracker: Box<RadarTracker<T>>,
    /// Z measurements of radar 0, all inside every gate.
    pub measurements: Vec<SVector<T, 3>>,
    /// The scan's geometry (radar 0).
    pub geometry: ScanGeometry<T>,
}

impl<T: Real> RadarWorstCase<T> {
    /// Processes the worst-case scan.
    ///
    /// # Errors
    /// The tracker's.
    pub fn step(&mut self) -> Result<StepReport<T>, StepError> {
        self.tracker.step_scan(&self.geometry, &self.measurements)
    }
}

/// The worst case of [`RadarTracker`] at [`ssa_caps`] (K = `TRACKS_3D`): H hypotheses of N − 1 objects
/// drawn from K / N versions of each, all in one cluster (position σ 3 km, within ±1 km of each other) in
/// radar 0's field of view, the B birth cells centred on it, and Z measurements within ±1 km of its
/// predicted centre, so every entry is inside the gate (25) and every matrix dense, as in [`worst_case`].
///
/// # Panics
/// If the configuration or the prior is rejected (a bug in this function).
pub fn radar_worst_case<T: Real>() -> RadarWorstCase<T> {
    let mut state = 0x3d_5eed_u64;
    let (hypotheses, cells, centre) = cluster_prior::<T>(&mut state);
    let prior: Vec<PriorHypothesis<'_, T, 6>> = hypotheses
        .iter()
        .enumerate()
        .map(|(h, objects)| PriorHypothesis { weight: T::of_f64(1.0 / (1.0 + h as f64)), objects })
        .collect();
    let config: RadarConfig<T> = Config {
        motion: radar_motion(),
        measurement: radar_network(),
        sensor: radar_network::<T>().sensors()[0].detection,
        birth: cluster_births(cells),
        death_probability: T::of_f64(1e-4),
        gate: Some(T::of_f64(25.0)),
        children: ChildGeneration::Sampled(SamplerConfig::default()),
        selection: Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 1,
    };
    let tracker = Box::new(Tracker::new(config, &prior, 0.0).expect("worst-case prior"));
    let geometry = ScanGeometry::single(RADAR_WORST_CASE_DT);
    let placed = radar_network::<f64>().place(&ScanGeometry::single(RADAR_WORST_CASE_DT)).expect("placement");
    let measurements = cluster_points(&mut state, &centre)
        .map(|point| {
            let z = placed.measure(&point);
            SVector::from([T::of_f64(z[0]), T::of_f64(z[1]), T::of_f64(z[2])])
        })
        .collect();
    RadarWorstCase { tracker, measurements, geometry }
}

/// The fused tracker at its caps and the scan that fills them (see [`network_worst_case`]).
pub struct NetworkWorstCase<T: Real> {
    /// The tracker, boxed (it is large).
    pub tracker: Box<NetworkTracker<T>>,
    /// Z measurements of the radar with range-rate, all inside every gate (padded to four components).
    pub measurements: Vec<SVector<T, 4>>,
    /// The scan's geometry (the radar with range-rate).
    pub geometry: ScanGeometry<T>,
}

impl<T: Real> NetworkWorstCase<T> {
    /// Processes the worst-case scan.
    ///
    /// # Errors
    /// The tracker's.
    pub fn step(&mut self) -> Result<StepReport<T>, StepError> {
        self.tracker.step_scan(&self.geometry, &self.measurements)
    }
}

/// The sensor of [`network_worst_case`] measuring all four components: the radar with range-rate.
pub const NETWORK_WORST_CASE_SENSOR: usize = 1;

/// A network of every kind ([`SensorKind::ALL`], in that order) at radar 0's site of [`radar_network`],
/// each with that radar's field of view and the windows its kind measures (range-rate ±8 km/s), σ 20 m,
/// 0.02° and 10 m/s in its own components.
pub fn mixed_network<T: Real>() -> Network<T> {
    let radar = radar_network::<f64>().sensors()[0];
    let c = T::of_f64;
    let sensors = SensorKind::ALL.map(|kind| {
        let components = kind.components();
        let sigma: [T; 4] = core::array::from_fn(|i| match components.get(i) {
            Some(&"range") => c(radar.sigma[0]),
            Some(&"range_rate") => c(0.01),
            Some(_) => c(radar.sigma[1]),
            None => T::zero(),
        });
        let Region::Look { shape: LookShape::Cone { azimuth, elevation, half_angle }, min_elevation, .. } =
            radar.detection.field_of_view
        else {
            unreachable!("radar_network's field of view is a cone")
        };
        let axes = kind.axes();
        let field_of_view = Region::Look {
            shape: LookShape::Cone { azimuth: c(azimuth), elevation: c(elevation), half_angle: c(half_angle) },
            min_elevation: c(min_elevation),
            range: axes.range.then_some([c(200.0), c(3000.0)]),
            range_rate: axes.range_rate.then_some([c(-8.0), c(8.0)]),
        };
        let Platform::Ground(site) = radar.platform else { unreachable!("radar_network's sites are on the ground") };
        MixedSensor {
            kind,
            sensor: SiteSensor {
                platform: Platform::Ground(GroundSite {
                    latitude: c(site.latitude),
                    longitude: c(site.longitude),
                    height: c(site.height),
                }),
                sigma,
                detection: Sensor {
                    detection_probability: c(radar.detection.detection_probability),
                    clutter_rate: c(radar.detection.clutter_rate),
                    field_of_view,
                },
            },
        }
    });
    Network::new(EarthRotation::new(c(0.3)), &sensors).expect("valid network")
}

/// The worst case of [`NetworkTracker`] at [`ssa_caps`]: the prior and birth cells of
/// [`radar_worst_case`], a [`mixed_network`] of every kind, and Z measurements of the radar with
/// range-rate (four components, [`NETWORK_WORST_CASE_SENSOR`]) within ±1 km of the cluster's predicted
/// centre, so every entry is inside the gate and every matrix dense.
///
/// # Panics
/// If the configuration or the prior is rejected (a bug in this function).
pub fn network_worst_case<T: Real>() -> NetworkWorstCase<T> {
    let mut state = 0x3d_5eed_u64;
    let (hypotheses, cells, centre) = cluster_prior::<T>(&mut state);
    let prior: Vec<PriorHypothesis<'_, T, 6>> = hypotheses
        .iter()
        .enumerate()
        .map(|(h, objects)| PriorHypothesis { weight: T::of_f64(1.0 / (1.0 + h as f64)), objects })
        .collect();
    let network = mixed_network::<T>();
    let config: NetworkConfig<T> = Config {
        motion: radar_motion(),
        measurement: network,
        sensor: network.sensors()[0].sensor.detection,
        birth: cluster_births(cells),
        death_probability: T::of_f64(1e-4),
        gate: Some(T::of_f64(25.0)),
        children: ChildGeneration::Sampled(SamplerConfig::default()),
        selection: Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 1,
    };
    let tracker = Box::new(Tracker::new(config, &prior, 0.0).expect("worst-case prior"));
    let geometry = ScanGeometry { sensor: NETWORK_WORST_CASE_SENSOR, time: RADAR_WORST_CASE_DT, observer: None };
    let at = ScanGeometry { sensor: NETWORK_WORST_CASE_SENSOR, time: RADAR_WORST_CASE_DT, observer: None };
    let placed = mixed_network::<f64>().place(&at).expect("placement");
    let measurements = cluster_points(&mut state, &centre).map(|point| placed.measure(&point).map(T::of_f64)).collect();
    NetworkWorstCase { tracker, measurements, geometry }
}

/// Z points within ±1 km of `centre` in position (its velocity), drawn from `state`.
fn cluster_points(state: &mut u64, centre: &SVector<f64, 6>) -> impl Iterator<Item = SVector<f64, 6>> {
    (0..ssa_caps::MEASUREMENTS)
        .map(|_| {
            let mut point = *centre;
            for k in 0..3 {
                point[k] += uniform(state) * 2.0 - 1.0;
            }
            point
        })
        .collect::<Vec<_>>()
        .into_iter()
}

/// The birth model of the 3-D worst cases: α = 10⁻³ in each of `cells`, all detected.
fn cluster_births<T: Real>(
    cells: heapless::Vec<Gaussian<T, 6>, { ssa_caps::BIRTH_CELLS }>,
) -> BirthModel<T, 6, { ssa_caps::BIRTH_CELLS }> {
    BirthModel {
        probability: T::of_f64(1e-3),
        cells,
        detection: BirthDetection::AllDetected,
        events: Default::default(),
        measured: None,
    }
}

/// The prior of the 3-D worst cases (see [`radar_worst_case`]): H hypotheses of N − 1 objects, the B
/// birth cells and the cluster's centre at the scan time.
#[allow(clippy::type_complexity)]
fn cluster_prior<T: Real>(
    state: &mut u64,
) -> (Vec<Vec<PriorObject<T, 6>>>, heapless::Vec<Gaussian<T, 6>, { ssa_caps::BIRTH_CELLS }>, SVector<f64, 6>) {
    const H: usize = ssa_caps::HYPOTHESES;
    const N: usize = ssa_caps::OBJECTS;
    const K: usize = ssa_caps::TRACKS_3D;
    const B: usize = ssa_caps::BIRTH_CELLS;
    let objects = N - 1;
    let versions = (K / N).max(1);
    let base = radar_cluster_state();
    let tracks: Vec<Vec<PriorObject<T, 6>>> = (0..objects)
        .map(|label| {
            let offset: [f64; 3] = core::array::from_fn(|_| uniform(state) * 2.0 - 1.0);
            (0..versions)
                .map(|version| {
                    let shift = 0.05 * version as f64;
                    let mut mean = base;
                    for k in 0..3 {
                        mean[k] += offset[k] + shift;
                    }
                    let state = gaussian6(mean, [9.0, 9.0, 9.0, 1e-6, 1e-6, 1e-6]);
                    PriorObject { label: TrackLabel(label as u32), state }
                })
                .collect()
        })
        .collect();
    let hypotheses: Vec<Vec<PriorObject<T, 6>>> = (0..H)
        .map(|h| {
            (0..objects)
                .map(|label| {
                    let mut key = ((h / versions) as u64) << 32 | label as u64;
                    tracks[label][(h + (splitmix(&mut key) % versions as u64) as usize) % versions]
                })
                .collect()
        })
        .collect();
    let motion = radar_motion::<f64>();
    let centre = motion.propagate(&SVector::from(base), RADAR_WORST_CASE_DT).expect("J2").state;
    let mut cells = heapless::Vec::new();
    for _ in 0..B {
        let mean: [f64; 6] = core::array::from_fn(|k| centre[k]);
        let _ = cells.push(gaussian6(mean, [100.0, 100.0, 100.0, 1e-2, 1e-2, 1e-2]));
    }
    (hypotheses, cells, centre)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn radar_worst_case_fills_the_caps_with_dense_matrices() {
        // A debug build moves the 424 KB tracker through several stack frames: a roomy thread.
        fn check<T: Real>() {
            let mut case = radar_worst_case::<T>();
            assert_eq!(case.tracker.hypotheses().len(), ssa_caps::HYPOTHESES);
            let report = case.step().unwrap();
            assert_eq!(report.hypotheses, ssa_caps::HYPOTHESES);
            assert_eq!(report.numerical_drops.count, 0);
            assert!(report.sampler_steps > 0, "sampled children: {report:?}");
            assert_eq!(report.measurements, ssa_caps::MEASUREMENTS);
        }
        let check = || {
            check::<f64>();
            check::<f32>();
        };
        std::thread::Builder::new().stack_size(64 << 20).spawn(check).unwrap().join().unwrap();
    }

    #[test]
    fn network_worst_case_fills_the_caps_with_dense_matrices() {
        fn check<T: Real>() {
            let mut case = network_worst_case::<T>();
            assert_eq!(case.tracker.hypotheses().len(), ssa_caps::HYPOTHESES);
            let report = case.step().unwrap();
            assert_eq!(report.hypotheses, ssa_caps::HYPOTHESES);
            assert_eq!(report.numerical_drops.count, 0);
            assert!(report.sampler_steps > 0, "sampled children: {report:?}");
            assert_eq!(report.measurements, ssa_caps::MEASUREMENTS);
            // Every kind is in the network; the scan's measures all four components.
            assert_eq!(case.tracker.config().measurement.kinds().count(), SensorKind::ALL.len());
            assert!(case.measurements.iter().all(|z| z.iter().all(|v| *v != T::zero())));
        }
        let check = || {
            check::<f64>();
            check::<f32>();
        };
        std::thread::Builder::new().stack_size(64 << 20).spawn(check).unwrap().join().unwrap();
    }

    #[test]
    fn worst_case_fills_the_caps_with_dense_matrices() {
        // Small caps keep the test fast; the construction is the same at the SSA caps.
        let mut case = worst_case::<f64, 4, 8, 6, 32, 2>(7);
        assert_eq!(case.tracker.hypotheses().len(), 4);
        assert_eq!(case.tracker.tracks().len(), 28);
        let report = case.step().unwrap();
        assert_eq!(report.hypotheses, 4);
        assert_eq!(report.births_beyond_object_capacity, 0);
        // Every measurement is inside every gate: δ finite for every track and birth cell.
        let config = worst_case_config::<f64, 2>(2);
        let weights = tracker_core::weight::WeightModel::from_config(&config);
        let prior = worst_case::<f64, 4, 8, 6, 32, 2>(7);
        for track in prior.tracker.tracks() {
            let predicted = tracker_core::ekf::predict(&config.motion, &track.state, WORST_CASE_DT).unwrap();
            let innovation = tracker_core::ekf::innovation(&config.measurement, &predicted).unwrap();
            for z in &prior.measurements {
                assert!(weights.entry(&innovation, z).is_finite());
            }
        }
        for cell in &config.birth.cells {
            let innovation = tracker_core::ekf::innovation(&config.measurement, cell).unwrap();
            for z in &prior.measurements {
                assert!(weights.entry(&innovation, z).is_finite());
            }
        }
    }

    #[test]
    fn host_sim_perf_measures_the_same_crossing_matrices() {
        for (rows, columns, in_gate, seed) in [(32, 64, 8, 1), (16, 32, 4, 3), (5, 9, 2, 7)] {
            let ours: AssociationMatrix<f64, 64, 32> = crossing_matrix(rows, columns, in_gate, seed);
            assert_eq!(ours, host_sim::experiments::perf::crossing_matrix(rows, columns, in_gate, seed));
        }
    }
}
