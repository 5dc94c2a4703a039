//! The compile-time image of each default tracker before its configuration: what `rfisst_tracker_init`
//! copies into the caller's storage before `Tracker::reset_with` installs the run-time configuration and
//! the prior in place (as firmware/qemu-m4 does with its static trackers). So no tracker passes through
//! the stack: building one by value (`Tracker::empty(config)`) took about 2.2 × its size of stack.
//!
//! The placeholder configurations hold zeros and networks of no sensors (`unconfigured()`): a tracker
//! refuses them, so an image is only ever a starting point for `reset_with`. Everything else in an empty
//! tracker is independent of its configuration, or reset from it by `reset_with` (the sampler's
//! settings), so the result is the tracker `Tracker::empty(config)` followed by `Tracker::reset` gives.

use tracker_core::config::{ChildGeneration, Selection};
use tracker_core::model::ProcessNoise;
use tracker_core::real::zeros;
use tracker_core::sampler::SamplerConfig;
use tracker_core::{
    BirthDetection, BirthEvents, BirthModel, Config, NumericalFailure, PositionMeasurement, Real, Sensor,
    StoreOverflow, TrackLoss, TwoBody, TwoBodyJ2, ssa_caps,
};

/// A configuration of `motion` and `measurement` with every other number zero and the core's defaults.
const fn config<T: Real, M, G, const S: usize>(
    motion: M,
    measurement: G,
) -> Config<T, M, G, S, { ssa_caps::BIRTH_CELLS }> {
    Config {
        motion,
        measurement,
        sensor: Sensor::UNCONFIGURED,
        birth: BirthModel {
            probability: T::ZERO,
            cells: heapless::Vec::new(),
            detection: BirthDetection::AllDetected,
            events: BirthEvents::FirstOrder,
            measured: None,
        },
        death_probability: T::ZERO,
        gate: None,
        children: ChildGeneration::Sampled(SamplerConfig::DEFAULT),
        selection: Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: NumericalFailure::DropTrack,
        track_loss: TrackLoss::Never,
        seed: 0,
    }
}

/// The planar placeholder: a point mass of μ = 0, a zero noise.
pub const fn planar<T: Real>() -> tracker_core::SsaConfig<T> {
    let motion =
        TwoBody { mu: T::ZERO, acceleration_noise: T::ZERO, max_step: T::ZERO, max_substeps: 0, min_radius: T::ZERO };
    config(motion, PositionMeasurement { noise: zeros() })
}

/// A 3-D placeholder with the network `measurement` (of no sensors).
pub const fn orbital<T: Real, G>(measurement: G) -> Config<T, TwoBodyJ2<T>, G, 6, { ssa_caps::BIRTH_CELLS }> {
    let motion = TwoBodyJ2 {
        mu: T::ZERO,
        j2: T::ZERO,
        radius: T::ZERO,
        min_radius: T::ZERO,
        noise: ProcessNoise::Isotropic(T::ZERO),
        max_step: T::ZERO,
        max_substeps: 0,
    };
    config(motion, measurement)
}
