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

/// A calendar date and time of day as written `YYYY-MM-DDThh:mm:ss[.f…][Z]` (ISO 8601, the CCSDS calendar
/// form): the one reader of UTC times in host-sim. It reads the fields and nothing more; each format checks the
/// ranges it allows ([`CalendarTime::is_valid`], its own years and fraction digits).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CalendarTime<'a> {
    /// Year, four digits.
    pub year: i32,
    /// Month, two digits (not yet checked to be 1–12).
    pub month: u32,
    /// Day of the month, two digits (not yet checked against the month).
    pub day: u32,
    /// Hour, two digits.
    pub hour: u32,
    /// Minute, two digits.
    pub minute: u32,
    /// Whole seconds, two digits.
    pub second: u32,
    /// The digits after the decimal point (empty when there is none).
    pub fraction: &'a str,
    /// The seconds as written, `ss[.f…]`.
    pub seconds_text: &'a str,
}

impl<'a> CalendarTime<'a> {
    /// Reads `YYYY-MM-DDThh:mm:ss[.f…][Z]`: fixed-width digit fields, a fraction of at least one digit when
    /// the point is written. `None` for any other form.
    pub fn parse(text: &'a str) -> Option<Self> {
        let body = text.strip_suffix('Z').unwrap_or(text);
        let b = body.as_bytes();
        if b.len() < 19 || b[4] != b'-' || b[7] != b'-' || b[10] != b'T' || b[13] != b':' || b[16] != b':' {
            return None;
        }
        let number = |from: usize, to: usize| -> Option<u32> {
            let field = body.get(from..to)?;
            if field.bytes().all(|c| c.is_ascii_digit()) { field.parse().ok() } else { None }
        };
        let fraction = match body.get(19..)? {
            "" => "",
            rest => {
                let digits = rest.strip_prefix('.')?;
                if digits.is_empty() || !digits.bytes().all(|c| c.is_ascii_digit()) {
                    return None;
                }
                digits
            }
        };
        Some(CalendarTime {
            year: i32::try_from(number(0, 4)?).ok()?,
            month: number(5, 7)?,
            day: number(8, 10)?,
            hour: number(11, 13)?,
            minute: number(14, 16)?,
            second: number(17, 19)?,
            fraction,
            seconds_text: body.get(17..)?,
        })
    }

    /// Whether the date exists in the Gregorian calendar and the time of day is one (no leap second).
    pub fn is_valid(&self) -> bool {
        let leap = (self.year % 4 == 0 && self.year % 100 != 0) || self.year % 400 == 0;
        let month_days = [31, if leap { 29 } else { 28 }, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
        (1..=12).contains(&self.month)
            && self.day >= 1
            && self.day <= month_days[(self.month.max(1) - 1) as usize]
            && self.hour < 24
            && self.minute < 60
            && self.second < 60
    }
}

/// Parses `YYYY-MM-DDTHH:MM:SS[.fff][Z]` (UTC, [`CalendarTime`]) into a Julian date.
///
/// # Errors
/// [`SsaError::BadEpoch`] for any other form, a field out of range, or a year outside 1901–2099.
pub fn parse_iso8601(text: &str) -> Result<f64, SsaError> {
    let time = CalendarTime::parse(text).ok_or(SsaError::BadEpoch)?;
    if !(1901..=2099).contains(&time.year) || !time.is_valid() {
        return Err(SsaError::BadEpoch);
    }
    let second: f64 = time.seconds_text.parse().map_err(|_| SsaError::BadEpoch)?;
    Ok(julian_date(time.year, time.month, time.day, time.hour, time.minute, second))
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
