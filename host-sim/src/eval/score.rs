//! Scoring one scan's MAP estimates against the truth: GOSPA (α = 2, cut-off and order from the scenario's
//! `evaluation`), OSPA, the pairs GOSPA assigns (for label switches), and which estimates lie within the
//! error bound (GOSPA with cut-off `error_bound` assigns them to a true object).

use crate::eval::components::components;
use crate::eval::metrics::{gospa, ospa};
use crate::scenario::EvaluationSpec;

/// The scored estimates of one scan.
#[derive(Debug, Clone, PartialEq)]
pub struct Scored {
    /// GOSPA of the MAP estimates.
    pub gospa: f64,
    /// OSPA of the MAP estimates.
    pub ospa: f64,
    /// (truth id, label) pairs within the GOSPA cut-off.
    pub pairs: Vec<(u64, u32)>,
    /// Per MAP estimate: within the error bound.
    pub within_bound: Vec<bool>,
    /// Per true object, the MAP estimate GOSPA with cut-off `error_bound` assigns to it.
    pub bound_assignment: Vec<Option<usize>>,
}

/// Above this many (true object, estimate) pairs a scan is scored component by component
/// ([`score_by_components`]): 2,048 × 2,048, where one assignment over the whole sets begins to cost
/// seconds and a matrix of tens of megabytes.
pub const COMPONENTS_ABOVE_PAIRS: usize = 2048 * 2048;

/// Scores the MAP estimates `map` (label, position) against the true objects `truth` (id, position): over
/// the whole sets, or component by component above [`COMPONENTS_ABOVE_PAIRS`] (the same figures, exactly
/// but for the order of the sums).
pub fn score<const P: usize>(
    truth: &[(u64, [f64; P])],
    map: &[(u32, [f64; P])],
    evaluation: &EvaluationSpec,
) -> Scored {
    match truth.len().saturating_mul(map.len()) > COMPONENTS_ABOVE_PAIRS {
        true => score_by_components(truth, map, evaluation),
        false => score_whole(truth, map, evaluation),
    }
}

/// [`score`] with one assignment over the whole sets.
fn score_whole<const P: usize>(
    truth: &[(u64, [f64; P])],
    map: &[(u32, [f64; P])],
    evaluation: &EvaluationSpec,
) -> Scored {
    let points: Vec<[f64; P]> = truth.iter().map(|t| t.1).collect();
    let estimates: Vec<[f64; P]> = map.iter().map(|t| t.1).collect();
    let g = gospa(&points, &estimates, evaluation.gospa_cutoff, evaluation.gospa_order);
    let pairs = g.assignment.iter().enumerate().filter_map(|(i, e)| e.map(|e| (truth[i].0, map[e].0))).collect();
    let bound = gospa(&points, &estimates, evaluation.error_bound, 1.0);
    let mut within_bound = vec![false; estimates.len()];
    for e in bound.assignment.iter().flatten() {
        within_bound[*e] = true;
    }
    Scored {
        gospa: g.distance,
        ospa: ospa(&points, &estimates, evaluation.gospa_cutoff, evaluation.gospa_order),
        pairs,
        within_bound,
        bound_assignment: bound.assignment,
    }
}

