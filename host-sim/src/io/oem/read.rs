//! A reader of CCSDS OEMs (CCSDS 502.0-B-2, KVN form) for `host-sim track --prior-oem`: per segment its
//! object, its last ephemeris state and the covariance at that state's epoch; every other line is checked
//! and dropped, so memory grows with the segments, not the ephemeris lines.
//!
//! Accepted: `CCSDS_OEM_VERS` 1.0, 2.0 or 3.0; per segment `CENTER_NAME = EARTH`, `REF_FRAME` TEME (the
//! tracker's frame) or EME2000/J2000/GCRF/ICRF (turned into TEME where the prior is built;
//! [`SUPPORTED_FRAMES`]), `TIME_SYSTEM` UTC, TAI, GPS or TT (moved to UTC likewise), ephemeris lines `epoch x y z vx vy vz
//! [ax ay az]` (km, km/s, km/s²) in increasing time, an optional covariance section (lower triangle, one
//! row per line, `COV_REF_FRAME` the segment's frame when given). Bad input is an [`OemError`]: the line,
//! the keyword and what is wrong, with any value quoted shortened to [`EXCERPT_CHARS`] characters.

use crate::error::Error;
use crate::io::ccsds::Instant;
use crate::sim::fk5::{Frame, TimeSystem};
use std::fmt;
use std::path::Path;

/// Reference frames a prior can be read in: the tracker's own (its states are TEME).
pub const SUPPORTED_FRAMES: &[&str] = &["TEME", "EME2000", "J2000", "GCRF", "ICRF"];

/// The most characters of a value quoted in a message.
pub const EXCERPT_CHARS: usize = 40;

/// A problem of an OEM: 1-based line, keyword, message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OemError {
    /// Line (1-based; the last line + 1 for a file that ends too early).
    pub line: usize,
    /// The keyword at fault (`EPHEMERIS` for an ephemeris line, `COVARIANCE` for a covariance row).
    pub keyword: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for OemError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}: {}", self.line, self.keyword, self.message)
    }
}

impl OemError {
    /// The error as bad input of `file`: `file:line: KEYWORD: message`.
    pub fn in_file(&self, file: &Path) -> Error {
        Error::input(format!("{}:{}: {}: {}", file.display(), self.line, self.keyword, self.message))
    }
}

fn fail<T>(line: usize, keyword: &str, message: impl fmt::Display) -> Result<T, OemError> {
    Err(OemError { line, keyword: excerpt(keyword), message: message.to_string() })
}

/// `text` on one line, at most [`EXCERPT_CHARS`] characters (then `…`).
pub fn excerpt(text: &str) -> String {
    let mut short: String = text.chars().take(EXCERPT_CHARS).collect();
    if text.chars().nth(EXCERPT_CHARS).is_some() {
        short.push('…');
    }
    crate::scenario::one_line(&short)
}

/// One ephemeris state.
#[derive(Debug, Clone, PartialEq)]
pub struct OemState {
    /// Its line.
    pub line: usize,
    /// Its epoch.
    pub epoch: Instant,
    /// Position and velocity (km, km/s).
    pub state: [f64; 6],
}

/// One covariance (km², km²/s, km²/s²), symmetric, as read from its lower triangle.
#[derive(Debug, Clone, PartialEq)]
pub struct OemCovariance {
    /// Line of its `EPOCH`.
    pub line: usize,
    /// The matrix.
    pub matrix: [[f64; 6]; 6],
}

/// One segment: its object, last state and the covariance at that state's epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct OemSegment {
    /// Line of `META_START`.
    pub meta_line: usize,
    /// `OBJECT_NAME`.
    pub object_name: String,
    /// `OBJECT_ID` and its line.
    pub object_id: (String, usize),
    /// The last ephemeris line's state.
    pub last: OemState,
    /// The covariance whose `EPOCH` is the last state's (the last such block), if any.
    pub covariance: Option<OemCovariance>,
    /// `REF_FRAME` and its line.
    pub frame: (Frame, usize),
    /// `TIME_SYSTEM` and its line.
    pub time_system: (TimeSystem, usize),
}

/// A parsed OEM: its segments in file order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Oem {
    /// The segments (at least one).
    pub segments: Vec<OemSegment>,
    /// Lines read.
    pub lines: usize,
}

