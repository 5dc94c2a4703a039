//! From the C configuration ([`crate::config`]) to tracker-core's configurations of the default
//! trackers, and between the C and core Gaussians and tracks. Every `double` is rounded once to the
//! tracker's scalar ([`Real::of_f64`], `value as f32` for `f32`), as host-sim and the QEMU firmware do; every
//! `uint32_t` code is checked (an unknown one is [`Failure`], never undefined behaviour). No allocation.

use crate::config::{
    RfisstConfig, RfisstDetection, RfisstGaussian, RfisstRegion, RfisstSensor, RfisstTrack, choice, region, sensor,
};
use crate::status::{Failure, RfisstStatus};
use nalgebra::{SMatrix, SVector};
use tracker_core::config::Selection;
use tracker_core::model::ProcessNoise;
use tracker_core::sampler::{Proposal, SamplerConfig};
use tracker_core::sensor::{EarthRotation, GroundSite, Platform, SiteSensor};
use tracker_core::{
    BirthDetection, BirthEvents, BirthModel, ChildGeneration, Config, Gaussian, LookShape, MixedSensor,
    NumericalFailure, PositionMeasurement, Real, Region, Sensor, SensorKind, StoreOverflow, Track, TwoBody, TwoBodyJ2,
    ssa_caps,
};

/// Birth cells of every default tracker.
const B: usize = ssa_caps::BIRTH_CELLS;

/// A C Gaussian as the core's `S`-state Gaussian: the first `S` mean entries and the upper-left `S`×`S`
/// block of the row-major 6×6 covariance.
pub fn gaussian<T: Real, const S: usize>(g: &RfisstGaussian) -> Gaussian<T, S> {
    Gaussian {
        mean: SVector::from_fn(|i, _| T::of_f64(g.mean.get(i).copied().unwrap_or(f64::NAN))),
        covariance: SMatrix::from_fn(|i, j| T::of_f64(g.covariance.get(i * 6 + j).copied().unwrap_or(f64::NAN))),
    }
}

/// A core track as a C track (entries beyond `S` are 0).
pub fn track<T: Real, const S: usize>(t: &Track<T, S>) -> RfisstTrack {
    let mut state = RfisstGaussian::ZERO;
    for i in 0..S.min(6) {
        state.mean[i] = t.state.mean[i].as_f64();
        for j in 0..S.min(6) {
            state.covariance[i * 6 + j] = t.state.covariance[(i, j)].as_f64();
        }
    }
    RfisstTrack { label: t.label.0, existence: t.existence.as_f64(), state }
}

/// A C region as the core's.
pub fn region<T: Real>(r: &RfisstRegion) -> Result<Region<T>, Failure> {
    let of = T::of_f64;
    Ok(match r.r#type {
        region::RFISST_REGION_EVERYWHERE => Region::Everywhere { volume: of(r.volume) },
        region::RFISST_REGION_RECTANGLE => Region::Rectangle { min: r.min.map(of), max: r.max.map(of) },
        region::RFISST_REGION_SECTOR => Region::Sector {
            origin: r.origin.map(of),
            look_direction: of(r.look_direction),
            half_angle: of(r.half_angle),
            max_range: of(r.max_range),
        },
        region::RFISST_REGION_LOOK => Region::Look {
            shape: match r.shape {
                region::RFISST_LOOK_CONE => {
                    LookShape::Cone { azimuth: of(r.azimuth), elevation: of(r.elevation), half_angle: of(r.half_angle) }
                }
                region::RFISST_LOOK_BOX => LookShape::Box {
                    azimuth: of(r.azimuth),
                    half_width: of(r.half_width),
                    elevation: r.elevation_window.map(of),
                },
                _ => return Err(Failure::invalid("field_of_view.shape: unknown RFISST_LOOK_* code")),
            },
            min_elevation: of(r.min_elevation),
            range: flag(r.has_range, "field_of_view.has_range")?.then(|| r.range.map(of)),
            range_rate: flag(r.has_range_rate, "field_of_view.has_range_rate")?.then(|| r.range_rate.map(of)),
        },
        _ => return Err(Failure::invalid("field_of_view.type: unknown RFISST_REGION_* code")),
    })
}

