//! Motion and measurement models: what the EKF needs to know about how one object moves and how a
//! sensor measures it.
//!
//! A [`MotionModel`] propagates a state over a time step and returns the state transition matrix (the
//! Jacobian of the propagation, Φ) and the process noise Q. A measurement model is three traits, one per
//! job: [`Measure`] (the predicted measurement h(x), its Jacobian H, the noise covariance R and the
//! residual), [`Placement`] (its sensor or sensors, placed at each scan; in [`crate::sensor`]) and
//! [`BirthGeometry`] (the birth density from one measurement); [`MeasurementModel`] is the three together,
//! the tracker's bound. All are pure: the same inputs give the same bits, and a failure is a value.
//!
//! Built in:
//! - [`ConstantVelocity`]: 2-D constant velocity, linear, for exactness tests and cross-checks.
//! - [`TwoBody`]: planar Keplerian gravity, state and transition matrix integrated together by a
//!   fixed-step RK4 with a bounded number of sub-steps.
//! - [`TwoBodyJ2`]: 3-D two-body + J2 (Earth oblateness) in an Earth-centred inertial frame, with
//!   the analytic gravity gradient in the variational equations and RIC-frame process noise.
//! - [`PositionMeasurement`]: the position (x, y) of a planar state with Gaussian noise.
//! - [`RadarRangeAzEl`], [`RadarRangeRate`], [`OpticalRaDec`]: range, azimuth, elevation (and range-rate)
//!   from a ground site, topocentric right ascension and declination, of a 3-D inertial state; with the
//!   site geometry of [`crate::sensor::frames`]; their residuals wrap angles
//!   ([`wrap_angle`](crate::sensor::wrap_angle)).
//! - [`AdmissibleRegion`], [`BirthGeometry::birth_components`]: the birth density of a new object
//!   from one measurement, a weighted Gaussian mixture over its admissible states.
//! - [`SensorNetwork`]: up to `C` sensors of one of those types on ground sites or spacecraft, each a
//!   [`SiteSensor`](crate::sensor::SiteSensor) with its own noise, field of view, p_D and clutter, placed at
//!   every scan ([`ScanGeometry`](crate::sensor::ScanGeometry)).
//! - [`LightTime`] ([`light_time`]): a [`SensorNetwork`] sensor's measurements of the object at the signal's
//!   emission or bounce time (opt-in per sensor, [`SensorNetwork::with_light_time`]).
//! - [`MixedNetwork`]: up to `C` sensors of mixed kinds ([`SensorKind`]: radar, radar with range-rate,
//!   right ascension and declination, azimuth and elevation only, range only, range and range-rate) in
//!   one tracker; each kind measures its own components, padded to the tracker's `D = 4`.

pub(crate) mod admissible;
mod constant_velocity;
pub mod light_time;
mod mixed;
mod network;
mod optical;
mod position;
mod radar;
mod two_body;
mod two_body_j2;

/// The Earth's equatorial radius, with the other Earth constants (it lives with the WGS-84 ellipsoid in
/// [`crate::sensor::frames`]).
pub use crate::sensor::EARTH_RADIUS;
pub use admissible::tracklet::{
    Attributable, LinkLimits, MAX_TRACKLET_FRAMES, SkyPoint, TrackletError, TrackletFrame, tracklet_births,
};
pub use admissible::{AdmissibleRegion, BirthComponent, BirthError, GEO_RADIUS, MAX_BIRTH_COMPONENTS};
pub use constant_velocity::ConstantVelocity;
pub use light_time::LightTime;
pub use mixed::{
    KindError, KindMeasurement, MIXED_DIMENSION, MixedLook, MixedNetwork, MixedSensor, SensorBirths, SensorKind,
};
pub use network::{Placeable, SensorNetwork};
pub use optical::OpticalRaDec;
pub use position::PositionMeasurement;
pub use radar::{RadarRangeAzEl, RadarRangeRate};
pub use two_body::TwoBody;
pub use two_body_j2::{EARTH_J2, EARTH_MIN_RADIUS, EARTH_MU, ProcessNoise, TwoBodyJ2};

use crate::real::Real;
use crate::sensor::Placement;
use nalgebra::{SMatrix, SVector};

/// Why a model could not produce a prediction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum ModelError {
    /// The time step needs more integrator sub-steps than the model allows.
    TimeStepTooLarge,
    /// The state is at a singularity of the model (for example at the centre of attraction).
    Singular,
    /// The propagation produced a NaN or an infinity.
    NonFinite,
    /// The object is (or passes) inside the central body: closer to the centre than the model's
    /// minimum radius.
    InsideBody,
    /// The integrator cannot follow the motion: a sub-step is too long for the local dynamics (a close
    /// approach to the centre of attraction), or the propagated state is absurd (its energy changed by
    /// more than the model allows).
    Unresolved,
}

