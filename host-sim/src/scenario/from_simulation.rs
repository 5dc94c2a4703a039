//! `host-sim generate radar-leo | optical-geo | optical-leo | optical-heo | tiny-3d`: the 3-D presets of [`crate::ssa`]
//! written as version 2 scenario files ([`crate::scenario::v2`]).
//!
//! The truth of every object at every scan comes from [`crate::sim::orbit`]'s adaptive RKF7(8) two-body + J2
//! integrator, step by step from the epoch (never from the tracker's fixed-step RK4). Every object exists
//! for the whole run unless it is a break-up fragment (from its `birth_time` on), and is in the prior unless
//! the simulation says otherwise ([`truth::Unknowns`]), 1 s before the first scan: its prior mean is the true
//! state then plus an error drawn from the prior covariance (stream [`Stream::Prior`] of the seed). A birth
//! is confirmed at existence ≥ 0.5 (the evaluation's `confirmation_existence`). A detection whose noisy measurement
//! falls outside the sensor's field of view (an object at the edge) is dropped: the sensor does not report
//! it, and the tracker rejects a scan with a measurement outside the field of view.

use crate::error::Error;
use crate::pipeline::orbital::{FieldOfViewCheck, measurements_in_radians};
use crate::scenario::v2::*;
use crate::scenario::{
    AdmissiblePresetSpec, BirthDetectionSpec, BirthEventsSpec, BirthRegionSpec, EvaluationSpec, MeasuredBirthsSpec,
    NumericalFailureSpec, SamplerSpec, SelectionSpec, SensorRegionSpec, StoreOverflowSpec, TrackerSpec, TrackletSpec,
    TruthObjectSpec,
};
use crate::sim::network::NetworkConfig;
use crate::sim::orbit::Propagator;
use crate::sim::presets::OpticalGeoConfig;
use crate::sim::presets::RadarLeoConfig;
use crate::sim::rng::{Random, Stream};
use crate::sim::sensor::SensorKind;
use crate::sim::ssa::SsaScenario;
use crate::sim::truth::Unknowns;
use crate::sim::{field_of_view, presets, sensor};
use nalgebra::SMatrix;

/// The 3-D presets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Preset3d {
    /// Two ground radars, 120 LEO objects (10 crossing pairs), 6 h.
    RadarLeo,
    /// A staring telescope on the GEO belt, 32 objects (3 co-located clusters), 4 h.
    OpticalGeo,
    /// A wide-field telescope at twilight, 100 sunlit LEO objects crossing its field, a frame every 2 s;
    /// unknown objects born from tracklets ([`crate::sim::optical_leo`]).
    OpticalLeo,
    /// The GEO telescope at night, 6 GEO objects it knows and 4 GTO and 4 Molniya objects it must start
    /// from tracklets ([`crate::sim::optical_heo`]).
    OpticalHeo,
    /// One radar, 3 LEO objects, 11 scans over 100 s (tests).
    #[value(name = "tiny-3d")]
    Tiny3d,
    /// Two radars, two telescopes, an az/el and a ranging station; LEO, GEO and Molniya objects, some
    /// unknown to the prior; 3 h ([`crate::sim::network`]).
    SsaNetwork,
    /// `ssa-network`'s sensors over 2 LEO (one unknown), 1 GEO and 1 Molniya object, 10 minutes (tests).
    #[value(name = "tiny-network")]
    TinyNetwork,
}

impl Preset3d {
    /// The simulation of this preset with `seed`.
    ///
    /// # Errors
    /// The simulator's message.
    pub fn simulate(self, seed: u64) -> Result<SsaScenario, Error> {
        self.simulate_with(seed, &Unknowns::default())
    }

