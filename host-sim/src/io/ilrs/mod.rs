//! Satellite laser ranging files of the International Laser Ranging Service (ILRS), for `host-sim
//! track-ilrs`: normal points in the Consolidated Laser Ranging Data format ([`crd`], CRD v1/v2), predictions
//! in the Consolidated Prediction Format ([`cpf`], CPF v1/v2, interpolated), station positions from the
//! `SOLUTION/ESTIMATE` block of a SINEX file ([`sinex`], e.g. the ILRS's SLRF2014), and the reduction of a
//! normal point to what the tracker takes: a one-way geometric range at the bounce time ([`reduction`]),
//! written as a TDM and a configuration for `host-sim track` ([`import`]).
//!
//! Bad input is an [`IlrsError`]: the line, the record field and what is wrong, shown as
//! `file:line: field: message` ([`IlrsError::in_file`]). Records are free-format (fields separated by
//! blanks, as CRD v2 and CPF v2 allow and v1 files satisfy); record types are read case-insensitively.

pub mod cpf;
pub mod crd;
pub mod import;
pub mod reduction;
pub mod sinex;

use crate::error::Error;
use std::fmt;
use std::path::Path;

/// Speed of light (m/s).
pub const SPEED_OF_LIGHT: f64 = 299_792_458.0;

/// The most characters of a value quoted in a message.
const EXCERPT_CHARS: usize = 40;

/// A problem of an ILRS file: 1-based line, field, message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct IlrsError {
    /// Line (1-based; the last line + 1 for a file that ends too early).
    pub line: usize,
    /// The record and field at fault, e.g. `11 time of flight`.
    pub field: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for IlrsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}: {}", self.line, self.field, self.message)
    }
}

impl IlrsError {
    /// The error as bad input of `file`: `file:line: field: message`.
    pub fn in_file(&self, file: &Path) -> Error {
        Error::input(format!("{}:{}: {}: {}", file.display(), self.line, self.field, self.message))
    }
}

/// The error at `line` (the field's name on one line, then cut to twice [`EXCERPT_CHARS`]: a record type
/// may be any text, and a control character is written as an escape of several characters).
pub(crate) fn fail<T>(line: usize, field: &str, message: impl fmt::Display) -> Result<T, IlrsError> {
    let escaped = crate::scenario::one_line(field);
    let mut name: String = escaped.chars().take(2 * EXCERPT_CHARS).collect();
    if escaped.chars().nth(2 * EXCERPT_CHARS).is_some() {
        name.push('…');
    }
    Err(IlrsError { line, field: name, message: crate::scenario::one_line(&message.to_string()) })
}

/// `text` on one line, at most [`EXCERPT_CHARS`] characters (then `…`), for quoting bad input.
fn excerpt(text: &str) -> String {
    let escaped = crate::scenario::one_line(text);
    let mut short: String = escaped.chars().take(EXCERPT_CHARS).collect();
    if escaped.chars().nth(EXCERPT_CHARS).is_some() {
        short.push('…');
    }
    short
}

/// The blank-separated fields of one record line, read by position with the record's name in errors.
pub(crate) struct Fields<'a> {
    line: usize,
    record: String,
    fields: Vec<&'a str>,
}

impl<'a> Fields<'a> {
    /// The fields of `text` (line `line`); the record type is the first, lower-cased.
    pub(crate) fn of(line: usize, text: &'a str) -> Self {
        let fields: Vec<&str> = text.split_whitespace().collect();
        let record = fields.first().map_or_else(String::new, |r| r.to_ascii_lowercase());
        Self { line, record, fields }
    }

    /// The record type (lower case): `h1`, `c0`, `11`, …
    pub(crate) fn record(&self) -> &str {
        &self.record
    }

