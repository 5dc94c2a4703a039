//! Host only (`std`): a scenario-format JSON text (docs/scenario-format.md) as the C interface's values,
//! through host-sim's parser and configuration builders, so that a tracker built from JSON is the tracker
//! host-sim builds: [`CScenario`] (configuration, prior, scans in the tracker's units), the exported
//! `rfisst_tracker_init_json`, and the C source of a scenario for firmware ([`c_source`]).

use crate::api::{RfisstTracker, init};
use crate::config::{
    RFISST_MAX_SENSORS, RfisstAdmissibleRegion, RfisstConfig, RfisstDetection, RfisstGaussian, RfisstMeasuredBirths,
    RfisstPriorHypothesis, RfisstPriorObject, RfisstRegion, RfisstSensor, choice, region, sensor,
};
use crate::handle::{FAILED, Header, RfisstKind};
use crate::status::RfisstStatus;
use core::ffi::{CStr, c_char, c_void};
use host_sim::pipeline::orbital::corrections::corrected_measurements;
use host_sim::pipeline::orbital::tracker::{config3d, measurements_in_radians};
use host_sim::pipeline::planar::setup;
use host_sim::pipeline::tracker::TrackerKind;
use host_sim::scenario::v2::{Measurement3dSpec, Scenario3d};
use host_sim::scenario::{Scenario, ScenarioError};
use std::fmt::Write as _;
use tracker_core::config::Selection;
use tracker_core::model::{
    AdmissibleRegion, LightTime, MIXED_DIMENSION, MixedNetwork, Placeable, ProcessNoise, RadarRangeRate, SensorBirths,
    SensorKind, SensorNetwork,
};
use tracker_core::sampler::Proposal;
use tracker_core::sensor::{Platform, SiteSensor};
use tracker_core::{
    BirthDetection, BirthEvents, ChildGeneration, Config, Gaussian, LookShape, NumericalFailure, OpticalRaDec,
    PriorObject, RadarRangeAzEl, Region, Sensor, StoreOverflow, TrackLoss, ssa_caps,
};

/// One scan in the tracker's units (planar as in the file; 3-D angles in radians).
#[derive(Debug, Clone, PartialEq)]
pub struct CScan {
    /// Time (s).
    pub time: f64,
    /// Sensor index.
    pub sensor: usize,
    /// `count × dimension` values, row after row.
    pub measurements: Vec<f64>,
}

/// A scenario as the C interface's values.
#[derive(Debug, Clone)]
pub struct CScenario {
    /// The scenario's name.
    pub name: String,
    /// The configuration.
    pub config: RfisstConfig,
    /// The prior hypotheses: weight and objects.
    pub prior: Vec<(f64, Vec<RfisstPriorObject>)>,
    /// The prior's time (s).
    pub prior_time: f64,
    /// The scans.
    pub scans: Vec<CScan>,
    /// Components of one measurement for `kind`.
    pub dimension: usize,
}

impl CScenario {
    /// The prior as C hypotheses pointing into `self`.
    pub fn hypotheses(&self) -> Vec<RfisstPriorHypothesis> {
        self.prior
            .iter()
            .map(|(weight, objects)| RfisstPriorHypothesis {
                weight: *weight,
                objects: objects.as_ptr(),
                object_count: objects.len(),
            })
            .collect()
    }
}

/// Reads `text` (a version 1 or 2 scenario) for a tracker of `kind`. `detected_in` restricts a 3-D prior
/// to the objects that the first `n` scans detect (`truth.scans[k].origins`), as `host-sim digest` and the
/// QEMU firmware do.
///
/// # Errors
/// A one-line message: the JSON does not parse, the scenario does not fit `kind` (planar files for the
/// planar tracker; radar files for the radar or network tracker, optical files for the optical or
/// network tracker, radar with range-rate for the network tracker), or it uses what the C configuration
/// does not hold (measured births, a constant-velocity planar model, more than 8 sensors).
pub fn from_json(text: &str, kind: RfisstKind, detected_in: Option<usize>) -> Result<CScenario, String> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let version = serde_json::from_str::<serde_json::Value>(text)
        .ok()
        .and_then(|v| v.get("version").and_then(serde_json::Value::as_u64));
    if version == Some(2) {
        let scenario = Scenario3d::from_json(text).map_err(|e: ScenarioError| e.0)?;
        orbital(&scenario, kind, detected_in)
    } else {
        let scenario = Scenario::from_json(text).map_err(|e: ScenarioError| e.0)?;
        planar(&scenario, kind)
    }
}

