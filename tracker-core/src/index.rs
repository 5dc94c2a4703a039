//! Indexing without a panic path, for the panic-freedom proof (see [`crate::tracker`], "Panics").
//!
//! The tracker's indices come from its own tables (slots, columns and rows stored as `u16`), so their
//! bounds are invariants the optimiser cannot see, and a plain `array[i]` would keep a call to the panic
//! handler. Three patterns remove it:
//!
//! - [`below`] turns a table entry into `Option<usize>` (the markers `CLUTTER` and `NONE` are `u16::MAX`,
//!   never an index): one comparison, which both tells a marker from an index and proves the index in
//!   bounds for every later use. The hot loops (sampler step, exhaustive enumeration, selection) use it,
//!   or iterate over slices, so they carry no more checks than before.
//! - [`At`] clamps an index to the array (`min`), where a check is rare enough not to matter. An index out
//!   of bounds is a logic error: debug builds assert that the clamp never changes it.
//! - Sizes are returned clamped to the capacity (`len().min(N)`), so loops up to them index in bounds.
//!
//! Arrays whose length may be zero (the birth-cell arrays, `B = 0`) use `get`.

/// The "no index" marker of the index tables ("no slot", "no row", "missed"); the same value as
/// [`crate::association::CLUTTER`], so [`below`] tells both from an index.
pub(crate) const NONE: u16 = u16::MAX;

/// Indexing of a fixed-size array of non-zero length without a panic path.
pub(crate) trait At<X> {
    /// The element at `index`, which must be in bounds (debug builds assert it; release builds clamp it).
    fn at(&self, index: usize) -> &X;
    /// The element at `index`, mutably; as [`At::at`].
    fn at_mut(&mut self, index: usize) -> &mut X;
    /// Swaps the elements at `a` and `b`; as [`At::at`].
    fn swap_at(&mut self, a: usize, b: usize);
}

impl<X, const L: usize> At<X> for [X; L] {
    #[inline(always)]
    fn at(&self, index: usize) -> &X {
        &self[clamp(index, L)]
    }

    #[inline(always)]
    fn at_mut(&mut self, index: usize) -> &mut X {
        &mut self[clamp(index, L)]
    }

    #[inline(always)]
    fn swap_at(&mut self, a: usize, b: usize) {
        self.swap(clamp(a, L), clamp(b, L));
    }
}

/// `index` clamped to `0..len` (`len > 0`).
#[inline(always)]
fn clamp(index: usize, len: usize) -> usize {
    debug_assert!(index < len, "index {index} out of bounds 0..{len}");
    index.min(len.saturating_sub(1))
}

/// `value` as an index below `L`, or `None` (for the markers `CLUTTER` and `NONE`, `u16::MAX`).
#[inline(always)]
pub(crate) fn below<const L: usize>(value: u16) -> Option<usize> {
    let index = usize::from(value);
    (index < L).then_some(index)
}

/// Copies the common prefix of `source` into `target` (`copy_from_slice` without its length check).
#[inline(always)]
pub(crate) fn copy_prefix<X: Copy>(target: &mut [X], source: &[X]) {
    let len = target.len().min(source.len());
    debug_assert_eq!(len, source.len(), "source longer than target");
    target[..len].copy_from_slice(&source[..len]);
}

/// Stable insertion sort by `less`. For the tracker's short lists (at most H, N or C items), where every
/// comparison is a total order, so the result is the same as any other sort's.
#[inline]
pub(crate) fn insertion_sort_by<X>(items: &mut [X], mut less: impl FnMut(&X, &X) -> bool) {
    for i in 1..items.len() {
        let mut j = i;
        while j > 0 && less(&items[j], &items[j - 1]) {
            items.swap(j, j - 1);
            j -= 1;
        }
    }
}

/// A binary heap of up to `C` item indices with the **worst** item at the root, under an order the caller
/// passes to each operation (the items live in the caller's arrays). The scan's selection and a chain's
/// best children both keep their best items and evict the worst.
#[derive(Debug, Clone)]
pub(crate) struct WorstFirstHeap<const C: usize> {
    heap: [u16; C],
    len: usize,
}

