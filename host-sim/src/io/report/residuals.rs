//! `residuals` of `summary.json`: per sensor, how the MAP tracks' associated measurements agree with the
//! tracker's own innovation covariance ([`crate::eval::consistency`]).

use serde::{Deserialize, Serialize};

/// One sensor's entry of `residuals`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorResiduals {
    /// RMS of the residual per measurement component, in the file's units (km, degrees, km/s); `null`
    /// without associated measurements.
    pub rms: Option<Vec<f64>>,
    /// Mean normalised innovation squared νᵀ S⁻¹ ν; `null` without associated measurements.
    pub mean_nis: Option<f64>,
    /// Two-sided 95 % χ² band of that mean, [low, high]; `null` without associated measurements.
    pub nis_band: Option<[f64; 2]>,
    /// Measurements associated with MAP tracks / all the sensor's measurements (0 without measurements).
    pub associated_fraction: f64,
    /// The sensor's measurements in the scans the tracker took.
    pub measurements: usize,
}
