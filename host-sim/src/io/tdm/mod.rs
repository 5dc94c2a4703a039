//! CCSDS Tracking Data Messages (TDM, CCSDS 503.0-B-2, KVN form): a writer of one TDM per sensor of a
//! version 2 scenario (`host-sim export-tdm`), a reader, and the scans a set of TDMs gives a scenario's
//! tracker (`host-sim track`). Conventions (also in `docs/scenario-format.md`, "TDM and OEM"):
//!
//! - one segment per sensor; `PARTICIPANT_1` is the sensor's `name` in the scenario (the configuration);
//! - radar: `ANGLE_TYPE = AZEL`, `RANGE` (one-way slant range, `RANGE_UNITS = km`), `ANGLE_1` (azimuth,
//!   deg), `ANGLE_2` (elevation, deg), `DOPPLER_INSTANTANEOUS` (range-rate, km/s) for `radar-range-rate`;
//!   optical: `ANGLE_TYPE = RADEC`, `ANGLE_1` (right ascension, deg), `ANGLE_2` (declination, deg);
//!   `ANGLE_1` (azimuth or right ascension) in any convention within [−360°, 720°], wrapped exactly to
//!   (−180°, 180°] as it is read ([`crate::io::angles`]);
//! - `TIME_SYSTEM`, `REFERENCE_FRAME` and the `CORRECTION_*` keywords are applied on the way in
//!   ([`Reduction`]: times moved to UTC, EME2000 right ascensions turned into TEME, corrections added when
//!   `CORRECTIONS_APPLIED = NO`);
//! - `PATH` and `TIMETAG_REF` give a sensor's light time and `ANGLE_TYPE = AZEL` its refraction where the
//!   configuration does not state them ([`physics`]);
//! - a measurement is its components' lines in that order, all with the scan's time; every distinct time
//!   is one scan; a scan without measurements is a data-section line `COMMENT EMPTY_SCAN <time>`;
//! - values are written in their shortest round-trip decimal form (the scenario's own degrees: no unit
//!   conversion happens), times as in [`crate::io::ccsds`]: the scans read back are bit-identical.
//!
//! Bad input is a [`TdmError`]: the line, the keyword and what is wrong.

mod export;
pub mod physics;
mod reduction;

pub use export::{export, stage, write};
pub use reduction::Reduction;

use crate::error::Error;
use crate::io::ccsds::Instant;
use crate::scenario::v2::{Measurement3dSpec, Scan3dSpec, Scenario3d};
use std::fmt;
use std::path::{Path, PathBuf};

/// The marker of an empty scan in a data section's `COMMENT`.
pub const EMPTY_SCAN: &str = "EMPTY_SCAN";

/// A problem of a TDM: 1-based line, keyword, message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TdmError {
    /// Line (1-based; the last line + 1 for a file that ends too early).
    pub line: usize,
    /// The keyword at fault.
    pub keyword: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for TdmError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}: {}: {}", self.line, self.keyword, self.message)
    }
}

/// The error at `line`: the keyword and any quoted input cut to an excerpt (an unknown keyword may be 10 MB).
fn fail<T>(line: usize, keyword: &str, message: impl fmt::Display) -> Result<T, TdmError> {
    let keyword = crate::scenario::excerpt(keyword, crate::scenario::quote::EXCERPT_CHARS);
    Err(TdmError { line, keyword, message: crate::scenario::cut_quotes(&message.to_string()) })
}

/// The angle types supported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AngleType {
    /// Azimuth, elevation (radar).
    AzEl,
    /// Right ascension, declination (optical).
    RaDec,
}

/// The data types supported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataKind {
    /// `RANGE` (km).
    Range,
    /// `ANGLE_1` (deg).
    Angle1,
    /// `ANGLE_2` (deg).
    Angle2,
    /// `DOPPLER_INSTANTANEOUS` (km/s).
    Doppler,
}

