//! Stage 2 of a scan: the children of every (parent, event), offered to the scan's selection.
//!
//! For each parent hypothesis the stage builds its **no-event matrix** (one column per object in the field
//! of view, entries from stage 1) and records its column layout ([`ParentColumns`]); the matrix of each
//! other event is a copy of it (docs/maths.md §5.1): a birth in a cell appends the cell's column when the
//! sensor can see the cell; the death of an object makes its column impossible. A child generator offers
//! each matrix's children to the selection through an [`EventSink`], which knows their (parent, event).
//!
//! **Deaths with sampled children.** The death child of object o with association σ (σ leaves o's column
//! free) weighs exactly the no-event child σ times β / (P(no event) (1 − p_D)) (docs/maths.md §5.4), so
//! the no-event children pass through a recording sink and each one's death children are derived from it
//! once the generator has offered them all, instead of one chain per object. (With p_D = 1 the sets
//! differ, and each death gets its own matrix and chain.)

use super::score::{BirthCells, Scores};
use crate::association::{AssociationMatrix, CLUTTER, ColumnLayout, ParentColumns};
use crate::children::{ChildGenerator, ChildSink, ExhaustiveChildren, GenerateError};
use crate::cluster::ClusteredChildren;
use crate::config::{ChildGeneration, Config, Selection};
use crate::error::StepError;
use crate::hypothesis::Hypothesis;
use crate::index::{At, below, copy_prefix};
use crate::random::{chain_seed, selection_seed};
use crate::real::{Real, exp, ln};
use crate::sampler::SamplerConfig;
use crate::selection::TopChildren;
use crate::weight::{Event, WeightModel};

/// Scratch and results of stage 2: the scan's selection and each parent's column layout, read by stage 3.
#[derive(Debug, Clone)]
pub(super) struct Generation<T: Real, const H: usize, const N: usize, const Z: usize> {
    /// The current parent's no-event matrix.
    objects: AssociationMatrix<T, N, Z>,
    /// The matrix of one of its other events.
    event: AssociationMatrix<T, N, Z>,
    /// Per parent: the columns of its no-event matrix.
    columns: [ParentColumns<N>; H],
    /// The best H children of the scan and the normaliser.
    pub(super) top: TopChildren<T, H, Z>,
    /// The current parent's no-event children, from which its death children are derived.
    no_event_children: OfferedChildren<T, H, Z>,
    /// The sampled generator (by clusters), kept across scans for its tables.
    clustered: ClusteredChildren<T, N, Z, H>,
}

/// What stage 2 reports besides the selection.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Generated {
    /// Birth events not generated because their parent already held `N` objects.
    pub(super) births_skipped: u64,
    /// Metropolis moves made.
    pub(super) sampler_moves: u64,
}

/// One parent as its events' matrices need it.
struct Parent<T> {
    index: u16,
    log_weight: T,
    /// Objects in the field of view: the no-event matrix's columns.
    in_view: usize,
    rows: usize,
}

impl<T: Real, const H: usize, const N: usize, const Z: usize> Generation<T, H, N, Z> {
    pub(super) const fn new(sampler: SamplerConfig) -> Self {
        Self {
            objects: AssociationMatrix::new(0, 0, T::ZERO),
            event: AssociationMatrix::new(0, 0, T::ZERO),
            columns: [const { ParentColumns::new() }; H],
            top: TopChildren::new(),
            no_event_children: OfferedChildren::new(),
            clustered: ClusteredChildren::empty(sampler),
        }
    }