/// A 0/1 flag.
fn flag(value: u32, what: &'static str) -> Result<bool, Failure> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(Failure::Plain(RfisstStatus::RfisstInvalidConfig, what)),
    }
}

/// A C detection model as the core's sensor.
pub fn detection<T: Real>(d: &RfisstDetection) -> Result<Sensor<T>, Failure> {
    Ok(Sensor {
        detection_probability: T::of_f64(d.detection_probability),
        clutter_rate: T::of_f64(d.clutter_rate),
        field_of_view: region(&d.field_of_view)?,
    })
}

/// The core's sensor kind of a C code.
pub fn sensor_kind(code: u32) -> Result<SensorKind, Failure> {
    Ok(match code {
        sensor::RFISST_SENSOR_RADAR => SensorKind::Radar,
        sensor::RFISST_SENSOR_RADAR_RANGE_RATE => SensorKind::RadarRangeRate,
        sensor::RFISST_SENSOR_OPTICAL => SensorKind::OpticalRaDec,
        sensor::RFISST_SENSOR_AZ_EL => SensorKind::AzEl,
        sensor::RFISST_SENSOR_RANGE => SensorKind::Range,
        sensor::RFISST_SENSOR_RANGE_RANGE_RATE => SensorKind::RangeRangeRate,
        _ => return Err(Failure::invalid("sensors[].kind: unknown RFISST_SENSOR_* code")),
    })
}

/// A C sensor as the core's site sensor with `D` noise components.
pub fn site_sensor<T: Real, const D: usize>(s: &RfisstSensor) -> Result<SiteSensor<T, D>, Failure> {
    let of = T::of_f64;
    let platform = match s.platform {
        sensor::RFISST_PLATFORM_GROUND => {
            Platform::Ground(GroundSite { latitude: of(s.latitude), longitude: of(s.longitude), height: of(s.height) })
        }
        sensor::RFISST_PLATFORM_SPACECRAFT => Platform::Spacecraft,
        _ => return Err(Failure::invalid("sensors[].platform: unknown RFISST_PLATFORM_* code")),
    };
    Ok(SiteSensor {
        platform,
        sigma: core::array::from_fn(|i| of(s.sigma.get(i).copied().unwrap_or(f64::NAN))),
        detection: detection(&s.detection)?,
    })
}

/// The used sensors of a 3-D configuration, at most `capacity`.
fn used_sensors(c: &RfisstConfig, capacity: usize) -> Result<&[RfisstSensor], Failure> {
    let count = c.sensor_count as usize;
    if count == 0 || count > capacity {
        return Err(Failure::invalid("sensor_count: must be at least 1 and at most the tracker's sensor capacity"));
    }
    c.sensors.get(..count).ok_or(Failure::invalid("sensor_count: above RFISST_MAX_SENSORS"))
}

/// The site sensors of a single-kind network (radar or optical): every sensor must be of `kind`.
pub fn single_kind_sensors<T: Real, const D: usize, const C: usize>(
    c: &RfisstConfig,
    kind: u32,
) -> Result<heapless::Vec<SiteSensor<T, D>, C>, Failure> {
    let mut sensors = heapless::Vec::new();
    for s in used_sensors(c, C)? {
        if s.kind != kind {
            return Err(Failure::invalid(
                "sensors[].kind: the radar tracker takes RFISST_SENSOR_RADAR sensors only, the optical tracker \
                 RFISST_SENSOR_OPTICAL only (the network tracker takes any)",
            ));
        }
        sensors.push(site_sensor(s)?).map_err(|_| Failure::invalid("sensor_count: above the sensor capacity"))?;
    }
    Ok(sensors)
}

