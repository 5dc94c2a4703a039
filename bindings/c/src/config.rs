//! The C configuration: plain `#[repr(C)]` structs of `double`s and `uint32_t` codes that a C program can
//! write as a static initialiser, for every default tracker (planar, radar, optical, network) in both
//! scalars. Values are given in `double` and rounded once (`value as float`) for the `f32` trackers, as
//! host-sim and the QEMU firmware round them. Enumerations are `uint32_t` fields checked on use, so a bad
//! value is a status code, never undefined behaviour.

use tracker_core::ssa_caps;

/// Sensors a 3-D configuration holds (the network tracker's capacity; the radar and optical trackers take
/// at most [`RFISST_MAX_SENSORS_SINGLE_KIND`]).
pub const RFISST_MAX_SENSORS: usize = 8;
/// Sensors of the radar and optical trackers.
pub const RFISST_MAX_SENSORS_SINGLE_KIND: usize = 4;
/// Birth cells a configuration holds.
pub const RFISST_MAX_BIRTH_CELLS: usize = 8;
/// Objects one prior hypothesis holds (as `RFISST_MAX_OBJECTS`). Kept for compatibility: the prior
/// is no longer limited over all its hypotheses together, since its objects are converted one at a time
/// as the tracker reads them (no buffer), with or without `std`.
pub const RFISST_MAX_PRIOR_OBJECTS: usize = 64;
/// Measurements one scan may hold (the trackers' Z).
pub const RFISST_MAX_MEASUREMENTS: usize = 32;
/// Hypotheses a tracker keeps (H∞).
pub const RFISST_MAX_HYPOTHESES: usize = 32;
/// Objects one hypothesis holds (N).
pub const RFISST_MAX_OBJECTS: usize = 64;
/// Components of a measurement of the network tracker (each kind's components first, then zeros).
pub const RFISST_NETWORK_DIMENSION: usize = 4;

// Literal values, so that cbindgen writes them into the header; tracker-core's capacities must agree.
const _: () = assert!(
    RFISST_MAX_SENSORS == ssa_caps::NETWORK_SENSORS
        && RFISST_MAX_SENSORS_SINGLE_KIND == ssa_caps::SENSORS
        && RFISST_MAX_BIRTH_CELLS == ssa_caps::BIRTH_CELLS
        && RFISST_MAX_PRIOR_OBJECTS == ssa_caps::OBJECTS
        && RFISST_MAX_MEASUREMENTS == ssa_caps::MEASUREMENTS
        && RFISST_MAX_HYPOTHESES == ssa_caps::HYPOTHESES
        && RFISST_MAX_OBJECTS == ssa_caps::OBJECTS
        && RFISST_NETWORK_DIMENSION == tracker_core::model::MIXED_DIMENSION
);

/// A field of view. `type` selects the variant and the fields it reads (`RFISST_REGION_*`); angles in
/// radians.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstRegion {
    /// `RFISST_REGION_EVERYWHERE` (reads `volume`), `_RECTANGLE` (`min`, `max`), `_SECTOR` (`origin`,
    /// `look_direction`, `half_angle`, `max_range`) or `_LOOK` (`shape` and its fields, `min_elevation`,
    /// the range and range-rate windows).
    pub r#type: u32,
    /// Clutter volume of `EVERYWHERE`.
    pub volume: f64,
    /// Lower corner of `RECTANGLE`.
    pub min: [f64; 2],
    /// Upper corner of `RECTANGLE`.
    pub max: [f64; 2],
    /// Sensor position of `SECTOR`.
    pub origin: [f64; 2],
    /// Boresight of `SECTOR` (from +x, counter-clockwise).
    pub look_direction: f64,
    /// Half opening angle of `SECTOR`, or of a `LOOK` cone.
    pub half_angle: f64,
    /// Largest range of `SECTOR`.
    pub max_range: f64,
    /// `RFISST_LOOK_CONE` (`azimuth`, `elevation`, `half_angle`) or `RFISST_LOOK_BOX` (`azimuth`,
    /// `half_width`, `elevation_window`).
    pub shape: u32,
    /// Boresight (cone) or centre (box) azimuth, from North towards East.
    pub azimuth: f64,
    /// Boresight elevation of a cone.
    pub elevation: f64,
    /// Half azimuth extent of a box.
    pub half_width: f64,
    /// `[min, max]` elevation of a box.
    pub elevation_window: [f64; 2],
    /// Elevation mask of `LOOK`.
    pub min_elevation: f64,
    /// Whether `range` is given (required exactly when the sensor measures range).
    pub has_range: u32,
    /// `[min, max]` range (km).
    pub range: [f64; 2],
    /// Whether `range_rate` is given (required exactly when the sensor measures range-rate).
    pub has_range_rate: u32,
    /// `[min, max]` range-rate (km/s).
    pub range_rate: [f64; 2],
}

