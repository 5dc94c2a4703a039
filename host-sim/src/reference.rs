//! The unbounded reference tracker: the same hypothesis-level FISST recursion as tracker-core, with `Vec`
//! instead of capacities and **every** child of every parent kept.
//!
//! It calls the core's model, EKF ([`tracker_core::ekf`]) and weight code ([`WeightModel`]); only the
//! bookkeeping is its own: a recursive enumeration of associations (independent of the core's iterative
//! enumerator, so the two check each other), hash maps for shared tracks, and merging of identical
//! hypotheses. No child is dropped unless a memory budget is reached; then the lowest-weight children are
//! dropped, and the scan's report and [`ReferenceTracker::budget_scans`] say so.

use crate::snapshot::{HypothesisOut, Snapshot, TrackOut};
use nalgebra::SVector;
use std::collections::HashMap;
use tracker_core::ekf::{self, Gaussian, Innovation};
use tracker_core::real::{LogSumExp, log_add};
use tracker_core::weight::{Event, WeightModel};
use tracker_core::{Config, MotionModel, PositionMeasurement, PriorObject, Region, StepError, TrackLabel};

const CLUTTER: u16 = u16::MAX;
/// Estimated bytes of one enumerated child before materialisation (weight, parent, event, assignment).
const CHILD_BYTES: usize = 64;

#[derive(Debug, Clone)]
struct Track {
    label: u32,
    state: Gaussian<f64, 4>,
}

#[derive(Debug, Clone)]
struct Hypothesis {
    log_weight: f64,
    /// Track indices, sorted by label.
    tracks: Vec<u32>,
}

#[derive(Debug, Clone)]
struct Child {
    log_weight: f64,
    parent: u32,
    event: Event,
    assignment: Vec<u16>,
}

#[derive(Debug, Clone, Copy)]
struct Predicted {
    state: Gaussian<f64, 4>,
    innovation: Innovation<f64, 2>,
    in_view: bool,
}

/// What one reference scan did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReferenceReport {
    /// Children with non-zero weight.
    pub children: u64,
    /// Hypotheses after the scan.
    pub hypotheses: usize,
    /// Whether the memory budget forced dropping children this scan.
    pub budget_reached: bool,
    /// Fraction of the children's weight kept (1 unless the budget was reached).
    pub captured_mass: f64,
}

/// The unbounded exhaustive tracker.
pub struct ReferenceTracker<M> {
    motion: M,
    measurement: PositionMeasurement<f64>,
    region: Region<f64>,
    weights: WeightModel<f64>,
    births: Vec<(Gaussian<f64, 4>, Innovation<f64, 2>, bool)>,
    tracks: Vec<Track>,
    hypotheses: Vec<Hypothesis>,
    time: f64,
    next_label: u32,
    budget_bytes: usize,
    max_children: u64,
    budget_scans: Vec<usize>,
    scans: usize,
}

impl<M: MotionModel<f64, 4>> ReferenceTracker<M> {
    /// A reference tracker for `config` (its capacities do not apply), the prior hypotheses and a memory
    /// budget in bytes. The first-order event model needs M_b α + M_d β < 1 for every parent; like the
    /// core, the reference checks it for up to `max_objects` objects in view (the compared profile's N)
    /// when it is built, and again for every parent at every scan.
    ///
    /// # Errors
    /// A message when the event probabilities are impossible or a birth cell's innovation cannot be
    /// factored.
    pub fn new<const B: usize>(
        config: &Config<f64, M, PositionMeasurement<f64>, 4, B>,
        prior: &[(f64, Vec<PriorObject<f64, 4>>)],
        time: f64,
        budget_bytes: usize,
        max_objects: usize,
    ) -> Result<Self, String>
    where
        M: Clone,
    {
        let cells = config.birth.cells.len() as f64;
        if !(1.0 - cells * config.birth.probability - max_objects as f64 * config.death_probability > 0.0) {
            return Err(format!(
                "tracker configuration: {} (N = {max_objects})",
                tracker_core::ConfigError::EventProbabilities
            ));
        }
        let region = config.sensor.field_of_view;
        let mut births = vec![];
        for (cell, gaussian) in config.birth.cells.iter().enumerate() {
            let innovation =
                ekf::innovation(&config.measurement, gaussian).map_err(|e| format!("birth cell {cell}: {e}"))?;
            let in_view = region.contains(&innovation.predicted);
            births.push((*gaussian, innovation, in_view));
        }
        let mut tracks: Vec<Track> = vec![];
        let mut hypotheses = vec![];
        let total: f64 = prior.iter().map(|p| p.0).sum();
        let mut next_label = 0;
        for (weight, objects) in prior {
            let mut indices = vec![];
            for object in objects {
                next_label = next_label.max(object.label.0 + 1);
                let index = tracks
                    .iter()
                    .position(|t| t.label == object.label.0 && t.state == object.state)
                    .unwrap_or_else(|| {
                        tracks.push(Track { label: object.label.0, state: object.state });
                        tracks.len() - 1
                    });
                indices.push(index as u32);
            }
            indices.sort_by_key(|&i| tracks[i as usize].label);
            if *weight > 0.0 {
                hypotheses.push(Hypothesis { log_weight: (weight / total).ln(), tracks: indices });
            }
        }
        Ok(Self {
            motion: config.motion.clone(),
            measurement: config.measurement,
            region,
            weights: WeightModel::from_config(config),
            births,
            tracks,
            hypotheses,
            time,
            next_label,
            budget_bytes,
            max_children: u64::MAX,
            budget_scans: vec![],
            scans: 0,
        })
    }