    /// Field `index` (0 is the record type), named `name` in errors.
    pub(crate) fn text(&self, index: usize, name: &str) -> Result<&'a str, IlrsError> {
        match self.fields.get(index) {
            Some(text) => Ok(text),
            None => fail(self.line, &self.field_name(name), format!("missing (field {index} of the record)")),
        }
    }

    /// Field `index` as a finite number.
    pub(crate) fn number(&self, index: usize, name: &str) -> Result<f64, IlrsError> {
        let text = self.text(index, name)?;
        match text.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => fail(self.line, &self.field_name(name), format!("\"{}\" is not a finite number", excerpt(text))),
        }
    }

    /// Field `index` as a whole number within `range`.
    pub(crate) fn integer(
        &self,
        index: usize,
        name: &str,
        range: std::ops::RangeInclusive<i64>,
    ) -> Result<i64, IlrsError> {
        let text = self.text(index, name)?;
        match text.parse::<i64>() {
            Ok(v) if range.contains(&v) => Ok(v),
            Ok(v) => {
                fail(self.line, &self.field_name(name), format!("{v} is not in [{}, {}]", range.start(), range.end()))
            }
            Err(_) => fail(self.line, &self.field_name(name), format!("\"{}\" is not a whole number", excerpt(text))),
        }
    }

    /// The error `message` about field `name` of this record.
    pub(crate) fn fail<T>(&self, name: &str, message: impl fmt::Display) -> Result<T, IlrsError> {
        fail(self.line, &self.field_name(name), message)
    }

    fn field_name(&self, name: &str) -> String {
        format!("{} {name}", excerpt(&self.record))
    }
}

/// A UTC time as a day number since 1970-01-01 and seconds of that day (the form both formats use, which
/// keeps sub-microsecond digits exact in f64 whatever the year).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DayTime {
    /// Days since 1970-01-01 (MJD − 40587).
    pub day: i64,
    /// Seconds of the day, [0, 86400).
    pub seconds: f64,
}

impl DayTime {
    /// Seconds since the start of day `epoch_day`.
    pub fn since(&self, epoch_day: i64) -> f64 {
        (self.day - epoch_day) as f64 * 86_400.0 + self.seconds
    }

    /// This time moved by `dt` seconds (the day renumbered when it crosses midnight).
    pub fn plus(&self, dt: f64) -> DayTime {
        let seconds = self.seconds + dt;
        let days = (seconds / 86_400.0).floor();
        DayTime { day: self.day + days as i64, seconds: seconds - days * 86_400.0 }
    }
}

/// Days since 1970-01-01 of a Gregorian date, checked; `None` when the date does not exist or lies
/// outside 1950–2099 (the years a two-digit SINEX year can name).
pub fn day_number(year: i64, month: i64, day: i64) -> Option<i64> {
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    let month_days = [31, if leap { 29 } else { 28 }, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31];
    if !(1950..=2099).contains(&year) || !(1..=12).contains(&month) || day < 1 || day > month_days[(month - 1) as usize]
    {
        return None;
    }
    let y = if month <= 2 { year - 1 } else { year };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let doy = (153 * ((month + 9) % 12) + 2) / 5 + day - 1;
    Some(era * 146_097 + yoe * 365 + yoe / 4 - yoe / 100 + doy - 719_468)
}

/// The UTC calendar date `YYYY-MM-DD` of a day number.
pub fn date_of(day: i64) -> String {
    let z = day + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = if m <= 2 { yoe + era * 400 + 1 } else { yoe + era * 400 };
    format!("{y:04}-{m:02}-{d:02}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn day_numbers_match_the_calendar_and_refuse_missing_dates() {
        assert_eq!(day_number(1970, 1, 1), Some(0));
        // MJD 57431 is 2016-02-13.
        assert_eq!(day_number(2016, 2, 13), Some(57_431 - 40_587));
        assert_eq!(date_of(57_431 - 40_587), "2016-02-13");
        assert_eq!(day_number(2016, 2, 30), None);
        assert_eq!(day_number(2015, 2, 29), None);
        assert_eq!(day_number(2100, 1, 1), None);
        let late = DayTime { day: 5, seconds: 86_399.5 }.plus(1.0);
        assert_eq!((late.day, late.seconds), (6, 0.5));
        assert_eq!(late.since(5), 86_400.5);
    }

    #[test]
    fn fields_name_the_record_and_field_in_errors() {
        let f = Fields::of(7, "11 abc");
        let e = f.number(1, "seconds of day").unwrap_err();
        assert_eq!((e.line, e.field.as_str()), (7, "11 seconds of day"));
        assert!(e.message.contains("\"abc\" is not a finite number"), "{}", e.message);
        let missing = f.text(5, "time of flight").unwrap_err();
        assert!(missing.message.contains("missing"), "{}", missing.message);
        let range = Fields::of(1, "h2 X 99999").integer(2, "pad", 1000..=9999).unwrap_err();
        assert!(range.message.contains("not in [1000, 9999]"), "{}", range.message);
    }
}
