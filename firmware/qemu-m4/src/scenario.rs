//! The recorded scenario, embedded at build time: `build.rs` turns the host-sim scenario file named by
//! `RFISST_SCENARIO` into `$OUT_DIR/scenario.rs`, included here.
//!
//! The generated file defines `NAME`, `SCANS_IN_FILE`, `CONFIG` (an `SsaConfig<f32>` constant), `PRIOR_TIME`,
//! `PRIOR` and `SCANS`. Every value in it is written as `f32::from_bits` / `f64::from_bits` of the value the
//! host computes, so the host and the target start from the same bits. Matrices are written row by row,
//! as in the scenario file.

use nalgebra::{ArrayStorage, SMatrix, SVector};
use tracker_core::config::Selection;
use tracker_core::sampler::{Proposal, SamplerConfig};
use tracker_core::{
    BirthDetection, BirthEvents, BirthModel, ChildGeneration, Config, Gaussian, PositionMeasurement, PriorHypothesis,
    PriorObject, Region, Sensor, SsaConfig, StoreOverflow, TrackLabel, TwoBody, ssa_caps,
};

/// One scan: its time and measurements.
pub struct Scan {
    /// Time (s).
    pub time: f64,
    /// Measurements (x, y).
    pub measurements: &'static [SVector<f32, 2>],
}

/// A 2-vector.
const fn vector2(v: [f32; 2]) -> SVector<f32, 2> {
    SVector::from_array_storage(ArrayStorage([v]))
}

/// A 2×2 matrix from its rows (nalgebra stores columns).
const fn matrix2(r: [[f32; 2]; 2]) -> SMatrix<f32, 2, 2> {
    SMatrix::from_array_storage(ArrayStorage([[r[0][0], r[1][0]], [r[0][1], r[1][1]]]))
}

/// A Gaussian from its mean and its covariance's rows.
const fn gaussian(mean: [f32; 4], r: [[f32; 4]; 4]) -> Gaussian<f32, 4> {
    let mut columns = [[0.0; 4]; 4];
    let mut i = 0;
    while i < 4 {
        let mut j = 0;
        while j < 4 {
            columns[j][i] = r[i][j];
            j += 1;
        }
        i += 1;
    }
    Gaussian {
        mean: SVector::from_array_storage(ArrayStorage([mean])),
        covariance: SMatrix::from_array_storage(ArrayStorage(columns)),
    }
}

include!(concat!(env!("OUT_DIR"), "/scenario.rs"));