const HEADER_KEYS: &[&str] = &["COMMENT", "CREATION_DATE", "ORIGINATOR", "MESSAGE_ID"];
const META_REQUIRED: &[&str] =
    &["OBJECT_NAME", "OBJECT_ID", "CENTER_NAME", "REF_FRAME", "TIME_SYSTEM", "START_TIME", "STOP_TIME"];
const META_IGNORED: &[&str] =
    &["COMMENT", "REF_FRAME_EPOCH", "USEABLE_START_TIME", "USEABLE_STOP_TIME", "INTERPOLATION", "INTERPOLATION_DEGREE"];

/// `KEY = value` (or a bare `KEY`, or `COMMENT text`): the keyword and the value, trimmed.
fn split_line(text: &str) -> (&str, &str) {
    if let Some(rest) = text.strip_prefix("COMMENT")
        && (rest.is_empty() || rest.starts_with([' ', '\t']))
    {
        return ("COMMENT", rest.trim());
    }
    match text.split_once('=') {
        Some((key, value)) => (key.trim(), value.trim()),
        None => (text.trim(), ""),
    }
}

fn parse_time(line: usize, keyword: &str, text: &str) -> Result<Instant, OemError> {
    Instant::parse(text).or_else(|_| {
        fail(line, keyword, format!("\"{}\" is not a time YYYY-MM-DDThh:mm:ss[.fff] (UTC)", excerpt(text)))
    })
}

fn parse_number(line: usize, keyword: &str, text: &str) -> Result<f64, OemError> {
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => fail(line, keyword, format!("\"{}\" is not a finite number", excerpt(text))),
    }
}

/// The metadata of the segment being read.
struct Meta {
    line: usize,
    seen: Vec<(&'static str, String, usize)>,
}

impl Meta {
    fn value(&self, key: &str) -> Option<&(&'static str, String, usize)> {
        self.seen.iter().find(|(k, _, _)| *k == key)
    }

    /// A metadata line other than `META_STOP`: a supported value of a known keyword.
    fn read(&mut self, line: usize, key: &str, value: &str) -> Result<(), OemError> {
        if META_IGNORED.contains(&key) {
            return Ok(());
        }
        let Some(required) = META_REQUIRED.iter().find(|k| **k == key) else {
            return match key {
                "META_START" | "COVARIANCE_START" => fail(line, key, "inside a META block (META_STOP missing)"),
                _ => fail(line, key, "unknown keyword in the metadata"),
            };
        };
        if self.value(key).is_some() {
            return fail(line, key, "given twice in the metadata");
        }
        match key {
            "CENTER_NAME" if value != "EARTH" => {
                return fail(line, key, format!("centre \"{}\" is not supported (EARTH)", excerpt(value)));
            }
            "REF_FRAME" if !SUPPORTED_FRAMES.contains(&value) => {
                return fail(
                    line,
                    key,
                    format!(
                        "reference frame \"{}\" is not supported ({})",
                        excerpt(value),
                        SUPPORTED_FRAMES.join(", ")
                    ),
                );
            }
            "TIME_SYSTEM" if TimeSystem::from_ccsds(value).is_none() => {
                return fail(
                    line,
                    key,
                    format!("time system \"{}\" is not supported (UTC, TAI, GPS or TT)", excerpt(value)),
                );
            }
            "START_TIME" | "STOP_TIME" => {
                parse_time(line, key, value)?;
            }
            "OBJECT_NAME" | "OBJECT_ID" if value.is_empty() => return fail(line, key, "empty"),
            _ => {}
        }
        self.seen.push((required, value.to_string(), line));
        Ok(())
    }

    /// At `META_STOP`: every required keyword given.
    fn finish(&self, line: usize) -> Result<(), OemError> {
        match META_REQUIRED.iter().find(|k| self.value(k).is_none()) {
            Some(missing) => fail(line, missing, "required in the metadata, missing"),
            None => Ok(()),
        }
    }
}

/// The segment being read: its metadata, its last state, the covariance being read.
struct Reading {
    meta: Meta,
    last: Option<OemState>,
    covariance: Option<OemCovariance>,
    /// The covariance block being read: its line, whether it is at the last state's epoch, rows so far.
    block: Option<(usize, bool, Vec<Vec<f64>>)>,
}

impl Reading {
    fn new(line: usize) -> Self {
        Reading { meta: Meta { line, seen: vec![] }, last: None, covariance: None, block: None }
    }

