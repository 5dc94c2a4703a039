//! The prior of a run continued from an earlier run's OEM (`host-sim track --prior-oem`): one hypothesis
//! (weight 1) holding one object per OEM segment, its last state and the covariance at that state's epoch,
//! at the OEM's last epoch; it replaces the configuration's prior.
//! States and covariances in EME2000 are turned into TEME, and epochs of TAI, GPS or TT moved to UTC.
//!
//! Refused, with the OEM's line and keyword: a segment without a covariance at its last epoch (the prior
//! needs one; the configuration's prior covariance is not substituted), a covariance that is not
//! positive definite (or has entries beyond the scenario limit), segments that end at different epochs, an
//! epoch before the configuration's, more segments than the tracker holds objects (N).
//!
//! Labels: the segments' `OBJECT_ID`s when every one is a distinct integer in [0, `MAX_PRIOR_LABEL`] (as
//! `tracks.oem` writes them), else 1, 2, … in file order.

use crate::io::ccsds::Instant;
use crate::io::oem::read::{Oem, OemError, OemSegment};
use crate::scenario::MAX_PRIOR_LABEL;
use crate::scenario::v2::{Prior3dSpec, PriorHypothesis3dSpec, PriorObject3dSpec};
use crate::sim::fk5;

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
    let last_epoch = utc_epoch(first)?;
    let Some(time) = last_epoch.since(epoch) else {
        return fail(first.last.line, "EPHEMERIS", format!("{last_epoch} is before the configuration's epoch {epoch}"));
    };
    let (labels, renumbered) = labels(oem);
    let mut objects = Vec::with_capacity(oem.segments.len());
    for (segment, label) in oem.segments.iter().zip(labels) {
        let last = &segment.last;
        if utc_epoch(segment)? != last_epoch {
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
        let (mean, covariance) = in_teme(segment, &last_epoch, covariance.matrix)?;
        objects.push(PriorObject3dSpec { label, mean, covariance });
    }
    Ok(OemPrior {
        prior: Prior3dSpec { time, hypotheses: vec![PriorHypothesis3dSpec { weight: 1.0, objects }] },
        epoch: last_epoch,
        renumbered,
    })
}

/// The segment's last epoch in UTC (moved from its `TIME_SYSTEM` exactly, docs/maths.md §6.11).
fn utc_epoch(segment: &OemSegment) -> Result<Instant, OemError> {
    let (system, line) = segment.time_system;
    let epoch = &segment.last.epoch;
    match fk5::to_utc_offset(system, epoch.julian_date()) {
        Ok(offset) => Ok(epoch.shifted_millis((offset * 1000.0).round() as i64)),
        Err(_) => fail(line, "TIME_SYSTEM", format!("{epoch}: its leap seconds are not in the table (1972 to 2027)")),
    }
}

/// The last state and covariance in TEME: as read, or turned from EME2000 at the UTC epoch `utc`.
fn in_teme(
    segment: &OemSegment,
    utc: &Instant,
    covariance: [[f64; 6]; 6],
) -> Result<([f64; 6], [[f64; 6]; 6]), OemError> {
    let (frame, line) = segment.frame;
    if frame != fk5::Frame::Eme2000 {
        return Ok((segment.last.state, covariance));
    }
    let jd = utc.julian_date();
    match (fk5::state_eme2000_to_teme(segment.last.state, jd), fk5::covariance_eme2000_to_teme(covariance, jd)) {
        (Ok(state), Ok(covariance)) => Ok((state, covariance)),
        _ => fail(line, "REF_FRAME", format!("{utc}: its leap seconds are not in the table (1972 to 2027)")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::oem::read::{OemCovariance, OemState};
    use crate::sim::fk5::{Frame, Reduction, TimeSystem, apply, tt_of_utc};

    fn segment(epoch: &str, state: [f64; 6], covariance: [[f64; 6]; 6], frame: Frame, system: TimeSystem) -> Oem {
        let last = OemState { line: 9, epoch: Instant::parse(epoch).expect("epoch"), state };
        let segment = OemSegment {
            meta_line: 1,
            object_name: "A".into(),
            object_id: ("7".into(), 3),
            last,
            covariance: Some(OemCovariance { line: 10, matrix: covariance }),
            frame: (frame, 4),
            time_system: (system, 5),
        };
        Oem { segments: vec![segment], lines: 20 }
    }

    #[test]
    fn an_oem_in_eme2000_and_tai_gives_the_prior_of_its_teme_and_utc_twin() {
        let epoch = Instant::parse("2020-01-01T00:00:00").expect("epoch");
        let state = [7000.0, 100.0, -200.0, 0.1, 7.5, 1.0];
        let mut covariance = [[0.0; 6]; 6];
        for (k, row) in covariance.iter_mut().enumerate() {
            row[k] = if k < 3 { 0.01 } else { 1e-6 };
        }
        covariance[0][1] = 0.004;
        covariance[1][0] = 0.004;
        let teme = prior_from_oem(
            &segment("2020-01-02T03:04:05.5", state, covariance, Frame::Teme, TimeSystem::Utc),
            &epoch,
            8,
            "test",
        )
        .expect("TEME prior");
        // The same state written in EME2000 at the same instant, its epoch in TAI (37 s ahead of UTC).
        let utc = Instant::parse("2020-01-02T03:04:05.5").expect("utc");
        let m = Reduction::at(tt_of_utc(utc.julian_date()).expect("tt")).teme_to_j2000();
        let r = apply(&m, [state[0], state[1], state[2]]);
        let v = apply(&m, [state[3], state[4], state[5]]);
        let product: [[f64; 6]; 6] = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let block = |a: usize, b: usize| if a / 3 == b / 3 { m[a % 3][b % 3] } else { 0.0 };
                (0..6).map(|k| (0..6).map(|l| block(i, k) * covariance[k][l] * block(j, l)).sum::<f64>()).sum()
            })
        });
        let turned: [[f64; 6]; 6] =
            std::array::from_fn(|i| std::array::from_fn(|j| 0.5 * (product[i][j] + product[j][i])));
        let eme = prior_from_oem(
            &segment(
                "2020-01-02T03:04:42.5",
                [r[0], r[1], r[2], v[0], v[1], v[2]],
                turned,
                Frame::Eme2000,
                TimeSystem::Tai,
            ),
            &epoch,
            8,
            "test",
        )
        .expect("EME2000 prior");
        assert_eq!(eme.epoch, teme.epoch, "TAI epoch moved to UTC exactly");
        assert_eq!(eme.prior.time, teme.prior.time);
        let (a, b) = (&eme.prior.hypotheses[0].objects[0], &teme.prior.hypotheses[0].objects[0]);
        for k in 0..6 {
            assert!((a.mean[k] - b.mean[k]).abs() < 1e-9, "mean {k}: {} vs {}", a.mean[k], b.mean[k]);
            for j in 0..6 {
                assert!((a.covariance[k][j] - b.covariance[k][j]).abs() < 1e-15, "covariance {k} {j}");
            }
        }
        // The two frames differ by 0.28° in 2020: the EME2000 state was really turned.
        let moved = (0..3).map(|k| (r[k] - state[k]).powi(2)).sum::<f64>().sqrt();
        assert!(moved > 10.0, "{moved} km");
    }
}