    /// Offers every child of every parent in `parents` to the selection.
    ///
    /// # Errors
    /// [`StepError::ChildBudgetExceeded`] when the exhaustive generator's budget runs out,
    /// [`StepError::NoViableChild`] when no child has non-zero weight.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn run<M, G, const S: usize, const D: usize, const K: usize, const B: usize>(
        &mut self,
        config: &Config<T, M, G, S, B>,
        weight_model: &WeightModel<T>,
        birth_cells: &BirthCells<T, D, B>,
        scores: &Scores<T, S, D, Z, K, B>,
        parents: &[Hypothesis<T, N>],
        rows: usize,
        scan_seed: u64,
        max_moves: u64,
    ) -> Result<Generated, StepError> {
        // The scan check bounds the rows by Z; the clamp shows it to the optimiser.
        let rows = rows.min(Z);
        let Self { objects, event, columns, top, no_event_children, clustered } = self;
        let moves_before = clustered.chain().steps_taken();
        let mut generator = match config.children {
            ChildGeneration::Exhaustive { max_children_per_scan } => {
                Generator::Exhaustive(ExhaustiveChildren::new(max_children_per_scan))
            }
            ChildGeneration::Sampled(_) => Generator::Sampled(clustered),
        };
        let derive_deaths = matches!(generator, Generator::Sampled(_))
            && weight_model.deaths_possible()
            && !weight_model.detection_required();
        let birth_cell_count = if weight_model.births_possible() { config.birth.cells.len() } else { 0 };
        match config.selection {
            Selection::TopWeight => top.clear(),
            Selection::SampledByWeight => top.clear_sampling(selection_seed(scan_seed)),
        }
        let mut births_skipped = 0u64;
        let mut scan_moves = MoveBudget::new(max_moves);
        for ((index, hypothesis), parent_columns) in parents.iter().enumerate().zip(columns.iter_mut()) {
            build_no_event_matrix(objects, parent_columns, hypothesis, scores, rows, weight_model);
            let parent =
                Parent { index: index as u16, log_weight: hypothesis.log_weight, in_view: objects.columns(), rows };
            let seed = |event| chain_seed(scan_seed, parent.index, event_code::<B>(event));
            let births = if hypothesis.len() >= N {
                0
            } else {
                let cells = birth_cells.in_field_of_view.iter().take(birth_cell_count);
                cells.filter(|&&detectable| detectable || !weight_model.birth_required()).count()
            };
            let deaths = if weight_model.deaths_possible() && !derive_deaths { parent.in_view } else { 0 };
            let mut moves = scan_moves.parent_share(hypothesis.log_weight, 1 + births + deaths);

            // No event, and the deaths derived from its children.
            set_baseline(objects, weight_model, &parent, Event::None, parent.in_view);
            generator.prepare(seed(Event::None), &mut moves);
            let mut sink = top.for_event(parent.index, Event::None);
            if derive_deaths {
                no_event_children.clear();
                generator.generate(
                    objects,
                    &mut Recording { inner: &mut sink, record: no_event_children },
                    &mut moves,
                )?;
                derive_death_children(top, weight_model, &parent, parent_columns, no_event_children);
            } else {
                generator.generate(objects, &mut sink, &mut moves)?;
            }

            // One birth in a cell (α each), if the child can hold one more object.
            if hypothesis.len() >= N {
                births_skipped += birth_cell_count as u64;
            } else {
                for cell in 0..birth_cell_count {
                    let Some(detectable) = birth_cells.in_field_of_view(cell) else { break };
                    if !detectable && weight_model.birth_required() {
                        continue; // a birth that must be detected where it cannot be
                    }
                    event.copy_from(objects, None);
                    if let (true, Some(entries)) = (detectable, scores.birth_entries(cell, rows)) {
                        // The parent holds fewer than N objects, so the matrix has room.
                        let _ = event.push_column(entries, weight_model.birth_required());
                    }
                    let birth = Event::Birth { cell: cell as u16 };
                    set_baseline(event, weight_model, &parent, birth, parent.in_view + usize::from(detectable));
                    generator.prepare(seed(birth), &mut moves);
                    generator.generate(event, &mut top.for_event(parent.index, birth), &mut moves)?;
                }
            }

            // One death among the objects in the field of view (β each), each by its own matrix.
            if weight_model.deaths_possible() && !derive_deaths {
                for (column, &position) in parent_columns.positions().iter().enumerate() {
                    event.copy_from(objects, Some(column));
                    let death = Event::Death { object: position };
                    set_baseline(event, weight_model, &parent, death, parent.in_view - 1);
                    generator.prepare(seed(death), &mut moves);
                    generator.generate(event, &mut top.for_event(parent.index, death), &mut moves)?;
                }
            }
            scan_moves.spend(moves.used());
        }
        let sampler_moves = match &generator {
            Generator::Sampled(clustered) => clustered.chain().steps_taken() - moves_before,
            Generator::Exhaustive(_) => 0,
        };
        if top.is_empty() {
            return Err(StepError::NoViableChild);
        }
        Ok(Generated { births_skipped, sampler_moves })
    }

    /// The column layout of the matrix of (`parent`, `event`) in the last scan (`None`: no such parent
    /// or birth cell).
    pub(super) fn layout<const D: usize, const B: usize>(
        &self,
        parent: u16,
        event: Event,
        birth_cells: &BirthCells<T, D, B>,
    ) -> Option<ColumnLayout<'_>> {
        let columns = self.columns.get(usize::from(parent))?;
        let birth_column = match event {
            Event::Birth { cell } => birth_cells.in_field_of_view(usize::from(cell))?.then_some(cell),
            Event::None | Event::Death { .. } => None,
        };
        Some(columns.layout(event, birth_column))
    }

    /// Restarts the sampled generator with `config`'s sampler (after a reset).
    pub(super) fn reset(&mut self, children: ChildGeneration) {
        if let ChildGeneration::Sampled(sampler) = children {
            self.clustered = ClusteredChildren::empty(sampler);
        }
    }
}

