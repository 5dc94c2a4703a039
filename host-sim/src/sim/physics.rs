//! Measurement physics of a simulated scenario: a sensor's constant bias, light time and tropospheric
//! refraction, put into the measurements of the objects (not the clutter) of an already drawn
//! [`SsaScenario`] ([`apply`]).
//!
//! Each detection z = h(x) + noise becomes h_phys(x) + bias + noise: the difference h_phys(x) − h(x) of the
//! noise-free measurements is added, so the noise drawn is unchanged. h_phys is computed here
//! independently of the tracker's model (tracker-core's `light_time`): the object's state at the emission
//! or bounce time is propagated with the simulator's own two-body + J2 integrator, the light-time
//! equation is solved to 10⁻¹² s, and a two-way range is the mean of both legs with the site's position at
//! the transmission and the reception. Refraction lifts the elevation to the apparent one E_a solving
//! E_a − R(E_a) = E (Bennett, [`super::refraction`]).

use super::error::SsaError;
use super::orbit::Propagator;
use super::refraction::{Atmosphere, refraction};
use super::sensor::{SensorKind, SensorSpec};
use super::site::Observer;
use super::ssa::SsaScenario;
use super::time::earth_rotation_angle;
use super::vector::{norm, pos, sub, wrap_angle};
use tracker_core::model::LightTime;
use tracker_core::model::light_time::SPEED_OF_LIGHT;

/// The physics of one sensor's measurements.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SensorPhysics {
    /// Added to every detection, per component (km, rad, km/s); empty: none.
    pub bias: Vec<f64>,
    /// Light time.
    pub light_time: LightTime,
    /// The air whose refraction lifts the elevations (radar only), or `None`.
    pub refraction: Option<Atmosphere>,
}

/// Fixed-point steps of a light-time equation (each gains a factor v/c).
const ITERATIONS: usize = 6;

/// Puts `physics[s]` into every detection of sensor `s` of `sim` (a sensor without an entry is left as
/// it is).
///
/// # Errors
/// [`SsaError::BadSensor`] for refraction on an optical sensor, a bias of the wrong length or a two-way
/// light time without a range; [`SsaError::Orbit`] when the retarded state cannot be propagated.
pub fn apply(sim: &mut SsaScenario, physics: &[SensorPhysics]) -> Result<(), SsaError> {
    for (sensor, p) in sim.sensors.iter().zip(physics) {
        let optical = sensor.kind == SensorKind::Optical;
        let bad_bias = !p.bias.is_empty() && p.bias.len() != sensor.kind.dimension();
        if (optical && (p.refraction.is_some() || p.light_time.two_way())) || bad_bias {
            return Err(SsaError::BadSensor);
        }
    }
    let epoch_jd = sim.epoch_jd;
    for scan in &mut sim.scans {
        let Some(p) = physics.get(scan.sensor) else { continue };
        let sensor = &sim.sensors[scan.sensor];
        let observer_at = |t: f64| sensor.site.observer(earth_rotation_angle(epoch_jd, t));
        let observer = observer_at(scan.time);
        for truth in &scan.truth {
            let Some(z) = truth.measurement.and_then(|j| scan.measurements.get_mut(j)) else { continue };
            let plain = sensor.measure(&observer, &truth.state);
            let physical = measure(sensor, p, scan.time, &truth.state, &observer_at)?;
            for (i, v) in z.iter_mut().enumerate() {
                *v += physical[i] - plain[i] + p.bias.get(i).copied().unwrap_or(0.0);
            }
            let azimuth = if sensor.kind == SensorKind::Optical { 0 } else { 1 };
            z[azimuth] = wrap_angle(z[azimuth]);
        }
    }
    Ok(())
}

