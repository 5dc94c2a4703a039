/* rfisst.h: the C interface of tracker-core (R-FISST). Generated from bindings/c by cbindgen
 * (tests/header.rs); do not edit. Guide: docs/c-api.md. */

#ifndef RFISST_H
#define RFISST_H

#include <stddef.h>
#include <stdint.h>

// Sensors a 3-D configuration holds (the network tracker's capacity; the radar and optical trackers take
// at most [`RFISST_MAX_SENSORS_SINGLE_KIND`]).
#define RFISST_MAX_SENSORS 8

// Sensors of the radar and optical trackers.
#define RFISST_MAX_SENSORS_SINGLE_KIND 4

// Birth cells a configuration holds.
#define RFISST_MAX_BIRTH_CELLS 8

// Objects one prior hypothesis holds (as `RFISST_MAX_OBJECTS`). Kept for compatibility: the prior
// is no longer limited over all its hypotheses together, since its objects are converted one at a time
// as the tracker reads them (no buffer), with or without `std`.
#define RFISST_MAX_PRIOR_OBJECTS 64

// Measurements one scan may hold (the trackers' Z).
#define RFISST_MAX_MEASUREMENTS 32

// Hypotheses a tracker keeps (H∞).
#define RFISST_MAX_HYPOTHESES 32

// Objects one hypothesis holds (N).
#define RFISST_MAX_OBJECTS 64

// Components of a measurement of the network tracker (each kind's components first, then zeros).
#define RFISST_NETWORK_DIMENSION 4

// No boundary.
#define RFISST_REGION_EVERYWHERE 0

// Axis-aligned rectangle (planar).
#define RFISST_REGION_RECTANGLE 1

// Circular sector (planar).
#define RFISST_REGION_SECTOR 2

// Look angles of a 3-D sensor.
#define RFISST_REGION_LOOK 3

// A cone of look directions.
#define RFISST_LOOK_CONE 0

// An azimuth/elevation box.
#define RFISST_LOOK_BOX 1

// Range, azimuth, elevation (km, rad, rad).
#define RFISST_SENSOR_RADAR 0

// Range, azimuth, elevation, range-rate.
#define RFISST_SENSOR_RADAR_RANGE_RATE 1

// Topocentric right ascension and declination (rad).
#define RFISST_SENSOR_OPTICAL 2

// Azimuth and elevation.
#define RFISST_SENSOR_AZ_EL 3

// Range.
#define RFISST_SENSOR_RANGE 4

// Range and range-rate.
#define RFISST_SENSOR_RANGE_RANGE_RATE 5

// A sensor's births come from the configuration's `measured_births.region`.
#define RFISST_BIRTHS_FROM_MODEL 0

// A sensor's births come from its own `birth_region`.
#define RFISST_BIRTHS_REGION 1

// A sensor's measurements start no track.
#define RFISST_BIRTHS_OFF 2

// A ground site.
#define RFISST_PLATFORM_GROUND 0

// A spacecraft: each scan gives the observer's inertial state.
#define RFISST_PLATFORM_SPACECRAFT 1

// Same density along every axis.
#define RFISST_NOISE_ISOTROPIC 0

// Radial, in-track, cross-track densities.
#define RFISST_NOISE_RIC 1

// Births are detected when born.
#define RFISST_BIRTH_ALL_DETECTED 0

// Births may go undetected.
#define RFISST_BIRTH_ALLOW_UNDETECTED 1

// R-FISST's first-order birth/death events.
#define RFISST_BIRTH_FIRST_ORDER 0

// Independent births per cell.
#define RFISST_BIRTH_INDEPENDENT 1

// R-FISST's sampled children.
#define RFISST_CHILDREN_SAMPLED 0

// Every child (HOMHT).
#define RFISST_CHILDREN_EXHAUSTIVE 1

// Paper 003's proposal.
#define RFISST_PROPOSAL_PAPER 0

// Move or swap.
#define RFISST_PROPOSAL_MOVE_OR_SWAP 1

// Informed (the default).
#define RFISST_PROPOSAL_INFORMED 2

// Keep the heaviest hypotheses.
#define RFISST_SELECTION_TOP_WEIGHT 0

// Sample hypotheses by weight.
#define RFISST_SELECTION_SAMPLED_BY_WEIGHT 1

// Keep the heaviest hypotheses within `selection_floor_decades` decades of the heaviest.
#define RFISST_SELECTION_TOP_WEIGHT_WITHIN 2

