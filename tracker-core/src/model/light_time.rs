//! Light time: a measurement of a 3-D inertial state made with a signal that took τ = ρ / c to travel
//! between the object and the sensor (docs/maths.md §6.12).
//!
//! The measurement at scan time t is that of the object at the emission (one-way) or bounce (two-way)
//! time t + kτ: k = −1 when the time tag is the reception at the sensor, k = +1 when it is the
//! transmission from the sensor. With r, v the object's state at t (the tracker's state) and r_s the
//! observer's position at t, the retarded position is r' = r + kτv with τ = |r' − r_s| / c, solved by
//! [`ITERATIONS`] fixed-point steps (each gains a factor v/c ≈ 2.5·10⁻⁵), and h(x) is the model's h at
//! (r', v). Two-way, the reported range is the mean of the up- and down-leg: the observer moved 2τv_s
//! between them, which adds −kτ (d̂ · v_s) to the range (d = r' − r_s).
//!
//! **Jacobian.** With d̂ = d / |d| and g = d̂ / (c − k d̂·v) (= ∂τ/∂r), ∂r'/∂r = I + k v gᵀ and
//! ∂r'/∂v = kτ I + τ v gᵀ; H = H_model(r', v) · ∂(r', v)/∂(r, v). The two-way range term's own derivative
//! (of order v_s / c ≈ 1.5·10⁻⁶ of ∂ρ/∂r) is neglected.
//!
//! **Sizes.** LEO, ρ = 1000–2000 km: τ = 3.3–6.7 ms, vτ = 25–50 m along track. GEO, ρ ≈ 36 000–38 000 km:
//! τ ≈ 0.12 s, vτ ≈ 0.37 km. The neglected station motion of a one-way signal time-tagged at the object
//! (PATH 1,2 tagged at reception) is at most v_s τ: 1.5 m in LEO, 55 m at GEO.

use super::Measure;
use crate::real::{Real, c, sqrt};
use nalgebra::{SMatrix, SVector};

/// The speed of light in vacuum (km/s).
pub const SPEED_OF_LIGHT: f64 = 299_792.458;

/// Fixed-point steps of τ = |r + kτv − r_s| / c (the first from τ = 0).
pub const ITERATIONS: usize = 3;

/// How a sensor's measurements are delayed by light time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum LightTime {
    /// None: the object at the scan time (every configuration unless it asks otherwise).
    #[default]
    Off,
    /// One-way, time tag at reception (a downlink, PATH 2,1): the object at t − τ.
    OneWayReceive,
    /// One-way, time tag at transmission (an uplink, PATH 1,2): the object at t + τ.
    OneWayTransmit,
    /// Two-way (PATH 1,2,1), time tag at reception: bounce at t − τ, range the mean of both legs.
    TwoWayReceive,
    /// Two-way, time tag at transmission: bounce at t + τ, range the mean of both legs.
    TwoWayTransmit,
}

impl LightTime {
    /// k: −1 (the object earlier), +1 (later) or 0 (off).
    fn direction(self) -> i8 {
        match self {
            LightTime::Off => 0,
            LightTime::OneWayReceive | LightTime::TwoWayReceive => -1,
            LightTime::OneWayTransmit | LightTime::TwoWayTransmit => 1,
        }
    }

    /// Whether the signal went there and back (the range is the mean of both legs).
    pub fn two_way(self) -> bool {
        matches!(self, LightTime::TwoWayReceive | LightTime::TwoWayTransmit)
    }
}

/// The retarded state (r', v), τ, d = r' − r_s and k for `state` seen from `observer`.
fn retarded<T: Real>(observer: &[T; 6], mode: LightTime, state: &SVector<T, 6>) -> (SVector<T, 6>, T, [T; 3], T) {
    let k = T::of_f64(f64::from(mode.direction()));
    let light = c::<T>(SPEED_OF_LIGHT);
    let mut tau = T::zero();
    let mut d = [T::zero(); 3];
    for _ in 0..ITERATIONS {
        d = core::array::from_fn(|i| state[i] + k * tau * state[i + 3] - observer[i]);
        tau = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) / light;
    }
    let mut shifted = *state;
    for i in 0..3 {
        shifted[i] = state[i] + k * tau * state[i + 3];
        d[i] = shifted[i] - observer[i];
    }
    (shifted, tau, d, k)
}

