//! The look geometry of a version 2 scenario's ground sensors on the host side (look angles, range,
//! range-rate, topocentric right ascension and declination, field-of-view membership of a state), and the
//! core's own field-of-view test of measurements.

use super::tracker::{ScenarioNetwork, network, padded};
use crate::error::Error;
use crate::scenario::v2::{Measurement3dSpec, Scenario3d};
use crate::with_measurement;
use tracker_core::sensor::{EarthRotation, GroundSite, ScanGeometry};
use tracker_core::{Look, Region};

/// The look geometry of the scenario's ground sensors, host side: look angles, range and range-rate of an
/// inertial state, topocentric right ascension and declination, and field-of-view membership.
pub struct SiteGeometry {
    rotation: EarthRotation<f64>,
    sites: Vec<GroundSite<f64>>,
    regions: Vec<Region<f64>>,
    kinds: Vec<Measurement3dSpec>,
}

impl SiteGeometry {
    /// The geometry of `scenario`'s sensors.
    pub fn new(scenario: &Scenario3d) -> Self {
        Self {
            rotation: EarthRotation::new(scenario.earth_rotation_at_epoch()),
            sites: scenario
                .sensors
                .iter()
                .map(|s| GroundSite {
                    latitude: s.site.latitude_deg.to_radians(),
                    longitude: s.site.longitude_deg.to_radians(),
                    height: s.site.height_km,
                })
                .collect(),
            regions: scenario.sensors.iter().map(|s| s.field_of_view.region()).collect(),
            kinds: (0..scenario.sensors.len()).map(|i| scenario.kind(i)).collect(),
        }
    }

    /// Line of sight from sensor `sensor` at `time` (inertial, km), the relative velocity, and the site's
    /// East, North, Up rows.
    fn line_of_sight(&self, sensor: usize, time: f64, state: &[f64; 6]) -> ([f64; 3], [f64; 3], [[f64; 3]; 3]) {
        let site = self.sites[sensor];
        let observer = site.observer(&self.rotation, time);
        let enu = site.enu(&self.rotation, time);
        let d = [state[0] - observer[0], state[1] - observer[1], state[2] - observer[2]];
        let w = [state[3] - observer[3], state[4] - observer[4], state[5] - observer[5]];
        (d, w, enu)
    }

    /// Look angles (rad), range (km) and range-rate (km/s) of `state` from sensor `sensor` at `time`; the
    /// range and range-rate only where the sensor's kind has them.
    pub fn look(&self, sensor: usize, time: f64, state: &[f64; 6]) -> Look<f64> {
        let kind = self.kinds[sensor];
        let (d, w, enu) = self.line_of_sight(sensor, time, state);
        let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let (e, n, u) = (dot(&enu[0], &d), dot(&enu[1], &d), dot(&enu[2], &d));
        let range = dot(&d, &d).sqrt();
        Look {
            azimuth: e.atan2(n),
            elevation: u.atan2(e.hypot(n)),
            range: kind.has_range().then_some(range),
            range_rate: kind.has_range_rate().then(|| dot(&d, &w) / range),
        }
    }

    /// Topocentric right ascension and declination (rad) of `state` from sensor `sensor` at `time`.
    pub fn ra_dec(&self, sensor: usize, time: f64, state: &[f64; 6]) -> (f64, f64) {
        let (d, _, _) = self.line_of_sight(sensor, time, state);
        (d[1].atan2(d[0]), d[2].atan2(d[0].hypot(d[1])))
    }

    /// Whether `state` lies in sensor `sensor`'s field of view at `time`.
    pub fn in_view(&self, sensor: usize, time: f64, state: &[f64; 6]) -> bool {
        self.regions[sensor].contains_look(&self.look(sensor, time, state))
    }

    /// The sky-plot point of `state`: (right ascension, declination) for a telescope, (hours since the
    /// epoch, range km) for a kind without angles, (azimuth, elevation) for every other kind.
    pub fn sky_point(&self, sensor: usize, time: f64, state: &[f64; 6]) -> (f64, f64) {
        if self.kinds[sensor].sky_in_range() {
            let (d, _, _) = self.line_of_sight(sensor, time, state);
            (time / 3600.0, (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        } else if self.kinds[sensor].sky_in_ra_dec() {
            self.ra_dec(sensor, time, state)
        } else {
            let look = self.look(sensor, time, state);
            (look.azimuth, look.elevation)
        }
    }
}

/// The core's own field-of-view test of measurements ([`Region::sees`] through the placed network), the
/// test `step_scan` applies: a measurement it fails is
/// [`StepError::MeasurementOutsideFieldOfView`](tracker_core::StepError::MeasurementOutsideFieldOfView).
pub struct FieldOfViewCheck {
    sees: Box<Sees>,
}

/// Whether a measurement (tracker units) of sensor `sensor` at `time` is in its field of view.
type Sees = dyn Fn(usize, f64, &[f64]) -> bool + Send + Sync;

fn sees_in<G: ScenarioNetwork<D>, const D: usize>(network: &G, sensor: usize, time: f64, z: &[f64]) -> bool {
    match network.place(&ScanGeometry { sensor, time, observer: None }) {
        Ok(placed) => {
            z.len() == placed.dimension() && {
                let z = padded::<D>(z);
                placed.detection().is_some_and(|d| placed.measurement_in_view(&d.field_of_view, &z))
            }
        }
        Err(_) => false,
    }
}

/// The check of the network `G`.
fn check_for<G: ScenarioNetwork<D>, const D: usize>(scenario: &Scenario3d) -> Result<FieldOfViewCheck, Error> {
    let network = network::<G, D>(scenario)?;
    Ok(FieldOfViewCheck { sees: Box::new(move |sensor, time, z| sees_in(&network, sensor, time, z)) })
}

impl FieldOfViewCheck {
    /// The check of `scenario`'s sensors.
    ///
    /// # Errors
    /// The core's message when it rejects the network.
    pub fn new(scenario: &Scenario3d) -> Result<Self, Error> {
        with_measurement!(scenario.measurement, check_for, (scenario))
    }

    /// Whether measurement `z` (tracker units: km, rad, km/s) of sensor `sensor` at `time` is in its field of
    /// view.
    pub fn sees(&self, sensor: usize, time: f64, z: &[f64]) -> bool {
        (self.sees)(sensor, time, z)
    }
}
