//! Exact UTC times for the CCSDS files (TDM, OEM): an [`Instant`] is whole seconds since 1970-01-01 and a
//! decimal fraction kept as digits, so that a scan time (f64 seconds since the scenario epoch) written as
//! `YYYY-MM-DDThh:mm:ss.fff…` and read back is the same f64, bit for bit, and a time read from a file is
//! written back with the digits it was read with.
//!
//! How: the writer ([`Instant::after`]) adds the shortest round-trip decimal form of t (Rust's `{}` of an
//! f64: `2169.6898`, never an exponent) to the epoch's digits, exactly, in decimal; the reader
//! ([`Instant::since`]) subtracts the epoch's digits exactly and parses the difference once (correctly
//! rounded). So `since(after(t)) = t` for every t, and `after(since(x)) = x` for every instant x whose offset
//! from the epoch is the shortest form of its f64, which holds whenever the offset has at most 15
//! significant digits (1 ns resolution within 10⁶ s ≈ 11.5 days of the epoch, 1 µs within 10⁹ s ≈ 31
//! years): no `12:36:09.6897999999…` for a scan read as `12:36:09.6898`. UTC is taken as uniform (no leap
//! seconds: a second of 60 is refused); dates from year 1000 to 9999.

use crate::scenario::v2::Scenario3d;
use crate::sim::time::CalendarTime;
use std::cmp::Ordering;
use std::fmt;

/// The longest fraction of a second read (digits): more than any f64's shortest decimal form needs.
pub const MAX_FRACTION_DIGITS: usize = 1100;

/// The largest time after the epoch written (s): about 31,700 years would leave the calendar range anyway.
const MAX_OFFSET: f64 = 1e11;

/// A UTC instant: whole seconds since 1970-01-01T00:00:00 (no leap seconds) and a fraction in decimal
/// digits without trailing zeros.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Instant {
    seconds: i64,
    fraction: String,
}

impl Ord for Instant {
    fn cmp(&self, other: &Self) -> Ordering {
        // Without trailing zeros, digit strings compare as the fractions they spell.
        self.seconds.cmp(&other.seconds).then_with(|| self.fraction.cmp(&other.fraction))
    }
}