fn planar(scenario: &Scenario, kind: RfisstKind) -> Result<CScenario, String> {
    if !kind.is_planar() {
        return Err(format!("kind: a version 1 (planar) scenario needs a planar tracker kind, not {}", kind.name()));
    }
    if scenario.birth.measured.is_some() {
        return Err("birth.measured: measured births are not in the C configuration".into());
    }
    let motion = setup::two_body(&scenario.motion)
        .ok_or("motion: the planar tracker (SsaTracker) is two-body; this scenario is constant-velocity")?;
    let core: Config<f64, _, _, 4, { ssa_caps::BIRTH_CELLS }> =
        setup::config(scenario, motion, setup::sampled(scenario)).map_err(|e| e.0)?;
    let mut config = common(&core)?;
    config.mu = core.motion.mu;
    config.acceleration_noise = core.motion.acceleration_noise;
    config.max_step = core.motion.max_step;
    config.max_substeps = core.motion.max_substeps;
    config.min_radius = core.motion.min_radius;
    config.position_noise = [0, 1, 2, 3].map(|k| core.measurement.noise[(k / 2, k % 2)]);
    config.sensor = detection(&core.sensor);
    let prior =
        setup::prior(scenario).into_iter().map(|(w, objects)| (w, objects.iter().map(object).collect())).collect();
    let scans = scenario
        .scans
        .iter()
        .map(|s| CScan { time: s.time, sensor: 0, measurements: s.measurements.iter().flatten().copied().collect() })
        .collect();
    Ok(CScenario { name: scenario.name.clone(), config, prior, prior_time: scenario.prior.time, scans, dimension: 2 })
}

fn orbital(scenario: &Scenario3d, kind: RfisstKind, detected_in: Option<usize>) -> Result<CScenario, String> {
    use RfisstKind as K;
    let measurement = scenario.measurement;
    let fits = match measurement {
        Measurement3dSpec::Radar => {
            matches!(kind, K::RfisstRadarF32 | K::RfisstRadarF64 | K::RfisstNetworkF32 | K::RfisstNetworkF64)
        }
        Measurement3dSpec::Optical => {
            matches!(kind, K::RfisstOpticalF32 | K::RfisstOpticalF64 | K::RfisstNetworkF32 | K::RfisstNetworkF64)
        }
        Measurement3dSpec::RadarRangeRate | Measurement3dSpec::Network => {
            matches!(kind, K::RfisstNetworkF32 | K::RfisstNetworkF64)
        }
        other => {
            return Err(format!(
                "measurement: a {} scenario is not read from JSON by the C interface yet; give the network tracker \
                 a configuration struct (RfisstConfig) with each sensor's kind",
                other.name()
            ));
        }
    };
    if !fits {
        return Err(format!("kind: a {} scenario does not fit a {} tracker", measurement.name(), kind.name()));
    }
    let (mut config, prior) = match measurement {
        Measurement3dSpec::Radar => orbital_config::<RadarRangeAzEl<f64>, 3>(scenario, sensor::RFISST_SENSOR_RADAR)?,
        Measurement3dSpec::Optical => orbital_config::<OpticalRaDec<f64>, 2>(scenario, sensor::RFISST_SENSOR_OPTICAL)?,
        Measurement3dSpec::RadarRangeRate => {
            orbital_config::<RadarRangeRate<f64>, 4>(scenario, sensor::RFISST_SENSOR_RADAR_RANGE_RATE)?
        }
        Measurement3dSpec::Network => network_config(scenario)?,
        other => return Err(format!("measurement: a {} scenario is not read from JSON yet", other.name())),
    };
    config.earth_rotation_angle = scenario.earth_rotation_at_epoch();
    // A network scenario's prior is the file's whole prior, as `host-sim digest` replays it.
    let detected_in = detected_in.filter(|_| measurement != Measurement3dSpec::Network);
    let detected = match detected_in {
        Some(count) => Some(host_sim::pipeline::digest::orbital::detected(scenario, count).map_err(|e| e.0)?),
        None => None,
    };
    let prior = prior
        .into_iter()
        .map(|(w, objects)| {
            let kept = objects.iter().filter(|o| detected.as_ref().is_none_or(|d| d.contains(&u64::from(o.label.0))));
            (w, kept.map(object).collect())
        })
        .collect();
    let network = matches!(kind, K::RfisstNetworkF32 | K::RfisstNetworkF64);
    let dimension = if network { crate::config::RFISST_NETWORK_DIMENSION } else { measurement.dimension() };
    let scans = scenario
        .scans
        .iter()
        .map(|s| {
            let rows = if measurement == Measurement3dSpec::Network {
                corrected_measurements(scenario, s)
            } else {
                measurements_in_radians(measurement, &s.measurements)
            };
            let measurements =
                rows.iter().flat_map(|z| (0..dimension).map(move |i| z.get(i).copied().unwrap_or(0.0))).collect();
            CScan { time: s.time, sensor: s.sensor, measurements }
        })
        .collect();
    Ok(CScenario { name: scenario.name.clone(), config, prior, prior_time: scenario.prior.time, scans, dimension })
}