    /// An ephemeris line: an epoch after the previous one and 6 (or 9) finite numbers.
    fn ephemeris(&mut self, line: usize, text: &str) -> Result<(), OemError> {
        let mut parts = text.split_whitespace();
        let epoch = parse_time(line, "EPHEMERIS", parts.next().unwrap_or_default())?;
        let values: Vec<&str> = parts.take(10).collect();
        if values.len() != 6 && values.len() != 9 {
            return fail(line, "EPHEMERIS", "expected `epoch x y z vx vy vz [ax ay az]` (6 or 9 numbers)");
        }
        let mut state = [0.0; 6];
        for (i, v) in values.iter().enumerate() {
            let v = parse_number(line, "EPHEMERIS", v)?;
            if let Some(s) = state.get_mut(i) {
                *s = v;
            }
        }
        if let Some(previous) = &self.last
            && epoch <= previous.epoch
        {
            return fail(line, "EPHEMERIS", format!("{epoch} is not after the previous epoch {}", previous.epoch));
        }
        self.last = Some(OemState { line, epoch, state });
        Ok(())
    }

    /// A covariance section line other than `COVARIANCE_START` and `COVARIANCE_STOP`.
    fn covariance_line(&mut self, line: usize, key: &str, value: &str, text: &str) -> Result<(), OemError> {
        match key {
            "COMMENT" => {}
            "EPOCH" => {
                self.close_block(line, key)?;
                let epoch = parse_time(line, key, value)?;
                let at_last = self.last.as_ref().is_some_and(|s| s.epoch == epoch);
                self.block = Some((line, at_last, vec![]));
            }
            "COV_REF_FRAME" => {
                let frame = self.meta.value("REF_FRAME").map(|(_, v, _)| v.as_str()).unwrap_or_default();
                match &self.block {
                    Some((_, _, rows)) if rows.is_empty() => {}
                    _ => return fail(line, key, "expected right after EPOCH"),
                }
                if value != frame {
                    return fail(line, key, format!("\"{}\" is not the segment's REF_FRAME {frame}", excerpt(value)));
                }
            }
            _ => {
                let Some((_, _, rows)) = &mut self.block else {
                    return fail(line, "COVARIANCE", "a covariance row before its EPOCH");
                };
                let values: Vec<&str> = text.split_whitespace().take(7).collect();
                if rows.len() == 6 {
                    return fail(line, "COVARIANCE", "a seventh row (EPOCH or COVARIANCE_STOP expected)");
                }
                if values.len() != rows.len() + 1 {
                    return fail(
                        line,
                        "COVARIANCE",
                        format!("row {} of the lower triangle needs {} numbers", rows.len() + 1, rows.len() + 1),
                    );
                }
                let row = values.iter().map(|v| parse_number(line, "COVARIANCE", v)).collect::<Result<_, _>>()?;
                rows.push(row);
            }
        }
        Ok(())
    }

    /// Ends the covariance block being read (at the next `EPOCH` or `COVARIANCE_STOP`): six rows.
    fn close_block(&mut self, line: usize, key: &str) -> Result<(), OemError> {
        let Some((epoch_line, at_last, rows)) = self.block.take() else { return Ok(()) };
        if rows.len() != 6 {
            return fail(line, key, format!("the covariance of line {epoch_line} has {} of its 6 rows", rows.len()));
        }
        if at_last {
            let matrix = core::array::from_fn(|i| core::array::from_fn(|j| rows[i.max(j)][i.min(j)]));
            self.covariance = Some(OemCovariance { line: epoch_line, matrix });
        }
        Ok(())
    }

    /// The segment, at its end (`line`: the next `META_START` or the end of the file).
    fn finish(self, line: usize) -> Result<OemSegment, OemError> {
        let Some(last) = self.last else {
            return fail(line, "EPHEMERIS", "the segment has no ephemeris line");
        };
        let value = |key: &str| self.meta.value(key).map(|(_, v, l)| (v.clone(), *l)).unwrap_or_default();
        let (frame, frame_line) = value("REF_FRAME");
        let (time_system, time_line) = value("TIME_SYSTEM");
        Ok(OemSegment {
            meta_line: self.meta.line,
            object_name: value("OBJECT_NAME").0,
            object_id: value("OBJECT_ID"),
            last,
            covariance: self.covariance,
            frame: (Frame::from_ccsds(&frame).unwrap_or(Frame::Teme), frame_line),
            time_system: (TimeSystem::from_ccsds(&time_system).unwrap_or(TimeSystem::Utc), time_line),
        })
    }
}

/// Where the reader is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    Start,
    Header,
    Meta,
    Data,
    Covariance,
    AfterCovariance,
}