/// How a sensor detects: p_D inside its field of view, Poisson clutter of mean `clutter_rate` per scan.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstDetection {
    /// p_D.
    pub detection_probability: f64,
    /// λ_C.
    pub clutter_rate: f64,
    /// Where it sees.
    pub field_of_view: RfisstRegion,
}

/// One sensor of a 3-D tracker.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstSensor {
    /// What it measures (`RFISST_SENSOR_*`): the radar tracker takes `RADAR` only, the optical tracker
    /// `OPTICAL` only, the network tracker any.
    pub kind: u32,
    /// `RFISST_PLATFORM_GROUND` (reads `latitude`, `longitude`, `height`) or `RFISST_PLATFORM_SPACECRAFT`
    /// (the scan gives the observer).
    pub platform: u32,
    /// Geodetic latitude (rad).
    pub latitude: f64,
    /// Longitude (rad, East).
    pub longitude: f64,
    /// Height above the WGS-84 ellipsoid (km).
    pub height: f64,
    /// Noise standard deviations of the kind's components in order, then zeros.
    pub sigma: [f64; 4],
    /// How it detects.
    pub detection: RfisstDetection,
    /// Network tracker only: where the births of its measurements come from (`RFISST_BIRTHS_*`):
    /// `FROM_MODEL` (0, the configuration's `measured_births.region`), `REGION` (its own
    /// `birth_region`) or `OFF` (its measurements start no track). The radar and optical trackers take
    /// `FROM_MODEL` only.
    pub births: u32,
    /// The sensor's own admissible region, read when `births` is `RFISST_BIRTHS_REGION`.
    pub birth_region: RfisstAdmissibleRegion,
}

/// The admissible region a measurement's birth density is cut from (tracker-core's `AdmissibleRegion`,
/// docs/maths.md §5.7): bound orbits between two radii, up to an inclination, or a shell of radii.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstAdmissibleRegion {
    /// Gravitational parameter μ (km³/s²).
    pub mu: f64,
    /// Smallest perigee radius (km).
    pub min_perigee_radius: f64,
    /// Largest apogee radius (km).
    pub max_apogee_radius: f64,
    /// Largest inclination (rad).
    pub max_inclination: f64,
    /// `[min, max]` radius of the shell the missing range is drawn from (km).
    pub shell: [f64; 2],
    /// Headings of the missing velocity direction.
    pub headings: u32,
    /// Speeds.
    pub speeds: u32,
    /// Climb angles.
    pub climbs: u32,
    /// Ranges of an angles-only measurement.
    pub ranges: u32,
    /// Standard deviation of each component's velocity (km/s).
    pub velocity_sigma: f64,
}

/// Births from the measurements (tracker-core's `MeasuredBirths`, docs/maths.md §5.8): the measurements
/// no track explains become birth cells of a pool. Births from tracklets are not in the C configuration.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstMeasuredBirths {
    /// 1: on; 0: off (the other fields are not read).
    pub enabled: u32,
    /// The admissible region of the sensors whose births come from the model.
    pub region: RfisstAdmissibleRegion,
    /// Expected births per scan λ_B.
    pub expected_births: f64,
    /// The largest α of one measurement's cells together, in (0, 1).
    pub max_probability: f64,
    /// The smallest r_U for a measurement to make cells, in [0, 1].
    pub min_unexplained: f64,
    /// Seconds a cell lives after its measurement.
    pub lifetime: f64,
    /// 1: the cells the full pool does not keep wait for a later measurement to link with; 0: dropped.
    pub link_waiting: u32,
}