type Prior6 = Vec<(f64, Vec<PriorObject<f64, 6>>)>;

/// The 3-D configuration through host-sim's `config3d` for the measurement model `X`.
fn orbital_config<X: Placeable<f64, D> + Send + Sync + 'static, const D: usize>(
    scenario: &Scenario3d,
    kind: u32,
) -> Result<(RfisstConfig, Prior6), String> {
    let (core, prior) = config3d::<
        SensorNetwork<f64, X, D, { host_sim::pipeline::orbital::C }>,
        D,
        { ssa_caps::BIRTH_CELLS },
    >(scenario, TrackerKind::Rfisst)
    .map_err(|e| e.to_string())?;
    let mut config = common(&core)?;
    motion(&mut config, &core.motion);
    let sensors = core.measurement.sensors();
    if sensors.len() > RFISST_MAX_SENSORS {
        return Err(format!("sensors: {} sensors, the C configuration holds {RFISST_MAX_SENSORS}", sensors.len()));
    }
    config.sensor_count = sensors.len() as u32;
    for (slot, s) in config.sensors.iter_mut().zip(sensors) {
        *slot = site_sensor(kind, s);
    }
    Ok((config, prior))
}

/// The configuration of a network scenario (sensors of mixed kinds, each with its births), through
/// host-sim's `config3d` as `host-sim digest` builds it. Light time is not in the C configuration.
fn network_config(scenario: &Scenario3d) -> Result<(RfisstConfig, Prior6), String> {
    let (core, prior) = config3d::<
        MixedNetwork<f64, { host_sim::pipeline::orbital::C }>,
        MIXED_DIMENSION,
        { ssa_caps::BIRTH_CELLS },
    >(scenario, TrackerKind::Rfisst)
    .map_err(|e| e.to_string())?;
    let mut config = common(&core)?;
    motion(&mut config, &core.motion);
    let network = &core.measurement;
    let sensors = network.sensors();
    if sensors.len() > RFISST_MAX_SENSORS {
        return Err(format!("sensors: {} sensors, the C configuration holds {RFISST_MAX_SENSORS}", sensors.len()));
    }
    config.sensor_count = sensors.len() as u32;
    for (index, (slot, s)) in config.sensors.iter_mut().zip(sensors).enumerate() {
        if network.light_time(index) != LightTime::Off {
            return Err(format!("sensors[{index}].light_time: light time is not in the C configuration"));
        }
        *slot = site_sensor(kind_code(s.kind), &s.sensor);
        (slot.births, slot.birth_region) = match network.births(index) {
            SensorBirths::FromModel => (sensor::RFISST_BIRTHS_FROM_MODEL, RfisstAdmissibleRegion::ZERO),
            SensorBirths::Region(region) => (sensor::RFISST_BIRTHS_REGION, admissible(&region)),
            SensorBirths::Off => (sensor::RFISST_BIRTHS_OFF, RfisstAdmissibleRegion::ZERO),
        };
    }
    Ok((config, prior))
}

