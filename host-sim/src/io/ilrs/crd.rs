//! A reader of ILRS normal points in the Consolidated Laser Ranging Data format (CRD v1 and v2, ILRS
//! "Consolidated Laser Ranging Data Format Version 2.01", 2019): per pass (H1 … H8) the station (H2), the
//! target (H3), the pass's flags (H4), each system configuration's wavelength (C0), the meteorological
//! records (20) and the normal points (11).
//!
//! Read: H1 (format `CRD`, version 1 or 2), H2 (station name and CDP pad number), H3 (target name), H4
//! (data type 1, normal points; start time; whether troposphere, centre of mass and station delay are
//! applied; range type), C0 (wavelength in nm per configuration), 20 (pressure hPa, temperature K,
//! humidity %), 11 (seconds of day, two-way time of flight in s, configuration, epoch event), H8, H9.
//! Checked for their place and ignored: H5, C1–C7, 12, 21, 30, 40–42, 50, 60, 9x (user records) and 00
//! (comments). Refused: full-rate or sampled engineering data (H4 data type 0 or 2, records 10), records of
//! unknown type, a record outside a pass, a pass without H2, H3 or H4.
//!
//! Times are UTC: a record's seconds of day count from the midnight of H4's start date, or of the next day
//! when they are more than 12 h before H4's start (a pass crossing midnight).

use super::{DayTime, Fields, IlrsError, day_number, fail};

/// One normal point (record 11).
#[derive(Debug, Clone, PartialEq)]
pub struct NormalPoint {
    /// Its line.
    pub line: usize,
    /// Its epoch (UTC), the event `epoch_event` names.
    pub time: DayTime,
    /// Two-way time of flight (s), > 0.
    pub time_of_flight: f64,
    /// The system configuration (C0's id).
    pub configuration: String,
    /// What `time` is: 0 ground receive, 1 spacecraft bounce, 2 ground transmit (two-way ranges).
    pub epoch_event: u8,
}

/// One meteorological record (20).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Meteo {
    /// Its epoch (UTC).
    pub time: DayTime,
    /// Surface pressure (hPa).
    pub pressure_hpa: f64,
    /// Surface temperature (K).
    pub temperature_k: f64,
    /// Relative humidity (%).
    pub humidity_percent: f64,
}

/// What H4 says is already in the times of flight.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Applied {
    /// The tropospheric refraction correction.
    pub troposphere: bool,
    /// The target's centre-of-mass correction.
    pub centre_of_mass: bool,
    /// The station's system delay (calibration).
    pub station_delay: bool,
}

/// One pass: H1 … H8.
#[derive(Debug, Clone, PartialEq)]
pub struct Pass {
    /// Line of its H4.
    pub line: usize,
    /// The station's name (H2), e.g. `YARL`.
    pub station: String,
    /// The station's CDP pad number (H2), e.g. 7090.
    pub pad: u32,
    /// The target's name (H3).
    pub target: String,
    /// The pass's start (H4).
    pub start: DayTime,
    /// What the times of flight already contain.
    pub applied: Applied,
    /// Wavelength (nm) per system configuration (C0).
    pub wavelengths: Vec<(String, f64)>,
    /// Meteorological records, in file order.
    pub meteo: Vec<Meteo>,
    /// Normal points, in file order.
    pub points: Vec<NormalPoint>,
}

impl Pass {
    /// The wavelength (nm) of configuration `id`.
    pub fn wavelength(&self, id: &str) -> Option<f64> {
        self.wavelengths.iter().find(|(c, _)| c == id).map(|&(_, w)| w)
    }

    /// The meteorological record in force at `t` (s since `epoch_day`): the last one at or before it, or
    /// the pass's first when none precedes it.
    pub fn meteo_at(&self, t: f64, epoch_day: i64) -> Option<&Meteo> {
        self.meteo.iter().rev().find(|m| m.time.since(epoch_day) <= t).or(self.meteo.first())
    }
}

/// The headers read so far of the pass being read.
#[derive(Default)]
struct Open {
    station: Option<(String, u32)>,
    target: Option<String>,
    pass: Option<Pass>,
    /// Line of the H1 that opened it.
    line: usize,
}