/// The no-event matrix of `hypothesis`: its objects in the field of view as columns, in its order.
fn build_no_event_matrix<
    T: Real,
    const S: usize,
    const D: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    matrix: &mut AssociationMatrix<T, N, Z>,
    columns: &mut ParentColumns<N>,
    hypothesis: &Hypothesis<T, N>,
    scores: &Scores<T, S, D, Z, K, B>,
    rows: usize,
    weight_model: &WeightModel<T>,
) {
    *matrix = AssociationMatrix::new(rows, 0, T::zero());
    columns.clear();
    for (position, &slot) in hypothesis.slots().iter().enumerate() {
        let slot = usize::from(slot);
        if scores.predicted(slot).in_field_of_view {
            // A parent holds at most N objects, so both have room.
            if matrix.push_column(scores.entries(slot, rows), weight_model.detection_required()).is_some() {
                let _ = columns.push(position as u16);
            }
        }
    }
}

/// Sets the baseline of `event`'s matrix: ln w_i + ln P(e) + N'_F ln(1 − p_D) + m ln λ_C (docs/maths.md
/// §4.2), with `detectable` objects in the child's field of view.
fn set_baseline<T: Real, const N: usize, const Z: usize>(
    matrix: &mut AssociationMatrix<T, N, Z>,
    weight_model: &WeightModel<T>,
    parent: &Parent<T>,
    event: Event,
    detectable: usize,
) {
    let log_probability = weight_model.event_log_probability(event, parent.in_view);
    matrix.set_baseline(weight_model.baseline(parent.log_weight, log_probability, detectable, parent.rows));
}

/// The number of `event` among a parent's events, for its chain's seed.
fn event_code<const B: usize>(event: Event) -> u64 {
    match event {
        Event::None => 0,
        Event::Birth { cell } => 1 + u64::from(cell),
        Event::Death { object } => 1 + B as u64 + u64::from(object),
    }
}

/// Offers the death children of the recorded no-event children: for each child σ and each object column
/// σ leaves free, the death of that object with weight w(σ) β / (P(no event) (1 − p_D)).
fn derive_death_children<T: Real, const H: usize, const N: usize, const Z: usize>(
    top: &mut TopChildren<T, H, Z>,
    weight_model: &WeightModel<T>,
    parent: &Parent<T>,
    columns: &ParentColumns<N>,
    no_event_children: &OfferedChildren<T, H, Z>,
) {
    // ln r = ln β − ln P(no event) − ln(1 − p_D)
    let log_ratio = weight_model.event_log_probability(Event::Death { object: 0 }, parent.in_view)
        - weight_model.event_log_probability(Event::None, parent.in_view)
        - weight_model.finite_miss();
    let positions = columns.positions();
    for (score, assignment) in no_event_children.iter(parent.rows) {
        let mut assigned = [false; N];
        for &column in assignment {
            if let Some(column) = below::<N>(column) {
                assigned[column] = true;
            }
        }
        let free = assigned.iter().take(positions.len()).filter(|&&taken| !taken).count();
        if free == 0 {
            continue;
        }
        let death_score = score + log_ratio;
        if top.selects_by_weight() && !(death_score > top.threshold()) {
            // None of this association's death children can be kept: count their mass at once.
            top.unoffered(death_score + ln(T::of_f64(free as f64)));
            continue;
        }
        for (&position, _) in positions.iter().zip(&assigned).filter(|&(_, &taken)| !taken) {
            top.offer_child(parent.index, Event::Death { object: position }, death_score, assignment);
        }
    }
}

/// The child generator of a scan.
enum Generator<'a, T: Real, const N: usize, const Z: usize, const H: usize> {
    Exhaustive(ExhaustiveChildren),
    Sampled(&'a mut ClusteredChildren<T, N, Z, H>),
}

impl<T: Real, const N: usize, const Z: usize, const H: usize> Generator<'_, T, N, Z, H> {
    /// Seeds the next matrix's chains and limits their moves to the next event's share of `moves` (the
    /// exhaustive generator draws nothing and makes no move).
    fn prepare(&mut self, seed: u64, moves: &mut ParentMoves) {
        if let Generator::Sampled(sampler) = self {
            sampler.reseed(seed);
            sampler.limit_moves(moves.next_share());
        }
    }

    /// Offers the children of `matrix` to `sink`, charging the moves made to `moves`.
    fn generate<Sink: ChildSink<T>>(
        &mut self,
        matrix: &AssociationMatrix<T, N, Z>,
        sink: &mut Sink,
        moves: &mut ParentMoves,
    ) -> Result<(), StepError> {
        let result = match self {
            Generator::Exhaustive(exhaustive) => exhaustive.generate(matrix, sink),
            Generator::Sampled(sampled) => {
                let before = sampled.chain().steps_taken();
                let result = sampled.generate(matrix, sink);
                moves.charge(sampled.chain().steps_taken() - before);
                result
            }
        };
        result.map(|_| ()).map_err(|error| match error {
            GenerateError::BudgetExceeded { budget } => StepError::ChildBudgetExceeded { budget },
        })
    }
}

