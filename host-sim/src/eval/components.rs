//! Scoring a whole catalogue at once: the true objects and the estimates split into *components*, the
//! connected groups of the pairs closer than a cut-off c, so that GOSPA (α = 2) over thousands of objects is
//! the sum of small assignment problems instead of one of size N³.
//!
//! Why it is exact: in GOSPA a pair at distance ≥ c costs c^p = c^p/2 + c^p/2, what leaving both unassigned
//! costs, so some optimal assignment pairs only objects and estimates closer than c; those pairs lie inside
//! one component, and the components' problems share nothing: d^p = Σ over components of d_component^p.
//! Anything computed from pairs closer than a bound b ≤ c (GOSPA with cut-off b, "within b of a true
//! object") also stays inside the components of c.
//!
//! The pairs are found on a grid of cells of side c, so the cost grows with the objects and estimates and
//! with the pairs closer than c, not with their product.

use crate::eval::metrics::gospa;
use std::collections::HashMap;

/// One component: indices into the true objects and into the estimates, each in increasing order.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Component {
    /// True objects.
    pub truth: Vec<usize>,
    /// Estimates.
    pub estimates: Vec<usize>,
}

fn distance<const P: usize>(a: &[f64; P], b: &[f64; P]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum::<f64>().sqrt()
}

fn cell<const P: usize>(position: &[f64; P], size: f64) -> [i64; P] {
    core::array::from_fn(|i| (position[i] / size).floor() as i64)
}

fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// The components of `truth` and `estimates` under the pairs closer than `cutoff` (> 0), in the order of
/// their first member (true objects numbered before estimates); every object and estimate is in exactly
/// one. A non-finite position is alone in its component.
pub fn components<const P: usize>(truth: &[[f64; P]], estimates: &[[f64; P]], cutoff: f64) -> Vec<Component> {
    let n = truth.len();
    let mut parent: Vec<usize> = (0..n + estimates.len()).collect();
    if cutoff > 0.0 && cutoff.is_finite() {
        let mut grid: HashMap<[i64; P], Vec<usize>> = HashMap::new();
        for (i, p) in truth.iter().enumerate().filter(|(_, p)| p.iter().all(|x| x.is_finite())) {
            grid.entry(cell(p, cutoff)).or_default().push(i);
        }
        for (j, e) in estimates.iter().enumerate().filter(|(_, e)| e.iter().all(|x| x.is_finite())) {
            let c = cell(e, cutoff);
            for k in 0..3usize.pow(P as u32) {
                let near: [i64; P] = core::array::from_fn(|d| c[d] + (k / 3usize.pow(d as u32) % 3) as i64 - 1);
                for &i in grid.get(&near).map_or(&[][..], Vec::as_slice) {
                    if distance(&truth[i], e) < cutoff {
                        let (a, b) = (find(&mut parent, i), find(&mut parent, n + j));
                        parent[a.max(b)] = a.min(b);
                    }
                }
            }
        }
    }
    let mut index_of_root: HashMap<usize, usize> = HashMap::new();
    let mut out: Vec<Component> = vec![];
    for node in 0..parent.len() {
        let root = find(&mut parent, node);
        let k = *index_of_root.entry(root).or_insert_with(|| {
            out.push(Component::default());
            out.len() - 1
        });
        if node < n { out[k].truth.push(node) } else { out[k].estimates.push(node - n) }
    }
    out
}

/// GOSPA (α = 2, cut-off `c`, order `p`) of `truth` and `estimates`, component by component
/// ([`crate::eval::metrics::gospa`] on each): the same distance as one [`gospa`] over the whole sets.
pub fn gospa_by_components<const P: usize>(truth: &[[f64; P]], estimates: &[[f64; P]], c: f64, p: f64) -> f64 {
    let sum: f64 = components(truth, estimates, c)
        .iter()
        .map(|k| {
            let t: Vec<[f64; P]> = k.truth.iter().map(|&i| truth[i]).collect();
            let e: Vec<[f64; P]> = k.estimates.iter().map(|&j| estimates[j]).collect();
            gospa(&t, &e, c, p).distance.powf(p)
        })
        .sum();
    sum.powf(1.0 / p)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::rng::{Random, Stream};

    #[test]
    fn the_components_give_the_whole_sets_gospa() {
        let mut random = Random::stream(7, Stream::Scenario, 0);
        for (objects, tracks, spread) in [(40, 35, 60.0), (60, 70, 150.0), (25, 0, 50.0), (0, 12, 50.0)] {
            let truth: Vec<[f64; 3]> =
                (0..objects).map(|_| [0.0; 3].map(|_: f64| random.between(-spread, spread))).collect();
            // Estimates near some objects, and a few anywhere.
            let estimates: Vec<[f64; 3]> = (0..tracks)
                .map(|j| match truth.get(j) {
                    Some(t) if j % 4 != 0 => t.map(|x| x + random.between(-8.0, 8.0)),
                    _ => [0.0; 3].map(|_: f64| random.between(-spread, spread)),
                })
                .collect();
            for (c, p) in [(10.0, 2.0), (25.0, 1.0)] {
                let whole = gospa(&truth, &estimates, c, p).distance;
                let parts = gospa_by_components(&truth, &estimates, c, p);
                assert!((whole - parts).abs() <= 1e-9 * whole.max(1.0), "{objects} {tracks}: {whole} vs {parts}");
            }
            let parts = components(&truth, &estimates, 10.0);
            assert_eq!(parts.iter().map(|k| k.truth.len()).sum::<usize>(), objects);
            assert_eq!(parts.iter().map(|k| k.estimates.len()).sum::<usize>(), tracks);
        }
    }

    #[test]
    fn pairs_closer_than_the_cut_off_join_and_others_stay_apart() {
        let truth = [[0.0, 0.0], [100.0, 0.0], [9.0, 0.0]];
        let estimates = [[5.0, 0.0], [200.0, 0.0], [f64::NAN, 0.0]];
        let parts = components(&truth, &estimates, 6.0);
        // Object 0 and 2 are both within 6 of estimate 0 (through it, one component).
        assert_eq!(parts[0], Component { truth: vec![0, 2], estimates: vec![0] });
        assert_eq!(parts[1], Component { truth: vec![1], estimates: vec![] });
        assert_eq!(parts[2], Component { truth: vec![], estimates: vec![1] });
        assert_eq!(parts[3], Component { truth: vec![], estimates: vec![2] });
    }
}