// Drop children that do not fit the track store.
#define RFISST_STORE_OVERFLOW_PRUNE_CHILDREN 0

// Fail the scan when the store overflows.
#define RFISST_STORE_OVERFLOW_ERROR 1

// Drop a track whose EKF fails.
#define RFISST_NUMERICAL_FAILURE_DROP_TRACK 0

// Fail the scan.
#define RFISST_NUMERICAL_FAILURE_ERROR 1

// The outcome of a call. Every value but `RFISST_OK` leaves the tracker as it was.
enum RfisstStatus
#if defined(__cplusplus) || __STDC_VERSION__ >= 202311L
  : uint32_t
#endif // defined(__cplusplus) || __STDC_VERSION__ >= 202311L
 {
  // Success.
  RFISST_OK = 0,
  // A pointer argument was null.
  RFISST_NULL_POINTER = 1,
  // A size or count argument is wrong: storage smaller than `rfisst_tracker_size`, a measurement
  // dimension that is not the tracker's, a count whose product overflows.
  RFISST_BAD_SIZE = 2,
  // The storage is not aligned to `rfisst_tracker_align`.
  RFISST_MISALIGNED = 3,
  // The kind is not one of `RfisstKind`.
  RFISST_UNKNOWN_KIND = 4,
  // The handle was not initialised (or its initialisation failed).
  RFISST_INVALID_HANDLE = 5,
  // A field of the C configuration or prior is out of range (an unknown code, a count above its
  // capacity, a sensor kind the tracker does not take).
  RFISST_INVALID_CONFIG = 6,
  // tracker-core rejected the configuration or the prior (its `ConfigError`).
  RFISST_CONFIG_REJECTED = 7,
  // tracker-core rejected the scan (its `StepError`); the tracker is unchanged.
  RFISST_STEP_REJECTED = 8,
  // The scenario JSON does not parse, or does not fit the kind asked for.
  RFISST_SCENARIO = 9,
  // Not available in this build (the JSON path needs the `std` feature).
  RFISST_UNSUPPORTED = 10,
  // An output array is smaller than what there is to write; `written` says how many are needed.
  RFISST_BUFFER_TOO_SMALL = 11,
  // An index (hypothesis) is past the end.
  RFISST_OUT_OF_RANGE = 12,
};
#ifndef __cplusplus
#if __STDC_VERSION__ >= 202311L
typedef enum RfisstStatus RfisstStatus;
#else
typedef uint32_t RfisstStatus;
#endif // __STDC_VERSION__ >= 202311L
#endif // __cplusplus

// The default trackers, by code (`RfisstKind` in C).
enum RfisstKind
#if defined(__cplusplus) || __STDC_VERSION__ >= 202311L
  : uint32_t
#endif // defined(__cplusplus) || __STDC_VERSION__ >= 202311L
 {
  // `SsaTracker<f32>`: planar two-body, position measurements.
  RFISST_SSA_F32 = 0,
  // `SsaTracker<f64>`.
  RFISST_SSA_F64 = 1,
  // `RadarTracker<f32>`: two-body + J2, up to 4 radars (range, azimuth, elevation).
  RFISST_RADAR_F32 = 2,
  // `RadarTracker<f64>`.
  RFISST_RADAR_F64 = 3,
  // `OpticalTracker<f32>`: two-body + J2, up to 4 telescopes (right ascension, declination).
  RFISST_OPTICAL_F32 = 4,
  // `OpticalTracker<f64>`.
  RFISST_OPTICAL_F64 = 5,
  // `NetworkTracker<f32>`: two-body + J2, up to 8 sensors of mixed kinds (measurements padded to 4).
  RFISST_NETWORK_F32 = 6,
  // `NetworkTracker<f64>`.
  RFISST_NETWORK_F64 = 7,
};
#ifndef __cplusplus
#if __STDC_VERSION__ >= 202311L
typedef enum RfisstKind RfisstKind;
#else
typedef uint32_t RfisstKind;
#endif // __STDC_VERSION__ >= 202311L
#endif // __cplusplus

// An initialised tracker: the storage given to `rfisst_tracker_init`, seen as a handle.
typedef struct RfisstTracker RfisstTracker;