/// The children one sampled generator run offered (at most `C`: it offers its best `C`).
#[derive(Debug, Clone)]
struct OfferedChildren<T, const C: usize, const Z: usize> {
    scores: [T; C],
    assignments: [[u16; Z]; C],
    rows: [u16; C],
    len: usize,
}

impl<T: Real, const C: usize, const Z: usize> OfferedChildren<T, C, Z> {
    const fn new() -> Self {
        Self { scores: [T::NEG_INFINITY; C], assignments: [[CLUTTER; Z]; C], rows: [0; C], len: 0 }
    }

    fn clear(&mut self) {
        self.len = 0;
    }

    fn push(&mut self, score: T, assignment: &[u16]) {
        // A sampled generator offers at most C children per matrix, so there is always room.
        debug_assert!(self.len < C, "more than C children offered by one sampled generator run");
        if self.len < C {
            *self.scores.at_mut(self.len) = score;
            copy_prefix(self.assignments.at_mut(self.len), assignment);
            *self.rows.at_mut(self.len) = assignment.len().min(Z) as u16;
            self.len += 1;
        }
    }

    /// The recorded children as (log-weight, assignment over `rows` rows).
    fn iter(&self, rows: usize) -> impl Iterator<Item = (T, &[u16])> + '_ {
        let rows = rows.min(Z);
        self.scores
            .iter()
            .zip(&self.assignments)
            .take(self.len.min(C))
            .map(move |(&score, assignment)| (score, &assignment[..rows]))
    }
}

/// A sink that passes children on to `inner` and records those with non-zero weight.
struct Recording<'a, Inner, T, const C: usize, const Z: usize> {
    inner: Inner,
    record: &'a mut OfferedChildren<T, C, Z>,
}

impl<Inner: ChildSink<T>, T: Real, const C: usize, const Z: usize> ChildSink<T> for Recording<'_, Inner, T, C, Z> {
    fn offer(&mut self, log_weight: T, assignment: &[u16]) {
        self.inner.offer(log_weight, assignment);
        if log_weight > T::NEG_INFINITY {
            self.record.push(log_weight, assignment);
        }
    }

    fn unoffered(&mut self, log_mass: T) {
        self.inner.unoffered(log_mass);
    }
}

/// A scan's budget of Metropolis moves, shared among its parents in proportion to their weights
/// (docs/maths.md §7.9). `u64::MAX` is no budget: every chain makes its configured moves.
struct MoveBudget {
    total: u64,
    left: u64,
}

impl MoveBudget {
    fn new(total: u64) -> Self {
        Self { total, left: total }
    }

    /// The moves of a parent of log-weight `log_weight` with `events` events: ⌊total · w⌋, and never more
    /// than the scan has left.
    fn parent_share<T: Real>(&self, log_weight: T, events: usize) -> ParentMoves {
        let share = if self.total == u64::MAX {
            u64::MAX
        } else {
            let exact = self.total as f64 * exp(log_weight).as_f64();
            // `as` saturates (and maps NaN to 0); the `min` keeps the scan within its budget.
            (exact as u64).min(self.left)
        };
        ParentMoves { left: share, events_left: events.max(1) as u64, used: 0 }
    }

    fn spend(&mut self, moves: u64) {
        if self.total != u64::MAX {
            self.left -= moves.min(self.left);
        }
    }
}

/// One parent's moves, shared among its events in turn: each event gets an equal part of what the events
/// before it left.
struct ParentMoves {
    left: u64,
    events_left: u64,
    used: u64,
}

impl ParentMoves {
    /// The next event's share.
    fn next_share(&self) -> u64 {
        if self.left == u64::MAX { u64::MAX } else { self.left / self.events_left.max(1) }
    }

    /// Records the moves the last event made.
    fn charge(&mut self, moves: u64) {
        self.used += moves;
        if self.left != u64::MAX {
            self.left -= moves.min(self.left);
        }
        self.events_left = self.events_left.saturating_sub(1);
    }

    fn used(&self) -> u64 {
        self.used
    }
}
