//! CCSDS Orbit Ephemeris Message (OEM, CCSDS 502.0-B-2, KVN form) of a run's MAP tracks: `tracks.oem` in
//! every version 2 `run` and `track` output folder.
//!
//! One segment per *confirmed* track: a label of the last scan's MAP hypothesis whose existence is at least
//! the scenario's `evaluation.confirmation_existence` (the threshold of the birth confirmations in
//! `summary.json`). Its ephemeris lines are the track's MAP mean (km, km/s; TEME, centre EARTH, UTC) at
//! accepted scans where the label is in the MAP hypothesis (a label that leaves the MAP and returns leaves
//! a gap): the first such scan, then the first one at least [`OEM_STEP_S`] after the last line, and always
//! the last one (a 24-hour catalogue run at every scan wrote 560 MB), each with its covariance (lower
//! triangle, km², km²/s, km²/s²). Values are written in their shortest round-trip decimal form, the same
//! f64 as `estimates.csv`; times as in [`crate::io::ccsds`]: a scan time is written with the digits it was
//! read with (a TDM's, a scenario's). [`read`] reads an OEM back, for `host-sim track --prior-oem`.

pub mod read;

use crate::error::Error;
use crate::io::ccsds::{self, Instant};
use crate::pipeline::snapshot::Track6;
use crate::scenario::v2::Scenario3d;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// One ephemeris point: time, mean, covariance.
type Point = (Instant, [f64; 6], [[f64; 6]; 6]);

/// The shortest time (s) between two ephemeris lines of a track, its last line aside.
pub const OEM_STEP_S: f64 = 60.0;

/// A track's ephemeris lines, the time of the last one, and its latest state when that is not a line yet.
#[derive(Debug, Clone, Default)]
struct Series {
    points: Vec<Point>,
    last_time: f64,
    latest: Option<Point>,
}

/// The MAP tracks of a run, scan by scan, and their OEM.
#[derive(Debug, Clone)]
pub struct OemTracks {
    epoch: Instant,
    threshold: f64,
    tracks: BTreeMap<u32, Series>,
    last: Vec<(u32, f64)>,
}

impl OemTracks {
    /// No tracks yet, for `scenario`'s epoch and confirmation threshold.
    pub fn new(scenario: &Scenario3d) -> Self {
        OemTracks {
            epoch: Instant::epoch_of(scenario),
            threshold: scenario.evaluation.confirmation_existence,
            tracks: BTreeMap::new(),
            last: vec![],
        }
    }

    /// Records the MAP tracks after an accepted scan at `time` (s since the epoch; a scan before the epoch
    /// has no UTC time here and is left out).
    pub fn record(&mut self, time: f64, map: &[Track6]) {
        let Ok(at) = self.epoch.after(time) else { return };
        for t in map {
            let series = self.tracks.entry(t.label).or_default();
            let point = (at.clone(), t.mean, t.covariance);
            if series.points.is_empty() || time - series.last_time >= OEM_STEP_S {
                series.points.push(point);
                series.last_time = time;
                series.latest = None;
            } else {
                series.latest = Some(point);
            }
        }
        self.last = map.iter().map(|t| (t.label, t.existence)).collect();
    }

    /// The labels written: those of the last MAP hypothesis with existence ≥ the threshold.
    pub fn confirmed(&self) -> Vec<u32> {
        let mut labels: Vec<u32> = self.last.iter().filter(|(_, e)| *e >= self.threshold).map(|(l, _)| *l).collect();
        labels.sort_unstable();
        labels
    }

    /// The OEM text.
    pub fn text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "CCSDS_OEM_VERS = 2.0");
        let _ = writeln!(s, "COMMENT MAP tracks of R-FISST, existence >= {} at the last scan", self.threshold);
        let _ = writeln!(s, "CREATION_DATE = {}", ccsds::now());
        let _ = writeln!(s, "ORIGINATOR = R-FISST host-sim");
        for label in self.confirmed() {
            let Some(series) = self.tracks.get(&label) else { continue };
            let points: Vec<&Point> = series.points.iter().chain(&series.latest).collect();
            let (Some(first), Some(last)) = (points.first(), points.last()) else { continue };
            let _ = writeln!(s, "\nMETA_START");
            let _ = writeln!(s, "OBJECT_NAME = TRACK {label}");
            let _ = writeln!(s, "OBJECT_ID = {label}");
            let _ = writeln!(s, "CENTER_NAME = EARTH");
            let _ = writeln!(s, "REF_FRAME = TEME");
            let _ = writeln!(s, "TIME_SYSTEM = UTC");
            let _ = writeln!(s, "START_TIME = {}", first.0);
            let _ = writeln!(s, "STOP_TIME = {}", last.0);
            let _ = writeln!(s, "META_STOP\n");
            for (t, m, _) in &points {
                let _ = writeln!(s, "{} {} {} {} {} {} {}", t, m[0], m[1], m[2], m[3], m[4], m[5]);
            }
            let _ = writeln!(s, "\nCOVARIANCE_START");
            for (t, _, p) in &points {
                let _ = writeln!(s, "EPOCH = {}", t);
                let _ = writeln!(s, "COV_REF_FRAME = TEME");
                for (i, row) in p.iter().enumerate() {
                    let values: Vec<String> = row[..=i].iter().map(f64::to_string).collect();
                    let _ = writeln!(s, "{}", values.join(" "));
                }
            }
            let _ = writeln!(s, "COVARIANCE_STOP");
        }
        s
    }

    /// Writes the OEM to `path`.
    ///
    /// # Errors
    /// [`Error::Output`] when it cannot be written.
    pub fn write(&self, path: &Path) -> Result<(), Error> {
        crate::io::atomic::write(path, self.text())
    }
}