// A field of view. `type` selects the variant and the fields it reads (`RFISST_REGION_*`); angles in
// radians.
typedef struct RfisstRegion {
  // `RFISST_REGION_EVERYWHERE` (reads `volume`), `_RECTANGLE` (`min`, `max`), `_SECTOR` (`origin`,
  // `look_direction`, `half_angle`, `max_range`) or `_LOOK` (`shape` and its fields, `min_elevation`,
  // the range and range-rate windows).
  uint32_t type;
  // Clutter volume of `EVERYWHERE`.
  double volume;
  // Lower corner of `RECTANGLE`.
  double min[2];
  // Upper corner of `RECTANGLE`.
  double max[2];
  // Sensor position of `SECTOR`.
  double origin[2];
  // Boresight of `SECTOR` (from +x, counter-clockwise).
  double look_direction;
  // Half opening angle of `SECTOR`, or of a `LOOK` cone.
  double half_angle;
  // Largest range of `SECTOR`.
  double max_range;
  // `RFISST_LOOK_CONE` (`azimuth`, `elevation`, `half_angle`) or `RFISST_LOOK_BOX` (`azimuth`,
  // `half_width`, `elevation_window`).
  uint32_t shape;
  // Boresight (cone) or centre (box) azimuth, from North towards East.
  double azimuth;
  // Boresight elevation of a cone.
  double elevation;
  // Half azimuth extent of a box.
  double half_width;
  // `[min, max]` elevation of a box.
  double elevation_window[2];
  // Elevation mask of `LOOK`.
  double min_elevation;
  // Whether `range` is given (required exactly when the sensor measures range).
  uint32_t has_range;
  // `[min, max]` range (km).
  double range[2];
  // Whether `range_rate` is given (required exactly when the sensor measures range-rate).
  uint32_t has_range_rate;
  // `[min, max]` range-rate (km/s).
  double range_rate[2];
} RfisstRegion;

// How a sensor detects: p_D inside its field of view, Poisson clutter of mean `clutter_rate` per scan.
typedef struct RfisstDetection {
  // p_D.
  double detection_probability;
  // λ_C.
  double clutter_rate;
  // Where it sees.
  struct RfisstRegion field_of_view;
} RfisstDetection;

// The admissible region a measurement's birth density is cut from (tracker-core's `AdmissibleRegion`,
// docs/maths.md §5.7): bound orbits between two radii, up to an inclination, or a shell of radii.
typedef struct RfisstAdmissibleRegion {
  // Gravitational parameter μ (km³/s²).
  double mu;
  // Smallest perigee radius (km).
  double min_perigee_radius;
  // Largest apogee radius (km).
  double max_apogee_radius;
  // Largest inclination (rad).
  double max_inclination;
  // `[min, max]` radius of the shell the missing range is drawn from (km).
  double shell[2];
  // Headings of the missing velocity direction.
  uint32_t headings;
  // Speeds.
  uint32_t speeds;
  // Climb angles.
  uint32_t climbs;
  // Ranges of an angles-only measurement.
  uint32_t ranges;
  // Standard deviation of each component's velocity (km/s).
  double velocity_sigma;
} RfisstAdmissibleRegion;

// One sensor of a 3-D tracker.
typedef struct RfisstSensor {
  // What it measures (`RFISST_SENSOR_*`): the radar tracker takes `RADAR` only, the optical tracker
  // `OPTICAL` only, the network tracker any.
  uint32_t kind;
  // `RFISST_PLATFORM_GROUND` (reads `latitude`, `longitude`, `height`) or `RFISST_PLATFORM_SPACECRAFT`
  // (the scan gives the observer).
  uint32_t platform;
  // Geodetic latitude (rad).
  double latitude;
  // Longitude (rad, East).
  double longitude;
  // Height above the WGS-84 ellipsoid (km).
  double height;
  // Noise standard deviations of the kind's components in order, then zeros.
  double sigma[4];
  // How it detects.
  struct RfisstDetection detection;
  // Network tracker only: where the births of its measurements come from (`RFISST_BIRTHS_*`):
  // `FROM_MODEL` (0, the configuration's `measured_births.region`), `REGION` (its own
  // `birth_region`) or `OFF` (its measurements start no track). The radar and optical trackers take
  // `FROM_MODEL` only.
  uint32_t births;
  // The sensor's own admissible region, read when `births` is `RFISST_BIRTHS_REGION`.
  struct RfisstAdmissibleRegion birth_region;
} RfisstSensor;

