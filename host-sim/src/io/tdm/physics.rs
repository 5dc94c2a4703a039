//! What a TDM segment states about its measurements' physics, and how `host-sim track` uses it
//! (docs/scenario-format.md, "TDM and OEM"):
//!
//! - light time from `PATH` and `TIMETAG_REF` (`PARTICIPANT_1` is the sensor): `1,2,1` two-way, `2,1`
//!   one-way downlink, `1,2` one-way uplink; the time tag `RECEIVE` (the default of CCSDS 503.0-B-2) or
//!   `TRANSMIT`. A downlink tagged at transmission or an uplink tagged at reception is tagged at the
//!   object: no delay of the object (the site's motion over τ, ≤ v_s τ, is neglected). No `PATH`: none.
//! - refraction: the elevations of `ANGLE_TYPE = AZEL` from a ground site are taken as observed
//!   (apparent), Bennett's refraction in standard air removed; right ascensions and declinations as
//!   astrometric (refraction removed by the reduction against stars).
//! - `COMMENT LIGHT_TIME NONE` and `COMMENT REFRACTION NONE` in the metadata say the data has neither
//!   (`export-tdm` writes them for simulated sensors without them, so that exports track back as before).
//!
//! A sensor's `light_time` and `refraction` in the configuration win over what the TDM states.

use super::{TdmError, fail};
use crate::scenario::v2::{LightTimeSpec, Measurement3dSpec, RefractionSpec, Sensor3dSpec};

/// The metadata comment: no light time in the data.
pub const NO_LIGHT_TIME: &str = "LIGHT_TIME NONE";

/// The metadata comment: no refraction in the elevations.
pub const NO_REFRACTION: &str = "REFRACTION NONE";

/// The signal path of a segment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SignalPath {
    /// `1,2,1`.
    TwoWay,
    /// `2,1`: object to sensor.
    Downlink,
    /// `1,2`: sensor to object.
    Uplink,
}

/// What a segment's metadata states.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Statement {
    /// `PATH`.
    pub path: Option<SignalPath>,
    /// `TIMETAG_REF = TRANSMIT`.
    pub transmit_tag: bool,
    /// `COMMENT LIGHT_TIME NONE`.
    pub no_light_time: bool,
    /// `COMMENT REFRACTION NONE`.
    pub no_refraction: bool,
}

impl Statement {
    /// Reads a metadata line it owns (`PATH`, `TIMETAG_REF`, the two comments); `false` for any other.
    ///
    /// # Errors
    /// A `PATH` or `TIMETAG_REF` value not supported.
    pub fn read(&mut self, line: usize, key: &str, value: &str) -> Result<bool, TdmError> {
        match key {
            "PATH" => {
                let hops: String = value.chars().filter(|c| !c.is_whitespace()).collect();
                self.path = Some(match hops.as_str() {
                    "1,2,1" => SignalPath::TwoWay,
                    "2,1" => SignalPath::Downlink,
                    "1,2" => SignalPath::Uplink,
                    _ => {
                        return fail(
                            line,
                            key,
                            format!("path \"{value}\" is not supported (1,2,1, 2,1 or 1,2; PARTICIPANT_1 the sensor)"),
                        );
                    }
                });
            }
            "TIMETAG_REF" => match value {
                "RECEIVE" => self.transmit_tag = false,
                "TRANSMIT" => self.transmit_tag = true,
                _ => return fail(line, key, format!("\"{value}\" is not RECEIVE or TRANSMIT")),
            },
            "COMMENT" if value == NO_LIGHT_TIME => self.no_light_time = true,
            "COMMENT" if value == NO_REFRACTION => self.no_refraction = true,
            _ => return Ok(false),
        }
        Ok(true)
    }

    /// The light time the segment states.
    pub fn light_time(&self) -> LightTimeSpec {
        match (self.path, self.transmit_tag) {
            _ if self.no_light_time => LightTimeSpec::Off,
            (None, _) | (Some(SignalPath::Downlink), true) | (Some(SignalPath::Uplink), false) => LightTimeSpec::Off,
            (Some(SignalPath::TwoWay), false) => LightTimeSpec::TwoWayReceive,
            (Some(SignalPath::TwoWay), true) => LightTimeSpec::TwoWayTransmit,
            (Some(SignalPath::Downlink), false) => LightTimeSpec::OneWayReceive,
            (Some(SignalPath::Uplink), true) => LightTimeSpec::OneWayTransmit,
        }
    }

    /// The refraction an azimuth and elevation segment states (`az_el`); none for right ascension and
    /// declination.
    pub fn refraction(&self, az_el: bool) -> RefractionSpec {
        if az_el && !self.no_refraction { RefractionSpec::STANDARD } else { RefractionSpec::None }
    }
}