/// [`score`] component by component ([`components`], cut-off the larger of GOSPA's and the error bound):
/// the pairs closer than the cut-off decide GOSPA's and OSPA's assignments and everything within the error
/// bound, and they lie inside one component. OSPA from the same pairs: its optimum minimises
/// Σ d^p − q c^p over q pairs closer than c, as GOSPA's does, so OSPA^p = (L + c^p (n − q)) / n with L
/// and q GOSPA's localisation and proper pairs and n the larger set's size.
pub fn score_by_components<const P: usize>(
    truth: &[(u64, [f64; P])],
    map: &[(u32, [f64; P])],
    evaluation: &EvaluationSpec,
) -> Scored {
    let (c, p) = (evaluation.gospa_cutoff, evaluation.gospa_order);
    let points: Vec<[f64; P]> = truth.iter().map(|t| t.1).collect();
    let estimates: Vec<[f64; P]> = map.iter().map(|t| t.1).collect();
    let (mut localisation, mut proper) = (0.0, 0usize);
    let mut pairs: Vec<(usize, (u64, u32))> = vec![];
    let mut within_bound = vec![false; map.len()];
    let mut bound_assignment = vec![None; truth.len()];
    for part in components(&points, &estimates, c.max(evaluation.error_bound)) {
        if part.truth.is_empty() || part.estimates.is_empty() {
            continue; // no pair: missed objects or false estimates only
        }
        let t: Vec<[f64; P]> = part.truth.iter().map(|&i| points[i]).collect();
        let e: Vec<[f64; P]> = part.estimates.iter().map(|&j| estimates[j]).collect();
        let g = gospa(&t, &e, c, p);
        localisation += g.localisation;
        proper += t.len() - g.missed;
        for (i, assigned) in g.assignment.iter().enumerate() {
            if let Some(j) = assigned {
                let (i, j) = (part.truth[i], part.estimates[*j]);
                pairs.push((i, (truth[i].0, map[j].0)));
            }
        }
        for (i, assigned) in gospa(&t, &e, evaluation.error_bound, 1.0).assignment.iter().enumerate() {
            if let Some(j) = assigned {
                within_bound[part.estimates[*j]] = true;
                bound_assignment[part.truth[i]] = Some(part.estimates[*j]);
            }
        }
    }
    pairs.sort_by_key(|(i, _)| *i);
    let cp = c.powf(p);
    let unpaired = (truth.len() + map.len() - 2 * proper) as f64;
    let n = truth.len().max(map.len());
    let ospa = match (n, truth.len().min(map.len())) {
        (0, _) => 0.0,
        (_, 0) => c,
        (n, _) => ((localisation + cp * (n - proper) as f64) / n as f64).powf(1.0 / p),
    };
    Scored {
        gospa: (localisation + cp / 2.0 * unpaired).powf(1.0 / p),
        ospa,
        pairs: pairs.into_iter().map(|(_, pair)| pair).collect(),
        within_bound,
        bound_assignment,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sim::rng::{Random, Stream};

    /// Random scans of up to 40 objects and estimates in a 200 km cube, some estimates near their object,
    /// some far: by components, the same figures as over the whole sets.
    #[test]
    fn scoring_by_components_gives_the_whole_sets_figures() {
        let evaluation = EvaluationSpec { gospa_cutoff: 10.0, error_bound: 5.0, ..EvaluationSpec::default() };
        let mut random = Random::stream(11, Stream::Scenario, 0);
        let mut paired = 0;
        for case in 0..200 {
            let n = (random.uniform() * 40.0) as usize;
            let m = (random.uniform() * 40.0) as usize;
            let truth: Vec<(u64, [f64; 3])> =
                (0..n).map(|i| (i as u64, core::array::from_fn(|_| random.uniform() * 200.0))).collect();
            let map: Vec<(u32, [f64; 3])> = (0..m)
                .map(|j| {
                    let position = match j < n && random.uniform() < 0.7 {
                        true => core::array::from_fn(|d| truth[j].1[d] + (random.uniform() - 0.5) * 12.0),
                        false => core::array::from_fn(|_| random.uniform() * 200.0),
                    };
                    (j as u32 + 100, position)
                })
                .collect();
            let (whole, parts) =
                (score_whole(&truth, &map, &evaluation), score_by_components(&truth, &map, &evaluation));
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * a.abs().max(1.0);
            assert!(close(whole.gospa, parts.gospa), "case {case}: GOSPA {} vs {}", whole.gospa, parts.gospa);
            assert!(close(whole.ospa, parts.ospa), "case {case}: OSPA {} vs {}", whole.ospa, parts.ospa);
            assert_eq!(whole.pairs, parts.pairs, "case {case}");
            assert_eq!(whole.within_bound, parts.within_bound, "case {case}");
            assert_eq!(whole.bound_assignment, parts.bound_assignment, "case {case}");
            paired += whole.pairs.len();
        }
        assert!(paired > 1000, "{paired} pairs: the cases must pair objects");
    }
}
