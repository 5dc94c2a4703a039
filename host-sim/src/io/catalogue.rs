//! Catalogue input: two- and three-line element sets (TLE, with Alpha-5 catalogue numbers) and CCSDS OMM
//! mean elements (CelesTrak's JSON and CSV) read into one [`CatalogueEntry`], then into the `sgp4` crate's
//! elements and propagated in AFSPC-compatibility mode (WGS-72), the mode of the Vallado et al. (2006)
//! verification cases (`sgp4_check`).
//!
//! Every parser is ours: each field is checked (columns, checksums, ranges) and a bad file is a
//! [`CatalogueError`] naming the file, the line and the keyword (TLE: the line and columns of the field),
//! printed by the CLI as one line with exit code 2. Files are read through [`crate::scenario::MAX_FILE_BYTES`].
//!
//! Frame (docs/maths.md §6.8, "Catalogue objects"): SGP4's TEME is taken as the tracker's inertial frame;
//! [`Satellite::tracker_state`] converts the tracker time t (s since the scenario epoch) into minutes since
//! the element set's epoch and returns SGP4's TEME position and velocity (km, km/s) unchanged.

use crate::Error;
use sgp4::chrono::{NaiveDate, NaiveDateTime, NaiveTime};
use std::fmt;
use std::path::Path;

/// The longest name line of a three-line element set (CelesTrak's are 24 characters).
pub const MAX_NAME_CHARS: usize = 128;

/// A bad catalogue file: where and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CatalogueError {
    /// The file (as given), or a label such as `<input>`.
    pub file: String,
    /// Line number, from 1 (0 when the whole file is at fault).
    pub line: usize,
    /// The keyword (OMM) or the TLE line and columns of the field.
    pub keyword: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for CatalogueError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}: {}", self.file, self.line, self.keyword, self.message)
    }
}

impl std::error::Error for CatalogueError {}

impl From<CatalogueError> for Error {
    fn from(e: CatalogueError) -> Self {
        Error::input(e)
    }
}

/// One object's mean elements, as read from a TLE or an OMM (units of the TLE: degrees, revolutions per day).
#[derive(Debug, Clone, PartialEq)]
pub struct CatalogueEntry {
    /// Object name (the name line of a 3LE, OMM `OBJECT_NAME`).
    pub name: Option<String>,
    /// Catalogue number (Alpha-5 "A0001" is 100001).
    pub norad_id: u64,
    /// International designator as written (TLE columns 10-17, OMM `OBJECT_ID`).
    pub international_designator: Option<String>,
    /// 'U', 'C' or 'S'.
    pub classification: char,
    /// Epoch (UTC).
    pub epoch: NaiveDateTime,
    /// First derivative of the mean motion divided by two (rev/day²).
    pub mean_motion_dot: f64,
    /// Second derivative of the mean motion divided by six (rev/day³).
    pub mean_motion_ddot: f64,
    /// B* drag term (1/earth radii).
    pub bstar: f64,
    /// Inclination (degrees, [0, 180]).
    pub inclination: f64,
    /// Right ascension of the ascending node (degrees, [0, 360]).
    pub right_ascension: f64,
    /// Eccentricity, [0, 1).
    pub eccentricity: f64,
    /// Argument of perigee (degrees, [0, 360]).
    pub argument_of_perigee: f64,
    /// Mean anomaly (degrees, [0, 360]).
    pub mean_anomaly: f64,
    /// Kozai mean motion (rev/day, > 0).
    pub mean_motion: f64,
    /// Element set number.
    pub element_set_number: u64,
    /// Revolution number at epoch.
    pub revolution_number: u64,
    /// Ephemeris type (0 for SGP4 element sets).
    pub ephemeris_type: u8,
    /// The line of its file where the entry starts.
    pub line: usize,
}

/// The fields whose range [`CatalogueEntry::check_ranges`] checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Field {
    Inclination,
    RightAscension,
    Eccentricity,
    ArgumentOfPerigee,
    MeanAnomaly,
    MeanMotion,
}

impl Field {
    fn omm(self) -> &'static str {
        match self {
            Field::Inclination => "INCLINATION",
            Field::RightAscension => "RA_OF_ASC_NODE",
            Field::Eccentricity => "ECCENTRICITY",
            Field::ArgumentOfPerigee => "ARG_OF_PERICENTER",
            Field::MeanAnomaly => "MEAN_ANOMALY",
            Field::MeanMotion => "MEAN_MOTION",
        }
    }

    fn tle(self) -> &'static str {
        match self {
            Field::Inclination => "line 2 columns 9-16 (inclination)",
            Field::RightAscension => "line 2 columns 18-25 (right ascension)",
            Field::Eccentricity => "line 2 columns 27-33 (eccentricity)",
            Field::ArgumentOfPerigee => "line 2 columns 35-42 (argument of perigee)",
            Field::MeanAnomaly => "line 2 columns 44-51 (mean anomaly)",
            Field::MeanMotion => "line 2 columns 53-63 (mean motion)",
        }
    }
}

