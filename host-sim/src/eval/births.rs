//! Births and false tracks of a run, scan by scan, for `summary.json` of `host-sim run` (planar and 3-D).
//!
//! A *birth* is a true object the prior does not know (`in_prior` false, whether it exists from the
//! start or is born during the run). It is *confirmed* at the first scan where the MAP hypothesis holds a
//! track of existence ≥ `confirmation_existence` that GOSPA with cut-off `error_bound` (order 1) assigns
//! to it, from its first detection on (before it, a track near the object is a neighbour's). Its *detections to confirmation* are the measurements the truth attributes to it (the scan's
//! `origins`) from its first one up to and including the confirmation scan, and its *scans to
//! confirmation* the scans from the first detection to the confirmation, both ends counted.
//!
//! Its *labels* are the distinct labels of the confirmed MAP tracks (existence ≥ `confirmation_existence`)
//! that GOSPA assigns to it at any scan from its first detection on: 1 when it is confirmed under one label
//! and keeps it (or loses it and is never found again), more when a second label takes it over.
//!
//! A *false track* is a label that is in the MAP hypothesis with existence ≥ `confirmation_existence`
//! at one scan at least, and whose MAP estimate is never closer than `error_bound` to a true object at
//! any scan where the label is in the MAP hypothesis.

use crate::io::report::{BirthConfirmation, BirthFigures, BirthRecord, BirthsSummary};
use std::collections::{BTreeMap, BTreeSet};

/// One MAP track as the tally sees it: label, position, existence of the label.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapTrack<'a> {
    /// Label.
    pub label: u32,
    /// Position (the first components of the state).
    pub position: &'a [f64],
    /// Existence probability of the label.
    pub existence: f64,
}

#[derive(Debug, Clone, Default, PartialEq)]
struct Birth {
    first_detection: Option<usize>,
    detections: usize,
    /// (scan, detections by then).
    confirmed: Option<(usize, usize)>,
    /// The confirmed labels assigned to it from its first detection on.
    labels: BTreeSet<u32>,
}

/// What the tally knows of a label of the MAP hypothesis.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Label {
    confirmed: bool,
    near: bool,
}

/// Births and false tracks of a run.
#[derive(Debug, Clone, PartialEq)]
pub struct BirthTally {
    births: BTreeMap<u64, Birth>,
    labels: BTreeMap<u32, Label>,
    threshold: f64,
    error_bound: f64,
}

impl BirthTally {
    /// A tally of the births `births` (truth ids), with the scenario's confirmation threshold and error
    /// bound.
    pub fn new(births: impl IntoIterator<Item = u64>, threshold: f64, error_bound: f64) -> Self {
        BirthTally {
            births: births.into_iter().map(|id| (id, Birth::default())).collect(),
            labels: BTreeMap::new(),
            threshold,
            error_bound,
        }
    }

