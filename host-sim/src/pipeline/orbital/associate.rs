//! The association of a scan's measurements with the MAP tracks that judges a run without truth
//! ([`crate::eval::consistency`]): each MAP track predicted to the scan with the tracker's motion model, put
//! through the scan's placed measurement model with tracker-core's own [`ekf::innovation`] and residual
//! (angles wrapped as the tracker wraps them), and each measurement given to the track of smallest d² below
//! the χ²_d 99.9 % gate.

use crate::eval::consistency::gate;
use nalgebra::SVector;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::sensor::ScanGeometry;
use tracker_core::{Tracker, ekf};

/// A measurement associated with a MAP track: its label, ν = z − ẑ (the tracker's units) and νᵀ S⁻¹ ν.
pub type Association = (u32, Vec<f64>, f64);

/// Per measurement of a scan of `sensor` at `time` (the tracker's units), its association with a MAP track
/// of `tracker` before the update, or `None`; and the measurement model's dimension. Any state dimension
/// `S`: the planar world's trackers use it too. No association when
/// the scan cannot be placed; a track whose prediction or innovation fails numerically takes none.
#[allow(clippy::type_complexity)]
pub fn associate<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    tracker: &Tracker<f64, M, G, S, D, H, N, Z, K, B>,
    sensor: usize,
    time: f64,
    measurements: &[Vec<f64>],
) -> (usize, Vec<Option<Association>>)
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D> + Clone,
{
    let config = tracker.config();
    let Ok(placed) = config.measurement.place(&ScanGeometry { sensor, time, observer: None }) else {
        return (D, vec![None; measurements.len()]);
    };
    let dimension = placed.dimension();
    let dt = time - tracker.time();
    let Some(map) = tracker.hypotheses().next() else {
        return (dimension, vec![None; measurements.len()]);
    };
    let predicted: Vec<_> = map
        .tracks()
        .filter_map(|t| {
            let prediction = ekf::predict(&config.motion, &t.state, dt).ok()?;
            Some((t.label.0, ekf::innovation(&placed, &prediction).ok()?))
        })
        .collect();
    let limit = gate(dimension);
    let associations = measurements
        .iter()
        .map(|z| {
            let z = SVector::<f64, D>::from_iterator(z.iter().copied().chain(core::iter::repeat(0.0)).take(D));
            predicted
                .iter()
                .map(|(label, innovation)| {
                    let residual = placed.residual(&z, &innovation.predicted);
                    (*label, residual, innovation.score_residual(&residual).0)
                })
                .filter(|(_, _, d2)| *d2 < limit)
                .min_by(|a, b| a.2.total_cmp(&b.2))
                .map(|(label, residual, d2)| (label, residual.iter().take(dimension).copied().collect(), d2))
        })
        .collect();
    (dimension, associations)
}
