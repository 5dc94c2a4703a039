//! UTC and the Earth's rotation: Julian dates, the ISO-8601 UTC form, GMST (IAU-82) and the Earth rotation angle.

use super::error::SsaError;
use core::f64::consts::TAU;

/// Earth rotation rate ω_E (rad/s).
pub const EARTH_ROTATION_RATE: f64 = 7.292_115e-5;

/// The Julian date of a Gregorian UTC calendar time (valid 1900-03-01 to 2100-02-28).
pub fn julian_date(year: i32, month: u32, day: u32, hour: u32, minute: u32, second: f64) -> f64 {
    let (y, m) = (year as f64, month as f64);
    let day_number = 367.0 * y - ((7.0 * (y + ((m + 9.0) / 12.0).floor())) * 0.25).floor()
        + (275.0 * m / 9.0).floor()
        + day as f64
        + 1_721_013.5;
    day_number + (hour as f64 * 3600.0 + minute as f64 * 60.0 + second) / 86_400.0
}

/// Parses `YYYY-MM-DDTHH:MM:SS[.fff][Z]` (UTC) into a Julian date.
///
/// # Errors
/// [`SsaError::BadEpoch`] for any other form, a field out of range, or a year outside 1901–2099.
pub fn parse_iso8601(text: &str) -> Result<f64, SsaError> {
    let text = text.strip_suffix('Z').unwrap_or(text);
    let (date, time) = text.split_once('T').ok_or(SsaError::BadEpoch)?;
    let date: Vec<&str> = date.split('-').collect();
    let time: Vec<&str> = time.split(':').collect();
    if date.len() != 3 || time.len() != 3 || date[0].len() != 4 || date[1].len() != 2 || date[2].len() != 2 {
        return Err(SsaError::BadEpoch);
    }
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if !date.iter().all(|s| digits(s)) || !digits(time[0]) || !digits(time[1]) {
        return Err(SsaError::BadEpoch);
    }
    let second_ok = time[2].bytes().all(|b| b.is_ascii_digit() || b == b'.') && time[2].len() >= 2;
    if !second_ok {
        return Err(SsaError::BadEpoch);
    }
    let year: i32 = date[0].parse().map_err(|_| SsaError::BadEpoch)?;
    let month: u32 = date[1].parse().map_err(|_| SsaError::BadEpoch)?;
    let day: u32 = date[2].parse().map_err(|_| SsaError::BadEpoch)?;
    let hour: u32 = time[0].parse().map_err(|_| SsaError::BadEpoch)?;
    let minute: u32 = time[1].parse().map_err(|_| SsaError::BadEpoch)?;
    let second: f64 = time[2].parse().map_err(|_| SsaError::BadEpoch)?;
    let leap = year % 4 == 0; // exact for 1901–2099
    let month_days = [31, if leap { 29 } else { 28 }, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    let valid = (1901..=2099).contains(&year)
        && (1..=12).contains(&month)
        && day >= 1
        && day <= month_days[(month.max(1) - 1) as usize]
        && hour < 24
        && minute < 60
        && (0.0..60.0).contains(&second);
    if !valid {
        return Err(SsaError::BadEpoch);
    }
    Ok(julian_date(year, month, day, hour, minute, second))
}

/// Greenwich mean sidereal time (rad, in [0, 2π)) at a UT1 Julian date: the IAU-82 polynomial in
/// Julian centuries T from J2000, GMST = 67310.54841 s + (876600 h + 8640184.812866 s) T
/// + 0.093104 s T² − 6.2e-6 s T³, as SGP4 uses.
pub fn gmst(jd_ut1: f64) -> f64 {
    let t = (jd_ut1 - 2_451_545.0) / 36_525.0;
    let seconds = 67_310.548_41 + (876_600.0 * 3600.0 + 8_640_184.812_866) * t + 0.093_104 * t * t - 6.2e-6 * t * t * t;
    // 1 s of time = 1/240 degree.
    (seconds / 240.0).to_radians().rem_euclid(TAU)
}

/// The Earth rotation angle θ(t) = GMST(epoch) + ω_E t (rad, in [0, 2π)), `t` in s since the epoch.
pub fn earth_rotation_angle(epoch_jd: f64, t: f64) -> f64 {
    (gmst(epoch_jd) + EARTH_ROTATION_RATE * t).rem_euclid(TAU)
}
