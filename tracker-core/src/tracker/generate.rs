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
    /// Objects in the field of view: the no-event matrix's object columns.
    in_view: usize,
    rows: usize,
    /// Independent-birth cells left out of its matrices because a child would exceed `N` objects.
    births_skipped: u64,
}

/// What every parent's children need to know about the scan (read-only).
struct ScanInputs<'a, T: Real, const S: usize, const D: usize, const Z: usize, const K: usize, const B: usize> {
    weight_model: &'a WeightModel<T>,
    birth_cells: &'a BirthCells<T, S, D, B>,
    scores: &'a Scores<T, S, D, Z, K, B>,
    rows: usize,
    scan_seed: u64,
    /// Whether death children are derived from the no-event children (sampled, p_D < 1).
    derive_deaths: bool,
    /// Birth cells in use (0 when births are impossible).
    birth_cell_count: usize,
}

impl<T: Real, const S: usize, const D: usize, const Z: usize, const K: usize, const B: usize>
    ScanInputs<'_, T, S, D, Z, K, B>
{
    /// The seed of the chain of (`parent`, `event`).
    fn seed(&self, parent: &Parent<T>, event: Event) -> u64 {
        chain_seed(self.scan_seed, parent.index, event_code::<B>(event))
    }
}

/// The scratch one parent's children are generated in.
struct ParentScratch<'a, T, const H: usize, const N: usize, const Z: usize> {
    objects: &'a mut AssociationMatrix<T, N, Z>,
    event: &'a mut AssociationMatrix<T, N, Z>,
    columns: &'a mut ParentColumns<N>,
    top: &'a mut TopChildren<T, H, Z>,
    no_event_children: &'a mut OfferedChildren<T, H, Z>,
}

impl<T: Real> Parent<T> {
    /// Builds the no-event matrix and column layout of parent `index` into `scratch`.
    fn new<
        const S: usize,
        const D: usize,
        const H: usize,
        const N: usize,
        const Z: usize,
        const K: usize,
        const B: usize,
    >(
        scratch: &mut ParentScratch<'_, T, H, N, Z>,
        scan: &ScanInputs<'_, T, S, D, Z, K, B>,
        index: usize,
        hypothesis: &Hypothesis<T, N>,
    ) -> Self {
        build_no_event_matrix(scratch.objects, scratch.columns, hypothesis, scan.scores, scan.rows, scan.weight_model);
        let in_view = scratch.objects.columns();
        let births_skipped = if scan.weight_model.independent_births() {
            push_birth_columns(scratch.objects, scratch.columns, scan, N.saturating_sub(hypothesis.len()))
        } else {
            0
        };
        Parent { index: index as u16, log_weight: hypothesis.log_weight, in_view, rows: scan.rows, births_skipped }
    }

    /// The number of the parent's events that get a matrix (no event, births, deaths not derived).
    fn events<const S: usize, const D: usize, const N: usize, const Z: usize, const K: usize, const B: usize>(
        &self,
        scan: &ScanInputs<'_, T, S, D, Z, K, B>,
        hypothesis: &Hypothesis<T, N>,
    ) -> usize {
        let births = if hypothesis.len() >= N || scan.weight_model.independent_births() {
            0
        } else {
            let cells = scan.birth_cells.in_field_of_view.iter().take(scan.birth_cell_count);
            cells.filter(|&&detectable| detectable || !scan.weight_model.birth_required()).count()
        };
        let deaths = if scan.weight_model.deaths_possible() && !scan.derive_deaths { self.in_view } else { 0 };
        1 + births + deaths
    }
}

/// The children of the parent's no-event matrix, and the death children derived from them.
fn offer_no_event<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    scratch: &mut ParentScratch<'_, T, H, N, Z>,
    generator: &mut Generator<'_, T, N, Z, H>,
    scan: &ScanInputs<'_, T, S, D, Z, K, B>,
    parent: &Parent<T>,
    moves: &mut ParentMoves,
) -> Result<(), StepError> {
    set_baseline(scratch.objects, scan.weight_model, parent, Event::None, parent.in_view);
    generator.prepare(scan.seed(parent, Event::None), moves);
    let mut sink = scratch.top.for_event(parent.index, Event::None);
    if !scan.derive_deaths {
        return generator.generate(scratch.objects, &mut sink, moves);
    }
    scratch.no_event_children.clear();
    let mut recording = Recording { inner: &mut sink, record: scratch.no_event_children };
    generator.generate(scratch.objects, &mut recording, moves)?;
    derive_death_children(scratch.top, scan.weight_model, parent, scratch.columns, scratch.no_event_children);
    Ok(())
}