    /// The simulation of this preset with `seed` and objects unknown to the prior (`radar-leo`: missing
    /// objects and a break-up; `optical-geo`, `optical-leo` and `tiny-3d`: missing objects).
    ///
    /// # Errors
    /// Bad input: unknowns the preset cannot have; otherwise the simulator's message.
    pub fn simulate_with(self, seed: u64, unknowns: &Unknowns) -> Result<SsaScenario, Error> {
        let result = match self {
            Preset3d::RadarLeo => {
                presets::radar_leo_with(seed, &RadarLeoConfig { unknowns: *unknowns, ..RadarLeoConfig::PRESET })
            }
            Preset3d::OpticalGeo => {
                presets::optical_geo_with(seed, &OpticalGeoConfig { unknowns: *unknowns, ..OpticalGeoConfig::PRESET })
            }
            Preset3d::OpticalLeo => crate::sim::optical_leo::optical_leo_with(
                seed,
                &crate::sim::optical_leo::OpticalLeoConfig {
                    unknowns: *unknowns,
                    ..crate::sim::optical_leo::OpticalLeoConfig::PRESET
                },
            ),
            // Its eccentric objects are always unknown and its GEO objects always known.
            Preset3d::OpticalHeo if *unknowns != Unknowns::default() => Err(crate::sim::error::SsaError::BadUnknowns),
            Preset3d::OpticalHeo => crate::sim::optical_heo::optical_heo(seed),
            Preset3d::Tiny3d => presets::tiny_3d_with(seed, unknowns),
            Preset3d::SsaNetwork => crate::sim::network::ssa_network(seed, unknowns, &NetworkConfig::PRESET),
            Preset3d::TinyNetwork => crate::sim::network::ssa_network(seed, unknowns, &NetworkConfig::TINY),
        };
        result.map_err(|e| match e {
            crate::sim::error::SsaError::BadUnknowns => Error::input(e.to_string()),
            e => Error::internal(format!("simulation: {e}")),
        })
    }
}

/// Prior standard deviations (position km, velocity km/s), process noise q (km²/s³) and the birth pool
/// (used when some object is unknown to the prior) of a preset.
struct Settings {
    position_sigma: f64,
    velocity_sigma: f64,
    q: f64,
    evaluation: EvaluationSpec,
    births: MeasuredBirthsSpec,
    /// Track loss (`tracker.lost_after_unseen_scans`).
    lost_after_unseen_scans: Option<core::num::NonZeroU16>,
}

fn settings(measurement: Measurement3dSpec) -> Settings {
    match measurement {
        // LEO radar: a catalogue-quality prior; GOSPA in km.
        Measurement3dSpec::Radar
        | Measurement3dSpec::RadarRangeRate
        | Measurement3dSpec::Range
        | Measurement3dSpec::RangeRangeRate => Settings {
            position_sigma: 0.2,
            velocity_sigma: 2e-4,
            q: 1e-12,
            evaluation: EvaluationSpec {
                error_bound: 5.0,
                gospa_cutoff: 10.0,
                gospa_order: 2.0,
                confirmation_existence: 0.5,
            },
            births: RADAR_LEO_BIRTHS,
            lost_after_unseen_scans: None,
        },
        // A network of LEO, GEO and Molniya objects: the radar prior, the telescope's error bound and
        // cut-off (its GEO objects' range is weakly observed), cells that live until the sensor's next scan
        // (each sensor scans once a minute); each sensor's region is its own (`network_birth_region`).
        Measurement3dSpec::Network => Settings {
            position_sigma: 0.2,
            velocity_sigma: 2e-4,
            q: 1e-12,
            evaluation: EvaluationSpec {
                error_bound: 10.0,
                gospa_cutoff: 20.0,
                gospa_order: 2.0,
                confirmation_existence: 0.5,
            },
            births: MeasuredBirthsSpec { lifetime: 300.0, ..RADAR_LEO_BIRTHS },
            // A track in view of 5 scans in a row with no measurement in its gate has left its object
            // (p_D ≥ 0.8: a true track misses 5 in a row with probability ≤ 0.2⁵ = 3e-4).
            lost_after_unseen_scans: core::num::NonZeroU16::new(5),
        },
        // GEO telescope: angles only, range weakly observed: a looser prior and cut-off.
        Measurement3dSpec::Optical | Measurement3dSpec::AzEl => Settings {
            position_sigma: 1.0,
            velocity_sigma: 1e-4,
            q: 1e-12,
            evaluation: EvaluationSpec {
                error_bound: 10.0,
                gospa_cutoff: 20.0,
                gospa_order: 2.0,
                confirmation_existence: 0.5,
            },
            births: TELESCOPE_GEO_BIRTHS,
            lost_after_unseen_scans: None,
        },
    }
}