/// The C code of a sensor kind.
fn kind_code(kind: SensorKind) -> u32 {
    match kind {
        SensorKind::Radar => sensor::RFISST_SENSOR_RADAR,
        SensorKind::RadarRangeRate => sensor::RFISST_SENSOR_RADAR_RANGE_RATE,
        SensorKind::OpticalRaDec => sensor::RFISST_SENSOR_OPTICAL,
        SensorKind::AzEl => sensor::RFISST_SENSOR_AZ_EL,
        SensorKind::Range => sensor::RFISST_SENSOR_RANGE,
        SensorKind::RangeRangeRate => sensor::RFISST_SENSOR_RANGE_RANGE_RATE,
    }
}

/// A core site sensor of kind `kind` as a C sensor (births from the model).
fn site_sensor<const D: usize>(kind: u32, s: &SiteSensor<f64, D>) -> RfisstSensor {
    let (platform, [latitude, longitude, height]) = match s.platform {
        Platform::Ground(site) => (sensor::RFISST_PLATFORM_GROUND, [site.latitude, site.longitude, site.height]),
        Platform::Spacecraft => (sensor::RFISST_PLATFORM_SPACECRAFT, [0.0; 3]),
    };
    let mut sigma = [0.0; 4];
    for (to, from) in sigma.iter_mut().zip(s.sigma) {
        *to = from;
    }
    RfisstSensor {
        kind,
        platform,
        latitude,
        longitude,
        height,
        sigma,
        detection: detection(&s.detection),
        births: sensor::RFISST_BIRTHS_FROM_MODEL,
        birth_region: RfisstAdmissibleRegion::ZERO,
    }
}

/// The 3-D motion model's values into `config`.
fn motion(config: &mut RfisstConfig, motion: &tracker_core::TwoBodyJ2<f64>) {
    config.mu = motion.mu;
    config.j2 = motion.j2;
    config.radius = motion.radius;
    config.min_radius = motion.min_radius;
    (config.process_noise_type, config.process_noise) = match motion.noise {
        ProcessNoise::Isotropic(q) => (choice::RFISST_NOISE_ISOTROPIC, [q, 0.0, 0.0]),
        ProcessNoise::Ric { radial, in_track, cross_track } => {
            (choice::RFISST_NOISE_RIC, [radial, in_track, cross_track])
        }
    };
    config.max_step = motion.max_step;
    config.max_substeps = motion.max_substeps;
}

