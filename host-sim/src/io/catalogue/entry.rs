//! One element set of any format ([`CatalogueEntry`]), its checks and the error naming a bad file's line and keyword.

use crate::Error;
use sgp4::chrono::NaiveDateTime;
use std::fmt;

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
pub(super) enum Field {
    Inclination,
    RightAscension,
    Eccentricity,
    ArgumentOfPerigee,
    MeanAnomaly,
    MeanMotion,
}

impl Field {
    pub(super) fn omm(self) -> &'static str {
        match self {
            Field::Inclination => "INCLINATION",
            Field::RightAscension => "RA_OF_ASC_NODE",
            Field::Eccentricity => "ECCENTRICITY",
            Field::ArgumentOfPerigee => "ARG_OF_PERICENTER",
            Field::MeanAnomaly => "MEAN_ANOMALY",
            Field::MeanMotion => "MEAN_MOTION",
        }
    }

    pub(super) fn tle(self) -> &'static str {
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
    pub(super) fn check_ranges(&self) -> Result<(), (Field, String)> {
        let angle = |field, v: f64, max: f64| {
            if (0.0..=max).contains(&v) {
                Ok(())
            } else {
                Err((field, format!("{} is not in [0, {max}] degrees", crate::scenario::Readable(v))))
            }
        };
        angle(Field::Inclination, self.inclination, 180.0)?;
        angle(Field::RightAscension, self.right_ascension, 360.0)?;
        angle(Field::ArgumentOfPerigee, self.argument_of_perigee, 360.0)?;
        angle(Field::MeanAnomaly, self.mean_anomaly, 360.0)?;
        if !(0.0..1.0).contains(&self.eccentricity) {
            return Err((
                Field::Eccentricity,
                format!("{} is not in [0, 1)", crate::scenario::Readable(self.eccentricity)),
            ));
        }
        if !(self.mean_motion > 0.0 && self.mean_motion.is_finite()) {
            return Err((
                Field::MeanMotion,
                format!("{} rev/day is not finite and > 0", crate::scenario::Readable(self.mean_motion)),
            ));
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

/// A catalogue error at `line` of `file`, naming the keyword (both cut to one line, quoted input to an
/// excerpt).
pub(crate) fn err(file: &str, line: usize, keyword: impl Into<String>, message: impl Into<String>) -> CatalogueError {
    let cut = |text: String| crate::scenario::one_line(&crate::scenario::cut_quotes(&text));
    CatalogueError { file: file.to_string(), line, keyword: cut(keyword.into()), message: cut(message.into()) }
}
