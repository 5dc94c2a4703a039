//! Shared fixtures of the conformance tests: linear configurations, a textbook Kalman filter written
//! independently of tracker-core's EKF (explicit inverse and determinant, as in the papers), and a
//! fingerprint of everything a tracker exposes, to check that a failed step changes nothing.

use nalgebra::{SMatrix, SVector};
use tracker_core::{
    BirthModel, ChildGeneration, Config, ConstantVelocity, Gaussian, LinearConfig, Measure, MeasurementModel,
    MotionModel, PositionMeasurement, Real, Region, Sensor, StoreOverflow, Tracker,
};

/// 2-vector.
pub type V2 = SVector<f64, 2>;
/// 4-vector.
pub type V4 = SVector<f64, 4>;
/// 4 × 4 matrix.
pub type M4 = SMatrix<f64, 4, 4>;

/// A constant-velocity configuration with no birth, no death and no gate: the exact recursion.
pub fn linear_config<const B: usize>(
    detection_probability: f64,
    clutter_rate: f64,
    volume: f64,
) -> LinearConfig<f64, B> {
    Config {
        motion: ConstantVelocity { acceleration_noise: 0.05 },
        measurement: PositionMeasurement::isotropic(0.4),
        sensor: Sensor { detection_probability, clutter_rate, field_of_view: Region::Everywhere { volume } },
        birth: BirthModel::none(),
        death_probability: 0.0,
        gate: None,
        children: ChildGeneration::Exhaustive { max_children_per_scan: 10_000_000 },
        selection: tracker_core::config::Selection::TopWeight,
        store_overflow: StoreOverflow::PruneChildren,
        numerical_failure: Default::default(),
        track_loss: Default::default(),
        seed: 7,
    }
}

/// A Gaussian with mean `mean` and covariance `variance · I`.
pub fn gaussian(mean: [f64; 4], variance: f64) -> Gaussian<f64, 4> {
    Gaussian { mean: V4::from(mean), covariance: M4::identity() * variance }
}

/// Textbook Kalman filter for a linear configuration, independent of tracker-core's EKF code.
pub struct TextbookKf<'a, const B: usize> {
    /// The configuration whose models are used.
    pub config: &'a LinearConfig<f64, B>,
}

impl<const B: usize> TextbookKf<'_, B> {
    /// x⁻ = F x, P⁻ = F P Fᵀ + Q.
    pub fn predict(&self, g: &Gaussian<f64, 4>, dt: f64) -> Gaussian<f64, 4> {
        let f = self.config.motion.propagate(&g.mean, dt).unwrap().transition;
        Gaussian {
            mean: f * g.mean,
            covariance: f * g.covariance * f.transpose() + self.config.motion.process_noise(&g.mean, dt),
        }
    }

    /// N(z; H x⁻, H P⁻ Hᵀ + R) from the explicit inverse and determinant.
    pub fn likelihood(&self, g: &Gaussian<f64, 4>, z: &V2) -> f64 {
        let h = self.config.measurement.jacobian(&g.mean);
        let s = h * g.covariance * h.transpose() + self.config.measurement.noise;
        let nu = z - h * g.mean;
        let d2 = (nu.transpose() * s.try_inverse().unwrap() * nu)[0];
        (-0.5 * d2).exp() / (2.0 * std::f64::consts::PI * s.determinant().sqrt())
    }

    /// K = P Hᵀ S⁻¹, x = x⁻ + K ν, P = (I − K H) P⁻.
    pub fn update(&self, g: &Gaussian<f64, 4>, z: &V2) -> Gaussian<f64, 4> {
        let h = self.config.measurement.jacobian(&g.mean);
        let s = h * g.covariance * h.transpose() + self.config.measurement.noise;
        let k = g.covariance * h.transpose() * s.try_inverse().unwrap();
        Gaussian { mean: g.mean + k * (z - h * g.mean), covariance: (M4::identity() - k * h) * g.covariance }
    }
}

/// Every association of `rows` measurements to `objects` objects (`None` = clutter), each object at
/// most once: the A_N(m) children of docs/maths.md §7.1.
pub fn all_associations(rows: usize, objects: usize) -> Vec<Vec<Option<usize>>> {
    let mut out = vec![vec![]];
    for _ in 0..rows {
        let mut next = vec![];
        for partial in &out {
            next.push([partial.clone(), vec![None]].concat());
            for o in 0..objects {
                if !partial.contains(&Some(o)) {
                    next.push([partial.clone(), vec![Some(o)]].concat());
                }
            }
        }
        out = next;
    }
    out
}

/// The bits of everything a tracker exposes: time, scan count, each hypothesis's weight and tracks.
pub fn fingerprint<
    T: Real,
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
    tracker: &Tracker<T, M, G, S, D, H, N, Z, K, B>,
) -> Vec<u64>
where
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    let mut bits = vec![tracker.time().to_bits(), tracker.scans()];
    for h in tracker.hypotheses() {
        bits.push(h.log_weight().as_f64().to_bits());
        for track in h.tracks() {
            bits.push(u64::from(track.label.0));
            bits.push(track.existence.as_f64().to_bits());
            bits.extend(track.state.mean.iter().chain(track.state.covariance.iter()).map(|v| v.as_f64().to_bits()));
        }
    }
    bits.push(tracker.tracks().len() as u64);
    bits
}

/// Relative difference |a − b| / max(|a|, |b|), 0 when both are 0.
pub fn relative_difference(a: f64, b: f64) -> f64 {
    let scale = a.abs().max(b.abs());
    if scale == 0.0 { 0.0 } else { (a - b).abs() / scale }
}

/// Runs `f` on a thread with a 256 MiB stack: trackers with large capacities hold several MiB inline.
pub fn with_large_stack<F: FnOnce() + Send + 'static>(f: F) {
    std::thread::Builder::new().stack_size(256 << 20).spawn(f).expect("spawn").join().expect("test thread panicked");
}