/// What every configuration shares.
fn common<M, G, const S: usize>(
    core: &Config<f64, M, G, S, { ssa_caps::BIRTH_CELLS }>,
) -> Result<RfisstConfig, String> {
    let mut c = RfisstConfig::default_for(S == 4);
    c.birth_probability = core.birth.probability;
    c.birth_cell_count = core.birth.cells.len() as u32;
    for (slot, cell) in c.birth_cells.iter_mut().zip(&core.birth.cells) {
        *slot = gaussian(cell);
    }
    c.birth_detection = match core.birth.detection {
        BirthDetection::AllDetected => choice::RFISST_BIRTH_ALL_DETECTED,
        BirthDetection::AllowUndetected => choice::RFISST_BIRTH_ALLOW_UNDETECTED,
    };
    c.birth_events = match core.birth.events {
        BirthEvents::FirstOrder => choice::RFISST_BIRTH_FIRST_ORDER,
        BirthEvents::Independent => choice::RFISST_BIRTH_INDEPENDENT,
    };
    if let Some(m) = &core.birth.measured {
        if m.tracklets.is_some() {
            return Err("birth.measured.tracklets: births from tracklets are not in the C configuration".into());
        }
        c.measured_births = RfisstMeasuredBirths {
            enabled: 1,
            region: admissible(&m.region),
            expected_births: m.expected_births,
            max_probability: m.max_probability,
            min_unexplained: m.min_unexplained,
            lifetime: m.lifetime,
            link_waiting: u32::from(m.link_waiting),
        };
    }
    c.death_probability = core.death_probability;
    (c.has_gate, c.gate) = core.gate.map_or((0, 0.0), |g| (1, g));
    match core.children {
        ChildGeneration::Exhaustive { max_children_per_scan } => {
            c.children = choice::RFISST_CHILDREN_EXHAUSTIVE;
            c.max_children_per_scan = max_children_per_scan;
        }
        ChildGeneration::Sampled(s) => {
            c.children = choice::RFISST_CHILDREN_SAMPLED;
            c.sampler.burn_in = s.burn_in;
            c.sampler.steps = s.steps;
            c.sampler.proposal = match s.proposal {
                Proposal::Paper => choice::RFISST_PROPOSAL_PAPER,
                Proposal::MoveOrSwap => choice::RFISST_PROPOSAL_MOVE_OR_SWAP,
                Proposal::Informed => choice::RFISST_PROPOSAL_INFORMED,
            };
            c.sampler.clusters = u32::from(s.clusters);
            c.sampler.exhaustive_limit = s.exhaustive_limit;
            c.sampler.exact_start = u32::from(s.exact_start);
        }
    }
    c.selection = match core.selection {
        Selection::TopWeight => choice::RFISST_SELECTION_TOP_WEIGHT,
        Selection::SampledByWeight => choice::RFISST_SELECTION_SAMPLED_BY_WEIGHT,
        Selection::TopWeightWithin { decades } => {
            c.selection_floor_decades = u32::from(decades);
            choice::RFISST_SELECTION_TOP_WEIGHT_WITHIN
        }
    };
    c.store_overflow = match core.store_overflow {
        StoreOverflow::PruneChildren => choice::RFISST_STORE_OVERFLOW_PRUNE_CHILDREN,
        StoreOverflow::Error => choice::RFISST_STORE_OVERFLOW_ERROR,
    };
    c.numerical_failure = match core.numerical_failure {
        NumericalFailure::DropTrack => choice::RFISST_NUMERICAL_FAILURE_DROP_TRACK,
        NumericalFailure::Error => choice::RFISST_NUMERICAL_FAILURE_ERROR,
    };
    c.lost_after_unseen_scans = match core.track_loss {
        TrackLoss::Never => 0,
        TrackLoss::AfterUnseenScans(n) => u32::from(n.get()),
    };
    c.seed = core.seed;
    Ok(c)
}

fn admissible(r: &AdmissibleRegion<f64>) -> RfisstAdmissibleRegion {
    let count = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    RfisstAdmissibleRegion {
        mu: r.mu,
        min_perigee_radius: r.min_perigee_radius,
        max_apogee_radius: r.max_apogee_radius,
        max_inclination: r.max_inclination,
        shell: r.shell,
        headings: count(r.headings),
        speeds: count(r.speeds),
        climbs: count(r.climbs),
        ranges: count(r.ranges),
        velocity_sigma: r.velocity_sigma,
    }
}

fn gaussian<const S: usize>(g: &Gaussian<f64, S>) -> RfisstGaussian {
    let mut out = RfisstGaussian::ZERO;
    for i in 0..S.min(6) {
        out.mean[i] = g.mean[i];
        for j in 0..S.min(6) {
            out.covariance[i * 6 + j] = g.covariance[(i, j)];
        }
    }
    out
}

fn object<const S: usize>(o: &PriorObject<f64, S>) -> RfisstPriorObject {
    RfisstPriorObject { label: o.label.0, state: gaussian(&o.state) }
}

fn detection(s: &Sensor<f64>) -> RfisstDetection {
    RfisstDetection {
        detection_probability: s.detection_probability,
        clutter_rate: s.clutter_rate,
        field_of_view: region_of(&s.field_of_view),
    }
}