/// One birth in a cell (α each): the no-event matrix with the cell's column when the sensor can see it.
fn offer_births<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    scratch: &mut ParentScratch<'_, T, H, N, Z>,
    generator: &mut Generator<'_, T, N, Z, H>,
    scan: &ScanInputs<'_, T, S, D, Z, K, B>,
    parent: &Parent<T>,
    moves: &mut ParentMoves,
) -> Result<(), StepError> {
    let required = scan.weight_model.birth_required();
    for cell in 0..scan.birth_cell_count {
        let Some(detectable) = scan.birth_cells.in_field_of_view(cell) else { break };
        if !detectable && required {
            continue; // a birth that must be detected where it cannot be
        }
        scratch.event.copy_from(scratch.objects, None);
        if let (true, Some(entries)) = (detectable, scan.scores.birth_entries(cell, scan.rows)) {
            // The parent holds fewer than N objects, so the matrix has room.
            let _ = scratch.event.push_column(entries, required);
        }
        let birth = Event::Birth { cell: cell as u16 };
        set_baseline(scratch.event, scan.weight_model, parent, birth, parent.in_view + usize::from(detectable));
        generator.prepare(scan.seed(parent, birth), moves);
        generator.generate(scratch.event, &mut scratch.top.for_event(parent.index, birth), moves)?;
    }
    Ok(())
}

