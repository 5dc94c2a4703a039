//! Splitting a cluster whose hypotheses factor into independent groups of labels (docs/maths.md §13.4):
//! candidate groups from pairwise dependence, then the whole factorisation checked by the total variation
//! between the cluster's hypotheses and the product of the groups' marginals.

use super::hypotheses::Hypothesis;
use std::collections::BTreeMap;
use tracker_core::model::{MeasurementModel, MotionModel};
use tracker_core::{PriorObject, Tracker};

/// A total variation at or below this is rounding: the hypotheses factor exactly.
pub const EXACT: f64 = 1e-12;

/// A cluster's factorisation: the groups' marginal hypothesis sets (heaviest first; groups in the order of
/// their smallest label) and the total variation between the cluster and their product (0 when exact).
#[derive(Debug, Clone, PartialEq)]
pub struct Factors<const S: usize> {
    pub groups: Vec<Vec<Hypothesis<S>>>,
    pub moved: f64,
}

/// Which track (store slot) of each label a hypothesis holds: `None` when it holds none.
type Key = Vec<Option<u16>>;

/// The factorisation of `core`'s hypotheses into two or more groups of labels whose product is within
/// total variation max(`epsilon`, [`EXACT`]) of them; `None` when they do not factor (or hold one label).
pub fn factor<
    M,
    G,
    const S: usize,
    const D: usize,
    const H: usize,
    const N: usize,
    const Z: usize,
    const K: usize,
    const B: usize,
>(
    core: &Tracker<f64, M, G, S, D, H, N, Z, K, B>,
    epsilon: f64,
) -> Option<Factors<S>>
where
    M: MotionModel<f64, S>,
    G: MeasurementModel<f64, S, D>,
{
    let tracks = core.tracks();
    let mut labels: Vec<u32> = tracks.iter().map(|t| t.label.0).collect();
    labels.sort_unstable();
    labels.dedup();
    if labels.len() < 2 {
        return None;
    }
    let column = |label: u32| labels.binary_search(&label).expect("a stored label");
    let rows: Vec<(f64, Key)> = core
        .hypotheses()
        .map(|h| {
            let mut key = vec![None; labels.len()];
            for (&slot, track) in h.slots().iter().zip(h.tracks()) {
                key[column(track.label.0)] = Some(slot);
            }
            (h.weight(), key)
        })
        .collect();
    let groups = dependent_groups(&rows, labels.len(), epsilon.max(EXACT));
    if groups.len() < 2 {
        return None;
    }
    let marginals: Vec<BTreeMap<Key, f64>> = groups.iter().map(|g| marginal(&rows, g)).collect();
    let mut covered = 0.0;
    let mut difference = 0.0;
    for (p, key) in &rows {
        let q: f64 = groups.iter().zip(&marginals).map(|(g, m)| m[&restrict(key, g)]).product();
        covered += q;
        difference += (p - q).abs();
    }
    let moved = 0.5 * (difference + (1.0 - covered).max(0.0));
    if moved > epsilon.max(EXACT) {
        return None;
    }
    let object = |slot: u16| {
        let t = &tracks[usize::from(slot)];
        PriorObject { label: t.label, state: t.state }
    };
    let sets = groups
        .iter()
        .zip(&marginals)
        .map(|(_, m)| {
            let mut set: Vec<Hypothesis<S>> = m
                .iter()
                .map(|(key, &weight)| Hypothesis {
                    weight,
                    objects: key.iter().flatten().map(|&s| object(s)).collect(),
                })
                .collect();
            set.iter_mut().for_each(|h| h.objects.sort_by_key(|o| o.label));
            set.sort_by(|a, b| b.weight.total_cmp(&a.weight));
            set
        })
        .collect();
    Some(Factors { groups: sets, moved: if moved <= EXACT { 0.0 } else { moved } })
}

/// `key` restricted to the label columns of `group` (the others `None`).
fn restrict(key: &Key, group: &[usize]) -> Key {
    let mut out = vec![None; key.len()];
    for &c in group {
        out[c] = key[c];
    }
    out
}

/// The marginal over the label columns of `group`: weight per restricted key.
fn marginal(rows: &[(f64, Key)], group: &[usize]) -> BTreeMap<Key, f64> {
    let mut m = BTreeMap::new();
    for (w, key) in rows {
        *m.entry(restrict(key, group)).or_insert(0.0) += w;
    }
    m
}

/// Groups of label columns joined when some pair's joint differs from the product of its marginals by more
/// than `tolerance` (each group in column order, groups in the order of their first column).
fn dependent_groups(rows: &[(f64, Key)], labels: usize, tolerance: f64) -> Vec<Vec<usize>> {
    let mut group: Vec<usize> = (0..labels).collect();
    for a in 0..labels {
        for b in a + 1..labels {
            if group[a] != group[b] && dependent(rows, a, b, tolerance) {
                let (from, to) = (group[a].max(group[b]), group[a].min(group[b]));
                group.iter_mut().filter(|g| **g == from).for_each(|g| *g = to);
            }
        }
    }
    let mut out: Vec<Vec<usize>> = vec![];
    for root in 0..labels {
        let members: Vec<usize> = (0..labels).filter(|&c| group[c] == root).collect();
        if !members.is_empty() {
            out.push(members);
        }
    }
    out
}

fn dependent(rows: &[(f64, Key)], a: usize, b: usize, tolerance: f64) -> bool {
    let mut joint: BTreeMap<(Option<u16>, Option<u16>), f64> = BTreeMap::new();
    let (mut pa, mut pb): (BTreeMap<Option<u16>, f64>, BTreeMap<Option<u16>, f64>) = Default::default();
    for (w, key) in rows {
        *joint.entry((key[a], key[b])).or_insert(0.0) += w;
        *pa.entry(key[a]).or_insert(0.0) += w;
        *pb.entry(key[b]).or_insert(0.0) += w;
    }
    pa.iter().any(|(x, wx)| {
        pb.iter().any(|(y, wy)| (joint.get(&(*x, *y)).copied().unwrap_or(0.0) - wx * wy).abs() > tolerance)
    })
}
