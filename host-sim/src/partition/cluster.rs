//! One cluster of the partitioned tracker at rest: its id, the state its core carries between scans
//! ([`Rest`]: tracks, hypotheses, time, scan count, next label; a few hundred bytes an object instead of a
//! core's fixed capacities) and, per sensor, the time until which that sensor cannot see it (docs/maths.md
//! §13.2). A scan loads the state into a reused core ([`super::cores`]), steps it and stores it back.

use super::error::{ClusterId, PartitionError};
use super::hypotheses::Hypothesis;
use nalgebra::SVector;
use tracker_core::hypothesis::Hypothesis as CoreHypothesis;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::real::exp;
use tracker_core::{PriorObject, Track, Tracker, TrackerState};

/// What a cluster's core carries from one scan to the next ([`TrackerState`]), owned.
#[derive(Debug, Clone, PartialEq)]
pub struct Rest<const S: usize, const N: usize> {
    time: f64,
    scans: u64,
    next_label: u32,
    tracks: Box<[Track<f64, S>]>,
    hypotheses: Box<[CoreHypothesis<f64, N>]>,
    /// The most objects a hypothesis holds and the distinct labels, read once (every scan's routing and
    /// report ask them of every cluster).
    max_objects: usize,
    label_count: usize,
}

impl<const S: usize, const N: usize> Rest<S, N> {
    /// The state of cluster `id`'s `core`.
    ///
    /// # Errors
    /// [`PartitionError::Unresumable`] when the core has none (no prior, or a birth pool with cells).
    pub fn of<M, G, const D: usize, const H: usize, const Z: usize, const K: usize, const B: usize>(
        id: ClusterId,
        core: &Tracker<f64, M, G, S, D, H, N, Z, K, B>,
    ) -> Result<Self, PartitionError>
    where
        M: MotionModel<f64, S>,
        G: MeasurementModel<f64, S, D>,
    {
        let state = core.state().ok_or(PartitionError::Unresumable { cluster: id })?;
        let tracks = state.tracks;
        let label_count = if tracks.iter().all(|t| t.label == tracks[0].label) {
            usize::from(!tracks.is_empty())
        } else {
            (0..tracks.len()).filter(|&i| tracks[..i].iter().all(|t| t.label != tracks[i].label)).count()
        };
        Ok(Self {
            time: state.time,
            scans: state.scans,
            next_label: state.next_label,
            tracks: state.tracks.into(),
            hypotheses: state.hypotheses.into(),
            max_objects: state.hypotheses.iter().map(|h| h.slots().len()).max().unwrap_or(0),
            label_count,
        })
    }

    /// The state to load into a core ([`Tracker::resume`]).
    pub fn view(&self) -> TrackerState<'_, f64, S, N> {
        TrackerState {
            time: self.time,
            scans: self.scans,
            next_label: self.next_label,
            tracks: &self.tracks,
            hypotheses: &self.hypotheses,
        }
    }

    /// The time of the cluster's last step (or load).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Its tracks, as its core stores them.
    pub fn tracks(&self) -> &[Track<f64, S>] {
        &self.tracks
    }

    /// How many hypotheses it holds.
    pub fn hypothesis_count(&self) -> usize {
        self.hypotheses.len()
    }

    /// The most objects any of its hypotheses holds: a merge's product holds at most the sum of its
    /// members' (docs/maths.md §13.3).
    pub fn max_objects(&self) -> usize {
        self.max_objects
    }

    /// Its hypotheses, best first: each one's weight (as the core gives it) and tracks.
    pub fn weighted(&self) -> impl Iterator<Item = (f64, impl Iterator<Item = &Track<f64, S>>)> {
        self.hypotheses.iter().map(|h| {
            let tracks = h.slots().iter().filter_map(|&slot| self.tracks.get(usize::from(slot)));
            (exp(h.log_weight), tracks)
        })
    }

    /// Its hypotheses as owned data (as [`super::hypotheses::read`] reads a core).
    pub fn read(&self) -> Vec<Hypothesis<S>> {
        self.weighted()
            .map(|(weight, tracks)| Hypothesis {
                weight,
                objects: tracks.map(|t| PriorObject { label: t.label, state: t.state }).collect(),
            })
            .collect()
    }

    /// The state an empty scan at `time` leaves a cluster with no track in view in (docs/maths.md §13.2):
    /// every track's Gaussian replaced by its prediction `predicted` (one per track, in store order); the
    /// hypotheses, existences and unseen-scan counts are unchanged (out of view a track takes no
    /// measurement, no missed-detection factor and no death). The scan count is not advanced: the next
    /// scan's random streams are those of the scan after the cluster's last step.
    pub(super) fn advance(&mut self, time: f64, predicted: Vec<tracker_core::Gaussian<f64, S>>) {
        debug_assert_eq!(predicted.len(), self.tracks.len());
        for (track, state) in self.tracks.iter_mut().zip(predicted) {
            track.state = state;
        }
        self.time = time;
    }

    /// How many distinct labels it holds (as `labels().len()`, without allocating).
    pub fn label_count(&self) -> usize {
        self.label_count
    }

    /// Its distinct labels, in order.
    pub fn labels(&self) -> Vec<u32> {
        let mut labels: Vec<u32> = self.tracks.iter().map(|t| t.label.0).collect();
        labels.sort_unstable();
        labels.dedup();
        labels
    }

    /// The expected number of objects (as [`Tracker::expected_cardinality`] sums it).
    pub fn expected_cardinality(&self) -> f64 {
        self.hypotheses.iter().fold(0.0, |sum, h| sum + exp(h.log_weight) * h.len() as f64)
    }
}