/// The file's kind of a simulator's sensor.
fn file_kind(kind: SensorKind) -> Measurement3dSpec {
    match kind {
        SensorKind::Radar => Measurement3dSpec::Radar,
        SensorKind::RadarRangeRate { .. } => Measurement3dSpec::RadarRangeRate,
        SensorKind::Optical => Measurement3dSpec::Optical,
        SensorKind::AzEl => Measurement3dSpec::AzEl,
        SensorKind::Range => Measurement3dSpec::Range,
        SensorKind::RangeRangeRate { .. } => Measurement3dSpec::RangeRangeRate,
    }
}

/// A network sensor's own births: telescopes on the GEO belt (as `optical-geo`); none from an az/el
/// station (single-frame angles-only births of LEO objects do not land within kilometres: its objects are
/// born from the radars' measurements and kept by the station); radars use `birth.measured`'s LEO region
/// and range-only kinds give none.
pub(crate) fn network_birth_region(kind: Measurement3dSpec) -> Option<BirthRegionSpec> {
    let region = |region| BirthRegionSpec { region, headings: None, speeds: None, climbs: None, ranges: None };
    match kind {
        // The GEO belt's wider region, 2 headings (measured before `optical-geo` moved to geosynchronous
        // orbits and 3 headings; the network's firmware replay and its digests are made with these).
        Measurement3dSpec::Optical => {
            Some(BirthRegionSpec { headings: Some(2), ranges: Some(1), ..region(SensorRegionSpec::Geo) })
        }
        Measurement3dSpec::AzEl => Some(region(SensorRegionSpec::None)),
        _ => None,
    }
}

/// The birth pool a radar preset writes when objects are unknown to the prior (docs/results.md, "Births
/// from the measurements"): 12 headings keep each component narrow enough for the EKF update of a new
/// track (4 headings left it overconfident: the third detection fell outside its gate); λ_B and the cap
/// on α set how fast a birth is confirmed against how often two clutter returns make a track. The cells the
/// full pool cannot keep wait for a link (docs/maths.md §5.8, "Births in clutter").
pub const RADAR_LEO_BIRTHS: MeasuredBirthsSpec = MeasuredBirthsSpec {
    region: AdmissiblePresetSpec::Leo,
    velocity_sigma: 1.0,
    headings: Some(12),
    speeds: Some(1),
    climbs: Some(1),
    ranges: None,
    expected_births: 1e-2,
    max_probability: 1e-3,
    min_unexplained: 0.5,
    lifetime: 60.0,
    tracklets: None,
    link_waiting: true,
};

/// The birth pool a telescope preset writes when objects are unknown to the prior: geosynchronous orbits
/// (the preset's objects keep their longitudes; from one site over minutes, range is known only as well
/// as the region bounds it: docs/results.md, "Births from the measurements"), one radius cell, 3 headings
/// (an odd count puts a cell on the equatorial heading most GEO objects have), cells that live 20 minutes
/// (the revisit of a staring sensor's slow objects).
pub const TELESCOPE_GEO_BIRTHS: MeasuredBirthsSpec = MeasuredBirthsSpec {
    region: AdmissiblePresetSpec::Geosynchronous,
    velocity_sigma: 1.0,
    headings: Some(3),
    speeds: None,
    climbs: None,
    ranges: Some(1),
    expected_births: 1e-3,
    max_probability: 1e-2,
    min_unexplained: 0.5,
    lifetime: 1200.0,
    tracklets: None,
    link_waiting: true,
};

/// The name of the `optical-leo` simulation, whose settings are not its measurement kind's.
const OPTICAL_LEO: &str = "optical-leo";