impl CatalogueEntry {
    /// Angles in their ranges, 0 ≤ e < 1, a positive finite mean motion.
    fn check_ranges(&self) -> Result<(), (Field, String)> {
        let angle = |field, v: f64, max: f64| {
            if (0.0..=max).contains(&v) { Ok(()) } else { Err((field, format!("{v} is not in [0, {max}] degrees"))) }
        };
        angle(Field::Inclination, self.inclination, 180.0)?;
        angle(Field::RightAscension, self.right_ascension, 360.0)?;
        angle(Field::ArgumentOfPerigee, self.argument_of_perigee, 360.0)?;
        angle(Field::MeanAnomaly, self.mean_anomaly, 360.0)?;
        if !(0.0..1.0).contains(&self.eccentricity) {
            return Err((Field::Eccentricity, format!("{} is not in [0, 1)", self.eccentricity)));
        }
        if !(self.mean_motion > 0.0 && self.mean_motion.is_finite()) {
            return Err((Field::MeanMotion, format!("{} rev/day is not finite and > 0", self.mean_motion)));
        }
        Ok(())
    }

    /// The `sgp4` crate's elements.
    pub fn to_sgp4(&self) -> sgp4::Elements {
        sgp4::Elements {
            object_name: self.name.clone(),
            international_designator: self.international_designator.clone(),
            norad_id: self.norad_id,
            classification: match self.classification {
                'C' => sgp4::Classification::Classified,
                'S' => sgp4::Classification::Secret,
                _ => sgp4::Classification::Unclassified,
            },
            datetime: self.epoch,
            mean_motion_dot: self.mean_motion_dot,
            mean_motion_ddot: self.mean_motion_ddot,
            drag_term: self.bstar,
            element_set_number: self.element_set_number,
            inclination: self.inclination,
            right_ascension: self.right_ascension,
            eccentricity: self.eccentricity,
            argument_of_perigee: self.argument_of_perigee,
            mean_anomaly: self.mean_anomaly,
            mean_motion: self.mean_motion,
            revolution_number: self.revolution_number,
            ephemeris_type: self.ephemeris_type,
        }
    }
}

/// An SGP4 propagator of one catalogue entry (WGS-72, AFSPC-compatibility mode).
#[derive(Debug, Clone)]
pub struct Satellite {
    /// The elements it was built from.
    pub entry: CatalogueEntry,
    constants: sgp4::Constants,
}

/// Why SGP4 cannot give a state: its initialisation or its propagation failed.
#[derive(Debug, Clone, PartialEq)]
pub enum PropagationError {
    /// The epoch elements are refused (`sgp4::ElementsError`).
    Elements(sgp4::ElementsError),
    /// The propagation diverged (`sgp4::Error`).
    Propagation(sgp4::Error),
}

impl PropagationError {
    /// A short name of the SGP4 error (those of the verification data's expected file).
    pub fn kind(&self) -> &'static str {
        match self {
            PropagationError::Elements(sgp4::ElementsError::KozaiElementsError(
                sgp4::KozaiElementsError::NegativeKozaiMeanMotion,
            )) => "negative-kozai-mean-motion",
            PropagationError::Elements(sgp4::ElementsError::KozaiElementsError(
                sgp4::KozaiElementsError::NegativeBrouwerMeanMotion,
            )) => "negative-brouwer-mean-motion",
            PropagationError::Elements(sgp4::ElementsError::OutOfRangeEpochEccentricity(_)) => {
                "epoch-eccentricity-out-of-range"
            }
            PropagationError::Propagation(sgp4::Error::OutOfRangeEccentricity { .. }) => "diverging-eccentricity",
            PropagationError::Propagation(sgp4::Error::OutOfRangePerturbedEccentricity { .. }) => {
                "diverging-perturbed-eccentricity"
            }
            PropagationError::Propagation(sgp4::Error::NegativeSemiLatusRectum { .. }) => "negative-semi-latus-rectum",
        }
    }
}

impl fmt::Display for PropagationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PropagationError::Elements(e) => write!(f, "SGP4 initialisation: {e}"),
            PropagationError::Propagation(e) => write!(f, "SGP4: {e}"),
        }
    }
}

/// Position and velocity (km, km/s).
pub type State = ([f64; 3], [f64; 3]);

impl Satellite {
    /// SGP4's epoch quantities of `entry` (WGS-72, AFSPC epoch and sidereal time).
    pub fn new(entry: CatalogueEntry) -> Result<Self, PropagationError> {
        let constants = sgp4::Constants::from_elements_afspc_compatibility_mode(&entry.to_sgp4())
            .map_err(PropagationError::Elements)?;
        Ok(Satellite { entry, constants })
    }

    /// SGP4's TEME position and velocity (km, km/s) `minutes` after the element set's epoch.
    pub fn teme(&self, minutes: f64) -> Result<State, PropagationError> {
        let p = self
            .constants
            .propagate_afspc_compatibility_mode(sgp4::MinutesSinceEpoch(minutes))
            .map_err(PropagationError::Propagation)?;
        Ok((p.position, p.velocity))
    }

    /// Minutes from the element set's epoch to `t` seconds after `scenario_epoch` (UTC, leap seconds not
    /// counted, as SGP4 does not).
    pub fn minutes_since_epoch(&self, scenario_epoch: NaiveDateTime, t: f64) -> f64 {
        let d = scenario_epoch - self.entry.epoch;
        (d.num_seconds() as f64 + d.subsec_nanos() as f64 * 1e-9 + t) / 60.0
    }

    /// The state in the tracker's inertial frame (docs/maths.md §6.8) at tracker time `t` (s since
    /// `scenario_epoch`): SGP4's TEME state, the frame the tracker's Earth rotation θ(t) = GMST(epoch) + ω t
    /// is referred to.
    pub fn tracker_state(&self, scenario_epoch: NaiveDateTime, t: f64) -> Result<State, PropagationError> {
        self.teme(self.minutes_since_epoch(scenario_epoch, t))
    }
}

