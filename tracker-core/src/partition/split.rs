//! Splitting a cluster whose hypotheses factor into independent groups of labels (docs/maths.md §13.4),
//! in fixed memory: candidate groups from pairwise dependence of the labels' slots, then the whole
//! factorisation checked by the total variation between the cluster's hypotheses and the product of the
//! groups' marginals. The host's partition does the same with maps; every sum here is taken in the same
//! order (hypotheses best first), so both decide alike and give the same groups bit for bit.

use super::rest::ClusterRest;
use crate::index::insertion_sort_by;
use crate::real::Real;
use core::cmp::Ordering;

/// The tolerance of an exact split: dependence and total variation below it are rounding.
pub const EXACT: f64 = 1e-12;

/// No slot: the hypothesis does not hold the label.
const ABSENT: u16 = u16::MAX;

/// A cluster's factorisation: for each track slot, the group of its label (groups numbered 0, 1, ... in
/// the order of their smallest label), how many groups, and the total variation moved (0 when exact).
pub(super) struct Factors<T, const K: usize> {
    pub group_of_slot: [u16; K],
    pub groups: u16,
    pub moved: T,
}

/// The distinct labels of `rest`'s tracks, sorted, and each slot's column among them.
fn columns<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    rest: &ClusterRest<T, S, N, H, K>,
) -> (heapless::Vec<u32, K>, [u16; K]) {
    let mut labels = heapless::Vec::<u32, K>::new();
    for t in rest.tracks() {
        if !labels.contains(&t.label.0) {
            // At most K tracks, so at most K labels.
            let _ = labels.push(t.label.0);
        }
    }
    insertion_sort_by(&mut labels, |a, b| a < b);
    let mut column = [ABSENT; K];
    for (column, t) in column.iter_mut().zip(rest.tracks()) {
        *column = labels.iter().position(|&l| l == t.label.0).map_or(ABSENT, |c| c as u16);
    }
    (labels, column)
}

/// The factorisation of `rest` within total variation `epsilon` (at least [`EXACT`]), or `None` when it has
/// fewer than two labels or does not factor.
pub(super) fn factor<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    rest: &ClusterRest<T, S, N, H, K>,
    epsilon: T,
) -> Option<Factors<T, K>> {
    let (labels, column) = columns(rest);
    if labels.len() < 2 {
        return None;
    }
    let tolerance = epsilon.max(T::of_f64(EXACT));
    let rows = rest.hypotheses().len();
    let value = |row: usize, c: usize| {
        let of = |s: &u16| column.get(usize::from(*s)) == Some(&(c as u16));
        rest.slots(row).iter().copied().find(of).unwrap_or(ABSENT)
    };
    // Union of dependent columns, each group named by its smallest column.
    let count = labels.len().min(K);
    let mut group = [0u16; K];
    for (c, g) in group.iter_mut().enumerate().take(count) {
        *g = c as u16;
    }
    for a in 0..count {
        for b in a + 1..count {
            let (ga, gb) = (group.get(a).copied().unwrap_or(0), group.get(b).copied().unwrap_or(0));
            if ga != gb && dependent(rest, rows, |r| value(r, a), |r| value(r, b), tolerance) {
                let (from, to) = (ga.max(gb), ga.min(gb));
                group.iter_mut().take(count).filter(|g| **g == from).for_each(|g| *g = to);
            }
        }
    }
    // Groups renumbered 0, 1, ... by their smallest column.
    let mut number = [ABSENT; K];
    let mut groups = 0u16;
    for (c, (number, &g)) in number.iter_mut().zip(&group).enumerate().take(count) {
        if usize::from(g) == c {
            *number = groups;
            groups += 1;
        }
    }
    if groups < 2 {
        return None;
    }
    let mut group_of_slot = [ABSENT; K];
    for (of_slot, &c) in group_of_slot.iter_mut().zip(&column).take(rest.tracks().len()) {
        let root = group.get(usize::from(c)).copied().unwrap_or(ABSENT);
        *of_slot = number.get(usize::from(root)).copied().unwrap_or(ABSENT);
    }
    let factors = Factors { group_of_slot, groups, moved: T::zero() };
    let moved = moved(rest, &factors);
    if moved > tolerance {
        return None;
    }
    Some(Factors { moved: if moved <= T::of_f64(EXACT) { T::zero() } else { moved }, ..factors })
}