/// `optical-leo`'s settings: a catalogue-quality prior (as the LEO radars'), the telescope's error bound
/// (10 km) and cut-off (20 km), births only from tracklets ([`OPTICAL_LEO_BIRTHS`]).
fn optical_leo_settings() -> Settings {
    let telescope = settings(Measurement3dSpec::Optical);
    Settings { births: OPTICAL_LEO_BIRTHS, evaluation: telescope.evaluation, ..settings(Measurement3dSpec::Radar) }
}

/// The birth pool `optical-leo` writes when objects are unknown to the prior: births only from 3-frame
/// tracklets (docs/maths.md §5.10) in the LEO region, no single-frame cells (`single_frame` false), 12 ln-range
/// × 4 range-rate cells (48, within the host profile's B = 64). A pass gives 5 to 15 frames 2 s apart, so a
/// tracklet spans 4 s (6 s with one frame missed); three frames fit exactly (no χ² test, docs/maths.md
/// §5.10), so only the rate and acceleration bounds of a LEO object seen from the ground above 20° elevation
/// test them (angular rate ≤ 2°/s, acceleration ≤ 0.05°/s², jerk ≤ 10⁻³ °/s³). Four frames confirmed
/// fewer births: a short pass ends before its track is confirmed (docs/results.md, "optical-leo"). Cells
/// live 5 s: the next frame, or the one after when the next misses.
pub const OPTICAL_LEO_BIRTHS: MeasuredBirthsSpec = MeasuredBirthsSpec {
    region: AdmissiblePresetSpec::Leo,
    velocity_sigma: 1.0,
    headings: None,
    speeds: None,
    climbs: None,
    ranges: None,
    expected_births: 1e-2,
    max_probability: 1e-2,
    min_unexplained: 0.5,
    lifetime: 5.0,
    tracklets: Some(TrackletSpec {
        frames: 3,
        max_span: 6.5,
        max_chi_squared: 13.8,
        max_rate_deg_s: 2.0,
        max_acceleration_deg_s2: 0.05,
        max_jerk_deg_s3: 1e-3,
        region: AdmissiblePresetSpec::Leo,
        cells: [12, 4],
        single_frame: false,
    }),
    link_waiting: false,
};

/// The name of the `optical-heo` simulation, whose births are not its measurement kind's.
const OPTICAL_HEO: &str = "optical-heo";

/// `optical-heo`'s settings: the telescope's prior, error bound and cut-off, births only from tracklets
/// ([`OPTICAL_HEO_BIRTHS`]).
fn optical_heo_settings() -> Settings {
    Settings { births: OPTICAL_HEO_BIRTHS, ..settings(Measurement3dSpec::Optical) }
}

/// The birth pool `optical-heo` writes: births only from 4-frame tracklets (docs/maths.md §5.10) in the region
/// of every bound orbit (`bound`: perigee ≥ R_E + 150 km, apogee ≤ 50,000 km, any inclination: GTO and
/// Molniya orbits), no single-frame cells, 12 ln-range × 4 range-rate cells. Frames come every 30 s, so 4
/// frames span 90 s (120 s with one missed); the fourth frame gives the fit a χ² test (2 degrees of freedom,
/// 18.5: 99.99 %). The preset's eccentric objects move at most 0.03°/s across the sky, and the second
/// differences of their angles stay below 4·10⁻⁵ °/s² (seeds 1–10, noise included). Cells live 65 s: the
/// next frame, or the one after.
/// Three frames, or 16 × 4 cells, confirmed fewer births on seeds 1 and 2 (docs/results.md, "optical-heo").
pub const OPTICAL_HEO_BIRTHS: MeasuredBirthsSpec = MeasuredBirthsSpec {
    region: AdmissiblePresetSpec::Bound,
    velocity_sigma: 1.0,
    headings: None,
    speeds: None,
    climbs: None,
    ranges: None,
    expected_births: 1e-2,
    max_probability: 1e-2,
    min_unexplained: 0.5,
    lifetime: 65.0,
    tracklets: Some(TrackletSpec {
        frames: 4,
        max_span: 125.0,
        max_chi_squared: 18.5,
        max_rate_deg_s: 0.1,
        max_acceleration_deg_s2: 1e-4,
        max_jerk_deg_s3: 1e-6,
        region: AdmissiblePresetSpec::Bound,
        cells: [12, 4],
        single_frame: false,
    }),
    link_waiting: false,
};