impl core::fmt::Display for ModelError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            ModelError::TimeStepTooLarge => f.write_str("time step needs more integrator sub-steps than allowed"),
            ModelError::Singular => f.write_str("state at a singularity of the motion model"),
            ModelError::NonFinite => f.write_str("propagation produced a non-finite value"),
            ModelError::InsideBody => f.write_str("object inside the central body (closer than min_radius)"),
            ModelError::Unresolved => {
                f.write_str("integrator cannot follow the motion (close approach or absurd propagated state)")
            }
        }
    }
}

impl core::error::Error for ModelError {}

/// A propagated mean and the state transition matrix Φ = ∂x(t+dt)/∂x(t) at the prior mean.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Propagation<T: Real, const S: usize> {
    /// The propagated state.
    pub state: SVector<T, S>,
    /// The state transition matrix Φ, used for P⁻ = Φ P Φᵀ + Q.
    pub transition: SMatrix<T, S, S>,
}

/// How one object's state evolves between scans.
///
/// # Examples
/// A model of its own: a 1-D random walk, with the EKF.
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::model::{ModelError, MotionModel, Propagation};
/// use tracker_core::{Gaussian, ekf};
///
/// struct RandomWalk {
///     q: f64,
/// }
///
/// impl MotionModel<f64, 1> for RandomWalk {
///     fn propagate(&self, state: &SVector<f64, 1>, _dt: f64) -> Result<Propagation<f64, 1>, ModelError> {
///         Ok(Propagation { state: *state, transition: SMatrix::identity() })
///     }
///     fn process_noise(&self, _state: &SVector<f64, 1>, dt: f64) -> SMatrix<f64, 1, 1> {
///         SMatrix::from([[self.q * dt]])
///     }
///     fn validate(&self) -> Result<(), &'static str> {
///         if self.q > 0.0 { Ok(()) } else { Err("random walk: q must be > 0") }
///     }
/// }
///
/// let prior = Gaussian { mean: SVector::from([5.0]), covariance: SMatrix::from([[1.0]]) };
/// let predicted = ekf::predict(&RandomWalk { q: 0.5 }, &prior, 4.0)?;
/// assert_eq!((predicted.mean[0], predicted.covariance[(0, 0)]), (5.0, 3.0));
/// assert!(RandomWalk { q: 0.0 }.validate().is_err());
/// # Ok::<(), tracker_core::NumericalError>(())
/// ```
pub trait MotionModel<T: Real, const S: usize> {
    /// Propagates `state` forward by `dt` seconds (`dt > 0`) and returns the new state with the
    /// transition matrix Φ.
    ///
    /// # Errors
    /// A [`ModelError`] when the propagation cannot be done within the model's bounds.
    fn propagate(&self, state: &SVector<T, S>, dt: T) -> Result<Propagation<T, S>, ModelError>;

    /// The state [`Self::propagate`] gives, bit for bit, without the transition matrix: for a caller that
    /// needs only where the mean goes (the partitioned tracker's coasting clusters, docs/maths.md §13.2).
    /// The default calls [`Self::propagate`]; a model whose Φ costs more than its state overrides it.
    ///
    /// # Errors
    /// A [`ModelError`] when the propagation of the state alone cannot be done within the model's bounds
    /// (where [`Self::propagate`] fails on Φ alone, this may succeed).
    fn propagate_mean(&self, state: &SVector<T, S>, dt: T) -> Result<SVector<T, S>, ModelError> {
        self.propagate(state, dt).map(|p| p.state)
    }

    /// The process noise covariance Q accumulated over `dt` seconds from `state`.
    fn process_noise(&self, state: &SVector<T, S>, dt: T) -> SMatrix<T, S, S>;

    /// Checks the model's parameters; called once when a tracker is built.
    ///
    /// # Errors
    /// A static description of the first invalid parameter.
    fn validate(&self) -> Result<(), &'static str>;

    /// The longest time step (s) one prediction can bridge, `None` when any finite step can. A scan
    /// further than this after the last one is refused before anything changes
    /// ([`StepError::TimeStepTooLong`](crate::StepError::TimeStepTooLong)).
    fn max_time_step(&self) -> Option<f64> {
        None
    }
}