// A Gaussian. The 3-D trackers use all of it; the planar tracker its first 4 mean entries and the
// upper-left 4×4 block of the covariance (the rest is ignored on input and 0 on output).
typedef struct RfisstGaussian {
  // Mean: planar (x, y, vx, vy), 3-D (x, y, z, vx, vy, vz) in km and km/s.
  double mean[6];
  // Covariance, row-major 6×6.
  double covariance[36];
} RfisstGaussian;

// Births from the measurements (tracker-core's `MeasuredBirths`, docs/maths.md §5.8): the measurements
// no track explains become birth cells of a pool. Births from tracklets are not in the C configuration.
typedef struct RfisstMeasuredBirths {
  // 1: on; 0: off (the other fields are not read).
  uint32_t enabled;
  // The admissible region of the sensors whose births come from the model.
  struct RfisstAdmissibleRegion region;
  // Expected births per scan λ_B.
  double expected_births;
  // The largest α of one measurement's cells together, in (0, 1).
  double max_probability;
  // The smallest r_U for a measurement to make cells, in [0, 1].
  double min_unexplained;
  // Seconds a cell lives after its measurement.
  double lifetime;
  // 1: the cells the full pool does not keep wait for a later measurement to link with; 0: dropped.
  uint32_t link_waiting;
} RfisstMeasuredBirths;
// Off.
#define RfisstMeasuredBirths_OFF (RfisstMeasuredBirths){ .enabled = 0, .region = RfisstAdmissibleRegion_ZERO, .expected_births = 0.0, .max_probability = 0.0, .min_unexplained = 0.0, .lifetime = 0.0, .link_waiting = 0 }

// R-FISST's Metropolis sampler (tracker-core's `SamplerConfig`).
typedef struct RfisstSampler {
  // Burn-in steps per chain.
  uint32_t burn_in;
  // Steps per chain after burn-in.
  uint32_t steps;
  // `RFISST_PROPOSAL_PAPER`, `_MOVE_OR_SWAP` or `_INFORMED`.
  uint32_t proposal;
  // 1: sample each cluster apart; 0: one chain over the whole matrix.
  uint32_t clusters;
  // Clusters with at most this many leaves are enumerated exactly.
  uint64_t exhaustive_limit;
  // 1: start each chain from the best association.
  uint32_t exact_start;
} RfisstSampler;

// A tracker configuration. `rfisst_config_default` fills one for a kind; change what differs.
typedef struct RfisstConfig {
  // Gravitational parameter μ (km³/s²).
  double mu;
  // Planar: white acceleration noise density.
  double acceleration_noise;
  // 3-D: J2 (0: two-body).
  double j2;
  // 3-D: J2's reference radius (km).
  double radius;
  // Smallest distance from the centre a state may have (km).
  double min_radius;
  // 3-D: `RFISST_NOISE_ISOTROPIC` (reads `process_noise[0]`) or `RFISST_NOISE_RIC` (radial, in-track,
  // cross-track).
  uint32_t process_noise_type;
  // 3-D: process noise densities (km²/s³).
  double process_noise[3];
  // Largest RK4 sub-step (s).
  double max_step;
  // Most sub-steps one propagation takes.
  uint32_t max_substeps;
  // Planar: the position measurement's noise covariance R, row-major 2×2.
  double position_noise[4];
  // Planar: the sensor (3-D trackers use each sensor's own).
  struct RfisstDetection sensor;
  // 3-D: Earth rotation angle at time 0 (rad; `rfisst_gmst_iau82(jd)` of the epoch).
  double earth_rotation_angle;
  // 3-D: the sensors, `sensor_count` of them.
  struct RfisstSensor sensors[RFISST_MAX_SENSORS];
  // 3-D: how many of `sensors` are used (at least 1).
  uint32_t sensor_count;
  // α: probability of a birth in each cell.
  double birth_probability;
  // The birth cells, `birth_cell_count` of them.
  struct RfisstGaussian birth_cells[RFISST_MAX_BIRTH_CELLS];
  // How many of `birth_cells` are used.
  uint32_t birth_cell_count;
  // `RFISST_BIRTH_ALL_DETECTED` or `RFISST_BIRTH_ALLOW_UNDETECTED`.
  uint32_t birth_detection;
  // `RFISST_BIRTH_FIRST_ORDER` or `RFISST_BIRTH_INDEPENDENT`.
  uint32_t birth_events;
  // Births from the measurements (off by default).
  struct RfisstMeasuredBirths measured_births;
  // β: probability that an object in the field of view dies before a scan.
  double death_probability;
  // 1: gate at `gate` (Mahalanobis distance); 0: no gate.
  uint32_t has_gate;
  // The gate.
  double gate;
  // `RFISST_CHILDREN_SAMPLED` (R-FISST, reads `sampler`) or `RFISST_CHILDREN_EXHAUSTIVE` (reads
  // `max_children_per_scan`).
  uint32_t children;
  // Budget of exhaustive children per scan.
  uint64_t max_children_per_scan;
  // The sampler of sampled children.
  struct RfisstSampler sampler;
  // `RFISST_SELECTION_TOP_WEIGHT`, `RFISST_SELECTION_SAMPLED_BY_WEIGHT` or
  // `RFISST_SELECTION_TOP_WEIGHT_WITHIN` (reads `selection_floor_decades`).
  uint32_t selection;
  // With `RFISST_SELECTION_TOP_WEIGHT_WITHIN`: the children lighter than 10^-decades times the heaviest
  // are dropped (0..=255; docs/maths.md §8.1). Not read otherwise.
  uint32_t selection_floor_decades;
  // `RFISST_STORE_OVERFLOW_PRUNE_CHILDREN` or `RFISST_STORE_OVERFLOW_ERROR`.
  uint32_t store_overflow;
  // `RFISST_NUMERICAL_FAILURE_DROP_TRACK` or `RFISST_NUMERICAL_FAILURE_ERROR`.
  uint32_t numerical_failure;
  // The lost-track rule: 0, tracks are never declared lost (the exact recursion, the default); n in
  // 1..=65535, a track unseen in n consecutive scans is dropped (`TrackLoss::AfterUnseenScans`; needs a
  // gate, docs/maths.md).
  uint32_t lost_after_unseen_scans;
  // The tracker's random seed.
  uint64_t seed;
} RfisstConfig;