/// Figures of a generated file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Generated {
    /// Objects.
    pub objects: usize,
    /// Scans.
    pub scans: usize,
    /// Measurements over all scans.
    pub measurements: usize,
    /// Most measurements in one scan.
    pub max_measurements: usize,
    /// Measurements dropped because they fell outside the field of view (noisy detections at its edge).
    pub dropped_outside: usize,
}

/// The generated scenarios' `motion.max_substeps`: with 20 s sub-steps, gaps of up to 48 h.
pub const MAX_SUBSTEPS: u32 = 8640;

/// How a catalogue's trackers keep their hypotheses (`run-catalogue`, `generate catalogue`, the catalogue
/// at scale): the H∞ heaviest children within nine decades of the heaviest (docs/maths.md §8.1). Without
/// the floor each observed object's cluster fills H∞ with versions of it that missed one scan (in the
/// catalogue experiment most of them between 10⁻¹² and 10⁻⁹ of the heaviest), and every version is a track
/// predicted at every scan
/// (docs/performance.md, "A floor under the hypotheses' weights").
pub const CATALOGUE_SELECTION: SelectionSpec = SelectionSpec::TopWeightWithin { decades: 9 };

/// The catalogue scenarios' track loss (`tracker.lost_after_unseen_scans`, docs/maths.md §5.9) where the
/// sensors' own preset sets none, but for a telescope alone (it misses the objects in the Earth's shadow,
/// which its field of view counts as in view): a track in view of 8 scans in a row with no measurement in
/// its gate has left its object (p_D 0.9: a track on its object misses 8 in a row with probability 10⁻⁸).
/// Without it a track that a long prediction between passes has carried away from its object stays in
/// every hypothesis while the object is born again under a second label, and the scoring alternates
/// between the two (docs/performance.md, "Tracks lost between passes").
pub const CATALOGUE_TRACK_LOSS: Option<core::num::NonZeroU16> = core::num::NonZeroU16::new(8);

/// The version 2 scenario of a simulation.
///
/// # Errors
/// [`Error::Internal`] when the sensors mix measurement types, or truth propagation fails.
pub fn to_scenario(sim: &SsaScenario) -> Result<(Scenario3d, Generated), Error> {
    to_scenario_with(sim, None)
}

/// Truth the caller computes: `state(object, time)` (inertial km, km/s at `time` s since the epoch), named
/// `source` in the file's description.
pub struct KnownTruth<'a> {
    /// The state of object `i` at time `t`.
    pub state: &'a dyn Fn(usize, f64) -> Result<[f64; 6], Error>,
    /// How the truth was computed, e.g. "SGP4".
    pub source: &'a str,
}

/// A generated scenario's description: what made it, its objects, sensors and `scans`, the truth's `source`.
pub fn description(sim: &SsaScenario, scans: usize, source: &str) -> String {
    format!(
        "host-sim generate {} --seed {}: {} objects ({} unknown to the prior), {} sensors, {scans} scans; truth by \
         {source}",
        sim.name,
        sim.seed,
        sim.objects.len(),
        sim.objects.iter().filter(|o| !o.in_prior).count(),
        sim.sensors.len(),
    )
}