/// d̂ (zero at d = 0).
fn unit<T: Real>(d: &[T; 3]) -> [T; 3] {
    let norm = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if norm > T::zero() { d.map(|v| v / norm) } else { [T::zero(); 3] }
}

/// h of `model` at the light-time retarded state; `range` says whether component 0 is a range (for the
/// two-way leg mean).
pub fn measure<T: Real, X: Measure<T, 6, D>, const D: usize>(
    model: &X,
    observer: &[T; 6],
    mode: LightTime,
    range: bool,
    state: &SVector<T, 6>,
) -> SVector<T, D> {
    let (shifted, tau, d, k) = retarded(observer, mode, state);
    let mut z = model.measure(&shifted);
    if mode.two_way() && range && D > 0 {
        let u = unit(&d);
        let along = u[0] * observer[3] + u[1] * observer[4] + u[2] * observer[5];
        z[0] -= k * tau * along;
    }
    z
}

/// ∂h/∂x of [`measure`] (the two-way range term's own derivative neglected).
pub fn jacobian<T: Real, X: Measure<T, 6, D>, const D: usize>(
    model: &X,
    observer: &[T; 6],
    mode: LightTime,
    state: &SVector<T, 6>,
) -> SMatrix<T, D, 6> {
    let (shifted, tau, d, k) = retarded(observer, mode, state);
    let inner = model.jacobian(&shifted);
    let u = unit(&d);
    let velocity = [state[3], state[4], state[5]];
    let closing = c::<T>(SPEED_OF_LIGHT) - k * (u[0] * velocity[0] + u[1] * velocity[1] + u[2] * velocity[2]);
    let g = u.map(|v| v / closing);
    // ∂(r', v)/∂(r, v).
    let mut chain = SMatrix::<T, 6, 6>::identity();
    for i in 0..3 {
        for j in 0..3 {
            let identity = if i == j { T::one() } else { T::zero() };
            chain[(i, j)] = identity + k * velocity[i] * g[j];
            chain[(i, j + 3)] = k * tau * identity + tau * velocity[i] * g[j];
        }
    }
    inner * chain
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{OpticalRaDec, RadarRangeRate};

    const MODES: [LightTime; 4] =
        [LightTime::OneWayReceive, LightTime::OneWayTransmit, LightTime::TwoWayReceive, LightTime::TwoWayTransmit];

    fn radar() -> RadarRangeRate<f64> {
        let enu = [[0.0, 1.0, 0.0], [-0.6, 0.0, 0.8], [0.8, 0.0, 0.6]];
        RadarRangeRate { observer: [5000.0, 0.0, 3800.0, 0.0, 0.36, 0.0], enu, sigma: [0.01, 1e-4, 1e-4, 1e-3] }
    }

    fn leo() -> SVector<f64, 6> {
        SVector::from([6200.0, 900.0, 3200.0, -3.0, 6.5, 2.0])
    }

    #[test]
    fn the_retarded_state_solves_the_light_time_equation() {
        let model = radar();
        for mode in MODES {
            let (shifted, tau, d, k) = retarded(&model.observer, mode, &leo());
            let rho = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            assert!((tau * SPEED_OF_LIGHT - rho).abs() < 1e-9, "{mode:?}");
            assert!((shifted[0] - (leo()[0] + k * tau * leo()[3])).abs() < 1e-12);
            // LEO at ≈ 1500 km: a few ms, tens of metres along track.
            assert!((3e-3..8e-3).contains(&tau), "{tau}");
        }
    }

    #[test]
    fn the_jacobian_matches_central_differences() {
        let model = radar();
        let optical = OpticalRaDec { observer: model.observer, sigma: [1e-5, 1e-5] };
        for mode in MODES {
            let analytic = jacobian(&model, &model.observer, mode, &leo());
            let analytic_optical = jacobian(&optical, &optical.observer, mode, &leo());
            for j in 0..6 {
                let step = if j < 3 { 1e-3 } else { 1e-6 };
                let (mut up, mut down) = (leo(), leo());
                up[j] += step;
                down[j] -= step;
                let numeric = (measure(&model, &model.observer, mode, true, &up)
                    - measure(&model, &model.observer, mode, true, &down))
                    / (2.0 * step);
                let numeric_optical = (measure(&optical, &optical.observer, mode, false, &up)
                    - measure(&optical, &optical.observer, mode, false, &down))
                    / (2.0 * step);
                for i in 0..4 {
                    let scale = analytic[(i, j)].abs().max(1e-3);
                    assert!((analytic[(i, j)] - numeric[i]).abs() / scale < 1e-4, "{mode:?} ({i},{j})");
                }
                for i in 0..2 {
                    let scale = analytic_optical[(i, j)].abs().max(1e-6);
                    assert!((analytic_optical[(i, j)] - numeric_optical[i]).abs() / scale < 1e-4, "{mode:?}");
                }
            }
        }
    }

    #[test]
    fn a_network_applies_light_time_only_to_the_sensors_that_set_it() {
        use crate::model::{RadarRangeAzEl, SensorNetwork};
        use crate::sensor::{
            EarthRotation, GroundSite, LookShape, Placement, Platform, Region, ScanGeometry, Sensor, SiteSensor,
        };
        let field_of_view = Region::Look {
            shape: LookShape::Cone { azimuth: 0.0, elevation: 1.0, half_angle: 1.5 },
            min_elevation: 0.0,
            range: Some([100.0, 5000.0]),
            range_rate: None,
        };
        let site = |latitude: f64| SiteSensor {
            platform: Platform::Ground(GroundSite { latitude, longitude: 0.1, height: 0.1 }),
            sigma: [0.01, 1e-4, 1e-4],
            detection: Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view },
        };
        let plain: SensorNetwork<f64, RadarRangeAzEl<f64>, 3, 2> =
            SensorNetwork::new(EarthRotation::new(0.2), &[site(0.5), site(0.6)]).unwrap();
        assert!(plain.with_light_time(2, LightTime::OneWayReceive).is_err());
        let network = plain.with_light_time(1, LightTime::TwoWayReceive).unwrap();
        assert_eq!((network.light_time(0), network.light_time(1)), (LightTime::Off, LightTime::TwoWayReceive));
        let at = |sensor| ScanGeometry { sensor, time: 30.0, observer: None };
        // Sensor 0: exactly the network without the setting; sensor 1: the retarded measurement.
        let (first, unset) = (network.place(&at(0)).unwrap(), plain.place(&at(0)).unwrap());
        assert_eq!(first.measure(&leo()), unset.measure(&leo()));
        assert_eq!(first.jacobian(&leo()), unset.jacobian(&leo()));
        let second = network.place(&at(1)).unwrap();
        let placed = plain.place(&at(1)).unwrap();
        assert_ne!(second.measure(&leo()), placed.measure(&leo()));
        let expected = measure(placed.placed(), &placed.placed().observer, LightTime::TwoWayReceive, true, &leo());
        assert_eq!(second.measure(&leo()), expected);
        let optical: SensorNetwork<f64, OpticalRaDec<f64>, 2, 1> = SensorNetwork::new(
            EarthRotation::new(0.2),
            &[SiteSensor {
                platform: Platform::Ground(GroundSite { latitude: 0.5, longitude: 0.1, height: 0.1 }),
                sigma: [1e-5, 1e-5],
                detection: Sensor {
                    detection_probability: 0.9,
                    clutter_rate: 1.0,
                    field_of_view: Region::Look {
                        shape: LookShape::Cone { azimuth: 0.0, elevation: 1.0, half_angle: 0.2 },
                        min_elevation: 0.0,
                        range: None,
                        range_rate: None,
                    },
                },
            }],
        )
        .unwrap();
        assert!(optical.with_light_time(0, LightTime::TwoWayReceive).is_err());
        assert!(optical.with_light_time(0, LightTime::OneWayReceive).is_ok());
    }

    #[test]
    fn receive_and_transmit_tags_move_the_object_opposite_ways_by_v_tau() {
        let model = radar();
        let plain = model.measure(&leo());
        let earlier = measure(&model, &model.observer, LightTime::OneWayReceive, true, &leo());
        let later = measure(&model, &model.observer, LightTime::OneWayTransmit, true, &leo());
        // The range moves by (d̂ · v) τ, earlier or later.
        let d: [f64; 3] = core::array::from_fn(|i| leo()[i] - model.observer[i]);
        let approach = (0..3).map(|i| d[i] * leo()[i + 3]).sum::<f64>() / plain[0];
        let tau = plain[0] / SPEED_OF_LIGHT;
        assert!((earlier[0] - (plain[0] - approach * tau)).abs() < 1e-5, "{earlier} {plain}");
        assert!((later[0] - (plain[0] + approach * tau)).abs() < 1e-5, "{later} {plain}");
        assert!((approach * tau).abs() > 1e-3, "a shift of metres at least");
    }
}