/// The mixed sensors of a network tracker.
pub fn mixed_sensors<T: Real, const C: usize>(c: &RfisstConfig) -> Result<heapless::Vec<MixedSensor<T>, C>, Failure> {
    let mut sensors = heapless::Vec::new();
    for s in used_sensors(c, C)? {
        let mixed = MixedSensor { kind: sensor_kind(s.kind)?, sensor: site_sensor(s)? };
        sensors.push(mixed).map_err(|_| Failure::invalid("sensor_count: above the sensor capacity"))?;
    }
    Ok(sensors)
}

/// The Earth rotation of a 3-D configuration.
pub fn rotation<T: Real>(c: &RfisstConfig) -> EarthRotation<T> {
    EarthRotation::new(T::of_f64(c.earth_rotation_angle))
}

/// The planar configuration (`SsaConfig<T>`).
pub fn planar<T: Real>(c: &RfisstConfig) -> Result<Config<T, TwoBody<T>, PositionMeasurement<T>, 4, B>, Failure> {
    let of = T::of_f64;
    let motion = TwoBody {
        mu: of(c.mu),
        acceleration_noise: of(c.acceleration_noise),
        max_step: of(c.max_step),
        max_substeps: c.max_substeps,
        min_radius: of(c.min_radius),
    };
    let noise = SMatrix::<T, 2, 2>::from_fn(|i, j| of(c.position_noise.get(i * 2 + j).copied().unwrap_or(f64::NAN)));
    common(c, motion, PositionMeasurement { noise }, detection(&c.sensor)?)
}

/// The 3-D motion model.
pub fn motion3d<T: Real>(c: &RfisstConfig) -> Result<TwoBodyJ2<T>, Failure> {
    let of = T::of_f64;
    let [a, b, d] = c.process_noise;
    let noise = match c.process_noise_type {
        choice::RFISST_NOISE_ISOTROPIC => ProcessNoise::Isotropic(of(a)),
        choice::RFISST_NOISE_RIC => ProcessNoise::Ric { radial: of(a), in_track: of(b), cross_track: of(d) },
        _ => return Err(Failure::invalid("process_noise_type: unknown RFISST_NOISE_* code")),
    };
    Ok(TwoBodyJ2 {
        mu: of(c.mu),
        j2: of(c.j2),
        radius: of(c.radius),
        min_radius: of(c.min_radius),
        noise,
        max_step: of(c.max_step),
        max_substeps: c.max_substeps,
    })
}

/// A 3-D configuration around the measurement model `measurement`; the configuration's own sensor is the
/// first sensor's detection model (each scan uses its own sensor's), as host-sim does.
pub fn config3d<T: Real, G>(c: &RfisstConfig, measurement: G) -> Result<Config<T, TwoBodyJ2<T>, G, 6, B>, Failure> {
    let first = used_sensors(c, usize::MAX)?.first().ok_or(Failure::invalid("sensor_count: 0"))?;
    common(c, motion3d(c)?, measurement, detection(&first.detection)?)
}