/// The noise-free measurement of `state` (at scan time `t`) with light time and refraction.
fn measure(
    sensor: &SensorSpec,
    p: &SensorPhysics,
    t: f64,
    state: &[f64; 6],
    observer_at: &dyn Fn(f64) -> Observer,
) -> Result<Vec<f64>, SsaError> {
    let observer = observer_at(t);
    let (object, sensor_time) = match p.light_time {
        LightTime::Off => (*state, t),
        LightTime::OneWayReceive | LightTime::TwoWayReceive => (retarded(state, &observer, -1.0)?, t),
        // Transmitted at t: the bounce (or reception) at t + τ, the reception at the site at t + 2τ.
        LightTime::OneWayTransmit | LightTime::TwoWayTransmit => {
            let object = retarded(state, &observer, 1.0)?;
            (object, t + 2.0 * norm(sub(pos(&object), observer.position)) / SPEED_OF_LIGHT)
        }
    };
    // The leg the angles are measured along: the down-leg to the site at its reception time.
    let down_observer = if p.light_time == LightTime::TwoWayTransmit { observer_at(sensor_time) } else { observer };
    let mut z = sensor.measure(&down_observer, &object);
    if p.light_time.two_way() {
        z[0] = two_way_range(&object, t, sensor_time, p.light_time == LightTime::TwoWayReceive, observer_at);
    }
    if let Some(air) = p.refraction {
        z[2] = apparent_elevation(z[2], air);
    }
    Ok(z)
}

/// The object's state at t + kτ where τ = |r(t + kτ) − r_s(t)| / c.
fn retarded(state: &[f64; 6], observer: &Observer, k: f64) -> Result<[f64; 6], SsaError> {
    let mut tau = 0.0;
    let mut object = *state;
    for _ in 0..ITERATIONS {
        object = Propagator::EARTH.propagate(*state, k * tau)?;
        tau = norm(sub(pos(&object), observer.position)) / SPEED_OF_LIGHT;
    }
    Ok(object)
}

/// The mean of the up- and down-leg of a two-way signal bounced by `object`: tagged at reception
/// (`receive`, the site receiving at `t`) or at transmission (sent at `t`, received at `received`).
fn two_way_range(
    object: &[f64; 6],
    t: f64,
    received: f64,
    receive: bool,
    observer_at: &dyn Fn(f64) -> Observer,
) -> f64 {
    let at = |time: f64| norm(sub(pos(object), observer_at(time).position));
    if receive {
        let down = at(t);
        // The up-leg left the site at t − τ_down − τ_up.
        let mut up = down;
        for _ in 0..ITERATIONS {
            up = at(t - (down + up) / SPEED_OF_LIGHT);
        }
        (up + down) / 2.0
    } else {
        (at(t) + at(received)) / 2.0
    }
}

/// The apparent elevation E_a with E_a − R(E_a) = `geometric` (unchanged where R is undefined).
fn apparent_elevation(geometric: f64, air: Atmosphere) -> f64 {
    let mut apparent = geometric;
    for _ in 0..ITERATIONS {
        match refraction(apparent, air) {
            Some(r) => apparent = geometric + r,
            None => return geometric,
        }
    }
    apparent
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refraction_lifts_the_elevation_by_bennett_at_the_apparent_elevation() {
        let geometric = 10f64.to_radians();
        let apparent = apparent_elevation(geometric, Atmosphere::STANDARD);
        let lift = refraction(apparent, Atmosphere::STANDARD).unwrap();
        assert!((apparent - lift - geometric).abs() < 1e-12);
        // ≈ 5.3′ at 10°.
        assert!((lift.to_degrees() * 60.0 - 5.3).abs() < 0.1, "{}", lift.to_degrees() * 60.0);
    }

    #[test]
    fn light_time_moves_a_leo_detection_by_tens_of_metres() {
        let mut sim = crate::sim::presets::tiny_3d(1).unwrap();
        let plain = sim.clone();
        let physics = vec![SensorPhysics { light_time: LightTime::TwoWayReceive, ..SensorPhysics::default() }];
        apply(&mut sim, &physics).unwrap();
        let mut moved = 0;
        for (a, b) in sim.scans.iter().zip(&plain.scans) {
            for truth in &a.truth {
                let Some(j) = truth.measurement else { continue };
                let (za, zb) = (&a.measurements[j], &b.measurements[j]);
                let tau = zb[0] / SPEED_OF_LIGHT;
                // |Δρ| ≤ |v| τ ≈ 7.5 km/s × 5 ms; the angles move by at most vτ/ρ.
                assert!((za[0] - zb[0]).abs() < 7.8 * tau + 1e-6, "{} {}", za[0], zb[0]);
                assert!((za[1] - zb[1]).abs() < 7.8 * tau / zb[0] / zb[2].cos() + 1e-9);
                moved += usize::from((za[0] - zb[0]).abs() > 1e-3);
            }
        }
        assert!(moved > 0);
    }
}