/// Record types checked for their place and not used.
const IGNORED: &[&str] =
    &["h5", "c1", "c2", "c3", "c4", "c5", "c6", "c7", "12", "21", "30", "40", "41", "42", "50", "60"];

/// Parses a CRD file of normal points.
///
/// # Errors
/// The first problem: a malformed or misplaced record, an unknown record type, data other than normal
/// points, a date that does not exist, a time of flight not in (0, 10) s.
pub fn parse(text: &str) -> Result<Vec<Pass>, IlrsError> {
    let mut passes = vec![];
    let mut open: Option<Open> = None;
    let mut last = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        last = line;
        let f = Fields::of(line, raw);
        let record = f.record().to_string();
        if record.is_empty() || record == "00" || (record.len() == 2 && record.starts_with('9')) {
            continue;
        }
        if record == "h1" {
            if open.is_some() {
                return fail(line, "h1", "a new pass before the previous one's H8");
            }
            header_h1(&f)?;
            open = Some(Open { line, ..Open::default() });
            continue;
        }
        if record == "h9" {
            if open.is_some() {
                return fail(line, "h9", "end of file inside a pass (H8 missing)");
            }
            return if passes.is_empty() { fail(line, "h9", "no pass in the file") } else { Ok(passes) };
        }
        let Some(current) = open.as_mut() else {
            return fail(line, &record, "a record outside a pass (H1 … H8)");
        };
        if record == "h8" {
            let Some(pass) = current.pass.take() else { return fail(line, "h8", "a pass without H4") };
            passes.push(pass);
            open = None;
            continue;
        }
        pass_record(current, &f, &record)?;
    }
    match open {
        Some(o) => fail(last + 1, "h8", format!("the file ends inside the pass opened on line {}", o.line)),
        None if passes.is_empty() => fail(last + 1, "h1", "no pass in the file"),
        None => Ok(passes),
    }
}

/// H1: the format and its version.
fn header_h1(f: &Fields) -> Result<(), IlrsError> {
    if !f.text(1, "format")?.eq_ignore_ascii_case("CRD") {
        return f.fail("format", "not a CRD file (H1 must say CRD)");
    }
    f.integer(2, "version", 1..=2)?;
    Ok(())
}

/// A record inside a pass (after H1, before H8).
fn pass_record(current: &mut Open, f: &Fields, record: &str) -> Result<(), IlrsError> {
    match record {
        "h2" => {
            let name = f.text(1, "station name")?.to_string();
            let pad = f.integer(2, "pad number", 1000..=9999)? as u32;
            current.station = Some((name, pad));
        }
        "h3" => current.target = Some(f.text(1, "target name")?.to_string()),
        "h4" => current.pass = Some(header_h4(current, f)?),
        _ => {
            let Some(pass) = current.pass.as_mut() else {
                return f.fail("record", "a configuration or data record before H4");
            };
            match record {
                "c0" => {
                    let wavelength = f.number(2, "wavelength")?;
                    if !(100.0..=20_000.0).contains(&wavelength) {
                        return f.fail("wavelength", format!("{wavelength} nm is not in [100, 20000]"));
                    }
                    pass.wavelengths.push((f.text(3, "system configuration id")?.to_string(), wavelength));
                }
                "20" => pass.meteo.push(meteo(pass, f)?),
                "11" => pass.points.push(normal_point(pass, f)?),
                "10" => return f.fail("record", "full-rate data is not supported (normal points, records 11)"),
                _ if IGNORED.contains(&record) => {}
                _ => return f.fail("record", "unknown record type"),
            }
        }
    }
    Ok(())
}

