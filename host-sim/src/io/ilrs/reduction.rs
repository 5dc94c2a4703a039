//! A normal point reduced to what the tracker takes: a one-way geometric range (km) from the station to
//! the target's centre of mass at the bounce time (docs/results.md, "Real data: laser ranging").
//!
//! - Time: the bounce time t_b, from the CRD epoch event: transmit t + τ/2, bounce t, receive t − τ/2, with
//!   τ the two-way time of flight. The range at t_b is the mean of the up and down legs to within
//!   (v_s τ)² / ρ ≈ 1e-5 m (v_s the station's speed), so the tracker needs no light-time model
//!   (the TDM says `COMMENT LIGHT_TIME NONE`).
//! - Range: c τ / 2, minus the Marini–Murray tropospheric delay (ILRS standard until 2006, from the pass's
//!   meteorological record, wavelength, station latitude and height, and the elevation of the CPF's
//!   position) unless H4 says it is applied, plus the centre-of-mass offset unless H4 says it is applied.
//!   Not modelled: the relativistic (Shapiro) delay, ≤ 2 cm for LAGEOS. The station delay must be applied
//!   already (H4); a pass without it is refused.

use super::cpf::Cpf;
use super::crd::{NormalPoint, Pass};
use super::sinex::Station;
use super::{DayTime, SPEED_OF_LIGHT};
use crate::sim::site::{WGS84_A, WGS84_F};

/// A normal point reduced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reduced {
    /// The bounce time (s since the epoch day).
    pub time: f64,
    /// One-way geometric range (km).
    pub range_km: f64,
    /// The target's elevation seen from the station (deg, from the CPF).
    pub elevation_deg: f64,
    /// The tropospheric delay removed (m; 0 when the CRD had it applied).
    pub troposphere_m: f64,
    /// The station at the bounce time, ITRF (m).
    pub station_m: [f64; 3],
    /// The CPF's position at the bounce time, ITRF (m).
    pub cpf_m: [f64; 3],
}

/// Geodetic latitude (rad), longitude (rad) and height (m) on WGS-84 of an Earth-fixed position (m).
pub fn geodetic(r: [f64; 3]) -> (f64, f64, f64) {
    let a = WGS84_A * 1e3;
    let e2 = WGS84_F * (2.0 - WGS84_F);
    let p = r[0].hypot(r[1]);
    let longitude = r[1].atan2(r[0]);
    let mut latitude = r[2].atan2(p * (1.0 - e2));
    let mut height = 0.0;
    for _ in 0..8 {
        let (s, c) = latitude.sin_cos();
        let n = a / (1.0 - e2 * s * s).sqrt();
        height = p / c - n;
        latitude = r[2].atan2(p * (1.0 - e2 * n / (n + height)));
    }
    (latitude, longitude, height)
}

/// Elevation (rad) of `target` seen from `station` (Earth-fixed, m), above the geodetic horizon.
pub fn elevation(station: [f64; 3], target: [f64; 3]) -> f64 {
    let (lat, lon, _) = geodetic(station);
    let up = [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()];
    let d: [f64; 3] = std::array::from_fn(|k| target[k] - station[k]);
    let rho = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    ((d[0] * up[0] + d[1] * up[1] + d[2] * up[2]) / rho).clamp(-1.0, 1.0).asin()
}

/// The Marini–Murray (1973) one-way tropospheric delay (m) at elevation `e` (rad), for pressure (hPa),
/// temperature (K), relative humidity (%), wavelength (µm), station latitude (rad) and height (m).
pub fn marini_murray(
    e: f64,
    pressure: f64,
    temperature: f64,
    humidity: f64,
    wavelength_um: f64,
    latitude: f64,
    height: f64,
) -> f64 {
    let celsius = temperature - 273.15;
    let vapour = humidity / 100.0 * 6.11 * 10f64.powf(7.5 * celsius / (237.3 + celsius));
    let k = 1.163 - 0.00968 * (2.0 * latitude).cos() - 0.00104 * temperature + 0.000_014_35 * pressure;
    let a = 0.002_357 * pressure + 0.000_141 * vapour;
    let b =
        1.084e-8 * pressure * temperature * k + 4.734e-8 * pressure * pressure / temperature * 2.0 / (3.0 - 1.0 / k);
    let f_lambda = 0.9650 + 0.0164 / wavelength_um.powi(2) + 0.000_228 / wavelength_um.powi(4);
    let f_site = 1.0 - 0.0026 * (2.0 * latitude).cos() - 0.000_31 * height / 1e3;
    let s = e.sin();
    f_lambda / f_site * (a + b) / (s + (b / (a + b)) / (s + 0.01))
}