/// A Gaussian. The 3-D trackers use all of it; the planar tracker its first 4 mean entries and the
/// upper-left 4×4 block of the covariance (the rest is ignored on input and 0 on output).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstGaussian {
    /// Mean: planar (x, y, vx, vy), 3-D (x, y, z, vx, vy, vz) in km and km/s.
    pub mean: [f64; 6],
    /// Covariance, row-major 6×6.
    pub covariance: [f64; 36],
}

/// R-FISST's Metropolis sampler (tracker-core's `SamplerConfig`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstSampler {
    /// Burn-in steps per chain.
    pub burn_in: u32,
    /// Steps per chain after burn-in.
    pub steps: u32,
    /// `RFISST_PROPOSAL_PAPER`, `_MOVE_OR_SWAP` or `_INFORMED`.
    pub proposal: u32,
    /// 1: sample each cluster apart; 0: one chain over the whole matrix.
    pub clusters: u32,
    /// Clusters with at most this many leaves are enumerated exactly.
    pub exhaustive_limit: u64,
    /// 1: start each chain from the best association.
    pub exact_start: u32,
}

/// A tracker configuration. `rfisst_config_default` fills one for a kind; change what differs.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstConfig {
    /// Gravitational parameter μ (km³/s²).
    pub mu: f64,
    /// Planar: white acceleration noise density.
    pub acceleration_noise: f64,
    /// 3-D: J2 (0: two-body).
    pub j2: f64,
    /// 3-D: J2's reference radius (km).
    pub radius: f64,
    /// Smallest distance from the centre a state may have (km).
    pub min_radius: f64,
    /// 3-D: `RFISST_NOISE_ISOTROPIC` (reads `process_noise[0]`) or `RFISST_NOISE_RIC` (radial, in-track,
    /// cross-track).
    pub process_noise_type: u32,
    /// 3-D: process noise densities (km²/s³).
    pub process_noise: [f64; 3],
    /// Largest RK4 sub-step (s).
    pub max_step: f64,
    /// Most sub-steps one propagation takes.
    pub max_substeps: u32,
    /// Planar: the position measurement's noise covariance R, row-major 2×2.
    pub position_noise: [f64; 4],
    /// Planar: the sensor (3-D trackers use each sensor's own).
    pub sensor: RfisstDetection,
    /// 3-D: Earth rotation angle at time 0 (rad; `rfisst_gmst_iau82(jd)` of the epoch).
    pub earth_rotation_angle: f64,
    /// 3-D: the sensors, `sensor_count` of them.
    pub sensors: [RfisstSensor; RFISST_MAX_SENSORS],
    /// 3-D: how many of `sensors` are used (at least 1).
    pub sensor_count: u32,
    /// α: probability of a birth in each cell.
    pub birth_probability: f64,
    /// The birth cells, `birth_cell_count` of them.
    pub birth_cells: [RfisstGaussian; RFISST_MAX_BIRTH_CELLS],
    /// How many of `birth_cells` are used.
    pub birth_cell_count: u32,
    /// `RFISST_BIRTH_ALL_DETECTED` or `RFISST_BIRTH_ALLOW_UNDETECTED`.
    pub birth_detection: u32,
    /// `RFISST_BIRTH_FIRST_ORDER` or `RFISST_BIRTH_INDEPENDENT`.
    pub birth_events: u32,
    /// Births from the measurements (off by default).
    pub measured_births: RfisstMeasuredBirths,
    /// β: probability that an object in the field of view dies before a scan.
    pub death_probability: f64,
    /// 1: gate at `gate` (Mahalanobis distance); 0: no gate.
    pub has_gate: u32,
    /// The gate.
    pub gate: f64,
    /// `RFISST_CHILDREN_SAMPLED` (R-FISST, reads `sampler`) or `RFISST_CHILDREN_EXHAUSTIVE` (reads
    /// `max_children_per_scan`).
    pub children: u32,
    /// Budget of exhaustive children per scan.
    pub max_children_per_scan: u64,
    /// The sampler of sampled children.
    pub sampler: RfisstSampler,
    /// `RFISST_SELECTION_TOP_WEIGHT`, `RFISST_SELECTION_SAMPLED_BY_WEIGHT` or
    /// `RFISST_SELECTION_TOP_WEIGHT_WITHIN` (reads `selection_floor_decades`).
    pub selection: u32,
    /// With `RFISST_SELECTION_TOP_WEIGHT_WITHIN`: the children lighter than 10^-decades times the heaviest
    /// are dropped (0..=255; docs/maths.md §8.1). Not read otherwise.
    pub selection_floor_decades: u32,
    /// `RFISST_STORE_OVERFLOW_PRUNE_CHILDREN` or `RFISST_STORE_OVERFLOW_ERROR`.
    pub store_overflow: u32,
    /// `RFISST_NUMERICAL_FAILURE_DROP_TRACK` or `RFISST_NUMERICAL_FAILURE_ERROR`.
    pub numerical_failure: u32,
    /// The lost-track rule: 0, tracks are never declared lost (the exact recursion, the default); n in
    /// 1..=65535, a track unseen in n consecutive scans is dropped (`TrackLoss::AfterUnseenScans`; needs a
    /// gate, docs/maths.md).
    pub lost_after_unseen_scans: u32,
    /// The tracker's random seed.
    pub seed: u64,
}

