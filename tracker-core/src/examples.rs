//! The set-up the documentation's examples share (hidden from the docs; not part of the API): one small
//! constant-velocity tracker configuration, one object and a two-hypothesis prior, so that each example
//! shows only what it is about.

use crate::config::BirthModel;
use crate::gaussian::Gaussian;
use crate::model::{ConstantVelocity, PositionMeasurement};
use crate::sensor::{Region, Sensor};
use crate::store::TrackLabel;
use crate::tracker::{PriorHypothesis, PriorObject};
use crate::{ConfigError, LinearConfig, LinearTracker};
use nalgebra::{SMatrix, SVector};

/// The examples' tracker: constant velocity, position measurements, H = 8, N = 4, Z = 4, K = 16, one birth
/// cell.
pub type Example = LinearTracker<f64, 8, 4, 4, 16, 1>;

/// The examples' configuration: p_D 0.9, one clutter return per scan over a 100 × 100 square centred on
/// the origin, no births, no deaths, no gate, seed 1.
pub fn config() -> LinearConfig<f64, 1> {
    crate::Config {
        motion: ConstantVelocity { acceleration_noise: 0.01 },
        measurement: PositionMeasurement::isotropic(0.5),
        sensor: Sensor {
            detection_probability: 0.9,
            clutter_rate: 1.0,
            field_of_view: Region::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] },
        },
        birth: BirthModel::none(),
        death_probability: 0.0,
        gate: None,
        children: Default::default(),
        selection: Default::default(),
        store_overflow: Default::default(),
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 1,
    }
}

/// An object at the origin moving along +x at unit speed, with unit covariance.
pub fn object() -> Gaussian<f64, 4> {
    Gaussian { mean: SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() }
}

/// A tracker of [`config`] whose prior has two hypotheses: object 7 ([`object`]) exists with probability
/// 3/4.
///
/// # Errors
/// None in practice; [`ConfigError`] if the configuration were invalid.
pub fn two_hypotheses() -> Result<Example, ConfigError> {
    let objects = [PriorObject { label: TrackLabel(7), state: object() }];
    let prior = [PriorHypothesis { weight: 3.0, objects: &objects }, PriorHypothesis { weight: 1.0, objects: &[] }];
    Example::new(config(), &prior, 0.0)
}
