//! Scoring a whole catalogue against its truth with the run's own metric code, component by component
//! ([`crate::eval::components`]): GOSPA and label switches ([`crate::eval::score`]), births and false
//! tracks ([`BirthTally`]), the observed and unobserved objects' errors ([`observed_errors`]).
//!
//! Detections are recorded at every scan; the MAP tracks are scored once a simulated minute
//! ([`SCORE_INTERVAL_S`]) and at the last scan, so that scoring costs little beside tracking.

use crate::eval::births::{BirthTally, MapTrack};
use crate::eval::components::components;
use crate::eval::metrics::LabelSwitches;
use crate::eval::observed::{MATCH_CUTOFF_KM, ObjectAt, ObservedErrors, observed_errors};
use crate::eval::score::score;
use crate::pipeline::orbital::Posterior6;
use crate::scenario::EvaluationSpec;
use std::collections::{HashMap, HashSet};

/// Simulated seconds between two scored scans.
pub const SCORE_INTERVAL_S: f64 = 60.0;

/// The run's figures so far.
pub struct Score {
    evaluation: EvaluationSpec,
    births: BirthTally,
    switches: LabelSwitches,
    /// Each scored scan's GOSPA.
    gospa: Vec<f64>,
    prior_labels: HashSet<u32>,
    last_observed: HashMap<u64, f64>,
    next: f64,
    /// At the last scored scan.
    pub observed: ObservedErrors,
}

/// What the scoring gives the report.
pub struct Figures {
    pub births_total: usize,
    pub births_confirmed: usize,
    pub false_tracks: usize,
    pub mean_gospa: f64,
    pub label_switches: usize,
    pub scored_scans: usize,
    pub observed: ObservedErrors,
}

impl Score {
    /// The scoring of a run whose births are `births` (truth ids) and whose prior labels are `prior_labels`.
    pub fn new(evaluation: EvaluationSpec, births: Vec<u64>, prior_labels: HashSet<u32>) -> Self {
        Score {
            evaluation,
            births: BirthTally::new(births, evaluation.confirmation_existence, evaluation.error_bound),
            switches: LabelSwitches::new(),
            gospa: vec![],
            prior_labels,
            last_observed: HashMap::new(),
            next: f64::NEG_INFINITY,
            observed: ObservedErrors::default(),
        }
    }

    /// Records the objects `detected` at scan `k` (time `time`).
    pub fn detected(&mut self, k: usize, time: f64, detected: &[u64]) {
        for &id in detected {
            self.last_observed.insert(id, time);
        }
        self.births.record(k, &[], detected.iter().copied(), &[], &[]);
    }

    /// Whether scan at `time` is scored (the last one always is).
    pub fn due(&self, time: f64) -> bool {
        time >= self.next
    }

    /// Scores scan `k` at `time`: `truth` (id, position) against the MAP tracks of `posterior`.
    pub fn score(&mut self, k: usize, time: f64, truth: &[(u64, [f64; 3])], posterior: &Posterior6) {
        self.next = time + SCORE_INTERVAL_S;
        let map: Vec<(u32, [f64; 3])> =
            posterior.map.iter().map(|t| (t.label, [t.mean[0], t.mean[1], t.mean[2]])).collect();
        let points: Vec<[f64; 3]> = truth.iter().map(|t| t.1).collect();
        let estimates: Vec<[f64; 3]> = map.iter().map(|t| t.1).collect();
        let e = self.evaluation;
        let mut sum = 0.0;
        // The error bound is within the cut-off: everything the tally looks at is inside one component.
        for part in components(&points, &estimates, e.gospa_cutoff.max(e.error_bound)) {
            let t: Vec<(u64, [f64; 3])> = part.truth.iter().map(|&i| truth[i]).collect();
            let m: Vec<(u32, [f64; 3])> = part.estimates.iter().map(|&j| map[j]).collect();
            let scored = score(&t, &m, &e);
            sum += scored.gospa.powf(e.gospa_order);
            self.switches.record(&scored.pairs);
            let objects: Vec<(u64, &[f64])> = t.iter().map(|(id, p)| (*id, &p[..])).collect();
            let tracks: Vec<MapTrack<'_>> = part
                .estimates
                .iter()
                .zip(&m)
                .map(|(&j, (label, p))| MapTrack {
                    label: *label,
                    position: &p[..],
                    existence: posterior.map[j].existence,
                })
                .collect();
            self.births.record(k, &objects, [], &tracks, &scored.bound_assignment);
        }
        self.gospa.push(sum.powf(1.0 / e.gospa_order));
        let objects: Vec<ObjectAt<3>> = truth
            .iter()
            .map(|&(id, position)| ObjectAt {
                id,
                position,
                prior_label: u32::try_from(id).ok().filter(|l| self.prior_labels.contains(l)),
                last_observed: self.last_observed.get(&id).copied(),
            })
            .collect();
        self.observed = observed_errors(time, &objects, &map, MATCH_CUTOFF_KM);
    }

    /// The figures of the run.
    pub fn figures(&self) -> Figures {
        let births = self.births.figures();
        Figures {
            births_total: births.births_total,
            births_confirmed: births.births_confirmed,
            false_tracks: births.false_tracks,
            mean_gospa: crate::experiments::common::mean(&self.gospa),
            label_switches: self.switches.total(),
            scored_scans: self.gospa.len(),
            observed: self.observed,
        }
    }
}
