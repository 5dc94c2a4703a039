//! A cluster between scans, in fixed memory: its core's [`TrackerState`] owned (at most `K` tracks and `H`
//! hypotheses), and the priors a cluster is rebuilt from (docs/maths.md §13): a merge's product of the
//! members' hypotheses, a split's group marginal, the birth cluster's hypotheses under fresh labels. Each
//! is read by the core's own prior loader ([`PriorSource`]) object by object, so no hypothesis set is
//! materialised.

use super::error::PoolError;
use crate::hypothesis::Hypothesis;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::{Real, exp};
use crate::store::{Track, TrackLabel};
use crate::tracker::{PriorObject, PriorSource, Tracker, TrackerState};

/// One cluster of the pool between scans: its id and what its core carries from one scan to the next.
#[derive(Debug, Clone)]
pub struct ClusterRest<T: Real, const S: usize, const N: usize, const H: usize, const K: usize> {
    id: u64,
    time: f64,
    scans: u64,
    next_label: u32,
    tracks: heapless::Vec<Track<T, S>, K>,
    hypotheses: heapless::Vec<Hypothesis<T, N>, H>,
}

impl<T: Real, const S: usize, const N: usize, const H: usize, const K: usize> ClusterRest<T, S, N, H, K> {
    /// A cluster holding nothing (a slot to store one in).
    pub(super) const EMPTY: Self = Self {
        id: 0,
        time: 0.0,
        scans: 0,
        next_label: 0,
        tracks: heapless::Vec::new(),
        hypotheses: heapless::Vec::new(),
    };

    /// Stores cluster `id` as `core` holds it, in place.
    ///
    /// # Errors
    /// [`PoolError::Unresumable`] when the core holds a birth pool (never for a cluster of objects, whose
    /// configuration has no births); the slot is then unchanged.
    pub(super) fn store<M, G, const D: usize, const Z: usize, const B: usize>(
        &mut self,
        id: u64,
        core: &Tracker<T, M, G, S, D, H, N, Z, K, B>,
    ) -> Result<(), PoolError>
    where
        M: MotionModel<T, S>,
        G: MeasurementModel<T, S, D>,
    {
        let state = core.state().ok_or(PoolError::Unresumable { cluster: id })?;
        self.fill(id, &state);
        Ok(())
    }

    /// Copies `other` into this slot, in place.
    pub(super) fn copy_from(&mut self, other: &Self) {
        self.fill(other.id, &other.view());
    }

    fn fill(&mut self, id: u64, state: &TrackerState<'_, T, S, N>) {
        (self.id, self.time, self.scans, self.next_label) = (id, state.time, state.scans, state.next_label);
        self.tracks.clear();
        self.hypotheses.clear();
        // A core's state holds at most K tracks and H hypotheses: both fit.
        let _ = self.tracks.extend_from_slice(state.tracks);
        let _ = self.hypotheses.extend_from_slice(state.hypotheses);
    }

    /// Loads the cluster into `core` (one of the pool's configuration without births).
    pub(super) fn load<M, G, const D: usize, const Z: usize, const B: usize>(
        &self,
        core: &mut Tracker<T, M, G, S, D, H, N, Z, K, B>,
    ) -> Result<(), PoolError>
    where
        M: MotionModel<T, S>,
        G: MeasurementModel<T, S, D>,
    {
        core.resume(&self.view()).map_err(|error| PoolError::Rebuild { cluster: self.id, error })
    }

    /// The cluster's id (fixed for its life; a merge keeps its first member's, a split's first group keeps
    /// the cluster's).
    pub fn id(&self) -> u64 {
        self.id
    }