/// Reduces `point` of `pass` ranged from `station`, times in seconds since `epoch_day`; `None` when its
/// bounce time lies outside the CPF's span (no elevation for the troposphere). `centre_of_mass_m` is the
/// target's offset added unless the pass has it applied.
///
/// # Errors
/// A message when the pass lacks the station delay, the CPF has the target below the horizon, the
/// point's configuration has no C0 wavelength, or the pass has no meteorological record while its
/// troposphere is not applied.
pub fn reduce(
    pass: &Pass,
    point: &NormalPoint,
    station: &Station,
    cpf: &Cpf,
    epoch_day: i64,
    centre_of_mass_m: f64,
) -> Result<Option<Reduced>, String> {
    if !pass.applied.station_delay {
        return Err("the station's system delay is not applied (H4): not supported".into());
    }
    let tau = point.time_of_flight;
    let shift = match point.epoch_event {
        0 => -tau / 2.0,
        1 => 0.0,
        _ => tau / 2.0,
    };
    let bounce: DayTime = point.time.plus(shift);
    let time = bounce.since(epoch_day);
    let Some((cpf_m, _)) = cpf.state_at(time, epoch_day) else { return Ok(None) };
    let station_m = station.position_at(bounce);
    let e = elevation(station_m, cpf_m);
    if e < 0.0 {
        return Err(format!(
            "the CPF has the target below the station's horizon ({:.1} deg) at this point",
            e.to_degrees()
        ));
    }
    let mut range_m = SPEED_OF_LIGHT * tau / 2.0;
    let mut troposphere_m = 0.0;
    if !pass.applied.troposphere {
        let wavelength = pass.wavelength(&point.configuration).ok_or_else(|| {
            format!("system configuration \"{}\" has no C0 record (its wavelength)", point.configuration)
        })?;
        let meteo = pass.meteo_at(time, epoch_day).ok_or("no meteorological record (20) in the pass")?;
        let (lat, _, height) = geodetic(station_m);
        troposphere_m = marini_murray(
            e,
            meteo.pressure_hpa,
            meteo.temperature_k,
            meteo.humidity_percent,
            wavelength / 1e3,
            lat,
            height,
        );
        range_m -= troposphere_m;
    }
    if !pass.applied.centre_of_mass {
        range_m += centre_of_mass_m;
    }
    Ok(Some(Reduced { time, range_km: range_m / 1e3, elevation_deg: e.to_degrees(), troposphere_m, station_m, cpf_m }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geodetic_inverts_the_site_position() {
        let site = crate::sim::site::Site {
            latitude: (-29.046_f64).to_radians(),
            longitude: 115.35_f64.to_radians(),
            height: 0.244,
        };
        let r = site.earth_fixed().map(|x| x * 1e3);
        let (lat, lon, h) = geodetic(r);
        assert!((lat - site.latitude).abs() < 1e-12 && (lon - site.longitude).abs() < 1e-12, "{lat} {lon}");
        assert!((h - 244.0).abs() < 1e-6, "{h}");
        let zenith = r.map(|x| x * 2.0);
        assert!((elevation(r, zenith).to_degrees() - 90.0).abs() < 0.2);
    }

    /// A CPF of a target fixed 6000 km above (or below) Yarragadee, the pass `crd` with its first point.
    fn refusal(crd: &str, above: bool) -> String {
        let station = Station {
            code: 7090,
            position: [-2_389_007.5, 5_043_329.4, -3_078_524.2],
            velocity: [0.0; 3],
            epoch: DayTime { day: 0, seconds: 0.0 },
            line: 1,
        };
        let (lat, lon, _) = geodetic(station.position);
        let up = [lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin()];
        let sign = if above { 1.0 } else { -1.0 };
        let target: [f64; 3] = std::array::from_fn(|k| station.position[k] + sign * 6e6 * up[k]);
        let records =
            (0..12).map(|k| (DayTime { day: 16_844, seconds: 49_000.0 + 60.0 * f64::from(k) }, target)).collect();
        let cpf = Cpf { target: "lageos2".into(), centre_of_mass_m: None, records };
        let passes = crate::io::ilrs::crd::parse(crd).expect("valid CRD");
        let pass = &passes[0];
        match reduce(pass, &pass.points[0], &station, &cpf, 16_844, 0.251) {
            Err(message) => message,
            Ok(reduced) => format!("reduced: {reduced:?}"),
        }
    }

    const PASS: &str = "h1 CRD 1 2016 2 13 14\nh2 YARL 7090 5 13 3\nh3 lageos2 9207002 5986 22195 0 1\n\
        h4 1 2016 2 13 13 42 16 2016 2 13 14 6 46 0 0 0 0 1 0 2 0\nc0 0 532.000 std\n\
        20 49382.401 983.70 301.40 24. 0\n11 49382.400562600000 0.04 std 2 120.0\nh8\nh9\n";

    #[test]
    fn points_that_cannot_be_reduced_are_refused_with_the_reason() {
        let ok = refusal(PASS, true);
        assert!(ok.starts_with("reduced"), "{ok}");
        assert!(refusal(PASS, false).contains("below the station's horizon"));
        let no_delay = PASS.replace("0 0 0 0 1 0 2 0", "0 0 0 0 0 0 2 0");
        assert!(refusal(&no_delay, true).contains("system delay is not applied"));
        assert!(refusal(&PASS.replace("c0 0 532.000 std", "c0 0 532.000 other"), true).contains("no C0 record"));
        let no_meteo = PASS.replace("20 49382.401 983.70 301.40 24. 0\n", "");
        assert!(refusal(&no_meteo, true).contains("no meteorological record"));
        // Troposphere and centre of mass applied in the data: c τ / 2 exactly.
        let applied = refusal(&PASS.replace("0 0 0 0 1 0 2 0", "0 1 1 0 1 0 2 0"), true);
        assert!(applied.contains(&format!("range_km: {},", SPEED_OF_LIGHT * 0.04 / 2.0 / 1e3)), "{applied}");
    }

    #[test]
    fn marini_murray_gives_the_known_zenith_delay_and_grows_towards_the_horizon() {
        // Standard air at sea level, 532 nm: about 2.4 m at the zenith (Marini and Murray 1973).
        let zenith = marini_murray(std::f64::consts::FRAC_PI_2, 1013.25, 288.15, 50.0, 0.532, 0.7, 0.0);
        assert!((2.3..2.5).contains(&zenith), "{zenith}");
        let low = marini_murray(20f64.to_radians(), 1013.25, 288.15, 50.0, 0.532, 0.7, 0.0);
        // Close to zenith / sin e at 20°.
        assert!((low / (zenith / 20f64.to_radians().sin()) - 1.0).abs() < 0.02, "{low}");
    }
}