    /// Bounds the children enumerated per scan: beyond it the scan fails with
    /// [`StepError::ChildBudgetExceeded`] and the tracker is unchanged (the reference is then "broken",
    /// as exhaustive enumeration is in paper 003 §V-B).
    pub fn set_max_children(&mut self, max_children: u64) {
        self.max_children = max_children;
    }

    /// Scans (1-based) at which the memory budget forced dropping children.
    pub fn budget_scans(&self) -> &[usize] {
        &self.budget_scans
    }

    /// Number of hypotheses.
    pub fn len(&self) -> usize {
        self.hypotheses.len()
    }

    /// Whether there is no hypothesis.
    pub fn is_empty(&self) -> bool {
        self.hypotheses.is_empty()
    }

    /// Processes one scan.
    ///
    /// # Errors
    /// The core's [`StepError`] for the same bad inputs (non-finite values, time, numerical failure).
    pub fn step(&mut self, time: f64, measurements: &[SVector<f64, 2>]) -> Result<ReferenceReport, StepError> {
        if !time.is_finite() {
            return Err(StepError::NonFiniteTime);
        }
        if time <= self.time {
            return Err(StepError::TimeNotAfterLastScan);
        }
        for (index, z) in measurements.iter().enumerate() {
            if !z.iter().all(|v| v.is_finite()) {
                return Err(StepError::NonFiniteMeasurement { index });
            }
            if !self.region.contains(z) {
                return Err(StepError::MeasurementOutsideFieldOfView { index });
            }
        }
        let dt = time - self.time;
        let rows = measurements.len();

        // Predict and score every track once.
        let mut predicted = Vec::with_capacity(self.tracks.len());
        let mut entries: Vec<Vec<f64>> = Vec::with_capacity(self.tracks.len());
        for track in &self.tracks {
            let numerical = |error| StepError::Numerical { label: TrackLabel(track.label), error };
            let state = ekf::predict(&self.motion, &track.state, dt).map_err(numerical)?;
            let innovation = ekf::innovation(&self.measurement, &state).map_err(numerical)?;
            let in_view = self.region.contains(&innovation.predicted);
            entries.push(
                measurements
                    .iter()
                    .map(|z| if in_view { self.weights.entry(&innovation, z) } else { f64::NEG_INFINITY })
                    .collect(),
            );
            predicted.push(Predicted { state, innovation, in_view });
        }
        let birth_entries: Vec<Vec<f64>> = self
            .births
            .iter()
            .map(|(_, innovation, in_view)| {
                measurements
                    .iter()
                    .map(|z| if *in_view { self.weights.entry(innovation, z) } else { f64::NEG_INFINITY })
                    .collect()
            })
            .collect();

        // Enumerate every child of every parent and event.
        let max_children = (self.budget_bytes / CHILD_BYTES).max(1);
        let mut children: Vec<Child> = vec![];
        let mut total = LogSumExp::new();
        let mut count = 0u64;
        let mut budget_reached = false;
        let detection_required = self.weights.detection_required();
        for (parent_index, parent) in self.hypotheses.iter().enumerate() {
            let columns: Vec<(usize, usize)> = parent
                .tracks
                .iter()
                .enumerate()
                .filter(|(_, t)| predicted[**t as usize].in_view)
                .map(|(position, t)| (position, *t as usize))
                .collect();
            let in_view = columns.len();
            if !(self.weights.event_log_probability(Event::None, in_view) > f64::NEG_INFINITY) {
                // M_b α + M_d β ≥ 1 for this parent: the first-order event model does not apply.
                return Err(StepError::NoViableChild);
            }
            let mut events = vec![(Event::None, in_view)];
            if self.weights.births_possible() {
                for (cell, (_, _, detectable)) in self.births.iter().enumerate() {
                    if *detectable || !self.weights.birth_required() {
                        events.push((Event::Birth { cell: cell as u16 }, in_view + usize::from(*detectable)));
                    }
                }
            }
            if self.weights.deaths_possible() {
                for &(position, _) in &columns {
                    events.push((Event::Death { object: position as u16 }, in_view - 1));
                }
            }
            for (event, child_in_view) in events {
                // The event's matrix: columns with entries and required flags.
                let mut matrix: Vec<(Vec<f64>, bool)> = columns
                    .iter()
                    .map(|&(position, track)| {
                        if event == (Event::Death { object: position as u16 }) {
                            (vec![f64::NEG_INFINITY; rows], false)
                        } else {
                            (entries[track].clone(), detection_required)
                        }
                    })
                    .collect();
                if let Event::Birth { cell } = event
                    && self.births[cell as usize].2
                {
                    matrix.push((birth_entries[cell as usize].clone(), self.weights.birth_required()));
                }
                let baseline = self.weights.baseline(
                    parent.log_weight,
                    self.weights.event_log_probability(event, in_view),
                    child_in_view,
                    rows,
                );
                let mut assignment = vec![CLUTTER; rows];
                let mut used = vec![false; matrix.len()];
                let limit = self.max_children;
                let complete =
                    enumerate(&matrix, 0, baseline, &mut assignment, &mut used, &mut |log_weight, assignment| {
                        if count >= limit {
                            return false;
                        }
                        total.add(log_weight);
                        count += 1;
                        children.push(Child {
                            log_weight,
                            parent: parent_index as u32,
                            event,
                            assignment: assignment.to_vec(),
                        });
                        if children.len() >= 2 * max_children {
                            keep_best(&mut children, max_children);
                            budget_reached = true;
                        }
                        true
                    });
                if !complete {
                    return Err(StepError::ChildBudgetExceeded { budget: limit });
                }
            }
        }
        if children.is_empty() {
            return Err(StepError::NoViableChild);
        }
        // The hypotheses themselves must fit the budget too.
        let objects_per = self.hypotheses.iter().map(|h| h.tracks.len() + 1).max().unwrap_or(1);
        let max_hypotheses = (self.budget_bytes / (48 + 4 * objects_per)).max(1);
        if children.len() > max_children.min(max_hypotheses) {
            keep_best(&mut children, max_children.min(max_hypotheses));
            budget_reached = true;
        }
        // Best first; ties keep the enumeration order.
        children.sort_by(|a, b| b.log_weight.total_cmp(&a.log_weight));

        // Materialise: shared tracks keyed by (source, measurement), identical hypotheses merged.
        let mut new_tracks: Vec<Track> = vec![];
        let mut track_keys: HashMap<(bool, u32, u16), u32> = HashMap::new();
        let mut hypothesis_keys: HashMap<Vec<u32>, usize> = HashMap::new();
        let mut new_hypotheses: Vec<Hypothesis> = vec![];
        let mut next_label = self.next_label;
        // One label per new object: per measurement for detected births, per cell for undetected ones.
        let mut birth_labels: HashMap<(bool, u16), u32> = HashMap::new();
        for child in &children {
            let parent = &self.hypotheses[child.parent as usize];
            let mut row_of_column = vec![CLUTTER; parent.tracks.len() + 1];
            for (row, &column) in child.assignment.iter().enumerate() {
                if column != CLUTTER {
                    row_of_column[column as usize] = row as u16;
                }
            }
            let mut sources: Vec<(bool, u32, u16)> = vec![];
            let mut column = 0;
            for (position, &track) in parent.tracks.iter().enumerate() {
                let row = if predicted[track as usize].in_view {
                    column += 1;
                    row_of_column[column - 1]
                } else {
                    CLUTTER
                };
                if child.event != (Event::Death { object: position as u16 }) {
                    sources.push((false, track, row));
                }
            }
            if let Event::Birth { cell } = child.event {
                let row = if self.births[cell as usize].2 { row_of_column[column] } else { CLUTTER };
                sources.push((true, u32::from(cell), row));
            }
            let mut indices = Vec::with_capacity(sources.len());
            for key in sources {
                let index = match track_keys.get(&key) {
                    Some(&index) => index,
                    None => {
                        let (is_birth, source, row) = key;
                        let (label, prior, innovation) = if is_birth {
                            let birth_key = if row == CLUTTER { (false, source as u16) } else { (true, row) };
                            let label = *birth_labels.entry(birth_key).or_insert_with(|| {
                                next_label += 1;
                                next_label - 1
                            });
                            let (gaussian, innovation, _) = self.births[source as usize];
                            (label, gaussian, innovation)
                        } else {
                            let p = &predicted[source as usize];
                            (self.tracks[source as usize].label, p.state, p.innovation)
                        };
                        let state = if row == CLUTTER {
                            prior
                        } else {
                            ekf::update(&self.measurement, &prior, &innovation, &measurements[row as usize])
                                .map_err(|error| StepError::Numerical { label: TrackLabel(label), error })?
                        };
                        new_tracks.push(Track { label, state });
                        let index = (new_tracks.len() - 1) as u32;
                        track_keys.insert(key, index);
                        index
                    }
                };
                indices.push(index);
            }
            indices.sort_by_key(|&i| new_tracks[i as usize].label);
            match hypothesis_keys.get(&indices) {
                Some(&existing) => {
                    let h = &mut new_hypotheses[existing];
                    h.log_weight = log_add(h.log_weight, child.log_weight);
                }
                None => {
                    hypothesis_keys.insert(indices.clone(), new_hypotheses.len());
                    new_hypotheses.push(Hypothesis { log_weight: child.log_weight, tracks: indices });
                }
            }
        }
        let mut kept = LogSumExp::new();
        for h in &new_hypotheses {
            kept.add(h.log_weight);
        }
        let log_kept = kept.value();
        for h in &mut new_hypotheses {
            h.log_weight -= log_kept;
        }
        new_hypotheses.sort_by(|a, b| b.log_weight.total_cmp(&a.log_weight));

        self.tracks = new_tracks;
        self.hypotheses = new_hypotheses;
        self.time = time;
        self.next_label = next_label;
        self.scans += 1;
        if budget_reached {
            self.budget_scans.push(self.scans);
        }
        Ok(ReferenceReport {
            children: count,
            hypotheses: self.hypotheses.len(),
            budget_reached,
            captured_mass: (log_kept - total.value()).exp(),
        })
    }