fn region_of(r: &Region<f64>) -> RfisstRegion {
    let mut c = RfisstRegion::EMPTY;
    match *r {
        Region::Everywhere { volume } => c.volume = volume,
        Region::Rectangle { min, max } => (c.r#type, c.min, c.max) = (region::RFISST_REGION_RECTANGLE, min, max),
        Region::Sector { origin, look_direction, half_angle, max_range } => {
            c.r#type = region::RFISST_REGION_SECTOR;
            (c.origin, c.look_direction, c.half_angle, c.max_range) = (origin, look_direction, half_angle, max_range);
        }
        Region::Look { shape, min_elevation, range, range_rate } => {
            c.r#type = region::RFISST_REGION_LOOK;
            match shape {
                LookShape::Cone { azimuth, elevation, half_angle } => {
                    c.shape = region::RFISST_LOOK_CONE;
                    (c.azimuth, c.elevation, c.half_angle) = (azimuth, elevation, half_angle);
                }
                LookShape::Box { azimuth, half_width, elevation } => {
                    c.shape = region::RFISST_LOOK_BOX;
                    (c.azimuth, c.half_width, c.elevation_window) = (azimuth, half_width, elevation);
                }
            }
            c.min_elevation = min_elevation;
            if let Some(window) = range {
                (c.has_range, c.range) = (1, window);
            }
            if let Some(window) = range_rate {
                (c.has_range_rate, c.range_rate) = (1, window);
            }
        }
    }
    c
}

/// Initialises a tracker of `kind` in `storage` from a scenario-format JSON text (NUL-terminated UTF-8):
/// its configuration and whole prior, as host-sim builds them (angles in the file in degrees, converted
/// to radians). As `rfisst_tracker_init` otherwise; `SCENARIO` when the text does not parse or does not
/// fit `kind`. Host builds only (the `std` feature); allocates while it parses, never in a step.
///
/// # Safety
/// As `rfisst_tracker_init`; `json` null or a NUL-terminated string.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn rfisst_tracker_init_json(
    storage: *mut c_void,
    size: usize,
    kind: u32,
    json: *const c_char,
    tracker: *mut *mut RfisstTracker,
) -> RfisstStatus {
    if tracker.is_null() {
        return RfisstStatus::RfisstNullPointer;
    }
    if !tracker.is_aligned() {
        return RfisstStatus::RfisstMisaligned;
    }
    // SAFETY: non-null and aligned; the caller promises it is writable.
    unsafe { tracker.write(core::ptr::null_mut()) };
    let Some(kind) = RfisstKind::of(kind) else { return RfisstStatus::RfisstUnknownKind };
    if storage.is_null() || json.is_null() {
        return RfisstStatus::RfisstNullPointer;
    }
    if size < crate::handle::size(kind) {
        return RfisstStatus::RfisstBadSize;
    }
    if !(storage as usize).is_multiple_of(crate::handle::align(kind)) {
        return RfisstStatus::RfisstMisaligned;
    }
    // SAFETY: non-null; the caller promises a NUL-terminated string.
    let text = unsafe { CStr::from_ptr(json) };
    let parsed = match text.to_str() {
        Ok(text) => from_json(text, kind, None),
        Err(_) => Err("the JSON text is not UTF-8".to_string()),
    };
    let scenario = match parsed {
        Ok(scenario) => scenario,
        Err(message) => {
            let mut header = Header::new(FAILED, kind);
            header.record(&format_args!("scenario: {}", host_sim::scenario::checks::one_line(&message)));
            // SAFETY: checked size and alignment (a slot starts with its header).
            unsafe { storage.cast::<Header>().write(header) };
            return RfisstStatus::RfisstScenario;
        }
    };
    let hypotheses = scenario.hypotheses();
    // SAFETY: checked size and alignment.
    match unsafe { init(storage, kind, &scenario.config, &hypotheses, scenario.prior_time) } {
        Ok(()) => {
            // SAFETY: as above.
            unsafe { tracker.write(storage.cast()) };
            RfisstStatus::RfisstOk
        }
        Err(failure) => failure.status(),
    }
}

/// `value` as a C `double` literal that parses back to the same bits.
fn c_double(value: f64) -> String {
    if value.is_nan() {
        "__builtin_nan(\"\")".into()
    } else if value.is_infinite() {
        if value > 0.0 { "__builtin_inf()".into() } else { "-__builtin_inf()".into() }
    } else {
        let text = format!("{value:?}");
        if text.contains(['.', 'e', 'E']) { text } else { format!("{text}.0") }
    }
}

