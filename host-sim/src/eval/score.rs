//! Scoring one scan's MAP estimates against the truth: GOSPA (α = 2, cut-off and order from the scenario's
//! `evaluation`), OSPA, the pairs GOSPA assigns (for label switches), and which estimates lie within the
//! error bound (GOSPA with cut-off `error_bound` assigns them to a true object).

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

/// Scores the MAP estimates `map` (label, position) against the true objects `truth` (id, position).
pub fn score<const P: usize>(
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