    /// Records scan `k`: the true objects (id, position), the ids that produced a measurement, the MAP
    /// tracks and, per true object, the MAP track GOSPA (cut-off `error_bound`) assigns to it.
    pub fn record(
        &mut self,
        k: usize,
        truth: &[(u64, &[f64])],
        detected: impl IntoIterator<Item = u64>,
        map: &[MapTrack<'_>],
        assignment: &[Option<usize>],
    ) {
        for id in detected {
            if let Some(b) = self.births.get_mut(&id) {
                b.detections += 1;
                b.first_detection.get_or_insert(k);
            }
        }
        for ((id, _), assigned) in truth.iter().zip(assignment) {
            let Some(b) = self.births.get_mut(id) else { continue };
            // Not before its first detection: a track near an undetected birth is a neighbour's.
            let confirmed_track = assigned
                .and_then(|e| map.get(e))
                .filter(|t| t.existence >= self.threshold && b.first_detection.is_some());
            if let Some(track) = confirmed_track {
                b.confirmed.get_or_insert((k, b.detections));
                b.labels.insert(track.label);
            }
        }
        let near_truth = Near::new(truth.iter().map(|(_, p)| *p), self.error_bound, map.len());
        for t in map {
            let near = near_truth.any_within(t.position);
            let label = self.labels.entry(t.label).or_default();
            label.confirmed |= t.existence >= self.threshold;
            label.near |= near;
        }
    }

    /// The scan at which birth `id` was confirmed, if it is a birth and was.
    pub fn confirmed_at(&self, id: u64) -> Option<usize> {
        self.births.get(&id).and_then(|b| b.confirmed).map(|c| c.0)
    }

    /// The labels `counted` picks that the MAP hypothesis held with existence ≥ the confirmation threshold
    /// at some scan (near a true object or not).
    pub fn confirmed_labels(&self, counted: impl Fn(u32) -> bool) -> usize {
        self.labels.iter().filter(|(label, l)| l.confirmed && counted(**label)).count()
    }

    /// Whether `id` is a birth.
    pub fn is_birth(&self, id: u64) -> bool {
        self.births.contains_key(&id)
    }

    /// The figures so far.
    pub fn figures(&self) -> BirthFigures {
        let records: Vec<BirthRecord> = self
            .births
            .iter()
            .map(|(&object, b)| BirthRecord {
                object,
                first_detection_scan: b.first_detection,
                confirmation_scan: b.confirmed.map(|c| c.0),
                detections_to_confirm: b.confirmed.map(|c| c.1),
                scans_to_confirm: b.confirmed.zip(b.first_detection).map(|((scan, _), first)| scan + 1 - first),
                confirmed_labels: b.labels.len(),
            })
            .collect();
        let detections: Vec<usize> = records.iter().filter_map(|r| r.detections_to_confirm).collect();
        BirthFigures {
            births_total: records.len(),
            births_confirmed: detections.len(),
            mean_detections_to_confirm: (!detections.is_empty())
                .then(|| detections.iter().sum::<usize>() as f64 / detections.len() as f64),
            max_detections_to_confirm: detections.iter().copied().max(),
            max_labels_per_birth: records
                .iter()
                .filter(|r| r.confirmation_scan.is_some())
                .map(|r| r.confirmed_labels)
                .max(),
            false_tracks: self.labels.values().filter(|l| l.confirmed && !l.near).count(),
            records,
        }
    }
}

fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

impl BirthFigures {
    /// The summary `summary.json` writes; false tracks only with a truth to compare with.
    pub fn summary(self, has_truth: bool) -> BirthsSummary {
        BirthsSummary {
            births_total: self.births_total,
            births_confirmed: self.births_confirmed,
            birth_confirmation_scans: self
                .records
                .iter()
                .map(|r| BirthConfirmation { object: r.object, scan: r.confirmation_scan })
                .collect(),
            mean_detections_to_confirm: self.mean_detections_to_confirm,
            max_detections_to_confirm: self.max_detections_to_confirm,
            max_labels_per_birth: self.max_labels_per_birth,
            false_tracks: has_truth.then_some(self.false_tracks),
            birth_confirmations: self.records,
        }
    }
}

/// Whether a position lies within `bound` of one of a set of points: each point tried in turn, or, when
/// the points times the queries exceed [`Near::GRID_ABOVE`], only the points of the grid cells (side
/// `bound`) around it: the same answer (a point within `bound` lies in a neighbouring cell), at a cost that
/// grows with the points and queries rather than their product.
struct Near<'a> {
    points: Vec<&'a [f64]>,
    bound: f64,
    grid: Option<std::collections::HashMap<[i64; 3], Vec<usize>>>,
}

impl<'a> Near<'a> {
    /// Above this many (point, query) pairs the points go into a grid.
    const GRID_ABOVE: usize = 1 << 20;

    fn cell(&self, position: &[f64]) -> [i64; 3] {
        // `as` saturates; a non-finite coordinate is never within the bound of anything.
        core::array::from_fn(|d| position.get(d).map_or(0, |x| (x / self.bound).floor() as i64))
    }