/// One object of a prior hypothesis.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstPriorObject {
    /// Its label (distinct within a hypothesis).
    pub label: u32,
    /// Its state.
    pub state: RfisstGaussian,
}

/// One prior hypothesis: a weight (the weights need not add up to 1) and its objects.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct RfisstPriorHypothesis {
    /// Its weight (finite, ≥ 0).
    pub weight: f64,
    /// Its objects (may be null when `object_count` is 0).
    pub objects: *const RfisstPriorObject,
    /// How many.
    pub object_count: usize,
}

/// One track of a hypothesis.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RfisstTrack {
    /// The object's label.
    pub label: u32,
    /// Existence probability of this track (its weight summed over the hypotheses holding it).
    pub existence: f64,
    /// Its state (planar: the first 4 entries and the upper-left 4×4 block, the rest 0).
    pub state: RfisstGaussian,
}

/// What one scan did (tracker-core's `StepReport`).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RfisstStepReport {
    /// Scans processed so far, this one included.
    pub scan: u64,
    /// Measurements in the scan.
    pub measurements: usize,
    /// Hypotheses kept.
    pub hypotheses: usize,
    /// Tracks in the store.
    pub tracks: usize,
    /// Children with non-zero weight generated.
    pub children: u64,
    /// Fraction of the children's weight kept.
    pub captured_mass: f64,
    /// Metropolis moves made.
    pub sampler_steps: u64,
    /// Tracks dropped for a numerical failure.
    pub numerical_drops: usize,
    /// Expected number of objects after the scan.
    pub expected_cardinality: f64,
}

/// Field-of-view variants ([`RfisstRegion::r#type`]).
pub mod region {
    /// No boundary.
    pub const RFISST_REGION_EVERYWHERE: u32 = 0;
    /// Axis-aligned rectangle (planar).
    pub const RFISST_REGION_RECTANGLE: u32 = 1;
    /// Circular sector (planar).
    pub const RFISST_REGION_SECTOR: u32 = 2;
    /// Look angles of a 3-D sensor.
    pub const RFISST_REGION_LOOK: u32 = 3;
    /// A cone of look directions.
    pub const RFISST_LOOK_CONE: u32 = 0;
    /// An azimuth/elevation box.
    pub const RFISST_LOOK_BOX: u32 = 1;
}

/// Sensor kinds and platforms ([`RfisstSensor`]).
pub mod sensor {
    /// Range, azimuth, elevation (km, rad, rad).
    pub const RFISST_SENSOR_RADAR: u32 = 0;
    /// Range, azimuth, elevation, range-rate.
    pub const RFISST_SENSOR_RADAR_RANGE_RATE: u32 = 1;
    /// Topocentric right ascension and declination (rad).
    pub const RFISST_SENSOR_OPTICAL: u32 = 2;
    /// Azimuth and elevation.
    pub const RFISST_SENSOR_AZ_EL: u32 = 3;
    /// Range.
    pub const RFISST_SENSOR_RANGE: u32 = 4;
    /// Range and range-rate.
    pub const RFISST_SENSOR_RANGE_RANGE_RATE: u32 = 5;
    /// A sensor's births come from the configuration's `measured_births.region`.
    pub const RFISST_BIRTHS_FROM_MODEL: u32 = 0;
    /// A sensor's births come from its own `birth_region`.
    pub const RFISST_BIRTHS_REGION: u32 = 1;
    /// A sensor's measurements start no track.
    pub const RFISST_BIRTHS_OFF: u32 = 2;
    /// A ground site.
    pub const RFISST_PLATFORM_GROUND: u32 = 0;
    /// A spacecraft: each scan gives the observer's inertial state.
    pub const RFISST_PLATFORM_SPACECRAFT: u32 = 1;
}

