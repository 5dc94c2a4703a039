//! SGP4 propagation of an entry (AFSPC-compatibility mode, WGS-72): TEME position and velocity at a tracker time.

use super::entry::CatalogueEntry;
use sgp4::chrono::NaiveDateTime;
use std::fmt;

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
    /// SGP4 returned a state that is not finite (elements far outside its domain, such as a mean motion of
    /// 1e141 revolutions a day, which it does not refuse).
    NonFinite,
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
            PropagationError::NonFinite => "non-finite-state",
        }
    }
}

impl fmt::Display for PropagationError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PropagationError::Elements(e) => write!(f, "SGP4 initialisation: {e}"),
            PropagationError::Propagation(e) => write!(f, "SGP4: {e}"),
            PropagationError::NonFinite => write!(f, "SGP4: the state is not finite (elements outside SGP4's domain)"),
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
        if !p.position.iter().chain(&p.velocity).all(|x| x.is_finite()) {
            return Err(PropagationError::NonFinite);
        }
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