/// One object of `host-sim catalogue`'s output.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ObjectReport {
    /// Catalogue number.
    pub norad_id: u64,
    /// Name, if the file gives one.
    pub name: Option<String>,
    /// The line of the file where its element set starts.
    pub line: usize,
    /// Epoch (UTC, ISO 8601).
    pub epoch: String,
    /// Eccentricity, inclination (deg), mean motion (rev/day), B*.
    pub eccentricity: f64,
    /// Inclination (degrees).
    pub inclination_deg: f64,
    /// Mean motion (rev/day).
    pub mean_motion_rev_per_day: f64,
    /// B* (1/earth radii).
    pub bstar: f64,
    /// SGP4 TEME position at the epoch (km), when SGP4 gives one.
    pub position_km: Option<[f64; 3]>,
    /// SGP4 TEME velocity at the epoch (km/s).
    pub velocity_km_s: Option<[f64; 3]>,
    /// The SGP4 error instead, if any.
    pub sgp4_error: Option<String>,
}

/// `host-sim catalogue`'s output: every entry with its SGP4 state at its epoch.
pub fn report(entries: &[CatalogueEntry]) -> Vec<ObjectReport> {
    entries
        .iter()
        .map(|e| {
            let state = Satellite::new(e.clone()).and_then(|s| s.teme(0.0));
            ObjectReport {
                norad_id: e.norad_id,
                name: e.name.clone(),
                line: e.line,
                epoch: e.epoch.format("%Y-%m-%dT%H:%M:%S%.6fZ").to_string(),
                eccentricity: e.eccentricity,
                inclination_deg: e.inclination,
                mean_motion_rev_per_day: e.mean_motion,
                bstar: e.bstar,
                position_km: state.as_ref().ok().map(|s| s.0),
                velocity_km_s: state.as_ref().ok().map(|s| s.1),
                sgp4_error: state.err().map(|e| e.to_string()),
            }
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------------
// Files
// ---------------------------------------------------------------------------------------------------

/// The format of a catalogue file, told from its first characters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Two- or three-line element sets.
    Tle,
    /// OMM as a JSON array of objects (or one object).
    OmmJson,
    /// OMM as CSV with a header line.
    OmmCsv,
}

/// The format of `text`: JSON if it starts with `[` or `{`, CSV if its first line names `NORAD_CAT_ID`,
/// else TLE.
pub fn detect(text: &str) -> Format {
    let text = text.trim_start();
    if text.starts_with(['[', '{']) {
        Format::OmmJson
    } else if text.lines().next().is_some_and(|l| l.contains("NORAD_CAT_ID") && l.contains(',')) {
        Format::OmmCsv
    } else {
        Format::Tle
    }
}

/// Reads a catalogue file of at most [`crate::scenario::MAX_FILE_BYTES`] in any [`Format`].
pub fn load(path: &Path) -> Result<Vec<CatalogueEntry>, Error> {
    let text = crate::scenario::read_limited(path)?;
    Ok(parse(&path.display().to_string(), &text)?)
}

/// Parses `text` (its file named `file` in errors) in the [`Format`] [`detect`] finds. An empty catalogue
/// is an error.
pub fn parse(file: &str, text: &str) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let entries = match detect(text) {
        Format::Tle => parse_tle(file, text)?,
        Format::OmmJson => parse_omm_json(file, text)?,
        Format::OmmCsv => parse_omm_csv(file, text)?,
    };
    if entries.is_empty() {
        return Err(err(file, 0, "catalogue", "no element set"));
    }
    Ok(entries)
}

fn err(file: &str, line: usize, keyword: impl Into<String>, message: impl Into<String>) -> CatalogueError {
    CatalogueError {
        file: file.to_string(),
        line,
        keyword: crate::scenario::one_line(&keyword.into()),
        message: crate::scenario::one_line(&message.into()),
    }
}

// ---------------------------------------------------------------------------------------------------
// TLE
// ---------------------------------------------------------------------------------------------------

/// Parses two-line (and three-line, with a name line, optionally "0 NAME") element sets. Blank lines and
/// lines starting with `#` are skipped; lines 1 and 2 must follow each other.
pub fn parse_tle(file: &str, text: &str) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let lines: Vec<&str> = text.lines().collect();
    let mut entries = vec![];
    let mut name: Option<(usize, String)> = None;
    let mut i = 0;
    while i < lines.len() {
        let number = i + 1;
        let line = lines[i].trim_end();
        i += 1;
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if line.starts_with("1 ") {
            let Some(next) = lines.get(i).map(|l| l.trim_end()) else {
                return Err(err(file, number, "line 2", "missing after line 1"));
            };
            if !next.starts_with("2 ") {
                return Err(err(file, number + 1, "line 2", "expected \"2 \" right after line 1"));
            }
            i += 1;
            let mut entry = tle_pair(file, number, line, next)?;
            if let Some((name_line, text)) = name.take() {
                entry.name = Some(text);
                entry.line = name_line;
            }
            entries.push(entry);
        } else if line.starts_with("2 ") {
            return Err(err(file, number, "line 2", "without a line 1 before it"));
        } else {
            if let Some((name_line, _)) = name {
                return Err(err(file, name_line, "name line", "not followed by a line 1"));
            }
            let text = line.strip_prefix("0 ").unwrap_or(line).trim();
            if text.chars().count() > MAX_NAME_CHARS {
                return Err(err(file, number, "name line", format!("longer than {MAX_NAME_CHARS} characters")));
            }
            name = Some((number, text.to_string()));
        }
    }
    if let Some((name_line, _)) = name {
        return Err(err(file, name_line, "name line", "not followed by a line 1"));
    }
    Ok(entries)
}