    fn new(points: impl Iterator<Item = &'a [f64]>, bound: f64, queries: usize) -> Self {
        let mut near = Near { points: points.collect(), bound, grid: None };
        let gridded = bound > 0.0 && bound.is_finite() && near.points.iter().all(|p| p.len() <= 3);
        if gridded && near.points.len().saturating_mul(queries) > Self::GRID_ABOVE {
            let mut grid: std::collections::HashMap<[i64; 3], Vec<usize>> = std::collections::HashMap::new();
            for (i, p) in near.points.iter().enumerate() {
                grid.entry(near.cell(p)).or_default().push(i);
            }
            near.grid = Some(grid);
        }
        near
    }

    fn any_within(&self, position: &[f64]) -> bool {
        let Some(grid) = &self.grid else {
            return self.points.iter().any(|p| distance(p, position) < self.bound);
        };
        let centre = self.cell(position);
        (0..27usize).any(|k| {
            let cell: [i64; 3] =
                core::array::from_fn(|d| centre[d].saturating_add((k / 3usize.pow(d as u32) % 3) as i64 - 1));
            grid.get(&cell).is_some_and(|near| near.iter().any(|&i| distance(self.points[i], position) < self.bound))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn track(label: u32, position: &[f64], existence: f64) -> MapTrack<'_> {
        MapTrack { label, position, existence }
    }

    /// The grid answers as trying every point does, in 2-D and 3-D, on points at about the bound.
    #[test]
    fn near_by_grid_answers_as_every_point() {
        let mut random = crate::sim::rng::Random::stream(3, crate::sim::rng::Stream::Scenario, 0);
        for (dimension, bound) in [(2, 1.5), (3, 5.0)] {
            let points: Vec<Vec<f64>> =
                (0..2000).map(|_| (0..dimension).map(|_| random.uniform() * 100.0 - 50.0).collect()).collect();
            let queries: Vec<Vec<f64>> =
                (0..2000).map(|_| (0..dimension).map(|_| random.uniform() * 100.0 - 50.0).collect()).collect();
            let slices = || points.iter().map(Vec::as_slice);
            let (gridded, linear) = (Near::new(slices(), bound, queries.len()), Near::new(slices(), bound, 0));
            assert!(gridded.grid.is_some() && linear.grid.is_none());
            let answers: Vec<bool> = queries.iter().map(|q| gridded.any_within(q)).collect();
            assert_eq!(answers, queries.iter().map(|q| linear.any_within(q)).collect::<Vec<_>>());
            let near = answers.iter().filter(|&&a| a).count();
            assert!(near > 200 && near < 1800, "{near} of 2000 near: both answers occur");
        }
    }

    #[test]
    fn counts_detections_and_scans_from_the_first_detection() {
        // Object 7 is a birth, object 1 is not.
        let mut tally = BirthTally::new([7], 0.5, 3.0);
        let (p1, p7) = ([0.0, 0.0], [10.0, 10.0]);
        let truth = [(1, &p1[..]), (7, &p7[..])];
        // Scan 0 assigns it a confirmed track before any detection (a neighbour's): not a confirmation.
        let neighbour = [11.0, 10.0];
        tally.record(0, &truth, [], &[track(1, &p1, 0.99), track(2, &neighbour, 0.99)], &[Some(0), Some(1)]);
        assert_eq!(tally.confirmed_at(7), None);
        // Scan 0 again: not detected. Scan 1: detected, no track. Scan 2: missed. Scan 3: detected, a track of
        // existence 0.4. Scan 4: detected, existence 0.6: confirmed with 3 detections over 4 scans.
        tally.record(0, &truth, [1], &[track(1, &p1, 0.99)], &[Some(0), None]);
        tally.record(1, &truth, [1, 7], &[track(1, &p1, 0.99)], &[Some(0), None]);
        tally.record(2, &truth, [1], &[track(1, &p1, 0.99)], &[Some(0), None]);
        let near = [10.5, 10.0];
        tally.record(3, &truth, [7], &[track(1, &p1, 0.99), track(9, &near, 0.4)], &[Some(0), Some(1)]);
        assert_eq!(tally.confirmed_at(7), None);
        tally.record(4, &truth, [7], &[track(1, &p1, 0.99), track(9, &near, 0.6)], &[Some(0), Some(1)]);
        assert_eq!(tally.confirmed_at(7), Some(4));
        assert_eq!(tally.confirmed_at(1), None, "not a birth");
        let f = tally.figures();
        assert_eq!((f.births_total, f.births_confirmed, f.false_tracks), (1, 1, 0));
        assert_eq!(
            f.records,
            vec![BirthRecord {
                object: 7,
                first_detection_scan: Some(1),
                confirmation_scan: Some(4),
                detections_to_confirm: Some(3),
                scans_to_confirm: Some(4),
                confirmed_labels: 1,
            }]
        );
        assert_eq!((f.mean_detections_to_confirm, f.max_detections_to_confirm), (Some(3.0), Some(3)));
        assert_eq!(f.max_labels_per_birth, Some(1));
    }

    #[test]
    fn a_birth_taken_over_by_a_second_label_counts_two_labels() {
        // Births 7 and 8, both detected at scan 0. Birth 7: label 9 confirms it at scan 1, label 9 again at
        // scan 2, then label 12 takes it at scan 3 (a re-birth): 2 labels. Birth 8: label 10, unconfirmed
        // at scan 1 (existence 0.3, not counted), confirmed at scan 2 and kept: 1 label.
        let mut tally = BirthTally::new([7, 8], 0.5, 3.0);
        let (p7, p8) = ([0.0, 0.0], [50.0, 0.0]);
        let truth = [(7, &p7[..]), (8, &p8[..])];
        tally.record(0, &truth, [7, 8], &[], &[None, None]);
        let scans: [(u32, f64, u32, f64); 3] = [(9, 0.8, 10, 0.3), (9, 0.9, 10, 0.7), (12, 0.9, 10, 0.8)];
        for (k, (l7, e7, l8, e8)) in scans.into_iter().enumerate() {
            let map = [track(l7, &p7, e7), track(l8, &p8, e8)];
            tally.record(k + 1, &truth, [7, 8], &map, &[Some(0), Some(1)]);
        }
        let f = tally.figures();
        let labels: Vec<usize> = f.records.iter().map(|r| r.confirmed_labels).collect();
        assert_eq!(labels, vec![2, 1]);
        assert_eq!(f.max_labels_per_birth, Some(2));
        assert_eq!(f.records[0].confirmation_scan, Some(1), "confirmed by its first label");
        // None confirmed: no maximum.
        assert_eq!(BirthTally::new([1], 0.5, 3.0).figures().max_labels_per_birth, None);
    }

    #[test]
    fn none_confirmed_gives_no_mean() {
        let mut tally = BirthTally::new([2, 3], 0.5, 3.0);
        let p = [0.0, 0.0];
        tally.record(0, &[(2, &p[..])], [2], &[], &[None]);
        let f = tally.figures();
        assert_eq!((f.births_total, f.births_confirmed), (2, 0));
        assert_eq!((f.mean_detections_to_confirm, f.max_detections_to_confirm), (None, None));
        assert_eq!(f.records[0].first_detection_scan, Some(0));
        assert_eq!(f.records[1].first_detection_scan, None);
    }

    #[test]
    fn a_false_track_is_confirmed_once_and_never_near() {
        let mut tally = BirthTally::new([], 0.5, 3.0);
        let p = [0.0, 0.0];
        let truth = [(1, &p[..])];
        let (far, near) = ([20.0, 0.0], [1.0, 0.0]);
        // Label 5: far and confirmed: false. Label 6: far but never confirmed: not counted. Label 8:
        // confirmed far away, later near an object: not false.
        tally.record(0, &truth, [], &[track(5, &far, 0.9), track(6, &far, 0.3), track(8, &far, 0.9)], &[None]);
        tally.record(1, &truth, [], &[track(5, &far, 0.2), track(8, &near, 0.9)], &[Some(1)]);
        assert_eq!(tally.figures().false_tracks, 1);
    }
}
