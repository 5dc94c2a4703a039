//! The tracker: one scan of the hypothesis-level FISST recursion with birth and death.
//!
//! [`Tracker::step`] does, for a scan at time t with measurements z₁..z_m:
//!
//! 1. **Predict** every track of the shared store once (EKF), factor its innovation covariance, decide
//!    whether it is in the field of view, and score it against every measurement once: the entry
//!    δ_{z,o} of digest §4.4 for each (track, measurement) pair, `-inf` outside the gate or the field of
//!    view. Birth cells are scored the same way.
//! 2. **Generate children.** For each parent and each event (no event, a birth in each cell, the death of
//!    each object in the field of view) gather the parent's columns into an [`AssociationMatrix`] and let
//!    the child generator offer every child to a [`TopChildren`] sink, which keeps the H best and the
//!    global log-sum-exp.
//! 3. **Materialise** only the kept children, best first: each child's tracks are keyed by (source track
//!    or birth cell, measurement or missed); a key seen before reuses its track, a new key gets one EKF
//!    update. Children that hold exactly the same tracks are merged (their weights add). Weights are
//!    normalised over the kept hypotheses; the mass of the rest is reported as `1 − captured_mass`.
//! 4. **Commit.** Everything above writes into the inactive half of double-buffered store and
//!    hypotheses and into scratch space; only a scan that succeeds swaps them in. A failed `step` leaves
//!    the tracker bit-for-bit as it was.
//!
//! # Panics
//! [`Tracker::new`], [`Tracker::step`] and [`Tracker::digest`] do not panic on any input in a release
//! build: capacity, finiteness and time are checked first, numerical failure is returned as
//! [`StepError::Numerical`], and every index into the fixed-size tables is proved in bounds or clamped
//! (the private `index` module), so no panic path is left. This is proved at link time: `nostd-check`'s
//! `panic_free` binary calls them on inputs the optimiser cannot see through, with a panic handler that
//! references an undefined symbol, and it links only when the optimiser removed every path to a panic
//! (`cd nostd-check && cargo build --release --bin panic_free`; see `docs/embedded.md`, "Panic-freedom").
//! The proof covers the monomorphisations that binary instantiates. Debug builds keep `debug_assert!`s on
//! internal invariants.

use crate::association::{AssociationMatrix, CLUTTER};
use crate::children::{ChildGenerator, ChildSink, ExhaustiveChildren, GenerateError};
use crate::cluster::ClusteredChildren;
use crate::config::Selection;
use crate::config::{ChildGeneration, Config, StoreOverflow};
use crate::ekf::{self, Gaussian, Innovation};
use crate::error::{ConfigError, StepError};
use crate::hypothesis::{Hypothesis, HypothesisSet};
use crate::index::{At, insertion_sort_by};
use crate::model::{MeasurementModel, MotionModel};
use crate::real::{LogSumExp, Real, exp, ln, log_add};
use crate::report::StepReport;
use crate::sampler::{SamplerConfig, mix};
use crate::selection::TopChildren;
use crate::store::{Track, TrackLabel, TrackStore};
use crate::weight::{Event, WeightModel};
use nalgebra::SVector;

/// "No slot" / "missed" marker in the materialisation tables.
const NONE: u16 = u16::MAX;

/// One object of a prior hypothesis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PriorObject<T: Real, const S: usize> {
    /// The object's label; the same object in several prior hypotheses carries the same label.
    pub label: TrackLabel,
    /// Its Gaussian at the prior time.
    pub state: Gaussian<T, S>,
}

/// One hypothesis of the prior: a weight (normalised over the prior by the tracker) and its objects.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PriorHypothesis<'a, T: Real, const S: usize> {
    /// Relative weight (≥ 0).
    pub weight: T,
    /// The objects.
    pub objects: &'a [PriorObject<T, S>],
}

/// A track after prediction to the current scan.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Predicted<T: Real, const S: usize, const D: usize> {
    state: Gaussian<T, S>,
    innovation: Innovation<T, D>,
    in_field_of_view: bool,
}

/// Scratch space of one scan. Its contents never outlive a `step` call.
#[derive(Debug, Clone)]
struct Workspace<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> {
    predicted: [Predicted<T, S, D>; K],
    /// δ of digest §4.4 for every (track slot, measurement).
    entries: [[T; Z]; K],
    /// δ for every (birth cell, measurement).
    birth_entries: [[T; Z]; B],
    matrix: AssociationMatrix<T, N, Z>,
    saved_column: [T; Z],
    top: TopChildren<T, H, Z>,
    order: [u16; H],
    /// First new slot made from each old slot / birth cell, and the chain of new slots per source.
    source_head: [u16; K],
    birth_head: [u16; B],
    next_same_source: [u16; K],
    /// The measurement each new slot took, or `NONE` when missed.
    new_slot_measurement: [u16; K],
    row_of_column: [u16; N],
    /// Matrix column → position of its object in the parent.
    column_position: [u16; N],
    child_sources: [(Source, u16); N],
    child_slots: [u16; N],
    hashes: [u64; H],
    /// The label of the object born from each measurement this scan, whatever its birth cell.
    birth_label_of_row: [Option<TrackLabel>; Z],
    /// The label of the undetected object born in each cell this scan.
    birth_label_of_cell: [Option<TrackLabel>; B],
}