    /// The hypotheses and tracks, best first, with existence per track.
    pub fn snapshot(&self) -> Snapshot {
        let mut tracks: Vec<TrackOut> = self
            .tracks
            .iter()
            .map(|t| TrackOut {
                label: t.label,
                mean: t.state.mean.into(),
                covariance: t.state.covariance.into(),
                existence: 0.0,
            })
            .collect();
        let hypotheses = self
            .hypotheses
            .iter()
            .map(|h| {
                let weight = h.log_weight.exp();
                for &t in &h.tracks {
                    tracks[t as usize].existence += weight;
                }
                HypothesisOut {
                    weight,
                    log_weight: h.log_weight,
                    tracks: h.tracks.iter().map(|&t| t as usize).collect(),
                }
            })
            .collect();
        Snapshot { hypotheses, tracks }
    }
}

/// Calls `offer` with every association of rows `row..` (clutter first, then each unused column with a
/// finite entry), skipping children that leave a required column unassigned. Stops, returning `false`,
/// as soon as `offer` returns `false`.
fn enumerate(
    matrix: &[(Vec<f64>, bool)],
    row: usize,
    value: f64,
    assignment: &mut Vec<u16>,
    used: &mut Vec<bool>,
    offer: &mut dyn FnMut(f64, &[u16]) -> bool,
) -> bool {
    if row == assignment.len() {
        let complete = matrix.iter().zip(used.iter()).all(|((_, required), used)| !required || *used);
        return !complete || offer(value, assignment);
    }
    assignment[row] = CLUTTER;
    if !enumerate(matrix, row + 1, value, assignment, used, offer) {
        return false;
    }
    for (column, (entries, _)) in matrix.iter().enumerate() {
        if !used[column] && entries[row] > f64::NEG_INFINITY {
            used[column] = true;
            assignment[row] = column as u16;
            let go_on = enumerate(matrix, row + 1, value + entries[row], assignment, used, offer);
            used[column] = false;
            if !go_on {
                return false;
            }
        }
    }
    assignment[row] = CLUTTER;
    true
}

/// Keeps the `keep` children of largest weight (ties: earlier first), in enumeration order.
fn keep_best(children: &mut Vec<Child>, keep: usize) {
    if children.len() <= keep {
        return;
    }
    let mut order: Vec<usize> = (0..children.len()).collect();
    order.select_nth_unstable_by(keep - 1, |&a, &b| {
        children[b].log_weight.total_cmp(&children[a].log_weight).then(a.cmp(&b))
    });
    let mut chosen: Vec<usize> = order[..keep].to_vec();
    chosen.sort_unstable();
    let mut next = Vec::with_capacity(keep);
    for index in chosen {
        next.push(std::mem::replace(
            &mut children[index],
            Child { log_weight: 0.0, parent: 0, event: Event::None, assignment: vec![] },
        ));
    }
    *children = next;
}