impl DataKind {
    /// The keyword.
    pub fn keyword(self) -> &'static str {
        match self {
            DataKind::Range => "RANGE",
            DataKind::Angle1 => "ANGLE_1",
            DataKind::Angle2 => "ANGLE_2",
            DataKind::Doppler => "DOPPLER_INSTANTANEOUS",
        }
    }

    /// The components of a measurement type, in order.
    pub fn components(kind: Measurement3dSpec) -> &'static [DataKind] {
        match kind {
            Measurement3dSpec::Radar => &[DataKind::Range, DataKind::Angle1, DataKind::Angle2],
            Measurement3dSpec::RadarRangeRate => {
                &[DataKind::Range, DataKind::Angle1, DataKind::Angle2, DataKind::Doppler]
            }
            Measurement3dSpec::Optical | Measurement3dSpec::AzEl => &[DataKind::Angle1, DataKind::Angle2],
            Measurement3dSpec::Range => &[DataKind::Range],
            Measurement3dSpec::RangeRangeRate => &[DataKind::Range, DataKind::Doppler],
            Measurement3dSpec::Network => &[],
        }
    }
}

/// The `ANGLE_TYPE` of a sensor kind's angles (`None`: it measures none).
fn angle_type_of(kind: Measurement3dSpec) -> Option<AngleType> {
    match kind {
        Measurement3dSpec::Optical => Some(AngleType::RaDec),
        Measurement3dSpec::Radar | Measurement3dSpec::RadarRangeRate | Measurement3dSpec::AzEl => Some(AngleType::AzEl),
        Measurement3dSpec::Range | Measurement3dSpec::RangeRangeRate | Measurement3dSpec::Network => None,
    }
}

/// One data line, or an empty scan.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Its line.
    pub line: usize,
    /// Its time.
    pub time: Instant,
    /// The data type and value; `None` for an empty scan.
    pub value: Option<(DataKind, f64)>,
}

/// One segment: metadata and data.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// Line of `META_START`.
    pub meta_line: usize,
    /// Line of `META_STOP`.
    pub meta_stop_line: usize,
    /// `PARTICIPANT_1` and its line.
    pub participant: (String, usize),
    /// `ANGLE_TYPE` and its line.
    pub angle_type: Option<(AngleType, usize)>,
    /// Time system, reference frame and corrections ([`Reduction`]).
    pub reduction: Reduction,
    /// Signal path, time tag and what the data lacks ([`physics::Statement`]).
    pub physics: physics::Statement,
    /// The data lines and empty scans, in file order (times in UTC, corrections applied).
    pub records: Vec<Record>,
}

/// A parsed TDM.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Tdm {
    /// Its segments.
    pub segments: Vec<Segment>,
}

const HEADER_KEYS: &[&str] = &["COMMENT", "CREATION_DATE", "ORIGINATOR", "MESSAGE_ID"];

/// Metadata keywords of CCSDS 503.0-B-2 whose values this reader does not need (their values are not
/// checked); `TRANSMIT_DELAY_n`, `RECEIVE_DELAY_n` and `PARTICIPANT_2..5` too.
const META_IGNORED: &[&str] = &[
    "COMMENT",
    "TRACK_ID",
    "DATA_TYPES",
    "START_TIME",
    "STOP_TIME",
    "MODE",
    "PATH",
    "PATH_1",
    "PATH_2",
    "EPHEMERIS_NAME_1",
    "EPHEMERIS_NAME_2",
    "EPHEMERIS_NAME_3",
    "EPHEMERIS_NAME_4",
    "EPHEMERIS_NAME_5",
    "TRANSMIT_BAND",
    "RECEIVE_BAND",
    "TURNAROUND_NUMERATOR",
    "TURNAROUND_DENOMINATOR",
    "TIMETAG_REF",
    "INTEGRATION_INTERVAL",
    "INTEGRATION_REF",
    "FREQ_OFFSET",
    "RANGE_MODE",
    "RANGE_MODULUS",
    "INTERPOLATION",
    "INTERPOLATION_DEGREE",
    "DOPPLER_COUNT_BIAS",
    "DOPPLER_COUNT_SCALE",
    "DOPPLER_COUNT_ROLLOVER",
    "DATA_QUALITY",
    "CORRECTION_MAG",
    "CORRECTION_RCS",
    "CORRECTION_RECEIVE",
    "CORRECTION_TRANSMIT",
];