impl<const C: usize> WorstFirstHeap<C> {
    /// An empty heap (usable in a `const` context).
    pub(crate) const fn new() -> Self {
        Self { heap: [0; C], len: 0 }
    }

    /// Number of items (at most `C`).
    #[inline]
    pub(crate) fn len(&self) -> usize {
        // The `min` only shows the optimiser the invariant `len ≤ C`.
        self.len.min(C)
    }

    /// Removes every item.
    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }

    /// Whether the heap holds `C` items.
    #[inline]
    pub(crate) fn is_full(&self) -> bool {
        self.len >= C
    }

    /// The worst item (`None` when empty).
    #[inline]
    pub(crate) fn root(&self) -> Option<u16> {
        if self.len > 0 { self.heap.first().copied() } else { None }
    }

    /// Adds `item` (the caller has written it) when there is room. `worse(a, b)`: item `a` ranks below `b`.
    #[inline]
    pub(crate) fn push(&mut self, item: u16, worse: impl Fn(u16, u16) -> bool) {
        let Some(entry) = self.heap.get_mut(self.len) else { return };
        *entry = item;
        self.len += 1;
        let mut at = self.len - 1;
        while at > 0 {
            let parent = (at - 1) / 2;
            if !worse(*self.heap.at(at), *self.heap.at(parent)) {
                return;
            }
            self.heap.swap_at(at, parent);
            at = parent;
        }
    }

    /// Restores the order after the caller replaced the root's item with a better one.
    #[inline]
    pub(crate) fn root_replaced(&mut self, worse: impl Fn(u16, u16) -> bool) {
        let mut at = 0;
        // Each pass moves one level down: at most log2(C) + 1 passes.
        loop {
            let (left, right) = (2 * at + 1, 2 * at + 2);
            let mut worst = at;
            if left < self.len && worse(*self.heap.at(left), *self.heap.at(worst)) {
                worst = left;
            }
            if right < self.len && worse(*self.heap.at(right), *self.heap.at(worst)) {
                worst = right;
            }
            if worst == at {
                return;
            }
            self.heap.swap_at(at, worst);
            at = worst;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn insertion_sort_is_stable_and_sorted() {
        let mut items = [(3, 'a'), (1, 'b'), (3, 'c'), (0, 'd'), (1, 'e')];
        insertion_sort_by(&mut items, |a, b| a.0 < b.0);
        assert_eq!(items, [(0, 'd'), (1, 'b'), (1, 'e'), (3, 'a'), (3, 'c')]);
    }

    #[test]
    fn copy_prefix_copies_the_source() {
        let mut target = [0u16; 4];
        copy_prefix(&mut target, &[7, 8]);
        assert_eq!(target, [7, 8, 0, 0]);
    }

    #[test]
    fn below_tells_indices_from_markers() {
        assert_eq!(below::<4>(3), Some(3));
        assert_eq!(below::<4>(u16::MAX), None);
    }

    #[test]
    fn worst_first_heap_keeps_the_worst_item_at_the_root() {
        let values = [5, 3, 9, 1, 7, 4];
        let mut heap = WorstFirstHeap::<4>::new();
        let mut items = [0; 4];
        let worse = |items: &[i32; 4], a: u16, b: u16| items[a as usize] < items[b as usize];
        for &value in &values {
            if !heap.is_full() {
                let item = heap.len();
                items[item] = value;
                let snapshot = items;
                heap.push(item as u16, |a, b| worse(&snapshot, a, b));
            } else if let Some(root) = heap.root()
                && value > items[root as usize]
            {
                items[root as usize] = value;
                let snapshot = items;
                heap.root_replaced(|a, b| worse(&snapshot, a, b));
            }
        }
        // The best four of the values are kept and the worst of them is at the root.
        let mut kept = items;
        kept.sort();
        assert_eq!(kept, [4, 5, 7, 9]);
        assert_eq!(items[heap.root().unwrap() as usize], 4);
    }

    #[test]
    fn clamped_indexing_reads_in_bounds_indices() {
        let mut a = [1, 2, 3];
        assert_eq!(*a.at(2), 3);
        *a.at_mut(0) = 9;
        a.swap_at(0, 1);
        assert_eq!(a, [2, 9, 3]);
    }
}