fn c_doubles(values: &[f64]) -> String {
    format!("{{{}}}", values.iter().map(|&v| c_double(v)).collect::<Vec<_>>().join(", "))
}

fn c_gaussian(g: &RfisstGaussian) -> String {
    format!("{{{}, {}}}", c_doubles(&g.mean), c_doubles(&g.covariance))
}

fn c_region(r: &RfisstRegion) -> String {
    format!(
        "{{{}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}}}",
        r.r#type,
        c_double(r.volume),
        c_doubles(&r.min),
        c_doubles(&r.max),
        c_doubles(&r.origin),
        c_double(r.look_direction),
        c_double(r.half_angle),
        c_double(r.max_range),
        r.shape,
        c_double(r.azimuth),
        c_double(r.elevation),
        c_double(r.half_width),
        c_doubles(&r.elevation_window),
        c_double(r.min_elevation),
        r.has_range,
        c_doubles(&r.range),
        r.has_range_rate,
        c_doubles(&r.range_rate)
    )
}

fn c_detection(d: &RfisstDetection) -> String {
    format!("{{{}, {}, {}}}", c_double(d.detection_probability), c_double(d.clutter_rate), c_region(&d.field_of_view))
}

fn c_admissible(r: &RfisstAdmissibleRegion) -> String {
    format!(
        "{{{}, {}, {}, {}, {}, {}u, {}u, {}u, {}u, {}}}",
        c_double(r.mu),
        c_double(r.min_perigee_radius),
        c_double(r.max_apogee_radius),
        c_double(r.max_inclination),
        c_doubles(&r.shell),
        r.headings,
        r.speeds,
        r.climbs,
        r.ranges,
        c_double(r.velocity_sigma)
    )
}

fn c_config(c: &RfisstConfig) -> String {
    let sensors: Vec<String> = c
        .sensors
        .iter()
        .map(|s| {
            format!(
                "{{{}, {}, {}, {}, {}, {}, {}, {}u, {}}}",
                s.kind,
                s.platform,
                c_double(s.latitude),
                c_double(s.longitude),
                c_double(s.height),
                c_doubles(&s.sigma),
                c_detection(&s.detection),
                s.births,
                c_admissible(&s.birth_region)
            )
        })
        .collect();
    let cells: Vec<String> = c.birth_cells.iter().map(c_gaussian).collect();
    let s = &c.sampler;
    let m = &c.measured_births;
    [
        format!("    .mu = {}, .acceleration_noise = {},", c_double(c.mu), c_double(c.acceleration_noise)),
        format!(
            "    .j2 = {}, .radius = {}, .min_radius = {},",
            c_double(c.j2),
            c_double(c.radius),
            c_double(c.min_radius)
        ),
        format!(
            "    .process_noise_type = {}, .process_noise = {},",
            c.process_noise_type,
            c_doubles(&c.process_noise)
        ),
        format!("    .max_step = {}, .max_substeps = {}u,", c_double(c.max_step), c.max_substeps),
        format!("    .position_noise = {},", c_doubles(&c.position_noise)),
        format!("    .sensor = {},", c_detection(&c.sensor)),
        format!("    .earth_rotation_angle = {},", c_double(c.earth_rotation_angle)),
        format!("    .sensors = {{\n        {}}},", sensors.join(",\n        ")),
        format!("    .sensor_count = {}u,", c.sensor_count),
        format!("    .birth_probability = {},", c_double(c.birth_probability)),
        format!("    .birth_cells = {{\n        {}}},", cells.join(",\n        ")),
        format!(
            "    .birth_cell_count = {}u, .birth_detection = {}u, .birth_events = {}u,",
            c.birth_cell_count, c.birth_detection, c.birth_events
        ),
        format!(
            "    .measured_births = {{{}u, {}, {}, {}, {}, {}, {}u}},",
            m.enabled,
            c_admissible(&m.region),
            c_double(m.expected_births),
            c_double(m.max_probability),
            c_double(m.min_unexplained),
            c_double(m.lifetime),
            m.link_waiting
        ),
        format!(
            "    .death_probability = {}, .has_gate = {}u, .gate = {},",
            c_double(c.death_probability),
            c.has_gate,
            c_double(c.gate)
        ),
        format!("    .children = {}u, .max_children_per_scan = {}ull,", c.children, c.max_children_per_scan),
        format!(
            "    .sampler = {{{}u, {}u, {}u, {}u, {}ull, {}u}},",
            s.burn_in, s.steps, s.proposal, s.clusters, s.exhaustive_limit, s.exact_start
        ),
        format!(
            "    .selection = {}u, .selection_floor_decades = {}u, .store_overflow = {}u, .numerical_failure = {}u,",
            c.selection, c.selection_floor_decades, c.store_overflow, c.numerical_failure
        ),
        format!("    .lost_after_unseen_scans = {}u,", c.lost_after_unseen_scans),
        format!("    .seed = {}ull,", c.seed),
    ]
    .join("\n")
}

