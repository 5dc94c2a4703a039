//! Paper 004's Fig. 4 data association matrix (docs/maths.md §10.5): the exhaustive generator's count, MAP and
//! deterministic tie order.

use tracker_core::association::{AssociationMatrix, CLUTTER};
use tracker_core::children::{ChildGenerator, ChildSink, ExhaustiveChildren};
use tracker_core::selection::TopChildren;

const TABLE: [[f64; 10]; 5] = [
    [0.1, 0.2, 0.0, 0.03, 0.05, 0.004, 0.002, 0.001, 0.01, 0.005],
    [0.04, 0.03, 0.05, 0.01, 0.04, 0.014, 0.2, 0.004, 0.005, 0.006],
    [0.09, 0.05, 0.04, 0.03, 0.01, 0.004, 0.005, 0.006, 0.1, 0.001],
    [0.09, 0.04, 0.1, 0.01, 0.02, 0.04, 0.3, 0.004, 0.005, 0.006],
    [0.001, 0.003, 0.002, 0.004, 0.005, 0.006, 0.007, 0.5, 0.01, 0.03],
];

fn matrix() -> AssociationMatrix<f64, 10, 5> {
    let rows: Vec<&[f64]> = TABLE.iter().map(|r| r.as_slice()).collect();
    AssociationMatrix::from_likelihoods(&rows, &[0.02; 5])
}

/// The paper's 1-based object numbers (clutter printed as 11).
fn paper(assignment: &[u16]) -> Vec<u16> {
    assignment.iter().map(|&c| if c == CLUTTER { 11 } else { c + 1 }).collect()
}

struct All(Vec<(f64, Vec<u16>)>);

impl ChildSink<f64> for All {
    fn offer(&mut self, log_weight: f64, assignment: &[u16]) {
        self.0.push((log_weight, assignment.to_vec()));
    }
}

#[test]
fn exhaustive_children_of_fig4() {
    let m = matrix();
    let mut all = All(vec![]);
    let mut generator = ExhaustiveChildren::new(u64::MAX);
    generator.generate(&m, &mut all).unwrap();
    // 63,591 associations, of which 5,509 use the zero entry M1 → 3 and are impossible.
    assert_eq!(all.0.len(), 58_082);
    assert_eq!(generator.leaves_visited(), 58_082);
    let total: f64 = all.0.iter().map(|c| c.0.exp()).sum();
    let mut ranked: Vec<(f64, Vec<u16>)> = all.0.iter().map(|(w, a)| (w.exp() / total, paper(a))).collect();
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0));
    assert_eq!(ranked[0].1, vec![2, 7, 9, 3, 8]);
    assert!((ranked[0].0 - 0.021415).abs() < 5e-7, "MAP probability {}", ranked[0].0);
    assert!((all.0.iter().map(|c| c.0).fold(f64::MIN, f64::max).exp() - 2.0e-4).abs() < 1e-12);
    assert!((ranked[1].0 - 0.019274).abs() < 5e-7 && (ranked[2].0 - 0.019274).abs() < 5e-7);
    assert!((ranked[3].0 - 0.016061).abs() < 5e-7 && ranked[3].1 == vec![2, 3, 9, 7, 8]);
    assert!((ranked[4].0 - 0.014455).abs() < 5e-7 && ranked[4].1 == vec![2, 3, 1, 7, 8]);
    assert_eq!(ranked.iter().filter(|c| c.0 > 1e-3).count(), 182);
    // The paper's illustrative green hypothesis [5 4 2 1 7].
    let green = ranked.iter().position(|c| c.1 == vec![5, 4, 2, 1, 7]).unwrap();
    assert!((ranked[green].0 - 1.69e-6).abs() < 5e-9, "green probability {}", ranked[green].0);
    // Its rank is 10,755 in docs/maths.md §10.5; several children share its probability, so the rank is any
    // position within its tie group.
    let green_weight = ranked[green].0;
    let better = ranked.iter().filter(|c| c.0 > green_weight * (1.0 + 1e-12)).count();
    let tied = ranked.iter().filter(|c| (c.0 / green_weight - 1.0).abs() <= 1e-12).count();
    assert!(better < 10_755 && 10_755 <= better + tied, "green ties span ranks {}..={}", better + 1, better + tied);
}

#[test]
fn top_selection_breaks_the_tie_in_enumeration_order() {
    let m = matrix();
    let run = || {
        let mut top = TopChildren::<f64, 3, 5>::new();
        ExhaustiveChildren::new(u64::MAX).generate(&m, &mut top).unwrap();
        let mut order = [0u16; 3];
        let n = top.best_first(&mut order);
        order[..n].iter().map(|&i| paper(&top.kept()[i as usize].assignment)).collect::<Vec<_>>()
    };
    let best = run();
    // Enumeration visits rows in order, clutter first then columns ascending, so [2,7,1,3,8] (object 1
    // in row 3) is produced before [2,7,9,1,8] and wins the tie.
    assert_eq!(best, vec![vec![2, 7, 9, 3, 8], vec![2, 7, 1, 3, 8], vec![2, 7, 9, 1, 8]]);
    assert_eq!(best, run());
}