impl PartialOrd for Instant {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Days from 1970-01-01 to the civil date (proleptic Gregorian).
fn days_from_civil(year: i64, month: i64, day: i64) -> i64 {
    let y = if month <= 2 { year - 1 } else { year };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (month + 9) % 12;
    let doy = (153 * mp + 2) / 5 + day - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The civil date of a day count from 1970-01-01.
fn civil_from_days(days: i64) -> (i64, i64, i64) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    (if month <= 2 { yoe + era * 400 + 1 } else { yoe + era * 400 }, month, day)
}

fn days_in_month(year: i64, month: i64) -> i64 {
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    match month {
        2 if leap => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

fn trimmed(mut digits: String) -> String {
    while digits.ends_with('0') {
        digits.pop();
    }
    digits
}

impl Instant {
    /// Parses `YYYY-MM-DDThh:mm:ss[.f…][Z]` (the CCSDS calendar form, UTC).
    ///
    /// # Errors
    /// A short description of what is wrong.
    pub fn parse(text: &str) -> Result<Self, String> {
        let bad = || format!("\"{text}\" is not a time YYYY-MM-DDThh:mm:ss[.fff] (UTC)");
        let time = CalendarTime::parse(text).ok_or_else(bad)?;
        if time.fraction.len() > MAX_FRACTION_DIGITS {
            return Err(format!("\"{text}\": more than {MAX_FRACTION_DIGITS} digits of a second"));
        }
        let (year, month, day) = (i64::from(time.year), i64::from(time.month), i64::from(time.day));
        let (hour, minute, second) = (i64::from(time.hour), i64::from(time.minute), i64::from(time.second));
        let fraction = time.fraction;
        if !(1000..=9999).contains(&year) || !(1..=12).contains(&month) || day < 1 || day > days_in_month(year, month) {
            return Err(format!("\"{text}\": no such date (years 1000 to 9999)"));
        }
        if hour > 23 || minute > 59 || second > 59 {
            return Err(format!("\"{text}\": no such time of day (leap seconds are not supported)"));
        }
        let seconds = days_from_civil(year, month, day) * 86_400 + hour * 3600 + minute * 60 + second;
        Ok(Instant { seconds, fraction: trimmed(fraction.to_string()) })
    }

    /// The instant of a Julian date (UTC), rounded to the nanosecond.
    pub fn from_julian_date(jd: f64) -> Self {
        let ns = ((jd - 2_440_587.5) * 86_400e9).round() as i128;
        let seconds = ns.div_euclid(1_000_000_000) as i64;
        let fraction = trimmed(format!("{:09}", ns.rem_euclid(1_000_000_000)));
        Instant { seconds, fraction }
    }

    /// The scenario's epoch: its `utc` when given (the exact digits), else its Julian date.
    pub fn epoch_of(scenario: &Scenario3d) -> Self {
        scenario
            .epoch
            .utc
            .as_deref()
            .and_then(|utc| Instant::parse(utc).ok())
            .unwrap_or_else(|| Instant::from_julian_date(scenario.epoch_jd()))
    }

    /// `self + t` for t in [0, 1e11] s: the epoch plus the shortest decimal form of t, exactly.
    ///
    /// # Errors
    /// t negative, not finite or too large.
    pub fn after(&self, t: f64) -> Result<Self, String> {
        if !(t.is_finite() && (0.0..=MAX_OFFSET).contains(&t)) {
            return Err(format!(
                "time {} s is not in [0, {MAX_OFFSET}] s after the epoch",
                crate::scenario::Readable(t)
            ));
        }
        // `+ 0.0` turns −0 into 0; Display of an f64 is its shortest round-trip decimal, without exponent.
        let text = format!("{}", t + 0.0);
        let (whole, digits) = text.split_once('.').unwrap_or((&text, ""));
        let whole: i64 = whole.parse().map_err(|_| format!("time {t} s has no whole seconds"))?;
        let (a, b) = (self.fraction.as_bytes(), digits.as_bytes());
        let n = a.len().max(b.len());
        let mut sum = vec![0u8; n];
        let mut carry = 0;
        for i in (0..n).rev() {
            let d = a.get(i).map_or(0, |c| c - b'0') + b.get(i).map_or(0, |c| c - b'0') + carry;
            sum[i] = b'0' + d % 10;
            carry = d / 10;
        }
        let fraction = trimmed(String::from_utf8(sum).unwrap_or_default());
        Ok(Instant { seconds: self.seconds + whole + i64::from(carry), fraction })
    }

    /// The Julian date (UTC) of the instant (to about 20 µs: for leap-second and frame lookups).
    pub fn julian_date(&self) -> f64 {
        let fraction: f64 = format!("0.{}0", self.fraction).parse().unwrap_or(0.0);
        2_440_587.5 + (self.seconds as f64 + fraction) / 86_400.0
    }

    /// `self` moved by `millis` milliseconds, exactly (a time system's offset from UTC).
    pub fn shifted_millis(&self, millis: i64) -> Instant {
        let mut digits = self.fraction.clone();
        while digits.len() < 3 {
            digits.push('0');
        }
        let (head, rest) = digits.split_at(3);
        let total = self.seconds * 1000 + head.parse::<i64>().unwrap_or(0) + millis;
        let fraction = trimmed(format!("{:03}{rest}", total.rem_euclid(1000)));
        Instant { seconds: total.div_euclid(1000), fraction }
    }

    /// Seconds from `epoch` to `self` (the inverse of [`Instant::after`]): the exact decimal difference,
    /// rounded once to the nearest f64; `None` when `self` is before the epoch.
    pub fn since(&self, epoch: &Instant) -> Option<f64> {
        let (a, b) = (self.fraction.as_bytes(), epoch.fraction.as_bytes());
        let n = a.len().max(b.len());
        let mut difference = vec![0u8; n];
        let mut borrow = 0i16;
        for i in (0..n).rev() {
            let mut d = i16::from(a.get(i).map_or(0, |c| c - b'0')) - i16::from(b.get(i).map_or(0, |c| c - b'0'));
            d -= borrow;
            borrow = i16::from(d < 0);
            difference[i] = b'0' + (d + 10 * borrow) as u8;
        }
        let whole = self.seconds.checked_sub(epoch.seconds)?.checked_sub(i64::from(borrow))?;
        if whole < 0 {
            return None;
        }
        let digits = String::from_utf8(difference).unwrap_or_default();
        format!("{whole}.{digits}0").parse().ok()
    }
}

impl fmt::Display for Instant {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (year, month, day) = civil_from_days(self.seconds.div_euclid(86_400));
        let s = self.seconds.rem_euclid(86_400);
        write!(f, "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)?;
        if !self.fraction.is_empty() {
            write!(f, ".{}", self.fraction)?;
        }
        Ok(())
    }
}

/// The current time (for `CREATION_DATE`), to the microsecond.
pub fn now() -> Instant {
    let elapsed = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).unwrap_or_default();
    Instant { seconds: elapsed.as_secs() as i64, fraction: trimmed(format!("{:06}", elapsed.subsec_micros())) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn calendar_round_trip() {
        for text in ["2000-01-01T12:00:00", "1999-12-31T23:59:59.999", "2024-02-29T00:00:00.5", "1000-01-01T00:00:00"] {
            assert_eq!(Instant::parse(text).map(|i| i.to_string()).as_deref(), Ok(text));
        }
        assert_eq!(Instant::parse("1970-01-01T00:00:01Z").map(|i| i.seconds), Ok(1));
        for bad in [
            "2023-02-29T00:00:00",
            "2000-01-01T24:00:00",
            "2000-01-01T23:59:60",
            "2000-01-01 00:00:00",
            "x",
            "2000-01-01T00:00:0\u{e9}",
        ] {
            assert!(Instant::parse(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn offsets_round_trip_bit_exactly() {
        let epochs =
            [Instant::parse("2000-01-01T12:00:00").unwrap(), Instant::parse("2024-03-01T00:00:59.987654321").unwrap()];
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for epoch in &epochs {
            for k in 0..20_000 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let t = match k % 4 {
                    0 => f64::from_bits(x).abs() % 1e9,
                    1 => (x >> 11) as f64 / (1u64 << 53) as f64 * 86_400.0,
                    2 => (x % 100_000) as f64 * 0.1,
                    _ => f64::from_bits(x).abs() % 1.0,
                };
                if !t.is_finite() {
                    continue;
                }
                let at = epoch.after(t).unwrap();
                let back = Instant::parse(&at.to_string()).unwrap().since(epoch).unwrap();
                assert_eq!(back.to_bits(), t.to_bits(), "t = {t:e}, written {at}");
            }
        }
        assert_eq!(Instant::parse("1999-12-31T23:59:59").unwrap().since(&epochs[0]), None);
        assert!(epochs[0].after(-1.0).is_err());
    }

    /// Issue 29 item 6: a time read from a file (a TDM line, a scenario's seconds) is written back with the
    /// digits it was read with, not `12:36:09.6897999999…` (the epoch plus ⌊t⌋ plus the f64 t − ⌊t⌋).
    #[test]
    fn times_read_are_written_back_with_their_digits() {
        let epochs =
            [Instant::parse("2024-03-01T12:00:00").unwrap(), Instant::parse("2010-06-30T23:59:59.25").unwrap()];
        for epoch in &epochs {
            // Offsets of up to 15 significant digits: ms over 30 years, µs over 3 years, ns over 11 days.
            for offset in ["2169.6898", "0.001", "86399.999999", "999999.123456789", "946080000.123", "94608000.123456"]
            {
                let t: f64 = offset.parse().unwrap();
                let written = epoch.after(t).unwrap();
                assert_eq!(written.since(epoch).map(f64::to_bits), Some(t.to_bits()), "{offset}");
                let text = written.to_string();
                assert!(!text.contains("99999999") && !text.contains("00000000"), "{epoch} + {offset} = {text}");
                if epoch.fraction.is_empty() {
                    assert_eq!(text.split_once('.').map(|(_, f)| f), offset.split_once('.').map(|(_, f)| f));
                }
            }
        }
        // Instants as a TDM gives them: read (seconds since the epoch), then written, are the same text
        // (offsets of at most 15 significant digits).
        let cases = [
            (
                "2024-03-01T12:00:00",
                ["2024-03-01T12:36:09.6898", "2024-03-12T09:46:39.123456789", "2027-01-01T00:00:00.5"],
            ),
            (
                "2010-06-30T23:59:59.25",
                ["2010-07-01T00:36:09.6898", "2010-07-05T00:00:00.000001", "2024-03-13T13:46:39.125"],
            ),
        ];
        for (epoch, texts) in cases {
            let epoch = Instant::parse(epoch).unwrap();
            for text in texts {
                let t = Instant::parse(text).unwrap().since(&epoch).unwrap();
                assert_eq!(epoch.after(t).unwrap().to_string(), text, "{epoch}");
            }
        }
        let noon = &epochs[0];
        assert_eq!(noon.after(2169.6898).unwrap().to_string(), "2024-03-01T12:36:09.6898");
    }
}