/// H4: the pass's data type, start and flags, with the H2 and H3 read before it.
fn header_h4(current: &Open, f: &Fields) -> Result<Pass, IlrsError> {
    let Some((station, pad)) = current.station.clone() else { return f.fail("record", "H4 before H2") };
    let Some(target) = current.target.clone() else { return f.fail("record", "H4 before H3") };
    if f.integer(1, "data type", 0..=2)? != 1 {
        return f.fail("data type", "not normal points (data type 1): full-rate and sampled data are not supported");
    }
    let year = f.integer(2, "start year", 1950..=2099)?;
    let month = f.integer(3, "start month", 1..=12)?;
    let day = f.integer(4, "start day", 1..=31)?;
    let Some(day) = day_number(year, month, day) else {
        return f.fail("start day", format!("{year}-{month:02}-{day:02} is not a date"));
    };
    let hms = [
        f.integer(5, "start hour", 0..=23)?,
        f.integer(6, "start minute", 0..=59)?,
        f.integer(7, "start second", 0..=60)?,
    ];
    let flag = |i: usize, name: &str| f.integer(i, name, 0..=1).map(|v| v == 1);
    let applied = Applied {
        troposphere: flag(15, "troposphere correction applied")?,
        centre_of_mass: flag(16, "centre of mass correction applied")?,
        station_delay: flag(18, "station system delay applied")?,
    };
    if f.integer(20, "range type", 0..=4)? != 2 {
        return f.fail("range type", "not two-way ranges (range type 2)");
    }
    Ok(Pass {
        line: f.line,
        station,
        pad,
        target,
        start: DayTime { day, seconds: (hms[0] * 3600 + hms[1] * 60 + hms[2]) as f64 },
        applied,
        wavelengths: vec![],
        meteo: vec![],
        points: vec![],
    })
}

/// The time of a record's seconds of day in `pass` (next day when more than 12 h before the start).
fn time_of(pass: &Pass, f: &Fields) -> Result<DayTime, IlrsError> {
    let seconds = f.number(1, "seconds of day")?;
    if !(0.0..86_400.0).contains(&seconds) {
        return f.fail("seconds of day", format!("{seconds} is not in [0, 86400)"));
    }
    let next = seconds + 43_200.0 < pass.start.seconds;
    Ok(DayTime { day: pass.start.day + i64::from(next), seconds })
}

/// Record 20.
fn meteo(pass: &Pass, f: &Fields) -> Result<Meteo, IlrsError> {
    let m = Meteo {
        time: time_of(pass, f)?,
        pressure_hpa: f.number(2, "pressure")?,
        temperature_k: f.number(3, "temperature")?,
        humidity_percent: f.number(4, "humidity")?,
    };
    if !(500.0..=1100.0).contains(&m.pressure_hpa) {
        return f.fail("pressure", format!("{} hPa is not in [500, 1100]", m.pressure_hpa));
    }
    if !(180.0..=340.0).contains(&m.temperature_k) {
        return f.fail("temperature", format!("{} K is not in [180, 340]", m.temperature_k));
    }
    if !(0.0..=100.0).contains(&m.humidity_percent) {
        return f.fail("humidity", format!("{} % is not in [0, 100]", m.humidity_percent));
    }
    Ok(m)
}

/// Record 11.
fn normal_point(pass: &Pass, f: &Fields) -> Result<NormalPoint, IlrsError> {
    let time = time_of(pass, f)?;
    let time_of_flight = f.number(2, "time of flight")?;
    if !(time_of_flight > 0.0 && time_of_flight < 10.0) {
        return f.fail("time of flight", format!("{time_of_flight} s is not in (0, 10)"));
    }
    let configuration = f.text(3, "system configuration id")?.to_string();
    let epoch_event = f.integer(4, "epoch event", 0..=4)? as u8;
    if epoch_event > 2 {
        return f.fail("epoch event", format!("{epoch_event} is a one-way epoch (two-way: 0, 1 or 2)"));
    }
    Ok(NormalPoint { line: f.line, time, time_of_flight, configuration, epoch_event })
}

#[cfg(test)]
mod tests {
    use super::*;

    const PASS: &str = "\
h1 CRD  1 2016  2 13 14
h2 YARL       7090  5 13 3
h3 lageos2     9207002 5986    22195 0 1
h4  1 2016  2 13 23 42 16 2016  2 14  0  6 46  0 0 0 0 1 0 2 0
c0 0  532.000 std la1 mcp ti1
00 a comment
20 85382.401  983.70 301.40  24. 0
11 85382.400562600000     0.039237325685 std 2  120.0     94   57.0   0.183  -0.536      -1.0  15.67 0
20   103.601  983.70 301.40  24. 0
11   103.600567399997     0.038462695003 std 2  120.0     39   65.0   0.083  -0.301      -1.0   6.50 0
50 std   57.5   0.002   2.862   -1.0 0
h8
h9
";