/// As [`to_scenario`], the truth and the prior means from `known` instead of the RKF7(8) integrator.
///
/// # Errors
/// As [`to_scenario`], and `known`'s errors.
pub fn to_scenario_with(sim: &SsaScenario, known: Option<KnownTruth<'_>>) -> Result<(Scenario3d, Generated), Error> {
    let kinds: Vec<Measurement3dSpec> = sim.sensors.iter().map(|s| file_kind(s.kind)).collect();
    let first = *kinds.first().ok_or_else(|| Error::internal("simulation has no sensor"))?;
    let measurement = if kinds.iter().all(|k| *k == first) { first } else { Measurement3dSpec::Network };
    let settings = match sim.name.as_str() {
        OPTICAL_LEO => optical_leo_settings(),
        OPTICAL_HEO => optical_heo_settings(),
        _ => settings(measurement),
    };
    let unknown = sim.objects.iter().any(|o| !o.in_prior);
    let mut sensors: Vec<Sensor3dSpec> = sim.sensors.iter().map(sensor_spec).collect();
    if measurement == Measurement3dSpec::Network {
        for (sensor, kind) in sensors.iter_mut().zip(&kinds) {
            sensor.kind = Some(*kind);
            sensor.birth_region = unknown.then(|| network_birth_region(*kind)).flatten();
        }
    }

    let times: Vec<f64> = sim.scans.iter().map(|s| s.time).collect();
    let mut truth_scans = truth_at(sim, &times, known.as_ref())?;
    // The prior holds 1 s before the first scan (a scan must come after it).
    let prior_time = times.first().map_or(0.0, |&t| t.min(0.0)) - 1.0;
    let objects = prior_objects(sim, &settings, prior_time, known.as_ref())?;

    let mut scenario = Scenario3d {
        format: FORMAT_V2.into(),
        version: 2,
        name: sim.name.clone(),
        description: description(sim, sim.scans.len(), known.as_ref().map_or("RKF7(8) two-body + J2", |k| k.source)),
        epoch: EpochSpec { utc: Some(sim.epoch.clone()), julian_date: Some(sim.epoch_jd) },
        motion: Motion3dSpec::TwoBodyJ2 {
            process_noise: ProcessNoiseSpec::Isotropic { q: settings.q },
            max_step: 20.0,
            // 20 s × 8640 = 172 800 s: gaps of up to 48 h between scans (issue 29); a prediction costs
            // ⌈gap / 20 s⌉ RK4 sub-steps, so ordinary gaps cost what they did.
            max_substeps: MAX_SUBSTEPS,
        },
        measurement,
        sensors,
        // Objects unknown to the prior: births from the measurements (docs/maths.md §5.8).
        birth: Birth3dSpec {
            probability: 0.0,
            detection: BirthDetectionSpec::AllDetected,
            events: if unknown { BirthEventsSpec::Independent } else { BirthEventsSpec::FirstOrder },
            measured: unknown.then_some(settings.births),
            cells: vec![],
        },
        death_probability: 0.0,
        tracker: TrackerSpec {
            gate: Some(25.0),
            max_children_per_scan: 2_000_000,
            store_overflow: StoreOverflowSpec::PruneChildren,
            numerical_failure: NumericalFailureSpec::DropTrack,
            lost_after_unseen_scans: settings.lost_after_unseen_scans,
            seed: sim.seed,
            sampler: SamplerSpec::default(),
            selection: SelectionSpec::default(),
        },
        prior: Prior3dSpec { time: prior_time, hypotheses: vec![PriorHypothesis3dSpec { weight: 1.0, objects }] },
        scans: vec![],
        truth: None,
        evaluation: settings.evaluation,
    };

    let (scans, dropped_outside) = scans_in_view(sim, &scenario, &mut truth_scans)?;
    scenario.scans = scans;
    scenario.truth = Some(Truth3dSpec {
        objects: (0..sim.objects.len())
            .map(|i| TruthObjectSpec {
                id: i as u64,
                in_prior: sim.objects[i].in_prior,
                birth_time: sim.objects[i].birth_time,
                death_time: None,
            })
            .collect(),
        scans: truth_scans,
    });
    let figures = Generated {
        objects: sim.objects.len(),
        scans: scenario.scans.len(),
        measurements: scenario.scans.iter().map(|s| s.measurements.len()).sum(),
        max_measurements: scenario.max_measurements(),
        dropped_outside,
    };
    // The file must load: check it as `run` will.
    scenario.validate().map_err(|e| Error::internal(format!("generated scenario: {e}")))?;
    Ok((scenario, figures))
}