impl<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
> Workspace<T, S, D, H, N, Z, K, B>
{
    /// Empty scratch space (usable in a `const` context).
    const fn new() -> Self {
        Self {
            predicted: [Predicted { state: Gaussian::ZERO, innovation: Innovation::EMPTY, in_field_of_view: false }; K],
            entries: [[T::NEG_INFINITY; Z]; K],
            birth_entries: [[T::NEG_INFINITY; Z]; B],
            matrix: AssociationMatrix::new(0, 0, T::ZERO),
            saved_column: [T::NEG_INFINITY; Z],
            top: TopChildren::new(),
            order: [0; H],
            source_head: [NONE; K],
            birth_head: [NONE; B],
            next_same_source: [NONE; K],
            new_slot_measurement: [NONE; K],
            row_of_column: [NONE; N],
            column_position: [0; N],
            child_sources: [(Source::Track(0), NONE); N],
            child_slots: [0; N],
            hashes: [0; H],
            birth_label_of_row: [None; Z],
            birth_label_of_cell: [None; B],
        }
    }
}

/// Where a child's track comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Source {
    /// A predicted track of the previous store.
    Track(u16),
    /// A birth cell.
    Birth(u16),
}

/// The R-FISST / hypothesis-level FISST tracker with fixed capacities.
///
/// - `T`: scalar (`f32` or `f64`); `M`: [`MotionModel`]; `G`: [`MeasurementModel`].
/// - `S`, `D`: state and measurement dimensions.
/// - `H`: hypotheses kept per scan (H∞); `N`: objects per hypothesis; `Z`: measurements per scan;
///   `K`: tracks in the shared store (≥ N); `B`: birth cells.
///
/// All memory is inside the value; `step` allocates nothing. The capacities are checked at compile time.
///
/// # Examples
/// ```
/// use nalgebra::{SMatrix, SVector};
/// use tracker_core::{Config, ConstantVelocity, PositionMeasurement, Region, Sensor, Tracker, BirthModel, Gaussian};
/// use tracker_core::config::{ChildGeneration, Selection, StoreOverflow};
///
/// let config = Config {
///     motion: ConstantVelocity { acceleration_noise: 0.01 },
///     measurement: PositionMeasurement::isotropic(0.5),
///     sensor: Sensor { detection_probability: 0.9, clutter_rate: 1.0, field_of_view: Region::Rectangle { min: [-50.0, -50.0], max: [50.0, 50.0] } },
///     birth: BirthModel::none(),
///     death_probability: 0.0,
///     gate: None,
///     children: ChildGeneration::default(),
///     selection: Selection::default(),
///     store_overflow: StoreOverflow::default(),
///     seed: 1,
/// };
/// let object = Gaussian { mean: SVector::from([0.0, 0.0, 1.0, 0.0]), covariance: SMatrix::identity() };
/// let mut tracker: Tracker<f64, _, _, 4, 2, 8, 4, 4, 16, 1> = Tracker::with_objects(config, &[object], 0.0).unwrap();
/// let report = tracker.step(1.0, &[SVector::from([1.1, 0.05])]).unwrap();
/// assert_eq!(report.hypotheses, 2); // z from the object, or clutter and the object missed
/// assert!(tracker.map_hypothesis().weight() > 0.9);
/// ```
#[derive(Debug, Clone)]
pub struct Tracker<
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
    config: Config<T, M, G, S, B>,
    weights: WeightModel<T>,
    birth_innovations: [Innovation<T, D>; B],
    birth_in_field_of_view: [bool; B],
    stores: [TrackStore<T, S, K>; 2],
    hypotheses: [HypothesisSet<T, N, H>; 2],
    /// Which half of `stores` and `hypotheses` is live (`false`: index 0).
    active: bool,
    time: f64,
    scans: u64,
    next_label: u32,
    /// Whether a prior has been loaded ([`Tracker::reset`]).
    initialised: bool,
    work: Workspace<T, S, D, H, N, Z, K, B>,
    /// The sampler's state (used when children are sampled).
    sampler: ClusteredChildren<T, N, Z, H>,
    /// Children sampled or enumerated in the last scan's chains: Metropolis steps taken.
    last_sampler_steps: u64,
}

/// A read-only view of one hypothesis and the tracks it holds.
#[derive(Debug, Clone, Copy)]
pub struct HypothesisView<'a, T: Real, const S: usize, const N: usize> {
    hypothesis: &'a Hypothesis<T, N>,
    tracks: &'a [Track<T, S>],
}

impl<'a, T: Real, const S: usize, const N: usize> HypothesisView<'a, T, S, N> {
    /// Normalised weight w.
    pub fn weight(&self) -> T {
        exp(self.hypothesis.log_weight)
    }

    /// Normalised log-weight ln w.
    pub fn log_weight(&self) -> T {
        self.hypothesis.log_weight
    }

    /// Number of objects.
    pub fn len(&self) -> usize {
        self.hypothesis.len()
    }

    /// Whether the hypothesis holds no object.
    pub fn is_empty(&self) -> bool {
        self.hypothesis.is_empty()
    }

    /// Store slots of its tracks (in label order).
    pub fn slots(&self) -> &'a [u16] {
        self.hypothesis.slots()
    }

    /// Its tracks, in label order.
    pub fn tracks(&self) -> impl Iterator<Item = &'a Track<T, S>> + 'a {
        let tracks = self.tracks;
        // Every slot of a hypothesis is a live track of the store.
        self.hypothesis.slots().iter().filter_map(move |&slot| tracks.get(usize::from(slot)))
    }
}

/// The live half of a double buffer and the other half, mutably.
fn split_pair<X>(pair: &mut [X; 2], active: bool) -> (&X, &mut X) {
    let [first, second] = pair;
    if active { (second, first) } else { (first, second) }
}