/// One cluster: its identity, its state at rest, its clearances and its coast.
#[derive(Debug, Clone, PartialEq)]
pub struct Cluster<const S: usize, const N: usize> {
    pub id: ClusterId,
    pub rest: Rest<S, N>,
    /// Per sensor, the time until which the cluster is certainly out of that sensor's field of view and is
    /// left unstepped by its scans (docs/maths.md §13.2); empty without a view skip.
    pub clear_until: Vec<f64>,
    /// While the cluster coasts (gated from its means alone and cleared from the scanning sensor, its rest
    /// left at its own time, §13.2): its tracks' means predicted to the last scan that gated it.
    pub coast: Option<Coast<S>>,
}

/// A coasting cluster's tracks' means (one per track, in store order) predicted to `time`, a chain of
/// mean-only predictions from its rest (docs/maths.md §13.2).
#[derive(Debug, Clone, PartialEq)]
pub struct Coast<const S: usize> {
    pub time: f64,
    pub means: Box<[SVector<f64, S>]>,
}

impl<const S: usize, const N: usize> Cluster<S, N> {
    /// The cluster `id` at `rest`, due at every sensor's next scan.
    pub fn new(id: ClusterId, rest: Rest<S, N>) -> Self {
        Self { id, rest, clear_until: vec![], coast: None }
    }

    /// Whether a scan of `sensor` at `time` may leave the cluster unstepped.
    pub(super) fn clear_at(&self, sensor: usize, time: f64) -> bool {
        self.clear_until.get(sensor).is_some_and(|&until| time < until)
    }
}

/// What a scan does with one cluster.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Fate {
    /// Certainly out of the sensor's field of view: not touched (§13.2).
    Skipped,
    /// No measurement and no track in view: stepped with an empty scan (with a view skip: its tracks'
    /// predictions stored, or its coast, §13.2).
    Quiet,
    /// Stepped (alone or merged) with its measurements.
    Stepped,
}

/// How long a quiet cluster is left out of each sensor's scans (§13.2).
#[derive(Debug, Clone, Copy)]
pub(super) struct Clearance {
    pub time: f64,
    /// The motion model's longest prediction: a skipped cluster is caught up over at most this.
    pub cap: Option<f64>,
}

impl Clearance {
    /// Raises each sensor's entry of `until` to the scan's time plus its `clear_for` (seconds, at most the
    /// cap; 0: nothing known), keeping a later entry: both bound the same track means, which a quiet
    /// cluster keeps (a cluster whose tracks are updated starts with no clearance).
    pub fn record(&self, until: &mut Vec<f64>, clear_for: &[f64]) {
        if until.len() < clear_for.len() {
            until.resize(clear_for.len(), f64::NEG_INFINITY);
        }
        for (until, &clear) in until.iter_mut().zip(clear_for) {
            if clear > 0.0 {
                *until = until.max(self.time + clear.min(self.cap.unwrap_or(f64::INFINITY)));
            }
        }
    }
}