/// The TLE modulo-10 checksum of the first 68 columns: digits count their value, '-' counts 1.
pub fn tle_checksum(line: &[u8]) -> u32 {
    line.iter()
        .take(68)
        .map(|&b| match b {
            b'0'..=b'9' => u32::from(b - b'0'),
            b'-' => 1,
            _ => 0,
        })
        .sum::<u32>()
        % 10
}

/// A catalogue number of 5 columns: digits (leading blanks allowed) or Alpha-5, a letter (A-Z without I
/// and O, A = 10) followed by 4 digits: "A0001" = 100001, "Z9999" = 339999.
pub fn parse_catalogue_number(field: &str) -> Option<u64> {
    let bytes = field.as_bytes();
    if bytes.len() != 5 {
        return None;
    }
    let first = bytes[0];
    if first == b' ' {
        let t = field.trim_start();
        return (!t.is_empty() && t.bytes().all(|b| b.is_ascii_digit())).then(|| t.parse().ok()).flatten();
    }
    let rest = &field[1..];
    if !rest.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let rest: u64 = rest.parse().ok()?;
    let lead = match first {
        b'0'..=b'9' => u64::from(first - b'0'),
        b'A'..=b'H' => u64::from(first - b'A') + 10,
        b'J'..=b'N' => u64::from(first - b'J') + 18,
        b'P'..=b'Z' => u64::from(first - b'P') + 23,
        _ => return None,
    };
    Some(lead * 10_000 + rest)
}

/// A decimal field (`-.00000084`, `15.56387291`): optional sign, digits and at most one point, blanks around.
fn decimal(field: &str) -> Option<f64> {
    let t = field.trim();
    let body = t.strip_prefix(['-', '+']).unwrap_or(t);
    let valid = !body.is_empty()
        && body.bytes().all(|b| b.is_ascii_digit() || b == b'.')
        && body.bytes().filter(|&b| b == b'.').count() <= 1
        && body.bytes().any(|b| b.is_ascii_digit());
    if !valid {
        return None;
    }
    t.parse::<f64>().ok().filter(|v| v.is_finite())
}

/// An 8-column field with an assumed leading decimal point and an exponent: " 12345-3" = 0.12345e-3.
fn assumed_exponent(field: &str) -> Option<f64> {
    let b = field.as_bytes();
    if b.len() != 8 {
        return None;
    }
    let sign = match b[0] {
        b' ' | b'+' => 1.0,
        b'-' => -1.0,
        _ => return None,
    };
    if !b[1..6].iter().all(u8::is_ascii_digit) || !b[7].is_ascii_digit() {
        return None;
    }
    let exponent_sign = match b[6] {
        b' ' | b'+' => 1,
        b'-' => -1,
        _ => return None,
    };
    let mantissa: f64 = field[1..6].parse::<u32>().ok()? as f64 / 1e5;
    let exponent = exponent_sign * i32::from(b[7] - b'0');
    Some(sign * mantissa * 10f64.powi(exponent))
}

/// An unsigned integer field, blanks around; a blank field is `blank`.
fn unsigned(field: &str, blank: Option<u64>) -> Option<u64> {
    let t = field.trim();
    if t.is_empty() {
        return blank;
    }
    if !t.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    t.parse().ok()
}

/// The epoch of TLE columns 19-32: two-digit year (57-99 → 19xx, 00-56 → 20xx) and day of the year with
/// its fraction (day 1.0 is 1 January 0h).
fn tle_epoch(year: &str, day: &str) -> Option<NaiveDateTime> {
    if !year.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let yy: i32 = year.parse().ok()?;
    let year = if yy < 57 { 2000 + yy } else { 1900 + yy };
    let day = decimal(day).filter(|d| *d >= 1.0 && !day.trim().starts_with(['-', '+']))?;
    let ordinal = day.floor();
    let nanos = ((day - ordinal) * 86_400e9).round() as u64;
    let (ordinal, nanos) = if nanos >= 86_400_000_000_000 { (ordinal + 1.0, 0) } else { (ordinal, nanos) };
    let date = NaiveDate::from_yo_opt(year, ordinal as u32)?;
    let time =
        NaiveTime::from_num_seconds_from_midnight_opt((nanos / 1_000_000_000) as u32, (nanos % 1_000_000_000) as u32)?;
    Some(date.and_time(time))
}