/// 64-bit FNV-1a of a slot list, to find identical children quickly.
fn slots_hash(slots: &[u16]) -> u64 {
    let mut hash = Fnv1a::new();
    for &slot in slots {
        hash.write(&slot.to_le_bytes());
    }
    hash.finish()
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
    const CAPACITY_CHECK: () = {
        assert!(S > 0 && D > 0, "state and measurement dimensions must be > 0");
        assert!(H > 0 && N > 0 && Z > 0, "capacities H, N and Z must be > 0");
        assert!(K >= N, "the track store must hold at least N tracks so that the best child always fits");
        assert!(
            H < u16::MAX as usize
                && N < u16::MAX as usize
                && Z < u16::MAX as usize
                && K < u16::MAX as usize
                && B < u16::MAX as usize,
            "capacities must fit in u16"
        );
    };

    /// Builds a tracker from a configuration, a prior (one or more weighted hypotheses) and the prior's
    /// time in seconds.
    ///
    /// The tracker is returned by value, which can take a few times its size of stack; on a small target
    /// put it in a `static` with [`Tracker::empty`] and load it with [`Tracker::reset`] instead.
    ///
    /// # Errors
    /// [`ConfigError`] naming the first invalid parameter or prior entry.
    pub fn new(
        config: Config<T, M, G, S, B>,
        prior: &[PriorHypothesis<'_, T, S>],
        time: f64,
    ) -> Result<Self, ConfigError> {
        let mut tracker = Self::empty(config);
        tracker.reset(prior, time)?;
        Ok(tracker)
    }

    /// A tracker holding `config` but no prior yet, built in a `const` context so that it can be the
    /// initial value of a `static` (no stack is used for its storage):
    ///
    /// ```ignore
    /// static TRACKER: Mutex<RefCell<SsaTracker<f32>>> = Mutex::new(RefCell::new(SsaTracker::empty(CONFIG)));
    /// ```
    ///
    /// The configuration is checked, and the prior loaded, by [`Tracker::reset`]; until then `step` fails
    /// with [`StepError::NotInitialised`].
    pub const fn empty(config: Config<T, M, G, S, B>) -> Self {
        #[allow(clippy::let_unit_value)]
        let () = Self::CAPACITY_CHECK;
        let sampler = match config.children {
            ChildGeneration::Sampled(sampler) => sampler,
            ChildGeneration::Exhaustive { .. } => SamplerConfig::DEFAULT,
        };
        Self {
            config,
            weights: WeightModel::EMPTY,
            birth_innovations: [Innovation::EMPTY; B],
            birth_in_field_of_view: [false; B],
            stores: [TrackStore::new(), TrackStore::new()],
            hypotheses: [HypothesisSet::new(), HypothesisSet::new()],
            active: false,
            time: 0.0,
            scans: 0,
            next_label: 0,
            initialised: false,
            work: Workspace::new(),
            sampler: ClusteredChildren::empty(sampler),
            last_sampler_steps: 0,
        }
    }

    /// Checks the configuration and loads `prior` at `time` (seconds), in place: the tracker restarts
    /// from this prior with no scan processed.
    ///
    /// # Errors
    /// [`ConfigError`] naming the first invalid parameter or prior entry; the tracker is then unchanged.
    pub fn reset(&mut self, prior: &[PriorHypothesis<'_, T, S>], time: f64) -> Result<(), ConfigError> {
        let (birth_innovations, birth_in_field_of_view) = Self::validate(&self.config)?;
        if !time.is_finite() {
            return Err(ConfigError::PriorTime);
        }
        // Into the inactive buffers; swapped in only on success.
        let next_label = self.load_prior(prior)?;
        self.active = !self.active;
        self.weights = WeightModel::from_config(&self.config);
        self.birth_innovations = birth_innovations;
        self.birth_in_field_of_view = birth_in_field_of_view;
        self.time = time;
        self.scans = 0;
        self.next_label = next_label;
        self.initialised = true;
        if let ChildGeneration::Sampled(sampler) = self.config.children {
            self.sampler = ClusteredChildren::empty(sampler);
        }
        Ok(())
    }

    /// Builds a tracker whose prior is one hypothesis (weight 1) holding `objects`, labelled 0, 1, ...
    ///
    /// # Errors
    /// As [`Tracker::new`].
    pub fn with_objects(
        config: Config<T, M, G, S, B>,
        objects: &[Gaussian<T, S>],
        time: f64,
    ) -> Result<Self, ConfigError> {
        let mut prior: heapless::Vec<PriorObject<T, S>, N> = heapless::Vec::new();
        for (index, state) in objects.iter().enumerate() {
            prior
                .push(PriorObject { label: TrackLabel(index as u32), state: *state })
                .map_err(|_| ConfigError::PriorTooManyObjects { hypothesis: 0 })?;
        }
        Self::new(config, &[PriorHypothesis { weight: T::one(), objects: &prior }], time)
    }

    #[allow(clippy::type_complexity)]
    fn validate(config: &Config<T, M, G, S, B>) -> Result<([Innovation<T, D>; B], [bool; B]), ConfigError> {
        config.motion.validate().map_err(ConfigError::Motion)?;
        config.sensor.validate(D).map_err(ConfigError::Sensor)?;
        if !ekf::is_valid_covariance(&config.measurement.noise_covariance()) {
            return Err(ConfigError::MeasurementNoise);
        }
        let alpha = config.birth.probability;
        if !(alpha.is_finite_value() && alpha >= T::zero() && alpha <= T::one()) {
            return Err(ConfigError::BirthProbability);
        }
        let beta = config.death_probability;
        if !(beta.is_finite_value() && beta >= T::zero() && beta <= T::one()) {
            return Err(ConfigError::DeathProbability);
        }
        // P(no event) = 1 − M_b α − M_d β must stay > 0 for every parent: M_d ≤ N.
        let cells = T::of_f64(config.birth.cells.len() as f64);
        if !(T::one() - cells * alpha - T::of_f64(N as f64) * beta > T::zero()) {
            return Err(ConfigError::EventProbabilities);
        }
        if let Some(gate) = config.gate
            && !(gate.is_finite_value() && gate > T::zero())
        {
            return Err(ConfigError::Gate);
        }
        match config.children {
            ChildGeneration::Exhaustive { max_children_per_scan } => {
                if max_children_per_scan == 0 {
                    return Err(ConfigError::ChildBudget);
                }
            }
            ChildGeneration::Sampled(sampler) => {
                if sampler.steps == 0 {
                    return Err(ConfigError::ChildBudget);
                }
            }
        }
        let mut innovations = [Innovation::default(); B];
        let mut in_view = [false; B];
        let cells = config.birth.cells.iter().zip(innovations.iter_mut().zip(in_view.iter_mut()));
        for (cell, (birth, (innovation, in_view))) in cells.enumerate() {
            if !(birth.mean.iter().all(|v| v.is_finite_value()) && ekf::is_valid_covariance(&birth.covariance)) {
                return Err(ConfigError::BirthCell { cell });
            }
            *innovation =
                ekf::innovation(&config.measurement, birth).map_err(|_| ConfigError::BirthInnovation { cell })?;
            *in_view = config.sensor.field_of_view.contains(&innovation.predicted);
        }
        Ok((innovations, in_view))
    }

    /// Checks `prior` and writes it into the inactive buffers; returns the next free label.
    fn load_prior(&mut self, prior: &[PriorHypothesis<'_, T, S>]) -> Result<u32, ConfigError> {
        if prior.is_empty() {
            return Err(ConfigError::PriorEmpty);
        }
        if prior.len() > H {
            return Err(ConfigError::PriorTooManyHypotheses);
        }
        let mut total = T::zero();
        for (index, hypothesis) in prior.iter().enumerate() {
            if !(hypothesis.weight.is_finite_value() && hypothesis.weight >= T::zero()) {
                return Err(ConfigError::PriorWeight { hypothesis: index });
            }
            total += hypothesis.weight;
        }
        if !(total > T::zero() && total.is_finite_value()) {
            return Err(ConfigError::PriorWeight { hypothesis: 0 });
        }
        let inactive = usize::from(!self.active);
        let store = self.stores.at_mut(inactive);
        store.clear();
        let set = self.hypotheses.at_mut(inactive);
        set.clear();
        let mut next_label: u32 = 0;
        for (index, hypothesis) in prior.iter().enumerate() {
            if hypothesis.objects.len() > N {
                return Err(ConfigError::PriorTooManyObjects { hypothesis: index });
            }
            let mut slots = [0u16; N];
            for (position, (object, slot)) in hypothesis.objects.iter().zip(slots.iter_mut()).enumerate() {
                let state = &object.state;
                if !(state.mean.iter().all(|v| v.is_finite_value()) && ekf::is_valid_covariance(&state.covariance)) {
                    return Err(ConfigError::PriorObject { hypothesis: index, object: position });
                }
                if hypothesis.objects.iter().take(position).any(|other| other.label == object.label) {
                    return Err(ConfigError::PriorDuplicateLabel { hypothesis: index });
                }
                next_label = next_label.max(object.label.0.saturating_add(1));
                let existing = store.as_slice().iter().position(|t| t.label == object.label && t.state == *state);
                *slot = match existing {
                    Some(slot) => slot as u16,
                    None => store
                        .push(Track { label: object.label, state: *state, existence: T::zero() })
                        .map_err(|_| ConfigError::PriorTrackStoreFull)?,
                };
            }
            if hypothesis.weight == T::zero() {
                continue;
            }
            let slots = &mut slots[..hypothesis.objects.len()];
            // Labels are distinct within a hypothesis, so the order is unique.
            let tracks = store.as_slice();
            let label = |slot: u16| tracks.get(usize::from(slot)).map(|track| track.label);
            insertion_sort_by(slots, |&a, &b| label(a) < label(b));
            // The prior has at most H hypotheses, so this push cannot fail.
            let _ = set.push(Hypothesis::new(ln(hypothesis.weight / total), slots));
        }
        finish_hypotheses(set, store);
        Ok(next_label)
    }

    /// Processes one scan taken at `time` (seconds, after the previous scan) with `measurements`.
    ///
    /// # Errors
    /// [`StepError`]; the tracker is then exactly as it was before the call.
    pub fn step(&mut self, time: f64, measurements: &[SVector<T, D>]) -> Result<StepReport<T>, StepError> {
        if !self.initialised {
            return Err(StepError::NotInitialised);
        }
        self.check_scan(time, measurements)?;
        let dt = T::of_f64(time - self.time);
        self.predict_and_score(dt, measurements)?;
        let births_skipped = self.generate_children(measurements.len())?;
        let outcome = self.materialise(measurements)?;

        // Commit.
        self.active = !self.active;
        self.time = time;
        self.scans += 1;
        self.next_label = outcome.next_label;
        let top = &self.work.top;
        Ok(StepReport {
            scan: self.scans,
            measurements: measurements.len(),
            hypotheses: self.hypotheses[self.live()].len(),
            tracks: self.stores[self.live()].len(),
            children: top.offered(),
            // The kept sum is part of the total: a ratio above 1 is rounding.
            captured_mass: exp(outcome.kept_total.log_ratio(top.total())).min(T::one()),
            merged_children: outcome.merged,
            children_dropped_for_store: outcome.dropped_for_store,
            births_beyond_object_capacity: births_skipped,
            sampler_steps: self.last_sampler_steps,
            expected_cardinality: self.expected_cardinality(),
        })
    }

    fn check_scan(&self, time: f64, measurements: &[SVector<T, D>]) -> Result<(), StepError> {
        if measurements.len() > Z {
            return Err(StepError::TooManyMeasurements { received: measurements.len(), capacity: Z });
        }
        if !time.is_finite() {
            return Err(StepError::NonFiniteTime);
        }
        if time <= self.time {
            return Err(StepError::TimeNotAfterLastScan);
        }
        for (index, z) in measurements.iter().enumerate() {
            if !z.iter().all(|v| v.is_finite_value()) {
                return Err(StepError::NonFiniteMeasurement { index });
            }
            if !self.config.sensor.field_of_view.contains(z) {
                return Err(StepError::MeasurementOutsideFieldOfView { index });
            }
        }
        Ok(())
    }

    /// Step 1: predict every track once and score it against every measurement once.
    fn predict_and_score(&mut self, dt: T, measurements: &[SVector<T, D>]) -> Result<(), StepError> {
        let store = &self.stores[self.live()];
        let slots = self.work.predicted.iter_mut().zip(self.work.entries.iter_mut());
        for (track, (predicted, entries)) in store.as_slice().iter().zip(slots) {
            let numerical = |error| StepError::Numerical { label: track.label, error };
            let state = ekf::predict(&self.config.motion, &track.state, dt).map_err(numerical)?;
            let innovation = ekf::innovation(&self.config.measurement, &state).map_err(numerical)?;
            let in_field_of_view = self.config.sensor.field_of_view.contains(&innovation.predicted);
            for (entry, z) in entries.iter_mut().zip(measurements) {
                *entry = if in_field_of_view { self.weights.entry(&innovation, z) } else { T::NEG_INFINITY };
            }
            *predicted = Predicted { state, innovation, in_field_of_view };
        }
        let cells =
            self.work.birth_entries.iter_mut().zip(self.birth_innovations.iter().zip(&self.birth_in_field_of_view));
        for (entries, (innovation, &in_field_of_view)) in cells.take(self.config.birth.cells.len()) {
            for (entry, z) in entries.iter_mut().zip(measurements) {
                *entry = if in_field_of_view { self.weights.entry(innovation, z) } else { T::NEG_INFINITY };
            }
        }
        Ok(())
    }

    /// Step 2: offer every (parent, event) child to the selection. Returns the number of birth events
    /// skipped because the parent already holds `N` objects.
    ///
    /// Deaths with sampled children: a death child of object o with association σ (σ leaves o
    /// unassigned) weighs exactly the no-event child σ times β / (P(no event) (1 − p_D)), so the death
    /// children are derived from the no-event chain's kept children instead of running one chain per
    /// object. (With p_D = 1 the sets differ, and each death gets its own chain.)
    fn generate_children(&mut self, rows: usize) -> Result<u64, StepError> {
        // `check_scan` bounds the rows by Z; the clamp shows it to the optimiser.
        let rows = rows.min(Z);
        let scan_seed = mix(self.config.seed ^ mix(self.scans + 1));
        let steps_before = self.sampler.sampler().steps_taken();
        let sampled = matches!(self.config.children, ChildGeneration::Sampled(_));
        let mut generator = match self.config.children {
            ChildGeneration::Exhaustive { max_children_per_scan } => {
                Generator::Exhaustive(ExhaustiveChildren::new(max_children_per_scan))
            }
            ChildGeneration::Sampled(_) => Generator::Sampled(&mut self.sampler),
        };
        let weights = self.weights;
        let birth_cells = if weights.births_possible() { self.config.birth.cells.len() } else { 0 };
        let derive_deaths = sampled && weights.deaths_possible() && !weights.detection_required();
        let mut births_skipped = 0u64;

        let work = &mut self.work;
        match self.config.selection {
            Selection::TopWeight => work.top.clear(),
            Selection::SampledByWeight => work.top.clear_sampling(mix(scan_seed ^ 0x5e1e_c7ed)),
        }
        let parents = self.hypotheses[usize::from(self.active)].as_slice();
        for (parent_index, parent) in parents.iter().enumerate() {
            // Columns: the parent's objects in the field of view, in the parent's order.
            work.matrix = AssociationMatrix::new(rows, 0, T::zero());
            for (position, &slot) in parent.slots().iter().enumerate() {
                let slot = usize::from(slot);
                if work.predicted.at(slot).in_field_of_view {
                    // A parent holds at most N objects, so the matrix has room.
                    if let Some(column) =
                        work.matrix.push_column(&work.entries.at(slot)[..rows], weights.detection_required())
                    {
                        *work.column_position.at_mut(column) = position as u16;
                    }
                }
            }
            let in_view = work.matrix.columns();
            let context =
                ParentContext { index: parent_index as u16, log_weight: parent.log_weight, in_view, rows, scan_seed };

            offer_event(&mut generator, work, &weights, &context, Event::None, in_view)?;
            if derive_deaths {
                derive_death_children(&generator, work, &weights, &context);
            }

            // One birth in a cell (α each), if the child can hold one more object.
            if parent.len() >= N {
                births_skipped += birth_cells as u64;
            } else {
                for cell in 0..birth_cells {
                    let Some(&detectable) = self.birth_in_field_of_view.get(cell) else { break };
                    if detectable {
                        // `cell < B`: checked by the `get` above.
                        let _ = work.matrix.push_column(&work.birth_entries[cell][..rows], weights.birth_required());
                    } else if weights.birth_required() {
                        continue; // a birth that must be detected where it cannot be
                    }
                    let event = Event::Birth { cell: cell as u16 };
                    let result =
                        offer_event(&mut generator, work, &weights, &context, event, in_view + usize::from(detectable));
                    if detectable {
                        work.matrix.pop_column();
                    }
                    result?;
                }
            }

            // One death among the objects in the field of view (β each), each by its own matrix.
            if weights.deaths_possible() && !derive_deaths {
                for column in 0..in_view {
                    work.matrix.column(column, &mut work.saved_column);
                    let required = work.matrix.is_required(column);
                    work.matrix.set_column(column, &[T::NEG_INFINITY; Z][..rows], false);
                    let event = Event::Death { object: *work.column_position.at(column) };
                    let result = offer_event(&mut generator, work, &weights, &context, event, in_view - 1);
                    work.matrix.set_column(column, &work.saved_column[..rows], required);
                    result?;
                }
            }
        }
        if work.top.is_empty() {
            return Err(StepError::NoViableChild);
        }
        self.last_sampler_steps = self.sampler.sampler().steps_taken() - steps_before;
        Ok(births_skipped)
    }

    /// Step 3: build the kept children's tracks and hypotheses in the inactive buffers.
    fn materialise(&mut self, measurements: &[SVector<T, D>]) -> Result<Materialised<T>, StepError> {
        let active = self.active;
        let (store, next_store) = split_pair(&mut self.stores, active);
        let (parents, next_set) = split_pair(&mut self.hypotheses, active);
        let work = &mut self.work;
        let config = &self.config;
        next_store.clear();
        next_set.clear();
        work.source_head[..store.len()].fill(NONE);
        work.birth_head.fill(NONE);
        work.birth_label_of_row.fill(None);
        work.birth_label_of_cell.fill(None);

        let mut next_label = self.next_label;
        let mut dropped_for_store = 0usize;
        let mut merged = 0usize;
        let kept = work.top.best_first(&mut work.order);
        // A candidate naming a parent, a birth cell or a track that does not exist cannot occur; it would be
        // skipped like a child that does not fit.
        'children: for rank in 0..kept {
            let Some(&candidate) = work.top.kept().get(usize::from(*work.order.at(rank))) else { continue };
            let Some(parent) = parents.as_slice().get(usize::from(candidate.parent)) else { continue };

            // Which row took each column.
            work.row_of_column.fill(NONE);
            for (row, &column) in candidate.assignment.iter().enumerate().take(measurements.len()) {
                if column != CLUTTER {
                    *work.row_of_column.at_mut(usize::from(column)) = row as u16;
                }
            }
            // The child's objects as (source, measurement) keys.
            let mut count = 0usize;
            let mut column = 0usize;
            for (position, &slot) in parent.slots().iter().enumerate() {
                let row = if work.predicted.at(usize::from(slot)).in_field_of_view {
                    column += 1;
                    *work.row_of_column.at(column - 1)
                } else {
                    NONE
                };
                if candidate.event == (Event::Death { object: position as u16 }) {
                    continue;
                }
                *work.child_sources.at_mut(count) = (Source::Track(slot), row);
                count += 1;
            }
            if let Event::Birth { cell } = candidate.event {
                let Some(&detectable) = self.birth_in_field_of_view.get(usize::from(cell)) else { continue };
                let row = if detectable { *work.row_of_column.at(column) } else { NONE };
                *work.child_sources.at_mut(count) = (Source::Birth(cell), row);
                count += 1;
            }
            // A child holds at most N objects; the clamp shows it to the optimiser.
            let count = count.min(N);

            // Room for its new tracks?
            let new_tracks = work.child_sources[..count]
                .iter()
                .filter(|&&(source, row)| lookup(work, source, row).is_none())
                .count();
            if next_store.len() + new_tracks > K {
                match config.store_overflow {
                    StoreOverflow::PruneChildren => {
                        dropped_for_store += 1;
                        continue;
                    }
                    StoreOverflow::Error => return Err(StepError::TrackStoreFull { capacity: K }),
                }
            }

            for index in 0..count {
                let (source, row) = work.child_sources[index];
                let slot = match lookup(work, source, row) {
                    Some(slot) => slot,
                    None => {
                        let (label, prior, innovation) = match source {
                            Source::Track(old) => {
                                let old = usize::from(old);
                                let Some(track) = store.as_slice().get(old) else { continue 'children };
                                let predicted = work.predicted.at(old);
                                (track.label, predicted.state, predicted.innovation)
                            }
                            Source::Birth(cell) => {
                                let cell = usize::from(cell);
                                let (Some(&prior), Some(&innovation), Some(by_cell)) = (
                                    config.birth.cells.get(cell),
                                    self.birth_innovations.get(cell),
                                    work.birth_label_of_cell.get_mut(cell),
                                ) else {
                                    continue 'children;
                                };
                                // One new object per measurement (or per cell when undetected): the same
                                // birth explained by different cells' pdfs is one object with one label.
                                let known = match work.birth_label_of_row.get_mut(usize::from(row)) {
                                    Some(by_row) => by_row,
                                    None => by_cell,
                                };
                                let label = match *known {
                                    Some(label) => label,
                                    None => {
                                        let label = TrackLabel(next_label);
                                        next_label = next_label.checked_add(1).ok_or(StepError::LabelsExhausted)?;
                                        *known = Some(label);
                                        label
                                    }
                                };
                                (label, prior, innovation)
                            }
                        };
                        // Missed (`row == NONE`): the prediction; else the update with the measurement.
                        let state = match measurements.get(usize::from(row)) {
                            None => prior,
                            Some(z) => ekf::update(&config.measurement, &prior, &innovation, z)
                                .map_err(|error| StepError::Numerical { label, error })?,
                        };
                        // Room was checked above; the error path is unreachable but kept panic-free.
                        let new_slot = next_store
                            .push(Track { label, state, existence: T::zero() })
                            .map_err(|_| StepError::TrackStoreFull { capacity: K })?;
                        let head = match source {
                            Source::Track(old) => Some(work.source_head.at_mut(usize::from(old))),
                            Source::Birth(cell) => work.birth_head.get_mut(usize::from(cell)),
                        };
                        if let Some(head) = head {
                            *work.next_same_source.at_mut(usize::from(new_slot)) = *head;
                            *head = new_slot;
                        }
                        *work.new_slot_measurement.at_mut(usize::from(new_slot)) = row;
                        new_slot
                    }
                };
                work.child_slots[index] = slot;
            }
            let tracks = next_store.as_slice();
            let slots = &mut work.child_slots[..count];
            // Labels are distinct within a child, so the order is unique.
            let label = |slot: u16| tracks.get(usize::from(slot)).map(|track| track.label);
            insertion_sort_by(slots, |&a, &b| label(a) < label(b));

            // Merge with an identical child kept earlier, else keep it.
            let hash = slots_hash(slots);
            let existing = next_set
                .as_mut_slice()
                .iter_mut()
                .zip(work.hashes.iter())
                .find(|(h, other)| **other == hash && h.slots() == &*slots);
            match existing {
                Some((hypothesis, _)) => {
                    hypothesis.log_weight = log_add(hypothesis.log_weight, candidate.log_weight);
                    merged += 1;
                }
                None => {
                    if let Ok(index) = next_set.push(Hypothesis::new(candidate.log_weight, slots)) {
                        *work.hashes.at_mut(index) = hash;
                    }
                }
            }
        }

        // Normalise over the kept hypotheses.
        let mut kept_total = LogSumExp::new();
        for hypothesis in next_set.as_slice() {
            kept_total.add(hypothesis.log_weight);
        }
        for hypothesis in next_set.as_mut_slice() {
            hypothesis.log_weight = kept_total.normalise(hypothesis.log_weight);
        }
        finish_hypotheses(next_set, next_store);
        Ok(Materialised { kept_total, next_label, dropped_for_store, merged })
    }

    /// Index of the live half of the double buffers (0 or 1).
    fn live(&self) -> usize {
        usize::from(self.active)
    }

    /// The configuration.
    pub fn config(&self) -> &Config<T, M, G, S, B> {
        &self.config
    }

    /// Time of the last scan (or of the prior), in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Number of scans processed.
    pub fn scans(&self) -> u64 {
        self.scans
    }

    /// The hypotheses, best first, with normalised weights.
    pub fn hypotheses(&self) -> impl ExactSizeIterator<Item = HypothesisView<'_, T, S, N>> + '_ {
        let tracks = self.stores[self.live()].as_slice();
        self.hypotheses[self.live()].as_slice().iter().map(move |hypothesis| HypothesisView { hypothesis, tracks })
    }

    /// The maximum a posteriori hypothesis (the first of [`Tracker::hypotheses`]; ties keep the
    /// deterministic enumeration order).
    pub fn map_hypothesis(&self) -> HypothesisView<'_, T, S, N> {
        let tracks = self.stores[self.live()].as_slice();
        // There is always at least one hypothesis: the prior has one and every scan keeps one.
        HypothesisView { hypothesis: &self.hypotheses[self.live()].as_slice()[0], tracks }
    }

    /// Every track of the shared store, with its existence probability.
    pub fn tracks(&self) -> &[Track<T, S>] {
        self.stores[self.live()].as_slice()
    }

    /// Existence probability of the object `label`: the total weight of the hypotheses that hold a
    /// track with that label.
    pub fn label_existence(&self, label: TrackLabel) -> T {
        self.tracks().iter().filter(|track| track.label == label).fold(T::zero(), |sum, track| sum + track.existence)
    }

    /// P(number of objects = `n`).
    pub fn cardinality_probability(&self, n: usize) -> T {
        self.hypotheses().filter(|h| h.len() == n).fold(T::zero(), |sum, h| sum + h.weight())
    }

    /// Expected number of objects Σ_h w_h N_h.
    pub fn expected_cardinality(&self) -> T {
        self.hypotheses().fold(T::zero(), |sum, h| sum + h.weight() * T::of_f64(h.len() as f64))
    }

    /// A 64-bit digest (FNV-1a) of everything the tracker exposes: time, scan count, and for every
    /// hypothesis in order its log-weight and its tracks' labels, means and covariances, as raw bits.
    /// Two trackers with the same digest agree bit for bit (up to hash collisions); it is how the host and
    /// an embedded target are compared.
    pub fn digest(&self) -> u64 {
        let mut hash = Fnv1a::new();
        hash.write(&self.time.to_bits().to_le_bytes());
        hash.write(&self.scans.to_le_bytes());
        for hypothesis in self.hypotheses() {
            hash.write(&hypothesis.log_weight().as_f64().to_bits().to_le_bytes());
            for track in hypothesis.tracks() {
                hash.write(&track.label.0.to_le_bytes());
                for value in track.state.mean.iter().chain(track.state.covariance.iter()) {
                    hash.write(&value.as_f64().to_bits().to_le_bytes());
                }
            }
        }
        hash.finish()
    }
}

/// 64-bit FNV-1a.
struct Fnv1a(u64);

impl Fnv1a {
    fn new() -> Self {
        Fnv1a(0xcbf2_9ce4_8422_2325)
    }

    fn write(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            self.0 ^= u64::from(byte);
            self.0 = self.0.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// What the child generation of one parent needs to know about it.
struct ParentContext<T> {
    index: u16,
    log_weight: T,
    in_view: usize,
    rows: usize,
    scan_seed: u64,
}

/// Generates the children of the current matrix for `event` into the selection.
fn offer_event<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    generator: &mut Generator<'_, T, N, Z, H>,
    work: &mut Workspace<T, S, D, H, N, Z, K, B>,
    weights: &WeightModel<T>,
    parent: &ParentContext<T>,
    event: Event,
    child_in_view: usize,
) -> Result<(), StepError> {
    let log_probability = weights.event_log_probability(event, parent.in_view);
    work.matrix.set_baseline(weights.baseline(parent.log_weight, log_probability, child_in_view, parent.rows));
    work.top.set_context(parent.index, event);
    // One random stream per (scan, parent, event): a chain's draws do not depend on the others.
    let event_code = match event {
        Event::None => 0,
        Event::Birth { cell } => 1 + u64::from(cell),
        Event::Death { object } => 1 + B as u64 + u64::from(object),
    };
    generator.reseed(mix(parent.scan_seed ^ mix((u64::from(parent.index) << 32) | event_code)));
    generator.generate(&work.matrix, &mut work.top).map(|_| ()).map_err(|error| match error {
        GenerateError::BudgetExceeded { budget } => StepError::ChildBudgetExceeded { budget },
    })
}

/// Offers the death children derived from the no-event children just generated (see
/// `generate_children`).
fn derive_death_children<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    generator: &Generator<'_, T, N, Z, H>,
    work: &mut Workspace<T, S, D, H, N, Z, K, B>,
    weights: &WeightModel<T>,
    parent: &ParentContext<T>,
) {
    let Generator::Sampled(sampled) = generator else { return };
    // ln r = ln β − ln P(no event) − ln(1 − p_D)
    let log_ratio = weights.event_log_probability(Event::Death { object: 0 }, parent.in_view)
        - weights.event_log_probability(Event::None, parent.in_view)
        - weights.finite_miss();
    for (score, assignment) in sampled.offered(parent.rows) {
        let mut assigned = [false; N];
        for &column in assignment {
            if column != CLUTTER {
                *assigned.at_mut(usize::from(column)) = true;
            }
        }
        let unassigned = || assigned.iter().enumerate().take(parent.in_view).filter(|&(_, &a)| !a).map(|(c, _)| c);
        let free = unassigned().count();
        if free == 0 {
            continue;
        }
        let death_score = score + log_ratio;
        if work.top.selects_by_weight() && !(death_score > work.top.threshold()) {
            // None of this association's death children can be kept: count their mass at once.
            work.top.unoffered(death_score + ln(T::of_f64(free as f64)));
            continue;
        }
        for column in unassigned() {
            work.top.set_context(parent.index, Event::Death { object: *work.column_position.at(column) });
            work.top.offer(death_score, assignment);
        }
    }
}

/// The child generator of a scan.
enum Generator<'a, T: Real, const N: usize, const Z: usize, const H: usize> {
    Exhaustive(ExhaustiveChildren),
    Sampled(&'a mut ClusteredChildren<T, N, Z, H>),
}

impl<T: Real, const N: usize, const Z: usize, const H: usize> Generator<'_, T, N, Z, H> {
    fn reseed(&mut self, seed: u64) {
        if let Generator::Sampled(sampler) = self {
            sampler.reseed(seed);
        }
    }
}

impl<T: Real, const N: usize, const Z: usize, const H: usize> ChildGenerator<T, N, Z> for Generator<'_, T, N, Z, H> {
    fn generate<Sink: ChildSink<T>>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        sink: &mut Sink,
    ) -> Result<u64, GenerateError> {
        match self {
            Generator::Exhaustive(exhaustive) => exhaustive.generate(matrix, sink),
            Generator::Sampled(sampled) => sampled.generate(matrix, sink),
        }
    }
}