/// Data keywords of CCSDS 503.0-B-2 that are valid but not supported here.
const DATA_UNSUPPORTED: &[&str] = &[
    "CARRIER_POWER",
    "CLOCK_BIAS",
    "CLOCK_DRIFT",
    "DOPPLER_COUNT",
    "DOPPLER_INTEGRATED",
    "DOR",
    "MAG",
    "PC_N0",
    "PR_N0",
    "PRESSURE",
    "RCS",
    "RECEIVE_FREQ",
    "RECEIVE_FREQ_1",
    "RECEIVE_FREQ_2",
    "RECEIVE_FREQ_3",
    "RECEIVE_FREQ_4",
    "RECEIVE_FREQ_5",
    "RECEIVE_PHASE_CT_1",
    "RECEIVE_PHASE_CT_2",
    "RECEIVE_PHASE_CT_3",
    "RECEIVE_PHASE_CT_4",
    "RECEIVE_PHASE_CT_5",
    "RHUMIDITY",
    "STEC",
    "TEMPERATURE",
    "TRANSMIT_FREQ_1",
    "TRANSMIT_FREQ_2",
    "TRANSMIT_FREQ_3",
    "TRANSMIT_FREQ_4",
    "TRANSMIT_FREQ_5",
    "TRANSMIT_FREQ_RATE_1",
    "TRANSMIT_FREQ_RATE_2",
    "TRANSMIT_FREQ_RATE_3",
    "TRANSMIT_FREQ_RATE_4",
    "TRANSMIT_FREQ_RATE_5",
    "TRANSMIT_PHASE_CT_1",
    "TRANSMIT_PHASE_CT_2",
    "TRANSMIT_PHASE_CT_3",
    "TRANSMIT_PHASE_CT_4",
    "TRANSMIT_PHASE_CT_5",
    "TROPO_DRY",
    "TROPO_WET",
    "VLBI_DELAY",
];

fn is_numbered(key: &str, prefix: &str, range: std::ops::RangeInclusive<u32>) -> bool {
    key.strip_prefix(prefix).and_then(|n| n.parse::<u32>().ok()).is_some_and(|n| range.contains(&n))
}

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

fn parse_time(line: usize, keyword: &str, text: &str) -> Result<Instant, TdmError> {
    Instant::parse(text).or_else(|e| fail(line, keyword, e))
}

/// Where the reader is.
#[derive(Clone, Copy, PartialEq, Eq)]
enum State {
    Start,
    Header,
    Meta,
    BetweenMetaAndData,
    Data,
    AfterData,
}

/// The metadata of the segment being read.
struct MetaBlock {
    /// Line of its `META_START`.
    line: usize,
    /// Line of `TIME_SYSTEM = UTC`.
    time_system: Option<usize>,
    participant: Option<(String, usize)>,
    angle_type: Option<(AngleType, usize)>,
    reduction: Reduction,
    physics: physics::Statement,
}

impl MetaBlock {
    fn starting_at(line: usize) -> Self {
        Self {
            line,
            time_system: None,
            participant: None,
            angle_type: None,
            reduction: Reduction::default(),
            physics: physics::Statement::default(),
        }
    }