/// Lines 1 and 2 of one element set (line 1 at `number`).
fn tle_pair(file: &str, number: usize, line1: &str, line2: &str) -> Result<CatalogueEntry, CatalogueError> {
    for (k, line) in [(1, line1), (2, line2)] {
        let at = number + k - 1;
        if !line.is_ascii() {
            return Err(err(file, at, format!("line {k}"), "not ASCII"));
        }
        if line.len() != 69 {
            return Err(err(file, at, format!("line {k}"), format!("{} columns, expected 69", line.len())));
        }
        let b = line.as_bytes();
        if !b[68].is_ascii_digit() {
            return Err(err(file, at, format!("line {k} column 69 (checksum)"), "not a digit"));
        }
        let sum = tle_checksum(b);
        if sum != u32::from(b[68] - b'0') {
            return Err(err(
                file,
                at,
                format!("line {k} column 69 (checksum)"),
                format!("is {}, the columns 1-68 give {sum}", b[68] - b'0'),
            ));
        }
        let blanks: &[usize] = if k == 1 { &[2, 9, 18, 33, 44, 53, 62, 64] } else { &[2, 8, 17, 26, 34, 43, 52] };
        if let Some(&c) = blanks.iter().find(|&&c| b[c - 1] != b' ') {
            return Err(err(file, at, format!("line {k} column {c}"), "expected a blank"));
        }
    }
    let l2 = number + 1;
    let f1 = |a: usize, b: usize| &line1[a - 1..b];
    let f2 = |a: usize, b: usize| &line2[a - 1..b];
    let bad = |line: usize, cols: &str, what: &str, expected: &str, value: &str| {
        err(file, line, format!("line {} columns {cols} ({what})", line + 1 - number), format!("{value:?}: {expected}"))
    };
    let norad_id = parse_catalogue_number(f1(3, 7))
        .ok_or_else(|| bad(number, "3-7", "catalogue number", "expected 5 digits or Alpha-5", f1(3, 7)))?;
    let norad_2 = parse_catalogue_number(f2(3, 7))
        .ok_or_else(|| bad(l2, "3-7", "catalogue number", "expected 5 digits or Alpha-5", f2(3, 7)))?;
    if norad_2 != norad_id {
        return Err(bad(l2, "3-7", "catalogue number", &format!("differs from line 1's {norad_id}"), f2(3, 7)));
    }
    let classification = match line1.as_bytes()[7] {
        c @ (b'U' | b'C' | b'S') => c as char,
        _ => return Err(bad(number, "8-8", "classification", "expected U, C or S", f1(8, 8))),
    };
    let designator = f1(10, 17).trim();
    let epoch = tle_epoch(f1(19, 20), f1(21, 32))
        .ok_or_else(|| bad(number, "19-32", "epoch", "expected YYDDD.DDDDDDDD with a day of the year", f1(19, 32)))?;
    let mean_motion_dot =
        decimal(f1(34, 43)).ok_or_else(|| bad(number, "34-43", "mean motion dot", "expected a decimal", f1(34, 43)))?;
    let mean_motion_ddot = assumed_exponent(f1(45, 52))
        .ok_or_else(|| bad(number, "45-52", "mean motion ddot", "expected [sign]DDDDD[sign]D", f1(45, 52)))?;
    let bstar = assumed_exponent(f1(54, 61))
        .ok_or_else(|| bad(number, "54-61", "B*", "expected [sign]DDDDD[sign]D", f1(54, 61)))?;
    let ephemeris_type = unsigned(f1(63, 63), Some(0))
        .ok_or_else(|| bad(number, "63-63", "ephemeris type", "expected a digit", f1(63, 63)))?
        as u8;
    let element_set_number = unsigned(f1(65, 68), Some(0))
        .ok_or_else(|| bad(number, "65-68", "element set number", "expected digits", f1(65, 68)))?;
    let angle = |a, b, what| {
        decimal(f2(a, b)).ok_or_else(|| bad(l2, &format!("{a}-{b}"), what, "expected a decimal", f2(a, b)))
    };
    let inclination = angle(9, 16, "inclination")?;
    let right_ascension = angle(18, 25, "right ascension")?;
    let ecc = f2(27, 33);
    if !ecc.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad(l2, "27-33", "eccentricity", "expected 7 digits after an assumed \"0.\" (0 <= e < 1)", ecc));
    }
    let eccentricity =
        ecc.parse::<u32>().map_err(|_| bad(l2, "27-33", "eccentricity", "expected 7 digits", ecc))? as f64 / 1e7;
    let argument_of_perigee = angle(35, 42, "argument of perigee")?;
    let mean_anomaly = angle(44, 51, "mean anomaly")?;
    let mean_motion = angle(53, 63, "mean motion")?;
    let revolution_number = unsigned(f2(64, 68), Some(0))
        .ok_or_else(|| bad(l2, "64-68", "revolution number", "expected digits", f2(64, 68)))?;
    let entry = CatalogueEntry {
        name: None,
        norad_id,
        international_designator: (!designator.is_empty()).then(|| designator.to_string()),
        classification,
        epoch,
        mean_motion_dot,
        mean_motion_ddot,
        bstar,
        inclination,
        right_ascension,
        eccentricity,
        argument_of_perigee,
        mean_anomaly,
        mean_motion,
        element_set_number,
        revolution_number,
        ephemeris_type,
        line: number,
    };
    entry.check_ranges().map_err(|(field, message)| err(file, l2, field.tle(), message))?;
    Ok(entry)
}

// ---------------------------------------------------------------------------------------------------
// OMM
// ---------------------------------------------------------------------------------------------------