// One object of a prior hypothesis.
typedef struct RfisstPriorObject {
  // Its label (distinct within a hypothesis).
  uint32_t label;
  // Its state.
  struct RfisstGaussian state;
} RfisstPriorObject;

// One prior hypothesis: a weight (the weights need not add up to 1) and its objects.
typedef struct RfisstPriorHypothesis {
  // Its weight (finite, ≥ 0).
  double weight;
  // Its objects (may be null when `object_count` is 0).
  const struct RfisstPriorObject *objects;
  // How many.
  size_t object_count;
} RfisstPriorHypothesis;

// What one scan did (tracker-core's `StepReport`).
typedef struct RfisstStepReport {
  // Scans processed so far, this one included.
  uint64_t scan;
  // Measurements in the scan.
  size_t measurements;
  // Hypotheses kept.
  size_t hypotheses;
  // Tracks in the store.
  size_t tracks;
  // Children with non-zero weight generated.
  uint64_t children;
  // Fraction of the children's weight kept.
  double captured_mass;
  // Metropolis moves made.
  uint64_t sampler_steps;
  // Tracks dropped for a numerical failure.
  size_t numerical_drops;
  // Expected number of objects after the scan.
  double expected_cardinality;
} RfisstStepReport;

// One track of a hypothesis.
typedef struct RfisstTrack {
  // The object's label.
  uint32_t label;
  // Existence probability of this track (its weight summed over the hypotheses holding it).
  double existence;
  // Its state (planar: the first 4 entries and the upper-left 4×4 block, the rest 0).
  struct RfisstGaussian state;
} RfisstTrack;

// Every kind, in code order.
#define RfisstKind_ALL { RfisstKind_RfisstSsaF32, RfisstKind_RfisstSsaF64, RfisstKind_RfisstRadarF32, RfisstKind_RfisstRadarF64, RfisstKind_RfisstOpticalF32, RfisstKind_RfisstOpticalF64, RfisstKind_RfisstNetworkF32, RfisstKind_RfisstNetworkF64, }

// Every status, in code order.
#define STATUSES { RfisstStatus_RfisstOk, RfisstStatus_RfisstNullPointer, RfisstStatus_RfisstBadSize, RfisstStatus_RfisstMisaligned, RfisstStatus_RfisstUnknownKind, RfisstStatus_RfisstInvalidHandle, RfisstStatus_RfisstInvalidConfig, RfisstStatus_RfisstConfigRejected, RfisstStatus_RfisstStepRejected, RfisstStatus_RfisstScenario, RfisstStatus_RfisstUnsupported, RfisstStatus_RfisstBufferTooSmall, RfisstStatus_RfisstOutOfRange, }

