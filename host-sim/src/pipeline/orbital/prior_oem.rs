//! The prior of a run continued from an earlier run's OEM (`host-sim track --prior-oem`): one hypothesis
//! (weight 1) holding one object per OEM segment, its last state and the covariance at that state's epoch,
//! at the OEM's last epoch; it replaces the configuration's prior.
//!
//! Refused, with the OEM's line and keyword: a segment without a covariance at its last epoch (the prior
//! needs one; the configuration's prior covariance is not substituted), a covariance that is not
//! positive definite (or has entries beyond the scenario limit), segments that end at different epochs, an
//! epoch before the configuration's, more segments than the tracker holds objects (N).
//!
//! Labels: the segments' `OBJECT_ID`s when every one is a distinct integer in [0, `MAX_PRIOR_LABEL`] (as
//! `tracks.oem` writes them), else 1, 2, … in file order.

use crate::io::ccsds::Instant;
use crate::io::oem::read::{Oem, OemError};
use crate::scenario::MAX_PRIOR_LABEL;
use crate::scenario::v2::{Prior3dSpec, PriorHypothesis3dSpec, PriorObject3dSpec};

/// A prior read from an OEM.
#[derive(Debug, Clone, PartialEq)]
pub struct OemPrior {
    /// The prior (time: seconds from the configuration's epoch to the OEM's last epoch).
    pub prior: Prior3dSpec,
    /// The OEM's last epoch.
    pub epoch: Instant,
    /// Whether the labels are the segments' numbers in file order (the `OBJECT_ID`s are not labels).
    pub renumbered: bool,
}

fn fail<T>(line: usize, keyword: &str, message: impl std::fmt::Display) -> Result<T, OemError> {
    Err(OemError { line, keyword: keyword.into(), message: message.to_string() })
}

/// The labels of the segments: their `OBJECT_ID`s when they are distinct labels, else 1, 2, …
fn labels(oem: &Oem) -> (Vec<u32>, bool) {
    let ids: Vec<Option<u32>> =
        oem.segments.iter().map(|s| s.object_id.0.parse::<u32>().ok().filter(|&l| l <= MAX_PRIOR_LABEL)).collect();
    let mut sorted: Vec<u32> = ids.iter().flatten().copied().collect();
    sorted.sort_unstable();
    sorted.dedup();
    if sorted.len() == ids.len() {
        (ids.into_iter().flatten().collect(), false)
    } else {
        ((1..=oem.segments.len() as u32).collect(), true)
    }
}

/// The prior of `oem` for a configuration with epoch `epoch`, for a tracker of `capacity` objects per
/// hypothesis (`profile` names it in the message).
///
/// # Errors
/// See the module documentation.
pub fn prior_from_oem(oem: &Oem, epoch: &Instant, capacity: usize, profile: &str) -> Result<OemPrior, OemError> {
    if let Some(extra) = oem.segments.get(capacity) {
        return fail(
            extra.meta_line,
            "META_START",
            format!(
                "{} objects, more than the {capacity} a hypothesis of the {profile} profile holds (N)",
                oem.segments.len()
            ),
        );
    }
    let Some(first) = oem.segments.first() else {
        return fail(oem.lines + 1, "META_START", "no segment");
    };
    let last_epoch = first.last.epoch.clone();
    let Some(time) = last_epoch.since(epoch) else {
        return fail(first.last.line, "EPHEMERIS", format!("{last_epoch} is before the configuration's epoch {epoch}"));
    };
    let (labels, renumbered) = labels(oem);
    let mut objects = Vec::with_capacity(oem.segments.len());
    for (segment, label) in oem.segments.iter().zip(labels) {
        let last = &segment.last;
        if last.epoch != last_epoch {
            return fail(
                last.line,
                "EPHEMERIS",
                format!("the segment ends at {}, the first one at {last_epoch}: a prior needs one epoch", last.epoch),
            );
        }
        let Some(covariance) = &segment.covariance else {
            return fail(
                last.line,
                "COVARIANCE",
                format!("no covariance at the segment's last epoch {} (--prior-oem needs one)", last.epoch),
            );
        };
        let matrix = nalgebra::SMatrix::<f64, 6, 6>::from_fn(|i, j| covariance.matrix[i][j]);
        if let Err(e) = crate::scenario::check_covariance("", matrix) {
            let reason = e.0.trim_start_matches(": ");
            return fail(covariance.line, "COVARIANCE", format!("the covariance at {}: {reason}", last.epoch));
        }
        objects.push(PriorObject3dSpec { label, mean: last.state, covariance: covariance.matrix });
    }
    Ok(OemPrior {
        prior: Prior3dSpec { time, hypotheses: vec![PriorHypothesis3dSpec { weight: 1.0, objects }] },
        epoch: last_epoch,
        renumbered,
    })
}
