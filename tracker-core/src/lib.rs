//! # tracker-core: hypothesis-level FISST (R-FISST) in fixed memory
//!
//! A multi-object tracker that keeps many data association hypotheses at once, with birth and death, in
//! memory fixed at compile time and with a bounded cost per scan. `#![no_std]`, no `alloc`, no `unsafe`.
//! The maths is written out in the repository's `docs/maths.md`, with numbered sections that comments
//! cite as "docs/maths.md §n"; [000]–[004] are the papers listed there ([000] = Chakravorty et al., the
//! FISST form used here).
//!
//! ## Layers
//!
//! - **Estimation** ([`gaussian`], [`model`], [`ekf`]): each object under each hypothesis is a
//!   [`Gaussian`], predicted and updated by an EKF (Joseph form, Cholesky-factored innovation covariance).
//!   A measurement model is three traits: how it measures ([`Measure`]), its sensors placed at each scan
//!   ([`Placement`]) and its birth geometry ([`BirthGeometry`]); [`MeasurementModel`] is the three.
//! - **Sensor** ([`sensor`]): the one home of a sensor: where it is (a ground site or a spacecraft, placed
//!   at each scan), its field of view (p_D inside, 0 outside) and its Poisson clutter of intensity λ_C over
//!   it. The sensor module imports no measurement model.
//! - **Weights** ([`weight`], [`pool`]): the event probabilities and detection factors of one scan, and
//!   the birth cells made from measurements.
//! - **Association** ([`association`], [`children`], [`sampler`], [`optimal`], [`cluster`], [`selection`]):
//!   for each parent hypothesis and birth/death event, a data association matrix of log ratios δ_{z,o} and
//!   its column layout; a child generator offers the children (association vectors) with their exact
//!   log-weights to a sink that knows their (parent, event); the best H∞ are kept and the global
//!   log-sum-exp normalises them.
//! - **Hypotheses** ([`store`], [`hypothesis`], [`tracker`]): hypotheses hold indices into one track
//!   store shared by all of them, so a track with one history is stored, predicted and scored once.
//! - **Around them**: [`config`] and [`error`] (what a tracker is built from, and every typed failure),
//!   [`report`] (what one scan did), [`digest`] (a hash of the state, for bit-identity checks), [`real`]
//!   (the scalar type and its `libm` functions).
//!
//! ## The weight (docs/maths.md §4.1–§4.2, [000]'s FISST form)
//!
//! ```text
//! w̃_ij = w_i P(e) (1 − p_D)^{N'_F} λ_C^m Π_{(z,o)∈σ} p_D ĝ_{z,o} / ((1 − p_D) λ_C)
//! ```
//!
//! normalised by one log-sum-exp over all parents and all their children. P(e) is R-FISST's first-order
//! birth/death model: no event 1 − M_b α − M_d β, a birth in one of M_b cells α each, the death of one of
//! the M_d objects in the field of view β each. No 1/A_N(m) or (m choose k) k! factor is applied (docs/maths.md
//! §4.5: they are not normalised across cardinalities).
//!
//! ## Determinism
//!
//! The caller supplies time and the seed; the core reads no clock. Every transcendental function goes
//! through `libm` ([`real`]), so the host and a bare-metal target give the same bits.
#![cfg_attr(not(test), no_std)]
#![forbid(unsafe_code)]
#![deny(missing_docs)]
// `!(x > 0)` is deliberate throughout: unlike `x <= 0` it also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Index loops over parallel fixed-size arrays (rows, columns, slots) read closer to the maths.
#![allow(clippy::needless_range_loop)]

pub mod association;
pub mod children;
pub mod cluster;
pub mod config;
pub mod digest;
pub mod ekf;
pub mod error;
#[doc(hidden)]
pub mod examples;
pub mod gaussian;
pub mod hypothesis;
mod index;
pub mod model;
pub mod optimal;
pub mod partition;
pub mod pool;
mod random;
pub mod real;
pub mod report;
pub mod sampler;
pub mod selection;
pub mod sensor;
pub mod store;
pub mod tracker;
pub mod weight;

pub use config::{
    BirthDetection, BirthEvents, BirthModel, ChildGeneration, Config, NumericalFailure, StoreOverflow, TrackLoss,
};
pub use ekf::NumericalError;
pub use error::{ConfigError, StepError};
pub use gaussian::Gaussian;
pub use model::{
    BirthGeometry, ConstantVelocity, KindMeasurement, Measure, MeasurementModel, MixedNetwork, MixedSensor,
    MotionModel, OpticalRaDec, PositionMeasurement, RadarRangeAzEl, SensorKind, SensorNetwork, TwoBody, TwoBodyJ2,
};
pub use real::Real;
pub use report::StepReport;
pub use sensor::{Look, LookShape, Placement, Region, ScanGeometry, Sensor};
pub use store::{Track, TrackLabel};
pub use tracker::{HypothesisView, PriorHypothesis, PriorObject, PriorSource, Tracker, TrackerState};

/// The README's rust examples, compiled and run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../README.md")]
pub struct ReadmeDoctests;