/// How a sensor measures one object: the measurement function h, its Jacobian, the noise and the
/// residual. This is all the EKF ([`crate::ekf`]) needs.
///
/// # Examples
/// A model of its own: the x coordinate alone of a planar state.
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::model::Measure;
/// use tracker_core::{Gaussian, ekf};
///
/// struct XOnly;
///
/// impl Measure<f64, 4, 1> for XOnly {
///     fn measure(&self, state: &SVector<f64, 4>) -> SVector<f64, 1> {
///         SVector::from([state[0]])
///     }
///     fn jacobian(&self, _state: &SVector<f64, 4>) -> SMatrix<f64, 1, 4> {
///         SMatrix::from([[1.0], [0.0], [0.0], [0.0]])
///     }
///     fn noise_covariance(&self) -> SMatrix<f64, 1, 1> {
///         SMatrix::from([[1.0]])
///     }
/// }
///
/// let track = Gaussian { mean: SVector::from([2.0, 7.0, 0.0, 0.0]), covariance: SMatrix::identity() };
/// let innovation = ekf::innovation(&XOnly, &track)?;
/// let updated = ekf::update(&XOnly, &track, &innovation, &SVector::from([4.0]))?;
/// assert_eq!(updated.mean, SVector::from([3.0, 7.0, 0.0, 0.0])); // gain 1/2 on x, y untouched
/// # Ok::<(), tracker_core::NumericalError>(())
/// ```
pub trait Measure<T: Real, const S: usize, const D: usize> {
    /// The noise-free measurement h(x).
    fn measure(&self, state: &SVector<T, S>) -> SVector<T, D>;

    /// The Jacobian H = ∂h/∂x at `state`.
    fn jacobian(&self, state: &SVector<T, S>) -> SMatrix<T, D, S>;

    /// The measurement noise covariance R (symmetric positive definite).
    fn noise_covariance(&self) -> SMatrix<T, D, D>;

    /// The residual ν = z − ẑ that every innovation, gate and score uses; models with angles wrap them
    /// into (−π, π] ([`wrap_angle`](crate::sensor::wrap_angle)). The default is the plain difference.
    fn residual(&self, z: &SVector<T, D>, predicted: &SVector<T, D>) -> SVector<T, D> {
        z - predicted
    }

    /// How many components this model measures: `D`, or fewer for a model of a network of mixed kinds
    /// ([`MixedLook`]) whose measurements fill the first components and pad the rest (docs/maths.md
    /// §6.10). The Gaussian's normaliser (2π)^(−d/2) uses it.
    fn dimension(&self) -> usize {
        D
    }

    /// The look direction of `state` from the sensor, when the field of view must be read from the state
    /// rather than from its predicted measurement (a sensor that measures no angles). The default,
    /// `None`, reads the field of view through the predicted measurement.
    fn look_of_state(&self, _state: &SVector<T, S>) -> Option<crate::sensor::Look<T>> {
        None
    }
}

/// Where a new object may be, given one measurement: the birth geometry of a measurement kind.
pub trait BirthGeometry<T: Real, const S: usize, const D: usize> {
    /// The birth density of a new object seen by measurement `z` at the current placement: a weighted
    /// Gaussian mixture over the states of `region` that explain `z` (docs/maths.md §5.7), written to
    /// `out`; returns how many components were written (their weights sum to 1). At most
    /// [`AdmissibleRegion::max_components`] are written. The default has no birth geometry.
    ///
    /// # Errors
    /// [`BirthError::Unsupported`] without a birth geometry, [`BirthError::InvalidRegion`],
    /// [`BirthError::Degenerate`] when no admissible state explains `z`, [`BirthError::NonFinite`],
    /// [`BirthError::TooManyComponents`] when `out` is too short (its contents are then unspecified).
    fn birth_components(
        &self,
        _z: &SVector<T, D>,
        _region: &AdmissibleRegion<T>,
        _out: &mut [BirthComponent<T, S>],
    ) -> Result<usize, BirthError> {
        Err(BirthError::Unsupported)
    }

    /// Measurement `z` at the current placement as a direction on the sky, for tracklet births
    /// (docs/maths.md §5.10). The default, `None`, is for kinds that measure no direction.
    fn sky_point(&self, _z: &SVector<T, D>) -> Option<SkyPoint<T>> {
        None
    }