/// Every object at every scan time `times`: from `known`, or RKF7(8) step by step from the epoch.
fn truth_at(sim: &SsaScenario, times: &[f64], known: Option<&KnownTruth<'_>>) -> Result<Vec<TruthScan3dSpec>, Error> {
    let mut truth_scans: Vec<TruthScan3dSpec> =
        times.iter().map(|_| TruthScan3dSpec { objects: vec![], origins: None }).collect();
    for (i, object) in sim.objects.iter().enumerate() {
        let mut state = object.initial_state;
        let mut t = 0.0;
        for (k, &time) in times.iter().enumerate() {
            state = match known {
                Some(known) => (known.state)(i, time)?,
                None => Propagator::EARTH
                    .propagate(state, time - t)
                    .map_err(|e| Error::internal(format!("truth propagation of object {i}: {e}")))?,
            };
            t = time;
            if object.exists_at(time) {
                truth_scans[k].objects.push(TruthState3dSpec { id: i as u64, state });
            }
        }
    }

    Ok(truth_scans)
}

/// The prior objects at `prior_time`: the true state (from `known`, or propagated) plus a draw of the
/// prior's error.
fn prior_objects(
    sim: &SsaScenario,
    settings: &Settings,
    prior_time: f64,
    known: Option<&KnownTruth<'_>>,
) -> Result<Vec<PriorObject3dSpec>, Error> {
    let prior_covariance = SMatrix::<f64, 6, 6>::from_diagonal(&nalgebra::SVector::from([
        settings.position_sigma.powi(2),
        settings.position_sigma.powi(2),
        settings.position_sigma.powi(2),
        settings.velocity_sigma.powi(2),
        settings.velocity_sigma.powi(2),
        settings.velocity_sigma.powi(2),
    ]));
    let covariance: [[f64; 6]; 6] = core::array::from_fn(|i| core::array::from_fn(|j| prior_covariance[(i, j)]));
    let mut objects = Vec::with_capacity(sim.objects.len());
    for (i, o) in sim.objects.iter().enumerate().filter(|(_, o)| o.in_prior) {
        let state = match known {
            Some(known) => (known.state)(i, prior_time)?,
            None => Propagator::EARTH
                .propagate(o.initial_state, prior_time)
                .map_err(|e| Error::internal(format!("prior propagation of object {i}: {e}")))?,
        };
        let error = Random::stream(sim.seed, Stream::Prior, i as u64).gaussian(&prior_covariance);
        objects.push(PriorObject3dSpec {
            label: i as u32,
            mean: core::array::from_fn(|j| state[j] + error[j]),
            covariance,
        });
    }

    Ok(objects)
}

/// The scans of the file: measurements in degrees, detections outside the field of view dropped (their
/// count returned); each scan's truth origins recorded in `truth_scans`.
fn scans_in_view(
    sim: &SsaScenario,
    scenario: &Scenario3d,
    truth_scans: &mut [TruthScan3dSpec],
) -> Result<(Vec<Scan3dSpec>, usize), Error> {
    // Scans: measurements in degrees, detections outside the field of view dropped.
    let check = FieldOfViewCheck::new(scenario)?;
    let mut dropped_outside = 0;
    let mut scans = Vec::with_capacity(sim.scans.len());
    for (k, scan) in sim.scans.iter().enumerate() {
        let origin_of: Vec<Option<u64>> = (0..scan.measurements.len())
            .map(|j| scan.truth.iter().find(|t| t.measurement == Some(j)).map(|t| t.object as u64))
            .collect();
        let mut measurements = vec![];
        let mut origins = vec![];
        let measurement = scenario.kind(scan.sensor);
        for (z, origin) in scan.measurements.iter().zip(origin_of) {
            let in_file: Vec<f64> =
                z.iter().enumerate().map(|(i, &v)| if measurement.is_angle(i) { v.to_degrees() } else { v }).collect();
            // The test the tracker applies, to the value it will read back from the file.
            let read_back = measurements_in_radians(measurement, std::slice::from_ref(&in_file));
            if !check.sees(scan.sensor, scan.time, &read_back[0]) {
                dropped_outside += 1;
                continue;
            }
            measurements.push(in_file);
            origins.push(origin);
        }
        truth_scans[k].origins = Some(origins);
        scans.push(Scan3dSpec { time: scan.time, sensor: scan.sensor, measurements });
    }
    Ok((scans, dropped_outside))
}