/// The metadata lines `export-tdm` writes for `sensor`'s physics: `PATH`, `TIMETAG_REF` and the comments
/// that say what the data lacks: a sensor of `kind` without range receives only (downlink), one without
/// elevations needs no refraction comment.
pub fn export_lines(sensor: &Sensor3dSpec, kind: Measurement3dSpec) -> Vec<String> {
    let light_time = sensor.light_time.unwrap_or_default();
    let passive = !kind.has_range();
    let (path, tag) = match light_time {
        LightTimeSpec::Off | LightTimeSpec::OneWayReceive if passive => ("2,1", None),
        LightTimeSpec::Off | LightTimeSpec::TwoWayReceive => ("1,2,1", None),
        LightTimeSpec::TwoWayTransmit => ("1,2,1", Some("TRANSMIT")),
        LightTimeSpec::OneWayReceive => ("2,1", None),
        LightTimeSpec::OneWayTransmit => ("1,2", Some("TRANSMIT")),
    };
    let mut lines = vec![format!("PATH = {path}")];
    lines.extend(tag.map(|t| format!("TIMETAG_REF = {t}")));
    if light_time == LightTimeSpec::Off {
        lines.push(format!("COMMENT {NO_LIGHT_TIME}"));
    }
    if kind.measures_elevation() && sensor.atmosphere().is_none() {
        lines.push(format!("COMMENT {NO_REFRACTION}"));
    }
    lines
}

/// `sensor`'s light time and refraction where the configuration does not state them: as `statement`
/// says. `stated` holds what an earlier segment of the same sensor stated.
///
/// # Errors
/// A message when two segments of the sensor state different physics.
pub fn adopt(
    sensor: &mut Sensor3dSpec,
    statement: &Statement,
    az_el: bool,
    stated: &mut Option<(LightTimeSpec, RefractionSpec)>,
) -> Result<(), String> {
    let now = (statement.light_time(), statement.refraction(az_el));
    match stated {
        Some(before) if *before != now => {
            return Err(format!(
                "sensor \"{}\": its segments state different light time or refraction ({} and {})",
                sensor.name,
                before.0.name(),
                now.0.name()
            ));
        }
        Some(_) => return Ok(()),
        None => *stated = Some(now),
    }
    sensor.light_time.get_or_insert(now.0);
    sensor.refraction.get_or_insert(now.1);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stated(lines: &[(&str, &str)]) -> Result<Statement, TdmError> {
        let mut statement = Statement::default();
        for (i, (key, value)) in lines.iter().enumerate() {
            assert!(statement.read(i + 1, key, value)?, "{key} is the statement's");
        }
        Ok(statement)
    }

    #[test]
    fn path_and_time_tag_give_the_light_time() {
        let cases = [
            (vec![], LightTimeSpec::Off),
            (vec![("PATH", "1,2,1")], LightTimeSpec::TwoWayReceive),
            (vec![("PATH", "1, 2, 1"), ("TIMETAG_REF", "TRANSMIT")], LightTimeSpec::TwoWayTransmit),
            (vec![("PATH", "2,1"), ("TIMETAG_REF", "RECEIVE")], LightTimeSpec::OneWayReceive),
            (vec![("PATH", "2,1"), ("TIMETAG_REF", "TRANSMIT")], LightTimeSpec::Off),
            (vec![("PATH", "1,2"), ("TIMETAG_REF", "TRANSMIT")], LightTimeSpec::OneWayTransmit),
            (vec![("PATH", "1,2")], LightTimeSpec::Off),
            (vec![("PATH", "1,2,1"), ("COMMENT", NO_LIGHT_TIME)], LightTimeSpec::Off),
        ];
        for (lines, wanted) in cases {
            assert_eq!(stated(&lines).expect("read").light_time(), wanted, "{lines:?}");
        }
        let none = stated(&[("COMMENT", NO_REFRACTION)]).expect("read");
        assert_eq!(none.refraction(true), RefractionSpec::None);
        assert_eq!(Statement::default().refraction(true), RefractionSpec::STANDARD);
        assert_eq!(Statement::default().refraction(false), RefractionSpec::None);
        assert!(!Statement::default().read(1, "COMMENT", "another remark").expect("not an error"));
    }

    #[test]
    fn unsupported_paths_and_time_tags_are_refused() {
        let path = stated(&[("PATH", "1,2,3")]).unwrap_err();
        assert_eq!((path.line, path.keyword.as_str()), (1, "PATH"));
        assert!(path.message.contains("path \"1,2,3\" is not supported"), "{}", path.message);
        let tag = stated(&[("TIMETAG_REF", "MIDDLE")]).unwrap_err();
        assert_eq!(tag.keyword, "TIMETAG_REF");
    }
}