/// One OMM value before conversion.
enum Raw<'a> {
    Text(&'a str),
    Number(&'a serde_json::Number),
    /// A JSON value of another type (its name).
    Other(&'static str),
}

/// An OMM ISO-8601 epoch `YYYY-MM-DDTHH:MM:SS[.fraction of up to 9 digits][Z]`, year in 1900-2099.
pub fn parse_omm_epoch(text: &str) -> Option<NaiveDateTime> {
    let text = text.strip_suffix('Z').unwrap_or(text);
    let (date, time) = text.split_once('T')?;
    let digits = |s: &str, n: usize| s.len() == n && s.bytes().all(|b| b.is_ascii_digit());
    let d: Vec<&str> = date.split('-').collect();
    let (hms, fraction) = time.split_once('.').unwrap_or((time, ""));
    let t: Vec<&str> = hms.split(':').collect();
    if d.len() != 3 || t.len() != 3 || !digits(d[0], 4) || !digits(d[1], 2) || !digits(d[2], 2) {
        return None;
    }
    if !t.iter().all(|s| digits(s, 2)) || fraction.len() > 9 || !fraction.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    if time.contains('.') && fraction.is_empty() {
        return None;
    }
    let year: i32 = d[0].parse().ok()?;
    if !(1900..=2099).contains(&year) {
        return None;
    }
    let nanos: u32 = if fraction.is_empty() { 0 } else { format!("{fraction:0<9}").parse().ok()? };
    NaiveDate::from_ymd_opt(year, d[1].parse().ok()?, d[2].parse().ok()?)?.and_hms_nano_opt(
        t[0].parse().ok()?,
        t[1].parse().ok()?,
        t[2].parse().ok()?,
        nanos,
    )
}

/// One OMM record: its values by keyword and the line of each.
fn omm_entry<'a>(
    file: &str,
    start: usize,
    get: &dyn Fn(&str) -> Option<Raw<'a>>,
    line_of: &dyn Fn(&str) -> usize,
) -> Result<CatalogueEntry, CatalogueError> {
    let fail = |key: &str, message: String| err(file, line_of(key), key, message);
    let text = |key: &str| -> Result<Option<String>, CatalogueError> {
        match get(key) {
            None => Ok(None),
            Some(Raw::Text(s)) => Ok(Some(s.to_string())),
            Some(Raw::Number(n)) => Err(fail(key, format!("expected a string, found the number {n}"))),
            Some(Raw::Other(t)) => Err(fail(key, format!("expected a string, found {t}"))),
        }
    };
    let number = |key: &str, required: bool| -> Result<Option<f64>, CatalogueError> {
        let value = match get(key) {
            None if required => return Err(fail(key, "missing".into())),
            None => return Ok(None),
            Some(Raw::Number(n)) => n.as_f64(),
            Some(Raw::Text(s)) if s.trim().is_empty() && !required => return Ok(None),
            Some(Raw::Text(s)) => {
                let t = s.trim();
                let ok = !t.is_empty() && t.bytes().all(|b| b.is_ascii_digit() || b"+-.eE".contains(&b));
                if ok { t.parse::<f64>().ok() } else { None }
            }
            Some(Raw::Other(t)) => return Err(fail(key, format!("expected a number, found {t}"))),
        };
        match value {
            Some(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(fail(key, "expected a finite number".into())),
        }
    };
    let integer = |key: &str, required: bool, max: u64| -> Result<Option<u64>, CatalogueError> {
        let value = match get(key) {
            None if required => return Err(fail(key, "missing".into())),
            None => return Ok(None),
            Some(Raw::Number(n)) => n.as_u64(),
            Some(Raw::Text(s)) if s.trim().is_empty() && !required => return Ok(None),
            Some(Raw::Text(s)) => unsigned(s, None),
            Some(Raw::Other(t)) => return Err(fail(key, format!("expected an integer, found {t}"))),
        };
        match value {
            Some(v) if v <= max => Ok(Some(v)),
            _ => Err(fail(key, format!("expected an integer in [0, {max}]"))),
        }
    };
    if let Some(theory) = text("MEAN_ELEMENT_THEORY")?
        && theory.trim() != "SGP4"
    {
        return Err(fail("MEAN_ELEMENT_THEORY", format!("{theory:?} is not SGP4")));
    }
    let epoch_text = text("EPOCH")?.ok_or_else(|| fail("EPOCH", "missing".into()))?;
    let epoch = parse_omm_epoch(epoch_text.trim())
        .ok_or_else(|| fail("EPOCH", format!("{epoch_text:?} is not YYYY-MM-DDTHH:MM:SS[.ffffff] (1900-2099)")))?;
    let classification = match text("CLASSIFICATION_TYPE")?.as_deref().map(str::trim) {
        None | Some("") | Some("U") => 'U',
        Some("C") => 'C',
        Some("S") => 'S',
        Some(other) => return Err(fail("CLASSIFICATION_TYPE", format!("{other:?} is not U, C or S"))),
    };
    let required = |key: &str| number(key, true).map(|v| v.unwrap_or(0.0));
    let entry = CatalogueEntry {
        name: text("OBJECT_NAME")?.map(|s| s.trim().to_string()),
        norad_id: integer("NORAD_CAT_ID", true, 999_999_999)?.unwrap_or(0),
        international_designator: text("OBJECT_ID")?.map(|s| s.trim().to_string()).filter(|s| !s.is_empty()),
        classification,
        epoch,
        mean_motion_dot: required("MEAN_MOTION_DOT")?,
        mean_motion_ddot: required("MEAN_MOTION_DDOT")?,
        bstar: required("BSTAR")?,
        inclination: required("INCLINATION")?,
        right_ascension: required("RA_OF_ASC_NODE")?,
        eccentricity: required("ECCENTRICITY")?,
        argument_of_perigee: required("ARG_OF_PERICENTER")?,
        mean_anomaly: required("MEAN_ANOMALY")?,
        mean_motion: required("MEAN_MOTION")?,
        element_set_number: integer("ELEMENT_SET_NO", false, u64::from(u32::MAX))?.unwrap_or(0),
        revolution_number: integer("REV_AT_EPOCH", false, u64::from(u32::MAX))?.unwrap_or(0),
        ephemeris_type: integer("EPHEMERIS_TYPE", false, 9)?.unwrap_or(0) as u8,
        line: start,
    };
    entry.check_ranges().map_err(|(field, message)| fail(field.omm(), message))?;
    Ok(entry)
}

/// The byte spans of the top-level objects of a JSON text (of an array's elements, or the text's one
/// object), found outside strings.
fn object_spans(text: &str) -> Vec<(usize, usize)> {
    let (mut depth, mut in_string, mut escaped) = (0usize, false, false);
    let mut start = 0;
    let mut spans = vec![];
    let top = usize::from(text.trim_start().starts_with('['));
    for (i, c) in text.char_indices() {
        if in_string {
            match c {
                _ if escaped => escaped = false,
                '\\' => escaped = true,
                '"' => in_string = false,
                _ => {}
            }
            continue;
        }
        match c {
            '"' => in_string = true,
            '{' | '[' => {
                if c == '{' && depth == top {
                    start = i;
                }
                depth += 1;
            }
            '}' | ']' => {
                depth = depth.saturating_sub(1);
                if c == '}' && depth == top {
                    spans.push((start, i + 1));
                }
            }
            _ => {}
        }
    }
    spans
}

fn line_at(text: &str, byte: usize) -> usize {
    1 + text.as_bytes()[..byte.min(text.len())].iter().filter(|&&b| b == b'\n').count()
}

/// Parses OMM records in JSON: an array of objects with CelesTrak's keywords (numbers as JSON numbers or
/// strings), or one object.
pub fn parse_omm_json(file: &str, text: &str) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let value: serde_json::Value =
        serde_json::from_str(text).map_err(|e| err(file, e.line(), "JSON", e.to_string()))?;
    let objects: Vec<&serde_json::Value> = match &value {
        serde_json::Value::Array(items) => items.iter().collect(),
        object @ serde_json::Value::Object(_) => vec![object],
        _ => return Err(err(file, 1, "JSON", "expected an array of OMM objects or one object")),
    };
    let spans = object_spans(text);
    let mut entries = Vec::with_capacity(objects.len());
    for (k, object) in objects.into_iter().enumerate() {
        let (from, to) = spans.get(k).copied().unwrap_or((0, 0));
        let start = line_at(text, from);
        let Some(map) = object.as_object() else {
            return Err(err(file, start, format!("element {k}"), "expected an OMM object"));
        };
        let get = |key: &str| -> Option<Raw<'_>> {
            map.get(key).map(|v| match v {
                serde_json::Value::String(s) => Raw::Text(s),
                serde_json::Value::Number(n) => Raw::Number(n),
                serde_json::Value::Null => Raw::Other("null"),
                serde_json::Value::Bool(_) => Raw::Other("a boolean"),
                serde_json::Value::Array(_) => Raw::Other("an array"),
                serde_json::Value::Object(_) => Raw::Other("an object"),
            })
        };
        let span = &text[from..to];
        let line_of = |key: &str| span.find(&format!("\"{key}\"")).map_or(start, |at| line_at(text, from + at));
        entries.push(omm_entry(file, start, &get, &line_of)?);
    }
    Ok(entries)
}