/// Degrees of a configuration angle, rounded to 1e-9° (≈ 2e-11 rad) so that 15° reads 15, not 14.999999999999998.
fn degrees(rad: f64) -> f64 {
    (rad.to_degrees() * 1e9).round() / 1e9
}

/// The file form of a simulator's sensor.
pub fn sensor_spec(sensor: &sensor::SensorSpec) -> Sensor3dSpec {
    let arcsec = |rad: f64| (rad.to_degrees() * 3600.0 * 1e9).round() / 1e9;
    let noise = match sensor.kind {
        SensorKind::Radar => NoiseSpec {
            range_km: Some(sensor.sigma[0]),
            azimuth_arcsec: Some(arcsec(sensor.sigma[1])),
            elevation_arcsec: Some(arcsec(sensor.sigma[2])),
            ..NoiseSpec::default()
        },
        SensorKind::RadarRangeRate { .. } => NoiseSpec {
            range_km: Some(sensor.sigma[0]),
            azimuth_arcsec: Some(arcsec(sensor.sigma[1])),
            elevation_arcsec: Some(arcsec(sensor.sigma[2])),
            range_rate_km_s: Some(sensor.sigma[3]),
            ..NoiseSpec::default()
        },
        SensorKind::Optical => NoiseSpec {
            right_ascension_arcsec: Some(arcsec(sensor.sigma[0])),
            declination_arcsec: Some(arcsec(sensor.sigma[1])),
            ..NoiseSpec::default()
        },
        SensorKind::AzEl => NoiseSpec {
            azimuth_arcsec: Some(arcsec(sensor.sigma[0])),
            elevation_arcsec: Some(arcsec(sensor.sigma[1])),
            ..NoiseSpec::default()
        },
        SensorKind::Range => NoiseSpec { range_km: Some(sensor.sigma[0]), ..NoiseSpec::default() },
        SensorKind::RangeRangeRate { .. } => NoiseSpec {
            range_km: Some(sensor.sigma[0]),
            range_rate_km_s: Some(sensor.sigma[1]),
            ..NoiseSpec::default()
        },
    };
    let shape = match sensor.fov.shape {
        field_of_view::LookShape::Cone { azimuth, elevation, half_angle } => ShapeSpec::Cone {
            azimuth_deg: degrees(azimuth),
            elevation_deg: degrees(elevation),
            half_angle_deg: degrees(half_angle),
        },
        field_of_view::LookShape::Box { azimuth_centre, azimuth_half_width, elevation_min, elevation_max } => {
            ShapeSpec::Box {
                azimuth_deg: degrees(azimuth_centre),
                half_width_deg: degrees(azimuth_half_width).min(180.0),
                elevation_deg: [degrees(elevation_min), degrees(elevation_max).min(90.0)],
            }
        }
    };
    Sensor3dSpec {
        name: sensor.name.clone(),
        kind: None,
        birth_region: None,
        site: SiteSpec {
            latitude_deg: degrees(sensor.site.latitude),
            longitude_deg: degrees(sensor.site.longitude),
            height_km: sensor.site.height,
        },
        noise,
        field_of_view: FieldOfView3dSpec {
            shape,
            min_elevation_deg: degrees(sensor.fov.min_elevation),
            range_km: sensor.fov.range,
            range_rate_km_s: match sensor.kind {
                SensorKind::RadarRangeRate { max_range_rate } | SensorKind::RangeRangeRate { max_range_rate } => {
                    Some([-max_range_rate, max_range_rate])
                }
                _ => None,
            },
        },
        detection_probability: sensor.detection_probability,
        clutter_rate: sensor.clutter_rate,
        bias: None,
        light_time: None,
        refraction: None,
    }
}
