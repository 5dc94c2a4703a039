//! Tropospheric refraction of optical and azimuth/elevation measurements from the ground (docs/maths.md
//! §6.11): light from an object at geometric elevation E arrives at the apparent elevation E + R, so a
//! measured elevation (or a right ascension and declination reduced from it) is corrected by −R.
//!
//! Model: Bennett (1982, *Journal of Navigation* 35, 255–259), R = cot(h + 7.31/(h + 4.4)) arcminutes at
//! apparent altitude h in degrees, for 101.0 kPa and 10 °C, scaled by (P / 101.0 kPa)(283 K / (273 K + T)).
//! Accurate to 0.07′ from 0° to 90° against the Pulkovo tables; its small offset at the zenith
//! (−0.0014′) is removed so that R(90°) = 0. Not modelled: the wavelength and humidity (≲ 1 %), and
//! anything below −1° apparent (refused: the formula does not hold and no sensor looks there).

/// Degrees to radians.
const DEGREE: f64 = std::f64::consts::PI / 180.0;

/// Bennett's cotangent in arcminutes at apparent altitude `h` (degrees).
fn bennett(h: f64) -> f64 {
    1.0 / ((h + 7.31 / (h + 4.4)) * DEGREE).tan()
}

/// The air at the sensor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Atmosphere {
    /// Pressure (kPa).
    pub pressure_kpa: f64,
    /// Temperature (°C).
    pub temperature_c: f64,
}

impl Atmosphere {
    /// The standard air of Bennett's formula: 101.0 kPa, 10 °C.
    pub const STANDARD: Atmosphere = Atmosphere { pressure_kpa: 101.0, temperature_c: 10.0 };
}

/// The refraction R (rad) at apparent elevation `apparent` (rad), or `None` below −1° or for an
/// atmosphere that is not finite with pressure ≥ 0 and temperature above −100 °C.
pub fn refraction(apparent: f64, air: Atmosphere) -> Option<f64> {
    let h = apparent / DEGREE;
    let valid_air = air.pressure_kpa.is_finite()
        && air.pressure_kpa >= 0.0
        && air.temperature_c.is_finite()
        && air.temperature_c > -100.0;
    if !(h.is_finite() && (-1.0..=90.0).contains(&h) && valid_air) {
        return None;
    }
    // Its value at the zenith (−0.0014′) is removed in proportion to h so that R(90°) = 0.
    let arcmin = bennett(h) - bennett(90.0) * h / 90.0;
    let scale = (air.pressure_kpa / 101.0) * (283.0 / (273.0 + air.temperature_c));
    Some((arcmin * scale / 60.0 * DEGREE).max(0.0))
}

/// The geometric elevation (rad) of a measured (apparent) elevation `apparent`.
pub fn geometric_elevation(apparent: f64, air: Atmosphere) -> Option<f64> {
    refraction(apparent, air).map(|r| apparent - r)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn arcmin(apparent_deg: f64) -> f64 {
        refraction(apparent_deg * DEGREE, Atmosphere::STANDARD).unwrap() / DEGREE * 60.0
    }

    #[test]
    fn bennett_values_at_standard_air() {
        // The refraction of the almanac tables (standard air): 34.5′ at the horizon (Bennett's formula
        // 34.48′), 5.3′ at 10°, 1.0′ at 45°, 0 at the zenith.
        assert!((arcmin(0.0) - 34.5).abs() < 0.1, "{}", arcmin(0.0));
        assert!((arcmin(10.0) - 5.3).abs() < 0.1, "{}", arcmin(10.0));
        assert!((arcmin(45.0) - 1.0).abs() < 0.05, "{}", arcmin(45.0));
        assert!(arcmin(90.0).abs() < 1e-9, "{}", arcmin(90.0));
        // Monotone: lower objects are lifted more.
        assert!((1..90).all(|h| arcmin(f64::from(h) - 1.0) > arcmin(f64::from(h))));
    }

    #[test]
    fn thinner_and_warmer_air_refracts_less_and_bad_input_is_none() {
        let high = Atmosphere { pressure_kpa: 70.0, temperature_c: 0.0 };
        let ratio = refraction(20.0 * DEGREE, high).unwrap() / refraction(20.0 * DEGREE, Atmosphere::STANDARD).unwrap();
        assert!((ratio - 70.0 / 101.0 * 283.0 / 273.0).abs() < 1e-12, "{ratio}");
        assert_eq!(refraction(-2.0 * DEGREE, Atmosphere::STANDARD), None);
        assert_eq!(refraction(f64::NAN, Atmosphere::STANDARD), None);
        assert_eq!(refraction(0.3, Atmosphere { pressure_kpa: -1.0, temperature_c: 10.0 }), None);
        let e = geometric_elevation(30.0 * DEGREE, Atmosphere::STANDARD).unwrap();
        assert!(e < 30.0 * DEGREE && 30.0 * DEGREE - e < 2.0 / 60.0 * DEGREE);
    }
}
