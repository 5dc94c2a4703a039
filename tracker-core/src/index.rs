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
    fn clamped_indexing_reads_in_bounds_indices() {
        let mut a = [1, 2, 3];
        assert_eq!(*a.at(2), 3);
        *a.at_mut(0) = 9;
        a.swap_at(0, 1);
        assert_eq!(a, [2, 9, 3]);
    }
}
