//! From the C configuration ([`crate::config`]) to tracker-core's configurations of the default
//! trackers, and between the C and core Gaussians and tracks. Every `double` is rounded once to the
//! tracker's scalar ([`Real::of_f64`], `value as f32` for `f32`), as host-sim and the QEMU firmware do; every
//! `uint32_t` code is checked (an unknown one is [`Failure`], never undefined behaviour). No allocation.

use crate::config::{
    RfisstAdmissibleRegion, RfisstConfig, RfisstDetection, RfisstGaussian, RfisstMeasuredBirths, RfisstRegion,
    RfisstSensor, RfisstTrack, choice, region, sensor,
};
use crate::status::{Failure, RfisstStatus};
use nalgebra::{SMatrix, SVector};
use tracker_core::config::Selection;
use tracker_core::model::{AdmissibleRegion, ProcessNoise, SensorBirths};
use tracker_core::pool::MeasuredBirths;
use tracker_core::sampler::{Proposal, SamplerConfig};
use tracker_core::sensor::{EarthRotation, GroundSite, Platform, SiteSensor};
use tracker_core::{
    BirthDetection, BirthEvents, ChildGeneration, Config, Gaussian, LookShape, MixedSensor, NumericalFailure,
    PositionMeasurement, Real, Region, Sensor, SensorKind, StoreOverflow, Track, TwoBody, TwoBodyJ2, ssa_caps,
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

/// A C admissible region as the core's (checked when the tracker is configured).
pub fn admissible<T: Real>(r: &RfisstAdmissibleRegion) -> AdmissibleRegion<T> {
    let of = T::of_f64;
    AdmissibleRegion {
        mu: of(r.mu),
        min_perigee_radius: of(r.min_perigee_radius),
        max_apogee_radius: of(r.max_apogee_radius),
        max_inclination: of(r.max_inclination),
        shell: r.shell.map(of),
        headings: r.headings as usize,
        speeds: r.speeds as usize,
        climbs: r.climbs as usize,
        ranges: r.ranges as usize,
        velocity_sigma: of(r.velocity_sigma),
    }
}

/// The measured births of a configuration (`None` when off).
fn measured<T: Real>(m: &RfisstMeasuredBirths) -> Result<Option<MeasuredBirths<T>>, Failure> {
    if !flag(m.enabled, "measured_births.enabled: must be 0 or 1")? {
        return Ok(None);
    }
    Ok(Some(MeasuredBirths {
        region: admissible(&m.region),
        expected_births: T::of_f64(m.expected_births),
        max_probability: T::of_f64(m.max_probability),
        min_unexplained: T::of_f64(m.min_unexplained),
        lifetime: m.lifetime,
        tracklets: None,
        link_waiting: flag(m.link_waiting, "measured_births.link_waiting: must be 0 or 1")?,
    }))
}

/// Where a sensor's births come from.
pub fn sensor_births<T: Real>(s: &RfisstSensor) -> Result<SensorBirths<T>, Failure> {
    match s.births {
        sensor::RFISST_BIRTHS_FROM_MODEL => Ok(SensorBirths::FromModel),
        sensor::RFISST_BIRTHS_REGION => Ok(SensorBirths::Region(admissible(&s.birth_region))),
        sensor::RFISST_BIRTHS_OFF => Ok(SensorBirths::Off),
        _ => Err(Failure::invalid("sensors[].births: unknown RFISST_BIRTHS_* code")),
    }
}

/// The site sensors of a single-kind network (radar or optical): every sensor must be of `kind`.
pub fn single_kind_sensors<T: Real, const D: usize, const C: usize>(
    c: &RfisstConfig,
    kind: u32,
) -> Result<heapless::Vec<SiteSensor<T, D>, C>, Failure> {
    let mut sensors = heapless::Vec::new();
    for s in used_sensors(c, C)? {
        if s.births != sensor::RFISST_BIRTHS_FROM_MODEL {
            return Err(Failure::invalid(
                "sensors[].births: the radar and optical trackers take RFISST_BIRTHS_FROM_MODEL only (the network \
                 tracker takes any)",
            ));
        }
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

/// The planar configuration (`SsaConfig<T>`), by value ([`planar_into`] fills one in place).
pub fn planar<T: Real>(c: &RfisstConfig) -> Result<Config<T, TwoBody<T>, PositionMeasurement<T>, 4, B>, Failure> {
    let mut config = crate::placeholder::planar();
    planar_into(c, &mut config)?;
    Ok(config)
}

/// Fills the planar configuration `out` from `c` in place (no configuration passes through the stack).
pub fn planar_into<T: Real>(
    c: &RfisstConfig,
    out: &mut Config<T, TwoBody<T>, PositionMeasurement<T>, 4, B>,
) -> Result<(), Failure> {
    let of = T::of_f64;
    out.motion = TwoBody {
        mu: of(c.mu),
        acceleration_noise: of(c.acceleration_noise),
        max_step: of(c.max_step),
        max_substeps: c.max_substeps,
        min_radius: of(c.min_radius),
    };
    let noise = SMatrix::<T, 2, 2>::from_fn(|i, j| of(c.position_noise.get(i * 2 + j).copied().unwrap_or(f64::NAN)));
    out.measurement = PositionMeasurement { noise };
    out.sensor = detection(&c.sensor)?;
    common_into(c, out)
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

/// Fills a 3-D configuration `out` from `c` in place, all but its measurement model (the caller's: a
/// sensor network); the configuration's own sensor is the first sensor's detection model (each scan uses
/// its own sensor's), as host-sim does.
pub fn config3d_into<T: Real, G>(c: &RfisstConfig, out: &mut Config<T, TwoBodyJ2<T>, G, 6, B>) -> Result<(), Failure> {
    let first = used_sensors(c, usize::MAX)?.first().ok_or(Failure::invalid("sensor_count: 0"))?;
    out.motion = motion3d(c)?;
    out.sensor = detection(&first.detection)?;
    common_into(c, out)
}

/// Fills what every configuration shares: births, deaths, gate, children, policies, seed. The birth cells
/// are written into `out`'s own list, so that no list of them is built on the stack.
fn common_into<T: Real, M, G, const S: usize>(
    c: &RfisstConfig,
    out: &mut Config<T, M, G, S, B>,
) -> Result<(), Failure> {
    let count = c.birth_cell_count as usize;
    let used = c.birth_cells.get(..count).ok_or(Failure::invalid("birth_cell_count: above RFISST_MAX_BIRTH_CELLS"))?;
    out.birth.cells.clear();
    for cell in used {
        out.birth
            .cells
            .push(gaussian(cell))
            .map_err(|_| Failure::invalid("birth_cell_count: above RFISST_MAX_BIRTH_CELLS"))?;
    }
    out.birth.probability = T::of_f64(c.birth_probability);
    out.birth.detection = match c.birth_detection {
        choice::RFISST_BIRTH_ALL_DETECTED => BirthDetection::AllDetected,
        choice::RFISST_BIRTH_ALLOW_UNDETECTED => BirthDetection::AllowUndetected,
        _ => return Err(Failure::invalid("birth_detection: unknown RFISST_BIRTH_* code")),
    };
    out.birth.events = match c.birth_events {
        choice::RFISST_BIRTH_FIRST_ORDER => BirthEvents::FirstOrder,
        choice::RFISST_BIRTH_INDEPENDENT => BirthEvents::Independent,
        _ => return Err(Failure::invalid("birth_events: unknown RFISST_BIRTH_* code")),
    };
    out.birth.measured = measured(&c.measured_births)?;
    out.death_probability = T::of_f64(c.death_probability);
    out.gate = flag(c.has_gate, "has_gate: must be 0 or 1")?.then(|| T::of_f64(c.gate));
    out.children = children(c)?;
    out.selection = match c.selection {
        choice::RFISST_SELECTION_TOP_WEIGHT => Selection::TopWeight,
        choice::RFISST_SELECTION_SAMPLED_BY_WEIGHT => Selection::SampledByWeight,
        choice::RFISST_SELECTION_TOP_WEIGHT_WITHIN => Selection::TopWeightWithin {
            decades: u8::try_from(c.selection_floor_decades)
                .map_err(|_| Failure::invalid("selection_floor_decades: must be 0..=255"))?,
        },
        _ => return Err(Failure::invalid("selection: unknown RFISST_SELECTION_* code")),
    };
    out.store_overflow = match c.store_overflow {
        choice::RFISST_STORE_OVERFLOW_PRUNE_CHILDREN => StoreOverflow::PruneChildren,
        choice::RFISST_STORE_OVERFLOW_ERROR => StoreOverflow::Error,
        _ => return Err(Failure::invalid("store_overflow: unknown RFISST_STORE_OVERFLOW_* code")),
    };
    out.numerical_failure = match c.numerical_failure {
        choice::RFISST_NUMERICAL_FAILURE_DROP_TRACK => NumericalFailure::DropTrack,
        choice::RFISST_NUMERICAL_FAILURE_ERROR => NumericalFailure::Error,
        _ => return Err(Failure::invalid("numerical_failure: unknown RFISST_NUMERICAL_FAILURE_* code")),
    };
    out.track_loss = track_loss(c.lost_after_unseen_scans)?;
    out.seed = c.seed;
    Ok(())
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
