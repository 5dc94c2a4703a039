//! Why a simulation failed, and the measurement capacity no simulated scan may exceed.

use crate::sim::orbit::OrbitError;

/// The core's default measurement capacity: no simulated scan may carry more.
pub const MAX_MEASUREMENTS: usize = 32;

/// Why a simulation failed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SsaError {
    /// The epoch string is not `YYYY-MM-DDTHH:MM:SS[.fff][Z]` or is out of range.
    BadEpoch,
    /// A sensor is inconsistent (radar without range window, wrong number of σ, p_D outside [0, 1]...).
    BadSensor,
    /// Clutter rejection sampling found no point of the field of view (zero or tiny volume).
    EmptyFieldOfView,
    /// A scan would carry more than [`MAX_MEASUREMENTS`] measurements.
    TooManyMeasurements {
        /// The scan's index.
        scan: usize,
    },
    /// No orbit with the required passes was found for an object in the allowed number of draws.
    OrbitSearch,
    /// Truth propagation failed.
    Orbit(OrbitError),
    /// A missing fraction outside [0, 1], or a break-up asked of a preset without one.
    BadUnknowns,
}

impl core::fmt::Display for SsaError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SsaError::BadEpoch => f.write_str("epoch is not an ISO-8601 UTC time between 1900 and 2100"),
            SsaError::BadSensor => f.write_str("inconsistent sensor specification"),
            SsaError::EmptyFieldOfView => f.write_str("clutter sampling found no point in the field of view"),
            SsaError::TooManyMeasurements { scan } => {
                write!(f, "scan {scan} has more than {MAX_MEASUREMENTS} measurements")
            }
            SsaError::OrbitSearch => f.write_str("no orbit with enough passes found for an object"),
            SsaError::Orbit(e) => write!(f, "truth propagation: {e}"),
            SsaError::BadUnknowns => f.write_str("--missing-fraction must be in [0, 1]; --breakup needs radar-leo"),
        }
    }
}

impl std::error::Error for SsaError {}

impl From<OrbitError> for SsaError {
    fn from(e: OrbitError) -> Self {
        SsaError::Orbit(e)
    }
}