    #[test]
    fn a_pass_is_read_with_its_flags_meteo_and_normal_points() {
        let passes = parse(PASS).expect("valid");
        assert_eq!(passes.len(), 1);
        let p = &passes[0];
        assert_eq!((p.station.as_str(), p.pad, p.target.as_str()), ("YARL", 7090, "lageos2"));
        assert_eq!(p.applied, Applied { troposphere: false, centre_of_mass: false, station_delay: true });
        assert_eq!(p.wavelength("std"), Some(532.0));
        assert_eq!(p.points.len(), 2);
        assert_eq!(p.points[0].time_of_flight, 0.039237325685);
        assert_eq!(p.points[0].epoch_event, 2);
        // The second point is after midnight: the next day.
        assert_eq!(p.points[1].time.day, p.start.day + 1);
        assert_eq!(p.points[1].line, 10);
        let day = p.start.day;
        // The record 0.4 ms after the second point is not yet in force at it.
        assert_eq!(p.meteo_at(p.points[1].time.since(day), day).map(|m| m.time.seconds), Some(85_382.401));
        assert_eq!(p.meteo_at(p.points[1].time.since(day) + 1.0, day).map(|m| m.time.seconds), Some(103.601));
    }

    #[test]
    fn control_characters_in_a_record_keep_the_message_short() {
        // Found by the fuzz target `ilrs`: 72 control characters in a record type, each escaped as
        // `\u{e}`, made a message of over 400 characters when the record was cut before it was escaped.
        let text = format!("h{}1 CPF  1 SGF\n", "\u{e}".repeat(72));
        let message = parse(&text).expect_err("not a record").to_string();
        assert!(message.chars().count() < 200 && !message.contains('\n'), "{message}");
        assert!(message.contains("\\u{e}") && message.contains('…'), "{message}");
    }

    fn error_of(from: &str, to: &str) -> IlrsError {
        let text = PASS.replacen(from, to, 1);
        assert_ne!(text, PASS, "{from} is in the sample");
        parse(&text).expect_err(to)
    }

    #[test]
    fn malformed_records_name_their_line_and_field() {
        let cases = [
            ("0.039237325685", "abc", 8, "11 time of flight", "\"abc\" is not a finite number"),
            ("0.039237325685", "-0.1", 8, "11 time of flight", "not in (0, 10)"),
            ("std 2  120.0     94", "std 3  120.0     94", 8, "11 epoch event", "one-way"),
            ("85382.400562600000", "86400.5", 8, "11 seconds of day", "not in [0, 86400)"),
            ("h4  1 2016", "h4  0 2016", 4, "h4 data type", "not normal points"),
            ("2016  2 13 23 42", "2016  2 30 23 42", 4, "h4 start day", "not a date"),
            ("0 1 0 2 0\n", "0 1 0 1 0\n", 4, "h4 range type", "two-way"),
            ("983.70 301.40  24.", "98.70 301.40  24.", 7, "20 pressure", "not in [500, 1100]"),
            ("CRD  1", "CPF  1", 1, "h1 format", "not a CRD file"),
            ("h2 YARL       7090", "h2 YARL       70", 2, "h2 pad number", "not in [1000, 9999]"),
            ("50 std", "77 std", 11, "77 record", "unknown record type"),
            ("50 std", "10 std", 11, "10 record", "full-rate"),
        ];
        for (from, to, line, field, message) in cases {
            let e = error_of(from, to);
            assert_eq!((e.line, e.field.as_str()), (line, field), "{to}: {e}");
            assert!(e.message.contains(message), "{to}: {}", e.message);
        }
    }

    #[test]
    fn misplaced_and_missing_records_are_refused() {
        let e = error_of("h8\n", "");
        assert!(e.message.contains("inside a pass") || e.message.contains("ends inside"), "{e}");
        let before = error_of("h3 lageos2", "h3x lageos2");
        assert_eq!(before.field, "h3x record", "{before}");
        let outside = parse("11 1.0 0.04 std 2\n").unwrap_err();
        assert!(outside.message.contains("outside a pass"), "{outside}");
        assert!(parse("").unwrap_err().message.contains("no pass"));
        let no_h4 = error_of("h4  1 2016  2 13 23 42 16 2016  2 14  0  6 46  0 0 0 0 1 0 2 0\n", "");
        assert!(no_h4.message.contains("before H4"), "{no_h4}");
    }
}