/// Parses an OEM in KVN form.
///
/// # Errors
/// The first problem: an unknown keyword or one out of place, a missing required keyword, a centre other
/// than EARTH, a frame not in [`SUPPORTED_FRAMES`], a time system other than UTC, a malformed time or
/// number (non-finite numbers included), epochs out of order, an incomplete covariance, no segment.
pub fn parse(text: &str) -> Result<Oem, OemError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut oem = Oem::default();
    let mut state = State::Start;
    let mut header = [("CREATION_DATE", false), ("ORIGINATOR", false)];
    let mut reading: Option<Reading> = None;
    let mut last = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        last = line;
        let content = raw.trim();
        if content.is_empty() {
            continue;
        }
        let (key, value) = split_line(content);
        state = match (state, key) {
            (State::Start, "CCSDS_OEM_VERS") if ["1.0", "2.0", "3.0"].contains(&value) => State::Header,
            (State::Start, "CCSDS_OEM_VERS") => {
                return fail(line, key, format!("version \"{}\" is not 1.0, 2.0 or 3.0", excerpt(value)));
            }
            (State::Start, _) => return fail(line, key, "an OEM starts with CCSDS_OEM_VERS"),
            (State::Header, "META_START") => {
                if let Some((missing, _)) = header.iter().find(|(_, seen)| !seen) {
                    return fail(line, missing, "required in the header, missing");
                }
                reading = Some(Reading::new(line));
                State::Meta
            }
            (State::Header, _) if HEADER_KEYS.contains(&key) => {
                if key == "CREATION_DATE" {
                    parse_time(line, key, value)?;
                }
                header.iter_mut().filter(|(name, _)| *name == key).for_each(|(_, seen)| *seen = true);
                State::Header
            }
            (State::Header, _) => return fail(line, key, "unknown keyword in the header"),
            (State::Meta, "META_STOP") => {
                reading.as_ref().map_or(Ok(()), |r| r.meta.finish(line))?;
                State::Data
            }
            (State::Meta, _) => {
                reading.as_mut().map_or(Ok(()), |r| r.meta.read(line, key, value))?;
                State::Meta
            }
            (State::Data | State::AfterCovariance, "META_START") => {
                oem.segments.extend(reading.take().map(|r| r.finish(line)).transpose()?);
                reading = Some(Reading::new(line));
                State::Meta
            }
            (State::Data | State::AfterCovariance, "COMMENT") => state,
            (State::Data, "COVARIANCE_START") => State::Covariance,
            (State::Data, _) if content.contains('=') => {
                return fail(line, key, "unknown keyword in the ephemeris data");
            }
            (State::Data, _) => {
                reading.as_mut().map_or(Ok(()), |r| r.ephemeris(line, content))?;
                State::Data
            }
            (State::Covariance, "META_START") => return fail(line, key, "COVARIANCE_STOP missing before it"),
            (State::Covariance, "COVARIANCE_STOP") => {
                reading.as_mut().map_or(Ok(()), |r| r.close_block(line, key))?;
                State::AfterCovariance
            }
            (State::Covariance, _) => {
                reading.as_mut().map_or(Ok(()), |r| r.covariance_line(line, key, value, content))?;
                State::Covariance
            }
            (State::AfterCovariance, _) => return fail(line, key, "META_START expected after COVARIANCE_STOP"),
        };
    }
    oem.lines = last;
    match state {
        State::Data | State::AfterCovariance => {
            oem.segments.extend(reading.take().map(|r| r.finish(last + 1)).transpose()?);
            Ok(oem)
        }
        State::Start => fail(last + 1, "CCSDS_OEM_VERS", "empty file"),
        State::Header => fail(last + 1, "META_START", "no META block"),
        State::Meta => fail(last + 1, "META_STOP", "the file ends inside a META block"),
        State::Covariance => fail(last + 1, "COVARIANCE_STOP", "the file ends inside the covariance section"),
    }
}

/// Reads and parses the OEM `file` (at most [`crate::scenario::MAX_FILE_BYTES`]).
///
/// # Errors
/// Bad input naming the file (and the line and keyword, [`parse`]).
pub fn read(file: &Path) -> Result<Oem, Error> {
    let text = crate::scenario::read_limited(file)?;
    parse(&text).map_err(|e| e.in_file(file))
}

#[cfg(test)]
mod tests;