/// One death among the objects in the field of view (β each), each by its own matrix.
fn offer_deaths<
    T: Real,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    scratch: &mut ParentScratch<'_, T, H, N, Z>,
    generator: &mut Generator<'_, T, N, Z, H>,
    scan: &ScanInputs<'_, T, S, D, Z, K, B>,
    parent: &Parent<T>,
    moves: &mut ParentMoves,
) -> Result<(), StepError> {
    for (column, &position) in scratch.columns.positions().iter().enumerate() {
        scratch.event.copy_from(scratch.objects, Some(column));
        let death = Event::Death { object: position };
        set_baseline(scratch.event, scan.weight_model, parent, death, parent.in_view - 1);
        generator.prepare(scan.seed(parent, death), moves);
        generator.generate(scratch.event, &mut scratch.top.for_event(parent.index, death), moves)?;
    }
    Ok(())
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
        birth_cells: &BirthCells<T, S, D, B>,
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
        let birth_cell_count = if weight_model.births_possible() { birth_cells.count } else { 0 };
        match config.selection {
            Selection::TopWeight | Selection::TopWeightWithin { .. } => top.clear(),
            Selection::SampledByWeight => top.clear_sampling(selection_seed(scan_seed)),
        }
        let scan = ScanInputs { weight_model, birth_cells, scores, rows, scan_seed, derive_deaths, birth_cell_count };
        let mut births_skipped = 0u64;
        let mut scan_moves = MoveBudget::new(max_moves);
        for ((index, hypothesis), columns) in parents.iter().enumerate().zip(columns.iter_mut()) {
            let mut scratch = ParentScratch { objects, event, columns, top, no_event_children };
            let parent = Parent::new(&mut scratch, &scan, index, hypothesis);
            let mut moves = scan_moves.parent_share(hypothesis.log_weight, parent.events(&scan, hypothesis));
            offer_no_event(&mut scratch, &mut generator, &scan, &parent, &mut moves)?;
            if weight_model.independent_births() {
                births_skipped += parent.births_skipped;
            } else if hypothesis.len() >= N {
                births_skipped += birth_cell_count as u64;
            } else {
                offer_births(&mut scratch, &mut generator, &scan, &parent, &mut moves)?;
            }
            if weight_model.deaths_possible() && !derive_deaths {
                offer_deaths(&mut scratch, &mut generator, &scan, &parent, &mut moves)?;
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
    pub(super) fn layout<const S: usize, const D: usize, const B: usize>(
        &self,
        parent: u16,
        event: Event,
        birth_cells: &BirthCells<T, S, D, B>,
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
            // In place: a new generator would pass through the stack (about 30 KB at `ssa_caps`).
            self.clustered.configure(sampler);
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

/// Independent births (docs/maths.md §5.6): appends a column for each birth cell that some measurement may
/// take, at most `room` of them (a child holds at most `N` objects); returns how many such cells found no
/// room. A cell no measurement can take is born in no child with non-zero weight and needs no column.
fn push_birth_columns<
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
    scan: &ScanInputs<'_, T, S, D, Z, K, B>,
    room: usize,
) -> u64 {
    let mut skipped = 0u64;
    let mut added = 0usize;
    for cell in 0..scan.birth_cell_count.min(B) {
        let Some(entries) = scan.scores.birth_entries(cell, scan.rows) else { break };
        if !entries.iter().any(|&entry| entry > T::NEG_INFINITY) {
            continue;
        }
        if added >= room || columns.push_birth(cell as u16).is_err() {
            skipped += 1;
            continue;
        }
        // `push_birth` succeeded, so the matrix (same width) has room too.
        let _ = matrix.push_column(entries, false);
        added += 1;
    }
    skipped
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
    len: usize,
}

impl<T: Real, const C: usize, const Z: usize> OfferedChildren<T, C, Z> {
    const fn new() -> Self {
        Self { scores: [T::NEG_INFINITY; C], assignments: [[CLUTTER; Z]; C], len: 0 }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::BirthDetection;
    use crate::sensor::{Region, Sensor};

    #[test]
    fn move_budget_shares_never_exceed_the_scan_budget() {
        for total in [0u64, 1, 7, 999, 1_000_000] {
            let mut budget = MoveBudget::new(total);
            let mut spent = 0;
            // Weights that sum to a little more than 1 in floating point.
            for weight in [0.5f64, 0.3, 0.2 + 1e-15] {
                let mut moves = budget.parent_share(weight.ln(), 3);
                for _ in 0..3 {
                    let share = moves.next_share();
                    moves.charge(share); // every event uses all it is given
                }
                assert!(moves.used() <= (total as f64 * weight) as u64 + 1);
                spent += moves.used();
                budget.spend(moves.used());
            }
            assert!(spent <= total, "{spent} > {total}");
        }
        let unlimited = MoveBudget::new(u64::MAX).parent_share(0.5f64.ln(), 4);
        assert_eq!(unlimited.next_share(), u64::MAX);
    }

    #[test]
    fn event_codes_are_distinct() {
        let mut codes = std::vec![event_code::<4>(Event::None)];
        codes.extend((0..4).map(|cell| event_code::<4>(Event::Birth { cell })));
        codes.extend((0..64).map(|object| event_code::<4>(Event::Death { object })));
        let distinct: std::collections::BTreeSet<_> = codes.iter().collect();
        assert_eq!(distinct.len(), codes.len());
    }

    #[test]
    fn death_children_are_derived_with_the_exact_ratio_for_each_free_object() {
        let sensor = Sensor {
            detection_probability: 0.8,
            clutter_rate: 2.0,
            field_of_view: Region::Everywhere { volume: 100.0 },
        };
        let model = WeightModel::new(&sensor, None, 0.0, 0, BirthDetection::AllDetected, 0.05);
        let mut columns = ParentColumns::<4>::new();
        for position in [0, 2, 3] {
            columns.push(position).unwrap();
        }
        let parent = Parent { index: 1, log_weight: 0.0, in_view: 3, rows: 2, births_skipped: 0 };
        let mut recorded = OfferedChildren::<f64, 8, 2>::new();
        recorded.push(-3.0, &[1, CLUTTER]); // takes column 1 (position 2): positions 0 and 3 may die
        let mut top = TopChildren::<f64, 8, 2>::new();
        derive_death_children(&mut top, &model, &parent, &columns, &recorded);
        // ln r = ln β − ln P(no event) − ln(1 − p_D), P(no event) = 1 − 3 β.
        let ratio = 0.05f64.ln() - (1.0 - 3.0 * 0.05f64).ln() - 0.2f64.ln();
        let mut deaths: std::vec::Vec<_> = top.kept().iter().map(|c| (c.event, c.parent, c.log_weight)).collect();
        deaths.sort_by_key(|d| match d.0 {
            Event::Death { object } => object,
            _ => u16::MAX,
        });
        assert_eq!(deaths.len(), 2);
        for ((event, parent_index, weight), object) in deaths.into_iter().zip([0, 3]) {
            assert_eq!(event, Event::Death { object });
            assert_eq!(parent_index, 1);
            assert!((weight - (-3.0 + ratio)).abs() < 1e-12);
        }
    }
}