#ifdef __cplusplus
extern "C" {
#endif // __cplusplus

// Bytes of storage a tracker of `kind` needs (0 for an unknown kind).
size_t rfisst_tracker_size(uint32_t kind);

// Alignment (bytes) the storage of a tracker of `kind` needs (0 for an unknown kind).
size_t rfisst_tracker_align(uint32_t kind);

// The static, NUL-terminated message of a status code (the unknown code's message for any other value).
const char *rfisst_status_message(uint32_t status);

// Fills `config` with the defaults of `kind` (`RfisstConfig::default_for`): the Earth's constants and
// tracker-core's sampler defaults, no sensor, no birth cell.
//
// # Safety
// `config` is null or points to writable memory for one `RfisstConfig`.
RfisstStatus rfisst_config_default(uint32_t kind,
                                   struct RfisstConfig *config);

// Greenwich mean sidereal time (IAU 1982) at the UT1 Julian date `jd_ut1`, in radians: the
// `earth_rotation_angle` of a configuration whose time 0 is that date.
double rfisst_gmst_iau82(double jd_ut1);

// Initialises a tracker of `kind` in `storage` (`size` bytes, at least `rfisst_tracker_size(kind)`,
// aligned to `rfisst_tracker_align(kind)`) from `config` and a prior of `prior_count` hypotheses at
// `prior_time` (s). On success `*tracker` is the handle (the address of `storage`). On failure `*tracker`
// is null; when the status is not `NULL_POINTER`, `BAD_SIZE`, `MISALIGNED` or `UNKNOWN_KIND`,
// `rfisst_tracker_last_error((RfisstTracker *)storage)` says why. Nothing is allocated; the storage
// is the caller's until it stops using the handle (there is nothing to free).
//
// # Safety
// `storage` is null or writable for `size` bytes; `config` null or readable; `prior` null or readable for
// `prior_count` hypotheses whose `objects` are readable for `object_count` objects; `tracker` null or
// writable. No other thread uses `storage` during the call.
RfisstStatus rfisst_tracker_init(void *storage,
                                 size_t size,
                                 uint32_t kind,
                                 const struct RfisstConfig *config,
                                 const struct RfisstPriorHypothesis *prior,
                                 size_t prior_count,
                                 double prior_time,
                                 struct RfisstTracker **tracker);

// The last error's text of a handle (or of storage whose initialisation failed), NUL-terminated and
// valid until the next call on the handle; "" when there is none, a static text when `tracker` is null.
//
// # Safety
// `tracker` is null, a handle, or storage given to `rfisst_tracker_init` that passed its size and
// alignment checks.
const char *rfisst_tracker_last_error(const struct RfisstTracker *tracker);

// The kind code of a handle, or `UINT32_MAX` when it is not a ready tracker.
//
// # Safety
// As `rfisst_tracker_step`.
uint32_t rfisst_tracker_kind(struct RfisstTracker *tracker);

// Components of one measurement of the tracker (planar 2, radar 3, optical 2, network 4), or 0 when the
// handle is not a ready tracker.
//
// # Safety
// As `rfisst_tracker_step`.
size_t rfisst_tracker_dimension(struct RfisstTracker *tracker);

// Restarts the tracker from a prior of `prior_count` hypotheses at `prior_time` (s); on failure the
// tracker is unchanged.
//
// # Safety
// `tracker` as in `rfisst_tracker_step`; `prior` as in `rfisst_tracker_init`.
RfisstStatus rfisst_tracker_reset(struct RfisstTracker *tracker,
                                  const struct RfisstPriorHypothesis *prior,
                                  size_t prior_count,
                                  double prior_time);

// Processes one scan of sensor `sensor` (0 for the planar tracker) at `time` (s, after the previous
// scan): `count` measurements of `dimension` doubles each, row after row, in the tracker's units (km,
// rad, km/s; network: the kind's components, then zeros up to 4). `observer` is null, or the observer's
// inertial position and velocity (6 doubles) for a spacecraft sensor. `report` may be null. Allocates
// nothing. On failure (`STEP_REJECTED` for the core's errors) the tracker is unchanged.
//
// # Safety
// `tracker` is null or a handle not used by another thread during the call; `measurements` is null or
// readable for `count * dimension` doubles; `observer` null or readable for 6; `report` null or writable.
RfisstStatus rfisst_tracker_step(struct RfisstTracker *tracker,
                                 double time,
                                 size_t sensor,
                                 const double *observer,
                                 const double *measurements,
                                 size_t count,
                                 size_t dimension,
                                 struct RfisstStepReport *report);

// Writes the number of hypotheses held to `*count`.
//
// # Safety
// As `rfisst_tracker_step`; `count` null or writable.
RfisstStatus rfisst_tracker_hypothesis_count(struct RfisstTracker *tracker, size_t *count);

// Writes the weights (normalised) and cardinalities of the hypotheses, heaviest (the MAP) first, into
// `weights` and `cardinalities` (either may be null), `capacity` entries each; `*written` is the number
// of hypotheses (written, or needed with `BUFFER_TOO_SMALL`).
//
// # Safety
// As `rfisst_tracker_step`; `weights` and `cardinalities` null or writable for `capacity` entries,
// `written` writable.
RfisstStatus rfisst_tracker_hypotheses(struct RfisstTracker *tracker,
                                       double *weights,
                                       size_t *cardinalities,
                                       size_t capacity,
                                       size_t *written);

// Writes the tracks of hypothesis `hypothesis` (0: the MAP) into `tracks` (`capacity` entries);
// `*written` is its number of tracks (written, or needed with `BUFFER_TOO_SMALL`).
//
// # Safety
// As `rfisst_tracker_step`; `tracks` null or writable for `capacity` tracks, `written` writable.
RfisstStatus rfisst_tracker_tracks(struct RfisstTracker *tracker,
                                   size_t hypothesis,
                                   struct RfisstTrack *tracks,
                                   size_t capacity,
                                   size_t *written);

// The MAP hypothesis's tracks: `rfisst_tracker_tracks` of hypothesis 0.
//
// # Safety
// As `rfisst_tracker_tracks`.
RfisstStatus rfisst_tracker_map_tracks(struct RfisstTracker *tracker,
                                       struct RfisstTrack *tracks,
                                       size_t capacity,
                                       size_t *written);

// Writes the expected number of objects Σ_h w_h N_h to `*cardinality`.
//
// # Safety
// As `rfisst_tracker_step`; `cardinality` null or writable.
RfisstStatus rfisst_tracker_expected_cardinality(struct RfisstTracker *tracker,
                                                 double *cardinality);

// Writes tracker-core's 64-bit digest of the tracker's state to `*digest` (the value the QEMU firmware
// and `host-sim digest` print per scan).
//
// # Safety
// As `rfisst_tracker_step`; `digest` null or writable.
RfisstStatus rfisst_tracker_digest(struct RfisstTracker *tracker,
                                   uint64_t *digest);

// Writes the time of the last scan (or of the prior) to `*time` and the scans processed since the prior
// to `*scans` (either may be null).
//
// # Safety
// As `rfisst_tracker_step`; `time` and `scans` null or writable.
RfisstStatus rfisst_tracker_clock(struct RfisstTracker *tracker,
                                  double *time,
                                  uint64_t *scans);

// Without the `std` feature there is no JSON path: `rfisst_tracker_init_json` returns `UNSUPPORTED`.
//
// # Safety
// `tracker` null or writable.
RfisstStatus rfisst_tracker_init_json(void *_storage,
                                      size_t _size,
                                      uint32_t _kind,
                                      const char *_json,
                                      struct RfisstTracker **tracker);

// Initialises a tracker of `kind` in `storage` from a scenario-format JSON text (NUL-terminated UTF-8):
// its configuration and whole prior, as host-sim builds them (angles in the file in degrees, converted
// to radians). As `rfisst_tracker_init` otherwise; `SCENARIO` when the text does not parse or does not
// fit `kind`. Host builds only (the `std` feature); allocates while it parses, never in a step.
//
// # Safety
// As `rfisst_tracker_init`; `json` null or a NUL-terminated string.
RfisstStatus rfisst_tracker_init_json(void *storage,
                                      size_t size,
                                      uint32_t kind,
                                      const char *json,
                                      struct RfisstTracker **tracker);

#ifdef __cplusplus
}  // extern "C"
#endif  // __cplusplus

#endif  /* RFISST_H */
