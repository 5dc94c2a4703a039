//! The measurements of a scan as the tracker takes them: in the tracker's units
//! ([`super::measurements_in_radians`]), the sensor's known bias subtracted (`bias`) and, for a sensor
//! whose elevations carry tropospheric refraction (`refraction`), the refraction removed from the
//! elevation (Bennett, [`crate::sim::refraction`]). Light time is modelled in the measurement function
//! (tracker-core's [`tracker_core::model::light_time`], set on the network by [`super::network`]).
//! A sensor without these settings gives exactly the measurements of [`super::measurements_in_radians`].

use super::measurements_in_radians;
use crate::scenario::v2::{Measurement3dSpec, Scan3dSpec, Scenario3d};
use crate::sim::refraction::geometric_elevation;
use tracker_core::sensor::wrap_angle;

/// The elevation's component of a measurement kind that has one (radar: A, E after ρ; az/el: E after A).
fn elevation_component(kind: Measurement3dSpec) -> Option<usize> {
    match kind {
        Measurement3dSpec::Radar | Measurement3dSpec::RadarRangeRate => Some(2),
        Measurement3dSpec::AzEl => Some(1),
        _ => None,
    }
}

/// The scan's measurements in the tracker's units with its sensor's bias and refraction removed.
pub fn corrected_measurements(scenario: &Scenario3d, scan: &Scan3dSpec) -> Vec<Vec<f64>> {
    let kind = scenario.kind(scan.sensor);
    let mut zs = measurements_in_radians(kind, &scan.measurements);
    let Some(sensor) = scenario.sensors.get(scan.sensor) else { return zs };
    if sensor.bias.is_some() {
        let bias = sensor.bias_values(kind);
        for z in &mut zs {
            for (i, (v, b)) in z.iter_mut().zip(&bias).enumerate() {
                *v -= b;
                if kind.wraps(i) {
                    *v = wrap_angle(*v);
                }
            }
        }
    }
    if let (Some(air), Some(e)) = (sensor.atmosphere(), elevation_component(kind)) {
        for z in &mut zs {
            // Below −1° apparent the formula does not hold: such an elevation is left as measured.
            if let Some(geometric) = z.get(e).and_then(|&apparent| geometric_elevation(apparent, air)) {
                z[e] = geometric;
            }
        }
    }
    zs
}
