//! From a planar scenario to tracker-core values: models, sensor, birth model, configuration and prior
//! (the conversions every world shares are [`crate::pipeline::settings`]).

use crate::pipeline::settings;
use crate::pipeline::tracker::TrackerKind;
use crate::scenario::*;
use nalgebra::{SMatrix, SVector};
use tracker_core::{
    BirthModel, ChildGeneration, Config, ConstantVelocity, Gaussian, PositionMeasurement, PriorObject, Region, Sensor,
    TwoBody,
};

/// The core's region for a field-of-view spec.
pub fn region(spec: &FieldOfViewSpec) -> Region<f64> {
    match *spec {
        FieldOfViewSpec::Sector { origin, look_direction_deg, field_of_view_deg, max_range } => Region::Sector {
            origin,
            look_direction: look_direction_deg.to_radians(),
            half_angle: field_of_view_deg.to_radians() / 2.0,
            max_range,
        },
        FieldOfViewSpec::Rectangle { min, max } => Region::Rectangle { min, max },
        FieldOfViewSpec::Everywhere { volume } => Region::Everywhere { volume },
    }
}

/// The core's sensor.
pub fn sensor(spec: &SensorSpec) -> Sensor<f64> {
    Sensor {
        detection_probability: spec.detection_probability,
        clutter_rate: spec.clutter_rate,
        field_of_view: region(&spec.field_of_view),
    }
}

/// A Gaussian from mean and covariance arrays.
pub fn gaussian(mean: &[f64; 4], covariance: &[[f64; 4]; 4]) -> Gaussian<f64, 4> {
    settings::gaussian(mean, covariance)
}

/// The measurement model.
pub fn measurement(spec: &MeasurementSpec) -> PositionMeasurement<f64> {
    let MeasurementSpec::Position { noise_covariance } = spec;
    PositionMeasurement { noise: SMatrix::<f64, 2, 2>::from_fn(|i, j| noise_covariance[i][j]) }
}

/// The two-body model of a two-body scenario.
pub fn two_body(spec: &MotionSpec) -> Option<TwoBody<f64>> {
    match *spec {
        MotionSpec::TwoBody { mu, acceleration_noise, max_step, max_substeps } => {
            Some(TwoBody { mu, acceleration_noise, max_step, max_substeps, min_radius: TwoBody::DEFAULT_MIN_RADIUS })
        }
        MotionSpec::ConstantVelocity { .. } => None,
    }
}

/// The constant-velocity model of a constant-velocity scenario.
pub fn constant_velocity(spec: &MotionSpec) -> Option<ConstantVelocity<f64>> {
    match *spec {
        MotionSpec::ConstantVelocity { acceleration_noise } => Some(ConstantVelocity { acceleration_noise }),
        MotionSpec::TwoBody { .. } => None,
    }
}

/// The tracker configuration of a scenario with motion model `motion` and at most `B` birth cells.
///
/// # Errors
/// A one-line message when the scenario has more birth cells than `B`.
pub fn config<M, const B: usize>(
    scenario: &Scenario,
    motion: M,
    children: ChildGeneration,
) -> Result<Config<f64, M, PositionMeasurement<f64>, 4, B>, ScenarioError> {
    let cells =
        settings::birth_cells(scenario.birth.cells.iter().map(|c| (&c.mean, &c.covariance)), "this tracker's capacity")
            .map_err(ScenarioError)?;
    let (selection, store_overflow, numerical_failure, track_loss) = settings::policies(&scenario.tracker);
    Ok(Config {
        motion,
        measurement: measurement(&scenario.measurement),
        sensor: sensor(&scenario.sensor),
        birth: BirthModel {
            events: scenario.birth.events.core(),
            measured: scenario.birth.measured.as_ref().map(|m| m.core()),
            probability: scenario.birth.probability,
            cells,
            detection: settings::birth_detection(scenario.birth.detection),
        },
        death_probability: scenario.death_probability,
        gate: scenario.tracker.gate,
        children,
        selection,
        store_overflow,
        numerical_failure,
        track_loss,
        seed: scenario.tracker.seed,
    })
}

/// The exhaustive child generation a scenario asks for.
pub fn exhaustive(scenario: &Scenario) -> ChildGeneration {
    settings::children(TrackerKind::Homht, &scenario.tracker)
}

/// The R-FISST child generation a scenario asks for.
pub fn sampled(scenario: &Scenario) -> ChildGeneration {
    settings::children(TrackerKind::Rfisst, &scenario.tracker)
}

/// The sampler settings a scenario asks for (`tracker.sampler`).
pub fn sampler_config(scenario: &Scenario) -> tracker_core::sampler::SamplerConfig {
    settings::sampler_config(&scenario.tracker)
}

/// The prior hypotheses as (weight, objects).
pub fn prior(scenario: &Scenario) -> Vec<(f64, Vec<PriorObject<f64, 4>>)> {
    settings::prior(
        scenario
            .prior
            .hypotheses
            .iter()
            .map(|h| (h.weight, h.objects.iter().map(|o| (o.label, &o.mean, &o.covariance)))),
    )
}

/// The scan's measurements as vectors.
pub fn measurements(scan: &ScanSpec) -> Vec<SVector<f64, 2>> {
    scan.measurements.iter().map(|z| SVector::from(*z)).collect()
}