    /// The core state the cluster resumes from.
    pub fn view(&self) -> TrackerState<'_, T, S, N> {
        TrackerState {
            time: self.time,
            scans: self.scans,
            next_label: self.next_label,
            tracks: &self.tracks,
            hypotheses: &self.hypotheses,
        }
    }

    /// The time of the cluster's last step.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// The cluster's live tracks.
    pub fn tracks(&self) -> &[Track<T, S>] {
        &self.tracks
    }

    /// The cluster's hypotheses, best first.
    pub fn hypotheses(&self) -> &[Hypothesis<T, N>] {
        &self.hypotheses
    }

    /// Objects of the cluster's largest hypothesis.
    pub fn max_objects(&self) -> usize {
        self.hypotheses.iter().map(Hypothesis::len).max().unwrap_or(0)
    }

    /// Distinct labels among the cluster's tracks.
    pub fn label_count(&self) -> usize {
        let tracks = &self.tracks;
        (0..tracks.len()).filter(|&i| tracks[..i].iter().all(|t| t.label != tracks[i].label)).count()
    }

    /// Weight of hypothesis `h`.
    pub(super) fn weight(&self, h: usize) -> T {
        self.hypotheses.get(h).map_or(T::zero(), |h| exp(h.log_weight))
    }

    /// The track in slot `slot`.
    pub(super) fn track(&self, slot: u16) -> Option<&Track<T, S>> {
        self.tracks.get(usize::from(slot))
    }

    /// Slots of hypothesis `h`, in label order.
    pub(super) fn slots(&self, h: usize) -> &[u16] {
        self.hypotheses.get(h).map_or(&[], Hypothesis::slots)
    }
}

/// An object of a prior out of range of its source: a NaN mean, which the core refuses (never for the
/// sources below, whose indices come from the loader within their own counts).
fn invalid<T: Real, const S: usize>() -> PriorObject<T, S> {
    let mut state = crate::gaussian::Gaussian::<T, S>::ZERO;
    state.mean.fill(T::of_f64(f64::NAN));
    PriorObject { label: TrackLabel(0), state }
}

fn object_of<T: Real, const S: usize>(track: Option<&Track<T, S>>) -> PriorObject<T, S> {
    track.map_or_else(invalid, |t| PriorObject { label: t.label, state: t.state })
}

/// The product of the members' hypothesis sets, pruned (docs/maths.md §13.3): each entry a weight and, per
/// member, the index of the member's hypothesis it takes; its objects are the members' objects in label
/// order.
pub(super) struct Product<'a, T: Real, const S: usize, const N: usize, const H: usize, const K: usize> {
    pub clusters: &'a [ClusterRest<T, S, N, H, K>],
    pub members: &'a [u16],
    pub entries: &'a [(T, [u16; N])],
}

impl<T: Real, const S: usize, const N: usize, const H: usize, const K: usize> Product<'_, T, S, N, H, K> {
    /// The (member, slot) of every object of entry `h`, in label order (labels are distinct across
    /// clusters); `None` past N objects.
    fn objects_of(&self, h: usize) -> Option<heapless::Vec<(u32, u16, u16), N>> {
        let (_, choice) = self.entries.get(h)?;
        let mut out = heapless::Vec::<(u32, u16, u16), N>::new();
        for (k, &hypothesis) in choice.iter().enumerate().take(self.members.len()) {
            let Some(rest) = self.member(k) else { continue };
            for &slot in rest.slots(usize::from(hypothesis)) {
                let label = rest.track(slot).map_or(0, |t| t.label.0);
                out.push((label, k as u16, slot)).ok()?;
            }
        }
        crate::index::insertion_sort_by(&mut out, |a, b| a.0 < b.0);
        Some(out)
    }

    /// Objects of entry `h` (may exceed N: the merge's check).
    pub fn count(&self, h: usize) -> usize {
        let Some((_, choice)) = self.entries.get(h) else { return 0 };
        let slots = |(k, &h): (usize, &u16)| self.member(k).map_or(0, |rest| rest.slots(usize::from(h)).len());
        choice.iter().enumerate().take(self.members.len()).map(slots).sum()
    }

    /// The state of member `k`.
    fn member(&self, k: usize) -> Option<&ClusterRest<T, S, N, H, K>> {
        self.members.get(k).and_then(|&m| self.clusters.get(usize::from(m)))
    }
}