/// The C source of the first `scans` scans of `scenario` for a firmware: `<prefix>_CONFIG`,
/// `<prefix>_PRIOR` (`<prefix>_PRIOR_COUNT` hypotheses), `<prefix>_PRIOR_TIME`, `<prefix>_SCANS`
/// (`<prefix>_SCAN_COUNT` of `RfisstReplayScan`, declared in the firmware's `replay.h`) and
/// `<prefix>_DIMENSION`. Every double is written so that it parses back to the same bits.
pub fn c_source(scenario: &CScenario, prefix: &str, scans: usize) -> String {
    let mut o = String::new();
    let _ = writeln!(o, "/* Generated by rfisst-c-scenario from scenario {:?}: do not edit. */", scenario.name);
    let _ = writeln!(o, "#include \"replay.h\"\n");
    let _ = writeln!(o, "const RfisstConfig {prefix}_CONFIG = {{\n{}\n}};\n", c_config(&scenario.config));
    for (h, (_, objects)) in scenario.prior.iter().enumerate() {
        let items: Vec<String> =
            objects.iter().map(|o| format!("    {{{}u, {}}}", o.label, c_gaussian(&o.state))).collect();
        let _ = writeln!(
            o,
            "static const RfisstPriorObject {prefix}_PRIOR_{h}[{}] = {{\n{}\n}};",
            objects.len().max(1),
            items.join(",\n")
        );
    }
    let hypotheses: Vec<String> = scenario
        .prior
        .iter()
        .enumerate()
        .map(|(h, (w, objects))| format!("    {{{}, {prefix}_PRIOR_{h}, {}u}}", c_double(*w), objects.len()))
        .collect();
    let _ = writeln!(
        o,
        "const RfisstPriorHypothesis {prefix}_PRIOR[{}] = {{\n{}\n}};",
        hypotheses.len(),
        hypotheses.join(",\n")
    );
    let _ = writeln!(o, "const size_t {prefix}_PRIOR_COUNT = {}u;", hypotheses.len());
    let _ = writeln!(o, "const double {prefix}_PRIOR_TIME = {};", c_double(scenario.prior_time));
    let _ = writeln!(o, "const size_t {prefix}_DIMENSION = {}u;\n", scenario.dimension);
    let count = scans.min(scenario.scans.len());
    for (k, scan) in scenario.scans[..count].iter().enumerate() {
        let values = if scan.measurements.is_empty() { "{0.0}".to_string() } else { c_doubles(&scan.measurements) };
        let _ = writeln!(o, "static const double {prefix}_Z_{k}[] = {values};");
    }
    let rows: Vec<String> = scenario.scans[..count]
        .iter()
        .enumerate()
        .map(|(k, s)| {
            format!(
                "    {{{}, {}u, {prefix}_Z_{k}, {}u}}",
                c_double(s.time),
                s.sensor,
                s.measurements.len() / scenario.dimension.max(1)
            )
        })
        .collect();
    let _ = writeln!(o, "\nconst RfisstReplayScan {prefix}_SCANS[{}] = {{\n{}\n}};", count.max(1), rows.join(",\n"));
    let _ = writeln!(o, "const size_t {prefix}_SCAN_COUNT = {count}u;");
    o
}