/// The other enumerations of [`RfisstConfig`].
pub mod choice {
    /// Same density along every axis.
    pub const RFISST_NOISE_ISOTROPIC: u32 = 0;
    /// Radial, in-track, cross-track densities.
    pub const RFISST_NOISE_RIC: u32 = 1;
    /// Births are detected when born.
    pub const RFISST_BIRTH_ALL_DETECTED: u32 = 0;
    /// Births may go undetected.
    pub const RFISST_BIRTH_ALLOW_UNDETECTED: u32 = 1;
    /// R-FISST's first-order birth/death events.
    pub const RFISST_BIRTH_FIRST_ORDER: u32 = 0;
    /// Independent births per cell.
    pub const RFISST_BIRTH_INDEPENDENT: u32 = 1;
    /// R-FISST's sampled children.
    pub const RFISST_CHILDREN_SAMPLED: u32 = 0;
    /// Every child (HOMHT).
    pub const RFISST_CHILDREN_EXHAUSTIVE: u32 = 1;
    /// Paper 003's proposal.
    pub const RFISST_PROPOSAL_PAPER: u32 = 0;
    /// Move or swap.
    pub const RFISST_PROPOSAL_MOVE_OR_SWAP: u32 = 1;
    /// Informed (the default).
    pub const RFISST_PROPOSAL_INFORMED: u32 = 2;
    /// Keep the heaviest hypotheses.
    pub const RFISST_SELECTION_TOP_WEIGHT: u32 = 0;
    /// Sample hypotheses by weight.
    pub const RFISST_SELECTION_SAMPLED_BY_WEIGHT: u32 = 1;
    /// Keep the heaviest hypotheses within `selection_floor_decades` decades of the heaviest.
    pub const RFISST_SELECTION_TOP_WEIGHT_WITHIN: u32 = 2;
    /// Drop children that do not fit the track store.
    pub const RFISST_STORE_OVERFLOW_PRUNE_CHILDREN: u32 = 0;
    /// Fail the scan when the store overflows.
    pub const RFISST_STORE_OVERFLOW_ERROR: u32 = 1;
    /// Drop a track whose EKF fails.
    pub const RFISST_NUMERICAL_FAILURE_DROP_TRACK: u32 = 0;
    /// Fail the scan.
    pub const RFISST_NUMERICAL_FAILURE_ERROR: u32 = 1;
}

impl RfisstRegion {
    /// Everywhere, volume 1 (a placeholder to overwrite).
    pub const EMPTY: Self = Self {
        r#type: region::RFISST_REGION_EVERYWHERE,
        volume: 1.0,
        min: [0.0; 2],
        max: [0.0; 2],
        origin: [0.0; 2],
        look_direction: 0.0,
        half_angle: 0.0,
        max_range: 0.0,
        shape: region::RFISST_LOOK_CONE,
        azimuth: 0.0,
        elevation: 0.0,
        half_width: 0.0,
        elevation_window: [0.0; 2],
        min_elevation: 0.0,
        has_range: 0,
        range: [0.0; 2],
        has_range_rate: 0,
        range_rate: [0.0; 2],
    };
}

impl RfisstGaussian {
    /// All zeros.
    pub const ZERO: Self = Self { mean: [0.0; 6], covariance: [0.0; 36] };
}