/// What every configuration shares: births, deaths, gate, children, policies, seed.
fn common<T: Real, M, G, const S: usize>(
    c: &RfisstConfig,
    motion: M,
    measurement: G,
    sensor: Sensor<T>,
) -> Result<Config<T, M, G, S, B>, Failure> {
    let count = c.birth_cell_count as usize;
    let used = c.birth_cells.get(..count).ok_or(Failure::invalid("birth_cell_count: above RFISST_MAX_BIRTH_CELLS"))?;
    let mut cells = heapless::Vec::new();
    for cell in used {
        cells.push(gaussian(cell)).map_err(|_| Failure::invalid("birth_cell_count: above RFISST_MAX_BIRTH_CELLS"))?;
    }
    let birth = BirthModel {
        probability: T::of_f64(c.birth_probability),
        cells,
        detection: match c.birth_detection {
            choice::RFISST_BIRTH_ALL_DETECTED => BirthDetection::AllDetected,
            choice::RFISST_BIRTH_ALLOW_UNDETECTED => BirthDetection::AllowUndetected,
            _ => return Err(Failure::invalid("birth_detection: unknown RFISST_BIRTH_* code")),
        },
        events: match c.birth_events {
            choice::RFISST_BIRTH_FIRST_ORDER => BirthEvents::FirstOrder,
            choice::RFISST_BIRTH_INDEPENDENT => BirthEvents::Independent,
            _ => return Err(Failure::invalid("birth_events: unknown RFISST_BIRTH_* code")),
        },
        measured: None,
    };
    Ok(Config {
        motion,
        measurement,
        sensor,
        birth,
        death_probability: T::of_f64(c.death_probability),
        gate: flag(c.has_gate, "has_gate: must be 0 or 1")?.then(|| T::of_f64(c.gate)),
        children: children(c)?,
        selection: match c.selection {
            choice::RFISST_SELECTION_TOP_WEIGHT => Selection::TopWeight,
            choice::RFISST_SELECTION_SAMPLED_BY_WEIGHT => Selection::SampledByWeight,
            _ => return Err(Failure::invalid("selection: unknown RFISST_SELECTION_* code")),
        },
        store_overflow: match c.store_overflow {
            choice::RFISST_STORE_OVERFLOW_PRUNE_CHILDREN => StoreOverflow::PruneChildren,
            choice::RFISST_STORE_OVERFLOW_ERROR => StoreOverflow::Error,
            _ => return Err(Failure::invalid("store_overflow: unknown RFISST_STORE_OVERFLOW_* code")),
        },
        numerical_failure: match c.numerical_failure {
            choice::RFISST_NUMERICAL_FAILURE_DROP_TRACK => NumericalFailure::DropTrack,
            choice::RFISST_NUMERICAL_FAILURE_ERROR => NumericalFailure::Error,
            _ => return Err(Failure::invalid("numerical_failure: unknown RFISST_NUMERICAL_FAILURE_* code")),
        },
        track_loss: track_loss(c.lost_after_unseen_scans)?,
        seed: c.seed,
    })
}

/// The lost-track rule of `lost_after_unseen_scans` (0: never).
fn track_loss(scans: u32) -> Result<tracker_core::TrackLoss, Failure> {
    match u16::try_from(scans).map(core::num::NonZeroU16::new) {
        Ok(None) => Ok(tracker_core::TrackLoss::Never),
        Ok(Some(n)) => Ok(tracker_core::TrackLoss::AfterUnseenScans(n)),
        Err(_) => Err(Failure::invalid("lost_after_unseen_scans: above 65535 (0: never)")),
    }
}

/// The child generation.
fn children(c: &RfisstConfig) -> Result<ChildGeneration, Failure> {
    match c.children {
        choice::RFISST_CHILDREN_EXHAUSTIVE => {
            Ok(ChildGeneration::Exhaustive { max_children_per_scan: c.max_children_per_scan })
        }
        choice::RFISST_CHILDREN_SAMPLED => {
            let s = &c.sampler;
            Ok(ChildGeneration::Sampled(SamplerConfig {
                burn_in: s.burn_in,
                steps: s.steps,
                proposal: match s.proposal {
                    choice::RFISST_PROPOSAL_PAPER => Proposal::Paper,
                    choice::RFISST_PROPOSAL_MOVE_OR_SWAP => Proposal::MoveOrSwap,
                    choice::RFISST_PROPOSAL_INFORMED => Proposal::Informed,
                    _ => return Err(Failure::invalid("sampler.proposal: unknown RFISST_PROPOSAL_* code")),
                },
                clusters: flag(s.clusters, "sampler.clusters: must be 0 or 1")?,
                exhaustive_limit: s.exhaustive_limit,
                exact_start: flag(s.exact_start, "sampler.exact_start: must be 0 or 1")?,
            }))
        }
        _ => Err(Failure::invalid("children: unknown RFISST_CHILDREN_* code")),
    }
}