/// Whether two labels (their slots in each hypothesis: `a(row)`, `b(row)`) are dependent: some joint
/// probability differs from the product of the marginals by more than `tolerance`.
fn dependent<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    rest: &ClusterRest<T, S, N, H, K>,
    rows: usize,
    a: impl Fn(usize) -> u16,
    b: impl Fn(usize) -> u16,
    tolerance: T,
) -> bool {
    // Each sum runs over the hypotheses in order, from zero, as the host's maps accumulate.
    let total = |matches: &dyn Fn(usize) -> bool| {
        (0..rows).filter(|&r| matches(r)).fold(T::zero(), |sum, r| sum + rest.weight(r))
    };
    let first = |r: usize, value: &dyn Fn(usize) -> u16| (0..r).all(|q| value(q) != value(r));
    (0..rows).filter(|&x| first(x, &a)).any(|x| {
        let wx = total(&|r| a(r) == a(x));
        (0..rows).filter(|&y| first(y, &b)).any(|y| {
            let wy = total(&|r| b(r) == b(y));
            let joint = total(&|r| a(r) == a(x) && b(r) == b(y));
            (joint - wx * wy).abs() > tolerance
        })
    })
}

/// Whether rows `p` and `q` hold the same slots in group `g`.
fn same_in_group<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    rest: &ClusterRest<T, S, N, H, K>,
    group_of_slot: &[u16],
    g: u16,
    p: usize,
    q: usize,
) -> bool {
    key_order(rest, group_of_slot, g, p, q) == Ordering::Equal
}

/// The order of rows `p` and `q` restricted to group `g`, as the host orders such keys: column by column
/// in label order, a label absent before any slot, slots by number.
fn key_order<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    rest: &ClusterRest<T, S, N, H, K>,
    group_of_slot: &[u16],
    g: u16,
    p: usize,
    q: usize,
) -> Ordering {
    let in_group = |s: &&u16| group_of_slot.get(usize::from(**s)) == Some(&g);
    let label = |s: u16| rest.track(s).map_or(0, |t| t.label.0);
    let mut left = rest.slots(p).iter().filter(in_group).copied();
    let mut right = rest.slots(q).iter().filter(in_group).copied();
    loop {
        match (left.next(), right.next()) {
            (None, None) => return Ordering::Equal,
            // The ended key is absent where the other holds a label.
            (None, Some(_)) => return Ordering::Less,
            (Some(_), None) => return Ordering::Greater,
            (Some(x), Some(y)) => match label(x).cmp(&label(y)) {
                // p holds the smaller label where q has none there.
                Ordering::Less => return Ordering::Greater,
                Ordering::Greater => return Ordering::Less,
                Ordering::Equal if x != y => return x.cmp(&y),
                Ordering::Equal => {}
            },
        }
    }
}

/// The marginal weight of row `row`'s slots in group `g`: the sum over the rows holding the same, in order.
fn marginal<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    rest: &ClusterRest<T, S, N, H, K>,
    group_of_slot: &[u16],
    g: u16,
    row: usize,
) -> T {
    (0..rest.hypotheses().len())
        .filter(|&r| same_in_group(rest, group_of_slot, g, r, row))
        .fold(T::zero(), |sum, r| sum + rest.weight(r))
}

/// The total variation between the cluster's hypotheses and the product of its groups' marginals: half of
/// Σ|p − q| plus the mass the product gives to hypotheses the cluster does not hold.
fn moved<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    rest: &ClusterRest<T, S, N, H, K>,
    factors: &Factors<T, K>,
) -> T {
    let (mut covered, mut difference) = (T::zero(), T::zero());
    for row in 0..rest.hypotheses().len() {
        let q =
            (0..factors.groups).fold(T::one(), |product, g| product * marginal(rest, &factors.group_of_slot, g, row));
        covered += q;
        difference += (rest.weight(row) - q).abs();
    }
    T::of_f64(0.5) * (difference + (T::one() - covered).max(T::zero()))
}

/// Group `g`'s marginal: one entry per distinct restriction of the hypotheses to the group (its weight and
/// the first hypothesis holding it), heaviest first, ties in the restriction's order.
pub(super) fn group_marginal<T: Real, const S: usize, const N: usize, const H: usize, const K: usize>(
    rest: &ClusterRest<T, S, N, H, K>,
    factors: &Factors<T, K>,
    g: u16,
) -> heapless::Vec<(T, u16), H> {
    let slots = &factors.group_of_slot;
    let mut entries = heapless::Vec::<(T, u16), H>::new();
    for row in 0..rest.hypotheses().len() {
        if (0..row).all(|r| !same_in_group(rest, slots, g, r, row)) {
            // At most one entry per hypothesis, so at most H.
            let _ = entries.push((marginal(rest, slots, g, row), row as u16));
        }
    }
    insertion_sort_by(&mut entries, |x, y| {
        key_order(rest, slots, g, usize::from(x.1), usize::from(y.1)) == Ordering::Less
    });
    insertion_sort_by(&mut entries, |x, y| x.0 > y.0);
    entries
}
