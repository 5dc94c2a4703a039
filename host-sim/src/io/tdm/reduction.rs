//! What a TDM segment's metadata says about its data, applied on the way in (docs/maths.md §6.11,
//! docs/scenario-format.md "TDM and OEM"): the time system (UTC, TAI, GPS, TT: times moved to UTC exactly,
//! with the leap seconds of their date), the reference frame of right ascensions and declinations (TEME
//! as read; EME2000/J2000/GCRF/ICRF turned into TEME at each measurement's time; an Earth-fixed frame only
//! for azimuth and elevation), and the corrections (`CORRECTION_RANGE`, `CORRECTION_ANGLE_1`,
//! `CORRECTION_ANGLE_2`, `CORRECTION_DOPPLER` added to the data when `CORRECTIONS_APPLIED = NO`, left out
//! when `YES`; correction keywords without `CORRECTIONS_APPLIED` are refused, never ignored).

use super::{DataKind, TdmError, fail};
use crate::io::ccsds::Instant;
use crate::sim::fk5::{self, Frame, TimeSystem};

/// The metadata a segment's data are read through.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reduction {
    /// `TIME_SYSTEM`.
    pub time_system: TimeSystem,
    /// `REFERENCE_FRAME` and its line (absent: TEME).
    pub frame: Option<(Frame, usize)>,
    /// `CORRECTIONS_APPLIED` (YES: true) and its line.
    pub applied: Option<(bool, usize)>,
    /// `CORRECTION_RANGE`, `_ANGLE_1`, `_ANGLE_2`, `_DOPPLER` (km, deg, deg, km/s) and the line of the first.
    pub corrections: [f64; 4],
    first_correction: Option<(usize, &'static str)>,
    /// Line of a `CORRECTION_ABERRATION_YEARLY` or `_DIURNAL`.
    aberration: Option<usize>,
}

impl Default for Reduction {
    fn default() -> Self {
        Self {
            time_system: TimeSystem::Utc,
            frame: None,
            applied: None,
            corrections: [0.0; 4],
            first_correction: None,
            aberration: None,
        }
    }
}

const CORRECTIONS: [(&str, DataKind); 4] = [
    ("CORRECTION_RANGE", DataKind::Range),
    ("CORRECTION_ANGLE_1", DataKind::Angle1),
    ("CORRECTION_ANGLE_2", DataKind::Angle2),
    ("CORRECTION_DOPPLER", DataKind::Doppler),
];

fn slot(kind: DataKind) -> usize {
    match kind {
        DataKind::Range => 0,
        DataKind::Angle1 => 1,
        DataKind::Angle2 => 2,
        DataKind::Doppler => 3,
    }
}

impl Reduction {
    /// Reads `key = value` when it is one of this module's keywords; `Ok(false)` for any other keyword.
    ///
    /// # Errors
    /// An unsupported time system or frame, a correction that is not a finite number, a `CORRECTIONS_APPLIED`
    /// other than YES or NO.
    pub fn read(&mut self, line: usize, key: &str, value: &str) -> Result<bool, TdmError> {
        match key {
            "TIME_SYSTEM" => match TimeSystem::from_ccsds(value) {
                Some(system) => self.time_system = system,
                None => {
                    return fail(line, key, format!("time system \"{value}\" is not supported (UTC, TAI, GPS or TT)"));
                }
            },
            "REFERENCE_FRAME" => match Frame::from_ccsds(value) {
                Some(frame) => self.frame = Some((frame, line)),
                None => {
                    return fail(
                        line,
                        key,
                        format!(
                            "reference frame \"{value}\" is not supported (TEME, EME2000/J2000/GCRF/ICRF, or ITRF/ECEF \
                             for azimuth and elevation)"
                        ),
                    );
                }
            },
            "CORRECTIONS_APPLIED" => {
                self.applied = Some(match value {
                    "YES" => (true, line),
                    "NO" => (false, line),
                    _ => return fail(line, key, format!("\"{value}\" is not YES or NO")),
                });
            }
            "CORRECTION_ABERRATION_YEARLY" | "CORRECTION_ABERRATION_DIURNAL" => {
                self.aberration.get_or_insert(line);
                self.first_correction.get_or_insert((line, "CORRECTION_ABERRATION"));
            }
            _ => {
                let Some(&(name, kind)) = CORRECTIONS.iter().find(|(name, _)| *name == key) else {
                    return Ok(false);
                };
                let correction: f64 = match value.parse() {
                    Ok(v) if f64::is_finite(v) => v,
                    _ => return fail(line, key, format!("\"{value}\" is not a finite number")),
                };
                self.corrections[slot(kind)] = correction;
                self.first_correction.get_or_insert((line, name));
            }
        }
        Ok(true)
    }

