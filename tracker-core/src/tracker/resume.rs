//! What a tracker carries from one scan to the next, read out ([`Tracker::state`]) and loaded back
//! ([`Tracker::resume`]) bit for bit: a host holding many small trackers (the partitioned catalogue tracker)
//! keeps each as this state and steps it in one reused tracker, instead of a whole tracker per object.
//!
//! Between scans a tracker's results depend on its configuration, its live track store and hypotheses,
//! its time, scan count (the scan's random seed) and next label, and its birth pool; everything else is
//! scratch that each scan rewrites before reading it. A tracker whose birth pool holds anything (cells,
//! waiting cells, tracklet frames) has no [`TrackerState`] (the pool is not part of it).

use super::{Tracker, prior};
use crate::error::ConfigError;
use crate::hypothesis::Hypothesis;
use crate::index::At;
use crate::model::{MeasurementModel, MotionModel};
use crate::real::Real;
use crate::store::Track;

/// A tracker's state between scans, borrowed: resuming it gives a tracker that steps to the same bits as
/// the one it was read from.
#[derive(Debug, Clone, Copy)]
pub struct TrackerState<'a, T: Real, const S: usize, const N: usize> {
    /// The time of the last scan (or of the prior).
    pub time: f64,
    /// Scans processed since the prior.
    pub scans: u64,
    /// The label the next birth takes.
    pub next_label: u32,
    /// The live track store.
    pub tracks: &'a [Track<T, S>],
    /// The hypotheses, best first, holding slots of `tracks`.
    pub hypotheses: &'a [Hypothesis<T, N>],
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
> Tracker<T, M, G, S, D, H, N, Z, K, B>
where
    T: Real,
    M: MotionModel<T, S>,
    G: MeasurementModel<T, S, D>,
{
    /// The tracker's state between scans; `None` before a prior is loaded or while the birth pool holds
    /// cells, waiting cells or tracklet frames (measurement-driven births, docs/maths.md §5.8, §5.10), which the
    /// state does not carry.
    ///
    /// # Examples
    /// A tracker resumed in another (here, one that held something else) steps to the same bits:
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// let mut a = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config.clone(), &[object], 0.0)?;
    /// a.step(1.0, &[SVector::from([1.1, 0.05])])?;
    /// let mut b = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object, object], 5.0)?;
    /// b.resume(&a.state().unwrap())?;
    /// assert_eq!((b.digest(), b.scans()), (a.digest(), 1));
    /// a.step(2.0, &[SVector::from([2.0, 0.1])])?;
    /// b.step(2.0, &[SVector::from([2.0, 0.1])])?;
    /// assert_eq!(b.digest(), a.digest());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn state(&self) -> Option<TrackerState<'_, T, S, N>> {
        if !self.initialised || !self.pool.is_empty() {
            return None;
        }
        Some(TrackerState {
            time: self.time,
            scans: self.scans,
            next_label: self.next_label,
            tracks: self.stores.at(self.live()).as_slice(),
            hypotheses: self.hypotheses.at(self.live()).as_slice(),
        })
    }

    /// Loads `state` (read from a tracker of the same capacities and configuration by [`Tracker::state`]):
    /// the tracker then steps exactly as the one it was read from. Its birth pool is emptied.
    ///
    /// # Errors
    /// The configuration's [`ConfigError`] when no prior was ever loaded and it is invalid;
    /// [`ConfigError::PriorTime`] for a time that is not finite, [`ConfigError::PriorEmpty`] for no
    /// hypothesis, [`ConfigError::PriorTooManyHypotheses`] above H, [`ConfigError::PriorTrackStoreFull`]
    /// above K tracks, [`ConfigError::PriorObject`] for a hypothesis holding a slot outside the tracks. The
    /// tracker is then unchanged.
    pub fn resume(&mut self, state: &TrackerState<'_, T, S, N>) -> Result<(), ConfigError> {
        if !self.initialised {
            prior::check_config::<T, M, G, S, D, N, B>(&self.config)?;
        }
        check(state, H, K)?;
        let inactive = usize::from(!self.active);
        let (store, set) = (self.stores.at_mut(inactive), self.hypotheses.at_mut(inactive));
        store.clear();
        set.clear();
        for track in state.tracks {
            // Room was checked above.
            let _ = store.push(*track);
        }
        for hypothesis in state.hypotheses {
            let _ = set.push(Hypothesis::new(hypothesis.log_weight, hypothesis.slots()));
        }
        self.active = !self.active;
        self.time = state.time;
        self.scans = state.scans;
        self.next_label = state.next_label;
        self.initialised = true;
        self.pool.clear();
        self.generation.reset(self.config.children);
        Ok(())
    }

    /// Makes this tracker step exactly as `other` would from here: the configuration, the live track store
    /// and hypotheses, the time, scan count and next label and the birth pool copied in place; the rest is
    /// scratch that each scan rewrites before reading it. A host that steps a spare copy of a tracker (the
    /// pool of clusters' birth cluster, [`crate::partition`]) copies it this way instead of with
    /// `clone_from`, which builds a whole tracker on the stack.
    ///
    /// # Examples
    /// ```
    /// # use nalgebra::SVector;
    /// # use tracker_core::LinearTracker;
    /// # let (config, object) = (tracker_core::examples::config(), tracker_core::examples::object());
    /// let mut a = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config.clone(), &[object], 0.0)?;
    /// a.step(1.0, &[SVector::from([1.1, 0.05])])?;
    /// let mut b = LinearTracker::<f64, 8, 4, 4, 16, 1>::with_objects(config, &[object, object], 5.0)?;
    /// b.copy_state_from(&a);
    /// a.step(2.0, &[SVector::from([2.0, 0.1])])?;
    /// b.step(2.0, &[SVector::from([2.0, 0.1])])?;
    /// assert_eq!(b.digest(), a.digest());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn copy_state_from(&mut self, other: &Self)
    where
        M: Clone,
        G: Clone,
    {
        self.config.clone_from(&other.config);
        let live = other.live();
        let (store, set) = (self.stores.at_mut(live), self.hypotheses.at_mut(live));
        store.clear();
        set.clear();
        // The same capacities: everything fits.
        for track in other.stores.at(live).as_slice() {
            let _ = store.push(*track);
        }
        for hypothesis in other.hypotheses.at(live).as_slice() {
            let _ = set.push(*hypothesis);
        }
        self.active = other.active;
        (self.time, self.scans, self.next_label) = (other.time, other.scans, other.next_label);
        self.initialised = other.initialised;
        self.pool.clone_from(&other.pool);
        self.generation.reset(self.config.children);
    }
}

/// The checks of [`Tracker::resume`] against capacities `h` and `k`.
fn check<T: Real, const S: usize, const N: usize>(
    state: &TrackerState<'_, T, S, N>,
    h: usize,
    k: usize,
) -> Result<(), ConfigError> {
    if !state.time.is_finite() {
        return Err(ConfigError::PriorTime);
    }
    if state.hypotheses.is_empty() {
        return Err(ConfigError::PriorEmpty);
    }
    if state.hypotheses.len() > h {
        return Err(ConfigError::PriorTooManyHypotheses);
    }
    if state.tracks.len() > k {
        return Err(ConfigError::PriorTrackStoreFull);
    }
    for (hypothesis, h) in state.hypotheses.iter().enumerate() {
        if let Some(object) = h.slots().iter().position(|&slot| usize::from(slot) >= state.tracks.len()) {
            return Err(ConfigError::PriorObject { hypothesis, object });
        }
    }
    Ok(())
}