    /// A metadata line other than `META_STOP`: a supported value of a known keyword.
    fn read(&mut self, line: usize, key: &str, value: &str) -> Result<(), TdmError> {
        if self.reduction.read(line, key, value)? {
            if key == "TIME_SYSTEM" {
                self.time_system = Some(line);
            }
            return Ok(());
        }
        if self.physics.read(line, key, value)? {
            return Ok(());
        }
        match key {
            "PARTICIPANT_1" if value.is_empty() => return fail(line, key, "empty"),
            "PARTICIPANT_1" => self.participant = Some((value.to_string(), line)),
            "ANGLE_TYPE" => {
                self.angle_type = Some(match value {
                    "AZEL" => (AngleType::AzEl, line),
                    "RADEC" => (AngleType::RaDec, line),
                    _ => {
                        return fail(line, key, format!("angle type \"{value}\" is not supported (AZEL or RADEC)"));
                    }
                });
            }
            "RANGE_UNITS" if value != "km" => {
                return fail(line, key, format!("range units \"{value}\" are not supported (km only)"));
            }
            "RANGE_UNITS" => {}
            _ if META_IGNORED.contains(&key)
                || is_numbered(key, "PARTICIPANT_", 2..=5)
                || is_numbered(key, "TRANSMIT_DELAY_", 1..=5)
                || is_numbered(key, "RECEIVE_DELAY_", 1..=5) => {}
            "META_START" | "DATA_START" => return fail(line, key, "inside a META block (META_STOP missing)"),
            _ => return fail(line, key, "unknown keyword in the metadata"),
        }
        Ok(())
    }
}

/// A header line: a known keyword, a valid `CREATION_DATE`; notes the required keywords seen.
fn header_line(line: usize, key: &str, value: &str, required: &mut [(&str, bool)]) -> Result<(), TdmError> {
    if !HEADER_KEYS.contains(&key) {
        return match key {
            "DATA_START" => fail(line, key, "no META_START ... META_STOP block before the data"),
            _ => fail(line, key, "unknown keyword in the header"),
        };
    }
    if key == "CREATION_DATE" {
        parse_time(line, key, value)?;
    }
    for (name, seen) in required.iter_mut() {
        *seen |= *name == key;
    }
    Ok(())
}

/// A data line (or an empty scan's `COMMENT`) of the last segment, appended to its records.
fn data_line(tdm: &mut Tdm, line: usize, key: &str, value: &str) -> Result<(), TdmError> {
    let segment = tdm.segments.last_mut().ok_or_else(|| TdmError {
        line,
        keyword: key.to_string(),
        message: "data outside a segment".into(),
    })?;
    if key == "COMMENT" {
        if let Some(time) = value.strip_prefix(EMPTY_SCAN) {
            let time = parse_time(line, "COMMENT EMPTY_SCAN", time.trim())?;
            let time = segment.reduction.utc(line, "COMMENT EMPTY_SCAN", time)?;
            segment.records.push(Record { line, time, value: None });
        }
        return Ok(());
    }
    let kind = match key {
        "RANGE" => DataKind::Range,
        "ANGLE_1" => DataKind::Angle1,
        "ANGLE_2" => DataKind::Angle2,
        "DOPPLER_INSTANTANEOUS" => DataKind::Doppler,
        _ if DATA_UNSUPPORTED.contains(&key) => return fail(line, key, "data type not supported"),
        _ => return fail(line, key, "unknown keyword in the data"),
    };
    let mut parts = value.split_whitespace();
    let (Some(time), Some(number), None) = (parts.next(), parts.next(), parts.next()) else {
        return fail(line, key, "expected `KEYWORD = time value`");
    };
    let time = segment.reduction.utc(line, key, parse_time(line, key, time)?)?;
    let number: f64 = match number.parse() {
        // Azimuth and right ascension: wrapped once, exactly, to (−180°, 180°] (crate::io::angles).
        Ok(v) if f64::is_finite(v) && kind == DataKind::Angle1 => match crate::io::angles::wrap_decimal(number) {
            Some(wrapped) => wrapped,
            None => return fail(line, key, format!("{v} deg is outside [-360, 720]")),
        },
        Ok(v) if f64::is_finite(v) => v,
        _ => return fail(line, key, format!("\"{number}\" is not a finite number")),
    };
    let number = segment.reduction.corrected(kind, number);
    segment.records.push(Record { line, time, value: Some((kind, number)) });
    Ok(())
}