    /// The checks at `META_STOP`: corrections need `CORRECTIONS_APPLIED`.
    ///
    /// # Errors
    /// A correction keyword without `CORRECTIONS_APPLIED`, aberration corrections still to be applied.
    pub fn finish(&self) -> Result<(), TdmError> {
        match (self.first_correction, self.applied, self.aberration) {
            (Some((line, name)), None, _) => fail(
                line,
                name,
                "without CORRECTIONS_APPLIED: say whether the data include it (YES) or it must be added (NO)",
            ),
            (_, Some((false, _)), Some(line)) => fail(
                line,
                "CORRECTION_ABERRATION",
                "aberration corrections are not applied by this reader: apply them first (CORRECTIONS_APPLIED = YES)",
            ),
            _ => Ok(()),
        }
    }

    /// `time` of this segment's time system as a UTC instant.
    ///
    /// # Errors
    /// A date whose leap seconds are not in the table.
    pub fn utc(&self, line: usize, keyword: &str, time: Instant) -> Result<Instant, TdmError> {
        if self.time_system == TimeSystem::Utc {
            return Ok(time);
        }
        match fk5::to_utc_offset(self.time_system, time.julian_date()) {
            Ok(offset) => Ok(time.shifted_millis((offset * 1000.0).round() as i64)),
            Err(e) => fail(line, keyword, format!("{time}: {}", leap_second_message(e))),
        }
    }

    /// `value` of data type `kind` with its correction added when `CORRECTIONS_APPLIED = NO` (a zero
    /// correction leaves the value's bits alone); a corrected azimuth or right ascension is wrapped again.
    pub fn corrected(&self, kind: DataKind, value: f64) -> f64 {
        let correction = self.corrections[slot(kind)];
        match self.applied {
            Some((false, _)) if correction != 0.0 && kind == DataKind::Angle1 => {
                crate::io::angles::wrap(value + correction)
            }
            Some((false, _)) if correction != 0.0 => value + correction,
            _ => value,
        }
    }

    /// Whether right ascensions and declinations must be turned from EME2000 into TEME.
    pub fn from_eme2000(&self) -> bool {
        matches!(self.frame, Some((Frame::Eme2000, _)))
    }
}

fn leap_second_message(error: fk5::TimeScaleError) -> String {
    match error {
        fk5::TimeScaleError::BeforeTable => "before 1972, where UTC has no leap-second table".into(),
        fk5::TimeScaleError::AfterTable => {
            "after the last date the leap-second table knows (2027-01-01): extend sim::fk5::LEAP_SECONDS".into()
        }
    }
}

/// A measurement's (α, δ) in degrees of EME2000 as TEME ones at `time` (UTC).
///
/// # Errors
/// A date whose leap seconds are not in the table.
pub fn ra_dec_to_teme(line: usize, time: &Instant, z: &mut [f64]) -> Result<(), TdmError> {
    let (Some(&alpha), Some(&delta)) = (z.first(), z.get(1)) else { return Ok(()) };
    match fk5::ra_dec_eme2000_to_teme(alpha.to_radians(), delta.to_radians(), time.julian_date()) {
        Ok((alpha, delta)) => {
            z[0] = alpha.to_degrees();
            z[1] = delta.to_degrees();
            Ok(())
        }
        Err(e) => fail(line, "REFERENCE_FRAME", format!("{time}: {}", leap_second_message(e))),
    }
}