    /// The birth density of a tracklet's `attributable` seen from `observer` (docs/maths.md §5.10), written
    /// to `out` as [`tracklet_births`] does; the default has none.
    ///
    /// # Errors
    /// [`BirthError::Unsupported`] by default; else as [`tracklet_births`].
    fn tracklet_components(
        &self,
        _attributable: &Attributable<T>,
        _observer: &[T; 6],
        _settings: &crate::pool::TrackletBirths<T>,
        _out: &mut [BirthComponent<T, S>],
    ) -> Result<usize, BirthError> {
        Err(BirthError::Unsupported)
    }
}

/// Everything a tracker needs of its measurement model: how it measures ([`Measure`]), its sensor(s)
/// placed at each scan ([`Placement`]) and its birth geometry ([`BirthGeometry`]). Implemented for every
/// type that has the three; a model without sensors of its own or birth geometry takes the defaults
/// with empty `impl`s.
///
/// # Examples
/// The x coordinate alone of a planar state, as a tracker's measurement model.
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::model::{BirthGeometry, Measure, MeasurementModel};
/// use tracker_core::sensor::{Placement, ScanGeometry};
///
/// #[derive(Clone)]
/// struct XOnly;
///
/// impl Measure<f64, 4, 1> for XOnly {
///     fn measure(&self, state: &SVector<f64, 4>) -> SVector<f64, 1> {
///         SVector::from([state[0]])
///     }
///     fn jacobian(&self, _state: &SVector<f64, 4>) -> SMatrix<f64, 1, 4> {
///         SMatrix::from([[1.0], [0.0], [0.0], [0.0]])
///     }
///     fn noise_covariance(&self) -> SMatrix<f64, 1, 1> {
///         SMatrix::from([[1.0]])
///     }
/// }
/// impl Placement<f64, 1> for XOnly {} // one sensor, no sensor frame
/// impl BirthGeometry<f64, 4, 1> for XOnly {} // no birth geometry
///
/// fn sensors<G: MeasurementModel<f64, 4, 1>>(model: &G) -> usize {
///     model.sensor_count()
/// }
/// assert_eq!(sensors(&XOnly), 1);
/// assert!(XOnly.place(&ScanGeometry { sensor: 1, time: 0.0, observer: None }).is_err());
/// ```
pub trait MeasurementModel<T: Real, const S: usize, const D: usize>:
    Measure<T, S, D> + Placement<T, D> + BirthGeometry<T, S, D>
{
}

impl<T: Real, G, const S: usize, const D: usize> MeasurementModel<T, S, D> for G where
    G: Measure<T, S, D> + Placement<T, D> + BirthGeometry<T, S, D>
{
}

/// The covariance of white acceleration noise of spectral density `q` over `dt` for a planar
/// position-velocity state (x, y, vx, vy):
/// Q = q [[dt³/3 I, dt²/2 I], [dt²/2 I, dt I]].
pub(crate) fn white_acceleration_noise<T: Real>(q: T, dt: T) -> SMatrix<T, 4, 4> {
    let dt2 = dt * dt;
    let pp = q * dt2 * dt / crate::real::c(3.0);
    let pv = q * dt2 / crate::real::c(2.0);
    let vv = q * dt;
    let mut noise = SMatrix::<T, 4, 4>::zeros();
    for axis in 0..2 {
        noise[(axis, axis)] = pp;
        noise[(axis, axis + 2)] = pv;
        noise[(axis + 2, axis)] = pv;
        noise[(axis + 2, axis + 2)] = vv;
    }
    noise
}

/// The largest accepted `max_substeps` of the integrated models: 10⁶ RK4 sub-steps per prediction, so that
/// no configuration makes one prediction (and so one scan) endless (issue 17).
pub const MAX_RK4_SUBSTEPS: u32 = 1_000_000;

/// The fixed-step RK4 split of a step `dt`: n = ⌈dt / `max_step`⌉ equal sub-steps (at least one) and their
/// length h = dt / n.
///
/// # Errors
/// [`ModelError::NonFinite`] for a negative or non-finite ratio, [`ModelError::TimeStepTooLarge`] when n
/// exceeds `max_substeps` (which bounds the cost of one prediction).
pub(crate) fn rk4_substeps<T: Real>(dt: T, max_step: T, max_substeps: u32) -> Result<(u32, T), ModelError> {
    let ratio = dt / max_step;
    if !ratio.is_finite_value() || ratio < T::zero() {
        return Err(ModelError::NonFinite);
    }
    let steps_real = -crate::real::floor(-ratio);
    if steps_real > T::of_f64(f64::from(max_substeps)) {
        return Err(ModelError::TimeStepTooLarge);
    }
    let steps = (steps_real.as_f64() as u32).max(1);
    Ok((steps, dt / T::of_f64(f64::from(steps))))
}