/// Parses a TDM in KVN form.
///
/// # Errors
/// The first problem: an unknown keyword, a keyword out of place, a missing `META` block or required
/// keyword, a time system, frame or correction that cannot be read ([`Reduction`]), an angle type other than AZEL or RADEC, range units other than
/// km, a malformed time or value.
pub fn parse(text: &str) -> Result<Tdm, TdmError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut tdm = Tdm::default();
    let mut state = State::Start;
    let mut header_required = [("CREATION_DATE", false), ("ORIGINATOR", false)];
    let mut meta = MetaBlock::starting_at(0);
    let mut last = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        last = line;
        let content = raw.trim();
        if content.is_empty() {
            continue;
        }
        let (key, value) = split_line(content);
        match state {
            State::Start => {
                if key != "CCSDS_TDM_VERS" {
                    return fail(line, key, "a TDM starts with CCSDS_TDM_VERS");
                }
                if value != "1.0" && value != "2.0" {
                    return fail(line, key, format!("version \"{value}\" is not 1.0 or 2.0"));
                }
                state = State::Header;
            }
            State::Header if key == "META_START" => {
                if let Some((missing, _)) = header_required.iter().find(|(_, seen)| !seen) {
                    return fail(line, missing, "required in the header, missing");
                }
                state = State::Meta;
                meta = MetaBlock::starting_at(line);
            }
            State::Header => header_line(line, key, value, &mut header_required)?,
            State::Meta if key == "META_STOP" => {
                if meta.time_system.is_none() {
                    return fail(line, "TIME_SYSTEM", "required in the metadata, missing");
                }
                let Some(participant) = meta.participant.take() else {
                    return fail(line, "PARTICIPANT_1", "required in the metadata, missing");
                };
                meta.reduction.finish()?;
                if let (Some((AngleType::RaDec, _)), Some((crate::sim::fk5::Frame::EarthFixed, frame_line))) =
                    (meta.angle_type, meta.reduction.frame)
                {
                    return fail(
                        frame_line,
                        "REFERENCE_FRAME",
                        "right ascension and declination in an Earth-fixed frame",
                    );
                }
                tdm.segments.push(Segment {
                    meta_line: meta.line,
                    meta_stop_line: line,
                    participant,
                    angle_type: meta.angle_type,
                    reduction: meta.reduction,
                    physics: meta.physics,
                    records: vec![],
                });
                state = State::BetweenMetaAndData;
            }
            State::Meta => meta.read(line, key, value)?,
            State::BetweenMetaAndData if key == "DATA_START" => state = State::Data,
            State::BetweenMetaAndData if key == "COMMENT" => {}
            State::BetweenMetaAndData => return fail(line, key, "DATA_START expected after META_STOP"),
            State::Data if key == "DATA_STOP" => state = State::AfterData,
            State::Data => data_line(&mut tdm, line, key, value)?,
            State::AfterData if key == "META_START" => {
                state = State::Meta;
                meta = MetaBlock::starting_at(line);
            }
            State::AfterData if key == "COMMENT" => {}
            State::AfterData => return fail(line, key, "META_START expected after DATA_STOP"),
        }
    }
    match state {
        State::AfterData => Ok(tdm),
        State::Start => fail(last + 1, "CCSDS_TDM_VERS", "empty file"),
        State::Header => fail(last + 1, "META_START", "no META block"),
        State::Meta => fail(last + 1, "META_STOP", "the file ends inside a META block"),
        State::BetweenMetaAndData => fail(last + 1, "DATA_START", "the file ends before the data"),
        State::Data => fail(last + 1, "DATA_STOP", "the file ends inside the data"),
    }
}

/// A scan read from a TDM, with where it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct SourcedScan {
    /// The scan (sensor index into the configuration, time since its epoch, measurements in degrees).
    pub scan: Scan3dSpec,
    /// The file.
    pub file: PathBuf,
    /// Line of its first record.
    pub line: usize,
}