/// Capacities of the default SSA (embedded) configuration: the 50-object scenario of paper 003 §IV.
pub mod ssa_caps {
    /// H∞: hypotheses kept per scan.
    pub const HYPOTHESES: usize = 32;
    /// N: objects per hypothesis (50 objects with room for births).
    pub const OBJECTS: usize = 64;
    /// Z: measurements per scan.
    pub const MEASUREMENTS: usize = 32;
    /// K: tracks in the shared store.
    pub const TRACKS: usize = 256;
    /// B: birth cells.
    pub const BIRTH_CELLS: usize = 8;
    /// K of the 3-D trackers: a 6-state track is 1.7 times a planar one, and 192 keeps a
    /// [`RadarTracker`](crate::RadarTracker) under 256 KiB in `f32` (`cargo run -p tracker-core --example sizes`).
    pub const TRACKS_3D: usize = 192;
    /// C: sensors of a [`RadarTracker`](crate::RadarTracker) or [`OpticalTracker`](crate::OpticalTracker).
    pub const SENSORS: usize = 4;
    /// C of a [`NetworkTracker`](crate::NetworkTracker): sensors of mixed kinds. Eight covers a regional
    /// network (two radars, two telescopes, an angles-only and a ranging station, and room for two more)
    /// at about 0.2 KiB per sensor; the host profile takes more (host-sim's `--profile host`).
    pub const NETWORK_SENSORS: usize = 8;
}

/// The default SSA tracker: planar two-body motion, position measurements, [`ssa_caps`] capacities.
pub type SsaTracker<T> = Tracker<
    T,
    TwoBody<T>,
    PositionMeasurement<T>,
    4,
    2,
    { ssa_caps::HYPOTHESES },
    { ssa_caps::OBJECTS },
    { ssa_caps::MEASUREMENTS },
    { ssa_caps::TRACKS },
    { ssa_caps::BIRTH_CELLS },
>;

/// The configuration type of [`SsaTracker`].
pub type SsaConfig<T> = Config<T, TwoBody<T>, PositionMeasurement<T>, 4, { ssa_caps::BIRTH_CELLS }>;

/// Up to [`ssa_caps::SENSORS`] radars measuring range, azimuth and elevation.
pub type RadarNetwork<T> = SensorNetwork<T, RadarRangeAzEl<T>, 3, { ssa_caps::SENSORS }>;

/// Up to [`ssa_caps::SENSORS`] telescopes measuring topocentric right ascension and declination.
pub type OpticalNetwork<T> = SensorNetwork<T, OpticalRaDec<T>, 2, { ssa_caps::SENSORS }>;

/// The 3-D radar tracker: two-body + J2 motion in an Earth-centred inertial frame, a [`RadarNetwork`],
/// [`ssa_caps`] capacities.
pub type RadarTracker<T> = Tracker<
    T,
    TwoBodyJ2<T>,
    RadarNetwork<T>,
    6,
    3,
    { ssa_caps::HYPOTHESES },
    { ssa_caps::OBJECTS },
    { ssa_caps::MEASUREMENTS },
    { ssa_caps::TRACKS_3D },
    { ssa_caps::BIRTH_CELLS },
>;

/// The configuration type of [`RadarTracker`].
pub type RadarConfig<T> = Config<T, TwoBodyJ2<T>, RadarNetwork<T>, 6, { ssa_caps::BIRTH_CELLS }>;

/// The 3-D optical tracker: two-body + J2 motion, an [`OpticalNetwork`], [`ssa_caps`] capacities.
pub type OpticalTracker<T> = Tracker<
    T,
    TwoBodyJ2<T>,
    OpticalNetwork<T>,
    6,
    2,
    { ssa_caps::HYPOTHESES },
    { ssa_caps::OBJECTS },
    { ssa_caps::MEASUREMENTS },
    { ssa_caps::TRACKS_3D },
    { ssa_caps::BIRTH_CELLS },
>;

/// The configuration type of [`OpticalTracker`].
pub type OpticalConfig<T> = Config<T, TwoBodyJ2<T>, OpticalNetwork<T>, 6, { ssa_caps::BIRTH_CELLS }>;

/// Up to [`ssa_caps::NETWORK_SENSORS`] sensors of mixed kinds (radar, radar with range-rate, RA/Dec,
/// az/el, range, range and range-rate), measurements padded to 4 components (docs/maths.md §6.10).
pub type Network<T> = MixedNetwork<T, { ssa_caps::NETWORK_SENSORS }>;

/// The fused 3-D tracker: two-body + J2 motion, a [`Network`] of mixed kinds, [`ssa_caps`] capacities.
pub type NetworkTracker<T> = Tracker<
    T,
    TwoBodyJ2<T>,
    Network<T>,
    6,
    { model::MIXED_DIMENSION },
    { ssa_caps::HYPOTHESES },
    { ssa_caps::OBJECTS },
    { ssa_caps::MEASUREMENTS },
    { ssa_caps::TRACKS_3D },
    { ssa_caps::BIRTH_CELLS },
>;

/// The configuration type of [`NetworkTracker`].
pub type NetworkConfig<T> = Config<T, TwoBodyJ2<T>, Network<T>, 6, { ssa_caps::BIRTH_CELLS }>;

/// A constant-velocity tracker with position measurements and caller-chosen capacities.
pub type LinearTracker<T, const H: usize, const N: usize, const Z: usize, const K: usize, const B: usize> =
    Tracker<T, ConstantVelocity<T>, PositionMeasurement<T>, 4, 2, H, N, Z, K, B>;

/// The configuration type of [`LinearTracker`].
pub type LinearConfig<T, const B: usize> = Config<T, ConstantVelocity<T>, PositionMeasurement<T>, 4, B>;