impl RfisstSensor {
    /// A radar at (0, 0, 0) with no field of view set (a placeholder to overwrite).
    pub const EMPTY: Self = Self {
        kind: sensor::RFISST_SENSOR_RADAR,
        platform: sensor::RFISST_PLATFORM_GROUND,
        latitude: 0.0,
        longitude: 0.0,
        height: 0.0,
        sigma: [0.0; 4],
        detection: RfisstDetection {
            detection_probability: 0.9,
            clutter_rate: 0.0,
            field_of_view: RfisstRegion::EMPTY,
        },
        births: sensor::RFISST_BIRTHS_FROM_MODEL,
        birth_region: RfisstAdmissibleRegion::ZERO,
    };
}

impl RfisstAdmissibleRegion {
    /// All zeros (a placeholder to overwrite).
    pub const ZERO: Self = Self {
        mu: 0.0,
        min_perigee_radius: 0.0,
        max_apogee_radius: 0.0,
        max_inclination: 0.0,
        shell: [0.0; 2],
        headings: 0,
        speeds: 0,
        climbs: 0,
        ranges: 0,
        velocity_sigma: 0.0,
    };
}

impl RfisstMeasuredBirths {
    /// Off.
    pub const OFF: Self = Self {
        enabled: 0,
        region: RfisstAdmissibleRegion::ZERO,
        expected_births: 0.0,
        max_probability: 0.0,
        min_unexplained: 0.0,
        lifetime: 0.0,
        link_waiting: 0,
    };
}

impl RfisstConfig {
    /// The defaults of `rfisst_config_default`: the Earth's μ, J2 and radius, tracker-core's sampler
    /// defaults, no sensor and no birth cell; `planar` selects the planar model's μ (1) and minimum radius.
    pub fn default_for(planar: bool) -> Self {
        use tracker_core::model::{EARTH_J2, EARTH_MIN_RADIUS, EARTH_MU, EARTH_RADIUS};
        let sampler = tracker_core::sampler::SamplerConfig::DEFAULT;
        Self {
            mu: if planar { 1.0 } else { EARTH_MU },
            acceleration_noise: 0.0,
            j2: EARTH_J2,
            radius: EARTH_RADIUS,
            min_radius: if planar { 0.0 } else { EARTH_MIN_RADIUS },
            process_noise_type: choice::RFISST_NOISE_ISOTROPIC,
            process_noise: [0.0; 3],
            max_step: if planar { 1.0 } else { 20.0 },
            max_substeps: 1000,
            position_noise: [1.0, 0.0, 0.0, 1.0],
            sensor: RfisstDetection {
                detection_probability: 0.9,
                clutter_rate: 0.0,
                field_of_view: RfisstRegion::EMPTY,
            },
            earth_rotation_angle: 0.0,
            sensors: [RfisstSensor::EMPTY; RFISST_MAX_SENSORS],
            sensor_count: 0,
            birth_probability: 0.0,
            birth_cells: [RfisstGaussian::ZERO; RFISST_MAX_BIRTH_CELLS],
            birth_cell_count: 0,
            birth_detection: choice::RFISST_BIRTH_ALL_DETECTED,
            birth_events: choice::RFISST_BIRTH_FIRST_ORDER,
            measured_births: RfisstMeasuredBirths::OFF,
            death_probability: 0.0,
            has_gate: 0,
            gate: 0.0,
            children: choice::RFISST_CHILDREN_SAMPLED,
            max_children_per_scan: 1_000_000,
            sampler: RfisstSampler {
                burn_in: sampler.burn_in,
                steps: sampler.steps,
                proposal: match sampler.proposal {
                    tracker_core::sampler::Proposal::Paper => choice::RFISST_PROPOSAL_PAPER,
                    tracker_core::sampler::Proposal::MoveOrSwap => choice::RFISST_PROPOSAL_MOVE_OR_SWAP,
                    tracker_core::sampler::Proposal::Informed => choice::RFISST_PROPOSAL_INFORMED,
                },
                clusters: u32::from(sampler.clusters),
                exhaustive_limit: sampler.exhaustive_limit,
                exact_start: u32::from(sampler.exact_start),
            },
            selection: choice::RFISST_SELECTION_TOP_WEIGHT,
            selection_floor_decades: 0,
            store_overflow: choice::RFISST_STORE_OVERFLOW_PRUNE_CHILDREN,
            numerical_failure: choice::RFISST_NUMERICAL_FAILURE_DROP_TRACK,
            lost_after_unseen_scans: 0,
            seed: 1,
        }
    }
}