/// The scans of one parsed TDM under `config` (its sensors, each sensor's kind, and the epoch), in file
/// order.
///
/// # Errors
/// A sensor the configuration does not have, an angle type that is not the measurement type's, components
/// out of order or incomplete, a time before the epoch or before the previous one.
pub fn scans_of(tdm: &Tdm, config: &Scenario3d) -> Result<Vec<(Scan3dSpec, usize)>, TdmError> {
    let epoch = Instant::epoch_of(config);
    let mut scans: Vec<(Scan3dSpec, usize, Instant)> = vec![];
    for segment in &tdm.segments {
        let (name, name_line) = &segment.participant;
        let Some(sensor) = config.sensors.iter().position(|s| &s.name == name) else {
            return fail(*name_line, "PARTICIPANT_1", format!("\"{name}\" is not a sensor of the configuration"));
        };
        let kind = config.kind(sensor);
        let components = DataKind::components(kind);
        let wanted = angle_type_of(kind);
        check_angle_type(segment, wanted, kind)?;
        let first_of_segment = scans.len();
        let mut empty: Vec<(Scan3dSpec, usize, Instant)> = vec![];
        let mut next = 0; // the component the next data line must be
        for record in &segment.records {
            let keyword = record.value.map_or("COMMENT EMPTY_SCAN", |(k, _)| k.keyword());
            let Some(t) = record.time.since(&epoch) else {
                return fail(record.line, keyword, format!("{} is before the epoch {epoch}", record.time));
            };
            let Some((data, value)) = record.value else {
                if let Some((_, _, previous)) = empty.last()
                    && record.time <= *previous
                {
                    return fail(record.line, keyword, format!("{} is not after the previous empty scan", record.time));
                }
                empty.push((Scan3dSpec { time: t, sensor, measurements: vec![] }, record.line, record.time.clone()));
                continue;
            };
            let current = scans.last().filter(|_| scans.len() > first_of_segment);
            match current {
                Some((_, _, time)) if record.time < *time => {
                    return fail(record.line, keyword, format!("{} is before the previous time {time}", record.time));
                }
                Some((_, _, time)) if record.time == *time => {}
                _ => {
                    if next != 0 {
                        return fail(
                            record.line,
                            keyword,
                            format!("the previous measurement lacks {}", components[next].keyword()),
                        );
                    }
                    scans.push((
                        Scan3dSpec { time: t, sensor, measurements: vec![] },
                        record.line,
                        record.time.clone(),
                    ));
                }
            }
            if components.get(next) != Some(&data) {
                return fail(
                    record.line,
                    keyword,
                    format!(
                        "expected {} here (a {} measurement is {})",
                        components[next].keyword(),
                        kind.name(),
                        names(components)
                    ),
                );
            }
            let Some((scan, _, _)) = scans.last_mut() else { continue };
            if next == 0 {
                scan.measurements.push(vec![]);
            }
            if let Some(z) = scan.measurements.last_mut() {
                z.push(value);
            }
            next = (next + 1) % components.len();
        }
        if next != 0 {
            let line = segment.records.last().map_or(segment.meta_stop_line, |r| r.line);
            return fail(line, components[next].keyword(), "the last measurement is incomplete");
        }
        if wanted == Some(AngleType::RaDec) && segment.reduction.from_eme2000() {
            for (scan, line, time) in &mut scans[first_of_segment..] {
                for z in &mut scan.measurements {
                    reduction::ra_dec_to_teme(*line, time, z)?;
                }
            }
        }
        let with_data: std::collections::HashMap<&Instant, usize> =
            scans[first_of_segment..].iter().map(|(_, line, t)| (t, *line)).collect();
        let mut empty_scans = vec![];
        for (scan, line, time) in empty {
            if let Some(other) = with_data.get(&time) {
                return fail(line, "COMMENT EMPTY_SCAN", format!("{time} also has data (line {other})"));
            }
            empty_scans.push((scan, line, time));
        }
        for (scan, line, time) in empty_scans {
            scans.push((scan, line, time));
        }
    }
    Ok(scans.into_iter().map(|(scan, line, _)| (scan, line)).collect())
}