/// The fields of one CSV line: separated by commas, a field in double quotes may hold commas and `""`.
fn csv_fields(line: &str) -> Option<Vec<String>> {
    let mut fields = vec![];
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            '"' if quoted => quoted = false,
            '"' if field.is_empty() => quoted = true,
            ',' if !quoted => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    if quoted {
        return None;
    }
    fields.push(field);
    Some(fields)
}

/// Parses OMM records in CSV: a header line of keywords, then one record a line (blank lines skipped).
pub fn parse_omm_csv(file: &str, text: &str) -> Result<Vec<CatalogueEntry>, CatalogueError> {
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty());
    let Some((h, header)) = lines.next() else { return Ok(vec![]) };
    let header: Vec<String> = csv_fields(header.trim_end())
        .ok_or_else(|| err(file, h + 1, "header", "unterminated quote"))?
        .into_iter()
        .map(|s| s.trim().to_string())
        .collect();
    if let Some(key) = header.iter().enumerate().find_map(|(i, k)| header[..i].contains(k).then_some(k)) {
        return Err(err(file, h + 1, key.as_str(), "appears twice in the header"));
    }
    let mut entries = vec![];
    for (i, line) in lines {
        let number = i + 1;
        let fields = csv_fields(line.trim_end()).ok_or_else(|| err(file, number, "record", "unterminated quote"))?;
        if fields.len() != header.len() {
            return Err(err(
                file,
                number,
                "record",
                format!("{} fields, the header has {}", fields.len(), header.len()),
            ));
        }
        let get = |key: &str| header.iter().position(|k| k == key).map(|p| Raw::Text(fields[p].as_str()));
        entries.push(omm_entry(file, number, &get, &|_| number)?);
    }
    Ok(entries)
}

#[cfg(test)]
mod tests {
    use super::*;

    const L1: &str = "1 00005U 58002B   00179.78495062  .00000023  00000-0  28098-4 0  4753";
    const L2: &str = "2 00005  34.2682 348.7242 1859667 331.7664  19.3264 10.82419157413667";