/// What materialisation produced besides the buffers.
struct Materialised<T> {
    kept_total: LogSumExp<T>,
    next_label: u32,
    dropped_for_store: usize,
    merged: usize,
}

/// Finds the new slot made from `source` with measurement `row` (or missed), if any.
fn lookup<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    work: &Workspace<T, S, D, H, N, Z, K, B>,
    source: Source,
    row: u16,
) -> Option<u16> {
    let mut slot = match source {
        Source::Track(old) => *work.source_head.at(usize::from(old)),
        Source::Birth(cell) => work.birth_head.get(usize::from(cell)).copied().unwrap_or(NONE),
    };
    // Each source has at most Z + 1 distinct new slots (one per measurement, one missed).
    while slot != NONE {
        if *work.new_slot_measurement.at(usize::from(slot)) == row {
            return Some(slot);
        }
        slot = *work.next_same_source.at(usize::from(slot));
    }
    None
}

/// Orders hypotheses best first (stable, so ties keep their order) and sets every track's existence.
fn finish_hypotheses<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    set: &mut HypothesisSet<T, N, H>,
    store: &mut TrackStore<T, S, K>,
) {
    // Insertion sort: merging only raises weights of earlier entries, so few moves are needed.
    insertion_sort_by(set.as_mut_slice(), |a, b| a.log_weight > b.log_weight);
    let tracks = store.as_mut_slice();
    for track in tracks.iter_mut() {
        track.existence = T::zero();
    }
    for hypothesis in set.as_slice() {
        let weight = exp(hypothesis.log_weight);
        for &slot in hypothesis.slots() {
            if let Some(track) = tracks.get_mut(usize::from(slot)) {
                track.existence += weight;
            }
        }
    }
}