/// The segment's `ANGLE_TYPE` is `wanted` (that of the sensor's `kind` of measurement), or absent from a
/// segment without data; any (or none) for a kind without angles.
fn check_angle_type(segment: &Segment, wanted: Option<AngleType>, kind: Measurement3dSpec) -> Result<(), TdmError> {
    let Some(wanted) = wanted else { return Ok(()) };
    match segment.angle_type {
        Some((t, _)) if t == wanted => {}
        Some((_, line)) => {
            return fail(line, "ANGLE_TYPE", format!("does not match the sensor's {} measurements", kind.name()));
        }
        None if segment.records.iter().any(|r| r.value.is_some()) => {
            return fail(segment.meta_stop_line, "ANGLE_TYPE", "required with angle data, missing");
        }
        None => {}
    }
    Ok(())
}

fn names(components: &[DataKind]) -> String {
    components.iter().map(|c| c.keyword()).collect::<Vec<_>>().join(", ")
}

fn with_file(file: &Path, e: TdmError) -> Error {
    Error::input(format!("{}:{}: {}: {}", file.display(), e.line, e.keyword, e.message))
}

/// Reads the TDMs and makes `config` (a version 2 scenario) with their scans instead of its own and no
/// truth: the scans of every file merged by time.
///
/// # Errors
/// Bad input (exit code 2) naming the file, line and keyword: a TDM problem ([`parse`], [`scans_of`]), two
/// scans at the same time, a scan not after the prior, or a scan the scenario checks refuse.
pub fn scenario_from_tdms(files: &[PathBuf], config: &Scenario3d) -> Result<Scenario3d, Error> {
    scenario_after_prior(files, config, false).map(|(scenario, _)| scenario)
}

/// [`scenario_from_tdms`], with the scans at or before the prior's time left out when `skip` (a run
/// continued from an earlier run's OEM, `track --prior-oem`); returns the scenario and how many were left out.
///
/// # Errors
/// As [`scenario_from_tdms`].
pub fn scenario_after_prior(files: &[PathBuf], config: &Scenario3d, skip: bool) -> Result<(Scenario3d, usize), Error> {
    let mut all: Vec<SourcedScan> = vec![];
    let mut sensors = config.sensors.clone();
    let mut stated = vec![None; sensors.len()];
    for file in files {
        let text = crate::scenario::read_limited(file)?;
        let tdm = parse(&text).map_err(|e| with_file(file, e))?;
        let scans = scans_of(&tdm, config).map_err(|e| with_file(file, e))?;
        for segment in &tdm.segments {
            let Some(i) = sensors.iter().position(|s| s.name == segment.participant.0) else { continue };
            let az_el = config.kind(i).measures_elevation();
            physics::adopt(&mut sensors[i], &segment.physics, az_el, &mut stated[i])
                .map_err(|e| Error::input(format!("{}:{}: {e}", file.display(), segment.meta_line)))?;
        }
        all.extend(scans.into_iter().map(|(scan, line)| SourcedScan { scan, file: file.clone(), line }));
    }
    all.sort_by(|a, b| a.scan.time.total_cmp(&b.scan.time));
    let skipped = if skip { all.partition_point(|s| s.scan.time <= config.prior.time) } else { 0 };
    all.drain(..skipped);
    let at = |s: &SourcedScan| format!("{}:{}", s.file.display(), s.line);
    for pair in all.windows(2) {
        if pair[0].scan.time == pair[1].scan.time {
            return Err(Error::input(format!(
                "{}: two scans at the same time {} s after the epoch (the other at {})",
                at(&pair[1]),
                pair[1].scan.time,
                at(&pair[0])
            )));
        }
    }
    let mut scenario = config.clone();
    scenario.sensors = sensors;
    scenario.truth = None;
    scenario.scans = all.iter().map(|s| s.scan.clone()).collect();
    if let Err(e) = scenario.validate() {
        // A scan's problem names the scan's file and line.
        let text = e.0;
        let located = text.strip_prefix("scans[").and_then(|rest| {
            let (k, rest) = rest.split_once(']')?;
            let source = all.get(k.parse::<usize>().ok()?)?;
            Some(format!("{}: scan{rest}", at(source)))
        });
        return Err(Error::input(located.unwrap_or(text)));
    }
    Ok((scenario, skipped))
}

#[cfg(test)]
mod tests;