impl<T: Real, const S: usize, const N: usize, const H: usize, const K: usize> PriorSource<T, S>
    for Product<'_, T, S, N, H, K>
{
    fn hypotheses(&self) -> usize {
        self.entries.len()
    }

    fn weight(&self, hypothesis: usize) -> T {
        self.entries.get(hypothesis).map_or(T::zero(), |e| e.0)
    }

    fn objects(&self, hypothesis: usize) -> usize {
        self.count(hypothesis)
    }

    fn label(&self, hypothesis: usize, object: usize) -> TrackLabel {
        self.object(hypothesis, object).label
    }

    fn object(&self, hypothesis: usize, object: usize) -> PriorObject<T, S> {
        let found = self.objects_of(hypothesis).and_then(|objects| objects.get(object).copied());
        found.map_or_else(invalid, |(_, k, slot)| object_of(self.member(usize::from(k)).and_then(|r| r.track(slot))))
    }
}

/// One group of a split (docs/maths.md §13.4): its marginal, each entry a weight and a representative
/// hypothesis of `rest` whose objects in the group (`group_of_slot[slot] == group`) it holds.
pub(super) struct Group<'a, T: Real, const S: usize, const N: usize, const H: usize, const K: usize> {
    pub rest: &'a ClusterRest<T, S, N, H, K>,
    pub group_of_slot: &'a [u16],
    pub group: u16,
    pub entries: &'a [(T, u16)],
}

impl<T: Real, const S: usize, const N: usize, const H: usize, const K: usize> Group<'_, T, S, N, H, K> {
    fn slots(&self, hypothesis: usize) -> impl Iterator<Item = u16> + '_ {
        let row = self.entries.get(hypothesis).map_or(usize::MAX, |e| usize::from(e.1));
        self.rest.slots(row).iter().copied().filter(|&s| self.group_of_slot.get(usize::from(s)) == Some(&self.group))
    }
}

impl<T: Real, const S: usize, const N: usize, const H: usize, const K: usize> PriorSource<T, S>
    for Group<'_, T, S, N, H, K>
{
    fn hypotheses(&self) -> usize {
        self.entries.len()
    }

    fn weight(&self, hypothesis: usize) -> T {
        self.entries.get(hypothesis).map_or(T::zero(), |e| e.0)
    }

    fn objects(&self, hypothesis: usize) -> usize {
        self.slots(hypothesis).count()
    }

    fn label(&self, hypothesis: usize, object: usize) -> TrackLabel {
        self.object(hypothesis, object).label
    }

    fn object(&self, hypothesis: usize, object: usize) -> PriorObject<T, S> {
        object_of(self.slots(hypothesis).nth(object).and_then(|s| self.rest.track(s)))
    }
}

/// The birth cluster's hypotheses with its labels replaced by fresh ones: the i-th smallest of `own` (the
/// labels its hypotheses hold) becomes `first + i`.
pub(super) struct Relabelled<
    'a,
    T: Real,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> {
    pub birth: &'a Tracker<T, M, G, S, D, H, N, Z, K, B>,
    pub own: &'a [u32],
    pub first: u32,
}

impl<
    T,
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> PriorSource<T, S> for Relabelled<'_, T, M, G, S, D, H, N, Z, K, B>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    fn hypotheses(&self) -> usize {
        self.birth.hypotheses().len()
    }

    fn weight(&self, hypothesis: usize) -> T {
        self.birth.hypotheses().nth(hypothesis).map_or(T::zero(), |h| h.weight())
    }

    fn objects(&self, hypothesis: usize) -> usize {
        self.birth.hypotheses().nth(hypothesis).map_or(0, |h| h.len())
    }

    fn label(&self, hypothesis: usize, object: usize) -> TrackLabel {
        self.object(hypothesis, object).label
    }

    fn object(&self, hypothesis: usize, object: usize) -> PriorObject<T, S> {
        let track = self.birth.hypotheses().nth(hypothesis).and_then(|h| h.tracks().nth(object));
        let mut found = object_of(track);
        if let Ok(i) = self.own.binary_search(&found.label.0) {
            found.label = TrackLabel(self.first + i as u32);
        }
        found
    }
}