    #[test]
    fn alpha5_catalogue_numbers() {
        assert_eq!(parse_catalogue_number("A0001"), Some(100_001));
        assert_eq!(parse_catalogue_number("H9999"), Some(179_999));
        assert_eq!(parse_catalogue_number("J0000"), Some(180_000));
        assert_eq!(parse_catalogue_number("P0000"), Some(230_000));
        assert_eq!(parse_catalogue_number("Z9999"), Some(339_999));
        assert_eq!(parse_catalogue_number("00005"), Some(5));
        assert_eq!(parse_catalogue_number("    5"), Some(5));
        assert_eq!(parse_catalogue_number("I0001"), None);
        assert_eq!(parse_catalogue_number("O0001"), None);
        assert_eq!(parse_catalogue_number("a0001"), None);
        assert_eq!(parse_catalogue_number("     "), None);
        assert_eq!(parse_catalogue_number("0A001"), None);
    }

    #[test]
    fn tle_fields_are_read() {
        let e = &parse("t", &format!("{L1}\n{L2}\n")).unwrap()[0];
        assert_eq!(e.norad_id, 5);
        assert_eq!(e.international_designator.as_deref(), Some("58002B"));
        assert_eq!(e.epoch.to_string(), "2000-06-27 18:50:19.733567999");
        assert_eq!(e.mean_motion_dot, 0.00000023);
        assert_eq!(e.bstar, 0.28098e-4);
        assert_eq!(e.eccentricity, 0.1859667);
        assert_eq!(e.mean_motion, 10.82419157);
        assert_eq!(e.revolution_number, 41366);
        assert_eq!(e.element_set_number, 475);
    }

    #[test]
    fn tle_agrees_with_the_sgp4_crate_parser() {
        let ours = parse("t", &format!("{L1}\n{L2}\n")).unwrap()[0].to_sgp4();
        let theirs = sgp4::Elements::from_tle(None, L1.as_bytes(), L2.as_bytes()).unwrap();
        assert_eq!(ours.norad_id, theirs.norad_id);
        assert!((ours.datetime - theirs.datetime).num_nanoseconds().unwrap().abs() <= 1);
        for (a, b) in [
            (ours.drag_term, theirs.drag_term),
            (ours.eccentricity, theirs.eccentricity),
            (ours.mean_motion, theirs.mean_motion),
            (ours.inclination, theirs.inclination),
            (ours.mean_motion_ddot, theirs.mean_motion_ddot),
        ] {
            assert!((a - b).abs() <= 1e-15 * b.abs().max(1.0), "{a} vs {b}");
        }
    }

    #[test]
    fn checksum_is_verified() {
        let bad = format!("{}4", &L1[..68]);
        let e = parse("f.tle", &format!("{bad}\n{L2}\n")).unwrap_err();
        assert_eq!(e.line, 1);
        assert!(e.keyword.contains("checksum"), "{e}");
    }

    #[test]
    fn omm_json_and_csv_give_the_tle_elements() {
        let json = r#"[{"OBJECT_NAME":"X","OBJECT_ID":"1958-002B","EPOCH":"2000-06-27T18:50:19.733568",
            "MEAN_MOTION":10.82419157,"ECCENTRICITY":0.1859667,"INCLINATION":34.2682,"RA_OF_ASC_NODE":348.7242,
            "ARG_OF_PERICENTER":331.7664,"MEAN_ANOMALY":19.3264,"EPHEMERIS_TYPE":0,"CLASSIFICATION_TYPE":"U",
            "NORAD_CAT_ID":5,"ELEMENT_SET_NO":475,"REV_AT_EPOCH":41366,"BSTAR":2.8098e-5,
            "MEAN_MOTION_DOT":2.3e-7,"MEAN_MOTION_DDOT":0}]"#;
        let csv = "OBJECT_NAME,OBJECT_ID,EPOCH,MEAN_MOTION,ECCENTRICITY,INCLINATION,RA_OF_ASC_NODE,\
            ARG_OF_PERICENTER,MEAN_ANOMALY,EPHEMERIS_TYPE,CLASSIFICATION_TYPE,NORAD_CAT_ID,ELEMENT_SET_NO,\
            REV_AT_EPOCH,BSTAR,MEAN_MOTION_DOT,MEAN_MOTION_DDOT\n\
            X,1958-002B,2000-06-27T18:50:19.733568,10.82419157,.1859667,34.2682,348.7242,331.7664,19.3264,0,U,5,\
            475,41366,.28098E-4,.23E-6,0\n";
        let tle = Satellite::new(parse("t", &format!("{L1}\n{L2}\n")).unwrap().remove(0)).unwrap();
        for text in [json, csv] {
            let entries = parse("o", text).unwrap();
            assert_eq!(entries.len(), 1);
            assert_eq!(entries[0].name.as_deref(), Some("X"));
            let omm = Satellite::new(entries[0].clone()).unwrap();
            let (a, b) = (tle.teme(720.0).unwrap(), omm.teme(720.0).unwrap());
            for i in 0..3 {
                assert!((a.0[i] - b.0[i]).abs() < 1e-6, "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn tracker_time_is_minutes_since_the_element_epoch() {
        let sat = Satellite::new(parse("t", &format!("{L1}\n{L2}\n")).unwrap().remove(0)).unwrap();
        let start = parse_omm_epoch("2000-06-28T00:00:00").unwrap();
        let minutes = sat.minutes_since_epoch(start, 600.0);
        let expected = (86_400.0 - (18.0 * 3600.0 + 50.0 * 60.0 + 19.733568)) / 60.0 + 10.0;
        assert!((minutes - expected).abs() < 1e-9, "{minutes} {expected}");
        assert_eq!(sat.tracker_state(start, 600.0).unwrap(), sat.teme(minutes).unwrap());
    }
}
